/*
 * points.h: telling apart the points of a list by their coordinates,
 * shared inside the library by the mesh reader (a quad's neighbours) and
 * the assembly guide (the pieces' edges).  Not a public header.
 */
#ifndef UNROLL_POINTS_H
#define UNROLL_POINTS_H

#include <stddef.h>

#include "unroll/base.h"
#include "unroll/geom.h"

/*
 * Numbers the points: numbers[i] == numbers[j] exactly where points i and j
 * are the same point (ur_vec3_order), from 0 in that order.  O(n log n).
 */
ur_status geom_number_points(const ur_vec3 *points, size_t count, size_t *numbers, ur_error *error);

#endif
