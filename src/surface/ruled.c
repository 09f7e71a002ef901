/*
 * ruled.c: the developable ruled surfaces (cylinder, cone, tangent
 * developable), their rails, the intrinsic quantities the development needs,
 * a regularity check, and the 3D area by quadrature.
 */
#include "unroll/surface.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <stdio.h>
#include <string.h>

static ur_status take_curve(ur_ruled *ruled, ur_ruled_kind kind, ur_curve *curve)
{
    memset(ruled, 0, sizeof *ruled);
    ruled->kind = kind;
    ruled->curve = curve;
    gsl_set_error_handler_off();
    return UR_OK;
}

static ur_status refuse(ur_ruled *ruled, ur_curve *curve, ur_error *error, const char *message)
{
    ur_curve_free(curve);
    memset(ruled, 0, sizeof *ruled);
    return ur_error_set(error, UR_ERROR_INPUT, "%s", message);
}

ur_status ur_ruled_cylinder(ur_curve *curve, ur_vec3 direction, double height, ur_ruled *ruled,
                            ur_error *error)
{
    double length = ur_vec3_length(direction);
    if (!(length > 0) || !isfinite(length))
        return refuse(ruled, curve, error, "the cylinder's direction must be a non-zero vector");
    if (!(height > 0) || !isfinite(height))
        return refuse(ruled, curve, error, "the cylinder's height must be positive");
    take_curve(ruled, UR_RULED_CYLINDER, curve);
    ruled->direction = ur_vec3_scale(direction, 1.0 / length);
    ruled->height = height;
    return UR_OK;
}

ur_status ur_ruled_cone(ur_curve *curve, ur_vec3 apex, double cut, ur_ruled *ruled, ur_error *error)
{
    if (!isfinite(apex.x) || !isfinite(apex.y) || !isfinite(apex.z))
        return refuse(ruled, curve, error, "the cone's apex must be a finite point");
    if (!(cut != 0) || !(cut <= 1) || !isfinite(cut))
        return refuse(ruled, curve, error,
                      "the cone's cut must be at most 1 and not 0 (negative keeps the "
                      "rulings beyond the base, away from the apex)");
    take_curve(ruled, UR_RULED_CONE, curve);
    ruled->apex = apex;
    ruled->cut = cut;
    return UR_OK;
}

ur_status ur_ruled_tangent(ur_curve *curve, double offset, double width, ur_ruled *ruled,
                           ur_error *error)
{
    if (!(offset >= 0) || !isfinite(offset))
        return refuse(ruled, curve, error, "the offset must be zero or positive");
    if (!(width > 0) || !isfinite(width))
        return refuse(ruled, curve, error, "the width must be positive");
    take_curve(ruled, UR_RULED_TANGENT, curve);
    ruled->offset = offset;
    ruled->width = width;
    return UR_OK;
}

void ur_ruled_free(ur_ruled *ruled)
{
    if (ruled) {
        ur_curve_free(ruled->curve);
        ruled->curve = NULL;
    }
}

double ur_ruled_start(const ur_ruled *ruled)
{
    return ur_curve_start(ruled->curve);
}

double ur_ruled_end(const ur_ruled *ruled)
{
    return ur_curve_end(ruled->curve);
}

bool ur_ruled_is_closed(const ur_ruled *ruled)
{
    return ur_curve_is_closed(ruled->curve);
}

/* Unit tangent t = c'/|c'| and its derivative t' = (c'' - (c''.t) t) / |c'|. */
static void unit_tangent(const ur_vec3 d[3], ur_vec3 *tangent, ur_vec3 *tangent_derivative)
{
    double speed = ur_vec3_length(d[1]);
    *tangent = ur_vec3_scale(d[1], 1.0 / speed);
    ur_vec3 normal_part = ur_vec3_add_scaled(d[2], *tangent, -ur_vec3_dot(d[2], *tangent));
    *tangent_derivative = ur_vec3_scale(normal_part, 1.0 / speed);
}

void ur_ruled_rails(ur_ruled *ruled, double u, ur_vec3 rails[4])
{
    ur_vec3 d[3];
    ur_curve_eval(ruled->curve, u, d);
    switch (ruled->kind) {
    case UR_RULED_CYLINDER:
        rails[0] = d[0];
        rails[1] = d[1];
        rails[2] = ur_vec3_add_scaled(d[0], ruled->direction, ruled->height);
        rails[3] = d[1];
        break;
    case UR_RULED_CONE:
        rails[0] = d[0];
        rails[1] = d[1];
        rails[2] = ur_vec3_add_scaled(d[0], ur_vec3_sub(ruled->apex, d[0]), ruled->cut);
        rails[3] = ur_vec3_scale(d[1], 1.0 - ruled->cut);
        break;
    case UR_RULED_TANGENT: {
        ur_vec3 t, dt;
        unit_tangent(d, &t, &dt);
        double far = ruled->offset + ruled->width;
        rails[0] = ur_vec3_add_scaled(d[0], t, ruled->offset);
        rails[1] = ur_vec3_add_scaled(d[1], dt, ruled->offset);
        rails[2] = ur_vec3_add_scaled(d[0], t, far);
        rails[3] = ur_vec3_add_scaled(d[1], dt, far);
        break;
    }
    }
}

/*
 * For cylinders and cones the base curve is rail a and the tangent plane is
 * spanned by c' and the ruling e; its normal n = c' x e orients it, so the
 * ruling lies at an angle in (0, pi) to the left of c'.  For a tangent
 * developable the tangent plane is the osculating plane of the edge of
 * regression, so its geodesic curvature is its whole curvature and the
 * ruling is its tangent.
 */
void ur_ruled_intrinsics(ur_ruled *ruled, double u, ur_ruling_intrinsics *out)
{
    ur_vec3 d[3];
    ur_curve_eval(ruled->curve, u, d);
    double speed = ur_vec3_length(d[1]);
    out->speed = speed;
    if (ruled->kind == UR_RULED_TANGENT) {
        out->geodesic_curvature =
            ur_vec3_length(ur_vec3_cross(d[1], d[2])) / (speed * speed * speed);
        out->angle = 0.0;
        out->near = ruled->offset;
        out->far = ruled->offset + ruled->width;
        return;
    }
    ur_vec3 rails[4];
    ur_ruled_rails(ruled, u, rails);
    ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]);
    double length = ur_vec3_length(ruling);
    ur_vec3 e = ur_vec3_scale(ruling, 1.0 / length);
    ur_vec3 t = ur_vec3_scale(d[1], 1.0 / speed);
    ur_vec3 n = ur_vec3_cross(t, e);
    n = ur_vec3_scale(n, 1.0 / ur_vec3_length(n));
    ur_vec3 left = ur_vec3_cross(n, t);
    out->geodesic_curvature = ur_vec3_dot(d[2], left) / (speed * speed);
    out->angle = atan2(ur_vec3_dot(e, left), ur_vec3_dot(e, t));
    out->near = 0.0;
    out->far = length;
}

/* Where, in words the user can find: input point and arc length. */
static void describe_place(ur_ruled *ruled, double u, char *text, size_t size)
{
    ur_vec3 d[3];
    ur_curve_eval(ruled->curve, u, d);
    double arc = 0.0;
    ur_curve_length(ruled->curve, ur_curve_start(ruled->curve), u, &arc, NULL);
    size_t points = ur_curve_point_count(ruled->curve);
    size_t nearest = 0;
    for (size_t i = 1; i < points; i++)
        if (fabs(ur_curve_point_parameter(ruled->curve, i) - u) <
            fabs(ur_curve_point_parameter(ruled->curve, nearest) - u))
            nearest = i;
    if (points > 0)
        snprintf(text, size, "near point %zu (%.4g, %.4g, %.4g), %.4g mm along the curve",
                 nearest + 1, d[0].x, d[0].y, d[0].z, arc);
    else
        snprintf(text, size, "at (%.4g, %.4g, %.4g), %.4g mm along the curve", d[0].x, d[0].y,
                 d[0].z, arc);
}

enum { CHECK_SAMPLES = 4000 };

static ur_status check_tangent(ur_ruled *ruled, ur_error *error)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    ur_vec3 previous_binormal = {0, 0, 0};
    for (int i = 0; i <= CHECK_SAMPLES; i++) {
        double u = u0 + (u1 - u0) * i / CHECK_SAMPLES;
        ur_vec3 d[3];
        ur_curve_eval(ruled->curve, u, d);
        ur_vec3 binormal = ur_vec3_cross(d[1], d[2]);
        double speed = ur_vec3_length(d[1]);
        double curvature = ur_vec3_length(binormal) / (speed * speed * speed);
        bool flat = curvature * (speed * (u1 - u0)) < 1e-9;
        if (flat || ur_vec3_dot(binormal, previous_binormal) < 0) {
            char place[256];
            describe_place(ruled, u, place, sizeof place);
            return ur_error_set(
                error, UR_ERROR_INPUT,
                "the edge of regression has an inflection (curvature zero) %s: there its "
                "osculating plane turns over and consecutive tangents no longer meet, so the "
                "tangent developable is singular (it folds back along that tangent); split the "
                "curve there or change its shape so it bends one way only",
                place);
        }
        previous_binormal = binormal;
    }
    return UR_OK;
}

/* Cylinders and cones: the ruling must never run along the base curve. */
static ur_status check_ruling_across(ur_ruled *ruled, ur_error *error)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    for (int i = 0; i <= CHECK_SAMPLES; i++) {
        double u = u0 + (u1 - u0) * i / CHECK_SAMPLES;
        ur_vec3 rails[4];
        ur_ruled_rails(ruled, u, rails);
        ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]);
        double length = ur_vec3_length(ruling);
        double sine =
            ur_vec3_length(ur_vec3_cross(rails[1], ruling)) / (ur_vec3_length(rails[1]) * length);
        if (!(length > 1e-9) || !(sine > 1e-6)) {
            char place[256];
            describe_place(ruled, u, place, sizeof place);
            return ur_error_set(error, UR_ERROR_INPUT,
                                ruled->kind == UR_RULED_CONE
                                    ? "the base curve heads straight for the apex %s: the cone "
                                      "has no width there"
                                    : "the base curve runs along the cylinder's direction %s: "
                                      "the cylinder has no width there",
                                place);
        }
    }
    return UR_OK;
}

ur_status ur_ruled_check(ur_ruled *ruled, ur_error *error)
{
    if (ruled->kind == UR_RULED_TANGENT)
        return check_tangent(ruled, error);
    return check_ruling_across(ruled, error);
}

/* ---- Quadrature over the smooth pieces of the surface ------------------- */

enum { QUADRATURE_LIMIT = 2000 };

/*
 * An interpolated curve's third derivative jumps at its points, so anything
 * built on its curvature has kinks there.  Integrating knot to knot keeps
 * every piece smooth, and Gauss-Kronrod converges fast on each.
 */
static ur_status integrate_pieces(ur_curve *curve, gsl_function *f, double u_start, double u_end,
                                  double relative, double *result, ur_error *error)
{
    gsl_integration_workspace *workspace = gsl_integration_workspace_alloc(QUADRATURE_LIMIT);
    if (!workspace)
        return ur_error_out_of_memory(error);
    size_t points = ur_curve_point_count(curve);
    double from = u_start, total = 0.0, total_estimate = 0.0;
    int failure = 0;
    for (size_t i = 0; i <= points && !failure; i++) {
        double to = i < points ? ur_curve_point_parameter(curve, i) : u_end;
        if (to <= from)
            continue;
        to = fmin(to, u_end);
        double value, estimate;
        int code = gsl_integration_qag(f, from, to, 0.0, relative, QUADRATURE_LIMIT,
                                       GSL_INTEG_GAUSS41, workspace, &value, &estimate);
        if (code && !(estimate <= 1e3 * relative * fabs(value) + 1e-12))
            failure = code;
        total += value;
        total_estimate += estimate;
        from = to;
        if (from >= u_end)
            break;
    }
    gsl_integration_workspace_free(workspace);
    *result = total;
    if (failure)
        return ur_error_set(error, UR_ERROR_INTERNAL, "quadrature did not converge: %s",
                            gsl_strerror(failure));
    (void)total_estimate;
    return UR_OK;
}

/* ---- Area by nested adaptive quadrature --------------------------------- */

typedef struct area_context {
    ur_vec3 base, slope; /* r_u x r_v = base + v slope along one ruling */
    ur_ruled *ruled;
    gsl_integration_workspace *inner;
    int failure;
} area_context;

static double cross_norm_at_v(double v, void *data)
{
    const area_context *context = data;
    return ur_vec3_length(ur_vec3_add_scaled(context->base, context->slope, v));
}

/* Integral over v of |r_u x r_v| at one u: r_u = a' + v (b' - a'), r_v = b - a. */
static double ruling_integral(double u, void *data)
{
    area_context *context = data;
    ur_vec3 rails[4];
    ur_ruled_rails(context->ruled, u, rails);
    ur_vec3 r_v = ur_vec3_sub(rails[2], rails[0]);
    context->base = ur_vec3_cross(rails[1], r_v);
    context->slope = ur_vec3_cross(ur_vec3_sub(rails[3], rails[1]), r_v);
    gsl_function f = {cross_norm_at_v, context};
    double value, estimate;
    int code = gsl_integration_qag(&f, 0.0, 1.0, 0.0, 1e-13, QUADRATURE_LIMIT, GSL_INTEG_GAUSS21,
                                   context->inner, &value, &estimate);
    if (code && !(estimate <= 1e-10 * fabs(value)))
        context->failure = code;
    return value;
}

ur_status ur_ruled_area(ur_ruled *ruled, double u_start, double u_end, double *area,
                        ur_error *error)
{
    area_context context = {.ruled = ruled};
    context.inner = gsl_integration_workspace_alloc(QUADRATURE_LIMIT);
    if (!context.inner)
        return ur_error_out_of_memory(error);
    gsl_function f = {ruling_integral, &context};
    ur_status status = integrate_pieces(ruled->curve, &f, u_start, u_end, 1e-11, area, error);
    gsl_integration_workspace_free(context.inner);
    if (status == UR_OK && context.failure)
        status = ur_error_set(error, UR_ERROR_INTERNAL, "surface area did not converge: %s",
                              gsl_strerror(context.failure));
    return status;
}

typedef struct rail_context {
    ur_ruled *ruled;
    int rail;
} rail_context;

static double rail_speed(double u, void *data)
{
    const rail_context *context = data;
    ur_vec3 rails[4];
    ur_ruled_rails(context->ruled, u, rails);
    return ur_vec3_length(rails[context->rail == 0 ? 1 : 3]);
}

ur_status ur_ruled_rail_length(ur_ruled *ruled, int rail, double u_start, double u_end,
                               double *length, ur_error *error)
{
    rail_context context = {ruled, rail};
    gsl_function f = {rail_speed, &context};
    return integrate_pieces(ruled->curve, &f, u_start, u_end, 1e-12, length, error);
}
