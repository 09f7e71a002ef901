/*
 * test_strips.c: flattening in strips.  A hyperbolic paraboloid (built as
 * the command builds one, a general ruled surface on two straight rails)
 * cut along its rulings: its strain falls as the strips multiply, which is
 * what the search for the fewest strips assumes; the count found is the
 * smallest that fits, one fewer does not; a limit out of reach is refused
 * with a message that says so; strips come in order along the surface and
 * share their rulings; the surface's restriction survives.  A developable
 * cylinder needs one strip.  Meshes: the direction across the bands, bands
 * cut by planes (area kept, edges on the planes, groups and order), a
 * saddle's strain falling with the bands, and the chosen direction needing
 * fewer bands than the wrong one.
 */
#include "test_support.h"

#include <stdlib.h>

#include "unroll/flatten.h"
#include "unroll/mesh.h"

#define assert_message(error, text)                                                                \
    do {                                                                                           \
        if (!strstr((error).message, (text)))                                                      \
            fail_msg("message \"%s\" does not say \"%s\"", (error).message, (text));               \
    } while (0)

/* ---- Ruled surfaces ------------------------------------------------------ */

/* The straight line from p to q as an interpolating curve (as src/cli/surfaces.c makes one). */
static ur_curve *straight(ur_vec3 p, ur_vec3 q)
{
    ur_vec3 points[4];
    for (int k = 0; k < 4; k++)
        points[k] = ur_vec3_add_scaled(p, ur_vec3_sub(q, p), k / 3.0);
    ur_curve *curve = NULL;
    ur_error error;
    if (ur_curve_new_interpolating(points, 4, false, &curve, &error) != UR_OK)
        fail_msg("rail: %s", error.message);
    return curve;
}

/*
 * The hypar on the skew quadrilateral (0,0,0) (100,0,0) (100,100,60)
 * (0,100,0), rulings from rail (0,0,0)-(100,0,0) to (0,100,0)-(100,100,60)
 * at equal fractions of their lengths: ruling u lies in the plane x = u.
 */
static ur_ruled hypar(void)
{
    ur_ruled ruled;
    ur_error error;
    ur_curve *rail1 = straight(ur_vec3_make(0, 0, 0), ur_vec3_make(100, 0, 0));
    ur_curve *rail2 = straight(ur_vec3_make(0, 100, 0), ur_vec3_make(100, 100, 60));
    if (ur_ruled_general(rail1, rail2, UR_PAIR_ARC_LENGTH, &ruled, &error) != UR_OK)
        fail_msg("hypar: %s", error.message);
    return ruled;
}

static ur_strips strips_of_ruled(ur_ruled *ruled, size_t count)
{
    ur_strips strips;
    ur_error error;
    if (ur_strips_of_ruled(ruled, count, NULL, &strips, &error) != UR_OK)
        fail_msg("%zu strips: %s", count, error.message);
    return strips;
}

static bool fits(const ur_strips *strips, const ur_strip_limits *limits)
{
    return !strips->flipped && strips->max_stretch <= limits->max_stretch &&
           strips->max_compression <= limits->max_compression;
}

/* The worst strain of the whole is the worst of its pieces; each piece is its band's. */
static void assert_consistent(const ur_strips *strips)
{
    double stretch = 0, compression = 0;
    for (size_t i = 0; i < strips->count; i++) {
        stretch = fmax(stretch, strips->strips[i].flat.max_stretch);
        compression = fmax(compression, strips->strips[i].flat.max_compression);
        assert_true(strips->strips[i].band < strips->bands);
        if (i > 0)
            assert_true(strips->strips[i].band >= strips->strips[i - 1].band);
    }
    assert_true(stretch == strips->max_stretch);
    assert_true(compression == strips->max_compression);
}

/*
 * The assumption of the search (flatten.h): the worst stretch and the
 * worst compression both fall as the strips narrow, here by about 4 times
 * each time their count doubles, as a strain of about K w^2 would.
 */
static void test_hypar_strain_falls_with_strips(void **state)
{
    (void)state;
    ur_ruled ruled = hypar();
    double stretch = INFINITY, compression = INFINITY;
    for (size_t count = 1; count <= 8; count *= 2) {
        ur_strips strips = strips_of_ruled(&ruled, count);
        assert_int_equal(strips.bands, count);
        assert_int_equal(strips.count, count);
        assert_int_equal(strips.tried, 1);
        assert_false(strips.flipped);
        assert_consistent(&strips);
        if (!(strips.max_stretch < stretch && strips.max_compression < compression))
            fail_msg("%zu strips: stretch %g, compression %g; fewer: %g, %g", count,
                     strips.max_stretch, strips.max_compression, stretch, compression);
        stretch = strips.max_stretch;
        compression = strips.max_compression;
        ur_strips_free(&strips);
    }
    assert_true(stretch > 0 && stretch < 1e-3); /* 8 strips: well under 0.1 % */
    ur_ruled_free(&ruled);
}

/* The count found fits, and one fewer (flattened here) does not. */
static void test_hypar_fewest_strips(void **state)
{
    (void)state;
    ur_ruled ruled = hypar();
    ur_strip_limits limits = {.max_stretch = 0.001, .max_compression = 0.002, .max_strips = 64};
    ur_strips strips;
    ur_error error;
    if (ur_flatten_strips_ruled(&ruled, &limits, NULL, &strips, &error) != UR_OK)
        fail_msg("strips: %s", error.message);
    size_t count = strips.bands;
    assert_true(count > 2); /* a search with some bisecting to do */
    assert_true(fits(&strips, &limits));
    assert_int_equal(strips.count, count);
    assert_consistent(&strips);
    /* Doubling to count or the power of two above it, then bisecting: at most 2 log2 + 1. */
    assert_true(strips.tried >= 2 && strips.tried <= 2 * (size_t)ceil(log2((double)count)) + 1);
    ur_strips fewer = strips_of_ruled(&ruled, count - 1);
    if (fits(&fewer, &limits))
        fail_msg("%zu strips fit too: stretch %g, compression %g", count - 1, fewer.max_stretch,
                 fewer.max_compression);
    assert_false(ruled.restricted); /* the whole surface, as before */
    ur_strips_free(&fewer);
    ur_strips_free(&strips);
    ur_ruled_free(&ruled);
}

static void test_hypar_limit_out_of_reach(void **state)
{
    (void)state;
    ur_ruled ruled = hypar();
    ur_strip_limits limits = {.max_stretch = 1e-4, .max_compression = 1e-4, .max_strips = 4};
    ur_strips strips;
    ur_error error;
    assert_int_equal(ur_flatten_strips_ruled(&ruled, &limits, NULL, &strips, &error),
                     UR_ERROR_INPUT);
    assert_message(error, "the surface needs more than 4 strips to stay within 0.01 % stretch and "
                          "0.01 % compression: with 4, strip ");
    assert_message(error, " still stretches ");
    assert_null(strips.strips);
    assert_int_equal(strips.count, 0);
    assert_false(ruled.restricted);
    limits.max_strips = 1;
    assert_int_equal(ur_flatten_strips_ruled(&ruled, &limits, NULL, &strips, &error),
                     UR_ERROR_INPUT);
    assert_message(error, "needs more than 1 strip to stay within");
    ur_ruled_free(&ruled);
}

static void test_bad_limits(void **state)
{
    (void)state;
    ur_ruled ruled = hypar();
    ur_strips strips;
    ur_error error;
    ur_strip_limits negative = {.max_stretch = -0.01, .max_compression = 0.01, .max_strips = 4};
    assert_int_equal(ur_flatten_strips_ruled(&ruled, &negative, NULL, &strips, &error),
                     UR_ERROR_INPUT);
    assert_message(error, "numbers >= 0");
    ur_strip_limits nan = {.max_stretch = 0.01, .max_compression = NAN, .max_strips = 4};
    assert_int_equal(ur_flatten_strips_ruled(&ruled, &nan, NULL, &strips, &error), UR_ERROR_INPUT);
    ur_strip_limits none = {.max_stretch = 0.01, .max_compression = 0.01, .max_strips = 0};
    assert_int_equal(ur_flatten_strips_ruled(&ruled, &none, NULL, &strips, &error), UR_ERROR_INPUT);
    assert_int_equal(ur_strips_of_ruled(&ruled, 0, NULL, &strips, &error), UR_ERROR_INPUT);
    assert_null(strips.strips);
    ur_ruled_free(&ruled);
}

/* The ruling at u, from rail to rail, as the hypar has it. */
static double ruling_length(double u)
{
    return hypot(100, 60 * u / 100);
}

/*
 * Strip i covers the i-th quarter of u (x, on the hypar), its neighbours
 * share its rulings, and both lay each shared ruling out at its length.
 */
static void test_strips_in_order_share_rulings(void **state)
{
    (void)state;
    ur_ruled ruled = hypar();
    ur_strips strips = strips_of_ruled(&ruled, 4);
    for (size_t i = 0; i < 4; i++) {
        const ur_strip *strip = &strips.strips[i];
        assert_int_equal(strip->band, i);
        assert_relative(strip->start, 25.0 * i, 1e-12);
        assert_relative(strip->end, 25.0 * (i + 1), 1e-12);
        const ur_mesh *mesh = &strip->piece.mesh;
        for (size_t v = 0; v < mesh->vertex_count; v++)
            assert_true(mesh->vertices[v].x >= strip->start - 1e-9 &&
                        mesh->vertices[v].x <= strip->end + 1e-9);
        assert_int_equal(strip->seam_count, i == 0 || i == 3 ? 1 : 2);
        const ur_segment *seams = strip->seams;
        if (i > 0) { /* seams[0]: the ruling at start, shared with strip i - 1 */
            const ur_strip *before = &strips.strips[i - 1];
            const ur_segment *shared = &before->seams[before->seam_count - 1];
            double here = ur_vec2_distance(seams[0].start, seams[0].end);
            double there = ur_vec2_distance(shared->start, shared->end);
            assert_relative(here, ruling_length(strip->start), 5e-3);
            assert_relative(there, here, 5e-3);
        }
    }
    ur_strips_free(&strips);
    ur_ruled_free(&ruled);
}

/* Strips of the part in use, which is still the part in use afterwards. */
static void test_restriction_kept(void **state)
{
    (void)state;
    ur_ruled ruled = hypar();
    ur_ruled_restrict(&ruled, 20, 80);
    ur_strips strips = strips_of_ruled(&ruled, 3);
    for (size_t i = 0; i < 3; i++) {
        assert_relative(strips.strips[i].start, 20 + 20.0 * i, 1e-12);
        assert_relative(strips.strips[i].end, 40 + 20.0 * i, 1e-12);
    }
    assert_true(ruled.restricted);
    assert_true(ruled.u_min == 20 && ruled.u_max == 80);
    ur_strips_free(&strips);
    ur_strip_limits limits = {.max_stretch = 0.001, .max_compression = 0.002, .max_strips = 64};
    ur_error error;
    if (ur_flatten_strips_ruled(&ruled, &limits, NULL, &strips, &error) != UR_OK)
        fail_msg("strips: %s", error.message);
    assert_relative(strips.strips[0].start, 20, 1e-12);
    assert_relative(strips.strips[strips.count - 1].end, 80, 1e-12);
    assert_true(ruled.restricted && ruled.u_min == 20 && ruled.u_max == 80);
    ur_strips_free(&strips);
    ur_ruled_free(&ruled);
}

/*
 * A whole circular cylinder (closed: one strip is a tube that ur_mesh_pieces
 * cuts open) lays flat in one strip; cut in three, every strip shares both
 * its rulings, the last with the first.
 */
static void test_cylinder_needs_one_strip(void **state)
{
    (void)state;
    ur_curve *circle = NULL;
    ur_ruled ruled;
    ur_error error;
    assert_int_equal(ur_curve_new_circle(40, &circle, &error), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 100, &ruled, &error), UR_OK);
    ur_strip_limits limits = {.max_stretch = 1e-4, .max_compression = 1e-4, .max_strips = 8};
    ur_strips strips;
    if (ur_flatten_strips_ruled(&ruled, &limits, NULL, &strips, &error) != UR_OK)
        fail_msg("strips: %s", error.message);
    assert_int_equal(strips.bands, 1);
    assert_int_equal(strips.count, 1);
    assert_int_equal(strips.tried, 1);
    assert_true(strips.max_stretch < 1e-6 && strips.max_compression < 1e-6);
    assert_int_equal(strips.strips[0].seam_count, 0);
    ur_strips_free(&strips);
    strips = strips_of_ruled(&ruled, 3);
    for (size_t i = 0; i < 3; i++) {
        assert_int_equal(strips.strips[i].seam_count, 2);
        for (int k = 0; k < 2; k++) {
            ur_segment seam = strips.strips[i].seams[k];
            assert_relative(ur_vec2_distance(seam.start, seam.end), 100, 1e-6);
        }
    }
    ur_strips_free(&strips);
    ur_ruled_free(&ruled);
}

/* ---- Meshes -------------------------------------------------------------- */

typedef ur_vec3 (*surface_fn)(double s, double t);

/*
 * An n x n grid of quads over f, (s, t) in [0, 1]^2, each cut into two
 * triangles counter-clockwise in (s, t); triangles with s < 1/2 in group
 * 0, the others in group groups - 1.  Free with ur_mesh_free.
 */
static ur_mesh grid(size_t n, surface_fn f, size_t groups)
{
    size_t columns = n + 1;
    ur_mesh mesh = {0};
    mesh.vertex_count = columns * columns;
    mesh.triangle_count = 2 * n * n;
    mesh.vertices = calloc(mesh.vertex_count, sizeof *mesh.vertices);
    mesh.triangles = calloc(mesh.triangle_count, sizeof *mesh.triangles);
    mesh.groups = calloc(mesh.triangle_count, sizeof *mesh.groups);
    assert_non_null(mesh.vertices);
    assert_non_null(mesh.triangles);
    assert_non_null(mesh.groups);
    for (size_t j = 0; j <= n; j++)
        for (size_t i = 0; i <= n; i++)
            mesh.vertices[j * columns + i] = f((double)i / n, (double)j / n);
    size_t t = 0;
    for (size_t j = 0; j < n; j++)
        for (size_t i = 0; i < n; i++) {
            size_t a = j * columns + i, b = a + 1, c = b + columns, d = a + columns;
            size_t first[3] = {a, b, c}, second[3] = {a, c, d};
            size_t group = 2 * i < n ? 0 : groups - 1;
            memcpy(mesh.triangles[t], first, sizeof first);
            mesh.groups[t++] = group;
            memcpy(mesh.triangles[t], second, sizeof second);
            mesh.groups[t++] = group;
        }
    mesh.group_count = groups;
    return mesh;
}

/*
 * A saddle over a 100 x 100 square bent much more along x (radius 60)
 * than along y (radius 400): its normals turn most along x, and bands
 * between planes across x run along y, the way it bends least.
 */
static ur_vec3 long_saddle(double s, double t)
{
    double x = 100 * s - 50, y = 100 * t - 50;
    return ur_vec3_make(x, y, x * x / 120 - y * y / 800);
}

/* A quarter of a tube of radius 50 round the z axis, 100 long: developable. */
static ur_vec3 quarter_tube(double s, double t)
{
    double angle = 0.5 * M_PI * s;
    return ur_vec3_make(50 * cos(angle), 50 * sin(angle), 100 * t);
}

/* A flat 120 x 70 rectangle, longest along y. */
static ur_vec3 flat_sheet(double s, double t)
{
    return ur_vec3_make(70 * s, 120 * t, 5);
}

static ur_vec3 bending_direction(const ur_mesh *mesh)
{
    ur_vec3 d;
    ur_error error;
    if (ur_mesh_bending_direction(mesh, &d, &error) != UR_OK)
        fail_msg("direction: %s", error.message);
    assert_relative(ur_vec3_length(d), 1, 1e-12);
    return d;
}

static void test_bending_direction(void **state)
{
    (void)state;
    ur_mesh saddle = grid(24, long_saddle, 1);
    ur_vec3 d = bending_direction(&saddle);
    assert_true(d.x > 0.99);
    ur_mesh_free(&saddle);
    /* Across the quarter tube: along the chord of its arc, square to the axis. */
    ur_mesh tube = grid(24, quarter_tube, 1);
    d = bending_direction(&tube);
    assert_true(fabs(d.z) < 1e-9);
    assert_relative(fabs(ur_vec3_dot(d, ur_vec3_make(-M_SQRT1_2, M_SQRT1_2, 0))), 1, 1e-9);
    ur_mesh_free(&tube);
    /* No bending: across its longest extent (by the triangles' centroids, so not quite). */
    ur_mesh sheet = grid(12, flat_sheet, 1);
    d = bending_direction(&sheet);
    assert_relative(d.y, 1, 1e-4);
    ur_mesh_free(&sheet);
    ur_mesh empty = {0};
    ur_error error;
    assert_int_equal(ur_mesh_bending_direction(&empty, &d, &error), UR_ERROR_INPUT);
}

/* The offset of a point along the unit direction d. */
static double offset(ur_vec3 p, ur_vec3 d)
{
    return ur_vec3_dot(p, d);
}

/* Whether the banded mesh's band b uses vertex v. */
static bool band_uses(const ur_mesh *banded, size_t groups, size_t b, size_t v)
{
    for (size_t t = 0; t < banded->triangle_count; t++)
        if (banded->groups[t] / groups == b)
            for (int k = 0; k < 3; k++)
                if (banded->triangles[t][k] == v)
                    return true;
    return false;
}

/*
 * Five bands across an oblique direction: the area is kept, every triangle
 * lies in its band, the new vertices on the planes, the bands come in
 * order with the groups inside them kept apart, and neighbours share the
 * vertices of the plane between them.
 */
static void test_bands_cut_by_planes(void **state)
{
    (void)state;
    ur_mesh mesh = grid(16, long_saddle, 2);
    ur_vec3 direction = ur_vec3_make(2, 0.6, 0.3);
    ur_vec3 d = ur_vec3_scale(direction, 1 / ur_vec3_length(direction));
    double planes[4];
    ur_error error;
    assert_int_equal(ur_mesh_band_planes(&mesh, direction, 5, planes, &error), UR_OK);
    ur_mesh banded;
    assert_int_equal(ur_mesh_bands(&mesh, direction, planes, 5, &banded, &error), UR_OK);
    assert_relative(ur_mesh_area(&banded), ur_mesh_area(&mesh), 1e-9);
    assert_int_equal(banded.group_count, 10);
    assert_true(banded.triangle_count > mesh.triangle_count);
    for (size_t v = 0; v < mesh.vertex_count; v++)
        assert_true(ur_vec3_distance(banded.vertices[v], mesh.vertices[v]) == 0);
    for (size_t v = mesh.vertex_count; v < banded.vertex_count; v++) {
        double s = offset(banded.vertices[v], d), nearest = INFINITY;
        for (size_t j = 0; j < 4; j++)
            nearest = fmin(nearest, fabs(s - planes[j]));
        assert_true(nearest < 1e-9);
    }
    for (size_t t = 0; t < banded.triangle_count; t++) {
        size_t band = banded.groups[t] / 2;
        if (t > 0)
            assert_true(banded.groups[t] / 2 >= banded.groups[t - 1] / 2);
        double low = band > 0 ? planes[band - 1] : -INFINITY;
        double high = band < 4 ? planes[band] : INFINITY;
        for (int k = 0; k < 3; k++) {
            double s = offset(banded.vertices[banded.triangles[t][k]], d);
            assert_true(s >= low - 1e-3 && s <= high + 1e-3); /* snapped: 1e-6 of the extent */
        }
    }
    for (size_t b = 0; b < 4; b++) {
        size_t shared = 0;
        for (size_t v = 0; v < banded.vertex_count; v++)
            if (band_uses(&banded, 2, b, v) && band_uses(&banded, 2, b + 1, v)) {
                assert_true(fabs(offset(banded.vertices[v], d) - planes[b]) < 1e-3);
                shared++;
            }
        assert_true(shared > 16); /* the whole section, at least a vertex a grid line */
    }
    ur_mesh_piece *pieces = NULL;
    size_t count = 0;
    assert_int_equal(ur_mesh_pieces(&banded, NULL, 0, &pieces, &count, &error), UR_OK);
    assert_true(count >= 5);
    for (size_t p = 1; p < count; p++)
        assert_true(pieces[p].mesh.groups[0] / 2 >= pieces[p - 1].mesh.groups[0] / 2);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&banded);
    ur_mesh_free(&mesh);
}

/* Planes through rows of vertices cut no triangle: they run along edges. */
static void test_bands_through_vertices(void **state)
{
    (void)state;
    ur_mesh mesh = grid(8, flat_sheet, 1); /* x = 0, 8.75, ..., 70 */
    double planes[3] = {17.5, 35, 52.5};
    ur_mesh banded;
    ur_error error;
    assert_int_equal(ur_mesh_bands(&mesh, ur_vec3_make(1, 0, 0), planes, 4, &banded, &error),
                     UR_OK);
    assert_int_equal(banded.vertex_count, mesh.vertex_count);
    assert_int_equal(banded.triangle_count, mesh.triangle_count);
    assert_relative(ur_mesh_area(&banded), 70 * 120, 1e-12);
    for (size_t b = 0; b < 4; b++) {
        size_t count = 0;
        for (size_t t = 0; t < banded.triangle_count; t++)
            count += banded.groups[t] == b;
        assert_int_equal(count, mesh.triangle_count / 4);
    }
    ur_mesh_free(&banded);
    double bad[3] = {17.5, 17.5, 52.5};
    assert_int_equal(ur_mesh_bands(&mesh, ur_vec3_make(1, 0, 0), bad, 4, &banded, &error),
                     UR_ERROR_INPUT);
    assert_message(error, "increase");
    assert_int_equal(ur_mesh_bands(&mesh, ur_vec3_make(0, 0, 0), planes, 4, &banded, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_mesh_bands(&mesh, ur_vec3_make(1, 0, 0), planes, 0, &banded, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_mesh_band_planes(&mesh, ur_vec3_make(0, 0, 1), 3, planes, &error),
                     UR_ERROR_INPUT); /* the sheet is flat in z */
    assert_message(error, "no extent");
    ur_mesh_free(&mesh);
}

/* Planes for equal widths on a flat sheet are evenly spaced. */
static void test_band_planes_even_on_flat(void **state)
{
    (void)state;
    ur_mesh mesh = grid(10, flat_sheet, 1);
    double planes[4];
    ur_error error;
    assert_int_equal(ur_mesh_band_planes(&mesh, ur_vec3_make(0, 1, 0), 5, planes, &error), UR_OK);
    for (size_t j = 0; j < 4; j++)
        assert_relative(planes[j], 24.0 * (j + 1), 1e-9);
    ur_mesh_free(&mesh);
}

static ur_strips strips_of_mesh(const ur_mesh *mesh, ur_vec3 d, size_t count)
{
    ur_strips strips;
    ur_error error;
    if (ur_strips_of_mesh(mesh, NULL, 0, d, count, NULL, &strips, &error) != UR_OK)
        fail_msg("%zu bands: %s", count, error.message);
    return strips;
}

/* The saddle's worst strain falls as the bands multiply; the area stays. */
static void test_mesh_strain_falls_with_bands(void **state)
{
    (void)state;
    ur_mesh mesh = grid(32, long_saddle, 1);
    ur_vec3 d = bending_direction(&mesh);
    double stretch = INFINITY, compression = INFINITY, area = ur_mesh_area(&mesh);
    for (size_t count = 1; count <= 8; count *= 2) {
        ur_strips strips = strips_of_mesh(&mesh, d, count);
        assert_int_equal(strips.bands, count);
        assert_int_equal(strips.count, count);
        assert_consistent(&strips);
        assert_relative(ur_vec3_dot(strips.direction, d), 1, 1e-12);
        double sum = 0;
        for (size_t i = 0; i < strips.count; i++) {
            assert_int_equal(strips.strips[i].band, i);
            assert_int_equal(strips.strips[i].seam_count, 0);
            sum += strips.strips[i].flat.area_3d;
        }
        assert_relative(sum, area, 1e-9);
        double worst = fmax(strips.max_stretch, strips.max_compression);
        if (!(worst < fmax(stretch, compression)))
            fail_msg("%zu bands: stretch %g, compression %g; fewer: %g, %g", count,
                     strips.max_stretch, strips.max_compression, stretch, compression);
        stretch = strips.max_stretch;
        compression = strips.max_compression;
        ur_strips_free(&strips);
    }
    ur_mesh_free(&mesh);
}

static size_t fewest_bands(const ur_mesh *mesh, const ur_vec3 *direction,
                           const ur_strip_limits *limits)
{
    ur_strips strips;
    ur_error error;
    if (ur_flatten_strips_mesh(mesh, NULL, 0, direction, limits, NULL, &strips, &error) != UR_OK)
        fail_msg("bands: %s", error.message);
    size_t count = strips.bands;
    assert_true(fits(&strips, limits));
    ur_strips_free(&strips);
    return count;
}

/*
 * The fewest bands fit and one fewer do not; cut along the way the saddle
 * bends most, it takes more.
 */
static void test_mesh_fewest_bands(void **state)
{
    (void)state;
    ur_mesh mesh = grid(32, long_saddle, 1);
    ur_strip_limits limits = {.max_stretch = 0.001, .max_compression = 0.001, .max_strips = 64};
    size_t count = fewest_bands(&mesh, NULL, &limits);
    assert_true(count > 2);
    ur_strips fewer = strips_of_mesh(&mesh, bending_direction(&mesh), count - 1);
    assert_false(fits(&fewer, &limits));
    ur_strips_free(&fewer);
    ur_vec3 wrong = ur_vec3_make(0, 1, 0);
    size_t wrong_count = fewest_bands(&mesh, &wrong, &limits);
    if (!(count < wrong_count))
        fail_msg("%zu bands across x, %zu across y", count, wrong_count);
    ur_mesh_free(&mesh);
}

static void test_developable_mesh_one_band(void **state)
{
    (void)state;
    ur_mesh mesh = grid(16, quarter_tube, 1);
    ur_strip_limits limits = {.max_stretch = 1e-6, .max_compression = 1e-6, .max_strips = 8};
    assert_int_equal(fewest_bands(&mesh, NULL, &limits), 1);
    ur_mesh_free(&mesh);
}

/* Piece vertices at p: two where the piece is cut open through p, one where it is whole. */
static size_t copies_at(const ur_mesh *piece, ur_vec3 p)
{
    size_t count = 0;
    for (size_t v = 0; v < piece->vertex_count; v++)
        count += ur_vec3_distance(piece->vertices[v], p) < 1e-9;
    return count;
}

/*
 * A tube cut into two rings by a plane across its axis, with the user's
 * seam along the generator at x = -30 (crossing the plane): both rings are
 * cut open there and nowhere along the opposite generator.
 */
static void test_mesh_strips_keep_seams(void **state)
{
    (void)state;
    ur_curve *circle = NULL;
    ur_ruled ruled;
    ur_error error;
    assert_int_equal(ur_curve_new_circle(30, &circle, &error), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 60, &ruled, &error), UR_OK);
    ur_mesh mesh;
    assert_int_equal(ur_mesh_from_ruled(&ruled, 48, 5, &mesh, &error), UR_OK);
    ur_mesh_repairs repairs;
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, &repairs, &error), UR_OK);
    /* The generator at x = -30, bottom to top: 5 edges, vertices by height. */
    size_t line[6], found = 0;
    for (size_t v = 0; v < mesh.vertex_count; v++)
        if (fabs(mesh.vertices[v].x + 30) < 1e-9 && fabs(mesh.vertices[v].y) < 1e-9)
            line[found++] = v;
    assert_int_equal(found, 6);
    for (size_t i = 0; i < 6; i++) /* sort by z */
        for (size_t j = i + 1; j < 6; j++)
            if (mesh.vertices[line[j]].z < mesh.vertices[line[i]].z) {
                size_t swap = line[i];
                line[i] = line[j];
                line[j] = swap;
            }
    ur_seam seams[5];
    for (size_t i = 0; i < 5; i++)
        seams[i] = (ur_seam){line[i], line[i + 1]};
    ur_strips strips;
    if (ur_strips_of_mesh(&mesh, seams, 5, ur_vec3_make(0, 0, 1), 2, NULL, &strips, &error) !=
        UR_OK)
        fail_msg("strips: %s", error.message);
    assert_int_equal(strips.count, 2);
    for (size_t k = 0; k < 2; k++) {
        const ur_mesh *piece = &strips.strips[k].piece.mesh;
        /* The plane is at z = 30, across the seam's middle edge, 24 mm up: its
         * crossing point is cut open too, in both rings. */
        assert_int_equal(copies_at(piece, ur_vec3_make(-30, 0, 30)), 2);
        assert_int_equal(copies_at(piece, ur_vec3_make(30, 0, 30)), 1);
        assert_true(strips.strips[k].flat.max_stretch < 1e-3);
    }
    ur_strips_free(&strips);
    ur_mesh_free(&mesh);
    ur_ruled_free(&ruled);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hypar_strain_falls_with_strips),
        cmocka_unit_test(test_hypar_fewest_strips),
        cmocka_unit_test(test_hypar_limit_out_of_reach),
        cmocka_unit_test(test_bad_limits),
        cmocka_unit_test(test_strips_in_order_share_rulings),
        cmocka_unit_test(test_restriction_kept),
        cmocka_unit_test(test_cylinder_needs_one_strip),
        cmocka_unit_test(test_mesh_strips_keep_seams),
        cmocka_unit_test(test_bending_direction),
        cmocka_unit_test(test_bands_cut_by_planes),
        cmocka_unit_test(test_bands_through_vertices),
        cmocka_unit_test(test_band_planes_even_on_flat),
        cmocka_unit_test(test_mesh_strain_falls_with_bands),
        cmocka_unit_test(test_mesh_fewest_bands),
        cmocka_unit_test(test_developable_mesh_one_band),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
