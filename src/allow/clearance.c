/*
 * clearance.c: what a piece's joints must keep clear of (allow_internal.h,
 * allow_board), so that each test of a joint looks only at what is near.
 *
 * A board holds one piece's net outline, cut into its edges in a GEOS
 * STRtree, and the joints placed on it so far in a grid (grid.c), which
 * takes new ones between queries.  A joint is tested against both with
 * two regions: inner, the joint shrunk by TOUCH, which nothing may meet;
 * outer, the joint grown by the gap on its outward side only (beyond its
 * base's chord), which nothing may meet but what shares a corner with the
 * joint's edges, and that only at the corner: the outline's neighbouring
 * edges and the joints on them touch it at the seam's corners, where the
 * notch between two tabs closes.  Where such a neighbour comes near the
 * joint away from the corner (a tab across a narrow notch, nearly touching
 * its other side) the notch would close there too, leaving a pocket no
 * cutter can reach.  Behind the base is the piece itself, whose outline
 * runs on from the base's ends.
 */
#include "allow_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/*
 * Joints sharing a corner may touch there but not overlap: each is tested
 * shrunk by this much (mm), far below a cutter's resolution, so that
 * rounding where they meet is no clash.
 */
#define TOUCH 1e-4

/* What meets() is told for a joint, which is no edge of the outline. */
#define NOT_AN_EDGE SIZE_MAX

/* A joint on the board: its shape (the caller's), the outline edges under it, the caller's tag. */
typedef struct board_joint {
    const GEOSGeometry *shape;
    size_t first, edges;
    size_t tag;
} board_joint;

struct allow_board {
    GEOSContextHandle_t geos;
    double gap;
    ur_vec2 *corners; /* owned: the outline's points, edge e from corners[e] */
    GEOSSTRtree *tree;
    GEOSGeometry **segments; /* owned: outline edge e from point e to e + 1 */
    size_t *edge_ids;        /* the tree's items: edge_ids[e] == e */
    size_t edge_count;
    allow_grid grid;
    board_joint *joints; /* per grid item */
    size_t joint_capacity;
    allow_items found; /* what a query found */
    bool out_of_memory;
};

void allow_board_close(allow_board *b)
{
    if (!b)
        return;
    if (b->tree)
        GEOSSTRtree_destroy_r(b->geos, b->tree);
    for (size_t e = 0; b->segments && e < b->edge_count; e++)
        if (b->segments[e])
            GEOSGeom_destroy_r(b->geos, b->segments[e]);
    free(b->segments);
    free(b->edge_ids);
    free(b->corners);
    free(b->joints);
    allow_grid_free(&b->grid);
    allow_items_free(&b->found);
    free(b);
}

ur_status allow_board_open(GEOSContextHandle_t geos, const ur_vec2 *outline, size_t count,
                           double reach, double gap, allow_board **board, ur_error *error)
{
    *board = NULL;
    allow_board *b = calloc(1, sizeof *b);
    if (!b)
        return ur_error_out_of_memory(error);
    b->geos = geos;
    b->gap = gap;
    b->edge_count = count;
    b->tree = GEOSSTRtree_create_r(geos, 8);
    b->segments = calloc(count ? count : 1, sizeof *b->segments);
    b->edge_ids = calloc(count ? count : 1, sizeof *b->edge_ids);
    b->corners = calloc(count ? count : 1, sizeof *b->corners);
    ur_status status =
        b->tree && b->segments && b->edge_ids && b->corners ? UR_OK : ur_error_out_of_memory(error);
    if (status == UR_OK && count > 0)
        memcpy(b->corners, outline, count * sizeof *outline);
    for (size_t e = 0; status == UR_OK && e < count; e++) {
        ur_vec2 ends[2] = {outline[e], outline[(e + 1) % count]};
        b->segments[e] = allow_line(geos, ends, 2);
        if (!b->segments[e]) {
            status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not build an outline");
            break;
        }
        b->edge_ids[e] = e;
        GEOSSTRtree_insert_r(geos, b->tree, b->segments[e], &b->edge_ids[e]);
    }
    ur_box region = ur_box_of_points(outline, count);
    region.min = ur_vec2_add(region.min, ur_vec2_make(-reach, -reach));
    region.max = ur_vec2_add(region.max, ur_vec2_make(reach, reach));
    if (status == UR_OK)
        status = allow_grid_init(&b->grid, region, reach, error);
    if (status != UR_OK) {
        allow_board_close(b);
        return status;
    }
    *board = b;
    return UR_OK;
}

ur_status allow_board_add(allow_board *b, const GEOSGeometry *shape, size_t first, size_t edges,
                          size_t tag, ur_error *error)
{
    if (b->grid.count == b->joint_capacity) {
        size_t capacity = b->joint_capacity ? 2 * b->joint_capacity : 16;
        board_joint *joints = realloc(b->joints, capacity * sizeof *joints);
        if (!joints)
            return ur_error_out_of_memory(error);
        b->joints = joints;
        b->joint_capacity = capacity;
    }
    b->joints[b->grid.count] = (board_joint){shape, first, edges, tag};
    return allow_grid_add(&b->grid, allow_box(b->geos, shape), NULL, error);
}

void allow_board_replace(allow_board *b, size_t tag, const GEOSGeometry *shape)
{
    for (size_t k = 0; k < b->grid.count; k++)
        if (b->joints[k].tag == tag)
            b->joints[k].shape = shape;
}

size_t allow_board_joint_count(const allow_board *b)
{
    return b->grid.count;
}

size_t allow_board_joint_tag(const allow_board *b, size_t k)
{
    return b->joints[k].tag;
}

/*
 * How edges [a, a + la) of an outline of n edges stand to a joint's
 * [c, c + lc): overlapping (sharing an edge), or meeting at up to two
 * corners (the outline's points where one run ends and the other begins).
 */
typedef struct contact {
    bool overlap;
    size_t corner_count;
    size_t corners[2];
} contact;

static contact contact_of(size_t n, size_t a, size_t la, size_t c, size_t lc)
{
    contact with = {.overlap = (c + n - a) % n < la || (a + n - c) % n < lc};
    if (!with.overlap && (c + n - a) % n == la)
        with.corners[with.corner_count++] = c;
    if (!with.overlap && (a + n - c) % n == lc)
        with.corners[with.corner_count++] = a;
    return with;
}

static void collect_edge(void *item, void *userdata)
{
    allow_board *b = userdata;
    if (allow_items_push(&b->found, *(const size_t *)item, NULL) != UR_OK)
        b->out_of_memory = true;
}

/*
 * The joint's two test regions: inner, the joint shrunk by TOUCH, which
 * nothing may meet; outer, the joint grown by the gap on its outward side
 * only (beyond its base's chord, lifted by TOUCH), which nothing but what
 * shares a corner with it may meet.  Behind the base is the piece itself,
 * whose outline runs on from the base's ends.
 */
typedef struct regions {
    GEOSGeometry *shrunk, *grown, *clipped;
    const GEOSPreparedGeometry *inner, *outer;
    ur_points clipped_ring; /* clipped's points, first not repeated */
    bool out_of_memory;     /* making them: not a joint that cannot go, a run that must stop */
} regions;

static void regions_free(const allow_board *b, regions *r)
{
    if (r->inner)
        GEOSPreparedGeom_destroy_r(b->geos, r->inner);
    if (r->outer)
        GEOSPreparedGeom_destroy_r(b->geos, r->outer);
    GEOSGeometry *all[] = {r->shrunk, r->grown, r->clipped};
    for (size_t k = 0; k < 3; k++)
        if (all[k])
            GEOSGeom_destroy_r(b->geos, all[k]);
    ur_points_free(&r->clipped_ring);
}

/*
 * The line outward of which the joint's outer region lies: the base's
 * chord, lifted by TOUCH past the base's own points (which may stray from
 * a straight chord); *out is its outward unit normal, *level the value of
 * dot(point, out) on it.  False for a base of no length.
 */
static bool outward_line(const ur_vec2 *base, size_t count, ur_vec2 *out, double *level)
{
    ur_vec2 a = base[0], along = ur_vec2_sub(base[count - 1], a);
    double length = ur_vec2_length(along);
    if (!(length > 0))
        return false;
    *out = ur_vec2_make(along.y / length, -along.x / length);
    double lift = TOUCH;
    for (size_t k = 0; k < count; k++)
        lift = fmax(lift, TOUCH + ur_vec2_dot(ur_vec2_sub(base[k], a), *out));
    *level = ur_vec2_dot(a, *out) + lift;
    return true;
}

/*
 * The polygon's exterior ring clipped to the half-plane dot(p, out) >=
 * level (Sutherland and Hodgman: the grown joint of a tab is convex, so
 * the clipped ring is too), as a polygon; NULL when nothing is left.
 */
static GEOSGeometry *clip_outward(const allow_board *b, const GEOSGeometry *polygon, ur_vec2 out,
                                  double level, ur_points *kept_ring, bool *out_of_memory)
{
    const GEOSGeometry *shell = GEOSGetExteriorRing_r(b->geos, polygon);
    const GEOSCoordSequence *sequence = shell ? GEOSGeom_getCoordSeq_r(b->geos, shell) : NULL;
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(b->geos, sequence, &size) || size < 4)
        return NULL;
    ur_points kept = {0};
    bool failed = false;
    ur_vec2 previous;
    GEOSCoordSeq_getXY_r(b->geos, sequence, size - 2, &previous.x, &previous.y);
    for (unsigned i = 0; i + 1 < size && !failed; i++) {
        ur_vec2 point;
        GEOSCoordSeq_getXY_r(b->geos, sequence, i, &point.x, &point.y);
        double before = ur_vec2_dot(previous, out) - level, after = ur_vec2_dot(point, out) - level;
        if ((before >= 0) != (after >= 0)) /* the edge crosses the line: keep where */
            failed = ur_points_push(&kept,
                                    ur_vec2_add_scaled(previous, ur_vec2_sub(point, previous),
                                                       before / (before - after)),
                                    NULL) != UR_OK;
        if (after >= 0 && !failed)
            failed = ur_points_push(&kept, point, NULL) != UR_OK;
        previous = point;
    }
    GEOSGeometry *clipped =
        !failed && kept.count >= 3 ? geos_polygon_of_ring(b->geos, kept.items, kept.count) : NULL;
    *kept_ring = kept;
    *out_of_memory = failed;
    return clipped;
}

/*
 * Whether the ring (counter-clockwise, first point not repeated) is
 * convex with no edge of zero length: a tab is, a lap on a bent seam is not.
 */
static bool convex_ring(const ur_vec2 *ring, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        ur_vec2 a = ring[i], b = ring[(i + 1) % n], c = ring[(i + 2) % n];
        if (!(ur_vec2_length(ur_vec2_sub(b, a)) > 0) ||
            ur_vec2_cross(ur_vec2_sub(b, a), ur_vec2_sub(c, b)) < 0)
            return false;
    }
    return true;
}

/* The outward unit normals of the ring's sides before and after corner i (counter-clockwise). */
static void corner_normals(const ur_vec2 *ring, size_t n, size_t i, ur_vec2 *before, ur_vec2 *after)
{
    ur_vec2 p = ring[(i + n - 1) % n], q = ring[i], r = ring[(i + 1) % n];
    ur_vec2 d0 = ur_vec2_sub(q, p), d1 = ur_vec2_sub(r, q);
    *before = ur_vec2_scale(ur_vec2_make(d0.y, -d0.x), 1 / ur_vec2_length(d0));
    *after = ur_vec2_scale(ur_vec2_make(d1.y, -d1.x), 1 / ur_vec2_length(d1));
}

/* Where the two sides at corner q meet once each is moved out by distance along its normal. */
static ur_vec2 mitre_point(ur_vec2 q, ur_vec2 n0, ur_vec2 n1, double distance)
{
    return ur_vec2_add_scaled(q, ur_vec2_add(n0, n1), distance / (1 + ur_vec2_dot(n0, n1)));
}

/*
 * A convex ring moved out by distance (in when negative) with mitred
 * corners, as a polygon: GEOS's buffer is exact but slow for the many
 * joints of a large mesh, and a convex joint's corners are no sharper
 * than 45 degrees, so a mitre is at most 2.7 times the distance.
 */
static GEOSGeometry *offset_convex(const allow_board *b, const ur_vec2 *ring, size_t n,
                                   double distance, bool *out_of_memory)
{
    ur_vec2 *moved = malloc(n * sizeof *moved);
    if (!moved) {
        *out_of_memory = true;
        return NULL;
    }
    for (size_t i = 0; i < n; i++) {
        ur_vec2 n0, n1;
        corner_normals(ring, n, i, &n0, &n1);
        moved[i] = mitre_point(ring[i], n0, n1, distance);
    }
    GEOSGeometry *polygon = geos_polygon_of_ring(b->geos, moved, n);
    free(moved);
    return polygon;
}

/*
 * Whether a mitred offset of the ring (counter-clockwise, first point not
 * repeated) is worth trying: no edge of zero length and no corner sharper
 * than a tab's, whose mitre would reach far.  A tab on a stretch of
 * several edges that is not quite straight has such a ring, convex but
 * for its base's points.
 */
static bool mitres_well(const ur_vec2 *ring, size_t n)
{
    double area = 0;
    for (size_t i = 0; i < n; i++)
        area += ur_vec2_cross(ring[i], ring[(i + 1) % n]);
    if (!(area > 0))
        return false;
    for (size_t i = 0; i < n; i++) {
        ur_vec2 d0 = ur_vec2_sub(ring[(i + 1) % n], ring[i]);
        ur_vec2 d1 = ur_vec2_sub(ring[(i + 2) % n], ring[(i + 1) % n]);
        double l0 = ur_vec2_length(d0), l1 = ur_vec2_length(d1);
        if (!(l0 > 0 && l1 > 0) || ur_vec2_dot(d0, d1) / (l0 * l1) < -0.9)
            return false;
    }
    return true;
}

/* The polygon if GEOS finds it valid; else NULL, the polygon freed. */
static GEOSGeometry *valid_or_none(const allow_board *b, GEOSGeometry *polygon)
{
    if (polygon && GEOSisValid_r(b->geos, polygon) != 1) {
        GEOSGeom_destroy_r(b->geos, polygon);
        return NULL;
    }
    return polygon;
}

/*
 * The ring moved out by distance, its convex corners rounded as GEOS's
 * buffer with two segments a quarter turn rounds them (points on the
 * circle, in equal steps, as many as 45 degree steps fit the turn, rounded,
 * and at least one), its concave ones where the moved edges meet: a valid
 * polygon (nothing swallowed), else NULL.
 */
static GEOSGeometry *rounded_outward(const allow_board *b, const ur_vec2 *ring, size_t n,
                                     double distance, bool *out_of_memory)
{
    ur_points moved = {0};
    bool failed = false;
    for (size_t i = 0; i < n && !failed; i++) {
        ur_vec2 q = ring[i], n0, n1;
        corner_normals(ring, n, i, &n0, &n1);
        ur_vec2 d0 = ur_vec2_sub(q, ring[(i + n - 1) % n]), d1 = ur_vec2_sub(ring[(i + 1) % n], q);
        if (ur_vec2_cross(d0, d1) <= 0) { /* concave or straight: the sides' lines meet */
            failed = ur_points_push(&moved, mitre_point(q, n0, n1, distance), NULL) != UR_OK;
            continue;
        }
        double from = atan2(n0.y, n0.x), turn = atan2(ur_vec2_cross(n0, n1), ur_vec2_dot(n0, n1));
        int steps = (int)(turn / (M_PI / 4) + 0.5); /* as GEOS divides a turn */
        steps = steps > 0 ? steps : 1;
        for (int k = 0; k <= steps && !failed; k++) {
            double angle = from + turn * (double)k / (double)steps;
            failed =
                ur_points_push(
                    &moved, ur_vec2_add_scaled(q, ur_vec2_make(cos(angle), sin(angle)), distance),
                    NULL) != UR_OK;
        }
    }
    GEOSGeometry *polygon = failed ? NULL : geos_polygon_of_ring(b->geos, moved.items, moved.count);
    *out_of_memory = failed;
    ur_points_free(&moved);
    return valid_or_none(b, polygon);
}

/* offset_convex's polygon for any ring, if valid (nothing swallowed); NULL otherwise. */
static GEOSGeometry *offset_valid(const allow_board *b, const ur_vec2 *ring, size_t n,
                                  double distance, bool *out_of_memory)
{
    return valid_or_none(b, offset_convex(b, ring, n, distance, out_of_memory));
}

/*
 * The joint shrunk and grown: by offset_convex when it is convex; when it
 * is convex but for a few corners (mitres_well), shrunk mitred and grown
 * by rounded_outward, each if it stays valid (GEOS's buffer cost a
 * quarter of a papercraft sphere's tabs); by GEOS's buffer otherwise.
 */
static void shrink_and_grow(const allow_board *b, const GEOSGeometry *joint, regions *r)
{
    ur_vec2 *ring = NULL;
    size_t n = 0;
    ur_status status = allow_exterior_ring(b->geos, joint, &ring, &n, NULL);
    r->out_of_memory = status == UR_ERROR_MEMORY;
    if (r->out_of_memory)
        return;
    if (status == UR_OK && convex_ring(ring, n)) {
        r->shrunk = offset_convex(b, ring, n, -TOUCH, &r->out_of_memory);
        r->grown = offset_convex(b, ring, n, b->gap, &r->out_of_memory);
    } else if (status == UR_OK && mitres_well(ring, n)) {
        r->shrunk = offset_valid(b, ring, n, -TOUCH, &r->out_of_memory);
        r->grown = r->shrunk ? rounded_outward(b, ring, n, b->gap, &r->out_of_memory) : NULL;
    }
    if (!r->out_of_memory && !r->shrunk)
        r->shrunk = GEOSBuffer_r(b->geos, joint, -TOUCH, 1);
    if (!r->out_of_memory && !r->grown)
        r->grown = GEOSBuffer_r(b->geos, joint, b->gap, 2);
    free(ring);
}

static bool regions_make(const allow_board *b, const GEOSGeometry *joint, const ur_vec2 *base,
                         size_t count, regions *r)
{
    memset(r, 0, sizeof *r);
    shrink_and_grow(b, joint, r);
    ur_vec2 out;
    double level;
    if (!r->shrunk || !r->grown || GEOSisEmpty_r(b->geos, r->shrunk) ||
        GEOSGeomTypeId_r(b->geos, r->grown) != GEOS_POLYGON ||
        !outward_line(base, count, &out, &level))
        return false;
    r->clipped = clip_outward(b, r->grown, out, level, &r->clipped_ring, &r->out_of_memory);
    if (!r->clipped)
        return false;
    r->inner = GEOSPrepare_r(b->geos, r->shrunk);
    r->outer = GEOSPrepare_r(b->geos, r->clipped);
    return r->inner && r->outer;
}

/* The sides of an outer region whose meetings with an edge edge_away_from_corners finds itself. */
#define MOST_SIDES 64

/*
 * Where an edge meets a region's sides, as parameters along it: two per
 * side at most, and its ends.
 */
typedef struct meetings {
    double at[2 * MOST_SIDES + 2];
    size_t count;
} meetings;

static void add_meeting(meetings *m, double t)
{
    m->at[m->count++] = t;
}

/*
 * Adds where segment p0 + t d meets the side a + u e (0 <= t, u <= 1):
 * nowhere, once, or at both ends of the stretch they share if along it.
 */
static void add_meetings(ur_vec2 p0, ur_vec2 d, ur_vec2 a, ur_vec2 e, meetings *m)
{
    double denominator = ur_vec2_cross(d, e);
    ur_vec2 w = ur_vec2_sub(a, p0);
    double scale = ur_vec2_length(d) * ur_vec2_length(e);
    if (fabs(denominator) > 1e-12 * scale) {
        double t = ur_vec2_cross(w, e) / denominator, u = ur_vec2_cross(w, d) / denominator;
        if (t >= 0 && t <= 1 && u >= 0 && u <= 1)
            add_meeting(m, t);
        return;
    }
    double length2 = ur_vec2_dot(d, d);
    if (!(length2 > 0) || fabs(ur_vec2_cross(w, d)) > 1e-12 * length2) /* parallel, apart */
        return;
    double ta = ur_vec2_dot(w, d) / length2, tb = ur_vec2_dot(ur_vec2_add(w, e), d) / length2;
    double from = fmax(0, fmin(ta, tb)), to = fmin(1, fmax(ta, tb));
    if (from <= to)
        add_meeting(m, from);
    if (from < to)
        add_meeting(m, to);
}

/* Whether p lies inside the ring or on it (crossings, and a side it lies on). */
static bool inside_or_on(const ur_vec2 *ring, size_t n, ur_vec2 p)
{
    bool inside = false;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        ur_vec2 a = ring[j], b = ring[i];
        if (sqrt(allow_distance2_to_segment(p, a, b)) <= 1e-12 * (1 + fabs(p.x) + fabs(p.y)))
            return true;
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y))
            inside = !inside;
    }
    return inside;
}

static int compare_numbers(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/*
 * away_from_corners for outline edge e: the edge cut where it meets the
 * outer region's ring, each piece between two cuts kept if its middle is
 * inside, pieces that touch one part, and a point where the edge only
 * touches the ring a part of its own, as GEOS's overlay gives them (which
 * took a third of the time tabs took on a papercraft sphere).  3 when that
 * leaves nothing although GEOS found the two to meet (a touch, to
 * rounding): then GEOS says.
 */
static char edge_away_from_corners(const allow_board *b, const regions *r, size_t e,
                                   const contact *with)
{
    const ur_vec2 *ring = r->clipped_ring.items;
    size_t n = r->clipped_ring.count;
    if (n > MOST_SIDES)
        return 3;
    ur_vec2 p0 = b->corners[e], p1 = b->corners[(e + 1) % b->edge_count];
    ur_vec2 d = ur_vec2_sub(p1, p0);
    meetings m = {.count = 0};
    for (size_t i = 0; i < n; i++)
        add_meetings(p0, d, ring[i], ur_vec2_sub(ring[(i + 1) % n], ring[i]), &m);
    add_meeting(&m, 0);
    add_meeting(&m, 1);
    qsort(m.at, m.count, sizeof *m.at, compare_numbers);
    size_t unique = 1; /* a meeting at a corner of the ring comes from both its sides */
    for (size_t i = 1; i < m.count; i++)
        if (m.at[i] != m.at[unique - 1])
            m.at[unique++] = m.at[i];
    m.count = unique;
    const double *at = m.at;
    char away = 0;
    bool any = false, open = false; /* a part under way, from part_start */
    double part_start = 0, part_end = 0;
    for (size_t i = 0; i < m.count && away == 0; i++) {
        double t = at[i], next = i + 1 < m.count ? at[i + 1] : t;
        bool inside = next > t && inside_or_on(ring, n, ur_vec2_add_scaled(p0, d, (t + next) / 2));
        bool on_ring = inside_or_on(ring, n, ur_vec2_add_scaled(p0, d, t));
        if (!open && (inside || on_ring)) {
            open = any = true;
            part_start = t;
        }
        if (open)
            part_end = t;
        if (open && !inside) { /* the part ends at t */
            ur_vec2 from = ur_vec2_add_scaled(p0, d, part_start);
            ur_vec2 to = ur_vec2_add_scaled(p0, d, part_end);
            double nearest = INFINITY;
            for (size_t c = 0; c < with->corner_count; c++)
                nearest =
                    fmin(nearest,
                         sqrt(allow_distance2_to_segment(b->corners[with->corners[c]], from, to)));
            away = nearest > b->gap + TOUCH;
            open = false;
        }
    }
    return any ? away : 3;
}

/*
 * Whether some part of what thing has in the outer region lies farther
 * than the gap from every corner it shares with the joint: 1 or 0, 2 when
 * GEOS fails.  Each part (one, for a tab and an edge or another tab, all
 * convex) must come that near a corner, as a neighbour touching the joint
 * at their corner does.
 */
static char away_from_corners(const allow_board *b, const regions *r, const GEOSGeometry *thing,
                              const contact *with)
{
    GEOSGeometry *common = GEOSIntersection_r(b->geos, r->clipped, thing);
    if (!common)
        return 2;
    char away = 0;
    for (int i = 0, n = GEOSGetNumGeometries_r(b->geos, common); away == 0 && i < n; i++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(b->geos, common, i);
        double nearest = INFINITY;
        for (size_t c = 0; away == 0 && c < with->corner_count; c++) {
            ur_vec2 at = b->corners[with->corners[c]];
            GEOSGeometry *point = GEOSGeom_createPointFromXY_r(b->geos, at.x, at.y);
            double distance;
            if (!point || GEOSDistance_r(b->geos, point, part, &distance) != 1)
                away = 2;
            else
                nearest = fmin(nearest, distance);
            if (point)
                GEOSGeom_destroy_r(b->geos, point);
        }
        if (away == 0 && nearest > b->gap + TOUCH)
            away = 1;
    }
    GEOSGeom_destroy_r(b->geos, common);
    return away;
}

/*
 * Whether thing meets the joint: its inner region, and unless it shares an
 * edge with the joint, its outer, away from the corners it shares.
 */
static ur_status meets(const allow_board *b, const contact *with, const regions *r,
                       const GEOSGeometry *thing, size_t edge, bool *hit, ur_error *error)
{
    char result = GEOSPreparedIntersects_r(b->geos, r->inner, thing);
    if (result == 0 && !with->overlap) {
        result = GEOSPreparedIntersects_r(b->geos, r->outer, thing);
        if (result == 1 && with->corner_count > 0) {
            result = edge != NOT_AN_EDGE ? edge_away_from_corners(b, r, edge, with) : 3;
            if (result == 3) /* a neighbouring joint, or a touch the edge's cuts missed */
                result = away_from_corners(b, r, thing, with);
        }
    }
    if (result == 2)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS failed testing a joint");
    *hit = result == 1;
    return UR_OK;
}

static ur_status test_near(allow_board *b, const regions *r, size_t first, size_t edges,
                           allow_verdict *v, ur_error *error)
{
    size_t n = b->edge_count;
    b->found.count = 0;
    GEOSSTRtree_query_r(b->geos, b->tree, r->grown, collect_edge, b);
    if (b->out_of_memory)
        return ur_error_out_of_memory(error);
    bool hit = false;
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && !hit && k < b->found.count; k++) {
        size_t e = b->found.items[k];
        contact with = contact_of(n, e, 1, first, edges);
        status = meets(b, &with, r, b->segments[e], e, &hit, error);
        if (hit)
            *v = (allow_verdict){ALLOW_BLOCKED_OUTLINE, b->segments[e], e};
    }
    if (status != UR_OK || hit)
        return status;
    status = allow_grid_query(&b->grid, allow_box(b->geos, r->grown), &b->found, error);
    for (size_t k = 0; status == UR_OK && !hit && k < b->found.count; k++) {
        const board_joint *q = &b->joints[b->found.items[k]];
        contact with = contact_of(n, q->first, q->edges, first, edges);
        status = meets(b, &with, r, q->shape, NOT_AN_EDGE, &hit, error);
        if (hit)
            *v = (allow_verdict){ALLOW_BLOCKED_JOINT, q->shape, 0};
    }
    return status;
}

ur_status allow_board_test(allow_board *b, const GEOSGeometry *joint, const ur_vec2 *base,
                           size_t count, size_t first, size_t edges, allow_verdict *v,
                           ur_error *error)
{
    *v = (allow_verdict){ALLOW_BLOCKED_SHAPE, NULL, 0};
    if (!joint || GEOSisValid_r(b->geos, joint) != 1)
        return UR_OK;
    regions r;
    ur_status status = UR_OK;
    if (regions_make(b, joint, base, count, &r)) {
        *v = (allow_verdict){ALLOW_BLOCKED_NOT, NULL, 0};
        status = test_near(b, &r, first, edges, v, error);
    } else if (r.out_of_memory) {
        status = ur_error_out_of_memory(error);
    }
    regions_free(b, &r);
    return status;
}
