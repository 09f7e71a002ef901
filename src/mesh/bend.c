/*
 * bend.c: how tightly a mesh bends (ur_mesh_tightest_bend), for a chart
 * that is to be bent, not folded, into shape: a material has a smallest
 * radius it bends to without cracking.
 *
 * A faceted surface bends only at its edges, each turning by the angle
 * theta between its two faces' normals; spread over the faces on either
 * side, whose widths across the edge are their heights h1 and h2 over it,
 * that is a bend of radius
 *
 *     R = ((h1 + h2) / 2) / theta.
 *
 * On a regular n-sided prism of radius r it is r sin(pi/n) / (pi/n): the
 * cylinder's radius, less 0.16 % at 32 sides.
 */
#include "mesh_internal.h"

#include <math.h>
#include <stdlib.h>

static ur_vec3 triangle_normal(const ur_mesh *mesh, size_t t)
{
    const size_t *v = mesh->triangles[t];
    ur_vec3 a = mesh->vertices[v[0]];
    return ur_vec3_cross(ur_vec3_sub(mesh->vertices[v[1]], a),
                         ur_vec3_sub(mesh->vertices[v[2]], a));
}

/* The radius the two triangles of half-edge h and its twin g bend to; INFINITY where flat. */
static double edge_bend(const ur_mesh *mesh, size_t h, size_t g)
{
    size_t t = h / 3, u = g / 3;
    ur_vec3 a = mesh->vertices[mesh->triangles[t][h % 3]];
    ur_vec3 b = mesh->vertices[mesh->triangles[t][(h + 1) % 3]];
    double length = ur_vec3_distance(a, b);
    ur_vec3 n = triangle_normal(mesh, t), m = triangle_normal(mesh, u);
    double twice_t = ur_vec3_length(n), twice_u = ur_vec3_length(m);
    if (!(length > 0 && twice_t > 0 && twice_u > 0))
        return INFINITY; /* a degenerate triangle says nothing of the bend */
    double theta = atan2(ur_vec3_length(ur_vec3_cross(n, m)), ur_vec3_dot(n, m));
    if (!(theta > 0))
        return INFINITY;
    double mean_height = (twice_t + twice_u) / (2 * length); /* (h1 + h2) / 2 */
    return mean_height / theta;
}

ur_status ur_mesh_tightest_bend(const ur_mesh *mesh, double *radius, ur_vec3 *at, ur_error *error)
{
    *radius = INFINITY;
    *at = ur_vec3_make(0, 0, 0);
    size_t *twins = NULL;
    ur_status status = ur_mesh_twins(mesh, &twins, error);
    if (status != UR_OK)
        return status;
    for (size_t h = 0; h < 3 * mesh->triangle_count; h++) {
        size_t g = twins[h];
        if (g == UR_NO_EDGE || g < h)
            continue;
        double r = edge_bend(mesh, h, g);
        if (r < *radius) {
            size_t t = h / 3;
            *radius = r;
            *at = ur_vec3_scale(ur_vec3_add(mesh->vertices[mesh->triangles[t][h % 3]],
                                            mesh->vertices[mesh->triangles[t][(h + 1) % 3]]),
                                0.5);
        }
    }
    free(twins);
    return UR_OK;
}
