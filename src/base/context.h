/*
 * context.h (library-internal): what a ur_context holds.  The public side
 * is in unroll/base.h; the output set's files are held here for
 * src/base/atomic.c, which alone reads and changes them.
 */
#ifndef UNROLL_BASE_CONTEXT_H
#define UNROLL_BASE_CONTEXT_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>

#include "unroll/base.h"

struct atomic_file;

/*
 * The cancel flag is stored from a signal handler, which may only touch a
 * lock-free atomic object, and read by worker threads, which need an atomic
 * object to read it without a data race.
 */
#if ATOMIC_INT_LOCK_FREE != 2
#error "cancelling from a signal handler needs a lock-free atomic int"
#endif

struct ur_context {
    atomic_int cancelled;
    struct {
        size_t depth;             /* begins not yet ended */
        bool refused;             /* an end said not to commit */
        struct atomic_file *held; /* closed temporaries, renamed at the outermost end */
        size_t count, capacity;
    } output_set;
    /* Test hook: bytes the writers may still write in all; -1 for no limit. */
    long long write_budget;
    ur_message_handler message_handler;
    void *message_data;
    const char *const *profile_roots; /* borrowed; NULL for none */
};

#endif
