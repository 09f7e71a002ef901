/*
 * curve.c: space curves, analytic (circle, helix) or interpolating points.
 *
 * Interpolation uses one GSL cubic spline per coordinate over the chord-length
 * parameter, so second derivatives (and so curvature) are continuous.  GSL's
 * open cubic spline is "natural": zero second derivative at both ends, which
 * would give every curve a false inflection at its ends and make a tangent
 * developable singular there.  So an open curve is padded with twelve ghost
 * points at each end, taken from the cubic through the four end points; the
 * natural end conditions then act on the ghosts, and the real ends keep the
 * curvature the data implies.  The error of a spline's end condition shrinks
 * by a factor 2 - sqrt(3) = 0.27 per knot, so three ghosts still left 2% of
 * it in the curvature at the real end (and a visible error in where a strip's
 * domain of existence ends); twelve leave about 1e-7.
 *
 * GSL solves for the splines; evaluating them is what the surfaces spend
 * most of their time on, so each interval's cubic is then kept for all three
 * coordinates together, and one search for the interval and one Horner
 * scheme give position and both derivatives at once.
 */
#include "unroll/surface.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_spline.h>
#include <stdlib.h>
#include "../base/gsl_errors.h"

enum curve_kind { CURVE_HELIX, CURVE_SPLINE };

enum { GHOSTS = 12 };

struct ur_curve {
    enum curve_kind kind;
    double u_start, u_end;
    bool closed;
    /* helix and circle */
    double radius, rise; /* rise = pitch / 2 pi */
    /* spline */
    size_t point_count; /* the caller's points */
    size_t first_point; /* index of the caller's first point among the knots */
    double *knots;      /* parameters of every interpolated point, ghosts included */
    size_t knot_count;
    /* per interval between knots and coordinate: the cubic's a, b, c, d in powers of u - knot */
    double (*cubics)[3][4];
    size_t hint; /* the interval of the last evaluation: evaluations come in sequence */
};

static ur_curve *curve_alloc(ur_error *error)
{
    ur_curve *curve = calloc(1, sizeof *curve);
    if (!curve)
        ur_error_out_of_memory(error);
    return curve;
}

ur_status ur_curve_new_helix(double radius, double pitch, double t_start, double t_end,
                             ur_curve **curve, ur_error *error)
{
    if (!(radius > 0) || !isfinite(pitch) || !(t_end > t_start))
        return ur_error_set(error, UR_ERROR_INPUT, "helix needs a positive radius and turns");
    *curve = curve_alloc(error);
    if (!*curve)
        return UR_ERROR_MEMORY;
    (*curve)->kind = CURVE_HELIX;
    (*curve)->radius = radius;
    (*curve)->rise = pitch / (2 * M_PI);
    (*curve)->u_start = t_start;
    (*curve)->u_end = t_end;
    return UR_OK;
}

ur_status ur_curve_new_circle(double radius, ur_curve **curve, ur_error *error)
{
    ur_status status = ur_curve_new_helix(radius, 0.0, 0.0, 2 * M_PI, curve, error);
    if (status == UR_OK)
        (*curve)->closed = true;
    return status;
}

/* Value at t of the cubic through (t[k], y[k]), k = 0..3 (Lagrange form). */
static double cubic_through(const double t[4], const double y[4], double at)
{
    double sum = 0.0;
    for (int k = 0; k < 4; k++) {
        double term = y[k];
        for (int j = 0; j < 4; j++)
            if (j != k)
                term *= (at - t[j]) / (t[k] - t[j]);
        sum += term;
    }
    return sum;
}

static double coordinate(ur_vec3 p, int axis)
{
    return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
}

/*
 * Fills knots and values (count + 2 GHOSTS entries each for an open curve,
 * count + 1 for a closed one, whose last entry repeats the first).
 */
static void spline_data(const ur_vec3 *points, size_t count, bool closed, double *knots,
                        double *values[3])
{
    size_t offset = closed ? 0 : GHOSTS;
    knots[offset] = 0.0;
    for (size_t i = 1; i < count; i++)
        knots[offset + i] = knots[offset + i - 1] + ur_vec3_distance(points[i], points[i - 1]);
    for (int axis = 0; axis < 3; axis++)
        for (size_t i = 0; i < count; i++)
            values[axis][offset + i] = coordinate(points[i], axis);
    if (closed) {
        knots[count] = knots[count - 1] + ur_vec3_distance(points[0], points[count - 1]);
        for (int axis = 0; axis < 3; axis++)
            values[axis][count] = values[axis][0];
        return;
    }
    size_t last = offset + count - 1;
    double step_start = knots[offset + 1] - knots[offset];
    double step_end = knots[last] - knots[last - 1];
    for (int g = 1; g <= GHOSTS; g++) {
        knots[offset - g] = knots[offset] - g * step_start;
        knots[last + g] = knots[last] + g * step_end;
    }
    for (int axis = 0; axis < 3; axis++) {
        double *y = values[axis];
        for (int g = 1; g <= GHOSTS; g++) {
            y[offset - g] = cubic_through(&knots[offset], &y[offset], knots[offset - g]);
            y[last + g] = cubic_through(&knots[last - 3], &y[last - 3], knots[last + g]);
        }
    }
}

/*
 * GSL's spline of one coordinate through (knots, values), kept as the cubic
 * of each interval: its values and second derivatives at the two ends
 * determine it, with the same coefficients GSL evaluates.
 */
static ur_status keep_cubics(ur_curve *curve, const double *values, int axis, ur_error *error)
{
    const double *knots = curve->knots;
    size_t n = curve->knot_count;
    gsl_errors_off();
    gsl_spline *spline =
        gsl_spline_alloc(curve->closed ? gsl_interp_cspline_periodic : gsl_interp_cspline, n);
    gsl_interp_accel *accel = gsl_interp_accel_alloc();
    bool built = spline && accel && gsl_spline_init(spline, knots, values, n) == GSL_SUCCESS;
    double second = built ? gsl_spline_eval_deriv2(spline, knots[0], accel) : 0.0;
    for (size_t i = 0; built && i + 1 < n; i++) {
        double h = knots[i + 1] - knots[i];
        double next = gsl_spline_eval_deriv2(spline, knots[i + 1], accel);
        double *cubic = curve->cubics[i][axis];
        cubic[0] = values[i];
        cubic[1] = (values[i + 1] - values[i]) / h - h * (2 * second + next) / 6;
        cubic[2] = second / 2;
        cubic[3] = (next - second) / (6 * h);
        second = next;
    }
    if (spline)
        gsl_spline_free(spline);
    if (accel)
        gsl_interp_accel_free(accel);
    gsl_errors_restore();
    return built ? UR_OK
                 : ur_error_set(error, UR_ERROR_INTERNAL, "cannot build the curve's spline");
}

ur_status ur_curve_new_interpolating(const ur_vec3 *points, size_t count, bool closed,
                                     ur_curve **curve_out, ur_error *error)
{
    if (count < 4)
        return ur_error_set(error, UR_ERROR_INPUT, "a curve needs at least 4 points");
    ur_curve *curve = curve_alloc(error);
    if (!curve)
        return UR_ERROR_MEMORY;
    curve->kind = CURVE_SPLINE;
    curve->closed = closed;
    curve->point_count = count;
    curve->first_point = closed ? 0 : GHOSTS;
    size_t knot_count = closed ? count + 1 : count + 2 * GHOSTS;
    double *values[3] = {NULL, NULL, NULL};
    ur_status status = UR_OK;
    curve->knots = ur_alloc_array(knot_count, sizeof(double), error);
    for (int axis = 0; axis < 3; axis++)
        values[axis] = ur_alloc_array(knot_count, sizeof(double), error);
    if (!curve->knots || !values[0] || !values[1] || !values[2]) {
        status = UR_ERROR_MEMORY;
        goto done;
    }
    spline_data(points, count, closed, curve->knots, values);
    curve->knot_count = knot_count;
    curve->cubics = ur_alloc_array(knot_count - 1, sizeof *curve->cubics, error);
    if (!curve->cubics) {
        status = UR_ERROR_MEMORY;
        goto done;
    }
    for (int axis = 0; axis < 3 && status == UR_OK; axis++)
        status = keep_cubics(curve, values[axis], axis, error);
    curve->u_start = curve->knots[curve->first_point];
    curve->u_end = closed ? curve->knots[count] : curve->knots[curve->first_point + count - 1];
done:
    for (int axis = 0; axis < 3; axis++)
        free(values[axis]);
    if (status != UR_OK) {
        ur_curve_free(curve);
        curve = NULL;
    }
    *curve_out = curve;
    return status;
}

void ur_curve_free(ur_curve *curve)
{
    if (!curve)
        return;
    free(curve->knots);
    free(curve->cubics);
    free(curve);
}

static void helix_eval(const ur_curve *curve, double t, ur_vec3 d[3])
{
    double c = cos(t), s = sin(t), r = curve->radius;
    d[0] = ur_vec3_make(r * c, r * s, curve->rise * t);
    d[1] = ur_vec3_make(-r * s, r * c, curve->rise);
    d[2] = ur_vec3_make(-r * c, -r * s, 0.0);
}

/* The interval [knots[i], knots[i + 1]] that holds u (the first or last one beyond the ends). */
static size_t knot_interval(ur_curve *curve, double u)
{
    const double *knots = curve->knots;
    size_t low = curve->hint;
    if (knots[low] <= u && u < knots[low + 1])
        return low;
    size_t high = curve->knot_count - 1;
    low = 0;
    while (high - low > 1) {
        size_t middle = low + (high - low) / 2;
        if (knots[middle] > u)
            high = middle;
        else
            low = middle;
    }
    curve->hint = low;
    return low;
}

static void spline_eval(ur_curve *curve, double u, ur_vec3 d[3])
{
    if (curve->closed) {
        double period = curve->u_end - curve->u_start;
        u = curve->u_start + fmod(fmod(u - curve->u_start, period) + period, period);
    } else {
        u = fmin(fmax(u, curve->u_start), curve->u_end);
    }
    size_t i = knot_interval(curve, u);
    double t = u - curve->knots[i], out[3][3];
    for (int axis = 0; axis < 3; axis++) {
        const double *c = curve->cubics[i][axis];
        out[0][axis] = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
        out[1][axis] = c[1] + t * (2 * c[2] + 3 * t * c[3]);
        out[2][axis] = 2 * c[2] + 6 * t * c[3];
    }
    for (int k = 0; k < 3; k++)
        d[k] = ur_vec3_make(out[k][0], out[k][1], out[k][2]);
}

void ur_curve_eval(ur_curve *curve, double u, ur_vec3 derivatives[3])
{
    if (curve->kind == CURVE_HELIX)
        helix_eval(curve, u, derivatives);
    else
        spline_eval(curve, u, derivatives);
}

double ur_curve_start(const ur_curve *curve)
{
    return curve->u_start;
}

double ur_curve_end(const ur_curve *curve)
{
    return curve->u_end;
}

bool ur_curve_is_closed(const ur_curve *curve)
{
    return curve->closed;
}

size_t ur_curve_point_count(const ur_curve *curve)
{
    return curve->kind == CURVE_SPLINE ? curve->point_count : 0;
}

double ur_curve_point_parameter(const ur_curve *curve, size_t index)
{
    if (curve->kind != CURVE_SPLINE || index >= curve->point_count)
        return NAN;
    return curve->knots[curve->first_point + index];
}

double ur_curve_curvature(ur_curve *curve, double u)
{
    ur_vec3 d[3];
    ur_curve_eval(curve, u, d);
    double speed = ur_vec3_length(d[1]);
    return ur_vec3_length(ur_vec3_cross(d[1], d[2])) / (speed * speed * speed);
}

static double speed_at(double u, void *curve)
{
    ur_vec3 d[3];
    ur_curve_eval(curve, u, d);
    return ur_vec3_length(d[1]);
}

ur_status ur_curve_length(ur_curve *curve, double u_start, double u_end, double *length,
                          ur_error *error)
{
    enum { LIMIT = 2000 };
    gsl_errors_off();
    gsl_integration_workspace *workspace = gsl_integration_workspace_alloc(LIMIT);
    bool allocated = workspace != NULL;
    gsl_function f = {speed_at, curve};
    double estimate = 0.0;
    int code = allocated ? gsl_integration_qag(&f, u_start, u_end, 0.0, 1e-12, LIMIT,
                                               GSL_INTEG_GAUSS41, workspace, length, &estimate)
                         : GSL_ENOMEM;
    if (allocated)
        gsl_integration_workspace_free(workspace);
    gsl_errors_restore();
    if (!allocated)
        return ur_error_out_of_memory(error);
    if (code && !(estimate <= 1e-9 * fabs(*length)))
        return ur_error_set(error, UR_ERROR_INTERNAL, "curve length did not converge: %s",
                            gsl_strerror(code));
    return UR_OK;
}
