/*
 * flaps.c: triangles on the same three corners as another.
 *
 * A flap of no thickness is two such triangles back to back, standing on
 * a surface.  Blender's monkey head has one under its chin: two quads that
 * mirror each other each fold a triangle into the mirror plane, and the
 * two triangles meet there back to back.  Left in, the pair makes an edge
 * of four triangles (the flap's foot, and the surface on either side of
 * it), and unfolding gives the flap as a piece of its own that nothing can
 * be glued to.  A pair is such a flap when, the pair taken away, every one
 * of its edges is left with two triangles (the surface closes over the
 * foot) or with none (the flap's own folds), and at least one with two.  A
 * pair that shares an edge with other triangles on repeated corners is
 * left alone: a sheet modelled with a face on each side is such pairs
 * side by side, and taking them away would take the sheet.
 *
 * A duplicate is a face given twice: an extrusion of no length, or a face
 * filled again over one that was there, leaves one in a modeller's file.
 * Its edges then carry three triangles, and the mesh was refused.  Of the
 * triangles on the same corners the first in the file stays; another
 * goes when it runs the same way round (two faces facing the same way on
 * the same corners are never both meant), or when it runs the other way
 * in a surface: one of its edges carries an odd number of triangles
 * (counted again as copies go, so that those of a face of many
 * triangles go from its rim inwards), and at most one (on the surface's
 * rim) carries the two alone.  A sheet with a face on each side has two
 * or four on every edge, and a flap on a sheet's rim carries the two
 * alone on both its folds: both are left as they were.
 */
#include "mesh_internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A triangle's corners in increasing order: the same for a pair, whichever way each runs. */
typedef struct corners_key {
    size_t corner[3];
    size_t triangle;
} corners_key;

static int compare_keys(const void *a, const void *b)
{
    const corners_key *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x->corner[k] != y->corner[k])
            return x->corner[k] < y->corner[k] ? -1 : 1;
    return (x->triangle > y->triangle) - (x->triangle < y->triangle);
}

static corners_key key_of(const size_t (*triangles)[3], size_t t)
{
    size_t a = triangles[t][0], b = triangles[t][1], c = triangles[t][2], swap;
    if (a > b)
        swap = a, a = b, b = swap;
    if (b > c)
        swap = b, b = c, c = swap;
    if (a > b)
        swap = a, a = b, b = swap;
    return (corners_key){{a, b, c}, t};
}

static bool same_corners(const corners_key *x, const corners_key *y)
{
    return memcmp(x->corner, y->corner, sizeof x->corner) == 0;
}

/* Whether triangles s and t run opposite ways round the same corners. */
static bool back_to_back(const size_t (*triangles)[3], size_t s, size_t t)
{
    for (int k = 0; k < 3; k++)
        if (triangles[t][k] == triangles[s][0])
            return triangles[t][(k + 1) % 3] == triangles[s][2];
    return false;
}

/* The first entry on the edge in the sorted edges. */
static size_t first_on_edge(const mesh_edge_key *edges, size_t count, const mesh_edge_key *edge)
{
    size_t from = 0, to = count;
    while (from < to) {
        size_t middle = from + (to - from) / 2;
        if (mesh_compare_edge_ends(&edges[middle], edge) < 0)
            from = middle + 1;
        else
            to = middle;
    }
    return from;
}

typedef struct flap_search {
    const size_t (*triangles)[3];
    mesh_edge_key *edges; /* every triangle's edges, sorted */
    size_t edge_count;
    bool *repeated; /* per triangle: another not dropped has the same corners */
    bool *drop;     /* per triangle: dropped (the caller's) */
} flap_search;

/* The end of the group of keys on the same corners that begins at i. */
static size_t group_end(const corners_key *keys, size_t count, size_t i)
{
    size_t j = i + 1;
    while (j < count && same_corners(&keys[j], &keys[i]))
        j++;
    return j;
}

/* The triangles on an edge, from the sorted edges: [*from, return value). */
static size_t edge_range(const flap_search *p, size_t t, int k, size_t *from)
{
    mesh_edge_key edge = mesh_edge_key_of(p->triangles[t][k], p->triangles[t][(k + 1) % 3], 0);
    size_t i = *from = first_on_edge(p->edges, p->edge_count, &edge);
    while (i < p->edge_count && mesh_compare_edge_ends(&p->edges[i], &edge) == 0)
        i++;
    return i;
}

/*
 * Drops each triangle that runs the same way round as an earlier one on
 * the same corners, not dropped: two faces facing the same way on the
 * same corners are never both meant.
 */
static void drop_same_way(const flap_search *p, const corners_key *keys, size_t count,
                          size_t *duplicates)
{
    for (size_t i = 0, j; i < count; i = j) {
        j = group_end(keys, count, i);
        for (size_t k = i + 1; k < j; k++)
            for (size_t e = i; e < k && !p->drop[keys[k].triangle]; e++)
                if (!p->drop[keys[e].triangle] &&
                    !back_to_back(p->triangles, keys[e].triangle, keys[k].triangle)) {
                    p->drop[keys[k].triangle] = true;
                    (*duplicates)++;
                }
    }
}

/* Marks the triangles not dropped that another not dropped repeats, in p->repeated. */
static void mark_repeated(const flap_search *p, const corners_key *keys, size_t count)
{
    for (size_t i = 0, j; i < count; i = j) {
        j = group_end(keys, count, i);
        size_t kept = 0;
        for (size_t k = i; k < j; k++)
            kept += !p->drop[keys[k].triangle];
        for (size_t k = i; k < j; k++)
            p->repeated[keys[k].triangle] = kept > 1 && !p->drop[keys[k].triangle];
    }
}

/* Whether the pair s, t stands as a flap on the surface (see the top of the file). */
static bool is_flap(const flap_search *p, size_t s, size_t t)
{
    bool foot = false;
    for (int k = 0; k < 3; k++) {
        size_t from, to = edge_range(p, s, k, &from), others = 0;
        for (size_t i = from; i < to; i++) {
            size_t u = p->edges[i].index; /* a triangle on the edge */
            if (u == s || u == t || p->drop[u])
                continue;
            if (p->repeated[u])
                return false;
            others++;
        }
        if (others != 0 && others != 2)
            return false;
        foot = foot || others == 2;
    }
    return foot;
}

/* The first triangle of the group [i, j) not dropped, and the second; false unless just two. */
static bool two_kept(const flap_search *p, const corners_key *keys, size_t i, size_t j,
                     size_t *first, size_t *second)
{
    size_t kept = 0;
    for (size_t k = i; k < j; k++)
        if (!p->drop[keys[k].triangle]) {
            if (kept == 0)
                *first = keys[k].triangle;
            else
                *second = keys[k].triangle;
            kept++;
        }
    return kept == 2;
}

static void find_flaps(const flap_search *p, const corners_key *keys, size_t count, size_t *pairs)
{
    for (size_t i = 0, j; i < count; i = j) {
        j = group_end(keys, count, i);
        size_t s = 0, t = 0;
        if (j - i >= 2 && two_kept(p, keys, i, j, &s, &t) && back_to_back(p->triangles, s, t) &&
            is_flap(p, s, t)) {
            p->drop[s] = p->drop[t] = true;
            (*pairs)++;
        }
    }
}

/*
 * Whether triangle t, back to back with kept on the same corners, doubles
 * a face of a surface: an edge of theirs carries an odd number of the
 * triangles not dropped, and at most one carries the two alone (the rim
 * of an open surface).  A flap standing on the rim of a sheet (its foot
 * on three triangles) has two edges that carry the two alone, its folds;
 * it is not a face given twice, and stays.
 */
static bool doubles_a_face(const flap_search *p, size_t t, size_t kept)
{
    bool odd = false;
    int alone = 0;
    for (int k = 0; k < 3; k++) {
        size_t from, to = edge_range(p, t, k, &from), on = 0, others = 0;
        for (size_t i = from; i < to; i++) {
            size_t u = p->edges[i].index;
            on += !p->drop[u];
            others += !p->drop[u] && u != t && u != kept;
        }
        alone += others == 0;
        odd = odd || on % 2 == 1;
    }
    return odd && alone <= 1;
}

/*
 * Drops the triangles back to back with the first of their group not
 * dropped that double a face inside a surface; true when it dropped any.
 * A copy inside a doubled face of many triangles (a cylinder's cap) has
 * no edge on an odd number until the copies round it are dropped: the
 * caller asks again while copies go.
 */
static bool drop_turned_copies(const flap_search *p, const corners_key *keys, size_t count,
                               size_t *duplicates)
{
    bool dropped = false;
    for (size_t i = 0, j; i < count; i = j) {
        j = group_end(keys, count, i);
        size_t kept = SIZE_MAX;
        for (size_t k = i; k < j; k++) {
            size_t t = keys[k].triangle;
            if (p->drop[t])
                continue;
            if (kept == SIZE_MAX)
                kept = t; /* the first in the file: keys sort by triangle last */
            else if (doubles_a_face(p, t, kept)) {
                p->drop[t] = true;
                (*duplicates)++;
                dropped = true;
            }
        }
    }
    return dropped;
}

/* Flaps and duplicates, once the triangles' edges are listed and sorted. */
static void find_repeated(const flap_search *p, const corners_key *keys, size_t count,
                          size_t *flaps, size_t *duplicates)
{
    drop_same_way(p, keys, count, duplicates);
    mark_repeated(p, keys, count);
    find_flaps(p, keys, count, flaps);
    while (drop_turned_copies(p, keys, count, duplicates))
        ;
}

ur_status mesh_find_repeated(const size_t (*triangles)[3], size_t count, bool *drop, size_t *flaps,
                             size_t *duplicates, ur_error *error)
{
    *flaps = *duplicates = 0;
    memset(drop, 0, count * sizeof *drop);
    corners_key *keys = ur_alloc_array(count, sizeof *keys, error);
    flap_search p = {triangles, NULL, 0, ur_alloc_array(count, sizeof *p.repeated, error), drop};
    if (!keys || !p.repeated) {
        free(keys);
        free(p.repeated);
        return UR_ERROR_MEMORY;
    }
    for (size_t t = 0; t < count; t++)
        keys[t] = key_of(triangles, t);
    qsort(keys, count, sizeof *keys, compare_keys);
    bool any = false;
    for (size_t i = 1; i < count && !any; i++)
        any = same_corners(&keys[i], &keys[i - 1]);
    ur_status status = UR_OK;
    if (any) { /* most meshes have no repeated corners: no edges to list */
        p.edges = ur_alloc_array(3 * count, sizeof *p.edges, error);
        status = p.edges ? UR_OK : UR_ERROR_MEMORY;
        for (size_t t = 0; status == UR_OK && t < count; t++)
            for (int k = 0; k < 3; k++) {
                size_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
                p.edges[p.edge_count++] = mesh_edge_key_of(a, b, t);
            }
        if (status == UR_OK) {
            qsort(p.edges, p.edge_count, sizeof *p.edges, mesh_compare_edge_keys);
            find_repeated(&p, keys, count, flaps, duplicates);
        }
    }
    free(keys);
    free(p.repeated);
    free(p.edges);
    return status;
}
