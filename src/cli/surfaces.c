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
    cli_message("%s: %s", job->command, error->message);
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

/* ---- Two rails ----------------------------------------------------------- */

static int read_points(const cli_job *job, const char *path, ur_vec3 **points, size_t *count,
                       bool *closed)
{
    ur_error error;
    if (ur_curve_csv_read(path, points, count, closed, &error) != UR_OK)
        return fail(&error, job);
    if (*count < 4) {
        cli_message("%s: %s: a rail needs at least 4 points (it has %zu)", job->command, path,
                    *count);
        free(*points);
        *points = NULL;
        return EXIT_USAGE;
    }
    return 0;
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
static int check_rails_apart(const cli_job *job, const ur_vec3 *first, size_t first_count,
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
        return fail(&error, job);
    if (meet) {
        cli_message("%s: the rails meet or cross between points %zu and %zu of --rail1 (%g, %g, "
                    "%g): a strip needs them apart everywhere",
                    job->command, where + 1, where + 2, first[where].x, first[where].y,
                    first[where].z);
        return EXIT_USAGE;
    }
    return 0;
}

/* A copy of a rail's points for --adjusted-rail, or NULL with *code set. */
static ur_vec3 *copy_rail(const cli_job *job, const ur_vec3 *points, size_t count, int *code)
{
    ur_error error;
    ur_vec3 *copy = ur_alloc_array(count, sizeof *copy, &error);
    if (!copy)
        *code = fail(&error, job);
    else
        memcpy(copy, points, count * sizeof *copy);
    return copy;
}

static const char *const adjust_names[4] = {"", "rail 1", "rail 2", "the rails"};

/* --adjust: reshapes the rails and keeps a copy of each moved one for --adjusted-rail. */
static int adjust_rails(const cli_job *job, ur_vec3 *points[2], const size_t count[2], bool closed,
                        cli_adjusted_rail *adjusted)
{
    if (closed) {
        cli_message("%s: --adjust works on open rails only", job->command);
        return EXIT_USAGE;
    }
    ur_rail_repair_options options = {
        .rails = job->adjust_rails,
        .move_ends = job->adjust_ends,
        .direction = job->has_adjust_direction ? &job->adjust_direction : NULL,
        .plane_normal = job->has_adjust_plane ? &job->adjust_plane : NULL,
        .max_displacement = isnan(job->adjust_max) ? 0.0 : job->adjust_max};
    ur_rail_repair_report report;
    ur_error error;
    if (ur_rails_repair(points[0], count[0], points[1], count[1], &options, &report, &error) !=
        UR_OK)
        return fail(&error, job);
    char written[300] = "";
    if (job->adjusted_rail_path && report.largest > 0)
        snprintf(written, sizeof written, "; written to %s%s%s", job->adjusted_rail_path,
                 job->adjusted_rail1_path ? " and " : "",
                 job->adjusted_rail1_path ? job->adjusted_rail1_path : "");
    if (!job->quiet && report.largest > 0)
        cli_message("%s: --adjust: %s moved by at most %.4g mm (point %zu of rail %d, %.1f mm "
                    "along it), %.4g mm on average%s",
                    job->command, adjust_names[job->adjust_rails], report.largest,
                    report.largest_point + 1, report.largest_rail, report.largest_along,
                    report.mean, written);
    else if (!job->quiet)
        cli_message("%s: --adjust: the strip exists along all of rail 1; %s unchanged",
                    job->command,
                    job->adjust_rails == UR_REPAIR_BOTH ? "the rails are" : "the rail is");
    if (!adjusted)
        return 0;
    int code = 0;
    adjusted->report = report;
    for (int k = 0; k < 2 && !code; k++) {
        if (!(job->adjust_rails & (1u << k)))
            continue;
        adjusted->rails[k] = copy_rail(job, points[k], count[k], &code);
        adjusted->counts[k] = count[k];
    }
    return code;
}

/* The path --adjusted-rail writes rail k to, or NULL. */
static const char *adjusted_path(const cli_job *job, int k)
{
    if (k == 1)
        return job->adjusted_rail_path;
    return job->adjust_rails == UR_REPAIR_RAIL1 ? job->adjusted_rail_path
                                                : job->adjusted_rail1_path;
}

int cli_write_adjusted_rail(const cli_job *job, const cli_adjusted_rail *adjusted)
{
    for (int k = 0; k < 2; k++) {
        const char *path = adjusted_path(job, k);
        if (!path || !adjusted->rails[k])
            continue;
        ur_error error;
        if (ur_curve_csv_write(path, adjusted->rails[k], adjusted->counts[k], &error) != UR_OK) {
            cli_message("%s: --adjusted-rail %s: %s", job->command, path, error.message);
            return cli_exit_status(&error);
        }
    }
    return 0;
}

/*
 * Reads both rails, checks them, orients rail 2 like rail 1 and, with
 * --adjust, moves them.
 */
static int read_rails(const cli_job *job, ur_curve *rails[2], bool *same_count,
                      cli_adjusted_rail *adjusted)
{
    ur_vec3 *points[2] = {NULL, NULL};
    size_t count[2] = {0, 0};
    bool closed[2] = {false, false};
    const char *options[2] = {"rail1", "rail2"};
    int code = 0;
    rails[0] = rails[1] = NULL;
    for (int k = 0; k < 2 && !code; k++) {
        if (!job->rail_paths[k]) {
            cli_message("%s: --%s FILE.csv is required", job->command, options[k]);
            code = EXIT_USAGE;
        } else {
            code = read_points(job, job->rail_paths[k], &points[k], &count[k], &closed[k]);
        }
    }
    if (!code && closed[0] != closed[1]) {
        cli_message("%s: --rail1 is %s but --rail2 is %s: give two open or two closed rails",
                    job->command, closed[0] ? "closed" : "open", closed[1] ? "closed" : "open");
        code = EXIT_USAGE;
    }
    if (!code)
        code = check_rails_apart(job, points[0], count[0], points[1], count[1]);
    if (!code && runs_against(points[0], count[0], closed[0], points[1], count[1])) {
        reverse_points(points[1], count[1]);
        if (!job->quiet)
            cli_message("note: --rail2 runs against --rail1; using it reversed");
    }
    if (!code && job->adjust_rails)
        code = adjust_rails(job, points, count, closed[0], adjusted);
    ur_error error;
    for (int k = 0; k < 2 && !code; k++)
        if (ur_curve_new_interpolating(points[k], count[k], closed[k], &rails[k], &error) !=
            UR_OK) {
            ur_error_prefix(&error, "%s: ", job->rail_paths[k]);
            code = fail(&error, job);
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

static int build_strip(const cli_job *job, ur_ruled *ruled, cli_adjusted_rail *adjusted)
{
    if (job->adjust_rails && job->natural_pairing) {
        cli_message("strip: --adjust goes with --pairing developable");
        return EXIT_USAGE;
    }
    ur_curve *rails[2];
    bool same_count;
    int code = read_rails(job, rails, &same_count, adjusted);
    if (code)
        return code;
    ur_error error;
    ur_status status = job->natural_pairing
                           ? ur_ruled_general(rails[0], rails[1], UR_PAIR_ARC_LENGTH, ruled, &error)
                           : ur_ruled_strip(rails[0], rails[1], ruled, &error);
    return status == UR_OK ? 0 : fail(&error, job);
}

static int build_ruled(const cli_job *job, ur_ruled *ruled)
{
    ur_curve *rails[2];
    bool same_count;
    int code = read_rails(job, rails, &same_count, NULL);
    if (code)
        return code;
    ur_error error;
    ur_pairing_rule rule = same_count ? UR_PAIR_POINTS : UR_PAIR_ARC_LENGTH;
    return ur_ruled_general(rails[0], rails[1], rule, ruled, &error) == UR_OK ? 0
                                                                              : fail(&error, job);
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
static int build_triangle(const cli_job *job, const ur_vec3 *c, int apex, ur_ruled *ruled)
{
    int first = (apex + 2) % 4, second = (apex + 3) % 4;
    if (!job->quiet)
        cli_message("note: corners %d and %d are the same point: the hypar is a flat triangle, "
                    "developed exactly",
                    apex + 1, (apex + 1) % 4 + 1);
    ur_curve *edge = NULL;
    ur_error error;
    if (straight_rail(c[first], c[second], &edge, &error) != UR_OK ||
        ur_ruled_cone(edge, c[apex], 1.0, ruled, &error) != UR_OK)
        return fail(&error, job);
    return 0;
}

/* Which adjacent pair of corners coincides (the first of the two), or -1; 4 if worse. */
static int repeated_corner(const ur_vec3 *c, double size)
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
static int build_hypar(const cli_job *job, ur_ruled *ruled)
{
    if (!job->has_corners) {
        cli_message("hypar: --corners X,Y,Z:X,Y,Z:X,Y,Z:X,Y,Z is required");
        return EXIT_USAGE;
    }
    const ur_vec3 *c = job->corners;
    double size = 0.0;
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            size = fmax(size, ur_vec3_distance(c[i], c[j]));
    int repeated = repeated_corner(c, size);
    if (repeated == 4 || !(size > 0)) {
        cli_message("hypar: --corners: opposite or more than two corners are the same point: "
                    "that is no surface");
        return EXIT_USAGE;
    }
    if (repeated >= 0)
        return build_triangle(job, c, repeated, ruled);
    ur_vec3 normal = ur_vec3_cross(ur_vec3_sub(c[1], c[0]), ur_vec3_sub(c[3], c[0]));
    if (!(ur_vec3_length(normal) > 1e-12 * size * size)) {
        cli_message("hypar: --corners: corners 1, 2 and 4 lie on one line");
        return EXIT_USAGE;
    }
    double lift = fabs(ur_vec3_dot(ur_vec3_sub(c[2], c[0]), normal)) / ur_vec3_length(normal);
    if (lift <= 1e-9 * size && !job->quiet)
        cli_message("note: the four corners lie in one plane: the hypar is a flat quadrilateral, "
                    "developed exactly");
    ur_curve *rails[2] = {NULL, NULL};
    ur_error error;
    if (straight_rail(c[0], c[1], &rails[0], &error) != UR_OK ||
        straight_rail(c[3], c[2], &rails[1], &error) != UR_OK) {
        ur_curve_free(rails[0]);
        return fail(&error, job);
    }
    return ur_ruled_general(rails[0], rails[1], UR_PAIR_ARC_LENGTH, ruled, &error) == UR_OK
               ? 0
               : fail(&error, job);
}

int cli_build_surface(const cli_job *job, ur_ruled *ruled, cli_adjusted_rail *adjusted)
{
    if (adjusted)
        memset(adjusted, 0, sizeof *adjusted);
    if (strcmp(job->surface, "strip") == 0)
        return build_strip(job, ruled, adjusted);
    if (strcmp(job->surface, "ruled") == 0)
        return build_ruled(job, ruled);
    if (strcmp(job->surface, "hypar") == 0)
        return build_hypar(job, ruled);
    if (strcmp(job->surface, "cylinder") == 0)
        return build_cylinder(job, ruled);
    if (strcmp(job->surface, "cone") == 0)
        return build_cone(job, ruled);
    if (strcmp(job->surface, "helicoid") == 0)
        return build_helicoid(job, ruled);
    return build_tangent(job, ruled);
}

void cli_adjusted_rail_free(cli_adjusted_rail *adjusted)
{
    free(adjusted->rails[0]);
    free(adjusted->rails[1]);
    adjusted->rails[0] = adjusted->rails[1] = NULL;
}
