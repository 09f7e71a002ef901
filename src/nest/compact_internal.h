/*
 * compact_internal.h (internal to src/nest/): what the overlap search
 * (compact.c) and the code that sets searches up and runs them side by
 * side (compact_run.c) share: the search's state and its entry points.
 */
#ifndef UNROLL_NEST_COMPACT_INTERNAL_H
#define UNROLL_NEST_COMPACT_INTERNAL_H

#include "depth_index.h"
#include "nest_internal.h"

#include <stdatomic.h>
#include <threads.h>

/* The least overlapping layouts exploration keeps at one length, at most (compact.c). */
#define NEAR_MISSES 32

/* Where the parts are: one state of the search. */
typedef struct state {
    size_t *turn;
    ur_vec2 *at;
    size_t *sheet; /* the nester's sheet each is on */
} state;

/*
 * The least overlapping layouts the separations at one length ended with,
 * least overlap first: exploration jolts one of them when a separation
 * fails, so that it goes on from a good layout, not just the last one.
 */
typedef struct near_misses {
    state layout[NEAR_MISSES]; /* each owned */
    double total[NEAR_MISSES]; /* each one's total overlap */
    size_t count;
} near_misses;

/*
 * What the searches running side by side share: the shortest verified
 * layout any of them has found, and the nester, whose GEOS context and
 * no-fit polygons only one may use at a time.
 */
typedef struct shared_best {
    mtx_t lock;                /* held to use the nester, or to read or write the fields below */
    double length;             /* of best (reach_of) */
    state best;                /* owned */
    atomic_uint version;       /* one more with each new best: read without the lock */
    atomic_size_t separations; /* tried by all the searches: the progress line's count */
} shared_best;

typedef struct compactor {
    nester *n;
    shared_best *shared;
    unsigned seen;  /* the shared version this search has caught up with */
    ur_error error; /* its own, copied to the nester's when it fails */
    ur_status status;
    /*
     * The parts keep within length of the nester's sheet strip_sheet (from
     * its margin): a roll, or a sheet whose parts are pushed to one end
     * (to_one_end), every part on it.  Or, across_sheets, a sheet search:
     * every part, on the nester's sheets 0 to sheet_count - 1, whole ones
     * but for the last, strip_sheet, which the parts of the sheets dropped
     * lengthen at first (see search_fewer); sheet_length is its own.
     */
    bool across_sheets, to_one_end;
    size_t strip_sheet, sheet_count;
    double sheet_length;
    size_t stock_sheets; /* stock sheets of the layout: what progress tells */
    size_t count;        /* parts searched over */
    size_t *index;       /* per part: its placement in the nester */
    size_t *piece;       /* per part */
    state now, best;
    double *depth;      /* count x count: how far each pair overlaps */
    double *weight;     /* count x count: guided local search's weight of each pair */
    double *pair_scale; /* count x count: each pair's size (pair_cost) */
    double *pair_floor; /* count x count: each pair's least overlap (pair_cost) */
    depth_index *nfps;  /* per (class, turn, class, turn), as the nester keys them */
    double length;      /* a strip: the length the parts must keep within, from the margin (mm) */
    double deadline;    /* on nest_seconds_now's clock */
    bool out_of_time;   /* a no-fit polygon was not made: the deadline had passed */
    uint64_t random;
    const depth_index *
        *row;           /* scratch: per turn and part, the no-fit polygon a moving part meets */
    size_t *order;      /* scratch: the order parts move in during a round */
    state least;        /* scratch: a separation's least overlapping layout */
    near_misses misses; /* exploration's, at its current length */
} compactor;

/* Copies the parts' turns, places and sheets of from into to. */
void compact_copy_state(const compactor *c, state *to, const state *from);

/*
 * The status of a step that failed: none (UR_OK) when it stopped because a
 * no-fit polygon was due after the deadline (the search then ends, its
 * best kept), out of memory otherwise.
 */
ur_status compact_failure(compactor *c);

/* Every pair's depth where the parts are now; false on a failure (compact_failure says which). */
bool compact_recompute_depths(compactor *c);

/* How far the parts reach along the strip, from the sheet's margin (mm). */
double compact_reach_of(const compactor *c);

/* Each pair's size and floor for the cost of an overlap, from the parts' areas and sizes. */
void compact_size_pairs(compactor *c);

/* The three searches: a shorter roll, fewer sheets, the last sheet's parts to one end. */
ur_status compact_search_shorter(compactor *c);
ur_status compact_search_fewer(compactor *c);
ur_status compact_push_to_one_end(compactor *c);

#endif
