/*
 * fuzz_job.c: fuzz target for job files (src/io/job.c): libxml2 parses the
 * file, profiles/schema/job.rng validates it, and the reader turns the tree
 * into a ur_job_file with its paths joined to the job file's directory.
 *
 * The schema is read from ./profiles/schema: run the target from the top of
 * the source tree (make fuzz does).
 */
#include "fuzz_support.h"

#include "unroll/io.h"

#define FUZZ_TERMINATED(array) FUZZ_CHECK(memchr((array), '\0', sizeof(array)) != NULL)

static void check_option(const ur_job_file_option *option)
{
    FUZZ_TERMINATED(option->name);
    FUZZ_TERMINATED(option->value);
    FUZZ_CHECK(option->line >= 0);
}

static void check_job(const ur_job_file *job)
{
    FUZZ_TERMINATED(job->name);
    FUZZ_TERMINATED(job->machine);
    FUZZ_TERMINATED(job->material);
    FUZZ_TERMINATED(job->output_directory);
    FUZZ_TERMINATED(job->formats);
    FUZZ_TERMINATED(job->report);
    FUZZ_CHECK(job->option_count == 0 || job->options != NULL);
    for (size_t i = 0; i < job->option_count; i++)
        check_option(&job->options[i]);
    FUZZ_CHECK(job->part_count == 0 || job->parts != NULL);
    for (size_t k = 0; k < job->part_count; k++) {
        const ur_job_file_part *part = &job->parts[k];
        FUZZ_TERMINATED(part->surface);
        FUZZ_TERMINATED(part->name);
        FUZZ_TERMINATED(part->file);
        /* Part names are unique within a job. */
        for (size_t j = 0; part->name[0] && j < k; j++)
            FUZZ_CHECK(strcmp(job->parts[j].name, part->name) != 0);
        for (size_t i = 0; i < part->option_count; i++)
            check_option(&part->options[i]);
    }
}

static const char *const roots[] = {"./profiles", NULL};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ur_job_file job;
    ur_error error;
    if (ur_job_file_read_buffer(roots, "job.xml", data, size, &job, &error) == UR_OK) {
        check_job(&job);
        ur_job_file_free(&job);
    } else {
        FUZZ_CHECK(strstr(error.message, "job.xml") != NULL);
        FUZZ_CHECK(job.parts == NULL && job.options == NULL);
    }
    return 0;
}
