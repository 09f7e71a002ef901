/*
 * io_internal.h: what the readers share: reading an XML file (profile.c,
 * job.c) and validating it against its RelaxNG schema, with libxml2's
 * messages turned into "FILE:LINE: message" errors; reading a whole file
 * into memory; small text helpers.
 */
#ifndef UNROLL_IO_INTERNAL_H
#define UNROLL_IO_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <assimp/cfileio.h>
#include <libxml/tree.h>

#include "unroll/base.h"
#include "unroll/geom.h"
#include "unroll/io.h"

/* "machine" or "material": a profile kind's schema and root element. */
const char *profile_kind_word(ur_profile_kind kind);

/* The path of schema/WORD.rng in the first root that has it; UR_ERROR_INTERNAL naming the roots. */
ur_status profile_find_schema(const char *const *roots, const char *word, char *path, size_t size,
                              ur_error *error);

/*
 * Parses path (no network) and validates it against schema/SCHEMA.rng from
 * the profile roots; the caller frees *doc with xmlFreeDoc.  UR_ERROR_INPUT
 * naming the file and line for a file that is not well formed or valid.
 */
ur_status io_xml_load(const char *const *roots, const char *schema, const char *path,
                      xmlDocPtr *doc, ur_error *error);

/*
 * The same for size bytes of text in memory, name standing for the file in
 * messages (and, for a job file, the place its relative paths start from).
 */
ur_status io_xml_load_buffer(const char *const *roots, const char *schema, const char *name,
                             const char *text, size_t size, xmlDocPtr *doc, ur_error *error);

/*
 * Reads the whole file at path into *text, NUL-terminated after its *size
 * bytes; the caller frees *text.  UR_ERROR_INPUT "path: cannot open: why"
 * or "cannot read", and for a file over max_bytes (0: no limit) "path: N
 * bytes: too large for WHAT".
 */
ur_status io_read_file(const char *path, long max_bytes, const char *what, char **text,
                       size_t *size, ur_error *error);

/* A copy of size bytes of data with a NUL after them, or NULL with error set; free() it. */
char *io_copy_text(const void *data, size_t size, ur_error *error);

/*
 * Whether the length bytes at word are a whole number (a sign allowed
 * when signed_ok) of at most max, then in *value; and whether they are a
 * real number as XML formats write one (xs:double: 1, -2.5, .5, 3e-7, INF,
 * NaN), or, where decimal_comma is set, with a comma before its fraction
 * (2,5: assimp's Collada reader reads one, as 3ds Max writes it in some
 * locales).
 */
bool io_whole_number(const char *word, size_t length, bool signed_ok, uint64_t max,
                     uint64_t *value);
bool io_real_number(const char *word, size_t length, bool decimal_comma);

/* Trims white space (the '\r' of CRLF files too) at both ends, in place. */
char *io_trim(char *text);

/*
 * The files assimp may open while it reads the mesh called name (mesh_files.c):
 * the mesh itself (size bytes of data, or when data is NULL the file at
 * name) and, for a glTF on disk, the files beside it; never a material
 * library.  Pass &files.io to aiImportFileEx; files must outlive the import.
 */
typedef struct io_mesh_files {
    struct aiFileIO io;
    const char *name;
    const void *data;
    size_t size;
} io_mesh_files;

void io_mesh_files_init(io_mesh_files *files, const char *name, const void *data, size_t size);

/*
 * The length unit a mesh file declares in its content (mesh_units.c):
 * Collada's <unit>, 3MF's <model unit>.  mm is 0 for a format that has
 * none (OBJ, STL, PLY, glTF).
 */
typedef struct io_declared_unit {
    double mm;      /* millimetres in one unit of the file's numbers; 0: none declared */
    double applied; /* what assimp multiplied the numbers by (Collada: the unit in metres) */
    char name[32];  /* as the file names it ("inch"), or "0.0254 m" */
} io_declared_unit;
/*
 * The unit of the file at path, or of size bytes of data when data is not
 * NULL (path naming it); UR_ERROR_INPUT naming the file when the part that
 * declares it cannot be read or the unit is not one.
 */
ur_status io_mesh_declared_unit(const char *path, const void *data, size_t size,
                                io_declared_unit *unit, ur_error *error);
/* Whether the file's format is one that declares a unit (Collada, 3MF), by its extension. */
bool io_mesh_may_declare_unit(const char *path);
/*
 * The 3MF archive (the file at path, or size bytes of data) made ready for
 * assimp 5.2 (mesh_3mf.c): a new archive in *archive (the caller frees it)
 * holding the content types, root relationships and model alone, the
 * objects the model's components take from other parts copied into it.
 */
ur_status io_3mf_for_assimp(const char *path, const void *data, size_t size,
                            unsigned char **archive, size_t *archive_size, ur_error *error);
/*
 * A Collada document (the file at path, or size bytes of data) checked for
 * what would make assimp 5.2 crash or run out of memory (mesh_collada.c):
 * UR_ERROR_INPUT naming the line of the first such thing.
 */
ur_status io_collada_check(const char *path, const void *data, size_t size, ur_error *error);
/*
 * A .gltf or .glb (the file at path, of size bytes, or size bytes of data) checked to be
 * glTF 2.0 that assimp 5.2's glTF 2.0 reader takes as its own
 * (mesh_gltf.c), lest assimp try its other readers on it: UR_ERROR_INPUT
 * naming the line (of a .glb, of its JSON chunk) of the first fault.
 */
ur_status io_gltf_check(const char *path, const void *data, size_t size, ur_error *error);
/* The unit a 3MF's model declares (mesh_3mf.c), as io_mesh_declared_unit gives it. */
ur_status io_3mf_unit(const char *path, const void *data, size_t size, io_declared_unit *unit,
                      ur_error *error);
/* libxml2's streaming reader on the next element (depth: 0 the root); false at the end. */
struct _xmlTextReader;
bool io_reader_next_element(struct _xmlTextReader *reader, int *depth);
/* Whether the reader's element has that local name. */
bool io_reader_is(struct _xmlTextReader *reader, const char *name);
/* The attribute's value into value (cut to size - 1 bytes; "" when absent); false when absent. */
bool io_reader_attribute(struct _xmlTextReader *reader, const char *name, char *value, size_t size);
/* The bytes a 3MF's parts take unpacked (0 for other files, or one that cannot be read). */
size_t io_mesh_unpacked_size(const char *path);
/*
 * The faces of more than three corners of a raw assimp scene, found again
 * once assimp has triangulated it (mesh_polygons.c): per mesh, per face of
 * the triangulated mesh, the number of corners of the file's face whose
 * triangles begin there (its triangles follow in order), or 0.
 */
struct aiScene;
typedef struct io_polygon_marks {
    unsigned mesh_count;
    unsigned **corners;  /* owned, per mesh: NULL for a mesh of triangles alone */
    size_t *face_counts; /* owned, per mesh: its faces once triangulated */
} io_polygon_marks;

/* Marks the polygons of a scene not yet triangulated; io_polygon_marks_free releases them. */
ur_status io_polygon_marks_read(const struct aiScene *raw, io_polygon_marks *marks,
                                ur_error *error);

/* Forgets the marks of every mesh that triangulating did not turn into as many faces as foreseen.
 */
void io_polygon_marks_match(io_polygon_marks *marks, const struct aiScene *triangulated);

/* A mesh's marks, or NULL. */
const unsigned *io_polygon_marks_of(const io_polygon_marks *marks, unsigned mesh);

void io_polygon_marks_free(io_polygon_marks *marks);

/*
 * Triangulates again each flat polygon of five corners or more (its
 * corners[k] - 2 triangles from starts[k]): the constrained Delaunay
 * triangulation of its corners in its plane, which leaves no slivers to
 * fold inside it where the polygon has corners almost in line.  Polygons
 * that are not flat, or that GEOS cannot triangulate, keep their
 * triangles.  Fails only when out of memory or without GEOS.
 */
ur_status io_triangulate_flat_polygons(const ur_vec3 *vertices, size_t (*triangles)[3],
                                       size_t triangle_count, const size_t *starts,
                                       const size_t *corners, size_t polygon_count,
                                       ur_error *error);

/* An edge of a triangle, between two positions (their numbers, the smaller first). */
typedef struct io_edge_record {
    size_t low, high, triangle;
} io_edge_record;

/*
 * Triangles with their edges by position (mesh_surface.c): vertices at
 * the same point share a position number; every triangle's three edges,
 * sorted by their ends' positions.  The surface does not own vertices or
 * triangles; it owns position and edges.
 */
typedef struct io_surface {
    const ur_vec3 *vertices;
    size_t (*triangles)[3];
    size_t *position;      /* per vertex: the number of its position */
    io_edge_record *edges; /* three per triangle, sorted */
    size_t edge_count;
} io_surface;

/* Makes the surface of the triangles; io_surface_free it also on failure. */
ur_status io_surface_make(io_surface *s, const ur_vec3 *vertices, size_t vertex_count,
                          size_t (*triangles)[3], size_t triangle_count, ur_error *error);
void io_surface_free(io_surface *s);

/* Edge ab (vertices) of triangle, by position. */
io_edge_record io_surface_edge(const io_surface *s, size_t triangle, size_t a, size_t b);

/* The order of the surface's edges: by their ends' positions, then triangle. */
int io_compare_edges(const void *a, const void *b);

/* The first of the records of edge ab (vertices, by position), or where it would be. */
size_t io_surface_first(const io_surface *s, size_t a, size_t b);

/* Whether two records are of one edge. */
bool io_edge_same(const io_edge_record *record, const io_edge_record *key);

/* How many triangles have edge ab (vertices, by position). */
size_t io_surface_count(const io_surface *s, size_t a, size_t b);

/*
 * Splits each twisted quad (the triangles quads[k] and quads[k] + 1 of the
 * triangles, as assimp made them from one face) whose sides all fold one
 * way along the diagonal that folds that way too.  Neighbours are found
 * by position.
 */
ur_status io_quads_follow_surface(const ur_vec3 *vertices, size_t vertex_count,
                                  size_t (*triangles)[3], size_t triangle_count,
                                  const size_t *quads, size_t quad_count, ur_error *error);

/*
 * Gives each face (a quad: two triangles from quads[k]; a polygon:
 * polygon_corners[k] - 2 from polygon_starts[k]) on the same corners, by
 * position, as an earlier one, with a side on an odd number of triangles
 * besides those of the faces on those corners, the earlier one's
 * triangulation (mesh_repeats.c): a face given twice, whose copy the
 * mesh's cleaning then drops.  Fails only when out of memory.
 */
ur_status io_repeated_faces_alike(const ur_vec3 *vertices, size_t vertex_count,
                                  size_t (*triangles)[3], size_t triangle_count,
                                  const size_t *quads, size_t quad_count,
                                  const size_t *polygon_starts, const size_t *polygon_corners,
                                  size_t polygon_count, ur_error *error);

/* Whether path's file name ends in "." and extension, in any case ("obj": x.OBJ). */
bool io_has_extension(const char *path, const char *extension);

/* "plate" from "dir/plate.svg": the file name without directory and extension. */
void io_file_stem(const char *path, char *stem, size_t size);

#endif
