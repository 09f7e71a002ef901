/*
 * outputs.c: the cut files a job writes: the formats asked for (or the
 * output's extension), the DXF version and the preview's resolution, and
 * the report that names them, every one written all or nothing together
 * (one output set, unroll/out.h); and the summary's words for them.
 */
#include "stages.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/*
 * What the layout uses, for the summary line: "2 sheets of 600 x 400 mm",
 * "remnant 200 x 120 mm (sheet 1) and 1 sheet of 600 x 400 mm", ..., and
 * the offcut the last stock sheet leaves (", the last leaving an offcut of
 * 265 x 200 mm").  Stock sheets all have one size; remnants are named one
 * by one.
 */
void job_describe_sheets(const ur_layout *layout, char *text, size_t size)
{
    size_t used = 0, stock = 0;
    const ur_sheet *stock_sheet = NULL;
    text[0] = '\0';
    for (size_t s = 0; s < layout->sheet_count; s++) {
        const ur_sheet *sheet = &layout->sheets[s];
        if (!sheet->remnant) {
            stock++;
            stock_sheet = sheet;
            continue;
        }
        int n = c_snprintf(text + used, size - used, "%sremnant %g x %g mm (sheet %zu)",
                           used ? ", " : "", sheet->width, sheet->height, s + 1);
        if (n < 0 || (size_t)n >= size - used)
            return; /* cut short: the report has every sheet */
        used += (size_t)n;
    }
    if (stock_sheet || used == 0) {
        int n =
            c_snprintf(text + used, size - used, "%s%zu sheet%s of %g x %g mm", used ? " and " : "",
                       stock, stock == 1 ? "" : "s", stock_sheet ? stock_sheet->width : 0.0,
                       stock_sheet ? stock_sheet->height : 0.0);
        if (n < 0 || (size_t)n >= size - used)
            return;
        used += (size_t)n;
    }
    if (stock_sheet && stock_sheet->offcut_width >= 1) /* less is no offcut to keep */
        c_snprintf(text + used, size - used, ", the last leaving an offcut of %.0f x %g mm",
                   floor(stock_sheet->offcut_width), stock_sheet->height);
}

/* "812 mm" or "3.54 m": a cut length as a maker reads it. */
static void describe_length(double millimetres, char *text, size_t size)
{
    if (millimetres < 1000)
        c_snprintf(text, size, "%.0f mm", millimetres);
    else
        c_snprintf(text, size, "%.2f m", millimetres / 1000);
}

/* "45 s", "4 min 6 s" or "1 h 5 min": a machine time as a maker reads it. */
static void describe_time(double seconds, char *text, size_t size)
{
    long whole = lround(seconds);
    if (whole < 60)
        c_snprintf(text, size, "%ld s", whole);
    else if (whole < 3600)
        c_snprintf(text, size, "%ld min %ld s", whole / 60, whole % 60);
    else
        c_snprintf(text, size, "%ld h %ld min", whole / 3600, (whole % 3600 + 30) / 60);
}

void job_describe_cutting(const job_run *run, const ur_machine *machine, const ur_layout *layout,
                          const ur_piece *pieces, char *text, size_t size)
{
    double used = 0.0, room = 0.0, cut = 0.0, seconds = 0.0;
    for (size_t s = 0; s < layout->sheet_count; s++) {
        const ur_sheet *sheet = &layout->sheets[s];
        double area = sheet->width * sheet->height;
        used += ur_sheet_utilisation(sheet, pieces) * area;
        room += area;
        ur_cut_plan plan;
        ur_error error;
        /* As the report does: the files' order (ur_report_write's cutting_json). */
        if (ur_sheet_cut_plan(sheet, pieces, ur_operation_order(), !run->job.drawing_order, machine,
                              &plan, &error) != UR_OK) {
            text[0] = '\0';
            return;
        }
        ur_cut_plan_free(&plan);
        cut += plan.cut_length;
        seconds += plan.seconds;
    }
    char length[64], time[64];
    describe_length(cut, length, sizeof length);
    describe_time(seconds, time, sizeof time);
    c_snprintf(text, size, ", utilisation %.1f %%, cut %s in about %s",
               room > 0 ? 100 * used / room : 0.0, length, time);
}

void job_not_placed_warning(const job_run *run, const ur_layout *layout, const ur_piece *pieces)
{
    if (layout->not_placed_count == 0)
        return;
    char names[512] = "";
    size_t used = 0;
    for (size_t k = 0; k < layout->not_placed_count && used + 40 < sizeof names; k++)
        used += (size_t)c_snprintf(names + used, sizeof names - used, "%s%s", k ? ", " : "",
                                   pieces[layout->not_placed[k]].name);
    /* Only a limit on the sheets leaves pieces off: the warning says which. */
    size_t allowed = run->job.max_sheets > 0 ? (size_t)run->job.max_sheets : layout->sheet_count;
    job_warn_about(run, "sheets", "%s: warning: sheets %zu: %zu piece%s found no room: %s%s",
                   run->job.command, allowed, layout->not_placed_count,
                   layout->not_placed_count == 1 ? "" : "s", names,
                   used + 40 >= sizeof names ? ", ..." : "");
}

/* The formats to write: -o - without --format is an SVG, as a program reading a pipe expects. */
static unsigned formats_asked(const job_run *run)
{
    return run->job.formats == 0 && strcmp(run->job.output_path, "-") == 0 ? UR_FORMAT_SVG
                                                                           : run->job.formats;
}

double job_sheets_lower_bound(const ur_piece *pieces, size_t count, const ur_layout *layout,
                              double margin)
{
    const ur_sheet *stock = NULL;
    double area = 0.0;
    for (size_t k = 0; k < count; k++)
        area += pieces[k].measures.flat_area;
    for (size_t s = 0; s < layout->sheet_count; s++) {
        const ur_sheet *sheet = &layout->sheets[s];
        if (sheet->remnant) /* what a remnant holds, no stock sheet need */
            area -= fmax(0, (sheet->width - 2 * margin) * (sheet->height - 2 * margin));
        else if (!stock)
            stock = sheet;
        else if (sheet->width != stock->width || sheet->height != stock->height ||
                 strcmp(sheet->material, stock->material) != 0)
            return 0; /* stock of several kinds: no one bound */
    }
    double room = stock ? (stock->width - 2 * margin) * (stock->height - 2 * margin) : 0;
    return room > 0 ? fmax(0, ceil(area / room - 1e-9)) : 0;
}

/* A list of file names, grown as needed. */
typedef struct name_list {
    char (*names)[UR_OUTPUT_NAME_SIZE];
    size_t count;
} name_list;

static bool among(char (*names)[UR_OUTPUT_NAME_SIZE], size_t count, const char *name)
{
    for (size_t k = 0; k < count; k++)
        if (strcmp(names[k], name) == 0)
            return true;
    return false;
}

static bool add_name(name_list *list, const char *name)
{
    char(*grown)[UR_OUTPUT_NAME_SIZE] = realloc(list->names, (list->count + 1) * sizeof *grown);
    if (!grown)
        return false;
    list->names = grown;
    c_snprintf(list->names[list->count++], UR_OUTPUT_NAME_SIZE, "%s", name);
    return true;
}

/*
 * The files an output of sheet_count sheets would have that exist but
 * were not written now, into stale; whether any was new.
 */
static bool find_stale(const job_run *run, unsigned asked, size_t sheet_count,
                       const name_list *written, name_list *stale)
{
    char(*names)[UR_OUTPUT_NAME_SIZE] = NULL;
    size_t count = 0;
    ur_error ignored;
    if (ur_output_files(run->job.output_path, asked, sheet_count, &names, &count, &ignored) !=
        UR_OK)
        return false;
    bool found = false;
    for (size_t k = 0; k < count; k++) {
        if (among(written->names, written->count, names[k]) ||
            among(stale->names, stale->count, names[k]) || access(names[k], F_OK) != 0)
            continue;
        found = add_name(stale, names[k]);
        if (!found)
            break;
    }
    free(names);
    return found;
}

/*
 * Sheet files of an earlier run under the same name that this run did not
 * write over (net-3.svg after a run of two sheets, net.svg after one of
 * several, net-1.svg after one of one) are said: sent to the cutter with
 * the others they would be cut too.  They are left where they are: they
 * may be the maker's own.
 */
static void warn_of_stale_sheets(const job_run *run, unsigned asked, size_t sheet_count,
                                 const name_list *written)
{
    if (run->job.quiet || strcmp(run->job.output_path, "-") == 0)
        return;
    name_list stale = {NULL, 0};
    if (sheet_count > 1)
        find_stale(run, asked, 1, written, &stale);
    for (size_t more = sheet_count + 1; more < sheet_count + 10000; more++)
        if (!find_stale(run, asked, more, written, &stale))
            break;
    char more[48] = "";
    if (stale.count > 2)
        c_snprintf(more, sizeof more, " and %zu more", stale.count - 2);
    if (stale.count == 1)
        job_warn(run,
                 "%s: %s is left from an earlier run under this name and is not a sheet of this "
                 "one: remove it before sending the files to the cutter",
                 run->job.command, stale.names[0]);
    else if (stale.count > 1)
        job_warn(run,
                 "%s: %s%s%s%s are left from an earlier run under this name and are not sheets "
                 "of this one: remove them before sending the files to the cutter",
                 run->job.command, stale.names[0], stale.count == 2 ? " and " : ", ",
                 stale.names[1], more);
    free(stale.names);
}

ur_status job_write_outputs(const job_run *run, const ur_machine *machine, const ur_layout *layout,
                            const ur_piece *pieces, size_t count, ur_report_context *context,
                            ur_error *error)
{
    char title[128];
    c_snprintf(title, sizeof title, "unroll %s", run->job.command);
    ur_output_options output = {title, run->job.context};
    ur_format_options formats = {.job_name =
                                     run->job.job_name ? run->job.job_name : run->job.surface,
                                 .dxf_version = (ur_dxf_version)run->job.dxf_version,
                                 .dpi = run->job.dpi,
                                 .drawing_order = run->job.drawing_order};
    unsigned asked = formats_asked(run);
    if (run->job.roll_width <= 0)
        context->sheets_lower_bound = job_sheets_lower_bound(
            pieces, count, layout, run->job.margin >= 0 ? run->job.margin : machine->margin);
    char(*names)[UR_OUTPUT_NAME_SIZE] = NULL;
    size_t name_count = 0;
    ur_output_set_begin(run->job.context); /* the cut files and the report appear together */
    ur_status status = ur_output_files(run->job.output_path, asked, layout->sheet_count, &names,
                                       &name_count, error);
    if (status == UR_OK)
        status = ur_write_outputs(run->job.output_path, asked, layout, pieces, machine, &output,
                                  &formats, error);
    const char **outputs = NULL;
    if (status == UR_OK && run->job.report_path) {
        outputs = ur_alloc_array(name_count + 1, sizeof *outputs, error);
        if (!outputs)
            status = UR_ERROR_MEMORY;
        for (size_t k = 0; outputs && k < name_count; k++)
            outputs[k] = names[k];
        context->outputs = outputs;
        context->drawing_order = run->job.drawing_order;
        if (status == UR_OK)
            status = ur_report_write(run->job.report_path, context, pieces, count, layout,
                                     run->job.context, error);
    }
    free(outputs);
    ur_status ended = ur_output_set_end(run->job.context, status == UR_OK, error);
    if (status == UR_OK && ended == UR_OK)
        warn_of_stale_sheets(run, asked, layout->sheet_count, &(name_list){names, name_count});
    free(names);
    return status == UR_OK ? ended : status;
}
