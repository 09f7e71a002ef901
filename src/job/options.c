/*
 * options.c: the settings a job takes by name, as words (a command line's
 * options, a job file's <option> elements), described once: each value
 * checked here, with a message that says what is wrong with it (the
 * caller names the setting).
 */
#include "stages.h"

#include "../base/c_locale.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Whether text is a whole number from least to most (decimal, nothing after it). */
static bool whole_number(const char *text, long least, long most, long *value)
{
    char *end = NULL;
    errno = 0;
    long parsed = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || parsed < least || parsed > most)
        return false;
    *value = parsed;
    return true;
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
    if (!whole_number(value, 1, 360, &count))
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
    if (!whole_number(value, 1, 10000, &count))
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
    long threads;
    if (!whole_number(value, 1, UR_NEST_MAX_THREADS, &threads))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a whole number from 1 to %d", value,
                            UR_NEST_MAX_THREADS);
    job->threads = (size_t)threads;
    return UR_OK;
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

/* Every setting a job takes by name, described once. */
static const struct {
    const char *name;
    bool takes_value;
    ur_status (*set)(ur_job *job, const char *value, ur_error *error);
} settings[] = {
    {"machine", true, set_machine},
    {"material", true, set_material},
    {"report", true, set_report},
    {"quiet", false, set_quiet},
    {"no-kerf-compensation", false, set_no_kerf_compensation},
    {"format", true, set_formats},
    {"dxf-version", true, set_dxf_version},
    {"dpi", true, set_dpi},
    {"job-name", true, set_job_name},
    {"order", true, set_order},
    {"rotations", true, set_rotations},
    {"no-holes", false, set_no_holes},
    {"merge-lines", false, set_merge_lines},
    {"roll", true, set_roll},
    {"sheets", true, set_sheet_count},
    {"remnant", true, set_remnant},
    {"nest-time", true, set_nest_time},
    {"seed", true, set_seed},
    {"threads", true, set_threads},
};

enum { SETTING_COUNT = sizeof settings / sizeof settings[0] };

size_t ur_job_option_count(void)
{
    return SETTING_COUNT;
}

const char *ur_job_option_name(size_t index, bool *takes_value)
{
    if (index >= SETTING_COUNT)
        return NULL;
    if (takes_value)
        *takes_value = settings[index].takes_value;
    return settings[index].name;
}

ur_status ur_job_option_set(ur_job *job, const char *name, const char *value, ur_error *error)
{
    for (size_t k = 0; k < SETTING_COUNT; k++)
        if (strcmp(settings[k].name, name) == 0) {
            if (settings[k].takes_value && !value)
                return ur_error_set(error, UR_ERROR_INPUT, "needs a value");
            return settings[k].set(job, value, error);
        }
    return ur_error_set(error, UR_ERROR_INPUT, "'%s' is no setting of a job", name);
}
