/*
 * charts.c: a mesh cut into charts that each lie flat within the
 * material's strain (ur_flatten_charts).
 *
 * First the mesh is cut at its sharp edges (faces turning by more than
 * UR_CHART_SHARP_ANGLE), at the user's seams and between groups, and into
 * disks (ur_mesh_pieces).  Each disk is laid flat (ur_flatten, which turns
 * no triangle over) and scaled into the limits where its strain's spread
 * allows (ur_flat_piece_fit_limits).  A chart still over the limits is cut
 * in two as D-Charts (Julius, Kraevoy and Sheffer 2005) grows its charts:
 * two proxies, each a plane's normal, two seed triangles, and a region
 * grown from each across the triangles' edges, cheapest triangle first,
 * the cost being how far a triangle's normal is from the proxy's plus how
 * far it lies from the seed; the proxies are refitted to their regions and
 * the regions grown again a few times (Lloyd's iteration).  Both halves go
 * back to be laid flat, and so on until every chart fits: a single
 * triangle always does, so it ends.  Where the strain grows with a chart's
 * size, as on any curved surface, the halves strain less; a sphere's
 * charts strain by about the square of their size over its radius.
 *
 * Last, neighbouring charts are joined again where the two together are
 * one disk that still lies flat within the limits (never across a sharp
 * edge or a seam): the pairs with the smaller chart smallest first, then
 * the longest shared edges, so that stray small charts join a neighbour
 * first.  Cutting in two halves a chart wherever it is over, though a
 * narrower cut elsewhere might have done; joining takes back the cuts that
 * were not needed, and on a sphere it joins the caps that halving leaves
 * into long gores, which strain less for their area (by the square of
 * their width, not of their length): a 512-face sphere in 0.3 mm paper
 * goes from 96 charts to 18.  Then the borders are smoothed: a triangle
 * that meets another chart along two of its edges (a tooth of a border
 * grown triangle by triangle) moves over to it, pair of charts by pair,
 * where both still lie flat within the limits; that shortens the borders
 * by 3 to 10 %.
 */
#include "unroll/flatten.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NONE ((size_t)-1)
#define UNGROWN ((size_t)-2) /* region of a triangle of the set being cut, not yet grown to */

/* A turn this little over UR_CHART_SHARP_ANGLE is still not sharp (rounding). */
#define SHARP_MARGIN 1e-3

/* Rounds of moving the triangles that jut from one chart into another. */
enum { SMOOTHING_ROUNDS = 4 };

/* Rounds of refitting the proxies and growing the regions again. */
enum { LLOYD_ROUNDS = 3 };

/*
 * The weight of the distance from the seed in a triangle's cost, against
 * 1 - cos of its normal's angle from the proxy's: a triangle across the
 * region's whole size costs as much as one turned by 60 degrees.
 */
#define COMPACTNESS 0.5

/* A set of the input mesh's triangles. */
typedef struct triangle_set {
    size_t *triangles;
    size_t count;
} triangle_set;

typedef struct charting {
    const ur_mesh *mesh;
    const ur_strip_limits *limits;
    const ur_flatten_options *options;
    size_t *twins;
    bool *cut; /* per half-edge: sharp, a user's seam or between groups: never joined */
    ur_vec3 *normals, *centres;
    double *areas;
    size_t *region;      /* per input triangle: 0 or 1 while a set is cut in two, else NONE */
    size_t *vertex_map;  /* per input vertex: its number in the mesh being built, else NONE */
    triangle_set *queue; /* sets still to lay out */
    size_t queued, queue_capacity;
    ur_charts *charts;
    size_t chart_capacity;
} charting;

/* ---- Geometry of the input mesh ---- */

static ur_status measure_triangles(charting *c, ur_error *error)
{
    const ur_mesh *m = c->mesh;
    c->normals = ur_alloc_array(m->triangle_count, sizeof *c->normals, error);
    c->centres = ur_alloc_array(m->triangle_count, sizeof *c->centres, error);
    c->areas = ur_alloc_array(m->triangle_count, sizeof *c->areas, error);
    c->region = ur_alloc_array(m->triangle_count, sizeof *c->region, error);
    c->vertex_map = ur_alloc_array(m->vertex_count, sizeof *c->vertex_map, error);
    if (!c->normals || !c->centres || !c->areas || !c->region || !c->vertex_map)
        return UR_ERROR_MEMORY;
    for (size_t t = 0; t < m->triangle_count; t++) {
        ur_vec3 a = m->vertices[m->triangles[t][0]], b = m->vertices[m->triangles[t][1]];
        ur_vec3 d = m->vertices[m->triangles[t][2]];
        ur_vec3 n = ur_vec3_cross(ur_vec3_sub(b, a), ur_vec3_sub(d, a));
        double length = ur_vec3_length(n);
        c->areas[t] = 0.5 * length;
        c->normals[t] = length > 0 ? ur_vec3_scale(n, 1 / length) : ur_vec3_make(0, 0, 0);
        c->centres[t] = ur_vec3_scale(ur_vec3_add(ur_vec3_add(a, b), d), 1.0 / 3);
        c->region[t] = NONE;
    }
    for (size_t v = 0; v < m->vertex_count; v++)
        c->vertex_map[v] = NONE;
    return ur_mesh_twins(m, &c->twins, error);
}

bool ur_chart_edge_is_sharp(const ur_mesh *mesh, size_t t, size_t u)
{
    const size_t *a = mesh->triangles[t], *b = mesh->triangles[u];
    ur_vec3 na = ur_vec3_cross(ur_vec3_sub(mesh->vertices[a[1]], mesh->vertices[a[0]]),
                               ur_vec3_sub(mesh->vertices[a[2]], mesh->vertices[a[0]]));
    ur_vec3 nb = ur_vec3_cross(ur_vec3_sub(mesh->vertices[b[1]], mesh->vertices[b[0]]),
                               ur_vec3_sub(mesh->vertices[b[2]], mesh->vertices[b[0]]));
    double la = ur_vec3_length(na), lb = ur_vec3_length(nb);
    if (!(la > 0) || !(lb > 0))
        return false;
    return ur_vec3_dot(na, nb) < cos(UR_CHART_SHARP_ANGLE + SHARP_MARGIN) * la * lb;
}

/* An edge by its ends, the lower first. */
typedef struct edge_key {
    size_t low, high;
} edge_key;

static edge_key key_of(size_t a, size_t b)
{
    return a < b ? (edge_key){a, b} : (edge_key){b, a};
}

static int compare_keys(const void *a, const void *b)
{
    const edge_key *x = a, *y = b;
    if (x->low != y->low)
        return (x->low > y->low) - (x->low < y->low);
    return (x->high > y->high) - (x->high < y->high);
}

/* Marks the half-edges (both sides) of the user's seams in c->cut. */
static ur_status mark_seams(charting *c, const ur_seam *seams, size_t seam_count, ur_error *error)
{
    const ur_mesh *m = c->mesh;
    edge_key *keys = ur_alloc_array(seam_count, sizeof *keys, error);
    if (!keys)
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < seam_count; k++)
        keys[k] = key_of(seams[k].a, seams[k].b);
    qsort(keys, seam_count, sizeof *keys, compare_keys);
    for (size_t h = 0; seam_count > 0 && h < 3 * m->triangle_count; h++) {
        edge_key key = key_of(m->triangles[h / 3][h % 3], m->triangles[h / 3][(h % 3 + 1) % 3]);
        if (bsearch(&key, keys, seam_count, sizeof *keys, compare_keys))
            c->cut[h] = true;
    }
    free(keys);
    return UR_OK;
}

/* Marks the half-edges between two groups in c->cut (ur_mesh_pieces cuts there itself). */
static void mark_groups(charting *c)
{
    const ur_mesh *m = c->mesh;
    for (size_t h = 0; m->groups && h < 3 * m->triangle_count; h++)
        if (c->twins[h] != NONE && m->groups[h / 3] != m->groups[c->twins[h] / 3])
            c->cut[h] = true;
}

/*
 * The user's seams and every sharp edge, once each; both marked in c->cut,
 * and the boundaries between groups too.
 */
static ur_status cut_edges(charting *c, const ur_seam *seams, size_t seam_count, ur_seam **cuts,
                           size_t *cut_count, size_t *sharp, ur_error *error)
{
    const ur_mesh *m = c->mesh;
    *sharp = 0;
    *cut_count = 0;
    c->cut = ur_alloc_array(3 * m->triangle_count, sizeof *c->cut, error);
    *cuts = ur_alloc_array(seam_count + 3 * m->triangle_count / 2 + 1, sizeof **cuts, error);
    if (!*cuts || !c->cut)
        return UR_ERROR_MEMORY;
    ur_status status = mark_seams(c, seams, seam_count, error);
    if (status)
        return status;
    mark_groups(c);
    for (size_t s = 0; s < seam_count; s++)
        (*cuts)[(*cut_count)++] = seams[s];
    for (size_t h = 0; h < 3 * m->triangle_count; h++) {
        size_t twin = c->twins[h];
        if (twin == NONE || twin < h || !ur_chart_edge_is_sharp(m, h / 3, twin / 3))
            continue;
        size_t t = h / 3, k = h % 3;
        (*cuts)[(*cut_count)++] = (ur_seam){m->triangles[t][k], m->triangles[t][(k + 1) % 3]};
        c->cut[h] = c->cut[twin] = true;
        ++*sharp;
    }
    return UR_OK;
}

/* ---- The queue of sets and the charts made ---- */

static ur_status queue_set(charting *c, triangle_set set, ur_error *error)
{
    triangle_set *grown =
        ur_array_grow(c->queue, &c->queue_capacity, c->queued, sizeof *grown, 16, error);
    if (!grown) {
        free(set.triangles);
        return UR_ERROR_MEMORY;
    }
    c->queue = grown;
    c->queue[c->queued++] = set;
    return UR_OK;
}

static ur_status add_chart(charting *c, ur_mesh_piece *piece, ur_flat_piece *flat, ur_error *error)
{
    ur_chart *grown = ur_array_grow(c->charts->charts, &c->chart_capacity, c->charts->count,
                                    sizeof *grown, 16, error);
    if (!grown)
        return UR_ERROR_MEMORY;
    c->charts->charts = grown;
    c->charts->charts[c->charts->count++] = (ur_chart){*piece, *flat};
    memset(piece, 0, sizeof *piece);
    memset(flat, 0, sizeof *flat);
    return UR_OK;
}

/*
 * The triangles of set as a mesh of their own (vertices numbered in order
 * of first use), with the input vertex of each of its vertices.
 */
static ur_status subset_mesh(charting *c, const triangle_set *set, ur_mesh *sub, size_t **originals,
                             ur_error *error)
{
    const ur_mesh *m = c->mesh;
    size_t(*triangles)[3] = ur_alloc_array(set->count, sizeof *triangles, error);
    size_t *original = ur_alloc_array(3 * set->count, sizeof *original, error);
    ur_vec3 *vertices = ur_alloc_array(3 * set->count, sizeof *vertices, error);
    size_t used = 0;
    ur_status status = triangles && original && vertices ? UR_OK : UR_ERROR_MEMORY;
    for (size_t i = 0; !status && i < set->count; i++)
        for (int k = 0; k < 3; k++) {
            size_t v = m->triangles[set->triangles[i]][k];
            if (c->vertex_map[v] == NONE) {
                c->vertex_map[v] = used;
                original[used] = v;
                vertices[used++] = m->vertices[v];
            }
            triangles[i][k] = c->vertex_map[v];
        }
    for (size_t i = 0; original && i < used; i++)
        c->vertex_map[original[i]] = NONE;
    if (!status)
        status = ur_mesh_new(vertices, used, (const size_t(*)[3])triangles, set->count, NULL, sub,
                             error);
    free(triangles);
    free(vertices);
    if (status)
        free(original);
    else
        *originals = original;
    return status;
}

/* Renumbers a piece of the subset into the input mesh's vertices, triangles and groups. */
static void to_input(const charting *c, const triangle_set *set, const size_t *originals,
                     ur_mesh_piece *piece)
{
    for (size_t v = 0; v < piece->mesh.vertex_count; v++)
        piece->original[v] = originals[piece->original[v]];
    for (size_t t = 0; t < piece->mesh.triangle_count; t++) {
        size_t input = set->triangles[piece->source_triangles[t]];
        piece->source_triangles[t] = input;
        piece->mesh.groups[t] = c->mesh->groups ? c->mesh->groups[input] : 0;
    }
    piece->mesh.group_count = c->mesh->group_count;
}

/*
 * The subset cut into disks, renumbered into the input mesh; the caller
 * frees them with ur_mesh_pieces_free.
 */
static ur_status disks_of_set(charting *c, const triangle_set *set, ur_mesh_piece **disks,
                              size_t *count, ur_error *error)
{
    ur_mesh sub;
    size_t *originals = NULL;
    ur_status status = subset_mesh(c, set, &sub, &originals, error);
    if (status)
        return status;
    status = ur_mesh_pieces(&sub, NULL, 0, disks, count, error);
    for (size_t k = 0; !status && k < *count; k++)
        to_input(c, set, originals, &(*disks)[k]);
    free(originals);
    ur_mesh_free(&sub);
    return status;
}

/* ---- Cutting a chart in two (D-Charts' region growing) ---- */

typedef struct candidate {
    double cost;
    size_t triangle, region;
} candidate;

typedef struct heap {
    candidate *items;
    size_t count;
} heap;

static void heap_push(heap *h, candidate item)
{
    size_t i = h->count++;
    while (i > 0 && h->items[(i - 1) / 2].cost > item.cost) {
        h->items[i] = h->items[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h->items[i] = item;
}

static candidate heap_pop(heap *h)
{
    candidate top = h->items[0], last = h->items[--h->count];
    size_t i = 0;
    for (;;) {
        size_t child = 2 * i + 1;
        if (child >= h->count)
            break;
        if (child + 1 < h->count && h->items[child + 1].cost < h->items[child].cost)
            child++;
        if (h->items[child].cost >= last.cost)
            break;
        h->items[i] = h->items[child];
        i = child;
    }
    if (h->count > 0)
        h->items[i] = last;
    return top;
}

/* Two regions of a set: their proxies' normals, their seeds, and the set's size. */
typedef struct split {
    ur_vec3 proxy[2];
    size_t seed[2];
    double size;
} split;

/* What adding triangle t to region k costs: how far its normal turns, how far it lies. */
static double cost_of(const charting *c, const split *s, size_t t, size_t k)
{
    double away = ur_vec3_distance(c->centres[t], c->centres[s->seed[k]]) / s->size;
    return 1 - ur_vec3_dot(c->normals[t], s->proxy[k]) + COMPACTNESS * away * away;
}

/*
 * Grows the two regions from their seeds over the set's triangles (the
 * others' region is NONE); every triangle of a connected set ends in one,
 * any other in region 0.
 */
static void grow(charting *c, const triangle_set *set, const split *s, heap *h)
{
    for (size_t i = 0; i < set->count; i++)
        c->region[set->triangles[i]] = UNGROWN;
    h->count = 0;
    for (size_t k = 0; k < 2; k++)
        heap_push(h, (candidate){0, s->seed[k], k});
    while (h->count > 0) {
        candidate next = heap_pop(h);
        if (c->region[next.triangle] != UNGROWN)
            continue;
        c->region[next.triangle] = next.region;
        for (int e = 0; e < 3; e++) {
            size_t twin = c->twins[3 * next.triangle + e];
            if (twin == NONE || c->region[twin / 3] != UNGROWN)
                continue;
            heap_push(h, (candidate){cost_of(c, s, twin / 3, next.region), twin / 3, next.region});
        }
    }
    for (size_t i = 0; i < set->count; i++)
        if (c->region[set->triangles[i]] == UNGROWN)
            c->region[set->triangles[i]] = 0;
}

static ur_vec3 unit_or(ur_vec3 v, ur_vec3 fallback)
{
    double length = ur_vec3_length(v);
    return length > 0 ? ur_vec3_scale(v, 1 / length) : fallback;
}

/* The seeds: the triangle turned farthest from the mean, and the one turned farthest from it. */
static void first_seeds(const charting *c, const triangle_set *set, split *s)
{
    ur_vec3 mean = ur_vec3_make(0, 0, 0);
    for (size_t i = 0; i < set->count; i++)
        mean = ur_vec3_add(
            mean, ur_vec3_scale(c->normals[set->triangles[i]], c->areas[set->triangles[i]]));
    s->seed[0] = s->seed[1] = set->triangles[0];
    for (size_t i = 0; i < set->count; i++)
        if (ur_vec3_dot(c->normals[set->triangles[i]], mean) <
            ur_vec3_dot(c->normals[s->seed[0]], mean))
            s->seed[0] = set->triangles[i];
    ur_vec3 first = c->normals[s->seed[0]];
    for (size_t i = 0; i < set->count; i++)
        if (ur_vec3_dot(c->normals[set->triangles[i]], first) <
            ur_vec3_dot(c->normals[s->seed[1]], first))
            s->seed[1] = set->triangles[i];
    if (s->seed[1] == s->seed[0] || ur_vec3_dot(c->normals[s->seed[1]], first) > 1 - 1e-9) {
        /* All turned alike: the farthest apart instead. */
        for (size_t i = 0; i < set->count; i++)
            if (ur_vec3_distance(c->centres[set->triangles[i]], c->centres[s->seed[0]]) >
                ur_vec3_distance(c->centres[s->seed[1]], c->centres[s->seed[0]]))
                s->seed[1] = set->triangles[i];
    }
    s->size = 0;
    for (size_t i = 0; i < set->count; i++)
        s->size =
            fmax(s->size, ur_vec3_distance(c->centres[set->triangles[i]], c->centres[s->seed[0]]));
    if (!(s->size > 0))
        s->size = 1;
    for (size_t k = 0; k < 2; k++)
        s->proxy[k] = c->normals[s->seed[k]];
}

/* Each proxy the area-weighted mean normal of its region, each seed its region's best fit. */
static void refit(const charting *c, const triangle_set *set, split *s)
{
    ur_vec3 sum[2] = {{0, 0, 0}, {0, 0, 0}}, centre[2] = {{0, 0, 0}, {0, 0, 0}};
    double area[2] = {0, 0};
    for (size_t i = 0; i < set->count; i++) {
        size_t t = set->triangles[i], k = c->region[t];
        sum[k] = ur_vec3_add(sum[k], ur_vec3_scale(c->normals[t], c->areas[t]));
        centre[k] = ur_vec3_add(centre[k], ur_vec3_scale(c->centres[t], c->areas[t]));
        area[k] += c->areas[t];
    }
    double best[2] = {INFINITY, INFINITY};
    for (size_t k = 0; k < 2; k++) {
        s->proxy[k] = unit_or(sum[k], s->proxy[k]);
        if (area[k] > 0)
            centre[k] = ur_vec3_scale(centre[k], 1 / area[k]);
    }
    for (size_t i = 0; i < set->count; i++) {
        size_t t = set->triangles[i], k = c->region[t];
        double away = ur_vec3_distance(c->centres[t], centre[k]) / s->size;
        double fit = 1 - ur_vec3_dot(c->normals[t], s->proxy[k]) + COMPACTNESS * away * away;
        if (fit < best[k]) {
            best[k] = fit;
            s->seed[k] = t;
        }
    }
}

/*
 * Cuts the set in two regions; halves[k] gets region k's triangles.  The
 * set must be connected and have at least two triangles.
 */
static ur_status cut_in_two(charting *c, const triangle_set *set, triangle_set halves[2],
                            ur_error *error)
{
    heap h = {ur_alloc_array(3 * set->count + 2, sizeof *h.items, error), 0};
    halves[0].triangles = ur_alloc_array(set->count, sizeof *halves[0].triangles, error);
    halves[1].triangles = ur_alloc_array(set->count, sizeof *halves[1].triangles, error);
    halves[0].count = halves[1].count = 0;
    if (!h.items || !halves[0].triangles || !halves[1].triangles) {
        free(h.items);
        free(halves[0].triangles);
        free(halves[1].triangles);
        return UR_ERROR_MEMORY;
    }
    split s;
    first_seeds(c, set, &s);
    for (int round = 0; round < LLOYD_ROUNDS; round++) {
        grow(c, set, &s, &h);
        refit(c, set, &s);
    }
    grow(c, set, &s, &h);
    for (size_t i = 0; i < set->count; i++) {
        size_t t = set->triangles[i], k = c->region[t];
        halves[k].triangles[halves[k].count++] = t;
        c->region[t] = NONE;
    }
    free(h.items);
    return UR_OK;
}

/* ---- Laying out ---- */

static bool within(const ur_flat_piece *flat, const ur_strip_limits *limits)
{
    const double rounding = 1e-9;
    return flat->max_stretch <= limits->max_stretch + rounding &&
           flat->max_compression <= limits->max_compression + rounding && !flat->flipped;
}

/* The set of a disk's triangles (in the input's numbering). */
static ur_status set_of(const ur_mesh_piece *disk, triangle_set *set, ur_error *error)
{
    set->count = disk->mesh.triangle_count;
    set->triangles = ur_alloc_array(set->count, sizeof *set->triangles, error);
    if (!set->triangles)
        return UR_ERROR_MEMORY;
    memcpy(set->triangles, disk->source_triangles, set->count * sizeof *set->triangles);
    return UR_OK;
}

/* Lays a disk flat: a chart when it fits (or is one triangle), else its two halves are queued. */
static ur_status lay_out_disk(charting *c, ur_mesh_piece *disk, ur_error *error)
{
    ur_flat_piece flat;
    ur_status status = ur_flatten(&disk->mesh, c->options, &flat, error);
    if (status)
        return status;
    ur_flat_piece_fit_limits(&flat, c->limits);
    c->charts->flattened++;
    if (within(&flat, c->limits) || disk->mesh.triangle_count < 2)
        return add_chart(c, disk, &flat, error);
    ur_flat_piece_free(&flat);
    triangle_set set = {NULL, 0}, halves[2] = {{NULL, 0}, {NULL, 0}};
    status = set_of(disk, &set, error);
    if (!status)
        status = cut_in_two(c, &set, halves, error);
    free(set.triangles);
    for (int k = 0; !status && k < 2; k++) {
        status = queue_set(c, halves[k], error);
        halves[k].triangles = NULL;
    }
    if (status) {
        free(halves[0].triangles);
        free(halves[1].triangles);
    }
    return status;
}

/* Lays out every set queued, cutting those over the limits, until none is left. */
static ur_status lay_out_queue(charting *c, ur_error *error)
{
    ur_status status = UR_OK;
    while (!status && c->queued > 0) {
        triangle_set set = c->queue[--c->queued];
        ur_mesh_piece *disks = NULL;
        size_t count = 0;
        status = ur_context_check(c->options->context, error);
        if (!status)
            status = disks_of_set(c, &set, &disks, &count, error);
        for (size_t k = 0; !status && k < count; k++)
            status = lay_out_disk(c, &disks[k], error);
        ur_mesh_pieces_free(disks, count);
        free(set.triangles);
    }
    return status;
}

/* Queues the disks of the mesh cut at the seams and the sharp edges. */
static ur_status queue_first(charting *c, const ur_seam *seams, size_t seam_count, ur_error *error)
{
    ur_seam *cuts = NULL;
    size_t cut_count = 0;
    ur_mesh_piece *disks = NULL;
    size_t count = 0;
    ur_status status =
        cut_edges(c, seams, seam_count, &cuts, &cut_count, &c->charts->sharp_edges, error);
    if (!status)
        status = ur_mesh_pieces(c->mesh, cuts, cut_count, &disks, &count, error);
    /* Queued last first, so that the first disk is laid out first. */
    for (size_t k = count; !status && k-- > 0;) {
        triangle_set set;
        status = set_of(&disks[k], &set, error);
        if (!status)
            status = queue_set(c, set, error);
    }
    ur_mesh_pieces_free(disks, count);
    free(cuts);
    return status;
}

/* ---- Joining neighbours again ---- */

/* Two charts that share edges, and how long those edges are in all. */
typedef struct neighbours {
    size_t a, b; /* a < b */
    double shared;
    size_t smaller; /* triangles of the smaller chart */
} neighbours;

/* Smaller charts first (a stray triangle joins before large charts do), then longer edges. */
static int compare_neighbours(const void *x, const void *y)
{
    const neighbours *p = x, *q = y;
    if (p->smaller != q->smaller)
        return (p->smaller > q->smaller) - (p->smaller < q->smaller);
    if (p->shared != q->shared)
        return (p->shared < q->shared) - (p->shared > q->shared);
    if (p->a != q->a)
        return (p->a > q->a) - (p->a < q->a);
    return (p->b > q->b) - (p->b < q->b);
}

static int compare_pairs(const void *x, const void *y)
{
    const neighbours *p = x, *q = y;
    if (p->a != q->a)
        return (p->a > q->a) - (p->a < q->a);
    return (p->b > q->b) - (p->b < q->b);
}

static size_t chart_root(size_t *parent, size_t k)
{
    while (parent[k] != k)
        k = parent[k] = parent[parent[k]];
    return k;
}

/*
 * Every pair of charts that meet across an edge that is neither sharp nor
 * a seam, with the length of the edges they share, in the order they are
 * to be tried.
 */
static ur_status find_neighbours(const charting *c, const size_t *chart_of, neighbours **pairs,
                                 size_t *count, ur_error *error)
{
    const ur_mesh *m = c->mesh;
    const ur_charts *charts = c->charts;
    *count = 0;
    *pairs = ur_alloc_array(3 * m->triangle_count / 2 + 1, sizeof **pairs, error);
    if (!*pairs)
        return UR_ERROR_MEMORY;
    for (size_t h = 0; h < 3 * m->triangle_count; h++) {
        size_t twin = c->twins[h];
        if (twin == NONE || twin < h || c->cut[h])
            continue;
        size_t a = chart_of[h / 3], b = chart_of[twin / 3];
        if (a == b)
            continue;
        size_t from = m->triangles[h / 3][h % 3], to = m->triangles[h / 3][(h % 3 + 1) % 3];
        size_t ta = charts->charts[a].piece.mesh.triangle_count;
        size_t tb = charts->charts[b].piece.mesh.triangle_count;
        (*pairs)[(*count)++] =
            (neighbours){a < b ? a : b, a < b ? b : a,
                         ur_vec3_distance(m->vertices[from], m->vertices[to]), ta < tb ? ta : tb};
    }
    /* One entry per pair: sort by the pair, sum the shared lengths. */
    neighbours *p = *pairs;
    qsort(p, *count, sizeof *p, compare_pairs);
    size_t kept = 0;
    for (size_t i = 0; i < *count; i++) {
        if (kept > 0 && p[kept - 1].a == p[i].a && p[kept - 1].b == p[i].b)
            p[kept - 1].shared += p[i].shared;
        else
            p[kept++] = p[i];
    }
    *count = kept;
    qsort(p, *count, sizeof *p, compare_neighbours);
    return UR_OK;
}

/* The triangles of two charts as one set. */
static ur_status union_set(const ur_chart *a, const ur_chart *b, triangle_set *set, ur_error *error)
{
    size_t na = a->piece.mesh.triangle_count, nb = b->piece.mesh.triangle_count;
    set->count = na + nb;
    set->triangles = ur_alloc_array(set->count, sizeof *set->triangles, error);
    if (!set->triangles)
        return UR_ERROR_MEMORY;
    memcpy(set->triangles, a->piece.source_triangles, na * sizeof *set->triangles);
    memcpy(set->triangles + na, b->piece.source_triangles, nb * sizeof *set->triangles);
    return UR_OK;
}

static void chart_free(ur_chart *chart)
{
    ur_mesh_free(&chart->piece.mesh);
    free(chart->piece.original);
    free(chart->piece.source_triangles);
    ur_flat_piece_free(&chart->flat);
    memset(chart, 0, sizeof *chart);
}

/*
 * The set as one chart, laid flat and scaled into the limits: *fits says
 * whether it is one disk within them; when it is not, *chart is empty.
 */
static ur_status chart_of_set(charting *c, const triangle_set *set, ur_chart *chart, bool *fits,
                              ur_error *error)
{
    memset(chart, 0, sizeof *chart);
    *fits = false;
    ur_mesh_piece *disks = NULL;
    size_t count = 0;
    ur_status status = disks_of_set(c, set, &disks, &count, error);
    if (!status && count == 1) {
        status = ur_flatten(&disks[0].mesh, c->options, &chart->flat, error);
        if (!status) {
            ur_flat_piece_fit_limits(&chart->flat, c->limits);
            c->charts->flattened++;
            *fits = within(&chart->flat, c->limits);
            if (*fits) {
                chart->piece = disks[0];
                memset(&disks[0], 0, sizeof disks[0]);
            } else
                ur_flat_piece_free(&chart->flat);
        }
    }
    ur_mesh_pieces_free(disks, count);
    return status;
}

/*
 * Tries charts a and b (roots) as one: when their union is one disk that
 * lies flat within the limits, it takes a's place and b is emptied.
 */
static ur_status try_joining(charting *c, size_t a, size_t b, bool *joined, ur_error *error)
{
    ur_chart *charts = c->charts->charts, joint;
    triangle_set set;
    *joined = false;
    ur_status status = union_set(&charts[a], &charts[b], &set, error);
    if (!status)
        status = chart_of_set(c, &set, &joint, joined, error);
    free(set.triangles);
    if (!status && *joined) {
        chart_free(&charts[a]);
        chart_free(&charts[b]);
        charts[a] = joint;
    }
    return status;
}

/* Drops the charts emptied by joining, keeping the others' order. */
static void drop_empty(ur_charts *charts)
{
    size_t kept = 0;
    for (size_t k = 0; k < charts->count; k++)
        if (charts->charts[k].piece.mesh.triangle_count > 0)
            charts->charts[kept++] = charts->charts[k];
    charts->count = kept;
}

/* Joins neighbouring charts where the two lie flat within the limits together. */
static ur_status join_neighbours(charting *c, ur_error *error)
{
    const ur_mesh *m = c->mesh;
    ur_charts *charts = c->charts;
    size_t *chart_of = ur_alloc_array(m->triangle_count, sizeof *chart_of, error);
    size_t *parent = ur_alloc_array(charts->count, sizeof *parent, error);
    neighbours *pairs = NULL;
    size_t pair_count = 0;
    ur_status status = chart_of && parent ? UR_OK : UR_ERROR_MEMORY;
    for (size_t k = 0; !status && k < charts->count; k++) {
        parent[k] = k;
        for (size_t t = 0; t < charts->charts[k].piece.mesh.triangle_count; t++)
            chart_of[charts->charts[k].piece.source_triangles[t]] = k;
    }
    if (!status)
        status = find_neighbours(c, chart_of, &pairs, &pair_count, error);
    for (size_t i = 0; !status && i < pair_count; i++) {
        size_t a = chart_root(parent, pairs[i].a), b = chart_root(parent, pairs[i].b);
        bool joined = false;
        if (a == b)
            continue;
        status = ur_context_check(c->options->context, error);
        if (!status)
            status = try_joining(c, a < b ? a : b, a < b ? b : a, &joined, error);
        if (joined)
            parent[a < b ? b : a] = a < b ? a : b;
    }
    if (!status)
        drop_empty(charts);
    free(pairs);
    free(parent);
    free(chart_of);
    return status;
}

/* ---- Smoothing the charts' borders ---- */

/* A triangle that juts from chart from into chart to (two of its edges on it). */
typedef struct jut {
    size_t from, to, triangle;
} jut;

static int compare_juts(const void *x, const void *y)
{
    const jut *p = x, *q = y;
    if (p->from != q->from)
        return (p->from > q->from) - (p->from < q->from);
    if (p->to != q->to)
        return (p->to > q->to) - (p->to < q->to);
    return (p->triangle > q->triangle) - (p->triangle < q->triangle);
}

/* The chart of each triangle. */
static void number_charts(const ur_charts *charts, size_t *chart_of)
{
    for (size_t k = 0; k < charts->count; k++)
        for (size_t t = 0; t < charts->charts[k].piece.mesh.triangle_count; t++)
            chart_of[charts->charts[k].piece.source_triangles[t]] = k;
}

/*
 * Every triangle that meets one other chart along two of its edges
 * (neither sharp nor a seam): the teeth a border grown triangle by
 * triangle leaves.  Sorted by the pair of charts.
 */
static size_t find_juts(const charting *c, const size_t *chart_of, jut *juts)
{
    size_t count = 0;
    for (size_t t = 0; t < c->mesh->triangle_count; t++) {
        size_t other[3], found = 0;
        for (int e = 0; e < 3; e++) {
            size_t twin = c->twins[3 * t + e];
            if (twin != NONE && !c->cut[3 * t + e] && chart_of[twin / 3] != chart_of[t])
                other[found++] = chart_of[twin / 3];
        }
        size_t to = found >= 2 && other[0] == other[1]   ? other[0]
                    : found == 3 && other[2] == other[0] ? other[0]
                    : found == 3 && other[2] == other[1] ? other[1]
                                                         : NONE;
        if (to != NONE)
            juts[count++] = (jut){chart_of[t], to, t};
    }
    qsort(juts, count, sizeof *juts, compare_juts);
    return count;
}

/* Chart k's triangles without (or with) the juts given. */
static ur_status moved_set(const ur_chart *chart, const jut *juts, size_t count, bool add,
                           const size_t *chart_of, size_t k, triangle_set *set, ur_error *error)
{
    size_t n = chart->piece.mesh.triangle_count;
    set->triangles = ur_alloc_array(n + count, sizeof *set->triangles, error);
    set->count = 0;
    if (!set->triangles)
        return UR_ERROR_MEMORY;
    for (size_t t = 0; t < n; t++)
        if (add || chart_of[chart->piece.source_triangles[t]] == k)
            set->triangles[set->count++] = chart->piece.source_triangles[t];
    for (size_t i = 0; add && i < count; i++)
        set->triangles[set->count++] = juts[i].triangle;
    return UR_OK;
}

/*
 * Moves the juts from chart from to chart to when both stay one disk
 * within the limits; chart_of follows.
 */
static ur_status move_juts(charting *c, const jut *juts, size_t count, size_t *chart_of,
                           size_t *moved, ur_error *error)
{
    ur_chart *charts = c->charts->charts, next[2];
    memset(next, 0, sizeof next);
    size_t from = juts[0].from, to = juts[0].to;
    if (count >= charts[from].piece.mesh.triangle_count)
        return UR_OK; /* all of it: joining's business */
    for (size_t i = 0; i < count; i++)
        chart_of[juts[i].triangle] = to; /* as if moved, for moved_set */
    triangle_set sets[2] = {{NULL, 0}, {NULL, 0}};
    bool fits[2] = {false, false};
    ur_status status =
        moved_set(&charts[from], juts, count, false, chart_of, from, &sets[0], error);
    if (!status)
        status = moved_set(&charts[to], juts, count, true, chart_of, to, &sets[1], error);
    for (int k = 0; !status && k < 2 && (k == 0 || fits[0]); k++)
        status = chart_of_set(c, &sets[k], &next[k], &fits[k], error);
    bool done = !status && fits[0] && fits[1];
    for (int k = 0; k < 2; k++) {
        free(sets[k].triangles);
        size_t chart = k == 0 ? from : to;
        if (done) {
            chart_free(&charts[chart]);
            charts[chart] = next[k];
        } else
            chart_free(&next[k]);
    }
    for (size_t i = 0; !done && i < count; i++)
        chart_of[juts[i].triangle] = from;
    *moved += done ? count : 0;
    return status;
}

/*
 * Moves the triangles that jut from one chart into another over to it,
 * pair of charts by pair, where both stay within the limits; a few rounds,
 * since filling one tooth can leave the next jutting.
 */
static ur_status smooth_borders(charting *c, ur_error *error)
{
    const ur_mesh *m = c->mesh;
    size_t *chart_of = ur_alloc_array(m->triangle_count, sizeof *chart_of, error);
    jut *juts = ur_alloc_array(m->triangle_count, sizeof *juts, error);
    ur_status status = chart_of && juts ? UR_OK : UR_ERROR_MEMORY;
    size_t moved = 1;
    for (int round = 0; !status && moved > 0 && round < SMOOTHING_ROUNDS; round++) {
        moved = 0;
        number_charts(c->charts, chart_of);
        size_t count = find_juts(c, chart_of, juts);
        for (size_t i = 0, j; !status && i < count; i = j) {
            for (j = i + 1; j < count && juts[j].from == juts[i].from && juts[j].to == juts[i].to;)
                j++;
            status = ur_context_check(c->options->context, error);
            if (!status)
                status = move_juts(c, juts + i, j - i, chart_of, &moved, error);
        }
    }
    free(juts);
    free(chart_of);
    return status;
}

static int by_first_triangle(const void *a, const void *b)
{
    const ur_chart *x = a, *y = b;
    size_t first_x = x->piece.source_triangles[0], first_y = y->piece.source_triangles[0];
    for (size_t t = 1; t < x->piece.mesh.triangle_count; t++)
        first_x = first_x < x->piece.source_triangles[t] ? first_x : x->piece.source_triangles[t];
    for (size_t t = 1; t < y->piece.mesh.triangle_count; t++)
        first_y = first_y < y->piece.source_triangles[t] ? first_y : y->piece.source_triangles[t];
    return (first_x > first_y) - (first_x < first_y);
}

static void sum_up(ur_charts *charts)
{
    qsort(charts->charts, charts->count, sizeof *charts->charts, by_first_triangle);
    for (size_t k = 0; k < charts->count; k++) {
        charts->max_stretch = fmax(charts->max_stretch, charts->charts[k].flat.max_stretch);
        charts->max_compression =
            fmax(charts->max_compression, charts->charts[k].flat.max_compression);
    }
}

static void charting_free(charting *c)
{
    for (size_t k = 0; k < c->queued; k++)
        free(c->queue[k].triangles);
    free(c->queue);
    free(c->twins);
    free(c->cut);
    free(c->normals);
    free(c->centres);
    free(c->areas);
    free(c->region);
    free(c->vertex_map);
}

static ur_status check_limits(const ur_strip_limits *limits, ur_error *error)
{
    if (!(limits->max_stretch >= 0) || !(limits->max_compression >= 0) ||
        !isfinite(limits->max_stretch) || !isfinite(limits->max_compression))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the strain limits must be numbers >= 0, not %g and %g",
                            limits->max_stretch, limits->max_compression);
    return UR_OK;
}

ur_status ur_flatten_charts(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                            const ur_strip_limits *limits, const ur_flatten_options *options,
                            ur_charts *charts, ur_error *error)
{
    memset(charts, 0, sizeof *charts);
    ur_flatten_options defaults;
    ur_flatten_options_default(&defaults);
    if (!options)
        options = &defaults;
    ur_status status = check_limits(limits, error);
    if (status)
        return status;
    if (!mesh->triangle_count)
        return ur_error_set(error, UR_ERROR_INPUT, "the mesh has no triangles");
    charting c = {.mesh = mesh, .limits = limits, .options = options, .charts = charts};
    status = measure_triangles(&c, error);
    if (!status)
        status = queue_first(&c, seams, seam_count, error);
    if (!status)
        status = lay_out_queue(&c, error);
    if (!status)
        status = join_neighbours(&c, error);
    if (!status)
        status = smooth_borders(&c, error);
    charting_free(&c);
    if (status)
        ur_charts_free(charts);
    else
        sum_up(charts);
    return status;
}

void ur_charts_free(ur_charts *charts)
{
    if (!charts)
        return;
    for (size_t k = 0; k < charts->count; k++) {
        ur_mesh_free(&charts->charts[k].piece.mesh);
        free(charts->charts[k].piece.original);
        free(charts->charts[k].piece.source_triangles);
        ur_flat_piece_free(&charts->charts[k].flat);
    }
    free(charts->charts);
    memset(charts, 0, sizeof *charts);
}
