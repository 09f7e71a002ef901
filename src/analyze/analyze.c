/*
 * analyze.c: the curvature of a ruled surface in closed form on its rails
 * (see analyze.h for the formulas), sampled ruling by ruling into the
 * analysis behind `unroll analyze`: developability residual, Gaussian
 * curvature, bend radius, striction line and area.
 */
#include "unroll/analyze.h"

#include <stdlib.h>
#include <string.h>

enum { DEFAULT_RULINGS = 256, DEFAULT_ACROSS = 17 };

/*
 * Step of the differences for a'' and b'', as a fraction of the u range:
 * truncation about h^2 / 6, some 1e-9 relative on a range of 2 pi, against
 * rounding of about 1e-16 / h = 1e-11.
 */
static const double DIFFERENCE_STEP = 1e-5;

/* |r_u x r_v| below this fraction of (|a'| + |b'|) |b - a|: no tangent plane. */
static const double SINGULAR = 1e-10;

/* det(a', b', b - a) below this fraction of |a'| |b'| |b - a| is rounding. */
static const double ROUNDING = 1e-12;

/* A largest curvature below this over the surface's size is no bending at all. */
static const double FLAT = 1e-8;

void ur_analysis_options_default(ur_analysis_options *options)
{
    options->rulings = DEFAULT_RULINGS;
    options->across = DEFAULT_ACROSS;
    options->tolerance = UR_DEVELOPABLE_RESIDUAL;
}

/*
 * The part of [start, end] around u that has a surface: a strip's rails go on
 * into the gaps of its domain, but the rulings there are no continuation.
 */
static void surface_part(ur_ruled *ruled, double u, double *u0, double *u1)
{
    *u0 = ur_ruled_start(ruled);
    *u1 = ur_ruled_end(ruled);
    const ur_interval *gaps = NULL;
    size_t count = ur_ruled_gaps(ruled, &gaps);
    for (size_t k = 0; k < count; k++) {
        if (gaps[k].u_end <= u)
            *u0 = fmax(*u0, gaps[k].u_end);
        if (gaps[k].u_start >= u)
            *u1 = fmin(*u1, gaps[k].u_start);
    }
}

/*
 * a'' (second[0]) and b'' (second[1]) at u: central differences of a' and b',
 * one-sided of the same (second) order where the centre would leave the part
 * of the surface u is in, since the rails need not exist (or not as this
 * surface) outside it.
 */
static void rail_second_derivatives(ur_ruled *ruled, double u, ur_vec3 second[2])
{
    double u0, u1;
    surface_part(ruled, u, &u0, &u1);
    double range = ur_ruled_end(ruled) - ur_ruled_start(ruled);
    double h = fmin(DIFFERENCE_STEP * range, (u1 - u0) / 4);
    double at[3], weight[3];
    int count = 3;
    if (u - h < u0) {
        at[0] = u, at[1] = u + h, at[2] = u + 2 * h;
        weight[0] = -1.5, weight[1] = 2.0, weight[2] = -0.5;
    } else if (u + h > u1) {
        at[0] = u, at[1] = u - h, at[2] = u - 2 * h;
        weight[0] = 1.5, weight[1] = -2.0, weight[2] = 0.5;
    } else {
        count = 2;
        at[0] = u - h, at[1] = u + h;
        weight[0] = -0.5, weight[1] = 0.5;
    }
    second[0] = second[1] = ur_vec3_make(0, 0, 0);
    for (int k = 0; k < count; k++) {
        ur_vec3 rails[4];
        ur_ruled_rails(ruled, at[k], rails);
        second[0] = ur_vec3_add_scaled(second[0], rails[1], weight[k] / h);
        second[1] = ur_vec3_add_scaled(second[1], rails[3], weight[k] / h);
    }
}

static void set_singular(ur_point_curvature *curvature)
{
    curvature->normal = ur_vec3_make(0, 0, 0);
    curvature->singular = true;
    curvature->gaussian = NAN;
    curvature->mean = NAN;
    curvature->bend_radius = 0.0;
}

/* 1 / max |kappa|, the principal curvatures being H +- sqrt(H^2 - K). */
static double bend_radius(double gaussian, double mean, double size)
{
    double largest = fabs(mean) + sqrt(fmax(mean * mean - gaussian, 0.0));
    return largest * size <= FLAT ? INFINITY : 1.0 / largest;
}

/*
 * What the curvature anywhere along the ruling at u needs: the rails, a''
 * and b'', and the size of the surface.  Worked out once per ruling, since
 * each costs the rails' pairing.
 */
typedef struct ruling_frame {
    ur_vec3 rails[4];
    ur_vec3 second[2];
    double u_range;
} ruling_frame;

static void ruling_frame_at(ur_ruled *ruled, double u, ruling_frame *frame)
{
    ur_ruled_rails(ruled, u, frame->rails);
    rail_second_derivatives(ruled, u, frame->second);
    frame->u_range = ur_ruled_end(ruled) - ur_ruled_start(ruled);
}

static void point_curvature(const ruling_frame *frame, double v, ur_point_curvature *curvature)
{
    const ur_vec3 *rails = frame->rails;
    ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]); /* r_v */
    ur_vec3 twist = ur_vec3_sub(rails[3], rails[1]);  /* r_uv */
    ur_vec3 r_u = ur_vec3_add_scaled(rails[1], twist, v);
    ur_vec3 n = ur_vec3_cross(r_u, ruling);
    double n_length = ur_vec3_length(n);
    double a_speed = ur_vec3_length(rails[1]), b_speed = ur_vec3_length(rails[3]);
    double ruling_length = ur_vec3_length(ruling);
    curvature->point = ur_vec3_add_scaled(rails[0], ruling, v);
    curvature->area_element = n_length;
    if (!(n_length > SINGULAR * (a_speed + b_speed) * ruling_length)) {
        set_singular(curvature);
        return;
    }
    curvature->singular = false;
    curvature->normal = ur_vec3_scale(n, 1.0 / n_length);
    double det = ur_vec3_det(rails[1], rails[3], ruling);
    if (fabs(det) <= ROUNDING * a_speed * b_speed * ruling_length)
        det = 0.0;
    const ur_vec3 *second = frame->second;
    ur_vec3 r_uu = ur_vec3_add_scaled(second[0], ur_vec3_sub(second[1], second[0]), v);
    double area_squared = n_length * n_length; /* E G - F^2 */
    double F = ur_vec3_dot(r_u, ruling), G = ruling_length * ruling_length;
    double L = ur_vec3_dot(r_uu, curvature->normal);
    double M = -det / n_length; /* r_uv . N = det(b' - a', r_u, r_v) / |n| */
    curvature->gaussian = -(M * M) / area_squared;
    curvature->mean = (G * L - 2 * F * M) / (2 * area_squared);
    double size = fmax(ruling_length, ur_vec3_length(r_u) * frame->u_range);
    curvature->bend_radius = bend_radius(curvature->gaussian, curvature->mean, size);
}

void ur_analyze_point(ur_ruled *ruled, double u, double v, ur_point_curvature *curvature)
{
    ruling_frame frame;
    ruling_frame_at(ruled, u, &frame);
    point_curvature(&frame, v, curvature);
}

double ur_analyze_bend_radius(ur_ruled *ruled, double u, size_t across, double *v)
{
    if (across < 2)
        across = 2;
    ruling_frame frame;
    ruling_frame_at(ruled, u, &frame);
    double smallest = INFINITY, where = 0.0;
    for (size_t j = 0; j < across; j++) {
        ur_point_curvature point;
        point_curvature(&frame, (double)j / (double)(across - 1), &point);
        if (point.bend_radius < smallest) {
            smallest = point.bend_radius;
            where = (double)j / (double)(across - 1);
        }
    }
    if (v)
        *v = where;
    return smallest;
}

/* ---- The analysis ------------------------------------------------------- */

static ur_status check_options(const ur_analysis_options *options, ur_error *error)
{
    if (options->rulings < 2)
        return ur_error_set(error, UR_ERROR_INPUT, "the analysis needs at least 2 rulings");
    if (options->across < 2)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the analysis needs at least 2 samples along each ruling");
    if (!(options->tolerance >= 0) || !isfinite(options->tolerance))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the developability tolerance must be zero or positive");
    return UR_OK;
}

/*
 * The parts of rail 1 that have a surface (ur_ruled_domain), in an array the
 * caller frees.  A ruling exists when it lies in one of them, ends included:
 * there the strip still has its limiting ruling.
 */
static ur_status domain_parts(ur_ruled *ruled, ur_interval **parts, size_t *count, ur_error *error)
{
    ur_interval probe;
    *count = ur_ruled_domain(ruled, &probe, 1);
    *parts = ur_alloc_array(*count, sizeof **parts, error);
    if (!*parts)
        return UR_ERROR_MEMORY;
    *count = ur_ruled_domain(ruled, *parts, *count);
    return UR_OK;
}

static bool exists(const ur_interval *parts, size_t count, double u)
{
    for (size_t k = 0; k < count; k++)
        if (u >= parts[k].u_start && u <= parts[k].u_end)
            return true;
    return false;
}

/* The area of the parts of the surface, within [start, end]. */
static ur_status domain_area(ur_ruled *ruled, const ur_interval *parts, size_t count, double *area,
                             ur_error *error)
{
    /* The domain covers the whole rail; the surface may be restricted to part of it. */
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    ur_status status = UR_OK;
    *area = 0.0;
    for (size_t k = 0; k < count && status == UR_OK; k++) {
        double from = fmax(parts[k].u_start, u0), to = fmin(parts[k].u_end, u1), part = 0.0;
        if (to > from)
            status = ur_ruled_area(ruled, from, to, &part, error);
        *area += part;
    }
    return status;
}

/* Parameters, arc lengths along rail a and ends of the rulings. */
static ur_status place_rulings(ur_ruled *ruled, ur_analysis *analysis, ur_error *error)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    size_t count = analysis->ruling_count;
    for (size_t i = 0; i < count; i++) {
        ur_ruling_analysis *ruling = &analysis->rulings[i];
        /* The last ruling at u1 exactly, not u0 plus a rounded multiple. */
        ruling->u = i + 1 == count ? u1 : u0 + (u1 - u0) * (double)i / (double)(count - 1);
        ruling->arc = 0.0;
        if (i > 0) {
            double piece;
            ur_status status = ur_ruled_rail_length(ruled, 0, analysis->rulings[i - 1].u, ruling->u,
                                                    &piece, error);
            if (status != UR_OK)
                return status;
            ruling->arc = analysis->rulings[i - 1].arc + piece;
        }
        ur_vec3 rails[4];
        ur_ruled_rails(ruled, ruling->u, rails);
        ruling->near = rails[0];
        ruling->far = rails[2];
    }
    return UR_OK;
}

static void mark_gap(ur_ruling_analysis *ruling)
{
    ruling->in_gap = true;
    ruling->residual = NAN;
    ruling->gaussian_min = ruling->gaussian_max = NAN;
    ruling->bend_radius = ruling->bend_v = NAN;
    ruling->striction_v = NAN;
}

/* What the surface-wide extremes have seen so far. */
typedef struct extremes {
    bool seen_gaussian, seen_bend;
} extremes;

static void note_point(ur_analysis *analysis, extremes *seen, const ur_point_curvature *point)
{
    if (!seen->seen_bend || point->bend_radius < analysis->min_bend_radius) {
        analysis->min_bend_radius = point->bend_radius;
        analysis->min_bend_at = point->point;
        seen->seen_bend = true;
    }
    if (point->singular)
        return;
    if (!seen->seen_gaussian || point->gaussian < analysis->gaussian_min) {
        analysis->gaussian_min = point->gaussian;
        analysis->gaussian_min_at = point->point;
    }
    if (!seen->seen_gaussian || point->gaussian > analysis->gaussian_max) {
        analysis->gaussian_max = point->gaussian;
        analysis->gaussian_max_at = point->point;
    }
    seen->seen_gaussian = true;
}

/*
 * Samples one ruling at `across` points from rail a to rail b; returns in
 * integrals[0] the integral over v of K |n| and in integrals[1] that of |n|
 * (trapezoid rule), the ruling's share of the integral of K dA and of the area.
 */
static void sample_ruling(ur_ruled *ruled, ur_analysis *analysis, extremes *seen,
                          ur_ruling_analysis *ruling, double integrals[2])
{
    size_t across = analysis->across;
    ruling->gaussian_min = INFINITY;
    ruling->gaussian_max = -INFINITY;
    ruling->bend_radius = INFINITY;
    ruling->bend_v = 0.0;
    integrals[0] = integrals[1] = 0.0;
    ruling_frame frame;
    ruling_frame_at(ruled, ruling->u, &frame);
    for (size_t j = 0; j < across; j++) {
        double v = (double)j / (double)(across - 1);
        ur_point_curvature point;
        point_curvature(&frame, v, &point);
        note_point(analysis, seen, &point);
        if (point.bend_radius < ruling->bend_radius) {
            ruling->bend_radius = point.bend_radius;
            ruling->bend_v = v;
        }
        if (point.singular)
            continue; /* |n| = 0 there: nothing to add to either integral */
        ruling->gaussian_min = fmin(ruling->gaussian_min, point.gaussian);
        ruling->gaussian_max = fmax(ruling->gaussian_max, point.gaussian);
        double weight = (j == 0 || j + 1 == across ? 0.5 : 1.0) / (double)(across - 1);
        integrals[0] += weight * point.gaussian * point.area_element;
        integrals[1] += weight * point.area_element;
    }
    if (ruling->gaussian_min > ruling->gaussian_max) /* every sample singular */
        ruling->gaussian_min = ruling->gaussian_max = NAN;
}

static void analyze_ruling(ur_ruled *ruled, ur_analysis *analysis, extremes *seen,
                           ur_ruling_analysis *ruling, double integrals[2])
{
    sample_ruling(ruled, analysis, seen, ruling, integrals);
    ruling->residual = ur_ruled_residual(ruled, ruling->u);
    ur_vec3 striction;
    double v;
    ruling->striction_v = ur_ruled_regression(ruled, ruling->u, &striction, &v) ? v : NAN;
}

/* Largest residual; a NAN residual (should one appear) sticks and fails the test. */
static void note_residual(ur_analysis *analysis, size_t index)
{
    double residual = analysis->rulings[index].residual;
    if (isnan(residual) || residual > analysis->max_residual) {
        analysis->max_residual = residual;
        analysis->worst_ruling = index;
    }
}

/* Every ruling, and the trapezoid rule across them for the mean of K. */
static void analyze_rulings(ur_ruled *ruled, const ur_interval *parts, size_t part_count,
                            ur_analysis *analysis)
{
    extremes seen = {false, false};
    double previous[2] = {0, 0}, gaussian_integral = 0.0, area_integral = 0.0;
    bool previous_exists = false;
    analysis->max_residual = 0.0;
    analysis->min_bend_radius = INFINITY; /* should every ruling be in a gap */
    for (size_t i = 0; i < analysis->ruling_count; i++) {
        ur_ruling_analysis *ruling = &analysis->rulings[i];
        if (!exists(parts, part_count, ruling->u)) {
            mark_gap(ruling);
            previous_exists = false;
            continue;
        }
        double integrals[2];
        analyze_ruling(ruled, analysis, &seen, ruling, integrals);
        note_residual(analysis, i);
        if (previous_exists) {
            double step = 0.5 * (ruling->u - analysis->rulings[i - 1].u);
            gaussian_integral += step * (previous[0] + integrals[0]);
            area_integral += step * (previous[1] + integrals[1]);
        }
        previous[0] = integrals[0], previous[1] = integrals[1];
        previous_exists = true;
    }
    if (!seen.seen_gaussian)
        analysis->gaussian_min = analysis->gaussian_max = NAN;
    analysis->gaussian_mean = area_integral > 0 ? gaussian_integral / area_integral : NAN;
}

ur_status ur_analyze(ur_ruled *ruled, const ur_analysis_options *options, ur_analysis *analysis,
                     ur_error *error)
{
    memset(analysis, 0, sizeof *analysis);
    ur_analysis_options defaults;
    if (!options) {
        ur_analysis_options_default(&defaults);
        options = &defaults;
    }
    ur_status status = check_options(options, error);
    if (status != UR_OK)
        return status;
    analysis->rulings = ur_alloc_array(options->rulings, sizeof *analysis->rulings, error);
    if (!analysis->rulings)
        return UR_ERROR_MEMORY;
    analysis->ruling_count = options->rulings;
    analysis->across = options->across;
    ur_interval *parts = NULL;
    size_t part_count = 0;
    status = domain_parts(ruled, &parts, &part_count, error);
    if (status == UR_OK)
        status = domain_area(ruled, parts, part_count, &analysis->area_3d, error);
    if (status == UR_OK)
        status = place_rulings(ruled, analysis, error);
    if (status == UR_OK)
        analyze_rulings(ruled, parts, part_count, analysis);
    free(parts);
    if (status != UR_OK)
        return status;
    analysis->developable = analysis->max_residual <= options->tolerance;
    return UR_OK;
}

void ur_analysis_free(ur_analysis *analysis)
{
    if (analysis) {
        free(analysis->rulings);
        memset(analysis, 0, sizeof *analysis);
    }
}
