/*
 * test_job_file.c: job files run through the library alone
 * (ur_job_file_read_buffer, ur_job_file_run), as a program other than
 * unroll would run them, and the settings they give by name
 * (ur_job_option_set).  The files written are read back with libxml2 and
 * jansson; the areas are checked against the surfaces' closed forms (a
 * cylinder's side 2 pi r h, a cone's pi r s), the counts against the
 * quantities asked for.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <jansson.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "unroll/job.h"

#include "test_support.h"

/* The profiles and schemas of the source tree (the tests run from its root). */
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

static int setup(void **state)
{
    char *directory = strdup("/tmp/unroll-test-job-file-XXXXXX");
    if (!directory || !mkdtemp(directory)) {
        free(directory);
        return -1;
    }
    *state = directory;
    return 0;
}

/* The test directory, and the output directory "out" a job file made in it. */
static int teardown(void **state)
{
    char out[200]; /* with room for a file's name within each_entry's 512 */
    snprintf(out, sizeof out, "%s/out", (const char *)*state);
    if (exists(out))
        remove_test_directory(out);
    int status = remove_test_directory(*state);
    free(*state);
    return status;
}

/* Reads the job file text as if from NAME. */
static void read_job(const char *name, const char *text, ur_job_file *file)
{
    ur_error error;
    if (ur_job_file_read_buffer(profile_roots, name, text, strlen(text), file, &error) != UR_OK)
        fail_msg("ur_job_file_read_buffer: %s", error.message);
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

/* The paths an SVG cuts (its layer <g id="cut">); the SVG must parse. */
static size_t paths_cut(const char *path)
{
    xmlDocPtr document = xmlReadFile(path, NULL, XML_PARSE_NONET);
    assert_non_null(document);
    xmlNodePtr root = xmlDocGetRootElement(document);
    assert_non_null(root);
    assert_string_equal((const char *)root->name, "svg");
    size_t count = 0;
    for (xmlNodePtr child = root->children; child; child = child->next) {
        if (child->type != XML_ELEMENT_NODE)
            continue;
        xmlChar *id = xmlGetProp(child, (const xmlChar *)"id");
        if (id && xmlStrcmp(id, (const xmlChar *)"cut") == 0)
            count += count_elements(child, "path") + count_elements(child, "polygon");
        xmlFree(id);
    }
    xmlFreeDoc(document);
    return count;
}

/* How many of the report's pieces are named name; their 3D area summed into *area. */
static size_t pieces_named(json_t *report, const char *prefix, double *area)
{
    size_t count = 0;
    json_t *pieces = json_object_get(report, "pieces");
    for (size_t k = 0; k < json_array_size(pieces); k++) {
        json_t *piece = json_array_get(pieces, k);
        const char *name = json_string_value(json_object_get(piece, "name"));
        if (name && strncmp(name, prefix, strlen(prefix)) == 0) {
            count++;
            *area += json_real_value(json_object_get(piece, "area_3d_mm2"));
        }
    }
    return count;
}

/*
 * Two parts: a drum (a cylinder whose radius is the job's) twice, and a
 * cap (a cone whose own radius replaces the job's) once; nested together
 * on one 600 x 400 sheet into the output directory, which the run makes.
 */
static const char two_parts[] = "<?xml version=\"1.0\"?>\n"
                                "<job name=\"pair\">\n"
                                "  <machine>co2-60w</machine>\n"
                                "  <material>paper-0.3mm</material>\n"
                                "  <option name=\"radius\" value=\"30\"/>\n"
                                "  <option name=\"allowances\" value=\"none\"/>\n"
                                "  <option name=\"sheet\" value=\"600x400\"/>\n"
                                "  <option name=\"nest-time\" value=\"0\"/>\n"
                                "  <part surface=\"cylinder\" name=\"drum\" quantity=\"2\">\n"
                                "    <option name=\"height\" value=\"50\"/>\n"
                                "  </part>\n"
                                "  <part surface=\"cone\" name=\"cap\">\n"
                                "    <option name=\"radius\" value=\"40\"/>\n"
                                "    <option name=\"height\" value=\"30\"/>\n"
                                "  </part>\n"
                                "  <output name=\"pair\" report=\"pair.json\"/>\n"
                                "</job>\n";

static void test_parts_run_from_a_job_file(void **state)
{
    const char *directory = *state;
    char out[512], svg[600], report_path[600];
    path_in(directory, "out", out, sizeof out);
    path_in(out, "pair.svg", svg, sizeof svg);
    path_in(out, "pair.json", report_path, sizeof report_path);
    ur_job_file file;
    read_job("pair.xml", two_parts, &file);
    ur_job_result result;
    ur_error error;
    ur_status status = ur_job_file_run(&file, context, out, true, NULL, &result, &error);
    ur_job_file_free(&file);
    if (status != UR_OK)
        fail_msg("ur_job_file_run: %s", error.message);

    double drum = 2 * M_PI * 30 * 50;                   /* a cylinder's side, 2 pi r h */
    double cap = M_PI * 40 * sqrt(40.0 * 40 + 30 * 30); /* a cone's, pi r s */
    assert_relative(result.surface_area, 2 * drum + cap, 1e-3);
    assert_relative(result.flat_area, 2 * drum + cap, 1e-3); /* developed exactly */
    assert_int_equal(result.sheet_count, 1);
    assert_string_equal(result.first_file, svg);

    json_error_t json_error;
    json_t *report = json_load_file(report_path, 0, &json_error);
    assert_non_null(report);
    size_t count = json_array_size(json_object_get(report, "pieces"));
    assert_int_equal(count, result.piece_count);
    double drum_area = 0, cap_area = 0;
    size_t drum_copies = pieces_named(report, "drum-", &drum_area);
    size_t caps = pieces_named(report, "cap-", &cap_area);
    assert_int_equal(drum_copies + caps, count);
    assert_true(caps >= 1 && drum_copies == 2 * (drum_copies / 2) && drum_copies >= 2);
    assert_int_equal(pieces_named(report, "drum-P1#1", &(double){0}), 1);
    assert_int_equal(pieces_named(report, "drum-P1#2", &(double){0}), 1);
    assert_relative(drum_area, 2 * drum, 1e-3);
    assert_relative(cap_area, cap, 1e-3);
    json_decref(report);
    assert_true(paths_cut(svg) >= count);
}

/* The line of bad_radius[]'s part, whose radius is no number. */
#define BAD_PART_LINE 4

static const char bad_radius[] = "<?xml version=\"1.0\"?>\n"
                                 "<job name=\"bad\">\n"
                                 "  <material>paper-0.3mm</material>\n"
                                 "  <part surface=\"cylinder\">\n"
                                 "    <option name=\"radius\" value=\"forty\"/>\n"
                                 "    <option name=\"height\" value=\"50\"/>\n"
                                 "  </part>\n"
                                 "  <output name=\"bad\" report=\"bad.json\"/>\n"
                                 "</job>\n";

/* A bad value in a part: bad input naming the file and the part's line, and nothing written. */
static void test_bad_value_names_file_and_line(void **state)
{
    const char *directory = *state;
    char out[512];
    path_in(directory, "out", out, sizeof out);
    ur_job_file file;
    read_job("bad.xml", bad_radius, &file);
    ur_error error;
    ur_status status = ur_job_file_run(&file, context, out, true, NULL, NULL, &error);
    ur_job_file_free(&file);
    assert_int_equal(status, UR_ERROR_INPUT);
    char start[64];
    snprintf(start, sizeof start, "bad.xml:%d: cylinder: option radius: 'forty'", BAD_PART_LINE);
    if (strncmp(error.message, start, strlen(start)) != 0)
        fail_msg("message '%s' does not start with '%s'", error.message, start);
    assert_null(strstr(error.message, "--"));
    assert_false(exists(out));
    assert_int_equal(entries_in(directory), 0);
}

/* One part of quantity 1 writes what the same job run alone writes, byte for byte. */
static const char one_part[] = "<?xml version=\"1.0\"?>\n"
                               "<job name=\"drum\">\n"
                               "  <material>cardboard-2mm</material>\n"
                               "  <option name=\"nest-time\" value=\"0\"/>\n"
                               "  <part surface=\"cylinder\">\n"
                               "    <option name=\"radius\" value=\"35\"/>\n"
                               "    <option name=\"height\" value=\"80\"/>\n"
                               "  </part>\n"
                               "  <output name=\"drum\"/>\n"
                               "</job>\n";

static char *file_text(const char *path, long *size)
{
    FILE *stream = fopen(path, "rb");
    assert_non_null(stream);
    assert_int_equal(fseek(stream, 0, SEEK_END), 0);
    *size = ftell(stream);
    rewind(stream);
    char *text = malloc((size_t)*size + 1);
    assert_non_null(text);
    assert_int_equal(fread(text, 1, (size_t)*size, stream), (size_t)*size);
    fclose(stream);
    return text;
}

static void test_one_part_writes_what_its_job_writes(void **state)
{
    const char *directory = *state;
    char out[512], from_file[600], alone[512];
    path_in(directory, "out", out, sizeof out);
    path_in(out, "drum.svg", from_file, sizeof from_file);
    path_in(directory, "alone.svg", alone, sizeof alone);
    ur_job_file file;
    read_job("drum.xml", one_part, &file);
    ur_error error;
    ur_status status = ur_job_file_run(&file, context, out, true, NULL, NULL, &error);
    ur_job_file_free(&file);
    if (status != UR_OK)
        fail_msg("ur_job_file_run: %s", error.message);

    ur_job job;
    ur_job_init(&job, "cylinder");
    job.context = context;
    const char *settings[][2] = {
        {"material", "cardboard-2mm"}, {"nest-time", "0"}, {"radius", "35"}, {"height", "80"},
        {"job-name", "drum"},          {"quiet", NULL}};
    for (size_t k = 0; k < sizeof settings / sizeof settings[0]; k++)
        assert_int_equal(ur_job_option_set(&job, settings[k][0], settings[k][1], &error), UR_OK);
    job.output_path = alone;
    if (ur_job_run(&job, NULL, NULL, &error) != UR_OK)
        fail_msg("ur_job_run: %s", error.message);
    long size_a, size_b;
    char *a = file_text(from_file, &size_a), *b = file_text(alone, &size_b);
    assert_int_equal(size_a, size_b);
    assert_memory_equal(a, b, (size_t)size_a);
    free(a);
    free(b);
}

/* Every setting the table names is one ur_job_option_set takes, on a surface it applies to. */
static void test_every_named_setting_is_taken(void **state)
{
    (void)state;
    const char *surfaces[] = {"cylinder", "cone",  "helicoid", "tangent",
                              "strip",    "ruled", "hypar",    "mesh"};
    bool takes_value;
    const char *name;
    size_t k = 0;
    for (; (name = ur_job_option_name(k, &takes_value)); k++) {
        size_t applies = 0;
        for (size_t s = 0; s < sizeof surfaces / sizeof surfaces[0]; s++)
            applies += ur_job_option_applies(name, surfaces[s]);
        if (applies == 0)
            fail_msg("setting '%s' applies to no surface", name);
        ur_job job;
        ur_job_init(&job, "cylinder");
        ur_error error;
        ur_status status = ur_job_option_set(&job, name, takes_value ? NULL : "x", &error);
        assert_int_equal(status, UR_ERROR_INPUT); /* a value missing, or a flag given one */
    }
    assert_int_equal(k, ur_job_option_count());
    assert_true(k > 60);
}

/* Values set and refused by name, the messages naming no setting and no flag. */
static void test_settings_by_name(void **state)
{
    (void)state;
    ur_job job;
    ur_job_init(&job, "cylinder");
    ur_error error;
    assert_int_equal(ur_job_option_set(&job, "radius", "30", &error), UR_OK);
    assert_true(job.radius == 30);
    assert_int_equal(ur_job_option_set(&job, "direction", "0,1,0", &error), UR_OK);
    assert_true(job.has_direction && job.direction.y == 1);
    assert_int_equal(ur_job_option_set(&job, "allowances", "tabs,bending", &error), UR_OK);
    assert_true(job.allowances == (UR_ALLOW_TABS | UR_ALLOW_BENDING) && !job.allowances_auto);
    assert_int_equal(ur_job_option_set(&job, "margin", "2.5", &error), UR_OK);
    assert_true(job.margin == 2.5);

    assert_int_equal(ur_job_option_set(&job, "radius", "x", &error), UR_ERROR_INPUT);
    assert_string_equal(error.message, "'x' is not a finite number");
    assert_int_equal(ur_job_option_set(&job, "pitch", "2", &error), UR_ERROR_INPUT);
    assert_string_equal(error.message, "does not apply to a cylinder");
    assert_int_equal(ur_job_option_set(&job, "flatten", "arap", &error), UR_ERROR_INPUT);
    assert_int_equal(ur_job_option_set(&job, "colour", "red", &error), UR_ERROR_INPUT);
    assert_null(strstr(error.message, "--"));

    ur_job strip;
    ur_job_init(&strip, "strip");
    assert_int_equal(ur_job_option_set(&strip, "adjust-max", "3", &error), UR_OK);
    assert_int_equal(ur_job_check(&strip, &error), UR_ERROR_INPUT); /* no adjust */
    assert_null(strstr(error.message, "--"));
    assert_int_equal(ur_job_option_set(&strip, "adjust", "rail2", &error), UR_OK);
    assert_int_equal(ur_job_check(&strip, &error), UR_OK);
    assert_int_equal(ur_job_option_set(&strip, "adjust-direction", "0,0,0", &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_job_option_set(&strip, "flatten", "charts", &error), UR_ERROR_INPUT);
    assert_int_equal(ur_job_option_set(&strip, "max-strain", "0.02", &error), UR_OK);
    assert_int_equal(ur_job_check(&strip, &error), UR_ERROR_INPUT); /* not strips */
    assert_int_equal(ur_job_option_set(&strip, "flatten", "strips", &error), UR_OK);
    assert_int_equal(ur_job_check(&strip, &error), UR_OK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_parts_run_from_a_job_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_value_names_file_and_line, setup, teardown),
        cmocka_unit_test_setup_teardown(test_one_part_writes_what_its_job_writes, setup, teardown),
        cmocka_unit_test(test_every_named_setting_is_taken),
        cmocka_unit_test(test_settings_by_name),
    };
    return cmocka_run_group_tests(tests, make_context, free_context);
}
