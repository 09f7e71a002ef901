/*
 * assembly.c: the assembly guide (--assembly): the model drawn from four
 * directions, every piece in its own colour with its name, and the seam
 * labels where the seams lie, so that a person holding a cut piece can find
 * where it goes and which edge to glue to which (Pepakura's 3D view, on
 * paper).  PNG through a cairo image, PDF through cairo's PDF surface.
 *
 * The four views look from the corners of a regular tetrahedron: front
 * right and back left from above, front left and back right from below.
 * Their directions sum to zero, so every face of the model faces at least
 * one of them (its normal makes less than 71 degrees with it): no face of
 * a convex model is left unseen, as it could be with views along the axes.
 *
 * Hidden faces: the painter's algorithm, faces drawn from far to near by
 * the depth of their centroids, with the faces turned away culled when the
 * mesh is closed (they are always behind); an open mesh shows their inside
 * in a greyer tint.  The painter's order can be wrong where faces overlap
 * in depth, so what the labels need, whether a point is seen, is decided
 * exactly: a grid over each view indexes the projected faces, and a point
 * is hidden when a face over it lies nearer the viewer.  That keeps a
 * label of a seam behind the model off the picture, and it stays fast on
 * meshes of 100,000 faces.
 *
 * Colours: evenly spaced hues, one per piece, stepped round the circle by
 * about 1/phi^2 of a turn so that pieces numbered one after another (often
 * neighbours) differ most, lit by a light from the viewer's upper left.
 * Shading scales a colour toward black and the back side mixes it with
 * grey: neither changes its hue, so a piece keeps one hue everywhere.
 *
 * Labels never overlap: piece names go first (each piece named in every
 * view where enough of it is seen, and at least once), then the seam
 * labels not yet shown in an earlier view, then the rest; a label that has
 * no room at its point moves a little aside on a leader line, or is left
 * out.  The cut pieces carry every label: the guide shows where they are.
 */
#include "unroll/out.h"

#include <cairo-pdf.h>
#include <cairo.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "atomic.h"
#include "draw.h"
#include "png.h"

/* The picture in pixels of the PNG; the PDF draws the same at PDF_SCALE points a pixel. */
enum {
    CELL = 1150,  /* one view's square */
    MARGIN = 24,  /* round and between the views */
    HEADER = 184, /* title, key and swatches above the views */
    CAPTION = 44, /* a view's caption, at the top of its square */
    INSET = 16,   /* between a view's square and its drawing */
    COLUMNS = 2,
    ROWS = 2,
    VIEWS = COLUMNS * ROWS,
    CANVAS_WIDTH = COLUMNS * CELL + (COLUMNS + 1) * MARGIN,
    CANVAS_HEIGHT = HEADER + ROWS * CELL + ROWS * MARGIN,
};

/* About 297 mm wide: A3's short side, A4 landscape at 70 %. */
static const double PDF_SCALE = 0.355;

/* Type sizes, pixels. */
static const double TITLE_SIZE = 34, KEY_SIZE = 19, CAPTION_SIZE = 23, NAME_SIZE = 24,
                    SEAM_SIZE = 15;

/* A piece is named in a view where this much of it (pixels^2) is seen. */
static const double NAME_MIN_AREA = 2500;

/* A fold is drawn where the faces turn by more than this (radians) and it is this long (pixels). */
static const double FOLD_MIN_ANGLE = 0.035, FOLD_MIN_LENGTH = 7;

/* Rows of swatches in the key; the pieces that find no room there are told by their names alone. */
enum { SWATCH_ROWS = 2 };

/* ---- The model ----------------------------------------------------------- */

typedef struct face {
    ur_vec3 corner[3];
    ur_vec3 normal; /* unit, toward the outside */
    size_t piece;
    unsigned char border; /* bit k: the edge from corner k to k + 1 is on its piece's outline */
    unsigned char fold;   /* bit k: that edge is a fold inside the piece */
} face;

/* Where a seam is: the middle of its run, by length, in 3D. */
typedef struct seam_mark {
    int seam;
    ur_vec3 point;
} seam_mark;

typedef struct model {
    face *faces;
    size_t face_count;
    size_t piece_count;   /* the nets, drawn or not */
    size_t pieces_drawn;  /* nets with faces */
    bool *outlined;       /* per piece: its net has faces and its outline in 3D */
    const char **names;   /* per piece, borrowed */
    double (*colours)[3]; /* per piece, sRGB 0..1 */
    seam_mark *seams;
    size_t seam_count;
    bool closed; /* every edge has a face on both sides */
    ur_vec3 centre;
    double size; /* the diagonal of the box round it */
} model;

static void model_free(model *m)
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

/*
 * Piece k gets hue j / n, j = k m mod n, m the whole number nearest
 * n / phi^2 that is prime to n: every hue used once, and pieces numbered
 * one after another far apart on the circle.
 */
static void choose_colours(model *m)
{
    size_t n = m->piece_count, step = 1;
    if (n > 2) {
        step = (size_t)fmax(1, round((double)n * 0.381966));
        while (greatest_divisor(n, step) != 1)
            step++;
    }
    for (size_t k = 0; k < n; k++) {
        double j = (double)((k * step) % n);
        double saturation = k % 2 ? 0.62 : 0.5;
        hsv_to_rgb(0.58 + j / (double)n, saturation, 0.97, m->colours[k]);
    }
}

static int compare_points(const ur_vec3 *a, const ur_vec3 *b)
{
    if (a->x != b->x)
        return a->x < b->x ? -1 : 1;
    if (a->y != b->y)
        return a->y < b->y ? -1 : 1;
    if (a->z != b->z)
        return a->z < b->z ? -1 : 1;
    return 0;
}

typedef struct point_ref {
    const ur_vec3 *point;
    size_t index;
} point_ref;

static int compare_point_refs(const void *a, const void *b)
{
    const point_ref *p = a, *q = b;
    int order = compare_points(p->point, q->point);
    return order ? order : (p->index > q->index) - (p->index < q->index);
}

/* An edge of a face, or of a piece's outline (face NO_FACE). */
typedef struct edge_ref {
    size_t low, high; /* the point numbers of its ends */
    size_t face;
    size_t piece;
    int side; /* a face's edge from corner side to side + 1 */
} edge_ref;

#define NO_FACE ((size_t)-1)

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
    point_ref *points = ur_alloc_array(count, sizeof *points, error);
    if (!points)
        return UR_ERROR_INTERNAL;
    size_t n = 0;
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++, n++)
            points[n] = (point_ref){&m->faces[f].corner[k], n};
    for (size_t k = 0; k < nets->count; k++)
        for (size_t i = 0; m->outlined[k] && i < nets->nets[k].outline_count; i++, n++)
            points[n] = (point_ref){&nets->nets[k].outline_3d[i], n};
    qsort(points, count, sizeof *points, compare_point_refs);
    size_t number = 0;
    for (size_t i = 0; i < count; i++) {
        if (i > 0 && compare_points(points[i - 1].point, points[i].point) != 0)
            number++;
        numbers[points[i].index] = number;
    }
    free(points);
    return UR_OK;
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
static void classify_run(model *m, const edge_ref *run, size_t count)
{
    size_t faces = 0;
    for (size_t i = 0; i < count; i++)
        faces += run[i].face != NO_FACE;
    if (faces == 1)
        m->closed = false;
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
}

static ur_status classify_edges(model *m, const ur_net_list *nets, ur_error *error)
{
    size_t count = 3 * m->face_count;
    for (size_t k = 0; k < nets->count; k++)
        count += m->outlined[k] ? nets->nets[k].outline_count : 0;
    size_t *numbers = ur_alloc_array(count, sizeof *numbers, error);
    edge_ref *edges = ur_alloc_array(count, sizeof *edges, error);
    ur_status status =
        numbers && edges ? number_points(m, nets, count, numbers, error) : UR_ERROR_INTERNAL;
    if (status == UR_OK) {
        list_edges(m, nets, numbers, edges);
        qsort(edges, count, sizeof *edges, compare_edges);
        m->closed = true;
        for (size_t i = 0, j; i < count; i = j) {
            for (j = i + 1;
                 j < count && edges[j].low == edges[i].low && edges[j].high == edges[i].high; j++)
                ;
            classify_run(m, &edges[i], j - i);
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

/* The seams, each once, at the middle of its run (both sides run over the same edges). */
static ur_status find_seam_marks(model *m, const ur_net_list *nets, ur_error *error)
{
    size_t sides = 0;
    for (size_t k = 0; k < nets->count; k++)
        sides += nets->nets[k].outline_3d ? nets->nets[k].seam_side_count : 0;
    m->seams = ur_alloc_array(sides ? sides : 1, sizeof *m->seams, error);
    if (!m->seams)
        return UR_ERROR_INTERNAL;
    for (size_t k = 0; k < nets->count; k++) {
        const ur_net *net = &nets->nets[k];
        for (size_t s = 0; net->outline_3d && net->outline_count && s < net->seam_side_count; s++) {
            const ur_seam_side *side = &net->seam_sides[s];
            bool seen = false;
            for (size_t j = 0; j < m->seam_count && !seen; j++)
                seen = m->seams[j].seam == side->seam;
            if (seen || side->count < 2)
                continue;
            double length = 0;
            for (size_t i = 0; i + 1 < side->count; i++)
                length += ur_vec3_distance(outline_point(net, side->first, i),
                                           outline_point(net, side->first, i + 1));
            double walked = 0;
            ur_vec3 middle = outline_point(net, side->first, 0);
            for (size_t i = 0; i + 1 < side->count; i++) {
                ur_vec3 a = outline_point(net, side->first, i);
                ur_vec3 b = outline_point(net, side->first, i + 1);
                double step = ur_vec3_distance(a, b);
                if (walked + step >= length / 2 && step > 0) {
                    middle = ur_vec3_add_scaled(a, ur_vec3_sub(b, a), (length / 2 - walked) / step);
                    break;
                }
                walked += step;
            }
            m->seams[m->seam_count++] = (seam_mark){side->seam, middle};
        }
    }
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

static ur_status build_model(const ur_net_list *nets, const ur_assembly_options *options, model *m,
                             ur_error *error)
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
        return UR_ERROR_INTERNAL;
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
    if (status == UR_OK)
        status = classify_edges(m, nets, error);
    if (status == UR_OK)
        status = find_seam_marks(m, nets, error);
    if (status != UR_OK)
        return status;
    measure_model(m);
    choose_colours(m);
    return UR_OK;
}

/* ---- Views ----------------------------------------------------------------- */

typedef struct camera {
    const char *caption;
    ur_vec3 toward; /* from the model to the viewer, unit */
    ur_vec3 right, up;
} camera;

/* The corners of a tetrahedron round the model, in its frame (up, toward the front, right). */
static void make_cameras(bool y_up, camera cameras[VIEWS])
{
    ur_vec3 up = y_up ? ur_vec3_make(0, 1, 0) : ur_vec3_make(0, 0, 1);
    ur_vec3 front = y_up ? ur_vec3_make(0, 0, 1) : ur_vec3_make(0, -1, 0);
    ur_vec3 right = ur_vec3_make(1, 0, 0);
    static const struct {
        const char *caption;
        double right, front, up;
    } corners[VIEWS] = {
        {"front right, from above", 1, 1, 1},
        {"back left, from above", -1, -1, 1},
        {"front left, from below", -1, 1, -1},
        {"back right, from below", 1, -1, -1},
    };
    for (int v = 0; v < VIEWS; v++) {
        ur_vec3 t = ur_vec3_add(ur_vec3_add(ur_vec3_scale(right, corners[v].right),
                                            ur_vec3_scale(front, corners[v].front)),
                                ur_vec3_scale(up, corners[v].up));
        t = ur_vec3_scale(t, 1 / ur_vec3_length(t));
        ur_vec3 r = ur_vec3_cross(up, t);
        r = ur_vec3_scale(r, 1 / ur_vec3_length(r));
        cameras[v] = (camera){corners[v].caption, t, r, ur_vec3_cross(t, r)};
    }
}

/* The faces drawn in a view, indexed by where they fall on it. */
typedef struct grid {
    double left, top, cell; /* pixels */
    size_t columns, rows;
    size_t *start; /* columns * rows + 1: the faces of cell c are faces[start[c] .. start[c + 1]) */
    size_t *faces;
} grid;

typedef struct view {
    camera camera;
    double left, top, width, height; /* the drawing area, pixels */
    double scale;                    /* pixels a model unit */
    ur_vec2 middle;                  /* the model point drawn at the area's middle (view plane) */
    ur_vec2 (*points)[3];            /* per face: its corners on the picture */
    double (*depth)[3];              /* per face: its corners' depths, larger nearer */
    size_t *order;                   /* the faces drawn, far to near */
    size_t drawn;
    grid grid;
    double *seen_area;   /* per piece: pixels^2 seen */
    ur_vec2 *name_point; /* per piece: where its name goes */
} view;

static void view_free(view *v)
{
    free(v->points);
    free(v->depth);
    free(v->order);
    free(v->grid.start);
    free(v->grid.faces);
    free(v->seen_area);
    free(v->name_point);
    memset(v, 0, sizeof *v);
}

static ur_vec2 plane_point(const camera *c, const model *m, ur_vec3 p)
{
    ur_vec3 d = ur_vec3_sub(p, m->centre);
    return ur_vec2_make(ur_vec3_dot(d, c->right), ur_vec3_dot(d, c->up));
}

static double depth_of(const camera *c, const model *m, ur_vec3 p)
{
    return ur_vec3_dot(ur_vec3_sub(p, m->centre), c->toward);
}

static ur_vec2 to_picture(const view *v, ur_vec2 plane)
{
    return ur_vec2_make(v->left + v->width / 2 + (plane.x - v->middle.x) * v->scale,
                        v->top + v->height / 2 - (plane.y - v->middle.y) * v->scale);
}

/* The model's extent on the view plane, and the scale at which it fills the area. */
static double fit_scale(view *v, const model *m)
{
    double low_x = INFINITY, high_x = -INFINITY, low_y = INFINITY, high_y = -INFINITY;
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++) {
            ur_vec2 p = plane_point(&v->camera, m, m->faces[f].corner[k]);
            low_x = fmin(low_x, p.x), high_x = fmax(high_x, p.x);
            low_y = fmin(low_y, p.y), high_y = fmax(high_y, p.y);
        }
    v->middle = ur_vec2_make((low_x + high_x) / 2, (low_y + high_y) / 2);
    double sx = high_x > low_x ? v->width / (high_x - low_x) : INFINITY;
    double sy = high_y > low_y ? v->height / (high_y - low_y) : INFINITY;
    return fmin(sx, sy);
}

typedef struct depth_key {
    double depth;
    size_t face;
} depth_key;

static int compare_depths(const void *a, const void *b)
{
    const depth_key *p = a, *q = b;
    if (p->depth != q->depth)
        return p->depth < q->depth ? -1 : 1;
    return (p->face > q->face) - (p->face < q->face);
}

static bool faces_viewer(const view *v, const face *f)
{
    return ur_vec3_dot(f->normal, v->camera.toward) > 0;
}

/* The faces to draw (those turned away only on an open mesh), far to near. */
static ur_status sort_faces(view *v, const model *m, ur_error *error)
{
    depth_key *keys = ur_alloc_array(m->face_count, sizeof *keys, error);
    v->order = ur_alloc_array(m->face_count, sizeof *v->order, error);
    if (!keys || !v->order) {
        free(keys);
        return UR_ERROR_INTERNAL;
    }
    v->drawn = 0;
    for (size_t f = 0; f < m->face_count; f++)
        if (!m->closed || faces_viewer(v, &m->faces[f]))
            keys[v->drawn++] =
                (depth_key){(v->depth[f][0] + v->depth[f][1] + v->depth[f][2]) / 3, f};
    qsort(keys, v->drawn, sizeof *keys, compare_depths);
    for (size_t i = 0; i < v->drawn; i++)
        v->order[i] = keys[i].face;
    free(keys);
    return UR_OK;
}

static void cell_range(const grid *g, double low, double high, size_t cells, double origin,
                       size_t *first, size_t *last)
{
    double a = floor((low - origin) / g->cell), b = floor((high - origin) / g->cell);
    *first = (size_t)fmax(0, fmin((double)cells - 1, a));
    *last = (size_t)fmax(0, fmin((double)cells - 1, b));
}

static void face_cells(const grid *g, const ur_vec2 p[3], size_t range[4])
{
    double x0 = fmin(p[0].x, fmin(p[1].x, p[2].x)), x1 = fmax(p[0].x, fmax(p[1].x, p[2].x));
    double y0 = fmin(p[0].y, fmin(p[1].y, p[2].y)), y1 = fmax(p[0].y, fmax(p[1].y, p[2].y));
    cell_range(g, x0, x1, g->columns, g->left, &range[0], &range[1]);
    cell_range(g, y0, y1, g->rows, g->top, &range[2], &range[3]);
}

/* About one face a cell, at most 1024 cells a side. */
static ur_status build_grid(view *v, ur_error *error)
{
    grid *g = &v->grid;
    double side = fmax(v->width, v->height);
    g->columns = g->rows = (size_t)fmax(1, fmin(1024, ceil(sqrt((double)v->drawn))));
    g->cell = side / (double)g->columns;
    g->left = v->left;
    g->top = v->top;
    size_t cells = g->columns * g->rows;
    g->start = calloc(cells + 1, sizeof *g->start);
    if (!g->start)
        return ur_error_out_of_memory(error);
    size_t range[4];
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < v->drawn; i++) {
            face_cells(g, v->points[v->order[i]], range);
            for (size_t r = range[2]; r <= range[3]; r++)
                for (size_t c = range[0]; c <= range[1]; c++) {
                    size_t cell = r * g->columns + c;
                    if (pass == 0)
                        g->start[cell + 1]++;
                    else
                        g->faces[g->start[cell]++] = v->order[i];
                }
        }
        if (pass == 0) {
            for (size_t c = 0; c < cells; c++)
                g->start[c + 1] += g->start[c];
            g->faces =
                ur_alloc_array(g->start[cells] ? g->start[cells] : 1, sizeof *g->faces, error);
            if (!g->faces)
                return UR_ERROR_INTERNAL;
        }
    }
    for (size_t c = cells; c > 0; c--) /* the fill moved each start to the next cell's */
        g->start[c] = g->start[c - 1];
    g->start[0] = 0;
    return UR_OK;
}

/*
 * Whether the model point drawn at q with that depth is in sight: no face
 * drawn over q lies nearer the viewer by more than tolerance.
 */
static bool in_sight(const view *v, ur_vec2 q, double depth, double tolerance)
{
    const grid *g = &v->grid;
    double column = floor((q.x - g->left) / g->cell), row = floor((q.y - g->top) / g->cell);
    if (column < 0 || row < 0 || column >= (double)g->columns || row >= (double)g->rows)
        return true;
    size_t cell = (size_t)row * g->columns + (size_t)column;
    for (size_t i = g->start[cell]; i < g->start[cell + 1]; i++) {
        size_t f = g->faces[i];
        const ur_vec2 *p = v->points[f];
        double area = ur_vec2_cross(ur_vec2_sub(p[1], p[0]), ur_vec2_sub(p[2], p[0]));
        if (fabs(area) < 1e-12)
            continue; /* seen edge on */
        double w[3];
        for (int k = 0; k < 3; k++)
            w[k] = ur_vec2_cross(ur_vec2_sub(p[(k + 2) % 3], p[(k + 1) % 3]),
                                 ur_vec2_sub(q, p[(k + 1) % 3])) /
                   area;
        if (w[0] < -1e-9 || w[1] < -1e-9 || w[2] < -1e-9)
            continue;
        double there = w[0] * v->depth[f][0] + w[1] * v->depth[f][1] + w[2] * v->depth[f][2];
        if (there > depth + tolerance)
            return false;
    }
    return true;
}

static double face_area_on_picture(const ur_vec2 p[3])
{
    return 0.5 * fabs(ur_vec2_cross(ur_vec2_sub(p[1], p[0]), ur_vec2_sub(p[2], p[0])));
}

/*
 * How much of each piece is seen, and where its name goes: the middle of
 * the face seen nearest the centroid of what is seen of it.
 */
static ur_status measure_pieces(view *v, const model *m, ur_error *error)
{
    size_t n = m->piece_count;
    v->seen_area = calloc(n ? n : 1, sizeof *v->seen_area);
    v->name_point = calloc(n ? n : 1, sizeof *v->name_point);
    ur_vec2 *weighted = calloc(n ? n : 1, sizeof *weighted);
    double *nearest = ur_alloc_array(n ? n : 1, sizeof *nearest, error);
    bool *face_seen = calloc(m->face_count, sizeof *face_seen);
    if (!v->seen_area || !v->name_point || !weighted || !nearest || !face_seen) {
        free(weighted);
        free(nearest);
        free(face_seen);
        return ur_error_out_of_memory(error);
    }
    double tolerance = 1e-4 * m->size;
    for (size_t i = 0; i < v->drawn; i++) {
        size_t f = v->order[i];
        const ur_vec2 *p = v->points[f];
        ur_vec2 middle = ur_vec2_scale(ur_vec2_add(ur_vec2_add(p[0], p[1]), p[2]), 1.0 / 3);
        double depth = (v->depth[f][0] + v->depth[f][1] + v->depth[f][2]) / 3;
        if (!faces_viewer(v, &m->faces[f]) || !in_sight(v, middle, depth, tolerance))
            continue;
        face_seen[f] = true;
        double area = face_area_on_picture(p);
        size_t piece = m->faces[f].piece;
        v->seen_area[piece] += area;
        weighted[piece] = ur_vec2_add_scaled(weighted[piece], middle, area);
    }
    for (size_t k = 0; k < n; k++) {
        nearest[k] = INFINITY;
        if (v->seen_area[k] > 0)
            weighted[k] = ur_vec2_scale(weighted[k], 1 / v->seen_area[k]);
    }
    for (size_t f = 0; f < m->face_count; f++) {
        if (!face_seen[f])
            continue;
        const ur_vec2 *p = v->points[f];
        ur_vec2 middle = ur_vec2_scale(ur_vec2_add(ur_vec2_add(p[0], p[1]), p[2]), 1.0 / 3);
        size_t piece = m->faces[f].piece;
        double distance = ur_vec2_distance(middle, weighted[piece]);
        if (distance < nearest[piece]) {
            nearest[piece] = distance;
            v->name_point[piece] = middle;
        }
    }
    free(weighted);
    free(nearest);
    free(face_seen);
    return UR_OK;
}

static ur_status prepare_view(view *v, const model *m, ur_error *error)
{
    v->points = ur_alloc_array(m->face_count, sizeof *v->points, error);
    v->depth = ur_alloc_array(m->face_count, sizeof *v->depth, error);
    if (!v->points || !v->depth)
        return UR_ERROR_INTERNAL;
    for (size_t f = 0; f < m->face_count; f++)
        for (int k = 0; k < 3; k++) {
            ur_vec3 p = m->faces[f].corner[k];
            v->points[f][k] = to_picture(v, plane_point(&v->camera, m, p));
            v->depth[f][k] = depth_of(&v->camera, m, p);
        }
    ur_status status = sort_faces(v, m, error);
    if (status == UR_OK)
        status = build_grid(v, error);
    if (status == UR_OK)
        status = measure_pieces(v, m, error);
    return status;
}

/* The views in their squares, all at one scale, so that the model keeps its size. */
static ur_status prepare_views(view views[VIEWS], const model *m, bool y_up, ur_error *error)
{
    camera cameras[VIEWS];
    make_cameras(y_up, cameras);
    double scale = INFINITY;
    for (int k = 0; k < VIEWS; k++) {
        view *v = &views[k];
        v->camera = cameras[k];
        v->left = MARGIN + (k % COLUMNS) * (CELL + MARGIN) + INSET;
        v->top = HEADER + (k / COLUMNS) * (CELL + MARGIN) + CAPTION;
        v->width = CELL - 2 * INSET;
        v->height = CELL - CAPTION - INSET;
        scale = fmin(scale, fit_scale(v, m));
    }
    if (!isfinite(scale) || !(scale > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "the pieces' faces have no extent to draw");
    ur_status status = UR_OK;
    for (int k = 0; k < VIEWS && status == UR_OK; k++) {
        views[k].scale = 0.94 * scale;
        status = prepare_view(&views[k], m, error);
    }
    return status;
}

/* ---- Labels -------------------------------------------------------------- */

typedef struct box {
    double left, top, right, bottom;
} box;

typedef struct label {
    char text[40];
    bool name;      /* a piece's name (bold, on a halo), else a seam's label (in a box) */
    ur_vec2 point;  /* what it labels */
    ur_vec2 centre; /* where it stands */
    box extent;
} label;

typedef struct label_list {
    label *items;
    size_t count, capacity;
} label_list;

static bool boxes_meet(box a, box b)
{
    return a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
}

static bool box_inside(box a, const view *v)
{
    return a.left >= v->left && a.top >= v->top && a.right <= v->left + v->width &&
           a.bottom <= v->top + v->height;
}

static box box_round(ur_vec2 centre, double width, double height)
{
    return (box){centre.x - width / 2, centre.y - height / 2, centre.x + width / 2,
                 centre.y + height / 2};
}

/* Sets the label's font on cr. */
static void label_font(cairo_t *cr, bool name)
{
    ur_draw_set_font(cr, name ? NAME_SIZE : SEAM_SIZE, name);
}

/*
 * Places a label at its point, or a little aside (on a leader line) where
 * it covers no other label; false when it finds no room.
 */
static bool place_label(cairo_t *cr, const view *v, label_list *labels, label *l)
{
    label_font(cr, l->name);
    double size = l->name ? NAME_SIZE : SEAM_SIZE;
    double width = ur_draw_text_width(cr, l->text) + (l->name ? 8 : 10);
    double height = size * (l->name ? 1.2 : 1.45);
    static const double aside[][2] = {{0, 0},  {0, -1},  {0, 1},  {1, 0},  {-1, 0},
                                      {1, -1}, {-1, -1}, {1, 1},  {-1, 1}, {0, -2},
                                      {0, 2},  {2, 0},   {-2, 0}, {2, -2}, {-2, 2}};
    for (size_t a = 0; a < sizeof aside / sizeof aside[0]; a++) {
        if (l->name && a > 8) /* a name strays no further than one step */
            break;
        ur_vec2 centre = ur_vec2_make(l->point.x + aside[a][0] * (width / 2 + height * 0.7),
                                      l->point.y + aside[a][1] * height * 1.05);
        box extent = box_round(centre, width, height);
        bool free_room = box_inside(extent, v);
        for (size_t i = 0; i < labels->count && free_room; i++)
            free_room = !boxes_meet(extent, labels->items[i].extent);
        if (!free_room)
            continue;
        l->centre = centre;
        l->extent = extent;
        labels->items[labels->count++] = *l;
        return true;
    }
    return false;
}

/* In which views each piece is named: where enough of it is seen, and where most is otherwise. */
static void choose_name_views(const view views[VIEWS], const model *m, bool (*named)[VIEWS])
{
    for (size_t k = 0; k < m->piece_count; k++) {
        int best = -1;
        bool any = false;
        for (int v = 0; v < VIEWS; v++) {
            named[k][v] = views[v].seen_area[k] >= NAME_MIN_AREA;
            any = any || named[k][v];
            if (views[v].seen_area[k] > 0 &&
                (best < 0 || views[v].seen_area[k] > views[best].seen_area[k]))
                best = v;
        }
        if (!any && best >= 0)
            named[k][best] = true;
    }
}

/*
 * The labels of one view: piece names, then the seams no earlier view
 * shows, then the others.  first_view[s]: the first view that shows seam
 * s, -1 while none does.
 */
static ur_status place_labels(cairo_t *cr, const view *v, int index, const model *m,
                              bool (*named)[VIEWS], int *first_view, label_list *labels,
                              ur_error *error)
{
    labels->count = 0;
    labels->capacity = m->piece_count + m->seam_count;
    labels->items =
        ur_alloc_array(labels->capacity ? labels->capacity : 1, sizeof *labels->items, error);
    if (!labels->items)
        return UR_ERROR_INTERNAL;
    for (size_t k = 0; k < m->piece_count; k++) {
        if (!named[k][index])
            continue;
        label l = {.name = true, .point = v->name_point[k]};
        snprintf(l.text, sizeof l.text, "%s", m->names[k]);
        place_label(cr, v, labels, &l);
    }
    double tolerance = 1e-4 * m->size;
    for (int pass = 0; pass < 2; pass++)
        for (size_t s = 0; s < m->seam_count; s++) {
            bool earlier = first_view[s] >= 0 && first_view[s] < index;
            if (earlier != (pass == 1) || first_view[s] == index)
                continue;
            ur_vec3 point = m->seams[s].point;
            ur_vec2 q = to_picture(v, plane_point(&v->camera, m, point));
            if (!in_sight(v, q, depth_of(&v->camera, m, point), tolerance))
                continue;
            label l = {.name = false, .point = q};
            ur_seam_label(m->seams[s].seam, l.text, sizeof l.text);
            if (place_label(cr, v, labels, &l) && first_view[s] < 0)
                first_view[s] = index;
        }
    return UR_OK;
}

/* ---- Drawing ------------------------------------------------------------- */

/* A light from the viewer's upper left, mostly from the front: every face seen is lit. */
static double lighting(const view *v, ur_vec3 normal)
{
    ur_vec3 light = ur_vec3_add(
        ur_vec3_add(ur_vec3_scale(v->camera.right, -0.35), ur_vec3_scale(v->camera.up, 0.45)),
        ur_vec3_scale(v->camera.toward, 0.82));
    light = ur_vec3_scale(light, 1 / ur_vec3_length(light));
    return 0.55 + 0.45 * fmax(0, ur_vec3_dot(normal, light));
}

static void face_colour(const view *v, const model *m, const face *f, double rgb[3])
{
    bool front = faces_viewer(v, f);
    double light = lighting(v, front ? f->normal : ur_vec3_scale(f->normal, -1));
    for (int k = 0; k < 3; k++) {
        double c = m->colours[f->piece][k];
        if (!front) /* the inside of an open mesh: the same hue, greyer */
            c = 0.5 * c + 0.5 * 0.62;
        rgb[k] = c * light;
    }
}

static void draw_face(cairo_t *cr, const view *v, const model *m, size_t index)
{
    const face *f = &m->faces[index];
    const ur_vec2 *p = v->points[index];
    double rgb[3];
    face_colour(v, m, f, rgb);
    cairo_move_to(cr, p[0].x, p[0].y);
    cairo_line_to(cr, p[1].x, p[1].y);
    cairo_line_to(cr, p[2].x, p[2].y);
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_set_line_width(cr, 0.8); /* the same colour round it closes the seams of antialiasing */
    cairo_fill_preserve(cr);
    cairo_stroke(cr);
    for (int k = 0; k < 3; k++) {
        ur_vec2 a = p[k], b = p[(k + 1) % 3];
        if (f->border & (1u << k)) {
            cairo_set_source_rgb(cr, 0.08, 0.08, 0.1);
            cairo_set_line_width(cr, 2.2);
        } else if ((f->fold & (1u << k)) && ur_vec2_distance(a, b) >= FOLD_MIN_LENGTH) {
            cairo_set_source_rgb(cr, rgb[0] * 0.6, rgb[1] * 0.6, rgb[2] * 0.6);
            cairo_set_line_width(cr, 0.8);
        } else
            continue;
        cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
        ur_draw_line(cr, a.x, a.y, b.x, b.y);
    }
}

static void draw_label(cairo_t *cr, const label *l)
{
    label_font(cr, l->name);
    bool aside = ur_vec2_distance(l->point, l->centre) > 0.5;
    if (aside) { /* a leader from what it labels to the nearest point of its box */
        ur_vec2 end = ur_vec2_make(fmax(l->extent.left, fmin(l->point.x, l->extent.right)),
                                   fmax(l->extent.top, fmin(l->point.y, l->extent.bottom)));
        cairo_set_source_rgb(cr, 1, 1, 1);
        cairo_set_line_width(cr, 3.2);
        ur_draw_line(cr, l->point.x, l->point.y, end.x, end.y);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        cairo_set_line_width(cr, 1.2);
        ur_draw_line(cr, l->point.x, l->point.y, end.x, end.y);
        cairo_arc(cr, l->point.x, l->point.y, l->name ? 3.5 : 2.5, 0, 2 * M_PI);
        cairo_fill(cr);
    }
    double size = l->name ? NAME_SIZE : SEAM_SIZE;
    double baseline = l->centre.y + 0.36 * size;
    if (l->name) { /* bold on a white halo, over its own colour */
        double width = ur_draw_text_width(cr, l->text);
        cairo_move_to(cr, l->centre.x - width / 2, baseline);
        cairo_text_path(cr, l->text);
        cairo_set_source_rgb(cr, 1, 1, 1);
        cairo_set_line_width(cr, 5);
        cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
        cairo_stroke_preserve(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_fill(cr);
        return;
    }
    double radius = 3;
    box b = l->extent;
    cairo_new_sub_path(cr);
    cairo_arc(cr, b.right - radius, b.top + radius, radius, -M_PI / 2, 0);
    cairo_arc(cr, b.right - radius, b.bottom - radius, radius, 0, M_PI / 2);
    cairo_arc(cr, b.left + radius, b.bottom - radius, radius, M_PI / 2, M_PI);
    cairo_arc(cr, b.left + radius, b.top + radius, radius, M_PI, 3 * M_PI / 2);
    cairo_close_path(cr);
    cairo_set_source_rgba(cr, 1, 1, 0.94, 0.9);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    cairo_set_line_width(cr, 0.9);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
    ur_draw_show_text(cr, l->centre.x, baseline, UR_ALIGN_CENTRE, l->text);
}

static void draw_view_frame(cairo_t *cr, const view *v)
{
    double left = v->left - INSET, top = v->top - CAPTION;
    cairo_rectangle(cr, left, top, CELL, CELL);
    cairo_set_source_rgb(cr, 0.985, 0.985, 0.98);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
    ur_draw_set_font(cr, CAPTION_SIZE, true);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    ur_draw_show_text(cr, left + 14, top + CAPTION - 12, UR_ALIGN_LEFT, v->camera.caption);
}

static void draw_view(cairo_t *cr, const view *v, const model *m, const label_list *labels)
{
    draw_view_frame(cr, v);
    cairo_save(cr);
    cairo_rectangle(cr, v->left - INSET, v->top, CELL, v->height + INSET);
    cairo_clip(cr);
    for (size_t i = 0; i < v->drawn; i++)
        draw_face(cr, v, m, v->order[i]);
    for (size_t i = 0; i < labels->count; i++)
        draw_label(cr, &labels->items[i]);
    cairo_restore(cr);
}

/* Title, what the picture shows, and a swatch of each piece's colour. */
static void draw_header(cairo_t *cr, const model *m, const char *title, size_t seams_shown)
{
    char text[512];
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    ur_draw_set_font(cr, TITLE_SIZE, true);
    snprintf(text, sizeof text, "%s%sassembly guide: %zu piece%s, %zu seam%s", title ? title : "",
             title ? ": " : "", m->pieces_drawn, m->pieces_drawn == 1 ? "" : "s", m->seam_count,
             m->seam_count == 1 ? "" : "s");
    ur_draw_show_text(cr, MARGIN, MARGIN + TITLE_SIZE, UR_ALIGN_LEFT, text);
    ur_draw_set_font(cr, KEY_SIZE, false);
    snprintf(text, sizeof text,
             "Each piece has its own colour and its name. Edges with the same label are glued "
             "together (labels of %zu of the %zu seams have room here; the cut pieces carry all). "
             "Thick lines: cuts between pieces; thin: folds.",
             seams_shown, m->seam_count);
    ur_draw_show_text(cr, MARGIN, MARGIN + TITLE_SIZE + 14 + KEY_SIZE, UR_ALIGN_LEFT, text);
    double x = MARGIN, y = MARGIN + TITLE_SIZE + 2 * KEY_SIZE + 36;
    int row = 0;
    ur_draw_set_font(cr, KEY_SIZE, true);
    for (size_t k = 0; k < m->piece_count; k++) {
        double width = ur_draw_text_width(cr, m->names[k]);
        if (x + 26 + width > CANVAS_WIDTH - MARGIN - 60) {
            if (++row == SWATCH_ROWS) {
                cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
                ur_draw_show_text(cr, x, y, UR_ALIGN_LEFT, "...");
                break;
            }
            x = MARGIN;
            y += KEY_SIZE + 12;
        }
        cairo_rectangle(cr, x, y - KEY_SIZE + 2, 20, KEY_SIZE);
        cairo_set_source_rgb(cr, m->colours[k][0], m->colours[k][1], m->colours[k][2]);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
        cairo_set_line_width(cr, 1);
        cairo_stroke(cr);
        ur_draw_show_text(cr, x + 26, y, UR_ALIGN_LEFT, m->names[k]);
        x += 26 + width + 22;
    }
}

typedef struct guide {
    model model;
    view views[VIEWS];
    const char *title;
    ur_status status; /* of drawing, which allocates the labels */
    ur_error *error;
} guide;

static void guide_free(guide *g)
{
    for (int v = 0; v < VIEWS; v++)
        view_free(&g->views[v]);
    model_free(&g->model);
}

/* The whole picture on cr, in pixels of the PNG. */
static ur_status draw_guide(cairo_t *cr, guide *g, ur_error *error)
{
    const model *m = &g->model;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    bool(*named)[VIEWS] = calloc(m->piece_count ? m->piece_count : 1, sizeof *named);
    int *first_view = ur_alloc_array(m->seam_count ? m->seam_count : 1, sizeof *first_view, error);
    ur_status status = named && first_view ? UR_OK : ur_error_out_of_memory(error);
    for (size_t s = 0; first_view && s < m->seam_count; s++)
        first_view[s] = -1;
    if (status == UR_OK)
        choose_name_views(g->views, m, named);
    for (int v = 0; v < VIEWS && status == UR_OK; v++) {
        label_list labels = {0};
        status = place_labels(cr, &g->views[v], v, m, named, first_view, &labels, error);
        if (status == UR_OK)
            draw_view(cr, &g->views[v], m, &labels);
        free(labels.items);
    }
    size_t shown = 0;
    for (size_t s = 0; first_view && s < m->seam_count; s++)
        shown += first_view[s] >= 0;
    if (status == UR_OK)
        draw_header(cr, m, g->title, shown);
    free(named);
    free(first_view);
    if (status == UR_OK && cairo_status(cr) != CAIRO_STATUS_SUCCESS)
        status = ur_error_set(error, UR_ERROR_INTERNAL, "drawing the assembly guide: %s",
                              cairo_status_to_string(cairo_status(cr)));
    return status;
}

/* ---- Files ----------------------------------------------------------------- */

static bool ends_with(const char *path, const char *extension)
{
    size_t length = strlen(path), tail = strlen(extension);
    if (length <= tail)
        return false;
    for (size_t i = 0; i < tail; i++)
        if (tolower((unsigned char)path[length - tail + i]) != extension[i])
            return false;
    return true;
}

static ur_status write_png(const char *path, guide *g, ur_error *error)
{
    cairo_surface_t *surface =
        cairo_image_surface_create(CAIRO_FORMAT_RGB24, CANVAS_WIDTH, CANVAS_HEIGHT);
    cairo_t *cr = cairo_create(surface);
    ur_status status =
        cairo_status(cr) == CAIRO_STATUS_SUCCESS
            ? draw_guide(cr, g, error)
            : ur_error_set(error, UR_ERROR_INTERNAL, "cannot make a %d x %d picture: %s",
                           CANVAS_WIDTH, CANVAS_HEIGHT, cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    cairo_surface_flush(surface);
    if (status == UR_OK)
        status = ur_atomic_write(path, png_emit, surface, "assembly guide", error);
    cairo_surface_destroy(surface);
    return status;
}

static cairo_status_t pdf_write_bytes(void *stream, const unsigned char *data, unsigned int length)
{
    return fwrite(data, 1, length, stream) == length ? CAIRO_STATUS_SUCCESS
                                                     : CAIRO_STATUS_WRITE_ERROR;
}

/* An ur_emitter: the guide as a one-page PDF, drawn straight into the stream. */
static bool pdf_emit(FILE *stream, const void *data)
{
    guide *g = (guide *)data;
    cairo_surface_t *surface = cairo_pdf_surface_create_for_stream(
        pdf_write_bytes, stream, CANVAS_WIDTH * PDF_SCALE, CANVAS_HEIGHT * PDF_SCALE);
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE,
                                   g->title ? g->title : "assembly guide");
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "unroll");
    cairo_t *cr = cairo_create(surface);
    cairo_scale(cr, PDF_SCALE, PDF_SCALE);
    g->status = cairo_status(cr) == CAIRO_STATUS_SUCCESS
                    ? draw_guide(cr, g, g->error)
                    : ur_error_set(g->error, UR_ERROR_INTERNAL, "cannot start a PDF: %s",
                                   cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    cairo_surface_finish(surface);
    bool written = cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS;
    cairo_surface_destroy(surface);
    return g->status == UR_OK && written;
}

static ur_status write_pdf(const char *path, guide *g, ur_error *error)
{
    ur_error drawing;
    ur_error_clear(&drawing);
    g->error = &drawing;
    g->status = UR_OK;
    ur_status status = ur_atomic_write(path, pdf_emit, g, "assembly guide", error);
    if (g->status != UR_OK) { /* the drawing's own reason, not "cannot write" */
        *error = drawing;
        status = g->status;
    }
    return status;
}

ur_status ur_assembly_write(const ur_net_list *nets, const char *path,
                            const ur_assembly_options *options, ur_error *error)
{
    ur_assembly_options defaults = {0};
    if (!options)
        options = &defaults;
    if (!nets || !path || (nets->count > 0 && !nets->nets))
        return ur_error_set(error, UR_ERROR_INTERNAL, "assembly guide writer called without %s",
                            !path ? "a path" : "its pieces");
    bool png = ends_with(path, ".png"), pdf = ends_with(path, ".pdf");
    if (!png && !pdf)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s': the assembly guide is a .png or a .pdf file", path);
    guide g;
    memset(&g, 0, sizeof g);
    g.title = options->title;
    ur_status status = build_model(nets, options, &g.model, error);
    if (status == UR_OK)
        status = prepare_views(g.views, &g.model, options->y_up, error);
    if (status == UR_OK)
        status = png ? write_png(path, &g, error) : write_pdf(path, &g, error);
    guide_free(&g);
    return status;
}
