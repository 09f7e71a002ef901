/*
 * assembly.c: the assembly guide (--assembly): the model drawn from four
 * directions, every piece in its own colour with its name, and the seam
 * labels where the seams lie, so that a person holding a cut piece can find
 * where it goes and which edge to glue to which (Pepakura's 3D view, on
 * paper).  PNG through a cairo image, PDF through cairo's PDF surface.
 * The model is assembly_model.c's, the views assembly_view.c's; this file
 * labels and draws them.
 *
 * The views (assembly_view.c) look at the model from the corners of a
 * tetrahedron, so that every face of a convex model is seen, with hidden
 * faces removed and an exact test of what is in sight for the labels.
 *
 * Faces are lit by a light from the viewer's upper left and tinted with
 * their piece's colour (assembly_model.c: one hue a piece).  Shading
 * scales a colour toward black and the inside of an open mesh mixes it
 * with grey: neither changes its hue, so a piece keeps one hue everywhere.
 *
 * Labels never overlap: piece names go first (each piece named in every
 * view where enough of it is seen, and at least once), then the seam
 * labels not yet shown in an earlier view, then the rest; a label that has
 * no room at its point moves a little aside on a leader line, or is left
 * out.  The cut pieces carry every label: the guide shows where they are.
 */
#include "assembly.h"

#include <cairo-pdf.h>
#include <cairo.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../base/atomic.h"
#include "draw.h"
#include "png.h"
#include "../base/c_locale.h"

/* About 297 mm wide: A3's short side, A4 landscape at 70 %. */
static const double PDF_SCALE = 0.355;

/* Type sizes, pixels (a piece's name: NAME_SIZE). */
static const double TITLE_SIZE = 34, KEY_SIZE = 19, CAPTION_SIZE = 23, SEAM_SIZE = 15;

/* A piece is named in a view where this much of it (pixels^2) is seen. */
static const double NAME_MIN_AREA = 2500;

/* Faces smaller than this on the picture (pixels^2) are filled without antialiasing. */
static const double SMALL_FACE = 60;

/* A fold is drawn where it is this long on the picture (pixels). */
static const double FOLD_MIN_LENGTH = 7;

/* Rows of swatches in the key; the pieces that find no room there are told by their names alone. */
enum { SWATCH_ROWS = 2 };

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
    draw_set_font(cr, name ? NAME_SIZE : SEAM_SIZE, name);
}

/*
 * Places a label at its point, or a little aside (on a leader line) where
 * it covers no other label; false when it finds no room.
 */
static bool place_label(cairo_t *cr, const view *v, label_list *labels, label *l)
{
    label_font(cr, l->name);
    double size = l->name ? NAME_SIZE : SEAM_SIZE;
    double width = draw_text_width(cr, l->text) + (l->name ? 8 : 10);
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
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < m->piece_count; k++) {
        if (!named[k][index])
            continue;
        label l = {.name = true, .point = v->name_point[k]};
        c_snprintf(l.text, sizeof l.text, "%s", m->names[k]);
        place_label(cr, v, labels, &l);
    }
    double tolerance = 1e-4 * m->size;
    for (int pass = 0; pass < 2; pass++)
        for (size_t s = 0; s < m->seam_count; s++) {
            bool earlier = first_view[s] >= 0 && first_view[s] < index;
            if (earlier != (pass == 1) || first_view[s] == index)
                continue;
            ur_vec3 point = m->seams[s].point;
            ur_vec2 q = assembly_picture_point(v, m, point);
            if (!assembly_in_sight(v, q, assembly_depth(v, m, point), tolerance))
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
    bool front = assembly_faces_viewer(v, f);
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
    if (assembly_face_area(p) < SMALL_FACE) {
        /*
         * Small faces of a fine mesh, filled whole pixels at a time: they
         * meet without the hairline gaps antialiasing leaves, and a stroke
         * round each, which would close those, would cost more than the fill.
         */
        cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
        cairo_fill(cr);
        cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
    } else {
        cairo_set_line_width(cr,
                             0.8); /* the same colour round it closes the gaps of antialiasing */
        cairo_fill_preserve(cr);
        cairo_stroke(cr);
    }
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
        draw_line(cr, a.x, a.y, b.x, b.y);
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
        draw_line(cr, l->point.x, l->point.y, end.x, end.y);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        cairo_set_line_width(cr, 1.2);
        draw_line(cr, l->point.x, l->point.y, end.x, end.y);
        cairo_arc(cr, l->point.x, l->point.y, l->name ? 3.5 : 2.5, 0, 2 * M_PI);
        cairo_fill(cr);
    }
    double size = l->name ? NAME_SIZE : SEAM_SIZE;
    double baseline = l->centre.y + 0.36 * size;
    if (l->name) { /* bold on a white halo, over its own colour */
        double width = draw_text_width(cr, l->text);
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
    draw_show_text(cr, l->centre.x, baseline, ALIGN_CENTRE, l->text);
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
    draw_set_font(cr, CAPTION_SIZE, true);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    draw_show_text(cr, left + 14, top + CAPTION - 12, ALIGN_LEFT, v->camera.caption);
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
    draw_set_font(cr, TITLE_SIZE, true);
    c_snprintf(text, sizeof text, "%s%sassembly guide: %zu piece%s, %zu seam%s", title ? title : "",
               title ? ": " : "", m->pieces_drawn, m->pieces_drawn == 1 ? "" : "s", m->seam_count,
               m->seam_count == 1 ? "" : "s");
    draw_show_text(cr, MARGIN, MARGIN + TITLE_SIZE, ALIGN_LEFT, text);
    draw_set_font(cr, KEY_SIZE, false);
    c_snprintf(
        text, sizeof text,
        "Each piece has its own colour and its name. Edges with the same label are glued "
        "together (labels of %zu of the %zu seams have room here; the cut pieces carry all). "
        "Thick lines: cuts between pieces; thin: folds.",
        seams_shown, m->seam_count);
    draw_show_text(cr, MARGIN, MARGIN + TITLE_SIZE + 14 + KEY_SIZE, ALIGN_LEFT, text);
    double x = MARGIN, y = MARGIN + TITLE_SIZE + 2 * KEY_SIZE + 36;
    int row = 0;
    draw_set_font(cr, KEY_SIZE, true);
    for (size_t k = 0; k < m->piece_count; k++) {
        double width = draw_text_width(cr, m->names[k]);
        if (x + 26 + width > CANVAS_WIDTH - MARGIN - 60) {
            if (++row == SWATCH_ROWS) {
                cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
                draw_show_text(cr, x, y, ALIGN_LEFT, "...");
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
        draw_show_text(cr, x + 26, y, ALIGN_LEFT, m->names[k]);
        x += 26 + width + 22;
    }
}

typedef struct guide {
    model model;
    view views[VIEWS];
    const char *title;
    ur_context *context; /* the file is opened in it; NULL for none */
    ur_status status;    /* of drawing, which allocates the labels */
    ur_error *error;
} guide;

static void guide_free(guide *g)
{
    for (int v = 0; v < VIEWS; v++)
        assembly_view_free(&g->views[v]);
    assembly_model_free(&g->model);
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
        status = ur_error_set(error, draw_failure_status(cairo_status(cr)),
                              "drawing the assembly guide: %s",
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
    ur_status status = cairo_status(cr) == CAIRO_STATUS_SUCCESS
                           ? draw_guide(cr, g, error)
                           : ur_error_set(error, draw_failure_status(cairo_status(cr)),
                                          "cannot make a %d x %d picture: %s", CANVAS_WIDTH,
                                          CANVAS_HEIGHT, cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    cairo_surface_flush(surface);
    if (status == UR_OK)
        status = atomic_write(path, png_emit, surface, "assembly guide", g->context, error);
    cairo_surface_destroy(surface);
    return status;
}

static cairo_status_t pdf_write_bytes(void *stream, const unsigned char *data, unsigned int length)
{
    return fwrite(data, 1, length, stream) == length ? CAIRO_STATUS_SUCCESS
                                                     : CAIRO_STATUS_WRITE_ERROR;
}

/* An atomic_emitter: the guide as a one-page PDF, drawn straight into the stream. */
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
    g->status =
        cairo_status(cr) == CAIRO_STATUS_SUCCESS
            ? draw_guide(cr, g, g->error)
            : ur_error_set(g->error, draw_failure_status(cairo_status(cr)),
                           "cannot start a PDF: %s", cairo_status_to_string(cairo_status(cr)));
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
    ur_status status = atomic_write(path, pdf_emit, g, "assembly guide", g->context, error);
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
    g.context = options->context;
    ur_status status = assembly_model_build(nets, options, &g.model, error);
    if (status == UR_OK)
        status = assembly_views_prepare(g.views, &g.model, options->y_up, error);
    if (status == UR_OK)
        status = png ? write_png(path, &g, error) : write_pdf(path, &g, error);
    guide_free(&g);
    return status;
}
