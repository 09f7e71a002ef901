/*
 * json.c: what the JSON reports share: writing a document atomically (or to
 * standard output for "-") and the shapes that appear in several reports.
 */
#include "json.h"

#include "../base/atomic.h"

/* Every real with the 17 digits that make it read back exactly. */
#define JSON_FLAGS (JSON_INDENT(2) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(17))

json_t *json_number(double value)
{
    if (value == 0)
        value = 0.0; /* -0 is zero: a developable's curvature is not negative */
    return isfinite(value) ? json_real(value) : json_null();
}

json_t *json_point(ur_vec3 p)
{
    return json_pack("[fff]", p.x, p.y, p.z);
}

json_t *json_intervals(const ur_interval *intervals, size_t count)
{
    json_t *array = json_array();
    for (size_t k = 0; array && k < count; k++) {
        const ur_interval *gap = &intervals[k];
        json_t *item =
            json_pack("{s:f, s:f, s:f, s:f, s:o, s:o, s:s}", "u_start", gap->u_start, "u_end",
                      gap->u_end, "arc_start_mm", gap->arc_start, "arc_end_mm", gap->arc_end,
                      "start", json_point(gap->start), "end", json_point(gap->end), "reason",
                      gap->reason == UR_GAP_NO_RULING ? "no ruling" : "rulings cross");
        if (!item || json_array_append_new(array, item) != 0) {
            json_decref(array);
            return NULL;
        }
    }
    return array;
}

static bool emit_json(FILE *stream, const void *root)
{
    return json_dumpf(root, stream, JSON_FLAGS) == 0 && fputc('\n', stream) != EOF;
}

ur_status json_write(const char *path, json_t *root, ur_context *context, ur_error *error)
{
    return atomic_write(path, emit_json, root, "report", context, error);
}

ur_status json_write_stream(FILE *stream, json_t *root, ur_error *error)
{
    return atomic_stream_write(stream, emit_json, root, "report", error);
}
