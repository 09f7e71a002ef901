/*
 * adjacency.c: the edges of a piece and whether it can be laid flat in one
 * piece: every edge on one or two triangles that run it opposite ways, one
 * connected part, a boundary, no handle.  Built here rather than taken from
 * ur_mesh_twins so that flattening needs nothing of a mesh but its arrays.
 *
 * Half-edges are bucketed by their smaller vertex (a counting sort), then
 * each bucket is sorted by the larger one: linear in the piece but for the
 * small sort of each bucket.
 */
#include "flatten_internal.h"

#include "../base/union_find.h"

#include <stdlib.h>
#include <string.h>

/* A half-edge in its bucket: its larger vertex, then its number 3 t + k. */
typedef struct half_key {
    size_t high, half;
} half_key;

static int compare_keys(const void *a, const void *b)
{
    const half_key *x = a, *y = b;
    if (x->high != y->high)
        return x->high < y->high ? -1 : 1;
    return x->half < y->half ? -1 : x->half > y->half;
}

static size_t half_from(const ur_mesh *mesh, size_t half)
{
    return mesh->triangles[half / 3][half % 3];
}

static size_t half_to(const ur_mesh *mesh, size_t half)
{
    return mesh->triangles[half / 3][(half % 3 + 1) % 3];
}

/* What the scan of the edges finds out, and its scratch arrays (owned). */
typedef struct scan {
    const ur_mesh *mesh;
    half_key *keys;    /* 3 T, grouped by smaller vertex */
    size_t *start;     /* V + 1: bucket v is keys[start[v]] .. keys[start[v + 1]] */
    size_t *parts;     /* union-find over triangles' corners */
    size_t *loops;     /* union-find over boundary edges */
    bool *on_boundary; /* per vertex */
    size_t boundary_edges;
} scan;

static void scan_free(scan *s)
{
    free(s->keys);
    free(s->start);
    free(s->parts);
    free(s->loops);
    free(s->on_boundary);
}

static ur_status scan_alloc(scan *s, const ur_mesh *mesh, ur_error *error)
{
    memset(s, 0, sizeof *s);
    s->mesh = mesh;
    size_t halves = 3 * mesh->triangle_count, vertices = mesh->vertex_count;
    s->keys = ur_alloc_array(halves, sizeof *s->keys, error);
    s->start = ur_alloc_array(vertices + 1, sizeof *s->start, error);
    s->parts = ur_alloc_array(vertices, sizeof *s->parts, error);
    s->loops = ur_alloc_array(vertices, sizeof *s->loops, error);
    s->on_boundary = ur_alloc_array(vertices, sizeof *s->on_boundary, error);
    if (!s->keys || !s->start || !s->parts || !s->loops || !s->on_boundary) {
        scan_free(s);
        return UR_ERROR_MEMORY;
    }
    for (size_t v = 0; v < vertices; v++)
        s->parts[v] = s->loops[v] = v;
    return UR_OK;
}

/* Counting sort of the half-edges by smaller vertex, then each bucket by larger. */
static void bucket_halves(scan *s)
{
    const ur_mesh *mesh = s->mesh;
    size_t halves = 3 * mesh->triangle_count;
    for (size_t h = 0; h < halves; h++) {
        size_t a = half_from(mesh, h), b = half_to(mesh, h);
        s->start[(a < b ? a : b) + 1]++;
    }
    for (size_t v = 0; v < mesh->vertex_count; v++)
        s->start[v + 1] += s->start[v];
    /* Filling moves start[v] to the end of bucket v, the start of v + 1: shifted back after. */
    for (size_t h = 0; h < halves; h++) {
        size_t a = half_from(mesh, h), b = half_to(mesh, h);
        half_key key = {a < b ? b : a, h};
        s->keys[s->start[a < b ? a : b]++] = key;
    }
    for (size_t v = mesh->vertex_count; v > 0; v--)
        s->start[v] = s->start[v - 1];
    s->start[0] = 0;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        qsort(s->keys + s->start[v], s->start[v + 1] - s->start[v], sizeof *s->keys, compare_keys);
}

/* One undirected edge: the run of count half-edges at keys[first]. */
static ur_status take_edge(scan *s, size_t low, size_t first, size_t count, flat_topology *topology,
                           ur_error *error)
{
    const half_key *run = s->keys + first;
    size_t high = run[0].high;
    if (count > 2)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the edge between vertices %zu and %zu is shared by %zu triangles: "
                            "a piece to flatten must be a surface",
                            low + 1, high + 1, count);
    if (count == 2 && half_from(s->mesh, run[0].half) == half_from(s->mesh, run[1].half))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "triangles %zu and %zu run their common edge %zu-%zu the same way: "
                            "the piece is not consistently oriented",
                            run[0].half / 3 + 1, run[1].half / 3 + 1, low + 1, high + 1);
    size_t e = topology->edge_count++;
    topology->edges[e][0] = low;
    topology->edges[e][1] = high;
    for (size_t k = 0; k < count; k++)
        topology->edge_of[run[k].half] = e;
    if (count == 1) {
        s->boundary_edges++;
        s->on_boundary[low] = s->on_boundary[high] = true;
        union_find_join(s->loops, low, high);
    }
    return UR_OK;
}

static ur_status take_edges(scan *s, flat_topology *topology, ur_error *error)
{
    for (size_t v = 0; v < s->mesh->vertex_count; v++) {
        size_t end = s->start[v + 1];
        for (size_t first = s->start[v]; first < end;) {
            size_t next = first + 1;
            while (next < end && s->keys[next].high == s->keys[first].high)
                next++;
            ur_status status = take_edge(s, v, first, next - first, topology, error);
            if (status)
                return status;
            first = next;
        }
    }
    return UR_OK;
}

/* Every vertex used, and all of them in one connected part. */
static ur_status check_parts(scan *s, ur_error *error)
{
    const ur_mesh *mesh = s->mesh;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        union_find_join(s->parts, mesh->triangles[t][0], mesh->triangles[t][1]);
        union_find_join(s->parts, mesh->triangles[t][0], mesh->triangles[t][2]);
    }
    size_t count = 0;
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        if (union_find_root(s->parts, v) != v)
            continue;
        /*
         * A root is the smallest vertex of its part (join keeps the smaller),
         * so a used one is the smaller end of its edges: an empty bucket
         * means no triangle uses it.
         */
        if (s->start[v + 1] == s->start[v])
            return ur_error_set(error, UR_ERROR_INPUT,
                                "vertex %zu belongs to no triangle: clean the mesh first", v + 1);
        count++;
    }
    if (count > 1)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the piece has %zu separate parts: flatten each on its own", count);
    return UR_OK;
}

/*
 * A connected surface with b boundary loops and genus g has Euler
 * characteristic 2 - 2 g - b; flattening needs g = 0 and b >= 1 (a disk,
 * possibly with holes).  A vertex where the boundary touches itself joins
 * two loops into one here, and is refused as well: it is no disk either.
 */
static ur_status check_shape(scan *s, const flat_topology *topology, ur_error *error)
{
    const ur_mesh *mesh = s->mesh;
    if (s->boundary_edges == 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the piece is closed (it has no boundary): cut it open first");
    size_t loops = 0;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        loops += s->on_boundary[v] && union_find_root(s->loops, v) == v;
    long long euler = (long long)mesh->vertex_count - (long long)topology->edge_count +
                      (long long)mesh->triangle_count;
    if (euler + (long long)loops != 2)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the piece is not a disk (Euler characteristic %lld, %zu boundary "
                            "loop%s): it has a handle or its boundary touches itself; cut it "
                            "into disks first",
                            euler, loops, loops == 1 ? "" : "s");
    return UR_OK;
}

/* The boundary vertex farthest (in 3D) from vertex from. */
static size_t farthest_on_boundary(const scan *s, size_t from)
{
    const ur_mesh *mesh = s->mesh;
    size_t best = from;
    double best_distance = -1;
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        if (!s->on_boundary[v])
            continue;
        double d = ur_vec3_distance(mesh->vertices[v], mesh->vertices[from]);
        if (d > best_distance) {
            best_distance = d;
            best = v;
        }
    }
    return best;
}

/*
 * Two boundary vertices nearly as far apart as any: from any boundary
 * vertex the farthest one, and from that the farthest again (at least half
 * the diameter, in practice nearly all of it, in linear time).
 */
static void choose_pins(const scan *s, flat_topology *topology)
{
    size_t any = 0;
    while (!s->on_boundary[any])
        any++;
    size_t a = farthest_on_boundary(s, any);
    size_t b = farthest_on_boundary(s, a);
    topology->pins[0] = a;
    topology->pins[1] = b;
}

static ur_status build(scan *s, flat_topology *topology, ur_error *error)
{
    size_t halves = 3 * s->mesh->triangle_count;
    topology->edges = ur_alloc_array(halves, sizeof *topology->edges, error);
    topology->edge_of = ur_alloc_array(halves, sizeof *topology->edge_of, error);
    if (!topology->edges || !topology->edge_of)
        return UR_ERROR_MEMORY;
    bucket_halves(s);
    ur_status status = take_edges(s, topology, error);
    if (!status)
        status = check_parts(s, error);
    if (!status)
        status = check_shape(s, topology, error);
    if (!status)
        choose_pins(s, topology);
    return status;
}

ur_status flat_topology_of(const ur_mesh *mesh, flat_topology *topology, ur_error *error)
{
    memset(topology, 0, sizeof *topology);
    scan s;
    ur_status status = scan_alloc(&s, mesh, error);
    if (status)
        return status;
    status = build(&s, topology, error);
    scan_free(&s);
    return status;
}

void flat_topology_free(flat_topology *topology)
{
    free(topology->edges);
    free(topology->edge_of);
    memset(topology, 0, sizeof *topology);
}
