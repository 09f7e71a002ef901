/*
 * unroll/flatten.h: laying a mesh piece (a topological disk) flat with the
 * least strain, and measuring the strain.
 *
 * LSCM (least-squares conformal maps) gives the first layout; ARAP
 * (as-rigid-as-possible) local/global iterations then bring every triangle
 * as close to its 3D shape as the surface allows.  The global step's matrix
 * (the cotangent Laplacian) is built and factored once with CHOLMOD; every
 * iteration only solves.  Per triangle, the singular values sigma1 >=
 * sigma2 of the 3D-to-flat map say how much it is stretched (sigma > 1) or
 * compressed (sigma < 1).
 */
#ifndef UNROLL_FLATTEN_H
#define UNROLL_FLATTEN_H

#include "unroll/develop.h"
#include "unroll/mesh.h"

typedef enum ur_flatten_method { UR_FLATTEN_ARAP, UR_FLATTEN_LSCM } ur_flatten_method;

/* "arap", "lscm"; ur_flatten_method_from_name returns -1 when unknown. */
const char *ur_flatten_method_name(ur_flatten_method method);
int ur_flatten_method_from_name(const char *name);

typedef struct ur_flatten_options {
    ur_flatten_method method;
    size_t iterations; /* most ARAP iterations; default 100 */
    double tolerance;  /* stop when the energy improves by less than this fraction; 1e-9 */
                       /* (ARAP also stops once ur_flatten_energy is below 1e-14) */
} ur_flatten_options;

void ur_flatten_options_default(ur_flatten_options *options);

/* The strain of one triangle. */
typedef struct ur_strain {
    double sigma1, sigma2; /* singular values of the 3D-to-flat map, sigma1 >= sigma2 */
    ur_vec2 direction;     /* unit flat direction of sigma1 (principal stretch) */
} ur_strain;

typedef struct ur_flat_piece {
    ur_vec2 *flat;     /* owned: flat position of each vertex of the piece's mesh */
    ur_strain *strain; /* owned: per triangle */
    size_t vertex_count, triangle_count;
    double area_3d, flat_area;
    double coverage;        /* flat_area / area_3d */
    double max_stretch;     /* largest sigma1 - 1 (0 when none is stretched) */
    double max_compression; /* largest 1 - sigma2 (0 when none is compressed) */
    size_t iterations;      /* ARAP iterations done */
    bool flipped;           /* some flat triangle is turned over (should never be) */
} ur_flat_piece;

/*
 * Flattens a mesh piece; free the result with ur_flat_piece_free.  The
 * piece must be one connected, consistently oriented surface with a
 * boundary and no handle: a topological disk, which may have holes (what
 * ur_mesh_pieces makes).  Refused with UR_ERROR_INPUT otherwise, and for no
 * triangles, a vertex no triangle uses, a triangle of no area, a coordinate
 * that is not finite, or bad options.  options may be NULL (the defaults).
 */
ur_status ur_flatten(const ur_mesh *piece, const ur_flatten_options *options, ur_flat_piece *flat,
                     ur_error *error);

void ur_flat_piece_free(ur_flat_piece *flat);

/*
 * Measures a layout made elsewhere (layout: one flat point per vertex of
 * the piece): copies it into a new ur_flat_piece and fills the strain, the
 * areas, coverage, the largest stretch and compression and the flipped
 * flag; iterations is 0.  Free the result with ur_flat_piece_free.
 */
ur_status ur_flat_piece_measure(const ur_mesh *piece, const ur_vec2 *layout, ur_flat_piece *flat,
                                ur_error *error);

/*
 * The ARAP energy of a layout: the area-weighted mean over the triangles of
 * |J - R|^2 (Frobenius), J the Jacobian of the 3D-to-flat map and R the
 * rotation closest to it, i.e. (sigma1 - 1)^2 + (sigma2 - 1)^2 for a
 * triangle that is not flipped.  0 for an isometry; dimensionless, so
 * pieces and methods compare.  ARAP minimises it.
 */
ur_status ur_flatten_energy(const ur_mesh *piece, const ur_vec2 *layout, double *energy,
                            ur_error *error);

/*
 * The net of a flattened piece (net.c): its boundary loop laid flat
 * (counter-clockwise), its areas, the largest relative error of a boundary
 * edge's length, and its strain.  Free it as part of a ur_net_list.
 */
ur_status ur_net_from_flat(const ur_mesh *piece, const ur_flat_piece *flat, const char *name,
                           ur_net *net, ur_error *error);

#endif
