/*
 * compact_run.c: setting up the overlap searches of compact.c and running
 * them side by side, one per thread: each with its own random steps and
 * copies of the no-fit polygons, all sharing the shortest layout found,
 * which the nester takes back at the end (nest_compact_roll,
 * nest_push_to_one_end, nest_fewer_sheets).
 */
#include "compact_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void state_free(state *s)
{
    free(s->turn);
    free(s->at);
    free(s->sheet);
}

static bool state_make(state *s, size_t count)
{
    *s = (state){calloc(count, sizeof(size_t)), calloc(count, sizeof(ur_vec2)),
                 calloc(count, sizeof(size_t))};
    return s->turn && s->at && s->sheet;
}

static void compactor_free(compactor *c)
{
    size_t keys = c->n->class_count * c->n->turn_count * c->n->class_count * c->n->turn_count;
    for (size_t k = 0; c->nfps && k < keys; k++)
        depth_index_free(&c->nfps[k]);
    free(c->nfps);
    free(c->index);
    free(c->piece);
    state_free(&c->now);
    state_free(&c->best);
    state_free(&c->least);
    free(c->depth);
    free(c->weight);
    free(c->pair_scale);
    free(c->pair_floor);
    free(c->row);
    free(c->order);
    for (size_t k = 0; k < NEAR_MISSES; k++)
        state_free(&c->misses.layout[k]);
}

/*
 * What a search works on: the parts on one sheet as a strip (sheets 0:
 * a roll, or to_one_end), or every part on the first sheets (a sheet
 * search: the parts of the others put at the end of the last).
 */
typedef struct search_kind {
    size_t sheet;  /* the strip's sheet (a sheet search: the last it keeps) */
    size_t sheets; /* a sheet search: how many sheets it keeps (remnants too); 0 otherwise */
    bool to_one_end;
} search_kind;

/* Whether the nester's placement p is one the search works on. */
static bool searched(const nester *n, const search_kind *kind, size_t p)
{
    return kind->sheets > 0 || n->sheet_of[p] == kind->sheet;
}

/* The stock sheets the nester's layout uses. */
static size_t stock_sheets_of(const nester *n)
{
    return n->sheet_count > n->remnant_count ? n->sheet_count - n->remnant_count : 0;
}

/*
 * A sheet search's first layout: the parts of each sheet past the last
 * kept go on the last, a sheet's length (and the spacing) further along
 * for each sheet past it, so that the last sheet is a strip as long as
 * all of them, to be shortened to its own length.
 */
static void lengthen_last_sheet(compactor *c)
{
    double step = c->sheet_length + c->n->options->spacing;
    for (size_t i = 0; i < c->count; i++)
        if (c->now.sheet[i] > c->strip_sheet) {
            c->now.at[i].x += step * (double)(c->now.sheet[i] - c->strip_sheet);
            c->now.sheet[i] = c->strip_sheet;
        }
}

/*
 * Sets up search number k (its own random steps) over the count parts the
 * kind says, from the nester's layout; false when out of memory.
 */
static bool compactor_make(compactor *c, nester *n, const search_kind *kind, size_t count,
                           shared_best *shared, size_t k)
{
    size_t keys = n->class_count * n->turn_count * n->class_count * n->turn_count;
    double width, height;
    nest_sheet_size(n, kind->sheet, &width, &height);
    *c = (compactor){.n = n,
                     .shared = shared,
                     .count = count,
                     .across_sheets = kind->sheets > 0,
                     .to_one_end = kind->to_one_end,
                     .strip_sheet = kind->sheet,
                     .sheet_count = kind->sheets,
                     .sheet_length = width - 2 * n->options->margin,
                     .stock_sheets = stock_sheets_of(n)};
    c->random = (n->options->seed + k) * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL;
    c->index = calloc(count, sizeof *c->index);
    c->piece = calloc(count, sizeof *c->piece);
    bool states =
        state_make(&c->now, count) && state_make(&c->best, count) && state_make(&c->least, count);
    c->depth = calloc(count * count, sizeof *c->depth);
    c->weight = calloc(count * count, sizeof *c->weight);
    c->pair_scale = calloc(count * count, sizeof *c->pair_scale);
    c->pair_floor = calloc(count * count, sizeof *c->pair_floor);
    c->row = calloc(count * n->turn_count, sizeof *c->row);
    c->nfps = calloc(keys, sizeof *c->nfps);
    c->order = calloc(count, sizeof *c->order);
    if (!c->index || !c->piece || !states || !c->depth || !c->weight || !c->pair_scale ||
        !c->pair_floor || !c->row || !c->nfps || !c->order)
        return false;
    for (size_t m = 0; m < NEAR_MISSES; m++)
        if (!state_make(&c->misses.layout[m], count))
            return false;
    for (size_t p = 0, i = 0; p < n->placed_count; p++)
        if (searched(n, kind, p)) {
            c->index[i] = p;
            c->piece[i] = n->placements[p].piece;
            c->now.turn[i] = n->placements[p].turn;
            c->now.sheet[i] = n->sheet_of[p];
            c->now.at[i++] = n->placements[p].at;
        }
    if (c->across_sheets)
        lengthen_last_sheet(c);
    c->length = compact_reach_of(c);
    compact_size_pairs(c);
    return true;
}

/*
 * A search in a thread of its own: the depths of its first layout, then
 * the search.  If rounding makes a pair of the first layout's parts look
 * a nanometre deep, the search clears that on the way.
 */
static int run_search(void *context)
{
    compactor *c = context;
    if (!compact_recompute_depths(c))
        c->status = compact_failure(c);
    else
        c->status = c->across_sheets ? compact_search_fewer(c)
                    : c->to_one_end  ? compact_push_to_one_end(c)
                                     : compact_search_shorter(c);
    return 0;
}

/* Searches run side by side: options->threads, or one per processor. */
static size_t search_count(const ur_nest_options *o)
{
    if (o->threads > 0)
        return o->threads < NEST_MAX_THREADS ? o->threads : NEST_MAX_THREADS;
    long processors = sysconf(_SC_NPROCESSORS_ONLN);
    return processors < 1                  ? 1
           : processors < NEST_MAX_THREADS ? (size_t)processors
                                           : NEST_MAX_THREADS;
}

/*
 * Runs the searches (the first in this thread, the others in threads of
 * their own: fewer if a thread cannot start) and waits for them all; the
 * first failure's status, its message in the nester's error.
 */
static ur_status run_searches(compactor *searches, size_t count)
{
    thrd_t threads[NEST_MAX_THREADS];
    bool started[NEST_MAX_THREADS] = {false};
    for (size_t k = 1; k < count; k++)
        started[k] = thrd_create(&threads[k], run_search, &searches[k]) == thrd_success;
    run_search(&searches[0]);
    for (size_t k = 1; k < count; k++)
        if (started[k])
            thrd_join(threads[k], NULL);
    for (size_t k = 0; k < count; k++)
        if ((k == 0 || started[k]) && searches[k].status != UR_OK) {
            if (searches[0].n->error)
                *searches[0].n->error = searches[k].error;
            return searches[k].status;
        }
    return UR_OK;
}

/*
 * Writes the best layout back into the nester: the parts' turns and
 * places, and after a sheet search, their sheets and the sheets' count
 * and areas.
 */
static void write_back(nester *n, const compactor *c, const shared_best *shared)
{
    for (size_t i = 0; i < c->count; i++) {
        n->placements[c->index[i]].turn = shared->best.turn[i];
        n->placements[c->index[i]].at = shared->best.at[i];
        n->sheet_of[c->index[i]] = shared->best.sheet[i];
    }
    if (!c->across_sheets)
        return;
    n->sheet_count = c->sheet_count;
    memset(n->sheet_area, 0, n->sheet_slots * sizeof *n->sheet_area);
    for (size_t p = 0; p < n->placed_count; p++)
        n->sheet_area[n->sheet_of[p]] += nest_shape_of(n, n->placements[p].piece, 0)->area;
}

/*
 * Sets up and runs the searches of a kind over count parts until deadline,
 * and keeps what they found: a shorter strip, or a sheet search's layout
 * if its last sheet is no longer than itself (*done then).
 */
static ur_status run_kind(nester *n, const search_kind *kind, size_t count, double deadline,
                          bool *done)
{
    shared_best shared = {.length = 0};
    atomic_init(&shared.version, 0);
    atomic_init(&shared.separations, 0);
    bool lock_made = mtx_init(&shared.lock, mtx_plain) == thrd_success;
    size_t search_total = kind->to_one_end ? 1 : search_count(n->options), made = 0;
    compactor searches[NEST_MAX_THREADS];
    ur_status status =
        state_make(&shared.best, count) && lock_made ? UR_OK : ur_error_out_of_memory(n->error);
    for (; status == UR_OK && made < search_total; made++)
        if (!compactor_make(&searches[made], n, kind, count, &shared, made)) {
            status = ur_error_out_of_memory(n->error);
            made++; /* freed below */
            break;
        }
    if (status == UR_OK) {
        /* The first layout is everyone's best until a better one is separated and verified. */
        shared.length = compact_reach_of(&searches[0]);
        compact_copy_state(&searches[0], &shared.best, &searches[0].now);
        for (size_t k = 0; k < made; k++)
            searches[k].deadline = deadline;
        status = run_searches(searches, made);
    }
    *done = status == UR_OK && (kind->sheets == 0 || shared.length <= searches[0].sheet_length);
    if (*done)
        write_back(n, &searches[0], &shared);
    for (size_t k = 0; k < made; k++)
        compactor_free(&searches[k]);
    if (lock_made)
        mtx_destroy(&shared.lock);
    state_free(&shared.best);
    return status;
}

/* Runs a strip search over the parts on sheet: the roll's, or one end's (to_one_end). */
static ur_status compact_strip(nester *n, size_t sheet, bool to_one_end, double deadline)
{
    size_t count = 0;
    for (size_t k = 0; k < n->placed_count; k++)
        count += n->sheet_of[k] == sheet;
    if (count < 2 || nest_seconds_now() > deadline)
        return UR_OK;
    search_kind kind = {.sheet = sheet, .to_one_end = to_one_end};
    bool done;
    return run_kind(n, &kind, count, deadline, &done);
}

ur_status nest_compact_roll(nester *n, double deadline)
{
    return compact_strip(n, n->remnant_count, false, deadline);
}

ur_status nest_push_to_one_end(nester *n, size_t sheet, double deadline)
{
    return compact_strip(n, sheet, true, deadline);
}

ur_status nest_fewer_sheets(nester *n, size_t least, double deadline)
{
    size_t stock = stock_sheets_of(n);
    least = least > 1 ? least : 1;
    if (n->placed_count < 2 || stock <= least)
        return UR_OK;
    double start = nest_seconds_now(), share = (deadline - start) / (double)(stock - least);
    bool done = false;
    ur_status status = UR_OK;
    for (size_t k = least; status == UR_OK && !done && k < stock; k++) {
        double until = start + share * (double)(k - least + 1);
        if (nest_seconds_now() >= until)
            continue;
        search_kind kind = {.sheet = n->remnant_count + k - 1, .sheets = n->remnant_count + k};
        status = run_kind(n, &kind, n->placed_count, until, &done);
    }
    return status;
}
