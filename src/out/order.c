/*
 * order.c: the order a good operator cuts a sheet in (ur_sheet_cut_plan).
 *
 * The operations go in the writers' layer order (engrave and mark, scores
 * and kerfs, cuts last).  Within each, the pieces come one after another
 * along a short tour: nearest neighbour from the machine's origin (the
 * sheet's lower left corner), then 2-opt, which undoes the crossings a
 * greedy tour leaves.  Within a piece, inner contours come before its
 * outline (paths[0]), so the part still holds in the sheet while they are
 * cut.  Every closed path starts in the middle of its longest edge: on a
 * straight stretch, away from the corners where a start mark would show.
 *
 * The plan also measures the job: cut length, travel between paths (from
 * the origin, straight lines at the travel speed) and the time both take
 * at the machine profile's speeds.
 */
#include "unroll/out.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Where a placed piece is on the sheet: its box's middle, the point the tour visits. */
static ur_vec2 piece_point(const ur_sheet *sheet, const ur_piece *pieces, size_t p)
{
    const ur_placement *placement = &sheet->placements[p];
    const ur_piece *piece = &pieces[placement->piece_index];
    ur_vec2 middle = ur_vec2_make((piece->box.min.x + piece->box.max.x) / 2,
                                  (piece->box.min.y + piece->box.max.y) / 2);
    return ur_transform2_apply(placement->transform, middle);
}

/* Nearest neighbour from the origin; the order is left as it is when memory runs out. */
static void nearest_tour(const ur_vec2 *points, size_t count, size_t *order)
{
    bool *visited = calloc(count ? count : 1, sizeof *visited);
    if (!visited)
        return;
    ur_vec2 at = ur_vec2_make(0, 0);
    for (size_t k = 0; k < count; k++) {
        size_t best = 0;
        double best_distance = INFINITY;
        for (size_t i = 0; i < count; i++)
            if (!visited[i] && ur_vec2_distance(at, points[i]) < best_distance) {
                best = i;
                best_distance = ur_vec2_distance(at, points[i]);
            }
        order[k] = best;
        visited[best] = true;
        at = points[best];
    }
    free(visited);
}

/* The tour's point k, the origin before the first. */
static ur_vec2 tour_point(const ur_vec2 *points, const size_t *order, size_t k)
{
    return k == 0 ? ur_vec2_make(0, 0) : points[order[k - 1]];
}

/*
 * 2-opt on an open tour starting at the origin: reverse order[i..j] when
 * that shortens it, until no reversal does (or a pass limit: the tours are
 * short, this only guards against rounding loops).
 */
static void two_opt(const ur_vec2 *points, size_t count, size_t *order)
{
    for (int pass = 0; pass < 50; pass++) {
        bool improved = false;
        for (size_t i = 0; i + 1 < count; i++)
            for (size_t j = i + 1; j < count; j++) {
                ur_vec2 a = tour_point(points, order, i), b = points[order[i]];
                ur_vec2 c = points[order[j]];
                double before = ur_vec2_distance(a, b), after = ur_vec2_distance(a, c);
                if (j + 1 < count) {
                    ur_vec2 d = points[order[j + 1]];
                    before += ur_vec2_distance(c, d);
                    after += ur_vec2_distance(b, d);
                }
                if (after < before - 1e-9) {
                    for (size_t lo = i, hi = j; lo < hi; lo++, hi--) {
                        size_t swap = order[lo];
                        order[lo] = order[hi];
                        order[hi] = swap;
                    }
                    improved = true;
                }
            }
        if (!improved)
            break;
    }
}

size_t ur_path_start(const ur_path *path)
{
    if (!path->closed || path->count < 3)
        return 0;
    size_t best = 0;
    double longest = -1;
    for (size_t i = 0; i < path->count; i++) {
        double length = ur_vec2_distance(path->points[i], path->points[(i + 1) % path->count]);
        if (length > longest) {
            longest = length;
            best = i;
        }
    }
    return best;
}

/* Where a path starts and ends on the sheet, as the writers will run it. */
static void path_ends(const ur_path *path, ur_transform2 transform, bool ordered, ur_vec2 *start,
                      ur_vec2 *end)
{
    if (path->closed && ordered && path->count >= 3) {
        size_t i = ur_path_start(path);
        ur_vec2 middle =
            ur_vec2_scale(ur_vec2_add(path->points[i], path->points[(i + 1) % path->count]), 0.5);
        *start = *end = ur_transform2_apply(transform, middle);
        return;
    }
    *start = ur_transform2_apply(transform, path->points[0]);
    *end = ur_transform2_apply(transform,
                               path->closed ? path->points[0] : path->points[path->count - 1]);
}

/* Adds one piece's paths of one operation to the measures, in the writers' order. */
static void measure_piece(const ur_sheet *sheet, const ur_piece *pieces, size_t p, ur_op op,
                          bool ordered, ur_vec2 *at, ur_cut_plan *plan)
{
    const ur_placement *placement = &sheet->placements[p];
    const ur_piece *piece = &pieces[placement->piece_index];
    for (size_t k = 1; k <= piece->path_count; k++) {
        const ur_path *path = &piece->paths[k % piece->path_count];
        if (path->op != op || path->count == 0)
            continue;
        ur_vec2 start, end;
        path_ends(path, placement->transform, ordered, &start, &end);
        plan->travel_length += ur_vec2_distance(*at, start);
        plan->cut_length += ur_polyline_length(path->points, path->count, path->closed);
        *at = end;
    }
}

ur_status ur_sheet_cut_plan(const ur_sheet *sheet, const ur_piece *pieces, const ur_op *op_order,
                            bool ordered, const ur_machine *machine, ur_cut_plan *plan,
                            ur_error *error)
{
    memset(plan, 0, sizeof *plan);
    size_t count = sheet->placement_count;
    plan->order = ur_alloc_array(count, sizeof *plan->order, error);
    ur_vec2 *points = ur_alloc_array(count, sizeof *points, error);
    if (!plan->order || !points) {
        free(points);
        ur_cut_plan_free(plan);
        return UR_ERROR_MEMORY;
    }
    for (size_t p = 0; p < count; p++) {
        points[p] = piece_point(sheet, pieces, p);
        plan->order[p] = p;
    }
    if (ordered) {
        nearest_tour(points, count, plan->order);
        two_opt(points, count, plan->order);
    }
    free(points);
    ur_vec2 at = ur_vec2_make(0, 0);
    for (size_t o = 0; o < UR_OP_COUNT; o++)
        for (size_t k = 0; k < count; k++)
            measure_piece(sheet, pieces, plan->order[k], op_order[o], ordered, &at, plan);
    if (machine && machine->cut_speed > 0 && machine->travel_speed > 0)
        plan->seconds =
            plan->cut_length / machine->cut_speed + plan->travel_length / machine->travel_speed;
    return UR_OK;
}

void ur_cut_plan_free(ur_cut_plan *plan)
{
    free(plan->order);
    plan->order = NULL;
}
