/*
 * surfaces.h: building the ruled surface a job describes.
 */
#ifndef UNROLL_JOB_SURFACES_H
#define UNROLL_JOB_SURFACES_H

#include "stages.h"
#include "unroll/surface.h"

/* The rails as the job's repair (adjust_rails) left them, for the adjusted rail files. */
typedef struct job_adjusted_rail {
    ur_vec3 *rails[2]; /* owned; NULL for a rail not adjusted */
    size_t counts[2];
    bool repaired;                /* the job asked for a repair and it was done */
    ur_rail_repair_report report; /* then what it did */
} job_adjusted_rail;

/*
 * UR_OK with *ruled built, or a status with the run's error set.
 * adjusted (may be NULL) receives the rails as the repair left them; the
 * caller frees them with job_adjusted_rail_free.
 */
ur_status job_build_surface(const job_run *run, ur_ruled *ruled, job_adjusted_rail *adjusted);

void job_adjusted_rail_free(job_adjusted_rail *adjusted);

/* Writes the adjusted rails, if the job names files for them. */
ur_status job_write_adjusted_rail(const job_run *run, const job_adjusted_rail *adjusted);

#endif
