/*
 * test_streams.c: every reader gives the same from a memory buffer as from
 * the file holding the same bytes, and every writer to a stream
 * (open_memstream) the same bytes as to a path.
 *
 * The inputs are the project's own: profiles, samples made by its scripts,
 * and files the writers make here.
 */
#include "test_support.h"

#include <libxml/xmlerror.h>

#include "unroll/out.h"

/* The profiles of the source tree: the tests run from its root. */
static const char *const profile_roots[] = {"./profiles", NULL};

typedef struct fixture {
    char dir[64];
    ur_piece piece;
    ur_machine machine;
    ur_placement placement;
    ur_sheet sheet;
    ur_layout layout;
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/unroll-test-streams-XXXXXX");
    if (!mkdtemp(f->dir)) {
        free(f);
        return -1;
    }
    const ur_vec2 outline[] = {{0, 0}, {120, 0}, {120, 60}, {0, 60}};
    const ur_vec2 hole[] = {{70, 20}, {80, 20}, {80, 30.5}, {70, 30}};
    const ur_vec2 fold[] = {{50, 0}, {50, 60}};
    ur_error error;
    snprintf(f->piece.name, sizeof f->piece.name, "panel");
    if (ur_piece_add_path(&f->piece, UR_OP_CUT, outline, 4, true, &error) != UR_OK ||
        ur_piece_add_path(&f->piece, UR_OP_CUT, hole, 4, true, &error) != UR_OK ||
        ur_piece_add_path(&f->piece, UR_OP_SCORE, fold, 2, false, &error) != UR_OK)
        return -1;
    f->machine.kind = UR_MACHINE_LASER;
    snprintf(f->machine.name, sizeof f->machine.name, "test-laser");
    f->machine.cut_speed = 20;
    f->machine.travel_speed = 200;
    for (int op = 0; op < UR_OP_COUNT; op++) {
        ur_op_style *style = &f->machine.styles[op];
        snprintf(style->layer, sizeof style->layer, "%s", ur_op_name((ur_op)op));
        snprintf(style->colour, sizeof style->colour, "#0000FF");
        style->line_width = 0.025;
    }
    f->placement = (ur_placement){0, ur_transform2_make(0.5, ur_vec2_make(100, 40))};
    f->sheet =
        (ur_sheet){.width = 300, .height = 200, .placements = &f->placement, .placement_count = 1};
    f->layout = (ur_layout){&f->sheet, 1, NULL, 0};
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    remove_test_directory(f->dir);
    ur_piece_free(&f->piece);
    free(f);
    return 0;
}

/* The whole file; the caller frees it. */
static char *read_all(const char *path, size_t *size)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        fail_msg("cannot open %s", path);
    assert_int_equal(fseek(file, 0, SEEK_END), 0);
    long length = ftell(file);
    assert_true(length > 0);
    rewind(file);
    char *text = malloc((size_t)length);
    assert_non_null(text);
    assert_int_equal(fread(text, 1, (size_t)length, file), (size_t)length);
    fclose(file);
    *size = (size_t)length;
    return text;
}

/* What a writer put into a memory stream. */
typedef struct memory_stream {
    FILE *file;
    char *bytes;
    size_t size;
} memory_stream;

static void stream_open(memory_stream *m)
{
    m->bytes = NULL;
    m->size = 0;
    m->file = open_memstream(&m->bytes, &m->size);
    assert_non_null(m->file);
}

/* Closes the stream and checks it holds exactly the file at path; frees the bytes. */
static void assert_stream_is_file(memory_stream *m, const char *path)
{
    assert_int_equal(fclose(m->file), 0);
    size_t size;
    char *text = read_all(path, &size);
    if (size != m->size || memcmp(text, m->bytes, size) != 0)
        fail_msg("%s: %zu bytes in the file, %zu different ones in the stream", path, size,
                 m->size);
    free(text);
    free(m->bytes);
}

/* ---- Writers ---------------------------------------------------------------- */

static void test_cut_files_to_a_stream(void **state)
{
    fixture *f = *state;
    ur_error error;
    ur_output_options options = {"unroll stream test", NULL};
    ur_format_options as_drawn = {.job_name = "streams", .drawing_order = true};
    char path[256];

    path_in(f->dir, "a.svg", path, sizeof path);
    assert_int_equal(ur_write_svg(path, &f->layout, &f->piece, &f->machine, &options, &error),
                     UR_OK);
    memory_stream m;
    stream_open(&m);
    /* ur_write_svg records no job name */
    ur_format_options svg_options = {.drawing_order = true};
    assert_int_equal(ur_write_stream(m.file, UR_FORMAT_SVG, &f->layout, &f->piece, &f->machine,
                                     &options, &svg_options, &error),
                     UR_OK);
    assert_true(m.size > 500);
    assert_stream_is_file(&m, path);

    unsigned formats[] = {UR_FORMAT_DXF, UR_FORMAT_PNG, UR_FORMAT_SVG};
    const char *names[] = {"b.dxf", "b.png", "b.svg"};
    for (size_t i = 0; i < 3; i++) {
        path_in(f->dir, names[i], path, sizeof path);
        assert_int_equal(ur_write_outputs(path, formats[i], &f->layout, &f->piece, &f->machine,
                                          &options, &as_drawn, &error),
                         UR_OK);
        stream_open(&m);
        assert_int_equal(ur_write_stream(m.file, (ur_format)formats[i], &f->layout, &f->piece,
                                         &f->machine, &options, &as_drawn, &error),
                         UR_OK);
        assert_stream_is_file(&m, path);
    }
}

static void test_two_sheets_are_refused_on_a_stream(void **state)
{
    fixture *f = *state;
    ur_sheet sheets[2] = {f->sheet, f->sheet};
    ur_layout two = {sheets, 2, NULL, 0};
    ur_error error;
    memory_stream m;
    stream_open(&m);
    assert_int_equal(
        ur_write_stream(m.file, UR_FORMAT_SVG, &two, &f->piece, &f->machine, NULL, NULL, &error),
        UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "2 sheets"));
    fclose(m.file);
    free(m.bytes);
}

static void test_report_and_curve_to_a_stream(void **state)
{
    fixture *f = *state;
    ur_error error;
    char path[256];
    path_in(f->dir, "r.json", path, sizeof path);
    ur_report_context context = {
        .surface = "test", .method = "exact", .machine = &f->machine, .surface_area = 7200};
    assert_int_equal(ur_report_write(path, &context, &f->piece, 1, &f->layout, NULL, &error),
                     UR_OK);
    memory_stream m;
    stream_open(&m);
    assert_int_equal(ur_report_write_stream(m.file, &context, &f->piece, 1, &f->layout, &error),
                     UR_OK);
    assert_stream_is_file(&m, path);

    const ur_vec3 curve[] = {{0, 0, 0}, {10, 1, 0.5}, {20, 3, 1}, {30, 6, 1.5}, {40, 10, 2}};
    path_in(f->dir, "c.csv", path, sizeof path);
    assert_int_equal(ur_curve_csv_write(path, curve, 5, NULL, &error), UR_OK);
    stream_open(&m);
    assert_int_equal(ur_curve_csv_write_stream(m.file, curve, 5, &error), UR_OK);
    assert_stream_is_file(&m, path);
}

/* ---- Readers ---------------------------------------------------------------- */

static void test_curve_from_a_buffer(void **state)
{
    fixture *f = *state;
    ur_error error;
    char path[256];
    path_in(f->dir, "c.csv", path, sizeof path);
    /* A closed curve of 5 points, with a comment and CRLF */
    const char text[] = "# a square\r\n0,0,0\r\n10,0,0\r\n10,10,0\r\n0,10,0\r\n5,12,0\r\n0,0,0\r\n";
    FILE *file = fopen(path, "wb");
    assert_non_null(file);
    assert_int_equal(fwrite(text, 1, sizeof text - 1, file), sizeof text - 1);
    assert_int_equal(fclose(file), 0);
    ur_vec3 *from_file, *from_buffer;
    size_t file_count, buffer_count;
    bool file_closed, buffer_closed;
    assert_int_equal(ur_curve_csv_read(path, &from_file, &file_count, &file_closed, &error), UR_OK);
    assert_int_equal(ur_curve_csv_read_buffer("c.csv", text, sizeof text - 1, &from_buffer,
                                              &buffer_count, &buffer_closed, &error),
                     UR_OK);
    assert_int_equal(file_count, 5);
    assert_true(file_closed);
    assert_int_equal(buffer_count, file_count);
    assert_true(buffer_closed);
    assert_memory_equal(from_file, from_buffer, file_count * sizeof *from_file);
    free(from_file);
    free(from_buffer);
    /* The buffer's own name in messages, as a path would be */
    assert_int_equal(ur_curve_csv_read_buffer("bad.csv", "1,2\n", 4, &from_buffer, &buffer_count,
                                              &buffer_closed, &error),
                     UR_ERROR_INPUT);
    assert_string_equal(error.message, "bad.csv:1: expected 3 fields 'x,y,z', found 2");
    assert_int_equal(ur_curve_csv_read_buffer("empty.csv", "", 0, &from_buffer, &buffer_count,
                                              &buffer_closed, &error),
                     UR_ERROR_INPUT);
}

static void test_profiles_from_a_buffer(void **state)
{
    (void)state;
    ur_error error;
    size_t size;
    const char *material_path = "profiles/materials/plywood-3mm.xml";
    char *text = read_all(material_path, &size);
    ur_material from_file, from_buffer;
    assert_int_equal(ur_material_read(profile_roots, material_path, &from_file, &error), UR_OK);
    assert_int_equal(
        ur_material_read_buffer(profile_roots, material_path, text, size, &from_buffer, &error),
        UR_OK);
    assert_true(from_file.thickness == 3.0);
    assert_memory_equal(&from_file, &from_buffer, sizeof from_file);
    free(text);

    const char *machine_path = "profiles/machines/co2-60w.xml";
    text = read_all(machine_path, &size);
    ur_machine machine_file, machine_buffer;
    assert_int_equal(ur_machine_read(profile_roots, machine_path, &machine_file, &error), UR_OK);
    assert_int_equal(
        ur_machine_read_buffer(profile_roots, machine_path, text, size, &machine_buffer, &error),
        UR_OK);
    assert_string_equal(machine_buffer.name, "co2-60w");
    assert_memory_equal(&machine_file, &machine_buffer, sizeof machine_file);
    /* Cut short: libxml2's message with the buffer's name and line */
    assert_int_equal(
        ur_machine_read_buffer(profile_roots, "cut.xml", text, size / 2, &machine_buffer, &error),
        UR_ERROR_INPUT);
    assert_true(strncmp(error.message, "cut.xml:", 8) == 0);
    free(text);
}

static void assert_same_options(const ur_job_file_option *a, const ur_job_file_option *b,
                                size_t count)
{
    for (size_t i = 0; i < count; i++) {
        assert_string_equal(a[i].name, b[i].name);
        assert_string_equal(a[i].value, b[i].value);
        assert_int_equal(a[i].has_value, b[i].has_value);
        assert_int_equal(a[i].line, b[i].line);
    }
}

static void test_job_from_a_buffer(void **state)
{
    (void)state;
    const char *path = "samples/jobs/lamp.xml";
    ur_error error;
    size_t size;
    char *text = read_all(path, &size);
    ur_job_file from_file, from_buffer;
    assert_int_equal(ur_job_file_read(profile_roots, path, &from_file, &error), UR_OK);
    assert_int_equal(ur_job_file_read_buffer(profile_roots, path, text, size, &from_buffer, &error),
                     UR_OK);
    assert_true(from_file.part_count > 0);
    assert_int_equal(from_file.part_count, from_buffer.part_count);
    assert_int_equal(from_file.option_count, from_buffer.option_count);
    assert_string_equal(from_file.output_directory, from_buffer.output_directory);
    assert_string_equal(from_file.machine, from_buffer.machine);
    assert_same_options(from_file.options, from_buffer.options, from_file.option_count);
    for (size_t k = 0; k < from_file.part_count; k++) {
        assert_string_equal(from_file.parts[k].surface, from_buffer.parts[k].surface);
        assert_string_equal(from_file.parts[k].file, from_buffer.parts[k].file);
        assert_int_equal(from_file.parts[k].option_count, from_buffer.parts[k].option_count);
        assert_same_options(from_file.parts[k].options, from_buffer.parts[k].options,
                            from_file.parts[k].option_count);
    }
    ur_job_file_free(&from_file);
    ur_job_file_free(&from_buffer);
    free(text);
}

static void assert_same_parts(const ur_parts *a, const ur_parts *b)
{
    assert_int_equal(a->count, b->count);
    assert_int_equal(a->warning_count, b->warning_count);
    for (size_t i = 0; i < a->count; i++) {
        assert_string_equal(a->pieces[i].name, b->pieces[i].name);
        assert_int_equal(a->pieces[i].path_count, b->pieces[i].path_count);
        for (size_t p = 0; p < a->pieces[i].path_count; p++) {
            const ur_path *path_a = &a->pieces[i].paths[p], *path_b = &b->pieces[i].paths[p];
            assert_int_equal(path_a->op, path_b->op);
            assert_int_equal(path_a->count, path_b->count);
            assert_memory_equal(path_a->points, path_b->points,
                                path_a->count * sizeof *path_a->points);
        }
    }
}

static void parts_both_ways(const char *path, const char *name, size_t expected_parts)
{
    ur_error error;
    size_t size;
    char *text = read_all(path, &size);
    ur_parts from_file, from_buffer;
    if (ur_parts_import(path, NULL, &from_file, &error) != UR_OK)
        fail_msg("%s", error.message);
    if (ur_parts_import_buffer(name, text, size, NULL, &from_buffer, &error) != UR_OK)
        fail_msg("%s", error.message);
    assert_int_equal(from_file.count, expected_parts);
    assert_same_parts(&from_file, &from_buffer);
    ur_parts_free(&from_file);
    ur_parts_free(&from_buffer);
    free(text);
}

static void test_parts_from_a_buffer(void **state)
{
    fixture *f = *state;
    ur_error error;
    char path[256];
    /* Our own SVG and DXF of the panel (its hole and fold inside it), and the sample drawing */
    path_in(f->dir, "panel.svg", path, sizeof path);
    assert_int_equal(ur_write_svg(path, &f->layout, &f->piece, &f->machine, NULL, &error), UR_OK);
    parts_both_ways(path, "panel.svg", 1);
    path_in(f->dir, "panel.dxf", path, sizeof path);
    assert_int_equal(ur_write_dxf(path, &f->layout, &f->piece, &f->machine, NULL, NULL, &error),
                     UR_OK);
    parts_both_ways(path, "panel.dxf", 1);
    ur_parts parts;
    assert_int_equal(ur_parts_import_buffer("plate.txt", "x", 1, NULL, &parts, &error),
                     UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "plate.txt: unknown kind of file"));
    assert_int_equal(ur_parts_import_buffer("plate.svg", "<svg", 4, NULL, &parts, &error),
                     UR_ERROR_INPUT);
    assert_true(strncmp(error.message, "plate.svg:1: ", 13) == 0);
}

static void test_meshes_from_a_buffer(void **state)
{
    (void)state;
    const char *paths[] = {"samples/lampshade.obj", "samples/lampshade.ply",
                           "samples/lampshade-binary.stl", "samples/lampshade.glb"};
    size_t first_triangles = 0;
    for (size_t i = 0; i < 4; i++) {
        ur_error error;
        size_t size;
        char *text = read_all(paths[i], &size);
        ur_mesh from_file, from_buffer;
        char(*file_names)[64], (*buffer_names)[64];
        if (ur_mesh_import(paths[i], NULL, &from_file, &file_names, &error) != UR_OK)
            fail_msg("%s", error.message);
        if (ur_mesh_import_buffer(paths[i], text, size, NULL, &from_buffer, &buffer_names,
                                  &error) != UR_OK)
            fail_msg("%s", error.message);
        /* The same lampshade in every format: as many triangles in each */
        if (i == 0)
            first_triangles = from_file.triangle_count;
        assert_int_equal(from_file.triangle_count, first_triangles);
        assert_int_equal(from_file.vertex_count, from_buffer.vertex_count);
        assert_int_equal(from_file.triangle_count, from_buffer.triangle_count);
        assert_int_equal(from_file.group_count, from_buffer.group_count);
        assert_memory_equal(from_file.vertices, from_buffer.vertices,
                            from_file.vertex_count * sizeof *from_file.vertices);
        assert_memory_equal(from_file.triangles, from_buffer.triangles,
                            from_file.triangle_count * sizeof *from_file.triangles);
        assert_memory_equal(file_names, buffer_names, from_file.group_count * sizeof *file_names);
        ur_mesh_free(&from_file);
        ur_mesh_free(&from_buffer);
        free(file_names);
        free(buffer_names);
        free(text);
    }
}

/* ---- libxml2's handlers ------------------------------------------------------ */

static int host_errors;

#if LIBXML_VERSION >= 21200
static void host_handler(void *context, const xmlError *xml_error)
#else
static void host_handler(void *context, xmlError *xml_error)
#endif
{
    (void)context;
    (void)xml_error;
    host_errors++;
}

static void host_generic_handler(void *context, const char *format, ...)
{
    (void)context;
    (void)format;
    host_errors++;
}

/*
 * A host program's own libxml2 handlers are neither called by the
 * library's parsing nor replaced after it, on success or failure.
 */
static void test_xml_handlers_are_restored(void **state)
{
    (void)state;
    int context = 0;
    xmlSetStructuredErrorFunc(&context, host_handler);
    xmlSetGenericErrorFunc(&context, host_generic_handler);
    ur_error error;
    ur_machine machine;
    ur_material material;
    ur_parts parts;
    const char broken[] = "<machine><kerf>";
    assert_int_equal(ur_machine_read_buffer(profile_roots, "broken.xml", broken, sizeof broken - 1,
                                            &machine, &error),
                     UR_ERROR_INPUT);
    const char invalid[] = "<material name=\"x\"/>";
    assert_int_equal(ur_material_read_buffer(profile_roots, "invalid.xml", invalid,
                                             sizeof invalid - 1, &material, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(
        ur_parts_import_buffer("p.svg", broken, sizeof broken - 1, NULL, &parts, &error),
        UR_ERROR_INPUT);
    assert_int_equal(
        ur_machine_read(profile_roots, "profiles/machines/co2-60w.xml", &machine, &error), UR_OK);
    assert_int_equal(host_errors, 0);
    assert_ptr_equal(xmlStructuredError, host_handler);
    assert_ptr_equal(xmlStructuredErrorContext, &context);
    assert_ptr_equal(xmlGenericError, host_generic_handler);
    assert_ptr_equal(xmlGenericErrorContext, &context);
    xmlSetStructuredErrorFunc(NULL, NULL);
    xmlSetGenericErrorFunc(NULL, NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_cut_files_to_a_stream, setup, teardown),
        cmocka_unit_test_setup_teardown(test_two_sheets_are_refused_on_a_stream, setup, teardown),
        cmocka_unit_test_setup_teardown(test_report_and_curve_to_a_stream, setup, teardown),
        cmocka_unit_test_setup_teardown(test_curve_from_a_buffer, setup, teardown),
        cmocka_unit_test(test_profiles_from_a_buffer),
        cmocka_unit_test(test_job_from_a_buffer),
        cmocka_unit_test_setup_teardown(test_parts_from_a_buffer, setup, teardown),
        cmocka_unit_test(test_meshes_from_a_buffer),
        cmocka_unit_test(test_xml_handlers_are_restored),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
