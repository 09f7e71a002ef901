/*
 * unroll/out.h: writing the cut files and the report.
 *
 * Every format is one file under src/out/ behind the same small interface
 * (begin sheet, path with operation, end sheet).  Writes are atomic: each
 * file is written to a temporary file in the target directory and renamed
 * into place only when every file of the output has been written; on error
 * nothing is left behind and nothing already on disk is touched.
 */
#ifndef UNROLL_OUT_H
#define UNROLL_OUT_H

#include "unroll/allow.h"
#include "unroll/analyze.h"
#include "unroll/develop.h"
#include "unroll/io.h"
#include "unroll/nest.h"

typedef struct ur_output_options {
    const char *title; /* document title, e.g. "unroll helicoid" */
} ur_output_options;

/*
 * Writes one SVG per sheet.  With one sheet the file is output_path; with
 * several, NAME.svg becomes NAME-1.svg, NAME-2.svg, ...  Each file is
 * width × height mm with a matching viewBox, one layer group per operation
 * (id = operation name, Inkscape layer label and stroke from the machine),
 * each path a separate <path> in absolute coordinates.
 */
ur_status ur_write_svg(const char *output_path, const ur_layout *layout, const ur_piece *pieces,
                       const ur_machine *machine, const ur_output_options *options,
                       ur_error *error);

/* What the report says beyond the pieces and sheets. */
/* The material layer the 3D surface is and the one developed (--surface). */
typedef struct ur_report_layer {
    const char *surface;   /* "outer", "inner", "mid" or "neutral" */
    const char *developed; /* the layer whose lengths the net keeps: "neutral" */
    double offset;         /* mm from the first to the second, toward the inside of the bend */
    double k_factor;       /* the neutral layer's place, a fraction of the thickness */
    double thickness;      /* mm */
} ur_report_layer;

typedef struct ur_report_context {
    const char *surface; /* e.g. "helicoid" */
    const char *method;  /* "exact", "triangle" or "quad" */
    const ur_machine *machine;
    const ur_material *material;
    double surface_area;        /* 3D area of the whole surface */
    const char *const *outputs; /* files written, NULL-terminated; may be NULL */
    /* output_path given to ur_write_svg, so the report names each sheet's file; may be NULL */
    const char *sheet_path;
    /* gaps in a strip's domain of existence (ur_ruled_gaps); may be NULL, 0 */
    const ur_interval *gaps;
    size_t gap_count;
    const struct ur_report_layer *layer; /* the layer developed; NULL: not reported (meshes) */
} ur_report_context;

/*
 * Writes the JSON report to path ("-" for stdout), atomically for a file.
 * layout may be NULL (nothing placed yet); every placement's piece_index
 * must be below piece_count.
 */
ur_status ur_report_write(const char *path, const ur_report_context *context,
                          const ur_piece *pieces, size_t piece_count, const ur_layout *layout,
                          ur_error *error);

/*
 * The file names an output of sheet_count sheets gets: output_path itself for
 * one sheet, NAME-1.EXT ... otherwise, the number going before the extension
 * of the base name ("dir.v2/net" becomes "dir.v2/net-1").  sheet_index counts
 * from 0.  Writes into name (size name_size); a name that does not fit is
 * UR_ERROR_INPUT.
 */
ur_status ur_sheet_file_name(const char *output_path, size_t sheet_index, size_t sheet_count,
                             char *name, size_t name_size, ur_error *error);

/*
 * The comparison of the discrete methods with the exact net (ur_compare) as
 * a 900 x 600 PNG: two log-log panels against n, |relative area error| and
 * the largest boundary distance to the exact net, one colour and marker per
 * method, with a legend and the title (NULL for "unroll compare").  Values
 * below 1e-16, zeros included, are drawn at 1e-16, as the plot says.
 * Written atomically ("-" for stdout).
 */
ur_status ur_compare_plot_png(const char *path, const ur_compare_table *table, const char *title,
                              ur_error *error);

/*
 * The same as CSV, one line per n after the header
 *     n,triangle_area_error,quad_area_error,exact_area_error,
 *     triangle_edge_error,quad_edge_error,exact_edge_error,
 *     triangle_distance,quad_distance
 * (one line), numbers as %.17g, the fields of a method that does not apply
 * (the triangle method off tangent developables) left empty.  Written
 * atomically; "-" for stdout.
 */
ur_status ur_compare_csv_write(const char *path, const ur_compare_table *table, ur_error *error);

/*
 * The JSON report of an analysis (ur_analyze of ruled) to path ("-" for
 * standard output), atomically for a file.
 */
ur_status ur_analysis_report_write(const char *path, const char *surface, ur_ruled *ruled,
                                   const ur_analysis *analysis, ur_error *error);

/* The resolution of the strain picture unless told otherwise, dots per inch. */
#define UR_STRAIN_PNG_DPI 96.0

/*
 * The strain picture: one PNG per sheet of the layout, named as ur_write_svg
 * names its SVGs (path itself for one sheet, NAME-1.png, NAME-2.png, ... for
 * several; ur_sheet_file_name).  Each image is the sheet at dpi dots per inch
 * (0 for UR_STRAIN_PNG_DPI), width × dpi / 25.4 by height × dpi / 25.4
 * pixels rounded to the nearest, every piece placed by the layout.  Each
 * triangle of a piece's shading is filled by a diverging colour map of its
 * strain: white at 0, darker red the more it is stretched, darker blue the
 * more it is compressed, its lightness falling with |strain| so that it
 * reads in grey too.  The scale runs from -s to +s, s the largest |strain|
 * of all piece_count pieces, so that every sheet uses the same one.  A
 * piece without shading (a development) stays white, labelled "exact: no
 * strain".  Outlines are dark grey, each piece's name stands inside it with
 * its range of strain, and a legend (colour bar with its numbers in per
 * cent, scale bar) goes in the corner of the sheet where it covers the
 * least.  Text keeps its size on paper: 1 point = dpi / 96 pixels.
 *
 * Written atomically, every sheet or none: on error nothing is left behind
 * and files already there stay as they were.  "-" writes a one-sheet layout
 * to standard output.  Refused with UR_ERROR_INPUT: no sheets, a dpi that is
 * not a positive number, a sheet of no usable size or of more pixels than a
 * picture may have (32767 a side, 1e8 in all), a missing directory.
 */
ur_status ur_strain_png_write(const char *path, const ur_layout *layout, const ur_piece *pieces,
                              size_t piece_count, double dpi, ur_error *error);

#endif
