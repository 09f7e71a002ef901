/*
 * svg_path.c: a path's d attribute drawn as sub-paths: every command,
 * relative and absolute, curves flattened within the element's tolerance,
 * and a sub-path of arcs of one circle going once round kept as that
 * circle.
 */
#include "svg_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../base/c_locale.h"

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
        c_snprintf(message, sizeof message, "bad path data at \"%.*s\"", SVG_QUOTE_MAX, at);
    else
        c_snprintf(message, sizeof message, "path data ends before its last command is complete");
    return svg_element_error(state->element, error, message);
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
        return svg_element_line(state->element, points, error);
    return svg_element_ring(state->element, points, round ? &circle : NULL, error);
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
        const char *at = (svg_skip_separators(scanner), scanner->at);
        bool flag = false;
        bool good = upper == 'A' && (i == 3 || i == 4) ? svg_scan_flag(scanner, &flag)
                                                       : svg_scan_number(scanner, &v[i]);
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

ur_status svg_parse_path_data(svg_element *element, const char *data, ur_error *error)
{
    svg_path_state state = {.element = element};
    svg_scanner scanner = {data};
    char command = 0;
    ur_status status = UR_OK;
    while (status == UR_OK && !svg_at_end(&scanner)) {
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
