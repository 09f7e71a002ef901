/*
 * relief_slits.c: the cuts of the relief (relief.c): kerfing slits that
 * open, overlap slits with their zones, kept clear of the cuts made
 * before and clipped to the net, and the record of what a region needed.
 */
#include "relief_internal.h"

#include "../base/c_locale.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ur_status relief_geos_failed(relief_job *job, const char *what)
{
    return ur_error_set(job->error, UR_ERROR_INTERNAL, "GEOS failed to %s for piece '%s'", what,
                        job->piece->name);
}

ur_vec2 relief_perpendicular(ur_vec2 v)
{
    return ur_vec2_make(-v.y, v.x);
}

/* ---- GEOS helpers --------------------------------------------------- */

/*
 * The points of a line string or a ring (closed: its last point is dropped);
 * when GEOS cannot give them, the job fails saying it could not do what.
 */
static ur_status geometry_points(relief_job *job, const GEOSGeometry *line, ur_points *points,
                                 bool drop_last, const char *what)
{
    GEOSContextHandle_t geos = job->geos;
    const GEOSCoordSequence *sequence = line ? GEOSGeom_getCoordSeq_r(geos, line) : NULL;
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size))
        return relief_geos_failed(job, what);
    if (drop_last && size > 0)
        size--;
    for (unsigned i = 0; i < size; i++) {
        ur_vec2 p;
        GEOSCoordSeq_getXY_r(geos, sequence, i, &p.x, &p.y);
        ur_status status = ur_points_push(points, p, job->error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* The ends of each line string part of geometry, in order: parts[2 k], parts[2 k + 1]. */
static ur_status line_parts(relief_job *job, const GEOSGeometry *geometry, ur_points *ends)
{
    int parts = GEOSGetNumGeometries_r(job->geos, geometry);
    for (int k = 0; k < parts; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(job->geos, geometry, k);
        if (!part || GEOSGeomTypeId_r(job->geos, part) != GEOS_LINESTRING)
            continue;
        ur_points points = {0};
        ur_status status = geometry_points(job, part, &points, false, "read a line");
        if (status != UR_OK) {
            ur_points_free(&points);
            return status;
        }
        if (points.count >= 2) {
            status = ur_points_push(ends, points.items[0], job->error);
            if (status == UR_OK)
                status = ur_points_push(ends, points.items[points.count - 1], job->error);
        }
        ur_points_free(&points);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* The ends of the parts of segment a b inside area and, unless avoid is NULL, outside avoid. */
ur_status relief_clip_segment(relief_job *job, ur_vec2 a, ur_vec2 b, const GEOSGeometry *area,
                              const GEOSGeometry *avoid, ur_points *ends)
{
    ur_vec2 ab[2] = {a, b};
    GEOSGeometry *line = allow_line(job->geos, ab, 2);
    GEOSGeometry *inside = line ? GEOSIntersection_r(job->geos, line, area) : NULL;
    if (inside && avoid) {
        GEOSGeometry *clear = GEOSDifference_r(job->geos, inside, avoid);
        GEOSGeom_destroy_r(job->geos, inside);
        inside = clear;
    }
    ur_status status =
        inside ? line_parts(job, inside, ends) : relief_geos_failed(job, "clip a slit");
    if (inside)
        GEOSGeom_destroy_r(job->geos, inside);
    if (line)
        GEOSGeom_destroy_r(job->geos, line);
    return status;
}

/* Adds the exterior ring of every polygon of geometry as a closed path. */
static ur_status add_rings(relief_job *job, const GEOSGeometry *geometry, ur_op op)
{
    int parts = GEOSGetNumGeometries_r(job->geos, geometry);
    ur_status status = UR_OK;
    for (int k = 0; status == UR_OK && k < parts; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(job->geos, geometry, k);
        if (!part || GEOSGeomTypeId_r(job->geos, part) != GEOS_POLYGON)
            continue;
        const GEOSGeometry *ring = GEOSGetExteriorRing_r(job->geos, part);
        ur_points points = {0};
        status = geometry_points(job, ring, &points, true, "read an overlap zone");
        if (status == UR_OK && points.count >= 3)
            status =
                ur_piece_add_path(job->piece, op, points.items, points.count, true, job->error);
        ur_points_free(&points);
    }
    return status;
}

/* Adds the part of an open polyline inside the outline as paths of op. */
static ur_status add_clipped_polyline(relief_job *job, const ur_vec2 *points, size_t count,
                                      ur_op op)
{
    GEOSGeometry *line = allow_line(job->geos, points, count);
    GEOSGeometry *inside = line ? GEOSIntersection_r(job->geos, line, job->outline) : NULL;
    ur_status status = inside ? UR_OK : relief_geos_failed(job, "clip a dart");
    GEOSGeometry *merged = inside ? GEOSLineMerge_r(job->geos, inside) : NULL;
    const GEOSGeometry *use = merged ? merged : inside;
    int parts = use ? GEOSGetNumGeometries_r(job->geos, use) : 0;
    for (int k = 0; status == UR_OK && k < parts; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(job->geos, use, k);
        if (!part || GEOSGeomTypeId_r(job->geos, part) != GEOS_LINESTRING)
            continue;
        ur_points got = {0};
        status = geometry_points(job, part, &got, false, "read a dart");
        if (status == UR_OK && got.count >= 2)
            status = ur_piece_add_path(job->piece, op, got.items, got.count, false, job->error);
        ur_points_free(&got);
    }
    if (merged)
        GEOSGeom_destroy_r(job->geos, merged);
    if (inside)
        GEOSGeom_destroy_r(job->geos, inside);
    if (line)
        GEOSGeom_destroy_r(job->geos, line);
    return status;
}

/* ---- Slits ------------------------------------------------------------ */

/*
 * Adds a relief cut (an open polyline) to the keep-out: no later relief
 * cut comes within margin of it, so that no two cross and no part of the
 * piece is cut loose between them and the outline.
 */
static ur_status keep_out(relief_job *job, const ur_vec2 *points, size_t count)
{
    double distance = fmax(job->limits->margin, 1e-6 * job->size);
    GEOSGeometry *line = allow_line(job->geos, points, count);
    GEOSGeometry *zone = line ? GEOSBuffer_r(job->geos, line, distance, 4) : NULL;
    if (line)
        GEOSGeom_destroy_r(job->geos, line);
    if (zone && job->keepout) {
        GEOSGeometry *joined = GEOSUnion_r(job->geos, job->keepout, zone);
        GEOSGeom_destroy_r(job->geos, zone);
        zone = joined;
        if (joined)
            GEOSGeom_destroy_r(job->geos, job->keepout);
    }
    if (!zone)
        return relief_geos_failed(job, "keep slits apart");
    job->keepout = zone;
    return UR_OK;
}

/*
 * Adds the relief cuts of one region, the piece's KERF paths from first on,
 * to the keep-out once the region is done: its own slits are parallel and
 * may lie closer than margin to each other.
 */
ur_status relief_keep_out_since(relief_job *job, size_t first)
{
    ur_status status = UR_OK;
    for (size_t i = first; status == UR_OK && i < job->piece->path_count; i++)
        if (job->piece->paths[i].op == UR_OP_KERF)
            status = keep_out(job, job->piece->paths[i].points, job->piece->paths[i].count);
    return status;
}

static ur_status add_cut(relief_job *job, const ur_vec2 *points, size_t count)
{
    return ur_piece_add_path(job->piece, UR_OP_KERF, points, count, false, job->error);
}

/* One KERF slit: the parts of segment a b inside area, those shorter than opening dropped. */
ur_status relief_kerfing_slit(relief_job *job, ur_vec2 a, ur_vec2 b, const GEOSGeometry *area,
                              bool *cut)
{
    ur_points ends = {0};
    ur_status status = relief_clip_segment(job, a, b, area, job->keepout, &ends);
    *cut = false;
    for (size_t i = 0; status == UR_OK && i + 1 < ends.count; i += 2) {
        if (ur_vec2_distance(ends.items[i], ends.items[i + 1]) < job->limits->opening)
            continue;
        status = add_cut(job, &ends.items[i], 2);
        *cut = true;
    }
    ur_points_free(&ends);
    return status;
}

/*
 * Where an overlap slit from start along unit u may end near `target`
 * (a distance along u): the point of the chord inside the inner outline
 * nearest to it, preferring one short of it.  False when none is.
 */
static ur_status slit_end(relief_job *job, ur_vec2 start, ur_vec2 u, double length, double target,
                          double *end, bool *found)
{
    ur_points ends = {0};
    *found = false;
    ur_status status = relief_clip_segment(job, start, ur_vec2_add_scaled(start, u, length),
                                           job->inner, NULL, &ends);
    double best_below = -1, best_above = INFINITY;
    for (size_t i = 0; status == UR_OK && i + 1 < ends.count; i += 2) {
        double a = ur_vec2_dot(ur_vec2_sub(ends.items[i], start), u);
        double b = ur_vec2_dot(ur_vec2_sub(ends.items[i + 1], start), u);
        double low = fmin(a, b), high = fmax(a, b);
        if (low <= target && target <= high)
            best_below = target;
        else if (high < target)
            best_below = fmax(best_below, high);
        else
            best_above = fmin(best_above, low);
    }
    ur_points_free(&ends);
    if (best_below > 0) {
        *end = best_below;
        *found = true;
    } else if (isfinite(best_above)) {
        *end = best_above;
        *found = true;
    }
    return status;
}

/*
 * One overlap slit (or dart) from start, on the outline, along unit u to
 * the distance `end`, with its zone of width w on the side `side` over the
 * distances zone_from to end.
 */
static ur_status overlap_slit(relief_job *job, ur_vec2 start, ur_vec2 u, double zone_from,
                              double end, double w, ur_vec2 side)
{
    ur_vec2 tip = ur_vec2_add_scaled(start, u, end);
    if (job->limits->darts) {
        double reach = w + 0.01 * end; /* the arms start outside and are clipped to the outline */
        ur_vec2 base = ur_vec2_add_scaled(start, u, -reach);
        ur_vec2 v[3] = {ur_vec2_add_scaled(base, side, 0.5 * w * (end + reach) / end), tip,
                        ur_vec2_add_scaled(base, side, -0.5 * w * (end + reach) / end)};
        return add_clipped_polyline(job, v, 3, UR_OP_KERF);
    }
    ur_vec2 slit[2] = {start, tip};
    ur_status status = add_cut(job, slit, 2);
    if (status != UR_OK || !(end - zone_from > 0))
        return status;
    ur_vec2 from = ur_vec2_add_scaled(start, u, fmax(zone_from, 0));
    ur_vec2 zone[4] = {from, tip, ur_vec2_add_scaled(tip, side, w),
                       ur_vec2_add_scaled(from, side, w)};
    if (ur_polygon_signed_area(zone, 4) < 0) {
        ur_vec2 swap = zone[1];
        zone[1] = zone[3];
        zone[3] = swap;
    }
    GEOSGeometry *polygon = geos_polygon_of_ring(job->geos, zone, 4);
    GEOSGeometry *inside = polygon ? GEOSIntersection_r(job->geos, polygon, job->outline) : NULL;
    status = inside ? add_rings(job, inside, UR_OP_MARK) : relief_geos_failed(job, "mark a zone");
    if (inside)
        GEOSGeom_destroy_r(job->geos, inside);
    if (polygon)
        GEOSGeom_destroy_r(job->geos, polygon);
    return status;
}

/*
 * Shortens the slit from start along u to where it first comes within
 * margin of an earlier relief cut; found false when it starts there or its
 * new end is less than margin from the outline.
 */
static ur_status clear_length(relief_job *job, ur_vec2 start, ur_vec2 u, double *end, bool *found)
{
    ur_points ends = {0};
    ur_status status =
        relief_clip_segment(job, ur_vec2_add_scaled(start, u, -1e-3),
                            ur_vec2_add_scaled(start, u, *end), job->outline, job->keepout, &ends);
    *found = false;
    for (size_t i = 0; status == UR_OK && i + 1 < ends.count; i += 2) {
        double a = ur_vec2_dot(ur_vec2_sub(ends.items[i], start), u);
        double b = ur_vec2_dot(ur_vec2_sub(ends.items[i + 1], start), u);
        if (fmin(a, b) > 1e-6 * job->size)
            continue; /* not the part from the start */
        *found = fmax(a, b) >= *end - 1e-9 * job->size;
        if (!*found) { /* shortened: its new end must still be margin inside */
            *end = fmax(a, b);
            GEOSGeometry *point =
                GEOSGeom_createPointFromXY_r(job->geos, start.x + *end * u.x, start.y + *end * u.y);
            *found = point && GEOSIntersects_r(job->geos, point, job->inner) == 1;
            if (point)
                GEOSGeom_destroy_r(job->geos, point);
        }
    }
    ur_points_free(&ends);
    return status;
}

/*
 * An overlap slit on the chord a b (both on the outline) whose part in the
 * region lies between distances low and high from a: from the nearer end
 * of the chord through that part.
 */
ur_status relief_overlap_on_chord(relief_job *job, ur_vec2 a, ur_vec2 b, double low, double high,
                                  double w, ur_vec2 side, bool *cut)
{
    double length = ur_vec2_distance(a, b);
    *cut = false;
    if (!(length > 0))
        return UR_OK;
    ur_vec2 u = ur_vec2_scale(ur_vec2_sub(b, a), 1 / length);
    ur_vec2 start = a;
    double from = low, target = high;
    if (low > length - high) { /* the region is nearer b: start there */
        start = b;
        u = ur_vec2_scale(u, -1);
        from = length - high;
        target = length - low;
    }
    double end = 0;
    bool found = false;
    ur_status status = slit_end(job, start, u, length, target, &end, &found);
    if (status == UR_OK && found && job->keepout)
        status = clear_length(job, start, u, &end, &found);
    if (status != UR_OK || !found || end < job->limits->opening || end <= from)
        return status;
    *cut = true;
    return overlap_slit(job, start, u, fmin(from, end), end, w, side);
}

/* ---- Records ---------------------------------------------------------- */

ur_status relief_record_need(relief_job *job, const relief_need *need, const char *across)
{
    ur_allowance_record record = {0};
    bool kerfing = need->kind == RELIEF_KERFING;
    record.kind = kerfing ? UR_ALLOWANCE_KERFING : UR_ALLOWANCE_OVERLAP;
    record.count = need->cut;
    record.value = need->value;
    record.limit = need->limit;
    record.where = need->where;
    record.warning = need->cut < need->wanted;
    char missing[96] = "", reason[512];
    if (record.warning)
        c_snprintf(missing, sizeof missing,
                   "; only %zu fit, %.3g mm clear of the outline and slits", need->cut,
                   job->limits->margin);
    if (kerfing)
        c_snprintf(reason, sizeof reason,
                   "the net is %.3g mm shorter than the surface %s (forming needs %.3g %% stretch, "
                   "the material takes %.3g %%): %zu kerfing slits opening up to %.3g mm%s",
                   need->length, across, 100 * need->value, 100 * need->limit, need->wanted,
                   job->limits->opening, missing);
    else
        c_snprintf(reason, sizeof reason,
                   "the net is %.3g mm longer than the surface %s (forming needs %.3g %% "
                   "compression, the material takes %.3g %%): %zu overlap %s %.3g mm%s",
                   need->length, across, 100 * need->value, 100 * need->limit, need->wanted,
                   job->limits->darts ? "darts, each as wide at the outline as"
                                      : "slits, each lapping",
                   need->length / (double)need->wanted, missing);
    size_t length = strlen(reason); /* at most what the record holds */
    length = length < sizeof record.reason ? length : sizeof record.reason - 1;
    memcpy(record.reason, reason, length);
    record.reason[length] = '\0';
    return ur_piece_record(job->piece, &record, job->error);
}

/* n = ceil(length / opening), at least 1, at most one per opening of span and RELIEF_MAX_SLITS. */
size_t relief_slit_count(double length, double opening, double span)
{
    double n = ceil(length / opening - 1e-9);
    n = fmin(n, fmax(1, floor(span / opening)));
    n = fmin(n, RELIEF_MAX_SLITS);
    return n < 1 ? 1 : (size_t)n;
}
