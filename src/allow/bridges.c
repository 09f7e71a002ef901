/*
 * bridges.c: holding bridges, short stretches of the outline left uncut so
 * that a part stays in the sheet until it is broken out (a router would
 * otherwise throw it, a laser let it drop and tilt into the beam).
 *
 * Positions are arc lengths along the outline from its first point.  The
 * gaps are spread evenly, then kept off corners, where a bridge would leave
 * a nub that spoils the corner and holds poorly:
 *
 *   A corner is a stretch of the outline no longer than three gap widths
 *   (a gap and its clearance on either side) over which the direction
 *   turns by more than 30 degrees in all, counting every vertex's turn
 *   whatever its side, and which would not without its first or its last
 *   vertex (so a slight bend on the way into a sharp corner is no part of
 *   it).  A single vertex turning more than 30 degrees is one; so is a
 *   curve tighter than a radius of about 5.7 gap widths (3 w / (pi / 6)),
 *   or a few small turns close together.
 *
 * Every gap keeps at least its own width of cut between it and every
 * corner, and between it and the next gap.
 */
#include "unroll/allow.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

#define BRIDGE_CORNER_TURN (30.0 * M_PI / 180.0)
#define BRIDGE_CORNER_REACH 3.0        /* gap widths */
#define BRIDGE_AUTOMATIC_SPACING 300.0 /* mm of outline per bridge */
#define BRIDGE_OFFSETS 64 /* even spreads tried besides the allowed stretches' middles */

/* A closed interval of arc length, lo <= hi, within [0, length] of the outline. */
typedef struct span {
    double lo, hi;
} span;

typedef struct spans {
    span *items;
    size_t count, capacity;
} spans;

/* The outline as arc lengths: at[i] is where point i is, length the whole ring. */
typedef struct ring {
    const ur_vec2 *points;
    size_t count;
    double *at;
    double length;
} ring;

static ur_status spans_push(spans *list, double lo, double hi, ur_error *error)
{
    span *items =
        ur_array_grow(list->items, &list->capacity, list->count, sizeof *list->items, 16, error);
    if (!items)
        return UR_ERROR_MEMORY;
    list->items = items;
    list->items[list->count++] = (span){lo, hi};
    return UR_OK;
}

/* Pushes [lo, hi] (any reals) folded into [0, length] as one or two spans. */
static ur_status spans_push_circular(spans *list, double lo, double hi, double length,
                                     ur_error *error)
{
    if (hi - lo >= length)
        return spans_push(list, 0, length, error);
    double shift = floor(lo / length) * length;
    lo -= shift;
    hi -= shift;
    if (hi <= length)
        return spans_push(list, lo, hi, error);
    ur_status status = spans_push(list, lo, length, error);
    return status == UR_OK ? spans_push(list, 0, hi - length, error) : status;
}

static int compare_spans(const void *a, const void *b)
{
    const span *x = a, *y = b;
    return (x->lo > y->lo) - (x->lo < y->lo);
}

/* Distance from t to s going either way round a ring of that length (0 inside s). */
static double circular_distance(span s, double t, double length)
{
    double best = INFINITY;
    for (int m = -1; m <= 1; m++) {
        double u = t + m * length;
        double d = u < s.lo ? s.lo - u : u > s.hi ? u - s.hi : 0;
        if (d < best)
            best = d;
    }
    return best;
}

/* ---- Where gaps may go ------------------------------------------------- */

static double turn_at(const ur_vec2 *p, size_t n, size_t i)
{
    ur_vec2 in = ur_vec2_sub(p[i], p[(i + n - 1) % n]);
    ur_vec2 out = ur_vec2_sub(p[(i + 1) % n], p[i]);
    return fabs(atan2(ur_vec2_cross(in, out), ur_vec2_dot(in, out)));
}

/*
 * The corners (see the top of the file), each grown by the clearance a gap
 * centre needs, 1.5 widths, as spans of forbidden centres.  From each
 * turning vertex the turns are summed on until they pass the limit within
 * reach: the shortest corner starting there.  It counts only when its first
 * vertex is needed too, so a slight bend on the way into a sharp corner
 * does not stretch the corner back to it; every corner that cannot lose an
 * end vertex is found from its first one.
 */
static ur_status forbidden_centres(const ring *r, const double *turn, double width, spans *out,
                                   ur_error *error)
{
    double reach = BRIDGE_CORNER_REACH * width, clearance = 1.5 * width;
    size_t n = r->count;
    for (size_t i = 0; i < n; i++) {
        if (turn[i] <= 0)
            continue;
        double sum = 0, last = -1;
        for (size_t k = 0; k < n; k++) {
            size_t j = (i + k) % n;
            double at = r->at[j] + (i + k >= n ? r->length : 0);
            if (at - r->at[i] > reach)
                break;
            sum += turn[j];
            if (sum > BRIDGE_CORNER_TURN) {
                last = at;
                break;
            }
        }
        if (last < 0 || sum - turn[i] > BRIDGE_CORNER_TURN)
            continue;
        ur_status status =
            spans_push_circular(out, r->at[i] - clearance, last + clearance, r->length, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* Merges sorted spans in place. */
static void merge(spans *list)
{
    size_t kept = 0;
    for (size_t i = 0; i < list->count; i++) {
        if (kept > 0 && list->items[i].lo <= list->items[kept - 1].hi) {
            if (list->items[i].hi > list->items[kept - 1].hi)
                list->items[kept - 1].hi = list->items[i].hi;
        } else
            list->items[kept++] = list->items[i];
    }
    list->count = kept;
}

/* The gap centres allowed: [0, length] less the forbidden spans (merged, sorted). */
static ur_status allowed_centres(const spans *forbidden, double length, spans *out, ur_error *error)
{
    double from = 0;
    ur_status status = UR_OK;
    for (size_t i = 0; status == UR_OK && i < forbidden->count; i++) {
        if (forbidden->items[i].lo > from)
            status = spans_push(out, from, forbidden->items[i].lo, error);
        if (forbidden->items[i].hi > from)
            from = forbidden->items[i].hi;
    }
    if (status == UR_OK && from < length)
        status = spans_push(out, from, length, error);
    return status;
}

/*
 * Removes the open span (lo, hi) from allowed: what it cuts keeps its
 * parts outside, ends included, so a centre exactly at the limit stays.
 */
static ur_status remove_open(spans *allowed, double lo, double hi, ur_error *error)
{
    size_t count = allowed->count;
    ur_status status = UR_OK;
    for (size_t i = 0; status == UR_OK && i < count; i++) {
        span s = allowed->items[i];
        if (s.hi <= lo || s.lo >= hi)
            continue;
        if (s.hi >= hi)
            status = spans_push(allowed, hi, s.hi, error);
        /* The left part, or an empty span (lo > hi) dropped below. */
        allowed->items[i] = s.lo <= lo ? (span){s.lo, lo} : (span){1, 0};
    }
    size_t kept = 0;
    for (size_t i = 0; i < allowed->count; i++)
        if (allowed->items[i].lo <= allowed->items[i].hi)
            allowed->items[kept++] = allowed->items[i];
    allowed->count = kept;
    return status;
}

/* The allowed centre nearest t round the ring; *shift how far it is (INFINITY: none). */
static double nearest(const spans *allowed, double t, double length, double *shift)
{
    double best = t;
    *shift = INFINITY;
    for (size_t i = 0; i < allowed->count; i++)
        for (int m = -1; m <= 1; m++) {
            double u = t + m * length;
            span s = allowed->items[i];
            double p = u < s.lo ? s.lo : u > s.hi ? s.hi : u;
            if (fabs(p - u) < *shift) {
                *shift = fabs(p - u);
                best = p;
            }
        }
    return best >= length ? best - length : best;
}

/* ---- Spreading the gaps ------------------------------------------------ */

/*
 * How well an even spread starting at `offset` fits: the total distance the
 * gaps must move to allowed centres (smaller is better), then the least
 * room any gap keeps to a corner (larger is better).
 */
static void score(const spans *allowed, const spans *forbidden, double length, size_t count,
                  double offset, double *moved, double *room)
{
    *moved = 0;
    *room = INFINITY;
    for (size_t k = 0; k < count; k++) {
        double shift, at = nearest(allowed, offset + k * length / count, length, &shift);
        *moved += shift;
        for (size_t f = 0; f < forbidden->count; f++) {
            double d = circular_distance(forbidden->items[f], at, length);
            if (d < *room)
                *room = d;
        }
    }
}

/* The even spread's first position that fits the corners best. */
static double best_offset(const spans *allowed, const spans *forbidden, double length, size_t count)
{
    double spacing = length / count, best = 0, best_moved = INFINITY, best_room = -1;
    size_t tries = BRIDGE_OFFSETS + allowed->count;
    for (size_t i = 0; i < tries; i++) {
        /* The middles of the allowed stretches first: a gap centred in each. */
        double offset = i < allowed->count
                            ? fmod((allowed->items[i].lo + allowed->items[i].hi) / 2, spacing)
                            : spacing * (double)(i - allowed->count) / BRIDGE_OFFSETS;
        double moved, room;
        score(allowed, forbidden, length, count, offset, &moved, &room);
        double tolerance = 1e-9 * length;
        if (moved < best_moved - tolerance ||
            (moved <= best_moved + tolerance && room > best_room + tolerance)) {
            best = offset;
            best_moved = moved;
            best_room = room;
        }
    }
    return best;
}

/*
 * Gap centres into centres (sorted), *placed how many: the even spread,
 * each moved to the nearest allowed centre at least two widths (a width of
 * cut) from the gaps already placed; those that find none are left out.
 */
static ur_status place(spans *allowed, const spans *forbidden, double length, size_t count,
                       double width, double *centres, size_t *placed, ur_error *error)
{
    double offset = best_offset(allowed, forbidden, length, count);
    *placed = 0;
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < count; k++) {
        double shift, at = nearest(allowed, offset + k * length / count, length, &shift);
        if (!isfinite(shift))
            break;
        centres[(*placed)++] = at;
        /* No other centre within two widths of this one, round the ring. */
        for (int m = -1; status == UR_OK && m <= 1; m++)
            status = remove_open(allowed, at - 2 * width + m * length, at + 2 * width + m * length,
                                 error);
    }
    for (size_t i = 1; i < *placed; i++) /* insertion sort: a handful of gaps */
        for (size_t j = i; j > 0 && centres[j] < centres[j - 1]; j--) {
            double swap = centres[j];
            centres[j] = centres[j - 1];
            centres[j - 1] = swap;
        }
    return status;
}

/* ---- Cutting the outline open ------------------------------------------ */

/* The point at arc length t (any real) along the ring. */
static ur_vec2 point_at(const ring *r, double t)
{
    t -= floor(t / r->length) * r->length;
    size_t i = 0;
    while (i + 1 < r->count && r->at[i + 1] <= t)
        i++;
    ur_vec2 a = r->points[i], b = r->points[(i + 1) % r->count];
    double end = i + 1 < r->count ? r->at[i + 1] : r->length;
    double share = end > r->at[i] ? (t - r->at[i]) / (end - r->at[i]) : 0;
    if (share > 1)
        share = 1;
    return ur_vec2_add_scaled(a, ur_vec2_sub(b, a), share);
}

/*
 * The open polyline from arc length from to to (from < to <= from +
 * length): its end points and the ring's points strictly between, in
 * order.  Points closer than a nanometre to an end are left out, so none
 * repeats.
 */
static ur_status stretch(const ring *r, double from, double to, ur_points *out, ur_error *error)
{
    const double close = 1e-9;
    ur_status status = ur_points_push(out, point_at(r, from), error);
    for (int m = 0; status == UR_OK && m <= 2; m++)
        for (size_t i = 0; status == UR_OK && i < r->count; i++) {
            double at = r->at[i] + m * r->length;
            if (at > from + close && at < to - close)
                status = ur_points_push(out, r->points[i], error);
        }
    return status == UR_OK ? ur_points_push(out, point_at(r, to), error) : status;
}

/* The point of the circle nearest point (straight out from the centre). */
static ur_vec2 onto_circle(ur_path_circle circle, ur_vec2 point)
{
    ur_vec2 out = ur_vec2_sub(point, circle.centre);
    double length = ur_vec2_length(out);
    return length > 0 ? ur_vec2_add_scaled(circle.centre, out, circle.radius / length) : point;
}

/*
 * A stretch of a round outline as the arc it is: its ends, found on the
 * chords, moved out onto the circle (by less than the flattening's
 * tolerance), so that every point lies on it and the cut is the arc.
 */

static ur_path_circle arc_of(ur_path_circle circle, ur_points *stretch)
{
    ur_vec2 *first = &stretch->items[0], *last = &stretch->items[stretch->count - 1];
    *first = onto_circle(circle, *first);
    *last = onto_circle(circle, *last);
    circle.sweep = ur_arc_sweep(circle.centre, stretch->items, stretch->count);
    return circle;
}

/* The outline cut open at the gaps: paths[0] the first stretch, the rest appended. */
static ur_status open_outline(ur_piece *piece, const ring *r, const double *centres, size_t placed,
                              double width, ur_error *error)
{
    ur_points *pieces = calloc(placed, sizeof *pieces);
    ur_path *paths = NULL;
    ur_status status = pieces ? UR_OK : ur_error_out_of_memory(error);
    for (size_t k = 0; status == UR_OK && k < placed; k++) {
        double next = k + 1 < placed ? centres[k + 1] : centres[0] + r->length;
        status = stretch(r, centres[k] + width / 2, next - width / 2, &pieces[k], error);
    }
    if (status == UR_OK) {
        paths = realloc(piece->paths, (piece->path_count + placed - 1) * sizeof *paths);
        if (!paths)
            status = ur_error_out_of_memory(error);
    }
    if (status == UR_OK) {
        piece->paths = paths;
        piece->outline_area = fabs(ur_polygon_signed_area(paths[0].points, paths[0].count));
        ur_path_circle circle = paths[0].circle;
        free(paths[0].points);
        for (size_t k = 0; k < placed; k++) {
            ur_path *path = k == 0 ? &paths[0] : &paths[piece->path_count + k - 1];
            ur_path_circle arc = {{0, 0}, 0, 0};
            if (circle.radius > 0 && pieces[k].count >= 2)
                arc = arc_of(circle, &pieces[k]);
            *path = (ur_path){UR_OP_CUT, false, pieces[k].items, pieces[k].count, arc};
            pieces[k] = (ur_points){0};
        }
        piece->path_count += placed - 1;
        piece->bridged = true;
    }
    for (size_t k = 0; pieces && k < placed; k++)
        ur_points_free(&pieces[k]);
    free(pieces);
    return status;
}

/* ---- The whole ----------------------------------------------------------- */

/* The outline without repeated points, as arc lengths, and each vertex's turn. */
static ur_status measure(const ur_piece *piece, ur_vec2 **points, ring *r, double **turn,
                         ur_error *error)
{
    const ur_path *outline = &piece->paths[0];
    size_t n = outline->count, kept = 0;
    *points = ur_alloc_array(n, sizeof **points, error);
    r->at = ur_alloc_array(n, sizeof *r->at, error);
    *turn = ur_alloc_array(n, sizeof **turn, error);
    if (!*points || !r->at || !*turn)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < n; i++)
        if (kept == 0 || ur_vec2_distance(outline->points[i], (*points)[kept - 1]) > 0)
            (*points)[kept++] = outline->points[i];
    while (kept > 1 && ur_vec2_distance((*points)[kept - 1], (*points)[0]) == 0)
        kept--;
    r->points = *points;
    r->count = kept;
    r->length = 0;
    for (size_t i = 0; i < kept; i++) {
        r->at[i] = r->length;
        r->length += ur_vec2_distance((*points)[i], (*points)[(i + 1) % kept]);
        (*turn)[i] = kept >= 3 ? turn_at(*points, kept, i) : 0;
    }
    return kept >= 3 && r->length > 0
               ? UR_OK
               : ur_error_set(error, UR_ERROR_INPUT, "piece %s has a degenerate outline",
                              piece->name);
}

static size_t automatic_count(double length, bool router)
{
    size_t count = (size_t)floor(length / BRIDGE_AUTOMATIC_SPACING + 0.5);
    size_t least = router ? 3 : 2;
    return count < least ? least : count;
}

static ur_status record(ur_piece *piece, size_t asked, size_t placed, double width, bool automatic,
                        ur_error *error)
{
    ur_allowance_record entry = {.kind = UR_ALLOWANCE_BRIDGES,
                                 .count = placed,
                                 .value = width,
                                 .limit = NAN,
                                 .warning = placed < asked};
    entry.where = ur_vec2_make((piece->box.min.x + piece->box.max.x) / 2,
                               (piece->box.min.y + piece->box.max.y) / 2);
    if (placed < asked)
        c_snprintf(entry.reason, sizeof entry.reason,
                   "only %zu of %zu bridges of %g mm fit: the rest of the outline is too near "
                   "corners, tight curves or the other bridges",
                   placed, asked, width);
    else
        c_snprintf(entry.reason, sizeof entry.reason,
                   "%zu bridge%s of %g mm left uncut in the outline to hold the part%s", placed,
                   placed == 1 ? "" : "s", width, automatic ? " (one per 300 mm of outline)" : "");
    return ur_piece_record(piece, &entry, error);
}

static ur_status check(const ur_piece *piece, double width, ur_error *error)
{
    if (!isfinite(width) || width <= 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece %s: a bridge must be wider than 0 mm, not %g", piece->name,
                            width);
    if (piece->bridged)
        return ur_error_set(error, UR_ERROR_INPUT, "piece %s already has bridges", piece->name);
    if (piece->path_count == 0 || !piece->paths[0].closed || piece->paths[0].count < 3)
        return ur_error_set(error, UR_ERROR_INPUT, "piece %s has no closed outline for bridges",
                            piece->name);
    return UR_OK;
}

ur_status ur_piece_add_bridges(ur_piece *piece, size_t count, double width, bool router,
                               ur_error *error)
{
    ur_status status = check(piece, width, error);
    if (status != UR_OK)
        return status;
    ur_vec2 *points = NULL;
    double *turn = NULL, *centres = NULL;
    ring r = {0};
    spans forbidden = {0}, allowed = {0};
    status = measure(piece, &points, &r, &turn, error);
    size_t asked = count ? count : automatic_count(r.length, router), placed = 0;
    if (status == UR_OK)
        status = forbidden_centres(&r, turn, width, &forbidden, error);
    if (status == UR_OK) {
        if (forbidden.count > 0) /* a round outline has none */
            qsort(forbidden.items, forbidden.count, sizeof *forbidden.items, compare_spans);
        merge(&forbidden);
        status = allowed_centres(&forbidden, r.length, &allowed, error);
    }
    if (status == UR_OK) {
        centres = ur_alloc_array(asked, sizeof *centres, error);
        status = centres
                     ? place(&allowed, &forbidden, r.length, asked, width, centres, &placed, error)
                     : UR_ERROR_MEMORY;
    }
    if (status == UR_OK && placed > 0)
        status = open_outline(piece, &r, centres, placed, width, error);
    if (status == UR_OK) {
        ur_piece_recompute_box(piece);
        status = record(piece, asked, placed, width, count == 0, error);
    }
    free(points);
    free(r.at);
    free(turn);
    free(centres);
    free(forbidden.items);
    free(allowed.items);
    return status;
}
