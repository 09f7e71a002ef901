/*
 * test_geom.c: segment distances against hand-worked cases, the polyline
 * meeting test on rails that cross, touch and stay apart, and the hulls:
 * two merged, the least-area rectangle against every edge tried in full,
 * and fits at a turn.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "unroll/geom.h"

#include <math.h>
#include <string.h>

#include "../../src/geom/hull.h" /* internal: the unfolder's and nester's hulls */

static void test_segment_distance(void **state)
{
    (void)state;
    ur_vec3 o = {0, 0, 0};
    /* Skew segments across each other: the distance of their lines, 3. */
    assert_float_equal(ur_segment_distance(ur_vec3_make(-1, 0, 0), ur_vec3_make(1, 0, 0),
                                           ur_vec3_make(0, -1, 3), ur_vec3_make(0, 1, 3)),
                       3.0, 1e-15);
    /* Parallel, overlapping by half: 2 apart. */
    assert_float_equal(
        ur_segment_distance(o, ur_vec3_make(2, 0, 0), ur_vec3_make(1, 2, 0), ur_vec3_make(3, 2, 0)),
        2.0, 1e-15);
    /* End to end along one line: the gap between them, 1. */
    assert_float_equal(
        ur_segment_distance(o, ur_vec3_make(1, 0, 0), ur_vec3_make(2, 0, 0), ur_vec3_make(5, 0, 0)),
        1.0, 1e-15);
    /* A point and a segment: the perpendicular, 5. */
    assert_float_equal(ur_segment_distance(ur_vec3_make(0, 5, 0), ur_vec3_make(0, 5, 0),
                                           ur_vec3_make(-1, 0, 0), ur_vec3_make(1, 0, 0)),
                       5.0, 1e-15);
    /* Past the ends of both: corner to corner, sqrt(2). */
    assert_float_equal(
        ur_segment_distance(o, ur_vec3_make(1, 0, 0), ur_vec3_make(2, 1, 0), ur_vec3_make(2, 3, 0)),
        sqrt(2.0), 1e-15);
}

enum { N = 31 };

static void line(ur_vec3 *points, double y0, double slope, double z)
{
    for (int i = 0; i < N; i++) {
        double x = 100.0 * i / (N - 1);
        points[i] = ur_vec3_make(x, y0 + slope * x, z);
    }
}

static void test_polylines_meet(void **state)
{
    (void)state;
    ur_vec3 a[N], b[N];
    bool meet;
    size_t where = 99;
    /* Crossing at x = 51.67 (between points 15 and 16 of a): found there. */
    line(a, 0, 0, 0);
    line(b, 31, -0.6, 0);
    assert_int_equal(ur_polylines_meet(a, N, b, N, 1e-9, &meet, &where, NULL), UR_OK);
    assert_true(meet);
    assert_int_equal(where, 15);
    /* The same lines 1 mm apart in z: apart at any tolerance below 1. */
    line(b, 31, -0.6, 1);
    assert_int_equal(ur_polylines_meet(a, N, b, N, 0.999, &meet, &where, NULL), UR_OK);
    assert_false(meet);
    assert_int_equal(ur_polylines_meet(a, N, b, N, 1.001, &meet, &where, NULL), UR_OK);
    assert_true(meet);
}

/* A number in [0, 1) from a small linear congruential generator: the same everywhere. */
static double next_unit(uint64_t *state)
{
    *state = *state * 6364136223846793005u + 1442695040888963407u;
    return (double)(*state >> 11) / 9007199254740992.0;
}

/*
 * The hull of two convex polygons joined in linear time is the hull of all
 * their points sorted afresh, point for point: random hulls, one turned
 * about by an angle that rounds its coordinates (as the unfolder moves a
 * piece), or both the same square (every point twice), or sharing a
 * vertical edge.
 */
static void test_hull_of_two(void **state)
{
    (void)state;
    uint64_t seed = 7;
    enum { MOST = 64 };
    for (int round = 0; round < 500; round++) {
        ur_vec2 cloud[2][MOST], hulls[2][MOST + 1];
        size_t counts[2];
        for (int h = 0; h < 2; h++) {
            size_t n = 3 + (size_t)(next_unit(&seed) * (MOST - 3));
            double angle = 2 * M_PI * next_unit(&seed), c = cos(angle), s = sin(angle);
            for (size_t i = 0; i < n; i++) {
                double x = 100 * next_unit(&seed), y = 40 * next_unit(&seed);
                if (round % 5 == 0) /* a square's corners only, both the same */
                    x = (i & 1) ? 10 : 0, y = (i & 2) ? 10 : 0;
                if (round % 5 == 1 && h == 1) /* beside the first: x = 100 on both */
                    x = 100 + x / 10;
                cloud[h][i] = round % 5 < 2 ? ur_vec2_make(x, y)
                                            : ur_vec2_make(c * x - s * y + 50 * h, s * x + c * y);
            }
            counts[h] = geom_convex_hull(cloud[h], n, hulls[h]);
        }
        ur_vec2 joined[2 * MOST], all[2 * MOST], work[2 * MOST], fast[2 * MOST + 1],
            slow[2 * MOST + 1];
        size_t count = 0;
        for (int h = 0; h < 2; h++)
            for (size_t i = 0; i < counts[h]; i++)
                joined[count] = all[count] = hulls[h][i], count++;
        size_t k = geom_convex_hull_of_two(joined, counts[0], counts[1], work, fast);
        size_t expected = geom_convex_hull(all, count, slow);
        assert_int_equal(k, expected);
        assert_true(k >= 3);
        assert_memory_equal(fast, slow, k * sizeof *fast);
    }
}

/* The polygon's extents along the direction of angle and across it. */
static void extents_at(const ur_vec2 *points, size_t count, double angle, double *along,
                       double *across)
{
    double c = cos(angle), s = sin(angle), low = INFINITY, high = -INFINITY;
    double left = INFINITY, right = -INFINITY;
    for (size_t i = 0; i < count; i++) {
        double a = c * points[i].x + s * points[i].y, b = -s * points[i].x + c * points[i].y;
        low = fmin(low, a), high = fmax(high, a), left = fmin(left, b), right = fmax(right, b);
    }
    *along = high - low;
    *across = right - left;
}

/* Whether the hull of points fits length x width at some turn; checks the angle it gives. */
static bool fits_turned(const ur_vec2 *points, size_t count, double length, double width)
{
    ur_vec2 copy[200], hull[201];
    assert_true(count <= 200);
    memcpy(copy, points, count * sizeof *copy);
    size_t corners = geom_convex_hull(copy, count, hull);
    double angle, along, across;
    bool fits = geom_hull_fit_angle(hull, corners, length, width, &angle);
    if (fits) {
        extents_at(points, count, angle, &along, &across);
        assert_true(along <= length * (1 + 1e-12) && across <= width * (1 + 1e-12));
    }
    return fits;
}

/* The corners of a w x h rectangle turned by angle. */
static void turned_rectangle(double w, double h, double angle, ur_vec2 corners[4])
{
    double c = cos(angle), s = sin(angle);
    for (int k = 0; k < 4; k++) {
        double x = (k == 1 || k == 2) ? w : 0, y = k >= 2 ? h : 0;
        corners[k] = ur_vec2_make(c * x - s * y, s * x + c * y);
    }
}

/* The least-area rectangle the slow way: every edge's direction against every point. */
static double least_area_by_every_point(const ur_vec2 *hull, size_t count, double *length,
                                        double *width)
{
    double best = INFINITY;
    *length = *width = 0;
    for (size_t i = 0; i < count; i++) {
        double dx = hull[(i + 1) % count].x - hull[i].x, dy = hull[(i + 1) % count].y - hull[i].y;
        double norm = hypot(dx, dy);
        double low = INFINITY, high = -INFINITY, left = INFINITY, right = -INFINITY;
        for (size_t j = 0; j < count; j++) {
            double px = hull[j].x - hull[i].x, py = hull[j].y - hull[i].y;
            double along = (px * dx + py * dy) / norm, off = (dx * py - dy * px) / norm;
            low = fmin(low, along), high = fmax(high, along);
            left = fmin(left, off), right = fmax(right, off);
        }
        double across = right - left;
        if ((high - low) * across < best) {
            best = (high - low) * across;
            *length = fmax(high - low, across);
            *width = fmin(high - low, across);
        }
    }
    return best;
}

static uint64_t next_random(uint64_t *state)
{
    *state ^= *state << 13, *state ^= *state >> 7, *state ^= *state << 17;
    return *state;
}

static double uniform(uint64_t *state)
{
    return (double)(next_random(state) >> 11) * 0x1.0p-53;
}

/*
 * The rotating calipers find the rectangle that trying every edge against
 * every point finds: on hulls of random points in a disc and in a long
 * thin strip, and on a regular 2,000-gon (parallel edges: calipers that
 * stop on a tie must still hold the extreme points).
 */
static void test_least_area_box(void **state)
{
    (void)state;
    enum { MOST = 2000 };
    static ur_vec2 points[MOST], hull[MOST + 1];
    uint64_t random = 12345;
    for (int trial = 0; trial < 300; trial++) {
        size_t count = 3 + (size_t)(uniform(&random) * 400);
        double stretch = trial % 2 ? 1.0 : 40.0, turn = uniform(&random) * 6.3;
        for (size_t k = 0; k < count; k++) {
            double r = sqrt(uniform(&random)), a = 2 * M_PI * uniform(&random);
            double x = stretch * r * cos(a), y = r * sin(a);
            points[k] = ur_vec2_make(x * cos(turn) - y * sin(turn), x * sin(turn) + y * cos(turn));
        }
        size_t corners = geom_convex_hull(points, count, hull);
        double length, width, slow_length, slow_width;
        geom_least_area_box(hull, corners, &length, &width);
        double slow = least_area_by_every_point(hull, corners, &slow_length, &slow_width);
        assert_float_equal(length * width, slow, 1e-9 * slow);
        assert_float_equal(length, slow_length, 1e-9 * slow_length);
        assert_float_equal(width, slow_width, 1e-9 * slow_length);
    }
    for (size_t k = 0; k < MOST; k++)
        hull[k] = ur_vec2_make(50 * cos(2 * M_PI * (double)k / MOST),
                               50 * sin(2 * M_PI * (double)k / MOST));
    double length, width;
    geom_least_area_box(hull, MOST, &length, &width);
    /* A square on an edge: its sides 100 cos(pi / 2000), edge to opposite edge, both ways. */
    assert_float_equal(length, 100 * cos(M_PI / MOST), 1e-9);
    assert_float_equal(width, 100 * cos(M_PI / MOST), 1e-9);
}

/* The least turn of a polygon at its corners, over its size squared (< 0: not convex). */
static double least_turn(const ur_vec2 *hull, size_t count)
{
    double least = INFINITY, size = 0;
    for (size_t i = 0; i < count; i++)
        size = fmax(size, fmax(fabs(hull[i].x), fabs(hull[i].y)));
    for (size_t i = 0; i < count; i++) {
        ur_vec2 a = hull[i], b = hull[(i + 1) % count], c = hull[(i + 2) % count];
        least = fmin(least, (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x));
    }
    return least / (size * size);
}

/* The least-area rectangle by turning a rectangle round in steps of a millionth of a quarter. */
static double least_area_by_turning(const ur_vec2 *points, size_t count)
{
    double best = INFINITY;
    for (int k = 0; k < 1000000; k++) {
        double along, across;
        extents_at(points, count, 0.5 * M_PI * k / 1e6, &along, &across);
        best = fmin(best, along * across);
    }
    return best;
}

/*
 * A corner laid twice, a few units of the last place apart (the hull of a
 * piece of Blender's bevelled cube, triangulated, as the unfolder met it):
 * the chain's turn test on so short a base said anything, and the hull
 * kept a corner where it turns the wrong way by a whole edge.  Its least
 * rectangle then came out 70,505 mm2 where none is under 75,610, and the
 * piece passed for fitting a sheet it did not fit.  Now the hull is convex
 * and its rectangle that of a rectangle turned round it in fine steps;
 * also for random hulls with a corner given twice so.
 */
static void test_hull_of_a_corner_laid_twice(void **state)
{
    (void)state;
    ur_vec2 points[9] = {{-105.72622627169116, 15.152341888446408},
                         {-24.588458245177399, -6.5884575299216745},
                         {-24.588458245177396, -6.5884575299216772},
                         {59.39696860814562, -59.39696860814562},
                         {118.79393721629124, 0},
                         {140.53473663465937, 37.656169189777515},
                         {147.12319416458104, 62.244627434954921},
                         {-8.6730884737680825, 264.26096362160627},
                         {-89.81085650028183, 242.52016420323815}};
    ur_vec2 copy[9], hull[10];
    memcpy(copy, points, sizeof copy);
    size_t corners = geom_convex_hull(copy, 9, hull);
    assert_int_equal(corners, 7); /* the corner laid twice lies inside: both copies go */
    assert_true(least_turn(hull, corners) > 0);
    double length, width;
    geom_least_area_box(hull, corners, &length, &width);
    double turning = least_area_by_turning(points, 9);
    assert_true(turning > 75600);
    assert_float_equal(length * width, turning, 1e-6 * turning);

    uint64_t random = 777;
    ur_vec2 many[101], round_hull[102];
    for (int trial = 0; trial < 20; trial++) {
        for (size_t k = 0; k < 100; k++) {
            double a = 2 * M_PI * uniform(&random), r = 50 + 100 * uniform(&random);
            many[k] = ur_vec2_make(r * cos(a), 0.5 * r * sin(a));
        }
        many[100] = many[trial]; /* a point of the hull (maybe) given again, a hair off */
        many[100].x = nextafter(nextafter(many[100].x, INFINITY), INFINITY);
        many[100].y = nextafter(many[100].y, -INFINITY);
        size_t n = geom_convex_hull(many, 101, round_hull);
        assert_true(least_turn(round_hull, n) > 0);
        geom_least_area_box(round_hull, n, &length, &width);
        double slow_length, slow_width;
        double slow = least_area_by_every_point(round_hull, n, &slow_length, &slow_width);
        assert_float_equal(length * width, slow, 1e-9 * slow);
    }
}

/*
 * A piece fits a sheet at some turn, not only level: closed forms for a
 * needle (it fits L x W exactly when it is no longer than the diagonal)
 * and a square (turning never helps it), a long thin rectangle that fits
 * only diagonally, and a Blender cylinder's net (a 377 x 120 mm strip of
 * 32 faces with both 120 mm caps) whose caps on faces 8 and 22 fit the
 * 397 x 274 mm room turned by about 25 degrees (391 x 270 mm), and on one
 * face no way (least overflow 1.27; both from a scan of every 0.005
 * degree).
 */
static void test_hull_fits_turned(void **state)
{
    (void)state;
    double diagonal = hypot(100, 50);
    ur_vec2 needle[2] = {{0, 0}, {0.999 * diagonal, 0}};
    assert_true(fits_turned(needle, 2, 100, 50));
    needle[1].x = 1.001 * diagonal;
    assert_false(fits_turned(needle, 2, 100, 50));
    ur_vec2 square[4];
    turned_rectangle(50.05, 50.05, 0.3, square);
    assert_false(fits_turned(square, 4, 1000, 50));
    turned_rectangle(49.95, 49.95, 0.3, square);
    assert_true(fits_turned(square, 4, 1000, 50));
    ur_vec2 thin[4];
    turned_rectangle(110, 2, 1.0, thin); /* cos 0.9 turns it to 99.9 x 49.8 */
    assert_true(fits_turned(thin, 4, 100, 50));
    turned_rectangle(100, 10, M_PI / 6, thin); /* level: the least-area rectangle's own turn */
    double angle;
    ur_vec2 hull[5];
    size_t corners = geom_convex_hull(thin, 4, hull);
    assert_true(geom_hull_fit_angle(hull, corners, 101, 11, &angle));
    assert_true(fabs(fmod(angle + 2 * M_PI, M_PI) - M_PI / 6) < 1e-9);

    enum { SIDES = 32 };
    const double radius = 60, face = 2 * radius * sin(M_PI / SIDES), height = 120;
    for (int pair = 0; pair < 2; pair++) {
        int top = pair ? 0 : 22, bottom = pair ? 0 : 8;
        ur_vec2 net[4 + 2 * SIDES] = {
            {0, 0}, {SIDES * face, 0}, {SIDES * face, height}, {0, height}};
        double apothem = radius * cos(M_PI / SIDES);
        for (int k = 0; k < SIDES; k++) {
            double a = 2 * M_PI * k / SIDES + M_PI / SIDES;
            net[4 + k] = ur_vec2_make((top + 0.5) * face + radius * cos(a),
                                      height + apothem + radius * sin(a));
            net[4 + SIDES + k] =
                ur_vec2_make((bottom + 0.5) * face + radius * cos(a), -apothem + radius * sin(a));
        }
        assert_int_equal(fits_turned(net, 4 + 2 * SIDES, 397, 274), pair == 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_segment_distance),
        cmocka_unit_test(test_polylines_meet),
        cmocka_unit_test(test_hull_of_two),
        cmocka_unit_test(test_least_area_box),
        cmocka_unit_test(test_hull_of_a_corner_laid_twice),
        cmocka_unit_test(test_hull_fits_turned),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
