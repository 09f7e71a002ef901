/*
 * mesh_units.c: the length unit a mesh file declares in its content, for
 * the two formats that have one: Collada (<asset><unit meter="0.0254"
 * name="inch"/>, SketchUp's export) and 3MF (<model unit="inch">, the 3D
 * printers' format, a zip archive: mesh_3mf.c).  assimp applies
 * Collada's unit (its coordinates come out in metres) and ignores 3MF's:
 * mesh_import.c needs both, to read a file in its own unit unless the
 * caller gives another.
 *
 * Only the start of each document is read, with libxml2's streaming
 * reader: the unit comes before any geometry.
 */
#include "io_internal.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/xmlreader.h>

#include "../base/c_locale.h"
#include "xml_errors.h"

/* ---- Reading the start of an XML document ------------------------------ */

/* The element the reader stands on next, at depth (0 the root); false at the end or an error. */
bool io_reader_next_element(xmlTextReaderPtr reader, int *depth)
{
    int status;
    while ((status = xmlTextReaderRead(reader)) == 1)
        if (xmlTextReaderNodeType(reader) == XML_READER_TYPE_ELEMENT) {
            *depth = xmlTextReaderDepth(reader);
            return true;
        }
    return false;
}

bool io_reader_is(xmlTextReaderPtr reader, const char *name)
{
    const xmlChar *local = xmlTextReaderConstLocalName(reader);
    return local && strcmp((const char *)local, name) == 0;
}

/* A copy of the attribute's value cut to size - 1 bytes, or "" when absent; false when absent. */
bool io_reader_attribute(xmlTextReaderPtr reader, const char *name, char *value, size_t size)
{
    xmlChar *text = xmlTextReaderGetAttribute(reader, (const xmlChar *)name);
    value[0] = '\0';
    if (!text)
        return false;
    c_snprintf(value, size, "%s", (const char *)text);
    xmlFree(text);
    return true;
}

/*
 * libxml2's message for a document that is not well formed: a Collada
 * file's line is the file's, as the import's own check says it
 * (mesh_collada.c); a 3MF model's is a line of the model inside the
 * archive.
 */
static ur_status refuse_xml(const io_xml_report *report, const char *path, bool collada,
                            ur_error *error)
{
    if (collada)
        return io_xml_refuse_file(report, path, "Collada", error);
    return ur_error_set(error, UR_ERROR_INPUT, "%s: 3MF model: line %d: %s", path, report->line,
                        report->message);
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
    if (!io_reader_next_element(reader, &depth) || !io_reader_is(reader, "COLLADA"))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s: not a Collada file: its first element is not <COLLADA>", path);
    char meter[64] = "1", name[sizeof unit->name] = "";
    bool in_asset = false;
    while (io_reader_next_element(reader, &depth) && depth >= 1) {
        if (depth == 1) {
            if (in_asset || !io_reader_is(reader, "asset"))
                break; /* the asset comes first: the unit is declared there or nowhere */
            in_asset = true;
        } else if (depth == 2 && io_reader_is(reader, "unit")) {
            if (!io_reader_attribute(reader, "meter", meter, sizeof meter))
                c_snprintf(meter, sizeof meter, "1");
            io_reader_attribute(reader, "name", name, sizeof name);
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

bool io_mesh_may_declare_unit(const char *path)
{
    return io_has_extension(path, "dae") || io_has_extension(path, "3mf");
}

ur_status io_mesh_declared_unit(const char *path, const void *data, size_t size,
                                io_declared_unit *unit, ur_error *error)
{
    *unit = (io_declared_unit){.mm = 0.0, .applied = 1.0};
    if (!io_mesh_may_declare_unit(path))
        return UR_OK;
    bool collada = io_has_extension(path, "dae");
    io_xml_capture capture;
    io_xml_capture_begin(&capture);
    errno = 0;
    ur_status status = collada ? collada_unit_of(path, data, size, unit, error)
                               : io_3mf_unit(path, data, size, unit, error);
    io_xml_capture_end(&capture);
    if (capture.report.have) /* what went wrong first */
        status = refuse_xml(&capture.report, path, collada, error);
    return status;
}
