/*
 * test_nest_shapes.c: the shapes the nester makes of pieces (nfp.c): their
 * triangles merged into few convex parts, which cover the piece; and the
 * bound on sheets by area (order_search.c), checked against the fewest
 * bins found by trying every packing.
 */
#include "test_support.h"

#include <geos_c.h>

#include "../../src/nest/nest_internal.h" /* internal: the shapes' convex parts */

static GEOSContextHandle_t geos;

static int start(void **state)
{
    (void)state;
    geos = GEOS_init_r();
    return geos ? 0 : -1;
}

static int finish(void **state)
{
    (void)state;
    GEOS_finish_r(geos);
    return 0;
}

/* The total area of a shape's convex parts, each checked convex (its hull's area). */
static double convex_parts_area(const nest_shape *shape)
{
    double total = 0;
    for (size_t k = 0; k < shape->convex_count; k++) {
        double area, hull_area;
        GEOSGeometry *hull = GEOSConvexHull_r(geos, shape->convex[k]);
        assert_non_null(hull);
        assert_true(GEOSArea_r(geos, shape->convex[k], &area));
        assert_true(GEOSArea_r(geos, hull, &hull_area));
        assert_true(hull_area <= area * (1 + 1e-9) + 1e-9);
        GEOSGeom_destroy_r(geos, hull);
        total += area;
    }
    return total;
}

/*
 * A piece's triangles are merged into convex parts: a regular 40-gon
 * (38 triangles) into one, an L into two, a comb of five teeth (eight
 * notch corners, each needing a cut of its own, a cut serving two at
 * most: at least five parts) into few; their areas add up to the piece's.
 */
static void test_convex_parts_merge(void **state)
{
    (void)state;
    ur_vec2 disc[40], comb[20];
    ur_vec2 l[6] = {{0, 0}, {60, 0}, {60, 20}, {20, 20}, {20, 60}, {0, 60}};
    for (size_t i = 0; i < 40; i++)
        disc[i] =
            ur_vec2_make(50 * cos(2 * M_PI * (double)i / 40), 50 * sin(2 * M_PI * (double)i / 40));
    size_t n = 0;
    comb[n++] = ur_vec2_make(0, 0);
    comb[n++] = ur_vec2_make(90, 0);
    for (int t = 4; t >= 0; t--) { /* teeth 10 wide and 30 tall on a base 10 high, right to left */
        double x = 20.0 * t;
        if (t < 4)
            comb[n++] = ur_vec2_make(x + 10, 10);
        comb[n++] = ur_vec2_make(x + 10, 40);
        comb[n++] = ur_vec2_make(x, 40);
        if (t > 0)
            comb[n++] = ur_vec2_make(x, 10);
    }
    struct {
        ur_piece piece;
        size_t least, most;
    } cases[3] = {{polygon_piece("disc", disc, 40), 1, 1},
                  {polygon_piece("L", l, 6), 2, 2},
                  {polygon_piece("comb", comb, n), 5, 12}};
    for (int c = 0; c < 3; c++) {
        nest_shape shape;
        assert_int_equal(
            nest_shape_make(geos, &cases[c].piece, 0.0, 0.0, false, NULL, &shape, NULL), UR_OK);
        assert_in_range(shape.convex_count, cases[c].least, cases[c].most);
        double area = cases[c].piece.measures.flat_area;
        assert_true(fabs(convex_parts_area(&shape) - area) < 1e-3 * area);
        nest_shape_free(geos, &shape);
        ur_piece_free(&cases[c].piece);
    }
}

static double size_at(const void *items, size_t k)
{
    return ((const double *)items)[k];
}

/* Whether items k.. fit in bins (each holding what is left of it) by trying every bin for each. */
static bool packs(const double *sizes, size_t count, size_t k, double *left, size_t bins)
{
    if (k == count)
        return true;
    for (size_t b = 0; b < bins; b++) {
        if (sizes[k] > left[b])
            continue;
        left[b] -= sizes[k];
        bool done = packs(sizes, count, k + 1, left, bins);
        left[b] += sizes[k];
        if (done)
            return true;
        if (left[b] == 1.0)
            break; /* the other empty bins would do no better */
    }
    return false;
}

/* The fewest bins of capacity 1 that hold the items. */
static size_t fewest_bins(const double *sizes, size_t count)
{
    double left[16];
    for (size_t bins = 1;; bins++) {
        for (size_t b = 0; b < bins; b++)
            left[b] = 1.0;
        if (packs(sizes, count, 0, left, bins))
            return bins;
    }
}

/*
 * The bound: three items over half a bin take three bins (the area says
 * two); 0.7 and two of 0.3 take two; four quarters one; and on random
 * sets of up to 8 items it is never more than the fewest bins, nor less
 * than the area's bound.
 */
static void test_bins_bound(void **state)
{
    (void)state;
    double over_half[3] = {0.6, 0.6, 0.6}, mixed[3] = {0.7, 0.3, 0.3};
    double quarters[4] = {0.25, 0.25, 0.25, 0.25};
    assert_int_equal(nest_bins_bound(size_at, over_half, 3, 1.0), 3);
    assert_int_equal(nest_bins_bound(size_at, mixed, 3, 1.0), 2);
    assert_int_equal(nest_bins_bound(size_at, quarters, 4, 1.0), 1);
    srand(7);
    size_t raised = 0;
    for (int trial = 0; trial < 300; trial++) {
        double sizes[8], total = 0;
        size_t count = 1 + (size_t)(rand() % 8);
        for (size_t k = 0; k < count; k++) {
            sizes[k] = 0.05 + 0.9 * rand() / (double)RAND_MAX;
            total += sizes[k];
        }
        size_t bound = nest_bins_bound(size_at, sizes, count, 1.0);
        size_t by_area = (size_t)ceil(total - 1e-12);
        assert_true(bound >= by_area);
        assert_true(bound <= fewest_bins(sizes, count));
        raised += bound > by_area;
    }
    assert_true(raised > 0); /* the bound says more than the area, at times */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_convex_parts_merge),
        cmocka_unit_test(test_bins_bound),
    };
    return cmocka_run_group_tests(tests, start, finish);
}
