/*
 * writer.h (private to src/out/): the one small interface every cut-file
 * format implements, in the manner of potrace's backends.
 *
 * The driver (output.c) owns the files, the placement transforms, the order
 * of operations and the atomic rename; a format only turns a stream of calls
 *
 *     begin_sheet
 *         begin_layer(op)  path(op, ...) ...  end_layer(op)    once per op
 *     end_sheet
 *
 * into bytes on an open FILE.  Every operation gets its begin_layer/end_layer
 * pair, in cutting order, even when it has no paths, so formats with layers
 * always have all of them.  Paths arrive grouped by operation and already in
 * sheet coordinates: millimetres, origin at the sheet's lower left, y up.
 *
 * Adding a format (DXF, PDF, PNG) is one more file defining one more
 * ur_writer and one more public ur_write_* calling the driver.
 */
#ifndef UNROLL_OUT_WRITER_H
#define UNROLL_OUT_WRITER_H

#include <stdbool.h>
#include <stdio.h>

#include "unroll/out.h"

typedef struct ur_writer {
    const char *format;    /* for messages: "SVG" */
    const char *extension; /* without the dot: "svg" */

    /*
     * Starts a sheet of width × height mm on file and sets *state, owned by
     * the writer until end_sheet or discard_sheet.  file stays the caller's.
     */
    ur_status (*begin_sheet)(void **state, FILE *file, double width, double height,
                             const ur_machine *machine, const ur_output_options *options,
                             ur_error *error);

    /* Brackets the paths of one operation; either may be NULL when not needed. */
    ur_status (*begin_layer)(void *state, ur_op op, ur_error *error);
    ur_status (*end_layer)(void *state, ur_op op, ur_error *error);

    /* One polyline of count >= 1 finite points; closed joins the last to the first. */
    ur_status (*path)(void *state, ur_op op, const ur_vec2 *points, size_t count, bool closed,
                      ur_error *error);

    /* Finishes the sheet, writes what is buffered, frees state (also on failure). */
    ur_status (*end_sheet)(void *state, ur_error *error);

    /* Frees state after a failure; what was written no longer matters. */
    void (*discard_sheet)(void *state);
} ur_writer;

extern const ur_writer ur_svg_writer;

#endif
