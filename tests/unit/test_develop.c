/*
 * test_develop.c: curves, surface areas and developments against closed
 * forms, the seed paper's observations on the discrete methods ([Seed2018] in
 * docs/bibliography.md), and the splitting of nets that would overlap
 * themselves.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <geos_c.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/develop.h"

#include "test_support.h"

static ur_ruled helicoid(double radius, double pitch, double turns, double offset, double width)
{
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_helix(radius, pitch, 0, 2 * M_PI * turns, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, offset, width, &ruled, NULL), UR_OK);
    return ruled;
}

static double total_flat_area(const ur_net_list *nets)
{
    double area = 0;
    for (size_t k = 0; k < nets->count; k++)
        area += nets->nets[k].flat_area;
    return area;
}

/* Circle through three points (for checking that points lie on one circle). */
static ur_vec2 circle_centre(ur_vec2 a, ur_vec2 b, ur_vec2 c)
{
    double d = 2 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
    double a2 = a.x * a.x + a.y * a.y, b2 = b.x * b.x + b.y * b.y, c2 = c.x * c.x + c.y * c.y;
    return ur_vec2_make((a2 * (b.y - c.y) + b2 * (c.y - a.y) + c2 * (a.y - b.y)) / d,
                        (a2 * (c.x - b.x) + b2 * (a.x - c.x) + c2 * (b.x - a.x)) / d);
}

static void test_helix_curvature(void **state)
{
    (void)state;
    ur_curve *curve;
    assert_int_equal(ur_curve_new_helix(30, 20 * M_PI, 0, 3, &curve, NULL), UR_OK);
    /* kappa = r / (r^2 + c^2), c = pitch / 2 pi = 10 */
    assert_relative(ur_curve_curvature(curve, 1.234), 30.0 / 1000.0, 1e-14);
    double length;
    assert_int_equal(ur_curve_length(curve, 0, 3, &length, NULL), UR_OK);
    assert_relative(length, 3 * sqrt(1000.0), 1e-12);
    ur_curve_free(curve);
}

/* Ghost end points keep the curvature at the ends of an open interpolated curve. */
static void test_spline_keeps_curvature_at_ends(void **state)
{
    (void)state;
    enum { N = 40 };
    ur_vec3 points[N];
    for (int i = 0; i < N; i++) {
        double t = 1.5 * M_PI * i / (N - 1);
        points[i] = ur_vec3_make(50 * cos(t), 50 * sin(t), 0);
    }
    ur_curve *curve;
    assert_int_equal(ur_curve_new_interpolating(points, N, false, &curve, NULL), UR_OK);
    /* A natural spline would give 0 here; the ghosts' cubic gets within a few per cent. */
    assert_relative(ur_curve_curvature(curve, ur_curve_start(curve)), 1.0 / 50, 5e-2);
    assert_relative(ur_curve_curvature(curve, ur_curve_end(curve)), 1.0 / 50, 5e-2);
    assert_relative(ur_curve_curvature(curve, 0.5 * ur_curve_end(curve)), 1.0 / 50, 1e-3);
    ur_curve_free(curve);
}

static void test_surface_areas(void **state)
{
    (void)state;
    ur_curve *circle;
    ur_ruled ruled;
    double area;
    assert_int_equal(ur_curve_new_circle(40, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 120, &ruled, NULL), UR_OK);
    assert_int_equal(ur_ruled_area(&ruled, 0, 2 * M_PI, &area, NULL), UR_OK);
    assert_relative(area, 2 * M_PI * 40 * 120, 1e-10);
    ur_ruled_free(&ruled);

    /* right cone r = 60, h = 80: slant 100, lateral area pi r l */
    assert_int_equal(ur_curve_new_circle(60, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cone(circle, ur_vec3_make(0, 0, 80), 1.0, &ruled, NULL), UR_OK);
    assert_int_equal(ur_ruled_area(&ruled, 0, 2 * M_PI, &area, NULL), UR_OK);
    assert_relative(area, M_PI * 60 * 100, 1e-10);
    ur_ruled_free(&ruled);

    /* helicoid: area = s kappa L^2 / 2 */
    ruled = helicoid(30, 20 * M_PI, 0.25, 0, 25);
    assert_int_equal(ur_ruled_area(&ruled, 0, M_PI / 2, &area, NULL), UR_OK);
    assert_relative(area, (M_PI / 2) * sqrt(1000.0) * 0.03 * 25 * 25 / 2, 1e-10);
    assert_relative(area, 465.68, 1e-4);
    ur_ruled_free(&ruled);
}

/* The helicoid develops to an annular sector: Leroy's construction. */
static void test_helicoid_annulus(void **state)
{
    (void)state;
    double radius = 30, c = 10, width = 25, turns = 0.75;
    ur_ruled ruled = helicoid(radius, 2 * M_PI * c, turns, 0, width);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 8, 1e-5);
    assert_int_equal(nets.count, 1);
    const ur_net *net = &nets.nets[0];
    double rho = (radius * radius + c * c) / radius;
    double outer = sqrt(rho * rho + width * width);
    /* The outline runs along one arc and back along the other; find both radii. */
    ur_vec2 centre = circle_centre(net->outline[0], net->outline[net->outline_count / 5],
                                   net->outline[net->outline_count / 3]);
    double inner_seen = INFINITY, outer_seen = 0;
    for (size_t i = 0; i < net->outline_count; i++) {
        double r = ur_vec2_distance(net->outline[i], centre);
        inner_seen = fmin(inner_seen, r);
        outer_seen = fmax(outer_seen, r);
    }
    double expected_first = ur_vec2_distance(net->outline[0], centre);
    assert_true(fabs(expected_first - rho) < 1e-7 * rho ||
                fabs(expected_first - outer) < 1e-7 * outer);
    assert_relative(inner_seen, rho, 1e-8);
    assert_relative(outer_seen, outer, 1e-8);
    double angle = turns * 2 * M_PI * radius / sqrt(radius * radius + c * c);
    assert_relative(net->area_3d, angle * (outer * outer - rho * rho) / 2, 1e-9);
    assert_relative(net->flat_area, net->area_3d, 1e-6);
    assert_true(net->edge_error < 1e-6);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* Dense sampling switches integrators (see develop.c); the net must stay exact. */
static void test_dense_sampling_stays_exact(void **state)
{
    (void)state;
    double radius = 30, c = 10, rho = (radius * radius + c * c) / radius;
    ur_ruled ruled = helicoid(radius, 2 * M_PI * c, 0.75, 0, 25);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 60000, 0.01);
    assert_int_equal(nets.count, 1);
    const ur_net *net = &nets.nets[0];
    assert_true(net->outline_count > 2 * 40000);
    /* Every outline point lies on one of the two circles of the annulus. */
    double outer = sqrt(rho * rho + 25 * 25);
    ur_vec2 centre = circle_centre(net->outline[0], net->outline[net->outline_count / 8],
                                   net->outline[net->outline_count / 4]);
    double worst = 0;
    for (size_t i = 0; i < net->outline_count; i++) {
        double r = ur_vec2_distance(net->outline[i], centre);
        worst = fmax(worst, fmin(fabs(r - rho) / rho, fabs(r - outer) / outer));
    }
    if (!(worst < 1e-8))
        fail_msg("worst relative radius error %g", worst);
    assert_relative(net->flat_area, net->area_3d, 1e-6);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* [Seed2018]: triangle net < surface < quad net, both errors shrinking with n. */
static void test_discrete_methods(void **state)
{
    (void)state;
    ur_ruled ruled = helicoid(30, 20 * M_PI, 0.25, 0, 25);
    double surface;
    assert_int_equal(ur_ruled_area(&ruled, 0, M_PI / 2, &surface, NULL), UR_OK);
    double previous_triangle = 0, previous_quad = INFINITY;
    size_t parts[] = {16, 32, 64, 128};
    for (size_t k = 0; k < 4; k++) {
        ur_net_list triangles = develop(&ruled, UR_METHOD_TRIANGLE, parts[k], 0.01);
        ur_net_list quads = develop(&ruled, UR_METHOD_QUAD, parts[k], 0.01);
        double triangle = total_flat_area(&triangles), quad = total_flat_area(&quads);
        assert_true(triangle < surface);
        assert_true(quad > surface);
        assert_true(triangle > previous_triangle);
        assert_true(quad < previous_quad);
        if (parts[k] == 16) { /* the reference figures, docs/algorithms.md section 5 */
            assert_relative(triangle, 436.1, 2e-4);
            assert_relative(quad, 522.8, 2e-4);
        }
        previous_triangle = triangle;
        previous_quad = quad;
        ur_net_list_free(&triangles);
        ur_net_list_free(&quads);
    }
    ur_ruled_free(&ruled);
}

/* The outline point at distance `slant` from every other one (a cone's apex), or count. */
static size_t apex_index(const ur_net *net, double slant)
{
    for (size_t k = 0; k < net->outline_count; k++) {
        size_t j = 0;
        while (j < net->outline_count &&
               (j == k ||
                fabs(ur_vec2_distance(net->outline[j], net->outline[k]) - slant) <= 1e-9 * slant))
            j++;
        if (j == net->outline_count)
            return k;
    }
    return net->outline_count;
}

/*
 * The quad method on a full cone (cut 1): every far corner is the apex, so
 * each cell is the flat triangle apex P_i P_i+1, and the net is that of the
 * inscribed pyramid: n isosceles triangles with legs the slant height l and
 * bases the chord c = 2 r sin(pi / n), side by side in one piece.  Each has
 * area c sqrt(4 l^2 - c^2) / 4.
 */
static void test_cone_quad_is_inscribed_pyramid(void **state)
{
    (void)state;
    double radius = 60, height = 80, slant = hypot(radius, height);
    const size_t parts[] = {8, 16, 64};
    for (size_t k = 0; k < 3; k++) {
        size_t n = parts[k];
        ur_curve *circle;
        ur_ruled ruled;
        assert_int_equal(ur_curve_new_circle(radius, &circle, NULL), UR_OK);
        assert_int_equal(ur_ruled_cone(circle, ur_vec3_make(0, 0, height), 1.0, &ruled, NULL),
                         UR_OK);
        ur_net_list nets = develop(&ruled, UR_METHOD_QUAD, n, 0.01);
        assert_int_equal(nets.count, 1);
        const ur_net *net = &nets.nets[0];
        double chord = 2 * radius * sin(M_PI / n);
        assert_relative(net->flat_area, n * chord * sqrt(4 * slant * slant - chord * chord) / 4,
                        1e-9);
        /* The n + 1 ends of the rulings on the base, one chord apart, and the apex once. */
        assert_int_equal(net->outline_count, n + 2);
        size_t apex = apex_index(net, slant);
        assert_true(apex < net->outline_count);
        for (size_t i = 1; i <= n; i++)
            assert_relative(ur_vec2_distance(net->outline[(apex + i) % (n + 2)],
                                             net->outline[(apex + i + 1) % (n + 2)]),
                            chord, 1e-9);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
}

/* The inscribed polyhedral cone: the 3D triangles apex P_i P_i+1 of n equal parameter steps. */
static double inscribed_cone_area(ur_ruled *ruled, size_t n)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled), area = 0;
    ur_vec3 previous[4], rails[4];
    ur_ruled_rails(ruled, u0, previous);
    for (size_t i = 1; i <= n; i++) {
        ur_ruled_rails(ruled, u0 + (u1 - u0) * i / n, rails);
        ur_vec3 side = ur_vec3_sub(previous[0], ruled->apex);
        area += ur_vec3_length(ur_vec3_cross(side, ur_vec3_sub(rails[0], ruled->apex))) / 2;
        previous[0] = rails[0];
    }
    return area;
}

/*
 * A cone over a loop interpolated through points as a CSV file gives them,
 * its apex off centre: the quad net is the inscribed polyhedral cone laid
 * flat in one piece, smaller than the surface, and it converges to the
 * surface as n grows (the error falls about fourfold as n doubles).
 */
static void test_cone_quad_over_curve(void **state)
{
    (void)state;
    static const ur_vec3 points[] = {
        {70, 0, 0},    {52, 38, 0},   {10, 55, 0},  {-35, 41, 0}, {-58, 5, 0},
        {-47, -30, 0}, {-12, -44, 0}, {30, -37, 0}, {58, -20, 0},
    };
    double previous_error = INFINITY;
    for (size_t n = 8; n <= 128; n *= 2) {
        ur_curve *curve;
        ur_ruled ruled;
        assert_int_equal(ur_curve_new_interpolating(points, sizeof points / sizeof points[0], true,
                                                    &curve, NULL),
                         UR_OK);
        assert_int_equal(ur_ruled_cone(curve, ur_vec3_make(15, -10, 65), 1.0, &ruled, NULL), UR_OK);
        ur_net_list nets = develop(&ruled, UR_METHOD_QUAD, n, 0.01);
        assert_int_equal(nets.count, 1);
        const ur_net *net = &nets.nets[0];
        assert_relative(net->flat_area, inscribed_cone_area(&ruled, n), 1e-9);
        double error = (net->area_3d - net->flat_area) / net->area_3d;
        if (!(error > 0 && error < previous_error / 3))
            fail_msg("n = %zu: relative area deficit %g after %g", n, error, previous_error);
        previous_error = error;
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
    assert_true(previous_error < 3e-4);
}

static bool outline_is_valid(const ur_net *net)
{
    GEOSContextHandle_t geos = GEOS_init_r();
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)net->outline_count + 1, 2);
    for (size_t i = 0; i <= net->outline_count; i++) {
        ur_vec2 p = net->outline[i % net->outline_count];
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, p.x, p.y);
    }
    GEOSGeometry *polygon =
        GEOSGeom_createPolygon_r(geos, GEOSGeom_createLinearRing_r(geos, sequence), NULL, 0);
    bool valid = GEOSisValid_r(geos, polygon) == 1;
    GEOSGeom_destroy_r(geos, polygon);
    GEOS_finish_r(geos);
    return valid;
}

/*
 * One turn of this helicoid develops to 2 pi R / sqrt(R^2 + c^2) = 0.949 of a
 * full circle, so 3.5 turns need ceil(3.5 * 0.949) = 4 pieces.
 */
static void test_split_into_fewest_pieces(void **state)
{
    (void)state;
    ur_ruled ruled = helicoid(30, 20 * M_PI, 3.5, 0, 25);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 8, 0.01);
    assert_int_equal(nets.count, 4);
    double area_3d = 0;
    for (size_t k = 0; k < nets.count; k++) {
        assert_true(outline_is_valid(&nets.nets[k]));
        assert_relative(nets.nets[k].u_end - nets.nets[k].u_start, 7 * M_PI / 4, 1e-3);
        assert_int_equal(nets.nets[k].seam_count, (k == 0 || k == 3) ? 1 : 2);
        area_3d += nets.nets[k].area_3d;
    }
    assert_relative(area_3d, 7 * M_PI * sqrt(1000.0) * 0.03 * 625 / 2, 1e-9);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* An S curve has an inflection: its tangent developable is refused. */
static void test_inflection_refused(void **state)
{
    (void)state;
    enum { N = 30 };
    ur_vec3 points[N];
    for (int i = 0; i < N; i++) {
        double t = -2 + 4.0 * i / (N - 1);
        points[i] = ur_vec3_make(20 * t, 10 * t * t * t, 2 * t);
    }
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_interpolating(points, N, false, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, 0, 10, &ruled, NULL), UR_OK);
    ur_develop_options options;
    ur_develop_options_default(&options);
    ur_net_list nets;
    ur_error error;
    assert_int_equal(ur_develop(&ruled, &options, &nets, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "inflection"));
    assert_non_null(strstr(error.message, "near point 15"));
    ur_ruled_free(&ruled);
}

static void test_triangle_method_needs_tangent_developable(void **state)
{
    (void)state;
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(40, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 120, &ruled, NULL), UR_OK);
    ur_develop_options options;
    ur_develop_options_default(&options);
    options.method = UR_METHOD_TRIANGLE;
    ur_net_list nets;
    ur_error error;
    assert_int_equal(ur_develop(&ruled, &options, &nets, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "triangle"));
    ur_ruled_free(&ruled);
}

/* An oblique cylinder over a circle: the base develops to a sine-like curve of the same length. */
static void test_oblique_cylinder_isometry(void **state)
{
    (void)state;
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(40, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(1, 0, 2), 100, &ruled, NULL), UR_OK);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 8, 1e-5);
    assert_int_equal(nets.count, 1);
    assert_relative(nets.nets[0].flat_area, nets.nets[0].area_3d, 2e-6);
    assert_true(nets.nets[0].edge_error < 1e-6);
    /* lateral area of an oblique cylinder = perimeter of the right section x slant length */
    double e = 1 / sqrt(5.0);                /* sine of the tilt from the vertical axis */
    double b = 40, a = 40 * sqrt(1 - e * e); /* right section: ellipse with semi-axes a, b */
    double h = (a - b) * (a - b) / ((a + b) * (a + b));
    double perimeter = M_PI * (a + b) * (1 + 3 * h / (10 + sqrt(4 - 3 * h))); /* Ramanujan */
    assert_relative(nets.nets[0].area_3d, perimeter * 100, 1e-7);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_helix_curvature),
        cmocka_unit_test(test_spline_keeps_curvature_at_ends),
        cmocka_unit_test(test_surface_areas),
        cmocka_unit_test(test_helicoid_annulus),
        cmocka_unit_test(test_dense_sampling_stays_exact),
        cmocka_unit_test(test_discrete_methods),
        cmocka_unit_test(test_cone_quad_is_inscribed_pyramid),
        cmocka_unit_test(test_cone_quad_over_curve),
        cmocka_unit_test(test_split_into_fewest_pieces),
        cmocka_unit_test(test_inflection_refused),
        cmocka_unit_test(test_triangle_method_needs_tangent_developable),
        cmocka_unit_test(test_oblique_cylinder_isometry),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
