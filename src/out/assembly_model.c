/*
 * assembly_model.c: the model the assembly guide draws (assembly.h): the
 * faces of every net in 3D with their normals; each face's edges told
 * apart as cuts (on its piece's outline: to another piece, or a slit
 * within the same one), folds (inside the piece, where the faces turn) or
 * flat; whether the mesh is closed (its faces turned away are then never
 * seen); each seam's place, the middle of its run; and a colour a piece.
 *
 * The pieces share the mesh's vertices exactly, so edges are matched by
 * their end points: every point is numbered by sorting, and the edges of
 * the faces and of the outlines sorted by their two numbers, so that the
 * faces on an edge and the outline along it come together.
 *
 * Colours: evenly spaced hues, one per piece, given out so that pieces
 * that meet at a seam get hues far apart (choose_slots).
 */
#include "assembly.h"
#include "../geom/points.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A fold is a fold where its faces turn by more than this (radians): 2 degrees. */
static const double FOLD_MIN_ANGLE = 0.035;

void assembly_model_free(model *m)
{
    free(m->faces);
    free(m->outlined);
    free(m->names);
    free(m->colours);
    free(m->seams);
    memset(m, 0, sizeof *m);
}

static void hsv_to_rgb(double hue, double saturation, double value, double rgb[3])
{
    double h = fmod(hue, 1.0) * 6.0, c = value * saturation;
    double x = c * (1 - fabs(fmod(h, 2.0) - 1)), m = value - c;
    int sector = (int)h % 6;
    static const int pick[6][3] = {{0, 1, 2}, {1, 0, 2}, {2, 0, 1},
                                   {2, 1, 0}, {1, 2, 0}, {0, 2, 1}};
    double parts[3] = {c, x, 0};
    for (int k = 0; k < 3; k++)
        rgb[k] = parts[pick[sector][k]] + m;
}

static size_t greatest_divisor(size_t a, size_t b)
{
    while (b) {
        size_t r = a % b;
        a = b;
        b = r;
    }
    return a;
}

/* Two pieces that share a seam. */
typedef struct piece_pair {
    size_t a, b;
} piece_pair;

typedef struct pair_list {
    piece_pair *items;
    size_t count, capacity;
} pair_list;

static bool add_pair(pair_list *pairs, size_t a, size_t b)
{
    if (pairs->count == pairs->capacity) {
        size_t capacity = pairs->capacity ? 2 * pairs->capacity : 64;
        piece_pair *grown = realloc(pairs->items, capacity * sizeof *grown);
        if (!grown)
            return false;
        pairs->items = grown;
        pairs->capacity = capacity;
    }
    pairs->items[pairs->count++] = (piece_pair){a < b ? a : b, a < b ? b : a};
    return true;
}

static int compare_pairs(const void *x, const void *y)
{
    const piece_pair *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

/* Each piece's neighbours: those of piece k are list[start[k] .. start[k + 1]). */
typedef struct neighbours {
    size_t *start, *list;
} neighbours;

static ur_status find_neighbours(pair_list *pairs, size_t n, neighbours *out, ur_error *error)
{
    if (pairs->count > 1) /* none at all for one piece: no array to sort */
        qsort(pairs->items, pairs->count, sizeof *pairs->items, compare_pairs);
    size_t unique = 0;
    for (size_t i = 0; i < pairs->count; i++)
        if (unique == 0 || compare_pairs(&pairs->items[unique - 1], &pairs->items[i]) != 0)
            pairs->items[unique++] = pairs->items[i];
    pairs->count = unique;
    out->start = calloc(n + 1, sizeof *out->start);
    out->list = ur_alloc_array(2 * unique + 1, sizeof *out->list, error);
    if (!out->start || !out->list)
        return ur_error_out_of_memory(error);
    for (size_t i = 0; i < unique; i++) {
        out->start[pairs->items[i].a + 1]++;
        out->start[pairs->items[i].b + 1]++;
    }
    for (size_t k = 0; k < n; k++)
        out->start[k + 1] += out->start[k];
    for (size_t i = 0; i < unique; i++) { /* fills each piece's run from its start on */
        out->list[out->start[pairs->items[i].a]++] = pairs->items[i].b;
        out->list[out->start[pairs->items[i].b]++] = pairs->items[i].a;
    }
    for (size_t k = n; k > 0; k--) /* which moved each start to the next piece's */
        out->start[k] = out->start[k - 1];
    out->start[0] = 0;
    return UR_OK;
}

typedef struct degree_key {
    size_t degree, piece;
} degree_key;

static int compare_degrees(const void *x, const void *y)
{
    const degree_key *p = x, *q = y;
    if (p->degree != q->degree)
        return p->degree > q->degree ? -1 : 1;
    return (p->piece > q->piece) - (p->piece < q->piece);
}

/* More pieces than this get their hues in golden steps alone (the choice is quadratic). */
enum { MOST_CHOSEN_HUES = 4096 };

/* How far apart hue slots i and j of n are round the circle. */
static size_t slots_apart(size_t i, size_t j, size_t n)
{
    size_t apart = i > j ? i - j : j - i;
    return apart < n - apart ? apart : n - apart;
}

/*
 * Which of the n hues each piece gets (slot[k]): every hue once.  In golden
 * steps (j = k s mod n, s the whole number nearest n / phi^2 prime to n),
 * pieces numbered one after another come far apart on the circle; better,
 * the most connected pieces first, each takes the hue left that is
 * farthest from its neighbours' (the pieces it shares a seam with), so
 * that pieces that meet differ most.
 */
static void choose_slots(size_t n, const neighbours *near, size_t *slot)
{
    size_t step = 1;
    if (n > 2) {
        step = (size_t)fmax(1, round((double)n * 0.381966));
        while (greatest_divisor(n, step) != 1)
            step++;
    }
    degree_key *order = calloc(n ? n : 1, sizeof *order);
    bool *used = calloc(n ? n : 1, sizeof *used);
    if (!order || !used || n > MOST_CHOSEN_HUES) {
        for (size_t k = 0; k < n; k++)
            slot[k] = (k * step) % n;
        free(order);
        free(used);
        return;
    }
    for (size_t k = 0; k < n; k++) {
        order[k] = (degree_key){near->start[k + 1] - near->start[k], k};
        slot[k] = NO_FACE;
    }
    qsort(order, n, sizeof *order, compare_degrees);
    for (size_t i = 0; i < n; i++) {
        size_t piece = order[i].piece, best = NO_FACE, best_gap = 0;
        for (size_t t = 0; t < n; t++) {
            size_t j = (t * step) % n, gap = n;
            if (used[j])
                continue;
            for (size_t e = near->start[piece]; e < near->start[piece + 1]; e++)
                if (slot[near->list[e]] != NO_FACE) {
                    size_t apart = slots_apart(j, slot[near->list[e]], n);
                    gap = apart < gap ? apart : gap;
                }
            if (best == NO_FACE || gap > best_gap) {
                best = j;
                best_gap = gap;
            }
            if (gap == n)
                break; /* no neighbour has a hue yet: the next in golden steps */
        }
        slot[piece] = best;
        used[best] = true;
    }
    free(order);
    free(used);
}

/* Hue slot j of n; its saturation alternates, so that hues next to each other differ more. */
static void slot_colour(size_t j, size_t n, double rgb[3])
{
    hsv_to_rgb(0.58 + (double)j / (double)n, j % 2 ? 0.62 : 0.5, 0.97, rgb);
}

static ur_status choose_colours(model *m, pair_list *pairs, ur_error *error)
{
    size_t n = m->piece_count;
    neighbours near = {NULL, NULL};
    size_t *slot = ur_alloc_array(n ? n : 1, sizeof *slot, error);
    ur_status status = slot ? find_neighbours(pairs, n, &near, error) : UR_ERROR_MEMORY;
    if (status == UR_OK) {
        choose_slots(n, &near, slot);
        for (size_t k = 0; k < n; k++)
            slot_colour(slot[k], n, m->colours[k]);
    }
    free(near.start);
    free(near.list);
    free(slot);
    return status;
}

/* An edge of a face, or of a piece's outline (face NO_FACE). */
typedef struct edge_ref {
    size_t low, high; /* the point numbers of its ends */
    size_t face;
    size_t piece;
    int side; /* a face's edge from corner side to side + 1 */
} edge_ref;

static int compare_edges(const void *a, const void *b)
{
    const edge_ref *p = a, *q = b;
    if (p->low != q->low)
        return p->low < q->low ? -1 : 1;
    if (p->high != q->high)
        return p->high < q->high ? -1 : 1;
    return (p->face > q->face) - (p->face < q->face);
}

/*
 * Every face corner, then every outline point of the nets that have
 * faces, numbered alike where they are the same point (the pieces share
 * the mesh's vertices exactly).
 */
static ur_status number_points(const model *m, const ur_net_list *nets, size_t count,
                               size_t *numbers, ur_error *error)
{
    ur_vec3 *points = ur_alloc_array(count, sizeof *points, error);
    if (!points)
        return UR_ERROR_MEMORY;
    size_t n = 0;
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++)
            points[n++] = m->faces[f].corner[k];
    for (size_t k = 0; k < nets->count; k++)
        for (size_t i = 0; m->outlined[k] && i < nets->nets[k].outline_count; i++)
            points[n++] = nets->nets[k].outline_3d[i];
    ur_status status = geom_number_points(points, count, numbers, error);
    free(points);
    return status;
}

static edge_ref edge_between(size_t a, size_t b, size_t face_index, size_t piece, int side)
{
    return (edge_ref){a < b ? a : b, a < b ? b : a, face_index, piece, side};
}

/* The edges of the faces, then those of the outlines, in the order number_points numbered them. */
static void list_edges(const model *m, const ur_net_list *nets, const size_t *numbers,
                       edge_ref *edges)
{
    size_t n = 0;
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++, n++)
            edges[n] = edge_between(numbers[3 * f + (size_t)k],
                                    numbers[3 * f + (size_t)(k + 1) % 3], f, m->faces[f].piece, k);
    for (size_t k = 0; k < nets->count; k++) {
        size_t count = m->outlined[k] ? nets->nets[k].outline_count : 0;
        for (size_t i = 0; i < count; i++, n++)
            edges[n] = edge_between(numbers[n], numbers[n - i + (i + 1) % count], NO_FACE, k, -1);
    }
}

/*
 * Marks the faces' edges of one run of edges that are the same edge: on
 * its piece's outline (a cut, to another piece or within the same one),
 * or a fold inside the piece.  A piece without an outline in 3D is cut
 * wherever its neighbour is another piece's.
 */
static bool classify_run(model *m, const edge_ref *run, size_t count, pair_list *pairs)
{
    size_t faces = 0;
    for (size_t i = 0; i < count; i++)
        faces += run[i].face != NO_FACE;
    if (faces == 1)
        m->closed = false;
    for (size_t i = 0; i < count; i++)
        for (size_t j = i + 1; j < count; j++)
            if (run[i].face != NO_FACE && run[j].face != NO_FACE && run[i].piece != run[j].piece &&
                !add_pair(pairs, run[i].piece, run[j].piece))
                return false;
    for (size_t i = 0; i < count; i++) {
        if (run[i].face == NO_FACE)
            continue;
        face *f = &m->faces[run[i].face];
        const face *partner = NULL;
        bool on_outline = false;
        for (size_t j = 0; j < count; j++) {
            if (j == i || run[j].piece != f->piece)
                continue;
            if (run[j].face == NO_FACE)
                on_outline = true;
            else if (!partner)
                partner = &m->faces[run[j].face];
        }
        unsigned char bit = (unsigned char)(1u << run[i].side);
        if (m->outlined[f->piece] ? on_outline : !partner)
            f->border |= bit;
        else if (partner &&
                 acos(fmax(-1, fmin(1, ur_vec3_dot(f->normal, partner->normal)))) > FOLD_MIN_ANGLE)
            f->fold |= bit;
    }
    return true;
}

/* Marks every face's edges; the pairs of pieces that meet go into pairs. */
static ur_status classify_edges(model *m, const ur_net_list *nets, pair_list *pairs,
                                ur_error *error)
{
    size_t count = 3 * m->face_count;
    for (size_t k = 0; k < nets->count; k++)
        count += m->outlined[k] ? nets->nets[k].outline_count : 0;
    size_t *numbers = ur_alloc_array(count, sizeof *numbers, error);
    edge_ref *edges = ur_alloc_array(count, sizeof *edges, error);
    ur_status status =
        numbers && edges ? number_points(m, nets, count, numbers, error) : UR_ERROR_MEMORY;
    if (status == UR_OK) {
        list_edges(m, nets, numbers, edges);
        qsort(edges, count, sizeof *edges, compare_edges);
        m->closed = true;
        for (size_t i = 0, j; i < count && status == UR_OK; i = j) {
            for (j = i + 1;
                 j < count && edges[j].low == edges[i].low && edges[j].high == edges[i].high; j++)
                ;
            if (!classify_run(m, &edges[i], j - i, pairs))
                status = ur_error_out_of_memory(error);
        }
    }
    free(numbers);
    free(edges);
    return status;
}

static ur_status add_faces(model *m, const ur_net *net, size_t piece, ur_error *error)
{
    for (size_t t = 0; t < net->face_count; t++) {
        const ur_vec3 *c = net->faces_3d[t];
        for (int k = 0; k < 3; k++)
            if (!isfinite(c[k].x) || !isfinite(c[k].y) || !isfinite(c[k].z))
                return ur_error_set(error, UR_ERROR_INPUT,
                                    "piece %s: face %zu has a corner that is not finite",
                                    m->names[piece], t + 1);
        ur_vec3 normal = ur_vec3_cross(ur_vec3_sub(c[1], c[0]), ur_vec3_sub(c[2], c[0]));
        double length = ur_vec3_length(normal);
        if (!(length > 0))
            continue; /* no area: nothing to draw */
        face *f = &m->faces[m->face_count++];
        memset(f, 0, sizeof *f);
        memcpy(f->corner, c, sizeof f->corner);
        f->normal = ur_vec3_scale(normal, 1 / length);
        f->piece = piece;
    }
    return UR_OK;
}

static ur_vec3 outline_point(const ur_net *net, size_t first, size_t i)
{
    return net->outline_3d[(first + i) % net->outline_count];
}

/* The middle of a seam side's run by length, in 3D. */
static ur_vec3 run_middle(const ur_net *net, const ur_seam_side *side)
{
    double length = 0;
    for (size_t i = 0; i + 1 < side->count; i++)
        length += ur_vec3_distance(outline_point(net, side->first, i),
                                   outline_point(net, side->first, i + 1));
    double walked = 0;
    for (size_t i = 0; i + 1 < side->count; i++) {
        ur_vec3 a = outline_point(net, side->first, i), b = outline_point(net, side->first, i + 1);
        double step = ur_vec3_distance(a, b);
        if (walked + step >= length / 2 && step > 0)
            return ur_vec3_add_scaled(a, ur_vec3_sub(b, a), (length / 2 - walked) / step);
        walked += step;
    }
    return outline_point(net, side->first, 0);
}

static int compare_seam_marks(const void *a, const void *b)
{
    const seam_mark *p = a, *q = b;
    return (p->seam > q->seam) - (p->seam < q->seam);
}

/*
 * The seams, each once (in order of number), at the middle of its run:
 * both sides of a seam run over the same edges, so either will do.
 */
static ur_status find_seam_marks(model *m, const ur_net_list *nets, ur_error *error)
{
    size_t sides = 0;
    for (size_t k = 0; k < nets->count; k++)
        sides += nets->nets[k].outline_3d ? nets->nets[k].seam_side_count : 0;
    m->seams = ur_alloc_array(sides ? sides : 1, sizeof *m->seams, error);
    if (!m->seams)
        return UR_ERROR_MEMORY;
    size_t count = 0;
    for (size_t k = 0; k < nets->count; k++) {
        const ur_net *net = &nets->nets[k];
        for (size_t s = 0; net->outline_3d && net->outline_count && s < net->seam_side_count; s++)
            if (net->seam_sides[s].count >= 2)
                m->seams[count++] =
                    (seam_mark){net->seam_sides[s].seam, run_middle(net, &net->seam_sides[s])};
    }
    /* stable enough: a seam's two marks are the same point */
    qsort(m->seams, count, sizeof *m->seams, compare_seam_marks);
    for (size_t i = 0; i < count; i++)
        if (m->seam_count == 0 || m->seams[m->seam_count - 1].seam != m->seams[i].seam)
            m->seams[m->seam_count++] = m->seams[i];
    return UR_OK;
}

static void measure_model(model *m)
{
    ur_vec3 low = m->faces[0].corner[0], high = low;
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++) {
            ur_vec3 p = m->faces[f].corner[k];
            low = ur_vec3_make(fmin(low.x, p.x), fmin(low.y, p.y), fmin(low.z, p.z));
            high = ur_vec3_make(fmax(high.x, p.x), fmax(high.y, p.y), fmax(high.z, p.z));
        }
    m->centre = ur_vec3_scale(ur_vec3_add(low, high), 0.5);
    m->size = ur_vec3_distance(low, high);
}

ur_status assembly_model_build(const ur_net_list *nets, const ur_assembly_options *options,
                               model *m, ur_error *error)
{
    memset(m, 0, sizeof *m);
    size_t faces = 0;
    for (size_t k = 0; k < nets->count; k++) {
        if (nets->nets[k].face_count > 0 && !nets->nets[k].faces_3d)
            return ur_error_set(error, UR_ERROR_INTERNAL, "net %s has %zu faces but no array",
                                nets->nets[k].name, nets->nets[k].face_count);
        faces += nets->nets[k].face_count;
        m->pieces_drawn += nets->nets[k].face_count > 0;
    }
    if (faces == 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the assembly guide draws meshes, and these pieces have no 3D faces "
                            "(a surface developed exactly): it is only for meshes and surfaces "
                            "flattened as meshes");
    m->piece_count = nets->count;
    m->faces = ur_alloc_array(faces, sizeof *m->faces, error);
    m->names = ur_alloc_array(nets->count, sizeof *m->names, error);
    m->colours = ur_alloc_array(nets->count, sizeof *m->colours, error);
    m->outlined = ur_alloc_array(nets->count, sizeof *m->outlined, error);
    if (!m->faces || !m->names || !m->colours || !m->outlined)
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < nets->count; k++) {
        const ur_net *net = &nets->nets[k];
        m->names[k] = options->names && options->names[k] ? options->names[k] : net->name;
        m->outlined[k] = net->face_count > 0 && net->outline_3d && net->outline_count >= 2;
    }
    ur_status status = UR_OK;
    for (size_t k = 0; k < nets->count && status == UR_OK; k++)
        status = add_faces(m, &nets->nets[k], k, error);
    if (status == UR_OK && m->face_count == 0)
        status = ur_error_set(error, UR_ERROR_INPUT, "every face of the pieces has no area");
    pair_list pairs = {NULL, 0, 0};
    if (status == UR_OK)
        status = classify_edges(m, nets, &pairs, error);
    if (status == UR_OK)
        status = find_seam_marks(m, nets, error);
    if (status == UR_OK)
        status = choose_colours(m, &pairs, error);
    free(pairs.items);
    if (status != UR_OK)
        return status;
    measure_model(m);
    return UR_OK;
}
