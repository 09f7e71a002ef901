/*
 * test_joints.c: glue tabs and laps on seams, with their labels.
 *
 * A closed cylinder's one seam gets one tab whose area is worked out here
 * (a trapezoid tapered at the tab angle from the seam, the stock's
 * thickness of it a band with its own fold); a helicoid split into pieces
 * gets one tab per seam and the same label on both sides; every edge of
 * an unfolded icosphere's seams gets a tab of its own (or a warning), off
 * its piece and off the other tabs (the grown outline is simple and as
 * large as the net and the tabs together); a seam that is a closed loop
 * (a grid's centre quad) gets a tab on each edge and its labels; laps mark
 * the zone on both pieces; two turns of a helicoid, in cardboard and in
 * plywood, get every seam joined, by a splice piece where nothing fits;
 * the icosphere's labels stand a word's space apart.
 * Geometry is checked with GEOS, independently of the code under test.
 *
 * Run from the repository root (it reads samples/icosphere.obj).
 */
#include "test_support.h"
#include "test_geos.h"
#include <stdlib.h>

#include "unroll/allow.h"
#include "unroll/flatten.h"
#include "unroll/io.h"
#include "unroll/mesh.h"

static GEOSGeometry *line_of(const ur_vec2 *points, size_t count)
{
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)count, 2);
    for (size_t i = 0; i < count; i++)
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, points[i].x, points[i].y);
    GEOSGeometry *line = GEOSGeom_createLineString_r(geos, sequence);
    assert_non_null(line);
    return line;
}

static double area_of(const GEOSGeometry *g)
{
    double area;
    assert_int_equal(GEOSArea_r(geos, g, &area), 1);
    return area;
}

static size_t count_op(const ur_piece *piece, ur_op op)
{
    size_t count = 0;
    for (size_t k = 0; k < piece->path_count; k++)
        count += piece->paths[k].op == op;
    return count;
}

static size_t count_records(const ur_piece *piece, ur_allowance_kind kind, bool warning)
{
    size_t count = 0;
    for (size_t k = 0; k < piece->record_count; k++)
        count += piece->records[k].kind == kind && piece->records[k].warning == warning;
    return count;
}

/* How many joints the piece's records say went on (a record counts all of a seam side's tabs). */
static size_t count_joints(const ur_piece *piece)
{
    size_t count = 0;
    for (size_t k = 0; k < piece->record_count; k++)
        if (piece->records[k].kind == UR_ALLOWANCE_JOINT && !piece->records[k].warning)
            count += piece->records[k].count;
    return count;
}

static ur_piece *pieces_of(const ur_net_list *nets)
{
    ur_piece *pieces = calloc(nets->count, sizeof *pieces);
    assert_non_null(pieces);
    for (size_t k = 0; k < nets->count; k++)
        assert_int_equal(ur_piece_from_net(&nets->nets[k], NULL, &pieces[k], NULL), UR_OK);
    return pieces;
}

static void free_pieces(ur_piece *pieces, size_t count)
{
    for (size_t k = 0; k < count; k++)
        ur_piece_free(&pieces[k]);
    free(pieces);
}

static ur_joint_options tab_options(const ur_font *font)
{
    ur_joint_options options = {.lap = false,
                                .tab_depth = 10,
                                .tab_angle = 45,
                                .lap_width = 15,
                                .thickness = 2,
                                .font = font,
                                .label_height = 5,
                                .name_pieces = false};
    return options;
}

/*
 * No other line of the piece (labels, folds, marks) crosses its grown
 * outline: each keeps off it or touches it only at a fold's ends.
 */
static void check_nothing_crosses_outline(const ur_piece *piece)
{
    GEOSGeometry *outline = polygon(piece->paths[0].points, piece->paths[0].count);
    GEOSGeometry *inside = GEOSBuffer_r(geos, outline, 1e-6, 8);
    for (size_t k = 1; k < piece->path_count; k++) {
        const ur_path *path = &piece->paths[k];
        for (size_t i = 0; i < path->count; i++) {
            GEOSGeometry *point =
                GEOSGeom_createPointFromXY_r(geos, path->points[i].x, path->points[i].y);
            if (GEOSContains_r(geos, inside, point) != 1)
                fail_msg("piece %s: path %zu (op %d) point %zu lies outside its outline",
                         piece->name, k, path->op, i);
            GEOSGeom_destroy_r(geos, point);
        }
    }
    GEOSGeom_destroy_r(geos, inside);
    GEOSGeom_destroy_r(geos, outline);
}

/* Every engraved point lies inside the net's own outline (not on a tab). */
static void check_engraving_inside(const ur_piece *piece, const ur_net *net)
{
    GEOSGeometry *outline = polygon(net->outline, net->outline_count);
    for (size_t k = 0; k < piece->path_count; k++) {
        const ur_path *path = &piece->paths[k];
        if (path->op != UR_OP_ENGRAVE)
            continue;
        for (size_t i = 0; i < path->count; i++) {
            GEOSGeometry *point =
                GEOSGeom_createPointFromXY_r(geos, path->points[i].x, path->points[i].y);
            assert_int_equal(GEOSContains_r(geos, outline, point), 1);
            GEOSGeom_destroy_r(geos, point);
        }
    }
    GEOSGeom_destroy_r(geos, outline);
}

static void test_cylinder_tab(void **state)
{
    (void)state;
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(40, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 120, &ruled, NULL), UR_OK);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 8, 0.01);
    ur_piece *pieces = pieces_of(&nets);
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_joint_options options = tab_options(font);
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);

    /* One tab: a trapezoid on the 120 mm seam, 2 mm of band and 10 mm of
     * depth high, its sides tapered at 45 degrees from the seam up, so its
     * top is 120 - 2 * 12 / tan(45 degrees) = 96 mm long. */
    double expected = nets.nets[0].flat_area + (120 + 96) / 2.0 * 12;
    GEOSGeometry *grown = polygon(pieces[0].paths[0].points, pieces[0].paths[0].count);
    assert_int_equal(GEOSisValid_r(geos, grown), 1);
    assert_relative(area_of(grown), expected, 1e-9);
    GEOSGeom_destroy_r(geos, grown);
    assert_int_equal(count_records(&pieces[0], UR_ALLOWANCE_JOINT, false), 1);
    /* Two folds: at the seam and at the band's edge. */
    assert_int_equal(count_op(&pieces[0], UR_OP_SCORE), 2);
    /* The label A1 on both sides of the seam, inside the net. */
    assert_int_equal(count_records(&pieces[0], UR_ALLOWANCE_LABEL, false), 2);
    check_engraving_inside(&pieces[0], &nets.nets[0]);
    check_nothing_crosses_outline(&pieces[0]);

    ur_font_close(font);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/* Whether a label record's reason names the label (as 'A7'). */
static bool names_label(const ur_allowance_record *record, const char *label)
{
    char quoted[32];
    snprintf(quoted, sizeof quoted, "'%s'", label);
    return record->kind == UR_ALLOWANCE_LABEL && !record->warning && strstr(record->reason, quoted);
}

/*
 * The developed pieces of a helicoid (tangents of a helix of radius 30 mm
 * and pitch 20 pi mm, 25 mm long) up to angle end; ruled keeps the
 * surface, for ur_ruled_free.
 */
static ur_net_list helicoid_nets(double end, ur_ruled *ruled)
{
    ur_curve *curve;
    assert_int_equal(ur_curve_new_helix(30, 20 * M_PI, 0, end, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, 0, 25, ruled, NULL), UR_OK);
    return develop(ruled, UR_METHOD_EXACT, 8, 0.01);
}

static void test_helicoid_labels_pair(void **state)
{
    (void)state;
    ur_ruled ruled;
    /* 2.5 turns develop to about 850 degrees: 3 pieces with room for tabs between. */
    ur_net_list nets = helicoid_nets(5 * M_PI, &ruled);
    assert_true(nets.count >= 3);
    ur_piece *pieces = pieces_of(&nets);
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_joint_options options = tab_options(font);
    options.thickness = 0.3; /* paper: no band */
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    size_t tabs = 0;
    for (size_t k = 0; k < nets.count; k++)
        tabs += count_records(&pieces[k], UR_ALLOWANCE_JOINT, false);
    assert_int_equal(tabs, nets.count - 1); /* one per seam */
    for (int seam = 1; seam < (int)nets.count; seam++) {
        char label[16];
        ur_seam_label(seam, label, sizeof label);
        /* Seam j joins nets j - 1 and j: each carries the label once, nobody else. */
        for (size_t k = 0; k < nets.count; k++) {
            size_t found = 0;
            for (size_t r = 0; r < pieces[k].record_count; r++)
                found += names_label(&pieces[k].records[r], label);
            bool expected = k + 1 == (size_t)seam || k == (size_t)seam;
            assert_int_equal(found, expected ? 1 : 0);
        }
    }
    for (size_t k = 0; k < nets.count; k++) {
        check_engraving_inside(&pieces[k], &nets.nets[k]);
        check_nothing_crosses_outline(&pieces[k]);
    }
    ur_font_close(font);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/*
 * A helicoid's pieces are sectors of a ring: the centre of a piece's box
 * lies in the ring's hole, and a name sought from there was engraved
 * smaller (3.2 and 4 mm of 5 on the README's helicoid) beside the inner
 * edge.  From the centre of the largest circle inside the outline each
 * name has its full height.
 */
static void test_names_full_height_on_sectors(void **state)
{
    (void)state;
    ur_ruled ruled;
    ur_net_list nets = helicoid_nets(4 * M_PI, &ruled);
    assert_true(nets.count >= 2);
    ur_piece *pieces = pieces_of(&nets);
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_joint_options options = tab_options(font);
    options.name_pieces = true;
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    for (size_t k = 0; k < nets.count; k++) {
        size_t names = 0;
        for (size_t r = 0; r < pieces[k].record_count; r++)
            if (names_label(&pieces[k].records[r], pieces[k].name)) {
                names++;
                assert_true(pieces[k].records[r].value == options.label_height);
            }
        assert_int_equal(names, 1);
        check_engraving_inside(&pieces[k], &nets.nets[k]);
    }
    ur_font_close(font);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

static void test_seam_labels(void **state)
{
    (void)state;
    char label[16];
    ur_seam_label(1, label, sizeof label);
    assert_string_equal(label, "A1");
    ur_seam_label(99, label, sizeof label);
    assert_string_equal(label, "A99");
    ur_seam_label(100, label, sizeof label);
    assert_string_equal(label, "B1");
    ur_seam_label(26 * 99 + 1, label, sizeof label);
    assert_string_equal(label, "AA1");
}

/* The unfolded icosphere's nets with their seams, as the command line makes them. */
static ur_net_list icosphere_nets(void)
{
    size_t cut_edges;
    ur_net_list nets = unfolded_nets("samples/icosphere.obj", &cut_edges);
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    return nets;
}

static void test_unfolded_tabs_clear(void **state)
{
    (void)state;
    ur_net_list nets = icosphere_nets();
    ur_piece *pieces = pieces_of(&nets);
    ur_error error;
    ur_joint_options options = tab_options(NULL);
    options.tab_depth = 3; /* the icosphere's edges are about 9 mm */
    options.thickness = 0.3;
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    size_t tabs = 0, warnings = 0, seams = (size_t)ur_net_list_last_seam(&nets);
    for (size_t k = 0; k < nets.count; k++) {
        tabs += count_joints(&pieces[k]);
        warnings += count_records(&pieces[k], UR_ALLOWANCE_JOINT, true);
        /* The grown outline is simple and holds the whole net. */
        GEOSGeometry *grown = polygon(pieces[k].paths[0].points, pieces[k].paths[0].count);
        GEOSGeometry *net = polygon(nets.nets[k].outline, nets.nets[k].outline_count);
        assert_int_equal(GEOSisValid_r(geos, grown), 1);
        GEOSGeometry *outside = GEOSDifference_r(geos, net, grown);
        assert_true(area_of(outside) <= 1e-9 * area_of(net));
        GEOSGeom_destroy_r(geos, outside);
        /* Each tab's fold is a seam of this piece: the tabs' area is outside the net. */
        assert_true(area_of(grown) > area_of(net));
        /*
         * Every tab on the outline, as a part of its own: the outline is
         * grown by splicing each tab in where its base lies, and none may
         * be lost, nor two run into one.
         */
        GEOSGeometry *tabs_only = GEOSDifference_r(geos, grown, net);
        assert_int_equal((size_t)GEOSGetNumGeometries_r(geos, tabs_only), count_joints(&pieces[k]));
        assert_relative(area_of(tabs_only), area_of(grown) - area_of(net), 1e-9);
        GEOSGeom_destroy_r(geos, tabs_only);
        GEOSGeom_destroy_r(geos, grown);
        GEOSGeom_destroy_r(geos, net);
        check_nothing_crosses_outline(&pieces[k]);
    }
    /* The seams' edges, counted on their sides: each edge is on two. */
    size_t edges = 0;
    for (size_t k = 0; k < nets.count; k++)
        for (size_t i = 0; i < nets.nets[k].seam_side_count; i++)
            edges += nets.nets[k].seam_sides[i].count - 1;
    edges /= 2;
    print_message("%zu seams, %zu edges: %zu tabs, %zu without\n", seams, edges, tabs, warnings);
    /* One tab per edge (no two edges of an icosphere run on straight), or a warning. */
    assert_int_equal(tabs + warnings, edges);
    assert_true(tabs >= edges * 9 / 10);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
}

/* Whether seam sides a and b of net end and begin at one point of the plane: they meet there. */
static bool flat_sides_meet(const ur_net *net, const ur_seam_side *a, const ur_seam_side *b)
{
    size_t n = net->outline_count;
    ur_vec2 a_start = net->outline[a->first % n],
            a_end = net->outline[(a->first + a->count - 1) % n];
    ur_vec2 b_start = net->outline[b->first % n],
            b_end = net->outline[(b->first + b->count - 1) % n];
    return ur_vec2_distance(a_end, b_start) < 1e-9 || ur_vec2_distance(b_end, a_start) < 1e-9;
}

/* How many records of the piece say the seam's two sides share one label. */
static size_t one_label_notes(const ur_piece *piece, const char *label)
{
    char note[48];
    snprintf(note, sizeof note, "seam %s: one label for both sides", label);
    size_t found = 0;
    for (size_t r = 0; r < piece->record_count; r++)
        found += piece->records[r].kind == UR_ALLOWANCE_LABEL && !piece->records[r].warning &&
                 strstr(piece->records[r].reason, note) != NULL;
    return found;
}

/*
 * The cube unfolded whole (no sheet): a cross, whose seams at its inner
 * corners have both sides on it, meeting there; those get their label
 * once, with a note, the others on both sides.
 */
static void test_label_once_where_sides_meet(void **state)
{
    (void)state;
    size_t cut_edges;
    ur_net_list nets = unfolded_nets("samples/cube.obj", &cut_edges);
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    ur_piece *pieces = pieces_of(&nets);
    ur_font *font;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_joint_options options = tab_options(font);
    options.thickness = 0.3;
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    size_t meeting = 0, apart = 0;
    for (int seam = 1; seam <= ur_net_list_last_seam(&nets); seam++) {
        const ur_seam_side *sides[2] = {NULL, NULL};
        size_t net_of[2] = {0, 0}, found = 0;
        for (size_t k = 0; k < nets.count; k++)
            for (size_t i = 0; i < nets.nets[k].seam_side_count; i++)
                if (nets.nets[k].seam_sides[i].seam == seam && found < 2) {
                    net_of[found] = k;
                    sides[found++] = &nets.nets[k].seam_sides[i];
                }
        assert_int_equal(found, 2);
        bool meet =
            net_of[0] == net_of[1] && flat_sides_meet(&nets.nets[net_of[0]], sides[0], sides[1]);
        char label[16];
        ur_seam_label(seam, label, sizeof label);
        size_t labels = 0, notes = 0;
        for (size_t k = 0; k < nets.count; k++) {
            for (size_t r = 0; r < pieces[k].record_count; r++)
                labels += names_label(&pieces[k].records[r], label);
            notes += one_label_notes(&pieces[k], label);
        }
        assert_int_equal(labels, meet ? 1 : 2);
        assert_int_equal(notes, meet ? 1 : 0);
        meeting += meet;
        apart += !meet;
    }
    assert_true(meeting >= 1 && apart >= 1); /* a cross has both */
    ur_font_close(font);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
}

/* A net of the given outline, its 3D points (x, y, 0) on the grid. */
static ur_net grid_net(const char *name, const ur_vec2 *flat, const ur_vec2 *grid, size_t count)
{
    ur_net net;
    memset(&net, 0, sizeof net);
    snprintf(net.name, sizeof net.name, "%s", name);
    net.outline = malloc(count * sizeof *net.outline);
    net.outline_3d = malloc(count * sizeof *net.outline_3d);
    assert_true(net.outline && net.outline_3d);
    for (size_t i = 0; i < count; i++) {
        net.outline[i] = flat[i];
        net.outline_3d[i] = ur_vec3_make(grid[i].x, grid[i].y, 0);
    }
    net.outline_count = count;
    net.flat_area = fabs(ur_polygon_signed_area(flat, count));
    return net;
}

/*
 * A 60 mm square of 3 x 3 quads whose centre quad is a piece of its own:
 * the centre's whole outline is one seam side, a closed loop, and so is the
 * rim of the hole it leaves in the frame.  The frame is one piece, cut
 * open along the grid line x = 20 below the hole (that slit is a second
 * seam, both of its sides on the frame) and laid out with the slit opened
 * by opening (mm), so that the frame's outline is a simple ring.
 */
static ur_net_list grid_with_centre(double opening)
{
    static const ur_vec2 centre[] = {{20, 20}, {40, 20}, {40, 40}, {20, 40}};
    static const ur_vec2 frame_grid[] = {{20, 0},  {60, 0},  {60, 60}, {0, 60},  {0, 0},  {20, 0},
                                         {20, 20}, {20, 40}, {40, 40}, {40, 20}, {20, 20}};
    ur_vec2 frame_flat[11];
    for (size_t i = 0; i < 11; i++)
        frame_flat[i] = frame_grid[i];
    frame_flat[5].x = frame_flat[6].x = 20 - opening; /* the slit's left side, opened */
    ur_net_list nets = {calloc(2, sizeof(ur_net)), 2};
    assert_non_null(nets.nets);
    nets.nets[0] = grid_net("P1", frame_flat, frame_grid, 11);
    nets.nets[1] = grid_net("P2", centre, centre, 4);
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    return nets;
}

/* Paper's joints for the frame: 5 mm tabs, 0.3 mm stock, 3 mm labels. */
static ur_joint_options frame_options(const ur_font *font)
{
    ur_joint_options options = tab_options(font);
    options.tab_depth = 5;
    options.thickness = 0.3;
    options.label_height = 3;
    return options;
}

/* Adds laps width mm wide (frame_options otherwise) to the nets' pieces, which must succeed. */
static void add_laps(ur_piece *pieces, const ur_net_list *nets, const ur_font *font, double width)
{
    ur_joint_options options = frame_options(font);
    options.lap = true;
    options.lap_width = width;
    ur_error error;
    if (ur_pieces_add_joints(pieces, nets, &options, &error) != UR_OK)
        fail_msg("ur_pieces_add_joints: %s", error.message);
}

/* Whether seam side k of the net ends where it starts (in 3D): a closed loop. */
static bool side_is_loop(const ur_net *net, size_t k)
{
    const ur_seam_side *side = &net->seam_sides[k];
    ur_vec3 a = net->outline_3d[side->first];
    ur_vec3 b = net->outline_3d[(side->first + side->count - 1) % net->outline_count];
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

static void test_loop_seams_joined(void **state)
{
    (void)state;
    ur_net_list nets = grid_with_centre(4);
    /* The seams found: the slit and the loop round the centre quad. */
    assert_int_equal(ur_net_list_last_seam(&nets), 2);
    assert_int_equal(nets.nets[1].seam_side_count, 1);
    assert_true(side_is_loop(&nets.nets[1], 0));
    assert_int_equal(nets.nets[1].seam_sides[0].count, 5); /* four edges, round to the start */
    ur_piece *pieces = pieces_of(&nets);
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_joint_options options = frame_options(font);
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    /* Each seam's label on both its sides: the loop's on both pieces, the slit's twice on the
     * frame. */
    for (int seam = 1; seam <= 2; seam++) {
        char label[16];
        ur_seam_label(seam, label, sizeof label);
        size_t found[2] = {0, 0};
        for (size_t k = 0; k < 2; k++)
            for (size_t r = 0; r < pieces[k].record_count; r++)
                found[k] += names_label(&pieces[k].records[r], label);
        size_t frame_side = nets.nets[0].seam_sides[0].seam == seam ? 0 : 1;
        bool loop = side_is_loop(&nets.nets[0], frame_side);
        assert_int_equal(found[0], loop ? 1 : 2);
        assert_int_equal(found[1], loop ? 1 : 0);
    }
    /*
     * The loop's four edges each get a tab of their own, on the centre
     * quad or into the hole: the pieces grow by four tapered tabs, each at
     * most 5 mm deep on its 20 mm edge and no larger than (20 + 10) / 2 * 5.
     */
    int loop_seam = nets.nets[1].seam_sides[0].seam;
    char loop_label[16], quoted[24];
    ur_seam_label(loop_seam, loop_label, sizeof loop_label);
    snprintf(quoted, sizeof quoted, "seam %s,", loop_label);
    size_t loop_tabs = 0;
    double grown_area = 0;
    for (size_t k = 0; k < nets.count; k++) {
        for (size_t r = 0; r < pieces[k].record_count; r++) {
            const ur_allowance_record *record = &pieces[k].records[r];
            if (record->kind == UR_ALLOWANCE_JOINT && !record->warning &&
                strstr(record->reason, quoted))
                loop_tabs += record->count;
        }
        GEOSGeometry *grown = polygon(pieces[k].paths[0].points, pieces[k].paths[0].count);
        assert_int_equal(GEOSisValid_r(geos, grown), 1);
        grown_area += area_of(grown) - nets.nets[k].flat_area;
        GEOSGeom_destroy_r(geos, grown);
        check_engraving_inside(&pieces[k], &nets.nets[k]);
        check_nothing_crosses_outline(&pieces[k]);
    }
    assert_int_equal(loop_tabs, 4);
    assert_true(grown_area > 4 * 0.2 * 5 * 20 * 0.5);
    assert_true(grown_area <= 4 * 75 + 2 * 20 * 5 + 1e-9); /* and the slit's, if any */
    ur_font_close(font);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
}

/*
 * The same frame with its slit opened 1 mm: a 5 mm tab finds room on
 * neither side of it, and the warning says why once, since both sides
 * meet the same (each other, 1 mm away).
 */
static void test_narrow_slit_said_once(void **state)
{
    (void)state;
    ur_net_list nets = grid_with_centre(1);
    ur_piece *pieces = pieces_of(&nets);
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_joint_options options = frame_options(font);
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    size_t warnings = 0;
    for (size_t r = 0; r < pieces[0].record_count; r++) {
        const ur_allowance_record *record = &pieces[0].records[r];
        if (record->kind != UR_ALLOWANCE_JOINT || !record->warning)
            continue;
        warnings++;
        print_message("%s\n", record->reason);
        const char *why = "on P1 the seam's other side comes within 1.0 mm (a narrow slit)";
        const char *first = strstr(record->reason, why);
        assert_non_null(first);
        assert_null(strstr(first + 1, why));
        assert_non_null(strstr(record->reason, "(a narrow slit), on either side: join it by hand"));
    }
    assert_int_equal(warnings, 1);
    ur_font_close(font);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
}

/* Whether the two pieces have the same outline, point for point. */
static bool same_outline(const ur_piece *a, const ur_piece *b)
{
    const ur_path *p = &a->paths[0], *q = &b->paths[0];
    if (p->count != q->count)
        return false;
    for (size_t i = 0; i < p->count; i++)
        if (p->points[i].x != q->points[i].x || p->points[i].y != q->points[i].y)
            return false;
    return true;
}

/* The piece's UR_ALLOWANCE_JOINT records, in order; whether they come one after another. */
static size_t joint_records(const ur_piece *piece, const ur_allowance_record **out, bool *together)
{
    size_t count = 0, first = 0, last = 0;
    for (size_t r = 0; r < piece->record_count; r++)
        if (piece->records[r].kind == UR_ALLOWANCE_JOINT) {
            if (count == 0)
                first = r;
            last = r;
            out[count++] = &piece->records[r];
        }
    *together = count == 0 || last - first + 1 == count;
    return count;
}

/*
 * Joints on the nets' pieces with options as given and again with labels
 * and names (font), which seeks the tabs beside them in a thread of their
 * own: the tabs come out as they do alone, outlines and joint records
 * alike, and each piece's joint records (the warnings held while the
 * labels went on, then a count per seam side) lie together, after the
 * labels beside the seams.  How many edges found no tab.
 */
static size_t check_tabs_beside_labels(const ur_net_list *nets, ur_joint_options options,
                                       const ur_font *font)
{
    ur_error error;
    ur_piece *alone = pieces_of(nets), *beside = pieces_of(nets);
    options.font = NULL;
    assert_int_equal(ur_pieces_add_joints(alone, nets, &options, &error), UR_OK);
    options.font = font;
    options.name_pieces = true;
    assert_int_equal(ur_pieces_add_joints(beside, nets, &options, &error), UR_OK);
    size_t warnings = 0, labels_first = 0;
    for (size_t k = 0; k < nets->count; k++) {
        assert_true(same_outline(&alone[k], &beside[k]));
        const ur_allowance_record *a[256], *b[256];
        assert_true(alone[k].record_count <= 256 && beside[k].record_count <= 256);
        bool together;
        size_t count = joint_records(&alone[k], a, &together);
        assert_int_equal(joint_records(&beside[k], b, &together), count);
        assert_true(together);
        for (size_t r = 0; r < count; r++) {
            assert_int_equal(a[r]->count, b[r]->count);
            assert_int_equal(a[r]->warning, b[r]->warning);
            assert_string_equal(a[r]->reason, b[r]->reason);
            warnings += a[r]->warning;
        }
        /* Before the joint records: those of the labels beside the seams, and nothing else. */
        for (const ur_allowance_record *r = beside[k].records; count > 0 && r < b[0]; r++) {
            assert_int_equal(r->kind, UR_ALLOWANCE_LABEL);
            labels_first++;
        }
    }
    assert_true(labels_first > 0);
    free_pieces(alone, nets->count);
    free_pieces(beside, nets->count);
    return warnings;
}

/* The icosphere's many tabs, and the narrow slit's warning, beside labels as alone. */
static void test_tabs_beside_labels_as_alone(void **state)
{
    (void)state;
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_net_list nets = icosphere_nets();
    ur_joint_options options = tab_options(NULL);
    options.tab_depth = 3;
    options.thickness = 0.3;
    options.label_height = 2;
    check_tabs_beside_labels(&nets, options, font);
    ur_net_list_free(&nets);
    nets = grid_with_centre(1);
    assert_int_equal(check_tabs_beside_labels(&nets, frame_options(NULL), font), 1);
    ur_net_list_free(&nets);
    ur_font_close(font);
}

/* What the progress callback heard: each phase's name, reports and last fraction. */
typedef struct heard {
    char phases[4][16];
    size_t phase_count, reports[4];
    double last[4];
    bool backwards;
} heard;

static void listen(void *context, const char *phase, double fraction)
{
    heard *h = context;
    if (h->phase_count == 0 || strcmp(h->phases[h->phase_count - 1], phase) != 0) {
        assert_true(h->phase_count < 4);
        snprintf(h->phases[h->phase_count], sizeof h->phases[0], "%s", phase);
        h->last[h->phase_count++] = 0.0;
    }
    size_t k = h->phase_count - 1;
    h->backwards = h->backwards || fraction < h->last[k] || fraction < 0 || fraction > 1;
    h->last[k] = fraction;
    h->reports[k]++;
}

/*
 * The progress callback hears the labels, then the tabs (with laps, the
 * laps, then the labels), each from 0 up to 1 and never back.
 */
static void test_progress_reported(void **state)
{
    (void)state;
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    for (int lap = 0; lap < 2; lap++) {
        ur_net_list nets = grid_with_centre(4);
        ur_piece *pieces = pieces_of(&nets);
        ur_joint_options options = frame_options(font);
        options.lap = lap;
        heard h = {0};
        options.progress = listen;
        options.progress_context = &h;
        assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
        assert_int_equal(h.phase_count, 2);
        assert_string_equal(h.phases[0], lap ? "laps" : "labels");
        assert_string_equal(h.phases[1], lap ? "labels" : "tabs");
        assert_false(h.backwards);
        for (size_t k = 0; k < 2; k++) {
            assert_true(h.reports[k] >= 2); /* the two seams' starts and the end */
            assert_true(h.last[k] == 1.0);
        }
        free_pieces(pieces, nets.count);
        ur_net_list_free(&nets);
    }
    ur_font_close(font);
}

/*
 * A plate with a V notch of the given angle (degrees), its two 40 mm
 * walls seams to two other plates, on which each wall's twin is a wall of
 * a slot 1 mm wide: no tab fits there, so both tabs must go into the
 * notch, where near its point they are in each other's way.  Each net's
 * 3D points are its flat ones at its own height, the seams' ends shared.
 */
static ur_net_list notch_and_slots(double angle)
{
    double half = 0.5 * angle * M_PI / 180.0;
    ur_vec2 v = {50, 20}, p = {50 - 40 * sin(half), 20 + 40 * cos(half)},
            q = {50 + 40 * sin(half), 20 + 40 * cos(half)};
    const ur_vec2 plate[] = {{0, 0}, {100, 0}, {100, 70}, q, v, p, {0, 70}};
    const ur_vec2 slot[] = {{0, 0},   {60, 0},  {60, 60}, {31, 60},
                            {31, 20}, {30, 20}, {30, 60}, {0, 60}};
    ur_net_list nets = {calloc(3, sizeof(ur_net)), 3};
    assert_non_null(nets.nets);
    nets.nets[0] = grid_net("P1", plate, plate, 7);
    for (int k = 1; k <= 2; k++) {
        char name[16];
        snprintf(name, sizeof name, "P%d", k + 1);
        nets.nets[k] = grid_net(name, slot, slot, 8);
        for (size_t i = 0; i < 8; i++)
            nets.nets[k].outline_3d[i].z = 10.0 * k;
        /* The slot's left wall, (30, 20) up to (30, 60), is a notch wall run the other way. */
        nets.nets[k].outline_3d[5] = nets.nets[0].outline_3d[k == 1 ? 5 : 4];
        nets.nets[k].outline_3d[6] = nets.nets[0].outline_3d[k == 1 ? 4 : 3];
    }
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    assert_int_equal(ur_net_list_last_seam(&nets), 2);
    return nets;
}

/*
 * Two tabs in a V notch of 12 degrees: the first one joined goes on (2.5
 * mm deep, 12 mm from each end of its wall), and the second then finds
 * no room beside it, not even a fifth of the depth deep, which left it to
 * join by hand, until the first is lowered on its base.  Both must go on,
 * off each other and off the plate: its grown outline a simple ring
 * holding the plate.  (Between 12 and 17 degrees the lowered shape's
 * sides, computed anew, lay outside the old ones by a last digit to
 * GEOSCovers at some angles, and no tab was lowered there.)
 */
static void test_tab_in_the_way_is_lowered(void **state)
{
    (void)state;
    ur_net_list nets = notch_and_slots(12);
    ur_piece *pieces = pieces_of(&nets);
    ur_error error;
    ur_joint_options options = frame_options(NULL);
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    size_t smaller = 0;
    for (size_t k = 0; k < nets.count; k++)
        for (size_t r = 0; r < pieces[k].record_count; r++) {
            const ur_allowance_record *record = &pieces[k].records[r];
            print_message("%s: %s\n", pieces[k].name, record->reason);
            assert_false(record->kind == UR_ALLOWANCE_JOINT && record->warning);
            smaller += k == 0 && strstr(record->reason, "made smaller to fit") != NULL;
        }
    assert_int_equal(count_joints(&pieces[0]), 2);
    assert_int_equal(count_joints(&pieces[1]) + count_joints(&pieces[2]), 0);
    assert_int_equal(smaller, 2);
    GEOSGeometry *grown = polygon(pieces[0].paths[0].points, pieces[0].paths[0].count);
    GEOSGeometry *plate = polygon(nets.nets[0].outline, nets.nets[0].outline_count);
    assert_int_equal(GEOSisValid_r(geos, grown), 1);
    GEOSGeometry *outside = GEOSDifference_r(geos, plate, grown);
    assert_true(area_of(outside) <= 1e-9 * area_of(plate));
    assert_true(area_of(grown) > area_of(plate));
    GEOSGeom_destroy_r(geos, outside);
    GEOSGeom_destroy_r(geos, grown);
    GEOSGeom_destroy_r(geos, plate);
    check_nothing_crosses_outline(&pieces[0]);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
}

/*
 * A plate with a V notch of the given angle (degrees) and 40 mm walls,
 * which are the two sides of one seam: glued, they close the notch, as
 * the faces round a vertex of an ico sphere do.  The tab on one wall
 * lies in the notch, and a tab that reaches across it to nearly touch
 * the other wall away from the notch's point closes a pocket there: the
 * outline moved out by half a 0.1 mm kerf closed round it, and the pocket,
 * the seam's two sides, came out uncut (the sample ico sphere in paper,
 * 19 times).
 */
static ur_net_list notch_seam(double angle)
{
    double half = 0.5 * angle * M_PI / 180.0;
    ur_vec2 v = {50, 20}, p = {50 - 40 * sin(half), 20 + 40 * cos(half)},
            q = {50 + 40 * sin(half), 20 + 40 * cos(half)};
    const ur_vec2 plate[] = {{0, 0}, {100, 0}, {100, 70}, q, v, p, {0, 70}};
    ur_net_list nets = {calloc(1, sizeof(ur_net)), 1};
    assert_non_null(nets.nets);
    nets.nets[0] = grid_net("P1", plate, plate, 7);
    nets.nets[0].outline_3d[5] = nets.nets[0].outline_3d[3]; /* the walls one edge in 3D */
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    assert_int_equal(ur_net_list_last_seam(&nets), 1);
    return nets;
}

/*
 * The outline moved out by half the joints' gap (0.2 mm) closes round
 * no pocket: nothing the tabs added comes nearer the rest of the outline
 * than the gap but at the corners they share, where the notch between
 * them opens outward.  At every angle the tab goes on.
 */
static void test_tab_keeps_off_the_far_side_of_a_notch(void **state)
{
    (void)state;
    const double angles[] = {8, 10, 12, 16, 20, 30};
    for (size_t a = 0; a < sizeof angles / sizeof *angles; a++) {
        ur_net_list nets = notch_seam(angles[a]);
        ur_piece *pieces = pieces_of(&nets);
        ur_error error;
        ur_joint_options options = frame_options(NULL);
        assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
        for (size_t r = 0; r < pieces[0].record_count; r++)
            assert_false(pieces[0].records[r].kind == UR_ALLOWANCE_JOINT &&
                         pieces[0].records[r].warning);
        assert_int_equal(count_joints(&pieces[0]), 1);
        GEOSGeometry *grown = polygon(pieces[0].paths[0].points, pieces[0].paths[0].count);
        GEOSGeometry *moved = GEOSBuffer_r(geos, grown, 0.1, 8);
        assert_non_null(moved);
        if (GEOSGetNumInteriorRings_r(geos, moved) != 0)
            fail_msg("a %g degree notch: the tab closes %d pockets", angles[a],
                     GEOSGetNumInteriorRings_r(geos, moved));
        GEOSGeom_destroy_r(geos, moved);
        GEOSGeom_destroy_r(geos, grown);
        check_nothing_crosses_outline(&pieces[0]);
        free_pieces(pieces, nets.count);
        ur_net_list_free(&nets);
    }
}

/*
 * Every closed mark of the piece is a lap (outside its net's outline) or
 * the zone another piece's lap covers (inside it), never some of each.
 */
static void check_laps_and_zones_apart(const ur_piece *piece, const ur_net *net)
{
    GEOSGeometry *outline = polygon(net->outline, net->outline_count);
    for (size_t k = 0; k < piece->path_count; k++) {
        const ur_path *mark = &piece->paths[k];
        if (mark->op != UR_OP_MARK || !mark->closed || mark->count < 3)
            continue;
        GEOSGeometry *zone = polygon(mark->points, mark->count);
        GEOSGeometry *in = GEOSIntersection_r(geos, zone, outline);
        GEOSGeometry *out = GEOSDifference_r(geos, zone, outline);
        assert_true(in && out);
        double whole = area_of(zone);
        assert_true(area_of(in) < 1e-6 * whole || area_of(out) < 1e-6 * whole);
        GEOSGeom_destroy_r(geos, in);
        GEOSGeom_destroy_r(geos, out);
        GEOSGeom_destroy_r(geos, zone);
    }
    GEOSGeom_destroy_r(geos, outline);
}

/* The outline of net m moved so that its side t lies on net k's side s the other way round. */
static GEOSGeometry *laid_on(const ur_net *k_net, const ur_seam_side *s, const ur_net *m_net,
                             const ur_seam_side *t)
{
    size_t nk = k_net->outline_count, nm = m_net->outline_count;
    ur_vec2 a = k_net->outline[s->first % nk], b = k_net->outline[(s->first + s->count - 1) % nk];
    ur_vec2 c = m_net->outline[t->first % nm], d = m_net->outline[(t->first + t->count - 1) % nm];
    /* c goes to b, d to a */
    double angle = atan2(b.y - a.y, b.x - a.x) - atan2(c.y - d.y, c.x - d.x);
    ur_vec2 *moved = malloc(nm * sizeof *moved);
    assert_non_null(moved);
    for (size_t i = 0; i < nm; i++) {
        ur_vec2 v = ur_vec2_sub(m_net->outline[i], d);
        moved[i] = ur_vec2_add(a, ur_vec2_make(cos(angle) * v.x - sin(angle) * v.y,
                                               sin(angle) * v.x + cos(angle) * v.y));
    }
    GEOSGeometry *g = polygon(moved, nm);
    free(moved);
    return g;
}

/*
 * Checks that the laps of piece k (its grown outline less its net) are,
 * on each straight seam side that has one, the band width mm wide beyond
 * the side cut to the other piece laid over it: a lap ends where the
 * piece it lies on ends.  What lies beyond that piece may be up to
 * `beyond` of the laps' area: at each end a lap is cut along the other
 * piece's next edge only, exact where that edge runs on past the lap
 * (a mesh's faces), a little short where it is one chord of a curve.
 * None of what lies on the other piece is cut off.
 */
static void check_laps_on_the_other_piece(const ur_net_list *nets, const ur_piece *pieces, size_t k,
                                          double width, double beyond)
{
    const ur_net *net = &nets->nets[k];
    GEOSGeometry *grown = polygon(pieces[k].paths[0].points, pieces[k].paths[0].count);
    GEOSGeometry *own = polygon(net->outline, net->outline_count);
    GEOSGeometry *laps = GEOSDifference_r(geos, grown, own);
    GEOSGeometry *expected = GEOSGeom_createEmptyPolygon_r(geos);
    for (size_t i = 0; i < net->seam_side_count; i++) {
        const ur_seam_side *s = &net->seam_sides[i];
        if (s->count != 2)
            continue; /* straight sides only */
        for (size_t m = 0; m < nets->count; m++)
            for (size_t q = 0; m != k && q < nets->nets[m].seam_side_count; q++) {
                const ur_seam_side *t = &nets->nets[m].seam_sides[q];
                if (t->seam != s->seam)
                    continue;
                ur_vec2 a = net->outline[s->first % net->outline_count];
                ur_vec2 b = net->outline[(s->first + 1) % net->outline_count];
                ur_vec2 along = ur_vec2_scale(ur_vec2_sub(b, a), 1.0 / ur_vec2_distance(a, b));
                ur_vec2 out = ur_vec2_make(along.y, -along.x); /* right of a run: outward */
                ur_vec2 band_ring[4] = {a, b, ur_vec2_add_scaled(b, out, width),
                                        ur_vec2_add_scaled(a, out, width)};
                GEOSGeometry *band = polygon(band_ring, 4);
                GEOSGeometry *other = laid_on(net, s, &nets->nets[m], t);
                GEOSGeometry *lap = GEOSIntersection_r(geos, band, other);
                GEOSGeometry *there = GEOSIntersection_r(geos, lap, laps);
                if (area_of(there) > 0.5 * area_of(lap)) { /* this side has the lap */
                    GEOSGeometry *both = GEOSUnion_r(geos, expected, lap);
                    GEOSGeom_destroy_r(geos, expected);
                    expected = both;
                }
                GEOSGeometry *all[] = {band, other, lap, there};
                for (size_t g = 0; g < 4; g++)
                    GEOSGeom_destroy_r(geos, all[g]);
            }
    }
    GEOSGeometry *over = GEOSDifference_r(geos, laps, expected);
    GEOSGeometry *short_of = GEOSDifference_r(geos, expected, laps);
    assert_true(area_of(laps) > 0);
    assert_true(area_of(over) <= beyond * area_of(laps) + 1e-9);
    assert_true(area_of(short_of) < 1e-9 * area_of(laps));
    GEOSGeometry *all[] = {grown, own, laps, expected, over, short_of};
    for (size_t g = 0; g < 6; g++)
        GEOSGeom_destroy_r(geos, all[g]);
}

/*
 * Nets P1, P2, P3 of up to 4 corners on the grid, each laid `apart` mm to
 * the right of the one before, with their seams found.
 */
static ur_net_list three_nets_apart(const ur_vec2 *const grids[3], const size_t counts[3],
                                    double apart)
{
    ur_net_list nets = {calloc(3, sizeof(ur_net)), 3};
    assert_non_null(nets.nets);
    for (size_t n = 0; n < 3; n++) {
        ur_vec2 flat[4];
        assert_true(counts[n] <= 4);
        for (size_t i = 0; i < counts[n]; i++)
            flat[i] = ur_vec2_add(grids[n][i], ur_vec2_make(apart * (double)n, 0));
        char name[8];
        snprintf(name, sizeof name, "P%zu", n + 1);
        nets.nets[n] = grid_net(name, flat, grids[n], counts[n]);
    }
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    return nets;
}

/*
 * A triangle with 80 mm sides (60 degree corners), a plate seamed to its
 * lower side and a triangle to its left side, laid 200 mm apart.
 */
static ur_net_list triangle_between_two(void)
{
    double h = 40 * sqrt(3.0);
    const ur_vec2 triangle[] = {{0, 0}, {80, 0}, {40, h}};
    const ur_vec2 plate[] = {{0, -40}, {80, -40}, {80, 0}, {0, 0}};
    const ur_vec2 left[] = {{0, 0}, {40, h}, {-40, h}};
    const ur_vec2 *const grids[] = {triangle, plate, left};
    const size_t counts[] = {3, 4, 3};
    return three_nets_apart(grids, counts, 200);
}

/*
 * The triangle between two, lapped (6 mm): the triangle's lap on one seam,
 * the left triangle's on the other, over the triangle.  That lap ends
 * where the triangle does, mitred along its other sides (a band square to
 * the seam stuck out past the triangle's 60 degree corners, onto the
 * plate and the triangle's own lap).  The zone it covers, a band square
 * to its seam, also reaches past that corner; it is marked on the
 * triangle only, not on the triangle's own lap there, which lies under
 * the plate.
 */
static void test_laps_end_where_their_piece_does(void **state)
{
    (void)state;
    ur_net_list nets = triangle_between_two();
    assert_int_equal(ur_net_list_last_seam(&nets), 2);
    ur_piece *pieces = pieces_of(&nets);
    add_laps(pieces, &nets, NULL, 6);
    assert_int_equal(count_joints(&pieces[0]), 1); /* to the plate */
    assert_int_equal(count_joints(&pieces[1]), 0);
    assert_int_equal(count_joints(&pieces[2]), 1); /* over the triangle */
    assert_int_equal(count_op(&pieces[0], UR_OP_MARK), 2);
    /*
     * The lap on the plate's 90 degree corners stays a 6 x 80 mm band; the
     * one over the triangle is mitred at 60 degrees at both ends, less two
     * triangles of 6 mm by 6 / tan 60 mm.
     */
    const double lap_area[] = {6 * 80, 0, 6 * 80 - 36 / tan(M_PI / 3)};
    for (size_t k = 0; k < 3; k++) {
        GEOSGeometry *grown = polygon(pieces[k].paths[0].points, pieces[k].paths[0].count);
        GEOSGeometry *net = polygon(nets.nets[k].outline, nets.nets[k].outline_count);
        assert_true(fabs(area_of(grown) - area_of(net) - lap_area[k]) < 1e-6);
        GEOSGeom_destroy_r(geos, grown);
        GEOSGeom_destroy_r(geos, net);
        if (k != 1)
            check_laps_on_the_other_piece(&nets, pieces, k, 6, 0.0);
    }
    for (size_t k = 0; k < nets.count; k++)
        check_laps_and_zones_apart(&pieces[k], &nets.nets[k]);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
}

/*
 * Two plates whose common edge meanders: three teeth 2 mm wide and 20 mm
 * high, each plate's fitting between the other's.  No lap can follow it
 * whole (15 mm wide, 5.25 mm at the lowest tried, it would cross itself in
 * every 2 mm slot, on either side), so the seam is cut where it has turned
 * by more than 90 degrees: into seven stretches, each a slot's floor or a
 * tooth's top and the wall after it, and the last edge alone.  The last
 * two, on the outer tooth, get their laps; each of the other five says
 * which edges it is and why it has none (the other teeth, 2 to 4 mm away;
 * for the first, the other plate's 2 mm tooth, which a lap cut to it
 * leaves too small to glue).  Before, the whole 134 mm seam went without
 * a lap.
 */
static void test_lap_on_a_bent_seam_in_stretches(void **state)
{
    (void)state;
    static const ur_vec2 lower[] = {{-2, -10}, {12, -10}, {12, 0}, {10, 0}, {10, 20}, {8, 20},
                                    {8, 0},    {6, 0},    {6, 20}, {4, 20}, {4, 0},   {2, 0},
                                    {2, 20},   {0, 20},   {0, 0},  {-2, 0}};
    static const ur_vec2 upper[] = {{-2, 0}, {0, 0},  {0, 20},  {2, 20}, {2, 0},  {4, 0},
                                    {4, 20}, {6, 20}, {6, 0},   {8, 0},  {8, 20}, {10, 20},
                                    {10, 0}, {12, 0}, {12, 30}, {-2, 30}};
    size_t n = sizeof lower / sizeof *lower;
    ur_net_list nets = {calloc(2, sizeof(ur_net)), 2};
    assert_non_null(nets.nets);
    nets.nets[0] = grid_net("P1", lower, lower, n);
    nets.nets[1] = grid_net("P2", upper, upper, n);
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    assert_int_equal(ur_net_list_last_seam(&nets), 1);
    ur_piece *pieces = pieces_of(&nets);
    add_laps(pieces, &nets, NULL, 15);
    static const char *const unjoined[] = {"(edges 1 to 2 of 13)", "(edges 3 to 4 of 13)",
                                           "(edges 5 to 6 of 13)", "(edges 7 to 8 of 13)",
                                           "(edges 9 to 10 of 13)"};
    size_t warned = 0, laps = 0;
    for (size_t k = 0; k < nets.count; k++) {
        laps += count_joints(&pieces[k]);
        for (size_t r = 0; r < pieces[k].record_count; r++) {
            const ur_allowance_record *record = &pieces[k].records[r];
            if (record->kind != UR_ALLOWANCE_JOINT || !record->warning)
                continue;
            print_message("%s\n", record->reason);
            assert_true(warned < 5);
            assert_non_null(strstr(record->reason, unjoined[warned]));
            assert_true(strstr(record->reason, "its own outline comes within") ||
                        strstr(record->reason, "ends is too small to glue"));
            warned++;
        }
    }
    assert_int_equal(warned, 5);
    assert_int_equal(laps, 2);
    for (size_t k = 0; k < nets.count; k++)
        check_laps_and_zones_apart(&pieces[k], &nets.nets[k]);
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
}

static void test_laps_marked_on_both(void **state)
{
    (void)state;
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_helix(30, 20 * M_PI, 0, 5 * M_PI, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, 0, 25, &ruled, NULL), UR_OK);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 8, 0.01);
    ur_piece *pieces = pieces_of(&nets);
    ur_error error;
    ur_joint_options options = tab_options(NULL);
    options.lap = true;
    options.lap_width = 6;
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    size_t marks = 0, laps = 0;
    for (size_t k = 0; k < nets.count; k++) {
        marks += count_op(&pieces[k], UR_OP_MARK);
        laps += count_records(&pieces[k], UR_ALLOWANCE_JOINT, false);
        assert_int_equal(count_op(&pieces[k], UR_OP_SCORE), 0); /* wood does not fold */
    }
    assert_int_equal(laps, nets.count - 1);
    assert_int_equal(marks, 2 * laps); /* the lap and the zone it lies under */
    /*
     * A lap along a 25 mm ruling, 6 mm wide, is the band along it (the
     * rulings are straight: the two sides of a seam are congruent), 150
     * mm2, cut where the other piece ends: a piece's edges meet its
     * rulings at an angle, and the square band stuck out past them.  Its
     * edges are curves; what the chord next to the corner leaves of the
     * lap beyond them is under 5 % of it (4 % here).
     */
    for (size_t k = 0; k < nets.count; k++)
        if (count_records(&pieces[k], UR_ALLOWANCE_JOINT, false) == 1) {
            GEOSGeometry *grown = polygon(pieces[k].paths[0].points, pieces[k].paths[0].count);
            GEOSGeometry *net = polygon(nets.nets[k].outline, nets.nets[k].outline_count);
            double lap = area_of(grown) - area_of(net);
            assert_true(lap > 0.75 * 25 * 6 && lap < 25 * 6);
            GEOSGeom_destroy_r(geos, grown);
            GEOSGeom_destroy_r(geos, net);
            check_laps_on_the_other_piece(&nets, pieces, k, 6, 0.05);
        }
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

/*
 * Two turns of a helicoid (radius 30, pitch 62.83, ruling width 25, as the
 * README's example) develop to about 680 degrees and split in two pieces
 * whose seam has the other turn within a few millimetres on both sides:
 * no tab or lap fits (a lap cut to where the other piece ends, at the edge
 * of regression where the strips come to a point, is too small to glue).
 * In cardboard (tabs) and in plywood (laps) every seam is joined all the
 * same: by a tab or lap, or by a splice piece, a strip glued behind the
 * seam, as wide on each side as the tab is deep (the lap wide): its area
 * is twice that width times the seam's 25 mm, it marks the seam and
 * carries both pieces' names with the seam's label.
 */
static void test_every_seam_joined(void **state)
{
    (void)state;
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    for (int wood = 0; wood < 2; wood++) {
        ur_curve *curve;
        ur_ruled ruled;
        assert_int_equal(ur_curve_new_helix(30, 20 * M_PI, 0, 4 * M_PI, &curve, NULL), UR_OK);
        assert_int_equal(ur_ruled_tangent(curve, 0, 25, &ruled, NULL), UR_OK);
        ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 64, 0.01);
        assert_true(nets.count >= 2);
        ur_piece *pieces = pieces_of(&nets);
        ur_splice_list splices = {NULL, 0};
        ur_joint_options options = tab_options(font);
        options.lap = wood;
        options.thickness = wood ? 3 : 2;
        options.splices = &splices;
        assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
        int seams = ur_net_list_last_seam(&nets);
        assert_true(seams >= 1);
        size_t joined = 0;
        for (size_t k = 0; k < nets.count; k++) {
            assert_int_equal(count_records(&pieces[k], UR_ALLOWANCE_JOINT, true), 0);
            joined += count_joints(&pieces[k]);
        }
        double width = wood ? options.lap_width : options.tab_depth;
        for (size_t s = 0; s < splices.count; s++) {
            const ur_piece *splice = &splices.pieces[s];
            GEOSGeometry *outline = polygon(splice->paths[0].points, splice->paths[0].count);
            assert_int_equal(GEOSisValid_r(geos, outline), 1);
            assert_relative(area_of(outline), 2 * width * 25, 1e-6);
            GEOSGeom_destroy_r(geos, outline);
            assert_int_equal(count_op(splice, UR_OP_MARK), 1);
            assert_true(count_op(splice, UR_OP_ENGRAVE) > 0);
            size_t labels = 0;
            for (size_t r = 0; r < splice->record_count; r++)
                labels += splice->records[r].kind == UR_ALLOWANCE_LABEL &&
                          !splice->records[r].warning && strstr(splice->records[r].reason, "A1");
            assert_int_equal(labels, 2);
        }
        /* Each seam: a joint on one side, or a splice. */
        assert_int_equal(joined + splices.count, (size_t)seams);
        assert_true(splices.count >= 1); /* the example's seam has no room either side */
        ur_splice_list_free(&splices);
        free_pieces(pieces, nets.count);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
    ur_font_close(font);
}

/*
 * Two nets seamed along the side they share: P1 laid as its grid, P2 laid
 * 100 mm to the right of its grid (at most 8 corners).
 */
static ur_net_list strip_beside(const ur_vec2 *strip, size_t strip_count, const ur_vec2 *other,
                                size_t other_count)
{
    ur_vec2 other_flat[8];
    assert_true(other_count <= 8);
    for (size_t i = 0; i < other_count; i++)
        other_flat[i] = ur_vec2_add(other[i], ur_vec2_make(100, 0));
    ur_net_list nets = {calloc(2, sizeof(ur_net)), 2};
    assert_non_null(nets.nets);
    nets.nets[0] = grid_net("P1", strip, strip, strip_count);
    nets.nets[1] = grid_net("P2", other_flat, other, other_count);
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    return nets;
}

/*
 * An 80 x 30 mm plate lapped (6 mm) onto a plate below it whose left side
 * leaves the seam at 80 or 88 degrees: at 80 the lap is cut along that
 * side, less a triangle of 6 mm by 6 tan 10 mm; at 88 the cut would take
 * a sliver of 0.6 mm2, under 5 % of the lap width squared, and the lap
 * stays a 6 x 80 mm band (slivers that small came out as slits between
 * the laps of neighbouring seams).
 */
static void test_lap_cut_only_where_it_matters(void **state)
{
    (void)state;
    static const ur_vec2 plate[] = {{0, 0}, {80, 0}, {80, 30}, {0, 30}};
    const double angles[] = {80, 88};
    for (size_t a = 0; a < 2; a++) {
        double lean = 30 / tan(angles[a] * M_PI / 180);
        const ur_vec2 below[] = {{lean, -30}, {80, -30}, {80, 0}, {0, 0}};
        ur_net_list nets = strip_beside(plate, 4, below, 4);
        ur_piece *pieces = pieces_of(&nets);
        add_laps(pieces, &nets, NULL, 6);
        assert_int_equal(count_joints(&pieces[0]), 1);
        GEOSGeometry *grown = polygon(pieces[0].paths[0].points, pieces[0].paths[0].count);
        GEOSGeometry *net = polygon(nets.nets[0].outline, nets.nets[0].outline_count);
        double cut = a == 0 ? 0.5 * 6 * 6 * tan(10 * M_PI / 180) : 0;
        assert_true(fabs(area_of(grown) - area_of(net) - (6 * 80 - cut)) < 1e-6);
        GEOSGeom_destroy_r(geos, grown);
        GEOSGeom_destroy_r(geos, net);
        free_pieces(pieces, nets.count);
        ur_net_list_free(&nets);
    }
}

/* Whether every engraved point of the piece lies inside ring and none inside net's outline. */
static bool engraved_on(const ur_piece *piece, const GEOSGeometry *ring, const ur_net *net)
{
    GEOSGeometry *outline = polygon(net->outline, net->outline_count);
    bool on = false, off = false;
    for (size_t k = 0; k < piece->path_count; k++) {
        const ur_path *path = &piece->paths[k];
        for (size_t i = 0; path->op == UR_OP_ENGRAVE && i < path->count; i++) {
            GEOSGeometry *point =
                GEOSGeom_createPointFromXY_r(geos, path->points[i].x, path->points[i].y);
            on = on || GEOSContains_r(geos, ring, point) == 1;
            off = off || GEOSContains_r(geos, ring, point) != 1 ||
                  GEOSContains_r(geos, outline, point) == 1;
            GEOSGeom_destroy_r(geos, point);
        }
    }
    GEOSGeom_destroy_r(geos, outline);
    return on && !off;
}

/* The piece has one tab, and its one label stands on it, inside the grown outline. */
static void check_label_on_its_tab(const ur_piece *piece, const ur_net *net)
{
    assert_int_equal(count_joints(piece), 1);
    assert_int_equal(count_records(piece, UR_ALLOWANCE_LABEL, true), 0);
    assert_int_equal(count_records(piece, UR_ALLOWANCE_LABEL, false), 1);
    GEOSGeometry *grown = polygon(piece->paths[0].points, piece->paths[0].count);
    assert_true(engraved_on(piece, grown, net));
    GEOSGeom_destroy_r(geos, grown);
    check_nothing_crosses_outline(piece);
}

/*
 * A strip 3 mm wide seamed along its 40 mm side to a 40 mm square: a 5 mm
 * label (2.5 mm at the least, 0.75 mm clear of the edges) has no room on
 * the strip, so it goes on the strip's tab, 12 mm deep, or on its lap
 * (laps go on before the labels, which go on a lap only where nothing
 * else has room: the maker reads it there before gluing); the square
 * keeps its label beside the seam.
 */
static void test_label_goes_on_the_tab(void **state)
{
    (void)state;
    static const ur_vec2 strip[] = {{0, 0}, {40, 0}, {40, 3}, {0, 3}};
    static const ur_vec2 square_grid[] = {{0, 3}, {40, 3}, {40, 43}, {0, 43}};
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    for (int lap = 0; lap < 2; lap++) {
        ur_net_list nets = strip_beside(strip, 4, square_grid, 4);
        assert_int_equal(ur_net_list_last_seam(&nets), 1);
        ur_piece *pieces = pieces_of(&nets);
        ur_joint_options options = tab_options(font);
        options.lap = lap;
        assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
        assert_int_equal(count_records(&pieces[1], UR_ALLOWANCE_LABEL, true), 0);
        check_engraving_inside(&pieces[1], &nets.nets[1]);
        check_label_on_its_tab(&pieces[0], &nets.nets[0]); /* the tab or lap went on the strip */
        free_pieces(pieces, nets.count);
        ur_net_list_free(&nets);
    }
    ur_font_close(font);
}

/*
 * A strip 4.4 mm long and 3 mm wide seamed along its 4.4 mm side to a
 * large piece, with tabs 20 mm deep whose sides stand at 88 degrees (the
 * tab narrows to 3 mm): the strip's label, 3.4 mm long at its least
 * height (2.56 mm) and kept 0.5 mm clear of the lines, has no room along
 * the tab's fold (it has from a 4.8 mm strip on), and goes across the
 * tab, reading outward.
 */
static void test_label_across_the_tab(void **state)
{
    (void)state;
    static const ur_vec2 strip[] = {{0, 0}, {4.4, 0}, {4.4, 3}, {0, 3}};
    static const ur_vec2 large_grid[] = {{0, 3},   {4.4, 3},  {45, 30},
                                         {45, 60}, {-40, 60}, {-40, 30}};
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_net_list nets = strip_beside(strip, 4, large_grid, 6);
    ur_piece *pieces = pieces_of(&nets);
    ur_joint_options options = tab_options(font);
    options.tab_depth = 20;
    options.tab_angle = 88;
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    check_label_on_its_tab(&pieces[0], &nets.nets[0]);
    ur_box text = ur_box_empty(); /* across: longer up the tab (y) than along its fold (x) */
    for (size_t k = 0; k < pieces[0].path_count; k++)
        for (size_t i = 0; pieces[0].paths[k].op == UR_OP_ENGRAVE && i < pieces[0].paths[k].count;
             i++)
            ur_box_add(&text, pieces[0].paths[k].points[i]);
    assert_true(ur_box_height(text) > ur_box_width(text));
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
    ur_font_close(font);
}

static bool is_fold(const ur_path *path)
{
    return path->op == UR_OP_SCORE || path->op == UR_OP_SCORE_VALLEY;
}

/* A lap, or the zone it covers. */
static bool is_lap_mark(const ur_path *path)
{
    return path->op == UR_OP_MARK && path->closed && path->count >= 3;
}

/*
 * Whether a stroke of an engraved path meets one of the piece's paths that
 * `wanted` picks: its line, or with `area` the polygon it bounds.
 */
static bool engraving_meets(const ur_piece *piece, bool (*wanted)(const ur_path *), bool area)
{
    bool meets = false;
    for (size_t k = 0; k < piece->path_count && !meets; k++) {
        const ur_path *path = &piece->paths[k];
        if (!wanted(path))
            continue;
        GEOSGeometry *other =
            area ? polygon(path->points, path->count) : line_of(path->points, path->count);
        for (size_t e = 0; e < piece->path_count && !meets; e++) {
            const ur_path *text = &piece->paths[e];
            if (text->op != UR_OP_ENGRAVE || text->count < 2)
                continue;
            GEOSGeometry *stroke = line_of(text->points, text->count);
            meets = GEOSIntersects_r(geos, stroke, other) == 1;
            GEOSGeom_destroy_r(geos, stroke);
        }
        GEOSGeom_destroy_r(geos, other);
    }
    return meets;
}

static bool engraving_crosses_a_fold(const ur_piece *piece)
{
    return engraving_meets(piece, is_fold, false);
}

/*
 * A 40 x 30 mm strip folded every 2.5 mm across (faces narrower than any
 * label: 2.5 mm at the least, 0.75 mm clear of each line), lapped along
 * its 40 mm side to a 40 mm square: its label goes across the folds
 * (laps carry no label), inside the strip's own outline and clear of the
 * lap's mark; the square's, with no fold to cross, stands clear as before.
 */
static void test_label_crosses_folds(void **state)
{
    (void)state;
    static const ur_vec2 strip[] = {{0, 0}, {40, 0}, {40, 30}, {0, 30}};
    static const ur_vec2 square_grid[] = {{0, 30}, {40, 30}, {40, 70}, {0, 70}};
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_net_list nets = strip_beside(strip, 4, square_grid, 4);
    ur_piece *pieces = pieces_of(&nets);
    for (int k = 1; k < 16; k++) {
        ur_vec2 fold[2] = {{2.5 * k, 0}, {2.5 * k, 30}};
        assert_int_equal(ur_piece_add_path(&pieces[0], k % 2 ? UR_OP_SCORE : UR_OP_SCORE_VALLEY,
                                           fold, 2, false, &error),
                         UR_OK);
    }
    ur_joint_options options = tab_options(font);
    options.lap = true;
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    for (size_t n = 0; n < 2; n++) {
        assert_int_equal(count_records(&pieces[n], UR_ALLOWANCE_LABEL, true), 0);
        assert_int_equal(count_records(&pieces[n], UR_ALLOWANCE_LABEL, false), 1);
        check_engraving_inside(&pieces[n], &nets.nets[n]);
    }
    assert_true(engraving_crosses_a_fold(&pieces[0]));
    assert_false(engraving_crosses_a_fold(&pieces[1])); /* no folds there */
    /* Clear of the lap's mark: the label's lines meet no mark line. */
    for (size_t k = 0; k < pieces[0].path_count; k++) {
        const ur_path *mark = &pieces[0].paths[k];
        if (mark->op != UR_OP_MARK || mark->count < 2)
            continue;
        GEOSGeometry *line = line_of(mark->points, mark->count);
        for (size_t e = 0; e < pieces[0].path_count; e++) {
            const ur_path *text = &pieces[0].paths[e];
            if (text->op != UR_OP_ENGRAVE || text->count < 2)
                continue;
            GEOSGeometry *stroke = line_of(text->points, text->count);
            assert_int_equal(GEOSIntersects_r(geos, stroke, line), 0);
            GEOSGeom_destroy_r(geos, stroke);
        }
        GEOSGeom_destroy_r(geos, line);
    }
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
    ur_font_close(font);
}

static bool engraving_meets_a_lap(const ur_piece *piece)
{
    return engraving_meets(piece, is_lap_mark, true);
}

/*
 * A 60 x 30 mm plate, a 12 mm square and a strip 60 x 12 mm, seamed to the
 * plate along its long lower side and to the square at its left end, laid
 * 100 mm apart.  Laps go on the first side of a seam that has room for
 * them: the plate's and the square's, over the strip.
 */
static ur_net_list strip_in_a_corner(void)
{
    static const ur_vec2 strip[] = {{0, 0}, {60, 0}, {60, 12}, {0, 12}};
    static const ur_vec2 square[] = {{-12, 0}, {0, 0}, {0, 12}, {-12, 12}};
    static const ur_vec2 plate[] = {{0, -30}, {60, -30}, {60, 0}, {0, 0}};
    const ur_vec2 *const grids[] = {plate, square, strip};
    const size_t counts[] = {4, 4, 4};
    return three_nets_apart(grids, counts, 100);
}

/*
 * The strip in a corner, lapped (6 mm laps, 3 mm labels): the label of
 * the short seam, 1 mm beyond its own seam's zone, fell in the zone of the
 * long seam beside it (the strip is 12 mm wide) when labels went on before
 * the laps.  Every label now finds room outside every lap and every zone
 * a lap covers, where it stays in sight once glued and no mark line runs
 * through it.
 */
static void test_labels_keep_off_laps(void **state)
{
    (void)state;
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_net_list nets = strip_in_a_corner();
    assert_int_equal(ur_net_list_last_seam(&nets), 2);
    ur_piece *pieces = pieces_of(&nets);
    add_laps(pieces, &nets, font, 6);
    size_t laps = 0;
    for (size_t n = 0; n < nets.count; n++) {
        laps += count_joints(&pieces[n]);
        assert_int_equal(count_records(&pieces[n], UR_ALLOWANCE_LABEL, true), 0);
        assert_true(count_op(&pieces[n], UR_OP_ENGRAVE) > 0);
        assert_false(engraving_meets_a_lap(&pieces[n]));
    }
    assert_int_equal(laps, 2);
    assert_int_equal(count_joints(&pieces[2]), 0); /* both laps lie on the strip */
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
    ur_font_close(font);
}

/* The least distance between the strokes of two labels of a piece (GEOS). */
static double label_distance(const ur_piece *piece, const ur_allowance_record *a,
                             const ur_allowance_record *b)
{
    double least = INFINITY;
    for (size_t i = a->first_path; i < a->first_path + a->path_count; i++)
        for (size_t k = b->first_path; k < b->first_path + b->path_count; k++) {
            GEOSGeometry *p = line_of(piece->paths[i].points, piece->paths[i].count);
            GEOSGeometry *q = line_of(piece->paths[k].points, piece->paths[k].count);
            double distance;
            assert_int_equal(GEOSDistance_r(geos, p, q, &distance), 1);
            least = fmin(least, distance);
            GEOSGeom_destroy_r(geos, p);
            GEOSGeom_destroy_r(geos, q);
        }
    return least;
}

/*
 * The unfolded icosphere's many short seams, labelled 3 mm high: no two
 * labels of a piece come closer than half the smaller one's height (a
 * word's space), else labels of neighbouring seams run together and read
 * as one ("A16A15A12").
 */
static void test_labels_stand_apart(void **state)
{
    (void)state;
    ur_font *font;
    ur_error error;
    assert_int_equal(ur_font_open(NULL, &font, &error), UR_OK);
    ur_net_list nets = icosphere_nets();
    ur_piece *pieces = pieces_of(&nets);
    ur_joint_options options = tab_options(font);
    options.tab_depth = 3;
    options.thickness = 0.3;
    options.label_height = 5;
    options.name_pieces = true;
    assert_int_equal(ur_pieces_add_joints(pieces, &nets, &options, &error), UR_OK);
    size_t pairs = 0;
    for (size_t n = 0; n < nets.count; n++) {
        const ur_piece *piece = &pieces[n];
        for (size_t i = 0; i < piece->record_count; i++)
            for (size_t k = i + 1; k < piece->record_count; k++) {
                const ur_allowance_record *a = &piece->records[i], *b = &piece->records[k];
                if (a->path_count == 0 || b->path_count == 0)
                    continue;
                double distance = label_distance(piece, a, b);
                double space = 0.5 * fmin(a->value, b->value);
                if (distance < space - 1e-9)
                    fail_msg("piece %zu: %s and %s only %g mm apart (under %g)", n, a->reason,
                             b->reason, distance, space);
                pairs += distance < 4 * space; /* neighbours, not labels across the piece */
            }
    }
    print_message("%zu pairs of labels within four spaces\n", pairs);
    assert_true(pairs > 0); /* some labels were close enough to have mattered */
    free_pieces(pieces, nets.count);
    ur_net_list_free(&nets);
    ur_font_close(font);
}

static void test_bad_options(void **state)
{
    (void)state;
    ur_net_list nets = {NULL, 0};
    ur_error error;
    ur_joint_options options = tab_options(NULL);
    options.tab_angle = 0;
    assert_int_equal(ur_pieces_add_joints(NULL, &nets, &options, &error), UR_ERROR_INPUT);
    options = tab_options(NULL);
    options.tab_depth = NAN;
    assert_int_equal(ur_pieces_add_joints(NULL, &nets, &options, &error), UR_ERROR_INPUT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_seam_labels),
        cmocka_unit_test(test_cylinder_tab),
        cmocka_unit_test(test_helicoid_labels_pair),
        cmocka_unit_test(test_every_seam_joined),
        cmocka_unit_test(test_unfolded_tabs_clear),
        cmocka_unit_test(test_tabs_beside_labels_as_alone),
        cmocka_unit_test(test_loop_seams_joined),
        cmocka_unit_test(test_narrow_slit_said_once),
        cmocka_unit_test(test_progress_reported),
        cmocka_unit_test(test_laps_marked_on_both),
        cmocka_unit_test(test_bad_options),
        cmocka_unit_test(test_label_goes_on_the_tab),
        cmocka_unit_test(test_label_crosses_folds),
        cmocka_unit_test(test_labels_keep_off_laps),
        cmocka_unit_test(test_labels_stand_apart),
        cmocka_unit_test(test_label_across_the_tab),
        cmocka_unit_test(test_tab_in_the_way_is_lowered),
        cmocka_unit_test(test_tab_keeps_off_the_far_side_of_a_notch),
        cmocka_unit_test(test_lap_on_a_bent_seam_in_stretches),
        cmocka_unit_test(test_laps_end_where_their_piece_does),
        cmocka_unit_test(test_lap_cut_only_where_it_matters),
        cmocka_unit_test(test_label_once_where_sides_meet),
        cmocka_unit_test(test_names_full_height_on_sectors),
    };
    return cmocka_run_group_tests(tests, geos_start, geos_finish);
}
