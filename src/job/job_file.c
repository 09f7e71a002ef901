/*
 * job_file.c: a job file run whole (unroll-job(5)): each part made into a
 * job of its own (its surface and file, the job's profiles and settings,
 * then the part's own material and settings, the file's formats and
 * output), its pieces made as a surface job would make them, as many as
 * its quantity; then every part's pieces nested together and written
 * once, with one report, into the output directory (made when missing).
 * A job with one part of quantity 1 writes what the same surface job
 * writes, byte for byte.  Messages name the job file and the part's line.
 */
#include "options.h"
#include "stages.h"

#include "../base/c_locale.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* What a run of a job file keeps while its parts are made: the paths its jobs borrow. */
typedef struct file_run {
    const ur_job_file *file;
    ur_context *context;
    const char *directory;
    char output_path[4200];
    char report_path[4200];
    ur_job layout; /* the first part's job: the sheets and files of the whole */
} file_run;

/*
 * A part's warnings and notes go to the handler the context had, prefixed
 * with the file and the part's line: the part's run has this one in its
 * place.
 */
typedef struct located_messages {
    ur_message_handler handler;
    void *data;
    char where[1100];
} located_messages;

static void located_message(void *data, ur_message_kind kind, const char *message,
                            const char *setting)
{
    const located_messages *located = data;
    char text[9300];
    c_snprintf(text, sizeof text, "%s: %s", located->where, message);
    located->handler(located->data, kind, text, setting);
}

/* The job's settings, or a part's, on a part's job; the message names the file and line. */
static ur_status set_options(ur_job *job, const ur_job_file_option *options, size_t count,
                             const ur_job_file *file, int line, ur_error *error)
{
    for (size_t k = 0; k < count; k++) {
        const ur_job_file_option *option = &options[k];
        const char *value = option->has_value ? option->value : NULL;
        ur_status status;
        if (job_setting_kind(option->name) == UR_JOB_OPTION_ANALYSIS)
            status = ur_error_set(error, UR_ERROR_INPUT,
                                  "is an analysis's file, which a job file does not write");
        else
            status = ur_job_option_set(job, option->name, value, error);
        if (status != UR_OK)
            return ur_error_prefix(error, "%s:%d: %s: option %s: ", file->source, line,
                                   job->command, option->name);
    }
    return UR_OK;
}

/* Part index as a job: what its command line would say (unroll-job(5)). */
static ur_status part_job(const file_run *run, size_t index, ur_job *job, ur_error *error)
{
    const ur_job_file *file = run->file;
    const ur_job_file_part *part = &file->parts[index];
    ur_job_init(job, part->surface);
    job->context = run->context;
    bool mesh = strcmp(part->surface, "mesh") == 0;
    if (part->file[0] && !mesh)
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: %s: a file is for a mesh part",
                            file->source, part->line, part->surface);
    job->mesh_path = part->file[0] ? part->file : NULL;
    if (file->machine[0])
        job->machine_name = file->machine;
    if (file->material[0])
        job->material_name = file->material;
    ur_status status = set_options(job, file->options, file->option_count, file, part->line, error);
    if (status != UR_OK)
        return status;
    if (part->material[0])
        job->material_name = part->material;
    status = set_options(job, part->options, part->option_count, file, part->line, error);
    if (status == UR_OK && file->formats[0] &&
        ur_job_option_set(job, "format", file->formats, error) != UR_OK)
        return ur_error_prefix(error, "%s:%d: output formats: ", file->source, file->output_line);
    if (status == UR_OK && job->assembly_path) /* the parts share sheets, not one model */
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s:%d: %s: the assembly guide is not drawn from a job file: draw a "
                            "part's guide in a job of its own",
                            file->source, part->line, part->surface);
    job->output_path = run->output_path;
    job->piece_prefix = part->name[0] ? part->name : NULL;
    return status;
}

/* Makes part index's pieces into parts, its warnings and failure naming its line. */
static ur_status add_part(file_run *run, size_t index, ur_job_parts *parts,
                          const ur_job_callbacks *callbacks, ur_error *error)
{
    const ur_job_file_part *part = &run->file->parts[index];
    ur_job *job = index == 0 ? &run->layout : malloc(sizeof *job); /* a job is large */
    if (!job)
        return ur_error_out_of_memory(error);
    ur_status status = part_job(run, index, job, error);
    if (status == UR_OK) {
        located_messages located;
        ur_context_message_handler(run->context, &located.handler, &located.data);
        c_snprintf(located.where, sizeof located.where, "%s:%d", run->file->source, part->line);
        if (located.handler)
            ur_context_set_message_handler(run->context, located_message, &located);
        status = ur_job_parts_add(parts, job, part->quantity, callbacks, error);
        if (located.handler)
            ur_context_set_message_handler(run->context, located.handler, located.data);
        if (status != UR_OK)
            ur_error_prefix(error, "%s:%d: ", run->file->source, part->line);
    }
    if (index > 0)
        free(job);
    return status;
}

/* The cut files' path, DIRECTORY/NAME with the first format's extension, and the report's. */
static ur_status output_paths(file_run *run, ur_error *error)
{
    const ur_job_file *file = run->file;
    char first[16] = "svg";
    if (file->formats[0])
        sscanf(file->formats, "%15[a-z]", first);
    int length = c_snprintf(run->output_path, sizeof run->output_path, "%s/%s.%s", run->directory,
                            file->output_name, first);
    int report = c_snprintf(run->report_path, sizeof run->report_path, "%s/%s", run->directory,
                            file->report);
    if (length < 0 || (size_t)length >= sizeof run->output_path || report < 0 ||
        (size_t)report >= sizeof run->report_path)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: the output directory's path is too long",
                            file->source);
    return UR_OK;
}

/*
 * Nests and writes every part's pieces into the output directory, made
 * now when missing (not its parents) and removed again when the run fails.
 */
static ur_status place_and_write(file_run *run, ur_job_parts *parts, bool quiet,
                                 const ur_job_callbacks *callbacks, ur_job_result *result,
                                 ur_error *error)
{
    const ur_job_file *file = run->file;
    bool made = mkdir(run->directory, 0777) == 0;
    if (!made && errno != EEXIST)
        return ur_error_set(error, UR_ERROR_IO, "%s: cannot make the output directory %s: %s",
                            file->source, run->directory, strerror(errno));
    ur_job *job = &run->layout;
    /* One part alone writes as its surface job would: its own name and title. */
    const char *surface = file->part_count == 1 ? file->parts[0].surface : "job";
    job->command = surface;
    if (!job->job_name) /* <option name="job-name"> says otherwise */
        job->job_name = file->name;
    job->report_path = file->report[0] ? run->report_path : NULL;
    job->quiet = quiet;
    ur_status status = ur_job_parts_run(parts, job, surface, file->name, callbacks, result, error);
    if (status != UR_OK) {
        ur_error_prefix(error, "%s: ", file->source);
        if (made)
            rmdir(run->directory); /* nothing is left behind */
    }
    return status;
}

ur_status ur_job_file_run(const ur_job_file *file, ur_context *context,
                          const char *output_directory, bool quiet,
                          const ur_job_callbacks *callbacks, ur_job_result *result, ur_error *error)
{
    file_run *run = calloc(1, sizeof *run);
    ur_job_parts *parts = ur_job_parts_new();
    ur_status status = run && parts ? UR_OK : ur_error_out_of_memory(error);
    if (status == UR_OK) {
        run->file = file;
        run->context = context;
        run->directory = output_directory ? output_directory : file->output_directory;
        status = output_paths(run, error);
    }
    for (size_t k = 0; status == UR_OK && k < file->part_count; k++)
        status = add_part(run, k, parts, callbacks, error);
    if (status == UR_OK && file->part_count == 0)
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: the job has no part", file->source);
    ur_job_result unused;
    if (status == UR_OK)
        status = place_and_write(run, parts, quiet, callbacks, result ? result : &unused, error);
    ur_job_parts_free(parts);
    free(run);
    return status;
}
