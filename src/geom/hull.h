/*
 * hull.h: the convex hull of points and the smallest rectangle round it,
 * shared inside the library by the unfolder (does a piece fit the room),
 * the nester (convex sums, the level turn).  Not a public header.
 */
#ifndef UNROLL_HULL_H
#define UNROLL_HULL_H

#include <stdbool.h>
#include <stddef.h>

#include "unroll/geom.h"

/*
 * The convex hull of points (sorted in place), counter-clockwise, without
 * collinear points and without the first point repeated, into hull (room
 * for count + 1, not points itself); its count.  Fewer than 3 points are
 * copied as they are.
 */
size_t geom_convex_hull(ur_vec2 *points, size_t count, ur_vec2 *hull);

/*
 * The same for two convex polygons, counter-clockwise (as geom_convex_hull
 * gives them), in points one after the other (first, then second points;
 * overwritten), in linear time: each polygon's points come sorted by
 * walking it, and are merged.  work: room for first + second points.
 */
size_t geom_convex_hull_of_two(ur_vec2 *points, size_t first, size_t second, ur_vec2 *work,
                               ur_vec2 *hull);

/*
 * The least-area rectangle round a convex polygon (hull, counter-clockwise):
 * its longer side in *length, the other in *width; returns the angle of
 * its longer side (radians).  0 and 0 x 0 for fewer than 2 distinct points.
 */
double geom_least_area_box(const ur_vec2 *hull, size_t count, double *length, double *width);

/*
 * Whether the convex polygon (hull) fits a length x width rectangle at
 * some turn, not only with its least-area rectangle's sides along the
 * rectangle's (a long net with wings at either end fits a sheet
 * diagonally): *angle gets the angle of a direction along which its
 * extent is at most length while across it it is at most width.
 */
bool geom_hull_fit_angle(const ur_vec2 *hull, size_t count, double length, double width,
                         double *angle);

#endif
