/*
 * run_job.c: a job file run through libunroll alone, as 'unroll job' runs
 * one: a paper drum (a cylinder 30 mm in radius, 60 mm high) developed
 * exactly, twice, its seam given a glue tab and labels, nested on a
 * 600 x 400 mm sheet and written as SVG with a JSON report beside it.
 *
 *   cc run_job.c $(pkg-config --cflags --libs unroll) -o run_job
 *   ./run_job drum.svg "$(pkg-config --variable=profiledir unroll)" [JOB.xml]
 *
 * The second argument is where the machine and material profiles (and
 * the job file's schema) are: the installed ones.  Without JOB.xml the
 * program runs the job file below, read from memory, writing the first
 * argument; with it, that file (samples/jobs/lamp.xml, say), writing into
 * the first argument's directory.  Warnings and notes come back through the
 * context's message handler; the library prints nothing itself.  The program fails unless the flat
 * pieces of its own job cover the two drums' sides exactly, 2 x 2 pi r h.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <unroll/unroll.h>

#define RADIUS 30.0
#define HEIGHT 60.0
#define PI 3.14159265358979323846

/* The job: %s is the name of the output files (the SVG's, without .svg). */
static const char job_text[] = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                               "<job name=\"drums\">\n"
                               "  <machine>co2-60w</machine>\n"
                               "  <material>paper-0.3mm</material>\n"
                               "  <option name=\"allowances\" value=\"tabs\"/>\n"
                               "  <option name=\"sheet\" value=\"600x400\"/>\n"
                               "  <part surface=\"cylinder\" name=\"drum\" quantity=\"2\">\n"
                               "    <option name=\"radius\" value=\"30\"/>\n"
                               "    <option name=\"height\" value=\"60\"/>\n"
                               "  </part>\n"
                               "  <output name=\"%s\" report=\"%s.json\"/>\n"
                               "</job>\n";

/* Warnings and notes alike: each sentence says which it is, and names its settings. */
static void print_message(void *data, ur_message_kind kind, const char *message,
                          const char *setting)
{
    (void)data;
    (void)kind;
    (void)setting;
    fprintf(stderr, "run_job: %s\n", message);
}

/* OUTPUT.svg as its directory and its name without .svg; -1 when it is no .svg. */
static int split_output(const char *output, char *directory, char *name, size_t size)
{
    size_t length = strlen(output);
    if (length < 5 || strcmp(output + length - 4, ".svg") != 0 || length >= size)
        return -1;
    const char *slash = strrchr(output, '/');
    const char *base = slash ? slash + 1 : output;
    if (slash)
        snprintf(directory, size, "%.*s", (int)(slash - output), output);
    else
        strcpy(directory, ".");
    snprintf(name, size, "%.*s", (int)(strlen(base) - 4), base);
    return 0;
}

/* Reads the job file at path, or the drums' job from memory when path is NULL. */
static ur_status read_job(const char *const *roots, const char *path, const char *name,
                          ur_job_file *file, ur_error *error)
{
    if (path)
        return ur_job_file_read(roots, path, file, error);
    char text[sizeof job_text + 512];
    int length = snprintf(text, sizeof text, job_text, name, name);
    if (length < 0 || (size_t)length >= sizeof text)
        return ur_error_set(error, UR_ERROR_INPUT, "the output's name is too long");
    return ur_job_file_read_buffer(roots, "drums.xml", text, (size_t)length, file, error);
}

int main(int argc, char **argv)
{
    char directory[4096], name[4096];
    if ((argc != 3 && argc != 4) || split_output(argv[1], directory, name, sizeof name) != 0) {
        fprintf(stderr, "usage: run_job OUTPUT.svg PROFILE_DIRECTORY [JOB.xml]\n");
        return 2;
    }
    const char *const roots[] = {argv[2], NULL};
    const char *job_path = argc == 4 ? argv[3] : NULL;
    ur_context *context = ur_context_new();
    if (!context) {
        fprintf(stderr, "run_job: out of memory\n");
        return 1;
    }
    ur_context_set_profile_roots(context, roots);
    ur_context_set_message_handler(context, print_message, NULL);

    ur_job_file file;
    ur_error error;
    ur_status status = read_job(roots, job_path, name, &file, &error);
    ur_job_callbacks callbacks = {NULL, NULL, NULL};
    ur_job_result result;
    if (status == UR_OK) {
        status = ur_job_file_run(&file, context, directory, true, &callbacks, &result, &error);
        ur_job_file_free(&file);
    }
    ur_context_free(context);
    if (status != UR_OK) {
        /* error.setting names the settings the message is about, if any. */
        fprintf(stderr, "run_job: %s%s%s%s\n", error.message,
                error.setting[0] ? " (settings: " : "", error.setting, error.setting[0] ? ")" : "");
        return 1;
    }
    fprintf(stderr, "run_job: %zu pieces, %s -> %s\n", result.piece_count, result.sheets,
            result.first_file);
    double sides = 2 * 2 * PI * RADIUS * HEIGHT;
    if (!job_path && (fabs(result.surface_area - sides) > 1e-3 * sides || result.piece_count != 2 ||
                      result.sheet_count != 1)) {
        fprintf(stderr,
                "run_job: surface %.3f mm2 in %zu pieces on %zu sheets, expected %.3f "
                "mm2 in 2 on 1\n",
                result.surface_area, result.piece_count, result.sheet_count, sides);
        return 1;
    }
    return 0;
}
