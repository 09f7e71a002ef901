/*
 * mesh_units.c: the length unit a mesh file declares in its content, for
 * the two formats that have one: Collada (<asset><unit meter="0.0254"
 * name="inch"/>, SketchUp's export) and 3MF (<model unit="inch">, the 3D
 * printers' format, a zip archive).  assimp applies Collada's unit (its
 * coordinates come out in metres) and ignores 3MF's: mesh_import.c needs
 * both, to read a file in its own unit unless the caller gives another.
 *
 * Only the start of each document is read, with libxml2's streaming
 * reader: the unit comes before any geometry.  A 3MF's parts are read
 * through minizip (assimp's own unzip library), from disk or from memory.
 */
#include "io_internal.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/xmlreader.h>
#include <minizip/unzip.h>

#include "../base/c_locale.h"
#include "xml_errors.h"

/* ---- Reading the start of an XML document ------------------------------ */

/* The element the reader stands on next, at depth (0 the root); false at the end or an error. */
static bool next_element(xmlTextReaderPtr reader, int *depth)
{
    int status;
    while ((status = xmlTextReaderRead(reader)) == 1)
        if (xmlTextReaderNodeType(reader) == XML_READER_TYPE_ELEMENT) {
            *depth = xmlTextReaderDepth(reader);
            return true;
        }
    return false;
}

static bool element_is(xmlTextReaderPtr reader, const char *name)
{
    const xmlChar *local = xmlTextReaderConstLocalName(reader);
    return local && strcmp((const char *)local, name) == 0;
}

/* A copy of the attribute's value cut to size - 1 bytes, or "" when absent; false when absent. */
static bool attribute(xmlTextReaderPtr reader, const char *name, char *value, size_t size)
{
    xmlChar *text = xmlTextReaderGetAttribute(reader, (const xmlChar *)name);
    value[0] = '\0';
    if (!text)
        return false;
    c_snprintf(value, size, "%s", (const char *)text);
    xmlFree(text);
    return true;
}

/* "path: what: libxml2's message" for a document that is not well formed. */
static ur_status refuse_xml(const io_xml_capture *capture, const char *path, const char *what,
                            ur_error *error)
{
    if (capture->report.have)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: %s: line %d: %s", path, what,
                            capture->report.line, capture->report.message);
    return ur_error_set(error, UR_ERROR_INPUT, "%s: %s: not XML", path, what);
}

/* ---- Collada ----------------------------------------------------------- */

static const struct {
    const char *name;
    double metres;
} collada_names[] = {{"meter", 1},         {"metre", 1},          {"centimeter", 0.01},
                     {"centimetre", 0.01}, {"millimeter", 0.001}, {"millimetre", 0.001},
                     {"inch", 0.0254},     {"foot", 0.3048},      {"kilometer", 1000}};

/*
 * The unit's name for messages: the file's, where it is a unit of that
 * size (3ds Max has written name="centimeter" on a unit of one metre),
 * else its size in metres.
 */
static void name_collada_unit(const char *name, double metres, char *text, size_t size)
{
    for (size_t i = 0; i < sizeof collada_names / sizeof collada_names[0]; i++)
        if (strcmp(name, collada_names[i].name) == 0 &&
            fabs(metres - collada_names[i].metres) <= 1e-6 * metres) {
            c_snprintf(text, size, "%s", name);
            return;
        }
    c_snprintf(text, size, "%g m", metres);
}

/*
 * COLLADA/asset/unit: metres in one unit (the specification's default is
 * 1 when the element or the attribute is absent) and the unit's name.
 */
static ur_status collada_unit(xmlTextReaderPtr reader, const char *path, io_declared_unit *unit,
                              ur_error *error)
{
    int depth = 0;
    if (!next_element(reader, &depth) || !element_is(reader, "COLLADA"))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a Collada file: its first element is not <COLLADA>", path);
    char meter[64] = "1", name[sizeof unit->name] = "";
    bool in_asset = false;
    while (next_element(reader, &depth) && depth >= 1) {
        if (depth == 1) {
            if (in_asset || !element_is(reader, "asset"))
                break; /* the asset comes first: the unit is declared there or nowhere */
            in_asset = true;
        } else if (depth == 2 && element_is(reader, "unit")) {
            if (!attribute(reader, "meter", meter, sizeof meter))
                c_snprintf(meter, sizeof meter, "1");
            attribute(reader, "name", name, sizeof name);
            break;
        }
    }
    char *comma = strchr(meter, ',');
    if (comma) /* "0,010000": 3ds Max writes a decimal comma where the locale has one */
        *comma = '.';
    char *end = NULL;
    double metres = c_strtod(meter, &end);
    if (comma)
        *comma = ',';
    if (end == meter || *end != '\0' || !(metres > 0) || !isfinite(metres))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: <unit meter=\"%s\">: the metres in one unit must be a positive "
                            "number",
                            path, meter);
    unit->mm = 1000.0 * metres;
    /* assimp scales by the unit in single precision: its coordinates are raw * (float)metres. */
    unit->applied = (double)(float)metres;
    name_collada_unit(name, metres, unit->name, sizeof unit->name);
    return UR_OK;
}

/* ---- 3MF --------------------------------------------------------------- */

/*
 * minizip's file functions over a stdio stream: the file at the path, or
 * the buffer (fmemopen) when there is one, so that disk and memory are one
 * code path.
 */
typedef struct zip_source {
    const char *path;
    const void *data;
    size_t size;
} zip_source;

static voidpf zip_open(voidpf opaque, const void *name, int mode)
{
    (void)name, (void)mode;
    const zip_source *source = opaque;
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
    (void)opaque, (void)stream, (void)buffer, (void)size;
    return 0; /* read only */
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
    (void)opaque;
    return fclose(stream);
}

static int zip_error(voidpf opaque, voidpf stream)
{
    (void)opaque;
    return ferror(stream);
}

static unzFile zip_open_source(zip_source *source)
{
    zlib_filefunc64_def functions = {.zopen64_file = zip_open,
                                     .zread_file = zip_read,
                                     .zwrite_file = zip_write,
                                     .ztell64_file = zip_tell,
                                     .zseek64_file = zip_seek,
                                     .zclose_file = zip_close,
                                     .zerror_file = zip_error,
                                     .opaque = source};
    return unzOpen2_64(source->path, &functions);
}

/* libxml2 reads the archive's current part through this. */
static int read_part(void *context, char *buffer, int size)
{
    int count = unzReadCurrentFile(context, buffer, (unsigned)size);
    return count < 0 ? -1 : count;
}

static int close_part(void *context)
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
        xmlReaderForIO(read_part, close_part, zip, name, NULL, XML_PARSE_NONET);
    if (!reader)
        unzCloseCurrentFile(zip);
    return reader;
}

static void close_reader(unzFile zip, xmlTextReaderPtr reader)
{
    xmlFreeTextReader(reader);
    unzCloseCurrentFile(zip);
}

#define MODEL_RELATIONSHIP "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"

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
    while (!part[0] && next_element(reader, &depth))
        if (element_is(reader, "Relationship") && attribute(reader, "Type", type, sizeof type) &&
            strcmp(type, MODEL_RELATIONSHIP) == 0 &&
            attribute(reader, "Target", target, sizeof target))
            c_snprintf(part, size, "%s", target[0] == '/' ? target + 1 : target);
    close_reader(zip, reader);
    if (!part[0])
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a 3MF file: _rels/.rels names no 3D model", path);
    return UR_OK;
}

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
    bool model = next_element(reader, &depth) && element_is(reader, "model");
    if (model && !attribute(reader, "unit", name, sizeof name))
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

static ur_status three_mf_unit(const char *path, const void *data, size_t size,
                               io_declared_unit *unit, ur_error *error)
{
    zip_source source = {.path = path, .data = data, .size = size};
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

/* ---- 3MF thumbnails ---------------------------------------------------- */

/*
 * assimp 5.2 takes every picture whose name holds "thumbnail" (a 3MF's
 * Metadata/thumbnail.png, which PrusaSlicer, Cura and 3D Builder all
 * write) for a texture of the model, and then frees it twice: the import
 * crashes (assimp's issues 5307 and 5328, mended in later versions).
 * Such a part is renamed in a copy of the archive, its central directory
 * entry's "thumbnail" becoming "Thumbnail" (same length: nothing else
 * moves), and assimp reads the copy.  The model never needs a picture.
 */
#define ZIP_ENTRY_NAME_AT 46 /* bytes of a central directory entry before its name */

/* Renames the current entry in bytes if its name holds "thumbnail"; false if not where expected. */
static bool rename_thumbnail(unzFile zip, unsigned char *bytes, size_t size, bool *renamed)
{
    char name[1024];
    unz_file_info64 info;
    if (unzGetCurrentFileInfo64(zip, &info, name, sizeof name, NULL, 0, NULL, 0) != UNZ_OK)
        return false;
    if (!strstr(name, "thumbnail"))
        return true;
    size_t length = strlen(name);
    ZPOS64_T entry = unzGetOffset64(zip);
    if (info.size_filename != length || entry > size || size - entry < ZIP_ENTRY_NAME_AT + length)
        return false;
    char *stored = (char *)bytes + entry + ZIP_ENTRY_NAME_AT;
    if (memcmp(stored, name, length) != 0)
        return false; /* not a plain archive (data before it): leave it to the refusal */
    for (size_t i = 0; i + 9 <= length; i++)
        if (memcmp(stored + i, "thumbnail", 9) == 0)
            stored[i] = 'T';
    *renamed = true;
    return true;
}

ur_status io_3mf_without_thumbnails(const char *path, const void *data, size_t size,
                                    unsigned char **copy, size_t *copy_size, ur_error *error)
{
    *copy = NULL;
    *copy_size = 0;
    char *bytes = NULL;
    size_t length = size;
    ur_status status = data ? ((bytes = io_copy_text(data, size, error)) ? UR_OK : UR_ERROR_MEMORY)
                            : io_read_file(path, 0, "a mesh", &bytes, &length, error);
    if (status != UR_OK)
        return status;
    zip_source source = {.path = path, .data = bytes, .size = length};
    unzFile zip = zip_open_source(&source);
    bool renamed = false, understood = zip != NULL;
    for (int at = zip ? unzGoToFirstFile(zip) : UNZ_OK; understood && zip && at == UNZ_OK;
         at = unzGoToNextFile(zip))
        understood = rename_thumbnail(zip, (unsigned char *)bytes, length, &renamed);
    if (zip)
        unzClose(zip);
    if (!understood || !renamed) {
        free(bytes);
        if (zip && !understood)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "%s: cannot read the 3MF archive's table of contents", path);
        return UR_OK; /* nothing to rename, or not an archive (refused elsewhere) */
    }
    *copy = (unsigned char *)bytes;
    *copy_size = length;
    return UR_OK;
}

/* ---- Either ------------------------------------------------------------ */

static ur_status collada_unit_of(const char *path, const void *data, size_t size,
                                 io_declared_unit *unit, ur_error *error)
{
    if (data && size > INT_MAX) /* libxml2 takes the length as an int */
        return ur_error_set(error, UR_ERROR_INPUT, "%s: %zu bytes: too large to read from memory",
                            path, size);
    xmlTextReaderPtr reader = data
                                  ? xmlReaderForMemory(data, (int)size, path, NULL, XML_PARSE_NONET)
                                  : xmlReaderForFile(path, NULL, XML_PARSE_NONET);
    if (!reader)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path,
                            errno ? strerror(errno) : "not XML");
    ur_status status = collada_unit(reader, path, unit, error);
    xmlFreeTextReader(reader);
    return status;
}

ur_status io_mesh_declared_unit(const char *path, const void *data, size_t size,
                                io_declared_unit *unit, ur_error *error)
{
    *unit = (io_declared_unit){.mm = 0.0, .applied = 1.0};
    bool collada = io_has_extension(path, "dae"), three_mf = io_has_extension(path, "3mf");
    if (!collada && !three_mf)
        return UR_OK;
    io_xml_capture capture;
    io_xml_capture_begin(&capture);
    errno = 0;
    ur_status status = collada ? collada_unit_of(path, data, size, unit, error)
                               : three_mf_unit(path, data, size, unit, error);
    io_xml_capture_end(&capture);
    if (capture.report.have) /* what went wrong first */
        status = refuse_xml(&capture, path, collada ? "Collada" : "3MF model", error);
    return status;
}

size_t io_mesh_unpacked_size(const char *path)
{
    if (!io_has_extension(path, "3mf"))
        return 0;
    zip_source source = {.path = path};
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
