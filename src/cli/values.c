/*
 * values.c: the library's settings (ur_job_option_name) in a getopt table
 * and set through it, the message naming the option; and whether -o and
 * --format name files to write.
 */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

size_t cli_option_table(const struct option *own, bool surface_jobs, struct option *table,
                        size_t most)
{
    size_t count = 0;
    for (; own[count].name && count + 1 < most; count++)
        table[count] = own[count];
    bool takes_value;
    const char *name;
    for (size_t k = 0; (name = ur_job_option_name(k, &takes_value)) && count + 1 < most; k++)
        if (surface_jobs || ur_job_option_kind_at(k) == UR_JOB_OPTION_OUTPUT)
            table[count++] = (struct option){name, takes_value ? required_argument : no_argument,
                                             NULL, CLI_SHARED_OPTION + (int)k};
    table[count] = (struct option){NULL, 0, NULL, 0};
    return count;
}

bool cli_set_option(ur_job *job, const char *name, const char *value)
{
    ur_error error;
    if (ur_job_option_set(job, name, value, &error) == UR_OK)
        return true;
    cli_message("%s: --%s: %s", job->command, name, error.message);
    return false;
}
