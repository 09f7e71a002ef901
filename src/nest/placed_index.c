/*
 * placed_index.c: the placements on each sheet in a grid of buckets (cells
 * of the sheet from its lower left corner), by the box each reaches (its
 * shape's grown outline where it lies), so that a cell of a room (room.c)
 * asks only for the placements whose no-fit polygons may reach it, not
 * for every placement on every sheet: a box test per placement and cell,
 * which grows with the square of the parts.
 */
#include "nest_internal.h"

#include <math.h>
#include <stdlib.h>

double nest_reach_slack(const nest_shape *shape)
{
    return 1e-3 * (ur_box_width(shape->reach) + ur_box_height(shape->reach));
}

/*
 * The bucket column (or row) of coordinate v, counting from the sheet's
 * edge, kept within 0 to count - 1: a box beyond the sheet's edge goes in
 * the edge's buckets, which keeps every two boxes that meet in buckets
 * that do.
 */
static size_t bucket_of(double v, double size, size_t count)
{
    double i = floor(v / size);
    if (!(i > 0))
        return 0;
    return i >= (double)(count - 1) ? count - 1 : (size_t)i;
}

/* Makes a sheet's grid of empty buckets; false when memory runs out. */
static bool index_make(nester *n, size_t sheet, sheet_state *state)
{
    double width, height;
    nest_sheet_size(n, sheet, &width, &height);
    state->columns = (size_t)fmax(1.0, ceil(width / n->cell_size));
    state->rows = (size_t)fmax(1.0, ceil(height / n->cell_size));
    state->buckets = calloc(state->columns * state->rows, sizeof *state->buckets);
    if (!state->buckets) {
        state->columns = state->rows = 0;
        return false;
    }
    return true;
}

static bool bucket_add(index_bucket *bucket, size_t k)
{
    if (bucket->count == bucket->room) {
        size_t room = bucket->room ? 2 * bucket->room : 8;
        size_t *grown = realloc(bucket->items, room * sizeof *grown);
        if (!grown)
            return false;
        bucket->items = grown;
        bucket->room = room;
    }
    bucket->items[bucket->count++] = k;
    return true;
}

/* The buckets a box covers: columns i0 to i1, rows j0 to j1. */
static void bucket_range(const nester *n, const sheet_state *s, const double *box, size_t *range)
{
    range[0] = bucket_of(box[0], n->cell_size, s->columns);
    range[1] = bucket_of(box[1], n->cell_size, s->rows);
    range[2] = bucket_of(box[2], n->cell_size, s->columns);
    range[3] = bucket_of(box[3], n->cell_size, s->rows);
}

bool nest_index_add(nester *n, size_t k)
{
    sheet_state *state = &n->sheets[n->sheet_of[k]];
    if (!state->buckets && !index_make(n, n->sheet_of[k], state)) {
        n->out_of_memory = true;
        return false;
    }
    const placed *p = &n->placements[k];
    const nest_shape *shape = nest_shape_of(n, p->piece, p->turn);
    double slack = nest_reach_slack(shape);
    double box[4] = {p->at.x + shape->reach.min.x - slack, p->at.y + shape->reach.min.y - slack,
                     p->at.x + shape->reach.max.x + slack, p->at.y + shape->reach.max.y + slack};
    size_t range[4];
    bucket_range(n, state, box, range);
    for (size_t i = range[0]; i <= range[2]; i++)
        for (size_t j = range[1]; j <= range[3]; j++)
            if (!bucket_add(&state->buckets[i * state->rows + j], k)) {
                n->out_of_memory = true;
                return false;
            }
    return true;
}

void nest_index_rewind(nester *n, size_t kept)
{
    for (size_t s = 0; s < n->sheet_slots; s++) {
        sheet_state *state = &n->sheets[s];
        for (size_t b = 0; state->buckets && b < state->columns * state->rows; b++) {
            index_bucket *bucket = &state->buckets[b];
            /* Placements are numbered in the order made: the forgotten ones are at the end. */
            while (bucket->count > 0 && bucket->items[bucket->count - 1] >= kept)
                bucket->count--;
        }
    }
}

static int smaller_number_first(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

/* Makes room for count more numbers in n->near; false when memory runs out. */
static bool near_reserve(nester *n, size_t count)
{
    if (count <= n->near_room)
        return true;
    size_t room = n->near_room ? n->near_room : 64;
    while (room < count)
        room *= 2;
    size_t *grown = realloc(n->near, room * sizeof *grown);
    if (!grown)
        return false;
    n->near = grown;
    n->near_room = room;
    return true;
}

bool nest_index_near(nester *n, size_t sheet, const double *box, size_t from, size_t *count)
{
    *count = 0;
    const sheet_state *state = &n->sheets[sheet];
    if (!state->buckets)
        return true; /* nothing placed on it */
    size_t range[4];
    bucket_range(n, state, box, range);
    for (size_t i = range[0]; i <= range[2]; i++)
        for (size_t j = range[1]; j <= range[3]; j++) {
            const index_bucket *bucket = &state->buckets[i * state->rows + j];
            if (!near_reserve(n, *count + bucket->count)) {
                n->out_of_memory = true;
                return false;
            }
            for (size_t q = bucket->count; q > 0 && bucket->items[q - 1] >= from; q--)
                n->near[(*count)++] = bucket->items[q - 1];
        }
    /* A placement reaching several buckets was found in each: sorted, its copies are neighbours. */
    qsort(n->near, *count, sizeof *n->near, smaller_number_first);
    size_t unique = 0;
    for (size_t q = 0; q < *count; q++)
        if (unique == 0 || n->near[unique - 1] != n->near[q])
            n->near[unique++] = n->near[q];
    *count = unique;
    return true;
}

void nest_index_free(sheet_state *sheet)
{
    for (size_t b = 0; sheet->buckets && b < sheet->columns * sheet->rows; b++)
        free(sheet->buckets[b].items);
    free(sheet->buckets);
    sheet->buckets = NULL;
    sheet->columns = sheet->rows = 0;
}
