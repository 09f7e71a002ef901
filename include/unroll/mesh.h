/*
 * unroll/mesh.h: indexed triangle meshes, the input of approximate
 * flattening: building one (from points and triangles, or by triangulating a
 * ruled surface), cleaning it (welding, dropping degenerate triangles and
 * unused vertices, making the orientation consistent, refusing non-manifold
 * edges), edge adjacency, and cutting it into pieces that are topological
 * disks (user seams and group boundaries always cut).
 */
#ifndef UNROLL_MESH_H
#define UNROLL_MESH_H

#include <stdbool.h>
#include <stddef.h>

#include "unroll/base.h"
#include "unroll/geom.h"
#include "unroll/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* No twin: a boundary edge. */
#define UR_NO_EDGE ((size_t)-1)

typedef struct ur_mesh {
    ur_vec3 *vertices; /* owned */
    size_t vertex_count;
    size_t (*triangles)[3]; /* owned: vertex indices, counter-clockwise seen from outside */
    size_t triangle_count;
    size_t *groups; /* owned: per triangle, its group (OBJ group or object); pieces never cross */
    size_t group_count;
} ur_mesh;

/*
 * Copies the arrays into a new mesh; groups may be NULL (one group). Indices are checked.
 * Refuses (UR_ERROR_INPUT) a NaN or infinite coordinate, naming the vertex,
 * and an index out of range, naming the triangle (both from 1).
 * group_count is one more than the largest group.
 */
UR_API ur_status ur_mesh_new(const ur_vec3 *vertices, size_t vertex_count,
                             const size_t (*triangles)[3], size_t triangle_count,
                             const size_t *groups, ur_mesh *mesh, ur_error *error);

UR_API void ur_mesh_free(ur_mesh *mesh);

/* What ur_mesh_clean changed, for the user to read. */
typedef struct ur_mesh_repairs {
    size_t welded;     /* vertices merged into another within the tolerance */
    size_t degenerate; /* zero-area triangles dropped */
    size_t isolated;   /* vertices no triangle uses, dropped */
    size_t flipped;    /* triangles turned to agree with their neighbours */
    size_t split;      /* vertices copied to take apart surfaces that touch along an edge */
    size_t flaps;      /* pairs of triangles back to back on the same corners, dropped */
    size_t kept_apart; /* vertices left unwelded: welding would put 3+ triangles on an edge */
    size_t duplicates; /* triangles on the same corners as an earlier one (a face given twice) */
} ur_mesh_repairs;

/*
 * Welds vertices closer than weld_tolerance (mm), drops zero-area triangles,
 * flaps of no thickness and unused vertices, and orients every connected
 * part consistently.  A flap is two triangles on the same three corners,
 * back to back, that stand on the surface: taken away, they leave each of
 * their edges with two triangles or none, and one edge with two (Blender's
 * monkey head has one under its chin).  A face given twice (two triangles
 * on the same corners the same way round, or the other way round where an
 * edge of theirs carries an odd number of triangles and at most one, on
 * the rim, carries the two alone) keeps its first triangle in the input;
 * a sheet with a face on each side is kept whole.
 * Refuses (UR_ERROR_INPUT, naming a vertex) NaN or infinite coordinates, a
 * mesh with no triangles left, and non-manifold edges (three or more
 * triangles on one edge), which cannot be repaired safely.  An edge that
 * only welding made non-manifold (two parts that touch, each with its own
 * vertices) is not: the vertices welded into its ends are left apart.  Nor
 * is an edge of four (or six...) triangles whose ends the surfaces share
 * in the input: each surface round an end (a fan of triangles joined
 * across manifold edges) gets its own copy of the vertex, and the edge
 * comes apart if the copies leave no edge of more than two triangles.
 *
 * Welding merges each vertex, in order, into the nearest vertex kept before
 * it at a distance <= weld_tolerance (0 merges identical points only); it
 * is not transitive, so a tolerance never collapses a fine mesh.  A
 * triangle has zero area when two corners weld together or its area is at
 * most 1e-12 times the square of the bounding box's diagonal.  Kept
 * vertices keep their input order.  A part that cannot be oriented (a
 * Mobius strip) is refused; a closed part is turned outward (positive
 * signed volume), an open one the way most of its triangles already run.
 * On failure the mesh is left as it was.  Messages number input vertices
 * and triangles from 1.
 */
UR_API ur_status ur_mesh_clean(ur_mesh *mesh, double weld_tolerance, ur_mesh_repairs *repairs,
                               ur_error *error);

/* Where ur_mesh_clean_map puts an input vertex it dropped. */
#define UR_NO_VERTEX ((size_t)-1)

/*
 * ur_mesh_clean that also says where each input vertex went, so that seams
 * given by input vertex numbers can follow the welding and renumbering:
 * (*vertex_map)[v] is the cleaned vertex of input vertex v (its welded
 * partner's for a welded one), or UR_NO_VERTEX when it was dropped.  The
 * caller frees *vertex_map; it is NULL on failure, when the mesh is left as
 * it was.
 */
UR_API ur_status ur_mesh_clean_map(ur_mesh *mesh, double weld_tolerance, ur_mesh_repairs *repairs,
                                   size_t **vertex_map, ur_error *error);

/*
 * Half-edge k of triangle t runs from corner k to corner k + 1 (mod 3) and
 * is numbered 3 t + k; twins[3 t + k] is the half-edge of the neighbouring
 * triangle on the same edge, or UR_NO_EDGE on the boundary.  The caller
 * frees *twins.  Refuses (UR_ERROR_INPUT, *twins NULL) an edge of three or
 * more triangles: "non-manifold edge between vertices A and B (N
 * triangles)".
 */
UR_API ur_status ur_mesh_twins(const ur_mesh *mesh, size_t **twins, ur_error *error);

/* An edge the user marks as a seam, by its two vertex indices. */
typedef struct ur_seam {
    size_t a, b;
} ur_seam;

/*
 * Splits the mesh into pieces: connected across edges that are not seams
 * (user seams, group boundaries), each then cut further along a cut graph
 * of edges until it is a topological disk (one boundary loop, Euler
 * characteristic 1), so that closed and higher-genus meshes work.  Each
 * piece is a mesh of its own (vertices on cuts duplicated); original[i]
 * names the input vertex of its vertex i.  The caller frees them with
 * ur_mesh_pieces_free.
 *
 * The mesh must be manifold and consistently oriented (as ur_mesh_clean
 * leaves it); each seam must be an edge of it.  Cuts follow shortest paths
 * (by edge length): from a piece's first boundary loop to its others, in
 * loops through one vertex around the handles of a closed piece, and from
 * pole to pole (two vertices far apart) on a closed piece of genus 0.
 * Pieces come in the order of their first triangle; a piece keeps the
 * triangles' order, corners and groups, and the mesh's group_count.
 * Every piece is checked to be a disk before it is returned.
 */
typedef struct ur_mesh_piece {
    ur_mesh mesh;
    size_t *original;         /* owned: input vertex of each piece vertex */
    size_t *source_triangles; /* owned: input triangle of each piece triangle */
} ur_mesh_piece;

UR_API ur_status ur_mesh_pieces(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                                ur_mesh_piece **pieces, size_t *piece_count, ur_error *error);

UR_API void ur_mesh_pieces_free(ur_mesh_piece *pieces, size_t piece_count);

/*
 * The boundary of a disk as one loop of vertex indices, in the order the
 * triangles run (counter-clockwise seen from outside); the caller frees it.
 * Refuses (UR_ERROR_INPUT, saying why) a mesh that is not a disk: closed,
 * several boundary loops, Euler characteristic other than 1, a boundary
 * through a vertex twice, or triangles not consistently oriented.
 */
UR_API ur_status ur_mesh_boundary(const ur_mesh *mesh, size_t **loop, size_t *count,
                                  ur_error *error);

/* 3D area (sum of triangle areas). */
UR_API double ur_mesh_area(const ur_mesh *mesh);

/* The diagonal of the mesh's bounding box (0 without vertices): its size. */
UR_API double ur_mesh_size(const ur_mesh *mesh);

/* A triangle of less area than this times the square of the mesh's size has none. */
#define UR_MESH_ZERO_AREA 1e-12

/* Refuses (UR_ERROR_INPUT, naming it 1-based) a vertex with a NaN or infinite coordinate. */
UR_API ur_status ur_mesh_check_vertices(const ur_vec3 *vertices, size_t count, ur_error *error);

/*
 * Triangulates a ruled surface over its whole domain: along + 1 rulings
 * evenly spaced in u, each cut into across parts, every quad split on its
 * shorter diagonal.  Vertex (i, j), ruling i and point j along it, is
 * i (across + 1) + j; triangles run counter-clockwise in (u, v), so normals
 * point along r_u x r_v.  A closed surface keeps its last ruling as
 * vertices of their own, equal to the first: the mesh is one disk, already
 * cut along the first ruling (ur_mesh_clean welds them when a closed mesh
 * is wanted, and welds a cone's apex, which is one vertex per ruling).
 */
UR_API ur_status ur_mesh_from_ruled(ur_ruled *ruled, size_t along, size_t across, ur_mesh *mesh,
                                    ur_error *error);

/*
 * ---- Bands between parallel planes (bands.c) ----
 *
 * To flatten a mesh in strips (flatten.h, ur_flatten_strips_mesh) it is
 * cut by parallel planes into bands.  The planes are perpendicular to the
 * direction in which the surface turns most, so that each band runs along
 * the way it turns least, as a boat's planks run along its hull: a band of
 * a cylinder lies along the axis and is exactly developable.  A narrow
 * band strains by about its Gaussian curvature times the square of its
 * width whichever way it runs, but on a saddle bent more one way than the
 * other, bands along the flatter way need fewer of them (test_strips.c).
 * Parallel planes suit open shells best: on a closed tube the bands at its
 * flanks, where the planes touch it, fold round it and come out about
 * twice as wide as the others, and strain most.
 */

/*
 * The unit vector in which the mesh's normals vary most: the eigenvector
 * of the largest eigenvalue of the normals' spread about their mean,
 * sum over the triangles of area (n - m)(n - m)^T, n a triangle's unit
 * normal and m their area-weighted mean.  For a cylinder it is
 * perpendicular to the axis (for part of one, along the chord of its arc),
 * for a sphere or a saddle as curved one way as the other any direction
 * across it will do.  A flat mesh, whose normals do not vary, gives the
 * direction of its longest extent.  Normals are taken as the triangles
 * run, so the mesh must be consistently oriented (ur_mesh_clean); the sign
 * makes the largest component positive.  Refuses (UR_ERROR_INPUT) a mesh
 * with no triangles or no area.
 */
UR_API ur_status ur_mesh_bending_direction(const ur_mesh *mesh, ur_vec3 *direction,
                                           ur_error *error);

/*
 * The tightest bend of the mesh (mm) and the middle of the edge where it
 * is: over its edges, the edge's length divided by the angle (radians)
 * between its ends' normals, each vertex's normal its triangles' weighted
 * by their angles there.  The least over the edges approaches the
 * smallest radius of curvature (a regular n-sided prism of radius r: r
 * sin(pi/n) / (pi/n)).  INFINITY for a flat mesh; UR_ERROR_MEMORY only.
 */
UR_API ur_status ur_mesh_tightest_bend(const ur_mesh *mesh, double *radius, ur_vec3 *at,
                                       ur_error *error);

/*
 * Offsets (p . d, d the unit direction) of count - 1 planes, increasing,
 * into planes[0 .. count - 2], that cut the mesh into count bands of about
 * the same width measured on the surface: width accumulates along d as
 * area over section length, so that where the surface runs nearly parallel
 * to the planes (the flanks of a whole cylinder) they come closer
 * together, and a gap in the mesh takes no band.  Nothing is written for
 * count 1.  Refuses (UR_ERROR_INPUT) count 0, a direction of no length and
 * a mesh with no extent along it.
 */
UR_API ur_status ur_mesh_band_planes(const ur_mesh *mesh, ur_vec3 direction, size_t count,
                                     double *planes, ur_error *error);

/*
 * Cuts the mesh into count bands between the count - 1 planes p . d =
 * planes[j] (d the unit direction, planes increasing): every triangle a
 * plane crosses is split along it, each part triangulated, so that the
 * bands' edges are the plane sections and neighbouring bands share them
 * vertex for vertex.  Band b lies between planes[b - 1] and planes[b] (the
 * first and the last reach to infinity); a triangle of band b in group g
 * gets group b * mesh->group_count + g, so ur_mesh_pieces separates the
 * bands (and the groups, as before) and b is group / mesh->group_count.
 * Triangles come band by band, each band's in the order of the triangles
 * they come from, so that pieces come in band order; a triangle keeps its
 * orientation.  The vertices of the mesh come first with their numbers,
 * then the points where planes cross edges, once per edge and plane.  A
 * vertex within a hundred-thousandth of the mesh's extent along d of a
 * plane is taken to lie on it, so that no sliver of a triangle comes out
 * (one too small to flatten); the area is kept to rounding.  Free the result with ur_mesh_free.
 * Refuses (UR_ERROR_INPUT) count 0, planes that do not increase, a direction of no length and a
 * mesh with no triangles or a bad vertex or index.
 */
UR_API ur_status ur_mesh_bands(const ur_mesh *mesh, ur_vec3 direction, const double *planes,
                               size_t count, ur_mesh *banded, ur_error *error);

/*
 * Cuts a piece in two along its length: across the line where the
 * distance along its edges from one end (the far end of a double sweep)
 * splits its area in two.  A ribbon that winds round comes out as two
 * halves that each wind half as far, where planes would cut it at every
 * turn.  The result is as ur_mesh_bands leaves it with two bands (groups
 * b * mesh->group_count + g); free it with ur_mesh_free.  The cut runs
 * through triangles, so a single one is halved too.  Refuses
 * (UR_ERROR_INPUT) the meshes cutting refuses (ur_mesh_pieces).
 */
UR_API ur_status ur_mesh_halve(const ur_mesh *mesh, ur_mesh *halves, ur_error *error);

/*
 * The same cut into parts pieces of equal area, one after another along
 * the piece's length (ur_mesh_halve is parts 2): for a flat piece too long
 * for any sheet, whatever its count of triangles.  Refuses
 * (UR_ERROR_INPUT) parts below 2.
 */
UR_API ur_status ur_mesh_split_along(const ur_mesh *mesh, size_t parts, ur_mesh *split,
                                     ur_error *error);

/*
 * The same cut into parts pieces of equal area at the levels of field, a
 * value at each vertex taken as linear over each triangle (field[v] for
 * vertex v): with a flat piece's position along its longer side, the cuts
 * run straight across it.  The result is as ur_mesh_split_along's.  Refuses
 * (UR_ERROR_INPUT) parts below 2, a value that is not finite, and the
 * meshes ur_mesh_bands refuses.
 */
UR_API ur_status ur_mesh_split_by(const ur_mesh *mesh, const double *field, size_t parts,
                                  ur_mesh *split, ur_error *error);

#ifdef __cplusplus
}
#endif

#endif
