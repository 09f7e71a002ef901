/*
 * output.c: the driver behind every cut-file format.
 *
 * It names the files (one per sheet, or one for a format of pages), walks
 * the layout in cutting order, moves each path from piece to sheet
 * coordinates and hands it to a format (writer.h), and makes the whole
 * output atomic, across formats too: every file is written to its own
 * temporary first, and only when all of them are complete are they renamed
 * into place.  On any error every temporary is removed and the files
 * already on disk are left as they were.
 */
#include "writer.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "../base/atomic.h"
#include "../base/c_locale.h"

/*
 * Cutting order: engrave and mark while the sheet is still whole, then fold
 * lines and relief cuts, and the through cuts last so that no part drops out
 * or shifts before everything on it is done.
 */
_Static_assert(UR_OP_COUNT == 6, "put every operation into cut_order");
static const ur_op cut_order[UR_OP_COUNT] = {UR_OP_ENGRAVE,      UR_OP_MARK, UR_OP_SCORE,
                                             UR_OP_SCORE_VALLEY, UR_OP_KERF, UR_OP_CUT};

void write_kerf_note(const write_job *job, size_t sheet, char *text)
{
    text[0] = '\0';
    double kerf = -1; /* none placed yet */
    for (size_t s = 0; s < job->layout->sheet_count; s++) {
        if (sheet != WRITE_ALL_SHEETS && s != sheet)
            continue;
        const ur_sheet *on = &job->layout->sheets[s];
        for (size_t p = 0; p < on->placement_count; p++) {
            double this_one = job->pieces[on->placements[p].piece_index].kerf_compensated;
            if (kerf >= 0 && this_one != kerf)
                return; /* pieces compensated differently: the file says nothing */
            kerf = this_one;
        }
    }
    if (kerf > 0 && isfinite(kerf))
        c_snprintf(text, WRITE_KERF_NOTE_SIZE, UR_KERF_NOTE "%.6g mm", kerf);
}

/* Every format, in the order their files are written; a new format adds a line. */
static const struct {
    ur_format format;
    const format_writer *writer;
} formats_known[] = {
    {UR_FORMAT_SVG, &svg_writer},
    {UR_FORMAT_DXF, &dxf_writer},
    {UR_FORMAT_PDF, &pdf_writer},
    {UR_FORMAT_PNG, &png_writer},
};
enum { FORMAT_COUNT = sizeof formats_known / sizeof *formats_known };

const ur_op *ur_operation_order(void)
{
    return cut_order;
}

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
        length = c_snprintf(name, name_size, "%s", output_path);
    } else {
        /* The extension is that of the base name: "dir.v2/net" has none. */
        const char *slash = strrchr(output_path, '/');
        const char *base = slash ? slash + 1 : output_path;
        const char *dot = strrchr(base, '.');
        if (!dot || dot == base) /* ".hidden" is a name, not an extension */
            dot = base + strlen(base);
        length = c_snprintf(name, name_size, "%.*s-%zu%s", (int)(dot - output_path), output_path,
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

/*
 * A closed path turned to start in the middle of its longest edge: that
 * point, then the edge's end and round (scratch holds count + 1 points).
 */
static size_t start_on_straight(const ur_path *path, ur_vec2 *scratch)
{
    size_t n = path->count, i = ur_path_start(path);
    ur_vec2 *turned = scratch + n + 1; /* the second half of scratch */
    turned[0] = ur_vec2_scale(ur_vec2_add(scratch[i], scratch[(i + 1) % n]), 0.5);
    for (size_t k = 0; k < n; k++)
        turned[k + 1] = scratch[(i + 1 + k) % n];
    memcpy(scratch, turned, (n + 1) * sizeof *scratch);
    return n + 1;
}

static ur_status write_path(const format_writer *writer, void *state, const ur_path *path,
                            const ur_placement *placement, const ur_piece *piece, ur_vec2 *scratch,
                            bool ordered, ur_error *error)
{
    if (path->count == 0) /* nothing to cut */
        return UR_OK;
    ur_status status = place_path(path, placement->transform, piece->name, scratch, error);
    if (status != UR_OK)
        return status;
    size_t count = path->count;
    if (ordered && path->closed && count >= 3)
        count = start_on_straight(path, scratch);
    /* A placement turns and moves, never mirrors: the arc keeps its radius and its sweep. */
    ur_path_circle circle = path->circle;
    circle.centre = ur_transform2_apply(placement->transform, circle.centre);
    bool round = circle.radius > 0 && isfinite(circle.radius) && isfinite(circle.centre.x) &&
                 isfinite(circle.centre.y) && (path->closed || count >= 2);
    return writer->path(state, path->op, scratch, count, path->closed, round ? &circle : NULL,
                        error);
}

/*
 * The paths of one operation for one placed piece.  paths[0] is the outer
 * outline, so it goes last: inner contours are cut while the part still
 * holds in the sheet.
 */
static ur_status write_piece_paths(const format_writer *writer, void *state, ur_op op,
                                   const ur_placement *placement, const ur_piece *piece,
                                   ur_vec2 *scratch, bool ordered, ur_error *error)
{
    for (size_t i = 1; i <= piece->path_count; i++) {
        const ur_path *path = &piece->paths[i % piece->path_count];
        if (path->op != op)
            continue;
        ur_status status =
            write_path(writer, state, path, placement, piece, scratch, ordered, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status write_layer(const format_writer *writer, void *state, ur_op op,
                             const ur_sheet *sheet, const ur_piece *pieces, const ur_cut_plan *plan,
                             bool ordered, ur_vec2 *scratch, ur_error *error)
{
    ur_status status = writer->begin_layer ? writer->begin_layer(state, op, error) : UR_OK;
    for (size_t i = 0; status == UR_OK && i < sheet->placement_count; i++) {
        const ur_placement *placement = &sheet->placements[plan->order[i]];
        status = write_piece_paths(writer, state, op, placement, &pieces[placement->piece_index],
                                   scratch, ordered, error);
    }
    if (status == UR_OK && writer->end_layer)
        status = writer->end_layer(state, op, error);
    return status;
}

/* The pieces placed on the sheet, before any layer: formats that fill or label them. */
static ur_status write_pieces(const format_writer *writer, void *state, const ur_sheet *sheet,
                              const ur_piece *pieces, ur_error *error)
{
    ur_status status = UR_OK;
    for (size_t i = 0; writer->piece && status == UR_OK && i < sheet->placement_count; i++) {
        const ur_placement *placement = &sheet->placements[i];
        status = writer->piece(state, &pieces[placement->piece_index], placement, error);
    }
    return status;
}

static ur_status write_sheet(const format_writer *writer, void *document, FILE *file, size_t index,
                             const write_job *job, ur_vec2 *scratch, ur_error *error)
{
    const ur_sheet *sheet = &job->layout->sheets[index];
    void *state = NULL;
    ur_status status = writer->begin_sheet(&state, document, file, index, job, error);
    if (status != UR_OK)
        return status;
    status = write_pieces(writer, state, sheet, job->pieces, error);
    bool ordered = !job->options->drawing_order;
    ur_cut_plan plan = {NULL, 0, 0, 0};
    if (status == UR_OK)
        status =
            ur_sheet_cut_plan(sheet, job->pieces, cut_order, ordered, job->machine, &plan, error);
    for (size_t i = 0; status == UR_OK && i < UR_OP_COUNT; i++)
        status = write_layer(writer, state, cut_order[i], sheet, job->pieces, &plan, ordered,
                             scratch, error);
    ur_cut_plan_free(&plan);
    if (status != UR_OK) {
        writer->discard_sheet(state);
        return status;
    }
    return writer->end_sheet(state, error);
}

/* The most points any placed path has: the size of the one scratch buffer. */
static size_t longest_path(const ur_layout *layout, const ur_piece *pieces)
{
    size_t longest = 1;
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

/* One target of a write: a format and the name its file or files are numbered from. */
typedef struct target {
    const format_writer *writer;
    char path[NAME_SIZE];
} target;

/* How many files a target makes. */
static size_t file_count(const target *t, const ur_layout *layout)
{
    return t->writer->one_file ? 1 : layout->sheet_count;
}

/* Every sheet of a one-file format into one temporary, *file. */
static ur_status write_document(const target *t, const write_job *job, ur_vec2 *scratch,
                                atomic_file *file, ur_error *error)
{
    const format_writer *writer = t->writer;
    ur_status status = atomic_open(file, t->path, job->options->context, error);
    void *document = NULL;
    if (status == UR_OK && writer->begin_document)
        status = writer->begin_document(&document, job, error);
    for (size_t i = 0; status == UR_OK && i < job->layout->sheet_count; i++)
        status = write_sheet(writer, document, NULL, i, job, scratch, error);
    if (status != UR_OK) {
        if (document && writer->discard_document)
            writer->discard_document(document);
        return status;
    }
    status = writer->end_document ? writer->end_document(document, file->stream, error) : UR_OK;
    /* a write error (or bad input): the format's message does not name the file */
    if (status == UR_ERROR_IO || status == UR_ERROR_INPUT)
        ur_error_prefix(error, "%s: ", t->path);
    return status == UR_OK ? atomic_close(file, error) : status;
}

/* Each sheet into its own temporary, files[0 .. sheet_count - 1]. */
static ur_status write_sheets(const target *t, const write_job *job, ur_vec2 *scratch,
                              atomic_file *files, ur_error *error)
{
    const format_writer *writer = t->writer;
    void *document = NULL;
    ur_status status =
        writer->begin_document ? writer->begin_document(&document, job, error) : UR_OK;
    size_t count = job->layout->sheet_count;
    for (size_t i = 0; status == UR_OK && i < count; i++) {
        char name[NAME_SIZE];
        status = ur_sheet_file_name(t->path, i, count, name, sizeof name, error);
        if (status == UR_OK)
            status = atomic_open(&files[i], name, job->options->context, error);
        if (status == UR_OK) {
            status = write_sheet(writer, document, files[i].stream, i, job, scratch, error);
            if (status == UR_ERROR_IO || status == UR_ERROR_INPUT) /* as in write_document */
                ur_error_prefix(error, "%s: ", name);
        }
        if (status == UR_OK)
            status = atomic_close(&files[i], error);
    }
    if (status == UR_OK && writer->end_document)
        return writer->end_document(document, NULL, error);
    if (document && writer->discard_document)
        writer->discard_document(document);
    return status;
}

/*
 * All temporaries of every target first, then every rename.  A rename
 * failing half-way (the directory removed or made read-only meanwhile) is
 * the one case that can leave some files new and some old; the message then
 * says which file.
 */
static ur_status write_all(const target *targets, size_t target_count, const write_job *job,
                           ur_error *error)
{
    size_t count = 0;
    for (size_t t = 0; t < target_count; t++)
        count += file_count(&targets[t], job->layout);
    atomic_file *files = ur_alloc_array(count, sizeof *files, error);
    ur_vec2 *scratch = files ? ur_alloc_array(2 * (longest_path(job->layout, job->pieces) + 1),
                                              sizeof *scratch, error)
                             : NULL;
    ur_status status = files && scratch ? UR_OK : UR_ERROR_MEMORY;
    for (size_t t = 0, first = 0; status == UR_OK && t < target_count; t++) {
        status = targets[t].writer->one_file
                     ? write_document(&targets[t], job, scratch, &files[first], error)
                     : write_sheets(&targets[t], job, scratch, &files[first], error);
        first += file_count(&targets[t], job->layout);
    }
    if (status == UR_OK)
        status = atomic_commit_all(files, count, error);
    for (size_t i = 0; files && i < count; i++)
        atomic_discard(&files[i]); /* removes what was not committed */
    free(files);
    free(scratch);
    return status;
}

/* A stream that is not ours to close: the document, or the one sheet, to it. */
static ur_status write_stream(const target *t, const write_job *job, FILE *stream, ur_error *error)
{
    const char *where = stream == stdout ? "standard output" : "a stream";
    if (!t->writer->one_file && job->layout->sheet_count != 1)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "cannot write %zu sheets of %s to %s: name a file",
                            job->layout->sheet_count, t->writer->format, where);
    ur_vec2 *scratch =
        ur_alloc_array(2 * (longest_path(job->layout, job->pieces) + 1), sizeof *scratch, error);
    if (!scratch)
        return UR_ERROR_MEMORY;
    const format_writer *writer = t->writer;
    void *document = NULL;
    ur_status status =
        writer->begin_document ? writer->begin_document(&document, job, error) : UR_OK;
    FILE *file = writer->one_file ? NULL : stream;
    for (size_t i = 0; status == UR_OK && i < job->layout->sheet_count; i++)
        status = write_sheet(writer, document, file, i, job, scratch, error);
    if (status == UR_OK && writer->end_document)
        status = writer->end_document(document, writer->one_file ? stream : NULL, error);
    else if (document && writer->discard_document)
        writer->discard_document(document);
    free(scratch);
    if (status == UR_OK && (fflush(stream) != 0 || ferror(stream)))
        status =
            ur_error_set(error, UR_ERROR_IO, "cannot write the %s to %s", writer->format, where);
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
    if (!layout->sheets)
        return ur_error_set(error, UR_ERROR_INTERNAL, "the layout has no sheets array");
    for (size_t i = 0; i < layout->sheet_count; i++) {
        ur_status status = check_sheet(&layout->sheets[i], i, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status check_options(const write_settings *options, ur_error *error)
{
    if (options->dxf_version != UR_DXF_R12 && options->dxf_version != UR_DXF_R2000)
        return ur_error_set(error, UR_ERROR_INPUT, "unknown DXF version %d",
                            (int)options->dxf_version);
    if (!(options->dpi > 0) || !isfinite(options->dpi))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the resolution of the preview must be a positive number of dots per "
                            "inch, not %g",
                            options->dpi);
    return UR_OK;
}

/* Checks everything, fills in the defaults, then writes to stream (when not NULL) or the files. */
static ur_status write_targets(const target *targets, size_t target_count, FILE *stream,
                               const ur_layout *layout, const ur_piece *pieces,
                               const ur_machine *machine, const ur_output_options *options,
                               const ur_format_options *format_options, ur_error *error)
{
    write_settings chosen = {NULL, NULL, UR_DXF_R12, UR_PNG_DPI, false, NULL};
    if (options) {
        chosen.title = options->title;
        chosen.context = options->context;
    }
    if (format_options) {
        chosen.job_name = format_options->job_name;
        chosen.dxf_version = format_options->dxf_version;
        chosen.dpi = format_options->dpi == 0 ? UR_PNG_DPI : format_options->dpi;
        chosen.drawing_order = format_options->drawing_order;
    }
    ur_status status = check_arguments(targets[0].path, layout, pieces, machine, error);
    if (status == UR_OK)
        status = check_options(&chosen, error);
    if (status != UR_OK)
        return status;
    write_job job = {layout, pieces, machine, &chosen};
    if (stream)
        return write_stream(&targets[0], &job, stream, error);
    if (strcmp(targets[0].path, "-") == 0)
        return write_stream(&targets[0], &job, stdout, error);
    return write_all(targets, target_count, &job, error);
}

/* One format, its file or files named from output_path as it is. */
static ur_status write_one(const format_writer *writer, const char *output_path,
                           const ur_layout *layout, const ur_piece *pieces,
                           const ur_machine *machine, const ur_output_options *options,
                           const ur_format_options *format_options, ur_error *error)
{
    target t = {writer, ""};
    if (output_path && c_snprintf(t.path, sizeof t.path, "%s", output_path) >= (int)sizeof t.path)
        return ur_error_set(error, UR_ERROR_INPUT, "output name '%s' is too long", output_path);
    if (!output_path)
        return check_arguments(NULL, layout, pieces, machine, error);
    return write_targets(&t, 1, NULL, layout, pieces, machine, options, format_options, error);
}

ur_status ur_write_svg(const char *output_path, const ur_layout *layout, const ur_piece *pieces,
                       const ur_machine *machine, const ur_output_options *options, ur_error *error)
{
    static const ur_format_options as_drawn = {.drawing_order = true};
    return write_one(&svg_writer, output_path, layout, pieces, machine, options, &as_drawn, error);
}

ur_status ur_write_dxf(const char *output_path, const ur_layout *layout, const ur_piece *pieces,
                       const ur_machine *machine, const ur_output_options *options,
                       const ur_format_options *format_options, ur_error *error)
{
    return write_one(&dxf_writer, output_path, layout, pieces, machine, options, format_options,
                     error);
}

ur_status ur_write_pdf(const char *output_path, const ur_layout *layout, const ur_piece *pieces,
                       const ur_machine *machine, const ur_output_options *options,
                       const ur_format_options *format_options, ur_error *error)
{
    return write_one(&pdf_writer, output_path, layout, pieces, machine, options, format_options,
                     error);
}

ur_status ur_write_png(const char *output_path, const ur_layout *layout, const ur_piece *pieces,
                       const ur_machine *machine, const ur_output_options *options,
                       const ur_format_options *format_options, ur_error *error)
{
    return write_one(&png_writer, output_path, layout, pieces, machine, options, format_options,
                     error);
}

/* ---- Formats by name and extension -------------------------------------- */

const char *ur_format_name(ur_format format)
{
    for (size_t i = 0; i < FORMAT_COUNT; i++)
        if (formats_known[i].format == format)
            return formats_known[i].writer->extension;
    return "unknown";
}

ur_format ur_format_from_name(const char *name)
{
    for (size_t i = 0; name && i < FORMAT_COUNT; i++)
        if (strcasecmp(name, formats_known[i].writer->extension) == 0)
            return formats_known[i].format;
    return 0;
}

/* The extension of path's base name, without the dot; NULL for none. */
static const char *extension_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    return dot && dot != base ? dot + 1 : NULL; /* ".hidden" is a name, not an extension */
}

ur_format ur_format_from_path(const char *path)
{
    return path ? ur_format_from_name(extension_of(path)) : 0;
}

ur_status ur_formats_parse(const char *list, unsigned *formats, ur_error *error)
{
    *formats = 0;
    const char *at = list ? list : "";
    do {
        size_t length = strcspn(at, ",");
        char name[8] = "";
        if (length < sizeof name) {
            memcpy(name, at, length);
            name[length] = '\0';
        }
        ur_format format = length < sizeof name ? ur_format_from_name(name) : 0;
        if (!format)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "unknown format '%.*s' in '%s': the formats are svg, dxf, pdf "
                                "and png",
                                (int)length, at, list ? list : "");
        *formats |= (unsigned)format;
        at += length;
    } while (*at++ == ',');
    return UR_OK;
}

/* ---- Several formats at once -------------------------------------------- */

/* The stem every format's name is made from: path less an extension that names a format. */
static ur_status make_targets(const char *path, unsigned formats, target *targets, size_t *count,
                              ur_error *error)
{
    ur_format named = ur_format_from_path(path);
    size_t stem = named ? strlen(path) - strlen(extension_of(path)) - 1 : strlen(path);
    *count = 0;
    for (size_t i = 0; i < FORMAT_COUNT; i++) {
        if (!(formats & (unsigned)formats_known[i].format))
            continue;
        target *t = &targets[(*count)++];
        t->writer = formats_known[i].writer;
        int length = strcmp(path, "-") == 0 || formats_known[i].format == named
                         ? c_snprintf(t->path, sizeof t->path, "%s", path)
                         : c_snprintf(t->path, sizeof t->path, "%.*s.%s", (int)stem, path,
                                      t->writer->extension);
        if (length < 0 || (size_t)length >= sizeof t->path)
            return ur_error_set(error, UR_ERROR_INPUT, "output name '%s' is too long", path);
    }
    return UR_OK;
}

static ur_status check_formats(const char *path, unsigned *formats, ur_error *error)
{
    ur_format named = ur_format_from_path(path);
    if (*formats & ~(unsigned)UR_FORMAT_ALL)
        return ur_error_set(error, UR_ERROR_INTERNAL, "unknown format bits %#x", *formats);
    if (*formats == 0 && !named)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "cannot tell the format of '%s': end it in .svg, .dxf, .pdf or .png, "
                            "or name the format",
                            path);
    if (*formats == 0)
        *formats = (unsigned)named;
    if (named && !(*formats & (unsigned)named))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' names a %s file, which is not one of the formats asked for", path,
                            ur_format_name(named));
    if (strcmp(path, "-") == 0 && (*formats & (*formats - 1)) != 0)
        return ur_error_set(error, UR_ERROR_INPUT, "standard output takes one format, not several");
    return UR_OK;
}

ur_status ur_write_outputs(const char *path, unsigned formats, const ur_layout *layout,
                           const ur_piece *pieces, const ur_machine *machine,
                           const ur_output_options *options,
                           const ur_format_options *format_options, ur_error *error)
{
    if (!path)
        return check_arguments(NULL, layout, pieces, machine, error);
    ur_status status = check_formats(path, &formats, error);
    target targets[FORMAT_COUNT];
    size_t count = 0;
    if (status == UR_OK)
        status = make_targets(path, formats, targets, &count, error);
    if (status != UR_OK)
        return status;
    return write_targets(targets, count, NULL, layout, pieces, machine, options, format_options,
                         error);
}

ur_status ur_write_stream(FILE *stream, ur_format format, const ur_layout *layout,
                          const ur_piece *pieces, const ur_machine *machine,
                          const ur_output_options *options, const ur_format_options *format_options,
                          ur_error *error)
{
    target t = {NULL, "(stream)"};
    for (size_t i = 0; i < FORMAT_COUNT; i++)
        if (formats_known[i].format == format)
            t.writer = formats_known[i].writer;
    if (!stream || !t.writer)
        return ur_error_set(error, UR_ERROR_INTERNAL, "stream writer called without %s",
                            stream ? "one known format" : "a stream");
    return write_targets(&t, 1, stream, layout, pieces, machine, options, format_options, error);
}

ur_status ur_output_files(const char *path, unsigned formats, size_t sheet_count,
                          char (**names)[UR_OUTPUT_NAME_SIZE], size_t *count, ur_error *error)
{
    *names = NULL;
    *count = 0;
    ur_status status = check_formats(path, &formats, error);
    target targets[FORMAT_COUNT];
    size_t target_count = 0;
    if (status == UR_OK)
        status = make_targets(path, formats, targets, &target_count, error);
    size_t total = 0;
    for (size_t t = 0; status == UR_OK && t < target_count; t++)
        total += targets[t].writer->one_file ? 1 : sheet_count;
    if (status == UR_OK) {
        *names = ur_alloc_array(total, sizeof **names, error);
        if (!*names)
            status = UR_ERROR_MEMORY;
    }
    for (size_t t = 0; status == UR_OK && t < target_count; t++) {
        size_t files = targets[t].writer->one_file ? 1 : sheet_count;
        for (size_t s = 0; status == UR_OK && s < files; s++)
            status = ur_sheet_file_name(targets[t].path, s, files, (*names)[(*count)++],
                                        UR_OUTPUT_NAME_SIZE, error);
    }
    if (status != UR_OK) {
        free(*names);
        *names = NULL;
        *count = 0;
    }
    return status;
}
