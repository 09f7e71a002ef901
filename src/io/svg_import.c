/*
 * svg_import.c: the closed shapes of an SVG drawing as rings in millimetres,
 * y up, for parts_import.c to sort into parts and holes: the document
 * walk, from the root's units through groups to each shape (svg_internal.h
 * names the files that read the rest).
 *
 * libxml2 reads the file without network access and without substituting
 * entities; its messages are collected (never printed, xml_errors.c) and
 * the first becomes "FILE:LINE: message".  The walk keeps the transform from user
 * units to millimetres (the root's size and viewBox, every g's and the
 * element's own transform) and flattens curves in the element's own
 * coordinates with the tolerance scaled by how much that transform can
 * stretch, so the flattened curve is within tolerance once in millimetres.
 */
#include "svg_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/parser.h>
#include <libxml/tree.h>

#include "xml_errors.h"
#include "../base/c_locale.h"

/* ---- Reading state ------------------------------------------------------ */

ur_status svg_element_error(const svg_element *element, ur_error *error, const char *message)
{
    return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: %s: %s", element->reader->path,
                        element->line, element->what, message);
}

/*
 * Transforms the points to mm and hands them over as a ring.  circle (user
 * units, NULL for none) is the circle the ring exactly is; it stays one
 * only under a transform that keeps circles circles.
 */
ur_status svg_element_ring(svg_element *element, parts_points *points, const ur_path_circle *circle,
                           ur_error *error)
{
    for (size_t i = 0; i < points->count; i++)
        points->items[i] = parts_matrix_apply(element->matrix, points->items[i]);
    ur_path_circle in_mm = {{0, 0}, 0, 0};
    double scale = circle ? parts_matrix_similarity_scale(element->matrix) : 0;
    if (scale > 0) {
        in_mm.centre = parts_matrix_apply(element->matrix, circle->centre);
        in_mm.radius = circle->radius * scale;
    }
    if (element->reader->op != UR_OP_CUT)
        return parts_add_line(element->reader->collection, points, true, element->reader->op,
                              element->line, element->what, error);
    element->sub++;
    return parts_add_ring(element->reader->collection, points, element->line, element->what,
                          element->id, element->sub, in_mm.radius > 0 ? &in_mm : NULL, error);
}

/* An open shape, in mm: it goes with the part that holds it, or is left out. */
ur_status svg_element_line(svg_element *element, parts_points *points, ur_error *error)
{
    for (size_t i = 0; i < points->count; i++)
        points->items[i] = parts_matrix_apply(element->matrix, points->items[i]);
    return parts_add_line(element->reader->collection, points, false, element->reader->op,
                          element->line, element->what, error);
}

/* ---- The document tree ------------------------------------------------------ */

bool svg_named(xmlNodePtr node, const char *name)
{
    return strcmp((const char *)node->name, name) == 0;
}

static bool named_any(xmlNodePtr node, const char *const *names)
{
    for (size_t i = 0; names[i]; i++)
        if (svg_named(node, names[i]))
            return true;
    return false;
}

/* SVG elements, or elements of a file that declares no namespace at all. */
static bool svg_element_node(xmlNodePtr node)
{
    return node->type == XML_ELEMENT_NODE &&
           (!node->ns || !node->ns->href ||
            strcmp((const char *)node->ns->href, SVG_NAMESPACE) == 0);
}

/* display="none" or style="...display:none...": Inkscape's hidden layers. */
bool svg_hidden(xmlNodePtr node)
{
    char *display = svg_attribute(node, "display");
    bool none = display && strcmp(display, "none") == 0;
    xmlFree(display);
    char *style = svg_attribute(node, "style");
    if (style && !none) {
        /* Squeezed in place: "display : none" says the same. */
        size_t n = 0;
        for (const char *p = style; *p; p++)
            if (!isspace((unsigned char)*p))
                style[n++] = *p;
        style[n] = '\0';
        none = strstr(style, "display:none") != NULL;
    }
    xmlFree(style);
    return none;
}

static void describe(svg_element *element)
{
    char *id = svg_attribute(element->node, "id");
    /* A copy drawn through use is no longer the element of that id: its parts are numbered. */
    bool copy = element->reader && element->reader->using_count > 0;
    c_snprintf(element->id, sizeof element->id, "%s", id && !copy ? id : "");
    if (id)
        c_snprintf(element->what, sizeof element->what, "%s id=\"%.40s\"",
                   (const char *)element->node->name, id);
    else
        c_snprintf(element->what, sizeof element->what, "%s", (const char *)element->node->name);
    xmlFree(id);
    long line = xmlGetLineNo(element->node);
    element->line = line > 0 && line < 1000000000 ? (int)line : 0;
}

/* Starts the element: who it is, and its user units to mm. */
ur_status svg_element_begin(svg_element *element, svg_reader *reader, xmlNodePtr node,
                            parts_matrix parent, ur_error *error)
{
    memset(element, 0, sizeof *element);
    element->reader = reader;
    element->node = node;
    describe(element);
    parts_matrix own;
    ur_status status = svg_parse_transform(element, &own, error);
    element->matrix = parts_matrix_multiply(parent, own);
    double stretch = parts_matrix_stretch(element->matrix);
    element->tolerance =
        stretch > 0 ? reader->collection->tolerance / stretch : reader->collection->tolerance;
    if (status == UR_OK && reader->using_count > 0 && ++reader->used > SVG_MAX_USED_ELEMENTS)
        status = svg_element_error(element, error,
                                   "more than 100000 elements drawn through use: not a drawing of "
                                   "parts");
    return status;
}

ur_status svg_read_viewbox(svg_element *element, svg_viewbox *box, ur_error *error)
{
    memset(box, 0, sizeof *box);
    char *text = svg_attribute(element->node, "viewBox");
    if (!text)
        return UR_OK;
    svg_scanner scanner = {text};
    bool good = svg_scan_number(&scanner, &box->x) && svg_scan_number(&scanner, &box->y) &&
                svg_scan_number(&scanner, &box->width) && svg_scan_number(&scanner, &box->height) &&
                svg_at_end(&scanner) && box->width > 0 && box->height > 0;
    ur_status status = UR_OK;
    if (!good) {
        char message[128];
        c_snprintf(message, sizeof message,
                   "viewBox=\"%.*s\" is not four numbers with a positive width and height",
                   SVG_QUOTE_MAX, text);
        status = svg_element_error(element, error, message);
    }
    box->given = good;
    xmlFree(text);
    return status;
}

/* A nested svg: its x, y and, with a viewBox and a size, the viewBox's scale. */
static ur_status read_nested_svg(svg_element *element, int depth, ur_error *error)
{
    static const char *const names[] = {"x", "y", "width", "height", NULL};
    double v[4];
    svg_viewbox box;
    ur_status status = svg_lengths(element, names, v, error);
    if (status == UR_OK)
        status = svg_read_viewbox(element, &box, error);
    if (status != UR_OK)
        return status;
    parts_matrix viewport = {1, 0, 0, 1, v[0], v[1]};
    if (box.given && v[2] > 0 && v[3] > 0) {
        double s = fmin(v[2] / box.width, v[3] / box.height);
        viewport = (parts_matrix){s, 0, 0, s, v[0] - s * box.x, v[1] - s * box.y};
    }
    return svg_walk(element->reader, element->node,
                    parts_matrix_multiply(element->matrix, viewport), depth + 1, error);
}

/*
 * What a group's id or Inkscape label says its paths are (unroll writes
 * each operation as a group named after it, "score", "engrave" ...);
 * inherited when it names none.
 */
static ur_op group_op(xmlNodePtr node, ur_op inherited)
{
    static const char *const names[] = {"label", "id"};
    for (size_t i = 0; i < 2; i++) {
        char *name = svg_attribute(node, names[i]);
        ur_op op = name ? parts_layer_op(name) : UR_OP_COUNT;
        xmlFree(name);
        if (op != UR_OP_COUNT)
            return op;
    }
    return inherited;
}

/* Elements that hold no shape to cut, or only shapes used by reference. */
static const char *const skipped[] = {"defs",
                                      "clipPath",
                                      "mask",
                                      "marker",
                                      "pattern",
                                      "symbol",
                                      "metadata",
                                      "title",
                                      "desc",
                                      "style",
                                      "script",
                                      "linearGradient",
                                      "radialGradient",
                                      "filter",
                                      "foreignObject",
                                      "animate",
                                      "animateTransform",
                                      "set",
                                      NULL};

/* Shapes that are not outlines: left out with a warning. */
static const char *const not_outlines[] = {"text", "image", NULL};

ur_status svg_read_shape(svg_element *element, int depth, ur_error *error)
{
    xmlNodePtr node = element->node;
    if (svg_named(node, "g") || svg_named(node, "a") || svg_named(node, "switch")) {
        if (depth >= PARTS_MAX_DEPTH)
            return svg_element_error(element, error, "groups nest too deep");
        svg_reader *reader = element->reader;
        ur_op outer = reader->op;
        reader->op = group_op(node, outer);
        ur_status status = svg_walk(reader, node, element->matrix, depth + 1, error);
        reader->op = outer;
        return status;
    }
    if (svg_named(node, "svg"))
        return depth >= PARTS_MAX_DEPTH ? svg_element_error(element, error, "groups nest too deep")
                                        : read_nested_svg(element, depth, error);
    if (svg_named(node, "path"))
        return svg_read_path(element, error);
    if (svg_named(node, "rect"))
        return svg_read_rect(element, error);
    if (svg_named(node, "circle") || svg_named(node, "ellipse"))
        return svg_read_ellipse(element, svg_named(node, "circle"), error);
    if (svg_named(node, "polygon") || svg_named(node, "polyline"))
        return svg_read_poly(element, svg_named(node, "polygon"), error);
    if (svg_named(node, "line"))
        return svg_read_line(element, error);
    if (svg_named(node, "use"))
        return depth >= PARTS_MAX_DEPTH ? svg_element_error(element, error, "groups nest too deep")
                                        : svg_read_use(element, depth, error);
    return UR_OK; /* other SVG elements draw nothing to cut */
}

ur_status svg_walk(svg_reader *reader, xmlNodePtr parent, parts_matrix matrix, int depth,
                   ur_error *error)
{
    for (xmlNodePtr node = parent->children; node; node = node->next) {
        if (!svg_element_node(node) || named_any(node, skipped) || svg_hidden(node))
            continue;
        svg_element element;
        ur_status status = svg_element_begin(&element, reader, node, matrix, error);
        if (status == UR_OK && named_any(node, not_outlines))
            status = parts_warn(reader->collection, error, "%s:%d: %s: left out: not a shape",
                                reader->path, element.line, element.what);
        else if (status == UR_OK)
            status = svg_read_shape(&element, depth, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* ---- The root: units ---------------------------------------------------------- */

/* The root's width or height: given at all, in a physical unit, how many mm. */
typedef struct svg_size {
    bool given, physical;
    double value, mm;
} svg_size;

static ur_status root_size(svg_element *root, const char *name, svg_size *size, ur_error *error)
{
    memset(size, 0, sizeof *size);
    char *text = svg_attribute(root->node, name);
    if (!text)
        return UR_OK;
    char unit[8] = "";
    bool good = svg_parse_length_text(text, &size->value, unit, sizeof unit) && size->value > 0;
    double mm = good ? ur_parts_unit_mm(unit) : 0;
    if (good && strcmp(unit, "%") == 0) {
        xmlFree(text);
        return UR_OK; /* relative to a window: says nothing about size */
    }
    good = good && (unit[0] == '\0' || (mm > 0 && strcmp(unit, "m") != 0 && strcmp(unit, "ft")));
    ur_status status = UR_OK;
    if (good) {
        size->given = true;
        size->physical = unit[0] != '\0';
        size->mm = size->value * mm;
    } else {
        char message[160];
        c_snprintf(message, sizeof message,
                   "%s=\"%.*s\" is not a positive length in mm, cm, in, pt, pc or px", name,
                   SVG_QUOTE_MAX, text);
        status = svg_element_error(root, error, message);
    }
    xmlFree(text);
    return status;
}

/*
 * mm per user unit along one axis, 0 when the file does not say and no
 * unit was given.  Without a viewBox user units are CSS px whatever unit
 * the size is in; a size without a unit is in the caller's unit.
 */
static double axis_scale(const svg_size *size, bool has_box, double box_extent, double unit)
{
    if (size->physical)
        return has_box ? size->mm / box_extent : 25.4 / 96;
    if (unit <= 0)
        return 0;
    return has_box && size->given ? size->value * unit / box_extent : unit;
}

static ur_status root_matrix(svg_element *root, parts_matrix *matrix, ur_error *error)
{
    svg_size width, height;
    svg_viewbox box;
    ur_status status = root_size(root, "width", &width, error);
    if (status == UR_OK)
        status = root_size(root, "height", &height, error);
    if (status == UR_OK)
        status = svg_read_viewbox(root, &box, error);
    if (status != UR_OK)
        return status;
    double unit = root->reader->collection->unit;
    double sx = axis_scale(&width, box.given, box.width, unit);
    double sy = axis_scale(&height, box.given, box.height, unit);
    if (!width.physical && !height.physical && unit <= 0) {
        svg_element_error(root, error,
                          "the drawing gives no physical size (width and height in mm, cm, in, pt, "
                          "pc or px): give its unit with units");
        return ur_error_set_setting(error, "units");
    }
    double s = width.physical && height.physical ? fmin(sx, sy) : width.physical ? sx : sy;
    if (!width.physical && !height.physical)
        s = width.given ? sx : sy;
    /* y up: measured from the bottom of the viewBox, or of the page. */
    double bottom = box.given      ? box.y + box.height
                    : height.given ? (height.physical ? height.mm / s : height.value)
                                   : 0;
    double left = box.given ? box.x : 0;
    *matrix = (parts_matrix){s, 0, 0, -s, -s * left, s * bottom};
    return UR_OK;
}

/*
 * The kerf an SVG's metadata says its cut paths were compensated for: a
 * Dublin Core description holding UR_KERF_NOTE (unroll writes it in
 * rdf:RDF / rdf:Description; another program may move it, as Inkscape's
 * own metadata goes in a cc:Work), at most depth elements down.
 */
static bool find_kerf_note(xmlNodePtr node, int depth, double *kerf)
{
    for (xmlNodePtr child = node->children; child && depth > 0; child = child->next) {
        if (child->type != XML_ELEMENT_NODE) /* RDF's and Dublin Core's, not SVG's */
            continue;
        if (svg_named(child, "description") && child->ns &&
            xmlStrEqual(child->ns->href, BAD_CAST DC_NAMESPACE)) {
            xmlChar *text = xmlNodeGetContent(child);
            bool found = text && parts_read_kerf_note((const char *)text, kerf);
            xmlFree(text);
            if (found)
                return true;
        } else if (find_kerf_note(child, depth - 1, kerf))
            return true;
    }
    return false;
}

static void read_kerf_note(svg_reader *reader, xmlNodePtr root)
{
    for (xmlNodePtr child = root->children; child; child = child->next)
        if (svg_element_node(child) && svg_named(child, "metadata") &&
            find_kerf_note(child, 4, &reader->collection->kerf_compensated))
            return;
}

static ur_status read_root(svg_reader *reader, xmlNodePtr node, ur_error *error)
{
    svg_element root;
    memset(&root, 0, sizeof root);
    root.reader = reader;
    root.node = node;
    describe(&root);
    if (!node || !svg_element_node(node) || !svg_named(node, "svg"))
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: the root element is %s, not svg",
                            reader->path, root.line, node ? (const char *)node->name : "missing");
    parts_matrix base = parts_identity, own = parts_identity;
    ur_status status = root_matrix(&root, &base, error);
    if (status == UR_OK)
        status = svg_parse_transform(&root, &own, error);
    if (status == UR_OK)
        status = svg_walk(reader, node, parts_matrix_multiply(base, own), 0, error);
    if (status == UR_OK)
        read_kerf_note(reader, node);
    return status;
}

ur_status parts_read_svg(parts_collection *collection, ur_error *error)
{
    xmlDocPtr doc = NULL;
    ur_status status = io_xml_parse(collection->path, collection->text, collection->size,
                                    XML_PARSE_BIG_LINES, "cannot parse as XML", &doc, error);
    if (status != UR_OK)
        return status;
    svg_reader reader = {.collection = collection, .path = collection->path, .op = UR_OP_CUT};
    status = read_root(&reader, xmlDocGetRootElement(doc), error);
    xmlFreeDoc(doc);
    return status;
}
