/*
 * unroll/io.h: reading what the user gives: curves as CSV, the machine and
 * material profiles (XML validated against RelaxNG schemas), meshes (OBJ,
 * STL, PLY, glTF) and flat parts drawn elsewhere (SVG, DXF).
 *
 * Every error message names the file and, where there is one, the line:
 * "FILE:LINE: message".
 */
#ifndef UNROLL_IO_H
#define UNROLL_IO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "unroll/base.h"
#include "unroll/core.h"
#include "unroll/geom.h"
#include "unroll/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Curves ------------------------------------------------------------ */

/*
 * Reads "x,y,z" per line; '#' starts a comment, blank lines are skipped.  A
 * last point equal to the first marks a closed curve: it is dropped and
 * *closed set.  Refuses fewer than 4 points, non-numeric, NaN or infinite
 * coordinates and a point equal to the one before it.  The caller frees
 * *points with free().
 */
UR_API ur_status ur_curve_csv_read(const char *path, ur_vec3 **points, size_t *count, bool *closed,
                                   ur_error *error);

/* The same for a path of at least min_count points (a seam of two). */
UR_API ur_status ur_points_csv_read(const char *path, size_t min_count, ur_vec3 **points,
                                    size_t *count, bool *closed, ur_error *error);

/*
 * The same for size bytes of CSV in memory (no NUL needed), name standing
 * for the file in messages.
 */
UR_API ur_status ur_curve_csv_read_buffer(const char *name, const void *data, size_t size,
                                   ur_vec3 **points, size_t *count, bool *closed, ur_error *error);
UR_API ur_status ur_points_csv_read_buffer(const char *name, const void *data, size_t size,
                                    size_t min_count, ur_vec3 **points, size_t *count, bool *closed,
                                    ur_error *error);

/* Writes points as CSV, atomically (temporary file, then rename). */
UR_API ur_status ur_curve_csv_write(const char *path, const ur_vec3 *points, size_t count,
                                    ur_context *context, ur_error *error);

/* The same bytes to a stream the caller owns (flushed, not closed). */
UR_API ur_status ur_curve_csv_write_stream(FILE *stream, const ur_vec3 *points, size_t count,
                                    ur_error *error);

/* ---- Profiles ---------------------------------------------------------- */

typedef struct ur_op_style {
    char layer[64];    /* layer name shown in the cutter software */
    char colour[8];    /* "#RRGGBB" */
    double line_width; /* stroke width in mm */
    char dash[32];     /* dash pattern, mm: "3 1.5" (dash, gap, ...); empty for solid */
} ur_op_style;

typedef enum ur_machine_kind { UR_MACHINE_LASER, UR_MACHINE_ROUTER } ur_machine_kind;

typedef struct ur_machine {
    char name[64]; /* the file name without .xml */
    char description[256];
    char source[1024]; /* the file it was read from */
    ur_machine_kind kind;
    double bed_width, bed_height; /* mm */
    double kerf;                  /* mm: beam width or bit diameter */
    double margin;                /* mm kept free along sheet edges */
    double spacing;               /* mm kept free between parts */
    double cut_speed;             /* mm/s */
    double travel_speed;          /* mm/s */
    ur_op_style styles[UR_OP_COUNT];
    /*
     * Holding bridges: uncut gaps of this width (mm) along the outline.
     * From <bridge width=".." default="none|auto"/>; when absent 0.5 mm for
     * a laser and 3 mm for a router, off for a laser and on for a router.
     */
    double bridge_width;
    bool bridges_by_default;
} ur_machine;

typedef struct ur_sheet_size {
    double width, height; /* mm */
} ur_sheet_size;

/* How two pieces meet along a seam. */
typedef enum ur_joint_kind {
    UR_JOINT_TAB, /* a tapered glue tab on one side (paper, cardboard, polypropylene) */
    UR_JOINT_LAP, /* one piece extends under the other (plywood, MDF) */
} ur_joint_kind;

/* How a region that must shrink is relieved. */
typedef enum ur_overlap_style { UR_OVERLAP_SLIT, UR_OVERLAP_DART } ur_overlap_style;

/* Which layer of the material the 3D surface describes (--surface). */
typedef enum ur_surface_layer {
    UR_LAYER_NEUTRAL, /* develop the surface as given */
    UR_LAYER_OUTER,   /* the surface is the outer (convex) face */
    UR_LAYER_INNER,   /* the inner (concave) face */
    UR_LAYER_MID,     /* the middle of the thickness */
} ur_surface_layer;

/* "neutral", "outer", "inner", "mid"; ur_surface_layer_from_name returns -1 when unknown. */
UR_API const char *ur_surface_layer_name(ur_surface_layer layer);
UR_API int ur_surface_layer_from_name(const char *name);

/*
 * How far the neutral layer lies from the given layer, in mm toward the
 * inside of the bend (the centre of curvature; negative: away from it).
 * The neutral layer lies k_factor * thickness from the inner face, so outer
 * (1 - K) t, inner -K t, mid (1/2 - K) t, neutral 0.
 */
UR_API double ur_surface_layer_offset(ur_surface_layer layer, double thickness, double k_factor);

typedef enum ur_grain_rule {
    UR_GRAIN_NONE,   /* no grain: any rotation */
    UR_GRAIN_ALONG,  /* rulings (bending axes) along the grain */
    UR_GRAIN_ACROSS, /* rulings across the grain */
} ur_grain_rule;

#define UR_MAX_STOCK_SIZES 8

typedef struct ur_material {
    char name[64];
    char description[256];
    char source[1024];
    double thickness;                        /* mm */
    ur_sheet_size stock[UR_MAX_STOCK_SIZES]; /* first is the default */
    int stock_count;
    double kerf_laser;               /* mm, overrides the machine's; 0 when not given */
    double kerf_router;              /* likewise */
    double bend_radius_with_grain;   /* mm: smallest radius without cracking */
    double bend_radius_across_grain; /* mm */
    double max_stretch;              /* allowed strain, e.g. 0.01 for 1 % */
    double max_compression;          /* allowed strain */
    double k_factor;                 /* neutral layer position, 0..1 of thickness */
    double tab_depth;                /* glue tab depth, mm */
    double tab_angle;                /* taper of the tab sides, degrees */
    ur_grain_rule grain;
    double grain_tolerance;  /* degrees */
    double hinge_cut_length; /* living hinge: slit length, mm */
    double hinge_connection; /* uncut bridge between slits, mm */
    double hinge_distance;   /* distance between slit rows, mm */
    /*
     * What the allowances need.  Each element is optional; the defaults
     * (unroll-profile(5)) are filled in when it is absent.
     */
    ur_joint_kind joint;    /* <joint type=".."/>: default tab */
    double lap_width;       /* <joint lap-width=".."/>: default the tab depth */
    double label_height;    /* <label height=".."/>: engraved text, default 4 mm */
    double kerfing_opening; /* <kerfing opening=".."/>: widest a slit opens, default 0.5 mm */
    double kerfing_margin;  /* <kerfing margin=".."/>: slits stop this far from the outline, default
                               3 mm */
    ur_overlap_style overlap; /* <overlap style=".."/>: default slit */
    double groove_skin; /* <groove skin=".."/>: uncut skin under a routed groove, default t / 3 */
    double
        facet_angle; /* <bending facet-angle=".."/>: degrees per groove or hinge row, default 5 */
    double min_web;  /* <bending min-web=".."/>: thinnest web between kerfs, mm; 0 when not
                        given: the command takes three laser kerfs */
    ur_surface_layer surface_layer; /* <surface layer=".."/>: default neutral */
} ur_material;

/* "machines" or "materials": the sub-folder of a profile root. */
typedef enum ur_profile_kind { UR_PROFILE_MACHINE, UR_PROFILE_MATERIAL } ur_profile_kind;

/*
 * Profile roots: the directories profiles are searched in, in order, as a
 * NULL-terminated list of paths (roots), e.g. {"/usr/share/unroll/profiles",
 * NULL}; a root that does not exist is empty.  A profile NAME is the file
 * ROOT/machines/NAME.xml or ROOT/materials/NAME.xml; the schemas are
 * ROOT/schema/machine.rng, material.rng and job.rng, taken from the first
 * root that has them.  The library searches nothing else: the command's
 * roots (next to its executable, $UNROLL_PROFILES, ./profiles) are its own
 * (unroll(1), PROFILES); `pkg-config --variable=profiledir unroll` names
 * the installed ones.
 */
UR_API ur_status ur_profile_find(const char *const *roots, ur_profile_kind kind, const char *name,
                                 char *path, size_t path_size, ur_error *error);

/* Reads and validates one profile file (its schema from roots). */
UR_API ur_status ur_machine_read(const char *const *roots, const char *path, ur_machine *machine,
                                 ur_error *error);
UR_API ur_status ur_material_read(const char *const *roots, const char *path, ur_material *material,
                                  ur_error *error);

/*
 * The same for a profile's size bytes in memory (no NUL needed).  name
 * stands for the file: messages name it, and the profile is named by it as
 * by a path ("dir/paper.xml" gives "paper"); source is name.  The schema
 * comes from roots.
 */
UR_API ur_status ur_machine_read_buffer(const char *const *roots, const char *name, const void *data,
                                        size_t size, ur_machine *machine, ur_error *error);
UR_API ur_status ur_material_read_buffer(const char *const *roots, const char *name,
                                         const void *data, size_t size, ur_material *material,
                                         ur_error *error);

/* Finds NAME in the roots, then reads it. */
UR_API ur_status ur_machine_load(const char *const *roots, const char *name, ur_machine *machine,
                                 ur_error *error);
UR_API ur_status ur_material_load(const char *const *roots, const char *name, ur_material *material,
                                  ur_error *error);

/* One entry of a listing of every profile in the roots. */
typedef struct ur_profile_entry {
    ur_profile_kind kind;
    char name[64];
    char description[256];
    char source[1024];
} ur_profile_entry;

/*
 * Lists every profile found (a name found in an earlier root hides the same
 * name in later ones), sorted by kind then name.  The caller frees *entries.
 */
UR_API ur_status ur_profile_list(const char *const *roots, ur_profile_entry **entries,
                                 size_t *count, ur_error *error);

/* The kerf a machine cuts in a material: the material's figure if it has one. */
UR_API double ur_effective_kerf(const ur_machine *machine, const ur_material *material);

/* ---- Meshes ------------------------------------------------------------ */

/*
 * The length unit of a mesh file's coordinates; unroll works in
 * millimetres.  UR_UNIT_FILE is the one the file declares in its content
 * (Collada's <unit>, 3MF's <model unit>), millimetres for a format that
 * declares none (OBJ, STL, PLY; glTF too, although its specification says
 * metres).
 */
typedef enum ur_length_unit {
    UR_UNIT_MM,
    UR_UNIT_CM,
    UR_UNIT_M,
    UR_UNIT_IN,
    UR_UNIT_FILE
} ur_length_unit;

/*
 * "mm", "cm", "m", "in" ("file" for UR_UNIT_FILE); ur_length_unit_from_name
 * returns -1 when unknown, and never UR_UNIT_FILE.
 */
UR_API const char *ur_length_unit_name(ur_length_unit unit);
UR_API int ur_length_unit_from_name(const char *name);

/* Millimetres in one unit: 1, 10, 1000, 25.4; NaN for UR_UNIT_FILE. */
UR_API double ur_length_unit_mm(ur_length_unit unit);

typedef struct ur_mesh_import_options {
    ur_length_unit unit; /* of the file's coordinates; default UR_UNIT_FILE */
    double scale;        /* multiplies after the unit: positive and finite; default 1 */
} ur_mesh_import_options;

UR_API void ur_mesh_import_options_default(ur_mesh_import_options *options);

/* More vertices than this (counting every node's copy) are refused: memory. */
#define UR_MESH_IMPORT_MAX_VERTICES 50000000u

/* Coordinates beyond 1000 km, once in millimetres, are refused. */
#define UR_MESH_IMPORT_MAX_COORDINATE UR_LENGTH_MAX

/*
 * About how many bytes reading the mesh file at path takes at its peak
 * (assimp's scene, its post-processing and unroll's copy): forty times the
 * file's size, measured on binary STL, the densest format (a 3MF: forty
 * times its size unpacked, which assimp holds whole); 0 when the file
 * cannot be read.  A caller can refuse a file that will not fit before
 * assimp starts: assimp does not survive running out of memory while it
 * post-processes (it crashes releasing the scene).
 */
UR_API size_t ur_mesh_import_memory_estimate(const char *path);

/*
 * Reads OBJ, STL (ASCII and binary), PLY, glTF 2 (.gltf, .glb), Collada
 * (.dae) and 3MF (.3mf), known by the file's extension, into one mesh in
 * millimetres: every node's meshes
 * with the node's transform (and its parents') applied, a mesh used by
 * several nodes copied for each.  Triangles keep the file's winding, also
 * under a mirroring transform.  Each node that carries triangles (an OBJ
 * group or object, an STL solid, a glTF node) becomes a group, so that
 * pieces never cross groups; groups of the same name are one group, in the
 * order they first appear.  Polygons are triangulated and identical
 * vertices within one mesh joined; nothing is welded across meshes
 * (ur_mesh_clean does that); points and lines are left out.  options may be
 * NULL (defaults).  The numbers are read in options->unit: by default
 * (UR_UNIT_FILE) the unit a Collada or 3MF file declares, millimetres for
 * the others; glTF files are in metres by their specification, but read
 * in millimetres unless the caller says otherwise.  Only the file and a
 * glTF's buffers beside it are read, never an OBJ's material library.
 *
 * When group_names is not NULL, *group_names receives mesh->group_count
 * names (NUL-terminated, cut to 63 bytes; unnamed groups take the file's
 * name), which the caller frees with free().  The caller frees the mesh with
 * ur_mesh_free (or by freeing its three arrays).  On failure both are empty.
 *
 * Refuses, with UR_ERROR_INPUT and a message naming the file: a missing,
 * empty or unreadable file, an unsupported extension, a file assimp cannot
 * read (its reason quoted), a scene with no meshes, no triangles (points and
 * lines only), NaN or infinite coordinates (naming the mesh and vertex),
 * more than UR_MESH_IMPORT_MAX_VERTICES vertices (a PLY or binary STL
 * header that announces them, or more than the file can hold, is refused
 * before assimp reads on) and coordinates beyond
 * UR_MESH_IMPORT_MAX_COORDINATE mm after the unit, scale and transforms.
 * An unknown unit or a scale that is not positive and finite is refused
 * with UR_ERROR_INPUT too, the message naming the value.
 *
 * Not thread-safe: assimp keeps its last error message in a global.
 */
UR_API ur_status ur_mesh_import(const char *path, const ur_mesh_import_options *options,
                                ur_mesh *mesh, char (**group_names)[64], ur_error *error);

/*
 * The same for a file's size bytes in memory.  name stands for the file:
 * its extension says the format, messages and unnamed groups take it.  A
 * .gltf whose buffers are files of their own cannot find them from memory
 * (give .glb, or a .gltf with its buffers embedded).
 */
UR_API ur_status ur_mesh_import_buffer(const char *name, const void *data, size_t size,
                                const ur_mesh_import_options *options, ur_mesh *mesh,
                                char (**group_names)[64], ur_error *error);

/*
 * The unit the mesh file at path declares in its content, as
 * ur_mesh_import reads it by default: *mm the millimetres in one unit and
 * name what the file calls it ("inch"; "0.0254 m" for a Collada unit
 * without a name), or *mm 0 and name "" for a format that declares none
 * (OBJ, STL, PLY, glTF: the file is not opened).  UR_ERROR_INPUT naming the
 * file when the part that declares the unit cannot be read.
 */
UR_API ur_status ur_mesh_declared_unit(const char *path, double *mm, char name[32],
                                       ur_error *error);

/*
 * Which axis of a mesh file's coordinates points up, for drawings of the
 * model (the assembly guide): UR_UP_Y for glTF (.gltf, .glb: +y up by its
 * specification), for Collada (.dae: read +y up, assimp turning the file's
 * declared up axis so) and for an OBJ file Blender wrote (its first comment
 * lines start "# Blender"; its OBJ export is +y up unless told otherwise),
 * UR_UP_Z for every other file (CAD programs, STL and 3MF files, Blender's
 * STL export).  A guess from the writer, never from the shape: a file exported
 * with another axis up needs to be told.  ur_mesh_up_axis reads the name's
 * extension and size bytes of the file's start (head, which may be NULL);
 * ur_mesh_file_up_axis reads the start of the file at path (UR_UP_Z when
 * it cannot).  Never UR_UP_AUTO.
 */
typedef enum ur_up_axis {
    UR_UP_AUTO = 0, /* not decided: guess it from the file */
    UR_UP_Z,
    UR_UP_Y
} ur_up_axis;

UR_API ur_up_axis ur_mesh_up_axis(const char *name, const void *head, size_t size);
UR_API ur_up_axis ur_mesh_file_up_axis(const char *path);

/* ---- Job files ---------------------------------------------------------- */

/*
 * One option of a job, named as the job's settings are (ur_job_option_name,
 * the command line's options without their dashes): a value, a path
 * (already made relative to the working directory: the job file's
 * directory joined in front) or neither (a flag).  ur_job_file_run
 * (job.h) runs a job file read.
 */
typedef struct ur_job_file_option {
    char name[64];
    char value[2048];
    bool has_value;
    int line; /* in the job file, for messages */
} ur_job_file_option;

typedef struct ur_job_file_part {
    char surface[16];  /* cylinder, cone, ..., mesh */
    char name[64];     /* "" when not given */
    long quantity;     /* 1 when not given */
    char file[2048];   /* a mesh part's file, relative to the working directory; "" otherwise */
    char material[64]; /* the part's own material, "" for the job's */
    ur_job_file_option *options; /* owned */
    size_t option_count;
    int line;
} ur_job_file_part;

typedef struct ur_job_file {
    char name[64];
    char source[1024];              /* the job file */
    char machine[64], material[64]; /* "" when not given */
    ur_job_file_option *options;         /* owned: for every part, the sheets and the files */
    size_t option_count;
    ur_job_file_part *parts; /* owned */
    size_t part_count;
    char output_directory[2048]; /* relative to the working directory; "." when not given */
    char output_name[64];
    char formats[64]; /* "" when not given: SVG */
    char report[64];  /* a file name in the output directory; "" for none */
    int output_line;  /* of <output>, for messages */
} ur_job_file;

/*
 * Reads and validates a job file (schema/job.rng from the profile roots;
 * unroll-job(5)).
 * Paths in it (path options, a mesh part's file, the output directory) are
 * relative to the job file and come back joined to its directory.  Refuses
 * with UR_ERROR_INPUT, "FILE:LINE: message": a file that is not well formed
 * or not valid (the schema's message), two parts of one name, a path too
 * long.  Free with ur_job_file_free.
 */
UR_API ur_status ur_job_file_read(const char *const *roots, const char *path, ur_job_file *job,
                                  ur_error *error);

/*
 * The same for a job file's size bytes in memory; name stands for the file
 * (messages name it, and relative paths are joined to its directory).
 */
UR_API ur_status ur_job_file_read_buffer(const char *const *roots, const char *name,
                                         const void *data, size_t size, ur_job_file *job,
                                         ur_error *error);
UR_API void ur_job_file_free(ur_job_file *job);

/* ---- Parts from SVG and DXF -------------------------------------------- */

typedef struct ur_parts_import_options {
    /*
     * Millimetres in one unit of the file's coordinates, used only when the
     * file does not say (an SVG without a width or height in a physical
     * unit, a DXF without $INSUNITS); 0, the default, refuses such a file
     * asking for --units.  ur_parts_unit_mm turns a unit name into it.
     */
    double unit;
    /*
     * mm: farthest a flattened curve strays from the curve; default 0.01.
     * Ends this close meet: a path whose end is this close to its start is
     * closed, an arc or ellipse this close to a full turn is one.
     */
    double tolerance;
    /*
     * Refuse a file with anything that would be left out (an open shape,
     * or a score, engrave, mark or kerf line no part holds) instead of
     * leaving it out with a warning; default false.
     */
    bool strict;
} ur_parts_import_options;

UR_API void ur_parts_import_options_default(ur_parts_import_options *options);

/* Millimetres in "mm", "cm", "m", "in", "ft", "pt", "pc" or "px" (96 per inch); 0 when unknown. */
UR_API double ur_parts_unit_mm(const char *name);

/* Coordinates beyond 1 km, once in millimetres, are refused. */
#define UR_PARTS_IMPORT_MAX_COORDINATE 1e6

/* What one file held: its parts and what was done to them without asking. */
typedef struct ur_parts {
    ur_piece *pieces; /* owned; in the order their outlines appear in the file */
    size_t count;
    char (*warnings)[256]; /* owned; "FILE:LINE: ..." sentences for the user */
    size_t warning_count;
    /*
     * The kerf (mm) the file says its cut paths were compensated for
     * (UR_KERF_NOTE, as unroll writes it), also in each piece's
     * kerf_compensated; 0 when it says nothing.
     */
    double kerf_compensated;
} ur_parts;

/*
 * Reads the closed shapes of an SVG or DXF file (known by its extension,
 * .svg or .dxf in any case) as parts, in millimetres, y up.  Each closed
 * shape is a ring; a ring directly inside another is a hole of it, a ring
 * inside a hole a part of its own again, and so on (containment, computed
 * with GEOS).  A part's paths[0] is its outline, a closed counter-clockwise
 * CUT ring (first point not repeated); its holes follow as closed clockwise
 * CUT rings.  measures.flat_area is the outline's area less the holes'.
 * Every other path (an open shape; any shape on a layer or in a group
 * named score, fold, score valley, engrave, kerf or mark, as unroll writes
 * them) follows, with that operation (CUT when open on another layer),
 * in the part whose outline holds it (within the tolerance): unroll's own
 * folds and labels, another program's engraving or slits.  What no part
 * holds is left out with one warning (the file, the first one's line, how
 * many), or refused with options->strict.  A path whose end lies within the
 * tolerance of its start is closed.
 * Curves (arcs, circles, ellipses, Bezier curves, bulges) are flattened to
 * within options->tolerance, every point on the curve; a ring that is
 * exactly a circle (SVG circle, an ellipse of equal radii, a sub-path of
 * arcs of one circle going once round, under a transform that keeps
 * circles circles; DXF CIRCLE) keeps it as its path's circle, in mm.  Parts are named by their SVG
 * id, else the file's name without extension and the part's number ("plate-3"); a path whose
 * several sub-paths become parts names the second and later "ID-2", "ID-3"...  options may be NULL
 * (defaults).
 *
 * SVG (libxml2, no network, no entity expansion): path (every command),
 * rect (rx, ry round the corners), circle, ellipse, polygon, and polyline
 * or a path's sub-path that ends where it starts without closing; inside g
 * and nested svg elements, with every transform; use (href or xlink:href
 * "#id", x, y, transform, uses of uses) draws a copy of the element or
 * symbol (viewBox scaled to the use's width and height) it names, its parts
 * numbered rather than named by the copied id.  Elements hidden with
 * display:none, defs, clipPath, mask, marker, pattern, symbol, metadata and
 * elements of other namespaces (Inkscape's, Sodipodi's) are skipped where
 * they stand; text and image are skipped with a warning.  Units: a
 * root width or height in mm, cm, in, pt, pc or px (96 per inch) with the
 * viewBox sets the size of a user unit (the smaller of the two scales when
 * they differ); a width without a unit is taken in options->unit.  The y
 * axis is turned to point up (about the viewBox's bottom edge).
 *
 * DXF (ASCII): $INSUNITS (1 in, 2 ft, 4 mm, 5 cm, 6 m, 8 microinch, 9 mil,
 * 10 yd, 13 micron, 14 dm; 0 or absent: options->unit); in ENTITIES:
 * LWPOLYLINE and POLYLINE (closed by flag 1, with bulges), CIRCLE, ELLIPSE,
 * SPLINE (NURBS of any degree, rational or not, any non-decreasing knots,
 * by its control points), INSERT (the block of BLOCKS, less its base point,
 * scaled, turned, in columns and rows, blocks inside blocks; entities on
 * layer 0 take the INSERT's layer), and LINE, ARC and open polylines and
 * splines, which are chained end to end (ends within the tolerance meet)
 * into closed loops.  An ARC or ELLIPSE within the tolerance of a full
 * turn is one.  An extrusion direction of (0, 0, -1) mirrors the entity,
 * as AutoCAD draws it.  TEXT, MTEXT, DIMENSION, HATCH, POINT and other
 * entities that draw no outline are skipped with a warning; 3D polygon
 * meshes, polyface meshes and splines given by fit points only are refused,
 * naming the entity and line.
 *
 * A file that says its cut paths were compensated for a kerf (UR_KERF_NOTE:
 * an SVG's Dublin Core description in its metadata, a DXF 999 comment)
 * gives that kerf in parts->kerf_compensated and each part's.
 *
 * Refuses with UR_ERROR_INPUT, "FILE:LINE: message" where there is a line:
 * a missing, empty or unreadable file, another extension, malformed XML
 * (libxml2's message) or DXF (a group code that is not a number, a code
 * without its value, a number that is not one), no physical size and no
 * options->unit ("give --units"), with options->strict an open shape
 * (naming the SVG element and its id, or the DXF entity, that does not
 * close), a block that inserts itself (directly or through others) or is
 * not defined, a spline of degree 0 or with decreasing knots, a use that
 * points at itself (or a group holding it), at nothing or outside the
 * file, more than 200000 entities drawn by INSERTs or 100000 elements by
 * uses, NaN, infinite or
 * too-large coordinates, a ring of zero area, two rings that cross, a part
 * whose holes together fill it (naming its outline), and a file with no
 * closed shape at all.  A ring that crosses itself is
 * repaired with GEOSMakeValid when that gives one polygon (a warning says
 * so) and refused, naming the part, when it does not.  On failure *parts is
 * empty.  Free with ur_parts_free.
 */
UR_API ur_status ur_parts_import(const char *path, const ur_parts_import_options *options,
                                 ur_parts *parts, ur_error *error);

/*
 * The same for a file's size bytes in memory (no NUL needed).  name stands
 * for the file: its extension says SVG or DXF, messages name it, and parts
 * without an id are named after it.
 */
UR_API ur_status ur_parts_import_buffer(const char *name, const void *data, size_t size,
                                        const ur_parts_import_options *options, ur_parts *parts,
                                        ur_error *error);

UR_API void ur_parts_free(ur_parts *parts);

#ifdef __cplusplus
}
#endif

#endif
