/*
 * job.c: unroll job FILE.xml [-o DIR]: a whole build from one file
 * (unroll-job(5)).  Each part is turned into the command line it stands
 * for (its surface, the job's options, its own) and made into pieces as a
 * surface job would; the pieces of every part, as many of each as its
 * quantity, are then nested together and written once, with one report.
 * A job with one part of quantity 1 writes what the same command line
 * writes, byte for byte.
 */
#include "cli.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Room for the words of one part's command line, and for each word. */
enum { MOST_WORDS = 512, WORD_SIZE = 4400 };

typedef struct words {
    char *items[MOST_WORDS];
    size_t count;
    char text[MOST_WORDS][WORD_SIZE]; /* each word's own copy */
} words;

static bool add_word(words *w, const char *word)
{
    if (w->count == MOST_WORDS || strlen(word) >= WORD_SIZE)
        return false;
    memcpy(w->text[w->count], word, strlen(word) + 1);
    w->items[w->count] = w->text[w->count];
    w->count++;
    return true;
}

static bool add_options(words *w, const ur_job_file_option *options, size_t count)
{
    for (size_t k = 0; k < count; k++) {
        char flag[80];
        snprintf(flag, sizeof flag, "--%s", options[k].name);
        if (!add_word(w, flag) || (options[k].has_value && !add_word(w, options[k].value)))
            return false;
    }
    return true;
}

/* The output files' path: DIRECTORY/NAME with the first format's extension. */
static void output_path(const ur_job_file *job, char *path, size_t size)
{
    char first[16] = "svg";
    if (job->formats[0])
        sscanf(job->formats, "%15[a-z]", first);
    snprintf(path, size, "%s/%s.%s", job->output_directory, job->output_name, first);
}

/*
 * The command line a part stands for: surface, file, the job's profiles and
 * options, then the part's own material and options (the last word wins, so
 * a part's own override the job's), formats, -o.
 */
static bool part_words(const ur_job_file *job, const ur_job_file_part *part, const char *out,
                       words *w)
{
    bool ok = add_word(w, part->surface) && (!part->file[0] || add_word(w, part->file));
    if (ok && job->machine[0])
        ok = add_word(w, "--machine") && add_word(w, job->machine);
    if (ok && job->material[0])
        ok = add_word(w, "--material") && add_word(w, job->material);
    ok = ok && add_options(w, job->options, job->option_count);
    if (ok && part->material[0])
        ok = add_word(w, "--material") && add_word(w, part->material);
    ok = ok && add_options(w, part->options, part->option_count);
    if (ok && job->formats[0])
        ok = add_word(w, "--format") && add_word(w, job->formats);
    return ok && add_word(w, "-o") && add_word(w, out);
}

/*
 * Parses one part's command line into job (whose strings point into w, to
 * be kept as long as job is used) and makes its pieces.
 */
static int make_part(const ur_job_file *file, size_t index, const char *out, words *w,
                     char *command, size_t command_size, ur_job *job, ur_job_parts *parts)
{
    const ur_job_file_part *part = &file->parts[index];
    if (!part_words(file, part, out, w)) {
        cli_message("%s:%d: the part has too many options", file->source, part->line);
        return EXIT_USAGE;
    }
    snprintf(command, command_size, "%s:%d", file->source, part->line);
    cli_message_context(command);
    snprintf(command, command_size, "%s", part->surface);
    int code = cli_parse_job((int)w->count, w->items, CLI_DEVELOP, command, job);
    if (code == -1)
        code = EXIT_USAGE;             /* --help in a job file */
    if (!code && job->assembly_path) { /* the parts share sheets, not one model */
        cli_message("%s: --assembly is not taken in a job file: draw a part's guide with its own "
                    "command line ('unroll %s ... --assembly FILE')",
                    command, part->surface);
        code = EXIT_USAGE;
    }
    if (!code) {
        job->piece_prefix = part->name[0] ? part->name : NULL;
        ur_job_callbacks callbacks = cli_callbacks(job);
        ur_error error;
        if (ur_job_parts_add(parts, job, part->quantity, &callbacks, &error) != UR_OK) {
            cli_message("%s", error.message);
            code = cli_exit_status(&error);
        }
    }
    cli_message_context(NULL);
    return code;
}

/* The job's pieces, every part's, as many as asked; *layout_job describes the sheets and files. */
static int all_pieces(const ur_job_file *file, const char *out, words *first_words,
                      ur_job *layout_job, char *command, size_t command_size, ur_job_parts *parts)
{
    words *w = calloc(1, sizeof *w);
    if (!w) {
        cli_message("job: out of memory");
        return EXIT_MEMORY;
    }
    int code = 0;
    for (size_t p = 0; !code && p < file->part_count; p++) {
        char part_command[1200];
        ur_job job;
        words *use = p == 0 ? first_words : w;
        memset(use, 0, sizeof *use);
        code = make_part(file, p, out, use, p == 0 ? command : part_command,
                         p == 0 ? command_size : sizeof part_command, &job, parts);
        if (!code && p == 0)
            *layout_job = job;
    }
    free(w);
    return code;
}

static int place_and_write(const ur_job_file *file, const ur_job *job, ur_job_parts *parts)
{
    ur_job_callbacks callbacks = cli_callbacks(job);
    ur_job_result result;
    ur_error error;
    const char *surface = file->part_count == 1 ? file->parts[0].surface : "job";
    if (ur_job_parts_run(parts, job, surface, file->name, &callbacks, &result, &error) != UR_OK) {
        cli_message("%s: %s", file->source, error.message);
        return cli_exit_status(&error);
    }
    if (!job->quiet)
        cli_message("job %s: %zu piece%s on %zu sheet%s%s -> %s", file->name, result.piece_count,
                    result.piece_count == 1 ? "" : "s", result.sheet_count,
                    result.sheet_count == 1 ? "" : "s", result.cutting, job->output_path);
    return 0;
}

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
    if (directory)
        snprintf(file.output_directory, sizeof file.output_directory, "%s", directory);

    char out[4200], report[4200], command[1200];
    output_path(&file, out, sizeof out);
    snprintf(report, sizeof report, "%s/%s", file.output_directory, file.report);
    words *first = calloc(1, sizeof *first);
    ur_job job;
    ur_job_parts *parts = ur_job_parts_new();
    if (first && parts)
        code = all_pieces(&file, out, first, &job, command, sizeof command, parts);
    else {
        cli_message("job: out of memory");
        code = EXIT_MEMORY;
    }
    /* The output directory is made when missing (its parent must exist), only now. */
    bool made_directory = false;
    if (!code) {
        made_directory = mkdir(file.output_directory, 0777) == 0;
        if (!made_directory && errno != EEXIST) {
            cli_message("%s: cannot make the output directory %s: %s", file.source,
                        file.output_directory, strerror(errno));
            code = EXIT_IO;
        }
    }
    if (!code) {
        /* One part alone writes as its command line would: its own name and title. */
        job.command = file.part_count == 1 ? file.parts[0].surface : "job";
        if (!job.job_name) /* <option name="job-name"> says otherwise */
            job.job_name = file.name;
        job.report_path = file.report[0] ? report : NULL;
        job.quiet = quiet;
        code = place_and_write(&file, &job, parts);
    }
    if (code && made_directory)
        rmdir(file.output_directory); /* nothing is left behind */
    ur_job_parts_free(parts);
    free(first);
    ur_job_file_free(&file);
    return code;
}
