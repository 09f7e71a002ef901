/*
 * test_assembly.c: the assembly guide (ur_assembly_write) and the 3D faces
 * a net carries for it (ur_net_set_faces, ur_net_from_flat).
 *
 * The guide of a cube cut into two pieces (four faces and two) is read
 * back with cairo's PNG reader and its colours counted by hue: two pieces,
 * two hues.  The view from front left below looks along (1, 1, 1) and sees
 * only the faces toward -x, -y and -z, all of the larger piece: its hue
 * alone there, or a hidden face was drawn.
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

typedef struct fixture {
    char dir[64];
} fixture;

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/unroll-test-assembly-XXXXXX");
    if (!mkdtemp(f->dir)) {
        free(f);
        return -1;
    }
    *state = f;
    return 0;
}

static int remove_entry(const char *path)
{
    return remove(path);
}

static int teardown(void **state)
{
    fixture *f = *state;
    each_entry(f->dir, remove_entry);
    rmdir(f->dir);
    free(f);
    return 0;
}

/* ---- A cube in two pieces ----------------------------------------------- */

/* Vertex i of the cube of side 40 at (x, y, z) = bits 0, 1, 2 of i. */
static void cube_mesh(ur_mesh *mesh)
{
    ur_vec3 vertices[8];
    for (int i = 0; i < 8; i++)
        vertices[i] = ur_vec3_make(40.0 * (i & 1), 40.0 * (i >> 1 & 1), 40.0 * (i >> 2 & 1));
    /* Quads counter-clockwise from outside: -x, -y, -z, +x, then +y, +z. */
    static const size_t quads[6][4] = {{0, 4, 6, 2}, {0, 1, 5, 4}, {0, 2, 3, 1},
                                       {1, 3, 7, 5}, {2, 6, 7, 3}, {4, 5, 7, 6}};
    size_t triangles[12][3];
    for (int q = 0; q < 6; q++) {
        const size_t *c = quads[q];
        memcpy(triangles[2 * q], (size_t[3]){c[0], c[1], c[2]}, sizeof triangles[0]);
        memcpy(triangles[2 * q + 1], (size_t[3]){c[0], c[2], c[3]}, sizeof triangles[0]);
    }
    ur_error error;
    assert_int_equal(
        ur_mesh_new(vertices, 8, (const size_t(*)[3])triangles, 12, NULL, mesh, &error), UR_OK);
}

/*
 * P1: the eight triangles toward -x, -y, -z and +x; P2: the four toward
 * +y and +z.  Each face of a cube faces two of the guide's four views, so
 * P1 shows twice the area of P2.
 */
static void two_pieces(ur_net_list *nets)
{
    ur_mesh mesh;
    cube_mesh(&mesh);
    nets->count = 2;
    nets->nets = calloc(2, sizeof *nets->nets);
    assert_non_null(nets->nets);
    ur_error error;
    const size_t first[2] = {0, 8}, count[2] = {8, 4};
    for (size_t k = 0; k < 2; k++) {
        size_t triangles[8];
        for (size_t t = 0; t < count[k]; t++)
            triangles[t] = first[k] + t;
        snprintf(nets->nets[k].name, sizeof nets->nets[k].name, "P%zu", k + 1);
        assert_int_equal(ur_net_set_faces(&nets->nets[k], &mesh, triangles, count[k], &error),
                         UR_OK);
        assert_int_equal(nets->nets[k].face_count, count[k]);
    }
    ur_mesh_free(&mesh);
}

/* ---- Reading the picture ------------------------------------------------ */

/* Pixels of each whole degree of hue, counting only clearly coloured ones (no grey, no text). */
typedef struct hues {
    size_t count[360];
    size_t coloured;
} hues;

static void count_hues(cairo_surface_t *image, int left, int top, int right, int bottom, hues *h)
{
    memset(h, 0, sizeof *h);
    const unsigned char *data = cairo_image_surface_get_data(image);
    int stride = cairo_image_surface_get_stride(image);
    for (int y = top; y < bottom; y++)
        for (int x = left; x < right; x++) {
            uint32_t value;
            memcpy(&value, data + (size_t)y * (size_t)stride + 4 * (size_t)x, sizeof value);
            double r = value >> 16 & 0xff, g = value >> 8 & 0xff, b = value & 0xff;
            double high = fmax(r, fmax(g, b)), low = fmin(r, fmin(g, b)), chroma = high - low;
            if (chroma < 40)
                continue;
            double hue = high == r   ? fmod((g - b) / chroma + 6, 6)
                         : high == g ? (b - r) / chroma + 2
                                     : (r - g) / chroma + 4;
            h->count[(int)(hue * 60) % 360]++;
            h->coloured++;
        }
}

enum { MOST_CLUSTERS = 8 };

/* A colour seen: its pixels and their middle hue, degrees. */
typedef struct cluster {
    size_t pixels;
    double hue;
} cluster;

/*
 * Groups of the degrees that hold at least `least` pixels each, a group
 * ending where 20 degrees in a row hold fewer: one group a colour (its
 * shades round to hues a degree or two apart; blends where two colours
 * touch are far fewer pixels).  Returns how many, the first MOST_CLUSTERS
 * of them in found.
 */
static int hue_clusters(const hues *h, size_t least, cluster found[MOST_CLUSTERS])
{
    int first = -1;
    for (int d = 0; d < 360 && first < 0; d++)
        if (h->count[d] < least && h->count[(d + 1) % 360] >= least)
            first = (d + 1) % 360; /* a degree where a group starts after a gap */
    if (first < 0)
        return h->count[0] >= least ? 1 : 0;
    int count = 0, empty = 20;
    double weighted = 0;
    for (int step = 0; step < 360; step++) {
        int d = (first + step) % 360;
        if (h->count[d] < least) {
            empty++;
            continue;
        }
        if (empty >= 20) {
            count++;
            if (count <= MOST_CLUSTERS)
                found[count - 1] = (cluster){0, 0};
            weighted = 0;
        }
        empty = 0;
        if (count <= MOST_CLUSTERS) {
            cluster *c = &found[count - 1];
            c->pixels += h->count[d];
            weighted += (double)h->count[d] * (first + step);
            c->hue = fmod(weighted / (double)c->pixels, 360);
        }
    }
    return count;
}

/* Whether two hues, degrees, are within tolerance of each other round the circle. */
static bool same_hue(double a, double b, double tolerance)
{
    double d = fabs(a - b);
    return fmin(d, 360 - d) <= tolerance;
}

static cairo_surface_t *read_png(const char *path)
{
    cairo_surface_t *image = cairo_image_surface_create_from_png(path);
    assert_int_equal(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
    return image;
}

/* ---- Tests ------------------------------------------------------------- */

static void test_two_pieces_two_colours(void **state)
{
    fixture *f = *state;
    ur_net_list nets;
    two_pieces(&nets);
    char path[128];
    path_in(f->dir, "guide.png", path, sizeof path);
    ur_error error;
    ur_assembly_options options = {.title = "cube"};
    assert_int_equal(ur_assembly_write(&nets, path, &options, &error), UR_OK);
    cairo_surface_t *image = read_png(path);
    int width = cairo_image_surface_get_width(image),
        height = cairo_image_surface_get_height(image);
    assert_true(width > 1000 && height > 1000);
    hues all, below_left, below_right;
    cluster everywhere[MOST_CLUSTERS], left[MOST_CLUSTERS], right[MOST_CLUSTERS];
    count_hues(image, 0, 0, width, height, &all);
    assert_int_equal(hue_clusters(&all, 200, everywhere), 2);
    assert_false(same_hue(everywhere[0].hue, everywhere[1].hue, 30));
    /* P1 is the colour seen most. */
    const cluster *p1 =
        everywhere[0].pixels > everywhere[1].pixels ? &everywhere[0] : &everywhere[1];
    /*
     * The lower 45 % holds the lower two views.  From front left below only
     * the faces toward -x, -y and -z are in sight, all P1's; from back right
     * below those toward +x (P1), +y and -z (P2).
     */
    int top = height * 55 / 100;
    count_hues(image, 0, top, width / 2, height, &below_left);
    count_hues(image, width / 2, top, width, height, &below_right);
    assert_true(below_left.coloured > 10000);
    assert_int_equal(hue_clusters(&below_left, 200, left), 1);
    assert_true(same_hue(left[0].hue, p1->hue, 3));
    assert_int_equal(hue_clusters(&below_right, 200, right), 2);
    cairo_surface_destroy(image);
    ur_net_list_free(&nets);
}

static void test_pdf(void **state)
{
    fixture *f = *state;
    ur_net_list nets;
    two_pieces(&nets);
    char path[128];
    path_in(f->dir, "guide.PDF", path, sizeof path);
    ur_error error;
    assert_int_equal(ur_assembly_write(&nets, path, NULL, &error), UR_OK);
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    char head[5] = {0};
    assert_int_equal(fread(head, 1, 4, file), 4);
    fclose(file);
    assert_string_equal(head, "%PDF");
    ur_net_list_free(&nets);
}

/* An open surface: both sides may show; one piece, one hue. */
static void test_open_surface(void **state)
{
    fixture *f = *state;
    const ur_vec3 vertices[] = {{0, 0, 0}, {50, 0, 0}, {50, 30, 10}, {0, 30, 10}};
    const size_t triangles[][3] = {{0, 1, 2}, {0, 2, 3}};
    ur_mesh mesh;
    ur_error error;
    assert_int_equal(ur_mesh_new(vertices, 4, triangles, 2, NULL, &mesh, &error), UR_OK);
    ur_net_list nets = {calloc(1, sizeof(ur_net)), 1};
    assert_non_null(nets.nets);
    assert_int_equal(ur_net_set_faces(&nets.nets[0], &mesh, NULL, 2, &error), UR_OK);
    char path[128];
    path_in(f->dir, "open.png", path, sizeof path);
    assert_int_equal(ur_assembly_write(&nets, path, NULL, &error), UR_OK);
    cairo_surface_t *image = read_png(path);
    hues all;
    cluster found[MOST_CLUSTERS];
    count_hues(image, 0, 0, cairo_image_surface_get_width(image),
               cairo_image_surface_get_height(image), &all);
    assert_int_equal(hue_clusters(&all, 200, found), 1);
    cairo_surface_destroy(image);
    ur_net_list_free(&nets);
    ur_mesh_free(&mesh);
}

static void test_refusals(void **state)
{
    fixture *f = *state;
    ur_net_list nets;
    two_pieces(&nets);
    char path[128];
    ur_error error;
    path_in(f->dir, "guide.svg", path, sizeof path);
    assert_int_equal(ur_assembly_write(&nets, path, NULL, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, ".png or a .pdf"));
    /* Nets without faces, as a development's: nothing to draw. */
    ur_net_list bare = {calloc(1, sizeof(ur_net)), 1};
    assert_non_null(bare.nets);
    path_in(f->dir, "bare.png", path, sizeof path);
    assert_int_equal(ur_assembly_write(&bare, path, NULL, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "only for meshes"));
    path_in(f->dir, "missing/guide.png", path, sizeof path);
    assert_int_equal(ur_assembly_write(&nets, path, NULL, &error), UR_ERROR_IO);
    assert_int_equal(each_entry(f->dir, NULL), 0); /* nothing written, nothing left behind */
    ur_net_list_free(&bare);
    ur_net_list_free(&nets);
}

/* A flattened piece's net carries its triangles in 3D, corner for corner. */
static void test_flat_net_has_faces(void **state)
{
    (void)state;
    const ur_vec3 vertices[] = {{0, 0, 0}, {30, 0, 0}, {30, 20, 5}, {0, 20, 5}, {15, 10, 9}};
    const size_t triangles[][3] = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    ur_mesh mesh;
    ur_error error;
    assert_int_equal(ur_mesh_new(vertices, 5, triangles, 4, NULL, &mesh, &error), UR_OK);
    ur_flat_piece flat;
    assert_int_equal(ur_flatten(&mesh, NULL, &flat, &error), UR_OK);
    ur_net net;
    assert_int_equal(ur_net_from_flat(&mesh, &flat, "P1", &net, &error), UR_OK);
    assert_int_equal(net.face_count, 4);
    for (size_t t = 0; t < 4; t++)
        for (int k = 0; k < 3; k++)
            assert_true(ur_vec3_distance(net.faces_3d[t][k], vertices[triangles[t][k]]) == 0);
    ur_net_free(&net);
    ur_flat_piece_free(&flat);
    ur_mesh_free(&mesh);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_two_pieces_two_colours, setup, teardown),
        cmocka_unit_test_setup_teardown(test_pdf, setup, teardown),
        cmocka_unit_test_setup_teardown(test_open_surface, setup, teardown),
        cmocka_unit_test_setup_teardown(test_refusals, setup, teardown),
        cmocka_unit_test(test_flat_net_has_faces),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
