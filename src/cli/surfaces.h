/*
 * surfaces.h: building the ruled surface a subcommand describes.
 */
#ifndef UNROLL_CLI_SURFACES_H
#define UNROLL_CLI_SURFACES_H

#include "cli.h"
#include "unroll/surface.h"

/* The rails as --adjust moved them, for --adjusted-rail and the report. */
typedef struct cli_adjusted_rail {
    ur_vec3 *rails[2]; /* owned; NULL for a rail not adjusted */
    size_t counts[2];
    ur_rail_repair_report report;
} cli_adjusted_rail;

/*
 * Returns 0 with *ruled built, or an exit status after printing a message.
 * adjusted (may be NULL) receives the rails as --adjust left them; the
 * caller frees them with cli_adjusted_rail_free.
 */
int cli_build_surface(const cli_job *job, ur_ruled *ruled, cli_adjusted_rail *adjusted);

void cli_adjusted_rail_free(cli_adjusted_rail *adjusted);

/* Writes --adjusted-rail, if asked for; returns 0 or an exit status. */
int cli_write_adjusted_rail(const cli_job *job, const cli_adjusted_rail *adjusted);

#endif
