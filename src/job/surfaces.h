/*
 * surfaces.h: building the ruled surface a job describes.
 */
#ifndef UNROLL_JOB_SURFACES_H
#define UNROLL_JOB_SURFACES_H

#include "stages.h"
#include "unroll/surface.h"

/* Rail 2 as --adjust-rail2 moved it, for --adjusted-rail. */
typedef struct job_adjusted_rail {
    ur_vec3 *points; /* owned; NULL when rail 2 was not adjusted */
    size_t count;
    double largest_move;
} job_adjusted_rail;

/*
 * UR_OK with *ruled built, or a status with the run's error set.
 * adjusted (may be NULL) receives rail 2 as --adjust-rail2 left it; the
 * caller frees its points.
 */
ur_status job_build_surface(const job_run *run, ur_ruled *ruled, job_adjusted_rail *adjusted);

/* Writes the adjusted rail 2, if the job names a file for it. */
ur_status job_write_adjusted_rail(const job_run *run, const job_adjusted_rail *adjusted);

#endif
