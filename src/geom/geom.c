/*
 * geom.c: polygon measures, boxes, rigid transforms and growable point arrays.
 */
#include "unroll/geom.h"

#include <stdlib.h>

double ur_polygon_signed_area(const ur_vec2 *points, size_t count)
{
    double twice_area = 0.0;
    for (size_t i = 0; i < count; i++) {
        ur_vec2 p = points[i];
        ur_vec2 q = points[(i + 1) % count];
        twice_area += ur_vec2_cross(p, q);
    }
    return 0.5 * twice_area;
}

void ur_points_reverse(ur_vec2 *points, size_t count)
{
    for (size_t i = 0, j = count ? count - 1 : 0; i < j; i++, j--) {
        ur_vec2 swap = points[i];
        points[i] = points[j];
        points[j] = swap;
    }
}

double ur_polyline_length(const ur_vec2 *points, size_t count, bool closed)
{
    double length = 0.0;
    for (size_t i = 0; i + 1 < count; i++)
        length += ur_vec2_distance(points[i], points[i + 1]);
    if (closed && count > 1)
        length += ur_vec2_distance(points[count - 1], points[0]);
    return length;
}

ur_box ur_box_empty(void)
{
    ur_box box = {{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
    return box;
}

void ur_box_add(ur_box *box, ur_vec2 point)
{
    box->min.x = fmin(box->min.x, point.x);
    box->min.y = fmin(box->min.y, point.y);
    box->max.x = fmax(box->max.x, point.x);
    box->max.y = fmax(box->max.y, point.y);
}

ur_box ur_box_of_points(const ur_vec2 *points, size_t count)
{
    ur_box box = ur_box_empty();
    for (size_t i = 0; i < count; i++)
        ur_box_add(&box, points[i]);
    return box;
}

ur_transform2 ur_transform2_identity(void)
{
    ur_transform2 transform = {1.0, 0.0, {0.0, 0.0}};
    return transform;
}

ur_transform2 ur_transform2_make(double angle, ur_vec2 translation)
{
    ur_transform2 transform = {cos(angle), sin(angle), translation};
    return transform;
}

ur_vec2 ur_transform2_apply(ur_transform2 t, ur_vec2 p)
{
    return ur_vec2_make(t.cosine * p.x - t.sine * p.y + t.translation.x,
                        t.sine * p.x + t.cosine * p.y + t.translation.y);
}

ur_status ur_points_push(ur_points *points, ur_vec2 point, ur_error *error)
{
    ur_vec2 *items = ur_array_grow(points->items, &points->capacity, points->count,
                                   sizeof *points->items, 64, error);
    if (!items)
        return UR_ERROR_MEMORY;
    points->items = items;
    points->items[points->count++] = point;
    return UR_OK;
}

void ur_points_free(ur_points *points)
{
    free(points->items);
    points->items = NULL;
    points->count = points->capacity = 0;
}
