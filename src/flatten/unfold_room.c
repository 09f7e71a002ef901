/*
 * unfold_room.c: whether a piece fits the room a sheet leaves it: the
 * smallest rectangle round its convex hull, longer side along the room's
 * longer side, as nesting first turns a piece.  The smallest rectangle
 * round a convex polygon has a side on one of its edges (Freeman and
 * Shapira 1975), so each edge's direction is tried.
 */
#include "unfold_internal.h"

#include <stdlib.h>

static int compare_points(const void *a, const void *b)
{
    const ur_vec2 *p = a, *q = b;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    return (p->y > q->y) - (p->y < q->y);
}

static double turn(ur_vec2 o, ur_vec2 a, ur_vec2 b)
{
    return ur_vec2_cross(ur_vec2_sub(a, o), ur_vec2_sub(b, o));
}

/* Andrew's monotone chain. */
size_t unfold_hull(ur_vec2 *points, size_t count, ur_vec2 *chain, ur_vec2 *hull)
{
    if (count < 3) {
        for (size_t i = 0; i < count; i++)
            hull[i] = points[i];
        return count;
    }
    qsort(points, count, sizeof *points, compare_points);
    size_t k = 0;
    for (size_t i = 0; i < count; i++) {
        while (k >= 2 && turn(chain[k - 2], chain[k - 1], points[i]) <= 0)
            k--;
        chain[k++] = points[i];
    }
    for (size_t i = count - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && turn(chain[k - 2], chain[k - 1], points[i]) <= 0)
            k--;
        chain[k++] = points[i];
    }
    k--; /* the first point again */
    for (size_t i = 0; i < k; i++)
        hull[i] = chain[i];
    return k;
}

void unfold_hull_size(const ur_vec2 *hull, size_t count, double *length, double *width)
{
    double best_area = INFINITY;
    *length = *width = 0.0;
    for (size_t i = 0; i < count; i++) {
        ur_vec2 d = ur_vec2_sub(hull[(i + 1) % count], hull[i]);
        double norm = sqrt(ur_vec2_dot(d, d));
        if (!(norm > 0))
            continue;
        d = ur_vec2_scale(d, 1.0 / norm);
        double low = 0.0, high = 0.0, across = 0.0;
        /* The area only grows as points are added: stop once it is no better. */
        for (size_t j = 0; j < count && (high - low) * across < best_area; j++) {
            ur_vec2 p = ur_vec2_sub(hull[j], hull[i]);
            double along = ur_vec2_dot(p, d), side = fabs(ur_vec2_cross(d, p));
            low = along < low ? along : low;
            high = along > high ? along : high;
            across = side > across ? side : across;
        }
        if ((high - low) * across < best_area) {
            best_area = (high - low) * across;
            *length = high - low > across ? high - low : across;
            *width = high - low > across ? across : high - low;
        }
    }
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
    ur_box box = ur_box_of_points(hull, count);
    if (count > 0 && hypot(ur_box_width(box), ur_box_height(box)) <= room_width)
        return true;
    double length, width;
    unfold_hull_size(hull, count, &length, &width);
    return length <= room_length && width <= room_width;
}
