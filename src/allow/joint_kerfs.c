/*
 * joint_kerfs.c: hinges and joints agree.  Kerf lines (bending grooves,
 * living-hinge slits, kerfing cuts) go on before the joints, which then add
 * folds and marks where they will: a slit on a lap zone's mark line cuts
 * through where the glue goes, a groove across a tab's fold weakens the
 * fold.  Once the joints are on, every kerf line is cut back to keep
 * `clearance` from each fold and mark line the joints drew (GEOS: the
 * lines minus the union of the joint lines buffered by the clearance);
 * what is left of a line shorter than `shortest` is dropped.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* GEOS rounds the buffer's ends with this many segments per quarter circle. */
enum { QUADRANT_SEGMENTS = 8 };

static bool is_joint_line(const ur_path *path)
{
    return path->count >= 2 &&
           (path->op == UR_OP_MARK || path->op == UR_OP_SCORE || path->op == UR_OP_SCORE_VALLEY);
}

static bool is_kerf_line(const ur_path *path)
{
    return path->op == UR_OP_KERF && !path->closed && path->count >= 2;
}

/* The joint lines of paths[first ..] buffered by clearance, united; NULL when none (or GEOS fails).
 */
static GEOSGeometry *keep_out(GEOSContextHandle_t geos, const ur_piece *piece, size_t first,
                              double clearance, bool *failed)
{
    GEOSGeometry *all = NULL;
    *failed = false;
    for (size_t i = first; i < piece->path_count && !*failed; i++) {
        const ur_path *path = &piece->paths[i];
        if (!is_joint_line(path))
            continue;
        ur_vec2 *points = path->points;
        size_t count = path->count;
        ur_vec2 *ring = NULL;
        if (path->closed) { /* a closed ring as a line: its first point again at the end */
            ring = malloc((count + 1) * sizeof *ring);
            if (!ring) {
                *failed = true;
                break;
            }
            memcpy(ring, points, count * sizeof *ring);
            ring[count] = points[0];
            points = ring;
            count++;
        }
        GEOSGeometry *line = allow_line(geos, points, count);
        free(ring);
        GEOSGeometry *band = line ? GEOSBuffer_r(geos, line, clearance, QUADRANT_SEGMENTS) : NULL;
        if (line)
            GEOSGeom_destroy_r(geos, line);
        GEOSGeometry *united = band && all ? GEOSUnion_r(geos, all, band) : NULL;
        if (!band || (all && !united)) {
            *failed = true;
            if (band)
                GEOSGeom_destroy_r(geos, band);
            break;
        }
        if (all) {
            GEOSGeom_destroy_r(geos, all);
            GEOSGeom_destroy_r(geos, band);
            all = united;
        } else
            all = band;
    }
    if (*failed && all) {
        GEOSGeom_destroy_r(geos, all);
        all = NULL;
    }
    return all;
}

/*
 * The points of a GEOS line string into a new array (*count 0 and no
 * array when it is none: a point where the line only touched).
 */
static ur_status line_points(GEOSContextHandle_t geos, const GEOSGeometry *line, ur_vec2 **points,
                             size_t *count, ur_error *error)
{
    *points = NULL;
    *count = 0;
    if (GEOSGeomTypeId_r(geos, line) != GEOS_LINESTRING)
        return UR_OK;
    const GEOSCoordSequence *sequence = GEOSGeom_getCoordSeq_r(geos, line);
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size) || size < 2)
        return UR_OK;
    *points = ur_alloc_array(size, sizeof **points, error);
    if (!*points)
        return UR_ERROR_MEMORY;
    for (unsigned k = 0; k < size; k++)
        GEOSCoordSeq_getXY_r(geos, sequence, k, &(*points)[k].x, &(*points)[k].y);
    *count = size;
    return UR_OK;
}

/*
 * Replaces kerf line `index` by its parts outside `out`, appended at the
 * end; the line itself is emptied (count 0) for removal.  *cut says
 * whether it lost anything.
 */
static ur_status trim_line(GEOSContextHandle_t geos, ur_piece *piece, size_t index,
                           const GEOSGeometry *out, double shortest, bool *cut, ur_error *error)
{
    ur_path *path = &piece->paths[index];
    GEOSGeometry *line = allow_line(geos, path->points, path->count);
    if (!line)
        return ur_error_out_of_memory(error);
    *cut = GEOSIntersects_r(geos, line, out) == 1;
    if (!*cut) {
        GEOSGeom_destroy_r(geos, line);
        return UR_OK;
    }
    GEOSGeometry *kept = GEOSDifference_r(geos, line, out);
    GEOSGeom_destroy_r(geos, line);
    if (!kept)
        return ur_error_set(error, UR_ERROR_INTERNAL, "piece %s: GEOS could not cut a kerf line",
                            piece->name);
    free(path->points);
    path->points = NULL;
    path->count = 0;
    ur_status status = UR_OK;
    int parts = GEOSGetNumGeometries_r(geos, kept);
    for (int k = 0; k < parts && status == UR_OK; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(geos, kept, k);
        ur_vec2 *points = NULL;
        size_t count = 0;
        if (part)
            status = line_points(geos, part, &points, &count, error);
        /* A failed allocation must fail the run: the line would be cut short silently. */
        if (status == UR_OK && count > 0 && ur_polyline_length(points, count, false) >= shortest)
            status = ur_piece_add_path(piece, UR_OP_KERF, points, count, false, error);
        free(points);
    }
    GEOSGeom_destroy_r(geos, kept);
    return status;
}

/*
 * Drops the paths trim_line emptied, keeping the others in order; a
 * label's record moves with its strokes (never a kerf line, so they stay
 * together).
 */
static void drop_empty(ur_piece *piece)
{
    size_t kept = 0;
    for (size_t i = 0; i < piece->path_count; i++) {
        if (piece->paths[i].count == 0 && i > 0)
            continue;
        for (size_t r = 0; r < piece->record_count; r++)
            if (piece->records[r].path_count > 0 && piece->records[r].first_path == i)
                piece->records[r].first_path = kept;
        piece->paths[kept++] = piece->paths[i];
    }
    piece->path_count = kept;
}

ur_status ur_piece_keep_kerfs_off_joints(ur_piece *piece, size_t first, double clearance,
                                         double shortest, size_t *trimmed, ur_error *error)
{
    *trimmed = 0;
    if (!(clearance > 0) || !isfinite(clearance) || !(shortest >= 0))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece %s: kerf lines keep a positive clearance from the joints",
                            piece->name);
    bool any = false;
    for (size_t i = 1; i < piece->path_count && !any; i++)
        any = is_kerf_line(&piece->paths[i]);
    if (!any)
        return UR_OK; /* a papercraft piece's many tabs need no buffering */
    GEOSContextHandle_t geos = GEOS_init_r();
    if (!geos)
        return ur_error_out_of_memory(error);
    bool failed = false;
    GEOSGeometry *out = keep_out(geos, piece, first, clearance, &failed);
    ur_status status =
        failed ? ur_error_set(error, UR_ERROR_INTERNAL,
                              "piece %s: GEOS could not buffer the joint lines", piece->name)
               : UR_OK;
    size_t count = piece->path_count; /* the parts appended are clear already */
    for (size_t i = 1; out && status == UR_OK && i < count; i++) {
        if (!is_kerf_line(&piece->paths[i]))
            continue;
        bool cut = false;
        status = trim_line(geos, piece, i, out, shortest, &cut, error);
        *trimmed += cut;
    }
    drop_empty(piece);
    if (out)
        GEOSGeom_destroy_r(geos, out);
    GEOS_finish_r(geos);
    ur_piece_recompute_box(piece);
    return status;
}
