/*
 * unfold_piece.c: a grown piece as the caller gets it: its triangles and
 * their flat corners, its folds, its outline and areas.
 *
 * The outline is walked along the half-edges the piece does not join,
 * leaving each one's end by turning about it through the triangles joined
 * there until the next half-edge not joined: with counter-clockwise
 * triangles that keeps the piece on the left, so the outline runs
 * counter-clockwise.  A disk has one such loop; GEOS then checks that it is
 * a simple polygon, which with every triangle laid counter-clockwise and
 * every inner vertex closed means that no two triangles overlap.
 */
#include "unfold_internal.h"
#include "../geom/geos_polygon.h"

#include <stdlib.h>

static ur_status copy_triangles(const unfolder *u, ur_unfolded_piece *piece, ur_error *error)
{
    size_t n = u->member_count;
    piece->triangles = ur_alloc_array(n, sizeof *piece->triangles, error);
    piece->flat = ur_alloc_array(n, sizeof *piece->flat, error);
    if (!piece->triangles || !piece->flat)
        return UR_ERROR_INTERNAL;
    const ur_mesh *mesh = u->mesh;
    for (size_t i = 0; i < n; i++) {
        size_t t = u->members[i];
        piece->triangles[i] = t;
        for (int k = 0; k < 3; k++)
            piece->flat[i][k] = u->flat[t][k];
        ur_vec3 a = mesh->vertices[mesh->triangles[t][0]];
        ur_vec3 b = mesh->vertices[mesh->triangles[t][1]];
        ur_vec3 c = mesh->vertices[mesh->triangles[t][2]];
        piece->area_3d += 0.5 * ur_vec3_length(ur_vec3_cross(ur_vec3_sub(b, a), ur_vec3_sub(c, a)));
    }
    piece->triangle_count = n;
    return UR_OK;
}

/* Whether half-edge h is a fold of its piece, counted from its lower-numbered half. */
static bool is_fold(const unfolder *u, size_t h)
{
    return u->joined[h] && h < u->edges.twins[h] && fabs(u->edges.bend[h]) >= UR_UNFOLD_FLAT_ANGLE;
}

static ur_status collect_folds(const unfolder *u, ur_unfolded_piece *piece, ur_error *error)
{
    size_t count = 0;
    for (size_t i = 0; i < u->member_count; i++)
        for (size_t h = 3 * u->members[i]; h < 3 * u->members[i] + 3; h++)
            count += is_fold(u, h);
    piece->folds = ur_alloc_array(count, sizeof *piece->folds, error);
    if (!piece->folds)
        return UR_ERROR_INTERNAL;
    for (size_t i = 0; i < u->member_count; i++)
        for (size_t h = 3 * u->members[i]; h < 3 * u->members[i] + 3; h++) {
            if (!is_fold(u, h))
                continue;
            double bend = u->edges.bend[h];
            piece->folds[piece->fold_count++] = (ur_fold){
                .start = u->flat[h / 3][h % 3],
                .end = u->flat[h / 3][(h % 3 + 1) % 3],
                .a = unfold_from(u->mesh, h),
                .b = unfold_to(u->mesh, h),
                .valley = bend < 0,
                .angle = fabs(bend),
            };
        }
    return UR_OK;
}

/* The half-edge not joined that leaves the end of half-edge h, turning about it. */
static size_t next_on_outline(const unfolder *u, size_t h, size_t limit)
{
    size_t n = unfold_next(h);
    for (size_t turns = 0; u->joined[n]; turns++) {
        if (turns > limit)
            return UNFOLD_NONE;
        n = unfold_next(u->edges.twins[n]);
    }
    return n;
}

static ur_status not_a_disk(const unfolder *u, ur_error *error)
{
    return ur_error_set(error, UR_ERROR_INTERNAL,
                        "piece %zu of the unfolding is not a disk (its outline is not one loop)",
                        u->current + 1);
}

static ur_status walk_outline(const unfolder *u, ur_unfolded_piece *piece, ur_error *error)
{
    size_t count = 0, start = UNFOLD_NONE, limit = 3 * u->member_count;
    for (size_t i = 0; i < u->member_count; i++)
        for (size_t h = 3 * u->members[i]; h < 3 * u->members[i] + 3; h++)
            if (!u->joined[h]) {
                count++;
                start = start == UNFOLD_NONE ? h : start;
            }
    if (start == UNFOLD_NONE)
        return not_a_disk(u, error);
    piece->outline = ur_alloc_array(count, sizeof *piece->outline, error);
    piece->outline_vertices = ur_alloc_array(count, sizeof *piece->outline_vertices, error);
    if (!piece->outline || !piece->outline_vertices)
        return UR_ERROR_INTERNAL;
    size_t h = start;
    do {
        if (piece->outline_count == count)
            return not_a_disk(u, error);
        piece->outline[piece->outline_count] = u->flat[h / 3][h % 3];
        piece->outline_vertices[piece->outline_count++] = unfold_from(u->mesh, h);
        h = next_on_outline(u, h, limit);
        if (h == UNFOLD_NONE)
            return not_a_disk(u, error);
    } while (h != start);
    if (piece->outline_count != count)
        return not_a_disk(u, error);
    piece->flat_area = ur_polygon_signed_area(piece->outline, count);
    return UR_OK;
}

static ur_status check_simple(const unfolder *u, GEOSContextHandle_t geos,
                              const ur_unfolded_piece *piece, ur_error *error)
{
    GEOSGeometry *polygon = ur_geos_polygon(geos, piece->outline, piece->outline_count);
    if (!polygon)
        return ur_error_set(error, UR_ERROR_INTERNAL,
                            "GEOS could not build the outline of "
                            "piece %zu of the unfolding",
                            u->current + 1);
    char valid = GEOSisValid_r(geos, polygon);
    char *reason = valid == 1 ? NULL : GEOSisValidReason_r(geos, polygon);
    ur_status status = UR_OK;
    if (valid != 1)
        status = ur_error_set(error, UR_ERROR_INTERNAL,
                              "piece %zu of the unfolding overlaps itself (%s)", u->current + 1,
                              reason ? reason : "GEOS gives no reason");
    else if (!(piece->flat_area > 0))
        status = ur_error_set(error, UR_ERROR_INTERNAL,
                              "the outline of piece %zu of the unfolding runs clockwise",
                              u->current + 1);
    if (reason)
        GEOSFree_r(geos, reason);
    GEOSGeom_destroy_r(geos, polygon);
    return status;
}

ur_status unfold_piece_build(const unfolder *u, GEOSContextHandle_t geos, ur_unfolded_piece *piece,
                             ur_error *error)
{
    *piece = (ur_unfolded_piece){0};
    ur_status status = copy_triangles(u, piece, error);
    if (status == UR_OK)
        status = collect_folds(u, piece, error);
    if (status == UR_OK)
        status = walk_outline(u, piece, error);
    if (status == UR_OK)
        status = check_simple(u, geos, piece, error);
    if (status != UR_OK)
        unfold_piece_free(piece);
    return status;
}

void unfold_piece_free(ur_unfolded_piece *piece)
{
    free(piece->outline);
    free(piece->outline_vertices);
    free(piece->folds);
    free(piece->triangles);
    free(piece->flat);
    *piece = (ur_unfolded_piece){0};
}
