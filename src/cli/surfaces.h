/*
 * surfaces.h: building the ruled surface a subcommand describes.
 */
#ifndef UNROLL_CLI_SURFACES_H
#define UNROLL_CLI_SURFACES_H

#include "cli.h"
#include "unroll/surface.h"

/* Rail 2 as --adjust-rail2 moved it, for --adjusted-rail. */
typedef struct cli_adjusted_rail {
    ur_vec3 *points; /* owned; NULL when rail 2 was not adjusted */
    size_t count;
    double largest_move;
} cli_adjusted_rail;

/*
 * Returns 0 with *ruled built, or an exit status after printing a message.
 * adjusted (may be NULL) receives rail 2 as --adjust-rail2 left it; the
 * caller frees its points.
 */
int cli_build_surface(const cli_job *job, ur_ruled *ruled, cli_adjusted_rail *adjusted);

/* Writes --adjusted-rail, if asked for; returns 0 or an exit status. */
int cli_write_adjusted_rail(const cli_job *job, const cli_adjusted_rail *adjusted);

#endif
