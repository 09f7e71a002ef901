/*
 * svg_use.c: use elements, which draw a copy of the element or symbol
 * they name ("#id"): its place, a symbol's viewBox scaled to the use's
 * size, and the refusals of a use that points at itself, at nothing or
 * outside the file.
 */
#include "svg_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/tree.h>

#include "../base/c_locale.h"

/* ---- use and symbol --------------------------------------------------------- */

/* The first element of the document, in document order, whose id is id. */
static xmlNodePtr element_by_id(xmlNodePtr node, const char *id)
{
    for (; node; node = node->next) {
        if (node->type != XML_ELEMENT_NODE)
            continue;
        char *own = svg_attribute(node, "id");
        bool found = own && strcmp(own, id) == 0;
        xmlFree(own);
        if (found)
            return node;
        xmlNodePtr inside = element_by_id(node->children, id);
        if (inside)
            return inside;
    }
    return NULL;
}

/* Whether drawing target from this use would draw the use again: a loop. */
static bool loops(const svg_element *element, xmlNodePtr target)
{
    for (xmlNodePtr node = element->node; node; node = node->parent)
        if (node == target)
            return true; /* the use itself, or a group that holds it */
    const svg_reader *reader = element->reader;
    for (size_t i = 0; i < reader->using_count; i++)
        if (reader->using[i] == target)
            return true;
    return false;
}

/* The element href (or xlink:href) names as "#id"; a message when it names none. */
static ur_status use_target(svg_element *element, xmlNodePtr *target, ur_error *error)
{
    char *href = svg_attribute(element->node, "href"); /* xlink:href too: any namespace */
    char message[160];
    *target = NULL;
    if (!href)
        c_snprintf(message, sizeof message, "no href: the use points at nothing");
    else if (href[0] != '#')
        c_snprintf(message, sizeof message,
                   "href=\"%.*s\" points outside the file: only \"#id\" is read", SVG_QUOTE_MAX,
                   href);
    else if ((*target = element_by_id(xmlDocGetRootElement(element->node->doc), href + 1)) == NULL)
        c_snprintf(message, sizeof message, "href=\"%.*s\" points at no element of the file",
                   SVG_QUOTE_MAX, href);
    else if (loops(element, *target))
        c_snprintf(message, sizeof message,
                   "href=\"%.*s\" refers to itself (directly or through other uses)", SVG_QUOTE_MAX,
                   href);
    else
        message[0] = '\0';
    xmlFree(href);
    return message[0] ? svg_element_error(element, error, message) : UR_OK;
}

/*
 * A symbol's viewport: with a viewBox and a size (the use's width and
 * height, else the symbol's own), the viewBox scaled into it as a nested
 * svg's is; without, its user units are the use's.
 */
static ur_status symbol_viewport(svg_element *use, svg_element *symbol, parts_matrix *viewport,
                                 ur_error *error)
{
    double size[2], own[2];
    svg_viewbox box;
    static const char *const names[] = {"width", "height", NULL};
    ur_status status = svg_lengths(use, names, size, error);
    if (status == UR_OK)
        status = svg_lengths(symbol, names, own, error);
    if (status == UR_OK)
        status = svg_read_viewbox(symbol, &box, error);
    *viewport = parts_identity;
    double width = size[0] > 0 ? size[0] : own[0], height = size[1] > 0 ? size[1] : own[1];
    if (status == UR_OK && box.given && width > 0 && height > 0) {
        double s = fmin(width / box.width, height / box.height);
        *viewport = (parts_matrix){s, 0, 0, s, -s * box.x, -s * box.y};
    }
    return status;
}

/* Draws what the use points at, moved by its x and y (after its transform). */
static ur_status draw_target(svg_element *element, xmlNodePtr target, int depth, ur_error *error)
{
    static const char *const names[] = {"x", "y", NULL};
    double at[2];
    ur_status status = svg_lengths(element, names, at, error);
    if (status != UR_OK)
        return status;
    parts_matrix moved =
        parts_matrix_multiply(element->matrix, (parts_matrix){1, 0, 0, 1, at[0], at[1]});
    svg_reader *reader = element->reader;
    svg_element drawn;
    status = svg_element_begin(&drawn, reader, target, moved, error);
    if (status != UR_OK || svg_hidden(target))
        return status;
    if (!svg_named(target, "symbol"))
        return svg_read_shape(&drawn, depth + 1, error);
    parts_matrix viewport;
    status = symbol_viewport(element, &drawn, &viewport, error);
    if (status == UR_OK)
        status = svg_walk(reader, target, parts_matrix_multiply(drawn.matrix, viewport), depth + 1,
                          error);
    return status;
}

/* use: a copy of another element (a symbol, a group, a shape) drawn here. */
ur_status svg_read_use(svg_element *element, int depth, ur_error *error)
{
    svg_reader *reader = element->reader;
    xmlNodePtr target = NULL;
    ur_status status = use_target(element, &target, error);
    if (status != UR_OK)
        return status;
    if (reader->using_count == PARTS_MAX_DEPTH)
        return svg_element_error(element, error, "uses nest too deep");
    reader->using[reader->using_count++] = target;
    status = draw_target(element, target, depth, error);
    reader->using_count--;
    return status;
}
