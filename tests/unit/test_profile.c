/*
 * test_profile.c: machine and material profiles: the shipped profiles load
 * with the figures they were written with, bad files are refused naming file
 * and line, names are checked, the search path and the listing behave.
 *
 * Run from the repository root: ./profiles is the first profile root the
 * tests give the library.  The bad profiles go into a temporary second
 * root, under names that do not exist in ./profiles.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <libxml/parser.h>

#include "unroll/io.h"

#define MAX_WRITTEN 32

static char root[64];
/* The roots every test searches: ./profiles, then the temporary root. */
static const char *roots[] = {"./profiles", root, NULL};
static char written[MAX_WRITTEN][256];
static int written_count;

static int make_root(void **state)
{
    (void)state;
    if (access("profiles/schema/machine.rng", R_OK) != 0) {
        fprintf(stderr, "test_profile: run from the repository root\n");
        return -1;
    }
    strcpy(root, "/tmp/unroll-test-profile-XXXXXX");
    if (!mkdtemp(root))
        return -1;
    char path[128];
    snprintf(path, sizeof path, "%s/machines", root);
    if (mkdir(path, 0755) != 0)
        return -1;
    snprintf(path, sizeof path, "%s/materials", root);
    if (mkdir(path, 0755) != 0)
        return -1;
    return 0;
}

static int remove_root(void **state)
{
    (void)state;
    for (int i = 0; i < written_count; i++)
        unlink(written[i]);
    char path[128];
    snprintf(path, sizeof path, "%s/machines", root);
    rmdir(path);
    snprintf(path, sizeof path, "%s/materials", root);
    rmdir(path);
    xmlCleanupParser(); /* so valgrind sees libxml2's globals freed */
    return rmdir(root);
}

/* Writes ROOT/FOLDER/NAME.xml and returns its path (kept until teardown). */
static const char *write_profile(const char *folder, const char *name, const char *text)
{
    assert_true(written_count < MAX_WRITTEN);
    char *path = written[written_count++];
    snprintf(path, sizeof written[0], "%s/%s/%s.xml", root, folder, name);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_int_equal(fwrite(text, 1, strlen(text), file), strlen(text));
    assert_int_equal(fclose(file), 0);
    return path;
}

/* Asserts that message begins with "PATH:LINE: " and contains fragment. */
static void expect_located(const char *message, const char *path, int line, const char *fragment)
{
    char prefix[300];
    snprintf(prefix, sizeof prefix, "%s:%d: ", path, line);
    if (strncmp(message, prefix, strlen(prefix)) != 0)
        fail_msg("message '%s' does not start with '%s'", message, prefix);
    if (fragment && !strstr(message, fragment))
        fail_msg("message '%s' lacks '%s'", message, fragment);
}

/* Replaces the first from in text by to; from must be there. */
static void replace(char *text, size_t size, const char *from, const char *to)
{
    char *found = strstr(text, from);
    assert_non_null(found);
    size_t from_length = strlen(from), to_length = strlen(to);
    assert_true(strlen(text) - from_length + to_length < size);
    memmove(found + to_length, found + from_length, strlen(found + from_length) + 1);
    memcpy(found, to, to_length);
}

static void expect_style(const ur_op_style *style, const char *layer, const char *colour,
                         double width)
{
    assert_string_equal(style->layer, layer);
    assert_string_equal(style->colour, colour);
    assert_true(style->line_width == width);
}

/* ---- The shipped machines ---------------------------------------------- */

static void test_co2_laser(void **state)
{
    (void)state;
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "co2-60w", &machine, &error), UR_OK);
    assert_string_equal(machine.name, "co2-60w");
    assert_string_equal(machine.source, "./profiles/machines/co2-60w.xml");
    assert_non_null(strstr(machine.description, "60 W"));
    assert_int_equal(machine.kind, UR_MACHINE_LASER);
    assert_true(machine.bed_width == 600.0 && machine.bed_height == 400.0);
    assert_true(machine.kerf == 0.2);
    assert_true(machine.margin == 5.0 && machine.spacing == 2.0);
    assert_true(machine.cut_speed == 15.0 && machine.travel_speed == 300.0);
    /* LightBurn's palette: red cut, blue score, green kerf, black engrave. */
    expect_style(&machine.styles[UR_OP_CUT], "Cut", "#FF0000", 0.025);
    expect_style(&machine.styles[UR_OP_SCORE], "Score", "#0000FF", 0.025);
    expect_style(&machine.styles[UR_OP_KERF], "Kerf", "#00E000", 0.025);
    expect_style(&machine.styles[UR_OP_ENGRAVE], "Engrave", "#000000", 0.1);
    expect_style(&machine.styles[UR_OP_MARK], "Mark", "#FF00FF", 0.025);
}

static void test_diode_laser(void **state)
{
    (void)state;
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "diode-10w", &machine, &error), UR_OK);
    assert_int_equal(machine.kind, UR_MACHINE_LASER);
    assert_true(machine.bed_width == 400.0 && machine.bed_height == 400.0);
    assert_true(machine.kerf == 0.1);
    assert_true(machine.cut_speed > 0.0 && machine.cut_speed < machine.travel_speed);
    expect_style(&machine.styles[UR_OP_CUT], "Cut", "#FF0000", 0.025);
    expect_style(&machine.styles[UR_OP_MARK], "Mark", "#FF00FF", 0.025);
}

static void test_router(void **state)
{
    (void)state;
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "router", &machine, &error), UR_OK);
    assert_int_equal(machine.kind, UR_MACHINE_ROUTER);
    assert_true(machine.bed_width == 2440.0 && machine.bed_height == 1220.0);
    assert_true(machine.kerf == 3.175);
    assert_true(machine.spacing == 6.35);
    assert_true(machine.spacing >= machine.kerf); /* docs/design.md section 8 */
    assert_true(machine.margin == 10.0);
    assert_string_equal(machine.styles[UR_OP_CUT].colour, "#FF0000");
}

/* ---- The shipped materials --------------------------------------------- */

static void load_material(const char *name, ur_material *material)
{
    ur_error error = {0};
    if (ur_material_load(roots, name, material, &error) != UR_OK)
        fail_msg("%s: %s", name, error.message);
    assert_string_equal(material->name, name);
    /* Figures every material must have, whatever it is. */
    assert_true(material->stock_count >= 1);
    assert_true(material->bend_radius_with_grain > 0.0);
    assert_true(material->bend_radius_across_grain > 0.0);
    assert_true(material->max_stretch > 0.0 && material->max_stretch < 0.1);
    assert_true(material->max_compression > 0.0 && material->max_compression < 0.1);
    assert_true(material->k_factor > 0.0 && material->k_factor <= 0.5);
    assert_true(material->tab_depth > 0.0);
    assert_true(material->tab_angle > 0.0 && material->tab_angle <= 90.0);
    assert_true(material->hinge_cut_length > material->hinge_connection);
    assert_true(material->hinge_distance > 0.0);
}

static void expect_stock(const ur_material *material, int index, double width, double height)
{
    assert_true(index < material->stock_count);
    assert_true(material->stock[index].width == width);
    assert_true(material->stock[index].height == height);
}

static void test_plywood(void **state)
{
    (void)state;
    ur_material material;
    load_material("plywood-3mm", &material);
    assert_true(material.thickness == 3.0);
    assert_int_equal(material.stock_count, 3);
    expect_stock(&material, 0, 600.0, 400.0);
    expect_stock(&material, 1, 1220.0, 610.0);
    expect_stock(&material, 2, 2440.0, 1220.0);
    assert_true(material.kerf_laser == 0.20); /* docs/design.md section 8 */
    assert_true(material.kerf_router == 0.0); /* the router's bit decides */
    assert_int_equal(material.grain, UR_GRAIN_ACROSS);
    assert_true(material.grain_tolerance == 15.0);
    /* Plywood bends tighter across its face grain than along it. */
    assert_true(material.bend_radius_across_grain < material.bend_radius_with_grain);
    /* docs/design.md section 8: slit about 5 t, bridge 1 t, rows 0.5 t apart. */
    assert_true(material.hinge_cut_length == 15.0);
    assert_true(material.hinge_connection == 3.0);
    assert_true(material.hinge_distance == 1.5);

    load_material("plywood-6mm", &material);
    assert_true(material.thickness == 6.0);
    assert_true(material.kerf_laser == 0.25);
    expect_stock(&material, 0, 600.0, 400.0);
}

static void test_mdf(void **state)
{
    (void)state;
    ur_material material;
    load_material("mdf-3mm", &material);
    assert_true(material.thickness == 3.0);
    assert_true(material.kerf_laser == 0.18);
    assert_int_equal(material.grain, UR_GRAIN_NONE);
    assert_true(material.grain_tolerance == 0.0);
    assert_true(material.bend_radius_with_grain == material.bend_radius_across_grain);
}

static void test_cardboard_paper_polypropylene(void **state)
{
    (void)state;
    ur_material material;
    load_material("cardboard-2mm", &material);
    assert_true(material.thickness == 2.0);
    expect_stock(&material, 0, 1000.0, 700.0);
    assert_true(material.kerf_laser >= 0.12 && material.kerf_laser <= 0.19);
    assert_true(material.max_stretch < material.max_compression);
    assert_int_equal(material.grain, UR_GRAIN_ALONG);

    load_material("paper-0.3mm", &material);
    assert_true(material.thickness == 0.3);
    expect_stock(&material, 0, 420.0, 297.0); /* A3 */
    expect_stock(&material, 1, 297.0, 210.0); /* A4 */
    assert_true(material.max_stretch < material.max_compression);

    load_material("polypropylene-0.8mm", &material);
    assert_true(material.thickness == 0.8);
    expect_stock(&material, 0, 1000.0, 700.0);
    expect_stock(&material, 1, 600.0, 400.0);
    assert_int_equal(material.grain, UR_GRAIN_NONE);
}

static void test_effective_kerf(void **state)
{
    (void)state;
    ur_machine co2, diode, router;
    ur_material plywood, mdf;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "co2-60w", &co2, &error), UR_OK);
    assert_int_equal(ur_machine_load(roots, "diode-10w", &diode, &error), UR_OK);
    assert_int_equal(ur_machine_load(roots, "router", &router, &error), UR_OK);
    assert_int_equal(ur_material_load(roots, "plywood-6mm", &plywood, &error), UR_OK);
    assert_int_equal(ur_material_load(roots, "mdf-3mm", &mdf, &error), UR_OK);
    assert_true(ur_effective_kerf(&co2, &plywood) == 0.25);
    assert_true(ur_effective_kerf(&diode, &mdf) == 0.18);
    assert_true(ur_effective_kerf(&router, &plywood) == 3.175); /* no router figure */
    assert_true(ur_effective_kerf(&co2, NULL) == 0.2);
    plywood.kerf_router = 3.3;
    assert_true(ur_effective_kerf(&router, &plywood) == 3.3);
    plywood.kerf_laser = 0.0;
    assert_true(ur_effective_kerf(&co2, &plywood) == 0.2);
}

/* ---- Bad profiles ------------------------------------------------------ */

static const char good_machine_head[] = "<?xml version=\"1.0\"?>\n"           /* 1 */
                                        "<machine>\n"                         /* 2 */
                                        "  <description>Test</description>\n" /* 3 */
                                        "  <kind>laser</kind>\n";             /* 4 */

static const char good_machine_tail[] =
    "  <margin>5</margin>\n"
    "  <spacing>2</spacing>\n"
    "  <speed cut=\"10\" travel=\"100\"/>\n"
    "  <operation name=\"cut\" layer=\"Cut\" colour=\"#ff0000\" line-width=\"0.025\"/>\n"
    "  <operation name=\"score\" layer=\"Score\" colour=\"#0000FF\" line-width=\"0.025\"/>\n"
    "  <operation name=\"score-valley\" layer=\"Valley\" colour=\"#00E0E0\" line-width=\"0.025\"\n"
    "             dash=\"3 1.5\"/>\n"
    "  <operation name=\"kerf\" layer=\"Kerf\" colour=\"#00E000\" line-width=\"0.025\"/>\n"
    "  <operation name=\"engrave\" layer=\"Engrave\" colour=\"#000000\" line-width=\"0.1\"/>\n"
    "  <operation name=\"mark\" layer=\"Mark\" colour=\"#FF00FF\" line-width=\"0.025\"/>\n"
    "</machine>\n";

/* A machine file: the head, then middle (lines 5 on), then the tail. */
static const char *write_machine(const char *name, const char *middle)
{
    char text[4096];
    snprintf(text, sizeof text, "%s%s%s", good_machine_head, middle, good_machine_tail);
    return write_profile("machines", name, text);
}

static void test_own_profile_from_a_root(void **state)
{
    (void)state;
    const char *path = write_machine("test-good", "  <bed width=\"300\" height=\"200\"/>\n"
                                                  "  <kerf>0.15</kerf>\n");
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "test-good", &machine, &error), UR_OK);
    assert_string_equal(machine.source, path);
    assert_true(machine.bed_width == 300.0 && machine.bed_height == 200.0);
    assert_true(machine.kerf == 0.15);
    assert_string_equal(machine.styles[UR_OP_CUT].colour, "#FF0000"); /* upper-cased */
}

static void test_malformed_xml(void **state)
{
    (void)state;
    const char *path = write_machine("test-malformed", "  <bed width=\"300\" height=\"200\"/>\n"
                                                       "  <kerf>0.15</kref>\n"); /* line 6 */
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "test-malformed", &machine, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 6, "kerf");
    assert_null(strchr(error.message, '\n'));

    path = write_profile("machines", "test-unclosed", "<machine>\n<description>x\n\n\n");
    assert_int_equal(ur_machine_load(roots, "test-unclosed", &machine, &error), UR_ERROR_INPUT);
    assert_int_equal(strncmp(error.message, path, strlen(path)), 0);
    assert_int_equal(error.message[strlen(path)], ':');
}

static void test_negative_kerf(void **state)
{
    (void)state;
    const char *path = write_machine("test-negative", "  <bed width=\"300\" height=\"200\"/>\n"
                                                      "  <kerf>-0.2</kerf>\n");
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "test-negative", &machine, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 6, "kerf");
}

static void test_colour_name_refused(void **state)
{
    (void)state;
    char text[4096];
    snprintf(text, sizeof text, "%s%s%s", good_machine_head,
             "  <bed width=\"300\" height=\"200\"/>\n  <kerf>0.2</kerf>\n", good_machine_tail);
    /* The score operation is on line 11; make its colour a name. */
    replace(text, sizeof text, "#0000FF", "red");
    const char *path = write_profile("machines", "test-colour", text);
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "test-colour", &machine, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 11, "operation");
}

static void test_missing_bed(void **state)
{
    (void)state;
    const char *path = write_machine("test-no-bed", "  <kerf>0.2</kerf>\n"); /* line 5 */
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "test-no-bed", &machine, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 5, "kerf");
}

static void test_bad_kind_and_material_values(void **state)
{
    (void)state;
    char text[4096];
    snprintf(text, sizeof text, "%s%s%s", good_machine_head,
             "  <bed width=\"300\" height=\"200\"/>\n  <kerf>0.2</kerf>\n", good_machine_tail);
    replace(text, sizeof text, "<kind>laser", "<kind>lathe");
    const char *path = write_profile("machines", "test-kind", text);
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "test-kind", &machine, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 4, "kind");

    /* A strain written with an exponent is not a plain decimal (line 6). */
    path = write_profile("materials", "test-strain",
                         "<material>\n"
                         "  <description>Test</description>\n"
                         "  <thickness>1</thickness>\n"
                         "  <stock width=\"100\" height=\"100\"/>\n"
                         "  <bend-radius with-grain=\"5\" across-grain=\"5\"/>\n"
                         "  <strain stretch=\"1e-3\" compression=\"0.01\"/>\n"
                         "  <k-factor>0.5</k-factor>\n"
                         "  <tab depth=\"5\" angle=\"45\"/>\n"
                         "  <grain rule=\"along\"/>\n"
                         "  <living-hinge cut-length=\"5\" connection=\"1\" distance=\"1\"/>\n"
                         "</material>\n");
    ur_material material;
    assert_int_equal(ur_material_load(roots, "test-strain", &material, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 6, "strain");
}

static void test_material_rules(void **state)
{
    (void)state;
    /* Grain "along" needs a tolerance (line 9); a router kerf is optional. */
    const char *text = "<material>\n"
                       "  <description>Test\n    wrapped</description>\n" /* 2-3 */
                       "  <thickness>1.5</thickness>\n"
                       "  <stock width=\"100\" height=\"50\"/>\n"
                       "  <kerf router=\"3.3\"/>\n"
                       "  <bend-radius with-grain=\"5\" across-grain=\"7\"/>\n"
                       "  <strain stretch=\"0\" compression=\"0.01\"/>\n"
                       "  <k-factor>0.45</k-factor>\n"
                       "  <tab depth=\"5\" angle=\"60\"/>\n"
                       "  <grain rule=\"along\"/>\n" /* line 11 */
                       "  <living-hinge cut-length=\"5\" connection=\"1\" distance=\"1\"/>\n"
                       "</material>\n";
    const char *path = write_profile("materials", "test-grain", text);
    ur_material material;
    ur_error error = {0};
    assert_int_equal(ur_material_load(roots, "test-grain", &material, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 11, "grain");

    char fixed[2048];
    snprintf(fixed, sizeof fixed, "%s", text);
    replace(fixed, sizeof fixed, "rule=\"along\"", "rule=\"none\"");
    path = write_profile("materials", "test-grain-none", fixed);
    assert_int_equal(ur_material_load(roots, "test-grain-none", &material, &error), UR_OK);
    assert_string_equal(material.description, "Test wrapped");
    assert_true(material.kerf_laser == 0.0 && material.kerf_router == 3.3);
    assert_true(material.max_stretch == 0.0 && material.k_factor == 0.45);
    assert_true(material.tab_angle == 60.0);
    assert_int_equal(material.stock_count, 1);
    assert_int_equal(material.grain, UR_GRAIN_NONE);
    assert_string_equal(material.source, path);
}

/*
 * The allowance elements are optional: a profile without them (test-grain-none
 * above, written by test_material_rules) gets the documented defaults, the
 * shipped ones their figures, and a bad choice is refused with its line.
 */
static void test_allowance_fields(void **state)
{
    (void)state;
    ur_material material;
    ur_error error = {0};
    assert_int_equal(ur_material_load(roots, "test-grain-none", &material, &error), UR_OK);
    assert_int_equal(material.joint, UR_JOINT_TAB);
    assert_true(material.lap_width == material.tab_depth);
    assert_true(material.label_height == 4.0);
    assert_true(material.kerfing_opening == 0.5 && material.kerfing_margin == 3.0);
    assert_int_equal(material.overlap, UR_OVERLAP_SLIT);
    assert_true(material.groove_skin == 0.5); /* a third of 1.5 mm */
    assert_true(material.facet_angle == 5.0 && material.min_web == 0.0);
    assert_int_equal(material.surface_layer, UR_LAYER_NEUTRAL);

    load_material("plywood-3mm", &material);
    assert_int_equal(material.joint, UR_JOINT_LAP);
    assert_true(material.lap_width == 15.0 && material.groove_skin == 1.0);
    load_material("paper-0.3mm", &material);
    assert_int_equal(material.overlap, UR_OVERLAP_DART);

    const char *text = "<material>\n"
                       "  <description>Test</description>\n"
                       "  <thickness>3</thickness>\n"
                       "  <stock width=\"100\" height=\"50\"/>\n"
                       "  <bend-radius with-grain=\"5\" across-grain=\"7\"/>\n"
                       "  <strain stretch=\"0\" compression=\"0.01\"/>\n"
                       "  <k-factor>0.45</k-factor>\n"
                       "  <tab depth=\"5\" angle=\"60\"/>\n"
                       "  <grain rule=\"none\"/>\n"
                       "  <living-hinge cut-length=\"5\" connection=\"1\" distance=\"1\"/>\n"
                       "  <groove skin=\"3\"/>\n" /* line 11: no groove left */
                       "</material>\n";
    const char *path = write_profile("materials", "test-skin", text);
    assert_int_equal(ur_material_load(roots, "test-skin", &material, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 11, "skin");

    const char *bending = "<material>\n"
                          "  <description>Test</description>\n"
                          "  <thickness>3</thickness>\n"
                          "  <stock width=\"100\" height=\"50\"/>\n"
                          "  <bend-radius with-grain=\"5\" across-grain=\"7\"/>\n"
                          "  <strain stretch=\"0\" compression=\"0.01\"/>\n"
                          "  <k-factor>0.45</k-factor>\n"
                          "  <tab depth=\"5\" angle=\"60\"/>\n"
                          "  <grain rule=\"none\"/>\n"
                          "  <living-hinge cut-length=\"5\" connection=\"1\" distance=\"1\"/>\n"
                          "  <bending facet-angle=\"%s\" min-web=\"0.8\"/>\n" /* line 11 */
                          "</material>\n";
    char text_of[1024];
    snprintf(text_of, sizeof text_of, bending, "2.5");
    write_profile("materials", "test-bending", text_of);
    assert_int_equal(ur_material_load(roots, "test-bending", &material, &error), UR_OK);
    assert_true(material.facet_angle == 2.5 && material.min_web == 0.8);
    snprintf(text_of, sizeof text_of, bending, "120");
    path = write_profile("materials", "test-bending", text_of);
    assert_int_equal(ur_material_load(roots, "test-bending", &material, &error), UR_ERROR_INPUT);
    expect_located(error.message, path, 11, "facet angle");

    ur_machine machine;
    assert_int_equal(ur_machine_load(roots, "router", &machine, &error), UR_OK);
    assert_true(machine.bridge_width == 3.0 && machine.bridges_by_default);
    assert_int_equal(ur_machine_load(roots, "co2-60w", &machine, &error), UR_OK);
    assert_true(machine.bridge_width == 0.5 && !machine.bridges_by_default);
}

/* libxml2 must not print: stderr stays empty while a bad file is read. */
static void test_nothing_printed(void **state)
{
    (void)state;
    char capture[128];
    snprintf(capture, sizeof capture, "%s/stderr.txt", root);
    assert_true(written_count < MAX_WRITTEN);
    strcpy(written[written_count++], capture);
    fflush(stderr);
    int saved = dup(2);
    int fd = open(capture, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_true(saved >= 0 && fd >= 0);
    assert_true(dup2(fd, 2) == 2);
    close(fd);
    write_machine("test-quiet", "  <kerf>0.2</kref>\n");
    write_machine("test-quiet-invalid", "  <kerf>0.2</kerf>\n");
    ur_machine machine;
    ur_error error = {0};
    ur_status malformed = ur_machine_load(roots, "test-quiet", &machine, &error);
    ur_status invalid = ur_machine_load(roots, "test-quiet-invalid", &machine, &error);
    fflush(stderr);
    assert_true(dup2(saved, 2) == 2);
    close(saved);
    assert_int_equal(malformed, UR_ERROR_INPUT);
    assert_int_equal(invalid, UR_ERROR_INPUT);
    struct stat info;
    assert_int_equal(stat(capture, &info), 0);
    assert_int_equal(info.st_size, 0);
}

/* ---- Names and the search path ----------------------------------------- */

static void test_unknown_name(void **state)
{
    (void)state;
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "no-such-machine", &machine, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "unknown machine 'no-such-machine'"));
    assert_non_null(strstr(error.message, "./profiles"));
    char expected[128];
    snprintf(expected, sizeof expected, "(searched ./profiles, %s)", root);
    assert_non_null(strstr(error.message, expected));
    assert_non_null(strstr(error.message, "unroll profiles"));
    ur_material material;
    assert_int_equal(ur_material_load(roots, "co2-60w", &material, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "unknown material 'co2-60w'"));
}

static void test_bad_names(void **state)
{
    (void)state;
    static const char *const bad[] = {
        "../x",
        "..",
        ".hidden",
        "",
        "a/b",
        "a b",
        "co2-60w.xml/",
        "x\n",
        "a-name-that-is-far-too-long-to-fit-in-the-sixty-four-bytes-of-a-name"};
    char path[1024];
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ur_error error = {0};
        if (ur_profile_find(roots, UR_PROFILE_MACHINE, bad[i], path, sizeof path, &error) !=
            UR_ERROR_INPUT)
            fail_msg("name '%s' accepted", bad[i]);
        assert_non_null(strstr(error.message, "bad machine name"));
    }
    ur_error error = {0};
    assert_int_equal(
        ur_profile_find(roots, UR_PROFILE_MATERIAL, "paper-0.3mm", path, sizeof path, &error),
        UR_OK);
    assert_string_equal(path, "./profiles/materials/paper-0.3mm.xml");
}

static void test_first_root_wins(void **state)
{
    (void)state;
    /* A co2-60w in the second root is hidden by the one in ./profiles. */
    write_machine("co2-60w", "  <bed width=\"1\" height=\"1\"/>\n  <kerf>9</kerf>\n");
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(roots, "co2-60w", &machine, &error), UR_OK);
    assert_true(machine.bed_width == 600.0);
    assert_string_equal(machine.source, "./profiles/machines/co2-60w.xml");
}

/*
 * The library searches the roots it is given and nothing else: not
 * $UNROLL_PROFILES (the command's business), and with no roots, nothing.
 */
static void test_only_the_roots_given(void **state)
{
    (void)state;
    write_machine("test-only-given", "  <bed width=\"100\" height=\"50\"/>\n"
                                     "  <kerf>0.2</kerf>\n");
    assert_int_equal(setenv("UNROLL_PROFILES", root, 1), 0);
    static const char *const shipped_only[] = {"./profiles", NULL};
    ur_machine machine;
    ur_error error = {0};
    assert_int_equal(ur_machine_load(shipped_only, "test-only-given", &machine, &error),
                     UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "(searched ./profiles)"));
    assert_int_equal(ur_machine_load(roots, "test-only-given", &machine, &error), UR_OK);
    assert_true(machine.bed_width == 100.0 && machine.bed_height == 50.0);
    assert_int_equal(ur_machine_load(NULL, "co2-60w", &machine, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "no profile directory given"));
    assert_int_equal(unsetenv("UNROLL_PROFILES"), 0);
}

static void test_listing(void **state)
{
    (void)state;
    write_machine("test-list-bad", "  <kerf>0.2</kerf>\n");
    write_machine("co2-60w", "  <bed width=\"1\" height=\"1\"/>\n  <kerf>9</kerf>\n");
    ur_profile_entry *entries = NULL;
    size_t count = 0;
    ur_error error = {0};
    assert_int_equal(ur_profile_list(roots, &entries, &count, &error), UR_OK);
    static const char *const shipped_machines[] = {"co2-60w", "diode-10w", "router"};
    static const char *const shipped_materials[] = {"cardboard-2mm", "mdf-3mm",
                                                    "paper-0.3mm",   "plywood-3mm",
                                                    "plywood-6mm",   "polypropylene-0.8mm"};
    size_t machines = 0, materials = 0, shipped_found = 0;
    const ur_profile_entry *bad = NULL;
    for (size_t i = 0; i < count; i++) {
        const ur_profile_entry *entry = &entries[i];
        if (i > 0) { /* sorted by kind, then name */
            const ur_profile_entry *previous = &entries[i - 1];
            assert_true(previous->kind < entry->kind ||
                        (previous->kind == entry->kind && strcmp(previous->name, entry->name) < 0));
        }
        if (entry->kind == UR_PROFILE_MACHINE) {
            machines++;
            for (size_t j = 0; j < 3; j++)
                if (strcmp(entry->name, shipped_machines[j]) == 0) {
                    shipped_found++;
                    assert_int_equal(strncmp(entry->source, "./profiles/machines/", 20), 0);
                    assert_null(strstr(entry->description, "invalid"));
                }
        } else {
            materials++;
            for (size_t j = 0; j < 6; j++)
                if (strcmp(entry->name, shipped_materials[j]) == 0) {
                    shipped_found++;
                    assert_int_equal(strncmp(entry->source, "./profiles/materials/", 21), 0);
                    assert_null(strstr(entry->description, "invalid"));
                }
        }
        if (strcmp(entry->name, "test-list-bad") == 0)
            bad = entry;
    }
    assert_int_equal(shipped_found, 9);
    assert_true(machines >= 4 && materials >= 6);
    assert_non_null(bad);
    assert_int_equal(strncmp(bad->description, "(invalid: ", 10), 0);
    assert_non_null(strstr(bad->description, ":5: "));
    assert_string_equal(entries[0].name, "co2-60w");
    free(entries);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_co2_laser),
        cmocka_unit_test(test_diode_laser),
        cmocka_unit_test(test_router),
        cmocka_unit_test(test_plywood),
        cmocka_unit_test(test_mdf),
        cmocka_unit_test(test_cardboard_paper_polypropylene),
        cmocka_unit_test(test_effective_kerf),
        cmocka_unit_test(test_own_profile_from_a_root),
        cmocka_unit_test(test_malformed_xml),
        cmocka_unit_test(test_negative_kerf),
        cmocka_unit_test(test_colour_name_refused),
        cmocka_unit_test(test_missing_bed),
        cmocka_unit_test(test_bad_kind_and_material_values),
        cmocka_unit_test(test_material_rules),
        cmocka_unit_test(test_allowance_fields),
        cmocka_unit_test(test_nothing_printed),
        cmocka_unit_test(test_unknown_name),
        cmocka_unit_test(test_bad_names),
        cmocka_unit_test(test_first_root_wins),
        cmocka_unit_test(test_only_the_roots_given),
        cmocka_unit_test(test_listing),
    };
    return cmocka_run_group_tests(tests, make_root, remove_root);
}
