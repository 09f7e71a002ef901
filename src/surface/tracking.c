/*
 * tracking.c: solving the pairing of a developable strip between two rails.
 *
 * The pairing sigma(u) is the root of
 *     F(u, sigma) = det(c1'(u), c2'(sigma), c2(sigma) - c1(u)),
 * the condition that one plane touches the surface along the whole ruling.
 * A table of roots is built once by continuing the root along rail 1
 * (predict with the slope of the solution curve, correct by Newton's method,
 * a scan of the whole of rail 2 when that fails), then any u is answered by
 * Newton's method started from the table and falling back to GSL's Brent
 * solver on the table's bracket.  The slope follows from the implicit
 * function theorem: sigma' = -F_u / F_sigma with F_u = det(c1'', c2', d) and
 * F_sigma = det(c1', c2'', d), d = c2 - c1.
 *
 * Where the rails have inflections the condition has double roots: two
 * branches of solutions cross there (on a general cylinder, sigma = u and the
 * points whose tangent is the mirror image), both derivatives of F vanish and
 * the nearest root may lie on the other branch.  So the continuation looks at
 * both roots near the prediction and keeps the one whose slope continues the
 * slope it came with; at the double root itself, where -F_u / F_sigma is 0 / 0,
 * the slope comes from the neighbouring samples instead.  Rails of unlike
 * parametrisation are interpolated a little differently, and there the two
 * branches miss each other, each turning back: the pairing is carried over
 * the turn (bridge) and answered there from the table's interpolation.
 *
 * Where there is no root, where the root jumps to another branch, or where
 * consecutive rulings cross inside the strip (sigma decreasing, or the edge
 * of regression between the rails), rail 1 has a gap in the domain of
 * existence; gap ends are refined by bisection.
 */
#include "pairing.h"

#include <gsl/gsl_errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "../base/gsl_errors.h"

enum {
    MIN_SAMPLES = 2048,  /* rail 1 samples of the root table */
    MIN_SCAN = 2048,     /* rail 2 samples of a full scan */
    RESCAN_EVERY = 32,   /* inside a gap, scan all of rail 2 only this often */
    BISECTIONS = 48,     /* refinement of gap ends */
    NEWTON_STEPS = 64,   /* near a double root Newton's method only halves the error each step */
    BRIDGE_SAMPLES = 24, /* the farthest a branch is followed past roots that turn back */
    BRIDGE_MARGIN = 4,   /* samples kept off the turn on either side of a bridge */
};

/* The largest relative change of slope from one table sample to the next that continues it. */
#define SLOPE_CHANGE 0.2

/*
 * Both derivatives of F, per unit of the rails' parameter ranges, below this
 * fraction of F's natural size: at or next to a double root.  There F's
 * rounding moves the root by up to the square root of it (about 1e-8 of the
 * rail) and the implicit slope is 0 / 0; outside, Newton's root is good to
 * about 1e-10 of the rail and the implicit slope to about 1e-6.
 */
#define DOUBLE_ROOT 1e-3

/* The same, below which interpolation errors of the rails may move the root (near_double_root). */
#define NEAR_DOUBLE_ROOT 0.05

/* ---- The condition and its derivatives ---------------------------------- */

/* F at (u, sigma) for rail 1's derivatives c1 at u, and rail 2's d2 at sigma. */
static double condition(const ur_vec3 c1[3], const ur_vec3 d2[3])
{
    return determinant3(c1[1], d2[1], ur_vec3_sub(d2[0], c1[0]));
}

/* F divided by its natural size, so that tolerances mean the same at any scale. */
static double condition_scale(const ur_vec3 c1[3], const ur_vec3 d2[3])
{
    return ur_vec3_length(c1[1]) * ur_vec3_length(d2[1]) *
           fmax(ur_vec3_length(ur_vec3_sub(d2[0], c1[0])), 1e-300);
}

double pairing_implicit_slope(const ur_vec3 c1[3], const ur_vec3 d2[3])
{
    ur_vec3 d = ur_vec3_sub(d2[0], c1[0]);
    double f_u = determinant3(c1[2], d2[1], d);
    double f_sigma = determinant3(c1[1], d2[2], d);
    return -f_u / f_sigma;
}

/* Whether both derivatives of F at (c1, d2) are below `fraction` of F's natural size. */
static bool gradient_below(const ur_pairing *pairing, const ur_vec3 c1[3], const ur_vec3 d2[3],
                           double fraction)
{
    ur_vec3 d = ur_vec3_sub(d2[0], c1[0]);
    double f_u = determinant3(c1[2], d2[1], d), f_sigma = determinant3(c1[1], d2[2], d);
    double range1 = ur_curve_end(pairing->rail1) - ur_curve_start(pairing->rail1);
    double size = fraction * condition_scale(c1, d2);
    return fabs(f_u) * range1 <= size && fabs(f_sigma) * (pairing->s1 - pairing->s0) <= size;
}

/* Whether (c1, d2) is at or next to a double root: grad F nearly zero. */
static bool at_double_root(const ur_pairing *pairing, const ur_vec3 c1[3], const ur_vec3 d2[3])
{
    return gradient_below(pairing, c1, d2, DOUBLE_ROOT);
}

typedef struct root_context {
    ur_pairing *pairing;
    const ur_vec3 *c1;
} root_context;

static double condition_at(double sigma, void *data)
{
    const root_context *context = data;
    ur_vec3 d2[3];
    pairing_rail2(context->pairing, sigma, d2);
    return condition(context->c1, d2);
}

/* Roots a rounding error beyond rail 2's ends still count as on it. */
static bool in_rail2(const ur_pairing *pairing, double sigma)
{
    double slack = 1e-9 * (pairing->s1 - pairing->s0);
    return pairing->wrap || (sigma >= pairing->s0 - slack && sigma <= pairing->s1 + slack);
}

/*
 * Roots within the end slack past rail 2's ends (a ruling meant to end on an
 * end of rail 2 misses it by the interpolation error) count as on it.
 */
static bool near_rail2(const ur_pairing *pairing, double sigma)
{
    double slack = fmax(pairing->end_slack, 1e-9) * (pairing->s1 - pairing->s0);
    return pairing->wrap || (sigma >= pairing->s0 - slack && sigma <= pairing->s1 + slack);
}

/* Brent's method on a bracket with a sign change. */
static double brent_steps(ur_pairing *pairing, const ur_vec3 c1[3], double low, double high)
{
    root_context context = {pairing, c1};
    gsl_function f = {condition_at, &context};
    if (gsl_root_fsolver_set(pairing->solver, &f, low, high) != GSL_SUCCESS)
        return 0.5 * (low + high);
    double root = 0.5 * (low + high);
    double tolerance = 1e-15 * (fabs(pairing->s1) + fabs(pairing->s1 - pairing->s0));
    for (int k = 0; k < 200; k++) {
        if (gsl_root_fsolver_iterate(pairing->solver) != GSL_SUCCESS)
            break;
        root = gsl_root_fsolver_root(pairing->solver);
        low = gsl_root_fsolver_x_lower(pairing->solver);
        high = gsl_root_fsolver_x_upper(pairing->solver);
        if (gsl_root_test_interval(low, high, tolerance, 0.0) == GSL_SUCCESS)
            break;
    }
    return root;
}

static double brent(ur_pairing *pairing, const ur_vec3 c1[3], double low, double high)
{
    gsl_errors_off();
    double root = brent_steps(pairing, c1, low, high);
    gsl_errors_restore();
    return root;
}

/*
 * A root that falls on an end of an open rail 2 (within rounding) shows no
 * sign change inside the rail: extrapolate the condition linearly past the
 * end to see whether it vanishes there.
 */
static bool root_at_rail_end(ur_pairing *pairing, const ur_vec3 c1[3], double guess, double window,
                             double *root)
{
    if (pairing->wrap)
        return false;
    double ends[2] = {pairing->s0, pairing->s1}, inward[2] = {1, -1};
    for (int k = 0; k < 2; k++) {
        if (fabs(ends[k] - guess) > window)
            continue;
        root_context context = {pairing, c1};
        double h = pairing->step / 4;
        double at_end = condition_at(ends[k], &context);
        double inside = condition_at(ends[k] + inward[k] * h, &context);
        double crossing = at_end / (at_end - inside); /* in steps of h, inward */
        /*
         * Or the condition, in radians between the tangent planes at the
         * ruling's ends, nearly holds there: next to a double root a small
         * error of the interpolation moves the root a long way.
         */
        ur_vec3 d2[3];
        pairing_rail2(pairing, ends[k], d2);
        double angle = fabs(at_end) / condition_scale(c1, d2);
        if (fabs(crossing) * h <= pairing->end_slack * (pairing->s1 - pairing->s0) ||
            angle <= pairing->end_slack) {
            *root = ends[k];
            return true;
        }
    }
    return false;
}

/*
 * The root nearest to `guess` within `window`, stepping outward on both
 * sides.  A touching (double) root shows no sign change; it is accepted when
 * the condition nearly vanishes at a sample.
 */
static bool local_root(ur_pairing *pairing, const ur_vec3 c1[3], double guess, double window,
                       double *root)
{
    double step = fmin(pairing->step / 4, window);
    if (!pairing->wrap)
        guess = fmin(fmax(guess, pairing->s0), pairing->s1);
    ur_vec3 d2[3];
    pairing_rail2(pairing, guess, d2);
    double at_guess = condition(c1, d2);
    if (at_guess == 0.0 && in_rail2(pairing, guess)) {
        *root = guess;
        return true;
    }
    double best = fabs(at_guess) / condition_scale(c1, d2), best_sigma = guess;
    double before[2] = {at_guess, at_guess}, where[2] = {guess, guess};
    for (double offset = step; offset <= window * (1 + 1e-12); offset += step) {
        bool found = false;
        for (int side = 0; side < 2; side++) {
            /* Step outward, stopping on an end of an open rail 2 rather than passing it. */
            double sigma = side == 0 ? guess + offset : guess - offset;
            if (!pairing->wrap)
                sigma = fmin(fmax(sigma, pairing->s0), pairing->s1);
            if (sigma == where[side] || !in_rail2(pairing, where[side]))
                continue;
            pairing_rail2(pairing, sigma, d2);
            double value = condition(c1, d2);
            if ((value <= 0) != (before[side] <= 0)) {
                /* A root on each side at the same distance: the nearer one. */
                double candidate =
                    brent(pairing, c1, fmin(sigma, where[side]), fmax(sigma, where[side]));
                if (!found || fabs(candidate - guess) < fabs(*root - guess))
                    *root = candidate;
                found = true;
                continue;
            }
            before[side] = value;
            where[side] = sigma;
            double relative = fabs(value) / condition_scale(c1, d2);
            if (relative < best) {
                best = relative;
                best_sigma = sigma;
            }
        }
        if (found)
            return true;
    }
    if (best < 1e-10 && in_rail2(pairing, best_sigma)) {
        *root = best_sigma;
        return true;
    }
    return root_at_rail_end(pairing, c1, guess, window, root);
}

/* The window in which the root at the next sample is looked for. */
static double search_window(const ur_pairing *pairing, double predicted_change)
{
    return fmax(4 * pairing->step, 2 * fabs(predicted_change));
}

/*
 * Newton's method on F(u, .) from guess, kept inside [low, high] and on rail
 * 2.  From a good prediction it converges to the nearest root, also to a
 * double root (slowly) where a search for a sign change sees none.  With
 * `other`, it looks for a second root by deflation: F / (sigma - other).
 */
static bool newton_root(ur_pairing *pairing, const ur_vec3 c1[3], double guess, double low,
                        double high, const double *other, double *root)
{
    double sigma = guess, tolerance = 1e-14 * (fabs(pairing->s1) + (pairing->s1 - pairing->s0));
    for (int k = 0; k < NEWTON_STEPS; k++) {
        ur_vec3 d2[3];
        pairing_rail2(pairing, sigma, d2);
        double f = condition(c1, d2);
        double f_sigma = determinant3(c1[1], d2[2], ur_vec3_sub(d2[0], c1[0]));
        if (other) {
            double apart = sigma - *other;
            if (fabs(apart) <= tolerance)
                return false;
            f_sigma = f_sigma - f / apart; /* of F / (sigma - other), times (sigma - other) */
        }
        double next = sigma - f / f_sigma;
        if (!isfinite(next) || next < low || next > high)
            return false;
        if (!pairing->wrap && (next < pairing->s0 || next > pairing->s1)) {
            /* Rail 2 ends here: a root past it within the end slack is on its end. */
            double end = next < pairing->s0 ? pairing->s0 : pairing->s1;
            if (sigma == end) {
                /* As root_at_rail_end: within the end slack, in length or in angle. */
                *root = end;
                bool near = near_rail2(pairing, next) ||
                            fabs(f) / condition_scale(c1, d2) <= pairing->end_slack;
                return near && (!other || fabs(end - *other) > tolerance);
            }
            next = end;
        }
        bool done = fabs(next - sigma) <= tolerance || f == 0.0;
        sigma = next;
        if (done) {
            *root = sigma;
            return !other || fabs(sigma - *other) > tolerance;
        }
    }
    return false;
}

static void store_root(ur_pairing *pairing, size_t i, double sigma, double slope)
{
    if (!pairing->wrap)
        sigma = fmin(fmax(sigma, pairing->s0), pairing->s1);
    pairing->sigma[i] = sigma;
    pairing->slope[i] = isfinite(slope) ? slope : 0.0;
    pairing->state[i] = SAMPLE_GOOD;
}

/* Cubic Hermite value and slope at u between table samples i and j. */
static void hermite(const ur_pairing *pairing, size_t i, size_t j, double u, double *sigma,
                    double *slope)
{
    double h = pairing->u[j] - pairing->u[i], t = (u - pairing->u[i]) / h;
    double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
    double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
    double d00 = 6 * t * (t - 1), d10 = (1 - t) * (1 - 3 * t), d11 = t * (3 * t - 2);
    *sigma = h00 * pairing->sigma[i] + h10 * h * pairing->slope[i] + h01 * pairing->sigma[j] +
             h11 * h * pairing->slope[j];
    *slope = d00 * (pairing->sigma[i] - pairing->sigma[j]) / h + d10 * pairing->slope[i] +
             d11 * pairing->slope[j];
}

/*
 * The slope at a root reached from a root at (u_from, sigma_from, slope_from):
 * -F_u / F_sigma, or at a double root, where that is 0 / 0, the slope of the
 * parabola through the two roots that has slope_from at u_from.
 */
static double continued_slope(ur_pairing *pairing, const ur_vec3 c1[3], double sigma, double u_from,
                              double sigma_from, double slope_from, double u)
{
    ur_vec3 d2[3];
    pairing_rail2(pairing, sigma, d2);
    double slope = pairing_implicit_slope(c1, d2);
    if (isfinite(slope) && !at_double_root(pairing, c1, d2))
        return slope;
    if (u == u_from)
        return slope_from;
    return 2 * (sigma - sigma_from) / (u - u_from) - slope_from;
}

/*
 * The root at u on the branch of the root at table sample `from`: predicted
 * with that sample's slope and corrected by Newton's method.  Next to a
 * double root the other branch's root is near too, so both are found and
 * the one kept is the one whose position and slope continue the branch
 * best (slope continuity, not the nearest root).
 */
static bool follow_from(ur_pairing *pairing, double u_from, double sigma_from, double slope_from,
                        double u, const ur_vec3 c1[3], double *root, double *slope)
{
    double change = slope_from * (u - u_from), predicted = sigma_from + change;
    double window = search_window(pairing, change);
    double candidates[2];
    int count = 0;
    if (newton_root(pairing, c1, predicted, predicted - window, predicted + window, NULL,
                    &candidates[0]) ||
        local_root(pairing, c1, predicted, window, &candidates[0]))
        count = 1;
    if (count == 0)
        return false;
    /* The other branch, if it passes close by. */
    double near = fmax(fabs(candidates[0] - predicted), pairing->step);
    double start = candidates[0] == predicted ? predicted + 0.5 * near : predicted;
    if (newton_root(pairing, c1, start, predicted - 4 * near, predicted + 4 * near, &candidates[0],
                    &candidates[1]))
        count = 2;
    double best = INFINITY;
    for (int k = 0; k < count; k++) {
        double m = continued_slope(pairing, c1, candidates[k], u_from, sigma_from, slope_from, u);
        double score =
            fabs(candidates[k] - predicted) + 0.5 * fabs(u - u_from) * fabs(m - slope_from);
        if (score < best) {
            best = score;
            *root = candidates[k];
            *slope = m;
        }
    }
    return true;
}

static bool follow_root(ur_pairing *pairing, size_t from, double u, const ur_vec3 c1[3],
                        double *root, double *slope)
{
    return follow_from(pairing, pairing->u[from], pairing->sigma[from], pairing->slope[from], u, c1,
                       root, slope);
}

/*
 * Whether a slope continues the one before: on a smooth branch the slope
 * changes little from one table sample to the next.
 */
static bool continues(double slope_from, double slope)
{
    return fabs(slope - slope_from) <= SLOPE_CHANGE * fmax(fabs(slope_from), fabs(slope));
}

/*
 * Where the rails' interpolations differ a little (rails with inflections
 * and unlike parametrisations), the two branches that would cross at a
 * double root miss each other instead: near the inflection each turns back
 * and neither root there continues the slope.  The branch goes on beyond:
 * predicted from sample `from` a few samples on, a root there continues the
 * slope.  Then the samples in between take the branch's Hermite
 * interpolation and are marked bridged; returns the landing sample, or
 * SIZE_MAX when no root continues the branch (a true end of it).  `bad` is
 * the first sample where the branch did not go on; the landing is at least
 * BRIDGE_MARGIN past it, where the roots no longer feel the turn.
 */
static size_t bridge(ur_pairing *pairing, size_t from, size_t bad)
{
    size_t first = bad + BRIDGE_MARGIN > from + 2 ? bad + BRIDGE_MARGIN : from + 2;
    for (size_t land = first; land <= bad + BRIDGE_SAMPLES && land < pairing->count; land++) {
        ur_vec3 c1[3];
        ur_curve_eval(pairing->rail1, pairing->u[land], c1);
        double root, slope;
        if (!follow_root(pairing, from, pairing->u[land], c1, &root, &slope) ||
            !continues(pairing->slope[from], slope))
            continue;
        double predicted =
            pairing->sigma[from] + pairing->slope[from] * (pairing->u[land] - pairing->u[from]);
        if (fabs(root - predicted) > SLOPE_CHANGE * fabs(predicted - pairing->sigma[from]))
            continue;
        store_root(pairing, land, root, slope);
        for (size_t k = from + 1; k < land; k++) {
            hermite(pairing, from, land, pairing->u[k], &pairing->sigma[k], &pairing->slope[k]);
            pairing->state[k] = SAMPLE_GOOD;
        }
        for (size_t k = from; k < land; k++)
            pairing->joined[k] = pairing->bridged[k] = true;
        return land;
    }
    return SIZE_MAX;
}

/*
 * The slope at a root found without a neighbour (a scan): -F_u / F_sigma, or
 * at a double root the slope of the branch that starts a strip there: the
 * roots a little way along rail 1, whose rulings do not cross, the one
 * running forward along rail 2 most slowly.
 */
static double fresh_slope(ur_pairing *pairing, double u, const ur_vec3 c1[3], double sigma);

/* Length of the ruling from c1 to rail 2 at sigma. */
static double ruling_length(ur_pairing *pairing, const ur_vec3 c1[3], double sigma)
{
    ur_vec3 d2[3];
    pairing_rail2(pairing, sigma, d2);
    return ur_vec3_distance(d2[0], c1[0]);
}

static bool rulings_cross(ur_pairing *pairing, double u, double sigma, double slope);

/* Whether the ruling from c1 to rail 2 at sigma would cross its neighbours. */
static bool candidate_crosses(ur_pairing *pairing, double u, const ur_vec3 c1[3], double sigma)
{
    return rulings_cross(pairing, u, sigma, fresh_slope(pairing, u, c1, sigma));
}

typedef struct scan_choice {
    bool have_previous;
    double predicted;
    double best; /* the score of *root: distance from the prediction, or ruling length */
    bool found;
} scan_choice;

/* Keeps candidate if it scores better than the root chosen so far. */
static void consider(ur_pairing *pairing, double u, const ur_vec3 c1[3], double candidate,
                     scan_choice *choice, double *root)
{
    if (pairing->wrap && choice->have_previous) /* unwrap to the turn nearest the prediction */
        candidate += (pairing->s1 - pairing->s0) *
                     round((choice->predicted - candidate) / (pairing->s1 - pairing->s0));
    double score = choice->have_previous ? fabs(candidate - choice->predicted)
                                         : ruling_length(pairing, c1, candidate);
    if (score < choice->best &&
        (choice->have_previous || !candidate_crosses(pairing, u, c1, candidate))) {
        choice->best = score;
        *root = candidate;
        choice->found = true;
    }
}

/*
 * Where |F| dips without changing sign between scan samples (or at an end
 * of rail 2), two roots may lie closer together than a scan step, or one
 * on the end: Newton's method from there finds them.
 */
static void dip_roots(ur_pairing *pairing, double u, const ur_vec3 c1[3], double sigma,
                      scan_choice *choice, double *root)
{
    double window = 2 * pairing->step, first, second;
    if ((sigma == pairing->s0 || sigma >= pairing->s1) &&
        root_at_rail_end(pairing, c1, sigma, window, &first))
        consider(pairing, u, c1, first, choice, root);
    if (!newton_root(pairing, c1, sigma, sigma - window, sigma + window, NULL, &first))
        return;
    consider(pairing, u, c1, first, choice, root);
    double start = first == sigma ? sigma + 0.5 * pairing->step : sigma;
    if (newton_root(pairing, c1, start, sigma - window, sigma + window, &first, &second))
        consider(pairing, u, c1, second, choice, root);
}

/*
 * Every root on rail 2 (one period when closed).  With a previous root, the
 * one nearest the prediction; without, the shortest ruling among those that
 * do not cross their neighbours (a crossing ruling cannot start a strip).
 */
static bool scan_root(ur_pairing *pairing, double u, const ur_vec3 c1[3], bool have_previous,
                      double predicted, double *root)
{
    scan_choice choice = {have_previous, predicted, INFINITY, false};
    size_t n = pairing->scan_count;
    double before = 0.0, value = 0.0, after = 0.0;
    for (size_t j = 0; j < n; j++) {
        before = value;
        value = j == 0 ? determinant3(c1[1], pairing->scan_tangent[0],
                                      ur_vec3_sub(pairing->scan_position[0], c1[0]))
                       : after;
        if (j + 1 < n)
            after = determinant3(c1[1], pairing->scan_tangent[j + 1],
                                 ur_vec3_sub(pairing->scan_position[j + 1], c1[0]));
        double sigma = pairing->s0 + pairing->step * (double)j;
        if (j > 0 && (value <= 0) != (before <= 0))
            consider(pairing, u, c1, brent(pairing, c1, sigma - pairing->step, sigma), &choice,
                     root);
        bool dip = (j == 0 || ((value <= 0) == (before <= 0) && fabs(value) <= fabs(before))) &&
                   (j + 1 == n || ((value <= 0) == (after <= 0) && fabs(value) <= fabs(after)));
        if (dip)
            dip_roots(pairing, u, c1, sigma, &choice, root);
    }
    return choice.found;
}

/* ---- The root table ----------------------------------------------------- */

ur_status pairing_table_alloc(ur_pairing *pairing, size_t count, ur_error *error)
{
    pairing->count = count;
    pairing->u = ur_alloc_array(count, sizeof *pairing->u, error);
    pairing->sigma = ur_alloc_array(count, sizeof *pairing->sigma, error);
    pairing->slope = ur_alloc_array(count, sizeof *pairing->slope, error);
    pairing->state = ur_alloc_array(count, sizeof *pairing->state, error);
    pairing->joined = ur_alloc_array(count, sizeof *pairing->joined, error);
    pairing->bridged = ur_alloc_array(count, sizeof *pairing->bridged, error);
    if (!pairing->u || !pairing->sigma || !pairing->slope || !pairing->state || !pairing->joined ||
        !pairing->bridged)
        return UR_ERROR_MEMORY;
    double u0 = ur_curve_start(pairing->rail1), u1 = ur_curve_end(pairing->rail1);
    for (size_t i = 0; i < count; i++) {
        pairing->u[i] = u0 + (u1 - u0) * (double)i / (double)(count - 1);
        pairing->state[i] = SAMPLE_NO_ROOT;
        pairing->bridged[i] = false;
    }
    return UR_OK;
}

static ur_status scan_alloc(ur_pairing *pairing, ur_error *error)
{
    size_t points = ur_curve_point_count(pairing->rail2);
    size_t n = points * 4 > MIN_SCAN ? points * 4 : MIN_SCAN;
    pairing->scan_count = n + 1;
    pairing->step = (pairing->s1 - pairing->s0) / (double)n;
    pairing->scan_position = ur_alloc_array(n + 1, sizeof(ur_vec3), error);
    pairing->scan_tangent = ur_alloc_array(n + 1, sizeof(ur_vec3), error);
    if (!pairing->scan_position || !pairing->scan_tangent)
        return UR_ERROR_MEMORY;
    for (size_t j = 0; j <= n; j++) {
        ur_vec3 d2[3];
        pairing_rail2(pairing, pairing->s0 + pairing->step * (double)j, d2);
        pairing->scan_position[j] = d2[0];
        pairing->scan_tangent[j] = d2[1];
    }
    return UR_OK;
}

/* Follows the root from sample `from` backward while it lasts (after a rescan). */
static void track_backward(ur_pairing *pairing, size_t from, size_t stop)
{
    for (size_t i = from; i > stop; i--) {
        size_t k = i - 1;
        if (pairing->state[k] == SAMPLE_GOOD)
            return;
        ur_vec3 c1[3];
        ur_curve_eval(pairing->rail1, pairing->u[k], c1);
        double root, slope;
        if (!follow_root(pairing, i, pairing->u[k], c1, &root, &slope))
            return;
        store_root(pairing, k, root, slope);
        pairing->joined[k] = true;
    }
}

static void build_table(ur_pairing *pairing)
{
    size_t last_good = SIZE_MAX, since_scan = RESCAN_EVERY;
    for (size_t i = 0; i < pairing->count; i++) {
        ur_vec3 c1[3];
        ur_curve_eval(pairing->rail1, pairing->u[i], c1);
        pairing->joined[i] = false;
        bool have_previous = last_good != SIZE_MAX;
        double predicted = 0.0, root, slope;
        if (have_previous)
            predicted = pairing->sigma[last_good] +
                        pairing->slope[last_good] * (pairing->u[i] - pairing->u[last_good]);
        if (have_previous && last_good + 1 == i) {
            bool found = follow_root(pairing, last_good, pairing->u[i], c1, &root, &slope);
            if (!found || !continues(pairing->slope[last_good], slope)) {
                /*
                 * From a few samples back, before the branch began to turn,
                 * to a few samples past the turn.
                 */
                size_t from = last_good;
                while (last_good - from < BRIDGE_MARGIN && from > 0 && pairing->joined[from - 1] &&
                       !pairing->bridged[from - 1])
                    from--;
                size_t land = bridge(pairing, from, i);
                if (land == SIZE_MAX && from != last_good)
                    land = bridge(pairing, last_good, i);
                if (land != SIZE_MAX) {
                    last_good = i = land;
                    continue;
                }
            }
            if (found) {
                store_root(pairing, i, root, slope);
                pairing->joined[i - 1] = true;
                last_good = i;
                continue;
            }
        }
        /* Lost or never found: scan rail 2, but only now and then inside a gap. */
        if (since_scan + 1 < RESCAN_EVERY && i + 1 < pairing->count) {
            since_scan++;
            continue;
        }
        since_scan = 0;
        if (scan_root(pairing, pairing->u[i], c1, have_previous, predicted, &root)) {
            store_root(pairing, i, root, fresh_slope(pairing, pairing->u[i], c1, root));
            track_backward(pairing, i, have_previous ? last_good + 1 : 0);
            last_good = i;
        }
    }
}

/* ---- Classifying samples and finding the gaps --------------------------- */

/*
 * Consecutive rulings of a developable meet at the point where r_u is
 * parallel to the ruling; inside the strip (strictly between the rails) the
 * rulings cross and the surface folds.  A decreasing sigma runs rail 2
 * backwards, which is the same fold seen from rail 2.
 */
static bool rulings_cross(ur_pairing *pairing, double u, double sigma, double slope)
{
    if (slope < 0)
        return true;
    ur_vec3 c1[3], d2[3];
    ur_curve_eval(pairing->rail1, u, c1);
    pairing_rail2(pairing, sigma, d2);
    ur_vec3 ruling = ur_vec3_sub(d2[0], c1[0]);
    ur_vec3 b_prime = ur_vec3_scale(d2[1], slope);
    ur_vec3 normal = ur_vec3_cross(c1[1], ruling);
    double size = ur_vec3_length(normal);
    if (!(size > 0))
        return false;
    /* Components across the ruling, in the tangent plane, of a' and b'. */
    ur_vec3 across =
        ur_vec3_scale(ur_vec3_cross(normal, ruling), 1.0 / (size * ur_vec3_length(ruling)));
    double along_a = ur_vec3_dot(c1[1], across), along_b = ur_vec3_dot(b_prime, across);
    double margin = 1e-9 * (fabs(along_a) + fabs(along_b));
    return along_a * along_b < 0 && fabs(along_a) > margin && fabs(along_b) > margin;
}

static double fresh_slope(ur_pairing *pairing, double u, const ur_vec3 c1[3], double sigma)
{
    ur_vec3 d2[3];
    pairing_rail2(pairing, sigma, d2);
    double slope = pairing_implicit_slope(c1, d2);
    if (isfinite(slope) && !at_double_root(pairing, c1, d2))
        return slope;
    double u0 = ur_curve_start(pairing->rail1), u1 = ur_curve_end(pairing->rail1);
    double h = (u1 - u0) / (double)(4 * (pairing->count - 1));
    if (u + h > u1)
        h = -h;
    ur_vec3 next[3];
    ur_curve_eval(pairing->rail1, u + h, next);
    double window = search_window(pairing, 0.0), roots[2], best = INFINITY;
    int count = 0;
    if (newton_root(pairing, next, sigma, sigma - window, sigma + window, NULL, &roots[0]) ||
        local_root(pairing, next, sigma, window, &roots[0]))
        count = 1;
    if (count == 1 && newton_root(pairing, next, sigma + 0.5 * window, sigma - window,
                                  sigma + window, &roots[0], &roots[1]))
        count = 2;
    for (int k = 0; k < count; k++) {
        double candidate = (roots[k] - sigma) / h;
        if (candidate < best && !rulings_cross(pairing, u + h, roots[k], candidate))
            best = candidate;
    }
    return isfinite(best) ? best : isfinite(slope) ? slope : 0.0;
}

/*
 * Whether (c1, d2) is near enough to a double root that an error of the
 * rails' interpolation, not only of F's rounding, moves the root: where two
 * rails of unlike parametrisation have inflections, the branches that
 * should cross there miss each other by about the square root of it.
 */
static bool near_double_root(const ur_pairing *pairing, const ur_vec3 c1[3], const ur_vec3 d2[3])
{
    return gradient_below(pairing, c1, d2, NEAR_DOUBLE_ROOT);
}

/* Whether the root of table sample i is near a double root (near_double_root). */
static bool sample_near_double_root(ur_pairing *pairing, size_t i)
{
    ur_vec3 c1[3], d2[3];
    ur_curve_eval(pairing->rail1, pairing->u[i], c1);
    pairing_rail2(pairing, pairing->sigma[i], d2);
    return near_double_root(pairing, c1, d2);
}

/*
 * Samples near a double root have roots that F's rounding (at the double
 * root) or the rails' interpolation (next to it, for rails of unlike
 * parametrisation) move off the branch, and slopes to match: the run of
 * them takes the Hermite interpolation of the branch between the samples
 * on either side, and is marked bridged so that sigma is answered from it.
 */
static void smooth_double_roots(ur_pairing *pairing)
{
    size_t n = pairing->count;
    for (size_t i = 1; i + 1 < n; i++) {
        if (pairing->state[i] != SAMPLE_GOOD || !pairing->joined[i - 1] ||
            !sample_near_double_root(pairing, i))
            continue;
        size_t before = i - 1, after = i;
        while (after + 1 < n && pairing->joined[after] && after - i < BRIDGE_SAMPLES &&
               sample_near_double_root(pairing, after))
            after++;
        if (!pairing->joined[after - 1] || sample_near_double_root(pairing, after) ||
            sample_near_double_root(pairing, before)) {
            i = after;
            continue;
        }
        for (size_t k = i; k < after; k++)
            hermite(pairing, before, after, pairing->u[k], &pairing->sigma[k], &pairing->slope[k]);
        for (size_t k = before; k < after; k++)
            pairing->bridged[k] = true;
        i = after;
    }
}

static void classify_samples(ur_pairing *pairing)
{
    for (size_t i = 0; i < pairing->count; i++)
        if (pairing->state[i] == SAMPLE_GOOD &&
            rulings_cross(pairing, pairing->u[i], pairing->sigma[i], pairing->slope[i]))
            pairing->state[i] = SAMPLE_CROSS;
}

/* Whether the table runs on one branch from sample i to i + 1. */
static bool table_joined(const ur_pairing *pairing, size_t i)
{
    return pairing->state[i] != SAMPLE_NO_ROOT && pairing->state[i + 1] != SAMPLE_NO_ROOT &&
           pairing->joined[i];
}

/* The state at u, following the root from a good sample at u_good. */
static enum sample_state state_at(ur_pairing *pairing, double u, size_t good, double *sigma)
{
    ur_vec3 c1[3];
    ur_curve_eval(pairing->rail1, u, c1);
    double slope;
    if (!follow_root(pairing, good, u, c1, sigma, &slope))
        return SAMPLE_NO_ROOT;
    return rulings_cross(pairing, u, *sigma, slope) ? SAMPLE_CROSS : SAMPLE_GOOD;
}

static bool usable(const ur_pairing *pairing, size_t i)
{
    return pairing->state[i] == SAMPLE_GOOD;
}

/* Where, between good sample `good` and its neighbour `bad`, the strip ends. */
static double refine_end(ur_pairing *pairing, size_t good, size_t bad)
{
    /*
     * Where a ruling leaves rail 2 through its end, find exactly where: the
     * table let roots a rounding error past the end count, so the first good
     * samples may not be good without that slack.
     */
    pairing->end_slack = 0.0;
    double sigma;
    size_t step = good > bad ? 1 : (size_t)-1;
    while (state_at(pairing, pairing->u[good], good, &sigma) != SAMPLE_GOOD) {
        size_t next = good + step;
        if (next >= pairing->count || !usable(pairing, next))
            break;
        bad = good;
        good = next;
    }
    double inside = pairing->u[good], outside = pairing->u[bad];
    for (int k = 0; k < BISECTIONS; k++) {
        double middle = 0.5 * (inside + outside);
        if (state_at(pairing, middle, good, &sigma) == SAMPLE_GOOD)
            inside = middle;
        else
            outside = middle;
    }
    pairing->end_slack = ROUNDING;
    return inside;
}

static ur_status add_gap(ur_pairing *pairing, double u_start, double u_end, ur_gap_reason reason,
                         size_t *capacity, ur_error *error)
{
    if (pairing->gap_count == *capacity) {
        size_t grown = *capacity ? 2 * *capacity : 8;
        ur_interval *gaps = realloc(pairing->gaps, grown * sizeof *gaps);
        if (!gaps)
            return ur_error_out_of_memory(error);
        pairing->gaps = gaps;
        *capacity = grown;
    }
    ur_interval *gap = &pairing->gaps[pairing->gap_count++];
    memset(gap, 0, sizeof *gap);
    gap->u_start = u_start;
    gap->u_end = u_end;
    gap->reason = reason;
    return UR_OK;
}

/* The reason for a run of unusable samples: crossing wins if any sample crossed. */
static ur_gap_reason run_reason(const ur_pairing *pairing, size_t first, size_t last)
{
    for (size_t i = first; i <= last; i++)
        if (pairing->state[i] == SAMPLE_CROSS)
            return UR_GAP_RULINGS_CROSS;
    return UR_GAP_NO_RULING;
}

static ur_status find_gaps(ur_pairing *pairing, ur_error *error)
{
    size_t capacity = 0, n = pairing->count;
    size_t i = 0;
    while (i < n) {
        if (usable(pairing, i)) {
            /* A jump to another branch between two good samples: the rulings in between cross. */
            if (i + 1 < n && usable(pairing, i + 1) && !pairing->joined[i]) {
                double at = 0.5 * (pairing->u[i] + pairing->u[i + 1]);
                ur_status status = add_gap(pairing, at, at, UR_GAP_RULINGS_CROSS, &capacity, error);
                if (status != UR_OK)
                    return status;
            }
            i++;
            continue;
        }
        size_t first = i;
        while (i < n && !usable(pairing, i))
            i++;
        size_t last = i - 1;
        double start = first == 0 ? pairing->u[0] : refine_end(pairing, first - 1, first);
        double end = i == n ? pairing->u[n - 1] : refine_end(pairing, i, last);
        bool at_an_end = first == 0 || i == n;
        if (at_an_end && end - start <= ROUNDING * (pairing->u[n - 1] - pairing->u[0]))
            continue; /* an interpolation error at the very end of rail 1 */
        ur_status status =
            add_gap(pairing, start, end, run_reason(pairing, first, last), &capacity, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* ---- Answering sigma(u) ------------------------------------------------- */

static size_t table_interval(ur_pairing *pairing, double u)
{
    size_t n = pairing->count, i = pairing->hint;
    if (i + 1 < n && pairing->u[i] <= u && u <= pairing->u[i + 1])
        return i;
    double u0 = pairing->u[0], u1 = pairing->u[n - 1];
    double position = (u - u0) / (u1 - u0) * (double)(n - 1);
    if (!(position > 0))
        i = 0;
    else if (position >= (double)(n - 1))
        i = n - 2;
    else
        i = (size_t)position;
    pairing->hint = i;
    return i;
}

/*
 * The nearest sample with a root, the start for u in a gap or at a jump of
 * the pairing; preferably one inside [low, high], the part of the surface in
 * use, so that a piece that starts at a jump takes the branch it is on.
 */
static size_t nearest_root_sample(const ur_pairing *pairing, size_t i, double u, double low,
                                  double high)
{
    size_t fallback = SIZE_MAX;
    bool right_first = pairing->u[i + 1] - u < u - pairing->u[i];
    for (size_t step = 0; step < pairing->count; step++) {
        size_t right = i + 1 + step, left = i >= step ? i - step : SIZE_MAX;
        size_t candidates[2] = {right_first ? right : left, right_first ? left : right};
        for (int k = 0; k < 2; k++) {
            size_t c = candidates[k];
            if (c >= pairing->count || pairing->state[c] == SAMPLE_NO_ROOT)
                continue;
            if (pairing->u[c] >= low && pairing->u[c] <= high)
                return c;
            if (fallback == SIZE_MAX)
                fallback = c;
        }
    }
    return fallback;
}

double pairing_solved_sigma(ur_pairing *pairing, double u, double low_u, double high_u,
                            const ur_vec3 c1[3], bool *on_table)
{
    size_t i = table_interval(pairing, u);
    bool both = table_joined(pairing, i);
    double guess, low, high, slope;
    *on_table = false;
    if (both) {
        hermite(pairing, i, i + 1, u, &guess, &slope);
        low = fmin(pairing->sigma[i], pairing->sigma[i + 1]) - pairing->step;
        high = fmax(pairing->sigma[i], pairing->sigma[i + 1]) + pairing->step;
    } else {
        size_t k = nearest_root_sample(pairing, i, u, low_u, high_u);
        if (k == SIZE_MAX)
            return pairing->s0;
        guess = pairing->sigma[k] + pairing->slope[k] * (u - pairing->u[k]);
        low = guess - 4 * pairing->step;
        high = guess + 4 * pairing->step;
    }
    /*
     * At a double root F's rounding leaves the root uncertain by about 1e-8
     * of the rail; the table's branch through well-conditioned samples is
     * better there (and keeps to the branch).
     */
    ur_vec3 d2[3];
    pairing_rail2(pairing, guess, d2);
    *on_table = both && (pairing->bridged[i] || at_double_root(pairing, c1, d2));
    if (*on_table)
        return guess;
    double sigma;
    if (newton_root(pairing, c1, guess, low, high, NULL, &sigma))
        return sigma;
    double root;
    if (local_root(pairing, c1, guess, 0.5 * (high - low), &root))
        return root;
    return guess;
}

double pairing_solved_slope(ur_pairing *pairing, double u, const ur_vec3 c1[3], const ur_vec3 d2[3],
                            bool on_table)
{
    double slope = pairing_implicit_slope(c1, d2);
    size_t i = table_interval(pairing, u);
    if (isfinite(slope) && !on_table && !at_double_root(pairing, c1, d2))
        return slope;
    /* At a double root -F_u / F_sigma is 0 / 0: the slope of the table's branch instead. */
    if (!table_joined(pairing, i))
        return isfinite(slope) ? slope : 0.0;
    double sigma;
    hermite(pairing, i, i + 1, u, &sigma, &slope);
    return slope;
}

ur_status pairing_track(ur_pairing *pairing, ur_error *error)
{
    pairing->solved = true;
    gsl_errors_off();
    pairing->solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_errors_restore();
    if (!pairing->solver)
        return ur_error_out_of_memory(error);
    size_t points = ur_curve_point_count(pairing->rail1);
    size_t n = points * 2 > MIN_SAMPLES ? points * 2 : MIN_SAMPLES;
    ur_status status = pairing_table_alloc(pairing, n + 1, error);
    if (status == UR_OK)
        status = scan_alloc(pairing, error);
    if (status != UR_OK)
        return status;
    build_table(pairing);
    smooth_double_roots(pairing);
    classify_samples(pairing);
    return find_gaps(pairing, error);
}
