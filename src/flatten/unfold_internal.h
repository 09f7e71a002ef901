/*
 * unfold_internal.h: what the files of the exact unfolding share: the
 * mesh's edges with their bends and what may never be folded
 * (unfold_edges.c), how two flat triangles touch and a hash grid to find
 * the triangles near one (unfold_contact.c), the state of a growing piece
 * (unfold.c), laying one triangle on it (unfold_lay.c) and turning a grown
 * piece into its outline and folds (unfold_piece.c).
 */
#ifndef UNROLL_UNFOLD_INTERNAL_H
#define UNROLL_UNFOLD_INTERNAL_H

#include "unroll/flatten.h"

#include <geos_c.h>

/*
 * Flat points closer than this fraction of the mesh's size meet: edges
 * that land within it of each other are joined, triangles that come within
 * it touch.  Coordinates read from files are often 32-bit floats (7
 * digits), so that the triangles round a flat vertex or along a straight
 * crease of a modelled mesh close up only to about 1e-7 of its size; a
 * millionth is still far below what a cutter can tell (0.1 um on 100 mm).
 */
#define UNFOLD_CONTACT 1e-6

/* No piece, no corner, no entry. */
#define UNFOLD_NONE ((size_t)-1)

/* Half-edge k of triangle t runs from corner k to corner k + 1 and is numbered 3 t + k. */
static inline size_t unfold_next(size_t half)
{
    return half - half % 3 + (half % 3 + 1) % 3;
}

static inline size_t unfold_from(const ur_mesh *mesh, size_t half)
{
    return mesh->triangles[half / 3][half % 3];
}

static inline size_t unfold_to(const ur_mesh *mesh, size_t half)
{
    return mesh->triangles[half / 3][(half % 3 + 1) % 3];
}

/* The mesh's edges, per half-edge. */
typedef struct unfold_edges {
    size_t *twins; /* ur_mesh_twins */
    double *bend;  /* signed turn of the surface across the edge: > 0 convex, 0 on the boundary */
    bool *cut;     /* never folded: the boundary, a group boundary, a user seam */
    double scale;  /* the diagonal of the mesh's bounding box */
    double mean_edge;
} unfold_edges;

/*
 * Checks the mesh (see ur_unfold for what is refused), pairs its edges and
 * measures their bends.  Free with unfold_edges_free, also on failure.
 */
ur_status unfold_edges_build(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                             unfold_edges *edges, ur_error *error);
void unfold_edges_free(unfold_edges *edges);

/*
 * How a candidate triangle t touches a laid one q, both counter-clockwise:
 * overlap when their interiors overlap deeper than eps; otherwise the bits
 * of t_near (q_near) are the corners of t (q) within eps of the other
 * triangle.  Where two triangles touch without overlapping, the contact is
 * a point or a segment whose ends are among those corners.
 */
typedef struct unfold_contact {
    bool overlap;
    unsigned t_near, q_near;
} unfold_contact;

unfold_contact unfold_triangle_contact(const ur_vec2 t[3], const ur_vec2 q[3], double eps);

/*
 * The triangles of the growing piece, bucketed by the square cells their
 * boxes cover (cells of about a mean edge, hashed into slots), so that
 * laying a triangle looks at its neighbours only.  A triangle whose box
 * covers many cells is kept on a list that every query reads.
 */
typedef struct unfold_grid {
    double cell;
    size_t mask;        /* slots - 1, a power of two less one */
    size_t *head;       /* per slot: first entry */
    size_t *head_piece; /* per slot: the piece head belongs to (else the slot is empty) */
    size_t piece;       /* the piece being grown */
    size_t *entry_item; /* per entry: a triangle */
    size_t *entry_next; /* per entry: the next in its slot */
    size_t entry_count, entry_capacity;
    size_t *big; /* triangles on every query's list */
    size_t big_count;
    size_t *seen; /* per triangle: the last query that found it */
    size_t query;
    size_t *found; /* what the last query found */
    size_t found_count;
} unfold_grid;

ur_status unfold_grid_init(unfold_grid *grid, size_t triangle_count, double cell, ur_error *error);
void unfold_grid_free(unfold_grid *grid);

/* Empties the grid for a new piece. */
void unfold_grid_restart(unfold_grid *grid);

ur_status unfold_grid_add(unfold_grid *grid, ur_box box, size_t triangle, ur_error *error);

/* Fills grid->found with every triangle whose box may meet box, once each. */
void unfold_grid_query(unfold_grid *grid, ur_box box);

/* A piece being grown and the mesh it comes from. */
typedef struct unfolder {
    const ur_mesh *mesh;
    unfold_edges edges;
    size_t *piece;      /* per triangle: the piece it is laid in, or UNFOLD_NONE */
    ur_vec2 (*flat)[3]; /* per triangle: its corners, once laid */
    bool *joined;       /* per half-edge: joined to its twin inside a piece */
    size_t *parent;     /* union-find over corners 3 t + k: the flat vertices of pieces */
    size_t *members;    /* the triangles of the current piece, in the order laid */
    size_t member_count;
    size_t current; /* the number of the piece being grown */
    double eps;     /* UNFOLD_CONTACT of the mesh's size */
} unfolder;

/* The union-find root of corner c (with path halving). */
size_t unfold_find(unfolder *u, size_t corner);

/*
 * A triangle about to be laid (unfold_lay.c): across half-edge entry of
 * its own, from the laid triangle on the other side.
 */
typedef struct unfold_candidate {
    size_t triangle, entry;
    ur_vec2 corner[3]; /* flat corners in the triangle's corner order */
    size_t join[3];    /* per half-edge k: the laid twin it is joined to, or UNFOLD_NONE */
    size_t root[3][2]; /* per corner: the flat vertices (roots) it is one with, or UNFOLD_NONE */
} unfold_candidate;

/* The first triangle of a piece: corner 0 at the origin, corner 1 along +x. */
void unfold_seed(const unfolder *u, size_t triangle, unfold_candidate *c);

/*
 * Lays the triangle of half-edge entry on the laid triangle across it,
 * and joins it along its other edges too where it lands on a laid twin
 * edge on edge, closing the ring of triangles around a flat vertex.
 * False when that would join it on all three edges (filling a hole, which
 * a disk has not: rounding).
 */
bool unfold_prepare(unfolder *u, size_t entry, unfold_candidate *c);

/*
 * Whether the candidate fits the piece: overlaps none of its triangles and
 * touches them only at the flat vertices it is joined to.
 */
bool unfold_fits(unfolder *u, unfold_grid *grid, const unfold_candidate *c);

/* Lays the candidate in piece u->current: its corners, joins, flat vertices, grid. */
ur_status unfold_commit(unfolder *u, unfold_grid *grid, const unfold_candidate *c, ur_error *error);

/*
 * Turns the piece just grown (u->members) into *piece: triangles and their
 * flat corners, the folds, the outline (walked along the edges not
 * joined) checked to be a simple polygon with GEOS, and the areas.  Frees
 * what it made on failure.
 */
ur_status unfold_piece_build(const unfolder *u, GEOSContextHandle_t geos, ur_unfolded_piece *piece,
                             ur_error *error);

void unfold_piece_free(ur_unfolded_piece *piece);

#endif
