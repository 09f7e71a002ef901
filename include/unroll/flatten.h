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
    /*
     * Called after every ARAP iteration with the iteration's number and the
     * energy, so that a caller can show progress (the library never
     * prints); NULL for none.
     */
    void (*progress)(void *context, size_t iteration, double energy);
    void *progress_context;
} ur_flatten_options;

void ur_flatten_options_default(ur_flatten_options *options);

/*
 * About how many bytes flattening a mesh of triangle_count triangles
 * (ur_flatten, LSCM then ARAP) takes at its peak, with the mesh, its cut
 * pieces, the Laplacian and its Cholesky factor: measured from 10k to 1M
 * triangles (bench/bench_flatten.c), where it grows linearly.  A caller can
 * refuse a mesh that will not fit before it starts.
 */
size_t ur_flatten_memory_estimate(size_t triangle_count);

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
 * edge's length, its strain and its 3D faces.  Free it as part of a
 * ur_net_list.
 */
ur_status ur_net_from_flat(const ur_mesh *piece, const ur_flat_piece *flat, const char *name,
                           ur_net *net, ur_error *error);

/*
 * Gives the net the 3D corners of the mesh's triangles listed (all of
 * them when triangles is NULL), replacing any it had: the faces the
 * assembly guide draws (ur_net.faces_3d).
 */
ur_status ur_net_set_faces(ur_net *net, const ur_mesh *mesh, const size_t *triangles, size_t count,
                           ur_error *error);

/*
 * ---- Exact unfolding of a polyhedral mesh (unfold.c) ----
 *
 * A low-poly (papercraft) mesh is unfolded along its edges, as Pepakura and
 * Blender's paper model export do: every face keeps its exact shape, laid
 * flat rigidly across the edge it shares with a face already laid, and a
 * piece grows face by face along a spanning tree of the faces.  The edges
 * joined inside a piece are folds, the others seams (cut, glued when the
 * model is built).  A face that would overlap its piece, touch it anywhere
 * but along its fold, or close a hole in it starts or joins another piece
 * instead: every piece is a topological disk laid flat without overlap.
 *
 * Orientation: a triangle runs counter-clockwise seen from the outside (as
 * ur_mesh_clean leaves a closed mesh), and the net shows the outside face
 * up, so that every flat triangle runs counter-clockwise too.  Folded with
 * that side up, a convex edge (the surface turns away from the viewer, the
 * crease rises towards them) is a mountain fold, a concave edge a valley.
 */

/*
 * Two faces that turn by less than this (radians) across their edge are
 * flat there: joined, with nothing to fold and no fold line drawn.  Over a
 * face a metre across it moves the far edge by a micrometre; coplanar
 * quads split in two by a modeller come out well within it.
 */
#define UR_UNFOLD_FLAT_ANGLE 1e-6

/* One fold line of a piece. */
typedef struct ur_fold {
    ur_vec2 start, end; /* the edge on the piece */
    size_t a, b;        /* the mesh vertices at start and end */
    bool valley;        /* a concave edge; false: a mountain (convex) */
    /*
     * How far the faces turn at the fold, radians, in (0, pi): pi minus
     * the dihedral angle inside the surface (pi / 2 on a cube's edges).
     */
    double angle;
} ur_fold;

/* One piece of an unfolding, in its own plane coordinates.  All arrays are owned. */
typedef struct ur_unfolded_piece {
    ur_vec2 *outline;         /* its boundary, counter-clockwise, first point not repeated */
    size_t *outline_vertices; /* the mesh vertex at each outline point */
    size_t outline_count;     /* an edge between two pieces shows in both outlines */
    ur_fold *folds;           /* the edges joined inside the piece that fold */
    size_t fold_count;
    size_t *triangles;  /* the mesh triangles of the piece, in the order laid */
    ur_vec2 (*flat)[3]; /* each one's flat corners, in the mesh triangle's corner order */
    size_t triangle_count;
    double area_3d, flat_area; /* sum of the triangles' 3D areas; area inside the outline */
} ur_unfolded_piece;

/*
 * Every edge of the mesh is exactly one of: a fold, a flat join, a seam
 * (two faces cut apart) or a boundary edge (the mesh's own boundary, one
 * face).
 */
typedef struct ur_unfolding {
    ur_unfolded_piece *pieces;
    size_t count;
    size_t folds;    /* edges folded, in all pieces */
    size_t valleys;  /* of which valley folds */
    size_t flat;     /* edges joined with nothing to fold (UR_UNFOLD_FLAT_ANGLE) */
    size_t seams;    /* edges between two faces that are cut */
    size_t boundary; /* edges of one face */
} ur_unfolding;

/*
 * Unfolds a mesh that is manifold and consistently oriented (as
 * ur_mesh_clean leaves it) into pieces; free them with ur_unfolding_free.
 *
 * Pieces grow one at a time from the first face not yet laid, always
 * across the cheapest edge on their border (Prim's algorithm): flat edges
 * first, then convex ones from the least to the most turned, concave ones
 * last, longer edges before shorter at equal angles.  User seams, the
 * boundaries between groups and the mesh's boundary are never folded.
 * Each new face is placed from the two side lengths on its shared edge, so
 * it is congruent to its 3D triangle to rounding.  Where a face closes the
 * ring of faces around a vertex that lies flat (angles summing to 2 pi),
 * or continues a straight crease, it lands on a laid neighbour edge on edge
 * and is joined there too.  Points within a millionth of the mesh's size
 * (the diagonal of its box) meet, so that meshes of 32-bit coordinates
 * close up as well.  The outline of every piece is checked to be a simple
 * polygon (GEOS) before it is returned.  Pieces come in the order grown,
 * the first from triangle 0; where the surface has saddles, whose faces
 * cannot all lie flat round the vertex, the first pieces tend to be large
 * and to leave small pieces of one to a few faces in their notches.
 *
 * Refuses (UR_ERROR_INPUT) an empty mesh, a coordinate that is not finite,
 * a triangle of no area, a non-manifold edge, neighbours that run their
 * edge the same way, and a seam that is not an edge of the mesh (messages
 * number vertices, triangles and seams from 1).  On failure *out is empty.
 */
ur_status ur_unfold(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count, ur_unfolding *out,
                    ur_error *error);

void ur_unfolding_free(ur_unfolding *unfolding);

/*
 * ---- Flattening in strips (strips.c) ----
 *
 * A surface that one piece cannot lay flat within the material's strain is
 * cut into strips, each flattened on its own (ur_flatten), and the fewest
 * strips are found whose worst stretch (sigma1 - 1) and compression
 * (1 - sigma2) stay within the limits.  A ruled surface is cut along its
 * rulings into strips of equal width in u; a mesh is cut by parallel
 * planes into bands (mesh.h, ur_mesh_bands) that run along the way it
 * turns least.  Neighbouring strips share the cut between them, and strips
 * are numbered in order across the surface so that they can be put back
 * together.
 *
 * The search assumes that the worst strain falls as the strips narrow,
 * which it does on a smooth surface: a narrow strip strains by about its
 * Gaussian curvature times the square of its width.  It doubles the count
 * from 1 until the strips fit, then bisects between the last count that
 * did not fit and the first that did, so it flattens about 2 log2 N counts
 * to find N.  Where the strain does not fall steadily (a coarse mesh, a
 * surface whose curvature sits in one place that some counts cut across
 * and others do not) the count found fits, and no count below it that was
 * tried does, but a smaller one that was not tried might.
 *
 * A ruled surface is triangulated with 24 parts across each ruling and,
 * along it, about 96 parts over the whole surface, at least 8 in each
 * strip; each strip is triangulated, cleaned (welding at a millionth of its
 * size) and cut into disks on its own (ur_mesh_from_ruled, ur_mesh_clean,
 * ur_mesh_pieces).
 */

typedef struct ur_strip_limits {
    double max_stretch;     /* largest sigma1 - 1 allowed (0.005 is 0.5 %) */
    double max_compression; /* largest 1 - sigma2 allowed */
    size_t max_strips;      /* refuse a surface that needs more strips than this */
} ur_strip_limits;

/* One piece of one strip. */
typedef struct ur_strip {
    /*
     * The piece, a topological disk, and its layout with its strain.  Its
     * vertices are the strip's own (piece.original numbers the vertices of
     * the strip's mesh before it was cut into disks, of no use outside).
     */
    ur_mesh_piece piece;
    ur_flat_piece flat;
    size_t band; /* which strip, from 0, in order across the surface */
    /*
     * Where the strip lies: for a ruled surface its range of u; for a mesh
     * the offsets along the direction of its two planes (the mesh's extent
     * for the outer side of the first and the last).
     */
    double start, end;
    /*
     * Ruled surfaces: the rulings the piece shares with the strips before
     * and after it (seams[0] at start, then the one at end; on a closed
     * surface the first and the last strip share one too), flat, between
     * the layout's points of the ruling's two ends.  Meshes: none.
     */
    ur_segment seams[2];
    size_t seam_count;
} ur_strip;

typedef struct ur_strips {
    ur_strip *strips;  /* owned: band by band, in order */
    size_t count;      /* pieces: one a strip, more where a band of a mesh falls apart */
    size_t bands;      /* how many strips the surface was cut into */
    ur_vec3 direction; /* meshes: the unit normal of the cutting planes; zero for ruled */
    double max_stretch, max_compression; /* the worst over the pieces */
    bool flipped; /* a piece came out with a triangle turned over (never when within limits) */
    size_t tried; /* ur_flatten_strips_*: how many counts of strips were flattened */
} ur_strips;

/*
 * The fewest strips of the ruled surface (of the part of it in use,
 * ur_ruled_restrict) whose pieces are all laid flat within the limits,
 * none with a triangle turned over.  options may be NULL (the defaults).
 * The surface's restriction is as it was afterwards, also on failure.
 * Refuses (UR_ERROR_INPUT) limits that are not numbers >= 0 or max_strips
 * 0, and a surface that needs more than max_strips strips: "the surface
 * needs more than N strips to stay within 0.5 % stretch and 3 %
 * compression: with N, strip K still stretches ... % and compresses ...
 * %", for the caller to add how to allow more.  Free the result with
 * ur_strips_free; it is empty on failure.
 */
ur_status ur_flatten_strips_ruled(ur_ruled *ruled, const ur_strip_limits *limits,
                                  const ur_flatten_options *options, ur_strips *strips,
                                  ur_error *error);

/*
 * The same for a mesh, manifold and consistently oriented (as
 * ur_mesh_clean leaves it), cut by planes perpendicular to direction, or
 * when it is NULL to ur_mesh_bending_direction, at ur_mesh_band_planes;
 * each band is cut into disks by ur_mesh_pieces, groups and the given
 * seams (edges of the mesh, as for ur_mesh_pieces; a seam edge a plane
 * crosses is cut on both sides of the plane) still cut.
 */
ur_status ur_flatten_strips_mesh(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                                 const ur_vec3 *direction, const ur_strip_limits *limits,
                                 const ur_flatten_options *options, ur_strips *strips,
                                 ur_error *error);

/* Exactly count strips, each flattened, whatever their strain (tried is 1). */
ur_status ur_strips_of_ruled(ur_ruled *ruled, size_t count, const ur_flatten_options *options,
                             ur_strips *strips, ur_error *error);
ur_status ur_strips_of_mesh(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                            ur_vec3 direction, size_t count, const ur_flatten_options *options,
                            ur_strips *strips, ur_error *error);

void ur_strips_free(ur_strips *strips);

#endif
