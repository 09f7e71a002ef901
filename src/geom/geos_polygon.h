/*
 * geos_polygon.h: a ring of points as a GEOS polygon, shared inside the
 * library by the modules that hand outlines to GEOS (reentrant API; the
 * caller owns the context).  Not part of the public headers, so that they
 * stay free of GEOS types.
 */
#ifndef UNROLL_GEOS_POLYGON_H
#define UNROLL_GEOS_POLYGON_H

#include <geos_c.h>

#include "unroll/geom.h"

/* A polygon from a ring (first point not repeated, at least 3 points), or NULL. */
GEOSGeometry *geos_polygon_of_ring(GEOSContextHandle_t geos, const ur_vec2 *ring, size_t count);

#endif
