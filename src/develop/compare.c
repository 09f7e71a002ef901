/*
 * compare.c: the seed paper's observation ([Seed2018] in
 * docs/bibliography.md), measured.  For n = n_min, 2 n_min, ...
 * the triangle and quad nets are compared with the exact one: flat area
 * against the 3D area, flat rail lengths against the 3D arc lengths, and how
 * far each boundary point lies from its place in the exact net.
 *
 * It works on the strips (the flat ends of the rulings) rather than on the
 * nets, because only the strips say which flat point belongs to which
 * ruling; that is why it lives in the develop module.  The exact net is
 * developed independently of the discrete ones, with ur_develop at a tight
 * tolerance, so that its own errors are measured and not assumed.
 */
#include "develop_internal.h"

#include <stdlib.h>
#include <string.h>

/* The exact net's tolerance, relative to the surface's size (see ur_compare). */
#define EXACT_TOLERANCE 1e-8

/* A rail shorter than this fraction of the size is a point (a cone's apex). */
#define POINT_RAIL 1e-12

enum { SIZE_PROBES = 256 };

/* What every row is measured against. */
typedef struct reference {
    double area_3d;
    double size; /* the larger of rail a's length and the longest ruling, mm */
} reference;

/* ---- The boundary of a strip as one ring ------------------------------- */

/*
 * The strip's outline, as develop.c draws it: the near rail forward (without
 * the triangle method's first near point, which is no vertex of the net),
 * then the far rail back.  Ring point k of two strips with the same u is the
 * same point of the surface.
 */
static size_t ring_count(const strip *s)
{
    return 2 * s->count - (s->skip_first_near ? 1 : 0);
}

static ur_vec2 ring_point(const strip *s, size_t k)
{
    size_t first = s->skip_first_near ? 1 : 0, near_count = s->count - first;
    return k < near_count ? s->near[first + k] : s->far[s->count - 1 - (k - near_count)];
}

/* Shoelace area, taken about the first point so large coordinates do not cancel. */
static double ring_area(const strip *s)
{
    size_t count = ring_count(s);
    ur_vec2 origin = ring_point(s, 0), previous = {0, 0};
    double twice = 0;
    for (size_t k = 1; k <= count; k++) {
        ur_vec2 p = ur_vec2_sub(ring_point(s, k % count), origin);
        twice += ur_vec2_cross(previous, p);
        previous = p;
    }
    return fabs(twice) / 2;
}

/* ---- Lengths ------------------------------------------------------------ */

static double polyline_length(const ur_vec2 *points, size_t first, size_t last)
{
    return ur_polyline_length(points + first, last - first + 1, false);
}

/* The relative error of one rail, or 0 for a rail that is a single point. */
static ur_status rail_error(ur_ruled *ruled, int rail, const strip *s, size_t first, double size,
                            double *relative, ur_error *error)
{
    size_t last = s->count - 1;
    double space;
    ur_status status = ur_ruled_rail_length(ruled, rail, s->u[first], s->u[last], &space, error);
    if (status != UR_OK)
        return status;
    double flat = polyline_length(rail == 0 ? s->near : s->far, first, last);
    *relative = space > POINT_RAIL * size ? fabs(flat - space) / space : 0.0;
    return UR_OK;
}

static ur_status edge_error(ur_ruled *ruled, const strip *s, double size, double *largest,
                            ur_error *error)
{
    double near, far;
    ur_status status = rail_error(ruled, 0, s, s->skip_first_near ? 1 : 0, size, &near, error);
    if (status == UR_OK)
        status = rail_error(ruled, 1, s, 0, size, &far, error);
    if (status == UR_OK)
        *largest = fmax(near, far);
    return status;
}

/* The size that scales the exact net's tolerance. */
static ur_status surface_size(ur_ruled *ruled, double *size, ur_error *error)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled), rail;
    ur_status status = ur_ruled_rail_length(ruled, 0, u0, u1, &rail, error);
    if (status != UR_OK)
        return status;
    double longest = 0;
    for (int k = 0; k <= SIZE_PROBES; k++) {
        ur_vec3 rails[4];
        ur_ruled_rails(ruled, u0 + (u1 - u0) * k / SIZE_PROBES, rails);
        longest = fmax(longest, ur_vec3_distance(rails[0], rails[2]));
    }
    *size = fmax(rail, longest);
    if (!(*size > 0) || !isfinite(*size))
        return ur_error_set(error, UR_ERROR_INPUT, "the surface has no extent to compare");
    return UR_OK;
}

/* ---- Rigid fit ---------------------------------------------------------- */

static ur_vec2 ring_centroid(const strip *s)
{
    size_t count = ring_count(s);
    ur_vec2 sum = {0, 0};
    for (size_t k = 0; k < count; k++)
        sum = ur_vec2_add(sum, ring_point(s, k));
    return ur_vec2_scale(sum, 1.0 / count);
}

/*
 * The largest distance between corresponding ring points once `moved` is
 * fitted to `fixed` by the rotation (or, when that fits better, reflection)
 * and translation that minimise the sum of squared distances (Kabsch in the
 * plane: the angle comes straight from the summed dot and cross products).
 */
static double fitted_distance(const strip *moved, const strip *fixed)
{
    size_t count = ring_count(moved);
    ur_vec2 cp = ring_centroid(moved), cq = ring_centroid(fixed);
    double dot = 0, cross = 0, mirror_dot = 0, mirror_cross = 0;
    for (size_t k = 0; k < count; k++) {
        ur_vec2 p = ur_vec2_sub(ring_point(moved, k), cp);
        ur_vec2 q = ur_vec2_sub(ring_point(fixed, k), cq);
        dot += ur_vec2_dot(p, q);
        cross += ur_vec2_cross(p, q);
        mirror_dot += p.x * q.x - p.y * q.y; /* the same with p mirrored, y -> -y */
        mirror_cross += p.x * q.y + p.y * q.x;
    }
    bool mirror = hypot(mirror_dot, mirror_cross) > hypot(dot, cross);
    double angle = mirror ? atan2(mirror_cross, mirror_dot) : atan2(cross, dot);
    double c = cos(angle), s = sin(angle), largest = 0;
    for (size_t k = 0; k < count; k++) {
        ur_vec2 p = ur_vec2_sub(ring_point(moved, k), cp);
        if (mirror)
            p.y = -p.y;
        ur_vec2 turned = {c * p.x - s * p.y, s * p.x + c * p.y};
        ur_vec2 q = ur_vec2_sub(ring_point(fixed, k), cq);
        largest = fmax(largest, ur_vec2_distance(turned, q));
    }
    return largest;
}

/* ---- Rows --------------------------------------------------------------- */

static ur_status discrete_strip(ur_ruled *ruled, ur_method method, size_t n, strip *s,
                                ur_error *error)
{
    ur_develop_options options;
    ur_develop_options_default(&options);
    options.method = method;
    options.rulings = n;
    return develop_discrete(ruled, &options, s, error);
}

/* The exact net at the discrete strip's parameters: its corresponding points. */
static ur_status exact_strip(ur_ruled *ruled, const strip *discrete, strip *s, ur_error *error)
{
    ur_status status = strip_alloc(s, discrete->count, error);
    if (status != UR_OK)
        return status;
    memcpy(s->u, discrete->u, discrete->count * sizeof *s->u);
    status = develop_exact_at(ruled, s, error);
    if (status != UR_OK)
        strip_free(s);
    return status;
}

/* Fills method k of row from its strip and the exact strip at the same u. */
static ur_status measure(ur_ruled *ruled, const strip *s, const strip *exact,
                         const reference *against, int k, ur_compare_row *row, ur_error *error)
{
    row->available[k] = true;
    row->area_error[k] = (ring_area(s) - against->area_3d) / against->area_3d;
    strip same = *exact; /* a view: the exact points, left out where s leaves them out */
    same.skip_first_near = s->skip_first_near;
    row->distance[k] = fitted_distance(s, &same);
    return edge_error(ruled, s, against->size, &row->edge_error[k], error);
}

static ur_status method_row(ur_ruled *ruled, ur_method method, int k, const strip *exact,
                            const reference *against, ur_compare_row *row, ur_error *error)
{
    strip s;
    ur_status status = discrete_strip(ruled, method, row->n, &s, error);
    if (status != UR_OK)
        return status;
    /* Both methods place the rulings at the same u, so one exact strip serves both. */
    if (s.count != exact->count || memcmp(s.u, exact->u, s.count * sizeof *s.u) != 0)
        status = ur_error_set(error, UR_ERROR_INTERNAL,
                              "the %s method placed its rulings elsewhere", ur_method_name(method));
    if (status == UR_OK)
        status = measure(ruled, &s, exact, against, k, row, error);
    strip_free(&s);
    return status;
}

static ur_status discrete_row(ur_ruled *ruled, const reference *against, ur_compare_row *row,
                              ur_error *error)
{
    strip quad, exact;
    ur_status status = discrete_strip(ruled, UR_METHOD_QUAD, row->n, &quad, error);
    if (status != UR_OK)
        return status;
    status = exact_strip(ruled, &quad, &exact, error);
    if (status != UR_OK) {
        strip_free(&quad);
        return status;
    }
    status = measure(ruled, &quad, &exact, against, UR_COMPARE_QUAD, row, error);
    strip_free(&quad);
    if (status == UR_OK && ruled->kind == UR_RULED_TANGENT)
        status =
            method_row(ruled, UR_METHOD_TRIANGLE, UR_COMPARE_TRIANGLE, &exact, against, row, error);
    strip_free(&exact);
    return status;
}

/* The exact net's own errors, measured once: they do not depend on n. */
static ur_status exact_errors(ur_ruled *ruled, const reference *against, double *area_error,
                              double *edge_error, ur_error *error)
{
    ur_develop_options options;
    ur_develop_options_default(&options);
    options.method = UR_METHOD_EXACT;
    options.tolerance = EXACT_TOLERANCE * against->size;
    options.split = true; /* a helicoid of a turn or more needs pieces */
    ur_net_list nets;
    ur_status status = ur_develop(ruled, &options, &nets, error);
    if (status != UR_OK) {
        ur_error_prefix(error, "the exact net: ");
        return status;
    }
    double flat = 0, edge = 0;
    for (size_t k = 0; k < nets.count; k++) {
        flat += nets.nets[k].flat_area;
        edge = fmax(edge, nets.nets[k].edge_error);
    }
    ur_net_list_free(&nets);
    *area_error = (flat - against->area_3d) / against->area_3d;
    *edge_error = edge;
    return UR_OK;
}

static void row_clear(ur_compare_row *row, size_t n)
{
    memset(row, 0, sizeof *row);
    row->n = n;
    for (int k = 0; k < UR_COMPARE_METHODS; k++) {
        row->area_error[k] = NAN;
        row->edge_error[k] = NAN;
        row->distance[k] = NAN;
    }
}

/* How many of n_min, 2 n_min, ... are at most n_max (without overflowing). */
static size_t row_count(size_t n_min, size_t n_max)
{
    size_t count = 1;
    for (size_t n = n_min; n <= n_max / 2; n *= 2)
        count++;
    return count;
}

static ur_status fill_rows(ur_ruled *ruled, size_t n_min, const reference *against,
                           ur_compare_table *table, ur_error *error)
{
    double area_error, edge_error;
    ur_status status = exact_errors(ruled, against, &area_error, &edge_error, error);
    size_t n = n_min;
    for (size_t r = 0; status == UR_OK && r < table->count; r++, n *= 2) {
        ur_compare_row *row = &table->rows[r];
        row_clear(row, n);
        row->available[UR_COMPARE_EXACT] = true;
        row->area_error[UR_COMPARE_EXACT] = area_error;
        row->edge_error[UR_COMPARE_EXACT] = edge_error;
        row->distance[UR_COMPARE_EXACT] = 0;
        status = discrete_row(ruled, against, row, error);
        if (status != UR_OK)
            ur_error_prefix(error, "n = %zu: ", n);
    }
    return status;
}

ur_status ur_compare(ur_ruled *ruled, size_t n_min, size_t n_max, ur_compare_table *table,
                     ur_error *error)
{
    memset(table, 0, sizeof *table);
    if (n_min < 1 || n_max < n_min)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the numbers of parts must satisfy 1 <= n_min <= n_max "
                            "(got %zu and %zu)",
                            n_min, n_max);
    ur_status status = ur_ruled_check(ruled, error);
    if (status != UR_OK)
        return status;
    reference against;
    status =
        ur_ruled_area(ruled, ur_ruled_start(ruled), ur_ruled_end(ruled), &against.area_3d, error);
    if (status == UR_OK && !(against.area_3d > 0))
        status = ur_error_set(error, UR_ERROR_INPUT, "the surface has no area to compare");
    if (status == UR_OK)
        status = surface_size(ruled, &against.size, error);
    if (status != UR_OK)
        return status;
    table->area_3d = against.area_3d;
    table->count = row_count(n_min, n_max);
    table->rows = ur_alloc_array(table->count, sizeof *table->rows, error);
    if (!table->rows) {
        table->count = 0;
        return UR_ERROR_MEMORY;
    }
    status = fill_rows(ruled, n_min, &against, table, error);
    if (status != UR_OK)
        ur_compare_table_free(table);
    return status;
}

void ur_compare_table_free(ur_compare_table *table)
{
    free(table->rows);
    memset(table, 0, sizeof *table);
}
