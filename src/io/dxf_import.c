/*
 * dxf_import.c: the closed shapes of an ASCII DXF drawing as rings in
 * millimetres, for parts_import.c to sort into parts and holes.
 *
 * A DXF file is a list of pairs of lines, a group code (an integer) and its
 * value; an entity runs from one code 0 to the next.  That is simple enough
 * to read by hand, and doing so keeps the line of every pair for messages.
 * Closed polylines, circles and full ellipses are rings as they stand.
 * LINEs, ARCs and open polylines are how many CAD programs draw an outline,
 * piece by piece, so they are chained end to end (ends within the tolerance
 * meet) and only what then stays open is refused, naming the entity.
 */
#include "io_internal.h"
#include "parts_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

/* Kinds of entities left out, counted for one warning each. */
#define DXF_MAX_IGNORED_KINDS 16

/* Entities drawn by INSERTs (arrays of arrays multiply): more is a runaway. */
#define DXF_MAX_DRAWN_ENTITIES 200000

/* A spline of higher degree than this is not a drawing. */
#define DXF_MAX_SPLINE_DEGREE 25

typedef struct dxf_pair {
    int code;
    const char *value; /* trimmed, inside the file's text */
    int line;          /* of the group code */
} dxf_pair;

/* An open piece of outline waiting to be chained: mm. */
typedef struct dxf_segment {
    parts_points points;
    int line;
    char what[24];
} dxf_segment;

typedef struct dxf_ignored {
    char type[24];
    size_t count;
    int line; /* of the first */
} dxf_ignored;

/* A block definition in the BLOCKS section: its entities are pairs[begin .. end). */
typedef struct dxf_block {
    const char *name;
    ur_vec2 base;
    size_t begin, end;
    bool inserting; /* being drawn now: an INSERT of it inside is a loop */
} dxf_block;

typedef struct dxf_reader {
    parts_collection *collection;
    const char *path;
    char *text; /* the collection's, cut into lines in place */
    dxf_pair *pairs;
    size_t count;
    double scale;        /* mm per drawing unit */
    parts_matrix matrix; /* the block being drawn's coordinates to the drawing's */
    double tolerance;    /* in the block being drawn's units */
    ur_op block_op;      /* the INSERT's layer's: what entities on layer 0 of a block are */
    int depth;           /* blocks inside blocks being drawn */
    size_t drawn;        /* entities drawn by INSERTs so far */
    dxf_block *blocks;
    size_t block_count;
    dxf_segment *segments;
    size_t segment_count;
    dxf_ignored ignored[DXF_MAX_IGNORED_KINDS];
    size_t ignored_count;
} dxf_reader;

/* One entity: its pairs from the code 0 that names it to the next code 0. */
typedef struct dxf_entity {
    dxf_reader *reader;
    const dxf_pair *pairs;
    size_t count;
    const char *type;
    int line;
    bool mirrored; /* extrusion (0, 0, -1): AutoCAD draws it with x turned over */
    ur_op op;      /* what its layer says it is: cut unless the layer names another */
} dxf_entity;

static ur_status entity_error(const dxf_entity *entity, ur_error *error, const char *message)
{
    return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: %s: %s", entity->reader->path, entity->line,
                        entity->type, message);
}

/* ---- The file as pairs ---------------------------------------------------- */

/* Cuts the text into lines in place; *lines points into it. */
static ur_status split_lines(dxf_reader *reader, size_t size, char ***lines, size_t *count,
                             ur_error *error)
{
    size_t n = 1;
    for (size_t i = 0; i < size; i++)
        n += reader->text[i] == '\n';
    *lines = ur_alloc_array(n, sizeof **lines, error);
    if (!*lines)
        return UR_ERROR_MEMORY;
    *count = 0;
    char *start = reader->text;
    for (char *p = reader->text;; p++) {
        if (*p == '\n' || *p == '\0') {
            bool end = *p == '\0';
            *p = '\0';
            (*lines)[(*count)++] = io_trim(start);
            if (end)
                break;
            start = p + 1;
        }
    }
    return UR_OK;
}

static bool parse_code(const char *text, int *code)
{
    char *end = NULL;
    errno = 0;
    long value = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || value < -5 || value > 1071)
        return false;
    *code = (int)value;
    return true;
}

/* Pairs up to "0 EOF" (what follows it is not read) or the end of the file. */
static ur_status make_pairs(dxf_reader *reader, char **lines, size_t line_count, ur_error *error)
{
    reader->pairs = ur_alloc_array(line_count / 2 + 1, sizeof *reader->pairs, error);
    if (!reader->pairs)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < line_count; i += 2) {
        if (i + 1 == line_count && lines[i][0] == '\0')
            break; /* the newline after the last value */
        dxf_pair *pair = &reader->pairs[reader->count];
        pair->line = (int)(i + 1);
        if (!parse_code(lines[i], &pair->code))
            return ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: \"%.24s\" is not a group code",
                                reader->path, i + 1, lines[i]);
        if (i + 1 == line_count)
            return ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: group code %d has no value",
                                reader->path, i + 1, pair->code);
        pair->value = lines[i + 1];
        reader->count++;
        if (pair->code == 0 && strcmp(pair->value, "EOF") == 0)
            break;
    }
    return UR_OK;
}

static ur_status read_pairs(dxf_reader *reader, ur_error *error)
{
    /* The collection's copy of the file, which split_lines cuts up in place. */
    reader->text = reader->collection->text;
    size_t size = reader->collection->size;
    if (strncmp(reader->text, "AutoCAD Binary DXF", 18) == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: a binary DXF file: save it as ASCII DXF",
                            reader->path);
    char **lines = NULL;
    size_t line_count = 0;
    ur_status status = split_lines(reader, size, &lines, &line_count, error);
    if (status == UR_OK)
        status = make_pairs(reader, lines, line_count, error);
    free(lines);
    return status;
}

/* ---- Values --------------------------------------------------------------- */

static ur_status pair_number(const dxf_reader *reader, const dxf_pair *pair, double *value,
                             ur_error *error)
{
    char *end = NULL;
    *value = c_strtod(pair->value, &end);
    if (end == pair->value || *end != '\0' || !isfinite(*value))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s:%d: \"%.24s\" is not a finite number (group code %d)", reader->path,
                            pair->line + 1, pair->value, pair->code);
    return UR_OK;
}

/* The entity's value for code, fallback when it has none. */
static ur_status entity_number(const dxf_entity *entity, int code, double fallback, double *value,
                               ur_error *error)
{
    *value = fallback;
    for (size_t i = 1; i < entity->count; i++)
        if (entity->pairs[i].code == code)
            return pair_number(entity->reader, &entity->pairs[i], value, error);
    return UR_OK;
}

/* The entity's text for code, NULL when it has none. */
static const char *entity_text(const dxf_entity *entity, int code)
{
    for (size_t i = 1; i < entity->count; i++)
        if (entity->pairs[i].code == code)
            return entity->pairs[i].value;
    return NULL;
}

static ur_status entity_flags(const dxf_entity *entity, int *flags, ur_error *error)
{
    double value = 0;
    ur_status status = entity_number(entity, 70, 0, &value, error);
    *flags = status == UR_OK && fabs(value) < 65536 ? (int)value : 0;
    return status;
}

/* Reads the codes in order into values (fallback 0); stops at the first failure. */
static ur_status entity_numbers(const dxf_entity *entity, const int *codes, double *values,
                                size_t count, ur_error *error)
{
    for (size_t i = 0; i < count; i++) {
        ur_status status = entity_number(entity, codes[i], 0, &values[i], error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* ---- Units ------------------------------------------------------------------ */

static double insunits_mm(int code)
{
    switch (code) {
    case 1:
        return 25.4;
    case 2:
        return 304.8;
    case 4:
        return 1.0;
    case 5:
        return 10.0;
    case 6:
        return 1000.0;
    case 8:
        return 25.4e-6;
    case 9:
        return 0.0254;
    case 10:
        return 914.4;
    case 13:
        return 0.001;
    case 14:
        return 100.0;
    default:
        return 0.0;
    }
}

/* $INSUNITS from the HEADER, wherever it is; else the caller's unit; else refuse. */
static ur_status find_units(dxf_reader *reader, ur_error *error)
{
    int line = 0, code = 0;
    for (size_t i = 0; i + 1 < reader->count; i++) {
        if (reader->pairs[i].code != 9 || strcmp(reader->pairs[i].value, "$INSUNITS") != 0)
            continue;
        double value = 0;
        ur_status status = pair_number(reader, &reader->pairs[i + 1], &value, error);
        if (status != UR_OK)
            return status;
        line = reader->pairs[i + 1].line;
        code = fabs(value) < 1000 ? (int)value : -1;
        break;
    }
    double unit = insunits_mm(code);
    if (code != 0 && unit == 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s:%d: $INSUNITS %d is not a length unit this reader knows (1 in, "
                            "2 ft, 4 mm, 5 cm, 6 m ...)",
                            reader->path, line, code);
    if (code == 0)
        unit = reader->collection->unit;
    if (unit <= 0 && line > 0) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "%s:%d: the drawing gives no unit ($INSUNITS is 0, unitless): give its "
                     "unit with units",
                     reader->path, line);
        return ur_error_set_setting(error, "units");
    }
    if (unit <= 0) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "%s: the drawing gives no unit (no $INSUNITS): give its unit with units",
                     reader->path);
        return ur_error_set_setting(error, "units");
    }
    reader->scale = unit;
    reader->tolerance = reader->collection->tolerance / unit;
    return UR_OK;
}

/* ---- Shapes ----------------------------------------------------------------- */

/*
 * Hands points (drawing units) over in mm: a ring when closed, or when it
 * ends where it starts; an open piece otherwise, for chaining.  circle
 * (drawing units, NULL for none) is the circle a closed ring exactly is.
 */
static ur_status emit(const dxf_entity *entity, parts_points *points, bool closed,
                      const ur_path_circle *circle, ur_error *error)
{
    dxf_reader *reader = entity->reader;
    parts_matrix mirror = {entity->mirrored ? -1 : 1, 0, 0, 1, 0, 0};
    parts_matrix to_mm =
        parts_matrix_multiply((parts_matrix){reader->scale, 0, 0, reader->scale, 0, 0},
                              parts_matrix_multiply(reader->matrix, mirror));
    for (size_t i = 0; i < points->count; i++)
        points->items[i] = parts_matrix_apply(to_mm, points->items[i]);
    /* A circle stays one under a block's turn, mirror and even scale, not under uneven scales. */
    ur_path_circle in_mm = {{0, 0}, 0, 0};
    double similarity = circle && closed ? parts_matrix_similarity_scale(to_mm) : 0;
    if (similarity > 0) {
        in_mm.centre = parts_matrix_apply(to_mm, circle->centre);
        in_mm.radius = circle->radius * similarity;
    }
    double tolerance = reader->collection->tolerance;
    if (!closed && points->count > 2 &&
        ur_vec2_distance(points->items[0], points->items[points->count - 1]) <= tolerance) {
        points->count--;
        closed = true;
    }
    if (entity->op != UR_OP_CUT)
        return parts_add_line(reader->collection, points, closed, entity->op, entity->line,
                              entity->type, error);
    if (closed)
        return parts_add_ring(reader->collection, points, entity->line, entity->type, NULL, 1,
                              in_mm.radius > 0 ? &in_mm : NULL, error);
    if (points->count < 2)
        return UR_OK; /* a line of no length: nothing to cut */
    dxf_segment *segments =
        realloc(reader->segments, (reader->segment_count + 1) * sizeof *segments);
    if (!segments)
        return ur_error_out_of_memory(error);
    reader->segments = segments;
    dxf_segment *segment = &segments[reader->segment_count++];
    segment->points = *points;
    segment->line = entity->line;
    c_snprintf(segment->what, sizeof segment->what, "%s", entity->type);
    memset(points, 0, sizeof *points);
    return UR_OK;
}

/* Emits and frees points whatever happens. */
static ur_status emit_points(const dxf_entity *entity, parts_points *points, bool closed,
                             const ur_path_circle *circle, ur_status status, ur_error *error)
{
    if (status == UR_OK)
        status = emit(entity, points, closed, circle, error);
    parts_points_free(points);
    return status;
}

static ur_status read_line_entity(const dxf_entity *entity, ur_error *error)
{
    static const int codes[] = {10, 20, 11, 21};
    double v[4];
    parts_points points = {0};
    ur_status status = entity_numbers(entity, codes, v, 4, error);
    if (status == UR_OK)
        status = parts_points_push(&points, ur_vec2_make(v[0], v[1]), error);
    if (status == UR_OK)
        status = parts_points_push(&points, ur_vec2_make(v[2], v[3]), error);
    return emit_points(entity, &points, false, NULL, status, error);
}

static ur_status positive_radius(const dxf_entity *entity, double radius, ur_error *error)
{
    if (radius > 0)
        return UR_OK;
    char message[64];
    c_snprintf(message, sizeof message, "radius %g is not positive", radius);
    return entity_error(entity, error, message);
}

/* CIRCLE, and ARC from angle 50 counter-clockwise to angle 51 (degrees). */
static ur_status read_circle_entity(const dxf_entity *entity, bool arc, ur_error *error)
{
    static const int codes[] = {10, 20, 40, 50, 51};
    double v[5];
    ur_status status = entity_numbers(entity, codes, v, arc ? 5 : 3, error);
    if (status == UR_OK)
        status = positive_radius(entity, v[2], error);
    if (status != UR_OK)
        return status;
    double sweep = 2 * M_PI, start = 0;
    if (arc) {
        start = v[3] * M_PI / 180;
        sweep = fmod(v[4] - v[3], 360.0);
        sweep = (sweep <= 0 ? sweep + 360 : sweep) * M_PI / 180;
        /* Within the tolerance of a full turn either way: a circle, drawn as an arc. */
        double slack = entity->reader->tolerance / v[2];
        if (sweep <= slack || fabs(sweep - 2 * M_PI) <= slack)
            sweep = 2 * M_PI;
    }
    parts_arc shape = {ur_vec2_make(v[0], v[1]), v[2], v[2], 0, start, sweep};
    parts_points points = {0};
    double tolerance = entity->reader->tolerance;
    status = parts_points_push(&points, parts_arc_point(&shape, start), error);
    if (status == UR_OK)
        status = parts_flatten_arc(&points, &shape, tolerance, error);
    /* A CIRCLE is exactly one; its points all lie on it. */
    ur_path_circle circle = {shape.centre, v[2], 0};
    return emit_points(entity, &points, !arc, arc ? NULL : &circle, status, error);
}

/* ELLIPSE: in world coordinates, major axis end 11/21 from the centre, ratio 40. */
static ur_status read_ellipse_entity(dxf_entity *entity, ur_error *error)
{
    static const int codes[] = {10, 20, 11, 21, 40};
    double v[5], start = 0, end = 2 * M_PI;
    ur_status status = entity_numbers(entity, codes, v, 5, error);
    if (status == UR_OK)
        status = entity_number(entity, 41, 0, &start, error);
    if (status == UR_OK)
        status = entity_number(entity, 42, 2 * M_PI, &end, error);
    double rx = hypot(v[2], v[3]);
    if (status == UR_OK)
        status = positive_radius(entity, rx * v[4], error);
    if (status != UR_OK)
        return status;
    double sweep = fmod(end - start, 2 * M_PI);
    sweep = sweep <= 0 ? sweep + 2 * M_PI : sweep;
    /* Within the tolerance of a full turn either way (LibreCAD writes 2 pi as 6.28318530718). */
    double slack = entity->reader->tolerance / fmax(rx, rx * fabs(v[4]));
    bool full = sweep <= slack || fabs(sweep - 2 * M_PI) <= slack;
    if (full)
        sweep = 2 * M_PI;
    /* Its minor axis is the extrusion crossed with the major: the other way round when mirrored. */
    parts_arc shape = {ur_vec2_make(v[0], v[1]), rx,    (entity->mirrored ? -1 : 1) * rx * v[4],
                       atan2(v[3], v[2]),        start, sweep};
    entity->mirrored = false; /* world coordinates: nothing to turn over */
    parts_points points = {0};
    status = parts_points_push(&points, parts_arc_point(&shape, start), error);
    if (status == UR_OK)
        status = parts_flatten_arc(&points, &shape, entity->reader->tolerance, error);
    return emit_points(entity, &points, full, NULL, status, error);
}

/* ---- Splines ------------------------------------------------------------------ */

typedef struct dxf_spline {
    int degree;
    double *knots, *weights;
    size_t knot_count, weight_count, knot_capacity, weight_capacity;
    parts_points points, fit;
} dxf_spline;

static ur_status push_number(double **items, size_t *count, size_t *capacity, double value,
                             ur_error *error)
{
    double *grown = ur_array_grow(*items, capacity, *count, sizeof **items, 16, error);
    if (!grown)
        return UR_ERROR_MEMORY;
    *items = grown;
    grown[(*count)++] = value;
    return UR_OK;
}

/* 40 knots, 41 weights, 10/20 control points, 11/21 fit points, in the order written. */
static ur_status spline_field(const dxf_entity *entity, const dxf_pair *pair, dxf_spline *spline,
                              ur_error *error)
{
    int code = pair->code;
    if (code != 40 && code != 41 && code != 10 && code != 20 && code != 11 && code != 21)
        return UR_OK;
    double value = 0;
    ur_status status = pair_number(entity->reader, pair, &value, error);
    if (status != UR_OK)
        return status;
    if (code == 40)
        return push_number(&spline->knots, &spline->knot_count, &spline->knot_capacity, value,
                           error);
    if (code == 41)
        return push_number(&spline->weights, &spline->weight_count, &spline->weight_capacity, value,
                           error);
    parts_points *points = code == 10 || code == 20 ? &spline->points : &spline->fit;
    if (code == 10 || code == 11) {
        /* Pushed as it comes: two equal control points in a row are both needed. */
        ur_vec2 *items = ur_array_grow(points->items, &points->capacity, points->count,
                                       sizeof *points->items, 16, error);
        if (!items)
            return UR_ERROR_MEMORY;
        points->items = items;
        items[points->count++] = ur_vec2_make(value, 0);
        return UR_OK;
    }
    if (points->count == 0)
        return entity_error(entity, error, "a y coordinate before its x");
    points->items[points->count - 1].y = value;
    return UR_OK;
}

/* Degree, knots and weights as a NURBS needs them; the message names what is wrong. */
static ur_status check_spline(const dxf_entity *entity, const dxf_spline *spline, ur_error *error)
{
    char message[160];
    size_t n = spline->points.count, p = (size_t)(spline->degree > 0 ? spline->degree : 0);
    if (spline->degree < 1 || spline->degree > DXF_MAX_SPLINE_DEGREE)
        c_snprintf(message, sizeof message, "degree %d: a spline's degree is from 1 to %d",
                   spline->degree, DXF_MAX_SPLINE_DEGREE);
    else if (n == 0 && spline->fit.count > 0)
        c_snprintf(message, sizeof message,
                   "a spline given by fit points only is not read: save it with its control "
                   "points");
    else if (n < p + 1)
        c_snprintf(message, sizeof message, "%zu control points: a spline of degree %zu needs %zu",
                   n, p, p + 1);
    else if (spline->knot_count != n + p + 1)
        c_snprintf(message, sizeof message, "%zu knots: %zu control points of degree %zu need %zu",
                   spline->knot_count, n, p, n + p + 1);
    else if (spline->weight_count != 0 && spline->weight_count != n)
        c_snprintf(message, sizeof message, "%zu weights for %zu control points",
                   spline->weight_count, n);
    else
        message[0] = '\0';
    for (size_t i = 0; !message[0] && i + 1 < spline->knot_count; i++)
        if (spline->knots[i + 1] < spline->knots[i])
            c_snprintf(message, sizeof message, "its knots decrease (knot %zu is %g, knot %zu %g)",
                       i + 1, spline->knots[i], i + 2, spline->knots[i + 1]);
    for (size_t i = 0; !message[0] && i < spline->weight_count; i++)
        if (!(spline->weights[i] > 0))
            c_snprintf(message, sizeof message, "weight %zu is %g: weights must be positive", i + 1,
                       spline->weights[i]);
    if (!message[0] && !(spline->knots[n] > spline->knots[p]))
        c_snprintf(message, sizeof message, "its knots span nothing (all %g)", spline->knots[p]);
    return message[0] ? entity_error(entity, error, message) : UR_OK;
}

/* SPLINE: a NURBS curve in world coordinates, flattened to the tolerance. */
static ur_status read_spline(dxf_entity *entity, ur_error *error)
{
    double degree = 0;
    int flags = 0;
    dxf_spline spline = {0};
    ur_status status = entity_number(entity, 71, 0, &degree, error);
    if (status == UR_OK)
        status = entity_flags(entity, &flags, error);
    spline.degree = fabs(degree) < 1000 ? (int)degree : -1;
    for (size_t i = 1; status == UR_OK && i < entity->count; i++)
        status = spline_field(entity, &entity->pairs[i], &spline, error);
    if (status == UR_OK)
        status = check_spline(entity, &spline, error);
    entity->mirrored = false; /* world coordinates, as an ELLIPSE's */
    parts_points points = {0};
    if (status == UR_OK) {
        parts_nurbs curve = {spline.degree, spline.points.items,
                             spline.weight_count ? spline.weights : NULL, spline.points.count,
                             spline.knots};
        status = parts_flatten_nurbs(&points, &curve, entity->reader->tolerance, error);
    }
    free(spline.knots);
    free(spline.weights);
    parts_points_free(&spline.points);
    parts_points_free(&spline.fit);
    /* Flag 1, closed: its ends meet, and emit closes what ends where it starts. */
    return emit_points(entity, &points, false, NULL, status, error);
}

/* ---- Polylines ---------------------------------------------------------------- */

typedef struct dxf_vertex {
    ur_vec2 p;
    double bulge; /* tan of a quarter of the arc's angle to the next vertex; + counter-clockwise */
} dxf_vertex;

typedef struct dxf_vertices {
    dxf_vertex *items;
    size_t count, capacity;
} dxf_vertices;

static ur_status vertices_push(dxf_vertices *vertices, ur_error *error)
{
    dxf_vertex *items = ur_array_grow(vertices->items, &vertices->capacity, vertices->count,
                                      sizeof *vertices->items, 16, error);
    if (!items)
        return UR_ERROR_MEMORY;
    vertices->items = items;
    vertices->items[vertices->count++] = (dxf_vertex){{0, 0}, 0};
    return UR_OK;
}

/* The arc from a to b that a bulge describes, flattened; b is pushed exactly. */
static ur_status bulge_to(parts_points *points, ur_vec2 a, ur_vec2 b, double bulge,
                          double tolerance, ur_error *error)
{
    double c = ur_vec2_distance(a, b);
    if (bulge == 0 || c == 0)
        return parts_points_push(points, b, error);
    ur_vec2 middle = ur_vec2_scale(ur_vec2_add(a, b), 0.5);
    ur_vec2 left = ur_vec2_make(-(b.y - a.y) / c, (b.x - a.x) / c);
    /* The centre lies r cos(angle / 2) = (c / 2) (1 - bulge^2) / (2 bulge) left of the chord. */
    ur_vec2 centre = ur_vec2_add_scaled(middle, left, c / 2 * (1 - bulge * bulge) / (2 * bulge));
    double r = ur_vec2_distance(a, centre);
    parts_arc arc = {centre, r, r, 0, atan2(a.y - centre.y, a.x - centre.x), 4 * atan(bulge)};
    ur_status status = parts_flatten_arc(points, &arc, tolerance, error);
    if (status == UR_OK)
        points->items[points->count - 1] = b;
    return status;
}

static ur_status emit_polyline(const dxf_entity *entity, const dxf_vertices *vertices, bool closed,
                               ur_error *error)
{
    size_t n = vertices->count;
    if (n == 0)
        return UR_OK;
    parts_points points = {0};
    ur_status status = parts_points_push(&points, vertices->items[0].p, error);
    size_t edges = closed ? n : n - 1;
    for (size_t i = 0; status == UR_OK && i < edges; i++)
        status = bulge_to(&points, vertices->items[i].p, vertices->items[(i + 1) % n].p,
                          vertices->items[i].bulge, entity->reader->tolerance, error);
    return emit_points(entity, &points, closed, NULL, status, error);
}

/* One vertex's field: 10 starts a vertex, 20 and 42 fill it in. */
static ur_status vertex_field(const dxf_entity *entity, const dxf_pair *pair,
                              dxf_vertices *vertices, ur_error *error)
{
    if (pair->code != 10 && pair->code != 20 && pair->code != 42)
        return UR_OK;
    double value = 0;
    ur_status status = pair_number(entity->reader, pair, &value, error);
    if (status == UR_OK && pair->code == 10)
        status = vertices_push(vertices, error);
    if (status != UR_OK)
        return status;
    if (vertices->count == 0)
        return entity_error(entity, error, "a vertex field before the first vertex");
    dxf_vertex *vertex = &vertices->items[vertices->count - 1];
    if (pair->code == 10)
        vertex->p.x = value;
    else if (pair->code == 20)
        vertex->p.y = value;
    else
        vertex->bulge = value;
    return UR_OK;
}

static ur_status read_lwpolyline(const dxf_entity *entity, ur_error *error)
{
    int flags = 0;
    ur_status status = entity_flags(entity, &flags, error);
    dxf_vertices vertices = {0};
    for (size_t i = 1; status == UR_OK && i < entity->count; i++)
        status = vertex_field(entity, &entity->pairs[i], &vertices, error);
    if (status == UR_OK)
        status = emit_polyline(entity, &vertices, flags & 1, error);
    free(vertices.items);
    return status;
}

/* The entity that starts at pairs[*index] (code 0); *index moves to the next. */
static dxf_entity next_entity(dxf_reader *reader, size_t *index, size_t end)
{
    /* Messages give the line of the entity's name, the value after its code 0. */
    dxf_entity entity = {reader,
                         &reader->pairs[*index],
                         1,
                         reader->pairs[*index].value,
                         reader->pairs[*index].line + 1,
                         false,
                         UR_OP_CUT};
    size_t i = *index + 1;
    while (i < end && reader->pairs[i].code != 0)
        i++;
    entity.count = i - *index;
    *index = i;
    return entity;
}

/* POLYLINE, then its VERTEX entities up to SEQEND. */
static ur_status read_polyline(dxf_entity *entity, size_t *index, size_t end, ur_error *error)
{
    int flags = 0;
    ur_status status = entity_flags(entity, &flags, error);
    if (status == UR_OK && (flags & (16 | 64)))
        status = entity_error(entity, error,
                              "polygon and polyface meshes are not read: only flat outlines");
    dxf_vertices vertices = {0};
    while (status == UR_OK && *index < end) {
        size_t at = *index;
        dxf_entity vertex = next_entity(entity->reader, index, end);
        if (strcmp(vertex.type, "VERTEX") != 0) {
            if (strcmp(vertex.type, "SEQEND") != 0)
                *index = at; /* no SEQEND: the next entity is not ours */
            break;
        }
        int vertex_flags = 0;
        status = entity_flags(&vertex, &vertex_flags, error);
        if (vertex_flags & 16)
            continue; /* a spline's frame control point, not on the curve */
        for (size_t i = 1; status == UR_OK && i < vertex.count; i++)
            status = vertex_field(&vertex, &vertex.pairs[i], &vertices, error);
    }
    if (status == UR_OK)
        status = emit_polyline(entity, &vertices, flags & 1, error);
    free(vertices.items);
    return status;
}

/* ---- Entities ------------------------------------------------------------------ */

static ur_status note_ignored(dxf_reader *reader, const dxf_entity *entity)
{
    size_t k = 0;
    while (k < reader->ignored_count && strcmp(reader->ignored[k].type, entity->type) != 0)
        k++;
    if (k == reader->ignored_count) {
        if (k == DXF_MAX_IGNORED_KINDS)
            k--; /* the last kind counts the rest */
        else {
            reader->ignored_count++;
            c_snprintf(reader->ignored[k].type, sizeof reader->ignored[k].type, "%s", entity->type);
            reader->ignored[k].line = entity->line;
        }
    }
    reader->ignored[k].count++;
    return UR_OK;
}

static ur_status warn_ignored(dxf_reader *reader, ur_error *error)
{
    for (size_t k = 0; k < reader->ignored_count; k++) {
        const dxf_ignored *kind = &reader->ignored[k];
        ur_status status = parts_warn(
            reader->collection, error, "%s:%d: %zu %s entit%s left out: not an outline",
            reader->path, kind->line, kind->count, kind->type, kind->count == 1 ? "y" : "ies");
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status read_insert(const dxf_entity *entity, ur_error *error);

static ur_status read_entity(dxf_entity *entity, size_t *index, size_t end, ur_error *error)
{
    double extrusion = 1;
    ur_status status = entity_number(entity, 230, 1, &extrusion, error);
    entity->mirrored = extrusion < 0;
    const char *layer = entity_text(entity, 8);
    ur_op op = parts_layer_op(layer);
    /* Inside a block, layer 0 takes the layer of the INSERT that draws it. */
    if (!layer || strcmp(layer, "0") == 0)
        op = entity->reader->block_op;
    entity->op = op == UR_OP_COUNT ? UR_OP_CUT : op;
    const char *type = entity->type;
    if (status == UR_OK && entity->reader->depth > 0 &&
        ++entity->reader->drawn > DXF_MAX_DRAWN_ENTITIES)
        status = entity_error(entity, error,
                              "more than 200000 entities drawn by block references: not a "
                              "drawing of parts");
    if (status != UR_OK)
        return status;
    if (strcmp(type, "LINE") == 0)
        return read_line_entity(entity, error);
    if (strcmp(type, "CIRCLE") == 0 || strcmp(type, "ARC") == 0)
        return read_circle_entity(entity, strcmp(type, "ARC") == 0, error);
    if (strcmp(type, "ELLIPSE") == 0)
        return read_ellipse_entity(entity, error);
    if (strcmp(type, "LWPOLYLINE") == 0)
        return read_lwpolyline(entity, error);
    if (strcmp(type, "POLYLINE") == 0)
        return read_polyline(entity, index, end, error);
    if (strcmp(type, "SPLINE") == 0)
        return read_spline(entity, error);
    if (strcmp(type, "INSERT") == 0)
        return read_insert(entity, error);
    if (strcmp(type, "REGION") == 0 || strcmp(type, "3DSOLID") == 0 || strcmp(type, "BODY") == 0)
        return entity_error(entity, error, "not read: explode it into lines and arcs first");
    return note_ignored(entity->reader, entity);
}

/* Index of the pair after "0 SECTION / 2 name", and of its "0 ENDSEC"; false when none. */
static bool find_section(const dxf_reader *reader, const char *name, size_t *begin, size_t *end)
{
    for (size_t i = 0; i + 1 < reader->count; i++) {
        const dxf_pair *pair = &reader->pairs[i];
        if (pair->code != 0 || strcmp(pair->value, "SECTION") != 0 ||
            reader->pairs[i + 1].code != 2 || strcmp(reader->pairs[i + 1].value, name) != 0)
            continue;
        *begin = i + 2;
        *end = *begin;
        while (*end < reader->count &&
               !(reader->pairs[*end].code == 0 && strcmp(reader->pairs[*end].value, "ENDSEC") == 0))
            (*end)++;
        return true;
    }
    return false;
}

/* The entities of pairs[index .. end): the ENTITIES section, or a block's. */
static ur_status read_entity_list(dxf_reader *reader, size_t index, size_t end, ur_error *error)
{
    while (index < end && reader->pairs[index].code != 0)
        index++;
    while (index < end) {
        dxf_entity entity = next_entity(reader, &index, end);
        ur_status status = read_entity(&entity, &index, end, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status read_entities(dxf_reader *reader, ur_error *error)
{
    size_t index = 0, end = 0;
    if (!find_section(reader, "ENTITIES", &index, &end))
        return ur_error_set(error, UR_ERROR_INPUT, "%s: no ENTITIES section: nothing drawn",
                            reader->path);
    ur_status status = read_entity_list(reader, index, end, error);
    if (status == UR_OK)
        status = warn_ignored(reader, error);
    return status;
}

/* ---- Blocks ------------------------------------------------------------------------ */

/* Each "0 BLOCK" of the BLOCKS section: its name, base point and entities up to "0 ENDBLK". */
static ur_status find_blocks(dxf_reader *reader, ur_error *error)
{
    size_t index = 0, end = 0;
    if (!find_section(reader, "BLOCKS", &index, &end))
        return UR_OK;
    size_t capacity = 0;
    while (index < end) {
        if (reader->pairs[index].code != 0 || strcmp(reader->pairs[index].value, "BLOCK") != 0) {
            index++;
            continue;
        }
        dxf_entity header = next_entity(reader, &index, end);
        dxf_block *blocks = ur_array_grow(reader->blocks, &capacity, reader->block_count,
                                          sizeof *reader->blocks, 16, error);
        if (!blocks)
            return UR_ERROR_MEMORY;
        reader->blocks = blocks;
        dxf_block *block = &blocks[reader->block_count++];
        memset(block, 0, sizeof *block);
        block->name = entity_text(&header, 2);
        static const int codes[] = {10, 20};
        double base[2];
        ur_status status = entity_numbers(&header, codes, base, 2, error);
        if (status != UR_OK)
            return status;
        block->base = ur_vec2_make(base[0], base[1]);
        block->begin = index;
        while (index < end && !(reader->pairs[index].code == 0 &&
                                strcmp(reader->pairs[index].value, "ENDBLK") == 0))
            index++;
        block->end = index;
    }
    return UR_OK;
}

static dxf_block *find_block(dxf_reader *reader, const char *name)
{
    for (size_t k = 0; name && k < reader->block_count; k++)
        if (reader->blocks[k].name && strcmp(reader->blocks[k].name, name) == 0)
            return &reader->blocks[k];
    return NULL;
}

/* An INSERT's placement: codes 10/20 point, 41/42 scales, 50 turn, 70/71 columns and rows, 44/45
 * their spacing. */
typedef struct dxf_insertion {
    double v[9];
} dxf_insertion;

enum { AT_X, AT_Y, SCALE_X, SCALE_Y, TURN, COLUMNS, ROWS, COLUMN_STEP, ROW_STEP };

static ur_status read_insertion(const dxf_entity *entity, dxf_insertion *at, ur_error *error)
{
    static const int codes[] = {10, 20, 41, 42, 50, 70, 71, 44, 45};
    static const double fallbacks[] = {0, 0, 1, 1, 0, 1, 1, 0, 0};
    for (size_t i = 0; i < 9; i++) {
        ur_status status = entity_number(entity, codes[i], fallbacks[i], &at->v[i], error);
        if (status != UR_OK)
            return status;
    }
    char message[128];
    if (at->v[SCALE_X] == 0 || at->v[SCALE_Y] == 0) {
        c_snprintf(message, sizeof message, "a scale of 0 (%g by %g) draws nothing", at->v[SCALE_X],
                   at->v[SCALE_Y]);
        return entity_error(entity, error, message);
    }
    if (!(at->v[COLUMNS] >= 1 && at->v[COLUMNS] <= 32767 && at->v[ROWS] >= 1 &&
          at->v[ROWS] <= 32767)) {
        c_snprintf(message, sizeof message, "%g columns by %g rows: not from 1 to 32767",
                   at->v[COLUMNS], at->v[ROWS]);
        return entity_error(entity, error, message);
    }
    return UR_OK;
}

/*
 * The block's coordinates to the INSERT's for one copy of an array: less
 * the base point, scaled, moved by the copy's column and row, turned, put
 * at the insertion point, all in the INSERT's own (OCS) coordinates, which
 * an extrusion of (0, 0, -1) turns over.
 */
static parts_matrix copy_matrix(const dxf_insertion *at, ur_vec2 base, double column, double row,
                                bool mirrored)
{
    double turn = at->v[TURN] * M_PI / 180, c = cos(turn), s = sin(turn);
    double sx = at->v[SCALE_X], sy = at->v[SCALE_Y];
    ur_vec2 offset = ur_vec2_make(column * at->v[COLUMN_STEP] - sx * base.x,
                                  row * at->v[ROW_STEP] - sy * base.y);
    parts_matrix m = {c * sx,
                      s * sx,
                      -s * sy,
                      c * sy,
                      at->v[AT_X] + c * offset.x - s * offset.y,
                      at->v[AT_Y] + s * offset.x + c * offset.y};
    parts_matrix mirror = {mirrored ? -1 : 1, 0, 0, 1, 0, 0};
    return parts_matrix_multiply(mirror, m);
}

/* Draws the block once per copy of the array, under the INSERT's placement. */
static ur_status draw_block(const dxf_entity *entity, dxf_block *block, const dxf_insertion *at,
                            ur_error *error)
{
    dxf_reader *reader = entity->reader;
    parts_matrix outer = reader->matrix;
    double outer_tolerance = reader->tolerance;
    ur_op outer_op = reader->block_op;
    reader->block_op = entity->op;
    reader->depth++;
    block->inserting = true;
    ur_status status = UR_OK;
    for (int row = 0; status == UR_OK && row < (int)at->v[ROWS]; row++)
        for (int column = 0; status == UR_OK && column < (int)at->v[COLUMNS]; column++) {
            reader->matrix = parts_matrix_multiply(
                outer, copy_matrix(at, block->base, column, row, entity->mirrored));
            double stretch = parts_matrix_stretch(reader->matrix) * reader->scale;
            reader->tolerance = reader->collection->tolerance / stretch;
            status = read_entity_list(reader, block->begin, block->end, error);
        }
    block->inserting = false;
    reader->depth--;
    reader->matrix = outer;
    reader->tolerance = outer_tolerance;
    reader->block_op = outer_op;
    return status;
}

/* INSERT: a block drawn here, scaled, turned, in columns and rows; blocks may insert blocks. */
static ur_status read_insert(const dxf_entity *entity, ur_error *error)
{
    dxf_reader *reader = entity->reader;
    const char *name = entity_text(entity, 2);
    dxf_block *block = find_block(reader, name);
    char message[160];
    if (!block) {
        c_snprintf(message, sizeof message, "block '%.60s' is not defined in the drawing",
                   name ? name : "");
        return entity_error(entity, error, message);
    }
    if (block->inserting) {
        c_snprintf(message, sizeof message,
                   "block '%.60s' refers to itself (directly or through other blocks)", name);
        return entity_error(entity, error, message);
    }
    if (reader->depth >= PARTS_MAX_DEPTH)
        return entity_error(entity, error, "blocks nest too deep");
    dxf_insertion at;
    ur_status status = read_insertion(entity, &at, error);
    if (status == UR_OK)
        status = draw_block(entity, block, &at, error);
    return status;
}

/* ---- Chaining open pieces into loops ----------------------------------------------- */

/* The unused segment with an end nearest to p, within tolerance; *reversed when its end. */
static size_t nearest_segment(const dxf_reader *reader, const bool *used, ur_vec2 p,
                              double tolerance, bool *reversed)
{
    size_t best = SIZE_MAX;
    double best_distance = tolerance;
    for (size_t k = 0; k < reader->segment_count; k++) {
        if (used[k])
            continue;
        const parts_points *points = &reader->segments[k].points;
        double to_start = ur_vec2_distance(p, points->items[0]);
        double to_end = ur_vec2_distance(p, points->items[points->count - 1]);
        if (to_start <= best_distance) {
            best = k;
            best_distance = to_start;
            *reversed = false;
        }
        if (to_end <= best_distance && to_end < to_start) {
            best = k;
            best_distance = to_end;
            *reversed = true;
        }
    }
    return best;
}

static ur_status append_segment(parts_points *chain, const parts_points *points, bool reversed,
                                ur_error *error)
{
    for (size_t i = 1; i < points->count; i++) {
        size_t k = reversed ? points->count - 1 - i : i;
        ur_status status = parts_points_push(chain, points->items[k], error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static void reverse_points(parts_points *points)
{
    ur_points_reverse(points->items, points->count);
}

/*
 * Follows segment first on, end to end, until the loop closes; when an end
 * meets nothing, back from its start: what then stays open is an open shape,
 * named by the piece whose end met nothing first.
 */
static ur_status chain_from(dxf_reader *reader, bool *used, size_t first, ur_error *error)
{
    double tolerance = reader->collection->tolerance;
    parts_points chain = {0};
    used[first] = true;
    ur_status status = parts_points_push(&chain, reader->segments[first].points.items[0], error);
    if (status == UR_OK)
        status = append_segment(&chain, &reader->segments[first].points, false, error);
    size_t last = first, dangling = SIZE_MAX;
    bool closed = false;
    while (status == UR_OK) {
        ur_vec2 end = chain.items[chain.count - 1];
        if (dangling == SIZE_MAX && chain.count > 2 &&
            ur_vec2_distance(end, chain.items[0]) <= tolerance) {
            chain.count--;
            closed = true;
            break;
        }
        bool reversed = false;
        size_t next = nearest_segment(reader, used, end, tolerance, &reversed);
        if (next == SIZE_MAX && dangling != SIZE_MAX)
            break;
        if (next == SIZE_MAX) {
            dangling = last;
            reverse_points(&chain);
            continue;
        }
        used[next] = true;
        last = next;
        status = append_segment(&chain, &reader->segments[next].points, reversed, error);
    }
    if (dangling != SIZE_MAX)
        reverse_points(&chain); /* from the start it had, as drawn */
    const dxf_segment *segment = &reader->segments[closed ? first : dangling];
    if (status == UR_OK && closed)
        status = parts_add_ring(reader->collection, &chain, segment->line, segment->what, NULL, 1,
                                NULL, error);
    if (status == UR_OK && closed)
        reader->collection->rings[reader->collection->count - 1].chained = true;
    else if (status == UR_OK)
        status = parts_add_line(reader->collection, &chain, false, UR_OP_CUT, segment->line,
                                segment->what, error);
    parts_points_free(&chain);
    return status;
}

static ur_status chain_segments(dxf_reader *reader, ur_error *error)
{
    if (reader->segment_count == 0)
        return UR_OK;
    bool *used = ur_alloc_array(reader->segment_count, sizeof *used, error);
    if (!used)
        return UR_ERROR_MEMORY;
    memset(used, 0, reader->segment_count * sizeof *used);
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < reader->segment_count; k++)
        if (!used[k])
            status = chain_from(reader, used, k, error);
    free(used);
    return status;
}

/* The kerf a 999 comment says the cut paths were compensated for (UR_KERF_NOTE), if any. */
static void read_kerf_note(dxf_reader *reader)
{
    for (size_t i = 0; i < reader->count; i++)
        if (reader->pairs[i].code == 999 &&
            parts_read_kerf_note(reader->pairs[i].value, &reader->collection->kerf_compensated))
            return;
}

ur_status parts_read_dxf(parts_collection *collection, ur_error *error)
{
    dxf_reader reader = {.collection = collection,
                         .path = collection->path,
                         .matrix = parts_identity,
                         .block_op = UR_OP_CUT};
    ur_status status = read_pairs(&reader, error);
    if (status == UR_OK)
        status = find_units(&reader, error);
    if (status == UR_OK)
        read_kerf_note(&reader);
    if (status == UR_OK)
        status = find_blocks(&reader, error);
    if (status == UR_OK)
        status = read_entities(&reader, error);
    if (status == UR_OK)
        status = chain_segments(&reader, error);
    for (size_t k = 0; k < reader.segment_count; k++)
        parts_points_free(&reader.segments[k].points);
    free(reader.segments);
    free(reader.blocks);
    free(reader.pairs);
    return status;
}
