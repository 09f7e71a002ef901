/*
 * assembly_view.c: the four views of the assembly guide (assembly.h).
 *
 * They look from the corners of a regular tetrahedron: front right and
 * back left from above, front left and back right from below.  Their
 * directions sum to zero, so every face of the model faces at least one of
 * them (its normal makes less than 71 degrees with it): no face of a convex
 * model is left unseen, as it could be with views along the axes.  The
 * projection is orthographic, every view at the same scale.
 *
 * Hidden faces: the faces are drawn from far to near by the depth of their
 * centroids (the painter's algorithm), those turned away left out when the
 * mesh is closed (they are always behind).  That order can be wrong where
 * faces overlap in depth, so what the labels need, whether a point is
 * seen, is decided exactly: a grid over the view indexes the faces drawn,
 * and a point is hidden when a face over it lies nearer the viewer.  It
 * stays fast on meshes of 100,000 faces (about a face a cell).
 */
#include "assembly.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

void assembly_view_free(view *v)
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

ur_vec2 assembly_picture_point(const view *v, const model *m, ur_vec3 p)
{
    return to_picture(v, plane_point(&v->camera, m, p));
}

double assembly_depth(const view *v, const model *m, ur_vec3 p)
{
    return depth_of(&v->camera, m, p);
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

bool assembly_faces_viewer(const view *v, const face *f)
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
        return UR_ERROR_MEMORY;
    }
    v->drawn = 0;
    for (size_t f = 0; f < m->face_count; f++)
        if (!m->closed || assembly_faces_viewer(v, &m->faces[f]))
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
                return UR_ERROR_MEMORY;
        }
    }
    for (size_t c = cells; c > 0; c--) /* the fill moved each start to the next cell's */
        g->start[c] = g->start[c - 1];
    g->start[0] = 0;
    return UR_OK;
}

/* Whether face f is drawn over q, and its depth there. */
static bool face_over(const view *v, size_t f, ur_vec2 q, double *depth)
{
    const ur_vec2 *p = v->points[f];
    double area = ur_vec2_cross(ur_vec2_sub(p[1], p[0]), ur_vec2_sub(p[2], p[0]));
    if (fabs(area) < 1e-12)
        return false; /* seen edge on */
    double w[3];
    for (int k = 0; k < 3; k++)
        w[k] = ur_vec2_cross(ur_vec2_sub(p[(k + 2) % 3], p[(k + 1) % 3]),
                             ur_vec2_sub(q, p[(k + 1) % 3])) /
               area;
    if (w[0] < -1e-9 || w[1] < -1e-9 || w[2] < -1e-9)
        return false;
    *depth = w[0] * v->depth[f][0] + w[1] * v->depth[f][1] + w[2] * v->depth[f][2];
    return true;
}

/* The faces the grid holds over q: [*first, *end) of grid.faces (none off the grid). */
static void faces_near(const view *v, ur_vec2 q, size_t *first, size_t *end)
{
    const grid *g = &v->grid;
    double column = floor((q.x - g->left) / g->cell), row = floor((q.y - g->top) / g->cell);
    *first = *end = 0;
    if (column < 0 || row < 0 || column >= (double)g->columns || row >= (double)g->rows)
        return;
    size_t cell = (size_t)row * g->columns + (size_t)column;
    *first = g->start[cell];
    *end = g->start[cell + 1];
}

/*
 * Whether the model point drawn at q with that depth is in sight: no face
 * drawn over q lies nearer the viewer by more than tolerance.
 */
bool assembly_in_sight(const view *v, ur_vec2 q, double depth, double tolerance)
{
    size_t first, end;
    faces_near(v, q, &first, &end);
    for (size_t i = first; i < end; i++) {
        double there;
        if (face_over(v, v->grid.faces[i], q, &there) && there > depth + tolerance)
            return false;
    }
    return true;
}

/* The face seen at q: the nearest drawn over it; NO_FACE where there is none. */
static size_t face_seen_at(const view *v, ur_vec2 q)
{
    size_t first, end, seen = NO_FACE;
    double nearest = -INFINITY, there;
    faces_near(v, q, &first, &end);
    for (size_t i = first; i < end; i++)
        if (face_over(v, v->grid.faces[i], q, &there) && there > nearest) {
            nearest = there;
            seen = v->grid.faces[i];
        }
    return seen;
}

double assembly_face_area(const ur_vec2 p[3])
{
    return 0.5 * fabs(ur_vec2_cross(ur_vec2_sub(p[1], p[0]), ur_vec2_sub(p[2], p[0])));
}

static ur_vec2 face_middle(const view *v, size_t f)
{
    const ur_vec2 *p = v->points[f];
    return ur_vec2_scale(ur_vec2_add(ur_vec2_add(p[0], p[1]), p[2]), 1.0 / 3);
}

/* A face seen, and how far its middle is from the middle of what is seen of its piece. */
typedef struct candidate {
    size_t piece;
    double distance;
    size_t face;
} candidate;

static int compare_candidates(const void *a, const void *b)
{
    const candidate *p = a, *q = b;
    if (p->piece != q->piece)
        return p->piece < q->piece ? -1 : 1;
    if (p->distance != q->distance)
        return p->distance < q->distance ? -1 : 1;
    return (p->face > q->face) - (p->face < q->face);
}

/* The faces of a piece tried for its name, nearest the middle first. */
enum { NAME_TRIES = 300 };

/* How many of nine points round `at`, as far apart as a name is wide and tall, show the piece. */
static int name_room(const view *v, const model *m, size_t piece, ur_vec2 at)
{
    double half_width = 0.3 * NAME_SIZE * (double)strlen(m->names[piece]) + 4;
    double half_height = 0.55 * NAME_SIZE;
    int room = 0;
    for (int i = -1; i <= 1; i++)
        for (int j = -1; j <= 1; j++) {
            size_t f = face_seen_at(v, ur_vec2_make(at.x + i * half_width, at.y + j * half_height));
            room += f != NO_FACE && m->faces[f].piece == piece;
        }
    return room;
}

/*
 * Where each piece's name goes in the view: on the face seen nearest the
 * middle of what is seen of the piece where the name has the most room on
 * it (a ring's middle is in its hole, a crescent's off it).
 */
static void place_names(view *v, const model *m, candidate *seen, size_t count)
{
    qsort(seen, count, sizeof *seen, compare_candidates);
    for (size_t i = 0, j; i < count; i = j) {
        size_t piece = seen[i].piece;
        int best = -1;
        for (j = i; j < count && seen[j].piece == piece; j++) {
            if (j - i >= NAME_TRIES || best == 9)
                continue;
            ur_vec2 at = face_middle(v, seen[j].face);
            int room = name_room(v, m, piece, at);
            if (room > best) {
                best = room;
                v->name_point[piece] = at;
            }
        }
    }
}

/* How much of each piece is seen (pixels^2), and where its name goes. */
static ur_status measure_pieces(view *v, const model *m, ur_error *error)
{
    size_t n = m->piece_count;
    v->seen_area = calloc(n ? n : 1, sizeof *v->seen_area);
    v->name_point = calloc(n ? n : 1, sizeof *v->name_point);
    ur_vec2 *weighted = calloc(n ? n : 1, sizeof *weighted);
    candidate *seen = ur_alloc_array(v->drawn ? v->drawn : 1, sizeof *seen, error);
    if (!v->seen_area || !v->name_point || !weighted || !seen) {
        free(weighted);
        free(seen);
        return ur_error_out_of_memory(error);
    }
    double tolerance = 1e-4 * m->size;
    size_t count = 0;
    for (size_t i = 0; i < v->drawn; i++) {
        size_t f = v->order[i];
        ur_vec2 middle = face_middle(v, f);
        double depth = (v->depth[f][0] + v->depth[f][1] + v->depth[f][2]) / 3;
        if (!assembly_in_sight(v, middle, depth, tolerance))
            continue; /* the faces drawn are those that can be seen: an open mesh's inside too */
        double area = assembly_face_area(v->points[f]);
        size_t piece = m->faces[f].piece;
        v->seen_area[piece] += area;
        weighted[piece] = ur_vec2_add_scaled(weighted[piece], middle, area);
        seen[count++] = (candidate){piece, 0, f};
    }
    for (size_t k = 0; k < n; k++)
        if (v->seen_area[k] > 0)
            weighted[k] = ur_vec2_scale(weighted[k], 1 / v->seen_area[k]);
    for (size_t i = 0; i < count; i++)
        seen[i].distance = ur_vec2_distance(face_middle(v, seen[i].face), weighted[seen[i].piece]);
    place_names(v, m, seen, count);
    free(weighted);
    free(seen);
    return UR_OK;
}

static ur_status prepare_view(view *v, const model *m, ur_error *error)
{
    v->points = ur_alloc_array(m->face_count, sizeof *v->points, error);
    v->depth = ur_alloc_array(m->face_count, sizeof *v->depth, error);
    if (!v->points || !v->depth)
        return UR_ERROR_MEMORY;
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
ur_status assembly_views_prepare(view views[VIEWS], const model *m, bool y_up, ur_error *error)
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
