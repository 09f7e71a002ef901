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
 * inside a surface: one of its edges carries an odd number of triangles
 * (counted again as copies go, so that those of a face of many
 * triangles go from its rim inwards), and none carries the two alone.  A
 * sheet with a face on each side has two or four on every edge, and a
 * flap on a sheet's rim carries the two alone on its folds: both are left
 * as they were.
 */
#include "mesh_internal.h"

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
    bool *repeated; /* per triangle: another has the same corners */
} flap_search;

/* Whether the pair s, t stands as a flap on the surface (see the top of the file). */
static bool is_flap(const flap_search *p, size_t s, size_t t)
{
    bool foot = false;
    for (int k = 0; k < 3; k++) {
        mesh_edge_key edge = mesh_edge_key_of(p->triangles[s][k], p->triangles[s][(k + 1) % 3], 0);
        size_t others = 0;
        for (size_t i = first_on_edge(p->edges, p->edge_count, &edge);
             i < p->edge_count && mesh_compare_edge_ends(&p->edges[i], &edge) == 0; i++) {
            size_t u = p->edges[i].index; /* a triangle on the edge */
            if (u == s || u == t)
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

static void find_flaps(const flap_search *p, const corners_key *keys, size_t count, bool *drop,
                       size_t *pairs)
{
    for (size_t i = 0, j; i < count; i = j) {
        for (j = i + 1; j < count && same_corners(&keys[j], &keys[i]); j++)
            ;
        if (j - i == 2 && back_to_back(p->triangles, keys[i].triangle, keys[i + 1].triangle) &&
            is_flap(p, keys[i].triangle, keys[i + 1].triangle)) {
            drop[keys[i].triangle] = drop[keys[i + 1].triangle] = true;
            (*pairs)++;
        }
    }
}

/*
 * Whether triangle t, back to back with kept on the same corners, doubles
 * a face inside a surface: an edge of theirs carries an odd number of the
 * triangles not dropped, and each carries some triangle besides the two.
 * A flap on the rim of a sheet (its foot on three triangles) has edges
 * that carry the two alone, its folds; it is not a face given twice, and
 * stays.
 */
static bool doubles_a_face(const flap_search *p, const bool *drop, size_t t, size_t kept)
{
    bool odd = false;
    for (int k = 0; k < 3; k++) {
        mesh_edge_key edge = mesh_edge_key_of(p->triangles[t][k], p->triangles[t][(k + 1) % 3], 0);
        size_t on = 0, others = 0;
        for (size_t i = first_on_edge(p->edges, p->edge_count, &edge);
             i < p->edge_count && mesh_compare_edge_ends(&p->edges[i], &edge) == 0; i++) {
            size_t u = p->edges[i].index;
            on += !drop[u];
            others += !drop[u] && u != t && u != kept;
        }
        if (others == 0)
            return false;
        odd = odd || on % 2 == 1;
    }
    return odd;
}

/*
 * Marks the copies in the groups of triangles on the same corners (see the
 * top of the file) among those not dropped as flaps; true when it marked
 * any.  A copy inside a doubled face of many triangles (a cylinder's cap)
 * has no edge on an odd number until the copies round it are dropped: the
 * caller asks again while copies go.
 */
static bool mark_copies(const flap_search *p, const corners_key *keys, size_t count, bool *drop,
                        size_t *duplicates)
{
    bool marked = false;
    for (size_t i = 0, j; i < count; i = j) {
        for (j = i + 1; j < count && same_corners(&keys[j], &keys[i]); j++)
            ;
        size_t kept = keys[i].triangle; /* the first in the file: keys sort by triangle last */
        if (j - i < 2 || drop[kept])
            continue;
        for (size_t k = i + 1; k < j; k++) {
            size_t t = keys[k].triangle;
            if (!drop[t] &&
                (!back_to_back(p->triangles, kept, t) || doubles_a_face(p, drop, t, kept))) {
                drop[t] = true;
                (*duplicates)++;
                marked = true;
            }
        }
    }
    return marked;
}

static void find_duplicates(const flap_search *p, const corners_key *keys, size_t count, bool *drop,
                            size_t *duplicates)
{
    while (mark_copies(p, keys, count, drop, duplicates))
        ;
}

ur_status mesh_find_repeated(const size_t (*triangles)[3], size_t count, bool *drop, size_t *flaps,
                             size_t *duplicates, ur_error *error)
{
    *flaps = *duplicates = 0;
    memset(drop, 0, count * sizeof *drop);
    corners_key *keys = ur_alloc_array(count, sizeof *keys, error);
    flap_search p = {triangles, NULL, 0, ur_alloc_array(count, sizeof *p.repeated, error)};
    if (!keys || !p.repeated) {
        free(keys);
        free(p.repeated);
        return UR_ERROR_MEMORY;
    }
    for (size_t t = 0; t < count; t++)
        keys[t] = key_of(triangles, t);
    qsort(keys, count, sizeof *keys, compare_keys);
    bool any = false;
    for (size_t i = 0; i < count; i++) {
        p.repeated[keys[i].triangle] = (i > 0 && same_corners(&keys[i], &keys[i - 1])) ||
                                       (i + 1 < count && same_corners(&keys[i], &keys[i + 1]));
        any = any || p.repeated[keys[i].triangle];
    }
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
            find_flaps(&p, keys, count, drop, flaps);
            find_duplicates(&p, keys, count, drop, duplicates);
        }
    }
    free(keys);
    free(p.repeated);
    free(p.edges);
    return status;
}
