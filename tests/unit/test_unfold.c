/*
 * test_unfold.c: the exact unfolding of polyhedra built here (a cube, an
 * icosahedron, a 500-face torus and a 500-face bumpy sphere, a flat fan, a
 * lampshade of 32-bit coordinates, open and grouped meshes, two faces
 * folded either way), checked by code of its own rather than the
 * library's: every flat triangle congruent to its 3D triangle, no two
 * triangles of a piece overlapping (a pairwise 2D test), which edges a
 * piece joins found from the flat corners, each fold's mountain or valley
 * found from which side of one face the other face's far corner lies on,
 * outlines walked edge by edge, and every edge counted exactly once as a
 * fold, a flat join, a seam or a boundary edge.  Then flat faces (a
 * cube's squares, a torus's float-rounded quads, a ring of quads round a
 * hole), no single face on the head that could have joined a neighbour
 * (each moved onto its neighbours and checked), pieces within a room (the
 * smallest rectangle found by the test), a face larger than the room
 * refused, and the search giving the same result for a seed.
 */
#include "test_support.h"

#include <stdlib.h>

#include "unroll/flatten.h"
#include "unroll/io.h"

#define assert_message(error, text)                                                                \
    do {                                                                                           \
        if (!strstr((error).message, (text)))                                                      \
            fail_msg("message \"%s\" does not say \"%s\"", (error).message, (text));               \
    } while (0)

/* ---- building meshes ---- */

typedef struct builder {
    ur_vec3 *vertices;
    size_t vertex_count;
    size_t (*triangles)[3];
    size_t *groups;
    size_t triangle_count;
} builder;

static size_t add_vertex(builder *b, ur_vec3 p)
{
    b->vertices = realloc(b->vertices, (b->vertex_count + 1) * sizeof *b->vertices);
    assert_non_null(b->vertices);
    b->vertices[b->vertex_count] = p;
    return b->vertex_count++;
}

static void add_triangle(builder *b, size_t v0, size_t v1, size_t v2, size_t group)
{
    size_t t = b->triangle_count++;
    b->triangles = realloc(b->triangles, b->triangle_count * sizeof *b->triangles);
    b->groups = realloc(b->groups, b->triangle_count * sizeof *b->groups);
    assert_non_null(b->triangles);
    assert_non_null(b->groups);
    b->triangles[t][0] = v0;
    b->triangles[t][1] = v1;
    b->triangles[t][2] = v2;
    b->groups[t] = group;
}

static ur_vec3 normal_of(const ur_vec3 *v, const size_t tri[3])
{
    return ur_vec3_cross(ur_vec3_sub(v[tri[1]], v[tri[0]]), ur_vec3_sub(v[tri[2]], v[tri[0]]));
}

/* Adds the triangle turned, if need be, so that its normal points away from centre. */
static void add_outward(builder *b, size_t v0, size_t v1, size_t v2, ur_vec3 centre)
{
    size_t tri[3] = {v0, v1, v2};
    ur_vec3 middle = ur_vec3_scale(
        ur_vec3_add(ur_vec3_add(b->vertices[v0], b->vertices[v1]), b->vertices[v2]), 1.0 / 3);
    if (ur_vec3_dot(normal_of(b->vertices, tri), ur_vec3_sub(middle, centre)) > 0)
        add_triangle(b, v0, v1, v2, 0);
    else
        add_triangle(b, v0, v2, v1, 0);
}

/* Signed volume (positive when the triangles face outward). */
static double signed_volume(const builder *b)
{
    double volume = 0;
    for (size_t t = 0; t < b->triangle_count; t++) {
        const size_t *tri = b->triangles[t];
        volume += ur_vec3_det(b->vertices[tri[0]], b->vertices[tri[1]], b->vertices[tri[2]]) / 6;
    }
    return volume;
}

/* Turns every triangle of a closed mesh whose triangles face inward. */
static void face_outward(builder *b)
{
    if (signed_volume(b) > 0)
        return;
    for (size_t t = 0; t < b->triangle_count; t++) {
        size_t swap = b->triangles[t][1];
        b->triangles[t][1] = b->triangles[t][2];
        b->triangles[t][2] = swap;
    }
}

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

/* Corners of a cube of side 40 at (5, -3, 2); vertex x + 2 y + 4 z. */
static void cube_vertices(builder *b)
{
    for (int i = 0; i < 8; i++)
        add_vertex(b, ur_vec3_make(5 + 40 * (i & 1), -3 + 40 * (i >> 1 & 1), 2 + 40 * (i >> 2)));
}

/* The quads of the cube, each split on its diagonal from its first corner. */
static const size_t cube_quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                        {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};

/* A closed cube of 12 triangles facing outward; open leaves out the top (z = 42). */
static ur_mesh cube(bool open)
{
    builder b = {0};
    cube_vertices(&b);
    ur_vec3 centre = ur_vec3_make(25, 17, 22);
    for (int f = 0; f < 6; f++) {
        if (open && f == 1)
            continue;
        const size_t *q = cube_quads[f];
        add_outward(&b, q[0], q[1], q[2], centre);
        add_outward(&b, q[0], q[2], q[3], centre);
    }
    return build(&b);
}

/* The regular icosahedron of edge 2: the vertices (0, +-1, +-phi) and their cyclic turns. */
static ur_mesh icosahedron(void)
{
    builder b = {0};
    double phi = (1 + sqrt(5)) / 2;
    for (int turn = 0; turn < 3; turn++)
        for (int s = 0; s < 4; s++) {
            double c[3] = {0, s & 1 ? -1 : 1, s & 2 ? -phi : phi};
            add_vertex(&b, ur_vec3_make(c[turn % 3], c[(turn + 1) % 3], c[(turn + 2) % 3]));
        }
    for (size_t i = 0; i < 12; i++)
        for (size_t j = i + 1; j < 12; j++)
            for (size_t k = j + 1; k < 12; k++)
                if (fabs(ur_vec3_distance(b.vertices[i], b.vertices[j]) - 2) < 1e-9 &&
                    fabs(ur_vec3_distance(b.vertices[j], b.vertices[k]) - 2) < 1e-9 &&
                    fabs(ur_vec3_distance(b.vertices[i], b.vertices[k]) - 2) < 1e-9)
                    add_outward(&b, i, j, k, ur_vec3_make(0, 0, 0));
    assert_int_equal(b.triangle_count, 20);
    return build(&b);
}

/* A torus, around x around, tube around the tube: 2 around tube triangles. */
static ur_mesh torus(size_t around, size_t tube, double big, double small)
{
    builder b = {0};
    for (size_t i = 0; i < around; i++)
        for (size_t j = 0; j < tube; j++) {
            double u = 2 * M_PI * (double)i / (double)around;
            double v = 2 * M_PI * (double)j / (double)tube;
            double r = big + small * cos(v);
            add_vertex(&b, ur_vec3_make(r * cos(u), r * sin(u), small * sin(v)));
        }
    for (size_t i = 0; i < around; i++)
        for (size_t j = 0; j < tube; j++) {
            size_t p00 = i * tube + j, p01 = i * tube + (j + 1) % tube;
            size_t p10 = (i + 1) % around * tube + j,
                   p11 = (i + 1) % around * tube + (j + 1) % tube;
            add_triangle(&b, p00, p10, p11, 0);
            add_triangle(&b, p00, p11, p01, 0);
        }
    face_outward(&b);
    return build(&b);
}

/*
 * A globe of radius 50: two poles and rings rings of around points, every
 * third point pushed in by a fifth of the radius so that edges around it
 * are concave.  2 around (rings - 1) + 2 around triangles.
 */
/* A sphere of radius 50 in rings of quads, every third vertex pulled in to radius bump. */
static ur_mesh sphere(size_t around, size_t rings, double bump)
{
    builder b = {0};
    size_t north = add_vertex(&b, ur_vec3_make(0, 0, 50));
    for (size_t j = 0; j < rings; j++)
        for (size_t i = 0; i < around; i++) {
            double theta = M_PI * (double)(j + 1) / (double)(rings + 1);
            double phi = 2 * M_PI * ((double)i + 0.5 * (double)(j % 2)) / (double)around;
            double r = (j * around + i) % 3 == 0 ? bump : 50;
            add_vertex(&b, ur_vec3_make(r * sin(theta) * cos(phi), r * sin(theta) * sin(phi),
                                        r * cos(theta)));
        }
    size_t south = add_vertex(&b, ur_vec3_make(0, 0, -50));
    for (size_t i = 0; i < around; i++) {
        size_t i1 = (i + 1) % around;
        add_triangle(&b, north, 1 + i, 1 + i1, 0);
        add_triangle(&b, south, 1 + (rings - 1) * around + i1, 1 + (rings - 1) * around + i, 0);
        for (size_t j = 0; j + 1 < rings; j++) {
            size_t a = 1 + j * around + i, c = 1 + j * around + i1;
            size_t d = a + around, e = c + around;
            add_triangle(&b, a, d, e, 0);
            add_triangle(&b, a, e, c, 0);
        }
    }
    face_outward(&b);
    return build(&b);
}

/* A modeller's UV sphere of radius r: rings of quads (two triangles each), fans at the poles. */
static ur_mesh uv_sphere(size_t around, size_t rings, double r)
{
    builder b = {0};
    size_t north = add_vertex(&b, ur_vec3_make(0, 0, r));
    for (size_t j = 1; j < rings; j++)
        for (size_t i = 0; i < around; i++) {
            double theta = M_PI * (double)j / (double)rings;
            double phi = 2 * M_PI * (double)i / (double)around;
            add_vertex(&b, ur_vec3_make(r * sin(theta) * cos(phi), r * sin(theta) * sin(phi),
                                        r * cos(theta)));
        }
    size_t south = add_vertex(&b, ur_vec3_make(0, 0, -r)), last = 1 + (rings - 2) * around;
    for (size_t i = 0; i < around; i++) {
        size_t i1 = (i + 1) % around;
        add_triangle(&b, north, 1 + i, 1 + i1, 0);
        add_triangle(&b, south, last + i1, last + i, 0);
        for (size_t j = 0; j + 2 < rings; j++) {
            size_t a = 1 + j * around + i, c = 1 + j * around + i1;
            add_triangle(&b, a, a + around, c + around, 0);
            add_triangle(&b, a, c + around, c, 0);
        }
    }
    face_outward(&b);
    return build(&b);
}

static ur_mesh bumpy_sphere(size_t around, size_t rings)
{
    return sphere(around, rings, 40);
}

/* n triangles round a centre, all in z = 0 (flat: their angles add to 2 pi). */
static ur_mesh flat_fan(size_t n)
{
    builder b = {0};
    size_t centre = add_vertex(&b, ur_vec3_make(0, 0, 0));
    for (size_t i = 0; i < n; i++) {
        double a = 2 * M_PI * (double)i / (double)n;
        add_vertex(&b, ur_vec3_make(30 * cos(a) + (i % 2) * 3, 30 * sin(a), 0));
    }
    for (size_t i = 0; i < n; i++)
        add_triangle(&b, centre, 1 + i, 1 + (i + 1) % n, 0);
    return build(&b);
}

/*
 * A lampshade as a modeller exports it: a frustum of a cone (radii 100 and
 * 60, 120 high), around quads round and rows up, each quad split in two,
 * every coordinate rounded to a 32-bit float.  Its quads are flat and its
 * creases straight only to that rounding.
 */
static ur_mesh float_frustum(size_t around, size_t rows)
{
    builder b = {0};
    for (size_t j = 0; j <= rows; j++)
        for (size_t i = 0; i < around; i++) {
            double t = (double)j / (double)rows, a = 2 * M_PI * (double)i / (double)around;
            double r = 100 - 40 * t;
            add_vertex(&b,
                       ur_vec3_make((float)(r * cos(a)), (float)(r * sin(a)), (float)(120 * t)));
        }
    for (size_t j = 0; j < rows; j++)
        for (size_t i = 0; i < around; i++) {
            size_t p00 = j * around + i, p10 = j * around + (i + 1) % around;
            add_triangle(&b, p00, p10, p10 + around, 0);
            add_triangle(&b, p00, p10 + around, p00 + around, 0);
        }
    return build(&b);
}

/* ---- checking an unfolding, independently of the library ---- */

/* An undirected edge of the mesh and the triangles on it (second is SIZE_MAX on the boundary). */
typedef struct edge {
    size_t low, high;
    size_t first, second;
} edge;

static int compare_edges(const void *a, const void *b)
{
    const edge *x = a, *y = b;
    if (x->low != y->low)
        return x->low < y->low ? -1 : 1;
    return (x->high > y->high) - (x->high < y->high);
}

/* The edges of a manifold mesh, sorted; *count of them. */
static edge *mesh_edges(const ur_mesh *mesh, size_t *count)
{
    size_t n = 3 * mesh->triangle_count;
    edge *all = malloc(n * sizeof *all);
    assert_non_null(all);
    for (size_t h = 0; h < n; h++) {
        size_t a = mesh->triangles[h / 3][h % 3], b = mesh->triangles[h / 3][(h % 3 + 1) % 3];
        all[h] = (edge){a < b ? a : b, a < b ? b : a, h / 3, SIZE_MAX};
    }
    qsort(all, n, sizeof *all, compare_edges);
    size_t kept = 0;
    for (size_t i = 0; i < n; i++) {
        if (kept > 0 && compare_edges(&all[i], &all[kept - 1]) == 0) {
            assert_int_equal(all[kept - 1].second, SIZE_MAX);
            all[kept - 1].second = all[i].first;
        } else
            all[kept++] = all[i];
    }
    *count = kept;
    return all;
}

static edge *find_edge(edge *edges, size_t count, size_t a, size_t b)
{
    edge key = {a < b ? a : b, a < b ? b : a, 0, 0};
    return bsearch(&key, edges, count, sizeof *edges, compare_edges);
}

/* Where each triangle went: its piece and its place there. */
typedef struct placement {
    size_t piece, index;
} placement;

static placement *placements(const ur_mesh *mesh, const ur_unfolding *u)
{
    placement *where = malloc(mesh->triangle_count * sizeof *where);
    assert_non_null(where);
    for (size_t t = 0; t < mesh->triangle_count; t++)
        where[t].piece = SIZE_MAX;
    for (size_t p = 0; p < u->count; p++)
        for (size_t i = 0; i < u->pieces[p].triangle_count; i++) {
            size_t t = u->pieces[p].triangles[i];
            assert_true(t < mesh->triangle_count);
            assert_int_equal(where[t].piece, SIZE_MAX); /* laid once */
            where[t] = (placement){p, i};
        }
    for (size_t t = 0; t < mesh->triangle_count; t++)
        assert_int_not_equal(where[t].piece, SIZE_MAX); /* laid at all */
    return where;
}

/* The flat position of mesh vertex v in triangle t as laid. */
static ur_vec2 flat_vertex(const ur_mesh *mesh, const ur_unfolding *u, const placement *where,
                           size_t t, size_t v)
{
    for (int k = 0; k < 3; k++)
        if (mesh->triangles[t][k] == v)
            return u->pieces[where[t].piece].flat[where[t].index][k];
    fail_msg("vertex %zu is not a corner of triangle %zu", v, t);
    return ur_vec2_make(0, 0);
}

static double mesh_size(const ur_mesh *mesh)
{
    ur_box box = ur_box_empty();
    double low_z = INFINITY, high_z = -INFINITY;
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        ur_box_add(&box, ur_vec2_make(mesh->vertices[v].x, mesh->vertices[v].y));
        low_z = fmin(low_z, mesh->vertices[v].z);
        high_z = fmax(high_z, mesh->vertices[v].z);
    }
    return sqrt(pow(ur_box_width(box), 2) + pow(ur_box_height(box), 2) + pow(high_z - low_z, 2));
}

/* Whether the piece's outline runs along the edge from vertex a to b, either way. */
static bool on_outline(const ur_unfolded_piece *piece, size_t a, size_t b)
{
    size_t n = piece->outline_count;
    for (size_t i = 0; i < n; i++) {
        size_t p = piece->outline_vertices[i], q = piece->outline_vertices[(i + 1) % n];
        if ((p == a && q == b) || (p == b && q == a))
            return true;
    }
    return false;
}

/*
 * Whether the edge's two faces lie in one piece, edge on edge: a join, seen
 * from the net.  Within a millionth of the mesh's size, so that a mesh of
 * 32-bit coordinates, whose flat regions close up only to about 1e-7, is
 * judged as a cutter would.  A slit is no join: a flat face round a hole
 * lies in one piece cut from the hole out, both sides of the cut on each
 * other and the outline along both.
 */
static bool joined(const ur_mesh *mesh, const ur_unfolding *u, const placement *where,
                   const edge *e)
{
    if (e->second == SIZE_MAX || where[e->first].piece != where[e->second].piece ||
        on_outline(&u->pieces[where[e->first].piece], e->low, e->high))
        return false;
    double tolerance = 1e-6 * mesh_size(mesh);
    return ur_vec2_distance(flat_vertex(mesh, u, where, e->first, e->low),
                            flat_vertex(mesh, u, where, e->second, e->low)) <= tolerance &&
           ur_vec2_distance(flat_vertex(mesh, u, where, e->first, e->high),
                            flat_vertex(mesh, u, where, e->second, e->high)) <= tolerance;
}

/* The corner of triangle t that is on neither end of the edge. */
static size_t far_corner(const ur_mesh *mesh, size_t t, const edge *e)
{
    for (int k = 0; k < 3; k++)
        if (mesh->triangles[t][k] != e->low && mesh->triangles[t][k] != e->high)
            return mesh->triangles[t][k];
    fail_msg("triangle %zu has no corner off its edge", t);
    return 0;
}

/*
 * +1 where the surface is concave across the edge (a valley), -1 where it
 * is convex (a mountain): the side of the first face's plane that the
 * second face's far corner lies on.  *angle is the angle between normals.
 */
static int concavity(const ur_mesh *mesh, const edge *e, double *angle)
{
    const ur_vec3 *v = mesh->vertices;
    ur_vec3 n1 = normal_of(v, mesh->triangles[e->first]);
    ur_vec3 n2 = normal_of(v, mesh->triangles[e->second]);
    double side = ur_vec3_dot(n1, ur_vec3_sub(v[far_corner(mesh, e->second, e)], v[e->low]));
    double c = ur_vec3_dot(n1, n2) / (ur_vec3_length(n1) * ur_vec3_length(n2));
    *angle = acos(fmax(-1.0, fmin(1.0, c)));
    return side > 0 ? 1 : -1;
}

/*
 * The flat angle of the unfolding checked (joins turning less are flat),
 * and how much shorter, relatively, a triangle's side may come out: 1e-9
 * for faces laid as they are; a flat face of triangles that turn a little
 * is laid projected on one plane, and a triangle leaning by up to twice
 * the flat angle from it shortens by up to 1 - cos of that.
 */
static double flat_angle = UR_UNFOLD_FLAT_ANGLE;
static double length_tolerance = 1e-9;

static void allow_projection(void)
{
    length_tolerance = 1 - cos(2 * flat_angle) + 1e-9;
}

static void check_congruent(const ur_mesh *mesh, const ur_unfolded_piece *piece)
{
    for (size_t i = 0; i < piece->triangle_count; i++) {
        const size_t *tri = mesh->triangles[piece->triangles[i]];
        for (int k = 0; k < 3; k++) {
            double space =
                ur_vec3_distance(mesh->vertices[tri[k]], mesh->vertices[tri[(k + 1) % 3]]);
            assert_relative(ur_vec2_distance(piece->flat[i][k], piece->flat[i][(k + 1) % 3]), space,
                            length_tolerance);
        }
        assert_true(ur_polygon_signed_area(piece->flat[i], 3) > 0); /* outside face up */
    }
}

static double orientation(ur_vec2 a, ur_vec2 b, ur_vec2 c)
{
    return ur_vec2_cross(ur_vec2_sub(b, a), ur_vec2_sub(c, a));
}

static bool crosses(ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d)
{
    double o1 = orientation(a, b, c), o2 = orientation(a, b, d);
    double o3 = orientation(c, d, a), o4 = orientation(c, d, b);
    return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

/*
 * Whether the line of edge k of triangle a keeps b out of a's side by at
 * least -margin: an overlap thinner than margin is a touch.
 */
static bool edge_separates(const ur_vec2 a[3], int k, const ur_vec2 b[3], double margin)
{
    ur_vec2 p = a[k], q = a[(k + 1) % 3];
    double length = ur_vec2_distance(p, q);
    for (int i = 0; i < 3; i++)
        if (orientation(p, q, b[i]) / length > margin)
            return false;
    return true;
}

/*
 * Whether two counter-clockwise triangles overlap by more than margin: two
 * convex polygons are apart exactly when the line of one of their edges
 * separates them.
 */
static bool overlap(const ur_vec2 first[3], const ur_vec2 second[3], double margin)
{
    for (int k = 0; k < 3; k++)
        if (edge_separates(first, k, second, margin) || edge_separates(second, k, first, margin))
            return false;
    return true;
}

/*
 * No two triangles of a piece overlap by more than 1e-6 of the mesh's
 * size, the tolerance within which the library joins edges that close a
 * ring round a vertex (flatten.h).
 */
static void check_no_overlap(const ur_mesh *mesh, const ur_unfolded_piece *piece)
{
    double margin = 1e-6 * mesh_size(mesh);
    for (size_t i = 0; i < piece->triangle_count; i++)
        for (size_t j = i + 1; j < piece->triangle_count; j++)
            if (overlap(piece->flat[i], piece->flat[j], margin))
                fail_msg("triangles %zu and %zu of a piece overlap", piece->triangles[i],
                         piece->triangles[j]);
}

/* The outline: a simple counter-clockwise ring of the piece's edges that are not joined. */
static void check_outline(const ur_mesh *mesh, const ur_unfolded_piece *piece, size_t open_edges)
{
    size_t n = piece->outline_count;
    assert_int_equal(n, open_edges);
    /* An outline point where a ring closed up is either triangle's copy of the vertex. */
    double tolerance = 2e-6 * mesh_size(mesh);
    for (size_t i = 0; i < n; i++) {
        size_t j = (i + 1) % n;
        double space = ur_vec3_distance(mesh->vertices[piece->outline_vertices[i]],
                                        mesh->vertices[piece->outline_vertices[j]]);
        double plane = ur_vec2_distance(piece->outline[i], piece->outline[j]);
        if (!(fabs(plane - space) <= tolerance + length_tolerance * space))
            fail_msg("outline edge %zu is %.12g long, its 3D edge %.12g", i, plane, space);
        for (size_t k = i + 2; k < n; k++)
            if ((k + 1) % n != i)
                assert_false(crosses(piece->outline[i], piece->outline[j], piece->outline[k],
                                     piece->outline[(k + 1) % n]));
    }
    double flat = 0;
    for (size_t i = 0; i < piece->triangle_count; i++)
        flat += ur_polygon_signed_area(piece->flat[i], 3);
    assert_relative(ur_polygon_signed_area(piece->outline, n), flat, 1e-6);
    assert_relative(piece->flat_area, ur_polygon_signed_area(piece->outline, n), 1e-12);
    assert_relative(piece->area_3d, flat, 2 * length_tolerance);
}

/* A fold of the piece: on a joined edge, at the flat corners of its ends, with the right sign. */
static void check_fold(const ur_mesh *mesh, const ur_unfolding *u, const placement *where,
                       edge *edges, size_t edge_count, size_t p, const ur_fold *fold, bool *listed)
{
    edge *e = find_edge(edges, edge_count, fold->a, fold->b);
    assert_non_null(e);
    assert_true(joined(mesh, u, where, e));
    assert_int_equal(where[e->first].piece, p);
    assert_false(listed[e - edges]);
    listed[e - edges] = true;
    double angle;
    int sign = concavity(mesh, e, &angle);
    assert_true(angle >= flat_angle);
    if (fold->valley != (sign > 0))
        fail_msg("the fold between vertices %zu and %zu is a %s, but the edge is %s", fold->a,
                 fold->b, fold->valley ? "valley" : "mountain", sign > 0 ? "concave" : "convex");
    assert_true(fabs(fold->angle - angle) < 1e-9);
    double tolerance = 2e-6 * mesh_size(mesh); /* either triangle's copy of the edge */
    assert_true(ur_vec2_distance(fold->start, flat_vertex(mesh, u, where, e->first, fold->a)) <=
                tolerance);
    assert_true(ur_vec2_distance(fold->end, flat_vertex(mesh, u, where, e->first, fold->b)) <=
                tolerance);
}

/* What an unfolding is made of, counted by the test. */
typedef struct tally {
    size_t folds, valleys, flat, seams, boundary;
} tally;

/*
 * Checks everything above and returns the counts found from the net; the
 * seams and group boundaries must not be joined.
 */
static tally check_unfolding(const ur_mesh *mesh, const ur_unfolding *u, const ur_seam *seams,
                             size_t seam_count)
{
    size_t edge_count;
    edge *edges = mesh_edges(mesh, &edge_count);
    placement *where = placements(mesh, u);
    bool *listed = calloc(edge_count, sizeof *listed);
    size_t *open_edges = calloc(u->count, sizeof *open_edges);
    assert_non_null(listed);
    assert_non_null(open_edges);
    tally found = {0};
    for (size_t i = 0; i < edge_count; i++) {
        edge *e = &edges[i];
        double angle;
        if (e->second == SIZE_MAX) {
            found.boundary++;
            open_edges[where[e->first].piece]++;
        } else if (!joined(mesh, u, where, e)) {
            found.seams++;
            open_edges[where[e->first].piece]++;
            open_edges[where[e->second].piece]++;
        } else {
            int sign = concavity(mesh, e, &angle);
            found.flat += angle < flat_angle;
            found.folds += angle >= flat_angle;
            found.valleys += angle >= flat_angle && sign > 0;
        }
        if (e->second != SIZE_MAX && mesh->groups &&
            mesh->groups[e->first] != mesh->groups[e->second])
            assert_false(joined(mesh, u, where, e));
    }
    for (size_t s = 0; s < seam_count; s++)
        assert_false(joined(mesh, u, where, find_edge(edges, edge_count, seams[s].a, seams[s].b)));
    size_t listed_folds = 0;
    for (size_t p = 0; p < u->count; p++) {
        const ur_unfolded_piece *piece = &u->pieces[p];
        check_congruent(mesh, piece);
        check_no_overlap(mesh, piece);
        check_outline(mesh, piece, open_edges[p]);
        for (size_t f = 0; f < piece->fold_count; f++)
            check_fold(mesh, u, where, edges, edge_count, p, &piece->folds[f], listed);
        listed_folds += piece->fold_count;
    }
    assert_int_equal(listed_folds, found.folds); /* every fold is listed */
    assert_int_equal(u->folds, found.folds);
    assert_int_equal(u->valleys, found.valleys);
    assert_int_equal(u->flat, found.flat);
    assert_int_equal(u->seams, found.seams);
    assert_int_equal(u->boundary, found.boundary);
    assert_int_equal(found.folds + found.flat + found.seams + found.boundary, edge_count);
    free(edges);
    free(where);
    free(listed);
    free(open_edges);
    return found;
}

static ur_unfolding unfold(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count)
{
    ur_unfolding u;
    ur_error error;
    if (ur_unfold(mesh, seams, seam_count, &u, &error) != UR_OK)
        fail_msg("ur_unfold: %s", error.message);
    return u;
}

/* ---- the tests ---- */

static void test_cube(void **state)
{
    (void)state;
    ur_mesh mesh = cube(false);
    ur_unfolding u = unfold(&mesh, NULL, 0);
    tally t = check_unfolding(&mesh, &u, NULL, 0);
    /* A cube unfolds in one piece: its 6 squares along 5 of its 12 edges. */
    assert_int_equal(u.count, 1);
    assert_int_equal(t.folds, 5);
    assert_int_equal(t.flat, 6); /* the squares' diagonals */
    assert_int_equal(t.seams, 7);
    assert_int_equal(t.valleys, 0);
    for (size_t f = 0; f < u.pieces[0].fold_count; f++)
        assert_relative(u.pieces[0].folds[f].angle, M_PI / 2, 1e-12);
    assert_relative(u.pieces[0].area_3d, 6 * 40 * 40, 1e-12);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

static void test_icosahedron(void **state)
{
    (void)state;
    ur_mesh mesh = icosahedron();
    ur_unfolding u = unfold(&mesh, NULL, 0);
    tally t = check_unfolding(&mesh, &u, NULL, 0);
    assert_int_equal(t.valleys, 0);
    assert_int_equal(t.flat, 0);
    /* A spanning forest of the 20 faces: 19 folds in one piece, one fewer per piece more. */
    assert_int_equal(t.folds, 20 - u.count);
    assert_int_equal(t.seams, 30 - t.folds);
    for (size_t p = 0; p < u.count; p++)
        for (size_t f = 0; f < u.pieces[p].fold_count; f++)
            assert_relative(u.pieces[p].folds[f].angle, acos(sqrt(5) / 3), 1e-12);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

static void test_torus(void **state)
{
    (void)state;
    ur_mesh mesh = torus(25, 10, 60, 25);
    assert_int_equal(mesh.triangle_count, 500);
    ur_unfolding u = unfold(&mesh, NULL, 0);
    tally t = check_unfolding(&mesh, &u, NULL, 0);
    assert_true(t.valleys > 0);           /* the inside of the ring is concave one way */
    assert_true(t.folds - t.valleys > 0); /* and the outside convex */
    assert_true(t.flat > 0);              /* each quad of a torus is flat: its diagonal */
    /* A piece is a tree of faces (no vertex of a torus is flat): one fold fewer than faces. */
    assert_int_equal(t.folds + t.flat, 500 - u.count);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

static void test_bumpy_sphere(void **state)
{
    (void)state;
    ur_mesh mesh = bumpy_sphere(25, 10);
    assert_int_equal(mesh.triangle_count, 500);
    ur_unfolding u = unfold(&mesh, NULL, 0);
    tally t = check_unfolding(&mesh, &u, NULL, 0);
    assert_true(t.valleys > 0);
    assert_true(t.folds > t.valleys);
    assert_int_equal(t.folds + t.flat, 500 - u.count);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* Around a flat vertex the last triangle lands edge on edge with the first: joined there too. */
static void test_flat_fan_closes(void **state)
{
    (void)state;
    ur_mesh mesh = flat_fan(7);
    ur_unfolding u = unfold(&mesh, NULL, 0);
    tally t = check_unfolding(&mesh, &u, NULL, 0);
    assert_int_equal(u.count, 1);
    assert_int_equal(t.flat, 7);
    assert_int_equal(t.folds + t.seams, 0);
    assert_int_equal(u.pieces[0].outline_count, 7); /* the centre is inside */
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* Float coordinates: the strips still close up along their straight creases, in one sector. */
static void test_float_frustum(void **state)
{
    (void)state;
    ur_mesh mesh = float_frustum(24, 3);
    ur_unfolding u = unfold(&mesh, NULL, 0);
    tally t = check_unfolding(&mesh, &u, NULL, 0);
    assert_int_equal(u.count, 1); /* an annular sector of 114 degrees */
    assert_int_equal(t.boundary, 48);
    assert_int_equal(t.flat, 24 * 3 + 24 * 2); /* diagonals, and rows of one strip */
    assert_int_equal(t.seams, 3);              /* one ruling, cut */
    assert_int_equal(t.folds, 23 * 3);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* An open box: its rim is boundary, a user seam and a group boundary are cut. */
static void test_seams_groups_and_boundary(void **state)
{
    (void)state;
    ur_mesh mesh = cube(true);
    assert_int_equal(mesh.triangle_count, 10);
    mesh.groups[0] = mesh.groups[1] = 1; /* the bottom */
    mesh.group_count = 2;
    ur_seam seams[] = {{0, 4}, {4, 0}}; /* a vertical edge, twice */
    ur_unfolding u = unfold(&mesh, seams, 2);
    tally t = check_unfolding(&mesh, &u, seams, 2);
    assert_int_equal(t.boundary, 4);
    assert_true(u.count >= 2); /* the bottom is a piece of its own */
    assert_true(t.seams >= 5); /* four edges of the bottom and the user's seam */
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

static void expect_refused(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                           const char *text)
{
    ur_unfolding u;
    ur_error error;
    assert_int_equal(ur_unfold(mesh, seams, seam_count, &u, &error), UR_ERROR_INPUT);
    assert_message(error, text);
    assert_null(u.pieces);
    assert_int_equal(u.count, 0);
}

static void test_refusals(void **state)
{
    (void)state;
    ur_mesh mesh = cube(false);
    ur_seam bad_seam = {0, 7}, far_seam = {0, 99};
    expect_refused(&mesh, &bad_seam, 1, "seam 1 (vertices 1 and 8) is not an edge");
    expect_refused(&mesh, &far_seam, 1, "seam 1 names vertex 100");
    size_t swap = mesh.triangles[3][1];
    mesh.triangles[3][1] = mesh.triangles[3][2];
    mesh.triangles[3][2] = swap;
    expect_refused(&mesh, NULL, 0, "not consistently oriented");
    mesh.vertices[5].x = NAN;
    expect_refused(&mesh, NULL, 0, "vertex 6 has a coordinate that is not a finite number");
    mesh.triangle_count = 0;
    expect_refused(&mesh, NULL, 0, "no triangles");
    ur_mesh_free(&mesh);

    builder b = {0}; /* three triangles on one edge */
    for (int i = 0; i < 5; i++)
        add_vertex(&b, ur_vec3_make(i < 2 ? 0 : cos(i), i < 2 ? 0 : sin(i), i == 1 ? 1 : 0));
    for (size_t i = 2; i < 5; i++)
        add_triangle(&b, 0, 1, i, 0);
    ur_mesh fin = build(&b);
    expect_refused(&fin, NULL, 0, "non-manifold edge");
    ur_mesh_free(&fin);

    for (int i = 0; i < 4; i++) /* a triangle of no area beside one of some */
        add_vertex(&b, ur_vec3_make(i, i == 3, 0));
    add_triangle(&b, 0, 1, 3, 0);
    add_triangle(&b, 0, 1, 2, 0);
    ur_mesh flat = build(&b);
    expect_refused(&flat, NULL, 0, "triangle 2 has no area");
    ur_mesh_free(&flat);
}

/* The folds show which side is which: a single fold between two triangles, both ways. */
static void test_one_fold_each_way(void **state)
{
    (void)state;
    for (int way = -1; way <= 1; way += 2) {
        builder b = {0};
        add_vertex(&b, ur_vec3_make(0, 0, 0));
        add_vertex(&b, ur_vec3_make(10, 0, 0));
        add_vertex(&b, ur_vec3_make(5, 8, 0));
        add_vertex(&b, ur_vec3_make(5, -8, 3 * way)); /* up: concave; down: convex */
        add_triangle(&b, 0, 1, 2, 0);
        add_triangle(&b, 1, 0, 3, 0);
        ur_mesh mesh = build(&b);
        ur_unfolding u = unfold(&mesh, NULL, 0);
        check_unfolding(&mesh, &u, NULL, 0);
        assert_int_equal(u.count, 1);
        assert_int_equal(u.pieces[0].fold_count, 1);
        assert_int_equal(u.pieces[0].folds[0].valley, way > 0);
        assert_relative(u.pieces[0].folds[0].angle, atan2(3, 8), 1e-12);
        ur_unfolding_free(&u);
        ur_mesh_free(&mesh);
    }
}

/* ---- flat faces, stray pieces and the room ---- */

static ur_unfolding unfold_with(const ur_mesh *mesh, const ur_unfold_options *options)
{
    ur_unfolding u;
    ur_error error;
    if (ur_unfold_with_options(mesh, NULL, 0, options, &u, &error) != UR_OK)
        fail_msg("ur_unfold_with_options: %s", error.message);
    return u;
}

/* The cube's 12 triangles are 6 flat faces: no fold inside a face, all of its area laid. */
static void test_cube_faces_whole(void **state)
{
    (void)state;
    ur_mesh mesh = cube(false);
    ur_unfolding u = unfold(&mesh, NULL, 0);
    check_unfolding(&mesh, &u, NULL, 0);
    double area = 0;
    for (size_t p = 0; p < u.count; p++) {
        area += u.pieces[p].flat_area;
        for (size_t f = 0; f < u.pieces[p].fold_count; f++) /* cube edges only: 90 degrees */
            assert_relative(u.pieces[p].folds[f].angle, M_PI / 2, 1e-12);
    }
    assert_relative(area, 6 * 40 * 40, 1e-12);
    assert_int_equal(u.flat, 6); /* each square's diagonal */
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/*
 * A torus of quads flat only to 32-bit rounding, as a modeller exports it:
 * every quad's diagonal is a flat join, never a fold (25 x 10 quads).  Its
 * top and bottom rows of quads (centred at 90 and 270 degrees round the
 * tube) lie in one plane each: flat rings of 25 quads, each one piece cut
 * once, so joined flat across 24 of their 25 edges.
 */
static void test_torus_quads_not_folded(void **state)
{
    (void)state;
    ur_mesh mesh = torus(25, 10, 60, 25);
    for (size_t v = 0; v < mesh.vertex_count; v++)
        mesh.vertices[v] = ur_vec3_make((float)mesh.vertices[v].x, (float)mesh.vertices[v].y,
                                        (float)mesh.vertices[v].z);
    ur_unfolding u = unfold(&mesh, NULL, 0);
    tally t = check_unfolding(&mesh, &u, NULL, 0);
    assert_int_equal(t.flat, 250 + 2 * 24);
    for (size_t p = 0; p < u.count; p++)
        for (size_t f = 0; f < u.pieces[p].fold_count; f++) {
            const ur_fold *fold = &u.pieces[p].folds[f];
            size_t i = fold->a / 10, j = fold->a % 10, k = fold->b / 10, l = fold->b % 10;
            bool across = (i + 1) % 25 == k || (k + 1) % 25 == i;
            bool around = (j + 1) % 10 == l || (l + 1) % 10 == j;
            if (across && around)
                fail_msg("a fold on the diagonal from vertex %zu to %zu", fold->a, fold->b);
        }
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* Two triangles turning by 0.3 degrees are one flat face; with a flat angle of 0.1 a fold. */
static void test_flat_angle(void **state)
{
    (void)state;
    builder b = {0};
    add_vertex(&b, ur_vec3_make(0, 0, 0));
    add_vertex(&b, ur_vec3_make(10, 0, 0));
    add_vertex(&b, ur_vec3_make(5, 8, 0));
    add_vertex(&b, ur_vec3_make(5, -8, -8 * tan(0.3 * M_PI / 180)));
    add_triangle(&b, 0, 1, 2, 0);
    add_triangle(&b, 1, 0, 3, 0);
    ur_mesh mesh = build(&b);
    ur_unfold_options options;
    ur_unfold_options_default(&options);
    ur_unfolding u = unfold_with(&mesh, &options);
    assert_int_equal(u.count, 1);
    assert_int_equal(u.flat, 1);
    assert_int_equal(u.folds, 0);
    assert_int_equal(u.pieces[0].face_count, 1);
    ur_unfolding_free(&u);
    options.flat_angle = flat_angle = 0.1 * M_PI / 180;
    u = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &u, NULL, 0);
    flat_angle = UR_UNFOLD_FLAT_ANGLE;
    assert_int_equal(u.folds, 1);
    assert_int_equal(u.pieces[0].face_count, 2);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* A 3 x 3 grid of 20 mm quads in z = 0, the centre quad a group of its own. */
static ur_mesh grid_with_centre(void)
{
    builder b = {0};
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++)
            add_vertex(&b, ur_vec3_make(20 * i, 20 * j, 0));
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            size_t v = (size_t)(4 * j + i), group = i == 1 && j == 1;
            add_triangle(&b, v, v + 1, v + 5, group);
            add_triangle(&b, v, v + 5, v + 4, group);
        }
    return build(&b);
}

/*
 * The ring of 8 coplanar quads round the centre is one flat face round a
 * hole: one piece, cut along one edge from the hole to the outside (both
 * sides of the cut lie on each other), not a quad cut off.
 */
static void test_ring_one_piece(void **state)
{
    (void)state;
    ur_mesh mesh = grid_with_centre();
    ur_unfolding u = unfold(&mesh, NULL, 0);
    assert_int_equal(u.count, 2);
    size_t ring = u.pieces[0].triangle_count == 16 ? 0 : 1;
    assert_int_equal(u.pieces[ring].triangle_count, 16);
    assert_int_equal(u.pieces[1 - ring].triangle_count, 2);
    for (size_t p = 0; p < 2; p++) {
        check_congruent(&mesh, &u.pieces[p]);
        check_no_overlap(&mesh, &u.pieces[p]);
        assert_int_equal(u.pieces[p].fold_count, 0);
    }
    /* The outline runs round the outside, along the cut, round the hole and back. */
    assert_relative(ur_polygon_signed_area(u.pieces[ring].outline, u.pieces[ring].outline_count),
                    8 * 400, 1e-12);
    assert_int_equal(u.pieces[ring].outline_count, 12 + 4 + 2);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/*
 * A 20 mm plate round a 6 mm hole, flat, and on its right a 7 x 20 mm
 * flange, a fan round its middle lifted 0.1 mm: the fan's triangles fold
 * by 0.57 to 1.7 degrees, more than the flat angle, and close round the
 * middle to 5.7e-4 radians short of a turn.  A separate triangle 10 m
 * away makes the mesh that large, so that the unfolding joins edges that
 * land within 10 um: the fan closes with a gap of about 6 um at its far
 * corners, 0.03 mm2 in all, 6e-5 of the piece.  So CAD meshes' sliver
 * triangles close (OpenCASCADE's motor.stl); the check of the outline,
 * which runs up a slit to the hole, allows it as a band of u->eps along
 * the outline, where a millionth of the area alone refused the piece
 * (exit 1, "overlaps itself").
 */
static ur_mesh plate_with_lifted_flange(void)
{
    builder b = {0};
    double outer[4][2] = {{10, -10}, {10, 10}, {-10, 10}, {-10, -10}};
    size_t o[4], in[4];
    for (int k = 0; k < 4; k++) {
        o[k] = add_vertex(&b, ur_vec3_make(outer[k][0], outer[k][1], 0));
        in[k] = add_vertex(&b, ur_vec3_make(0.3 * outer[k][0], 0.3 * outer[k][1], 0));
    }
    for (int k = 0; k < 4; k++) {
        int next = (k + 1) % 4;
        add_triangle(&b, o[k], o[next], in[next], 0);
        add_triangle(&b, o[k], in[next], in[k], 0);
    }
    size_t lifted = add_vertex(&b, ur_vec3_make(13.5, 0, 0.1));
    size_t right[2] = {add_vertex(&b, ur_vec3_make(17, -10, 0)),
                       add_vertex(&b, ur_vec3_make(17, 10, 0))};
    add_triangle(&b, lifted, o[0], right[0], 0);
    add_triangle(&b, lifted, right[0], right[1], 0);
    add_triangle(&b, lifted, right[1], o[1], 0);
    add_triangle(&b, lifted, o[1], o[0], 0);
    size_t far[3];
    for (int k = 0; k < 3; k++)
        far[k] = add_vertex(&b, ur_vec3_make(10000 + 5 * (k == 1), 5 * (k == 2), 0));
    add_triangle(&b, far[0], far[1], far[2], 1);
    return build(&b);
}

static void test_piece_closing_within_contact(void **state)
{
    (void)state;
    ur_mesh mesh = plate_with_lifted_flange();
    ur_unfolding u = unfold(&mesh, NULL, 0);
    assert_int_equal(u.count, 2);
    size_t ring = u.pieces[0].triangle_count > 1 ? 0 : 1;
    const ur_unfolded_piece *piece = &u.pieces[ring];
    assert_int_equal(piece->triangle_count, 12);
    check_congruent(&mesh, piece);
    double triangles = 0;
    for (size_t i = 0; i < piece->triangle_count; i++)
        triangles += ur_polygon_signed_area(piece->flat[i], 3);
    /* The plate's 364 mm2 and the flange's 140, and what the lifted middle adds. */
    /* What the 3D triangles have: the plate's 364 mm2, the flange's 140 and a little more. */
    assert_true(triangles > 504 && triangles < 504.1);
    /*
     * The outline holds the gap besides, about 5.7e-4 radians times half
     * the square of the fan's 10.6 mm edges: more than a millionth of the
     * piece, far less than the band.
     */
    double gap = ur_polygon_signed_area(piece->outline, piece->outline_count) - triangles;
    assert_true(gap > 10e-6 * triangles && gap < 0.05);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* The flat position of corner k of triangle i of the piece, moved. */
static ur_vec2 moved_corner(const ur_vec2 corner, ur_vec2 from, double c, double s, ur_vec2 to)
{
    ur_vec2 d = ur_vec2_sub(corner, from);
    return ur_vec2_add(to, ur_vec2_make(c * d.x - s * d.y, s * d.x + c * d.y));
}

static double point_triangle_distance(ur_vec2 p, const ur_vec2 t[3])
{
    bool inside = true;
    double nearest = INFINITY;
    for (int k = 0; k < 3; k++) {
        ur_vec2 a = t[k], b = t[(k + 1) % 3], d = ur_vec2_sub(b, a);
        inside = inside && orientation(a, b, p) > 0;
        double s = fmax(0, fmin(1, ur_vec2_dot(ur_vec2_sub(p, a), d) / ur_vec2_dot(d, d)));
        nearest = fmin(nearest, ur_vec2_distance(p, ur_vec2_add_scaled(a, d, s)));
    }
    return inside ? 0 : nearest;
}

/* Whether the corners of one triangle come within margin of the other anywhere but at ends. */
static bool touches_away_from(const ur_vec2 a[3], const ur_vec2 b[3], ur_vec2 end0, ur_vec2 end1,
                              double margin)
{
    for (int k = 0; k < 3; k++) {
        bool at_end =
            ur_vec2_distance(a[k], end0) <= margin || ur_vec2_distance(a[k], end1) <= margin;
        if (!at_end && point_triangle_distance(a[k], b) <= margin)
            return true;
    }
    return false;
}

/*
 * Whether piece s, moved rigidly so that its copy of the edge from vertex
 * va to vb lies on piece n's, would overlap n or touch it anywhere but at
 * the edge's ends: then it cannot join n there.
 */
static bool blocked(const ur_mesh *mesh, const ur_unfolding *u, const placement *where, size_t ts,
                    size_t tn, size_t va, size_t vb)
{
    const ur_unfolded_piece *s = &u->pieces[where[ts].piece], *n = &u->pieces[where[tn].piece];
    ur_vec2 sa = flat_vertex(mesh, u, where, ts, va), sb = flat_vertex(mesh, u, where, ts, vb);
    ur_vec2 na = flat_vertex(mesh, u, where, tn, va), nb = flat_vertex(mesh, u, where, tn, vb);
    ur_vec2 ds = ur_vec2_sub(sb, sa), dn = ur_vec2_sub(nb, na);
    double angle = atan2(ur_vec2_cross(ds, dn), ur_vec2_dot(ds, dn));
    double margin = 1e-6 * mesh_size(mesh);
    for (size_t i = 0; i < s->triangle_count; i++) {
        ur_vec2 moved[3];
        for (int k = 0; k < 3; k++)
            moved[k] = moved_corner(s->flat[i][k], sa, cos(angle), sin(angle), na);
        for (size_t j = 0; j < n->triangle_count; j++) {
            if (s->triangles[i] == ts && n->triangles[j] == tn)
                continue; /* the two faces of the edge */
            if (overlap(moved, n->flat[j], margin) ||
                touches_away_from(moved, n->flat[j], na, nb, margin) ||
                touches_away_from(n->flat[j], moved, na, nb, margin))
                return true;
        }
    }
    return false;
}

/*
 * The head: no piece of a single face could have joined a neighbour: across
 * every one of its seams, moved onto the piece on the other side, it would
 * overlap it or touch it away from the seam.
 */
static void test_head_no_stray_faces(void **state)
{
    (void)state;
    ur_mesh mesh = cleaned_mesh_file("samples/head.obj");
    ur_unfold_options options;
    ur_unfold_options_default(&options);
    options.time_budget = 0; /* the greedy joining and nothing more: every edge tried */
    ur_unfolding u = unfold_with(&mesh, &options);
    allow_projection();
    check_unfolding(&mesh, &u, NULL, 0);
    length_tolerance = 1e-9;
    size_t edge_count;
    edge *edges = mesh_edges(&mesh, &edge_count);
    placement *where = placements(&mesh, &u);
    size_t singles = 0;
    for (size_t i = 0; i < edge_count; i++) {
        const edge *e = &edges[i];
        if (e->second == SIZE_MAX || where[e->first].piece == where[e->second].piece)
            continue;
        for (int side = 0; side < 2; side++) {
            size_t ts = side ? e->second : e->first, tn = side ? e->first : e->second;
            if (u.pieces[where[ts].piece].face_count != 1)
                continue;
            singles++;
            if (!blocked(&mesh, &u, where, ts, tn, e->low, e->high))
                fail_msg("the single face of triangle %zu fits its neighbour across the edge from "
                         "vertex %zu to %zu",
                         ts + 1, e->low + 1, e->high + 1);
        }
    }
    assert_int_equal(u.single_face, 0); /* and in fact there are none */
    (void)singles;
    free(edges);
    free(where);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* The sides of the smallest rectangle round the points (all directions of pairs tried). */
static void smallest_rectangle(const ur_vec2 *points, size_t count, double *length, double *width)
{
    double best = INFINITY;
    for (size_t i = 0; i < count; i++)
        for (size_t j = i + 1; j < count; j++) {
            ur_vec2 d = ur_vec2_sub(points[j], points[i]);
            if (!(ur_vec2_length(d) > 0))
                continue;
            d = ur_vec2_scale(d, 1 / ur_vec2_length(d));
            double low = INFINITY, high = -INFINITY, down = INFINITY, up = -INFINITY;
            for (size_t k = 0; k < count; k++) {
                double x = ur_vec2_dot(points[k], d), y = ur_vec2_cross(d, points[k]);
                low = fmin(low, x), high = fmax(high, x), down = fmin(down, y), up = fmax(up, y);
            }
            if ((high - low) * (up - down) < best) {
                best = (high - low) * (up - down);
                *length = fmax(high - low, up - down);
                *width = fmin(high - low, up - down);
            }
        }
}

/* The default options with a room of length x width mm. */
static ur_unfold_options room_options(double length, double width)
{
    ur_unfold_options options;
    ur_unfold_options_default(&options);
    options.room_length = length;
    options.room_width = width;
    return options;
}

/* The defaults in a room of 150 x 200 mm, which the sample 100 mm cube fits in 3 pieces. */
static ur_unfold_options cube_room_options(void)
{
    return room_options(150, 200);
}

/*
 * A 100 mm cube in a room of 200 x 150 mm: two squares side by side fit,
 * three in a row or an L do not, so its six squares need 3 pieces.
 */
static void test_room_splits(void **state)
{
    (void)state;
    ur_mesh mesh = cleaned_mesh_file("samples/cube.obj");
    ur_unfold_options options = cube_room_options();
    ur_unfolding u = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &u, NULL, 0);
    assert_int_equal(u.count, 3);
    for (size_t p = 0; p < u.count; p++) {
        double length = INFINITY, width = INFINITY;
        smallest_rectangle(u.pieces[p].outline, u.pieces[p].outline_count, &length, &width);
        assert_true(length <= 200 + 1e-9 && width <= 150 + 1e-9);
    }
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* An accordion of 11 panels, each 10 x 2 mm flat, folded 60 degrees: flat, a 110 x 2 mm strip. */
static ur_mesh accordion(void)
{
    builder b = {0};
    const double turn = M_PI / 6;
    for (int i = 0; i <= 11; i++)
        for (int j = 0; j < 2; j++)
            add_vertex(&b, ur_vec3_make(10 * i * cos(turn), 2.0 * j, 10 * (i % 2) * sin(turn)));
    for (size_t i = 0; i < 11; i++) {
        add_triangle(&b, 2 * i, 2 * i + 2, 2 * i + 3, 0);
        add_triangle(&b, 2 * i, 2 * i + 3, 2 * i + 1, 0);
    }
    return build(&b);
}

/* Whether the outline fits length x width at one of 18,000 turns (a scan, not the library's). */
static bool fits_at_some_turn(const ur_vec2 *outline, size_t count, double length, double width)
{
    for (int step = 0; step < 18000; step++) {
        ur_box box = turned_box_of(outline, count, step * M_PI / 18000);
        if (ur_box_width(box) <= length && ur_box_height(box) <= width)
            return true;
    }
    return false;
}

/*
 * The accordion's 110 x 2 mm strip fits a 100 x 50 mm room neither level
 * nor on end, but turned by about 25 degrees (the room's diagonal is
 * 111.8 mm): one piece, which a scan of turns finds fitting; a 100 x 5 mm
 * room (diagonal 100.1 mm) takes it at no turn: two pieces.
 */
static void test_room_taken_turned(void **state)
{
    (void)state;
    ur_mesh mesh = accordion();
    ur_unfold_options options = room_options(100, 50);
    ur_unfolding u = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &u, NULL, 0);
    assert_int_equal(u.count, 1);
    double length = INFINITY, width = INFINITY;
    smallest_rectangle(u.pieces[0].outline, u.pieces[0].outline_count, &length, &width);
    assert_true(fabs(length - 110) < 1e-6 && fabs(width - 2) < 1e-6);
    assert_true(fits_at_some_turn(u.pieces[0].outline, u.pieces[0].outline_count, 100, 50));
    ur_unfolding_free(&u);
    options.room_width = 5;
    u = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &u, NULL, 0);
    assert_int_equal(u.count, 2);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/* Options as the mesh job sets them for 6 mm tabs: counted steps, a 3 mm gap, the room given. */
static ur_unfold_options papercraft_options(double room_length, double room_width)
{
    ur_unfold_options options = room_options(room_length, room_width);
    options.time_budget = 0;
    options.min_gap = 3;
    return options;
}

/* The mesh unfolded, its pieces checked (nearly flat faces laid flat). */
static ur_unfolding checked_unfolding(const ur_mesh *mesh, const ur_unfold_options *options)
{
    ur_unfolding u = unfold_with(mesh, options);
    allow_projection();
    check_unfolding(mesh, &u, NULL, 0);
    length_tolerance = 1e-9;
    return u;
}

/*
 * Steps past the first 200 are kept only when, after the last run, they
 * leave neither more pieces nor more seams joined without the gap: the
 * sample head and UV sphere with a 3 mm gap in an A3 sheet's room (397 x
 * 274 mm) never come out worse with 700 steps than with 200, and the head
 * comes out in fewer pieces.
 */
static void test_longer_search_only_when_it_pays(void **state)
{
    (void)state;
    const char *files[] = {"samples/head.obj", "samples/uvsphere.obj"};
    for (size_t f = 0; f < 2; f++) {
        ur_mesh mesh = cleaned_mesh_file(files[f]);
        ur_unfold_options options = papercraft_options(397, 274);
        ur_unfolding u[2];
        for (int longer = 0; longer < 2; longer++) {
            options.max_steps = longer ? 700 : 200;
            u[longer] = checked_unfolding(&mesh, &options);
        }
        print_message("%s: %zu pieces, %zu without the gap in 200 steps; %zu, %zu in 700\n",
                      files[f], u[0].count, u[0].gap_breaks, u[1].count, u[1].gap_breaks);
        assert_true(u[1].count <= u[0].count && u[1].gap_breaks <= u[0].gap_breaks);
        if (f == 0)
            assert_true(u[1].count < u[0].count);
        ur_unfolding_free(&u[0]);
        ur_unfolding_free(&u[1]);
        ur_mesh_free(&mesh);
    }
}

/*
 * A walk that finds nothing better for 100 steps starts again from the
 * first order while the steps last: the level search takes all of them
 * (the turned one, half as many, comes on top), and the sample UV sphere
 * comes out in 6 pieces in 700 steps against 7 in 200.  Stopping at the
 * first stall instead, it took 600 steps of 700 and stayed at 7.
 */
static void test_stalled_search_starts_again(void **state)
{
    (void)state;
    ur_mesh mesh = cleaned_mesh_file("samples/uvsphere.obj");
    ur_unfold_options options = papercraft_options(397, 274);
    ur_unfolding u[2];
    size_t steps[2] = {200, 700};
    for (int k = 0; k < 2; k++) {
        options.max_steps = steps[k];
        u[k] = checked_unfolding(&mesh, &options);
    }
    print_message("uvsphere: %zu pieces in %zu steps (of 200), %zu in %zu (of 700)\n", u[0].count,
                  u[0].steps, u[1].count, u[1].steps);
    assert_true(u[0].steps >= 200);
    assert_true(u[1].steps >= 700);
    assert_true(u[1].count < u[0].count);
    ur_unfolding_free(&u[0]);
    ur_unfolding_free(&u[1]);
    ur_mesh_free(&mesh);
}

/*
 * steps_per_piece: a search whose first 200 steps leave many pieces goes
 * on (8 steps a piece, up to 1,000 in all) and comes out in no more
 * pieces; one that leaves few takes max_steps as before.  The sample UV
 * sphere in a 60 x 40 mm room comes in 47 pieces after 200 steps (45 after
 * 8 steps a piece), in a 397 x 274 mm room in 7.
 */
static void test_steps_for_many_pieces(void **state)
{
    (void)state;
    ur_mesh mesh = cleaned_mesh_file("samples/uvsphere.obj");
    double rooms[2][2] = {{60, 40}, {397, 274}};
    for (int r = 0; r < 2; r++) {
        ur_unfold_options options = papercraft_options(rooms[r][0], rooms[r][1]);
        options.max_steps = 200;
        ur_unfolding u[2];
        for (int k = 0; k < 2; k++) {
            options.steps_per_piece = k ? 8 : 0;
            u[k] = checked_unfolding(&mesh, &options);
        }
        print_message("room %g x %g: %zu pieces in %zu steps; by pieces %zu in %zu\n", rooms[r][0],
                      rooms[r][1], u[0].count, u[0].steps, u[1].count, u[1].steps);
        if (r == 0) {
            assert_true(u[0].count >= 40);
            assert_true(u[1].steps >= u[0].steps + 8 * 40 - 200);
            assert_true(u[1].count <= u[0].count);
        } else {
            assert_true(8 * u[0].count < 200);
            assert_int_equal(u[1].steps, u[0].steps);
            assert_int_equal(u[1].count, u[0].count);
        }
        ur_unfolding_free(&u[0]);
        ur_unfolding_free(&u[1]);
    }
    ur_mesh_free(&mesh);
}

/* A face larger than the room cannot be split: refused, naming it and its size. */
static void test_face_larger_than_room(void **state)
{
    (void)state;
    ur_mesh mesh = cleaned_mesh_file("samples/cube.obj");
    ur_unfold_options options;
    ur_unfold_options_default(&options);
    options.room_length = options.room_width = 90;
    ur_unfolding u;
    ur_error error;
    assert_int_equal(ur_unfold_with_options(&mesh, NULL, 0, &options, &u, &error), UR_ERROR_INPUT);
    assert_message(error, "is 100.0 x 100.0 mm, larger than the room of 90.0 x 90.0 mm");
    assert_message(error, "the flat face of triangle ");
    assert_null(u.pieces);
    options.room_length = -1;
    assert_int_equal(ur_unfold_with_options(&mesh, NULL, 0, &options, &u, &error), UR_ERROR_INPUT);
    ur_mesh_free(&mesh);
}

/* A seed and a number of steps give the same unfolding every time; progress is told. */
static void count_calls(void *context, const char *phase, double fraction)
{
    assert_non_null(phase);
    assert_true(fraction >= 0 && fraction <= 1);
    (*(size_t *)context)++;
}

/* The same pieces, triangle for triangle and corner for corner, after as many steps. */
static void assert_same_pieces(const ur_unfolding *a, const ur_unfolding *b)
{
    assert_int_equal(a->count, b->count);
    assert_int_equal(a->seams, b->seams);
    assert_int_equal(a->steps, b->steps);
    assert_int_equal(a->folds, b->folds);
    assert_int_equal(a->valleys, b->valleys);
    assert_int_equal(a->flat, b->flat);
    assert_int_equal(a->boundary, b->boundary);
    assert_int_equal(a->single_face, b->single_face);
    assert_int_equal(a->gap_breaks, b->gap_breaks);
    assert_true(a->seam_length == b->seam_length);
    for (size_t p = 0; p < a->count; p++) {
        assert_int_equal(a->pieces[p].triangle_count, b->pieces[p].triangle_count);
        assert_memory_equal(a->pieces[p].triangles, b->pieces[p].triangles,
                            a->pieces[p].triangle_count * sizeof *a->pieces[p].triangles);
        assert_memory_equal(a->pieces[p].flat, b->pieces[p].flat,
                            a->pieces[p].triangle_count * sizeof *a->pieces[p].flat);
        assert_int_equal(a->pieces[p].outline_count, b->pieces[p].outline_count);
        assert_memory_equal(a->pieces[p].outline, b->pieces[p].outline,
                            a->pieces[p].outline_count * sizeof *a->pieces[p].outline);
        assert_int_equal(a->pieces[p].fold_count, b->pieces[p].fold_count);
        assert_int_equal(a->pieces[p].face_count, b->pieces[p].face_count);
    }
}

static void test_search_repeats(void **state)
{
    (void)state;
    ur_mesh mesh = bumpy_sphere(25, 10);
    ur_unfold_options options;
    ur_unfold_options_default(&options);
    options.time_budget = 1000; /* the steps end it */
    options.max_steps = 40;
    options.seed = 7;
    size_t calls = 0;
    options.progress = count_calls;
    options.progress_context = &calls;
    ur_unfolding first = unfold_with(&mesh, &options), second = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &first, NULL, 0);
    assert_true(calls >= 4);
    assert_same_pieces(&first, &second);
    options.time_budget = 0;
    options.max_steps = 0;
    ur_unfolding greedy = unfold_with(&mesh, &options);
    assert_true(first.count <= greedy.count); /* the search keeps the best it saw */
    ur_unfolding_free(&first);
    ur_unfolding_free(&second);
    ur_unfolding_free(&greedy);
    ur_mesh_free(&mesh);
}

/*
 * The search with the room turned, run beside the level one (threads 2)
 * on a state of its own, finds what it finds after it (threads 1): the
 * sample UV sphere with a 3 mm gap in a 100 x 60 mm room, 100 level steps
 * and 50 turned, where the turned search's best (29 pieces) beats the
 * level one's (30; seen with a print in the library), so that its order
 * is the one kept and run again.  (Here the turned search, slower a step
 * in so small a room, has ended after the level one whenever it was
 * looked at, and the level thread runs its order again; pieces built
 * ahead are test_turned_pieces_built_ahead's.)
 */
static void test_turned_search_beside(void **state)
{
    (void)state;
    ur_mesh mesh = cleaned_mesh_file("samples/uvsphere.obj");
    ur_unfold_options options = papercraft_options(100, 60);
    options.max_steps = 100;
    ur_unfolding after = checked_unfolding(&mesh, &options);
    options.threads = 2;
    ur_unfolding beside = checked_unfolding(&mesh, &options);
    print_message("%zu pieces in %zu steps after, %zu in %zu beside\n", after.count, after.steps,
                  beside.count, beside.steps);
    assert_int_equal(after.steps, 150); /* both searches ran */
    assert_same_pieces(&after, &beside);
    ur_unfolding_free(&after);
    ur_unfolding_free(&beside);
    ur_mesh_free(&mesh);
}

/*
 * The accordion in a 100 x 50 mm room (a 0.5 mm gap) is one piece turned
 * and two level: the turned search ends at its first run, at the fewest
 * pieces there can be, and builds its pieces while the level one goes on
 * through its 1,000 steps; they are the pieces the search after it makes
 * (threads 1).
 */
static void test_turned_pieces_built_ahead(void **state)
{
    (void)state;
    ur_mesh mesh = accordion();
    ur_unfold_options options = papercraft_options(100, 50);
    options.max_steps = 1000;
    options.min_gap = 0.5; /* a last run, after the search's */
    ur_unfolding after = unfold_with(&mesh, &options);
    options.threads = 2;
    ur_unfolding beside = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &beside, NULL, 0);
    assert_int_equal(beside.count, 1);
    assert_same_pieces(&after, &beside);
    ur_unfolding_free(&after);
    ur_unfolding_free(&beside);
    ur_mesh_free(&mesh);
}

/* What ur_unfold_options.started was told, and what it answers. */
typedef struct start_seen {
    size_t calls;
    double cost;
    bool go_on;
    size_t threads_given; /* set for the search when go_on */
} start_seen;

static bool note_start(void *context, double cost, size_t *threads)
{
    start_seen *seen = context;
    seen->calls++;
    seen->cost = cost;
    if (seen->go_on && seen->threads_given)
        *threads = seen->threads_given;
    return seen->go_on;
}

/*
 * The started callback is told the cost of the run the search starts
 * from: with no search and no gap, that run's pieces are the unfolding's
 * (the sample cube in a 150 x 200 mm room: 3).  Told to stop, the
 * unfolding ends there with UR_ERROR_CANCELLED and no pieces; given two
 * threads, it unfolds as with one (the sample UV sphere in a 60 x 40 mm
 * room, with its turned search).
 */
static void test_started_callback(void **state)
{
    (void)state;
    ur_mesh cube = cleaned_mesh_file("samples/cube.obj");
    ur_unfold_options options = cube_room_options();
    options.time_budget = 0;
    start_seen seen = {.go_on = true};
    options.started = note_start;
    options.started_context = &seen;
    ur_unfolding u = unfold_with(&cube, &options);
    assert_int_equal(seen.calls, 1);
    assert_true(seen.cost == (double)u.count);
    assert_int_equal(u.count, 3);
    ur_unfolding_free(&u);
    seen = (start_seen){.go_on = false};
    ur_error error;
    assert_int_equal(ur_unfold_with_options(&cube, NULL, 0, &options, &u, &error),
                     UR_ERROR_CANCELLED);
    assert_message(error, "stopped after its first run");
    assert_int_equal(u.count, 0);
    assert_null(u.pieces);
    assert_int_equal(seen.calls, 1);
    ur_mesh_free(&cube);

    ur_mesh sphere = cleaned_mesh_file("samples/uvsphere.obj");
    options = papercraft_options(60, 40);
    options.max_steps = 60;
    ur_unfolding one = checked_unfolding(&sphere, &options);
    seen = (start_seen){.go_on = true, .threads_given = 2};
    options.started = note_start;
    options.started_context = &seen;
    ur_unfolding two = checked_unfolding(&sphere, &options);
    assert_int_equal(seen.calls, 1);
    assert_true(seen.cost >= (double)two.count);
    assert_int_equal(two.steps, 90);
    assert_same_pieces(&one, &two);
    ur_unfolding_free(&one);
    ur_unfolding_free(&two);
    ur_mesh_free(&sphere);
}

/* The fractions the search reported, in order. */
typedef struct reported {
    double fractions[4096];
    size_t count;
} reported;

static void note_improving(void *context, const char *phase, double fraction)
{
    reported *r = context;
    if (strcmp(phase, "improving") == 0 && r->count < 4096)
        r->fractions[r->count++] = fraction;
}

/* The mesh unfolded in the room with 200 steps and 8 a piece, the search's reports noted in r. */
static ur_unfolding reporting_unfolding(const ur_mesh *mesh, double room_length, double room_width,
                                        reported *r)
{
    ur_unfold_options options = papercraft_options(room_length, room_width);
    options.max_steps = 200;
    options.steps_per_piece = 8;
    r->count = 0;
    options.progress = note_improving;
    options.progress_context = r;
    return checked_unfolding(mesh, &options);
}

/*
 * The "improving" line only moves forward, through all the search's parts
 * (the first 200 steps, the steps the pieces ask for, the turned room):
 * the sample UV sphere in a 60 x 40 mm room takes all three.  Before,
 * each part started again from 0.
 */
static void test_progress_moves_forward(void **state)
{
    (void)state;
    ur_mesh mesh = cleaned_mesh_file("samples/uvsphere.obj");
    static reported r;
    ur_unfolding u = reporting_unfolding(&mesh, 60, 40, &r);
    print_message("%zu reports over %zu steps, the last at %.3f\n", r.count, u.steps,
                  r.count ? r.fractions[r.count - 1] : 0.0);
    assert_true(u.steps > 400); /* a second part and a turned one */
    assert_true(r.count >= u.steps / 32);
    for (size_t k = 0; k < r.count; k++) {
        assert_true(r.fractions[k] >= 0 && r.fractions[k] <= 1);
        if (k > 0)
            assert_true(r.fractions[k] >= r.fractions[k - 1]);
    }
    assert_true(r.fractions[r.count - 1] > 2.0 / 3); /* the turned search's third */
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

/*
 * When the pieces ask for no more steps than the first 200, the line goes
 * on to the end of the level search's window (two thirds, the turned
 * search taking the last third) instead of stopping half way: a 48 x 24
 * UV sphere of radius 60 mm in a 390 x 270 mm room, whose first run makes
 * more than 25 pieces (more than 200 steps at 8 a piece) and whose search
 * ends with fewer.  No two reports are further apart than a few of the 32
 * steps between them (before: from a third to two thirds at once).
 */
static void test_progress_follows_the_pieces(void **state)
{
    (void)state;
    ur_mesh mesh = uv_sphere(48, 24, 60);
    static reported r;
    ur_unfolding u = reporting_unfolding(&mesh, 390, 270, &r);
    print_message("%zu pieces in %zu steps, %zu reports:", u.count, u.steps, r.count);
    for (size_t k = 0; k < r.count; k++)
        print_message(" %.3f", r.fractions[k]);
    print_message("\n");
    assert_true(u.steps == 300); /* 200 level, 100 turned: the pieces asked for no more */
    assert_true(r.fractions[0] == 0);
    for (size_t k = 1; k < r.count; k++) {
        assert_true(r.fractions[k] >= r.fractions[k - 1]);
        assert_true(r.fractions[k] - r.fractions[k - 1] < 0.15);
    }
    assert_true(r.fractions[r.count - 1] > 0.9);
    ur_unfolding_free(&u);
    ur_mesh_free(&mesh);
}

static double point_segment_distance(ur_vec2 p, ur_vec2 a, ur_vec2 b)
{
    ur_vec2 d = ur_vec2_sub(b, a);
    double s = fmax(0.0, fmin(1.0, ur_vec2_dot(ur_vec2_sub(p, a), d) / ur_vec2_dot(d, d)));
    return ur_vec2_distance(p, ur_vec2_add_scaled(a, d, s));
}

static double segment_distance(ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d)
{
    if (crosses(a, b, c, d))
        return 0;
    return fmin(fmin(point_segment_distance(a, c, d), point_segment_distance(b, c, d)),
                fmin(point_segment_distance(c, a, b), point_segment_distance(d, a, b)));
}

/* The triangle of the piece with outline edge i (its flat corners at both ends). */
static size_t triangle_of_outline_edge(const ur_unfolded_piece *piece, size_t i, double tolerance)
{
    ur_vec2 a = piece->outline[i], b = piece->outline[(i + 1) % piece->outline_count];
    for (size_t t = 0; t < piece->triangle_count; t++)
        for (int k = 0; k < 3; k++)
            if (ur_vec2_distance(piece->flat[t][k], a) <= tolerance &&
                ur_vec2_distance(piece->flat[t][(k + 1) % 3], b) <= tolerance)
                return t;
    fail_msg("outline edge %zu is no triangle's edge", i);
    return 0;
}

/* Whether two triangles of a piece have a corner of one mesh vertex at one flat point. */
static bool share_flat_vertex(const ur_mesh *mesh, const ur_unfolded_piece *piece, size_t t,
                              size_t q, double tolerance)
{
    const size_t *a = mesh->triangles[piece->triangles[t]],
                 *b = mesh->triangles[piece->triangles[q]];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (a[i] == b[j] && ur_vec2_distance(piece->flat[t][i], piece->flat[q][j]) <= tolerance)
                return true;
    return false;
}

/*
 * How many pairs of outline edges of the pieces, not next to each other,
 * come closer than gap, other than those of triangles that meet at a flat
 * vertex (round which edges must come close).
 */
static size_t narrow_gaps(const ur_mesh *mesh, const ur_unfolding *u, double gap)
{
    double tolerance = 2e-6 * mesh_size(mesh);
    size_t count = 0;
    for (size_t p = 0; p < u->count; p++) {
        const ur_unfolded_piece *piece = &u->pieces[p];
        size_t n = piece->outline_count;
        for (size_t i = 0; i < n; i++)
            for (size_t k = i + 2; k < n; k++) {
                if ((k + 1) % n == i)
                    continue;
                const ur_vec2 *o = piece->outline;
                if (segment_distance(o[i], o[(i + 1) % n], o[k], o[(k + 1) % n]) >= gap)
                    continue;
                size_t t = triangle_of_outline_edge(piece, i, tolerance);
                size_t q = triangle_of_outline_edge(piece, k, tolerance);
                if (!share_flat_vertex(mesh, piece, t, q, tolerance))
                    count++;
            }
    }
    return count;
}

/* With a gap asked for, no two edges of a piece's outline come closer but at a flat vertex. */
static void test_min_gap(void **state)
{
    (void)state;
    ur_mesh mesh = sphere(24, 11, 50);
    ur_unfold_options options;
    ur_unfold_options_default(&options);
    options.max_steps = 50;
    options.time_budget = 0; /* the steps end it, however loaded the machine */
    options.gap_strands_faces = true;
    options.gap_both_sides = true;
    double gap = 3.0;
    ur_unfolding any = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &any, NULL, 0);
    assert_true(narrow_gaps(&mesh, &any, gap) > 0); /* without it, bands lie close */
    options.min_gap = gap;
    ur_unfolding apart = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &apart, NULL, 0);
    assert_int_equal(narrow_gaps(&mesh, &apart, gap), 0);
    ur_unfolding_free(&any);
    ur_unfolding_free(&apart);
    ur_mesh_free(&mesh);
}

/*
 * No search, and a gap of 2.5 mm kept everywhere, on both sides of a slit,
 * even where a face is left a piece of its own.
 */
static ur_unfold_options strict_gap_options(void)
{
    ur_unfold_options options;
    ur_unfold_options_default(&options);
    options.max_steps = 0;
    options.time_budget = 0;
    options.min_gap = 2.5;
    options.gap_strands_faces = true;
    options.gap_both_sides = true;
    return options;
}

/*
 * A UV sphere's pole triangles close a fan whose last wedge is narrower
 * than the gap: kept strictly, the gap strands some of them as pieces of
 * one face; by default each joins a neighbour without it, and every such
 * join is counted.  Without the search both runs join the same edges
 * first, so the pieces joined so are exactly the pieces fewer.
 */
static void test_gap_spares_single_faces(void **state)
{
    (void)state;
    allow_projection(); /* the quads' two triangles are flat within the flat angle */
    ur_mesh mesh = uv_sphere(48, 24, 60);
    ur_unfold_options options = strict_gap_options();
    ur_unfolding strict = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &strict, NULL, 0);
    assert_true(strict.single_face > 0);
    assert_int_equal(strict.gap_breaks, 0);
    options.gap_strands_faces = false;
    ur_unfolding spared = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &spared, NULL, 0);
    assert_true(spared.single_face < strict.single_face);
    assert_true(spared.gap_breaks > 0);
    assert_int_equal(spared.count + spared.gap_breaks, strict.count);
    ur_unfolding_free(&strict);
    ur_unfolding_free(&spared);
    ur_mesh_free(&mesh);
    length_tolerance = 1e-9;
}

/*
 * The outline edges of the pieces that come closer than gap to another
 * (as narrow_gaps counts them), as pairs of mesh vertices in the order
 * the outline runs; their count.
 */
static size_t narrow_edges(const ur_mesh *mesh, const ur_unfolding *u, double gap,
                           size_t (*edges)[2], size_t most)
{
    double tolerance = 2e-6 * mesh_size(mesh);
    size_t count = 0;
    for (size_t p = 0; p < u->count; p++) {
        const ur_unfolded_piece *piece = &u->pieces[p];
        size_t n = piece->outline_count;
        const ur_vec2 *o = piece->outline;
        for (size_t i = 0; i < n; i++)
            for (size_t k = i + 2; k < n; k++) {
                if ((k + 1) % n == i ||
                    segment_distance(o[i], o[(i + 1) % n], o[k], o[(k + 1) % n]) >= gap)
                    continue;
                size_t t = triangle_of_outline_edge(piece, i, tolerance);
                size_t q = triangle_of_outline_edge(piece, k, tolerance);
                if (share_flat_vertex(mesh, piece, t, q, tolerance))
                    continue;
                size_t ends[2][2] = {{i, (i + 1) % n}, {k, (k + 1) % n}};
                for (int e = 0; e < 2 && count < most; e++) {
                    edges[count][0] = piece->outline_vertices[ends[e][0]];
                    edges[count][1] = piece->outline_vertices[ends[e][1]];
                    count++;
                }
            }
    }
    return count;
}

/*
 * A seam needs its tab on one side only: by default the last run also
 * makes joins that leave slits narrower than the gap where the tabs can
 * go on the other sides, and only adds joins to the search's best: fewer
 * pieces than with the gap kept on both sides, and still no seam with
 * both its sides (which run between the same two mesh vertices in
 * opposite directions) closer than the gap to another outline edge.
 */
static void test_gap_one_side(void **state)
{
    (void)state;
    allow_projection();
    ur_mesh mesh = sphere(48, 23, 80);
    ur_unfold_options options;
    ur_unfold_options_default(&options);
    options.max_steps = 50;
    options.time_budget = 0; /* the steps end it, however loaded the machine */
    options.min_gap = 3.0;
    options.gap_strands_faces = true; /* no join without the gap */
    options.gap_both_sides = true;
    ur_unfolding both = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &both, NULL, 0);
    options.gap_both_sides = false;
    ur_unfolding one = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &one, NULL, 0);
    assert_true(one.count < both.count);
    size_t most = 4 * 3 * mesh.triangle_count;
    size_t(*edges)[2] = calloc(most, sizeof *edges);
    assert_non_null(edges);
    size_t count = narrow_edges(&mesh, &one, 3.0, edges, most);
    for (size_t i = 0; i < count; i++)
        for (size_t j = 0; j < count; j++)
            assert_false(edges[i][0] == edges[j][1] && edges[i][1] == edges[j][0]);
    free(edges);
    ur_unfolding_free(&both);
    ur_unfolding_free(&one);
    ur_mesh_free(&mesh);
    length_tolerance = 1e-9;
}

/*
 * An open cone of 8 triangles round its apex, slant edges 10 mm long,
 * whose angles there fall short of a full turn by deficit: laid in one
 * piece, it is cut along one slant edge, whose two sides make a wedge at
 * the apex, 10 sin(deficit) wide at its open end.
 */
static ur_mesh cone_fan(double deficit)
{
    builder b = {0};
    double slant = 10, angle = (2 * M_PI - deficit) / 8;
    double radius = slant * sin(angle / 2) / sin(M_PI / 8);
    size_t apex = add_vertex(&b, ur_vec3_make(0, 0, sqrt(slant * slant - radius * radius)));
    for (int k = 0; k < 8; k++)
        add_vertex(&b, ur_vec3_make(radius * cos(k * M_PI / 4), radius * sin(k * M_PI / 4), 0));
    for (size_t k = 0; k < 8; k++)
        add_triangle(&b, apex, 1 + k, 1 + (k + 1) % 8, 0);
    return build(&b);
}

/*
 * A wedge between the two sides of one seam must hold that seam's tab:
 * with a gap of 2 mm its open end is kept 3 mm wide.  The cone comes in
 * one piece when its wedge opens 3.2 mm, in two (no wedge) when it opens
 * 2.5 mm, which the gap alone would let through.
 */
static void test_wedge_holds_its_tab(void **state)
{
    (void)state;
    ur_unfold_options options = strict_gap_options();
    options.min_gap = 2.0;
    double opens[2] = {3.2, 2.5};
    size_t pieces[2] = {1, 2};
    for (int i = 0; i < 2; i++) {
        ur_mesh mesh = cone_fan(asin(opens[i] / 10));
        ur_unfolding u = unfold_with(&mesh, &options);
        check_unfolding(&mesh, &u, NULL, 0);
        assert_int_equal(u.count, pieces[i]);
        ur_unfolding_free(&u);
        ur_mesh_free(&mesh);
    }
}

/*
 * Joins without the gap at a cost below a piece: pieces of any size the
 * gap kept apart are joined at the end of the run, not only single faces
 * (fewer pieces than at the default cost), so that with the same first
 * order there are exactly as many pieces fewer as joins made so, and the
 * pieces still lie flat without overlap.  A cost outside 0 to 1 is
 * refused.
 */
static void test_gap_break_cost(void **state)
{
    (void)state;
    allow_projection();
    ur_mesh mesh = uv_sphere(48, 24, 60);
    ur_unfold_options options = strict_gap_options();
    ur_unfolding strict = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &strict, NULL, 0);
    options.gap_strands_faces = false;
    ur_unfolding faces_only = unfold_with(&mesh, &options); /* the default cost, one piece */
    options.gap_break_cost = 0.5;
    ur_unfolding cheap = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &cheap, NULL, 0);
    assert_int_equal(cheap.count + cheap.gap_breaks, strict.count);
    assert_true(cheap.count < faces_only.count);
    assert_int_equal(cheap.single_face, 0);
    ur_unfolding refused;
    ur_error error;
    options.gap_break_cost = 1.5;
    assert_int_equal(ur_unfold_with_options(&mesh, NULL, 0, &options, &refused, &error),
                     UR_ERROR_INPUT);
    ur_unfolding_free(&strict);
    ur_unfolding_free(&faces_only);
    ur_unfolding_free(&cheap);
    ur_mesh_free(&mesh);
    length_tolerance = 1e-9;
}

/*
 * Pieces smaller than small_piece_area are joined without the gap, as
 * single faces are: with the same first order there are exactly as many
 * pieces fewer as joins made so, every piece still lies flat without
 * overlap, and fewer pieces of less than that area are left (the 48 x 24
 * sphere with a 2.5 mm gap leaves pieces of a few faces round its poles).
 * A negative or NaN area is refused.
 */
static void test_small_pieces_join_without_the_gap(void **state)
{
    (void)state;
    allow_projection();
    ur_mesh mesh = uv_sphere(48, 24, 60);
    ur_unfold_options options = strict_gap_options();
    ur_unfolding strict = unfold_with(&mesh, &options);
    options.gap_strands_faces = false;
    ur_unfolding faces_only = unfold_with(&mesh, &options);
    const double small = 36.0;
    options.small_piece_area = small;
    ur_unfolding joined = unfold_with(&mesh, &options);
    check_unfolding(&mesh, &joined, NULL, 0);
    assert_int_equal(joined.count + joined.gap_breaks, strict.count);
    size_t small_before = 0, small_after = 0;
    for (size_t p = 0; p < faces_only.count; p++)
        small_before += faces_only.pieces[p].area_3d < small;
    for (size_t p = 0; p < joined.count; p++)
        small_after += joined.pieces[p].area_3d < small;
    assert_true(small_before > 0);
    assert_true(small_after < small_before);
    assert_true(joined.count < faces_only.count);
    ur_unfolding refused;
    ur_error error;
    double bad[] = {-1.0, NAN, INFINITY};
    for (size_t k = 0; k < 3; k++) {
        options.small_piece_area = bad[k];
        assert_int_equal(ur_unfold_with_options(&mesh, NULL, 0, &options, &refused, &error),
                         UR_ERROR_INPUT);
    }
    ur_unfolding_free(&strict);
    ur_unfolding_free(&faces_only);
    ur_unfolding_free(&joined);
    ur_mesh_free(&mesh);
    length_tolerance = 1e-9;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cube),
        cmocka_unit_test(test_icosahedron),
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_bumpy_sphere),
        cmocka_unit_test(test_flat_fan_closes),
        cmocka_unit_test(test_float_frustum),
        cmocka_unit_test(test_seams_groups_and_boundary),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_one_fold_each_way),
        cmocka_unit_test(test_cube_faces_whole),
        cmocka_unit_test(test_torus_quads_not_folded),
        cmocka_unit_test(test_flat_angle),
        cmocka_unit_test(test_ring_one_piece),
        cmocka_unit_test(test_piece_closing_within_contact),
        cmocka_unit_test(test_head_no_stray_faces),
        cmocka_unit_test(test_room_splits),
        cmocka_unit_test(test_room_taken_turned),
        cmocka_unit_test(test_longer_search_only_when_it_pays),
        cmocka_unit_test(test_stalled_search_starts_again),
        cmocka_unit_test(test_steps_for_many_pieces),
        cmocka_unit_test(test_progress_moves_forward),
        cmocka_unit_test(test_face_larger_than_room),
        cmocka_unit_test(test_search_repeats),
        cmocka_unit_test(test_turned_search_beside),
        cmocka_unit_test(test_turned_pieces_built_ahead),
        cmocka_unit_test(test_progress_follows_the_pieces),
        cmocka_unit_test(test_started_callback),
        cmocka_unit_test(test_min_gap),
        cmocka_unit_test(test_gap_break_cost),
        cmocka_unit_test(test_gap_one_side),
        cmocka_unit_test(test_wedge_holds_its_tab),
        cmocka_unit_test(test_gap_spares_single_faces),
        cmocka_unit_test(test_small_pieces_join_without_the_gap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
