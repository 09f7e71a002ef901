/*
 * unfold.c: ur_unfold: the exact unfolding of a polyhedral mesh along its
 * edges, grown piece by piece.
 *
 * A piece starts from the first triangle not yet laid and grows across the
 * cheapest edge on its border (a binary heap of border edges: Prim's
 * algorithm on the faces' graph).  Flat edges cost nothing, convex ones
 * their turn, concave ones pi more than that, so a piece folds across
 * gentle convex edges first and leaves sharp and concave ones to be cut
 * where it can.  The new triangle is laid rigidly on the shared edge
 * (unfold_lay.c) and kept only if it fits: it must not overlap the piece,
 * nor touch it anywhere but at the flat vertices it shares with it, so
 * that the piece stays a disk that can be cut out whole.  A triangle that
 * does not fit may still fit when reached across another edge, later in
 * this piece or in another.
 */
#include "unfold_internal.h"

#include <stdlib.h>

/* ---- the border of the growing piece: a binary heap of half-edges ---- */

typedef struct border_edge {
    double weight, length;
    size_t half; /* in a laid triangle; its twin's triangle is not laid */
} border_edge;

/* Room for 3 n edges: a triangle is laid once and puts at most its three edges here. */
typedef struct border {
    border_edge *items;
    size_t count;
} border;

/* Cheapest first; at equal weight the longer edge, so that short edges are cut. */
static bool before(border_edge a, border_edge b)
{
    if (a.weight != b.weight)
        return a.weight < b.weight;
    if (a.length != b.length)
        return a.length > b.length;
    return a.half < b.half;
}

static void border_push(border *b, border_edge edge)
{
    size_t i = b->count++;
    while (i > 0 && before(edge, b->items[(i - 1) / 2])) {
        b->items[i] = b->items[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    b->items[i] = edge;
}

static size_t border_pop(border *b)
{
    size_t top = b->items[0].half;
    border_edge last = b->items[--b->count];
    size_t i = 0;
    for (;;) {
        size_t child = 2 * i + 1;
        if (child >= b->count)
            break;
        if (child + 1 < b->count && before(b->items[child + 1], b->items[child]))
            child++;
        if (!before(b->items[child], last))
            break;
        b->items[i] = b->items[child];
        i = child;
    }
    if (b->count > 0)
        b->items[i] = last;
    return top;
}

/* What folding across an edge costs: flat, then convex by turn, then concave. */
static double fold_weight(double bend)
{
    if (fabs(bend) < UR_UNFOLD_FLAT_ANGLE)
        return 0.0;
    return bend > 0 ? bend : M_PI - bend;
}

/* The edges of triangle t that could take the piece further. */
static void push_border(const unfolder *u, border *b, size_t t)
{
    for (size_t h = 3 * t; h < 3 * t + 3; h++) {
        if (u->edges.cut[h] || u->joined[h] || u->piece[u->edges.twins[h] / 3] != UNFOLD_NONE)
            continue;
        double length = ur_vec3_distance(u->mesh->vertices[unfold_from(u->mesh, h)],
                                         u->mesh->vertices[unfold_to(u->mesh, h)]);
        border_push(b, (border_edge){fold_weight(u->edges.bend[h]), length, h});
    }
}

/* ---- growing ---- */

static ur_status lay(unfolder *u, unfold_grid *grid, border *b, const unfold_candidate *c,
                     ur_error *error)
{
    ur_status status = unfold_commit(u, grid, c, error);
    if (status == UR_OK)
        push_border(u, b, c->triangle);
    return status;
}

/* Grows piece u->current from seed until no edge on its border takes a triangle that fits. */
static ur_status grow(unfolder *u, unfold_grid *grid, border *b, size_t seed, ur_error *error)
{
    u->member_count = 0;
    b->count = 0;
    unfold_grid_restart(grid);
    unfold_candidate c;
    unfold_seed(u, seed, &c);
    ur_status status = lay(u, grid, b, &c, error);
    while (status == UR_OK && b->count > 0) {
        size_t g = u->edges.twins[border_pop(b)];
        if (u->piece[g / 3] != UNFOLD_NONE)
            continue;
        if (unfold_prepare(u, g, &c) && unfold_fits(u, grid, &c))
            status = lay(u, grid, b, &c, error);
    }
    return status;
}

/* ---- the unfolding ---- */

size_t unfold_find(unfolder *u, size_t corner)
{
    while (u->parent[corner] != corner) {
        u->parent[corner] = u->parent[u->parent[corner]];
        corner = u->parent[corner];
    }
    return corner;
}

static ur_status unfolder_init(unfolder *u, const ur_mesh *mesh, const ur_seam *seams,
                               size_t seam_count, ur_error *error)
{
    *u = (unfolder){.mesh = mesh};
    ur_status status = unfold_edges_build(mesh, seams, seam_count, &u->edges, error);
    if (status != UR_OK)
        return status;
    size_t n = mesh->triangle_count;
    u->piece = ur_alloc_array(n, sizeof *u->piece, error);
    u->flat = ur_alloc_array(n, sizeof *u->flat, error);
    u->joined = ur_alloc_array(3 * n, sizeof *u->joined, error);
    u->parent = ur_alloc_array(3 * n, sizeof *u->parent, error);
    u->members = ur_alloc_array(n, sizeof *u->members, error);
    if (!u->piece || !u->flat || !u->joined || !u->parent || !u->members)
        return UR_ERROR_INTERNAL;
    for (size_t t = 0; t < n; t++)
        u->piece[t] = UNFOLD_NONE;
    for (size_t c = 0; c < 3 * n; c++)
        u->parent[c] = c;
    u->eps = UNFOLD_CONTACT * u->edges.scale;
    return UR_OK;
}

static void unfolder_free(unfolder *u)
{
    unfold_edges_free(&u->edges);
    free(u->piece);
    free(u->flat);
    free(u->joined);
    free(u->parent);
    free(u->members);
}

/* Folds, flat joins, seams and boundary edges, each edge counted once. */
static void count_edges(const unfolder *u, ur_unfolding *out)
{
    for (size_t h = 0; h < 3 * u->mesh->triangle_count; h++) {
        size_t g = u->edges.twins[h];
        if (g == UR_NO_EDGE)
            out->boundary++;
        else if (h > g)
            continue;
        else if (!u->joined[h])
            out->seams++;
        else if (fabs(u->edges.bend[h]) < UR_UNFOLD_FLAT_ANGLE)
            out->flat++;
        else {
            out->folds++;
            out->valleys += u->edges.bend[h] < 0;
        }
    }
}

/* Grows every piece, one from each triangle not yet laid. */
static ur_status grow_all(unfolder *u, GEOSContextHandle_t geos, ur_unfolding *out, ur_error *error)
{
    size_t n = u->mesh->triangle_count;
    unfold_grid grid;
    border b = {ur_alloc_array(3 * n, sizeof *b.items, error), 0};
    out->pieces = ur_alloc_array(n, sizeof *out->pieces, error);
    ur_status status = unfold_grid_init(&grid, n, u->edges.mean_edge, error);
    if (!b.items || !out->pieces)
        status = UR_ERROR_INTERNAL;
    for (size_t seed = 0; seed < n && status == UR_OK; seed++) {
        if (u->piece[seed] != UNFOLD_NONE)
            continue;
        u->current = out->count;
        status = grow(u, &grid, &b, seed, error);
        if (status == UR_OK)
            status = unfold_piece_build(u, geos, &out->pieces[out->count], error);
        if (status == UR_OK)
            out->count++;
    }
    unfold_grid_free(&grid);
    free(b.items);
    /* Room was made for a piece per triangle; give back what is not used. */
    ur_unfolded_piece *fitted = status == UR_OK && out->count > 0
                                    ? realloc(out->pieces, out->count * sizeof *fitted)
                                    : NULL;
    if (fitted)
        out->pieces = fitted;
    return status;
}

ur_status ur_unfold(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count, ur_unfolding *out,
                    ur_error *error)
{
    *out = (ur_unfolding){0};
    unfolder u;
    ur_status status = unfolder_init(&u, mesh, seams, seam_count, error);
    GEOSContextHandle_t geos = status == UR_OK ? GEOS_init_r() : NULL;
    if (status == UR_OK && !geos)
        status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not be started");
    if (status == UR_OK)
        status = grow_all(&u, geos, out, error);
    if (status == UR_OK)
        count_edges(&u, out);
    if (geos)
        GEOS_finish_r(geos);
    unfolder_free(&u);
    if (status != UR_OK)
        ur_unfolding_free(out);
    return status;
}

void ur_unfolding_free(ur_unfolding *unfolding)
{
    if (!unfolding)
        return;
    for (size_t i = 0; i < unfolding->count; i++)
        unfold_piece_free(&unfolding->pieces[i]);
    free(unfolding->pieces);
    *unfolding = (ur_unfolding){0};
}
