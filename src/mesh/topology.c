/*
 * topology.c: edge adjacency (twins), the shape of a mesh (Euler
 * characteristic, boundary loops) and the boundary loop of a disk.
 *
 * Edges are found by bucketing half-edges under their smaller vertex and
 * sorting each bucket by the larger one, rather than by one global sort:
 * buckets hold a handful of half-edges, so a mesh of millions of triangles
 * is paired in linear time, and a fan of thousands (a cone's apex) still
 * sorts in n log n.
 */
#include "mesh_internal.h"

#include <stdlib.h>

typedef struct keyed {
    size_t key, half_edge;
} keyed;

static int compare_keyed(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return (x->half_edge > y->half_edge) - (x->half_edge < y->half_edge);
}

static void sort_keyed(keyed *items, size_t count)
{
    if (count > 16) {
        qsort(items, count, sizeof *items, compare_keyed);
        return;
    }
    for (size_t i = 1; i < count; i++) {
        keyed item = items[i];
        size_t j = i;
        for (; j > 0 && compare_keyed(&items[j - 1], &item) > 0; j--)
            items[j] = items[j - 1];
        items[j] = item;
    }
}

static size_t smaller_end(const size_t (*triangles)[3], size_t h)
{
    size_t a = mesh_from(triangles, h), b = mesh_to(triangles, h);
    return a < b ? a : b;
}

static size_t larger_end(const size_t (*triangles)[3], size_t h)
{
    size_t a = mesh_from(triangles, h), b = mesh_to(triangles, h);
    return a < b ? b : a;
}

/*
 * Counting sort of the half-edges by smaller vertex: order lists them,
 * bucket v is order[start[v]] to order[start[v + 1]]; returns the largest.
 */
static size_t bucket_half_edges(const size_t (*triangles)[3], size_t half_edge_count,
                                size_t vertex_count, size_t *start, size_t *order)
{
    for (size_t h = 0; h < half_edge_count; h++)
        start[smaller_end(triangles, h) + 1]++;
    size_t largest = 0;
    for (size_t v = 0; v < vertex_count; v++) {
        if (start[v + 1] > largest)
            largest = start[v + 1];
        start[v + 1] += start[v];
    }
    /* Filling moves each start[v] to start[v + 1]; shift them back after. */
    for (size_t h = 0; h < half_edge_count; h++)
        order[start[smaller_end(triangles, h)]++] = h;
    for (size_t v = vertex_count; v > 0; v--)
        start[v] = start[v - 1];
    start[0] = 0;
    return largest;
}

int mesh_compare_edge_ends(const void *a, const void *b)
{
    const mesh_edge_key *x = a, *y = b;
    if (x->low != y->low)
        return x->low < y->low ? -1 : 1;
    return (x->high > y->high) - (x->high < y->high);
}

int mesh_compare_edge_keys(const void *a, const void *b)
{
    int by_ends = mesh_compare_edge_ends(a, b);
    if (by_ends != 0)
        return by_ends;
    const mesh_edge_key *x = a, *y = b;
    return (x->index > y->index) - (x->index < y->index);
}

/* Pairs the half-edges of one bucket; false (and *bad) on a shared edge of three. */
static bool pair_bucket(const size_t (*triangles)[3], const size_t *bucket, size_t count,
                        keyed *scratch, size_t *twins, mesh_bad_edge *bad)
{
    for (size_t i = 0; i < count; i++) {
        scratch[i].key = larger_end(triangles, bucket[i]);
        scratch[i].half_edge = bucket[i];
    }
    sort_keyed(scratch, count);
    for (size_t i = 0, j; i < count; i = j) {
        for (j = i + 1; j < count && scratch[j].key == scratch[i].key; j++)
            ;
        if (j - i > 2) {
            bad->a = smaller_end(triangles, scratch[i].half_edge);
            bad->b = scratch[i].key;
            bad->count = j - i;
            return false;
        }
        size_t h = scratch[i].half_edge;
        size_t g = j - i == 2 ? scratch[i + 1].half_edge : UR_NO_EDGE;
        twins[h] = g;
        if (g != UR_NO_EDGE)
            twins[g] = h;
    }
    return true;
}

ur_status mesh_pair_edges(const size_t (*triangles)[3], size_t triangle_count, size_t vertex_count,
                          size_t *twins, mesh_bad_edge *bad, ur_error *error)
{
    size_t half_edge_count = 3 * triangle_count;
    size_t *start = ur_alloc_array(vertex_count + 1, sizeof *start, error);
    size_t *order = ur_alloc_array(half_edge_count, sizeof *order, error);
    keyed *scratch = NULL;
    ur_status status = UR_ERROR_MEMORY;
    if (!start || !order)
        goto done;
    size_t largest = bucket_half_edges(triangles, half_edge_count, vertex_count, start, order);
    scratch = ur_alloc_array(largest, sizeof *scratch, error);
    if (!scratch)
        goto done;
    status = UR_OK;
    for (size_t v = 0; v < vertex_count && status == UR_OK; v++)
        if (!pair_bucket(triangles, order + start[v], start[v + 1] - start[v], scratch, twins, bad))
            status = UR_ERROR_INPUT;
done:
    free(start);
    free(order);
    free(scratch);
    return status;
}

ur_status ur_mesh_twins(const ur_mesh *mesh, size_t **twins, ur_error *error)
{
    *twins = ur_alloc_array(3 * mesh->triangle_count, sizeof **twins, error);
    if (!*twins)
        return UR_ERROR_MEMORY;
    mesh_bad_edge bad = {0, 0, 0};
    ur_status status = mesh_check_triangles((const size_t(*)[3])mesh->triangles,
                                            mesh->triangle_count, mesh->vertex_count, error);
    if (status == UR_OK)
        status = mesh_pair_edges((const size_t(*)[3])mesh->triangles, mesh->triangle_count,
                                 mesh->vertex_count, *twins, &bad, error);
    if (status == UR_ERROR_INPUT && bad.count > 0)
        ur_error_set(error, status,
                     "non-manifold edge between vertices %zu and %zu (%zu triangles)", bad.a + 1,
                     bad.b + 1, bad.count);
    if (status != UR_OK) {
        free(*twins);
        *twins = NULL;
    }
    return status;
}

/*
 * outgoing[v]: the boundary half-edge leaving vertex v, or UR_NO_EDGE.  A
 * vertex with two is pinched (two boundary fans meet there): *pinched.
 */
static size_t *boundary_outgoing(const ur_mesh *mesh, const size_t *twins, bool *pinched,
                                 ur_error *error)
{
    size_t *outgoing = ur_alloc_array(mesh->vertex_count, sizeof *outgoing, error);
    if (!outgoing)
        return NULL;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        outgoing[v] = UR_NO_EDGE;
    *pinched = false;
    const size_t(*triangles)[3] = (const size_t(*)[3])mesh->triangles;
    for (size_t h = 0; h < 3 * mesh->triangle_count; h++) {
        if (twins[h] != UR_NO_EDGE)
            continue;
        size_t v = mesh_from(triangles, h);
        if (outgoing[v] != UR_NO_EDGE)
            *pinched = true;
        outgoing[v] = h;
    }
    return outgoing;
}

/*
 * Walks the boundary loop through h0, clearing outgoing as it goes; false
 * when the walk cannot close (a boundary edge runs the wrong way).
 */
static bool walk_loop(const size_t (*triangles)[3], size_t *outgoing, size_t h0, size_t *loop,
                      size_t *length)
{
    size_t start = mesh_from(triangles, h0), h = h0;
    *length = 0;
    for (;;) {
        if (loop)
            loop[*length] = mesh_from(triangles, h);
        ++*length;
        outgoing[mesh_from(triangles, h)] = UR_NO_EDGE;
        size_t v = mesh_to(triangles, h);
        if (v == start)
            return true;
        h = outgoing[v];
        if (h == UR_NO_EDGE)
            return false;
    }
}

static size_t count_used(const ur_mesh *mesh, bool *used)
{
    size_t count = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            size_t v = mesh->triangles[t][k];
            count += !used[v];
            used[v] = true;
        }
    return count;
}

static void count_edges(const ur_mesh *mesh, const size_t *twins, mesh_shape *shape)
{
    const size_t(*triangles)[3] = (const size_t(*)[3])mesh->triangles;
    size_t half_edges = 3 * mesh->triangle_count;
    shape->boundary_edges = 0;
    shape->oriented = true;
    for (size_t h = 0; h < half_edges; h++) {
        size_t g = twins[h];
        if (g == UR_NO_EDGE)
            shape->boundary_edges++;
        else if (mesh_from(triangles, h) != mesh_to(triangles, g))
            shape->oriented = false;
    }
    shape->edges = (half_edges - shape->boundary_edges) / 2 + shape->boundary_edges;
}

static void count_loops(const ur_mesh *mesh, const size_t *twins, size_t *outgoing,
                        mesh_shape *shape)
{
    const size_t(*triangles)[3] = (const size_t(*)[3])mesh->triangles;
    shape->loops = 0;
    for (size_t h = 0; h < 3 * mesh->triangle_count && !shape->pinched; h++) {
        /* Each loop is walked from its first half-edge; the walk clears the rest. */
        if (twins[h] != UR_NO_EDGE || outgoing[mesh_from(triangles, h)] != h)
            continue;
        size_t length;
        if (!walk_loop(triangles, outgoing, h, NULL, &length))
            shape->pinched = true;
        shape->loops++;
    }
}

ur_status mesh_shape_of(const ur_mesh *mesh, const size_t *twins, mesh_shape *shape,
                        ur_error *error)
{
    bool *used = ur_alloc_array(mesh->vertex_count, sizeof *used, error);
    if (!used)
        return UR_ERROR_MEMORY;
    shape->vertices = count_used(mesh, used);
    free(used);
    shape->triangles = mesh->triangle_count;
    count_edges(mesh, twins, shape);
    size_t *outgoing = boundary_outgoing(mesh, twins, &shape->pinched, error);
    if (!outgoing)
        return UR_ERROR_MEMORY;
    count_loops(mesh, twins, outgoing, shape);
    free(outgoing);
    return UR_OK;
}

/* Refuses a shape that is not a disk, saying why. */
static ur_status refuse_non_disk(const mesh_shape *shape, ur_error *error)
{
    const char *prefix = "the mesh is not a topological disk";
    if (shape->triangles == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: it has no triangles", prefix);
    if (!shape->oriented)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: its triangles are not consistently oriented", prefix);
    if (shape->pinched)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: its boundary passes twice through a vertex",
                            prefix);
    if (shape->boundary_edges == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: it is closed", prefix);
    if (shape->loops != 1)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: it has %zu boundary loops", prefix,
                            shape->loops);
    if (mesh_euler(shape) != 1)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: its Euler characteristic is %lld, not 1",
                            prefix, mesh_euler(shape));
    return UR_OK;
}

/* The loop itself, once the mesh is known to be a disk. */
static ur_status disk_loop(const ur_mesh *mesh, const size_t *twins, size_t length, size_t **loop,
                           size_t *count, ur_error *error)
{
    bool pinched;
    size_t *outgoing = boundary_outgoing(mesh, twins, &pinched, error);
    *loop = outgoing ? ur_alloc_array(length, sizeof **loop, error) : NULL;
    if (!*loop) {
        free(outgoing);
        return UR_ERROR_MEMORY;
    }
    const size_t(*triangles)[3] = (const size_t(*)[3])mesh->triangles;
    size_t h0 = 0;
    while (twins[h0] != UR_NO_EDGE)
        h0++;
    bool closed = walk_loop(triangles, outgoing, h0, *loop, count);
    free(outgoing);
    if (closed && *count == length)
        return UR_OK;
    free(*loop);
    *loop = NULL;
    *count = 0;
    return ur_error_set(error, UR_ERROR_INTERNAL, "the boundary of a disk did not close (a bug)");
}

/* The twins and shape of a mesh that must be a disk; *twins is the caller's on success. */
static ur_status disk_shape(const ur_mesh *mesh, size_t **twins, mesh_shape *shape, ur_error *error)
{
    ur_status status = ur_mesh_twins(mesh, twins, error);
    if (status != UR_OK)
        return status;
    status = mesh_shape_of(mesh, *twins, shape, error);
    if (status == UR_OK)
        status = refuse_non_disk(shape, error);
    if (status != UR_OK) {
        free(*twins);
        *twins = NULL;
    }
    return status;
}

ur_status mesh_check_disk(const ur_mesh *mesh, ur_error *error)
{
    size_t *twins;
    mesh_shape shape;
    ur_status status = disk_shape(mesh, &twins, &shape, error);
    if (status == UR_OK)
        free(twins);
    return status;
}

ur_status ur_mesh_boundary(const ur_mesh *mesh, size_t **loop, size_t *count, ur_error *error)
{
    *loop = NULL;
    *count = 0;
    size_t *twins;
    mesh_shape shape;
    ur_status status = disk_shape(mesh, &twins, &shape, error);
    if (status != UR_OK)
        return status;
    status = disk_loop(mesh, twins, shape.boundary_edges, loop, count, error);
    free(twins);
    return status;
}
