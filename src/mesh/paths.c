/*
 * paths.c: shortest paths over the cut surface (see cutter.h), by
 * Dijkstra's algorithm on its edges with their lengths in space.  They
 * steer where cut.c cuts: along shortest paths rather than wherever a
 * breadth-first search happens to leave edges.
 */
#include "cutter.h"

#include <math.h>
#include <stdlib.h>

/* Edges of the cut surface at each vertex: an edge is named by one of its half-edges. */
typedef struct adjacency {
    size_t *start; /* edges at v: edge[start[v]] to edge[start[v + 1]] */
    size_t *edge;
} adjacency;

/* Whether half-edge h names an edge of the cut surface (once per edge) in a part being cut. */
static bool names_edge(const cutter *c, const bool *cutting, size_t h)
{
    return cutting[c->part[h / 3]] && (c->seam[h] || h < c->twins[h]);
}

static ur_status adjacency_build(adjacency *a, const cutter *c, const bool *cutting,
                                 ur_error *error)
{
    a->start = ur_alloc_array(c->vertex_count + 1, sizeof *a->start, error);
    size_t *fill = ur_alloc_array(c->vertex_count, sizeof *fill, error);
    if (!a->start || !fill) {
        free(fill);
        return UR_ERROR_MEMORY;
    }
    for (size_t h = 0; h < c->half_edge_count; h++)
        if (names_edge(c, cutting, h)) {
            a->start[c->corner[h] + 1]++;
            a->start[c->corner[mesh_next(h)] + 1]++;
        }
    for (size_t v = 0; v < c->vertex_count; v++)
        a->start[v + 1] += a->start[v];
    a->edge = ur_alloc_array(a->start[c->vertex_count], sizeof *a->edge, error);
    if (!a->edge) {
        free(fill);
        return UR_ERROR_MEMORY;
    }
    for (size_t h = 0; h < c->half_edge_count; h++)
        if (names_edge(c, cutting, h)) {
            size_t v = c->corner[h], w = c->corner[mesh_next(h)];
            a->edge[a->start[v] + fill[v]++] = h;
            a->edge[a->start[w] + fill[w]++] = h;
        }
    free(fill);
    return UR_OK;
}

/* A binary min-heap of (distance, vertex), with stale entries skipped when popped. */
typedef struct entry {
    double distance;
    size_t vertex;
} entry;

typedef struct heap {
    entry *items;
    size_t count;
} heap;

static void heap_push(heap *q, double distance, size_t vertex)
{
    size_t i = q->count++;
    for (; i > 0 && q->items[(i - 1) / 2].distance > distance; i = (i - 1) / 2)
        q->items[i] = q->items[(i - 1) / 2];
    q->items[i] = (entry){distance, vertex};
}

static entry heap_pop(heap *q)
{
    entry top = q->items[0], last = q->items[--q->count];
    size_t i = 0;
    for (;;) {
        size_t child = 2 * i + 1;
        if (child >= q->count)
            break;
        if (child + 1 < q->count && q->items[child + 1].distance < q->items[child].distance)
            child++;
        if (q->items[child].distance >= last.distance)
            break;
        q->items[i] = q->items[child];
        i = child;
    }
    if (q->count > 0)
        q->items[i] = last;
    return top;
}

static double edge_length(const cutter *c, size_t h)
{
    const ur_vec3 *vertices = c->mesh->vertices;
    return ur_vec3_distance(vertices[mesh_from(c->triangles, h)],
                            vertices[mesh_to(c->triangles, h)]);
}

static void relax_all(const cutter *c, const adjacency *a, heap *q, mesh_paths *out)
{
    while (q->count > 0) {
        entry e = heap_pop(q);
        if (e.distance > out->distance[e.vertex])
            continue;
        for (size_t i = a->start[e.vertex]; i < a->start[e.vertex + 1]; i++) {
            size_t h = a->edge[i];
            size_t w = cutter_other_end(c, h, e.vertex);
            double d = e.distance + edge_length(c, h);
            if (d < out->distance[w]) {
                out->distance[w] = d;
                out->via[w] = h;
                heap_push(q, d, w);
            }
        }
    }
}

ur_status mesh_paths_from(const cutter *c, const bool *cutting, const size_t *sources,
                          size_t source_count, mesh_paths *out, ur_error *error)
{
    adjacency a = {NULL, NULL};
    heap q = {NULL, 0};
    ur_status status = adjacency_build(&a, c, cutting, error);
    if (status == UR_OK) {
        q.items = ur_alloc_array(source_count + a.start[c->vertex_count], sizeof *q.items, error);
        out->via = ur_alloc_array(c->vertex_count, sizeof *out->via, error);
        out->distance = ur_alloc_array(c->vertex_count, sizeof *out->distance, error);
        if (!q.items || !out->via || !out->distance)
            status = UR_ERROR_MEMORY;
    }
    if (status == UR_OK) {
        for (size_t v = 0; v < c->vertex_count; v++) {
            out->via[v] = UR_NO_EDGE;
            out->distance[v] = INFINITY;
        }
        for (size_t i = 0; i < source_count; i++) {
            out->distance[sources[i]] = 0;
            heap_push(&q, 0, sources[i]);
        }
        relax_all(c, &a, &q, out);
    }
    free(a.start);
    free(a.edge);
    free(q.items);
    return status;
}

void mesh_paths_free(mesh_paths *p)
{
    free(p->via);
    free(p->distance);
    p->via = NULL;
    p->distance = NULL;
}
