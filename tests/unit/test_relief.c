/*
 * test_relief.c: kerfing cuts and overlap allowances (relief.c) and the
 * strain directions they follow (net.c).  The two cases of [Seed2018]
 * (docs/bibliography.md): a helicoid developed with the triangle method
 * under-covers and gets kerfing slits, with the quad method over-covers and
 * gets overlaps, exactly developed gets neither, the counts following the
 * documented formula recomputed here from the net's own figures; a hyperbolic
 * paraboloid flattened with ARAP in a cardboard-like limit gets both, every
 * slit where it belongs and inside the outline by the margin, measured here
 * independently.
 */
#include "test_support.h"

#include <stdlib.h>

#include "unroll/allow.h"
#include "unroll/flatten.h"

#define HELIX_RADIUS 30.0
#define HELIX_C 10.0 /* pitch / 2 pi */
#define WIDTH 25.0
#define OPENING 0.5
#define MARGIN 2.0

static ur_relief_limits cardboard_limits(void)
{
    ur_relief_limits limits = {0.005, 0.005, OPENING, MARGIN, false, true, true};
    return limits;
}

/* ---- Plane geometry, done here rather than trusted to GEOS ------------ */

static double point_segment_distance(ur_vec2 p, ur_vec2 a, ur_vec2 b)
{
    ur_vec2 ab = ur_vec2_sub(b, a);
    double length2 = ur_vec2_dot(ab, ab);
    double t = length2 > 0 ? ur_vec2_dot(ur_vec2_sub(p, a), ab) / length2 : 0;
    t = fmax(0, fmin(1, t));
    return ur_vec2_distance(p, ur_vec2_add_scaled(a, ab, t));
}

static bool segments_cross(ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d)
{
    double d1 = ur_vec2_cross(ur_vec2_sub(b, a), ur_vec2_sub(c, a));
    double d2 = ur_vec2_cross(ur_vec2_sub(b, a), ur_vec2_sub(d, a));
    double d3 = ur_vec2_cross(ur_vec2_sub(d, c), ur_vec2_sub(a, c));
    double d4 = ur_vec2_cross(ur_vec2_sub(d, c), ur_vec2_sub(b, c));
    return (d1 > 0) != (d2 > 0) && (d3 > 0) != (d4 > 0);
}

static double segment_distance(ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d)
{
    if (segments_cross(a, b, c, d))
        return 0;
    return fmin(fmin(point_segment_distance(a, c, d), point_segment_distance(b, c, d)),
                fmin(point_segment_distance(c, a, b), point_segment_distance(d, a, b)));
}

/* The distance of segment a b from the net's outline. */
static double outline_distance(const ur_net *net, ur_vec2 a, ur_vec2 b)
{
    double nearest = INFINITY;
    for (size_t i = 0; i < net->outline_count; i++)
        nearest = fmin(nearest, segment_distance(a, b, net->outline[i],
                                                 net->outline[(i + 1) % net->outline_count]));
    return nearest;
}

static bool inside_ring(const ur_vec2 *ring, size_t count, ur_vec2 p)
{
    bool inside = false;
    for (size_t i = 0, j = count - 1; i < count; j = i++)
        if ((ring[i].y > p.y) != (ring[j].y > p.y) &&
            p.x < ring[j].x + (ring[i].x - ring[j].x) * (p.y - ring[j].y) / (ring[i].y - ring[j].y))
            inside = !inside;
    return inside;
}

/* The shading triangle holding p, or SIZE_MAX. */
static size_t triangle_at(const ur_shading *shading, ur_vec2 p)
{
    for (size_t t = 0; t < shading->count; t++)
        if (inside_ring(shading->triangles[t], 3, p))
            return t;
    return SIZE_MAX;
}

/* ---- Pieces ------------------------------------------------------------ */

static ur_piece piece_of(const ur_net *net)
{
    ur_piece piece;
    ur_error error;
    if (ur_piece_from_net(net, NULL, &piece, &error) != UR_OK)
        fail_msg("piece: %s", error.message);
    return piece;
}

static void relieve(ur_piece *piece, const ur_net *net, const ur_relief_limits *limits)
{
    ur_error error;
    if (ur_piece_add_relief(piece, net, limits, &error) != UR_OK)
        fail_msg("relief: %s", error.message);
}

static size_t paths_of(const ur_piece *piece, ur_op op)
{
    size_t count = 0;
    for (size_t i = 0; i < piece->path_count; i++)
        count += piece->paths[i].op == op;
    return count;
}

static const ur_allowance_record *record_of(const ur_piece *piece, ur_allowance_kind kind)
{
    for (size_t i = 0; i < piece->record_count; i++)
        if (piece->records[i].kind == kind)
            return &piece->records[i];
    return NULL;
}

static size_t records_of(const ur_piece *piece, ur_allowance_kind kind)
{
    size_t count = 0;
    for (size_t i = 0; i < piece->record_count; i++)
        count += piece->records[i].kind == kind;
    return count;
}

/* ---- The strain direction of a known map ------------------------------- */

/* Two triangles of a unit square in a tilted plane laid flat by R(angle) diag(a, b) R(-angle). */
static ur_net known_map(double a, double b, double angle)
{
    double c = cos(angle), s = sin(angle);
    ur_vec3 u = {0.6, 0.8, 0}, v = {0, 0, 1};
    ur_vec2 square[4] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    ur_vec3 vertices[4];
    ur_vec2 layout[4];
    for (int k = 0; k < 4; k++) {
        ur_vec2 p = square[k];
        vertices[k] = ur_vec3_add(ur_vec3_scale(u, p.x), ur_vec3_scale(v, p.y));
        double x = c * p.x + s * p.y, y = -s * p.x + c * p.y; /* R(-angle) */
        x *= a;
        y *= b;
        layout[k] = ur_vec2_make(c * x - s * y, s * x + c * y);
    }
    size_t triangles[2][3] = {{0, 1, 2}, {0, 2, 3}};
    ur_mesh mesh = {vertices, 4, triangles, 2, NULL, 1};
    ur_flat_piece flat;
    ur_net net;
    assert_int_equal(ur_flat_piece_measure(&mesh, layout, &flat, NULL), UR_OK);
    assert_int_equal(ur_net_from_flat(&mesh, &flat, "known", &net, NULL), UR_OK);
    ur_flat_piece_free(&flat);
    return net;
}

static void assert_axis(ur_vec2 direction, ur_vec2 expected)
{
    assert_true(fabs(ur_vec2_length(direction) - 1) <= 1e-12);
    if (!(fabs(fabs(ur_vec2_dot(direction, expected)) - 1) <= 1e-12))
        fail_msg("direction (%g, %g), expected +-(%g, %g)", direction.x, direction.y, expected.x,
                 expected.y);
}

static void test_direction_of_known_map(void **state)
{
    (void)state;
    double angle = 0.6;
    ur_vec2 along = {cos(angle), sin(angle)}, across = {-sin(angle), cos(angle)};
    /* Stretched 3 % along `along`, shrunk 1 % across: the stretch dominates. */
    ur_net net = known_map(1.03, 0.99, angle);
    assert_int_equal(net.shading.count, 2);
    assert_non_null(net.shading.direction);
    for (size_t t = 0; t < 2; t++) {
        assert_relative(net.shading.strain[t], 0.03, 1e-9);
        assert_axis(net.shading.direction[t], along);
    }
    ur_net_free(&net);
    /* Stretched 1 %, shrunk 4 % across: the compression dominates, across. */
    net = known_map(1.01, 0.96, angle);
    for (size_t t = 0; t < 2; t++) {
        assert_relative(net.shading.strain[t], -0.04, 1e-9);
        assert_axis(net.shading.direction[t], across);
    }
    ur_piece piece = piece_of(&net);
    assert_non_null(piece.shading.direction);
    assert_axis(piece.shading.direction[0], across);
    ur_piece_free(&piece);
    ur_net_free(&net);
}

/* The known map relieved: one region, slits across its direction, the count by the formula. */
static void test_known_map_slits(void **state)
{
    (void)state;
    double angle = 0.6;
    ur_vec2 across = {-sin(angle), cos(angle)};
    ur_net net = known_map(1.0, 0.96, angle); /* 4 % short across: kerfing */
    ur_piece piece = piece_of(&net);
    ur_relief_limits limits = cardboard_limits();
    limits.margin = 0.5;
    limits.opening = 0.25;
    relieve(&piece, &net, &limits);
    const ur_allowance_record *record = record_of(&piece, UR_ALLOWANCE_KERFING);
    assert_non_null(record);
    assert_int_equal(records_of(&piece, UR_ALLOWANCE_OVERLAP), 0);
    assert_relative(record->value, 0.04, 1e-9);
    assert_relative(record->limit, 0.005, 0);
    /*
     * The longest line along `across` through the flat square crosses it
     * along the image of the 3D direction (-sin 0.6, cos 0.6), whose
     * longest chord in the 10 x 10 square is 10 / cos 0.6 = 12.1 mm; flat,
     * 0.96 of it, missing 0.04 / 0.96 of its flat length: 0.485 mm.  The
     * 64 lines sampled find between 0.47 and 0.485 mm: two slits of 0.25.
     */
    assert_int_equal(record->count, 2);
    assert_false(record->warning);
    for (size_t i = 1; i < piece.path_count; i++) {
        const ur_path *path = &piece.paths[i];
        assert_int_equal(path->op, UR_OP_KERF);
        ur_vec2 d = ur_vec2_sub(path->points[1], path->points[0]);
        /* across the direction of needed stretch */
        assert_true(fabs(ur_vec2_dot(d, across)) <= 1e-9 * ur_vec2_length(d));
        assert_true(outline_distance(&net, path->points[0], path->points[1]) >= 0.5 - 1e-9);
    }
    ur_piece_free(&piece);
    ur_net_free(&net);
}

/* ---- The helicoid, developed three ways -------------------------------- */

static ur_net_list helicoid(ur_method method, size_t n)
{
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(
        ur_curve_new_helix(HELIX_RADIUS, 2 * M_PI * HELIX_C, 0, M_PI / 2, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, 0, WIDTH, &ruled, NULL), UR_OK);
    ur_net_list nets = develop(&ruled, method, n, 0.01);
    ur_ruled_free(&ruled);
    assert_int_equal(nets.count, 1);
    return nets;
}

/* ceil(|area_3d - flat_area| / mean ruling length / opening), from the net's own figures. */
static size_t expected_slits(const ur_net *net)
{
    double total = 0;
    for (size_t i = 0; i < net->ruling_count; i++)
        total += ur_vec2_distance(net->rulings[i].start, net->rulings[i].end);
    double mean = total / (double)net->ruling_count;
    return (size_t)ceil(fabs(net->area_3d - net->flat_area) / mean / OPENING);
}

static void test_triangle_method_gets_kerfing(void **state)
{
    (void)state;
    ur_net_list nets = helicoid(UR_METHOD_TRIANGLE, 8);
    const ur_net *net = &nets.nets[0];
    double coverage = net->flat_area / net->area_3d;
    assert_true(coverage < 0.99); /* the triangle method under-covers */
    ur_piece piece = piece_of(net);
    ur_relief_limits limits = cardboard_limits();
    relieve(&piece, net, &limits);
    assert_int_equal(records_of(&piece, UR_ALLOWANCE_OVERLAP), 0);
    assert_int_equal(records_of(&piece, UR_ALLOWANCE_KERFING), 1);
    assert_int_equal(paths_of(&piece, UR_OP_MARK), 0);
    const ur_allowance_record *record = record_of(&piece, UR_ALLOWANCE_KERFING);
    size_t expected = expected_slits(net);
    print_message("triangle n=8: coverage %.4f, %zu kerfing slits\n", coverage, expected);
    assert_true(expected >= 2);
    assert_int_equal(record->count, expected);
    assert_false(record->warning);
    assert_relative(record->value, 1 - coverage, 1e-12);
    assert_int_equal(paths_of(&piece, UR_OP_KERF), expected);
    for (size_t i = 1; i < piece.path_count; i++) {
        const ur_path *path = &piece.paths[i];
        assert_int_equal(path->count, 2);
        double distance = outline_distance(net, path->points[0], path->points[1]);
        assert_true(distance >= MARGIN - 1e-6);
        assert_true(inside_ring(net->outline, net->outline_count, path->points[0]));
    }
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
}

static void test_quad_method_gets_overlaps(void **state)
{
    (void)state;
    ur_net_list nets = helicoid(UR_METHOD_QUAD, 8);
    const ur_net *net = &nets.nets[0];
    double coverage = net->flat_area / net->area_3d;
    assert_true(coverage > 1.01); /* the quad method over-covers */
    ur_piece piece = piece_of(net);
    ur_relief_limits limits = cardboard_limits();
    relieve(&piece, net, &limits);
    assert_int_equal(records_of(&piece, UR_ALLOWANCE_KERFING), 0);
    assert_int_equal(records_of(&piece, UR_ALLOWANCE_OVERLAP), 1);
    const ur_allowance_record *record = record_of(&piece, UR_ALLOWANCE_OVERLAP);
    size_t expected = expected_slits(net);
    print_message("quad n=8: coverage %.4f, %zu overlap slits\n", coverage, expected);
    assert_true(expected >= 2);
    assert_int_equal(record->count, expected);
    assert_false(record->warning);
    assert_relative(record->value, coverage - 1, 1e-12);
    assert_int_equal(paths_of(&piece, UR_OP_KERF), expected);
    assert_int_equal(paths_of(&piece, UR_OP_MARK), expected);
    double zones = 0;
    for (size_t i = 1; i < piece.path_count; i++) {
        const ur_path *path = &piece.paths[i];
        if (path->op == UR_OP_MARK) {
            assert_true(path->closed);
            zones += fabs(ur_polygon_signed_area(path->points, path->count));
            continue;
        }
        /* from the outline into the net, its inner end the margin inside */
        ur_vec2 start = path->points[0], end = path->points[path->count - 1];
        assert_true(outline_distance(net, start, start) <= 1e-6);
        assert_true(outline_distance(net, end, end) >= MARGIN - 1e-6);
    }
    /* zones of width excess / n along slits a little shorter than the rulings */
    double excess = net->flat_area - net->area_3d;
    assert_true(zones > 0.5 * excess && zones < 1.01 * excess);
    ur_piece_free(&piece);

    /* darts instead: one V each, no zones */
    piece = piece_of(net);
    limits.darts = true;
    relieve(&piece, net, &limits);
    assert_int_equal(paths_of(&piece, UR_OP_KERF), expected);
    assert_int_equal(paths_of(&piece, UR_OP_MARK), 0);
    for (size_t i = 1; i < piece.path_count; i++)
        assert_int_equal(piece.paths[i].count, 3);
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
}

static void test_exact_net_gets_neither(void **state)
{
    (void)state;
    ur_net_list nets = helicoid(UR_METHOD_EXACT, 8);
    const ur_net *net = &nets.nets[0];
    ur_piece piece = piece_of(net);
    size_t paths = piece.path_count;
    ur_relief_limits limits = cardboard_limits();
    limits.max_stretch = limits.max_compression = 0;
    relieve(&piece, net, &limits);
    assert_int_equal(piece.record_count, 0);
    assert_int_equal(piece.path_count, paths);
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
}

/* Selecting one kind leaves the other out. */
static void test_kinds_selected(void **state)
{
    (void)state;
    ur_net_list nets = helicoid(UR_METHOD_TRIANGLE, 8);
    ur_piece piece = piece_of(&nets.nets[0]);
    ur_relief_limits limits = cardboard_limits();
    limits.kerfing = false;
    relieve(&piece, &nets.nets[0], &limits);
    assert_int_equal(piece.record_count, 0);
    assert_int_equal(piece.path_count, 1);
    limits.kerfing = true;
    limits.opening = 0;
    ur_error error;
    assert_int_equal(ur_piece_add_relief(&piece, &nets.nets[0], &limits, &error), UR_ERROR_INPUT);
    ur_piece_free(&piece);
    ur_net_list_free(&nets);
}

/* ---- The hyperbolic paraboloid, flattened ------------------------------ */

static ur_vec3 saddle(double s, double t)
{
    double x = 100 * s - 50, y = 100 * t - 50;
    return ur_vec3_make(x, y, x * y / 100);
}

/* The saddle as an n x n grid of quads cut in two, flattened with ARAP, as a net. */
static ur_net saddle_net(size_t n)
{
    size_t columns = n + 1;
    ur_mesh mesh = {0};
    mesh.vertex_count = columns * columns;
    mesh.triangle_count = 2 * n * n;
    mesh.vertices = malloc(mesh.vertex_count * sizeof *mesh.vertices);
    mesh.triangles = malloc(mesh.triangle_count * sizeof *mesh.triangles);
    assert_non_null(mesh.vertices);
    assert_non_null(mesh.triangles);
    mesh.group_count = 1;
    for (size_t j = 0; j <= n; j++)
        for (size_t i = 0; i <= n; i++)
            mesh.vertices[j * columns + i] = saddle((double)i / n, (double)j / n);
    size_t t = 0;
    for (size_t j = 0; j < n; j++)
        for (size_t i = 0; i < n; i++) {
            size_t a = j * columns + i, b = a + 1, c = b + columns, d = a + columns;
            size_t first[3] = {a, b, c}, second[3] = {a, c, d};
            memcpy(mesh.triangles[t++], first, sizeof first);
            memcpy(mesh.triangles[t++], second, sizeof second);
        }
    ur_flat_piece flat;
    ur_net net;
    ur_error error;
    if (ur_flatten(&mesh, NULL, &flat, &error) != UR_OK)
        fail_msg("flatten: %s", error.message);
    assert_int_equal(ur_net_from_flat(&mesh, &flat, "saddle", &net, NULL), UR_OK);
    ur_flat_piece_free(&flat);
    free(mesh.vertices);
    free(mesh.triangles);
    return net;
}

/* The kerfing slits of a saddle: inside by the margin, where the net is short. */
static void check_kerfing(const ur_net *net, const ur_piece *piece, double limit)
{
    size_t slits = 0;
    for (size_t i = 1; i < piece->path_count; i++) {
        const ur_path *path = &piece->paths[i];
        assert_int_equal(path->op, UR_OP_KERF);
        assert_int_equal(path->count, 2);
        assert_true(outline_distance(net, path->points[0], path->points[1]) >= MARGIN - 1e-6);
        ur_vec2 middle = ur_vec2_scale(ur_vec2_add(path->points[0], path->points[1]), 0.5);
        size_t t = triangle_at(&net->shading, middle);
        assert_true(t != SIZE_MAX);
        assert_true(net->shading.strain[t] < -limit); /* the flat net is short there */
        slits++;
    }
    size_t recorded = 0;
    for (size_t i = 0; i < piece->record_count; i++) {
        assert_int_equal(piece->records[i].kind, UR_ALLOWANCE_KERFING);
        assert_true(piece->records[i].value > limit);
        recorded += piece->records[i].count;
    }
    assert_true(slits >= recorded && recorded > 0);
    print_message("saddle: %zu kerfing regions, %zu slit lines, %zu slits\n", piece->record_count,
                  recorded, slits);
}

/* The overlap slits of a saddle: from the outline, through where the net is long. */
static void check_overlaps(const ur_net *net, const ur_piece *piece, double limit)
{
    size_t slits = 0, zones = 0;
    for (size_t i = 1; i < piece->path_count; i++) {
        const ur_path *path = &piece->paths[i];
        if (path->op == UR_OP_MARK) {
            zones++;
            continue;
        }
        assert_int_equal(path->op, UR_OP_KERF);
        ur_vec2 start = path->points[0], end = path->points[1];
        assert_true(outline_distance(net, start, start) <= 1e-6);
        assert_true(outline_distance(net, end, end) >= MARGIN - 1e-6);
        bool long_there = false; /* some point of it lies where the net is too long */
        for (int k = 1; k < 100 && !long_there; k++) {
            size_t t = triangle_at(&net->shading,
                                   ur_vec2_add_scaled(start, ur_vec2_sub(end, start), k / 100.0));
            long_there = t != SIZE_MAX && net->shading.strain[t] > limit;
        }
        assert_true(long_there);
        slits++;
    }
    size_t recorded = 0;
    for (size_t i = 0; i < piece->record_count; i++) {
        assert_int_equal(piece->records[i].kind, UR_ALLOWANCE_OVERLAP);
        recorded += piece->records[i].count;
    }
    assert_true(slits == recorded && recorded > 0);
    assert_true(zones >= slits);
    print_message("saddle: %zu overlap regions, %zu slits, %zu zones\n", piece->record_count, slits,
                  zones);
}

static void test_saddle_gets_both(void **state)
{
    (void)state;
    ur_net net = saddle_net(24);
    print_message("saddle: stretch %.3f %%, compression %.3f %%\n", 100 * net.max_stretch,
                  100 * net.max_compression);
    ur_relief_limits limits = cardboard_limits();
    ur_piece both = piece_of(&net);
    relieve(&both, &net, &limits);
    assert_true(records_of(&both, UR_ALLOWANCE_KERFING) > 0);
    assert_true(records_of(&both, UR_ALLOWANCE_OVERLAP) > 0);
    ur_piece_free(&both);

    limits.overlaps = false;
    ur_piece kerfing = piece_of(&net);
    relieve(&kerfing, &net, &limits);
    check_kerfing(&net, &kerfing, limits.max_stretch);
    ur_piece_free(&kerfing);

    limits.overlaps = true;
    limits.kerfing = false;
    ur_piece overlaps = piece_of(&net);
    relieve(&overlaps, &net, &limits);
    check_overlaps(&net, &overlaps, limits.max_compression);
    ur_piece_free(&overlaps);
    ur_net_free(&net);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_direction_of_known_map),
        cmocka_unit_test(test_known_map_slits),
        cmocka_unit_test(test_triangle_method_gets_kerfing),
        cmocka_unit_test(test_quad_method_gets_overlaps),
        cmocka_unit_test(test_exact_net_gets_neither),
        cmocka_unit_test(test_kinds_selected),
        cmocka_unit_test(test_saddle_gets_both),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
