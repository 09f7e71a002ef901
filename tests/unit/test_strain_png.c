/*
 * test_strain_png.c: the strain picture (ur_strain_png_write) and the
 * per-triangle strain it draws, carried from a flattened mesh through its
 * net (ur_net_from_flat) to its piece (ur_piece_from_net).
 *
 * The pictures are drawn from pieces made by hand: an 80 mm square cut along
 * its diagonal into a stretched triangle (+2%) and a compressed one (-1%),
 * turned a quarter turn onto a 254 x 127 mm sheet, so that at 100 dpi the
 * picture is 1000 x 500 pixels and every expected pixel was worked out by
 * hand from the placement.  They are read back with cairo's own PNG reader.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/flatten.h"
#include "unroll/out.h"

#include "test_support.h"

#define PI 3.14159265358979323846

enum { PIECES = 2 };

typedef struct fixture {
    char dir[64];
    ur_piece pieces[PIECES];
    ur_placement placements[2];
    ur_sheet sheets[2];
    ur_layout layout;
} fixture;

/* ---- The pieces and the layout ------------------------------------------ */

static void add_path(ur_piece *piece, const ur_vec2 *points, size_t count)
{
    ur_error error;
    assert_int_equal(ur_piece_add_path(piece, UR_OP_CUT, points, count, true, &error), UR_OK);
}

/* Two triangles of the square (0, 0)-(80, 80): below the diagonal +2%, above it -1%. */
static void make_shaded_square(ur_piece *piece)
{
    const ur_vec2 square[] = {{0, 0}, {80, 0}, {80, 80}, {0, 80}};
    snprintf(piece->name, sizeof piece->name, "P1");
    add_path(piece, square, 4);
    piece->shading.triangles = calloc(2, sizeof *piece->shading.triangles);
    piece->shading.strain = calloc(2, sizeof *piece->shading.strain);
    assert_non_null(piece->shading.triangles);
    assert_non_null(piece->shading.strain);
    const ur_vec2 below[3] = {{0, 0}, {80, 0}, {80, 80}}, above[3] = {{0, 0}, {80, 80}, {0, 80}};
    memcpy(piece->shading.triangles[0], below, sizeof below);
    memcpy(piece->shading.triangles[1], above, sizeof above);
    piece->shading.strain[0] = 0.02;
    piece->shading.strain[1] = -0.01;
    piece->shading.count = 2;
}

/* A 100 x 60 mm rectangle with no shading: a development. */
static void make_exact_panel(ur_piece *piece)
{
    const ur_vec2 panel[] = {{0, 0}, {100, 0}, {100, 60}, {0, 60}};
    snprintf(piece->name, sizeof piece->name, "P2");
    add_path(piece, panel, 4);
}

/*
 * Sheet 1 (254 x 127 mm): the square a quarter turn, then moved by (100, 10),
 * so (x, y) goes to (100 - y, 10 + x) and the square covers x 20..100,
 * y 10..90.  Sheet 2 (127 x 127 mm): the panel moved by (10, 10).
 */
static void make_layout(fixture *f)
{
    f->placements[0] = (ur_placement){0, ur_transform2_make(PI / 2, ur_vec2_make(100, 10))};
    f->placements[1] = (ur_placement){1, ur_transform2_make(0, ur_vec2_make(10, 10))};
    f->sheets[0] = (ur_sheet){
        .width = 254, .height = 127, .placements = &f->placements[0], .placement_count = 1};
    f->sheets[1] = (ur_sheet){
        .width = 127, .height = 127, .placements = &f->placements[1], .placement_count = 1};
    f->layout = (ur_layout){f->sheets, 1, NULL, 0};
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/unroll-test-strain-XXXXXX");
    if (!mkdtemp(f->dir)) {
        free(f);
        return -1;
    }
    make_shaded_square(&f->pieces[0]);
    make_exact_panel(&f->pieces[1]);
    make_layout(f);
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

/* ---- Reading the pictures back ------------------------------------------ */

typedef struct rgb {
    int r, g, b;
} rgb;

static cairo_surface_t *load_png(const char *path, int width, int height)
{
    cairo_surface_t *image = cairo_image_surface_create_from_png(path);
    assert_int_equal(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
    assert_int_equal(cairo_image_surface_get_width(image), width);
    assert_int_equal(cairo_image_surface_get_height(image), height);
    return image;
}

/* The pixel of the sheet point (x, y) mm, the sheet height_mm tall, at 100 dpi. */
static rgb pixel_at(cairo_surface_t *image, double x, double y, double height_mm)
{
    int column = (int)floor(x * 100 / 25.4), row = (int)floor((height_mm - y) * 100 / 25.4);
    assert_true(column >= 0 && column < cairo_image_surface_get_width(image));
    assert_true(row >= 0 && row < cairo_image_surface_get_height(image));
    cairo_surface_flush(image);
    const unsigned char *data = cairo_image_surface_get_data(image);
    uint32_t value;
    memcpy(&value, data + (size_t)row * cairo_image_surface_get_stride(image) + 4 * column,
           sizeof value);
    return (rgb){(int)(value >> 16 & 0xff), (int)(value >> 8 & 0xff), (int)(value & 0xff)};
}

static double lightness(rgb c)
{
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

static void assert_white(rgb c)
{
    if (c.r != 255 || c.g != 255 || c.b != 255)
        fail_msg("expected white, got (%d, %d, %d)", c.r, c.g, c.b);
}

/* Writes the fixture's layout to NAME in the test directory; the full path into path. */
static ur_status write_picture(fixture *f, const char *name, double dpi, char *path, size_t size,
                               ur_error *error)
{
    path_in(f->dir, name, path, size);
    return ur_strain_png_write(path, &f->layout, f->pieces, PIECES, dpi, NULL, error);
}

/* ---- The picture -------------------------------------------------------- */

static void test_colours_at_the_triangles(void **state)
{
    fixture *f = *state;
    char path[256];
    ur_error error;
    assert_int_equal(write_picture(f, "strain.png", 100, path, sizeof path, &error), UR_OK);
    assert_int_equal(entries_in(f->dir), 1);
    cairo_surface_t *image = load_png(path, 1000, 500);
    /* Centroids: below (53.3, 26.7) goes to (73.3, 63.3), above (26.7, 53.3) to (46.7, 36.7). */
    rgb stretched = pixel_at(image, 100 - 80.0 / 3, 10 + 160.0 / 3, 127);
    rgb compressed = pixel_at(image, 100 - 160.0 / 3, 10 + 80.0 / 3, 127);
    if (!(stretched.r > stretched.b))
        fail_msg("stretch is not red: (%d, %d, %d)", stretched.r, stretched.g, stretched.b);
    if (!(compressed.b > compressed.r))
        fail_msg("compression is not blue: (%d, %d, %d)", compressed.r, compressed.g, compressed.b);
    /* In grey: the larger |strain| is the darker, and both are darker than no strain. */
    assert_true(lightness(stretched) < lightness(compressed));
    assert_true(lightness(compressed) < 250);
    /* Outside the piece, away from the legend (bottom right, where nothing lies). */
    assert_white(pixel_at(image, 180, 100, 127));
    assert_white(pixel_at(image, 10, 60, 127));
    cairo_surface_destroy(image);
}

static void test_default_resolution(void **state)
{
    fixture *f = *state;
    char path[256];
    ur_error error;
    assert_int_equal(write_picture(f, "default.png", 0, path, sizeof path, &error), UR_OK);
    cairo_surface_t *image = load_png(path, 960, 480); /* 254 x 127 mm at 96 dpi */
    cairo_surface_destroy(image);
}

static void test_two_sheets_two_files(void **state)
{
    fixture *f = *state;
    f->layout.sheet_count = 2;
    char path[256], first[256], second[256];
    ur_error error;
    assert_int_equal(write_picture(f, "strain.png", 100, path, sizeof path, &error), UR_OK);
    path_in(f->dir, "strain-1.png", first, sizeof first);
    path_in(f->dir, "strain-2.png", second, sizeof second);
    assert_false(exists(path));
    assert_int_equal(entries_in(f->dir), 2);
    cairo_surface_t *image = load_png(first, 1000, 500);
    cairo_surface_destroy(image);
    image = load_png(second, 500, 500);
    /* The development inside its panel (10..110 x 10..70 mm), away from its label: white. */
    assert_white(pixel_at(image, 30, 25, 127));
    cairo_surface_destroy(image);
}

/* ---- Failures leave nothing --------------------------------------------- */

static void test_missing_directory(void **state)
{
    fixture *f = *state;
    f->layout.sheet_count = 2;
    char path[256];
    ur_error error;
    assert_int_equal(write_picture(f, "missing/strain.png", 100, path, sizeof path, &error),
                     UR_ERROR_IO);
    assert_non_null(strstr(error.message, "does not exist"));
    assert_int_equal(entries_in(f->dir), 0);
}

/* A sheet that cannot be drawn: no picture is written, and an old one stays as it was. */
static void test_failure_keeps_old_files(void **state)
{
    fixture *f = *state;
    char old[256], text[8] = {0};
    path_in(f->dir, "strain-1.png", old, sizeof old);
    FILE *file = fopen(old, "w");
    assert_non_null(file);
    assert_true(fputs("old", file) >= 0);
    assert_int_equal(fclose(file), 0);
    f->layout.sheet_count = 2;
    f->sheets[1].width = NAN;
    char path[256];
    ur_error error;
    assert_int_equal(write_picture(f, "strain.png", 100, path, sizeof path, &error),
                     UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "sheet 2"));
    assert_int_equal(entries_in(f->dir), 1);
    file = fopen(old, "r");
    assert_non_null(file);
    assert_non_null(fgets(text, sizeof text, file));
    assert_int_equal(fclose(file), 0);
    assert_string_equal(text, "old");
}

static void test_refusals(void **state)
{
    fixture *f = *state;
    char path[256];
    ur_error error;
    assert_int_equal(write_picture(f, "a.png", -1, path, sizeof path, &error), UR_ERROR_INPUT);
    assert_int_equal(write_picture(f, "a.png", NAN, path, sizeof path, &error), UR_ERROR_INPUT);
    f->sheets[0].width = 10000; /* 10 m at 300 dpi: 118110 pixels across */
    assert_int_equal(write_picture(f, "a.png", 300, path, sizeof path, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "pixels"));
    f->sheets[0].width = 254;
    f->pieces[0].shading.strain[1] = NAN;
    assert_int_equal(write_picture(f, "a.png", 100, path, sizeof path, &error), UR_ERROR_INTERNAL);
    f->pieces[0].shading.strain[1] = -0.01;
    f->placements[0].piece_index = PIECES;
    assert_int_equal(write_picture(f, "a.png", 100, path, sizeof path, &error), UR_ERROR_INTERNAL);
    f->placements[0].piece_index = 0;
    f->layout.sheet_count = 0;
    assert_int_equal(write_picture(f, "a.png", 100, path, sizeof path, &error), UR_ERROR_INPUT);
    assert_int_equal(entries_in(f->dir), 0);
}

/* ---- Shading from a flattened mesh to its piece -------------------------- */

/* A 4 x 4 grid over a saddle z = x y / 400 on (0..40)^2: flattened, it has strain. */
static void saddle(ur_mesh *mesh)
{
    enum { N = 4 };
    ur_vec3 vertices[(N + 1) * (N + 1)];
    size_t triangles[2 * N * N][3], t = 0;
    for (int j = 0; j <= N; j++)
        for (int i = 0; i <= N; i++) {
            double x = 10.0 * i, y = 10.0 * j;
            vertices[j * (N + 1) + i] = ur_vec3_make(x, y, (x - 20) * (y - 20) / 40);
        }
    for (size_t j = 0; j < N; j++)
        for (size_t i = 0; i < N; i++) {
            size_t a = j * (N + 1) + i, b = a + 1, c = b + N + 1, d = a + N + 1;
            size_t first[3] = {a, b, c}, second[3] = {a, c, d};
            memcpy(triangles[t++], first, sizeof first);
            memcpy(triangles[t++], second, sizeof second);
        }
    ur_error error;
    assert_int_equal(ur_mesh_new(vertices, (N + 1) * (N + 1), (const size_t(*)[3])triangles, t,
                                 NULL, mesh, &error),
                     UR_OK);
}

static void test_shading_from_flat_to_piece(void **state)
{
    (void)state;
    ur_mesh mesh;
    saddle(&mesh);
    ur_flat_piece flat;
    ur_net_list nets = {calloc(1, sizeof(ur_net)), 1};
    assert_non_null(nets.nets);
    ur_error error;
    assert_int_equal(ur_flatten(&mesh, NULL, &flat, &error), UR_OK);
    assert_int_equal(ur_net_from_flat(&mesh, &flat, "P1", &nets.nets[0], &error), UR_OK);
    const ur_shading *shading = &nets.nets[0].shading;
    assert_int_equal(shading->count, mesh.triangle_count);
    double largest = 0;
    for (size_t t = 0; t < mesh.triangle_count; t++) {
        for (int k = 0; k < 3; k++) {
            ur_vec2 corner = flat.flat[mesh.triangles[t][k]];
            assert_true(shading->triangles[t][k].x == corner.x);
            assert_true(shading->triangles[t][k].y == corner.y);
        }
        double stretch = flat.strain[t].sigma1 - 1, compression = 1 - flat.strain[t].sigma2;
        assert_true(shading->strain[t] == (stretch >= compression ? stretch : -compression));
        largest = fmax(largest, fabs(shading->strain[t]));
    }
    assert_true(largest > 1e-4); /* a saddle does not flatten without strain */

    ur_allowance_options options = {false};
    ur_piece piece;
    assert_int_equal(ur_piece_from_net(&nets.nets[0], &options, &piece, &error), UR_OK);
    assert_int_equal(piece.shading.count, shading->count);
    assert_ptr_not_equal(piece.shading.strain, shading->strain);
    assert_memory_equal(piece.shading.strain, shading->strain,
                        shading->count * sizeof *shading->strain);
    assert_memory_equal(piece.shading.triangles, shading->triangles,
                        shading->count * sizeof *shading->triangles);
    ur_piece_free(&piece);
    assert_null(piece.shading.triangles);
    assert_null(piece.shading.strain);
    assert_int_equal(piece.shading.count, 0);
    ur_flat_piece_free(&flat);
    ur_net_list_free(&nets);
    ur_mesh_free(&mesh);
}

/* A development's net has no shading, and neither has its piece. */
static void test_no_shading_for_a_development(void **state)
{
    (void)state;
    ur_vec2 outline[] = {{0, 0}, {10, 0}, {10, 5}, {0, 5}};
    ur_net net = {.name = "P1", .outline = outline, .outline_count = 4};
    ur_piece piece;
    ur_error error;
    assert_int_equal(ur_piece_from_net(&net, NULL, &piece, &error), UR_OK);
    assert_null(piece.shading.triangles);
    assert_null(piece.shading.strain);
    assert_int_equal(piece.shading.count, 0);
    ur_piece_free(&piece);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_colours_at_the_triangles, setup, teardown),
        cmocka_unit_test_setup_teardown(test_default_resolution, setup, teardown),
        cmocka_unit_test_setup_teardown(test_two_sheets_two_files, setup, teardown),
        cmocka_unit_test_setup_teardown(test_missing_directory, setup, teardown),
        cmocka_unit_test_setup_teardown(test_failure_keeps_old_files, setup, teardown),
        cmocka_unit_test_setup_teardown(test_refusals, setup, teardown),
        cmocka_unit_test(test_shading_from_flat_to_piece),
        cmocka_unit_test(test_no_shading_for_a_development),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
