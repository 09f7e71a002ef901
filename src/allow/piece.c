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

ur_status ur_piece_add_path(ur_piece *piece, ur_op op, const ur_vec2 *points, size_t count,
                            bool closed, ur_error *error)
{
    ur_path *paths = realloc(piece->paths, (piece->path_count + 1) * sizeof *paths);
    if (!paths)
        return ur_error_out_of_memory(error);
    piece->paths = paths;
    ur_vec2 *copy = ur_alloc_array(count, sizeof *copy, error);
    if (!copy)
        return UR_ERROR_INTERNAL;
    memcpy(copy, points, count * sizeof *copy);
    if (piece->path_count == 0)
        piece->box = ur_box_empty();
    for (size_t i = 0; i < count; i++)
        ur_box_add(&piece->box, points[i]);
    ur_path *path = &piece->paths[piece->path_count++];
    path->op = op;
    path->closed = closed;
    path->points = copy;
    path->count = count;
    path->circle = (ur_path_circle){{0, 0}, 0, 0};
    return UR_OK;
}

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

/* The piece's own copy of the net's per-triangle strain, for the strain picture. */
static ur_status copy_shading(ur_piece *piece, const ur_shading *shading, ur_error *error)
{
    if (shading->count == 0)
        return UR_OK;
    if (!shading->triangles || !shading->strain)
        return ur_error_set(error, UR_ERROR_INTERNAL,
                            "net '%s' has %zu shaded triangles but no data", piece->name,
                            shading->count);
    ur_shading *copy = &piece->shading;
    copy->triangles = ur_alloc_array(shading->count, sizeof *copy->triangles, error);
    copy->strain = ur_alloc_array(shading->count, sizeof *copy->strain, error);
    if (!copy->triangles || !copy->strain)
        return UR_ERROR_INTERNAL; /* ur_piece_free frees what was allocated */
    memcpy(copy->triangles, shading->triangles, shading->count * sizeof *copy->triangles);
    memcpy(copy->strain, shading->strain, shading->count * sizeof *copy->strain);
    if (shading->direction) {
        copy->direction = ur_alloc_array(shading->count, sizeof *copy->direction, error);
        if (!copy->direction)
            return UR_ERROR_INTERNAL;
        memcpy(copy->direction, shading->direction, shading->count * sizeof *copy->direction);
    }
    copy->count = shading->count;
    return UR_OK;
}

ur_status ur_piece_from_net(const ur_net *net, const ur_allowance_options *options, ur_piece *piece,
                            ur_error *error)
{
    memset(piece, 0, sizeof *piece);
    ur_c_snprintf(piece->name, sizeof piece->name, "%s", net->name);
    piece->measures.area_3d = net->area_3d;
    piece->measures.flat_area = net->flat_area;
    piece->measures.edge_error = net->edge_error;
    piece->measures.max_stretch = net->max_stretch;
    piece->measures.max_compression = net->max_compression;
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
        status = copy_shading(piece, &net->shading, error);
    if (status != UR_OK)
        ur_piece_free(piece);
    return status;
}

void ur_piece_free(ur_piece *piece)
{
    for (size_t i = 0; i < piece->path_count; i++)
        free(piece->paths[i].points);
    free(piece->paths);
    piece->paths = NULL;
    piece->path_count = 0;
    free(piece->shading.triangles);
    free(piece->shading.strain);
    free(piece->shading.direction);
    memset(&piece->shading, 0, sizeof piece->shading);
    free(piece->records);
    piece->records = NULL;
    piece->record_count = 0;
}

ur_status ur_piece_copy(const ur_piece *from, ur_piece *to, ur_error *error)
{
    memset(to, 0, sizeof *to);
    memcpy(to->name, from->name, sizeof to->name);
    to->measures = from->measures;
    to->bridged = from->bridged;
    to->outline_area = from->outline_area;
    to->rotations = from->rotations;
    to->ruling_angle = from->ruling_angle;
    to->has_rulings = from->has_rulings;
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < from->path_count; k++) {
        status = ur_piece_add_path(to, from->paths[k].op, from->paths[k].points,
                                   from->paths[k].count, from->paths[k].closed, error);
        if (status == UR_OK)
            to->paths[k].circle = from->paths[k].circle;
    }
    if (status == UR_OK)
        status = copy_shading(to, &from->shading, error);
    for (size_t r = 0; status == UR_OK && r < from->record_count; r++)
        status = ur_piece_record(to, &from->records[r], error);
    if (status != UR_OK)
        ur_piece_free(to);
    else
        to->box = from->box;
    return status;
}

void ur_piece_recompute_box(ur_piece *piece)
{
    piece->box = ur_box_empty();
    for (size_t i = 0; i < piece->path_count; i++)
        for (size_t k = 0; k < piece->paths[i].count; k++)
            ur_box_add(&piece->box, piece->paths[i].points[k]);
}

ur_status ur_piece_record(ur_piece *piece, const ur_allowance_record *record, ur_error *error)
{
    ur_allowance_record *records =
        realloc(piece->records, (piece->record_count + 1) * sizeof *records);
    if (!records)
        return ur_error_out_of_memory(error);
    piece->records = records;
    piece->records[piece->record_count++] = *record;
    return UR_OK;
}

const char *ur_allowance_kind_name(ur_allowance_kind kind)
{
    static const char *const names[UR_ALLOWANCE_KIND_COUNT] = {
        "joint", "label", "kerfing", "overlap", "bending", "kerf-compensation", "bridges"};
    return (unsigned)kind < UR_ALLOWANCE_KIND_COUNT ? names[kind] : "?";
}
