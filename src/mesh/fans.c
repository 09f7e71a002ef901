/*
 * fans.c: taking apart two surfaces that only touch along an edge, where
 * a file gives both the same vertices (an STL, where every corner is a
 * point, or an OBJ whose duplicate vertices were merged: the edge carries
 * four triangles).
 *
 * Round each end of such an edge the triangles fall into fans: triangles
 * at the vertex joined across the edges that two of them share (an edge of
 * three or more joins none).  Each surface makes its own fan, and giving
 * every fan but the first its own copy of the vertex separates them.
 */
#include "mesh_internal.h"

#include <stdlib.h>

#include "../base/union_find.h"

/* A triangle at the vertex, and one of its two other corners. */
typedef struct spoke {
    size_t corner;   /* the other end of the edge from the vertex */
    size_t triangle; /* its index among the triangles at the vertex */
} spoke;

static int by_corner(const void *a, const void *b)
{
    const spoke *x = a, *y = b;
    if (x->corner != y->corner)
        return x->corner < y->corner ? -1 : 1;
    return (x->triangle > y->triangle) - (x->triangle < y->triangle);
}

/* The triangles at v, in order, into at (room for all); their count. */
static size_t triangles_at(const size_t (*triangles)[3], size_t count, size_t v, size_t *at)
{
    size_t found = 0;
    for (size_t t = 0; t < count; t++)
        if (triangles[t][0] == v || triangles[t][1] == v || triangles[t][2] == v)
            at[found++] = t;
    return found;
}

/* Joins into fans (parent) the triangles at v that share an edge with no third triangle on it. */
static void join_fans(const size_t (*triangles)[3], const size_t *at, size_t found, size_t v,
                      spoke *spokes, size_t *parent)
{
    size_t n = 0;
    for (size_t i = 0; i < found; i++)
        for (int k = 0; k < 3; k++)
            if (triangles[at[i]][k] != v)
                spokes[n++] = (spoke){triangles[at[i]][k], i};
    qsort(spokes, n, sizeof *spokes, by_corner);
    union_find_init(parent, found);
    for (size_t i = 0, j; i < n; i = j) {
        for (j = i + 1; j < n && spokes[j].corner == spokes[i].corner; j++)
            ;
        if (j - i == 2)
            union_find_join(parent, spokes[i].triangle, spokes[i + 1].triangle);
    }
}

ur_status mesh_split_fans(size_t (*triangles)[3], size_t count, size_t v, size_t next_vertex,
                          size_t *copies, ur_error *error)
{
    *copies = 0;
    size_t *at = ur_alloc_array(count, sizeof *at, error);
    size_t *parent = ur_alloc_array(count, sizeof *parent, error);
    size_t *copy_of = ur_alloc_array(count, sizeof *copy_of, error);
    spoke *spokes = ur_alloc_array(2 * count, sizeof *spokes, error);
    ur_status status = at && parent && copy_of && spokes ? UR_OK : UR_ERROR_MEMORY;
    if (status == UR_OK) {
        size_t found = triangles_at((const size_t(*)[3])triangles, count, v, at);
        join_fans((const size_t(*)[3])triangles, at, found, v, spokes, parent);
        /* Roots come in order, so the first triangle's fan keeps v. */
        for (size_t i = 0; i < found; i++) {
            size_t root = union_find_root(parent, i);
            if (root == i)
                copy_of[i] = root == 0 ? v : next_vertex + (*copies)++;
            size_t *corner = triangles[at[i]];
            for (int k = 0; k < 3; k++)
                if (corner[k] == v)
                    corner[k] = copy_of[root];
        }
    }
    free(at);
    free(parent);
    free(copy_of);
    free(spokes);
    return status;
}
