/*
 * cutter.h: what pieces.c (seams, parts, building the pieces), cut_surface.c
 * (the vertices and shape of the cut surface), cut.c (cutting a part open
 * until it is a disk) and paths.c (shortest paths) share.
 *
 * The cut surface is the mesh with its triangles unglued along every seam
 * half-edge.  Its vertices are classes of triangle corners: two corners at
 * the same mesh vertex are one vertex of the cut surface when a fan of
 * triangles glued across non-seam edges joins them.  That makes the cut
 * surface a manifold even where the mesh is pinched at a vertex, and turns
 * a cut into duplicated vertices without any further bookkeeping.
 */
#ifndef UNROLL_MESH_CUTTER_H
#define UNROLL_MESH_CUTTER_H

#include "mesh_internal.h"

typedef struct cutter {
    const ur_mesh *mesh;
    const size_t (*triangles)[3];
    size_t half_edge_count;
    size_t *twins;
    bool *seam;        /* per half-edge, the same on both sides: unglued */
    bool *tree;        /* per half-edge: crossed by the spanning tree of its part's triangles */
    size_t *part;      /* per triangle: its part, the piece it becomes */
    size_t *part_size; /* per part: its triangles */
    size_t part_count;
    size_t *corner;      /* per corner: its vertex of the cut surface */
    size_t vertex_count; /* of the cut surface */
} cutter;

/* The topology of one part of the cut surface. */
typedef struct part_shape {
    size_t vertices, edges, triangles, loops;
    bool broken; /* its boundary is not a set of simple loops: a bug */
} part_shape;

static inline long long part_euler(const part_shape *shape)
{
    return (long long)shape->vertices - (long long)shape->edges + (long long)shape->triangles;
}

static inline void cutter_unglue(cutter *c, size_t h)
{
    c->seam[h] = true;
    if (c->twins[h] != UR_NO_EDGE)
        c->seam[c->twins[h]] = true;
}

/*
 * A cutter over the mesh with no seam and every triangle in part 0 until
 * the caller says otherwise (pieces.c); refuses a mesh whose triangles have
 * two corners at one vertex or are not consistently oriented.  Free it with
 * cutter_free, also on failure.
 */
ur_status cutter_init(cutter *c, const ur_mesh *mesh, ur_error *error);
void cutter_free(cutter *c);

/* Numbers the vertices of the cut surface (c->corner) from the seams. */
ur_status cutter_corners(cutter *c, ur_error *error);

/* Fills shapes[p] for every part (c->corner must be current). */
ur_status cutter_shapes(const cutter *c, part_shape *shapes, ur_error *error);

/*
 * Unglues a neighbouring edge of every seam made of one edge whose two ends
 * touch no other seam: such a slit opens into a boundary loop of two edges
 * between the same two vertices, which a mesh cannot tell from one edge.
 * Recomputes c->corner.
 */
ur_status cutter_open_slits(cutter *c, ur_error *error);

/*
 * Cuts each part that is not a disk along its cut graph (see cut.c);
 * c->corner is then out of date.
 */
ur_status cutter_cut(cutter *c, const part_shape *shapes, ur_error *error);

/* Shortest paths over the cut surface from a set of its vertices (paths.c). */
typedef struct mesh_paths {
    size_t *via;      /* per vertex: the half-edge of the last edge on its path, or UR_NO_EDGE */
    double *distance; /* per vertex: the path's length; infinite when unreached */
} mesh_paths;

/* Over the parts with cutting[p] only; the caller frees *out with mesh_paths_free. */
ur_status mesh_paths_from(const cutter *c, const bool *cutting, const size_t *sources,
                          size_t source_count, mesh_paths *out, ur_error *error);

void mesh_paths_free(mesh_paths *p);

/* The other end of edge h of the cut surface from vertex v. */
static inline size_t cutter_other_end(const cutter *c, size_t h, size_t v)
{
    return c->corner[h] == v ? c->corner[mesh_next(h)] : c->corner[h];
}

#endif
