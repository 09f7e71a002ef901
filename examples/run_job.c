/*
 * run_job.c: a whole job through libunroll alone, as the unroll command
 * runs one: a paper drum (a cylinder 30 mm in radius, 60 mm high)
 * developed exactly, its seam given a glue tab and labels, nested on a
 * 600 x 400 mm sheet and written as SVG with a JSON report beside it.
 *
 *   cc run_job.c $(pkg-config --cflags --libs unroll) -o run_job
 *   ./run_job drum.svg "$(pkg-config --variable=profiledir unroll)"
 *
 * The last argument is where the machine and material profiles are (the
 * installed ones).  Warnings and notes come back through the context's
 * message handler, the summary through a callback; the library prints
 * nothing itself.  The program fails unless the flat
 * piece covers the drum's side exactly, 2 pi r h.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <unroll/unroll.h>

#define RADIUS 30.0
#define HEIGHT 60.0
#define PI 3.14159265358979323846

/* Warnings and notes alike: each sentence says which it is, and names its settings. */
static void print_message(void *data, ur_message_kind kind, const char *message,
                          const char *setting)
{
    (void)data;
    (void)kind;
    (void)setting;
    fprintf(stderr, "run_job: %s\n", message);
}

static void print_summary(void *user, const ur_job_result *result)
{
    (void)user;
    fprintf(stderr, "run_job: %zu piece(s), %s -> %s\n", result->piece_count, result->sheets,
            result->first_file);
}

/* The report's name: the SVG's with .json in place of .svg. */
static int report_path_of(const char *output, char *report, size_t size)
{
    size_t length = strlen(output);
    if (length < 4 || strcmp(output + length - 4, ".svg") != 0 || length + 2 > size)
        return -1;
    memcpy(report, output, length - 4);
    strcpy(report + length - 4, ".json");
    return 0;
}

int main(int argc, char **argv)
{
    char report[4096];
    if (argc != 3 || report_path_of(argv[1], report, sizeof report) != 0) {
        fprintf(stderr, "usage: run_job OUTPUT.svg PROFILE_DIRECTORY\n");
        return 2;
    }
    const char *const roots[] = {argv[2], NULL};
    ur_context *context = ur_context_new();
    if (!context) {
        fprintf(stderr, "run_job: out of memory\n");
        return 1;
    }
    ur_context_set_profile_roots(context, roots);
    ur_context_set_message_handler(context, print_message, NULL);

    ur_job job;
    ur_job_init(&job, "cylinder");
    job.context = context;
    job.radius = RADIUS;
    job.height = HEIGHT;
    job.material_name = "paper-0.3mm";
    job.allowances = UR_ALLOW_TABS; /* a glue tab on the seam, and its labels */
    job.allowances_auto = false;
    job.sheet_width = 600;
    job.sheet_height = 400;
    job.output_path = argv[1];
    job.report_path = report;

    ur_job_callbacks callbacks = {NULL, NULL, print_summary};
    ur_job_result result;
    ur_error error;
    ur_status status = ur_job_run(&job, &callbacks, &result, &error);
    ur_context_free(context);
    if (status != UR_OK) {
        /* error.setting names the settings the message is about, if any. */
        fprintf(stderr, "run_job: %s%s%s%s\n", error.message,
                error.setting[0] ? " (settings: " : "", error.setting, error.setting[0] ? ")" : "");
        return 1;
    }
    double side = 2 * PI * RADIUS * HEIGHT;
    if (fabs(result.surface_area - side) > 1e-3 * side ||
        fabs(result.flat_area - side) > 1e-3 * side || result.sheet_count != 1) {
        fprintf(stderr,
                "run_job: surface %.3f mm2, flat %.3f mm2 on %zu sheets, expected %.3f "
                "mm2 on 1\n",
                result.surface_area, result.flat_area, result.sheet_count, side);
        return 1;
    }
    return 0;
}
