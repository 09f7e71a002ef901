/*
 * parts_check.h: what fuzz_svg.c and fuzz_dxf.c check on the parts the
 * importer accepted (src/io/parts_import.c), header-only: the promises of
 * ur_parts_import in unroll/io.h.
 */
#ifndef UNROLL_FUZZ_PARTS_CHECK_H
#define UNROLL_FUZZ_PARTS_CHECK_H

#include "fuzz_support.h"

#include <math.h>

#include "unroll/io.h"

/* A ring (outline or hole), or a line that goes with the part (open, or not a cut). */
static inline bool is_ring(const ur_path *path)
{
    return path->op == UR_OP_CUT && path->closed;
}

static inline void check_path(const ur_path *path)
{
    FUZZ_CHECK(path->op < UR_OP_COUNT);
    FUZZ_CHECK(path->count >= (path->closed ? 3u : 2u) && path->points != NULL);
    for (size_t i = 0; i < path->count; i++) {
        ur_vec2 p = path->points[i];
        FUZZ_CHECK(isfinite(p.x) && isfinite(p.y));
        FUZZ_CHECK(fabs(p.x) <= UR_PARTS_IMPORT_MAX_COORDINATE &&
                   fabs(p.y) <= UR_PARTS_IMPORT_MAX_COORDINATE);
    }
}

/* Twice the signed area of a ring: positive counter-clockwise. */
static inline double ring_area2(const ur_path *path)
{
    double sum = 0.0;
    for (size_t i = 0; i < path->count; i++) {
        ur_vec2 a = path->points[i], b = path->points[(i + 1) % path->count];
        sum += a.x * b.y - b.x * a.y;
    }
    return sum;
}

static inline void check_parts(const ur_parts *parts)
{
    FUZZ_CHECK(parts->count > 0 && parts->pieces != NULL);
    for (size_t k = 0; k < parts->count; k++) {
        const ur_piece *piece = &parts->pieces[k];
        FUZZ_CHECK(memchr(piece->name, '\0', sizeof piece->name) != NULL);
        FUZZ_CHECK(piece->path_count >= 1);
        FUZZ_CHECK(is_ring(&piece->paths[0]));
        for (size_t i = 0; i < piece->path_count; i++) {
            check_path(&piece->paths[i]);
            /* The outline runs counter-clockwise, its holes clockwise. */
            double area2 = ring_area2(&piece->paths[i]);
            if (is_ring(&piece->paths[i]))
                FUZZ_CHECK(i == 0 ? area2 > 0 : area2 < 0);
        }
        FUZZ_CHECK(isfinite(piece->measures.flat_area) && piece->measures.flat_area > 0);
    }
    for (size_t i = 0; i < parts->warning_count; i++)
        FUZZ_CHECK(memchr(parts->warnings[i], '\0', sizeof parts->warnings[i]) != NULL);
}

/*
 * Reads size bytes of data as parts of a file called name, in millimetres
 * when it does not say, and checks them.
 */
static inline void import_and_check(const char *name, const uint8_t *data, size_t size)
{
    ur_parts_import_options options;
    ur_parts_import_options_default(&options);
    options.unit = 1.0; /* so that files without units are read on, not refused */
    ur_parts parts;
    ur_error error;
    if (ur_parts_import_buffer(name, data, size, &options, &parts, &error) == UR_OK) {
        check_parts(&parts);
        ur_parts_free(&parts);
    } else {
        FUZZ_CHECK(parts.count == 0 && parts.pieces == NULL);
        FUZZ_CHECK(error.message[0] != '\0');
    }
}

#endif
