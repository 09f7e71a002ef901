/*
 * test_kerf.c: kerf compensation and holding bridges, measured on the
 * geometry they leave.  A rectangle with a round hole grows and its hole
 * shrinks by exactly half the kerf, corners square; holes and slots the
 * kerf would close are refused by name; a slot whose mouth closes has the
 * room behind it cut as a hole.  Bridges are found again from the
 * open outline pieces (where each starts and ends along the original
 * outline): their number and width, their spacing, and their distance from
 * corners and tight fillets, worked out here independently.
 */
#include "test_support.h"

#include <stdlib.h>

#include "unroll/allow.h"

/*
 * actual within tolerance (absolute) of expected, in double: cmocka's
 * assert_float_equal works in float and casts only the first operand of an
 * expression.
 */
#define assert_close(actual, expected, tolerance)                                                  \
    do {                                                                                           \
        double a_ = (actual), e_ = (expected);                                                     \
        if (!(fabs(a_ - e_) <= (tolerance)))                                                       \
            fail_msg("%s = %.12g, expected %.12g within %g", #actual, a_, e_,                      \
                     (double)(tolerance));                                                         \
    } while (0)

/* ---- Building pieces ----------------------------------------------------- */

static ur_piece piece_named(const char *name)
{
    ur_piece piece;
    memset(&piece, 0, sizeof piece);
    snprintf(piece.name, sizeof piece.name, "%s", name);
    return piece;
}

static void add(ur_piece *piece, ur_op op, const ur_vec2 *points, size_t count, bool closed)
{
    assert_int_equal(ur_piece_add_path(piece, op, points, count, closed, NULL), UR_OK);
}

/* Counter-clockwise rectangle from (x, y), w by h. */
static void rectangle(ur_vec2 *p, double x, double y, double w, double h)
{
    p[0] = ur_vec2_make(x, y);
    p[1] = ur_vec2_make(x + w, y);
    p[2] = ur_vec2_make(x + w, y + h);
    p[3] = ur_vec2_make(x, y + h);
}

/*
 * A regular n-gon about centre whose apothem (centre to each side) is
 * `apothem`: vertices at apothem / cos(pi / n).  clockwise as a hole may be.
 */
static void regular(ur_vec2 *p, size_t n, ur_vec2 centre, double apothem, bool clockwise)
{
    double radius = apothem / cos(M_PI / (double)n);
    for (size_t k = 0; k < n; k++) {
        double angle = 2 * M_PI * (double)k / (double)n * (clockwise ? -1 : 1);
        p[k] = ur_vec2_make(centre.x + radius * cos(angle), centre.y + radius * sin(angle));
    }
}

/* ---- Measuring ------------------------------------------------------------ */

static double shoelace(const ur_vec2 *p, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += p[i].x * p[(i + 1) % n].y - p[(i + 1) % n].x * p[i].y;
    return sum / 2;
}

/* Interior angle at vertex i of a counter-clockwise ring, degrees. */
static double interior_angle(const ur_vec2 *p, size_t n, size_t i)
{
    ur_vec2 a = p[(i + n - 1) % n], b = p[i], c = p[(i + 1) % n];
    double ux = a.x - b.x, uy = a.y - b.y, vx = c.x - b.x, vy = c.y - b.y;
    return atan2(fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / M_PI;
}

/* Distance from p to the infinite line through a and b. */
static double line_distance(ur_vec2 p, ur_vec2 a, ur_vec2 b)
{
    double dx = b.x - a.x, dy = b.y - a.y;
    return fabs(dx * (p.y - a.y) - dy * (p.x - a.x)) / hypot(dx, dy);
}

static double perimeter(const ur_vec2 *p, size_t n, bool closed)
{
    double sum = 0;
    for (size_t i = 0; i + 1 < n + (closed ? 1 : 0); i++)
        sum += hypot(p[(i + 1) % n].x - p[i].x, p[(i + 1) % n].y - p[i].y);
    return sum;
}

/* Arc length along the closed ring from its first point to q, which must lie on it. */
static double arc_at(const ur_vec2 *ring, size_t n, ur_vec2 q)
{
    double at = 0;
    for (size_t i = 0; i < n; i++) {
        ur_vec2 a = ring[i], b = ring[(i + 1) % n];
        double dx = b.x - a.x, dy = b.y - a.y, length = hypot(dx, dy);
        double along = ((q.x - a.x) * dx + (q.y - a.y) * dy) / length;
        if (along >= -1e-9 && along <= length + 1e-9 && line_distance(q, a, b) < 1e-9)
            return at + along;
        at += length;
    }
    fail_msg("point (%g, %g) is not on the outline", q.x, q.y);
    return 0;
}

static double wrap(double t, double length)
{
    return t - floor(t / length) * length;
}

enum { MAX_GAPS = 64 };

/* The gaps an open outline leaves, as arc lengths along the original ring. */
typedef struct gaps {
    size_t count;
    double start[MAX_GAPS], width[MAX_GAPS], centre[MAX_GAPS];
    double cut; /* length of outline still cut */
} gaps;

static int compare_doubles(const void *a, const void *b)
{
    double x = ((const double *)a)[0], y = ((const double *)b)[0];
    return (x > y) - (x < y);
}

static gaps find_gaps(const ur_piece *piece, const ur_vec2 *ring, size_t n)
{
    double length = perimeter(ring, n, true);
    double ends[MAX_GAPS][2]; /* start and end of each cut stretch, sorted by start */
    gaps g = {0};
    for (size_t i = 0; i < piece->path_count; i++) {
        const ur_path *path = &piece->paths[i];
        if (path->op != UR_OP_CUT || path->closed)
            continue;
        assert_true(g.count < MAX_GAPS);
        double from = arc_at(ring, n, path->points[0]);
        double to = arc_at(ring, n, path->points[path->count - 1]);
        double along = perimeter(path->points, path->count, false);
        /* Every vertex of the ring between its ends is in the stretch. */
        assert_relative(along, wrap(to - from, length), 1e-12);
        for (size_t k = 1; k + 1 < path->count; k++)
            arc_at(ring, n, path->points[k]);
        ends[g.count][0] = from;
        ends[g.count][1] = to;
        g.cut += along;
        g.count++;
    }
    qsort(ends, g.count, sizeof ends[0], compare_doubles);
    for (size_t k = 0; k < g.count; k++) {
        double next = ends[(k + 1) % g.count][0];
        g.start[k] = ends[k][1];
        g.width[k] = wrap(next - ends[k][1], length);
        g.centre[k] = wrap(g.start[k] + g.width[k] / 2, length);
    }
    qsort(g.centre, g.count, sizeof g.centre[0], compare_doubles);
    return g;
}

/* Distance along a ring of that length between the span [a, a + w] and the span [c, d]. */
static double span_distance(double a, double w, double c, double d, double length)
{
    double best = INFINITY;
    for (int m = -1; m <= 1; m++) {
        double lo = a + m * length, hi = lo + w;
        double gap = hi < c ? c - hi : lo > d ? lo - d : 0;
        if (gap < best)
            best = gap;
    }
    return best;
}

/* Every gap at least its width from every vertex turning more than 30 degrees. */
static void assert_clear_of_corners(const gaps *g, const ur_vec2 *ring, size_t n)
{
    double length = perimeter(ring, n, true), at = 0;
    for (size_t i = 0; i < n; i++) {
        if (i > 0)
            at += hypot(ring[i].x - ring[i - 1].x, ring[i].y - ring[i - 1].y);
        if (180 - interior_angle(ring, n, i) <= 30)
            continue;
        for (size_t k = 0; k < g->count; k++)
            assert_true(span_distance(g->start[k], g->width[k], wrap(at, length), wrap(at, length),
                                      length) >= g->width[k] - 1e-9);
    }
}

static const ur_allowance_record *last_record(const ur_piece *piece)
{
    assert_true(piece->record_count > 0);
    return &piece->records[piece->record_count - 1];
}

/* ---- Kerf compensation ----------------------------------------------------- */

enum { HOLE_SIDES = 64 };

static void test_kerf_rectangle_with_hole(void **state)
{
    (void)state;
    ur_piece piece = piece_named("plate");
    ur_vec2 outline[4], hole[HOLE_SIDES], score[2] = {{10, 5}, {90, 5}};
    rectangle(outline, 0, 0, 100, 50);
    regular(hole, HOLE_SIDES, ur_vec2_make(30, 25), 10, true);
    add(&piece, UR_OP_CUT, outline, 4, true);
    add(&piece, UR_OP_SCORE, score, 2, false);
    add(&piece, UR_OP_CUT, hole, HOLE_SIDES, true);
    add(&piece, UR_OP_ENGRAVE, hole, 8, false); /* open: not a hole, left alone */

    ur_error error;
    assert_int_equal(ur_piece_compensate_kerf(&piece, 0.2, &error), UR_OK);
    assert_int_equal(piece.path_count, 4);

    /* The outline: 0.1 mm out all round, four square corners, counter-clockwise. */
    const ur_path *out = &piece.paths[0];
    assert_true(out->closed);
    assert_int_equal(out->op, UR_OP_CUT);
    assert_int_equal(out->count, 4);
    ur_box box = ur_box_of_points(out->points, out->count);
    assert_relative(box.max.x - box.min.x, 100.2, 1e-12);
    assert_relative(box.max.y - box.min.y, 50.2, 1e-12);
    assert_close(box.min.x, -0.1, 1e-12);
    assert_close(box.min.y, -0.1, 1e-12);
    for (size_t i = 0; i < 4; i++)
        assert_close(interior_angle(out->points, 4, i), 90, 1e-9);
    assert_true(shoelace(out->points, 4) > 0);
    assert_relative(shoelace(out->points, 4), 100.2 * 50.2, 1e-12);

    /* The hole: every side 9.9 mm from the centre, 19.8 across flats, still clockwise. */
    const ur_path *in = &piece.paths[2];
    assert_true(in->closed);
    assert_int_equal(in->count, HOLE_SIDES);
    assert_true(shoelace(in->points, in->count) < 0);
    for (size_t i = 0; i < in->count; i++) {
        double apothem =
            line_distance(ur_vec2_make(30, 25), in->points[i], in->points[(i + 1) % in->count]);
        assert_close(2 * apothem, 19.8, 1e-6);
    }

    /* The score and the open engraving untouched. */
    assert_int_equal(piece.paths[1].count, 2);
    assert_memory_equal(piece.paths[1].points, score, sizeof score);
    assert_int_equal(piece.paths[3].count, 8);
    assert_memory_equal(piece.paths[3].points, hole, 8 * sizeof *hole);

    /* The box is the new outline's; one record says what was done. */
    assert_close(piece.box.min.x, -0.1, 1e-12);
    assert_close(piece.box.max.y, 50.1, 1e-12);
    assert_int_equal(piece.record_count, 1);
    const ur_allowance_record *record = last_record(&piece);
    assert_int_equal(record->kind, UR_ALLOWANCE_KERF_COMPENSATION);
    assert_close(record->value, 0.2, 0);
    assert_true(isnan(record->limit));
    assert_false(record->warning);
    assert_non_null(strstr(record->reason, "1 hole"));
    ur_piece_free(&piece);
}

/* A triangle's sharp corner stays a point: the mitre is not cut off. */
static void test_kerf_sharp_corner(void **state)
{
    (void)state;
    ur_piece piece = piece_named("wedge");
    /* A 30-degree tip at the origin. */
    ur_vec2 outline[3] = {{0, 0}, {100, 0}, {100, 100 * tan(M_PI / 6)}};
    add(&piece, UR_OP_CUT, outline, 3, true);
    assert_int_equal(ur_piece_compensate_kerf(&piece, 1, NULL), UR_OK);
    const ur_path *out = &piece.paths[0];
    assert_int_equal(out->count, 3);
    for (size_t i = 0; i < 3; i++) /* each side moved 0.5 mm out, parallel */
        for (size_t k = 0; k < 3; k++) {
            double d = line_distance(outline[k], out->points[i], out->points[(i + 1) % 3]);
            assert_true(d > 0.5 - 1e-9); /* the old corners all inside */
        }
    /* The tip moved out along its bisector by 0.5 / sin(15 degrees). */
    double tip = INFINITY;
    for (size_t i = 0; i < 3; i++)
        tip = fmin(tip, hypot(out->points[i].x, out->points[i].y));
    assert_relative(tip, 0.5 / sin(M_PI / 12), 1e-9);
    ur_piece_free(&piece);
}

static ur_piece plate_with_hole(ur_vec2 *hole, size_t n)
{
    ur_piece piece = piece_named("plate-7");
    ur_vec2 outline[4];
    rectangle(outline, 0, 0, 100, 50);
    add(&piece, UR_OP_CUT, outline, 4, true);
    add(&piece, UR_OP_CUT, hole, n, true);
    return piece;
}

static void assert_refused(ur_piece *piece, double kerf, const char *words)
{
    ur_error error;
    memset(&error, 0, sizeof error);
    size_t paths = piece->path_count, first = piece->paths[0].count;
    ur_vec2 corner = piece->paths[0].points[0];
    assert_int_equal(ur_piece_compensate_kerf(piece, kerf, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, piece->name));
    if (words && !strstr(error.message, words))
        fail_msg("'%s' does not say '%s'", error.message, words);
    /* Nothing was changed. */
    assert_int_equal(piece->path_count, paths);
    assert_int_equal(piece->paths[0].count, first);
    assert_close(piece->paths[0].points[0].x, corner.x, 0);
    assert_int_equal(piece->record_count, 0);
}

/*
 * A hole the kerf cannot move in (it would vanish or split) is cut as
 * drawn: the hole keeps its points, the outline (the 100 x 50 plate)
 * still moves out by half the kerf, and one warning, placed within 3 mm
 * of where the hole is, says it comes out wider; the piece's record counts
 * the outline alone as moved.
 */
static void assert_cut_as_drawn(ur_piece *piece, double kerf, ur_vec2 hole_middle)
{
    size_t count = piece->paths[1].count;
    ur_vec2 *hole = malloc(count * sizeof *hole);
    assert_non_null(hole);
    memcpy(hole, piece->paths[1].points, count * sizeof *hole);
    assert_int_equal(ur_piece_compensate_kerf(piece, kerf, NULL), UR_OK);
    assert_int_equal(piece->paths[1].count, count);
    assert_memory_equal(piece->paths[1].points, hole, count * sizeof *hole);
    free(hole);
    assert_close(fabs(ur_polygon_signed_area(piece->paths[0].points, piece->paths[0].count)),
                 (100 + kerf) * (50 + kerf), 1e-6);
    assert_int_equal(piece->record_count, 2);
    const ur_allowance_record *warning = &piece->records[0];
    assert_true(warning->warning);
    assert_int_equal(warning->count, 1);
    assert_non_null(strstr(warning->reason, "cut as drawn"));
    assert_true(ur_vec2_distance(warning->where, hole_middle) < 3);
    const ur_allowance_record *moved = &piece->records[1];
    assert_false(moved->warning);
    assert_int_equal(moved->count, 1);
    assert_null(strstr(moved->reason, "hole"));
}

static void test_kerf_cuts_vanishing_hole_as_drawn(void **state)
{
    (void)state;
    ur_vec2 hole[HOLE_SIDES];
    regular(hole, HOLE_SIDES, ur_vec2_make(50, 25), 0.05, false); /* 0.1 mm across */
    ur_piece piece = plate_with_hole(hole, HOLE_SIDES);
    assert_cut_as_drawn(&piece, 0.2, ur_vec2_make(50, 25));
    ur_piece_free(&piece);
}

static void test_kerf_narrow_features(void **state)
{
    (void)state;
    /* A dumbbell hole: two 5 mm squares joined by a 0.1 mm channel, split by a 0.2 kerf. */
    ur_vec2 dumbbell[] = {{20, 20}, {25, 20}, {25, 22.45}, {35, 22.45}, {35, 20}, {40, 20},
                          {40, 25}, {35, 25}, {35, 22.55}, {25, 22.55}, {25, 25}, {20, 25}};
    size_t corners = sizeof dumbbell / sizeof *dumbbell;
    ur_piece piece = plate_with_hole(dumbbell, corners);
    assert_cut_as_drawn(&piece, 0.2, ur_vec2_make(30, 22.5));
    ur_piece_free(&piece);
    /* A kerf narrower than the channel moves the hole in: 50 mm2 less 0.05 all round. */
    piece = plate_with_hole(dumbbell, corners);
    assert_int_equal(ur_piece_compensate_kerf(&piece, 0.05, NULL), UR_OK);
    assert_false(piece.records[0].warning);
    assert_int_equal(piece.records[0].count, 2);
    double area = fabs(ur_polygon_signed_area(piece.paths[1].points, piece.paths[1].count));
    assert_true(area > 49 && area < 50); /* 51 mm2 less about its 60 mm round by 0.025 */
    ur_piece_free(&piece);

    /*
     * A keyhole slot in the outline: a 0.1 mm channel to a 10 x 5 mm room.
     * At a 0.2 mm kerf the channel closes as the outline moves out; the
     * room behind it is cut as a hole, its sides moved in by 0.1 mm (9.8 x
     * 4.8 mm, clockwise against the outline), so that its sides are still
     * cut; the warning says where and that the mouth holds.  The outline is
     * the plate grown by 0.1 mm.
     */
    ur_vec2 keyhole[] = {{0, 0},   {100, 0}, {100, 50}, {50.05, 50}, {50.05, 30}, {55, 30},
                         {55, 25}, {45, 25}, {45, 30},  {49.95, 30}, {49.95, 50}, {0, 50}};
    ur_piece slot = piece_named("slotted");
    add(&slot, UR_OP_CUT, keyhole, sizeof keyhole / sizeof *keyhole, true);
    assert_int_equal(ur_piece_compensate_kerf(&slot, 0.2, NULL), UR_OK);
    assert_int_equal(slot.record_count, 2);
    const ur_allowance_record *warning = &slot.records[0];
    assert_true(warning->warning && warning->count == 1);
    assert_true(strstr(warning->reason, "mouth") != NULL);
    assert_close(warning->where.x, 50, 1e-9); /* the room, 45..55 across */
    assert_close(warning->where.y, 27.5, 1e-9);
    assert_close(ur_box_width(slot.box), 100.2, 1e-9);
    assert_close(ur_box_height(slot.box), 50.2, 1e-9);
    assert_close(fabs(ur_polygon_signed_area(slot.paths[0].points, slot.paths[0].count)),
                 100.2 * 50.2, 1e-6);
    assert_int_equal(slot.path_count, 2);
    const ur_path *room = &slot.paths[1];
    assert_true(room->op == UR_OP_CUT && room->closed);
    assert_close(ur_polygon_signed_area(room->points, room->count), -9.8 * 4.8, 1e-9);
    ur_box room_box = ur_box_of_points(room->points, room->count);
    assert_close(room_box.min.x, 45.1, 1e-9);
    assert_close(room_box.max.x, 54.9, 1e-9);
    assert_close(room_box.min.y, 25.1, 1e-9);
    assert_close(room_box.max.y, 29.9, 1e-9);
    ur_piece_free(&slot);

    /* A room less than a kerf square once its sides move in (0.05 x 0.05 mm) is filled. */
    ur_vec2 pinhole[] = {{0, 0},       {100, 0},     {100, 50},       {50.05, 50},
                         {50.05, 30},  {50.125, 30}, {50.125, 29.75}, {49.875, 29.75},
                         {49.875, 30}, {49.95, 30},  {49.95, 50},     {0, 50}};
    slot = piece_named("pinhole");
    add(&slot, UR_OP_CUT, pinhole, sizeof pinhole / sizeof *pinhole, true);
    assert_int_equal(ur_piece_compensate_kerf(&slot, 0.2, NULL), UR_OK);
    assert_int_equal(slot.path_count, 1);
    assert_true(slot.records[0].warning && strstr(slot.records[0].reason, "filled") != NULL);
    assert_close(fabs(ur_polygon_signed_area(slot.paths[0].points, slot.paths[0].count)),
                 100.2 * 50.2, 1e-6);
    ur_piece_free(&slot);
}

static void test_kerf_values(void **state)
{
    (void)state;
    ur_vec2 hole[HOLE_SIDES];
    regular(hole, HOLE_SIDES, ur_vec2_make(50, 25), 10, false);
    ur_piece piece = plate_with_hole(hole, HOLE_SIDES);
    assert_refused(&piece, NAN, "kerf");
    assert_refused(&piece, -0.1, "kerf");
    assert_refused(&piece, INFINITY, "kerf");
    /* No kerf: nothing to do, nothing recorded. */
    assert_int_equal(ur_piece_compensate_kerf(&piece, 0, NULL), UR_OK);
    assert_int_equal(piece.record_count, 0);
    assert_close(piece.paths[0].points[2].x, 100, 0);
    assert_memory_equal(piece.paths[1].points, hole, sizeof hole);
    ur_piece_free(&piece);
}

/* The piece compensated for a 0.1 mm kerf; its warning about narrow material, or NULL. */
static const ur_allowance_record *narrow_warning(ur_piece *piece)
{
    assert_int_equal(ur_piece_compensate_kerf(piece, 0.1, NULL), UR_OK);
    const ur_allowance_record *found = NULL;
    for (size_t k = 0; k < piece->record_count; k++)
        if (piece->records[k].warning && strstr(piece->records[k].reason, "narrower than the kerf"))
            found = &piece->records[k];
    return found;
}

static ur_piece outline_piece(const char *name, const ur_vec2 *points, size_t count)
{
    ur_piece piece = piece_named(name);
    add(&piece, UR_OP_CUT, points, count, true);
    return piece;
}

/*
 * Material narrower than the kerf, which the beam burns away, is found by
 * the opening of the outline by the kerf, and said with where it is: a
 * strip 0.05 mm wide (a unfolded gem's girdle) goes whole; two squares on
 * a 0.05 mm neck come apart; a 30 mm tail 0.05 mm wide is lost, 1.5 mm2
 * (1.5 % of the piece: over the 1 % from which narrow parts are sought).
 * A 5 degree point loses only its tip (about 0.05 mm2 at a 0.1 mm kerf)
 * and a plain rectangle nothing: no warning.
 */
static void test_kerf_finds_material_it_would_burn(void **state)
{
    (void)state;
    ur_vec2 strip[4];
    rectangle(strip, 0, 0, 20, 0.05);
    ur_piece piece = outline_piece("strip", strip, 4);
    const ur_allowance_record *w = narrow_warning(&piece);
    assert_non_null(w);
    assert_non_null(strstr(w->reason, "everywhere"));
    ur_piece_free(&piece);

    ur_vec2 dumbbell[] = {{0, 0},   {10, 0},  {10, 4.975}, {13, 4.975}, {13, 0},  {23, 0},
                          {23, 10}, {13, 10}, {13, 5.025}, {10, 5.025}, {10, 10}, {0, 10}};
    piece = outline_piece("dumbbell", dumbbell, sizeof dumbbell / sizeof *dumbbell);
    w = narrow_warning(&piece);
    assert_non_null(w);
    assert_non_null(strstr(w->reason, "leave it in 2 parts"));
    assert_close(w->where.x, 11.5, 0.1); /* the neck, 10 to 13 */
    assert_close(w->where.y, 5, 0.1);
    ur_piece_free(&piece);

    ur_vec2 tailed[] = {{0, 0},      {10, 0},     {10, 4.975}, {40, 4.975},
                        {40, 5.025}, {10, 5.025}, {10, 10},    {0, 10}};
    piece = outline_piece("tailed", tailed, sizeof tailed / sizeof *tailed);
    w = narrow_warning(&piece);
    assert_non_null(w);
    assert_non_null(strstr(w->reason, "burn that away"));
    assert_close(w->where.x, 25, 0.1);
    double lost = 0;
    assert_int_equal(sscanf(w->reason, "%lf mm2", &lost), 1);
    assert_close(lost, 30 * 0.05, 0.02); /* the tail, less the bit the opening keeps at its root */
    ur_piece_free(&piece);

    double half = 2.5 * M_PI / 180; /* a 5 degree point 50 mm long */
    ur_vec2 point[] = {{0, 0}, {50 * cos(half), -50 * sin(half)}, {50 * cos(half), 50 * sin(half)}};
    piece = outline_piece("point", point, 3);
    assert_null(narrow_warning(&piece));
    ur_piece_free(&piece);
    ur_vec2 plain[4];
    rectangle(plain, 0, 0, 30, 20);
    piece = outline_piece("plain", plain, 4);
    assert_null(narrow_warning(&piece));
    ur_piece_free(&piece);
}

/* ---- Bridges ----------------------------------------------------------------- */

static void assert_even(const gaps *g, double length)
{
    for (size_t k = 0; k < g->count; k++) {
        double next = g->centre[(k + 1) % g->count] + (k + 1 == g->count ? length : 0);
        assert_close(next - g->centre[k], length / (double)g->count, 1e-9);
    }
}

static void assert_widths(const gaps *g, double width, double length)
{
    for (size_t k = 0; k < g->count; k++)
        assert_close(g->width[k], width, 1e-9);
    assert_close(length - g->cut, (double)g->count * width, 1e-9);
}

static void test_bridges_rectangle(void **state)
{
    (void)state;
    ur_piece piece = piece_named("panel");
    ur_vec2 outline[4], score[2] = {{10, 5}, {90, 5}};
    rectangle(outline, 0, 0, 100, 50);
    add(&piece, UR_OP_CUT, outline, 4, true);
    add(&piece, UR_OP_SCORE, score, 2, false);
    assert_int_equal(ur_piece_add_bridges(&piece, 4, 2, false, NULL), UR_OK);

    assert_true(piece.bridged);
    assert_int_equal(piece.path_count, 2 + 3); /* the score stays second, 3 stretches appended */
    assert_int_equal(piece.paths[1].op, UR_OP_SCORE);
    assert_false(piece.paths[0].closed);
    gaps g = find_gaps(&piece, outline, 4);
    assert_int_equal(g.count, 4);
    assert_widths(&g, 2, 300);
    assert_even(&g, 300);
    assert_clear_of_corners(&g, outline, 4);
    /* A perimeter of 300 shared by 4 lands one gap in the middle of each side. */
    double middles[4] = {50, 125, 200, 275};
    for (size_t k = 0; k < 4; k++)
        assert_close(g.centre[k], middles[k], 1e-9);

    const ur_allowance_record *record = last_record(&piece);
    assert_int_equal(record->kind, UR_ALLOWANCE_BRIDGES);
    assert_int_equal(record->count, 4);
    assert_close(record->value, 2, 0);
    assert_false(record->warning);

    /* Once is enough. */
    ur_error error;
    assert_int_equal(ur_piece_add_bridges(&piece, 4, 2, false, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "panel"));
    ur_piece_free(&piece);
}

/* Wide bridges on a square: three evenly spread cannot all miss the corners; moved off. */
static void test_bridges_shifted_off_corners(void **state)
{
    (void)state;
    ur_piece piece = piece_named("square");
    ur_vec2 outline[4];
    rectangle(outline, 0, 0, 100, 100);
    add(&piece, UR_OP_CUT, outline, 4, true);
    assert_int_equal(ur_piece_add_bridges(&piece, 3, 20, true, NULL), UR_OK);
    gaps g = find_gaps(&piece, outline, 4);
    assert_int_equal(g.count, 3);
    assert_widths(&g, 20, 400);
    assert_clear_of_corners(&g, outline, 4);
    /* And at least a width of cut between gaps. */
    for (size_t k = 0; k < g.count; k++) {
        double next = g.centre[(k + 1) % g.count] + (k + 1 == g.count ? 400 : 0);
        assert_true(next - g.centre[k] >= 2 * 20 - 1e-9);
    }
    assert_false(last_record(&piece)->warning);
    ur_piece_free(&piece);
}

static void test_bridges_automatic_count(void **state)
{
    (void)state;
    ur_vec2 outline[4];
    /* 2200 mm of outline: one bridge per 300 mm, 7.33 rounded to 7. */
    rectangle(outline, 0, 0, 1000, 100);
    ur_piece piece = piece_named("long");
    add(&piece, UR_OP_CUT, outline, 4, true);
    assert_int_equal(ur_piece_add_bridges(&piece, 0, 3, false, NULL), UR_OK);
    gaps g = find_gaps(&piece, outline, 4);
    assert_int_equal(g.count, 7);
    assert_widths(&g, 3, 2200);
    assert_clear_of_corners(&g, outline, 4);
    assert_int_equal(last_record(&piece)->count, 7);
    ur_piece_free(&piece);

    /* 200 mm rounds to 1: a router holds a part by 3 at least, a laser by 2. */
    rectangle(outline, 0, 0, 50, 50);
    bool router[2] = {true, false};
    size_t least[2] = {3, 2};
    for (size_t k = 0; k < 2; k++) {
        piece = piece_named("small");
        add(&piece, UR_OP_CUT, outline, 4, true);
        assert_int_equal(ur_piece_add_bridges(&piece, 0, 1, router[k], NULL), UR_OK);
        g = find_gaps(&piece, outline, 4);
        assert_int_equal(g.count, least[k]);
        assert_widths(&g, 1, 200);
        assert_clear_of_corners(&g, outline, 4);
        ur_piece_free(&piece);
    }
}

enum { CIRCLE_SIDES = 256 };

/* No corners on a round disc: exactly even. */
static void test_bridges_circle(void **state)
{
    (void)state;
    ur_vec2 outline[CIRCLE_SIDES];
    regular(outline, CIRCLE_SIDES, ur_vec2_make(0, 0), 50, false);
    double length = perimeter(outline, CIRCLE_SIDES, true);
    ur_piece piece = piece_named("disc");
    add(&piece, UR_OP_CUT, outline, CIRCLE_SIDES, true);
    assert_int_equal(ur_piece_add_bridges(&piece, 5, 2, false, NULL), UR_OK);
    gaps g = find_gaps(&piece, outline, CIRCLE_SIDES);
    assert_int_equal(g.count, 5);
    assert_widths(&g, 2, length);
    assert_even(&g, length);
    ur_piece_free(&piece);
}

/*
 * A rectangle with fillets of radius 3 mm (16 sides each, 5.6 degrees a
 * vertex): no single vertex is a corner, but each fillet turns 90 degrees
 * within 4.7 mm.  Gaps of 2 mm stay 2 mm off every fillet.
 */
static void test_bridges_tight_curves(void **state)
{
    (void)state;
    enum { STEPS = 16, N = 4 * (STEPS + 1) };
    ur_vec2 outline[N];
    ur_vec2 centres[4] = {{97, 3}, {97, 47}, {3, 47}, {3, 3}};
    size_t n = 0;
    for (size_t c = 0; c < 4; c++)
        for (size_t s = 0; s <= STEPS; s++) {
            double angle = (double)c * M_PI / 2 - M_PI / 2 + (double)s * M_PI / 2 / STEPS;
            outline[n++] =
                ur_vec2_make(centres[c].x + 3 * cos(angle), centres[c].y + 3 * sin(angle));
        }
    double length = perimeter(outline, N, true), fillet[4][2];
    for (size_t c = 0; c < 4; c++) {
        fillet[c][0] = arc_at(outline, N, outline[c * (STEPS + 1)]);
        fillet[c][1] = arc_at(outline, N, outline[c * (STEPS + 1) + STEPS]);
    }
    /* 13 gaps spread evenly would land some on the fillets: they are moved. */
    ur_piece piece = piece_named("rounded");
    add(&piece, UR_OP_CUT, outline, N, true);
    assert_int_equal(ur_piece_add_bridges(&piece, 13, 2, false, NULL), UR_OK);
    gaps g = find_gaps(&piece, outline, N);
    assert_int_equal(g.count, 13);
    assert_widths(&g, 2, length);
    for (size_t k = 0; k < g.count; k++)
        for (size_t c = 0; c < 4; c++)
            assert_true(span_distance(g.start[k], g.width[k], fillet[c][0], fillet[c][1], length) >=
                        2 - 1e-9);
    ur_piece_free(&piece);
}

/* More gaps than the sides have room for: what fits, and a warning. */
static void test_bridges_too_many(void **state)
{
    (void)state;
    ur_vec2 outline[4];
    rectangle(outline, 0, 0, 100, 100);
    ur_piece piece = piece_named("crowded");
    add(&piece, UR_OP_CUT, outline, 4, true);
    /* Centres 30..70 on each side, 40 apart at least: two a side at most. */
    assert_int_equal(ur_piece_add_bridges(&piece, 12, 20, false, NULL), UR_OK);
    gaps g = find_gaps(&piece, outline, 4);
    assert_true(g.count >= 4 && g.count <= 8);
    assert_widths(&g, 20, 400);
    assert_clear_of_corners(&g, outline, 4);
    const ur_allowance_record *record = last_record(&piece);
    assert_true(record->warning);
    assert_int_equal(record->count, g.count);
    ur_piece_free(&piece);

    /* A part too small for any: left closed, the warning says so. */
    rectangle(outline, 0, 0, 10, 10);
    piece = piece_named("tiny");
    add(&piece, UR_OP_CUT, outline, 4, true);
    assert_int_equal(ur_piece_add_bridges(&piece, 2, 5, false, NULL), UR_OK);
    assert_false(piece.bridged);
    assert_true(piece.paths[0].closed);
    assert_int_equal(piece.path_count, 1);
    assert_true(last_record(&piece)->warning);
    assert_int_equal(last_record(&piece)->count, 0);
    ur_piece_free(&piece);
}

static void test_bridges_refused(void **state)
{
    (void)state;
    ur_vec2 outline[4];
    rectangle(outline, 0, 0, 100, 50);
    ur_piece piece = piece_named("refused-9");
    add(&piece, UR_OP_CUT, outline, 4, true);
    double widths[] = {0, -1, NAN, INFINITY};
    for (size_t k = 0; k < sizeof widths / sizeof *widths; k++) {
        ur_error error;
        assert_int_equal(ur_piece_add_bridges(&piece, 4, widths[k], false, &error), UR_ERROR_INPUT);
        assert_non_null(strstr(error.message, "refused-9"));
    }
    assert_false(piece.bridged);
    assert_int_equal(piece.path_count, 1);
    assert_int_equal(piece.record_count, 0);
    ur_piece_free(&piece);
}

/* Kerf first, then bridges (the pipeline's order): the hole stays closed. */
static void test_kerf_then_bridges(void **state)
{
    (void)state;
    ur_vec2 hole[HOLE_SIDES];
    regular(hole, HOLE_SIDES, ur_vec2_make(50, 25), 10, false);
    ur_piece piece = plate_with_hole(hole, HOLE_SIDES);
    assert_int_equal(ur_piece_compensate_kerf(&piece, 0.2, NULL), UR_OK);
    ur_vec2 grown[4];
    memcpy(grown, piece.paths[0].points, sizeof grown);
    assert_int_equal(ur_piece_add_bridges(&piece, 0, 2, true, NULL), UR_OK);
    assert_true(piece.paths[1].closed);
    assert_int_equal(piece.paths[1].count, HOLE_SIDES);
    gaps g = find_gaps(&piece, grown, 4);
    assert_int_equal(g.count, 3);
    assert_widths(&g, 2, 2 * (100.2 + 50.2));
    assert_int_equal(piece.record_count, 2);
    /* Kerf compensation needs the closed outline bridges opened. */
    ur_error error;
    assert_int_equal(ur_piece_compensate_kerf(&piece, 0.2, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "plate-7"));
    ur_piece_free(&piece);
}

/* n points on the circle about centre of radius r, counter-clockwise from angle 0 (or clockwise).
 */
static void on_circle(ur_vec2 *p, size_t n, ur_vec2 centre, double r, bool clockwise)
{
    for (size_t k = 0; k < n; k++) {
        double angle = (clockwise ? -2 : 2) * M_PI * (double)k / (double)n;
        p[k] = ur_vec2_make(centre.x + r * cos(angle), centre.y + r * sin(angle));
    }
}

/* Every point of the path lies on its circle. */
static void assert_on_circle(const ur_path *path)
{
    for (size_t k = 0; k < path->count; k++)
        assert_close(ur_vec2_distance(path->points[k], path->circle.centre), path->circle.radius,
                     1e-9);
}

/*
 * A disc of radius 40 with a round hole of radius 10, both exact circles:
 * kerf 0.4 makes them circles of radius 40.2 and 9.8 about the same
 * centres, every point on them, the hole still clockwise; a kerf of 20 or
 * more would close the hole and is refused.
 */
static void test_kerf_keeps_circles(void **state)
{
    (void)state;
    ur_vec2 disc[CIRCLE_SIDES], hole[64];
    ur_vec2 centre = ur_vec2_make(5, -3), hole_centre = ur_vec2_make(15, 0);
    on_circle(disc, CIRCLE_SIDES, centre, 40, false);
    on_circle(hole, 64, hole_centre, 10, true);
    ur_piece piece = piece_named("washer");
    add(&piece, UR_OP_CUT, disc, CIRCLE_SIDES, true);
    add(&piece, UR_OP_CUT, hole, 64, true);
    piece.paths[0].circle = (ur_path_circle){centre, 40, 0};
    piece.paths[1].circle = (ur_path_circle){hole_centre, 10, 0};
    ur_piece copy;
    assert_int_equal(ur_piece_copy(&piece, &copy, NULL), UR_OK);
    assert_close(copy.paths[1].circle.radius, 10, 0);
    assert_int_equal(ur_piece_compensate_kerf(&piece, 0.4, NULL), UR_OK);
    assert_close(piece.paths[0].circle.radius, 40.2, 1e-12);
    assert_close(piece.paths[1].circle.radius, 9.8, 1e-12);
    assert_close(ur_vec2_distance(piece.paths[1].circle.centre, hole_centre), 0, 0);
    assert_int_equal(piece.paths[0].count, CIRCLE_SIDES);
    assert_on_circle(&piece.paths[0]);
    assert_on_circle(&piece.paths[1]);
    assert_true(ur_polygon_signed_area(piece.paths[1].points, piece.paths[1].count) < 0);
    /*
     * A kerf wider than the hole: the hole is cut as drawn, still the
     * circle it was, and the only warning (the disc, a speck beside 50
     * kerf squares, is not burned away).
     */
    assert_int_equal(ur_piece_compensate_kerf(&copy, 20, NULL), UR_OK);
    assert_close(copy.paths[1].circle.radius, 10, 0);
    assert_on_circle(&copy.paths[1]);
    assert_close(copy.paths[0].circle.radius, 50, 1e-12);
    assert_int_equal(copy.record_count, 2);
    assert_true(copy.records[0].warning);
    assert_close(ur_vec2_distance(copy.records[0].where, hole_centre), 0, 0);
    assert_non_null(strstr(copy.records[0].reason, "cut as drawn, it comes out 10 mm wider"));
    ur_piece_free(&copy);
    ur_piece_free(&piece);
}

/*
 * Bridges on an exact circle of radius 50 leave arcs of it: each open path
 * keeps the circle, all its points on it (the ends moved there from the
 * chords), its sweep the counter-clockwise angle from its first point to
 * its last; the sweeps and the gaps between them make one turn, each gap
 * about the bridge's width over the radius.
 */
static void test_bridges_leave_arcs(void **state)
{
    (void)state;
    ur_vec2 disc[CIRCLE_SIDES];
    on_circle(disc, CIRCLE_SIDES, ur_vec2_make(0, 0), 50, false);
    ur_piece piece = piece_named("disc");
    add(&piece, UR_OP_CUT, disc, CIRCLE_SIDES, true);
    piece.paths[0].circle = (ur_path_circle){{0, 0}, 50, 0};
    assert_int_equal(ur_piece_add_bridges(&piece, 5, 2, false, NULL), UR_OK);
    assert_int_equal(piece.path_count, 5);
    double turn = 0;
    for (size_t k = 0; k < piece.path_count; k++) {
        const ur_path *path = &piece.paths[k];
        assert_false(path->closed);
        assert_close(path->circle.radius, 50, 0);
        assert_on_circle(path);
        ur_vec2 a = path->points[0], b = path->points[path->count - 1];
        double angle = atan2(ur_vec2_cross(a, b), ur_vec2_dot(a, b));
        if (angle < 0)
            angle += 2 * M_PI;
        assert_close(path->circle.sweep, angle, 1e-9);
        /* The gap to the next arc (paths after the first follow on round the circle). */
        const ur_path *next = &piece.paths[(k + 1) % piece.path_count];
        ur_vec2 c = next->points[0];
        double gap = atan2(ur_vec2_cross(b, c), ur_vec2_dot(b, c));
        assert_close(gap, 2.0 / 50, 1e-4);
        turn += path->circle.sweep + gap;
    }
    assert_close(turn, 2 * M_PI, 1e-9);
    ur_piece_free(&piece);
}

/* The piece of a net with this outline and nothing else. */
static void piece_of_outline(ur_vec2 *outline, size_t count, ur_piece *piece)
{
    ur_net net;
    memset(&net, 0, sizeof net);
    net.outline = outline;
    net.outline_count = count;
    ur_error error;
    assert_int_equal(ur_piece_from_net(&net, NULL, piece, &error), UR_OK);
}

/*
 * A flat frame unfolded as one piece: its outline runs in from the rim to
 * the window along a slit of no width, round the window and back.  It is
 * cut as its rim and its window (60 x 60 and 20 x 20 mm), and kerf
 * compensation then moves the rim out and the window in, as for any hole.
 */
static void test_slit_to_a_window_is_cut_as_a_hole(void **state)
{
    (void)state;
    ur_vec2 frame[] = {{0, 0},   {20, 0},  {40, 0},  {60, 0},  {60, 20}, {40, 20},
                       {20, 20}, {20, 40}, {40, 40}, {40, 20}, {60, 20}, {60, 40},
                       {60, 60}, {40, 60}, {20, 60}, {0, 60},  {0, 40},  {0, 20}};
    ur_piece piece;
    piece_of_outline(frame, sizeof frame / sizeof frame[0], &piece);
    ur_error error;
    assert_int_equal(piece.path_count, 2);
    assert_true(piece.paths[1].op == UR_OP_CUT && piece.paths[1].closed);
    assert_float_equal(ur_polygon_signed_area(piece.paths[0].points, piece.paths[0].count), 3600,
                       1e-9);
    assert_float_equal(fabs(ur_polygon_signed_area(piece.paths[1].points, piece.paths[1].count)),
                       400, 1e-9);
    assert_int_equal(ur_piece_compensate_kerf(&piece, 0.2, &error), UR_OK);
    assert_float_equal(ur_polygon_signed_area(piece.paths[0].points, piece.paths[0].count),
                       60.2 * 60.2, 1e-6);
    assert_float_equal(fabs(ur_polygon_signed_area(piece.paths[1].points, piece.paths[1].count)),
                       19.8 * 19.8, 1e-6);
    ur_piece_free(&piece);
}

/*
 * A plate with two windows, unfolded as one piece: a slit runs in from the
 * rim to the first window, and another from it to the second.  Laid flat
 * two ways round the windows, the second slit's sides end a rounding
 * apart (1e-14 mm, as on Cura's farm2 bed).  It is still cut as the rim
 * and two windows, each a path that does not cross itself, not as one
 * hole of both windows joined by a slit of no width.
 */
static void test_slits_a_rounding_apart_leave_two_windows(void **state)
{
    (void)state;
    const double rounding = 1e-14;
    ur_vec2 plate[] = {{0, 0},
                       {30, 0},
                       {30, 20},
                       {20, 20},
                       {20, 40},
                       {40, 40},
                       {40, 30},
                       {60, 30},
                       {60, 40},
                       {80, 40},
                       {80, 20},
                       {60, 20},
                       {60, 30 + rounding},
                       {40, 30 - rounding},
                       {40, 20},
                       {30, 20},
                       {30, 0},
                       {100, 0},
                       {100, 60},
                       {0, 60}};
    ur_piece piece;
    piece_of_outline(plate, sizeof plate / sizeof plate[0], &piece);
    assert_int_equal(piece.path_count, 3);
    assert_float_equal(ur_polygon_signed_area(piece.paths[0].points, piece.paths[0].count), 6000,
                       1e-9);
    for (size_t k = 1; k < 3; k++) {
        const ur_path *window = &piece.paths[k];
        assert_true(window->op == UR_OP_CUT && window->closed);
        ur_box box = ur_box_empty();
        for (size_t i = 0; i < window->count; i++) {
            ur_box_add(&box, window->points[i]);
            for (size_t j = 0; j < i; j++) /* no point comes back: the path does not cross itself */
                assert_true(ur_vec2_distance(window->points[i], window->points[j]) > 1e-6);
        }
        assert_float_equal(ur_box_width(box), 20, 1e-9);
        assert_float_equal(ur_box_height(box), 20, 1e-9);
        assert_float_equal(fabs(ur_polygon_signed_area(window->points, window->count)), 400, 1e-9);
    }
    ur_piece_free(&piece);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kerf_rectangle_with_hole),
        cmocka_unit_test(test_slit_to_a_window_is_cut_as_a_hole),
        cmocka_unit_test(test_slits_a_rounding_apart_leave_two_windows),
        cmocka_unit_test(test_kerf_sharp_corner),
        cmocka_unit_test(test_kerf_cuts_vanishing_hole_as_drawn),
        cmocka_unit_test(test_kerf_narrow_features),
        cmocka_unit_test(test_kerf_values),
        cmocka_unit_test(test_kerf_finds_material_it_would_burn),
        cmocka_unit_test(test_bridges_rectangle),
        cmocka_unit_test(test_bridges_shifted_off_corners),
        cmocka_unit_test(test_bridges_automatic_count),
        cmocka_unit_test(test_bridges_circle),
        cmocka_unit_test(test_bridges_tight_curves),
        cmocka_unit_test(test_bridges_too_many),
        cmocka_unit_test(test_bridges_refused),
        cmocka_unit_test(test_kerf_then_bridges),
        cmocka_unit_test(test_kerf_keeps_circles),
        cmocka_unit_test(test_bridges_leave_arcs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
