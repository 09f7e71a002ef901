/*
 * domain.c: what a job says and writes about a two-rail surface beyond
 * its net: the domain of existence of a strip (refused when strict), and
 * its edge of regression.
 */
#include "stages.h"
#include "domain.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/io.h"

static const char *gap_reason(ur_gap_reason reason)
{
    return reason == UR_GAP_NO_RULING
               ? "no ruling: no plane through this part of rail 1 touches rail 2"
               : "rulings cross: the edge of regression passes between the rails, so the net "
                 "would fold over itself";
}

/* "u 0 to 0.4, 0 to 20 mm along rail 1, from (50, 0, 0) to (46, 19.5, 0)" */
static void describe_gap(const ur_interval *gap, char *text, size_t size)
{
    c_snprintf(text, size,
               "u %.6g to %.6g, %.6g to %.6g mm along rail 1, from (%.4g, %.4g, %.4g) to (%.4g, "
               "%.4g, %.4g)",
               gap->u_start, gap->u_end, gap->arc_start, gap->arc_end, gap->start.x, gap->start.y,
               gap->start.z, gap->end.x, gap->end.y, gap->end.z);
}

ur_status job_check_domain(const job_run *run, ur_ruled *ruled)
{
    const ur_interval *gaps;
    size_t count = ur_ruled_gaps(ruled, &gaps);
    if (count == 0)
        return UR_OK;
    if (run->job.strict) {
        char text[4096];
        size_t used = 0;
        for (size_t k = 0; k < count && used < sizeof text; k++) {
            char place[512];
            describe_gap(&gaps[k], place, sizeof place);
            used += (size_t)c_snprintf(
                text + used, sizeof text - used, "%s%s (%s)", k ? "; " : "", place,
                gaps[k].reason == UR_GAP_NO_RULING ? "no ruling" : "rulings cross");
        }
        return job_fail_about(run, UR_ERROR_INPUT, "strict",
                              "%s: strict: the strip does not exist along the whole of rail 1: %s",
                              run->job.command, text);
    }
    if (run->job.quiet)
        return UR_OK;
    size_t parts = ur_ruled_domain(ruled, NULL, 0);
    if (parts == 1)
        job_warn(run,
                 "%s: the strip's domain of existence leaves out %zu part%s of rail 1; the "
                 "rest is developed:",
                 run->job.command, count, count == 1 ? "" : "s");
    else
        job_warn(run,
                 "%s: the strip's domain of existence leaves out %zu part%s of rail 1; the "
                 "%zu parts that exist are developed separately:",
                 run->job.command, count, count == 1 ? "" : "s", parts);
    for (size_t k = 0; k < count; k++) {
        char place[512];
        describe_gap(&gaps[k], place, sizeof place);
        job_warn(run, "  %s: %s%s", place, gap_reason(gaps[k].reason),
                 gaps[k].reason == UR_GAP_RULINGS_CROSS ? "; the strip is split there" : "");
    }
    return UR_OK;
}

/* Inside a part of rail 1 that has no ruling at all. */
static bool in_empty_gap(const ur_ruled *ruled, double u)
{
    const ur_interval *gaps;
    size_t count = ur_ruled_gaps(ruled, &gaps);
    for (size_t k = 0; k < count; k++)
        if (gaps[k].reason == UR_GAP_NO_RULING && u >= gaps[k].u_start && u <= gaps[k].u_end)
            return true;
    return false;
}

enum { REGRESSION_POINTS = 1000 };

ur_status job_regression_points(const job_run *run, ur_ruled *ruled, ur_vec3 **points,
                                size_t *count)
{
    ur_error error;
    *count = 0;
    *points = ur_alloc_array(REGRESSION_POINTS + 1, sizeof **points, &error);
    if (!*points) {
        return job_fail(run, UR_ERROR_MEMORY, "%s: %s", run->job.command, error.message);
    }
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    for (int i = 0; i <= REGRESSION_POINTS; i++) {
        double u = u0 + (u1 - u0) * i / REGRESSION_POINTS, v;
        if (!in_empty_gap(ruled, u) && ur_ruled_regression(ruled, u, &(*points)[*count], &v))
            (*count)++;
    }
    if (*count < 4) {
        free(*points);
        *points = NULL;
        return job_fail_about(
            run, UR_ERROR_INPUT, "regression",
            "%s: regression: the rulings are parallel (the surface is a cylinder), so "
            "the edge of regression is at infinity and there is nothing to write",
            run->job.command);
    }
    return UR_OK;
}

ur_status job_write_regression(const job_run *run, const ur_vec3 *points, size_t count)
{
    ur_error error;
    if (ur_curve_csv_write(run->job.regression_path, points, count, run->job.context, &error) !=
        UR_OK) {
        return job_fail_about(run, error.status, "regression", "%s: regression %s: %s",
                              run->job.command, run->job.regression_path, error.message);
    }
    if (!run->job.quiet)
        job_note(run, "%s: edge of regression: %zu points -> %s", run->job.command, count,
                 run->job.regression_path);
    return UR_OK;
}
