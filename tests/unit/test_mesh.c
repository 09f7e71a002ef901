/*
 * test_mesh.c: triangle meshes against numbers worked out by hand: counts,
 * Euler characteristics, boundary loops and areas of solids and tubes with
 * closed forms; welding a triangle soup, repairing flipped triangles and
 * refusing what cannot be repaired; cutting closed and higher-genus
 * meshes into disks; triangulating ruled surfaces.  The edge and loop
 * counts that check the pieces are computed here, independently of the
 * library.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/mesh.h"

#define assert_relative(actual, expected, tolerance)                                               \
    do {                                                                                           \
        double a_ = (actual), e_ = (expected);                                                     \
        if (!(fabs(a_ - e_) <= (tolerance)*fabs(e_)))                                              \
            fail_msg("%s = %.15g, expected %.15g within %g", #actual, a_, e_,                      \
                     (double)(tolerance));                                                         \
    } while (0)

#define assert_message(error, text)                                                                \
    do {                                                                                           \
        if (!strstr((error).message, (text)))                                                      \
            fail_msg("message \"%s\" does not say \"%s\"", (error).message, (text));               \
    } while (0)

/* ---- building meshes ---- */

typedef struct builder {
    ur_vec3 *vertices;
    size_t vertex_count, vertex_capacity;
    size_t (*triangles)[3];
    size_t *groups;
    size_t triangle_count, triangle_capacity;
} builder;

static size_t add_vertex(builder *b, double x, double y, double z)
{
    if (b->vertex_count == b->vertex_capacity) {
        b->vertex_capacity = b->vertex_capacity ? 2 * b->vertex_capacity : 64;
        b->vertices = realloc(b->vertices, b->vertex_capacity * sizeof *b->vertices);
        assert_non_null(b->vertices);
    }
    b->vertices[b->vertex_count] = ur_vec3_make(x, y, z);
    return b->vertex_count++;
}

static void add_triangle(builder *b, size_t v0, size_t v1, size_t v2, size_t group)
{
    if (b->triangle_count == b->triangle_capacity) {
        b->triangle_capacity = b->triangle_capacity ? 2 * b->triangle_capacity : 64;
        b->triangles = realloc(b->triangles, b->triangle_capacity * sizeof *b->triangles);
        b->groups = realloc(b->groups, b->triangle_capacity * sizeof *b->groups);
        assert_non_null(b->triangles);
        assert_non_null(b->groups);
    }
    size_t t = b->triangle_count++;
    b->triangles[t][0] = v0;
    b->triangles[t][1] = v1;
    b->triangles[t][2] = v2;
    b->groups[t] = group;
}

/* The mesh of what b holds (b is emptied). */
static ur_mesh build(builder *b)
{
    ur_mesh mesh;
    ur_error error;
    if (ur_mesh_new(b->vertices, b->vertex_count, (const size_t(*)[3])b->triangles,
                    b->triangle_count, b->groups, &mesh, &error) != UR_OK)
        fail_msg("ur_mesh_new: %s", error.message);
    free(b->vertices);
    free(b->triangles);
    free(b->groups);
    memset(b, 0, sizeof *b);
    return mesh;
}

/* Adds a mesh's vertices and triangles (group 0) to b; the number its first vertex gets. */
static size_t add_mesh(builder *b, const ur_mesh *m)
{
    size_t base = b->vertex_count;
    for (size_t v = 0; v < m->vertex_count; v++)
        add_vertex(b, m->vertices[v].x, m->vertices[v].y, m->vertices[v].z);
    for (size_t t = 0; t < m->triangle_count; t++)
        add_triangle(b, base + m->triangles[t][0], base + m->triangles[t][1],
                     base + m->triangles[t][2], 0);
    return base;
}

/* A k x k grid of unit squares in z = 0, counter-clockwise seen from +z; columns >= split in
 * group 1. */
static ur_mesh grid(size_t k, size_t split)
{
    builder b = {0};
    for (size_t j = 0; j <= k; j++)
        for (size_t i = 0; i <= k; i++)
            add_vertex(&b, (double)i, (double)j, 0);
    for (size_t j = 0; j < k; j++)
        for (size_t i = 0; i < k; i++) {
            size_t p00 = j * (k + 1) + i, p10 = p00 + 1, p01 = p00 + k + 1, p11 = p01 + 1;
            size_t group = i < split ? 0 : 1;
            add_triangle(&b, p00, p10, p11, group);
            add_triangle(&b, p00, p11, p01, group);
        }
    return build(&b);
}

/* An open tube: n points round, m bands high, normals outward. */
static ur_mesh tube(size_t n, size_t m, double radius, double height)
{
    builder b = {0};
    for (size_t j = 0; j <= m; j++)
        for (size_t i = 0; i < n; i++) {
            double t = 2 * M_PI * (double)i / (double)n;
            add_vertex(&b, radius * cos(t), radius * sin(t), height * (double)j / (double)m);
        }
    for (size_t j = 0; j < m; j++)
        for (size_t i = 0; i < n; i++) {
            size_t p00 = j * n + i, p10 = j * n + (i + 1) % n;
            size_t p01 = p00 + n, p11 = p10 + n;
            add_triangle(&b, p00, p10, p11, 0);
            add_triangle(&b, p00, p11, p01, 0);
        }
    return build(&b);
}

/* A torus: n quads round the axis, m round the tube; the half theta >= pi in group `half`. */
static ur_mesh torus(size_t n, size_t m, double big, double small, size_t half)
{
    builder b = {0};
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < m; j++) {
            double theta = 2 * M_PI * (double)i / (double)n, phi = 2 * M_PI * (double)j / (double)m;
            double rho = big + small * cos(phi);
            add_vertex(&b, rho * cos(theta), rho * sin(theta), small * sin(phi));
        }
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < m; j++) {
            size_t p00 = i * m + j, p10 = (i + 1) % n * m + j;
            size_t p01 = i * m + (j + 1) % m, p11 = (i + 1) % n * m + (j + 1) % m;
            size_t group = 2 * i >= n ? half : 0;
            add_triangle(&b, p00, p10, p11, group);
            add_triangle(&b, p00, p11, p01, group);
        }
    return build(&b);
}

/* A unit UV sphere: two poles and m - 1 rings of n points, normals outward. */
static ur_mesh uv_sphere(size_t n, size_t m)
{
    builder b = {0};
    size_t north = add_vertex(&b, 0, 0, 1), south = add_vertex(&b, 0, 0, -1);
    for (size_t j = 1; j < m; j++)
        for (size_t i = 0; i < n; i++) {
            double alpha = M_PI * (double)j / (double)m, theta = 2 * M_PI * (double)i / (double)n;
            add_vertex(&b, sin(alpha) * cos(theta), sin(alpha) * sin(theta), cos(alpha));
        }
    for (size_t i = 0; i < n; i++) {
        size_t next = (i + 1) % n;
        add_triangle(&b, north, 2 + i, 2 + next, 0);
        size_t last = 2 + (m - 2) * n;
        add_triangle(&b, south, last + next, last + i, 0);
        for (size_t j = 1; j + 1 < m; j++) {
            size_t up = 2 + (j - 1) * n, down = up + n;
            add_triangle(&b, up + i, down + i, down + next, 0);
            add_triangle(&b, up + i, down + next, up + next, 0);
        }
    }
    return build(&b);
}

/*
 * The convex solid with these vertices (centred on the origin) whose faces
 * are the triangles of three vertices `edge` apart, each turned outward.
 */
static ur_mesh solid(const double (*points)[3], size_t count, double edge)
{
    builder b = {0};
    for (size_t i = 0; i < count; i++)
        add_vertex(&b, points[i][0], points[i][1], points[i][2]);
    for (size_t i = 0; i < count; i++)
        for (size_t j = i + 1; j < count; j++)
            for (size_t k = j + 1; k < count; k++) {
                ur_vec3 p = b.vertices[i], q = b.vertices[j], r = b.vertices[k];
                if (fabs(ur_vec3_distance(p, q) - edge) > 1e-9 ||
                    fabs(ur_vec3_distance(q, r) - edge) > 1e-9 ||
                    fabs(ur_vec3_distance(r, p) - edge) > 1e-9)
                    continue;
                if (ur_vec3_det(p, q, r) > 0)
                    add_triangle(&b, i, j, k, 0);
                else
                    add_triangle(&b, i, k, j, 0);
            }
    return build(&b);
}

static ur_mesh tetrahedron(void)
{
    static const double points[][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    return solid(points, 4, 2 * sqrt(2.0));
}

static ur_mesh octahedron(void)
{
    static const double points[][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                       {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    return solid(points, 6, sqrt(2.0));
}

#define PHI 1.6180339887498948482

/* Edge 2: (0, +-1, +-phi) and its cyclic permutations. */
static ur_mesh icosahedron(void)
{
    double points[12][3];
    size_t n = 0;
    for (int s = -1; s <= 1; s += 2)
        for (int t = -1; t <= 1; t += 2) {
            double a = s, c = t * PHI;
            double rows[3][3] = {{0, a, c}, {a, c, 0}, {c, 0, a}};
            for (int r = 0; r < 3; r++, n++)
                memcpy(points[n], rows[r], sizeof rows[r]);
        }
    return solid((const double(*)[3])points, 12, 2);
}

/* ---- measuring meshes, independently of the library ---- */

static double signed_volume(const ur_mesh *mesh)
{
    double volume = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const size_t *c = mesh->triangles[t];
        volume += ur_vec3_det(mesh->vertices[c[0]], mesh->vertices[c[1]], mesh->vertices[c[2]]);
    }
    return volume / 6;
}

typedef struct directed {
    size_t low, high, from, to;
} directed;

static int compare_directed(const void *a, const void *b)
{
    const directed *x = a, *y = b;
    if (x->low != y->low)
        return x->low < y->low ? -1 : 1;
    return (x->high > y->high) - (x->high < y->high);
}

static int compare_from(const void *a, const void *b)
{
    const directed *x = a, *y = b;
    return (x->from > y->from) - (x->from < y->from);
}

/* Edges, boundary edges and boundary loops, by sorting every edge of every triangle. */
typedef struct topology {
    size_t vertices, edges, boundary_edges, loops;
    long long euler;
    double boundary_length;
} topology;

static size_t count_loops(directed *boundary, size_t count)
{
    qsort(boundary, count, sizeof *boundary, compare_from);
    bool *seen = calloc(count + 1, sizeof *seen);
    assert_non_null(seen);
    size_t loops = 0;
    for (size_t i = 0; i < count; i++) {
        if (seen[i])
            continue;
        loops++;
        for (size_t k = i; !seen[k];) {
            seen[k] = true;
            directed key = {0, 0, boundary[k].to, 0};
            directed *next = bsearch(&key, boundary, count, sizeof *boundary, compare_from);
            if (!next) /* the boundary of a one-sided strip runs both ways */
                break;
            k = (size_t)(next - boundary);
        }
    }
    free(seen);
    return loops;
}

static topology topology_of(const ur_mesh *mesh)
{
    size_t n = 3 * mesh->triangle_count;
    directed *edges = malloc(n * sizeof *edges), *boundary = malloc(n * sizeof *boundary);
    bool *used = calloc(mesh->vertex_count, sizeof *used);
    assert_true(edges && boundary && used);
    topology top = {0};
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            size_t a = mesh->triangles[t][k], b = mesh->triangles[t][(k + 1) % 3];
            edges[3 * t + k] = (directed){a < b ? a : b, a < b ? b : a, a, b};
            top.vertices += !used[a];
            used[a] = true;
        }
    qsort(edges, n, sizeof *edges, compare_directed);
    for (size_t i = 0, j; i < n; i = j) {
        for (j = i + 1; j < n && compare_directed(&edges[i], &edges[j]) == 0; j++)
            ;
        top.edges++;
        if (j - i == 1) {
            boundary[top.boundary_edges++] = edges[i];
            top.boundary_length +=
                ur_vec3_distance(mesh->vertices[edges[i].low], mesh->vertices[edges[i].high]);
        }
    }
    top.loops = count_loops(boundary, top.boundary_edges);
    top.euler = (long long)top.vertices - (long long)top.edges + (long long)mesh->triangle_count;
    free(edges);
    free(boundary);
    free(used);
    return top;
}

/* Every piece a disk, its triangles and vertices the mesh's own, nothing lost or doubled. */
static void check_pieces(const ur_mesh *mesh, const ur_mesh_piece *pieces, size_t count)
{
    size_t *uses = calloc(mesh->triangle_count, sizeof *uses);
    assert_non_null(uses);
    double area = 0;
    for (size_t p = 0; p < count; p++) {
        const ur_mesh *piece = &pieces[p].mesh;
        for (size_t i = 0; i < piece->triangle_count; i++) {
            size_t t = pieces[p].source_triangles[i];
            assert_true(t < mesh->triangle_count);
            uses[t]++;
            for (int k = 0; k < 3; k++) {
                size_t v = piece->triangles[i][k];
                assert_int_equal(pieces[p].original[v], mesh->triangles[t][k]);
                assert_memory_equal(&piece->vertices[v], &mesh->vertices[mesh->triangles[t][k]],
                                    sizeof(ur_vec3));
            }
        }
        topology top = topology_of(piece);
        assert_int_equal(top.vertices, piece->vertex_count);
        assert_int_equal(top.euler, 1);
        assert_int_equal(top.loops, 1);
        size_t *loop, length;
        ur_error error;
        if (ur_mesh_boundary(piece, &loop, &length, &error) != UR_OK)
            fail_msg("piece %zu: %s", p, error.message);
        assert_int_equal(length, top.boundary_edges);
        free(loop);
        area += ur_mesh_area(piece);
    }
    for (size_t t = 0; t < mesh->triangle_count; t++)
        assert_int_equal(uses[t], 1);
    free(uses);
    assert_relative(area, ur_mesh_area(mesh), 1e-12);
}

static ur_mesh_piece *cut(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                          size_t *count)
{
    ur_mesh_piece *pieces;
    ur_error error;
    if (ur_mesh_pieces(mesh, seams, seam_count, &pieces, count, &error) != UR_OK)
        fail_msg("ur_mesh_pieces: %s", error.message);
    check_pieces(mesh, pieces, *count);
    return pieces;
}

static ur_mesh_repairs clean(ur_mesh *mesh, double tolerance)
{
    ur_mesh_repairs repairs;
    ur_error error;
    if (ur_mesh_clean(mesh, tolerance, &repairs, &error) != UR_OK)
        fail_msg("ur_mesh_clean: %s", error.message);
    return repairs;
}

/* ---- ur_mesh_new, ur_mesh_area ---- */

static void test_new(void **state)
{
    (void)state;
    ur_vec3 vertices[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    size_t triangles[2][3] = {{0, 1, 3}, {0, 3, 2}};
    ur_mesh mesh;
    assert_int_equal(ur_mesh_new(vertices, 4, (const size_t(*)[3])triangles, 2, NULL, &mesh, NULL),
                     UR_OK);
    /* Copies: changing the input afterwards does not change the mesh. */
    vertices[1].x = 7;
    triangles[1][2] = 1;
    assert_int_equal(mesh.vertex_count, 4);
    assert_int_equal(mesh.triangle_count, 2);
    assert_true(mesh.vertices[1].x == 1);
    assert_int_equal(mesh.triangles[1][2], 2);
    assert_int_equal(mesh.groups[0], 0);
    assert_int_equal(mesh.groups[1], 0);
    assert_int_equal(mesh.group_count, 1);
    assert_relative(ur_mesh_area(&mesh), 1.0, 1e-15);
    ur_mesh_free(&mesh);
    assert_null(mesh.vertices);

    size_t groups[2] = {3, 1};
    assert_int_equal(
        ur_mesh_new(vertices, 4, (const size_t(*)[3])triangles, 2, groups, &mesh, NULL), UR_OK);
    assert_int_equal(mesh.group_count, 4);
    assert_int_equal(mesh.groups[0], 3);
    ur_mesh_free(&mesh);
}

static void test_new_refuses(void **state)
{
    (void)state;
    ur_vec3 vertices[3] = {{0, 0, 0}, {NAN, 0, 0}, {0, 1, 0}};
    size_t triangles[2][3] = {{0, 1, 2}, {0, 2, 7}};
    ur_mesh mesh;
    ur_error error;
    assert_int_equal(
        ur_mesh_new(vertices, 3, (const size_t(*)[3])triangles, 1, NULL, &mesh, &error),
        UR_ERROR_INPUT);
    assert_message(error, "vertex 2 ");
    assert_null(mesh.vertices);
    vertices[1].x = 1;
    vertices[2].z = -INFINITY;
    assert_int_equal(
        ur_mesh_new(vertices, 3, (const size_t(*)[3])triangles, 1, NULL, &mesh, &error),
        UR_ERROR_INPUT);
    assert_message(error, "vertex 3 ");
    vertices[2].z = 0;
    assert_int_equal(
        ur_mesh_new(vertices, 3, (const size_t(*)[3])triangles, 2, NULL, &mesh, &error),
        UR_ERROR_INPUT);
    assert_message(error, "triangle 2 uses vertex 8, but the mesh has 3 vertices");
}

static void test_area(void **state)
{
    (void)state;
    /* Regular solids: tetrahedron of edge 2 sqrt 2 (area sqrt 3 a^2 = 8 sqrt 3),
       octahedron of edge sqrt 2 (2 sqrt 3 a^2 = 4 sqrt 3), icosahedron of edge 2
       (5 sqrt 3 a^2 = 20 sqrt 3). */
    ur_mesh mesh = tetrahedron();
    assert_int_equal(mesh.triangle_count, 4);
    assert_relative(ur_mesh_area(&mesh), 8 * sqrt(3.0), 1e-14);
    ur_mesh_free(&mesh);
    mesh = octahedron();
    assert_int_equal(mesh.triangle_count, 8);
    assert_relative(ur_mesh_area(&mesh), 4 * sqrt(3.0), 1e-14);
    ur_mesh_free(&mesh);
    mesh = icosahedron();
    assert_int_equal(mesh.triangle_count, 20);
    assert_relative(ur_mesh_area(&mesh), 20 * sqrt(3.0), 1e-14);
    ur_mesh_free(&mesh);
    /* A tube of n flat rectangles: n 2 r sin(pi / n) h, which tends to 2 pi r h. */
    double r = 10, h = 5;
    size_t n = 2000;
    mesh = tube(n, 3, r, h);
    assert_relative(ur_mesh_area(&mesh), (double)n * 2 * r * sin(M_PI / (double)n) * h, 1e-12);
    assert_relative(ur_mesh_area(&mesh), 2 * M_PI * r * h, 1e-6);
    ur_mesh_free(&mesh);
}

/* ---- ur_mesh_twins ---- */

static void test_twins(void **state)
{
    (void)state;
    ur_vec3 vertices[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}};
    size_t triangles[3][3] = {{0, 1, 2}, {2, 1, 3}, {1, 0, 4}};
    ur_mesh mesh;
    assert_int_equal(ur_mesh_new(vertices, 5, (const size_t(*)[3])triangles, 2, NULL, &mesh, NULL),
                     UR_OK);
    size_t *twins;
    assert_int_equal(ur_mesh_twins(&mesh, &twins, NULL), UR_OK);
    /* Edge 1-2 is half-edge 1 of triangle 0 (1 -> 2) and 0 of triangle 1 (2 -> 1). */
    size_t expected[6] = {UR_NO_EDGE, 3, UR_NO_EDGE, 1, UR_NO_EDGE, UR_NO_EDGE};
    assert_memory_equal(twins, expected, sizeof expected);
    free(twins);
    ur_mesh_free(&mesh);

    /* A third triangle on edge 0-1 (two of them 0 -> 1 is no matter here). */
    size_t fan[3][3] = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    assert_int_equal(ur_mesh_new(vertices, 5, (const size_t(*)[3])fan, 3, NULL, &mesh, NULL),
                     UR_OK);
    ur_error error;
    assert_int_equal(ur_mesh_twins(&mesh, &twins, &error), UR_ERROR_INPUT);
    assert_null(twins);
    assert_message(error, "non-manifold edge between vertices 1 and 2 (3 triangles)");
    ur_mesh_free(&mesh);
}

/* ---- ur_mesh_clean ---- */

/*
 * The 12 triangles of the cube [0, 2]^3 as a soup: 36 vertices, each moved
 * by up to jitter / 2 along each axis; outward but for flipped_one, or all
 * inward.
 */
static ur_mesh cube_soup(bool inward, size_t flipped_one, double jitter)
{
    static const int faces[6][4][3] = {
        {{0, 0, 0}, {0, 2, 0}, {2, 2, 0}, {2, 0, 0}}, {{0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}},
        {{0, 0, 0}, {2, 0, 0}, {2, 0, 2}, {0, 0, 2}}, {{0, 2, 0}, {0, 2, 2}, {2, 2, 2}, {2, 2, 0}},
        {{0, 0, 0}, {0, 0, 2}, {0, 2, 2}, {0, 2, 0}}, {{2, 0, 0}, {2, 2, 0}, {2, 2, 2}, {2, 0, 2}},
    };
    builder b = {0};
    unsigned seed = 12345;
    for (int f = 0; f < 6; f++)
        for (int half = 0; half < 2; half++) {
            int corners[3] = {0, half ? 2 : 1, half ? 3 : 2};
            size_t v[3];
            for (int k = 0; k < 3; k++) {
                double p[3];
                for (int d = 0; d < 3; d++) {
                    seed = seed * 1103515245u + 12345u;
                    double unit = (double)(seed >> 16 & 0x7fff) / 32767 - 0.5;
                    p[d] = faces[f][corners[k]][d] + jitter * unit;
                }
                v[k] = add_vertex(&b, p[0], p[1], p[2]);
            }
            bool turn = inward != (b.triangle_count == flipped_one);
            if (turn)
                add_triangle(&b, v[0], v[2], v[1], 0);
            else
                add_triangle(&b, v[0], v[1], v[2], 0);
        }
    return build(&b);
}

static void test_clean_welds_soup(void **state)
{
    (void)state;
    ur_mesh mesh = cube_soup(false, SIZE_MAX, 1e-6);
    assert_int_equal(mesh.vertex_count, 36);
    assert_relative(signed_volume(&mesh), 8, 1e-5);
    ur_mesh_repairs repairs = clean(&mesh, 1e-4);
    assert_int_equal(mesh.vertex_count, 8);
    assert_int_equal(mesh.triangle_count, 12);
    assert_int_equal(repairs.welded, 28);
    assert_int_equal(repairs.degenerate, 0);
    assert_int_equal(repairs.isolated, 0);
    assert_int_equal(repairs.flipped, 0);
    assert_relative(ur_mesh_area(&mesh), 24, 1e-5);
    assert_relative(signed_volume(&mesh), 8, 1e-5);
    topology top = topology_of(&mesh);
    assert_int_equal(top.edges, 18);
    assert_int_equal(top.boundary_edges, 0);
    assert_int_equal(top.euler, 2);
    ur_mesh_free(&mesh);

    /* Too small a tolerance welds nothing; 0 welds only identical points. */
    mesh = cube_soup(false, SIZE_MAX, 1e-6);
    repairs = clean(&mesh, 1e-9);
    assert_int_equal(repairs.welded, 0);
    assert_int_equal(mesh.vertex_count, 36);
    ur_mesh_free(&mesh);
    mesh = cube_soup(false, SIZE_MAX, 0);
    repairs = clean(&mesh, 0);
    assert_int_equal(repairs.welded, 28);
    assert_int_equal(mesh.vertex_count, 8);
    ur_mesh_free(&mesh);
}

static void test_clean_orients(void **state)
{
    (void)state;
    /* One triangle of the soup turned inward: repaired, counted. */
    ur_mesh mesh = cube_soup(false, 7, 1e-6);
    /* Triangle 7 lies in y = 2 (area 2): it counted 2 * 2 / 3, now against. */
    assert_relative(signed_volume(&mesh), 8 - 8.0 / 3, 1e-5);
    ur_mesh_repairs repairs = clean(&mesh, 1e-4);
    assert_int_equal(repairs.flipped, 1);
    assert_relative(signed_volume(&mesh), 8, 1e-5);
    ur_mesh_free(&mesh);
    /* All inward: a closed part is turned outward, all 12. */
    mesh = cube_soup(true, SIZE_MAX, 1e-6);
    assert_relative(signed_volume(&mesh), -8, 1e-5);
    repairs = clean(&mesh, 1e-4);
    assert_int_equal(repairs.flipped, 12);
    assert_relative(signed_volume(&mesh), 8, 1e-5);
    ur_mesh_free(&mesh);
    /* Closed: outward even when most faces were inward (5 of the octahedron's 8). */
    mesh = octahedron();
    for (size_t t = 0; t < 5; t++) {
        size_t corner = mesh.triangles[t][1];
        mesh.triangles[t][1] = mesh.triangles[t][2];
        mesh.triangles[t][2] = corner;
    }
    repairs = clean(&mesh, 0);
    assert_int_equal(repairs.flipped, 5);
    assert_int_equal(repairs.welded, 0);
    assert_relative(signed_volume(&mesh), 4.0 / 3, 1e-14);
    ur_mesh_free(&mesh);
    /* Open: the way most triangles run.  Triangle 6 of a 3 x 3 grid turned down. */
    mesh = grid(3, 3);
    size_t corner = mesh.triangles[6][1];
    mesh.triangles[6][1] = mesh.triangles[6][2];
    mesh.triangles[6][2] = corner;
    repairs = clean(&mesh, 1e-6);
    assert_int_equal(repairs.flipped, 1);
    for (size_t t = 0; t < mesh.triangle_count; t++) {
        const size_t *c = mesh.triangles[t];
        ur_vec3 normal = ur_vec3_cross(ur_vec3_sub(mesh.vertices[c[1]], mesh.vertices[c[0]]),
                                       ur_vec3_sub(mesh.vertices[c[2]], mesh.vertices[c[0]]));
        assert_true(normal.z > 0);
    }
    ur_mesh_free(&mesh);
}

static void test_clean_drops(void **state)
{
    (void)state;
    ur_mesh base = grid(2, 2); /* 9 vertices, 8 triangles */
    builder b = {0};
    add_mesh(&b, &base);
    ur_mesh_free(&base);
    /* Vertex 9 on edge 0-1: triangle 0 9 1 has no area, and 9 is then unused. */
    add_vertex(&b, 0.5, 0, 0);
    add_triangle(&b, 0, 9, 1, 0);
    /* Vertices 10-12 weld into one point: their triangle goes, and the point. */
    add_vertex(&b, 5, 5, 0);
    add_vertex(&b, 5, 5, 1e-9);
    add_vertex(&b, 5 + 1e-9, 5, 0);
    add_triangle(&b, 10, 11, 12, 0);
    /* Vertex 13 no triangle uses; vertex 14 welds into vertex 4 (1, 1, 0). */
    add_vertex(&b, 7, 7, 7);
    add_vertex(&b, 1, 1, 1e-8);
    ur_mesh mesh = build(&b);
    ur_mesh_repairs repairs;
    size_t *map;
    ur_error error;
    if (ur_mesh_clean_map(&mesh, 1e-6, &repairs, &map, &error) != UR_OK)
        fail_msg("%s", error.message);
    assert_int_equal(repairs.welded, 3);
    assert_int_equal(repairs.degenerate, 2);
    assert_int_equal(repairs.isolated, 3);
    assert_int_equal(repairs.flipped, 0);
    assert_int_equal(mesh.vertex_count, 9);
    assert_int_equal(mesh.triangle_count, 8);
    for (size_t v = 0; v < 9; v++)
        assert_int_equal(map[v], v);
    for (size_t v = 9; v < 14; v++)
        assert_int_equal(map[v], UR_NO_VERTEX);
    assert_int_equal(map[14], 4);
    free(map);
    assert_relative(ur_mesh_area(&mesh), 4, 1e-15);
    ur_mesh_free(&mesh);
}

/* A triangle (0-based corners) added to a 2 x 2 grid with an unused vertex 0 in front. */
static ur_mesh grid_with_extra(size_t a, size_t b2, size_t c, double extra_z)
{
    ur_mesh base = grid(2, 2);
    builder b = {0};
    add_vertex(&b, -5, -5, -5);
    add_mesh(&b, &base);
    ur_mesh_free(&base);
    size_t top = add_vertex(&b, 0.5, 0.5, extra_z);
    add_triangle(&b, a, b2, c == SIZE_MAX ? top : c, 0);
    return build(&b);
}

/*
 * An octahedron with a flap on one edge: two triangles back to back on the
 * edge's ends and a point off the surface, as Blender's monkey head has
 * under its chin.  The pair goes, the point with it, and the octahedron
 * is left whole (every edge on two triangles, Euler characteristic 2).
 * Without the flap dropped the edge carries four triangles, and taking
 * the surfaces apart there left the flap a closed surface of its own.  So
 * too when all of it is given twice (a modeller's copy in place): the
 * copies go first, and the flap is found among what is left.
 */
static void test_clean_drops_flaps(void **state)
{
    (void)state;
    for (int variant = 0; variant < 3; variant++) {
        bool turned = variant == 1, doubled = variant == 2;
        ur_mesh base = octahedron();
        builder b = {0};
        add_mesh(&b, &base);
        size_t foot_a = base.triangles[3][0], foot_b = base.triangles[3][1];
        size_t tip = add_vertex(&b, 2, 2, 2);
        /* the flap, each way round first */
        add_triangle(&b, turned ? foot_b : foot_a, turned ? foot_a : foot_b, tip, 0);
        add_triangle(&b, turned ? foot_a : foot_b, turned ? foot_b : foot_a, tip, 0);
        ur_mesh_free(&base);
        if (doubled) { /* all of it given twice, the same way round: the copies go, then the flap */
            ur_mesh once = build(&b);
            add_mesh(&b, &once);
            add_mesh(&b, &once);
            ur_mesh_free(&once);
        }
        ur_mesh mesh = build(&b);
        ur_mesh_repairs repairs = clean(&mesh, 1e-6);
        assert_int_equal(repairs.duplicates, doubled ? 10 : 0);
        assert_int_equal(repairs.flaps, 1);
        assert_int_equal(repairs.split, 0);
        assert_int_equal(repairs.isolated, 1); /* the tip */
        assert_int_equal(mesh.triangle_count, 8);
        assert_int_equal(mesh.vertex_count, 6);
        size_t *twins;
        ur_error error;
        assert_int_equal(ur_mesh_twins(&mesh, &twins, &error), UR_OK);
        for (size_t h = 0; h < 24; h++)
            assert_int_not_equal(twins[h], UR_NO_EDGE);
        free(twins);
        ur_mesh_free(&mesh);
    }
}

/*
 * A face given twice: one triangle of an octahedron added again, the same
 * way round or the other way (every edge of it then on three triangles);
 * the whole octahedron added again over itself with vertices of its own
 * (welded onto the first); and seven of its eight triangles added again
 * the other way round, where the copy of the triangle opposite the eighth
 * has every edge on four triangles until the copies round it go.  The
 * copies are in group 1.  Each goes, the first of each in the input stays
 * (group 0), and the octahedron is whole and closed again: 8 triangles,
 * every edge on two, Euler characteristic 2.  The build before the repair
 * refused the first two ("non-manifold edge").
 */
static void test_clean_drops_faces_given_twice(void **state)
{
    (void)state;
    for (int c = 0; c < 4; c++) {
        ur_mesh base = octahedron();
        builder b = {0};
        add_mesh(&b, &base);
        const size_t *t = base.triangles[3];
        size_t copies = 1;
        if (c == 0)
            add_triangle(&b, t[0], t[1], t[2], 1);
        else if (c == 1)
            add_triangle(&b, t[0], t[2], t[1], 1);
        else if (c == 2) {
            size_t copy = add_mesh(&b, &base);
            for (size_t k = base.triangle_count; k < 2 * base.triangle_count; k++)
                b.groups[k] = 1;
            assert_int_equal(copy, base.vertex_count);
            copies = base.triangle_count;
        } else {
            for (size_t k = 1; k < base.triangle_count; k++) {
                const size_t *u = base.triangles[k];
                add_triangle(&b, u[0], u[2], u[1], 1);
            }
            copies = base.triangle_count - 1;
        }
        ur_mesh_free(&base);
        ur_mesh mesh = build(&b);
        ur_mesh_repairs repairs = clean(&mesh, 1e-6);
        assert_int_equal(repairs.duplicates, copies);
        assert_int_equal(repairs.flaps, 0);
        assert_int_equal(repairs.split, 0);
        assert_int_equal(mesh.triangle_count, 8);
        assert_int_equal(mesh.vertex_count, 6);
        for (size_t k = 0; k < mesh.triangle_count; k++)
            assert_int_equal(mesh.groups[k], 0);
        topology top = topology_of(&mesh);
        assert_int_equal(top.boundary_edges, 0);
        assert_int_equal(top.euler, 2);
        size_t *twins;
        ur_error error;
        assert_int_equal(ur_mesh_twins(&mesh, &twins, &error), UR_OK);
        free(twins);
        ur_mesh_free(&mesh);
    }
}

/*
 * A face given twice on the rim of an open surface: a triangle of a 3 x 3
 * grid with one edge on its rim, added again the other way round.  That
 * edge carries the two alone, as a flap's folds do on a sheet's rim; the
 * others carry three and four.  The copy goes, and the grid is as it was;
 * given three times (once more the same way), both copies go.  The build
 * before this case's rule refused it ("non-manifold edge").
 */
static void test_clean_drops_a_face_given_twice_on_the_rim(void **state)
{
    (void)state;
    for (int times = 2; times <= 3; times++) {
        ur_mesh base = grid(3, 3);
        size_t *twins;
        ur_error error;
        assert_int_equal(ur_mesh_twins(&base, &twins, &error), UR_OK);
        size_t rim_one = SIZE_MAX;
        for (size_t t = 0; t < base.triangle_count && rim_one == SIZE_MAX; t++) {
            int rim = 0;
            for (int k = 0; k < 3; k++)
                rim += twins[3 * t + (size_t)k] == UR_NO_EDGE;
            if (rim == 1)
                rim_one = t;
        }
        free(twins);
        assert_int_not_equal(rim_one, SIZE_MAX);
        topology before = topology_of(&base);
        builder b = {0};
        add_mesh(&b, &base);
        const size_t *t = base.triangles[rim_one];
        add_triangle(&b, t[0], t[2], t[1], 1);
        if (times == 3)
            add_triangle(&b, t[0], t[1], t[2], 1);
        size_t count = base.triangle_count;
        ur_mesh_free(&base);
        ur_mesh mesh = build(&b);
        ur_mesh_repairs repairs = clean(&mesh, 1e-6);
        assert_int_equal(repairs.duplicates, (size_t)times - 1);
        assert_int_equal(repairs.split, 0);
        assert_int_equal(mesh.triangle_count, count);
        topology after = topology_of(&mesh);
        assert_int_equal(after.boundary_edges, before.boundary_edges);
        assert_int_equal(after.euler, before.euler);
        ur_mesh_free(&mesh);
    }
}

/*
 * What is not a flap stays: a sheet modelled with a face on each side (a
 * grid and the same grid turned over: pairs side by side, and taking them
 * would take the sheet; its two sides come apart as two surfaces, as
 * before), and a pair standing on the edge of an open grid (its foot then
 * on three triangles: refused, as before).
 */
static void test_clean_keeps_what_is_no_flap(void **state)
{
    (void)state;
    ur_mesh sheet = grid(3, 3);
    builder b = {0};
    add_mesh(&b, &sheet);
    for (size_t t = 0; t < sheet.triangle_count; t++) /* the same faces turned over */
        add_triangle(&b, sheet.triangles[t][0], sheet.triangles[t][2], sheet.triangles[t][1], 0);
    size_t faces = b.triangle_count;
    ur_mesh both_sides = build(&b);
    ur_mesh_repairs repairs;
    ur_error error;
    assert_int_equal(ur_mesh_clean(&both_sides, 1e-6, &repairs, &error), UR_OK);
    assert_int_equal(repairs.flaps, 0);
    assert_int_equal(repairs.duplicates, 0);            /* no edge on an odd number of triangles */
    assert_int_equal(both_sides.triangle_count, faces); /* its sides taken apart, both kept */
    assert_true(repairs.split > 0);
    ur_mesh_free(&both_sides);

    add_mesh(&b, &sheet);
    size_t foot_a = sheet.triangles[0][0], foot_b = sheet.triangles[0][1];
    size_t tip = add_vertex(&b, 0.5, 0.5, 1);
    add_triangle(&b, foot_a, foot_b, tip, 0);
    add_triangle(&b, foot_b, foot_a, tip, 0);
    ur_mesh_free(&sheet);
    ur_mesh open = build(&b);
    assert_int_equal(ur_mesh_clean(&open, 1e-6, &repairs, &error), UR_ERROR_INPUT);
    assert_message(error, "non-manifold edge");
    ur_mesh_free(&open);
}

/*
 * Two tetrahedra, each with its own vertices, that touch along one edge
 * (two of their corners at the same places): welding alone would join
 * them by an edge of four triangles.
 */
static void test_clean_unwelds_touching_parts(void **state)
{
    (void)state;
    static const double first[][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    static const double second[][3] = {{1, 1, 1}, {1, -1, -1}, {3, 1, -1}, {3, -1, 1}};
    ur_mesh a = solid(first, 4, 2 * sqrt(2.0)), b = solid(second, 4, 2 * sqrt(2.0));
    builder both = {0};
    add_mesh(&both, &a);
    add_mesh(&both, &b);
    ur_mesh_free(&a);
    ur_mesh_free(&b);
    ur_mesh mesh = build(&both);
    ur_mesh_repairs repairs;
    ur_error error;
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, &repairs, &error), UR_OK);
    assert_int_equal(mesh.vertex_count, 8); /* the shared corners welded no more */
    assert_int_equal(mesh.triangle_count, 8);
    assert_int_equal(repairs.welded, 0);
    assert_int_equal(repairs.kept_apart, 2); /* the second tetrahedron's two touching corners */
    ur_mesh_free(&mesh);
}

/*
 * The same two tetrahedra with the touching corners given once (as an STL
 * read through assimp has them): the edge of four triangles comes apart,
 * each tetrahedron keeping a copy of its ends, and every edge then has two
 * triangles.
 */
static void test_clean_splits_surfaces_touching_along_an_edge(void **state)
{
    (void)state;
    static const double first[][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    static const double second[][3] = {{1, 1, 1}, {1, -1, -1}, {3, 1, -1}, {3, -1, 1}};
    ur_mesh a = solid(first, 4, 2 * sqrt(2.0)), b = solid(second, 4, 2 * sqrt(2.0));
    builder both = {0};
    for (size_t v = 0; v < 4; v++)
        add_vertex(&both, first[v][0], first[v][1], first[v][2]);
    for (size_t v = 2; v < 4; v++)
        add_vertex(&both, second[v][0], second[v][1], second[v][2]);
    const size_t second_index[4] = {0, 1, 4, 5};
    for (size_t t = 0; t < 4; t++) {
        add_triangle(&both, a.triangles[t][0], a.triangles[t][1], a.triangles[t][2], 0);
        add_triangle(&both, second_index[b.triangles[t][0]], second_index[b.triangles[t][1]],
                     second_index[b.triangles[t][2]], 0);
    }
    ur_mesh_free(&a);
    ur_mesh_free(&b);
    ur_mesh mesh = build(&both);
    size_t *twins;
    ur_error error;
    assert_int_equal(ur_mesh_twins(&mesh, &twins, &error), UR_ERROR_INPUT);
    assert_message(error, "(4 triangles)");
    ur_mesh_repairs repairs;
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, &repairs, &error), UR_OK);
    assert_int_equal(repairs.split, 2);
    assert_int_equal(repairs.welded, 0);
    assert_int_equal(repairs.kept_apart, 0); /* given once: nothing was welded */
    assert_int_equal(mesh.vertex_count, 8);
    assert_int_equal(mesh.triangle_count, 8);
    assert_int_equal(ur_mesh_twins(&mesh, &twins, &error), UR_OK);
    for (size_t h = 0; h < 24; h++)
        assert_int_not_equal(twins[h], UR_NO_EDGE); /* two closed surfaces */
    free(twins);
    ur_mesh_free(&mesh);
}

static void test_clean_refuses(void **state)
{
    (void)state;
    ur_error error;
    /* A third triangle on the grid's edge from (1,0) to (1,1): input vertices 3 and 6 (1-based). */
    ur_mesh mesh = grid_with_extra(2, 5, SIZE_MAX, 1);
    size_t vertex_count = mesh.vertex_count;
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, NULL, &error), UR_ERROR_INPUT);
    assert_message(error, "non-manifold edge between vertices 3 and 6 (3 triangles)");
    assert_int_equal(mesh.vertex_count, vertex_count); /* left as it was */
    assert_int_equal(mesh.triangle_count, 9);
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, NULL, NULL), UR_ERROR_INPUT); /* no error asked */
    ur_mesh_free(&mesh);

    mesh = grid(2, 2);
    mesh.vertices[4].y = NAN;
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, NULL, &error), UR_ERROR_INPUT);
    assert_message(error, "vertex 5 ");
    mesh.vertices[4].y = 1;
    assert_int_equal(ur_mesh_clean(&mesh, -1, NULL, &error), UR_ERROR_INPUT);
    assert_message(error, "tolerance");
    assert_int_equal(ur_mesh_clean(&mesh, NAN, NULL, &error), UR_ERROR_INPUT);
    /* Everything welded into one point: no triangle left. */
    assert_int_equal(ur_mesh_clean(&mesh, 10, NULL, &error), UR_ERROR_INPUT);
    assert_message(error, "no triangles left");
    assert_int_equal(mesh.triangle_count, 8);
    ur_mesh_free(&mesh);
}

/* A Moebius strip: n quads round a circle of radius 10, the ruling turning half a turn. */
static ur_mesh moebius(size_t n)
{
    builder b = {0};
    for (size_t i = 0; i < n; i++) {
        double t = 2 * M_PI * (double)i / (double)n, half = t / 2;
        ur_vec3 centre = ur_vec3_make(10 * cos(t), 10 * sin(t), 0);
        ur_vec3 across = ur_vec3_make(cos(half) * cos(t), cos(half) * sin(t), sin(half));
        ur_vec3 p = ur_vec3_add_scaled(centre, across, -2),
                q = ur_vec3_add_scaled(centre, across, 2);
        add_vertex(&b, p.x, p.y, p.z);
        add_vertex(&b, q.x, q.y, q.z);
    }
    for (size_t i = 0; i < n; i++) {
        size_t a = 2 * i, a2 = 2 * i + 1;
        /* After a whole turn the ruling has turned over: its ends swap. */
        size_t c = i + 1 < n ? 2 * (i + 1) : 1, c2 = i + 1 < n ? 2 * (i + 1) + 1 : 0;
        add_triangle(&b, a, c, c2, 0);
        add_triangle(&b, a, c2, a2, 0);
    }
    return build(&b);
}

static void test_clean_refuses_moebius(void **state)
{
    (void)state;
    ur_mesh mesh = moebius(24);
    topology top = topology_of(&mesh);
    assert_int_equal(top.euler, 0);
    assert_int_equal(top.boundary_edges, 48); /* one edge, twice round */
    ur_error error;
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, NULL, &error), UR_ERROR_INPUT);
    assert_message(error, "cannot be oriented: a Mobius strip?");
    /* Cutting refuses it as well: its triangles cannot all agree. */
    ur_mesh_piece *pieces;
    size_t count;
    assert_int_equal(ur_mesh_pieces(&mesh, NULL, 0, &pieces, &count, &error), UR_ERROR_INPUT);
    assert_message(error, "not consistently oriented");
    assert_null(pieces);
    ur_mesh_free(&mesh);
}

/*
 * A million vertices: the soup of a 409 x 409 grid, 334,562 triangles with
 * their own corners (1,003,686), welded into 410^2 = 168,100.  Not timed
 * here: the weld takes about 0.1 s in a release build.
 */
static void test_clean_million(void **state)
{
    (void)state;
    const size_t k = 409;
    builder b = {0};
    for (size_t j = 0; j < k; j++)
        for (size_t i = 0; i < k; i++) {
            double x = (double)i, y = (double)j, z = 0.01 * sin(x / 20) * cos(y / 30);
            double dx = 0.01 * sin((x + 1) / 20) * cos(y / 30);
            double dy = 0.01 * sin(x / 20) * cos((y + 1) / 30);
            double dxy = 0.01 * sin((x + 1) / 20) * cos((y + 1) / 30);
            size_t p00 = add_vertex(&b, x, y, z), p10 = add_vertex(&b, x + 1, y, dx);
            size_t p11 = add_vertex(&b, x + 1, y + 1, dxy);
            add_triangle(&b, p00, p10, p11, 0);
            p00 = add_vertex(&b, x, y, z);
            p11 = add_vertex(&b, x + 1, y + 1, dxy);
            size_t p01 = add_vertex(&b, x, y + 1, dy);
            add_triangle(&b, p00, p11, p01, 0);
        }
    ur_mesh mesh = build(&b);
    assert_int_equal(mesh.vertex_count, 1003686);
    ur_mesh_repairs repairs = clean(&mesh, 1e-3);
    assert_int_equal(mesh.vertex_count, 410 * 410);
    assert_int_equal(mesh.triangle_count, 2 * k * k);
    assert_int_equal(repairs.welded, 1003686 - 410 * 410);
    assert_int_equal(repairs.flipped, 0);
    ur_mesh_free(&mesh);
}

/* ---- ur_mesh_boundary ---- */

static void test_boundary(void **state)
{
    (void)state;
    ur_mesh mesh = grid(3, 3);
    size_t *loop, count;
    assert_int_equal(ur_mesh_boundary(&mesh, &loop, &count, NULL), UR_OK);
    assert_int_equal(count, 12);
    /* The way the triangles run: counter-clockwise seen from +z, enclosing 9. */
    double area = 0;
    for (size_t i = 0; i < count; i++) {
        ur_vec3 p = mesh.vertices[loop[i]], q = mesh.vertices[loop[(i + 1) % count]];
        area += 0.5 * (p.x * q.y - q.x * p.y);
        assert_relative(ur_vec3_distance(p, q), 1, 1e-15);
    }
    assert_relative(area, 9, 1e-15);
    free(loop);
    ur_mesh_free(&mesh);

    ur_error error;
    mesh = tetrahedron();
    assert_int_equal(ur_mesh_boundary(&mesh, &loop, &count, &error), UR_ERROR_INPUT);
    assert_message(error, "closed");
    assert_null(loop);
    ur_mesh_free(&mesh);
    mesh = tube(8, 2, 1, 1);
    assert_int_equal(ur_mesh_boundary(&mesh, &loop, &count, &error), UR_ERROR_INPUT);
    assert_message(error, "2 boundary loops");
    ur_mesh_free(&mesh);
}

/* ---- ur_mesh_pieces ---- */

static void test_pieces_disk(void **state)
{
    (void)state;
    ur_mesh mesh = grid(4, 4);
    size_t count;
    ur_mesh_piece *pieces = cut(&mesh, NULL, 0, &count);
    assert_int_equal(count, 1);
    assert_int_equal(pieces[0].mesh.vertex_count, 25); /* nothing cut */
    assert_int_equal(pieces[0].mesh.triangle_count, 32);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&mesh);
}

static void test_pieces_groups(void **state)
{
    (void)state;
    /* Columns 0-1 and 2-3 of a 4 x 4 grid: two 2 x 4 halves sharing 5 vertices. */
    ur_mesh mesh = grid(4, 2);
    assert_int_equal(mesh.group_count, 2);
    size_t count;
    ur_mesh_piece *pieces = cut(&mesh, NULL, 0, &count);
    assert_int_equal(count, 2);
    for (size_t p = 0; p < 2; p++) {
        assert_int_equal(pieces[p].mesh.vertex_count, 15);
        assert_int_equal(pieces[p].mesh.triangle_count, 16);
        assert_int_equal(pieces[p].mesh.groups[0], p);
        assert_relative(ur_mesh_area(&pieces[p].mesh), 8, 1e-15);
    }
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&mesh);

    /* A torus in two groups: two tubes, each cut open along one path. */
    mesh = torus(16, 8, 10, 3, 1);
    pieces = cut(&mesh, NULL, 0, &count);
    assert_int_equal(count, 2);
    assert_int_equal(pieces[0].mesh.triangle_count, 128);
    assert_int_equal(pieces[1].mesh.triangle_count, 128);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&mesh);
}

static void test_pieces_user_seams(void **state)
{
    (void)state;
    /* A tube (annulus, chi 0) with a seam up one side is a disk without further cuts. */
    const size_t n = 12, m = 4;
    ur_mesh mesh = tube(n, m, 5, 8);
    topology top = topology_of(&mesh);
    assert_int_equal(top.euler, 0);
    assert_int_equal(top.loops, 2);
    ur_seam seams[4];
    for (size_t j = 0; j < m; j++)
        seams[j] = (ur_seam){j * n, (j + 1) * n};
    size_t count;
    ur_mesh_piece *pieces = cut(&mesh, seams, m, &count);
    assert_int_equal(count, 1);
    assert_int_equal(pieces[0].mesh.vertex_count, n * (m + 1) + m + 1);
    size_t *loop, length;
    assert_int_equal(ur_mesh_boundary(&pieces[0].mesh, &loop, &length, NULL), UR_OK);
    assert_int_equal(length, 2 * n + 2 * m);
    free(loop);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&mesh);

    /* A seam right across a 4 x 4 grid, along x = 2: two halves. */
    mesh = grid(4, 4);
    for (size_t j = 0; j < 4; j++)
        seams[j] = (ur_seam){j * 5 + 2, (j + 1) * 5 + 2};
    pieces = cut(&mesh, seams, 4, &count);
    assert_int_equal(count, 2);
    assert_int_equal(pieces[0].mesh.vertex_count + pieces[1].mesh.vertex_count, 30);
    ur_mesh_pieces_free(pieces, count);
    /* One edge inside (a slit from (2,1) to (2,2)), given twice: still one disk. */
    ur_seam slit[2] = {{7, 12}, {12, 7}};
    pieces = cut(&mesh, slit, 2, &count);
    assert_int_equal(count, 1);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&mesh);
    /* One edge of a closed octahedron: a disk too. */
    mesh = octahedron();
    ur_seam edge = {mesh.triangles[0][0], mesh.triangles[0][1]};
    pieces = cut(&mesh, &edge, 1, &count);
    assert_int_equal(count, 1);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&mesh);
}

static void test_pieces_refuses_seams(void **state)
{
    (void)state;
    ur_mesh mesh = grid(2, 2);
    ur_mesh_piece *pieces;
    size_t count;
    ur_error error;
    ur_seam seams[2] = {{0, 1}, {0, 8}};
    assert_int_equal(ur_mesh_pieces(&mesh, seams, 2, &pieces, &count, &error), UR_ERROR_INPUT);
    assert_message(error, "seam 2 (vertices 1 and 9) is not an edge of the mesh");
    assert_null(pieces);
    assert_int_equal(count, 0);
    seams[1] = (ur_seam){3, 9};
    assert_int_equal(ur_mesh_pieces(&mesh, seams, 2, &pieces, &count, &error), UR_ERROR_INPUT);
    assert_message(error, "seam 2 names vertex 10, but the mesh has 9 vertices");
    seams[0] = (ur_seam){4, 4};
    assert_int_equal(ur_mesh_pieces(&mesh, seams, 1, &pieces, &count, &error), UR_ERROR_INPUT);
    assert_message(error, "seam 1 joins vertex 5 to itself");
    ur_mesh_free(&mesh);
}

/*
 * A closed or higher-genus mesh: one piece, a disk (check_pieces), the same
 * triangles; its boundary as long as expected unless that is NAN.
 */
static void check_one_disk(ur_mesh mesh, long long euler, size_t loops, double boundary)
{
    topology top = topology_of(&mesh);
    assert_int_equal(top.euler, euler);
    assert_int_equal(top.loops, loops);
    size_t count;
    ur_mesh_piece *pieces = cut(&mesh, NULL, 0, &count);
    assert_int_equal(count, 1);
    assert_int_equal(pieces[0].mesh.triangle_count, mesh.triangle_count);
    assert_true(pieces[0].mesh.vertex_count > mesh.vertex_count);
    if (!isnan(boundary))
        assert_relative(topology_of(&pieces[0].mesh).boundary_length, boundary, 1e-12);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&mesh);
}

static void test_pieces_cut_to_disks(void **state)
{
    (void)state;
    /* A tetrahedron's farthest vertices are neighbours: a path of two edges (2 sqrt 2 each). */
    check_one_disk(tetrahedron(), 2, 0, 4 * 2 * sqrt(2.0));
    /* Opposite corners of the octahedron, two edges of sqrt 2 apart. */
    check_one_disk(octahedron(), 2, 0, 4 * sqrt(2.0));
    /* Opposite corners of the icosahedron are three edges of 2 apart. */
    check_one_disk(icosahedron(), 2, 0, 6 * 2);
    /* Pole to pole along a meridian: 8 chords of 2 sin(pi / 16), opened on both sides. */
    check_one_disk(uv_sphere(16, 8), 2, 0, 2 * 8 * 2 * sin(M_PI / 16));
    /* A tube: its two rims and a cut straight up it (height 10), twice. */
    check_one_disk(tube(12, 5, 3, 10), 0, 2, 2 * 12 * 2 * 3 * sin(M_PI / 12) + 2 * 10);
    check_one_disk(torus(12, 6, 10, 3, 0), 0, 0, NAN);
    check_one_disk(torus(40, 20, 10, 3, 0), 0, 0, NAN);
}

static void test_pieces_pillow(void **state)
{
    (void)state;
    /* Two triangles back to back: a sphere of three vertices.  Its farthest vertices are
       neighbours, so the slit takes two of its three edges: four vertices, a loop of four. */
    ur_vec3 vertices[3] = {{0, 0, 0}, {3, 0, 0}, {0, 4, 0}};
    size_t triangles[2][3] = {{0, 1, 2}, {0, 2, 1}};
    ur_mesh mesh;
    assert_int_equal(ur_mesh_new(vertices, 3, (const size_t(*)[3])triangles, 2, NULL, &mesh, NULL),
                     UR_OK);
    assert_int_equal(topology_of(&mesh).euler, 2);
    size_t count;
    ur_mesh_piece *pieces = cut(&mesh, NULL, 0, &count);
    assert_int_equal(count, 1);
    assert_int_equal(pieces[0].mesh.vertex_count, 4);
    assert_int_equal(topology_of(&pieces[0].mesh).boundary_edges, 4);
    ur_mesh_pieces_free(pieces, count);
    /* No triangles: no pieces, and no boundary. */
    mesh.triangle_count = 0;
    pieces = cut(&mesh, NULL, 0, &count);
    assert_int_equal(count, 0);
    ur_mesh_pieces_free(pieces, count);
    size_t *loop, length;
    ur_error error;
    assert_int_equal(ur_mesh_boundary(&mesh, &loop, &length, &error), UR_ERROR_INPUT);
    assert_message(error, "no triangles");
    ur_mesh_free(&mesh);
}

static void test_pieces_components(void **state)
{
    (void)state;
    /* Two tetrahedra side by side in one mesh: two pieces. */
    ur_mesh one = tetrahedron();
    builder b = {0};
    for (int copy = 0; copy < 2; copy++) {
        for (size_t v = 0; v < 4; v++)
            add_vertex(&b, one.vertices[v].x + 5 * copy, one.vertices[v].y, one.vertices[v].z);
        for (size_t t = 0; t < 4; t++)
            add_triangle(&b, one.triangles[t][0] + 4 * (size_t)copy,
                         one.triangles[t][1] + 4 * (size_t)copy,
                         one.triangles[t][2] + 4 * (size_t)copy, 0);
    }
    ur_mesh_free(&one);
    ur_mesh mesh = build(&b);
    size_t count;
    ur_mesh_piece *pieces = cut(&mesh, NULL, 0, &count);
    assert_int_equal(count, 2);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&mesh);
}

/* ---- ur_mesh_from_ruled ---- */

static void test_from_ruled_cylinder(void **state)
{
    (void)state;
    const double r = 10, h = 5;
    const size_t along = 64, across = 3;
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(r, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), h, &ruled, NULL), UR_OK);
    ur_mesh mesh;
    assert_int_equal(ur_mesh_from_ruled(&ruled, along, across, &mesh, NULL), UR_OK);
    ur_ruled_free(&ruled);
    assert_int_equal(mesh.vertex_count, 65 * 4);
    assert_int_equal(mesh.triangle_count, 2 * 64 * 3);
    /* Vertex (i, j) at angle 2 pi i / 64 and height 5 j / 3. */
    ur_vec3 p = mesh.vertices[10 * 4 + 2];
    assert_relative(p.x, r * cos(2 * M_PI * 10 / 64), 1e-12);
    assert_relative(p.y, r * sin(2 * M_PI * 10 / 64), 1e-12);
    assert_relative(p.z, h * 2 / 3, 1e-12);
    /* Flat rectangles: 64 chords of 2 r sin(pi / 64) by h. */
    assert_relative(ur_mesh_area(&mesh), 64 * 2 * r * sin(M_PI / 64) * h, 1e-12);
    for (size_t t = 0; t < mesh.triangle_count; t++) {
        const size_t *c = mesh.triangles[t];
        ur_vec3 a = mesh.vertices[c[0]], b = mesh.vertices[c[1]], d = mesh.vertices[c[2]];
        ur_vec3 normal = ur_vec3_cross(ur_vec3_sub(b, a), ur_vec3_sub(d, a));
        ur_vec3 outward = ur_vec3_make(a.x + b.x + d.x, a.y + b.y + d.y, 0);
        assert_true(ur_vec3_dot(normal, outward) > 0);
    }
    /* The seam ruling is doubled: already a disk, its boundary round all four sides. */
    topology top = topology_of(&mesh);
    assert_int_equal(top.euler, 1);
    assert_int_equal(top.boundary_edges, 2 * 64 + 2 * 3);
    size_t count;
    ur_mesh_piece *pieces = cut(&mesh, NULL, 0, &count);
    assert_int_equal(count, 1);
    assert_int_equal(pieces[0].mesh.vertex_count, 260);
    ur_mesh_pieces_free(pieces, count);
    /* Welding closes the seam: a tube, chi 0. */
    ur_mesh_repairs repairs = clean(&mesh, 1e-9);
    assert_int_equal(repairs.welded, 4);
    assert_int_equal(mesh.vertex_count, 256);
    top = topology_of(&mesh);
    assert_int_equal(top.euler, 0);
    assert_int_equal(top.loops, 2);
    ur_mesh_free(&mesh);
}

static void test_from_ruled_cone(void **state)
{
    (void)state;
    /* Radius 10, apex 20 above: planar triangles apex-chord, n (1/2) 2 R sin(pi/n) times the
       apex's distance from the chord, sqrt(h^2 + (R cos(pi/n))^2). */
    const double r = 10, h = 20;
    const size_t n = 48, across = 4;
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(r, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cone(circle, ur_vec3_make(0, 0, h), 1, &ruled, NULL), UR_OK);
    ur_mesh mesh;
    assert_int_equal(ur_mesh_from_ruled(&ruled, n, across, &mesh, NULL), UR_OK);
    ur_ruled_free(&ruled);
    double c = cos(M_PI / (double)n);
    double area = (double)n * r * sin(M_PI / (double)n) * sqrt(h * h + r * r * c * c);
    assert_relative(ur_mesh_area(&mesh), area, 1e-12);
    assert_relative(area, M_PI * r * sqrt(r * r + h * h), 1e-2);
    /* Cleaning welds the apex (49 into 1) and the seam (4), dropping a triangle per ruling. */
    ur_mesh_repairs repairs = clean(&mesh, 1e-9);
    assert_int_equal(repairs.welded, 48 + 4);
    assert_int_equal(repairs.degenerate, 48);
    assert_int_equal(repairs.flipped, 0);
    assert_int_equal(mesh.vertex_count, 48 * 4 + 1);
    assert_int_equal(mesh.triangle_count, 2 * 48 * 4 - 48);
    assert_relative(ur_mesh_area(&mesh), area, 1e-12);
    topology top = topology_of(&mesh);
    assert_int_equal(top.euler, 1);
    assert_int_equal(top.loops, 1);
    assert_int_equal(top.boundary_edges, 48);
    ur_mesh_free(&mesh);
}

static void test_from_ruled_refuses(void **state)
{
    (void)state;
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(1, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 1, &ruled, NULL), UR_OK);
    ur_mesh mesh;
    ur_error error;
    assert_int_equal(ur_mesh_from_ruled(&ruled, 0, 3, &mesh, &error), UR_ERROR_INPUT);
    assert_message(error, "at least 1");
    assert_null(mesh.vertices);
    ur_ruled_free(&ruled);
}

/* A helical ribbon of `turns` turns: n steps along, 4 across, radius 30, rising 4 mm per radian. */
static ur_mesh helical_ribbon(double turns, size_t n)
{
    builder b = {0};
    for (size_t i = 0; i <= n; i++) {
        double t = 2 * M_PI * turns * (double)i / (double)n;
        for (size_t j = 0; j <= 4; j++) {
            double r = 30 + 5.0 * (double)j;
            add_vertex(&b, r * cos(t), r * sin(t), 4 * t);
        }
    }
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < 4; j++) {
            size_t a = i * 5 + j;
            add_triangle(&b, a, a + 5, a + 6, 0);
            add_triangle(&b, a, a + 6, a + 1, 0);
        }
    return build(&b);
}

/*
 * A ribbon of 1.6 turns is halved along its length: two pieces of equal
 * area, each winding about 0.8 turn and so less than one (its points'
 * angles span 0.7 to 0.9 of 2 pi), where any plane would cut it at every
 * turn.
 */
static void test_halve_along_the_length(void **state)
{
    (void)state;
    ur_mesh ribbon = helical_ribbon(1.6, 160);
    ur_mesh halves;
    ur_error error;
    assert_int_equal(ur_mesh_halve(&ribbon, &halves, &error), UR_OK);
    assert_relative(ur_mesh_area(&halves), ur_mesh_area(&ribbon), 1e-12);
    size_t count;
    ur_mesh_piece *pieces = cut(&halves, NULL, 0, &count);
    assert_int_equal(count, 2);
    for (size_t k = 0; k < 2; k++) {
        assert_relative(ur_mesh_area(&pieces[k].mesh), ur_mesh_area(&ribbon) / 2, 0.02);
        double low = INFINITY, high = -INFINITY;
        for (size_t v = 0; v < pieces[k].mesh.vertex_count; v++) {
            double height = pieces[k].mesh.vertices[v].z; /* 4 mm per radian: the angle */
            low = fmin(low, height / 4);
            high = fmax(high, height / 4);
        }
        /* 0.8 turn, give or take the slant of a cut that follows distances from a corner. */
        assert_true(high - low < 0.9 * 2 * M_PI && high - low > 0.7 * 2 * M_PI);
    }
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&halves);
    ur_mesh_free(&ribbon);
    ur_mesh tiny = grid(1, 1);
    ur_mesh one = {0};
    assert_int_equal(ur_mesh_halve(&tiny, &one, &error), UR_OK); /* two triangles: fine */
    ur_mesh_free(&one);
    ur_mesh_free(&tiny);
}

/* The mesh cut into parts along its length, each with its share of the area. */
static void assert_split_evenly(const ur_mesh *mesh, size_t parts)
{
    ur_mesh split;
    ur_error error;
    assert_int_equal(ur_mesh_split_along(mesh, parts, &split, &error), UR_OK);
    size_t count;
    ur_mesh_piece *pieces = cut(&split, NULL, 0, &count);
    assert_int_equal(count, parts);
    for (size_t k = 0; k < count; k++)
        assert_relative(ur_mesh_area(&pieces[k].mesh), ur_mesh_area(mesh) / (double)parts, 1e-4);
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&split);
}

/*
 * A fan of four triangles, one holding three quarters of the area, cut
 * into four along its length: each part a quarter of the area, the cuts
 * running through the large triangle.  Levels taken triangle by triangle
 * fell three times on the large one, and the cut was refused as planes
 * that do not increase.  Cut into 7, more parts than it has triangles,
 * each part is a seventh.
 */
static void test_split_along_through_a_large_triangle(void **state)
{
    (void)state;
    builder b = {0};
    add_vertex(&b, 0, 10, 0); /* the apex */
    double base[5] = {0, 1, 2, 3, 12};
    for (size_t i = 0; i < 5; i++)
        add_vertex(&b, base[i], 0, 0);
    for (size_t i = 1; i < 5; i++)
        add_triangle(&b, 0, i, i + 1, 0);
    ur_mesh fan = build(&b);
    double total = ur_mesh_area(&fan); /* 60: 5 + 5 + 5 + 45 */
    assert_relative(total, 60.0, 1e-12);
    assert_split_evenly(&fan, 4);
    assert_split_evenly(&fan, 7); /* more parts than triangles: the cuts run through them */
    ur_mesh split;
    ur_error error;
    assert_int_equal(ur_mesh_split_along(&fan, 1, &split, &error), UR_ERROR_INPUT);
    assert_message(error, "2 parts or more");
    ur_mesh_free(&fan);
}

/*
 * A 6 x 6 square cut at the levels of x into 4 parts: each a rectangle of
 * 1.5 x 6, whatever the diagonals of its triangles (the distance along
 * the edges from a corner would cut it on the slant).  A value that is
 * not finite is refused, naming its vertex.
 */
static void test_split_by_cuts_straight_across(void **state)
{
    (void)state;
    ur_mesh square = grid(6, 0);
    double *field = malloc(square.vertex_count * sizeof *field);
    assert_non_null(field);
    for (size_t v = 0; v < square.vertex_count; v++)
        field[v] = square.vertices[v].x;
    ur_mesh split;
    ur_error error;
    assert_int_equal(ur_mesh_split_by(&square, field, 4, &split, &error), UR_OK);
    size_t count;
    ur_mesh_piece *pieces = cut(&split, NULL, 0, &count);
    assert_int_equal(count, 4);
    bool seen[4] = {false};
    for (size_t k = 0; k < count; k++) {
        const ur_mesh *part = &pieces[k].mesh;
        double low = INFINITY, high = -INFINITY;
        for (size_t v = 0; v < part->vertex_count; v++) {
            low = fmin(low, part->vertices[v].x);
            high = fmax(high, part->vertices[v].x);
        }
        size_t band = (size_t)lround(low / 1.5);
        assert_true(band < 4 && !seen[band]);
        seen[band] = true;
        assert_true(fabs(low - 1.5 * (double)band) < 1e-9);
        assert_true(fabs(high - 1.5 * (double)(band + 1)) < 1e-9);
        assert_relative(ur_mesh_area(part), 9.0, 1e-9);
    }
    ur_mesh_pieces_free(pieces, count);
    ur_mesh_free(&split);
    field[7] = NAN;
    assert_int_equal(ur_mesh_split_by(&square, field, 4, &split, &error), UR_ERROR_INPUT);
    assert_message(error, "vertex 8");
    assert_int_equal(ur_mesh_split_by(&square, field, 1, &split, &error), UR_ERROR_INPUT);
    assert_message(error, "2 parts or more");
    free(field);
    ur_mesh_free(&square);
}

/*
 * A plane just past the snapping distance of a sharp corner (11.4
 * degrees) would cut off a triangle with legs of 2e-6 and an area of
 * 4e-13, below what flattening takes as a triangle (1e-12 of the size
 * squared): the corner is taken onto the plane instead, and no triangle
 * of the cut is that small.
 */
static void test_bands_leave_no_sliver(void **state)
{
    (void)state;
    builder b = {0};
    add_vertex(&b, 0, 0, 0);
    add_vertex(&b, 1, -0.1, 0);
    add_vertex(&b, 1, 0.1, 0);
    add_triangle(&b, 0, 1, 2, 0);
    ur_mesh wedge = build(&b);
    double planes[1] = {2e-6}, size = ur_mesh_size(&wedge);
    ur_mesh banded;
    ur_error error;
    assert_int_equal(ur_mesh_bands(&wedge, ur_vec3_make(1, 0, 0), planes, 2, &banded, &error),
                     UR_OK);
    double total = 0;
    for (size_t t = 0; t < banded.triangle_count; t++) {
        const size_t *c = banded.triangles[t];
        ur_vec3 a = banded.vertices[c[0]];
        double area = 0.5 * ur_vec3_length(ur_vec3_cross(ur_vec3_sub(banded.vertices[c[1]], a),
                                                         ur_vec3_sub(banded.vertices[c[2]], a)));
        assert_true(area > UR_MESH_ZERO_AREA * size * size);
        total += area;
    }
    assert_relative(total, 0.1, 1e-12);
    ur_mesh_free(&banded);
    ur_mesh_free(&wedge);
}

/*
 * An open prism of 32 sides round a circle of radius 60, 40 high, its
 * quads split in two: along its rims the normal turns by 2 pi / 32 over
 * an edge 2 * 60 sin(pi / 32) long, a radius of 60 sin(pi/32) / (pi/32);
 * it does not turn up its sides.  The hyperbolic paraboloid z = x y / 50
 * bends tightest at its saddle point, to a radius of 50 (its principal
 * curvatures there are 1/50 and -1/50): meshed in squares of 2.5 mm, each
 * folded along a diagonal, it comes within 5 %, where the angle between
 * the two triangles of a square over their heights gave half of it.  A
 * flat grid does not bend.
 */
static void test_tightest_bend(void **state)
{
    (void)state;
    ur_mesh prism = tube(32, 1, 60, 40);
    double radius;
    ur_vec3 at;
    ur_error error;
    assert_int_equal(ur_mesh_tightest_bend(&prism, &radius, &at, &error), UR_OK);
    assert_relative(radius, 60 * sin(M_PI / 32) / (M_PI / 32), 1e-9);
    assert_true(fabs(hypot(at.x, at.y) - 60 * cos(M_PI / 32)) < 1e-9); /* on a rim */
    assert_true(fabs(at.z) < 1e-9 || fabs(at.z - 40) < 1e-9);
    ur_mesh_free(&prism);
    ur_mesh saddle = grid(32, 32);
    for (size_t v = 0; v < saddle.vertex_count; v++) {
        ur_vec3 *p = &saddle.vertices[v];
        p->x = 2.5 * (p->x - 16), p->y = 2.5 * (p->y - 16);
        p->z = p->x * p->y / 50;
    }
    assert_int_equal(ur_mesh_tightest_bend(&saddle, &radius, &at, &error), UR_OK);
    assert_relative(radius, 50, 0.05);
    assert_true(hypot(at.x, at.y) < 5); /* at the saddle point */
    ur_mesh_free(&saddle);
    ur_mesh flat = grid(3, 0);
    assert_int_equal(ur_mesh_tightest_bend(&flat, &radius, &at, &error), UR_OK);
    assert_true(isinf(radius));
    ur_mesh_free(&flat);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_new),
        cmocka_unit_test(test_new_refuses),
        cmocka_unit_test(test_area),
        cmocka_unit_test(test_twins),
        cmocka_unit_test(test_clean_welds_soup),
        cmocka_unit_test(test_clean_orients),
        cmocka_unit_test(test_clean_drops),
        cmocka_unit_test(test_clean_refuses),
        cmocka_unit_test(test_clean_drops_flaps),
        cmocka_unit_test(test_clean_drops_faces_given_twice),
        cmocka_unit_test(test_clean_drops_a_face_given_twice_on_the_rim),
        cmocka_unit_test(test_clean_keeps_what_is_no_flap),
        cmocka_unit_test(test_clean_unwelds_touching_parts),
        cmocka_unit_test(test_clean_splits_surfaces_touching_along_an_edge),
        cmocka_unit_test(test_clean_refuses_moebius),
        cmocka_unit_test(test_clean_million),
        cmocka_unit_test(test_boundary),
        cmocka_unit_test(test_pieces_disk),
        cmocka_unit_test(test_pieces_groups),
        cmocka_unit_test(test_pieces_user_seams),
        cmocka_unit_test(test_pieces_refuses_seams),
        cmocka_unit_test(test_pieces_cut_to_disks),
        cmocka_unit_test(test_pieces_pillow),
        cmocka_unit_test(test_pieces_components),
        cmocka_unit_test(test_from_ruled_cylinder),
        cmocka_unit_test(test_from_ruled_cone),
        cmocka_unit_test(test_from_ruled_refuses),
        cmocka_unit_test(test_halve_along_the_length),
        cmocka_unit_test(test_split_along_through_a_large_triangle),
        cmocka_unit_test(test_split_by_cuts_straight_across),
        cmocka_unit_test(test_bands_leave_no_sliver),
        cmocka_unit_test(test_tightest_bend),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
