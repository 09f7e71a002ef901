/*
 * arap.c: as-rigid-as-possible flattening by local/global iterations (Liu,
 * Zhang, Xu, Gotsman, Gortler 2008).
 *
 * The energy is sum_t sum_edges ij of t cot(theta_ij) |(u_i - u_j) - R_t
 * (x_i - x_j)|^2, theta_ij the angle of t opposite edge ij and x the
 * corners in t's own plane; for a linear map it equals 2 A_t |J_t - R_t|^2,
 * so it is the energy ur_flatten_energy reports.  The local step gives each
 * triangle the rotation R_t closest to its Jacobian; the global step
 * minimises over u with the rotations fixed, which is the cotangent
 * Laplacian system L u = b for the x and the y column at once.  L does not
 * depend on u: it is built and factored once, and each iteration is one
 * pass over the triangles and one solve.  Neither step can raise the
 * energy, so it falls until it stalls.  One vertex is pinned, which removes
 * the translations (the only freedom left once rotations are fitted).
 *
 * The energy does not stop a triangle from turning over, so the move from
 * the layout to the global step's solution is bounded (Smith and Schaefer
 * 2015, as SLIM does): each corner moves on a straight line, each
 * triangle's signed area is a quadratic along it, and the step goes
 * FLIP_MARGIN of the way to the first zero of any of them.  From a layout
 * with every triangle the right way round, every layout after is too.  The
 * shorter step still lowers the global step's quadratic (a convex function
 * falls all along the segment to its minimum), so the energy still falls.
 *
 * The cotangent Laplacian is the Dirichlet energy of the piecewise linear
 * map, so it is positive semidefinite whatever the angles (cotangents of
 * obtuse angles are negative) and definite once a vertex of a connected
 * piece is pinned.  Only rounding on nearly degenerate triangles can make
 * CHOLMOD find otherwise; then every cotangent is clamped up to
 * CLAMPED_COTANGENT, which makes L a weighted graph Laplacian (definite
 * after pinning); the iterations then converge to a slightly different
 * layout, still measured honestly by the strain.
 */
#include "flatten_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CLAMPED_COTANGENT 0.01

/*
 * Below this energy (an RMS distance of 1e-7 from a rotation) the layout
 * is an isometry to the precision of single-precision coordinates (STL,
 * glTF) or of six printed decimals (OBJ): iterating on chases rounding in
 * the input, by ever smaller relative steps.
 */
#define NEGLIGIBLE_ENERGY 1e-14

#define NOT_FREE ((size_t)-1)

/* The share of the way to the first triangle that would turn over that a step goes. */
#define FLIP_MARGIN 0.8

/* A step bounded to less than this of the way moves nothing worth another iteration. */
#define SMALLEST_STEP 1e-9

typedef struct arap {
    const ur_mesh *mesh;
    const flat_frame *frames;
    const flat_topology *topology;
    size_t pin, free_count;
    double *weight; /* 3 T: cotangent at each corner, clamped on fallback */
    double *pinned; /* 2 F: the pinned vertex's share of b (x column, then y) */
    ur_vec2 *next;  /* V: the global step's solution, before the step is bounded */
    double area;    /* 3D area */
    flat_solver solver;
    cholmod_dense *rhs;
} arap;

static size_t free_index(const arap *a, size_t v)
{
    return v == a->pin ? NOT_FREE : v < a->pin ? v : v - 1;
}

static void arap_free(arap *a)
{
    if (a->rhs)
        cholmod_l_free_dense(&a->rhs, &a->solver.common);
    flat_solver_finish(&a->solver);
    free(a->weight);
    free(a->pinned);
    free(a->next);
}

static ur_status arap_alloc(arap *a, ur_error *error)
{
    size_t t = a->mesh->triangle_count;
    a->free_count = a->mesh->vertex_count - 1;
    a->weight = ur_alloc_array(3 * t, sizeof *a->weight, error);
    a->pinned = ur_alloc_array(2 * a->free_count, sizeof *a->pinned, error);
    a->next = ur_alloc_array(a->mesh->vertex_count, sizeof *a->next, error);
    if (!a->weight || !a->pinned || !a->next)
        return UR_ERROR_MEMORY;
    a->area = 0;
    for (size_t k = 0; k < t; k++) {
        memcpy(&a->weight[3 * k], a->frames[k].cot, sizeof a->frames[k].cot);
        a->area += a->frames[k].area;
    }
    return flat_solver_start(&a->solver, error);
}

/* The weight of the edge from corner k to corner k + 1 of t: the cotangent opposite it. */
static double edge_weight(const arap *a, size_t t, int k)
{
    return a->weight[3 * t + (k + 2) % 3];
}

/* Sums the cotangents of each edge's (one or two) opposite angles. */
static ur_status edge_weights(const arap *a, double **weights, ur_error *error)
{
    double *w = ur_alloc_array(a->topology->edge_count, sizeof *w, error);
    if (!w)
        return UR_ERROR_MEMORY;
    for (size_t t = 0; t < a->mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++)
            w[a->topology->edge_of[3 * t + k]] += edge_weight(a, t, k);
    *weights = w;
    return UR_OK;
}

/* L on the free vertices, and the pinned vertex's share of b. */
static void fill_laplacian(arap *a, const double *w, const ur_vec2 *layout, cholmod_triplet *m)
{
    size_t n = a->free_count;
    ur_vec2 pinned = layout[a->pin];
    memset(a->pinned, 0, 2 * n * sizeof *a->pinned);
    for (size_t e = 0; e < a->topology->edge_count; e++) {
        size_t i = free_index(a, a->topology->edges[e][0]);
        size_t j = free_index(a, a->topology->edges[e][1]);
        if (i != NOT_FREE)
            flat_triplet_add(m, i, i, w[e]);
        if (j != NOT_FREE)
            flat_triplet_add(m, j, j, w[e]);
        if (i != NOT_FREE && j != NOT_FREE)
            flat_triplet_add(m, i, j, -w[e]);
        else {
            size_t k = i != NOT_FREE ? i : j;
            a->pinned[k] += w[e] * pinned.x;
            a->pinned[n + k] += w[e] * pinned.y;
        }
    }
}

static ur_status factor_once(arap *a, const ur_vec2 *layout, bool *definite, ur_error *error)
{
    double *w = NULL;
    cholmod_triplet *m = NULL;
    /* Each edge adds at most two diagonal entries and one off the diagonal. */
    size_t capacity = 3 * a->topology->edge_count;
    ur_status status = edge_weights(a, &w, error);
    if (!status)
        status = flat_solver_triplets(&a->solver, a->free_count, capacity, &m, error);
    if (!status) {
        fill_laplacian(a, w, layout, m);
        status = flat_solver_factor(&a->solver, &m, definite, error);
    }
    if (m)
        cholmod_l_free_triplet(&m, &a->solver.common);
    free(w);
    return status;
}

/* Builds and factors L; falls back to clamped cotangents if CHOLMOD finds it indefinite. */
static ur_status factor(arap *a, const ur_vec2 *layout, ur_error *error)
{
    bool definite;
    ur_status status = factor_once(a, layout, &definite, error);
    if (status || definite)
        return status;
    for (size_t k = 0; k < 3 * a->mesh->triangle_count; k++)
        if (a->weight[k] < CLAMPED_COTANGENT)
            a->weight[k] = CLAMPED_COTANGENT;
    status = factor_once(a, layout, &definite, error);
    if (!status && !definite)
        status = ur_error_set(error, UR_ERROR_INTERNAL,
                              "ARAP: the Laplacian is singular even with clamped weights");
    return status;
}

/* Adds triangle t's share of b = sum c R (x_i - x_j) for its rotation R. */
static void add_rhs(const arap *a, size_t t, double cosine, double sine, double *b)
{
    size_t n = a->free_count;
    const flat_frame *frame = &a->frames[t];
    for (int k = 0; k < 3; k++) {
        int l = (k + 1) % 3;
        double c = edge_weight(a, t, k);
        ur_vec2 e = ur_vec2_sub(frame->corner[k], frame->corner[l]);
        double dx = c * (cosine * e.x - sine * e.y), dy = c * (sine * e.x + cosine * e.y);
        size_t i = free_index(a, a->mesh->triangles[t][k]);
        size_t j = free_index(a, a->mesh->triangles[t][l]);
        if (i != NOT_FREE) {
            b[i] += dx;
            b[n + i] += dy;
        }
        if (j != NOT_FREE) {
            b[j] -= dx;
            b[n + j] -= dy;
        }
    }
}

/*
 * The local step: each triangle's closest rotation, and with it the
 * energy of the layout and the right-hand side of the next global step.
 */
static double local_step(arap *a, const ur_vec2 *layout)
{
    double *b = a->rhs->x;
    memcpy(b, a->pinned, 2 * a->free_count * sizeof *b);
    double energy = 0;
    for (size_t t = 0; t < a->mesh->triangle_count; t++) {
        double cosine, sine;
        flat_matrix j = flat_triangle_jacobian(a->mesh, a->frames, layout, t);
        energy += a->frames[t].area * flat_rotation(j, &cosine, &sine);
        add_rhs(a, t, cosine, sine, b);
    }
    return energy / a->area;
}

/*
 * The largest fraction of the step from a to b (each triangle's corners
 * moving on straight lines) before triangle t's signed area reaches zero,
 * or 1 when it never does within the step: the smallest root in (0, 1] of
 * the quadratic twice area(s) = c + b s + q s^2, c > 0.
 */
static double room_to_flip(const size_t corner[3], const ur_vec2 *from, const ur_vec2 *to)
{
    ur_vec2 e1 = ur_vec2_sub(from[corner[1]], from[corner[0]]);
    ur_vec2 e2 = ur_vec2_sub(from[corner[2]], from[corner[0]]);
    ur_vec2 d1 = ur_vec2_sub(ur_vec2_sub(to[corner[1]], to[corner[0]]), e1);
    ur_vec2 d2 = ur_vec2_sub(ur_vec2_sub(to[corner[2]], to[corner[0]]), e2);
    double c = ur_vec2_cross(e1, e2);
    double b = ur_vec2_cross(e1, d2) + ur_vec2_cross(d1, e2);
    double q = ur_vec2_cross(d1, d2);
    if (!(c > 0))
        return 0;
    if (c + b + q > 0 && (b >= 0 || q <= 0 || b * b < 4 * q * c))
        return 1; /* positive at both ends, and no dip below zero between */
    double root = 1;
    if (fabs(q) <= 1e-12 * (fabs(b) + c)) {
        if (b < 0)
            root = -c / b;
    } else {
        double discriminant = b * b - 4 * q * c;
        if (discriminant >= 0) {
            /* The two roots without cancellation: c / (a root of the reversed quadratic). */
            double w = -0.5 * (b + copysign(sqrt(discriminant), b));
            double r1 = w / q, r2 = c / w;
            if (r1 > 0 && r1 < root)
                root = r1;
            if (r2 > 0 && r2 < root)
                root = r2;
        }
    }
    return root;
}

/*
 * How far to go from the layout towards the global step's solution: all
 * the way, unless a triangle would turn over on the way; then
 * FLIP_MARGIN of the way to the first that would (Smith and Schaefer
 * 2015), so that every triangle keeps a positive area.
 */
static double bounded_step(const arap *a, const ur_vec2 *from, const ur_vec2 *to)
{
    double step = 1;
    for (size_t t = 0; t < a->mesh->triangle_count; t++) {
        double room = room_to_flip(a->mesh->triangles[t], from, to);
        if (room < 1)
            step = fmin(step, FLIP_MARGIN * room);
    }
    return step;
}

static ur_status global_step(arap *a, ur_vec2 *layout, double *step, ur_error *error)
{
    const double *u;
    ur_status status = flat_solver_solve(&a->solver, a->rhs, &u, error);
    if (status)
        return status;
    size_t n = a->free_count;
    for (size_t v = 0; v < a->mesh->vertex_count; v++) {
        size_t i = free_index(a, v);
        a->next[v] = i != NOT_FREE ? ur_vec2_make(u[i], u[n + i]) : layout[v];
    }
    *step = bounded_step(a, layout, a->next);
    for (size_t v = 0; v < a->mesh->vertex_count; v++)
        layout[v] =
            ur_vec2_add(layout[v], ur_vec2_scale(ur_vec2_sub(a->next[v], layout[v]), *step));
    return UR_OK;
}

static ur_status iterate(arap *a, const ur_flatten_options *options, ur_vec2 *layout,
                         size_t *iterations, ur_error *error)
{
    double energy = local_step(a, layout);
    while (*iterations < options->iterations && energy > NEGLIGIBLE_ENERGY) {
        ur_status status = ur_context_check(options->context, error);
        double step = 0;
        if (status == UR_OK)
            status = global_step(a, layout, &step, error);
        if (status)
            return status;
        ++*iterations;
        double next = local_step(a, layout);
        if (options->progress)
            options->progress(options->progress_context, *iterations, next);
        bool stalled = energy - next <= options->tolerance * energy || step < SMALLEST_STEP;
        energy = next;
        if (stalled)
            break;
    }
    return UR_OK;
}

ur_status flat_arap(const ur_mesh *mesh, const flat_frame *frames, const flat_topology *topology,
                    size_t pin, const ur_flatten_options *options, ur_vec2 *layout,
                    size_t *iterations, ur_error *error)
{
    *iterations = 0;
    if (options->iterations == 0)
        return UR_OK;
    arap a = {.mesh = mesh, .frames = frames, .topology = topology, .pin = pin};
    ur_status status = arap_alloc(&a, error);
    if (!status)
        status = factor(&a, layout, error);
    if (!status)
        status = flat_solver_rhs(&a.solver, 2, &a.rhs, error);
    if (!status)
        status = iterate(&a, options, layout, iterations, error);
    arap_free(&a);
    return status;
}
