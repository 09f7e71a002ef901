/*
 * domain.h: the domain of existence and edge of regression of a two-rail
 * surface, as the command reports and writes them (domain.c).
 */
#ifndef UNROLL_CLI_DOMAIN_H
#define UNROLL_CLI_DOMAIN_H

#include "cli.h"
#include "unroll/surface.h"

/* Reports the gaps of a strip's domain; with --strict refuses them (exit 2). */
int cli_check_domain(const cli_job *job, ur_ruled *ruled);

/* Samples the edge of regression where the surface has rulings; owned by the caller. */
int cli_regression_points(const cli_job *job, ur_ruled *ruled, ur_vec3 **points, size_t *count);

int cli_write_regression(const cli_job *job, const ur_vec3 *points, size_t count);

#endif
