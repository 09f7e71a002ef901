/*
 * draw.c: text and lines for the PNG pictures (draw.h), so that the analysis
 * map and the comparison plot measure and place text in one way.
 */
#include "draw.h"

#include <math.h>

void draw_set_font(cairo_t *cr, double size, bool bold)
{
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

/* The advance, not the ink extent: text placed one after another meets without overlap. */
double draw_text_width(cairo_t *cr, const char *text)
{
    cairo_text_extents_t extents;
    cairo_text_extents(cr, text, &extents);
    return extents.x_advance;
}

double draw_text_width_at(cairo_t *cr, const char *text, double size, bool bold)
{
    draw_set_font(cr, size, bold);
    return draw_text_width(cr, text);
}

double draw_left(double x, double width, text_align align)
{
    return align == ALIGN_LEFT ? x : align == ALIGN_CENTRE ? x - width / 2 : x - width;
}

void draw_show_text(cairo_t *cr, double x, double y, text_align align, const char *text)
{
    cairo_move_to(cr, draw_left(x, draw_text_width(cr, text), align), y);
    cairo_show_text(cr, text);
    cairo_new_path(cr); /* show_text leaves a current point the next path would start from */
}

void draw_line(cairo_t *cr, double x0, double y0, double x1, double y1)
{
    cairo_move_to(cr, x0, y0);
    cairo_line_to(cr, x1, y1);
    cairo_stroke(cr);
}

/*
 * ColorBrewer RdBu from its white middle outwards, in 8-bit sRGB.  Every
 * channel falls from one stop to the next, so lightness falls with |strain|
 * and the picture still reads printed in grey.
 */
enum { STOPS = 6 };
static const unsigned char stretch_stops[STOPS][3] = {
    {255, 255, 255}, {253, 219, 199}, {244, 165, 130}, {214, 96, 77}, {178, 24, 43}, {103, 0, 31},
};
static const unsigned char compression_stops[STOPS][3] = {
    {255, 255, 255}, {209, 229, 240}, {146, 197, 222}, {67, 147, 195}, {33, 102, 172}, {5, 48, 97},
};

void draw_strain_colour(cairo_t *cr, double strain, double range)
{
    double t = range > 0 ? fmin(fabs(strain) / range, 1.0) : 0.0;
    const unsigned char(*stops)[3] = strain >= 0 ? stretch_stops : compression_stops;
    double at = t * (STOPS - 1);
    int k = (int)fmin(floor(at), STOPS - 2);
    double f = at - k, rgb[3];
    for (int c = 0; c < 3; c++)
        rgb[c] = (stops[k][c] + f * (stops[k + 1][c] - stops[k][c])) / 255.0;
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
}

double draw_nice_below(double limit)
{
    double magnitude = pow(10, floor(log10(limit)));
    double fraction = limit / magnitude;
    return (fraction >= 5 ? 5 : fraction >= 2 ? 2 : 1) * magnitude;
}

double draw_overlap(double a0, double a1, double b0, double b1)
{
    return fmax(0.0, fmin(a1, b1) - fmax(a0, b0));
}

void draw_legend_corner(double picture_width, double picture_height, double inset, double box_width,
                        double box_height, draw_cover *covered, const void *context, double *left,
                        double *top)
{
    double right = picture_width - inset - box_width, bottom = picture_height - inset - box_height;
    const double corners[4][2] = {{right, bottom}, {inset, bottom}, {right, inset}, {inset, inset}};
    double least = INFINITY;
    for (int k = 0; k < 4; k++) {
        double area = covered(context, corners[k][0], corners[k][1], box_width, box_height);
        if (area < least) {
            least = area;
            *left = corners[k][0];
            *top = corners[k][1];
        }
    }
}

void draw_legend_frame(cairo_t *cr, double left, double top, double width, double height,
                       double unit)
{
    cairo_rectangle(cr, left, top, width, height);
    cairo_set_source_rgba(cr, 1, 1, 1, 0.9);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 0.8 * unit);
    cairo_stroke(cr);
}

ur_status draw_failure_status(cairo_status_t status)
{
    if (status == CAIRO_STATUS_NO_MEMORY)
        return UR_ERROR_MEMORY;
    if (status == CAIRO_STATUS_WRITE_ERROR)
        return UR_ERROR_IO;
    return UR_ERROR_INTERNAL;
}
