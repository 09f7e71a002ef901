/*
 * unroll/nest.h: placing pieces on sheets of stock.
 *
 * Sheet coordinates are millimetres with the origin at the sheet's lower left
 * corner, x to the right and y up.  A placement is a rigid motion taking piece
 * coordinates to sheet coordinates.  Pieces go in rows (ur_layout_rows) or
 * at their true shape (ur_layout_nest), on stock sheets, remnants or a roll.
 */
#ifndef UNROLL_NEST_H
#define UNROLL_NEST_H

#include "unroll/allow.h"
#include "unroll/core.h"
#include "unroll/geom.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ur_layout_options {
    double sheet_width, sheet_height;
    double margin;  /* kept free along every sheet edge */
    double spacing; /* kept free between pieces */
} ur_layout_options;

/*
 * Places every piece on as many sheets as needed, row by row.  Each piece is
 * first turned so that its smallest enclosing rectangle lies flat, then a
 * quarter turn more if that is what makes it fit.  Fails with UR_ERROR_INPUT,
 * naming both sizes, when a piece fits no sheet.
 */
UR_API ur_status ur_layout_rows(const ur_piece *pieces, size_t piece_count,
                                const ur_layout_options *options, ur_layout *layout,
                                ur_error *error);

/*
 * True-shape nesting (nest.c): every part at its exact shape (holes too,
 * where other parts may go), largest first, each at the leftmost then
 * lowest place where it fits on the first sheet that has room, at the best
 * of its allowed turns; new sheets as needed.  Turns are rotations steps of
 * 360 / rotations degrees from the part as drawn, or with level from the
 * turn that lays the part's smallest enclosing rectangle level.  Places
 * come from no-fit polygons (GEOS): placed parts never overlap and keep
 * the spacing (to a micrometre), and stay inside the margin.  With
 * max_sheets, parts that find no room on those sheets are left out of the
 * layout and listed in its not_placed.  Refuses (UR_ERROR_INPUT) a part
 * that fits no empty sheet in any allowed turn, naming it, and a margin
 * that leaves no room.
 */
typedef struct ur_nest_options {
    double sheet_width, sheet_height;
    double margin;     /* kept free along every sheet edge */
    double spacing;    /* kept free between parts */
    size_t rotations;  /* allowed turns: 0 or 1 the first only, N equal steps; see ur_piece */
    bool level;        /* turns start from the level one (else from the part as drawn) */
    bool holes;        /* parts may go inside holes of other parts */
    size_t max_sheets; /* stock sheets (remnants not counted); 0: as many as needed */
    /*
     * Remnants: sheets at hand, filled before any stock sheet is opened.
     * A part goes on the first remnant (in this order) where it finds room,
     * else on the stock sheets; remnants left empty are not in the layout,
     * and those used come first in it, marked remnant.  Same margin and
     * spacing as the stock.  NULL and 0: none.
     */
    const ur_remnant *remnants;
    size_t remnant_count;
    /*
     * Roll stock: > 0 nests on one strip this wide (sheet_height is
     * ignored; sheet_width too) and as short as it can (each part takes
     * the turn that lengthens the strip least, then the leftmost); the
     * layout's one sheet is then as long as what was used, margin
     * included.
     */
    double roll_width;
    /*
     * A grain rule: parts with rulings (ur_piece.has_rulings) turn only so
     * that their rulings make grain_angle (radians) with the sheet's x axis,
     * the grain, end for end, or grain_tolerance either side (2 turns, or 6
     * with a tolerance).  Parts without rulings turn as rotations says, or
     * as their own ur_piece.rotations says when it is not 0.
     */
    bool grain;
    double grain_angle, grain_tolerance;
    /*
     * The search after the first, largest-first layout: layouts tried (two
     * parts swapped, or one moved, in the current order; or, one try in
     * three, one part held at another of its allowed turns, or freed to
     * take its best again; any layout at least as good replaces the
     * current one) until time_budget seconds have passed,
     * a run of tries brought no new best (20 per second of budget, at
     * least 40), or 100,000 tries were made.  A better layout places more parts, or uses fewer
     * stock sheets, or less of the last sheet's length, or at equal length has that sheet's parts
     * reach less far on average.  0: no search.  The steps come from seed (xorshift64*), so a
     * search that stops for want of improvement or at its try limit gives the same layout every
     * time. That search has a fifth of the budget.  On a roll, shortening the strip by overlap
     * minimisation (src/nest/compact.c) has the rest: it stops when the time is up or after 200
     * failed cuts in a row.  On sheets, with every part placed, the same search looks for a layout
     * on fewer stock sheets, from the area bound up (each count an equal
     * share of the time up to four fifths of the budget; parts overlap on
     * the way, and a layout is kept only once GEOS finds no overlap left),
     * then pushes the last stock sheet's parts toward its left edge (one
     * search, ending when its cuts are tried or at the budget), which
     * leaves its offcut (ur_sheet.offcut_width) in one piece.
     * Shortening runs as many searches side by side as threads says (0:
     * one per processor; at most UR_NEST_MAX_THREADS), each going on from
     * the shortest layout any of them has found: the same time, more tries.
     */
    double time_budget;
    size_t threads;
    unsigned long long seed;
    /* Called when the search finds a better layout; NULL for none. */
    void (*progress)(void *context, size_t sheets, double length, size_t tries);
    /*
     * Called as the first layout is made, after each part placed (placed
     * of count), before any search: with many parts that takes a while.
     * NULL for none.  Both get progress_context.
     */
    void (*placing)(void *context, size_t placed, size_t count);
    void *progress_context;
    /*
     * The run's: the search (and its worker threads) stops with
     * UR_ERROR_CANCELLED soon after it is cancelled; NULL: never.
     */
    const ur_context *context;
} ur_nest_options;

/* The most searches ur_nest_options.threads runs side by side. */
enum { UR_NEST_MAX_THREADS = 16 };

UR_API ur_status ur_layout_nest(const ur_piece *pieces, size_t count,
                                const ur_nest_options *options, ur_layout *layout, ur_error *error);

/*
 * Common-line cutting (merge_lines.c): going through each sheet's pieces
 * in placement order, every CUT path loses the stretches that lie within
 * tolerance (mm) of what the pieces before it on the sheet cut, so that a
 * line two touching parts share is cut once.  What is left of a path
 * becomes open paths (the first in its place, the others appended to the
 * piece; a path left with nothing has no points); an opened outline marks
 * the piece bridged, keeping its area in outline_area.  *saved is the cut
 * length taken off, mm.  Parts touch only when nested with no spacing.
 */
UR_API ur_status ur_layout_merge_lines(const ur_layout *layout, ur_piece *pieces, size_t count,
                                       double tolerance, double *saved, ur_error *error);

/*
 * The size of an outline turned so that its smallest enclosing rectangle
 * lies level, as nesting first turns a piece: *length the longer side,
 * *width the shorter (mm).
 */
UR_API ur_status ur_outline_level_size(const ur_vec2 *outline, size_t count, double *length,
                                       double *width, ur_error *error);

/* The turn (radians) that lays the outline's smallest enclosing rectangle level. */
UR_API double ur_outline_level_angle(const ur_vec2 *outline, size_t count);

/*
 * Whether the outline fits a length x width rectangle at some turn: level
 * (its smallest enclosing rectangle along the rectangle's sides) or any
 * other, as a long net with wings at both ends fits a sheet diagonally and
 * nesting then turns it so.  *angle: a turn that fits it with its longer
 * extent along x.  UR_ERROR_MEMORY only.
 */
UR_API ur_status ur_outline_fit_turn(const ur_vec2 *outline, size_t count, double length,
                                     double width, bool *fits, double *angle, ur_error *error);

/*
 * A part cut into the fewest parts that fit room_length x room_width
 * (split_part.c): turned level, it is cut across its length by straight
 * lines, each within the slack the even shares leave, where it is
 * narrowest.  Appends to out one net per new part, whose outline_3d are
 * its points at height id (give each part split a different id) so that
 * ur_net_list_find_seams pairs the two sides of every cut, and the piece
 * made from it (ur_piece_from_net) with the holes that fall in it.
 * Refuses (UR_ERROR_INPUT) a part wider than room_width when level, and
 * one with no closed outline.
 */
typedef struct ur_split_parts {
    ur_net_list nets; /* owned */
    ur_piece *pieces; /* owned; pieces[k] made from nets.nets[k] */
} ur_split_parts;

UR_API ur_status ur_part_split(const ur_piece *part, double room_length, double room_width,
                               double id, ur_split_parts *out, ur_error *error);
UR_API void ur_split_parts_free(ur_split_parts *parts);

#ifdef __cplusplus
}
#endif

#endif
