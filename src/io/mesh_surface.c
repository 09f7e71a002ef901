/*
 * mesh_surface.c: the triangles the reader has made, with their edges
 * found by position (io_surface): an OBJ's faces keep their corners apart
 * (normals and texture coordinates make them different vertices), so
 * which triangles meet across an edge is told by where its ends are.
 * Used to turn a twisted quad's diagonal (mesh_quads.c) and to find a
 * face given twice (mesh_repeats.c).
 */
#include "io_internal.h"
#include "../geom/points.h"

#include <stdlib.h>

int io_compare_edges(const void *a, const void *b)
{
    const io_edge_record *p = a, *q = b;
    if (p->low != q->low)
        return p->low < q->low ? -1 : 1;
    if (p->high != q->high)
        return p->high < q->high ? -1 : 1;
    return (p->triangle > q->triangle) - (p->triangle < q->triangle);
}

io_edge_record io_surface_edge(const io_surface *s, size_t triangle, size_t a, size_t b)
{
    size_t p = s->position[a], q = s->position[b];
    return (io_edge_record){p < q ? p : q, p < q ? q : p, triangle};
}

ur_status io_surface_make(io_surface *s, const ur_vec3 *vertices, size_t vertex_count,
                          size_t (*triangles)[3], size_t triangle_count, ur_error *error)
{
    *s = (io_surface){
        .vertices = vertices, .triangles = triangles, .edge_count = 3 * triangle_count};
    s->position = ur_alloc_array(vertex_count, sizeof *s->position, error);
    s->edges = ur_alloc_array(s->edge_count, sizeof *s->edges, error);
    if (!s->position || !s->edges)
        return UR_ERROR_MEMORY;
    /* Vertices at the same point share a position number. */
    ur_status status = geom_number_points(vertices, vertex_count, s->position, error);
    if (status != UR_OK)
        return status;
    for (size_t t = 0; t < triangle_count; t++)
        for (int k = 0; k < 3; k++)
            s->edges[3 * t + k] = io_surface_edge(s, t, triangles[t][k], triangles[t][(k + 1) % 3]);
    qsort(s->edges, s->edge_count, sizeof *s->edges, io_compare_edges);
    return UR_OK;
}

void io_surface_free(io_surface *s)
{
    free(s->position);
    free(s->edges);
    *s = (io_surface){0};
}

size_t io_surface_first(const io_surface *s, size_t a, size_t b)
{
    io_edge_record key = io_surface_edge(s, 0, a, b);
    size_t low = 0, high = s->edge_count;
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        if (io_compare_edges(&s->edges[middle], &key) < 0)
            low = middle + 1;
        else
            high = middle;
    }
    return low;
}

bool io_edge_same(const io_edge_record *record, const io_edge_record *key)
{
    return record->low == key->low && record->high == key->high;
}

size_t io_surface_count(const io_surface *s, size_t a, size_t b)
{
    io_edge_record key = io_surface_edge(s, 0, a, b);
    size_t count = 0;
    for (size_t r = io_surface_first(s, a, b);
         r < s->edge_count && io_edge_same(&s->edges[r], &key); r++)
        count++;
    return count;
}
