/*
 * test_bending.c: the surface parameter of each drawn ruling
 * (ur_net.ruling_parameters) and bending kerfs: router grooves and laser
 * hinge rows on cylinders of several radii, each turning the sheet by at
 * most the facet angle and never farther apart than w R / d (or the hinge
 * distance), warnings where webs would be too thin or the skin too thick,
 * none where the bend is gentle, a laser living hinge with its rows, slits,
 * bridges and margins, a cone whose bend radius varies along it, a cone's
 * apex where no two slits come nearer than the minimum web, grooves that
 * would merge, and meshes left alone.
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

#include <geos_c.h>

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

/* The positions across the net of the piece's KERF lines (all parallel to the rulings), sorted. */
static double *positions_across(const ur_piece *piece, const ur_net *net, size_t *count)
{
    ur_vec2 along = unit(ur_vec2_sub(net->rulings[0].end, net->rulings[0].start));
    ur_vec2 across = {-along.y, along.x};
    ur_segment *lines = kerf_lines(piece, count);
    double *at = calloc(*count ? *count : 1, sizeof *at);
    assert_non_null(at);
    for (size_t i = 0; i < *count; i++) {
        ur_vec2 d = unit(ur_vec2_sub(lines[i].end, lines[i].start));
        assert_true(fabs(ur_vec2_cross(d, along)) < 1e-9); /* parallel to the rulings */
        at[i] = ur_vec2_dot(middle(lines[i]), across);
    }
    qsort(at, *count, sizeof *at, compare_doubles);
    free(lines);
    return at;
}

/*
 * Cylinders of several radii on a router: each groove turns the sheet by
 * at most the facet angle (on a cylinder the flat spacing over R, since
 * the net keeps lengths) and grooves are never farther apart than w R / d;
 * ceil(L / s) of them for s = min(R theta, w R / d), evenly spaced, centred,
 * every line from outline to outline.  The last case, a facet limit of 60
 * degrees in 6 mm plywood (w / d = 40 degrees), gives the nonagon of the
 * old rule: w R / d decides.
 */
static void test_router_cylinders_round(void **state)
{
    (void)state;
    const double height = 100;
    const struct {
        double radius, depth, facet, min_web;
        size_t expected; /* worked out by hand from the formula */
    } cases[] = {
        {40, 2.0, 0, 0, 72},       /* default 5 degrees: 2 pi 40 / 3.49 */
        {120, 2.0, 5, 0.6, 72},    /* s = 10.47 mm, webs of 7.3 mm */
        {300, 4.5, 5, 0.6, 72},    /* the 6 mm plywood drum: not 9 grooves */
        {300, 4.5, 60, 0.6, 9},    /* w R / d = 211.7 mm decides */
        {160, 2.0, 2.5, 0.6, 144}, /* a finer facet, twice the grooves */
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double radius = cases[c].radius, depth = cases[c].depth;
        ur_ruled ruled = cylinder(radius, height);
        ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 24, 0.01);
        ur_bending_options options = router_options();
        options.groove_depth = depth;
        options.facet_angle = cases[c].facet;
        options.min_web = cases[c].min_web;
        options.min_radius = 1000;
        ur_piece piece = bent_piece(&nets, &ruled, &options);
        const ur_net *net = &nets.nets[0];
        double theta = (cases[c].facet > 0 ? cases[c].facet : 5.0) * M_PI / 180;
        double widest = WIDTH * radius / depth, length = 2 * M_PI * radius;
        double s = fmin(radius * theta, widest);
        size_t count;
        double *at = positions_across(&piece, net, &count);
        assert_int_equal(count, (size_t)ceil(length / s - 1e-9));
        assert_int_equal(count, cases[c].expected);
        for (size_t i = 1; i < count; i++) {
            double spacing = at[i] - at[i - 1];
            assert_true(spacing / radius <= theta * (1 + 1e-6));
            assert_true(spacing <= widest * (1 + 1e-9));
            assert_true(spacing - WIDTH >= cases[c].min_web - 1e-9);
            assert_relative(spacing, s, 1e-6);
        }
        ur_segment *lines = kerf_lines(&piece, &count);
        for (size_t i = 0; i < count; i++) {
            assert_relative(ur_vec2_distance(lines[i].start, lines[i].end), height, 1e-9);
            assert_true(distance_to_outline(net, lines[i].start) < 1e-9);
            assert_true(distance_to_outline(net, lines[i].end) < 1e-9);
        }
        /* Centred: the same margin to both ends of the net. */
        ur_vec2 along = unit(ur_vec2_sub(net->rulings[0].end, net->rulings[0].start));
        ur_vec2 across = {-along.y, along.x};
        double low = INFINITY, high = -INFINITY;
        for (size_t i = 0; i < net->outline_count; i++) {
            low = fmin(low, ur_vec2_dot(net->outline[i], across));
            high = fmax(high, ur_vec2_dot(net->outline[i], across));
        }
        assert_relative(high - low, length, 1e-6);
        assert_relative(at[0] - low, high - at[count - 1], 1e-6);
        assert_true(at[0] - low <= 0.5 * s * (1 + 1e-6));
        assert_int_equal(piece.record_count, 1);
        const ur_allowance_record *record = &piece.records[0];
        assert_int_equal(record->kind, UR_ALLOWANCE_BENDING);
        assert_int_equal(record->count, count);
        assert_int_equal(record->rows, count);
        assert_true(record->facet_angle <= theta * 180 / M_PI * (1 + 1e-6));
        assert_relative(record->facet_angle, s / radius * 180 / M_PI, 1e-4);
        assert_relative(record->value, radius, 1e-6);
        assert_false(record->warning);
        assert_non_null(strstr(record->reason, "grooves 3.175 mm wide"));
        free(lines);
        free(at);
        ur_piece_free(&piece);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
}

/*
 * 5 degrees on R = 40 would leave 0.32 mm webs between 3.175 mm grooves:
 * with a 0.6 mm minimum they stay 3.775 mm apart, each turning by
 * 3.775 / 40 rad, and a warning says so; the 1 mm skin of 3 mm stock that
 * bends no tighter than 150 mm takes 50 mm, not 40: a second warning.
 */
static void test_router_limits_warn(void **state)
{
    (void)state;
    const double radius = 40;
    ur_ruled ruled = cylinder(radius, 100);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 24, 0.01);
    ur_bending_options options = router_options();
    options.min_web = 0.6;
    options.thickness = 3.0;
    ur_piece piece = bent_piece(&nets, &ruled, &options);
    size_t count;
    double *at = positions_across(&piece, &nets.nets[0], &count);
    double s = WIDTH + 0.6;
    assert_int_equal(count, (size_t)ceil(2 * M_PI * radius / s));
    for (size_t i = 1; i < count; i++)
        assert_relative(at[i] - at[i - 1], s, 1e-6);
    assert_int_equal(piece.record_count, 3);
    assert_false(piece.records[0].warning);
    assert_relative(piece.records[0].facet_angle, s / radius * 180 / M_PI, 1e-4);
    assert_true(piece.records[1].warning);
    assert_non_null(strstr(piece.records[1].reason, "webs under 0.6 mm"));
    assert_non_null(strstr(piece.records[1].reason, "living hinge"));
    assert_true(piece.records[2].warning);
    assert_non_null(strstr(piece.records[2].reason, "skin"));
    assert_non_null(strstr(piece.records[2].reason, "needs a skin of 0.8 mm"));
    free(at);
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

/*
 * Laser hinges on cylinders of several radii: rows never farther apart
 * than the hinge's row distance nor than R theta (each row turns the sheet
 * by at most the facet angle), and never closer than the kerf plus the
 * minimum web.  On R = 5 the facet angle would need rows 0.44 mm apart,
 * webs of 0.24 mm: they stay 0.8 mm apart and a warning says so.
 */
static void test_laser_cylinders_round(void **state)
{
    (void)state;
    const double kerf = 0.2, web = 0.6, theta = 5 * M_PI / 180;
    const double radii[] = {5, 10, 20, 40};
    for (size_t c = 0; c < sizeof radii / sizeof radii[0]; c++) {
        double radius = radii[c];
        ur_ruled ruled = cylinder(radius, 60);
        ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 24, 0.001);
        ur_bending_options options = laser_options();
        options.kerf = kerf;
        options.min_web = web;
        ur_piece piece = bent_piece(&nets, &ruled, &options);
        size_t count, rows = 0;
        double *at = positions_across(&piece, &nets.nets[0], &count);
        double expected = fmax(fmin(radius * theta, DISTANCE), kerf + web);
        bool thin = radius * theta < kerf + web;
        assert_true(count > 0);
        for (size_t i = 1; i < count; i++) {
            double spacing = at[i] - at[i - 1];
            if (spacing < 1e-6)
                continue; /* another slit of the same row */
            rows++;
            assert_relative(spacing, expected, 1e-6);
            assert_true(spacing - kerf >= web - 1e-9);
            assert_true(spacing <= DISTANCE * (1 + 1e-9));
            if (!thin)
                assert_true(spacing / radius <= theta * (1 + 1e-6));
        }
        assert_true(rows > 10);
        const ur_allowance_record *record = &piece.records[0];
        assert_int_equal(piece.record_count, thin ? 2 : 1);
        assert_relative(record->facet_angle, expected / radius * 180 / M_PI, 1e-4);
        if (thin) {
            assert_true(piece.records[1].warning);
            assert_non_null(strstr(piece.records[1].reason, "webs under 0.6 mm"));
        } else
            assert_true(record->facet_angle <= 5 * (1 + 1e-6));
        free(at);
        ur_piece_free(&piece);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
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

/* ---- A cone's apex ---------------------------------------------------------- */

/*
 * A right cone in cardboard (radius 60, height 80) bends to radius 0 at
 * its apex, where the hinge's rows converge: no two slits come nearer than
 * the kerf plus the minimum web (GEOS distance between every pair), though
 * without the rule neighbouring rows met within 0.09 mm.  The seam (the
 * cut ruling from base to apex) has its two sides, so it gets its joint.
 */
static void test_cone_apex_webs(void **state)
{
    (void)state;
    const double kerf = 0.15, web = 0.45;
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(60, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_cone(curve, ur_vec3_make(0, 0, 80), 1.0, &ruled, NULL), UR_OK);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 48, 0.01);
    assert_int_equal(nets.count, 1);
    assert_int_equal(nets.nets[0].seam_side_count, 2);
    ur_bending_options options = {0};
    options.min_radius = 10;
    options.hinge_cut_length = 10;
    options.hinge_connection = 2;
    options.hinge_distance = 1;
    options.kerf = kerf;
    options.min_web = web;
    ur_piece piece = bent_piece(&nets, &ruled, &options);
    size_t count;
    ur_segment *lines = kerf_lines(&piece, &count);
    assert_true(count > 50);
    GEOSContextHandle_t geos = GEOS_init_r();
    GEOSGeometry **slits = calloc(count, sizeof *slits);
    assert_non_null(slits);
    for (size_t i = 0; i < count; i++) {
        GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, 2, 2);
        GEOSCoordSeq_setXY_r(geos, sequence, 0, lines[i].start.x, lines[i].start.y);
        GEOSCoordSeq_setXY_r(geos, sequence, 1, lines[i].end.x, lines[i].end.y);
        slits[i] = GEOSGeom_createLineString_r(geos, sequence);
        assert_non_null(slits[i]);
    }
    double nearest = INFINITY;
    for (size_t i = 0; i < count; i++)
        for (size_t k = i + 1; k < count; k++) {
            double distance;
            assert_int_equal(GEOSDistance_r(geos, slits[i], slits[k], &distance), 1);
            nearest = fmin(nearest, distance);
        }
    assert_true(nearest - kerf >= web - 1e-6);
    for (size_t i = 0; i < count; i++)
        GEOSGeom_destroy_r(geos, slits[i]);
    free(slits);
    GEOS_finish_r(geos);
    assert_false(piece.records[0].warning);
    assert_non_null(strstr(piece.records[0].reason, "fanned out"));
    assert_true(piece.records[0].facet_angle <= 5 * (1 + 1e-6));
    free(lines);
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* ---- Hinges and joints agree ------------------------------------------------ */

/* A GEOS line through a path's points (a closed one back to its first point). */
static GEOSGeometry *path_line(GEOSContextHandle_t geos, const ur_path *path)
{
    size_t count = path->count + (path->closed ? 1 : 0);
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)count, 2);
    for (size_t k = 0; k < count; k++) {
        ur_vec2 p = path->points[k % path->count];
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)k, p.x, p.y);
    }
    return GEOSGeom_createLineString_r(geos, sequence);
}

/*
 * The nearest any KERF line of the piece comes to a MARK or SCORE line
 * among paths[first ..] (the joints'), by GEOS.
 */
static double kerf_to_joint_lines(const ur_piece *piece, size_t first)
{
    GEOSContextHandle_t geos = GEOS_init_r();
    double nearest = INFINITY;
    for (size_t i = 0; i < piece->path_count; i++) {
        if (piece->paths[i].op != UR_OP_KERF)
            continue;
        GEOSGeometry *kerf = path_line(geos, &piece->paths[i]);
        for (size_t k = first; k < piece->path_count; k++) {
            ur_op op = piece->paths[k].op;
            if (op != UR_OP_MARK && op != UR_OP_SCORE)
                continue;
            GEOSGeometry *line = path_line(geos, &piece->paths[k]);
            double distance;
            assert_int_equal(GEOSDistance_r(geos, kerf, line, &distance), 1);
            nearest = fmin(nearest, distance);
            GEOSGeom_destroy_r(geos, line);
        }
        GEOSGeom_destroy_r(geos, kerf);
    }
    GEOS_finish_r(geos);
    return nearest;
}

/* KERF lines whose middle lies outside the net's own outline: on its joints. */
static size_t kerfs_outside_net(const ur_piece *piece, const ur_net *net)
{
    GEOSContextHandle_t geos = GEOS_init_r();
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)net->outline_count + 1, 2);
    for (size_t k = 0; k <= net->outline_count; k++) {
        ur_vec2 p = net->outline[k % net->outline_count];
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)k, p.x, p.y);
    }
    GEOSGeometry *outline =
        GEOSGeom_createPolygon_r(geos, GEOSGeom_createLinearRing_r(geos, sequence), NULL, 0);
    size_t count = 0;
    for (size_t i = 0; i < piece->path_count; i++) {
        const ur_path *path = &piece->paths[i];
        if (path->op != UR_OP_KERF)
            continue;
        ur_vec2 m = ur_vec2_lerp(path->points[0], path->points[path->count - 1], 0.5);
        GEOSGeometry *point = GEOSGeom_createPointFromXY_r(geos, m.x, m.y);
        count += GEOSContains_r(geos, outline, point) != 1;
        GEOSGeom_destroy_r(geos, point);
    }
    GEOSGeom_destroy_r(geos, outline);
    GEOS_finish_r(geos);
    return count;
}

/*
 * A 3 mm plywood cylinder of radius 40 with a 15 mm lap on its seam: on a
 * laser (living hinge) and on a router (grooves), the lap tongue carries
 * the hinge of the zone it lies on (kerf lines outside the net's outline),
 * and once the kerfs are kept off the joints no kerf line comes nearer a
 * mark line than the clearance.  A cardboard cone's tab: no slit nears its
 * folds.
 */
static void test_hinges_and_joints_agree(void **state)
{
    (void)state;
    const double clearance = 0.7;
    for (int router = 0; router < 3; router++) {
        bool cone = router == 2;
        ur_ruled ruled;
        if (cone) {
            ur_curve *curve;
            assert_int_equal(ur_curve_new_circle(60, &curve, NULL), UR_OK);
            assert_int_equal(ur_ruled_cone(curve, ur_vec3_make(0, 0, 80), 1.0, &ruled, NULL),
                             UR_OK);
        } else
            ruled = cylinder(40, 100);
        ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 48, 0.01);
        ur_bending_options options = router == 1 ? router_options() : laser_options();
        options.kerf = 0.2;
        options.min_web = 0.6;
        if (cone) {
            options.min_radius = 10;
            options.hinge_cut_length = 10;
            options.hinge_connection = 2;
            options.hinge_distance = 1;
        }
        ur_piece piece = bent_piece(&nets, &ruled, &options);
        size_t first = piece.path_count;
        ur_joint_options joints = {.lap = !cone,
                                   .tab_depth = 10,
                                   .tab_angle = 45,
                                   .lap_width = 15,
                                   .thickness = cone ? 2 : 3,
                                   .lap_kerfs = true,
                                   .lap_kerf_margin = router == 1 ? 0 : CONNECTION};
        ur_error error;
        assert_int_equal(ur_pieces_add_joints(&piece, &nets, &joints, &error), UR_OK);
        if (!cone)
            assert_true(kerfs_outside_net(&piece, &nets.nets[0]) >= (router == 1 ? 4 : 10));
        size_t trimmed = 0;
        assert_int_equal(
            ur_piece_keep_kerfs_off_joints(&piece, first, clearance, 0.6, &trimmed, &error), UR_OK);
        assert_true(kerf_to_joint_lines(&piece, first) >= clearance - 1e-6);
        if (!cone)
            assert_true(kerfs_outside_net(&piece, &nets.nets[0]) >= (router == 1 ? 4 : 10));
        ur_piece_free(&piece);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
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
    options = router_options();
    options.facet_angle = 91;
    assert_int_equal(ur_piece_add_bending_kerfs(&piece, &net, NULL, &options, &error),
                     UR_ERROR_INPUT);
    options.facet_angle = 5;
    options.min_web = -1;
    assert_int_equal(ur_piece_add_bending_kerfs(&piece, &net, NULL, &options, &error),
                     UR_ERROR_INPUT);
    ur_piece_free(&piece);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ruling_parameters),
        cmocka_unit_test(test_router_cylinders_round),
        cmocka_unit_test(test_router_limits_warn),
        cmocka_unit_test(test_gentle_bend_needs_none),
        cmocka_unit_test(test_laser_hinge_cylinder),
        cmocka_unit_test(test_laser_cylinders_round),
        cmocka_unit_test(test_cone_grooves_only_where_tight),
        cmocka_unit_test(test_cone_apex_webs),
        cmocka_unit_test(test_hinges_and_joints_agree),
        cmocka_unit_test(test_merging_grooves_warn),
        cmocka_unit_test(test_too_few_rulings_warn),
        cmocka_unit_test(test_mesh_left_alone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
