/*
 * test_label.c: engraved labels: the strokes of text at a cap height, and
 * placing them on pieces: inside the outline and clear of it, moved in from
 * an edge, never upside down, off a score line and out of a hole, refused
 * when there is no room, with the piece then unchanged.
 */
#include "test_support.h"

#include <stdlib.h>

#include "unroll/allow.h"

/* ---- Helpers ---------------------------------------------------------------- */

static int open_font(void **state)
{
    ur_font *font;
    ur_error error;
    if (ur_font_open(NULL, &font, &error) != UR_OK) {
        fprintf(stderr, "%s\n", error.message);
        return -1;
    }
    *state = font;
    return 0;
}

static int close_font(void **state)
{
    ur_font_close(*state);
    return 0;
}

/* A piece whose outline is the counter-clockwise rectangle [0, w] x [0, h]. */
static ur_piece rectangle(double w, double h)
{
    ur_piece piece;
    memset(&piece, 0, sizeof piece);
    snprintf(piece.name, sizeof piece.name, "test");
    ur_vec2 ring[4] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
    assert_int_equal(ur_piece_add_path(&piece, UR_OP_CUT, ring, 4, true, NULL), UR_OK);
    return piece;
}

static bool inside(const ur_vec2 *ring, size_t n, ur_vec2 p)
{
    bool in = false;
    for (size_t i = 0, j = n - 1; i < n; j = i++)
        if ((ring[i].y > p.y) != (ring[j].y > p.y) &&
            p.x < ring[i].x + (p.y - ring[i].y) * (ring[j].x - ring[i].x) / (ring[j].y - ring[i].y))
            in = !in;
    return in;
}

static double segment_distance(ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d)
{
    return ur_segment_distance(ur_vec3_make(a.x, a.y, 0), ur_vec3_make(b.x, b.y, 0),
                               ur_vec3_make(c.x, c.y, 0), ur_vec3_make(d.x, d.y, 0));
}

/* The least distance between the segments of two paths (a closed one back to its start). */
static double path_distance(const ur_path *p, const ur_path *q)
{
    double least = INFINITY;
    size_t pn = p->count > 1 ? p->count - !p->closed : 1;
    size_t qn = q->count > 1 ? q->count - !q->closed : 1;
    for (size_t i = 0; i < pn; i++)
        for (size_t k = 0; k < qn; k++)
            least = fmin(least, segment_distance(p->points[i], p->points[(i + 1) % p->count],
                                                 q->points[k], q->points[(k + 1) % q->count]));
    return least;
}

/*
 * Every path from `first` on is an open ENGRAVE path inside the outline,
 * at least clearance from every path before `first`; and out of the ring
 * of path `hole` unless that is 0.
 */
static void assert_clear(const ur_piece *piece, size_t first, double clearance, size_t hole)
{
    const ur_path *outline = &piece->paths[0];
    assert_true(piece->path_count > first);
    for (size_t i = first; i < piece->path_count; i++) {
        const ur_path *path = &piece->paths[i];
        assert_int_equal(path->op, UR_OP_ENGRAVE);
        assert_false(path->closed);
        assert_true(path->count >= 2);
        for (size_t k = 0; k < path->count; k++) {
            assert_true(inside(outline->points, outline->count, path->points[k]));
            if (hole)
                assert_false(
                    inside(piece->paths[hole].points, piece->paths[hole].count, path->points[k]));
        }
        for (size_t j = 0; j < first; j++) {
            double d = path_distance(path, &piece->paths[j]);
            if (d < clearance)
                fail_msg("stroke %zu is %g mm from path %zu, under the clearance %g", i, d, j,
                         clearance);
        }
    }
}

/* The centre of the box of the paths from first on. */
static ur_vec2 centre_of(const ur_piece *piece, size_t first)
{
    ur_box box = ur_box_empty();
    for (size_t i = first; i < piece->path_count; i++)
        for (size_t k = 0; k < piece->paths[i].count; k++)
            ur_box_add(&box, piece->paths[i].points[k]);
    return ur_vec2_make(0.5 * (box.min.x + box.max.x), 0.5 * (box.min.y + box.max.y));
}

/* ---- Text ------------------------------------------------------------------------ */

static void test_strokes_of_h(void **state)
{
    ur_font *font = *state;
    ur_path *paths;
    size_t count;
    double width;
    ur_error error;
    assert_int_equal(ur_text_strokes(font, "H", 7.5, &paths, &count, &width, &error), UR_OK);
    assert_int_equal(count, 3);
    ur_box box = ur_box_empty();
    for (size_t i = 0; i < count; i++)
        for (size_t k = 0; k < paths[i].count; k++)
            ur_box_add(&box, paths[i].points[k]);
    assert_float_equal(ur_box_height(box), 7.5, 1e-9);
    assert_float_equal(box.min.y, 0, 1e-9);
    assert_true(box.min.x >= 0 && box.max.x <= width);
    assert_true(width > 0);
    ur_paths_free(paths, count);
}

static void test_strokes_of_a7(void **state)
{
    ur_font *font = *state;
    ur_path *paths;
    size_t count;
    double width, before = 0;
    const char *texts[] = {"A7", "A7B", "A7BC", "A7BC 12"};
    for (size_t t = 0; t < 4; t++) {
        assert_int_equal(ur_text_strokes(font, texts[t], 4, &paths, &count, &width, NULL), UR_OK);
        if (t == 0) {
            assert_true(count >= 4);
            for (size_t i = 0; i < count; i++) {
                assert_int_equal(paths[i].op, UR_OP_ENGRAVE);
                assert_false(paths[i].closed);
                assert_true(paths[i].count >= 2);
            }
        }
        assert_true(width > before);
        before = width;
        ur_paths_free(paths, count);
    }
}

static void test_strokes_refused(void **state)
{
    ur_font *font = *state;
    ur_path *paths;
    size_t count;
    double width;
    ur_error error;
    assert_int_equal(ur_text_strokes(font, "A\x01", 4, &paths, &count, &width, &error),
                     UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "character 2"));
    assert_int_equal(ur_text_strokes(font, "caf\xc3\xa9", 4, &paths, &count, &width, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_text_strokes(font, "A", 0, &paths, &count, &width, &error), UR_ERROR_INPUT);
    assert_int_equal(ur_text_strokes(font, NULL, 4, &paths, &count, &width, &error),
                     UR_ERROR_INPUT);
    assert_null(paths);
    assert_int_equal(count, 0);
}

static void test_unknown_font(void **state)
{
    (void)state;
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open("nosuchfont", &font, &error), UR_ERROR_INPUT);
    assert_null(font);
    assert_non_null(strstr(error.message, "nosuchfont"));
    assert_non_null(strstr(error.message, "hershey-fonts-data"));
    assert_int_equal(ur_font_open("../rowmans", &font, &error), UR_ERROR_INPUT);
    assert_int_equal(ur_font_open("futural", &font, &error), UR_OK);
    ur_font_close(font);
}

/* ---- Placing labels ------------------------------------------------------------------- */

static void test_label_at_centre(void **state)
{
    ur_font *font = *state;
    ur_piece piece = rectangle(100, 50);
    bool placed;
    ur_error error;
    assert_int_equal(ur_piece_add_label(&piece, font, "A7", ur_vec2_make(50, 25),
                                        ur_vec2_make(1, 0), 6, 3, 1, &placed, &error),
                     UR_OK);
    assert_true(placed);
    assert_clear(&piece, 1, 1, 0);
    ur_vec2 centre = centre_of(&piece, 1);
    assert_float_equal(centre.x, 50, 1e-9);
    assert_float_equal(centre.y, 25, 1e-9);
    assert_int_equal(piece.record_count, 1);
    const ur_allowance_record *record = &piece.records[0];
    assert_int_equal(record->kind, UR_ALLOWANCE_LABEL);
    assert_int_equal(record->count, 1);
    assert_float_equal(record->value, 6, 1e-12);
    assert_true(isnan(record->limit));
    assert_false(record->warning);
    assert_string_equal(record->reason, "label 'A7' 6 mm high");
    /* The text is 6 mm high: its tallest glyph spans the cap height. */
    ur_box box = ur_box_empty();
    for (size_t i = 1; i < piece.path_count; i++)
        for (size_t k = 0; k < piece.paths[i].count; k++)
            ur_box_add(&box, piece.paths[i].points[k]);
    assert_float_equal(ur_box_height(box), 6, 1e-9);
    /* Upright: the first stroke of 'A' runs down from its apex, on the left of the '7'. */
    assert_float_equal(piece.paths[1].points[0].y, box.max.y, 1e-9);
    assert_float_equal(piece.paths[1].points[1].y, box.min.y, 1e-9);
    assert_true(piece.paths[1].points[0].x < piece.paths[piece.path_count - 1].points[0].x);
    ur_piece_free(&piece);
}

static void test_label_moved_in_from_edges(void **state)
{
    ur_font *font = *state;
    const ur_vec2 nears[] = {{50, 0.5}, {50, 50}, {0, 25}, {1, 1}, {99, 49}};
    for (size_t n = 0; n < sizeof nears / sizeof nears[0]; n++) {
        ur_piece piece = rectangle(100, 50);
        bool placed;
        assert_int_equal(ur_piece_add_label(&piece, font, "B12", nears[n], ur_vec2_make(1, 0), 5, 2,
                                            1.5, &placed, NULL),
                         UR_OK);
        assert_true(placed);
        assert_clear(&piece, 1, 1.5, 0);
        /* Full height still fits, just in from the edge. */
        assert_float_equal(piece.records[0].value, 5, 1e-12);
        assert_true(ur_vec2_distance(centre_of(&piece, 1), nears[n]) < 20);
        ur_piece_free(&piece);
    }
}

static void test_label_never_upside_down(void **state)
{
    ur_font *font = *state;
    const ur_vec2 directions[] = {{-1, 0}, {-1, -0.2}, {0, -1}};
    for (size_t d = 0; d < 3; d++) {
        ur_piece piece = rectangle(100, 50);
        bool placed;
        assert_int_equal(ur_piece_add_label(&piece, font, "A7", ur_vec2_make(50, 25), directions[d],
                                            6, 3, 1, &placed, NULL),
                         UR_OK);
        assert_true(placed);
        assert_clear(&piece, 1, 1, 0);
        /* The first glyph's first point comes before the last's along the reading direction. */
        ur_vec2 first = piece.paths[1].points[0];
        ur_vec2 last = piece.paths[piece.path_count - 1].points[0];
        if (d < 2)
            assert_true(first.x < last.x);
        else
            assert_true(first.y < last.y); /* straight down turns to read upward */
        ur_piece_free(&piece);
    }
}

static void test_label_turned(void **state)
{
    ur_font *font = *state;
    ur_piece piece = rectangle(100, 50);
    bool placed;
    assert_int_equal(ur_piece_add_label(&piece, font, "SEAM 3", ur_vec2_make(20, 10),
                                        ur_vec2_make(1, 1), 5, 2, 1, &placed, NULL),
                     UR_OK);
    assert_true(placed);
    assert_clear(&piece, 1, 1, 0);
    ur_piece_free(&piece);
}

static void test_label_shrinks(void **state)
{
    ur_font *font = *state;
    /* 12 mm high with 1 mm clearance all round leaves room for less than 10 mm. */
    ur_piece piece = rectangle(100, 12);
    bool placed;
    assert_int_equal(ur_piece_add_label(&piece, font, "A7", ur_vec2_make(50, 6), ur_vec2_make(1, 0),
                                        20, 4, 1, &placed, NULL),
                     UR_OK);
    assert_true(placed);
    assert_clear(&piece, 1, 1, 0);
    assert_true(piece.records[0].value < 10 && piece.records[0].value >= 4);
    ur_piece_free(&piece);
}

static void test_no_room(void **state)
{
    ur_font *font = *state;
    ur_piece piece = rectangle(5, 5);
    ur_box box = piece.box;
    bool placed = true;
    assert_int_equal(ur_piece_add_label(&piece, font, "A7", ur_vec2_make(2.5, 2.5),
                                        ur_vec2_make(1, 0), 4, 3, 0.5, &placed, NULL),
                     UR_OK);
    assert_false(placed);
    assert_int_equal(piece.path_count, 1);
    assert_int_equal(piece.record_count, 0);
    assert_memory_equal(&piece.box, &box, sizeof box);
    ur_piece_free(&piece);
}

static void test_label_off_score(void **state)
{
    ur_font *font = *state;
    ur_piece piece = rectangle(100, 50);
    ur_vec2 score[2] = {{0, 25}, {100, 25}};
    assert_int_equal(ur_piece_add_path(&piece, UR_OP_SCORE, score, 2, false, NULL), UR_OK);
    bool placed;
    assert_int_equal(ur_piece_add_label(&piece, font, "A7", ur_vec2_make(50, 25),
                                        ur_vec2_make(1, 0), 8, 3, 1.2, &placed, NULL),
                     UR_OK);
    assert_true(placed);
    assert_clear(&piece, 2, 1.2, 0);
    /* A second label keeps clear of the first too. */
    size_t first = piece.path_count;
    assert_int_equal(ur_piece_add_label(&piece, font, "B8", ur_vec2_make(50, 25),
                                        ur_vec2_make(1, 0), 8, 3, 1.2, &placed, NULL),
                     UR_OK);
    assert_true(placed);
    assert_clear(&piece, first, 1.2, 0);
    assert_int_equal(piece.record_count, 2);
    ur_piece_free(&piece);
}

static void test_label_out_of_hole(void **state)
{
    ur_font *font = *state;
    ur_piece piece = rectangle(100, 50);
    ur_vec2 hole[4] = {{30, 10}, {30, 40}, {70, 40}, {70, 10}}; /* clockwise, as holes go */
    assert_int_equal(ur_piece_add_path(&piece, UR_OP_CUT, hole, 4, true, NULL), UR_OK);
    bool placed;
    assert_int_equal(ur_piece_add_label(&piece, font, "A7", ur_vec2_make(50, 25),
                                        ur_vec2_make(1, 0), 6, 3, 1, &placed, NULL),
                     UR_OK);
    assert_true(placed);
    assert_clear(&piece, 2, 1, 1);
    ur_piece_free(&piece);
}

/* Adds the ring as a closed CUT path, each side cut into steps of 2 mm (as a curve's would be). */
static void add_fine_ring(ur_piece *piece, const ur_vec2 *corners, size_t count)
{
    ur_vec2 points[1024];
    size_t n = 0;
    for (size_t i = 0; i < count; i++) {
        ur_vec2 a = corners[i], b = corners[(i + 1) % count];
        size_t steps = (size_t)ceil(ur_vec2_length(ur_vec2_sub(b, a)) / 2);
        for (size_t k = 0; k < steps; k++) {
            assert_true(n < 1024);
            points[n++] = ur_vec2_add_scaled(a, ur_vec2_sub(b, a), (double)k / (double)steps);
        }
    }
    assert_int_equal(ur_piece_add_path(piece, UR_OP_CUT, points, n, true, NULL), UR_OK);
}

/*
 * A U-shaped piece with a rectangular hole in its base: the label asked
 * for in the notch (off the piece) or in the hole finds its room on the
 * material around them, far from where it was asked; a label too tall for
 * any arm finds none.  Most candidates on the way lie in the notch, the
 * hole or beyond the outline, where no wall is near.
 */
static void test_label_far_from_notch_and_hole(void **state)
{
    ur_font *font = *state;
    ur_vec2 u[8] = {{0, 0},    {120, 0}, {120, 120}, {100, 120},
                    {100, 60}, {20, 60}, {20, 120},  {0, 120}};
    ur_vec2 hole[4] = {{20, 10}, {20, 50}, {100, 50}, {100, 10}}; /* clockwise, as holes go */
    ur_vec2 asked[2] = {{60, 100}, {60, 30}};                     /* in the notch, in the hole */
    for (int k = 0; k < 2; k++) {
        ur_piece piece;
        memset(&piece, 0, sizeof piece);
        snprintf(piece.name, sizeof piece.name, "test");
        add_fine_ring(&piece, u, 8);
        add_fine_ring(&piece, hole, 4);
        bool placed;
        assert_int_equal(ur_piece_add_label(&piece, font, "A7", asked[k], ur_vec2_make(1, 0), 8, 6,
                                            1, &placed, NULL),
                         UR_OK);
        assert_true(placed);
        assert_clear(&piece, 2, 1, 1);
        /* The arms and the strips round the hole are 10 to 20 mm wide: no room for 30 mm text. */
        assert_int_equal(ur_piece_add_label(&piece, font, "A7", asked[k], ur_vec2_make(1, 0), 40,
                                            30, 1, &placed, NULL),
                         UR_OK);
        assert_false(placed);
        ur_piece_free(&piece);
    }
}

static void test_many_labels_on_a_fine_outline(void **state)
{
    ur_font *font = *state;
    enum { POINTS = 4000, LABELS = 100 };
    ur_piece piece;
    memset(&piece, 0, sizeof piece);
    ur_vec2 *ring = malloc(POINTS * sizeof *ring);
    assert_non_null(ring);
    for (size_t i = 0; i < POINTS; i++) {
        double angle = 2 * M_PI * (double)i / POINTS;
        ring[i] = ur_vec2_make(300 * cos(angle), 150 * sin(angle));
    }
    assert_int_equal(ur_piece_add_path(&piece, UR_OP_CUT, ring, POINTS, true, NULL), UR_OK);
    free(ring);
    size_t placed_count = 0;
    for (size_t i = 0; i < LABELS; i++) {
        double angle = 2 * M_PI * (double)i / LABELS;
        ur_vec2 near = ur_vec2_make(300 * cos(angle), 150 * sin(angle));
        ur_vec2 along = ur_vec2_make(-300 * sin(angle), 150 * cos(angle)); /* the tangent */
        char text[8];
        snprintf(text, sizeof text, "S%zu", i);
        bool placed;
        assert_int_equal(
            ur_piece_add_label(&piece, font, text, near, along, 5, 3, 1, &placed, NULL), UR_OK);
        placed_count += placed;
    }
    assert_int_equal(placed_count, LABELS);
    assert_int_equal(piece.record_count, LABELS);
    for (size_t i = 0; i < piece.record_count; i++)
        assert_true(inside(piece.paths[0].points, piece.paths[0].count, piece.records[i].where));
    ur_piece_free(&piece);
}

static void test_bad_arguments(void **state)
{
    ur_font *font = *state;
    ur_piece piece = rectangle(100, 50);
    ur_vec2 c = {50, 25}, x = {1, 0};
    bool placed;
    ur_error error;
    assert_int_equal(ur_piece_add_label(&piece, font, NULL, c, x, 5, 3, 1, &placed, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_piece_add_label(&piece, font, "", c, x, 5, 3, 1, &placed, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_piece_add_label(&piece, font, "A", c, x, 0, 0, 1, &placed, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_piece_add_label(&piece, font, "A", c, x, -2, -3, 1, &placed, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_piece_add_label(&piece, font, "A", c, x, 3, 5, 1, &placed, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(
        ur_piece_add_label(&piece, font, "A", ur_vec2_make(NAN, 0), x, 5, 3, 1, &placed, &error),
        UR_ERROR_INPUT);
    assert_int_equal(
        ur_piece_add_label(&piece, font, "A", c, ur_vec2_make(0, 0), 5, 3, 1, &placed, &error),
        UR_ERROR_INPUT);
    assert_int_equal(ur_piece_add_label(&piece, font, "A", c, x, 5, 3, -1, &placed, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_piece_add_label(&piece, font, "A\n", c, x, 5, 3, 1, &placed, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(ur_piece_add_label(&piece, NULL, "A", c, x, 5, 3, 1, &placed, &error),
                     UR_ERROR_INPUT);
    assert_false(placed);
    assert_int_equal(piece.path_count, 1);
    assert_int_equal(piece.record_count, 0);
    ur_piece_free(&piece);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_strokes_of_h),
        cmocka_unit_test(test_strokes_of_a7),
        cmocka_unit_test(test_strokes_refused),
        cmocka_unit_test(test_unknown_font),
        cmocka_unit_test(test_label_at_centre),
        cmocka_unit_test(test_label_moved_in_from_edges),
        cmocka_unit_test(test_label_never_upside_down),
        cmocka_unit_test(test_label_turned),
        cmocka_unit_test(test_label_shrinks),
        cmocka_unit_test(test_no_room),
        cmocka_unit_test(test_label_off_score),
        cmocka_unit_test(test_label_out_of_hole),
        cmocka_unit_test(test_label_far_from_notch_and_hole),
        cmocka_unit_test(test_many_labels_on_a_fine_outline),
        cmocka_unit_test(test_bad_arguments),
    };
    return cmocka_run_group_tests(tests, open_font, close_font);
}
