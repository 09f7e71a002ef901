/*
 * text.c: small text helpers the readers share (io_internal.h), and
 * reading a whole file into memory for the readers that take a path: each
 * reads bytes in memory, so that its path and buffer versions are one code.
 */
#include "io_internal.h"

#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "../base/c_locale.h"

bool io_has_extension(const char *path, const char *extension)
{
    const char *dot = path ? strrchr(path, '.') : NULL;
    return dot && !strchr(dot, '/') && strcasecmp(dot + 1, extension) == 0;
}

bool io_whole_number(const char *word, size_t length, bool signed_ok, uint64_t max, uint64_t *value)
{
    size_t i = 0;
    if (signed_ok && length > 0 && (word[0] == '-' || word[0] == '+'))
        i = 1;
    if (i == length)
        return false;
    uint64_t n = 0;
    for (; i < length; i++) {
        if (word[i] < '0' || word[i] > '9')
            return false;
        n = 10 * n + (uint64_t)(word[i] - '0');
        if (n > max)
            return false;
    }
    *value = n;
    return true;
}

static size_t skip_digits(const char *word, size_t length, size_t i)
{
    while (i < length && word[i] >= '0' && word[i] <= '9')
        i++;
    return i;
}

static bool same_word(const char *word, size_t length, const char *name)
{
    return strlen(name) == length && strncasecmp(word, name, length) == 0;
}

bool io_real_number(const char *word, size_t length, bool decimal_comma)
{
    size_t i = (length > 0 && (word[0] == '-' || word[0] == '+')) ? 1 : 0;
    const char *rest = word + i;
    if (same_word(rest, length - i, "inf") || same_word(rest, length - i, "infinity") ||
        same_word(rest, length - i, "nan"))
        return true; /* the importer refuses a coordinate that is not finite, naming it */
    size_t digits_start = i;
    i = skip_digits(word, length, i);
    size_t digits = i - digits_start;
    bool comma = decimal_comma && i + 1 < length && word[i] == ',' && word[i + 1] >= '0' &&
                 word[i + 1] <= '9';
    if (i < length && (word[i] == '.' || comma)) {
        size_t fraction_start = ++i;
        i = skip_digits(word, length, i);
        digits += i - fraction_start;
    }
    if (digits == 0)
        return false;
    if (i < length && (word[i] == 'e' || word[i] == 'E')) {
        i++;
        if (i < length && (word[i] == '-' || word[i] == '+'))
            i++;
        size_t exponent_start = i;
        i = skip_digits(word, length, i);
        if (i == exponent_start)
            return false;
    }
    return i == length;
}

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
    c_snprintf(stem, size, "%.*s", (int)length, name);
}

ur_status io_read_file(const char *path, long max_bytes, const char *what, char **text,
                       size_t *size, ur_error *error)
{
    *text = NULL;
    *size = 0;
    FILE *file = fopen(path, "rb");
    if (!file)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path, strerror(errno));
    long length = fseek(file, 0, SEEK_END) == 0 ? ftell(file) : -1;
    ur_status status = UR_OK;
    if (length < 0 || fseek(file, 0, SEEK_SET) != 0)
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: cannot read: %s", path, strerror(errno));
    else if (max_bytes > 0 && length > max_bytes)
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: %ld bytes: too large for %s", path,
                              length, what);
    else if ((*text = ur_alloc_array((size_t)length + 1, 1, error)) == NULL)
        status = UR_ERROR_MEMORY;
    else if (fread(*text, 1, (size_t)length, file) != (size_t)length)
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: cannot read: %s", path,
                              strerror(errno ? errno : EIO));
    fclose(file);
    if (status != UR_OK) {
        free(*text);
        *text = NULL;
        return status;
    }
    (*text)[length] = '\0';
    *size = (size_t)length;
    return UR_OK;
}

char *io_copy_text(const void *data, size_t size, ur_error *error)
{
    if (size == SIZE_MAX) {
        ur_error_out_of_memory(error);
        return NULL;
    }
    char *text = ur_alloc_array(size + 1, 1, error);
    if (text) {
        if (size > 0)
            memcpy(text, data, size);
        text[size] = '\0';
    }
    return text;
}
