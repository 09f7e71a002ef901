/*
 * compact.c: shortening a roll layout by overlap minimisation, and the
 * same search on sheets: fewer sheets, and the last one's parts pushed to
 * one end.
 *
 * The first layout (nest.c) places each part where it fits; this search
 * lets parts overlap on the way to a shorter strip, as the best strip
 * packers do (guided local search, after Egeblad et al. 2007, Umetani et
 * al. 2009 and Gardeyn and Wauters 2025).  From the shortest layout found
 * so far it cuts the strip a little shorter, taking a slice out of it at a
 * random place (the parts beyond it move back, now overlapping those
 * before it), and then separates them: each overlapping part
 * in turn moves to the place and turn where it overlaps the others least
 * (random places across the strip at random turns, and near its own, the
 * best refined by smaller and smaller steps, then pushed out of the part
 * it overlaps most, to touch it exactly).  Overlap is the penetration
 * depth: how far a part must move to leave another, read off their no-fit
 * polygon (the distance from the one's origin to that polygon's edge when
 * it lies inside).  A part's cost at a place is the sum over the parts it
 * overlaps of the depth plus a floor, scaled by the pair's size and
 * weighted (see pair_cost).  Pairs that keep overlapping weigh more each
 * round (guided local search), so the parts make room for each other
 * instead of stopping at the first crowded layout.
 *
 * Exploration (most of the time) cuts 0.3% at a time; when the parts cannot
 * be separated it keeps the least overlapping layout among its near misses
 * at that length, jolts one of the best of them (two parts trade places)
 * and tries the same length again.  Compression (the rest) cuts
 * less and less from the best, once each.  Only layouts with no overlap
 * left are kept, so what the nester writes never overlaps.
 *
 * On sheets the parts may move between the nester's sheets as well
 * (random places on any of them): to put a layout on fewer sheets, the
 * parts of the sheets to drop go at the end of the last sheet kept, as if
 * it were a roll that long, and that strip is shortened as a roll is until
 * it is no longer than the sheet (search_fewer).  To leave the last
 * sheet's offcut whole, that sheet alone is shortened (push_to_one_end).
 *
 * Several searches may run side by side, one per thread (compact_run.c),
 * each with its own random steps and copies of the no-fit polygons; they
 * share the shortest layout found (each goes on from it as soon as it sees
 * it), and take turns with the nester, whose GEOS context is not theirs to
 * share.  The depths come from each no-fit polygon's index (depth_index.c).
 */
#include "compact_internal.h"

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>
#include <unistd.h>

/* Random places tried across the strip, and near the part, when a part moves. */
#define PLACES_ACROSS 60
#define PLACES_NEAR 20
/* The finest step of a move's refinement, as a fraction of the part's size. */
#define REFINE_FINEST 1e-4
/* Pushes out of the part a move overlaps most, at most. */
#define PUSHES_OUT 4
/*
 * Rounds of moves without a gain before a separation tries again from its
 * least overlapping layout: ROUNDS_PER_PART per part on the roll, at least
 * ROUNDS_WITHOUT_GAIN.  A round moves each overlapping part once, and the
 * more parts, the more rounds a gain takes to show (at 30 s, 50 rounds
 * did best with 25 parts, 200 with 99).  A gain is a fall of the total
 * overlap by GAIN below its least: smaller falls would keep a separation
 * that is going nowhere creeping on.
 */
#define ROUNDS_WITHOUT_GAIN 50
#define ROUNDS_PER_PART 2
#define GAIN 0.02
/* Tries in a row without a gain before a separation gives up. */
#define STRIKES 3
/*
 * The floor of an overlap's cost, as a fraction of the larger part's size
 * (sparrow's 1%): any overlap, however shallow, then costs something.
 */
#define OVERLAP_FLOOR 0.01
/*
 * Exploration's share of the time, and its cut of the strip (a fraction of
 * its length): small steps let the layout change bit by bit (with 1%,
 * jakobs2 stayed at the length of its first layout; 0.1%, sparrow's, was
 * slow on shirts' 99 parts at 60 s).
 */
#define EXPLORE_SHARE 0.8
#define EXPLORE_CUT 0.003
/*
 * How exploration picks the near miss (NEAR_MISSES, compact_internal.h) to
 * jolt next: the k-th best with k a fraction of them drawn from a
 * half-normal spread (Gardeyn and Wauters's 0.25), so mostly among the
 * best few but now and then a worse one.
 */
#define NEAR_MISS_SPREAD 0.25
/* Compression's first and last cut, and the failed cuts in a row that end it. */
#define COMPRESS_FIRST 0.005
#define COMPRESS_LAST 0.0001
#define COMPRESS_PATIENCE 200

/* A uniform random number in [0, 1). */
static double uniform(uint64_t *seed)
{
    return (double)(nest_next_random(seed) >> 11) * 0x1.0p-53;
}

/*
 * The no-fit polygon of part b at turn tb around part a at turn ta,
 * flattened; NULL on a failure, or (c->out_of_time) when it is not made
 * yet and the deadline has passed.  Making one is the union of many convex
 * sums for parts of many convex pieces (a net with its tabs): the pairs of
 * a 48 x 24 sphere's ten nets took a second, and the search for fewer
 * sheets went on that long past its budget before this check.
 */
static const depth_index *nfp_between(compactor *c, size_t a, size_t ta, size_t b, size_t tb)
{
    nester *n = c->n;
    size_t pa = c->piece[a], pb = c->piece[b], t = n->turn_count;
    size_t key = ((n->class_of[pa] * t + ta) * n->class_count + n->class_of[pb]) * t + tb;
    depth_index *f = &c->nfps[key];
    if (f->made)
        return f;
    if (nest_seconds_now() > c->deadline) {
        c->out_of_time = true;
        return NULL;
    }
    mtx_lock(&c->shared->lock);
    const GEOSGeometry *g = nest_nfp_of(n, pa, ta, pb, tb);
    bool made = g && depth_index_make(n->geos, g, f);
    mtx_unlock(&c->shared->lock);
    if (!made) {
        depth_index_free(f);
        return NULL;
    }
    f->made = true;
    return f;
}

ur_status compact_failure(compactor *c)
{
    if (c->out_of_time) {
        c->out_of_time = false;
        return UR_OK;
    }
    return ur_error_out_of_memory(&c->error);
}

/* How far parts i and j overlap where they are now (0 on different sheets); -1 on a failure. */
static double pair_depth(compactor *c, size_t i, size_t j)
{
    if (c->now.sheet[i] != c->now.sheet[j])
        return 0;
    const depth_index *f = nfp_between(c, j, c->now.turn[j], i, c->now.turn[i]);
    if (!f)
        return -1;
    return depth_index_depth(
        f, ur_vec2_make(c->now.at[i].x - c->now.at[j].x, c->now.at[i].y - c->now.at[j].y));
}

/* Brings the depth of the pair i, j up to date (both ways); false on a failure. */
static bool refresh_pair(compactor *c, size_t i, size_t j)
{
    double d = pair_depth(c, i, j);
    if (d < 0)
        return false;
    c->depth[i * c->count + j] = c->depth[j * c->count + i] = d;
    return true;
}

/* Brings part i's row and column of depths up to date; false on a failure. */
static bool update_depths(compactor *c, size_t i)
{
    for (size_t j = 0; j < c->count; j++)
        if (j != i && !refresh_pair(c, i, j))
            return false;
    return true;
}

static double total_depth(const compactor *c)
{
    double total = 0;
    for (size_t i = 0; i < c->count; i++)
        for (size_t j = i + 1; j < c->count; j++)
            total += c->depth[i * c->count + j];
    return total;
}

static bool overlaps_any(const compactor *c, size_t i)
{
    for (size_t j = 0; j < c->count; j++)
        if (c->depth[i * c->count + j] > 0)
            return true;
    return false;
}

/*
 * Where part i's origin may go at turn t on sheet (x0, y0, x1, y1), inside
 * the margin and, on the strip's sheet, within c->length of it; false when
 * it does not fit there at that turn.
 */
static bool inner_fit(const compactor *c, size_t sheet, size_t i, size_t t, double *box)
{
    const nester *n = c->n;
    const ur_nest_options *o = n->options;
    const nest_shape *shape = nest_shape_of(n, c->piece[i], t);
    double width, height;
    nest_sheet_size(n, sheet, &width, &height);
    box[0] = o->margin - shape->box.min.x;
    box[1] = o->margin - shape->box.min.y;
    box[2] =
        (sheet == c->strip_sheet ? o->margin + c->length : width - o->margin) - shape->box.max.x;
    box[3] = height - o->margin - shape->box.max.y;
    return box[2] >= box[0] && box[3] >= box[1];
}

/* Where part i may go at turn t on the sheet it is on now (inner_fit). */
static bool fits_where_it_is(const compactor *c, size_t i, size_t t, double *box)
{
    return inner_fit(c, c->now.sheet[i], i, t, box);
}

/* A candidate: part i at turn t, its origin at p on sheet, and its weighted overlap there. */
typedef struct candidate {
    size_t turn;
    ur_vec2 at;
    double cost;
    size_t sheet;
} candidate;

/*
 * Fills c->row (per turn, per part) with the no-fit polygons part i meets
 * at each of its turns; false on a failure.
 */
static bool fill_rows(compactor *c, size_t i, size_t turns)
{
    for (size_t t = 0; t < turns; t++)
        for (size_t j = 0; j < c->count; j++) {
            if (j == i)
                continue;
            c->row[t * c->count + j] = nfp_between(c, j, c->now.turn[j], i, t);
            if (!c->row[t * c->count + j])
                return false;
        }
    return true;
}

/*
 * What parts i and j overlapping by depth d (> 0) cost: the depth plus a
 * floor, times the pair's size and weight, as in sparrow (Gardeyn and
 * Wauters 2025: the square root of an overlap area, plus a floor, times
 * the geometric mean of the parts' square-rooted areas).  The floor makes
 * every overlap count, however shallow, so that a move clears overlaps
 * rather than spreading them thin; the size makes large parts' overlaps
 * count more, so they settle first and the small ones fill in around them.
 * With squared depths and no size, most 60 s runs of jakobs2 ended in its
 * two-column layout (24.00); with this cost, none of 8 did (see
 * bench/esicup/README.md).
 */
static double pair_cost(const compactor *c, size_t i, size_t j, double d)
{
    size_t k = i * c->count + j;
    return c->weight[k] * (d + c->pair_floor[k]) * c->pair_scale[k];
}

/* Part i's cost (pair_cost) at turn t and p on sheet, given up once above limit. */
static double cost_at(const compactor *c, size_t i, size_t t, size_t sheet, ur_vec2 p, double limit)
{
    const depth_index *const *row = c->row + t * c->count;
    double cost = 0;
    for (size_t j = 0; j < c->count && cost < limit; j++) {
        if (j == i || c->now.sheet[j] != sheet)
            continue;
        double d =
            depth_index_depth(row[j], ur_vec2_make(p.x - c->now.at[j].x, p.y - c->now.at[j].y));
        if (d > 0)
            cost += pair_cost(c, i, j, d);
    }
    return cost;
}

static ur_vec2 clamp_to(ur_vec2 p, const double *box)
{
    return ur_vec2_make(fmin(fmax(p.x, box[0]), box[2]), fmin(fmax(p.y, box[1]), box[3]));
}

/* Tries part i at turn t and p on sheet: the new best candidate when it overlaps less. */
static void try_place(const compactor *c, size_t i, size_t t, size_t sheet, ur_vec2 p,
                      candidate *best)
{
    double cost = cost_at(c, i, t, sheet, p, best->cost);
    if (cost < best->cost)
        *best = (candidate){t, p, cost, sheet};
}

/*
 * Refines a candidate by steps in eight directions, halving the step when
 * none helps, down to REFINE_FINEST of the part's size.
 */
static void refine(const compactor *c, size_t i, const double *box, double size, candidate *best)
{
    static const double dx[8] = {1, -1, 0, 0, 0.7071, -0.7071, 0.7071, -0.7071};
    static const double dy[8] = {0, 0, 1, -1, 0.7071, 0.7071, -0.7071, -0.7071};
    for (double step = 0.05 * size; step > REFINE_FINEST * size && best->cost > 0;) {
        bool better = false;
        for (int k = 0; k < 8 && !better; k++) {
            double before = best->cost;
            ur_vec2 p = {best->at.x + step * dx[k], best->at.y + step * dy[k]};
            try_place(c, i, best->turn, best->sheet, clamp_to(p, box), best);
            better = best->cost < before;
        }
        if (!better)
            step *= 0.5;
    }
}

/*
 * Pushes a candidate out of the part it overlaps most (pair_cost), across
 * the nearest edge of their no-fit polygon, while that lowers its cost.
 * Refinement only comes near a contact; this reaches it exactly, as a part
 * between two others or in a notch of its own width must.
 */
static void push_out(const compactor *c, size_t i, const double *box, candidate *best)
{
    const depth_index *const *row = c->row + best->turn * c->count;
    for (int push = 0; push < PUSHES_OUT && best->cost > 0; push++) {
        size_t most = i;
        double most_cost = 0;
        for (size_t j = 0; j < c->count; j++) {
            double d = j == i || c->now.sheet[j] != best->sheet
                           ? 0
                           : depth_index_depth(row[j], ur_vec2_make(best->at.x - c->now.at[j].x,
                                                                    best->at.y - c->now.at[j].y));
            double cost = d > 0 ? pair_cost(c, i, j, d) : 0;
            if (cost > most_cost) {
                most_cost = cost;
                most = j;
            }
        }
        if (most == i)
            return;
        ur_vec2 from = c->now.at[most];
        ur_vec2 out =
            depth_index_way_out(row[most], ur_vec2_make(best->at.x - from.x, best->at.y - from.y));
        ur_vec2 p = ur_vec2_make(out.x + from.x, out.y + from.y);
        if (p.x < box[0] || p.x > box[2] || p.y < box[1] || p.y > box[3])
            return;
        double before = best->cost;
        try_place(c, i, best->turn, best->sheet, p, best);
        if (best->cost >= before)
            return;
    }
}

/* Part i's size: the longer side of its box at turn 0. */
static double part_size(const compactor *c, size_t i)
{
    const nest_shape *shape = nest_shape_of(c->n, c->piece[i], 0);
    return fmax(ur_box_width(shape->box), ur_box_height(shape->box));
}

/* A sheet for a random place: the strip's, or in a sheet search any. */
static size_t random_sheet(compactor *c)
{
    if (!c->across_sheets)
        return c->strip_sheet;
    return c->sheet_count > 1 ? nest_next_random(&c->random) % c->sheet_count : 0;
}

/*
 * Moves part i to where it overlaps the others least (weighted): random
 * places across the strip (or the sheets) at random turns and near where
 * it is, the best refined.  False on a failure.
 */
static bool move_part(compactor *c, size_t i)
{
    nester *n = c->n;
    size_t turns = n->classes[n->class_of[c->piece[i]]].turn_count;
    double size = part_size(c, i);
    double box[4];
    size_t turn = c->now.turn[i], sheet = c->now.sheet[i];
    if (!fill_rows(c, i, turns))
        return false;
    /* Left outside a shorter strip, or on a sheet no longer used, it may go anywhere inside. */
    bool fits = inner_fit(c, sheet, i, turn, box);
    candidate best = {turn, c->now.at[i],
                      fits ? cost_at(c, i, turn, sheet, c->now.at[i], INFINITY) : INFINITY, sheet};
    for (int k = 0; fits && k < PLACES_NEAR; k++) {
        ur_vec2 p = {c->now.at[i].x + (2 * uniform(&c->random) - 1) * 0.25 * size,
                     c->now.at[i].y + (2 * uniform(&c->random) - 1) * 0.25 * size};
        try_place(c, i, turn, sheet, clamp_to(p, box), &best);
    }
    for (int k = 0; k < PLACES_ACROSS; k++) {
        size_t t = nest_next_random(&c->random) % turns, s = random_sheet(c);
        if (!inner_fit(c, s, i, t, box))
            continue;
        ur_vec2 p = {box[0] + uniform(&c->random) * (box[2] - box[0]),
                     box[1] + uniform(&c->random) * (box[3] - box[1])};
        try_place(c, i, t, s, p, &best);
    }
    if (!isfinite(best.cost))
        return true; /* no turn fits the strip: the caller keeps it longer */
    (void)inner_fit(c, best.sheet, i, best.turn, box); /* it fits: best was found inside it */
    refine(c, i, box, size, &best);
    push_out(c, i, box, &best);
    c->now.turn[i] = best.turn;
    c->now.at[i] = best.at;
    c->now.sheet[i] = best.sheet;
    return update_depths(c, i);
}

/*
 * Guided local search's weights: pairs that overlap weigh more, the more
 * their depth times size (pair_cost's) against the worst pair's, and the
 * others fall back toward 1.
 */
static void update_weights(compactor *c)
{
    size_t pairs = c->count * c->count;
    double worst = 0;
    for (size_t k = 0; k < pairs; k++)
        worst = fmax(worst, c->depth[k] * c->pair_scale[k]);
    for (size_t k = 0; k < pairs; k++)
        c->weight[k] = c->depth[k] > 0
                           ? c->weight[k] * (1.2 + 0.8 * c->depth[k] * c->pair_scale[k] / worst)
                           : fmax(1.0, 0.95 * c->weight[k]);
}

void compact_copy_state(const compactor *c, state *to, const state *from)
{
    memcpy(to->turn, from->turn, c->count * sizeof *to->turn);
    memcpy(to->at, from->at, c->count * sizeof *to->at);
    memcpy(to->sheet, from->sheet, c->count * sizeof *to->sheet);
}

bool compact_recompute_depths(compactor *c)
{
    for (size_t i = 0; i < c->count; i++)
        for (size_t j = i + 1; j < c->count; j++)
            if (!refresh_pair(c, i, j))
                return false;
    return true;
}

/* Shuffles the first count entries of order. */
static void shuffle(size_t *order, size_t count, uint64_t *random)
{
    for (size_t k = count; k > 1; k--) {
        size_t j = nest_next_random(random) % k, swap = order[k - 1];
        order[k - 1] = order[j];
        order[j] = swap;
    }
}

/* One round: each overlapping part, in random order, moves once; false on a failure. */
static bool move_overlapping(compactor *c)
{
    for (size_t k = 0; k < c->count; k++)
        c->order[k] = k;
    shuffle(c->order, c->count, &c->random);
    for (size_t k = 0; k < c->count; k++)
        if (overlaps_any(c, c->order[k]) && !move_part(c, c->order[k]))
            return false;
    return true;
}

/*
 * Separates the parts in the strip of c->length: rounds of moves of every
 * overlapping part, weights updated after each.  A try ends after a run of
 * rounds (patience) that did not bring the total overlap GAIN below its
 * least so far, and the next starts from the least overlapping layout; a
 * try that brought no such gain at all is a strike, and STRIKES in a row
 * end the separation.  True when no overlap is left (c->now holds that
 * layout); false when it gives up (c->now is then its least overlapping
 * layout) or time runs out, *status set on a failure.
 */
static bool separate(compactor *c, ur_status *status)
{
    atomic_fetch_add(&c->shared->separations, 1);
    size_t patience = c->count * ROUNDS_PER_PART;
    if (patience < ROUNDS_WITHOUT_GAIN)
        patience = ROUNDS_WITHOUT_GAIN;
    for (size_t k = 0; k < c->count * c->count; k++)
        c->weight[k] = 1.0;
    double least_total = total_depth(c);
    compact_copy_state(c, &c->least, &c->now);
    for (int strikes = 0; strikes < STRIKES;) {
        double try_start = least_total;
        for (size_t idle = 0; idle < patience;) {
            *status = ur_context_check(c->n->options->context, &c->error);
            if (*status != UR_OK || nest_seconds_now() > c->deadline)
                return false;
            if (!move_overlapping(c)) {
                *status = compact_failure(c);
                return false;
            }
            double total = total_depth(c);
            if (total == 0)
                return true;
            idle = total < least_total * (1 - GAIN) ? 0 : idle + 1;
            if (total < least_total) {
                least_total = total;
                compact_copy_state(c, &c->least, &c->now);
            }
            update_weights(c);
        }
        strikes = least_total < try_start * (1 - GAIN) ? 0 : strikes + 1;
        compact_copy_state(c, &c->now, &c->least);
        if (!compact_recompute_depths(c)) {
            *status = compact_failure(c);
            return false;
        }
    }
    return false;
}

/* How far along the strip the parts on it reach now, from the margin. */
double compact_reach_of(const compactor *c)
{
    double reach = 0;
    for (size_t i = 0; i < c->count; i++)
        if (c->now.sheet[i] == c->strip_sheet)
            reach = fmax(reach, c->now.at[i].x +
                                    nest_shape_of(c->n, c->piece[i], c->now.turn[i])->box.max.x);
    return reach - c->n->options->margin;
}

/*
 * The shortest strip any layout can have: the longest of the parts' least
 * lengths over their turns, and the parts' area over the strip's width
 * (a roll's or a sheet's, every part on it).
 */
static double shortest_possible(const compactor *c)
{
    const ur_nest_options *o = c->n->options;
    double area = 0, longest = 0;
    for (size_t i = 0; i < c->count; i++) {
        const nest_class *k = &c->n->classes[c->n->class_of[c->piece[i]]];
        double least = INFINITY;
        for (size_t t = 0; t < k->turn_count; t++)
            least = fmin(least, ur_box_width(k->turns[t].box));
        longest = fmax(longest, least);
        area += k->turns[0].area;
    }
    double width, height;
    nest_sheet_size(c->n, c->strip_sheet, &width, &height);
    return fmax(longest, area / (height - 2 * o->margin));
}

/*
 * The parts that no longer fit where they are (outside a shorter strip, on
 * a sheet no longer used) move to where they overlap the others least,
 * the depths and weights made afresh first.  False on a failure.
 */
static bool move_in(compactor *c)
{
    if (!compact_recompute_depths(c))
        return false;
    for (size_t k = 0; k < c->count * c->count; k++)
        c->weight[k] = 1.0;
    for (size_t i = 0; i < c->count; i++) {
        double box[4];
        if (!fits_where_it_is(c, i, c->now.turn[i], box) && !move_part(c, i))
            return false;
    }
    return true;
}

/*
 * Cuts the strip to length: a slice as wide as the cut comes out at a
 * random place along it, the parts beyond moving back by as much, so that
 * the overlap the cut makes is spread along one line across the strip
 * rather than piled at its end; parts still outside (those the slice went
 * through) then move in, overlapping.  False on a failure.
 */
static bool cut_to(compactor *c, double length)
{
    double reach = compact_reach_of(c);
    double slice = c->n->options->margin + uniform(&c->random) * reach;
    for (size_t i = 0; i < c->count; i++) {
        const ur_box *box = &nest_shape_of(c->n, c->piece[i], c->now.turn[i])->box;
        if (c->now.sheet[i] == c->strip_sheet &&
            c->now.at[i].x + 0.5 * (box->min.x + box->max.x) > slice)
            c->now.at[i].x -= reach - length;
    }
    c->length = length;
    for (size_t i = 0; i < c->count; i++) {
        double box[4];
        if (fits_where_it_is(c, i, c->now.turn[i], box))
            c->now.at[i] = clamp_to(c->now.at[i], box);
    }
    return move_in(c);
}

/*
 * A jolt out of a crowded layout: two parts of different shapes trade
 * places (their boxes' centres), the larger parts more often.  False on a
 * failure.
 */
static bool disrupt(compactor *c)
{
    size_t i = 0, j = 0;
    for (int tries = 0; tries < 20; tries++) {
        i = nest_next_random(&c->random) % c->count;
        j = nest_next_random(&c->random) % c->count;
        /* Of two drawn parts, the larger: a bias toward large parts. */
        size_t k = nest_next_random(&c->random) % c->count,
               l = nest_next_random(&c->random) % c->count;
        if (nest_shape_of(c->n, c->piece[k], 0)->area > nest_shape_of(c->n, c->piece[i], 0)->area)
            i = k;
        if (nest_shape_of(c->n, c->piece[l], 0)->area > nest_shape_of(c->n, c->piece[j], 0)->area)
            j = l;
        if (c->n->class_of[c->piece[i]] != c->n->class_of[c->piece[j]])
            break;
    }
    if (c->n->class_of[c->piece[i]] == c->n->class_of[c->piece[j]])
        return true; /* all one shape: nothing to trade */
    /* Where each part's box centre lies from its origin. */
    const ur_box *bi = &nest_shape_of(c->n, c->piece[i], c->now.turn[i])->box;
    const ur_box *bj = &nest_shape_of(c->n, c->piece[j], c->now.turn[j])->box;
    ur_vec2 oi = ur_vec2_make(0.5 * (bi->min.x + bi->max.x), 0.5 * (bi->min.y + bi->max.y));
    ur_vec2 oj = ur_vec2_make(0.5 * (bj->min.x + bj->max.x), 0.5 * (bj->min.y + bj->max.y));
    ur_vec2 ci = ur_vec2_add(c->now.at[i], oi), cj = ur_vec2_add(c->now.at[j], oj);
    size_t si = c->now.sheet[i], sj = c->now.sheet[j];
    double box_i[4], box_j[4];
    if (!inner_fit(c, sj, i, c->now.turn[i], box_i) || !inner_fit(c, si, j, c->now.turn[j], box_j))
        return true; /* one does not fit the other's sheet (a remnant): no trade */
    c->now.at[i] = clamp_to(ur_vec2_sub(cj, oi), box_i);
    c->now.at[j] = clamp_to(ur_vec2_sub(ci, oj), box_j);
    c->now.sheet[i] = sj;
    c->now.sheet[j] = si;
    return compact_recompute_depths(c);
}

/*
 * Whether the layout in c->now truly has no overlap and keeps within the
 * strip: every pair's relative place checked against GEOS's own no-fit
 * polygon, not the flattened copies the search reads, so that an error in
 * those can never reach a cut file.  False on a GEOS failure too.  The
 * caller holds the shared lock (the nester's GEOS context).
 */
static bool verified(compactor *c)
{
    nester *n = c->n;
    for (size_t i = 0; i < c->count; i++) {
        double box[4];
        ur_vec2 at = c->now.at[i];
        if (!fits_where_it_is(c, i, c->now.turn[i], box) || at.x < box[0] - 1e-9 ||
            at.x > box[2] + 1e-9 || at.y < box[1] - 1e-9 || at.y > box[3] + 1e-9)
            return false;
        for (size_t j = 0; j < i; j++) {
            if (c->now.sheet[j] != c->now.sheet[i])
                continue;
            const GEOSGeometry *nfp =
                nest_nfp_of(n, c->piece[j], c->now.turn[j], c->piece[i], c->now.turn[i]);
            GEOSGeometry *point =
                GEOSGeom_createPointFromXY_r(n->geos, at.x - c->now.at[j].x, at.y - c->now.at[j].y);
            char inside = nfp && point ? GEOSContains_r(n->geos, nfp, point) : 2;
            if (point)
                GEOSGeom_destroy_r(n->geos, point);
            if (inside != 0)
                return false;
        }
    }
    return true;
}

/* Tells the caller's progress of a new best (the shared lock held). */
static void tell_progress(const compactor *c, double best)
{
    const ur_nest_options *o = c->n->options;
    if (!o->progress)
        return;
    size_t tried = atomic_load(&c->shared->separations);
    size_t sheets = c->across_sheets ? c->sheet_count - c->n->remnant_count : c->stock_sheets;
    o->progress(o->progress_context, sheets, best + o->margin, tried);
}

/*
 * A layout with no overlap in a shorter strip than this search's best:
 * its new best, once verified, and everyone's if no other search has
 * found a shorter one meanwhile.  False when it is not verified.
 */
static bool keep_best(compactor *c, double *best_length)
{
    shared_best *shared = c->shared;
    mtx_lock(&shared->lock);
    bool kept = verified(c);
    if (kept) {
        *best_length = compact_reach_of(c);
        compact_copy_state(c, &c->best, &c->now);
    }
    if (kept && *best_length < shared->length) {
        shared->length = *best_length;
        compact_copy_state(c, &shared->best, &c->now);
        c->seen = atomic_fetch_add(&shared->version, 1) + 1;
        tell_progress(c, *best_length);
    }
    mtx_unlock(&shared->lock);
    return kept;
}

/* Whether another search has found a new best since this one last looked. */
static bool overtaken(const compactor *c)
{
    return atomic_load(&c->shared->version) != c->seen;
}

/*
 * Takes up the shared best when it is shorter than this search's own;
 * true when it did.
 */
static bool catch_up(compactor *c, double *best_length)
{
    if (!overtaken(c))
        return false;
    shared_best *shared = c->shared;
    mtx_lock(&shared->lock);
    c->seen = atomic_load(&shared->version);
    bool shorter = shared->length < *best_length;
    if (shorter) {
        *best_length = shared->length;
        compact_copy_state(c, &c->best, &shared->best);
    }
    mtx_unlock(&shared->lock);
    return shorter;
}

/*
 * Keeps the layout in c->now, whose total overlap is total, among the near
 * misses if it is among the NEAR_MISSES least; the most overlapping one
 * drops out when they are full.
 */
static void keep_near_miss(compactor *c, double total)
{
    near_misses *m = &c->misses;
    size_t at = m->count;
    while (at > 0 && m->total[at - 1] > total)
        at--;
    if (at == NEAR_MISSES)
        return;
    size_t last = m->count < NEAR_MISSES ? m->count++ : NEAR_MISSES - 1;
    state spare = m->layout[last]; /* its arrays are reused for the new one */
    for (size_t k = last; k > at; k--) {
        m->layout[k] = m->layout[k - 1];
        m->total[k] = m->total[k - 1];
    }
    m->layout[at] = spare;
    m->total[at] = total;
    compact_copy_state(c, &m->layout[at], &c->now);
}

/* One of the near misses (there is one at least), the least overlapping most often. */
static const state *pick_near_miss(compactor *c)
{
    double u = uniform(&c->random), v = uniform(&c->random);
    double spread = fabs(sqrt(-2 * log(1 - u)) * cos(2 * M_PI * v)) * NEAR_MISS_SPREAD;
    size_t k = (size_t)(fmin(spread, 0.999) * (double)c->misses.count);
    return &c->misses.layout[k < c->misses.count ? k : c->misses.count - 1];
}

/*
 * Exploration: the strip cut to length (by EXPLORE_CUT from the best), or
 * the parts put on that many sheets, and separated again and again, each time from one of the near
 * misses so far, jolted, until a layout fits, the phase's time is up or another search gets ahead.
 * False when it stops without a layout (or *status says why).
 */
static bool explore_once(compactor *c, double length, double until, size_t tries, ur_status *status)
{
    c->misses.count = 0;
    compact_copy_state(c, &c->now, &c->best);
    if (!cut_to(c, length)) {
        *status = compact_failure(c);
        return false;
    }
    double saved = c->deadline;
    c->deadline = until;
    bool fits = false;
    for (size_t tried = 0;
         !fits && *status == UR_OK && tried < tries && nest_seconds_now() < until && !overtaken(c);
         tried++) {
        fits = separate(c, status);
        if (!fits && *status == UR_OK) {
            keep_near_miss(c, total_depth(c)); /* separate left its least in c->now */
            compact_copy_state(c, &c->now, pick_near_miss(c));
            if (!disrupt(c))
                *status = compact_failure(c);
        }
    }
    c->deadline = saved;
    return fits;
}

/*
 * One search, c set up: exploration (EXPLORE_SHARE of the time), then
 * compression, which cuts the best strip by less and less (from
 * COMPRESS_FIRST to COMPRESS_LAST of its length as time runs out) and
 * separates once per cut.  Each step starts from the shortest layout any
 * search has found; the best ends in c->shared.
 */
ur_status compact_search_shorter(compactor *c)
{
    ur_status status = UR_OK;
    double best_length = compact_reach_of(c), floor = shortest_possible(c);
    compact_copy_state(c, &c->best, &c->now);
    double start = nest_seconds_now(), span = c->deadline - start;
    double until = start + EXPLORE_SHARE * span;
    while (status == UR_OK && nest_seconds_now() < until) {
        (void)catch_up(c, &best_length);
        double length = best_length * (1 - EXPLORE_CUT);
        if (length < floor)
            break;
        if (explore_once(c, length, until, SIZE_MAX, &status))
            (void)keep_best(c, &best_length); /* or, not verified, the same cut again */
    }
    double compress_start = nest_seconds_now();
    for (int failures = 0; status == UR_OK && failures < COMPRESS_PATIENCE;) {
        double now = nest_seconds_now();
        if (now > c->deadline)
            break;
        if (catch_up(c, &best_length))
            failures = 0;
        double done = (now - compress_start) / fmax(1e-9, c->deadline - compress_start);
        double cut = COMPRESS_FIRST + (COMPRESS_LAST - COMPRESS_FIRST) * done;
        double length = best_length * (1 - cut);
        if (length < floor)
            break;
        compact_copy_state(c, &c->now, &c->best);
        if (!cut_to(c, length))
            return compact_failure(c);
        bool fits = separate(c, &status);
        if (fits && compact_reach_of(c) < best_length && keep_best(c, &best_length)) {
            failures = 0;
        } else {
            failures++;
        }
    }
    return status;
}

/*
 * A sheet search's cut while cuts go through: doubled after each layout
 * found at the first separation, up to FEWER_CUT_MOST, and back to
 * EXPLORE_CUT after FEWER_TRIES separations fail.  The lengthened sheet
 * has much slack at first (the first layout's, and the sheets dropped
 * end to end), which small cuts would take long to take up.
 */
#define FEWER_CUT_MOST 0.05
#define FEWER_TRIES 2

/*
 * A sheet search at one count of sheets, c set up (compactor_make): the
 * last sheet, lengthened at first by the parts of the sheets dropped, is
 * shortened as a roll is, to its own length; parts move between all the
 * sheets on the way.  It ends when the parts fit (the shared best is then
 * within sheet_length), at the deadline, or when another search has done
 * it.
 */
ur_status compact_search_fewer(compactor *c)
{
    ur_status status = UR_OK;
    double best_length = compact_reach_of(c), cut = EXPLORE_CUT;
    compact_copy_state(c, &c->best, &c->now);
    while (status == UR_OK && best_length > c->sheet_length && nest_seconds_now() < c->deadline) {
        (void)catch_up(c, &best_length);
        if (best_length <= c->sheet_length)
            break;
        double length = fmax(c->sheet_length, best_length * (1 - cut));
        size_t tries = cut > EXPLORE_CUT ? FEWER_TRIES : SIZE_MAX;
        if (!explore_once(c, length, c->deadline, tries, &status))
            cut = EXPLORE_CUT;
        else if (keep_best(c, &best_length)) /* or, not verified, the same cut again */
            cut = fmin(FEWER_CUT_MOST, 2 * cut);
    }
    return status;
}

/*
 * push_to_one_end's cuts: the first, the most and the least (a fraction
 * of the strip's length), and the separations it tries at each length.
 */
#define END_CUT_FIRST 0.01
#define END_CUT_MOST 0.04
#define END_CUT_LEAST 0.0005
#define END_TRIES 2

/*
 * A sheet's parts pushed to one end (c a strip over that sheet), so that
 * what is left at the other is one piece of stock: the strip is cut and
 * separated as a roll is, the cut doubled after each layout found and
 * halved after END_TRIES separations fail, until it falls below
 * END_CUT_LEAST.  It stops then, not only at the deadline, so that one
 * search (the caller runs one) gives the same layout every time.
 */
ur_status compact_push_to_one_end(compactor *c)
{
    ur_status status = UR_OK;
    double best_length = compact_reach_of(c), floor = shortest_possible(c);
    compact_copy_state(c, &c->best, &c->now);
    for (double cut = END_CUT_FIRST;
         status == UR_OK && cut >= END_CUT_LEAST && nest_seconds_now() < c->deadline;) {
        double length = best_length * (1 - cut);
        if (length >= floor && explore_once(c, length, c->deadline, END_TRIES, &status) &&
            keep_best(c, &best_length))
            cut = fmin(END_CUT_MOST, 2 * cut);
        else
            cut *= 0.5;
    }
    return status;
}

/* Each pair's size and floor for pair_cost, from the parts' areas and sizes at turn 0. */
void compact_size_pairs(compactor *c)
{
    for (size_t i = 0; i < c->count; i++) {
        double area_i = nest_shape_of(c->n, c->piece[i], 0)->area;
        for (size_t j = 0; j < c->count; j++) {
            double area_j = nest_shape_of(c->n, c->piece[j], 0)->area;
            c->pair_scale[i * c->count + j] = sqrt(sqrt(area_i) * sqrt(area_j));
            c->pair_floor[i * c->count + j] =
                OVERLAP_FLOOR * fmax(part_size(c, i), part_size(c, j));
        }
    }
}
