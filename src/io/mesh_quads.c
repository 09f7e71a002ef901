/*
 * mesh_quads.c: splitting a modeller's quads along the diagonal that
 * follows the surface around them.
 *
 * assimp splits every quad along its first diagonal (corner 0 to corner 2)
 * unless the quad is concave.  A flat quad does not care, but a twisted
 * one (a bevel's corners, every quad of a subdivided mesh) becomes two
 * triangles with a fold between them, and on half of them the first
 * diagonal folds the wrong way: a rounded cube gets valley folds, a
 * papercraft model small dents.  Here a twisted quad whose sides all fold
 * the same way (all hills, or all valleys) is split along the diagonal
 * that folds that way too: a hill on a hill, a valley in a bowl.  Where
 * its sides fold both ways (a saddle) neither diagonal is the surface's,
 * and the file's split stays: turning those too gave Blender's subdivided
 * monkey head a fifth more pieces.
 *
 * A face given twice (mesh_repeats.c) counts once: across a side the
 * quad's own copies are left out and a neighbour's copies count as one,
 * and a quad and its copy may take the same new diagonal.
 *
 * The quads are marked on the raw scene, before assimp triangulates it,
 * and found again afterwards (mesh_polygons.c): its triangulation puts a
 * quad's two triangles where the quad was, in order.  Neighbours are found by
 * position, as the file's corners of two faces may be different vertices
 * (an OBJ's normals and texture coordinates keep them apart).
 */
#include "io_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- Neighbours by position ------------------------------------------- */

/* The corner of triangle t that is at neither end of edge ab, by position; SIZE_MAX if none. */
static size_t far_corner(const io_surface *s, size_t t, size_t a, size_t b)
{
    for (int k = 0; k < 3; k++) {
        size_t p = s->position[s->triangles[t][k]];
        if (p != s->position[a] && p != s->position[b])
            return s->triangles[t][k];
    }
    return SIZE_MAX;
}

/*
 * The one triangle across edge ab other than those of the quad (first,
 * second), own being the quad's corner beside ab; SIZE_MAX on the rim of
 * the surface or where more than one meet there.  A face given twice
 * (mesh_repeats.c) is one face here: triangles whose far corner is own
 * are the quad's own copies, and those across with their far corners at
 * one point count as one.
 */
static size_t neighbour_across(const io_surface *s, size_t a, size_t b, size_t first, size_t second,
                               size_t own)
{
    io_edge_record key = io_surface_edge(s, 0, a, b);
    size_t found = SIZE_MAX;
    for (size_t k = io_surface_first(s, a, b);
         k < s->edge_count && io_edge_same(&s->edges[k], &key); k++) {
        size_t t = s->edges[k].triangle;
        if (t == first || t == second)
            continue;
        size_t x = far_corner(s, t, a, b);
        if (x == SIZE_MAX || s->position[x] == s->position[own])
            continue;
        if (found != SIZE_MAX && s->position[far_corner(s, found, a, b)] != s->position[x])
            return SIZE_MAX;
        if (found == SIZE_MAX)
            found = t;
    }
    return found;
}

/* ---- The fold of an edge --------------------------------------------------- */

/*
 * A fold of less than half a degree is taken as flat (the sine of 0.5
 * degrees): a side that flat says nothing about how the surface bends, and
 * a quad twisted less is left as split (unfolding lays faces within 0.5
 * degrees of each other as one flat face anyway).
 */
#define FLAT_SINE 0.008726535498373935

/*
 * How triangle (a, b, c) and a neighbour across ab whose far corner is x
 * fold: the sine of the fold, positive where x rises to the side the
 * triangle's normal points to (a valley, seen from that side), negative
 * where it falls away (a hill).  0 for a triangle of no area.
 */
static double fold_sine(ur_vec3 a, ur_vec3 b, ur_vec3 c, ur_vec3 x)
{
    ur_vec3 normal = ur_vec3_cross(ur_vec3_sub(b, a), ur_vec3_sub(c, a));
    ur_vec3 edge = ur_vec3_sub(b, a);
    double area = ur_vec3_length(normal), length = ur_vec3_length(edge);
    double reach =
        ur_vec3_length(ur_vec3_cross(edge, ur_vec3_sub(x, a))); /* length times x's distance */
    if (!(area > 0) || !(reach > 0))
        return 0;
    return ur_vec3_dot(ur_vec3_sub(x, a), normal) / area * length / reach;
}

/*
 * How the surface bends round the quad: +1 where each of its sides that
 * folds (against the triangle across it) folds as a valley, seen from the
 * side the normals point to; -1 where each is a hill; 0 where they differ
 * (a saddle, where neither diagonal is the surface's) or fewer than two
 * sides fold (a side on the rim, or flat, does not count).
 */
static int bend_around(const io_surface *s, size_t first, size_t second, const size_t corner[4])
{
    /*
     * The quad's corners u, q, w, p run round it, first is (u, w, p) and
     * second (w, u, q): each side, and the corner that makes its triangle.
     */
    static const int sides[4][3] = {{0, 1, 2}, {1, 2, 0}, {2, 3, 0}, {3, 0, 2}};
    int valleys = 0, hills = 0;
    for (int k = 0; k < 4; k++) {
        size_t a = corner[sides[k][0]], b = corner[sides[k][1]], c = corner[sides[k][2]];
        size_t across = neighbour_across(s, a, b, first, second, c);
        size_t x = across == SIZE_MAX ? SIZE_MAX : far_corner(s, across, a, b);
        if (x == SIZE_MAX)
            continue;
        double fold = fold_sine(s->vertices[a], s->vertices[b], s->vertices[c], s->vertices[x]);
        valleys += fold > FLAT_SINE;
        hills += fold < -FLAT_SINE;
    }
    if (valleys >= 2 && hills == 0)
        return 1;
    return hills >= 2 && valleys == 0 ? -1 : 0;
}

/* ---- Turning a quad's diagonal ------------------------------------------ */

/*
 * The quad of two triangles that share an edge (by their vertices, as
 * assimp made them from one face): its corners u, q, w, p in their turn,
 * the diagonal from u to w.  False when they share no edge.
 */
static bool quad_corners(size_t (*triangles)[3], size_t first, size_t second, size_t corner[4])
{
    for (int k = 0; k < 3; k++) {
        size_t u = triangles[first][k], w = triangles[first][(k + 1) % 3];
        for (int j = 0; j < 3; j++)
            if (triangles[second][j] == w && triangles[second][(j + 1) % 3] == u) {
                corner[0] = u;
                corner[1] = triangles[second][(j + 2) % 3];
                corner[2] = w;
                corner[3] = triangles[first][(k + 2) % 3];
                return corner[1] != corner[3];
            }
    }
    return false;
}

static ur_vec3 normal_of(const ur_vec3 *v, size_t a, size_t b, size_t c)
{
    return ur_vec3_cross(ur_vec3_sub(v[b], v[a]), ur_vec3_sub(v[c], v[a]));
}

/*
 * Whether the quad of triangles first and second is better split along its
 * other diagonal, from corner[1] to corner[3] (its corners as
 * quad_corners gives them): its sides all bend one way and this diagonal
 * the other.
 */
static bool should_turn(const io_surface *s, size_t first, size_t second, size_t corner[4])
{
    if (!quad_corners(s->triangles, first, second, corner))
        return false;
    const ur_vec3 *v = s->vertices;
    size_t u = corner[0], q = corner[1], w = corner[2], p = corner[3];
    double diagonal = fold_sine(v[u], v[w], v[p], v[q]);
    int around = bend_around(s, first, second, corner);
    if (around == 0 || !(fabs(diagonal) > FLAT_SINE) || (diagonal > 0) == (around > 0))
        return false;
    /* The other diagonal must stay inside the quad: both new triangles face as the old did. */
    ur_vec3 facing = ur_vec3_add(normal_of(v, u, w, p), normal_of(v, w, u, q));
    return ur_vec3_dot(normal_of(v, u, q, p), facing) > 0 &&
           ur_vec3_dot(normal_of(v, q, w, p), facing) > 0;
}

/* A quad to turn: its first triangle, its corners, its new diagonal as an edge. */
typedef struct turn {
    size_t first, corner[4];
    io_edge_record diagonal;
} turn;

static int compare_turns(const void *a, const void *b)
{
    return io_compare_edges(&((const turn *)a)->diagonal, &((const turn *)b)->diagonal);
}

/* Whether two turns are of quads on the same corners, by position: a face given twice. */
static bool same_quad(const io_surface *s, const turn *a, const turn *b)
{
    size_t found = 0;
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            found += s->position[a->corner[i]] == s->position[b->corner[k]];
    return found == 4;
}

/*
 * Whether turn k of the sorted turns may go ahead: its new diagonal is no
 * edge yet (at a corner of three faces it would make two triangles on the
 * same corners) and no other quad's new diagonal, but that of a copy of
 * the quad (a face given twice, whose copy the cleaning drops).
 */
static bool turn_allowed(const io_surface *s, const turn *turns, size_t count, size_t k)
{
    const io_edge_record *d = &turns[k].diagonal;
    size_t record = io_surface_first(s, turns[k].corner[1], turns[k].corner[3]);
    if (record < s->edge_count && io_edge_same(&s->edges[record], d))
        return false;
    for (size_t i = k; i-- > 0 && io_edge_same(&turns[i].diagonal, d);)
        if (!same_quad(s, &turns[i], &turns[k]))
            return false;
    for (size_t i = k + 1; i < count && io_edge_same(&turns[i].diagonal, d); i++)
        if (!same_quad(s, &turns[i], &turns[k]))
            return false;
    return true;
}

ur_status io_quads_follow_surface(const ur_vec3 *vertices, size_t vertex_count,
                                  size_t (*triangles)[3], size_t triangle_count,
                                  const size_t *quads, size_t quad_count, ur_error *error)
{
    if (quad_count == 0)
        return UR_OK;
    io_surface s;
    ur_status status =
        io_surface_make(&s, vertices, vertex_count, triangles, triangle_count, error);
    turn *turns = status == UR_OK ? ur_alloc_array(quad_count, sizeof *turns, error) : NULL;
    if (status == UR_OK && !turns)
        status = UR_ERROR_MEMORY;
    /* Every quad judged on the file's own split, so that the order of the faces does not matter. */
    size_t count = 0;
    for (size_t k = 0; status == UR_OK && k < quad_count; k++) {
        turn *t = &turns[count];
        t->first = quads[k];
        if (t->first + 1 < triangle_count && should_turn(&s, t->first, t->first + 1, t->corner)) {
            t->diagonal = io_surface_edge(&s, 0, t->corner[1], t->corner[3]);
            count++;
        }
    }
    if (status == UR_OK)
        qsort(turns, count, sizeof *turns, compare_turns);
    for (size_t k = 0; status == UR_OK && k < count; k++) {
        if (!turn_allowed(&s, turns, count, k))
            continue;
        const size_t *c = turns[k].corner;
        size_t *a = triangles[turns[k].first], *b = triangles[turns[k].first + 1];
        a[0] = c[0], a[1] = c[1], a[2] = c[3];
        b[0] = c[1], b[1] = c[2], b[2] = c[3];
    }
    free(turns);
    io_surface_free(&s);
    return status;
}
