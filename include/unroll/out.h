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

#ifdef __cplusplus
extern "C" {
#endif

/* The DXF dialects: R12 is what every cutter program reads. */
typedef enum ur_dxf_version {
    UR_DXF_R12 = 0, /* AC1009: POLYLINE/VERTEX/SEQEND and LINE, no handles */
    UR_DXF_R2000,   /* AC1015: LWPOLYLINE, handles, true colour, OBJECTS */
} ur_dxf_version;

/* The resolution of the PNG preview unless told otherwise, dots per inch. */
#define UR_PNG_DPI 96.0

typedef struct ur_output_options {
    const char *title;   /* document title, e.g. "unroll helicoid" */
    ur_context *context; /* the run's (its output set, cancel flag); NULL for none */
} ur_output_options;

/*
 * What the formats other than SVG need, and the job name every format
 * records (SVG, PDF).  Zeroed (or a NULL pointer) means the defaults: no
 * job name, DXF R12, the PNG preview at UR_PNG_DPI.
 */
typedef struct ur_format_options {
    const char *job_name;       /* the job the files come from; NULL for none */
    ur_dxf_version dxf_version; /* UR_DXF_R12 by default */
    double dpi;                 /* PNG preview resolution; 0 for UR_PNG_DPI */
    bool drawing_order;         /* --order none: paths as drawn, not in cutting order */
} ur_format_options;

/* Cut-file formats, as bits so that several can be asked for at once. */
typedef enum ur_format {
    UR_FORMAT_SVG = 1 << 0,
    UR_FORMAT_DXF = 1 << 1,
    UR_FORMAT_PDF = 1 << 2, /* one file, one page per sheet */
    UR_FORMAT_PNG = 1 << 3, /* a preview to look at, not to cut */
} ur_format;

#define UR_FORMAT_ALL (UR_FORMAT_SVG | UR_FORMAT_DXF | UR_FORMAT_PDF | UR_FORMAT_PNG)

/* The format the extension of path's base name names (any case), 0 for none. */
UR_API ur_format ur_format_from_path(const char *path);

/* "svg", "dxf", "pdf", "png" (also the extension) and back; 0 for an unknown name. */
UR_API const char *ur_format_name(ur_format format);
UR_API ur_format ur_format_from_name(const char *name);

/*
 * A comma-separated list of format names ("svg,dxf") as bits in *formats.
 * An empty list, an empty item or an unknown name is UR_ERROR_INPUT naming it.
 */
UR_API ur_status ur_formats_parse(const char *list, unsigned *formats, ur_error *error);

/* Output sets (ur_output_set_begin) are the context's: see unroll/base.h. */

/*
 * Writes the layout in every format of formats (ur_format bits; 0: the one
 * path's extension names).  Each format's file is path with that format's
 * extension: path's own extension, if it names a format, is replaced
 * ("net.svg" with SVG and DXF gives net.svg and net.dxf; "net" gives
 * net.svg and net.dxf), and it must then be one of the formats asked for.
 * SVG, DXF and PNG write one file per sheet, numbered when there are
 * several (ur_sheet_file_name: net-1.dxf, net-2.dxf, ...); PDF one file
 * with one page per sheet.  Every path goes to the layer of its operation,
 * in cutting order (engrave and mark, then scores and kerfs, then cuts;
 * inner contours before the outline).
 *
 * All or nothing: every file of every format is written to a temporary
 * first and renamed into place only when all are complete; on error no
 * file is left behind and files already there stay as they were.  "-"
 * writes one format (formats must name exactly one) of a one-sheet layout
 * (PDF: any number of sheets) to standard output.
 *
 * UR_ERROR_INPUT: no sheets, an extension or a format that is not known or
 * not asked for, a missing directory, a sheet of no usable size, a DPI that
 * is not a positive number or gives a picture too large, a style the
 * machine cannot give, an unwritable file.  pieces must hold every piece a
 * placement names.
 */
UR_API ur_status ur_write_outputs(const char *path, unsigned formats, const ur_layout *layout,
                                  const ur_piece *pieces, const ur_machine *machine,
                                  const ur_output_options *options,
                                  const ur_format_options *format_options, ur_error *error);

/*
 * ur_write_outputs for one format (one ur_format bit) to a stream the
 * caller owns (flushed, not closed), as to "-": the same bytes as that
 * format's file.  SVG, DXF and PNG take a layout of one sheet (more is
 * UR_ERROR_INPUT), PDF any number of sheets.  With the same options, an
 * SVG or DXF is the file ur_write_outputs writes, and with drawing_order
 * the one ur_write_svg and ur_write_dxf write.
 */
UR_API ur_status ur_write_stream(FILE *stream, ur_format format, const ur_layout *layout,
                          const ur_piece *pieces, const ur_machine *machine,
                          const ur_output_options *options, const ur_format_options *format_options,
                          ur_error *error);

/*
 * Writes one SVG per sheet.  With one sheet the file is output_path; with
 * several, NAME.svg becomes NAME-1.svg, NAME-2.svg, ...  Each file is
 * width × height mm with a matching viewBox, one layer group per operation
 * (id = operation name, Inkscape layer label and stroke from the machine),
 * each path a separate <path> in absolute coordinates, as drawn (the
 * pieces in placement order, paths starting where they start; the cutting
 * order is ur_write_outputs').
 */
UR_API ur_status ur_write_svg(const char *output_path, const ur_layout *layout,
                              const ur_piece *pieces, const ur_machine *machine,
                              const ur_output_options *options, ur_error *error);

/* ---- Cut order ----------------------------------------------------------- */

/*
 * The operations in the order they are cut: engrave and mark while the
 * sheet is whole, then scores and kerfs, the through cuts last.
 */
UR_API const ur_op *ur_operation_order(void);

/*
 * How a sheet is cut (order.c): the placements in the order the pieces are
 * visited, the same for every operation (nearest neighbour from the sheet's
 * origin, then 2-opt; the drawing order when not ordered), and what it
 * takes: cut length, travel between paths (from the origin) and time at
 * the machine's speeds (0 without a machine).  Within a piece inner
 * contours come before the outline; with ordered, every closed path starts
 * in the middle of its longest edge (ur_path_start).
 */
typedef struct ur_cut_plan {
    size_t *order;        /* placement indices in cutting order; owned */
    double cut_length;    /* mm */
    double travel_length; /* mm */
    double seconds;
} ur_cut_plan;

UR_API ur_status ur_sheet_cut_plan(const ur_sheet *sheet, const ur_piece *pieces,
                                   const ur_op *op_order, bool ordered, const ur_machine *machine,
                                   ur_cut_plan *plan, ur_error *error);
UR_API void ur_cut_plan_free(ur_cut_plan *plan);

/* The edge a closed path's cut starts in the middle of: its longest (0 for open paths). */
UR_API size_t ur_path_start(const ur_path *path);

/* Room for one output file name. */
#define UR_OUTPUT_NAME_SIZE 4096

/*
 * The names of every file ur_write_outputs writes for path and formats
 * with sheet_count sheets, in the order it writes them (for the report);
 * the caller frees *names.  Refuses what ur_write_outputs refuses about
 * the path and formats.
 */
UR_API ur_status ur_output_files(const char *path, unsigned formats, size_t sheet_count,
                                 char (**names)[UR_OUTPUT_NAME_SIZE], size_t *count,
                                 ur_error *error);

/*
 * The same for DXF, PDF and the PNG preview, output_path used as it is
 * (numbered per sheet for DXF and PNG; the one PDF file holds every sheet).
 * DXF (format_options->dxf_version): ASCII, $INSUNITS 4 (mm), $MEASUREMENT 1,
 * $EXTMIN/$EXTMAX the sheet, one LAYER per operation named as the machine
 * names it (characters DXF forbids in a name become '_') with the nearest
 * ACI colour (R2000: and the exact true colour), each path one entity: a
 * closed or open polyline (R12 POLYLINE, R2000 LWPOLYLINE), a path that
 * is exactly a circle (ur_path_circle) a CIRCLE, exactly an arc an ARC, a
 * two-point open path a LINE; a layer the machine dashes gets a LTYPE of
 * its dashes (DASH_3_1P5 for "3 1.5"); the job name is a 999 comment at
 * the top.  SVG draws exact circles as <circle> and arcs with A.  PDF (libharu): each page exactly
 * its sheet, paths in the machine's colours and line widths (dashes too), title, creator "unroll
 * VERSION" and job name in the document information (non-ASCII characters as '?').  PNG: each sheet
 * at format_options->dpi with the pieces filled by strain colour (where the piece has shading), the
 * lines in their operations' colours, the pieces' names, a scale bar and a legend of the
 * operations.
 */
UR_API ur_status ur_write_dxf(const char *output_path, const ur_layout *layout,
                              const ur_piece *pieces, const ur_machine *machine,
                              const ur_output_options *options,
                              const ur_format_options *format_options, ur_error *error);
UR_API ur_status ur_write_pdf(const char *output_path, const ur_layout *layout,
                              const ur_piece *pieces, const ur_machine *machine,
                              const ur_output_options *options,
                              const ur_format_options *format_options, ur_error *error);
UR_API ur_status ur_write_png(const char *output_path, const ur_layout *layout,
                              const ur_piece *pieces, const ur_machine *machine,
                              const ur_output_options *options,
                              const ur_format_options *format_options, ur_error *error);

/* What the report says beyond the pieces and sheets. */
/* The material layer the 3D surface is and the one developed (--surface). */
typedef struct ur_report_layer {
    const char *surface;   /* "outer", "inner", "mid" or "neutral" */
    const char *developed; /* the layer whose lengths the net keeps: "neutral" */
    double offset;         /* mm from the first to the second, toward the inside of the bend */
    double k_factor;       /* the neutral layer's place, a fraction of the thickness */
    double thickness;      /* mm */
} ur_report_layer;

/* What --adjust did to the rails (ur_rails_repair's report), for the report. */
typedef struct ur_report_repair {
    const char *rails;        /* "rail1", "rail2" or "both" */
    double largest, mean;     /* displacement, mm */
    int largest_rail;         /* 1 or 2 */
    size_t largest_point;     /* from 0 */
    ur_vec3 largest_position; /* where that point was, as given */
    double largest_along;     /* mm along that rail as given */
    /* the files written (--adjusted-rail, --adjusted-rail1); may be NULL */
    const char *adjusted_rail, *adjusted_rail1;
} ur_report_repair;

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
    bool drawing_order;                  /* the files keep the drawing order (--order none) */
    /* ceil(part area / usable sheet area), the fewest sheets any layout needs; 0: not known */
    double sheets_lower_bound;
    const ur_report_repair *repair; /* the rails' repair; NULL: none asked */
} ur_report_context;

/*
 * Writes the JSON report to path ("-" for stdout), atomically for a file.
 * layout may be NULL (nothing placed yet); every placement's piece_index
 * must be below piece_count.
 */
UR_API ur_status ur_report_write(const char *path, const ur_report_context *context,
                                 const ur_piece *pieces, size_t piece_count,
                                 const ur_layout *layout, ur_context *run, ur_error *error);

/* The same bytes to a stream the caller owns (flushed, not closed). */
UR_API ur_status ur_report_write_stream(FILE *stream, const ur_report_context *context,
                                 const ur_piece *pieces, size_t piece_count,
                                 const ur_layout *layout, ur_error *error);

/*
 * The file names an output of sheet_count sheets gets: output_path itself for
 * one sheet, NAME-1.EXT ... otherwise, the number going before the extension
 * of the base name ("dir.v2/net" becomes "dir.v2/net-1").  sheet_index counts
 * from 0.  Writes into name (size name_size); a name that does not fit is
 * UR_ERROR_INPUT.
 */
UR_API ur_status ur_sheet_file_name(const char *output_path, size_t sheet_index, size_t sheet_count,
                                    char *name, size_t name_size, ur_error *error);

/*
 * The comparison of the discrete methods with the exact net (ur_compare) as
 * a 900 x 600 PNG: two log-log panels against n, |relative area error| and
 * the largest boundary distance to the exact net, one colour and marker per
 * method, with a legend and the title (NULL for "unroll compare").  Values
 * below 1e-16, zeros included, are drawn at 1e-16, as the plot says.
 * Written atomically ("-" for stdout).
 */
UR_API ur_status ur_compare_plot_png(const char *path, const ur_compare_table *table,
                                     const char *title, ur_context *context, ur_error *error);

/*
 * The same as CSV, one line per n after the header
 *     n,triangle_area_error,quad_area_error,exact_area_error,
 *     triangle_edge_error,quad_edge_error,exact_edge_error,
 *     triangle_distance,quad_distance
 * (one line), numbers as %.17g, the fields of a method that does not apply
 * (the triangle method off tangent developables) left empty.  Written
 * atomically; "-" for stdout.
 */
UR_API ur_status ur_compare_csv_write(const char *path, const ur_compare_table *table,
                                      ur_context *context, ur_error *error);

/*
 * The JSON report of an analysis (ur_analyze of ruled) to path ("-" for
 * standard output), atomically for a file.
 */
UR_API ur_status ur_analysis_report_write(const char *path, const char *surface, ur_ruled *ruled,
                                          const ur_analysis *analysis, ur_context *context,
                                          ur_error *error);

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
UR_API ur_status ur_strain_png_write(const char *path, const ur_layout *layout,
                                     const ur_piece *pieces, size_t piece_count, double dpi,
                                     ur_context *context, ur_error *error);

/* ---- Assembly guide (assembly.c) ----------------------------------------- */

typedef struct ur_assembly_options {
    const char *title; /* the model's name, for the title; NULL for none */
    /*
     * The names the cut pieces carry, parallel to the nets (NULL, or an
     * entry NULL: the net's own name).
     */
    const char *const *names;
    bool y_up;           /* the model's up is +y (as Blender's OBJ export); false: +z */
    ur_context *context; /* the run's (its output set, cancel flag); NULL for none */
} ur_assembly_options;

/*
 * The assembly guide: the mesh the nets were cut from (their faces_3d),
 * drawn from four directions (front right and back left from above, front
 * left and back right from below: every face of a convex model faces one
 * of them) in a 2 x 2 grid under a title and a key.  Hidden faces are
 * removed (painter's algorithm; on a closed mesh the faces turned away are
 * not drawn, on an open one their inside is greyed); faces are lit from
 * the viewer's upper left and tinted with their piece's colour, one hue per
 * piece, all hues different and far apart where pieces meet; cuts between
 * pieces are thick dark lines, folds thin ones.  Each piece's name stands
 * on it in every view where enough of it is seen (at least once where any
 * of it is), and each seam's label (ur_seam_label) at the middle of the
 * seam where that point is in sight, in a box, moved aside on a leader
 * line when its place is taken; no two labels overlap, and a label with no
 * room is left out (the title says how many seams are shown).  The key
 * shows each piece's colour.
 *
 * path's extension says the format (any case): .png, a 2372 x 2532 pixel
 * RGB image; .pdf, the same drawing as vectors on one page about 297 mm
 * wide.  Written atomically (part of an output set when one is open).
 * Refused with UR_ERROR_INPUT: another extension, nets without any 3D face
 * (a development of a ruled surface), a face corner that is not finite, an
 * unwritable file.  options may be NULL.
 */
UR_API ur_status ur_assembly_write(const ur_net_list *nets, const char *path,
                                   const ur_assembly_options *options, ur_error *error);

#ifdef __cplusplus
}
#endif

#endif
