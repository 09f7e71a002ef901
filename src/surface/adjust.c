/*
 * adjust.c: moving rail 2 as little as needed so that the developable strip
 * exists along the whole of rail 1 (what the Tapeworm script the paper used
 * does by hand).
 *
 * Each gap of the domain of existence is widened into a window of rail 1.
 * Across the window a target pairing sigma(u) is laid: a monotone cubic
 * (Fritsch-Carlson) from the pairing where the strip exists on one side to
 * the pairing on the other, or to rail 2's end where the gap reaches an end
 * of rail 1 (the rails are taken to end together).  Then the points of rail 2
 * in that stretch move so that every ruling of the window satisfies the
 * tangency condition det(c1'(u), c2'(sigma), c2(sigma) - c1(u)) = 0, with
 * the smallest weighted displacement: Gauss-Newton steps, each the minimum
 * of |d|^2 + SMOOTHING |second differences of d|^2 under the linearised
 * conditions, so that the displacement is spread smoothly along the rail.
 * With a direction, every point moves along it only.
 */
#include "surface_internal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <stdlib.h>
#include <string.h>

enum {
    LOCAL_MARGIN = 30, /* knots of rail 2 kept on each side of the moved points */
    MOVED_MARGIN = 2,  /* extra points moved on each side of the window */
    MAX_ITERATIONS = 40,
};

#define SMOOTHING 10.0

typedef struct window {
    double u_start, u_end;         /* on rail 1 */
    double sigma_start, sigma_end; /* target pairing at the ends */
    double slope_start, slope_end;
} window;

typedef struct problem {
    ur_curve *rail1;
    const ur_vec3 *original; /* rail 2's points before */
    ur_vec3 *points;         /* rail 2's points, being moved */
    size_t count;
    const double *knots; /* rail 2's original parameter of each point */
    size_t first, last;  /* moved points first..last */
    size_t local_first, local_last;
    const ur_vec3 *direction; /* NULL: any direction */
    const window *w;
    size_t samples;
} problem;

/* ---- The target pairing ------------------------------------------------- */

/* Fritsch-Carlson: slopes that keep the cubic Hermite monotone. */
static void monotone_slopes(window *w)
{
    double secant = (w->sigma_end - w->sigma_start) / (w->u_end - w->u_start);
    double a = fmax(w->slope_start, 0.0) / secant, b = fmax(w->slope_end, 0.0) / secant;
    double size = a * a + b * b;
    if (size > 9) {
        double tau = 3 / sqrt(size);
        a *= tau;
        b *= tau;
    }
    w->slope_start = a * secant;
    w->slope_end = b * secant;
}

static double target_sigma(const window *w, double u)
{
    double h = w->u_end - w->u_start, t = (u - w->u_start) / h;
    double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
    double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
    return h00 * w->sigma_start + h10 * h * w->slope_start + h01 * w->sigma_end +
           h11 * h * w->slope_end;
}

/* ---- Rail 2 near the window, after moving ------------------------------- */

/* The index coordinate (point index plus fraction) of parameter sigma. */
static double index_of(const problem *p, double sigma)
{
    size_t low = 0, high = p->count - 1;
    if (sigma <= p->knots[0])
        return 0.0;
    if (sigma >= p->knots[high])
        return (double)high;
    while (high - low > 1) {
        size_t middle = (low + high) / 2;
        if (p->knots[middle] <= sigma)
            low = middle;
        else
            high = middle;
    }
    return (double)low + (sigma - p->knots[low]) / (p->knots[low + 1] - p->knots[low]);
}

/* The tangency condition at every sample of the window, each scaled to an angle. */
static ur_status conditions(const problem *p, double *values, ur_error *error)
{
    ur_curve *local;
    size_t n = p->local_last - p->local_first + 1;
    ur_status status = ur_curve_new_interpolating(p->points + p->local_first, n, false, &local, error);
    if (status != UR_OK)
        return status;
    for (size_t k = 0; k < p->samples; k++) {
        double u = p->w->u_start + (p->w->u_end - p->w->u_start) * (k + 0.5) / p->samples;
        double x = index_of(p, target_sigma(p->w, u)) - (double)p->local_first;
        size_t i = (size_t)fmin(fmax(floor(x), 0.0), (double)(n - 2));
        double k0 = ur_curve_point_parameter(local, i), k1 = ur_curve_point_parameter(local, i + 1);
        ur_vec3 c1[3], c2[3];
        ur_curve_eval(p->rail1, u, c1);
        ur_curve_eval(local, k0 + (x - (double)i) * (k1 - k0), c2);
        ur_vec3 d = ur_vec3_sub(c2[0], c1[0]);
        values[k] = determinant3(c1[1], c2[1], d) /
                    (ur_vec3_length(c1[1]) * ur_vec3_length(c2[1]) * ur_vec3_length(d));
    }
    ur_curve_free(local);
    return UR_OK;
}

/* ---- Unknowns ----------------------------------------------------------- */

static size_t unknowns_per_point(const problem *p)
{
    return p->direction ? 1 : 3;
}

static size_t unknown_count(const problem *p)
{
    return (p->last - p->first + 1) * unknowns_per_point(p);
}

static void move(problem *p, size_t unknown, double amount)
{
    size_t per = unknowns_per_point(p);
    ur_vec3 *point = &p->points[p->first + unknown / per];
    if (p->direction) {
        *point = ur_vec3_add_scaled(*point, *p->direction, amount);
        return;
    }
    double *coordinate = unknown % 3 == 0 ? &point->x : unknown % 3 == 1 ? &point->y : &point->z;
    *coordinate += amount;
}

/* The current displacement in the unknowns' terms. */
static void displacement(const problem *p, gsl_vector *out)
{
    size_t per = unknowns_per_point(p);
    for (size_t j = 0; j < unknown_count(p); j++) {
        size_t index = p->first + j / per;
        ur_vec3 moved = ur_vec3_sub(p->points[index], p->original[index]);
        double value = p->direction ? ur_vec3_dot(moved, *p->direction)
                       : j % 3 == 0 ? moved.x
                       : j % 3 == 1 ? moved.y
                                    : moved.z;
        gsl_vector_set(out, j, value);
    }
}

/* W = I + SMOOTHING D^T D, D the second differences of each coordinate. */
static void fill_weights(const problem *p, gsl_matrix *weights)
{
    size_t per = unknowns_per_point(p), points = p->last - p->first + 1;
    gsl_matrix_set_identity(weights);
    const double stencil[3] = {1, -2, 1};
    for (size_t c = 0; c < per; c++)
        for (size_t j = 1; j + 1 < points; j++)
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    size_t row = (j - 1 + (size_t)a) * per + c, column = (j - 1 + (size_t)b) * per + c;
                    double value = gsl_matrix_get(weights, row, column);
                    gsl_matrix_set(weights, row, column, value + SMOOTHING * stencil[a] * stencil[b]);
                }
}

/* ---- Gauss-Newton on the smallest weighted displacement ----------------- */

typedef struct workspace {
    gsl_matrix *jacobian, *weights, *spread, *system;
    gsl_vector *values, *target, *trial, *solution, *step, *moved;
} workspace;

static void workspace_free(workspace *s)
{
    gsl_matrix_free(s->jacobian);
    gsl_matrix_free(s->weights);
    gsl_matrix_free(s->spread);
    gsl_matrix_free(s->system);
    gsl_vector_free(s->values);
    gsl_vector_free(s->target);
    gsl_vector_free(s->moved);
    gsl_vector_free(s->trial);
    gsl_vector_free(s->solution);
    gsl_vector_free(s->step);
}

static ur_status workspace_alloc(workspace *s, size_t samples, size_t unknowns, ur_error *error)
{
    s->jacobian = gsl_matrix_alloc(samples, unknowns);
    s->weights = gsl_matrix_alloc(unknowns, unknowns);
    s->spread = gsl_matrix_alloc(unknowns, samples);
    s->system = gsl_matrix_alloc(samples, samples);
    s->values = gsl_vector_alloc(samples);
    s->target = gsl_vector_alloc(samples);
    s->moved = gsl_vector_alloc(unknowns);
    s->trial = gsl_vector_alloc(samples);
    s->solution = gsl_vector_alloc(samples);
    s->step = gsl_vector_alloc(unknowns);
    if (!s->jacobian || !s->weights || !s->spread || !s->system || !s->values || !s->target ||
        !s->moved || !s->trial || !s->solution || !s->step)
        return ur_error_out_of_memory(error);
    return UR_OK;
}

static ur_status jacobian(problem *p, workspace *s, ur_error *error)
{
    double h = 1e-7 * (p->knots[p->count - 1] - p->knots[0]);
    for (size_t j = 0; j < unknown_count(p); j++) {
        move(p, j, h);
        ur_status status = conditions(p, s->trial->data, error);
        move(p, j, -h);
        if (status != UR_OK)
            return status;
        for (size_t k = 0; k < p->samples; k++)
            gsl_matrix_set(s->jacobian, k, j,
                           (gsl_vector_get(s->trial, k) - gsl_vector_get(s->values, k)) / h);
    }
    return UR_OK;
}

/*
 * The step to the smallest weighted displacement m + step that meets the
 * linearised conditions J step = target - values:
 *     m + step = W^-1 J^T y,  (J W^-1 J^T) y = J m + target - values.
 */
static ur_status solve_step(workspace *s, ur_error *error)
{
    gsl_matrix *cholesky = s->weights; /* factored in place, once per call */
    if (gsl_linalg_cholesky_decomp1(cholesky) != GSL_SUCCESS)
        return ur_error_set(error, UR_ERROR_INTERNAL, "adjusting rail 2: weights not positive");
    /* spread = W^-1 J^T, column by column */
    for (size_t k = 0; k < s->jacobian->size1; k++) {
        gsl_vector_view row = gsl_matrix_row(s->jacobian, k);
        gsl_vector_view column = gsl_matrix_column(s->spread, k);
        gsl_linalg_cholesky_solve(cholesky, &row.vector, &column.vector);
    }
    /* system = J W^-1 J^T + mu I: the conditions may depend on one another */
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, s->jacobian, s->spread, 0.0, s->system);
    double trace = 0.0;
    for (size_t k = 0; k < s->system->size1; k++)
        trace += gsl_matrix_get(s->system, k, k);
    for (size_t k = 0; k < s->system->size1; k++)
        gsl_matrix_set(s->system, k, k,
                       gsl_matrix_get(s->system, k, k) + 1e-12 * trace / s->system->size1 + 1e-300);
    gsl_vector_memcpy(s->trial, s->target);
    gsl_vector_sub(s->trial, s->values);
    gsl_blas_dgemv(CblasNoTrans, 1.0, s->jacobian, s->moved, 1.0, s->trial);
    if (gsl_linalg_cholesky_decomp1(s->system) != GSL_SUCCESS ||
        gsl_linalg_cholesky_solve(s->system, s->trial, s->solution) != GSL_SUCCESS)
        return ur_error_set(error, UR_ERROR_INTERNAL, "adjusting rail 2: singular conditions");
    gsl_blas_dgemv(CblasNoTrans, 1.0, s->spread, s->solution, 0.0, s->step);
    gsl_vector_sub(s->step, s->moved);
    return UR_OK;
}

/* How far the conditions are from their target. */
static double miss(const gsl_vector *values, const gsl_vector *target)
{
    double largest = 0.0;
    for (size_t k = 0; k < values->size; k++)
        largest = fmax(largest, fabs(gsl_vector_get(values, k) - gsl_vector_get(target, k)));
    return largest;
}

static void move_all(problem *p, const gsl_vector *step, double fraction)
{
    for (size_t j = 0; j < unknown_count(p); j++)
        move(p, j, fraction * gsl_vector_get(step, j));
}

/*
 * Takes the step, or the largest of its halves that makes the conditions
 * smaller (the linearisation holds only near the current points).
 */
static ur_status damped_step(problem *p, workspace *s, double before, bool *improved,
                             ur_error *error)
{
    double fraction = 1.0;
    *improved = false;
    for (int halving = 0; halving < 30; halving++, fraction /= 2) {
        move_all(p, s->step, fraction);
        ur_status status = conditions(p, s->trial->data, error);
        if (status != UR_OK)
            return status;
        if (miss(s->trial, s->target) < before) {
            *improved = true;
            return UR_OK;
        }
        move_all(p, s->step, -fraction);
    }
    return UR_OK;
}

/* Gauss-Newton steps toward the current target; stops when they stop helping. */
static ur_status meet_target(problem *p, workspace *s, ur_error *error)
{
    bool improved = true;
    ur_status status = UR_OK;
    for (int iteration = 0; status == UR_OK && improved && iteration < MAX_ITERATIONS;
         iteration++) {
        status = conditions(p, s->values->data, error);
        double before = miss(s->values, s->target);
        if (status != UR_OK || before < 1e-12)
            break;
        fill_weights(p, s->weights);
        displacement(p, s->moved);
        status = jacobian(p, s, error);
        if (status == UR_OK)
            status = solve_step(s, error);
        if (status == UR_OK)
            status = damped_step(p, s, before, &improved, error);
    }
    return status;
}

/*
 * The conditions are brought to zero in stages, (1 - t) times their first
 * values for t = 1/STAGES ... 1, so that the points follow the smallest
 * displacement from where they are instead of jumping to a far solution.
 */
enum { STAGES = 8 };

static ur_status gauss_newton(problem *p, ur_error *error)
{
    workspace s;
    memset(&s, 0, sizeof s);
    ur_status status = workspace_alloc(&s, p->samples, unknown_count(p), error);
    if (status == UR_OK)
        status = conditions(p, s.values->data, error);
    gsl_vector *first = status == UR_OK ? gsl_vector_alloc(p->samples) : NULL;
    if (status == UR_OK && !first)
        status = ur_error_out_of_memory(error);
    if (status == UR_OK)
        gsl_vector_memcpy(first, s.values);
    for (int stage = 1; status == UR_OK && stage <= STAGES; stage++) {
        gsl_vector_memcpy(s.target, first);
        gsl_vector_scale(s.target, 1.0 - (double)stage / STAGES);
        status = meet_target(p, &s, error);
    }
    gsl_vector_free(first);
    workspace_free(&s);
    return status;
}

/* ---- Windows from the gaps ---------------------------------------------- */

static void fill_window_end(ur_ruled *strip, double u, bool at_rail_end, double rail_end,
                            double *sigma, double *slope)
{
    if (at_rail_end) {
        *sigma = rail_end;
        *slope = NAN;
    } else {
        ur_ruled_pairing(strip, u, sigma, slope);
    }
}

/* The gap widened on both sides by half its length and a few of rail 1's points. */
static window window_of(ur_ruled *strip, const ur_interval *gap, double step)
{
    double u0 = ur_curve_start(strip->curve), u1 = ur_curve_end(strip->curve);
    double margin = 0.5 * (gap->u_end - gap->u_start) + 4 * step;
    window w;
    w.u_start = fmax(u0, gap->u_start - margin);
    w.u_end = fmin(u1, gap->u_end + margin);
    fill_window_end(strip, w.u_start, w.u_start <= u0, ur_curve_start(strip->rail2),
                    &w.sigma_start, &w.slope_start);
    fill_window_end(strip, w.u_end, w.u_end >= u1, ur_curve_end(strip->rail2), &w.sigma_end,
                    &w.slope_end);
    double secant = (w.sigma_end - w.sigma_start) / (w.u_end - w.u_start);
    if (isnan(w.slope_start))
        w.slope_start = secant;
    if (isnan(w.slope_end))
        w.slope_end = secant;
    return w;
}

static ur_status adjust_window(problem *p, const window *w, ur_error *error)
{
    if (!(w->sigma_end > w->sigma_start))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "--adjust-rail2: rail 2 runs backwards across the gap from %g to %g "
                            "along rail 1; no small move fixes that",
                            w->u_start, w->u_end);
    p->w = w;
    double from = floor(index_of(p, w->sigma_start)), to = ceil(index_of(p, w->sigma_end));
    p->first = (size_t)fmax(0.0, from - MOVED_MARGIN);
    p->last = (size_t)fmin((double)(p->count - 1), to + MOVED_MARGIN);
    p->local_first = p->first > LOCAL_MARGIN ? p->first - LOCAL_MARGIN : 0;
    p->local_last = p->last + LOCAL_MARGIN < p->count ? p->last + LOCAL_MARGIN : p->count - 1;
    p->samples = 3 * (p->last - p->first + 1);
    return gauss_newton(p, error);
}

/* Builds the strip on the current points; the caller frees it. */
static ur_status strip_of(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                          size_t count2, bool closed, ur_ruled *strip, ur_error *error)
{
    ur_curve *curves[2] = {NULL, NULL};
    ur_status status = ur_curve_new_interpolating(rail1, count1, closed, &curves[0], error);
    if (status == UR_OK)
        status = ur_curve_new_interpolating(rail2, count2, closed, &curves[1], error);
    if (status != UR_OK) {
        ur_curve_free(curves[0]);
        return status;
    }
    return ur_ruled_strip(curves[0], curves[1], strip, error);
}

ur_status ur_strip_adjust_rail2(const ur_vec3 *rail1, size_t count1, ur_vec3 *rail2,
                                size_t count2, const ur_vec3 *direction, double *largest,
                                ur_error *error)
{
    *largest = 0.0;
    gsl_set_error_handler_off();
    ur_vec3 unit;
    if (direction) {
        double length = ur_vec3_length(*direction);
        if (!(length > 0))
            return ur_error_set(error, UR_ERROR_INPUT, "--adjust-direction must not be zero");
        unit = ur_vec3_scale(*direction, 1.0 / length);
        direction = &unit;
    }
    ur_ruled strip;
    ur_status status = strip_of(rail1, count1, rail2, count2, false, &strip, error);
    if (status != UR_OK)
        return status;
    const ur_interval *gaps;
    size_t gap_count = ur_ruled_gaps(&strip, &gaps);
    ur_vec3 *original = ur_alloc_array(count2, sizeof *original, error);
    double *knots = ur_alloc_array(count2, sizeof *knots, error);
    window *windows = ur_alloc_array(gap_count + 1, sizeof *windows, error);
    if (!original || !knots || !windows)
        status = UR_ERROR_INTERNAL;
    double step = (ur_curve_end(strip.curve) - ur_curve_start(strip.curve)) / (double)count1;
    for (size_t k = 0; status == UR_OK && k < gap_count; k++) {
        windows[k] = window_of(&strip, &gaps[k], step);
        monotone_slopes(&windows[k]);
    }
    for (size_t j = 0; status == UR_OK && j < count2; j++) {
        original[j] = rail2[j];
        knots[j] = ur_curve_point_parameter(strip.rail2, j);
    }
    problem p = {strip.curve, original, rail2, count2, knots, 0, 0, 0, 0, direction, NULL, 0};
    for (size_t k = 0; status == UR_OK && k < gap_count; k++)
        status = adjust_window(&p, &windows[k], error);
    for (size_t j = 0; status == UR_OK && j < count2; j++)
        *largest = fmax(*largest, ur_vec3_distance(rail2[j], original[j]));
    if (status != UR_OK)
        memcpy(rail2, original, count2 * sizeof *rail2);
    free(original);
    free(knots);
    free(windows);
    ur_ruled_free(&strip);
    return status;
}
