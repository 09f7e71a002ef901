/*
 * offset.c: the parallel surface of a ruled surface, at a signed distance
 * along its normal: a face of the material moved to the layer that keeps
 * its length when the sheet is bent (the neutral layer, see --surface).
 *
 * On a developable the unit normal n(u) is the same all along the ruling at
 * u, so moving both ends of every ruling by d n(u) moves the whole ruling:
 * the parallel surface is ruled again, its rulings parallel to the old ones
 * and its tangent plane along each of them parallel to the old one, so it is
 * developable again and its net exact.  Across the rulings lengths change by
 * the factor 1 - d k, k the normal curvature across the rulings (positive
 * when the surface bends toward n): that is what the offset is for.
 *
 * "Toward the inside of the bend" is the side of the centre of curvature of
 * the section across the rulings.  A surface that bends both ways (an
 * inflection) has no one inside: the side where the integral of k over the
 * area is positive, the side most of the bending goes to, counts.  Where
 * d k reaches 1 the parallel surface folds over itself (d is beyond the bend
 * radius there); that is refused.
 *
 * The new rails are sampled densely and interpolated (C2 splines), then
 * built with the constructor of their kind: a cylinder stays a cylinder with
 * the same direction and height; a cone reaching its apex with the apex
 * unmoved (a flat one) stays a cone; a general ruled surface pairs the new
 * rails' points as the old ones were paired; every other developable
 * becomes the developable strip between its two new rails, whose pairing is
 * solved, not assumed.  A surface that is not developable has a normal that
 * turns along the ruling: each rail moves along its own normal, which gives
 * the parallel surface along the rails and approximates it between them.
 */
#include "surface_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

enum {
    CHECK_RULINGS = 1000, /* rulings sampled for the bend survey */
    CHECK_ALONG = 9,      /* points along each of them */
    MIN_POINTS = 256,     /* points of each new rail */
    MAX_POINTS = 16384,
    POINTS_PER_RADIAN = 128, /* of the rails' turning: position error ~ (h k)^4 */
};

/* Rails at u and their second derivatives, by central differences inside [u0, u1]. */
static void rails_with_second(ur_ruled *ruled, double u, double u0, double u1, ur_vec3 rails[4],
                              ur_vec3 second[2])
{
    double h = 1e-5 * (u1 - u0);
    double low = fmax(u - h, u0), high = fmin(u + h, u1);
    ur_vec3 below[4], above[4];
    ur_ruled_rails(ruled, low, below);
    ur_ruled_rails(ruled, high, above);
    ur_ruled_rails(ruled, u, rails);
    second[0] = ur_vec3_scale(ur_vec3_sub(above[1], below[1]), 1.0 / (high - low));
    second[1] = ur_vec3_scale(ur_vec3_sub(above[3], below[3]), 1.0 / (high - low));
}

/* r_u at v: a' + v (b' - a'). */
static ur_vec3 along_u(const ur_vec3 rails[4], double v)
{
    return ur_vec3_add_scaled(rails[1], ur_vec3_sub(rails[3], rails[1]), v);
}

/* The unit normal r_u x r_v at v; false where r_u runs along the ruling or vanishes. */
static bool normal_at(const ur_vec3 rails[4], double v, ur_vec3 *normal)
{
    ur_vec3 r_v = ur_vec3_sub(rails[2], rails[0]);
    ur_vec3 cross = ur_vec3_cross(along_u(rails, v), r_v);
    double size = fmax(ur_vec3_length(rails[1]), ur_vec3_length(rails[3])) * ur_vec3_length(r_v);
    double length = ur_vec3_length(cross);
    if (!(length > 1e-9 * size))
        return false;
    *normal = ur_vec3_scale(cross, 1.0 / length);
    return true;
}

/*
 * The normal curvature across the ruling at v, k = (L G - 2 M F) / (E G - F^2)
 * (N = r_vv . n is 0 on a ruled surface; on a developable M is 0 too and k
 * is its one principal curvature), positive when the surface bends toward
 * r_u x r_v; *density is |r_u x r_v|, the area per du dv.  False where the
 * normal is undefined (an apex, the edge of regression).
 */
static bool across_curvature(const ur_vec3 rails[4], const ur_vec3 second[2], double v,
                             double *curvature, double *density)
{
    ur_vec3 n;
    if (!normal_at(rails, v, &n))
        return false;
    ur_vec3 r_u = along_u(rails, v), r_v = ur_vec3_sub(rails[2], rails[0]);
    ur_vec3 r_uu = ur_vec3_add_scaled(second[0], ur_vec3_sub(second[1], second[0]), v);
    double e = ur_vec3_dot(r_u, r_u), f = ur_vec3_dot(r_u, r_v), g = ur_vec3_dot(r_v, r_v);
    double l = ur_vec3_dot(r_uu, n), m = ur_vec3_dot(ur_vec3_sub(rails[3], rails[1]), n);
    double area2 = e * g - f * f;
    *density = ur_vec3_length(ur_vec3_cross(r_u, r_v));
    *curvature = (l * g - 2 * m * f) / area2;
    return isfinite(*curvature);
}

/* Where the surface bends most one way and the other, and which way it bends overall. */
typedef struct bend_survey {
    double integral;         /* of k over the area, k toward r_u x r_v */
    double most, least;      /* the largest and smallest k (+-INFINITY at an apex) */
    double most_u, most_v;   /* where most is */
    double least_u, least_v; /* where least is */
    double turning;          /* the larger total turning of the two rails' tangents */
} bend_survey;

static void note_curvature(bend_survey *survey, double k, double u, double v)
{
    if (k > survey->most) {
        survey->most = k;
        survey->most_u = u;
        survey->most_v = v;
    }
    if (k < survey->least) {
        survey->least = k;
        survey->least_u = u;
        survey->least_v = v;
    }
}

/*
 * k at v on one ruling.  At an end where the normal is undefined (an apex,
 * the edge of regression) k is infinite, with the sign it has a hundredth
 * of the ruling away: nearer, k is too small against the rounding of r_uu.
 */
static void survey_point(bend_survey *survey, const ur_vec3 rails[4], const ur_vec3 second[2],
                         double u, double v, double weight)
{
    double k, density;
    if (across_curvature(rails, second, v, &k, &density)) {
        survey->integral += weight * k * density;
        note_curvature(survey, k, u, v);
        return;
    }
    double nearby = v < 0.5 ? v + 1e-2 : v - 1e-2;
    if (across_curvature(rails, second, nearby, &k, &density) && k != 0)
        note_curvature(survey, k > 0 ? INFINITY : -INFINITY, u, v);
}

static double turning_angle(ur_vec3 from, ur_vec3 to)
{
    return atan2(ur_vec3_length(ur_vec3_cross(from, to)), ur_vec3_dot(from, to));
}

static void survey_bend(ur_ruled *ruled, bend_survey *survey)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    *survey = (bend_survey){.most = -INFINITY, .least = INFINITY};
    ur_vec3 previous[4];
    double turning[2] = {0.0, 0.0};
    for (int i = 0; i <= CHECK_RULINGS; i++) {
        double u = u0 + (u1 - u0) * i / CHECK_RULINGS;
        ur_vec3 rails[4], second[2];
        rails_with_second(ruled, u, u0, u1, rails, second);
        double weight_u = i == 0 || i == CHECK_RULINGS ? 0.5 : 1.0;
        for (int j = 0; j < CHECK_ALONG; j++) {
            double weight = weight_u * (j == 0 || j == CHECK_ALONG - 1 ? 0.5 : 1.0);
            survey_point(survey, rails, second, u, (double)j / (CHECK_ALONG - 1), weight);
        }
        if (i > 0) {
            turning[0] += turning_angle(previous[1], rails[1]);
            turning[1] += turning_angle(previous[3], rails[3]);
        }
        for (int k = 0; k < 4; k++)
            previous[k] = rails[k];
    }
    survey->turning =
        fmax(isfinite(turning[0]) ? turning[0] : 0.0, isfinite(turning[1]) ? turning[1] : 0.0);
}

/*
 * Moving by D along r_u x r_v folds the surface where D k >= 1: toward the
 * side it bends to, by at least the bend radius 1 / |k|.
 */
static ur_status check_fold(ur_ruled *ruled, const bend_survey *survey, double signed_distance,
                            double distance, ur_error *error)
{
    double k = signed_distance > 0 ? survey->most : survey->least;
    if (!(signed_distance * k >= 1.0))
        return UR_OK;
    double u = signed_distance > 0 ? survey->most_u : survey->least_u;
    double v = signed_distance > 0 ? survey->most_v : survey->least_v;
    char place[256], radius[64];
    describe_place(ruled, u, place, sizeof place);
    c_snprintf(radius, sizeof radius, isinf(k) ? "0 mm (an apex or edge of regression)" : "%.4g mm",
               1.0 / fabs(k));
    return ur_error_set(error, UR_ERROR_INPUT,
                        "moving the surface %.4g mm %s its bend would fold it over itself: the "
                        "bend radius there is only %s, %s, %.0f %% of the way along the ruling; "
                        "a layer that far from this face cannot bend that tightly",
                        fabs(distance), distance > 0 ? "toward the inside of" : "away from", radius,
                        place, 100 * v);
}

/* The normals to move each end of the ruling along: one for a developable, two otherwise. */
static bool ruling_normals(const ur_ruled *ruled, const ur_vec3 rails[4], ur_vec3 normals[2])
{
    static const double order[2][3] = {{0.0, 0.5, 1.0}, {1.0, 0.5, 0.0}};
    for (int end = 0; end < 2; end++) {
        bool found = false;
        for (int k = 0; k < 3 && !found; k++)
            found = normal_at(rails, order[end][k], &normals[end]);
        if (!found)
            return false;
    }
    if (ruled->kind != UR_RULED_GENERAL) {
        /* The same normal: where r_u is longer, it is better defined. */
        bool b_longer = ur_vec3_length(rails[3]) > ur_vec3_length(rails[1]);
        normals[b_longer ? 0 : 1] = normals[b_longer ? 1 : 0];
    }
    return true;
}

/* The points of both new rails at count parameters (one turn without its end when closed). */
static ur_status sample_rails(ur_ruled *ruled, double signed_distance, size_t count, bool closed,
                              ur_vec3 *points[2], ur_error *error)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    double steps = closed ? (double)count : (double)(count - 1);
    for (size_t i = 0; i < count; i++) {
        double u = u0 + (u1 - u0) * (double)i / steps;
        ur_vec3 rails[4], normals[2];
        ur_ruled_rails(ruled, u, rails);
        if (!ruling_normals(ruled, rails, normals)) {
            char place[256];
            describe_place(ruled, u, place, sizeof place);
            return ur_error_set(error, UR_ERROR_INPUT,
                                "the surface has no normal along the ruling %s (it has no width "
                                "there), so it cannot be moved to another layer",
                                place);
        }
        points[0][i] = ur_vec3_add_scaled(rails[0], normals[0], signed_distance);
        points[1][i] = ur_vec3_add_scaled(rails[2], normals[1], signed_distance);
    }
    return UR_OK;
}

/* All points within a billionth of the rails' size of the first: a cone's apex. */
static bool collapsed(const ur_vec3 *points, const ur_vec3 *other, size_t count)
{
    double size = 0.0, spread = 0.0;
    for (size_t i = 0; i < count; i++) {
        size = fmax(size, ur_vec3_distance(other[i], points[0]));
        spread = fmax(spread, ur_vec3_distance(points[i], points[0]));
    }
    return spread <= 1e-9 * size;
}

static ur_status build(ur_ruled *ruled, ur_vec3 *points[2], size_t count, bool closed,
                       ur_ruled *offset, ur_error *error)
{
    ur_curve *rails[2] = {NULL, NULL};
    ur_status status = ur_curve_new_interpolating(points[0], count, closed, &rails[0], error);
    if (status != UR_OK)
        return status;
    if (ruled->kind == UR_RULED_CYLINDER)
        return ur_ruled_cylinder(rails[0], ruled->direction, ruled->height, offset, error);
    if (collapsed(points[1], points[0], count))
        return ur_ruled_cone(rails[0], points[1][0], 1.0, offset, error);
    status = ur_curve_new_interpolating(points[1], count, closed, &rails[1], error);
    if (status != UR_OK) {
        ur_curve_free(rails[0]);
        return status;
    }
    if (ruled->kind == UR_RULED_GENERAL)
        return ur_ruled_general(rails[0], rails[1], UR_PAIR_POINTS, offset, error);
    return ur_ruled_strip(rails[0], rails[1], offset, error);
}

/* A strip is moved only where it exists. */
static ur_status check_no_gap(ur_ruled *ruled, ur_error *error)
{
    const ur_interval *gap = ruled_gap_in_use(ruled);
    if (gap)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the strip does not exist from %.6g to %.6g mm along rail 1: "
                            "move each part of its domain of existence on its own",
                            gap->arc_start, gap->arc_end);
    return UR_OK;
}

static size_t rail_points(const bend_survey *survey)
{
    double wanted = MIN_POINTS + POINTS_PER_RADIAN * survey->turning;
    return wanted < MAX_POINTS ? (size_t)wanted : MAX_POINTS;
}

ur_status ur_ruled_offset(ur_ruled *ruled, double distance, ur_ruled *offset, ur_error *error)
{
    memset(offset, 0, sizeof *offset);
    if (!isfinite(distance))
        return ur_error_set(error, UR_ERROR_INPUT, "the offset must be a finite distance");
    ur_status status = check_no_gap(ruled, error);
    if (status != UR_OK)
        return status;
    bend_survey survey;
    survey_bend(ruled, &survey);
    /* Toward the inside: along r_u x r_v when the surface bends that way overall. */
    double signed_distance = survey.integral >= 0 ? distance : -distance;
    status = check_fold(ruled, &survey, signed_distance, distance, error);
    if (status != UR_OK)
        return status;
    size_t count = rail_points(&survey);
    bool closed = ur_ruled_is_closed(ruled);
    ur_vec3 *points[2];
    points[0] = ur_alloc_array(count, sizeof *points[0], error);
    points[1] = ur_alloc_array(count, sizeof *points[1], error);
    status = points[0] && points[1] ? UR_OK : UR_ERROR_MEMORY;
    if (status == UR_OK)
        status = sample_rails(ruled, signed_distance, count, closed, points, error);
    if (status == UR_OK)
        status = build(ruled, points, count, closed, offset, error);
    free(points[0]);
    free(points[1]);
    return status;
}
