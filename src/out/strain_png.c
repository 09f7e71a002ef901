/*
 * strain_png.c: the sheets as PNG pictures (cairo) with every piece shaded
 * by its strain, for `--strain-png` (docs/design.md, section 6, Writers).
 *
 * Each picture is one sheet and nothing else, at the resolution asked for:
 * a 600 x 400 mm sheet at 96 dpi is 2268 x 1512 pixels, so a millimetre on
 * the picture is a millimetre on the sheet.  The pieces stand where the
 * layout puts them, each triangle of a flattened piece (ur_piece.shading)
 * filled with the colour of its strain, then the outlines and the names.
 *
 * The colour map is ColorBrewer's RdBu, diverging from white at no strain
 * to dark red for stretch and dark blue for compression.  From white
 * outwards every channel only falls, so lightness grows darker with |strain|
 * on both sides and the picture still reads printed in grey.  The scale is
 * symmetric, its ends the largest |strain| of all the pieces, so that every
 * sheet of a job uses the same colours for the same strain.  A development
 * has no strain (no shading): it stays white, and its label says so.
 *
 * The legend (colour bar in per cent, scale bar) has no room of its own,
 * since the picture is the sheet: it goes in the corner where it covers
 * the least of the pieces, on a white box.  Text and lines are sized in
 * points of 1/96 inch, so they keep their size on paper at any resolution.
 *
 * Like the cut files, the pictures are written atomically and all together:
 * every sheet to a temporary first, renamed into place only when all are
 * complete; on any error nothing is left behind.
 */
#include "unroll/out.h"

#include <cairo.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../base/atomic.h"
#include "draw.h"
#include "png.h"
#include "../base/c_locale.h"

/* Longest file name built; longer output names are refused, not cut off. */
enum { NAME_SIZE = 4096 };

/* cairo's largest image side; more pixels than MAX_PIXELS (400 MB) are refused as well. */
enum { MAX_SIDE = 32767 };
static const double MAX_PIXELS = 1e8;

/* Legend sizes, in points (pixels at 96 dpi). */
enum {
    PAD = 8,         /* inside the legend's box */
    INSET = 6,       /* between the box and the sheet's edge */
    BAR_WIDTH = 240, /* the colour bar */
    BAR_TOP = 28,    /* from the top of the box */
    BAR_HEIGHT = 14, /* its ticks hang 4 below, their numbers' baseline 16 below */
    CAPTION = 74,    /* baseline of the caption */
    SCALE_TOP = 84,  /* the scale bar, 6 tall */
    LEGEND_HEIGHT = 98,
    SCALE_LONGEST = 120, /* the scale bar is at most this long */
};

/* Five numbers under the colour bar: its ends, their halves and 0. */
enum { TICKS = 5 };

/* What every sheet shares. */
typedef struct picture {
    const ur_layout *layout;
    const ur_piece *pieces;
    size_t piece_count;
    double dpi;
    double range; /* largest |strain| of all pieces: the ends of the colour scale; 0 for none */
    ur_context *context; /* the files are opened in it; NULL for none */
} picture;

/* One sheet's image: sheet millimetres to pixels, y flipped. */
typedef struct canvas {
    const ur_sheet *sheet;
    size_t index;
    double scale;      /* pixels per millimetre */
    int width, height; /* pixels */
    double unit;       /* pixels per point */
} canvas;

static ur_vec2 to_pixels(const canvas *c, ur_vec2 sheet_point)
{
    return ur_vec2_make(sheet_point.x * c->scale, (c->sheet->height - sheet_point.y) * c->scale);
}

/* A piece point to pixels through its placement. */
static ur_vec2 place(const canvas *c, const ur_placement *placement, ur_vec2 point)
{
    return to_pixels(c, ur_transform2_apply(placement->transform, point));
}

/* ---- Checks ------------------------------------------------------------- */

static int pixels(double millimetres, double dpi)
{
    return (int)fmax(1.0, round(millimetres * dpi / 25.4));
}

static ur_status check_sheet(const ur_sheet *sheet, size_t index, const picture *p, ur_error *error)
{
    if (!(isfinite(sheet->width) && isfinite(sheet->height) && sheet->width > 0 &&
          sheet->height > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "sheet %zu has no usable size (%g x %g mm)",
                            index + 1, sheet->width, sheet->height);
    double width = round(sheet->width * p->dpi / 25.4),
           height = round(sheet->height * p->dpi / 25.4);
    if (width > MAX_SIDE || height > MAX_SIDE || width * height > MAX_PIXELS)
        return ur_error_set(
            error, UR_ERROR_INPUT,
            "at %g dpi sheet %zu (%g x %g mm) would be %.0f x %.0f pixels, more than "
            "a picture can have (%d a side, %.0f in all); use a lower resolution",
            p->dpi, index + 1, sheet->width, sheet->height, width, height, MAX_SIDE, MAX_PIXELS);
    if (sheet->placement_count > 0 && !sheet->placements)
        return ur_error_set(error, UR_ERROR_INTERNAL, "sheet %zu has no placements array",
                            index + 1);
    for (size_t i = 0; i < sheet->placement_count; i++)
        if (sheet->placements[i].piece_index >= p->piece_count)
            return ur_error_set(error, UR_ERROR_INTERNAL, "sheet %zu places piece %zu of only %zu",
                                index + 1, sheet->placements[i].piece_index + 1, p->piece_count);
    return UR_OK;
}

/* Every strain finite; the largest |strain| into p->range. */
static ur_status measure_strain(picture *p, ur_error *error)
{
    p->range = 0.0;
    for (size_t k = 0; k < p->piece_count; k++) {
        const ur_shading *shading = &p->pieces[k].shading;
        if (shading->count > 0 && (!shading->triangles || !shading->strain))
            return ur_error_set(error, UR_ERROR_INTERNAL,
                                "piece '%s' has %zu shaded triangles but no data",
                                p->pieces[k].name, shading->count);
        for (size_t t = 0; t < shading->count; t++) {
            if (!isfinite(shading->strain[t]))
                return ur_error_set(error, UR_ERROR_INTERNAL,
                                    "piece '%s' has a strain that is not a finite number",
                                    p->pieces[k].name);
            p->range = fmax(p->range, fabs(shading->strain[t]));
        }
    }
    return UR_OK;
}

static ur_status check_arguments(const char *path, const ur_layout *layout, const ur_piece *pieces,
                                 size_t piece_count, double dpi, ur_error *error)
{
    if (!path || !layout || (!pieces && piece_count > 0))
        return ur_error_set(error, UR_ERROR_INTERNAL, "strain picture writer called without %s",
                            !path     ? "an output path"
                            : !layout ? "a layout"
                                      : "pieces");
    if (layout->sheet_count == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': there is nothing to draw",
                            path);
    if (!layout->sheets)
        return ur_error_set(error, UR_ERROR_INTERNAL, "the layout has no sheets array");
    if (!(dpi > 0) || !isfinite(dpi))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the resolution of the strain picture must be a positive number of "
                            "dots per inch, not %g",
                            dpi);
    return UR_OK;
}

/* ---- Colour ------------------------------------------------------------- */

/* strain on the scale -range..range (draw.h). */
static void set_strain_colour(cairo_t *cr, double strain, double range)
{
    draw_strain_colour(cr, strain, range);
}

/* Strain as per cent with its sign: "+1.73%", "-0.5%", "0%". */
static void format_percent(double strain, char *text, size_t size)
{
    double percent = 100 * strain;
    if (fabs(percent) < 5e-7)
        c_snprintf(text, size, "0%%");
    else
        c_snprintf(text, size, "%+.3g%%", percent);
}

/* ---- Pieces ------------------------------------------------------------- */

/*
 * Each triangle filled without antialiasing, so that neighbours meet without
 * a light seam, and stroked one pixel wide in its own colour, so that pixels
 * on a shared edge belong to one of them rather than to neither.
 */
static void fill_triangles(cairo_t *cr, const canvas *c, const ur_placement *placement,
                           const ur_shading *shading, double range)
{
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
    cairo_set_line_width(cr, 1.0);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (size_t t = 0; t < shading->count; t++) {
        for (int k = 0; k < 3; k++) {
            ur_vec2 corner = place(c, placement, shading->triangles[t][k]);
            cairo_line_to(cr, corner.x, corner.y);
        }
        cairo_close_path(cr);
        set_strain_colour(cr, shading->strain[t], range);
        cairo_fill_preserve(cr);
        cairo_stroke(cr);
    }
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
}

/* Cut lines dark grey; the other operations (fold lines dashed) lighter and thinner. */
static void stroke_path(cairo_t *cr, const canvas *c, const ur_placement *placement,
                        const ur_path *path)
{
    for (size_t i = 0; i < path->count; i++) {
        ur_vec2 point = place(c, placement, path->points[i]);
        cairo_line_to(cr, point.x, point.y);
    }
    if (path->closed)
        cairo_close_path(cr);
    double dashes[2] = {4 * c->unit, 3 * c->unit};
    if (path->op == UR_OP_CUT) {
        cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
        cairo_set_line_width(cr, 1.2 * c->unit);
    } else {
        cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
        cairo_set_line_width(cr, 0.8 * c->unit);
        if (path->op == UR_OP_SCORE)
            cairo_set_dash(cr, dashes, 2, 0);
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/*
 * Where the label goes, in pixels: the middle of the longest run inside the
 * outline of the horizontal line through the middle of its box.  The box's
 * centre itself may lie outside a curved piece (an annular sector).
 * crossings has room for outline->count numbers.
 */
static ur_vec2 label_point(const canvas *c, const ur_placement *placement, const ur_path *outline,
                           double *crossings)
{
    ur_box box = ur_box_empty();
    for (size_t i = 0; i < outline->count; i++)
        ur_box_add(&box, place(c, placement, outline->points[i]));
    double y = (box.min.y + box.max.y) / 2;
    size_t count = 0;
    for (size_t i = 0; i < outline->count; i++) {
        ur_vec2 a = place(c, placement, outline->points[i]);
        ur_vec2 b = place(c, placement, outline->points[(i + 1) % outline->count]);
        if ((a.y > y) != (b.y > y))
            crossings[count++] = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
    }
    qsort(crossings, count, sizeof *crossings, compare_doubles);
    ur_vec2 best = ur_vec2_make((box.min.x + box.max.x) / 2, y);
    double longest = -1;
    for (size_t i = 0; i + 1 < count; i += 2)
        if (crossings[i + 1] - crossings[i] > longest) {
            longest = crossings[i + 1] - crossings[i];
            best.x = (crossings[i] + crossings[i + 1]) / 2;
        }
    return best;
}

/* The second line of a label: the piece's range of strain, or that it has none. */
static void strain_note(const ur_piece *piece, char *text, size_t size)
{
    if (piece->shading.count == 0) {
        c_snprintf(text, size, "exact: no strain");
        return;
    }
    double low = 0, high = 0;
    for (size_t t = 0; t < piece->shading.count; t++) {
        low = fmin(low, piece->shading.strain[t]);
        high = fmax(high, piece->shading.strain[t]);
    }
    char from[32], to[32];
    format_percent(low, from, sizeof from);
    format_percent(high, to, sizeof to);
    c_snprintf(text, size, "%s to %s", from, to);
}

/* The name, and the note below it, on a white box so that they read on any colour. */
static void draw_label(cairo_t *cr, const canvas *c, ur_vec2 at, const ur_piece *piece)
{
    char note[80];
    strain_note(piece, note, sizeof note);
    double u = c->unit;
    draw_set_font(cr, 10 * u, false);
    double width = draw_text_width(cr, note);
    draw_set_font(cr, 13 * u, true);
    width = fmax(width, draw_text_width(cr, piece->name));
    cairo_rectangle(cr, at.x - width / 2 - 3 * u, at.y - 15 * u, width + 6 * u, 30 * u);
    cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_show_text(cr, at.x, at.y - 2 * u, ALIGN_CENTRE, piece->name);
    draw_set_font(cr, 10 * u, false);
    draw_show_text(cr, at.x, at.y + 11 * u, ALIGN_CENTRE, note);
}

static ur_status draw_labels(cairo_t *cr, const canvas *c, const picture *p, ur_error *error)
{
    for (size_t i = 0; i < c->sheet->placement_count; i++) {
        const ur_placement *placement = &c->sheet->placements[i];
        const ur_piece *piece = &p->pieces[placement->piece_index];
        if (piece->path_count == 0 || piece->paths[0].count == 0)
            continue;
        double *crossings = ur_alloc_array(piece->paths[0].count, sizeof *crossings, error);
        if (!crossings)
            return UR_ERROR_MEMORY;
        draw_label(cr, c, label_point(c, placement, &piece->paths[0], crossings), piece);
        free(crossings);
    }
    return UR_OK;
}

static void draw_pieces(cairo_t *cr, const canvas *c, const picture *p)
{
    const ur_sheet *sheet = c->sheet;
    for (size_t i = 0; i < sheet->placement_count; i++) {
        const ur_placement *placement = &sheet->placements[i];
        fill_triangles(cr, c, placement, &p->pieces[placement->piece_index].shading, p->range);
    }
    for (size_t i = 0; i < sheet->placement_count; i++) {
        const ur_placement *placement = &sheet->placements[i];
        const ur_piece *piece = &p->pieces[placement->piece_index];
        for (size_t k = 0; k < piece->path_count; k++)
            stroke_path(cr, c, placement, &piece->paths[k]);
    }
}

/* ---- Legend ------------------------------------------------------------- */

/* The legend's box in pixels and what it says. */
typedef struct legend {
    double left, top, width, height;
    double unit; /* pixels per point inside the legend: smaller than the canvas's to fit a small
                    sheet */
    char title[96];
    char ticks[TICKS][32];
    double side; /* room left and right of the colour bar for the numbers at its ends, points */
    double scale_length; /* mm */
    char scale_label[32];
} legend;

static const char caption[] = "red: stretch \xcf\x83\xe2\x82\x81 \xe2\x88\x92 1   blue: "
                              "compression 1 \xe2\x88\x92 \xcf\x83\xe2\x82\x82";
static const char no_strain[] = "no strain on any piece";

/* The texts, and the box's size at unit pixels per point. */
static void measure_legend(cairo_t *cr, const canvas *c, const picture *p, double unit, legend *l)
{
    l->unit = unit;
    c_snprintf(l->title, sizeof l->title, "strain \xc2\xb7 sheet %zu of %zu, %g \xc3\x97 %g mm",
               c->index + 1, p->layout->sheet_count, c->sheet->width, c->sheet->height);
    double widest_tick = 0;
    for (int k = 0; k < TICKS; k++) {
        format_percent(p->range * (k - TICKS / 2) / (TICKS / 2), l->ticks[k], sizeof l->ticks[k]);
        widest_tick = fmax(widest_tick, draw_text_width_at(cr, l->ticks[k], 11, false));
    }
    l->side = widest_tick / 2 + 2;
    l->scale_length = draw_nice_below(SCALE_LONGEST * unit / c->scale);
    c_snprintf(l->scale_label, sizeof l->scale_label, "%g mm", l->scale_length);
    double scale_points = l->scale_length * c->scale / unit;
    double width = fmax(BAR_WIDTH + 2 * l->side, draw_text_width_at(cr, l->title, 12, true));
    width = fmax(width, draw_text_width_at(cr, p->range > 0 ? caption : no_strain, 11, false));
    width = fmax(width, scale_points + 6 + draw_text_width_at(cr, l->scale_label, 11, false));
    l->width = (width + 2 * PAD) * unit;
    l->height = LEGEND_HEIGHT * unit;
}

/* A sheet's picture, for working out what a legend box would hide. */
typedef struct sheet_picture {
    const canvas *canvas;
    const picture *picture;
} sheet_picture;

/* Pixels of a legend box at (left, top) that the placed pieces' boxes cover. */
static double pieces_covered(const void *context, double left, double top, double width,
                             double height)
{
    const sheet_picture *sheet = context;
    const canvas *c = sheet->canvas;
    double area = 0;
    for (size_t i = 0; i < c->sheet->placement_count; i++) {
        const ur_placement *placement = &c->sheet->placements[i];
        const ur_piece *piece = &sheet->picture->pieces[placement->piece_index];
        ur_box box = ur_box_empty();
        for (size_t k = 0; k < piece->path_count; k++)
            for (size_t j = 0; j < piece->paths[k].count; j++)
                ur_box_add(&box, place(c, placement, piece->paths[k].points[j]));
        area += draw_overlap(left, left + width, box.min.x, box.max.x) *
                draw_overlap(top, top + height, box.min.y, box.max.y);
    }
    return area;
}

/* Sized to the canvas's unit, smaller if the sheet is too small for that. */
static void fit_legend(cairo_t *cr, const canvas *c, const picture *p, legend *l)
{
    measure_legend(cr, c, p, c->unit, l);
    double room = fmin((c->width - 2 * INSET * c->unit) / l->width,
                       (c->height - 2 * INSET * c->unit) / l->height);
    if (room < 1)
        measure_legend(cr, c, p, c->unit * fmax(room, 0.25), l);
    sheet_picture sheet = {c, p};
    draw_legend_corner(c->width, c->height, INSET * l->unit, l->width, l->height, pieces_covered,
                       &sheet, &l->left, &l->top);
}

static void draw_colour_bar(cairo_t *cr, const legend *l, double range)
{
    double u = l->unit, x = l->left + (PAD + l->side) * u, y = l->top + BAR_TOP * u;
    double width = BAR_WIDTH * u, height = BAR_HEIGHT * u;
    int steps = (int)ceil(width);
    for (int i = 0; i < steps; i++) {
        set_strain_colour(cr, range * (2 * (i + 0.5) / steps - 1), range);
        cairo_rectangle(cr, x + width * i / steps, y, width / steps + 0.5, height);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cairo_set_line_width(cr, 0.8 * u);
    cairo_rectangle(cr, x, y, width, height);
    cairo_stroke(cr);
    draw_set_font(cr, 11 * u, false);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    for (int k = 0; k < TICKS; k++) {
        double at = x + width * k / (TICKS - 1);
        draw_line(cr, at, y + height, at, y + height + 4 * u);
        draw_show_text(cr, at, y + height + 16 * u, ALIGN_CENTRE, l->ticks[k]);
    }
    draw_show_text(cr, l->left + PAD * u, l->top + CAPTION * u, ALIGN_LEFT, caption);
}

/* Nothing strained: a white swatch that says so. */
static void draw_no_strain(cairo_t *cr, const legend *l)
{
    double u = l->unit, x = l->left + PAD * u, y = l->top + BAR_TOP * u;
    cairo_rectangle(cr, x, y, 26 * u, BAR_HEIGHT * u);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    cairo_set_line_width(cr, 0.8 * u);
    cairo_stroke(cr);
    draw_set_font(cr, 11 * u, false);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_show_text(cr, x + 34 * u, y + 11 * u, ALIGN_LEFT, no_strain);
}

static void draw_scale_bar(cairo_t *cr, const canvas *c, const legend *l)
{
    double u = l->unit, x = l->left + PAD * u, y = l->top + SCALE_TOP * u;
    double length = l->scale_length * c->scale;
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_rectangle(cr, x, y, length, 6 * u);
    cairo_fill(cr);
    draw_set_font(cr, 11 * u, false);
    draw_show_text(cr, x + length + 6 * u, y + 7 * u, ALIGN_LEFT, l->scale_label);
}

static void draw_legend(cairo_t *cr, const canvas *c, const picture *p)
{
    legend l;
    fit_legend(cr, c, p, &l);
    double u = l.unit;
    draw_legend_frame(cr, l.left, l.top, l.width, l.height, u);
    draw_set_font(cr, 12 * u, true);
    cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
    draw_show_text(cr, l.left + PAD * u, l.top + 20 * u, ALIGN_LEFT, l.title);
    if (p->range > 0)
        draw_colour_bar(cr, &l, p->range);
    else
        draw_no_strain(cr, &l);
    draw_scale_bar(cr, c, &l);
}

/* ---- Sheets and files --------------------------------------------------- */

static ur_status render(cairo_t *cr, const canvas *c, const picture *p, ur_error *error)
{
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw_pieces(cr, c, p);
    ur_status status = draw_labels(cr, c, p, error);
    if (status != UR_OK)
        return status;
    draw_legend(cr, c, p);
    /* The sheet's edge, so that a white sheet stands out on a white page. */
    cairo_rectangle(cr, 0.5, 0.5, c->width - 1, c->height - 1);
    cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
    return UR_OK;
}

static ur_status cairo_failed(cairo_status_t cause, size_t index, ur_error *error)
{
    return ur_error_set(error, draw_failure_status(cause), "cannot draw sheet %zu: %s", index + 1,
                        cairo_status_to_string(cause));
}

/* Sheet index as a new image in *surface; the caller destroys it. */
static ur_status draw_sheet(const picture *p, size_t index, cairo_surface_t **surface,
                            ur_error *error)
{
    const ur_sheet *sheet = &p->layout->sheets[index];
    canvas c = {sheet,
                index,
                p->dpi / 25.4,
                pixels(sheet->width, p->dpi),
                pixels(sheet->height, p->dpi),
                p->dpi / 96};
    *surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, c.width, c.height);
    cairo_t *cr = cairo_create(*surface); /* an error object, never NULL */
    ur_status status = UR_OK;
    if (cairo_status(cr) != CAIRO_STATUS_SUCCESS)
        status = cairo_failed(cairo_status(cr), index, error);
    if (status == UR_OK)
        status = render(cr, &c, p, error);
    if (status == UR_OK && cairo_status(cr) != CAIRO_STATUS_SUCCESS)
        status = cairo_failed(cairo_status(cr), index, error);
    cairo_destroy(cr);
    if (status != UR_OK) {
        cairo_surface_destroy(*surface);
        *surface = NULL;
    }
    return status;
}

/* Sheet index drawn into a new temporary, files[index], closed but not yet renamed. */
static ur_status write_sheet_file(const char *path, const picture *p, size_t index,
                                  atomic_file *files, ur_error *error)
{
    char name[NAME_SIZE];
    ur_status status =
        ur_sheet_file_name(path, index, p->layout->sheet_count, name, sizeof name, error);
    if (status == UR_OK)
        status = atomic_open(&files[index], name, p->context, error);
    cairo_surface_t *surface = NULL;
    if (status == UR_OK)
        status = draw_sheet(p, index, &surface, error);
    errno = 0;
    if (status == UR_OK && !png_emit(files[index].stream, surface))
        status = ur_error_set(error, UR_ERROR_IO, "cannot write '%s': %s", name,
                              errno ? strerror(errno) : "write error");
    if (status == UR_OK)
        status = atomic_close(&files[index], error);
    if (surface)
        cairo_surface_destroy(surface);
    return status;
}

/* Every temporary first, then every rename, as output.c does for the cut files. */
static ur_status write_files(const char *path, const picture *p, ur_error *error)
{
    size_t count = p->layout->sheet_count;
    atomic_file *files = ur_alloc_array(count, sizeof *files, error);
    if (!files)
        return UR_ERROR_MEMORY;
    ur_status status = UR_OK;
    for (size_t i = 0; status == UR_OK && i < count; i++)
        status = write_sheet_file(path, p, i, files, error);
    if (status == UR_OK)
        status = atomic_commit_all(files, count, error);
    for (size_t i = 0; i < count; i++)
        atomic_discard(&files[i]); /* removes what was not committed */
    free(files);
    return status;
}

/* One sheet to standard output. */
static ur_status write_stdout(const picture *p, ur_error *error)
{
    if (p->layout->sheet_count != 1)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "cannot write the %zu sheets of the strain picture to standard output",
                            p->layout->sheet_count);
    cairo_surface_t *surface = NULL;
    ur_status status = draw_sheet(p, 0, &surface, error);
    if (status == UR_OK)
        status = atomic_write("-", png_emit, surface, "strain picture", p->context, error);
    if (surface)
        cairo_surface_destroy(surface);
    return status;
}

ur_status ur_strain_png_write(const char *path, const ur_layout *layout, const ur_piece *pieces,
                              size_t piece_count, double dpi, ur_context *context, ur_error *error)
{
    if (dpi == 0)
        dpi = UR_STRAIN_PNG_DPI;
    ur_status status = check_arguments(path, layout, pieces, piece_count, dpi, error);
    if (status != UR_OK)
        return status;
    picture p = {layout, pieces, piece_count, dpi, 0.0, context};
    for (size_t i = 0; status == UR_OK && i < layout->sheet_count; i++)
        status = check_sheet(&layout->sheets[i], i, &p, error);
    if (status == UR_OK)
        status = measure_strain(&p, error);
    if (status != UR_OK)
        return status;
    return strcmp(path, "-") == 0 ? write_stdout(&p, error) : write_files(path, &p, error);
}
