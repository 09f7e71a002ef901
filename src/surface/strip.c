/*
 * strip.c: ruled surfaces on two rails, b(u) = c2(sigma(u)): building them
 * and answering sigma(u).
 *
 * A developable strip solves its pairing (tracking.c); a general ruled
 * surface takes it from the rails' arc lengths or input points instead,
 * through GSL's monotone Steffen interpolation.
 */
#include "pairing.h"
#include "surface_internal.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <string.h>
#include "../base/gsl_errors.h"

/* Samples of a pairing by arc length. */
enum { ARC_SAMPLES = 4096 };

double determinant3(ur_vec3 x, ur_vec3 y, ur_vec3 z)
{
    return ur_vec3_dot(x, ur_vec3_cross(y, z));
}

void pairing_rail2(ur_pairing *pairing, double sigma, ur_vec3 d[3])
{
    ur_curve_eval(pairing->rail2, sigma, d);
}

void pairing_free(ur_pairing *pairing)
{
    if (!pairing)
        return;
    free(pairing->u);
    free(pairing->sigma);
    free(pairing->slope);
    free(pairing->state);
    free(pairing->joined);
    free(pairing->bridged);
    free(pairing->scan_position);
    free(pairing->scan_tangent);
    free(pairing->gaps);
    if (pairing->interp)
        gsl_interp_free(pairing->interp);
    if (pairing->accel)
        gsl_interp_accel_free(pairing->accel);
    if (pairing->solver)
        gsl_root_fsolver_free(pairing->solver);
    free(pairing);
}

size_t pairing_gaps(const ur_pairing *pairing, const ur_interval **gaps)
{
    *gaps = pairing->gaps;
    return pairing->gap_count;
}

void pairing_eval(ur_pairing *pairing, double u, double low, double high, double *sigma,
                  double *slope)
{
    if (!pairing->solved) {
        gsl_errors_off(); /* u outside the table: NaN, not an abort */
        *sigma = gsl_interp_eval(pairing->interp, pairing->u, pairing->sigma, u, pairing->accel);
        *slope =
            gsl_interp_eval_deriv(pairing->interp, pairing->u, pairing->sigma, u, pairing->accel);
        gsl_errors_restore();
        return;
    }
    ur_vec3 c1[3], d2[3];
    ur_curve_eval(pairing->rail1, u, c1);
    bool on_table;
    *sigma = pairing_solved_sigma(pairing, u, low, high, c1, &on_table);
    pairing_rail2(pairing, *sigma, d2);
    *slope = pairing_solved_slope(pairing, u, c1, d2, on_table);
}

/* ---- Building the surfaces ---------------------------------------------- */

static ur_pairing *pairing_new(ur_curve *rail1, ur_curve *rail2, ur_error *error)
{
    ur_pairing *pairing = calloc(1, sizeof *pairing);
    if (!pairing) {
        ur_error_out_of_memory(error);
        return NULL;
    }
    pairing->rail1 = rail1;
    pairing->rail2 = rail2;
    pairing->s0 = ur_curve_start(rail2);
    pairing->s1 = ur_curve_end(rail2);
    pairing->wrap = ur_curve_is_closed(rail2);
    pairing->end_slack = ROUNDING;
    return pairing;
}

static ur_status take_rails(ur_curve *rail1, ur_curve *rail2, ur_ruled_kind kind, ur_ruled *ruled,
                            ur_error *error)
{
    memset(ruled, 0, sizeof *ruled);
    ruled->kind = kind;
    ruled->curve = rail1;
    ruled->rail2 = rail2;
    if (!rail1 || !rail2) {
        ur_ruled_free(ruled);
        return ur_error_set(error, UR_ERROR_INPUT, "a ruled surface needs two rails");
    }
    ruled->pairing = pairing_new(rail1, rail2, error);
    if (!ruled->pairing) {
        ur_ruled_free(ruled);
        return UR_ERROR_MEMORY;
    }
    return UR_OK;
}

/* Cumulative arc length of a curve at `count` equally spaced parameters. */
static ur_status arc_table(ur_curve *curve, size_t count, double *parameters, double *lengths,
                           ur_error *error)
{
    double u0 = ur_curve_start(curve), u1 = ur_curve_end(curve);
    lengths[0] = 0.0;
    parameters[0] = u0;
    for (size_t i = 1; i < count; i++) {
        parameters[i] = u0 + (u1 - u0) * (double)i / (double)(count - 1);
        double piece;
        ur_status status = ur_curve_length(curve, parameters[i - 1], parameters[i], &piece, error);
        if (status != UR_OK)
            return status;
        lengths[i] = lengths[i - 1] + piece;
    }
    return UR_OK;
}

/* sigma at equal arc-length fractions, inverted by linear interpolation. */
static ur_status arc_length_pairing(ur_pairing *pairing, ur_error *error)
{
    size_t n = ARC_SAMPLES;
    double *s = ur_alloc_array(n, sizeof *s, error);
    double *length1 = ur_alloc_array(n, sizeof *length1, error);
    double *length2 = ur_alloc_array(n, sizeof *length2, error);
    ur_status status = s && length1 && length2 ? UR_OK : UR_ERROR_MEMORY;
    if (status == UR_OK)
        status = pairing_table_alloc(pairing, n, error);
    if (status == UR_OK)
        status = arc_table(pairing->rail1, n, pairing->u, length1, error);
    if (status == UR_OK)
        status = arc_table(pairing->rail2, n, s, length2, error);
    for (size_t i = 0, j = 0; status == UR_OK && i < n; i++) {
        double target = length1[i] / length1[n - 1] * length2[n - 1];
        while (j + 2 < n && length2[j + 1] < target)
            j++;
        double t = (target - length2[j]) / (length2[j + 1] - length2[j]);
        pairing->sigma[i] = s[j] + fmin(fmax(t, 0.0), 1.0) * (s[j + 1] - s[j]);
    }
    free(s);
    free(length1);
    free(length2);
    return status;
}

static ur_status point_pairing(ur_pairing *pairing, ur_error *error)
{
    size_t n = ur_curve_point_count(pairing->rail1);
    if (n < 3 || n != ur_curve_point_count(pairing->rail2))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "pairing by points needs two rails with the same number of points "
                            "(%zu and %zu)",
                            n, ur_curve_point_count(pairing->rail2));
    ur_status status =
        pairing_table_alloc(pairing, n + (ur_curve_is_closed(pairing->rail1) ? 1 : 0), error);
    for (size_t i = 0; status == UR_OK && i < pairing->count; i++) {
        pairing->u[i] =
            i < n ? ur_curve_point_parameter(pairing->rail1, i) : ur_curve_end(pairing->rail1);
        pairing->sigma[i] =
            i < n ? ur_curve_point_parameter(pairing->rail2, i) : ur_curve_end(pairing->rail2);
    }
    return status;
}

static ur_status interpolate_pairing(ur_pairing *pairing, ur_error *error)
{
    gsl_errors_off();
    pairing->interp = gsl_interp_alloc(gsl_interp_steffen, pairing->count);
    pairing->accel = gsl_interp_accel_alloc();
    bool made = pairing->interp && pairing->accel;
    int code = made ? gsl_interp_init(pairing->interp, pairing->u, pairing->sigma, pairing->count)
                    : GSL_ENOMEM;
    gsl_errors_restore();
    if (!made)
        return ur_error_out_of_memory(error);
    if (code != GSL_SUCCESS)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the rails' pairing is not monotonic (repeated points?)");
    for (size_t i = 0; i < pairing->count; i++)
        pairing->state[i] = SAMPLE_GOOD;
    return UR_OK;
}

ur_status ur_ruled_general(ur_curve *rail1, ur_curve *rail2, ur_pairing_rule rule, ur_ruled *ruled,
                           ur_error *error)
{
    ur_status status = take_rails(rail1, rail2, UR_RULED_GENERAL, ruled, error);
    if (status != UR_OK)
        return status;
    status = rule == UR_PAIR_POINTS ? point_pairing(ruled->pairing, error)
                                    : arc_length_pairing(ruled->pairing, error);
    if (status == UR_OK)
        status = interpolate_pairing(ruled->pairing, error);
    if (status != UR_OK)
        ur_ruled_free(ruled);
    return status;
}

/* Both rails in one plane: every pairing is developable and the condition vanishes. */
static bool rails_coplanar(ur_pairing *pairing)
{
    enum { PROBES = 64 };
    ur_vec3 points[2 * PROBES];
    for (int k = 0; k < PROBES; k++) {
        ur_vec3 d[3];
        ur_curve_eval(pairing->rail1,
                      ur_curve_start(pairing->rail1) +
                          (ur_curve_end(pairing->rail1) - ur_curve_start(pairing->rail1)) * k /
                              (PROBES - 1),
                      d);
        points[k] = d[0];
        pairing_rail2(pairing, pairing->s0 + (pairing->s1 - pairing->s0) * k / (PROBES - 1), d);
        points[PROBES + k] = d[0];
    }
    /* The plane through the first point and the two most independent directions. */
    ur_vec3 normal = {0, 0, 0};
    double size = 0.0;
    for (int k = 1; k < 2 * PROBES; k++)
        size = fmax(size, ur_vec3_distance(points[k], points[0]));
    for (int j = 1; j < 2 * PROBES; j++)
        for (int k = j + 1; k < 2 * PROBES; k += 7) {
            ur_vec3 n =
                ur_vec3_cross(ur_vec3_sub(points[j], points[0]), ur_vec3_sub(points[k], points[0]));
            if (ur_vec3_length(n) > ur_vec3_length(normal))
                normal = n;
        }
    double length = ur_vec3_length(normal);
    if (!(length > 1e-12 * size * size))
        return true;
    normal = ur_vec3_scale(normal, 1.0 / length);
    for (int k = 1; k < 2 * PROBES; k++)
        if (fabs(ur_vec3_dot(ur_vec3_sub(points[k], points[0]), normal)) > 1e-9 * size)
            return false;
    return true;
}

static ur_status solve_pairing(ur_ruled *ruled, ur_error *error)
{
    ur_pairing *pairing = ruled->pairing;
    ur_status status = pairing_track(pairing, error);
    for (size_t k = 0; status == UR_OK && k < pairing->gap_count; k++)
        ur_ruled_describe_interval(ruled, &pairing->gaps[k]);
    return status;
}

static bool covers_all(const ur_ruled *ruled)
{
    const ur_pairing *pairing = ruled->pairing;
    if (pairing->gap_count != 1)
        return false;
    const ur_interval *gap = &pairing->gaps[0];
    return gap->u_start <= pairing->u[0] && gap->u_end >= pairing->u[pairing->count - 1];
}

ur_status ur_ruled_strip(ur_curve *rail1, ur_curve *rail2, ur_ruled *ruled, ur_error *error)
{
    ur_status status = take_rails(rail1, rail2, UR_RULED_STRIP, ruled, error);
    if (status != UR_OK)
        return status;
    if (rails_coplanar(ruled->pairing)) {
        /* A plane: any pairing is developable; equal arc-length fractions is the natural one. */
        status = arc_length_pairing(ruled->pairing, error);
        if (status == UR_OK)
            status = interpolate_pairing(ruled->pairing, error);
    } else {
        status = solve_pairing(ruled, error);
        if (status == UR_OK && covers_all(ruled))
            status = ur_error_set(error, UR_ERROR_INPUT,
                                  "no developable strip exists anywhere between the rails: no "
                                  "plane touches both rails along a ruling (%s)",
                                  ruled->pairing->gaps[0].reason == UR_GAP_RULINGS_CROSS
                                      ? "every candidate ruling crosses its neighbours"
                                      : "no ruling reaches rail 2 from any point of rail 1");
    }
    if (status != UR_OK)
        ur_ruled_free(ruled);
    return status;
}

/* The strip between two rails given as points (surface_internal.h). */
ur_status surface_strip_of_points(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                                  size_t count2, ur_ruled *strip, ur_error *error)
{
    ur_curve *curves[2] = {NULL, NULL};
    ur_status status = ur_curve_new_interpolating(rail1, count1, false, &curves[0], error);
    if (status == UR_OK)
        status = ur_curve_new_interpolating(rail2, count2, false, &curves[1], error);
    if (status != UR_OK) {
        ur_curve_free(curves[0]);
        return status;
    }
    return ur_ruled_strip(curves[0], curves[1], strip, error);
}
