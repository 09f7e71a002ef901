/*
 * allow_internal.h: what the allowance files share: moving rings of points
 * in and out of GEOS (reentrant API; the caller owns the context).
 */
#ifndef UNROLL_ALLOW_INTERNAL_H
#define UNROLL_ALLOW_INTERNAL_H

#include <geos_c.h>

#include "../geom/geos_polygon.h"
#include "unroll/allow.h"

/* An open line string through the points (at least 2), or NULL. */
GEOSGeometry *allow_line(GEOSContextHandle_t geos, const ur_vec2 *points, size_t count);

/*
 * The exterior ring of a polygon as points, counter-clockwise, first point
 * not repeated; the caller frees *ring.  Fails (UR_ERROR_INTERNAL) on
 * anything but a polygon with a ring of 3 points or more.
 */
ur_status allow_exterior_ring(GEOSContextHandle_t geos, const GEOSGeometry *polygon, ur_vec2 **ring,
                              size_t *count, ur_error *error);

/*
 * The region at least margin (> 0) inside a ring: the ring simplified to
 * within a hundredth of margin (at most 5 micrometres) and buffered inward
 * by margin plus that tolerance, so nothing of it comes nearer than margin
 * to the true ring.  Simplifying first keeps GEOS's inward buffer fast on
 * outlines of hundreds of thousands of points.  NULL when GEOS fails; may
 * be empty.
 */
GEOSGeometry *allow_inside(GEOSContextHandle_t geos, const ur_vec2 *ring, size_t count,
                           double margin, int quadrant_segments);

/* Area of a GEOS geometry (0 when GEOS fails). */
double allow_area(GEOSContextHandle_t geos, const GEOSGeometry *geometry);

#endif
