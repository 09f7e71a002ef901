/*
 * test_compare.c: ur_compare, the seed paper's observation ([Seed2018] in
 * docs/bibliography.md) measured, and its plot and CSV writers.
 *
 * On the reference helicoid of docs/algorithms.md, section 5 (R 30, pitch
 * 20 pi, a quarter turn, L 25) the triangle net must come out smaller and the
 * quad net larger than the surface at every n, both converging, with the
 * reference figures at n = 16.  On a frustum of a right circular cone the
 * quad method flattens planar trapezoids, so its net is the inscribed
 * polygonal frustum and every figure has a closed form.  Expected values
 * come from closed forms, the reference figures or rigid-motion invariants
 * computed here, never from the code under test.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unroll/out.h"

#include "test_support.h"

enum { TRIANGLE = UR_COMPARE_TRIANGLE, QUAD = UR_COMPARE_QUAD, EXACT = UR_COMPARE_EXACT };

#define HELIX_RADIUS 30.0
#define HELIX_C 10.0 /* pitch / 2 pi */
#define WIDTH 25.0
#define CONE_RADIUS 60.0
#define CONE_HEIGHT 80.0 /* slant 100 */
#define CONE_CUT 0.5     /* the frustum's top: radius 30, slant 50 */

#define assert_below(actual, bound)                                                                \
    do {                                                                                           \
        double a_ = (actual), b_ = (bound);                                                        \
        if (!(a_ <= b_))                                                                           \
            fail_msg("%s = %.6g, not at most %.6g", #actual, a_, b_);                              \
    } while (0)

/* Both tables are computed once: the sanitizer build is slow. */
typedef struct fixture {
    ur_ruled helicoid, frustum;
    ur_compare_table helicoid_table, frustum_table;
    char dir[64];
} fixture;

static void make_helicoid(ur_ruled *ruled)
{
    ur_curve *curve;
    assert_int_equal(
        ur_curve_new_helix(HELIX_RADIUS, 2 * M_PI * HELIX_C, 0, M_PI / 2, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, 0, WIDTH, ruled, NULL), UR_OK);
}

static void make_frustum(ur_ruled *ruled)
{
    ur_curve *circle;
    assert_int_equal(ur_curve_new_circle(CONE_RADIUS, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cone(circle, ur_vec3_make(0, 0, CONE_HEIGHT), CONE_CUT, ruled, NULL),
                     UR_OK);
}

static void compare(ur_ruled *ruled, ur_compare_table *table)
{
    ur_error error;
    if (ur_compare(ruled, 8, 4096, table, &error) != UR_OK)
        fail_msg("compare: %s", error.message);
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/unroll-test-compare-XXXXXX");
    if (!mkdtemp(f->dir)) {
        free(f);
        return -1;
    }
    make_helicoid(&f->helicoid);
    make_frustum(&f->frustum);
    compare(&f->helicoid, &f->helicoid_table);
    compare(&f->frustum, &f->frustum_table);
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    remove_test_directory(f->dir);
    ur_compare_table_free(&f->helicoid_table);
    ur_compare_table_free(&f->frustum_table);
    ur_ruled_free(&f->helicoid);
    ur_ruled_free(&f->frustum);
    free(f);
    cairo_debug_reset_static_data(); /* cairo's font caches: see below */
    return 0;
}

/* ---- The helicoid ------------------------------------------------------- */

/* 8, 16, ..., 4096: ten rows. */
static void assert_doubling_rows(const ur_compare_table *table)
{
    assert_int_equal(table->count, 10);
    for (size_t r = 0; r < table->count; r++)
        assert_int_equal(table->rows[r].n, (size_t)8 << r);
}

/* The exact net's own errors are tiny and do not depend on n. */
static void assert_exact_is_exact(const ur_compare_table *table)
{
    for (size_t r = 0; r < table->count; r++) {
        const ur_compare_row *row = &table->rows[r];
        assert_true(row->available[EXACT]);
        assert_below(fabs(row->area_error[EXACT]), 1e-6);
        assert_below(row->edge_error[EXACT], 1e-6);
        assert_true(row->distance[EXACT] == 0);
    }
}

/* |area error|, edge error and distance of method k all shrink as n doubles. */
static void assert_converging(const ur_compare_table *table, int k)
{
    for (size_t r = 1; r < table->count; r++) {
        const ur_compare_row *row = &table->rows[r], *previous = &table->rows[r - 1];
        if (!(fabs(row->area_error[k]) < fabs(previous->area_error[k])))
            fail_msg("method %d: |area error| %g at n = %zu after %g", k, row->area_error[k],
                     row->n, previous->area_error[k]);
        if (!(row->edge_error[k] < previous->edge_error[k]))
            fail_msg("method %d: edge error %g at n = %zu after %g", k, row->edge_error[k], row->n,
                     previous->edge_error[k]);
        if (!(row->distance[k] < previous->distance[k]))
            fail_msg("method %d: distance %g at n = %zu after %g", k, row->distance[k], row->n,
                     previous->distance[k]);
    }
}

/* Triangle net < surface < quad net at every n, both errors shrinking. */
static void test_helicoid_sign_pattern(void **state)
{
    const ur_compare_table *table = &((fixture *)*state)->helicoid_table;
    assert_doubling_rows(table);
    for (size_t r = 0; r < table->count; r++) {
        const ur_compare_row *row = &table->rows[r];
        assert_true(row->available[TRIANGLE] && row->available[QUAD]);
        if (!(row->area_error[TRIANGLE] < 0 && 0 < row->area_error[QUAD]))
            fail_msg("n = %zu: triangle %g, quad %g", row->n, row->area_error[TRIANGLE],
                     row->area_error[QUAD]);
        assert_true(row->distance[TRIANGLE] > 0 && row->distance[QUAD] > 0);
    }
    assert_converging(table, TRIANGLE);
    assert_converging(table, QUAD);
    assert_exact_is_exact(table);
}

/* docs/algorithms.md, section 5: n = 16 gives triangle 436.1, quad 522.8, surface 465.68 mm^2. */
static void test_helicoid_design_figures(void **state)
{
    const ur_compare_table *table = &((fixture *)*state)->helicoid_table;
    /* area = s kappa L^2 / 2, s the arc length of the edge, kappa = R / (R^2 + c^2) */
    double speed = sqrt(HELIX_RADIUS * HELIX_RADIUS + HELIX_C * HELIX_C);
    double kappa = HELIX_RADIUS / (speed * speed);
    assert_relative(table->area_3d, (M_PI / 2) * speed * kappa * WIDTH * WIDTH / 2, 1e-10);
    assert_relative(table->area_3d, 465.68, 1e-4);
    const ur_compare_row *row = &table->rows[1];
    assert_int_equal(row->n, 16);
    assert_relative(table->area_3d * (1 + row->area_error[TRIANGLE]), 436.1, 2e-4);
    assert_relative(table->area_3d * (1 + row->area_error[QUAD]), 522.8, 2e-4);
}

/*
 * The quad method keeps the chords P_i P_i+1 of the edge of regression, so
 * its flat edge is short of the helix by at least 1 - chord n / arc.
 */
static void test_helicoid_quad_edge_at_least_chord_deficit(void **state)
{
    const ur_compare_table *table = &((fixture *)*state)->helicoid_table;
    double arc = (M_PI / 2) * sqrt(HELIX_RADIUS * HELIX_RADIUS + HELIX_C * HELIX_C);
    for (size_t r = 0; r < table->count; r++) {
        double n = (double)table->rows[r].n, step = (M_PI / 2) / n;
        double chord = 2 * hypot(HELIX_RADIUS * sin(step / 2), HELIX_C * step / 2);
        double deficit = 1 - n * chord / arc;
        assert_true(deficit > 0);
        assert_below(deficit * (1 - 1e-6), table->rows[r].edge_error[QUAD]);
    }
}

/* ---- The distance against a rigid-motion invariant ---------------------- */

/* The helicoid's net by method with n parts: one piece, with its n - 1 interior rulings. */
static ur_net_list develop_one(ur_ruled *ruled, ur_method method, size_t n, double tolerance)
{
    ur_net_list nets = develop(ruled, method, n, tolerance);
    assert_int_equal(nets.count, 1);
    assert_int_equal(nets.nets[0].ruling_count, n - 1);
    return nets;
}

/* Ends of ruling i (0 near, 1 far) of a net: point 2 i + end. */
static ur_vec2 ruling_end(const ur_net *net, size_t point)
{
    const ur_segment *ruling = &net->rulings[point / 2];
    return point % 2 == 0 ? ruling->start : ruling->end;
}

/*
 * Distances between points do not change under a rigid motion or a mirror,
 * so if two nets differ in the distance between points p and q by D, some
 * point of one lies at least D / 2 from its place in the other however they
 * are fitted.  Checked on the interior rulings, which every net draws.
 */
static double rigid_lower_bound(const ur_net *a, const ur_net *b)
{
    size_t points = 2 * a->ruling_count;
    double bound = 0;
    for (size_t p = 0; p < points; p++)
        for (size_t q = p + 1; q < points; q++) {
            double da = ur_vec2_distance(ruling_end(a, p), ruling_end(a, q));
            double db = ur_vec2_distance(ruling_end(b, p), ruling_end(b, q));
            bound = fmax(bound, fabs(da - db) / 2);
        }
    return bound;
}

static void test_distance_at_least_invariant_bound(void **state)
{
    fixture *f = *state;
    const ur_compare_row *row = &f->helicoid_table.rows[1];
    assert_int_equal(row->n, 16);
    ur_net_list exact = develop_one(&f->helicoid, UR_METHOD_EXACT, 16, 1e-5);
    ur_net_list triangle = develop_one(&f->helicoid, UR_METHOD_TRIANGLE, 16, 0.01);
    ur_net_list quad = develop_one(&f->helicoid, UR_METHOD_QUAD, 16, 0.01);
    double triangle_bound = rigid_lower_bound(&triangle.nets[0], &exact.nets[0]);
    double quad_bound = rigid_lower_bound(&quad.nets[0], &exact.nets[0]);
    assert_true(triangle_bound > 0.1 && quad_bound > 0.1); /* visibly different nets */
    assert_below(triangle_bound, row->distance[TRIANGLE] * (1 + 1e-9));
    assert_below(quad_bound, row->distance[QUAD] * (1 + 1e-9));
    ur_net_list_free(&exact);
    ur_net_list_free(&triangle);
    ur_net_list_free(&quad);
}

/* ---- The frustum: quad only, closed forms ------------------------------- */

/*
 * Each quad P_i P_i+1 A_i+1 A_i of a frustum of a right circular cone is a
 * planar isosceles trapezoid with parallel sides the chords of the two
 * circles, so the quad net is the inscribed polygonal frustum: smaller than
 * the surface, with the chords' relative deficit as its edge error.
 */
static void test_frustum_quad_closed_forms(void **state)
{
    const ur_compare_table *table = &((fixture *)*state)->frustum_table;
    double top = CONE_RADIUS * (1 - CONE_CUT);
    double slant = CONE_CUT * hypot(CONE_RADIUS, CONE_HEIGHT);
    assert_relative(table->area_3d, M_PI * (CONE_RADIUS + top) * slant, 1e-10);
    assert_doubling_rows(table);
    for (size_t r = 0; r < table->count; r++) {
        const ur_compare_row *row = &table->rows[r];
        double n = (double)row->n, half = M_PI / n;
        double bottom_chord = 2 * CONE_RADIUS * sin(half), top_chord = 2 * top * sin(half);
        double height = sqrt(slant * slant - pow((bottom_chord - top_chord) / 2, 2));
        double flat = n * (bottom_chord + top_chord) / 2 * height;
        assert_true(row->area_error[QUAD] < 0);
        assert_relative(table->area_3d * (1 + row->area_error[QUAD]), flat, 1e-10);
        /* the 3D arc length is a quadrature: allow for its last digits */
        double edge = 1 - n * sin(half) / M_PI;
        if (!(fabs(row->edge_error[QUAD] - edge) <= 1e-6 * edge + 1e-11))
            fail_msg("n = %zu: edge error %.9g, expected %.9g", row->n, row->edge_error[QUAD],
                     edge);
    }
    assert_converging(table, QUAD);
    assert_exact_is_exact(table);
}

/* The triangle method needs a tangent developable. */
static void test_frustum_has_no_triangle_method(void **state)
{
    const ur_compare_table *table = &((fixture *)*state)->frustum_table;
    for (size_t r = 0; r < table->count; r++) {
        const ur_compare_row *row = &table->rows[r];
        assert_false(row->available[TRIANGLE]);
        assert_true(row->available[QUAD]);
        assert_true(isnan(row->area_error[TRIANGLE]) && isnan(row->edge_error[TRIANGLE]) &&
                    isnan(row->distance[TRIANGLE]));
    }
}

static void test_bad_ranges_refused(void **state)
{
    fixture *f = *state;
    ur_compare_table table;
    ur_error error;
    assert_int_equal(ur_compare(&f->helicoid, 0, 8, &table, &error), UR_ERROR_INPUT);
    assert_null(table.rows);
    assert_int_equal(table.count, 0);
    assert_int_equal(ur_compare(&f->helicoid, 16, 8, &table, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "n_min"));
    /* n_max need not be n_min times a power of two */
    assert_int_equal(ur_compare(&f->helicoid, 3, 20, &table, &error), UR_OK);
    assert_int_equal(table.count, 3); /* 3, 6, 12 */
    assert_int_equal(table.rows[2].n, 12);
    ur_compare_table_free(&table);
    assert_null(table.rows);
}

/* ---- Files -------------------------------------------------------------- */

static void test_png_loads_with_its_size(void **state)
{
    fixture *f = *state;
    int before = entries_in(f->dir);
    char path[256];
    path_in(f->dir, "helicoid.png", path, sizeof path);
    ur_error error;
    if (ur_compare_plot_png(path, &f->helicoid_table, "helicoid", NULL, &error) != UR_OK)
        fail_msg("plot: %s", error.message);
    path_in(f->dir, "frustum.png", path, sizeof path);
    if (ur_compare_plot_png(path, &f->frustum_table, NULL, NULL, &error) != UR_OK)
        fail_msg("plot: %s", error.message);
    const char *names[] = {"helicoid.png", "frustum.png"};
    for (int i = 0; i < 2; i++) {
        path_in(f->dir, names[i], path, sizeof path);
        cairo_surface_t *image = cairo_image_surface_create_from_png(path);
        assert_int_equal(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
        assert_int_equal(cairo_image_surface_get_width(image), 900);
        assert_int_equal(cairo_image_surface_get_height(image), 600);
        cairo_surface_destroy(image);
    }
    assert_int_equal(entries_in(f->dir), before + 2); /* no temporaries left */
}

/* Splits a CSV line in place into at most capacity fields; returns how many. */
static size_t split_fields(char *line, char **fields, size_t capacity)
{
    size_t count = 0;
    for (char *field = line; field && count < capacity; count++) {
        fields[count] = field;
        char *comma = strchr(field, ',');
        if (comma)
            *comma = '\0';
        field = comma ? comma + 1 : NULL;
    }
    return count;
}

/* Reads the CSV back: a header, then one line per row with every number. */
static void check_csv(const char *path, const ur_compare_table *table)
{
    static const char header[] =
        "n,triangle_area_error,quad_area_error,exact_area_error,triangle_edge_error,"
        "quad_edge_error,exact_edge_error,triangle_distance,quad_distance\n";
    FILE *file = fopen(path, "r");
    assert_non_null(file);
    char line[1024];
    size_t lines = 0;
    while (fgets(line, sizeof line, file)) {
        if (lines++ == 0) {
            assert_string_equal(line, header);
            continue;
        }
        const ur_compare_row *row = &table->rows[lines - 2];
        line[strcspn(line, "\n")] = '\0';
        char *fields[16];
        assert_int_equal(split_fields(line, fields, 16), 9);
        assert_int_equal(strtoull(fields[0], NULL, 10), row->n);
        const double expected[9] = {0,
                                    row->area_error[0],
                                    row->area_error[1],
                                    row->area_error[2],
                                    row->edge_error[0],
                                    row->edge_error[1],
                                    row->edge_error[2],
                                    row->distance[0],
                                    row->distance[1]};
        for (int c = 1; c < 9; c++) {
            bool triangle = c == 1 || c == 4 || c == 7;
            if (triangle && !row->available[TRIANGLE])
                assert_string_equal(fields[c], "");
            else
                assert_true(strtod(fields[c], NULL) == expected[c]); /* %.17g round-trips */
        }
    }
    fclose(file);
    assert_int_equal(lines, table->count + 1);
}

static void test_csv_lines(void **state)
{
    fixture *f = *state;
    char helicoid[256], frustum[256];
    path_in(f->dir, "helicoid.csv", helicoid, sizeof helicoid);
    path_in(f->dir, "frustum.csv", frustum, sizeof frustum);
    ur_error error;
    assert_int_equal(ur_compare_csv_write(helicoid, &f->helicoid_table, NULL, &error), UR_OK);
    assert_int_equal(ur_compare_csv_write(frustum, &f->frustum_table, NULL, &error), UR_OK);
    check_csv(helicoid, &f->helicoid_table);
    check_csv(frustum, &f->frustum_table);
}

static void test_missing_directory_leaves_nothing(void **state)
{
    fixture *f = *state;
    int before = entries_in(f->dir);
    char missing[256], png[300], csv[300];
    path_in(f->dir, "missing", missing, sizeof missing);
    snprintf(png, sizeof png, "%s/plot.png", missing);
    snprintf(csv, sizeof csv, "%s/table.csv", missing);
    ur_error error;
    ur_status status = ur_compare_plot_png(png, &f->helicoid_table, "x", NULL, &error);
    assert_int_equal(status, UR_ERROR_IO);
    assert_non_null(strstr(error.message, "missing"));
    status = ur_compare_csv_write(csv, &f->helicoid_table, NULL, &error);
    assert_int_equal(status, UR_ERROR_IO);
    assert_false(exists(missing));
    assert_int_equal(entries_in(f->dir), before);
}

/* A table with no rows is refused before anything is opened: the old file stays. */
static void test_empty_table_leaves_file_untouched(void **state)
{
    fixture *f = *state;
    char path[256];
    path_in(f->dir, "kept.csv", path, sizeof path);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_true(fputs("old\n", file) >= 0);
    assert_int_equal(fclose(file), 0);
    int before = entries_in(f->dir);
    ur_compare_table empty = {NULL, 0, 0};
    ur_error error;
    assert_int_equal(ur_compare_csv_write(path, &empty, NULL, &error), UR_ERROR_INTERNAL);
    assert_int_equal(ur_compare_plot_png(path, &empty, NULL, NULL, &error), UR_ERROR_INTERNAL);
    file = fopen(path, "r");
    assert_non_null(file);
    char line[16] = "";
    assert_non_null(fgets(line, sizeof line, file));
    fclose(file);
    assert_string_equal(line, "old\n");
    assert_int_equal(entries_in(f->dir), before);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_helicoid_sign_pattern),
        cmocka_unit_test(test_helicoid_design_figures),
        cmocka_unit_test(test_helicoid_quad_edge_at_least_chord_deficit),
        cmocka_unit_test(test_distance_at_least_invariant_bound),
        cmocka_unit_test(test_frustum_quad_closed_forms),
        cmocka_unit_test(test_frustum_has_no_triangle_method),
        cmocka_unit_test(test_bad_ranges_refused),
        cmocka_unit_test(test_png_loads_with_its_size),
        cmocka_unit_test(test_csv_lines),
        cmocka_unit_test(test_missing_directory_leaves_nothing),
        cmocka_unit_test(test_empty_table_leaves_file_untouched),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
