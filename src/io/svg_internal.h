/*
 * svg_internal.h: what the files of the SVG importer share (svg_import.c,
 * svg_values.c, svg_path.c, svg_shapes.c, svg_use.c), private to src/io.
 *
 * svg_import.c walks the document from the root (its units and viewBox)
 * through groups and nested svg elements to the shapes; svg_values.c reads
 * numbers, lengths and transforms from attribute text; svg_path.c a path's
 * d attribute; svg_shapes.c the basic shapes; svg_use.c use elements and
 * the symbols they draw.  Every shape ends as rings and lines handed to
 * parts_import.c (parts_internal.h) in millimetres, y up.
 */
#ifndef UNROLL_IO_SVG_INTERNAL_H
#define UNROLL_IO_SVG_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>

#include <libxml/tree.h>

#include "parts_internal.h"

#define SVG_NAMESPACE "http://www.w3.org/2000/svg"
/* Dublin Core, whose description in the metadata holds unroll's kerf note. */
#define DC_NAMESPACE "http://purl.org/dc/elements/1.1/"

/* Longest piece of attribute text quoted back in a message. */
#define SVG_QUOTE_MAX 24

/* Elements a file may draw through use (copies of copies multiply): more is a runaway. */
#define SVG_MAX_USED_ELEMENTS 100000

typedef struct svg_reader {
    parts_collection *collection;
    const char *path;
    ur_op op; /* what the enclosing layer (group) says its paths are: cut unless it names another */
    xmlNodePtr using[PARTS_MAX_DEPTH]; /* what the use elements being drawn point at */
    size_t using_count;
    size_t used; /* elements drawn through use so far */
} svg_reader;

/* The element being read: for messages and for the rings it gives. */
typedef struct svg_element {
    svg_reader *reader;
    xmlNodePtr node;
    int line;
    char what[96]; /* 'path id="a"' */
    char id[32];
    parts_matrix matrix; /* element's user units to mm */
    double tolerance;    /* in the element's user units */
    int sub;             /* rings given so far */
} svg_element;

/* A cursor over attribute text: numbers, flags and separators are read from it. */
typedef struct svg_scanner {
    const char *at;
} svg_scanner;

typedef struct svg_viewbox {
    bool given;
    double x, y, width, height;
} svg_viewbox;

/* ---- svg_values.c: numbers, lengths, lists and transforms ---------------------- */

/* Skips white space and commas. */
void svg_skip_separators(svg_scanner *scanner);

/* One number of SVG's grammar (no "inf", "nan" or hex); false when there is none. */
bool svg_scan_number(svg_scanner *scanner, double *value);

/* An arc's flag, "0" or "1", which needs no separator after it. */
bool svg_scan_flag(svg_scanner *scanner, bool *flag);

/* Whether only separators are left. */
bool svg_at_end(svg_scanner *scanner);

/* A length: its number and its unit ("" for none). */
bool svg_parse_length_text(const char *text, double *value, char *unit, size_t unit_size);

/* The attribute's text, or NULL when absent; free with xmlFree. */
char *svg_attribute(xmlNodePtr node, const char *name);

/* A length attribute in user units (px, mm, ...), fallback when absent. */
ur_status svg_length_attribute(svg_element *element, const char *name, double fallback,
                               double *value, ur_error *error);

/* The element's own transform attribute (identity when absent). */
ur_status svg_parse_transform(svg_element *element, parts_matrix *matrix, ur_error *error);

/* ---- svg_path.c: path data ------------------------------------------------------ */

/* Draws the sub-paths of a d attribute as rings and lines of the element. */
ur_status svg_parse_path_data(svg_element *element, const char *data, ur_error *error);

/* ---- svg_shapes.c: path, rect, circle, ellipse, polygon, polyline, line --------- */

ur_status svg_read_path(svg_element *element, ur_error *error);
ur_status svg_read_rect(svg_element *element, ur_error *error);
ur_status svg_read_ellipse(svg_element *element, bool circle, ur_error *error);
ur_status svg_read_poly(svg_element *element, bool polygon, ur_error *error);
ur_status svg_read_line(svg_element *element, ur_error *error);

/* The length attributes names (NULL-terminated), 0 for each one absent. */
ur_status svg_lengths(svg_element *element, const char *const *names, double *values,
                      ur_error *error);

/* ---- svg_use.c: use and symbol ---------------------------------------------------- */

/* Draws the element or symbol a use element names, at its place. */
ur_status svg_read_use(svg_element *element, int depth, ur_error *error);

/* ---- svg_import.c: the document walk ---------------------------------------------- */

/* UR_ERROR_INPUT "FILE:LINE: element: message". */
ur_status svg_element_error(const svg_element *element, ur_error *error, const char *message);

/*
 * Transforms the points to mm and hands them over as a ring.  circle (user
 * units, NULL for none) is the circle the ring exactly is; it stays one
 * only under a transform that keeps circles circles.
 */
ur_status svg_element_ring(svg_element *element, parts_points *points, const ur_path_circle *circle,
                           ur_error *error);

/* An open shape, in mm: it goes with the part that holds it, or is left out. */
ur_status svg_element_line(svg_element *element, parts_points *points, ur_error *error);

bool svg_named(xmlNodePtr node, const char *name);

/* display="none" or style="...display:none...": Inkscape's hidden layers. */
bool svg_hidden(xmlNodePtr node);

/* Starts the element: who it is, and its user units to mm. */
ur_status svg_element_begin(svg_element *element, svg_reader *reader, xmlNodePtr node,
                            parts_matrix parent, ur_error *error);

ur_status svg_read_viewbox(svg_element *element, svg_viewbox *box, ur_error *error);

/* The element (a shape, g, svg, use...) with what it holds. */
ur_status svg_read_shape(svg_element *element, int depth, ur_error *error);

/* The children of parent, under matrix (their user units to mm). */
ur_status svg_walk(svg_reader *reader, xmlNodePtr parent, parts_matrix matrix, int depth,
                   ur_error *error);

#endif
