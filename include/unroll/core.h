/*
 * unroll/core.h: the things every stage of the pipeline passes on to the
 * next: flat nets (what developing or flattening makes), pieces (what
 * will be cut: paths tagged with operations, and the allowances added),
 * and layouts (pieces placed on sheets).  Each stage's own header builds
 * on these; see docs/design.md, "Core types".
 */
#ifndef UNROLL_CORE_H
#define UNROLL_CORE_H

#include "unroll/base.h"
#include "unroll/geom.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Flat nets ---------------------------------------------------------- */

typedef struct ur_segment {
    ur_vec2 start, end;
} ur_segment;

/*
 * The strain of an approximate flattening triangle by triangle, for the
 * strain picture (ur_strain_png_write).  Each triangle of the flattened
 * mesh is given by its three flat corners, in the same coordinates as the
 * outline of the net (or piece) that carries it, with its dominant strain:
 * with sigma1 >= sigma2 the singular values of its 3D-to-flat map (see
 * flatten.h), the strain is sigma1 - 1 (stretch, >= 0) when
 * sigma1 - 1 >= 1 - sigma2, and -(1 - sigma2) (compression, < 0)
 * otherwise.  One signed number per triangle is what a diverging colour
 * can show, and the larger of the two deviations is the one that tears or
 * buckles the material.  A development keeps every length and has none:
 * triangles NULL, strain NULL, count 0.
 */
typedef struct ur_shading {
    ur_vec2 (*triangles)[3]; /* owned by the net or piece */
    double *strain;          /* owned: one per triangle, signed as above */
    /*
     * Owned: one per triangle, the flat unit direction of that dominant
     * strain (the left singular vector of sigma1 for stretch, of sigma2 for
     * compression): the direction in which the flat triangle is longer (or
     * shorter) than the 3D one.  Kerfing cuts go across it.
     */
    ur_vec2 *direction;
    size_t count;
} ur_shading;

/*
 * One side of a seam: a run of the outline that was cut from a neighbouring
 * part of the surface (another piece, or another run of the same piece, as
 * the two edges of a closed cylinder's cut ruling).  The two sides of a seam
 * carry the same seam number, unique within one ur_net_list, and each
 * follows its own outline counter-clockwise, so in 3D they run in opposite
 * directions: the first point of one side is the last point of the other.
 * A boundary of the surface itself is no seam.
 */
typedef struct ur_seam_side {
    size_t first; /* outline index of the run's first point */
    size_t count; /* points in the run, >= 2; indices wrap around the outline */
    int seam;     /* seam number, >= 1 */
} ur_seam_side;

/* One flat piece.  All arrays are owned by the net. */
typedef struct ur_net {
    char name[32];
    ur_vec2 *outline; /* closed ring, counter-clockwise, first point not repeated */
    size_t outline_count;
    ur_segment *rulings; /* rulings to draw (fold or score lines) */
    /*
     * Parallel to rulings for a development: the surface parameter u of
     * each drawn ruling, so that allowances can ask the surface about it
     * (bend radius, for bending kerfs).  NULL for a flattened mesh.
     */
    double *ruling_parameters;
    size_t ruling_count;
    ur_segment seams[2]; /* outline edges cut from a neighbouring piece */
    size_t seam_count;
    ur_seam_side *seam_sides; /* every seam side of the outline; owned */
    size_t seam_side_count;
    /*
     * A flattened or unfolded mesh piece: the 3D point of each outline
     * point (owned), from which ur_net_list_find_seams pairs the seams.
     * NULL for a development, whose seams are its cut rulings.
     */
    ur_vec3 *outline_3d;
    double u_start, u_end; /* the part of the surface this piece covers */
    double area_3d;        /* 3D area of that part (quadrature) */
    double flat_area;      /* area enclosed by the outline */
    double edge_error;     /* largest relative error of a flat boundary length */
    /*
     * Strain of an approximate flattening (flatten.h): the largest sigma1 - 1
     * and 1 - sigma2 over the piece's triangles.  Zero for an exact
     * development, which keeps every length.
     */
    double max_stretch, max_compression;
    /*
     * Fold lines of an unfolded polyhedron (flatten.h): always drawn, as
     * mountain (SCORE) or valley (SCORE_VALLEY) folds.  NULL, 0 otherwise.
     */
    ur_segment *folds;
    bool *fold_valley;
    size_t fold_count;
    ur_shading shading; /* per-triangle strain of a flattening; empty for a development */
    /*
     * A mesh piece's triangles in 3D (owned), corners counter-clockwise
     * seen from the outside as in the mesh, for the assembly guide
     * (ur_assembly_write).  NULL, 0 for a development.
     */
    ur_vec3 (*faces_3d)[3];
    size_t face_count;
    /*
     * An unfolded piece's faces as the mesh's polygons: triangles that lie
     * flat together (ur_unfold_options.flat_angle) count as one.  0 for any
     * other net.
     */
    size_t polygon_count;
} ur_net;

typedef struct ur_net_list {
    ur_net *nets;
    size_t count;
} ur_net_list;

/* Frees one net's arrays (not the net itself). */
UR_API void ur_net_free(ur_net *net);

UR_API void ur_net_list_free(ur_net_list *nets);

/*
 * Copies from's triangles, strains and directions into to (zeroed before);
 * UR_ERROR_INTERNAL when from is inconsistent, UR_ERROR_MEMORY.  to owns
 * what was copied even on failure (free it as a piece's or net's).
 */
UR_API ur_status ur_shading_copy(const ur_shading *from, ur_shading *to, ur_error *error);

/*
 * The angle a bending groove or hinge row turns the sheet by when the
 * material does not say (degrees): a material's default (io.h) that the
 * bending kerfs (allow.h) fall back on.
 */
#define UR_DEFAULT_FACET_ANGLE 5.0

/* ---- Pieces -------------------------------------------------------------- */

/*
 * The circle a path exactly is, or is an arc of, when it is known to be
 * one (a circle or arc read from a file, and what kerf compensation and
 * bridges make of it): the cut follows the circle, not the chords between
 * the points.  The points all lie on the circle and are its flattening,
 * for everything that works on polylines (nesting, areas, cut order, the
 * preview).  A closed path is the whole circle; an open one the arc from
 * its first point to its last, turning by sweep radians about the centre
 * (> 0 counter-clockwise).  radius 0 (a zeroed value) is no circle: the
 * path is its polyline.  Only exact knowledge sets it, never a fit.
 */
typedef struct ur_path_circle {
    ur_vec2 centre;
    double radius; /* mm; 0: the path is no circle */
    double sweep;  /* open paths: radians from the first point to the last */
} ur_path_circle;

typedef struct ur_path {
    ur_op op;
    bool closed;
    ur_vec2 *points; /* owned by the path */
    size_t count;
    ur_path_circle circle; /* radius 0 unless the path is exactly a circle or arc */
} ur_path;

/* What the report says of a piece: copied from its net. */
typedef struct ur_piece_measures {
    double area_3d;                      /* of the part of the surface the piece covers */
    double flat_area;                    /* enclosed by the outline */
    double edge_error;                   /* largest relative error of a flat edge length */
    double max_stretch, max_compression; /* of an approximate flattening; 0 when exact */
    size_t triangle_count;               /* of a mesh piece; 0 for a development or a part */
    size_t polygon_count;                /* of an unfolded piece (ur_net.polygon_count); else 0 */
} ur_piece_measures;

/* ---- What was added and why ----------------------------------------- */

typedef enum ur_allowance_kind {
    UR_ALLOWANCE_JOINT,             /* a glue tab or lap on a seam */
    UR_ALLOWANCE_LABEL,             /* an engraved seam label or piece name */
    UR_ALLOWANCE_KERFING,           /* slits where the net under-covers */
    UR_ALLOWANCE_OVERLAP,           /* slits or darts with overlap zones where it over-covers */
    UR_ALLOWANCE_BENDING,           /* bending kerfs where the bend is too tight */
    UR_ALLOWANCE_KERF_COMPENSATION, /* outline offset by half the kerf */
    UR_ALLOWANCE_BRIDGES,           /* uncut gaps holding the part in the sheet */
    UR_ALLOWANCE_KIND_COUNT
} ur_allowance_kind;

/* "joint", "label", "kerfing", "overlap", "bending", "kerf-compensation", "bridges". */
UR_API const char *ur_allowance_kind_name(ur_allowance_kind kind);

/*
 * One allowance added to a piece (or one that could not be added: warning),
 * for the report.  value and limit are what triggered it (a strain as a
 * fraction, a radius or a length in mm) and the profile's limit it
 * exceeded; NAN when there is none (a joint on a seam needs no trigger).
 */
typedef struct ur_allowance_record {
    ur_allowance_kind kind;
    size_t count;     /* cuts, tabs, bridges ... added */
    double value;     /* what triggered it, NAN when nothing did */
    double limit;     /* the limit it exceeded, NAN when none */
    ur_vec2 where;    /* piece coordinates: the middle of the region */
    bool warning;     /* not done, or only partly: the reason says what is missing */
    char reason[256]; /* one sentence for the report */
    /*
     * A label's strokes are paths[first_path .. first_path + path_count - 1]
     * of the piece, centred on where, their baseline along direction (unit);
     * path_count is 0 for other records.
     */
    size_t first_path, path_count;
    ur_vec2 direction;
    /*
     * Bending kerfs: the largest angle one groove or hinge row turns the
     * sheet by (degrees, between the tangent planes of consecutive rows)
     * and how many rows (grooves) the region has; 0 for other records.
     */
    double facet_angle;
    size_t rows;
} ur_allowance_record;

typedef struct ur_piece {
    char name[32];
    ur_path *paths; /* owned; paths[0] is the outer outline */
    size_t path_count;
    ur_box box; /* of every path, in piece coordinates */
    ur_piece_measures measures;
    /*
     * Per-triangle strain copied from the net, in piece coordinates (those
     * of paths[0]); empty (NULL, 0) for a development.  Owned: ur_piece_free
     * frees it.  Only the strain picture draws it; nothing is cut from it.
     */
    ur_shading shading;
    ur_allowance_record *records; /* owned; what was added and why */
    size_t record_count;
    bool bridged; /* bridges or merged lines opened the outline: paths[0] is no longer a ring */
    double outline_area; /* what the outline enclosed before it was opened; 0 until then */
    /*
     * The direction of the piece's rulings (its bending axes), radians in
     * piece coordinates, taken modulo a half turn, when has_rulings (not a
     * mesh's piece or a part from a file).  Nesting turns it to the
     * material's grain.
     */
    bool has_rulings;
    double ruling_angle;
    /* The piece's own allowed turns for nesting (as ur_nest_options.rotations); 0: the nesting's */
    size_t rotations;
    /*
     * The kerf (mm) its cut paths were moved for, half of it to each side:
     * what ur_piece_compensate_kerf added, or what the file a part was read
     * from says (UR_KERF_NOTE); 0 when they are as drawn.
     */
    double kerf_compensated;
} ur_piece;

/*
 * How unroll's cut files say that their cut paths were compensated: this,
 * the kerf in mm and " mm" (SVG: the Dublin Core description in the
 * metadata; DXF: a 999 comment; PDF: the keywords).  ur_parts_import
 * reads it back, so that nesting the file again does not compensate it
 * twice.
 */
#define UR_KERF_NOTE "cut paths compensated for a kerf of "

/* Copies points into a new path of the piece (no circle) and grows its box. */
UR_API ur_status ur_piece_add_path(ur_piece *piece, ur_op op, const ur_vec2 *points, size_t count,
                                   bool closed, ur_error *error);

UR_API void ur_piece_free(ur_piece *piece);

/* A deep copy of a piece (a second part of the same shape); free it with ur_piece_free. */
UR_API ur_status ur_piece_copy(const ur_piece *from, ur_piece *to, ur_error *error);

/* The piece's box, measured again on every path (after paths moved or went). */
UR_API void ur_piece_recompute_box(ur_piece *piece);

/* Appends a copy of record to the piece's records. */
UR_API ur_status ur_piece_record(ur_piece *piece, const ur_allowance_record *record,
                                 ur_error *error);

UR_API void ur_paths_free(ur_path *paths, size_t count);

/* ---- Layouts ------------------------------------------------------------- */

typedef struct ur_placement {
    size_t piece_index;
    ur_transform2 transform;
} ur_placement;

typedef struct ur_sheet {
    double width, height;
    ur_placement *placements; /* owned */
    size_t placement_count;
    /* Set by the caller when a job mixes materials: this sheet's; "" otherwise. */
    char material[64];
    bool remnant; /* one of ur_nest_options.remnants, not a stock sheet */
    /*
     * True-shape nesting on sheets, the last stock sheet: the offcut its
     * parts leave at its right end, as tall as the sheet, from their right
     * edges and the spacing to the sheet's edge (mm); 0 on other sheets.
     */
    double offcut_width;
} ur_sheet;

/* A sheet left over from an earlier job (an offcut), given by its size in mm. */
typedef struct ur_remnant {
    double width, height;
} ur_remnant;

typedef struct ur_layout {
    ur_sheet *sheets; /* owned */
    size_t sheet_count;
    size_t *not_placed; /* owned: pieces left out when the sheets ran out (max_sheets) */
    size_t not_placed_count;
} ur_layout;

/* Share of the sheet's area covered by the outlines placed on it, 0..1. */
UR_API double ur_sheet_utilisation(const ur_sheet *sheet, const ur_piece *pieces);

UR_API void ur_layout_free(ur_layout *layout);

#ifdef __cplusplus
}
#endif

#endif
