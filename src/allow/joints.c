/*
 * joints.c: glue tabs or laps on the seams of a net, and the labels that
 * tell which edge goes to which (allow.h, ur_pieces_add_joints).
 *
 * A seam has two sides, runs of two outlines (develop.h, ur_seam_side).
 * A joint is built on one side, outward of it: outlines run
 * counter-clockwise, so outward is to the right of the run.  The joint's
 * shape is the run, a "shoulder" band (the material's thickness, for a
 * tab on thick stock) and a top line offset by the depth, pulled in at
 * both ends by depth / tan(angle) for a tab's taper.  It is united with
 * the piece's outline (GEOS), so the cut goes around it and the seam
 * itself becomes a fold.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A tab on stock at least this thick (mm) wraps the other piece's edge. */
#define THICK_STOCK 1.0

/*
 * The shapes a joint tries, in order, before it goes to the other side:
 * the share of the full depth, and how much of the seam's length is left
 * out at each end (a tab clear of the corners, where the neighbouring
 * edges of the piece come closest).
 */
static const struct {
    double depth, shorten;
} shapes[] = {{1.0, 0.0},  {0.7, 0.0}, {1.0, 0.15}, {0.7, 0.15},
              {0.5, 0.15}, {0.5, 0.3}, {0.35, 0.3}};

#define SHAPE_COUNT (sizeof shapes / sizeof shapes[0])

/* A clash smaller than this share of the joint's area is rounding, not overlap. */
#define CLASH_SHARE 1e-6

void ur_seam_label(int seam, char *label, size_t size)
{
    int index = seam > 0 ? seam - 1 : 0;
    int number = index % 99 + 1, letters = index / 99;
    char prefix[8];
    size_t length = 0;
    /* bijective base 26: A..Z, then AA, AB, ... */
    char reversed[8];
    int value = letters + 1;
    while (value > 0 && length < sizeof reversed) {
        value--;
        reversed[length++] = (char)('A' + value % 26);
        value /= 26;
    }
    for (size_t i = 0; i < length; i++)
        prefix[i] = reversed[length - 1 - i];
    prefix[length] = '\0';
    snprintf(label, size, "%s%d", prefix, number);
}

/* ---- The shape of a joint ----------------------------------------------- */

typedef struct run {
    ur_vec2 *points; /* the side, copied from its net's outline */
    size_t count;
    double length;
} run;

static ur_status run_of(const ur_net *net, const ur_seam_side *side, run *r, ur_error *error)
{
    r->points = ur_alloc_array(side->count, sizeof *r->points, error);
    if (!r->points)
        return UR_ERROR_INTERNAL;
    for (size_t k = 0; k < side->count; k++)
        r->points[k] = net->outline[(side->first + k) % net->outline_count];
    r->count = side->count;
    r->length = ur_polyline_length(r->points, r->count, false);
    return UR_OK;
}

/* The right-hand unit normal of the run's segment k (outward of a counter-clockwise outline). */
static ur_vec2 segment_normal(const run *r, size_t k)
{
    ur_vec2 d = ur_vec2_sub(r->points[k + 1], r->points[k]);
    double length = ur_vec2_length(d);
    return length > 0 ? ur_vec2_make(d.y / length, -d.x / length) : ur_vec2_make(0, 0);
}

/* The mitred offset direction at vertex k, so that offset edges stay parallel. */
static ur_vec2 vertex_normal(const run *r, size_t k)
{
    if (k == 0)
        return segment_normal(r, 0);
    if (k + 1 == r->count)
        return segment_normal(r, k - 1);
    ur_vec2 a = segment_normal(r, k - 1), b = segment_normal(r, k);
    ur_vec2 sum = ur_vec2_add(a, b);
    double dot = ur_vec2_dot(sum, a);
    if (dot < 0.5) /* a turn of more than about 120 degrees: do not mitre to infinity */
        return a;
    return ur_vec2_scale(sum, 1.0 / dot);
}

/* The point at arc length s along the run and the segment it lies on. */
static ur_vec2 point_at(const run *r, double s, size_t *segment)
{
    double walked = 0;
    for (size_t k = 0; k + 1 < r->count; k++) {
        double length = ur_vec2_distance(r->points[k], r->points[k + 1]);
        if (walked + length >= s || k + 2 == r->count) {
            *segment = k;
            double t = length > 0 ? fmin(1.0, fmax(0.0, (s - walked) / length)) : 0.0;
            return ur_vec2_add_scaled(r->points[k], ur_vec2_sub(r->points[k + 1], r->points[k]), t);
        }
        walked += length;
    }
    *segment = 0;
    return r->points[0];
}

/*
 * The joint's ring: along the run, out by `band` at its ends, over the top
 * at band + depth between arc lengths inset and length - inset, back.
 * Negative band and depth build it inward (the lapped zone of the other
 * piece).
 */
static ur_status joint_ring(const run *r, double band, double depth, double inset, ur_points *ring,
                            ur_error *error)
{
    ur_status status = UR_OK;
    double height = band + depth;
    for (size_t k = 0; status == UR_OK && k < r->count; k++)
        status = ur_points_push(ring, r->points[r->count - 1 - k], error);
    if (status == UR_OK && band != 0)
        status = ur_points_push(ring, ur_vec2_add_scaled(r->points[0], vertex_normal(r, 0), band),
                                error);
    size_t segment;
    ur_vec2 start = point_at(r, inset, &segment);
    if (status == UR_OK)
        status = ur_points_push(ring, ur_vec2_add_scaled(start, segment_normal(r, segment), height),
                                error);
    double walked = 0;
    for (size_t k = 0; status == UR_OK && k + 1 < r->count; k++) {
        walked += ur_vec2_distance(r->points[k], r->points[k + 1]);
        if (k + 2 < r->count && walked > inset && walked < r->length - inset)
            status = ur_points_push(
                ring, ur_vec2_add_scaled(r->points[k + 1], vertex_normal(r, k + 1), height), error);
    }
    ur_vec2 end = point_at(r, r->length - inset, &segment);
    if (status == UR_OK)
        status = ur_points_push(ring, ur_vec2_add_scaled(end, segment_normal(r, segment), height),
                                error);
    if (status == UR_OK && band != 0)
        status = ur_points_push(
            ring, ur_vec2_add_scaled(r->points[r->count - 1], vertex_normal(r, r->count - 1), band),
            error);
    return status;
}

/* ---- Fitting a joint to a piece ----------------------------------------- */

typedef struct joiner {
    GEOSContextHandle_t geos;
    ur_piece *pieces;
    const ur_net_list *nets;
    const ur_joint_options *options;
    size_t *tab_count; /* per piece, to balance them */
} joiner;

static GEOSGeometry *outline_of(const joiner *j, const ur_piece *piece)
{
    return ur_geos_polygon(j->geos, piece->paths[0].points, piece->paths[0].count);
}

/*
 * How much of the joint overlaps the piece: its area inside the current
 * outline (which holds the tabs already added), or INFINITY when the
 * joint is no simple polygon.
 */
static double clash(const joiner *j, const ur_piece *piece, const GEOSGeometry *joint)
{
    if (!joint || GEOSisValid_r(j->geos, joint) != 1)
        return INFINITY;
    GEOSGeometry *outline = outline_of(j, piece);
    if (!outline)
        return INFINITY;
    GEOSGeometry *overlap = GEOSIntersection_r(j->geos, outline, joint);
    double area = overlap ? allow_area(j->geos, overlap) : INFINITY;
    if (overlap)
        GEOSGeom_destroy_r(j->geos, overlap);
    GEOSGeom_destroy_r(j->geos, outline);
    return area;
}

/* The joint united with the piece's outline, if that stays one ring. */
static ur_status grow_outline(const joiner *j, ur_piece *piece, const GEOSGeometry *joint,
                              bool *grown, ur_error *error)
{
    *grown = false;
    GEOSGeometry *outline = outline_of(j, piece);
    GEOSGeometry *exact = outline ? GEOSUnion_r(j->geos, outline, joint) : NULL;
    /*
     * Where a joint's corner meets the outline a hair's breadth off, the
     * union keeps a sliver a micrometre wide that folds back on itself;
     * simplifying by a micrometre, far below any cutter's resolution,
     * takes it out.
     */
    GEOSGeometry *united = exact ? GEOSTopologyPreserveSimplify_r(j->geos, exact, 1e-3) : NULL;
    if (exact)
        GEOSGeom_destroy_r(j->geos, exact);
    if (outline)
        GEOSGeom_destroy_r(j->geos, outline);
    if (!united)
        return UR_OK;
    ur_status status = UR_OK;
    if (GEOSGeomTypeId_r(j->geos, united) == GEOS_POLYGON &&
        GEOSGetNumInteriorRings_r(j->geos, united) == 0) {
        ur_vec2 *ring;
        size_t count;
        status = allow_exterior_ring(j->geos, united, &ring, &count, error);
        if (status == UR_OK) {
            free(piece->paths[0].points);
            piece->paths[0].points = ring;
            piece->paths[0].count = count;
            piece->paths[0].circle = (ur_path_circle){{0, 0}, 0, 0}; /* grown: no circle */
            for (size_t i = 0; i < count; i++)
                ur_box_add(&piece->box, ring[i]);
            *grown = true;
        }
    }
    GEOSGeom_destroy_r(j->geos, united);
    return status;
}

/* The joint's polygon for a run at a share of the full depth, or NULL. */
static GEOSGeometry *joint_polygon(const joiner *j, const run *r, double share, double *depth,
                                   ur_error *error)
{
    const ur_joint_options *o = j->options;
    double band = !o->lap && o->thickness >= THICK_STOCK ? o->thickness : 0.0;
    *depth = (o->lap ? o->lap_width : o->tab_depth) * share;
    double angle = o->lap ? 90.0 : o->tab_angle;
    double inset = angle >= 90.0 ? 0.0 : *depth / tan(angle * M_PI / 180.0);
    if (2 * inset > 0.8 * r->length) { /* a short seam: a lower tab keeps some top */
        inset = 0.4 * r->length;
        *depth = inset * tan(angle * M_PI / 180.0);
    }
    ur_points ring = {0};
    GEOSGeometry *polygon = NULL;
    if (joint_ring(r, band, *depth, inset, &ring, error) == UR_OK)
        polygon = ur_geos_polygon(j->geos, ring.items, ring.count);
    ur_points_free(&ring);
    return polygon;
}

static ur_status add_open_path(ur_piece *piece, ur_op op, const run *r, double offset,
                               ur_error *error)
{
    ur_vec2 *points = ur_alloc_array(r->count, sizeof *points, error);
    if (!points)
        return UR_ERROR_INTERNAL;
    for (size_t k = 0; k < r->count; k++)
        points[k] = ur_vec2_add_scaled(r->points[k], vertex_normal(r, k), offset);
    ur_status status = ur_piece_add_path(piece, op, points, r->count, false, error);
    free(points);
    return status;
}

/* The folds of a tab: at the seam, and at the shoulder on thick stock. */
static ur_status add_folds(const joiner *j, ur_piece *piece, const run *r, ur_error *error)
{
    ur_status status = add_open_path(piece, UR_OP_SCORE, r, 0.0, error);
    if (status == UR_OK && j->options->thickness >= THICK_STOCK)
        status = add_open_path(piece, UR_OP_SCORE, r, j->options->thickness, error);
    return status;
}

static ur_vec2 run_middle(const run *r)
{
    size_t segment;
    return point_at(r, r->length / 2, &segment);
}

static ur_status record(ur_piece *piece, ur_allowance_kind kind, ur_vec2 where, bool warning,
                        ur_error *error, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 6, 7)))
#endif
    ;

static ur_status record(ur_piece *piece, ur_allowance_kind kind, ur_vec2 where, bool warning,
                        ur_error *error, const char *format, ...)
{
    ur_allowance_record entry = {.kind = kind,
                                 .count = warning ? 0 : 1,
                                 .value = NAN,
                                 .limit = NAN,
                                 .where = where,
                                 .warning = warning};
    va_list args;
    va_start(args, format);
    vsnprintf(entry.reason, sizeof entry.reason, format, args);
    va_end(args);
    return ur_piece_record(piece, &entry, error);
}

/* ---- Laps: the zone marked on both pieces -------------------------------- */

static ur_status add_mark(ur_piece *piece, const GEOSGeometry *zone, const joiner *j,
                          ur_error *error)
{
    ur_vec2 *ring;
    size_t count;
    if (GEOSGeomTypeId_r(j->geos, zone) != GEOS_POLYGON || GEOSisEmpty_r(j->geos, zone))
        return UR_OK; /* nothing left to mark */
    ur_status status = allow_exterior_ring(j->geos, zone, &ring, &count, error);
    if (status == UR_OK)
        status = ur_piece_add_path(piece, UR_OP_MARK, ring, count, true, error);
    free(ring);
    return status;
}

/* The other piece's lapped zone: inward of its side, clipped to it. */
static ur_status mark_under(const joiner *j, ur_piece *piece, const run *r, ur_error *error)
{
    ur_points ring = {0};
    ur_status status = joint_ring(r, 0.0, -j->options->lap_width, 0.0, &ring, error);
    GEOSGeometry *zone = status == UR_OK ? ur_geos_polygon(j->geos, ring.items, ring.count) : NULL;
    ur_points_free(&ring);
    GEOSGeometry *outline = zone ? outline_of(j, piece) : NULL;
    GEOSGeometry *valid = zone ? GEOSMakeValid_r(j->geos, zone) : NULL;
    GEOSGeometry *clipped = outline && valid ? GEOSIntersection_r(j->geos, outline, valid) : NULL;
    if (status == UR_OK && clipped)
        status = add_mark(piece, clipped, j, error);
    GEOSGeometry *all[] = {zone, outline, valid, clipped};
    for (size_t k = 0; k < 4; k++)
        if (all[k])
            GEOSGeom_destroy_r(j->geos, all[k]);
    return status;
}

/* ---- One seam ------------------------------------------------------------ */

typedef struct seam_sides {
    size_t net[2], side[2];
    size_t found;
} seam_sides;

/*
 * The part of the run between arc lengths from and length - from, as a run
 * of its own (its ends interpolated); the caller frees out->points.
 */
static ur_status shortened(const run *r, double from, run *out, ur_error *error)
{
    size_t first_segment, last_segment;
    ur_vec2 start = point_at(r, from, &first_segment);
    ur_vec2 end = point_at(r, r->length - from, &last_segment);
    out->points = ur_alloc_array(last_segment - first_segment + 2, sizeof *out->points, error);
    if (!out->points)
        return UR_ERROR_INTERNAL;
    out->count = 0;
    out->points[out->count++] = start;
    for (size_t k = first_segment + 1; k <= last_segment; k++)
        out->points[out->count++] = r->points[k];
    out->points[out->count++] = end;
    out->length = ur_polyline_length(out->points, out->count, false);
    return UR_OK;
}

/* What a joint adds once it is on: marks (lap) or folds (tab), and the record. */
static ur_status finish_joint(const joiner *j, size_t piece_index, const run *base,
                              const GEOSGeometry *joint, const run *other, size_t other_piece,
                              const char *label, double depth, bool reduced, ur_error *error)
{
    ur_piece *piece = &j->pieces[piece_index];
    ur_status status;
    j->tab_count[piece_index]++;
    if (j->options->lap) {
        status = add_mark(piece, joint, j, error);
        if (status == UR_OK)
            status = mark_under(j, &j->pieces[other_piece], other, error);
        if (status == UR_OK)
            status = record(piece, UR_ALLOWANCE_JOINT, run_middle(base), false, error,
                            "lap %.3g mm under seam %s, marked on both pieces%s", depth, label,
                            reduced ? " (made smaller to fit)" : "");
        return status;
    }
    status = add_folds(j, piece, base, error);
    if (status == UR_OK)
        status = record(piece, UR_ALLOWANCE_JOINT, run_middle(base), false, error,
                        "glue tab on seam %s, %.3g mm deep%s", label, depth,
                        reduced ? " (made smaller to fit)" : "");
    return status;
}

/* Tries the joint on one side in every shape in turn; *placed says if it went on. */
static ur_status try_side(const joiner *j, size_t piece_index, const run *r, const run *other,
                          size_t other_piece, const char *label, bool *placed, ur_error *error)
{
    ur_piece *piece = &j->pieces[piece_index];
    *placed = false;
    ur_status status = UR_OK;
    for (size_t step = 0; status == UR_OK && !*placed && step < SHAPE_COUNT; step++) {
        run base;
        status = shortened(r, shapes[step].shorten * r->length, &base, error);
        if (status != UR_OK)
            break;
        double depth;
        GEOSGeometry *joint = joint_polygon(j, &base, shapes[step].depth, &depth, error);
        if (joint && clash(j, piece, joint) <= CLASH_SHARE * allow_area(j->geos, joint))
            status = grow_outline(j, piece, joint, placed, error);
        if (status == UR_OK && *placed)
            status = finish_joint(j, piece_index, &base, joint, other, other_piece, label, depth,
                                  step > 0, error);
        if (joint)
            GEOSGeom_destroy_r(j->geos, joint);
        free(base.points);
    }
    return status;
}

/* Which side first: the one that clashes less; when both are free, the piece with fewer joints. */
static int first_side(const joiner *j, const seam_sides *s, const run runs[2], ur_error *error)
{
    double clashes[2];
    for (int k = 0; k < 2; k++) {
        double depth;
        GEOSGeometry *joint = joint_polygon(j, &runs[k], 1.0, &depth, error);
        clashes[k] = clash(j, &j->pieces[s->net[k]], joint);
        if (joint) {
            clashes[k] /= fmax(allow_area(j->geos, joint), 1e-12);
            GEOSGeom_destroy_r(j->geos, joint);
        }
        if (clashes[k] <= CLASH_SHARE)
            clashes[k] = 0;
    }
    if (clashes[0] != clashes[1])
        return clashes[0] < clashes[1] ? 0 : 1;
    return j->tab_count[s->net[1]] < j->tab_count[s->net[0]] ? 1 : 0;
}

/*
 * The seam's direction where its label goes: that of the segment there.
 * A side that is a closed loop (the rim of a hole, the whole outline of a
 * piece) ends where it starts, so its chord says nothing; a zero-length
 * segment falls back to the chord, and that to +x.
 */
static ur_vec2 direction_at(const run *r, size_t segment)
{
    ur_vec2 along = ur_vec2_sub(r->points[segment + 1], r->points[segment]);
    if (!(ur_vec2_length(along) > 0))
        along = ur_vec2_sub(r->points[r->count - 1], r->points[0]);
    if (!(ur_vec2_length(along) > 0) || !isfinite(along.x) || !isfinite(along.y))
        along = ur_vec2_make(1, 0);
    return along;
}

/*
 * Engraves one label for the joints: the place and direction are ours, so
 * a refusal of them is our failure (UR_ERROR_INTERNAL), never bad input.
 */
static ur_status engrave_label(ur_piece *piece, const ur_font *font, const char *text, ur_vec2 near,
                               ur_vec2 along, double height, double clearance, bool *placed,
                               ur_error *error)
{
    ur_status status = ur_piece_add_label(piece, font, text, near, along, height, 0.5 * height,
                                          clearance, placed, error);
    if (status == UR_ERROR_INPUT) {
        if (error)
            error->status = UR_ERROR_INTERNAL;
        ur_error_prefix(error, "piece %s: ", piece->name);
        return UR_ERROR_INTERNAL;
    }
    return status;
}

static ur_status label_side(const joiner *j, ur_piece *piece, const run *r, const char *text,
                            ur_error *error)
{
    const ur_joint_options *o = j->options;
    size_t segment;
    ur_vec2 middle = point_at(r, r->length / 2, &segment);
    ur_vec2 inward = ur_vec2_scale(segment_normal(r, segment), -1.0);
    /* Beside the seam; with laps beyond the zone the other piece covers. */
    double lapped = o->lap ? o->lap_width : 0.0;
    ur_vec2 near = ur_vec2_add_scaled(middle, inward, lapped + 0.5 * o->label_height + 1.0);
    double clearance = fmax(0.3, 0.15 * o->label_height);
    bool placed;
    ur_status status = engrave_label(piece, o->font, text, near, direction_at(r, segment),
                                     o->label_height, clearance, &placed, error);
    if (status == UR_OK && !placed)
        status = record(piece, UR_ALLOWANCE_LABEL, middle, true, error,
                        "no room for label %s beside its seam", text);
    return status;
}

/*
 * Both sides of a seam get its label.  Labels go on before the joints, so
 * that they are placed within the net's own outline and never on a tab
 * (which is glued out of sight).
 */
static ur_status label_seam(const joiner *j, const seam_sides *s, int seam, ur_error *error)
{
    char label[16];
    ur_seam_label(seam, label, sizeof label);
    ur_status status = UR_OK;
    for (int k = 0; status == UR_OK && k < 2; k++) {
        const ur_net *net = &j->nets->nets[s->net[k]];
        run r = {0};
        status = run_of(net, &net->seam_sides[s->side[k]], &r, error);
        if (status == UR_OK)
            status = label_side(j, &j->pieces[s->net[k]], &r, label, error);
        free(r.points);
    }
    return status;
}

static ur_status join_seam(const joiner *j, const seam_sides *s, int seam, ur_error *error)
{
    char label[16];
    ur_seam_label(seam, label, sizeof label);
    run runs[2] = {{0}};
    ur_status status = UR_OK;
    for (int k = 0; status == UR_OK && k < 2; k++)
        status = run_of(&j->nets->nets[s->net[k]], &j->nets->nets[s->net[k]].seam_sides[s->side[k]],
                        &runs[k], error);
    int first = status == UR_OK ? first_side(j, s, runs, error) : 0;
    bool placed = false;
    for (int attempt = 0; status == UR_OK && !placed && attempt < 2; attempt++) {
        int k = attempt == 0 ? first : 1 - first;
        status =
            try_side(j, s->net[k], &runs[k], &runs[1 - k], s->net[1 - k], label, &placed, error);
    }
    if (status == UR_OK && !placed)
        status = record(&j->pieces[s->net[first]], UR_ALLOWANCE_JOINT, run_middle(&runs[first]),
                        true, error, "no room for a %s on seam %s on either side: join it by hand",
                        j->options->lap ? "lap" : "glue tab", label);
    free(runs[0].points);
    free(runs[1].points);
    return status;
}

/* ---- All seams ------------------------------------------------------------ */

/* For each seam number, where its two sides are. */
static ur_status gather_seams(const ur_net_list *nets, seam_sides **seams, int *last,
                              ur_error *error)
{
    *last = ur_net_list_last_seam(nets);
    *seams = calloc((size_t)*last + 1, sizeof **seams);
    if (!*seams)
        return ur_error_out_of_memory(error);
    for (size_t n = 0; n < nets->count; n++)
        for (size_t k = 0; k < nets->nets[n].seam_side_count; k++) {
            int seam = nets->nets[n].seam_sides[k].seam;
            seam_sides *s = &(*seams)[seam];
            if (seam < 1 || s->found == 2)
                continue; /* no seam has more than two sides (develop.h) */
            s->net[s->found] = n;
            s->side[s->found++] = k;
        }
    return UR_OK;
}

static ur_status name_piece(const joiner *j, ur_piece *piece, ur_error *error)
{
    ur_vec2 centre = ur_vec2_make((piece->box.min.x + piece->box.max.x) / 2,
                                  (piece->box.min.y + piece->box.max.y) / 2);
    const ur_joint_options *o = j->options;
    bool placed;
    ur_status status =
        engrave_label(piece, o->font, piece->name, centre, ur_vec2_make(1, 0), o->label_height,
                      fmax(0.3, 0.15 * o->label_height), &placed, error);
    if (status == UR_OK && !placed)
        status = record(piece, UR_ALLOWANCE_LABEL, centre, true, error,
                        "no room to engrave the piece's name %s", piece->name);
    return status;
}

static ur_status check_options(const ur_joint_options *o, ur_error *error)
{
    bool sizes = o->lap ? o->lap_width > 0 && isfinite(o->lap_width)
                        : o->tab_depth > 0 && isfinite(o->tab_depth) && o->tab_angle > 0 &&
                              o->tab_angle <= 90;
    if (!sizes || !(o->thickness >= 0) || (o->font && !(o->label_height > 0)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "joints need a positive tab depth (angle above 0 up to 90 degrees) "
                            "or lap width, and a positive label height");
    return UR_OK;
}

ur_status ur_pieces_add_joints(ur_piece *pieces, const ur_net_list *nets,
                               const ur_joint_options *options, ur_error *error)
{
    ur_status status = check_options(options, error);
    if (status != UR_OK)
        return status;
    for (size_t n = 0; n < nets->count; n++)
        if (pieces[n].path_count == 0 || !pieces[n].paths[0].closed)
            return ur_error_set(error, UR_ERROR_INTERNAL, "piece %s has no closed outline",
                                pieces[n].name);
    seam_sides *seams = NULL;
    int last = 0;
    joiner j = {GEOS_init_r(), pieces, nets, options, calloc(nets->count + 1, sizeof(size_t))};
    if (!j.geos || !j.tab_count)
        status = ur_error_out_of_memory(error);
    if (status == UR_OK)
        status = gather_seams(nets, &seams, &last, error);
    for (int seam = 1; status == UR_OK && options->font && seam <= last; seam++)
        if (seams[seam].found == 2)
            status = label_seam(&j, &seams[seam], seam, error);
    for (size_t n = 0; status == UR_OK && options->font && options->name_pieces && n < nets->count;
         n++)
        status = name_piece(&j, &pieces[n], error);
    for (int seam = 1; status == UR_OK && seam <= last; seam++)
        if (seams[seam].found == 2)
            status = join_seam(&j, &seams[seam], seam, error);
    free(seams);
    free(j.tab_count);
    if (j.geos)
        GEOS_finish_r(j.geos);
    return status;
}
