/*
 * values.c: --allowances and --bridges, each checked where the option's
 * name is known so that the message names it; the options every command
 * that writes cut files takes alike (the library's settings, ur_job_option_name)
 * in a getopt table; and whether -o and --format name files to write.
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

size_t cli_option_table(const struct option *own, struct option *table, size_t most)
{
    size_t count = 0;
    for (; own[count].name && count + 1 < most; count++)
        table[count] = own[count];
    bool takes_value;
    const char *name;
    for (size_t k = 0; (name = ur_job_option_name(k, &takes_value)) && count + 1 < most; k++)
        table[count++] = (struct option){name, takes_value ? required_argument : no_argument, NULL,
                                         CLI_SHARED_OPTION + (int)k};
    table[count] = (struct option){NULL, 0, NULL, 0};
    return count;
}

bool cli_take_shared_option(ur_job *job, int id, const char *value)
{
    const char *name = ur_job_option_name((size_t)(id - CLI_SHARED_OPTION), NULL);
    ur_error error;
    if (ur_job_option_set(job, name, value, &error) == UR_OK)
        return true;
    cli_message("%s: --%s: %s", job->command, name, error.message);
    return false;
}
