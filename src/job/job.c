/*
 * job.c: a job's defaults, and how one run of it reports: warnings and
 * notes to its context's message handler, progress to the caller's
 * callbacks, a failure into the caller's error.
 */
#include "stages.h"

#include "../base/c_locale.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void ur_job_init(ur_job *job, const char *surface)
{
    memset(job, 0, sizeof *job);
    job->command = surface;
    job->surface = surface;
    job->radius = job->height = job->top_radius = job->pitch = NAN;
    job->turns = job->width = job->offset = job->cut = NAN;
    job->scale = NAN;
    job->max_strain = NAN;
    job->adjust_max = NAN;
    job->flatten = -1;
    job->surface_layer = -1;
    job->allowances_auto = true;
    job->bridges = UR_JOB_BRIDGES_UNSET;
    job->margin = job->spacing = -1;
    job->level = true;
    job->nest_time = NAN;
    job->machine_name = "co2-60w";
    job->material_name = "plywood-3mm";
    ur_develop_options_default(&job->develop);
}

job_run job_run_make(const ur_job *job, const ur_job_callbacks *callbacks, ur_error *error)
{
    job_run run = {.job = *job, .error = error};
    if (callbacks)
        run.callbacks = *callbacks;
    return run;
}

/* A warning or note as the sentence shown, to the job's context's message handler. */
static void job_message(const job_run *run, ur_message_kind kind, const char *setting,
                        const char *format, va_list args)
{
    char message[8192]; /* a warning names pieces and paths: room for many */
    c_vsnprintf(message, sizeof message, format, args);
    ur_context_message_about(run->job.context, kind, setting, "%s", message);
}

void job_warn(const job_run *run, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    job_message(run, UR_MESSAGE_WARNING, "", format, args);
    va_end(args);
}

void job_warn_about(const job_run *run, const char *setting, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    job_message(run, UR_MESSAGE_WARNING, setting, format, args);
    va_end(args);
}

void job_note(const job_run *run, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    job_message(run, UR_MESSAGE_NOTE, "", format, args);
    va_end(args);
}

void job_note_about(const job_run *run, const char *setting, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    job_message(run, UR_MESSAGE_NOTE, setting, format, args);
    va_end(args);
}

ur_status job_fail(const job_run *run, ur_status status, const char *format, ...)
{
    run->error->status = status;
    run->error->setting[0] = '\0';
    va_list args;
    va_start(args, format);
    c_vsnprintf(run->error->message, sizeof run->error->message, format, args);
    va_end(args);
    return status;
}

ur_status job_fail_about(const job_run *run, ur_status status, const char *setting,
                         const char *format, ...)
{
    run->error->status = status;
    va_list args;
    va_start(args, format);
    c_vsnprintf(run->error->message, sizeof run->error->message, format, args);
    va_end(args);
    return ur_error_set_setting(run->error, setting);
}

ur_status job_fail_from(const job_run *run, const ur_error *cause)
{
    job_fail(run, cause->status, "%s: %s", run->job.command, cause->message);
    return ur_error_set_setting(run->error, cause->setting);
}

bool job_shows_progress(const job_run *run)
{
    return run->callbacks.progress && !run->job.quiet;
}

void job_progress(const job_run *run, const ur_job_progress *progress)
{
    if (job_shows_progress(run))
        run->callbacks.progress(run->callbacks.user, progress);
}
