/*
 * grid.c: a spatial index that grows (allow_internal.h, allow_grid).
 *
 * GEOS's STRtree is built once, on its first query, and takes nothing
 * after; the joints and labels placed on a piece must be found again by
 * the next ones, while they are being placed.  This index is a grid of
 * square cells over a region: an item is listed in every cell its box
 * meets (a box beyond the region in the border cells), and a query looks
 * only at the cells its box meets, so that each test stays local.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* About this many cells at most (three times it for a long thin region). */
#define MAX_CELLS (1u << 18)

typedef struct allow_cell {
    size_t *items;
    size_t count, capacity;
} allow_cell;

ur_status allow_grid_init(allow_grid *grid, ur_box region, double cell, ur_error *error)
{
    memset(grid, 0, sizeof *grid);
    double width = fmax(ur_box_width(region), 1e-9), height = fmax(ur_box_height(region), 1e-9);
    if (!(cell > 0) || !isfinite(cell) || !isfinite(width) || !isfinite(height))
        return ur_error_set(error, UR_ERROR_INTERNAL,
                            "a grid index needs a finite region and cell");
    /* Cells no smaller than the region allows within MAX_CELLS. */
    cell = fmax(cell, sqrt(width * height / MAX_CELLS));
    grid->region = region;
    grid->cell = cell;
    grid->columns = (size_t)fmin(ceil(width / cell), MAX_CELLS);
    grid->rows = (size_t)fmin(ceil(height / cell), MAX_CELLS);
    if (grid->columns == 0)
        grid->columns = 1;
    if (grid->rows == 0)
        grid->rows = 1;
    grid->cells = calloc(grid->columns * grid->rows, sizeof *grid->cells);
    if (!grid->cells)
        return ur_error_out_of_memory(error);
    return UR_OK;
}

void allow_grid_free(allow_grid *grid)
{
    if (grid->cells)
        for (size_t k = 0; k < grid->columns * grid->rows; k++)
            free(grid->cells[k].items);
    free(grid->cells);
    free(grid->boxes);
    free(grid->seen);
    memset(grid, 0, sizeof *grid);
}

/* The column (or row) of coordinate v, clamped to the grid. */
static size_t cell_index(double v, double start, double cell, size_t count)
{
    double index = floor((v - start) / cell);
    if (!(index > 0))
        return 0;
    if (index >= (double)count)
        return count - 1;
    return (size_t)index;
}

/* The cells box meets: columns [*x0, *x1], rows [*y0, *y1]. */
static void cells_of(const allow_grid *grid, ur_box box, size_t *x0, size_t *x1, size_t *y0,
                     size_t *y1)
{
    *x0 = cell_index(box.min.x, grid->region.min.x, grid->cell, grid->columns);
    *x1 = cell_index(box.max.x, grid->region.min.x, grid->cell, grid->columns);
    *y0 = cell_index(box.min.y, grid->region.min.y, grid->cell, grid->rows);
    *y1 = cell_index(box.max.y, grid->region.min.y, grid->cell, grid->rows);
}

static ur_status cell_push(allow_cell *cell, size_t item, ur_error *error)
{
    if (cell->count == cell->capacity) {
        size_t capacity = cell->capacity ? 2 * cell->capacity : 4;
        size_t *items = realloc(cell->items, capacity * sizeof *items);
        if (!items)
            return ur_error_out_of_memory(error);
        cell->items = items;
        cell->capacity = capacity;
    }
    cell->items[cell->count++] = item;
    return UR_OK;
}

ur_status allow_grid_add(allow_grid *grid, ur_box box, size_t *item, ur_error *error)
{
    if (grid->count == grid->capacity) {
        size_t capacity = grid->capacity ? 2 * grid->capacity : 16;
        ur_box *boxes = realloc(grid->boxes, capacity * sizeof *boxes);
        if (!boxes)
            return ur_error_out_of_memory(error);
        grid->boxes = boxes;
        unsigned *seen = realloc(grid->seen, capacity * sizeof *seen);
        if (!seen)
            return ur_error_out_of_memory(error);
        grid->seen = seen;
        grid->capacity = capacity;
    }
    size_t index = grid->count;
    size_t x0, x1, y0, y1;
    cells_of(grid, box, &x0, &x1, &y0, &y1);
    for (size_t y = y0; y <= y1; y++)
        for (size_t x = x0; x <= x1; x++) {
            ur_status status = cell_push(&grid->cells[y * grid->columns + x], index, error);
            if (status != UR_OK)
                return status;
        }
    grid->boxes[index] = box;
    grid->seen[index] = 0;
    grid->count++;
    if (item)
        *item = index;
    return UR_OK;
}

/* What allow_grid_query gathers through allow_grid_any: every item, until memory fails. */
typedef struct gathering {
    allow_items *found;
    ur_status status;
    ur_error *error;
} gathering;

static bool gather(size_t item, void *data)
{
    gathering *g = data;
    g->status = allow_items_push(g->found, item, g->error);
    return g->status != UR_OK;
}

ur_status allow_grid_query(allow_grid *grid, ur_box box, allow_items *found, ur_error *error)
{
    found->count = 0;
    gathering g = {found, UR_OK, error};
    allow_grid_any(grid, box, gather, &g);
    return g.status;
}

bool allow_grid_any(allow_grid *grid, ur_box box, bool (*test)(size_t item, void *data), void *data)
{
    if (grid->count == 0)
        return false;
    if (++grid->stamp == 0) { /* the stamps wrapped: forget every old one */
        memset(grid->seen, 0, grid->count * sizeof *grid->seen);
        grid->stamp = 1;
    }
    size_t x0, x1, y0, y1;
    cells_of(grid, box, &x0, &x1, &y0, &y1);
    for (size_t y = y0; y <= y1; y++)
        for (size_t x = x0; x <= x1; x++) {
            const allow_cell *cell = &grid->cells[y * grid->columns + x];
            for (size_t k = 0; k < cell->count; k++) {
                size_t item = cell->items[k];
                if (grid->seen[item] == grid->stamp || !allow_boxes_meet(grid->boxes[item], box))
                    continue;
                grid->seen[item] = grid->stamp;
                if (test(item, data))
                    return true;
            }
        }
    return false;
}

size_t allow_grid_cell_of(const allow_grid *grid, ur_vec2 p)
{
    size_t x = cell_index(p.x, grid->region.min.x, grid->cell, grid->columns);
    size_t y = cell_index(p.y, grid->region.min.y, grid->cell, grid->rows);
    return y * grid->columns + x;
}

ur_vec2 allow_grid_cell_centre(const allow_grid *grid, size_t cell)
{
    size_t x = cell % grid->columns, y = cell / grid->columns;
    return ur_vec2_make(grid->region.min.x + ((double)x + 0.5) * grid->cell,
                        grid->region.min.y + ((double)y + 0.5) * grid->cell);
}

bool allow_grid_cell_is_empty(const allow_grid *grid, size_t cell)
{
    return grid->cells[cell].count == 0;
}

ur_status allow_items_push(allow_items *items, size_t item, ur_error *error)
{
    if (items->count == items->capacity) {
        size_t capacity = items->capacity ? 2 * items->capacity : 16;
        size_t *grown = realloc(items->items, capacity * sizeof *grown);
        if (!grown)
            return ur_error_out_of_memory(error);
        items->items = grown;
        items->capacity = capacity;
    }
    items->items[items->count++] = item;
    return UR_OK;
}

void allow_items_free(allow_items *items)
{
    free(items->items);
    memset(items, 0, sizeof *items);
}
