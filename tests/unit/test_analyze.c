/*
 * test_analyze.c: the surface analysis against closed forms worked out by
 * hand, never numbers taken from the code under test, and its PNG map.
 *
 * The closed forms:
 *  - cylinder of radius R: K = 0, bend radius R everywhere, area 2 pi R H;
 *  - right circular cone of half-angle alpha: the parallel circle through a
 *    point at distance s from the apex crosses the ruling at right angles
 *    and has radius s sin alpha; its principal normal is horizontal, and the
 *    surface normal lies in the meridian plane at angle alpha to the
 *    horizontal, so the normal curvature across the ruling is
 *    cos(alpha) / (s sin alpha) (Meusnier): bend radius s tan alpha;
 *  - tangent developable of a curve with curvature kappa and torsion tau:
 *    the tangent plane is the osculating plane, whose normal (the binormal)
 *    turns at rate tau per unit arc length, while a point at distance w from
 *    the edge of regression moves across the ruling at w kappa per unit arc
 *    length: bend radius w kappa / tau, for the helix (R cos t, R sin t, c t)
 *    w R / c; its area between w0 and w1 is s kappa (w1^2 - w0^2) / 2;
 *  - hyperbolic paraboloid z = x y / c: K = -(1/c^2) / (1 + (x^2 + y^2)/c^2)^2,
 *    principal curvatures +-1/c at the origin (bend radius c), and over
 *    [-w, w] x [-h, h] the integral of K dA is minus the solid angle of its
 *    Gauss image, -4 atan(w h / (c sqrt(c^2 + w^2 + h^2))).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <cairo.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unroll/analyze.h"

#include "test_support.h"

#define assert_small(actual, bound)                                                                \
    do {                                                                                           \
        double a_ = (actual);                                                                      \
        if (!(fabs(a_) <= (bound)))                                                                \
            fail_msg("%s = %.12g, expected at most %g in size", #actual, a_, (double)(bound));     \
    } while (0)

/* ---- Surfaces ----------------------------------------------------------- */

static ur_ruled cylinder(double radius, double height)
{
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(radius, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), height, &ruled, NULL), UR_OK);
    return ruled;
}

/* Base circle of radius r in z = 0, apex (0, 0, h). */
static ur_ruled cone(double radius, double height, double cut)
{
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(radius, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cone(circle, ur_vec3_make(0, 0, height), cut, &ruled, NULL), UR_OK);
    return ruled;
}

static ur_ruled helicoid(double radius, double rise, double turns, double offset, double width)
{
    ur_curve *helix;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_helix(radius, 2 * M_PI * rise, 0, 2 * M_PI * turns, &helix, NULL),
                     UR_OK);
    assert_int_equal(ur_ruled_tangent(helix, offset, width, &ruled, NULL), UR_OK);
    return ruled;
}

/* z = x y / c over [-w, w] x [-h, h], ruled by the lines x = const. */
static ur_ruled hyperbolic_paraboloid(double c, double w, double h)
{
    enum { N = 9 };
    ur_vec3 near[N], far[N];
    for (int i = 0; i < N; i++) {
        double x = -w + 2 * w * i / (N - 1);
        near[i] = ur_vec3_make(x, -h, -x * h / c);
        far[i] = ur_vec3_make(x, h, x * h / c);
    }
    ur_curve *rail1, *rail2;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_interpolating(near, N, false, &rail1, NULL), UR_OK);
    assert_int_equal(ur_curve_new_interpolating(far, N, false, &rail2, NULL), UR_OK);
    ur_error error;
    if (ur_ruled_general(rail1, rail2, UR_PAIR_ARC_LENGTH, &ruled, &error) != UR_OK)
        fail_msg("general: %s", error.message);
    return ruled;
}

static ur_analysis analyze(ur_ruled *ruled, size_t rulings, size_t across)
{
    ur_analysis_options options;
    ur_analysis_options_default(&options);
    options.rulings = rulings;
    options.across = across;
    ur_analysis analysis;
    ur_error error;
    if (ur_analyze(ruled, &options, &analysis, &error) != UR_OK)
        fail_msg("analyze: %s", error.message);
    assert_int_equal(analysis.ruling_count, rulings);
    assert_int_equal(analysis.across, across);
    return analysis;
}

/* What every developable without singular points must show. */
static void assert_developable(const ur_analysis *analysis)
{
    assert_true(analysis->developable);
    assert_small(analysis->max_residual, 1e-9);
    assert_small(analysis->gaussian_min, 1e-9);
    assert_small(analysis->gaussian_max, 1e-9);
    assert_small(analysis->gaussian_mean, 1e-9);
    for (size_t i = 0; i < analysis->ruling_count; i++) {
        assert_false(analysis->rulings[i].in_gap);
        assert_small(analysis->rulings[i].gaussian_min, 1e-9);
        assert_small(analysis->rulings[i].gaussian_max, 1e-9);
    }
}

/* ---- Options ------------------------------------------------------------ */

static void test_options(void **state)
{
    (void)state;
    ur_analysis_options options;
    ur_analysis_options_default(&options);
    assert_int_equal(options.rulings, 256);
    assert_int_equal(options.across, 17);
    assert_true(options.tolerance == 1e-6);

    ur_ruled ruled = cylinder(10, 20);
    ur_analysis analysis;
    ur_error error;
    options.rulings = 1;
    assert_int_equal(ur_analyze(&ruled, &options, &analysis, &error), UR_ERROR_INPUT);
    assert_null(analysis.rulings);
    ur_analysis_options_default(&options);
    options.across = 1;
    assert_int_equal(ur_analyze(&ruled, &options, &analysis, &error), UR_ERROR_INPUT);
    ur_analysis_options_default(&options);
    options.tolerance = NAN;
    assert_int_equal(ur_analyze(&ruled, &options, &analysis, &error), UR_ERROR_INPUT);
    ur_analysis_free(&analysis); /* safe after a failure */

    /* NULL options: the defaults */
    assert_int_equal(ur_analyze(&ruled, NULL, &analysis, &error), UR_OK);
    assert_int_equal(analysis.ruling_count, 256);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
}

/* ---- Developables ------------------------------------------------------- */

static void test_cylinder(void **state)
{
    (void)state;
    double radius = 40, height = 120;
    ur_ruled ruled = cylinder(radius, height);
    ur_analysis analysis = analyze(&ruled, 65, 9);
    assert_developable(&analysis);
    assert_relative(analysis.area_3d, 2 * M_PI * radius * height, 1e-10);
    assert_relative(analysis.min_bend_radius, radius, 1e-7);
    for (size_t i = 0; i < analysis.ruling_count; i++) {
        const ur_ruling_analysis *ruling = &analysis.rulings[i];
        assert_relative(ruling->bend_radius, radius, 1e-7);
        assert_relative(ruling->arc, radius * 2 * M_PI * i / 64, 1e-10);
        assert_relative(ur_vec3_distance(ruling->near, ruling->far), height, 1e-12);
        assert_true(isnan(ruling->striction_v)); /* parallel rulings: no edge of regression */
    }

    ur_point_curvature point;
    ur_analyze_point(&ruled, 1.0, 0.25, &point);
    assert_false(point.singular);
    assert_relative(point.point.x, radius * cos(1.0), 1e-14);
    assert_relative(point.point.z, 0.25 * height, 1e-14);
    assert_relative(fabs(point.normal.x), cos(1.0), 1e-12); /* radial */
    assert_relative(point.area_element, radius * height, 1e-12);
    assert_relative(fabs(point.mean), 1 / (2 * radius), 1e-7);
    assert_relative(point.bend_radius, radius, 1e-7);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
}

/* Base radius 60, height 80 (slant 100, tan alpha = 3/4), cut halfway. */
static void test_cone_frustum(void **state)
{
    (void)state;
    ur_ruled ruled = cone(60, 80, 0.5);
    ur_analysis analysis = analyze(&ruled, 33, 17);
    assert_developable(&analysis);
    /* lateral area of a frustum: pi (r1 + r2) times its slant */
    assert_relative(analysis.area_3d, M_PI * (60 + 30) * 50, 1e-10);
    /* s tan alpha, smallest at the top, s = 50 */
    assert_relative(analysis.min_bend_radius, 50 * 0.75, 1e-7);
    assert_small(analysis.min_bend_at.z - 40, 1e-9);
    for (size_t i = 0; i < analysis.ruling_count; i++) {
        assert_relative(analysis.rulings[i].bend_radius, 37.5, 1e-7);
        assert_true(analysis.rulings[i].bend_v == 1.0);
        assert_relative(analysis.rulings[i].striction_v, 2.0, 1e-9); /* the apex */
    }
    ur_point_curvature point;
    ur_analyze_point(&ruled, 2.0, 0.0, &point);
    assert_relative(point.bend_radius, 100 * 0.75, 1e-7);
    ur_analyze_point(&ruled, 0.0, 0.5, &point); /* one-sided differences at the start */
    assert_relative(point.bend_radius, 75 * 0.75, 1e-7);
    ur_analyze_point(&ruled, 2 * M_PI, 0.5, &point); /* and at the end */
    assert_relative(point.bend_radius, 75 * 0.75, 1e-7);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
}

/* Up to the apex: no tangent plane there, and no bend radius the material can take. */
static void test_cone_apex_is_singular(void **state)
{
    (void)state;
    ur_ruled ruled = cone(60, 80, 1.0);
    ur_analysis analysis = analyze(&ruled, 16, 9);
    assert_true(analysis.developable);
    assert_small(analysis.gaussian_min, 1e-9); /* the apex left out */
    assert_small(analysis.gaussian_max, 1e-9);
    assert_true(analysis.min_bend_radius == 0.0);
    assert_small(ur_vec3_distance(analysis.min_bend_at, ur_vec3_make(0, 0, 80)), 1e-9);
    assert_relative(analysis.area_3d, M_PI * 60 * 100, 1e-10);
    ur_point_curvature point;
    ur_analyze_point(&ruled, 1.0, 1.0, &point);
    assert_true(point.singular);
    assert_true(isnan(point.gaussian));
    /* halfway, s = 50 */
    ur_analyze_point(&ruled, 1.0, 0.5, &point);
    assert_false(point.singular);
    assert_relative(point.bend_radius, 37.5, 1e-7);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
}

/* Helix radius 30, rise 10 per radian: bend radius 3 w at distance w from the helix. */
static void test_helicoid(void **state)
{
    (void)state;
    double radius = 30, rise = 10, turns = 0.75, offset = 5, width = 20;
    ur_ruled ruled = helicoid(radius, rise, turns, offset, width);
    ur_analysis analysis = analyze(&ruled, 41, 9);
    assert_developable(&analysis);
    double kappa = radius / (radius * radius + rise * rise);
    double s = 2 * M_PI * turns * sqrt(radius * radius + rise * rise);
    double far = offset + width;
    assert_relative(analysis.area_3d, s * kappa * (far * far - offset * offset) / 2, 1e-10);
    assert_relative(analysis.min_bend_radius, offset * radius / rise, 1e-7);
    for (size_t i = 0; i < analysis.ruling_count; i++) {
        assert_relative(analysis.rulings[i].bend_radius, offset * radius / rise, 1e-7);
        /* the edge of regression, offset before rail a */
        assert_relative(analysis.rulings[i].striction_v, -offset / width, 1e-7);
    }
    ur_point_curvature point;
    ur_analyze_point(&ruled, 1.0, 0.5, &point);
    assert_relative(point.bend_radius, (offset + 0.5 * width) * radius / rise, 1e-7);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
}

/*
 * No offset (the command's default): rail a is the edge of regression, a
 * cusp of the surface where r_u x r_v vanishes.  Still developable, K = 0
 * away from the cusp, and the bend radius goes to 0 at it.
 */
static void test_helicoid_from_its_edge(void **state)
{
    (void)state;
    double radius = 30, rise = 10, width = 20;
    ur_ruled ruled = helicoid(radius, rise, 0.75, 0, width);
    ur_analysis analysis = analyze(&ruled, 17, 9);
    assert_small(analysis.gaussian_min, 1e-9);
    assert_small(analysis.gaussian_max, 1e-9);
    assert_true(analysis.min_bend_radius == 0.0);
    ur_point_curvature point;
    ur_analyze_point(&ruled, 1.0, 0.0, &point);
    assert_true(point.singular);
    ur_analyze_point(&ruled, 1.0, 1.0 / 8, &point);
    assert_relative(point.bend_radius, width / 8 * radius / rise, 1e-7);
    /* The residual compares the normals a' x (b - a) and b' x (b - a); on the cusp the first is
       rounding, not a direction, and the residual must not read it as one. */
    if (!analysis.developable)
        fail_msg("largest residual %g rad at u = %g: ur_ruled_residual takes the rounding "
                 "a' x (b - a) on the edge of regression for a normal",
                 analysis.max_residual, analysis.rulings[analysis.worst_ruling].u);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
}

/* The tangent developable of points on the same helix, interpolated. */
static void test_interpolated_tangent_developable(void **state)
{
    (void)state;
    enum { N = 60 };
    double radius = 30, rise = 10, offset = 4, width = 20;
    ur_vec3 points[N];
    for (int i = 0; i < N; i++) {
        double t = 1.5 * M_PI * i / (N - 1);
        points[i] = ur_vec3_make(radius * cos(t), radius * sin(t), rise * t);
    }
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_interpolating(points, N, false, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, offset, width, &ruled, NULL), UR_OK);
    ur_analysis analysis = analyze(&ruled, 200, 17);
    assert_developable(&analysis);
    double area;
    assert_int_equal(
        ur_ruled_area(&ruled, ur_ruled_start(&ruled), ur_ruled_end(&ruled), &area, NULL), UR_OK);
    assert_relative(analysis.area_3d, area, 1e-12);
    /* the spline's torsion is close to the helix's away from its ends */
    ur_point_curvature point;
    double middle = (ur_ruled_start(&ruled) + ur_ruled_end(&ruled)) / 2;
    ur_analyze_point(&ruled, middle, 0.0, &point);
    assert_relative(point.bend_radius, offset * radius / rise, 1e-2);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
}

/* ---- Not developable ---------------------------------------------------- */

static void test_hyperbolic_paraboloid(void **state)
{
    (void)state;
    double c = 50, w = 40, h = 30;
    ur_ruled ruled = hyperbolic_paraboloid(c, w, h);
    ur_analysis analysis = analyze(&ruled, 257, 17);
    assert_false(analysis.developable);
    assert_true(analysis.max_residual > 0.1);
    /* K at points spread over the surface */
    for (int i = 0; i <= 4; i++)
        for (int j = 0; j <= 4; j++) {
            double u = ur_ruled_start(&ruled) +
                       (ur_ruled_end(&ruled) - ur_ruled_start(&ruled)) * (0.1 + 0.2 * i);
            ur_point_curvature point;
            ur_analyze_point(&ruled, u, 0.25 * j, &point);
            double x = point.point.x, y = point.point.y;
            assert_small(point.point.z - x * y / c, 1e-9 * c);
            double q = 1 + (x * x + y * y) / (c * c);
            assert_relative(point.gaussian, -1 / (c * c) / (q * q), 1e-8);
        }
    /* the saddle point: principal curvatures +-1/c */
    ur_point_curvature saddle;
    ur_analyze_point(&ruled, (ur_ruled_start(&ruled) + ur_ruled_end(&ruled)) / 2, 0.5, &saddle);
    assert_small(ur_vec3_length(saddle.point), 1e-9);
    assert_small(saddle.mean, 1e-9);
    assert_relative(saddle.bend_radius, c, 1e-7);
    /* |K| is largest at the saddle point and smallest at the corners */
    assert_relative(analysis.gaussian_min, -1 / (c * c), 1e-8);
    assert_small(ur_vec3_length(analysis.gaussian_min_at), 1e-9);
    double corner = 1 + (w * w + h * h) / (c * c);
    assert_relative(analysis.gaussian_max, -1 / (c * c) / (corner * corner), 1e-8);
    /* the total curvature is minus the solid angle of the Gauss image */
    double total = -4 * atan(w * h / (c * sqrt(c * c + w * w + h * h)));
    assert_relative(analysis.gaussian_mean * analysis.area_3d, total, 2e-3);
    /* the principal curvatures are largest at the saddle point too */
    assert_relative(analysis.min_bend_radius, c, 1e-7);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
}

/* ---- PNG ---------------------------------------------------------------- */

typedef struct png_counts {
    int height;
    size_t green, blue;
} png_counts;

/*
 * Loads path, checks its size (1000 px wide, at most 720 tall), and counts
 * clearly green and clearly blue pixels.
 */
static png_counts load_png(const char *path)
{
    cairo_surface_t *image = cairo_image_surface_create_from_png(path);
    assert_int_equal(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
    assert_int_equal(UR_ANALYSIS_PNG_WIDTH, 1000);
    assert_int_equal(UR_ANALYSIS_PNG_MAX_HEIGHT, 720);
    assert_int_equal(cairo_image_surface_get_width(image), 1000);
    png_counts counts = {cairo_image_surface_get_height(image), 0, 0};
    assert_in_range(counts.height, 200, 720);
    const unsigned char *data = cairo_image_surface_get_data(image);
    int stride = cairo_image_surface_get_stride(image);
    for (int y = 0; y < counts.height; y++)
        for (int x = 0; x < UR_ANALYSIS_PNG_WIDTH; x++) {
            uint32_t pixel;
            memcpy(&pixel, data + y * stride + 4 * x, sizeof pixel);
            int r = (pixel >> 16) & 0xff, g = (pixel >> 8) & 0xff, b = pixel & 0xff;
            counts.green += g > r + 60 && g > b + 60;
            counts.blue += b > r + 60 && b > g + 60;
        }
    cairo_surface_destroy(image);
    return counts;
}

/* A fresh directory under /tmp for each PNG test, removed even when the test fails. */
static int make_directory(void **state)
{
    char *directory = malloc(64);
    if (!directory)
        return -1;
    snprintf(directory, 64, "/tmp/unroll-test-analyze-XXXXXX");
    if (!mkdtemp(directory)) {
        free(directory);
        return -1;
    }
    *state = directory;
    return 0;
}

static int remove_directory(void **state)
{
    char *directory = *state;
    int status = remove_test_directory(directory);
    free(directory);
    return status;
}

static void test_png(void **state)
{
    const char *directory = *state;
    char path[128];
    ur_error error;

    /* A developable is green and nothing on it blue. */
    ur_ruled ruled = cylinder(40, 120);
    ur_analysis analysis = analyze(&ruled, 64, 9);
    snprintf(path, sizeof path, "%s/cylinder.png", directory);
    if (ur_analysis_png_write(path, &ruled, &analysis, "cylinder R 40", NULL, &error) != UR_OK)
        fail_msg("png: %s", error.message);
    png_counts counts = load_png(path);
    /* the map is 2 pi 40 x 120 mm, far more than 100 x 100 px at any sensible scale */
    assert_true(counts.green > 100 * 100);
    assert_true(counts.blue < 100);
    int squat = counts.height;
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);

    /* The map keeps the proportions: a tall cylinder makes a taller picture. */
    ruled = cylinder(5, 500);
    analysis = analyze(&ruled, 16, 5);
    snprintf(path, sizeof path, "%s/tall.png", directory);
    if (ur_analysis_png_write(path, &ruled, &analysis, "cylinder R 5", NULL, &error) != UR_OK)
        fail_msg("png: %s", error.message);
    counts = load_png(path);
    assert_true(counts.height > squat);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);

    /* A hyperbolic paraboloid is blue. */
    ruled = hyperbolic_paraboloid(50, 40, 30);
    analysis = analyze(&ruled, 64, 17);
    snprintf(path, sizeof path, "%s/hypar.png", directory);
    if (ur_analysis_png_write(path, &ruled, &analysis, NULL, NULL, &error) != UR_OK)
        fail_msg("png: %s", error.message);
    counts = load_png(path);
    assert_true(counts.blue > 100 * 100);
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
    assert_int_equal(entries_in(directory), 3);
}

static void test_png_failures_leave_nothing(void **state)
{
    const char *directory = *state;
    char path[160];
    ur_ruled ruled = helicoid(30, 10, 0.5, 5, 20);
    ur_analysis analysis = analyze(&ruled, 16, 5);
    ur_error error;

    /* into a directory that is not there */
    snprintf(path, sizeof path, "%s/missing/map.png", directory);
    assert_int_equal(ur_analysis_png_write(path, &ruled, &analysis, "t", NULL, &error),
                     UR_ERROR_IO);
    assert_non_null(strstr(error.message, "does not exist"));
    struct stat info;
    snprintf(path, sizeof path, "%s/missing", directory);
    assert_int_equal(stat(path, &info), -1);

    /* a failure leaves an existing file as it was */
    snprintf(path, sizeof path, "%s/map.png", directory);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_int_equal(fputs("old", file) >= 0, 1);
    assert_int_equal(fclose(file), 0);
    ur_analysis empty = {0};
    assert_int_not_equal(ur_analysis_png_write(path, &ruled, &empty, "t", NULL, &error), UR_OK);
    char text[16] = {0};
    file = fopen(path, "r");
    assert_non_null(file);
    assert_non_null(fgets(text, sizeof text, file));
    assert_int_equal(fclose(file), 0);
    assert_string_equal(text, "old");

    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
    assert_int_equal(entries_in(directory), 1); /* map.png only: no temporary left */
}

/* cairo keeps font caches for the life of the process; let them go before the leak check. */
static int release_cairo(void **state)
{
    (void)state;
    cairo_debug_reset_static_data();
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_options),
        cmocka_unit_test(test_cylinder),
        cmocka_unit_test(test_cone_frustum),
        cmocka_unit_test(test_cone_apex_is_singular),
        cmocka_unit_test(test_helicoid),
        cmocka_unit_test(test_helicoid_from_its_edge),
        cmocka_unit_test(test_interpolated_tangent_developable),
        cmocka_unit_test(test_hyperbolic_paraboloid),
        cmocka_unit_test_setup_teardown(test_png, make_directory, remove_directory),
        cmocka_unit_test_setup_teardown(test_png_failures_leave_nothing, make_directory,
                                        remove_directory),
    };
    return cmocka_run_group_tests(tests, NULL, release_cairo);
}
