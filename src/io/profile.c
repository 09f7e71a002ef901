/*
 * profile.c: machine and material profiles: reading them with libxml2,
 * validating them against the RelaxNG schemas and turning them into
 * ur_machine and ur_material (profile_find.c finds and lists them).
 *
 * libxml2 reports problems through callbacks and, left alone, prints them on
 * stderr.  Every call into it here runs with our handlers installed and the
 * caller's restored afterwards (xml_errors.c), so the library stays silent
 * and the first error becomes one "FILE:LINE: message".
 */
#include "unroll/io.h"

#include "io_internal.h"
#include "xml_errors.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <libxml/parser.h>
#include <libxml/relaxng.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include "../base/c_locale.h"

#define PROFILE_PATH_MAX 1024

/* ---- Parsing and validation -------------------------------------------- */

static ur_status validate_with(xmlRelaxNGPtr schema, xmlDocPtr doc, const char *path,
                               ur_error *error)
{
    xmlRelaxNGValidCtxtPtr context = xmlRelaxNGNewValidCtxt(schema);
    if (!context)
        return ur_error_out_of_memory(error);
    io_xml_report report = {0};
    xmlRelaxNGSetValidStructuredErrors(context, io_xml_collect_error, &report);
    int result = xmlRelaxNGValidateDoc(context, doc);
    xmlRelaxNGFreeValidCtxt(context);
    if (result == 0)
        return UR_OK;
    if (result < 0)
        return io_xml_report_error(&report, path, UR_ERROR_INTERNAL, "cannot validate", error);
    return io_xml_report_error(&report, path, UR_ERROR_INPUT, "does not match its schema", error);
}

static ur_status validate_document(xmlDocPtr doc, const char *schema_path, const char *path,
                                   ur_error *error)
{
    io_xml_capture capture;
    io_xml_capture_begin(&capture);
    ur_status status = UR_OK;
    xmlRelaxNGPtr schema = NULL;
    xmlRelaxNGParserCtxtPtr parser = xmlRelaxNGNewParserCtxt(schema_path);
    if (!parser) {
        status = ur_error_out_of_memory(error);
    } else {
        /* The schema's errors come through the parser's handler or the thread's: one report. */
        xmlRelaxNGSetParserStructuredErrors(parser, io_xml_collect_error, &capture.report);
        schema = xmlRelaxNGParse(parser);
        xmlRelaxNGFreeParserCtxt(parser);
        /* A broken schema is a broken installation, not bad user input. */
        if (!schema)
            status = io_xml_report_error(&capture.report, schema_path, UR_ERROR_INTERNAL,
                                         "cannot read the schema", error);
    }
    if (status == UR_OK)
        status = validate_with(schema, doc, path, error);
    xmlRelaxNGFree(schema);
    io_xml_capture_end(&capture);
    return status;
}

ur_status io_xml_load_buffer(const char *const *roots, const char *schema, const char *name,
                             const char *text, size_t size, xmlDocPtr *doc, ur_error *error)
{
    *doc = NULL;
    char schema_path[PROFILE_PATH_MAX];
    ur_status status = profile_find_schema(roots, schema, schema_path, sizeof schema_path, error);
    if (status != UR_OK)
        return status;
    status = io_xml_parse(name, text, size, 0, "cannot parse", doc, error);
    if (status != UR_OK)
        return status;
    status = validate_document(*doc, schema_path, name, error);
    if (status != UR_OK) {
        xmlFreeDoc(*doc);
        *doc = NULL;
    }
    return status;
}

/* The whole of the file at path, after our own checks: libxml2's wording for them is vague. */
static ur_status read_xml_file(const char *path, char **text, size_t *size, ur_error *error)
{
    *text = NULL;
    struct stat info;
    if (stat(path, &info) != 0 || access(path, R_OK) != 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path, strerror(errno));
    if (!S_ISREG(info.st_mode))
        return ur_error_set(error, UR_ERROR_INPUT, "%s: not a regular file", path);
    return io_read_file(path, 0, "", text, size, error);
}

ur_status io_xml_load(const char *const *roots, const char *schema, const char *path,
                      xmlDocPtr *doc, ur_error *error)
{
    *doc = NULL;
    char *text;
    size_t size;
    ur_status status = read_xml_file(path, &text, &size, error);
    if (status == UR_OK)
        status = io_xml_load_buffer(roots, schema, path, text, size, doc, error);
    free(text);
    return status;
}

/* ---- Reading values ---------------------------------------------------- */

/*
 * The schema already guarantees what is checked here; the loader checks
 * again so that a hand-edited schema cannot feed nonsense to the geometry.
 */
typedef struct profile_reader {
    const char *path;
    ur_error *error;
} profile_reader;

typedef struct value_range {
    double low, high;
    bool low_open, high_open;
    const char *wording;
} value_range;

static const value_range positive = {0.0, INFINITY, true, false, "a positive number"};
static const value_range non_negative = {0.0, INFINITY, false, false, "a number >= 0"};
static const value_range strain = {0.0, 1.0, false, true, "a fraction from 0 to below 1"};
static const value_range unit = {0.0, 1.0, false, false, "a fraction from 0 to 1"};
static const value_range tab_angle = {0.0, 90.0, true, false, "an angle above 0 and up to 90"};
static const value_range tolerance = {0.0, 90.0, false, false, "an angle from 0 to 90"};

static ur_status reader_fail(const profile_reader *reader, xmlNodePtr node, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static ur_status reader_fail(const profile_reader *reader, xmlNodePtr node, const char *format, ...)
{
    char message[512];
    va_list args;
    va_start(args, format);
    c_vsnprintf(message, sizeof message, format, args);
    va_end(args);
    long line = node ? xmlGetLineNo(node) : -1;
    if (line > 0)
        return ur_error_set(reader->error, UR_ERROR_INPUT, "%s:%ld: %s", reader->path, line,
                            message);
    return ur_error_set(reader->error, UR_ERROR_INPUT, "%s: %s", reader->path, message);
}

static bool is_element(xmlNodePtr node, const char *name)
{
    return node && node->type == XML_ELEMENT_NODE && xmlStrEqual(node->name, BAD_CAST name);
}

static xmlNodePtr next_element(xmlNodePtr node, const char *name)
{
    while (node && !is_element(node, name))
        node = node->next;
    return node;
}

static ur_status need_element(const profile_reader *reader, xmlNodePtr parent, const char *name,
                              xmlNodePtr *element)
{
    *element = next_element(parent->children, name);
    if (!*element)
        return reader_fail(reader, parent, "<%s> has no <%s>", (const char *)parent->name, name);
    return UR_OK;
}

static bool in_range(double value, const value_range *range)
{
    bool above = range->low_open ? value > range->low : value >= range->low;
    bool below = range->high_open ? value < range->high : value <= range->high;
    return above && below;
}

static ur_status parse_number(const profile_reader *reader, xmlNodePtr node, const char *what,
                              const char *text, const value_range *range, double *value)
{
    while (isspace((unsigned char)*text))
        text++;
    char *end = NULL;
    double parsed = c_strtod(text, &end);
    if (end != text)
        while (isspace((unsigned char)*end))
            end++;
    if (end == text || *end != '\0' || !isfinite(parsed) || !in_range(parsed, range))
        return reader_fail(reader, node, "%s must be %s, not '%.40s'", what, range->wording, text);
    *value = parsed;
    return UR_OK;
}

/* The number in an element's text, e.g. <kerf>0.2</kerf>. */
static ur_status element_number(const profile_reader *reader, xmlNodePtr parent, const char *name,
                                const value_range *range, double *value)
{
    xmlNodePtr element;
    ur_status status = need_element(reader, parent, name, &element);
    if (status != UR_OK)
        return status;
    xmlChar *text = xmlNodeGetContent(element);
    if (!text)
        return ur_error_out_of_memory(reader->error);
    status = parse_number(reader, element, name, (const char *)text, range, value);
    xmlFree(text);
    return status;
}

/* An attribute's number; a missing optional attribute leaves *value alone. */
static ur_status attribute_number(const profile_reader *reader, xmlNodePtr element,
                                  const char *name, bool required, const value_range *range,
                                  double *value)
{
    xmlChar *text = xmlGetProp(element, BAD_CAST name);
    if (!text) {
        if (!required)
            return UR_OK;
        return reader_fail(reader, element, "<%s> has no %s attribute", (const char *)element->name,
                           name);
    }
    char what[128];
    c_snprintf(what, sizeof what, "%s %s", (const char *)element->name, name);
    ur_status status = parse_number(reader, element, what, (const char *)text, range, value);
    xmlFree(text);
    return status;
}

/* Copies text with runs of white space collapsed, so descriptions may wrap. */
static ur_status copy_text(const profile_reader *reader, xmlNodePtr node, const char *what,
                           const char *text, char *out, size_t size)
{
    size_t length = 0;
    bool pending_space = false;
    for (const char *p = text; *p; p++) {
        if (isspace((unsigned char)*p)) {
            pending_space = length > 0;
            continue;
        }
        if (length + (pending_space ? 2 : 1) >= size)
            return reader_fail(reader, node, "%s is longer than %zu bytes", what, size - 1);
        if (pending_space)
            out[length++] = ' ';
        pending_space = false;
        out[length++] = *p;
    }
    out[length] = '\0';
    if (length == 0)
        return reader_fail(reader, node, "%s is empty", what);
    return UR_OK;
}

static ur_status element_text(const profile_reader *reader, xmlNodePtr parent, const char *name,
                              char *out, size_t size)
{
    xmlNodePtr element;
    ur_status status = need_element(reader, parent, name, &element);
    if (status != UR_OK)
        return status;
    xmlChar *text = xmlNodeGetContent(element);
    if (!text)
        return ur_error_out_of_memory(reader->error);
    status = copy_text(reader, element, name, (const char *)text, out, size);
    xmlFree(text);
    return status;
}

static ur_status attribute_text(const profile_reader *reader, xmlNodePtr element, const char *name,
                                char *out, size_t size)
{
    xmlChar *text = xmlGetProp(element, BAD_CAST name);
    if (!text)
        return reader_fail(reader, element, "<%s> has no %s attribute", (const char *)element->name,
                           name);
    ur_status status = copy_text(reader, element, name, (const char *)text, out, size);
    xmlFree(text);
    return status;
}

/*
 * An optional attribute naming one of choices (a NULL-terminated list):
 * *index is its position; a missing attribute leaves *index alone.
 */
static ur_status attribute_choice(const profile_reader *reader, xmlNodePtr element,
                                  const char *name, const char *const *choices, int *index)
{
    if (!xmlHasProp(element, BAD_CAST name))
        return UR_OK;
    char text[32];
    ur_status status = attribute_text(reader, element, name, text, sizeof text);
    if (status != UR_OK)
        return status;
    for (int i = 0; choices[i]; i++)
        if (strcmp(text, choices[i]) == 0) {
            *index = i;
            return UR_OK;
        }
    return reader_fail(reader, element, "%s %s '%s' is not one of the known values",
                       (const char *)element->name, name, text);
}

/* The profile name is the file name without ".xml". */
static ur_status set_identity(const char *path, char *name, size_t name_size, char *source,
                              size_t source_size, ur_error *error)
{
    if (strlen(path) >= source_size)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: path too long", path);
    strcpy(source, path);
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t length = strlen(base);
    if (length > 4 && strcmp(base + length - 4, ".xml") == 0)
        length -= 4;
    if (length == 0 || length >= name_size)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: file name unusable as a profile name",
                            path);
    memcpy(name, base, length);
    name[length] = '\0';
    return UR_OK;
}

/* ---- Machines ---------------------------------------------------------- */

static ur_status read_machine_kind(const profile_reader *reader, xmlNodePtr root,
                                   ur_machine_kind *kind)
{
    char text[16];
    xmlNodePtr element;
    ur_status status = need_element(reader, root, "kind", &element);
    if (status == UR_OK)
        status = element_text(reader, root, "kind", text, sizeof text);
    if (status != UR_OK)
        return status;
    if (strcmp(text, "laser") == 0)
        *kind = UR_MACHINE_LASER;
    else if (strcmp(text, "router") == 0)
        *kind = UR_MACHINE_ROUTER;
    else
        return reader_fail(reader, element, "kind must be 'laser' or 'router', not '%s'", text);
    return UR_OK;
}

static ur_status read_colour(const profile_reader *reader, xmlNodePtr element, char colour[8])
{
    char text[16];
    ur_status status = attribute_text(reader, element, "colour", text, sizeof text);
    if (status != UR_OK)
        return status;
    bool ok = strlen(text) == 7 && text[0] == '#';
    for (int i = 1; ok && i < 7; i++)
        ok = isxdigit((unsigned char)text[i]);
    if (!ok)
        return reader_fail(reader, element, "colour must be #RRGGBB, not '%s'", text);
    /* One spelling, so writers and tests can compare colours as strings. */
    for (int i = 0; i < 8; i++)
        colour[i] = (char)toupper((unsigned char)text[i]);
    return UR_OK;
}

/* An optional dash="3 1.5": positive lengths in mm separated by spaces. */
static ur_status read_dash(const profile_reader *reader, xmlNodePtr element, char *dash,
                           size_t size)
{
    dash[0] = '\0';
    if (!xmlHasProp(element, BAD_CAST "dash"))
        return UR_OK;
    ur_status status = attribute_text(reader, element, "dash", dash, size);
    if (status != UR_OK)
        return status;
    const char *p = dash;
    int lengths = 0;
    while (*p) {
        char *end;
        double length = c_strtod(p, &end);
        if (end == p || !(length > 0) || !isfinite(length) || (*end && *end != ' '))
            return reader_fail(reader, element,
                               "dash must be lengths in mm separated by spaces, not '%s'", dash);
        lengths++;
        p = *end ? end + 1 : end;
    }
    if (lengths == 0)
        return reader_fail(reader, element, "dash is empty");
    return UR_OK;
}

static ur_status read_style(const profile_reader *reader, xmlNodePtr element, ur_op_style *style)
{
    ur_status status = attribute_text(reader, element, "layer", style->layer, sizeof style->layer);
    if (status == UR_OK)
        status = read_colour(reader, element, style->colour);
    if (status == UR_OK)
        status =
            attribute_number(reader, element, "line-width", true, &positive, &style->line_width);
    if (status == UR_OK)
        status = read_dash(reader, element, style->dash, sizeof style->dash);
    return status;
}

/* One <operation> per ur_op, each exactly once. */
static ur_status read_operations(const profile_reader *reader, xmlNodePtr root, ur_machine *machine)
{
    bool seen[UR_OP_COUNT] = {false};
    for (xmlNodePtr node = next_element(root->children, "operation"); node;
         node = next_element(node->next, "operation")) {
        char name[16];
        ur_status status = attribute_text(reader, node, "name", name, sizeof name);
        if (status != UR_OK)
            return status;
        ur_op op = ur_op_from_name(name);
        if (op == UR_OP_COUNT)
            return reader_fail(reader, node, "unknown operation '%s'", name);
        if (seen[op])
            return reader_fail(reader, node, "operation '%s' given twice", name);
        seen[op] = true;
        status = read_style(reader, node, &machine->styles[op]);
        if (status != UR_OK)
            return status;
    }
    for (int op = 0; op < UR_OP_COUNT; op++)
        if (!seen[op])
            return reader_fail(reader, root, "no <operation name=\"%s\">", ur_op_name((ur_op)op));
    return UR_OK;
}

/* <bridge width=".." default="none|auto"/> is optional: defaults by kind. */
static ur_status read_bridges(const profile_reader *reader, xmlNodePtr root, ur_machine *machine)
{
    static const char *const defaults[] = {"none", "auto", NULL};
    bool router = machine->kind == UR_MACHINE_ROUTER;
    machine->bridge_width = router ? 3.0 : 0.5;
    machine->bridges_by_default = router;
    xmlNodePtr bridge = next_element(root->children, "bridge");
    if (!bridge)
        return UR_OK;
    int by_default = machine->bridges_by_default ? 1 : 0;
    ur_status status =
        attribute_number(reader, bridge, "width", false, &positive, &machine->bridge_width);
    if (status == UR_OK)
        status = attribute_choice(reader, bridge, "default", defaults, &by_default);
    machine->bridges_by_default = by_default == 1;
    return status;
}

static ur_status read_machine_fields(const profile_reader *reader, xmlNodePtr root,
                                     ur_machine *machine)
{
    xmlNodePtr bed, speed;
    ur_status status = element_text(reader, root, "description", machine->description,
                                    sizeof machine->description);
    if (status == UR_OK)
        status = read_machine_kind(reader, root, &machine->kind);
    if (status == UR_OK)
        status = need_element(reader, root, "bed", &bed);
    if (status == UR_OK)
        status = attribute_number(reader, bed, "width", true, &positive, &machine->bed_width);
    if (status == UR_OK)
        status = attribute_number(reader, bed, "height", true, &positive, &machine->bed_height);
    if (status == UR_OK)
        status = element_number(reader, root, "kerf", &positive, &machine->kerf);
    if (status == UR_OK)
        status = element_number(reader, root, "margin", &non_negative, &machine->margin);
    if (status == UR_OK)
        status = element_number(reader, root, "spacing", &non_negative, &machine->spacing);
    if (status == UR_OK)
        status = need_element(reader, root, "speed", &speed);
    if (status == UR_OK)
        status = attribute_number(reader, speed, "cut", true, &positive, &machine->cut_speed);
    if (status == UR_OK)
        status = attribute_number(reader, speed, "travel", true, &positive, &machine->travel_speed);
    if (status == UR_OK)
        status = read_operations(reader, root, machine);
    if (status == UR_OK)
        status = read_bridges(reader, root, machine);
    return status;
}

/* Fills one kind of profile from its root element. */
typedef ur_status (*field_reader)(const profile_reader *reader, xmlNodePtr root, void *profile);

static ur_status machine_fields(const profile_reader *reader, xmlNodePtr root, void *profile)
{
    return read_machine_fields(reader, root, profile);
}

/*
 * What machine and material reading share: name and source from the name
 * of the file (or buffer), the parsed and validated document, its root
 * element, then the kind's own fields.
 */
static ur_status read_profile(const char *const *roots, ur_profile_kind kind, const char *path,
                              const void *data, size_t size, char *name, size_t name_size,
                              char *source, size_t source_size, field_reader read_fields,
                              void *profile, ur_error *error)
{
    ur_status status = set_identity(path, name, name_size, source, source_size, error);
    if (status != UR_OK)
        return status;
    xmlDocPtr doc = NULL;
    status = io_xml_load_buffer(roots, profile_kind_word(kind), path, data, size, &doc, error);
    if (status != UR_OK)
        return status;
    const char *root_name = kind == UR_PROFILE_MACHINE ? "machine" : "material";
    profile_reader reader = {path, error};
    xmlNodePtr root = xmlDocGetRootElement(doc);
    if (!is_element(root, root_name))
        status = reader_fail(&reader, root, "not a <%s> profile", root_name);
    else
        status = read_fields(&reader, root, profile);
    xmlFreeDoc(doc);
    return status;
}

ur_status ur_machine_read_buffer(const char *const *roots, const char *name, const void *data,
                                 size_t size, ur_machine *machine, ur_error *error)
{
    memset(machine, 0, sizeof *machine);
    return read_profile(roots, UR_PROFILE_MACHINE, name, data, size, machine->name,
                        sizeof machine->name, machine->source, sizeof machine->source,
                        machine_fields, machine, error);
}

ur_status ur_machine_read(const char *const *roots, const char *path, ur_machine *machine,
                          ur_error *error)
{
    memset(machine, 0, sizeof *machine);
    char *text;
    size_t size;
    ur_status status = read_xml_file(path, &text, &size, error);
    if (status == UR_OK)
        status = ur_machine_read_buffer(roots, path, text, size, machine, error);
    free(text);
    return status;
}

/* ---- Materials --------------------------------------------------------- */

static ur_status read_stock(const profile_reader *reader, xmlNodePtr root, ur_material *material)
{
    for (xmlNodePtr node = next_element(root->children, "stock"); node;
         node = next_element(node->next, "stock")) {
        if (material->stock_count == UR_MAX_STOCK_SIZES)
            return reader_fail(reader, node, "more than %d stock sizes", UR_MAX_STOCK_SIZES);
        ur_sheet_size *size = &material->stock[material->stock_count];
        ur_status status = attribute_number(reader, node, "width", true, &positive, &size->width);
        if (status == UR_OK)
            status = attribute_number(reader, node, "height", true, &positive, &size->height);
        if (status != UR_OK)
            return status;
        material->stock_count++;
    }
    if (material->stock_count == 0)
        return reader_fail(reader, root, "no <stock> size");
    return UR_OK;
}

/* <kerf laser=".." router=".."/> is optional, and so is each attribute. */
static ur_status read_material_kerf(const profile_reader *reader, xmlNodePtr root,
                                    ur_material *material)
{
    xmlNodePtr kerf = next_element(root->children, "kerf");
    if (!kerf)
        return UR_OK;
    ur_status status =
        attribute_number(reader, kerf, "laser", false, &positive, &material->kerf_laser);
    if (status == UR_OK)
        status = attribute_number(reader, kerf, "router", false, &positive, &material->kerf_router);
    return status;
}

static ur_status read_grain(const profile_reader *reader, xmlNodePtr root, ur_material *material)
{
    xmlNodePtr grain;
    char rule[16];
    ur_status status = need_element(reader, root, "grain", &grain);
    if (status == UR_OK)
        status = attribute_text(reader, grain, "rule", rule, sizeof rule);
    if (status != UR_OK)
        return status;
    if (strcmp(rule, "none") == 0)
        material->grain = UR_GRAIN_NONE;
    else if (strcmp(rule, "along") == 0)
        material->grain = UR_GRAIN_ALONG;
    else if (strcmp(rule, "across") == 0)
        material->grain = UR_GRAIN_ACROSS;
    else
        return reader_fail(reader, grain, "grain rule must be none, along or across, not '%s'",
                           rule);
    /* A tolerance only means something when there is a rule to keep. */
    bool required = material->grain != UR_GRAIN_NONE;
    return attribute_number(reader, grain, "tolerance", required, &tolerance,
                            &material->grain_tolerance);
}

static ur_status read_bending(const profile_reader *reader, xmlNodePtr root, ur_material *material)
{
    xmlNodePtr radius, strain_element;
    ur_status status = need_element(reader, root, "bend-radius", &radius);
    if (status == UR_OK)
        status = attribute_number(reader, radius, "with-grain", true, &positive,
                                  &material->bend_radius_with_grain);
    if (status == UR_OK)
        status = attribute_number(reader, radius, "across-grain", true, &positive,
                                  &material->bend_radius_across_grain);
    if (status == UR_OK)
        status = need_element(reader, root, "strain", &strain_element);
    if (status == UR_OK)
        status = attribute_number(reader, strain_element, "stretch", true, &strain,
                                  &material->max_stretch);
    if (status == UR_OK)
        status = attribute_number(reader, strain_element, "compression", true, &strain,
                                  &material->max_compression);
    if (status == UR_OK)
        status = element_number(reader, root, "k-factor", &unit, &material->k_factor);
    return status;
}

static ur_status read_tab_and_hinge(const profile_reader *reader, xmlNodePtr root,
                                    ur_material *material)
{
    xmlNodePtr tab, hinge;
    ur_status status = need_element(reader, root, "tab", &tab);
    if (status == UR_OK)
        status = attribute_number(reader, tab, "depth", true, &positive, &material->tab_depth);
    if (status == UR_OK)
        status = attribute_number(reader, tab, "angle", true, &tab_angle, &material->tab_angle);
    if (status == UR_OK)
        status = need_element(reader, root, "living-hinge", &hinge);
    if (status == UR_OK)
        status = attribute_number(reader, hinge, "cut-length", true, &positive,
                                  &material->hinge_cut_length);
    if (status == UR_OK)
        status = attribute_number(reader, hinge, "connection", true, &positive,
                                  &material->hinge_connection);
    if (status == UR_OK)
        status =
            attribute_number(reader, hinge, "distance", true, &positive, &material->hinge_distance);
    return status;
}

static const char *const surface_layer_names[] = {"neutral", "outer", "inner", "mid", NULL};

const char *ur_surface_layer_name(ur_surface_layer layer)
{
    return (unsigned)layer < 4 ? surface_layer_names[layer] : "?";
}

int ur_surface_layer_from_name(const char *name)
{
    for (int i = 0; surface_layer_names[i]; i++)
        if (strcmp(name, surface_layer_names[i]) == 0)
            return i;
    return -1;
}

/* From the inner face: the neutral layer at K t, the mid layer at t / 2, the outer face at t. */
double ur_surface_layer_offset(ur_surface_layer layer, double thickness, double k_factor)
{
    double from_inner = layer == UR_LAYER_OUTER ? 1.0 : layer == UR_LAYER_MID ? 0.5 : 0.0;
    return layer == UR_LAYER_NEUTRAL ? 0.0 : (from_inner - k_factor) * thickness;
}

static void allowance_defaults(ur_material *material)
{
    material->joint = UR_JOINT_TAB;
    material->lap_width = material->tab_depth;
    material->label_height = 4.0;
    material->kerfing_opening = 0.5;
    material->kerfing_margin = 3.0;
    material->overlap = UR_OVERLAP_SLIT;
    material->groove_skin = material->thickness / 3.0;
    material->facet_angle = UR_DEFAULT_FACET_ANGLE;
    material->min_web = 0.0;
    material->surface_layer = UR_LAYER_NEUTRAL;
}

/* An optional element's optional number attribute. */
static ur_status optional_number(const profile_reader *reader, xmlNodePtr root,
                                 const char *element_name, const char *name, double *value)
{
    xmlNodePtr element = next_element(root->children, element_name);
    if (!element)
        return UR_OK;
    return attribute_number(reader, element, name, false, &positive, value);
}

/* An optional element's optional choice attribute. */
static ur_status optional_choice(const profile_reader *reader, xmlNodePtr root,
                                 const char *element_name, const char *name,
                                 const char *const *choices, int *index)
{
    xmlNodePtr element = next_element(root->children, element_name);
    if (!element)
        return UR_OK;
    return attribute_choice(reader, element, name, choices, index);
}

/* <joint>, <label>, <kerfing>, <overlap>, <groove>, <bending>, <surface>: all optional. */
static ur_status read_allowances(const profile_reader *reader, xmlNodePtr root,
                                 ur_material *material)
{
    static const char *const joints[] = {"tab", "lap", NULL};
    static const char *const overlaps[] = {"slit", "dart", NULL};
    allowance_defaults(material);
    int joint = (int)material->joint, overlap = (int)material->overlap,
        layer = (int)material->surface_layer;
    ur_status status = optional_choice(reader, root, "joint", "type", joints, &joint);
    if (status == UR_OK)
        status = optional_number(reader, root, "joint", "lap-width", &material->lap_width);
    if (status == UR_OK)
        status = optional_number(reader, root, "label", "height", &material->label_height);
    if (status == UR_OK)
        status = optional_number(reader, root, "kerfing", "opening", &material->kerfing_opening);
    if (status == UR_OK)
        status = optional_number(reader, root, "kerfing", "margin", &material->kerfing_margin);
    if (status == UR_OK)
        status = optional_choice(reader, root, "overlap", "style", overlaps, &overlap);
    if (status == UR_OK)
        status = optional_number(reader, root, "groove", "skin", &material->groove_skin);
    if (status == UR_OK)
        status = optional_number(reader, root, "bending", "facet-angle", &material->facet_angle);
    if (status == UR_OK)
        status = optional_number(reader, root, "bending", "min-web", &material->min_web);
    if (status == UR_OK)
        status = optional_choice(reader, root, "surface", "layer", surface_layer_names, &layer);
    material->joint = (ur_joint_kind)joint;
    material->overlap = (ur_overlap_style)overlap;
    material->surface_layer = (ur_surface_layer)layer;
    if (status == UR_OK && material->facet_angle > 90)
        status = reader_fail(reader, next_element(root->children, "bending"),
                             "facet angle %g degrees: a groove or hinge row turns the sheet by "
                             "more than 0 and at most 90 degrees",
                             material->facet_angle);
    if (status == UR_OK && material->groove_skin >= material->thickness)
        status = reader_fail(reader, next_element(root->children, "groove"),
                             "groove skin %g mm leaves no groove in %g mm stock",
                             material->groove_skin, material->thickness);
    return status;
}

static ur_status read_material_fields(const profile_reader *reader, xmlNodePtr root,
                                      ur_material *material)
{
    ur_status status = element_text(reader, root, "description", material->description,
                                    sizeof material->description);
    if (status == UR_OK)
        status = element_number(reader, root, "thickness", &positive, &material->thickness);
    if (status == UR_OK)
        status = read_stock(reader, root, material);
    if (status == UR_OK)
        status = read_material_kerf(reader, root, material);
    if (status == UR_OK)
        status = read_bending(reader, root, material);
    if (status == UR_OK)
        status = read_tab_and_hinge(reader, root, material);
    if (status == UR_OK)
        status = read_grain(reader, root, material);
    if (status == UR_OK)
        status = read_allowances(reader, root, material);
    return status;
}

static ur_status material_fields(const profile_reader *reader, xmlNodePtr root, void *profile)
{
    return read_material_fields(reader, root, profile);
}

ur_status ur_material_read_buffer(const char *const *roots, const char *name, const void *data,
                                  size_t size, ur_material *material, ur_error *error)
{
    memset(material, 0, sizeof *material);
    return read_profile(roots, UR_PROFILE_MATERIAL, name, data, size, material->name,
                        sizeof material->name, material->source, sizeof material->source,
                        material_fields, material, error);
}

ur_status ur_material_read(const char *const *roots, const char *path, ur_material *material,
                           ur_error *error)
{
    memset(material, 0, sizeof *material);
    char *text;
    size_t size;
    ur_status status = read_xml_file(path, &text, &size, error);
    if (status == UR_OK)
        status = ur_material_read_buffer(roots, path, text, size, material, error);
    free(text);
    return status;
}
