/*
 * analysis_png.c: the PNG map of a surface analysis (cairo), for
 * `unroll analyze`.
 *
 * The map is the surface's parameter domain in millimetres: x the arc length
 * along rail a, y the distance along each ruling from rail a.  Both axes use
 * one scale, so a ruling is drawn at its real length and the map keeps the
 * surface's proportions.  The picture is 1000 px wide and as tall as its
 * content, top to bottom: title and summary, the map (at most 456 px tall)
 * with its axes, then the legend and the scale bar.
 *
 * Colour is K: green where K = 0, shades of blue where K < 0 on a log scale
 * of |K|, pale for the smallest |K| on the map and dark for the largest.  A
 * ruled surface has K <= 0 and its values may span many decades (K falls
 * off like 1 / distance^4 away from a hyperbolic paraboloid's saddle), so a
 * linear scale would show one dark spot on pale.  |K| below 1e-9 of the
 * largest counts as 0, so the log scale spans at most nine decades, and a
 * surface the analysis found developable is green throughout, so rounding
 * never shows.  The scale spans at least one decade, so that a nearly
 * constant K (a small hyperbolic paraboloid) reads as one shade.
 */
#include "unroll/analyze.h"

#include <cairo.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../base/atomic.h"
#include "draw.h"
#include "png.h"
#include "../base/c_locale.h"

/* The layout, in pixels. */
enum {
    WIDTH = UR_ANALYSIS_PNG_WIDTH,
    MAP_LEFT = 90,
    MAP_RIGHT = WIDTH - 40,
    MAP_TOP = 100,
    MAP_HEIGHT = 456,   /* at most: 100 + 456 + 66 + 98 = UR_ANALYSIS_PNG_MAX_HEIGHT */
    X_AXIS_BAND = 66,   /* below the map: ticks, numbers, axis title, space */
    LEGEND_HEIGHT = 98, /* colour bar, its numbers and caption; keys; scale bar */
    COLOUR_BAR_WIDTH = 360,
    KEY_LEFT = 540,
};

/* Drawing resolution: rulings across the map at most, samples along each. */
enum { MAX_COLUMNS = 900, PNG_ACROSS = 48 };

/* |K| below this fraction of the largest is drawn as K = 0. */
static const double ZERO_FRACTION = 1e-9;

/* Millimetres on the map to pixels (y grows upwards from rail a), and where the rest goes. */
typedef struct map {
    double left, bottom;  /* the pixel of (0, 0) mm */
    double scale;         /* pixels per mm */
    double width, height; /* in pixels */
    double legend_top;
    int image_height;
} map;

static double map_x(const map *m, double arc)
{
    return m->left + m->scale * arc;
}

static double map_y(const map *m, double along)
{
    return m->bottom - m->scale * along;
}

/* K sampled for drawing, finer along the rulings than the analysis. */
typedef struct grid {
    size_t *columns; /* owned: indices of the rulings drawn, first and last included */
    size_t column_count;
    double *gaussian; /* owned: column_count x (PNG_ACROSS + 1); NAN when singular or in a gap */
    /* The colour scale: |K| <= zero is green, lower..upper the shades of blue. */
    double zero, lower, upper; /* upper = 0 draws everything green */
} grid;

static void grid_free(grid *g)
{
    free(g->columns);
    free(g->gaussian);
    memset(g, 0, sizeof *g);
}

static double ruling_length(const ur_ruling_analysis *ruling)
{
    return ur_vec3_distance(ruling->near, ruling->far);
}

static ur_status choose_columns(const ur_analysis *analysis, grid *g, ur_error *error)
{
    size_t count = analysis->ruling_count;
    size_t stride = (count + MAX_COLUMNS - 1) / MAX_COLUMNS;
    g->columns = ur_alloc_array(count / stride + 2, sizeof *g->columns, error);
    if (!g->columns)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < count; i += stride)
        g->columns[g->column_count++] = i;
    if (g->columns[g->column_count - 1] != count - 1)
        g->columns[g->column_count++] = count - 1;
    return UR_OK;
}

/* From the smallest |K| that is not zero to the largest, at least a decade. */
static void set_colour_scale(grid *g)
{
    size_t count = g->column_count * (PNG_ACROSS + 1);
    for (size_t i = 0; i < count; i++)
        if (fabs(g->gaussian[i]) > g->upper) /* false for NAN */
            g->upper = fabs(g->gaussian[i]);
    g->zero = ZERO_FRACTION * g->upper;
    g->lower = g->upper;
    for (size_t i = 0; i < count; i++)
        if (fabs(g->gaussian[i]) > g->zero && fabs(g->gaussian[i]) < g->lower)
            g->lower = fabs(g->gaussian[i]);
    g->lower = fmin(g->lower, g->upper / 10);
}

static ur_status compute_grid(ur_ruled *ruled, const ur_analysis *analysis, grid *g,
                              ur_error *error)
{
    memset(g, 0, sizeof *g);
    ur_status status = choose_columns(analysis, g, error);
    if (status != UR_OK)
        return status;
    g->gaussian = ur_alloc_array(g->column_count * (PNG_ACROSS + 1), sizeof *g->gaussian, error);
    if (!g->gaussian) {
        grid_free(g);
        return UR_ERROR_MEMORY;
    }
    for (size_t c = 0; c < g->column_count; c++) {
        const ur_ruling_analysis *ruling = &analysis->rulings[g->columns[c]];
        for (size_t j = 0; j <= PNG_ACROSS; j++) {
            double *k = &g->gaussian[c * (PNG_ACROSS + 1) + j];
            *k = NAN;
            if (ruling->in_gap)
                continue;
            ur_point_curvature point;
            ur_analyze_point(ruled, ruling->u, (double)j / PNG_ACROSS, &point);
            *k = point.gaussian;
        }
    }
    if (!analysis->developable)
        set_colour_scale(g);
    return UR_OK;
}

/* ---- Colour ------------------------------------------------------------- */

static void set_zero_colour(cairo_t *cr)
{
    cairo_set_source_rgb(cr, 0.20, 0.66, 0.32);
}

/* t = 0 pale blue (the smallest |K| on the scale) to 1 dark blue (the largest). */
static void set_shade(cairo_t *cr, double t)
{
    static const double stops[3][3] = {
        {0.66, 0.83, 0.96},
        {0.26, 0.54, 0.85},
        {0.07, 0.11, 0.47},
    };
    t = fmin(fmax(t, 0.0), 1.0);
    int k = t < 0.5 ? 0 : 1;
    double f = t < 0.5 ? 2 * t : 2 * t - 1;
    cairo_set_source_rgb(cr, stops[k][0] + f * (stops[k + 1][0] - stops[k][0]),
                         stops[k][1] + f * (stops[k + 1][1] - stops[k][1]),
                         stops[k][2] + f * (stops[k + 1][2] - stops[k][2]));
}

static void set_gaussian_colour(cairo_t *cr, const grid *g, double gaussian)
{
    if (!(g->upper > 0) || !(fabs(gaussian) > g->zero))
        set_zero_colour(cr);
    else
        set_shade(cr, log(fabs(gaussian) / g->lower) / log(g->upper / g->lower));
}

/* ---- Text --------------------------------------------------------------- */

/* Text on the map: dark on a white box, so that it reads on any colour. */
static void show_boxed_text(cairo_t *cr, double x, double y, text_align align, const char *text)
{
    double width = draw_text_width(cr, text);
    cairo_rectangle(cr, draw_left(x, width, align) - 3, y - 12, width + 6, 16);
    cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_show_text(cr, x, y, align, text);
}

/* ---- Map ---------------------------------------------------------------- */

static ur_status fit_map(const ur_analysis *analysis, map *m, ur_error *error)
{
    double width_mm = analysis->rulings[analysis->ruling_count - 1].arc, height_mm = 0;
    for (size_t i = 0; i < analysis->ruling_count; i++)
        height_mm = fmax(height_mm, ruling_length(&analysis->rulings[i]));
    if (!(width_mm > 0) || !(height_mm > 0) || !isfinite(width_mm) || !isfinite(height_mm))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the surface has no extent to map (rail a %g mm, rulings %g mm)",
                            width_mm, height_mm);
    m->scale = fmin((MAP_RIGHT - MAP_LEFT) / width_mm, MAP_HEIGHT / height_mm);
    m->width = m->scale * width_mm;
    m->height = m->scale * height_mm;
    m->left = MAP_LEFT;
    m->bottom = MAP_TOP + m->height;
    m->legend_top = m->bottom + X_AXIS_BAND;
    m->image_height = (int)ceil(m->legend_top + LEGEND_HEIGHT);
    return UR_OK;
}

/* Whether any ruling from first to last (inclusive) is in a gap. */
static bool gap_between(const ur_analysis *analysis, size_t first, size_t last)
{
    for (size_t i = first; i <= last; i++)
        if (analysis->rulings[i].in_gap)
            return true;
    return false;
}

/* Mean of the corners that have a K; NAN if none has. */
static double cell_gaussian(const grid *g, size_t c, size_t j)
{
    const double *k = g->gaussian;
    size_t row = PNG_ACROSS + 1;
    double corners[4] = {k[c * row + j], k[c * row + j + 1], k[(c + 1) * row + j],
                         k[(c + 1) * row + j + 1]};
    double sum = 0;
    int count = 0;
    for (int i = 0; i < 4; i++)
        if (!isnan(corners[i]))
            sum += corners[i], count++;
    return count ? sum / count : NAN;
}

static void draw_cells(cairo_t *cr, const map *m, const ur_analysis *analysis, const grid *g)
{
    /* Without antialiasing neighbouring cells meet without a seam. */
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
    for (size_t c = 0; c + 1 < g->column_count; c++) {
        const ur_ruling_analysis *r0 = &analysis->rulings[g->columns[c]];
        const ur_ruling_analysis *r1 = &analysis->rulings[g->columns[c + 1]];
        if (gap_between(analysis, g->columns[c], g->columns[c + 1]))
            continue;
        double x0 = map_x(m, r0->arc), x1 = map_x(m, r1->arc);
        double l0 = ruling_length(r0), l1 = ruling_length(r1);
        for (size_t j = 0; j < PNG_ACROSS; j++) {
            double k = cell_gaussian(g, c, j);
            if (isnan(k))
                continue;
            double v0 = (double)j / PNG_ACROSS, v1 = (double)(j + 1) / PNG_ACROSS;
            cairo_move_to(cr, x0, map_y(m, v0 * l0));
            cairo_line_to(cr, x1, map_y(m, v0 * l1));
            cairo_line_to(cr, x1, map_y(m, v1 * l1));
            cairo_line_to(cr, x0, map_y(m, v1 * l0));
            cairo_close_path(cr);
            set_gaussian_colour(cr, g, k);
            cairo_fill(cr);
        }
    }
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
}

/* The boundary of each run of rulings outside the gaps. */
static void draw_outline(cairo_t *cr, const map *m, const ur_analysis *analysis)
{
    size_t count = analysis->ruling_count;
    cairo_new_path(cr);
    for (size_t first = 0; first < count; first++) {
        if (analysis->rulings[first].in_gap)
            continue;
        size_t last = first;
        while (last + 1 < count && !analysis->rulings[last + 1].in_gap)
            last++;
        for (size_t i = first; i <= last; i++)
            cairo_line_to(cr, map_x(m, analysis->rulings[i].arc), map_y(m, 0));
        for (size_t i = last + 1; i-- > first;) {
            const ur_ruling_analysis *ruling = &analysis->rulings[i];
            cairo_line_to(cr, map_x(m, ruling->arc), map_y(m, ruling_length(ruling)));
        }
        cairo_close_path(cr);
        cairo_new_sub_path(cr);
        first = last;
    }
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, 1.2);
    cairo_stroke(cr);
}

/* Arc length along rail a at u, interpolated between the rulings. */
static double arc_at(const ur_analysis *analysis, double u)
{
    const ur_ruling_analysis *r = analysis->rulings;
    size_t count = analysis->ruling_count;
    if (u <= r[0].u)
        return r[0].arc;
    for (size_t i = 1; i < count; i++)
        if (u <= r[i].u)
            return r[i - 1].arc +
                   (r[i].arc - r[i - 1].arc) * (u - r[i - 1].u) / (r[i].u - r[i - 1].u);
    return r[count - 1].arc;
}

static void hatch(cairo_t *cr, double x0, double y0, double x1, double y1)
{
    cairo_save(cr);
    cairo_rectangle(cr, x0, y0, x1 - x0, y1 - y0);
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_fill_preserve(cr);
    cairo_clip(cr);
    cairo_set_source_rgb(cr, 0.55, 0.55, 0.55);
    cairo_set_line_width(cr, 1.0);
    for (double x = x0 - (y1 - y0); x < x1; x += 8) {
        cairo_move_to(cr, x, y1);
        cairo_line_to(cr, x + (y1 - y0), y0);
    }
    cairo_stroke(cr);
    cairo_restore(cr);
}

static const char *gap_label(ur_gap_reason reason)
{
    return reason == UR_GAP_RULINGS_CROSS ? "rulings cross" : "no ruling";
}

/* Each gap as a hatched band the height of the map, labelled where it fits. */
static bool draw_gaps(cairo_t *cr, const map *m, const ur_analysis *analysis, ur_ruled *ruled)
{
    const ur_interval *gaps = NULL;
    size_t count = ur_ruled_gaps(ruled, &gaps);
    draw_set_font(cr, 12, false);
    for (size_t k = 0; k < count; k++) {
        double x0 = map_x(m, arc_at(analysis, gaps[k].u_start));
        double x1 = map_x(m, arc_at(analysis, gaps[k].u_end));
        double top = m->bottom - m->height;
        hatch(cr, x0, top, fmax(x1, x0 + 1), m->bottom);
        const char *label = gap_label(gaps[k].reason);
        double width = draw_text_width(cr, label);
        if (width + 8 < x1 - x0) {
            show_boxed_text(cr, (x0 + x1) / 2, top + m->height / 2, ALIGN_CENTRE, label);
        } else if (width + 8 < m->height) {
            cairo_save(cr);
            cairo_translate(cr, (x0 + x1) / 2 + 4, top + m->height / 2);
            cairo_rotate(cr, -M_PI / 2);
            show_boxed_text(cr, 0, 0, ALIGN_CENTRE, label);
            cairo_restore(cr);
        }
    }
    return count > 0;
}

static bool striction_inside(const ur_ruling_analysis *ruling)
{
    return !ruling->in_gap && ruling->striction_v >= -1e-9 && ruling->striction_v <= 1 + 1e-9;
}

/*
 * The striction line (edge of regression) where it runs inside the surface,
 * one polyline per stretch so that the dashes run on along it.
 */
static bool draw_striction(cairo_t *cr, const map *m, const ur_analysis *analysis)
{
    bool drawn = false;
    cairo_new_path(cr);
    for (size_t i = 0; i < analysis->ruling_count; i++) {
        const ur_ruling_analysis *ruling = &analysis->rulings[i];
        if (!striction_inside(ruling)) {
            cairo_new_sub_path(cr);
            continue;
        }
        cairo_line_to(cr, map_x(m, ruling->arc),
                      map_y(m, ruling->striction_v * ruling_length(ruling)));
        drawn = true;
    }
    static const double dashes[2] = {7, 4};
    cairo_set_source_rgb(cr, 0.85, 0.10, 0.10);
    cairo_set_line_width(cr, 2.0);
    cairo_set_dash(cr, dashes, 2, 0);
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
    return drawn;
}

static void bend_marker(cairo_t *cr, double x, double y)
{
    cairo_new_path(cr); /* not joined to wherever the last text ended */
    cairo_arc(cr, x, y, 6, 0, 2 * M_PI);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.85, 0.10, 0.10);
    cairo_set_line_width(cr, 2.5);
    cairo_stroke(cr);
}

/* The place of the smallest bend radius, marked and labelled. */
static bool draw_min_bend(cairo_t *cr, const map *m, const ur_analysis *analysis)
{
    if (!isfinite(analysis->min_bend_radius))
        return false;
    for (size_t i = 0; i < analysis->ruling_count; i++) {
        const ur_ruling_analysis *ruling = &analysis->rulings[i];
        if (ruling->in_gap || ruling->bend_radius != analysis->min_bend_radius)
            continue;
        double x = map_x(m, ruling->arc), y = map_y(m, ruling->bend_v * ruling_length(ruling));
        bend_marker(cr, x, y);
        char label[80];
        c_snprintf(label, sizeof label, "smallest bend radius %.4g mm", analysis->min_bend_radius);
        draw_set_font(cr, 12, false);
        bool left = x + 12 + draw_text_width(cr, label) > WIDTH - 4;
        double baseline = fmin(fmax(y + 4, m->bottom - m->height + 12), m->bottom - 4);
        show_boxed_text(cr, left ? x - 12 : x + 12, baseline, left ? ALIGN_RIGHT : ALIGN_LEFT,
                        label);
        return true;
    }
    return false;
}

/* ---- Axes, legend, scale bar -------------------------------------------- */

/* 1, 2 or 5 times a power of ten, about range / target. */
static double nice_step(double range, double target)
{
    double raw = range / fmax(target, 1.0);
    double magnitude = pow(10, floor(log10(raw)));
    double fraction = raw / magnitude;
    return (fraction <= 1 ? 1 : fraction <= 2 ? 2 : fraction <= 5 ? 5 : 10) * magnitude;
}

/*
 * Ticks and their millimetres, along rail a below the map or along the
 * rulings left of it.  Numbers side by side need more room than numbers one
 * above the other, so about one every 90 px across and every 45 px up.
 */
static void draw_ticks(cairo_t *cr, const map *m, bool vertical)
{
    double pixels = vertical ? m->height : m->width, range = pixels / m->scale;
    double step = nice_step(range, fmax(pixels / (vertical ? 45 : 90), 2));
    draw_set_font(cr, 12, false);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_set_line_width(cr, 1.0);
    for (double t = 0; t <= range * (1 + 1e-9); t += step) {
        char label[32];
        c_snprintf(label, sizeof label, "%.6g", t);
        if (vertical) {
            double y = map_y(m, t);
            draw_line(cr, m->left - 2, y, m->left - 7, y);
            draw_show_text(cr, m->left - 10, y + 4, ALIGN_RIGHT, label);
        } else {
            double x = map_x(m, t);
            draw_line(cr, x, m->bottom + 2, x, m->bottom + 7);
            draw_show_text(cr, x, m->bottom + 20, ALIGN_CENTRE, label);
        }
    }
}

static void draw_x_axis(cairo_t *cr, const map *m)
{
    draw_ticks(cr, m, false);
    const char *title = "arc length along rail a (mm)";
    double centre = fmax(m->left + m->width / 2, m->left + draw_text_width(cr, title) / 2);
    draw_show_text(cr, centre, m->bottom + 38, ALIGN_CENTRE, title);
}

static void draw_y_axis(cairo_t *cr, const map *m)
{
    draw_ticks(cr, m, true);
    const char *title = "along the ruling (mm)";
    if (m->height < draw_text_width(cr, title) + 20) { /* too short to write it alongside */
        draw_show_text(cr, 20, m->bottom - m->height - 10, ALIGN_LEFT, title);
        return;
    }
    cairo_save(cr);
    cairo_translate(cr, 26, m->bottom - m->height / 2);
    cairo_rotate(cr, -M_PI / 2);
    draw_show_text(cr, 0, 0, ALIGN_CENTRE, title);
    cairo_restore(cr);
}

/* A green swatch for K = 0, then the shades with K at four places. */
static void draw_colour_bar(cairo_t *cr, const map *m, const grid *g)
{
    double x = MAP_LEFT, y = m->legend_top, width = COLOUR_BAR_WIDTH, height = 16;
    double bar = x + 50;
    set_zero_colour(cr);
    cairo_rectangle(cr, x, y, 26, height);
    cairo_fill(cr);
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
    for (int i = 0; i < (int)width; i++) {
        set_shade(cr, (i + 0.5) / width);
        cairo_rectangle(cr, bar + i, y, 1, height);
        cairo_fill(cr);
    }
    cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
    draw_set_font(cr, 11, false);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_show_text(cr, x + 13, y + height + 17, ALIGN_CENTRE, "0");
    cairo_set_line_width(cr, 1.0);
    for (int tick = 0; tick <= 3; tick++) {
        char label[32];
        c_snprintf(label, sizeof label, "%.2g", -g->lower * pow(g->upper / g->lower, tick / 3.0));
        double at = bar + width * tick / 3;
        draw_line(cr, at, y + height, at, y + height + 4);
        draw_show_text(cr, at, y + height + 17, ALIGN_CENTRE, label);
    }
    draw_set_font(cr, 12, false);
    draw_show_text(cr, x, y + height + 38, ALIGN_LEFT,
                   "Gaussian curvature K (1/mm\xc2\xb2), log scale of |K|; green: K = 0");
}

/* Everything green: say why, and say so when the residual disagrees. */
static void draw_flat_legend(cairo_t *cr, const map *m, const ur_analysis *analysis)
{
    set_zero_colour(cr);
    cairo_rectangle(cr, MAP_LEFT, m->legend_top, 26, 16);
    cairo_fill(cr);
    char label[128];
    c_snprintf(label, sizeof label,
               analysis->developable ? "K = 0: developable (largest residual %.2g rad)"
                                     : "K = 0 at every sample, yet the residual reaches %.2g rad",
               analysis->max_residual);
    draw_set_font(cr, 12, false);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_show_text(cr, MAP_LEFT + 36, m->legend_top + 13, ALIGN_LEFT, label);
    draw_show_text(cr, MAP_LEFT, m->legend_top + 54, ALIGN_LEFT,
                   "Gaussian curvature K (1/mm\xc2\xb2)");
}

/* The keys for what is drawn over the colours, one line each. */
static void draw_keys(cairo_t *cr, const map *m, bool gaps, bool striction, bool bend)
{
    double y = m->legend_top + 8;
    draw_set_font(cr, 12, false);
    if (gaps) {
        hatch(cr, KEY_LEFT, y - 7, KEY_LEFT + 30, y + 7);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        draw_show_text(cr, KEY_LEFT + 40, y + 4, ALIGN_LEFT, "gap in the domain of existence");
        y += 22;
    }
    if (striction) {
        static const double dashes[2] = {7, 4};
        cairo_move_to(cr, KEY_LEFT, y);
        cairo_line_to(cr, KEY_LEFT + 30, y);
        cairo_set_source_rgb(cr, 0.85, 0.10, 0.10);
        cairo_set_line_width(cr, 2.0);
        cairo_set_dash(cr, dashes, 2, 0);
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        draw_show_text(cr, KEY_LEFT + 40, y + 4, ALIGN_LEFT,
                       "striction line (edge of regression of a developable)");
        y += 22;
    }
    if (bend) {
        bend_marker(cr, KEY_LEFT + 15, y);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        draw_show_text(cr, KEY_LEFT + 40, y + 4, ALIGN_LEFT, "smallest bend radius");
    }
}

/* About a quarter of the map's longer side, and no longer than 250 px. */
static void draw_scale_bar(cairo_t *cr, const map *m)
{
    double length = draw_nice_below(fmin(fmax(m->width, m->height) / 4, 250) / m->scale);
    double pixels = length * m->scale, right = MAP_RIGHT, y = m->image_height - 14;
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_rectangle(cr, right - pixels, y - 6, pixels, 6);
    cairo_fill(cr);
    char label[32];
    c_snprintf(label, sizeof label, "%.6g mm", length);
    draw_set_font(cr, 12, false);
    draw_show_text(cr, right - pixels - 8, y, ALIGN_RIGHT, label);
}

/* ---- Header and the whole picture --------------------------------------- */

static void draw_header(cairo_t *cr, const ur_analysis *analysis, const char *title)
{
    cairo_set_source_rgb(cr, 0.05, 0.05, 0.05);
    title = title ? title : "surface analysis";
    /* A long title (a whole command line) gets a smaller font rather than cut off. */
    double size = 20;
    draw_set_font(cr, size, true);
    while (size > 11 && draw_text_width(cr, title) > WIDTH - 40)
        draw_set_font(cr, --size, true);
    draw_show_text(cr, 20, 32, ALIGN_LEFT, title);
    char line[256];
    c_snprintf(line, sizeof line, "area %.6g mm\xc2\xb2 \xc2\xb7 %s (largest residual %.2g rad)",
               analysis->area_3d, analysis->developable ? "developable" : "not developable",
               analysis->max_residual);
    draw_set_font(cr, 13, false);
    draw_show_text(cr, 20, 54, ALIGN_LEFT, line);
    char bend[96];
    if (isfinite(analysis->min_bend_radius))
        c_snprintf(bend, sizeof bend, "smallest bend radius %.4g mm%s", analysis->min_bend_radius,
                   analysis->min_bend_radius > 0 ? "" : " (at a singular point)");
    else
        c_snprintf(bend, sizeof bend, "flat: no bending");
    /* + 0.0 turns -0 into 0 */
    c_snprintf(line, sizeof line, "K from %.3g to %.3g 1/mm\xc2\xb2 (mean %.3g) \xc2\xb7 %s",
               analysis->gaussian_min + 0.0, analysis->gaussian_max + 0.0,
               analysis->gaussian_mean + 0.0, bend);
    draw_show_text(cr, 20, 72, ALIGN_LEFT, line);
}

static ur_status render(cairo_t *cr, const map *m, ur_ruled *ruled, const ur_analysis *analysis,
                        const char *title, ur_error *error)
{
    grid g = {0};
    ur_status status = compute_grid(ruled, analysis, &g, error);
    if (status != UR_OK)
        return status;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw_header(cr, analysis, title);
    draw_cells(cr, m, analysis, &g);
    bool gaps = draw_gaps(cr, m, analysis, ruled);
    draw_outline(cr, m, analysis);
    bool striction = draw_striction(cr, m, analysis);
    bool bend = draw_min_bend(cr, m, analysis);
    draw_x_axis(cr, m);
    draw_y_axis(cr, m);
    if (g.upper > 0)
        draw_colour_bar(cr, m, &g);
    else
        draw_flat_legend(cr, m, analysis);
    draw_keys(cr, m, gaps, striction, bend);
    draw_scale_bar(cr, m);
    grid_free(&g);
    return UR_OK;
}

ur_status ur_analysis_png_write(const char *path, ur_ruled *ruled, const ur_analysis *analysis,
                                const char *title, ur_context *context, ur_error *error)
{
    if (analysis->ruling_count < 2)
        return ur_error_set(error, UR_ERROR_INTERNAL, "the analysis has fewer than 2 rulings");
    map layout = {0};
    ur_status status = fit_map(analysis, &layout, error);
    if (status != UR_OK)
        return status;
    cairo_surface_t *surface =
        cairo_image_surface_create(CAIRO_FORMAT_RGB24, WIDTH, layout.image_height);
    cairo_t *cr = cairo_create(surface); /* an error object, never NULL */
    if (cairo_status(cr) != CAIRO_STATUS_SUCCESS)
        status =
            ur_error_set(error, draw_failure_status(cairo_status(cr)),
                         "cannot draw the analysis: %s", cairo_status_to_string(cairo_status(cr)));
    if (status == UR_OK)
        status = render(cr, &layout, ruled, analysis, title, error);
    if (status == UR_OK && cairo_status(cr) != CAIRO_STATUS_SUCCESS)
        status = ur_error_set(error, UR_ERROR_INTERNAL, "cannot draw the analysis: %s",
                              cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    if (status == UR_OK)
        status = atomic_write(path, png_emit, surface, "picture", context, error);
    cairo_surface_destroy(surface);
    return status;
}
