/*
 * mesh.c: building, freeing and measuring an indexed triangle mesh, and the
 * checks of raw arrays that every way into a mesh goes through.
 */
#include "mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ur_status ur_mesh_check_vertices(const ur_vec3 *vertices, size_t count, ur_error *error)
{
    for (size_t i = 0; i < count; i++) {
        ur_vec3 p = vertices[i];
        if (!isfinite(p.x) || !isfinite(p.y) || !isfinite(p.z))
            return ur_error_set(error, UR_ERROR_INPUT,
                                "vertex %zu has a coordinate that is not a finite number: "
                                "(%g, %g, %g)",
                                i + 1, p.x, p.y, p.z);
    }
    return UR_OK;
}

ur_status mesh_check_triangles(const size_t (*triangles)[3], size_t count, size_t vertex_count,
                               ur_error *error)
{
    for (size_t t = 0; t < count; t++)
        for (int k = 0; k < 3; k++)
            if (triangles[t][k] >= vertex_count)
                return ur_error_set(error, UR_ERROR_INPUT,
                                    "triangle %zu uses vertex %zu, but the mesh has %zu "
                                    "vertices",
                                    t + 1, triangles[t][k] + 1, vertex_count);
    return UR_OK;
}

/* The number of groups: one more than the largest group number. */
static size_t count_groups(const size_t *groups, size_t triangle_count)
{
    size_t count = 1;
    for (size_t t = 0; groups && t < triangle_count; t++)
        if (groups[t] >= count)
            count = groups[t] + 1;
    return count;
}

ur_status ur_mesh_new(const ur_vec3 *vertices, size_t vertex_count, const size_t (*triangles)[3],
                      size_t triangle_count, const size_t *groups, ur_mesh *mesh, ur_error *error)
{
    memset(mesh, 0, sizeof *mesh);
    ur_status status = ur_mesh_check_vertices(vertices, vertex_count, error);
    if (status == UR_OK)
        status = mesh_check_triangles(triangles, triangle_count, vertex_count, error);
    if (status != UR_OK)
        return status;
    mesh->vertices = ur_alloc_array(vertex_count, sizeof *mesh->vertices, error);
    mesh->triangles = ur_alloc_array(triangle_count, sizeof *mesh->triangles, error);
    mesh->groups = ur_alloc_array(triangle_count, sizeof *mesh->groups, error);
    if (!mesh->vertices || !mesh->triangles || !mesh->groups) {
        ur_mesh_free(mesh);
        return ur_error_out_of_memory(error);
    }
    if (vertex_count > 0)
        memcpy(mesh->vertices, vertices, vertex_count * sizeof *vertices);
    if (triangle_count > 0)
        memcpy(mesh->triangles, triangles, triangle_count * sizeof *triangles);
    if (groups && triangle_count > 0)
        memcpy(mesh->groups, groups, triangle_count * sizeof *groups);
    mesh->vertex_count = vertex_count;
    mesh->triangle_count = triangle_count;
    mesh->group_count = count_groups(groups, triangle_count);
    return UR_OK;
}

void ur_mesh_free(ur_mesh *mesh)
{
    if (!mesh)
        return;
    free(mesh->vertices);
    free(mesh->triangles);
    free(mesh->groups);
    memset(mesh, 0, sizeof *mesh);
}

double ur_mesh_area(const ur_mesh *mesh)
{
    double area = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const size_t *c = mesh->triangles[t];
        ur_vec3 a = mesh->vertices[c[0]];
        ur_vec3 ab = ur_vec3_sub(mesh->vertices[c[1]], a);
        ur_vec3 ac = ur_vec3_sub(mesh->vertices[c[2]], a);
        area += 0.5 * ur_vec3_length(ur_vec3_cross(ab, ac));
    }
    return area;
}

double ur_mesh_size(const ur_mesh *mesh)
{
    if (mesh->vertex_count == 0)
        return 0.0;
    ur_vec3 low = mesh->vertices[0], high = low;
    for (size_t v = 1; v < mesh->vertex_count; v++) {
        ur_vec3 p = mesh->vertices[v];
        low = ur_vec3_make(fmin(low.x, p.x), fmin(low.y, p.y), fmin(low.z, p.z));
        high = ur_vec3_make(fmax(high.x, p.x), fmax(high.y, p.y), fmax(high.z, p.z));
    }
    return ur_vec3_distance(low, high);
}
