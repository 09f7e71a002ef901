/*
 * test_seams.c: both sides of every seam are found and numbered alike: the
 * cut ruling of a closed cylinder, the rulings where a helicoid of two turns
 * is split, the cut of a tube flattened with ARAP and every edge of an
 * unfolded closed mesh; a slit lying closed in its piece is none.  The
 * two sides must be the same 3D edge run in opposite directions, and where
 * the net is exact, equally long flat.
 *
 * Run from the repository root (it reads samples/icosphere.obj).
 */
#include "test_support.h"

#include <stdlib.h>

#include "unroll/flatten.h"
#include "unroll/io.h"
#include "unroll/mesh.h"

static ur_vec2 side_point(const ur_net *net, const ur_seam_side *side, size_t k)
{
    return net->outline[(side->first + k) % net->outline_count];
}

static double side_flat_length(const ur_net *net, const ur_seam_side *side)
{
    double length = 0;
    for (size_t k = 0; k + 1 < side->count; k++)
        length += ur_vec2_distance(side_point(net, side, k), side_point(net, side, k + 1));
    return length;
}

/* The two sides of seam number `seam`: fails unless there are exactly two. */
static void find_pair(const ur_net_list *nets, int seam, size_t net_of[2], size_t side_of[2])
{
    size_t found = 0;
    for (size_t n = 0; n < nets->count; n++)
        for (size_t k = 0; k < nets->nets[n].seam_side_count; k++)
            if (nets->nets[n].seam_sides[k].seam == seam) {
                if (found == 2)
                    fail_msg("seam %d has more than two sides", seam);
                net_of[found] = n;
                side_of[found++] = k;
            }
    if (found != 2)
        fail_msg("seam %d has %zu sides", seam, found);
}

/* Every seam 1..last has two sides that are one 3D run in opposite directions. */
static void check_pairs_3d(const ur_net_list *nets, int last, double flat_tolerance)
{
    for (int seam = 1; seam <= last; seam++) {
        size_t n[2], k[2];
        find_pair(nets, seam, n, k);
        const ur_net *a = &nets->nets[n[0]], *b = &nets->nets[n[1]];
        const ur_seam_side *sa = &a->seam_sides[k[0]], *sb = &b->seam_sides[k[1]];
        assert_int_equal(sa->count, sb->count);
        for (size_t i = 0; i < sa->count; i++) {
            ur_vec3 p = a->outline_3d[(sa->first + i) % a->outline_count];
            ur_vec3 q = b->outline_3d[(sb->first + sb->count - 1 - i) % b->outline_count];
            assert_true(ur_vec3_distance(p, q) == 0.0);
        }
        if (flat_tolerance > 0)
            assert_relative(side_flat_length(a, sa), side_flat_length(b, sb), flat_tolerance);
    }
}

static size_t side_edges(const ur_net_list *nets)
{
    size_t edges = 0;
    for (size_t n = 0; n < nets->count; n++)
        for (size_t k = 0; k < nets->nets[n].seam_side_count; k++)
            edges += nets->nets[n].seam_sides[k].count - 1;
    return edges;
}

static void test_closed_cylinder(void **state)
{
    (void)state;
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(40, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 120, &ruled, NULL), UR_OK);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 8, 0.01);
    assert_int_equal(nets.count, 1);
    const ur_net *net = &nets.nets[0];
    assert_int_equal(net->seam_side_count, 2);
    double ends[2];
    for (size_t k = 0; k < 2; k++) {
        const ur_seam_side *side = &net->seam_sides[k];
        assert_int_equal(side->seam, 1);
        assert_int_equal(side->count, 2);
        assert_relative(side_flat_length(net, side), 120, 1e-9);
        ends[k] = side_point(net, side, 0).x;
    }
    /* The two sides are the two ends of the unrolled rectangle, 2 pi r apart. */
    assert_relative(fabs(ends[0] - ends[1]), 2 * M_PI * 40, 1e-6);
    assert_int_equal(ur_net_list_last_seam(&nets), 1);
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

static void test_split_helicoid(void **state)
{
    (void)state;
    ur_curve *curve;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_helix(30, 20 * M_PI, 0, 4 * M_PI, &curve, NULL), UR_OK);
    assert_int_equal(ur_ruled_tangent(curve, 0, 25, &ruled, NULL), UR_OK);
    ur_net_list nets = develop(&ruled, UR_METHOD_EXACT, 8, 0.01);
    assert_true(nets.count >= 2);
    assert_int_equal(ur_net_list_last_seam(&nets), (int)nets.count - 1);
    for (int seam = 1; seam < (int)nets.count; seam++) {
        size_t n[2], k[2];
        find_pair(&nets, seam, n, k);
        /* Seam j joins piece j to piece j + 1 (from 1): nets j - 1 and j. */
        assert_int_equal(n[0], (size_t)seam - 1);
        assert_int_equal(n[1], (size_t)seam);
        assert_relative(side_flat_length(&nets.nets[n[0]], &nets.nets[n[0]].seam_sides[k[0]]),
                        side_flat_length(&nets.nets[n[1]], &nets.nets[n[1]].seam_sides[k[1]]),
                        1e-9);
    }
    ur_net_list_free(&nets);
    ur_ruled_free(&ruled);
}

static void test_flattened_tube(void **state)
{
    (void)state;
    ur_curve *circle;
    ur_ruled ruled;
    assert_int_equal(ur_curve_new_circle(30, &circle, NULL), UR_OK);
    assert_int_equal(ur_ruled_cylinder(circle, ur_vec3_make(0, 0, 1), 50, &ruled, NULL), UR_OK);
    ur_mesh mesh;
    ur_error error;
    assert_int_equal(ur_mesh_from_ruled(&ruled, 48, 6, &mesh, &error), UR_OK);
    ur_mesh_repairs repairs;
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, &repairs, &error), UR_OK);
    ur_mesh_piece *pieces;
    size_t piece_count;
    assert_int_equal(ur_mesh_pieces(&mesh, NULL, 0, &pieces, &piece_count, &error), UR_OK);
    assert_int_equal(piece_count, 1);
    ur_flatten_options options;
    ur_flatten_options_default(&options);
    ur_flat_piece flat;
    assert_int_equal(ur_flatten(&pieces[0].mesh, &options, &flat, &error), UR_OK);
    ur_net_list nets = {calloc(1, sizeof(ur_net)), 1};
    assert_int_equal(ur_net_from_flat(&pieces[0].mesh, &flat, "P1", &nets.nets[0], &error), UR_OK);
    int next;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    /* The tube is cut once from its bottom to its top: one seam, both sides on the piece. */
    assert_int_equal(next, 2);
    assert_int_equal(nets.nets[0].seam_side_count, 2);
    check_pairs_3d(&nets, 1, 1e-3);
    /* The cut runs from the bottom circle to the top: 50 mm in 3D, at least 6 edges. */
    assert_true(nets.nets[0].seam_sides[0].count >= 7);
    ur_net_list_free(&nets);
    ur_flat_piece_free(&flat);
    ur_mesh_pieces_free(pieces, piece_count);
    ur_mesh_free(&mesh);
    ur_ruled_free(&ruled);
}

static void test_unfolded_icosphere(void **state)
{
    (void)state;
    size_t cut_edges;
    ur_net_list nets = unfolded_nets("samples/icosphere.obj", &cut_edges);
    size_t outline_edges = 0;
    for (size_t k = 0; k < nets.count; k++)
        outline_edges += nets.nets[k].outline_count;
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    /* A closed mesh has no boundary: every outline edge is one side of a seam. */
    assert_int_equal(side_edges(&nets), outline_edges);
    assert_int_equal(ur_net_list_last_seam(&nets), next - 1);
    /* Every face keeps its shape, so both sides of a seam are equally long. */
    check_pairs_3d(&nets, next - 1, 1e-9);
    /* Seams may run over several edges, but each edge is cut once: half the edges. */
    assert_int_equal(side_edges(&nets) / 2, cut_edges);
    ur_net_list_free(&nets);
}

/* Whether the net's outline runs along some 3D edge both ways: it has a slit. */
static bool has_slit(const ur_net *net)
{
    size_t n = net->outline_count;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            if (i != j && ur_vec3_distance(net->outline_3d[i], net->outline_3d[(j + 1) % n]) == 0 &&
                ur_vec3_distance(net->outline_3d[(i + 1) % n], net->outline_3d[j]) == 0)
                return true;
    return false;
}

/*
 * The sample's frame of 8 quads round a square hole unfolds into one piece
 * cut once from its hole to its rim; the two sides of that slit lie on each
 * other, the material whole there: no seam.  The grid beside it keeps its
 * one seam round its centre quad, on both pieces.
 */
static void test_closed_slit_is_no_seam(void **state)
{
    (void)state;
    size_t cut_edges;
    ur_net_list nets = unfolded_nets("samples/grid-hole.obj", &cut_edges);
    int next;
    ur_error error;
    assert_int_equal(ur_net_list_find_seams(&nets, 1, &next, &error), UR_OK);
    assert_int_equal(nets.count, 3);
    size_t slits = 0, without = 0;
    for (size_t k = 0; k < nets.count; k++) {
        slits += has_slit(&nets.nets[k]);
        without += nets.nets[k].seam_side_count == 0;
    }
    assert_int_equal(slits, 2);   /* the frame and the grid's rim round its centre */
    assert_int_equal(without, 1); /* the frame */
    assert_int_equal(next, 2);    /* one seam: round the centre quad */
    check_pairs_3d(&nets, next - 1, 1e-9);
    ur_net_list_free(&nets);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_cylinder),        cmocka_unit_test(test_split_helicoid),
        cmocka_unit_test(test_flattened_tube),         cmocka_unit_test(test_unfolded_icosphere),
        cmocka_unit_test(test_closed_slit_is_no_seam),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
