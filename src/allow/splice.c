/*
 * splice.c: splice pieces.  Where no glue tab or lap fits on either side of
 * a seam (the outline folds back too close to it, as where two turns of a
 * helicoid come near each other), the seam is joined from behind: a
 * separate strip, `width` mm on each side of the seam, is glued under both
 * pieces across it.  For paper and board it is a splice strip, for wood a
 * butt strap; a maker knows both.  The strip is the seam's run (as one
 * piece's outline has it) buffered by the width with flat ends, so it
 * follows a curved seam too; the seam is a MARK line along its middle, and
 * each half is engraved with the name of the piece that goes on it and the
 * seam's label ("P1 A1" and "P2 A1"), so that it cannot go on the wrong
 * way round.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

/* GEOS rounds nothing here (flat ends, mitred corners); this only bounds its work. */
enum { QUADRANT_SEGMENTS = 8 };

/* The strip's outline: the seam buffered by width, flat at both ends. */
static ur_status strip_ring(const ur_vec2 *seam, size_t count, double width, ur_vec2 **ring,
                            size_t *ring_count, ur_error *error)
{
    GEOSContextHandle_t geos = GEOS_init_r();
    if (!geos)
        return ur_error_out_of_memory(error);
    GEOSGeometry *line = allow_line(geos, seam, count);
    GEOSGeometry *strip = line ? GEOSBufferWithStyle_r(geos, line, width, QUADRANT_SEGMENTS,
                                                       GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_MITRE, 5.0)
                               : NULL;
    ur_status status =
        strip && GEOSGeomTypeId_r(geos, strip) == GEOS_POLYGON
            ? allow_exterior_ring(geos, strip, ring, ring_count, error)
            : ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not draw a splice strip");
    if (strip)
        GEOSGeom_destroy_r(geos, strip);
    if (line)
        GEOSGeom_destroy_r(geos, line);
    GEOS_finish_r(geos);
    return status;
}

/* The point half way along the polyline and the direction of its segment there. */
static void middle_of(const ur_vec2 *points, size_t count, ur_vec2 *middle, ur_vec2 *along)
{
    double half = 0.5 * ur_polyline_length(points, count, false), walked = 0;
    *middle = points[0];
    *along = ur_vec2_sub(points[count - 1], points[0]);
    for (size_t k = 0; k + 1 < count; k++) {
        double length = ur_vec2_distance(points[k], points[k + 1]);
        if (walked + length >= half && length > 0) {
            *along = ur_vec2_sub(points[k + 1], points[k]);
            *middle = ur_vec2_lerp(points[k], points[k + 1], (half - walked) / length);
            return;
        }
        walked += length;
    }
}

/* "P1 A1" on the half of the strip on `side` (+1 right of the seam, -1 left). */
static ur_status label_half(ur_piece *piece, const ur_splice_request *request, const char *name,
                            double side, ur_error *error)
{
    if (!request->font)
        return UR_OK;
    ur_vec2 middle, along;
    middle_of(request->seam, request->count, &middle, &along);
    double length = ur_vec2_length(along);
    ur_vec2 right =
        length > 0 ? ur_vec2_make(along.y / length, -along.x / length) : ur_vec2_make(0, -1);
    char text[80];
    c_snprintf(text, sizeof text, "%s %s", name, request->label);
    double height = fmin(request->label_height, 0.6 * request->width);
    bool placed = false;
    ur_status status = ur_piece_add_label(
        piece, request->font, text, ur_vec2_add_scaled(middle, right, side * 0.5 * request->width),
        length > 0 ? along : ur_vec2_make(1, 0), height, 0.4 * height, 0.1 * height, &placed,
        error);
    if (status != UR_OK || placed)
        return status;
    ur_allowance_record warning = {
        .kind = UR_ALLOWANCE_LABEL, .value = NAN, .limit = NAN, .where = middle, .warning = true};
    c_snprintf(warning.reason, sizeof warning.reason, "no room for label %s on the splice", text);
    return ur_piece_record(piece, &warning, error);
}

static ur_status check_request(const ur_splice_request *r, ur_error *error)
{
    if (!r->seam || r->count < 2 || !(r->width > 0) || !isfinite(r->width) ||
        (r->font && !(r->label_height > 0)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "a splice piece needs a seam of 2 points or more, a positive width "
                            "and a positive label height");
    if (!(ur_polyline_length(r->seam, r->count, false) > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "a splice piece needs a seam of some length");
    return UR_OK;
}

ur_status ur_splice_piece(const ur_splice_request *request, ur_piece *piece, ur_error *error)
{
    memset(piece, 0, sizeof *piece);
    ur_status status = check_request(request, error);
    if (status != UR_OK)
        return status;
    c_snprintf(piece->name, sizeof piece->name, "%s", request->name);
    ur_vec2 *ring = NULL;
    size_t ring_count = 0;
    status = strip_ring(request->seam, request->count, request->width, &ring, &ring_count, error);
    if (status == UR_OK)
        status = ur_piece_add_path(piece, UR_OP_CUT, ring, ring_count, true, error);
    free(ring);
    if (status == UR_OK)
        status = ur_piece_add_path(piece, UR_OP_MARK, request->seam, request->count, false, error);
    /* The run follows piece a's outline counter-clockwise: piece a lies on its left. */
    if (status == UR_OK)
        status = label_half(piece, request, request->piece_a, -1.0, error);
    if (status == UR_OK)
        status = label_half(piece, request, request->piece_b, 1.0, error);
    if (status == UR_OK) {
        ur_allowance_record entry = {.kind = UR_ALLOWANCE_JOINT,
                                     .count = 1,
                                     .value = NAN,
                                     .limit = NAN,
                                     .where = piece->paths[1].points[0]};
        c_snprintf(entry.reason, sizeof entry.reason,
                   "%s for seam %s, glued behind it under %s and %s, %g mm on each side",
                   request->strap ? "butt strap" : "splice strip", request->label, request->piece_a,
                   request->piece_b, request->width);
        status = ur_piece_record(piece, &entry, error);
    }
    if (status != UR_OK)
        ur_piece_free(piece);
    return status;
}

ur_status ur_splice_list_add(ur_splice_list *list, const ur_splice_request *request,
                             ur_error *error)
{
    ur_piece *grown = realloc(list->pieces, (list->count + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    list->pieces = grown;
    ur_status status = ur_splice_piece(request, &list->pieces[list->count], error);
    if (status == UR_OK)
        list->count++;
    return status;
}

void ur_splice_list_free(ur_splice_list *list)
{
    for (size_t k = 0; k < list->count; k++)
        ur_piece_free(&list->pieces[k]);
    free(list->pieces);
    list->pieces = NULL;
    list->count = 0;
}
