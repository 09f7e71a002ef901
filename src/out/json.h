/*
 * json.h: shared pieces of the JSON reports (json.c), private to src/out.
 */
#ifndef UNROLL_OUT_JSON_H
#define UNROLL_OUT_JSON_H

#include <jansson.h>

#include "unroll/surface.h"

/* Writes root to path ("-" for standard output), atomically for a file. */
ur_status json_write(const char *path, json_t *root, ur_context *context, ur_error *error);

/* The same to a stream the caller owns (flushed, not closed). */
ur_status json_write_stream(FILE *stream, json_t *root, ur_error *error);

/* A number, or null when it is not finite (JSON has no NaN or infinity). */
json_t *json_number(double value);

/* [x, y, z] */
json_t *json_point(ur_vec3 p);

/* Intervals of rail 1 (the gaps of a domain of existence); NULL without memory. */
json_t *json_intervals(const ur_interval *intervals, size_t count);

#endif
