/*
 * fuzz_csv.c: fuzz target for curves as CSV (src/io/csv.c), and for what
 * the command does next with an accepted curve: interpolate it with splines
 * (src/surface/curve.c) and evaluate it.
 *
 * The first byte picks the least number of points (2 for a seam path, 4
 * for a curve), as the two callers ask; the rest is the file.
 */
#include "fuzz_support.h"

#include <math.h>
#include <stdbool.h>

#include "unroll/io.h"
#include "unroll/surface.h"

/* An accepted curve is what the reader promises: enough finite points, none repeated. */
static void check_points(const ur_vec3 *points, size_t count, size_t min_count)
{
    FUZZ_CHECK(points != NULL && count >= min_count);
    for (size_t i = 0; i < count; i++) {
        FUZZ_CHECK(isfinite(points[i].x) && isfinite(points[i].y) && isfinite(points[i].z));
        if (i > 0)
            FUZZ_CHECK(points[i].x != points[i - 1].x || points[i].y != points[i - 1].y ||
                       points[i].z != points[i - 1].z);
    }
}

/* The spline through the points, evaluated along it: NaN is allowed, a crash is not. */
static void interpolate(const ur_vec3 *points, size_t count, bool closed)
{
    ur_curve *curve = NULL;
    ur_error error;
    if (ur_curve_new_interpolating(points, count, closed, &curve, &error) != UR_OK)
        return;
    double start = ur_curve_start(curve), end = ur_curve_end(curve);
    for (int i = 0; i <= 8; i++) {
        ur_vec3 derivatives[3];
        ur_curve_eval(curve, start + (end - start) * i / 8.0, derivatives);
    }
    ur_curve_free(curve);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    size_t min_count = data[0] & 1 ? 2 : 4;
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = false;
    ur_error error;
    if (ur_points_csv_read_buffer("curve.csv", data + 1, size - 1, min_count, &points, &count,
                                  &closed, &error) != UR_OK) {
        FUZZ_CHECK(points == NULL && count == 0);
        FUZZ_CHECK(strstr(error.message, "curve.csv") == error.message);
        return 0;
    }
    check_points(points, count, min_count);
    if (count >= 4)
        interpolate(points, count, closed);
    free(points);
    return 0;
}
