/*
 * svg_values.c: numbers, lengths, lists and transforms read from SVG
 * attribute text, by SVG's grammar rather than strtod's (no "inf", "nan"
 * or hex; "1.5.5" is two numbers).
 */
#include "svg_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/tree.h>

#include "../base/c_locale.h"

/* ---- Numbers, lengths, lists -------------------------------------------- */

void svg_skip_separators(svg_scanner *scanner)
{
    while (isspace((unsigned char)*scanner->at) || *scanner->at == ',')
        scanner->at++;
}

/* SVG's number grammar: no "inf", "nan" or hex, which strtod would take. */
bool svg_scan_number(svg_scanner *scanner, double *value)
{
    svg_skip_separators(scanner);
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
    *value = c_strtod(text, NULL);
    if (!isfinite(*value))
        return false;
    scanner->at = p;
    return true;
}

/* An arc's flag: a single 0 or 1, which may run into what follows ("a1 1 0 01.5 2"). */
bool svg_scan_flag(svg_scanner *scanner, bool *flag)
{
    svg_skip_separators(scanner);
    if (*scanner->at != '0' && *scanner->at != '1')
        return false;
    *flag = *scanner->at++ == '1';
    return true;
}

bool svg_at_end(svg_scanner *scanner)
{
    svg_skip_separators(scanner);
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
bool svg_parse_length_text(const char *text, double *value, char *unit, size_t unit_size)
{
    svg_scanner scanner = {text};
    if (!svg_scan_number(&scanner, value))
        return false;
    const char *rest = scanner.at;
    size_t length = strlen(rest);
    while (length > 0 && isspace((unsigned char)rest[length - 1]))
        length--;
    if (length >= unit_size)
        return false;
    c_snprintf(unit, unit_size, "%.*s", (int)length, rest);
    return true;
}

/* The attribute as a string; the caller frees it with xmlFree. */
char *svg_attribute(xmlNodePtr node, const char *name)
{
    return (char *)xmlGetProp(node, (const xmlChar *)name);
}

/* A length attribute in user units; fallback when absent. */
ur_status svg_length_attribute(svg_element *element, const char *name, double fallback,
                               double *value, ur_error *error)
{
    char *text = svg_attribute(element->node, name);
    *value = fallback;
    if (!text)
        return UR_OK;
    char unit[8];
    double number = 0;
    double px = svg_parse_length_text(text, &number, unit, sizeof unit) ? unit_in_px(unit) : 0.0;
    ur_status status = UR_OK;
    if (px > 0)
        *value = number * px;
    else {
        char message[128];
        c_snprintf(message, sizeof message, "%s=\"%.*s\" is not a length", name, SVG_QUOTE_MAX,
                   text);
        status = svg_element_error(element, error, message);
    }
    xmlFree(text);
    return status;
}

/* ---- Transforms ------------------------------------------------------------ */

/* Up to max numbers inside "( ... )"; *count says how many. */
static bool scan_arguments(svg_scanner *scanner, double *values, int max, int *count)
{
    svg_skip_separators(scanner);
    if (*scanner->at != '(')
        return false;
    scanner->at++;
    *count = 0;
    for (;;) {
        svg_skip_separators(scanner);
        if (*scanner->at == ')') {
            scanner->at++;
            return true;
        }
        if (*count == max || !svg_scan_number(scanner, &values[*count]))
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
    svg_skip_separators(scanner);
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
ur_status svg_parse_transform(svg_element *element, parts_matrix *matrix, ur_error *error)
{
    *matrix = parts_identity;
    char *text = svg_attribute(element->node, "transform");
    if (!text)
        return UR_OK;
    svg_scanner scanner = {text};
    bool good = true;
    while (good && !svg_at_end(&scanner)) {
        parts_matrix step;
        good = scan_transform(&scanner, &step);
        if (good)
            *matrix = parts_matrix_multiply(*matrix, step);
    }
    ur_status status = UR_OK;
    if (!good) {
        char message[128];
        c_snprintf(message, sizeof message, "transform=\"%.*s\" is not a transform", SVG_QUOTE_MAX,
                   text);
        status = svg_element_error(element, error, message);
    }
    xmlFree(text);
    return status;
}
