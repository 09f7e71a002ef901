/*
 * test_merge_lines.c: common-line cutting (ur_layout_merge_lines) on
 * layouts whose shared lengths are known by hand: squares side by side, a
 * 3 x 3 tiling, a T where one square meets the middle of a longer edge,
 * parts a little apart, and a square with a hole.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/nest.h"

#define TOLERANCE 0.01

static ur_piece rectangle(double w, double h)
{
    ur_piece piece;
    memset(&piece, 0, sizeof piece);
    ur_vec2 ring[4] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
    ur_error error;
    assert_int_equal(ur_piece_add_path(&piece, UR_OP_CUT, ring, 4, true, &error), UR_OK);
    return piece;
}

/* Every CUT path's length, open or closed. */
static double cut_length(const ur_piece *pieces, size_t count)
{
    double total = 0;
    for (size_t p = 0; p < count; p++)
        for (size_t k = 0; k < pieces[p].path_count; k++) {
            const ur_path *path = &pieces[p].paths[k];
            size_t segments = path->closed ? path->count : path->count ? path->count - 1 : 0;
            for (size_t i = 0; path->op == UR_OP_CUT && i < segments; i++)
                total += ur_vec2_distance(path->points[i], path->points[(i + 1) % path->count]);
        }
    return total;
}

/* One sheet with the pieces at the given offsets (and turns, radians). */
static ur_layout layout_of(const ur_vec2 *at, const double *turn, size_t count)
{
    ur_layout layout = {calloc(1, sizeof(ur_sheet)), 1, NULL, 0};
    assert_non_null(layout.sheets);
    layout.sheets[0].width = 1000;
    layout.sheets[0].height = 1000;
    layout.sheets[0].placements = calloc(count, sizeof(ur_placement));
    assert_non_null(layout.sheets[0].placements);
    layout.sheets[0].placement_count = count;
    for (size_t k = 0; k < count; k++)
        layout.sheets[0].placements[k] =
            (ur_placement){k, ur_transform2_make(turn ? turn[k] : 0, at[k])};
    return layout;
}

static double merge(ur_layout *layout, ur_piece *pieces, size_t count)
{
    double saved = -1;
    ur_error error;
    assert_int_equal(ur_layout_merge_lines(layout, pieces, count, TOLERANCE, &saved, &error),
                     UR_OK);
    return saved;
}

static void free_all(ur_layout *layout, ur_piece *pieces, size_t count)
{
    for (size_t k = 0; k < count; k++)
        ur_piece_free(&pieces[k]);
    ur_layout_free(layout);
}

/* Two 50 mm squares touching along x = 50 (the second off by a micrometre): 50 mm saved. */
static void test_two_squares_share_a_side(void **state)
{
    (void)state;
    ur_piece pieces[2] = {rectangle(50, 50), rectangle(50, 50)};
    ur_vec2 at[2] = {{10, 10}, {60.000001, 9.999999}};
    ur_layout layout = layout_of(at, NULL, 2);
    double before = cut_length(pieces, 2);
    double utilisation = ur_sheet_utilisation(&layout.sheets[0], pieces);
    assert_true(fabs(merge(&layout, pieces, 2) - 50) < 1e-5);
    assert_true(fabs(cut_length(pieces, 2) - (before - 50)) < 1e-5);
    /* The first is whole; the second's outline is one open path of three sides. */
    assert_true(pieces[0].paths[0].closed && !pieces[0].bridged);
    assert_true(pieces[1].bridged && !pieces[1].paths[0].closed);
    assert_int_equal(pieces[1].path_count, 1);
    assert_int_equal(pieces[1].paths[0].count, 4);
    /* The area the outline enclosed still counts. */
    assert_true(fabs(ur_sheet_utilisation(&layout.sheets[0], pieces) - utilisation) < 1e-12);
    free_all(&layout, pieces, 2);
}

/*
 * A 3 x 3 tiling of 20 mm squares: what is cut is the grid, 4 lines of 60
 * each way (480 mm) against 9 x 80 = 720 mm; the middle square, placed
 * last, has nothing left to cut.
 */
static void test_tiling_cuts_the_grid_once(void **state)
{
    (void)state;
    ur_piece pieces[9];
    ur_vec2 at[9];
    size_t order[9] = {0, 1, 2, 3, 5, 6, 7, 8, 4}; /* the middle one last */
    for (size_t k = 0; k < 9; k++) {
        pieces[k] = rectangle(20, 20);
        at[k] = (ur_vec2){100 + 20.0 * (double)(order[k] % 3), 100 + 20.0 * (double)(order[k] / 3)};
    }
    ur_layout layout = layout_of(at, NULL, 9);
    assert_true(fabs(merge(&layout, pieces, 9) - 240) < 1e-6);
    assert_true(fabs(cut_length(pieces, 9) - 480) < 1e-6);
    assert_int_equal(pieces[8].paths[0].count, 0);
    free_all(&layout, pieces, 9);
}

/*
 * A 30 mm square on the middle of a 100 x 20 bar, turned a quarter turn
 * (so its edges are rotated too): only the 30 mm it shares goes; the
 * square's sides that meet the bar keep their full length.
 */
static void test_t_junction_keeps_the_meeting_sides(void **state)
{
    (void)state;
    ur_piece pieces[2] = {rectangle(100, 20), rectangle(30, 30)};
    ur_vec2 at[2] = {{0, 0}, {65, 20}}; /* turned by 90 degrees: x from 35 to 65 */
    double turn[2] = {0, M_PI / 2};
    ur_layout layout = layout_of(at, turn, 2);
    assert_true(fabs(merge(&layout, pieces, 2) - 30) < 1e-6);
    assert_true(fabs(cut_length(pieces, 2) - (240 + 90)) < 1e-6);
    assert_int_equal(pieces[1].path_count, 1);
    assert_int_equal(pieces[1].paths[0].count, 4);
    free_all(&layout, pieces, 2);
}

/* Parts 0.1 mm apart (ten times the tolerance) share nothing. */
static void test_parts_apart_keep_their_cuts(void **state)
{
    (void)state;
    ur_piece pieces[2] = {rectangle(50, 50), rectangle(50, 50)};
    ur_vec2 at[2] = {{0, 0}, {50.1, 0}};
    ur_layout layout = layout_of(at, NULL, 2);
    assert_true(merge(&layout, pieces, 2) == 0);
    assert_true(pieces[1].paths[0].closed && pieces[1].paths[0].count == 4);
    assert_true(!pieces[1].bridged);
    free_all(&layout, pieces, 2);
}

/*
 * A 20 mm plug exactly filling a ring's 20 mm hole: the plug, placed
 * after, has nothing to cut; the ring keeps its hole.
 */
static void test_plug_in_a_hole(void **state)
{
    (void)state;
    ur_piece pieces[2] = {rectangle(60, 60), rectangle(20, 20)};
    ur_vec2 hole[4] = {{20, 20}, {20, 40}, {40, 40}, {40, 20}};
    ur_error error;
    assert_int_equal(ur_piece_add_path(&pieces[0], UR_OP_CUT, hole, 4, true, &error), UR_OK);
    ur_vec2 at[2] = {{0, 0}, {20, 20}};
    ur_layout layout = layout_of(at, NULL, 2);
    assert_true(fabs(merge(&layout, pieces, 2) - 80) < 1e-9);
    assert_true(pieces[0].paths[1].closed && pieces[0].paths[1].count == 4);
    assert_int_equal(pieces[1].paths[0].count, 0);
    free_all(&layout, pieces, 2);
}

static void test_refuses_no_tolerance(void **state)
{
    (void)state;
    ur_piece pieces[1] = {rectangle(10, 10)};
    ur_vec2 at[1] = {{0, 0}};
    ur_layout layout = layout_of(at, NULL, 1);
    double saved;
    ur_error error;
    assert_int_equal(ur_layout_merge_lines(&layout, pieces, 1, 0, &saved, &error), UR_ERROR_INPUT);
    free_all(&layout, pieces, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_squares_share_a_side),
        cmocka_unit_test(test_tiling_cuts_the_grid_once),
        cmocka_unit_test(test_t_junction_keeps_the_meeting_sides),
        cmocka_unit_test(test_parts_apart_keep_their_cuts),
        cmocka_unit_test(test_plug_in_a_hole),
        cmocka_unit_test(test_refuses_no_tolerance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
