/*
 * test_offset.c: the parallel surfaces that move a face of the material to
 * its neutral layer (ur_ruled_offset, ur_surface_layer_offset), against the
 * closed forms of the offset cylinder, frustum and developable helicoid, and
 * their nets against the 3D areas and lengths of the offset surfaces.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/develop.h"
#include "unroll/io.h"

#include "test_support.h"

static ur_ruled cylinder(double radius, double height)
{
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(radius, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), height, &ruled, NULL), UR_OK);
    return ruled;
}

static ur_ruled offset_of(ur_ruled *ruled, double distance)
{
    ur_ruled offset;
    ur_error error;
    if (ur_ruled_offset(ruled, distance, &offset, &error) != UR_OK)
        fail_msg("offset: %s", error.message);
    return offset;
}

/* The net is exact: one piece per closed or open surface, its area the 3D area of the offset. */
static double exact_net_area(ur_ruled *offset)
{
    double area_3d;
    assert_int_equal(
        ur_ruled_area(offset, ur_ruled_start(offset), ur_ruled_end(offset), &area_3d, NULL), UR_OK);
    ur_net_list nets = develop(offset, UR_METHOD_EXACT, 8, 1e-6);
    double flat = 0.0;
    for (size_t k = 0; k < nets.count; k++) {
        flat += nets.nets[k].flat_area;
        assert_true(nets.nets[k].edge_error < 1e-6);
    }
    assert_relative(flat, area_3d, 1e-6);
    ur_net_list_free(&nets);
    return flat;
}

static double rail_length(ur_ruled *ruled, int rail)
{
    double length;
    assert_int_equal(ur_ruled_rail_length(ruled, rail, ur_ruled_start(ruled), ur_ruled_end(ruled),
                                          &length, NULL),
                     UR_OK);
    return length;
}

/* The neutral layer at K t from the inner face; distances toward the centre of curvature. */
static void test_layer_distances(void **state)
{
    (void)state;
    assert_relative(ur_surface_layer_offset(UR_LAYER_OUTER, 3, 0.5), 1.5, 1e-15);
    assert_relative(ur_surface_layer_offset(UR_LAYER_INNER, 3, 0.5), -1.5, 1e-15);
    assert_relative(ur_surface_layer_offset(UR_LAYER_OUTER, 3, 0.3), 2.1, 1e-15);
    assert_relative(ur_surface_layer_offset(UR_LAYER_INNER, 3, 0.3), -0.9, 1e-15);
    /* mid at t/2 from the inner face, neutral at 0.3 t: 0.2 t nearer the centre */
    assert_relative(ur_surface_layer_offset(UR_LAYER_MID, 3, 0.3), 0.6, 1e-14);
    assert_true(ur_surface_layer_offset(UR_LAYER_NEUTRAL, 3, 0.3) == 0.0);
}

/*
 * R = 40, t = 3.  The outer face has radius R, the inner R - t; the neutral
 * layer, K t out from the inner face, has radius R - t + K t.  Given the
 * inner face (radius R), the neutral layer has R + K t; given the middle,
 * R - t/2 + K t.
 */
static void test_cylinder_layers(void **state)
{
    (void)state;
    const double radius = 40, t = 3, height = 100;
    const struct {
        ur_surface_layer layer;
        double k, expected_radius;
    } cases[] = {
        {UR_LAYER_OUTER, 0.5, 40 - 1.5},     {UR_LAYER_INNER, 0.5, 40 + 1.5},
        {UR_LAYER_MID, 0.3, 40 - 1.5 + 0.9}, {UR_LAYER_OUTER, 0.3, 40 - 3 + 0.9},
        {UR_LAYER_NEUTRAL, 0.5, 40},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        ur_ruled ruled = cylinder(radius, height);
        double d = ur_surface_layer_offset(cases[c].layer, t, cases[c].k);
        ur_ruled offset = offset_of(&ruled, d);
        assert_int_equal(offset.kind, UR_RULED_CYLINDER);
        assert_true(ur_ruled_is_closed(&offset));
        double length = 2 * M_PI * cases[c].expected_radius;
        assert_relative(rail_length(&offset, 0), length, 1e-6);
        assert_relative(rail_length(&offset, 1), length, 1e-6);
        /* The developed length: the net is a rectangle length x height. */
        double flat = exact_net_area(&offset);
        assert_relative(flat / height, length, 1e-6);
        ur_ruled_free(&offset);
        ur_ruled_free(&ruled);
    }
}

/* Offsetting a cylinder of radius 40 by 40 or more toward its axis folds it. */
static void test_fold_refused(void **state)
{
    (void)state;
    ur_ruled ruled = cylinder(40, 50), offset;
    ur_error error;
    assert_int_equal(ur_ruled_offset(&ruled, 40.5, &offset, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "bend radius there is only 40 mm,"));
    /* Away from the axis any distance is fine. */
    offset = offset_of(&ruled, -40.5);
    assert_relative(rail_length(&offset, 0), 2 * M_PI * 80.5, 1e-6);
    ur_ruled_free(&offset);
    ur_ruled_free(&ruled);

    /* A whole cone has no room at its apex toward the inside, plenty outside. */
    ur_curve *circle;
    assert_int_equal(ur_curve_new_circle(60, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cone(circle, ur_vec3_make(0, 0, 80), 1.0, &ruled, NULL), UR_OK);
    assert_int_equal(ur_ruled_offset(&ruled, 0.5, &offset, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "fold"));
    offset = offset_of(&ruled, -0.5);
    /* base radius 60 + 0.5 * 0.8, top a circle of radius 0.5 * 0.8 round the axis */
    assert_relative(rail_length(&offset, 0), 2 * M_PI * 60.4, 1e-6);
    assert_relative(rail_length(&offset, 1), 2 * M_PI * 0.4, 1e-5);
    exact_net_area(&offset);
    ur_ruled_free(&offset);
    ur_ruled_free(&ruled);
}

/*
 * The frustum R = 60, r = 30, height 40 (apex at 80, slant of the whole
 * cone 100): the normal makes 0.8 with the horizontal and 0.6 with the
 * axis, so moving d toward the axis gives the frustum with radii R - 0.8 d
 * and r - 0.8 d, rulings parallel and as long (50), area pi (R' + r') 50.
 */
static void test_frustum(void **state)
{
    (void)state;
    const double distances[] = {2.0, -2.0, 10.0};
    for (size_t c = 0; c < sizeof distances / sizeof distances[0]; c++) {
        double d = distances[c];
        ur_curve *circle;
        ur_ruled ruled;
        assert_int_equal(ur_curve_new_circle(60, &circle, NULL), UR_OK);
        assert_int_equal(ur_ruled_cone(circle, ur_vec3_make(0, 0, 80), 0.5, &ruled, NULL), UR_OK);
        ur_ruled offset = offset_of(&ruled, d);
        double big = 60 - 0.8 * d, small = 30 - 0.8 * d;
        assert_relative(rail_length(&offset, 0), 2 * M_PI * big, 1e-6);
        assert_relative(rail_length(&offset, 1), 2 * M_PI * small, 1e-6);
        ur_vec3 rails[4];
        ur_ruled_rails(&offset, ur_ruled_start(&offset), rails);
        assert_relative(ur_vec3_distance(rails[0], rails[2]), 50, 1e-7);
        assert_relative(rails[0].z, -0.6 * d, 1e-6);
        double flat = exact_net_area(&offset);
        assert_relative(flat, M_PI * (big + small) * 50, 1e-6);
        ur_ruled_free(&offset);
        ur_ruled_free(&ruled);
    }
}

/* Polyline length of g + o T + d B on the helix (R cos t, R sin t, c t), t in [0, end]. */
static double offset_rail_length(double radius, double c, double end, double o, double d)
{
    enum { N = 200000 };
    double speed = sqrt(radius * radius + c * c), length = 0.0;
    ur_vec3 previous = {0, 0, 0};
    for (int i = 0; i <= N; i++) {
        double t = end * i / N, s = sin(t), co = cos(t);
        ur_vec3 g = ur_vec3_make(radius * co, radius * s, c * t);
        ur_vec3 tangent = ur_vec3_make(-radius * s / speed, radius * co / speed, c / speed);
        ur_vec3 binormal = ur_vec3_make(c * s / speed, -c * co / speed, radius / speed);
        ur_vec3 p = ur_vec3_add_scaled(ur_vec3_add_scaled(g, tangent, o), binormal, d);
        if (i > 0)
            length += ur_vec3_distance(p, previous);
        previous = p;
    }
    return length;
}

/*
 * The developable helicoid on the helix R = 30, c = 10 (curvature 0.03,
 * torsion 0.01), rulings from 10 to 35 mm along the tangent.  Its bend
 * radius at distance v from the edge of regression is v kappa / tau = 3 v,
 * toward the binormal.  Moving it d along the binormal gives the tangent
 * developable of the same helix raised by d L / R, rulings starting at
 * o - d tau / kappa = o - d / 3: a narrower annulus in the net.
 */
static void test_helicoid(void **state)
{
    (void)state;
    const double radius = 30, c = 10, o = 10, width = 25, end = 1.5 * M_PI;
    const double kappa = 0.03, speed = sqrt(1000.0);
    const double distances[] = {2.0, -2.0};
    for (size_t k = 0; k < 2; k++) {
        double d = distances[k], near = o - d / 3;
        ur_curve *helix;
        ur_ruled ruled;
        assert_int_equal(ur_curve_new_helix(radius, 2 * M_PI * c, 0, end, &helix, NULL), UR_OK);
        assert_int_equal(ur_ruled_tangent(helix, o, width, &ruled, NULL), UR_OK);
        ur_ruled offset = offset_of(&ruled, d);
        double inner = speed * end * sqrt(1 + near * near * kappa * kappa);
        double outer = speed * end * sqrt(1 + (near + width) * (near + width) * kappa * kappa);
        assert_relative(offset_rail_length(radius, c, end, o, d), inner, 1e-8);
        assert_relative(offset_rail_length(radius, c, end, o + width, d), outer, 1e-8);
        assert_relative(rail_length(&offset, 0), inner, 1e-6);
        assert_relative(rail_length(&offset, 1), outer, 1e-6);
        /* area of the annular sector: s kappa ((near + w)^2 - near^2) / 2 */
        double flat = exact_net_area(&offset);
        double area = speed * end * kappa * ((near + width) * (near + width) - near * near) / 2;
        assert_relative(flat, area, 1e-6);
        ur_ruled_free(&offset);
        ur_ruled_free(&ruled);
    }
    /* Toward the binormal the rulings' near ends (radius 3 * 10 = 30) are the limit. */
    ur_curve *helix;
    ur_ruled ruled, offset;
    ur_error error;
    assert_int_equal(ur_curve_new_helix(radius, 2 * M_PI * c, 0, end, &helix, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(helix, o, width, &ruled, NULL), UR_OK);
    assert_int_equal(ur_ruled_offset(&ruled, 30.5, &offset, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "only 30 mm"));
    ur_ruled_free(&ruled);
}

/*
 * A cylinder over an S: three quarters of a circle of radius 50 one way,
 * a quarter the other way.  Most of it bends round the first centre, so
 * that is the inside: moving 1 mm inward shortens the long arc by pi/2 * 3
 * and lengthens the short one by pi/2.
 */
static void test_inflection_side(void **state)
{
    (void)state;
    enum { N = 400 };
    ur_vec3 points[N];
    double first = 1.5 * M_PI, second = 0.5 * M_PI, total = first + second;
    for (int i = 0; i < N; i++) {
        double s = total * i / (N - 1);
        if (s <= first) {
            points[i] = ur_vec3_make(50 * cos(s), 50 * sin(s), 0);
        } else {
            /* the reverse arc round (0, -100): starts at (0, -50) heading +x */
            double a = M_PI / 2 - (s - first);
            points[i] = ur_vec3_make(50 * cos(a), -100 + 50 * sin(a), 0);
        }
    }
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_interpolating(points, N, false, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(curve, ur_vec3_make(0, 0, 1), 20, &ruled, NULL), UR_OK);
    ur_ruled offset = offset_of(&ruled, 1.0);
    double expected = 49 * first + 51 * second;
    assert_relative(rail_length(&offset, 0), expected, 1e-3);
    assert_true(rail_length(&offset, 0) < rail_length(&ruled, 0));
    exact_net_area(&offset);
    ur_ruled_free(&offset);
    ur_ruled_free(&ruled);
}

/* A flat triangle (a cone over one edge) only moves: same net. */
static void test_flat_moves(void **state)
{
    (void)state;
    ur_vec3 points[4];
    for (int k = 0; k < 4; k++)
        points[k] = ur_vec3_make(100.0 * k / 3, 0, 0);
    ur_curve *edge;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_interpolating(points, 4, false, &edge, NULL), UR_OK);
    assert_int_equal(ur_ruled_cone(edge, ur_vec3_make(30, 40, 0), 1.0, &ruled, NULL), UR_OK);
    ur_ruled offset = offset_of(&ruled, 5.0);
    assert_int_equal(offset.kind, UR_RULED_CONE);
    assert_relative(fabs(offset.apex.z), 5.0, 1e-12);
    assert_relative(exact_net_area(&offset), 100 * 40 / 2.0, 1e-9);
    ur_ruled_free(&offset);
    ur_ruled_free(&ruled);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_layer_distances), cmocka_unit_test(test_cylinder_layers),
        cmocka_unit_test(test_fold_refused),    cmocka_unit_test(test_frustum),
        cmocka_unit_test(test_helicoid),        cmocka_unit_test(test_inflection_side),
        cmocka_unit_test(test_flat_moves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
