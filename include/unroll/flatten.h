/*
 * unroll/flatten.h: laying a mesh piece (a topological disk) flat with the
 * least strain, and measuring the strain.
 *
 * LSCM (least-squares conformal maps) gives the first layout; ARAP
 * (as-rigid-as-possible) local/global iterations then bring every triangle
 * as close to its 3D shape as the surface allows, by steps bounded so that
 * no triangle turns over.  Where LSCM's layout turns one over (a piece
 * curved far from any flat shape), Tutte's embedding (the boundary on a
 * circle) is the first layout instead, and ARAP follows whatever the
 * method.  The global step's matrix (the cotangent Laplacian) is built and
 * factored once with CHOLMOD; every iteration only solves.  Per triangle,
 * the singular values sigma1 >= sigma2 of the 3D-to-flat map say how much
 * it is stretched (sigma > 1) or compressed (sigma < 1).
 */
#ifndef UNROLL_FLATTEN_H
#define UNROLL_FLATTEN_H

#include <stdint.h>

#include "unroll/develop.h"
#include "unroll/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ur_flatten_method { UR_FLATTEN_ARAP, UR_FLATTEN_LSCM } ur_flatten_method;

/* "arap", "lscm"; ur_flatten_method_from_name returns -1 when unknown. */
UR_API const char *ur_flatten_method_name(ur_flatten_method method);
UR_API int ur_flatten_method_from_name(const char *name);

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
    const ur_context *context; /* stops with UR_ERROR_CANCELLED once it is cancelled; NULL: never */
} ur_flatten_options;

UR_API void ur_flatten_options_default(ur_flatten_options *options);

/*
 * About how many bytes flattening a mesh of triangle_count triangles
 * (ur_flatten, LSCM then ARAP) takes at its peak, with the mesh, its cut
 * pieces, the Laplacian and its Cholesky factor: measured from 10k to 1M
 * triangles (bench/bench_flatten.c), where it grows linearly.  A caller can
 * refuse a mesh that will not fit before it starts.
 */
UR_API size_t ur_flatten_memory_estimate(size_t triangle_count);

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
    bool flipped;           /* some flat triangle is turned over: only a piece with holes, */
                            /* which has no Tutte embedding, whose LSCM layout turns one */
} ur_flat_piece;

/*
 * Flattens a mesh piece; free the result with ur_flat_piece_free.  The
 * piece must be one connected, consistently oriented surface with a
 * boundary and no handle: a topological disk, which may have holes (what
 * ur_mesh_pieces makes).  Refused with UR_ERROR_INPUT otherwise, and for no
 * triangles, a vertex no triangle uses, a triangle of no area, a coordinate
 * that is not finite, or bad options.  options may be NULL (the defaults).
 */
UR_API ur_status ur_flatten(const ur_mesh *piece, const ur_flatten_options *options,
                            ur_flat_piece *flat, ur_error *error);

UR_API void ur_flat_piece_free(ur_flat_piece *flat);

/*
 * Measures a layout made elsewhere (layout: one flat point per vertex of
 * the piece): copies it into a new ur_flat_piece and fills the strain, the
 * areas, coverage, the largest stretch and compression and the flipped
 * flag; iterations is 0.  Free the result with ur_flat_piece_free.
 */
UR_API ur_status ur_flat_piece_measure(const ur_mesh *piece, const ur_vec2 *layout,
                                       ur_flat_piece *flat, ur_error *error);

/*
 * The ARAP energy of a layout: the area-weighted mean over the triangles of
 * |J - R|^2 (Frobenius), J the Jacobian of the 3D-to-flat map and R the
 * rotation closest to it, i.e. (sigma1 - 1)^2 + (sigma2 - 1)^2 for a
 * triangle that is not flipped.  0 for an isometry; dimensionless, so
 * pieces and methods compare.  ARAP minimises it.
 */
UR_API ur_status ur_flatten_energy(const ur_mesh *piece, const ur_vec2 *layout, double *energy,
                                   ur_error *error);

/*
 * The net of a flattened piece (net.c): its boundary loop laid flat
 * (counter-clockwise), its areas, the largest relative error of a boundary
 * edge's length, its strain and its 3D faces.  Free it as part of a
 * ur_net_list.
 */
UR_API ur_status ur_net_from_flat(const ur_mesh *piece, const ur_flat_piece *flat, const char *name,
                                  ur_net *net, ur_error *error);

/*
 * Gives the net the 3D corners of the mesh's triangles listed (all of
 * them when triangles is NULL), replacing any it had: the faces the
 * assembly guide draws (ur_net.faces_3d).
 */
UR_API ur_status ur_net_set_faces(ur_net *net, const ur_mesh *mesh, const size_t *triangles,
                                  size_t count, ur_error *error);

/*
 * ---- Exact unfolding of a polyhedral mesh (unfold.c) ----
 *
 * A low-poly (papercraft) mesh is unfolded along its edges, as Pepakura and
 * Blender's paper model export do: every face keeps its exact shape, laid
 * flat rigidly across the edge it shares with a face already laid, and the
 * faces of a piece hang together along a spanning tree.  The edges joined
 * inside a piece are folds, the others seams (cut, glued when the model is
 * built).  Every piece is a topological disk laid flat without overlap.
 *
 * Orientation: a triangle runs counter-clockwise seen from the outside (as
 * ur_mesh_clean leaves a closed mesh), and the net shows the outside face
 * up, so that every flat triangle runs counter-clockwise too.  Folded with
 * that side up, a convex edge (the surface turns away from the viewer, the
 * crease rises towards them) is a mountain fold, a concave edge a valley.
 */

/*
 * The default flat angle (radians, 0.5 degrees): triangles that turn by
 * less than this across their edge lie in one flat face (see
 * ur_unfold_options).  Quads a modeller made planar and then split in two
 * come out well within it (a torus's quads are flat to 0.0004 degrees after
 * 32-bit export); over a face 100 mm across it is 0.9 mm out of plane.
 */
#define UR_UNFOLD_FLAT_ANGLE (0.5 * M_PI / 180.0)

typedef struct ur_unfold_options {
    /*
     * Triangles that turn by less than flat_angle (radians) across an edge
     * that is not a seam, and whose normals are within it of the first
     * triangle of their face, are one flat face: laid as one rigid unit in
     * its own plane (each point projected on it) and never cut inside.
     * Every joined edge that turns by less than it, or lies inside a face,
     * is flat: no fold line.  0: every triangle is a face of its own.
     */
    double flat_angle;
    /*
     * Seconds spent improving the cut after the greedy growth (see
     * ur_unfold); 0 keeps the greedy result.  Default 1.
     */
    double time_budget;
    size_t max_steps; /* most improvement steps, 0 for no limit but the time */
    /*
     * With max_steps: the search takes at least this many steps for each
     * piece its first 200 steps leave, up to 1,000 in all (a mesh in many
     * pieces is searched longer: each piece costs the nesting far more
     * than a step costs the search).  Default 0: max_steps alone.
     */
    size_t steps_per_piece;
    uint64_t seed; /* of the search's random choices; default 1 */
    /*
     * The room a piece may take (mm, any order): every piece's smallest
     * enclosing rectangle fits it (long side along the long side).  0 x 0:
     * no limit.
     */
    double room_length, room_width;
    /*
     * The narrowest gap (mm) a join may leave between the outline of the
     * piece it moves and the outline of the other piece: no join leaves
     * two edges of a piece's outline closer than this with the outside
     * between them (a slit with no room for a glue tab), nor a wedge
     * narrower than this at a vertex it closes (measured from the far end
     * of the shorter side).  Two edges of a straight or convex stretch of
     * the outline, or with the piece between them, may come closer.  Not
     * kept inside a flat face (nor, unless gap_both_sides, where both edges
     * of a slit can give their tabs to their twins).  0: any gap (pieces
     * only never overlap).
     */
    double min_gap;
    /*
     * Whether the gap is kept even where a face would be left a piece of
     * its own (a UV sphere's thin pole triangles).  Default false: such a
     * face is joined to a neighbour without it, and the search counts
     * each such join (gap_breaks) as it counts a piece.
     */
    bool gap_strands_faces;
    /*
     * Whether the gap is kept on both sides of every slit.  Default false:
     * the last run, after the search, also makes the joins that leave a
     * slit narrower than the gap whose two edges can both give their seam's
     * tab to their twins (a seam needs its tabs on one side only), each
     * twin then kept out of any such slit.
     */
    bool gap_both_sides;
    /*
     * What a join made without the gap costs the search, in pieces, from 0
     * to 1.  Default 1: only single faces are joined so, and the search
     * weighs each such join as the piece it saves.  Below 1, pieces of any
     * size are joined without the gap at the end of each run, and the
     * search prefers them to pieces: far fewer pieces (Blender's UV sphere
     * on A3 with 6 mm tabs: 6 pieces at 1, 3 at 0.5), but more seam edges
     * whose tab finds no room (0 and 9), which the tabs then say.
     */
    double gap_break_cost;
    /*
     * Pieces of less area than this (mm2) are joined without the gap at
     * the end of each run as single faces are (unless gap_strands_faces),
     * each join weighed as gap_break_cost: a piece smaller than a tab is
     * no piece a maker can hold and glue tabs to (Blender's subdivided
     * monkey head with 6 mm tabs: 36 of its 101 pieces under 36 mm2).
     * Default 0: single faces only.
     */
    double small_piece_area;
    /*
     * Called now and then with the phase ("unfolding", "improving") and
     * how far it is, from 0 to 1; NULL for none.
     */
    void (*progress)(void *context, const char *phase, double fraction);
    void *progress_context;
    /* The search stops with UR_ERROR_CANCELLED once it is cancelled (each step); NULL: never. */
    const ur_context *context;
    /*
     * The threads the search may use.  With 2 or more and the room
     * limited, the search with the room taken at any turn runs beside the
     * level one, in a thread of its own with its own copy of the run's
     * state, instead of after it (see ur_unfold).  Default 1: one after
     * the other.
     */
    size_t threads;
    /*
     * Called once, in the unfolding's thread, when the run the search
     * starts from is made, with its cost (its pieces, and its joins made
     * without the gap at gap_break_cost each); NULL: none.  Returning false
     * stops the unfolding there (UR_ERROR_CANCELLED), for a caller that
     * runs several side by side and drops one that starts far behind the
     * others; it may set *threads (the options' threads) for the search
     * that follows, when another unfolding it ran beside has stopped.
     */
    bool (*started)(void *context, double cost, size_t *threads);
    void *started_context;
} ur_unfold_options;

UR_API void ur_unfold_options_default(ur_unfold_options *options);

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
    size_t *triangles;  /* the mesh triangles of the piece */
    ur_vec2 (*flat)[3]; /* each one's flat corners, in the mesh triangle's corner order */
    size_t triangle_count;
    size_t face_count;         /* flat faces (ur_unfold_options.flat_angle) in the piece */
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
    size_t folds;       /* edges folded, in all pieces */
    size_t valleys;     /* of which valley folds */
    size_t flat;        /* edges joined with nothing to fold (inside a flat face) */
    size_t seams;       /* edges between two faces that are cut */
    size_t boundary;    /* edges of one face */
    size_t single_face; /* pieces of one flat face */
    double seam_length; /* of the seams, mm */
    size_t steps;       /* improvement steps done */
    size_t gap_breaks;  /* joins of a single face made without min_gap */
} ur_unfolding;

/*
 * Unfolds a mesh that is manifold and consistently oriented (as
 * ur_mesh_clean leaves it) into pieces; free them with ur_unfolding_free.
 * ur_unfold uses the default options.
 *
 * First the flat faces (options.flat_angle) are laid each as one piece in
 * its own plane, joined across their longest edges first; a face that is
 * not a disk (a ring round a hole) stays cut along the edge that would
 * close it, one of its shortest.  Then pieces are joined across the other
 * edges in order, as Blender's paper model export does: flat edges first,
 * then convex ones from the least to the most turned, concave ones last,
 * longer edges before shorter at equal angles.  A join moves the smaller
 * piece rigidly onto the larger, so that the edge meets, and is kept only
 * if no two triangles overlap, the pieces touch nowhere but along the edge
 * and the points where it closes the ring round a vertex (then the edges
 * that land on each other there are joined too, as round a flat vertex or
 * along a straight crease), and the joined piece fits the room.  Points
 * within a millionth of the mesh's size (or of the error the faces'
 * flattening makes, if larger) meet, so that meshes of 32-bit coordinates
 * close up as well.
 *
 * Then, while the time budget lasts, the order of the edges is changed
 * (Takahashi et al. 2011 search over which edges are cut): a seam edge of
 * one of the smallest pieces goes first, or a fold goes last, and the
 * joining is done again; a change that leaves fewer pieces, or as many with
 * fewer of a single face, or as many with a shorter cut, is kept (worse
 * ones now and then early on, annealing).  After 100 steps with nothing
 * better the walk starts again from the first order, as hot as at first,
 * while max_steps leaves at least 100 more (without max_steps the search
 * stops there); the best of all walks is kept.  The search stops early
 * when the pieces are as few as the mesh's parts.  For a seed and a
 * number of steps the result is always the same;
 * within a time budget the number of steps depends on the machine.  When
 * the room is limited and a join it refused would have fitted it turned,
 * a second search, of half the steps and budget, takes the room at any
 * turn, from the same first order, and the better is kept (the level one
 * when as good).  With options.threads of 2 or more it runs beside the
 * level search from the start, on a state of its own, and is dropped when
 * not needed: the caches a search keeps over its runs then differ, and
 * the pieces may differ from one thread's where a hull kept from an earlier
 * run rounds a piece's size across the room's edge.  Every
 * edge was tried, so a piece of one face had nowhere to go: across every
 * one of its seams it would overlap or touch its neighbour.
 *
 * User seams, the boundaries between groups and the mesh's boundary are
 * never joined.  The outline of every piece is checked to be a simple
 * polygon (GEOS) before it is returned.  Pieces come in the order of their
 * first triangle.
 *
 * Refuses (UR_ERROR_INPUT) an empty mesh, a coordinate that is not finite,
 * a triangle of no area, a non-manifold edge, neighbours that run their
 * edge the same way, a seam that is not an edge of the mesh, options out of
 * range, and a flat face (or triangle) larger than the room, naming it and
 * its size (messages number vertices, triangles and seams from 1).  On
 * failure *out is empty.
 */
UR_API ur_status ur_unfold(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                           ur_unfolding *out, ur_error *error);

/* The same with options (NULL: the defaults). */
UR_API ur_status ur_unfold_with_options(const ur_mesh *mesh, const ur_seam *seams,
                                        size_t seam_count, const ur_unfold_options *options,
                                        ur_unfolding *out, ur_error *error);

UR_API void ur_unfolding_free(ur_unfolding *unfolding);

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
UR_API ur_status ur_flatten_strips_ruled(ur_ruled *ruled, const ur_strip_limits *limits,
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
UR_API ur_status ur_flatten_strips_mesh(const ur_mesh *mesh, const ur_seam *seams,
                                        size_t seam_count, const ur_vec3 *direction,
                                        const ur_strip_limits *limits,
                                        const ur_flatten_options *options, ur_strips *strips,
                                        ur_error *error);

/* Exactly count strips, each flattened, whatever their strain (tried is 1). */
UR_API ur_status ur_strips_of_ruled(ur_ruled *ruled, size_t count,
                                    const ur_flatten_options *options, ur_strips *strips,
                                    ur_error *error);
UR_API ur_status ur_strips_of_mesh(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                                   ur_vec3 direction, size_t count,
                                   const ur_flatten_options *options, ur_strips *strips,
                                   ur_error *error);

UR_API void ur_strips_free(ur_strips *strips);

/*
 * ---- Charts within the material's strain (charts.c) ----
 *
 * A mesh from a modeller cut into charts that each lie flat within the
 * limits (ur_strip_limits: the largest stretch and compression of the
 * 3D-to-flat map): first at its sharp edges, where the faces turn by more
 * than UR_CHART_SHARP_ANGLE (a cube's edges, the rim of a flat base), at
 * the user's seams and between groups, then into disks (ur_mesh_pieces);
 * each is flattened (ur_flatten) and scaled into the limits
 * (ur_flat_piece_fit_limits), and a chart still over them is cut in two
 * the way D-Charts grows its charts (Julius, Kraevoy and Sheffer 2005:
 * regions of like normals grown from two seeds, refitted a few times),
 * each half laid out again, until every chart fits.  A single triangle
 * always fits, so it ends; a flat face (a cube's) is one chart with no
 * strain at all.  Then neighbouring charts are joined wherever the two
 * together are one disk within the limits (smallest first, never across a
 * sharp edge, a seam or a group boundary), and triangles that jut from one
 * chart into another move over where both stay within the limits.  The
 * charts follow the mesh's edges, so their borders are as jagged as its
 * triangles.
 */

/*
 * Faces that turn by more than this across their edge (radians, 30
 * degrees) meet at a sharp edge, where charts are always cut: a cube's
 * edges (90 degrees), the rim of a flat base, not a smooth surface of a
 * few hundred faces (a 32-segment sphere turns by 11).  A turn of 30
 * degrees to a thousandth of a radian is not sharp, so that a tube of 12
 * sides (Blender's torus) is cut the same way at every edge, by nothing
 * but its strain.
 */
#define UR_CHART_SHARP_ANGLE (3.14159265358979323846 / 6)

/* Whether the faces of triangles t and u (neighbours) turn by more than UR_CHART_SHARP_ANGLE. */
UR_API bool ur_chart_edge_is_sharp(const ur_mesh *mesh, size_t t, size_t u);

typedef struct ur_chart {
    /*
     * The chart, a disk: original and source_triangles number the input
     * mesh's vertices and triangles, its groups are theirs.
     */
    ur_mesh_piece piece;
    ur_flat_piece flat; /* its layout, within the limits */
} ur_chart;

typedef struct ur_charts {
    ur_chart *charts; /* owned, in the order of their first input triangle */
    size_t count;
    size_t sharp_edges;                  /* edges cut for being sharp */
    double max_stretch, max_compression; /* the worst over the charts */
    size_t flattened;                    /* layouts made to find them */
} ur_charts;

/*
 * Cuts the mesh, manifold and consistently oriented (as ur_mesh_clean
 * leaves it), into charts within the limits (max_strips is not used), the
 * seams (edges of the mesh, as for ur_mesh_pieces) and group boundaries
 * always cut.  options may be NULL (the defaults).  Refuses
 * (UR_ERROR_INPUT) limits that are not numbers >= 0, a mesh with no
 * triangles, and what ur_mesh_pieces and ur_flatten refuse.  Free the
 * result with ur_charts_free; it is empty on failure.
 */
UR_API ur_status ur_flatten_charts(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                                   const ur_strip_limits *limits, const ur_flatten_options *options,
                                   ur_charts *charts, ur_error *error);

UR_API void ur_charts_free(ur_charts *charts);

/*
 * Scales a layout about the origin so that its strain falls within the
 * limits where the spread of its singular values allows (largest sigma1
 * over smallest sigma2 at most (1 + max_stretch) / (1 - max_compression)),
 * by the factor nearest 1 that does; where it does not, by the factor that
 * leaves both over by the same share of their limit.  Coverage, areas,
 * strain and the largest stretch and compression follow.  A layout within
 * the limits is left as it is.
 */
UR_API void ur_flat_piece_fit_limits(ur_flat_piece *flat, const ur_strip_limits *limits);

#ifdef __cplusplus
}
#endif

#endif
