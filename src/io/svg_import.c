/*
 * svg_import.c: the closed shapes of an SVG drawing as rings in millimetres,
 * y up, for parts_import.c to sort into parts and holes.
 *
 * libxml2 reads the file without network access and without substituting
 * entities; its messages are collected (never printed, xml_errors.c) and
 * the first becomes "FILE:LINE: message".  The walk keeps the transform from user
 * units to millimetres (the root's size and viewBox, every g's and the
 * element's own transform) and flattens curves in the element's own
 * coordinates with the tolerance scaled by how much that transform can
 * stretch, so the flattened curve is within tolerance once in millimetres.
 */
#include "parts_internal.h"
#include "xml_errors.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include "../base/c_locale.h"

#define SVG_NAMESPACE "http://www.w3.org/2000/svg"

/* Longest piece of attribute text quoted back in a message. */
#define SVG_QUOTE_MAX 24

/* ---- Reading state ------------------------------------------------------ */

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

static ur_status element_error(const svg_element *element, ur_error *error, const char *message)
{
    return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: %s: %s", element->reader->path,
                        element->line, element->what, message);
}

/*
 * Transforms the points to mm and hands them over as a ring.  circle (user
 * units, NULL for none) is the circle the ring exactly is; it stays one
 * only under a transform that keeps circles circles.
 */
static ur_status element_ring(svg_element *element, parts_points *points,
                              const ur_path_circle *circle, ur_error *error)
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
static ur_status element_line(svg_element *element, parts_points *points, ur_error *error)
{
    for (size_t i = 0; i < points->count; i++)
        points->items[i] = parts_matrix_apply(element->matrix, points->items[i]);
    return parts_add_line(element->reader->collection, points, false, element->reader->op,
                          element->line, element->what, error);
}

/* ---- Numbers, lengths, lists -------------------------------------------- */

typedef struct svg_scanner {
    const char *at;
} svg_scanner;

static void skip_separators(svg_scanner *scanner)
{
    while (isspace((unsigned char)*scanner->at) || *scanner->at == ',')
        scanner->at++;
}

/* SVG's number grammar: no "inf", "nan" or hex, which strtod would take. */
static bool scan_number(svg_scanner *scanner, double *value)
{
    skip_separators(scanner);
    const char *p = scanner->at;
    if (*p == '+' || *p == '-')
        p++;
    size_t digits = 0;
    while (isdigit((unsigned char)*p))
        p++, digits++;
    if (*p == '.')
        for (p++; isdigit((unsigned char)*p); p++)
            digits++;
    if (digits == 0)
        return false;
    if (*p == 'e' || *p == 'E') {
        const char *q = p + 1;
        if (*q == '+' || *q == '-')
            q++;
        if (isdigit((unsigned char)*q)) {
            while (isdigit((unsigned char)*q))
                q++;
            p = q;
        }
    }
    char text[64];
    size_t length = (size_t)(p - scanner->at);
    if (length >= sizeof text)
        return false;
    memcpy(text, scanner->at, length);
    text[length] = '\0';
    *value = ur_c_strtod(text, NULL);
    if (!isfinite(*value))
        return false;
    scanner->at = p;
    return true;
}

/* An arc's flag: a single 0 or 1, which may run into what follows ("a1 1 0 01.5 2"). */
static bool scan_flag(svg_scanner *scanner, bool *flag)
{
    skip_separators(scanner);
    if (*scanner->at != '0' && *scanner->at != '1')
        return false;
    *flag = *scanner->at++ == '1';
    return true;
}

static bool at_end(svg_scanner *scanner)
{
    skip_separators(scanner);
    return *scanner->at == '\0';
}

/* User units (CSS px) in one unit of an attribute's length. */
static double unit_in_px(const char *unit)
{
    if (*unit == '\0')
        return 1.0;
    double mm = ur_parts_unit_mm(unit);
    return mm > 0 && strcmp(unit, "m") != 0 && strcmp(unit, "ft") != 0 ? mm * 96 / 25.4 : 0.0;
}

/* A length "12", "12.5mm": *unit points at what follows the number, trimmed. */
static bool parse_length_text(const char *text, double *value, char *unit, size_t unit_size)
{
    svg_scanner scanner = {text};
    if (!scan_number(&scanner, value))
        return false;
    const char *rest = scanner.at;
    size_t length = strlen(rest);
    while (length > 0 && isspace((unsigned char)rest[length - 1]))
        length--;
    if (length >= unit_size)
        return false;
    ur_c_snprintf(unit, unit_size, "%.*s", (int)length, rest);
    return true;
}

/* The attribute as a string; the caller frees it with xmlFree. */
static char *attribute(xmlNodePtr node, const char *name)
{
    return (char *)xmlGetProp(node, (const xmlChar *)name);
}

/* A length attribute in user units; fallback when absent. */
static ur_status length_attribute(svg_element *element, const char *name, double fallback,
                                  double *value, ur_error *error)
{
    char *text = attribute(element->node, name);
    *value = fallback;
    if (!text)
        return UR_OK;
    char unit[8];
    double number = 0;
    double px = parse_length_text(text, &number, unit, sizeof unit) ? unit_in_px(unit) : 0.0;
    ur_status status = UR_OK;
    if (px > 0)
        *value = number * px;
    else {
        char message[128];
        ur_c_snprintf(message, sizeof message, "%s=\"%.*s\" is not a length", name, SVG_QUOTE_MAX,
                      text);
        status = element_error(element, error, message);
    }
    xmlFree(text);
    return status;
}

/* ---- Transforms ------------------------------------------------------------ */

/* Up to max numbers inside "( ... )"; *count says how many. */
static bool scan_arguments(svg_scanner *scanner, double *values, int max, int *count)
{
    skip_separators(scanner);
    if (*scanner->at != '(')
        return false;
    scanner->at++;
    *count = 0;
    for (;;) {
        skip_separators(scanner);
        if (*scanner->at == ')') {
            scanner->at++;
            return true;
        }
        if (*count == max || !scan_number(scanner, &values[*count]))
            return false;
        (*count)++;
    }
}

/* One transform function by name and arguments; false when they do not fit. */
static bool transform_function(const char *name, size_t length, const double *v, int n,
                               parts_matrix *m)
{
#define IS(word) (length == strlen(word) && strncmp(name, word, length) == 0)
    double radians = n > 0 ? v[0] * M_PI / 180 : 0;
    if (IS("matrix") && n == 6)
        *m = (parts_matrix){v[0], v[1], v[2], v[3], v[4], v[5]};
    else if (IS("translate") && (n == 1 || n == 2))
        *m = (parts_matrix){1, 0, 0, 1, v[0], n == 2 ? v[1] : 0};
    else if (IS("scale") && (n == 1 || n == 2))
        *m = (parts_matrix){v[0], 0, 0, n == 2 ? v[1] : v[0], 0, 0};
    else if (IS("rotate") && (n == 1 || n == 3)) {
        double c = cos(radians), s = sin(radians);
        double cx = n == 3 ? v[1] : 0, cy = n == 3 ? v[2] : 0;
        *m = (parts_matrix){c, s, -s, c, cx - c * cx + s * cy, cy - s * cx - c * cy};
    } else if (IS("skewX") && n == 1)
        *m = (parts_matrix){1, 0, tan(radians), 1, 0, 0};
    else if (IS("skewY") && n == 1)
        *m = (parts_matrix){1, tan(radians), 0, 1, 0, 0};
    else
        return false;
    return true;
#undef IS
}

/* One "name(arguments)" of a transform list into *step. */
static bool scan_transform(svg_scanner *scanner, parts_matrix *step)
{
    skip_separators(scanner);
    const char *name = scanner->at;
    while (isalpha((unsigned char)*scanner->at))
        scanner->at++;
    size_t length = (size_t)(scanner->at - name);
    double values[6];
    int count = 0;
    return length > 0 && scan_arguments(scanner, values, 6, &count) &&
           transform_function(name, length, values, count, step);
}

/* The element's transform attribute, identity when it has none. */
static ur_status parse_transform(svg_element *element, parts_matrix *matrix, ur_error *error)
{
    *matrix = parts_identity;
    char *text = attribute(element->node, "transform");
    if (!text)
        return UR_OK;
    svg_scanner scanner = {text};
    bool good = true;
    while (good && !at_end(&scanner)) {
        parts_matrix step;
        good = scan_transform(&scanner, &step);
        if (good)
            *matrix = parts_matrix_multiply(*matrix, step);
    }
    ur_status status = UR_OK;
    if (!good) {
        char message[128];
        ur_c_snprintf(message, sizeof message, "transform=\"%.*s\" is not a transform",
                      SVG_QUOTE_MAX, text);
        status = element_error(element, error, message);
    }
    xmlFree(text);
    return status;
}

/* ---- Path data ------------------------------------------------------------- */

typedef struct svg_path_state {
    svg_element *element;
    parts_points points; /* the sub-path being drawn, user units */
    ur_vec2 current, start;
    ur_vec2 control; /* the last control point, reflected by S and T */
    char previous;   /* the last command, upper case */
    bool started;    /* the path began with a moveto */
    /*
     * Whether the sub-path so far is arcs of one circle only (a circle drawn
     * as two half arcs, as many programs write one): their centre, radius
     * and the angle they have turned through in all.
     */
    size_t arcs;  /* circular arcs drawn in this sub-path */
    bool not_arc; /* something else was drawn too */
    ur_vec2 centre;
    double radius, swept;
} svg_path_state;

/* The sub-path's arcs so far are of one circle, with no other segment. */
static void note_segment(svg_path_state *state, const parts_arc *arc)
{
    if (!arc || arc->rx != arc->ry) {
        state->not_arc = true;
        return;
    }
    double slack = 1e-9 * fmax(1.0, arc->rx);
    if (state->arcs > 0 && (ur_vec2_distance(arc->centre, state->centre) > slack ||
                            fabs(arc->rx - state->radius) > slack || arc->sweep * state->swept < 0))
        state->not_arc = true;
    if (state->arcs == 0) {
        state->centre = arc->centre;
        state->radius = arc->rx;
    }
    state->arcs++;
    state->swept += arc->sweep;
}

static ur_status path_data_error(svg_path_state *state, const char *at, ur_error *error)
{
    char message[128];
    if (*at)
        ur_c_snprintf(message, sizeof message, "bad path data at \"%.*s\"", SVG_QUOTE_MAX, at);
    else
        ur_c_snprintf(message, sizeof message,
                      "path data ends before its last command is complete");
    return element_error(state->element, error, message);
}

/*
 * Ends the sub-path: closed by Z, or by ending where it started (within the
 * tolerance), it becomes a ring; a lone moveto is nothing; anything else is open.
 */
static ur_status finish_subpath(svg_path_state *state, bool closed, ur_error *error)
{
    parts_points *points = &state->points;
    /* Arcs of one circle that go once round, ending where they began, are that circle. */
    double slack = 1e-9 * fmax(1.0, state->radius);
    bool round = state->arcs > 0 && !state->not_arc && points->count > 0 &&
                 ur_vec2_distance(points->items[0], points->items[points->count - 1]) <= slack &&
                 fabs(fabs(state->swept) - 2 * M_PI) <= 1e-9;
    ur_path_circle circle = {state->centre, state->radius, 0};
    state->arcs = 0;
    state->not_arc = false;
    state->swept = 0;
    if (points->count == 0 || (points->count == 1 && !closed)) {
        points->count = 0;
        return UR_OK;
    }
    ur_vec2 first = points->items[0], last = points->items[points->count - 1];
    if (!closed && ur_vec2_distance(first, last) > state->element->tolerance)
        return element_line(state->element, points, error);
    return element_ring(state->element, points, round ? &circle : NULL, error);
}

/* After Z a drawing command starts again where the sub-path started. */
static ur_status begin_if_needed(svg_path_state *state, ur_error *error)
{
    if (state->points.count > 0)
        return UR_OK;
    return parts_points_push(&state->points, state->current, error);
}

static ur_status line_to(svg_path_state *state, ur_vec2 p, ur_error *error)
{
    if (ur_vec2_distance(state->current, p) > 0)
        note_segment(state, NULL);
    ur_status status = begin_if_needed(state, error);
    if (status == UR_OK)
        status = parts_points_push(&state->points, p, error);
    return status;
}

static double vector_angle(ur_vec2 u, ur_vec2 v)
{
    return atan2(ur_vec2_cross(u, v), ur_vec2_dot(u, v));
}

/* The endpoint arc of SVG (implementation notes F.6.5) to its centre form. */
static bool arc_centre(ur_vec2 p0, ur_vec2 p1, double rx, double ry, double degrees, bool large,
                       bool sweep, parts_arc *arc)
{
    double phi = degrees * M_PI / 180, c = cos(phi), s = sin(phi);
    double dx = (p0.x - p1.x) / 2, dy = (p0.y - p1.y) / 2;
    double x1 = c * dx + s * dy, y1 = -s * dx + c * dy;
    rx = fabs(rx);
    ry = fabs(ry);
    double lambda = x1 * x1 / (rx * rx) + y1 * y1 / (ry * ry);
    if (lambda > 1) {
        rx *= sqrt(lambda);
        ry *= sqrt(lambda);
    }
    double numerator = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
    double denominator = rx * rx * y1 * y1 + ry * ry * x1 * x1;
    if (!(denominator > 0))
        return false;
    double k = sqrt(fmax(0, numerator / denominator)) * (large == sweep ? -1 : 1);
    double cx = k * rx * y1 / ry, cy = -k * ry * x1 / rx;
    ur_vec2 u = ur_vec2_make((x1 - cx) / rx, (y1 - cy) / ry);
    ur_vec2 v = ur_vec2_make((-x1 - cx) / rx, (-y1 - cy) / ry);
    double delta = vector_angle(u, v);
    if (!sweep && delta > 0)
        delta -= 2 * M_PI;
    else if (sweep && delta < 0)
        delta += 2 * M_PI;
    *arc = (parts_arc){
        ur_vec2_make(c * cx - s * cy + (p0.x + p1.x) / 2, s * cx + c * cy + (p0.y + p1.y) / 2),
        rx,
        ry,
        phi,
        vector_angle(ur_vec2_make(1, 0), u),
        delta};
    return true;
}

static ur_status arc_to(svg_path_state *state, const double *v, ur_vec2 end, ur_error *error)
{
    parts_arc arc;
    if (ur_vec2_distance(state->current, end) == 0)
        return UR_OK; /* the spec: an arc to where it starts is left out */
    if (v[0] == 0 || v[1] == 0 ||
        !arc_centre(state->current, end, v[0], v[1], v[2], v[3] != 0, v[4] != 0, &arc))
        return line_to(state, end, error);
    note_segment(state, &arc);
    ur_status status = begin_if_needed(state, error);
    if (status == UR_OK)
        status = parts_flatten_arc(&state->points, &arc, state->element->tolerance, error);
    if (status == UR_OK)
        state->points.items[state->points.count - 1] = end; /* exactly, not rounded */
    return status;
}

static int argument_count(char upper)
{
    switch (upper) {
    case 'M':
    case 'L':
    case 'T':
        return 2;
    case 'H':
    case 'V':
        return 1;
    case 'S':
    case 'Q':
        return 4;
    case 'C':
        return 6;
    case 'A':
        return 7;
    case 'Z':
        return 0;
    default:
        return -1;
    }
}

/* 2 c - p: the control point S and T take when they follow their own kind. */
static ur_vec2 reflected(svg_path_state *state, char a, char b)
{
    if (state->previous != a && state->previous != b)
        return state->current;
    return ur_vec2_sub(ur_vec2_scale(state->current, 2), state->control);
}

/* The curve commands; v holds the arguments made absolute where they are points. */
static ur_status curve_command(svg_path_state *state, char upper, const double *v, ur_error *error)
{
    double tolerance = state->element->tolerance;
    ur_vec2 p0 = state->current, c1, c2, end;
    note_segment(state, NULL);
    ur_status status = begin_if_needed(state, error);
    if (status != UR_OK)
        return status;
    switch (upper) {
    case 'C':
    case 'S':
        c1 = upper == 'C' ? ur_vec2_make(v[0], v[1]) : reflected(state, 'C', 'S');
        c2 = upper == 'C' ? ur_vec2_make(v[2], v[3]) : ur_vec2_make(v[0], v[1]);
        end = upper == 'C' ? ur_vec2_make(v[4], v[5]) : ur_vec2_make(v[2], v[3]);
        status = parts_flatten_cubic(&state->points, p0, c1, c2, end, tolerance, error);
        state->control = c2;
        break;
    default: /* Q, T */
        c1 = upper == 'Q' ? ur_vec2_make(v[0], v[1]) : reflected(state, 'Q', 'T');
        end = upper == 'Q' ? ur_vec2_make(v[2], v[3]) : ur_vec2_make(v[0], v[1]);
        status = parts_flatten_quadratic(&state->points, p0, c1, end, tolerance, error);
        state->control = c1;
        break;
    }
    state->current = end;
    return status;
}

/* Makes the point arguments of a relative command absolute. */
static void absolute_arguments(char upper, double *v, int count, ur_vec2 base)
{
    if (upper == 'A') {
        v[5] += base.x;
        v[6] += base.y;
    } else if (upper == 'H')
        v[0] += base.x;
    else if (upper == 'V')
        v[0] += base.y;
    else
        for (int i = 0; i + 1 < count; i += 2) {
            v[i] += base.x;
            v[i + 1] += base.y;
        }
}

static ur_status run_command(svg_path_state *state, char upper, double *v, ur_error *error)
{
    ur_status status = UR_OK;
    ur_vec2 end = state->current;
    switch (upper) {
    case 'M':
        status = finish_subpath(state, false, error);
        state->current = state->start = ur_vec2_make(v[0], v[1]);
        if (status == UR_OK)
            status = parts_points_push(&state->points, state->current, error);
        break;
    case 'Z':
        status = finish_subpath(state, true, error);
        state->current = state->start;
        break;
    case 'A':
        end = ur_vec2_make(v[5], v[6]);
        status = arc_to(state, v, end, error);
        state->current = end;
        break;
    case 'C':
    case 'S':
    case 'Q':
    case 'T':
        return curve_command(state, upper, v, error);
    default: /* L, H, V */
        end = upper == 'H'   ? ur_vec2_make(v[0], end.y)
              : upper == 'V' ? ur_vec2_make(end.x, v[0])
                             : ur_vec2_make(v[0], v[1]);
        status = line_to(state, end, error);
        state->current = end;
        break;
    }
    state->control = state->current;
    return status;
}

static ur_status path_command(svg_path_state *state, char command, svg_scanner *scanner,
                              ur_error *error)
{
    char upper = (char)toupper((unsigned char)command);
    int count = argument_count(upper);
    if (count < 0 || (!state->started && upper != 'M'))
        return path_data_error(state, scanner->at - 1, error);
    state->started = true;
    double v[7];
    for (int i = 0; i < count; i++) {
        const char *at = (skip_separators(scanner), scanner->at);
        bool flag = false;
        bool good = upper == 'A' && (i == 3 || i == 4) ? scan_flag(scanner, &flag)
                                                       : scan_number(scanner, &v[i]);
        if (!good)
            return path_data_error(state, at, error);
        if (upper == 'A' && (i == 3 || i == 4))
            v[i] = flag;
    }
    if (command != upper)
        absolute_arguments(upper, v, count, state->current);
    ur_status status = run_command(state, upper, v, error);
    state->previous = upper;
    return status;
}

static ur_status parse_path_data(svg_element *element, const char *data, ur_error *error)
{
    svg_path_state state = {.element = element};
    svg_scanner scanner = {data};
    char command = 0;
    ur_status status = UR_OK;
    while (status == UR_OK && !at_end(&scanner)) {
        char c = *scanner.at;
        if (isalpha((unsigned char)c)) {
            command = c;
            scanner.at++;
        } else if (command == 0 || command == 'Z' || command == 'z') {
            status = path_data_error(&state, scanner.at, error);
            break;
        } else if (command == 'M' || command == 'm') {
            command = command == 'M' ? 'L' : 'l'; /* further pairs after a moveto are lines */
        }
        status = path_command(&state, command, &scanner, error);
    }
    if (status == UR_OK)
        status = finish_subpath(&state, false, error);
    parts_points_free(&state.points);
    return status;
}

/* ---- Shapes ----------------------------------------------------------------- */

static ur_status read_path(svg_element *element, ur_error *error)
{
    char *data = attribute(element->node, "d");
    if (!data)
        return element_error(element, error, "a path without d draws nothing");
    ur_status status = parse_path_data(element, data, error);
    xmlFree(data);
    return status;
}

/* Lengths named in names (NULL-terminated) into values, 0 when absent. */
static ur_status lengths(svg_element *element, const char *const *names, double *values,
                         ur_error *error)
{
    for (size_t i = 0; names[i]; i++) {
        ur_status status = length_attribute(element, names[i], 0.0, &values[i], error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status positive(svg_element *element, const char *name, double value, ur_error *error)
{
    if (value > 0)
        return UR_OK;
    char message[96];
    ur_c_snprintf(message, sizeof message, "%s must be positive, not %g", name, value);
    return element_error(element, error, message);
}

/* A corner of a rounded rectangle: a quarter ellipse from angle start. */
static ur_status rect_corner(svg_element *element, parts_points *points, ur_vec2 centre, double rx,
                             double ry, double start, ur_error *error)
{
    parts_arc arc = {centre, rx, ry, 0, start, M_PI / 2};
    ur_status status = parts_points_push(points, parts_arc_point(&arc, start), error);
    if (status == UR_OK && rx > 0 && ry > 0)
        status = parts_flatten_arc(points, &arc, element->tolerance, error);
    return status;
}

/* rx and ry as SVG 1.1 fixes them: one stands for both, neither more than half the side. */
static ur_status rect_radii(svg_element *element, double w, double h, double *rx, double *ry,
                            ur_error *error)
{
    char *has_rx = attribute(element->node, "rx"), *has_ry = attribute(element->node, "ry");
    ur_status status = length_attribute(element, "rx", 0, rx, error);
    if (status == UR_OK)
        status = length_attribute(element, "ry", 0, ry, error);
    if (has_rx && !has_ry)
        *ry = *rx;
    if (has_ry && !has_rx)
        *rx = *ry;
    xmlFree(has_rx);
    xmlFree(has_ry);
    *rx = fmin(fabs(*rx), w / 2);
    *ry = fmin(fabs(*ry), h / 2);
    return status;
}

static ur_status read_rect(svg_element *element, ur_error *error)
{
    static const char *const names[] = {"x", "y", "width", "height", NULL};
    double v[4], rx = 0, ry = 0;
    ur_status status = lengths(element, names, v, error);
    if (status == UR_OK)
        status = positive(element, "width", v[2], error);
    if (status == UR_OK)
        status = positive(element, "height", v[3], error);
    if (status == UR_OK)
        status = rect_radii(element, v[2], v[3], &rx, &ry, error);
    double x0 = v[0] + rx, x1 = v[0] + v[2] - rx, y0 = v[1] + ry, y1 = v[1] + v[3] - ry;
    ur_vec2 centres[4] = {{x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
    parts_points points = {0};
    for (int k = 0; status == UR_OK && k < 4; k++)
        status = rect_corner(element, &points, centres[k], rx, ry, (k - 1) * M_PI / 2, error);
    if (status == UR_OK)
        status = element_ring(element, &points, NULL, error);
    parts_points_free(&points);
    return status;
}

static ur_status read_ellipse(svg_element *element, bool circle, ur_error *error)
{
    static const char *const circle_names[] = {"cx", "cy", "r", NULL};
    static const char *const ellipse_names[] = {"cx", "cy", "rx", "ry", NULL};
    double v[4];
    ur_status status = lengths(element, circle ? circle_names : ellipse_names, v, error);
    if (circle)
        v[3] = v[2];
    if (status == UR_OK)
        status = positive(element, circle ? "r" : "rx", v[2], error);
    if (status == UR_OK)
        status = positive(element, circle ? "r" : "ry", v[3], error);
    parts_arc arc = {ur_vec2_make(v[0], v[1]), v[2], v[3], 0, 0, 2 * M_PI};
    /* A circle, or an ellipse of equal radii: its points lie on the circle. */
    ur_path_circle round = {arc.centre, v[2], 0};
    parts_points points = {0};
    if (status == UR_OK)
        status = parts_flatten_arc(&points, &arc, element->tolerance, error);
    if (status == UR_OK)
        status = element_ring(element, &points, v[2] == v[3] ? &round : NULL, error);
    parts_points_free(&points);
    return status;
}

/* polygon and polyline: "x,y x,y ..."; a polyline must end where it starts. */
static ur_status read_poly(svg_element *element, bool polygon, ur_error *error)
{
    char *text = attribute(element->node, "points");
    if (!text)
        return element_error(element, error, "no points");
    svg_scanner scanner = {text};
    parts_points points = {0};
    ur_status status = UR_OK;
    double x, y;
    while (status == UR_OK && !at_end(&scanner)) {
        const char *at = scanner.at;
        if (!scan_number(&scanner, &x) || !scan_number(&scanner, &y)) {
            char message[128];
            ur_c_snprintf(message, sizeof message, "bad points at \"%.*s\"", SVG_QUOTE_MAX, at);
            status = element_error(element, error, message);
        } else
            status = parts_points_push(&points, ur_vec2_make(x, y), error);
    }
    xmlFree(text);
    bool open =
        !polygon && points.count > 1 &&
        ur_vec2_distance(points.items[0], points.items[points.count - 1]) > element->tolerance;
    if (status == UR_OK && open)
        status = element_line(element, &points, error);
    else if (status == UR_OK)
        status = element_ring(element, &points, NULL, error);
    parts_points_free(&points);
    return status;
}

static ur_status read_line(svg_element *element, ur_error *error)
{
    static const char *const names[] = {"x1", "y1", "x2", "y2", NULL};
    double v[4];
    parts_points points = {0};
    ur_status status = lengths(element, names, v, error);
    if (status == UR_OK)
        status = parts_points_push(&points, ur_vec2_make(v[0], v[1]), error);
    if (status == UR_OK)
        status = parts_points_push(&points, ur_vec2_make(v[2], v[3]), error);
    if (status == UR_OK)
        status = element_line(element, &points, error);
    parts_points_free(&points);
    return status;
}

/* ---- The document tree ------------------------------------------------------ */

static bool named(xmlNodePtr node, const char *name)
{
    return strcmp((const char *)node->name, name) == 0;
}

static bool named_any(xmlNodePtr node, const char *const *names)
{
    for (size_t i = 0; names[i]; i++)
        if (named(node, names[i]))
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
static bool hidden(xmlNodePtr node)
{
    char *display = attribute(node, "display");
    bool none = display && strcmp(display, "none") == 0;
    xmlFree(display);
    char *style = attribute(node, "style");
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
    char *id = attribute(element->node, "id");
    /* A copy drawn through use is no longer the element of that id: its parts are numbered. */
    bool copy = element->reader && element->reader->using_count > 0;
    ur_c_snprintf(element->id, sizeof element->id, "%s", id && !copy ? id : "");
    if (id)
        ur_c_snprintf(element->what, sizeof element->what, "%s id=\"%.40s\"",
                      (const char *)element->node->name, id);
    else
        ur_c_snprintf(element->what, sizeof element->what, "%s", (const char *)element->node->name);
    xmlFree(id);
    long line = xmlGetLineNo(element->node);
    element->line = line > 0 && line < 1000000000 ? (int)line : 0;
}

/* Starts the element: who it is, and its user units to mm. */
static ur_status element_begin(svg_element *element, svg_reader *reader, xmlNodePtr node,
                               parts_matrix parent, ur_error *error)
{
    memset(element, 0, sizeof *element);
    element->reader = reader;
    element->node = node;
    describe(element);
    parts_matrix own;
    ur_status status = parse_transform(element, &own, error);
    element->matrix = parts_matrix_multiply(parent, own);
    double stretch = parts_matrix_stretch(element->matrix);
    element->tolerance =
        stretch > 0 ? reader->collection->tolerance / stretch : reader->collection->tolerance;
    if (status == UR_OK && reader->using_count > 0 && ++reader->used > SVG_MAX_USED_ELEMENTS)
        status = element_error(element, error,
                               "more than 100000 elements drawn through use: not a drawing of "
                               "parts");
    return status;
}

typedef struct svg_viewbox {
    bool given;
    double x, y, width, height;
} svg_viewbox;

static ur_status read_viewbox(svg_element *element, svg_viewbox *box, ur_error *error)
{
    memset(box, 0, sizeof *box);
    char *text = attribute(element->node, "viewBox");
    if (!text)
        return UR_OK;
    svg_scanner scanner = {text};
    bool good = scan_number(&scanner, &box->x) && scan_number(&scanner, &box->y) &&
                scan_number(&scanner, &box->width) && scan_number(&scanner, &box->height) &&
                at_end(&scanner) && box->width > 0 && box->height > 0;
    ur_status status = UR_OK;
    if (!good) {
        char message[128];
        ur_c_snprintf(message, sizeof message,
                      "viewBox=\"%.*s\" is not four numbers with a positive width and height",
                      SVG_QUOTE_MAX, text);
        status = element_error(element, error, message);
    }
    box->given = good;
    xmlFree(text);
    return status;
}

static ur_status walk(svg_reader *reader, xmlNodePtr parent, parts_matrix matrix, int depth,
                      ur_error *error);

/* A nested svg: its x, y and, with a viewBox and a size, the viewBox's scale. */
static ur_status read_nested_svg(svg_element *element, int depth, ur_error *error)
{
    static const char *const names[] = {"x", "y", "width", "height", NULL};
    double v[4];
    svg_viewbox box;
    ur_status status = lengths(element, names, v, error);
    if (status == UR_OK)
        status = read_viewbox(element, &box, error);
    if (status != UR_OK)
        return status;
    parts_matrix viewport = {1, 0, 0, 1, v[0], v[1]};
    if (box.given && v[2] > 0 && v[3] > 0) {
        double s = fmin(v[2] / box.width, v[3] / box.height);
        viewport = (parts_matrix){s, 0, 0, s, v[0] - s * box.x, v[1] - s * box.y};
    }
    return walk(element->reader, element->node, parts_matrix_multiply(element->matrix, viewport),
                depth + 1, error);
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
        char *name = attribute(node, names[i]);
        ur_op op = name ? parts_layer_op(name) : UR_OP_COUNT;
        xmlFree(name);
        if (op != UR_OP_COUNT)
            return op;
    }
    return inherited;
}

/* ---- use and symbol --------------------------------------------------------- */

static ur_status read_shape(svg_element *element, int depth, ur_error *error);

/* The first element of the document, in document order, whose id is id. */
static xmlNodePtr element_by_id(xmlNodePtr node, const char *id)
{
    for (; node; node = node->next) {
        if (node->type != XML_ELEMENT_NODE)
            continue;
        char *own = attribute(node, "id");
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
    char *href = attribute(element->node, "href"); /* xlink:href too: any namespace */
    char message[160];
    *target = NULL;
    if (!href)
        ur_c_snprintf(message, sizeof message, "no href: the use points at nothing");
    else if (href[0] != '#')
        ur_c_snprintf(message, sizeof message,
                      "href=\"%.*s\" points outside the file: only \"#id\" is read", SVG_QUOTE_MAX,
                      href);
    else if ((*target = element_by_id(xmlDocGetRootElement(element->node->doc), href + 1)) == NULL)
        ur_c_snprintf(message, sizeof message, "href=\"%.*s\" points at no element of the file",
                      SVG_QUOTE_MAX, href);
    else if (loops(element, *target))
        ur_c_snprintf(message, sizeof message,
                      "href=\"%.*s\" refers to itself (directly or through other uses)",
                      SVG_QUOTE_MAX, href);
    else
        message[0] = '\0';
    xmlFree(href);
    return message[0] ? element_error(element, error, message) : UR_OK;
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
    ur_status status = lengths(use, names, size, error);
    if (status == UR_OK)
        status = lengths(symbol, names, own, error);
    if (status == UR_OK)
        status = read_viewbox(symbol, &box, error);
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
    ur_status status = lengths(element, names, at, error);
    if (status != UR_OK)
        return status;
    parts_matrix moved =
        parts_matrix_multiply(element->matrix, (parts_matrix){1, 0, 0, 1, at[0], at[1]});
    svg_reader *reader = element->reader;
    svg_element drawn;
    status = element_begin(&drawn, reader, target, moved, error);
    if (status != UR_OK || hidden(target))
        return status;
    if (!named(target, "symbol"))
        return read_shape(&drawn, depth + 1, error);
    parts_matrix viewport;
    status = symbol_viewport(element, &drawn, &viewport, error);
    if (status == UR_OK)
        status =
            walk(reader, target, parts_matrix_multiply(drawn.matrix, viewport), depth + 1, error);
    return status;
}

/* use: a copy of another element (a symbol, a group, a shape) drawn here. */
static ur_status read_use(svg_element *element, int depth, ur_error *error)
{
    svg_reader *reader = element->reader;
    xmlNodePtr target = NULL;
    ur_status status = use_target(element, &target, error);
    if (status != UR_OK)
        return status;
    if (reader->using_count == PARTS_MAX_DEPTH)
        return element_error(element, error, "uses nest too deep");
    reader->using[reader->using_count++] = target;
    status = draw_target(element, target, depth, error);
    reader->using_count--;
    return status;
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

static ur_status read_shape(svg_element *element, int depth, ur_error *error)
{
    xmlNodePtr node = element->node;
    if (named(node, "g") || named(node, "a") || named(node, "switch")) {
        if (depth >= PARTS_MAX_DEPTH)
            return element_error(element, error, "groups nest too deep");
        svg_reader *reader = element->reader;
        ur_op outer = reader->op;
        reader->op = group_op(node, outer);
        ur_status status = walk(reader, node, element->matrix, depth + 1, error);
        reader->op = outer;
        return status;
    }
    if (named(node, "svg"))
        return depth >= PARTS_MAX_DEPTH ? element_error(element, error, "groups nest too deep")
                                        : read_nested_svg(element, depth, error);
    if (named(node, "path"))
        return read_path(element, error);
    if (named(node, "rect"))
        return read_rect(element, error);
    if (named(node, "circle") || named(node, "ellipse"))
        return read_ellipse(element, named(node, "circle"), error);
    if (named(node, "polygon") || named(node, "polyline"))
        return read_poly(element, named(node, "polygon"), error);
    if (named(node, "line"))
        return read_line(element, error);
    if (named(node, "use"))
        return depth >= PARTS_MAX_DEPTH ? element_error(element, error, "groups nest too deep")
                                        : read_use(element, depth, error);
    return UR_OK; /* other SVG elements draw nothing to cut */
}

static ur_status walk(svg_reader *reader, xmlNodePtr parent, parts_matrix matrix, int depth,
                      ur_error *error)
{
    for (xmlNodePtr node = parent->children; node; node = node->next) {
        if (!svg_element_node(node) || named_any(node, skipped) || hidden(node))
            continue;
        svg_element element;
        ur_status status = element_begin(&element, reader, node, matrix, error);
        if (status == UR_OK && named_any(node, not_outlines))
            status = parts_warn(reader->collection, error, "%s:%d: %s: left out: not a shape",
                                reader->path, element.line, element.what);
        else if (status == UR_OK)
            status = read_shape(&element, depth, error);
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
    char *text = attribute(root->node, name);
    if (!text)
        return UR_OK;
    char unit[8] = "";
    bool good = parse_length_text(text, &size->value, unit, sizeof unit) && size->value > 0;
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
        ur_c_snprintf(message, sizeof message,
                      "%s=\"%.*s\" is not a positive length in mm, cm, in, pt, pc or px", name,
                      SVG_QUOTE_MAX, text);
        status = element_error(root, error, message);
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
        status = read_viewbox(root, &box, error);
    if (status != UR_OK)
        return status;
    double unit = root->reader->collection->unit;
    double sx = axis_scale(&width, box.given, box.width, unit);
    double sy = axis_scale(&height, box.given, box.height, unit);
    if (!width.physical && !height.physical && unit <= 0)
        return element_error(root, error,
                             "the drawing gives no physical size (width and height in mm, cm, "
                             "in, pt, pc or px): give its unit with --units");
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

static ur_status read_root(svg_reader *reader, xmlNodePtr node, ur_error *error)
{
    svg_element root;
    memset(&root, 0, sizeof root);
    root.reader = reader;
    root.node = node;
    describe(&root);
    if (!node || !svg_element_node(node) || !named(node, "svg"))
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: the root element is %s, not svg",
                            reader->path, root.line, node ? (const char *)node->name : "missing");
    parts_matrix base = parts_identity, own = parts_identity;
    ur_status status = root_matrix(&root, &base, error);
    if (status == UR_OK)
        status = parse_transform(&root, &own, error);
    if (status == UR_OK)
        status = walk(reader, node, parts_matrix_multiply(base, own), 0, error);
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
