/*
 * merge_lines.c: common-line cutting (--merge-lines).  Where two placed
 * parts touch, both outlines run along the same line and the cutter would
 * cut it twice: the second pass costs time and widens or scorches the
 * edge.  Going through each sheet's pieces in placement order, every cut
 * path loses the stretches of its segments that lie along a segment an
 * earlier piece cuts (both ends of that one within the tolerance of the
 * segment's line); what is left of it becomes open paths.
 *
 * Parts touch only where nothing keeps them apart, so the nesting that
 * goes before this uses no spacing (kerf compensation has already moved
 * each outline out by half the kerf: two compensated outlines that touch
 * put the beam on one line between two true edges a kerf apart).
 *
 * The earlier segments are found through a grid of square cells over the
 * sheet, each listing the segments whose box (grown by the tolerance)
 * meets it, so that a piece is compared with its neighbours only.
 */
#include "unroll/nest.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cells in the grid, about: enough that a cell holds a few segments. */
#define GRID_CELLS 16384.0

typedef struct segment {
    ur_vec2 a, b; /* sheet coordinates */
} segment;

typedef struct cell {
    size_t *items; /* indices into the grid's segments */
    size_t count, capacity;
} cell;

typedef struct grid {
    segment *segments;
    size_t segment_count, segment_capacity;
    cell *cells;
    size_t columns, rows;
    double size, tolerance;
    size_t *seen; /* per segment: the query that last saw it, so each is tried once */
    size_t query;
} grid;

/* A stretch of a segment as fractions of its length, 0 <= lo <= hi <= 1. */
typedef struct interval {
    double lo, hi;
} interval;

typedef struct intervals {
    interval *items;
    size_t count, capacity;
} intervals;

static ur_status grid_make(grid *g, double width, double height, double tolerance, ur_error *error)
{
    memset(g, 0, sizeof *g);
    g->tolerance = tolerance;
    g->size = fmax(sqrt(width * height / GRID_CELLS), 100 * tolerance);
    g->columns = (size_t)ceil(width / g->size) + 1;
    g->rows = (size_t)ceil(height / g->size) + 1;
    g->cells = calloc(g->columns * g->rows, sizeof *g->cells);
    return g->cells ? UR_OK : ur_error_out_of_memory(error);
}

static void grid_free(grid *g)
{
    for (size_t k = 0; g->cells && k < g->columns * g->rows; k++)
        free(g->cells[k].items);
    free(g->cells);
    free(g->segments);
    free(g->seen);
    memset(g, 0, sizeof *g);
}

/* The range of cells [*c0, *c1] x [*r0, *r1] the box of a and b, grown by the tolerance, meets. */
static void cell_range(const grid *g, ur_vec2 a, ur_vec2 b, size_t *c0, size_t *c1, size_t *r0,
                       size_t *r1)
{
    double reach = g->tolerance;
    double x0 = fmax(0, (fmin(a.x, b.x) - reach) / g->size);
    double x1 = fmax(0, (fmax(a.x, b.x) + reach) / g->size);
    double y0 = fmax(0, (fmin(a.y, b.y) - reach) / g->size);
    double y1 = fmax(0, (fmax(a.y, b.y) + reach) / g->size);
    *c0 = (size_t)fmin(x0, (double)(g->columns - 1));
    *c1 = (size_t)fmin(x1, (double)(g->columns - 1));
    *r0 = (size_t)fmin(y0, (double)(g->rows - 1));
    *r1 = (size_t)fmin(y1, (double)(g->rows - 1));
}

static ur_status grid_add(grid *g, ur_vec2 a, ur_vec2 b, ur_error *error)
{
    if (g->segment_count == g->segment_capacity) {
        size_t capacity = g->segment_capacity ? 2 * g->segment_capacity : 256;
        segment *segments = realloc(g->segments, capacity * sizeof *segments);
        if (segments)
            g->segments = segments;
        size_t *seen = realloc(g->seen, capacity * sizeof *seen);
        if (seen)
            g->seen = seen;
        if (!segments || !seen)
            return ur_error_out_of_memory(error);
        g->segment_capacity = capacity;
    }
    size_t index = g->segment_count++;
    g->segments[index] = (segment){a, b};
    g->seen[index] = 0;
    size_t c0, c1, r0, r1;
    cell_range(g, a, b, &c0, &c1, &r0, &r1);
    for (size_t r = r0; r <= r1; r++)
        for (size_t c = c0; c <= c1; c++) {
            cell *here = &g->cells[r * g->columns + c];
            size_t *items =
                ur_array_grow(here->items, &here->capacity, here->count, sizeof *items, 8, error);
            if (!items)
                return UR_ERROR_MEMORY;
            here->items = items;
            items[here->count++] = index;
        }
    return UR_OK;
}

/*
 * The stretch of segment pq that segment s runs along, when both ends of s
 * are within the tolerance of pq's line and the common stretch is longer
 * than the tolerance.
 */
static bool along(ur_vec2 p, ur_vec2 q, const segment *s, double tolerance, interval *out)
{
    ur_vec2 d = ur_vec2_sub(q, p);
    double length = ur_vec2_length(d);
    if (length <= tolerance)
        return false;
    ur_vec2 u = ur_vec2_scale(d, 1 / length);
    ur_vec2 a = ur_vec2_sub(s->a, p), b = ur_vec2_sub(s->b, p);
    if (fabs(ur_vec2_cross(u, a)) > tolerance || fabs(ur_vec2_cross(u, b)) > tolerance)
        return false;
    double ta = ur_vec2_dot(u, a) / length, tb = ur_vec2_dot(u, b) / length;
    out->lo = fmax(0, fmin(ta, tb));
    out->hi = fmin(1, fmax(ta, tb));
    return (out->hi - out->lo) * length > tolerance;
}

static int by_start(const void *a, const void *b)
{
    const interval *x = a, *y = b;
    return (x->lo > y->lo) - (x->lo < y->lo);
}

/* The stretches of pq that earlier segments run along, sorted and joined where they meet. */
static ur_status covered(grid *g, ur_vec2 p, ur_vec2 q, intervals *out, ur_error *error)
{
    out->count = 0;
    g->query++;
    size_t c0, c1, r0, r1;
    cell_range(g, p, q, &c0, &c1, &r0, &r1);
    for (size_t r = r0; r <= r1; r++)
        for (size_t c = c0; c <= c1; c++) {
            const cell *here = &g->cells[r * g->columns + c];
            for (size_t k = 0; k < here->count; k++) {
                size_t index = here->items[k];
                interval stretch;
                if (g->seen[index] == g->query)
                    continue;
                g->seen[index] = g->query;
                if (!along(p, q, &g->segments[index], g->tolerance, &stretch))
                    continue;
                interval *items =
                    ur_array_grow(out->items, &out->capacity, out->count, sizeof *items, 8, error);
                if (!items)
                    return UR_ERROR_MEMORY;
                out->items = items;
                items[out->count++] = stretch;
            }
        }
    if (out->count > 1)
        qsort(out->items, out->count, sizeof *out->items, by_start);
    size_t joined = 0;
    for (size_t k = 0; k < out->count; k++) {
        if (joined > 0 && out->items[k].lo <= out->items[joined - 1].hi)
            out->items[joined - 1].hi = fmax(out->items[joined - 1].hi, out->items[k].hi);
        else
            out->items[joined++] = out->items[k];
    }
    out->count = joined;
    return UR_OK;
}

/* The open stretches a path keeps, in piece coordinates, as they are built. */
typedef struct stretches {
    ur_points *items;
    size_t count, capacity;
    bool open; /* the last one goes on */
} stretches;

static void stretches_free(stretches *list)
{
    for (size_t k = 0; k < list->count; k++)
        ur_points_free(&list->items[k]);
    free(list->items);
    memset(list, 0, sizeof *list);
}

/*
 * Adds the piece-coordinate stretch from a to b, joined to the last one
 * when that one went on to the end of its segment and this one starts
 * its segment.
 */
static ur_status keep(stretches *list, ur_vec2 a, ur_vec2 b, bool starts_segment, bool ends_segment,
                      ur_error *error)
{
    if (!list->open || !starts_segment) {
        ur_points *items =
            ur_array_grow(list->items, &list->capacity, list->count, sizeof *items, 4, error);
        if (!items)
            return UR_ERROR_MEMORY;
        list->items = items;
        items[list->count] = (ur_points){0};
        ur_status status = ur_points_push(&items[list->count++], a, error);
        if (status != UR_OK)
            return status;
    }
    list->open = ends_segment;
    return ur_points_push(&list->items[list->count - 1], b, error);
}

/*
 * Walks the path's segments: what no earlier cut covers is kept, and the
 * length taken off added to *saved.  A closed path kept whole is left as
 * it is (*changed false).
 */
static ur_status walk_path(grid *g, const ur_path *path, ur_transform2 placement, stretches *kept,
                           double *saved, bool *changed, ur_error *error)
{
    size_t segments = path->closed ? path->count : path->count - 1;
    intervals cover = {0};
    ur_status status = UR_OK;
    *changed = false;
    for (size_t i = 0; status == UR_OK && i < segments; i++) {
        ur_vec2 a = path->points[i], b = path->points[(i + 1) % path->count];
        ur_vec2 p = ur_transform2_apply(placement, a), q = ur_transform2_apply(placement, b);
        status = covered(g, p, q, &cover, error);
        double length = ur_vec2_length(ur_vec2_sub(q, p)), from = 0;
        for (size_t k = 0; status == UR_OK && k <= cover.count; k++) {
            double to = k < cover.count ? cover.items[k].lo : 1;
            if ((to - from) * length > g->tolerance || (to == 1 && from == 0))
                status = keep(kept, ur_vec2_lerp(a, b, from), ur_vec2_lerp(a, b, to), from == 0,
                              to == 1, error);
            else
                kept->open = false;
            if (k < cover.count) {
                *saved += (cover.items[k].hi - cover.items[k].lo) * length;
                *changed = true;
                from = cover.items[k].hi;
            }
        }
    }
    free(cover.items);
    return status;
}

/*
 * A closed path opened where it was covered: its last stretch, running on
 * through the first point, and its first are one.
 */
static ur_status close_up(const ur_path *path, stretches *kept, ur_error *error)
{
    if (!path->closed || kept->count < 2 || !kept->open)
        return UR_OK;
    ur_points *first = &kept->items[0], *last = &kept->items[kept->count - 1];
    if (first->items[0].x != path->points[0].x || first->items[0].y != path->points[0].y)
        return UR_OK;
    ur_status status = UR_OK;
    for (size_t k = 1; status == UR_OK && k < first->count; k++)
        status = ur_points_push(last, first->items[k], error);
    if (status != UR_OK)
        return status;
    ur_points_free(first);
    memmove(&kept->items[0], &kept->items[1], (kept->count - 1) * sizeof *kept->items);
    kept->count--;
    return UR_OK;
}

/*
 * Replaces piece->paths[index] by the stretches kept: the first in its
 * place, the others appended; none leaves it with no points, which no
 * writer draws.
 */
static ur_status replace_path(ur_piece *piece, size_t index, stretches *kept, ur_error *error)
{
    ur_op op = piece->paths[index].op;
    if (index == 0 && piece->paths[0].closed && !piece->bridged)
        piece->outline_area =
            fabs(ur_polygon_signed_area(piece->paths[0].points, piece->paths[0].count));
    if (index == 0)
        piece->bridged = true; /* the outline is open now */
    free(piece->paths[index].points);
    piece->paths[index] = (ur_path){.op = op}; /* open, and no longer a whole circle */
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < kept->count; k++) {
        if (k == 0) {
            piece->paths[index].points = kept->items[0].items;
            piece->paths[index].count = kept->items[0].count;
            kept->items[0] = (ur_points){0};
        } else
            status = ur_piece_add_path(piece, op, kept->items[k].items, kept->items[k].count, false,
                                       error);
    }
    return status;
}

/* One path of a placed piece: what earlier pieces cut comes off it; then it is cut too. */
static ur_status merge_path(grid *g, ur_piece *piece, size_t index, ur_transform2 placement,
                            double *saved, ur_error *error)
{
    stretches kept = {0};
    bool changed = false;
    ur_status status = walk_path(g, &piece->paths[index], placement, &kept, saved, &changed, error);
    if (status == UR_OK && changed)
        status = close_up(&piece->paths[index], &kept, error);
    const ur_path *path = &piece->paths[index];
    size_t segments = path->closed ? path->count : path->count - 1;
    for (size_t i = 0; status == UR_OK && i < segments; i++)
        status =
            grid_add(g, ur_transform2_apply(placement, path->points[i]),
                     ur_transform2_apply(placement, path->points[(i + 1) % path->count]), error);
    if (status == UR_OK && changed)
        status = replace_path(piece, index, &kept, error);
    stretches_free(&kept);
    return status;
}

static ur_status merge_sheet(const ur_sheet *sheet, ur_piece *pieces, size_t count,
                             double tolerance, double *saved, ur_error *error)
{
    grid g;
    ur_status status = grid_make(&g, sheet->width, sheet->height, tolerance, error);
    for (size_t p = 0; status == UR_OK && p < sheet->placement_count; p++) {
        const ur_placement *placement = &sheet->placements[p];
        if (placement->piece_index >= count)
            continue;
        ur_piece *piece = &pieces[placement->piece_index];
        size_t path_count = piece->path_count; /* not the stretches appended on the way */
        for (size_t k = 0; status == UR_OK && k < path_count; k++)
            if (piece->paths[k].op == UR_OP_CUT && piece->paths[k].count >= 2)
                status = merge_path(&g, piece, k, placement->transform, saved, error);
    }
    grid_free(&g);
    return status;
}

ur_status ur_layout_merge_lines(const ur_layout *layout, ur_piece *pieces, size_t count,
                                double tolerance, double *saved, ur_error *error)
{
    *saved = 0;
    if (!(tolerance > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "merging lines: the tolerance must be above 0");
    ur_status status = UR_OK;
    for (size_t s = 0; status == UR_OK && s < layout->sheet_count; s++)
        status = merge_sheet(&layout->sheets[s], pieces, count, tolerance, saved, error);
    return status;
}
