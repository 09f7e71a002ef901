/*
 * job.c: unroll job FILE.xml [-o DIR] [--quiet]: a whole build from one
 * file (unroll-job(5)), read (ur_job_file_read) and run (ur_job_file_run)
 * by the library; this says how it went.
 */
#include "cli.h"

#include <stdio.h>
#include <string.h>

/* unroll job FILE.xml [-o DIR] [--quiet] */
static int parse_job_command(int argc, char **argv, const char **path, const char **directory,
                             bool *quiet)
{
    *path = NULL;
    *directory = NULL;
    *quiet = false;
    for (int k = 1; k < argc; k++) {
        if (strcmp(argv[k], "-o") == 0 && k + 1 < argc)
            *directory = argv[++k];
        else if (strcmp(argv[k], "--quiet") == 0)
            *quiet = true;
        else if (argv[k][0] != '-' && !*path)
            *path = argv[k];
        else {
            cli_message("job: '%s' is not FILE.xml, -o DIR or --quiet (see unroll-job(5))",
                        argv[k]);
            return EXIT_USAGE;
        }
    }
    if (!*path) {
        cli_message("job: give the job file: unroll job FILE.xml [-o DIR]");
        return EXIT_USAGE;
    }
    return 0;
}

int cli_job_command(int argc, char **argv)
{
    const char *path, *directory;
    bool quiet;
    int code = parse_job_command(argc, argv, &path, &directory, &quiet);
    if (code)
        return code;
    ur_job_file file;
    ur_error error;
    if (ur_job_file_read(cli_profile_roots(), path, &file, &error) != UR_OK) {
        cli_message("%s", error.message);
        return cli_exit_status(&error);
    }
    /* What the progress lines name: the one part's surface, or the job. */
    ur_job shown;
    ur_job_init(&shown, file.part_count == 1 ? file.parts[0].surface : "job");
    ur_job_callbacks callbacks = cli_callbacks(&shown);
    ur_job_result result;
    if (ur_job_file_run(&file, cli_context(), directory, quiet, &callbacks, &result, &error) !=
        UR_OK) {
        cli_message("%s", error.message);
        code = cli_exit_status(&error);
    } else if (!quiet)
        cli_message("job %s: %zu piece%s on %zu sheet%s%s -> %s", file.name, result.piece_count,
                    result.piece_count == 1 ? "" : "s", result.sheet_count,
                    result.sheet_count == 1 ? "" : "s", result.cutting, result.first_file);
    ur_job_file_free(&file);
    return code;
}
