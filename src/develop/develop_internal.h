/*
 * develop_internal.h: what the files of the develop module share.
 */
#ifndef UNROLL_DEVELOP_INTERNAL_H
#define UNROLL_DEVELOP_INTERNAL_H

#include "unroll/develop.h"

/*
 * A flat strip: the flat ends of a sequence of rulings, near (on rail a) and
 * far (on rail b).  Pieces are ranges of it.
 */
typedef struct strip {
    size_t count;
    double *u;
    ur_vec2 *near, *far;
    bool *drawn;          /* ruling drawn as a score line */
    bool skip_first_near; /* triangle method: the first near point is not in the net */
} strip;

ur_status strip_alloc(strip *s, size_t count, ur_error *error);
void strip_free(strip *s);

/*
 * The exact development (develop.c) at the parameters already in s->u
 * (count >= 2, increasing): fills s->near and s->far.  The strip stays the
 * caller's, also on failure.  ur_develop samples its own parameters;
 * ur_compare (compare.c) uses this to evaluate the exact net at the
 * rulings of a discrete one.
 */
ur_status develop_exact_at(ur_ruled *ruled, strip *s, ur_error *error);

/* The triangle and quad methods of [Seed2018] (docs/bibliography.md; discrete.c). */
ur_status develop_discrete(ur_ruled *ruled, const ur_develop_options *options, strip *s,
                           ur_error *error);

#endif
