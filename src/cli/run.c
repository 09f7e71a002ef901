/*
 * run.c: one surface job through the library (ur_job_run), its progress
 * and summary on stderr, its failure as a message and exit status (its
 * warnings and notes come through the context's handler, signals.c).
 */
#include "cli.h"

#include <libgen.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool cli_directory_exists(const char *option, const char *path)
{
    char copy[4096];
    snprintf(copy, sizeof copy, "%s", path);
    const char *directory = dirname(copy);
    struct stat info;
    if (stat(directory, &info) != 0) {
        cli_message("%s '%s': directory '%s' does not exist", option, path, directory);
        return false;
    }
    if (!S_ISDIR(info.st_mode)) {
        cli_message("%s '%s': '%s' is not a directory", option, path, directory);
        return false;
    }
    return true;
}

int cli_exit_status(const ur_error *error)
{
    switch (error->status) {
    case UR_ERROR_INPUT:
        return EXIT_USAGE;
    case UR_ERROR_IO:
        return EXIT_IO;
    case UR_ERROR_MEMORY:
        return EXIT_MEMORY;
    default: /* UR_ERROR_CANCELLED ends in 128 + the signal (cli_signal_exit) */
        return EXIT_INTERNAL;
    }
}

/* On a terminal: each report on one line rewritten in place, cleared or ended when done. */
static void print_progress(void *user, const ur_job_progress *progress)
{
    const ur_job *job = user;
    switch (progress->kind) {
    case UR_JOB_NESTING:
        fprintf(stderr, "\runroll: %s: nesting: %zu sheet%s, %.1f mm of the last used (try %zu)   ",
                job->command, progress->sheets, progress->sheets == 1 ? "" : "s", progress->length,
                progress->tries);
        break;
    case UR_JOB_PLACING:
        fprintf(stderr, "\runroll: %s: nesting: placed %zu of %zu parts   ", job->command,
                progress->placed, progress->count);
        break;
    case UR_JOB_NESTING_DONE:
        fputc('\n', stderr);
        break;
    case UR_JOB_FLATTENING:
        fprintf(stderr, "\runroll: %s: flattening, ARAP iteration %zu, energy %.3g   ",
                job->command, progress->iteration, progress->energy);
        break;
    case UR_JOB_UNFOLDING:
    case UR_JOB_JOINING:
        fprintf(stderr, "\runroll: %s: %s, %.0f %%   ", job->command, progress->phase,
                100 * progress->fraction);
        break;
    case UR_JOB_FLATTENING_DONE:
    case UR_JOB_JOINING_DONE:
        fputs("\r\033[K", stderr);
        break;
    }
    fflush(stderr);
}

static void print_summary(void *user, const ur_job_result *result)
{
    const ur_job *job = user;
    fprintf(stderr,
            "unroll: %s (%s): %zu piece%s, surface %.2f mm2, net %.2f mm2 (coverage %.6f), "
            "%s (%s, %s)%s -> %s\n",
            job->surface, result->method, result->piece_count, result->piece_count == 1 ? "" : "s",
            result->surface_area, result->flat_area, result->flat_area / result->surface_area,
            result->sheets, result->material, result->machine, result->cutting, result->first_file);
}

ur_job_callbacks cli_callbacks(const ur_job *job)
{
    return (ur_job_callbacks){
        .user = (void *)job,
        .progress = isatty(STDERR_FILENO) ? print_progress : NULL,
        .summary = print_summary,
    };
}

/* Every file the job names can be written where it says, before any work. */
static bool directories_exist(const ur_job *job)
{
    return (strcmp(job->output_path, "-") == 0 || cli_directory_exists("-o", job->output_path)) &&
           (!job->report_path || strcmp(job->report_path, "-") == 0 ||
            cli_directory_exists("--report", job->report_path)) &&
           (!job->regression_path || cli_directory_exists("--regression", job->regression_path)) &&
           (!job->adjusted_rail_path ||
            cli_directory_exists("--adjusted-rail", job->adjusted_rail_path)) &&
           (!job->adjusted_rail1_path ||
            cli_directory_exists("--adjusted-rail1", job->adjusted_rail1_path)) &&
           (!job->strain_png_path || strcmp(job->strain_png_path, "-") == 0 ||
            cli_directory_exists("--strain-png", job->strain_png_path)) &&
           (!job->assembly_path || cli_directory_exists("--assembly", job->assembly_path));
}

int cli_run_job(const ur_job *job)
{
    if (!directories_exist(job))
        return EXIT_IO;
    ur_job_callbacks callbacks = cli_callbacks(job);
    ur_error error;
    if (ur_job_run(job, &callbacks, NULL, &error) != UR_OK) {
        cli_error(NULL, &error);
        return cli_exit_status(&error);
    }
    return 0;
}
