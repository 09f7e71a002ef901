/*
 * style.c: the machine's per-operation styles as the formats read them
 * (writer.h).  A machine filled in by hand may carry anything, so every
 * format refuses what it could not show in one place and in one wording.
 */
#include "writer.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

static bool is_colour(const char *colour)
{
    if (colour[0] != '#' || strlen(colour) != 7)
        return false;
    for (int i = 1; i < 7; i++)
        if (!strchr("0123456789abcdefABCDEF", colour[i]))
            return false;
    return true;
}

ur_status style_check(const ur_machine *machine, ur_op op, ur_error *error)
{
    const ur_op_style *style = &machine->styles[op];
    const char *name = memchr(machine->name, '\0', sizeof machine->name) ? machine->name : "?";
    if (!memchr(style->layer, '\0', sizeof style->layer) ||
        !memchr(style->colour, '\0', sizeof style->colour) || !is_colour(style->colour))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "machine '%s': the %s layer needs a name and a colour #RRGGBB", name,
                            ur_op_name(op));
    if (!isfinite(style->line_width) || style->line_width <= 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "machine '%s': the %s line width must be a positive number of mm", name,
                            ur_op_name(op));
    if (!memchr(style->dash, '\0', sizeof style->dash))
        return ur_error_set(error, UR_ERROR_INPUT, "machine '%s': the %s dash pattern is not text",
                            name, ur_op_name(op));
    return UR_OK;
}

unsigned long style_rgb(const ur_op_style *style)
{
    return strtoul(style->colour + 1, NULL, 16);
}

size_t style_dashes(const ur_op_style *style, double *dashes, size_t max)
{
    const char *at = style->dash;
    size_t count = 0;
    while (count < max) {
        char *end;
        double value = c_strtod(at, &end);
        if (end == at || !(value > 0) || !isfinite(value))
            break;
        dashes[count++] = value;
        at = end;
        while (*at == ' ' || *at == ',')
            at++;
    }
    return count;
}
