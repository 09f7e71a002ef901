/*
 * test_geom.c: segment distances against hand-worked cases, and the
 * polyline meeting test on rails that cross, touch and stay apart.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "unroll/geom.h"

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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_segment_distance),
        cmocka_unit_test(test_polylines_meet),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
