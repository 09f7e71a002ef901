/*
 * test_bending.c: the surface parameter of each drawn ruling
 * (ur_net.ruling_parameters) and bending kerfs: router grooves at
 * s = w R / d on a cylinder, none where the bend is gentle, a laser living
 * hinge with its rows, slits, bridges and margins, a cone whose bend
 * radius varies along it, grooves that would merge, and meshes left alone.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/allow.h"
#include "unroll/analyze.h"
#include "unroll/develop.h"

#include "test_support.h"

/* 3 mm plywood on a router: 1/8" bit, 1 mm skin, 150 mm smallest radius across the grain. */
static const double WIDTH = 3.175, DEPTH = 2.0, MIN_RADIUS = 150.0;

/* The plywood-3mm living hinge. */
static const double CUT = 15.0, CONNECTION = 3.0, DISTANCE = 1.5;

/* A cylinder standing on z over a circle, as `unroll cylinder --radius` builds it. */
static ur_ruled cylinder(double radius, double height)
{
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(radius, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(curve, ur_vec3_make(0, 0, 1), height, &ruled, NULL), UR_OK);
    return ruled;
}

/* A frustum of the oblique cone over a circle of 100 mm, apex off the axis: R varies along it. */
static ur_ruled oblique_frustum(void)
{
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(100, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_cone(curve, ur_vec3_make(60, 0, 200), 0.5, &ruled, NULL), UR_OK);
    return ruled;
}

static ur_ruled helicoid(double turns)
{
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_helix(30, 20 * M_PI, 0, 2 * M_PI * turns, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, 5, 25, &ruled, NULL), UR_OK);
    return ruled;
}

static ur_bending_options router_options(void)
{
    ur_bending_options options = {0};
    options.min_radius = MIN_RADIUS;
    options.router = true;
    options.groove_width = WIDTH;
    options.groove_depth = DEPTH;
    return options;
}

static ur_bending_options laser_options(void)
{
    ur_bending_options options = {0};
    options.min_radius = MIN_RADIUS;
    options.hinge_cut_length = CUT;
    options.hinge_connection = CONNECTION;
    options.hinge_distance = DISTANCE;
    return options;
}

/* The piece of the only net, with its bending kerfs added. */
static ur_piece bent_piece(const ur_net_list *nets, ur_ruled *ruled,
                           const ur_bending_options *options)
{
    assert_int_equal(nets->count, 1);
    ur_piece piece;
    ur_error error;
    assert_int_equal(ur_piece_from_net(&nets->nets[0], NULL, &piece, &error), UR_OK);
    if (ur_piece_add_bending_kerfs(&piece, &nets->nets[0], ruled, options, &error) != UR_OK)
        fail_msg("bending kerfs: %s", error.message);
    return piece;
}

static size_t kerf_count(const ur_piece *piece)
{
    size_t count = 0;
    for (size_t i = 0; i < piece->path_count; i++)
        count += piece->paths[i].op == UR_OP_KERF;
    return count;
}

/* The KERF lines of a piece, as segments, in a new array. */
static ur_segment *kerf_lines(const ur_piece *piece, size_t *count)
{
    *count = kerf_count(piece);
    ur_segment *lines = calloc(*count ? *count : 1, sizeof *lines);
    assert_non_null(lines);
    size_t n = 0;
    for (size_t i = 0; i < piece->path_count; i++) {
        const ur_path *path = &piece->paths[i];
        if (path->op != UR_OP_KERF)
            continue;
        assert_int_equal(path->count, 2);
        assert_false(path->closed);
        lines[n].start = path->points[0];
        lines[n++].end = path->points[1];
    }
    return lines;
}

static ur_vec2 unit(ur_vec2 v)
{
    return ur_vec2_scale(v, 1.0 / ur_vec2_length(v));
}

static ur_vec2 middle(ur_segment s)
{
    return ur_vec2_scale(ur_vec2_add(s.start, s.end), 0.5);
}

/* Distance from p to the outline ring. */
static double distance_to_outline(const ur_net *net, ur_vec2 p)
{
    double nearest = INFINITY;
    for (size_t i = 0; i < net->outline_count; i++) {
        ur_vec2 a = net->outline[i], b = net->outline[(i + 1) % net->outline_count];
        ur_vec2 ab = ur_vec2_sub(b, a);
        double f = ur_vec2_dot(ur_vec2_sub(p, a), ab) / ur_vec2_dot(ab, ab);
        f = fmin(fmax(f, 0.0), 1.0);
        nearest = fmin(nearest, ur_vec2_distance(p, ur_vec2_add_scaled(a, ab, f)));
    }
    return nearest;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* ---- Ruling parameters --------------------------------------------------- */

/* Every drawn ruling is as long flat as the 3D ruling at its parameter, which lies in the net. */
static void check_ruling_parameters(ur_ruled *ruled, const ur_net_list *nets, size_t *total)
{
    for (size_t k = 0; k < nets->count; k++) {
        const ur_net *net = &nets->nets[k];
        assert_non_null(net->ruling_parameters);
        for (size_t i = 0; i < net->ruling_count; i++) {
            double u = net->ruling_parameters[i];
            assert_true(u > net->u_start && u < net->u_end);
            if (i > 0)
                assert_true(u > net->ruling_parameters[i - 1]);
            ur_vec3 rails[4];
            ur_ruled_rails(ruled, u, rails);
            assert_relative(ur_vec2_distance(net->rulings[i].start, net->rulings[i].end),
                            ur_vec3_distance(rails[0], rails[2]), 1e-9);
        }
        *total += net->ruling_count;
    }
}

static void test_ruling_parameters(void **state)
{
    (void)state;
    struct {
        ur_ruled ruled;
        ur_method method;
    } cases[] = {
        {cylinder(40, 100), UR_METHOD_EXACT}, {oblique_frustum(), UR_METHOD_EXACT},
        {oblique_frustum(), UR_METHOD_QUAD},  {helicoid(2.5), UR_METHOD_EXACT},
        {helicoid(2.5), UR_METHOD_TRIANGLE},  {helicoid(2.5), UR_METHOD_QUAD},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        ur_net_list nets = develop(&cases[c].ruled, cases[c].method, 48, 0.01);
        size_t total = 0;
        check_ruling_parameters(&cases[c].ruled, &nets, &total);
        /* 47 rulings inside; a split net loses the cut ones to its seams. */
        assert_int_equal(total + (nets.count - 1), 47);
        if (c >= 3)
            assert_true(nets.count > 1); /* the helicoid of 2.5 turns is split */
        ur_net_list_free(&nets);
        ur_ruled_free(&cases[c].ruled);
    }
}

/* ---- Router grooves ------------------------------------------------------- */

/* Grooves on R = 40: s = w R / d = 63.5 mm, ceil(2 pi 40 / 63.5) = 4 of them, centred. */
static void test_router_cylinder(void **state)
{
    (void)state;
    const double radius = 40, height = 100;
    ur_ruled ruled = cylinder(radius, height);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 24, 0.01);
    ur_bending_options options = router_options();
    ur_piece piece = bent_piece(&nets, &ruled, &options);
    const ur_net *net = &nets.nets[0];
    double s = WIDTH * radius / DEPTH, length = 2 * M_PI * radius;
    assert_relative(s, 63.5, 1e-15);
    size_t count;
    ur_segment *lines = kerf_lines(&piece, &count);
    assert_int_equal(count, (size_t)ceil(length / s));
    assert_int_equal(count, 4);
    ur_vec2 along = unit(ur_vec2_sub(net->rulings[0].end, net->rulings[0].start));
    ur_vec2 across = {-along.y, along.x};
    double at[8];
    for (size_t i = 0; i < count; i++) {
        ur_vec2 d = unit(ur_vec2_sub(lines[i].end, lines[i].start));
        assert_true(fabs(ur_vec2_cross(d, along)) < 1e-9); /* parallel to the rulings */
        /* Edge to edge: the whole ruling, both ends on the outline. */
        assert_relative(ur_vec2_distance(lines[i].start, lines[i].end), height, 1e-9);
        assert_true(distance_to_outline(net, lines[i].start) < 1e-9);
        assert_true(distance_to_outline(net, lines[i].end) < 1e-9);
        at[i] = ur_vec2_dot(lines[i].start, across);
    }
    qsort(at, count, sizeof *at, compare_doubles);
    for (size_t i = 1; i < count; i++)
        assert_relative(at[i] - at[i - 1], s, 1e-6);
    /* Centred: the same margin to both ends of the net. */
    double low = INFINITY, high = -INFINITY;
    for (size_t i = 0; i < net->outline_count; i++) {
        low = fmin(low, ur_vec2_dot(net->outline[i], across));
        high = fmax(high, ur_vec2_dot(net->outline[i], across));
    }
    assert_relative(high - low, length, 1e-6);
    assert_relative(at[0] - low, 0.5 * (length - 3 * s), 1e-6);
    assert_relative(high - at[count - 1], 0.5 * (length - 3 * s), 1e-6);
    assert_int_equal(piece.record_count, 1);
    const ur_allowance_record *record = &piece.records[0];
    assert_int_equal(record->kind, UR_ALLOWANCE_BENDING);
    assert_int_equal(record->count, 4);
    assert_relative(record->value, radius, 1e-6);
    assert_relative(record->limit, MIN_RADIUS, 0);
    assert_false(record->warning);
    assert_string_equal(record->reason,
                        "bend radius 40 mm < 150 mm: 4 grooves 3.175 mm wide, 2 mm deep, every "
                        "63.5 mm");
    free(lines);
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

static void test_gentle_bend_needs_none(void **state)
{
    (void)state;
    ur_ruled ruled = cylinder(1000, 100);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 24, 0.01);
    ur_bending_options router = router_options(), laser = laser_options();
    ur_piece grooved = bent_piece(&nets, &ruled, &router);
    ur_piece hinged = bent_piece(&nets, &ruled, &laser);
    assert_int_equal(kerf_count(&grooved), 0);
    assert_int_equal(grooved.record_count, 0);
    assert_int_equal(kerf_count(&hinged), 0);
    assert_int_equal(hinged.record_count, 0);
    ur_piece_free(&grooved);
    ur_piece_free(&hinged);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* ---- Laser living hinge ----------------------------------------------------- */

/* The slits of one row (same position across the net), sorted along it. */
typedef struct slit {
    double across, from, to;
} slit;

static int compare_slits(const void *a, const void *b)
{
    const slit *x = a, *y = b;
    if (fabs(x->across - y->across) > 1e-6)
        return (x->across > y->across) - (x->across < y->across);
    return (x->from > y->from) - (x->from < y->from);
}

/* Checks the slits of one row from first to last (exclusive); returns their middles' phase. */
static void check_row(const slit *slits, size_t first, size_t last, double height, double *phase)
{
    double period = CUT + CONNECTION;
    for (size_t i = first; i < last; i++) {
        double length = slits[i].to - slits[i].from;
        assert_true(length <= CUT + 1e-9 && length >= CONNECTION - 1e-9);
        /* Solid margins at the ends of the rulings. */
        assert_true(slits[i].from >= CONNECTION - 1e-9);
        assert_true(slits[i].to <= height - CONNECTION + 1e-9);
        if (i > first) /* uncut bridges between the slits of a row */
            assert_relative(slits[i].from - slits[i - 1].to, CONNECTION, 1e-9);
    }
    /* A whole slit of the row tells where the pattern sits along it. */
    for (size_t i = first; i < last; i++)
        if (slits[i].to - slits[i].from > CUT - 1e-9) {
            *phase = fmod(0.5 * (slits[i].from + slits[i].to) - 0.5 * height + 10 * period, period);
            return;
        }
    fail_msg("a row without a whole slit");
}

static void test_laser_hinge_cylinder(void **state)
{
    (void)state;
    const double radius = 40, height = 60;
    ur_ruled ruled = cylinder(radius, height);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 24, 0.01);
    ur_bending_options options = laser_options();
    ur_piece piece = bent_piece(&nets, &ruled, &options);
    const ur_net *net = &nets.nets[0];
    ur_vec2 along = unit(ur_vec2_sub(net->rulings[0].end, net->rulings[0].start));
    ur_vec2 across = {-along.y, along.x};
    ur_vec2 base = net->rulings[0].start; /* rail a: 0 along the rulings */
    size_t count;
    ur_segment *lines = kerf_lines(&piece, &count);
    slit *slits = calloc(count, sizeof *slits);
    assert_non_null(slits);
    for (size_t i = 0; i < count; i++) {
        ur_vec2 d = unit(ur_vec2_sub(lines[i].end, lines[i].start));
        assert_true(fabs(ur_vec2_cross(d, along)) < 1e-9);
        assert_true(distance_to_outline(net, lines[i].start) >= CONNECTION - 1e-9);
        assert_true(distance_to_outline(net, lines[i].end) >= CONNECTION - 1e-9);
        double a = ur_vec2_dot(ur_vec2_sub(lines[i].start, base), along);
        double b = ur_vec2_dot(ur_vec2_sub(lines[i].end, base), along);
        slits[i] = (slit){ur_vec2_dot(middle(lines[i]), across), fmin(a, b), fmax(a, b)};
    }
    qsort(slits, count, sizeof *slits, compare_slits);
    /* Rows every hinge_distance: ceil(2 pi 40 / 1.5) = 168 of them. */
    size_t rows = 0, first = 0, odd_first = 0;
    double previous_across = 0, previous_phase = 0;
    for (size_t i = 1; i <= count; i++) {
        if (i < count && fabs(slits[i].across - slits[first].across) <= 1e-6)
            continue;
        double phase = NAN;
        check_row(slits, first, i, height, &phase);
        if (rows > 0) {
            assert_relative(slits[first].across - previous_across, DISTANCE, 1e-6);
            /* Alternate rows offset by half a period. */
            double shift = fabs(phase - previous_phase);
            assert_relative(fmin(shift, CUT + CONNECTION - shift), 0.5 * (CUT + CONNECTION), 1e-6);
        }
        /*
         * 60 mm rows, 3 mm margins: 3 whole slits centred (even rows), or 2
         * whole and 2 clipped to 7.5 mm (odd rows), alternately.
         */
        if (rows == 0)
            odd_first = i - first == 4;
        assert_int_equal(i - first, (rows + odd_first) % 2 == 0 ? 3 : 4);
        previous_across = slits[first].across;
        previous_phase = phase;
        rows++;
        first = i;
    }
    /*
     * ceil(L / 1.5) = 168 rows, centred, every 1.5 mm across the net of
     * L = 2 pi 40 mm; those within 3 mm of the net's ends (its seam) fall in
     * the margin and have no slit.
     */
    double length = 2 * M_PI * radius, phi = length / DISTANCE;
    size_t placed = (size_t)ceil(phi), cut = 0;
    for (size_t k = 0; k < placed; k++) {
        double t = (0.5 * (phi - (double)(placed - 1)) + (double)k) * DISTANCE;
        cut += t >= CONNECTION && t <= length - CONNECTION;
    }
    assert_int_equal(placed, 168);
    assert_int_equal(rows, cut);
    assert_int_equal(rows, 164);
    assert_int_equal(count, 82 * 3 + 82 * 4);
    assert_int_equal(piece.record_count, 1);
    assert_int_equal(piece.records[0].count, count);
    assert_relative(piece.records[0].value, radius, 1e-6);
    assert_false(piece.records[0].warning);
    assert_non_null(strstr(piece.records[0].reason, "living hinge, 574 slits 15 mm long with "
                                                    "3 mm bridges in 164 rows every 1.5 mm"));
    free(slits);
    free(lines);
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* ---- A cone: R varies along it ---------------------------------------------- */

/*
 * The parameter of a line of the developed cone (every ruling meets the
 * developed apex, where the rulings' lines cross): its angle at the apex,
 * interpolated between the drawn rulings'.
 */
static double cone_parameter(const ur_net *net, ur_vec2 apex, ur_segment line)
{
    double angle = atan2(line.start.y - apex.y, line.start.x - apex.x);
    double previous = NAN;
    for (size_t i = 0; i < net->ruling_count; i++) {
        ur_segment r = net->rulings[i];
        double a = atan2(r.start.y - apex.y, r.start.x - apex.x);
        if (i > 0) {
            double low = fmin(previous, a), high = fmax(previous, a);
            if (angle >= low && angle <= high)
                return net->ruling_parameters[i - 1] +
                       (net->ruling_parameters[i] - net->ruling_parameters[i - 1]) *
                           (angle - previous) / (a - previous);
        }
        previous = a;
    }
    /* Beyond the drawn rulings: in the end bands, by the first or last pair. */
    return NAN;
}

/* Where the lines through two rulings meet. */
static ur_vec2 meet(ur_segment a, ur_segment b)
{
    ur_vec2 da = ur_vec2_sub(a.end, a.start), db = ur_vec2_sub(b.end, b.start);
    double t = ur_vec2_cross(ur_vec2_sub(b.start, a.start), db) / ur_vec2_cross(da, db);
    return ur_vec2_add_scaled(a.start, da, t);
}

static void test_cone_grooves_only_where_tight(void **state)
{
    (void)state;
    ur_ruled ruled = oblique_frustum();
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 24, 0.01);
    ur_bending_options options = router_options();
    options.min_radius = 55; /* R runs from about 50 (at u = 0) to 64 (at u = pi) */
    ur_piece piece = bent_piece(&nets, &ruled, &options);
    const ur_net *net = &nets.nets[0];
    ur_vec2 apex = meet(net->rulings[0], net->rulings[12]);
    size_t count;
    ur_segment *lines = kerf_lines(&piece, &count);
    assert_true(count >= 4);
    size_t checked = 0;
    for (size_t i = 0; i < count; i++) {
        /* Along a ruling of the cone: its line passes through the apex. */
        ur_vec2 d = unit(ur_vec2_sub(lines[i].end, lines[i].start));
        assert_true(fabs(ur_vec2_cross(d, ur_vec2_sub(apex, lines[i].start))) < 1e-6);
        double u = cone_parameter(net, apex, lines[i]);
        if (isnan(u))
            continue;
        double radius = ur_analyze_bend_radius(&ruled, u, 17, NULL);
        assert_true(radius < options.min_radius * 1.001);
        checked++;
    }
    assert_true(checked >= 2);
    /* Every drawn ruling that bends too tightly has a groove within a spacing of it. */
    size_t tight = 0;
    for (size_t k = 0; k < net->ruling_count; k++) {
        double radius = ur_analyze_bend_radius(&ruled, net->ruling_parameters[k], 17, NULL);
        if (!(radius < options.min_radius))
            continue;
        tight++;
        double nearest = INFINITY;
        ur_vec2 m = middle(net->rulings[k]);
        for (size_t i = 0; i < count; i++) {
            ur_vec2 d = unit(ur_vec2_sub(lines[i].end, lines[i].start));
            nearest = fmin(nearest, fabs(ur_vec2_cross(d, ur_vec2_sub(m, lines[i].start))));
        }
        assert_true(nearest <= WIDTH * options.min_radius / DEPTH);
    }
    assert_true(tight > 0 && tight < net->ruling_count);
    /* The seam at u = 0 cuts the tight part in two: two regions, at each end of the net. */
    assert_int_equal(piece.record_count, 2);
    size_t recorded = 0;
    for (size_t k = 0; k < piece.record_count; k++) {
        const ur_allowance_record *record = &piece.records[k];
        assert_int_equal(record->kind, UR_ALLOWANCE_BENDING);
        assert_true(record->value < options.min_radius && record->value > 49);
        assert_false(record->warning);
        assert_non_null(strstr(record->reason, "grooves 3.175 mm wide, 2 mm deep, every "));
        recorded += record->count;
    }
    assert_int_equal(recorded, count);
    free(lines);
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* ---- Limits ----------------------------------------------------------------- */

/* R = 1.5 mm < d = 2 mm: grooves every w, touching, and a warning. */
static void test_merging_grooves_warn(void **state)
{
    (void)state;
    ur_ruled ruled = cylinder(1.5, 20);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 24, 0.001);
    ur_bending_options options = router_options();
    ur_piece piece = bent_piece(&nets, &ruled, &options);
    assert_int_equal(kerf_count(&piece), (size_t)ceil(2 * M_PI * 1.5 / WIDTH));
    assert_int_equal(piece.record_count, 1);
    assert_true(piece.records[0].warning);
    assert_non_null(strstr(piece.records[0].reason, "merge"));
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* One drawn ruling gives no direction across the net: a warning, no kerfs. */
static void test_too_few_rulings_warn(void **state)
{
    (void)state;
    ur_ruled ruled = cylinder(40, 100);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 2, 0.01);
    assert_int_equal(nets.nets[0].ruling_count, 1);
    ur_bending_options options = router_options();
    ur_piece piece = bent_piece(&nets, &ruled, &options);
    assert_int_equal(kerf_count(&piece), 0);
    assert_int_equal(piece.record_count, 1);
    assert_true(piece.records[0].warning);
    assert_relative(piece.records[0].value, 40, 1e-6);
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* A flattened mesh has no ruling parameters: nothing to do. */
static void test_mesh_left_alone(void **state)
{
    (void)state;
    ur_vec2 outline[4] = {{0, 0}, {100, 0}, {100, 50}, {0, 50}};
    ur_segment rulings[1] = {{{50, 0}, {50, 50}}};
    ur_net net = {0};
    net.outline = outline;
    net.outline_count = 4;
    net.rulings = rulings;
    net.ruling_count = 1;
    ur_piece piece;
    assert_int_equal(ur_piece_from_net(&net, NULL, &piece, NULL), UR_OK);
    ur_bending_options options = router_options();
    assert_int_equal(ur_piece_add_bending_kerfs(&piece, &net, NULL, &options, NULL), UR_OK);
    assert_int_equal(piece.path_count, 1);
    assert_int_equal(piece.record_count, 0);
    options.groove_depth = 0;
    ur_error error;
    assert_int_equal(ur_piece_add_bending_kerfs(&piece, &net, NULL, &options, &error),
                     UR_ERROR_INPUT);
    ur_piece_free(&piece);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ruling_parameters),
        cmocka_unit_test(test_router_cylinder),
        cmocka_unit_test(test_gentle_bend_needs_none),
        cmocka_unit_test(test_laser_hinge_cylinder),
        cmocka_unit_test(test_cone_grooves_only_where_tight),
        cmocka_unit_test(test_merging_grooves_warn),
        cmocka_unit_test(test_too_few_rulings_warn),
        cmocka_unit_test(test_mesh_left_alone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
