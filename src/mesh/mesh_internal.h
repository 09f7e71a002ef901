/*
 * mesh_internal.h: what the files of the mesh module share: checks of raw
 * arrays, half-edge helpers, edge pairing, welding, orientation and the
 * shape (Euler characteristic, boundary loops) of a mesh.
 */
#ifndef UNROLL_MESH_INTERNAL_H
#define UNROLL_MESH_INTERNAL_H

#include "unroll/mesh.h"

/* Corner k of triangle t is corner 3 t + k; half-edge 3 t + k leaves it. */
static inline size_t mesh_next(size_t half_edge)
{
    return half_edge - half_edge % 3 + (half_edge % 3 + 1) % 3;
}

static inline size_t mesh_from(const size_t (*triangles)[3], size_t half_edge)
{
    return triangles[half_edge / 3][half_edge % 3];
}

static inline size_t mesh_to(const size_t (*triangles)[3], size_t half_edge)
{
    return triangles[half_edge / 3][(half_edge % 3 + 1) % 3];
}

/* An edge by its ends in increasing order, and what it stands for (a triangle, a seam). */
typedef struct mesh_edge_key {
    size_t low, high, index;
} mesh_edge_key;

static inline mesh_edge_key mesh_edge_key_of(size_t a, size_t b, size_t index)
{
    return (mesh_edge_key){a < b ? a : b, a < b ? b : a, index};
}

/* qsort's order of edge keys: by their ends, then index. */
int mesh_compare_edge_keys(const void *a, const void *b);

/* By their ends alone, for bsearch. */
int mesh_compare_edge_ends(const void *a, const void *b);

/* Refuses a vertex index out of range, naming the triangle (1-based). */
ur_status mesh_check_triangles(const size_t (*triangles)[3], size_t count, size_t vertex_count,
                               ur_error *error);

/*
 * Gives each fan of triangles round vertex v (triangles at v joined across
 * edges that exactly two of them share) but the first its own copy of v,
 * numbered from next_vertex on; *copies says how many (the caller adds
 * the copies' points).  Two surfaces that only touch along an edge of v
 * come apart there.
 */
ur_status mesh_split_fans(size_t (*triangles)[3], size_t count, size_t v, size_t next_vertex,
                          size_t *copies, ur_error *error);

/*
 * Marks in drop (count entries, the caller's) the triangles on the same
 * corners as another that go (flaps.c says which): the pairs back to back
 * that stand on the surface as a flap of no thickness (*flaps counts the
 * pairs), and faces given twice (*duplicates counts the triangles).
 */
ur_status mesh_find_repeated(const size_t (*triangles)[3], size_t count, bool *drop, size_t *flaps,
                             size_t *duplicates, ur_error *error);

/* An edge that three or more triangles share (vertex indices, 0-based). */
typedef struct mesh_bad_edge {
    size_t a, b, count;
} mesh_bad_edge;

/*
 * Fills twins (3 triangle_count entries, the caller's) with the other
 * half-edge on the same undirected edge, or UR_NO_EDGE.  On an edge of
 * three or more triangles returns UR_ERROR_INPUT with *bad filled and error
 * untouched, so that each caller can name the vertices its own way.
 * Buckets half-edges by their smaller vertex, then sorts each bucket by
 * the larger one: linear in the mesh but for the sort of each bucket.
 */
ur_status mesh_pair_edges(const size_t (*triangles)[3], size_t triangle_count, size_t vertex_count,
                          size_t *twins, mesh_bad_edge *bad, ur_error *error);

/*
 * Welds vertices: map[v] is the vertex v is merged into (v itself when it is
 * kept), always a lower index; *welded counts the merged ones.
 */
ur_status mesh_weld(const ur_vec3 *vertices, size_t count, double tolerance, size_t *map,
                    size_t *welded, ur_error *error);

/* Two neighbouring triangles that no choice of directions can reconcile. */
typedef struct mesh_conflict {
    size_t first, second; /* triangles */
    size_t a, b;          /* the edge between them */
} mesh_conflict;

/*
 * Turns triangles over (in place) so that every edge with two triangles is
 * run in opposite directions by them: each connected part outward when it
 * is closed (positive signed volume), else the way most of its triangles
 * already run.  flipped[t] is set for each triangle turned.  Returns
 * UR_ERROR_INPUT with *conflict filled (error untouched) when a part cannot
 * be oriented.  twins is that of the triangles before any flip.
 */
ur_status mesh_orient(size_t (*triangles)[3], size_t triangle_count, const size_t *twins,
                      const ur_vec3 *vertices, bool *flipped, mesh_conflict *conflict,
                      ur_error *error);

/* What the topology of a mesh is, from its triangles and twins. */
typedef struct mesh_shape {
    size_t vertices; /* used by some triangle */
    size_t edges, triangles;
    size_t boundary_edges;
    size_t loops;  /* boundary loops */
    bool pinched;  /* some vertex is on the boundary twice: loops are not well defined */
    bool oriented; /* every inner edge is run both ways */
} mesh_shape;

ur_status mesh_shape_of(const ur_mesh *mesh, const size_t *twins, mesh_shape *shape,
                        ur_error *error);

/* Refuses (UR_ERROR_INPUT, saying why) a mesh that is not a topological disk. */
ur_status mesh_check_disk(const ur_mesh *mesh, ur_error *error);

static inline long long mesh_euler(const mesh_shape *shape)
{
    return (long long)shape->vertices - (long long)shape->edges + (long long)shape->triangles;
}

/*
 * The fraction of a triangle whose corners lie at offsets s[0] <= s[1] <=
 * s[2] that lies below offset x, the offset varying linearly over it
 * (bands.c).
 */
double mesh_fraction_below(const double s[3], double x);

/*
 * ur_mesh_bands with the offsets given per vertex (field) instead of along
 * a direction (bands.c): band b holds the mesh where planes[b - 1] <=
 * field <= planes[b].
 */
ur_status mesh_bands_of_field(const ur_mesh *mesh, const double *field, const double *planes,
                              size_t count, ur_mesh *banded, ur_error *error);

#endif
