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
 * piece (outline, holes, scores, engraves, kerfs, marks: one prepared GEOS
 * multi-linestring, "the walls"), and its centre must lie inside the
 * outline and outside every hole.  Since the rectangle meets no wall, the
 * centre decides for all of it.  Candidate centres lie on rings around
 * `near`, the nearest first, for each height from the largest down.
 */
#include "unroll/allow.h"

#include <geos_c.h>
#include <hersheyfont.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_FONT "rowmans"
#define FONT_PACKAGE "hershey-fonts-data"

/* The cap height and baseline of the Roman Hershey fonts, for a font with no 'H'. */
#define HERSHEY_CAP_HEIGHT 21.0
#define HERSHEY_BASELINE 0.0

/* Each smaller height tried is this fraction of the one before (until min_height). */
#define HEIGHT_STEP 0.8

/* Segments per quarter circle in the rounded corners of the grown rectangle. */
#define CORNER_SEGMENTS 4

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
    snprintf(opened->name, sizeof opened->name, "%s", name);
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

/* ---- Text as strokes ---------------------------------------------------- */

void ur_paths_free(ur_path *paths, size_t count)
{
    if (!paths)
        return;
    for (size_t i = 0; i < count; i++)
        free(paths[i].points);
    free(paths);
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
        return UR_ERROR_INTERNAL;
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
        return UR_ERROR_INTERNAL;
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

/* What a label search needs of the piece, built once per call. */
typedef struct room {
    GEOSContextHandle_t geos;
    GEOSGeometry *walls;              /* every path of the piece as lines */
    const GEOSPreparedGeometry *fast; /* the walls, prepared */
    ur_box outline_box;
    const ur_piece *piece;
} room;

/* A GEOS line string along points (a closed path comes back to its start), or NULL. */
static GEOSGeometry *path_line(GEOSContextHandle_t geos, const ur_path *path)
{
    /* A line string needs two points: a lone point becomes a line of length 0. */
    size_t n = path->count, total = n + (path->closed && n > 2 ? 1 : 0);
    if (total < 2)
        total = 2;
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)total, 2);
    if (!sequence)
        return NULL;
    for (size_t i = 0; i < total; i++) {
        ur_vec2 p = path->points[i < n ? i : i % n];
        if (!GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, p.x, p.y)) {
            GEOSCoordSeq_destroy_r(geos, sequence);
            return NULL;
        }
    }
    return GEOSGeom_createLineString_r(geos, sequence);
}

/* The walls: one multi-linestring of every path with points. */
static GEOSGeometry *piece_walls(GEOSContextHandle_t geos, const ur_piece *piece, ur_error *error)
{
    GEOSGeometry **lines = ur_alloc_array(piece->path_count, sizeof *lines, error);
    if (!lines)
        return NULL;
    size_t n = 0;
    bool failed = false;
    for (size_t i = 0; i < piece->path_count && !failed; i++) {
        if (piece->paths[i].count == 0)
            continue;
        lines[n] = path_line(geos, &piece->paths[i]);
        failed = !lines[n++];
    }
    GEOSGeometry *walls =
        failed ? NULL : GEOSGeom_createCollection_r(geos, GEOS_MULTILINESTRING, lines, (unsigned)n);
    if (!walls) {
        for (size_t i = 0; i < n; i++)
            if (lines[i])
                GEOSGeom_destroy_r(geos, lines[i]);
        ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not build the paths of piece '%s'",
                     piece->name);
    }
    free(lines); /* the collection owns the lines, not the array */
    return walls;
}

static void room_free(room *r)
{
    if (r->fast)
        GEOSPreparedGeom_destroy_r(r->geos, r->fast);
    if (r->walls)
        GEOSGeom_destroy_r(r->geos, r->walls);
    if (r->geos)
        GEOS_finish_r(r->geos);
}

static ur_status room_init(room *r, const ur_piece *piece, ur_error *error)
{
    memset(r, 0, sizeof *r);
    r->piece = piece;
    r->outline_box = ur_box_of_points(piece->paths[0].points, piece->paths[0].count);
    r->geos = GEOS_init_r();
    if (!r->geos)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not start");
    r->walls = piece_walls(r->geos, piece, error);
    if (!r->walls)
        return UR_ERROR_INTERNAL;
    r->fast = GEOSPrepare_r(r->geos, r->walls);
    if (!r->fast)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not prepare piece '%s'",
                            piece->name);
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
static bool on_material(const ur_piece *piece, ur_vec2 p)
{
    if (!inside_ring(piece->paths[0].points, piece->paths[0].count, p))
        return false;
    for (size_t i = 1; i < piece->path_count; i++) {
        const ur_path *path = &piece->paths[i];
        /* A closed through cut drops out with what it encloses. */
        bool hole =
            path->closed && path->count >= 3 && (path->op == UR_OP_CUT || path->op == UR_OP_KERF);
        if (hole && inside_ring(path->points, path->count, p))
            return false;
    }
    return true;
}

/* A label's frame: where its box's centre goes and which way its baseline runs. */
typedef struct frame {
    ur_vec2 centre, along, up; /* up is along turned a quarter left */
} frame;

static ur_vec2 frame_apply(const frame *f, double u, double v)
{
    return ur_vec2_add_scaled(ur_vec2_add_scaled(f->centre, f->along, u), f->up, v);
}

enum { SHAPE_POINTS = 4 * (CORNER_SEGMENTS + 1) + 1 };

/*
 * The text's box (half sizes a, b about its centre) grown by clearance with
 * rounded corners, as a closed ring of SHAPE_POINTS points.  The corner
 * radius is enlarged so that the chords of each arc, not only its points,
 * stay clearance away from the box.
 */
static void grown_box(const frame *f, double a, double b, double clearance, ur_vec2 *ring)
{
    const double quarter = M_PI / 2, step = quarter / CORNER_SEGMENTS;
    double radius = clearance / cos(step / 2);
    static const int sign[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
    size_t n = 0;
    for (int corner = 0; corner < 4; corner++)
        for (int k = 0; k <= CORNER_SEGMENTS; k++) {
            double angle = corner * quarter + k * step;
            ring[n++] = frame_apply(f, sign[corner][0] * a + radius * cos(angle),
                                    sign[corner][1] * b + radius * sin(angle));
        }
    ring[n] = ring[0];
}

/* Whether the grown box fits: within the outline's box, meeting no wall, on material. */
static ur_status box_fits(const room *r, const frame *f, double a, double b, double clearance,
                          bool *fits, ur_error *error)
{
    ur_vec2 ring[SHAPE_POINTS];
    grown_box(f, a, b, clearance, ring);
    ur_box box = ur_box_of_points(ring, SHAPE_POINTS);
    *fits = false;
    /* The cheap test first: most candidates far from the piece stop here. */
    if (box.min.x < r->outline_box.min.x || box.min.y < r->outline_box.min.y ||
        box.max.x > r->outline_box.max.x || box.max.y > r->outline_box.max.y)
        return UR_OK;
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(r->geos, SHAPE_POINTS, 2);
    for (unsigned i = 0; sequence && i < SHAPE_POINTS; i++)
        GEOSCoordSeq_setXY_r(r->geos, sequence, i, ring[i].x, ring[i].y);
    GEOSGeometry *shell = sequence ? GEOSGeom_createLinearRing_r(r->geos, sequence) : NULL;
    GEOSGeometry *polygon = shell ? GEOSGeom_createPolygon_r(r->geos, shell, NULL, 0) : NULL;
    if (!polygon) {
        if (shell)
            GEOSGeom_destroy_r(r->geos, shell);
        else if (sequence)
            GEOSCoordSeq_destroy_r(r->geos, sequence);
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not build a label's box");
    }
    char meets = GEOSPreparedIntersects_r(r->geos, r->fast, polygon);
    GEOSGeom_destroy_r(r->geos, polygon);
    if (meets == 2)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS failed testing a label on piece '%s'",
                            r->piece->name);
    /* Meeting no wall, the whole box is on one side of each: its centre tells which. */
    *fits = !meets && on_material(r->piece, f->centre);
    return UR_OK;
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
    const room *r;
    const unit_text *text;
    ur_vec2 near, along;
    double clearance;
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
    return hypot(dx, dy) + 1e-9;
}

/*
 * Near first, each height from the largest down; then, as a last resort,
 * the rest of the piece, again from the largest height down.  *height is
 * the one that fitted.
 */
static ur_status search_piece(const search *s, double max_height, double min_height, frame *f,
                              double *height, bool *found, ur_error *error)
{
    *found = false;
    for (int far = 0; far < 2; far++) {
        for (double h = max_height;; h = fmax(min_height, h * HEIGHT_STEP)) {
            double from = far ? near_radius(s, h) : 0;
            double to = far ? far_radius(s) : near_radius(s, h);
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
            status = UR_ERROR_INTERNAL;
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
    snprintf(record.reason, sizeof record.reason, "label '%.64s' %.3g mm high", label, height);
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

ur_status ur_piece_add_label(ur_piece *piece, const ur_font *font, const char *text, ur_vec2 near,
                             ur_vec2 direction, double height, double min_height, double clearance,
                             bool *placed, ur_error *error)
{
    *placed = false;
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
    room r;
    status = room_init(&r, piece, error);
    search s = {&r, &unit, near, reading_direction(direction), clearance};
    frame f = {{0, 0}, {0, 0}, {0, 0}};
    double used = 0;
    /* A text of spaces only has nothing to engrave, nor room to find. */
    if (status == UR_OK && unit.count > 0)
        status = search_piece(&s, height, min_height, &f, &used, placed, error);
    room_free(&r);
    if (status == UR_OK && *placed)
        status = engrave(piece, &unit, text, used, &f, error);
    if (status != UR_OK)
        *placed = false;
    ur_paths_free(unit.strokes, unit.count);
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
