/*
 * hull.c: the convex hull of points (Andrew's monotone chain) and the
 * least-area rectangle round a convex polygon.  That rectangle has a side
 * on one of the polygon's edges (Freeman and Shapira 1975), so each edge's
 * direction is tried.
 */
#include "hull.h"

#include <math.h>
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

size_t geom_convex_hull(ur_vec2 *points, size_t count, ur_vec2 *hull)
{
    if (count < 3) {
        for (size_t i = 0; i < count; i++)
            hull[i] = points[i];
        return count;
    }
    qsort(points, count, sizeof *points, compare_points);
    size_t k = 0;
    for (size_t i = 0; i < count; i++) {
        while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0)
            k--;
        hull[k++] = points[i];
    }
    for (size_t i = count - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0)
            k--;
        hull[k++] = points[i];
    }
    return k - 1; /* the first point came again */
}

double geom_least_area_box(const ur_vec2 *hull, size_t count, double *length, double *width)
{
    double best_area = INFINITY, angle = 0.0;
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
            angle = atan2(d.y, d.x) + (high - low >= across ? 0.0 : M_PI / 2);
        }
    }
    return angle;
}
