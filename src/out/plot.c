/*
 * plot.c: the comparison of the discrete methods with the exact net
 * (ur_compare) as a PNG plot, drawn with cairo, and as CSV.
 *
 * The plot has two log-log panels against the number of parts n: the
 * relative area error of each method, and how far the boundary of each
 * discrete net lies from the exact one.  Errors span many decades and the
 * exact method's may be exactly zero, so every value is drawn no lower than
 * PLOT_FLOOR, and the plot says so.  Both files are written atomically
 * (atomic.h): on error nothing is left behind and an existing file stays.
 */
#include "unroll/out.h"

#include "../base/atomic.h"
#include "draw.h"
#include "png.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "../base/c_locale.h"

#define PLOT_FLOOR 1e-16

enum { WIDTH = 900, HEIGHT = 600, MAX_Y_LABELS = 9 };

typedef enum quantity { AREA, DISTANCE } quantity;

/* Method k of a row (UR_COMPARE_TRIANGLE, ...): name, colour, marker. */
static const char *const method_names[UR_COMPARE_METHODS] = {"triangle", "quad", "exact"};
static const double method_colours[UR_COMPARE_METHODS][3] = {
    {0.84, 0.15, 0.16}, /* red */
    {0.12, 0.47, 0.71}, /* blue */
    {0.17, 0.63, 0.17}, /* green */
};

/* A panel: its rectangle in pixels and its ranges in log10 units. */
typedef struct panel {
    double left, right, top, bottom;
    double x_low, x_high, y_low, y_high;
} panel;

/* ---- Data --------------------------------------------------------------- */

/* The value drawn for method k, or NAN when there is none. */
static double plotted(const ur_compare_row *row, quantity what, int k)
{
    if (!row->available[k] || (what == DISTANCE && k == UR_COMPARE_EXACT))
        return NAN; /* the exact net's distance to itself is zero by definition */
    double value = what == AREA ? fabs(row->area_error[k]) : row->distance[k];
    return isfinite(value) ? fmax(value, PLOT_FLOOR) : NAN;
}

/* Whole decades around the values, at least one decade tall. */
static void y_range(const ur_compare_table *table, quantity what, panel *p)
{
    double low = INFINITY, high = -INFINITY;
    for (size_t r = 0; r < table->count; r++)
        for (int k = 0; k < UR_COMPARE_METHODS; k++) {
            double value = plotted(&table->rows[r], what, k);
            if (isfinite(value)) {
                low = fmin(low, log10(value));
                high = fmax(high, log10(value));
            }
        }
    if (!isfinite(low)) { /* nothing to draw: any decade will do */
        low = -1;
        high = 0;
    }
    p->y_low = floor(low);
    p->y_high = ceil(high);
    if (p->y_high - p->y_low < 1)
        p->y_high = p->y_low + 1;
}

/* From a little below the smallest n to a little above the largest. */
static void x_range(const ur_compare_table *table, panel *p)
{
    double low = log10((double)table->rows[0].n);
    double high = log10((double)table->rows[table->count - 1].n);
    double pad = fmax(0.08 * (high - low), 0.15);
    p->x_low = low - pad;
    p->x_high = high + pad;
}

static double to_x(const panel *p, double value)
{
    return p->left + (log10(value) - p->x_low) / (p->x_high - p->x_low) * (p->right - p->left);
}

static double to_y(const panel *p, double value)
{
    return p->bottom - (log10(value) - p->y_low) / (p->y_high - p->y_low) * (p->bottom - p->top);
}

/* ---- Text --------------------------------------------------------------- */

/* "10" with the exponent raised, as a tick label. */
static void show_power(cairo_t *cr, double x, double y, text_align align, int exponent)
{
    char power[16];
    c_snprintf(power, sizeof power, "%d", exponent);
    draw_set_font(cr, 12, false);
    double base = draw_text_width(cr, "10");
    draw_set_font(cr, 9, false);
    double left = draw_left(x, base + draw_text_width(cr, power), align);
    draw_set_font(cr, 12, false);
    draw_show_text(cr, left, y, ALIGN_LEFT, "10");
    draw_set_font(cr, 9, false);
    draw_show_text(cr, left + base, y - 6, ALIGN_LEFT, power);
}

/* ---- Axes --------------------------------------------------------------- */

/* Light grid lines at the decades, short ticks at 2..9 times them. */
static void x_ticks(cairo_t *cr, const panel *p)
{
    cairo_set_line_width(cr, 1);
    for (int decade = (int)floor(p->x_low); decade <= (int)ceil(p->x_high); decade++)
        for (int m = 1; m <= 9; m++) {
            double value = m * pow(10, decade), x = to_x(p, value);
            if (x < p->left - 0.5 || x > p->right + 0.5)
                continue;
            if (m == 1) {
                cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
                draw_line(cr, x, p->top, x, p->bottom);
            }
            cairo_set_source_rgb(cr, 0, 0, 0);
            draw_line(cr, x, p->bottom, x, p->bottom + (m == 1 ? 6 : 3));
            if (m == 1)
                show_power(cr, x, p->bottom + 22, ALIGN_CENTRE, decade);
        }
}

static void y_ticks(cairo_t *cr, const panel *p)
{
    int decades = (int)(p->y_high - p->y_low);
    int step = (decades + MAX_Y_LABELS - 1) / MAX_Y_LABELS;
    cairo_set_line_width(cr, 1);
    for (int decade = (int)p->y_low; decade <= (int)p->y_high; decade++) {
        double y = to_y(p, pow(10, decade));
        cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
        draw_line(cr, p->left, y, p->right, y);
        cairo_set_source_rgb(cr, 0, 0, 0);
        draw_line(cr, p->left - 6, y, p->left, y);
        if ((decade - (int)p->y_low) % step == 0)
            show_power(cr, p->left - 9, y + 4, ALIGN_RIGHT, decade);
        for (int m = 2; step == 1 && decade < (int)p->y_high && m <= 9; m++) {
            double minor = to_y(p, m * pow(10, decade));
            draw_line(cr, p->left - 3, minor, p->left, minor);
        }
    }
}

static void axes(cairo_t *cr, const panel *p, const char *x_title, const char *y_title)
{
    x_ticks(cr, p);
    y_ticks(cr, p);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.2);
    cairo_rectangle(cr, p->left, p->top, p->right - p->left, p->bottom - p->top);
    cairo_stroke(cr);
    draw_set_font(cr, 13, false);
    draw_show_text(cr, (p->left + p->right) / 2, p->bottom + 44, ALIGN_CENTRE, x_title);
    cairo_save(cr);
    cairo_translate(cr, p->left - 52, (p->top + p->bottom) / 2);
    cairo_rotate(cr, -M_PI / 2);
    draw_show_text(cr, 0, 0, ALIGN_CENTRE, y_title);
    cairo_restore(cr);
}

/* ---- Series ------------------------------------------------------------- */

/* Triangle, square and circle markers, so the methods differ without colour too. */
static void marker(cairo_t *cr, int k, double x, double y)
{
    const double r = 4.5;
    if (k == UR_COMPARE_TRIANGLE) {
        cairo_move_to(cr, x, y - r * 1.2);
        cairo_line_to(cr, x + r * 1.1, y + r * 0.8);
        cairo_line_to(cr, x - r * 1.1, y + r * 0.8);
        cairo_close_path(cr);
    } else if (k == UR_COMPARE_QUAD) {
        cairo_rectangle(cr, x - r * 0.9, y - r * 0.9, r * 1.8, r * 1.8);
    } else {
        cairo_new_sub_path(cr);
        cairo_arc(cr, x, y, r, 0, 2 * M_PI);
    }
    cairo_fill(cr);
}

static void set_colour(cairo_t *cr, int k)
{
    cairo_set_source_rgb(cr, method_colours[k][0], method_colours[k][1], method_colours[k][2]);
}

static void series(cairo_t *cr, const panel *p, const ur_compare_table *table, quantity what, int k)
{
    set_colour(cr, k);
    cairo_set_line_width(cr, 2);
    bool drawing = false;
    for (size_t r = 0; r < table->count; r++) {
        double value = plotted(&table->rows[r], what, k);
        if (!isfinite(value)) {
            drawing = false; /* a gap in the data is a gap in the line */
            continue;
        }
        double x = to_x(p, (double)table->rows[r].n), y = to_y(p, value);
        if (drawing)
            cairo_line_to(cr, x, y);
        else
            cairo_move_to(cr, x, y);
        drawing = true;
    }
    cairo_stroke(cr);
    for (size_t r = 0; r < table->count; r++) {
        double value = plotted(&table->rows[r], what, k);
        if (isfinite(value))
            marker(cr, k, to_x(p, (double)table->rows[r].n), to_y(p, value));
    }
}

static bool method_drawn(const ur_compare_table *table, int k)
{
    for (size_t r = 0; r < table->count; r++)
        if (table->rows[r].available[k])
            return true;
    return false;
}

static void panel_plot(cairo_t *cr, const panel *p, const ur_compare_table *table, quantity what,
                       const char *y_title)
{
    axes(cr, p, "rulings n", y_title);
    cairo_save(cr);
    cairo_rectangle(cr, p->left, p->top, p->right - p->left, p->bottom - p->top);
    cairo_clip(cr);
    for (int k = 0; k < UR_COMPARE_METHODS; k++)
        series(cr, p, table, what, k);
    cairo_restore(cr);
}

/* ---- Legend and the whole picture --------------------------------------- */

static void legend(cairo_t *cr, const ur_compare_table *table, double y)
{
    double x = 85;
    draw_set_font(cr, 13, false);
    for (int k = 0; k < UR_COMPARE_METHODS; k++) {
        char label[64];
        bool drawn = method_drawn(table, k);
        c_snprintf(label, sizeof label, "%s%s", method_names[k],
                   !drawn                  ? " (not applicable)"
                   : k == UR_COMPARE_EXACT ? " (distance 0 by definition)"
                                           : "");
        if (drawn)
            set_colour(cr, k);
        else
            cairo_set_source_rgb(cr, 0.75, 0.75, 0.75); /* greyed out: no data */
        cairo_set_line_width(cr, 2);
        draw_line(cr, x, y - 4, x + 28, y - 4);
        marker(cr, k, x + 14, y - 4);
        cairo_set_source_rgb(cr, 0, 0, 0);
        draw_show_text(cr, x + 36, y, ALIGN_LEFT, label);
        x += 36 + draw_text_width(cr, label) + 30;
    }
    draw_set_font(cr, 11, false);
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    draw_show_text(
        cr, 85, y + 20, ALIGN_LEFT,
        "values below 1e-16 (and zeros) are drawn at 1e-16; distances after the best rigid "
        "fit to the exact net");
}

static void draw(cairo_t *cr, const ur_compare_table *table, const char *title)
{
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_set_font(cr, 18, true);
    draw_show_text(cr, WIDTH / 2.0, 32, ALIGN_CENTRE, title ? title : "unroll compare");
    panel area = {85, 435, 60, 480, 0, 0, 0, 0};
    panel distance = {535, 885, 60, 480, 0, 0, 0, 0};
    x_range(table, &area);
    x_range(table, &distance);
    y_range(table, AREA, &area);
    y_range(table, DISTANCE, &distance);
    panel_plot(cr, &area, table, AREA, "|relative area error|");
    panel_plot(cr, &distance, table, DISTANCE, "largest distance to the exact net, mm");
    legend(cr, table, 560);
}

/* ---- Writing ------------------------------------------------------------ */

/* A table with rows of increasing n, as ur_compare makes them. */
static ur_status check_table(const ur_compare_table *table, ur_error *error)
{
    if (!table || table->count == 0 || !table->rows)
        return ur_error_set(error, UR_ERROR_INTERNAL, "the comparison has no rows");
    for (size_t r = 0; r < table->count; r++)
        if (table->rows[r].n < 1 || (r > 0 && table->rows[r].n <= table->rows[r - 1].n))
            return ur_error_set(error, UR_ERROR_INTERNAL,
                                "the comparison's rows are not in increasing n");
    return UR_OK;
}

ur_status ur_compare_plot_png(const char *path, const ur_compare_table *table, const char *title,
                              ur_context *context, ur_error *error)
{
    if (!path)
        return ur_error_set(error, UR_ERROR_INTERNAL, "the plot writer was called without a path");
    ur_status status = check_table(table, error);
    if (status != UR_OK)
        return status;
    cairo_surface_t *surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, WIDTH, HEIGHT);
    cairo_t *cr = cairo_create(surface); /* a cairo error gives an inert context, never NULL */
    draw(cr, table, title);
    cairo_status_t drawn = cairo_status(cr);
    cairo_destroy(cr);
    if (drawn == CAIRO_STATUS_SUCCESS)
        drawn = cairo_surface_status(surface);
    if (drawn != CAIRO_STATUS_SUCCESS)
        status = ur_error_set(error, draw_failure_status(drawn), "cannot draw the plot: %s",
                              cairo_status_to_string(drawn));
    else
        status = atomic_write(path, png_emit, surface, "plot", context, error);
    cairo_surface_destroy(surface);
    return status;
}

/* ---- CSV ---------------------------------------------------------------- */

/* One field: the number to full precision, or empty where there is none. */
static bool emit_number(FILE *stream, double value, bool available, bool last)
{
    int written = available && isfinite(value) ? c_fprintf(stream, "%.17g", value) : 0;
    return written >= 0 && fputc(last ? '\n' : ',', stream) != EOF;
}

static bool emit_row(FILE *stream, const ur_compare_row *row)
{
    const double *columns[] = {row->area_error, row->edge_error, row->distance};
    bool ok = c_fprintf(stream, "%zu,", row->n) >= 0;
    for (int c = 0; ok && c < 3; c++) {
        int methods = c == 2 ? UR_COMPARE_EXACT : UR_COMPARE_METHODS; /* no exact distance */
        for (int k = 0; ok && k < methods; k++)
            ok = emit_number(stream, columns[c][k], row->available[k], c == 2 && k == methods - 1);
    }
    return ok;
}

static bool emit_csv(FILE *stream, const void *data)
{
    const ur_compare_table *table = data;
    bool ok = fputs("n,triangle_area_error,quad_area_error,exact_area_error,"
                    "triangle_edge_error,quad_edge_error,exact_edge_error,"
                    "triangle_distance,quad_distance\n",
                    stream) != EOF;
    for (size_t r = 0; ok && r < table->count; r++)
        ok = emit_row(stream, &table->rows[r]);
    return ok;
}

ur_status ur_compare_csv_write(const char *path, const ur_compare_table *table, ur_context *context,
                               ur_error *error)
{
    if (!path)
        return ur_error_set(error, UR_ERROR_INTERNAL, "the CSV writer was called without a path");
    ur_status status = check_table(table, error);
    if (status != UR_OK)
        return status;
    return atomic_write(path, emit_csv, table, "comparison", context, error);
}
