/*
 * cut_surface.c: the cut surface of cutter.h: numbering its vertices (classes
 * of triangle corners, by union-find across glued edges), measuring the
 * topology of each part (vertices, edges, boundary loops), and opening
 * slits, the one kind of seam the mesh's vertex-pair edges cannot carry.
 */
#include "cutter.h"

#include "../base/union_find.h"

#include <stdlib.h>

ur_status cutter_corners(cutter *c, ur_error *error)
{
    size_t n = c->half_edge_count;
    size_t *parent = ur_alloc_array(n, sizeof *parent, error);
    if (!parent)
        return UR_ERROR_MEMORY;
    union_find_init(parent, n);
    /* Across a glued edge a -> b (twin b -> a), the corners at a meet, and those at b. */
    for (size_t h = 0; h < n; h++) {
        size_t g = c->twins[h];
        if (g == UR_NO_EDGE || c->seam[h] || g < h)
            continue;
        union_find_join(parent, h, mesh_next(g));
        union_find_join(parent, mesh_next(h), g);
    }
    /* Roots are the smallest corner of their class, so classes number in corner order. */
    c->vertex_count = 0;
    for (size_t x = 0; x < n; x++) {
        size_t root = union_find_root(parent, x);
        c->corner[x] = root == x ? c->vertex_count++ : c->corner[root];
    }
    free(parent);
    return UR_OK;
}

/* Counts the boundary loops of every part, walking seam half-edges vertex to vertex. */
static ur_status count_loops(const cutter *c, part_shape *shapes, ur_error *error)
{
    size_t *outgoing = ur_alloc_array(c->vertex_count, sizeof *outgoing, error);
    if (!outgoing)
        return UR_ERROR_MEMORY;
    for (size_t v = 0; v < c->vertex_count; v++)
        outgoing[v] = UR_NO_EDGE;
    for (size_t h = 0; h < c->half_edge_count; h++)
        if (c->seam[h]) {
            if (outgoing[c->corner[h]] != UR_NO_EDGE)
                shapes[c->part[h / 3]].broken = true;
            outgoing[c->corner[h]] = h;
        }
    for (size_t h = 0; h < c->half_edge_count; h++) {
        if (!c->seam[h] || outgoing[c->corner[h]] != h)
            continue;
        shapes[c->part[h / 3]].loops++;
        size_t x = h;
        while (x != UR_NO_EDGE) {
            outgoing[c->corner[x]] = UR_NO_EDGE;
            x = outgoing[c->corner[mesh_next(x)]];
        }
    }
    free(outgoing);
    return UR_OK;
}

ur_status cutter_shapes(const cutter *c, part_shape *shapes, ur_error *error)
{
    bool *seen = ur_alloc_array(c->vertex_count, sizeof *seen, error);
    if (!seen)
        return UR_ERROR_MEMORY;
    for (size_t p = 0; p < c->part_count; p++) {
        shapes[p] = (part_shape){0, 0, c->part_size[p], 0, false};
    }
    for (size_t h = 0; h < c->half_edge_count; h++) {
        part_shape *shape = &shapes[c->part[h / 3]];
        if (!seen[c->corner[h]]) {
            seen[c->corner[h]] = true;
            shape->vertices++;
        }
        if (c->seam[h] || h < c->twins[h])
            shape->edges++;
    }
    free(seen);
    return count_loops(c, shapes, error);
}

/* Whether seam half-edge h, with a twin, is a slit: both its ends touch no other seam. */
static bool is_slit(const cutter *c, size_t h)
{
    size_t g = c->twins[h];
    return c->corner[h] == c->corner[mesh_next(g)] && c->corner[mesh_next(h)] == c->corner[g];
}

ur_status cutter_open_slits(cutter *c, ur_error *error)
{
    /* Found first, opened after: ungluing changes which edges look like slits. */
    size_t *slits = NULL, count = 0;
    for (size_t h = 0; h < c->half_edge_count; h++)
        if (c->seam[h] && c->twins[h] != UR_NO_EDGE && h < c->twins[h] && is_slit(c, h)) {
            if (!slits && !(slits = ur_alloc_array(c->half_edge_count, sizeof *slits, error)))
                return UR_ERROR_MEMORY;
            slits[count++] = h;
        }
    if (count == 0)
        return UR_OK;
    /*
     * The edge of h's triangle that ends where h starts is glued (or h's
     * corner there would not share a vertex with its twin's): ungluing it
     * splits that vertex, and the slit becomes a path of two edges.
     */
    for (size_t i = 0; i < count; i++)
        cutter_unglue(c, mesh_next(mesh_next(slits[i])));
    free(slits);
    return cutter_corners(c, error);
}
