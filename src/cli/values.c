/*
 * values.c: the values of the options that say how a job is nested, which
 * allowances it gets and which files it writes (--allowances, --bridges,
 * --format, --dxf-version, --dpi, --order, --rotations, --roll, --sheets,
 * --remnant, --nest-time, --threads, --seed, --job-name), each checked
 * where the option's name is known so that the message names it; and the
 * table of the options every command that writes cut files takes alike
 * (surface jobs, job files' parts and nest), described once.
 */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const struct {
    const char *name;
    unsigned bit;
} allowance_names[] = {
    {"tabs", UR_ALLOW_TABS},       {"kerfing", UR_ALLOW_KERFING}, {"overlaps", UR_ALLOW_OVERLAPS},
    {"bending", UR_ALLOW_BENDING}, {"bridges", UR_ALLOW_BRIDGES},
};

static const size_t allowance_name_count = sizeof allowance_names / sizeof allowance_names[0];

/* One name of a LIST, length bytes long. */
static bool add_allowance(ur_job *job, const char *name, size_t length)
{
    for (size_t k = 0; k < allowance_name_count; k++)
        if (strlen(allowance_names[k].name) == length &&
            strncmp(allowance_names[k].name, name, length) == 0) {
            job->allowances |= allowance_names[k].bit;
            return true;
        }
    cli_message("%s: --allowances: '%.*s' is not one of tabs, kerfing, overlaps, bending, bridges "
                "(or give auto or none)",
                job->command, (int)length, name);
    return false;
}

bool cli_parse_allowances(ur_job *job, const char *value)
{
    job->allowances = 0;
    job->allowances_auto = strcmp(value, "auto") == 0;
    if (job->allowances_auto || strcmp(value, "none") == 0)
        return true;
    const char *start = value;
    for (;;) {
        const char *comma = strchr(start, ',');
        size_t length = comma ? (size_t)(comma - start) : strlen(start);
        if (!add_allowance(job, start, length))
            return false;
        if (!comma)
            return true;
        start = comma + 1;
    }
}

bool cli_parse_bridges(ur_job *job, const char *value)
{
    if (strcmp(value, "auto") == 0) {
        job->bridges = -1;
        return true;
    }
    if (strcmp(value, "none") == 0) {
        job->bridges = 0;
        return true;
    }
    long count;
    if (!cli_whole_number(value, 1, 1000, &count)) {
        cli_message("%s: --bridges: '%s' is not auto, none or a count from 1 to 1000", job->command,
                    value);
        return false;
    }
    job->bridges = count;
    return true;
}

bool cli_parse_formats(ur_job *job, const char *value)
{
    ur_error error;
    if (ur_formats_parse(value, &job->formats, &error) == UR_OK)
        return true;
    cli_message("%s: --format: %s (give svg, dxf, pdf or png, or several: svg,dxf)", job->command,
                error.message);
    return false;
}

bool cli_parse_dxf_version(ur_job *job, const char *value)
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

bool cli_parse_dpi(ur_job *job, const char *value)
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

bool cli_parse_order(ur_job *job, const char *value)
{
    job->drawing_order = strcmp(value, "none") == 0;
    if (job->drawing_order || strcmp(value, "cut") == 0)
        return true;
    cli_message("%s: --order: '%s' is not cut or none", job->command, value);
    return false;
}

bool cli_parse_rotations(ur_job *job, const char *value)
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

bool cli_parse_roll(ur_job *job, const char *value)
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

bool cli_parse_sheet_count(ur_job *job, const char *value)
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

/* --remnant WxH, repeatable: one more remnant sheet, filled before stock. */
bool cli_parse_remnant(ur_job *job, const char *value)
{
    char *end = NULL;
    double width = strtod(value, &end);
    double height = end != value && (*end == 'x' || *end == 'X') ? strtod(end + 1, &end) : NAN;
    if (*end != '\0' || !isfinite(width) || !isfinite(height) || !(width > 0) || !(height > 0)) {
        cli_message("%s: --remnant: '%s' is not WIDTHxHEIGHT in mm, e.g. 300x200", job->command,
                    value);
        return false;
    }
    if (job->remnant_count == UR_JOB_MAX_REMNANTS) {
        cli_message("%s: --remnant: more than %d remnants", job->command, UR_JOB_MAX_REMNANTS);
        return false;
    }
    job->remnants[job->remnant_count++] = (ur_remnant){width, height};
    return true;
}

bool cli_parse_nest_time(ur_job *job, const char *value)
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

bool cli_parse_threads(ur_job *job, const char *value)
{
    long threads;
    if (!cli_whole_number(value, 1, NEST_MAX_THREADS, &threads)) {
        cli_message("%s: --threads: '%s' is not a whole number from 1 to %d", job->command, value,
                    NEST_MAX_THREADS);
        return false;
    }
    job->threads = (size_t)threads;
    return true;
}

bool cli_parse_seed(ur_job *job, const char *value)
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

bool cli_parse_job_name(ur_job *job, const char *value)
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

/* The formats to write: -o - without --format is an SVG, as a program reading a pipe expects. */
static unsigned formats_asked(const ur_job *job)
{
    return job->formats == 0 && strcmp(job->output_path, "-") == 0 ? UR_FORMAT_SVG : job->formats;
}

bool cli_check_output(const ur_job *job)
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

static bool take_machine(ur_job *job, const char *value)
{
    job->machine_name = value;
    return true;
}

static bool take_material(ur_job *job, const char *value)
{
    job->material_name = value;
    return true;
}

static bool take_report(ur_job *job, const char *value)
{
    job->report_path = value;
    return true;
}

static bool take_quiet(ur_job *job, const char *value)
{
    (void)value;
    job->quiet = true;
    return true;
}

static bool take_no_kerf_compensation(ur_job *job, const char *value)
{
    (void)value;
    job->no_kerf_compensation = true;
    return true;
}

static bool take_no_holes(ur_job *job, const char *value)
{
    (void)value;
    job->no_holes = true;
    return true;
}

static bool take_merge_lines(ur_job *job, const char *value)
{
    (void)value;
    job->merge_lines = true;
    return true;
}

const cli_option cli_shared_options[] = {
    {"machine", true, take_machine},
    {"material", true, take_material},
    {"report", true, take_report},
    {"quiet", false, take_quiet},
    {"no-kerf-compensation", false, take_no_kerf_compensation},
    {"format", true, cli_parse_formats},
    {"dxf-version", true, cli_parse_dxf_version},
    {"dpi", true, cli_parse_dpi},
    {"job-name", true, cli_parse_job_name},
    {"order", true, cli_parse_order},
    {"rotations", true, cli_parse_rotations},
    {"no-holes", false, take_no_holes},
    {"merge-lines", false, take_merge_lines},
    {"roll", true, cli_parse_roll},
    {"sheets", true, cli_parse_sheet_count},
    {"remnant", true, cli_parse_remnant},
    {"nest-time", true, cli_parse_nest_time},
    {"seed", true, cli_parse_seed},
    {"threads", true, cli_parse_threads},
};

const size_t cli_shared_option_count = sizeof cli_shared_options / sizeof cli_shared_options[0];

size_t cli_option_table(const struct option *own, struct option *table, size_t most)
{
    size_t count = 0;
    for (; own[count].name && count + 1 < most; count++)
        table[count] = own[count];
    for (size_t k = 0; k < cli_shared_option_count && count + 1 < most; k++)
        table[count++] =
            (struct option){cli_shared_options[k].name,
                            cli_shared_options[k].takes_value ? required_argument : no_argument,
                            NULL, CLI_SHARED_OPTION + (int)k};
    table[count] = (struct option){NULL, 0, NULL, 0};
    return count;
}
