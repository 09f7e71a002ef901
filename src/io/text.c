/*
 * text.c: small text helpers the readers share (io_internal.h).
 */
#include "io_internal.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include "../base/c_locale.h"

char *io_trim(char *text)
{
    while (isspace((unsigned char)*text))
        text++;
    size_t length = strlen(text);
    while (length > 0 && isspace((unsigned char)text[length - 1]))
        text[--length] = '\0';
    return text;
}

void io_file_stem(const char *path, char *stem, size_t size)
{
    const char *slash = strrchr(path, '/');
    const char *name = slash ? slash + 1 : path;
    const char *dot = strrchr(name, '.');
    size_t length = dot && dot != name ? (size_t)(dot - name) : strlen(name);
    ur_c_snprintf(stem, size, "%.*s", (int)length, name);
}
