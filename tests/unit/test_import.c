/*
 * test_import.c: mesh files through assimp.  The lampshade sample in every
 * format (OBJ, ASCII and binary STL, PLY, glTF with node transforms, GLB
 * with an instanced, mirrored half) gives the same surface, facing the same
 * way; groups and their names; units and scale, and the units Collada and
 * 3MF files declare; and every refusal names the file; a twisted quad is
 * split along the diagonal that follows the surface.  Areas, boxes and orientation are computed
 * here, not with src/mesh, so that this test stands on the importer alone.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <minizip/zip.h>

#include "unroll/io.h"

#define LAMPSHADE_TRIANGLES 144 /* 24 segments x 3 rows x 2 */

static const char *const lampshades[] = {
    "samples/lampshade.obj", "samples/lampshade-ascii.stl", "samples/lampshade-binary.stl",
    "samples/lampshade.ply", "samples/lampshade.gltf",      "samples/lampshade.glb",
};
#define LAMPSHADE_COUNT (sizeof lampshades / sizeof lampshades[0])

/* Every test writes its bad files into one temporary directory. */
static char directory[64];
static char written[128][128];
static int written_count;

static int make_directory(void **state)
{
    (void)state;
    if (access("samples/lampshade.obj", R_OK) != 0) {
        fprintf(stderr, "test_import: run from the repository root\n");
        return -1;
    }
    strcpy(directory, "/tmp/unroll-test-import-XXXXXX");
    return mkdtemp(directory) ? 0 : -1;
}

static int remove_directory(void **state)
{
    (void)state;
    for (int i = 0; i < written_count; i++)
        unlink(written[i]);
    return rmdir(directory);
}

/* Writes text to NAME in the temporary directory; returns the path. */
static const char *write_file(const char *name, const char *text)
{
    assert_true(written_count < 128);
    char *path = written[written_count++];
    snprintf(path, sizeof written[0], "%s/%s", directory, name);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_int_equal(fwrite(text, 1, strlen(text), file), strlen(text));
    assert_int_equal(fclose(file), 0);
    return path;
}

/* The mesh's fields are public: freeing them here keeps src/mesh out of this test. */
static void free_mesh(ur_mesh *mesh)
{
    free(mesh->vertices);
    free(mesh->triangles);
    free(mesh->groups);
    *mesh = (ur_mesh){0};
}

static void import_ok(const char *path, const ur_mesh_import_options *options, ur_mesh *mesh,
                      char (**names)[64])
{
    ur_error error = {0};
    ur_status status = ur_mesh_import(path, options, mesh, names, &error);
    if (status != UR_OK)
        fail_msg("%s: %s", path, error.message);
    assert_true(mesh->vertex_count > 0);
    assert_true(mesh->triangle_count > 0);
    assert_true(mesh->group_count > 0);
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        for (int k = 0; k < 3; k++)
            assert_true(mesh->triangles[t][k] < mesh->vertex_count);
        assert_true(mesh->groups[t] < mesh->group_count);
    }
}

static ur_vec3 corner(const ur_mesh *mesh, size_t t, int k)
{
    return mesh->vertices[mesh->triangles[t][k]];
}

/* Twice the area vector of triangle t: its normal, by the right-hand rule. */
static ur_vec3 area_vector(const ur_mesh *mesh, size_t t)
{
    ur_vec3 a = corner(mesh, t, 0);
    return ur_vec3_cross(ur_vec3_sub(corner(mesh, t, 1), a), ur_vec3_sub(corner(mesh, t, 2), a));
}

static double total_area(const ur_mesh *mesh)
{
    double area = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        area += 0.5 * ur_vec3_length(area_vector(mesh, t));
    return area;
}

/* Bounding box of the vertices triangles use: low[0..2], high[0..2]. */
static void bounding_box(const ur_mesh *mesh, double low[3], double high[3])
{
    for (int i = 0; i < 3; i++) {
        low[i] = INFINITY;
        high[i] = -INFINITY;
    }
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            ur_vec3 p = corner(mesh, t, k);
            double c[3] = {p.x, p.y, p.z};
            for (int i = 0; i < 3; i++) {
                low[i] = fmin(low[i], c[i]);
                high[i] = fmax(high[i], c[i]);
            }
        }
}

static void assert_relative(double value, double expected, double tolerance, const char *what)
{
    if (!(fabs(value - expected) <= tolerance * fabs(expected)))
        fail_msg("%s: %.17g, expected %.17g", what, value, expected);
}

static void assert_names(char (*names)[64], size_t count, const char *const *expected)
{
    for (size_t g = 0; g < count; g++)
        if (strcmp(names[g], expected[g]) != 0)
            fail_msg("group %zu: '%s', expected '%s'", g, names[g], expected[g]);
}

/* ---- Every format, one surface ---------------------------------------- */

static void test_every_format_gives_the_same_surface(void **state)
{
    (void)state;
    ur_mesh reference = {0};
    import_ok(lampshades[0], NULL, &reference, NULL);
    double area = total_area(&reference);
    double low[3], high[3];
    bounding_box(&reference, low, high);
    /* 24 planar trapezoids: the box is exact, the area a little under the cone's. */
    double expected_low[3] = {-100, -100, 0}, expected_high[3] = {100, 100, 120};
    for (int i = 0; i < 3; i++) {
        assert_relative(low[i], expected_low[i], 1e-9, "box low");
        assert_relative(high[i], expected_high[i], 1e-9, "box high");
    }
    double cone = M_PI * (100 + 60) * hypot(120, 40);
    assert_true(area < cone && area > 0.98 * cone);
    for (size_t f = 1; f < LAMPSHADE_COUNT; f++) {
        ur_mesh mesh = {0};
        import_ok(lampshades[f], NULL, &mesh, NULL);
        assert_int_equal(mesh.triangle_count, LAMPSHADE_TRIANGLES);
        assert_relative(total_area(&mesh), area, 1e-6, lampshades[f]);
        double l[3], h[3];
        bounding_box(&mesh, l, h);
        for (int i = 0; i < 3; i++) {
            /* Relative to the box's size: a zero coordinate has no scale of its own. */
            if (fabs(l[i] - low[i]) > 1e-6 * 200 || fabs(h[i] - high[i]) > 1e-6 * 200)
                fail_msg("%s: box axis %d [%g, %g], expected [%g, %g]", lampshades[f], i, l[i],
                         h[i], low[i], high[i]);
        }
        free_mesh(&mesh);
    }
    assert_int_equal(reference.triangle_count, LAMPSHADE_TRIANGLES);
    free_mesh(&reference);
}

/*
 * Triangles run counter-clockwise seen from outside, in every format: the
 * GLB's back half is the front half under a mirroring node, so this fails
 * unless the importer turns mirrored triangles round.
 */
static void test_triangles_face_outwards(void **state)
{
    (void)state;
    for (size_t f = 0; f < LAMPSHADE_COUNT; f++) {
        ur_mesh mesh = {0};
        import_ok(lampshades[f], NULL, &mesh, NULL);
        for (size_t t = 0; t < mesh.triangle_count; t++) {
            ur_vec3 n = area_vector(&mesh, t);
            ur_vec3 c = ur_vec3_add(ur_vec3_add(corner(&mesh, t, 0), corner(&mesh, t, 1)),
                                    corner(&mesh, t, 2));
            if (n.x * c.x + n.y * c.y <= 0)
                fail_msg("%s: triangle %zu faces inwards", lampshades[f], t);
        }
        free_mesh(&mesh);
    }
}

/* The GLB's two nodes use one mesh: each gets its own copy of the vertices. */
static void test_instanced_mesh_is_copied_per_node(void **state)
{
    (void)state;
    ur_mesh mesh = {0};
    import_ok("samples/lampshade.glb", NULL, &mesh, NULL);
    assert_int_equal(mesh.vertex_count, 2 * 52); /* 13 x 4 per half */
    size_t below = 0;
    for (size_t v = 0; v < mesh.vertex_count; v++)
        below += mesh.vertices[v].y < -1e-9;
    assert_int_equal(below, 11 * 4); /* the mirrored copy, less its two seams on y = 0 */
    free_mesh(&mesh);
}

/* ---- Groups ------------------------------------------------------------ */

/* Front triangles lie at y >= 0, back ones at y <= 0. */
static void expect_front_and_back(const char *path)
{
    ur_mesh mesh = {0};
    char(*names)[64] = NULL;
    import_ok(path, NULL, &mesh, &names);
    assert_non_null(names);
    assert_int_equal(mesh.group_count, 2);
    assert_names(names, 2, (const char *const[]){"front", "back"});
    size_t per_group[2] = {0, 0};
    for (size_t t = 0; t < mesh.triangle_count; t++) {
        size_t g = mesh.groups[t];
        per_group[g]++;
        for (int k = 0; k < 3; k++) {
            double y = corner(&mesh, t, k).y;
            if (g == 0 ? y < -1e-6 : y > 1e-6)
                fail_msg("%s: triangle %zu of group %s at y = %g", path, t, names[g], y);
        }
    }
    assert_int_equal(per_group[0], LAMPSHADE_TRIANGLES / 2);
    assert_int_equal(per_group[1], LAMPSHADE_TRIANGLES / 2);
    free(names);
    free_mesh(&mesh);
}

static void test_obj_groups(void **state)
{
    (void)state;
    expect_front_and_back("samples/lampshade.obj");
}

static void test_stl_solids_and_gltf_nodes_are_groups(void **state)
{
    (void)state;
    expect_front_and_back("samples/lampshade-ascii.stl");
    expect_front_and_back("samples/lampshade.gltf");
    expect_front_and_back("samples/lampshade.glb");
}

/* A file with no names of its own gives its one group the file's name. */
static void test_unnamed_group_takes_the_file_name(void **state)
{
    (void)state;
    const char *paths[] = {"samples/lampshade-binary.stl", "samples/lampshade.ply"};
    const char *expected[] = {"lampshade-binary", "lampshade"};
    for (int i = 0; i < 2; i++) {
        ur_mesh mesh = {0};
        char(*names)[64] = NULL;
        import_ok(paths[i], NULL, &mesh, &names);
        assert_int_equal(mesh.group_count, 1);
        assert_string_equal(names[0], expected[i]);
        free(names);
        free_mesh(&mesh);
    }
}

/* "g a", "g b", "g a": assimp makes three nodes; unroll, two groups. */
static void test_group_named_twice_is_one_group(void **state)
{
    (void)state;
    const char *path = write_file("regroup.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                                 "f 1 2 3\n"
                                                 "g a\nf 2 4 3\n"
                                                 "g b\nf 1 3 2\n"
                                                 "g a\nf 2 3 4\n");
    ur_mesh mesh = {0};
    char(*names)[64] = NULL;
    import_ok(path, NULL, &mesh, &names);
    assert_int_equal(mesh.triangle_count, 4);
    assert_int_equal(mesh.group_count, 3);
    /* Faces before any "g" are in no named group: they take the file's name. */
    assert_names(names, 3, (const char *const[]){"regroup", "a", "b"});
    size_t expected[4] = {0, 1, 2, 1};
    for (size_t t = 0; t < 4; t++)
        assert_int_equal(mesh.groups[t], expected[t]);
    free(names);
    free_mesh(&mesh);
}

/* ---- A closed mesh ----------------------------------------------------- */

static void test_icosphere_is_closed_and_outward(void **state)
{
    (void)state;
    ur_mesh mesh = {0};
    char(*names)[64] = NULL;
    import_ok("samples/icosphere.obj", NULL, &mesh, &names);
    assert_int_equal(mesh.triangle_count, 80);
    assert_int_equal(mesh.vertex_count, 42); /* joined: no normals or uv to keep apart */
    assert_int_equal(mesh.group_count, 1);
    assert_string_equal(names[0], "icosphere");
    double volume = 0;
    for (size_t t = 0; t < mesh.triangle_count; t++)
        volume += ur_vec3_det(corner(&mesh, t, 0), corner(&mesh, t, 1), corner(&mesh, t, 2)) / 6;
    for (size_t v = 0; v < mesh.vertex_count; v++)
        assert_relative(ur_vec3_length(mesh.vertices[v]), 40, 1e-6, "radius");
    /* Positive: outward.  Inscribed in the sphere, so a little smaller. */
    double sphere = 4.0 / 3.0 * M_PI * 40 * 40 * 40;
    assert_true(volume > 0.8 * sphere && volume < sphere);
    free(names);
    free_mesh(&mesh);
}

/* ---- Twisted quads ----------------------------------------------------- */

/*
 * A 3 x 3 grid of quads on z = bend (x^2 + y^2 + xy) / 10, as OBJ with a
 * normal per face (as Blender writes flat faces, so that assimp keeps each
 * face's corners apart).  Each quad is twisted and written from its corner
 * (x, y): assimp splits it from there, along its long diagonal.  In the
 * metric of x^2 + y^2 + xy a cell is two equilateral triangles on the short
 * diagonal, so the lifted surface's hull (a dome for bend -1, a bowl for
 * +1) is the grid split along the short diagonals, every fold of it a hill
 * (a valley in the bowl).
 */
static void write_twisted_grid(char *text, size_t size, int bend)
{
    size_t used = (size_t)snprintf(text, size, "o grid\n");
    for (int y = 0; y <= 3; y++)
        for (int x = 0; x <= 3; x++)
            used += (size_t)snprintf(text + used, size - used, "v %d %d %g\n", x, y,
                                     bend * (x * x + y * y + x * y) / 10.0);
    for (int k = 1; k <= 9; k++)
        used += (size_t)snprintf(text + used, size - used, "vn 0 0 %d.%d\n", k % 2, k);
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 3; x++) {
            int a = 4 * y + x + 1, n = 3 * y + x + 1;
            used += (size_t)snprintf(text + used, size - used, "f %d//%d %d//%d %d//%d %d//%d\n", a,
                                     n, a + 1, n, a + 5, n, a + 4, n);
        }
    assert_true(used < size);
}

static bool same_point(ur_vec3 a, ur_vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

/*
 * For every edge two triangles share (by position): how far the other's
 * far corner lies above the plane of the one, along its unit normal; the
 * least and the most of these.
 */
static void fold_heights(const ur_mesh *mesh, double *least, double *most, int *edges)
{
    *least = INFINITY, *most = -INFINITY, *edges = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (size_t o = 0; o < mesh->triangle_count; o++)
            for (int k = 0; o != t && k < 3; k++) {
                ur_vec3 a = corner(mesh, t, k), b = corner(mesh, t, (k + 1) % 3);
                int shared = 0, far = -1;
                for (int j = 0; j < 3; j++) {
                    ur_vec3 p = corner(mesh, o, j);
                    if (same_point(p, a) || same_point(p, b))
                        shared++;
                    else
                        far = j;
                }
                if (shared != 2)
                    continue;
                ur_vec3 normal = area_vector(mesh, t);
                double height = ur_vec3_dot(ur_vec3_sub(corner(mesh, o, far), a), normal) /
                                ur_vec3_length(normal);
                *least = fmin(*least, height);
                *most = fmax(*most, height);
                (*edges)++;
            }
}

static void test_twisted_quads_follow_the_surface(void **state)
{
    (void)state;
    for (int bend = -1; bend <= 1; bend += 2) {
        char text[2048];
        write_twisted_grid(text, sizeof text, bend);
        const char *path = write_file(bend < 0 ? "dome.obj" : "bowl.obj", text);
        ur_mesh mesh = {0};
        import_ok(path, NULL, &mesh, NULL);
        assert_int_equal(mesh.triangle_count, 18);
        assert_int_equal(mesh.vertex_count, 36); /* the faces' corners kept apart */
        double area = 0;
        for (size_t t = 0; t < mesh.triangle_count; t++) {
            assert_true(area_vector(&mesh, t).z > 0); /* facing +z, as written */
            area += 0.5 * area_vector(&mesh, t).z;
        }
        assert_relative(area, 9, 1e-12, "area seen from above");
        double least, most;
        int edges;
        fold_heights(&mesh, &least, &most, &edges);
        assert_int_equal(edges, 2 * 21); /* 12 sides of quads inside the grid, 9 diagonals */
        /* Folds of at least a few hundredths: the far corner clearly below (dome) or above. */
        if (bend < 0 && !(most < -0.01))
            fail_msg("dome: a fold rises %g above its neighbour's plane", most);
        if (bend > 0 && !(least > 0.01))
            fail_msg("bowl: a fold falls %g below its neighbour's plane", least);
        free_mesh(&mesh);
    }
}

/* Whether triangle t of a and o of b have their corners at the same three points, in any order. */
static bool same_corners_of(const ur_mesh *a, size_t t, const ur_mesh *b, size_t o)
{
    int matched = 0;
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++)
            matched += same_point(corner(a, t, j), corner(b, o, k));
    return matched == 3;
}

static bool same_corners(const ur_mesh *mesh, size_t t, size_t o)
{
    return same_corners_of(mesh, t, mesh, o);
}

/* Whether some triangle of the quad (first, first + 1) has the corners of triangle t. */
static bool in_quad(const ur_mesh *mesh, size_t first, size_t t)
{
    return same_corners(mesh, first, t) || same_corners(mesh, first + 1, t);
}

/*
 * A face given twice: a unit cube whose top is written again the other way
 * round, on vertices of its own at the same points (as a modeller's
 * extrusion of no length leaves it).  assimp splits the copy along the
 * other diagonal; it comes out split as the top is, each of its triangles
 * on a triangle of the top's corners, so that the mesh's cleaning can drop
 * it; so do a third copy, and an octagonal prism's top (mesh_polygons.c's
 * Delaunay triangulation).  A bow tie through the top's corners is no copy.  A square sheet with a
 * face on each side keeps assimp's split, the two faces' triangles on different corners: the same
 * split would join its two sides round their rim.
 */
static void test_face_given_twice_split_alike(void **state)
{
    (void)state;
    const char *cube = "o box\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                       "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                       "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                       "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
                       "f 12 11 10 9\n";
    ur_mesh mesh = {0};
    import_ok(write_file("doubled.obj", cube), NULL, &mesh, NULL);
    assert_int_equal(mesh.triangle_count, 14);
    size_t top = 2, copy = 12; /* each face's triangles where the face was, in order */
    assert_true(area_vector(&mesh, top).z > 0);
    assert_true(area_vector(&mesh, copy).z < 0 && area_vector(&mesh, copy + 1).z < 0);
    assert_true(in_quad(&mesh, top, copy) && in_quad(&mesh, top, copy + 1));
    free_mesh(&mesh);

    /* The top given three times: its sides then carry four triangles, still one neighbour. */
    char thrice[512];
    snprintf(thrice, sizeof thrice, "%sf 9 10 11 12\n", cube);
    import_ok(write_file("tripled.obj", thrice), NULL, &mesh, NULL);
    assert_int_equal(mesh.triangle_count, 16);
    for (copy = 12; copy < 16; copy++)
        assert_true(in_quad(&mesh, top, copy));
    free_mesh(&mesh);

    /* A bow tie through the top's corners is no copy of it: its own split stays. */
    char bow_tie[512];
    snprintf(bow_tie, sizeof bow_tie, "%.*sf 9 10 12 11\n", (int)(strstr(cube, "f 12") - cube),
             cube);
    import_ok(write_file("bow-tie.obj", bow_tie), NULL, &mesh, NULL);
    assert_int_equal(mesh.triangle_count, 14);
    assert_false(in_quad(&mesh, top, 12) && in_quad(&mesh, top, 13));
    free_mesh(&mesh);

    /*
     * A regular octagon's corners lie on a circle, where its Delaunay
     * triangulation may take any of its ties: an octagonal prism whose top
     * is given again the other way round, on vertices of its own.
     */
    char text[2048];
    size_t used = (size_t)snprintf(text, sizeof text, "o prism\n");
    for (int ring = 0; ring < 3; ring++) /* the bottom, the top and the top's copy */
        for (int k = 0; k < 8; k++)
            used += (size_t)snprintf(text + used, sizeof text - used, "v %.17g %.17g %d\n",
                                     cos(k * M_PI / 4), sin(k * M_PI / 4), ring > 0);
    used += (size_t)snprintf(text + used, sizeof text - used, "f 8 7 6 5 4 3 2 1\n");
    used += (size_t)snprintf(text + used, sizeof text - used, "f 9 10 11 12 13 14 15 16\n");
    for (int k = 0; k < 8; k++)
        used += (size_t)snprintf(text + used, sizeof text - used, "f %d %d %d %d\n", k + 1,
                                 (k + 1) % 8 + 1, (k + 1) % 8 + 9, k + 9);
    used += (size_t)snprintf(text + used, sizeof text - used, "f 24 23 22 21 20 19 18 17\n");
    assert_true(used < sizeof text);
    import_ok(write_file("prism.obj", text), NULL, &mesh, NULL);
    assert_int_equal(mesh.triangle_count, 3 * 6 + 8 * 2);
    size_t top_start = 6, copy_start = 6 + 6 + 16;
    for (size_t k = copy_start; k < copy_start + 6; k++) {
        assert_true(area_vector(&mesh, k).z < 0);
        bool found = false;
        for (size_t j = top_start; j < top_start + 6; j++)
            found = found || same_corners(&mesh, j, k);
        if (!found)
            fail_msg("triangle %zu of the top's copy is on none of the top's corners", k);
    }
    free_mesh(&mesh);

    const char *sheet = "o sheet\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 4 3 2 1\n";
    import_ok(write_file("two-sided.obj", sheet), NULL, &mesh, NULL);
    assert_int_equal(mesh.triangle_count, 4);
    assert_false(in_quad(&mesh, 0, 2) || in_quad(&mesh, 0, 3));
    free_mesh(&mesh);
}

/*
 * The dome's quads each given twice, as a modeller's copy in place leaves
 * them: each copy is split along the diagonal its quad turns to, so that
 * the cleaning drops it, and the quads turn as they do given once.  Seen
 * twice across each side, the neighbours counted as two, and no quad was
 * turned (Blender's monkey head doubled: 9 pieces, against 14 once).
 */
static void test_twisted_quads_given_twice(void **state)
{
    (void)state;
    char text[4096];
    write_twisted_grid(text, sizeof text, -1);
    ur_mesh once = {0}, twice = {0};
    import_ok(write_file("dome-once.obj", text), NULL, &once, NULL);
    const char *faces = strstr(text, "f ");
    assert_non_null(faces);
    size_t length = strlen(text);
    assert_true(2 * length < sizeof text);
    memmove(text + length, faces, strlen(faces) + 1); /* the faces again, on the same vertices */
    import_ok(write_file("dome-twice.obj", text), NULL, &twice, NULL);
    assert_int_equal(once.triangle_count, 18);
    assert_int_equal(twice.triangle_count, 36);
    for (size_t t = 0; t < 18; t++) /* the faces' triangles in the file's order, each time */
        if (!same_corners_of(&once, t, &twice, t) || !same_corners_of(&once, t, &twice, t + 18))
            fail_msg("triangle %zu: split otherwise given twice", t);
    free_mesh(&once);
    free_mesh(&twice);
}

/* ---- Flat polygons ----------------------------------------------------- */

/* The largest angle (degrees) between the normals of triangles sharing an edge (by position). */
static double largest_fold(const ur_mesh *mesh)
{
    double largest = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (size_t o = t + 1; o < mesh->triangle_count; o++) {
            int shared = 0;
            for (int j = 0; j < 3; j++)
                for (int k = 0; k < 3; k++)
                    shared += same_point(corner(mesh, t, j), corner(mesh, o, k));
            if (shared != 2)
                continue;
            ur_vec3 a = area_vector(mesh, t), b = area_vector(mesh, o);
            double cosine = ur_vec3_dot(a, b) / (ur_vec3_length(a) * ur_vec3_length(b));
            largest = fmax(largest, acos(fmin(1.0, cosine)) * 180 / M_PI);
        }
    return largest;
}

/*
 * A six-cornered facet like those round a cut gem's girdle: an apex and
 * five corners almost in line, the middle one lifted by `lift` mm.  An
 * ear-clipped triangulation has a sliver 0.1 mm wide along the line, which
 * such a lift folds by about lift / 0.1 radians; the Delaunay one has none.
 */
static void test_flat_polygons_have_no_slivers(void **state)
{
    (void)state;
    const double lifts[] = {0.003, 1.0};
    for (int c = 0; c < 2; c++) {
        char text[512];
        snprintf(text, sizeof text,
                 "o facet\nv 0 30 0\nv -20 0 0\nv -10 -0.2 0\nv 0 -0.3 %g\nv 10 -0.2 0\nv 20 0 0\n"
                 "f 1 2 3 4 5 6\n",
                 lifts[c]);
        ur_mesh mesh = {0};
        import_ok(write_file("facet.obj", text), NULL, &mesh, NULL);
        assert_int_equal(mesh.triangle_count, 4);
        double area = 0;
        for (size_t t = 0; t < mesh.triangle_count; t++) {
            assert_true(area_vector(&mesh, t).z > 0); /* facing +z, as the face runs */
            area += 0.5 * area_vector(&mesh, t).z;
        }
        /* The shoelace area of the corners seen from above. */
        assert_relative(area, 600 + 2 * 0.5 * 10 * 0.2 + 2 * 0.5 * 10 * (0.2 + 0.3), 1e-9,
                        "facet area");
        double fold = largest_fold(&mesh);
        if (c == 0 && !(fold < 0.05)) /* flat to 1e-4 of its size: no sliver left to fold */
            fail_msg("a flat facet's triangles fold by %g degrees", fold);
        if (c == 1 && !(fold > 1.0)) /* lifted 1 mm over 30: not flat, folded as it is */
            fail_msg("a facet lifted 1 mm folds by only %g degrees", fold);
        free_mesh(&mesh);
    }
}

/*
 * A flat concave polygon (a U of eight corners, in a tilted plane) comes
 * out as triangles inside it: they cover its area once, all facing the
 * way it runs.
 */
static void test_concave_flat_polygon_triangulated_inside(void **state)
{
    (void)state;
    const double u[8][2] = {{0, 0},  {30, 0}, {30, 20}, {20, 20},
                            {20, 5}, {10, 5}, {10, 20}, {0, 20}};
    char text[1024];
    size_t used = (size_t)snprintf(text, sizeof text, "o u\n");
    for (int k = 0; k < 8; k++) /* the plane z = 0.5 x + 0.25 y */
        used += (size_t)snprintf(text + used, sizeof text - used, "v %g %g %g\n", u[k][0], u[k][1],
                                 0.5 * u[k][0] + 0.25 * u[k][1]);
    snprintf(text + used, sizeof text - used, "f 1 2 3 4 5 6 7 8\n");
    ur_mesh mesh = {0};
    import_ok(write_file("u.obj", text), NULL, &mesh, NULL);
    assert_int_equal(mesh.triangle_count, 6);
    ur_vec3 normal = {-0.5, -0.25, 1}; /* of the plane, up */
    double area = 0, size = 0;
    for (size_t t = 0; t < mesh.triangle_count; t++) {
        ur_vec3 a = area_vector(&mesh, t);
        assert_true(ur_vec3_dot(a, normal) > 0);
        area += 0.5 * a.z; /* seen from above */
        size += 0.5 * ur_vec3_length(a);
    }
    assert_relative(area, 30 * 20 - 10 * 15, 1e-9, "area seen from above");
    assert_relative(size, (30 * 20 - 10 * 15) * ur_vec3_length(normal), 1e-9, "area");
    assert_true(largest_fold(&mesh) < 1e-6);
    free_mesh(&mesh);
}

/* ---- Units ------------------------------------------------------------- */

static void test_unit_names(void **state)
{
    (void)state;
    assert_int_equal(ur_length_unit_from_name("mm"), UR_UNIT_MM);
    assert_int_equal(ur_length_unit_from_name("cm"), UR_UNIT_CM);
    assert_int_equal(ur_length_unit_from_name("m"), UR_UNIT_M);
    assert_int_equal(ur_length_unit_from_name("in"), UR_UNIT_IN);
    assert_int_equal(ur_length_unit_from_name("inch"), -1);
    assert_int_equal(ur_length_unit_from_name("MM"), -1);
    assert_int_equal(ur_length_unit_from_name(""), -1);
    assert_int_equal(ur_length_unit_from_name(NULL), -1);
    for (int u = UR_UNIT_MM; u <= UR_UNIT_IN; u++)
        assert_int_equal(ur_length_unit_from_name(ur_length_unit_name(u)), u);
    assert_true(ur_length_unit_mm(UR_UNIT_IN) == 25.4);
    assert_string_equal(ur_length_unit_name(UR_UNIT_FILE), "file");
    assert_int_equal(ur_length_unit_from_name("file"), -1);
    assert_true(isnan(ur_length_unit_mm(UR_UNIT_FILE)));
    ur_mesh_import_options options = {UR_UNIT_IN, 0};
    ur_mesh_import_options_default(&options);
    assert_int_equal(options.unit, UR_UNIT_FILE);
    assert_true(options.scale == 1.0);
}

/* The same file read in other units (and scaled) has every vertex multiplied. */
static void test_units_and_scale_multiply(void **state)
{
    (void)state;
    ur_mesh mm = {0};
    import_ok("samples/lampshade.obj", NULL, &mm, NULL);
    struct {
        ur_length_unit unit;
        double scale, factor;
    } cases[] = {{UR_UNIT_CM, 1, 10},
                 {UR_UNIT_M, 1, 1000},
                 {UR_UNIT_IN, 1, 25.4},
                 {UR_UNIT_CM, 0.5, 5},
                 {UR_UNIT_MM, 3, 3}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        ur_mesh_import_options options = {cases[c].unit, cases[c].scale};
        ur_mesh scaled = {0};
        import_ok("samples/lampshade.obj", &options, &scaled, NULL);
        assert_int_equal(scaled.vertex_count, mm.vertex_count);
        assert_int_equal(scaled.triangle_count, mm.triangle_count);
        double f = cases[c].factor;
        for (size_t v = 0; v < mm.vertex_count; v++) {
            ur_vec3 expected = ur_vec3_scale(mm.vertices[v], f);
            if (ur_vec3_distance(scaled.vertices[v], expected) > 1e-12 * f * 200)
                fail_msg("%s x%g: vertex %zu off", ur_length_unit_name(cases[c].unit),
                         cases[c].scale, v);
        }
        assert_relative(total_area(&scaled), f * f * total_area(&mm), 1e-12, "scaled area");
        free_mesh(&scaled);
    }
    free_mesh(&mm);
}

/* ---- Units the file declares ------------------------------------------ */

/*
 * A Collada square of 10 x 20 units in the z = 0 plane (z up), its unit
 * given by unit_element (an <asset> child, or "" for none), into text.
 */
static void collada_square(char *text, size_t size, const char *unit_element)
{
    snprintf(text, size,
             "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
             "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
             "  <asset>%s<up_axis>Z_UP</up_axis></asset>\n"
             "  <library_geometries><geometry id=\"g\" name=\"square\"><mesh>\n"
             "    <source id=\"p\"><float_array id=\"pa\" count=\"12\">0 0 0 10 0 0 10 20 0 0 20 0"
             "</float_array>\n"
             "      <technique_common><accessor source=\"#pa\" count=\"4\" stride=\"3\">"
             "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
             "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
             "    <vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
             "    <triangles count=\"2\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
             "<p>0 1 2 0 2 3</p></triangles>\n"
             "  </mesh></geometry></library_geometries>\n"
             "  <library_visual_scenes><visual_scene id=\"s\"><node id=\"n\" name=\"square\">"
             "<instance_geometry url=\"#g\"/></node></visual_scene></library_visual_scenes>\n"
             "  <scene><instance_visual_scene url=\"#s\"/></scene>\n"
             "</COLLADA>\n",
             unit_element);
}

static const char *write_collada(const char *name, const char *unit_element)
{
    char text[2048];
    collada_square(text, sizeof text, unit_element);
    return write_file(name, text);
}

/* The square in millimetres with the first "from" in its text made "to". */
static const char *write_collada_changed(const char *name, const char *from, const char *to)
{
    char text[2048], changed[8192];
    collada_square(text, sizeof text, "<unit meter=\"0.001\"/>");
    const char *at = strstr(text, from);
    assert_non_null(at);
    snprintf(changed, sizeof changed, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    return write_file(name, changed);
}

static void add_part(zipFile zip, const char *name, const char *text)
{
    assert_int_equal(zipOpenNewFileInZip(zip, name, NULL, NULL, 0, NULL, 0, NULL, Z_DEFLATED,
                                         Z_DEFAULT_COMPRESSION),
                     ZIP_OK);
    assert_int_equal(zipWriteInFileInZip(zip, text, (unsigned)strlen(text)), ZIP_OK);
    assert_int_equal(zipCloseFileInZip(zip), ZIP_OK);
}

#define MODEL_TYPE "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"

/*
 * A 3MF package (a zip archive) whose model part, 3D/3dmodel.model, holds
 * model; with rels false it has no _rels/.rels to name it; extra, when not
 * NULL, gives more parts: a name, its text, ..., then NULL.
 */
static const char *write_3mf(const char *name, const char *model, bool rels,
                             const char *const *extra)
{
    assert_true(written_count < 128);
    char *path = written[written_count++];
    snprintf(path, sizeof written[0], "%s/%s", directory, name);
    zipFile zip = zipOpen(path, APPEND_STATUS_CREATE);
    assert_non_null(zip);
    add_part(zip, "[Content_Types].xml",
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">"
             "<Default Extension=\"rels\" "
             "ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>"
             "<Default Extension=\"model\" "
             "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>\n");
    if (rels)
        add_part(zip, "_rels/.rels",
                 "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                 "<Relationships "
                 "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">"
                 "<Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" Type=\"" MODEL_TYPE
                 "\"/></Relationships>\n");
    add_part(zip, "3D/3dmodel.model", model);
    for (size_t i = 0; extra && extra[i]; i += 2)
        add_part(zip, extra[i], extra[i + 1]);
    assert_int_equal(zipClose(zip, NULL), ZIP_OK);
    return path;
}

/* A cube of side 10 from the origin as a 3MF <mesh>, written at text + at; returns the new end. */
static size_t cube_mesh(char *text, size_t size, size_t at)
{
    static const int corners[8][3] = {{0, 0, 0},  {10, 0, 0},  {10, 10, 0},  {0, 10, 0},
                                      {0, 0, 10}, {10, 0, 10}, {10, 10, 10}, {0, 10, 10}};
    static const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                     {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                     {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    at += (size_t)snprintf(text + at, size - at, "<mesh><vertices>\n");
    for (int v = 0; v < 8; v++)
        at += (size_t)snprintf(text + at, size - at, "<vertex x=\"%d\" y=\"%d\" z=\"%d\"/>\n",
                               corners[v][0], corners[v][1], corners[v][2]);
    at += (size_t)snprintf(text + at, size - at, "</vertices><triangles>\n");
    for (int f = 0; f < 12; f++)
        at += (size_t)snprintf(text + at, size - at,
                               "<triangle v1=\"%d\" v2=\"%d\" v3=\"%d\" p1=\"%d\"/>\n", faces[f][0],
                               faces[f][1], faces[f][2], f);
    assert_true(at < size);
    return at + (size_t)snprintf(text + at, size - at, "</triangles></mesh>");
}

#define MODEL_START                                                                                \
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model%s xml:lang=\"en-US\" "                     \
    "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\" "                         \
    "xmlns:p=\"http://schemas.microsoft.com/3dmanufacturing/production/2015/06\">\n"

/*
 * A 3MF model of a cube of side 10 from the origin, placed by its build
 * item at 2 times its size and 100 along x, in the unit given by
 * unit_attribute (' unit="inch"', or "" for the default).
 */
static void cube_model(char *text, size_t size, const char *unit_attribute)
{
    size_t at = (size_t)snprintf(text, size,
                                 MODEL_START "<resources><object id=\"1\" type=\"model\" "
                                             "name=\"box\">",
                                 unit_attribute);
    at = cube_mesh(text, size, at);
    snprintf(text + at, size - at,
             "</object></resources>\n<build><item objectid=\"1\" "
             "transform=\"2 0 0 0 2 0 0 0 2 100 0 0\"/></build></model>\n");
}

/* The box's sides, sorted, and its area, against the closed forms times mm per unit. */
static void expect_size(const ur_mesh *mesh, const double sides[3], double area, double mm)
{
    double low[3], high[3], extent[3];
    bounding_box(mesh, low, high);
    for (int k = 0; k < 3; k++)
        extent[k] = high[k] - low[k];
    for (int i = 0; i < 3; i++) /* sort the three */
        for (int j = i + 1; j < 3; j++)
            if (extent[j] < extent[i]) {
                double swap = extent[i];
                extent[i] = extent[j];
                extent[j] = swap;
            }
    for (int k = 0; k < 3; k++)
        if (fabs(extent[k] - sides[k] * mm) > 1e-9 * mm * 100)
            fail_msg("side %d: %.9g mm, expected %.9g", k, extent[k], sides[k] * mm);
    assert_relative(total_area(mesh), area * mm * mm, 1e-9, "area");
}

static void expect_declared(const char *path, double mm, const char *name)
{
    double found = -1;
    char found_name[32] = "?";
    ur_error error = {0};
    if (ur_mesh_declared_unit(path, &found, found_name, &error) != UR_OK)
        fail_msg("%s: %s", path, error.message);
    assert_true(found == mm);
    assert_string_equal(found_name, name);
}

/* A Collada file is read in its <unit> (metres when it has none) unless the caller gives one. */
static void test_collada_in_its_declared_unit(void **state)
{
    (void)state;
    static const double square[3] = {0, 10, 20};
    struct {
        const char *element;
        double mm;
        const char *name;
    } cases[] = {{"<unit name=\"inch\" meter=\"0.0254\"/>", 25.4, "inch"},
                 {"<unit meter=\"0.01\"/>", 10, "0.01 m"},
                 {"<unit meter=\"0,0254\"/>", 25.4, "0.0254 m"}, /* a decimal comma (3ds Max) */
                 {"<unit name=\"centimeter\" meter=\"1\"/>", 1000, "1 m"}, /* named wrong */
                 {"", 1000, "1 m"}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char name[32];
        snprintf(name, sizeof name, "square%zu.dae", c);
        const char *path = write_collada(name, cases[c].element);
        expect_declared(path, cases[c].mm, cases[c].name);
        ur_mesh mesh = {0};
        import_ok(path, NULL, &mesh, NULL);
        assert_int_equal(mesh.triangle_count, 2);
        expect_size(&mesh, square, 200, cases[c].mm);
        /* assimp turns z up to y up: the square lies across y. */
        double low[3], high[3];
        bounding_box(&mesh, low, high);
        assert_true(fabs(high[1] - low[1]) < 1e-9);
        free_mesh(&mesh);
        ur_mesh_import_options options = {UR_UNIT_CM, 2};
        import_ok(path, &options, &mesh, NULL);
        expect_size(&mesh, square, 200, 20); /* the numbers in cm, times 2 */
        free_mesh(&mesh);
    }
    assert_int_equal(ur_mesh_up_axis("square.dae", NULL, 0), UR_UP_Y);
}

/* A 3MF is read in its model's unit (millimetres when it gives none), its build transform applied.
 */
static void test_3mf_in_its_declared_unit(void **state)
{
    (void)state;
    static const double cube[3] = {20, 20, 20};
    struct {
        const char *attribute;
        double mm;
        const char *name;
    } cases[] = {{" unit=\"inch\"", 25.4, "inch"},      {"", 1, "millimeter"},
                 {" unit=\"micron\"", 0.001, "micron"}, {" unit=\"centimeter\"", 10, "centimeter"},
                 {" unit=\"foot\"", 304.8, "foot"},     {" unit=\"meter\"", 1000, "meter"}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char model[4096], name[32];
        cube_model(model, sizeof model, cases[c].attribute);
        snprintf(name, sizeof name, "cube%zu.3mf", c);
        const char *path = write_3mf(name, model, true, NULL);
        expect_declared(path, cases[c].mm, cases[c].name);
        ur_mesh mesh = {0};
        import_ok(path, NULL, &mesh, NULL);
        assert_int_equal(mesh.triangle_count, 12);
        expect_size(&mesh, cube, 6 * 20 * 20, cases[c].mm);
        double low[3], high[3];
        bounding_box(&mesh, low, high);
        assert_relative(low[0], 100 * cases[c].mm, 1e-9, "placed by the build item");
        free_mesh(&mesh);
        ur_mesh_import_options options = {UR_UNIT_MM, 1};
        import_ok(path, &options, &mesh, NULL);
        expect_size(&mesh, cube, 6 * 20 * 20, 1);
        free_mesh(&mesh);
    }
    /* Files that declare nothing. */
    expect_declared("samples/lampshade.obj", 0, "");
    expect_declared("samples/lampshade.gltf", 0, "");
    assert_int_equal(ur_mesh_up_axis("cube.3mf", NULL, 0), UR_UP_Z);
}

/* The bytes of the file at path; free() them. */
static char *file_bytes(const char *path, size_t *size)
{
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    assert_int_equal(fseek(file, 0, SEEK_END), 0);
    *size = (size_t)ftell(file);
    rewind(file);
    char *data = malloc(*size);
    assert_non_null(data);
    assert_int_equal(fread(data, 1, *size, file), *size);
    fclose(file);
    return data;
}

/*
 * A 3MF with a thumbnail, as slicers write them: assimp 5.2 took the
 * picture for a texture and freed it twice (the import aborted).  Read
 * from the file and from memory, neither of which is changed.
 */
static void test_3mf_with_a_thumbnail(void **state)
{
    (void)state;
    static const double cube[3] = {20, 20, 20};
    char model[4096];
    cube_model(model, sizeof model, "");
    /* not a real PNG: assimp keeps a texture's bytes as they are */
    const char *const thumbnail[] = {"Metadata/thumbnail.png", "\x89PNG\r\n\x1a\n", NULL};
    const char *path = write_3mf("thumbnail.3mf", model, true, thumbnail);
    size_t size = 0;
    char *before = file_bytes(path, &size);
    ur_mesh mesh = {0};
    import_ok(path, NULL, &mesh, NULL);
    expect_size(&mesh, cube, 6 * 20 * 20, 1);
    free_mesh(&mesh);
    size_t after_size = 0;
    char *after = file_bytes(path, &after_size);
    assert_true(after_size == size && memcmp(before, after, size) == 0);
    ur_error error = {0};
    if (ur_mesh_import_buffer("thumbnail.3mf", after, after_size, NULL, &mesh, NULL, &error) !=
        UR_OK)
        fail_msg("%s", error.message);
    expect_size(&mesh, cube, 6 * 20 * 20, 1);
    free_mesh(&mesh);
    assert_memory_equal(before, after, size);
    free(before);
    free(after);
}

/* A 3MF's memory is judged by its size unpacked: assimp holds the model whole. */
static void test_3mf_memory_by_its_unpacked_size(void **state)
{
    (void)state;
    enum { COMMENT = 1 << 20 };
    char *model = malloc(4096 + COMMENT + 16);
    assert_non_null(model);
    cube_model(model, 4096, "");
    size_t length = strlen(model); /* then a megabyte of comment, which packs to little */
    memcpy(model + length, "<!--", 4);
    memset(model + length + 4, 'x', COMMENT);
    strcpy(model + length + 4 + COMMENT, "-->\n");
    const char *path = write_3mf("comment.3mf", model, true, NULL);
    free(model);
    struct stat info;
    assert_int_equal(stat(path, &info), 0);
    assert_true(info.st_size < COMMENT / 100);
    assert_true(ur_mesh_import_memory_estimate(path) >= (size_t)40 * COMMENT);
}

/* ---- Refusals ---------------------------------------------------------- */

/* Expects UR_ERROR_INPUT, a message starting "PATH: " or "PATH:LINE: " and containing fragment. */
static void expect_refusal(const char *path, const ur_mesh_import_options *options,
                           const char *fragment)
{
    ur_mesh mesh = {(ur_vec3 *)&mesh, 99, NULL, 99, NULL, 99};
    char(*names)[64] = (char(*)[64]) & mesh;
    ur_error error = {0};
    assert_int_equal(ur_mesh_import(path, options, &mesh, &names, &error), UR_ERROR_INPUT);
    assert_int_equal(error.status, UR_ERROR_INPUT);
    assert_null(mesh.vertices);
    assert_null(mesh.triangles);
    assert_null(mesh.groups);
    assert_int_equal(mesh.vertex_count + mesh.triangle_count + mesh.group_count, 0);
    assert_null(names);
    char prefix[256];
    snprintf(prefix, sizeof prefix, "%s:", path);
    size_t length = strlen(prefix);
    const char *rest = error.message + length;
    bool named = strncmp(error.message, prefix, length) == 0 &&
                 (rest[0] == ' ' || (rest[0] >= '1' && rest[0] <= '9' &&
                                     strspn(rest, "0123456789") + rest == strstr(rest, ": ")));
    if (!named || !strstr(error.message, fragment))
        fail_msg("message '%s' lacks '%s' or '%s'", error.message, prefix, fragment);
}

static void test_missing_file(void **state)
{
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/missing.obj", directory);
    expect_refusal(path, NULL, "No such file");
    expect_refusal(directory, NULL, "not a regular file");
}

static void test_not_a_mesh(void **state)
{
    (void)state;
    const char *text = "Shopping list\nplywood, glue\n";
    expect_refusal(write_file("notes.txt", text), NULL, "unsupported file type: unroll reads");
    /* What makers often have, with what to export instead. */
    expect_refusal(write_file("model.fbx", text), NULL, "unsupported file type, FBX is not read");
    expect_refusal(write_file("chair.skp", text), NULL, "export it as Collada (.dae)");
    expect_refusal(write_file("bracket.STEP", text), NULL, "a CAD solid, not a mesh");
    /* Known extensions: assimp says why it cannot read them. */
    expect_refusal(write_file("notes.stl", text), NULL, "STL");
    expect_refusal(write_file("notes.ply", text), NULL, "ply");
    expect_refusal(write_file("notes.gltf", text), NULL, "notes.gltf: not a glTF file");
    expect_refusal(write_file("notes.glb", text), NULL, "notes.glb: not a binary glTF file");
    /* "plywood" reads as an OBJ point ("p") with a bad index. */
    expect_refusal(write_file("notes.obj", text), NULL, "cannot read as a mesh");
    /* Other text the OBJ reader skips line by line, finding nothing. */
    expect_refusal(write_file("letter.obj", "Hello there\nthis is text\n"), NULL, "empty scene");
}

static void test_empty_obj(void **state)
{
    (void)state;
    expect_refusal(write_file("empty.obj", ""), NULL, "empty");
    expect_refusal(write_file("comments.obj", "# nothing here\n# at all\n\n"), NULL, "empty scene");
}

static void test_vertices_only(void **state)
{
    (void)state;
    expect_refusal(write_file("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), NULL, "no triangles");
    expect_refusal(write_file("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n"), NULL,
                   "only 2 points and lines");
}

static void test_non_finite_coordinates(void **state)
{
    (void)state;
    expect_refusal(write_file("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"), NULL,
                   "vertex 2 (in face 1): coordinates (1, nan, 0): not a number");
    expect_refusal(write_file("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n"), NULL,
                   "infinite");
    /* Beyond a float: assimp reads it as infinity. */
    expect_refusal(write_file("huge.obj", "v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n"), NULL,
                   "single precision");
}

static void test_coordinates_beyond_1000_km(void **state)
{
    (void)state;
    ur_mesh_import_options options = {UR_UNIT_MM, 1e300};
    expect_refusal("samples/lampshade.obj", &options, "beyond 1000 km");
    options = (ur_mesh_import_options){UR_UNIT_M, 1e5}; /* 100 m x 1e5: 10 000 km */
    expect_refusal("samples/lampshade.obj", &options, "beyond 1000 km");
    /* Up to 1e9 mm is allowed: 120 mm x 8e6 = 960 km. */
    options = (ur_mesh_import_options){UR_UNIT_MM, 8e6};
    ur_mesh mesh = {0};
    import_ok("samples/lampshade.obj", &options, &mesh, NULL);
    free_mesh(&mesh);
}

/*
 * Headers that announce more than unroll takes are refused before assimp,
 * which would reserve memory for them and read on past the end of the file.
 */
static void test_headers_claiming_too_much(void **state)
{
    (void)state;
    const char *ply_header = "ply\nformat ascii 1.0\nelement vertex %s\n"
                             "property float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    char text[512];
    snprintf(text, sizeof text, ply_header, "1000000000");
    expect_refusal(write_file("billion.ply", text), NULL, "more than the 50000000");
    snprintf(text, sizeof text, ply_header, "1000000");
    expect_refusal(write_file("million.ply", text), NULL, "more than the 26 bytes");
    /* A binary STL of 20 million triangles, sparse: its size is what says binary. */
    const char *path = write_file("huge.stl", "");
    FILE *file = fopen(path, "wb");
    assert_non_null(file);
    unsigned char header[84] = {0};
    uint32_t triangles = 20000000;
    for (int i = 0; i < 4; i++)
        header[80 + i] = (unsigned char)(triangles >> (8 * i));
    assert_int_equal(fwrite(header, 1, sizeof header, file), sizeof header);
    assert_int_equal(fclose(file), 0);
    assert_int_equal(truncate(path, 84 + 50 * (off_t)triangles), 0);
    expect_refusal(path, NULL, "60000000 vertices, more than the 50000000");
}

/*
 * assimp 5.2 reads a PLY whose header never ends for ever, crashes on some
 * headers with lines PLY does not define and on a face whose count is far
 * more than its line holds, and aborts on a file that ends before its faces
 * (all found by fuzz_mesh).
 */
static void test_ply_header_checked(void **state)
{
    (void)state;
    expect_refusal(write_file("cut.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"
                                         "property float x\nproperty float y\nproperty float z\n"),
                   NULL, "cut.ply: the PLY header has no end_header line");
    /* Without end_header the first vertex is read as a header line. */
    expect_refusal(write_file("data.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"
                                          "property float x\nproperty float y\nproperty float z\n"
                                          "0 0 0\n"),
                   NULL, "data.ply:7: not a line of a PLY header");
    expect_refusal(write_file("magic.ply", "ply\n"), NULL, "no end_header");
    const char *bad[] = {"property floder\n", "ty float y\n",   "property floaist uchaces\n",
                         "element vertex\n",  "format ascii\n", "end_header extra\n"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[256];
        snprintf(text, sizeof text,
                 "ply\nformat ascii 1.0\ncomment fine\nelement vertex 3\n"
                 "property float x\n%sproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
                 bad[i]);
        expect_refusal(write_file("bad.ply", text), NULL, "bad.ply:6: not a line of a PLY header");
    }
    expect_refusal(write_file("start.ply", "PLY\nformat ascii 1.0\nend_header\n"), NULL,
                   "start.ply:1: not a PLY file");
    /*
     * A file that ends before its faces: assimp made faces without corners
     * and aborted; one whose vertex lines run short: it made 72 faces of the
     * last corner count it read.
     */
    expect_refusal(write_file("faces.ply",
                              "ply\nformat ascii 1.0\nelement vertex 3\n"
                              "property float x\nproperty float y\nproperty float z\n"
                              "element face 1\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0\n1 0 0\n0 1 0\n"),
                   NULL, "faces.ply: the file ends after 0 of the 1 lines of element 2");
    expect_refusal(write_file("short.ply",
                              "ply\nformat ascii 1.0\nelement vertex 3\n"
                              "property float x\nproperty float y\nproperty float z\n"
                              "element face 1\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0\n3 0 1 2\n"),
                   NULL, "short.ply: the file ends after 2 of the 3 lines of element 1");
    /* A face claiming 20 million corners: assimp read on for them and crashed. */
    expect_refusal(write_file("corners.ply",
                              "ply\nformat ascii 1.0\nelement vertex 3\n"
                              "property float x\nproperty float y\nproperty float z\n"
                              "element face 2\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
                              "20000000 0 1 2\n"),
                   NULL, "corners.ply:14: a list of 20000000 values on a line that holds fewer");
    /* A property before any element belongs to nothing. */
    expect_refusal(write_file("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\n"
                                            "end_header\n"),
                   NULL, "orphan.ply:3: not a line");
}

/*
 * assimp reads a file by its content when no reader its name asks for takes
 * it: a PLY header named .gltf went to assimp's PLY reader unchecked, which
 * looped for ever on this one (found by fuzz_mesh).  A .gltf must be JSON
 * (a .glb start with "glTF"), and the PLY checks go by the content, for a
 * file and for a buffer: named .obj, the header is checked as PLY.
 */
static void test_content_checked_whatever_the_name(void **state)
{
    (void)state;
    const char *text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                       "property floder\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    expect_refusal(write_file("hang.gltf", text), NULL, "hang.gltf: not a glTF file");
    expect_refusal(write_file("hang.glb", text), NULL, "hang.glb: not a binary glTF file");
    expect_refusal(write_file("hang.obj", text), NULL, "hang.obj:5: not a line of a PLY header");
    ur_mesh mesh;
    ur_error error;
    assert_int_equal(
        ur_mesh_import_buffer("hang.gltf", text, strlen(text), NULL, &mesh, NULL, &error),
        UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "hang.gltf: not a glTF file"));
    assert_int_equal(
        ur_mesh_import_buffer("hang.obj", text, strlen(text), NULL, &mesh, NULL, &error),
        UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "hang.obj:5: not a line of a PLY header"));
    /* JSON after a byte-order mark, which assimp's glTF 2.0 reader does not take. */
    expect_refusal(write_file("bom.gltf", "\xEF\xBB\xBF \n{}"), NULL, "byte-order mark");
    /* Only a first word "ply" makes a PLY: an OBJ that starts "plywood" is read as OBJ. */
    expect_refusal(write_file("notes.obj", "plywood\n"), NULL, "notes.obj");
    ur_error obj_error;
    assert_int_equal(
        ur_mesh_import_buffer("notes.obj", "plywood\n", 8, NULL, &mesh, NULL, &obj_error),
        UR_ERROR_INPUT);
    assert_null(strstr(obj_error.message, "PLY"));
}

/*
 * unroll reads no material library: assimp 5.2's OBJ reader crashed on one
 * with a texture line before its first material, from disk where the OBJ
 * names such a file (whatever its extension), and from a buffer whenever
 * the OBJ names a library, since assimp then read the OBJ itself as the
 * library (found by fuzz_mesh).  Both OBJs are read, their one triangle
 * whole.
 */
static void test_material_library_not_read(void **state)
{
    (void)state;
    const char *triangle = "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 3\n";
    char text[256];
    write_file("textures.mtl", "map_Kd wood.png\nnewmtl wood\n");
    write_file("textures.txt", "map_Kd wood.png\n");
    const char *libraries[] = {"textures.mtl", "textures.txt"};
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, "mtllib %s\nusemtl wood\n%s", libraries[k], triangle);
        ur_mesh mesh;
        import_ok(write_file(k ? "named-txt.obj" : "named-mtl.obj", text), NULL, &mesh, NULL);
        assert_int_equal(mesh.triangle_count, 1);
        free_mesh(&mesh);
    }
    snprintf(text, sizeof text, "map_db 0 0\nmtllib x\n%s", triangle);
    ur_mesh mesh;
    ur_error error;
    assert_int_equal(
        ur_mesh_import_buffer("buffer.obj", text, strlen(text), NULL, &mesh, NULL, &error), UR_OK);
    assert_int_equal(mesh.triangle_count, 1);
    free_mesh(&mesh);
}

static void test_bad_index_and_options(void **state)
{
    (void)state;
    expect_refusal(write_file("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"), NULL,
                   "index out of range");
    ur_mesh_import_options options[] = {{UR_UNIT_MM, 0},
                                        {UR_UNIT_MM, -1},
                                        {UR_UNIT_MM, NAN},
                                        {UR_UNIT_MM, INFINITY},
                                        {(ur_length_unit)7, 1}};
    for (size_t i = 0; i < sizeof options / sizeof options[0]; i++) {
        ur_mesh mesh = {0};
        ur_error error = {0};
        assert_int_equal(ur_mesh_import("samples/lampshade.obj", &options[i], &mesh, NULL, &error),
                         UR_ERROR_INPUT);
        assert_null(mesh.vertices);
    }
}

/*
 * Collada documents that crashed assimp 5.2, made it take gigabytes or
 * read past its arrays (the first found by fuzz_mesh, the others made
 * after assimp's reader), refused naming their line before it reads them.
 */
static void test_collada_lies_refused(void **state)
{
    (void)state;
    static const struct {
        const char *from, *to, *fragment;
    } cases[] = {
        {"<p>0 1 2", "<p>0 1x 2", ":8: <p> holds '1x': not a whole number"},
        {"<triangles count=\"2\">", "<triangles count=\"2000000000\">",
         ":8: <p> holds 6 indices where <triangles count=\"2000000000\"> with 1 index per corner "
         "needs 6000000000"},
        {"<triangles count=\"2\">", "<triangles count=\"-1\">",
         "<triangles count=\"-1\">: not a whole number from 0 to 4294967295"},
        {"count=\"12\">", "count=\"3\">", ":5: <float_array count=\"3\"> holds 12 values"},
        {"0 20 0<", "0 20 0 1..5<", "<float_array> holds '1..5': not a number"},
        {"stride=\"3\"", "stride=\"4\"",
         ":6: <accessor source=\"#pa\"> reaches value 16 of an array of 12"},
        {"stride=\"3\"", "stride=\"0\"", "<accessor stride=\"0\">: a stride is at least 1"},
        /* assimp reads the last array of an id: it held only 3 values */
        {"</source>",
         "</source><source id=\"q\"><float_array id=\"pa\" count=\"3\">0 0 "
         "0</float_array></source>",
         ":6: <accessor source=\"#pa\"> reaches value 12 of an array of 3"},
        {"<param name=\"X\" type=\"float\"/>",
         "<param name=\"W\" type=\"float\"/><param name=\"X\" type=\"float\"/>",
         "<accessor stride=\"3\"> has 4 parameter values"},
        {"semantic=\"VERTEX\" source=\"#v\"", "semantic=\"NORMAL\" source=\"#p\"",
         "<p> of <triangles> before an <input semantic=\"VERTEX\">"},
        {"<triangles count=\"2\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
         "<p>0 1 2 0 2 3</p></triangles>",
         "<tristrips count=\"0\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
         "<p>0 1 2 3</p></tristrips>",
         ":8: <tristrips count=\"0\"> has 1 <p>"},
        {"<instance_geometry url=\"#g\"/>",
         "<instance_geometry url=\"#g\"/><node id=\"m\"><instance_node url=\"#n\"/></node>",
         ":10: <instance_node> makes a node contain itself"},
        {"</asset>",
         "</asset><library_images><image id=\"i\"><init_from><hex format=\"PNG\">0a</hex>"
         "</init_from></image></library_images>",
         "an image given in <hex>"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char name[32];
        snprintf(name, sizeof name, "lie%zu.dae", c);
        expect_refusal(write_collada_changed(name, cases[c].from, cases[c].to), NULL,
                       cases[c].fragment);
    }
}

/* The square's file with scene (library nodes and visual scenes) in place of its visual scene. */
static const char *write_collada_scene(const char *name, const char *scene)
{
    char text[2048];
    collada_square(text, sizeof text, "<unit meter=\"0.001\"/>");
    const char *from = strstr(text, "  <library_visual_scenes>");
    const char *end = "</library_visual_scenes>";
    const char *to = strstr(text, end) + strlen(end);
    char whole[16384];
    assert_true((size_t)snprintf(whole, sizeof whole, "%.*s%s%s", (int)(from - text), text, scene,
                                 to) < sizeof whole);
    return write_file(name, whole);
}

/*
 * Nodes that instance the level below twice at each of 18 levels grow
 * into 2^18 nodes; at 10 levels (1,024 squares) they are a model, read in
 * full.  Each node's name is its id, as Blender writes them: a node found
 * by both is one node, not two (else 10 levels would grow into 4^10).
 */
static void test_collada_instances_bounded(void **state)
{
    (void)state;
    for (int levels = 10; levels <= 18; levels += 8) {
        char scene[8192] = "<library_nodes><node id=\"l0\" name=\"l0\">"
                           "<instance_geometry url=\"#g\"/></node>";
        for (int level = 1; level <= levels; level++) {
            size_t used = strlen(scene);
            snprintf(scene + used, sizeof scene - used,
                     "<node id=\"l%d\" name=\"l%d\"><instance_node url=\"#l%d\"/>"
                     "<node><matrix>1 0 0 0 0 1 0 0 0 0 1 %d 0 0 0 1</matrix>"
                     "<instance_node url=\"#l%d\"/></node></node>",
                     level, level, level - 1, 1 << level, level - 1);
        }
        size_t used = strlen(scene);
        snprintf(scene + used, sizeof scene - used,
                 "</library_nodes><library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
                 "<instance_node url=\"#l%d\"/></node></visual_scene></library_visual_scenes>",
                 levels);
        char name[32];
        snprintf(name, sizeof name, "levels%d.dae", levels);
        const char *path = write_collada_scene(name, scene);
        if (levels > 16) {
            expect_refusal(path, NULL, "this node grows into more than 100000 nodes");
            continue;
        }
        ur_mesh mesh;
        ur_error error;
        assert_int_equal(ur_mesh_import(path, NULL, &mesh, NULL, &error), UR_OK);
        assert_int_equal(mesh.triangle_count, 2u << levels);
        assert_relative(total_area(&mesh), 200.0 * (1 << levels), 1e-9, "squares' area");
        free_mesh(&mesh);
    }
}

/* An instance that names 65 nodes (all called "x") is a lie: ids and names are meant to be unique.
 */
static void test_collada_instance_names_many(void **state)
{
    (void)state;
    char scene[8192] = "<library_nodes>";
    for (int k = 0; k < 65; k++)
        strcat(scene, "<node name=\"x\"/>");
    strcat(scene, "</library_nodes><library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
                  "<instance_geometry url=\"#g\"/><instance_node url=\"#x\"/></node>"
                  "</visual_scene></library_visual_scenes>");
    expect_refusal(write_collada_scene("many.dae", scene), NULL,
                   ":10: <instance_node> names more than 64 nodes by one id or name");
}

/* 3ds Max writes a decimal comma in some locales; assimp reads it, and so does the check. */
static void test_collada_decimal_comma(void **state)
{
    (void)state;
    const char *path = write_collada_changed("comma.dae", "0 0 0 10 0 0 10 20 0 0 20 0",
                                             "0 0 0 10,5 0 0 10,5 20 0 0 20 0");
    ur_mesh mesh;
    ur_error error;
    assert_int_equal(ur_mesh_import(path, NULL, &mesh, NULL, &error), UR_OK);
    assert_relative(total_area(&mesh), 210.0, 1e-6, "a 10.5 x 20 mm square");
    free_mesh(&mesh);
}

/*
 * A 3MF vertex coordinate or triangle corner that is not a number: assimp
 * 5.2 reads it as 0, a wrong model without a word.
 */
static void test_3mf_numbers_checked(void **state)
{
    (void)state;
    static const struct {
        const char *from, *to, *fragment;
    } cases[] = {
        {"<vertex x=\"10\" y=\"0\"", "<vertex x=\"ten\" y=\"0\"",
         "line 5: <vertex x=\"ten\">: not a number"},
        {"<vertex x=\"10\" y=\"0\"", "<vertex x=\"1,5\" y=\"0\"",
         "<vertex x=\"1,5\">: not a number"},
        {"v2=\"2\" v3=\"1\"", "v2=\"2\" v3=\"-1\"",
         "line 13: <triangle v3=\"-1\">: not a vertex number"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char model[4096], changed[4096], name[32];
        cube_model(model, sizeof model, "");
        const char *at = strstr(model, cases[c].from);
        assert_non_null(at);
        snprintf(changed, sizeof changed, "%.*s%s%s", (int)(at - model), model, cases[c].to,
                 at + strlen(cases[c].from));
        snprintf(name, sizeof name, "numbers%zu.3mf", c);
        expect_refusal(write_3mf(name, changed, true, NULL), NULL, cases[c].fragment);
    }
}

/* Collada and 3MF files whose unit, or the part that declares it, cannot be read. */
static void test_declared_unit_refusals(void **state)
{
    (void)state;
    expect_refusal(write_collada("negative.dae", "<unit meter=\"-2\"/>"), NULL,
                   "<unit meter=\"-2\">: the metres in one unit must be a positive number");
    expect_refusal(write_collada("word.dae", "<unit meter=\"big\"/>"), NULL, "meter=\"big\"");
    expect_refusal(write_collada("zero.dae", "<unit meter=\"0\"/>"), NULL, "meter=\"0\"");
    expect_refusal(write_file("other.dae", "<?xml version=\"1.0\"?>\n<scene/>\n"), NULL,
                   "not a Collada file");
    const char *cut = write_file("cut.dae", "<?xml version=\"1.0\"?>\n<COLLADA>\n<asset><unit "
                                            "meter=\"1\"\n");
    expect_refusal(cut, NULL, ":4: Collada: ");
    double mm = -1;
    char unit_name[32];
    ur_error error = {0};
    /* the unit's reader says it as the import's check does */
    assert_int_equal(ur_mesh_declared_unit(cut, &mm, unit_name, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "cut.dae:4: Collada: "));
    expect_refusal(write_file("text.dae", "Shopping list\n"), NULL, "Collada");
    expect_refusal(write_file("text.3mf", "Shopping list\n"), NULL, "not a zip archive");
    char model[4096];
    cube_model(model, sizeof model, "");
    expect_refusal(write_3mf("norels.3mf", model, false, NULL), NULL, "no _rels/.rels");
    cube_model(model, sizeof model, " unit=\"parsec\"");
    expect_refusal(write_3mf("parsec.3mf", model, true, NULL), NULL,
                   "<model unit=\"parsec\">: not a 3MF unit");
    expect_refusal(write_3mf("notxml.3mf", "Shopping list\n", true, NULL), NULL, "3MF model");
    expect_refusal(write_3mf("scene.3mf", "<?xml version=\"1.0\"?>\n<scene/>\n", true, NULL), NULL,
                   "does not start with <model>");
    /* From memory, the same checks. */
    ur_mesh mesh = {0};
    const char text[] = "<?xml version=\"1.0\"?>\n<scene/>\n";
    assert_int_equal(
        ur_mesh_import_buffer("mem.dae", text, sizeof text - 1, NULL, &mesh, NULL, &error),
        UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "mem.dae: not a Collada file"));
    assert_int_equal(
        ur_mesh_import_buffer("mem.3mf", text, sizeof text - 1, NULL, &mesh, NULL, &error),
        UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "mem.3mf: not a 3MF file: not a zip archive"));
}

/* A glTF from memory refused, the message saying fragment; or (fragment NULL) passed to assimp. */
static void expect_gltf(const char *name, const void *data, size_t size, const char *fragment)
{
    ur_mesh mesh = {0};
    ur_error error = {0};
    assert_int_equal(ur_mesh_import_buffer(name, data, size, NULL, &mesh, NULL, &error),
                     UR_ERROR_INPUT);
    /* glTF 2.0's reader's own message for a document without a scene: it took the file */
    const char *expected = fragment ? fragment : "GLTF: No scene";
    if (!strstr(error.message, expected))
        fail_msg("%s: \"%s\" does not say \"%s\"", name, error.message, expected);
}

/* A binary glTF: its header (version, length), one chunk of JSON, and a chunk of type bin. */
static size_t glb_of(unsigned char *out, uint32_t version, const char *json, const char *type,
                     uint32_t length_extra, bool bin)
{
    size_t json_length = (strlen(json) + 3) & ~(size_t)3, at = 20 + json_length;
    memcpy(out, "glTF", 4);
    for (int i = 0; i < 4; i++) {
        out[4 + i] = (unsigned char)(version >> (8 * i));
        out[12 + i] = (unsigned char)(json_length >> (8 * i));
    }
    memcpy(out + 16, type, 4);
    memset(out + 20, ' ', json_length);
    memcpy(out + 20, json, strlen(json));
    if (bin) {
        memset(out + at, 0, 12);
        out[at] = 4; /* four bytes of data */
        memcpy(out + at + 4, "BIN", 4);
        at += 12;
    }
    uint32_t length = (uint32_t)at + length_extra;
    for (int i = 0; i < 4; i++)
        out[8 + i] = (unsigned char)(length >> (8 * i));
    return at;
}

/*
 * assimp 5.2 reads a .gltf or .glb that its glTF 2.0 reader does not take
 * with every other reader it has: a broken .gltf holding a zip archive
 * went to its 3MF reader, which stopped the process (found by fuzz_mesh;
 * in tests/fuzz/regressions/mesh).  So glTF is refused unless it is JSON
 * that reader takes, naming the line; what is goes to that reader, whose
 * message for a document without a scene says so.
 */
static void test_gltf_read_only_as_gltf2(void **state)
{
    (void)state;
    static const struct {
        const char *text, *fragment;
    } refused[] = {
        {"{\"asset\":{\"version\":\"2.0\"},}",
         "a.gltf:1: not a glTF file assimp reads: a member's"},
        {"{\"asset\":{\"version\":\"2.0\"}", "a ',' or '}' was expected"},
        {"{\"asset\":{\"version\":\"2.0\"},\n\"a\":\"tab\there\"}", ":2: not a glTF file"
                                                                    " assimp reads: a control"},
        {"{\"asset\":{\"version\":\"2.0\"},\"a\":\"\\q\"}", "a backslash before a letter"},
        {"{\"asset\":{\"version\":\"2.0\"},\"a\":\"\\udc00\"}", "second half of a surrogate"},
        {"{\"asset\":{\"version\":\"2.0\"},\"a\":\"\\ud800x\"}", "without its other half"},
        {"{\"asset\":{\"version\":\"2.0\"},\"a\":1e300}", "a number of 1e300 or more"},
        {"{\"asset\":{\"version\":\"2.0\"},\"a\":01}", "a ',' or '}' was expected"},
        {"{\"asset\":{\"version\":\"2.0\"},\"a\":-}", "a minus sign without a number"},
        {"{\"asset\":{\"version\":\"2.0\"},\"a\":1.}", "no digits after it"},
        {"{\"asset\":{\"version\":\"2.0\"},\"a\":tru}", "a value was expected"},
        {"{\"asset\":{\"version\":\"2.0\"}} {}", "something follows the JSON object"},
        {"\xEF\xBB\xBF{\"asset\":{\"version\":\"2.0\"}}", "byte-order mark"},
        {"{\"scene\":0}", "no \"asset\" with a \"version\""},
        {"{\"asset\":[]}", "its \"asset\" is not an object"},
        {"{\"asset\":{\"version\":2}}", "its asset's \"version\" is not a string"},
        {"{\"asset\":{\"version\":\"1.0\"}}", "glTF version '1.0': only glTF 2.0 is read"},
        {"{\"asset\":{\"version\":\"2.0\",\"profile\":\"WebGL\"}}", "\"profile\" is not an object"},
    };
    for (size_t c = 0; c < sizeof refused / sizeof refused[0]; c++)
        expect_gltf("a.gltf", refused[c].text, strlen(refused[c].text), refused[c].fragment);
    /* Taken: an escaped name, the first of two versions, a NUL and bytes after the object. */
    static const char escaped[] = "{\"\\u0061sset\":{\"version\":\"2.0\",\"version\":2},"
                                  "\"a\":[1e299,-0.5E-3,\"\\ud83d\\ude00\"]}\0PK\5\6";
    expect_gltf("b.gltf", escaped, sizeof escaped - 1, NULL);
    /* 256 deep is taken, 257 not (rapidjson reads nesting by recursion). */
    char deep[2048];
    for (int levels = 255; levels <= 256; levels++) {
        int at = snprintf(deep, sizeof deep, "{\"asset\":{\"version\":\"2.0\"},\"a\":");
        for (int i = 0; i < levels; i++)
            deep[at++] = '[';
        for (int i = 0; i < levels; i++)
            deep[at++] = ']';
        snprintf(deep + at, sizeof deep - (size_t)at, "}");
        expect_gltf("c.gltf", deep, strlen(deep), levels == 255 ? NULL : "256 deep");
    }
    unsigned char glb[256];
    const char *json = "{\"asset\":{\"version\":\"2.0\"}}";
    expect_gltf("d.glb", glb, glb_of(glb, 2, json, "JSON", 0, false), NULL);
    expect_gltf("e.glb", glb, glb_of(glb, 2, json, "JSON", 0, true), NULL);
    expect_gltf("f.glb", glb, glb_of(glb, 1, json, "JSON", 0, false), "binary glTF version 1");
    expect_gltf("g.glb", glb, glb_of(glb, 2, json, "BIN\0", 0, false), "not its JSON");
    expect_gltf("h.glb", glb, glb_of(glb, 2, json, "JSON", 8, false), "a BIN chunk follows");
    size_t size = glb_of(glb, 2, json, "JSON", 0, false);
    glb[12] = 200; /* the JSON chunk's length */
    expect_gltf("i.glb", glb, size, "goes past the end");
    size = glb_of(glb, 2, "{\"asset\":{\"version\":\"2.0\"}", "JSON", 0, false);
    expect_gltf("j.glb", glb, size, "j.glb: JSON chunk:1: not a glTF file assimp reads");
}

/* A 3MF read from memory is read as from its file. */
static void test_3mf_from_memory(void **state)
{
    (void)state;
    char model[4096];
    cube_model(model, sizeof model, " unit=\"inch\"");
    const char *path = write_3mf("memory.3mf", model, true, NULL);
    size_t size = 0;
    char *data = file_bytes(path, &size);
    ur_mesh mesh = {0};
    ur_error error = {0};
    if (ur_mesh_import_buffer("memory.3mf", data, size, NULL, &mesh, NULL, &error) != UR_OK)
        fail_msg("%s", error.message);
    free(data);
    static const double cube[3] = {20, 20, 20};
    expect_size(&mesh, cube, 6 * 20 * 20, 25.4);
    free_mesh(&mesh);
}

/*
 * Objects in parts of their own, named by components' p:path (3MF's
 * production extension, as Bambu Studio writes every model): assimp 5.2
 * reads only the model part and found no mesh.  The model here has two
 * components on one object of 3D/Objects/box.model, the second moved 50
 * along x, and a build item on an object of 3D/Objects/nest.model that is
 * a component of another object of that part.  The copied objects' colour
 * (pid 7, pindex 5) would name the model's own basematerials 7, which has
 * one entry: it is dropped.
 */
static void test_3mf_objects_in_parts_of_their_own(void **state)
{
    (void)state;
    static const char model[] =
        MODEL_START "<resources><basematerials id=\"7\"><base name=\"red\" "
                    "displaycolor=\"#FF0000\"/></basematerials>\n"
                    "<object id=\"1\" type=\"model\"><components>"
                    "<component p:path=\"/3D/Objects/box.model\" objectid=\"1\"/>"
                    "<component p:path=\"/3D/Objects/box.model\" objectid=\"1\" "
                    "transform=\"1 0 0 0 1 0 0 0 1 50 0 0\"/></components></object></resources>\n"
                    "<build><item objectid=\"1\"/><item p:path=\"/3D/Objects/nest.model\" "
                    "objectid=\"3\" transform=\"1 0 0 0 1 0 0 0 1 0 100 0\"/></build></model>\n";
    char text[4096], box[4096], nest[4096];
    snprintf(text, sizeof text, model, "");
    size_t at = (size_t)snprintf(box, sizeof box,
                                 MODEL_START "<resources><object id=\"1\" type=\"model\" "
                                             "pid=\"7\" pindex=\"5\">",
                                 "");
    at = cube_mesh(box, sizeof box, at);
    snprintf(box + at, sizeof box - at, "</object></resources><build/></model>\n");
    at = (size_t)snprintf(nest, sizeof nest,
                          MODEL_START "<resources><object id=\"2\" type=\"model\">", "");
    at = cube_mesh(nest, sizeof nest, at);
    snprintf(nest + at, sizeof nest - at,
             "</object><object id=\"3\" type=\"model\"><components><component objectid=\"2\"/>"
             "</components></object></resources><build/></model>\n");
    const char *const parts[] = {"3D/Objects/box.model", box, "3D/Objects/nest.model", nest, NULL};
    const char *path = write_3mf("parts.3mf", text, true, parts);
    ur_mesh mesh = {0};
    import_ok(path, NULL, &mesh, NULL);
    assert_int_equal(mesh.triangle_count, 3 * 12);
    assert_relative(total_area(&mesh), 3 * 600, 1e-12, "three cubes");
    double low[3], high[3];
    bounding_box(&mesh, low, high);
    assert_relative(high[0] - low[0], 60, 1e-12, "the second box 50 along");
    assert_relative(high[1] - low[1], 110, 1e-12, "the nested one 100 along y");
    free_mesh(&mesh);
    /* A part or an object that is not there. */
    const char *const no_part[] = {"3D/Objects/nest.model", nest, NULL};
    expect_refusal(write_3mf("nopart.3mf", text, true, no_part), NULL,
                   "3MF part '3D/Objects/box.model': a component names it, but the archive has no "
                   "such part");
    const char *const no_object[] = {"3D/Objects/box.model", nest, "3D/Objects/nest.model", nest,
                                     NULL};
    expect_refusal(write_3mf("noobject.3mf", text, true, no_object), NULL,
                   "3MF part '3D/Objects/box.model': a component names its object 1, which it "
                   "does not have");
}

/*
 * A component that names an object not defined before it (missing, later,
 * its own): assimp 5.2 crashed on the first and looped for ever on the
 * last.  A model that is not well formed past its start.
 */
static void test_3mf_components_checked(void **state)
{
    (void)state;
    static const char model[] =
        MODEL_START "<resources>%s<object id=\"1\" type=\"model\"><components>"
                    "<component objectid=\"%d\"/></components></object>%s</resources>"
                    "<build><item objectid=\"1\"/></build></model>\n";
    char mesh[4096], before[4096], text[8192];
    size_t at = (size_t)snprintf(mesh, sizeof mesh, "<object id=\"2\" type=\"model\">");
    at = cube_mesh(mesh, sizeof mesh, at);
    snprintf(mesh + at, sizeof mesh - at, "</object>");
    snprintf(before, sizeof before, "%s", mesh);
    struct {
        const char *first, *last;
        int named;
        const char *name;
    } cases[] = {{"", "", 9, "missing.3mf"},
                 {"", mesh, 2, "later.3mf"},
                 {"", "", 1, "itself.3mf"},
                 {before, "", 2, "before.3mf"}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char unit[1] = "";
        snprintf(text, sizeof text, model, unit, cases[c].first, cases[c].named, cases[c].last);
        const char *path = write_3mf(cases[c].name, text, true, NULL);
        if (c < 3) {
            char expected[96];
            snprintf(expected, sizeof expected,
                     "a component names object %d, which is not defined "
                     "before it",
                     cases[c].named);
            expect_refusal(path, NULL, expected);
        } else {
            ur_mesh mesh_read = {0};
            import_ok(path, NULL, &mesh_read, NULL);
            assert_int_equal(mesh_read.triangle_count, 12);
            free_mesh(&mesh_read);
        }
    }
    char cut[4096];
    cube_model(cut, sizeof cut, "");
    cut[strlen(cut) - 20] = '\0'; /* the end of the model lost */
    expect_refusal(write_3mf("cut.3mf", cut, true, NULL), NULL,
                   "3MF part '3D/3dmodel.model': line");
}

/* The up axis is the writer's: glTF's by its specification, Blender's OBJ export's, else +z. */
static void test_up_axis_from_the_writer(void **state)
{
    (void)state;
    const char legacy[] = "# Blender v3.4.1 OBJ File: ''\n# www.blender.org\nv 0 0 0\n";
    const char current[] = "# Blender 4.0.2\n# www.blender.org\nmtllib x.mtl\n";
    const char plain[] = "# written by hand\nv 0 0 0\n";
    const char later[] = "v 0 0 0\n# Blender 4.0.2\n"; /* not a first comment line */
    const char stl[] = "solid Exported from Blender-3.4.1\n";
    assert_int_equal(ur_mesh_up_axis("m.obj", legacy, sizeof legacy - 1), UR_UP_Y);
    assert_int_equal(ur_mesh_up_axis("M.OBJ", current, sizeof current - 1), UR_UP_Y);
    assert_int_equal(ur_mesh_up_axis("m.obj", plain, sizeof plain - 1), UR_UP_Z);
    assert_int_equal(ur_mesh_up_axis("m.obj", later, sizeof later - 1), UR_UP_Z);
    assert_int_equal(ur_mesh_up_axis("m.obj", legacy, 5), UR_UP_Z); /* cut before the name */
    assert_int_equal(ur_mesh_up_axis("m.obj", NULL, 0), UR_UP_Z);
    assert_int_equal(ur_mesh_up_axis("m.stl", stl, sizeof stl - 1), UR_UP_Z);
    assert_int_equal(ur_mesh_up_axis("scene.gltf", NULL, 0), UR_UP_Y);
    assert_int_equal(ur_mesh_up_axis("scene.glb", NULL, 0), UR_UP_Y);
    assert_int_equal(ur_mesh_up_axis("part.ply", NULL, 0), UR_UP_Z);
    /* From a file: the project's own samples are +z up; a file Blender wrote is read. */
    assert_int_equal(ur_mesh_file_up_axis("samples/lampshade.obj"), UR_UP_Z);
    assert_int_equal(ur_mesh_file_up_axis(write_file("blender.obj", legacy)), UR_UP_Y);
    assert_int_equal(ur_mesh_file_up_axis("no/such/file.obj"), UR_UP_Z);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_format_gives_the_same_surface),
        cmocka_unit_test(test_triangles_face_outwards),
        cmocka_unit_test(test_instanced_mesh_is_copied_per_node),
        cmocka_unit_test(test_obj_groups),
        cmocka_unit_test(test_stl_solids_and_gltf_nodes_are_groups),
        cmocka_unit_test(test_unnamed_group_takes_the_file_name),
        cmocka_unit_test(test_group_named_twice_is_one_group),
        cmocka_unit_test(test_icosphere_is_closed_and_outward),
        cmocka_unit_test(test_twisted_quads_follow_the_surface),
        cmocka_unit_test(test_flat_polygons_have_no_slivers),
        cmocka_unit_test(test_concave_flat_polygon_triangulated_inside),
        cmocka_unit_test(test_face_given_twice_split_alike),
        cmocka_unit_test(test_twisted_quads_given_twice),
        cmocka_unit_test(test_unit_names),
        cmocka_unit_test(test_units_and_scale_multiply),
        cmocka_unit_test(test_collada_in_its_declared_unit),
        cmocka_unit_test(test_3mf_in_its_declared_unit),
        cmocka_unit_test(test_3mf_from_memory),
        cmocka_unit_test(test_3mf_with_a_thumbnail),
        cmocka_unit_test(test_3mf_objects_in_parts_of_their_own),
        cmocka_unit_test(test_3mf_components_checked),
        cmocka_unit_test(test_3mf_numbers_checked),
        cmocka_unit_test(test_3mf_memory_by_its_unpacked_size),
        cmocka_unit_test(test_declared_unit_refusals),
        cmocka_unit_test(test_collada_lies_refused),
        cmocka_unit_test(test_collada_instances_bounded),
        cmocka_unit_test(test_collada_instance_names_many),
        cmocka_unit_test(test_collada_decimal_comma),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_not_a_mesh),
        cmocka_unit_test(test_empty_obj),
        cmocka_unit_test(test_vertices_only),
        cmocka_unit_test(test_non_finite_coordinates),
        cmocka_unit_test(test_coordinates_beyond_1000_km),
        cmocka_unit_test(test_headers_claiming_too_much),
        cmocka_unit_test(test_ply_header_checked),
        cmocka_unit_test(test_content_checked_whatever_the_name),
        cmocka_unit_test(test_gltf_read_only_as_gltf2),
        cmocka_unit_test(test_material_library_not_read),
        cmocka_unit_test(test_bad_index_and_options),
        cmocka_unit_test(test_up_axis_from_the_writer),
    };
    return cmocka_run_group_tests(tests, make_directory, remove_directory);
}
