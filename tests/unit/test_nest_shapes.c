/*
 * test_nest_shapes.c: the shapes the nester makes of pieces (nfp.c): their
 * triangles merged into few convex parts, which cover the piece; the
 * bound on sheets by area (order_search.c), checked against the fewest
 * bins found by trying every packing; the two indexes that keep nesting
 * many parts from costing their square (pair_table.c, placed_index.c),
 * checked against looking at every entry; and the sheet's raster
 * (sheet_raster.c), whose every place ruled out is checked against GEOS.
 */
#include "test_support.h"
#include "test_geos.h"

#include "../../src/nest/nest_internal.h" /* internal: the shapes' convex parts */

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

/*
 * The pairs met, by key: 20,000 keys spread as nest_pair_key spreads them
 * (and many the same modulo every table size) are each found with what
 * was put in, keys never added are not, and adding a key again gives its
 * entry, not a new one.
 */
static void test_pair_table(void **state)
{
    (void)state;
    pair_table table = {NULL, 0, 0};
    assert_null(pair_table_find(&table, 3));
    for (size_t k = 0; k < 20000; k++) {
        size_t key = k % 2 ? k * 4096 : k * 7 + 1;
        pair_entry *entry = pair_table_add(&table, key);
        assert_non_null(entry);
        assert_int_equal(entry->key, key);
        assert_int_equal(entry->met, 0);
        entry->met = k + 1;
    }
    assert_int_equal(table.count, 20000);
    assert_true(2 * table.count <= table.capacity);
    for (size_t k = 0; k < 20000; k++) {
        size_t key = k % 2 ? k * 4096 : k * 7 + 1;
        pair_entry *entry = pair_table_find(&table, key);
        assert_non_null(entry);
        assert_int_equal(entry->met, k + 1);
        assert_ptr_equal(pair_table_add(&table, key), entry);
    }
    assert_int_equal(table.count, 20000);
    assert_null(pair_table_find(&table, 4096 * 2 + 1));
    assert_null(pair_table_find(&table, 7 * 20000 + 1));
    pair_table_free(geos, &table);
    assert_null(table.slots);
}

/* Whether placement k's reach box, as the index widens it, meets box. */
static bool reach_meets(const nester *n, size_t k, const double *box)
{
    const placed *p = &n->placements[k];
    const nest_shape *shape = nest_shape_of(n, p->piece, p->turn);
    double slack = nest_reach_slack(shape);
    return p->at.x + shape->reach.min.x - slack < box[2] &&
           p->at.x + shape->reach.max.x + slack > box[0] &&
           p->at.y + shape->reach.min.y - slack < box[3] &&
           p->at.y + shape->reach.max.y + slack > box[1];
}

/*
 * The placements by where they reach: on two sheets of 300 x 200 mm with
 * 10 mm buckets, 400 placements of three sizes of part (some reaching past
 * the sheet's edge) are each found by every query box their reach meets,
 * in the order placed, once, from the first asked for on, and only on
 * their own sheet; a query far off finds few.  After forgetting all but
 * the first 150, the same holds of those.
 */
static void test_placed_index(void **state)
{
    (void)state;
    enum { PLACED = 400 };
    ur_nest_options options = {.sheet_width = 300, .sheet_height = 200};
    nest_shape shapes[3] = {0};
    double half[3] = {1, 6, 40};
    for (int s = 0; s < 3; s++)
        shapes[s].reach = (ur_box){{-half[s], -half[s] / 2}, {half[s], half[s] / 2}};
    nest_class classes[3] = {{0, &shapes[0], 1}, {1, &shapes[1], 1}, {2, &shapes[2], 1}};
    size_t class_of[PLACED];
    placed placements[PLACED];
    size_t sheet_of[PLACED];
    sheet_state sheets[2] = {0};
    nester n = {.count = PLACED,
                .options = &options,
                .turn_count = 1,
                .class_of = class_of,
                .classes = classes,
                .class_count = 3,
                .placements = placements,
                .sheet_of = sheet_of,
                .sheet_slots = 2,
                .sheets = sheets,
                .cell_size = 10};
    srand(11);
    for (size_t k = 0; k < PLACED; k++) {
        class_of[k] = k % 7 == 0 ? 2 : k % 3 == 0 ? 1 : 0;
        placements[k] =
            (placed){k, 0, {-20 + 340.0 * rand() / RAND_MAX, -20 + 240.0 * rand() / RAND_MAX}};
        sheet_of[k] = k % 5 == 0;
        n.placed_count = k + 1;
        assert_true(nest_index_add(&n, k));
    }
    for (int round = 0; round < 2; round++) {
        for (int q = 0; q < 300; q++) {
            double x = -30 + 360.0 * rand() / RAND_MAX, y = -30 + 260.0 * rand() / RAND_MAX;
            double w = 30.0 * rand() / RAND_MAX, h = 30.0 * rand() / RAND_MAX;
            double box[4] = {x, y, x + w, y + h};
            size_t sheet = (size_t)(q % 2), from = (size_t)(q % 4) * 40, count = 0, expected = 0;
            assert_true(nest_index_near(&n, sheet, box, from, &count));
            for (size_t i = 1; i < count; i++)
                assert_true(n.near[i - 1] < n.near[i]);
            for (size_t i = 0; i < count; i++) {
                assert_true(n.near[i] >= from && n.near[i] < n.placed_count);
                assert_int_equal(sheet_of[n.near[i]], sheet);
            }
            for (size_t k = from; k < n.placed_count; k++) {
                if (sheet_of[k] != sheet || !reach_meets(&n, k, box))
                    continue;
                expected++;
                bool found = false;
                for (size_t i = 0; i < count && !found; i++)
                    found = n.near[i] == k;
                assert_true(found);
            }
            /* Buckets of 10 mm round a box at most 30 mm across: few besides. */
            assert_true(count <= expected + 60);
        }
        nest_index_rewind(&n, 150);
        n.placed_count = 150;
    }
    free(n.near);
    nest_index_free(&sheets[0]);
    nest_index_free(&sheets[1]);
}

/* A star of n points about (0, 0), radii alternating r and r / 3, as a GEOS polygon. */
static GEOSGeometry *star(int n, double r, double turn)
{
    GEOSCoordSequence *ring = GEOSCoordSeq_create_r(geos, (unsigned)(2 * n + 1), 2);
    for (int i = 0; i <= 2 * n; i++) {
        double a = turn + M_PI * (i % (2 * n)) / n, radius = i % 2 ? r / 3 : r; /* closed */
        GEOSCoordSeq_setXY_r(geos, ring, (unsigned)i, radius * cos(a), radius * sin(a));
    }
    return GEOSGeom_createPolygon_r(geos, GEOSGeom_createLinearRing_r(geos, ring), NULL, 0);
}

static int move_xy(double *x, double *y, void *by)
{
    *x += ((const ur_vec2 *)by)->x;
    *y += ((const ur_vec2 *)by)->y;
    return 1;
}

static GEOSGeometry *shifted_copy(const GEOSGeometry *g, double x, double y)
{
    ur_vec2 by = {x, y};
    return GEOSGeom_transformXY_r(geos, g, move_xy, &by);
}

/*
 * Asks the raster about 6,000 small boxes of origins for piece (its shape
 * polygon), and checks that each box ruled out overlaps the parts placed
 * (placed_union) at its corners, centre and 8 random points, and each box
 * narrowed at 13 points outside what it was narrowed to.  Returns how many
 * boxes were ruled out; *narrowed_count counts those narrowed to less than
 * half.
 */
static size_t ask_raster(nester *n, size_t piece, const GEOSGeometry *polygon,
                         const GEOSGeometry *placed_union, size_t *narrowed_count)
{
    size_t ruled_out = 0;
    for (int q = 0; q < 6000; q++) {
        double x = 200.0 * rand() / RAND_MAX, y = 150.0 * rand() / RAND_MAX;
        double box[4] = {x, y, x + 12.0 * rand() / RAND_MAX, y + 12.0 * rand() / RAND_MAX};
        double narrowed[4];
        raster_verdict seen = nest_raster_room(n, 0, piece, 0, box, narrowed);
        if (seen == RASTER_NARROWED) {
            assert_true(narrowed[0] >= box[0] && narrowed[2] <= box[2] && narrowed[1] >= box[1] &&
                        narrowed[3] <= box[3]);
            *narrowed_count += (narrowed[2] - narrowed[0]) * (narrowed[3] - narrowed[1]) <
                               0.5 * (box[2] - box[0]) * (box[3] - box[1]);
        }
        if (seen == RASTER_UNKNOWN)
            continue;
        ruled_out += seen == RASTER_NONE;
        /* Ruled out: every point of the box overlaps; narrowed: every point outside it. */
        for (int t = 0, checked = 0; t < 200 && checked < 13; t++) {
            double u = t < 4 ? t % 2 : t == 4 ? 0.5 : (double)rand() / RAND_MAX;
            double v = t < 4 ? t / 2 : t == 4 ? 0.5 : (double)rand() / RAND_MAX;
            double px = box[0] + u * (box[2] - box[0]), py = box[1] + v * (box[3] - box[1]);
            if (seen == RASTER_NARROWED && px >= narrowed[0] && px <= narrowed[2] &&
                py >= narrowed[1] && py <= narrowed[3])
                continue;
            checked++;
            GEOSGeometry *there = shifted_copy(polygon, px, py);
            GEOSGeometry *common = GEOSIntersection_r(geos, there, placed_union);
            double area = 0;
            assert_true(common && GEOSArea_r(geos, common, &area));
            assert_true(area > 1e-6);
            GEOSGeom_destroy_r(geos, common);
            GEOSGeom_destroy_r(geos, there);
        }
    }
    return ruled_out;
}

/*
 * A raster brought up to date placement by placement is the one made anew
 * from all of them: in every pixel the same distance, or both beyond the
 * widest disc any of the count shapes can hold (half the shorter side of
 * its box), which no test looks beyond.  Sets the shapes' reach (the box
 * of the polygon) as nest_shape_make does, and leaves every placement on.
 */
static void check_raster_brought_up_to_date(nester *n, nest_shape *shapes, size_t count)
{
    double widest = 0;
    for (size_t k = 0; k < count; k++) {
        double b[4];
        assert_true(nest_box_of(geos, shapes[k].polygon, b));
        shapes[k].reach = (ur_box){{b[0], b[1]}, {b[2], b[3]}};
        widest = fmax(widest, 0.5 * fmin(b[2] - b[0], b[3] - b[1]));
    }
    size_t all = n->placed_count;
    double middle[4] = {99, 74, 101, 76};
    sheet_raster *raster = &n->sheets[0].raster;
    for (n->placed_count = 0; n->placed_count <= all; n->placed_count++) {
        n->sheets[0].version++;
        nest_raster_room(n, 0, all, 0, middle, NULL);
        assert_non_null(raster->distance);
    }
    n->placed_count = all;
    size_t pixels = raster->columns * raster->rows;
    float *added = malloc(pixels * sizeof *added);
    assert_non_null(added);
    memcpy(added, raster->distance, pixels * sizeof *added);
    n->sheets[0].version++; /* a version no placement explains: made anew */
    nest_raster_room(n, 0, all, 0, middle, NULL);
    size_t differ = 0;
    for (size_t q = 0; q < pixels; q++)
        differ +=
            added[q] != raster->distance[q] && !(added[q] > widest && raster->distance[q] > widest);
    assert_int_equal(differ, 0);
    free(added);
}

/*
 * The sheet's raster rules out only places that overlap: on a 200 x 150
 * mm sheet with 13 stars and a plate with a square hole placed, a star
 * and a 48-gon (whose inscribed disc is nearly all of it: a raster that
 * reached a pixel too far would rule out places where it does not
 * overlap) are asked about 6,000 small boxes of origins each.  Every box
 * ruled out is checked at its corners, centre and 8 random points, and
 * every box narrowed at 13 points outside what it was narrowed to: there
 * the piece overlaps a placed part by more than a square micrometre
 * (GEOS).  Over 300 boxes are ruled out and over 100 narrowed to less than
 * half, and the star's other discs rule out more than its largest alone;
 * the 48-gon in the middle of the
 * plate's hole is not; and after the parts are forgotten (a rewind), no
 * box is.
 */
static void test_raster_rules_out_only_overlaps(void **state)
{
    (void)state;
    enum { PLACED = 14 };
    ur_nest_options options = {.sheet_width = 200, .sheet_height = 150};
    nest_shape shapes[PLACED + 2] = {0};
    nest_class classes[PLACED + 2] = {0};
    size_t class_of[PLACED + 2];
    placed placements[PLACED];
    size_t sheet_of[PLACED] = {0};
    sheet_state sheets[1] = {0};
    srand(3);
    GEOSGeometry *placed_union = NULL;
    for (size_t k = 0; k < PLACED + 2; k++) {
        if (k == PLACED + 1) { /* a round piece: its disc is nearly all of it */
            shapes[k].polygon = star(24, 6, 0);
            GEOSGeometry *round = GEOSConvexHull_r(geos, shapes[k].polygon);
            GEOSGeom_destroy_r(geos, shapes[k].polygon);
            shapes[k].polygon = round;
        } else if (k == 3) { /* a plate with a square hole: parts may go in the hole */
            GEOSGeometry *plate = nest_rectangle_polygon(geos, -30, -30, 30, 30);
            GEOSGeometry *hole = nest_rectangle_polygon(geos, -15, -15, 15, 15);
            shapes[k].polygon = GEOSDifference_r(geos, plate, hole);
            GEOSGeom_destroy_r(geos, plate);
            GEOSGeom_destroy_r(geos, hole);
        } else {
            shapes[k].polygon = star(5 + (int)k % 4, 8 + 12.0 * rand() / RAND_MAX, k * 0.3);
        }
        classes[k] = (nest_class){k, &shapes[k], 1};
        class_of[k] = k;
        if (k >= PLACED)
            continue;
        /* The plate at the left, alone; the stars to its right, maybe over each other. */
        placements[k] =
            k == 3
                ? (placed){k, 0, {40, 75}}
                : (placed){k, 0, {95 + 90.0 * rand() / RAND_MAX, 20 + 110.0 * rand() / RAND_MAX}};
        GEOSGeometry *there =
            shifted_copy(shapes[k].polygon, placements[k].at.x, placements[k].at.y);
        GEOSGeometry *grown = placed_union ? GEOSUnion_r(geos, placed_union, there) : there;
        if (placed_union) {
            GEOSGeom_destroy_r(geos, placed_union);
            GEOSGeom_destroy_r(geos, there);
        }
        placed_union = grown;
    }
    nester n = {.geos = geos,
                .count = PLACED + 2,
                .options = &options,
                .turn_count = 1,
                .class_of = class_of,
                .classes = classes,
                .class_count = PLACED + 2,
                .placements = placements,
                .placed_count = PLACED,
                .sheet_of = sheet_of,
                .sheet_count = 1,
                .sheet_slots = 1,
                .sheets = sheets,
                .cell_size = 10,
                .first_run = true};
    n.raster_shapes = calloc(PLACED + 2, sizeof *n.raster_shapes);
    assert_non_null(n.raster_shapes);
    check_raster_brought_up_to_date(&n, shapes, PLACED + 2);
    size_t ruled_out = 0, narrowed_count = 0;
    for (size_t piece = PLACED; piece < PLACED + 2; piece++)
        ruled_out += ask_raster(&n, piece, shapes[piece].polygon, placed_union, &narrowed_count);
    assert_true(narrowed_count > 100);
    assert_true(ruled_out > 300);
    /*
     * The star's other discs, in its arms, rule out more than its largest
     * alone (1,120 of the same 6,000 boxes against 1,007), and only
     * overlapping places (ask_raster checks).
     */
    assert_true(n.raster_shapes[PLACED].more_count > 0);
    size_t unused = 0;
    srand(7);
    size_t with_discs = ask_raster(&n, PLACED, shapes[PLACED].polygon, placed_union, &unused);
    n.raster_shapes[PLACED].more_count = 0;
    srand(7);
    size_t largest_only = ask_raster(&n, PLACED, shapes[PLACED].polygon, placed_union, &unused);
    assert_true(with_discs > largest_only);
    /* In the plate's hole, 30 mm square, the round piece has room: its middle is not ruled out. */
    double middle[4] = {placements[3].at.x - 1, placements[3].at.y - 1, placements[3].at.x + 1,
                        placements[3].at.y + 1};
    assert_int_not_equal(nest_raster_room(&n, 0, PLACED + 1, 0, middle, NULL), RASTER_NONE);
    n.placed_count = 0;
    sheets[0].version++;
    for (int q = 0; q < 300; q++) {
        double x = 200.0 * rand() / RAND_MAX, y = 150.0 * rand() / RAND_MAX;
        double box[4] = {x, y, x + 1, y + 1};
        assert_int_not_equal(nest_raster_room(&n, 0, PLACED, 0, box, NULL), RASTER_NONE);
    }
    nest_raster_free(&n);
    for (size_t k = 0; k < PLACED + 2; k++)
        GEOSGeom_destroy_r(geos, shapes[k].polygon);
    GEOSGeom_destroy_r(geos, placed_union);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_convex_parts_merge),
        cmocka_unit_test(test_bins_bound),
        cmocka_unit_test(test_pair_table),
        cmocka_unit_test(test_placed_index),
        cmocka_unit_test(test_raster_rules_out_only_overlaps),
    };
    return cmocka_run_group_tests(tests, geos_start, geos_finish);
}
