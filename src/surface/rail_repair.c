/*
 * rail_repair.c: reshaping rail 2 (or rail 1, or both) as little as
 * possible so that the developable strip between the rails exists along
 * the whole of rail 1, what the seed's Tapeworm script does by hand.
 *
 * Unlike adjust.c, which moves rail 2 over a window round each gap, this
 * moves the whole rail at once.  It first tries smoothing (repair_by_smoothing):
 * the rail fitted with a few B-splines, which irons out a dent or a bump,
 * and the smallest share of the way there that gives a strip everywhere.
 * When that fails, by a smooth displacement: a cubic B-spline
 * of the point index with about one coefficient per six points (per axis
 * along which the points may move), added to each point.  The rail keeps
 * its number of points; its ends stay put unless asked otherwise.  The
 * pairing is unknown too: at samples x_k spread evenly over rail 1's
 * points (both ends included) it is sigma_k, a position on rail 2 in
 * point-index coordinates running from rail 2's first point to its last
 * through positive increments exp(a_k).  GSL's Levenberg-Marquardt solver
 * minimises the sum of the squares of
 *
 *     G_k / TANGENCY                      the ruling at x_k touches one plane
 *     CROSSING shortfall(q_k, MARGIN)     its edge of regression is outside
 *     CROSSING shortfall(s_k, STEEPNESS)  the pairing rises, with no fold
 *     CROSSING shortfall(g_k, GRADIENT)   away from where branches cross
 *     CHORD (log chord - log slope)       between samples, on one branch
 *     PAIRING (a_k+1 - a_k), d, sqrt(SMOOTHING) D c
 *
 * G_k = det(c1', c2', c2 - c1) at the sample scaled to an angle, q_k the
 * product of the components of c1' and c2' across the ruling in the
 * tangent plane (positive where the rulings' edge of regression lies
 * outside the strip, as tracking.c's rulings_cross has it), s_k = sin 2 phi
 * of the root curve F = 0 in the plane of (u, sigma) (zero where it turns
 * back: a fold), g_k its gradient's size, shortfall(v, w) = max(0, w - v) /
 * w, d the displacements of all the points (weighed so that |d|^2 is K times
 * their mean square) and D c the second differences of the coefficients.
 * The penalties vanish exactly when the sampled pairing is developable,
 * monotone, end to end, keeps to one branch and its rulings do not cross.
 *
 * The moving rails are first fitted with one B-spline per four points,
 * which leaves their shape and smooths away the rounding of their last
 * digits (the solver's terms use second derivatives, which magnify it).
 * Every few steps the rails are checked by building the strip again
 * (ur_ruled_strip) and following its edge of regression; the first step
 * that passes is the answer.  While none does, the penalties weigh ten
 * times more, a few times; a round ends early when the cost stalls, and
 * all rounds share a budget of SOLVER_BUDGET steps, so that a pair the
 * solver cannot repair is refused in seconds.
 *
 * A repair that only just straightens what was in the way leaves the edge
 * of regression touching a rail, where the rulings crowd together and the
 * strip bends as sharply as a crease; its displacement is then stretched,
 * in steps of 5 %, until the edge stays EDGE_CLEARANCE rulings beyond both
 * rails and the strip bends no tighter than BEND times the rails' distance
 * (or, when no step does that, only until the edge is clear).
 *
 * The pairing is first guessed in proportion along the rails, then, if
 * that fails, from the strip as it is.  This is a local method: it finds
 * the repair the first guesses lead to, not always the smallest, and may
 * find none where one exists (the caller is told so).
 */
#include "surface_internal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_bspline.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_multifit.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <stdlib.h>
#include <string.h>

#include "../base/c_locale.h"
#include "../base/gsl_errors.h"

enum {
    POINTS_PER_COEFFICIENT = 6,
    MIN_COEFFICIENTS = 8,
    MAX_COEFFICIENTS = 40,
    SAMPLES_PER_COEFFICIENT = 4,
    MAX_ITERATIONS = 100,
    ROUNDS = 4,
    SAMPLES_PER_POINT = 4, /* of rail 1, checking the edge of regression */
    NOISE_POINTS = 4,
    CHECK_EVERY = 5,     /* solver steps between looks at the strip */
    STALL_CHECKS = 4,    /* looks over which the cost must fall by STALL */
    SOLVER_BUDGET = 150, /* solver steps in all */
};

/*
 * How far beyond the rails, in rulings, the edge of regression must stay:
 * near a rail the rulings crowd together on it and the strip bends sharply
 * there (the bend radius on the rail is about this fraction of the one on
 * the other rail).
 */
#define EDGE_CLEARANCE 0.015

/*
 * The smallest bend radius a repair is stretched to leave, as a share of
 * the rails' distance: a crease is what the repair is there to avoid.  On
 * issue 25's rails the strip breaks when the repair is stretched by more
 * than about 15 %, which leaves radii up to about 1.5 % of the distance.
 */
#define BEND 0.015

#define TANGENCY 1e-4  /* radians of G that weigh as much as 1 mm of displacement */
#define MARGIN 0.02    /* q_k wanted, so that the edge of regression stays clear */
#define STEEPNESS 0.05 /* sin 2 phi wanted: the slope between about 1/40 and 40 */
#define CROSSING 1e3   /* weight of a whole shortfall, in mm */
#define GRADIENT 0.1   /* |grad F| wanted, in curvature times ruling length */
#define PAIRING 0.1    /* weight of the pairing's smoothness */
#define CHORD 10.0     /* weight of the chords' mismatch with the root curve */
#define SMOOTHING 1.0
#define STALL 0.02

/* One rail: where its points were, where they are, and how they may move. */
typedef struct rail {
    const ur_vec3 *original;
    ur_vec3 *smoothed;   /* original with the noise of its last digits fitted away, or NULL */
    const ur_vec3 *base; /* what the solver's displacement is added to: smoothed, or original */
    ur_vec3 *points;
    size_t count;
    bool moves;
    ur_curve *curve;      /* through points; rebuilt for each evaluation */
    gsl_matrix *basis;    /* count x coefficients: B-spline j at point i */
    gsl_matrix *gram;     /* L, L L^T = B^T B over the free coefficients */
    size_t coefficients;  /* all of them; with ends fixed the first and last stay 0 */
    size_t first_free;    /* 0, or 1 with ends fixed */
    size_t free_count;    /* coefficients that move */
    size_t first_unknown; /* where this rail's unknowns start */
} rail;

typedef struct problem {
    rail rails[2];
    ur_vec3 axes[3]; /* orthonormal directions the points may move along */
    size_t axis_count;
    size_t samples;       /* K */
    size_t first_pairing; /* where the K - 1 increments start */
    size_t unknowns, residual_count;
    double strength; /* the penalties' weight, raised round by round */
    double bend;     /* the smallest bend radius a repair should leave, mm */
    double *sigma;   /* K, scratch */
    const ur_context *context;
} problem;

/* ---- Geometry on point-index coordinates -------------------------------- */

/* The parameter of a rail's spline at index coordinate x (point i at x = i). */
static double parameter_at(const ur_curve *curve, size_t count, double x)
{
    double clamped = fmin(fmax(x, 0.0), (double)(count - 1));
    size_t i = (size_t)fmin(floor(clamped), (double)(count - 2));
    double k0 = ur_curve_point_parameter(curve, i), k1 = ur_curve_point_parameter(curve, i + 1);
    return k0 + (clamped - (double)i) * (k1 - k0);
}

/* The index coordinate of parameter s on a spline through count points. */
static double index_at(const ur_curve *curve, size_t count, double s)
{
    size_t low = 0, high = count - 1;
    if (s <= ur_curve_point_parameter(curve, 0))
        return 0.0;
    if (s >= ur_curve_point_parameter(curve, high))
        return (double)high;
    while (high - low > 1) {
        size_t middle = (low + high) / 2;
        if (ur_curve_point_parameter(curve, middle) <= s)
            low = middle;
        else
            high = middle;
    }
    double k0 = ur_curve_point_parameter(curve, low), k1 = ur_curve_point_parameter(curve, low + 1);
    return (double)low + (s - k0) / (k1 - k0);
}

static double sample_index(const problem *p, size_t k)
{
    return (double)(p->rails[0].count - 1) * (double)k / (double)(p->samples - 1);
}

/* ---- Unknowns ----------------------------------------------------------- */

static size_t rail_unknowns(const rail *r, const problem *p)
{
    return r->moves ? r->free_count * p->axis_count : 0;
}

/* The points of a rail moved by the coefficients in x (read through gsl_vector_get). */
static void place_points(const problem *p, rail *r, const gsl_vector *x)
{
    memcpy(r->points, r->base, r->count * sizeof *r->points);
    if (!r->moves)
        return;
    for (size_t m = 0; m < r->free_count; m++) {
        ur_vec3 move = ur_vec3_make(0, 0, 0);
        for (size_t a = 0; a < p->axis_count; a++)
            move = ur_vec3_add_scaled(move, p->axes[a],
                                      gsl_vector_get(x, r->first_unknown + m * p->axis_count + a));
        for (size_t i = 0; i < r->count; i++) {
            double weight = gsl_matrix_get(r->basis, i, r->first_free + m);
            if (weight != 0.0)
                r->points[i] = ur_vec3_add_scaled(r->points[i], move, weight);
        }
    }
}

/* sigma_k from the increments: rail 2's first point, then shares of the way to its last. */
static void place_pairing(const problem *p, const gsl_vector *x)
{
    double total = 0.0, end = (double)(p->rails[1].count - 1);
    for (size_t k = 0; k + 1 < p->samples; k++)
        total += exp(gsl_vector_get(x, p->first_pairing + k));
    double sum = 0.0;
    p->sigma[0] = 0.0;
    for (size_t k = 1; k < p->samples; k++) {
        sum += exp(gsl_vector_get(x, p->first_pairing + k - 1));
        p->sigma[k] = end * sum / total;
    }
    p->sigma[p->samples - 1] = end;
}

static int build_curves(problem *p)
{
    for (int r = 0; r < 2; r++) {
        rail *q = &p->rails[r];
        if (q->curve && !q->moves)
            continue;
        ur_curve_free(q->curve);
        q->curve = NULL;
        if (ur_curve_new_interpolating(q->points, q->count, false, &q->curve, NULL) != UR_OK)
            return GSL_EBADFUNC;
    }
    return GSL_SUCCESS;
}

/* ---- The residuals ------------------------------------------------------ */

/* What the residuals need of the ruling at one sample. */
typedef struct ruling_terms {
    double tangency;  /* G as an angle */
    double clearance; /* q: positive where the edge of regression is outside the strip */
    double steepness; /* sin 2 phi, phi the direction of the root curve: positive when rising */
    double gradient;  /* |grad F| against the rails' curvature: zero where branches cross */
    double slope;     /* d sigma / d u of the root curve, in mm of rail 2 per mm of rail 1 */
    double u, sigma;  /* the rails' parameters (about mm along them) */
} ruling_terms;

/*
 * The terms at sample k, on the rails as placed.  With F = det(c1', c2', d),
 * d = c2 - c1, the root curve F = 0 runs along (F_sigma |c1'|, -F_u |c2'|)
 * in mm of each rail; a fold of the pairing is where it turns vertical.
 */
static ruling_terms terms_at(problem *p, size_t k)
{
    rail *one = &p->rails[0], *two = &p->rails[1];
    ruling_terms t;
    ur_vec3 c1[3], c2[3];
    t.u = parameter_at(one->curve, one->count, sample_index(p, k));
    t.sigma = parameter_at(two->curve, two->count, p->sigma[k]);
    ur_curve_eval(one->curve, t.u, c1);
    ur_curve_eval(two->curve, t.sigma, c2);
    ur_vec3 ruling = ur_vec3_sub(c2[0], c1[0]);
    double length = ur_vec3_length(ruling), speed1 = ur_vec3_length(c1[1]);
    double speed2 = ur_vec3_length(c2[1]);
    t.tangency = determinant3(c1[1], c2[1], ruling) / (speed1 * speed2 * length);
    double rise = -determinant3(c1[2], c2[1], ruling) * speed2;
    double run = determinant3(c1[1], c2[2], ruling) * speed1;
    double size = rise * rise + run * run;
    t.steepness = size > 0 ? 2 * rise * run / size : 0.0;
    t.gradient = sqrt(size) / (speed1 * speed1 * speed2 * speed2);
    t.slope = rise / run;
    ur_vec3 normal = ur_vec3_cross(c1[1], ruling);
    double across_size = ur_vec3_length(normal);
    t.clearance = 0.0;
    if (across_size > 0) {
        ur_vec3 across = ur_vec3_scale(ur_vec3_cross(normal, ruling), 1.0 / (across_size * length));
        t.clearance = ur_vec3_dot(c1[1], across) / speed1 * ur_vec3_dot(c2[1], across) / speed2;
    }
    return t;
}

/*
 * How far the chord between two samples strays from the root curve's
 * slope at its ends, as a logarithm: zero up to the discretisation for a
 * pairing that follows one branch, large where it jumps to another.
 */
static double chord_mismatch(const ruling_terms *a, const ruling_terms *b)
{
    double chord = (b->sigma - a->sigma) / (b->u - a->u);
    if (!(chord > 0 && a->slope > 0 && b->slope > 0) || !isfinite(a->slope * b->slope))
        return 0.0; /* the steepness penalty speaks there */
    return log(chord) - 0.5 * (log(a->slope) + log(b->slope));
}

static size_t add_rail_terms(const problem *p, const rail *r, const gsl_vector *x, gsl_vector *f,
                             size_t row)
{
    if (!r->moves)
        return row;
    /*
     * |L^T c_a|^2 summed over the axes is the sum over the points of their
     * squared displacement, weighed as K samples of its mean.
     */
    double weight = sqrt((double)p->samples / (double)r->count);
    for (size_t a = 0; a < p->axis_count; a++)
        for (size_t m = 0; m < r->free_count; m++) {
            double sum = 0.0;
            for (size_t j = m; j < r->free_count; j++)
                sum += gsl_matrix_get(r->gram, j, m) *
                       gsl_vector_get(x, r->first_unknown + j * p->axis_count + a);
            gsl_vector_set(f, row++, weight * sum);
        }
    /* Second differences of the coefficients, the fixed ends counting as zeros. */
    double smoothing = sqrt(SMOOTHING);
    for (size_t m = 1; m + 1 < r->coefficients; m++)
        for (size_t a = 0; a < p->axis_count; a++) {
            double value[3];
            for (int s = 0; s < 3; s++) {
                size_t j = m - 1 + (size_t)s;
                bool free = j >= r->first_free && j < r->first_free + r->free_count;
                value[s] = free ? gsl_vector_get(x, r->first_unknown +
                                                        (j - r->first_free) * p->axis_count + a)
                                : 0.0;
            }
            gsl_vector_set(f, row++, smoothing * (value[0] - 2 * value[1] + value[2]));
        }
    return row;
}

/*
 * The penalty for a value below what is wanted: the square of the
 * shortfall as a fraction of it, so that it is smooth where it starts.
 */
static double shortfall(double value, double wanted)
{
    return fmax(0.0, wanted - value) / wanted * CROSSING;
}

static int residuals(const gsl_vector *x, void *data, gsl_vector *f)
{
    problem *p = data;
    for (int r = 0; r < 2; r++)
        place_points(p, &p->rails[r], x);
    place_pairing(p, x);
    int code = build_curves(p);
    if (code != GSL_SUCCESS)
        return code;
    size_t row = 0;
    ruling_terms previous = {0};
    for (size_t k = 0; k < p->samples; k++) {
        ruling_terms t = terms_at(p, k);
        gsl_vector_set(f, row++, p->strength * t.tangency / TANGENCY);
        gsl_vector_set(f, row++, p->strength * shortfall(t.clearance, MARGIN));
        gsl_vector_set(f, row++, p->strength * shortfall(t.steepness, STEEPNESS));
        gsl_vector_set(f, row++, p->strength * shortfall(t.gradient, GRADIENT));
        if (k > 0)
            gsl_vector_set(f, row++, CHORD * chord_mismatch(&previous, &t));
        previous = t;
    }
    for (size_t k = 0; k + 2 < p->samples; k++)
        gsl_vector_set(f, row++,
                       PAIRING * (gsl_vector_get(x, p->first_pairing + k + 1) -
                                  gsl_vector_get(x, p->first_pairing + k)));
    for (int r = 0; r < 2; r++)
        row = add_rail_terms(p, &p->rails[r], x, f, row);
    return row == p->residual_count ? GSL_SUCCESS : GSL_EBADLEN;
}

/* ---- Setting the problem up --------------------------------------------- */

static size_t coefficients_for(size_t count)
{
    size_t wanted = count / POINTS_PER_COEFFICIENT;
    if (wanted < MIN_COEFFICIENTS)
        wanted = MIN_COEFFICIENTS;
    if (wanted > MAX_COEFFICIENTS)
        wanted = MAX_COEFFICIENTS;
    return wanted < count ? wanted : count;
}

/* The cubic B-splines of the point index, evaluated at every point. */
static ur_status make_basis(rail *r, bool move_ends, ur_error *error)
{
    r->coefficients = coefficients_for(r->count);
    gsl_bspline_workspace *splines = gsl_bspline_alloc(4, r->coefficients - 2);
    gsl_vector *values = gsl_vector_alloc(r->coefficients);
    r->basis = gsl_matrix_alloc(r->count, r->coefficients);
    ur_status status = splines && values && r->basis ? UR_OK : ur_error_out_of_memory(error);
    if (status == UR_OK)
        gsl_bspline_knots_uniform(0.0, (double)(r->count - 1), splines);
    for (size_t i = 0; status == UR_OK && i < r->count; i++) {
        gsl_bspline_eval((double)i, values, splines);
        gsl_matrix_set_row(r->basis, i, values);
    }
    if (splines)
        gsl_bspline_free(splines);
    gsl_vector_free(values);
    r->first_free = move_ends ? 0 : 1;
    r->free_count = r->coefficients - (move_ends ? 0 : 2);
    if (status == UR_OK)
        r->gram = gsl_matrix_alloc(r->free_count, r->free_count);
    if (status == UR_OK && !r->gram)
        status = ur_error_out_of_memory(error);
    if (status == UR_OK) {
        gsl_matrix_const_view free_basis =
            gsl_matrix_const_submatrix(r->basis, 0, r->first_free, r->count, r->free_count);
        gsl_blas_dgemm(CblasTrans, CblasNoTrans, 1.0, &free_basis.matrix, &free_basis.matrix, 0.0,
                       r->gram);
        if (gsl_linalg_cholesky_decomp1(r->gram) != GSL_SUCCESS)
            status = ur_error_set(error, UR_ERROR_INTERNAL, "reshaping the rails: singular basis");
    }
    return status;
}

/* Directions the points may move along: one, two across a plane's normal, or all three. */
static ur_status set_axes(problem *p, const ur_rail_repair_options *options, ur_error *error)
{
    if (options->direction && options->plane_normal)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "a direction and a plane for the moves do not go together");
    const ur_vec3 *given = options->direction ? options->direction : options->plane_normal;
    if (!given) {
        p->axes[0] = ur_vec3_make(1, 0, 0);
        p->axes[1] = ur_vec3_make(0, 1, 0);
        p->axes[2] = ur_vec3_make(0, 0, 1);
        p->axis_count = 3;
        return UR_OK;
    }
    double length = ur_vec3_length(*given);
    if (!(length > 0) || !isfinite(length))
        return ur_error_set(error, UR_ERROR_INPUT, "the %s must not be zero",
                            options->direction ? "direction of the moves" : "planes' normal");
    ur_vec3 unit = ur_vec3_scale(*given, 1.0 / length);
    if (options->direction) {
        p->axes[0] = unit;
        p->axis_count = 1;
        return UR_OK;
    }
    /* Two directions across the normal: the axis least along it, made square to it. */
    ur_vec3 seed =
        fabs(unit.x) < fabs(unit.y)
            ? (fabs(unit.x) < fabs(unit.z) ? ur_vec3_make(1, 0, 0) : ur_vec3_make(0, 0, 1))
            : (fabs(unit.y) < fabs(unit.z) ? ur_vec3_make(0, 1, 0) : ur_vec3_make(0, 0, 1));
    ur_vec3 first = ur_vec3_add_scaled(seed, unit, -ur_vec3_dot(seed, unit));
    p->axes[0] = ur_vec3_scale(first, 1.0 / ur_vec3_length(first));
    p->axes[1] = ur_vec3_cross(unit, p->axes[0]);
    p->axis_count = 2;
    return UR_OK;
}

static ur_status smooth_rail(const rail *r, size_t coefficients, ur_vec3 *smooth, ur_error *error);
static void allowed_moves(const problem *p, const rail *r, ur_vec3 *moves);

/*
 * The solver works on derivatives of the rails up to the second, which
 * magnify the rounding of their points' last digits (3 decimals give the
 * wavy rail's curvature errors of a tenth of itself); it starts from the
 * rail fitted with one B-spline per NOISE_POINTS points, which leaves its
 * shape (a few micrometres off) and smooths that noise away.
 */
static ur_status smooth_away_noise(const problem *p, rail *r, ur_error *error)
{
    size_t coefficients = r->count / NOISE_POINTS;
    if (coefficients < 8)
        return UR_OK;
    r->smoothed = ur_alloc_array(r->count, sizeof *r->smoothed, error);
    if (!r->smoothed)
        return UR_ERROR_MEMORY;
    ur_status status = smooth_rail(r, coefficients, r->smoothed, error);
    if (status != UR_OK)
        return status;
    r->base = r->original;
    allowed_moves(p, r, r->smoothed);
    for (size_t i = 0; i < r->count; i++)
        r->smoothed[i] = ur_vec3_add(r->original[i], r->smoothed[i]);
    r->base = r->smoothed;
    return UR_OK;
}

static ur_status set_up(problem *p, const ur_rail_repair_options *options, ur_error *error)
{
    size_t unknowns = 0, most = 0;
    for (int r = 0; r < 2; r++) {
        rail *q = &p->rails[r];
        q->points = ur_alloc_array(q->count, sizeof *q->points, error);
        if (!q->points)
            return UR_ERROR_MEMORY;
        memcpy(q->points, q->original, q->count * sizeof *q->points);
        q->base = q->original;
        if (!q->moves)
            continue;
        ur_status status = make_basis(q, options->move_ends, error);
        if (status == UR_OK)
            status = smooth_away_noise(p, q, error);
        if (status != UR_OK)
            return status;
        q->first_unknown = unknowns;
        unknowns += rail_unknowns(q, p);
        if (q->coefficients > most)
            most = q->coefficients;
    }
    p->samples = SAMPLES_PER_COEFFICIENT * most;
    p->sigma = ur_alloc_array(p->samples, sizeof *p->sigma, error);
    if (!p->sigma)
        return UR_ERROR_MEMORY;
    p->first_pairing = unknowns;
    p->unknowns = unknowns + p->samples - 1;
    p->residual_count = 4 * p->samples + (p->samples - 1) + (p->samples - 2);
    for (int r = 0; r < 2; r++)
        if (p->rails[r].moves)
            p->residual_count +=
                (p->rails[r].free_count + p->rails[r].coefficients - 2) * p->axis_count;
    p->strength = 1.0;
    return UR_OK;
}

static void free_problem(problem *p)
{
    for (int r = 0; r < 2; r++) {
        free(p->rails[r].points);
        free(p->rails[r].smoothed);
        ur_curve_free(p->rails[r].curve);
        gsl_matrix_free(p->rails[r].basis);
        gsl_matrix_free(p->rails[r].gram);
    }
    free(p->sigma);
}

/* ---- The first guess ---------------------------------------------------- */

/*
 * The coefficients nearest (least squares) to given displacements of a
 * rail's points, e.g. adjust.c's local repair.
 */
static ur_status fit_displacements(const problem *p, const rail *r, const ur_vec3 *moved,
                                   gsl_vector *x, ur_error *error)
{
    gsl_matrix *design = gsl_matrix_alloc(r->count, r->free_count);
    gsl_matrix *covariance = gsl_matrix_alloc(r->free_count, r->free_count);
    gsl_vector *observed = gsl_vector_alloc(r->count), *fit = gsl_vector_alloc(r->free_count);
    gsl_multifit_linear_workspace *work = gsl_multifit_linear_alloc(r->count, r->free_count);
    ur_status status =
        design && covariance && observed && fit && work ? UR_OK : ur_error_out_of_memory(error);
    for (size_t i = 0; status == UR_OK && i < r->count; i++)
        for (size_t m = 0; m < r->free_count; m++)
            gsl_matrix_set(design, i, m, gsl_matrix_get(r->basis, i, r->first_free + m));
    for (size_t a = 0; status == UR_OK && a < p->axis_count; a++) {
        for (size_t i = 0; i < r->count; i++)
            gsl_vector_set(observed, i, ur_vec3_dot(ur_vec3_sub(moved[i], r->base[i]), p->axes[a]));
        double chi_squared;
        if (gsl_multifit_linear(design, observed, fit, covariance, &chi_squared, work) !=
            GSL_SUCCESS)
            break; /* a poorer first guess, not a failure */
        for (size_t m = 0; m < r->free_count; m++)
            gsl_vector_set(x, r->first_unknown + m * p->axis_count + a, gsl_vector_get(fit, m));
    }
    gsl_matrix_free(design);
    gsl_matrix_free(covariance);
    gsl_vector_free(observed);
    gsl_vector_free(fit);
    if (work)
        gsl_multifit_linear_free(work);
    return status;
}

/*
 * The pairing of the strip on the rails as x places them where it exists,
 * bridged linearly over its gaps and made increasing, as increments.
 */
static void guess_pairing(problem *p, bool proportional, gsl_vector *x)
{
    for (int r = 0; r < 2; r++)
        place_points(p, &p->rails[r], x);
    ur_curve *curves[2] = {NULL, NULL};
    ur_ruled strip;
    bool built = ur_curve_new_interpolating(p->rails[0].points, p->rails[0].count, false,
                                            &curves[0], NULL) == UR_OK &&
                 ur_curve_new_interpolating(p->rails[1].points, p->rails[1].count, false,
                                            &curves[1], NULL) == UR_OK;
    if (!built)
        ur_curve_free(curves[0]);
    built = built && ur_ruled_strip(curves[0], curves[1], &strip, NULL) == UR_OK;
    size_t count2 = p->rails[1].count;
    double end = (double)(count2 - 1);
    for (size_t k = 0; k < p->samples; k++) {
        p->sigma[k] = NAN;
        if (!built)
            continue;
        double u = parameter_at(strip.curve, p->rails[0].count, sample_index(p, k)), sigma, slope;
        const ur_interval *gaps;
        size_t gap_count = ur_ruled_gaps(&strip, &gaps);
        bool in_gap = false;
        for (size_t g = 0; g < gap_count; g++)
            in_gap = in_gap || (u >= gaps[g].u_start && u <= gaps[g].u_end);
        if (in_gap)
            continue;
        ur_ruled_pairing(&strip, u, &sigma, &slope);
        p->sigma[k] = index_at(strip.rail2, count2, sigma);
    }
    if (built)
        ur_ruled_free(&strip);
    if (proportional)
        for (size_t k = 0; k < p->samples; k++)
            p->sigma[k] = NAN;
    p->sigma[0] = 0.0;
    p->sigma[p->samples - 1] = end;
    /* Bridges: each unknown sample between the known ones on either side. */
    for (size_t k = 1; k + 1 < p->samples; k++) {
        if (!isnan(p->sigma[k]))
            continue;
        size_t next = k + 1;
        while (isnan(p->sigma[next]))
            next++;
        double before = p->sigma[k - 1];
        p->sigma[k] = before + (p->sigma[next] - before) / (double)(next - k + 1);
    }
    double floor_step = 1e-3 * end / (double)p->samples;
    for (size_t k = 0; k + 1 < p->samples; k++) {
        double step = fmax(p->sigma[k + 1] - p->sigma[k], floor_step);
        gsl_vector_set(x, p->first_pairing + k, log(step));
    }
}

static ur_status first_guess(problem *p, const ur_vec3 *const starts[2], bool proportional,
                             gsl_vector *x, ur_error *error)
{
    gsl_vector_set_zero(x);
    for (int r = 0; r < 2; r++) {
        if (!starts[r] || !p->rails[r].moves)
            continue;
        ur_status status = fit_displacements(p, &p->rails[r], starts[r], x, error);
        if (status != UR_OK)
            return status;
    }
    guess_pairing(p, proportional, x);
    return UR_OK;
}

/* ---- Solving and checking ----------------------------------------------- */

static bool strip_everywhere(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                             size_t count2, double clearance, bool developable);

/* Whether the rails as x places them have a strip everywhere; they are left so placed. */
static bool placed_everywhere(problem *p, const gsl_vector *x)
{
    for (int r = 0; r < 2; r++)
        place_points(p, &p->rails[r], x);
    return strip_everywhere(p->rails[0].points, p->rails[0].count, p->rails[1].points,
                            p->rails[1].count, 0.0, true);
}

static double squared_norm(const gsl_vector *v)
{
    double norm = gsl_blas_dnrm2(v);
    return norm * norm;
}

/*
 * Levenberg-Marquardt steps from x until the rails have a strip
 * everywhere (looked at every CHECK_EVERY steps: the first such step is
 * the answer, which makes it the same for inputs that differ in their last
 * digits, where the end of a long walk is not), the solver stalls or
 * stops, MAX_ITERATIONS, or the budget of steps runs out.  x is left where
 * it got to.
 */
static ur_status solve(problem *p, gsl_vector *x, size_t *iterations, size_t *budget,
                       bool *everywhere, ur_error *error)
{
    gsl_multifit_nlinear_parameters parameters = gsl_multifit_nlinear_default_parameters();
    /* The pairing's softmax has a direction that changes nothing: plain damping copes. */
    parameters.scale = gsl_multifit_nlinear_scale_levenberg;
    parameters.solver = gsl_multifit_nlinear_solver_cholesky;
    gsl_multifit_nlinear_workspace *solver = gsl_multifit_nlinear_alloc(
        gsl_multifit_nlinear_trust, &parameters, p->residual_count, p->unknowns);
    if (!solver)
        return ur_error_out_of_memory(error);
    gsl_multifit_nlinear_fdf fdf = {residuals, NULL, NULL, p->residual_count, p->unknowns, p,
                                    0,         0,    0};
    *everywhere = false;
    ur_status status = UR_OK;
    if (gsl_multifit_nlinear_init(x, &fdf, solver) != GSL_SUCCESS)
        status = ur_error_set(error, UR_ERROR_INTERNAL,
                              "reshaping the rails: the solver could not start");
    double costs[STALL_CHECKS] = {0};
    size_t checks = 0;
    for (size_t step = 1; status == UR_OK && step <= MAX_ITERATIONS && *budget > 0; step++) {
        --*budget;
        int info, code = gsl_multifit_nlinear_iterate(solver);
        bool still = code != GSL_SUCCESS ||
                     gsl_multifit_nlinear_test(1e-10, 1e-10, 1e-12, &info, solver) != GSL_CONTINUE;
        if (still || step % CHECK_EVERY == 0) {
            *everywhere = placed_everywhere(p, gsl_multifit_nlinear_position(solver));
            status = ur_context_check(p->context, error);
            /* Stalled: the cost fell by less than STALL over the last checks. */
            double cost = squared_norm(gsl_multifit_nlinear_residual(solver));
            still = still ||
                    (checks >= STALL_CHECKS && cost > (1 - STALL) * costs[checks % STALL_CHECKS]);
            costs[checks++ % STALL_CHECKS] = cost;
        }
        if (still || *everywhere)
            break;
    }
    gsl_vector_memcpy(x, gsl_multifit_nlinear_position(solver));
    *iterations += gsl_multifit_nlinear_niter(solver);
    gsl_multifit_nlinear_free(solver);
    return status;
}

/*
 * Whether the strip exists along all of rail 1 with its edge of regression
 * clear of the strip: at each of SAMPLES_PER_POINT samples per point of
 * rail 1 it lies beyond either rail by clearance of the ruling, or at
 * infinity; if developable, the ruling is developable too (the stretched
 * rails can pass by a place where the tracking misses the root).
 */
static bool strip_everywhere(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                             size_t count2, double clearance, bool developable)
{
    ur_ruled strip;
    if (surface_strip_of_points(rail1, count1, rail2, count2, &strip, NULL) != UR_OK)
        return false;
    const ur_interval *gaps;
    bool everywhere = ur_ruled_gaps(&strip, &gaps) == 0;
    double start = ur_ruled_start(&strip), end = ur_ruled_end(&strip);
    size_t samples = SAMPLES_PER_POINT * count1;
    for (size_t k = 0; everywhere && k <= samples; k++) {
        ur_vec3 edge;
        double v, u = start + (end - start) * (double)k / (double)samples;
        if (ur_ruled_regression(&strip, u, &edge, &v))
            everywhere = v < -clearance || v > 1 + clearance;
        if (developable)
            everywhere = everywhere && ur_ruled_residual(&strip, u) <= UR_DEVELOPABLE_RESIDUAL;
    }
    ur_ruled_free(&strip);
    return everywhere;
}

/* ---- Measuring ---------------------------------------------------------- */

/* The mean distance from rail 1's points to the nearest of rail 2's. */
static double rails_distance(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                             size_t count2)
{
    double sum = 0.0;
    for (size_t i = 0; i < count1; i++) {
        double nearest = INFINITY;
        for (size_t j = 0; j < count2; j++)
            nearest = fmin(nearest, ur_vec3_distance(rail1[i], rail2[j]));
        sum += nearest;
    }
    return sum / (double)count1;
}

static double along_polyline(const ur_vec3 *points, size_t index)
{
    double length = 0.0;
    for (size_t i = 0; i < index; i++)
        length += ur_vec3_distance(points[i], points[i + 1]);
    return length;
}

static void measure(const problem *p, ur_rail_repair_report *report)
{
    double sum = 0.0;
    size_t count = 0;
    report->largest = report->mean = 0.0;
    report->largest_rail = 2;
    report->largest_point = 0;
    for (int r = 0; r < 2; r++) {
        const rail *q = &p->rails[r];
        if (!q->moves)
            continue;
        for (size_t i = 0; i < q->count; i++) {
            double moved = ur_vec3_distance(q->points[i], q->original[i]);
            sum += moved;
            count++;
            if (moved > report->largest) {
                report->largest = moved;
                report->largest_rail = r + 1;
                report->largest_point = i;
            }
        }
    }
    report->mean = count ? sum / (double)count : 0.0;
    const rail *at = &p->rails[report->largest_rail - 1];
    report->largest_along = along_polyline(at->original, report->largest_point);
    report->largest_position = at->original[report->largest_point];
}

/* ---- Refusing ----------------------------------------------------------- */

static const char *rail_names[4] = {"", "rail 1", "rail 2", "both rails"};

/* The part of rail 1 the repair is for: the gaps of the strip before it. */
static void describe_gaps(const ur_interval *gaps, size_t gap_count, char *text, size_t size)
{
    if (gap_count == 1)
        c_snprintf(text, size, "from %.1f to %.1f mm along rail 1", gaps[0].arc_start,
                   gaps[0].arc_end);
    else
        c_snprintf(text, size, "from %.1f to %.1f mm along rail 1 (the first of %zu gaps)",
                   gaps[0].arc_start, gaps[0].arc_end, gap_count);
}

static ur_status refuse_too_far(const problem *p, const ur_rail_repair_options *options,
                                const ur_rail_repair_report *report, double limit,
                                const ur_interval *gaps, size_t gap_count, ur_error *error)
{
    char part[160];
    describe_gaps(gaps, gap_count, part, sizeof part);
    const rail *at = &p->rails[report->largest_rail - 1];
    size_t tenth = at->count / 10;
    bool near_end = report->largest_point < tenth || report->largest_point + tenth >= at->count;
    if (near_end && !options->move_ends) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "adjust: %s is too short for a strip %s: with its ends fixed, it would move "
                     "by %.3g mm (%.1f mm along it), more than adjust-max %.3g mm; give "
                     "adjust-ends or a longer rail",
                     rail_names[report->largest_rail], part, report->largest, report->largest_along,
                     limit);
        return ur_error_set_setting(error, "adjust adjust-max adjust-ends");
    }
    ur_error_set(error, UR_ERROR_INPUT,
                 "adjust: a strip %s needs %s moved by %.3g mm (%.1f mm along it), more than "
                 "adjust-max %.3g mm; change the rails' shape there",
                 part, rail_names[report->largest_rail], report->largest, report->largest_along,
                 limit);
    return ur_error_set_setting(error, "adjust adjust-max");
}

/* The gap at the start of rail 1, or else the last one. */
static const ur_interval *at_start_or_end(const ur_ruled *strip, const ur_interval *gaps,
                                          size_t gap_count)
{
    return gaps[0].u_start <= ur_curve_start(strip->curve) ? &gaps[0] : &gaps[gap_count - 1];
}

/* The moves allowed, for a message: "", " along X,Y,Z" or " each in its plane normal to X,Y,Z". */
static void describe_moves(const ur_rail_repair_options *options, char *text, size_t size)
{
    const ur_vec3 *given = options->direction ? options->direction : options->plane_normal;
    if (!given)
        c_snprintf(text, size, "%s", "");
    else
        c_snprintf(text, size,
                   options->direction ? " along %g,%g,%g"
                                      : " (each point in its plane normal to %g,%g,%g)",
                   given->x, given->y, given->z);
}

/*
 * No repair found.  Rail 2 is called too short only when the strip is
 * missing at an end of rail 1 and nowhere else, with the ends fixed.
 */
static ur_status refuse_no_repair(const ur_ruled *strip, const ur_rail_repair_options *options,
                                  double limit, const ur_interval *gaps, size_t gap_count,
                                  ur_error *error)
{
    bool at_start = gaps[0].u_start <= ur_curve_start(strip->curve);
    bool at_end = gaps[gap_count - 1].u_end >= ur_curve_end(strip->curve);
    bool only_at_ends = (size_t)at_start + (size_t)at_end >= gap_count;
    if (only_at_ends && !options->move_ends && !options->direction && !options->plane_normal) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "adjust: the strip is missing at an end of rail 1 (%.1f to %.1f mm along "
                     "it): rail 2 is too short there with its ends fixed; give adjust-ends to let "
                     "them move, or a longer rail 2",
                     at_start_or_end(strip, gaps, gap_count)->arc_start,
                     at_start_or_end(strip, gaps, gap_count)->arc_end);
        return ur_error_set_setting(error, "adjust adjust-ends");
    }
    char part[160], moves[120];
    describe_gaps(gaps, gap_count, part, sizeof part);
    describe_moves(options, moves, sizeof moves);
    ur_error_set(error, UR_ERROR_INPUT,
                 "adjust: no smooth reshaping of %s%s within %.3g mm gives a strip along all of "
                 "rail 1; the strip is missing %s; change the rails' shape there",
                 rail_names[options->rails & UR_REPAIR_BOTH], moves, limit, part);
    return ur_error_set_setting(error, "adjust");
}

/* ---- Keeping the edge of regression clear -------------------------------- */

enum { STRETCHES = 20 };
#define STRETCH 0.05

/* Whether the rails moved by share of their moves have a strip everywhere; they are placed so. */
static bool share_works(problem *p, ur_vec3 *const moves[2], double share)
{
    for (int r = 0; r < 2; r++) {
        rail *q = &p->rails[r];
        for (size_t i = 0; i < q->count; i++)
            q->points[i] =
                moves[r] ? ur_vec3_add_scaled(q->base[i], moves[r][i], share) : q->base[i];
    }
    return strip_everywhere(p->rails[0].points, p->rails[0].count, p->rails[1].points,
                            p->rails[1].count, EDGE_CLEARANCE, true);
}

/* ---- A repair by smoothing ---------------------------------------------- */

enum { BISECTIONS = 12 };
#define SHARE_MARGIN 1.25

static double coordinate(ur_vec3 v, int axis)
{
    return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
}

static void set_coordinate(ur_vec3 *v, int axis, double value)
{
    *(axis == 0 ? &v->x : axis == 1 ? &v->y : &v->z) = value;
}

/*
 * The points of a rail fitted (least squares) by `coefficients` cubic
 * B-splines of the point index, through its end points: the rail with its
 * dents and bumps ironed out.
 */
static ur_status smooth_rail(const rail *r, size_t coefficients, ur_vec3 *smooth, ur_error *error)
{
    size_t inner = coefficients - 2;
    gsl_bspline_workspace *splines = gsl_bspline_alloc(4, coefficients - 2);
    gsl_vector *values = gsl_vector_alloc(coefficients), *fit = gsl_vector_alloc(inner);
    gsl_matrix *basis = gsl_matrix_alloc(r->count, coefficients);
    gsl_matrix *design = gsl_matrix_alloc(r->count, inner);
    gsl_matrix *covariance = gsl_matrix_alloc(inner, inner);
    gsl_vector *observed = gsl_vector_alloc(r->count);
    gsl_multifit_linear_workspace *work = gsl_multifit_linear_alloc(r->count, inner);
    ur_status status = splines && values && fit && basis && design && covariance && observed && work
                           ? UR_OK
                           : ur_error_out_of_memory(error);
    if (status == UR_OK) {
        gsl_bspline_knots_uniform(0.0, (double)(r->count - 1), splines);
        for (size_t i = 0; i < r->count; i++) {
            gsl_bspline_eval((double)i, values, splines);
            gsl_matrix_set_row(basis, i, values);
        }
        gsl_matrix_const_view middle = gsl_matrix_const_submatrix(basis, 0, 1, r->count, inner);
        gsl_matrix_memcpy(design, &middle.matrix);
    }
    const ur_vec3 first = r->original[0], last = r->original[r->count - 1];
    for (int axis = 0; status == UR_OK && axis < 3; axis++) {
        for (size_t i = 0; i < r->count; i++) {
            double ends = coordinate(first, axis) * gsl_matrix_get(basis, i, 0) +
                          coordinate(last, axis) * gsl_matrix_get(basis, i, coefficients - 1);
            gsl_vector_set(observed, i, coordinate(r->original[i], axis) - ends);
        }
        double chi_squared;
        if (gsl_multifit_linear(design, observed, fit, covariance, &chi_squared, work) !=
            GSL_SUCCESS) {
            status =
                ur_error_set(error, UR_ERROR_INTERNAL, "reshaping the rails: smoothing failed");
            break;
        }
        for (size_t i = 0; i < r->count; i++) {
            double ends = coordinate(first, axis) * gsl_matrix_get(basis, i, 0) +
                          coordinate(last, axis) * gsl_matrix_get(basis, i, coefficients - 1);
            gsl_vector_const_view row = gsl_matrix_const_row(design, i);
            double value;
            gsl_blas_ddot(&row.vector, fit, &value);
            set_coordinate(&smooth[i], axis, ends + value);
        }
    }
    if (splines)
        gsl_bspline_free(splines);
    gsl_vector_free(values);
    gsl_vector_free(fit);
    gsl_matrix_free(basis);
    gsl_matrix_free(design);
    gsl_matrix_free(covariance);
    gsl_vector_free(observed);
    if (work)
        gsl_multifit_linear_free(work);
    return status;
}

/* The moves from a rail to its smoothed points, along the directions the points may move. */
static void allowed_moves(const problem *p, const rail *r, ur_vec3 *moves)
{
    for (size_t i = 0; i < r->count; i++) {
        ur_vec3 move = ur_vec3_sub(moves[i], r->base[i]), allowed = ur_vec3_make(0, 0, 0);
        for (size_t a = 0; a < p->axis_count; a++)
            allowed = ur_vec3_add_scaled(allowed, p->axes[a], ur_vec3_dot(move, p->axes[a]));
        moves[i] = allowed;
    }
}

/* Smooths the moving rails with `coefficients` B-splines; moves[r] gets each point's move. */
static ur_status smoothing_moves(const problem *p, size_t coefficients, ur_vec3 *const moves[2],
                                 ur_error *error)
{
    for (int r = 0; r < 2; r++) {
        if (!moves[r])
            continue;
        const rail *q = &p->rails[r];
        ur_status status =
            smooth_rail(q, coefficients < q->count ? coefficients : q->count, moves[r], error);
        if (status != UR_OK)
            return status;
        allowed_moves(p, q, moves[r]);
    }
    return UR_OK;
}

/*
 * The rails moved by the smallest share of moves (which work in whole)
 * that gives a strip everywhere, found by bisection; they are left so
 * placed.
 */
static ur_status least_share(problem *p, ur_vec3 *const moves[2], ur_error *error)
{
    double low = 0.0, high = 1.0;
    ur_status status = UR_OK;
    for (int step = 0; status == UR_OK && step < BISECTIONS; step++) {
        double middle = 0.5 * (low + high);
        if (share_works(p, moves, middle))
            high = middle;
        else
            low = middle;
        status = ur_context_check(p->context, error);
    }
    /*
     * The bisection ends next to rails with no strip, where the strip is
     * nearly singular; a little further from them, when that works too.
     */
    if (status == UR_OK && !share_works(p, moves, fmin(1.0, SHARE_MARGIN * high)))
        share_works(p, moves, high);
    return status;
}

/* Room for a move of each point of each moving rail (NULL for a fixed one); free both. */
static ur_status alloc_moves(const problem *p, ur_vec3 *moves[2], ur_error *error)
{
    for (int r = 0; r < 2; r++)
        if (p->rails[r].moves) {
            moves[r] = ur_alloc_array(p->rails[r].count, sizeof *moves[r], error);
            if (!moves[r])
                return UR_ERROR_MEMORY;
        }
    return UR_OK;
}

/*
 * A repair by smoothing: the moving rails smoothed with fewer
 * and fewer B-splines until the strip between them exists everywhere (the
 * smoothing irons out the dent or bump that caused the gap, so the
 * displacement stays below its size), then moved only the smallest share
 * of the way there that keeps it so (bisection).  The rails are left so
 * placed when it works (report->everywhere).
 */
static ur_status repair_by_smoothing(problem *p, ur_rail_repair_report *report, ur_error *error)
{
    static const size_t coefficient_counts[] = {12, 8, 6, 5, 4};
    ur_vec3 *moves[2] = {NULL, NULL};
    ur_status status = alloc_moves(p, moves, error);
    bool found = false;
    size_t levels = sizeof coefficient_counts / sizeof *coefficient_counts;
    for (size_t level = 0; status == UR_OK && !found && level < levels; level++) {
        status = smoothing_moves(p, coefficient_counts[level], moves, error);
        if (status == UR_OK)
            found = share_works(p, moves, 1.0);
    }
    if (found && status == UR_OK)
        status = least_share(p, moves, error);
    if (found && status == UR_OK) {
        report->everywhere = true;
        report->smoothed = true;
    }
    free(moves[0]);
    free(moves[1]);
    return status;
}

/* ---- The whole repair --------------------------------------------------- */

/* adjust.c's local repair of rail 2, when there is one, as a first guess; else NULL. */
static ur_vec3 *local_repair(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                             size_t count2, const ur_rail_repair_options *options)
{
    if (!(options->rails & UR_REPAIR_RAIL2) || options->plane_normal)
        return NULL;
    ur_vec3 *moved = malloc(count2 * sizeof *moved);
    if (!moved)
        return NULL;
    memcpy(moved, rail2, count2 * sizeof *moved);
    double largest;
    if (ur_strip_adjust_rail2(rail1, count1, moved, count2, options->direction, &largest, NULL) !=
        UR_OK) {
        free(moved);
        return NULL;
    }
    return moved;
}

/*
 * One attempt from one first guess, in rounds that weigh the penalties ten
 * times more while the strip is not everywhere.
 */
static ur_status attempt(problem *p, const ur_vec3 *const starts[2], bool proportional,
                         size_t *budget, ur_rail_repair_report *report, ur_error *error)
{
    gsl_vector *x = gsl_vector_alloc(p->unknowns);
    if (!x)
        return ur_error_out_of_memory(error);
    ur_status status = first_guess(p, starts, proportional, x, error);
    report->everywhere = false;
    p->strength = 1.0;
    for (int round = 0; status == UR_OK && round < ROUNDS && !report->everywhere; round++) {
        status = solve(p, x, &report->iterations, budget, &report->everywhere, error);
        if (status != UR_OK)
            break;
        p->strength *= 10;
    }
    gsl_vector_free(x);
    return status;
}

/* The unit normal of the strip along a ruling, from its ends as ur_ruled_rails gives them. */
static ur_vec3 strip_normal(const ur_vec3 rails[4])
{
    ur_vec3 normal = ur_vec3_cross(rails[1], ur_vec3_sub(rails[2], rails[0]));
    return ur_vec3_scale(normal, 1.0 / ur_vec3_length(normal));
}

/* The speed of a ruling's end across the ruling (direction the ruling's unit vector). */
static double speed_across(ur_vec3 velocity, ur_vec3 direction)
{
    return ur_vec3_length(
        ur_vec3_add_scaled(velocity, direction, -ur_vec3_dot(velocity, direction)));
}

/*
 * The smallest bend radius of the strip between the rails as placed, at
 * both ends of SAMPLES_PER_POINT rulings per point of rail 1: on a
 * developable the curvature across a ruling varies as one over the
 * distance from the edge of regression, so it is largest at an end.
 * There the radius is the end's speed across the ruling over the rate at
 * which the tangent plane's normal turns.  0 when there is no strip.
 */
static double smallest_bend_radius(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                                   size_t count2)
{
    ur_ruled strip;
    if (surface_strip_of_points(rail1, count1, rail2, count2, &strip, NULL) != UR_OK)
        return 0.0;
    double start = ur_ruled_start(&strip), end = ur_ruled_end(&strip), smallest = INFINITY;
    size_t samples = SAMPLES_PER_POINT * count1;
    double step = (end - start) / (double)samples;
    for (size_t k = 1; k < samples; k++) {
        ur_vec3 here[4], before[4], after[4];
        double u = start + step * (double)k;
        ur_ruled_rails(&strip, u, here);
        ur_ruled_rails(&strip, u - 0.5 * step, before);
        ur_ruled_rails(&strip, u + 0.5 * step, after);
        double turning = ur_vec3_distance(strip_normal(after), strip_normal(before)) / step;
        ur_vec3 ruling = ur_vec3_sub(here[2], here[0]);
        ur_vec3 direction = ur_vec3_scale(ruling, 1.0 / ur_vec3_length(ruling));
        double across = fmin(speed_across(here[1], direction), speed_across(here[3], direction));
        if (turning > 0)
            smallest = fmin(smallest, across / turning);
    }
    ur_ruled_free(&strip);
    return smallest;
}

static bool placed_bend_radius_enough(const problem *p)
{
    return smallest_bend_radius(p->rails[0].points, p->rails[0].count, p->rails[1].points,
                                p->rails[1].count) >= p->bend;
}

/*
 * A repair that only just straightens what was in the way leaves the edge
 * of regression near a rail, where the rulings crowd together and the
 * strip bends as sharply as a crease.  Its displacement is then made a
 * little larger: the smallest of STRETCHES steps of STRETCH that keeps the
 * edge clear and bends no tighter than p->bend; when none does, the
 * smallest that keeps the edge clear; when none does either, the repair as
 * it is, told so.
 */
static ur_status ease_the_bend(problem *p, ur_rail_repair_report *report, ur_error *error)
{
    if (strip_everywhere(p->rails[0].points, p->rails[0].count, p->rails[1].points,
                         p->rails[1].count, EDGE_CLEARANCE, false) &&
        placed_bend_radius_enough(p))
        return UR_OK;
    ur_vec3 *moves[2] = {NULL, NULL};
    ur_status status = alloc_moves(p, moves, error);
    for (int r = 0; status == UR_OK && r < 2; r++)
        for (size_t i = 0; moves[r] && i < p->rails[r].count; i++)
            moves[r][i] = ur_vec3_sub(p->rails[r].points[i], p->rails[r].base[i]);
    double clear = 0.0, eased = 0.0;
    for (int step = 1; status == UR_OK && !(eased > 0) && step <= STRETCHES; step++) {
        double share = 1.0 + STRETCH * step;
        if (share_works(p, moves, share)) {
            clear = clear > 0 ? clear : share;
            eased = placed_bend_radius_enough(p) ? share : 0.0;
        }
        status = ur_context_check(p->context, error);
    }
    if (status == UR_OK && !(eased > 0)) {
        share_works(p, moves, clear > 0 ? clear : 1.0);
        report->edge_too_close = !(clear > 0);
    }
    free(moves[0]);
    free(moves[1]);
    return status;
}

/*
 * First by smoothing, which is quick and irons out a dent or a bump; when
 * no smoothing gives a strip everywhere, by the solver, the pairing
 * guessed first in proportion along the rails, which lets the solver
 * straighten a fold, then as the strip on the start rails pairs them where
 * it exists, which stays near a repair of the ends.  A solver's repair
 * whose edge of regression comes close to a rail (the strip would bend
 * sharply there) is stretched until the edge is clear.
 */
static ur_status repair(problem *p, const ur_vec3 *local, ur_rail_repair_report *report,
                        ur_error *error)
{
    ur_status status = repair_by_smoothing(p, report, error);
    const ur_vec3 *starts[2] = {NULL, local};
    size_t budget = SOLVER_BUDGET;
    if (status == UR_OK && !report->everywhere)
        status = attempt(p, starts, true, &budget, report, error);
    if (status == UR_OK && !report->everywhere)
        status = attempt(p, starts, false, &budget, report, error);
    if (status == UR_OK && report->everywhere)
        status = ease_the_bend(p, report, error);
    if (status == UR_OK)
        measure(p, report);
    return status;
}

/*
 * adjust.c's local repair, when it gives a strip everywhere and moves rail
 * 2 less than the global one (or the global one failed), is the answer: it
 * moves only a window of rail 2 round each gap.
 */
static void prefer_local_repair(problem *p, const ur_vec3 *start, bool move_ends,
                                ur_rail_repair_report *report)
{
    rail *two = &p->rails[1];
    if (!start || !two->moves || p->rails[0].moves)
        return;
    bool ends_moved = ur_vec3_distance(start[0], two->original[0]) > 0 ||
                      ur_vec3_distance(start[two->count - 1], two->original[two->count - 1]) > 0;
    if (ends_moved && !move_ends)
        return;
    double largest = 0.0;
    for (size_t i = 0; i < two->count; i++)
        largest = fmax(largest, ur_vec3_distance(start[i], two->original[i]));
    if (report->everywhere && largest >= report->largest)
        return;
    if (!strip_everywhere(p->rails[0].points, p->rails[0].count, start, two->count, EDGE_CLEARANCE,
                          false))
        return;
    /* A repair that bends as it should is not traded for a smaller one that does not. */
    if (report->everywhere && !report->edge_too_close &&
        smallest_bend_radius(p->rails[0].points, p->rails[0].count, start, two->count) < p->bend)
        return;
    memcpy(two->points, start, two->count * sizeof *two->points);
    report->everywhere = true;
    report->used_local_repair = true;
    measure(p, report);
}

static ur_status repair_rails(ur_vec3 *rail1, size_t count1, ur_vec3 *rail2, size_t count2,
                              const ur_rail_repair_options *options, ur_rail_repair_report *report,
                              ur_error *error)
{
    memset(report, 0, sizeof *report);
    report->largest_rail = 2;
    if (!(options->rails & UR_REPAIR_BOTH))
        return ur_error_set(error, UR_ERROR_INPUT, "reshaping the rails: say which rails move");
    if (count1 < 4 || count2 < 4)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "reshaping the rails: each rail needs at least 4 points");
    problem p = {.rails = {{.original = rail1,
                            .count = count1,
                            .moves = (options->rails & UR_REPAIR_RAIL1) != 0},
                           {.original = rail2,
                            .count = count2,
                            .moves = (options->rails & UR_REPAIR_RAIL2) != 0}},
                 .context = options->context};
    ur_status status = set_axes(&p, options, error);
    if (status != UR_OK)
        return status;
    ur_ruled strip;
    status = surface_strip_of_points(rail1, count1, rail2, count2, &strip, error);
    if (status != UR_OK)
        return status;
    const ur_interval *gaps;
    size_t gap_count = ur_ruled_gaps(&strip, &gaps);
    report->everywhere = gap_count == 0;
    if (gap_count == 0) {
        ur_ruled_free(&strip);
        return UR_OK;
    }
    double distance = rails_distance(rail1, count1, rail2, count2);
    double limit = options->max_displacement > 0 ? options->max_displacement : 0.25 * distance;
    report->limit = limit;
    p.bend = BEND * distance;
    ur_vec3 *start = local_repair(rail1, count1, rail2, count2, options);
    report->from_local_repair = start != NULL;
    status = set_up(&p, options, error);
    if (status == UR_OK)
        status = repair(&p, start, report, error);
    if (status == UR_OK)
        prefer_local_repair(&p, start, options->move_ends, report);
    free(start);
    if (status == UR_OK && report->largest > limit)
        status = refuse_too_far(&p, options, report, limit, gaps, gap_count, error);
    if (status == UR_OK && !report->everywhere)
        status = refuse_no_repair(&strip, options, limit, gaps, gap_count, error);
    if (status == UR_OK) {
        memcpy(rail1, p.rails[0].points, count1 * sizeof *rail1);
        memcpy(rail2, p.rails[1].points, count2 * sizeof *rail2);
    }
    ur_ruled_free(&strip);
    free_problem(&p);
    return status;
}

ur_status ur_rails_repair(ur_vec3 *rail1, size_t count1, ur_vec3 *rail2, size_t count2,
                          const ur_rail_repair_options *options, ur_rail_repair_report *report,
                          ur_error *error)
{
    gsl_errors_off();
    ur_status status = repair_rails(rail1, count1, rail2, count2, options, report, error);
    gsl_errors_restore();
    return status;
}
