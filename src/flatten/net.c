/*
 * net.c: a flattened mesh piece as a net, the shape the rest of the
 * pipeline (pieces, sheets, writers, report) takes: its boundary loop laid
 * flat, its areas, how far its boundary lengths are from the 3D ones, and
 * its strain: the largest figures for the report and, triangle by
 * triangle, the shading the strain picture draws (with the direction of
 * each triangle's dominant strain, which the kerfing and overlap
 * allowances cut across).
 */
#include "unroll/flatten.h"
#include "unroll/develop.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

/* The largest relative difference between a flat boundary edge and its 3D length. */
static double boundary_error(const ur_mesh *piece, const ur_flat_piece *flat, const size_t *loop,
                             size_t count)
{
    double largest = 0.0;
    for (size_t i = 0; i < count; i++) {
        size_t a = loop[i], b = loop[(i + 1) % count];
        double space = ur_vec3_distance(piece->vertices[a], piece->vertices[b]);
        double plane = ur_vec2_distance(flat->flat[a], flat->flat[b]);
        if (space > 0)
            largest = fmax(largest, fabs(plane - space) / space);
    }
    return largest;
}

/* sigma1 - 1 or -(1 - sigma2), whichever deviates more (develop.h, ur_shading). */
static double dominant_strain(ur_strain strain)
{
    double stretch = strain.sigma1 - 1, compression = 1 - strain.sigma2;
    return stretch >= compression ? stretch : -compression;
}

/*
 * The flat unit direction of that dominant strain: the left singular vector
 * of sigma1 (ur_strain.direction, the leading eigenvector of J J^T) for
 * stretch, the one of sigma2, perpendicular to it, for compression.
 */
static ur_vec2 dominant_direction(ur_strain strain)
{
    if (dominant_strain(strain) >= 0)
        return strain.direction;
    return ur_vec2_make(-strain.direction.y, strain.direction.x);
}

/*
 * Every triangle of the piece laid flat, with its dominant strain and its
 * direction, for the strain picture and the kerfing and overlap allowances.
 */
static ur_status fill_shading(const ur_mesh *piece, const ur_flat_piece *flat, ur_shading *shading,
                              ur_error *error)
{
    size_t count = piece->triangle_count;
    if (flat->triangle_count != count || flat->vertex_count != piece->vertex_count || !flat->strain)
        return ur_error_set(error, UR_ERROR_INTERNAL,
                            "the flat piece (%zu vertices, %zu triangles) is not that of the mesh "
                            "(%zu vertices, %zu triangles)",
                            flat->vertex_count, flat->triangle_count, piece->vertex_count, count);
    shading->triangles = ur_alloc_array(count, sizeof *shading->triangles, error);
    shading->strain = ur_alloc_array(count, sizeof *shading->strain, error);
    shading->direction = ur_alloc_array(count, sizeof *shading->direction, error);
    if (!shading->triangles || !shading->strain || !shading->direction)
        return UR_ERROR_MEMORY;
    for (size_t t = 0; t < count; t++) {
        for (int k = 0; k < 3; k++)
            shading->triangles[t][k] = flat->flat[piece->triangles[t][k]];
        shading->strain[t] = dominant_strain(flat->strain[t]);
        shading->direction[t] = dominant_direction(flat->strain[t]);
    }
    shading->count = count;
    return UR_OK;
}

ur_status ur_net_from_flat(const ur_mesh *piece, const ur_flat_piece *flat, const char *name,
                           ur_net *net, ur_error *error)
{
    size_t *loop = NULL, count = 0;
    ur_status status = ur_mesh_boundary(piece, &loop, &count, error);
    if (status != UR_OK)
        return status;
    memset(net, 0, sizeof *net);
    c_snprintf(net->name, sizeof net->name, "%s", name);
    net->outline = ur_alloc_array(count, sizeof *net->outline, error);
    net->outline_3d = ur_alloc_array(count, sizeof *net->outline_3d, error);
    if (!net->outline || !net->outline_3d) {
        free(loop);
        ur_net_free(net);
        return UR_ERROR_MEMORY;
    }
    double area = 0.0;
    for (size_t i = 0; i < count; i++)
        net->outline[i] = flat->flat[loop[i]];
    area = ur_polygon_signed_area(net->outline, count);
    for (size_t i = 0; i < count; i++) { /* the writers want counter-clockwise outlines */
        size_t from = area < 0 ? count - 1 - i : i;
        net->outline[i] = flat->flat[loop[from]];
        net->outline_3d[i] = piece->vertices[loop[from]];
    }
    net->outline_count = count;
    net->flat_area = fabs(area);
    net->area_3d = flat->area_3d;
    net->edge_error = boundary_error(piece, flat, loop, count);
    net->max_stretch = flat->max_stretch;
    net->max_compression = flat->max_compression;
    free(loop);
    status = fill_shading(piece, flat, &net->shading, error);
    if (status == UR_OK)
        status = ur_net_set_faces(net, piece, NULL, piece->triangle_count, error);
    if (status != UR_OK)
        ur_net_free(net);
    return status;
}

ur_status ur_net_set_faces(ur_net *net, const ur_mesh *mesh, const size_t *triangles, size_t count,
                           ur_error *error)
{
    free(net->faces_3d);
    net->faces_3d = NULL;
    net->face_count = 0;
    if (count == 0)
        return UR_OK;
    net->faces_3d = ur_alloc_array(count, sizeof *net->faces_3d, error);
    if (!net->faces_3d)
        return UR_ERROR_MEMORY;
    for (size_t f = 0; f < count; f++) {
        size_t t = triangles ? triangles[f] : f;
        if (t >= mesh->triangle_count)
            return ur_error_set(error, UR_ERROR_INTERNAL,
                                "face %zu of a net is triangle %zu of %zu", f + 1, t + 1,
                                mesh->triangle_count);
        for (int k = 0; k < 3; k++)
            net->faces_3d[f][k] = mesh->vertices[mesh->triangles[t][k]];
    }
    net->face_count = count;
    return UR_OK;
}
