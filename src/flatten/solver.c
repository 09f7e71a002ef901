/*
 * solver.c: a sparse symmetric positive definite system assembled as
 * triplets, factored once by CHOLMOD and solved as often as needed.
 *
 * CHOLMOD reports through its return values and common->status; both are
 * checked after every call.  Its printing is turned off (print = 0): the
 * library never prints, and a matrix that is not positive definite is a
 * warning CHOLMOD would otherwise print.
 */
#include "flatten_internal.h"

#include <string.h>

static ur_status cholmod_failure(flat_solver *solver, const char *doing, ur_error *error)
{
    int status = solver->common.status;
    if (status == CHOLMOD_OUT_OF_MEMORY)
        return ur_error_out_of_memory(error);
    return ur_error_set(error, UR_ERROR_INTERNAL, "CHOLMOD failed while %s (status %d)", doing,
                        status);
}

ur_status flat_solver_start(flat_solver *solver, ur_error *error)
{
    memset(solver, 0, sizeof *solver);
    if (!cholmod_l_start(&solver->common))
        return ur_error_set(error, UR_ERROR_INTERNAL, "CHOLMOD could not start");
    solver->started = true;
    solver->common.print = 0;
    /* A failed factorisation is thrown away at once: the caller falls back. */
    solver->common.quick_return_if_not_posdef = 1;
    return UR_OK;
}

void flat_solver_finish(flat_solver *solver)
{
    if (!solver->started)
        return;
    cholmod_common *c = &solver->common;
    cholmod_l_free_factor(&solver->factor, c);
    cholmod_l_free_dense(&solver->solution, c);
    cholmod_l_free_dense(&solver->work_y, c);
    cholmod_l_free_dense(&solver->work_e, c);
    cholmod_l_finish(c);
    solver->started = false;
}

ur_status flat_solver_triplets(flat_solver *solver, size_t size, size_t capacity,
                               cholmod_triplet **triplets, ur_error *error)
{
    /* stype 1: symmetric, upper triangle stored. */
    *triplets = cholmod_l_allocate_triplet(size, size, capacity, 1, CHOLMOD_REAL, &solver->common);
    if (!*triplets || solver->common.status < CHOLMOD_OK)
        return cholmod_failure(solver, "allocating a matrix", error);
    solver->size = size;
    return UR_OK;
}

/* Symbolic analysis (fill-reducing ordering) and numeric factorisation of A. */
static ur_status analyse_and_factor(flat_solver *solver, cholmod_sparse *a, bool *definite,
                                    ur_error *error)
{
    cholmod_common *c = &solver->common;
    cholmod_l_free_factor(&solver->factor, c);
    solver->factor = cholmod_l_analyze(a, c);
    if (!solver->factor || c->status < CHOLMOD_OK)
        return cholmod_failure(solver, "ordering the matrix", error);
    int done = cholmod_l_factorize(a, solver->factor, c);
    if (c->status == CHOLMOD_NOT_POSDEF) {
        *definite = false;
        return UR_OK;
    }
    if (!done || c->status < CHOLMOD_OK)
        return cholmod_failure(solver, "factoring the matrix", error);
    *definite = true;
    return UR_OK;
}

ur_status flat_solver_factor(flat_solver *solver, cholmod_triplet **triplets, bool *definite,
                             ur_error *error)
{
    cholmod_common *c = &solver->common;
    *definite = false;
    cholmod_sparse *a = cholmod_l_triplet_to_sparse(*triplets, (*triplets)->nnz, c);
    cholmod_l_free_triplet(triplets, c);
    if (!a || c->status < CHOLMOD_OK) {
        cholmod_l_free_sparse(&a, c);
        return cholmod_failure(solver, "assembling the matrix", error);
    }
    ur_status status = analyse_and_factor(solver, a, definite, error);
    cholmod_l_free_sparse(&a, c);
    return status;
}

ur_status flat_solver_rhs(flat_solver *solver, size_t columns, cholmod_dense **rhs, ur_error *error)
{
    *rhs = cholmod_l_zeros(solver->size, columns, CHOLMOD_REAL, &solver->common);
    if (!*rhs || solver->common.status < CHOLMOD_OK)
        return cholmod_failure(solver, "allocating a right-hand side", error);
    return UR_OK;
}

ur_status flat_solver_solve(flat_solver *solver, cholmod_dense *rhs, const double **solution,
                            ur_error *error)
{
    cholmod_common *c = &solver->common;
    *solution = NULL;
    if (!solver->factor)
        return ur_error_set(error, UR_ERROR_INTERNAL, "solving before factoring");
    /* solve2 reuses the solution and its workspace from one call to the next. */
    if (!cholmod_l_solve2(CHOLMOD_A, solver->factor, rhs, NULL, &solver->solution, NULL,
                          &solver->work_y, &solver->work_e, c) ||
        c->status < CHOLMOD_OK)
        return cholmod_failure(solver, "solving", error);
    *solution = solver->solution->x;
    return UR_OK;
}
