/*
 * draw.h: text, lines and legends on a cairo context, shared by the PNG
 * pictures of src/out (analysis_png.c, plot.c, png.c, strain_png.c) so that
 * they set type and place their legends the same way.
 * Private to src/out.
 */
#ifndef UNROLL_OUT_DRAW_H
#define UNROLL_OUT_DRAW_H

#include <cairo.h>
#include <stdbool.h>

#include "unroll/base.h"

/* Where a piece of text stands relative to the x it is drawn at. */
typedef enum text_align { ALIGN_LEFT, ALIGN_CENTRE, ALIGN_RIGHT } text_align;

/* Sans-serif of size pixels, bold or regular. */
void draw_set_font(cairo_t *cr, double size, bool bold);

/* How far the current font advances over text, in pixels. */
double draw_text_width(cairo_t *cr, const char *text);

/* How far text advances in a sans-serif of size pixels; leaves that font set. */
double draw_text_width_at(cairo_t *cr, const char *text, double size, bool bold);

/* The left edge of something width wide aligned on x. */
double draw_left(double x, double width, text_align align);

/* Text with its baseline at y, aligned on x; leaves no current point behind. */
void draw_show_text(cairo_t *cr, double x, double y, text_align align, const char *text);

/* A straight line from (x0, y0) to (x1, y1), stroked with the current source and width. */
void draw_line(cairo_t *cr, double x0, double y0, double x1, double y1);

/*
 * The strain colour map (RdBu): white at 0, darker red the more strain
 * stretches, darker blue the more it compresses, clamped at -range..range;
 * white when range is 0.  Sets the source of cr.
 */
void draw_strain_colour(cairo_t *cr, double strain, double range);

/* The largest 1, 2 or 5 times a power of ten not above limit: a scale bar's length. */
double draw_nice_below(double limit);

/* How long the intervals a0..a1 and b0..b1 share, 0 when apart. */
double draw_overlap(double a0, double a1, double b0, double b1);

/* How much a legend box at (left, top), width by height pixels, would hide. */
typedef double draw_cover(const void *context, double left, double top, double width,
                          double height);

/*
 * The corner of a picture_width by picture_height picture, inset from its
 * edges, where a box_width by box_height legend hides least by covered:
 * bottom right first, then bottom left, top right, top left.
 */
void draw_legend_corner(double picture_width, double picture_height, double inset, double box_width,
                        double box_height, draw_cover *covered, const void *context, double *left,
                        double *top);

/* A legend's box: white, nine tenths opaque, in a grey frame unit pixels a point. */
void draw_legend_frame(cairo_t *cr, double left, double top, double width, double height,
                       double unit);

/* What a failed cairo status is to the caller: out of memory, a refused write, else ours. */
ur_status draw_failure_status(cairo_status_t status);

#endif
