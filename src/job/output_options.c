/*
 * output_options.c: the settings of every job that writes cut files (a
 * surface job, a job file's parts, parts nested as drawn): the profiles,
 * the stock and its sheets, nesting, and the files written.  Each value is
 * checked here, with a message that says what is wrong with it (the
 * caller names the setting).
 */
#include "options.h"

#include "unroll/out.h"

#include "../base/c_locale.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static ur_status set_output(ur_job *job, const char *value, ur_error *error)
{
    (void)error;
    job->output_path = value;
    return UR_OK;
}

/* WIDTHxHEIGHT in mm: the stock sheet, in place of the material's sizes. */
static ur_status set_sheet(ur_job *job, const char *value, ur_error *error)
{
    char *end = NULL;
    errno = 0;
    double width = c_strtod(value, &end);
    double height = NAN;
    if (end != value && (*end == 'x' || *end == 'X')) {
        const char *rest = end + 1;
        height = c_strtod(rest, &end);
        if (end == rest || *end != '\0' || errno != 0)
            height = NAN;
    }
    if (!(width > 0) || !(height > 0) || !(width <= UR_LENGTH_MAX) || !(height <= UR_LENGTH_MAX))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not WIDTHxHEIGHT in mm up to %g, e.g. 600x400", value,
                            UR_LENGTH_MAX);
    job->sheet_width = width;
    job->sheet_height = height;
    return UR_OK;
}

static ur_status set_length(const char *value, double *length, ur_error *error)
{
    char *end = NULL;
    double parsed = c_strtod(value, &end);
    if (end == value || *end != '\0' || !(parsed >= 0) || !(parsed <= UR_LENGTH_MAX))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a length from 0 to %g mm", value,
                            UR_LENGTH_MAX);
    *length = parsed;
    return UR_OK;
}

static ur_status set_margin(ur_job *job, const char *value, ur_error *error)
{
    return set_length(value, &job->margin, error);
}

static ur_status set_spacing(ur_job *job, const char *value, ur_error *error)
{
    return set_length(value, &job->spacing, error);
}

static ur_status set_no_split(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->develop.split = false;
    return UR_OK;
}

static ur_status set_formats(ur_job *job, const char *value, ur_error *error)
{
    ur_error parsed;
    if (ur_formats_parse(value, &job->formats, &parsed) == UR_OK)
        return UR_OK;
    return ur_error_set(error, UR_ERROR_INPUT,
                        "%s (give svg, dxf, pdf or png, or several: svg,dxf)", parsed.message);
}

static ur_status set_dxf_version(ur_job *job, const char *value, ur_error *error)
{
    if (strcmp(value, "12") == 0 || strcmp(value, "R12") == 0) {
        job->dxf_version = UR_DXF_R12;
        return UR_OK;
    }
    if (strcmp(value, "2000") == 0 || strcmp(value, "R2000") == 0) {
        job->dxf_version = UR_DXF_R2000;
        return UR_OK;
    }
    return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not 12 or 2000", value);
}

static ur_status set_dpi(ur_job *job, const char *value, ur_error *error)
{
    char *end = NULL;
    errno = 0;
    double dpi = c_strtod(value, &end);
    if (end == value || *end != '\0' || !isfinite(dpi) || dpi < 10 || dpi > 2400)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not a resolution from 10 to 2400 dots per inch", value);
    job->dpi = dpi;
    return UR_OK;
}

static ur_status set_order(ur_job *job, const char *value, ur_error *error)
{
    job->drawing_order = strcmp(value, "none") == 0;
    if (job->drawing_order || strcmp(value, "cut") == 0)
        return UR_OK;
    return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not cut or none", value);
}

static ur_status set_rotations(ur_job *job, const char *value, ur_error *error)
{
    long count;
    if (!job_whole_number(value, 1, 360, &count))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a count of turns from 1 to 360",
                            value);
    job->rotations = count;
    return UR_OK;
}

static ur_status set_roll(ur_job *job, const char *value, ur_error *error)
{
    char *end = NULL;
    double width = c_strtod(value, &end);
    if (end == value || *end != '\0' || !(width > 0) || !(width <= UR_LENGTH_MAX))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a width in mm up to %g", value,
                            UR_LENGTH_MAX);
    job->roll_width = width;
    return UR_OK;
}

static ur_status set_sheet_count(ur_job *job, const char *value, ur_error *error)
{
    long count;
    if (!job_whole_number(value, 1, 10000, &count))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a count of sheets from 1 to 10000",
                            value);
    job->max_sheets = count;
    return UR_OK;
}

/* WIDTHxHEIGHT, repeatable: one more remnant sheet, filled before stock. */
static ur_status set_remnant(ur_job *job, const char *value, ur_error *error)
{
    char *end = NULL;
    double width = c_strtod(value, &end);
    double height = end != value && (*end == 'x' || *end == 'X') ? c_strtod(end + 1, &end) : NAN;
    if (*end != '\0' || !isfinite(width) || !isfinite(height) || !(width > 0) || !(height > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not WIDTHxHEIGHT in mm, e.g. 300x200",
                            value);
    if (job->remnant_count == UR_JOB_MAX_REMNANTS)
        return ur_error_set(error, UR_ERROR_INPUT, "more than %d remnants", UR_JOB_MAX_REMNANTS);
    job->remnants[job->remnant_count++] = (ur_remnant){width, height};
    return UR_OK;
}

static ur_status set_nest_time(ur_job *job, const char *value, ur_error *error)
{
    char *end = NULL;
    double seconds = c_strtod(value, &end);
    if (end == value || *end != '\0' || !isfinite(seconds) || seconds < 0 || seconds > 3600)
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a number of seconds from 0 to 3600",
                            value);
    job->nest_time = seconds;
    return UR_OK;
}

static ur_status set_threads(ur_job *job, const char *value, ur_error *error)
{
    return job_count(value, UR_NEST_MAX_THREADS, &job->threads, error);
}

static ur_status set_seed(ur_job *job, const char *value, ur_error *error)
{
    char *end = NULL;
    errno = 0;
    unsigned long long seed = strtoull(value, &end, 10);
    if (end == value || *end != '\0' || errno != 0 || value[0] == '-')
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a whole number of 0 or more",
                            value);
    job->seed = seed;
    return UR_OK;
}

/* The most bytes a job name may have: it is a title, not a description. */
enum { JOB_NAME_MAX = 200 };

static ur_status set_job_name(ur_job *job, const char *value, ur_error *error)
{
    size_t length = strlen(value);
    bool control = false;
    for (const unsigned char *c = (const unsigned char *)value; *c; c++)
        control = control || *c < 0x20 || *c == 0x7F;
    if (length == 0 || length > JOB_NAME_MAX || control)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "give a name of 1 to %d bytes without control characters",
                            JOB_NAME_MAX);
    job->job_name = value;
    return UR_OK;
}

static ur_status set_machine(ur_job *job, const char *value, ur_error *error)
{
    (void)error;
    job->machine_name = value;
    return UR_OK;
}

static ur_status set_material(ur_job *job, const char *value, ur_error *error)
{
    (void)error;
    job->material_name = value;
    return UR_OK;
}

static ur_status set_report(ur_job *job, const char *value, ur_error *error)
{
    (void)error;
    job->report_path = value;
    return UR_OK;
}

static ur_status set_quiet(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->quiet = true;
    return UR_OK;
}

static ur_status set_no_kerf_compensation(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->no_kerf_compensation = true;
    return UR_OK;
}

static ur_status set_no_holes(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->no_holes = true;
    return UR_OK;
}

static ur_status set_merge_lines(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->merge_lines = true;
    return UR_OK;
}

/* Every setting of the profiles, the stock, nesting and the files, described once. */
const job_setting job_output_settings[] = {
    {"output", true, UR_JOB_OPTION_OUTPUT, NULL, set_output},
    {"machine", true, UR_JOB_OPTION_OUTPUT, NULL, set_machine},
    {"material", true, UR_JOB_OPTION_OUTPUT, NULL, set_material},
    {"report", true, UR_JOB_OPTION_OUTPUT, NULL, set_report},
    {"quiet", false, UR_JOB_OPTION_OUTPUT, NULL, set_quiet},
    {"sheet", true, UR_JOB_OPTION_OUTPUT, NULL, set_sheet},
    {"margin", true, UR_JOB_OPTION_OUTPUT, NULL, set_margin},
    {"spacing", true, UR_JOB_OPTION_OUTPUT, NULL, set_spacing},
    {"no-split", false, UR_JOB_OPTION_OUTPUT, NULL, set_no_split},
    {"no-kerf-compensation", false, UR_JOB_OPTION_OUTPUT, NULL, set_no_kerf_compensation},
    {"format", true, UR_JOB_OPTION_OUTPUT, NULL, set_formats},
    {"dxf-version", true, UR_JOB_OPTION_OUTPUT, NULL, set_dxf_version},
    {"dpi", true, UR_JOB_OPTION_OUTPUT, NULL, set_dpi},
    {"job-name", true, UR_JOB_OPTION_OUTPUT, NULL, set_job_name},
    {"order", true, UR_JOB_OPTION_OUTPUT, NULL, set_order},
    {"rotations", true, UR_JOB_OPTION_OUTPUT, NULL, set_rotations},
    {"no-holes", false, UR_JOB_OPTION_OUTPUT, NULL, set_no_holes},
    {"merge-lines", false, UR_JOB_OPTION_OUTPUT, NULL, set_merge_lines},
    {"roll", true, UR_JOB_OPTION_OUTPUT, NULL, set_roll},
    {"sheets", true, UR_JOB_OPTION_OUTPUT, NULL, set_sheet_count},
    {"remnant", true, UR_JOB_OPTION_OUTPUT, NULL, set_remnant},
    {"nest-time", true, UR_JOB_OPTION_OUTPUT, NULL, set_nest_time},
    {"seed", true, UR_JOB_OPTION_OUTPUT, NULL, set_seed},
    {"threads", true, UR_JOB_OPTION_OUTPUT, NULL, set_threads},
};

const size_t job_output_setting_count = sizeof job_output_settings / sizeof job_output_settings[0];
