/*
 * allow_internal.h: what the allowance files share: moving rings of points
 * in and out of GEOS (reentrant API; the caller owns the context).
 */
#ifndef UNROLL_ALLOW_INTERNAL_H
#define UNROLL_ALLOW_INTERNAL_H

#include <geos_c.h>
#include <math.h>

#include "../geom/geos_polygon.h"
#include "unroll/allow.h"

/* An open line string through the points (at least 2), or NULL. */
GEOSGeometry *allow_line(GEOSContextHandle_t geos, const ur_vec2 *points, size_t count);

/*
 * A GEOS linear ring as points, counter-clockwise, first point not
 * repeated; the caller frees *points.  Fails (UR_ERROR_INTERNAL) on a ring
 * of fewer than 3 points.
 */
ur_status allow_ring_points(GEOSContextHandle_t geos, const GEOSGeometry *ring, ur_vec2 **points,
                            size_t *count, ur_error *error);

/*
 * The exterior ring of a polygon as points, counter-clockwise, first point
 * not repeated; the caller frees *ring.  Fails (UR_ERROR_INTERNAL) on
 * anything but a polygon with a ring of 3 points or more.
 */
ur_status allow_exterior_ring(GEOSContextHandle_t geos, const GEOSGeometry *polygon, ur_vec2 **ring,
                              size_t *count, ur_error *error);

/*
 * Where each of the count pieces' names is sought first (name_centres.c):
 * the centre of the largest circle inside its outline, found with geos
 * and, beside it, in a thread with a context of its own.  *centres is
 * allocated (the caller frees it), one point per piece.
 */
ur_status allow_name_centres(GEOSContextHandle_t geos, const ur_piece *pieces, size_t count,
                             ur_vec2 **centres, ur_error *error);

/*
 * A piece whose outline reaches a hole through a slit of no width (slits.c)
 * is cut as its rim and its holes instead: the outline becomes the rim,
 * each hole a closed CUT path.  Any other piece is left as it is.
 */
ur_status allow_open_slits(ur_piece *piece, ur_error *error);

/*
 * The region at least margin (> 0) inside a ring: the ring simplified to
 * within a hundredth of margin (at most 5 micrometres) and buffered inward
 * by margin plus that tolerance, so nothing of it comes nearer than margin
 * to the true ring.  Simplifying first keeps GEOS's inward buffer fast on
 * outlines of hundreds of thousands of points.  NULL when GEOS fails; may
 * be empty.
 */
GEOSGeometry *allow_inside(GEOSContextHandle_t geos, const ur_vec2 *ring, size_t count,
                           double margin, int quadrant_segments);

/* Area of a GEOS geometry (0 when GEOS fails). */
double allow_area(GEOSContextHandle_t geos, const GEOSGeometry *geometry);

/* The box of a GEOS geometry (an empty box when it has none). */
ur_box allow_box(GEOSContextHandle_t geos, const GEOSGeometry *geometry);

/* Whether two boxes meet (touching counts). */
static inline bool allow_boxes_meet(ur_box a, ur_box b)
{
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

/* The squared distance from point to the segment from p to q. */
static inline double allow_distance2_to_segment(ur_vec2 point, ur_vec2 p, ur_vec2 q)
{
    ur_vec2 d = ur_vec2_sub(q, p);
    double length2 = ur_vec2_dot(d, d);
    double t =
        length2 > 0 ? fmin(1.0, fmax(0.0, ur_vec2_dot(ur_vec2_sub(point, p), d) / length2)) : 0.0;
    ur_vec2 off = ur_vec2_sub(point, ur_vec2_add_scaled(p, d, t));
    return ur_vec2_dot(off, off);
}

/* A growing list of item numbers. */
typedef struct allow_items {
    size_t *items;
    size_t count, capacity;
} allow_items;

ur_status allow_items_push(allow_items *items, size_t item, ur_error *error);
void allow_items_free(allow_items *items);

/*
 * A spatial index of boxes that takes new ones between queries (grid.c):
 * square cells over a region, each listing the items whose box meets it.
 * Items are numbered 0, 1, ... in the order they were added.
 */
typedef struct allow_cell allow_cell;
typedef struct allow_grid {
    ur_box region;
    double cell; /* mm */
    size_t columns, rows;
    allow_cell *cells;
    ur_box *boxes;         /* of each item */
    unsigned *seen, stamp; /* per item: the last query that found it */
    size_t count, capacity;
} allow_grid;

/* A grid over region with cells about cell mm wide (wider on a large region). */
ur_status allow_grid_init(allow_grid *grid, ur_box region, double cell, ur_error *error);
void allow_grid_free(allow_grid *grid);
ur_status allow_grid_add(allow_grid *grid, ur_box box, size_t *item, ur_error *error);
/* The items whose box meets box, each once, in found (emptied first). */
ur_status allow_grid_query(allow_grid *grid, ur_box box, allow_items *found, ur_error *error);
/*
 * Whether test(item, data) holds for an item whose box meets box: the
 * items are tested each once, until one passes (no list is made, and a
 * query that meets many items stops at the first that passes).
 */
bool allow_grid_any(allow_grid *grid, ur_box box, bool (*test)(size_t item, void *data),
                    void *data);
/* The cell p falls in (the nearest border cell for a p beyond the region), numbered row by row. */
size_t allow_grid_cell_of(const allow_grid *grid, ur_vec2 p);
ur_vec2 allow_grid_cell_centre(const allow_grid *grid, size_t cell);
/* Whether no item's box meets the cell. */
bool allow_grid_cell_is_empty(const allow_grid *grid, size_t cell);

/*
 * What the joints of one piece must keep clear of (clearance.c): its net's
 * outline edges in an STRtree, the joints placed so far in a grid.  A
 * joint over outline edges [first, first + edges) may touch what shares a
 * corner with those edges but not overlap it, and keeps `gap` mm from
 * everything else on its outward side (beyond the chord of its base, the
 * fold it is built on).  reach: how far beyond the outline joints go.
 */
typedef struct allow_board allow_board;

typedef enum allow_blocker {
    ALLOW_BLOCKED_NOT,     /* it fits */
    ALLOW_BLOCKED_SHAPE,   /* no joint, or no simple polygon */
    ALLOW_BLOCKED_OUTLINE, /* an edge of the piece's outline */
    ALLOW_BLOCKED_JOINT,   /* a joint placed before */
    ALLOW_BLOCKED_UNDER    /* a lap cut to the piece it lies on leaves too little to glue */
} allow_blocker;

typedef struct allow_verdict {
    allow_blocker by;
    const GEOSGeometry *what; /* the edge or joint in the way */
    size_t edge;              /* the outline edge in the way */
} allow_verdict;

ur_status allow_board_open(GEOSContextHandle_t geos, const ur_vec2 *outline, size_t count,
                           double reach, double gap, allow_board **board, ur_error *error);
void allow_board_close(allow_board *board);

/* Whether joint, built on base (count points), fits over outline edges [first, first + edges). */
ur_status allow_board_test(allow_board *board, const GEOSGeometry *joint, const ur_vec2 *base,
                           size_t count, size_t first, size_t edges, allow_verdict *verdict,
                           ur_error *error);

/* Puts the joint on the board (the caller keeps the shape alive), with a tag of the caller's. */
ur_status allow_board_add(allow_board *board, const GEOSGeometry *shape, size_t first, size_t edges,
                          size_t tag, ur_error *error);
/*
 * Puts shape in place of the joint tagged tag, which it must lie within
 * (a smaller tab on the same base): what the larger one kept clear of, it
 * keeps clear of too.  The board keeps the larger one's box.
 */
void allow_board_replace(allow_board *board, size_t tag, const GEOSGeometry *shape);
size_t allow_board_joint_count(const allow_board *board);
size_t allow_board_joint_tag(const allow_board *board, size_t k);

/*
 * Room for labels on one piece, kept between labels (label.c): the
 * segments of every path the piece has when it is opened, and the labels
 * engraved through it since, each in a grid.  The piece gets no other
 * paths while it is open.  The closed marks among its paths from index
 * zones_from on (SIZE_MAX: none) are zones where another piece will lie
 * once glued: labels keep out of them, as out of holes.
 */
typedef struct allow_room allow_room;

ur_status allow_room_open(ur_piece *piece, size_t zones_from, allow_room **room, ur_error *error);
void allow_room_close(allow_room *room);

/*
 * ur_piece_add_label on the room's piece, looking no farther than reach mm
 * from near (INFINITY: the whole piece); the room then keeps the label
 * clear of the later ones.
 */
ur_status allow_room_add_label(allow_room *room, const ur_font *font, const char *text,
                               ur_vec2 near, ur_vec2 direction, double height, double min_height,
                               double clearance, double reach, bool *placed, ur_error *error);

/*
 * Whether labels from now on may cross the fold lines (scores, mountain or
 * valley) the piece had when the room was opened, still clear of every
 * other line (not as opened).
 */
void allow_room_cross_folds(allow_room *room, bool cross);

/* Where labels from now on may go: out of the zones (as opened), into them, across their edges. */
typedef enum allow_zone_rule {
    ALLOW_ZONES_KEPT_OUT,
    ALLOW_ZONES_ENTERED,
    ALLOW_ZONES_CROSSED
} allow_zone_rule;
void allow_room_zone_rule(allow_room *room, allow_zone_rule rule);
bool allow_room_has_zones(const allow_room *room);

#endif
