/*
 * nurbs.c: a NURBS curve (DXF SPLINE) flattened into points, each chord
 * within the tolerance of the curve, for the part readers.
 *
 * de Boor's algorithm on homogeneous points (w x, w y, w) evaluates a
 * rational or plain B-spline of any degree on any non-decreasing knot
 * vector: repeated interior knots (a circle as a rational quadratic needs
 * them), unclamped and periodic vectors alike.  GSL's B-splines (2.7) build
 * their knots from breakpoints, clamped at the ends with simple knots
 * inside, so they cannot take the knot vectors DXF files hold.
 */
#include "parts_internal.h"

#include <math.h>
#include <stdlib.h>

/* Homogeneous control point. */
typedef struct nurbs_point {
    double x, y, w;
} nurbs_point;

/* Bisections of one knot span, at least and at most. */
#define NURBS_LEAST_DEPTH 3
#define NURBS_MOST_DEPTH 24

/* The span s (degree <= s < control_count) whose knots hold t. */
static size_t find_span(const parts_nurbs *curve, double t)
{
    size_t p = (size_t)curve->degree, last = curve->control_count - 1;
    if (t >= curve->knots[last + 1])
        return last;
    size_t low = p, high = last + 1;
    while (high - low > 1) {
        size_t middle = (low + high) / 2;
        if (t < curve->knots[middle])
            high = middle;
        else
            low = middle;
    }
    return low;
}

/* The curve at t by de Boor; work holds degree + 1 points. */
static ur_vec2 evaluate(const parts_nurbs *curve, double t, nurbs_point *work)
{
    size_t p = (size_t)curve->degree, s = find_span(curve, t);
    for (size_t j = 0; j <= p; j++) {
        size_t i = s - p + j;
        double w = curve->weights ? curve->weights[i] : 1.0;
        work[j] = (nurbs_point){curve->points[i].x * w, curve->points[i].y * w, w};
    }
    for (size_t r = 1; r <= p; r++)
        for (size_t j = p; j >= r; j--) {
            size_t i = s - p + j;
            double span = curve->knots[i + p + 1 - r] - curve->knots[i];
            double a = span > 0 ? (t - curve->knots[i]) / span : 0.0;
            work[j].x = (1 - a) * work[j - 1].x + a * work[j].x;
            work[j].y = (1 - a) * work[j - 1].y + a * work[j].y;
            work[j].w = (1 - a) * work[j - 1].w + a * work[j].w;
        }
    return ur_vec2_make(work[p].x / work[p].w, work[p].y / work[p].w);
}

/* How far p lies from the segment a b. */
static double distance_to_chord(ur_vec2 p, ur_vec2 a, ur_vec2 b)
{
    ur_vec2 d = ur_vec2_sub(b, a);
    double length2 = ur_vec2_dot(d, d);
    double t = length2 > 0 ? ur_vec2_dot(ur_vec2_sub(p, a), d) / length2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return ur_vec2_distance(p, ur_vec2_add_scaled(a, d, t));
}

typedef struct nurbs_flattening {
    const parts_nurbs *curve;
    parts_points *points;
    nurbs_point *work;
    double tolerance;
    size_t segments;
} nurbs_flattening;

/*
 * The curve from t0 (at a, pushed already) to t1 (at b): halved until the
 * middle and quarter points lie within the tolerance of the chord, at
 * least NURBS_LEAST_DEPTH times so that a span's wiggle is not missed.
 */
static ur_status flatten_piece(nurbs_flattening *f, double t0, ur_vec2 a, double t1, ur_vec2 b,
                               int depth, ur_error *error)
{
    double tm = (t0 + t1) / 2;
    ur_vec2 middle = evaluate(f->curve, tm, f->work);
    bool fine =
        depth >= NURBS_LEAST_DEPTH && distance_to_chord(middle, a, b) <= f->tolerance &&
        distance_to_chord(evaluate(f->curve, (t0 + tm) / 2, f->work), a, b) <= f->tolerance &&
        distance_to_chord(evaluate(f->curve, (tm + t1) / 2, f->work), a, b) <= f->tolerance;
    if (fine || depth >= NURBS_MOST_DEPTH || f->segments >= PARTS_MAX_CURVE_SEGMENTS) {
        f->segments++;
        return parts_points_push(f->points, b, error);
    }
    ur_status status = flatten_piece(f, t0, a, tm, middle, depth + 1, error);
    if (status == UR_OK)
        status = flatten_piece(f, tm, middle, t1, b, depth + 1, error);
    return status;
}

ur_status parts_flatten_nurbs(parts_points *points, const parts_nurbs *curve, double tolerance,
                              ur_error *error)
{
    size_t p = (size_t)curve->degree;
    nurbs_point *work = ur_alloc_array(p + 1, sizeof *work, error);
    if (!work)
        return UR_ERROR_MEMORY;
    nurbs_flattening f = {curve, points, work, tolerance, 0};
    double first = curve->knots[p], last = curve->knots[curve->control_count];
    ur_vec2 a = evaluate(curve, first, work);
    ur_status status = parts_points_push(points, a, error);
    for (size_t s = p; status == UR_OK && s < curve->control_count; s++) {
        double t0 = curve->knots[s], t1 = curve->knots[s + 1];
        if (!(t1 > t0))
            continue;
        ur_vec2 b = evaluate(curve, t1 < last ? t1 : last, work);
        status = flatten_piece(&f, t0, a, t1, b, 0, error);
        a = b;
    }
    free(work);
    return status;
}
