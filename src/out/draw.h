/*
 * draw.h: text and lines on a cairo context, shared by the PNG pictures of
 * src/out (analysis_png.c, plot.c) so that they set type the same way.
 * Private to src/out.
 */
#ifndef UNROLL_OUT_DRAW_H
#define UNROLL_OUT_DRAW_H

#include <cairo.h>
#include <stdbool.h>

/* Where a piece of text stands relative to the x it is drawn at. */
typedef enum ur_align { UR_ALIGN_LEFT, UR_ALIGN_CENTRE, UR_ALIGN_RIGHT } ur_align;

/* Sans-serif of size pixels, bold or regular. */
void ur_draw_set_font(cairo_t *cr, double size, bool bold);

/* How far the current font advances over text, in pixels. */
double ur_draw_text_width(cairo_t *cr, const char *text);

/* The left edge of something width wide aligned on x. */
double ur_draw_left(double x, double width, ur_align align);

/* Text with its baseline at y, aligned on x; leaves no current point behind. */
void ur_draw_show_text(cairo_t *cr, double x, double y, ur_align align, const char *text);

/* A straight line from (x0, y0) to (x1, y1), stroked with the current source and width. */
void ur_draw_line(cairo_t *cr, double x0, double y0, double x1, double y1);

/*
 * The strain colour map (RdBu): white at 0, darker red the more strain
 * stretches, darker blue the more it compresses, clamped at -range..range;
 * white when range is 0.  Sets the source of cr.
 */
void ur_draw_strain_colour(cairo_t *cr, double strain, double range);

#endif
