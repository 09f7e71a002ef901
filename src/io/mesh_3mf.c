/*
 * mesh_3mf.c: 3MF files (zip archives of XML parts) made ready for
 * assimp 5.2's reader, and the unit they declare.
 *
 * assimp reads 3MF, but in its version 5.2 only the one model part the
 * package's relationships name, and it aborts on a picture whose name
 * holds "thumbnail" (a 3MF's Metadata/thumbnail.png, which PrusaSlicer,
 * Cura and 3D Builder all write): it takes it for a texture and frees it
 * twice (assimp's issues 5307 and 5328, mended in later versions).  So
 * assimp is given a new archive, made here in memory, with the package's
 * content types, its root relationships and its model alone; where the
 * model's components lie in other parts (3MF's production extension, in
 * which Bambu Studio writes every model: the build names objects whose
 * meshes are in 3D/Objects/object_N.model), those objects are copied
 * into the model under new numbers first.  A part is read through
 * minizip (assimp's own unzip library), from disk or from memory, and
 * XML through libxml2.
 */
#include "io_internal.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlreader.h>
#include <minizip/unzip.h>
#include <minizip/zip.h>

#include "../base/c_locale.h"
#include "xml_errors.h"

#define MODEL_RELATIONSHIP "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"
#define PRODUCTION_NAMESPACE "http://schemas.microsoft.com/3dmanufacturing/production/2015/06"
#define CORE_NAMESPACE "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"

/* Components nested deeper than this (across parts) are not a model. */
#define MAX_COMPONENT_DEPTH 64

/* ---- The archive ------------------------------------------------------- */

/*
 * minizip's file functions over a stdio stream: the file at the path, the
 * buffer when there is one (fmemopen), or a stream written to memory
 * (open_memstream) for a new archive, so that all are one code path.
 */
typedef struct zip_stream {
    const char *path;
    const void *data;
    size_t size;
    FILE *written; /* a new archive: the stream it is written to */
} zip_stream;

static voidpf zip_open(voidpf opaque, const void *name, int mode)
{
    (void)name, (void)mode;
    const zip_stream *source = opaque;
    if (source->written)
        return source->written;
    /* "r": the buffer is only read */
    return source->data ? fmemopen((void *)source->data, source->size, "r")
                        : fopen(source->path, "rb");
}

static uLong zip_read(voidpf opaque, voidpf stream, void *buffer, uLong size)
{
    (void)opaque;
    return (uLong)fread(buffer, 1, size, stream);
}

static uLong zip_write(voidpf opaque, voidpf stream, const void *buffer, uLong size)
{
    (void)opaque;
    return (uLong)fwrite(buffer, 1, size, stream);
}

static ZPOS64_T zip_tell(voidpf opaque, voidpf stream)
{
    (void)opaque;
    off_t at = ftello(stream);
    return at < 0 ? (ZPOS64_T)-1 : (ZPOS64_T)at;
}

static long zip_seek(voidpf opaque, voidpf stream, ZPOS64_T offset, int origin)
{
    (void)opaque;
    int whence = origin == ZLIB_FILEFUNC_SEEK_SET   ? SEEK_SET
                 : origin == ZLIB_FILEFUNC_SEEK_CUR ? SEEK_CUR
                                                    : SEEK_END;
    return fseeko(stream, (off_t)offset, whence) == 0 ? 0 : -1;
}

static int zip_close(voidpf opaque, voidpf stream)
{
    const zip_stream *source = opaque;
    if (source->written) /* closed by whoever opened it, to keep what was written */
        return fflush(stream);
    return fclose(stream);
}

static int zip_error(voidpf opaque, voidpf stream)
{
    (void)opaque;
    return ferror(stream);
}

static zlib_filefunc64_def zip_functions(zip_stream *source)
{
    return (zlib_filefunc64_def){.zopen64_file = zip_open,
                                 .zread_file = zip_read,
                                 .zwrite_file = zip_write,
                                 .ztell64_file = zip_tell,
                                 .zseek64_file = zip_seek,
                                 .zclose_file = zip_close,
                                 .zerror_file = zip_error,
                                 .opaque = source};
}

static unzFile zip_open_source(zip_stream *source)
{
    zlib_filefunc64_def functions = zip_functions(source);
    return unzOpen2_64(source->path, &functions);
}

/* libxml2 reads the archive's current part through this. */
static int read_current(void *context, char *buffer, int size)
{
    int count = unzReadCurrentFile(context, buffer, (unsigned)size);
    return count < 0 ? -1 : count;
}

static int close_current(void *context)
{
    (void)context; /* the part is closed by whoever opened it */
    return 0;
}

/* A reader over the archive's part called name (no leading '/'), or NULL when it has none. */
static xmlTextReaderPtr open_part(unzFile zip, const char *name)
{
    if (unzLocateFile(zip, name, 0) != UNZ_OK || unzOpenCurrentFile(zip) != UNZ_OK)
        return NULL;
    xmlTextReaderPtr reader =
        xmlReaderForIO(read_current, close_current, zip, name, NULL, XML_PARSE_NONET);
    if (!reader)
        unzCloseCurrentFile(zip);
    return reader;
}

static void close_reader(unzFile zip, xmlTextReaderPtr reader)
{
    xmlFreeTextReader(reader);
    unzCloseCurrentFile(zip);
}

/* The whole of the part called name into *bytes (the caller frees it); false when it has none. */
static bool read_part(unzFile zip, const char *name, char **bytes, size_t *size)
{
    *bytes = NULL;
    *size = 0;
    unz_file_info64 info;
    if (unzLocateFile(zip, name, 0) != UNZ_OK ||
        unzGetCurrentFileInfo64(zip, &info, NULL, 0, NULL, 0, NULL, 0) != UNZ_OK ||
        info.uncompressed_size >= INT_MAX || unzOpenCurrentFile(zip) != UNZ_OK)
        return false;
    size_t length = (size_t)info.uncompressed_size;
    char *buffer = malloc(length + 1);
    int count = buffer ? unzReadCurrentFile(zip, buffer, (unsigned)length) : -1;
    bool whole = unzCloseCurrentFile(zip) == UNZ_OK && count >= 0 && (size_t)count == length;
    if (!whole) {
        free(buffer);
        return false;
    }
    buffer[length] = '\0';
    *bytes = buffer;
    *size = length;
    return true;
}

/* A part's name as a target gives it ("/3D/3dmodel.model"), without the leading '/'. */
static const char *part_name(const char *target)
{
    return target[0] == '/' ? target + 1 : target;
}

/*
 * The part holding the model, as assimp finds it: the target of the
 * package's 3D model relationship in _rels/.rels, without its leading '/'.
 */
static ur_status model_part(unzFile zip, const char *path, char *part, size_t size, ur_error *error)
{
    part[0] = '\0';
    xmlTextReaderPtr reader = open_part(zip, "_rels/.rels");
    if (!reader)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a 3MF file: the archive has no _rels/.rels", path);
    int depth = 0;
    char type[256], target[1024];
    while (!part[0] && io_reader_next_element(reader, &depth))
        if (io_reader_is(reader, "Relationship") &&
            io_reader_attribute(reader, "Type", type, sizeof type) &&
            strcmp(type, MODEL_RELATIONSHIP) == 0 &&
            io_reader_attribute(reader, "Target", target, sizeof target))
            c_snprintf(part, size, "%s", part_name(target));
    close_reader(zip, reader);
    if (!part[0])
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a 3MF file: _rels/.rels names no 3D model", path);
    return UR_OK;
}

/* ---- The unit ---------------------------------------------------------- */

static const struct {
    const char *name;
    double mm;
} model_units[] = {{"micron", 0.001}, {"millimeter", 1.0}, {"centimeter", 10.0},
                   {"inch", 25.4},    {"foot", 304.8},     {"meter", 1000.0}};

/* The unit attribute of the model part's root, <model>; millimetres when absent. */
static ur_status model_unit(unzFile zip, const char *path, const char *part, io_declared_unit *unit,
                            ur_error *error)
{
    xmlTextReaderPtr reader = open_part(zip, part);
    if (!reader)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a 3MF file: the archive has no part '%.200s'", path, part);
    int depth = 0;
    char name[64] = "millimeter";
    bool model = io_reader_next_element(reader, &depth) && io_reader_is(reader, "model");
    if (model && !io_reader_attribute(reader, "unit", name, sizeof name))
        c_snprintf(name, sizeof name, "millimeter");
    close_reader(zip, reader);
    if (!model)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a 3MF file: its model '%.200s' does not start with <model>",
                            path, part);
    for (size_t i = 0; i < sizeof model_units / sizeof model_units[0]; i++)
        if (strcmp(name, model_units[i].name) == 0) {
            unit->mm = model_units[i].mm;
            unit->applied = 1.0; /* assimp leaves the numbers as they are */
            c_snprintf(unit->name, sizeof unit->name, "%s", name);
            return UR_OK;
        }
    return ur_error_set(error, UR_ERROR_INPUT,
                        "%s: <model unit=\"%.60s\">: not a 3MF unit (micron, millimeter, "
                        "centimeter, inch, foot, meter)",
                        path, name);
}

ur_status io_3mf_unit(const char *path, const void *data, size_t size, io_declared_unit *unit,
                      ur_error *error)
{
    zip_stream source = {.path = path, .data = data, .size = size};
    unzFile zip = zip_open_source(&source);
    if (!zip)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: not a 3MF file: not a zip archive", path);
    char part[1024];
    ur_status status = model_part(zip, path, part, sizeof part, error);
    if (status == UR_OK)
        status = model_unit(zip, path, part, unit, error);
    unzClose(zip);
    return status;
}

size_t io_mesh_unpacked_size(const char *path)
{
    if (!io_has_extension(path, "3mf"))
        return 0;
    zip_stream source = {.path = path};
    unzFile zip = zip_open_source(&source);
    if (!zip)
        return 0;
    size_t total = 0;
    for (int at = unzGoToFirstFile(zip); at == UNZ_OK; at = unzGoToNextFile(zip)) {
        unz_file_info64 info;
        if (unzGetCurrentFileInfo64(zip, &info, NULL, 0, NULL, 0, NULL, 0) != UNZ_OK)
            break;
        total = info.uncompressed_size > SIZE_MAX - total ? SIZE_MAX
                                                          : total + (size_t)info.uncompressed_size;
    }
    unzClose(zip);
    return total;
}

/* ---- Objects from other parts ------------------------------------------ */

/* An object copied into the model: from which part, under which id, and its number there. */
typedef struct copied_object {
    char part[1024];
    int id, number;
} copied_object;

typedef struct read_document {
    char name[1024];
    xmlDocPtr doc;
} read_document;

typedef struct merger {
    unzFile zip;
    const char *path;      /* the file, for messages */
    const char *root_part; /* the model's own part */
    xmlNodePtr resources;  /* the model's <resources>, where copies go */
    int next_number;       /* above every id in the model */
    read_document *parts;  /* owned: the other parts read so far */
    size_t part_count;
    copied_object *copies; /* owned */
    size_t copy_count;
} merger;

static bool is_element(xmlNodePtr node, const char *name)
{
    return node && node->type == XML_ELEMENT_NODE && strcmp((const char *)node->name, name) == 0;
}

static xmlNodePtr child_element(xmlNodePtr parent, const char *name)
{
    for (xmlNodePtr node = parent ? parent->children : NULL; node; node = node->next)
        if (is_element(node, name))
            return node;
    return NULL;
}

/* An integer attribute; false when absent or not a whole number. */
static bool integer_attribute(xmlNodePtr node, const char *name, int *value)
{
    xmlChar *text = xmlGetProp(node, (const xmlChar *)name);
    if (!text)
        return false;
    char *end = NULL;
    long number = strtol((const char *)text, &end, 10);
    bool whole = end != (char *)text && *end == '\0' && number >= 0 && number < INT_MAX;
    xmlFree(text);
    if (whole)
        *value = (int)number;
    return whole;
}

static void set_integer_attribute(xmlNodePtr node, const char *name, int value)
{
    char text[32];
    c_snprintf(text, sizeof text, "%d", value);
    xmlSetProp(node, (const xmlChar *)name, (const xmlChar *)text);
}

static void remove_attribute(xmlNodePtr node, const char *name)
{
    xmlAttrPtr attribute = xmlHasProp(node, (const xmlChar *)name);
    if (attribute)
        xmlRemoveProp(attribute);
}

/* The production extension's p:path of a component or build item (xmlFree it), or NULL. */
static char *production_path(xmlNodePtr node)
{
    return (char *)xmlGetNsProp(node, (const xmlChar *)"path",
                                (const xmlChar *)PRODUCTION_NAMESPACE);
}

static void remove_production_path(xmlNodePtr node)
{
    xmlAttrPtr attribute =
        xmlHasNsProp(node, (const xmlChar *)"path", (const xmlChar *)PRODUCTION_NAMESPACE);
    if (attribute)
        xmlRemoveProp(attribute);
}

static ur_status refuse_part(const merger *m, const char *part, const char *why, ur_error *error)
{
    return ur_error_set(error, UR_ERROR_INPUT, "%s: 3MF part '%.200s': %s", m->path, part, why);
}

/* The parsed part called name, read once. */
static ur_status part_document(merger *m, const char *name, xmlDocPtr *doc, ur_error *error)
{
    for (size_t i = 0; i < m->part_count; i++)
        if (strcmp(m->parts[i].name, name) == 0) {
            *doc = m->parts[i].doc;
            return UR_OK;
        }
    char *bytes = NULL;
    size_t size = 0;
    if (!read_part(m->zip, name, &bytes, &size))
        return refuse_part(m, name, "a component names it, but the archive has no such part",
                           error);
    *doc = xmlReadMemory(bytes, (int)size, name, NULL, XML_PARSE_NONET);
    free(bytes);
    read_document *grown = realloc(m->parts, (m->part_count + 1) * sizeof *grown);
    if (!grown || !*doc) {
        xmlFreeDoc(*doc);
        if (grown)
            m->parts = grown;
        return grown ? refuse_part(m, name, "not XML", error) : ur_error_out_of_memory(error);
    }
    m->parts = grown;
    c_snprintf(m->parts[m->part_count].name, sizeof m->parts[0].name, "%s", name);
    m->parts[m->part_count++].doc = *doc;
    return UR_OK;
}

/* The part's <object id="id">, or NULL. */
static xmlNodePtr find_object(xmlDocPtr doc, int id)
{
    xmlNodePtr resources = child_element(xmlDocGetRootElement(doc), "resources");
    for (xmlNodePtr node = resources ? resources->children : NULL; node; node = node->next) {
        int found = -1;
        if (is_element(node, "object") && integer_attribute(node, "id", &found) && found == id)
            return node;
    }
    return NULL;
}

/*
 * Colours and materials (pid, pindex, p1 to p3) name resources of the part
 * the object came from, which are not copied: cut files have no colour, and
 * assimp 5.2 does not check that such an index is in range.
 */
static void drop_properties(xmlNodePtr object)
{
    remove_attribute(object, "pid");
    remove_attribute(object, "pindex");
    xmlNodePtr triangles = child_element(child_element(object, "mesh"), "triangles");
    for (xmlNodePtr node = triangles ? triangles->children : NULL; node; node = node->next)
        if (is_element(node, "triangle")) {
            remove_attribute(node, "pid");
            remove_attribute(node, "p1");
            remove_attribute(node, "p2");
            remove_attribute(node, "p3");
        }
}

static ur_status refer_within_model(merger *m, xmlNodePtr node, const char *part, int depth,
                                    ur_error *error);

/*
 * The number in the model of the object id of part: itself in the model's
 * own part, else a copy made once (its own components brought in too).
 */
static ur_status bring_object(merger *m, const char *part, int id, int depth, int *number,
                              ur_error *error)
{
    if (strcmp(part, m->root_part) == 0) {
        *number = id;
        return UR_OK;
    }
    for (size_t i = 0; i < m->copy_count; i++)
        if (m->copies[i].id == id && strcmp(m->copies[i].part, part) == 0) {
            *number = m->copies[i].number;
            return UR_OK;
        }
    if (depth > MAX_COMPONENT_DEPTH)
        return refuse_part(m, part, "components nested too deep (a loop?)", error);
    xmlDocPtr doc = NULL;
    ur_status status = part_document(m, part, &doc, error);
    if (status != UR_OK)
        return status;
    xmlNodePtr object = find_object(doc, id);
    if (!object) {
        char why[96];
        c_snprintf(why, sizeof why, "a component names its object %d, which it does not have", id);
        return refuse_part(m, part, why, error);
    }
    xmlNodePtr copy = xmlDocCopyNode(object, m->resources->doc, 1);
    copied_object *grown = realloc(m->copies, (m->copy_count + 1) * sizeof *grown);
    if (!copy || !grown) {
        xmlFreeNode(copy);
        if (grown)
            m->copies = grown;
        return ur_error_out_of_memory(error);
    }
    m->copies = grown;
    *number = m->next_number++;
    copied_object *record = &m->copies[m->copy_count++];
    c_snprintf(record->part, sizeof record->part, "%s", part);
    record->id = id;
    record->number = *number;
    set_integer_attribute(copy, "id", *number);
    drop_properties(copy);
    /* Before the first resource: an object comes before the objects that use it. */
    if (m->resources->children)
        xmlAddPrevSibling(m->resources->children, copy);
    else
        xmlAddChild(m->resources, copy);
    return refer_within_model(m, child_element(copy, "components"), part, depth + 1, error);
}

/*
 * Points every component (or build item) under parent that names an object
 * by part (its p:path, or the part it lies in) at that object's number in
 * the model.
 */
static ur_status refer_within_model(merger *m, xmlNodePtr parent, const char *part, int depth,
                                    ur_error *error)
{
    for (xmlNodePtr node = parent ? parent->children : NULL; node; node = node->next) {
        if (!is_element(node, "component") && !is_element(node, "item"))
            continue;
        char *path = production_path(node);
        char target[1024];
        c_snprintf(target, sizeof target, "%s", path ? part_name(path) : part);
        xmlFree(path);
        int id = -1, number = -1;
        if (!integer_attribute(node, "objectid", &id))
            continue; /* assimp skips it too */
        ur_status status = bring_object(m, target, id, depth, &number, error);
        if (status != UR_OK)
            return status;
        set_integer_attribute(node, "objectid", number);
        remove_production_path(node);
    }
    return UR_OK;
}

/* One more than the largest id of the model's resources. */
static int first_free_number(xmlNodePtr resources)
{
    int largest = 0;
    for (xmlNodePtr node = resources->children; node; node = node->next) {
        int id = 0;
        if (node->type == XML_ELEMENT_NODE && integer_attribute(node, "id", &id) && id > largest)
            largest = id;
    }
    return largest + 1;
}

/* The model with the objects its components take from other parts copied in, as XML text. */
static ur_status merge_parts(unzFile zip, const char *path, const char *root_part,
                             const char *bytes, size_t size, xmlChar **merged, int *merged_size,
                             ur_error *error)
{
    xmlDocPtr model = xmlReadMemory(bytes, (int)size, root_part, NULL, XML_PARSE_NONET);
    xmlNodePtr root = model ? xmlDocGetRootElement(model) : NULL;
    xmlNodePtr resources = child_element(root, "resources");
    if (!resources) {
        xmlFreeDoc(model);
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: 3MF model '%.200s': not XML, or no <resources>", path, root_part);
    }
    merger m = {.zip = zip,
                .path = path,
                .root_part = root_part,
                .resources = resources,
                .next_number = first_free_number(resources)};
    ur_status status = UR_OK;
    for (xmlNodePtr node = resources->children; status == UR_OK && node; node = node->next)
        if (is_element(node, "object"))
            status = refer_within_model(&m, child_element(node, "components"), root_part, 0, error);
    if (status == UR_OK)
        status = refer_within_model(&m, child_element(root, "build"), root_part, 0, error);
    if (status == UR_OK) {
        xmlDocDumpMemory(model, merged, merged_size);
        if (!*merged)
            status = ur_error_out_of_memory(error);
    }
    for (size_t i = 0; i < m.part_count; i++)
        xmlFreeDoc(m.parts[i].doc);
    free(m.parts);
    free(m.copies);
    xmlFreeDoc(model);
    return status;
}

/* ---- Components assimp can follow ------------------------------------- */

/* An object, or a component naming one, and the place of its object in the model (0, 1, ...). */
typedef struct object_place {
    int id;
    size_t place;
} object_place;

static int by_id(const void *a, const void *b)
{
    const object_place *p = a, *q = b;
    return (p->id > q->id) - (p->id < q->id);
}

static bool add_place(object_place **places, size_t *count, int id, size_t place)
{
    object_place *grown = realloc(*places, (*count + 1) * sizeof *grown);
    if (!grown)
        return false;
    grown[(*count)++] = (object_place){id, place};
    *places = grown;
    return true;
}

/*
 * The attributes of a core <vertex> (x, y, z) or <triangle> (v1, v2, v3)
 * that are present are numbers: assimp 5.2 reads a word as 0, which makes
 * a wrong model without a word.  UR_ERROR_INPUT naming the line.
 */
static ur_status check_numbers(xmlTextReaderPtr reader, const char *path, const char *part,
                               ur_error *error)
{
    const xmlChar *space = xmlTextReaderConstNamespaceUri(reader);
    bool vertex = io_reader_is(reader, "vertex");
    if (!space || strcmp((const char *)space, CORE_NAMESPACE) != 0 ||
        (!vertex && !io_reader_is(reader, "triangle")))
        return UR_OK; /* a slice's 2D vertex, say, is not read as the mesh's */
    static const char *const names[2][3] = {{"v1", "v2", "v3"}, {"x", "y", "z"}};
    for (int k = 0; k < 3; k++) {
        char text[64];
        if (!io_reader_attribute(reader, names[vertex][k], text, sizeof text))
            continue;
        uint64_t index = 0;
        char *word = io_trim(text);
        bool number = vertex ? io_real_number(word, strlen(word), false)
                             : io_whole_number(word, strlen(word), false, INT_MAX, &index);
        if (!number)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "%s: 3MF model '%.200s': line %ld: <%s %s=\"%s\">: not %s", path,
                                part, xmlGetLineNo(xmlTextReaderCurrentNode(reader)),
                                vertex ? "vertex" : "triangle", names[vertex][k], text,
                                vertex ? "a number" : "a vertex number");
    }
    return UR_OK;
}

/*
 * Every component must name an object the model defines before the one it
 * is in, as 3MF requires: assimp 5.2 dereferences a missing one and
 * follows a loop for ever (both crash it); and every vertex's coordinates
 * and triangle's corners are numbers (check_numbers).
 */
static ur_status check_model(const char *path, const char *part, const char *bytes, size_t size,
                             ur_error *error)
{
    xmlTextReaderPtr reader =
        xmlReaderForMemory(bytes, (int)size, part, NULL, XML_PARSE_NONET | XML_PARSE_BIG_LINES);
    if (!reader)
        return ur_error_out_of_memory(error);
    object_place *objects = NULL, *components = NULL;
    size_t object_count = 0, component_count = 0, place = 0;
    bool stored = true;
    int depth = 0, id = 0;
    char text[32];
    ur_status status = UR_OK;
    while (stored && status == UR_OK && io_reader_next_element(reader, &depth)) {
        if (depth == 2 && io_reader_is(reader, "object") &&
            io_reader_attribute(reader, "id", text, sizeof text))
            stored = add_place(&objects, &object_count, atoi(text), ++place);
        else if (depth == 4 && io_reader_is(reader, "component") &&
                 io_reader_attribute(reader, "objectid", text, sizeof text))
            stored = add_place(&components, &component_count, atoi(text), place);
        else if (depth == 5)
            status = check_numbers(reader, path, part, error);
    }
    xmlFreeTextReader(reader);
    if (status == UR_OK && object_count > 0)
        qsort(objects, object_count, sizeof *objects, by_id);
    if (status == UR_OK && !stored)
        status = ur_error_out_of_memory(error);
    for (size_t i = 0; status == UR_OK && i < component_count; i++) {
        const object_place *named = /* no object: its id missing, say */
            object_count ? bsearch(&components[i], objects, object_count, sizeof *objects, by_id)
                         : NULL;
        id = components[i].id;
        if (!named || named->place >= components[i].place)
            status = ur_error_set(error, UR_ERROR_INPUT,
                                  "%s: 3MF model '%.200s': a component names object %d, which "
                                  "is not defined before it",
                                  path, part, id);
    }
    free(objects);
    free(components);
    return status;
}

/* ---- The archive assimp reads ------------------------------------------ */

typedef struct archive_part {
    const char *name;
    const char *bytes;
    size_t size;
} archive_part;

/* A new zip archive of the parts (stored, not compressed), in memory the caller frees. */
static ur_status write_archive(const archive_part *parts, size_t count, unsigned char **archive,
                               size_t *archive_size, ur_error *error)
{
    char *buffer = NULL;
    size_t length = 0;
    FILE *stream = open_memstream(&buffer, &length);
    if (!stream)
        return ur_error_out_of_memory(error);
    zip_stream sink = {.path = "memory", .written = stream};
    zlib_filefunc64_def functions = zip_functions(&sink);
    zipFile zip = zipOpen2_64(sink.path, APPEND_STATUS_CREATE, NULL, &functions);
    bool written = zip != NULL;
    for (size_t i = 0; written && i < count; i++)
        written = parts[i].size < UINT_MAX &&
                  zipOpenNewFileInZip64(zip, parts[i].name, NULL, NULL, 0, NULL, 0, NULL, 0, 0,
                                        0) == ZIP_OK &&
                  zipWriteInFileInZip(zip, parts[i].bytes, (unsigned)parts[i].size) == ZIP_OK &&
                  zipCloseFileInZip(zip) == ZIP_OK;
    if (zip && zipClose(zip, NULL) != ZIP_OK)
        written = false;
    if (fclose(stream) != 0 || !written) {
        free(buffer);
        return ur_error_out_of_memory(error);
    }
    *archive = (unsigned char *)buffer;
    *archive_size = length;
    return UR_OK;
}

/* Whether the model may name parts (the production extension's p:path): worth parsing. */
static bool may_name_parts(const char *bytes)
{
    return strstr(bytes, PRODUCTION_NAMESPACE) != NULL && strstr(bytes, "path=") != NULL;
}

static ur_status prepare(const char *path, const void *data, size_t size, unsigned char **archive,
                         size_t *archive_size, ur_error *error)
{
    zip_stream source = {.path = path, .data = data, .size = size};
    unzFile zip = zip_open_source(&source);
    if (!zip)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: not a 3MF file: not a zip archive", path);
    char root_part[1024];
    char *types = NULL, *relationships = NULL, *model = NULL;
    size_t types_size = 0, relationships_size = 0, model_size = 0;
    xmlChar *merged = NULL;
    int merged_size = 0;
    ur_status status = model_part(zip, path, root_part, sizeof root_part, error);
    if (status == UR_OK && !read_part(zip, root_part, &model, &model_size))
        status =
            ur_error_set(error, UR_ERROR_INPUT,
                         "%s: not a 3MF file: the archive has no part '%.200s'", path, root_part);
    read_part(zip, "[Content_Types].xml", &types, &types_size);
    read_part(zip, "_rels/.rels", &relationships, &relationships_size);
    if (status == UR_OK && may_name_parts(model))
        status = merge_parts(zip, path, root_part, model, model_size, &merged, &merged_size, error);
    unzClose(zip);
    if (status == UR_OK)
        status = check_model(path, root_part, merged ? (const char *)merged : model,
                             merged ? (size_t)merged_size : model_size, error);
    if (status == UR_OK) {
        archive_part parts[] = {
            {"[Content_Types].xml", types, types_size},
            {"_rels/.rels", relationships, relationships_size},
            {root_part, merged ? (const char *)merged : model,
             merged ? (size_t)merged_size : model_size},
        };
        size_t first = types ? 0 : 1;
        status = write_archive(parts + first, 3 - first, archive, archive_size, error);
    }
    free(types);
    free(relationships);
    free(model);
    xmlFree(merged);
    return status;
}

/*
 * The archive made ready, or the first problem libxml2 saw in its XML.
 */
ur_status io_3mf_for_assimp(const char *path, const void *data, size_t size,
                            unsigned char **archive, size_t *archive_size, ur_error *error)
{
    *archive = NULL;
    *archive_size = 0;
    io_xml_capture capture;
    io_xml_capture_begin(&capture);
    ur_status status = prepare(path, data, size, archive, archive_size, error);
    io_xml_capture_end(&capture);
    if (capture.report.have && status == UR_OK) { /* the model, or a part, is not well formed */
        free(*archive);
        *archive = NULL;
        *archive_size = 0;
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: 3MF part '%.200s': line %d: %s", path,
                              capture.report.file[0] ? capture.report.file : "?",
                              capture.report.line, capture.report.message);
    }
    return status;
}
