/*
 * parts_import.c: parts drawn elsewhere (SVG, DXF) into pieces ready to
 * nest.  The readers (svg_import.c, dxf_import.c) only find closed shapes
 * and turn them into rings in millimetres; everything that does not depend
 * on the format lives here, so both formats get the same checks and the
 * same words: curve flattening, coordinate limits, zero-area and
 * self-crossing rings (repaired by GEOS where it gives one polygon), and the
 * sorting of rings into parts and holes by containment.
 */
#include "io_internal.h"
#include "parts_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "../geom/geos_polygon.h"
#include "../base/c_locale.h"

#define PARTS_DEFAULT_TOLERANCE 0.01

void ur_parts_import_options_default(ur_parts_import_options *options)
{
    options->unit = 0.0;
    options->tolerance = PARTS_DEFAULT_TOLERANCE;
    options->strict = false;
}

double ur_parts_unit_mm(const char *name)
{
    static const struct {
        const char *name;
        double mm;
    } units[] = {{"mm", 1.0},   {"cm", 10.0},        {"m", 1000.0},      {"in", 25.4},
                 {"ft", 304.8}, {"pt", 25.4 / 72.0}, {"pc", 25.4 / 6.0}, {"px", 25.4 / 96.0}};
    for (size_t i = 0; name && i < sizeof units / sizeof units[0]; i++)
        if (strcmp(name, units[i].name) == 0)
            return units[i].mm;
    return 0.0;
}

/* ---- Points and curves ------------------------------------------------- */

ur_status parts_points_push(parts_points *points, ur_vec2 p, ur_error *error)
{
    if (points->count > 0) {
        ur_vec2 last = points->items[points->count - 1];
        if (last.x == p.x && last.y == p.y)
            return UR_OK;
    }
    if (points->count == points->capacity) {
        size_t capacity = points->capacity ? 2 * points->capacity : 32;
        if (capacity > SIZE_MAX / sizeof(ur_vec2))
            return ur_error_out_of_memory(error);
        ur_vec2 *items = realloc(points->items, capacity * sizeof *items);
        if (!items)
            return ur_error_out_of_memory(error);
        points->items = items;
        points->capacity = capacity;
    }
    points->items[points->count++] = p;
    return UR_OK;
}

void parts_points_free(parts_points *points)
{
    free(points->items);
    points->items = NULL;
    points->count = points->capacity = 0;
}

/* Segments for a curve; NaN and runaways end at the cap (the coordinate check refuses them). */
static size_t segment_count(double wanted, size_t minimum)
{
    if (!(wanted < PARTS_MAX_CURVE_SEGMENTS))
        return PARTS_MAX_CURVE_SEGMENTS;
    size_t n = (size_t)ceil(wanted);
    return n < minimum ? minimum : n;
}

/*
 * Uniform steps: a chord of a curve whose second derivative is at most D
 * strays at most D h^2 / 8 from it, h the parameter step.
 */
ur_status parts_flatten_quadratic(parts_points *points, ur_vec2 p0, ur_vec2 p1, ur_vec2 p2,
                                  double tolerance, ur_error *error)
{
    ur_vec2 d = ur_vec2_add(ur_vec2_sub(p0, ur_vec2_scale(p1, 2)), p2);
    size_t n = segment_count(sqrt(2 * ur_vec2_length(d) / (8 * tolerance)), 1);
    for (size_t i = 1; i <= n; i++) {
        double t = (double)i / (double)n, s = 1 - t;
        ur_vec2 p = ur_vec2_make(s * s * p0.x + 2 * s * t * p1.x + t * t * p2.x,
                                 s * s * p0.y + 2 * s * t * p1.y + t * t * p2.y);
        ur_status status = parts_points_push(points, i == n ? p2 : p, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

ur_status parts_flatten_cubic(parts_points *points, ur_vec2 p0, ur_vec2 p1, ur_vec2 p2, ur_vec2 p3,
                              double tolerance, ur_error *error)
{
    ur_vec2 d1 = ur_vec2_add(ur_vec2_sub(p0, ur_vec2_scale(p1, 2)), p2);
    ur_vec2 d2 = ur_vec2_add(ur_vec2_sub(p1, ur_vec2_scale(p2, 2)), p3);
    double m = fmax(ur_vec2_length(d1), ur_vec2_length(d2));
    size_t n = segment_count(sqrt(6 * m / (8 * tolerance)), 1);
    for (size_t i = 1; i <= n; i++) {
        double t = (double)i / (double)n, s = 1 - t;
        double a = s * s * s, b = 3 * s * s * t, c = 3 * s * t * t, e = t * t * t;
        ur_vec2 p = ur_vec2_make(a * p0.x + b * p1.x + c * p2.x + e * p3.x,
                                 a * p0.y + b * p1.y + c * p2.y + e * p3.y);
        ur_status status = parts_points_push(points, i == n ? p3 : p, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

ur_vec2 parts_arc_point(const parts_arc *arc, double angle)
{
    double x = arc->rx * cos(angle), y = arc->ry * sin(angle);
    double c = cos(arc->rotation), s = sin(arc->rotation);
    return ur_vec2_make(arc->centre.x + c * x - s * y, arc->centre.y + s * x + c * y);
}

/* A chord of angle a on a circle of radius r strays r (1 - cos(a / 2)) from it. */
ur_status parts_flatten_arc(parts_points *points, const parts_arc *arc, double tolerance,
                            ur_error *error)
{
    double r = fmax(fabs(arc->rx), fabs(arc->ry));
    double step = tolerance < r ? 2 * acos(1 - tolerance / r) : M_PI / 2;
    size_t n = segment_count(fabs(arc->sweep) / fmin(step, M_PI / 2), 1);
    for (size_t i = 1; i <= n; i++) {
        double angle = arc->start + arc->sweep * (double)i / (double)n;
        ur_status status = parts_points_push(points, parts_arc_point(arc, angle), error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* ---- Affine transforms ------------------------------------------------- */

parts_matrix parts_matrix_multiply(parts_matrix m, parts_matrix n)
{
    parts_matrix r = {m.a * n.a + m.c * n.b,       m.b * n.a + m.d * n.b,
                      m.a * n.c + m.c * n.d,       m.b * n.c + m.d * n.d,
                      m.a * n.e + m.c * n.f + m.e, m.b * n.e + m.d * n.f + m.f};
    return r;
}

ur_vec2 parts_matrix_apply(parts_matrix m, ur_vec2 p)
{
    return ur_vec2_make(m.a * p.x + m.c * p.y + m.e, m.b * p.x + m.d * p.y + m.f);
}

double parts_matrix_stretch(parts_matrix m)
{
    double p = m.a * m.a + m.b * m.b + m.c * m.c + m.d * m.d;
    double q = m.a * m.d - m.b * m.c;
    return sqrt(p / 2 + sqrt(fmax(0, p * p / 4 - q * q)));
}

double parts_matrix_similarity_scale(parts_matrix m)
{
    double first = m.a * m.a + m.b * m.b, second = m.c * m.c + m.d * m.d;
    double slack = 1e-12 * fmax(first, second);
    if (!(fabs(first - second) <= slack && fabs(m.a * m.c + m.b * m.d) <= slack))
        return 0;
    return sqrt(fabs(m.a * m.d - m.b * m.c));
}

/* ---- Collecting rings ---------------------------------------------------- */

ur_status parts_add_ring(parts_collection *collection, parts_points *points, int line,
                         const char *what, const char *id, int sub, const ur_path_circle *circle,
                         ur_error *error)
{
    parts_ring *rings = ur_array_grow(collection->rings, &collection->capacity, collection->count,
                                      sizeof *collection->rings, 16, error);
    if (!rings)
        return UR_ERROR_MEMORY;
    collection->rings = rings;
    /*
     * The closing point repeats the first: rings here never do.  Nor a last
     * point within the tolerance of the first (a path closed in relative
     * coordinates, a full turn of a curve, end where rounding puts them):
     * left in, it would be an edge of no length that makes the ring cross itself.
     */
    while (points->count > 3 && ur_vec2_distance(points->items[points->count - 1],
                                                 points->items[0]) <= collection->tolerance)
        points->count--;
    while (points->count > 1 && points->items[points->count - 1].x == points->items[0].x &&
           points->items[points->count - 1].y == points->items[0].y)
        points->count--;
    parts_ring *ring = &collection->rings[collection->count++];
    memset(ring, 0, sizeof *ring);
    ring->points = points->items;
    ring->count = points->count;
    ring->line = line;
    ring->sub = sub;
    if (circle)
        ring->circle = *circle;
    c_snprintf(ring->what, sizeof ring->what, "%s", what);
    c_snprintf(ring->id, sizeof ring->id, "%s", id ? id : "");
    points->items = NULL;
    points->count = points->capacity = 0;
    return UR_OK;
}

ur_status parts_add_line(parts_collection *collection, parts_points *points, bool closed, ur_op op,
                         int line, const char *what, ur_error *error)
{
    while (closed && points->count > 3 &&
           ur_vec2_distance(points->items[points->count - 1], points->items[0]) <=
               collection->tolerance)
        points->count--; /* as parts_add_ring: the closing edge returns to the first point */
    if (points->count < 2) {
        parts_points_free(points);
        return UR_OK; /* a dot: nothing to cut or draw */
    }
    parts_line *lines = ur_array_grow(collection->lines, &collection->line_capacity,
                                      collection->line_count, sizeof *collection->lines, 16, error);
    if (!lines)
        return UR_ERROR_MEMORY;
    collection->lines = lines;
    parts_line *added = &lines[collection->line_count++];
    memset(added, 0, sizeof *added);
    added->points = points->items;
    added->count = points->count;
    added->closed = closed && points->count > 2;
    added->op = op;
    added->line = line;
    c_snprintf(added->what, sizeof added->what, "%s", what);
    points->items = NULL;
    points->count = points->capacity = 0;
    return UR_OK;
}

ur_op parts_layer_op(const char *name)
{
    static const struct {
        const char *name;
        ur_op op;
    } names[] = {{"cut", UR_OP_CUT},
                 {"score", UR_OP_SCORE},
                 {"fold", UR_OP_SCORE},
                 {"folds", UR_OP_SCORE},
                 {"score-valley", UR_OP_SCORE_VALLEY},
                 {"valley", UR_OP_SCORE_VALLEY},
                 {"engrave", UR_OP_ENGRAVE},
                 {"engraving", UR_OP_ENGRAVE},
                 {"kerf", UR_OP_KERF},
                 {"mark", UR_OP_MARK},
                 {"marks", UR_OP_MARK},
                 {"marking", UR_OP_MARK}};
    /* "Score valley", "score_valley" and "SCORE-VALLEY" are one name. */
    char plain[32];
    size_t n = 0;
    for (; name && name[n] && n + 1 < sizeof plain; n++) {
        char c = (char)tolower((unsigned char)name[n]);
        plain[n] = c == ' ' || c == '_' ? '-' : c;
    }
    plain[n] = '\0';
    for (size_t i = 0; name && name[n] == '\0' && i < sizeof names / sizeof names[0]; i++)
        if (strcmp(plain, names[i].name) == 0)
            return names[i].op;
    return UR_OP_COUNT;
}

bool parts_read_kerf_note(const char *text, double *kerf)
{
    while (isspace((unsigned char)*text))
        text++;
    size_t length = strlen(UR_KERF_NOTE);
    if (strncmp(text, UR_KERF_NOTE, length) != 0)
        return false;
    char *end = NULL;
    double value = c_strtod(text + length, &end);
    if (end == text + length || !(value > 0) || !isfinite(value) || strncmp(end, " mm", 3) != 0)
        return false;
    for (end += 3; isspace((unsigned char)*end); end++)
        ;
    if (*end != '\0')
        return false;
    *kerf = value;
    return true;
}

ur_status parts_warn(parts_collection *collection, ur_error *error, const char *format, ...)
{
    char(*warnings)[256] =
        realloc(collection->warnings, (collection->warning_count + 1) * sizeof *warnings);
    if (!warnings)
        return ur_error_out_of_memory(error);
    collection->warnings = warnings;
    va_list arguments;
    va_start(arguments, format);
    c_vsnprintf(warnings[collection->warning_count++], sizeof *warnings, format, arguments);
    va_end(arguments);
    return UR_OK;
}

void parts_collection_free(parts_collection *collection)
{
    for (size_t i = 0; i < collection->count; i++)
        free(collection->rings[i].points);
    free(collection->rings);
    for (size_t i = 0; i < collection->line_count; i++)
        free(collection->lines[i].points);
    free(collection->lines);
    collection->lines = NULL;
    collection->line_count = collection->line_capacity = 0;
    free(collection->warnings);
    free(collection->text);
    collection->text = NULL;
    collection->rings = NULL;
    collection->warnings = NULL;
    collection->count = collection->capacity = collection->warning_count = 0;
}

/* "FILE:LINE: what: " before a message about a shape; "FILE: what: " when the line is unknown. */
static ur_status shape_error(const parts_collection *collection, int line, const char *what,
                             ur_error *error, const char *message)
{
    if (line > 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: %s: %s", collection->path, line, what,
                            message);
    return ur_error_set(error, UR_ERROR_INPUT, "%s: %s: %s", collection->path, what, message);
}

static ur_status ring_error(const parts_collection *collection, const parts_ring *ring,
                            ur_error *error, const char *message)
{
    return shape_error(collection, ring->line, ring->what, error, message);
}

/* ---- Checking rings with GEOS ------------------------------------------- */

/* A ring's index and what to sort it by: its area, or its line. */
typedef struct parts_order {
    double key;
    size_t index;
} parts_order;

static int by_area_descending(const void *a, const void *b)
{
    const parts_order *p = a, *q = b;
    if (p->key != q->key)
        return p->key > q->key ? -1 : 1;
    return p->index < q->index ? -1 : p->index > q->index;
}

typedef struct parts_job {
    GEOSContextHandle_t geos;
    parts_collection *collection;
    GEOSGeometry **polygons; /* one per ring */
    double *areas;           /* positive */
    ur_box *boxes;
    int *parent, *depth;
    parts_order *order;   /* by area, largest first */
    int *piece_of;        /* the part a ring is the outline of, -1 for a hole */
    GEOSGeometry **grown; /* polygons grown by the tolerance, made when a line needs them */
} parts_job;

/* Replaces the ring's points by the exterior ring of polygon. */
static ur_status take_exterior(GEOSContextHandle_t geos, const GEOSGeometry *polygon,
                               parts_ring *ring, ur_error *error)
{
    const GEOSGeometry *shell = GEOSGetExteriorRing_r(geos, polygon);
    const GEOSCoordSequence *sequence = shell ? GEOSGeom_getCoordSeq_r(geos, shell) : NULL;
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size) || size < 4)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS gave a polygon without a ring");
    ur_vec2 *points = ur_alloc_array(size - 1, sizeof *points, error);
    if (!points)
        return UR_ERROR_MEMORY;
    for (unsigned i = 0; i + 1 < size; i++)
        GEOSCoordSeq_getXY_r(geos, sequence, i, &points[i].x, &points[i].y);
    free(ring->points);
    ring->points = points;
    ring->count = size - 1;
    ring->circle = (ur_path_circle){{0, 0}, 0, 0}; /* repaired: whatever it was, it is not that */
    return UR_OK;
}

/* GEOSMakeValid's answer; the structure method drops what collapses to lines (a spike). */
static GEOSGeometry *make_valid(GEOSContextHandle_t geos, const GEOSGeometry *polygon)
{
    GEOSMakeValidParams *params = GEOSMakeValidParams_create_r(geos);
    GEOSGeometry *valid = NULL;
    if (params && GEOSMakeValidParams_setMethod_r(geos, params, GEOS_MAKE_VALID_STRUCTURE) &&
        GEOSMakeValidParams_setKeepCollapsed_r(geos, params, 0))
        valid = GEOSMakeValidWithParams_r(geos, polygon, params);
    if (params)
        GEOSMakeValidParams_destroy_r(geos, params);
    return valid;
}

/* A copy of the one polygon without holes that valid is or holds; NULL when it is not that. */
static GEOSGeometry *single_polygon(GEOSContextHandle_t geos, const GEOSGeometry *valid)
{
    int type = GEOSGeomTypeId_r(geos, valid);
    if ((type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) &&
        GEOSGetNumGeometries_r(geos, valid) == 1)
        return single_polygon(geos, GEOSGetGeometryN_r(geos, valid, 0));
    if (type != GEOS_POLYGON || GEOSisEmpty_r(geos, valid) != 0 ||
        GEOSGetNumInteriorRings_r(geos, valid) != 0)
        return NULL;
    return GEOSGeom_clone_r(geos, valid);
}

static ur_status no_area_error(const parts_collection *collection, const parts_ring *ring,
                               ur_error *error)
{
    return ring_error(collection, ring, error, "the outline encloses no area");
}

static ur_status repair_ring(parts_job *job, size_t i, ur_error *error)
{
    parts_collection *collection = job->collection;
    parts_ring *ring = &collection->rings[i];
    GEOSGeometry *made = make_valid(job->geos, job->polygons[i]);
    if (!made)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not repair a polygon");
    double made_area = 0;
    GEOSArea_r(job->geos, made, &made_area);
    GEOSGeometry *valid = single_polygon(job->geos, made);
    GEOSGeom_destroy_r(job->geos, made);
    if (!valid && made_area <= collection->tolerance * collection->tolerance)
        return no_area_error(collection, ring, error);
    if (!valid)
        return ring_error(collection, ring, error,
                          "the outline crosses itself and cannot be repaired into one shape");
    double before = fabs(ur_polygon_signed_area(ring->points, ring->count));
    ur_status status = take_exterior(job->geos, valid, ring, error);
    GEOSGeom_destroy_r(job->geos, valid);
    if (status != UR_OK)
        return status;
    double after = fabs(ur_polygon_signed_area(ring->points, ring->count));
    GEOSGeom_destroy_r(job->geos, job->polygons[i]);
    job->polygons[i] = geos_polygon_of_ring(job->geos, ring->points, ring->count);
    if (!job->polygons[i])
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not make a polygon");
    return parts_warn(collection, error,
                      "%s:%d: %s: the outline crosses itself; repaired (area %.6g mm² is now "
                      "%.6g mm²)",
                      collection->path, ring->line, ring->what, before, after);
}

static ur_status check_coordinates(const parts_collection *collection, const ur_vec2 *points,
                                   size_t count, int line, const char *what, ur_error *error)
{
    for (size_t k = 0; k < count; k++) {
        ur_vec2 p = points[k];
        if (!isfinite(p.x) || !isfinite(p.y))
            return shape_error(collection, line, what, error,
                               "a coordinate is not a finite number");
        if (fabs(p.x) > UR_PARTS_IMPORT_MAX_COORDINATE ||
            fabs(p.y) > UR_PARTS_IMPORT_MAX_COORDINATE) {
            char message[160];
            c_snprintf(message, sizeof message,
                       "the point (%.6g, %.6g) mm lies beyond %g mm: check the units", p.x, p.y,
                       UR_PARTS_IMPORT_MAX_COORDINATE);
            return shape_error(collection, line, what, error, message);
        }
    }
    return UR_OK;
}

/* Coordinates, validity, area; leaves the ring counter-clockwise and its polygon made. */
static ur_status prepare_ring(parts_job *job, size_t i, ur_error *error)
{
    parts_collection *collection = job->collection;
    parts_ring *ring = &collection->rings[i];
    ur_status status =
        check_coordinates(collection, ring->points, ring->count, ring->line, ring->what, error);
    if (status != UR_OK)
        return status;
    if (ring->count < 3)
        return no_area_error(collection, ring, error);
    double area = ur_polygon_signed_area(ring->points, ring->count);
    double least = collection->tolerance * collection->tolerance;
    job->polygons[i] = geos_polygon_of_ring(job->geos, ring->points, ring->count);
    if (!job->polygons[i])
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not make a polygon");
    char valid = GEOSisValid_r(job->geos, job->polygons[i]);
    if (valid == 2)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not check a polygon");
    /* A bow tie's signed area is 0 too: only a valid ring is judged by it here. */
    if (valid && fabs(area) <= least)
        return no_area_error(collection, ring, error);
    if (!valid) {
        status = repair_ring(job, i, error);
        if (status != UR_OK)
            return status;
        area = ur_polygon_signed_area(ring->points, ring->count);
        if (fabs(area) <= least)
            return no_area_error(collection, ring, error);
    }
    if (area < 0)
        ur_points_reverse(ring->points, ring->count);
    job->areas[i] = fabs(area);
    job->boxes[i] = ur_box_of_points(ring->points, ring->count);
    return UR_OK;
}

/* ---- Containment --------------------------------------------------------- */

static int by_line(const void *a, const void *b)
{
    const parts_order *p = a, *q = b;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    return p->index < q->index ? -1 : p->index > q->index;
}

static bool boxes_meet(ur_box a, ur_box b)
{
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

static ur_status two_rings_error(const parts_collection *collection, const parts_ring *ring,
                                 const parts_ring *other, const char *relation, ur_error *error)
{
    char message[256];
    c_snprintf(message, sizeof message, "%s %s on line %d", relation, other->what, other->line);
    return ring_error(collection, ring, error, message);
}

/* How ring i (smaller) lies against ring j (larger): sets *inside, refuses crossings. */
static ur_status relate(parts_job *job, size_t i, size_t j, bool *inside, ur_error *error)
{
    const parts_collection *collection = job->collection;
    *inside = false;
    if (!boxes_meet(job->boxes[i], job->boxes[j]))
        return UR_OK;
    char contains = GEOSContains_r(job->geos, job->polygons[j], job->polygons[i]);
    char overlaps = contains ? 0 : GEOSOverlaps_r(job->geos, job->polygons[j], job->polygons[i]);
    if (contains == 2 || overlaps == 2)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not compare two outlines");
    if (overlaps)
        return two_rings_error(collection, &collection->rings[i], &collection->rings[j],
                               "the outline crosses", error);
    if (contains && job->areas[i] >= job->areas[j] * (1 - 1e-9))
        return two_rings_error(collection, &collection->rings[i], &collection->rings[j],
                               "the same outline as", error);
    *inside = contains;
    return UR_OK;
}

/* A ring's parent is the smallest ring that contains it; depth says part or hole. */
static ur_status nest_rings(parts_job *job, ur_error *error)
{
    size_t n = job->collection->count;
    for (size_t i = 0; i < n; i++)
        job->order[i] = (parts_order){job->areas[i], i};
    qsort(job->order, n, sizeof *job->order, by_area_descending);
    for (size_t a = 0; a < n; a++) {
        size_t i = job->order[a].index;
        job->parent[i] = -1;
        job->depth[i] = 0;
        for (size_t b = a; b-- > 0;) {
            size_t j = job->order[b].index;
            bool inside = false;
            ur_status status = relate(job, i, j, &inside, error);
            if (status != UR_OK)
                return status;
            if (inside && job->parent[i] < 0) {
                job->parent[i] = (int)j;
                job->depth[i] = job->depth[j] + 1;
            }
        }
    }
    return UR_OK;
}

/* ---- Pieces ---------------------------------------------------------------- */

/* The id, "ID-2" for an element's second ring, or "plate-3": cut to fit name. */
static void piece_name(const parts_collection *collection, const parts_ring *ring, size_t number,
                       char *name, size_t size)
{
    char full[96];
    if (ring->id[0] && ring->sub > 1)
        c_snprintf(full, sizeof full, "%.24s-%d", ring->id, ring->sub);
    else if (ring->id[0])
        c_snprintf(full, sizeof full, "%s", ring->id);
    else {
        char base[32];
        io_file_stem(collection->path, base, 20);
        c_snprintf(full, sizeof full, "%s-%zu", base, number);
    }
    c_snprintf(name, size, "%.*s", (int)(size - 1), full);
}

static ur_status build_piece(parts_job *job, size_t outer, size_t number, ur_piece *piece,
                             ur_error *error)
{
    parts_collection *collection = job->collection;
    parts_ring *ring = &collection->rings[outer];
    memset(piece, 0, sizeof *piece);
    piece_name(collection, ring, number, piece->name, sizeof piece->name);
    ur_status status = ur_piece_add_path(piece, UR_OP_CUT, ring->points, ring->count, true, error);
    if (status == UR_OK)
        piece->paths[0].circle = ring->circle;
    double area = job->areas[outer];
    for (size_t h = 0; status == UR_OK && h < collection->count; h++) {
        if (job->parent[h] != (int)outer)
            continue;
        parts_ring *hole = &collection->rings[h];
        ur_points_reverse(hole->points, hole->count); /* holes turn clockwise */
        status = ur_piece_add_path(piece, UR_OP_CUT, hole->points, hole->count, true, error);
        if (status == UR_OK)
            piece->paths[piece->path_count - 1].circle = hole->circle;
        area -= job->areas[h];
    }
    piece->measures.flat_area = area;
    /*
     * Holes that touch one another can fill the outline (found by fuzzing):
     * such a part is all cut lines and no material.
     */
    if (status == UR_OK && !(area > 1e-9 * job->areas[outer]))
        status = ring_error(collection, ring, error, "its holes leave nothing of it");
    if (status != UR_OK)
        ur_piece_free(piece);
    return status;
}

static ur_status build_pieces(parts_job *job, ur_parts *parts, ur_error *error)
{
    size_t n = job->collection->count, outers = 0;
    for (size_t i = 0; i < n; i++)
        outers += job->depth[i] % 2 == 0;
    parts->pieces = ur_alloc_array(outers, sizeof *parts->pieces, error);
    if (!parts->pieces)
        return UR_ERROR_MEMORY;
    /* In the order the file draws them: chained DXF loops come last otherwise. */
    for (size_t i = 0; i < n; i++)
        job->order[i] = (parts_order){(double)job->collection->rings[i].line, i};
    qsort(job->order, n, sizeof *job->order, by_line);
    for (size_t k = 0; k < n; k++) {
        size_t i = job->order[k].index;
        job->piece_of[i] = -1;
        if (job->depth[i] % 2 != 0)
            continue;
        job->piece_of[i] = (int)parts->count;
        ur_status status =
            build_piece(job, i, parts->count + 1, &parts->pieces[parts->count], error);
        if (status != UR_OK)
            return status;
        parts->count++;
    }
    return UR_OK;
}

static ur_status job_allocate(parts_job *job, size_t n, ur_error *error)
{
    job->polygons = ur_alloc_array(n, sizeof *job->polygons, error);
    job->areas = ur_alloc_array(n, sizeof *job->areas, error);
    job->boxes = ur_alloc_array(n, sizeof *job->boxes, error);
    job->parent = ur_alloc_array(n, sizeof *job->parent, error);
    job->depth = ur_alloc_array(n, sizeof *job->depth, error);
    job->order = ur_alloc_array(n, sizeof *job->order, error);
    job->piece_of = ur_alloc_array(n, sizeof *job->piece_of, error);
    job->grown = ur_alloc_array(n, sizeof *job->grown, error);
    if (!job->polygons || !job->areas || !job->boxes || !job->parent || !job->depth ||
        !job->order || !job->piece_of || !job->grown)
        return UR_ERROR_MEMORY;
    memset(job->polygons, 0, n * sizeof *job->polygons);
    memset(job->grown, 0, n * sizeof *job->grown);
    return UR_OK;
}

static void job_free(parts_job *job)
{
    for (size_t i = 0; job->polygons && i < job->collection->count; i++)
        if (job->polygons[i])
            GEOSGeom_destroy_r(job->geos, job->polygons[i]);
    for (size_t i = 0; job->grown && i < job->collection->count; i++)
        if (job->grown[i])
            GEOSGeom_destroy_r(job->geos, job->grown[i]);
    free(job->polygons);
    free(job->grown);
    free(job->piece_of);
    free(job->areas);
    free(job->boxes);
    free(job->parent);
    free(job->depth);
    free(job->order);
    if (job->geos)
        GEOS_finish_r(job->geos);
}

/* ---- Lines that go with a part ------------------------------------------- */

/* The line as a GEOS line string, back to its start when closed; NULL when GEOS fails. */
static GEOSGeometry *line_string(GEOSContextHandle_t geos, const parts_line *line)
{
    size_t n = line->count + (line->closed ? 1 : 0);
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)n, 2);
    if (!sequence)
        return NULL;
    for (size_t i = 0; i < n; i++) {
        ur_vec2 p = line->points[i % line->count];
        if (!GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, p.x, p.y)) {
            GEOSCoordSeq_destroy_r(geos, sequence);
            return NULL;
        }
    }
    return GEOSGeom_createLineString_r(geos, sequence);
}

/*
 * Ring i's polygon grown by the tolerance, made on first use: a fold or a
 * label that ends on the outline, written to six decimals, may end a hair
 * outside it.
 */
static const GEOSGeometry *grown_polygon(parts_job *job, size_t i)
{
    if (!job->grown[i])
        job->grown[i] = GEOSBuffer_r(job->geos, job->polygons[i], job->collection->tolerance, 2);
    return job->grown[i];
}

/* The smallest ring that holds the whole line, SIZE_MAX for none. */
static ur_status holding_ring(parts_job *job, const parts_line *line, size_t *found,
                              ur_error *error)
{
    *found = SIZE_MAX;
    GEOSGeometry *string = line_string(job->geos, line);
    if (!string)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not make a line");
    ur_box box = ur_box_of_points(line->points, line->count);
    double tolerance = job->collection->tolerance;
    ur_box wide = {{box.min.x + tolerance, box.min.y + tolerance},
                   {box.max.x - tolerance, box.max.y - tolerance}};
    ur_status status = UR_OK;
    for (size_t i = 0; i < job->collection->count; i++) {
        const ur_box *ring = &job->boxes[i];
        if (!(ring->min.x <= wide.min.x && ring->min.y <= wide.min.y && ring->max.x >= wide.max.x &&
              ring->max.y >= wide.max.y) ||
            (*found != SIZE_MAX && job->areas[i] >= job->areas[*found]))
            continue;
        const GEOSGeometry *grown = grown_polygon(job, i);
        char covers = grown ? GEOSCovers_r(job->geos, grown, string) : 2;
        if (covers == 2) {
            status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not place a line");
            break;
        }
        if (covers)
            *found = i;
    }
    GEOSGeom_destroy_r(job->geos, string);
    return status;
}

static ur_status left_out_error(const parts_collection *collection, const parts_line *line,
                                ur_error *error)
{
    char message[256];
    ur_vec2 a = line->points[0], b = line->points[line->count - 1];
    if (line->op == UR_OP_CUT && !line->closed)
        c_snprintf(message, sizeof message,
                   "the shape is open (it starts at (%.6g, %.6g) mm and ends at (%.6g, %.6g) mm): "
                   "only closed shapes can be parts",
                   a.x, a.y, b.x, b.y);
    else
        c_snprintf(message, sizeof message, "a %s line outside every part", ur_op_name(line->op));
    return shape_error(collection, line->line, line->what, error, message);
}

/* One warning for everything left out: how many, the first, the lines they start on. */
static ur_status warn_left_out(parts_collection *collection, const size_t *left, size_t count,
                               ur_error *error)
{
    if (count == 0)
        return UR_OK;
    bool all_open = true;
    for (size_t k = 0; k < count; k++)
        all_open = all_open && collection->lines[left[k]].op == UR_OP_CUT;
    char where[96] = "";
    size_t used = 0;
    for (size_t k = 0; k < count && k < 6 && used < sizeof where; k++)
        used += (size_t)c_snprintf(where + used, sizeof where - used, "%s%d", k ? ", " : "",
                                   collection->lines[left[k]].line);
    if (count > 6 && used < sizeof where)
        c_snprintf(where + used, sizeof where - used, " and %zu more", count - 6);
    const parts_line *first = &collection->lines[left[0]];
    return parts_warn(collection, error, "%s:%d: %zu %s left out (%s on line%s %s): %s",
                      collection->path, first->line, count,
                      all_open ? (count == 1 ? "open shape" : "open shapes")
                               : (count == 1 ? "shape" : "shapes"),
                      first->what, count == 1 ? "" : "s", where,
                      all_open ? "only closed shapes become parts"
                               : "open, or outside every part; only closed shapes become parts");
}

static int by_line_number(const void *a, const void *b, const parts_collection *collection)
{
    int p = collection->lines[*(const size_t *)a].line,
        q = collection->lines[*(const size_t *)b].line;
    return (p > q) - (p < q);
}

/*
 * Every line goes with the part whose outline holds it (the smallest ring
 * that does, when that ring is a part's outline and not a hole); what no
 * part holds is left out with one warning, or refused when strict.
 */
static ur_status attach_lines(parts_job *job, ur_parts *parts, ur_error *error)
{
    parts_collection *collection = job->collection;
    size_t *left = ur_alloc_array(collection->line_count + 1, sizeof *left, error);
    if (!left)
        return UR_ERROR_MEMORY;
    size_t left_count = 0;
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < collection->line_count; k++) {
        const parts_line *line = &collection->lines[k];
        size_t ring = SIZE_MAX;
        status =
            check_coordinates(collection, line->points, line->count, line->line, line->what, error);
        if (status == UR_OK)
            status = holding_ring(job, line, &ring, error);
        if (status != UR_OK)
            break;
        if (ring != SIZE_MAX && job->piece_of[ring] >= 0)
            status = ur_piece_add_path(&parts->pieces[job->piece_of[ring]], line->op, line->points,
                                       line->count, line->closed, error);
        else if (collection->strict)
            status = left_out_error(collection, line, error);
        else
            left[left_count++] = k;
    }
    /* Insertion sort: the order of the file, for the warning. */
    for (size_t a = 1; a < left_count; a++)
        for (size_t b = a; b > 0 && by_line_number(&left[b - 1], &left[b], collection) > 0; b--) {
            size_t t = left[b];
            left[b] = left[b - 1];
            left[b - 1] = t;
        }
    if (status == UR_OK)
        status = warn_left_out(collection, left, left_count, error);
    free(left);
    return status;
}

/* No ring at all: say so, naming the first open shape when there is one. */
static ur_status no_part_error(const parts_collection *collection, ur_error *error)
{
    if (collection->line_count == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: no closed shape: nothing to use as a part",
                            collection->path);
    const parts_line *first = &collection->lines[0];
    for (size_t k = 1; k < collection->line_count; k++)
        if (collection->lines[k].line < first->line)
            first = &collection->lines[k];
    if (collection->strict)
        return left_out_error(collection, first, error);
    return ur_error_set(error, UR_ERROR_INPUT,
                        "%s:%d: no closed shape: nothing to use as a part (%zu open shape%s: "
                        "%s first)",
                        collection->path, first->line, collection->line_count,
                        collection->line_count == 1 ? "" : "s", first->what);
}

/* Whether a chained ring encloses no area or crosses itself; 2 when GEOS fails. */
static int bad_chain(GEOSContextHandle_t geos, const parts_collection *collection,
                     const parts_ring *ring)
{
    double least = collection->tolerance * collection->tolerance;
    if (ring->count < 3 || fabs(ur_polygon_signed_area(ring->points, ring->count)) <= least)
        return 1;
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, ring->points, ring->count);
    char valid = polygon ? GEOSisValid_r(geos, polygon) : 2;
    if (polygon)
        GEOSGeom_destroy_r(geos, polygon);
    return valid == 2 ? 2 : !valid;
}

/*
 * Lines chained end to end that close into no shape (a line drawn twice, a
 * junction of three lines taken the wrong way round) are open shapes, not
 * outlines: without strict they join the lines, to be left out or go with
 * a part, rather than refuse the file.
 */
static ur_status release_bad_chains(parts_collection *collection, GEOSContextHandle_t geos,
                                    ur_error *error)
{
    size_t kept = 0;
    ur_status status = UR_OK;
    for (size_t i = 0; i < collection->count; i++) {
        parts_ring *ring = &collection->rings[i];
        int bad = status == UR_OK && ring->chained && !collection->strict
                      ? bad_chain(geos, collection, ring)
                      : 0;
        if (bad == 2)
            status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not check a polygon");
        if (bad != 1) {
            collection->rings[kept++] = *ring;
            continue;
        }
        parts_points points = {ring->points, ring->count, ring->count};
        status = parts_points_push(&points, ring->points[0], error); /* the loop drawn whole */
        if (status == UR_OK)
            status = parts_add_line(collection, &points, false, UR_OP_CUT, ring->line, ring->what,
                                    error);
        parts_points_free(&points);
    }
    collection->count = kept;
    return status;
}

ur_status parts_assemble(parts_collection *collection, ur_parts *parts, ur_error *error)
{
    parts_job job = {.collection = collection};
    job.geos = GEOS_init_r();
    if (!job.geos)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not start");
    ur_status status = release_bad_chains(collection, job.geos, error);
    if (status == UR_OK && collection->count == 0)
        status = no_part_error(collection, error);
    if (status != UR_OK) {
        GEOS_finish_r(job.geos);
        return status;
    }
    status = job_allocate(&job, collection->count, error);
    for (size_t i = 0; status == UR_OK && i < collection->count; i++)
        status = prepare_ring(&job, i, error);
    if (status == UR_OK)
        status = nest_rings(&job, error);
    if (status == UR_OK)
        status = build_pieces(&job, parts, error);
    if (status == UR_OK)
        status = attach_lines(&job, parts, error);
    job_free(&job);
    if (status == UR_OK) {
        parts->warnings = collection->warnings;
        parts->warning_count = collection->warning_count;
        parts->kerf_compensated = collection->kerf_compensated;
        for (size_t k = 0; k < parts->count; k++)
            parts->pieces[k].kerf_compensated = collection->kerf_compensated;
        collection->warnings = NULL;
        collection->warning_count = 0;
    }
    return status;
}

/* ---- The entry point -------------------------------------------------------- */

static ur_status check_file(const char *path, ur_error *error)
{
    struct stat info;
    if (stat(path, &info) != 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path, strerror(errno));
    if (!S_ISREG(info.st_mode))
        return ur_error_set(error, UR_ERROR_INPUT, "%s: not a regular file", path);
    if (info.st_size == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: the file is empty", path);
    return UR_OK;
}

static ur_status check_options(const char *path, const ur_parts_import_options *options,
                               ur_error *error)
{
    if (!(options->tolerance >= 1e-6 && options->tolerance <= 10))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: the curve tolerance %g mm is not between 1e-6 and 10 mm", path,
                            options->tolerance);
    if (!(options->unit >= 0 && isfinite(options->unit)))
        return ur_error_set(error, UR_ERROR_INPUT, "%s: the unit %g mm is not positive", path,
                            options->unit);
    return UR_OK;
}

/* Reads the parts of text (taken: freed here), size bytes named path, known as SVG or DXF. */
static ur_status import_text(const char *path, bool svg, char *text, size_t size,
                             const ur_parts_import_options *options, ur_parts *parts,
                             ur_error *error)
{
    parts_collection collection = {.path = path,
                                   .text = text,
                                   .size = size,
                                   .tolerance = options->tolerance,
                                   .unit = options->unit,
                                   .strict = options->strict};
    ur_status status =
        svg ? parts_read_svg(&collection, error) : parts_read_dxf(&collection, error);
    if (status == UR_OK)
        status = parts_assemble(&collection, parts, error);
    parts_collection_free(&collection);
    if (status != UR_OK)
        ur_parts_free(parts);
    return status;
}

/* The kind path's extension names, and the options with defaults; UR_ERROR_INPUT when neither. */
static ur_status start(const char *path, const ur_parts_import_options **options,
                       ur_parts_import_options *defaults, ur_parts *parts, bool *svg,
                       ur_error *error)
{
    memset(parts, 0, sizeof *parts);
    ur_parts_import_options_default(defaults);
    if (!*options)
        *options = defaults;
    *svg = io_has_extension(path, "svg");
    if (!*svg && !io_has_extension(path, "dxf"))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: unknown kind of file: parts are read from .svg and .dxf files",
                            path);
    return check_options(path, *options, error);
}

ur_status ur_parts_import(const char *path, const ur_parts_import_options *options, ur_parts *parts,
                          ur_error *error)
{
    ur_parts_import_options defaults;
    bool svg;
    ur_status status = start(path, &options, &defaults, parts, &svg, error);
    if (status == UR_OK)
        status = check_file(path, error);
    char *text = NULL;
    size_t size = 0;
    if (status == UR_OK)
        status = io_read_file(path, PARTS_MAX_BYTES, "a drawing of parts", &text, &size, error);
    if (status != UR_OK)
        return status;
    return import_text(path, svg, text, size, options, parts, error);
}

ur_status ur_parts_import_buffer(const char *name, const void *data, size_t size,
                                 const ur_parts_import_options *options, ur_parts *parts,
                                 ur_error *error)
{
    ur_parts_import_options defaults;
    bool svg;
    ur_status status = start(name, &options, &defaults, parts, &svg, error);
    if (status != UR_OK)
        return status;
    if (size == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: the file is empty", name);
    if (size > (size_t)PARTS_MAX_BYTES)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: %zu bytes: too large for a drawing of parts", name, size);
    char *text = io_copy_text(data, size, error);
    if (!text)
        return UR_ERROR_MEMORY;
    return import_text(name, svg, text, size, options, parts, error);
}

void ur_parts_free(ur_parts *parts)
{
    for (size_t i = 0; parts->pieces && i < parts->count; i++)
        ur_piece_free(&parts->pieces[i]);
    free(parts->pieces);
    free(parts->warnings);
    memset(parts, 0, sizeof *parts);
}
