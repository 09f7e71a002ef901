/*
 * csv.c: curves as CSV text, one "x,y,z" point per line.  Edges of regression
 * and rails come in this form; the reader refuses anything the geometry code
 * could choke on later (too few points, NaN, repeated points) and names the
 * file and line, the writer replaces its file atomically so a failed write
 * never leaves half a curve behind.
 */
#include "unroll/io.h"

#include "io_internal.h"

#include "../base/atomic.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "../base/c_locale.h"

/* A curve shorter than this has no usable tangent, normal and binormal. */
#define CURVE_MIN_POINTS 4

/* Longest field quoted back in a message: enough to recognise it. */
#define FIELD_QUOTE_MAX 40

/* ---- Reading ----------------------------------------------------------- */

typedef struct point_list {
    ur_vec3 *items;
    size_t count, capacity;
    size_t *lines; /* the line each point came from, for "repeats" messages */
} point_list;

static void point_list_free(point_list *list)
{
    free(list->items);
    free(list->lines);
    list->items = NULL;
    list->lines = NULL;
    list->count = list->capacity = 0;
}

static ur_status point_list_push(point_list *list, ur_vec3 point, size_t line, ur_error *error)
{
    if (list->count == list->capacity) {
        size_t capacity = list->capacity ? 2 * list->capacity : 64;
        if (capacity > SIZE_MAX / sizeof(ur_vec3))
            return ur_error_out_of_memory(error);
        ur_vec3 *items = realloc(list->items, capacity * sizeof *items);
        if (!items)
            return ur_error_out_of_memory(error);
        list->items = items;
        size_t *lines = realloc(list->lines, capacity * sizeof *lines);
        if (!lines)
            return ur_error_out_of_memory(error);
        list->lines = lines;
        list->capacity = capacity;
    }
    list->items[list->count] = point;
    list->lines[list->count] = line;
    list->count++;
    return UR_OK;
}

static ur_status parse_coordinate(const char *path, size_t line, char *field, double *value,
                                  ur_error *error)
{
    field = io_trim(field);
    if (*field == '\0')
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: empty field", path, line);
    char *end = NULL;
    double parsed = c_strtod(field, &end);
    if (end == field || *end != '\0')
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: '%.*s' is not a number", path, line,
                            FIELD_QUOTE_MAX, field);
    /* strtod accepts "nan" and "inf" and overflows to infinity: refuse all. */
    if (!isfinite(parsed))
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: '%.*s' is not a finite number", path,
                            line, FIELD_QUOTE_MAX, field);
    if (fabs(parsed) > UR_LENGTH_MAX)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s:%zu: '%.*s' is beyond the largest coordinate unroll takes, %g mm",
                            path, line, FIELD_QUOTE_MAX, field, UR_LENGTH_MAX);
    *value = parsed;
    return UR_OK;
}

/* Splits "x,y,z" (comment already removed) into a point. */
static ur_status parse_point(const char *path, size_t line, char *text, ur_vec3 *point,
                             ur_error *error)
{
    char *fields[3];
    size_t field_count = 0;
    char *cursor = text;
    for (;;) {
        char *comma = strchr(cursor, ',');
        if (field_count < 3)
            fields[field_count] = cursor;
        field_count++;
        if (!comma)
            break;
        *comma = '\0';
        cursor = comma + 1;
    }
    if (field_count != 3)
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: expected 3 fields 'x,y,z', found %zu",
                            path, line, field_count);
    double xyz[3];
    for (int i = 0; i < 3; i++) {
        ur_status status = parse_coordinate(path, line, fields[i], &xyz[i], error);
        if (status != UR_OK)
            return status;
    }
    *point = ur_vec3_make(xyz[0], xyz[1], xyz[2]);
    return UR_OK;
}

static bool same_point(ur_vec3 a, ur_vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

/* Handles one line of the file; blank and comment-only lines add nothing. */
static ur_status read_line(const char *path, size_t line, char *text, point_list *list,
                           ur_error *error)
{
    char *comment = strchr(text, '#');
    if (comment)
        *comment = '\0';
    text = io_trim(text);
    if (*text == '\0')
        return UR_OK;
    ur_vec3 point = {0, 0, 0};
    ur_status status = parse_point(path, line, text, &point, error);
    if (status != UR_OK)
        return status;
    /* A zero-length segment has no direction: tangents would be NaN. */
    if (list->count > 0 && same_point(point, list->items[list->count - 1]))
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: repeats the point on line %zu", path,
                            line, list->lines[list->count - 1]);
    return point_list_push(list, point, line, error);
}

/*
 * Longest line taken.  A curve file is short lines of text; a longer line
 * or a NUL byte means some other kind of file, refused at once rather than
 * read whole into memory (a 1 GB file with no newline, say).
 */
enum { LINE_LENGTH_MAX = 4096 };

static ur_status read_all_lines(FILE *file, const char *path, point_list *list, ur_error *error)
{
    char buffer[LINE_LENGTH_MAX + 1];
    size_t length = 0, line = 1;
    ur_status status = UR_OK;
    errno = 0;
    for (int c = getc(file); status == UR_OK && c != EOF; c = getc(file)) {
        if (c == '\n') {
            buffer[length] = '\0';
            status = read_line(path, line++, buffer, list, error);
            length = 0;
        } else if (c == '\0') {
            status = ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: a NUL byte: not a text file",
                                  path, line);
        } else if (length == LINE_LENGTH_MAX) {
            status = ur_error_set(error, UR_ERROR_INPUT, "%s:%zu: longer than %d characters", path,
                                  line, LINE_LENGTH_MAX);
        } else {
            buffer[length++] = (char)c;
        }
    }
    if (status == UR_OK && length > 0) { /* the last line, without a newline */
        buffer[length] = '\0';
        status = read_line(path, line, buffer, list, error);
    }
    if (status == UR_OK && ferror(file))
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: cannot read: %s", path,
                              strerror(errno ? errno : EIO));
    if (status == UR_ERROR_MEMORY) /* say for which file */
        ur_error_prefix(error, "%s: ", path);
    return status;
}

ur_status ur_curve_csv_read(const char *path, ur_vec3 **points, size_t *count, bool *closed,
                            ur_error *error)
{
    return ur_points_csv_read(path, CURVE_MIN_POINTS, points, count, closed, error);
}

/* Reads the points of file, named path in messages; the file stays the caller's. */
static ur_status read_points(FILE *file, const char *path, size_t min_count, ur_vec3 **points,
                             size_t *count, bool *closed, ur_error *error)
{
    point_list list = {0};
    ur_status status = file ? read_all_lines(file, path, &list, error) : UR_OK;
    if (status != UR_OK) {
        point_list_free(&list);
        return status;
    }
    bool is_closed = list.count > 2 && same_point(list.items[0], list.items[list.count - 1]);
    if (is_closed)
        list.count--;
    if (list.count < min_count) {
        size_t found = list.count;
        point_list_free(&list);
        return ur_error_set(error, UR_ERROR_INPUT, "%s: %s needs at least %zu points, found %zu",
                            path, min_count == CURVE_MIN_POINTS ? "a curve" : "a path", min_count,
                            found);
    }
    free(list.lines);
    *points = list.items;
    *count = list.count;
    *closed = is_closed;
    return UR_OK;
}

ur_status ur_points_csv_read(const char *path, size_t min_count, ur_vec3 **points, size_t *count,
                             bool *closed, ur_error *error)
{
    *points = NULL;
    *count = 0;
    *closed = false;
    FILE *file = fopen(path, "r");
    if (!file)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", path, strerror(errno));
    ur_status status = read_points(file, path, min_count, points, count, closed, error);
    if (fclose(file) != 0 && status == UR_OK) {
        status = ur_error_set(error, UR_ERROR_INPUT, "%s: cannot read: %s", path, strerror(errno));
        free(*points);
        *points = NULL;
        *count = 0;
    }
    return status;
}

ur_status ur_points_csv_read_buffer(const char *name, const void *data, size_t size,
                                    size_t min_count, ur_vec3 **points, size_t *count, bool *closed,
                                    ur_error *error)
{
    *points = NULL;
    *count = 0;
    *closed = false;
    /* Read through a stream over the buffer: the very code that reads a file. */
    FILE *file = NULL;
    if (size > 0) {
        file = fmemopen((void *)data, size, "r"); /* "r": the buffer is only read */
        if (!file)
            return ur_error_set(error, UR_ERROR_INTERNAL, "%s: cannot read the buffer: %s", name,
                                strerror(errno));
    }
    ur_status status = read_points(file, name, min_count, points, count, closed, error);
    if (file)
        fclose(file); /* nothing was written: closing cannot lose anything */
    return status;
}

ur_status ur_curve_csv_read_buffer(const char *name, const void *data, size_t size,
                                   ur_vec3 **points, size_t *count, bool *closed, ur_error *error)
{
    return ur_points_csv_read_buffer(name, data, size, CURVE_MIN_POINTS, points, count, closed,
                                     error);
}

/* ---- Writing ----------------------------------------------------------- */

typedef struct curve_text {
    const ur_vec3 *points;
    size_t count;
} curve_text;

/* The emitter for atomic_write: a comment line, then one point per line. */
static bool emit_points(FILE *file, const void *data)
{
    const curve_text *curve = data;
    if (c_fprintf(file, "# unroll curve: x,y,z in mm, %zu points\n", curve->count) < 0)
        return false;
    for (size_t i = 0; i < curve->count; i++) {
        const ur_vec3 *p = &curve->points[i];
        /* %.17g round-trips every double exactly. */
        if (c_fprintf(file, "%.17g,%.17g,%.17g\n", p->x, p->y, p->z) < 0)
            return false;
    }
    return true;
}

static ur_status check_finite(const char *path, const ur_vec3 *points, size_t count,
                              ur_error *error)
{
    for (size_t i = 0; i < count; i++)
        if (!isfinite(points[i].x) || !isfinite(points[i].y) || !isfinite(points[i].z))
            return ur_error_set(error, UR_ERROR_INTERNAL,
                                "%s: point %zu is not finite; refusing to write it", path, i + 1);
    return UR_OK;
}

ur_status ur_curve_csv_write(const char *path, const ur_vec3 *points, size_t count,
                             ur_context *context, ur_error *error)
{
    /* The reader would refuse NaN: better to fail here than write a bad file. */
    ur_status status = check_finite(path, points, count, error);
    if (status != UR_OK)
        return status;
    curve_text curve = {points, count};
    return atomic_write(path, emit_points, &curve, "curve", context, error);
}

ur_status ur_curve_csv_write_stream(FILE *stream, const ur_vec3 *points, size_t count,
                                    ur_error *error)
{
    ur_status status = check_finite("the curve", points, count, error);
    if (status != UR_OK)
        return status;
    curve_text curve = {points, count};
    return atomic_stream_write(stream, emit_points, &curve, "curve", error);
}
