/*
 * test_out_of_memory.c: whole jobs run again and again with one allocation
 * of the library refused, the first, then the second, and so on to the
 * last (every few for the longer jobs): each run must end with UR_OK or
 * UR_ERROR_MEMORY (never "internal error" or "bad input" for memory the
 * system refused), with its error saying the same, and leave no file
 * behind; a run that ends with UR_OK must have written the very files a
 * run without a refusal writes.  Under SANITIZE=1 LeakSanitizer checks at
 * exit that no failed run leaked what it had allocated, and ASan that none
 * touched freed or missing memory.
 *
 * The Makefile links this test with -Wl,--wrap=malloc,... so that the
 * library's own calls (the objects of libunroll-objects.a and this file)
 * go through the __wrap_ functions below; GEOS, cairo, libxml2 and the C
 * library itself keep the real allocator, whose failures this test does
 * not reach.  The nesting search is off (nest_time 0): its allocations
 * depend on the clock.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/job.h"
#include "unroll/out.h"

#include "test_support.h"

/* ---- The failing allocator -------------------------------------------------- */

void *__real_malloc(size_t size);
void *__real_calloc(size_t count, size_t size);
void *__real_realloc(void *memory, size_t size);
char *__real_strdup(const char *text);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t count, size_t size);
void *__wrap_realloc(void *memory, size_t size);
char *__wrap_strdup(const char *text);

/* Allocations counted since the run began (atomic: the nesting search runs threads). */
static atomic_long allocations;
/* The one that fails, counted from 1; 0: none does. */
static atomic_long failing;

static bool refuse(void)
{
    long number = atomic_fetch_add(&allocations, 1) + 1;
    return number == atomic_load(&failing);
}

void *__wrap_malloc(size_t size)
{
    return refuse() ? NULL : __real_malloc(size);
}

void *__wrap_calloc(size_t count, size_t size)
{
    return refuse() ? NULL : __real_calloc(count, size);
}

void *__wrap_realloc(void *memory, size_t size)
{
    return refuse() ? NULL : __real_realloc(memory, size);
}

char *__wrap_strdup(const char *text)
{
    return refuse() ? NULL : __real_strdup(text);
}

/* ---- The jobs ---------------------------------------------------------------- */

/* The profiles of the source tree (the tests run from its root). */
static const char *const profile_roots[] = {"./profiles", NULL};

/*
 * Loaded once, before any allocation fails, and given to every job: the
 * runs are then quicker, and the loading has a test of its own.
 */
static ur_machine machine;
static ur_material material;

/*
 * At most this many runs of a job (fewer for a slow one): past it, every
 * stride-th allocation fails, so that the test takes seconds.
 */
#ifndef MAX_RUNS /* -DMAX_RUNS=1000000 refuses every allocation in turn */
#define MAX_RUNS 250
#endif

typedef void (*job_maker)(ur_job *job, const char *directory, char *output, char *report);

/* A paper drum, its seam given a glue tab and labels, nested, as SVG with a report. */
static void cylinder_with_tabs(ur_job *job, const char *directory, char *output, char *report)
{
    ur_job_init(job, "cylinder");
    job->radius = 30;
    job->height = 60;
    job->allowances = UR_ALLOW_TABS;
    job->allowances_auto = false;
    job->sheet_width = 600;
    job->sheet_height = 400;
    path_in(directory, "drum.svg", output, 512);
    path_in(directory, "drum.json", report, 512);
    job->output_path = output;
    job->report_path = report;
}

/* samples/cube.obj (samples/make-meshes.py) unfolded along its edges with tabs, as SVG. */
static void cube_unfolded(ur_job *job, const char *directory, char *output, char *report)
{
    ur_job_init(job, "mesh");
    job->mesh_path = "samples/cube.obj";
    job->unfold = true;
    path_in(directory, "cube.svg", output, 512);
    path_in(directory, "cube.json", report, 512);
    job->output_path = output;
    job->report_path = report;
}

/* A strip between the rails of samples/band-rail*.csv, its rulings drawn, as SVG, DXF and PDF. */
static void band_in_three_formats(ur_job *job, const char *directory, char *output, char *report)
{
    ur_job_init(job, "strip");
    job->rail_paths[0] = "samples/band-rail1.csv";
    job->rail_paths[1] = "samples/band-rail2.csv";
    job->draw_rulings = true;
    job->formats = UR_FORMAT_SVG | UR_FORMAT_DXF | UR_FORMAT_PDF;
    path_in(directory, "band.svg", output, 512);
    path_in(directory, "band.json", report, 512);
    job->output_path = output;
    job->report_path = report;
}

/* samples/icosphere.obj (samples/make-meshes.py) flattened by ARAP, with its strain picture. */
static void icosphere_flattened(ur_job *job, const char *directory, char *output, char *report)
{
    ur_job_init(job, "mesh");
    job->mesh_path = "samples/icosphere.obj";
    job->flatten = UR_FLATTEN_ARAP;
    job->iterations = 2;
    path_in(directory, "sphere.svg", output, 512);
    path_in(directory, "sphere.png", report, 512);
    job->output_path = output;
    job->strain_png_path = report;
}

/* ---- What a run leaves ---------------------------------------------------------- */

typedef struct snapshot {
    char *bytes; /* each file's name, a newline, its size, a newline and its bytes, by name */
    size_t size;
} snapshot;

static void snapshot_add(snapshot *s, const void *data, size_t size)
{
    char *grown = realloc(s->bytes, s->size + size + 1);
    assert_non_null(grown);
    s->bytes = grown;
    memcpy(s->bytes + s->size, data, size);
    s->size += size;
}

/* Every file in directory, named and in full. */
static snapshot take_snapshot(const char *directory)
{
    snapshot s = {NULL, 0};
    struct dirent **entries;
    int count = scandir(directory, &entries, NULL, alphasort);
    assert_true(count >= 0);
    for (int i = 0; i < count; i++) {
        const char *name = entries[i]->d_name;
        if (strcmp(name, ".") != 0 && strcmp(name, "..") != 0) {
            char path[600], line[600];
            path_in(directory, name, path, sizeof path);
            FILE *file = fopen(path, "rb");
            assert_non_null(file);
            assert_int_equal(fseek(file, 0, SEEK_END), 0);
            long size = ftell(file);
            rewind(file);
            int length = snprintf(line, sizeof line, "%s\n%ld\n", name, size);
            snapshot_add(&s, line, (size_t)length);
            char buffer[4096];
            size_t got;
            while ((got = fread(buffer, 1, sizeof buffer, file)) > 0)
                snapshot_add(&s, buffer, got);
            fclose(file);
        }
        free(entries[i]);
    }
    free(entries);
    return s;
}

static bool same_snapshot(const snapshot *a, const snapshot *b)
{
    return a->size == b->size && memcmp(a->bytes, b->bytes, a->size) == 0;
}

/* One run of the job with allocation number fail_at (0: none) refused; returns its status. */
static ur_status run_failing(job_maker make, ur_context *context, const char *directory,
                             long fail_at, ur_error *error)
{
    char output[512], report[512];
    ur_job job;
    make(&job, directory, output, report);
    job.context = context;
    job.machine = &machine;
    job.material = &material;
    job.quiet = true;
    job.nest_time = 0; /* no search: the same allocations every run */
    job.threads = 1;
    ur_job_result result;
    error->status = UR_OK;
    atomic_store(&allocations, 0);
    atomic_store(&failing, fail_at);
    ur_status status = ur_job_run(&job, NULL, &result, error);
    atomic_store(&failing, 0);
    return status;
}

static void check_job(job_maker make, const char *name, long max_runs)
{
    char directory[] = "/tmp/unroll-test-oom-XXXXXX";
    assert_non_null(mkdtemp(directory));
    ur_context *context = ur_context_new();
    assert_non_null(context);
    ur_context_set_profile_roots(context, profile_roots);

    ur_error error;
    ur_status status = run_failing(make, context, directory, 0, &error);
    if (status != UR_OK)
        fail_msg("%s without a failure: %s", name, error.message);
    long total = atomic_load(&allocations);
    assert_true(total > 0);
    snapshot clean = take_snapshot(directory);
    each_entry(directory, unlink);

    long stride = total / max_runs + 1;
    long failed_runs = 0;
    for (long n = 1; n <= total; n += stride) {
        status = run_failing(make, context, directory, n, &error);
        if (status != UR_OK && status != UR_ERROR_MEMORY)
            fail_msg("%s, allocation %ld of %ld refused: status %d: %s", name, n, total, status,
                     error.message);
        if (status != UR_OK) {
            failed_runs++;
            if (error.status != UR_ERROR_MEMORY)
                fail_msg("%s, allocation %ld refused: returned out of memory, the error says "
                         "status %d: %s",
                         name, n, error.status, error.message);
            if (entries_in(directory) != 0)
                fail_msg("%s, allocation %ld refused: files left behind", name, n);
        } else {
            /*
             * A run that goes on without what it was refused must make the same files:
             * not, say, a tab silently left off or a part put on a sheet of its own.
             */
            snapshot got = take_snapshot(directory);
            bool same = same_snapshot(&got, &clean);
            free(got.bytes);
            if (!same)
                fail_msg("%s, allocation %ld refused: the run succeeded with other files", name, n);
        }
        each_entry(directory, unlink);
    }
    free(clean.bytes);
    printf("%s: %ld allocations, %ld refused one at a time (stride %ld), %ld runs failed\n", name,
           total, (total + stride - 1) / stride, stride, failed_runs);
    assert_true(failed_runs > 0);
    ur_context_free(context);
    assert_int_equal(remove_test_directory(directory), 0);
}

/* The profiles the jobs use, loaded with each allocation refused in turn. */
static void test_profiles(void **state)
{
    (void)state;
    ur_error error;
    ur_machine loaded_machine;
    ur_material loaded_material;
    atomic_store(&allocations, 0);
    assert_int_equal(ur_machine_load(profile_roots, "co2-60w", &loaded_machine, &error), UR_OK);
    assert_int_equal(ur_material_load(profile_roots, "paper-0.3mm", &loaded_material, &error),
                     UR_OK);
    long total = atomic_load(&allocations), failed_runs = 0;
    for (long n = 1; n <= total; n++) {
        atomic_store(&allocations, 0);
        atomic_store(&failing, n);
        ur_status status = ur_machine_load(profile_roots, "co2-60w", &loaded_machine, &error);
        if (status == UR_OK)
            status = ur_material_load(profile_roots, "paper-0.3mm", &loaded_material, &error);
        atomic_store(&failing, 0);
        if (status != UR_OK && status != UR_ERROR_MEMORY)
            fail_msg("profiles, allocation %ld of %ld refused: status %d: %s", n, total, status,
                     error.message);
        failed_runs += status != UR_OK;
    }
    printf("profiles: %ld allocations, %ld runs failed\n", total, failed_runs);
}

/*
 * The parts drawn in samples/brackets.dxf (samples/make-drawings.py), read with each allocation
 * refused in turn (nesting them takes seconds a run: the jobs above nest fewer parts).
 */
static void test_parts_read(void **state)
{
    (void)state;
    ur_parts_import_options options;
    ur_parts_import_options_default(&options);
    ur_parts parts;
    ur_error error;
    atomic_store(&allocations, 0);
    assert_int_equal(ur_parts_import("samples/brackets.dxf", &options, &parts, &error), UR_OK);
    long total = atomic_load(&allocations), failed_runs = 0;
    size_t count = parts.count;
    ur_parts_free(&parts);
    for (long n = 1; n <= total; n++) {
        atomic_store(&allocations, 0);
        atomic_store(&failing, n);
        ur_status status = ur_parts_import("samples/brackets.dxf", &options, &parts, &error);
        atomic_store(&failing, 0);
        if (status != UR_OK && status != UR_ERROR_MEMORY)
            fail_msg("parts, allocation %ld of %ld refused: status %d: %s", n, total, status,
                     error.message);
        if (status == UR_OK && parts.count != count)
            fail_msg("parts, allocation %ld refused: %zu parts read, not %zu", n, parts.count,
                     count);
        if (status == UR_OK)
            ur_parts_free(&parts);
        failed_runs += status != UR_OK;
    }
    printf("parts: %ld allocations, %ld runs failed\n", total, failed_runs);
    assert_true(failed_runs > 0);
}

static int load_profiles(void **state)
{
    (void)state;
    ur_error error;
    if (ur_machine_load(profile_roots, "co2-60w", &machine, &error) != UR_OK ||
        ur_material_load(profile_roots, "paper-0.3mm", &material, &error) != UR_OK) {
        fprintf(stderr, "test_out_of_memory: %s\n", error.message);
        return -1;
    }
    return 0;
}

static void test_cylinder_with_tabs(void **state)
{
    (void)state;
    check_job(cylinder_with_tabs, "cylinder with tabs", MAX_RUNS);
}

static void test_cube_unfolded(void **state)
{
    (void)state;
    check_job(cube_unfolded, "cube unfolded", MAX_RUNS);
}

static void test_band_in_three_formats(void **state)
{
    (void)state;
    check_job(band_in_three_formats, "band in three formats", MAX_RUNS);
}

static void test_icosphere_flattened(void **state)
{
    (void)state;
    check_job(icosphere_flattened, "icosphere flattened", MAX_RUNS / 6);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_profiles),
        cmocka_unit_test(test_parts_read),
        cmocka_unit_test(test_cylinder_with_tabs),
        cmocka_unit_test(test_cube_unfolded),
        cmocka_unit_test(test_band_in_three_formats),
        cmocka_unit_test(test_icosphere_flattened),
    };
    return cmocka_run_group_tests(tests, load_profiles, NULL);
}
