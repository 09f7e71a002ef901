/*
 * kerf.c: kerf compensation.  The beam or bit removes a strip of material
 * as wide as the kerf centred on the path it follows, so a part cut along
 * its drawn outline comes out half a kerf too small all round and its holes
 * half a kerf too large.  Moving the outline out and the holes in by half
 * the kerf (GEOS buffer, mitred joins so square corners stay square) makes
 * the part come out at its drawn size.
 *
 * Everything is worked out before the piece is touched, so a failure
 * leaves it as it was.  A slot of the outline whose mouth is narrower
 * than the kerf (a glue tab reaching across a narrow notch to its other
 * side, say) closes at the mouth as the outline moves out, and the room
 * behind the mouth becomes a hole of the moved outline: it is cut as a
 * hole, so that the slot's sides are still cut, with a warning that the
 * mouth, which no cutter can cut, holds them together.  Filling it would
 * leave the sides uncut: two faces of a net joined across a seam.  A room
 * too small to cut round (less than a kerf square) is filled.  A hole
 * with a part narrower than the kerf cannot move in (it would vanish or
 * split): it is cut as drawn, coming out half a kerf wider all round,
 * with a warning.
 * Material narrower than the kerf is burned away by the cut itself: where
 * the outline's own parts are (a strip of a modeller's micro-faces, such
 * as a cut gem's girdle 0.012 mm high, unfolded), a warning says so.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

/*
 * GEOS's mitre limit is the mitre's length over the offset distance.  10
 * keeps every corner down to about 11 degrees sharp (a right angle needs
 * only 1.41); sharper spikes are bevelled at ten offsets out rather than
 * reaching far past the part.
 */
#define KERF_MITRE_LIMIT 10.0

/* A vertex closer than this to the line through its neighbours adds nothing (mm). */
#define KERF_STRAIGHT 1e-9

/* A closed CUT path other than the outline: a hole to be shrunk. */
static bool is_hole(const ur_path *path)
{
    return path->op == UR_OP_CUT && path->closed && path->count >= 3;
}

/*
 * Drops the points GEOS may leave that carry no shape: repeats and points
 * on the straight line between their neighbours, so a rectangle stays four
 * corners.  The ring keeps at least 3 points.
 */
static void drop_straight_points(ur_vec2 *ring, size_t *count)
{
    size_t n = *count;
    bool changed = true;
    while (changed && n > 3) {
        changed = false;
        for (size_t i = 0; i < n && n > 3; i++) {
            ur_vec2 before = ring[(i + n - 1) % n], here = ring[i], after = ring[(i + 1) % n];
            ur_vec2 chord = ur_vec2_sub(after, before);
            double length = ur_vec2_length(chord);
            double off = length > 0 ? fabs(ur_vec2_cross(chord, ur_vec2_sub(here, before))) / length
                                    : ur_vec2_distance(here, before);
            bool between = ur_vec2_dot(ur_vec2_sub(here, before), chord) >= 0 &&
                           ur_vec2_dot(ur_vec2_sub(after, here), chord) >= 0;
            if (off < KERF_STRAIGHT && between) {
                memmove(&ring[i], &ring[i + 1], (n - i - 1) * sizeof *ring);
                n--;
                changed = true;
            }
        }
    }
    *count = n;
}

static ur_vec2 box_middle(ur_box box)
{
    return ur_vec2_make((box.min.x + box.max.x) / 2, (box.min.y + box.max.y) / 2);
}

/* The middle of a path's box: where the report and the messages say it is. */
static ur_vec2 path_middle(const ur_path *path)
{
    return box_middle(ur_box_of_points(path->points, path->count));
}

/* The middle of a GEOS geometry's box; (0, 0) for none. */
static ur_vec2 geometry_middle(GEOSContextHandle_t geos, const GEOSGeometry *g)
{
    ur_box box = allow_box(geos, g);
    return box.min.x <= box.max.x ? box_middle(box) : ur_vec2_make(0, 0);
}

/*
 * What offsetting found that the cutter cannot do as asked: slots of the
 * outline filled or cut behind their mouths (the rooms behind them, as
 * holes to add: owned), holes cut as drawn; each with the place of the
 * first.
 */
typedef struct kerf_findings {
    size_t slots, narrow_holes;
    ur_vec2 slot_at, narrow_hole_at, room_at;
    ur_path *rooms;
    size_t room_count, room_capacity;
} kerf_findings;

/* Frees the rooms not given to the piece (their points NULL once given); their count stays. */
static void findings_free(kerf_findings *found)
{
    for (size_t i = 0; i < found->room_count; i++)
        free(found->rooms[i].points);
    free(found->rooms);
    found->rooms = NULL;
}

/* Keeps a room behind a slot's mouth (its points, now the findings'), as a clockwise hole. */
static ur_status keep_room(kerf_findings *found, ur_vec2 *points, size_t count, ur_error *error)
{
    ur_path *grown = ur_array_grow(found->rooms, &found->room_capacity, found->room_count,
                                   sizeof *grown, 4, error);
    if (!grown) {
        free(points);
        return UR_ERROR_MEMORY;
    }
    found->rooms = grown;
    ur_points_reverse(points, count); /* a hole runs against its outline */
    ur_path *room = &found->rooms[found->room_count++];
    *room = (ur_path){.op = UR_OP_CUT, .closed = true, .points = points, .count = count};
    if (found->room_count == 1)
        found->room_at = path_middle(room);
    return UR_OK;
}

/*
 * The holes the outline moved out by half the kerf has: slots whose mouths
 * closed.  Each is the room behind its mouth, its sides moved in by half
 * the kerf as a hole's are: kept to be cut, or when it is less than a kerf
 * square, counted as filled.
 */
static ur_status closed_slots(GEOSContextHandle_t geos, const GEOSGeometry *buffered, double kerf,
                              kerf_findings *found, ur_error *error)
{
    ur_status status = UR_OK;
    for (int k = 0, n = GEOSGetNumInteriorRings_r(geos, buffered); status == UR_OK && k < n; k++) {
        const GEOSGeometry *ring = GEOSGetInteriorRingN_r(geos, buffered, k);
        ur_vec2 *points = NULL;
        size_t count = 0;
        status = allow_ring_points(geos, ring, &points, &count, error);
        if (status != UR_OK)
            break;
        if (ur_polygon_signed_area(points, count) >= kerf * kerf) {
            status = keep_room(found, points, count, error);
            continue;
        }
        if (found->slots++ == 0)
            found->slot_at = box_middle(ur_box_of_points(points, count));
        free(points);
    }
    return status;
}

/* Notes a hole too narrow to move in, which is then cut as drawn (its ring left NULL). */
static void note_narrow_hole(kerf_findings *found, ur_vec2 at)
{
    if (found->narrow_holes++ == 0)
        found->narrow_hole_at = at;
}

/*
 * The ring of path offset by distance (> 0 outward, < 0 inward) into
 * *ring (counter-clockwise), or *ring NULL for a hole that would vanish or
 * split, noted in found: the laser cannot cut it smaller, and cuts it as
 * drawn.  A slot of the outline whose mouth is narrower than the kerf
 * closes into a hole as the outline moves out: the room behind the mouth,
 * kept in found to be cut as a hole (closed_slots).
 */
static ur_status offset_ring(GEOSContextHandle_t geos, const GEOSBufferParams *params,
                             const ur_piece *piece, size_t index, double distance, ur_vec2 **ring,
                             size_t *count, kerf_findings *found, ur_error *error)
{
    const ur_path *path = &piece->paths[index];
    ur_vec2 at = path_middle(path);
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, path->points, path->count);
    GEOSGeometry *buffered =
        polygon ? GEOSBufferWithParams_r(geos, polygon, params, distance) : NULL;
    ur_status status = UR_OK;
    *ring = NULL;
    if (!buffered)
        status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not offset a path of piece %s",
                              piece->name);
    else if (index > 0 &&
             (GEOSisEmpty_r(geos, buffered) || GEOSGeomTypeId_r(geos, buffered) != GEOS_POLYGON ||
              GEOSGetNumInteriorRings_r(geos, buffered) != 0))
        note_narrow_hole(found, at);
    else if (GEOSGeomTypeId_r(geos, buffered) != GEOS_POLYGON || GEOSisEmpty_r(geos, buffered))
        status = ur_error_set(error, UR_ERROR_INPUT,
                              "piece %s: the outline at (%.1f, %.1f) has a part narrower than the "
                              "kerf (%g mm) that would split it",
                              piece->name, at.x, at.y, 2 * distance);
    else {
        status = closed_slots(geos, buffered, 2 * distance, found, error);
        if (status == UR_OK)
            status = allow_exterior_ring(geos, buffered, ring, count, error);
    }
    if (buffered)
        GEOSGeom_destroy_r(geos, buffered);
    if (polygon)
        GEOSGeom_destroy_r(geos, polygon);
    if (status == UR_OK && *ring)
        drop_straight_points(*ring, count);
    return status;
}

/*
 * A circle's offset is the circle of radius r + distance about the same
 * centre, exactly: its points move straight out (or in) from the centre,
 * keeping their order and staying on it, without GEOS, whose buffer of the
 * inscribed polygon would be a polygon near the circle but not on it.
 */
static ur_status offset_circle(const ur_piece *piece, size_t index, double distance, ur_vec2 **ring,
                               size_t *count, kerf_findings *found, ur_error *error)
{
    const ur_path *path = &piece->paths[index];
    ur_path_circle circle = path->circle;
    double radius = circle.radius + distance;
    *ring = NULL;
    if (!(radius > 0)) {
        note_narrow_hole(found, circle.centre);
        return UR_OK;
    }
    *ring = ur_alloc_array(path->count, sizeof **ring, error);
    if (!*ring)
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < path->count; k++) {
        ur_vec2 out = ur_vec2_sub(path->points[k], circle.centre);
        double length = ur_vec2_length(out);
        (*ring)[k] =
            length > 0 ? ur_vec2_add_scaled(circle.centre, out, radius / length) : path->points[k];
    }
    *count = path->count;
    return UR_OK;
}

/*
 * What of the outline's material is narrower than the kerf: what its
 * opening by the kerf (shrunk by half of it, then grown back, GEOS
 * buffers) takes away.  A sharp corner loses its tip there, little (a 5
 * degree point 0.05 mm2 at a 0.1 mm kerf); a strip narrower than the kerf
 * goes whole, and a neck parts what is left.
 */
typedef struct narrow_material {
    size_t parts;   /* the parts left, specks (a corner's tip cut off) not counted */
    double largest; /* the area of the largest part taken away (mm2), if made */
    ur_vec2 where;  /* the middle of that part's box, else of the smallest part left */
} narrow_material;

/*
 * A part taken away, or left, of more than this many kerf squares (a
 * strip 50 kerfs long) is worth a warning; less is a speck.
 */
#define KERF_NARROW_SQUARES 50.0

/*
 * And a part taken away is looked for only when all that is taken is more
 * than this share of the piece: the corners of a large net's many tabs
 * lose more than a speck in all, and the difference that finds the parts
 * took 8 of the 24 s a 99,904-triangle sphere took to unfold.
 */
#define KERF_NARROW_SHARE 0.01

/* The polygons of g larger than least, and the middle of the smallest of them. */
static size_t polygons_larger_than(GEOSContextHandle_t geos, const GEOSGeometry *g, double least,
                                   ur_vec2 *smallest)
{
    size_t count = 0;
    double fewest = INFINITY;
    for (int k = 0, n = GEOSGetNumGeometries_r(geos, g); k < n; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(geos, g, k);
        double area = allow_area(geos, part);
        if (area > least) {
            count++;
            if (area < fewest) {
                fewest = area;
                *smallest = geometry_middle(geos, part);
            }
        }
    }
    return count;
}

/* The largest polygon of what was taken away: its area and where it is. */
static void largest_taken(GEOSContextHandle_t geos, const GEOSGeometry *taken,
                          narrow_material *narrow)
{
    narrow->largest = 0;
    for (int k = 0, n = GEOSGetNumGeometries_r(geos, taken); k < n; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(geos, taken, k);
        double area = allow_area(geos, part);
        if (area > narrow->largest) {
            narrow->largest = area;
            narrow->where = geometry_middle(geos, part);
        }
    }
}

/*
 * False when GEOS cannot tell (the outline is left as it is, with no
 * warning).  What the opening took away is made (a difference, the
 * costly part) only when there may be something to say: the piece comes
 * apart, or loses more than KERF_NARROW_SHARE of itself.
 */
static bool measure_narrow(GEOSContextHandle_t geos, const ur_path *outline, double kerf,
                           narrow_material *narrow)
{
    double speck = KERF_NARROW_SQUARES * kerf * kerf, area = 0, kept = 0;
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, outline->points, outline->count);
    if (polygon && GEOSisValid_r(geos, polygon) != 1) {
        /* An outline touching itself (a flap held at a point): the overlay needs it valid. */
        GEOSGeometry *valid = GEOSMakeValid_r(geos, polygon);
        GEOSGeom_destroy_r(geos, polygon);
        polygon = valid;
    }
    GEOSGeometry *shrunk = polygon ? GEOSBuffer_r(geos, polygon, -kerf / 2, 2) : NULL;
    GEOSGeometry *opened = shrunk ? GEOSBuffer_r(geos, shrunk, kerf / 2, 2) : NULL;
    bool known =
        opened && GEOSArea_r(geos, polygon, &area) == 1 && GEOSArea_r(geos, opened, &kept) == 1;
    GEOSGeometry *taken = NULL;
    *narrow = (narrow_material){0};
    if (known) {
        /* A tenth of the piece is never a speck, however wide the kerf. */
        narrow->parts = polygons_larger_than(geos, opened, fmin(speck, 0.1 * area), &narrow->where);
        bool look = narrow->parts != 1 || area - kept > fmax(speck, KERF_NARROW_SHARE * area);
        taken = look ? GEOSDifference_r(geos, polygon, opened) : NULL;
        if (taken)
            largest_taken(geos, taken, narrow);
        /* Without the difference a piece in parts is still said, placed by its smallest part. */
        known = !look || taken || narrow->parts != 1;
    }
    GEOSGeometry *made[] = {polygon, shrunk, opened, taken};
    for (size_t i = 0; i < sizeof made / sizeof *made; i++)
        if (made[i])
            GEOSGeom_destroy_r(geos, made[i]);
    return known;
}

/* A warning of count things at where, its reason the text. */
static ur_status record_warning(ur_piece *piece, double kerf, size_t count, ur_vec2 where,
                                const char *text, ur_error *error)
{
    ur_allowance_record warning = {.kind = UR_ALLOWANCE_KERF_COMPENSATION,
                                   .count = count,
                                   .value = kerf,
                                   .limit = NAN,
                                   .where = where,
                                   .warning = true};
    c_snprintf(warning.reason, sizeof warning.reason, "%s", text);
    return ur_piece_record(piece, &warning, error);
}

/* The warning for material narrower than the kerf, when there is enough of it to matter. */
static ur_status record_narrow(ur_piece *piece, double kerf, const narrow_material *narrow,
                               ur_error *error)
{
    bool gone = narrow->parts == 0, parted = narrow->parts >= 2;
    if (!gone && !parted && !(narrow->largest > KERF_NARROW_SQUARES * kerf * kerf))
        return UR_OK;
    char text[sizeof((ur_allowance_record *)NULL)->reason];
    if (gone)
        c_snprintf(text, sizeof text,
                   "narrower than the kerf (%g mm) everywhere: the cut would burn it away", kerf);
    else if (parted)
        c_snprintf(text, sizeof text,
                   "narrower than the kerf (%g mm) near (%.1f, %.1f): the cut would leave it in "
                   "%zu parts",
                   kerf, narrow->where.x, narrow->where.y, narrow->parts);
    else
        c_snprintf(text, sizeof text,
                   "%.2f mm2 of it narrower than the kerf (%g mm) near (%.1f, %.1f): the cut "
                   "would burn that away",
                   narrow->largest, kerf, narrow->where.x, narrow->where.y);
    return record_warning(piece, kerf, 1, narrow->where, text, error);
}

/*
 * Every path's new ring (NULL: unchanged) into rings, counts; *holes how
 * many holes moved; found what could not be done as asked; *narrow (when
 * *measured) what of the outline as drawn is narrower than the kerf.
 */
static ur_status offset_all(const ur_piece *piece, double kerf, ur_vec2 **rings, size_t *counts,
                            size_t *holes, kerf_findings *found, narrow_material *narrow,
                            bool *measured, ur_error *error)
{
    GEOSContextHandle_t geos = GEOS_init_r();
    GEOSBufferParams *params = geos ? GEOSBufferParams_create_r(geos) : NULL;
    if (!params) {
        if (geos)
            GEOS_finish_r(geos);
        return ur_error_out_of_memory(error);
    }
    GEOSBufferParams_setJoinStyle_r(geos, params, GEOSBUF_JOIN_MITRE);
    GEOSBufferParams_setMitreLimit_r(geos, params, KERF_MITRE_LIMIT);
    ur_status status = UR_OK;
    *holes = 0;
    *measured = measure_narrow(geos, &piece->paths[0], kerf, narrow);
    for (size_t i = 0; status == UR_OK && i < piece->path_count; i++) {
        if (i > 0 && !is_hole(&piece->paths[i]))
            continue;
        double distance = i == 0 ? kerf / 2 : -kerf / 2;
        bool round = piece->paths[i].circle.radius > 0;
        status = round ? offset_circle(piece, i, distance, &rings[i], &counts[i], found, error)
                       : offset_ring(geos, params, piece, i, distance, &rings[i], &counts[i], found,
                                     error);
        if (status != UR_OK || !rings[i])
            continue; /* a hole cut as drawn */
        if (i > 0)
            (*holes)++;
        /* Holes keep the direction they had (a circle's points keep their order). */
        if (i > 0 && !round &&
            ur_polygon_signed_area(piece->paths[i].points, piece->paths[i].count) < 0)
            ur_points_reverse(rings[i], counts[i]);
    }
    GEOSBufferParams_destroy_r(geos, params);
    GEOS_finish_r(geos);
    return status;
}

static ur_status record_findings(ur_piece *piece, double kerf, const kerf_findings *found,
                                 ur_error *error)
{
    char text[sizeof((ur_allowance_record *)NULL)->reason];
    ur_status status = UR_OK;
    if (found->room_count > 0) {
        size_t n = found->room_count;
        c_snprintf(text, sizeof text,
                   "%zu slot%s of the outline with a mouth narrower than the kerf (%g mm), near "
                   "(%.1f, %.1f): the room behind %s cut as a hole, and the mouth, which the "
                   "cutter cannot cut, holds %s sides together: part %s by hand",
                   n, n == 1 ? "" : "s", kerf, found->room_at.x, found->room_at.y,
                   n == 1 ? "it is" : "each is", n == 1 ? "its" : "their", n == 1 ? "it" : "them");
        status = record_warning(piece, kerf, n, found->room_at, text, error);
    }
    if (status == UR_OK && found->slots > 0) {
        size_t n = found->slots;
        c_snprintf(text, sizeof text,
                   "%zu slot%s of the outline narrower than the kerf (%g mm), near (%.1f, %.1f), "
                   "closed as the outline moved out: filled, as the cutter could not cut %s",
                   n, n == 1 ? "" : "s", kerf, found->slot_at.x, found->slot_at.y,
                   n == 1 ? "it" : "them");
        status = record_warning(piece, kerf, n, found->slot_at, text, error);
    }
    if (status == UR_OK && found->narrow_holes > 0) {
        size_t n = found->narrow_holes;
        c_snprintf(text, sizeof text,
                   "%zu hole%s with a part narrower than the kerf (%g mm), near (%.1f, %.1f), "
                   "which moved in would vanish or split: cut as drawn, %s out %g mm wider all "
                   "round",
                   n, n == 1 ? "" : "s", kerf, found->narrow_hole_at.x, found->narrow_hole_at.y,
                   n == 1 ? "it comes" : "they come", kerf / 2);
        status = record_warning(piece, kerf, n, found->narrow_hole_at, text, error);
    }
    return status;
}

static ur_status record(ur_piece *piece, double kerf, size_t holes, const kerf_findings *found,
                        ur_error *error)
{
    ur_allowance_record entry = {
        .kind = UR_ALLOWANCE_KERF_COMPENSATION, .count = 1 + holes, .value = kerf, .limit = NAN};
    entry.where = ur_vec2_make((piece->box.min.x + piece->box.max.x) / 2,
                               (piece->box.min.y + piece->box.max.y) / 2);
    ur_status status = record_findings(piece, kerf, found, error);
    if (status != UR_OK)
        return status;
    if (holes == 0)
        c_snprintf(entry.reason, sizeof entry.reason,
                   "outline offset outward by half the kerf, %g mm", kerf / 2);
    else
        c_snprintf(entry.reason, sizeof entry.reason,
                   "outline offset outward and %zu hole%s inward by half the kerf, %g mm", holes,
                   holes == 1 ? "" : "s", kerf / 2);
    return ur_piece_record(piece, &entry, error);
}

/* Grows the piece's array of paths by `more`, so that adding them cannot fail. */
static ur_status make_room_for_paths(ur_piece *piece, size_t more, ur_error *error)
{
    ur_path *grown = realloc(piece->paths, (piece->path_count + more) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    piece->paths = grown;
    return UR_OK;
}

ur_status ur_piece_compensate_kerf(ur_piece *piece, double kerf, ur_error *error)
{
    if (!isfinite(kerf) || kerf < 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece %s: the kerf must be a width of 0 mm or more, not %g",
                            piece->name, kerf);
    if (kerf == 0)
        return UR_OK;
    if (piece->path_count == 0 || !piece->paths[0].closed || piece->bridged ||
        piece->paths[0].count < 3)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece %s has no closed outline to compensate for the kerf "
                            "(compensate before adding bridges)",
                            piece->name);
    ur_vec2 **rings = calloc(piece->path_count, sizeof *rings);
    size_t *counts = calloc(piece->path_count, sizeof *counts);
    size_t holes = 0;
    kerf_findings found = {0};
    narrow_material narrow = {0};
    bool measured = false;
    ur_status status = rings && counts ? offset_all(piece, kerf, rings, counts, &holes, &found,
                                                    &narrow, &measured, error)
                                       : ur_error_out_of_memory(error);
    if (status == UR_OK && found.room_count > 0) /* room for the slots' holes, before any change */
        status = make_room_for_paths(piece, found.room_count, error);
    for (size_t i = 0; status == UR_OK && i < piece->path_count; i++)
        if (rings[i]) {
            free(piece->paths[i].points);
            piece->paths[i].points = rings[i];
            piece->paths[i].count = counts[i];
            rings[i] = NULL;
            if (piece->paths[i].circle.radius > 0) /* out for the outline, in for a hole */
                piece->paths[i].circle.radius += i == 0 ? kerf / 2 : -kerf / 2;
        }
    for (size_t i = 0; rings && i < piece->path_count; i++)
        free(rings[i]);
    free(rings);
    free(counts);
    for (size_t i = 0; status == UR_OK && i < found.room_count; i++) {
        piece->paths[piece->path_count++] = found.rooms[i]; /* the piece owns its points now */
        found.rooms[i].points = NULL;
    }
    findings_free(&found);
    if (status != UR_OK)
        return status;
    ur_piece_recompute_box(piece);
    piece->kerf_compensated += kerf;
    status = measured ? record_narrow(piece, kerf, &narrow, error) : UR_OK;
    return status == UR_OK ? record(piece, kerf, holes, &found, error) : status;
}
