/*
 * adjust.c: moving rail 2 as little as needed so that the developable strip
 * exists along the whole of rail 1 (what the Tapeworm script the seed paper
 * used does by hand: [Tapeworm] and [Seed2018] in docs/bibliography.md;
 * docs/algorithms.md, section 3).
 *
 * Each gap of the domain of existence is widened into a window of rail 1
 * that reaches into the strip on both sides (or to an end of rail 1, where
 * the rails are taken to end together).  Over the window, the points of rail
 * 2 whose rulings it holds may move, and so may the pairing: at samples u_k
 * it is sigma_k, increasing from the pairing at one end of the window to the
 * pairing at the other.  GSL's Levenberg-Marquardt solver then minimises
 *
 *     sum_k (G_k / TANGENCY)^2 + |L^T d|^2 + PAIRING^2 sum_k (a_k+1 - a_k)^2,
 *
 * G_k = det(c1'(u_k), c2'(sigma_k), c2(sigma_k) - c1(u_k)) scaled to an
 * angle (zero where one plane touches the strip along the ruling), d the
 * displacements and L L^T = I + SMOOTHING D^T D, D their second differences
 * running on into the unmoved points, so that the displacement is small,
 * spread smoothly along the rail and fades out at the window's ends.  The
 * pairing being free, the points move only where no pairing at all would
 * do; its increments exp(a_k) are kept from changing abruptly.  With a direction, every point moves
 * along it only.  The result is checked by building the strip again: a repair that leaves a gap is
 * refused.
 */
#include "surface_internal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <stdlib.h>
#include <string.h>

#include "../base/gsl_errors.h"

enum {
    LOCAL_MARGIN = 30, /* knots of rail 2 kept on each side of the moved points */
    MOVED_MARGIN = 2,  /* extra points moved on each side of the window */
    MAX_MOVED = 80,    /* points of rail 2 one window may move */
    SAMPLES_PER_POINT = 3,
    MAX_ITERATIONS = 40,
};

#define SMOOTHING 10.0
/*
 * Radians of G that weigh as much as 1 mm of displacement: small enough that
 * the solution meets the tangency to about 1e-7 rad, large enough that the
 * solver converges in few iterations.
 */
#define TANGENCY 1e-4
#define PAIRING 0.1 /* weight of the pairing's smoothness */

typedef struct window {
    double u_start, u_end;         /* on rail 1 */
    double sigma_start, sigma_end; /* pairing at the ends */
    double slope_start, slope_end;
} window;

typedef struct problem {
    ur_curve *rail1;
    const ur_vec3 *original; /* rail 2's points before */
    ur_vec3 *points;         /* rail 2's points, moved */
    size_t count;
    const double *knots; /* rail 2's original parameter of each point */
    size_t first, last;  /* the moved points */
    size_t local_first, local_last;
    const ur_vec3 *direction; /* NULL: any direction */
    window w;
    size_t samples;
    gsl_matrix *cholesky; /* L, lower triangle, of the weights */
} problem;

/* ---- The window and its first pairing ----------------------------------- */

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

static double hermite_sigma(const window *w, double u)
{
    double h = w->u_end - w->u_start, t = (u - w->u_start) / h;
    double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
    double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
    return h00 * w->sigma_start + h10 * h * w->slope_start + h01 * w->sigma_end +
           h11 * h * w->slope_end;
}

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

/*
 * The gap widened on both sides by half its length and a few of rail 1's
 * points, and by as much of rail 1 as rail 2 skips there at the strip's
 * usual rate (a jump of the pairing has no length on rail 1 but may skip a
 * long stretch of rail 2).
 */
static window window_of(ur_ruled *strip, const ur_interval *gap, double step, double rate)
{
    double u0 = ur_curve_start(strip->curve), u1 = ur_curve_end(strip->curve);
    double before, after, slope, skipped = 0.0;
    if (gap->u_start > u0 && gap->u_end < u1) { /* the pairing exists at both ends */
        ur_ruled_pairing(strip, gap->u_start, &before, &slope);
        ur_ruled_pairing(strip, gap->u_end, &after, &slope);
        skipped = fmax(after - before, 0.0) / rate;
    }
    double margin = 0.5 * (gap->u_end - gap->u_start) + 0.5 * skipped + 4 * step;
    window w;
    w.u_start = fmax(u0, gap->u_start - margin);
    w.u_end = fmin(u1, gap->u_end + margin);
    fill_window_end(strip, w.u_start, w.u_start <= u0, ur_curve_start(strip->rail2), &w.sigma_start,
                    &w.slope_start);
    fill_window_end(strip, w.u_end, w.u_end >= u1, ur_curve_end(strip->rail2), &w.sigma_end,
                    &w.slope_end);
    double secant = (w.sigma_end - w.sigma_start) / (w.u_end - w.u_start);
    if (isnan(w.slope_start))
        w.slope_start = secant;
    if (isnan(w.slope_end))
        w.slope_end = secant;
    return w;
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

static double sample_u(const problem *p, size_t k)
{
    return p->w.u_start + (p->w.u_end - p->w.u_start) * ((double)k + 0.5) / (double)p->samples;
}

/* ---- Unknowns: displacements, then the pairing's increments -------------- */

static size_t per_point(const problem *p)
{
    return p->direction ? 1 : 3;
}

static size_t moved_unknowns(const problem *p)
{
    return (p->last - p->first + 1) * per_point(p);
}

static size_t unknown_count(const problem *p)
{
    return moved_unknowns(p) + p->samples + 1;
}

static void place_points(problem *p, const gsl_vector *x)
{
    size_t per = per_point(p);
    for (size_t j = p->first; j <= p->last; j++) {
        const double *d = x->data + (j - p->first) * per;
        ur_vec3 move =
            p->direction ? ur_vec3_scale(*p->direction, d[0]) : ur_vec3_make(d[0], d[1], d[2]);
        p->points[j] = ur_vec3_add(p->original[j], move);
    }
}

/*
 * sigma_k as index coordinates: the window's start plus the share of the
 * first k + 1 of the samples + 1 positive increments exp(a_i).
 */
static void pairing_indices(const problem *p, const gsl_vector *x, double *indices)
{
    const double *a = x->data + moved_unknowns(p);
    double total = 0.0;
    for (size_t i = 0; i <= p->samples; i++)
        total += exp(a[i]);
    double start = index_of(p, p->w.sigma_start), end = index_of(p, p->w.sigma_end);
    double sum = 0.0;
    for (size_t k = 0; k < p->samples; k++) {
        sum += exp(a[k]);
        indices[k] = start + (end - start) * sum / total;
    }
}

/* The first guess: no move, the monotone cubic for the pairing. */
static void first_guess(const problem *p, gsl_vector *x)
{
    gsl_vector_set_zero(x);
    double *a = x->data + moved_unknowns(p);
    double previous = index_of(p, p->w.sigma_start);
    for (size_t k = 0; k <= p->samples; k++) {
        double next = k < p->samples ? index_of(p, hermite_sigma(&p->w, sample_u(p, k)))
                                     : index_of(p, p->w.sigma_end);
        a[k] = log(fmax(next - previous, 1e-9));
        previous = next;
    }
}

/* ---- The residuals ------------------------------------------------------ */

/* G at each sample, scaled to an angle, on a spline through the moved points. */
static int tangency(problem *p, const double *indices, double *values)
{
    ur_curve *local;
    size_t n = p->local_last - p->local_first + 1;
    if (ur_curve_new_interpolating(p->points + p->local_first, n, false, &local, NULL) != UR_OK)
        return GSL_EBADFUNC;
    for (size_t k = 0; k < p->samples; k++) {
        double x = indices[k] - (double)p->local_first;
        size_t i = (size_t)fmin(fmax(floor(x), 0.0), (double)(n - 2));
        double k0 = ur_curve_point_parameter(local, i), k1 = ur_curve_point_parameter(local, i + 1);
        ur_vec3 c1[3], c2[3];
        ur_curve_eval(p->rail1, sample_u(p, k), c1);
        ur_curve_eval(local, k0 + (x - (double)i) * (k1 - k0), c2);
        ur_vec3 d = ur_vec3_sub(c2[0], c1[0]);
        values[k] = determinant3(c1[1], c2[1], d) /
                    (ur_vec3_length(c1[1]) * ur_vec3_length(c2[1]) * ur_vec3_length(d));
    }
    ur_curve_free(local);
    return GSL_SUCCESS;
}

/*
 * f = (G_k / TANGENCY, L^T d, PAIRING (a_k+1 - a_k)): what Levenberg-Marquardt
 * makes small.  GSL may hand x and f as strided views (a column of its
 * Jacobian), so they are read and written through gsl_vector_get and _set.
 */
static int residuals(const gsl_vector *x, void *data, gsl_vector *f)
{
    problem *p = data;
    size_t moved = moved_unknowns(p), unknowns = unknown_count(p);
    double *buffer = malloc((unknowns + 2 * p->samples) * sizeof *buffer);
    if (!buffer)
        return GSL_ENOMEM;
    gsl_vector_view copy = gsl_vector_view_array(buffer, unknowns);
    gsl_vector_memcpy(&copy.vector, x);
    double *indices = buffer + unknowns, *values = indices + p->samples;
    place_points(p, &copy.vector);
    pairing_indices(p, &copy.vector, indices);
    int code = tangency(p, indices, values);
    for (size_t k = 0; code == GSL_SUCCESS && k < p->samples; k++)
        gsl_vector_set(f, k, values[k] / TANGENCY);
    if (code == GSL_SUCCESS) {
        gsl_vector_view weighted = gsl_vector_subvector(&copy.vector, 0, moved);
        gsl_blas_dtrmv(CblasLower, CblasTrans, CblasNonUnit, p->cholesky, &weighted.vector);
        for (size_t j = 0; j < moved; j++)
            gsl_vector_set(f, p->samples + j, buffer[j]);
        const double *a = buffer + moved;
        for (size_t k = 0; k < p->samples; k++)
            gsl_vector_set(f, p->samples + moved + k, PAIRING * (a[k + 1] - a[k]));
    }
    free(buffer);
    return code;
}

/*
 * W = I + SMOOTHING D^T D, D the second differences of each coordinate,
 * factored W = L L^T.  Beyond the moved points rail 2 stays where it is, so
 * the differences run on into two fixed zeros on each side (unless the
 * moved points reach an end of rail 2, which is free).
 */
static ur_status weights(problem *p, ur_error *error)
{
    long per = (long)per_point(p), points = (long)(p->last - p->first + 1);
    bool free_start = p->first == 0, free_end = p->last == p->count - 1;
    gsl_matrix *w = p->cholesky;
    gsl_matrix_set_identity(w);
    const double stencil[3] = {1, -2, 1};
    for (long centre = free_start ? 1 : -1; centre < (free_end ? points - 1 : points + 1); centre++)
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                long i = centre - 1 + a, j = centre - 1 + b;
                if (i < 0 || j < 0 || i >= points || j >= points)
                    continue; /* a fixed point adds nothing */
                for (long c = 0; c < per; c++) {
                    size_t row = (size_t)(i * per + c), column = (size_t)(j * per + c);
                    gsl_matrix_set(w, row, column,
                                   gsl_matrix_get(w, row, column) +
                                       SMOOTHING * stencil[a] * stencil[b]);
                }
            }
    if (gsl_linalg_cholesky_decomp1(w) != GSL_SUCCESS)
        return ur_error_set(error, UR_ERROR_INTERNAL, "adjusting rail 2: weights not positive");
    return UR_OK;
}

/* ---- One window --------------------------------------------------------- */

static ur_status solve(problem *p, ur_error *error)
{
    size_t n = 2 * p->samples + moved_unknowns(p), unknowns = unknown_count(p);
    gsl_multifit_nlinear_parameters parameters = gsl_multifit_nlinear_default_parameters();
    /* The pairing's softmax has a direction that changes nothing: plain damping copes. */
    parameters.scale = gsl_multifit_nlinear_scale_levenberg;
    gsl_multifit_nlinear_workspace *solver =
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &parameters, n, unknowns);
    gsl_vector *x = gsl_vector_alloc(unknowns);
    if (!solver || !x) {
        if (solver)
            gsl_multifit_nlinear_free(solver);
        gsl_vector_free(x);
        return ur_error_out_of_memory(error);
    }
    gsl_multifit_nlinear_fdf fdf = {residuals, NULL, NULL, n, unknowns, p, 0, 0, 0};
    first_guess(p, x);
    int info, code = gsl_multifit_nlinear_init(x, &fdf, solver);
    if (code == GSL_SUCCESS) /* reaching MAX_ITERATIONS is not failure: the result is checked */
        code = gsl_multifit_nlinear_driver(MAX_ITERATIONS, 1e-14, 1e-14, 1e-14, NULL, NULL, &info,
                                           solver);
    if (code == GSL_SUCCESS || code == GSL_EMAXITER)
        place_points(p, gsl_multifit_nlinear_position(solver));
    gsl_multifit_nlinear_free(solver);
    gsl_vector_free(x);
    if (code != GSL_SUCCESS && code != GSL_EMAXITER) {
        ur_error_set(error, UR_ERROR_INPUT, "adjust-rail2: the solver failed: %s",
                     gsl_strerror(code));
        return ur_error_set_setting(error, "adjust-rail2");
    }
    return UR_OK;
}

static ur_status adjust_window(problem *p, const window *w, ur_error *error)
{
    if (!(w->sigma_end > w->sigma_start)) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "adjust-rail2: rail 2 runs backwards across the gap from %g to %g along "
                     "rail 1; no small move fixes that",
                     w->u_start, w->u_end);
        return ur_error_set_setting(error, "adjust-rail2");
    }
    p->w = *w;
    double from = floor(index_of(p, w->sigma_start)), to = ceil(index_of(p, w->sigma_end));
    p->first = (size_t)fmax(0.0, from - MOVED_MARGIN);
    p->last = (size_t)fmin((double)(p->count - 1), to + MOVED_MARGIN);
    if (p->last - p->first + 1 > MAX_MOVED) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "adjust-rail2: the gap from %g to %g along rail 1 spans %zu points of rail "
                     "2, more than a repair moves (%d)",
                     w->u_start, w->u_end, p->last - p->first + 1, MAX_MOVED);
        return ur_error_set_setting(error, "adjust-rail2");
    }
    p->local_first = p->first > LOCAL_MARGIN ? p->first - LOCAL_MARGIN : 0;
    p->local_last = p->last + LOCAL_MARGIN < p->count ? p->last + LOCAL_MARGIN : p->count - 1;
    p->samples = SAMPLES_PER_POINT * (p->last - p->first + 1);
    p->cholesky = gsl_matrix_alloc(moved_unknowns(p), moved_unknowns(p));
    if (!p->cholesky)
        return ur_error_out_of_memory(error);
    ur_status status = weights(p, error);
    if (status == UR_OK)
        status = solve(p, error);
    gsl_matrix_free(p->cholesky);
    p->cholesky = NULL;
    return status;
}

/* ---- All the gaps ------------------------------------------------------- */

static bool strip_everywhere(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                             size_t count2)
{
    ur_ruled strip;
    if (surface_strip_of_points(rail1, count1, rail2, count2, &strip, NULL) != UR_OK)
        return false;
    const ur_interval *gaps;
    bool everywhere = ur_ruled_gaps(&strip, &gaps) == 0;
    ur_ruled_free(&strip);
    return everywhere;
}

/* Each gap in order along rail 1, on the points as moved so far. */
static ur_status repair_gaps(ur_ruled *strip, problem *p, size_t count1, ur_error *error)
{
    const ur_interval *gaps;
    size_t gap_count = ur_ruled_gaps(strip, &gaps);
    double span = ur_curve_end(strip->curve) - ur_curve_start(strip->curve);
    double step = span / (double)count1;
    double rate = (ur_curve_end(strip->rail2) - ur_curve_start(strip->rail2)) / span;
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < gap_count; k++) {
        window w = window_of(strip, &gaps[k], step, rate);
        monotone_slopes(&w);
        status = adjust_window(p, &w, error);
        /* The next window starts from where this one left the points. */
        memcpy((ur_vec3 *)p->original, p->points, p->count * sizeof *p->points);
    }
    return status;
}

static ur_status adjust_rail2(const ur_vec3 *rail1, size_t count1, ur_vec3 *rail2, size_t count2,
                              const ur_vec3 *direction, double *largest, ur_error *error)
{
    *largest = 0.0;
    ur_vec3 unit;
    if (direction) {
        double length = ur_vec3_length(*direction);
        if (!(length > 0) || !isfinite(length)) {
            ur_error_set(error, UR_ERROR_INPUT, "adjust-direction must not be zero");
            return ur_error_set_setting(error, "adjust-direction");
        }
        unit = ur_vec3_scale(*direction, 1.0 / length);
        direction = &unit;
    }
    ur_ruled strip;
    ur_status status = surface_strip_of_points(rail1, count1, rail2, count2, &strip, error);
    if (status != UR_OK)
        return status;
    const ur_interval *gaps;
    if (ur_ruled_gaps(&strip, &gaps) == 0) {
        ur_ruled_free(&strip);
        return UR_OK;
    }
    ur_vec3 *moved = ur_alloc_array(count2, sizeof *moved, error);
    ur_vec3 *start = ur_alloc_array(count2, sizeof *start, error);
    double *knots = ur_alloc_array(count2, sizeof *knots, error);
    if (!moved || !start || !knots)
        status = UR_ERROR_MEMORY;
    for (size_t j = 0; status == UR_OK && j < count2; j++) {
        knots[j] = ur_curve_point_parameter(strip.rail2, j);
        moved[j] = start[j] = rail2[j];
    }
    if (status == UR_OK) {
        problem p = {.rail1 = strip.curve,
                     .original = start,
                     .points = moved,
                     .count = count2,
                     .knots = knots,
                     .direction = direction};
        status = repair_gaps(&strip, &p, count1, error);
    }
    if (status == UR_OK && !strip_everywhere(rail1, count1, moved, count2)) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "adjust-rail2: no small move of rail 2 gives a strip along the whole of rail "
                     "1 (the first gap is %.6g to %.6g mm along rail 1); change the rails' shape "
                     "there",
                     gaps[0].arc_start, gaps[0].arc_end);
        status = ur_error_set_setting(error, "adjust-rail2");
    }
    for (size_t j = 0; status == UR_OK && j < count2; j++) {
        *largest = fmax(*largest, ur_vec3_distance(moved[j], rail2[j]));
        rail2[j] = moved[j];
    }
    free(moved);
    free(start);
    free(knots);
    ur_ruled_free(&strip);
    return status;
}

ur_status ur_strip_adjust_rail2(const ur_vec3 *rail1, size_t count1, ur_vec3 *rail2, size_t count2,
                                const ur_vec3 *direction, double *largest, ur_error *error)
{
    gsl_errors_off();
    ur_status status = adjust_rail2(rail1, count1, rail2, count2, direction, largest, error);
    gsl_errors_restore();
    return status;
}
