/*
 * test_flatten.c: LSCM and ARAP on meshes built here (arrays filled by
 * hand, so that these tests need nothing of the mesh module): developable
 * meshes come out without strain, a saddle comes out with some and with
 * less ARAP energy than LSCM's, strain of layouts made by hand, options,
 * and pieces that cannot be flattened; no triangle turned over on pieces
 * far from flat.  Last, charts within a material's strain on the meshes of
 * samples/make-meshes.py (run from the repository root).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/flatten.h"
#include "unroll/io.h"

/* A surface patch over (s, t) in [0, 1]^2. */
typedef ur_vec3 (*surface_fn)(double s, double t);

/*
 * An ns x nt grid of quads over f, each cut into two triangles running
 * counter-clockwise in (s, t); wrap joins s = 1 back to s = 0 (a ring).
 * The arrays are malloc'd here and freed by free_mesh.
 */
static ur_mesh grid(size_t ns, size_t nt, bool wrap, surface_fn f)
{
    size_t columns = wrap ? ns : ns + 1;
    ur_mesh mesh = {0};
    mesh.vertex_count = columns * (nt + 1);
    mesh.triangle_count = 2 * ns * nt;
    mesh.vertices = malloc(mesh.vertex_count * sizeof *mesh.vertices);
    mesh.triangles = malloc(mesh.triangle_count * sizeof *mesh.triangles);
    assert_non_null(mesh.vertices);
    assert_non_null(mesh.triangles);
    for (size_t j = 0; j <= nt; j++)
        for (size_t i = 0; i < columns; i++)
            mesh.vertices[j * columns + i] = f((double)i / ns, (double)j / nt);
    size_t t = 0;
    for (size_t j = 0; j < nt; j++)
        for (size_t i = 0; i < ns; i++) {
            size_t a = j * columns + i, b = j * columns + (i + 1) % columns;
            size_t c = b + columns, d = a + columns;
            size_t first[3] = {a, b, c}, second[3] = {a, c, d};
            memcpy(mesh.triangles[t++], first, sizeof first);
            memcpy(mesh.triangles[t++], second, sizeof second);
        }
    mesh.group_count = 1;
    return mesh;
}

static void free_mesh(ur_mesh *mesh)
{
    free(mesh->vertices);
    free(mesh->triangles);
    free(mesh->groups);
}

/* A 120 x 70 rectangle in a tilted plane. */
static ur_vec3 tilted_plane(double s, double t)
{
    ur_vec3 a = {0.6, 0.8, 0}, b = {0, 0, 1};
    double c = cos(0.3), d = sin(0.3);
    ur_vec3 b2 = ur_vec3_add(ur_vec3_scale(b, c), ur_vec3_scale(ur_vec3_make(-0.8, 0.6, 0), d));
    return ur_vec3_add(ur_vec3_make(5, -3, 2),
                       ur_vec3_add(ur_vec3_scale(a, 120 * s), ur_vec3_scale(b2, 70 * t)));
}

/* A quarter of a tube of radius 50, 100 long. */
static ur_vec3 quarter_tube(double s, double t)
{
    double angle = 0.5 * M_PI * s;
    return ur_vec3_make(50 * cos(angle), 50 * sin(angle), 100 * t);
}

/* A small deterministic noise in [-0.5, 0.5). */
static double noise(double i, double j)
{
    double x = sin(i * 12.9898 + j * 78.233) * 43758.5453;
    return x - floor(x) - 0.5;
}

/* Grid size of jittered_tube (surface_fn takes no context). */
static size_t jitter_size = 40;

/*
 * The quarter tube with every inner vertex moved along the surface by up
 * to 0.3 of a grid step: still on the cylinder, but no longer on a grid of
 * rulings, so the polyhedron is not exactly developable (its vertices have
 * small angle defects that vanish as the grid is refined).
 */
static ur_vec3 jittered_tube(double s, double t)
{
    double n = (double)jitter_size, i = round(s * n), j = round(t * n);
    if (i > 0 && i < n && j > 0 && j < n) {
        s += 0.6 * noise(i, j) / n;
        t += 0.6 * noise(j + 7, i + 3) / n;
    }
    return quarter_tube(s, t);
}

/* Half of a cone of half-angle 30 degrees between distances 20 and 80 from the apex. */
static ur_vec3 half_cone(double s, double t)
{
    double angle = M_PI * s, distance = 20 + 60 * t;
    double r = distance * sin(M_PI / 6), z = distance * cos(M_PI / 6);
    return ur_vec3_make(r * cos(angle), r * sin(angle), z);
}

/* The hyperbolic paraboloid z = x y / 200 over a 100 x 100 square. */
static ur_vec3 saddle(double s, double t)
{
    double x = 100 * s - 50, y = 100 * t - 50;
    return ur_vec3_make(x, y, x * y / 200);
}

/* A flat ring between radii 30 and 60: a disk with a hole. */
static ur_vec3 flat_ring(double s, double t)
{
    double angle = 2 * M_PI * s, r = 30 + 30 * t;
    return ur_vec3_make(r * cos(angle), r * sin(angle), 0);
}

/*
 * A grid sheared so far that the angle opposite every diagonal is about
 * 167 degrees: the diagonals' cotangent weights are strongly negative.
 */
static ur_vec3 sheared(double s, double t)
{
    return ur_vec3_make(20 * s + 18 * t, 4 * t, 0);
}

static ur_vec3 sheared_saddle(double s, double t)
{
    ur_vec3 p = sheared(s, t);
    double x = 5 * (p.x - 19), y = 5 * (p.y - 2);
    return ur_vec3_make(x, y, x * y / 200);
}

static ur_flat_piece flatten(const ur_mesh *mesh, ur_flatten_method method)
{
    ur_flatten_options options;
    ur_flatten_options_default(&options);
    options.method = method;
    ur_flat_piece flat;
    ur_error error;
    if (ur_flatten(mesh, &options, &flat, &error) != UR_OK)
        fail_msg("flatten: %s", error.message);
    assert_int_equal(flat.vertex_count, mesh->vertex_count);
    assert_int_equal(flat.triangle_count, mesh->triangle_count);
    return flat;
}

/* The largest |sigma - 1| of a layout. */
static double worst_strain(const ur_flat_piece *flat)
{
    double worst = 0;
    for (size_t t = 0; t < flat->triangle_count; t++) {
        worst = fmax(worst, fabs(flat->strain[t].sigma1 - 1));
        worst = fmax(worst, fabs(flat->strain[t].sigma2 - 1));
    }
    return worst;
}

/* Every singular value within tolerance of 1, and nothing turned over. */
static void assert_no_strain(const ur_flat_piece *flat, double tolerance)
{
    double worst = worst_strain(flat);
    if (!(worst <= tolerance))
        fail_msg("largest |sigma - 1| = %.3g, expected within %g", worst, tolerance);
    assert_true(flat->max_stretch <= tolerance);
    assert_true(flat->max_compression <= tolerance);
    assert_false(flat->flipped);
}

/* Every edge keeps its 3D length to the relative tolerance. */
static void assert_edges_kept(const ur_mesh *mesh, const ur_flat_piece *flat, double tolerance)
{
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            size_t a = mesh->triangles[t][k], b = mesh->triangles[t][(k + 1) % 3];
            double space = ur_vec3_distance(mesh->vertices[a], mesh->vertices[b]);
            double plane = ur_vec2_distance(flat->flat[a], flat->flat[b]);
            if (!(fabs(plane - space) <= tolerance * space))
                fail_msg("edge %zu-%zu: flat %.12g, 3D %.12g", a, b, plane, space);
        }
}

static void test_method_names_and_defaults(void **state)
{
    (void)state;
    assert_string_equal(ur_flatten_method_name(UR_FLATTEN_ARAP), "arap");
    assert_string_equal(ur_flatten_method_name(UR_FLATTEN_LSCM), "lscm");
    assert_int_equal(ur_flatten_method_from_name("arap"), UR_FLATTEN_ARAP);
    assert_int_equal(ur_flatten_method_from_name("lscm"), UR_FLATTEN_LSCM);
    assert_int_equal(ur_flatten_method_from_name("ARAP"), -1);
    assert_int_equal(ur_flatten_method_from_name("smash"), -1);
    assert_int_equal(ur_flatten_method_from_name(""), -1);
    assert_int_equal(ur_flatten_method_from_name(NULL), -1);
    ur_flatten_options options;
    ur_flatten_options_default(&options);
    assert_int_equal(options.method, UR_FLATTEN_ARAP);
    assert_int_equal(options.iterations, 100);
    assert_true(options.tolerance == 1e-9);
}

/* A plane grid comes back as itself, moved rigidly: both methods. */
static void test_flat_grid_is_kept(void **state)
{
    (void)state;
    ur_mesh mesh = grid(24, 14, false, tilted_plane);
    for (int m = 0; m < 2; m++) {
        ur_flat_piece flat = flatten(&mesh, m == 0 ? UR_FLATTEN_ARAP : UR_FLATTEN_LSCM);
        assert_no_strain(&flat, 1e-9);
        assert_edges_kept(&mesh, &flat, 1e-9);
        assert_true(fabs(flat.area_3d - 120 * 70) <= 1e-9 * 120 * 70);
        assert_true(fabs(flat.coverage - 1) <= 1e-9);
        /* Strain is measured from the layout, not assumed: a far corner is where it must be. */
        assert_true(fabs(ur_vec2_distance(flat.flat[0], flat.flat[mesh.vertex_count - 1]) -
                         hypot(120, 70)) <= 1e-9 * 140);
        ur_flat_piece_free(&flat);
    }
    free_mesh(&mesh);
}

/* A triangulated quarter tube is a developable polyhedron: no strain. */
static void test_quarter_tube_has_no_strain(void **state)
{
    (void)state;
    ur_mesh mesh = grid(40, 40, false, quarter_tube);
    ur_flat_piece flat = flatten(&mesh, UR_FLATTEN_ARAP);
    assert_no_strain(&flat, 1e-3);
    assert_true(fabs(flat.coverage - 1) <= 1e-3);
    assert_true(fabs(flat.flat_area - flat.area_3d) <= 1e-3 * flat.area_3d);
    /* The unrolled width is the polygon's perimeter: 40 chords of the quarter circle. */
    double perimeter = 40 * 2 * 50 * sin(M_PI / 160);
    assert_true(fabs(ur_vec2_distance(flat.flat[0], flat.flat[40]) - perimeter) <= 1e-3);
    ur_flat_piece_free(&flat);
    free_mesh(&mesh);
}

static void test_cone_has_no_strain(void **state)
{
    (void)state;
    ur_mesh mesh = grid(60, 20, false, half_cone);
    ur_flat_piece flat = flatten(&mesh, UR_FLATTEN_ARAP);
    assert_no_strain(&flat, 1e-3);
    assert_true(fabs(flat.coverage - 1) <= 1e-3);
    assert_edges_kept(&mesh, &flat, 1e-3);
    ur_flat_piece_free(&flat);
    free_mesh(&mesh);
}

/*
 * A jittered tube is not exactly developable, so LSCM is not exact and
 * ARAP has work to do; what strain is left must be the triangulation's own
 * (vanishing as the grid is refined, like h^2), not invented.
 */
static void test_jittered_tube_converges(void **state)
{
    (void)state;
    double worst[2];
    for (int k = 0; k < 2; k++) {
        jitter_size = k == 0 ? 20 : 80;
        ur_mesh mesh = grid(jitter_size, jitter_size, false, jittered_tube);
        ur_flat_piece arap = flatten(&mesh, UR_FLATTEN_ARAP);
        ur_flat_piece lscm = flatten(&mesh, UR_FLATTEN_LSCM);
        assert_true(arap.iterations > 1);
        worst[k] = worst_strain(&arap);
        assert_true(worst[k] < worst_strain(&lscm));
        ur_flat_piece_free(&arap);
        ur_flat_piece_free(&lscm);
        free_mesh(&mesh);
    }
    assert_true(worst[1] < worst[0] / 8); /* four times finer: about 16 times less */
    jitter_size = 40;
    ur_mesh mesh = grid(jitter_size, jitter_size, false, jittered_tube);
    ur_flat_piece flat = flatten(&mesh, UR_FLATTEN_ARAP);
    assert_no_strain(&flat, 1e-3);
    assert_true(fabs(flat.coverage - 1) <= 1e-3);
    ur_flat_piece_free(&flat);
    free_mesh(&mesh);
}

/* A flat ring (a disk with a hole) is laid out as itself. */
static void test_ring_with_hole(void **state)
{
    (void)state;
    ur_mesh mesh = grid(48, 6, true, flat_ring);
    ur_flat_piece flat = flatten(&mesh, UR_FLATTEN_ARAP);
    assert_no_strain(&flat, 1e-9);
    assert_edges_kept(&mesh, &flat, 1e-9);
    ur_flat_piece_free(&flat);
    free_mesh(&mesh);
}

/* A saddle cannot lie flat: ARAP shows the strain and beats LSCM on its energy. */
static void test_saddle_shows_strain(void **state)
{
    (void)state;
    ur_mesh mesh = grid(30, 30, false, saddle);
    ur_flat_piece arap = flatten(&mesh, UR_FLATTEN_ARAP);
    ur_flat_piece lscm = flatten(&mesh, UR_FLATTEN_LSCM);
    assert_true(arap.max_stretch > 1e-3 || arap.max_compression > 1e-3);
    assert_true(arap.iterations > 0);
    assert_int_equal(lscm.iterations, 0);
    assert_false(arap.flipped);
    assert_false(lscm.flipped);
    /* Coverage is reported and, for a gentle saddle, near 1 but not 1. */
    assert_true(arap.coverage > 0.95 && arap.coverage < 1.05);
    assert_true(fabs(arap.coverage - 1) > 1e-6);
    assert_true(fabs(arap.coverage - arap.flat_area / arap.area_3d) <= 1e-15);
    assert_true(fabs(lscm.coverage - 1) <= 1e-12); /* LSCM is scaled to the 3D area */
    double arap_energy, lscm_energy;
    assert_int_equal(ur_flatten_energy(&mesh, arap.flat, &arap_energy, NULL), UR_OK);
    assert_int_equal(ur_flatten_energy(&mesh, lscm.flat, &lscm_energy, NULL), UR_OK);
    assert_true(arap_energy > 0);
    assert_true(arap_energy < lscm_energy);
    for (size_t t = 0; t < arap.triangle_count; t++) {
        assert_true(arap.strain[t].sigma1 >= arap.strain[t].sigma2);
        assert_true(fabs(ur_vec2_length(arap.strain[t].direction) - 1) <= 1e-12);
    }
    ur_flat_piece_free(&arap);
    ur_flat_piece_free(&lscm);
    free_mesh(&mesh);
}

/* Negative cotangent weights keep the Laplacian definite: exact when flat, better when not. */
static void test_obtuse_triangles(void **state)
{
    (void)state;
    ur_mesh flat_mesh = grid(20, 20, false, sheared);
    ur_flat_piece flat = flatten(&flat_mesh, UR_FLATTEN_ARAP);
    assert_no_strain(&flat, 1e-9);
    assert_edges_kept(&flat_mesh, &flat, 1e-9);
    ur_flat_piece_free(&flat);
    free_mesh(&flat_mesh);

    ur_mesh mesh = grid(20, 20, false, sheared_saddle);
    ur_flat_piece arap = flatten(&mesh, UR_FLATTEN_ARAP);
    ur_flat_piece lscm = flatten(&mesh, UR_FLATTEN_LSCM);
    assert_true(arap.iterations > 1);
    assert_false(arap.flipped);
    double arap_energy, lscm_energy;
    assert_int_equal(ur_flatten_energy(&mesh, arap.flat, &arap_energy, NULL), UR_OK);
    assert_int_equal(ur_flatten_energy(&mesh, lscm.flat, &lscm_energy, NULL), UR_OK);
    assert_true(arap_energy < lscm_energy);
    ur_flat_piece_free(&arap);
    ur_flat_piece_free(&lscm);
    free_mesh(&mesh);
}

/* Stopping after one ARAP iteration leaves more energy than converging. */
static void test_iterations_bound(void **state)
{
    (void)state;
    ur_mesh mesh = grid(20, 20, false, saddle);
    ur_flatten_options options;
    ur_flatten_options_default(&options);
    options.iterations = 1;
    ur_flat_piece one, many;
    assert_int_equal(ur_flatten(&mesh, &options, &one, NULL), UR_OK);
    assert_int_equal(one.iterations, 1);
    assert_int_equal(ur_flatten(&mesh, NULL, &many, NULL), UR_OK);
    assert_true(many.iterations > 1 && many.iterations <= 100);
    double e_one, e_many;
    assert_int_equal(ur_flatten_energy(&mesh, one.flat, &e_one, NULL), UR_OK);
    assert_int_equal(ur_flatten_energy(&mesh, many.flat, &e_many, NULL), UR_OK);
    assert_true(e_many < e_one);
    ur_flat_piece_free(&one);
    ur_flat_piece_free(&many);
    free_mesh(&mesh);
}

/* Strain of layouts made by hand: a stretch along x, then a triangle turned over. */
static void test_measure_by_hand(void **state)
{
    (void)state;
    ur_vec3 vertices[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    size_t triangles[1][3] = {{0, 1, 2}};
    ur_mesh mesh = {vertices, 3, triangles, 1, NULL, 1};
    ur_vec2 stretched[3] = {{0, 0}, {2, 0}, {0, 1}};
    ur_flat_piece flat;
    assert_int_equal(ur_flat_piece_measure(&mesh, stretched, &flat, NULL), UR_OK);
    assert_true(fabs(flat.strain[0].sigma1 - 2) <= 1e-15);
    assert_true(fabs(flat.strain[0].sigma2 - 1) <= 1e-15);
    assert_true(fabs(fabs(flat.strain[0].direction.x) - 1) <= 1e-15);
    assert_true(fabs(flat.max_stretch - 1) <= 1e-15);
    assert_true(flat.max_compression == 0);
    assert_true(fabs(flat.coverage - 2) <= 1e-15);
    assert_false(flat.flipped);
    double energy;
    assert_int_equal(ur_flatten_energy(&mesh, stretched, &energy, NULL), UR_OK);
    assert_true(fabs(energy - 1) <= 1e-15); /* (2 - 1)^2 + (1 - 1)^2 */
    ur_flat_piece_free(&flat);

    /* The same triangle mirrored: no strain, but turned over. */
    ur_vec2 mirrored[3] = {{0, 0}, {0, 1}, {1, 0}};
    assert_int_equal(ur_flat_piece_measure(&mesh, mirrored, &flat, NULL), UR_OK);
    assert_true(flat.flipped);
    assert_true(fabs(flat.strain[0].sigma1 - 1) <= 1e-15);
    assert_true(fabs(flat.strain[0].sigma2 - 1) <= 1e-15);
    assert_true(flat.coverage < 0);
    ur_flat_piece_free(&flat);
}

/* Rotating a layout changes no strain, only its direction. */
static void test_direction_turns_with_layout(void **state)
{
    (void)state;
    ur_vec3 vertices[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    size_t triangles[1][3] = {{0, 1, 2}};
    ur_mesh mesh = {vertices, 3, triangles, 1, NULL, 1};
    double c = cos(0.7), s = sin(0.7);
    /* Stretch by 3 along x, shrink to 0.5 along y, then turn by 0.7 rad. */
    ur_vec2 layout[3] = {{0, 0}, {3 * c, 3 * s}, {-0.5 * s, 0.5 * c}};
    ur_flat_piece flat;
    assert_int_equal(ur_flat_piece_measure(&mesh, layout, &flat, NULL), UR_OK);
    assert_true(fabs(flat.strain[0].sigma1 - 3) <= 1e-14);
    assert_true(fabs(flat.strain[0].sigma2 - 0.5) <= 1e-14);
    assert_true(fabs(fabs(ur_vec2_dot(flat.strain[0].direction, ur_vec2_make(c, s))) - 1) <= 1e-14);
    assert_true(fabs(flat.max_compression - 0.5) <= 1e-14);
    ur_flat_piece_free(&flat);
}

static void test_single_triangle(void **state)
{
    (void)state;
    ur_vec3 vertices[3] = {{0, 0, 0}, {4, 1, 2}, {-1, 3, 1}};
    size_t triangles[1][3] = {{0, 1, 2}};
    ur_mesh mesh = {vertices, 3, triangles, 1, NULL, 1};
    ur_flat_piece flat = flatten(&mesh, UR_FLATTEN_ARAP);
    assert_no_strain(&flat, 1e-12);
    assert_edges_kept(&mesh, &flat, 1e-12);
    ur_flat_piece_free(&flat);
}

static void expect_input_error(const ur_mesh *mesh, const ur_flatten_options *options,
                               const char *words)
{
    ur_flat_piece flat;
    ur_error error;
    ur_error_clear(&error);
    assert_int_equal(ur_flatten(mesh, options, &flat, &error), UR_ERROR_INPUT);
    assert_int_equal(error.status, UR_ERROR_INPUT);
    if (!strstr(error.message, words))
        fail_msg("error \"%s\" does not say \"%s\"", error.message, words);
    assert_null(flat.flat);
    assert_null(flat.strain);
}

static void test_bad_pieces(void **state)
{
    (void)state;
    ur_vec3 vertices[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {5, 5, 5}};
    ur_mesh empty = {vertices, 3, NULL, 0, NULL, 1};
    expect_input_error(&empty, NULL, "no triangles");

    /* A closed tetrahedron, outward. */
    size_t closed[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    ur_mesh tetrahedron = {vertices, 4, closed, 4, NULL, 1};
    expect_input_error(&tetrahedron, NULL, "closed");

    size_t fin[3][3] = {{0, 1, 2}, {0, 1, 3}, {1, 0, 4}};
    ur_mesh three_on_an_edge = {vertices, 5, fin, 3, NULL, 1};
    expect_input_error(&three_on_an_edge, NULL, "shared by 3 triangles");

    size_t same_way[2][3] = {{0, 1, 2}, {0, 1, 3}};
    ur_mesh misoriented = {vertices, 4, same_way, 2, NULL, 1};
    expect_input_error(&misoriented, NULL, "oriented");

    size_t apart[2][3] = {{0, 1, 2}, {3, 4, 2}};
    ur_mesh unused = {vertices, 5, apart, 1, NULL, 1};
    expect_input_error(&unused, NULL, "belongs to no triangle");

    ur_vec3 far[6] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
    size_t two[2][3] = {{0, 1, 2}, {3, 4, 5}};
    ur_mesh parts = {far, 6, two, 2, NULL, 1};
    expect_input_error(&parts, NULL, "2 separate parts");

    ur_vec3 line[3] = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
    size_t flat_one[1][3] = {{0, 1, 2}};
    ur_mesh degenerate = {line, 3, flat_one, 1, NULL, 1};
    expect_input_error(&degenerate, NULL, "no area");

    ur_vec3 nan_point[3] = {{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}};
    ur_mesh not_finite = {nan_point, 3, flat_one, 1, NULL, 1};
    expect_input_error(&not_finite, NULL, "not a finite number");

    size_t beyond[1][3] = {{0, 1, 7}};
    ur_mesh out_of_range = {vertices, 5, beyond, 1, NULL, 1};
    expect_input_error(&out_of_range, NULL, "uses vertex 8");

    ur_mesh triangle = {vertices, 3, flat_one, 1, NULL, 1};
    ur_flatten_options options;
    ur_flatten_options_default(&options);
    options.tolerance = -1;
    expect_input_error(&triangle, &options, "tolerance");
    options.tolerance = NAN;
    expect_input_error(&triangle, &options, "tolerance");
    ur_flatten_options_default(&options);
    options.method = (ur_flatten_method)7;
    expect_input_error(&triangle, &options, "method");
}

/* A closed tube is a disk with a hole, so it is accepted; its strain says it is no good. */
static ur_vec3 whole_tube(double s, double t)
{
    double angle = 2 * M_PI * s;
    return ur_vec3_make(20 * cos(angle), 20 * sin(angle), 30 * t);
}

static void test_closed_tube_is_strained(void **state)
{
    (void)state;
    ur_mesh mesh = grid(32, 8, true, whole_tube);
    ur_flat_piece flat = flatten(&mesh, UR_FLATTEN_ARAP);
    assert_true(flat.max_stretch > 0.1 || flat.max_compression > 0.1);
    ur_flat_piece_free(&flat);
    free_mesh(&mesh);
}

/* Twice the signed area of flat triangle t, from the layout itself. */
static double twice_signed_area(const ur_mesh *mesh, const ur_flat_piece *flat, size_t t)
{
    const size_t *c = mesh->triangles[t];
    return ur_vec2_cross(ur_vec2_sub(flat->flat[c[1]], flat->flat[c[0]]),
                         ur_vec2_sub(flat->flat[c[2]], flat->flat[c[0]]));
}

/* Every flat triangle runs the way its 3D triangle does, with some area. */
static void assert_none_turned(const ur_mesh *mesh, const ur_flat_piece *flat)
{
    for (size_t t = 0; t < mesh->triangle_count; t++)
        if (!(twice_signed_area(mesh, flat, t) > 0))
            fail_msg("triangle %zu is turned over (twice its signed area is %g)", t,
                     twice_signed_area(mesh, flat, t));
    assert_false(flat->flipped);
}

/* A sphere of radius 50 slit open along a meridian, from latitude -86 to 86 degrees. */
static ur_vec3 slit_sphere(double s, double t)
{
    double longitude = 2 * M_PI * s, latitude = (t - 0.5) * M_PI * 172 / 180;
    return ur_vec3_make(50 * cos(latitude) * cos(longitude), 50 * cos(latitude) * sin(longitude),
                        50 * sin(latitude));
}

/*
 * A bag: a tube of radius 20 whose rim, at the top, opens out to radius
 * 60, so that LSCM shrinks its bottom to almost nothing and ARAP, growing
 * it back, pushes triangles across their neighbours unless its steps are
 * bounded.
 */
static ur_vec3 flared_tube(double s, double t)
{
    double angle = 2 * M_PI * s * 0.98, r = 20 + 40 * pow(t, 6);
    return ur_vec3_make(r * cos(angle), r * sin(angle), 60 * t);
}

/*
 * Pieces curved far from any flat shape (nearly a whole sphere, a flared
 * bag): both methods lay every triangle the right way round.
 */
static void test_nothing_turns_over(void **state)
{
    (void)state;
    surface_fn shapes[] = {slit_sphere, flared_tube};
    for (size_t k = 0; k < 2; k++) {
        ur_mesh mesh = grid(48, 24, false, shapes[k]);
        for (int m = 0; m < 2; m++) {
            ur_flat_piece flat = flatten(&mesh, m == 0 ? UR_FLATTEN_ARAP : UR_FLATTEN_LSCM);
            assert_none_turned(&mesh, &flat);
            assert_true(flat.flat_area > 0);
            ur_flat_piece_free(&flat);
        }
        free_mesh(&mesh);
    }
}

/* ---- Charts within the strain ---- */

/* paper-0.3mm and cardboard-2mm as the CLI reads them (meshes.c, strip_limits). */
static const ur_strip_limits paper = {0.01, 0.002, 64}, cardboard = {0.03, 0.005, 64};

static ur_mesh sample(const char *name)
{
    char path[128];
    snprintf(path, sizeof path, "samples/%s", name);
    ur_mesh_import_options options;
    ur_mesh_import_options_default(&options);
    ur_mesh mesh;
    ur_mesh_repairs repairs;
    ur_error error;
    if (ur_mesh_import(path, &options, &mesh, NULL, &error) != UR_OK ||
        ur_mesh_clean(&mesh, 1e-6 * ur_mesh_size(&mesh), &repairs, &error) != UR_OK)
        fail_msg("%s: %s (run from the repository root)", path, error.message);
    return mesh;
}

static ur_charts charts_of(const ur_mesh *mesh, const ur_strip_limits *limits)
{
    ur_charts charts;
    ur_error error;
    if (ur_flatten_charts(mesh, NULL, 0, limits, NULL, &charts, &error) != UR_OK)
        fail_msg("charts: %s", error.message);
    return charts;
}

/*
 * What every set of charts must be: each input triangle in exactly one
 * chart, congruent to it in 3D; the 3D area kept; every chart within the
 * limits by its own singular values, with no triangle turned over.
 */
static void check_charts(const ur_mesh *mesh, const ur_charts *charts,
                         const ur_strip_limits *limits)
{
    size_t *uses = calloc(mesh->triangle_count, sizeof *uses);
    assert_non_null(uses);
    double area = 0;
    for (size_t k = 0; k < charts->count; k++) {
        const ur_chart *chart = &charts->charts[k];
        const ur_mesh *piece = &chart->piece.mesh;
        assert_int_equal(chart->flat.triangle_count, piece->triangle_count);
        assert_none_turned(piece, &chart->flat);
        for (size_t t = 0; t < piece->triangle_count; t++) {
            size_t input = chart->piece.source_triangles[t];
            assert_true(input < mesh->triangle_count);
            uses[input]++;
            for (int c = 0; c < 3; c++) {
                ur_vec3 a = piece->vertices[piece->triangles[t][c]];
                ur_vec3 b = mesh->vertices[mesh->triangles[input][c]];
                assert_true(ur_vec3_distance(a, b) == 0);
                assert_true(chart->piece.original[piece->triangles[t][c]] ==
                            mesh->triangles[input][c]);
            }
            const ur_strain *s = &chart->flat.strain[t];
            if (!(s->sigma1 - 1 <= limits->max_stretch + 1e-9 &&
                  1 - s->sigma2 <= limits->max_compression + 1e-9))
                fail_msg("chart %zu, triangle %zu: sigma %.6f, %.6f", k, t, s->sigma1, s->sigma2);
        }
        area += chart->flat.area_3d;
    }
    for (size_t t = 0; t < mesh->triangle_count; t++)
        if (uses[t] != 1)
            fail_msg("triangle %zu is in %zu charts", t, uses[t]);
    free(uses);
    assert_true(fabs(area - ur_mesh_area(mesh)) <= 1e-9 * area);
    assert_true(charts->max_stretch <= limits->max_stretch + 1e-9);
    assert_true(charts->max_compression <= limits->max_compression + 1e-9);
}

/* A 100 mm cube: its six faces, flat squares of 100 x 100 mm with no strain. */
static void test_cube_becomes_six_squares(void **state)
{
    (void)state;
    ur_mesh mesh = sample("cube.obj");
    ur_charts charts = charts_of(&mesh, &paper);
    check_charts(&mesh, &charts, &paper);
    assert_int_equal(charts.sharp_edges, 12);
    assert_int_equal(charts.count, 6);
    double flat = 0;
    for (size_t k = 0; k < charts.count; k++) {
        const ur_flat_piece *f = &charts.charts[k].flat;
        assert_no_strain(f, 1e-6);
        assert_true(fabs(f->coverage - 1) <= 1e-6);
        assert_true(fabs(f->flat_area - 10000) <= 1e-6 * 10000);
        assert_edges_kept(&charts.charts[k].piece.mesh, f, 1e-6);
        flat += f->flat_area;
    }
    assert_true(fabs(flat - 60000) <= 1e-6 * 60000);
    ur_charts_free(&charts);
    free_mesh(&mesh);
}

/*
 * Curved meshes come out within the material's strain, in fewer charts in
 * cardboard (which takes 3 % and 0.5 %) than in paper (1 % and 0.2 %);
 * one chart of the whole would not do.
 */
static void test_curved_meshes_fit_the_material(void **state)
{
    (void)state;
    const char *names[] = {"head.obj", "uvsphere.obj"};
    for (size_t k = 0; k < 2; k++) {
        ur_mesh mesh = sample(names[k]);
        ur_charts in_paper = charts_of(&mesh, &paper);
        ur_charts in_cardboard = charts_of(&mesh, &cardboard);
        check_charts(&mesh, &in_paper, &paper);
        check_charts(&mesh, &in_cardboard, &cardboard);
        assert_true(in_cardboard.count > 1);
        assert_true(in_cardboard.count < in_paper.count);
        /* A chart is cut only when over the limits: most are not single triangles. */
        size_t single = 0;
        for (size_t c = 0; c < in_cardboard.count; c++)
            single += in_cardboard.charts[c].piece.mesh.triangle_count == 1;
        assert_true(single * 10 < in_cardboard.count);
        ur_charts_free(&in_paper);
        ur_charts_free(&in_cardboard);
        free_mesh(&mesh);
    }
}

/*
 * The lampshade, a frustum in two groups (its halves): developable, so each
 * half is one chart without strain, and no chart joins the two.
 */
static void test_groups_stay_apart(void **state)
{
    (void)state;
    ur_mesh mesh = sample("lampshade.obj");
    assert_int_equal(mesh.group_count, 2);
    ur_charts charts = charts_of(&mesh, &paper);
    check_charts(&mesh, &charts, &paper);
    assert_int_equal(charts.count, 2);
    for (size_t k = 0; k < charts.count; k++) {
        const ur_chart *chart = &charts.charts[k];
        for (size_t t = 0; t < chart->piece.mesh.triangle_count; t++)
            assert_int_equal(mesh.groups[chart->piece.source_triangles[t]],
                             mesh.groups[chart->piece.source_triangles[0]]);
        assert_no_strain(&chart->flat, 1e-6);
    }
    ur_charts_free(&charts);
    free_mesh(&mesh);
}

/* A low-poly sphere is built too, a face or a few to a chart. */
static void test_low_poly_sphere_is_built(void **state)
{
    (void)state;
    ur_mesh mesh = sample("icosphere.obj");
    ur_charts charts = charts_of(&mesh, &paper);
    check_charts(&mesh, &charts, &paper);
    assert_true(charts.count > 1 && charts.count <= mesh.triangle_count);
    ur_charts_free(&charts);
    free_mesh(&mesh);
}

/*
 * An icosahedron, whose faces turn by 41.8 degrees at every edge: every
 * edge is sharp, so every face is a chart of its own, flat as it is.
 */
static void test_every_edge_sharp(void **state)
{
    (void)state;
    double g = (1 + sqrt(5)) / 2;
    ur_vec3 vertices[12] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                            {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                            {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    size_t triangles[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (size_t v = 0; v < 12; v++)
        vertices[v] = ur_vec3_scale(vertices[v], 20);
    ur_mesh mesh = {vertices, 12, triangles, 20, NULL, 1};
    ur_charts charts = charts_of(&mesh, &paper);
    check_charts(&mesh, &charts, &paper);
    assert_int_equal(charts.sharp_edges, 30);
    assert_int_equal(charts.count, 20);
    double side = 40; /* the edge, twice the 20 the unit coordinates were scaled by */
    for (size_t k = 0; k < charts.count; k++) {
        assert_no_strain(&charts.charts[k].flat, 1e-9);
        assert_true(fabs(charts.charts[k].flat.flat_area - sqrt(3) / 4 * side * side) <= 1e-9);
    }
    ur_charts_free(&charts);
}

/* The sharp angle by hand: two faces of a hinge opened to 29 and to 31 degrees. */
static void test_sharp_edges(void **state)
{
    (void)state;
    for (int k = 0; k < 2; k++) {
        double turn = (k == 0 ? 29.0 : 31.0) * M_PI / 180;
        ur_vec3 vertices[4] = {
            {0, 0, 0}, {10, 0, 0}, {5, 8, 0}, {5, -8 * cos(turn), 8 * sin(turn)}};
        size_t triangles[2][3] = {{0, 1, 2}, {1, 0, 3}};
        ur_mesh mesh = {vertices, 4, triangles, 2, NULL, 1};
        assert_int_equal(ur_chart_edge_is_sharp(&mesh, 0, 1), k == 1);
    }
}

/* Scaling into the limits, checked against the singular values of a layout made by hand. */
static void test_fit_limits(void **state)
{
    (void)state;
    ur_vec3 vertices[3] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
    size_t triangles[1][3] = {{0, 1, 2}};
    ur_mesh mesh = {vertices, 3, triangles, 1, NULL, 1};
    /* Stretched 2 % along x, compressed 1 % along y. */
    ur_vec2 layout[3] = {{0, 0}, {10.2, 0}, {0, 9.9}};
    ur_flat_piece flat;
    ur_error error;
    assert_int_equal(ur_flat_piece_measure(&mesh, layout, &flat, &error), UR_OK);
    /* Paper allows 1 % stretch, 0.2 % compression: the spread 1.02 / 0.99 is too wide. */
    ur_flat_piece_fit_limits(&flat, &paper);
    double s = (0.01 + 0.002) / (0.002 * 1.02 + 0.01 * 0.99);
    assert_true(fabs(flat.strain[0].sigma1 - 1.02 * s) <= 1e-12);
    assert_true(fabs(flat.flat[1].x - 10.2 * s) <= 1e-12);
    assert_true(fabs((flat.max_stretch) / 0.01 - flat.max_compression / 0.002) <= 1e-9);
    ur_flat_piece_free(&flat);
    /* Cardboard (3 %, 0.5 %) takes it, grown by the least that brings sigma2 to 0.995. */
    assert_int_equal(ur_flat_piece_measure(&mesh, layout, &flat, &error), UR_OK);
    ur_flat_piece_fit_limits(&flat, &cardboard);
    assert_true(fabs(flat.strain[0].sigma2 - 0.995) <= 1e-12);
    assert_true(fabs(flat.strain[0].sigma1 - 1.02 * 0.995 / 0.99) <= 1e-12);
    assert_true(fabs(flat.coverage - 1.02 * 0.99 * pow(0.995 / 0.99, 2)) <= 1e-12);
    ur_flat_piece_free(&flat);
    /* 4 % stretch and 1 % compression do not fit cardboard: both over by a like share. */
    layout[1].x = 10.4;
    assert_int_equal(ur_flat_piece_measure(&mesh, layout, &flat, &error), UR_OK);
    ur_flat_piece_fit_limits(&flat, &cardboard);
    s = (0.03 + 0.005) / (0.005 * 1.04 + 0.03 * 0.99);
    assert_true(fabs(flat.strain[0].sigma2 - 0.99 * s) <= 1e-12);
    assert_true(fabs(flat.max_stretch / 0.03 - flat.max_compression / 0.005) <= 1e-9);
    assert_true(flat.max_stretch > 0.03);
    ur_flat_piece_free(&flat);
    /* A layout within the limits is left as it is. */
    layout[1].x = 10.05;
    layout[2].y = 10;
    assert_int_equal(ur_flat_piece_measure(&mesh, layout, &flat, &error), UR_OK);
    ur_flat_piece_fit_limits(&flat, &paper);
    assert_true(flat.flat[1].x == 10.05 && fabs(flat.strain[0].sigma1 - 1.005) <= 1e-12);
    ur_flat_piece_free(&flat);
}

static void test_bad_limits(void **state)
{
    (void)state;
    ur_mesh mesh = grid(2, 2, false, tilted_plane);
    ur_strip_limits limits = {-0.01, 0.01, 64};
    ur_charts charts;
    ur_error error;
    assert_int_equal(ur_flatten_charts(&mesh, NULL, 0, &limits, NULL, &charts, &error),
                     UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "limits"));
    assert_int_equal(charts.count, 0);
    limits.max_stretch = NAN;
    assert_int_equal(ur_flatten_charts(&mesh, NULL, 0, &limits, NULL, &charts, &error),
                     UR_ERROR_INPUT);
    free_mesh(&mesh);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_method_names_and_defaults),
        cmocka_unit_test(test_flat_grid_is_kept),
        cmocka_unit_test(test_quarter_tube_has_no_strain),
        cmocka_unit_test(test_cone_has_no_strain),
        cmocka_unit_test(test_jittered_tube_converges),
        cmocka_unit_test(test_ring_with_hole),
        cmocka_unit_test(test_saddle_shows_strain),
        cmocka_unit_test(test_obtuse_triangles),
        cmocka_unit_test(test_iterations_bound),
        cmocka_unit_test(test_measure_by_hand),
        cmocka_unit_test(test_direction_turns_with_layout),
        cmocka_unit_test(test_single_triangle),
        cmocka_unit_test(test_bad_pieces),
        cmocka_unit_test(test_closed_tube_is_strained),
        cmocka_unit_test(test_nothing_turns_over),
        cmocka_unit_test(test_cube_becomes_six_squares),
        cmocka_unit_test(test_curved_meshes_fit_the_material),
        cmocka_unit_test(test_groups_stay_apart),
        cmocka_unit_test(test_low_poly_sphere_is_built),
        cmocka_unit_test(test_every_edge_sharp),
        cmocka_unit_test(test_sharp_edges),
        cmocka_unit_test(test_fit_limits),
        cmocka_unit_test(test_bad_limits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
