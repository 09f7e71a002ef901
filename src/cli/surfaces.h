/*
 * surfaces.h: building the ruled surface a subcommand describes.
 */
#ifndef UNROLL_CLI_SURFACES_H
#define UNROLL_CLI_SURFACES_H

#include "cli.h"
#include "unroll/surface.h"

/* Returns 0 with *ruled built, or an exit status after printing a message. */
int cli_build_surface(const cli_job *job, ur_ruled *ruled);

#endif
