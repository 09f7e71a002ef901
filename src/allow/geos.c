/*
 * geos.c: lines to GEOS and polygons back to rings of points, for the
 * allowance files (allow_internal.h); rings to polygons are geos_polygon_of_ring.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdlib.h>

/* An open line string through the points (at least 2), or NULL. */
GEOSGeometry *allow_line(GEOSContextHandle_t geos, const ur_vec2 *points, size_t count)
{
    if (count < 2)
        return NULL;
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)count, 2);
    if (!sequence)
        return NULL;
    for (size_t i = 0; i < count; i++)
        if (!GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, points[i].x, points[i].y)) {
            GEOSCoordSeq_destroy_r(geos, sequence);
            return NULL;
        }
    return GEOSGeom_createLineString_r(geos, sequence);
}

ur_status allow_ring_points(GEOSContextHandle_t geos, const GEOSGeometry *ring, ur_vec2 **points,
                            size_t *count, ur_error *error)
{
    *points = NULL;
    *count = 0;
    const GEOSCoordSequence *sequence = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size) || size < 4)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS gave a polygon without a ring");
    size_t n = size - 1; /* GEOS repeats the first point at the end */
    ur_vec2 *read = ur_alloc_array(n, sizeof *read, error);
    if (!read)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < n; i++)
        GEOSCoordSeq_getXY_r(geos, sequence, (unsigned)i, &read[i].x, &read[i].y);
    if (ur_polygon_signed_area(read, n) < 0)
        ur_points_reverse(read, n);
    *points = read;
    *count = n;
    return UR_OK;
}

ur_status allow_exterior_ring(GEOSContextHandle_t geos, const GEOSGeometry *polygon, ur_vec2 **ring,
                              size_t *count, ur_error *error)
{
    *ring = NULL;
    *count = 0;
    int type = GEOSGeomTypeId_r(geos, polygon);
    if (type != GEOS_POLYGON)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS gave a %s where a polygon was due",
                            type >= 0 ? "other geometry" : "nothing");
    return allow_ring_points(geos, GEOSGetExteriorRing_r(geos, polygon), ring, count, error);
}

GEOSGeometry *allow_inside(GEOSContextHandle_t geos, const ur_vec2 *ring, size_t count,
                           double margin, int quadrant_segments)
{
    double tolerance = fmin(5e-3, margin / 100);
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, ring, count);
    GEOSGeometry *simple =
        polygon ? GEOSTopologyPreserveSimplify_r(geos, polygon, tolerance) : NULL;
    GEOSGeometry *inside =
        simple ? GEOSBuffer_r(geos, simple, -(margin + tolerance), quadrant_segments) : NULL;
    if (simple)
        GEOSGeom_destroy_r(geos, simple);
    if (polygon)
        GEOSGeom_destroy_r(geos, polygon);
    return inside;
}

double allow_area(GEOSContextHandle_t geos, const GEOSGeometry *geometry)
{
    double area = 0.0;
    if (!geometry || !GEOSArea_r(geos, geometry, &area))
        return 0.0;
    return area;
}

ur_box allow_box(GEOSContextHandle_t geos, const GEOSGeometry *geometry)
{
    ur_box box = ur_box_empty();
    double x0, y0, x1, y1;
    if (geometry && !GEOSisEmpty_r(geos, geometry) && GEOSGeom_getXMin_r(geos, geometry, &x0) &&
        GEOSGeom_getYMin_r(geos, geometry, &y0) && GEOSGeom_getXMax_r(geos, geometry, &x1) &&
        GEOSGeom_getYMax_r(geos, geometry, &y1)) {
        ur_box_add(&box, ur_vec2_make(x0, y0));
        ur_box_add(&box, ur_vec2_make(x1, y1));
    }
    return box;
}
