/*
 * test_clearance.c: what a joint must keep clear of on its piece
 * (clearance.c's board), on outlines drawn here: the neighbouring outline
 * edge at a tab's corner is no clash, an edge that does not share a
 * corner must stay the gap away from the tab (the grown region's side is
 * exact along a straight edge of the tab, so 0.05 mm either side of the
 * gap decides), and a tab on a stretch whose middle point bends into it
 * (a ring that is not convex, grown without GEOS's buffer) keeps the same
 * gap.
 */
#include "test_support.h"
#include "test_geos.h"

#include "../../src/allow/allow_internal.h" /* internal: the board joints are tested on */

#define GAP 1.0
#define REACH 10.0

/*
 * What the board says of a tab 5 mm deep at 45 degrees on the floor of
 * outline (count points, counter-clockwise) from (40, 0) to (0, 0), over
 * its edges [first, first + edges), the floor's middle point (if any) at
 * middle.
 */
static allow_blocker verdict_of(const ur_vec2 *outline, size_t count, size_t first, size_t edges,
                                const ur_vec2 *middle)
{
    allow_board *board;
    ur_error error;
    assert_int_equal(allow_board_open(geos, outline, count, REACH, GAP, &board, &error), UR_OK);
    ur_vec2 base[3] = {{40, 0}, {0, 0}, {0, 0}};
    ur_vec2 ring[5] = {{0, 0}, {40, 0}, {35, 5}, {5, 5}, {0, 0}};
    size_t base_count = 2, ring_count = 4;
    if (middle) {
        base[1] = *middle;
        base[2] = ur_vec2_make(0, 0);
        base_count = 3;
        ring[1] = *middle;
        ring[2] = ur_vec2_make(40, 0);
        ring[3] = ur_vec2_make(35, 5);
        ring[4] = ur_vec2_make(5, 5);
        ring_count = 5;
    }
    GEOSGeometry *tab = polygon(ring, ring_count);
    allow_verdict verdict;
    assert_int_equal(allow_board_test(board, tab, base, base_count, first, edges, &verdict, &error),
                     UR_OK);
    GEOSGeom_destroy_r(geos, tab);
    allow_board_close(board);
    return verdict.by;
}

/*
 * An L: the tab's edge ends at the inner corner (0, 0), where the next
 * edge runs up beside the tab's side, within the gap of it for 1.4 mm
 * from the corner, as every tab beside a concave corner of a net is: no
 * clash.  Nor is the edge before it, which meets the tab's other end.
 */
static void test_neighbour_at_the_corner_is_no_clash(void **state)
{
    (void)state;
    const ur_vec2 l[] = {{-30, -30}, {40, -30}, {40, 0}, {0, 0}, {0, 30}, {-30, 30}};
    assert_int_equal(verdict_of(l, 6, 2, 1, NULL), ALLOW_BLOCKED_NOT);
}

/* A slot h mm high over the tab's floor: its roof shares no corner with the tab's edges. */
static allow_blocker verdict_in_slot(double h, const ur_vec2 *middle)
{
    ur_vec2 slot[9] = {{-30, -30}, {40, -30},    {40, 0},       {0, 0}, {0, h},
                       {40, h},    {40, h + 10}, {-30, h + 10}, {0, 0}};
    size_t count = 8, edges = 1;
    if (middle) { /* the floor through the middle point: one more edge under the tab */
        memmove(slot + 4, slot + 3, 5 * sizeof *slot);
        slot[3] = *middle;
        count = 9;
        edges = 2;
    }
    return verdict_of(slot, count, 2, edges, middle);
}

/*
 * The slot's roof runs along the tab's top (5 mm over the floor): the tab
 * goes on when the roof is 0.05 mm beyond the gap, not when it is 0.05
 * mm within it; on a straight floor, and on one whose middle point rises
 * 0.5 mm into the tab, whose top the gap is then kept from alike.
 */
static void test_roof_keeps_the_gap(void **state)
{
    (void)state;
    const ur_vec2 middle = {20, 0.5};
    const ur_vec2 *floors[] = {NULL, &middle};
    for (size_t f = 0; f < 2; f++) {
        assert_int_equal(verdict_in_slot(5 + GAP + 0.05, floors[f]), ALLOW_BLOCKED_NOT);
        assert_int_equal(verdict_in_slot(5 + GAP - 0.05, floors[f]), ALLOW_BLOCKED_OUTLINE);
        assert_int_equal(verdict_in_slot(4.9, floors[f]), ALLOW_BLOCKED_OUTLINE);
    }
    const ur_vec2 l[] = {{-30, -30}, {40, -30}, {40, 0}, {20, 0.5}, {0, 0}, {0, 30}, {-30, 30}};
    assert_int_equal(verdict_of(l, 7, 2, 2, &middle), ALLOW_BLOCKED_NOT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_neighbour_at_the_corner_is_no_clash),
        cmocka_unit_test(test_roof_keeps_the_gap),
    };
    return cmocka_run_group_tests(tests, geos_start, geos_finish);
}
