/*
 * develop.c: from a developable ruled surface to flat nets.
 *
 * Every method produces a "strip": the flat ends of a sequence of rulings.
 * The exact method integrates the base curve's geodesic curvature with an
 * adaptive Runge-Kutta-Prince-Dormand (8,9) integrator, at parameters chosen
 * so that every outline chord stays within the tolerance; the discrete
 * methods (discrete.c) place triangles or quadrilaterals one after another.
 * The strip is then cut into the fewest pieces whose outlines do not
 * overlap themselves (GEOS decides), and each piece becomes a net.
 */
#include "develop_internal.h"

#include "../geom/geos_polygon.h"
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"
#include "../base/gsl_errors.h"

const char *ur_method_name(ur_method method)
{
    static const char *const names[] = {"exact", "triangle", "quad"};
    return method <= UR_METHOD_QUAD ? names[method] : "unknown";
}

int ur_method_from_name(const char *name)
{
    for (int method = UR_METHOD_EXACT; method <= UR_METHOD_QUAD; method++)
        if (strcmp(name, ur_method_name((ur_method)method)) == 0)
            return method;
    return -1;
}

void ur_develop_options_default(ur_develop_options *options)
{
    options->method = UR_METHOD_EXACT;
    options->rulings = 24;
    options->tolerance = 0.01;
    options->split = true;
    options->fit_length = options->fit_width = 0;
}

ur_status strip_alloc(strip *s, size_t count, ur_error *error)
{
    memset(s, 0, sizeof *s);
    s->count = count;
    s->u = ur_alloc_array(count, sizeof *s->u, error);
    s->near = ur_alloc_array(count, sizeof *s->near, error);
    s->far = ur_alloc_array(count, sizeof *s->far, error);
    s->drawn = ur_alloc_array(count, sizeof *s->drawn, error);
    if (!s->u || !s->near || !s->far || !s->drawn) {
        strip_free(s);
        return UR_ERROR_MEMORY;
    }
    return UR_OK;
}

void strip_free(strip *s)
{
    free(s->u);
    free(s->near);
    free(s->far);
    free(s->drawn);
    memset(s, 0, sizeof *s);
}

/* ---- Where to sample the exact development ------------------------------ */

enum { CELLS = 256, CELL_PROBES = 4 };

/*
 * A chord of parameter length h on a curve x(u) strays at most h^2 max|x''|/8
 * from it.  The flat image of a rail has the rail's arc length and only part
 * of its curvature (the geodesic part), so |flat x''| <= |3D x''|, and the
 * 3D second derivative, estimated per cell, bounds the steps needed.
 */
static size_t cell_steps(ur_ruled *ruled, double u0, double u1, double tolerance)
{
    double largest = 0.0, h = (u1 - u0) / CELL_PROBES;
    ur_vec3 previous[4], rails[4];
    ur_ruled_rails(ruled, u0, previous);
    for (int k = 1; k <= CELL_PROBES; k++) {
        ur_ruled_rails(ruled, u0 + k * h, rails);
        largest = fmax(largest, ur_vec3_distance(rails[1], previous[1]) / h);
        largest = fmax(largest, ur_vec3_distance(rails[3], previous[3]) / h);
        memcpy(previous, rails, sizeof rails);
    }
    double steps = ceil(1.25 * (u1 - u0) * sqrt(largest / (8 * tolerance)));
    return steps < 1 ? 1 : (size_t)fmin(steps, 1e7);
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sample parameters: enough for the tolerance, plus every drawn ruling. */
static ur_status exact_parameters(ur_ruled *ruled, const ur_develop_options *options, strip *s,
                                  ur_error *error)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    size_t steps[CELLS], total = 0;
    for (int c = 0; c < CELLS; c++) {
        steps[c] = cell_steps(ruled, u0 + (u1 - u0) * c / CELLS, u0 + (u1 - u0) * (c + 1) / CELLS,
                              options->tolerance);
        total += steps[c];
    }
    size_t parts = options->rulings > 0 ? options->rulings : 1;
    double *u = ur_alloc_array(total + parts + 1, sizeof *u, error);
    if (!u)
        return UR_ERROR_MEMORY;
    size_t count = 0;
    for (int c = 0; c < CELLS; c++)
        for (size_t k = 0; k < steps[c]; k++)
            u[count++] = u0 + (u1 - u0) * (c + (double)k / steps[c]) / CELLS;
    for (size_t k = 1; k < parts; k++)
        u[count++] = u0 + (u1 - u0) * k / parts;
    u[count++] = u1;
    qsort(u, count, sizeof *u, compare_doubles);
    ur_status status = strip_alloc(s, count, error);
    if (status != UR_OK) {
        free(u);
        return status;
    }
    /* Keep one of any two parameters too close to tell apart, preferring drawn ones. */
    double close = 1e-12 * (u1 - u0);
    size_t kept = 0;
    for (size_t i = 0; i < count; i++) {
        if (kept > 0 && u[i] - s->u[kept - 1] <= close)
            continue;
        s->u[kept++] = u[i];
    }
    s->count = kept;
    for (size_t k = 1; k < parts; k++) {
        double target = u0 + (u1 - u0) * k / parts;
        double *found = bsearch(&target, s->u, kept, sizeof *s->u, compare_doubles);
        size_t index = found ? (size_t)(found - s->u) : 0;
        if (!found) /* merged with a neighbour closer than `close` */
            for (index = 0; index + 1 < kept && s->u[index + 1] < target; index++)
                ;
        s->drawn[index] = true;
    }
    free(u);
    return UR_OK;
}

/* ---- The exact development ---------------------------------------------- */

/* y = (x, y, theta): the flat base curve and its direction. */
static int flat_curve_rhs(double u, const double y[], double dydu[], void *data)
{
    ur_ruling_intrinsics in;
    ur_ruled_intrinsics(data, u, &in);
    dydu[0] = in.speed * cos(y[2]);
    dydu[1] = in.speed * sin(y[2]);
    dydu[2] = in.geodesic_curvature * in.speed;
    return isfinite(dydu[2]) ? GSL_SUCCESS : GSL_EBADFUNC;
}

static void lay_off_ruling(ur_ruled *ruled, strip *s, size_t i, const double y[3])
{
    ur_ruling_intrinsics in;
    ur_ruled_intrinsics(ruled, s->u[i], &in);
    ur_vec2 base = {y[0], y[1]};
    ur_vec2 e = {cos(y[2] + in.angle), sin(y[2] + in.angle)};
    s->near[i] = ur_vec2_add_scaled(base, e, in.near);
    s->far[i] = ur_vec2_add_scaled(base, e, in.far);
}

enum { DENSE_SAMPLES = 20000 };

static ur_status integrate_flat_curve(ur_ruled *ruled, strip *s, ur_error *error)
{
    if (s->count < 2 || !(s->u[s->count - 1] > s->u[0]))
        return ur_error_set(error, UR_ERROR_INTERNAL,
                            "the development needs at least two increasing parameters");
    gsl_odeiv2_system system = {flat_curve_rhs, NULL, 3, ruled};
    double span = s->u[s->count - 1] - s->u[0];
    /*
     * Every sample costs at least one step.  Where samples are sparse the
     * 8th-order Prince-Dormand pair takes long steps; where they are dense
     * (many drawn rulings) the steps are short anyway and the Cash-Karp
     * 4(5) pair meets the same tolerances with 6 evaluations instead of 13.
     */
    const gsl_odeiv2_step_type *stepper =
        s->count > DENSE_SAMPLES ? gsl_odeiv2_step_rkck : gsl_odeiv2_step_rk8pd;
    gsl_odeiv2_driver *driver =
        gsl_odeiv2_driver_alloc_y_new(&system, stepper, span / 64, 1e-11, 1e-12);
    if (!driver)
        return ur_error_out_of_memory(error);
    double y[3] = {0.0, 0.0, 0.0}, u = s->u[0];
    lay_off_ruling(ruled, s, 0, y);
    for (size_t i = 1; i < s->count; i++) {
        int code = gsl_odeiv2_driver_apply(driver, &u, s->u[i], y);
        if (code != GSL_SUCCESS) {
            gsl_odeiv2_driver_free(driver);
            return ur_error_set(error, UR_ERROR_INTERNAL,
                                "the development did not converge at u = %g: %s", s->u[i],
                                gsl_strerror(code));
        }
        lay_off_ruling(ruled, s, i, y);
    }
    gsl_odeiv2_driver_free(driver);
    return UR_OK;
}

static ur_status develop_exact(ur_ruled *ruled, const ur_develop_options *options, strip *s,
                               ur_error *error)
{
    ur_status status = exact_parameters(ruled, options, s, error);
    if (status != UR_OK)
        return status; /* s was never allocated, or already freed */
    status = develop_exact_at(ruled, s, error);
    if (status != UR_OK)
        strip_free(s);
    return status;
}

/* ---- Splitting into pieces that do not overlap themselves --------------- */

enum { CHECK_POINTS = 6000 };

/* The outline of rulings first..last: near rail forward, far rail back. */
static size_t piece_ring(const strip *s, size_t first, size_t last, size_t stride, ur_vec2 *ring)
{
    size_t n = 0;
    for (size_t i = first + (s->skip_first_near ? 1 : 0); i < last; i += stride)
        ring[n++] = s->near[i];
    ring[n++] = s->near[last];
    for (size_t i = last; i > first; i = i - first > stride ? i - stride : first)
        ring[n++] = s->far[i];
    ring[n++] = s->far[first];
    return n;
}

/* A cone's rulings all end at its apex: keep one point for it, not one per ruling. */
static size_t drop_repeated(ur_vec2 *ring, size_t n)
{
    size_t kept = 0;
    for (size_t i = 0; i < n; i++)
        if (kept == 0 || ur_vec2_distance(ring[i], ring[kept - 1]) > 1e-9)
            ring[kept++] = ring[i];
    while (kept > 1 && ur_vec2_distance(ring[kept - 1], ring[0]) <= 1e-9)
        kept--;
    return kept;
}

static bool ring_is_simple(GEOSContextHandle_t geos, const ur_vec2 *ring, size_t n)
{
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, ring, n);
    if (!polygon)
        return false;
    bool simple = GEOSisValid_r(geos, polygon) == 1;
    GEOSGeom_destroy_r(geos, polygon);
    return simple;
}

bool ur_outline_is_simple(const ur_vec2 *ring, size_t count)
{
    GEOSContextHandle_t geos = GEOS_init_r();
    if (!geos)
        return false;
    bool simple = count >= 3 && ring_is_simple(geos, ring, count);
    GEOS_finish_r(geos);
    return simple;
}

/* The room a piece must fit (fit_length >= fit_width), or 0, 0 for any size. */
typedef struct room {
    double length, width;
} room;

/* Whether the ring's smallest enclosing rectangle fits the room in some turn. */
static bool ring_fits(GEOSContextHandle_t geos, const ur_vec2 *ring, size_t n, const room *r)
{
    if (!(r->length > 0))
        return true;
    ur_box box = ur_box_of_points(ring, n);
    double w = ur_box_width(box), h = ur_box_height(box);
    if (fmax(w, h) <= r->length && fmin(w, h) <= r->width)
        return true; /* as it lies: no need to look further */
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)n, 2);
    if (!sequence)
        return false;
    for (size_t i = 0; i < n; i++)
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, ring[i].x, ring[i].y);
    GEOSGeometry *points = GEOSGeom_createLineString_r(geos, sequence);
    GEOSGeometry *rectangle = points ? GEOSMinimumRotatedRectangle_r(geos, points) : NULL;
    const GEOSGeometry *shell = rectangle ? GEOSGetExteriorRing_r(geos, rectangle) : NULL;
    const GEOSCoordSequence *corners = shell ? GEOSGeom_getCoordSeq_r(geos, shell) : NULL;
    bool fits = false;
    unsigned size = 0;
    if (corners && GEOSCoordSeq_getSize_r(geos, corners, &size) && size >= 3) {
        double x[3], y[3];
        for (unsigned k = 0; k < 3; k++)
            GEOSCoordSeq_getXY_r(geos, corners, k, &x[k], &y[k]);
        double a = hypot(x[1] - x[0], y[1] - y[0]), b = hypot(x[2] - x[1], y[2] - y[1]);
        fits = fmax(a, b) <= r->length && fmin(a, b) <= r->width;
    }
    if (rectangle)
        GEOSGeom_destroy_r(geos, rectangle);
    if (points)
        GEOSGeom_destroy_r(geos, points);
    return fits;
}

/* Whether first..last makes a piece: not overlapping itself, and fitting the room. */
static bool piece_is_simple(GEOSContextHandle_t geos, const strip *s, size_t first, size_t last,
                            ur_vec2 *ring, const room *r)
{
    size_t stride = (last - first) / (CHECK_POINTS / 2) + 1;
    size_t n = drop_repeated(ring, piece_ring(s, first, last, stride, ring));
    return n >= 3 && ring_is_simple(geos, ring, n) && ring_fits(geos, ring, n, r);
}

/* The furthest last such that first..last does not overlap itself. */
static size_t furthest_simple(GEOSContextHandle_t geos, const strip *s, size_t first, ur_vec2 *ring,
                              const room *r)
{
    size_t good = first + 1, bad = s->count;
    if (piece_is_simple(geos, s, first, s->count - 1, ring, r))
        return s->count - 1;
    bad = s->count - 1;
    while (bad - good > 1) {
        size_t middle = good + (bad - good) / 2;
        if (piece_is_simple(geos, s, first, middle, ring, r))
            good = middle;
        else
            bad = middle;
    }
    return good;
}

/*
 * Greedy furthest reach gives the fewest pieces (a part of a piece that does
 * not overlap itself does not either); then, with that many pieces, equal
 * parameter lengths are tried, since equal pieces are easier to build from.
 */
static ur_status split_points(const strip *s, const room *r, size_t **cuts, size_t *piece_count,
                              ur_error *error)
{
    GEOSContextHandle_t geos = GEOS_init_r();
    ur_vec2 *ring = ur_alloc_array(CHECK_POINTS + 8, sizeof *ring, error);
    size_t *greedy = ur_alloc_array(s->count + 1, sizeof *greedy, error);
    if (!geos || !ring || !greedy) {
        free(ring);
        free(greedy);
        if (geos)
            GEOS_finish_r(geos);
        return ur_error_out_of_memory(error);
    }
    size_t count = 0;
    greedy[0] = 0;
    for (size_t first = 0; first < s->count - 1;) {
        greedy[++count] = first = furthest_simple(geos, s, first, ring, r);
        /*
         * A piece between two neighbouring samples that does not fit is too
         * wide for the room whatever the cuts: split for overlaps only, and
         * let placing say that it does not fit.
         */
        if (r->length > 0 && first == greedy[count - 1] + 1 &&
            !piece_is_simple(geos, s, greedy[count - 1], first, ring, r)) {
            static const room any = {0, 0};
            r = &any;
            count = 0;
            first = 0;
        }
    }
    bool even_ok = count > 1;
    size_t *even = ur_alloc_array(count + 1, sizeof *even, error);
    for (size_t k = 0; even && even_ok && k <= count; k++) {
        double target = s->u[0] + (s->u[s->count - 1] - s->u[0]) * k / count;
        size_t index = 0;
        while (index + 1 < s->count && s->u[index + 1] <= target)
            index++;
        if (index + 1 < s->count && target - s->u[index] > s->u[index + 1] - target)
            index++;
        even[k] = index;
        if (k > 0 &&
            (even[k] <= even[k - 1] || !piece_is_simple(geos, s, even[k - 1], index, ring, r)))
            even_ok = false;
    }
    free(ring);
    GEOS_finish_r(geos);
    if (!even) {
        free(greedy);
        return UR_ERROR_MEMORY;
    }
    if (even_ok) {
        free(greedy);
        *cuts = even;
    } else {
        free(even);
        *cuts = greedy;
    }
    *piece_count = count;
    return UR_OK;
}

/* ---- From strip pieces to nets ------------------------------------------ */

static double polyline_length_range(const ur_vec2 *points, size_t first, size_t last)
{
    return ur_polyline_length(points + first, last - first + 1, false);
}

static double relative_error(double flat, double space)
{
    return space > 0 ? fabs(flat - space) / space : 0.0;
}

/* Compares the flat boundary lengths with those of the 3D surface. */
static ur_status measure_edges(ur_ruled *ruled, const strip *s, size_t first, size_t last,
                               ur_net *net, ur_error *error)
{
    size_t near_first = first + (s->skip_first_near ? 1 : 0);
    double near_3d, far_3d;
    ur_status status =
        ur_ruled_rail_length(ruled, 0, s->u[near_first], s->u[last], &near_3d, error);
    if (status == UR_OK)
        status = ur_ruled_rail_length(ruled, 1, s->u[first], s->u[last], &far_3d, error);
    if (status != UR_OK)
        return status;
    ur_vec3 rails[4];
    ur_ruled_rails(ruled, s->u[last], rails);
    double ruling_3d = ur_vec3_distance(rails[0], rails[2]);
    double errors[3] = {
        relative_error(polyline_length_range(s->near, near_first, last), near_3d),
        relative_error(polyline_length_range(s->far, first, last), far_3d),
        relative_error(ur_vec2_distance(s->near[last], s->far[last]), ruling_3d),
    };
    net->edge_error = fmax(errors[0], fmax(errors[1], errors[2]));
    return UR_OK;
}

static void add_seam(ur_net *net, const strip *s, size_t i)
{
    ur_segment seam = {s->near[i], s->far[i]};
    net->seams[net->seam_count++] = seam;
}

static ur_status fill_net(ur_ruled *ruled, const strip *s, size_t first, size_t last,
                          bool seam_before, bool seam_after, ur_net *net, ur_error *error)
{
    size_t capacity = 2 * (last - first + 1);
    net->outline = ur_alloc_array(capacity, sizeof *net->outline, error);
    net->rulings = ur_alloc_array(last - first + 1, sizeof *net->rulings, error);
    net->ruling_parameters =
        ur_alloc_array(last - first + 1, sizeof *net->ruling_parameters, error);
    if (!net->outline || !net->rulings || !net->ruling_parameters)
        return UR_ERROR_MEMORY;
    net->outline_count = drop_repeated(net->outline, piece_ring(s, first, last, 1, net->outline));
    double area = ur_polygon_signed_area(net->outline, net->outline_count);
    if (area < 0)
        ur_points_reverse(net->outline, net->outline_count);
    net->flat_area = fabs(area);
    for (size_t i = first + 1; i < last; i++)
        if (s->drawn[i]) {
            /* The parameter goes with the ruling so allowances can ask the surface about it. */
            ur_segment ruling = {s->near[i], s->far[i]};
            net->ruling_parameters[net->ruling_count] = s->u[i];
            net->rulings[net->ruling_count++] = ruling;
        }
    if (seam_before)
        add_seam(net, s, first);
    if (seam_after)
        add_seam(net, s, last);
    net->u_start = s->u[first];
    net->u_end = s->u[last];
    ur_status status = ur_ruled_area(ruled, net->u_start, net->u_end, &net->area_3d, error);
    if (status == UR_OK)
        status = measure_edges(ruled, s, first, last, net, error);
    return status;
}

/*
 * The outline index of a point the outline was copied from, or SIZE_MAX.
 * drop_repeated keeps one of a cone's apex points, which the rulings reach
 * within rounding of each other: the same tolerance finds it.
 */
static size_t outline_index(const ur_net *net, ur_vec2 point)
{
    for (size_t i = 0; i < net->outline_count; i++)
        if (ur_vec2_distance(net->outline[i], point) <= 1e-9)
            return i;
    return SIZE_MAX;
}

/*
 * A cut ruling as a seam side: its two ends are neighbours on the outline
 * (the outline runs along one rail, across the end ruling and back).  A
 * ruling of no length (at a cone's apex) is no side.
 */
static ur_status add_ruling_side(ur_net *net, ur_segment ruling, int seam, ur_error *error)
{
    size_t a = outline_index(net, ruling.start), b = outline_index(net, ruling.end);
    size_t n = net->outline_count;
    if (a == SIZE_MAX || b == SIZE_MAX || a == b)
        return UR_OK;
    size_t first;
    if ((a + 1) % n == b)
        first = a;
    else if ((b + 1) % n == a)
        first = b;
    else
        return ur_error_set(error, UR_ERROR_INTERNAL,
                            "net %s: a cut ruling's ends are not neighbours on its outline",
                            net->name);
    ur_seam_side *sides = realloc(net->seam_sides, (net->seam_side_count + 1) * sizeof *sides);
    if (!sides)
        return ur_error_out_of_memory(error);
    net->seam_sides = sides;
    sides[net->seam_side_count++] = (ur_seam_side){first, 2, seam};
    return UR_OK;
}

/*
 * Seam k (from 1) joins piece k to piece k + 1; on a closed surface seam
 * piece_count joins the last piece back to the first.  seams[0] of a
 * piece is its first ruling when it has a seam there (fill_net).
 */
static ur_status number_ruling_seams(ur_net *net, size_t k, size_t piece_count, bool closed,
                                     ur_error *error)
{
    bool before = k > 0 || closed, after = k + 1 < piece_count || closed;
    int before_seam = k > 0 ? (int)k : (int)piece_count;
    int after_seam = (int)k + 1;
    ur_status status = UR_OK;
    size_t next = 0;
    if (before)
        status = add_ruling_side(net, net->seams[next++], before_seam, error);
    if (status == UR_OK && after)
        status = add_ruling_side(net, net->seams[next], after_seam, error);
    return status;
}

static ur_status nets_from_strip(ur_ruled *ruled, const strip *s, const size_t *cuts,
                                 size_t piece_count, ur_net_list *nets, ur_error *error)
{
    nets->nets = ur_alloc_array(piece_count, sizeof *nets->nets, error);
    if (!nets->nets)
        return UR_ERROR_MEMORY;
    nets->count = piece_count;
    bool closed = ur_ruled_is_closed(ruled);
    for (size_t k = 0; k < piece_count; k++) {
        ur_net *net = &nets->nets[k];
        c_snprintf(net->name, sizeof net->name, "P%zu", k + 1);
        ur_status status = fill_net(ruled, s, cuts[k], cuts[k + 1], k > 0 || closed,
                                    k + 1 < piece_count || closed, net, error);
        if (status == UR_OK)
            status = number_ruling_seams(net, k, piece_count, closed, error);
        if (status != UR_OK) {
            ur_net_list_free(nets);
            return status;
        }
    }
    return UR_OK;
}

ur_status develop_exact_at(ur_ruled *ruled, strip *s, ur_error *error)
{
    gsl_errors_off(); /* GSL's default handler would abort */
    ur_status status = integrate_flat_curve(ruled, s, error);
    gsl_errors_restore();
    return status;
}

static ur_status develop(ur_ruled *ruled, const ur_develop_options *options, ur_net_list *nets,
                         ur_error *error)
{
    memset(nets, 0, sizeof *nets);
    if (!(options->tolerance > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "the tolerance must be positive");
    ur_status status = ur_ruled_check(ruled, error);
    if (status != UR_OK)
        return status;
    strip s;
    if (options->method == UR_METHOD_EXACT)
        status = develop_exact(ruled, options, &s, error);
    else
        status = develop_discrete(ruled, options, &s, error);
    if (status != UR_OK)
        return status;
    size_t *cuts = NULL, piece_count = 0;
    room fit = {fmax(options->fit_length, options->fit_width),
                fmin(options->fit_length, options->fit_width)};
    status = split_points(&s, &fit, &cuts, &piece_count, error);
    if (status == UR_OK && piece_count > 1 && !options->split)
        status = ur_error_set(error, UR_ERROR_INPUT,
                              "the net overlaps itself or is too long for the sheet, and would "
                              "need %zu pieces",
                              piece_count);
    if (status == UR_OK)
        status = nets_from_strip(ruled, &s, cuts, piece_count, nets, error);
    free(cuts);
    strip_free(&s);
    return status;
}

ur_status ur_develop(ur_ruled *ruled, const ur_develop_options *options, ur_net_list *nets,
                     ur_error *error)
{
    gsl_errors_off();
    ur_status status = develop(ruled, options, nets, error);
    gsl_errors_restore();
    return status;
}
