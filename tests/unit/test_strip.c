/*
 * test_strip.c: developable strips between two rails against closed forms
 * (frustum, cylinder, a helix's tangent developable), the domain of
 * existence, and general ruled surfaces (the hyperbolic paraboloid).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/analyze.h"
#include "unroll/develop.h"

#include "test_support.h"

/* Points of a circle arc of radius r at height z, angles from a to b. */
static ur_curve *arc(double r, double z, double a, double b, size_t n, bool closed)
{
    ur_vec3 *points = malloc(n * sizeof *points);
    assert_non_null(points);
    for (size_t i = 0; i < n; i++) {
        double t = closed ? a + (b - a) * (double)i / (double)n
                          : a + (b - a) * (double)i / (double)(n - 1);
        points[i] = ur_vec3_make(r * cos(t), r * sin(t), z);
    }
    ur_curve *curve;
    ur_error error;
    if (ur_curve_new_interpolating(points, n, closed, &curve, &error) != UR_OK)
        fail_msg("%s", error.message);
    free(points);
    return curve;
}

static ur_ruled strip(ur_curve *rail1, ur_curve *rail2)
{
    ur_ruled ruled;
    ur_error error;
    if (ur_ruled_strip(rail1, rail2, &ruled, &error) != UR_OK)
        fail_msg("strip: %s", error.message);
    return ruled;
}

/* The exact development, with the default 24 rulings drawn. */
static ur_net_list develop_exact(ur_ruled *ruled, double tolerance)
{
    return develop(ruled, UR_METHOD_EXACT, 24, tolerance);
}

/* Two coaxial circles: the frustum, a sector of an annulus when flat. */
static void test_strip_between_circles_is_a_frustum(void **state)
{
    (void)state;
    double r1 = 50, r2 = 20, h = 40;
    ur_ruled ruled = strip(arc(r1, 0, 0, 2 * M_PI, 400, true), arc(r2, h, 0, 2 * M_PI, 400, true));
    const ur_interval *gaps;
    assert_int_equal(ur_ruled_gaps(&ruled, &gaps), 0);
    assert_true(ur_ruled_is_closed(&ruled));
    /* The pairing keeps the angle: every ruling meets the axis at the apex. */
    double slant = sqrt((r1 - r2) * (r1 - r2) + h * h);
    for (int k = 0; k < 16; k++) {
        double u =
            ur_ruled_start(&ruled) + (ur_ruled_end(&ruled) - ur_ruled_start(&ruled)) * k / 16;
        ur_vec3 rails[4];
        ur_ruled_rails(&ruled, u, rails);
        assert_relative(ur_vec3_distance(rails[0], rails[2]), slant, 1e-6);
        ur_vec3 edge;
        double v;
        assert_true(ur_ruled_regression(&ruled, u, &edge, &v));
        assert_relative(v, r1 / (r1 - r2), 1e-5);
        assert_true(fabs(edge.x) < 1e-4 && fabs(edge.y) < 1e-4);
        assert_relative(edge.z, h * r1 / (r1 - r2), 1e-6);
        assert_true(ur_ruled_residual(&ruled, u) < 1e-9);
    }
    ur_net_list nets = develop_exact(&ruled, 1e-4);
    double flat = 0;
    for (size_t k = 0; k < nets.count; k++)
        flat += nets.nets[k].flat_area;
    assert_relative(flat, M_PI * (r1 + r2) * slant, 1e-6);
    /* The outline: outer arc of radius l1, inner of radius l2, about the flat apex. */
    double l1 = r1 * slant / (r1 - r2), l2 = r2 * slant / (r1 - r2);
    const ur_net *net = &nets.nets[0];
    double perimeter = 0;
    for (size_t i = 0; i < net->outline_count; i++)
        perimeter += ur_vec2_distance(net->outline[i], net->outline[(i + 1) % net->outline_count]);
    assert_relative(perimeter, 2 * M_PI * (r1 + r2) + 2 * slant, 1e-6);
    assert_relative(M_PI * (l1 * l1 - l2 * l2) * (r1 / l1), M_PI * (r1 + r2) * slant, 1e-12);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* A curve and a translated copy: a cylinder, a rectangle over the right section. */
static void test_strip_to_translated_copy_is_a_cylinder(void **state)
{
    (void)state;
    enum { N = 120 };
    ur_vec3 lower[N], upper[N];
    ur_vec3 shift = ur_vec3_make(0, 0, 30);
    for (int i = 0; i < N; i++) {
        double t = 2.0 * i / (N - 1);
        lower[i] = ur_vec3_make(60 * cos(t), 35 * sin(t), 0);
        upper[i] = ur_vec3_add(lower[i], shift);
    }
    ur_curve *rail1, *rail2;
    assert_int_equal(ur_curve_new_interpolating(lower, N, false, &rail1, NULL), UR_OK);
    assert_int_equal(ur_curve_new_interpolating(upper, N, false, &rail2, NULL), UR_OK);
    double length;
    assert_int_equal(
        ur_curve_length(rail1, ur_curve_start(rail1), ur_curve_end(rail1), &length, NULL), UR_OK);
    ur_ruled ruled = strip(rail1, rail2);
    const ur_interval *gaps;
    assert_int_equal(ur_ruled_gaps(&ruled, &gaps), 0);
    ur_vec3 edge;
    double v;
    assert_false(ur_ruled_regression(&ruled, 0.5 * ur_ruled_end(&ruled), &edge, &v));
    ur_net_list nets = develop_exact(&ruled, 1e-4);
    assert_int_equal(nets.count, 1);
    assert_relative(nets.nets[0].flat_area, 30 * length, 1e-6);
    /* A rectangle: its bounding box is the right section's length by the height. */
    ur_box box = ur_box_of_points(nets.nets[0].outline, nets.nets[0].outline_count);
    double w = box.max.x - box.min.x, hgt = box.max.y - box.min.y;
    double along = fmax(w, hgt), across = fmin(w, hgt);
    (void)along;
    assert_relative(across, 30, 1e-6);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* The helix (r cos t, r sin t, c t) and its unit tangent at t. */
static void helix(double r, double c, double t, ur_vec3 *point, ur_vec3 *tangent)
{
    *point = ur_vec3_make(r * cos(t), r * sin(t), c * t);
    double s = sqrt(r * r + c * c);
    *tangent = ur_vec3_make(-r * sin(t) / s, r * cos(t) / s, c / s);
}

/*
 * Two curves on the tangent developable of a helix: the strip between them
 * is that developable, and its edge of regression is the helix.
 */
static void test_strip_recovers_tangent_developable(void **state)
{
    (void)state;
    enum { N = 300 };
    double r = 30, c = 10;
    ur_vec3 near[N], far[N];
    for (int i = 0; i < N; i++) {
        double t = 2.0 * i / (N - 1), t2 = -0.2 + 2.4 * i / (N - 1);
        ur_vec3 p, e;
        helix(r, c, t, &p, &e);
        near[i] = ur_vec3_add_scaled(p, e, 5);
        helix(r, c, t2, &p, &e);
        far[i] = ur_vec3_add_scaled(p, e, 25 + 4 * sin(3 * t2));
    }
    ur_curve *rail1, *rail2;
    assert_int_equal(ur_curve_new_interpolating(near, N, false, &rail1, NULL), UR_OK);
    assert_int_equal(ur_curve_new_interpolating(far, N, false, &rail2, NULL), UR_OK);
    ur_ruled ruled = strip(rail1, rail2);
    const ur_interval *gaps;
    assert_int_equal(ur_ruled_gaps(&ruled, &gaps), 0);
    double size = 60, worst = 0;
    for (int k = 0; k <= 200; k++) {
        double u =
            ur_ruled_start(&ruled) + (ur_ruled_end(&ruled) - ur_ruled_start(&ruled)) * k / 200;
        ur_vec3 edge;
        double v;
        assert_true(ur_ruled_regression(&ruled, u, &edge, &v));
        assert_true(v < 0);
        /* The nearest helix point: the edge lies on the helix at the same height. */
        double t = edge.z / c;
        ur_vec3 on_helix, tangent;
        helix(r, c, t, &on_helix, &tangent);
        worst = fmax(worst, ur_vec3_distance(edge, on_helix));
        /* And the ruling is the helix's tangent there. */
        ur_vec3 rails[4];
        ur_ruled_rails(&ruled, u, rails);
        ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]);
        double sine = ur_vec3_length(ur_vec3_cross(ruling, tangent)) / ur_vec3_length(ruling);
        assert_true(sine < 1e-4);
    }
    if (!(worst <= 1e-4 * size))
        fail_msg("edge of regression %.3g mm from the helix", worst);
    ur_ruled_free(&ruled);
}

/* Rail 2 starts later than rail 1: no ruling reaches it from rail 1's start. */
static void test_domain_of_existence(void **state)
{
    (void)state;
    double r1 = 50, r2 = 30, h = 40, late = 0.4;
    ur_ruled ruled = strip(arc(r1, 0, 0, M_PI, 300, false), arc(r2, h, late, M_PI, 300, false));
    const ur_interval *gaps;
    size_t count = ur_ruled_gaps(&ruled, &gaps);
    assert_int_equal(count, 1);
    assert_int_equal(gaps[0].reason, UR_GAP_NO_RULING);
    assert_true(gaps[0].u_start == ur_curve_start(ruled.curve));
    /* The frustum's ruling at angle `late` is the first that reaches rail 2. */
    assert_relative(gaps[0].arc_end, r1 * late, 1e-6);
    ur_interval parts[4];
    assert_int_equal(ur_ruled_domain(&ruled, parts, 4), 1);
    assert_relative(parts[0].arc_start, r1 * late, 1e-6);
    /* Developing the whole strip is refused; the part that exists develops exactly. */
    ur_develop_options options;
    ur_develop_options_default(&options);
    ur_net_list nets;
    ur_error error;
    assert_int_equal(ur_develop(&ruled, &options, &nets, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "does not exist"));
    ur_ruled_restrict(&ruled, parts[0].u_start, parts[0].u_end);
    nets = develop_exact(&ruled, 1e-4);
    double slant = sqrt((r1 - r2) * (r1 - r2) + h * h);
    assert_relative(nets.nets[0].flat_area, 0.5 * (r1 + r2) * slant * (M_PI - late), 1e-6);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

static void arc_points(ur_vec3 *points, double r, double z, double a, double b, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double t = a + (b - a) * (double)i / (double)(n - 1);
        points[i] = ur_vec3_make(r * cos(t), r * sin(t), z);
    }
}

static size_t gaps_between(const ur_vec3 *rail1, const ur_vec3 *rail2, size_t n)
{
    ur_curve *c1, *c2;
    assert_int_equal(ur_curve_new_interpolating(rail1, n, false, &c1, NULL), UR_OK);
    assert_int_equal(ur_curve_new_interpolating(rail2, n, false, &c2, NULL), UR_OK);
    ur_ruled ruled = strip(c1, c2);
    const ur_interval *gaps;
    size_t count = ur_ruled_gaps(&ruled, &gaps);
    ur_ruled_free(&ruled);
    return count;
}

/*
 * Rail 2 starts 0.3 rad late on its circle, so the first 15 mm of rail 1
 * have no ruling.  Worked by hand: sliding rail 2 along its own circle until
 * it starts with rail 1 repairs it (the strip is then the frustum), moving
 * its first point by the chord 2 r2 sin(0.15); the smallest repair can be no
 * larger.  Far from the gap nothing moves.
 */
static void test_adjust_rail2_repairs_a_short_rail(void **state)
{
    (void)state;
    enum { N = 60 };
    ur_vec3 rail1[N], rail2[N], before[N];
    arc_points(rail1, 50, 0, 0, M_PI, N);
    arc_points(rail2, 30, 40, 0.3, M_PI, N);
    memcpy(before, rail2, sizeof before);
    assert_int_equal(gaps_between(rail1, rail2, N), 1);
    double largest;
    ur_error error;
    if (ur_strip_adjust_rail2(rail1, N, rail2, N, NULL, &largest, &error) != UR_OK)
        fail_msg("adjust: %s", error.message);
    assert_int_equal(gaps_between(rail1, rail2, N), 0);
    double by_hand = 2 * 30 * sin(0.15), measured = 0;
    for (int j = 0; j < N; j++)
        measured = fmax(measured, ur_vec3_distance(rail2[j], before[j]));
    assert_relative(largest, measured, 1e-12);
    if (!(largest > 0 && largest <= by_hand))
        fail_msg("moved %g mm; sliding along the circle moves %g", largest, by_hand);
    for (int j = 20; j < N; j++)
        assert_true(ur_vec3_distance(rail2[j], before[j]) == 0);
    /* Along z only: x and y stay exactly, and the strip exists everywhere. */
    memcpy(rail2, before, sizeof before);
    ur_vec3 up = {0, 0, 2};
    if (ur_strip_adjust_rail2(rail1, N, rail2, N, &up, &largest, &error) != UR_OK)
        fail_msg("adjust along z: %s", error.message);
    assert_int_equal(gaps_between(rail1, rail2, N), 0);
    for (int j = 0; j < N; j++)
        assert_true(rail2[j].x == before[j].x && rail2[j].y == before[j].y);
    assert_true(largest > 0 && largest <= by_hand);
}

/* The twisted cubic g(t) = (30 t, 15 t^2, 6 t^3) and a point d along its tangent. */
static ur_vec3 along_cubic(double t, double d, double lift)
{
    ur_vec3 g = ur_vec3_make(30 * t, 15 * t * t, 6 * t * t * t);
    ur_vec3 g1 = ur_vec3_make(30, 30 * t, 18 * t * t), g2 = ur_vec3_make(0, 30, 36 * t);
    ur_vec3 binormal = ur_vec3_cross(g1, g2);
    ur_vec3 point = ur_vec3_add_scaled(g, g1, d / ur_vec3_length(g1));
    return ur_vec3_add_scaled(point, binormal, lift / ur_vec3_length(binormal));
}

/*
 * Rail 2 on the cubic's tangent developable but for a 1 mm bump off it: the
 * pairing jumps to another branch there (the rulings in between would
 * cross), so the strip splits in two.  Each piece on its own branch must
 * still be an isometry: flat area and rail lengths as in 3D.
 */
static void test_pieces_on_both_sides_of_a_jump(void **state)
{
    (void)state;
    enum { N = 81 };
    ur_vec3 near[N], far[N];
    for (int i = 0; i < N; i++) {
        double t = -1.5 + 3.0 * i / (N - 1);
        near[i] = along_cubic(t, 30, 0);
        far[i] = along_cubic(t, 70 + 8 * sin(2 * t), exp(-pow((t - 0.5) / 0.1, 2)));
    }
    ur_curve *c1, *c2;
    assert_int_equal(ur_curve_new_interpolating(near, N, false, &c1, NULL), UR_OK);
    assert_int_equal(ur_curve_new_interpolating(far, N, false, &c2, NULL), UR_OK);
    ur_ruled ruled = strip(c1, c2);
    ur_interval parts[4];
    size_t count = ur_ruled_domain(&ruled, parts, 4);
    assert_true(count >= 2 && count <= 4);
    for (size_t k = 0; k < count; k++) {
        ur_ruled_restrict(&ruled, parts[k].u_start, parts[k].u_end);
        ur_net_list nets = develop_exact(&ruled, 1e-3);
        for (size_t j = 0; j < nets.count; j++) {
            assert_relative(nets.nets[j].flat_area, nets.nets[j].area_3d, 1e-5);
            assert_true(nets.nets[j].edge_error < 1e-5);
        }
        ur_net_list_free(&nets);
    }
    ur_ruled_free(&ruled);
}

/*
 * A sine wave y = 20 sin(2 pi x / 100), x from `from` to `to`, through n
 * points: inflections at every multiple of 50.  From 0 to 200 (sine_points)
 * it has two whole waves and five inflections, two of them on its ends, and
 * with n - 1 a multiple of 4 they fall on points, else between them.
 */
static void sine_points_from(ur_vec3 *points, size_t n, double from, double to)
{
    for (size_t i = 0; i < n; i++) {
        double x = from + (to - from) * (double)i / (double)(n - 1);
        points[i] = ur_vec3_make(x, 20 * sin(2 * M_PI * x / 100), 0);
    }
}

static void sine_points(ur_vec3 *points, size_t n)
{
    sine_points_from(points, n, 0, 200);
}

/* The turning of a plane curve in z = 0 at u: the sign of its curvature. */
static double turning(ur_curve *curve, double u)
{
    ur_vec3 d[3];
    ur_curve_eval(curve, u, d);
    return ur_vec3_cross(d[1], d[2]).z;
}

/*
 * The parameters of rail 1 (a sine wave in z = 0) at its inflections, found
 * where the sign of its curvature changes (bisected), and at its ends (where
 * the sample waves have inflections too), and just beside them.
 */
static size_t places_at_inflections(ur_curve *rail1, double *places)
{
    enum { SCAN = 4000 };
    double u0 = ur_curve_start(rail1), u1 = ur_curve_end(rail1), found[16];
    size_t inflections = 0;
    found[inflections++] = u0;
    found[inflections++] = u1;
    for (int k = 0; k < SCAN && inflections < 16; k++) {
        double low = u0 + (u1 - u0) * k / SCAN, high = u0 + (u1 - u0) * (k + 1) / SCAN;
        if (turning(rail1, low) * turning(rail1, high) >= 0)
            continue;
        for (int step = 0; step < 100; step++) {
            double middle = 0.5 * (low + high);
            if (turning(rail1, low) * turning(rail1, middle) <= 0)
                high = middle;
            else
                low = middle;
        }
        found[inflections++] = 0.5 * (low + high);
    }
    assert_true(inflections >= 5);
    size_t count = 0;
    for (size_t k = 0; k < inflections; k++) {
        const double offsets[] = {0, 1e-9, -1e-9, 1e-6, -1e-6, 1e-4, -1e-4, 1e-2, -1e-2};
        for (size_t j = 0; j < sizeof offsets / sizeof offsets[0]; j++) {
            double place = found[k] + offsets[j] * (u1 - u0);
            if (place >= u0 && place <= u1)
                places[count++] = place;
        }
    }
    return count;
}

/* Simpson's rule with `steps` (even) steps of f over [a, b]: an independent quadrature. */
static double simpson(double (*f)(ur_curve *, double, const void *), ur_curve *curve,
                      const void *data, double a, double b, int steps)
{
    double h = (b - a) / steps, sum = f(curve, a, data) + f(curve, b, data);
    for (int k = 1; k < steps; k++)
        sum += (k % 2 ? 4 : 2) * f(curve, a + h * k, data);
    return sum * h / 3;
}

/* |c'| x |d|: the area density of the cylinder of c along the translation d. */
static double cylinder_density(ur_curve *curve, double u, const void *data)
{
    ur_vec3 d[3];
    ur_curve_eval(curve, u, d);
    return ur_vec3_length(ur_vec3_cross(d[1], *(const ur_vec3 *)data));
}

/* |(c - A) x c'| / 2: the area density of the cone from the apex A to c. */
static double cone_density(ur_curve *curve, double u, const void *data)
{
    ur_vec3 d[3];
    ur_curve_eval(curve, u, d);
    return 0.5 * ur_vec3_length(ur_vec3_cross(ur_vec3_sub(d[0], *(const ur_vec3 *)data), d[1]));
}

static bool analyzed_developable(ur_ruled *ruled)
{
    ur_analysis analysis;
    ur_error error;
    if (ur_analyze(ruled, NULL, &analysis, &error) != UR_OK)
        fail_msg("analyze: %s", error.message);
    bool developable = analysis.developable;
    ur_analysis_free(&analysis);
    return developable;
}

/*
 * The exact net of a strip without gaps against the area computed
 * independently: one piece, flat area and 3D area as expected, every
 * boundary length kept.
 */
static void assert_develops_within(ur_ruled *ruled, double expected, double tolerance)
{
    ur_net_list nets = develop_exact(ruled, 1e-4);
    double flat = 0, surface = 0;
    for (size_t k = 0; k < nets.count; k++) {
        flat += nets.nets[k].flat_area;
        surface += nets.nets[k].area_3d;
        if (!(nets.nets[k].edge_error < tolerance))
            fail_msg("piece %zu: boundary lengths off by %.3g", k, nets.nets[k].edge_error);
    }
    assert_int_equal(nets.count, 1);
    assert_relative(surface, expected, tolerance);
    assert_relative(flat, expected, tolerance);
    ur_net_list_free(&nets);
}

static void assert_develops_to_area(ur_ruled *ruled, double expected)
{
    assert_develops_within(ruled, expected, 1e-6);
}

/*
 * A sine wave and the same wave translated (straight up, then slanting): a
 * general cylinder, the commonest curved wall.  At each inflection the
 * pairing condition has a double root (the branch sigma = u crosses the
 * branch of the points with the mirrored tangent); the pairing must stay on
 * sigma = u through all five, with vertical rulings of the height, and the
 * net is the cylinder's: area |d| x the length of the right section.
 */
static void check_sine_cylinder(size_t n, ur_vec3 shift)
{
    ur_vec3 *lower = malloc(n * sizeof *lower), *upper = malloc(n * sizeof *upper);
    assert_true(lower && upper);
    sine_points(lower, n);
    for (size_t i = 0; i < n; i++)
        upper[i] = ur_vec3_add(lower[i], shift);
    ur_curve *rail1, *rail2;
    assert_int_equal(ur_curve_new_interpolating(lower, n, false, &rail1, NULL), UR_OK);
    assert_int_equal(ur_curve_new_interpolating(upper, n, false, &rail2, NULL), UR_OK);
    free(lower);
    free(upper);
    double expected = simpson(cylinder_density, rail1, &shift, ur_curve_start(rail1),
                              ur_curve_end(rail1), 200000);
    ur_ruled ruled = strip(rail1, rail2);
    const ur_interval *gaps;
    assert_int_equal(ur_ruled_gaps(&ruled, &gaps), 0);
    double places[512];
    size_t count = places_at_inflections(rail1, places);
    for (int k = 0; k <= 400; k++)
        places[count++] =
            ur_ruled_start(&ruled) + (ur_ruled_end(&ruled) - ur_ruled_start(&ruled)) * k / 400.0;
    for (size_t k = 0; k < count; k++) {
        double sigma, slope;
        ur_ruled_pairing(&ruled, places[k], &sigma, &slope);
        if (!(fabs(sigma - places[k]) <= 1e-9 * ur_curve_end(rail1) && fabs(slope - 1) < 1e-6))
            fail_msg("at u = %.12g: sigma %.12g, slope %.9g (the ruling should be the "
                     "translation)",
                     places[k], sigma, slope);
        ur_vec3 rails[4];
        ur_ruled_rails(&ruled, places[k], rails);
        ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]);
        assert_true(ur_vec3_distance(ruling, shift) <= 1e-9 * ur_vec3_length(shift));
    }
    assert_true(analyzed_developable(&ruled));
    assert_develops_to_area(&ruled, expected);
    ur_ruled_free(&ruled);
}

static void test_strip_over_sine_is_a_general_cylinder(void **state)
{
    (void)state;
    check_sine_cylinder(121, ur_vec3_make(0, 0, 80)); /* inflections on points */
    check_sine_cylinder(31, ur_vec3_make(0, 0, 80));  /* fewer points: once said rulings cross */
    check_sine_cylinder(150, ur_vec3_make(0, 0, 80)); /* inflections between points */
    check_sine_cylinder(121, ur_vec3_make(15, -10, 60));
}

/*
 * A sine wave and a copy scaled by lambda towards an apex A: a cone over a
 * curve with inflections.  Chord lengths scale by lambda, so the pairing is
 * sigma = lambda u; every ruling heads for A and is (1 - lambda) |c - A|
 * long, and the strip is the cone's area from A less the part beyond rail 2,
 * (1 - lambda^2) times the integral of |(c - A) x c'| / 2.
 */
static void check_sine_cone(size_t n, ur_vec3 apex, double lambda)
{
    ur_vec3 *lower = malloc(n * sizeof *lower), *upper = malloc(n * sizeof *upper);
    assert_true(lower && upper);
    sine_points(lower, n);
    for (size_t i = 0; i < n; i++)
        upper[i] = ur_vec3_add_scaled(apex, ur_vec3_sub(lower[i], apex), lambda);
    ur_curve *rail1, *rail2;
    assert_int_equal(ur_curve_new_interpolating(lower, n, false, &rail1, NULL), UR_OK);
    assert_int_equal(ur_curve_new_interpolating(upper, n, false, &rail2, NULL), UR_OK);
    free(lower);
    free(upper);
    double expected =
        (1 - lambda * lambda) *
        simpson(cone_density, rail1, &apex, ur_curve_start(rail1), ur_curve_end(rail1), 200000);
    ur_ruled ruled = strip(rail1, rail2);
    const ur_interval *gaps;
    assert_int_equal(ur_ruled_gaps(&ruled, &gaps), 0);
    double places[512];
    size_t count = places_at_inflections(rail1, places);
    for (int k = 0; k <= 400; k++)
        places[count++] =
            ur_ruled_start(&ruled) + (ur_ruled_end(&ruled) - ur_ruled_start(&ruled)) * k / 400.0;
    for (size_t k = 0; k < count; k++) {
        double sigma, slope;
        ur_ruled_pairing(&ruled, places[k], &sigma, &slope);
        if (!(fabs(sigma - lambda * places[k]) <= 1e-9 * ur_curve_end(rail1) &&
              fabs(slope - lambda) < 1e-6))
            fail_msg("at u = %.12g: sigma %.12g, slope %.9g (expected %.12g, %g)", places[k], sigma,
                     slope, lambda * places[k], lambda);
        ur_vec3 rails[4];
        ur_ruled_rails(&ruled, places[k], rails);
        ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]), to_apex = ur_vec3_sub(apex, rails[0]);
        assert_relative(ur_vec3_length(ruling), (1 - lambda) * ur_vec3_length(to_apex), 1e-9);
        assert_true(ur_vec3_length(ur_vec3_cross(ruling, to_apex)) <=
                    1e-9 * ur_vec3_length(ruling) * ur_vec3_length(to_apex));
    }
    assert_true(analyzed_developable(&ruled));
    assert_develops_to_area(&ruled, expected);
    ur_ruled_free(&ruled);
}

static void test_strip_to_scaled_sine_is_a_cone(void **state)
{
    (void)state;
    check_sine_cone(121, ur_vec3_make(100, 0, 150), 0.6);
    check_sine_cone(31, ur_vec3_make(100, 0, 150), 0.6);
    check_sine_cone(150, ur_vec3_make(40, 30, 120), 0.35);
}

/* The height of the wall under a wavy top edge at x, and the cone's fraction towards its apex. */
static double top_height(double x)
{
    return 80 + 15 * sin(M_PI * x / 70);
}

static double apex_fraction(double x)
{
    return 0.5 + 0.15 * sin(M_PI * x / 60);
}

/* |c'| h(x): the area density of the wall of height h over c. */
static double wall_density(ur_curve *curve, double u, const void *data)
{
    (void)data;
    ur_vec3 d[3];
    ur_curve_eval(curve, u, d);
    return ur_vec3_length(d[1]) * top_height(d[0].x);
}

/* (1 - (1 - f(x))^2) |(c - A) x c'| / 2: the cone from c to the fraction f(x) of the way to A. */
static double cone_part_density(ur_curve *curve, double u, const void *data)
{
    ur_vec3 d[3];
    ur_curve_eval(curve, u, d);
    double near = 1 - apex_fraction(d[0].x); /* rail 2 is A + near (c - A) */
    return (1 - near * near) * cone_density(curve, u, data);
}

/*
 * Rails of different shapes, both with inflections: a sine wave under a top
 * edge that is the same wave at a height varying along it (a wall with a
 * wavy top: still a general cylinder, its rulings vertical), and a sine
 * wave joined to the points a varying fraction of the way to an apex (still
 * a cone, its rulings heading for the apex).  Rail 2 is S-shaped in space
 * and parametrised unlike rail 1, so the pairing is no simple formula; the
 * rulings and the area are known all the same.
 */
static void test_strip_to_an_s_shaped_rail(void **state)
{
    (void)state;
    enum { N = 441 }; /* 0.5 mm apart: interpolating rail 2 moves it off the surface by 1e-8 */
    ur_vec3 apex = ur_vec3_make(90, 20, 140);
    for (int kind = 0; kind < 2; kind++) {
        ur_vec3 lower[N], upper[N];
        sine_points_from(lower, N, -10, 210); /* inflections inside, not on the ends */
        for (int i = 0; i < N; i++) {
            double x = lower[i].x;
            upper[i] = kind == 0 ? ur_vec3_make(x, lower[i].y, top_height(x))
                                 : ur_vec3_add_scaled(lower[i], ur_vec3_sub(apex, lower[i]),
                                                      apex_fraction(x));
        }
        ur_curve *rail1, *rail2;
        assert_int_equal(ur_curve_new_interpolating(lower, N, false, &rail1, NULL), UR_OK);
        assert_int_equal(ur_curve_new_interpolating(upper, N, false, &rail2, NULL), UR_OK);
        double expected = simpson(kind == 0 ? wall_density : cone_part_density, rail1, &apex,
                                  ur_curve_start(rail1), ur_curve_end(rail1), 200000);
        ur_ruled ruled = strip(rail1, rail2);
        const ur_interval *gaps;
        assert_int_equal(ur_ruled_gaps(&ruled, &gaps), 0);
        double places[512];
        size_t count = places_at_inflections(rail1, places);
        for (int k = 0; k <= 400; k++)
            places[count++] = ur_ruled_start(&ruled) +
                              (ur_ruled_end(&ruled) - ur_ruled_start(&ruled)) * k / 400.0;
        for (size_t k = 0; k < count; k++) {
            ur_vec3 rails[4];
            ur_ruled_rails(&ruled, places[k], rails);
            ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]);
            ur_vec3 along = kind == 0 ? ur_vec3_make(0, 0, 1) : ur_vec3_sub(apex, rails[0]);
            double sine = ur_vec3_length(ur_vec3_cross(ruling, along)) /
                          (ur_vec3_length(ruling) * ur_vec3_length(along));
            /* Rail 2's spline leaves the surface most at its ends, where its end condition acts. */
            double u0 = ur_curve_start(rail1), u1 = ur_curve_end(rail1);
            bool end = places[k] - u0 < 2 || u1 - places[k] < 2;
            if (!(sine < (end || kind == 1 ? 1e-4 : 1e-5)))
                fail_msg("%s: the ruling at u = %.9g is %.3g rad off", kind ? "cone" : "wall",
                         places[k], asin(fmin(sine, 1)));
            double sigma, slope;
            ur_ruled_pairing(&ruled, places[k], &sigma, &slope);
            assert_true(slope > 0);
        }
        if (kind == 0) {
            assert_true(analyzed_developable(&ruled));
            assert_develops_to_area(&ruled, expected);
        } else {
            assert_develops_within(&ruled, expected, 1e-5);
        }
        ur_ruled_free(&ruled);
    }
}

/* Rails that cannot carry a strip anywhere: refused with the reason. */
static void test_no_strip_anywhere(void **state)
{
    (void)state;
    ur_ruled ruled;
    ur_error error;
    ur_status status =
        ur_ruled_strip(arc(50, 0, 0, 1, 50, false), arc(30, 40, 2, 3, 50, false), &ruled, &error);
    assert_int_equal(status, UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "no developable strip"));
}

/*
 * The hyperbolic paraboloid z = x y / c over [0, a] x [0, b], as the ruled
 * surface joining two opposite edges: not developable, K < 0, with the closed
 * form K = -(1/c^2) / (1 + (x^2 + y^2) / c^2)^2.
 */
static void test_hypar_is_not_developable(void **state)
{
    (void)state;
    double a = 100, b = 80, height = 30, c = a * b / height;
    ur_vec3 edge1[4], edge2[4];
    for (int i = 0; i < 4; i++) {
        double x = a * i / 3.0;
        edge1[i] = ur_vec3_make(x, 0, 0);
        edge2[i] = ur_vec3_make(x, b, height * x / a);
    }
    ur_curve *rail1, *rail2;
    assert_int_equal(ur_curve_new_interpolating(edge1, 4, false, &rail1, NULL), UR_OK);
    assert_int_equal(ur_curve_new_interpolating(edge2, 4, false, &rail2, NULL), UR_OK);
    ur_ruled ruled;
    assert_int_equal(ur_ruled_general(rail1, rail2, UR_PAIR_ARC_LENGTH, &ruled, NULL), UR_OK);
    double u = 0.5 * (ur_ruled_start(&ruled) + ur_ruled_end(&ruled));
    ur_vec3 rails[4];
    ur_ruled_rails(&ruled, u, rails);
    /* The middle ruling runs from (a/2, 0, 0) to (a/2, b, h/2). */
    assert_relative(rails[2].z, height / 2, 1e-9);
    assert_true(ur_ruled_residual(&ruled, u) > 0.1);
    (void)c;
    ur_develop_options options;
    ur_develop_options_default(&options);
    ur_net_list nets;
    ur_error error;
    assert_int_equal(ur_develop(&ruled, &options, &nets, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "not developable"));
    ur_ruled_free(&ruled);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_strip_between_circles_is_a_frustum),
        cmocka_unit_test(test_strip_to_translated_copy_is_a_cylinder),
        cmocka_unit_test(test_strip_recovers_tangent_developable),
        cmocka_unit_test(test_domain_of_existence),
        cmocka_unit_test(test_adjust_rail2_repairs_a_short_rail),
        cmocka_unit_test(test_pieces_on_both_sides_of_a_jump),
        cmocka_unit_test(test_strip_over_sine_is_a_general_cylinder),
        cmocka_unit_test(test_strip_to_scaled_sine_is_a_cone),
        cmocka_unit_test(test_strip_to_an_s_shaped_rail),
        cmocka_unit_test(test_no_strip_anywhere),
        cmocka_unit_test(test_hypar_is_not_developable),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
