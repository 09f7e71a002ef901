/*
 * joints.c: glue tabs or laps on the seams of a net, and the labels that
 * tell which edge goes to which (allow.h, ur_pieces_add_joints).
 *
 * A seam has two sides, runs of two outlines (develop.h, ur_seam_side),
 * which may be closed loops (the rim of a hole, a piece's whole outline).
 * Outlines run counter-clockwise, so outward is to the right of a run.
 *
 * Tabs: one per straight stretch of the seam, which on a folded mesh is
 * one per edge, since the tab on each edge is glued under a different
 * face of the other piece and must fold on its own line; on a fine mesh,
 * where each edge is too short for a tab, one tab spans the edges of a
 * nearly straight stretch (NEARLY_STRAIGHT_SHARE).  A tab is a
 * trapezoid on its stretch, tapered at the tab angle from its base, so
 * that the tabs of neighbouring edges leave a notch between them down to
 * the seam's corner and fold apart.  On thick stock its first `thickness`
 * mm is a band with a second fold, which wraps the other piece's edge.
 * Laps: one band along each seam side (each half of a loop), mitred at
 * its corners (wood does not fold); a seam that no lap can follow whole
 * (it doubles back, or turns into a notch) is cut where it has turned by
 * a quarter turn, a lap for each stretch.  A lap is cut where the piece
 * it lies on ends (trim_lap).
 *
 * A joint must not overlap its piece or another joint, and keeps a gap
 * from all but its neighbours at the seam's corners: each piece has a
 * board (clearance.c) of its net's outline and the joints placed on it,
 * indexed so that each test looks only at what is near.  The outline is
 * grown by all the joints of a piece at once at the end (one GEOS union),
 * and only then the folds and marks go on.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>
#include <time.h>
#include "../base/c_locale.h"

/* A tab on stock at least this thick (mm) wraps the other piece's edge. */
#define THICK_STOCK 1.0

/*
 * A tab on an edge too short for its taper gets steeper sides, up to this
 * many degrees (still a notch between neighbouring tabs), before it is
 * made lower; lower than LOWEST_SHARE of the tab depth it is too small to
 * glue.
 */
#define STEEPEST 75.0

#define LOWEST_SHARE 0.2

/*
 * A seam a lap cannot follow whole is cut into stretches that turn by no
 * more than this (radians: 90 degrees), each with its own lap.
 */
#define LAP_TURN (M_PI / 2)

/*
 * The shapes a joint tries, in order: the share of the full depth, and how
 * much of its stretch's length is left out at each end (clear of the
 * corners, where the neighbouring edges of the piece come closest).  A tab
 * first tries the full shape on both sides of the seam, then the smaller
 * ones on each; a lap all its shapes on one side, then on the other.  The
 * last, lowest tab is tried only where no splice piece may take a
 * stretch's place (a mesh's seams, the cuts of a part nest splits): a
 * splice joins far better, but without one a tab of a fifth of the depth
 * still glues (the wedges of narrow slits on Blender's monkey head: its
 * last 2 seam edges without a tab).
 */
typedef struct shape {
    double depth, shorten;
} shape;

static const shape tab_shapes[] = {{1.0, 0.0},  {0.7, 0.0},  {0.5, 0.0},
                                   {0.35, 0.0}, {0.7, 0.15}, {0.5, 0.15},
                                   {0.5, 0.3},  {0.35, 0.3}, {LOWEST_SHARE, 0.3}};
static const shape lap_shapes[] = {{1.0, 0.0},  {0.7, 0.0}, {1.0, 0.15}, {0.7, 0.15},
                                   {0.5, 0.15}, {0.5, 0.3}, {0.35, 0.3}};

#define COUNT(array) (sizeof array / sizeof array[0])

/* A stretch of a seam is straight when no point strays from its chord by more than this share of
 * the tab depth. */
#define STRAIGHT_SHARE 0.02

void ur_seam_label(int seam, char *label, size_t size)
{
    int index = seam > 0 ? seam - 1 : 0;
    int number = index % 99 + 1, letters = index / 99;
    char prefix[8];
    size_t length = 0;
    /* bijective base 26: A..Z, then AA, AB, ... */
    char reversed[8];
    int value = letters + 1;
    while (value > 0 && length < sizeof reversed) {
        value--;
        reversed[length++] = (char)('A' + value % 26);
        value /= 26;
    }
    for (size_t i = 0; i < length; i++)
        prefix[i] = reversed[length - 1 - i];
    prefix[length] = '\0';
    c_snprintf(label, size, "%s%d", prefix, number);
}

/* ---- The shape of a joint ----------------------------------------------- */

typedef struct run {
    ur_vec2 *points; /* the side, copied from its net's outline */
    size_t count;
    double length;
} run;

static ur_status run_of(const ur_net *net, const ur_seam_side *side, run *r, ur_error *error)
{
    r->points = ur_alloc_array(side->count, sizeof *r->points, error);
    if (!r->points)
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < side->count; k++)
        r->points[k] = net->outline[(side->first + k) % net->outline_count];
    r->count = side->count;
    r->length = ur_polyline_length(r->points, r->count, false);
    return UR_OK;
}

/* The right-hand unit normal of the run's segment k (outward of a counter-clockwise outline). */
static ur_vec2 segment_normal(const run *r, size_t k)
{
    ur_vec2 d = ur_vec2_sub(r->points[k + 1], r->points[k]);
    double length = ur_vec2_length(d);
    return length > 0 ? ur_vec2_make(d.y / length, -d.x / length) : ur_vec2_make(0, 0);
}

/* The mitred offset direction at vertex k, so that offset edges stay parallel. */
static ur_vec2 vertex_normal(const run *r, size_t k)
{
    if (k == 0)
        return segment_normal(r, 0);
    if (k + 1 == r->count)
        return segment_normal(r, k - 1);
    ur_vec2 a = segment_normal(r, k - 1), b = segment_normal(r, k);
    ur_vec2 sum = ur_vec2_add(a, b);
    double dot = ur_vec2_dot(sum, a);
    if (dot < 0.5) /* a turn of more than about 120 degrees: do not mitre to infinity */
        return a;
    return ur_vec2_scale(sum, 1.0 / dot);
}

/* The point at arc length s along the run and the segment it lies on. */
static ur_vec2 point_at(const run *r, double s, size_t *segment)
{
    double walked = 0;
    for (size_t k = 0; k + 1 < r->count; k++) {
        double length = ur_vec2_distance(r->points[k], r->points[k + 1]);
        if (walked + length >= s || k + 2 == r->count) {
            *segment = k;
            double t = length > 0 ? fmin(1.0, fmax(0.0, (s - walked) / length)) : 0.0;
            return ur_vec2_add_scaled(r->points[k], ur_vec2_sub(r->points[k + 1], r->points[k]), t);
        }
        walked += length;
    }
    *segment = 0;
    return r->points[0];
}

/*
 * The joint's ring: along the run, out by `band` at its ends, over the top
 * at band + depth between arc lengths inset and length - inset, back.
 * Negative band and depth build it inward (the lapped zone of the other
 * piece).
 */
static ur_status joint_ring(const run *r, double band, double depth, double inset, ur_points *ring,
                            ur_error *error)
{
    ur_status status = UR_OK;
    double height = band + depth;
    for (size_t k = 0; status == UR_OK && k < r->count; k++)
        status = ur_points_push(ring, r->points[r->count - 1 - k], error);
    if (status == UR_OK && band != 0)
        status = ur_points_push(ring, ur_vec2_add_scaled(r->points[0], vertex_normal(r, 0), band),
                                error);
    size_t segment;
    ur_vec2 start = point_at(r, inset, &segment);
    if (status == UR_OK)
        status = ur_points_push(ring, ur_vec2_add_scaled(start, segment_normal(r, segment), height),
                                error);
    double walked = 0;
    for (size_t k = 0; status == UR_OK && k + 1 < r->count; k++) {
        walked += ur_vec2_distance(r->points[k], r->points[k + 1]);
        if (k + 2 < r->count && walked > inset && walked < r->length - inset)
            status = ur_points_push(
                ring, ur_vec2_add_scaled(r->points[k + 1], vertex_normal(r, k + 1), height), error);
    }
    ur_vec2 end = point_at(r, r->length - inset, &segment);
    if (status == UR_OK)
        status = ur_points_push(ring, ur_vec2_add_scaled(end, segment_normal(r, segment), height),
                                error);
    if (status == UR_OK && band != 0)
        status = ur_points_push(
            ring, ur_vec2_add_scaled(r->points[r->count - 1], vertex_normal(r, r->count - 1), band),
            error);
    return status;
}

/* The part of the run from its edge first on, edges long, as a run of its own. */
static ur_status sub_run(const run *r, size_t first, size_t edges, run *out, ur_error *error)
{
    out->points = ur_alloc_array(edges + 1, sizeof *out->points, error);
    if (!out->points)
        return UR_ERROR_MEMORY;
    memcpy(out->points, r->points + first, (edges + 1) * sizeof *out->points);
    out->count = edges + 1;
    out->length = ur_polyline_length(out->points, out->count, false);
    return UR_OK;
}

/*
 * The part of the run between arc lengths from and length - from, as a run
 * of its own (its ends interpolated); the caller frees out->points.
 */
static ur_status shortened(const run *r, double from, run *out, ur_error *error)
{
    size_t first_segment, last_segment;
    ur_vec2 start = point_at(r, from, &first_segment);
    ur_vec2 end = point_at(r, r->length - from, &last_segment);
    out->points = ur_alloc_array(last_segment - first_segment + 2, sizeof *out->points, error);
    if (!out->points)
        return UR_ERROR_MEMORY;
    out->count = 0;
    out->points[out->count++] = start;
    for (size_t k = first_segment + 1; k <= last_segment; k++)
        out->points[out->count++] = r->points[k];
    out->points[out->count++] = end;
    out->length = ur_polyline_length(out->points, out->count, false);
    return UR_OK;
}

static ur_vec2 run_middle(const run *r)
{
    size_t segment;
    return point_at(r, r->length / 2, &segment);
}

/* ---- What a piece's joints must keep clear of ----------------------------- */

/* A joint placed on a piece; its folds or marks go on once the outline has grown. */
typedef struct placed {
    GEOSGeometry *shape; /* owned */
    size_t piece;
    size_t first_edge, edges; /* the outline edges under it */
    run base;                 /* owned: where it folds */
    run under;                /* laps: the other side, which the lap lies under; owned */
    size_t under_piece;
    int seam, side; /* side: 0 or 1 of the seam */
    double depth;
    bool reduced; /* smaller than the full shape */
    bool kept;    /* still on once the outline has grown */
} placed_joint;

typedef struct joiner {
    GEOSContextHandle_t geos;
    ur_piece *pieces;
    const ur_net_list *nets;
    const ur_joint_options *options;
    allow_board **boards; /* one per piece */
    size_t *tab_count;    /* per piece, to balance them */
    placed_joint *placed;
    size_t placed_count, placed_capacity;
    double gap; /* mm a joint keeps from anything it does not share a corner with */
    /*
     * The joints' records (warnings, splices), held until the labels
     * beside them are done (tabs_beside_labels): then given to their
     * pieces after the labels', in the order they were made.
     */
    struct held_record *held;
    size_t held_count, held_capacity;
    atomic_size_t *seams_joined; /* non-NULL: the tabs' progress, for the labels' thread to tell */
} joiner;

static double full_depth(const ur_joint_options *o)
{
    return o->lap ? o->lap_width : o->tab_depth;
}

static double band_of(const ur_joint_options *o)
{
    return !o->lap && o->thickness >= THICK_STOCK ? o->thickness : 0.0;
}

/*
 * The joint's shape on base at a share of the full depth in *joint, NULL
 * when it would be too small to glue (or GEOS could not make it).  A tab
 * is tapered from its base at the tab angle, band and all; on a short base
 * its sides are steeper, and it is made lower, so that some of its top is
 * left.
 */
static ur_status joint_shape(const joiner *j, const run *base, double share, double *depth,
                             GEOSGeometry **joint, ur_error *error)
{
    *joint = NULL;
    const ur_joint_options *o = j->options;
    double band = band_of(o);
    *depth = full_depth(o) * share;
    double height = band + *depth, inset = 0.0;
    if (!o->lap && o->tab_angle < 90.0) {
        double slope = tan(o->tab_angle * M_PI / 180.0);
        inset = height / slope;
        if (2 * inset > 0.8 * base->length) {
            /* Steeper sides first, up to STEEPEST, then lower. */
            inset = 0.4 * base->length;
            slope = fmax(slope, fmin(height / inset, tan(STEEPEST * M_PI / 180.0)));
            height = fmin(height, inset * slope);
            *depth = height - band;
        }
    }
    if (!o->lap && *depth < LOWEST_SHARE * o->tab_depth)
        return UR_OK;
    ur_points ring = {0};
    ur_status status = joint_ring(base, 0.0, height, inset, &ring, error);
    if (status == UR_OK)
        *joint = geos_polygon_of_ring(j->geos, ring.items, ring.count);
    ur_points_free(&ring);
    return status;
}

/* v turned counter-clockwise by angle. */
static ur_vec2 turned(ur_vec2 v, double angle)
{
    double c = cos(angle), s = sin(angle);
    return ur_vec2_make(c * v.x - s * v.y, s * v.x + c * v.y);
}

/* The unit vector from a to b (zero if they coincide). */
static ur_vec2 direction(ur_vec2 a, ur_vec2 b)
{
    ur_vec2 d = ur_vec2_sub(b, a);
    double length = ur_vec2_length(d);
    return length > 0 ? ur_vec2_scale(d, 1.0 / length) : d;
}

/* The counter-clockwise angle from the direction of a to that of b, in (-pi, pi]. */
static double angle_between(ur_vec2 a, ur_vec2 b)
{
    return atan2(ur_vec2_cross(a, b), ur_vec2_dot(a, b));
}

/*
 * The wedge at corner c from direction `from` counter-clockwise to `to`
 * (unit vectors), out to radius, as a polygon; NULL when it is not less
 * than a half turn (or GEOS fails).
 */
static GEOSGeometry *wedge(const joiner *j, ur_vec2 c, ur_vec2 from, ur_vec2 to, double radius)
{
    double angle = angle_between(from, to);
    if (!(angle > 1e-9) || angle >= M_PI) /* a half turn or more: atan2 gives 0 or less, or pi */
        return NULL;
    ur_vec2 ring[4] = {c, ur_vec2_add_scaled(c, from, radius),
                       ur_vec2_add_scaled(c, turned(from, angle / 2), radius),
                       ur_vec2_add_scaled(c, to, radius)};
    return geos_polygon_of_ring(j->geos, ring, 4);
}

/*
 * The part of a lap beyond the other piece at one end of the seam: the
 * lap's end is the seam's corner c, where the seam leaves along `along`
 * on the lap's side; on the other piece that corner is its outline point
 * o_c, with the seam leaving along o_along and the outline's other edge
 * along o_edge.  The other piece's corner, turned so that its seam runs
 * along the lap's, lies from along counter-clockwise to the turned edge;
 * beyond it, out to the seam's other direction, the lap would stick out.
 * `clockwise` takes the corner the other way round (the seam's far end).
 */
static GEOSGeometry *beyond_corner(const joiner *j, ur_vec2 c, ur_vec2 along, ur_vec2 o_along,
                                   ur_vec2 o_edge, bool clockwise, double radius)
{
    ur_vec2 edge = turned(o_edge, angle_between(o_along, along));
    ur_vec2 back = ur_vec2_scale(along, -1);
    return clockwise ? wedge(j, c, back, edge, radius) : wedge(j, c, edge, back, radius);
}

/*
 * A trim that would take less than this share of the lap width squared
 * (a triangle with a 5.7 degree corner) is not made: where a third piece's
 * edge leaves the seam's end nearly square to it, the laps of the seams on
 * either side, each trimmed along that edge as its own side of the seam
 * lays it, came out a degree or so apart, with a sliver of a slit between
 * them (a chart's sides of a seam differ by their strain).
 */
#define LAP_TRIM_LEAST 0.05

/*
 * A lap trimmed to less than this share of its full band (lap width by
 * seam length) is too small to glue: the least of lap_shapes, 35 % as
 * wide and 40 % as long, untrimmed.
 */
#define LAP_LEAST_SHARE (0.35 * 0.4)

/*
 * The lap trimmed to the piece it lies on, at the seam's two ends, as a
 * woodworker saws it: where that piece's outline turns away from the seam
 * at less than a half turn, the part of the lap beyond the outline's next
 * edge would stick out past that piece onto a third (a triangle's 60
 * degree corner).  Each end is read off on its own, from the last edge of
 * the seam on either side: a chart's two sides of a seam differ by their
 * strain, and no one turn lays the one on the other.  whole is the lap's
 * side of the seam (its first point the far end), under the other side,
 * outline points first onwards of net other.  A trim that would leave
 * more than one polygon is not made; one that leaves too little to glue
 * (LAP_LEAST_SHARE: the other piece is too narrow beside the seam, as a
 * tangent developable's strips are at their edge of regression) takes the
 * lap away, *too_small.
 */
static ur_status trim_lap(const joiner *j, const ur_net *other, size_t first, const run *under,
                          const run *whole, GEOSGeometry **lap, bool *too_small, ur_error *error)
{
    GEOSContextHandle_t geos = j->geos;
    size_t u = under->count, w = whole->count;
    *too_small = false;
    if (!*lap || GEOSisValid_r(geos, *lap) != 1 || u < 2 || w < 2)
        return UR_OK;
    size_t n = other->outline_count, last = (first + u - 1) % n;
    const ur_vec2 *o = other->outline, *up = under->points, *wp = whole->points;
    double radius = 4 * j->options->lap_width + whole->length;
    /* The other side's start is the lap's end, and its end the lap's start. */
    GEOSGeometry *cuts[2] = {
        beyond_corner(j, wp[w - 1], direction(wp[w - 1], wp[w - 2]), direction(up[0], up[1]),
                      direction(o[first], o[(first + n - 1) % n]), false, radius),
        beyond_corner(j, wp[0], direction(wp[0], wp[1]), direction(up[u - 1], up[u - 2]),
                      direction(o[last], o[(last + 1) % n]), true, radius)};
    bool cut = false; /* whether a cut was made */
    ur_status status = UR_OK;
    for (int k = 0; status == UR_OK && k < 2; k++) {
        if (!cuts[k])
            continue;
        GEOSGeometry *trimmed = GEOSDifference_r(geos, *lap, cuts[k]);
        double before = 0, after = 0, width = j->options->lap_width;
        if (!trimmed)
            status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not trim a lap");
        else if (GEOSGeomTypeId_r(geos, trimmed) == GEOS_POLYGON &&
                 GEOSisEmpty_r(geos, trimmed) == 0 && GEOSisValid_r(geos, trimmed) == 1 &&
                 GEOSArea_r(geos, *lap, &before) && GEOSArea_r(geos, trimmed, &after) &&
                 before - after >= LAP_TRIM_LEAST * width * width) {
            GEOSGeom_destroy_r(geos, *lap);
            *lap = trimmed;
            cut = true;
        } else
            GEOSGeom_destroy_r(geos, trimmed);
    }
    for (int k = 0; k < 2; k++)
        if (cuts[k])
            GEOSGeom_destroy_r(geos, cuts[k]);
    double area = 0;
    if (status == UR_OK && cut && GEOSArea_r(geos, *lap, &area) &&
        area < LAP_LEAST_SHARE * j->options->lap_width * whole->length) {
        GEOSGeom_destroy_r(geos, *lap);
        *lap = NULL;
        *too_small = true;
    }
    return status;
}

/* ---- One seam -------------------------------------------------------------- */

typedef struct seam_sides {
    size_t net[2], side[2];
    size_t found;
} seam_sides;

/* A seam being joined: its two sides and their edges. */
typedef struct seam_job {
    const seam_sides *s;
    int seam;
    char label[16];
    run runs[2];
    size_t edges[2]; /* of each side */
} seam_job;

/* A stretch of the seam: edges [first, first + count) of side 0, the same edges of side 1. */
typedef struct stretch {
    size_t first, count;
} stretch;

/* The stretch's first edge along side k (side 1 runs the other way). */
static size_t local_first(const seam_job *sj, int k, const stretch *st)
{
    if (sj->edges[0] != sj->edges[1]) /* one stretch, all of each side */
        return 0;
    return k == 0 ? st->first : sj->edges[1] - st->first - st->count;
}

static size_t local_count(const seam_job *sj, int k, const stretch *st)
{
    return sj->edges[0] != sj->edges[1] ? sj->edges[k] : st->count;
}

/* The outline edge of the piece under side k's local edge. */
static size_t outline_edge(const joiner *j, const seam_job *sj, int k, size_t local)
{
    const ur_net *net = &j->nets->nets[sj->s->net[k]];
    return (net->seam_sides[sj->s->side[k]].first + local) % net->outline_count;
}

static ur_status add_placed(joiner *j, const placed_joint *p, ur_error *error)
{
    if (j->placed_count == j->placed_capacity) {
        size_t capacity = j->placed_capacity ? 2 * j->placed_capacity : 64;
        placed_joint *grown = realloc(j->placed, capacity * sizeof *grown);
        if (!grown)
            return ur_error_out_of_memory(error);
        j->placed = grown;
        j->placed_capacity = capacity;
    }
    ur_status status = allow_board_add(j->boards[p->piece], p->shape, p->first_edge, p->edges,
                                       j->placed_count, error);
    if (status != UR_OK)
        return status;
    j->placed[j->placed_count++] = *p;
    j->tab_count[p->piece]++;
    return UR_OK;
}

/*
 * Tries shapes [from, to) of the joint on side k of the stretch; *done
 * says whether one went on, v (set by the caller) why the smallest one
 * built did not.
 */
static ur_status try_shapes(joiner *j, const seam_job *sj, int k, const stretch *st,
                            const shape *shapes, size_t from, size_t to, bool *done,
                            allow_verdict *v, ur_error *error)
{
    size_t piece = sj->s->net[k], first = local_first(sj, k, st), count = local_count(sj, k, st);
    size_t edge = outline_edge(j, sj, k, first);
    *done = false;
    /* The stretch on this side, and for a lap the other side, which it lies on. */
    run whole = {0}, under = {0};
    ur_status status = sub_run(&sj->runs[k], first, count, &whole, error);
    if (status == UR_OK && j->options->lap)
        status = sub_run(&sj->runs[1 - k], local_first(sj, 1 - k, st), local_count(sj, 1 - k, st),
                         &under, error);
    for (size_t step = from; status == UR_OK && !*done && step < to; step++) {
        run base = {0};
        status = shortened(&whole, shapes[step].shorten * whole.length, &base, error);
        double depth = 0;
        GEOSGeometry *joint = NULL;
        if (status == UR_OK)
            status = joint_shape(j, &base, shapes[step].depth, &depth, &joint, error);
        bool too_small = false;
        if (status == UR_OK && j->options->lap)
            status = trim_lap(j, &j->nets->nets[sj->s->net[1 - k]],
                              outline_edge(j, sj, 1 - k, local_first(sj, 1 - k, st)), &under,
                              &whole, &joint, &too_small, error);
        allow_verdict tried = {too_small ? ALLOW_BLOCKED_UNDER : ALLOW_BLOCKED_SHAPE, NULL, 0};
        if (status == UR_OK && !too_small)
            status = allow_board_test(j->boards[piece], joint, base.points, base.count, edge, count,
                                      &tried, error);
        /* What stopped the smallest shape that could be built says most. */
        if (tried.by != ALLOW_BLOCKED_SHAPE || v->by == ALLOW_BLOCKED_SHAPE)
            *v = tried;
        if (status == UR_OK && v->by == ALLOW_BLOCKED_NOT) {
            placed_joint p = {.shape = joint,
                              .piece = piece,
                              .first_edge = edge,
                              .edges = count,
                              .base = base,
                              .under_piece = sj->s->net[1 - k],
                              .seam = sj->seam,
                              .side = k,
                              .depth = depth,
                              .reduced = step > 0,
                              .under = under};
            status = add_placed(j, &p, error);
            if (status == UR_OK) {
                *done = true;
                under = (run){0};
                continue; /* the joiner owns the shape and the runs now */
            }
        }
        if (joint)
            GEOSGeom_destroy_r(j->geos, joint);
        free(base.points);
    }
    free(whole.points);
    free(under.points);
    return status;
}

/* Whether outline edge e of side k's piece is one of the seam's other side (on the same piece). */
static bool on_other_side(const joiner *j, const seam_job *sj, int k, size_t e)
{
    if (sj->s->net[0] != sj->s->net[1])
        return false;
    const ur_net *net = &j->nets->nets[sj->s->net[k]];
    size_t first = net->seam_sides[sj->s->side[1 - k]].first, n = net->outline_count;
    return (e + n - first % n) % n < sj->edges[1 - k];
}

/* Which side of the seam a describe() names, and what stopped its joint there. */
static void describe(const joiner *j, const seam_job *sj, int k, const stretch *st,
                     const allow_verdict *v, char *text, size_t size)
{
    const ur_piece *piece = &j->pieces[sj->s->net[k]];
    run r = {0};
    if (sub_run(&sj->runs[k], local_first(sj, k, st), local_count(sj, k, st), &r, NULL) != UR_OK) {
        c_snprintf(text, size, "on %s no room", piece->name);
        return;
    }
    ur_vec2 middle = run_middle(&r);
    double distance = -1;
    GEOSGeometry *point = GEOSGeom_createPointFromXY_r(j->geos, middle.x, middle.y);
    if (point && v->what)
        GEOSDistance_r(j->geos, point, v->what, &distance);
    if (point)
        GEOSGeom_destroy_r(j->geos, point);
    if (v->by == ALLOW_BLOCKED_OUTLINE && on_other_side(j, sj, k, v->edge))
        c_snprintf(text, size, "on %s the seam's other side comes within %.1f mm (a narrow slit)",
                   piece->name, distance);
    else if (v->by == ALLOW_BLOCKED_OUTLINE)
        c_snprintf(text, size, "on %s its own outline comes within %.1f mm", piece->name, distance);
    else if (v->by == ALLOW_BLOCKED_JOINT)
        c_snprintf(text, size, "on %s another %s comes within %.1f mm", piece->name,
                   j->options->lap ? "lap" : "tab", distance);
    else if (v->by == ALLOW_BLOCKED_UNDER)
        c_snprintf(text, size, "on %s a lap cut to where %s ends is too small to glue", piece->name,
                   j->pieces[sj->s->net[1 - k]].name);
    else if (j->options->lap) /* never too short (not tapered): its shape fails where it bends */
        c_snprintf(text, size,
                   "on %s the seam bends too much along its %.1f mm for a lap %g mm wide",
                   piece->name, r.length, j->options->lap_width);
    else
        c_snprintf(text, size, "on %s the edge (%.1f mm) is too short", piece->name, r.length);
    free(r.points);
}

static ur_allowance_record record_entry(ur_allowance_kind kind, ur_vec2 where, size_t count,
                                        bool warning, const char *format, va_list args)
{
    ur_allowance_record entry = {.kind = kind,
                                 .count = count,
                                 .value = NAN,
                                 .limit = NAN,
                                 .where = where,
                                 .warning = warning};
    c_vsnprintf(entry.reason, sizeof entry.reason, format, args);
    return entry;
}

static ur_status record(ur_piece *piece, ur_allowance_kind kind, ur_vec2 where, size_t count,
                        bool warning, ur_error *error, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 7, 8)))
#endif
    ;

static ur_status record(ur_piece *piece, ur_allowance_kind kind, ur_vec2 where, size_t count,
                        bool warning, ur_error *error, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    ur_allowance_record entry = record_entry(kind, where, count, warning, format, args);
    va_end(args);
    return ur_piece_record(piece, &entry, error);
}

typedef struct held_record {
    size_t piece;
    ur_allowance_record entry;
} held_record;

static ur_status hold_record(joiner *j, size_t piece, ur_vec2 where, bool warning, ur_error *error,
                             const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 6, 7)))
#endif
    ;

/* A joint's record for piece, held (joiner.held): a UR_ALLOWANCE_JOINT entry. */
static ur_status hold_record(joiner *j, size_t piece, ur_vec2 where, bool warning, ur_error *error,
                             const char *format, ...)
{
    if (j->held_count == j->held_capacity) {
        size_t capacity = j->held_capacity ? 2 * j->held_capacity : 16;
        held_record *grown = realloc(j->held, capacity * sizeof *grown);
        if (!grown)
            return ur_error_out_of_memory(error);
        j->held = grown;
        j->held_capacity = capacity;
    }
    va_list args;
    va_start(args, format);
    j->held[j->held_count++] =
        (held_record){piece, record_entry(UR_ALLOWANCE_JOINT, where, 0, warning, format, args)};
    va_end(args);
    return UR_OK;
}

/* The held records given to their pieces, in the order they were made. */
static ur_status give_held_records(joiner *j, ur_error *error)
{
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < j->held_count; k++)
        status = ur_piece_record(&j->pieces[j->held[k].piece], &j->held[k].entry, error);
    j->held_count = 0;
    return status;
}

/* The warning for a stretch that got no joint on either side, saying why. */
static ur_status warn_stretch(joiner *j, const seam_job *sj, const stretch *st, int first_side,
                              const allow_verdict why[2], ur_error *error)
{
    char sides[2][128];
    for (int k = 0; k < 2; k++)
        describe(j, sj, k, st, &why[k], sides[k], sizeof sides[k]);
    run r = {0};
    ur_status status = sub_run(&sj->runs[first_side], local_first(sj, first_side, st),
                               local_count(sj, first_side, st), &r, error);
    if (status != UR_OK)
        return status;
    size_t total = sj->edges[0];
    char which[48] = "";
    if (total > 1 && sj->edges[0] == sj->edges[1] && st->count == 1)
        c_snprintf(which, sizeof which, " (edge %zu of %zu)", st->first + 1, total);
    else if (total > 1 && sj->edges[0] == sj->edges[1] && st->count < total)
        c_snprintf(which, sizeof which, " (edges %zu to %zu of %zu)", st->first + 1,
                   st->first + st->count, total);
    /* Both sides of a slit in one piece meet the same: said once. */
    bool same = strcmp(sides[0], sides[1]) == 0;
    status = hold_record(j, sj->s->net[first_side], run_middle(&r), true, error,
                         "no room for a %s on seam %s%s: %s%s%s: join it by hand",
                         j->options->lap ? "lap" : "glue tab", sj->label, which, sides[first_side],
                         same ? ", on either side" : ", ", same ? "" : sides[1 - first_side]);
    free(r.points);
    return status;
}

/*
 * No joint fits either side of the stretch: a splice piece glued behind it
 * (splice.c), named after the seam (and the stretch, on a seam of several),
 * and a record on each piece saying so.
 */
static ur_status splice_stretch(joiner *j, const seam_job *sj, const stretch *st, int side,
                                ur_error *error)
{
    const ur_joint_options *o = j->options;
    run r = {0};
    ur_status status =
        sub_run(&sj->runs[side], local_first(sj, side, st), local_count(sj, side, st), &r, error);
    if (status != UR_OK)
        return status;
    const ur_piece *a = &j->pieces[sj->s->net[side]], *b = &j->pieces[sj->s->net[1 - side]];
    char name[32];
    if (sj->edges[0] > 1 && sj->edges[0] == sj->edges[1])
        c_snprintf(name, sizeof name, "S-%s.%zu", sj->label, st->first + 1);
    else
        c_snprintf(name, sizeof name, "S-%s", sj->label);
    ur_splice_request request = {.seam = r.points,
                                 .count = r.count,
                                 .width = full_depth(o),
                                 .name = name,
                                 .label = sj->label,
                                 .piece_a = a->name,
                                 .piece_b = b->name,
                                 .strap = o->lap,
                                 .font = o->font,
                                 .label_height = o->label_height};
    status = ur_splice_list_add(o->splices, &request, error);
    for (int k = 0; status == UR_OK && k < (sj->s->net[0] == sj->s->net[1] ? 1 : 2); k++)
        status = hold_record(j, sj->s->net[k], run_middle(&sj->runs[k]), false, error,
                             "no room for a %s on seam %s on either side: joined by %s %s, glued "
                             "behind the seam",
                             o->lap ? "lap" : "glue tab", sj->label,
                             o->lap ? "butt strap" : "splice strip", name);
    free(r.points);
    return status;
}

/*
 * Whether a splice piece is worth cutting for the stretch: one at least as
 * long as it is wide.  A papercraft mesh's seams are runs of short edges,
 * one stretch each; a strip for each short one the tabs miss (round a UV
 * sphere's poles) would be confetti, and such an edge is glued by hand.
 */
static bool worth_a_splice(const joiner *j, const seam_job *sj, const stretch *st, int side)
{
    const run *r = &sj->runs[side];
    size_t first = local_first(sj, side, st), edges = local_count(sj, side, st);
    if (first + edges >= r->count)
        return true;
    return ur_polyline_length(r->points + first, edges + 1, false) >= full_depth(j->options);
}

/*
 * The joint of one stretch: full on either side, then smaller on either;
 * done says whether one went on, why[] what stopped each side if not.
 */
static ur_status join_stretch(joiner *j, const seam_job *sj, const stretch *st, int first_side,
                              bool *done, allow_verdict why[2], ur_error *error)
{
    const ur_joint_options *o = j->options;
    const shape *shapes = o->lap ? lap_shapes : tab_shapes;
    size_t count = o->lap ? COUNT(lap_shapes) : COUNT(tab_shapes) - (o->splices ? 1 : 0);
    /* Tabs: the full shape on both sides before any smaller; laps: one side, then the other. */
    size_t split = o->lap ? count : 1;
    why[0] = why[1] = (allow_verdict){ALLOW_BLOCKED_SHAPE, NULL, 0};
    *done = false;
    ur_status status = UR_OK;
    for (int pass = 0; status == UR_OK && !*done && pass < 4; pass++) {
        int k = pass % 2 == 0 ? first_side : 1 - first_side;
        size_t from = pass < 2 ? 0 : split, to = pass < 2 ? split : count;
        if (from < to)
            status = try_shapes(j, sj, k, st, shapes, from, to, done, &why[k], error);
    }
    return status;
}

/*
 * The shares of the full depth a tab already placed may be lowered to, to
 * make room for one that found none beside it: most such tabs are stopped
 * by their neighbour round a concave corner of the outline, itself full
 * size (on A3 paper, every seam edge the sample head, Blender's torus and
 * a 48 x 24 sphere left without a tab was stopped so on at least one
 * side, and 1 of the 3 on Blender's monkey head, whose other 2 lay in the
 * wedges of narrow slits).
 */
static const double lower_shares[] = {0.7, 0.5, 0.35, LOWEST_SHARE};

/* The tab placed before whose shape stopped a joint (verdict v), or j->placed_count. */
static size_t blocking_tab(const joiner *j, const allow_verdict *v)
{
    if (v->by != ALLOW_BLOCKED_JOINT)
        return j->placed_count;
    for (size_t k = 0; k < j->placed_count; k++)
        if (j->placed[k].shape == v->what)
            return k;
    return j->placed_count;
}

/*
 * Whether inner lies within around, but for rounding: its sides lie on
 * around's, computed anew, and an exact test (GEOSCovers) said no to some
 * of them by a last digit.  What sticks out must be under 1e-9 of its area.
 */
static bool lies_within(GEOSContextHandle_t geos, const GEOSGeometry *around,
                        const GEOSGeometry *inner)
{
    GEOSGeometry *out = GEOSDifference_r(geos, inner, around);
    double out_area = 1, area = 0;
    bool within = out && GEOSArea_r(geos, out, &out_area) && GEOSArea_r(geos, inner, &area) &&
                  out_area <= 1e-9 * area;
    if (out)
        GEOSGeom_destroy_r(geos, out);
    return within;
}

/*
 * Placed tab b lowered on its base to a share of the full depth, in
 * *lower (NULL when that is not lower than it is, or does not lie within
 * it: a tab whose sides were made steeper on a short edge).
 */
static ur_status lowered_tab(const joiner *j, size_t b, double share, GEOSGeometry **lower,
                             double *depth, ur_error *error)
{
    const placed_joint *p = &j->placed[b];
    ur_status status = joint_shape(j, &p->base, share, depth, lower, error);
    if (status != UR_OK || !*lower)
        return status;
    if (!(*depth < p->depth - 1e-9) || !lies_within(j->geos, p->shape, *lower)) {
        GEOSGeom_destroy_r(j->geos, *lower);
        *lower = NULL;
    }
    return status;
}

/* Puts outline in place of placed tab b's shape, on its board too. */
static void swap_shape(joiner *j, size_t b, GEOSGeometry *outline)
{
    j->placed[b].shape = outline;
    allow_board_replace(j->boards[j->placed[b].piece], b, outline);
}

/*
 * The verdicts of the seam's stretches that name tab shape old name now
 * instead: old is about to be freed, and a stretch left without a tab
 * says later what stopped it (describe).
 */
static void rename_blocker(allow_verdict (*why)[2], size_t count, const GEOSGeometry *old,
                           const GEOSGeometry *now)
{
    for (size_t k = 0; k < count; k++)
        for (int side = 0; side < 2; side++)
            if (why[k][side].by == ALLOW_BLOCKED_JOINT && why[k][side].what == old)
                why[k][side].what = now;
}

/*
 * A stretch (the seam's stretch number k) that no tab fitted on either
 * side, tried again with the tab that stopped it on a side lowered, a
 * little at a time: the lowered tab lies within what it was (to rounding),
 * so it still keeps clear of everything, and stays lowered only if the
 * stretch's tab then fits.  why: the verdicts of all the seam's count
 * stretches so far.
 */
static ur_status make_room(joiner *j, const seam_job *sj, const stretch *st, size_t k,
                           int first_side, bool *done, allow_verdict (*why)[2], size_t count,
                           ur_error *error)
{
    ur_status status = UR_OK;
    for (int pass = 0; status == UR_OK && !j->options->lap && !*done && pass < 2; pass++) {
        size_t b = blocking_tab(j, &why[k][pass == 0 ? first_side : 1 - first_side]);
        for (size_t s = 0;
             status == UR_OK && b < j->placed_count && !*done && s < COUNT(lower_shares); s++) {
            GEOSGeometry *lower = NULL;
            double depth = 0;
            status = lowered_tab(j, b, lower_shares[s], &lower, &depth, error);
            if (status != UR_OK || !lower)
                continue;
            GEOSGeometry *old = j->placed[b].shape;
            swap_shape(j, b, lower);
            allow_verdict again[2];
            status = join_stretch(j, sj, st, first_side, done, again, error);
            if (status == UR_OK && *done) {
                j->placed[b].depth = depth;
                j->placed[b].reduced = true;
                rename_blocker(why, count, old, lower);
                GEOSGeom_destroy_r(j->geos, old);
            } else {
                swap_shape(j, b, old);
                GEOSGeom_destroy_r(j->geos, lower);
            }
        }
    }
    return status;
}

/*
 * The stretches no joint went on: a splice piece behind each, where the
 * seam has no joint at all and the stretch is worth one; else the warning
 * to join it by hand.  A seam that keeps joints elsewhere (a papercraft
 * mesh's seam of many edges, one tab each) is joined already: a strip for
 * each edge its tabs miss would be hundreds of pieces on a fine mesh.
 */
static ur_status finish_stretches(joiner *j, const seam_job *sj, const stretch *stretches,
                                  size_t count, int side, const bool *done,
                                  const allow_verdict (*why)[2], ur_error *error)
{
    bool any = false;
    for (size_t k = 0; k < count; k++)
        any = any || done[k];
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < count; k++) {
        if (done[k])
            continue;
        if (j->options->splices && !any && worth_a_splice(j, sj, &stretches[k], side))
            status = splice_stretch(j, sj, &stretches[k], side, error);
        else
            status = warn_stretch(j, sj, &stretches[k], side, why[k], error);
    }
    return status;
}

/* Whether the points stay within tolerance of the chord from the first to the last. */
static bool straight_2d(const ur_vec2 *points, size_t count, double tolerance)
{
    ur_vec3 a = ur_vec3_make(points[0].x, points[0].y, 0);
    ur_vec3 b = ur_vec3_make(points[count - 1].x, points[count - 1].y, 0);
    for (size_t i = 1; i + 1 < count; i++) {
        ur_vec3 p = ur_vec3_make(points[i].x, points[i].y, 0);
        if (ur_segment_distance(p, p, a, b) > tolerance)
            return false;
    }
    return true;
}

/* The same in 3D, for the mesh points of side 0's net, outline points first .. first + count - 1.
 */
static bool straight_3d(const ur_net *net, size_t first, size_t count, double tolerance)
{
    size_t n = net->outline_count;
    ur_vec3 a = net->outline_3d[first % n], b = net->outline_3d[(first + count - 1) % n];
    for (size_t i = 1; i + 1 < count; i++) {
        ur_vec3 p = net->outline_3d[(first + i) % n];
        if (ur_segment_distance(p, p, a, b) > tolerance)
            return false;
    }
    return true;
}

/* Whether side 0's edges [first, first + count) and side 1's stray less than tolerance. */
static bool within(const joiner *j, const seam_job *sj, size_t first, size_t count,
                   double tolerance)
{
    const ur_net *net = &j->nets->nets[sj->s->net[0]];
    size_t other_first = sj->edges[1] - first - count;
    return straight_2d(sj->runs[0].points + first, count + 1, tolerance) &&
           straight_2d(sj->runs[1].points + other_first, count + 1, tolerance) &&
           (!net->outline_3d ||
            straight_3d(net, net->seam_sides[sj->s->side[0]].first + first, count + 1, tolerance));
}

/* Whether side 0's edges [first, first + count) and the same edges of side 1 are straight. */
static bool stretch_straight(const joiner *j, const seam_job *sj, size_t first, size_t count)
{
    return within(j, sj, first, count, STRAIGHT_SHARE * j->options->tab_depth);
}

/*
 * How far a stretch of short edges may stray from its chord and still
 * carry one tab, as a share of the tab depth: on a fine mesh (a sphere's
 * 1 mm edges) no single edge is long enough for a tab, and the few
 * faces a tab then lies under turn so little from one another that the
 * paper follows them (a 15 mm stretch of a 60 mm sphere's seam strays
 * 0.5 mm, this share of a 6 mm tab).
 */
#define NEARLY_STRAIGHT_SHARE 0.1

/* The length of side 0's edges [first, first + count). */
static double stretch_length(const seam_job *sj, size_t first, size_t count)
{
    double length = 0;
    for (size_t i = first; i < first + count; i++)
        length += ur_vec2_distance(sj->runs[0].points[i], sj->runs[0].points[i + 1]);
    return length;
}

/* Whether a stretch is too short for a full tab (its tapered sides would meet). */
static bool too_short_for_a_tab(const joiner *j, const seam_job *sj, size_t first, size_t count)
{
    const ur_joint_options *o = j->options;
    if (o->tab_angle >= 90.0)
        return false;
    double inset = (band_of(o) + o->tab_depth) / tan(o->tab_angle * M_PI / 180.0);
    return 2 * inset > 0.8 * stretch_length(sj, first, count); /* as joint_shape steepens */
}

/* Whether some lap shape on side k's edges of the stretch is a simple ring (joint_shape). */
static ur_status lap_fits_the_seam(const joiner *j, const seam_job *sj, int k, const stretch *st,
                                   bool *simple, ur_error *error)
{
    *simple = false;
    run whole = {0};
    ur_status status =
        sub_run(&sj->runs[k], local_first(sj, k, st), local_count(sj, k, st), &whole, error);
    for (size_t step = 0; status == UR_OK && !*simple && step < COUNT(lap_shapes); step++) {
        run base = {0};
        status = shortened(&whole, lap_shapes[step].shorten * whole.length, &base, error);
        double depth;
        GEOSGeometry *lap = NULL;
        if (status == UR_OK)
            status = joint_shape(j, &base, lap_shapes[step].depth, &depth, &lap, error);
        *simple = lap && GEOSisValid_r(j->geos, lap) == 1;
        if (lap)
            GEOSGeom_destroy_r(j->geos, lap);
        free(base.points);
    }
    free(whole.points);
    return status;
}

/* How far side 0 turns at the start of its edge i (radians, either way). */
static double turn_before(const seam_job *sj, size_t i)
{
    const ur_vec2 *p = sj->runs[0].points;
    return fabs(angle_between(ur_vec2_sub(p[i], p[i - 1]), ur_vec2_sub(p[i + 1], p[i])));
}

/*
 * Adds a lap's stretch, cut where the seam turns too much for any lap
 * (on either side every lap shape would cross itself: a seam that doubles
 * back, or runs into a notch): a new stretch starts each time the turns
 * add up to more than LAP_TURN.  A seam some lap can follow stays one
 * stretch, as wood does not fold.
 */
static ur_status add_lap_stretch(const joiner *j, const seam_job *sj, stretch whole, stretch *out,
                                 size_t *count, ur_error *error)
{
    bool fits[2] = {false, false};
    ur_status status = UR_OK;
    for (int k = 0; status == UR_OK && k < 2 && !fits[0]; k++)
        status = lap_fits_the_seam(j, sj, k, &whole, &fits[k], error);
    if (status != UR_OK || fits[0] || fits[1] || sj->edges[0] != sj->edges[1]) {
        out[(*count)++] = whole;
        return status;
    }
    size_t first = whole.first;
    double turned = 0;
    for (size_t i = whole.first + 1; i < whole.first + whole.count; i++) {
        turned += turn_before(sj, i);
        if (turned > LAP_TURN) {
            out[(*count)++] = (stretch){first, i - first};
            first = i;
            turned = 0;
        }
    }
    out[(*count)++] = (stretch){first, whole.first + whole.count - first};
    return UR_OK;
}

/*
 * The seam cut into stretches: for tabs, its straight stretches (on a
 * folded mesh each edge, unless neighbouring edges run on in a straight
 * line on both pieces and in space), and a stretch too short for a tab
 * taken on over the next edges while it stays nearly straight; for laps,
 * all of it, or each half of a closed loop, cut again where a lap cannot
 * follow it (add_lap_stretch).
 */
static ur_status find_stretches(const joiner *j, const seam_job *sj, stretch **out, size_t *count,
                                ur_error *error)
{
    size_t m = sj->edges[0];
    bool paired = sj->edges[0] == sj->edges[1];
    *count = 0;
    *out = ur_alloc_array(m ? m : 1, sizeof **out, error);
    if (!*out)
        return UR_ERROR_MEMORY;
    if (!paired || (j->options->lap && m < 2)) {
        (*out)[(*count)++] = (stretch){0, m};
        return UR_OK;
    }
    if (j->options->lap) {
        const run *r = &sj->runs[0];
        bool loop = ur_vec2_distance(r->points[0], r->points[r->count - 1]) <= 1e-9 * r->length;
        ur_status status = UR_OK;
        if (loop) {
            status = add_lap_stretch(j, sj, (stretch){0, m / 2}, *out, count, error);
            if (status == UR_OK)
                status = add_lap_stretch(j, sj, (stretch){m / 2, m - m / 2}, *out, count, error);
        } else
            status = add_lap_stretch(j, sj, (stretch){0, m}, *out, count, error);
        return status;
    }
    for (size_t first = 0; first < m;) {
        size_t length = 1;
        while (first + length < m && stretch_straight(j, sj, first, length + 1))
            length++;
        while (first + length < m && too_short_for_a_tab(j, sj, first, length) &&
               within(j, sj, first, length + 1, NEARLY_STRAIGHT_SHARE * j->options->tab_depth))
            length++;
        (*out)[(*count)++] = (stretch){first, length};
        first += length;
    }
    return UR_OK;
}

/* The side most full joints fit on; when both are alike, the piece with fewer joints. */
static ur_status first_side(joiner *j, const seam_job *sj, const stretch *stretches, size_t count,
                            int *side, ur_error *error)
{
    const shape *shapes = j->options->lap ? lap_shapes : tab_shapes;
    size_t fits[2] = {0, 0};
    ur_status status = UR_OK;
    for (int k = 0; status == UR_OK && k < 2; k++)
        for (size_t s = 0; status == UR_OK && s < count; s++) {
            const stretch *st = &stretches[s];
            run base = {0};
            status =
                sub_run(&sj->runs[k], local_first(sj, k, st), local_count(sj, k, st), &base, error);
            double depth;
            GEOSGeometry *joint = NULL;
            if (status == UR_OK)
                status = joint_shape(j, &base, shapes[0].depth, &depth, &joint, error);
            allow_verdict v;
            if (status == UR_OK)
                status = allow_board_test(j->boards[sj->s->net[k]], joint, base.points, base.count,
                                          outline_edge(j, sj, k, local_first(sj, k, st)),
                                          local_count(sj, k, st), &v, error);
            if (status == UR_OK && v.by == ALLOW_BLOCKED_NOT)
                fits[k]++;
            if (joint)
                GEOSGeom_destroy_r(j->geos, joint);
            free(base.points);
        }
    if (fits[0] != fits[1])
        *side = fits[0] > fits[1] ? 0 : 1;
    else
        *side = j->tab_count[sj->s->net[1]] < j->tab_count[sj->s->net[0]] ? 1 : 0;
    return status;
}

static ur_status join_seam(joiner *j, const seam_sides *s, int seam, ur_error *error)
{
    seam_job sj = {.s = s, .seam = seam};
    ur_seam_label(seam, sj.label, sizeof sj.label);
    ur_status status = UR_OK;
    for (int k = 0; status == UR_OK && k < 2; k++) {
        const ur_net *net = &j->nets->nets[s->net[k]];
        status = run_of(net, &net->seam_sides[s->side[k]], &sj.runs[k], error);
        sj.edges[k] = status == UR_OK ? sj.runs[k].count - 1 : 0;
    }
    stretch *stretches = NULL;
    size_t count = 0;
    if (status == UR_OK)
        status = find_stretches(j, &sj, &stretches, &count, error);
    int side = 0;
    if (status == UR_OK)
        status = first_side(j, &sj, stretches, count, &side, error);
    bool *done = status == UR_OK ? ur_alloc_array(count ? count : 1, sizeof *done, error) : NULL;
    allow_verdict(*why)[2] = done ? ur_alloc_array(count ? count : 1, sizeof *why, error) : NULL;
    if (status == UR_OK && !why)
        status = UR_ERROR_MEMORY;
    for (size_t k = 0; status == UR_OK && k < count; k++) {
        status = join_stretch(j, &sj, &stretches[k], side, &done[k], why[k], error);
        if (status == UR_OK && !done[k])
            status = make_room(j, &sj, &stretches[k], k, side, &done[k], why, count, error);
    }
    if (status == UR_OK)
        status = finish_stretches(j, &sj, stretches, count, side, done,
                                  (const allow_verdict(*)[2])why, error);
    free(done);
    free(why);
    free(stretches);
    free(sj.runs[0].points);
    free(sj.runs[1].points);
    return status;
}

/* ---- Growing the outlines, then folds, marks and records ----------------- */

/* A polygon's exterior ring as the piece's outline (holes, if any, filled). */
static ur_status set_outline(const joiner *j, ur_piece *piece, const GEOSGeometry *polygon,
                             ur_error *error)
{
    ur_vec2 *ring;
    size_t count;
    ur_status status = allow_exterior_ring(j->geos, polygon, &ring, &count, error);
    if (status != UR_OK)
        return status;
    free(piece->paths[0].points);
    piece->paths[0].points = ring;
    piece->paths[0].count = count;
    piece->paths[0].circle = (ur_path_circle){{0, 0}, 0, 0}; /* grown: no circle */
    for (size_t i = 0; i < count; i++)
        ur_box_add(&piece->box, ring[i]);
    return UR_OK;
}

/*
 * Above this many points an outline is simplified here, not by GEOS, whose
 * simplifier mends a polygon it made invalid at a cost that grows faster
 * than its points (a 100,000-face sphere's net: 28 s of its 74).
 */
#define SIMPLIFY_BY_HAND 2000

/* How far a grown outline is simplified: a micrometre. */
#define SIMPLIFY_TOLERANCE 1e-3

/*
 * Drops the points of a ring within a micrometre of the chord between their
 * neighbours (straight runs, wiggles) and the tips of spikes that fold back
 * within it, in one pass with the ring as a stack; returns the count left.
 */
static size_t clean_ring(ur_vec2 *ring, size_t count)
{
    const double tolerance = SIMPLIFY_TOLERANCE;
    size_t top = 0;
    for (size_t i = 0; i < count; i++) {
        ring[top++] = ring[i];
        while (top >= 3) {
            ur_vec2 a = ring[top - 3], b = ring[top - 2], c = ring[top - 1];
            ur_vec2 chord = ur_vec2_sub(c, a);
            double length = ur_vec2_length(chord);
            if (length <= tolerance) { /* b is a spike's tip: back to a */
                top -= 2;
                continue;
            }
            double off = fabs(ur_vec2_cross(chord, ur_vec2_sub(b, a))) / length;
            bool between = ur_vec2_dot(ur_vec2_sub(b, a), chord) >= 0 &&
                           ur_vec2_dot(ur_vec2_sub(c, b), chord) >= 0;
            if (!(off <= tolerance && between))
                break;
            ring[top - 2] = c;
            top--;
        }
    }
    return top;
}

/* The polygon's rim, cleaned (clean_ring), as a polygon of its own; NULL on failure. */
static GEOSGeometry *rim_cleaned(const joiner *j, const GEOSGeometry *polygon)
{
    ur_vec2 *ring;
    size_t count;
    if (allow_exterior_ring(j->geos, polygon, &ring, &count, NULL) != UR_OK)
        return NULL;
    count = clean_ring(ring, count);
    GEOSGeometry *rim = count >= 3 ? geos_polygon_of_ring(j->geos, ring, count) : NULL;
    free(ring);
    return rim;
}

/*
 * The union (exact, taken over) simplified by a micrometre, far below any
 * cutter's resolution: where a shortened joint's corner meets the outline
 * a hair's breadth off, the union keeps a sliver that folds back on
 * itself.  Plain Douglas-Peucker is quick on an outline of thousands of
 * tabs; should it leave the polygon invalid, the exact union is kept.
 * NULL unless it is one polygon.
 */
static GEOSGeometry *simplified(const joiner *j, GEOSGeometry *exact)
{
    if (exact && GEOSGeomTypeId_r(j->geos, exact) != GEOS_POLYGON) {
        GEOSGeom_destroy_r(j->geos, exact);
        return NULL;
    }
    const GEOSGeometry *shell = exact ? GEOSGetExteriorRing_r(j->geos, exact) : NULL;
    int points = shell ? GEOSGeomGetNumPoints_r(j->geos, shell) : 0;
    GEOSGeometry *simple = points > SIMPLIFY_BY_HAND ? rim_cleaned(j, exact)
                           : exact ? GEOSSimplify_r(j->geos, exact, SIMPLIFY_TOLERANCE)
                                   : NULL;
    if (simple && (GEOSGeomTypeId_r(j->geos, simple) != GEOS_POLYGON ||
                   GEOSisValid_r(j->geos, simple) != 1)) {
        GEOSGeom_destroy_r(j->geos, simple);
        simple = NULL;
    }
    if (!simple)
        return exact;
    if (exact)
        GEOSGeom_destroy_r(j->geos, exact);
    return simple;
}

/* The union of all (a collection), simplified; NULL unless it is one polygon. */
static GEOSGeometry *united(const joiner *j, GEOSGeometry *all)
{
    return simplified(j, all ? GEOSUnaryUnion_r(j->geos, all) : NULL);
}

/* The collection of the polygon and the shapes (cloned), or NULL (*out_of_memory when so). */
static GEOSGeometry *collection(const joiner *j, const GEOSGeometry *outline,
                                const GEOSGeometry *const *shapes, size_t count,
                                bool *out_of_memory)
{
    GEOSGeometry **parts = calloc(count + 1, sizeof *parts);
    if (!parts) {
        *out_of_memory = true;
        return NULL;
    }
    bool failed = false;
    for (size_t k = 0; k <= count && !failed; k++)
        failed = !(parts[k] = GEOSGeom_clone_r(j->geos, k == 0 ? outline : shapes[k - 1]));
    GEOSGeometry *all = failed ? NULL
                               : GEOSGeom_createCollection_r(j->geos, GEOS_GEOMETRYCOLLECTION,
                                                             parts, (unsigned)(count + 1));
    *out_of_memory = !all; /* GEOS fails to copy or collect only for want of memory */
    if (!all)
        for (size_t k = 0; k <= count; k++)
            if (parts[k])
                GEOSGeom_destroy_r(j->geos, parts[k]);
    free(parts);
    return all;
}

/*
 * The part of a union that falls apart (parts, taken over) that holds the
 * outline, which is one ring and so lies in one part; NULL on failure.
 */
static GEOSGeometry *part_holding(const joiner *j, GEOSGeometry *parts, const GEOSGeometry *outline)
{
    GEOSGeometry *inside = GEOSPointOnSurface_r(j->geos, outline), *found = NULL;
    int count = inside ? GEOSGetNumGeometries_r(j->geos, parts) : 0;
    for (int k = 0; k < count && !found; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(j->geos, parts, k);
        if (GEOSIntersects_r(j->geos, part, inside) == 1)
            found = GEOSGeom_clone_r(j->geos, part);
    }
    if (inside)
        GEOSGeom_destroy_r(j->geos, inside);
    GEOSGeom_destroy_r(j->geos, parts);
    return found;
}

/* Whether a joint's shape lies on the grown outline: a point inside it does. */
static bool on_grown(const joiner *j, const GEOSPreparedGeometry *grown, const GEOSGeometry *joint)
{
    GEOSGeometry *inside = GEOSPointOnSurface_r(j->geos, joint);
    bool on = inside && GEOSPreparedIntersects_r(j->geos, grown, inside) == 1;
    if (inside)
        GEOSGeom_destroy_r(j->geos, inside);
    return on;
}

/*
 * The outline grown by all the joints at once.  Where the union falls
 * apart (a joint that meets the outline only at a point, on an edge a
 * hair long), the part holding the outline is kept and the joints off it
 * are left off: one union for the piece, where adding them one at a time
 * cost one union per joint (a 100,000-face sphere: 935 unions of a
 * 40,000-point outline).  NULL when even that fails, or when memory ran
 * out (*out_of_memory: then the joints must not be left off).
 */
static GEOSGeometry *grown_at_once(joiner *j, const allow_board *b, const GEOSGeometry *outline,
                                   const GEOSGeometry **shapes, size_t count, bool *out_of_memory)
{
    GEOSGeometry *all = collection(j, outline, shapes, count, out_of_memory);
    GEOSGeometry *exact = all ? GEOSUnaryUnion_r(j->geos, all) : NULL;
    if (all)
        GEOSGeom_destroy_r(j->geos, all);
    bool apart = exact && GEOSGeomTypeId_r(j->geos, exact) == GEOS_MULTIPOLYGON;
    if (apart)
        exact = part_holding(j, exact, outline);
    GEOSGeometry *grown = simplified(j, exact);
    const GEOSPreparedGeometry *prepared = grown && apart ? GEOSPrepare_r(j->geos, grown) : NULL;
    if (grown && apart && !prepared) {
        GEOSGeom_destroy_r(j->geos, grown);
        return NULL;
    }
    for (size_t k = 0; k < count; k++)
        j->placed[allow_board_joint_tag(b, k)].kept =
            grown && (!apart || on_grown(j, prepared, shapes[k]));
    if (prepared)
        GEOSPreparedGeom_destroy_r(j->geos, prepared);
    return grown;
}

/*
 * The outline united with one joint, as one polygon; NULL if it is not.
 * The outline has been simplified (by up to SIMPLIFY_TOLERANCE) since the
 * joint was placed on it, so a joint's base may lie a hair off it and
 * the union fall apart (a torus's tab on a 5-piece net): then the joint
 * grown by twice as much, which no cutter can tell, is tried.
 */
static GEOSGeometry *united_with(const joiner *j, const GEOSGeometry *grown,
                                 const GEOSGeometry *joint, bool *out_of_memory)
{
    GEOSGeometry *pair = collection(j, grown, &joint, 1, out_of_memory);
    GEOSGeometry *next = united(j, pair);
    if (pair)
        GEOSGeom_destroy_r(j->geos, pair);
    if (next || *out_of_memory)
        return next;
    GEOSGeometry *wider = GEOSBufferWithStyle_r(j->geos, joint, 2 * SIMPLIFY_TOLERANCE, 1,
                                                GEOSBUF_CAP_FLAT, GEOSBUF_JOIN_MITRE, 2.0);
    pair =
        wider ? collection(j, grown, (const GEOSGeometry *const *)&wider, 1, out_of_memory) : NULL;
    next = united(j, pair);
    if (pair)
        GEOSGeom_destroy_r(j->geos, pair);
    if (wider)
        GEOSGeom_destroy_r(j->geos, wider);
    return next;
}

/*
 * Adds to grown (taken over, returned) the joints not kept yet, one at a
 * time, leaving off any that would break the outline; stops when memory
 * runs out (*out_of_memory).
 */
static GEOSGeometry *grown_one_at_a_time(joiner *j, const allow_board *b, GEOSGeometry *grown,
                                         const GEOSGeometry **shapes, size_t count,
                                         bool *out_of_memory)
{
    for (size_t k = 0; k < count && !*out_of_memory; k++) {
        placed_joint *p = &j->placed[allow_board_joint_tag(b, k)];
        if (p->kept)
            continue;
        GEOSGeometry *next = united_with(j, grown, shapes[k], out_of_memory);
        if (next && GEOSGetNumInteriorRings_r(j->geos, next) == 0) {
            GEOSGeom_destroy_r(j->geos, grown);
            grown = next;
            p->kept = true;
        } else if (next)
            GEOSGeom_destroy_r(j->geos, next);
    }
    return grown;
}

/* ---- Growing the outline by splicing ------------------------------------ */

/*
 * Where a point lies along the outline (n points, counter-clockwise) from
 * edge first on, within edges edges: edge offset plus the share of that
 * edge; false when it lies on none of them (to a hundredth of a
 * micrometre: a base's ends are outline points or points on its edges).
 */
static bool position_on(const ur_vec2 *outline, size_t n, size_t first, size_t edges, ur_vec2 p,
                        double *position)
{
    for (size_t k = 0; k < edges; k++) {
        ur_vec2 a = outline[(first + k) % n], b = outline[(first + k + 1) % n];
        ur_vec2 along = ur_vec2_sub(b, a);
        double length = ur_vec2_length(along);
        if (!(length > 0))
            continue;
        double t = ur_vec2_dot(ur_vec2_sub(p, a), along) / (length * length);
        if (t < -1e-9 || t > 1 + 1e-9 ||
            fabs(ur_vec2_cross(along, ur_vec2_sub(p, a))) > 1e-8 * length)
            continue;
        *position = (double)(first + k) + fmin(1.0, fmax(0.0, t));
        return true;
    }
    return false;
}

/* A tab's stretch of the outline, from start to end (positions along it, end < start + n). */
typedef struct span {
    double start, end;
    const placed_joint *joint;
} span;

static int earlier_span(const void *a, const void *b)
{
    const span *x = a, *y = b;
    return (x->start > y->start) - (x->start < y->start);
}

/*
 * The spans of the piece's tabs along its outline, earliest first; false
 * when a base is not where it should be or two spans overlap.
 */
static bool tab_spans(const joiner *j, const allow_board *b, const ur_vec2 *outline, size_t n,
                      span *spans, size_t count)
{
    for (size_t k = 0; k < count; k++) {
        const placed_joint *p = &j->placed[allow_board_joint_tag(b, k)];
        const run *base = &p->base;
        double start, end;
        if (base->count < 2 || p->edges > n ||
            !position_on(outline, n, p->first_edge, p->edges, base->points[0], &start) ||
            !position_on(outline, n, p->first_edge, p->edges, base->points[base->count - 1],
                         &end) ||
            !(end > start))
            return false;
        double wrap = floor(start / (double)n) * (double)n;
        spans[k] = (span){start - wrap, end - wrap, p};
    }
    qsort(spans, count, sizeof *spans, earlier_span);
    for (size_t k = 0; k < count; k++) {
        double next = k + 1 < count ? spans[k + 1].start : spans[0].start + (double)n;
        if (spans[k].end > next + 1e-12)
            return false;
    }
    return true;
}

/*
 * Appends a tab's outward points, from its base's start to its end: its
 * ring (joint_ring) is the base backwards, then those points.  False when
 * the shape is not so made.
 */
static bool push_outward(const joiner *j, const placed_joint *p, ur_points *out, ur_error *error)
{
    ur_vec2 *ring;
    size_t count, base = p->base.count;
    if (allow_exterior_ring(j->geos, p->shape, &ring, &count, error) != UR_OK)
        return false;
    bool made = count > base;
    for (size_t k = 0; made && k < base; k++)
        made = ring[k].x == p->base.points[base - 1 - k].x &&
               ring[k].y == p->base.points[base - 1 - k].y;
    for (size_t k = base - 1; made && k <= count; k++)
        made = ur_points_push(out, k < count ? ring[k] : ring[0], error) == UR_OK;
    free(ring);
    return made;
}

/* Appends outline points strictly after position `from` and strictly before `to`. */
static bool push_between(const ur_vec2 *outline, size_t n, double from, double to, ur_points *out,
                         ur_error *error)
{
    bool ok = true;
    for (double v = floor(from) + 1; ok && v < to; v += 1)
        if (v > from)
            ok = ur_points_push(out, outline[(size_t)v % n], error) == UR_OK;
    return ok;
}

/* The ring with points repeated in a row (and a last equal to the first) left out; its count. */
static size_t without_repeats(ur_vec2 *ring, size_t count)
{
    size_t kept = 0;
    for (size_t i = 0; i < count; i++)
        if (kept == 0 || ring[i].x != ring[kept - 1].x || ring[i].y != ring[kept - 1].y)
            ring[kept++] = ring[i];
    while (kept > 1 && ring[kept - 1].x == ring[0].x && ring[kept - 1].y == ring[0].y)
        kept--;
    return kept;
}

/*
 * The outline grown by its tabs, each tab's outward points spliced in for
 * the stretch of outline its base covers: the tabs were tested to cover
 * nothing of the outline or of each other, so this is their union, made
 * in time linear in the points (GEOS's union of them took a tenth of a
 * papercraft sphere's time).  NULL when it cannot be so made (laps, cut to
 * fit; a base not on the outline; a result GEOS does not take for valid):
 * then the union.  *out_of_memory when memory ran out.
 */
static GEOSGeometry *spliced(joiner *j, const allow_board *b, const ur_piece *piece,
                             bool *out_of_memory)
{
    const ur_vec2 *outline = piece->paths[0].points;
    size_t n = piece->paths[0].count, count = allow_board_joint_count(b);
    if (j->options->lap || count == 0 || ur_polygon_signed_area(outline, n) <= 0)
        return NULL;
    span *spans = malloc(count * sizeof *spans);
    ur_points ring = {0};
    ur_error error;
    memset(&error, 0, sizeof error);
    bool ok = spans && tab_spans(j, b, outline, n, spans, count);
    for (size_t k = 0; ok && k < count; k++) {
        double next = k + 1 < count ? spans[k + 1].start : spans[0].start + (double)n;
        ok = push_outward(j, spans[k].joint, &ring, &error) &&
             push_between(outline, n, spans[k].end, next, &ring, &error);
    }
    *out_of_memory = !spans || error.status == UR_ERROR_MEMORY; /* not the union then */
    size_t kept = ok ? without_repeats(ring.items, ring.count) : 0;
    GEOSGeometry *grown = kept >= 3 ? geos_polygon_of_ring(j->geos, ring.items, kept) : NULL;
    if (grown && GEOSisValid_r(j->geos, grown) != 1) {
        GEOSGeom_destroy_r(j->geos, grown);
        grown = NULL;
    }
    free(spans);
    ur_points_free(&ring);
    return grown;
}

/*
 * The piece's outline grown by all its joints at once, then by those that
 * fell off it one at a time; should the union fail (no one polygon even
 * in part), by all of them one at a time from the outline.
 */
static ur_status grow_piece(joiner *j, size_t index, ur_error *error)
{
    const allow_board *b = j->boards[index];
    ur_piece *piece = &j->pieces[index];
    size_t count = allow_board_joint_count(b);
    if (count == 0)
        return UR_OK;
    const GEOSGeometry **shapes = calloc(count, sizeof *shapes);
    GEOSGeometry *outline =
        geos_polygon_of_ring(j->geos, piece->paths[0].points, piece->paths[0].count);
    if (!shapes || !outline) {
        free(shapes);
        if (outline)
            GEOSGeom_destroy_r(j->geos, outline);
        if (!shapes)
            return ur_error_out_of_memory(error);
        return ur_error_set(error, UR_ERROR_INTERNAL, "could not grow the outline of piece %s",
                            piece->name);
    }
    for (size_t k = 0; k < count; k++)
        shapes[k] = j->placed[allow_board_joint_tag(b, k)].shape;
    bool out_of_memory = false;
    GEOSGeometry *grown = spliced(j, b, piece, &out_of_memory);
    for (size_t k = 0; grown && k < count; k++)
        j->placed[allow_board_joint_tag(b, k)].kept = true;
    grown = grown           ? simplified(j, grown)
            : out_of_memory ? NULL
                            : grown_at_once(j, b, outline, shapes, count, &out_of_memory);
    if (out_of_memory) {
        GEOSGeom_destroy_r(j->geos, outline);
        free(shapes);
        return ur_error_out_of_memory(error);
    }
    if (!grown) {
        grown = outline;
        outline = NULL;
    }
    grown = grown_one_at_a_time(j, b, grown, shapes, count, &out_of_memory);
    ur_status status =
        out_of_memory ? ur_error_out_of_memory(error) : set_outline(j, piece, grown, error);
    GEOSGeom_destroy_r(j->geos, grown);
    if (outline)
        GEOSGeom_destroy_r(j->geos, outline);
    free(shapes);
    return status;
}

static ur_status add_open_path(ur_piece *piece, ur_op op, const run *r, double offset,
                               ur_error *error)
{
    ur_vec2 *points = ur_alloc_array(r->count, sizeof *points, error);
    if (!points)
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < r->count; k++)
        points[k] = ur_vec2_add_scaled(r->points[k], vertex_normal(r, k), offset);
    ur_status status = ur_piece_add_path(piece, op, points, r->count, false, error);
    free(points);
    return status;
}

/*
 * The folds of a tab: at the seam, and on thick stock at the band's top,
 * between the tab's tapered sides.
 */
static ur_status add_folds(const joiner *j, ur_piece *piece, const run *base, ur_error *error)
{
    ur_status status = add_open_path(piece, UR_OP_SCORE, base, 0.0, error);
    double band = band_of(j->options);
    if (status != UR_OK || band <= 0)
        return status;
    double inset =
        j->options->tab_angle < 90.0 ? band / tan(j->options->tab_angle * M_PI / 180.0) : 0.0;
    run inner = {0};
    if (base->length > 2 * inset)
        status = shortened(base, inset, &inner, error);
    if (status == UR_OK && inner.points)
        status = add_open_path(piece, UR_OP_SCORE, &inner, band, error);
    free(inner.points);
    return status;
}

static ur_status add_mark(const joiner *j, ur_piece *piece, const GEOSGeometry *zone,
                          ur_error *error)
{
    ur_vec2 *ring;
    size_t count;
    if (GEOSGeomTypeId_r(j->geos, zone) != GEOS_POLYGON || GEOSisEmpty_r(j->geos, zone))
        return UR_OK; /* nothing left to mark */
    ur_status status = allow_exterior_ring(j->geos, zone, &ring, &count, error);
    if (status == UR_OK)
        status = ur_piece_add_path(piece, UR_OP_MARK, ring, count, true, error);
    free(ring);
    return status;
}

/*
 * The other piece's lapped zone: inward of its side, clipped to its net's
 * outline (its own laps, grown onto the outline by now, lie under a third
 * piece: where a seam's laps change sides at a corner, the zone ran on
 * over the lap beside it).
 */
static ur_status mark_under(const joiner *j, size_t under, const run *r, ur_error *error)
{
    ur_piece *piece = &j->pieces[under];
    const ur_net *net = &j->nets->nets[under];
    ur_points ring = {0};
    ur_status status = joint_ring(r, 0.0, -j->options->lap_width, 0.0, &ring, error);
    GEOSGeometry *zone =
        status == UR_OK ? geos_polygon_of_ring(j->geos, ring.items, ring.count) : NULL;
    ur_points_free(&ring);
    GEOSGeometry *outline =
        zone ? geos_polygon_of_ring(j->geos, net->outline, net->outline_count) : NULL;
    GEOSGeometry *valid = zone ? GEOSMakeValid_r(j->geos, zone) : NULL;
    GEOSGeometry *clipped = outline && valid ? GEOSIntersection_r(j->geos, outline, valid) : NULL;
    if (status == UR_OK && clipped)
        status = add_mark(j, piece, clipped, error);
    GEOSGeometry *all[] = {zone, outline, valid, clipped};
    for (size_t k = 0; k < 4; k++)
        if (all[k])
            GEOSGeom_destroy_r(j->geos, all[k]);
    return status;
}

/*
 * Where the lapped zone's point q lands on the lap: the lap lies on the
 * zone, its seam run on the zone's seam run the other way round (a turn
 * about the two runs' middles, which shortening a lap leaves in place).
 */
static ur_vec2 onto_lap(const placed_joint *p, ur_vec2 q)
{
    ur_vec2 from = run_middle(&p->under), to = run_middle(&p->base);
    ur_vec2 along = ur_vec2_sub(p->under.points[p->under.count - 1], p->under.points[0]);
    ur_vec2 back = ur_vec2_sub(p->base.points[0], p->base.points[p->base.count - 1]);
    return ur_vec2_add(to, turned(ur_vec2_sub(q, from), angle_between(along, back)));
}

/* One kerf line of the zone, carried onto the lap and clipped to inside. */
static ur_status carry_line(const joiner *j, const placed_joint *p, const ur_path *line,
                            const GEOSGeometry *inside, ur_error *error)
{
    ur_vec2 *moved = ur_alloc_array(line->count, sizeof *moved, error);
    if (!moved)
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < line->count; k++)
        moved[k] = onto_lap(p, line->points[k]);
    GEOSGeometry *carried = allow_line(j->geos, moved, line->count);
    free(moved);
    GEOSGeometry *parts = carried ? GEOSIntersection_r(j->geos, carried, inside) : NULL;
    if (carried)
        GEOSGeom_destroy_r(j->geos, carried);
    if (!parts)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not carry a kerf onto a lap");
    ur_status status = UR_OK;
    ur_piece *piece = &j->pieces[p->piece];
    for (int k = 0; status == UR_OK && k < GEOSGetNumGeometries_r(j->geos, parts); k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(j->geos, parts, k);
        const GEOSCoordSequence *sequence =
            part && GEOSGeomTypeId_r(j->geos, part) == GEOS_LINESTRING
                ? GEOSGeom_getCoordSeq_r(j->geos, part)
                : NULL;
        unsigned size = 0;
        if (!sequence || !GEOSCoordSeq_getSize_r(j->geos, sequence, &size) || size < 2)
            continue;
        ur_vec2 ends[2];
        GEOSCoordSeq_getXY_r(j->geos, sequence, 0, &ends[0].x, &ends[0].y);
        GEOSCoordSeq_getXY_r(j->geos, sequence, size - 1, &ends[1].x, &ends[1].y);
        if (ur_vec2_distance(ends[0], ends[1]) > j->options->lap_kerf_margin)
            status = ur_piece_add_path(piece, UR_OP_KERF, ends, 2, false, error);
    }
    GEOSGeom_destroy_r(j->geos, parts);
    return status;
}

/*
 * A lap lies on the other piece's lapped zone and must bend as it does:
 * the zone's kerf lines (straight: grooves and slits) are carried onto it,
 * kept the margin inside its edges.
 */
static ur_status hinge_lap(const joiner *j, const placed_joint *p, ur_error *error)
{
    const ur_piece *under = &j->pieces[p->under_piece];
    size_t count = under->path_count; /* the lap may be on the same piece: not its new lines */
    double margin = j->options->lap_kerf_margin;
    GEOSGeometry *inside = margin > 0 ? GEOSBuffer_r(j->geos, p->shape, -margin, 8)
                                      : GEOSGeom_clone_r(j->geos, p->shape);
    if (!inside)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not shrink a lap");
    ur_status status = UR_OK;
    for (size_t i = 1; status == UR_OK && i < count; i++) {
        const ur_path *line = &j->pieces[p->under_piece].paths[i];
        if (line->op == UR_OP_KERF && !line->closed && line->count == 2)
            status = carry_line(j, p, line, inside, error);
    }
    GEOSGeom_destroy_r(j->geos, inside);
    return status;
}

/* What a kept joint adds: folds (tab) or marks on both pieces (lap), a lap its hinge. */
static ur_status finish_joint(const joiner *j, const placed_joint *p, ur_error *error)
{
    ur_piece *piece = &j->pieces[p->piece];
    if (!j->options->lap)
        return add_folds(j, piece, &p->base, error);
    ur_status status = j->options->lap_kerfs ? hinge_lap(j, p, error) : UR_OK;
    if (status == UR_OK)
        status = add_mark(j, piece, p->shape, error);
    if (status == UR_OK)
        status = mark_under(j, p->under_piece, &p->under, error);
    return status;
}

/* One record per side of a seam for its joints there, placed[from .. to - 1] being the seam's. */
static ur_status record_seam(joiner *j, size_t from, size_t to, ur_error *error)
{
    char label[16];
    ur_seam_label(j->placed[from].seam, label, sizeof label);
    ur_status status = UR_OK;
    for (int side = 0; status == UR_OK && side < 2; side++) {
        size_t kept = 0, dropped = 0, reduced = 0, first = to;
        double depth = 0;
        for (size_t k = from; k < to; k++) {
            const placed_joint *p = &j->placed[k];
            if (p->side != side)
                continue;
            if (!p->kept) {
                dropped++;
                continue;
            }
            if (first == to)
                first = k;
            kept++;
            reduced += p->reduced;
            depth = fmax(depth, p->depth);
        }
        const placed_joint *p = first < to ? &j->placed[first] : NULL;
        ur_piece *piece = p ? &j->pieces[p->piece] : NULL;
        char smaller[48] = "";
        if (reduced)
            c_snprintf(smaller, sizeof smaller, " (%zu made smaller to fit)", reduced);
        if (p && j->options->lap)
            status = record(piece, UR_ALLOWANCE_JOINT, run_middle(&p->base), kept, false, error,
                            "lap %.3g mm under seam %s, marked on both pieces%s", depth, label,
                            reduced ? " (made smaller to fit)" : "");
        else if (p)
            status = record(piece, UR_ALLOWANCE_JOINT, run_middle(&p->base), kept, false, error,
                            "%zu glue tab%s on seam %s, up to %.3g mm deep%s", kept,
                            kept == 1 ? "" : "s", label, depth, smaller);
        for (size_t k = from; status == UR_OK && dropped && k < to; k++)
            if (j->placed[k].side == side && !j->placed[k].kept)
                status = record(&j->pieces[j->placed[k].piece], UR_ALLOWANCE_JOINT,
                                run_middle(&j->placed[k].base), 0, true, error,
                                "a %s on seam %s was left off: the piece's outline would not "
                                "stay one ring with it: join it by hand",
                                j->options->lap ? "lap" : "glue tab", label);
    }
    return status;
}

static ur_status finish_all(joiner *j, ur_error *error)
{
    ur_status status = UR_OK;
    for (size_t n = 0; status == UR_OK && n < j->nets->count; n++)
        status = grow_piece(j, n, error);
    for (size_t k = 0; status == UR_OK && k < j->placed_count; k++)
        if (j->placed[k].kept)
            status = finish_joint(j, &j->placed[k], error);
    for (size_t from = 0; status == UR_OK && from < j->placed_count;) {
        size_t to = from + 1;
        while (to < j->placed_count && j->placed[to].seam == j->placed[from].seam)
            to++;
        status = record_seam(j, from, to, error);
        from = to;
    }
    return status;
}

/* ---- Labels ---------------------------------------------------------------- */

/*
 * The seam's direction where its label goes: that of the segment there.
 * A side that is a closed loop (the rim of a hole, the whole outline of a
 * piece) ends where it starts, so its chord says nothing; a zero-length
 * segment falls back to the chord, and that to +x.
 */
static ur_vec2 direction_at(const run *r, size_t segment)
{
    ur_vec2 along = ur_vec2_sub(r->points[segment + 1], r->points[segment]);
    if (!(ur_vec2_length(along) > 0))
        along = ur_vec2_sub(r->points[r->count - 1], r->points[0]);
    if (!(ur_vec2_length(along) > 0) || !isfinite(along.x) || !isfinite(along.y))
        along = ur_vec2_make(1, 0);
    return along;
}

/*
 * Engraves one label for the joints: the place and direction are ours, so
 * a refusal of them is our failure (UR_ERROR_INTERNAL), never bad input.
 */
static ur_status engrave_label(allow_room *room, const ur_piece *piece, const ur_font *font,
                               const char *text, ur_vec2 near, ur_vec2 along, double height,
                               double clearance, double reach, bool *placed, ur_error *error)
{
    ur_status status = allow_room_add_label(room, font, text, near, along, height, 0.5 * height,
                                            clearance, reach, placed, error);
    if (status == UR_ERROR_INPUT) {
        if (error)
            error->status = UR_ERROR_INTERNAL;
        ur_error_prefix(error, "piece %s: ", piece->name);
        return UR_ERROR_INTERNAL;
    }
    return status;
}

/*
 * A label near a place on its piece: clear of every line, else across the
 * net's folds, still clear of every other line (on a fine mesh no face may
 * be as large as a label, and a label engraved over a fold still reads).
 * Tabs go on after the labels: their folds are not crossed.  Laps go on
 * before the labels, and a label keeps out of the laps and the zones they
 * cover (the room's zones) where it can; on a piece too narrow for that
 * (every point of a strip is near a seam) it goes into one, else across
 * the lines that mark them, rather than nowhere: it still tells the maker
 * which edge goes where before the lap covers it.
 */
static ur_status engrave_near(allow_room *room, const ur_piece *piece, const ur_font *font,
                              const char *text, ur_vec2 near, ur_vec2 along, double height,
                              double clearance, double reach, bool *placed, ur_error *error)
{
    ur_status status = UR_OK;
    *placed = false;
    int rules = allow_room_has_zones(room) ? ALLOW_ZONES_CROSSED : ALLOW_ZONES_KEPT_OUT;
    for (int zones = ALLOW_ZONES_KEPT_OUT; zones <= rules; zones++) {
        allow_room_zone_rule(room, (allow_zone_rule)zones);
        for (int cross = 0; status == UR_OK && !*placed && cross < 2; cross++) {
            allow_room_cross_folds(room, cross == 1);
            status = engrave_label(room, piece, font, text, near, along, height, clearance, reach,
                                   placed, error);
        }
        allow_room_cross_folds(room, false);
        if (status != UR_OK || *placed)
            break;
    }
    allow_room_zone_rule(room, ALLOW_ZONES_KEPT_OUT);
    return status;
}

/* A label that found no room on its piece beside its seam, to try again on its tab. */
typedef struct unplaced_label {
    size_t piece;
    int seam, side; /* side: -1 for the piece's name */
    ur_vec2 where;
} unplaced_label;

/* The rooms for labels, one per piece, opened when first needed; the labels left over. */
typedef struct rooms {
    allow_room **of;
    ur_piece *pieces;
    size_t count;
    unplaced_label *unplaced;
    size_t unplaced_count;
    size_t *zones_from; /* laps: each piece's path count before its joints, its zones after */
} rooms;

static ur_status leave_for_tabs(rooms *r, size_t piece, int seam, int side, ur_vec2 where,
                                ur_error *error)
{
    unplaced_label *grown = realloc(r->unplaced, (r->unplaced_count + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    r->unplaced = grown;
    r->unplaced[r->unplaced_count++] = (unplaced_label){piece, seam, side, where};
    return UR_OK;
}

static void rooms_close(rooms *r)
{
    for (size_t n = 0; r->of && n < r->count; n++) {
        allow_room_close(r->of[n]);
        r->of[n] = NULL;
    }
}

static ur_status room_of(rooms *r, size_t piece, allow_room **room, ur_error *error)
{
    if (!r->of[piece]) {
        size_t zones_from = r->zones_from ? r->zones_from[piece] : SIZE_MAX;
        ur_status status = allow_room_open(&r->pieces[piece], zones_from, &r->of[piece], error);
        if (status != UR_OK)
            return status;
    }
    *room = r->of[piece];
    return UR_OK;
}

static ur_status label_side(const joiner *j, rooms *r, size_t piece_index, const run *seam_run,
                            int seam, int side, const char *text, ur_error *error)
{
    const ur_joint_options *o = j->options;
    ur_piece *piece = &j->pieces[piece_index];
    size_t segment;
    ur_vec2 middle = point_at(seam_run, seam_run->length / 2, &segment);
    ur_vec2 inward = ur_vec2_scale(segment_normal(seam_run, segment), -1.0);
    /* Beside the seam; with laps beyond the zone the other piece covers. */
    double lapped = o->lap ? o->lap_width : 0.0;
    ur_vec2 near = ur_vec2_add_scaled(middle, inward, lapped + 0.5 * o->label_height + 1.0);
    double clearance = fmax(0.3, 0.15 * o->label_height);
    /* A label far from its seam tells nothing: it stays within a few of its own lengths. */
    double reach = lapped + 12 * o->label_height + 0.5 * seam_run->length;
    allow_room *room;
    bool placed;
    ur_status status = room_of(r, piece_index, &room, error);
    if (status == UR_OK)
        status = engrave_near(room, piece, o->font, text, near, direction_at(seam_run, segment),
                              o->label_height, clearance, reach, &placed, error);
    if (status == UR_OK && !placed)
        status = leave_for_tabs(r, piece_index, seam, side, middle, error);
    return status;
}

/*
 * Whether the seam's two sides follow each other on one piece's outline,
 * meeting at a corner (*corner: its index on the outline): a notch or a
 * slit that closes as the piece is folded, its two edges plainly going
 * together (Blender's paper model numbers no such pair).
 */
static bool sides_meet(const joiner *j, const seam_sides *s, size_t *corner)
{
    if (s->net[0] != s->net[1])
        return false;
    const ur_net *net = &j->nets->nets[s->net[0]];
    const ur_seam_side *a = &net->seam_sides[s->side[0]], *b = &net->seam_sides[s->side[1]];
    size_t n = net->outline_count;
    size_t end_of_a = (a->first + a->count - 1) % n, end_of_b = (b->first + b->count - 1) % n;
    *corner = end_of_a == b->first % n ? end_of_a : end_of_b;
    return end_of_a == b->first % n || end_of_b == a->first % n;
}

/*
 * Both sides of a seam get its label, or one side when the sides meet at
 * a corner (sides_meet): one label then names the notch, where two beside
 * each other crowded it (a fine mesh's pole, cut into a fan of slits, had
 * a pair in each).  Labels go on before tabs, so that they are placed
 * within the net's own outline where they stay in sight; one with no room
 * there goes on its side's tab once the tabs are on (label_on_tabs), where
 * it still tells the maker which edge the tab goes under, as Blender's
 * paper model numbers its tabs.  Laps lie on the other piece, inside its
 * outline: labels go on after them, to keep out from under them and off
 * the lines that mark where they go (engrave_near).
 */
static ur_status label_seam(const joiner *j, rooms *r, const seam_sides *s, int seam,
                            ur_error *error)
{
    char label[16];
    ur_seam_label(seam, label, sizeof label);
    size_t corner;
    int sides = sides_meet(j, s, &corner) ? 1 : 2;
    ur_status status = UR_OK;
    if (sides == 1)
        status = record(&j->pieces[s->net[0]], UR_ALLOWANCE_LABEL,
                        j->nets->nets[s->net[0]].outline[corner], 0, false, error,
                        "seam %s: one label for both sides, which meet at a corner", label);
    for (int k = 0; status == UR_OK && k < sides; k++) {
        const ur_net *net = &j->nets->nets[s->net[k]];
        run seam_run = {0};
        status = run_of(net, &net->seam_sides[s->side[k]], &seam_run, error);
        if (status == UR_OK)
            status = label_side(j, r, s->net[k], &seam_run, seam, k, label, error);
        free(seam_run.points);
    }
    return status;
}

/* The piece's name, sought first round centre (allow_name_centres). */
static ur_status name_piece(const joiner *j, rooms *r, size_t index, ur_vec2 centre,
                            ur_error *error)
{
    ur_piece *piece = &j->pieces[index];
    const ur_joint_options *o = j->options;
    allow_room *room;
    bool placed;
    ur_status status = room_of(r, index, &room, error);
    if (status == UR_OK)
        status = engrave_near(room, piece, o->font, piece->name, centre, ur_vec2_make(1, 0),
                              o->label_height, fmax(0.3, 0.15 * o->label_height), INFINITY, &placed,
                              error);
    if (status == UR_OK && !placed)
        status = leave_for_tabs(r, index, 0, -1, centre, error);
    return status;
}

/*
 * The first joint placed on the seam: the seams are joined in turn, so
 * the joints come in the order of their seams.
 */
static size_t first_joint_of(const joiner *j, int seam)
{
    size_t low = 0, high = j->placed_count;
    while (low < high) {
        size_t middle = low + (high - low) / 2;
        if (j->placed[middle].seam < seam)
            low = middle + 1;
        else
            high = middle;
    }
    return low;
}

/*
 * Tries a label left over on the piece's tabs: those of its seam side, or
 * (the piece's name) any, each from the middle of its top half; along the
 * tab's fold, else across it, reading outward (a fine mesh's tabs are
 * deeper than their edges are long).
 */
static ur_status label_on_a_tab(const joiner *j, allow_room *room, const unplaced_label *u,
                                const char *text, bool *placed, ur_error *error)
{
    const ur_joint_options *o = j->options;
    ur_status status = UR_OK;
    *placed = false;
    for (size_t k = u->side >= 0 ? first_joint_of(j, u->seam) : 0;
         status == UR_OK && !*placed && k < j->placed_count; k++) {
        const placed_joint *p = &j->placed[k];
        if (u->side >= 0 && p->seam != u->seam)
            break;
        if (!p->kept || p->piece != u->piece || (u->side >= 0 && p->side != u->side))
            continue;
        size_t segment;
        ur_vec2 middle = point_at(&p->base, p->base.length / 2, &segment);
        ur_vec2 outward = segment_normal(&p->base, segment);
        ur_vec2 near = ur_vec2_add_scaled(middle, outward, band_of(o) + 0.5 * p->depth);
        ur_vec2 directions[2] = {direction_at(&p->base, segment), outward};
        for (int d = 0; d < 2 && status == UR_OK && !*placed; d++)
            status = engrave_label(room, &j->pieces[u->piece], o->font, text, near, directions[d],
                                   o->label_height, fmax(0.2, 0.1 * o->label_height),
                                   0.5 * (p->base.length + p->depth), placed, error);
    }
    return status;
}

/*
 * The labels that found no room beside their seams, on their tabs now
 * that the outlines have grown by them; a warning for each that still
 * finds none.
 */
static ur_status label_on_tabs(const joiner *j, rooms *r, ur_error *error)
{
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < r->unplaced_count; k++) {
        const unplaced_label *u = &r->unplaced[k];
        ur_piece *piece = &j->pieces[u->piece];
        char text[16];
        if (u->side >= 0)
            ur_seam_label(u->seam, text, sizeof text);
        allow_room *room;
        bool placed = false;
        status = room_of(r, u->piece, &room, error);
        if (status == UR_OK && !j->options->lap)
            status = label_on_a_tab(j, room, u, u->side >= 0 ? text : piece->name, &placed, error);
        if (status != UR_OK || placed)
            continue;
        if (u->side >= 0)
            status = record(piece, UR_ALLOWANCE_LABEL, u->where, 0, true, error,
                            "no room for label %s beside its seam%s", text,
                            j->options->lap ? ", even on a lap" : " or on a tab");
        else
            status = record(piece, UR_ALLOWANCE_LABEL, u->where, 0, true, error,
                            "no room to engrave the piece's name %s", piece->name);
    }
    return status;
}

/* ---- All seams ------------------------------------------------------------ */

/* For each seam number, where its two sides are. */
static ur_status gather_seams(const ur_net_list *nets, seam_sides **seams, int *last,
                              ur_error *error)
{
    *last = ur_net_list_last_seam(nets);
    *seams = calloc((size_t)*last + 1, sizeof **seams);
    if (!*seams)
        return ur_error_out_of_memory(error);
    for (size_t n = 0; n < nets->count; n++)
        for (size_t k = 0; k < nets->nets[n].seam_side_count; k++) {
            int seam = nets->nets[n].seam_sides[k].seam;
            seam_sides *s = &(*seams)[seam];
            if (seam < 1 || s->found == 2)
                continue; /* no seam has more than two sides (develop.h) */
            s->net[s->found] = n;
            s->side[s->found++] = k;
        }
    return UR_OK;
}

/* Tells the progress callback how far a phase is: about a hundred times over its count. */
static void report(const joiner *j, const char *phase, size_t done, size_t count)
{
    const ur_joint_options *o = j->options;
    if (o->progress && (done % (count / 100 + 1) == 0 || done == count))
        o->progress(o->progress_context, phase, count ? (double)done / (double)count : 1.0);
}

static ur_status add_labels(joiner *j, rooms *r, const seam_sides *seams, int last, ur_error *error)
{
    ur_status status = UR_OK;
    for (int seam = 1; status == UR_OK && seam <= last; seam++) {
        report(j, "labels", (size_t)seam - 1, (size_t)last);
        if (seams[seam].found == 2) {
            status = ur_context_check(j->options->context, error);
            if (status == UR_OK)
                status = label_seam(j, r, &seams[seam], seam, error);
        }
    }
    ur_vec2 *centres = NULL;
    if (status == UR_OK && j->options->name_pieces)
        status = allow_name_centres(j->geos, j->pieces, j->nets->count, &centres, error);
    for (size_t n = 0; status == UR_OK && j->options->name_pieces && n < j->nets->count; n++)
        status = name_piece(j, r, n, centres[n], error);
    free(centres);
    if (status == UR_OK)
        report(j, "labels", (size_t)last, (size_t)last);
    /* The tabs change the pieces: rooms are opened again for what is left. */
    rooms_close(r);
    return status;
}

static ur_status check_options(const ur_joint_options *o, ur_error *error)
{
    bool sizes = o->lap ? o->lap_width > 0 && isfinite(o->lap_width)
                        : o->tab_depth > 0 && isfinite(o->tab_depth) && o->tab_angle > 0 &&
                              o->tab_angle <= 90;
    if (!sizes || !(o->thickness >= 0) || !isfinite(o->thickness) ||
        (o->font && !(o->label_height > 0)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "joints need a positive tab depth (angle above 0 up to 90 degrees) "
                            "or lap width, and a positive label height");
    return UR_OK;
}

static void joiner_free(joiner *j)
{
    for (size_t k = 0; k < j->placed_count; k++) {
        GEOSGeom_destroy_r(j->geos, j->placed[k].shape);
        free(j->placed[k].base.points);
        free(j->placed[k].under.points);
    }
    free(j->placed);
    free(j->held);
    for (size_t n = 0; j->boards && n < j->nets->count; n++)
        allow_board_close(j->boards[n]);
    free(j->boards);
    free(j->tab_count);
    if (j->geos)
        GEOS_finish_r(j->geos);
}

/* How far the joints are: told, or kept for the labels' thread to tell (joiner.seams_joined). */
static void report_joints(const joiner *j, size_t done, size_t count)
{
    if (j->seams_joined)
        atomic_store(j->seams_joined, done);
    else
        report(j, j->options->lap ? "laps" : "tabs", done, count);
}

/* A joint on every seam, each tested on its piece's board; their records held. */
static ur_status join_all_seams(joiner *j, const seam_sides *seams, int last, ur_error *error)
{
    ur_status status = UR_OK;
    for (size_t n = 0; status == UR_OK && n < j->nets->count; n++)
        status = allow_board_open(j->geos, j->nets->nets[n].outline, j->nets->nets[n].outline_count,
                                  band_of(j->options) + full_depth(j->options) + j->gap, j->gap,
                                  &j->boards[n], error);
    for (int seam = 1; status == UR_OK && seam <= last; seam++) {
        report_joints(j, (size_t)seam - 1, (size_t)last);
        if (seams[seam].found == 2) {
            status = ur_context_check(j->options->context, error);
            if (status == UR_OK)
                status = join_seam(j, &seams[seam], seam, error);
        }
    }
    return status;
}

/* The joints' records given, then the outlines grown by the joints, and their folds and marks. */
static ur_status finish_joints(joiner *j, int last, ur_error *error)
{
    ur_status status = give_held_records(j, error);
    if (status == UR_OK)
        status = finish_all(j, error);
    if (status == UR_OK)
        report(j, j->options->lap ? "laps" : "tabs", (size_t)last, (size_t)last);
    return status;
}

static ur_status add_all_joints(joiner *j, const seam_sides *seams, int last, ur_error *error)
{
    ur_status status = join_all_seams(j, seams, last, error);
    return status == UR_OK ? finish_joints(j, last, error) : status;
}

/*
 * Tabs and labels side by side: labels go within the net's outline and
 * tabs outside it, tested against the outline and each other alone, so
 * neither waits for the other (a 2,208-triangle sphere's tabs took 33 ms
 * and its labels 12 ms, one after the other).  The tabs are sought in a
 * thread of their own with the joiner (its GEOS context, boards and
 * placed tabs), their records held; the labels here with a copy of it
 * that has a GEOS context of its own and reads the same pieces and nets.
 * This thread tells the labels' progress, then the tabs' while it waits
 * for them.  The pieces get the labels' records, then the tabs', as when
 * one came after the other; the outlines grow by the tabs once both are
 * done.
 */
typedef struct joint_work {
    joiner *j;
    const seam_sides *seams;
    int last;
    atomic_size_t seams_joined;
    mtx_t lock;
    cnd_t ended;
    bool done; /* under lock */
    ur_status status;
    ur_error error;
} joint_work;

static int join_beside(void *data)
{
    joint_work *w = data;
    w->status = join_all_seams(w->j, w->seams, w->last, &w->error);
    mtx_lock(&w->lock);
    w->done = true;
    cnd_signal(&w->ended);
    mtx_unlock(&w->lock);
    return 0;
}

/* How often the tabs' progress is told while the labels' thread waits for them. */
#define PROGRESS_SECONDS 0.1

/* Tells the tabs' progress as the thread beside reports it (never held back, as report() is). */
static void report_beside(const joiner *j, const joint_work *w)
{
    const ur_joint_options *o = j->options;
    size_t done = atomic_load(&w->seams_joined);
    if (o->progress && w->last > 0)
        o->progress(o->progress_context, "tabs", (double)done / (double)w->last);
}

/* Waits for the tabs' thread, telling how far it is at once and then now and then. */
static void wait_for_joints(const joiner *j, joint_work *w)
{
    mtx_lock(&w->lock);
    report_beside(j, w);
    while (!w->done) {
        struct timespec until;
        timespec_get(&until, TIME_UTC);
        until.tv_nsec += (long)(PROGRESS_SECONDS * 1e9);
        if (until.tv_nsec >= 1000000000L) {
            until.tv_sec++;
            until.tv_nsec -= 1000000000L;
        }
        cnd_timedwait(&w->ended, &w->lock, &until);
        report_beside(j, w);
    }
    mtx_unlock(&w->lock);
}

static ur_status tabs_beside_labels(joiner *j, rooms *r, const seam_sides *seams, int last,
                                    ur_error *error)
{
    joint_work w = {.j = j, .seams = seams, .last = last, .status = UR_OK};
    atomic_init(&w.seams_joined, 0);
    bool lock = mtx_init(&w.lock, mtx_plain) == thrd_success;
    bool signal = lock && cnd_init(&w.ended) == thrd_success;
    joiner labels = *j; /* copied before the tabs' thread changes j */
    labels.geos = signal ? GEOS_init_r() : NULL;
    j->seams_joined = &w.seams_joined;
    thrd_t thread;
    bool beside = labels.geos && thrd_create(&thread, join_beside, &w) == thrd_success;
    ur_status status = UR_OK;
    if (beside) {
        status = add_labels(&labels, r, seams, last, error);
        wait_for_joints(j, &w);
        thrd_join(thread, NULL);
        if (status == UR_OK && w.status != UR_OK) {
            *error = w.error;
            status = w.status;
        }
    } else { /* no thread: the tabs after the labels */
        j->seams_joined = NULL;
        status = add_labels(j, r, seams, last, error);
        if (status == UR_OK)
            status = join_all_seams(j, seams, last, error);
    }
    j->seams_joined = NULL;
    if (labels.geos)
        GEOS_finish_r(labels.geos);
    if (signal)
        cnd_destroy(&w.ended);
    if (lock)
        mtx_destroy(&w.lock);
    return status == UR_OK ? finish_joints(j, last, error) : status;
}

/* Laps, then labels kept out of the zones the laps lie on (the marks they add). */
static ur_status add_laps_then_labels(joiner *j, rooms *r, const seam_sides *seams, int last,
                                      ur_error *error)
{
    r->zones_from = ur_alloc_array(r->count + 1, sizeof *r->zones_from, error);
    if (!r->zones_from)
        return UR_ERROR_MEMORY;
    for (size_t n = 0; n < r->count; n++)
        r->zones_from[n] = j->pieces[n].path_count;
    ur_status status = add_all_joints(j, seams, last, error);
    if (status == UR_OK && j->options->font)
        status = add_labels(j, r, seams, last, error);
    return status;
}

ur_status ur_pieces_add_joints(ur_piece *pieces, const ur_net_list *nets,
                               const ur_joint_options *options, ur_error *error)
{
    ur_status status = check_options(options, error);
    if (status != UR_OK)
        return status;
    for (size_t n = 0; n < nets->count; n++)
        if (pieces[n].path_count == 0 || !pieces[n].paths[0].closed || pieces[n].paths[0].count < 3)
            return ur_error_set(error, UR_ERROR_INTERNAL, "piece %s has no closed outline",
                                pieces[n].name);
    seam_sides *seams = NULL;
    int last = 0;
    rooms r = {calloc(nets->count + 1, sizeof(allow_room *)), pieces, nets->count, NULL, 0, NULL};
    joiner j = {.geos = GEOS_init_r(),
                .pieces = pieces,
                .nets = nets,
                .options = options,
                .boards = calloc(nets->count + 1, sizeof(allow_board *)),
                .tab_count = calloc(nets->count + 1, sizeof(size_t)),
                .gap = fmax(0.2, 0.5 * options->thickness)};
    if (!j.geos || !j.boards || !j.tab_count || !r.of)
        status = ur_error_out_of_memory(error);
    if (status == UR_OK)
        status = gather_seams(nets, &seams, &last, error);
    if (status == UR_OK && options->lap)
        status = add_laps_then_labels(&j, &r, seams, last, error);
    else if (status == UR_OK && options->font)
        status = tabs_beside_labels(&j, &r, seams, last, error);
    else if (status == UR_OK)
        status = add_all_joints(&j, seams, last, error);
    if (status == UR_OK && options->font)
        status = label_on_tabs(&j, &r, error);
    rooms_close(&r);
    free(r.of);
    free(r.zones_from);
    free(r.unplaced);
    free(seams);
    joiner_free(&j);
    return status;
}
