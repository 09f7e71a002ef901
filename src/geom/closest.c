/*
 * closest.c: whether two 3D polylines come within a distance of each other
 * (two rails that meet or cross), without comparing every pair of segments:
 * the second polyline's segments are sorted along its longest axis, and
 * each segment of the first is compared only with those that overlap it
 * along that axis.
 */
#include "unroll/geom.h"

#include <stdlib.h>

typedef struct sorted_segment {
    double low, high; /* extent along the sweep axis */
    size_t index;     /* segment index..index + 1 */
} sorted_segment;

static double along(ur_vec3 p, int axis)
{
    return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
}

static int compare_low(const void *a, const void *b)
{
    double x = ((const sorted_segment *)a)->low, y = ((const sorted_segment *)b)->low;
    return (x > y) - (x < y);
}

/* The axis along which the points spread furthest. */
static int longest_axis(const ur_vec3 *points, size_t count)
{
    double low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < count; i++)
        for (int k = 0; k < 3; k++) {
            low[k] = fmin(low[k], along(points[i], k));
            high[k] = fmax(high[k], along(points[i], k));
        }
    int best = 0;
    for (int k = 1; k < 3; k++)
        if (high[k] - low[k] > high[best] - low[best])
            best = k;
    return best;
}

static double clamp01(double t)
{
    return t < 0 ? 0 : t > 1 ? 1 : t;
}

/* Distance between segments p0p1 and q0q1 (the closest points, clamped to both). */
double ur_segment_distance(ur_vec3 p0, ur_vec3 p1, ur_vec3 q0, ur_vec3 q1)
{
    ur_vec3 d1 = ur_vec3_sub(p1, p0), d2 = ur_vec3_sub(q1, q0), r = ur_vec3_sub(p0, q0);
    double a = ur_vec3_dot(d1, d1), e = ur_vec3_dot(d2, d2), f = ur_vec3_dot(d2, r);
    double s, t;
    if (a <= 0 && e <= 0)
        return ur_vec3_length(r);
    if (a <= 0) {
        s = 0;
        t = clamp01(f / e);
    } else {
        double c = ur_vec3_dot(d1, r);
        if (e <= 0) {
            t = 0;
            s = clamp01(-c / a);
        } else {
            double b = ur_vec3_dot(d1, d2), denominator = a * e - b * b;
            s = denominator > 0 ? clamp01((b * f - c * e) / denominator) : 0;
            t = (b * s + f) / e;
            if (t < 0) {
                t = 0;
                s = clamp01(-c / a);
            } else if (t > 1) {
                t = 1;
                s = clamp01((b - c) / a);
            }
        }
    }
    ur_vec3 on_p = ur_vec3_add_scaled(p0, d1, s), on_q = ur_vec3_add_scaled(q0, d2, t);
    return ur_vec3_distance(on_p, on_q);
}

ur_status ur_polylines_meet(const ur_vec3 *a, size_t a_count, const ur_vec3 *b, size_t b_count,
                            double tolerance, bool *meet, size_t *where, ur_error *error)
{
    *meet = false;
    if (a_count < 2 || b_count < 2)
        return UR_OK;
    sorted_segment *sorted = ur_alloc_array(b_count - 1, sizeof *sorted, error);
    if (!sorted)
        return UR_ERROR_MEMORY;
    int axis = longest_axis(b, b_count);
    for (size_t j = 0; j + 1 < b_count; j++) {
        double x0 = along(b[j], axis), x1 = along(b[j + 1], axis);
        sorted[j] = (sorted_segment){fmin(x0, x1), fmax(x0, x1), j};
    }
    qsort(sorted, b_count - 1, sizeof *sorted, compare_low);
    double longest = 0.0;
    for (size_t j = 0; j + 1 < b_count; j++)
        longest = fmax(longest, sorted[j].high - sorted[j].low);
    for (size_t i = 0; i + 1 < a_count && !*meet; i++) {
        double x0 = along(a[i], axis), x1 = along(a[i + 1], axis);
        double low = fmin(x0, x1) - tolerance, high = fmax(x0, x1) + tolerance;
        /* The first segment that could reach low: its start is at most `longest` before. */
        size_t first = 0, last = b_count - 1;
        while (first < last) {
            size_t middle = (first + last) / 2;
            if (sorted[middle].low < low - longest)
                first = middle + 1;
            else
                last = middle;
        }
        for (size_t k = first; k + 1 < b_count && sorted[k].low <= high; k++) {
            if (sorted[k].high < low)
                continue;
            size_t j = sorted[k].index;
            if (ur_segment_distance(a[i], a[i + 1], b[j], b[j + 1]) <= tolerance) {
                *meet = true;
                *where = i;
                break;
            }
        }
    }
    free(sorted);
    return UR_OK;
}
