/*
 * domain.c: what the command says and writes about a two-rail surface
 * beyond its net: the domain of existence of a strip (with --strict), its
 * edge of regression (--regression), and the refusal to develop a surface
 * that is not developable.
 */
#include "cli.h"
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
    snprintf(text, size,
             "u %.6g to %.6g, %.6g to %.6g mm along rail 1, from (%.4g, %.4g, %.4g) to (%.4g, "
             "%.4g, %.4g)",
             gap->u_start, gap->u_end, gap->arc_start, gap->arc_end, gap->start.x, gap->start.y,
             gap->start.z, gap->end.x, gap->end.y, gap->end.z);
}

int cli_check_domain(const cli_job *job, ur_ruled *ruled)
{
    const ur_interval *gaps;
    size_t count = ur_ruled_gaps(ruled, &gaps);
    if (count == 0)
        return 0;
    if (job->strict) {
        char text[4096];
        size_t used = 0;
        for (size_t k = 0; k < count && used < sizeof text; k++) {
            char place[512];
            describe_gap(&gaps[k], place, sizeof place);
            used += (size_t)snprintf(
                text + used, sizeof text - used, "%s%s (%s)", k ? "; " : "", place,
                gaps[k].reason == UR_GAP_NO_RULING ? "no ruling" : "rulings cross");
        }
        cli_message("%s: --strict: the strip does not exist along the whole of rail 1: %s",
                    job->command, text);
        return EXIT_USAGE;
    }
    if (job->quiet)
        return 0;
    size_t parts = ur_ruled_domain(ruled, NULL, 0);
    if (parts == 1)
        cli_message("%s: the strip's domain of existence leaves out %zu part%s of rail 1; the "
                    "rest is developed:",
                    job->command, count, count == 1 ? "" : "s");
    else
        cli_message("%s: the strip's domain of existence leaves out %zu part%s of rail 1; the "
                    "%zu parts that exist are developed separately:",
                    job->command, count, count == 1 ? "" : "s", parts);
    for (size_t k = 0; k < count; k++) {
        char place[512];
        describe_gap(&gaps[k], place, sizeof place);
        cli_message("  %s: %s%s", place, gap_reason(gaps[k].reason),
                    gaps[k].reason == UR_GAP_RULINGS_CROSS ? "; the strip is split there" : "");
    }
    return 0;
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

int cli_regression_points(const cli_job *job, ur_ruled *ruled, ur_vec3 **points, size_t *count)
{
    ur_error error;
    *count = 0;
    *points = ur_alloc_array(REGRESSION_POINTS + 1, sizeof **points, &error);
    if (!*points) {
        cli_message("%s: %s", job->command, error.message);
        return cli_exit_status(&error);
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
        cli_message("%s: --regression: the rulings are parallel (the surface is a cylinder), so "
                    "the edge of regression is at infinity and there is nothing to write",
                    job->command);
        return EXIT_USAGE;
    }
    return 0;
}

int cli_write_regression(const cli_job *job, const ur_vec3 *points, size_t count)
{
    ur_error error;
    if (ur_curve_csv_write(job->regression_path, points, count, cli_context(), &error) != UR_OK) {
        cli_message("%s: --regression %s: %s", job->command, job->regression_path, error.message);
        return cli_exit_status(&error);
    }
    if (!job->quiet)
        cli_message("%s: edge of regression: %zu points -> %s", job->command, count,
                    job->regression_path);
    return 0;
}
