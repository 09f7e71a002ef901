/*
 * hull.c: the convex hull of points (Andrew's monotone chain), the
 * least-area rectangle round a convex polygon, and whether the polygon
 * fits a rectangle at some turn.  The least-area rectangle has a side on
 * one of the polygon's edges (Freeman and Shapira 1975), so each edge's
 * direction is tried, with rotating calipers.
 */
#include "hull.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
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

/* Andrew's chain over points already sorted by compare_points. */
static size_t chain_sorted(const ur_vec2 *points, size_t count, ur_vec2 *hull)
{
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

/*
 * Drops from sorted points each that lies within rounding of the one kept
 * before it; the new count.  Two such points (a corner laid twice by two
 * motions) make the chain's turn test meaningless: its base is no longer
 * than rounding, so the test says anything, and the chain kept a corner
 * where the polygon turns the wrong way by a whole edge (a piece of a
 * bevelled cube then measured smaller than it is, and passed for fitting
 * a sheet it did not fit).
 */
static size_t drop_near_duplicates(ur_vec2 *points, size_t count)
{
    double scale = 0;
    for (size_t i = 0; i < count; i++)
        scale = fmax(scale, fmax(fabs(points[i].x), fabs(points[i].y)));
    double tiny = 64 * DBL_EPSILON * scale;
    size_t kept = count > 0 ? 1 : 0;
    for (size_t i = 1; i < count; i++) {
        ur_vec2 last = points[kept - 1];
        if (fabs(points[i].x - last.x) <= tiny && fabs(points[i].y - last.y) <= tiny)
            continue;
        points[kept++] = points[i];
    }
    return kept;
}

/* Fewer than 3 points, copied as they are: no chain; their count. */
static size_t copy_few(const ur_vec2 *points, size_t count, ur_vec2 *hull)
{
    for (size_t i = 0; i < count; i++)
        hull[i] = points[i];
    return count;
}

/* The hull of sorted points (near-duplicates dropped first, in place); its count. */
static size_t hull_of_sorted(ur_vec2 *points, size_t count, ur_vec2 *hull)
{
    count = drop_near_duplicates(points, count);
    return count < 3 ? copy_few(points, count, hull) : chain_sorted(points, count, hull);
}

size_t geom_convex_hull(ur_vec2 *points, size_t count, ur_vec2 *hull)
{
    if (count < 3)
        return copy_few(points, count, hull);
    qsort(points, count, sizeof *points, compare_points);
    return hull_of_sorted(points, count, hull);
}

/* Merges the sorted runs a and b (na and nb points) into out. */
static void merge_sorted(const ur_vec2 *a, size_t na, const ur_vec2 *b, size_t nb, ur_vec2 *out)
{
    size_t i = 0, j = 0, k = 0;
    while (i < na && j < nb)
        out[k++] = compare_points(&a[i], &b[j]) <= 0 ? a[i++] : b[j++];
    while (i < na)
        out[k++] = a[i++];
    while (j < nb)
        out[k++] = b[j++];
}

/*
 * A convex polygon's points sorted, in linear time: from its least point
 * to its greatest, the chain that runs forward and the one that runs
 * backward each come in order, and are merged.
 */
static void sort_convex(const ur_vec2 *polygon, size_t count, ur_vec2 *out)
{
    size_t least = 0, greatest = 0;
    for (size_t i = 1; i < count; i++) {
        if (compare_points(&polygon[i], &polygon[least]) < 0)
            least = i;
        if (compare_points(&polygon[i], &polygon[greatest]) > 0)
            greatest = i;
    }
    size_t k = 0;
    out[k++] = polygon[least];
    size_t forward = (least + 1) % count, backward = (least + count - 1) % count;
    while (forward != greatest || backward != greatest) {
        bool take_forward =
            backward == greatest ||
            (forward != greatest && compare_points(&polygon[forward], &polygon[backward]) <= 0);
        if (take_forward) {
            out[k++] = polygon[forward];
            forward = (forward + 1) % count;
        } else {
            out[k++] = polygon[backward];
            backward = (backward + count - 1) % count;
        }
    }
    if (greatest != least)
        out[k++] = polygon[greatest];
}

static bool is_sorted(const ur_vec2 *points, size_t count)
{
    for (size_t i = 1; i < count; i++)
        if (compare_points(&points[i - 1], &points[i]) > 0)
            return false;
    return true;
}

size_t geom_convex_hull_of_two(ur_vec2 *points, size_t first, size_t second, ur_vec2 *work,
                               ur_vec2 *hull)
{
    size_t count = first + second;
    if (first < 3 || second < 3)
        return geom_convex_hull(points, count, hull);
    sort_convex(points, first, work);
    sort_convex(points + first, second, work + first);
    merge_sorted(work, first, work + first, second, points);
    /* Rounding can leave a moved polygon a hair off convex, and its chains out of order. */
    if (!is_sorted(points, count))
        qsort(points, count, sizeof *points, compare_points);
    return hull_of_sorted(points, count, hull);
}

/* The diagonal of the points' box: at least the largest distance between two of them. */
static double diagonal_of(const ur_vec2 *hull, size_t count)
{
    ur_box box = ur_box_empty();
    for (size_t i = 0; i < count; i++)
        ur_box_add(&box, hull[i]);
    return hypot(ur_box_width(box), ur_box_height(box));
}

/* The index after i round a polygon of count points. */
static size_t next_index(size_t i, size_t count)
{
    return i + 1 < count ? i + 1 : 0;
}

/* Which extreme point of the polygon a caliper holds, seen from an edge. */
typedef enum caliper { AHEAD, BEHIND, ACROSS } caliper;

/*
 * How far point j lies from point i in the caliper's sense, for the edge
 * from i with unit direction d: along d, against it, or off its line.
 */
static double reach(const ur_vec2 *hull, size_t i, ur_vec2 d, size_t j, caliper c)
{
    ur_vec2 p = ur_vec2_sub(hull[j], hull[i]);
    if (c == ACROSS)
        return fabs(ur_vec2_cross(d, p));
    return c == AHEAD ? ur_vec2_dot(p, d) : -ur_vec2_dot(p, d);
}

/*
 * The caliper at j moved on round the polygon while that takes it no
 * nearer: as the edge turns, each extreme point only moves forward.
 */
static size_t advance(const ur_vec2 *hull, size_t count, size_t i, ur_vec2 d, size_t j, caliper c)
{
    for (size_t steps = 0; steps < count; steps++) {
        size_t next = next_index(j, count);
        if (reach(hull, i, d, next, c) < reach(hull, i, d, j, c))
            break;
        j = next;
    }
    return j;
}

/* The caliper's reach, also asked of the two points after it (rounding may dent the polygon). */
static double reach_at(const ur_vec2 *hull, size_t count, size_t i, ur_vec2 d, size_t j, caliper c)
{
    size_t after = next_index(j, count);
    double r = fmax(reach(hull, i, d, j, c), reach(hull, i, d, after, c));
    return fmax(r, reach(hull, i, d, next_index(after, count), c));
}

/*
 * Rotating calipers (Toussaint 1983): the points farthest ahead, behind
 * and across move forward as the edge does, so that every edge is tried
 * in linear time in all.  A hull of a large piece has thousands of points,
 * and the unfolder asks this of it at every join that its box leaves in
 * doubt.
 */
double geom_least_area_box(const ur_vec2 *hull, size_t count, double *length, double *width)
{
    double best_area = INFINITY, angle = 0.0;
    *length = *width = 0.0;
    size_t ahead = 0, behind = 0, across = 0;
    bool started = false;
    /*
     * An edge no longer than about rounding points anywhere: the calipers
     * would follow it past the extreme points and never come back.  The
     * hulls made here have none (drop_near_duplicates); one given from
     * elsewhere may.
     */
    double shortest = 1e-9 * diagonal_of(hull, count);
    for (size_t i = 0; i < count; i++) {
        ur_vec2 d = ur_vec2_sub(hull[next_index(i, count)], hull[i]);
        double norm = sqrt(ur_vec2_dot(d, d));
        if (!(norm > shortest))
            continue;
        d = ur_vec2_scale(d, 1.0 / norm);
        if (!started)
            ahead = i;
        ahead = advance(hull, count, i, d, ahead, AHEAD);
        across = advance(hull, count, i, d, started ? across : ahead, ACROSS);
        behind = advance(hull, count, i, d, started ? behind : across, BEHIND);
        started = true;
        double high = fmax(0.0, reach_at(hull, count, i, d, ahead, AHEAD));
        double low = fmin(0.0, -reach_at(hull, count, i, d, behind, BEHIND));
        double side = reach_at(hull, count, i, d, across, ACROSS);
        if ((high - low) * side < best_area) {
            best_area = (high - low) * side;
            *length = high - low > side ? high - low : side;
            *width = high - low > side ? side : high - low;
            angle = atan2(d.y, d.x) + (high - low >= side ? 0.0 : M_PI / 2);
        }
    }
    return angle;
}

/* The polygon's extents along the direction of angle and across it. */
static void extents_at(const ur_vec2 *hull, size_t count, double angle, double *along_extent,
                       double *across_extent)
{
    ur_vec2 along = ur_vec2_make(cos(angle), sin(angle));
    double low = INFINITY, high = -INFINITY, left = INFINITY, right = -INFINITY;
    for (size_t i = 0; i < count; i++) {
        double a = ur_vec2_dot(hull[i], along), c = ur_vec2_cross(along, hull[i]);
        low = fmin(low, a), high = fmax(high, a);
        left = fmin(left, c), right = fmax(right, c);
    }
    *along_extent = high - low;
    *across_extent = right - left;
}

/*
 * A fit at any turn, by branch and bound on the angle: an extent changes
 * by at most the polygon's diameter (at most its box's diagonal) times the
 * change of angle, so over an interval of half-width h round an angle each
 * extent is at least its value there less diagonal * h.  An interval where
 * either bound is over its side of the rectangle cannot fit; any other is
 * halved until it fits or is narrower than FIT_NARROWEST (a fit that only
 * a thousandth of a degree allows is none a cutter could hold).  Most
 * polygons that do not fit are refused on the FIT_FIRST first intervals;
 * FIT_MOST_TRIES bounds the rest.
 */
enum { FIT_FIRST = 16, FIT_STACK = 64, FIT_MOST_TRIES = 4096 };
#define FIT_NARROWEST 1e-5

bool geom_hull_fit_angle(const ur_vec2 *hull, size_t count, double length, double width,
                         double *angle)
{
    double least_length, least_width;
    *angle = geom_least_area_box(hull, count, &least_length, &least_width);
    if (least_length <= length && least_width <= width)
        return true;
    if (count < 2 || !(length > 0) || !(width > 0))
        return false;
    double diagonal = diagonal_of(hull, count);
    double centre[FIT_STACK], half[FIT_STACK];
    size_t top = 0;
    for (int k = FIT_FIRST - 1; k >= 0; k--) { /* the extents repeat after a half turn */
        half[top] = 0.5 * M_PI / FIT_FIRST;
        centre[top++] = (2 * k + 1) * half[0];
    }
    for (int tries = 0; top > 0 && tries < FIT_MOST_TRIES; tries++) {
        top--;
        double at = centre[top], h = half[top], along, across;
        extents_at(hull, count, at, &along, &across);
        if (along <= length && across <= width) {
            *angle = at;
            return true;
        }
        double least_change = diagonal * h;
        if (along - least_change > length || across - least_change > width || h < FIT_NARROWEST ||
            top + 2 > FIT_STACK)
            continue;
        centre[top] = at + 0.5 * h, half[top++] = 0.5 * h;
        centre[top] = at - 0.5 * h, half[top++] = 0.5 * h;
    }
    return false;
}
