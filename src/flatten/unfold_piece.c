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

static int compare_sizes(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

/* How many flat faces the piece's triangles (sorted) lie in. */
static ur_status count_faces(const unfolder *u, ur_unfolded_piece *piece, ur_error *error)
{
    size_t n = piece->triangle_count;
    size_t *faces = ur_alloc_array(n, sizeof *faces, error);
    if (!faces)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < n; i++)
        faces[i] = u->faces.face[piece->triangles[i]];
    qsort(faces, n, sizeof *faces, compare_sizes);
    for (size_t i = 0; i < n; i++)
        piece->face_count += i == 0 || faces[i] != faces[i - 1];
    free(faces);
    return UR_OK;
}

static ur_status copy_triangles(const unfolder *u, size_t p, ur_unfolded_piece *piece,
                                ur_error *error)
{
    size_t n = u->islands[p].triangle_count;
    piece->triangles = ur_alloc_array(n, sizeof *piece->triangles, error);
    piece->flat = ur_alloc_array(n, sizeof *piece->flat, error);
    if (!piece->triangles || !piece->flat)
        return UR_ERROR_MEMORY;
    const ur_mesh *mesh = u->mesh;
    size_t i = 0;
    for (size_t t = u->islands[p].first; t != UNFOLD_NONE; t = u->next_member[t], i++) {
        piece->triangles[i] = t;
        for (int k = 0; k < 3; k++)
            piece->flat[i][k] = u->flat[t][k];
        ur_vec3 a = mesh->vertices[mesh->triangles[t][0]];
        ur_vec3 b = mesh->vertices[mesh->triangles[t][1]];
        ur_vec3 c = mesh->vertices[mesh->triangles[t][2]];
        piece->area_3d += 0.5 * ur_vec3_length(ur_vec3_cross(ur_vec3_sub(b, a), ur_vec3_sub(c, a)));
    }
    piece->triangle_count = n;
    return count_faces(u, piece, error);
}

/* Whether half-edge h is a fold of its piece, counted from its lower-numbered half. */
static bool is_fold(const unfolder *u, size_t h)
{
    return u->joined[h] && h < u->edges.twins[h] && !u->faces.flat[h];
}

static ur_status collect_folds(const unfolder *u, ur_unfolded_piece *piece, ur_error *error)
{
    size_t count = 0;
    for (size_t i = 0; i < piece->triangle_count; i++)
        for (size_t h = 3 * piece->triangles[i]; h < 3 * piece->triangles[i] + 3; h++)
            count += is_fold(u, h);
    piece->folds = ur_alloc_array(count, sizeof *piece->folds, error);
    if (!piece->folds)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < piece->triangle_count; i++)
        for (size_t h = 3 * piece->triangles[i]; h < 3 * piece->triangles[i] + 3; h++) {
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

static ur_status not_a_disk(size_t index, ur_error *error)
{
    return ur_error_set(error, UR_ERROR_INTERNAL,
                        "piece %zu of the unfolding is not a disk (its outline is not one loop)",
                        index + 1);
}

static ur_status walk_outline(const unfolder *u, size_t index, ur_unfolded_piece *piece,
                              ur_error *error)
{
    size_t count = 0, start = UNFOLD_NONE;
    for (size_t i = 0; i < piece->triangle_count; i++)
        for (size_t h = 3 * piece->triangles[i]; h < 3 * piece->triangles[i] + 3; h++)
            if (!u->joined[h]) {
                count++;
                start = start == UNFOLD_NONE ? h : start;
            }
    if (start == UNFOLD_NONE)
        return not_a_disk(index, error);
    piece->outline = ur_alloc_array(count, sizeof *piece->outline, error);
    piece->outline_vertices = ur_alloc_array(count, sizeof *piece->outline_vertices, error);
    if (!piece->outline || !piece->outline_vertices)
        return UR_ERROR_MEMORY;
    size_t h = start;
    do {
        if (piece->outline_count == count)
            return not_a_disk(index, error);
        piece->outline[piece->outline_count] = u->flat[h / 3][h % 3];
        piece->outline_vertices[piece->outline_count++] = unfold_from(u->mesh, h);
        h = unfold_outline_next(u, h);
        if (h == UNFOLD_NONE)
            return not_a_disk(index, error);
    } while (h != start);
    if (piece->outline_count != count)
        return not_a_disk(index, error);
    piece->flat_area = ur_polygon_signed_area(piece->outline, count);
    return UR_OK;
}

/* Whether the piece has a slit: an edge it cuts with both sides in it (a face round a hole). */
static bool has_slit(const unfolder *u, const ur_unfolded_piece *piece)
{
    for (size_t i = 0; i < piece->triangle_count; i++)
        for (size_t h = 3 * piece->triangles[i]; h < 3 * piece->triangles[i] + 3; h++) {
            size_t g = u->edges.twins[h];
            if (g != UR_NO_EDGE && !u->joined[h] && u->piece[g / 3] == u->piece[h / 3])
                return true;
        }
    return false;
}

/*
 * The polygons of a made-valid outline: *count of more than `least` area,
 * *area their total; false for a part that is no polygon, line or point.
 */
static bool count_polygons(GEOSContextHandle_t geos, const GEOSGeometry *geometry, double least,
                           int *count, double *area)
{
    int type = GEOSGeomTypeId_r(geos, geometry);
    if (type == GEOS_LINESTRING || type == GEOS_MULTILINESTRING || type == GEOS_POINT ||
        type == GEOS_MULTIPOINT)
        return true;
    if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
        int parts = GEOSGetNumGeometries_r(geos, geometry);
        bool sound = parts >= 0;
        for (int i = 0; i < parts && sound; i++) {
            const GEOSGeometry *part = GEOSGetGeometryN_r(geos, geometry, i);
            sound = part && count_polygons(geos, part, least, count, area);
        }
        return sound;
    }
    double polygon_area;
    if (type != GEOS_POLYGON || GEOSArea_r(geos, geometry, &polygon_area) != 1)
        return false;
    if (polygon_area > least) {
        (*count)++;
        *area += polygon_area;
    }
    return true;
}

/* The length of a closed ring. */
static double perimeter(const ur_vec2 *ring, size_t count)
{
    double length = 0.0;
    for (size_t i = 0; i < count; i++)
        length += ur_vec2_distance(ring[i], ring[(i + 1) % count]);
    return length;
}

/*
 * An outline with a slit runs along both its sides, which GEOS calls a
 * self-intersection; made valid it must be one polygon of the triangles'
 * area (with a hole where the face had one) and the slits as lines.  A
 * slit's two sides may end a rounding apart (the same corner laid flat
 * two ways round the hole), which GEOS gives as points of their own, or
 * as a polygon of next to no area (a billionth of the piece's): those are
 * no part of the piece.
 */
static bool slit_outline_sound(const unfolder *u, GEOSContextHandle_t geos, GEOSGeometry *polygon,
                               const ur_unfolded_piece *piece)
{
    double triangles = 0.0;
    for (size_t i = 0; i < piece->triangle_count; i++)
        triangles += ur_polygon_signed_area(piece->flat[i], 3);
    GEOSGeometry *valid = GEOSMakeValid_r(geos, polygon);
    double area = 0.0;
    int polygons = 0;
    bool sound = valid && count_polygons(geos, valid, 1e-9 * triangles, &polygons, &area);
    if (valid)
        GEOSGeom_destroy_r(geos, valid);
    /*
     * A millionth: the outline is laid flat along chains of triangles, and
     * the same corner reached two ways round a hole differs in its last
     * digits (OpenSCAD's CSG example: 2e-9 of its area); an overlap big
     * enough to see in a cut is far more.  Or the band the outline may
     * move in, as the unfolding lets triangles come within u->eps of each
     * other: OpenCASCADE's motor.stl has a piece of 338 mm2 whose sliver
     * triangles close round their inner vertices only to that, overlapping
     * by 2e-5 mm2 here and leaving a gap of 1e-3 mm2 (2.8e-6 of the piece)
     * there, a band 2.5 nm wide along its 385 mm of outline.
     */
    double band = u->eps * perimeter(piece->outline, piece->outline_count);
    return sound && polygons == 1 && fabs(area - triangles) <= fmax(1e-6 * triangles, band);
}

static ur_status check_simple(const unfolder *u, size_t index, GEOSContextHandle_t geos,
                              const ur_unfolded_piece *piece, ur_error *error)
{
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, piece->outline, piece->outline_count);
    if (!polygon)
        return ur_error_set(error, UR_ERROR_INTERNAL,
                            "GEOS could not build the outline of "
                            "piece %zu of the unfolding",
                            index + 1);
    char valid = GEOSisValid_r(geos, polygon);
    if (valid != 1 && has_slit(u, piece) && slit_outline_sound(u, geos, polygon, piece))
        valid = 1;
    char *reason = valid == 1 ? NULL : GEOSisValidReason_r(geos, polygon);
    ur_status status = UR_OK;
    if (valid != 1)
        status = ur_error_set(error, UR_ERROR_INTERNAL,
                              "piece %zu of the unfolding overlaps itself (%s)", index + 1,
                              reason ? reason : "GEOS gives no reason");
    else if (!(piece->flat_area > 0))
        status =
            ur_error_set(error, UR_ERROR_INTERNAL,
                         "the outline of piece %zu of the unfolding runs clockwise", index + 1);
    if (reason)
        GEOSFree_r(geos, reason);
    GEOSGeom_destroy_r(geos, polygon);
    return status;
}

ur_status unfold_piece_build(const unfolder *u, size_t p, size_t index, GEOSContextHandle_t geos,
                             ur_unfolded_piece *piece, ur_error *error)
{
    *piece = (ur_unfolded_piece){0};
    ur_status status = copy_triangles(u, p, piece, error);
    if (status == UR_OK)
        status = collect_folds(u, piece, error);
    if (status == UR_OK)
        status = walk_outline(u, index, piece, error);
    if (status == UR_OK)
        status = check_simple(u, index, geos, piece, error);
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
