/*
 * ruled.c: ruled surfaces (cylinder, cone, tangent developable, and the
 * two-rail kinds of strip.c): their rails, the intrinsic quantities the
 * development needs, the developability residual and edge of regression, a
 * regularity check, the domain in use, and the 3D area by quadrature.
 */
#include "surface_internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <stdio.h>
#include <string.h>
#include "../base/c_locale.h"
#include "../base/gsl_errors.h"

static ur_status take_curve(ur_ruled *ruled, ur_ruled_kind kind, ur_curve *curve)
{
    memset(ruled, 0, sizeof *ruled);
    ruled->kind = kind;
    ruled->curve = curve;
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
        ur_curve_free(ruled->rail2);
        pairing_free(ruled->pairing);
        ruled->curve = ruled->rail2 = NULL;
        ruled->pairing = NULL;
    }
}

double ur_ruled_start(const ur_ruled *ruled)
{
    return ruled->restricted ? ruled->u_min : ur_curve_start(ruled->curve);
}

double ur_ruled_end(const ur_ruled *ruled)
{
    return ruled->restricted ? ruled->u_max : ur_curve_end(ruled->curve);
}

static bool two_rails(const ur_ruled *ruled)
{
    return ruled->kind == UR_RULED_STRIP || ruled->kind == UR_RULED_GENERAL;
}

/*
 * A two-rail surface closes when both rails do and the pairing runs once
 * round rail 2, so that the last ruling is the first.
 */
bool ur_ruled_is_closed(const ur_ruled *ruled)
{
    if (ruled->restricted || !ur_curve_is_closed(ruled->curve))
        return false;
    if (!two_rails(ruled))
        return true;
    const ur_interval *gaps;
    if (!ur_curve_is_closed(ruled->rail2) || ur_ruled_gaps(ruled, &gaps) > 0)
        return false;
    double sigma0, sigma1, slope;
    ur_ruled_pairing((ur_ruled *)ruled, ur_curve_start(ruled->curve), &sigma0, &slope);
    ur_ruled_pairing((ur_ruled *)ruled, ur_curve_end(ruled->curve), &sigma1, &slope);
    double period = ur_curve_end(ruled->rail2) - ur_curve_start(ruled->rail2);
    return fabs(fabs(sigma1 - sigma0) - period) <= 1e-9 * period;
}

void ur_ruled_restrict(ur_ruled *ruled, double u_start, double u_end)
{
    ruled->restricted = true;
    ruled->u_min = fmax(u_start, ur_curve_start(ruled->curve));
    ruled->u_max = fmin(u_end, ur_curve_end(ruled->curve));
}

void ur_ruled_pairing(ur_ruled *ruled, double u, double *sigma, double *slope)
{
    if (two_rails(ruled)) {
        pairing_eval(ruled->pairing, u, ur_ruled_start(ruled), ur_ruled_end(ruled), sigma, slope);
    } else {
        *sigma = u;
        *slope = 1.0;
    }
}

size_t ur_ruled_gaps(const ur_ruled *ruled, const ur_interval **gaps)
{
    *gaps = NULL;
    return two_rails(ruled) ? pairing_gaps(ruled->pairing, gaps) : 0;
}

size_t ur_ruled_domain(ur_ruled *ruled, ur_interval *parts, size_t capacity)
{
    const ur_interval *gaps;
    size_t gap_count = ur_ruled_gaps(ruled, &gaps), count = 0;
    double from = ur_curve_start(ruled->curve), end = ur_curve_end(ruled->curve);
    double close = 1e-12 * (end - from);
    for (size_t k = 0; k <= gap_count; k++) {
        double to = k < gap_count ? gaps[k].u_start : end;
        if (to - from > close) {
            if (count < capacity) {
                memset(&parts[count], 0, sizeof parts[count]);
                parts[count].u_start = from;
                parts[count].u_end = to;
                ur_ruled_describe_interval(ruled, &parts[count]);
            }
            count++;
        }
        if (k < gap_count)
            from = gaps[k].u_end;
    }
    return count;
}

void ur_ruled_describe_interval(ur_ruled *ruled, ur_interval *interval)
{
    double u0 = ur_curve_start(ruled->curve);
    ur_vec3 d[3];
    interval->arc_start = interval->arc_end = 0.0;
    ur_curve_length(ruled->curve, u0, interval->u_start, &interval->arc_start, NULL);
    ur_curve_length(ruled->curve, u0, interval->u_end, &interval->arc_end, NULL);
    ur_curve_eval(ruled->curve, interval->u_start, d);
    interval->start = d[0];
    ur_curve_eval(ruled->curve, interval->u_end, d);
    interval->end = d[0];
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
    case UR_RULED_STRIP:
    case UR_RULED_GENERAL: {
        double sigma, slope;
        ur_vec3 d2[3];
        pairing_eval(ruled->pairing, u, ur_ruled_start(ruled), ur_ruled_end(ruled), &sigma, &slope);
        pairing_rail2(ruled->pairing, sigma, d2);
        rails[0] = d[0];
        rails[1] = d[1];
        rails[2] = d2[0];
        rails[3] = ur_vec3_scale(d2[1], slope);
        break;
    }
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
void describe_place(ur_ruled *ruled, double u, char *text, size_t size)
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
        c_snprintf(text, size, "near point %zu (%.4g, %.4g, %.4g), %.4g mm along the curve",
                   nearest + 1, d[0].x, d[0].y, d[0].z, arc);
    else
        c_snprintf(text, size, "at (%.4g, %.4g, %.4g), %.4g mm along the curve", d[0].x, d[0].y,
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
            const char *why =
                ruled->kind == UR_RULED_CONE
                    ? "the base curve heads straight for the apex %s: the cone has no width there"
                : ruled->kind == UR_RULED_CYLINDER
                    ? "the base curve runs along the cylinder's direction %s: the cylinder has no "
                      "width there"
                    : "the rails meet, or rail 1 runs along the ruling, %s: the surface has no "
                      "width there";
            return ur_error_set(error, UR_ERROR_INPUT, why, place);
        }
    }
    return UR_OK;
}

const ur_interval *ruled_gap_in_use(ur_ruled *ruled)
{
    const ur_interval *gaps;
    size_t count = ur_ruled_gaps(ruled, &gaps);
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    double close = 1e-9 * (ur_curve_end(ruled->curve) - ur_curve_start(ruled->curve));
    for (size_t k = 0; k < count; k++)
        if (gaps[k].u_end > u0 + close && gaps[k].u_start < u1 - close)
            return &gaps[k];
    return NULL;
}

/* A strip may be developed only where it exists. */
static ur_status check_domain(ur_ruled *ruled, ur_error *error)
{
    const ur_interval *gap = ruled_gap_in_use(ruled);
    if (gap)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the strip does not exist from %.6g to %.6g mm along rail 1 (%s); "
                            "develop the parts of its domain of existence separately",
                            gap->arc_start, gap->arc_end,
                            gap->reason == UR_GAP_NO_RULING ? "no ruling" : "rulings cross");
    return UR_OK;
}

enum { RESIDUAL_SAMPLES = 2000 };

/* The largest developability residual over the part in use, and where. */
static double largest_residual(ur_ruled *ruled, double *where)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled), largest = 0.0;
    *where = u0;
    for (int i = 0; i <= RESIDUAL_SAMPLES; i++) {
        double u = u0 + (u1 - u0) * i / RESIDUAL_SAMPLES;
        double residual = ur_ruled_residual(ruled, u);
        if (!(residual <= largest)) {
            largest = residual;
            *where = u;
        }
    }
    return largest;
}

/* A general ruled surface is developed only when it happens to be developable. */
static ur_status check_developable(ur_ruled *ruled, ur_error *error)
{
    double where;
    double residual = largest_residual(ruled, &where);
    if (residual <= UR_DEVELOPABLE_RESIDUAL)
        return UR_OK;
    char place[256];
    describe_place(ruled, where, place, sizeof place);
    return ur_error_set(error, UR_ERROR_INPUT,
                        "the surface is not developable: its tangent plane turns by up to %.3g "
                        "degrees along a ruling (%s), so no flat net fits it without strain",
                        residual * 180 / M_PI, place);
}

ur_status ur_ruled_check(ur_ruled *ruled, ur_error *error)
{
    if (ruled->kind == UR_RULED_TANGENT)
        return check_tangent(ruled, error);
    ur_status status = check_ruling_across(ruled, error);
    if (status == UR_OK && ruled->kind == UR_RULED_STRIP)
        status = check_domain(ruled, error);
    if (status == UR_OK && ruled->kind == UR_RULED_GENERAL)
        status = check_developable(ruled, error);
    return status;
}

/* ---- Developability and the edge of regression -------------------------- */

/*
 * The tangent plane along a ruling is spanned by the ruling g = b - a and
 * r_u, which runs from a' at v = 0 to b' at v = 1.  On a developable the
 * normals a' x g and b' x g are parallel (det(a', b', g) = 0); the angle
 * between them is how far from developable the ruling is.  Where one of
 * them vanishes (a cone's apex, a tangent developable's edge of regression)
 * the plane is undefined there, and the middle of the ruling stands in.
 */
double ur_ruled_residual(ur_ruled *ruled, double u)
{
    ur_vec3 rails[4];
    ur_ruled_rails(ruled, u, rails);
    ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]);
    /* The normal (a' + v (b' - a')) x g at v = 0, 1 and 1/2, where it is defined. */
    ur_vec3 normals[2];
    int found = 0;
    const double at[3] = {0.0, 1.0, 0.5};
    for (int k = 0; k < 3 && found < 2; k++) {
        ur_vec3 r_u = ur_vec3_add_scaled(rails[1], ur_vec3_sub(rails[3], rails[1]), at[k]);
        ur_vec3 normal = ur_vec3_cross(r_u, ruling);
        double size = ur_vec3_length(r_u) * ur_vec3_length(ruling);
        if (ur_vec3_length(normal) > 1e-9 * size)
            normals[found++] = normal;
    }
    if (found < 2)
        return 0.0;
    double sine = ur_vec3_length(ur_vec3_cross(normals[0], normals[1]));
    double cosine = fabs(ur_vec3_dot(normals[0], normals[1]));
    return atan2(sine, cosine);
}

/*
 * With e the unit ruling direction, neighbouring rulings come closest at
 * distance w = -(a' . e') / |e'|^2 from a along e (the striction point); on
 * a developable they meet there, on the edge of regression.
 */
bool ur_ruled_regression(ur_ruled *ruled, double u, ur_vec3 *point, double *v)
{
    ur_vec3 rails[4];
    ur_ruled_rails(ruled, u, rails);
    ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]);
    double length = ur_vec3_length(ruling);
    ur_vec3 e = ur_vec3_scale(ruling, 1.0 / length);
    ur_vec3 change = ur_vec3_sub(rails[3], rails[1]);
    ur_vec3 e_prime =
        ur_vec3_scale(ur_vec3_add_scaled(change, e, -ur_vec3_dot(change, e)), 1.0 / length);
    double turning = ur_vec3_dot(e_prime, e_prime);
    /*
     * Rulings that turn by less than 1e-8 of a' per ruling length meet more
     * than 1e8 ruling lengths away: parallel, as on a cylinder, up to the
     * rounding of a pairing solved near a double root.
     */
    if (!(turning > 1e-16 * ur_vec3_dot(rails[1], rails[1]) / (length * length)))
        return false;
    double w = -ur_vec3_dot(rails[1], e_prime) / turning;
    *point = ur_vec3_add_scaled(rails[0], e, w);
    *v = w / length;
    return isfinite(w);
}

/* ---- Quadrature over the smooth pieces of the surface ------------------- */

enum { QUADRATURE_LIMIT = 2000, BREAK_STEPS = 60 };

/*
 * The first knot of a curve after s, of whichever turn of a closed curve s
 * is in; INFINITY when there is none (an analytic curve has no knots).
 */
static double knot_after(const ur_curve *curve, double s)
{
    size_t n = ur_curve_point_count(curve);
    if (n == 0)
        return INFINITY;
    double shift = 0.0, start = ur_curve_start(curve), end = ur_curve_end(curve);
    if (ur_curve_is_closed(curve) && !(s >= start && s < end)) {
        shift = (end - start) * floor((s - start) / (end - start));
        s -= shift;
    }
    size_t low = 0, high = n; /* the first knot above s is in [low, high] */
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        if (ur_curve_point_parameter(curve, middle) > s)
            high = middle;
        else
            low = middle + 1;
    }
    if (low < n)
        return ur_curve_point_parameter(curve, low) + shift;
    return ur_curve_is_closed(curve) ? end + shift : INFINITY;
}

/*
 * The u in (low, high) where the pairing reaches sigma = target, given that
 * it runs from below target at low to above it at high: Newton's method on
 * the pairing and its slope, kept inside the bracket by bisection.
 */
static double pairing_reaches(ur_ruled *ruled, double target, double low, double high)
{
    double u = 0.5 * (low + high), tolerance = 1e-9 * (high - low);
    for (int k = 0; k < BREAK_STEPS; k++) {
        double sigma, slope;
        ur_ruled_pairing(ruled, u, &sigma, &slope);
        if (sigma < target)
            low = u;
        else
            high = u;
        double next = u - (sigma - target) / slope;
        if (!(next > low && next < high))
            next = 0.5 * (low + high);
        if (fabs(next - u) <= tolerance)
            return next;
        u = next;
    }
    return u;
}

/*
 * The developable kinds are smooth between the break points below, and
 * |r_u x r_v| is linear in v along each of their rulings, so 15-point rules
 * meet the tolerances on each piece at once.  A general surface's pairing (a
 * Steffen interpolant) has kinks at each of its own samples besides, and its
 * |r_u x r_v| curves along a ruling: it keeps 41 and 21 points.
 */
static int quadrature_rule(const ur_ruled *ruled, bool along_ruling)
{
    if (ruled->kind != UR_RULED_GENERAL)
        return GSL_INTEG_GAUSS15;
    return along_ruling ? GSL_INTEG_GAUSS21 : GSL_INTEG_GAUSS41;
}

typedef struct quadrature {
    ur_ruled *ruled;
    gsl_function *f;
    bool through_rail2; /* f uses rail 2 of a two-rail surface */
    double relative;
    int rule;
    gsl_integration_workspace *workspace;
    double total;
    int failure;
} quadrature;

static void integrate_piece(quadrature *q, double from, double to)
{
    double value, estimate;
    int code = gsl_integration_qag(q->f, from, to, 0.0, q->relative, QUADRATURE_LIMIT, q->rule,
                                   q->workspace, &value, &estimate);
    /*
     * GSL gives up (roundoff) long before an error that matters here:
     * areas and lengths are reported to about 1e-7.
     */
    if (code && !(estimate <= 1e-7 * fabs(value) + 1e-12))
        q->failure = code;
    q->total += value;
}

/*
 * [from, to] lies between two knots of rail 1; through the pairing, rail 2's
 * knots put kinks in it too, where sigma reaches them.  sigma is the pairing
 * at from on entry and at to on return.
 */
static void integrate_between_knots(quadrature *q, double from, double to, double *sigma)
{
    if (!q->through_rail2) {
        integrate_piece(q, from, to);
        return;
    }
    double sigma_to, slope;
    ur_ruled_pairing(q->ruled, to, &sigma_to, &slope);
    for (double knot = knot_after(q->ruled->rail2, *sigma); knot < sigma_to && !q->failure;) {
        double at = pairing_reaches(q->ruled, knot, from, to);
        integrate_piece(q, from, at);
        from = at;
        double next = knot_after(q->ruled->rail2, knot);
        if (!(next > knot))
            break; /* rounding at a turn of a closed rail 2: leave the rest whole */
        knot = next;
    }
    integrate_piece(q, from, to);
    *sigma = sigma_to;
}

/*
 * An interpolated curve's third derivative jumps at its points, so anything
 * built on its curvature has kinks there, and Gauss-Kronrod, which converges
 * fast on a smooth piece, has to subdivide again and again around a kink.
 * So the integral runs from kink to kink: the knots of rail 1 and, when the
 * integrand goes through the pairing, where it reaches the knots of rail 2.
 */
static ur_status integrate_pieces(ur_ruled *ruled, gsl_function *f, bool through_rail2,
                                  double u_start, double u_end, double relative, double *result,
                                  ur_error *error)
{
    quadrature q = {.ruled = ruled,
                    .f = f,
                    .through_rail2 = through_rail2 && two_rails(ruled),
                    .relative = relative,
                    .rule = quadrature_rule(ruled, false)};
    gsl_errors_off();
    q.workspace = gsl_integration_workspace_alloc(QUADRATURE_LIMIT);
    if (!q.workspace) {
        gsl_errors_restore();
        return ur_error_out_of_memory(error);
    }
    double sigma = 0.0, slope;
    if (q.through_rail2)
        ur_ruled_pairing(ruled, u_start, &sigma, &slope);
    for (double from = u_start; from < u_end && !q.failure;) {
        double to = knot_after(ruled->curve, from);
        if (!(to > from) || to > u_end)
            to = u_end;
        integrate_between_knots(&q, from, to, &sigma);
        from = to;
    }
    gsl_integration_workspace_free(q.workspace);
    gsl_errors_restore();
    *result = q.total;
    if (q.failure)
        return ur_error_set(error, UR_ERROR_INTERNAL, "quadrature did not converge: %s",
                            gsl_strerror(q.failure));
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
    int code = gsl_integration_qag(&f, 0.0, 1.0, 0.0, 1e-13, QUADRATURE_LIMIT,
                                   quadrature_rule(context->ruled, true), context->inner, &value,
                                   &estimate);
    if (code && !(estimate <= 1e-10 * fabs(value)))
        context->failure = code;
    return value;
}

ur_status ur_ruled_area(ur_ruled *ruled, double u_start, double u_end, double *area,
                        ur_error *error)
{
    area_context context = {.ruled = ruled};
    gsl_errors_off();
    context.inner = gsl_integration_workspace_alloc(QUADRATURE_LIMIT);
    gsl_errors_restore();
    if (!context.inner)
        return ur_error_out_of_memory(error);
    gsl_function f = {ruling_integral, &context};
    ur_status status = integrate_pieces(ruled, &f, true, u_start, u_end, 1e-11, area, error);
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
    if (context->rail == 0 && two_rails(context->ruled)) {
        ur_curve_eval(context->ruled->curve, u, rails); /* rail a is rail 1: no pairing needed */
        return ur_vec3_length(rails[1]);
    }
    ur_ruled_rails(context->ruled, u, rails);
    return ur_vec3_length(rails[context->rail == 0 ? 1 : 3]);
}

ur_status ur_ruled_rail_length(ur_ruled *ruled, int rail, double u_start, double u_end,
                               double *length, ur_error *error)
{
    rail_context context = {ruled, rail};
    gsl_function f = {rail_speed, &context};
    return integrate_pieces(ruled, &f, rail == 1, u_start, u_end, 1e-12, length, error);
}
