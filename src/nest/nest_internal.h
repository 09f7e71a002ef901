/*
 * nest_internal.h: what the placement files share (layout.c: shelves,
 * nfp.c: no-fit polygons, nest.c: true-shape nesting).
 */
#ifndef UNROLL_NEST_INTERNAL_H
#define UNROLL_NEST_INTERNAL_H

#include <geos_c.h>

#include "unroll/nest.h"

/* The angle that turns the piece's smallest enclosing rectangle level (layout.c). */
double nest_level_angle(GEOSContextHandle_t geos, const ur_path *outline);

/*
 * A piece as nesting sees it, turned by one of its allowed angles about its
 * own origin: its polygon (outline and, with holes, its holes) grown by
 * half the spacing and by the simplification's tolerance, the convex parts
 * that polygon splits into, and the box of the actual (ungrown) outline.
 */
typedef struct nest_shape {
    GEOSGeometry *polygon;
    GEOSGeometry **convex; /* owned parts */
    size_t convex_count;
    ur_box box; /* of the turned outline itself */
    double angle;
    double area; /* of the piece itself (outline less holes) */
} nest_shape;

ur_status nest_shape_make(GEOSContextHandle_t geos, const ur_piece *piece, double angle,
                          double grow, bool holes, nest_shape *shape, ur_error *error);
void nest_shape_free(GEOSContextHandle_t geos, nest_shape *shape);

/*
 * The no-fit polygon of moving shape b around fixed shape a, both at their
 * origins: where b's origin may not go (a + (-b), the union of the convex
 * parts' sums).  NULL when GEOS fails.
 */
GEOSGeometry *nest_nfp(GEOSContextHandle_t geos, const nest_shape *a, const nest_shape *b);

#endif
