/*
 * tutte.c: a layout that turns no triangle over, for ARAP to start from
 * when LSCM's does (Tutte 1963, Floater 1997).
 *
 * The boundary loop goes round a circle, each vertex at its share of the
 * loop's 3D length, and every inner vertex sits at the mean of its
 * neighbours: a uniform graph Laplacian solved once (CHOLMOD).  With the
 * boundary on a strictly convex polygon and every inner vertex a convex
 * combination of its neighbours, the layout of a triangulated disk is an
 * embedding: every triangle keeps its orientation.  It is far from
 * isometric; ARAP then lowers the strain with steps that cannot turn a
 * triangle over (arap.c).
 */
#include "flatten_internal.h"

#include <math.h>
#include <stdlib.h>

#define NOT_FREE ((size_t)-1)

/* Puts the loop on a circle of the loop's 3D length, spaced by its edges' 3D lengths. */
static void place_boundary(const ur_mesh *mesh, const size_t *loop, size_t count, ur_vec2 *layout)
{
    double length = 0;
    for (size_t i = 0; i < count; i++)
        length += ur_vec3_distance(mesh->vertices[loop[i]], mesh->vertices[loop[(i + 1) % count]]);
    double radius = length / (2 * M_PI), walked = 0;
    for (size_t i = 0; i < count; i++) {
        double angle = 2 * M_PI * walked / length;
        layout[loop[i]] = ur_vec2_make(radius * cos(angle), radius * sin(angle));
        walked += ur_vec3_distance(mesh->vertices[loop[i]], mesh->vertices[loop[(i + 1) % count]]);
    }
}

/* The inner vertices numbered 0, 1, ...; NOT_FREE on the boundary. */
static size_t number_inner(const ur_mesh *mesh, const size_t *loop, size_t count, size_t *index)
{
    for (size_t v = 0; v < mesh->vertex_count; v++)
        index[v] = 0;
    for (size_t i = 0; i < count; i++)
        index[loop[i]] = NOT_FREE;
    size_t inner = 0;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        if (index[v] != NOT_FREE)
            index[v] = inner++;
    return inner;
}

/* Each edge a weight of 1: the graph Laplacian on the inner vertices, and the boundary's share. */
static void fill_system(const flat_topology *topology, const size_t *index, const ur_vec2 *layout,
                        size_t inner, cholmod_triplet *m, double *rhs)
{
    for (size_t e = 0; e < topology->edge_count; e++) {
        size_t a = topology->edges[e][0], b = topology->edges[e][1];
        size_t i = index[a], j = index[b];
        if (i != NOT_FREE)
            flat_triplet_add(m, i, i, 1);
        if (j != NOT_FREE)
            flat_triplet_add(m, j, j, 1);
        if (i != NOT_FREE && j != NOT_FREE)
            flat_triplet_add(m, i, j, -1);
        else if (i != NOT_FREE || j != NOT_FREE) {
            size_t k = i != NOT_FREE ? i : j;
            ur_vec2 fixed = layout[i != NOT_FREE ? b : a];
            rhs[k] += fixed.x;
            rhs[inner + k] += fixed.y;
        }
    }
}

static ur_status solve_inner(const ur_mesh *mesh, const flat_topology *topology,
                             const size_t *index, size_t inner, ur_vec2 *layout, ur_error *error)
{
    flat_solver solver;
    ur_status status = flat_solver_start(&solver, error);
    if (status)
        return status;
    cholmod_triplet *m = NULL;
    cholmod_dense *rhs = NULL;
    const double *x = NULL;
    bool definite = false;
    status = flat_solver_triplets(&solver, inner, 3 * topology->edge_count, &m, error);
    if (!status)
        status = flat_solver_rhs(&solver, 2, &rhs, error);
    if (!status) {
        fill_system(topology, index, layout, inner, m, rhs->x);
        status = flat_solver_factor(&solver, &m, &definite, error);
    }
    if (!status && !definite)
        status = ur_error_set(error, UR_ERROR_INTERNAL,
                              "Tutte layout: the graph Laplacian is singular (a loose vertex?)");
    if (!status)
        status = flat_solver_solve(&solver, rhs, &x, error);
    if (!status)
        for (size_t v = 0; v < mesh->vertex_count; v++)
            if (index[v] != NOT_FREE)
                layout[v] = ur_vec2_make(x[index[v]], x[inner + index[v]]);
    if (m)
        cholmod_l_free_triplet(&m, &solver.common);
    if (rhs)
        cholmod_l_free_dense(&rhs, &solver.common);
    flat_solver_finish(&solver);
    return status;
}

/* Scales about the origin so that the flat area is the 3D area. */
static void scale_to_area(const ur_mesh *mesh, const flat_frame *frames, ur_vec2 *layout)
{
    double flat = 0, area = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const size_t *c = mesh->triangles[t];
        flat += 0.5 * ur_vec2_cross(ur_vec2_sub(layout[c[1]], layout[c[0]]),
                                    ur_vec2_sub(layout[c[2]], layout[c[0]]));
        area += frames[t].area;
    }
    double scale = flat > 0 ? sqrt(area / flat) : 1;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        layout[v] = ur_vec2_scale(layout[v], scale);
}

ur_status flat_tutte(const ur_mesh *mesh, const flat_frame *frames, const flat_topology *topology,
                     ur_vec2 *layout, ur_error *error)
{
    size_t *loop = NULL, count = 0;
    ur_status status = ur_mesh_boundary(mesh, &loop, &count, error);
    if (status)
        return status;
    size_t *index = ur_alloc_array(mesh->vertex_count, sizeof *index, error);
    if (!index) {
        free(loop);
        return UR_ERROR_MEMORY;
    }
    place_boundary(mesh, loop, count, layout);
    size_t inner = number_inner(mesh, loop, count, index);
    if (inner > 0)
        status = solve_inner(mesh, topology, index, inner, layout, error);
    if (!status)
        scale_to_area(mesh, frames, layout);
    free(index);
    free(loop);
    return status;
}
