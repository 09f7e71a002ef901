/*
 * label.c: engraved labels in a single-stroke Hershey font.
 *
 * A laser or a router draws engraved text as lines, so the font must be
 * made of strokes, not outlines: libhersheyfont reads the Hershey fonts
 * (the .jhf files of the hershey-fonts-data package) and gives each ASCII
 * glyph as polylines.  ur_text_strokes turns a string into such polylines
 * at a given cap height; ur_piece_add_label finds room for them on a piece,
 * as near a given point as it can, and engraves them there.
 *
 * Font coordinates: libhersheyfont already turns the Hershey y axis (which
 * points down in the .jhf files) around, so its glyphs have y up, x from 0
 * at the glyph's left edge to its `width`, the advance.  Units are Hershey
 * units; the cap height of the Roman fonts is 21 of them and the baseline
 * is at y = 0.  Rather than trust those numbers for every font, the font
 * is measured when it is opened: the cap height is the height of its 'H'
 * and the baseline the bottom of it.
 *
 * Finding room: the text's bounding rectangle, turned along the label's
 * direction and grown by the clearance, must not meet any path of the
 * piece (outline, holes, scores, engraves, kerfs, marks: "the walls"), and
 * its centre must lie inside the outline and outside every hole, and
 * outside every zone the room was given (laps, and where laps will lie)
 * unless the caller lets labels in.  Since the rectangle meets no wall,
 * the centre decides for all of it.
 * Candidate centres lie on rings around `near`, the nearest first, for
 * each height from the largest down.  The walls are cut into their
 * segments in a grid index and the outline is a prepared polygon, so that
 * a test looks only at what is near the candidate: a piece with many seams
 * takes many labels, each trying thousands of candidates when it finds no
 * room, and each must stay quick (allow_room keeps all this from one label
 * to the next).
 */
#include "allow_internal.h"

#include <geos_c.h>
#include <hersheyfont.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

#define DEFAULT_FONT "rowmans"
#define FONT_PACKAGE "hershey-fonts-data"

/* The cap height and baseline of the Roman Hershey fonts, for a font with no 'H'. */
#define HERSHEY_CAP_HEIGHT 21.0
#define HERSHEY_BASELINE 0.0

/* Each smaller height tried is this fraction of the one before (until min_height). */
#define HEIGHT_STEP 0.8

struct ur_font {
    struct hershey_font *hershey;
    double cap_height; /* font units */
    double baseline;   /* font units */
    char name[72];     /* for messages */
};

/* ---- The font ------------------------------------------------------------ */

/*
 * Font names are file names under the system's font directory: refusing
 * anything but letters, digits, '_' and '-' keeps a name from reaching
 * another directory, and the length bound from overflowing the library's
 * path buffer.
 */
static bool font_name_is_plain(const char *name)
{
    size_t length = strlen(name);
    if (length == 0 || length > 64)
        return false;
    for (size_t i = 0; i < length; i++) {
        char c = name[i];
        bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                     c == '_' || c == '-';
        if (!plain)
            return false;
    }
    return true;
}

/* Cap height and baseline from the font's own 'H'. */
static void measure_font(ur_font *font)
{
    font->cap_height = HERSHEY_CAP_HEIGHT;
    font->baseline = HERSHEY_BASELINE;
    const struct hershey_glyph *glyph = hershey_font_glyph(font->hershey, 'H');
    double low = INFINITY, high = -INFINITY;
    for (const struct hershey_path *path = glyph ? glyph->paths : NULL; path; path = path->next)
        for (unsigned i = 0; i < path->nverts; i++) {
            low = fmin(low, path->verts[i].y);
            high = fmax(high, path->verts[i].y);
        }
    if (high > low) {
        font->cap_height = high - low;
        font->baseline = low;
    }
}

ur_status ur_font_open(const char *name, ur_font **font, ur_error *error)
{
    *font = NULL;
    if (!name)
        name = DEFAULT_FONT;
    if (!font_name_is_plain(name))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "font '%.64s' is not a Hershey font name such as '" DEFAULT_FONT "'",
                            name);
    ur_font *opened = calloc(1, sizeof *opened);
    if (!opened)
        return ur_error_out_of_memory(error);
    opened->hershey = hershey_font_load(name);
    if (!opened->hershey) {
        free(opened);
        return ur_error_set(
            error, UR_ERROR_INPUT,
            "Hershey font '%s' could not be loaded: the fonts (such as '" DEFAULT_FONT
            "') come with the package " FONT_PACKAGE,
            name);
    }
    measure_font(opened);
    c_snprintf(opened->name, sizeof opened->name, "%s", name);
    *font = opened;
    return UR_OK;
}

void ur_font_close(ur_font *font)
{
    if (!font)
        return;
    hershey_font_free(font->hershey);
    free(font);
}

/* The glyph for text[at]; an error saying where when it is not printable ASCII the font has. */
static ur_status text_glyph(const ur_font *font, const char *text, size_t at,
                            const struct hershey_glyph **glyph, ur_error *error)
{
    unsigned char c = (unsigned char)text[at];
    *glyph = c >= 32 && c <= 126 ? hershey_font_glyph(font->hershey, c) : NULL;
    /* A glyph the font lacks comes back with neither width nor strokes. */
    if (!*glyph || ((*glyph)->width == 0 && (*glyph)->npaths == 0))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "label '%.*s...': character %zu (code %u) is not printable ASCII that "
                            "font '%s' has",
                            (int)(at < 64 ? at : 64), text, at + 1, (unsigned)c, font->name);
    return UR_OK;
}

/* How many strokes text has; checks every character on the way. */
static ur_status count_strokes(const ur_font *font, const char *text, size_t *count,
                               ur_error *error)
{
    *count = 0;
    for (size_t at = 0; text[at]; at++) {
        const struct hershey_glyph *glyph;
        ur_status status = text_glyph(font, text, at, &glyph, error);
        if (status != UR_OK)
            return status;
        for (const struct hershey_path *path = glyph->paths; path; path = path->next)
            if (path->nverts > 0)
                (*count)++;
    }
    return UR_OK;
}

/* One glyph stroke, moved right by advance and scaled to millimetres. */
static ur_status glyph_stroke(const ur_font *font, const struct hershey_path *stroke,
                              double advance, double scale, ur_path *path, ur_error *error)
{
    path->op = UR_OP_ENGRAVE;
    path->closed = false;
    path->points = ur_alloc_array(stroke->nverts, sizeof *path->points, error);
    if (!path->points)
        return UR_ERROR_MEMORY;
    for (unsigned i = 0; i < stroke->nverts; i++)
        path->points[i] = ur_vec2_make((advance + stroke->verts[i].x) * scale,
                                       (stroke->verts[i].y - font->baseline) * scale);
    path->count = stroke->nverts;
    path->circle = (ur_path_circle){{0, 0}, 0, 0};
    return UR_OK;
}

ur_status ur_text_strokes(const ur_font *font, const char *text, double height, ur_path **paths,
                          size_t *count, double *width, ur_error *error)
{
    *paths = NULL;
    *count = 0;
    *width = 0;
    if (!font || !text || !isfinite(height) || height <= 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "text strokes need a font, a text and a positive height");
    size_t total;
    ur_status status = count_strokes(font, text, &total, error);
    if (status != UR_OK)
        return status;
    ur_path *out = ur_alloc_array(total, sizeof *out, error);
    if (!out)
        return UR_ERROR_MEMORY;
    double scale = height / font->cap_height, advance = 0;
    size_t made = 0;
    for (size_t at = 0; status == UR_OK && text[at]; at++) {
        const struct hershey_glyph *glyph =
            hershey_font_glyph(font->hershey, (unsigned char)text[at]);
        for (const struct hershey_path *p = glyph->paths; status == UR_OK && p; p = p->next)
            if (p->nverts > 0)
                status = glyph_stroke(font, p, advance, scale, &out[made++], error);
        advance += glyph->width;
    }
    if (status != UR_OK) {
        ur_paths_free(out, made);
        return status;
    }
    *paths = out;
    *count = total;
    *width = advance * scale;
    return UR_OK;
}

/* ---- Where the piece has room ------------------------------------------- */

/* One segment of a path (a path of one point: a segment of length 0). */
typedef struct wall {
    ur_vec2 from, to;
    bool fold; /* part of a fold line (a score, mountain or valley) */
    bool zone; /* the edge of a zone kept free of labels */
} wall;

/*
 * How many of the walls that stopped boxes lately are tried before a
 * query: the candidates alternate between the two sides of a ring, so
 * each side's last one must be among them.
 */
#define RECENT_WALLS 4

/*
 * What a cell of the walls' grid is known to be.  A cell that no wall
 * meets lies wholly on one side of the outline and of every hole (they are
 * walls), so that its centre answers for every point in it.
 */
typedef enum cell_state {
    CELL_UNTESTED,
    CELL_WALLED, /* a wall meets it: each point must be tested */
    CELL_ON_MATERIAL,
    CELL_OFF_MATERIAL
} cell_state;

/* A label engraved through the room: its text's box. */
typedef struct label_box {
    ur_vec2 centre, along, up;
    double a, b; /* half sizes along and up */
} label_box;

/* What a label search needs of the piece, built once and kept while labels go on. */
struct allow_room {
    GEOSContextHandle_t geos;
    ur_piece *piece;
    allow_grid wall_grid; /* the walls: the segments of every path of the piece when opened */
    wall *walls;          /* the grid's items */
    size_t recent[RECENT_WALLS]; /* walls that stopped boxes lately, the latest first */
    size_t recent_count;
    unsigned char *cells; /* a cell_state per cell of the walls' grid */
    allow_grid labels;    /* the boxes of the labels engraved since */
    label_box *boxes;     /* the grid's items */
    size_t box_capacity;
    GEOSGeometry *outline; /* paths[0] as a polygon, and prepared */
    const GEOSPreparedGeometry *outline_fast;
    size_t *holes; /* the paths that are holes */
    size_t hole_count;
    size_t zones_from; /* the closed marks from this path on are zones kept free of labels */
    size_t *zones;     /* those paths */
    size_t zone_count;
    ur_box outline_box;
    allow_items found; /* what a query of the labels found */
    bool cross_folds;  /* labels may cross the fold lines */
    allow_zone_rule zone_rule;
};

/* How many walls a path makes (a closed one runs back to its start). */
static size_t walls_of_path(const ur_path *path)
{
    size_t n = path->count;
    return n == 0 ? 0 : n == 1 ? 1 : n - 1 + (path->closed && n > 2 ? 1 : 0);
}

static bool is_zone(const allow_room *r, size_t i)
{
    const ur_path *path = &r->piece->paths[i];
    return i >= r->zones_from && path->op == UR_OP_MARK && path->closed && path->count >= 3;
}

/* The walls of every path, in order. */
static size_t collect_walls(const allow_room *r, wall *walls)
{
    size_t count = 0;
    for (size_t i = 0; i < r->piece->path_count; i++) {
        const ur_path *path = &r->piece->paths[i];
        bool fold = path->op == UR_OP_SCORE || path->op == UR_OP_SCORE_VALLEY;
        bool zone = is_zone(r, i);
        for (size_t k = 0, made = walls_of_path(path); k < made; k++)
            walls[count++] =
                (wall){path->points[k], path->points[(k + 1) % path->count], fold, zone};
    }
    return count;
}

/*
 * The walls in a grid whose cells are about as wide as a wall is long, or
 * wider where the walls are many short ones (a curve's chords): a cell for
 * about every wall.  A cell then lists a few walls, however fine the
 * mesh (the folds of a 100,000-face net are walls too), and a label's box
 * meets a few cells.
 */
static ur_status index_walls(allow_room *r, ur_error *error)
{
    size_t total = 0;
    for (size_t i = 0; i < r->piece->path_count; i++)
        total += walls_of_path(&r->piece->paths[i]);
    r->walls = ur_alloc_array(total ? total : 1, sizeof *r->walls, error);
    if (!r->walls)
        return UR_ERROR_MEMORY;
    size_t count = collect_walls(r, r->walls);
    double length = 0;
    for (size_t k = 0; k < count; k++)
        length += ur_vec2_length(ur_vec2_sub(r->walls[k].to, r->walls[k].from));
    ur_box region = r->piece->box;
    double walls = (double)(count ? count : 1);
    double cell = fmax(length / walls, sqrt(ur_box_width(region) * ur_box_height(region) / walls));
    cell = fmax(cell, 1e-3);
    ur_status status = allow_grid_init(&r->wall_grid, region, cell, error);
    for (size_t k = 0; status == UR_OK && k < count; k++) {
        ur_box box = ur_box_empty();
        ur_box_add(&box, r->walls[k].from);
        ur_box_add(&box, r->walls[k].to);
        status = allow_grid_add(&r->wall_grid, box, NULL, error);
    }
    if (status == UR_OK) {
        /* Untested, all of them: a cell is tested when a label first needs it. */
        r->cells = calloc(r->wall_grid.columns * r->wall_grid.rows, sizeof *r->cells);
        if (!r->cells)
            status = ur_error_out_of_memory(error);
    }
    return status;
}

void allow_room_close(allow_room *r)
{
    if (!r)
        return;
    allow_grid_free(&r->wall_grid);
    free(r->walls);
    free(r->cells);
    free(r->boxes);
    allow_grid_free(&r->labels);
    if (r->outline_fast)
        GEOSPreparedGeom_destroy_r(r->geos, r->outline_fast);
    if (r->outline)
        GEOSGeom_destroy_r(r->geos, r->outline);
    free(r->holes);
    free(r->zones);
    allow_items_free(&r->found);
    if (r->geos)
        GEOS_finish_r(r->geos);
    free(r);
}

/*
 * The paths that are holes (a closed through cut drops out with what it
 * encloses) and those that are zones.
 */
static ur_status find_holes(allow_room *r, ur_error *error)
{
    const ur_piece *piece = r->piece;
    r->holes = ur_alloc_array(piece->path_count, sizeof *r->holes, error);
    r->zones = r->holes ? ur_alloc_array(piece->path_count, sizeof *r->zones, error) : NULL;
    if (!r->zones)
        return UR_ERROR_MEMORY;
    for (size_t i = 1; i < piece->path_count; i++) {
        const ur_path *path = &piece->paths[i];
        if (path->closed && path->count >= 3 && (path->op == UR_OP_CUT || path->op == UR_OP_KERF))
            r->holes[r->hole_count++] = i;
        if (is_zone(r, i))
            r->zones[r->zone_count++] = i;
    }
    return UR_OK;
}

ur_status allow_room_open(ur_piece *piece, size_t zones_from, allow_room **room, ur_error *error)
{
    *room = NULL;
    allow_room *r = calloc(1, sizeof *r);
    if (!r)
        return ur_error_out_of_memory(error);
    r->piece = piece;
    r->zones_from = zones_from;
    r->outline_box = ur_box_of_points(piece->paths[0].points, piece->paths[0].count);
    r->geos = GEOS_init_r();
    ur_status status =
        r->geos ? UR_OK : ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not start");
    if (status == UR_OK)
        status = index_walls(r, error);
    ur_box region = piece->box;
    double size = fmax(ur_box_width(region), ur_box_height(region));
    if (status == UR_OK)
        status = allow_grid_init(&r->labels, region, fmax(size / 64, 1e-3), error);
    if (status == UR_OK) {
        r->outline = geos_polygon_of_ring(r->geos, piece->paths[0].points, piece->paths[0].count);
        r->outline_fast = r->outline ? GEOSPrepare_r(r->geos, r->outline) : NULL;
        if (!r->outline_fast)
            status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not prepare piece '%s'",
                                  piece->name);
    }
    if (status == UR_OK)
        status = find_holes(r, error);
    if (status != UR_OK) {
        allow_room_close(r);
        return status;
    }
    *room = r;
    return UR_OK;
}

/* Whether p is inside the ring (even-odd crossings; the ring's last point is not repeated). */
static bool inside_ring(const ur_vec2 *ring, size_t n, ur_vec2 p)
{
    bool inside = false;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        ur_vec2 a = ring[i], b = ring[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
            inside = !inside;
    }
    return inside;
}

/* Whether p falls where material stays: inside the outline, in no hole. */
static ur_status on_material(allow_room *r, ur_vec2 p, bool *inside, ur_error *error)
{
    GEOSGeometry *point = GEOSGeom_createPointFromXY_r(r->geos, p.x, p.y);
    char contained = point ? GEOSPreparedContains_r(r->geos, r->outline_fast, point) : 2;
    if (point)
        GEOSGeom_destroy_r(r->geos, point);
    if (contained == 2)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS failed testing a label on piece '%s'",
                            r->piece->name);
    *inside = contained == 1;
    for (size_t i = 0; *inside && i < r->hole_count; i++) {
        const ur_path *hole = &r->piece->paths[r->holes[i]];
        if (inside_ring(hole->points, hole->count, p))
            *inside = false;
    }
    return UR_OK;
}

/* What the cell of the walls' grid that p falls in is known to be (tested the first time). */
static ur_status material_of_cell(allow_room *r, ur_vec2 p, cell_state *state, ur_error *error)
{
    size_t cell = allow_grid_cell_of(&r->wall_grid, p);
    if (r->cells[cell] == CELL_UNTESTED && !allow_grid_cell_is_empty(&r->wall_grid, cell))
        r->cells[cell] = CELL_WALLED;
    if (r->cells[cell] == CELL_UNTESTED) {
        bool inside;
        ur_status status =
            on_material(r, allow_grid_cell_centre(&r->wall_grid, cell), &inside, error);
        if (status != UR_OK)
            return status;
        r->cells[cell] = inside ? CELL_ON_MATERIAL : CELL_OFF_MATERIAL;
    }
    *state = r->cells[cell];
    return UR_OK;
}

/* A label's frame: where its box's centre goes and which way its baseline runs. */
typedef struct frame {
    ur_vec2 centre, along, up; /* up is along turned a quarter left */
} frame;

static ur_vec2 frame_apply(const frame *f, double u, double v)
{
    return ur_vec2_add_scaled(ur_vec2_add_scaled(f->centre, f->along, u), f->up, v);
}

/* The squared distance from the point (u, v) to the rectangle [-a, a] x [-b, b]. */
static double point_to_box(double u, double v, double a, double b)
{
    double du = fmax(fabs(u) - a, 0.0), dv = fmax(fabs(v) - b, 0.0);
    return du * du + dv * dv;
}

/* Whether the segment from p to q (frame coordinates) crosses the rectangle [-a, a] x [-b, b]. */
static bool segment_crosses_box(ur_vec2 p, ur_vec2 q, double a, double b)
{
    double t0 = 0.0, t1 = 1.0;
    double d[2] = {q.x - p.x, q.y - p.y}, start[2] = {p.x, p.y}, half[2] = {a, b};
    for (int axis = 0; axis < 2; axis++) {
        if (d[axis] == 0) {
            if (fabs(start[axis]) > half[axis])
                return false;
            continue;
        }
        double ta = (-half[axis] - start[axis]) / d[axis],
               tb = (half[axis] - start[axis]) / d[axis];
        t0 = fmax(t0, fmin(ta, tb));
        t1 = fmin(t1, fmax(ta, tb));
        if (t0 > t1)
            return false;
    }
    return true;
}

/*
 * Whether the segment from p to q (piece coordinates) comes within
 * clearance of the label's box (half sizes a, b in frame f).
 */
static bool segment_near_box(const frame *f, double a, double b, double clearance, ur_vec2 p,
                             ur_vec2 q)
{
    ur_vec2 dp = ur_vec2_sub(p, f->centre), dq = ur_vec2_sub(q, f->centre);
    ur_vec2 u = ur_vec2_make(ur_vec2_dot(dp, f->along), ur_vec2_dot(dp, f->up));
    ur_vec2 v = ur_vec2_make(ur_vec2_dot(dq, f->along), ur_vec2_dot(dq, f->up));
    double reach = clearance * clearance; /* squared distances: no square roots */
    if (point_to_box(u.x, u.y, a, b) <= reach || point_to_box(v.x, v.y, a, b) <= reach ||
        segment_crosses_box(u, v, a, b))
        return true;
    static const int sign[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    for (int k = 0; k < 4; k++)
        if (allow_distance2_to_segment(ur_vec2_make(sign[k][0] * a, sign[k][1] * b), u, v) <= reach)
            return true;
    return false;
}

void allow_room_cross_folds(allow_room *room, bool cross)
{
    room->cross_folds = cross;
}

void allow_room_zone_rule(allow_room *room, allow_zone_rule rule)
{
    room->zone_rule = rule;
}

bool allow_room_has_zones(const allow_room *room)
{
    return room->zone_count > 0;
}

/*
 * Whether a label must keep clear of the wall: any but a fold, when labels
 * may cross folds, or a zone's edge, when labels may cross those.
 */
static bool stops(const allow_room *r, const wall *w)
{
    return !(w->fold && r->cross_folds) && !(w->zone && r->zone_rule == ALLOW_ZONES_CROSSED);
}

/* Makes stopper the latest of the recent walls. */
static void remember_wall(allow_room *r, size_t stopper)
{
    size_t at = 0;
    while (at < r->recent_count && r->recent[at] != stopper)
        at++;
    if (at == r->recent_count && r->recent_count < RECENT_WALLS)
        r->recent_count++;
    if (at == RECENT_WALLS)
        at--;
    for (; at > 0; at--)
        r->recent[at] = r->recent[at - 1];
    r->recent[0] = stopper;
}

/* A label's box being tested against the walls of a room. */
typedef struct wall_test {
    allow_room *r;
    const frame *f;
    double a, b, clearance;
} wall_test;

static bool wall_meets(size_t item, void *data)
{
    const wall_test *t = data;
    const wall *w = &t->r->walls[item];
    return stops(t->r, w) && segment_near_box(t->f, t->a, t->b, t->clearance, w->from, w->to);
}

/* Remembers the wall that stops a box, for the next boxes to try first. */
static bool wall_stops(size_t item, void *data)
{
    if (!wall_meets(item, data))
        return false;
    remember_wall(((wall_test *)data)->r, item);
    return true;
}

/*
 * Whether the box (half sizes a, b in frame f) comes within clearance of a
 * wall whose box meets `around`.  The walls that stopped boxes lately go
 * first: candidates come along rings, and most are stopped by a wall that
 * stopped one of the last few, which then needs no query; a query stops
 * at the first wall that meets the box (a label's box on a fine mesh's
 * net meets a hundred folds).  Whichever wall is tried first, the answer
 * is the same.
 */
static bool meets_wall(allow_room *r, const frame *f, double a, double b, double clearance,
                       ur_box around)
{
    wall_test test = {r, f, a, b, clearance};
    for (size_t k = 0; k < r->recent_count; k++)
        if (allow_boxes_meet(r->wall_grid.boxes[r->recent[k]], around) &&
            wall_meets(r->recent[k], &test))
            return true;
    return allow_grid_any(&r->wall_grid, around, wall_stops, &test);
}

/* The corners of a label's box, counter-clockwise. */
static void box_corners(const label_box *box, ur_vec2 corners[4])
{
    static const int sign[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; k++)
        corners[k] =
            ur_vec2_add_scaled(ur_vec2_add_scaled(box->centre, box->along, sign[k][0] * box->a),
                               box->up, sign[k][1] * box->b);
}

/* Whether the point lies in the label's box. */
static bool in_box(const label_box *box, ur_vec2 p)
{
    ur_vec2 d = ur_vec2_sub(p, box->centre);
    return fabs(ur_vec2_dot(d, box->along)) <= box->a && fabs(ur_vec2_dot(d, box->up)) <= box->b;
}

/* Whether the box (half sizes a, b in frame f) comes within clearance of a label engraved since. */
static ur_status meets_label(allow_room *r, const frame *f, double a, double b, double clearance,
                             ur_box around, bool *meets, ur_error *error)
{
    *meets = false;
    ur_status status = allow_grid_query(&r->labels, around, &r->found, error);
    for (size_t k = 0; status == UR_OK && !*meets && k < r->found.count; k++) {
        const label_box *other = &r->boxes[r->found.items[k]];
        ur_vec2 corners[4];
        box_corners(other, corners);
        *meets = in_box(other, f->centre);
        for (int i = 0; !*meets && i < 4; i++)
            *meets = segment_near_box(f, a, b, clearance, corners[i], corners[(i + 1) % 4]);
    }
    return status;
}

/* The box of the label's box grown by clearance, in piece coordinates. */
static ur_box box_around(const frame *f, double a, double b, double clearance)
{
    double half_x = fabs(f->along.x) * a + fabs(f->up.x) * b + clearance;
    double half_y = fabs(f->along.y) * a + fabs(f->up.y) * b + clearance;
    ur_box box = {{f->centre.x - half_x, f->centre.y - half_y},
                  {f->centre.x + half_x, f->centre.y + half_y}};
    return box;
}

/*
 * Whether the box fits: within the outline's box, no wall within
 * clearance of it and no label engraved since within a word's space, on
 * material.  Only the walls and labels near the box are tested (their
 * grids find them), each segment by its exact distance from the box.
 *
 * Most candidates of a search that finds no room fall in a cell of the
 * walls' grid that no wall meets, and its state says at once whether the
 * centre is on material.  Rounding may put a centre in the cell beside
 * its own, a hair from it; a wall between the two would then be within a
 * hair of the centre, and the box fails on that wall anyway.  So the
 * cell's answer is the exact one whenever it matters: a centre off
 * material fails before any wall is tested, one on material needs no
 * test of the outline.
 */
static ur_status box_fits(allow_room *r, const frame *f, double a, double b, double clearance,
                          bool *fits, ur_error *error)
{
    ur_box box = box_around(f, a, b, clearance);
    *fits = false;
    /* The cheap test first: most candidates far from the piece stop here. */
    if (box.min.x < r->outline_box.min.x || box.min.y < r->outline_box.min.y ||
        box.max.x > r->outline_box.max.x || box.max.y > r->outline_box.max.y)
        return UR_OK;
    cell_state state;
    ur_status status = material_of_cell(r, f->centre, &state, error);
    if (status != UR_OK || state == CELL_OFF_MATERIAL)
        return status;
    bool meets = meets_wall(r, f, a, b, clearance, box);
    /*
     * Between two labels at least a word's space, half their height (b):
     * labels of short seams side by side closer than that read as one
     * ("A16A15A12").
     */
    double apart = fmax(clearance, b);
    if (!meets)
        status = meets_label(r, f, a, b, apart, box_around(f, a, b, apart), &meets, error);
    if (status != UR_OK || meets)
        return status;
    /* Meeting no wall, the whole box is on one side of each: its centre tells which. */
    *fits = true;
    if (state != CELL_ON_MATERIAL)
        status = on_material(r, f->centre, fits, error);
    bool kept_out = r->zone_rule == ALLOW_ZONES_KEPT_OUT;
    for (size_t k = 0; status == UR_OK && *fits && kept_out && k < r->zone_count; k++) {
        const ur_path *zone = &r->piece->paths[r->zones[k]];
        *fits = !inside_ring(zone->points, zone->count, f->centre);
    }
    return status;
}

/* ---- The search ------------------------------------------------------------ */

/* The text at unit cap height: its strokes and their extents. */
typedef struct unit_text {
    ur_path *strokes;
    size_t count;
    ur_box extent; /* of the stroke points */
} unit_text;

/* What one search tries: a height, a ring of radii, what it must clear. */
typedef struct search {
    allow_room *r;
    const unit_text *text;
    ur_vec2 near, along;
    double clearance;
    double reach; /* the farthest from near a centre may be */
} search;

/* The distance from one ring of candidates to the next: finer near the start. */
static double ring_step(double radius, double height)
{
    return fmax(0.5 * height, 0.15 * radius);
}

/*
 * Tries centres on rings around near with radii in [from, to), each ring
 * starting across the baseline (the quickest way off an edge along it) and
 * alternating sides; *found says whether one fitted, f then holds it.
 */
static ur_status search_rings(const search *s, double height, double from, double to, frame *f,
                              bool *found, ur_error *error)
{
    double a = 0.5 * height * ur_box_width(s->text->extent);
    double b = 0.5 * height * ur_box_height(s->text->extent);
    f->along = s->along;
    f->up = ur_vec2_make(-s->along.y, s->along.x);
    *found = false;
    for (double radius = from; radius < to; radius += ring_step(radius, height)) {
        size_t n = radius > 0 ? (size_t)ceil(2 * M_PI * radius / ring_step(radius, height)) : 1;
        if (n < 6 && radius > 0)
            n = 6;
        for (size_t k = 0; k < n; k++) {
            /* 0, +1, -1, +2, -2 ... steps around from across the baseline */
            double turn = (double)((k + 1) / 2) * (k % 2 ? 1 : -1) * 2 * M_PI / (double)n;
            ur_vec2 offset = ur_vec2_add_scaled(ur_vec2_scale(f->up, cos(turn) * radius), f->along,
                                                sin(turn) * radius);
            f->centre = ur_vec2_add(s->near, offset);
            ur_status status = box_fits(s->r, f, a, b, s->clearance, found, error);
            if (status != UR_OK || *found)
                return status;
        }
    }
    return UR_OK;
}

/* How far from near a label still counts as near it: about its own length. */
static double near_radius(const search *s, double height)
{
    return height * (ur_box_width(s->text->extent) + 2) + 2 * s->clearance;
}

/* The farthest any centre on the piece can be from near. */
static double far_radius(const search *s)
{
    ur_box box = s->r->outline_box;
    double dx = fmax(fabs(box.min.x - s->near.x), fabs(box.max.x - s->near.x));
    double dy = fmax(fabs(box.min.y - s->near.y), fabs(box.max.y - s->near.y));
    return fmin(hypot(dx, dy) + 1e-9, s->reach);
}

/*
 * Near first, each height from the largest down; then, as a last resort,
 * the rest of the piece, again from the largest height down (not across
 * folds: a label far from its seam and over folds would be hard to tell
 * from the lines round it).  *height is the one that fitted.
 */
static ur_status search_piece(const search *s, double max_height, double min_height, frame *f,
                              double *height, bool *found, ur_error *error)
{
    *found = false;
    for (int far = 0; far < (s->r->cross_folds ? 1 : 2); far++) {
        for (double h = max_height;; h = fmax(min_height, h * HEIGHT_STEP)) {
            double from = far ? near_radius(s, h) : 0;
            double to = far ? far_radius(s) : fmin(near_radius(s, h), s->reach);
            ur_status status = search_rings(s, h, from, to, f, found, error);
            if (status != UR_OK || *found) {
                *height = h;
                return status;
            }
            if (h <= min_height)
                break;
        }
    }
    return UR_OK;
}

/* ---- Engraving ---------------------------------------------------------- */

/* Takes back the paths added to piece since it had `count` of them and box `box`. */
static void undo_paths(ur_piece *piece, size_t count, ur_box box)
{
    for (size_t i = count; i < piece->path_count; i++)
        free(piece->paths[i].points);
    piece->path_count = count;
    piece->box = box;
}

/* Adds the text's strokes at height in frame f, and the record; all or nothing. */
static ur_status engrave(ur_piece *piece, const unit_text *text, const char *label, double height,
                         const frame *f, ur_error *error)
{
    size_t old_count = piece->path_count;
    ur_box old_box = piece->box;
    ur_vec2 middle = ur_vec2_make(0.5 * (text->extent.min.x + text->extent.max.x),
                                  0.5 * (text->extent.min.y + text->extent.max.y));
    ur_status status = UR_OK;
    for (size_t i = 0; status == UR_OK && i < text->count; i++) {
        const ur_path *stroke = &text->strokes[i];
        ur_vec2 *points = ur_alloc_array(stroke->count, sizeof *points, error);
        if (!points) {
            status = UR_ERROR_MEMORY;
            break;
        }
        for (size_t k = 0; k < stroke->count; k++)
            points[k] = frame_apply(f, height * (stroke->points[k].x - middle.x),
                                    height * (stroke->points[k].y - middle.y));
        status = ur_piece_add_path(piece, UR_OP_ENGRAVE, points, stroke->count, false, error);
        free(points);
    }
    ur_allowance_record record = {.kind = UR_ALLOWANCE_LABEL,
                                  .count = 1,
                                  .value = height,
                                  .limit = NAN,
                                  .where = f->centre,
                                  .warning = false,
                                  .first_path = old_count,
                                  .path_count = text->count,
                                  .direction = f->along};
    c_snprintf(record.reason, sizeof record.reason, "label '%.64s' %.3g mm high", label, height);
    if (status == UR_OK)
        status = ur_piece_record(piece, &record, error);
    if (status != UR_OK)
        undo_paths(piece, old_count, old_box);
    return status;
}

static ur_status check_label_arguments(const ur_piece *piece, const ur_font *font, const char *text,
                                       ur_vec2 near, ur_vec2 direction, double height,
                                       double min_height, double clearance, ur_error *error)
{
    if (!piece || !font || !text || !text[0])
        return ur_error_set(error, UR_ERROR_INPUT, "a label needs a piece, a font and a text");
    if (piece->path_count == 0 || piece->bridged || !piece->paths[0].closed ||
        piece->paths[0].count < 3)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "label '%.64s': piece '%s' has no closed outline (labels go on before "
                            "bridges)",
                            text, piece->name);
    if (!isfinite(height) || !isfinite(min_height) || min_height <= 0 || min_height > height)
        return ur_error_set(
            error, UR_ERROR_INPUT,
            "label '%.64s': heights must satisfy 0 < min_height (%g) <= height (%g)", text,
            min_height, height);
    if (!isfinite(clearance) || clearance < 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "label '%.64s': clearance %g mm must be 0 or more", text, clearance);
    if (!isfinite(near.x) || !isfinite(near.y) || !isfinite(direction.x) ||
        !isfinite(direction.y) || ur_vec2_length(direction) == 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "label '%.64s': its place and a nonzero direction must be finite",
                            text);
    return UR_OK;
}

/* The baseline's unit direction, turned half round if it would read upside down. */
static ur_vec2 reading_direction(ur_vec2 direction)
{
    ur_vec2 along = ur_vec2_scale(direction, 1 / ur_vec2_length(direction));
    if (along.x < 0 || (along.x == 0 && along.y < 0))
        along = ur_vec2_scale(along, -1);
    return along;
}

/* Keeps the label just engraved in the room, for the next labels to keep clear of. */
static ur_status remember_label(allow_room *r, const unit_text *text, double height, const frame *f,
                                ur_error *error)
{
    label_box box = {f->centre, f->along, f->up, 0.5 * height * ur_box_width(text->extent),
                     0.5 * height * ur_box_height(text->extent)};
    if (r->labels.count == r->box_capacity) {
        size_t capacity = r->box_capacity ? 2 * r->box_capacity : 16;
        label_box *boxes = realloc(r->boxes, capacity * sizeof *boxes);
        if (!boxes)
            return ur_error_out_of_memory(error);
        r->boxes = boxes;
        r->box_capacity = capacity;
    }
    r->boxes[r->labels.count] = box;
    return allow_grid_add(&r->labels, box_around(f, box.a, box.b, 0.0), NULL, error);
}

ur_status allow_room_add_label(allow_room *room, const ur_font *font, const char *text,
                               ur_vec2 near, ur_vec2 direction, double height, double min_height,
                               double clearance, double reach, bool *placed, ur_error *error)
{
    *placed = false;
    ur_piece *piece = room->piece;
    ur_status status = check_label_arguments(piece, font, text, near, direction, height, min_height,
                                             clearance, error);
    unit_text unit = {0};
    double width;
    if (status == UR_OK)
        status = ur_text_strokes(font, text, 1.0, &unit.strokes, &unit.count, &width, error);
    if (status != UR_OK)
        return status;
    unit.extent = ur_box_empty();
    for (size_t i = 0; i < unit.count; i++)
        for (size_t k = 0; k < unit.strokes[i].count; k++)
            ur_box_add(&unit.extent, unit.strokes[i].points[k]);
    search s = {room, &unit, near, reading_direction(direction), clearance, reach};
    frame f = {{0, 0}, {0, 0}, {0, 0}};
    double used = 0;
    /* A text of spaces only has nothing to engrave, nor room to find. */
    if (unit.count > 0)
        status = search_piece(&s, height, min_height, &f, &used, placed, error);
    if (status == UR_OK && *placed)
        status = engrave(piece, &unit, text, used, &f, error);
    if (status == UR_OK && *placed)
        status = remember_label(room, &unit, used, &f, error);
    if (status != UR_OK)
        *placed = false;
    ur_paths_free(unit.strokes, unit.count);
    return status;
}

ur_status ur_piece_add_label(ur_piece *piece, const ur_font *font, const char *text, ur_vec2 near,
                             ur_vec2 direction, double height, double min_height, double clearance,
                             bool *placed, ur_error *error)
{
    *placed = false;
    ur_status status = check_label_arguments(piece, font, text, near, direction, height, min_height,
                                             clearance, error);
    allow_room *room = NULL;
    if (status == UR_OK)
        status = allow_room_open(piece, SIZE_MAX, &room, error);
    if (status == UR_OK)
        status = allow_room_add_label(room, font, text, near, direction, height, min_height,
                                      clearance, INFINITY, placed, error);
    allow_room_close(room);
    return status;
}

/* Whether a baseline along d reads upside down: it runs leftward (or straight down). */
static bool upside_down(ur_vec2 d)
{
    const double level = 1e-12;
    return d.x < -level || (fabs(d.x) <= level && d.y < 0);
}

void ur_piece_turn_labels(ur_piece *piece, double angle)
{
    double c = cos(angle), s = sin(angle);
    for (size_t r = 0; r < piece->record_count; r++) {
        ur_allowance_record *record = &piece->records[r];
        if (record->kind != UR_ALLOWANCE_LABEL || record->path_count == 0)
            continue;
        ur_vec2 d = record->direction;
        if (!upside_down(ur_vec2_make(c * d.x - s * d.y, s * d.x + c * d.y)))
            continue;
        /* Half a turn about the centre keeps the label in the box it was given. */
        ur_vec2 centre = record->where;
        for (size_t k = record->first_path;
             k < record->first_path + record->path_count && k < piece->path_count; k++)
            for (size_t i = 0; i < piece->paths[k].count; i++) {
                ur_vec2 *p = &piece->paths[k].points[i];
                *p = ur_vec2_sub(ur_vec2_scale(centre, 2.0), *p);
            }
        record->direction = ur_vec2_scale(d, -1.0);
    }
}
