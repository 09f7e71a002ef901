/*
 * test_job.c: whole jobs through the library alone (ur_job_run), as a
 * program other than unroll would run them: a cube mesh unfolded with
 * tabs, a cylinder developed, and two parts nested together as a job
 * file's, each written as SVG with a report into a directory under /tmp.  The files are read back
 * with libxml2 and jansson; the figures are checked against the cube's and the cylinder's known
 * areas and against the unfolding's own count of pieces; nothing may reach stderr.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <fcntl.h>
#include <jansson.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "unroll/job.h"
#include "unroll/out.h"

#include "test_support.h"

/* samples/cube.obj (samples/make-meshes.py): a cube of side 100 mm. */
#define CUBE_PATH "samples/cube.obj"
#define CUBE_SIDE 100.0

typedef struct heard {
    size_t warnings, notes;
    bool unfolded_note;    /* the note that says how the mesh was unfolded */
    char tiny_setting[64]; /* the settings the warning on a tiny mesh names */
    size_t flags;          /* messages that name a command-line flag */
    size_t summaries;
    size_t progress_after_done; /* nesting reports after the nesting said it was done */
    bool nesting_done;
} heard;

/* The context's message handler: a job's warnings and notes come only this way. */
static void on_message(void *user, ur_message_kind kind, const char *message, const char *setting)
{
    heard *h = user;
    if (kind == UR_MESSAGE_WARNING && strstr(message, "mm across"))
        snprintf(h->tiny_setting, sizeof h->tiny_setting, "%s", setting);
    if (strstr(message, " --"))
        h->flags++;
    if (kind == UR_MESSAGE_WARNING)
        h->warnings++;
    else
        h->notes++;
    if (kind == UR_MESSAGE_NOTE && strstr(message, "unfolded into"))
        h->unfolded_note = true;
}

static void on_progress(void *user, const ur_job_progress *progress)
{
    heard *h = user;
    if (progress->kind == UR_JOB_NESTING_DONE)
        h->nesting_done = true;
    else if (progress->kind == UR_JOB_NESTING && h->nesting_done)
        h->progress_after_done++;
}

static void on_summary(void *user, const ur_job_result *result)
{
    (void)result;
    ((heard *)user)->summaries++;
}

/* The profiles of the source tree (the tests run from its root), through every job's context. */
static const char *const profile_roots[] = {"./profiles", NULL};
static ur_context *context;

static int make_context(void **state)
{
    (void)state;
    context = ur_context_new();
    if (!context)
        return -1;
    ur_context_set_profile_roots(context, profile_roots);
    return 0;
}

static int free_context(void **state)
{
    (void)state;
    ur_context_free(context);
    return 0;
}

/* A job with the defaults, run in the tests' context. */
static void job_init(ur_job *job, const char *surface)
{
    ur_job_init(job, surface);
    job->context = context;
}

static int setup(void **state)
{
    char *directory = strdup("/tmp/unroll-test-job-XXXXXX");
    if (!directory || !mkdtemp(directory)) {
        free(directory);
        return -1;
    }
    *state = directory;
    return 0;
}

static int teardown(void **state)
{
    ur_context_set_message_handler(context, NULL, NULL); /* a test's handler data is its own */
    int status = remove_test_directory(*state);
    free(*state);
    return status;
}

/*
 * Runs job with stderr sent to a file, and checks that nothing was
 * written there: the library reports through its context's message
 * handler and the callbacks only.
 */
static ur_status run_silently(const ur_job *job, const ur_job_callbacks *callbacks,
                              ur_job_result *result, ur_error *error, const char *directory)
{
    char path[512];
    path_in(directory, "stderr.txt", path, sizeof path);
    fflush(stderr);
    int saved = dup(STDERR_FILENO);
    int file = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_true(saved >= 0 && file >= 0);
    assert_true(dup2(file, STDERR_FILENO) >= 0);
    ur_status status = ur_job_run(job, callbacks, result, error);
    fflush(stderr);
    assert_true(dup2(saved, STDERR_FILENO) >= 0);
    close(saved);
    off_t size = lseek(file, 0, SEEK_END);
    close(file);
    unlink(path);
    assert_int_equal(size, 0);
    return status;
}

/* How many elements named name lie under node, at any depth. */
static size_t count_elements(xmlNodePtr node, const char *name)
{
    size_t count = 0;
    for (xmlNodePtr child = node->children; child; child = child->next)
        if (child->type == XML_ELEMENT_NODE) {
            count += xmlStrcmp(child->name, (const xmlChar *)name) == 0;
            count += count_elements(child, name);
        }
    return count;
}

/* The layer <g id="id"> of an SVG, or NULL. */
static xmlNodePtr layer(xmlNodePtr root, const char *id)
{
    for (xmlNodePtr child = root->children; child; child = child->next) {
        if (child->type != XML_ELEMENT_NODE)
            continue;
        xmlChar *value = xmlGetProp(child, (const xmlChar *)"id");
        bool match = value && xmlStrcmp(value, (const xmlChar *)id) == 0;
        xmlFree(value);
        if (match)
            return child;
    }
    return NULL;
}

/*
 * Every sheet's SVG exists and parses, and has outlines to cut; returns
 * the paths cut over all sheets.
 */
static size_t check_sheets(const char *output, size_t sheet_count)
{
    size_t cut_paths = 0;
    for (size_t s = 0; s < sheet_count; s++) {
        char name[600];
        ur_error error;
        assert_int_equal(ur_sheet_file_name(output, s, sheet_count, name, sizeof name, &error),
                         UR_OK);
        assert_true(exists(name));
        xmlDocPtr document = xmlReadFile(name, NULL, XML_PARSE_NONET);
        assert_non_null(document);
        xmlNodePtr root = xmlDocGetRootElement(document);
        assert_non_null(root);
        assert_string_equal((const char *)root->name, "svg");
        xmlNodePtr cut = layer(root, "cut");
        assert_non_null(cut);
        size_t paths = count_elements(cut, "path") + count_elements(cut, "polygon") +
                       count_elements(cut, "polyline");
        assert_true(paths > 0);
        cut_paths += paths;
        xmlFreeDoc(document);
    }
    return cut_paths;
}

/* The report parses, names every sheet's file, and lists count pieces. */
static void check_report(const char *path, size_t count, size_t sheet_count)
{
    json_error_t json_error;
    json_t *report = json_load_file(path, 0, &json_error);
    assert_non_null(report);
    assert_int_equal(json_array_size(json_object_get(report, "pieces")), count);
    assert_int_equal(json_array_size(json_object_get(report, "sheets")), sheet_count);
    assert_int_equal(json_array_size(json_object_get(report, "outputs")), sheet_count);
    json_decref(report);
}

static void test_mesh_with_tabs_nested_to_svg(void **state)
{
    const char *directory = *state;
    char output[512], report[512];
    path_in(directory, "cube.svg", output, sizeof output);
    path_in(directory, "cube.json", report, sizeof report);
    ur_job job;
    job_init(&job, "mesh");
    job.mesh_path = CUBE_PATH;
    job.unfold = true;
    job.material_name = "paper-0.3mm"; /* glue tabs on the seams */
    job.output_path = output;
    job.report_path = report;
    heard h = {0};
    ur_context_set_message_handler(context, on_message, &h);
    ur_job_callbacks callbacks = {&h, on_progress, on_summary};
    ur_job_result result;
    ur_error error;
    ur_status status = run_silently(&job, &callbacks, &result, &error, directory);
    if (status != UR_OK)
        fail_msg("ur_job_run: %s", error.message);

    /* Every piece holds at least one of the six faces, and none is cut in two. */
    assert_true(result.piece_count >= 1 && result.piece_count <= 6);
    assert_string_equal(result.method, "unfold");
    assert_relative(result.surface_area, 6 * CUBE_SIDE * CUBE_SIDE, 1e-9);
    assert_relative(result.flat_area, 6 * CUBE_SIDE * CUBE_SIDE, 1e-9); /* every face exact */
    assert_string_equal(result.material, "paper-0.3mm");
    assert_true(result.sheet_count >= 1);
    assert_true(check_sheets(output, result.sheet_count) >= result.piece_count);
    check_report(report, result.piece_count, result.sheet_count);
    assert_true(h.unfolded_note);
    assert_int_equal(h.summaries, 1);
    assert_int_equal(h.progress_after_done, 0);
}

static void test_cylinder_developed_to_svg(void **state)
{
    const char *directory = *state;
    char output[512], report[512];
    path_in(directory, "cylinder.svg", output, sizeof output);
    path_in(directory, "cylinder.json", report, sizeof report);
    ur_job job;
    job_init(&job, "cylinder");
    job.radius = 30;
    job.height = 50;
    job.output_path = output;
    job.report_path = report;
    job.quiet = true; /* no notes, no summary: warnings only */
    heard h = {0};
    ur_context_set_message_handler(context, on_message, &h);
    ur_job_callbacks callbacks = {&h, on_progress, on_summary};
    ur_job_result result;
    ur_error error;
    ur_status status = run_silently(&job, &callbacks, &result, &error, directory);
    if (status != UR_OK)
        fail_msg("ur_job_run: %s", error.message);
    double area = 2 * M_PI * 30 * 50;
    /* What developing the same cylinder says, with the same default options. */
    ur_curve *circle = NULL;
    ur_ruled cylinder;
    assert_int_equal(ur_curve_new_circle(30, &circle, &error), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 50, &cylinder, &error),
                     UR_OK);
    ur_develop_options options;
    ur_develop_options_default(&options);
    ur_net_list nets;
    assert_int_equal(ur_develop(&cylinder, &options, &nets, &error), UR_OK);
    assert_int_equal(result.piece_count, nets.count);
    ur_net_list_free(&nets);
    ur_ruled_free(&cylinder);
    assert_relative(result.surface_area, area, 1e-3);
    assert_relative(result.flat_area, area, 1e-3); /* a cylinder develops without strain */
    assert_true(result.piece_count >= 1);
    assert_true(check_sheets(output, result.sheet_count) >= result.piece_count);
    check_report(report, result.piece_count, result.sheet_count);
    assert_int_equal(h.summaries, 0);
    assert_int_equal(h.notes, 0);
}

/* How many of the report's pieces are named name. */
static size_t pieces_named(const char *report_path, const char *name)
{
    json_error_t json_error;
    json_t *report = json_load_file(report_path, 0, &json_error);
    assert_non_null(report);
    json_t *pieces = json_object_get(report, "pieces");
    size_t count = 0;
    for (size_t k = 0; k < json_array_size(pieces); k++) {
        const char *piece = json_string_value(json_object_get(json_array_get(pieces, k), "name"));
        count += piece && strcmp(piece, name) == 0;
    }
    json_decref(report);
    return count;
}

/*
 * Two parts nested together, as a job file's: two drums and a cone, each
 * made as its own job would make it, on shared sheets with one report.
 */
static void test_parts_nested_together(void **state)
{
    const char *directory = *state;
    char alone[512], output[512], report[512];
    path_in(directory, "alone.svg", alone, sizeof alone);
    path_in(directory, "parts.svg", output, sizeof output);
    path_in(directory, "parts.json", report, sizeof report);
    ur_job drum, cone;
    job_init(&drum, "cylinder");
    drum.radius = 30;
    drum.height = 50;
    drum.quiet = true;
    drum.output_path = alone;
    ur_job_result result;
    ur_error error;
    assert_int_equal(ur_job_run(&drum, NULL, &result, &error), UR_OK);
    size_t drum_pieces = result.piece_count;
    double drum_area = result.surface_area;
    job_init(&cone, "cone");
    cone.radius = 40;
    cone.height = 30;
    cone.piece_prefix = "cap";
    drum.piece_prefix = "drum";

    ur_job_parts *parts = ur_job_parts_new();
    assert_non_null(parts);
    assert_int_equal(ur_job_parts_add(parts, &drum, 2, NULL, &error), UR_OK);
    assert_int_equal(ur_job_parts_add(parts, &cone, 1, NULL, &error), UR_OK);
    ur_job layout = drum;
    layout.output_path = output;
    layout.report_path = report;
    ur_status status = ur_job_parts_run(parts, &layout, "job", "test", NULL, &result, &error);
    ur_job_parts_free(parts);
    if (status != UR_OK)
        fail_msg("ur_job_parts_run: %s", error.message);
    assert_true(result.piece_count > 2 * drum_pieces);
    /* the cone's lateral area, pi r s, with s the slant height */
    double cone_area = M_PI * 40 * sqrt(40 * 40 + 30 * 30);
    assert_relative(result.surface_area, 2 * drum_area + cone_area, 1e-3);
    check_sheets(output, result.sheet_count);
    check_report(report, result.piece_count, result.sheet_count);
    assert_int_equal(pieces_named(report, "drum-P1#1"), 1);
    assert_int_equal(pieces_named(report, "drum-P1#2"), 1);
    assert_int_equal(pieces_named(report, "cap-P1"), 1);
    unlink(alone);
}

/* A job that cannot be made fails with a message naming no command-line flag. */
static void test_missing_mesh_is_bad_input(void **state)
{
    const char *directory = *state;
    char output[512];
    path_in(directory, "none.svg", output, sizeof output);
    ur_job job;
    job_init(&job, "mesh");
    job.mesh_path = "samples/no-such-mesh.obj";
    job.output_path = output;
    ur_error error;
    assert_int_equal(run_silently(&job, NULL, NULL, &error, directory), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "no-such-mesh.obj"));
    assert_null(strstr(error.message, "--"));
    assert_false(exists(output));
}

/* A failed run of job in the tests' directory: its status, and that it wrote nothing. */
static ur_status run_failing(const ur_job *job, ur_error *error, const char *directory)
{
    ur_status status = run_silently(job, NULL, NULL, error, directory);
    assert_int_equal(entries_in(directory), 0);
    return status;
}

/*
 * An error about a setting names it as the job's settings are named, in
 * the message and in error.setting, and never as a flag; the setting of
 * an earlier error does not stay behind.  Errors from the stages below
 * the job (developing, nesting) keep the setting they name.
 */
static void test_errors_name_their_setting(void **state)
{
    const char *directory = *state;
    char output[512];
    path_in(directory, "x.svg", output, sizeof output);
    ur_job job;
    ur_error error;

    job_init(&job, "cone");
    job.radius = 40;
    job.height = 30;
    job.top_radius = -1;
    job.output_path = output;
    assert_int_equal(run_failing(&job, &error, directory), UR_ERROR_INPUT);
    assert_string_equal(error.setting, "top-radius");
    assert_non_null(strstr(error.message, "top-radius"));
    assert_null(strstr(error.message, "--"));

    job.top_radius = 20;
    job.develop.method = UR_METHOD_TRIANGLE; /* for tangent developables only */
    assert_int_equal(run_failing(&job, &error, directory), UR_ERROR_INPUT);
    assert_int_equal(strncmp(error.setting, "method", 6), 0);
    assert_null(strstr(error.message, "--"));

    job_init(&job, "cylinder");
    job.radius = 100; /* 628 mm round: no piece fits a 600 x 400 mm sheet in any turn */
    job.height = 700;
    job.output_path = output;
    job.sheet_width = 600;
    job.sheet_height = 400;
    assert_int_equal(run_failing(&job, &error, directory), UR_ERROR_INPUT);
    assert_string_equal(error.setting, "sheet");
    assert_null(strstr(error.message, "--"));

    job.radius = -3;
    assert_int_equal(run_failing(&job, &error, directory), UR_ERROR_INPUT);
    assert_string_equal(error.setting, "radius");
    assert_null(strstr(error.message, "--"));

    /* Settings that do not go together: both named, for the surface alone too. */
    job_init(&job, "hypar");
    job.max_strain = 0.01; /* for flatten strips or charts only */
    job.output_path = output;
    assert_int_equal(run_failing(&job, &error, directory), UR_ERROR_INPUT);
    assert_string_equal(error.setting, "max-strain flatten");
    assert_null(strstr(error.message, "--"));
    ur_ruled ruled;
    assert_int_equal(ur_job_surface(&job, NULL, &ruled, &error), UR_ERROR_INPUT);
    assert_string_equal(error.setting, "max-strain flatten");

    /* No stale setting: an error about no setting has none. */
    assert_int_equal(ur_error_set(&error, UR_ERROR_INPUT, "no file"), UR_ERROR_INPUT);
    assert_string_equal(error.setting, "");
    assert_int_equal(ur_error_set_setting(&error, "units"), UR_ERROR_INPUT);
    ur_error_prefix(&error, "a.dxf: ");
    assert_string_equal(error.setting, "units");
    ur_error_clear(&error);
    assert_string_equal(error.setting, "");
}

/*
 * A warning that advises a setting names it to the message handler: a
 * mesh 2 mm across is read as millimetres, and the warning names units
 * (twice: metres and inches) and scale.
 */
static void test_warnings_name_their_settings(void **state)
{
    const char *directory = *state;
    char output[512], mesh[512];
    path_in(directory, "tiny.svg", output, sizeof output);
    path_in(directory, "tiny.obj", mesh, sizeof mesh);
    FILE *file = fopen(mesh, "w");
    assert_non_null(file);
    for (int corner = 0; corner < 8; corner++) /* a cube 2 units across, as Blender's default */
        fprintf(file, "v %d %d %d\n", corner & 1 ? 1 : -1, corner & 2 ? 1 : -1,
                corner & 4 ? 1 : -1);
    fputs("f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n", file);
    assert_int_equal(fclose(file), 0);
    ur_job job;
    job_init(&job, "mesh");
    job.mesh_path = mesh;
    job.material_name = "paper-0.3mm";
    job.unfold = true;
    job.output_path = output;
    heard h = {0};
    ur_context_set_message_handler(context, on_message, &h);
    ur_error error;
    ur_status status = run_silently(&job, NULL, NULL, &error, directory);
    if (status != UR_OK)
        fail_msg("ur_job_run: %s", error.message);
    assert_string_equal(h.tiny_setting, "units units scale");
    assert_int_equal(h.flags, 0);
}

/*
 * A cancelled context stops the job and leaves nothing on disk; cleared,
 * the same context runs it, and the files appear together.
 */
static void test_cancelled_context_writes_nothing(void **state)
{
    const char *directory = *state;
    char output[512], report[512];
    path_in(directory, "cone.svg", output, sizeof output);
    path_in(directory, "cone.json", report, sizeof report);
    ur_job job;
    job_init(&job, "cone");
    job.radius = 40;
    job.top_radius = 20;
    job.height = 30;
    job.output_path = output;
    job.report_path = report;
    job.quiet = true;
    ur_error error;
    ur_context_cancel(context);
    ur_status status = run_silently(&job, NULL, NULL, &error, directory);
    ur_context_cancel_clear(context);
    assert_int_equal(status, UR_ERROR_CANCELLED);
    assert_int_equal(entries_in(directory), 0);
    ur_job_result result;
    assert_int_equal(run_silently(&job, NULL, &result, &error, directory), UR_OK);
    assert_true(exists(report));
    assert_true(check_sheets(output, result.sheet_count) >= result.piece_count);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_mesh_with_tabs_nested_to_svg, setup, teardown),
        cmocka_unit_test_setup_teardown(test_cylinder_developed_to_svg, setup, teardown),
        cmocka_unit_test_setup_teardown(test_parts_nested_together, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_mesh_is_bad_input, setup, teardown),
        cmocka_unit_test_setup_teardown(test_errors_name_their_setting, setup, teardown),
        cmocka_unit_test_setup_teardown(test_warnings_name_their_settings, setup, teardown),
        cmocka_unit_test_setup_teardown(test_cancelled_context_writes_nothing, setup, teardown),
    };
    return cmocka_run_group_tests(tests, make_context, free_context);
}
