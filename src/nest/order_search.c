/*
 * order_search.c: after the first layout (nest.c), a search over the order
 * the parts go in and the turns they are held at (two parts swapped, one
 * moved, one held at another turn; any layout at least as good is kept);
 * then, on sheets, the layout on fewer stock sheets (compact.c) and the
 * last sheet's offcut left whole.
 */
#include "nest_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/*
 * Makes a cell of a grid whole again (no placement cut from it yet); on a
 * GEOS failure the whole grid goes, to be made again when next asked for.
 */
static void cell_renew(nester *n, room_grid *grid, size_t c)
{
    double box[4];
    nest_cell_box(n, grid, c, box);
    if (grid->free[c])
        GEOSGeom_destroy_r(n->geos, grid->free[c]);
    grid->free[c] = nest_rectangle_polygon(n->geos, box[0], box[1], box[2], box[3]);
    grid->applied[c] = grid->cut_by[c] = 0;
    if (!grid->free[c])
        nest_grid_free(n->geos, grid);
}

/*
 * Forgets all placements but the first kept (maybe none), as if only those
 * had been made: a cell that a later one cut is made whole again, the
 * others only forget having looked at the later ones.  Rooms thus kept
 * leave the places a run placing just the first kept would leave (their
 * cuts may have come in another order: room.c cuts each time the largest
 * first); the no-fit polygons stay, they hold for any run.
 */
static void rewind_run(nester *n, size_t kept)
{
    size_t slots = n->class_count * n->turn_count;
    for (size_t s = 0; s < n->sheet_slots; s++)
        for (size_t k = 0; n->sheets[s].rooms && k < slots; k++) {
            room_grid *grid = &n->sheets[s].rooms[k];
            n->sheets[s].full[k] = false; /* a later placement may have filled it */
            for (size_t c = 0; grid->cols && c < grid->cols * grid->rows; c++) {
                if (grid->cut_by[c] > kept)
                    cell_renew(n, grid, c);
                else if (grid->applied[c] > kept)
                    grid->applied[c] = kept;
            }
        }
    nest_index_rewind(n, kept);
    for (size_t k = kept; k < n->placed_count; k++)
        n->sheets[n->sheet_of[k]].version++; /* its raster is made again from what is kept */
    memset(n->sheet_area, 0, n->sheet_slots * sizeof *n->sheet_area);
    n->sheet_count = n->remnant_count;
    for (size_t k = 0; k < kept; k++) {
        n->sheet_area[n->sheet_of[k]] += nest_shape_of(n, n->placements[k].piece, 0)->area;
        if (n->sheet_of[k] >= n->sheet_count)
            n->sheet_count = n->sheet_of[k] + 1;
    }
    n->placed_count = kept;
}

/*
 * Places the pieces in order, each at its held turn (per piece; NULL: all
 * free).  Where the order and turns begin as the last run's did, that
 * run's placements stand: a placement depends only on those before it.
 */
ur_status nest_run_order(nester *n, const size_t *order, const size_t *held)
{
    size_t same = 0;
    while (same < n->run_length && n->run_piece[same] == order[same] &&
           n->run_held[same] == (held ? held[order[same]] : ANY_TURN))
        same++;
    rewind_run(n, n->run_placed[same]); /* run_placed[0] is 0: a run from the start */
    n->runs++;
    n->run_length = same;
    ur_status status = UR_OK;
    for (size_t k = same; status == UR_OK && k < n->count; k++) {
        /* A first layout of a thousand parts takes minutes: it stops when the run is cancelled. */
        status = ur_context_check(n->options->context, n->error);
        if (status != UR_OK)
            break;
        n->run_piece[k] = order[k];
        n->run_held[k] = held ? held[order[k]] : ANY_TURN;
        n->run_placed[k] = n->placed_count;
        status = nest_place_piece(n, order[k], n->run_held[k]);
        n->run_length = status == UR_OK ? k + 1 : 0;
        if (n->first_run && n->options->placing)
            n->options->placing(n->options->progress_context, k + 1, n->count);
    }
    n->run_placed[n->count] = n->placed_count; /* an order the same throughout keeps them all */
    return status;
}

/*
 * A layout's score: parts placed, stock sheets used, then how tightly the
 * last sheet is packed: the length of it used (up to its rightmost part),
 * then how far its parts reach on average (the mean of their right edges),
 * which tells apart layouts of the same length, some closer to freeing room
 * at the end than others, so that the search has somewhere to go.
 */
typedef struct score {
    size_t placed, sheets; /* sheets: stock sheets */
    double length, reach;
} score;

static score score_of(const nester *n)
{
    score s = {n->placed_count, n->sheet_count - n->remnant_count, 0.0, 0.0};
    size_t on_last = 0;
    for (size_t k = 0; k < n->placed_count; k++)
        if (n->sheet_of[k] + 1 == n->sheet_count) {
            const placed *p = &n->placements[k];
            double right = p->at.x + nest_shape_of(n, p->piece, p->turn)->box.max.x;
            s.length = fmax(s.length, right);
            s.reach += right;
            on_last++;
        }
    s.reach = on_last ? s.reach / (double)on_last : 0.0;
    return s;
}

/* Whether a is better than b (1), as good (0) or worse (-1). */
static int compare_scores(score a, score b)
{
    if (a.placed != b.placed)
        return a.placed > b.placed ? 1 : -1;
    if (a.sheets != b.sheets)
        return a.sheets < b.sheets ? 1 : -1;
    if (fabs(a.length - b.length) > 1e-9)
        return a.length < b.length ? 1 : -1;
    if (fabs(a.reach - b.reach) > 1e-9)
        return a.reach < b.reach ? 1 : -1;
    return 0;
}

uint64_t nest_next_random(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return *state * 2685821657736338717ULL;
}

/* Two parts swapped, or one moved elsewhere in the order. */
static void mutate(size_t *order, size_t count, uint64_t *state)
{
    size_t i = nest_next_random(state) % count, j = nest_next_random(state) % count;
    if (nest_next_random(state) & 1) {
        size_t swap = order[i];
        order[i] = order[j];
        order[j] = swap;
        return;
    }
    size_t moved = order[i];
    if (i < j)
        memmove(order + i, order + i + 1, (j - i) * sizeof *order);
    else
        memmove(order + j + 1, order + j, (i - j) * sizeof *order);
    order[j] = moved;
}

/*
 * Whether piece may be held at turn: only at turns that fit an empty stock
 * sheet, so that a held part always has a place (the first layout found
 * one for it at some turn) and never makes a try fail.
 */
static bool may_hold(const nester *n, size_t piece, size_t turn)
{
    double fit[4];
    return nest_inner_fit_box(n, n->remnant_count, nest_shape_of(n, piece, turn), fit);
}

/*
 * A part's turn changed: held at another of its turns, or freed to take
 * its best again.  False when the part drawn has no other choice (one
 * turn, or the others do not fit).
 */
static bool turn_move(const nester *n, size_t *held, uint64_t *state)
{
    size_t piece = nest_next_random(state) % n->count;
    size_t turns = n->classes[n->class_of[piece]].turn_count;
    if (turns < 2)
        return false;
    /* Choice turns stands for free; the part's present choice is not drawn. */
    size_t now = held[piece] < turns ? held[piece] : turns;
    size_t choice = nest_next_random(state) % turns;
    if (choice >= now)
        choice++;
    if (choice < turns && !may_hold(n, piece, choice))
        return false;
    held[piece] = choice < turns ? choice : ANY_TURN;
    return true;
}

double nest_seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/*
 * Improves on order (run and placed already, every part free to take its
 * best turn) within the options' budget; leaves the best placed.  A hill
 * climb over orders and turns that also takes sideways steps (a layout as
 * good as the current one replaces it), so that it wanders across the many
 * layouts of equal score instead of stopping at the first.  A step either
 * changes the order (mutate) or, one time in NEST_TURN_MOVES, one part's
 * turn (turn_move): the greedy choice of each part's turn is often not the
 * one that leaves the best room for the parts after it, and a part held at
 * one turn is tried at that turn alone.  It gives up after a run of tries
 * without a new best: NEST_PATIENCE, or NEST_PATIENCE_PER_SECOND per second
 * of budget if that is more.
 */
#define NEST_TURN_MOVES 3
ur_status nest_search_orders(nester *n, size_t *order, double budget)
{
    const ur_nest_options *o = n->options;
    if (!(budget > 0) || n->count < 2)
        return UR_OK;
    size_t bytes = n->count * sizeof *order;
    size_t *current = malloc(bytes), *candidate = malloc(bytes);
    /* Per piece: the turn it is held at, or ANY_TURN; for the current, candidate and best. */
    size_t *current_held = malloc(bytes), *candidate_held = malloc(bytes);
    size_t *best_held = malloc(bytes);
    if (!current || !candidate || !current_held || !candidate_held || !best_held) {
        free(current);
        free(candidate);
        free(current_held);
        free(candidate_held);
        free(best_held);
        return ur_error_out_of_memory(n->error);
    }
    memcpy(current, order, bytes);
    for (size_t p = 0; p < n->count; p++)
        current_held[p] = best_held[p] = ANY_TURN;
    bool turns = n->turn_count > 1; /* some part has a choice of turns */
    uint64_t state = o->seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL;
    score best = score_of(n), now = best;
    double start = nest_seconds_now();
    double patience = fmax(NEST_PATIENCE, NEST_PATIENCE_PER_SECOND * budget);
    ur_status status = UR_OK;
    size_t since_better = 0;
    for (size_t tries = 1; status == UR_OK && tries <= NEST_TRIES &&
                           (double)since_better < patience && nest_seconds_now() - start < budget;
         tries++) {
        status = ur_context_check(n->options->context, n->error);
        if (status != UR_OK)
            break;
        memcpy(candidate, current, bytes);
        memcpy(candidate_held, current_held, bytes);
        bool turned = turns && nest_next_random(&state) % NEST_TURN_MOVES == 0 &&
                      turn_move(n, candidate_held, &state);
        if (!turned)
            mutate(candidate, n->count, &state);
        status = nest_run_order(n, candidate, candidate_held);
        score s = score_of(n);
        since_better++;
        if (status != UR_OK || compare_scores(s, now) < 0)
            continue;
        now = s;
        memcpy(current, candidate, bytes);
        memcpy(current_held, candidate_held, bytes);
        if (compare_scores(s, best) > 0) {
            best = s;
            memcpy(order, candidate, bytes);
            memcpy(best_held, candidate_held, bytes);
            since_better = 0;
            if (o->progress)
                o->progress(o->progress_context, s.sheets, s.length, tries);
        }
    }
    if (status == UR_OK)
        status = nest_run_order(n, order, best_held); /* the best, placed again */
    free(current);
    free(candidate);
    free(current_held);
    free(candidate_held);
    free(best_held);
    return status;
}

/* ---- Fewer sheets, and the last one's offcut --------------------------------- */

/*
 * Martello and Toth's bound L2 on the bins of capacity `capacity` that
 * items of the sizes given (size(items, k) for k < count) need.  For each
 * alpha (0, or an item's size up to half a bin): an item larger than
 * capacity - alpha shares its bin with no item of alpha or more, and no
 * two items larger than half a bin share one, so each of those takes a
 * bin; the items from alpha to half a bin that the room left beside the
 * second kind cannot hold need bins of their own.  The largest over
 * alpha; O(count^2), and no memory.
 */
size_t nest_bins_bound(double (*size)(const void *items, size_t k), const void *items, size_t count,
                       double capacity)
{
    size_t best = 0;
    for (size_t a = 0; a <= count; a++) {
        double alpha = a < count ? size(items, a) : 0.0;
        if (alpha > capacity / 2)
            continue;
        size_t alone = 0, large = 0; /* over capacity - alpha; over half and up to it */
        double large_room = 0, small = 0;
        for (size_t k = 0; k < count; k++) {
            double s = size(items, k);
            if (s > capacity - alpha) {
                alone++;
            } else if (s > capacity / 2) {
                large++;
                large_room += capacity - s;
            } else if (s >= alpha) {
                small += s;
            }
        }
        double over = ceil((small - large_room) / capacity);
        size_t bound = alone + large + (over > 0 ? (size_t)over : 0);
        if (bound > best)
            best = bound;
    }
    return best;
}

/* The area of a nester's piece, as nest_bins_bound asks for sizes. */
static double shape_area(const void *items, size_t piece)
{
    return nest_shape_of(items, piece, 0)->area;
}

/*
 * The fewest stock sheets any layout needs by area: the parts' area less
 * the room inside the remnants' margins, over the room inside a stock
 * sheet's, rounded up.  Without remnants, better: parts on one sheet do
 * not overlap and lie inside its margins, so the areas of each sheet's
 * parts add up to no more than that room, and the sheets of any layout
 * hold the parts' areas as bins of that capacity hold items of those
 * sizes; nest_bins_bound's bound on such bins is one on the sheets (two
 * parts larger than half the room, say, never share a sheet), with the
 * capacity a billionth larger so that parts that tile a sheet exactly are
 * not kept apart by rounding.
 */
static size_t stock_sheets_bound(const nester *n)
{
    const ur_nest_options *o = n->options;
    double area = 0;
    for (size_t p = 0; p < n->count; p++)
        area += nest_shape_of(n, p, 0)->area;
    for (size_t s = 0; s < n->remnant_count; s++) {
        double width, height;
        nest_sheet_size(n, s, &width, &height);
        area -= fmax(0, (width - 2 * o->margin) * (height - 2 * o->margin));
    }
    double room = (o->sheet_width - 2 * o->margin) * (o->sheet_height - 2 * o->margin);
    double bound = area > 0 ? ceil(area / room - 1e-9) : 0;
    if (n->remnant_count == 0)
        bound = fmax(bound, (double)nest_bins_bound(shape_area, n, n->count, room * (1 + 1e-9)));
    return bound < (double)n->count ? (size_t)bound : n->count;
}

/* A stock sheet and the area of its parts, to sort the fullest first. */
typedef struct sheet_fill {
    double area;
    size_t sheet;
} sheet_fill;

static int fuller_first(const void *a, const void *b)
{
    const sheet_fill *x = a, *y = b;
    if (x->area != y->area)
        return x->area > y->area ? -1 : 1;
    return (x->sheet > y->sheet) - (x->sheet < y->sheet);
}

/*
 * Numbers the stock sheets anew, the fullest first (the remnants keep
 * theirs): the sheet search drops the last ones, and the last is the one
 * whose parts are pushed to one end.  Only once the nester's rooms are no
 * longer needed: they are kept per sheet number.
 */
static ur_status number_fullest_first(nester *n)
{
    size_t stock = n->sheet_count - n->remnant_count;
    sheet_fill *fills = calloc(stock + 1, sizeof *fills);
    size_t *renumbered = calloc(n->sheet_count + 1, sizeof *renumbered);
    if (!fills || !renumbered) {
        free(fills);
        free(renumbered);
        return ur_error_out_of_memory(n->error);
    }
    for (size_t k = 0; k < stock; k++)
        fills[k] = (sheet_fill){n->sheet_area[n->remnant_count + k], n->remnant_count + k};
    qsort(fills, stock, sizeof *fills, fuller_first);
    for (size_t s = 0; s < n->remnant_count; s++)
        renumbered[s] = s;
    for (size_t k = 0; k < stock; k++) {
        renumbered[fills[k].sheet] = n->remnant_count + k;
        n->sheet_area[n->remnant_count + k] = fills[k].area;
    }
    for (size_t p = 0; p < n->placed_count; p++)
        n->sheet_of[p] = renumbered[n->sheet_of[p]];
    free(fills);
    free(renumbered);
    return UR_OK;
}

/*
 * The most parts, and shapes at their turns, the searches on sheets take
 * on: each keeps tables of every pair of parts (32 bytes a pair) and of
 * every pair of shapes at their turns (a flattened no-fit polygon's
 * header, near 200 bytes a pair), which for thousands would be
 * gigabytes.  A layout of more stays as the search over orders left it.
 */
#define SEARCH_PARTS_MOST 1000
#define SEARCH_SHAPE_TURNS_MOST 600

/* Whether the searches on sheets take on count parts of the nester's. */
static bool searchable(const nester *n, size_t count)
{
    return count <= SEARCH_PARTS_MOST && n->class_count * n->turn_count <= SEARCH_SHAPE_TURNS_MOST;
}

/* The parts on a sheet of the nester. */
static size_t parts_on(const nester *n, size_t sheet)
{
    size_t count = 0;
    for (size_t p = 0; p < n->placed_count; p++)
        count += n->sheet_of[p] == sheet;
    return count;
}

/*
 * After the search over orders, on sheets with every part placed: fewer
 * stock sheets, from the area bound up (nest_fewer_sheets), until
 * fewer_until; then the last stock sheet's parts pushed to its left end
 * until deadline.
 */
ur_status nest_sheets_search(nester *n, double fewer_until, double deadline)
{
    if (n->placed_count < n->count || n->sheet_count <= n->remnant_count)
        return UR_OK;
    ur_status status = number_fullest_first(n);
    if (status == UR_OK && searchable(n, n->placed_count))
        status = nest_fewer_sheets(n, stock_sheets_bound(n), fewer_until);
    if (status == UR_OK)
        status = number_fullest_first(n);
    if (status == UR_OK && n->sheet_count > n->remnant_count &&
        searchable(n, parts_on(n, n->sheet_count - 1)))
        status = nest_push_to_one_end(n, n->sheet_count - 1, deadline);
    return status;
}

/*
 * The last stock sheet's offcut: from its parts' right edges and the
 * spacing to the sheet's right edge.
 */
void nest_measure_offcut(const nester *n, ur_layout *layout)
{
    if (n->sheet_count <= n->remnant_count || layout->sheet_count == 0)
        return;
    size_t last = n->sheet_count - 1;
    double reach = 0;
    for (size_t p = 0; p < n->placed_count; p++) {
        const placed *part = &n->placements[p];
        if (n->sheet_of[p] == last)
            reach = fmax(reach, part->at.x + nest_shape_of(n, part->piece, part->turn)->box.max.x);
    }
    ur_sheet *sheet = &layout->sheets[layout->sheet_count - 1];
    sheet->offcut_width = fmax(0, sheet->width - reach - n->options->spacing);
}
