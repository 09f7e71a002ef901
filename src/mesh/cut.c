/*
 * cut.c: cutting each part of the cut surface that is not a topological
 * disk until it is one.
 *
 * The cut is a cut graph found the tree-cotree way, so that it runs along
 * shortest paths.  T is a tree of shortest paths (paths.c) from the first
 * boundary loop of the part, or from one vertex when the part is closed.
 * A spanning tree of the part's triangles is then grown across edges that
 * are not in T wherever it can (Prim's algorithm with weights 0 and 1), and
 * the edges it does not cross, boundary included, form a graph G.  Cutting
 * along all of G would leave a disk (the tree's triangles); with
 * V - E + F = chi, G has 1 - chi more edges than vertices.  Removing, again
 * and again, an edge with an end of degree 1 in G drops the branches a cut
 * does not need and leaves the boundary loops (their vertices keep degree
 * 2), the 2 g loops of a genus-g part and the paths joining them, made of
 * edges of T where the triangles' tree could avoid them: shortest paths
 * from the first boundary loop to the others, and loops of shortest paths
 * through the root on a closed part (a meridian and a longitude of a
 * torus).
 *
 * A closed part of genus 0 (a sphere) would prune to nothing: it is slit
 * along the shortest path between two vertices far apart (the vertex
 * farthest from the farthest vertex from its first one: pole to pole on a
 * globe), which a flattening can open out far better than a short slit.
 * A path of one edge would open into two edges between the same two
 * vertices, so one more edge is added to it then.  Nothing here looks at
 * sharp features or at how well the piece will flatten.
 */
#include "cutter.h"

#include <stdlib.h>

/* The graph G of the parts being cut: boundary edges and edges the tree does not cross. */
typedef struct graph {
    size_t edge_count;
    size_t (*ends)[2];
    size_t *half_edge;
    bool *alive;
    size_t *start; /* the edges at vertex v: incident[start[v]] to incident[start[v + 1]] */
    size_t *incident;
    size_t *degree; /* alive edges at each vertex */
} graph;

static void graph_free(graph *g)
{
    free(g->ends);
    free(g->half_edge);
    free(g->alive);
    free(g->start);
    free(g->incident);
    free(g->degree);
}

static bool in_graph(const cutter *c, const bool *cutting, size_t h)
{
    if (!cutting[c->part[h / 3]])
        return false;
    return c->seam[h] || (!c->tree[h] && h < c->twins[h]);
}

static ur_status graph_alloc(graph *g, const cutter *c, const bool *cutting, ur_error *error)
{
    for (size_t h = 0; h < c->half_edge_count; h++)
        g->edge_count += in_graph(c, cutting, h);
    g->ends = ur_alloc_array(g->edge_count, sizeof *g->ends, error);
    g->half_edge = ur_alloc_array(g->edge_count, sizeof *g->half_edge, error);
    g->alive = ur_alloc_array(g->edge_count, sizeof *g->alive, error);
    g->start = ur_alloc_array(c->vertex_count + 1, sizeof *g->start, error);
    g->incident = ur_alloc_array(2 * g->edge_count, sizeof *g->incident, error);
    g->degree = ur_alloc_array(c->vertex_count, sizeof *g->degree, error);
    if (!g->ends || !g->half_edge || !g->alive || !g->start || !g->incident || !g->degree)
        return UR_ERROR_MEMORY;
    return UR_OK;
}

static ur_status graph_build(graph *g, const cutter *c, const bool *cutting, ur_error *error)
{
    ur_status status = graph_alloc(g, c, cutting, error);
    if (status != UR_OK)
        return status;
    size_t e = 0;
    for (size_t h = 0; h < c->half_edge_count; h++) {
        if (!in_graph(c, cutting, h))
            continue;
        g->ends[e][0] = c->corner[h];
        g->ends[e][1] = c->corner[mesh_next(h)];
        g->half_edge[e] = h;
        g->alive[e] = true;
        g->degree[g->ends[e][0]]++;
        g->degree[g->ends[e][1]]++;
        e++;
    }
    for (size_t v = 0; v < c->vertex_count; v++)
        g->start[v + 1] = g->start[v] + g->degree[v];
    size_t *fill = ur_alloc_array(c->vertex_count, sizeof *fill, error);
    if (!fill)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < g->edge_count; i++)
        for (int k = 0; k < 2; k++) {
            size_t v = g->ends[i][k];
            g->incident[g->start[v] + fill[v]++] = i;
        }
    free(fill);
    return UR_OK;
}

/* Removes vertex v's one remaining edge; returns its other end. */
static size_t remove_leaf_edge(graph *g, size_t v)
{
    for (size_t i = g->start[v]; i < g->start[v + 1]; i++) {
        size_t e = g->incident[i];
        if (!g->alive[e])
            continue;
        g->alive[e] = false;
        size_t w = g->ends[e][0] == v ? g->ends[e][1] : g->ends[e][0];
        g->degree[v]--;
        g->degree[w]--;
        return w;
    }
    return v; /* not reached: v had degree 1 */
}

/* Prunes dangling edges: removes edges with an end of degree 1 until there are none. */
static void graph_prune(graph *g, size_t vertex_count, size_t *queue)
{
    size_t head = 0, tail = 0;
    for (size_t v = 0; v < vertex_count; v++)
        if (g->degree[v] == 1)
            queue[tail++] = v;
    while (head < tail) {
        size_t v = queue[head++];
        if (g->degree[v] != 1)
            continue;
        size_t w = remove_leaf_edge(g, v);
        if (g->degree[w] == 1)
            queue[tail++] = w;
    }
}

/* Which parts need cutting, and which of those are spheres. */
static size_t choose_parts(const cutter *c, const part_shape *shapes, bool *cutting, bool *sphere)
{
    size_t count = 0;
    for (size_t p = 0; p < c->part_count; p++) {
        long long euler = part_euler(&shapes[p]);
        cutting[p] = euler != 1 || shapes[p].loops != 1;
        sphere[p] = cutting[p] && euler == 2 && shapes[p].loops == 0;
        count += cutting[p];
    }
    return count;
}

/* What cut.c keeps about the parts while it cuts them. */
typedef struct cutting_state {
    bool *cutting, *sphere, *general;  /* per part; general: cut along G */
    size_t *first_vertex, *first_seam; /* per part */
    size_t *start;    /* per part: where spheres' paths start (first vertex, then the farthest) */
    size_t *outgoing; /* per vertex: the seam half-edge leaving it */
    size_t *sources;
    size_t source_count;
} cutting_state;

static void state_free(cutting_state *s)
{
    free(s->cutting);
    free(s->sphere);
    free(s->general);
    free(s->first_vertex);
    free(s->first_seam);
    free(s->start);
    free(s->outgoing);
    free(s->sources);
}

static ur_status state_alloc(cutting_state *s, const cutter *c, ur_error *error)
{
    size_t n = c->part_count;
    s->cutting = ur_alloc_array(n, sizeof *s->cutting, error);
    s->sphere = ur_alloc_array(n, sizeof *s->sphere, error);
    s->general = ur_alloc_array(n, sizeof *s->general, error);
    s->first_vertex = ur_alloc_array(n, sizeof *s->first_vertex, error);
    s->first_seam = ur_alloc_array(n, sizeof *s->first_seam, error);
    s->start = ur_alloc_array(n, sizeof *s->start, error);
    s->outgoing = ur_alloc_array(c->vertex_count, sizeof *s->outgoing, error);
    s->sources = ur_alloc_array(c->vertex_count, sizeof *s->sources, error);
    if (!s->cutting || !s->sphere || !s->general || !s->first_vertex || !s->first_seam ||
        !s->start || !s->outgoing || !s->sources)
        return UR_ERROR_MEMORY;
    return UR_OK;
}

/* Each part's first vertex and first seam half-edge, and the seam leaving each vertex. */
static void find_firsts(const cutter *c, cutting_state *s)
{
    for (size_t p = 0; p < c->part_count; p++)
        s->first_vertex[p] = s->first_seam[p] = UR_NO_EDGE;
    for (size_t v = 0; v < c->vertex_count; v++)
        s->outgoing[v] = UR_NO_EDGE;
    for (size_t h = 0; h < c->half_edge_count; h++) {
        size_t p = c->part[h / 3];
        if (s->first_vertex[p] == UR_NO_EDGE)
            s->first_vertex[p] = c->corner[h];
        if (c->seam[h]) {
            if (s->first_seam[p] == UR_NO_EDGE)
                s->first_seam[p] = h;
            s->outgoing[c->corner[h]] = h;
        }
    }
    for (size_t p = 0; p < c->part_count; p++)
        s->start[p] = s->first_vertex[p];
}

/* Where the shortest paths start: each part's first boundary loop, else s->start[p]. */
static void gather_sources(const cutter *c, cutting_state *s)
{
    s->source_count = 0;
    for (size_t p = 0; p < c->part_count; p++) {
        if (!s->cutting[p])
            continue;
        size_t h = s->first_seam[p];
        if (h == UR_NO_EDGE) {
            s->sources[s->source_count++] = s->start[p];
            continue;
        }
        /* The loop's length bounds the walk, even if the loop were broken. */
        for (size_t steps = 0; steps < c->half_edge_count; steps++) {
            s->sources[s->source_count++] = c->corner[h];
            h = s->outgoing[c->corner[mesh_next(h)]];
            if (h == UR_NO_EDGE || h == s->first_seam[p])
                break;
        }
    }
}

/* The vertex of each part (with want[p]) farthest from the sources. */
static void farthest(const cutter *c, const mesh_paths *p, const bool *want, size_t *far)
{
    for (size_t h = 0; h < c->half_edge_count; h++) {
        size_t part = c->part[h / 3], v = c->corner[h];
        if (want[part] && p->distance[v] > p->distance[far[part]])
            far[part] = v;
    }
}

/* Unglues the edge of h's triangle that joins vertex v to the corner across from h. */
static void unglue_side(cutter *c, size_t h, size_t v)
{
    cutter_unglue(c, c->corner[mesh_next(h)] == v ? mesh_next(h) : mesh_next(mesh_next(h)));
}

/* Slits each sphere along the path of shortest paths from its farthest vertex. */
static void slit_spheres(cutter *c, const cutting_state *s, const mesh_paths *p, size_t *far)
{
    for (size_t q = 0; q < c->part_count; q++)
        far[q] = s->start[q];
    farthest(c, p, s->sphere, far);
    for (size_t q = 0; q < c->part_count; q++) {
        if (!s->sphere[q])
            continue;
        size_t v = far[q], edges = 0, last = UR_NO_EDGE;
        while (p->via[v] != UR_NO_EDGE) {
            last = p->via[v];
            cutter_unglue(c, last);
            v = cutter_other_end(c, last, v);
            edges++;
        }
        if (edges == 1)
            unglue_side(c, last, far[q]);
    }
}

/* Marks the half-edges of the edges of the shortest-path tree. */
static ur_status mark_tree_edges(const cutter *c, const mesh_paths *p, bool **shortest,
                                 ur_error *error)
{
    *shortest = ur_alloc_array(c->half_edge_count, sizeof **shortest, error);
    if (!*shortest)
        return UR_ERROR_MEMORY;
    for (size_t v = 0; v < c->vertex_count; v++) {
        size_t h = p->via[v];
        if (h == UR_NO_EDGE)
            continue;
        (*shortest)[h] = true;
        if (c->twins[h] != UR_NO_EDGE)
            (*shortest)[c->twins[h]] = true;
    }
    return UR_OK;
}

/* Two FIFO queues of half-edges: crossing into a new triangle for free, or across T. */
typedef struct frontier {
    size_t *cheap, *dear;
    size_t cheap_head, cheap_tail, dear_head, dear_tail;
} frontier;

static void reach(cutter *c, size_t t, const bool *shortest, bool *reached, frontier *f)
{
    reached[t] = true;
    for (size_t h = 3 * t; h < 3 * t + 3; h++) {
        if (c->seam[h] || reached[c->twins[h] / 3])
            continue;
        if (shortest[h])
            f->dear[f->dear_tail++] = h;
        else
            f->cheap[f->cheap_tail++] = h;
    }
}

/* Prim's algorithm from seed, crossing edges of T only when nothing else is left. */
static void grow_tree(cutter *c, size_t seed, const bool *shortest, bool *reached, frontier *f)
{
    f->cheap_head = f->cheap_tail = f->dear_head = f->dear_tail = 0;
    reach(c, seed, shortest, reached, f);
    while (f->cheap_head < f->cheap_tail || f->dear_head < f->dear_tail) {
        size_t h =
            f->cheap_head < f->cheap_tail ? f->cheap[f->cheap_head++] : f->dear[f->dear_head++];
        size_t t = c->twins[h] / 3;
        if (reached[t])
            continue;
        c->tree[h] = c->tree[c->twins[h]] = true;
        reach(c, t, shortest, reached, f);
    }
}

static ur_status grow_trees(cutter *c, const bool *general, const bool *shortest, ur_error *error)
{
    size_t triangle_count = c->mesh->triangle_count;
    bool *reached = ur_alloc_array(triangle_count, sizeof *reached, error);
    frontier f = {0};
    f.cheap = ur_alloc_array(c->half_edge_count, sizeof *f.cheap, error);
    f.dear = ur_alloc_array(c->half_edge_count, sizeof *f.dear, error);
    ur_status status = reached && f.cheap && f.dear ? UR_OK : UR_ERROR_MEMORY;
    for (size_t t = 0; t < triangle_count && status == UR_OK; t++)
        if (general[c->part[t]] && !reached[t])
            grow_tree(c, t, shortest, reached, &f);
    free(reached);
    free(f.cheap);
    free(f.dear);
    return status;
}

/* Cuts the parts that are not spheres along what pruning leaves of G. */
static ur_status cut_along_graph(cutter *c, const bool *general, ur_error *error)
{
    graph g = {0};
    size_t *queue = ur_alloc_array(c->vertex_count, sizeof *queue, error);
    ur_status status = queue ? graph_build(&g, c, general, error) : UR_ERROR_MEMORY;
    if (status == UR_OK) {
        graph_prune(&g, c->vertex_count, queue);
        /* What is left besides the boundary is the cut. */
        for (size_t e = 0; e < g.edge_count; e++)
            if (g.alive[e] && !c->seam[g.half_edge[e]])
                cutter_unglue(c, g.half_edge[e]);
    }
    graph_free(&g);
    free(queue);
    return status;
}

/* Shortest paths, a second time from each sphere's farthest vertex. */
static ur_status find_paths(const cutter *c, cutting_state *s, bool any_sphere, mesh_paths *p,
                            ur_error *error)
{
    gather_sources(c, s);
    ur_status status = mesh_paths_from(c, s->cutting, s->sources, s->source_count, p, error);
    if (status != UR_OK || !any_sphere)
        return status;
    farthest(c, p, s->sphere, s->start);
    mesh_paths_free(p);
    gather_sources(c, s);
    return mesh_paths_from(c, s->cutting, s->sources, s->source_count, p, error);
}

static ur_status cut_parts(cutter *c, cutting_state *s, ur_error *error)
{
    bool any_sphere = false, any_general = false;
    for (size_t p = 0; p < c->part_count; p++) {
        s->general[p] = s->cutting[p] && !s->sphere[p];
        any_sphere |= s->sphere[p];
        any_general |= s->general[p];
    }
    find_firsts(c, s);
    mesh_paths p = {NULL, NULL};
    bool *shortest = NULL;
    ur_status status = find_paths(c, s, any_sphere, &p, error);
    if (status == UR_OK && any_general) {
        status = mark_tree_edges(c, &p, &shortest, error);
        if (status == UR_OK)
            status = grow_trees(c, s->general, shortest, error);
        if (status == UR_OK)
            status = cut_along_graph(c, s->general, error);
    }
    size_t *far =
        status == UR_OK && any_sphere ? ur_alloc_array(c->part_count, sizeof *far, error) : NULL;
    if (status == UR_OK && any_sphere && !far)
        status = UR_ERROR_MEMORY;
    if (status == UR_OK && any_sphere)
        slit_spheres(c, s, &p, far);
    free(far);
    free(shortest);
    mesh_paths_free(&p);
    return status;
}

ur_status cutter_cut(cutter *c, const part_shape *shapes, ur_error *error)
{
    cutting_state s = {0};
    ur_status status = state_alloc(&s, c, error);
    if (status == UR_OK && choose_parts(c, shapes, s.cutting, s.sphere) > 0)
        status = cut_parts(c, &s, error);
    state_free(&s);
    return status;
}
