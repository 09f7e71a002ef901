/*
 * unfold_room.c: whether a piece fits the room a sheet leaves it: the
 * smallest rectangle round its convex hull, longer side along the room's
 * longer side, as nesting first turns a piece, or (u->turned_room) its
 * hull at any turn, as nesting turns a piece that fits only so
 * (src/geom/hull.c).
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
    if (u->turned_room) /* nesting turns a piece that fits only between level and on end so */
        return unfold_hull_fits_turned(u, hull, count);
    double length, width;
    unfold_hull_size(hull, count, &length, &width);
    return length <= room_length && width <= room_width;
}

bool unfold_hull_fits_turned(const unfolder *u, const ur_vec2 *hull, size_t count)
{
    double angle;
    return geom_hull_fit_angle(hull, count, fmax(u->options.room_length, u->options.room_width),
                               fmin(u->options.room_length, u->options.room_width), &angle);
}

/*
 * The circles only ever grow by rounding's worth (eps) more than they
 * must, so that they hold their pieces for sure; a piece grown from many
 * joins has a circle a few hundredths of a millimetre too large, which
 * only sends a join to its hull a little sooner.
 */
/* As ur_vec2_distance, without hypot's care, which rounding's eps makes up for. */
static double distance(ur_vec2 a, ur_vec2 b)
{
    ur_vec2 d = ur_vec2_sub(a, b);
    return sqrt(ur_vec2_dot(d, d));
}

unfold_circle unfold_circle_round(const unfolder *u, const ur_vec2 *corners, size_t count)
{
    ur_vec2 center = ur_vec2_make(0, 0);
    for (size_t i = 0; i < count; i++)
        center = ur_vec2_add(center, corners[i]);
    center = ur_vec2_scale(center, 1.0 / (double)count);
    double radius = 0;
    for (size_t i = 0; i < count; i++)
        radius = fmax(radius, distance(center, corners[i]));
    return (unfold_circle){center, radius + u->eps};
}

unfold_circle unfold_circle_join(const unfolder *u, unfold_circle a, unfold_circle b)
{
    double apart = distance(a.center, b.center);
    if (apart + b.radius <= a.radius)
        return a;
    if (apart + a.radius <= b.radius)
        return b;
    /* The circle through the far sides of both, on the line through their centres. */
    double radius = 0.5 * (apart + a.radius + b.radius);
    ur_vec2 toward_b = ur_vec2_scale(ur_vec2_sub(b.center, a.center), 1.0 / apart);
    return (unfold_circle){ur_vec2_add_scaled(a.center, toward_b, radius - a.radius),
                           radius + u->eps};
}

/*
 * The least-area rectangle's sides are the hull's extents in two
 * directions, neither more than the circle's diameter: within the room's
 * width, they fit either way round.
 */
bool unfold_circle_fits(const unfolder *u, unfold_circle circle)
{
    double room_width = fmin(u->options.room_length, u->options.room_width);
    return 2 * circle.radius < room_width * (1 - 1e-9);
}
