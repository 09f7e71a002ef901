/*
 * flatten_internal.h: what the files of the flatten module share: each
 * triangle in its own plane (frames.c), the Jacobian of a layout and its
 * strain, the piece's edges and topology (adjacency.c), a thin CHOLMOD
 * wrapper (solver.c), and the two methods, LSCM (lscm.c) and ARAP (arap.c).
 */
#ifndef UNROLL_FLATTEN_INTERNAL_H
#define UNROLL_FLATTEN_INTERNAL_H

#include "unroll/flatten.h"

#include <cholmod.h>

/*
 * A triangle laid in its own plane without distortion: corner 0 at the
 * origin, corner 1 on the positive x axis, corner 2 above it (so the
 * corners run counter-clockwise, as the 3D triangle does seen from
 * outside).  The inverse of the edge matrix [x1 - x0, x2 - x0] is kept
 * because every Jacobian needs it.
 */
typedef struct flat_frame {
    ur_vec2 corner[3];
    double area;
    double cot[3]; /* cotangent of the angle at corner k */
    double inverse[2][2];
} flat_frame;

/*
 * Checks what every function taking a mesh needs (vertices and triangles
 * present, indices in range, finite coordinates, no triangle of zero area)
 * and lays each triangle in its plane.  The caller frees *frames.
 */
ur_status flat_frames(const ur_mesh *mesh, flat_frame **frames, ur_error *error);

/* A 2 x 2 matrix [a b; c d]. */
typedef struct flat_matrix {
    double a, b, c, d;
} flat_matrix;

/* The Jacobian of the map from the triangle's frame to the flat positions of its corners. */
flat_matrix flat_jacobian(const flat_frame *frame, ur_vec2 u0, ur_vec2 u1, ur_vec2 u2);

/*
 * The rotation closest to J (cosine, sine) and |J - R|^2 (Frobenius).  The
 * closest rotation maximises trace(R^T J) = cos (a + d) + sin (c - b): its
 * angle is atan2(c - b, a + d), the rotation of the 2 x 2 SVD's polar
 * factor, with no SVD needed.
 */
double flat_rotation(flat_matrix j, double *cosine, double *sine);

/* The singular values of J and the flat direction of the larger. */
ur_strain flat_strain(flat_matrix j);

/* The Jacobian of triangle t under a layout. */
flat_matrix flat_triangle_jacobian(const ur_mesh *mesh, const flat_frame *frames,
                                   const ur_vec2 *layout, size_t t);

/* The ARAP energy (see ur_flatten_energy) of a layout. */
double flat_energy(const ur_mesh *mesh, const flat_frame *frames, const ur_vec2 *layout);

/*
 * The piece's undirected edges: edges[e] joins vertices edges[e][0] <
 * edges[e][1]; edge_of[3 t + k] is the edge from corner k to corner k + 1
 * of triangle t.  pins are two boundary vertices far apart.
 */
typedef struct flat_topology {
    size_t (*edges)[2];
    size_t edge_count;
    size_t *edge_of;
    size_t pins[2];
} flat_topology;

/*
 * Builds the edges and refuses (UR_ERROR_INPUT) what cannot be laid flat
 * in one piece: an edge of three or more triangles, neighbours that run
 * their edge the same way (inconsistent orientation), an unused vertex,
 * more than one connected part, no boundary (a closed surface) or a handle
 * (genus above 0).  Free with flat_topology_free, also on failure.
 */
ur_status flat_topology_of(const ur_mesh *mesh, flat_topology *topology, ur_error *error);
void flat_topology_free(flat_topology *topology);

/*
 * A sparse symmetric positive definite system factored once and solved
 * many times.  Long-index CHOLMOD (cholmod_l_*) throughout, so that a
 * factor of a large mesh cannot overflow int.
 */
typedef struct flat_solver {
    cholmod_common common;
    bool started;
    size_t size;
    cholmod_factor *factor;
    cholmod_dense *solution, *work_y, *work_e; /* reused by every solve */
} flat_solver;

ur_status flat_solver_start(flat_solver *solver, ur_error *error);
void flat_solver_finish(flat_solver *solver);

/* Room for capacity entries of the upper triangle of a size x size matrix. */
ur_status flat_solver_triplets(flat_solver *solver, size_t size, size_t capacity,
                               cholmod_triplet **triplets, ur_error *error);

/* Adds value at (row, column), mirrored into the upper triangle; duplicates are summed. */
static inline void flat_triplet_add(cholmod_triplet *triplets, size_t row, size_t column,
                                    double value)
{
    SuiteSparse_long *rows = triplets->i, *columns = triplets->j;
    double *values = triplets->x;
    size_t k = triplets->nnz++;
    rows[k] = (SuiteSparse_long)(row < column ? row : column);
    columns[k] = (SuiteSparse_long)(row < column ? column : row);
    values[k] = value;
}

/*
 * Analyses and factors the matrix; consumes (frees) *triplets.  *definite
 * is false, with UR_OK, when CHOLMOD finds the matrix not positive
 * definite, so that the caller can fall back.
 */
ur_status flat_solver_factor(flat_solver *solver, cholmod_triplet **triplets, bool *definite,
                             ur_error *error);

/* A size x columns right-hand side, zeroed; the caller frees it with cholmod_l_free_dense. */
ur_status flat_solver_rhs(flat_solver *solver, size_t columns, cholmod_dense **rhs,
                          ur_error *error);

/* Solves; the solution (column-major, size x columns) stays the solver's. */
ur_status flat_solver_solve(flat_solver *solver, cholmod_dense *rhs, const double **solution,
                            ur_error *error);

/*
 * LSCM (Levy et al. 2002) with the two pins, scaled about pins[0] so that
 * its area is the 3D area.  pins[0] lands at the origin.
 */
ur_status flat_lscm(const ur_mesh *mesh, const flat_frame *frames, const flat_topology *topology,
                    ur_vec2 *layout, ur_error *error);

/*
 * Tutte's embedding (tutte.c): the boundary on a circle, every inner vertex
 * the mean of its neighbours, scaled to the 3D area; no triangle is turned
 * over.  The piece must have one boundary loop (ur_mesh_boundary refuses
 * others, UR_ERROR_INPUT).
 */
ur_status flat_tutte(const ur_mesh *mesh, const flat_frame *frames, const flat_topology *topology,
                     ur_vec2 *layout, ur_error *error);

/*
 * ARAP (Liu et al. 2008) from the layout given, which it improves in
 * place; pin keeps its place.  *iterations counts the global steps done.
 * No step turns a triangle over: from a layout with none turned over,
 * none is after.
 */
ur_status flat_arap(const ur_mesh *mesh, const flat_frame *frames, const flat_topology *topology,
                    size_t pin, const ur_flatten_options *options, ur_vec2 *layout,
                    size_t *iterations, ur_error *error);

#endif
