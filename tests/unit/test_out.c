/*
 * test_out.c: the cut-file writers and the report, checked with real readers.
 *
 * A layout is built by hand (a 100 x 50 panel with a fold line, turned a
 * quarter turn; a triangle with an engraved mark, turned half a turn), the
 * machine's styles are filled in here, and the files written to a fresh
 * directory under /tmp are read back with libxml2, xmllint, rsvg-convert and
 * jansson.  Every expected coordinate below was worked out by hand from the
 * placements, not by calling the code under test.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <fcntl.h>
#include <jansson.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unroll/out.h"

#include "test_support.h"

#define SVG_NAMESPACE "http://www.w3.org/2000/svg"
#define INKSCAPE_NAMESPACE "http://www.inkscape.org/namespaces/inkscape"
#define PI 3.14159265358979323846

enum { PIECES = 3 };

typedef struct fixture {
    char dir[64];
    ur_piece pieces[PIECES];
    ur_placement placements[3];
    ur_sheet sheets[2];
    ur_layout layout;
    ur_machine machine;
    ur_output_options options;
} fixture;

/* ---- building the layout ----------------------------------------------- */

static void add_path(ur_piece *piece, ur_op op, const ur_vec2 *points, size_t count, bool closed)
{
    ur_error error;
    assert_int_equal(ur_piece_add_path(piece, op, points, count, closed, &error), UR_OK);
}

static void make_pieces(ur_piece pieces[PIECES])
{
    memset(pieces, 0, PIECES * sizeof *pieces);
    const ur_vec2 panel[] = {{0, 0}, {100, 0}, {100, 50}, {0, 50}};
    const ur_vec2 fold[] = {{50, 0}, {50, 50}};
    snprintf(pieces[0].name, sizeof pieces[0].name, "panel");
    add_path(&pieces[0], UR_OP_CUT, panel, 4, true);
    add_path(&pieces[0], UR_OP_SCORE, fold, 2, false);
    pieces[0].measures = (ur_piece_measures){.area_3d = 5100.0,
                                             .flat_area = 5000.0,
                                             .edge_error = 0.002,
                                             .triangle_count = 24,
                                             .polygon_count = 10};

    const ur_vec2 triangle[] = {{0, 0}, {40, 0}, {0, 30}};
    const ur_vec2 mark[] = {{5, 5}, {15, 5}};
    snprintf(pieces[1].name, sizeof pieces[1].name, "tab");
    add_path(&pieces[1], UR_OP_CUT, triangle, 3, true);
    add_path(&pieces[1], UR_OP_ENGRAVE, mark, 2, false);
    pieces[1].measures = (ur_piece_measures){.area_3d = 600.0, .flat_area = 600.0};

    const ur_vec2 square[] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    snprintf(pieces[2].name, sizeof pieces[2].name, "spare");
    add_path(&pieces[2], UR_OP_CUT, square, 4, true);
    pieces[2].measures = (ur_piece_measures){.area_3d = 0.0, .flat_area = 100.0};
}

static void set_style(ur_machine *machine, ur_op op, const char *layer, const char *colour,
                      double width)
{
    snprintf(machine->styles[op].layer, sizeof machine->styles[op].layer, "%s", layer);
    snprintf(machine->styles[op].colour, sizeof machine->styles[op].colour, "%s", colour);
    machine->styles[op].line_width = width;
}

static void make_machine(ur_machine *machine)
{
    memset(machine, 0, sizeof *machine);
    snprintf(machine->name, sizeof machine->name, "test-laser");
    set_style(machine, UR_OP_CUT, "Cut", "#FF0000", 0.025);
    set_style(machine, UR_OP_SCORE, "Score", "#0000FF", 0.025);
    set_style(machine, UR_OP_SCORE_VALLEY, "Score valley", "#00E0E0", 0.025);
    set_style(machine, UR_OP_KERF, "Kerf", "#00E000", 0.025);
    set_style(machine, UR_OP_ENGRAVE, "Engrave", "#000000", 0.1);
    set_style(machine, UR_OP_MARK, "Mark", "#FF00FF", 0.05);
}

/*
 * Sheet 1 (600 x 400): the panel a quarter turn about its origin, then moved
 * to (150, 20); the triangle half a turn, then moved to (300, 100).  Sheet 2
 * (300 x 200): the spare square moved to (10, 10); used by multi-sheet tests.
 */
static void make_layout(fixture *f)
{
    f->placements[0] = (ur_placement){0, ur_transform2_make(PI / 2, ur_vec2_make(150, 20))};
    f->placements[1] = (ur_placement){1, ur_transform2_make(PI, ur_vec2_make(300, 100))};
    f->placements[2] = (ur_placement){2, ur_transform2_make(0, ur_vec2_make(10, 10))};
    f->sheets[0] = (ur_sheet){
        .width = 600, .height = 400, .placements = &f->placements[0], .placement_count = 2};
    f->sheets[1] = (ur_sheet){
        .width = 300, .height = 200, .placements = &f->placements[2], .placement_count = 1};
    f->layout = (ur_layout){f->sheets, 1, NULL, 0};
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/unroll-test-out-XXXXXX");
    if (!mkdtemp(f->dir)) {
        free(f);
        return -1;
    }
    make_pieces(f->pieces);
    make_machine(&f->machine);
    make_layout(f);
    f->options.title = "unroll test & <layout>";
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    remove_test_directory(f->dir);
    for (int i = 0; i < PIECES; i++)
        ur_piece_free(&f->pieces[i]);
    free(f);
    return 0;
}

/* ---- small checks ------------------------------------------------------- */

static void assert_near(double actual, double expected)
{
    if (!(fabs(actual - expected) <= 1e-12 * fmax(1.0, fabs(expected)))) {
        print_error("%.17g is not %.17g\n", actual, expected);
        fail();
    }
}

static void write_text(const char *path, const char *text)
{
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_true(fputs(text, file) >= 0);
    assert_int_equal(fclose(file), 0);
}

static void assert_file_text(const char *path, const char *expected)
{
    char text[256] = "";
    FILE *file = fopen(path, "r");
    assert_non_null(file);
    size_t length = fread(text, 1, sizeof text - 1, file);
    text[length] = '\0';
    assert_int_equal(fclose(file), 0);
    assert_string_equal(text, expected);
}

static bool have_tool(const char *name)
{
    char command[128];
    snprintf(command, sizeof command, "command -v %s >/dev/null 2>&1", name);
    return system(command) == 0;
}

/* Attribute name (in namespace if non-NULL) of node equals expected. */
static void assert_attribute(xmlNode *node, const char *namespace, const char *name,
                             const char *expected)
{
    xmlChar *value = namespace ? xmlGetNsProp(node, BAD_CAST name, BAD_CAST namespace)
                               : xmlGetProp(node, BAD_CAST name);
    if (!value) {
        print_error("<%s> has no attribute %s\n", (const char *)node->name, name);
        fail();
    }
    int same = strcmp((const char *)value, expected) == 0;
    if (!same)
        print_error("%s=\"%s\", expected \"%s\"\n", name, (const char *)value, expected);
    xmlFree(value);
    assert_true(same);
}

/* The next element sibling named name, starting at node. */
static xmlNode *element(xmlNode *node, const char *name)
{
    for (; node; node = node->next)
        if (node->type == XML_ELEMENT_NODE && strcmp((const char *)node->name, name) == 0)
            return node;
    return NULL;
}

static void assert_text(xmlNode *node, const char *expected)
{
    xmlChar *text = xmlNodeGetContent(node);
    assert_non_null(text);
    int same = strcmp((const char *)text, expected) == 0;
    if (!same)
        print_error("<%s> says \"%s\"\n", (const char *)node->name, (const char *)text);
    xmlFree(text);
    assert_true(same);
}

/* ---- file names --------------------------------------------------------- */

static void assert_sheet_name(const char *output, size_t index, size_t count, const char *expected)
{
    char name[64];
    ur_error error;
    assert_int_equal(ur_sheet_file_name(output, index, count, name, sizeof name, &error), UR_OK);
    assert_string_equal(name, expected);
}

static void test_sheet_file_name(void **state)
{
    (void)state;
    assert_sheet_name("net.svg", 0, 1, "net.svg");
    assert_sheet_name("net.svg", 0, 2, "net-1.svg");
    assert_sheet_name("net.svg", 1, 2, "net-2.svg");
    assert_sheet_name("dir.v2/net.svg", 0, 3, "dir.v2/net-1.svg");
    assert_sheet_name("dir.v2/net", 1, 2, "dir.v2/net-2");
    assert_sheet_name("net", 0, 2, "net-1");
    assert_sheet_name("net.tar.svg", 9, 10, "net.tar-10.svg");
    assert_sheet_name("out/.hidden", 0, 2, "out/.hidden-1");
    assert_sheet_name("/abs/a.b/c.dxf", 1, 2, "/abs/a.b/c-2.dxf");

    char name[8];
    ur_error error;
    assert_int_equal(ur_sheet_file_name("longname.svg", 0, 2, name, sizeof name, &error),
                     UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "too long"));
    assert_int_equal(ur_sheet_file_name("a.svg", 2, 2, name, sizeof name, &error),
                     UR_ERROR_INTERNAL);
}

/* ---- SVG ---------------------------------------------------------------- */

static void write_svg(fixture *f, const char *name, ur_status expected, ur_error *error)
{
    char path[256];
    path_in(f->dir, name, path, sizeof path);
    ur_status status = ur_write_svg(path, &f->layout, f->pieces, &f->machine, &f->options, error);
    if (status != expected)
        print_error("status %d: %s\n", status, error->message);
    assert_int_equal(status, expected);
}

typedef struct layer_expectation {
    const char *id, *label, *stroke, *width;
    const char *paths[3]; /* d of each path in order, NULL-terminated */
} layer_expectation;

/* Cutting order, and every layer present even when empty. */
static const layer_expectation sheet_one_layers[] = {
    {"engrave", "Engrave", "#000000", "0.1", {"M 295 305 L 285 305", NULL}},
    {"mark", "Mark", "#FF00FF", "0.05", {NULL}},
    {"score", "Score", "#0000FF", "0.025", {"M 150 330 L 100 330", NULL}},
    {"score-valley", "Score valley", "#00E0E0", "0.025", {NULL}},
    {"kerf", "Kerf", "#00E000", "0.025", {NULL}},
    {"cut",
     "Cut",
     "#FF0000",
     "0.025",
     {"M 150 380 L 150 280 L 100 280 L 100 380 Z", "M 300 300 L 260 300 L 300 330 Z", NULL}},
};

static void assert_layer(xmlNode *group, const layer_expectation *expected)
{
    assert_attribute(group, NULL, "id", expected->id);
    assert_attribute(group, INKSCAPE_NAMESPACE, "groupmode", "layer");
    assert_attribute(group, INKSCAPE_NAMESPACE, "label", expected->label);
    assert_attribute(group, NULL, "stroke", expected->stroke);
    assert_attribute(group, NULL, "stroke-width", expected->width);
    assert_attribute(group, NULL, "fill", "none");
    xmlNode *path = element(group->children, "path");
    for (size_t i = 0; expected->paths[i]; i++) {
        assert_non_null(path);
        assert_attribute(path, NULL, "d", expected->paths[i]);
        path = element(path->next, "path");
    }
    assert_null(path);
}

static void test_svg_one_sheet(void **state)
{
    fixture *f = *state;
    ur_error error;
    write_svg(f, "net.svg", UR_OK, &error);
    assert_int_equal(entries_in(f->dir), 1); /* no temporary left */

    char path[256];
    path_in(f->dir, "net.svg", path, sizeof path);
    xmlDoc *doc = xmlReadFile(path, NULL, XML_PARSE_NONET);
    assert_non_null(doc);
    xmlNode *svg = xmlDocGetRootElement(doc);
    assert_string_equal((const char *)svg->name, "svg");
    assert_non_null(svg->ns);
    assert_string_equal((const char *)svg->ns->href, SVG_NAMESPACE);
    assert_attribute(svg, NULL, "width", "600mm");
    assert_attribute(svg, NULL, "height", "400mm");
    assert_attribute(svg, NULL, "viewBox", "0 0 600 400");
    assert_text(element(svg->children, "title"), "unroll test & <layout>");
    assert_text(element(svg->children, "desc"),
                "made by unroll " UR_VERSION "; 1 user unit = 1 mm");

    xmlNode *group = element(svg->children, "g");
    for (size_t i = 0; i < sizeof sheet_one_layers / sizeof *sheet_one_layers; i++) {
        assert_non_null(group);
        assert_layer(group, &sheet_one_layers[i]);
        group = element(group->next, "g");
    }
    assert_null(group);
    xmlFreeDoc(doc);
}

static void test_svg_readers_accept_it(void **state)
{
    fixture *f = *state;
    if (!have_tool("xmllint") || !have_tool("rsvg-convert"))
        skip();
    ur_error error;
    write_svg(f, "net.svg", UR_OK, &error);
    char command[1024];
    snprintf(command, sizeof command, "xmllint --noout '%s/net.svg'", f->dir);
    assert_int_equal(system(command), 0);
    /* rsvg-convert refuses /dev/null as output: render to a file next to it. */
    snprintf(command, sizeof command, "rsvg-convert -o '%s/preview.png' '%s/net.svg'", f->dir,
             f->dir);
    assert_int_equal(system(command), 0);
}

static void test_svg_file_mode_follows_umask(void **state)
{
    fixture *f = *state;
    mode_t old = umask(027);
    ur_error error;
    char path[256];
    path_in(f->dir, "net.svg", path, sizeof path);
    ur_status status = ur_write_svg(path, &f->layout, f->pieces, &f->machine, NULL, &error);
    umask(old);
    assert_int_equal(status, UR_OK);
    struct stat info;
    assert_int_equal(stat(path, &info), 0);
    assert_int_equal(info.st_mode & 0777, 0640);
}

static void test_svg_several_sheets(void **state)
{
    fixture *f = *state;
    f->layout.sheet_count = 2;
    ur_error error;
    write_svg(f, "net.svg", UR_OK, &error);
    char path[256];
    path_in(f->dir, "net.svg", path, sizeof path);
    assert_false(exists(path));
    path_in(f->dir, "net-1.svg", path, sizeof path);
    assert_true(exists(path));
    path_in(f->dir, "net-2.svg", path, sizeof path);
    xmlDoc *doc = xmlReadFile(path, NULL, XML_PARSE_NONET);
    assert_non_null(doc);
    xmlNode *svg = xmlDocGetRootElement(doc);
    assert_attribute(svg, NULL, "width", "300mm");
    assert_attribute(svg, NULL, "viewBox", "0 0 300 200");
    /* The square at (10, 10)..(20, 20), y flipped against 200. */
    xmlNode *cut = element(svg->children, "g");
    for (int i = 0; cut && i < 5; i++) /* engrave, mark, score, score-valley, kerf first */
        cut = element(cut->next, "g");
    assert_non_null(cut);
    assert_attribute(cut, NULL, "id", "cut");
    assert_attribute(element(cut->children, "path"), NULL, "d",
                     "M 10 190 L 20 190 L 20 180 L 10 180 Z");
    xmlFreeDoc(doc);
    assert_int_equal(entries_in(f->dir), 2);
}

static void test_svg_missing_directory(void **state)
{
    fixture *f = *state;
    ur_error error;
    write_svg(f, "missing/x.svg", UR_ERROR_IO, &error);
    char expected[512];
    snprintf(expected, sizeof expected,
             "cannot write '%s/missing/x.svg': directory '%s/missing' does not exist", f->dir,
             f->dir);
    assert_string_equal(error.message, expected);
    assert_int_equal(entries_in(f->dir), 0);
}

/* A failure on the second sheet, after the first is complete in its temporary. */
static void assert_second_sheet_failure(fixture *f, ur_status expected, const char *words)
{
    char one[256], two[256];
    path_in(f->dir, "net-1.svg", one, sizeof one);
    path_in(f->dir, "net-2.svg", two, sizeof two);
    write_text(one, "old sheet\n");
    f->layout.sheet_count = 2;
    ur_error error;
    write_svg(f, "net.svg", expected, &error);
    assert_non_null(strstr(error.message, words));
    assert_file_text(one, "old sheet\n"); /* untouched */
    assert_false(exists(two));
    assert_int_equal(entries_in(f->dir), 1); /* and no temporaries */
}

static void test_svg_failure_leaves_nothing(void **state)
{
    fixture *f = *state;
    f->placements[2].transform.translation.x = NAN;
    assert_second_sheet_failure(f, UR_ERROR_INTERNAL, "'spare'");
}

static void test_svg_bad_sheet_size(void **state)
{
    fixture *f = *state;
    f->sheets[1].width = 0;
    assert_second_sheet_failure(f, UR_ERROR_INPUT, "sheet 2");
}

static void test_svg_bad_style(void **state)
{
    fixture *f = *state;
    set_style(&f->machine, UR_OP_KERF, "Kerf", "green", 0.025);
    ur_error error;
    write_svg(f, "net.svg", UR_ERROR_INPUT, &error);
    assert_non_null(strstr(error.message, "kerf"));
    assert_int_equal(entries_in(f->dir), 0);
}

/* ---- report ------------------------------------------------------------- */

/* What the real ur_sheet_utilisation gives: outline areas over sheet area. */
static double expected_utilisation(const fixture *f, size_t sheet_index)
{
    const ur_sheet *sheet = &f->sheets[sheet_index];
    double area = 0;
    for (size_t i = 0; i < sheet->placement_count; i++) {
        const ur_path *outline = &f->pieces[sheet->placements[i].piece_index].paths[0];
        area += fabs(ur_polygon_signed_area(outline->points, outline->count));
    }
    return area / (sheet->width * sheet->height);
}

static ur_report_context make_context(const fixture *f, const char *const *outputs,
                                      const char *sheet_path, const ur_material *material)
{
    ur_report_context context = {
        .surface = "cylinder",
        .method = "exact",
        .machine = &f->machine,
        .material = material,
        .surface_area = 5700.0,
        .outputs = outputs,
        .sheet_path = sheet_path,
    };
    return context;
}

static double real_at(json_t *object, const char *key)
{
    json_t *value = json_object_get(object, key);
    assert_true(json_is_real(value));
    return json_real_value(value);
}

static const char *string_at(json_t *object, const char *key)
{
    json_t *value = json_object_get(object, key);
    assert_true(json_is_string(value));
    return json_string_value(value);
}

static void assert_report_pieces(json_t *pieces)
{
    assert_int_equal(json_array_size(pieces), 3);
    json_t *panel = json_array_get(pieces, 0);
    assert_string_equal(string_at(panel, "name"), "panel");
    assert_near(real_at(panel, "area_3d_mm2"), 5100.0);
    assert_near(real_at(panel, "flat_area_mm2"), 5000.0);
    assert_near(real_at(panel, "coverage"), 5000.0 / 5100.0);
    assert_near(real_at(panel, "edge_length_error"), 0.002);
    json_t *box = json_object_get(panel, "bounding_box");
    assert_near(real_at(box, "width_mm"), 100.0);
    assert_near(real_at(box, "height_mm"), 50.0);
    assert_int_equal(json_integer_value(json_object_get(panel, "sheet")), 1);
    assert_int_equal(json_integer_value(json_object_get(panel, "triangles")), 24);
    assert_int_equal(json_integer_value(json_object_get(panel, "faces")), 10);
    json_t *spare = json_array_get(pieces, 2);
    assert_true(json_is_null(json_object_get(spare, "triangles"))); /* not a mesh's piece */
    assert_true(json_is_null(json_object_get(spare, "faces")));
    assert_true(json_is_null(json_object_get(spare, "coverage"))); /* no 3D area */
    assert_true(json_is_null(json_object_get(spare, "sheet")));    /* not placed */
}

static void assert_report(const fixture *f, json_t *root)
{
    assert_string_equal(string_at(root, "unroll"), UR_VERSION);
    assert_string_equal(string_at(root, "surface"), "cylinder");
    assert_string_equal(string_at(root, "method"), "exact");
    assert_string_equal(string_at(root, "machine"), "test-laser");
    assert_near(real_at(root, "surface_area_mm2"), 5700.0);
    assert_report_pieces(json_object_get(root, "pieces"));
    json_t *sheets = json_object_get(root, "sheets");
    assert_int_equal(json_array_size(sheets), 1);
    json_t *sheet = json_array_get(sheets, 0);
    assert_int_equal(json_integer_value(json_object_get(sheet, "index")), 1);
    assert_near(real_at(sheet, "width_mm"), 600.0);
    assert_near(real_at(sheet, "height_mm"), 400.0);
    assert_int_equal(json_integer_value(json_object_get(sheet, "pieces")), 2);
    assert_near(real_at(sheet, "utilisation"), expected_utilisation(f, 0));
    assert_near(expected_utilisation(f, 0), 5600.0 / 240000.0); /* the by-hand figure */
}

static void test_report_file(void **state)
{
    fixture *f = *state;
    ur_material material;
    memset(&material, 0, sizeof material);
    snprintf(material.name, sizeof material.name, "plywood-3mm");
    const char *const outputs[] = {"out/net.svg", "out/report.json", NULL};
    ur_report_context context = make_context(f, outputs, "out/net.svg", &material);
    char path[256];
    path_in(f->dir, "report.json", path, sizeof path);
    ur_error error;
    assert_int_equal(ur_report_write(path, &context, f->pieces, PIECES, &f->layout, NULL, &error),
                     UR_OK);
    assert_int_equal(entries_in(f->dir), 1);

    json_error_t json_error;
    json_t *root = json_load_file(path, 0, &json_error);
    if (!root)
        print_error("%s:%d: %s\n", path, json_error.line, json_error.text);
    assert_non_null(root);
    assert_report(f, root);
    assert_string_equal(string_at(root, "material"), "plywood-3mm");
    json_t *sheet = json_array_get(json_object_get(root, "sheets"), 0);
    assert_string_equal(string_at(sheet, "file"), "out/net.svg");
    json_t *written = json_object_get(root, "outputs");
    assert_int_equal(json_array_size(written), 2);
    assert_string_equal(json_string_value(json_array_get(written, 1)), "out/report.json");
    json_decref(root);
}

static void test_report_several_sheets(void **state)
{
    fixture *f = *state;
    f->layout.sheet_count = 2;
    ur_report_context context = make_context(f, NULL, "net.svg", NULL);
    char path[256];
    path_in(f->dir, "report.json", path, sizeof path);
    ur_error error;
    assert_int_equal(ur_report_write(path, &context, f->pieces, PIECES, &f->layout, NULL, &error),
                     UR_OK);
    json_error_t json_error;
    json_t *root = json_load_file(path, 0, &json_error);
    assert_non_null(root);
    assert_true(json_is_null(json_object_get(root, "material")));
    assert_int_equal(json_array_size(json_object_get(root, "outputs")), 0);
    json_t *sheets = json_object_get(root, "sheets");
    assert_string_equal(string_at(json_array_get(sheets, 0), "file"), "net-1.svg");
    assert_string_equal(string_at(json_array_get(sheets, 1), "file"), "net-2.svg");
    assert_near(real_at(json_array_get(sheets, 1), "utilisation"), expected_utilisation(f, 1));
    json_t *spare = json_array_get(json_object_get(root, "pieces"), 2);
    assert_int_equal(json_integer_value(json_object_get(spare, "sheet")), 2);
    json_decref(root);
}

/* "-" goes to standard output: catch it in a file for the length of the call. */
static void test_report_stdout(void **state)
{
    fixture *f = *state;
    ur_report_context context = make_context(f, NULL, NULL, NULL);
    char path[256];
    path_in(f->dir, "stdout.json", path, sizeof path);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_true(fd >= 0);
    assert_int_equal(fflush(stdout), 0);
    int saved = dup(STDOUT_FILENO);
    assert_true(saved >= 0);
    assert_true(dup2(fd, STDOUT_FILENO) >= 0);
    ur_error error;
    ur_status status = ur_report_write("-", &context, f->pieces, PIECES, &f->layout, NULL, &error);
    fflush(stdout);
    assert_true(dup2(saved, STDOUT_FILENO) >= 0);
    close(saved);
    close(fd);
    assert_int_equal(status, UR_OK);

    json_error_t json_error;
    json_t *root = json_load_file(path, 0, &json_error);
    assert_non_null(root);
    assert_report(f, root);
    assert_null(json_object_get(json_array_get(json_object_get(root, "sheets"), 0), "file"));
    json_decref(root);
}

static void test_report_missing_directory(void **state)
{
    fixture *f = *state;
    ur_report_context context = make_context(f, NULL, NULL, NULL);
    char path[256];
    path_in(f->dir, "missing/report.json", path, sizeof path);
    ur_error error;
    assert_int_equal(ur_report_write(path, &context, f->pieces, PIECES, &f->layout, NULL, &error),
                     UR_ERROR_IO);
    assert_non_null(strstr(error.message, "does not exist"));
    assert_int_equal(entries_in(f->dir), 0);
}

static void test_report_bad_placement(void **state)
{
    fixture *f = *state;
    ur_report_context context = make_context(f, NULL, NULL, NULL);
    char path[256];
    path_in(f->dir, "report.json", path, sizeof path);
    ur_error error;
    /* Only two pieces, but sheet 1 places pieces 0 and 1 and sheet 2 piece 2. */
    f->layout.sheet_count = 2;
    assert_int_equal(ur_report_write(path, &context, f->pieces, 2, &f->layout, NULL, &error),
                     UR_ERROR_INTERNAL);
    assert_int_equal(entries_in(f->dir), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sheet_file_name),
        cmocka_unit_test_setup_teardown(test_svg_one_sheet, setup, teardown),
        cmocka_unit_test_setup_teardown(test_svg_readers_accept_it, setup, teardown),
        cmocka_unit_test_setup_teardown(test_svg_file_mode_follows_umask, setup, teardown),
        cmocka_unit_test_setup_teardown(test_svg_several_sheets, setup, teardown),
        cmocka_unit_test_setup_teardown(test_svg_missing_directory, setup, teardown),
        cmocka_unit_test_setup_teardown(test_svg_failure_leaves_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_svg_bad_sheet_size, setup, teardown),
        cmocka_unit_test_setup_teardown(test_svg_bad_style, setup, teardown),
        cmocka_unit_test_setup_teardown(test_report_file, setup, teardown),
        cmocka_unit_test_setup_teardown(test_report_several_sheets, setup, teardown),
        cmocka_unit_test_setup_teardown(test_report_stdout, setup, teardown),
        cmocka_unit_test_setup_teardown(test_report_missing_directory, setup, teardown),
        cmocka_unit_test_setup_teardown(test_report_bad_placement, setup, teardown),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    xmlCleanupParser();
    return failed;
}
