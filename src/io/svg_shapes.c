/*
 * svg_shapes.c: the basic shapes (path, rect with its rounded corners,
 * circle, ellipse, polygon, polyline and line) as rings and lines.
 */
#include "svg_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../base/c_locale.h"

/* ---- Shapes ----------------------------------------------------------------- */

ur_status svg_read_path(svg_element *element, ur_error *error)
{
    char *data = svg_attribute(element->node, "d");
    if (!data)
        return svg_element_error(element, error, "a path without d draws nothing");
    ur_status status = svg_parse_path_data(element, data, error);
    xmlFree(data);
    return status;
}

/* Lengths named in names (NULL-terminated) into values, 0 when absent. */
ur_status svg_lengths(svg_element *element, const char *const *names, double *values,
                      ur_error *error)
{
    for (size_t i = 0; names[i]; i++) {
        ur_status status = svg_length_attribute(element, names[i], 0.0, &values[i], error);
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
    c_snprintf(message, sizeof message, "%s must be positive, not %g", name, value);
    return svg_element_error(element, error, message);
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
    char *has_rx = svg_attribute(element->node, "rx"), *has_ry = svg_attribute(element->node, "ry");
    ur_status status = svg_length_attribute(element, "rx", 0, rx, error);
    if (status == UR_OK)
        status = svg_length_attribute(element, "ry", 0, ry, error);
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

ur_status svg_read_rect(svg_element *element, ur_error *error)
{
    static const char *const names[] = {"x", "y", "width", "height", NULL};
    double v[4], rx = 0, ry = 0;
    ur_status status = svg_lengths(element, names, v, error);
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
        status = svg_element_ring(element, &points, NULL, error);
    parts_points_free(&points);
    return status;
}

ur_status svg_read_ellipse(svg_element *element, bool circle, ur_error *error)
{
    static const char *const circle_names[] = {"cx", "cy", "r", NULL};
    static const char *const ellipse_names[] = {"cx", "cy", "rx", "ry", NULL};
    double v[4];
    ur_status status = svg_lengths(element, circle ? circle_names : ellipse_names, v, error);
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
        status = svg_element_ring(element, &points, v[2] == v[3] ? &round : NULL, error);
    parts_points_free(&points);
    return status;
}

/* polygon and polyline: "x,y x,y ..."; a polyline must end where it starts. */
ur_status svg_read_poly(svg_element *element, bool polygon, ur_error *error)
{
    char *text = svg_attribute(element->node, "points");
    if (!text)
        return svg_element_error(element, error, "no points");
    svg_scanner scanner = {text};
    parts_points points = {0};
    ur_status status = UR_OK;
    double x, y;
    while (status == UR_OK && !svg_at_end(&scanner)) {
        const char *at = scanner.at;
        if (!svg_scan_number(&scanner, &x) || !svg_scan_number(&scanner, &y)) {
            char message[128];
            c_snprintf(message, sizeof message, "bad points at \"%.*s\"", SVG_QUOTE_MAX, at);
            status = svg_element_error(element, error, message);
        } else
            status = parts_points_push(&points, ur_vec2_make(x, y), error);
    }
    xmlFree(text);
    bool open =
        !polygon && points.count > 1 &&
        ur_vec2_distance(points.items[0], points.items[points.count - 1]) > element->tolerance;
    if (status == UR_OK && open)
        status = svg_element_line(element, &points, error);
    else if (status == UR_OK)
        status = svg_element_ring(element, &points, NULL, error);
    parts_points_free(&points);
    return status;
}

ur_status svg_read_line(svg_element *element, ur_error *error)
{
    static const char *const names[] = {"x1", "y1", "x2", "y2", NULL};
    double v[4];
    parts_points points = {0};
    ur_status status = svg_lengths(element, names, v, error);
    if (status == UR_OK)
        status = parts_points_push(&points, ur_vec2_make(v[0], v[1]), error);
    if (status == UR_OK)
        status = parts_points_push(&points, ur_vec2_make(v[2], v[3]), error);
    if (status == UR_OK)
        status = svg_element_line(element, &points, error);
    parts_points_free(&points);
    return status;
}
