/*
 * output.c: the driver behind every cut-file format.
 *
 * It names the files (one per sheet), walks the layout in cutting order,
 * moves each path from piece to sheet coordinates and hands it to a format
 * (writer.h), and makes the whole output atomic: every sheet is written to
 * its own temporary file first, and only when all of them are complete are
 * they renamed into place.  On any error every temporary is removed and the
 * files already on disk are left as they were.
 */
#include "writer.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "atomic.h"

/*
 * Cutting order: engrave and mark while the sheet is still whole, then fold
 * lines and relief cuts, and the through cuts last so that no part drops out
 * or shifts before everything on it is done.
 */
_Static_assert(UR_OP_COUNT == 6, "put every operation into cut_order");
static const ur_op cut_order[UR_OP_COUNT] = {UR_OP_ENGRAVE,      UR_OP_MARK, UR_OP_SCORE,
                                             UR_OP_SCORE_VALLEY, UR_OP_KERF, UR_OP_CUT};

/* Longest path name we build; longer output names are refused, not cut off. */
enum { NAME_SIZE = 4096 };

ur_status ur_sheet_file_name(const char *output_path, size_t sheet_index, size_t sheet_count,
                             char *name, size_t name_size, ur_error *error)
{
    if (sheet_index >= sheet_count)
        return ur_error_set(error, UR_ERROR_INTERNAL, "sheet %zu of %zu does not exist",
                            sheet_index + 1, sheet_count);
    int length;
    if (sheet_count == 1) {
        length = snprintf(name, name_size, "%s", output_path);
    } else {
        /* The extension is that of the base name: "dir.v2/net" has none. */
        const char *slash = strrchr(output_path, '/');
        const char *base = slash ? slash + 1 : output_path;
        const char *dot = strrchr(base, '.');
        if (!dot || dot == base) /* ".hidden" is a name, not an extension */
            dot = base + strlen(base);
        length = snprintf(name, name_size, "%.*s-%zu%s", (int)(dot - output_path), output_path,
                          sheet_index + 1, dot);
    }
    if (length < 0 || (size_t)length >= name_size)
        return ur_error_set(error, UR_ERROR_INPUT, "output name '%s' is too long", output_path);
    return UR_OK;
}

/* Sheet sizes and points must be finite: no format has a way to say NaN. */
static ur_status check_sheet(const ur_sheet *sheet, size_t index, ur_error *error)
{
    if (!(isfinite(sheet->width) && isfinite(sheet->height) && sheet->width > 0 &&
          sheet->height > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "sheet %zu has no usable size (%g x %g mm)",
                            index + 1, sheet->width, sheet->height);
    if (sheet->placement_count > 0 && !sheet->placements)
        return ur_error_set(error, UR_ERROR_INTERNAL, "sheet %zu has no placements array",
                            index + 1);
    return UR_OK;
}

/* Moves path onto the sheet into scratch (room for path->count points). */
static ur_status place_path(const ur_path *path, ur_transform2 transform, const char *piece_name,
                            ur_vec2 *scratch, ur_error *error)
{
    for (size_t i = 0; i < path->count; i++) {
        scratch[i] = ur_transform2_apply(transform, path->points[i]);
        if (!isfinite(scratch[i].x) || !isfinite(scratch[i].y))
            return ur_error_set(error, UR_ERROR_INTERNAL,
                                "piece '%s' has a point that is not a finite number", piece_name);
    }
    return UR_OK;
}

static ur_status write_path(const ur_writer *writer, void *state, const ur_path *path,
                            const ur_placement *placement, const ur_piece *piece, ur_vec2 *scratch,
                            ur_error *error)
{
    if (path->count == 0) /* nothing to cut */
        return UR_OK;
    ur_status status = place_path(path, placement->transform, piece->name, scratch, error);
    if (status != UR_OK)
        return status;
    return writer->path(state, path->op, scratch, path->count, path->closed, error);
}

/*
 * The paths of one operation for one placed piece.  paths[0] is the outer
 * outline, so it goes last: inner contours are cut while the part still
 * holds in the sheet.
 */
static ur_status write_piece_paths(const ur_writer *writer, void *state, ur_op op,
                                   const ur_placement *placement, const ur_piece *piece,
                                   ur_vec2 *scratch, ur_error *error)
{
    for (size_t i = 1; i <= piece->path_count; i++) {
        const ur_path *path = &piece->paths[i % piece->path_count];
        if (path->op != op)
            continue;
        ur_status status = write_path(writer, state, path, placement, piece, scratch, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status write_layer(const ur_writer *writer, void *state, ur_op op, const ur_sheet *sheet,
                             const ur_piece *pieces, ur_vec2 *scratch, ur_error *error)
{
    ur_status status = writer->begin_layer ? writer->begin_layer(state, op, error) : UR_OK;
    for (size_t i = 0; status == UR_OK && i < sheet->placement_count; i++) {
        const ur_placement *placement = &sheet->placements[i];
        status = write_piece_paths(writer, state, op, placement, &pieces[placement->piece_index],
                                   scratch, error);
    }
    if (status == UR_OK && writer->end_layer)
        status = writer->end_layer(state, op, error);
    return status;
}

static ur_status write_sheet(const ur_writer *writer, FILE *file, const ur_sheet *sheet,
                             const ur_piece *pieces, const ur_machine *machine,
                             const ur_output_options *options, ur_vec2 *scratch, ur_error *error)
{
    void *state = NULL;
    ur_status status =
        writer->begin_sheet(&state, file, sheet->width, sheet->height, machine, options, error);
    if (status != UR_OK)
        return status;
    for (size_t i = 0; i < UR_OP_COUNT; i++) {
        status = write_layer(writer, state, cut_order[i], sheet, pieces, scratch, error);
        if (status != UR_OK) {
            writer->discard_sheet(state);
            return status;
        }
    }
    return writer->end_sheet(state, error);
}

/* The most points any placed path has: the size of the one scratch buffer. */
static size_t longest_path(const ur_layout *layout, const ur_piece *pieces)
{
    size_t longest = 0;
    for (size_t s = 0; s < layout->sheet_count; s++) {
        const ur_sheet *sheet = &layout->sheets[s];
        for (size_t p = 0; p < sheet->placement_count; p++) {
            const ur_piece *piece = &pieces[sheet->placements[p].piece_index];
            for (size_t i = 0; i < piece->path_count; i++)
                if (piece->paths[i].count > longest)
                    longest = piece->paths[i].count;
        }
    }
    return longest;
}

/* Writes sheet index to a new temporary in files[index]. */
static ur_status write_sheet_file(const ur_writer *writer, const char *output_path,
                                  const ur_layout *layout, size_t index, const ur_piece *pieces,
                                  const ur_machine *machine, const ur_output_options *options,
                                  ur_vec2 *scratch, ur_atomic_file *files, ur_error *error)
{
    char name[NAME_SIZE];
    ur_status status = check_sheet(&layout->sheets[index], index, error);
    if (status == UR_OK)
        status =
            ur_sheet_file_name(output_path, index, layout->sheet_count, name, sizeof name, error);
    if (status == UR_OK)
        status = ur_atomic_open(&files[index], name, error);
    if (status == UR_OK)
        status = write_sheet(writer, files[index].stream, &layout->sheets[index], pieces, machine,
                             options, scratch, error);
    if (status == UR_OK)
        status = ur_atomic_close(&files[index], error);
    return status;
}

/*
 * All temporaries first, then every rename.  A rename failing half-way (the
 * directory removed or made read-only meanwhile) is the one case that can
 * leave some sheets new and some old; the message then says which file.
 */
static ur_status write_all(const ur_writer *writer, const char *output_path,
                           const ur_layout *layout, const ur_piece *pieces,
                           const ur_machine *machine, const ur_output_options *options,
                           ur_error *error)
{
    size_t count = layout->sheet_count;
    ur_atomic_file *files = ur_alloc_array(count, sizeof *files, error);
    ur_vec2 *scratch = ur_alloc_array(longest_path(layout, pieces), sizeof *scratch, error);
    ur_status status = files && scratch ? UR_OK : UR_ERROR_INTERNAL;
    for (size_t i = 0; status == UR_OK && i < count; i++)
        status = write_sheet_file(writer, output_path, layout, i, pieces, machine, options, scratch,
                                  files, error);
    for (size_t i = 0; status == UR_OK && i < count; i++)
        status = ur_atomic_commit(&files[i], error);
    for (size_t i = 0; files && i < count; i++)
        ur_atomic_discard(&files[i]); /* removes what was not committed */
    free(files);
    free(scratch);
    return status;
}

static ur_status check_arguments(const char *output_path, const ur_layout *layout,
                                 const ur_piece *pieces, const ur_machine *machine, ur_error *error)
{
    if (!output_path || !layout || !machine || (!pieces && layout->sheet_count > 0))
        return ur_error_set(error, UR_ERROR_INTERNAL, "cut file writer called without %s",
                            !output_path ? "an output path"
                            : !layout    ? "a layout"
                            : !machine   ? "a machine"
                                         : "pieces");
    if (layout->sheet_count == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': there is nothing to cut",
                            output_path);
    return UR_OK;
}

static ur_status write_output(const ur_writer *writer, const char *output_path,
                              const ur_layout *layout, const ur_piece *pieces,
                              const ur_machine *machine, const ur_output_options *options,
                              ur_error *error)
{
    ur_status status = check_arguments(output_path, layout, pieces, machine, error);
    if (status != UR_OK)
        return status;
    ur_output_options no_options = {NULL};
    return write_all(writer, output_path, layout, pieces, machine, options ? options : &no_options,
                     error);
}

ur_status ur_write_svg(const char *output_path, const ur_layout *layout, const ur_piece *pieces,
                       const ur_machine *machine, const ur_output_options *options, ur_error *error)
{
    return write_output(&ur_svg_writer, output_path, layout, pieces, machine, options, error);
}
