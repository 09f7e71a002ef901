/*
 * geos_polygon.c: a ring of points as a GEOS polygon (geos_polygon.h).
 */
#include "geos_polygon.h"

GEOSGeometry *geos_polygon_of_ring(GEOSContextHandle_t geos, const ur_vec2 *ring, size_t count)
{
    if (count < 3)
        return NULL;
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)count + 1, 2);
    if (!sequence)
        return NULL;
    for (size_t i = 0; i <= count; i++)
        if (!GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, ring[i % count].x,
                                  ring[i % count].y)) {
            GEOSCoordSeq_destroy_r(geos, sequence);
            return NULL;
        }
    GEOSGeometry *shell = GEOSGeom_createLinearRing_r(geos, sequence);
    if (!shell)
        return NULL;
    GEOSGeometry *polygon = GEOSGeom_createPolygon_r(geos, shell, NULL, 0);
    if (!polygon)
        GEOSGeom_destroy_r(geos, shell);
    return polygon;
}
