/*
 * triangulate.c: a triangle mesh of a ruled surface, for flattening a
 * surface that has no exact development (a hyperbolic paraboloid, a general
 * ruled surface) or for comparing with one that has.
 *
 * Vertex (i, j) is r(u_i, v_j) = a + v_j (b - a) with u_i evenly spaced
 * over the surface's domain and v_j = j / across.  Triangles run
 * counter-clockwise in (u, v), so their normals point along r_u x r_v.  A
 * closed surface (a whole cylinder or cone) keeps its last ruling as
 * vertices of their own, equal to the first: the mesh is then already cut
 * along the first ruling into one disk, which is what flattening needs, and
 * ur_mesh_clean welds the two rulings back when a closed mesh is wanted.
 * Likewise a cone's apex is as many vertices as there are rulings, and
 * its triangles of no area are for ur_mesh_clean to drop.
 */
#include "mesh_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static ur_status sample(ur_ruled *ruled, size_t along, size_t across, ur_vec3 *vertices,
                        ur_error *error)
{
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    for (size_t i = 0; i <= along; i++) {
        /* The last ruling exactly at u1, not u0 plus a rounded sum. */
        double u = i == along ? u1 : u0 + (u1 - u0) * (double)i / (double)along;
        ur_vec3 rails[4];
        ur_ruled_rails(ruled, u, rails);
        ur_vec3 ruling = ur_vec3_sub(rails[2], rails[0]);
        for (size_t j = 0; j <= across; j++) {
            ur_vec3 p = ur_vec3_add_scaled(rails[0], ruling, (double)j / (double)across);
            if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(p.z))
                return ur_error_set(error, UR_ERROR_INPUT,
                                    "the surface has no finite point at u = %g, v = %g", u,
                                    (double)j / (double)across);
            vertices[i * (across + 1) + j] = p;
        }
    }
    return UR_OK;
}

/* Splits quad (i, j) on its shorter diagonal into triangles t and t + 1. */
static void split_quad(const ur_vec3 *vertices, size_t across, size_t i, size_t j,
                       size_t (*triangles)[3], size_t t)
{
    size_t p00 = i * (across + 1) + j, p01 = p00 + 1;
    size_t p10 = p00 + across + 1, p11 = p10 + 1;
    double d0 = ur_vec3_distance(vertices[p00], vertices[p11]);
    double d1 = ur_vec3_distance(vertices[p10], vertices[p01]);
    size_t first[3] = {p00, p10, p11}, second[3] = {p00, p11, p01};
    if (d1 < d0) {
        first[2] = p01;
        second[0] = p10;
        second[1] = p11;
        second[2] = p01;
    }
    for (int k = 0; k < 3; k++) {
        triangles[t][k] = first[k];
        triangles[t + 1][k] = second[k];
    }
}

ur_status ur_mesh_from_ruled(ur_ruled *ruled, size_t along, size_t across, ur_mesh *mesh,
                             ur_error *error)
{
    memset(mesh, 0, sizeof *mesh);
    if (along < 1 || across < 1)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "a mesh of a surface needs at least 1 part along and across it "
                            "(not %zu and %zu)",
                            along, across);
    if (along >= SIZE_MAX / 8 / across)
        return ur_error_set(error, UR_ERROR_INPUT, "%zu by %zu parts are too many for a mesh",
                            along, across);
    size_t vertex_count = (along + 1) * (across + 1), triangle_count = 2 * along * across;
    mesh->vertices = ur_alloc_array(vertex_count, sizeof *mesh->vertices, error);
    mesh->triangles = ur_alloc_array(triangle_count, sizeof *mesh->triangles, error);
    mesh->groups = ur_alloc_array(triangle_count, sizeof *mesh->groups, error);
    if (!mesh->vertices || !mesh->triangles || !mesh->groups) {
        ur_mesh_free(mesh);
        return UR_ERROR_MEMORY;
    }
    ur_status status = sample(ruled, along, across, mesh->vertices, error);
    if (status != UR_OK) {
        ur_mesh_free(mesh);
        return status;
    }
    for (size_t i = 0; i < along; i++)
        for (size_t j = 0; j < across; j++)
            split_quad(mesh->vertices, across, i, j, mesh->triangles, 2 * (i * across + j));
    mesh->vertex_count = vertex_count;
    mesh->triangle_count = triangle_count;
    mesh->group_count = 1;
    return UR_OK;
}
