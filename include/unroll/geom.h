/*
 * unroll/geom.h: points, vectors, polylines, boxes and rigid transforms in the
 * plane and in space.  Small value types; everything here is inline or pure.
 */
#ifndef UNROLL_GEOM_H
#define UNROLL_GEOM_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

#include "unroll/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ur_vec2 {
    double x, y;
} ur_vec2;

typedef struct ur_vec3 {
    double x, y, z;
} ur_vec3;

static inline ur_vec3 ur_vec3_make(double x, double y, double z)
{
    ur_vec3 v = {x, y, z};
    return v;
}
static inline ur_vec3 ur_vec3_add(ur_vec3 a, ur_vec3 b)
{
    return ur_vec3_make(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline ur_vec3 ur_vec3_sub(ur_vec3 a, ur_vec3 b)
{
    return ur_vec3_make(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline ur_vec3 ur_vec3_scale(ur_vec3 a, double s)
{
    return ur_vec3_make(a.x * s, a.y * s, a.z * s);
}
/* a + s b */
static inline ur_vec3 ur_vec3_add_scaled(ur_vec3 a, ur_vec3 b, double s)
{
    return ur_vec3_make(a.x + s * b.x, a.y + s * b.y, a.z + s * b.z);
}
static inline double ur_vec3_dot(ur_vec3 a, ur_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline ur_vec3 ur_vec3_cross(ur_vec3 a, ur_vec3 b)
{
    return ur_vec3_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double ur_vec3_length(ur_vec3 a)
{
    return sqrt(ur_vec3_dot(a, a));
}
static inline double ur_vec3_distance(ur_vec3 a, ur_vec3 b)
{
    return ur_vec3_length(ur_vec3_sub(a, b));
}
/* The order of two points by x, then y, then z: -1, 0 or 1 (for sorting; 0 and -0 are one). */
static inline int ur_vec3_order(ur_vec3 a, ur_vec3 b)
{
    if (a.x != b.x)
        return a.x < b.x ? -1 : 1;
    if (a.y != b.y)
        return a.y < b.y ? -1 : 1;
    if (a.z != b.z)
        return a.z < b.z ? -1 : 1;
    return 0;
}
/* Triple product det(a, b, c). */
static inline double ur_vec3_det(ur_vec3 a, ur_vec3 b, ur_vec3 c)
{
    return ur_vec3_dot(a, ur_vec3_cross(b, c));
}

static inline ur_vec2 ur_vec2_make(double x, double y)
{
    ur_vec2 v = {x, y};
    return v;
}
static inline ur_vec2 ur_vec2_add(ur_vec2 a, ur_vec2 b)
{
    return ur_vec2_make(a.x + b.x, a.y + b.y);
}
static inline ur_vec2 ur_vec2_sub(ur_vec2 a, ur_vec2 b)
{
    return ur_vec2_make(a.x - b.x, a.y - b.y);
}
static inline ur_vec2 ur_vec2_scale(ur_vec2 a, double s)
{
    return ur_vec2_make(a.x * s, a.y * s);
}
static inline ur_vec2 ur_vec2_add_scaled(ur_vec2 a, ur_vec2 b, double s)
{
    return ur_vec2_make(a.x + s * b.x, a.y + s * b.y);
}
/* The point a fraction t of the way from a to b. */
static inline ur_vec2 ur_vec2_lerp(ur_vec2 a, ur_vec2 b, double t)
{
    return ur_vec2_make(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
}
static inline double ur_vec2_dot(ur_vec2 a, ur_vec2 b)
{
    return a.x * b.x + a.y * b.y;
}
/* z component of the cross product: > 0 when b turns left from a. */
static inline double ur_vec2_cross(ur_vec2 a, ur_vec2 b)
{
    return a.x * b.y - a.y * b.x;
}
static inline double ur_vec2_length(ur_vec2 a)
{
    return hypot(a.x, a.y);
}
static inline double ur_vec2_distance(ur_vec2 a, ur_vec2 b)
{
    return ur_vec2_length(ur_vec2_sub(a, b));
}

/* Signed area by the shoelace formula: > 0 for counter-clockwise rings. */
UR_API double ur_polygon_signed_area(const ur_vec2 *points, size_t count);

/* Reverses the order of the points in place (a ring then turns the other way). */
UR_API void ur_points_reverse(ur_vec2 *points, size_t count);

/* Length of a polyline; closed adds the edge from the last point to the first. */
UR_API double ur_polyline_length(const ur_vec2 *points, size_t count, bool closed);

/* An axis-aligned box.  An empty box has min > max. */
typedef struct ur_box {
    ur_vec2 min, max;
} ur_box;

UR_API ur_box ur_box_empty(void);
UR_API void ur_box_add(ur_box *box, ur_vec2 point);
UR_API ur_box ur_box_of_points(const ur_vec2 *points, size_t count);
static inline double ur_box_width(ur_box box)
{
    return box.max.x - box.min.x;
}
static inline double ur_box_height(ur_box box)
{
    return box.max.y - box.min.y;
}

/* A rigid motion of the plane: rotate by angle about the origin, then translate. */
typedef struct ur_transform2 {
    double cosine, sine;
    ur_vec2 translation;
} ur_transform2;

UR_API ur_transform2 ur_transform2_identity(void);
UR_API ur_transform2 ur_transform2_make(double angle, ur_vec2 translation);
UR_API ur_vec2 ur_transform2_apply(ur_transform2 transform, ur_vec2 point);

/* Distance between the 3D segments p0p1 and q0q1. */
UR_API double ur_segment_distance(ur_vec3 p0, ur_vec3 p1, ur_vec3 q0, ur_vec3 q1);

/*
 * Whether the polylines a and b come within tolerance of each other
 * anywhere (they meet or cross); *where is then the first segment of a that
 * does.
 */
UR_API ur_status ur_polylines_meet(const ur_vec3 *a, size_t a_count, const ur_vec3 *b,
                                   size_t b_count, double tolerance, bool *meet, size_t *where,
                                   ur_error *error);

/* A growable array of plane points; the owner frees it with ur_points_free. */
typedef struct ur_points {
    ur_vec2 *items;
    size_t count, capacity;
} ur_points;

UR_API ur_status ur_points_push(ur_points *points, ur_vec2 point, ur_error *error);
UR_API void ur_points_free(ur_points *points);

#ifdef __cplusplus
}
#endif

#endif
