/*
 * test_split_part.c: parts too long for a sheet cut to fit
 * (ur_part_split): the fewest parts, each within the room, areas kept,
 * the two sides of every cut paired as one seam, the cut through the
 * narrowest place in reach, holes kept or opened.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "unroll/nest.h"

static ur_piece part_of(const ur_vec2 *ring, size_t count)
{
    ur_piece piece;
    memset(&piece, 0, sizeof piece);
    snprintf(piece.name, sizeof piece.name, "bar");
    ur_error error;
    assert_int_equal(ur_piece_add_path(&piece, UR_OP_CUT, ring, count, true, &error), UR_OK);
    return piece;
}

static double total_area(const ur_split_parts *split)
{
    double area = 0;
    for (size_t k = 0; k < split->nets.count; k++) {
        const ur_piece *piece = &split->pieces[k];
        area += fabs(ur_polygon_signed_area(piece->paths[0].points, piece->paths[0].count));
        for (size_t h = 1; h < piece->path_count; h++)
            area -= fabs(ur_polygon_signed_area(piece->paths[h].points, piece->paths[h].count));
    }
    return area;
}

/* 1000 x 50 into 400 x 100 rooms: 3 parts, each at most 400 long, 2 seams of two sides. */
static void test_bar_in_three(void **state)
{
    (void)state;
    ur_vec2 ring[4] = {{0, 0}, {1000, 0}, {1000, 50}, {0, 50}};
    ur_piece bar = part_of(ring, 4);
    ur_split_parts split = {{NULL, 0}, NULL};
    ur_error error;
    assert_int_equal(ur_part_split(&bar, 400, 100, 0, &split, &error), UR_OK);
    assert_int_equal(split.nets.count, 3);
    assert_true(fabs(total_area(&split) - 50000) < 1e-6);
    for (size_t k = 0; k < 3; k++) {
        double length, width;
        const ur_path *outline = &split.pieces[k].paths[0];
        assert_int_equal(
            ur_outline_level_size(outline->points, outline->count, &length, &width, &error), UR_OK);
        assert_true(length <= 400 + 1e-9 && fabs(width - 50) < 1e-9);
    }
    int next = 0;
    assert_int_equal(ur_net_list_find_seams(&split.nets, 1, &next, &error), UR_OK);
    assert_int_equal(next, 3); /* seams 1 and 2 */
    size_t sides[3] = {0, 0, 0};
    for (size_t k = 0; k < 3; k++)
        for (size_t s = 0; s < split.nets.nets[k].seam_side_count; s++)
            sides[split.nets.nets[k].seam_sides[s].seam]++;
    assert_int_equal(sides[1], 2);
    assert_int_equal(sides[2], 2);
    ur_split_parts_free(&split);
    ur_piece_free(&bar);
}

/*
 * An 800 x 100 bar with a square hole, cut for rooms of 500: into 2, the
 * paths the parts have between them (2 outlines and the holes left), and
 * the area kept.
 */
static void split_with_hole(const ur_vec2 hole[4], size_t paths, double area)
{
    ur_vec2 ring[4] = {{0, 0}, {800, 0}, {800, 100}, {0, 100}};
    ur_piece bar = part_of(ring, 4);
    ur_error error;
    assert_int_equal(ur_piece_add_path(&bar, UR_OP_CUT, hole, 4, true, &error), UR_OK);
    ur_split_parts split = {{NULL, 0}, NULL};
    assert_int_equal(ur_part_split(&bar, 500, 200, 0, &split, &error), UR_OK);
    assert_int_equal(split.nets.count, 2);
    assert_int_equal(split.pieces[0].path_count + split.pieces[1].path_count, paths);
    assert_true(fabs(total_area(&split) - area) < 1e-6);
    ur_split_parts_free(&split);
    ur_piece_free(&bar);
}

/*
 * A 60 mm hole at the middle: the shortest cut within reach of x = 400
 * (+- 50) goes through the hole (40 mm of cut instead of 100), which
 * becomes a notch in both parts.
 */
static void test_cut_through_the_hole(void **state)
{
    (void)state;
    ur_vec2 hole[4] = {{370, 20}, {370, 80}, {430, 80}, {430, 20}};
    split_with_hole(hole, 2, 80000 - 3600);
}

/* A 20 mm hole away from the cut stays a hole of its part. */
static void test_hole_kept(void **state)
{
    (void)state;
    ur_vec2 hole[4] = {{90, 40}, {90, 60}, {110, 60}, {110, 40}};
    split_with_hole(hole, 3, 80000 - 400);
}

/* Too wide for cuts across its length to help. */
static void test_too_wide(void **state)
{
    (void)state;
    ur_vec2 ring[4] = {{0, 0}, {1000, 0}, {1000, 300}, {0, 300}};
    ur_piece bar = part_of(ring, 4);
    ur_split_parts split = {{NULL, 0}, NULL};
    ur_error error;
    assert_int_equal(ur_part_split(&bar, 400, 200, 0, &split, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "wide"));
    assert_int_equal(split.nets.count, 0);
    ur_split_parts_free(&split);
    ur_piece_free(&bar);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bar_in_three),
        cmocka_unit_test(test_cut_through_the_hole),
        cmocka_unit_test(test_hole_kept),
        cmocka_unit_test(test_too_wide),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
