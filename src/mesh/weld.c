/*
 * weld.c: merging vertices that lie within a tolerance of each other, as a
 * triangle soup (an STL file: every triangle with its own three corners)
 * needs before it has any edges to share.
 *
 * A spatial hash keeps it linear: space is cut into cubes of side four
 * times the tolerance, and each cube hashes to a slot of a table twice as
 * large as the vertex count.  The points within the tolerance of a vertex
 * then lie in at most 2 x 2 x 2 cubes, and on average in 1.5 x 1.5 x 1.5:
 * 3.4 slots to look in, where cubes of side 2 tolerance would need 8 and
 * cubes of the tolerance 27 (each look is a cache miss on a big mesh),
 * while a cube still holds few vertices (kept ones are more than the
 * tolerance apart).  Vertices are taken in order; each is
 * merged into the nearest kept vertex within the tolerance, or kept and
 * chained into its slot.  Slots are not told apart by cube: a chain may mix
 * cubes that collide, which costs a distance test, never a wrong merge.
 * Merging is greedy, not transitive: of three vertices 0.8 tolerance apart
 * in a row, the first two merge and the third stays, so a tolerance never
 * pulls a whole fine mesh into one point.
 */
#include "mesh_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

typedef struct grid {
    const ur_vec3 *vertices;
    double tolerance, cell;
    size_t mask;   /* table size - 1: a power of two */
    size_t *heads; /* per slot: the last kept vertex hashed there, or UR_NO_VERTEX */
    size_t *next;  /* per kept vertex: the one kept before it in the same slot */
} grid;

/* The cube of a coordinate; clamped so that huge coordinates share a cube rather than overflow. */
static int64_t cube_of(double x, double cell)
{
    double index = floor(x / cell);
    const double limit = 4e18;
    if (index > limit)
        return (int64_t)limit;
    if (index < -limit)
        return -(int64_t)limit;
    return (int64_t)index;
}

static size_t slot_of(const grid *g, int64_t i, int64_t j, int64_t k)
{
    uint64_t h = (uint64_t)i * 0x9E3779B97F4A7C15u ^ (uint64_t)j * 0xC2B2AE3D27D4EB4Fu ^
                 (uint64_t)k * 0x165667B19E3779F9u;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9u;
    h ^= h >> 29;
    return (size_t)h & g->mask;
}

/*
 * Side of the cubes: four times the tolerance, but not so small against the
 * mesh that coordinates in cubes run out of range, and never zero, so that a
 * tolerance of 0 (merge only identical points) works too.
 */
static double cell_size(const ur_vec3 *vertices, size_t count, double tolerance)
{
    double extent = 0;
    for (size_t v = 0; v < count; v++) {
        double m = fmax(fabs(vertices[v].x), fmax(fabs(vertices[v].y), fabs(vertices[v].z)));
        extent = fmax(extent, m);
    }
    double cell = fmax(4 * tolerance, extent * 1e-12);
    return cell > 0 ? cell : 1;
}

static ur_status grid_init(grid *g, const ur_vec3 *vertices, size_t count, double tolerance,
                           ur_error *error)
{
    size_t slots = 16;
    while (slots < 2 * count)
        slots *= 2;
    g->vertices = vertices;
    g->tolerance = tolerance;
    g->cell = cell_size(vertices, count, tolerance);
    g->mask = slots - 1;
    g->heads = ur_alloc_array(slots, sizeof *g->heads, error);
    g->next = ur_alloc_array(count, sizeof *g->next, error);
    if (!g->heads || !g->next)
        return UR_ERROR_MEMORY;
    for (size_t s = 0; s < slots; s++)
        g->heads[s] = UR_NO_VERTEX;
    return UR_OK;
}

/* The nearest kept vertex within the tolerance of p in one slot, improving *best. */
static void search_slot(const grid *g, size_t slot, ur_vec3 p, size_t *best, double *best_d2)
{
    double limit = g->tolerance * g->tolerance;
    for (size_t w = g->heads[slot]; w != UR_NO_VERTEX; w = g->next[w]) {
        ur_vec3 d = ur_vec3_sub(g->vertices[w], p);
        double d2 = ur_vec3_dot(d, d);
        if (d2 <= limit && (d2 < *best_d2 || (d2 == *best_d2 && w < *best))) {
            *best = w;
            *best_d2 = d2;
        }
    }
}

/* The kept vertex p merges into, or UR_NO_VERTEX. */
static size_t find_partner(const grid *g, ur_vec3 p)
{
    double r = g->tolerance, c = g->cell;
    int64_t x0 = cube_of(p.x - r, c), x1 = cube_of(p.x + r, c);
    int64_t y0 = cube_of(p.y - r, c), y1 = cube_of(p.y + r, c);
    int64_t z0 = cube_of(p.z - r, c), z1 = cube_of(p.z + r, c);
    size_t best = UR_NO_VERTEX;
    double best_d2 = INFINITY;
    for (int64_t i = x0; i <= x1; i++)
        for (int64_t j = y0; j <= y1; j++)
            for (int64_t k = z0; k <= z1; k++)
                search_slot(g, slot_of(g, i, j, k), p, &best, &best_d2);
    return best;
}

static void keep(grid *g, size_t v)
{
    ur_vec3 p = g->vertices[v];
    size_t slot = slot_of(g, cube_of(p.x, g->cell), cube_of(p.y, g->cell), cube_of(p.z, g->cell));
    g->next[v] = g->heads[slot];
    g->heads[slot] = v;
}

ur_status mesh_weld(const ur_vec3 *vertices, size_t count, double tolerance, size_t *map,
                    size_t *welded, ur_error *error)
{
    grid g = {0};
    ur_status status = grid_init(&g, vertices, count, tolerance, error);
    *welded = 0;
    for (size_t v = 0; v < count && status == UR_OK; v++) {
        size_t partner = find_partner(&g, vertices[v]);
        if (partner == UR_NO_VERTEX) {
            map[v] = v;
            keep(&g, v);
        } else {
            map[v] = partner;
            ++*welded;
        }
    }
    free(g.heads);
    free(g.next);
    return status;
}
