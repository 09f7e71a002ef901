/*
 * surfaces.c: from a subcommand's parameters to a ruled surface, with a
 * message naming the option for every missing or impossible value.
 */
#include "cli.h"
#include "surfaces.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/io.h"

static bool given(double value)
{
    return !isnan(value);
}

static bool require(const cli_job *job, double value, const char *option)
{
    if (!given(value)) {
        cli_message("%s: --%s is required (see 'unroll help %s')", job->surface, option,
                    job->surface);
        return false;
    }
    return true;
}

static bool positive(const cli_job *job, double value, const char *option)
{
    if (!require(job, value, option))
        return false;
    if (!(value > 0)) {
        cli_message("%s: --%s must be positive (got %g)", job->surface, option, value);
        return false;
    }
    return true;
}

static int fail(const ur_error *error, const cli_job *job)
{
    cli_message("%s: %s", job->surface, error->message);
    return error->status == UR_ERROR_INPUT ? EXIT_USAGE : EXIT_INTERNAL;
}

static int curve_from_file(const cli_job *job, ur_curve **curve)
{
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = false;
    ur_error error;
    ur_status status = ur_curve_csv_read(job->curve_path, &points, &count, &closed, &error);
    if (status == UR_OK) {
        status = ur_curve_new_interpolating(points, count, closed, curve, &error);
        if (status != UR_OK)
            ur_error_prefix(&error, "%s: ", job->curve_path);
    }
    free(points);
    return status == UR_OK ? 0 : fail(&error, job);
}

/* Either --radius or --curve, never both. */
static int base_curve(const cli_job *job, ur_curve **curve)
{
    if (job->curve_path && given(job->radius)) {
        cli_message("%s: give either --radius or --curve, not both", job->surface);
        return EXIT_USAGE;
    }
    if (job->curve_path)
        return curve_from_file(job, curve);
    if (!positive(job, job->radius, "radius"))
        return EXIT_USAGE;
    ur_error error;
    return ur_curve_new_circle(job->radius, curve, &error) == UR_OK ? 0 : fail(&error, job);
}

static int build_cylinder(const cli_job *job, ur_ruled *ruled)
{
    if (!positive(job, job->height, "height"))
        return EXIT_USAGE;
    if (job->has_direction && !job->curve_path) {
        cli_message("cylinder: --direction goes with --curve (a --radius cylinder stands on z)");
        return EXIT_USAGE;
    }
    ur_curve *curve = NULL;
    int code = base_curve(job, &curve);
    if (code)
        return code;
    ur_vec3 direction = job->has_direction ? job->direction : ur_vec3_make(0, 0, 1);
    ur_error error;
    if (ur_ruled_cylinder(curve, direction, job->height, ruled, &error) != UR_OK) {
        ur_error_prefix(&error, "--direction: ");
        return fail(&error, job);
    }
    return 0;
}

/* Right circular cone or frustum: the apex above the base circle's centre. */
static int build_right_cone(const cli_job *job, ur_ruled *ruled)
{
    if (!positive(job, job->radius, "radius") || !positive(job, job->height, "height"))
        return EXIT_USAGE;
    if (given(job->cut) || job->has_apex) {
        cli_message("cone: --apex and --cut go with --curve; with --radius use --top-radius");
        return EXIT_USAGE;
    }
    double top = given(job->top_radius) ? job->top_radius : 0.0;
    if (!(top >= 0)) {
        cli_message("cone: --top-radius must be zero or positive (got %g)", top);
        return EXIT_USAGE;
    }
    if (fabs(top - job->radius) <= 1e-12 * job->radius) {
        cli_message("cone: --top-radius equals --radius: that is a cylinder ('unroll cylinder')");
        return EXIT_USAGE;
    }
    /* The rulings of a frustum meet at height H R / (R - r); the top is that far along. */
    double apex_height = job->height * job->radius / (job->radius - top);
    double cut = 1.0 - top / job->radius;
    ur_curve *curve = NULL;
    ur_error error;
    if (ur_curve_new_circle(job->radius, &curve, &error) != UR_OK ||
        ur_ruled_cone(curve, ur_vec3_make(0, 0, apex_height), cut, ruled, &error) != UR_OK)
        return fail(&error, job);
    return 0;
}

static int build_cone(const cli_job *job, ur_ruled *ruled)
{
    if (!job->curve_path)
        return build_right_cone(job, ruled);
    if (given(job->radius) || given(job->height) || given(job->top_radius)) {
        cli_message("cone: with --curve give --apex (and --cut), not --radius, --height or "
                    "--top-radius");
        return EXIT_USAGE;
    }
    if (!job->has_apex) {
        cli_message("cone: --apex X,Y,Z is required with --curve");
        return EXIT_USAGE;
    }
    double cut = given(job->cut) ? job->cut : 1.0;
    if (!(cut > 0 && cut <= 1)) {
        cli_message("cone: --cut must be in (0, 1] (got %g)", cut);
        return EXIT_USAGE;
    }
    ur_curve *curve = NULL;
    int code = curve_from_file(job, &curve);
    if (code)
        return code;
    ur_error error;
    return ur_ruled_cone(curve, job->apex, cut, ruled, &error) == UR_OK ? 0 : fail(&error, job);
}

static int build_tangent_of(const cli_job *job, ur_curve *curve, ur_ruled *ruled)
{
    double offset = given(job->offset) ? job->offset : 0.0;
    if (!(offset >= 0)) {
        ur_curve_free(curve);
        cli_message("%s: --offset must be zero or positive (got %g)", job->surface, offset);
        return EXIT_USAGE;
    }
    ur_error error;
    if (ur_ruled_tangent(curve, offset, job->width, ruled, &error) != UR_OK)
        return fail(&error, job);
    return 0;
}

static int build_helicoid(const cli_job *job, ur_ruled *ruled)
{
    if (!positive(job, job->radius, "radius") || !positive(job, job->pitch, "pitch") ||
        !positive(job, job->turns, "turns") || !positive(job, job->width, "width"))
        return EXIT_USAGE;
    ur_curve *curve = NULL;
    ur_error error;
    if (ur_curve_new_helix(job->radius, job->pitch, 0.0, 2 * M_PI * job->turns, &curve, &error) !=
        UR_OK)
        return fail(&error, job);
    return build_tangent_of(job, curve, ruled);
}

static int build_tangent(const cli_job *job, ur_ruled *ruled)
{
    if (!job->curve_path) {
        cli_message("tangent: --curve EDGE.csv is required");
        return EXIT_USAGE;
    }
    if (!positive(job, job->width, "width"))
        return EXIT_USAGE;
    ur_curve *curve = NULL;
    int code = curve_from_file(job, &curve);
    return code ? code : build_tangent_of(job, curve, ruled);
}

int cli_build_surface(const cli_job *job, ur_ruled *ruled)
{
    if (strcmp(job->surface, "cylinder") == 0)
        return build_cylinder(job, ruled);
    if (strcmp(job->surface, "cone") == 0)
        return build_cone(job, ruled);
    if (strcmp(job->surface, "helicoid") == 0)
        return build_helicoid(job, ruled);
    return build_tangent(job, ruled);
}
