/*
 * unfold_room.c: whether a piece fits the room a sheet leaves it: the
 * smallest rectangle round its convex hull, longer side along the room's
 * longer side, as nesting first turns a piece (src/geom/hull.c).
 */
#include "unfold_internal.h"

#include "../geom/hull.h"

#include <math.h>

size_t unfold_hull(ur_vec2 *points, size_t count, ur_vec2 *chain, ur_vec2 *hull)
{
    size_t k = geom_convex_hull(points, count, chain);
    for (size_t i = 0; i < k; i++)
        hull[i] = chain[i];
    return k;
}

void unfold_hull_size(const ur_vec2 *hull, size_t count, double *length, double *width)
{
    geom_least_area_box(hull, count, length, width);
}

bool unfold_hull_fits(const unfolder *u, const ur_vec2 *hull, size_t count)
{
    if (!u->room)
        return true;
    double room_length = fmax(u->options.room_length, u->options.room_width);
    double room_width = fmin(u->options.room_length, u->options.room_width);
    /*
     * A hull whose box's diagonal is within the room's width fits in any
     * direction (most joins of small pieces): no rectangle to look for.
     */
    ur_box box = unfold_box_of(hull, count);
    if (count > 0 && unfold_hypot_within(ur_box_width(box), ur_box_height(box), room_width))
        return true;
    /*
     * Nor is the rectangle needed when the box shows it fits (most of the
     * other joins): its longer side is the hull's extent in some
     * direction, at most the box's diagonal, and its shorter side squared
     * is at most its area, at most the box's.  Kept a hair inside the room,
     * so that rounding cannot make the rectangle say otherwise.
     */
    double box_area = ur_box_width(box) * ur_box_height(box);
    if (count > 0 &&
        unfold_hypot_within(ur_box_width(box), ur_box_height(box), room_length * (1 - 1e-9)) &&
        box_area < room_width * room_width * (1 - 1e-9))
        return true;
    double length, width;
    unfold_hull_size(hull, count, &length, &width);
    return length <= room_length && width <= room_width;
}
