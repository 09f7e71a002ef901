/*
 * seams.c: which runs of a net's outline were cut from which others, so
 * that joints and matching labels can be put on both sides of every seam.
 *
 * Mesh nets carry the 3D point of each outline point.  An edge of one
 * outline from P to Q and an edge from Q to P (of another outline, or of
 * the same one) are the two sides of one cut edge: every edge is sorted by
 * its end points, and equal neighbours in that order are partners (but
 * two sides of one net lying on each other: a closed slit, no seam).  Runs
 * of partnered edges that follow each other on both sides are one seam.
 * Developments set their seam sides themselves (develop.c): their seams
 * are cut rulings.
 */
#include "unroll/develop.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* One outline edge, from its net's point index to the next. */
typedef struct edge_entry {
    ur_vec3 low, high; /* its end points, smaller first */
    size_t net, index;
    bool forward; /* whether the edge runs from low to high */
} edge_entry;

/* Where an edge's partner is: net and edge index, or SIZE_MAX for none. */
typedef struct partner {
    size_t net, index;
} partner;

static int compare_entries(const void *a, const void *b)
{
    const edge_entry *x = a, *y = b;
    int order = ur_vec3_order(x->low, y->low);
    if (order == 0)
        order = ur_vec3_order(x->high, y->high);
    if (order == 0) /* keep the sort deterministic */
        order = x->net != y->net ? (x->net < y->net ? -1 : 1)
                                 : (x->index < y->index ? -1 : x->index > y->index);
    return order;
}

static size_t count_edges(const ur_net_list *nets)
{
    size_t count = 0;
    for (size_t n = 0; n < nets->count; n++)
        if (nets->nets[n].outline_3d)
            count += nets->nets[n].outline_count;
    return count;
}

/* Every edge of every net with 3D points, zero-length ones left out. */
static size_t collect_edges(const ur_net_list *nets, edge_entry *entries)
{
    size_t count = 0;
    for (size_t n = 0; n < nets->count; n++) {
        const ur_net *net = &nets->nets[n];
        if (!net->outline_3d)
            continue;
        for (size_t i = 0; i < net->outline_count; i++) {
            ur_vec3 from = net->outline_3d[i], to = net->outline_3d[(i + 1) % net->outline_count];
            int order = ur_vec3_order(from, to);
            if (order == 0)
                continue;
            edge_entry *e = &entries[count++];
            e->low = order < 0 ? from : to;
            e->high = order < 0 ? to : from;
            e->forward = order < 0;
            e->net = n;
            e->index = i;
        }
    }
    return count;
}

/* The diagonal of a net's outline's box: its size, for tolerances. */
static double net_size(const ur_net *net)
{
    ur_box box = ur_box_empty();
    for (size_t i = 0; i < net->outline_count; i++)
        ur_box_add(&box, net->outline[i]);
    return hypot(ur_box_width(box), ur_box_height(box));
}

/*
 * Whether two partnered edges of one net lie on each other laid flat, the
 * start of each at the end of the other: the slit that opens a flat face
 * round a hole into a disk (a frame round its window).  The material is
 * whole there, both sides in place: no seam, nothing to join or label.
 * Laid flat two ways round the hole, the ends may differ in their last
 * digits.
 */
static bool lies_closed(const ur_net_list *nets, const double *sizes, const edge_entry *a,
                        const edge_entry *b)
{
    if (a->net != b->net)
        return false;
    const ur_net *net = &nets->nets[a->net];
    size_t n = net->outline_count;
    double tolerance = 1e-9 * sizes[a->net];
    return ur_vec2_distance(net->outline[a->index], net->outline[(b->index + 1) % n]) <=
               tolerance &&
           ur_vec2_distance(net->outline[(a->index + 1) % n], net->outline[b->index]) <= tolerance;
}

/*
 * Pairs equal edges of opposite direction, but for the sides of a slit
 * lying closed (sizes: each net's, from net_size).  Three or more sides on
 * one edge (a non-manifold cut) pair the first two and leave the rest
 * unpaired.
 */
static void pair_edges(const ur_net_list *nets, const double *sizes, edge_entry *entries,
                       size_t count, partner **partners)
{
    qsort(entries, count, sizeof *entries, compare_entries);
    for (size_t k = 0; k + 1 < count; k++) {
        edge_entry *a = &entries[k], *b = &entries[k + 1];
        if (ur_vec3_order(a->low, b->low) != 0 || ur_vec3_order(a->high, b->high) != 0 ||
            a->forward == b->forward)
            continue;
        if (lies_closed(nets, sizes, a, b)) {
            k++;
            continue;
        }
        partners[a->net][a->index] = (partner){b->net, b->index};
        partners[b->net][b->index] = (partner){a->net, a->index};
        k++;
    }
}

static bool has_partner(const partner *p)
{
    return p->net != SIZE_MAX;
}

/*
 * Whether edge i of net n continues the run of edge i - 1: both have
 * partners, in the same net, the second's just before the first's (the
 * sides run in opposite directions), and the two are not each other's
 * partners (the tip of a slit, where the cut turns back).
 */
static bool continues(const ur_net_list *nets, partner *const *partners, size_t n, size_t i)
{
    size_t count = nets->nets[n].outline_count;
    size_t previous = (i + count - 1) % count;
    const partner *a = &partners[n][previous], *b = &partners[n][i];
    if (!has_partner(a) || !has_partner(b) || a->net != b->net)
        return false;
    if (a->net == n && a->index == i)
        return false;
    size_t partner_count = nets->nets[a->net].outline_count;
    return (b->index + 1) % partner_count == a->index;
}

static ur_status add_side(ur_net *net, size_t first, size_t edges, int seam, ur_error *error)
{
    ur_seam_side *sides = realloc(net->seam_sides, (net->seam_side_count + 1) * sizeof *sides);
    if (!sides)
        return ur_error_out_of_memory(error);
    net->seam_sides = sides;
    sides[net->seam_side_count++] = (ur_seam_side){first, edges + 1, seam};
    return UR_OK;
}

/*
 * The runs of net n, each numbered on its first edge: run_seam[n][i] is the
 * seam number of edge i's run (0 where the edge has no partner).  A run
 * whose partner run was numbered already takes its number.
 */
static ur_status number_runs(ur_net_list *nets, partner *const *partners, int **run_seam, size_t n,
                             int *next_seam, ur_error *error)
{
    ur_net *net = &nets->nets[n];
    size_t count = net->outline_count, start = 0;
    while (start < count && continues(nets, partners, n, start))
        start++;
    if (start == count)
        start = 0; /* one run all round: begin anywhere */
    for (size_t step = 0; step < count;) {
        size_t i = (start + step) % count;
        if (!has_partner(&partners[n][i])) {
            step++;
            continue;
        }
        size_t edges = 1;
        while (step + edges < count && continues(nets, partners, n, (i + edges) % count))
            edges++;
        /* The partner run is numbered already when it was met first. */
        const partner *last = &partners[n][(i + edges - 1) % count];
        int seam = run_seam[last->net][last->index];
        if (seam == 0)
            seam = (*next_seam)++;
        for (size_t k = 0; k < edges; k++)
            run_seam[n][(i + k) % count] = seam;
        ur_status status = add_side(net, i, edges, seam, error);
        if (status != UR_OK)
            return status;
        step += edges;
    }
    return UR_OK;
}

static void free_tables(partner **partners, int **run_seam, size_t count)
{
    for (size_t n = 0; n < count; n++) {
        if (partners)
            free(partners[n]);
        if (run_seam)
            free(run_seam[n]);
    }
    free(partners);
    free(run_seam);
}

static ur_status make_tables(const ur_net_list *nets, partner ***partners, int ***run_seam,
                             ur_error *error)
{
    *partners = calloc(nets->count ? nets->count : 1, sizeof **partners);
    *run_seam = calloc(nets->count ? nets->count : 1, sizeof **run_seam);
    if (!*partners || !*run_seam)
        return ur_error_out_of_memory(error);
    for (size_t n = 0; n < nets->count; n++) {
        size_t count = nets->nets[n].outline_3d ? nets->nets[n].outline_count : 0;
        (*partners)[n] = malloc((count ? count : 1) * sizeof ***partners);
        (*run_seam)[n] = calloc(count ? count : 1, sizeof ***run_seam);
        if (!(*partners)[n] || !(*run_seam)[n])
            return ur_error_out_of_memory(error);
        for (size_t i = 0; i < count; i++)
            (*partners)[n][i] = (partner){SIZE_MAX, SIZE_MAX};
    }
    return UR_OK;
}

ur_status ur_net_list_find_seams(ur_net_list *nets, int first_seam, int *next_seam, ur_error *error)
{
    *next_seam = first_seam;
    partner **partners = NULL;
    int **run_seam = NULL;
    size_t edge_count = count_edges(nets);
    edge_entry *entries = ur_alloc_array(edge_count ? edge_count : 1, sizeof *entries, error);
    double *sizes = ur_alloc_array(nets->count, sizeof *sizes, error);
    ur_status status =
        entries && sizes ? make_tables(nets, &partners, &run_seam, error) : UR_ERROR_MEMORY;
    for (size_t n = 0; status == UR_OK && n < nets->count; n++)
        sizes[n] = net_size(&nets->nets[n]);
    if (status == UR_OK) {
        pair_edges(nets, sizes, entries, collect_edges(nets, entries), partners);
        for (size_t n = 0; n < nets->count; n++) {
            ur_net *net = &nets->nets[n];
            if (!net->outline_3d)
                continue;
            free(net->seam_sides);
            net->seam_sides = NULL;
            net->seam_side_count = 0;
        }
        for (size_t n = 0; status == UR_OK && n < nets->count; n++)
            if (nets->nets[n].outline_3d)
                status = number_runs(nets, partners, run_seam, n, next_seam, error);
    }
    free(entries);
    free(sizes);
    free_tables(partners, run_seam, nets->count);
    return status;
}

int ur_net_list_last_seam(const ur_net_list *nets)
{
    int last = 0;
    for (size_t n = 0; n < nets->count; n++)
        for (size_t k = 0; k < nets->nets[n].seam_side_count; k++)
            if (nets->nets[n].seam_sides[k].seam > last)
                last = nets->nets[n].seam_sides[k].seam;
    return last;
}
