/*
 * unfold_search.c: improving which edges an unfolding cuts, after Takahashi
 * et al. 2011 ("Optimized topological surgery for unfolding 3D meshes"),
 * who search over the spanning trees of the faces for one whose pieces do
 * not overlap.  Here a run joins pieces across the edges in a given order
 * (unfold.c), so an order stands for a cut, and the search changes the
 * order: a seam of one of the smallest pieces goes first (that piece is
 * joined before its neighbours grow round it), or now and then a fold goes
 * last.  The run is done again and the change kept when the result is no
 * worse (fewer pieces, then fewer of one face, then a shorter cut), or,
 * early on, sometimes when it is a little worse (simulated annealing, the
 * temperature falling to nothing as the budget runs out).  A walk that
 * finds nothing better for a while starts again from the first order.  The
 * random choices come from the seed alone, so a number of steps always
 * gives the same result.
 */
#include "unfold_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* xorshift64*: small, fast and the same everywhere. */
static uint64_t next_random(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return *state * UINT64_C(2685821657736338717);
}

/* A number in [0, 1). */
static double uniform(uint64_t *state)
{
    return (double)(next_random(state) >> 11) * 0x1.0p-53;
}

static size_t below(uint64_t *state, size_t n)
{
    return (size_t)(uniform(state) * (double)n);
}

/* The fewest pieces any cut can give: the parts the uncut edges hold together. */
static size_t least_pieces(const unfolder *u, size_t *parent)
{
    size_t n = u->mesh->triangle_count, parts = n;
    for (size_t t = 0; t < n; t++)
        parent[t] = t;
    for (size_t h = 0; h < 3 * n; h++) {
        size_t g = u->edges.twins[h];
        if (g == UR_NO_EDGE || u->edges.cut[h])
            continue;
        size_t a = h / 3, b = g / 3;
        while (parent[a] != a)
            a = parent[a] = parent[parent[a]];
        while (parent[b] != b)
            b = parent[b] = parent[parent[b]];
        if (a != b) {
            parent[a] = b;
            parts--;
        }
    }
    return parts;
}

/* The pieces of the last run, smallest first (insertion sort: few pieces, mostly in order). */
static size_t pieces_by_size(const unfolder *u, size_t *pieces)
{
    size_t count = 0;
    for (size_t p = 0; p < u->mesh->triangle_count; p++) {
        if (u->islands[p].triangle_count == 0)
            continue;
        size_t i = count++;
        while (i > 0 && u->islands[pieces[i - 1]].triangle_count > u->islands[p].triangle_count) {
            pieces[i] = pieces[i - 1];
            i--;
        }
        pieces[i] = p;
    }
    return count;
}

/* The lower half of a seam of piece p that may be joined, chosen at random; UNFOLD_NONE if none. */
static size_t seam_of(const unfolder *u, size_t p, uint64_t *random)
{
    size_t seen = 0, chosen = UNFOLD_NONE;
    for (size_t t = u->islands[p].first; t != UNFOLD_NONE; t = u->next_member[t])
        for (size_t h = 3 * t; h < 3 * t + 3; h++) {
            size_t g = u->edges.twins[h];
            if (g == UR_NO_EDGE || u->edges.cut[h] || u->joined[h])
                continue;
            if (below(random, ++seen) == 0) /* each seam with chance 1 / seen */
                chosen = h < g ? h : g;
        }
    return chosen;
}

static size_t position_of(const size_t *order, size_t count, size_t half)
{
    for (size_t i = 0; i < count; i++)
        if (order[i] == half)
            return i;
    return UNFOLD_NONE;
}

/* Moves order[from] to the front (to_front) or to the back. */
static void move_edge(size_t *order, size_t count, size_t from, bool to_front)
{
    size_t half = order[from];
    if (to_front) {
        memmove(order + 1, order, from * sizeof *order);
        order[0] = half;
    } else {
        memmove(order + from, order + from + 1, (count - from - 1) * sizeof *order);
        order[count - 1] = half;
    }
}

/* Changes order after the pieces of the last run; false when there is nothing to change. */
static bool mutate(const unfolder *u, size_t *order, size_t count, size_t *pieces, uint64_t *random)
{
    if (uniform(random) < 0.2) { /* a fold, last */
        for (int tries = 0; tries < 16; tries++) {
            size_t i = below(random, count);
            if (u->joined[order[i]]) {
                move_edge(order, count, i, false);
                return true;
            }
        }
    }
    size_t piece_count = pieces_by_size(u, pieces);
    for (int tries = 0; tries < 16 && piece_count > 1; tries++) {
        double r = uniform(random); /* r squared: the smallest pieces most often */
        size_t p = pieces[(size_t)(r * r * (double)piece_count)];
        size_t half = seam_of(u, p, random);
        size_t i = half == UNFOLD_NONE ? UNFOLD_NONE : position_of(order, count, half);
        if (i != UNFOLD_NONE) {
            move_edge(order, count, i, true);
            return true;
        }
    }
    return false;
}

/* How much worse b is than a, in pieces, for the annealing's acceptance. */
static double worse_by(unfold_score a, unfold_score b, double total_length)
{
    return (double)unfold_score_cost(b) - (double)unfold_score_cost(a) +
           0.5 * ((double)b.single_face - (double)a.single_face) +
           (b.seam_length - a.seam_length) / total_length;
}

typedef struct search {
    unfolder *u;
    size_t *order, *trial, *best, *pieces, *first_order; /* first_order: where the walks begin */
    size_t count;
    unfold_score current, top, first;
    double start, total_length;
    uint64_t random;
} search;

/* How far the budget is spent, from 0 to 1. */
static double spent(const search *s, size_t step)
{
    const ur_unfold_options *o = &s->u->options;
    double by_time = o->time_budget > 0 ? (seconds_now() - s->start) / o->time_budget : 0.0;
    double by_steps = o->max_steps > 0 ? (double)step / (double)o->max_steps : 0.0;
    return fmax(by_time, by_steps);
}

static bool accept(search *s, unfold_score trial, double progress)
{
    if (unfold_score_compare(trial, s->current) <= 0)
        return true;
    double temperature = 0.3 * (1.0 - progress);
    double worse = worse_by(s->current, trial, s->total_length);
    return temperature > 0 && uniform(&s->random) < exp(-worse / temperature);
}

static ur_status step_once(search *s, double progress, bool *moved, ur_error *error)
{
    memcpy(s->trial, s->order, s->count * sizeof *s->trial);
    *moved = mutate(s->u, s->trial, s->count, s->pieces, &s->random);
    if (!*moved)
        return UR_OK;
    unfold_score score;
    ur_status status = unfold_run(s->u, s->trial, s->count, &score, error);
    if (status != UR_OK)
        return status;
    if (accept(s, score, progress)) {
        memcpy(s->order, s->trial, s->count * sizeof *s->order);
        s->current = score;
    }
    if (unfold_score_compare(score, s->top) < 0) {
        memcpy(s->best, s->trial, s->count * sizeof *s->best);
        s->top = score;
    }
    return UR_OK;
}

/*
 * After UNFOLD_PATIENCE steps without a new best the walk starts again
 * from the first order, its random choices going on, while at least that
 * many counted steps are left; the best of all walks is kept.  The longest
 * run of steps between two new bests in 200 was 93 on the sample UV sphere
 * (a seam without room for its tab before, none after), 53 on the sample
 * torus and at most 38 on the sample head, Blender's monkey, subdivided
 * monkey, torus and UV sphere and the bench's 48 x 24 sphere.  A walk
 * that has cooled into one cut rarely leaves it; a new one from the start
 * goes elsewhere (the sample UV sphere: 6 pieces in 700 steps, 7 when the
 * search stopped at its first stall).  Not every cut is found so:
 * Blender's cylinder is one piece only with its two caps on opposite sides
 * of the strip about a quarter of the way from each end, which, with its
 * caps split into triangles as assimp splits them, seeds 2 and 4 found in
 * 200 steps and no walk of seed 1 in 1,000 (split again without slivers,
 * the first order joins them so).  A search with no count of steps (time
 * alone) stops at its first stall.
 */
enum { UNFOLD_PATIENCE = 100 };

static bool may_restart(const search *s, size_t step)
{
    size_t most = s->u->options.max_steps;
    return most > 0 && step + UNFOLD_PATIENCE <= most;
}

static void start_again(search *s)
{
    memcpy(s->order, s->first_order, s->count * sizeof *s->order);
    s->current = s->first;
}

/* How far a walk that began at progress `from` has gone through what is left, from 0 to 1. */
static double walk_progress(double from, double progress)
{
    return from < 1.0 ? fmin(1.0, (progress - from) / (1.0 - from)) : 1.0;
}

static ur_status run_search(search *s, size_t least, size_t *steps, ur_error *error)
{
    const ur_unfold_options *o = &s->u->options;
    size_t stall = 0;
    double walk_from = 0.0; /* each walk cools from the same temperature */
    for (size_t step = 0;; step++) {
        double progress = spent(s, step);
        if (progress >= 1.0 || unfold_score_cost(s->top) <= least)
            return UR_OK;
        if (stall >= UNFOLD_PATIENCE) {
            if (!may_restart(s, step))
                return UR_OK;
            start_again(s);
            stall = 0;
            walk_from = progress;
        }
        if (step % 32 == 0 && o->progress)
            o->progress(o->progress_context, "improving",
                        s->u->progress_from +
                            s->u->progress_span * unfold_first_part_share(s->u, s->top) * progress);
        unfold_score before = s->top;
        bool moved;
        ur_status status = ur_context_check(o->context, error);
        if (status == UR_OK)
            status = step_once(s, walk_progress(walk_from, progress), &moved, error);
        if (status != UR_OK)
            return status;
        if (!moved)
            return UR_OK;
        *steps = step + 1;
        stall = unfold_score_compare(s->top, before) < 0 ? 0 : stall + 1;
        /* Carry on from the best when the walk has strayed far from it. */
        if (unfold_score_cost(s->current) > unfold_score_cost(s->top) + 2) {
            memcpy(s->order, s->best, s->count * sizeof *s->order);
            s->current = s->top;
        }
    }
}

ur_status unfold_search(unfolder *u, size_t *order, size_t count, size_t *steps, unfold_score *best,
                        ur_error *error)
{
    *steps = 0;
    unfold_score first;
    ur_status status = unfold_run(u, order, count, &first, error);
    *best = first;
    if (status != UR_OK)
        return status;
    const ur_unfold_options *o = &u->options;
    if (count == 0 || (o->time_budget <= 0 && o->max_steps == 0))
        return UR_OK;
    size_t n = u->mesh->triangle_count;
    search s = {.u = u,
                .order = order,
                .count = count,
                .current = first,
                .top = first,
                .first = first,
                .start = seconds_now(),
                .random = o->seed * UINT64_C(0x9E3779B97F4A7C15) | 1};
    s.trial = ur_alloc_array(count, sizeof *s.trial, error);
    s.best = ur_alloc_array(count, sizeof *s.best, error);
    s.pieces = ur_alloc_array(n, sizeof *s.pieces, error);
    s.first_order = ur_alloc_array(count, sizeof *s.first_order, error);
    status = s.trial && s.best && s.pieces && s.first_order ? UR_OK : UR_ERROR_MEMORY;
    if (status == UR_OK) {
        memcpy(s.best, order, count * sizeof *s.best);
        memcpy(s.first_order, order, count * sizeof *s.first_order);
        for (size_t h = 0; h < 3 * n; h++)
            if (u->edges.twins[h] != UR_NO_EDGE && h < u->edges.twins[h])
                s.total_length += unfold_edge_length(u->mesh, h);
        status = run_search(&s, least_pieces(u, s.pieces), steps, error);
    }
    if (status == UR_OK && *steps > 0) {
        memcpy(order, s.best, count * sizeof *order);
        status = unfold_run(u, order, count, best, error);
    }
    free(s.trial);
    free(s.best);
    free(s.pieces);
    free(s.first_order);
    return status;
}
