/*
 * options.c: the settings a job takes by name, as words (a command line's
 * options, a job file's <option> elements), looked up in one table (the
 * surface's in surface_options.c, the rest in output_options.c); the
 * parsers their values share; and whether a job's settings go together.
 * Messages say what is wrong with a value; the caller names the setting.
 */
#include "options.h"
#include "stages.h"

#include "../base/c_locale.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool job_whole_number(const char *text, long least, long most, long *value)
{
    char *end = NULL;
    errno = 0;
    long parsed = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || parsed < least || parsed > most)
        return false;
    *value = parsed;
    return true;
}

ur_status job_count(const char *text, long most, size_t *count, ur_error *error)
{
    long parsed;
    if (!job_whole_number(text, 1, most, &parsed))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a whole number from 1 to %ld", text,
                            most);
    *count = (size_t)parsed;
    return UR_OK;
}

ur_status job_number(const char *text, double *value, ur_error *error)
{
    char *end;
    errno = 0;
    double parsed = c_strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || !isfinite(parsed))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a finite number", text);
    if (fabs(parsed) > UR_LENGTH_MAX)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is beyond the largest number unroll takes, %g", text,
                            UR_LENGTH_MAX);
    *value = parsed;
    return UR_OK;
}

const char *job_scan_vector(const char *text, char last, ur_vec3 *vector)
{
    char *end;
    double c[3];
    for (int k = 0; k < 3; k++) {
        errno = 0;
        c[k] = c_strtod(text, &end);
        bool separator_ok = k < 2 ? *end == ',' : *end == last;
        if (end == text || !separator_ok || errno == ERANGE || !isfinite(c[k]) ||
            fabs(c[k]) > UR_LENGTH_MAX)
            return NULL;
        text = end + 1;
    }
    *vector = ur_vec3_make(c[0], c[1], c[2]);
    return text;
}

/* Setting index of the one table: the output settings, then the surface's. */
static const job_setting *setting_at(size_t index)
{
    if (index < job_output_setting_count)
        return &job_output_settings[index];
    index -= job_output_setting_count;
    return index < job_surface_setting_count ? &job_surface_settings[index] : NULL;
}

static const job_setting *setting_named(const char *name)
{
    const job_setting *setting;
    for (size_t k = 0; (setting = setting_at(k)); k++)
        if (strcmp(setting->name, name) == 0)
            return setting;
    return NULL;
}

ur_job_option_kind job_setting_kind(const char *name)
{
    const job_setting *setting = setting_named(name);
    return setting ? setting->kind : UR_JOB_OPTION_OUTPUT;
}

size_t ur_job_option_count(void)
{
    return job_output_setting_count + job_surface_setting_count;
}

const char *ur_job_option_name(size_t index, bool *takes_value)
{
    const job_setting *setting = setting_at(index);
    if (!setting)
        return NULL;
    if (takes_value)
        *takes_value = setting->takes_value;
    return setting->name;
}

ur_job_option_kind ur_job_option_kind_at(size_t index)
{
    const job_setting *setting = setting_at(index);
    return setting ? setting->kind : UR_JOB_OPTION_OUTPUT;
}

static bool applies(const job_setting *setting, const char *surface)
{
    if (!setting->surfaces)
        return true;
    char word[64];
    c_snprintf(word, sizeof word, " %s ", surface);
    return strstr(setting->surfaces, word) != NULL;
}

bool ur_job_option_applies(const char *name, const char *surface)
{
    const job_setting *setting = setting_named(name);
    return setting && surface && applies(setting, surface);
}

ur_status ur_job_option_set(ur_job *job, const char *name, const char *value, ur_error *error)
{
    const job_setting *setting = setting_named(name);
    if (!setting)
        return ur_error_set(error, UR_ERROR_INPUT, "no such setting");
    if (setting->takes_value && !value)
        return ur_error_set(error, UR_ERROR_INPUT, "needs a value");
    if (!setting->takes_value && value)
        return ur_error_set(error, UR_ERROR_INPUT, "takes no value (it is a flag), not '%s'",
                            value);
    if (job->surface && !applies(setting, job->surface))
        return ur_error_set(error, UR_ERROR_INPUT, "does not apply to a %s", job->surface);
    return setting->set(job, value, error);
}

/* The settings that say how a strip's rails move, which need adjust to say which move. */
static bool adjusting(const ur_job *job)
{
    return job->has_adjust_direction || job->has_adjust_plane || job->adjust_ends ||
           !isnan(job->adjust_max) || job->adjusted_rail_path || job->adjusted_rail1_path;
}

ur_status ur_job_check(const ur_job *job, ur_error *error)
{
    const char *command = job->command ? job->command : job->surface ? job->surface : "job";
    bool mesh = job->surface && strcmp(job->surface, "mesh") == 0;
    bool charts = mesh && job->flatten < 0 && !job->unfold;
    if (!isnan(job->max_strain) && !job->strips && !charts) {
        ur_error_set(error, UR_ERROR_INPUT, "%s: max-strain goes with flatten strips or charts",
                     command);
        return ur_error_set_setting(error, "max-strain flatten");
    }
    if (job->fewer_pieces && !(mesh && job->unfold)) {
        ur_error_set(error, UR_ERROR_INPUT, "%s: fewer-pieces goes with flatten unfold", command);
        return ur_error_set_setting(error, "fewer-pieces flatten");
    }
    if (job->unfold_steps > 0 && !(mesh && job->unfold)) {
        ur_error_set(error, UR_ERROR_INPUT, "%s: unfold-steps goes with flatten unfold", command);
        return ur_error_set_setting(error, "unfold-steps flatten");
    }
    if (job->hide_folds > 0 && !(mesh && job->unfold)) {
        ur_error_set(error, UR_ERROR_INPUT, "%s: hide-folds goes with flatten unfold", command);
        return ur_error_set_setting(error, "hide-folds flatten");
    }
    if (adjusting(job) && !job->adjust_rails) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "%s: adjust-direction, adjust-plane, adjust-ends, adjust-max and "
                     "adjusted-rail go with adjust (or adjust-rail2)",
                     command);
        return ur_error_set_setting(error, "adjust-direction adjust-plane adjust-ends adjust-max "
                                           "adjusted-rail adjust adjust-rail2");
    }
    if (job->has_adjust_direction && job->has_adjust_plane) {
        ur_error_set(error, UR_ERROR_INPUT, "%s: give adjust-direction or adjust-plane, not both",
                     command);
        return ur_error_set_setting(error, "adjust-direction adjust-plane");
    }
    if (job->adjusted_rail1_path && !(job->adjust_rails & UR_REPAIR_RAIL1)) {
        ur_error_set(error, UR_ERROR_INPUT, "%s: adjusted-rail1 goes with adjust rail1 or both",
                     command);
        return ur_error_set_setting(error, "adjusted-rail1 adjust");
    }
    return UR_OK;
}
