/*
 * bend.c: how tightly a mesh bends (ur_mesh_tightest_bend), for a piece
 * that is to be bent, not folded, into shape: a material has a smallest
 * radius it bends to without cracking.
 *
 * The surface's normal turns along an edge from one end's normal to the
 * other's: by the angle phi between them over the edge's length L, a rate
 * of |dn/ds| = phi / L.  Over all directions that rate is largest, equal
 * to the largest principal curvature in size, along the direction that
 * bends most, so the tightest radius is the least L / phi over the edges.
 * A vertex's normal is the mean of its triangles' normals weighted by
 * their angles there, which sees a quad split in two as the quad
 * [Thurmer1998].  Triangle by triangle instead (the angle between two
 * triangles' normals over their heights) the twist of a ruled surface's
 * thin quads, folded along their diagonals, came out as a bend 3.5 times
 * too tight: 14.3 mm for a hyperbolic paraboloid whose smallest bend
 * radius is 50 mm.
 *
 * On a regular n-sided prism of radius r it is r sin(pi/n) / (pi/n) along
 * its rims: the cylinder's radius, less 0.16 % at 32 sides.
 */
#include "mesh_internal.h"

#include <math.h>
#include <stdlib.h>

/* The angle of triangle t at its corner k. */
static double corner_angle(const ur_mesh *mesh, size_t t, int k)
{
    const size_t *v = mesh->triangles[t];
    ur_vec3 p = mesh->vertices[v[k]];
    ur_vec3 a = ur_vec3_sub(mesh->vertices[v[(k + 1) % 3]], p);
    ur_vec3 b = ur_vec3_sub(mesh->vertices[v[(k + 2) % 3]], p);
    return atan2(ur_vec3_length(ur_vec3_cross(a, b)), ur_vec3_dot(a, b));
}

/* Each vertex's unit normal, its triangles' unit normals weighted by their angles there. */
static ur_vec3 *vertex_normals(const ur_mesh *mesh, ur_error *error)
{
    ur_vec3 *normals =
        ur_alloc_array(mesh->vertex_count ? mesh->vertex_count : 1, sizeof *normals, error);
    if (!normals)
        return NULL;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        normals[v] = ur_vec3_make(0, 0, 0);
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const size_t *v = mesh->triangles[t];
        ur_vec3 a = mesh->vertices[v[0]];
        ur_vec3 n = ur_vec3_cross(ur_vec3_sub(mesh->vertices[v[1]], a),
                                  ur_vec3_sub(mesh->vertices[v[2]], a));
        double length = ur_vec3_length(n);
        if (!(length > 0))
            continue; /* a degenerate triangle has no normal to give */
        for (int k = 0; k < 3; k++)
            normals[v[k]] = ur_vec3_add_scaled(normals[v[k]], n, corner_angle(mesh, t, k) / length);
    }
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        double length = ur_vec3_length(normals[v]);
        normals[v] = length > 0 ? ur_vec3_scale(normals[v], 1 / length) : normals[v];
    }
    return normals;
}

ur_status ur_mesh_tightest_bend(const ur_mesh *mesh, double *radius, ur_vec3 *at, ur_error *error)
{
    *radius = INFINITY;
    *at = ur_vec3_make(0, 0, 0);
    ur_vec3 *normals = vertex_normals(mesh, error);
    if (!normals)
        return UR_ERROR_MEMORY;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            size_t a = mesh->triangles[t][k], b = mesh->triangles[t][(k + 1) % 3];
            ur_vec3 n = normals[a], m = normals[b];
            if (!(ur_vec3_length(n) > 0 && ur_vec3_length(m) > 0))
                continue;
            double phi = atan2(ur_vec3_length(ur_vec3_cross(n, m)), ur_vec3_dot(n, m));
            double length = ur_vec3_distance(mesh->vertices[a], mesh->vertices[b]);
            if (phi > 0 && length / phi < *radius) {
                *radius = length / phi;
                *at = ur_vec3_scale(ur_vec3_add(mesh->vertices[a], mesh->vertices[b]), 0.5);
            }
        }
    free(normals);
    return UR_OK;
}
