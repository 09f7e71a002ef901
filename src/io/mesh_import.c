/*
 * mesh_import.c: meshes from modellers' files (OBJ, STL, PLY, glTF) through
 * assimp's C API, into one ur_mesh in millimetres with a group per node.
 *
 * The scene is read raw first and every coordinate checked before assimp's
 * post-processing runs: joining identical vertices sorts them, and a NaN
 * there silently merges with a real vertex.  Node transforms are composed
 * and applied in double precision here rather than by assimp, so that each
 * node stays its own group and a mirroring node can have its triangles
 * turned back to face outwards.  Nothing is welded across meshes or nodes:
 * ur_mesh_clean does that with the user's tolerance.  A twisted quad is
 * split along the diagonal that follows the surface (mesh_quads.c), and a
 * flat polygon of five corners or more triangulated again without slivers
 * (mesh_polygons.c); a face given twice is triangulated as it was the
 * first time (mesh_repeats.c), for ur_mesh_clean to drop the copy.
 */
#include "io_internal.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include "../base/c_locale.h"

/* Assimp builds its node tree recursively: deeper than this is not a model. */
#define IMPORT_MAX_DEPTH 1000

/* Space for a group name and its terminating NUL, as ur_mesh_import returns it. */
#define GROUP_NAME_SIZE 64

/* ---- Units ------------------------------------------------------------- */

/* UR_UNIT_FILE has no size of its own, and is never taken by name. */
static const struct {
    const char *name;
    double mm;
} unit_table[] = {
    [UR_UNIT_MM] = {"mm", 1.0},  [UR_UNIT_CM] = {"cm", 10.0},    [UR_UNIT_M] = {"m", 1000.0},
    [UR_UNIT_IN] = {"in", 25.4}, [UR_UNIT_FILE] = {"file", NAN},
};

#define UNIT_COUNT (sizeof unit_table / sizeof unit_table[0])

static bool unit_valid(ur_length_unit unit)
{
    return (unsigned)unit < UNIT_COUNT;
}

const char *ur_length_unit_name(ur_length_unit unit)
{
    return unit_valid(unit) ? unit_table[unit].name : "?";
}

int ur_length_unit_from_name(const char *name)
{
    for (size_t i = 0; name && i < UNIT_COUNT; i++)
        if (i != UR_UNIT_FILE && strcmp(name, unit_table[i].name) == 0)
            return (int)i;
    return -1;
}

double ur_length_unit_mm(ur_length_unit unit)
{
    return unit_valid(unit) ? unit_table[unit].mm : NAN;
}

void ur_mesh_import_options_default(ur_mesh_import_options *options)
{
    options->unit = UR_UNIT_FILE;
    options->scale = 1.0;
}

/* ---- Names ------------------------------------------------------------- */

/* Copies at most size - 1 bytes of text, never cutting a UTF-8 character. */
static void copy_name(char *dest, size_t size, const char *text, size_t length)
{
    if (length > size - 1) {
        length = size - 1;
        /* Back off continuation bytes (10xxxxxx) to the start of a character. */
        while (length > 0 && ((unsigned char)text[length] & 0xC0) == 0x80)
            length--;
    }
    memcpy(dest, text, length);
    dest[length] = '\0';
}

/*
 * Whether an assimp node or mesh name says something: importers fill in
 * placeholders ("<STL_BINARY>", OBJ's "defaultobject") when the file has none.
 */
static bool name_usable(const struct aiString *name)
{
    size_t length = strnlen(name->data, sizeof name->data);
    return length > 0 && name->data[0] != '<' && name->data[0] != '$' &&
           strcmp(name->data, "defaultobject") != 0;
}

/* "mesh 'front'" or, for an unnamed mesh, "mesh 3" (1-based). */
static const char *mesh_label(const struct aiMesh *mesh, unsigned index, char *buffer, size_t size)
{
    if (name_usable(&mesh->mName))
        c_snprintf(buffer, size, "mesh '%.200s'", mesh->mName.data);
    else
        c_snprintf(buffer, size, "mesh %u", index + 1);
    return buffer;
}

/* The file name without directory and extension: the name of unnamed groups. */
static void file_stem(const char *path, char *stem, size_t size)
{
    const char *slash = strrchr(path, '/');
    const char *name = slash ? slash + 1 : path;
    const char *dot = strrchr(name, '.');
    size_t length = dot && dot != name ? (size_t)(dot - name) : strlen(name);
    copy_name(stem, size, name, length);
}

/* ---- The file itself --------------------------------------------------- */

/*
 * assimp reads dozens of formats; these are the ones modellers and 3D
 * printers write whose units unroll knows: none (plain numbers in the
 * caller's unit) or one the file declares (mesh_units.c).  FBX is left out:
 * its unit is a scale factor that exporters and assimp each apply or not.
 */
static const char *const supported_extensions[] = {
    "obj", "stl", "ply", "gltf", "glb", "dae", "3mf",
};

/* Files makers often have at hand, and what to export from them instead. */
static const struct {
    const char *extension, *advice;
} other_files[] = {
    {"fbx", "FBX is not read (programs disagree on how its unit applies)"},
    {"blend", "a Blender file: export it as OBJ (File > Export > Wavefront)"},
    {"skp", "a SketchUp file: export it as Collada (.dae)"},
    {"step", "a CAD solid, not a mesh: export it as STL, 3MF or OBJ"},
    {"stp", "a CAD solid, not a mesh: export it as STL, 3MF or OBJ"},
    {"f3d", "a Fusion file: export it as STL, 3MF or OBJ"},
};

static ur_status check_extension(const char *path, ur_error *error)
{
    for (size_t i = 0; i < sizeof supported_extensions / sizeof supported_extensions[0]; i++)
        if (io_has_extension(path, supported_extensions[i]))
            return UR_OK;
    const char *advice = "";
    for (size_t i = 0; i < sizeof other_files / sizeof other_files[0]; i++)
        if (io_has_extension(path, other_files[i].extension))
            advice = other_files[i].advice;
    return ur_error_set(error, UR_ERROR_INPUT,
                        "%s: unsupported file type%s%s: unroll reads meshes from .obj, .stl, "
                        ".ply, .gltf, .glb, .dae (Collada) and .3mf files",
                        path, advice[0] ? ", " : "", advice);
}

static ur_status refuse_too_many(const char *path, unsigned long long count, ur_error *error)
{
    return ur_error_set(error, UR_ERROR_INPUT,
                        "%s: %llu vertices, more than the %u unroll takes: too large to hold in "
                        "memory; simplify the mesh first",
                        path, count, UR_MESH_IMPORT_MAX_VERTICES);
}

/* One "element NAME COUNT" line of a PLY header adds COUNT to *claimed. */
static void ply_element(const char *line, unsigned long long *vertices, unsigned long long *claimed)
{
    char name[32];
    unsigned long long count = 0;
    if (sscanf(line, "element %31s %llu", name, &count) != 2)
        return;
    if (strcmp(name, "vertex") == 0)
        *vertices = count;
    if (strcmp(name, "vertex") == 0 || strcmp(name, "face") == 0)
        *claimed = count > ULLONG_MAX - *claimed ? ULLONG_MAX : *claimed + count;
}

/* The words of a header line (at most 8; 9 says more), split at white space in place. */
static int split_words(char *line, char *words[8])
{
    static const char *const space = " \t\r\n";
    char *state = NULL;
    int count = 0;
    for (char *word = strtok_r(line, space, &state); word; word = strtok_r(NULL, space, &state)) {
        if (count == 8)
            return 9;
        words[count++] = word;
    }
    return count;
}

static bool ply_scalar_type(const char *word)
{
    static const char *const types[] = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                                        "float", "double", "int8",    "uint8",  "int16", "uint16",
                                        "int32", "uint32", "float32", "float64"};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (strcmp(word, types[i]) == 0)
            return true;
    return false;
}

static bool all_digits(const char *word)
{
    if (!*word)
        return false;
    for (; *word; word++)
        if (*word < '0' || *word > '9')
            return false;
    return true;
}

#define PLY_MAX_ELEMENTS 16
#define PLY_MAX_PROPERTIES 32

/* One element of a PLY header: how many lines, and which of its properties are lists. */
typedef struct ply_element_layout {
    unsigned long long count;
    int property_count;
    bool list[PLY_MAX_PROPERTIES];
} ply_element_layout;

/* What a PLY header says each line of an ASCII body holds. */
typedef struct ply_layout {
    bool ascii;
    bool in_element; /* a property may follow */
    bool complete;   /* every element and property fitted in here */
    int element_count;
    ply_element_layout elements[PLY_MAX_ELEMENTS];
} ply_layout;

static bool ply_add_element(ply_layout *layout, const char *count)
{
    layout->in_element = all_digits(count);
    if (layout->in_element && layout->element_count < PLY_MAX_ELEMENTS)
        layout->elements[layout->element_count++].count = strtoull(count, NULL, 10);
    else
        layout->complete = false;
    return layout->in_element;
}

static void ply_add_property(ply_layout *layout, bool list)
{
    if (!layout->complete || layout->element_count == 0)
        return;
    ply_element_layout *element = &layout->elements[layout->element_count - 1];
    if (element->property_count < PLY_MAX_PROPERTIES)
        element->list[element->property_count++] = list;
    else
        layout->complete = false;
}

/*
 * Whether line (not the first, "ply") is one of the PLY header's lines:
 * format, comment, obj_info, element NAME COUNT, property TYPE NAME,
 * property list TYPE TYPE NAME (after an element), end_header; notes in
 * layout what it says.
 */
static bool ply_header_line_valid(const char *line, ply_layout *layout)
{
    char copy[256];
    if (strlen(line) >= sizeof copy)
        return strncmp(line, "comment", 7) == 0 || strncmp(line, "obj_info", 8) == 0;
    strcpy(copy, line);
    char *words[8];
    int count = split_words(copy, words);
    if (count == 0)
        return false;
    const char *keyword = words[0];
    if (strcmp(keyword, "comment") == 0 || strcmp(keyword, "obj_info") == 0)
        return true;
    if (strcmp(keyword, "format") == 0) {
        layout->ascii = count == 3 && strcmp(words[1], "ascii") == 0;
        return count == 3 && (layout->ascii || strcmp(words[1], "binary_little_endian") == 0 ||
                              strcmp(words[1], "binary_big_endian") == 0);
    }
    if (strcmp(keyword, "element") == 0)
        return count == 3 && ply_add_element(layout, words[2]);
    if (strcmp(keyword, "property") == 0) {
        bool scalar = count == 3 && ply_scalar_type(words[1]);
        bool list = count == 5 && strcmp(words[1], "list") == 0 && ply_scalar_type(words[2]) &&
                    ply_scalar_type(words[3]);
        if (layout->in_element && (scalar || list))
            ply_add_property(layout, list);
        return layout->in_element && (scalar || list);
    }
    return count == 1 && strcmp(keyword, "end_header") == 0;
}

/* Whether each list on one line of an ASCII body has as many values as its count says. */
static bool ply_line_lists_fit(char *line, int property_count, const bool *list,
                               unsigned long long *claimed)
{
    static const char *const space = " \t\r\n";
    char *state = NULL;
    for (int p = 0; p < property_count; p++) {
        char *word = strtok_r(p == 0 ? line : NULL, space, &state);
        if (!word)
            return true; /* a short line is assimp's to refuse */
        if (!list[p])
            continue;
        *claimed = strtoull(word, NULL, 10);
        for (unsigned long long k = 0; k < *claimed; k++)
            if (!strtok_r(NULL, space, &state))
                return false;
    }
    return true;
}

/*
 * assimp reads an ASCII PLY body a line per element and takes the count of
 * a list as it stands, reading on through the file for it; past the end of
 * the file it goes on making elements, the faces with the last count it
 * read.  A 2.6 kB file whose face said 20000000 corners made it read for
 * minutes and crash, one whose vertex lines ran short gave half a million
 * triangles (both found by fuzzing).  So every element the header
 * announces must have its line, and each list its values on that line.
 * line_number is the header's last line.
 */
static ur_status check_ply_ascii_body(const char *path, FILE *file, const ply_layout *layout,
                                      int line_number, ur_error *error)
{
    char *line = NULL;
    size_t line_size = 0;
    ur_status status = UR_OK;
    for (int e = 0; status == UR_OK && e < layout->element_count; e++) {
        int properties = layout->elements[e].property_count;
        for (unsigned long long i = 0; status == UR_OK && i < layout->elements[e].count; i++) {
            if (getline(&line, &line_size, file) < 0) {
                status = ur_error_set(error, UR_ERROR_INPUT,
                                      "%s: the file ends after %llu of the %llu lines of element "
                                      "%d that its PLY header announces",
                                      path, i, layout->elements[e].count, e + 1);
                break;
            }
            line_number++;
            unsigned long long claimed = 0;
            if (!ply_line_lists_fit(line, properties, layout->elements[e].list, &claimed))
                status = ur_error_set(error, UR_ERROR_INPUT,
                                      "%s:%d: a list of %llu values on a line that holds fewer",
                                      path, line_number, claimed);
        }
    }
    free(line);
    return status;
}

/*
 * assimp believes a PLY header's counts: it reserves memory for them and
 * reads on past the end of the file, for minutes and gigabytes when a
 * header claims a billion vertices.  Every vertex and face takes at least
 * one byte after the header, so a count above that is refused beforehand.
 * assimp 5.2 also loops for ever on a header that the file ends inside, and
 * crashes (a bad free) on some headers with lines that are not PLY's (both
 * found by fuzzing): the header must end, and every line of it be one that
 * PLY defines, before assimp reads the file.
 */
static ur_status check_ply_header(const char *path, FILE *file, off_t size, ur_error *error)
{
    char *line = NULL;
    size_t line_size = 0;
    unsigned long long vertices = 0, claimed = 0;
    bool ended = false, at_end = false;
    ply_layout layout = {.complete = true};
    int bad_line = 0, lines = 0;
    for (int n = 0; n < 1000 && !ended && !bad_line; n++, lines++) {
        if (getline(&line, &line_size, file) < 0) {
            at_end = true;
            break;
        }
        ended = strncmp(line, "end_header", 10) == 0;
        bool valid =
            n == 0 ? strncmp(line, "ply", 3) == 0 && strspn(line + 3, " \t\r\n") == strlen(line + 3)
                   : ply_header_line_valid(line, &layout);
        if (!valid)
            bad_line = n + 1;
        ply_element(line, &vertices, &claimed);
    }
    long body_start = ftell(file);
    free(line);
    if (bad_line == 1)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s:1: not a PLY file: it does not start with 'ply'", path);
    if (bad_line)
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: not a line of a PLY header", path,
                            bad_line);
    if (at_end && !ferror(file))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: the PLY header has no end_header line: the file ends inside it",
                            path);
    if (!ended || body_start < 0)
        return UR_OK;
    if (vertices > UR_MESH_IMPORT_MAX_VERTICES)
        return refuse_too_many(path, vertices, error);
    unsigned long long body = (unsigned long long)(size - body_start);
    if (claimed > body)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: the PLY header announces %llu vertices and faces, more than the "
                            "%llu bytes after it can hold",
                            path, claimed, body);
    if (layout.ascii && layout.complete)
        return check_ply_ascii_body(path, file, &layout, lines, error);
    return UR_OK;
}

/*
 * A binary STL says how many triangles it holds (3 vertices each) and is
 * exactly 84 + 50 per triangle bytes long, which is how assimp tells it from
 * ASCII: refuse a huge one before assimp reads it all.
 */
static ur_status check_stl_header(const char *path, FILE *file, off_t size, ur_error *error)
{
    unsigned char header[84];
    if (size < 84 || fread(header, 1, sizeof header, file) != sizeof header)
        return UR_OK;
    unsigned long long triangles = header[80] | (unsigned long long)header[81] << 8 |
                                   (unsigned long long)header[82] << 16 |
                                   (unsigned long long)header[83] << 24;
    if ((unsigned long long)size == 84 + 50 * triangles &&
        3 * triangles > UR_MESH_IMPORT_MAX_VERTICES)
        return refuse_too_many(path, 3 * triangles, error);
    return UR_OK;
}

/*
 * Whether the content starts like a PLY file ("ply" on its first line,
 * blanks allowed), whatever the name says: assimp reads a file by its
 * content when no reader its name asks for takes it, and its PLY reader
 * loops for ever on some headers (one under a .gltf name was found by
 * fuzzing).  glTF names are checked for glTF first (mesh_gltf.c); any
 * other file that starts so gets the PLY checks before assimp sees it.
 * Leaves the stream at its start.
 */
static bool starts_as_ply(FILE *file)
{
    char start[8] = {0};
    size_t count = fread(start, 1, sizeof start - 1, file);
    rewind(file);
    size_t blanks = strspn(start, " \t\r\n");
    const char *word = start + blanks;
    return count >= blanks + 3 && strncasecmp(word, "ply", 3) == 0 &&
           (word[3] == '\0' || strchr(" \t\r\n", word[3]) != NULL);
}

/*
 * What a header says, for the formats that assimp trusts blindly (a PLY's
 * or a binary STL's counts; a Collada document's counts, lists and node
 * instances; a glTF document as glTF 2.0's reader would take it): of
 * the file at path, or of size bytes of data when data is not NULL (read
 * through a stream over them: the same code).
 */
static ur_status check_header(const char *path, const void *data, off_t size, ur_error *error)
{
    if (io_has_extension(path, "dae")) /* a whole document, read by mesh_collada.c */
        return io_collada_check(path, data, (size_t)size, error);
    if (io_has_extension(path, "gltf") || io_has_extension(path, "glb"))
        return io_gltf_check(path, data, (size_t)size, error); /* the same, mesh_gltf.c */
    /* "r": the buffer is only read */
    FILE *file = data ? fmemopen((void *)data, (size_t)size, "r") : fopen(path, "rb");
    if (!file)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path, strerror(errno));
    bool ply = io_has_extension(path, "ply") || starts_as_ply(file);
    ur_status status = UR_OK;
    if (ply)
        status = check_ply_header(path, file, size, error);
    else if (io_has_extension(path, "stl"))
        status = check_stl_header(path, file, size, error);
    if (fclose(file) != 0 && status == UR_OK)
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: cannot read: %s", path, strerror(errno));
    return status;
}

/*
 * The file at path is a regular file with bytes in it and an extension
 * unroll reads; its size in *size.  assimp's own message for a missing
 * file is vaguer than strerror's.
 */
static ur_status check_file_itself(const char *path, off_t *size, ur_error *error)
{
    struct stat info;
    if (stat(path, &info) != 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path, strerror(errno));
    if (!S_ISREG(info.st_mode))
        return ur_error_set(error, UR_ERROR_INPUT, "%s: not a regular file", path);
    if (info.st_size == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: the file is empty", path);
    *size = info.st_size;
    return check_extension(path, error);
}

/* The file itself, then what its header (or a Collada file's whole document) says. */
static ur_status check_file(const char *path, ur_error *error)
{
    off_t size = 0;
    ur_status status = check_file_itself(path, &size, error);
    return status == UR_OK ? check_header(path, NULL, size, error) : status;
}

static ur_status check_buffer(const char *name, const void *data, size_t size, ur_error *error)
{
    if (size == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: the file is empty", name);
    /* assimp takes the length as an unsigned int */
    if (size > UINT_MAX)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: %zu bytes: too large to read from memory",
                            name, size);
    ur_status status = check_extension(name, error);
    if (status != UR_OK)
        return status;
    return check_header(name, data, (off_t)size, error);
}

static ur_status check_options(const ur_mesh_import_options *options, ur_error *error)
{
    if (!unit_valid(options->unit))
        return ur_error_set(error, UR_ERROR_INPUT, "unknown length unit %d", (int)options->unit);
    if (!isfinite(options->scale) || options->scale <= 0)
        return ur_error_set(error, UR_ERROR_INPUT, "scale %g: must be a positive number",
                            options->scale);
    return UR_OK;
}

/* ---- The raw scene ----------------------------------------------------- */

static bool finite_vector(struct aiVector3D v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

/* The first face (1-based) that uses vertex, or 0 when none does. */
static unsigned face_using(const struct aiMesh *mesh, unsigned vertex)
{
    for (unsigned f = 0; f < mesh->mNumFaces; f++)
        for (unsigned k = 0; k < mesh->mFaces[f].mNumIndices; k++)
            if (mesh->mFaces[f].mIndices[k] == vertex)
                return f + 1;
    return 0;
}

static ur_status refuse_vertex(const char *path, const struct aiMesh *mesh, unsigned index,
                               unsigned vertex, ur_error *error)
{
    char label[256];
    char face[64] = "";
    unsigned f = face_using(mesh, vertex);
    if (f > 0)
        c_snprintf(face, sizeof face, " (in face %u)", f);
    struct aiVector3D v = mesh->mVertices[vertex];
    bool nan = isnan(v.x) || isnan(v.y) || isnan(v.z);
    /* A number too large for assimp's floats arrives here as infinity. */
    return ur_error_set(error, UR_ERROR_INPUT, "%s: %s, vertex %u%s: coordinates (%g, %g, %g): %s",
                        path, mesh_label(mesh, index, label, sizeof label), vertex + 1, face,
                        (double)v.x, (double)v.y, (double)v.z,
                        nan ? "not a number"
                            : "infinite, or too large for assimp's single precision (3.4e38)");
}

/* Every face's indices point at a vertex of its mesh. */
static ur_status check_faces(const char *path, const struct aiMesh *mesh, unsigned index,
                             ur_error *error)
{
    char label[256];
    for (unsigned f = 0; f < mesh->mNumFaces; f++) {
        const struct aiFace *face = &mesh->mFaces[f];
        /*
         * A PLY file that ends before its faces gives faces without corners,
         * on which assimp's triangulation aborts (found by fuzzing).
         */
        if (face->mNumIndices == 0 || !face->mIndices)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "%s: %s, face %u has no corners: is the file cut short?", path,
                                mesh_label(mesh, index, label, sizeof label), f + 1);
        for (unsigned k = 0; k < face->mNumIndices; k++)
            if (face->mIndices[k] >= mesh->mNumVertices)
                return ur_error_set(error, UR_ERROR_INPUT,
                                    "%s: %s, face %u: vertex %u does not exist (%u vertices)", path,
                                    mesh_label(mesh, index, label, sizeof label), f + 1,
                                    face->mIndices[k] + 1, mesh->mNumVertices);
    }
    return UR_OK;
}

/*
 * Before post-processing: a size it is safe to go on with, valid indices and
 * finite coordinates.
 */
static ur_status check_raw_scene(const char *path, const struct aiScene *scene, ur_error *error)
{
    if (!scene->mRootNode || scene->mNumMeshes == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: no mesh in the file (empty scene)", path);
    size_t total = 0;
    for (unsigned m = 0; m < scene->mNumMeshes; m++) {
        total += scene->mMeshes[m]->mNumVertices;
        if (total > UR_MESH_IMPORT_MAX_VERTICES)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "%s: more than %u vertices: too large to hold in memory; "
                                "simplify the mesh first",
                                path, UR_MESH_IMPORT_MAX_VERTICES);
    }
    for (unsigned m = 0; m < scene->mNumMeshes; m++) {
        const struct aiMesh *mesh = scene->mMeshes[m];
        ur_status status = check_faces(path, mesh, m, error);
        if (status != UR_OK)
            return status;
        for (unsigned v = 0; v < mesh->mNumVertices; v++)
            if (!finite_vector(mesh->mVertices[v]))
                return refuse_vertex(path, mesh, m, v, error);
    }
    return UR_OK;
}

size_t ur_mesh_import_memory_estimate(const char *path)
{
    struct stat info;
    if (stat(path, &info) != 0 || info.st_size < 0)
        return 0;
    size_t size = (size_t)info.st_size, unpacked = io_mesh_unpacked_size(path);
    if (unpacked > size)
        size = unpacked;
    return size > SIZE_MAX / 40 ? SIZE_MAX : 40 * size;
}

/*
 * Reads the file at path, or size bytes of data when data is not NULL (the
 * format told by path's extension), and post-processes it; the caller
 * releases *scene.  assimp opens files through io_mesh_files: a .gltf finds
 * the .bin files beside it, and no material library is read.
 */
static ur_status load_scene(const char *path, const void *data, size_t size,
                            const struct aiScene **scene, io_polygon_marks *polygons,
                            ur_error *error)
{
    unsigned char *copy = NULL; /* a 3MF made ready for assimp, or NULL */
    size_t copy_size = 0;
    if (io_has_extension(path, "3mf")) {
        ur_status status = io_3mf_for_assimp(path, data, size, &copy, &copy_size, error);
        if (status != UR_OK)
            return status;
    }
    io_mesh_files files;
    io_mesh_files_init(&files, path, copy ? copy : data, copy ? copy_size : size);
    /* assimp keeps its last message even after a success: read it only on failure. */
    *scene = aiImportFileEx(path, 0, &files.io);
    free(copy);
    if (!*scene)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot read as a mesh: %s", path,
                            aiGetErrorString());
    ur_status status = check_raw_scene(path, *scene, error);
    if (status == UR_OK)
        status = io_polygon_marks_read(*scene, polygons, error);
    if (status != UR_OK) {
        aiReleaseImport(*scene);
        *scene = NULL;
        return status;
    }
    /* No normals: unroll computes its own from the triangles. */
    *scene = aiApplyPostProcessing(*scene, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (!*scene) { /* assimp has released the scene */
        io_polygon_marks_free(polygons);
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot process the mesh: %s", path,
                            aiGetErrorString());
    }
    io_polygon_marks_match(polygons, *scene);
    return UR_OK;
}

/* ---- Transforms -------------------------------------------------------- */

/*
 * The top three rows of a node transform: every supported format's node
 * transforms are affine (glTF requires matrices that decompose into
 * translation, rotation and scale).
 */
typedef struct affine {
    double m[3][4];
} affine;

static affine affine_identity(void)
{
    affine a = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
    return a;
}

static affine affine_from_ai(const struct aiMatrix4x4 *t)
{
    affine a = {
        {{t->a1, t->a2, t->a3, t->a4}, {t->b1, t->b2, t->b3, t->b4}, {t->c1, t->c2, t->c3, t->c4}}};
    return a;
}

/* parent * child: the child's coordinates into the parent's frame. */
static affine affine_compose(const affine *parent, const affine *child)
{
    affine r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            double sum = j == 3 ? parent->m[i][3] : 0.0;
            for (int k = 0; k < 3; k++)
                sum += parent->m[i][k] * child->m[k][j];
            r.m[i][j] = sum;
        }
    return r;
}

static ur_vec3 affine_apply(const affine *a, struct aiVector3D v)
{
    double p[3];
    for (int i = 0; i < 3; i++)
        p[i] = a->m[i][0] * v.x + a->m[i][1] * v.y + a->m[i][2] * v.z + a->m[i][3];
    return ur_vec3_make(p[0], p[1], p[2]);
}

/* < 0 for a mirroring transform, which turns triangles over. */
static double affine_det(const affine *a)
{
    ur_vec3 x = ur_vec3_make(a->m[0][0], a->m[1][0], a->m[2][0]);
    ur_vec3 y = ur_vec3_make(a->m[0][1], a->m[1][1], a->m[2][1]);
    ur_vec3 z = ur_vec3_make(a->m[0][2], a->m[1][2], a->m[2][2]);
    return ur_vec3_det(x, y, z);
}

/* ---- Walking the nodes ------------------------------------------------- */

typedef struct import_state {
    const char *path;
    const struct aiScene *scene;
    double factor; /* millimetres per file unit, times the scale */
    /* Counted by count_node, then used as cursors by fill_node. */
    size_t vertex_count, triangle_count, group_count;
    size_t stray_count;             /* points and lines, which are not surface */
    ur_vec3 *vertices;              /* owned until handed to the mesh */
    size_t (*triangles)[3];         /* likewise */
    size_t *groups;                 /* likewise */
    char (*names)[GROUP_NAME_SIZE]; /* likewise */
    bool *named;                    /* owned: whether the file named the group */
    io_polygon_marks polygons;      /* owned: the file's faces of more than three corners */
    size_t *quad_starts;            /* owned: the first triangle of each quad's two */
    size_t quad_count;
    size_t *polygon_starts;  /* owned: the first triangle of each face of five corners or more */
    size_t *polygon_corners; /* owned: its corners */
    size_t polygon_count;
} import_state;

static void state_free(import_state *state)
{
    free(state->vertices);
    free(state->triangles);
    free(state->groups);
    free(state->names);
    free(state->named);
    free(state->quad_starts);
    free(state->polygon_starts);
    free(state->polygon_corners);
    io_polygon_marks_free(&state->polygons);
    state->quad_starts = state->polygon_starts = state->polygon_corners = NULL;
    state->vertices = NULL;
    state->triangles = NULL;
    state->groups = NULL;
    state->names = NULL;
    state->named = NULL;
}

static size_t mesh_triangles(const struct aiMesh *mesh, size_t *strays)
{
    size_t count = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; f++) {
        if (mesh->mFaces[f].mNumIndices == 3)
            count++;
        else if (strays)
            (*strays)++;
    }
    return count;
}

/* The node's i-th mesh and its index in the scene. */
static ur_status node_mesh(const import_state *state, const struct aiNode *node, unsigned i,
                           const struct aiMesh **mesh, unsigned *index, ur_error *error)
{
    *index = node->mMeshes[i];
    if (*index >= state->scene->mNumMeshes)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: node '%.200s' uses mesh %u, which does not exist", state->path,
                            node->mName.data, *index + 1);
    *mesh = state->scene->mMeshes[*index];
    return UR_OK;
}

/* First pass: how many vertices, triangles and groups, so as to allocate once. */
static ur_status count_node(import_state *state, const struct aiNode *node, int depth,
                            ur_error *error)
{
    if (depth > IMPORT_MAX_DEPTH)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: nodes nested more than %d deep",
                            state->path, IMPORT_MAX_DEPTH);
    bool has_triangles = false;
    for (unsigned i = 0; i < node->mNumMeshes; i++) {
        const struct aiMesh *mesh = NULL;
        unsigned index = 0;
        ur_status status = node_mesh(state, node, i, &mesh, &index, error);
        if (status != UR_OK)
            return status;
        size_t triangles = mesh_triangles(mesh, &state->stray_count);
        if (triangles == 0)
            continue;
        has_triangles = true;
        state->triangle_count += triangles;
        state->vertex_count += mesh->mNumVertices;
        /* A mesh used by many nodes is copied for each: count the copies. */
        if (state->vertex_count > UR_MESH_IMPORT_MAX_VERTICES)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "%s: more than %u vertices once every node has its copy: too "
                                "large to hold in memory; simplify the mesh first",
                                state->path, UR_MESH_IMPORT_MAX_VERTICES);
    }
    if (has_triangles)
        state->group_count++;
    for (unsigned c = 0; c < node->mNumChildren; c++) {
        ur_status status = count_node(state, node->mChildren[c], depth + 1, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status allocate(import_state *state, ur_error *error)
{
    state->vertices = ur_alloc_array(state->vertex_count, sizeof *state->vertices, error);
    state->triangles = ur_alloc_array(state->triangle_count, sizeof *state->triangles, error);
    state->groups = ur_alloc_array(state->triangle_count, sizeof *state->groups, error);
    state->names = ur_alloc_array(state->group_count, sizeof *state->names, error);
    state->named = ur_alloc_array(state->group_count, sizeof *state->named, error);
    state->quad_starts = ur_alloc_array(state->triangle_count, sizeof *state->quad_starts, error);
    state->polygon_starts =
        ur_alloc_array(state->triangle_count, sizeof *state->polygon_starts, error);
    state->polygon_corners =
        ur_alloc_array(state->triangle_count, sizeof *state->polygon_corners, error);
    if (!state->vertices || !state->triangles || !state->groups || !state->names || !state->named ||
        !state->quad_starts || !state->polygon_starts || !state->polygon_corners)
        return UR_ERROR_MEMORY;
    /* The counts come back as fill_node moves its cursors over the arrays. */
    state->vertex_count = state->triangle_count = state->group_count = 0;
    return UR_OK;
}

/* Names a new group after its node, or else after its first mesh. */
static void name_group(import_state *state, const struct aiNode *node,
                       const struct aiMesh *first_mesh)
{
    size_t group = state->group_count;
    const struct aiString *name = name_usable(&node->mName)         ? &node->mName
                                  : name_usable(&first_mesh->mName) ? &first_mesh->mName
                                                                    : NULL;
    state->named[group] = name != NULL;
    if (name)
        copy_name(state->names[group], GROUP_NAME_SIZE, name->data,
                  strnlen(name->data, sizeof name->data));
}

static ur_status add_vertices(import_state *state, const struct aiMesh *mesh, unsigned index,
                              const affine *to_mm, ur_error *error)
{
    char label[256];
    for (unsigned v = 0; v < mesh->mNumVertices; v++) {
        ur_vec3 p = affine_apply(to_mm, mesh->mVertices[v]);
        double largest = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
        /* !(a <= b) also catches NaN, e.g. from an infinite node scale times zero. */
        if (!(largest <= UR_MESH_IMPORT_MAX_COORDINATE))
            return ur_error_set(error, UR_ERROR_INPUT,
                                "%s: %s, vertex %u lies at (%g, %g, %g) mm once unit, scale "
                                "and node transforms are applied: coordinates beyond 1000 km "
                                "are refused",
                                state->path, mesh_label(mesh, index, label, sizeof label), v + 1,
                                p.x, p.y, p.z);
        state->vertices[state->vertex_count + v] = p;
    }
    return UR_OK;
}

/*
 * Copies one mesh's triangles after its vertices, turned round under a
 * mirror, and notes where the triangles of its quads and larger polygons
 * begin.
 */
static void add_triangles(import_state *state, const struct aiMesh *mesh, unsigned index,
                          bool mirrored)
{
    size_t base = state->vertex_count;
    const unsigned *corners = io_polygon_marks_of(&state->polygons, index);
    for (unsigned f = 0; f < mesh->mNumFaces; f++) {
        const struct aiFace *face = &mesh->mFaces[f];
        if (face->mNumIndices != 3)
            continue;
        if (corners && corners[f] == 4 && f + 1 < mesh->mNumFaces &&
            mesh->mFaces[f + 1].mNumIndices == 3)
            state->quad_starts[state->quad_count++] = state->triangle_count;
        if (corners && corners[f] >= 5 && corners[f] - 2 <= mesh->mNumFaces - f) {
            state->polygon_starts[state->polygon_count] = state->triangle_count;
            state->polygon_corners[state->polygon_count++] = corners[f];
        }
        size_t *t = state->triangles[state->triangle_count];
        t[0] = base + face->mIndices[0];
        t[1] = base + face->mIndices[mirrored ? 2 : 1];
        t[2] = base + face->mIndices[mirrored ? 1 : 2];
        state->groups[state->triangle_count] = state->group_count;
        state->triangle_count++;
    }
    state->vertex_count += mesh->mNumVertices;
}

/* Adds the node's triangle meshes as one group (check_faces vetted every index). */
static ur_status fill_meshes(import_state *state, const struct aiNode *node, const affine *global,
                             ur_error *error)
{
    affine scale = {{{state->factor, 0, 0, 0}, {0, state->factor, 0, 0}, {0, 0, state->factor, 0}}};
    affine to_mm = affine_compose(&scale, global);
    bool mirrored = affine_det(global) < 0;
    bool started = false;
    for (unsigned i = 0; i < node->mNumMeshes; i++) {
        const struct aiMesh *mesh = NULL;
        unsigned index = 0;
        ur_status status = node_mesh(state, node, i, &mesh, &index, error);
        if (status != UR_OK)
            return status;
        if (mesh_triangles(mesh, NULL) == 0)
            continue;
        if (!started)
            name_group(state, node, mesh);
        started = true;
        status = add_vertices(state, mesh, index, &to_mm, error);
        if (status != UR_OK)
            return status;
        add_triangles(state, mesh, index, mirrored);
    }
    if (started)
        state->group_count++;
    return UR_OK;
}

/*
 * Second pass: each node's meshes in millimetres, its transform and its
 * parents' applied (count_node has bounded the depth).
 */
static ur_status fill_node(import_state *state, const struct aiNode *node, const affine *parent,
                           ur_error *error)
{
    affine local = affine_from_ai(&node->mTransformation);
    affine global = affine_compose(parent, &local);
    ur_status status = fill_meshes(state, node, &global, error);
    for (unsigned c = 0; status == UR_OK && c < node->mNumChildren; c++)
        status = fill_node(state, node->mChildren[c], &global, error);
    return status;
}

/* ---- Groups ------------------------------------------------------------ */

typedef struct group_key {
    const char *name;
    size_t index;
} group_key;

static int compare_keys(const void *a, const void *b)
{
    const group_key *p = a, *q = b;
    int order = strcmp(p->name, q->name);
    if (order != 0)
        return order;
    return (p->index > q->index) - (p->index < q->index);
}

/*
 * Gives unnamed groups the file's name ("NAME-2", ... when there are
 * several), so the report has something to show.
 */
static void name_unnamed(import_state *state)
{
    char stem[GROUP_NAME_SIZE];
    file_stem(state->path, stem, sizeof stem);
    size_t unnamed = 0;
    for (size_t g = 0; g < state->group_count; g++)
        unnamed += !state->named[g];
    size_t number = 0;
    for (size_t g = 0; g < state->group_count; g++) {
        if (state->named[g])
            continue;
        char suffix[32] = "";
        if (unnamed > 1)
            c_snprintf(suffix, sizeof suffix, "-%zu", ++number);
        size_t room = GROUP_NAME_SIZE - strlen(suffix);
        copy_name(state->names[g], room, stem, strlen(stem));
        strcat(state->names[g], suffix);
    }
}

/*
 * An OBJ group that comes back later ("g a", "g b", "g a") is one group,
 * which assimp splits into two nodes: groups of the same name become one,
 * numbered in the order they first appear.
 */
static ur_status merge_groups(import_state *state, ur_error *error)
{
    size_t count = state->group_count;
    group_key *keys = ur_alloc_array(count, sizeof *keys, error);
    size_t *renumber = ur_alloc_array(count, sizeof *renumber, error);
    if (!keys || !renumber) {
        free(keys);
        free(renumber);
        return UR_ERROR_MEMORY;
    }
    for (size_t g = 0; g < count; g++)
        keys[g] = (group_key){state->names[g], g};
    qsort(keys, count, sizeof *keys, compare_keys);
    /* renumber[g] first holds the earliest group of g's name (unnamed stay apart). */
    for (size_t k = 0; k < count; k++) {
        bool same = k > 0 && state->named[keys[k].index] && state->named[keys[k - 1].index] &&
                    strcmp(keys[k].name, keys[k - 1].name) == 0;
        renumber[keys[k].index] = same ? renumber[keys[k - 1].index] : keys[k].index;
    }
    size_t kept = 0;
    for (size_t g = 0; g < count; g++) {
        if (renumber[g] == g) {
            memmove(state->names[kept], state->names[g], GROUP_NAME_SIZE);
            renumber[g] = kept++;
        } else {
            renumber[g] = renumber[renumber[g]]; /* the earlier group is renumbered already */
        }
    }
    for (size_t t = 0; t < state->triangle_count; t++)
        state->groups[t] = renumber[state->groups[t]];
    state->group_count = kept;
    free(keys);
    free(renumber);
    return UR_OK;
}

/* ---- Import ------------------------------------------------------------ */

static ur_status refuse_no_triangles(const import_state *state, ur_error *error)
{
    if (state->stray_count > 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: no triangles, only %zu points and lines: unroll needs a surface",
                            state->path, state->stray_count);
    return ur_error_set(error, UR_ERROR_INPUT, "%s: no triangles: vertices but no faces",
                        state->path);
}

static ur_status build(import_state *state, ur_error *error)
{
    ur_status status = count_node(state, state->scene->mRootNode, 0, error);
    if (status != UR_OK)
        return status;
    if (state->triangle_count == 0)
        return refuse_no_triangles(state, error);
    status = allocate(state, error);
    if (status != UR_OK)
        return status;
    affine identity = affine_identity();
    status = fill_node(state, state->scene->mRootNode, &identity, error);
    if (status == UR_OK)
        status = io_quads_follow_surface(state->vertices, state->vertex_count, state->triangles,
                                         state->triangle_count, state->quad_starts,
                                         state->quad_count, error);
    if (status == UR_OK)
        status = io_triangulate_flat_polygons(state->vertices, state->triangles,
                                              state->triangle_count, state->polygon_starts,
                                              state->polygon_corners, state->polygon_count, error);
    if (status == UR_OK)
        status = io_repeated_faces_alike(state->vertices, state->vertex_count, state->triangles,
                                         state->triangle_count, state->quad_starts,
                                         state->quad_count, state->polygon_starts,
                                         state->polygon_corners, state->polygon_count, error);
    if (status != UR_OK)
        return status;
    name_unnamed(state);
    return merge_groups(state, error);
}

/* Hands the arrays over to mesh and *group_names; state keeps nothing. */
static void hand_over(import_state *state, ur_mesh *mesh, char (**group_names)[64])
{
    mesh->vertices = state->vertices;
    mesh->vertex_count = state->vertex_count;
    mesh->triangles = state->triangles;
    mesh->triangle_count = state->triangle_count;
    mesh->groups = state->groups;
    mesh->group_count = state->group_count;
    state->vertices = NULL;
    state->triangles = NULL;
    state->groups = NULL;
    if (group_names) {
        *group_names = state->names;
        state->names = NULL;
    }
    state_free(state);
}

/*
 * The millimetres in one of the file's numbers: the unit the caller gives,
 * or, by default, the one the file declares (millimetres when it has none).
 */
static double millimetres_per_number(const ur_mesh_import_options *options,
                                     const io_declared_unit *declared)
{
    if (options->unit != UR_UNIT_FILE)
        return ur_length_unit_mm(options->unit);
    return declared->mm > 0 ? declared->mm : 1.0;
}

/* The file at path, or size bytes of data named path when data is not NULL. */
static ur_status import_mesh(const char *path, const void *data, size_t size,
                             const ur_mesh_import_options *options, ur_mesh *mesh,
                             char (**group_names)[64], ur_error *error)
{
    *mesh = (ur_mesh){0};
    if (group_names)
        *group_names = NULL;
    ur_mesh_import_options defaults;
    ur_mesh_import_options_default(&defaults);
    if (!options)
        options = &defaults;
    ur_status status = check_options(options, error);
    if (status == UR_OK)
        status = data ? check_buffer(path, data, size, error) : check_file(path, error);
    io_declared_unit declared;
    if (status == UR_OK)
        status = io_mesh_declared_unit(path, data, size, &declared, error);
    import_state state = {.path = path};
    if (status == UR_OK)
        status = load_scene(path, data, size, &state.scene, &state.polygons, error);
    if (status != UR_OK)
        return status;
    state.factor = millimetres_per_number(options, &declared) / declared.applied * options->scale;
    status = build(&state, error);
    aiReleaseImport(state.scene);
    if (status != UR_OK) {
        state_free(&state);
        return status;
    }
    hand_over(&state, mesh, group_names);
    return UR_OK;
}

ur_status ur_mesh_import(const char *path, const ur_mesh_import_options *options, ur_mesh *mesh,
                         char (**group_names)[64], ur_error *error)
{
    return import_mesh(path, NULL, 0, options, mesh, group_names, error);
}

ur_status ur_mesh_import_buffer(const char *name, const void *data, size_t size,
                                const ur_mesh_import_options *options, ur_mesh *mesh,
                                char (**group_names)[64], ur_error *error)
{
    static const char nothing = 0; /* data NULL would mean a file: an empty buffer is refused */
    return import_mesh(name, data ? data : &nothing, size, options, mesh, group_names, error);
}

ur_status ur_mesh_declared_unit(const char *path, double *mm, char name[32], ur_error *error)
{
    *mm = 0;
    name[0] = '\0';
    if (!io_mesh_may_declare_unit(path))
        return UR_OK; /* a format that declares none: the file is not opened */
    /* Only the start of the file is read for its unit: assimp does not read it here, so the
     * whole document need not be checked again (ur_mesh_import checks it). */
    io_declared_unit declared;
    off_t size = 0;
    ur_status status = check_file_itself(path, &size, error);
    if (status == UR_OK)
        status = io_mesh_declared_unit(path, NULL, 0, &declared, error);
    if (status != UR_OK)
        return status;
    *mm = declared.mm;
    c_snprintf(name, 32, "%s", declared.mm > 0 ? declared.name : "");
    return UR_OK;
}
