/*
 * surface_job.c: the surface of a job on its own, for a program that
 * analyses or compares it rather than cutting it.
 */
#include "domain.h"
#include "stages.h"
#include "surfaces.h"

#include <stdlib.h>

ur_status ur_job_surface(const ur_job *job, const ur_job_callbacks *callbacks, ur_ruled *ruled,
                         ur_error *error)
{
    ur_status status = ur_job_check(job, error);
    if (status != UR_OK)
        return status;
    job_run run = job_run_make(job, callbacks, error);
    return job_build_surface(&run, ruled, NULL);
}

/* The strip's checks and curves on a built surface. */
static ur_status curves(const job_run *run, ur_ruled *ruled, const job_adjusted_rail *adjusted)
{
    ur_vec3 *edge = NULL;
    size_t edge_count = 0;
    ur_status status = UR_OK;
    if (run->job.strict)
        status = job_check_domain(run, ruled);
    if (status == UR_OK && run->job.regression_path)
        status = job_regression_points(run, ruled, &edge, &edge_count);
    if (status == UR_OK && edge)
        status = job_write_regression(run, edge, edge_count);
    if (status == UR_OK)
        status = job_write_adjusted_rail(run, adjusted);
    free(edge);
    return status;
}

ur_status ur_job_surface_with_curves(const ur_job *job, const ur_job_callbacks *callbacks,
                                     ur_ruled *ruled, ur_error *error)
{
    ur_status status = ur_job_check(job, error);
    if (status != UR_OK)
        return status;
    job_run run = job_run_make(job, callbacks, error);
    job_adjusted_rail adjusted = {.rails = {NULL, NULL}};
    status = job_build_surface(&run, ruled, &adjusted);
    if (status == UR_OK) {
        status = curves(&run, ruled, &adjusted);
        if (status != UR_OK)
            ur_ruled_free(ruled);
    }
    job_adjusted_rail_free(&adjusted);
    return status;
}
