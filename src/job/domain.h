/*
 * domain.h: the domain of existence and edge of regression of a two-rail
 * surface, as a job reports and writes them (domain.c).
 */
#ifndef UNROLL_JOB_DOMAIN_H
#define UNROLL_JOB_DOMAIN_H

#include "stages.h"
#include "unroll/surface.h"

/* Warns of the gaps of a strip's domain; a strict job refuses them (UR_ERROR_INPUT). */
ur_status job_check_domain(const job_run *run, ur_ruled *ruled);

/* Samples the edge of regression where the surface has rulings; owned by the caller. */
ur_status job_regression_points(const job_run *run, ur_ruled *ruled, ur_vec3 **points,
                                size_t *count);

ur_status job_write_regression(const job_run *run, const ur_vec3 *points, size_t count);

#endif
