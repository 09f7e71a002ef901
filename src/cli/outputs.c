/*
 * outputs.c: the cut files a job writes: the formats asked for (--format,
 * or -o's extension), the DXF version and the preview's resolution, and
 * the report that names them, every one written all or nothing together
 * (one output set, unroll/out.h).
 */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool cli_parse_formats(cli_job *job, const char *value)
{
    ur_error error;
    if (ur_formats_parse(value, &job->formats, &error) == UR_OK)
        return true;
    cli_message("%s: --format: %s (give svg, dxf, pdf or png, or several: svg,dxf)", job->command,
                error.message);
    return false;
}

bool cli_parse_dxf_version(cli_job *job, const char *value)
{
    if (strcmp(value, "12") == 0 || strcmp(value, "R12") == 0) {
        job->dxf_version = UR_DXF_R12;
        return true;
    }
    if (strcmp(value, "2000") == 0 || strcmp(value, "R2000") == 0) {
        job->dxf_version = UR_DXF_R2000;
        return true;
    }
    cli_message("%s: --dxf-version: '%s' is not 12 or 2000", job->command, value);
    return false;
}

bool cli_parse_dpi(cli_job *job, const char *value)
{
    char *end = NULL;
    errno = 0;
    double dpi = strtod(value, &end);
    if (end == value || *end != '\0' || !isfinite(dpi) || dpi < 10 || dpi > 2400) {
        cli_message("%s: --dpi: '%s' is not a resolution from 10 to 2400 dots per inch",
                    job->command, value);
        return false;
    }
    job->dpi = dpi;
    return true;
}

bool cli_parse_order(cli_job *job, const char *value)
{
    job->drawing_order = strcmp(value, "none") == 0;
    if (job->drawing_order || strcmp(value, "cut") == 0)
        return true;
    cli_message("%s: --order: '%s' is not cut or none", job->command, value);
    return false;
}

bool cli_parse_rotations(cli_job *job, const char *value)
{
    long count;
    if (!cli_whole_number(value, 1, 360, &count)) {
        cli_message("%s: --rotations: '%s' is not a count of turns from 1 to 360", job->command,
                    value);
        return false;
    }
    job->rotations = count;
    return true;
}

bool cli_parse_roll(cli_job *job, const char *value)
{
    char *end = NULL;
    double width = strtod(value, &end);
    if (end == value || *end != '\0' || !(width > 0) || !(width <= UR_LENGTH_MAX)) {
        cli_message("%s: --roll: '%s' is not a width in mm up to %g", job->command, value,
                    UR_LENGTH_MAX);
        return false;
    }
    job->roll_width = width;
    return true;
}

bool cli_parse_sheet_count(cli_job *job, const char *value)
{
    long count;
    if (!cli_whole_number(value, 1, 10000, &count)) {
        cli_message("%s: --sheets: '%s' is not a count of sheets from 1 to 10000", job->command,
                    value);
        return false;
    }
    job->max_sheets = count;
    return true;
}

/*
 * What the layout uses, for the summary line: "2 sheets of 600 x 400 mm",
 * "remnant 200 x 120 mm (sheet 1) and 1 sheet of 600 x 400 mm", ..., and
 * the offcut the last stock sheet leaves (", the last leaving an offcut of
 * 265 x 200 mm").  Stock sheets all have one size; remnants are named one
 * by one.
 */
void cli_describe_sheets(const ur_layout *layout, char *text, size_t size)
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
        int n = snprintf(text + used, size - used, "%sremnant %g x %g mm (sheet %zu)",
                         used ? ", " : "", sheet->width, sheet->height, s + 1);
        if (n < 0 || (size_t)n >= size - used)
            return; /* cut short: the report has every sheet */
        used += (size_t)n;
    }
    if (stock_sheet || used == 0) {
        int n =
            snprintf(text + used, size - used, "%s%zu sheet%s of %g x %g mm", used ? " and " : "",
                     stock, stock == 1 ? "" : "s", stock_sheet ? stock_sheet->width : 0.0,
                     stock_sheet ? stock_sheet->height : 0.0);
        if (n < 0 || (size_t)n >= size - used)
            return;
        used += (size_t)n;
    }
    if (stock_sheet && stock_sheet->offcut_width >= 1) /* less is no offcut to keep */
        snprintf(text + used, size - used, ", the last leaving an offcut of %.0f x %g mm",
                 floor(stock_sheet->offcut_width), stock_sheet->height);
}

/* "812 mm" or "3.54 m": a cut length as a maker reads it. */
static void describe_length(double millimetres, char *text, size_t size)
{
    if (millimetres < 1000)
        snprintf(text, size, "%.0f mm", millimetres);
    else
        snprintf(text, size, "%.2f m", millimetres / 1000);
}

/* "45 s", "4 min 6 s" or "1 h 5 min": a machine time as a maker reads it. */
static void describe_time(double seconds, char *text, size_t size)
{
    long whole = lround(seconds);
    if (whole < 60)
        snprintf(text, size, "%ld s", whole);
    else if (whole < 3600)
        snprintf(text, size, "%ld min %ld s", whole / 60, whole % 60);
    else
        snprintf(text, size, "%ld h %ld min", whole / 3600, (whole % 3600 + 30) / 60);
}

void cli_describe_cutting(const cli_job *job, const ur_machine *machine, const ur_layout *layout,
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
        if (ur_sheet_cut_plan(sheet, pieces, ur_operation_order(), !job->drawing_order, machine,
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
    snprintf(text, size, ", utilisation %.1f %%, cut %s in about %s",
             room > 0 ? 100 * used / room : 0.0, length, time);
}

/* --remnant WxH, repeatable: one more remnant sheet, filled before stock. */
bool cli_parse_remnant(cli_job *job, const char *value)
{
    char *end = NULL;
    double width = strtod(value, &end);
    double height = end != value && (*end == 'x' || *end == 'X') ? strtod(end + 1, &end) : NAN;
    if (*end != '\0' || !isfinite(width) || !isfinite(height) || !(width > 0) || !(height > 0)) {
        cli_message("%s: --remnant: '%s' is not WIDTHxHEIGHT in mm, e.g. 300x200", job->command,
                    value);
        return false;
    }
    if (job->remnant_count == CLI_MAX_REMNANTS) {
        cli_message("%s: --remnant: more than %d remnants", job->command, CLI_MAX_REMNANTS);
        return false;
    }
    job->remnants[job->remnant_count++] = (ur_remnant){width, height};
    return true;
}

bool cli_parse_nest_time(cli_job *job, const char *value)
{
    char *end = NULL;
    double seconds = strtod(value, &end);
    if (end == value || *end != '\0' || !isfinite(seconds) || seconds < 0 || seconds > 3600) {
        cli_message("%s: --nest-time: '%s' is not a number of seconds from 0 to 3600", job->command,
                    value);
        return false;
    }
    job->nest_time = seconds;
    return true;
}

bool cli_parse_threads(cli_job *job, const char *value)
{
    long threads;
    if (!cli_whole_number(value, 1, UR_NEST_MAX_THREADS, &threads)) {
        cli_message("%s: --threads: '%s' is not a whole number from 1 to %d", job->command, value,
                    UR_NEST_MAX_THREADS);
        return false;
    }
    job->threads = (size_t)threads;
    return true;
}

bool cli_parse_seed(cli_job *job, const char *value)
{
    char *end = NULL;
    errno = 0;
    unsigned long long seed = strtoull(value, &end, 10);
    if (end == value || *end != '\0' || errno != 0 || value[0] == '-') {
        cli_message("%s: --seed: '%s' is not a whole number of 0 or more", job->command, value);
        return false;
    }
    job->seed = seed;
    return true;
}

/* The most bytes a job name may have: it is a title, not a description. */
enum { JOB_NAME_MAX = 200 };

bool cli_parse_job_name(cli_job *job, const char *value)
{
    size_t length = strlen(value);
    bool control = false;
    for (const unsigned char *c = (const unsigned char *)value; *c; c++)
        control = control || *c < 0x20 || *c == 0x7F;
    if (length == 0 || length > JOB_NAME_MAX || control) {
        cli_message("%s: --job-name: give a name of 1 to %d bytes without control characters",
                    job->command, JOB_NAME_MAX);
        return false;
    }
    job->job_name = value;
    return true;
}

void cli_not_placed_warning(const cli_job *job, const ur_layout *layout, const ur_piece *pieces)
{
    if (layout->not_placed_count == 0)
        return;
    char names[512] = "";
    size_t used = 0;
    for (size_t k = 0; k < layout->not_placed_count && used + 40 < sizeof names; k++)
        used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", k ? ", " : "",
                                 pieces[layout->not_placed[k]].name);
    cli_message("%s: warning: %zu piece%s found no room on the %zu sheet%s allowed (--sheets): "
                "%s%s",
                job->command, layout->not_placed_count, layout->not_placed_count == 1 ? "" : "s",
                layout->sheet_count, layout->sheet_count == 1 ? "" : "s", names,
                used + 40 >= sizeof names ? ", ..." : "");
}

/* The formats to write: -o - without --format is an SVG, as a program reading a pipe expects. */
static unsigned formats_asked(const cli_job *job)
{
    return job->formats == 0 && strcmp(job->output_path, "-") == 0 ? UR_FORMAT_SVG : job->formats;
}

bool cli_check_output(const cli_job *job)
{
    char(*names)[UR_OUTPUT_NAME_SIZE] = NULL;
    size_t count = 0;
    ur_error error;
    ur_status status =
        ur_output_files(job->output_path, formats_asked(job), 1, &names, &count, &error);
    free(names);
    if (status != UR_OK)
        cli_message("%s: -o: %s", job->command, error.message);
    return status == UR_OK;
}

double cli_sheets_lower_bound(const ur_piece *pieces, size_t count, const ur_layout *layout,
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

ur_status cli_write_outputs(const cli_job *job, const ur_machine *machine, const ur_layout *layout,
                            const ur_piece *pieces, size_t count, ur_report_context *context,
                            ur_error *error)
{
    char title[128];
    snprintf(title, sizeof title, "unroll %s", job->command);
    ur_output_options output = {title, cli_context()};
    ur_format_options formats = {.job_name = job->job_name ? job->job_name : job->surface,
                                 .dxf_version = (ur_dxf_version)job->dxf_version,
                                 .dpi = job->dpi,
                                 .drawing_order = job->drawing_order};
    unsigned asked = formats_asked(job);
    if (job->roll_width <= 0)
        context->sheets_lower_bound = cli_sheets_lower_bound(
            pieces, count, layout, job->margin >= 0 ? job->margin : machine->margin);
    char(*names)[UR_OUTPUT_NAME_SIZE] = NULL;
    size_t name_count = 0;
    ur_output_set_begin(cli_context()); /* the cut files and the report appear together */
    ur_status status =
        ur_output_files(job->output_path, asked, layout->sheet_count, &names, &name_count, error);
    if (status == UR_OK)
        status = ur_write_outputs(job->output_path, asked, layout, pieces, machine, &output,
                                  &formats, error);
    const char **outputs = NULL;
    if (status == UR_OK && job->report_path) {
        outputs = ur_alloc_array(name_count + 1, sizeof *outputs, error);
        if (!outputs)
            status = UR_ERROR_INTERNAL;
        for (size_t k = 0; outputs && k < name_count; k++)
            outputs[k] = names[k];
        context->outputs = outputs;
        context->drawing_order = job->drawing_order;
        if (status == UR_OK)
            status = ur_report_write(job->report_path, context, pieces, count, layout,
                                     cli_context(), error);
    }
    free(outputs);
    free(names);
    ur_status ended = ur_output_set_end(cli_context(), status == UR_OK, error);
    return status == UR_OK ? ended : status;
}
