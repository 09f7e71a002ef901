/*
 * slits.c: an outline that reaches a hole through a slit of no width, as
 * the unfolding leaves a flat ring of faces (a frame round a window): one
 * piece, cut open along an edge from its hole to its rim, both sides of the
 * cut lying on each other.  A cutter needs the rim and the hole, and the
 * slit closes up in the offsets and unions the allowances make of the
 * outline (GEOS reads it as a polygon with a hole); so the piece is cut as
 * its rim and its holes (allow_internal.h, allow_open_slits).
 */
#include "allow_internal.h"
#include "../geom/geos_polygon.h"

#include <math.h>
#include <stdlib.h>

/* Two points this close (a share of the outline's size) are one. */
#define SAME_POINT 1e-9

/* A point of a ring and its place in it, to sort by x. */
typedef struct ring_point {
    ur_vec2 at;
    size_t index;
} ring_point;

static int compare_x(const void *a, const void *b)
{
    const ring_point *p = a, *q = b;
    return (p->at.x > q->at.x) - (p->at.x < q->at.x);
}

/*
 * A copy of the ring (*snapped, the caller's to free) in which each point
 * that comes back within the tolerance is made equal to where it was
 * first: the ends of a slit come back, twice.  Laid flat two ways round a
 * hole, a slit's sides may end a rounding apart, and GEOS then keeps the
 * slit as a hole of no width, joining the holes at its ends into one cut
 * path that crosses itself (Cura's farm2 bed: its round hole and its slot,
 * 1e-14 mm apart).  *repeated says whether any point came back.
 */
static ur_status snapped_ring(const ur_vec2 *points, size_t count, double tolerance,
                              ur_vec2 **snapped, bool *repeated, ur_error *error)
{
    *repeated = false;
    *snapped = ur_alloc_array(count, sizeof **snapped, error);
    ring_point *sorted = ur_alloc_array(count, sizeof *sorted, error);
    bool *taken = ur_alloc_array(count, sizeof *taken, error);
    if (!*snapped || !sorted || !taken) {
        free(*snapped);
        *snapped = NULL;
        free(sorted);
        free(taken);
        return UR_ERROR_MEMORY;
    }
    for (size_t i = 0; i < count; i++) {
        (*snapped)[i] = points[i];
        sorted[i] = (ring_point){points[i], i};
        taken[i] = false;
    }
    qsort(sorted, count, sizeof *sorted, compare_x);
    for (size_t i = 0; i < count; i++)
        for (size_t j = i + 1;
             !taken[i] && j < count && sorted[j].at.x - sorted[i].at.x <= tolerance; j++)
            if (!taken[j] && ur_vec2_distance(sorted[i].at, sorted[j].at) <= tolerance) {
                (*snapped)[sorted[j].index] = sorted[i].at;
                taken[j] = *repeated = true;
            }
    free(sorted);
    free(taken);
    return UR_OK;
}

/* Interior ring k of a polygon as points (last not repeated); NULL on failure. */
static ur_vec2 *interior_ring(GEOSContextHandle_t geos, const GEOSGeometry *polygon, int k,
                              size_t *count)
{
    const GEOSGeometry *ring = GEOSGetInteriorRingN_r(geos, polygon, k);
    const GEOSCoordSequence *sequence = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size) || size < 4)
        return NULL;
    *count = size - 1;
    ur_vec2 *points = malloc(*count * sizeof *points);
    for (unsigned i = 0; points && i < size - 1; i++)
        GEOSCoordSeq_getXY_r(geos, sequence, i, &points[i].x, &points[i].y);
    return points;
}

/*
 * The piece's outline replaced by the polygon's rim, its holes added as cut
 * paths: those of more than `least` area.  A slit whose two sides lie a
 * rounding apart (the same corner laid flat two ways round the hole) comes
 * back from GEOS as a hole of its own with next to no area, which no cutter
 * can cut and kerf compensation would refuse as too narrow.
 */
static ur_status take_rim_and_holes(GEOSContextHandle_t geos, ur_piece *piece,
                                    const GEOSGeometry *polygon, double least, ur_error *error)
{
    ur_vec2 *rim;
    size_t rim_count;
    ur_status status = allow_exterior_ring(geos, polygon, &rim, &rim_count, error);
    if (status != UR_OK)
        return status;
    free(piece->paths[0].points);
    piece->paths[0].points = rim;
    piece->paths[0].count = rim_count;
    int holes = GEOSGetNumInteriorRings_r(geos, polygon);
    for (int k = 0; status == UR_OK && k < holes; k++) {
        size_t count = 0;
        ur_vec2 *hole = interior_ring(geos, polygon, k, &count);
        if (!hole)
            status = ur_error_out_of_memory(error);
        else if (fabs(ur_polygon_signed_area(hole, count)) > least)
            status = ur_piece_add_path(piece, UR_OP_CUT, hole, count, true, error);
        free(hole);
    }
    return status;
}

/*
 * The one polygon of what GEOS made valid: itself, or the only polygon of
 * more than `least` area of a collection whose other parts are lines (the
 * slit, collapsed), points or such slivers; NULL otherwise.
 */
static const GEOSGeometry *only_polygon(GEOSContextHandle_t geos, const GEOSGeometry *valid,
                                        double least)
{
    if (GEOSGeomTypeId_r(geos, valid) == GEOS_POLYGON)
        return valid;
    if (GEOSGeomTypeId_r(geos, valid) != GEOS_GEOMETRYCOLLECTION)
        return NULL;
    const GEOSGeometry *found = NULL;
    int count = GEOSGetNumGeometries_r(geos, valid);
    for (int k = 0; k < count; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(geos, valid, k);
        int type = GEOSGeomTypeId_r(geos, part);
        double area = 0;
        if (type == GEOS_POLYGON && GEOSArea_r(geos, part, &area) == 1 && area <= least)
            continue;
        if (type == GEOS_POLYGON || type == GEOS_MULTIPOLYGON) {
            if (found || type == GEOS_MULTIPOLYGON)
                return NULL;
            found = part;
        }
    }
    return found;
}

ur_status allow_open_slits(ur_piece *piece, ur_error *error)
{
    if (piece->path_count == 0 || !piece->paths[0].closed || piece->paths[0].count < 6)
        return UR_OK;
    const ur_path *outline = &piece->paths[0];
    double size = hypot(ur_box_width(piece->box), ur_box_height(piece->box));
    ur_vec2 *ring = NULL;
    bool repeated = false;
    ur_status status =
        snapped_ring(outline->points, outline->count, SAME_POINT * size, &ring, &repeated, error);
    if (status != UR_OK || !repeated) {
        free(ring);
        return status;
    }
    GEOSContextHandle_t geos = GEOS_init_r();
    if (!geos) {
        free(ring);
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not be started");
    }
    GEOSGeometry *drawn = geos_polygon_of_ring(geos, ring, outline->count);
    free(ring);
    GEOSGeometry *valid = drawn ? GEOSMakeValid_r(geos, drawn) : NULL;
    double area = fabs(ur_polygon_signed_area(outline->points, outline->count)), valid_area = 0;
    double least = 1e-9 * area; /* a sliver's, a rounding wide */
    const GEOSGeometry *polygon = valid ? only_polygon(geos, valid, least) : NULL;
    /* Only a slit: one polygon with holes, of the outline's own area (a slit has none). */
    if (polygon && GEOSGetNumInteriorRings_r(geos, polygon) > 0 &&
        GEOSArea_r(geos, polygon, &valid_area) && fabs(valid_area - area) <= 1e-6 * area)
        status = take_rim_and_holes(geos, piece, polygon, least, error);
    if (valid)
        GEOSGeom_destroy_r(geos, valid);
    if (drawn)
        GEOSGeom_destroy_r(geos, drawn);
    GEOS_finish_r(geos);
    return status;
}
