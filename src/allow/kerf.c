/*
 * kerf.c: kerf compensation.  The beam or bit removes a strip of material
 * as wide as the kerf centred on the path it follows, so a part cut along
 * its drawn outline comes out half a kerf too small all round and its holes
 * half a kerf too large.  Moving the outline out and the holes in by half
 * the kerf (GEOS buffer, mitred joins so square corners stay square) makes
 * the part come out at its drawn size.
 *
 * Everything is worked out before the piece is touched, so a refusal
 * (a hole that would vanish, a slot that would close) leaves it as it was.
 */
#include "allow_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

static void reverse(ur_vec2 *ring, size_t count)
{
    for (size_t i = 0, j = count - 1; i < j; i++, j--) {
        ur_vec2 swap = ring[i];
        ring[i] = ring[j];
        ring[j] = swap;
    }
}

/*
 * The ring of path offset by distance (> 0 outward, < 0 inward) into
 * *ring (counter-clockwise), or a refusal naming the piece when the result
 * is not one polygon without holes: a hole that vanishes or splits, an
 * outline whose slot closes into a hole.
 */
static ur_status offset_ring(GEOSContextHandle_t geos, const GEOSBufferParams *params,
                             const ur_piece *piece, size_t index, double distance, ur_vec2 **ring,
                             size_t *count, ur_error *error)
{
    const ur_path *path = &piece->paths[index];
    const char *what = index == 0 ? "its outline" : "a hole";
    GEOSGeometry *polygon = allow_polygon(geos, path->points, path->count);
    GEOSGeometry *buffered =
        polygon ? GEOSBufferWithParams_r(geos, polygon, params, distance) : NULL;
    ur_status status = UR_OK;
    if (!buffered)
        status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not offset %s of piece %s",
                              what, piece->name);
    else if (GEOSisEmpty_r(geos, buffered))
        status = ur_error_set(error, UR_ERROR_INPUT,
                              "piece %s: a hole is no wider than the kerf (%g mm) and would vanish",
                              piece->name, -2 * distance);
    else if (GEOSGeomTypeId_r(geos, buffered) != GEOS_POLYGON ||
             GEOSGetNumInteriorRings_r(geos, buffered) != 0)
        status = ur_error_set(error, UR_ERROR_INPUT,
                              "piece %s: %s has a part narrower than the kerf (%g mm) that would "
                              "%s",
                              piece->name, what, 2 * fabs(distance),
                              index == 0 ? "close into a hole" : "split it");
    else
        status = allow_exterior_ring(geos, buffered, ring, count, error);
    if (buffered)
        GEOSGeom_destroy_r(geos, buffered);
    if (polygon)
        GEOSGeom_destroy_r(geos, polygon);
    if (status == UR_OK)
        drop_straight_points(*ring, count);
    return status;
}

/* Every path's new ring (NULL: unchanged) into rings, counts; *holes how many holes moved. */
static ur_status offset_all(const ur_piece *piece, double kerf, ur_vec2 **rings, size_t *counts,
                            size_t *holes, ur_error *error)
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
    for (size_t i = 0; status == UR_OK && i < piece->path_count; i++) {
        if (i > 0 && !is_hole(&piece->paths[i]))
            continue;
        double distance = i == 0 ? kerf / 2 : -kerf / 2;
        status = offset_ring(geos, params, piece, i, distance, &rings[i], &counts[i], error);
        /* Holes keep the direction they had; the outline stays counter-clockwise. */
        if (status == UR_OK && i > 0) {
            (*holes)++;
            if (ur_polygon_signed_area(piece->paths[i].points, piece->paths[i].count) < 0)
                reverse(rings[i], counts[i]);
        }
    }
    GEOSBufferParams_destroy_r(geos, params);
    GEOS_finish_r(geos);
    return status;
}

static ur_status record(ur_piece *piece, double kerf, size_t holes, ur_error *error)
{
    ur_allowance_record entry = {
        .kind = UR_ALLOWANCE_KERF_COMPENSATION, .count = 1 + holes, .value = kerf, .limit = NAN};
    entry.where = ur_vec2_make((piece->box.min.x + piece->box.max.x) / 2,
                               (piece->box.min.y + piece->box.max.y) / 2);
    if (holes == 0)
        snprintf(entry.reason, sizeof entry.reason,
                 "outline offset outward by half the kerf, %g mm", kerf / 2);
    else
        snprintf(entry.reason, sizeof entry.reason,
                 "outline offset outward and %zu hole%s inward by half the kerf, %g mm", holes,
                 holes == 1 ? "" : "s", kerf / 2);
    return ur_piece_record(piece, &entry, error);
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
    ur_status status = rings && counts ? offset_all(piece, kerf, rings, counts, &holes, error)
                                       : ur_error_out_of_memory(error);
    for (size_t i = 0; status == UR_OK && i < piece->path_count; i++)
        if (rings[i]) {
            free(piece->paths[i].points);
            piece->paths[i].points = rings[i];
            piece->paths[i].count = counts[i];
            rings[i] = NULL;
        }
    for (size_t i = 0; rings && i < piece->path_count; i++)
        free(rings[i]);
    free(rings);
    free(counts);
    if (status != UR_OK)
        return status;
    ur_piece_recompute_box(piece);
    return record(piece, kerf, holes, error);
}
