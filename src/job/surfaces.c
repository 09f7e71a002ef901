/*
 * surfaces.c: from a job's surface parameters to a ruled surface, with a
 * message naming the parameter for every missing or impossible value.
 */
#include "stages.h"
#include "surfaces.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../base/c_locale.h"
#include "unroll/io.h"

static bool given(double value)
{
    return !isnan(value);
}

static bool require(const job_run *run, double value, const char *option)
{
    if (!given(value)) {
        job_fail_about(run, UR_ERROR_INPUT, option, "%s: %s is required", run->job.surface, option);
        return false;
    }
    return true;
}

static bool positive(const job_run *run, double value, const char *option)
{
    if (!require(run, value, option))
        return false;
    if (!(value > 0)) {
        job_fail_about(run, UR_ERROR_INPUT, option, "%s: %s must be positive (got %g)",
                       run->job.surface, option, value);
        return false;
    }
    return true;
}

static ur_status fail(const ur_error *error, const job_run *run)
{
    job_fail(run, error->status != UR_OK ? error->status : UR_ERROR_INTERNAL, "%s: %s",
             run->job.command, error->message);
    return ur_error_set_setting(run->error, error->setting);
}

static ur_status curve_from_file(const job_run *run, ur_curve **curve)
{
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = false;
    ur_error error;
    ur_status status = ur_curve_csv_read(run->job.curve_path, &points, &count, &closed, &error);
    if (status == UR_OK) {
        status = ur_curve_new_interpolating(points, count, closed, curve, &error);
        if (status != UR_OK)
            ur_error_prefix(&error, "%s: ", run->job.curve_path);
    }
    free(points);
    return status == UR_OK ? UR_OK : fail(&error, run);
}

/* Either a radius or a curve, never both. */
static ur_status base_curve(const job_run *run, ur_curve **curve)
{
    if (run->job.curve_path && given(run->job.radius)) {
        return job_fail_about(run, UR_ERROR_INPUT, "radius curve",
                              "%s: give either radius or curve, not both", run->job.surface);
    }
    if (run->job.curve_path)
        return curve_from_file(run, curve);
    if (!positive(run, run->job.radius, "radius"))
        return UR_ERROR_INPUT;
    ur_error error;
    return ur_curve_new_circle(run->job.radius, curve, &error) == UR_OK ? UR_OK : fail(&error, run);
}

static ur_status build_cylinder(const job_run *run, ur_ruled *ruled)
{
    if (!positive(run, run->job.height, "height"))
        return UR_ERROR_INPUT;
    if (run->job.has_direction && !run->job.curve_path) {
        return job_fail_about(
            run, UR_ERROR_INPUT, "direction curve radius",
            "cylinder: direction goes with curve (a cylinder given its radius stands on z)");
    }
    ur_curve *curve = NULL;
    ur_status code = base_curve(run, &curve);
    if (code)
        return code;
    ur_vec3 direction = run->job.has_direction ? run->job.direction : ur_vec3_make(0, 0, 1);
    ur_error error;
    if (ur_ruled_cylinder(curve, direction, run->job.height, ruled, &error) != UR_OK) {
        ur_error_prefix(&error, "direction: ");
        ur_error_set_setting(&error, "direction");
        return fail(&error, run);
    }
    return UR_OK;
}

/* Right circular cone or frustum: the apex above the base circle's centre. */
static ur_status build_right_cone(const job_run *run, ur_ruled *ruled)
{
    if (!positive(run, run->job.radius, "radius") || !positive(run, run->job.height, "height"))
        return UR_ERROR_INPUT;
    if (given(run->job.cut) || run->job.has_apex) {
        return job_fail_about(run, UR_ERROR_INPUT, "apex cut curve radius top-radius",
                              "cone: apex and cut go with curve; with radius use top-radius");
    }
    double top = given(run->job.top_radius) ? run->job.top_radius : 0.0;
    if (!(top >= 0)) {
        return job_fail_about(run, UR_ERROR_INPUT, "top-radius",
                              "cone: top-radius must be zero or positive (got %g)", top);
    }
    if (fabs(top - run->job.radius) <= 1e-12 * run->job.radius) {
        return job_fail_about(
            run, UR_ERROR_INPUT, "top-radius radius",
            "cone: top-radius equals radius: that is a cylinder ('unroll cylinder')");
    }
    /* The rulings of a frustum meet at height H R / (R - r); the top is that far along. */
    double apex_height = run->job.height * run->job.radius / (run->job.radius - top);
    double cut = 1.0 - top / run->job.radius;
    ur_curve *curve = NULL;
    ur_error error;
    if (ur_curve_new_circle(run->job.radius, &curve, &error) != UR_OK ||
        ur_ruled_cone(curve, ur_vec3_make(0, 0, apex_height), cut, ruled, &error) != UR_OK)
        return fail(&error, run);
    return UR_OK;
}

static ur_status build_cone(const job_run *run, ur_ruled *ruled)
{
    if (!run->job.curve_path)
        return build_right_cone(run, ruled);
    if (given(run->job.radius) || given(run->job.height) || given(run->job.top_radius)) {
        return job_fail_about(run, UR_ERROR_INPUT, "curve apex cut radius height top-radius",
                              "cone: with curve give apex (and cut), not radius, height or "
                              "top-radius");
    }
    if (!run->job.has_apex) {
        return job_fail_about(run, UR_ERROR_INPUT, "apex curve",
                              "cone: apex X,Y,Z is required with curve");
    }
    double cut = given(run->job.cut) ? run->job.cut : 1.0;
    if (!(cut > 0 && cut <= 1)) {
        return job_fail_about(run, UR_ERROR_INPUT, "cut", "cone: cut must be in (0, 1] (got %g)",
                              cut);
    }
    ur_curve *curve = NULL;
    ur_status code = curve_from_file(run, &curve);
    if (code)
        return code;
    ur_error error;
    return ur_ruled_cone(curve, run->job.apex, cut, ruled, &error) == UR_OK ? UR_OK
                                                                            : fail(&error, run);
}

static ur_status build_tangent_of(const job_run *run, ur_curve *curve, ur_ruled *ruled)
{
    double offset = given(run->job.offset) ? run->job.offset : 0.0;
    if (!(offset >= 0)) {
        ur_curve_free(curve);
        return job_fail_about(run, UR_ERROR_INPUT, "offset",
                              "%s: offset must be zero or positive (got %g)", run->job.surface,
                              offset);
    }
    ur_error error;
    if (ur_ruled_tangent(curve, offset, run->job.width, ruled, &error) != UR_OK)
        return fail(&error, run);
    return UR_OK;
}

static ur_status build_helicoid(const job_run *run, ur_ruled *ruled)
{
    if (!positive(run, run->job.radius, "radius") || !positive(run, run->job.pitch, "pitch") ||
        !positive(run, run->job.turns, "turns") || !positive(run, run->job.width, "width"))
        return UR_ERROR_INPUT;
    ur_curve *curve = NULL;
    ur_error error;
    if (ur_curve_new_helix(run->job.radius, run->job.pitch, 0.0, 2 * M_PI * run->job.turns, &curve,
                           &error) != UR_OK)
        return fail(&error, run);
    return build_tangent_of(run, curve, ruled);
}

static ur_status build_tangent(const job_run *run, ur_ruled *ruled)
{
    if (!run->job.curve_path) {
        return job_fail_about(run, UR_ERROR_INPUT, "curve", "tangent: curve EDGE.csv is required");
    }
    if (!positive(run, run->job.width, "width"))
        return UR_ERROR_INPUT;
    ur_curve *curve = NULL;
    ur_status code = curve_from_file(run, &curve);
    return code ? code : build_tangent_of(run, curve, ruled);
}

/* ---- Two rails ----------------------------------------------------------- */

static ur_status read_points(const job_run *run, const char *path, ur_vec3 **points, size_t *count,
                             bool *closed)
{
    ur_error error;
    if (ur_curve_csv_read(path, points, count, closed, &error) != UR_OK)
        return fail(&error, run);
    if (*count < 4) {
        job_fail(run, UR_ERROR_INPUT, "%s: %s: a rail needs at least 4 points (it has %zu)",
                 run->job.command, path, *count);
        free(*points);
        *points = NULL;
        return UR_ERROR_INPUT;
    }
    return UR_OK;
}

static void reverse_points(ur_vec3 *points, size_t count)
{
    for (size_t i = 0, j = count - 1; i < j; i++, j--) {
        ur_vec3 swap = points[i];
        points[i] = points[j];
        points[j] = swap;
    }
}

static size_t nearest_point(const ur_vec3 *points, size_t count, ur_vec3 to)
{
    size_t best = 0;
    for (size_t i = 1; i < count; i++)
        if (ur_vec3_distance(points[i], to) < ur_vec3_distance(points[best], to))
            best = i;
    return best;
}

/*
 * The rails must run the same way for the pairing to be monotonic.  Open
 * rails: their ends pair up shorter one way than the other.  Closed rails:
 * the directions at rail 1's first point and the nearest point of rail 2.
 */
static bool runs_against(const ur_vec3 *first, size_t first_count, bool closed,
                         const ur_vec3 *second, size_t second_count)
{
    if (!closed) {
        ur_vec3 a0 = first[0], a1 = first[first_count - 1];
        ur_vec3 b0 = second[0], b1 = second[second_count - 1];
        return ur_vec3_distance(a0, b1) + ur_vec3_distance(a1, b0) <
               ur_vec3_distance(a0, b0) + ur_vec3_distance(a1, b1);
    }
    size_t j = nearest_point(second, second_count, first[0]);
    ur_vec3 along_first = ur_vec3_sub(first[1], first[0]);
    ur_vec3 along_second = ur_vec3_sub(second[(j + 1) % second_count], second[j]);
    return ur_vec3_dot(along_first, along_second) < 0;
}

/*
 * Rails that meet or cross leave a ruling of no length there.  Their
 * polylines are compared (the interpolating curves stay within a small
 * fraction of a segment of them); closer than 1e-6 of their size is meeting.
 */
static ur_status check_rails_apart(const job_run *run, const ur_vec3 *first, size_t first_count,
                                   const ur_vec3 *second, size_t second_count)
{
    double size = 0.0;
    for (size_t i = 0; i < first_count; i++)
        size = fmax(size, ur_vec3_distance(first[i], first[0]));
    bool meet;
    size_t where = 0;
    ur_error error;
    if (ur_polylines_meet(first, first_count, second, second_count, 1e-6 * size, &meet, &where,
                          &error) != UR_OK)
        return fail(&error, run);
    if (meet) {
        return job_fail_about(
            run, UR_ERROR_INPUT, "rail1",
            "%s: the rails meet or cross between points %zu and %zu of rail1 (%g, %g, "
            "%g): a strip needs them apart everywhere",
            run->job.command, where + 1, where + 2, first[where].x, first[where].y, first[where].z);
    }
    return UR_OK;
}

/* A copy of a rail's points for the adjusted rail files, or NULL with the run's error set. */
static ur_vec3 *copy_rail(const job_run *run, const ur_vec3 *points, size_t count)
{
    ur_error error;
    ur_vec3 *copy = ur_alloc_array(count, sizeof *copy, &error);
    if (!copy)
        fail(&error, run);
    else
        memcpy(copy, points, count * sizeof *copy);
    return copy;
}

static const char *const adjust_names[4] = {"", "rail 1", "rail 2", "the rails"};

/* What the repair did, as a note; the files named are written at the end of the run. */
static void note_repair(const job_run *run, const ur_rail_repair_report *report)
{
    if (run->job.quiet)
        return;
    if (!(report->largest > 0)) {
        job_note(run, "%s: the strip exists along all of rail 1; %s unchanged", run->job.command,
                 run->job.adjust_rails == UR_REPAIR_BOTH ? "the rails are" : "the rail is");
        return;
    }
    char written[300] = "";
    const char *second = run->job.adjusted_rail1_path;
    if (run->job.adjusted_rail_path)
        c_snprintf(written, sizeof written, "; written to %s%s%s", run->job.adjusted_rail_path,
                   second ? " and " : "", second ? second : "");
    char figures[300];
    c_snprintf(figures, sizeof figures,
               "moved by at most %.4g mm (point %zu of rail %d, %.1f mm along it), %.4g mm on "
               "average",
               report->largest, report->largest_point + 1, report->largest_rail,
               report->largest_along, report->mean);
    job_note(run, "%s: %s %s%s", run->job.command, adjust_names[run->job.adjust_rails], figures,
             written);
    if (report->edge_too_close)
        job_warn(run,
                 "%s: warning: the repaired strip's edge of regression comes close to a rail: it "
                 "bends sharply there (see analyze)",
                 run->job.command);
}

/* The repair the job asks for (adjust_rails); a copy of each moved rail kept for its file. */
static ur_status adjust_rails(const job_run *run, ur_vec3 *points[2], const size_t count[2],
                              bool closed, job_adjusted_rail *adjusted)
{
    if (closed) {
        return job_fail_about(run, UR_ERROR_INPUT, "adjust", "%s: adjust works on open rails only",
                              run->job.command);
    }
    const ur_job *job = &run->job;
    ur_rail_repair_options options = {
        .rails = job->adjust_rails,
        .move_ends = job->adjust_ends,
        .direction = job->has_adjust_direction ? &job->adjust_direction : NULL,
        .plane_normal = job->has_adjust_plane ? &job->adjust_plane : NULL,
        .max_displacement = isnan(job->adjust_max) ? 0.0 : job->adjust_max,
        .context = job->context};
    ur_rail_repair_report report;
    ur_error error;
    if (ur_rails_repair(points[0], count[0], points[1], count[1], &options, &report, &error) !=
        UR_OK)
        return fail(&error, run);
    note_repair(run, &report);
    if (!adjusted)
        return UR_OK;
    adjusted->repaired = true;
    adjusted->report = report;
    for (int k = 0; k < 2; k++) {
        if (!(job->adjust_rails & (1u << k)))
            continue;
        adjusted->rails[k] = copy_rail(run, points[k], count[k]);
        if (!adjusted->rails[k])
            return run->error->status;
        adjusted->counts[k] = count[k];
    }
    return UR_OK;
}

/* The file rail k (0 or 1) is written to, or NULL: the moved rail, rail 2 when both move. */
static const char *adjusted_path(const ur_job *job, int k)
{
    if (k == 1)
        return job->adjusted_rail_path;
    return job->adjust_rails == UR_REPAIR_RAIL1 ? job->adjusted_rail_path
                                                : job->adjusted_rail1_path;
}

ur_status job_write_adjusted_rail(const job_run *run, const job_adjusted_rail *adjusted)
{
    for (int k = 0; k < 2; k++) {
        const char *path = adjusted_path(&run->job, k);
        if (!path || !adjusted->rails[k])
            continue;
        ur_error error;
        if (ur_curve_csv_write(path, adjusted->rails[k], adjusted->counts[k], run->job.context,
                               &error) != UR_OK) {
            const char *setting =
                path == run->job.adjusted_rail_path ? "adjusted-rail" : "adjusted-rail1";
            return job_fail_about(run, error.status, setting, "%s: %s %s: %s", run->job.command,
                                  setting, path, error.message);
        }
    }
    return UR_OK;
}

void job_adjusted_rail_free(job_adjusted_rail *adjusted)
{
    free(adjusted->rails[0]);
    free(adjusted->rails[1]);
    adjusted->rails[0] = adjusted->rails[1] = NULL;
}

/*
 * Reads both rails, checks them, orients rail 2 like rail 1 and, when the
 * job asks, reshapes them.
 */
static ur_status read_rails(const job_run *run, ur_curve *rails[2], bool *same_count,
                            job_adjusted_rail *adjusted)
{
    ur_vec3 *points[2] = {NULL, NULL};
    size_t count[2] = {0, 0};
    bool closed[2] = {false, false};
    const char *options[2] = {"rail1", "rail2"};
    ur_status code = 0;
    rails[0] = rails[1] = NULL;
    for (int k = 0; k < 2 && !code; k++) {
        if (!run->job.rail_paths[k]) {
            code = job_fail_about(run, UR_ERROR_INPUT, options[k], "%s: %s FILE.csv is required",
                                  run->job.command, options[k]);
        } else {
            code = read_points(run, run->job.rail_paths[k], &points[k], &count[k], &closed[k]);
        }
    }
    if (!code && closed[0] != closed[1]) {
        code = job_fail_about(run, UR_ERROR_INPUT, "rail1 rail2",
                              "%s: rail1 is %s but rail2 is %s: give two open or two closed rails",
                              run->job.command, closed[0] ? "closed" : "open",
                              closed[1] ? "closed" : "open");
    }
    if (!code)
        code = check_rails_apart(run, points[0], count[0], points[1], count[1]);
    if (!code && runs_against(points[0], count[0], closed[0], points[1], count[1])) {
        reverse_points(points[1], count[1]);
        if (!run->job.quiet)
            job_note_about(run, "rail2 rail1", "note: rail2 runs against rail1; using it reversed");
    }
    if (!code && run->job.adjust_rails)
        code = adjust_rails(run, points, count, closed[0], adjusted);
    ur_error error;
    for (int k = 0; k < 2 && !code; k++)
        if (ur_curve_new_interpolating(points[k], count[k], closed[k], &rails[k], &error) !=
            UR_OK) {
            ur_error_prefix(&error, "%s: ", run->job.rail_paths[k]);
            code = fail(&error, run);
        }
    if (code) {
        ur_curve_free(rails[0]);
        ur_curve_free(rails[1]);
        rails[0] = rails[1] = NULL;
    }
    *same_count = count[0] == count[1];
    free(points[0]);
    free(points[1]);
    return code;
}

static ur_status build_strip(const job_run *run, ur_ruled *ruled, job_adjusted_rail *adjusted)
{
    if (run->job.adjust_rails && run->job.natural_pairing) {
        return job_fail_about(run, UR_ERROR_INPUT, "adjust pairing",
                              "strip: adjust goes with pairing developable");
    }
    ur_curve *rails[2];
    bool same_count;
    ur_status code = read_rails(run, rails, &same_count, adjusted);
    if (code)
        return code;
    ur_error error;
    ur_status status = run->job.natural_pairing
                           ? ur_ruled_general(rails[0], rails[1], UR_PAIR_ARC_LENGTH, ruled, &error)
                           : ur_ruled_strip(rails[0], rails[1], ruled, &error);
    return status == UR_OK ? UR_OK : fail(&error, run);
}

static ur_status build_ruled(const job_run *run, ur_ruled *ruled)
{
    ur_curve *rails[2];
    bool same_count;
    ur_status code = read_rails(run, rails, &same_count, NULL);
    if (code)
        return code;
    ur_error error;
    ur_pairing_rule rule = same_count ? UR_PAIR_POINTS : UR_PAIR_ARC_LENGTH;
    return ur_ruled_general(rails[0], rails[1], rule, ruled, &error) == UR_OK ? 0
                                                                              : fail(&error, run);
}

/* A straight rail from p to q, as a curve through four points on it. */
static ur_status straight_rail(ur_vec3 p, ur_vec3 q, ur_curve **rail, ur_error *error)
{
    ur_vec3 points[4];
    for (int k = 0; k < 4; k++)
        points[k] = ur_vec3_add_scaled(p, ur_vec3_sub(q, p), k / 3.0);
    return ur_curve_new_interpolating(points, 4, false, rail, error);
}

/*
 * Two adjacent corners at one point make the hypar the flat triangle of the
 * other three: the cone from that point over the opposite edge.
 */
static ur_status build_triangle(const job_run *run, const ur_vec3 *c, int apex, ur_ruled *ruled)
{
    int first = (apex + 2) % 4, second = (apex + 3) % 4;
    if (!run->job.quiet)
        job_note(run,
                 "note: corners %d and %d are the same point: the hypar is a flat triangle, "
                 "developed exactly",
                 apex + 1, (apex + 1) % 4 + 1);
    ur_curve *edge = NULL;
    ur_error error;
    if (straight_rail(c[first], c[second], &edge, &error) != UR_OK ||
        ur_ruled_cone(edge, c[apex], 1.0, ruled, &error) != UR_OK)
        return fail(&error, run);
    return UR_OK;
}

/* Which adjacent pair of corners coincides (the first of the two), or -1; 4 if worse. */
static ur_status repeated_corner(const ur_vec3 *c, double size)
{
    int found = -1, count = 0;
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            if (!(ur_vec3_distance(c[i], c[j]) > 1e-9 * size)) {
                count++;
                found = j == i + 1 ? i : i == 0 && j == 3 ? 3 : 4;
            }
    return count > 1 ? 4 : found;
}

/* Corners in order round the skew quadrilateral; rulings join P0P1 to P3P2. */
static ur_status build_hypar(const job_run *run, ur_ruled *ruled)
{
    if (!run->job.has_corners) {
        return job_fail_about(run, UR_ERROR_INPUT, "corners",
                              "hypar: corners X,Y,Z:X,Y,Z:X,Y,Z:X,Y,Z is required");
    }
    const ur_vec3 *c = run->job.corners;
    double size = 0.0;
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            size = fmax(size, ur_vec3_distance(c[i], c[j]));
    int repeated = repeated_corner(c, size);
    if (repeated == 4 || !(size > 0)) {
        return job_fail_about(run, UR_ERROR_INPUT, "corners",
                              "hypar: corners: opposite or more than two corners are the same "
                              "point: that is no surface");
    }
    if (repeated >= 0)
        return build_triangle(run, c, repeated, ruled);
    ur_vec3 normal = ur_vec3_cross(ur_vec3_sub(c[1], c[0]), ur_vec3_sub(c[3], c[0]));
    if (!(ur_vec3_length(normal) > 1e-12 * size * size)) {
        return job_fail_about(run, UR_ERROR_INPUT, "corners",
                              "hypar: corners: corners 1, 2 and 4 lie on one line");
    }
    double lift = fabs(ur_vec3_dot(ur_vec3_sub(c[2], c[0]), normal)) / ur_vec3_length(normal);
    if (lift <= 1e-9 * size && !run->job.quiet)
        job_note(run, "note: the four corners lie in one plane: the hypar is a flat quadrilateral, "
                      "developed exactly");
    ur_curve *rails[2] = {NULL, NULL};
    ur_error error;
    if (straight_rail(c[0], c[1], &rails[0], &error) != UR_OK ||
        straight_rail(c[3], c[2], &rails[1], &error) != UR_OK) {
        ur_curve_free(rails[0]);
        return fail(&error, run);
    }
    return ur_ruled_general(rails[0], rails[1], UR_PAIR_ARC_LENGTH, ruled, &error) == UR_OK
               ? 0
               : fail(&error, run);
}

ur_status job_build_surface(const job_run *run, ur_ruled *ruled, job_adjusted_rail *adjusted)
{
    if (adjusted)
        memset(adjusted, 0, sizeof *adjusted);
    if (strcmp(run->job.surface, "strip") == 0)
        return build_strip(run, ruled, adjusted);
    if (strcmp(run->job.surface, "ruled") == 0)
        return build_ruled(run, ruled);
    if (strcmp(run->job.surface, "hypar") == 0)
        return build_hypar(run, ruled);
    if (strcmp(run->job.surface, "cylinder") == 0)
        return build_cylinder(run, ruled);
    if (strcmp(run->job.surface, "cone") == 0)
        return build_cone(run, ruled);
    if (strcmp(run->job.surface, "helicoid") == 0)
        return build_helicoid(run, ruled);
    return build_tangent(run, ruled);
}
