/*
 * test_locale.c: files are written and read the same under a comma-decimal
 * locale (de_DE.UTF-8, which scripts/install-deps generates) as under "C",
 * as when a host program has called setlocale(LC_ALL, "").
 *
 * Each test does the same work twice, once in each locale, and compares:
 * the bytes of the SVG, DXF, JSON report and CSV written, and the numbers
 * read back from a profile, an SVG, a DXF, a CSV curve and an OBJ mesh.
 */
#include "test_support.h"

#include <locale.h>

#include "unroll/out.h"

/* The profiles of the source tree: the tests run from its root. */
static const char *const profile_roots[] = {"./profiles", NULL};

#define COMMA_LOCALE "de_DE.UTF-8"

typedef struct fixture {
    char dir[64];
    ur_piece piece;
    ur_machine machine;
    ur_placement placement;
    ur_sheet sheet;
    ur_layout layout;
} fixture;

/*
 * Switches the process to the comma-decimal locale; skips the test when
 * the machine does not have it, and fails when it has it but it does not
 * write a comma (then the test would prove nothing).
 */
static void enter_comma_locale(void)
{
    if (!setlocale(LC_ALL, COMMA_LOCALE)) {
        print_message("the locale " COMMA_LOCALE " is not installed (scripts/install-deps "
                      "generates it): skipped\n");
        skip();
    }
    char text[16];
    snprintf(text, sizeof text, "%.1f", 1.5);
    assert_string_equal(text, "1,5");
}

static void leave_comma_locale(void)
{
    assert_non_null(setlocale(LC_ALL, "C"));
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/unroll-test-locale-XXXXXX");
    if (!mkdtemp(f->dir)) {
        free(f);
        return -1;
    }
    /* Coordinates with many decimals: a comma would show in every one. */
    const ur_vec2 outline[] = {{0, 0}, {100.25, 0}, {100.25, 50.125}, {0.5, 50.375}};
    const ur_vec2 hole[] = {{70.1, 20.2}, {80.3, 20.4}, {80.5, 30.123456789}, {70.7, 30.9}};
    const ur_vec2 fold[] = {{50.5, 0}, {50.5, 50.25}};
    ur_error error;
    snprintf(f->piece.name, sizeof f->piece.name, "panel");
    if (ur_piece_add_path(&f->piece, UR_OP_CUT, outline, 4, true, &error) != UR_OK ||
        ur_piece_add_path(&f->piece, UR_OP_CUT, hole, 4, true, &error) != UR_OK ||
        ur_piece_add_path(&f->piece, UR_OP_SCORE, fold, 2, false, &error) != UR_OK ||
        /* a record whose reason holds a number, for the report */
        ur_piece_compensate_kerf(&f->piece, 0.15, &error) != UR_OK)
        return -1;
    f->machine.kind = UR_MACHINE_LASER;
    snprintf(f->machine.name, sizeof f->machine.name, "test-laser");
    f->machine.cut_speed = 12.5;
    f->machine.travel_speed = 150.5;
    for (int op = 0; op < UR_OP_COUNT; op++) {
        ur_op_style *style = &f->machine.styles[op];
        snprintf(style->layer, sizeof style->layer, "%s", ur_op_name((ur_op)op));
        snprintf(style->colour, sizeof style->colour, "#FF0000");
        style->line_width = 0.025;
    }
    snprintf(f->machine.styles[UR_OP_SCORE].dash, sizeof f->machine.styles[UR_OP_SCORE].dash,
             "3 1.5");
    f->placement = (ur_placement){0, ur_transform2_make(0.3, ur_vec2_make(150.5, 20.25))};
    f->sheet = (ur_sheet){
        .width = 600.5, .height = 400.25, .placements = &f->placement, .placement_count = 1};
    f->layout = (ur_layout){&f->sheet, 1, NULL, 0};
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    setlocale(LC_ALL, "C");
    remove_test_directory(f->dir);
    ur_piece_free(&f->piece);
    free(f);
    return 0;
}

static char *read_all(const char *path, size_t *size)
{
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    assert_int_equal(fseek(file, 0, SEEK_END), 0);
    long length = ftell(file);
    assert_true(length > 0);
    rewind(file);
    char *text = malloc((size_t)length + 1);
    assert_non_null(text);
    assert_int_equal(fread(text, 1, (size_t)length, file), (size_t)length);
    text[length] = '\0';
    fclose(file);
    *size = (size_t)length;
    return text;
}

static void assert_same_bytes(const char *a, const char *b)
{
    size_t size_a, size_b;
    char *text_a = read_all(a, &size_a), *text_b = read_all(b, &size_b);
    if (size_a != size_b || memcmp(text_a, text_b, size_a) != 0)
        fail_msg("%s and %s differ", a, b);
    free(text_a);
    free(text_b);
}

/* Writes TAG.svg, TAG.dxf, TAG.json and TAG.csv into the test directory. */
static void write_files(fixture *f, const char *tag)
{
    char path[256], name[64];
    ur_error error;
    ur_output_options options = {"unroll locale test", NULL};
    ur_format_options formats = {.job_name = "locale-job", .dxf_version = UR_DXF_R2000};
    snprintf(name, sizeof name, "%s.svg", tag);
    path_in(f->dir, name, path, sizeof path);
    assert_int_equal(ur_write_svg(path, &f->layout, &f->piece, &f->machine, &options, &error),
                     UR_OK);
    snprintf(name, sizeof name, "%s.dxf", tag);
    path_in(f->dir, name, path, sizeof path);
    assert_int_equal(
        ur_write_dxf(path, &f->layout, &f->piece, &f->machine, &options, &formats, &error), UR_OK);
    snprintf(name, sizeof name, "%s.json", tag);
    path_in(f->dir, name, path, sizeof path);
    ur_report_context context = {
        .surface = "test", .method = "exact", .machine = &f->machine, .surface_area = 4321.125};
    assert_int_equal(ur_report_write(path, &context, &f->piece, 1, &f->layout, NULL, &error),
                     UR_OK);
    snprintf(name, sizeof name, "%s.csv", tag);
    path_in(f->dir, name, path, sizeof path);
    const ur_vec3 curve[] = {
        {0.5, 1.25, 2.125}, {10.5, 0.1, -3.75}, {20.25, 5.5, 1e-7}, {30, 1, 0}};
    assert_int_equal(ur_curve_csv_write(path, curve, 4, NULL, &error), UR_OK);
}

static void test_writers_ignore_the_locale(void **state)
{
    fixture *f = *state;
    write_files(f, "c");
    enter_comma_locale();
    write_files(f, "comma");
    leave_comma_locale();
    const char *extensions[] = {"svg", "dxf", "json", "csv"};
    for (size_t i = 0; i < 4; i++) {
        char name[32], c_path[256], comma_path[256];
        snprintf(name, sizeof name, "c.%s", extensions[i]);
        path_in(f->dir, name, c_path, sizeof c_path);
        snprintf(name, sizeof name, "comma.%s", extensions[i]);
        path_in(f->dir, name, comma_path, sizeof comma_path);
        assert_same_bytes(c_path, comma_path);
    }
    /* The report says the kerf's reason with its number as written in C. */
    char path[256];
    size_t size;
    path_in(f->dir, "comma.json", path, sizeof path);
    char *report = read_all(path, &size);
    assert_non_null(strstr(report, "0.075 mm"));
    assert_non_null(strstr(report, "4321.125"));
    free(report);
}

/* ---- readers ------------------------------------------------------------- */

static void assert_same_parts(const ur_parts *a, const ur_parts *b)
{
    assert_int_equal(a->count, b->count);
    for (size_t i = 0; i < a->count; i++) {
        assert_int_equal(a->pieces[i].path_count, b->pieces[i].path_count);
        for (size_t p = 0; p < a->pieces[i].path_count; p++) {
            const ur_path *path_a = &a->pieces[i].paths[p], *path_b = &b->pieces[i].paths[p];
            assert_int_equal(path_a->count, path_b->count);
            assert_memory_equal(path_a->points, path_b->points,
                                path_a->count * sizeof *path_a->points);
        }
        assert_true(a->pieces[i].measures.flat_area == b->pieces[i].measures.flat_area);
    }
}

static void read_parts(const char *path, ur_parts *parts)
{
    ur_error error;
    if (ur_parts_import(path, NULL, parts, &error) != UR_OK)
        fail_msg("%s", error.message);
}

static void test_parts_readers_ignore_the_locale(void **state)
{
    fixture *f = *state;
    write_files(f, "c");
    const char *names[] = {"c.svg", "c.dxf"};
    for (size_t i = 0; i < 2; i++) {
        char path[256];
        path_in(f->dir, names[i], path, sizeof path);
        ur_parts in_c, in_comma;
        read_parts(path, &in_c);
        enter_comma_locale();
        read_parts(path, &in_comma);
        leave_comma_locale();
        /* The outline written is 100.25 x 50.125..50.375 less the hole, grown by the kerf. */
        assert_int_equal(in_c.count, 1);
        assert_true(in_c.pieces[0].measures.flat_area > 4500);
        assert_same_parts(&in_c, &in_comma);
        ur_parts_free(&in_c);
        ur_parts_free(&in_comma);
    }
}

static void test_profile_reader_ignores_the_locale(void **state)
{
    (void)state;
    ur_material in_c, in_comma;
    ur_machine machine_c, machine_comma;
    ur_error error;
    /* compared whole, padding too */
    memset(&in_c, 0, sizeof in_c);
    memset(&in_comma, 0, sizeof in_comma);
    memset(&machine_c, 0, sizeof machine_c);
    memset(&machine_comma, 0, sizeof machine_comma);
    assert_int_equal(
        ur_material_read(profile_roots, "profiles/materials/paper-0.3mm.xml", &in_c, &error),
        UR_OK);
    assert_int_equal(
        ur_machine_read(profile_roots, "profiles/machines/co2-60w.xml", &machine_c, &error), UR_OK);
    enter_comma_locale();
    ur_status material_status =
        ur_material_read(profile_roots, "profiles/materials/paper-0.3mm.xml", &in_comma, &error);
    ur_status machine_status =
        ur_machine_read(profile_roots, "profiles/machines/co2-60w.xml", &machine_comma, &error);
    leave_comma_locale();
    assert_int_equal(material_status, UR_OK);
    assert_int_equal(machine_status, UR_OK);
    /* 0.3 mm: read as 0 when the decimal point is a comma. */
    assert_true(in_c.thickness == 0.3);
    assert_memory_equal(&in_c, &in_comma, sizeof in_c);
    assert_memory_equal(&machine_c, &machine_comma, sizeof machine_c);
}

static void test_csv_and_mesh_readers_ignore_the_locale(void **state)
{
    fixture *f = *state;
    write_files(f, "c");
    char path[256];
    path_in(f->dir, "c.csv", path, sizeof path);
    ur_vec3 *points_c, *points_comma;
    size_t count_c, count_comma;
    bool closed_c, closed_comma;
    ur_error error;
    assert_int_equal(ur_curve_csv_read(path, &points_c, &count_c, &closed_c, &error), UR_OK);
    ur_mesh mesh_c, mesh_comma;
    assert_int_equal(ur_mesh_import("samples/lampshade.obj", NULL, &mesh_c, NULL, &error), UR_OK);
    enter_comma_locale();
    ur_status csv_status =
        ur_curve_csv_read(path, &points_comma, &count_comma, &closed_comma, &error);
    ur_status mesh_status =
        ur_mesh_import("samples/lampshade.obj", NULL, &mesh_comma, NULL, &error);
    leave_comma_locale();
    assert_int_equal(csv_status, UR_OK);
    assert_int_equal(mesh_status, UR_OK);
    assert_int_equal(count_c, 4);
    assert_true(points_c[0].y == 1.25);
    assert_int_equal(count_c, count_comma);
    assert_memory_equal(points_c, points_comma, count_c * sizeof *points_c);
    assert_int_equal(mesh_c.vertex_count, mesh_comma.vertex_count);
    assert_memory_equal(mesh_c.vertices, mesh_comma.vertices,
                        mesh_c.vertex_count * sizeof *mesh_c.vertices);
    free(points_c);
    free(points_comma);
    ur_mesh_free(&mesh_c);
    ur_mesh_free(&mesh_comma);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_writers_ignore_the_locale, setup, teardown),
        cmocka_unit_test_setup_teardown(test_parts_readers_ignore_the_locale, setup, teardown),
        cmocka_unit_test(test_profile_reader_ignores_the_locale),
        cmocka_unit_test_setup_teardown(test_csv_and_mesh_readers_ignore_the_locale, setup,
                                        teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
