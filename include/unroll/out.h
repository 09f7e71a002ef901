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
typedef struct ur_report_context {
    const char *surface; /* e.g. "helicoid" */
    const char *method;  /* "exact", "triangle" or "quad" */
    const ur_machine *machine;
    const ur_material *material;
    double surface_area;        /* 3D area of the whole surface */
    const char *const *outputs; /* files written, NULL-terminated; may be NULL */
    /* output_path given to ur_write_svg, so the report names each sheet's file; may be NULL */
    const char *sheet_path;
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

#endif
