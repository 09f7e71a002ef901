/*
 * png.c: the PNG preview behind writer.h (cairo): what a user looks at
 * before cutting (docs/design.md, section 6).
 *
 * Each sheet is one picture at the resolution asked for (1 mm on the
 * picture is a millimetre on the sheet at that dpi), white, its edge grey.
 * The pieces come first (writer.h's piece call): each triangle of a
 * flattened piece filled with the colour of its strain (the map of the
 * strain picture, draw.h, one scale for the whole layout, lightened so the
 * lines over it read), a development left white.  Then every path in its operation's colour, at
 * least one point wide so that hairlines show; then each piece's name on a white box, and a legend
 * (the operations drawn, with their layers' colours, the strain range, a scale bar) in the corner
 * it covers least.  Text and lines are sized in points of 1/96 inch, so they keep their size on
 * paper at any resolution.
 */
#include "writer.h"

#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw.h"
#include "png.h"
#include "../base/c_locale.h"

/* cairo's largest image side; more pixels than MAX_PIXELS (400 MB) are refused as well. */
enum { MAX_SIDE = 32767 };
static const double MAX_PIXELS = 1e8;

/* How much of the strain colour covers the white sheet. */
static const double FILL_ALPHA = 0.6;

/* Legend sizes, in points. */
enum { PAD = 8, INSET = 6, ROW = 16, SWATCH = 24, SCALE_LONGEST = 120 };

/* Where a piece's name goes, gathered while the pieces are filled. */
typedef struct png_label {
    const char *name;
    ur_vec2 at; /* pixels */
} png_label;

typedef struct png_sheet {
    FILE *file; /* the caller's */
    size_t index, count;
    const ur_sheet *sheet;
    const ur_machine *machine;
    double scale;      /* pixels per mm */
    double unit;       /* pixels per point */
    int width, height; /* pixels */
    double range;      /* largest |strain| of the placed pieces; 0 for none */
    cairo_surface_t *surface;
    cairo_t *cr;
    png_label *labels; /* owned, one per placement */
    size_t label_count;
    bool drawn[UR_OP_COUNT]; /* operations with paths on the sheet, for the legend */
} png_sheet;

static ur_vec2 to_pixels(const png_sheet *s, ur_vec2 point)
{
    return ur_vec2_make(point.x * s->scale, (s->sheet->height - point.y) * s->scale);
}

static int pixels(double millimetres, double dpi)
{
    return (int)fmax(1.0, round(millimetres * dpi / 25.4));
}

/* ---- Checks ------------------------------------------------------------- */

static ur_status check_size(const ur_sheet *sheet, size_t index, double dpi, ur_error *error)
{
    double width = round(sheet->width * dpi / 25.4), height = round(sheet->height * dpi / 25.4);
    if (width > MAX_SIDE || height > MAX_SIDE || width * height > MAX_PIXELS)
        return ur_error_set(
            error, UR_ERROR_INPUT,
            "at %g dpi sheet %zu (%g x %g mm) would be %.0f x %.0f pixels, more than "
            "a picture can have (%d a side, %.0f in all); use a lower resolution",
            dpi, index + 1, sheet->width, sheet->height, width, height, MAX_SIDE, MAX_PIXELS);
    return UR_OK;
}

/* The largest |strain| of every placed piece, so that all sheets share one scale. */
static ur_status strain_range(const write_job *job, double *range, ur_error *error)
{
    *range = 0;
    for (size_t s = 0; s < job->layout->sheet_count; s++) {
        const ur_sheet *sheet = &job->layout->sheets[s];
        for (size_t p = 0; p < sheet->placement_count; p++) {
            const ur_piece *piece = &job->pieces[sheet->placements[p].piece_index];
            const ur_shading *shading = &piece->shading;
            if (shading->count > 0 && (!shading->triangles || !shading->strain))
                return ur_error_set(error, UR_ERROR_INTERNAL,
                                    "piece '%s' has %zu shaded triangles but no data", piece->name,
                                    shading->count);
            for (size_t t = 0; t < shading->count; t++) {
                if (!isfinite(shading->strain[t]))
                    return ur_error_set(error, UR_ERROR_INTERNAL,
                                        "piece '%s' has a strain that is not a finite number",
                                        piece->name);
                *range = fmax(*range, fabs(shading->strain[t]));
            }
        }
    }
    return UR_OK;
}

static ur_status cairo_failed(const png_sheet *s, ur_error *error)
{
    return ur_error_set(error, draw_failure_status(cairo_status(s->cr)),
                        "cannot draw sheet %zu: %s", s->index + 1,
                        cairo_status_to_string(cairo_status(s->cr)));
}

/* ---- Sheet -------------------------------------------------------------- */

static void free_sheet(png_sheet *s)
{
    if (s->cr)
        cairo_destroy(s->cr);
    if (s->surface)
        cairo_surface_destroy(s->surface);
    free(s->labels);
    free(s);
}

static ur_status start_picture(png_sheet *s, ur_error *error)
{
    s->surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, s->width, s->height);
    s->cr = cairo_create(s->surface); /* an error object, never NULL */
    if (cairo_status(s->cr) != CAIRO_STATUS_SUCCESS)
        return cairo_failed(s, error);
    cairo_set_source_rgb(s->cr, 1, 1, 1);
    cairo_paint(s->cr);
    cairo_set_line_cap(s->cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(s->cr, CAIRO_LINE_JOIN_ROUND);
    return UR_OK;
}

static ur_status png_begin_sheet(void **state, void *document, FILE *file, size_t index,
                                 const write_job *job, ur_error *error)
{
    (void)document;
    *state = NULL;
    const ur_sheet *sheet = &job->layout->sheets[index];
    double dpi = job->options->dpi;
    ur_status status = check_size(sheet, index, dpi, error);
    for (int op = 0; status == UR_OK && op < UR_OP_COUNT; op++)
        status = style_check(job->machine, (ur_op)op, error);
    if (status != UR_OK)
        return status;
    png_sheet *s = calloc(1, sizeof *s);
    if (!s)
        return ur_error_out_of_memory(error);
    *s = (png_sheet){.file = file,
                     .index = index,
                     .count = job->layout->sheet_count,
                     .sheet = sheet,
                     .machine = job->machine,
                     .scale = dpi / 25.4,
                     .unit = dpi / 96,
                     .width = pixels(sheet->width, dpi),
                     .height = pixels(sheet->height, dpi)};
    status = strain_range(job, &s->range, error);
    if (status == UR_OK && sheet->placement_count > 0) {
        s->labels = ur_alloc_array(sheet->placement_count, sizeof *s->labels, error);
        if (!s->labels)
            status = UR_ERROR_MEMORY;
    }
    if (status == UR_OK)
        status = start_picture(s, error);
    if (status != UR_OK) {
        free_sheet(s);
        return status;
    }
    *state = s;
    return UR_OK;
}

/*
 * Each triangle filled without antialiasing, so that neighbours meet without
 * a light seam, and stroked one pixel wide in its own colour, so that pixels
 * on a shared edge belong to one of them rather than to neither.
 */
static void fill_strain(png_sheet *s, const ur_piece *piece, ur_transform2 transform)
{
    cairo_t *cr = s->cr;
    const ur_shading *shading = &piece->shading;
    if (shading->count == 0)
        return;
    cairo_push_group(cr);
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
    cairo_set_line_width(cr, 1.0);
    for (size_t t = 0; t < shading->count; t++) {
        for (int k = 0; k < 3; k++) {
            ur_vec2 corner = to_pixels(s, ur_transform2_apply(transform, shading->triangles[t][k]));
            cairo_line_to(cr, corner.x, corner.y);
        }
        cairo_close_path(cr);
        draw_strain_colour(cr, shading->strain[t], s->range);
        cairo_fill_preserve(cr);
        cairo_stroke(cr);
    }
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
    /* Lighter than the strain picture's, so that the lines drawn over it read. */
    cairo_pop_group_to_source(cr);
    cairo_paint_with_alpha(cr, FILL_ALPHA);
}

/* The middle of the piece's placed outline box: where its name goes. */
static ur_vec2 label_point(const png_sheet *s, const ur_piece *piece, ur_transform2 transform)
{
    ur_box box = ur_box_empty();
    const ur_path *outline = &piece->paths[0];
    for (size_t i = 0; i < outline->count; i++)
        ur_box_add(&box, to_pixels(s, ur_transform2_apply(transform, outline->points[i])));
    return ur_vec2_make((box.min.x + box.max.x) / 2, (box.min.y + box.max.y) / 2);
}

static ur_status png_piece(void *state, const ur_piece *piece, const ur_placement *placement,
                           ur_error *error)
{
    png_sheet *s = state;
    fill_strain(s, piece, placement->transform);
    if (piece->path_count > 0 && piece->paths[0].count > 0)
        s->labels[s->label_count++] =
            (png_label){piece->name, label_point(s, piece, placement->transform)};
    return cairo_status(s->cr) == CAIRO_STATUS_SUCCESS ? UR_OK : cairo_failed(s, error);
}

/* The operation's colour and dashes; at least a point wide so that hairlines show. */
static ur_status png_begin_layer(void *state, ur_op op, ur_error *error)
{
    png_sheet *s = state;
    const ur_op_style *style = &s->machine->styles[op];
    unsigned long rgb = style_rgb(style);
    cairo_set_source_rgb(s->cr, (rgb >> 16 & 0xFF) / 255.0, (rgb >> 8 & 0xFF) / 255.0,
                         (rgb & 0xFF) / 255.0);
    cairo_set_line_width(s->cr, fmax(style->line_width * s->scale, s->unit));
    double dashes[8];
    size_t count = style_dashes(style, dashes, 8);
    for (size_t i = 0; i < count; i++)
        dashes[i] *= s->scale;
    cairo_set_dash(s->cr, dashes, (int)count, 0);
    return cairo_status(s->cr) == CAIRO_STATUS_SUCCESS ? UR_OK : cairo_failed(s, error);
}

static ur_status png_path(void *state, ur_op op, const ur_vec2 *points, size_t count, bool closed,
                          const ur_path_circle *circle, ur_error *error)
{
    (void)circle; /* the points lie on it, within the flattening's tolerance */
    (void)error;
    png_sheet *s = state;
    s->drawn[op] = true;
    for (size_t i = 0; i < count; i++) {
        ur_vec2 point = to_pixels(s, points[i]);
        cairo_line_to(s->cr, point.x, point.y);
    }
    if (closed)
        cairo_close_path(s->cr);
    cairo_stroke(s->cr);
    return UR_OK;
}

/* ---- Labels and legend -------------------------------------------------- */

/* Each name on a white box so that it reads on any colour. */
static void draw_labels(png_sheet *s)
{
    cairo_t *cr = s->cr;
    double u = s->unit;
    cairo_set_dash(cr, NULL, 0, 0);
    draw_set_font(cr, 12 * u, true);
    for (size_t i = 0; i < s->label_count; i++) {
        const png_label *label = &s->labels[i];
        double width = draw_text_width(cr, label->name);
        cairo_rectangle(cr, label->at.x - width / 2 - 3 * u, label->at.y - 11 * u, width + 6 * u,
                        15 * u);
        cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
        cairo_fill(cr);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        draw_show_text(cr, label->at.x, label->at.y, ALIGN_CENTRE, label->name);
    }
}

typedef struct legend {
    double left, top, width, height, unit;
    char title[128];
    char strain[96];
    double scale_length; /* mm */
    char scale_label[32];
    int rows; /* operations listed */
} legend;

/* The texts and the box's size in pixels at unit pixels per point. */
static void measure_legend(png_sheet *s, double unit, legend *l)
{
    cairo_t *cr = s->cr;
    l->unit = unit;
    c_snprintf(l->title, sizeof l->title, "sheet %zu of %zu, %g \xc3\x97 %g mm", s->index + 1,
               s->count, s->sheet->width, s->sheet->height);
    if (s->range > 0)
        c_snprintf(l->strain, sizeof l->strain,
                   "fill: strain, blue \xe2\x88\x92%.3g%% to red +%.3g%%", 100 * s->range,
                   100 * s->range);
    else
        c_snprintf(l->strain, sizeof l->strain, "no strain on any piece");
    l->scale_length = draw_nice_below(SCALE_LONGEST * unit / s->scale);
    c_snprintf(l->scale_label, sizeof l->scale_label, "%g mm", l->scale_length);
    double width = fmax(draw_text_width_at(cr, l->title, 12, true),
                        draw_text_width_at(cr, l->strain, 11, false));
    width = fmax(width, l->scale_length * s->scale / unit + 6 +
                            draw_text_width_at(cr, l->scale_label, 11, false));
    l->rows = 0;
    for (int op = 0; op < UR_OP_COUNT; op++) {
        if (!s->drawn[op])
            continue;
        l->rows++;
        const ur_op_style *style = &s->machine->styles[op];
        width = fmax(
            width, SWATCH + 6 +
                       draw_text_width_at(
                           cr, style->layer[0] ? style->layer : ur_op_name((ur_op)op), 11, false));
    }
    l->width = (width + 2 * PAD) * unit;
    l->height = (2 * PAD + 14 + ROW * (l->rows + 1) + 12) * unit;
}

/* How much of the surroundings of the piece labels a legend box at (left, top) would hide. */
static double labels_covered(const void *context, double left, double top, double width,
                             double height)
{
    const png_sheet *s = context;
    double area = 0, around = 60 * s->unit;
    for (size_t i = 0; i < s->label_count; i++) {
        ur_vec2 at = s->labels[i].at;
        area += draw_overlap(left, left + width, at.x - around, at.x + around) *
                draw_overlap(top, top + height, at.y - around, at.y + around);
    }
    return area;
}

static void draw_operations(png_sheet *s, const legend *l, double *y)
{
    cairo_t *cr = s->cr;
    double u = l->unit, x = l->left + PAD * u;
    for (int op = 0; op < UR_OP_COUNT; op++) {
        if (!s->drawn[op])
            continue;
        const ur_op_style *style = &s->machine->styles[op];
        unsigned long rgb = style_rgb(style);
        cairo_set_source_rgb(cr, (rgb >> 16 & 0xFF) / 255.0, (rgb >> 8 & 0xFF) / 255.0,
                             (rgb & 0xFF) / 255.0);
        cairo_set_line_width(cr, 2 * u);
        draw_line(cr, x, *y - 4 * u, x + SWATCH * u, *y - 4 * u);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        draw_set_font(cr, 11 * u, false);
        draw_show_text(cr, x + (SWATCH + 6) * u, *y, ALIGN_LEFT,
                       style->layer[0] ? style->layer : ur_op_name((ur_op)op));
        *y += ROW * u;
    }
}

static void draw_legend(png_sheet *s)
{
    cairo_t *cr = s->cr;
    legend l;
    measure_legend(s, s->unit, &l);
    double room = fmin((s->width - 2 * INSET * s->unit) / l.width,
                       (s->height - 2 * INSET * s->unit) / l.height);
    if (room < 1) /* a small sheet: a smaller legend */
        measure_legend(s, s->unit * fmax(room, 0.25), &l);
    draw_legend_corner(s->width, s->height, INSET * l.unit, l.width, l.height, labels_covered, s,
                       &l.left, &l.top);
    double u = l.unit, x = l.left + PAD * u, y = l.top + (PAD + 12) * u;
    draw_legend_frame(cr, l.left, l.top, l.width, l.height, u);
    cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
    draw_set_font(cr, 12 * u, true);
    draw_show_text(cr, x, y, ALIGN_LEFT, l.title);
    y += ROW * u;
    draw_operations(s, &l, &y);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_set_font(cr, 11 * u, false);
    draw_show_text(cr, x, y, ALIGN_LEFT, l.strain);
    y += 6 * u;
    double length = l.scale_length * s->scale;
    cairo_rectangle(cr, x, y, length, 6 * u);
    cairo_fill(cr);
    draw_show_text(cr, x + length + 6 * u, y + 7 * u, ALIGN_LEFT, l.scale_label);
}

/* ---- Finishing ---------------------------------------------------------- */

static ur_status png_end_sheet(void *state, ur_error *error)
{
    png_sheet *s = state;
    draw_labels(s);
    draw_legend(s);
    /* The sheet's edge, so that a white sheet stands out on a white page. */
    cairo_rectangle(s->cr, 0.5, 0.5, s->width - 1, s->height - 1);
    cairo_set_source_rgb(s->cr, 0.7, 0.7, 0.7);
    cairo_set_line_width(s->cr, 1.0);
    cairo_stroke(s->cr);
    ur_status status = UR_OK;
    if (cairo_status(s->cr) != CAIRO_STATUS_SUCCESS)
        status = cairo_failed(s, error);
    cairo_surface_flush(s->surface);
    errno = 0;
    if (status == UR_OK && !png_emit(s->file, s->surface))
        status = ur_error_set(error, UR_ERROR_IO, "cannot write the PNG file: %s",
                              errno ? strerror(errno) : "write error");
    free_sheet(s);
    return status;
}

static void png_discard_sheet(void *state)
{
    free_sheet(state);
}

const format_writer png_writer = {
    .format = "PNG",
    .extension = "png",
    .begin_sheet = png_begin_sheet,
    .piece = png_piece,
    .begin_layer = png_begin_layer,
    .path = png_path,
    .end_sheet = png_end_sheet,
    .discard_sheet = png_discard_sheet,
};
