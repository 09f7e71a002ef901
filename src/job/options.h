/*
 * options.h: what the files of the job's settings share (options.c, the
 * lookup and the checks of a whole job; surface_options.c, the surface's
 * settings; output_options.c, the sheets', nesting's and files'): one
 * table entry per setting, and the parsers of its values.
 */
#ifndef UNROLL_JOB_OPTIONS_H
#define UNROLL_JOB_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>

#include "unroll/job.h"

typedef struct job_setting {
    const char *name;
    bool takes_value;
    ur_job_option_kind kind;
    /* the surfaces it applies to, each between spaces (" cylinder cone "); NULL: every one */
    const char *surfaces;
    /* sets the value (NULL for a flag) into job; the message says what is wrong with it */
    ur_status (*set)(ur_job *job, const char *value, ur_error *error);
} job_setting;

/* The surface's settings and how it becomes pieces (surface_options.c). */
extern const job_setting job_surface_settings[];
extern const size_t job_surface_setting_count;

/* The profiles', sheets', nesting's and files' settings (output_options.c). */
extern const job_setting job_output_settings[];
extern const size_t job_output_setting_count;

/* The kind of the named setting; UR_JOB_OPTION_OUTPUT for an unknown name (which set refuses). */
ur_job_option_kind job_setting_kind(const char *name);

/* Whether text is a whole number from least to most (decimal, nothing after it). */
bool job_whole_number(const char *text, long least, long most, long *value);

/* A count from 1 to most; the message gives the range. */
ur_status job_count(const char *text, long most, size_t *count, ur_error *error);

/* A finite number no larger than UR_LENGTH_MAX; the message says what is wrong. */
ur_status job_number(const char *text, double *value, ur_error *error);

/*
 * X,Y,Z ending at `last` (a ':' between corners, or the string's end),
 * each at most UR_LENGTH_MAX; the rest of the text, or NULL when it is not.
 */
const char *job_scan_vector(const char *text, char last, ur_vec3 *vector);

#endif
