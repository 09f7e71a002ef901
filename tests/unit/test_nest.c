/*
 * test_nest.c: true-shape nesting.  Placed parts never overlap and keep the
 * spacing (GEOS distance), stay inside the margin, are placed once each;
 * rectangles that tile a sheet exactly fill one sheet; a part goes in a
 * ring's hole when holes are allowed; L shapes interlock; parts with no
 * symmetry keep apart in 8 turns; the search over orders keeps every part
 * whatever its budget; a roll is shortened by the search.
 */
#include "test_support.h"
#include "test_geos.h"
#include <stdlib.h>

#include "nest_sets.h"
#include "unroll/nest.h"

static ur_piece rectangle(const char *name, double w, double h)
{
    ur_vec2 ring[4] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
    return polygon_piece(name, ring, 4);
}

static ur_piece l_shape(const char *name)
{
    ur_vec2 ring[6] = {{0, 0}, {60, 0}, {60, 20}, {20, 20}, {20, 60}, {0, 60}};
    return polygon_piece(name, ring, 6);
}

/* A placed piece as a GEOS polygon (outline and holes) in sheet coordinates. */
static GEOSGeometry *placed_polygon(const ur_piece *piece, ur_transform2 t)
{
    GEOSGeometry *shell = NULL, *holes[8];
    unsigned hole_count = 0;
    for (size_t k = 0; k < piece->path_count; k++) {
        const ur_path *path = &piece->paths[k];
        GEOSCoordSequence *s = GEOSCoordSeq_create_r(geos, (unsigned)path->count + 1, 2);
        for (size_t i = 0; i <= path->count; i++) {
            ur_vec2 p = ur_transform2_apply(t, path->points[i % path->count]);
            GEOSCoordSeq_setXY_r(geos, s, (unsigned)i, p.x, p.y);
        }
        GEOSGeometry *ring = GEOSGeom_createLinearRing_r(geos, s);
        if (k == 0)
            shell = ring;
        else
            holes[hole_count++] = ring;
    }
    return GEOSGeom_createPolygon_r(geos, shell, holes, hole_count);
}

/*
 * How deep two touching parts overlap, on average along the shorter
 * outline (mm): their common area over that outline's length.  The nester
 * lets parts overlap by a millionth of a millimetre (NEST_EXACT_FIT), so
 * that exact fits stay open; more is a true overlap.
 */
static double overlap_depth(const GEOSGeometry *a, const GEOSGeometry *b)
{
    GEOSGeometry *both = GEOSIntersection_r(geos, a, b);
    double area = 0, length_a = 0, length_b = 0;
    assert_non_null(both);
    assert_int_equal(GEOSArea_r(geos, both, &area), 1);
    assert_int_equal(GEOSLength_r(geos, a, &length_a), 1);
    assert_int_equal(GEOSLength_r(geos, b, &length_b), 1);
    GEOSGeom_destroy_r(geos, both);
    return area / fmin(length_a, length_b);
}

/* The invariants every layout keeps. */
static void check_layout(const ur_piece *pieces, size_t count, const ur_layout *layout,
                         const ur_nest_options *o)
{
    size_t *seen = calloc(count, sizeof *seen);
    for (size_t s = 0; s < layout->sheet_count; s++) {
        const ur_sheet *sheet = &layout->sheets[s];
        GEOSGeometry **placed = calloc(sheet->placement_count + 1, sizeof *placed);
        for (size_t p = 0; p < sheet->placement_count; p++) {
            const ur_placement *pl = &sheet->placements[p];
            seen[pl->piece_index]++;
            placed[p] = placed_polygon(&pieces[pl->piece_index], pl->transform);
            double x0, y0, x1, y1;
            GEOSGeom_getXMin_r(geos, placed[p], &x0);
            GEOSGeom_getYMin_r(geos, placed[p], &y0);
            GEOSGeom_getXMax_r(geos, placed[p], &x1);
            GEOSGeom_getYMax_r(geos, placed[p], &y1);
            assert_true(x0 >= o->margin - 1e-5 && y0 >= o->margin - 1e-5);
            assert_true(x1 <= sheet->width - o->margin + 1e-5);
            assert_true(y1 <= sheet->height - o->margin + 1e-5);
            for (size_t q = 0; q < p; q++) {
                double distance;
                assert_int_equal(GEOSDistance_r(geos, placed[p], placed[q], &distance), 1);
                double depth = distance > 0 ? 0 : overlap_depth(placed[p], placed[q]);
                if (distance < o->spacing - 1e-5 || depth > 1e-5)
                    fail_msg("parts %zu and %zu on sheet %zu are %g mm apart (overlap %g mm deep)",
                             p, q, s + 1, distance, depth);
            }
        }
        for (size_t p = 0; p < sheet->placement_count; p++)
            GEOSGeom_destroy_r(geos, placed[p]);
        free(placed);
    }
    for (size_t k = 0; k < count; k++)
        assert_int_equal(seen[k], 1);
    free(seen);
}

/* Nesting on sheets of w x h: margin, spacing, turns, holes allowed, no search. */
static ur_nest_options sheet_options(double w, double h, double margin, double spacing,
                                     size_t rotations, bool level)
{
    ur_nest_options o;
    memset(&o, 0, sizeof o);
    o.sheet_width = w;
    o.sheet_height = h;
    o.margin = margin;
    o.spacing = spacing;
    o.rotations = rotations;
    o.level = level;
    o.holes = true;
    return o;
}

static void free_pieces(ur_piece *pieces, size_t count)
{
    for (size_t k = 0; k < count; k++)
        ur_piece_free(&pieces[k]);
}

/* Nests the pieces on sheets, checks the layout and that it takes that many sheets. */
static void check_sheets_used(const ur_piece *pieces, size_t count, const ur_nest_options *o,
                              size_t sheets)
{
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, count, o, &layout, &error), UR_OK);
    assert_int_equal(layout.sheet_count, sheets);
    check_layout(pieces, count, &layout, o);
    ur_layout_free(&layout);
}

static void test_rectangles_tile_one_sheet(void **state)
{
    (void)state;
    ur_piece pieces[4];
    for (int k = 0; k < 4; k++)
        pieces[k] = rectangle("tile", 300, 200);
    ur_nest_options o = sheet_options(600, 400, 0, 0, 4, false);
    check_sheets_used(pieces, 4, &o, 1);
    free_pieces(pieces, 4);
}

/* What the placing callback heard: calls, and whether each counted one more part of all. */
typedef struct placing_heard {
    size_t calls, last;
    bool in_order;
} placing_heard;

static void hear_placing(void *context, size_t placed, size_t count)
{
    placing_heard *heard = context;
    heard->in_order = heard->in_order && placed == heard->last + 1 && count == 5;
    heard->last = placed;
    heard->calls++;
}

/* The first layout tells of each of its parts placed, once, in order; the search does not. */
static void test_placing_is_told(void **state)
{
    (void)state;
    ur_piece pieces[5];
    for (int k = 0; k < 5; k++)
        pieces[k] = rectangle("tile", 100 + 10 * k, 50);
    ur_nest_options o = sheet_options(600, 400, 0, 0, 4, false);
    placing_heard heard = {0, 0, true};
    o.placing = hear_placing;
    o.progress_context = &heard;
    o.time_budget = 0.05;
    check_sheets_used(pieces, 5, &o, 1);
    assert_int_equal(heard.calls, 5);
    assert_true(heard.in_order);
    free_pieces(pieces, 5);
}

/*
 * The search over orders places every part once and never ends worse than
 * its first layout, whatever the seed and budget.  With three parts many
 * of its tries give the order it already has; a budget too short for any
 * try places the first layout again, the same order as the run before it:
 * a run the same as the one before keeps every placement.
 */
static void test_search_keeps_every_part(void **state)
{
    (void)state;
    ur_piece pieces[3] = {rectangle("wide", 250, 120), rectangle("tall", 90, 260), l_shape("L")};
    ur_nest_options o = sheet_options(300, 300, 5, 3, 4, false);
    ur_layout first;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, 3, &o, &first, &error), UR_OK);
    for (uint64_t seed = 1; seed <= 12; seed++) {
        o.time_budget = seed % 2 ? 1e-9 : 0.2;
        o.seed = seed;
        ur_layout layout;
        assert_int_equal(ur_layout_nest(pieces, 3, &o, &layout, &error), UR_OK);
        assert_int_equal(layout.not_placed_count, 0);
        assert_true(layout.sheet_count <= first.sheet_count);
        check_layout(pieces, 3, &layout, &o);
        ur_layout_free(&layout);
    }
    ur_layout_free(&first);
    free_pieces(pieces, 3);
}

static void test_part_goes_in_a_hole(void **state)
{
    (void)state;
    ur_vec2 outer[4] = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    ur_vec2 inner[4] = {{20, 20}, {20, 80}, {80, 80}, {80, 20}};
    ur_piece pieces[2];
    pieces[0] = polygon_piece("ring", outer, 4);
    assert_int_equal(ur_piece_add_path(&pieces[0], UR_OP_CUT, inner, 4, true, NULL), UR_OK);
    pieces[0].measures.flat_area = 10000 - 3600;
    pieces[1] = rectangle("plug", 50, 50);
    ur_nest_options o = sheet_options(110, 110, 2, 2, 4, false);
    check_sheets_used(pieces, 2, &o, 1);
    o.holes = false; /* without holes the plug needs a sheet of its own */
    check_sheets_used(pieces, 2, &o, 2);
    free_pieces(pieces, 2);
}

/*
 * Two thin L shapes (arms 10 mm wide, 60 mm long) on a 74 x 74 sheet with
 * a 1 mm margin and spacing: their 60 x 60 boxes side by side need 121 mm,
 * but turned half a turn one sits in the other's corner (together 71 x 71)
 * and both fit one sheet.
 */
static void test_l_shapes_interlock(void **state)
{
    (void)state;
    ur_vec2 ring[6] = {{0, 0}, {60, 0}, {60, 10}, {10, 10}, {10, 60}, {0, 60}};
    ur_piece pieces[2] = {polygon_piece("L1", ring, 6), polygon_piece("L2", ring, 6)};
    ur_nest_options o = sheet_options(74, 74, 1, 1, 4, false);
    check_sheets_used(pieces, 2, &o, 1);
    free_pieces(pieces, 2);
}

/*
 * A key exactly as wide as a U's notch (60 mm) on a sheet exactly the U's
 * size: the only place for it is in the notch, touching both its sides.
 * Where the key fits is a line, not an area, and the no-fit polygon must
 * keep it open.
 */
static void test_part_fits_a_notch_exactly(void **state)
{
    (void)state;
    ur_vec2 u[8] = {{0, 0},   {100, 0}, {100, 100}, {80, 100},
                    {80, 20}, {20, 20}, {20, 100},  {0, 100}};
    ur_piece pieces[2] = {polygon_piece("U", u, 8), rectangle("key", 60, 70)};
    for (size_t rotations = 1; rotations <= 4; rotations *= 2) {
        ur_nest_options o = sheet_options(100, 100, 0, 0, rotations, false);
        check_sheets_used(pieces, 2, &o, 1);
    }
    free_pieces(pieces, 2);
}

static void test_mixed_parts_keep_apart(void **state)
{
    (void)state;
    enum { COUNT = 24 };
    ur_piece pieces[COUNT];
    for (int k = 0; k < COUNT; k++) {
        if (k % 3 == 0)
            pieces[k] = l_shape("L");
        else
            pieces[k] = rectangle("R", 30 + 7 * (k % 5), 15 + 11 * (k % 4));
    }
    ur_nest_options o = sheet_options(300, 200, 5, 3, 4, true);
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, COUNT, &o, &layout, &error), UR_OK);
    check_layout(pieces, COUNT, &layout, &o);
    /* Same input, same layout. */
    ur_layout again;
    assert_int_equal(ur_layout_nest(pieces, COUNT, &o, &again, &error), UR_OK);
    assert_int_equal(again.sheet_count, layout.sheet_count);
    for (size_t s = 0; s < layout.sheet_count; s++)
        assert_memory_equal(again.sheets[s].placements, layout.sheets[s].placements,
                            layout.sheets[s].placement_count * sizeof(ur_placement));
    ur_layout_free(&again);
    ur_layout_free(&layout);
    free_pieces(pieces, COUNT);
}

static void test_refusals(void **state)
{
    (void)state;
    ur_piece big = rectangle("big", 700, 100);
    ur_nest_options o = sheet_options(600, 400, 10, 2, 4, true);
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(&big, 1, &o, &layout, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "big"));
    o.margin = 300; /* nothing left inside the margin */
    assert_int_equal(ur_layout_nest(&big, 1, &o, &layout, &error), UR_ERROR_INPUT);
    ur_piece_free(&big);
}

/*
 * Remnants 200 x 120, 100 x 100 and 50 x 50 (5 mm margin, 2 mm spacing:
 * 190 x 110, 90 x 90 and 40 x 40 inside), then 600 x 400 stock.  Largest
 * first: 300 x 200 fits no remnant and opens a stock sheet; 150 x 100 fits
 * the first remnant; 80 x 80 finds no room beside it (190 - 150 - 2 = 38
 * across, 110 - 100 - 2 = 8 up) and goes on the second; 50 x 50 fits no
 * remnant's room left (38, 8, and 40 on the third) and joins the stock
 * sheet.  The third remnant, unused, is not in the layout.
 */
static void test_remnants_first(void **state)
{
    (void)state;
    ur_piece pieces[4] = {rectangle("A", 300, 200), rectangle("B", 150, 100),
                          rectangle("C", 80, 80), rectangle("D", 50, 50)};
    ur_remnant remnants[3] = {{200, 120}, {100, 100}, {50, 50}};
    ur_nest_options o = sheet_options(600, 400, 5, 2, 1, false);
    o.remnants = remnants;
    o.remnant_count = 3;
    o.max_sheets = 1; /* stock sheets only: the remnants come on top */
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, 4, &o, &layout, &error), UR_OK);
    assert_int_equal(layout.sheet_count, 3);
    assert_int_equal(layout.not_placed_count, 0);
    const ur_sheet *s = layout.sheets;
    assert_true(s[0].remnant && s[1].remnant && !s[2].remnant);
    assert_true(s[0].width == 200 && s[0].height == 120 && s[1].width == 100 &&
                s[1].height == 100 && s[2].width == 600 && s[2].height == 400);
    assert_int_equal(s[0].placement_count, 1);
    assert_int_equal(s[0].placements[0].piece_index, 1);
    assert_int_equal(s[1].placement_count, 1);
    assert_int_equal(s[1].placements[0].piece_index, 2);
    assert_int_equal(s[2].placement_count, 2);
    check_layout(pieces, 4, &layout, &o);
    ur_layout_free(&layout);
    remnants[1].width = 0;
    assert_int_equal(ur_layout_nest(pieces, 4, &o, &layout, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "remnant 2"));
    free_pieces(pieces, 4);
}

/*
 * Strips whose rulings lie at 30 degrees, in a material whose rulings must
 * run along the grain (the sheet's x axis) within 10 degrees: every placed
 * strip's rulings are turned to within 10 degrees of x, whichever end first.
 */
static void test_grain_rule_holds(void **state)
{
    (void)state;
    enum { COUNT = 6 };
    ur_piece pieces[COUNT];
    for (int k = 0; k < COUNT; k++) {
        pieces[k] = rectangle("strip", 120, 30);
        pieces[k].has_rulings = true;
        pieces[k].ruling_angle = M_PI / 6;
    }
    ur_nest_options o = sheet_options(300, 200, 5, 2, 4, false);
    o.grain = true;
    o.grain_angle = 0;
    o.grain_tolerance = 10 * M_PI / 180;
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, COUNT, &o, &layout, &error), UR_OK);
    check_layout(pieces, COUNT, &layout, &o);
    for (size_t s = 0; s < layout.sheet_count; s++)
        for (size_t p = 0; p < layout.sheets[s].placement_count; p++) {
            ur_transform2 t = layout.sheets[s].placements[p].transform;
            double rulings = atan2(t.sine, t.cosine) + M_PI / 6; /* on the sheet */
            double off = remainder(rulings, M_PI);               /* from the grain, -90..90 */
            if (fabs(off) > 10 * M_PI / 180 + 1e-9)
                fail_msg("rulings at %g degrees to the grain", off * 180 / M_PI);
        }
    ur_layout_free(&layout);
    free_pieces(pieces, COUNT);
}

/* The turn of a placement, degrees, in 0 .. 360. */
static double degrees_of(ur_transform2 t)
{
    double angle = atan2(t.sine, t.cosine) * 180 / M_PI;
    return angle < -1e-9 ? angle + 360 : fabs(angle);
}

/*
 * Under a grain rule, strips with rulings keep to it; L shapes without
 * rulings turn in the nesting's 4 quarter turns, not in the rule's steps;
 * L shapes with their own rotations of 1 do not turn at all.
 */
static void test_turns_of_each_piece(void **state)
{
    (void)state;
    enum { STRIPS = 3, FREE = 4, FIXED = 4, COUNT = STRIPS + FREE + FIXED };
    ur_piece pieces[COUNT];
    for (int k = 0; k < COUNT; k++) {
        pieces[k] =
            k < STRIPS ? rectangle("strip", 120, 30) : l_shape(k < STRIPS + FREE ? "L" : "fixed");
        pieces[k].has_rulings = k < STRIPS;
        pieces[k].ruling_angle = k < STRIPS ? M_PI / 6 : NAN;
        pieces[k].rotations = k >= STRIPS + FREE ? 1 : 0;
    }
    ur_nest_options o = sheet_options(300, 200, 5, 2, 4, false);
    o.grain = true;
    o.grain_angle = 0;
    o.grain_tolerance = 10 * M_PI / 180;
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, COUNT, &o, &layout, &error), UR_OK);
    check_layout(pieces, COUNT, &layout, &o);
    for (size_t s = 0; s < layout.sheet_count; s++)
        for (size_t p = 0; p < layout.sheets[s].placement_count; p++) {
            const ur_placement *placement = &layout.sheets[s].placements[p];
            double angle = degrees_of(placement->transform);
            size_t k = placement->piece_index;
            if (k < STRIPS) {
                double off = remainder(angle + 30, 180);
                if (fabs(off) > 10 + 1e-9)
                    fail_msg("rulings at %g degrees to the grain", off);
            } else if (k < STRIPS + FREE) {
                if (fabs(remainder(angle, 90)) > 1e-9)
                    fail_msg("an L shape turned by %g degrees", angle);
            } else if (fabs(remainder(angle, 360)) > 1e-9)
                fail_msg("an L shape that may not turn turned by %g degrees", angle);
        }
    ur_layout_free(&layout);
    free_pieces(pieces, COUNT);
}

/* Part k of a mix of three shapes with no symmetry: an L, a right triangle, a hook. */
static ur_piece asymmetric_piece(int k)
{
    ur_vec2 l[6] = {{0, 0}, {50, 0}, {50, 10}, {10, 10}, {10, 25}, {0, 25}};
    ur_vec2 triangle[3] = {{0, 0}, {40, 0}, {0, 15}};
    ur_vec2 hook[8] = {{0, 0}, {30, 0}, {30, 30}, {10, 30}, {10, 20}, {20, 20}, {20, 8}, {0, 8}};
    return k % 3 == 0   ? polygon_piece("L", l, 6)
           : k % 3 == 1 ? polygon_piece("triangle", triangle, 3)
                        : polygon_piece("hook", hook, 8);
}

/*
 * Parts with no symmetry (an L of unequal arms, a right triangle and a
 * hooked shape) in 8 turns, packed tightly: most no-fit polygons the
 * nester uses are others turned, and a wrong turn shows as an overlap.
 * The sheet is several of the nester's grid cells across and up, so parts
 * also meet across the cells' edges.
 */
static void test_turned_parts_keep_apart(void **state)
{
    (void)state;
    enum { COUNT = 60 };
    ur_piece pieces[COUNT];
    for (int k = 0; k < COUNT; k++)
        pieces[k] = asymmetric_piece(k);
    ur_nest_options o = sheet_options(260, 200, 2, 1, 8, false);
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, COUNT, &o, &layout, &error), UR_OK);
    check_layout(pieces, COUNT, &layout, &o);
    ur_layout_free(&layout);
    free_pieces(pieces, COUNT);
}

/*
 * Parts on a roll, the first layout alone (no time) and then shortened by
 * the search (a few seconds, by one search or several side by side): all
 * keep the invariants, the search's strip is shorter than the first
 * layout's, and no strip is shorter than the parts' area over the roll's
 * width.
 */
static double roll_length_of(const ur_piece *pieces, size_t count, double budget, double margin,
                             double spacing, size_t threads)
{
    ur_nest_options o = sheet_options(1, 1, margin, spacing, 4, false);
    o.roll_width = 120;
    o.time_budget = budget;
    o.seed = 3;
    o.threads = threads;
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, count, &o, &layout, &error), UR_OK);
    assert_int_equal(layout.sheet_count, 1);
    o.sheet_width = layout.sheets[0].width;
    o.sheet_height = o.roll_width;
    check_layout(pieces, count, &layout, &o);
    double length = layout.sheets[0].width;
    ur_layout_free(&layout);
    return length;
}

static void test_roll_is_shortened(void **state)
{
    (void)state;
    enum { COUNT = 30 };
    ur_piece pieces[COUNT];
    double area = 0;
    for (int k = 0; k < COUNT; k++) {
        pieces[k] = asymmetric_piece(k);
        area += pieces[k].measures.flat_area;
    }
    double first = roll_length_of(pieces, COUNT, 0, 2, 1, 1);
    double searched = roll_length_of(pieces, COUNT, 3, 2, 1, 1);
    /* More searches than this machine may have processors: they still share their best. */
    double side_by_side = roll_length_of(pieces, COUNT, 3, 2, 1, 3);
    print_message("roll: first layout %.2f mm, searched %.2f mm (3 side by side %.2f mm), "
                  "area bound %.2f mm\n",
                  first, searched, side_by_side, area / 116 + 4);
    assert_true(searched < first - 1);
    assert_true(side_by_side < first - 1);
    assert_true(searched >= area / 116 + 4);
    assert_true(side_by_side >= area / 116 + 4);
    /*
     * With no margin or spacing, parts pushed against the roll's edges sit
     * at whole millimetres, level with corners of their no-fit polygons,
     * where a point's inside test is most easily misled by rounding.
     */
    first = roll_length_of(pieces, COUNT, 0, 0, 0, 1);
    searched = roll_length_of(pieces, COUNT, 3, 0, 0, 2);
    assert_true(searched < first);
    assert_true(searched >= area / 120);
    free_pieces(pieces, COUNT);
}

/*
 * The outline of an unfolded UV sphere's largest piece (tests/data/nest/):
 * a long zigzag of 1,874 points.  Levelled and grown by 1 mm (2 mm apart,
 * as on the CO2 laser's profile), GEOS 3.11 fails to triangulate it whole;
 * nesting must still place two of it, apart.
 */
static void test_long_zigzag_nests(void **state)
{
    (void)state;
    FILE *file = fopen("tests/data/nest/sphere-net.csv", "r");
    assert_non_null(file);
    ur_vec2 *ring = NULL;
    size_t count = 0, room = 0;
    char line[128];
    while (fgets(line, sizeof line, file)) {
        ur_vec2 p;
        if (line[0] == '#' || sscanf(line, "%lf,%lf", &p.x, &p.y) != 2)
            continue;
        if (count == room) {
            room = room ? 2 * room : 256;
            ring = realloc(ring, room * sizeof *ring);
            assert_non_null(ring);
        }
        ring[count++] = p;
    }
    fclose(file);
    assert_true(count > 1000);
    ur_piece pieces[2] = {polygon_piece("Z1", ring, count), polygon_piece("Z2", ring, count)};
    free(ring);
    ur_nest_options o = sheet_options(1000, 1000, 5, 2, 4, true);
    check_sheets_used(pieces, 2, &o, 1);
    free_pieces(pieces, 2);
}

/* ---- The sheet search ------------------------------------------------------ */

/* The length a roll as wide as the options' sheet is tall takes (threads: 1). */
static double roll_for(const ur_piece *pieces, size_t count, const ur_nest_options *sheets,
                       double budget)
{
    ur_nest_options o = *sheets;
    o.roll_width = sheets->sheet_height;
    o.time_budget = budget;
    o.threads = 1;
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, count, &o, &layout, &error), UR_OK);
    assert_int_equal(layout.sheet_count, 1);
    o.sheet_width = layout.sheets[0].width;
    check_layout(pieces, count, &layout, &o);
    double length = layout.sheets[0].width;
    ur_layout_free(&layout);
    return length;
}

/* The sheets a layout uses, checked (check_layout), with the search's budget. */
static size_t sheets_for(const ur_piece *pieces, size_t count, ur_nest_options *o, double budget)
{
    o->time_budget = budget;
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, count, o, &layout, &error), UR_OK);
    check_layout(pieces, count, &layout, o);
    size_t sheets = layout.sheet_count;
    ur_layout_free(&layout);
    return sheets;
}

/*
 * A band 230 x 120 mm with a disc of radius 60 on its long side near one
 * end, as a cylinder's side and cap unfold: the least area any turned box
 * of it has, found by trying every hundredth of a degree, is what
 * ur_outline_level_size gives, about 240 x 240 mm.  The narrowest box
 * (GEOS's MinimumRotatedRectangle before 3.12) is 234 x 312 mm, too long
 * for a 250 mm square room the smallest box fits; so was a Blender
 * cylinder's net on A3.
 */
static void test_level_box_is_the_smallest(void **state)
{
    (void)state;
    enum { ARC = 64 };
    ur_vec2 outline[4 + ARC];
    size_t count = 0;
    outline[count++] = ur_vec2_make(0, 0);
    outline[count++] = ur_vec2_make(230, 0);
    outline[count++] = ur_vec2_make(230, 120);
    for (size_t k = 0; k < ARC; k++) { /* round the disc from where it touches the band */
        double t = -M_PI / 2 + 2 * M_PI * (double)k / ARC;
        outline[count++] = ur_vec2_make(50 + 60 * cos(t), 180 + 60 * sin(t));
    }
    outline[count++] = ur_vec2_make(0, 120);
    double least = INFINITY;
    for (int step = 0; step < 18000; step++) {
        ur_box box = turned_box_of(outline, count, step * M_PI / 18000);
        least = fmin(least, ur_box_width(box) * ur_box_height(box));
    }
    double length, width;
    ur_error error;
    assert_int_equal(ur_outline_level_size(outline, count, &length, &width, &error), UR_OK);
    print_message("level box %.2f x %.2f = %.0f mm2, least by search %.0f mm2\n", length, width,
                  length * width, least);
    assert_true(length * width <= least * (1 + 1e-6) + 1e-6);
    assert_true(length >= width && length <= 250);
}

/*
 * Strips 110 x 2 mm fit a 110 x 60 mm sheet with a 5 mm margin (100 x 50
 * mm inside) neither level nor on end, but diagonally: turned so that
 * their length takes cos a = 0.9 of it, 99.9 x 49.8 mm (2 mm across at
 * sin a = 0.436 adds 0.87 and 1.8 mm).  Nesting turns them so, one to a
 * sheet, and ur_outline_fit_turn gives such a turn; a 112 mm strip is
 * longer than the 111.8 mm diagonal and fits no way.
 */
static void test_strip_fits_diagonally(void **state)
{
    (void)state;
    ur_vec2 ring[4] = {{0, 0}, {110, 0}, {110, 2}, {0, 2}};
    ur_piece pieces[2] = {polygon_piece("strip", ring, 4), polygon_piece("strip", ring, 4)};
    ur_nest_options o = sheet_options(110, 60, 5, 1, 2, true);
    check_sheets_used(pieces, 2, &o, 2); /* a second one beside it would stick out */
    free_pieces(pieces, 2);

    bool fits;
    double angle;
    ur_error error;
    assert_int_equal(ur_outline_fit_turn(ring, 4, 100, 50, &fits, &angle, &error), UR_OK);
    assert_true(fits);
    ur_transform2 turn = ur_transform2_make(angle, ur_vec2_make(0, 0));
    ur_box box = ur_box_empty();
    for (int k = 0; k < 4; k++)
        ur_box_add(&box, ur_transform2_apply(turn, ring[k]));
    assert_true(ur_box_width(box) <= 100 && ur_box_height(box) <= 50);
    ring[1].x = ring[2].x = 112;
    assert_int_equal(ur_outline_fit_turn(ring, 4, 100, 50, &fits, &angle, &error), UR_OK);
    assert_false(fits);
}

/*
 * A set that the first layout puts on two sheets though its area fits
 * one: where the roll search (a roll as wide as the sheet is tall) fits it
 * in a sheet's length, the sheet search puts it on one sheet, every part
 * apart (GEOS); in general on no more sheets than the roll's length
 * shows enough.  The sheet search has four times the roll's budget: it
 * shares its budget with the search over orders and the last sheet's, and
 * the machine may be slow (a sanitizer's build, other work: twice the
 * budget failed under ASan with five other builds running).
 */
static void check_sheets_at_the_roll(ur_piece *pieces, size_t count, double width, double height,
                                     double budget)
{
    ur_nest_options o = sheet_options(width, height, 0, 1, 4, false);
    o.seed = 1;
    double area = 0;
    for (size_t k = 0; k < count; k++)
        area += pieces[k].measures.flat_area;
    assert_true(area <= width * height); /* the area bound: one sheet */
    size_t first = sheets_for(pieces, count, &o, 0);
    double roll = roll_for(pieces, count, &o, budget);
    size_t searched = sheets_for(pieces, count, &o, 4 * budget);
    print_message("%s...: first layout %zu sheets, roll %.1f mm of %g, searched %zu sheets\n",
                  pieces[0].name, first, roll, width, searched);
    assert_int_equal(first, 2); /* else the set tests nothing */
    assert_true((double)searched <= ceil(roll / width));
}

/*
 * Identical concave parts that must interlock: 40 curved strips (66 % of
 * a 600 x 400 sheet) and 36 crescents (74 %); and 32 irregular parts (16
 * shapes, two of each: 72 % of 300 x 200).  The roll fits each in one
 * sheet's length within its budget but under the heaviest load, and then
 * the sheet search must put it on one sheet.
 */
static void test_sheets_as_few_as_the_roll_shows(void **state)
{
    (void)state;
    ur_piece pieces[40];
    assert_true(nest_set_strips(pieces, 40));
    nest_set_fill(pieces, 40, 0.66, 600, 400);
    check_sheets_at_the_roll(pieces, 40, 600, 400, 2);
    free_pieces(pieces, 40);
    assert_true(nest_set_crescents(pieces, 36));
    nest_set_fill(pieces, 36, 0.74, 600, 400);
    check_sheets_at_the_roll(pieces, 36, 600, 400, 2);
    free_pieces(pieces, 36);
    assert_true(nest_set_irregular(pieces, 16, 1));
    for (size_t k = 0; k < 16; k++)
        assert_int_equal(ur_piece_copy(&pieces[k], &pieces[16 + k], NULL), UR_OK);
    nest_set_fill(pieces, 32, 0.72, 300, 200);
    check_sheets_at_the_roll(pieces, 32, 300, 200, 2);
    free_pieces(pieces, 32);
}

/* The largest x any placed part reaches on a sheet (GEOS). */
static double right_edge_of(const ur_piece *pieces, const ur_sheet *sheet)
{
    double right = 0;
    for (size_t p = 0; p < sheet->placement_count; p++) {
        const ur_placement *pl = &sheet->placements[p];
        GEOSGeometry *g = placed_polygon(&pieces[pl->piece_index], pl->transform);
        double x1;
        assert_int_equal(GEOSGeom_getXMax_r(geos, g, &x1), 1);
        right = fmax(right, x1);
        GEOSGeom_destroy_r(geos, g);
    }
    return right;
}

/*
 * Curved strips alike, a sheet's area (two sheets inside the margin): the
 * last sheet's parts are pushed to its left end, the offcut the layout
 * reports is what they leave there (GEOS), and it is larger than the
 * first layout's.
 */
static void test_last_sheet_leaves_an_offcut(void **state)
{
    (void)state;
    enum { COUNT = 40 };
    ur_piece pieces[COUNT];
    assert_true(nest_set_strips(pieces, COUNT));
    nest_set_fill(pieces, COUNT, 1.0, 600, 400);
    ur_nest_options o = sheet_options(600, 400, 5, 2, 4, false);
    o.seed = 1;
    o.threads = 1;
    double offcut[2];
    for (int run = 0; run < 2; run++) {
        o.time_budget = run == 0 ? 0 : 2;
        ur_layout layout;
        ur_error error;
        assert_int_equal(ur_layout_nest(pieces, COUNT, &o, &layout, &error), UR_OK);
        check_layout(pieces, COUNT, &layout, &o);
        assert_int_equal(layout.sheet_count, 2);
        const ur_sheet *last = &layout.sheets[1];
        assert_true(layout.sheets[0].offcut_width == 0);
        offcut[run] = last->offcut_width;
        assert_true(fabs(offcut[run] - (600 - right_edge_of(pieces, last) - o.spacing)) < 1e-6);
        ur_layout_free(&layout);
    }
    print_message("offcut: first layout %.1f mm, searched %.1f mm\n", offcut[0], offcut[1]);
    assert_true(offcut[1] > offcut[0]);
    free_pieces(pieces, COUNT);
}

/*
 * The sheet search with a remnant and a grain rule: strips whose rulings
 * must keep within 10 degrees of the grain, on a remnant first and then
 * on as few stock sheets as the first layout or fewer; the rule holds.
 */
static void test_sheet_search_keeps_remnants_and_grain(void **state)
{
    (void)state;
    enum { COUNT = 14 };
    ur_piece pieces[COUNT];
    for (int k = 0; k < COUNT; k++) {
        pieces[k] = rectangle("strip", 120 - 3 * k, 30);
        pieces[k].has_rulings = true;
        pieces[k].ruling_angle = M_PI / 6;
    }
    ur_remnant remnant = {150, 100};
    ur_nest_options o = sheet_options(300, 200, 5, 2, 4, false);
    o.grain = true;
    o.grain_tolerance = 10 * M_PI / 180;
    o.remnants = &remnant;
    o.remnant_count = 1;
    size_t first = sheets_for(pieces, COUNT, &o, 0);
    o.time_budget = 1;
    ur_layout layout;
    ur_error error;
    assert_int_equal(ur_layout_nest(pieces, COUNT, &o, &layout, &error), UR_OK);
    check_layout(pieces, COUNT, &layout, &o);
    assert_true(layout.sheet_count <= first);
    assert_true(layout.sheets[0].remnant && layout.sheets[0].width == 150);
    for (size_t s = 1; s < layout.sheet_count; s++)
        assert_false(layout.sheets[s].remnant);
    for (size_t s = 0; s < layout.sheet_count; s++)
        for (size_t p = 0; p < layout.sheets[s].placement_count; p++) {
            ur_transform2 t = layout.sheets[s].placements[p].transform;
            double off = remainder(atan2(t.sine, t.cosine) + M_PI / 6, M_PI);
            if (fabs(off) > 10 * M_PI / 180 + 1e-9)
                fail_msg("rulings at %g degrees to the grain", off * 180 / M_PI);
        }
    ur_layout_free(&layout);
    free_pieces(pieces, COUNT);
}

/* A comb: a spine w x 6 with teeth 2 wide and h long, one every 4, over a gap of 2. */
static ur_piece comb(const char *name, size_t teeth, double h)
{
    ur_vec2 ring[4 * 64 + 4];
    size_t n = 0;
    double w = 4.0 * (double)teeth;
    ring[n++] = ur_vec2_make(0, 0);
    ring[n++] = ur_vec2_make(w, 0);
    ring[n++] = ur_vec2_make(w, 6);
    for (size_t k = teeth; k-- > 0;) {
        double x = 4.0 * (double)k;
        ring[n++] = ur_vec2_make(x + 3, 6);
        ring[n++] = ur_vec2_make(x + 3, 6 + h);
        ring[n++] = ur_vec2_make(x + 1, 6 + h);
        ring[n++] = ur_vec2_make(x + 1, 6);
    }
    ring[n++] = ur_vec2_make(0, 6);
    return polygon_piece(name, ring, n);
}

/*
 * A search cut short by its budget ends without a failure and keeps what it
 * had.  Combs of many teeth, each of its own length, make no-fit polygons of
 * thousands of convex sums, which the sheet search makes as it needs them:
 * with a budget of a twentieth of a second the deadline passes while it
 * makes the first.  It used to go on making them all (past its budget by
 * seconds on the nets of a sphere); now it stops there, and a search that
 * stops so must not report running out of memory.
 */
static void test_search_cut_short_by_its_budget(void **state)
{
    (void)state;
    enum { COUNT = 8 };
    ur_piece pieces[COUNT];
    for (int k = 0; k < COUNT; k++) {
        char name[16];
        snprintf(name, sizeof name, "comb%d", k);
        pieces[k] = comb(name, 40 + 2 * (size_t)k, 20 + k);
    }
    ur_nest_options o = sheet_options(400, 120, 5, 2, 2, false);
    size_t first = sheets_for(pieces, COUNT, &o, 0);
    assert_true(first >= 2); /* something for the sheet search to try */
    assert_true(sheets_for(pieces, COUNT, &o, 0.05) <= first);
    free_pieces(pieces, COUNT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rectangles_tile_one_sheet),
        cmocka_unit_test(test_search_cut_short_by_its_budget),
        cmocka_unit_test(test_level_box_is_the_smallest),
        cmocka_unit_test(test_strip_fits_diagonally),
        cmocka_unit_test(test_part_goes_in_a_hole),
        cmocka_unit_test(test_search_keeps_every_part),
        cmocka_unit_test(test_l_shapes_interlock),
        cmocka_unit_test(test_part_fits_a_notch_exactly),
        cmocka_unit_test(test_mixed_parts_keep_apart),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_grain_rule_holds),
        cmocka_unit_test(test_remnants_first),
        cmocka_unit_test(test_turns_of_each_piece),
        cmocka_unit_test(test_turned_parts_keep_apart),
        cmocka_unit_test(test_roll_is_shortened),
        cmocka_unit_test(test_long_zigzag_nests),
        cmocka_unit_test(test_placing_is_told),
        cmocka_unit_test(test_sheets_as_few_as_the_roll_shows),
        cmocka_unit_test(test_last_sheet_leaves_an_offcut),
        cmocka_unit_test(test_sheet_search_keeps_remnants_and_grain),
    };
    return cmocka_run_group_tests(tests, geos_start, geos_finish);
}
