/*
 * piece.c: pieces (what will be cut) and building one from a flat net.
 *
 * The net's outline becomes the CUT path and, on request, its rulings
 * become SCORE lines; the allowances (joints.c, relief.c, bending.c and
 * the others of this module) are added to the piece afterwards.  A
 * flattened net's per-triangle strain comes along for the strain picture,
 * in the same coordinates as the outline.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

double ur_arc_sweep(ur_vec2 centre, const ur_vec2 *points, size_t count)
{
    double sweep = 0;
    for (size_t i = 1; i < count; i++) {
        ur_vec2 a = ur_vec2_sub(points[i - 1], centre), b = ur_vec2_sub(points[i], centre);
        sweep += atan2(ur_vec2_cross(a, b), ur_vec2_dot(a, b));
    }
    return sweep;
}

static ur_status add_rulings(ur_piece *piece, const ur_net *net, ur_error *error)
{
    for (size_t i = 0; i < net->ruling_count; i++) {
        ur_vec2 ends[2] = {net->rulings[i].start, net->rulings[i].end};
        ur_status status = ur_piece_add_path(piece, UR_OP_SCORE, ends, 2, false, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/*
 * The mean direction of the net's drawn rulings, weighted by length:
 * directions are axes (a ruling and its reverse are one), so their doubled
 * angles are averaged.  NAN without rulings.
 */
static double ruling_angle(const ur_net *net)
{
    double c = 0, s = 0;
    for (size_t k = 0; k < net->ruling_count; k++) {
        ur_vec2 d = ur_vec2_sub(net->rulings[k].end, net->rulings[k].start);
        double length = ur_vec2_length(d);
        if (!(length > 0))
            continue;
        double a = 2 * atan2(d.y, d.x);
        c += length * cos(a);
        s += length * sin(a);
    }
    return c == 0 && s == 0 ? NAN : 0.5 * atan2(s, c);
}

ur_status ur_piece_from_net(const ur_net *net, const ur_allowance_options *options, ur_piece *piece,
                            ur_error *error)
{
    memset(piece, 0, sizeof *piece);
    c_snprintf(piece->name, sizeof piece->name, "%s", net->name);
    piece->measures.area_3d = net->area_3d;
    piece->measures.flat_area = net->flat_area;
    piece->measures.edge_error = net->edge_error;
    piece->measures.max_stretch = net->max_stretch;
    piece->measures.max_compression = net->max_compression;
    piece->measures.triangle_count = net->face_count;
    piece->measures.polygon_count = net->polygon_count;
    piece->ruling_angle = ruling_angle(net);
    piece->has_rulings = !isnan(piece->ruling_angle);
    ur_status status =
        ur_piece_add_path(piece, UR_OP_CUT, net->outline, net->outline_count, true, error);
    if (status == UR_OK)
        status = allow_open_slits(piece, error);
    if (status == UR_OK && options && options->draw_rulings)
        status = add_rulings(piece, net, error);
    for (size_t k = 0; status == UR_OK && k < net->fold_count; k++) {
        ur_vec2 ends[2] = {net->folds[k].start, net->folds[k].end};
        status = ur_piece_add_path(piece, net->fold_valley[k] ? UR_OP_SCORE_VALLEY : UR_OP_SCORE,
                                   ends, 2, false, error);
    }
    if (status == UR_OK)
        status = ur_shading_copy(&net->shading, &piece->shading, error);
    if (status != UR_OK)
        ur_piece_free(piece);
    return status;
}
