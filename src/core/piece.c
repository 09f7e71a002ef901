/*
 * piece.c: pieces (core.h): their paths, records and strain, copied and
 * freed.  Building a piece from a net and adding allowances to it are
 * src/allow's.
 */
#include "unroll/core.h"

#include <stdlib.h>
#include <string.h>

ur_status ur_piece_add_path(ur_piece *piece, ur_op op, const ur_vec2 *points, size_t count,
                            bool closed, ur_error *error)
{
    ur_path *paths = realloc(piece->paths, (piece->path_count + 1) * sizeof *paths);
    if (!paths)
        return ur_error_out_of_memory(error);
    piece->paths = paths;
    ur_vec2 *copy = ur_alloc_array(count, sizeof *copy, error);
    if (!copy)
        return UR_ERROR_MEMORY;
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
    to->kerf_compensated = from->kerf_compensated;
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < from->path_count; k++) {
        status = ur_piece_add_path(to, from->paths[k].op, from->paths[k].points,
                                   from->paths[k].count, from->paths[k].closed, error);
        if (status == UR_OK)
            to->paths[k].circle = from->paths[k].circle;
    }
    if (status == UR_OK)
        status = ur_shading_copy(&from->shading, &to->shading, error);
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

/* ---- Text as strokes ---------------------------------------------------- */

void ur_paths_free(ur_path *paths, size_t count)
{
    if (!paths)
        return;
    for (size_t i = 0; i < count; i++)
        free(paths[i].points);
    free(paths);
}

/* The copy of a net's (or piece's) per-triangle strain, for the strain picture. */
ur_status ur_shading_copy(const ur_shading *from, ur_shading *to, ur_error *error)
{
    memset(to, 0, sizeof *to);
    if (from->count == 0)
        return UR_OK;
    if (!from->triangles || !from->strain)
        return ur_error_set(error, UR_ERROR_INTERNAL, "%zu shaded triangles but no data",
                            from->count);
    to->triangles = ur_alloc_array(from->count, sizeof *to->triangles, error);
    to->strain = ur_alloc_array(from->count, sizeof *to->strain, error);
    if (!to->triangles || !to->strain)
        return UR_ERROR_MEMORY;
    memcpy(to->triangles, from->triangles, from->count * sizeof *to->triangles);
    memcpy(to->strain, from->strain, from->count * sizeof *to->strain);
    if (from->direction) {
        to->direction = ur_alloc_array(from->count, sizeof *to->direction, error);
        if (!to->direction)
            return UR_ERROR_MEMORY;
        memcpy(to->direction, from->direction, from->count * sizeof *to->direction);
    }
    to->count = from->count;
    return UR_OK;
}
