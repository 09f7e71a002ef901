/*
 * writer.h (private to src/out/): the one small interface every cut-file
 * format implements, in the manner of potrace's backends.
 *
 * The driver (output.c) owns the files, the placement transforms, the order
 * of operations and the atomic rename; a format only turns a stream of calls
 *
 *     begin_document                                   (optional)
 *         begin_sheet
 *             piece(placed piece) ...                  (optional)
 *             begin_layer(op)  path(op, ...) ...  end_layer(op)    once per op
 *         end_sheet
 *         ...                                          once per sheet
 *     end_document                                     (optional)
 *
 * into bytes on an open FILE.  Every operation gets its begin_layer/end_layer
 * pair, in cutting order, even when it has no paths, so formats with layers
 * always have all of them.  Paths arrive grouped by operation and already in
 * sheet coordinates: millimetres, origin at the sheet's lower left, y up.
 *
 * A format of one file per sheet (SVG, DXF, PNG) gets each sheet's file in
 * begin_sheet; a one-file format (PDF) gets NULL there and its one file in
 * end_document, where it writes the whole document.
 *
 * Adding a format is one more file defining one more format_writer, and one
 * more entry in output.c's table of formats.
 */
#ifndef UNROLL_OUT_WRITER_H
#define UNROLL_OUT_WRITER_H

#include <stdbool.h>
#include <stdio.h>

#include "unroll/out.h"

/* The options of ur_output_options and ur_format_options together, defaults filled in. */
typedef struct write_settings {
    const char *title;    /* NULL for none */
    const char *job_name; /* NULL for none */
    ur_dxf_version dxf_version;
    double dpi;          /* > 0 */
    bool drawing_order;  /* paths as drawn, not in cutting order */
    ur_context *context; /* the files are opened in it; NULL for none */
} write_settings;

/* What every format may look at: the whole job, for the whole write. */
typedef struct write_job {
    const ur_layout *layout;
    const ur_piece *pieces;
    const ur_machine *machine;
    const write_settings *options; /* never NULL */
} write_job;

typedef struct format_writer {
    const char *format;    /* for messages: "SVG" */
    const char *extension; /* without the dot: "svg" */
    bool one_file;         /* every sheet in one file (PDF pages) */

    /*
     * Optional.  Sets *document, owned by the writer until end_document or
     * discard_document, before any sheet.
     */
    ur_status (*begin_document)(void **document, const write_job *job, ur_error *error);

    /*
     * Starts sheet index (of job->layout) on file and sets *state, owned by
     * the writer until end_sheet or discard_sheet.  file stays the caller's
     * (NULL for a one-file format); document is begin_document's (or NULL).
     */
    ur_status (*begin_sheet)(void **state, void *document, FILE *file, size_t index,
                             const write_job *job, ur_error *error);

    /* Optional: each piece placed on the sheet, before any layer (fills, labels). */
    ur_status (*piece)(void *state, const ur_piece *piece, const ur_placement *placement,
                       ur_error *error);

    /* Brackets the paths of one operation; either may be NULL when not needed. */
    ur_status (*begin_layer)(void *state, ur_op op, ur_error *error);
    ur_status (*end_layer)(void *state, ur_op op, ur_error *error);

    /*
     * One polyline of count >= 1 finite points; closed joins the last to the
     * first.  circle, in sheet coordinates, is NULL unless the path is
     * exactly that circle (closed) or an arc of it from points[0] to
     * points[count - 1] (open): a format that can say so draws the circle
     * or arc, one that cannot draws the points, which lie on it.
     */
    ur_status (*path)(void *state, ur_op op, const ur_vec2 *points, size_t count, bool closed,
                      const ur_path_circle *circle, ur_error *error);

    /* Finishes the sheet, writes what is buffered, frees state (also on failure). */
    ur_status (*end_sheet)(void *state, ur_error *error);

    /* Frees state after a failure; what was written no longer matters. */
    void (*discard_sheet)(void *state);

    /*
     * Optional.  Writes the document to file (a one-file format's, else
     * NULL) and frees it, also on failure.
     */
    ur_status (*end_document)(void *document, FILE *file, ur_error *error);

    /* Optional (needed with begin_document): frees the document after a failure. */
    void (*discard_document)(void *document);
} format_writer;

/*
 * The kerf the cut paths of the pieces placed on a sheet (its index, or
 * every sheet with WRITE_ALL_SHEETS) were compensated for, when all of
 * them were for one kerf; else 0, and the file says nothing.  Into text
 * (at least WRITE_KERF_NOTE_SIZE bytes): UR_KERF_NOTE with it, "" for 0.
 */
#define WRITE_ALL_SHEETS ((size_t)-1)
#define WRITE_KERF_NOTE_SIZE 80
void write_kerf_note(const write_job *job, size_t sheet, char *text);

/* Checks shared by the formats (style.c). */

/* The machine's style for op, refused when a format could not show it. */
ur_status style_check(const ur_machine *machine, ur_op op, ur_error *error);

/* "#RRGGBB" as 0xRRGGBB; the style has been checked. */
unsigned long style_rgb(const ur_op_style *style);

/*
 * The dash pattern of a style in mm, at most max numbers, into dashes;
 * returns how many (0: solid).  Numbers that are not positive end it.
 */
size_t style_dashes(const ur_op_style *style, double *dashes, size_t max);

extern const format_writer svg_writer;
extern const format_writer dxf_writer;
extern const format_writer pdf_writer;
extern const format_writer png_writer;

#endif
