/*
 * room.c: where a part may go (see nest.c): the inner-fit rectangle of a
 * sheet, less the no-fit polygons of the parts already there, kept per
 * sheet and shape in a grid of cells so that placing a part cuts only the
 * cells its no-fit polygon reaches; and placing a part at the leftmost,
 * then lowest, place of the best turn and sheet.
 */
#include "nest_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/*
 * The rectangle where the shape's origin may go on the empty sheet (x0, y0,
 * x1, y1); false when it does not fit.
 */
bool nest_inner_fit_box(const nester *n, size_t sheet, const nest_shape *shape, double *box)
{
    const ur_nest_options *o = n->options;
    double width, height;
    nest_sheet_size(n, sheet, &width, &height);
    double x0 = o->margin - shape->box.min.x, x1 = width - o->margin - shape->box.max.x;
    double y0 = o->margin - shape->box.min.y, y1 = height - o->margin - shape->box.max.y;
    if (x1 < x0 - 1e-9 || y1 < y0 - 1e-9)
        return false;
    /* Widened by the exact-fit allowance, so a part as large as the room still has a place. */
    box[0] = x0 - NEST_EXACT_FIT, box[1] = y0 - NEST_EXACT_FIT;
    box[2] = x1 + NEST_EXACT_FIT, box[3] = y1 + NEST_EXACT_FIT;
    return true;
}

/* A rectangle as a GEOS polygon; NULL on failure. */
GEOSGeometry *nest_rectangle_polygon(GEOSContextHandle_t geos, double x0, double y0, double x1,
                                     double y1)
{
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, 5, 2);
    if (!sequence)
        return NULL;
    double xs[5] = {x0, x1, x1, x0, x0}, ys[5] = {y0, y0, y1, y1, y0};
    for (unsigned i = 0; i < 5; i++)
        GEOSCoordSeq_setXY_r(geos, sequence, i, xs[i], ys[i]);
    GEOSGeometry *ring = GEOSGeom_createLinearRing_r(geos, sequence);
    return ring ? GEOSGeom_createPolygon_r(geos, ring, NULL, 0) : NULL;
}

static int shift_xy(double *x, double *y, void *userdata)
{
    const ur_vec2 *by = userdata;
    *x += by->x;
    *y += by->y;
    return 1;
}

/* The slot of (piece's class, turn) in a sheet's rooms. */
static size_t shape_slot(const nester *n, size_t piece, size_t turn)
{
    return n->class_of[piece] * n->turn_count + turn;
}

/* Makes a sheet's rooms, all not yet made; false when memory runs out. */
static bool rooms_make(nester *n, sheet_state *state)
{
    size_t slots = n->class_count * n->turn_count;
    state->rooms = calloc(slots, sizeof *state->rooms);
    state->full = calloc(slots, sizeof *state->full);
    if (state->rooms && state->full)
        return true;
    free(state->rooms);
    free(state->full);
    state->rooms = NULL;
    state->full = NULL;
    n->out_of_memory = true;
    return false;
}

void nest_grid_free(GEOSContextHandle_t geos, room_grid *grid)
{
    for (size_t c = 0; grid->free && c < grid->cols * grid->rows; c++)
        if (grid->free[c])
            GEOSGeom_destroy_r(geos, grid->free[c]);
    free(grid->free);
    free(grid->applied);
    free(grid->cut_by);
    memset(grid, 0, sizeof *grid);
}

/* The bounds of cell c of a grid (x0, y0, x1, y1). */
void nest_cell_box(const nester *n, const room_grid *grid, size_t c, double *box)
{
    size_t i = c / grid->rows, j = c % grid->rows;
    box[0] = grid->x0 + (double)i * n->cell_size;
    box[1] = grid->y0 + (double)j * n->cell_size;
    box[2] = i + 1 == grid->cols ? grid->x1 : grid->x0 + (double)(i + 1) * n->cell_size;
    box[3] = j + 1 == grid->rows ? grid->y1 : grid->y0 + (double)(j + 1) * n->cell_size;
}

/*
 * The grid of where piece (at turn) may go on the sheet, before any part
 * is cut out: the inner-fit rectangle in cells.  False when it does not
 * fit the sheet at all, or on a failure (then it has no place there).
 */
static bool grid_make(nester *n, size_t sheet, size_t piece, size_t turn, room_grid *grid)
{
    double fit[4];
    if (!nest_inner_fit_box(n, sheet, nest_shape_of(n, piece, turn), fit))
        return false;
    grid->x0 = fit[0], grid->y0 = fit[1], grid->x1 = fit[2], grid->y1 = fit[3];
    grid->cols = (size_t)fmax(1.0, ceil((fit[2] - fit[0]) / n->cell_size - 1e-9));
    grid->rows = (size_t)fmax(1.0, ceil((fit[3] - fit[1]) / n->cell_size - 1e-9));
    size_t cells = grid->cols * grid->rows;
    grid->free = calloc(cells, sizeof *grid->free);
    grid->applied = calloc(cells, sizeof *grid->applied);
    grid->cut_by = calloc(cells, sizeof *grid->cut_by);
    if (!grid->free || !grid->applied || !grid->cut_by) {
        nest_grid_free(n->geos, grid);
        n->out_of_memory = true;
        return false;
    }
    for (size_t c = 0; c < cells; c++) {
        double box[4];
        nest_cell_box(n, grid, c, box);
        grid->free[c] = nest_rectangle_polygon(n->geos, box[0], box[1], box[2], box[3]);
        if (!grid->free[c]) {
            nest_grid_free(n->geos, grid);
            return false;
        }
    }
    return true;
}

/*
 * Whether the no-fit polygon of piece (at turn) around placement p can
 * reach into a cell (x0, y0, x1, y1).  A no-fit polygon lies in the sum of
 * its two shapes' boxes, a + (-b); the box test spares making the no-fit
 * polygons of parts far apart, most of them on a sheet of many small
 * parts.  The slack covers the turned no-fit polygons of nest_nfp_of,
 * which equal the sums of the turned shapes only to rounding.
 */
static bool nfp_may_reach(const nester *n, const placed *p, size_t piece, size_t turn,
                          const double *cell)
{
    const ur_box *a = &nest_shape_of(n, p->piece, p->turn)->reach;
    const ur_box *b = &nest_shape_of(n, piece, turn)->reach;
    double slack = 1e-3 + nest_reach_slack(nest_shape_of(n, p->piece, p->turn)) +
                   nest_reach_slack(nest_shape_of(n, piece, turn));
    double x0 = p->at.x + a->min.x - b->max.x - slack, x1 = p->at.x + a->max.x - b->min.x + slack;
    double y0 = p->at.y + a->min.y - b->max.y - slack, y1 = p->at.y + a->max.y - b->min.y + slack;
    return x0 < cell[2] && x1 > cell[0] && y0 < cell[3] && y1 > cell[1];
}

/* Whether a box (x0, y0, x1, y1) reaches into a cell (x0, y0, x1, y1). */
static bool box_reaches(const double *b, const double *cell)
{
    return b[0] < cell[2] && b[2] > cell[0] && b[1] < cell[3] && b[3] > cell[1];
}

/*
 * A cell's room as it is cut: the room, its box, and the room prepared
 * for quick tests, made when first asked for and dropped when the room
 * changes.
 */
typedef struct room_cut {
    GEOSContextHandle_t geos;
    GEOSGeometry **room;
    double box[4];
    bool boxed; /* box holds the room's */
    const GEOSPreparedGeometry *prepared;
} room_cut;

static void room_cut_forget(room_cut *r)
{
    if (r->prepared)
        GEOSPreparedGeom_destroy_r(r->geos, r->prepared);
    r->prepared = NULL;
    r->boxed = false;
}

/* Whether a box (x0, y0, x1, y1) may meet the room: false only when it lies clear of the room's. */
static bool box_meets_room(room_cut *r, const double *box)
{
    if (!r->boxed)
        r->boxed = nest_box_of(r->geos, *r->room, r->box);
    const double *a = r->box;
    return !r->boxed || !(box[0] > a[2] || box[2] < a[0] || box[1] > a[3] || box[3] < a[1]);
}

/*
 * Whether a polygon may take something from the room: it meets the room
 * (its box has been found to meet the room's).  Most of a pair's convex
 * sums lie where others already took the room (a 2,208 triangle sphere's
 * 13 nets: three cuts in four left the room as it was), and a prepared
 * test costs a fraction of a difference.
 */
static bool takes_from(room_cut *r, const GEOSGeometry *shifted)
{
    if (!r->prepared)
        r->prepared = GEOSPrepare_r(r->geos, *r->room);
    return !r->prepared || GEOSPreparedIntersects_r(r->geos, r->prepared, shifted) != 0;
}

/* Cuts a polygon (taken over) out of the cell's room; false on a GEOS failure. */
static bool cut_out(room_cut *r, GEOSGeometry *shifted)
{
    GEOSContextHandle_t geos = r->geos;
    if (shifted && !takes_from(r, shifted)) {
        GEOSGeom_destroy_r(geos, shifted);
        return true;
    }
    GEOSGeometry *left = shifted ? GEOSDifference_r(geos, *r->room, shifted) : NULL;
    if (shifted)
        GEOSGeom_destroy_r(geos, shifted);
    if (!left)
        return false;
    room_cut_forget(r);
    GEOSGeom_destroy_r(geos, *r->room);
    *r->room = left;
    if (GEOSisEmpty_r(geos, left) == 1) {
        GEOSGeom_destroy_r(geos, left);
        *r->room = NULL; /* full: nothing placed later can free it */
    }
    return true;
}

/*
 * A pair's no-fit polygon is cut out of cells as its convex sums, each
 * that reaches the cell on its own, the first time the pair is met (one
 * placement in one run); after that as their union, made once and kept.
 * Nesting many different small parts once meets most pairs once, and
 * making their unions took nearly all its time (122 parts of an unfolded
 * mesh: 29 s; by sums 12 s); copies of a part and a search over orders
 * meet the same pairs again and again, and there the union, one cut per
 * cell instead of many, pays for itself (bench_nest: 3.8 s by unions
 * only, 8.9 s by sums only, 6.5 s so).
 */

/*
 * Whether placement k's no-fit polygon with piece at turn is cut out of
 * cells as a union: once the pair has been met before, at another
 * placement (a copy of a part) or in another run.
 */
static bool by_union(nester *n, size_t a, size_t ta, size_t b, size_t tb, size_t k)
{
    pair_entry *pair = pair_table_add(&n->pairs, nest_pair_key(n, a, ta, b, tb));
    if (!pair) {
        n->out_of_memory = true;
        return true; /* the union cannot be had either: the cell's update fails */
    }
    size_t meeting = n->runs * (n->count + 1) + k + 1;
    if (pair->nfp || (pair->met && pair->met != meeting))
        return true;
    pair->met = meeting;
    return false;
}

static void note_cut_by(size_t *cut_by, size_t k)
{
    if (*cut_by < k + 1)
        *cut_by = k + 1;
}

/*
 * A polygon to cut out of a cell: placement k's no-fit polygon, or sum
 * `sum` of its convex sums; its area, its place in the order gathered and
 * its box where the placement puts it.
 */
typedef struct cut_candidate {
    nest_sized size;
    const GEOSGeometry *nfp;
    const nest_sum_list *sums;
    size_t sum, k;
    double box[4];
} cut_candidate;

typedef struct candidates {
    cut_candidate *items;
    size_t count, room;
} candidates;

static bool add_candidate(nester *n, candidates *c, const cut_candidate *candidate)
{
    if (c->count == c->room) {
        size_t room = c->room ? 2 * c->room : 64;
        cut_candidate *grown = realloc(c->items, room * sizeof *grown);
        if (!grown) {
            n->out_of_memory = true;
            return false;
        }
        c->items = grown;
        c->room = room;
    }
    c->items[c->count] = *candidate;
    c->items[c->count].size.index = c->count;
    c->count++;
    return true;
}

/* Placement k's no-fit polygon, to be cut if it reaches the cell; false on a failure. */
static bool gather_nfp(nester *n, size_t piece, size_t turn, const double *cell, size_t k,
                       candidates *c)
{
    const placed *p = &n->placements[k];
    const GEOSGeometry *nfp = nest_nfp_of(n, p->piece, p->turn, piece, turn);
    cut_candidate candidate = {
        .nfp = nfp, .k = k, .box = {-INFINITY, -INFINITY, INFINITY, INFINITY}};
    if (!nfp)
        return false;
    if (nest_box_of(n->geos, nfp, candidate.box)) { /* no box: cut it out and let GEOS say */
        candidate.box[0] += p->at.x, candidate.box[2] += p->at.x;
        candidate.box[1] += p->at.y, candidate.box[3] += p->at.y;
    }
    return !box_reaches(candidate.box, cell) ||
           (GEOSArea_r(n->geos, nfp, &candidate.size.area) && add_candidate(n, c, &candidate));
}

/*
 * Placement k's polygons that reach the cell, to be cut (the sums held
 * meanwhile); false on a failure.
 */
static bool gather(nester *n, size_t piece, size_t turn, const double *cell, size_t k,
                   candidates *c)
{
    const placed *p = &n->placements[k];
    if (by_union(n, p->piece, p->turn, piece, turn, k))
        return gather_nfp(n, piece, turn, cell, k, c);
    const nest_sum_list *sums = nest_sums_of(n, p->piece, p->turn, piece, turn);
    if (!sums)
        return false;
    for (size_t q = 0; q < sums->count; q++) {
        const ur_box *b = &sums->box[q];
        cut_candidate candidate = {.size = {sums->area[q], 0},
                                   .sums = sums,
                                   .sum = q,
                                   .k = k,
                                   .box = {b->min.x + p->at.x, b->min.y + p->at.y,
                                           b->max.x + p->at.x, b->max.y + p->at.y}};
        if (box_reaches(candidate.box, cell) && !add_candidate(n, c, &candidate))
            return false;
    }
    return true;
}

/*
 * Cuts a candidate out of the cell's room, where its box meets the room's;
 * false on a GEOS failure.
 */
static bool cut_candidate_out(nester *n, room_cut *r, const cut_candidate *cut)
{
    if (!box_meets_room(r, cut->box))
        return true;
    ur_vec2 at = n->placements[cut->k].at;
    GEOSGeometry *shifted = cut->nfp ? GEOSGeom_transformXY_r(n->geos, cut->nfp, shift_xy, &at)
                                     : nest_sum_polygon(n->geos, cut->sums, cut->sum, at);
    return shifted && cut_out(r, shifted);
}

/*
 * Where the reach box of a placement whose no-fit polygon with piece (at
 * turn) may reach a cell lies: the cell less the piece's reach, widened by
 * the piece's share of nfp_may_reach's slack and a little more for
 * rounding (the index adds the placement's share).
 */
static void reach_box(const nester *n, size_t piece, size_t turn, const double *cell, double *box)
{
    const nest_shape *b = nest_shape_of(n, piece, turn);
    double slack = 2e-3 + nest_reach_slack(b);
    box[0] = cell[0] + b->reach.min.x - slack, box[1] = cell[1] + b->reach.min.y - slack;
    box[2] = cell[2] + b->reach.max.x + slack, box[3] = cell[3] + b->reach.max.y + slack;
}

/*
 * Cuts out of cell c the no-fit polygons (with piece at turn) of the parts
 * placed on the sheet since it was last brought up to date, those whose
 * box reaches into it: their convex sums (or, for a pair met before, their
 * union) largest first, whatever part they come from.  On a sheet filled
 * from the left most cells a new part looks at are full, and the large
 * ones fill a cell in fewer cuts.  False on a GEOS failure.
 */
static bool cell_update(nester *n, size_t sheet, size_t piece, size_t turn, room_grid *grid,
                        size_t c)
{
    double box[4];
    nest_cell_box(n, grid, c, box);
    candidates all = {NULL, 0, 0};
    double reach[4];
    reach_box(n, piece, turn, box, reach);
    size_t near = 0;
    bool ok = nest_index_near(n, sheet, reach, grid->applied[c], &near);
    nest_hold_sums(n, true);
    for (size_t q = 0; ok && q < near; q++) {
        size_t k = n->near[q];
        if (!nfp_may_reach(n, &n->placements[k], piece, turn, box))
            continue; /* too far away to matter: its no-fit polygon is never made */
        ok = gather(n, piece, turn, box, k, &all);
    }
    if (ok && all.count > 1)
        qsort(all.items, all.count, sizeof *all.items, nest_larger_first);
    room_cut r = {.geos = n->geos, .room = &grid->free[c]};
    for (size_t q = 0; ok && grid->free[c] && q < all.count; q++) {
        ok = cut_candidate_out(n, &r, &all.items[q]);
        note_cut_by(&grid->cut_by[c], all.items[q].k);
    }
    room_cut_forget(&r);
    free(all.items);
    nest_hold_sums(n, false);
    if (ok)
        grid->applied[c] = n->placed_count;
    return ok;
}

/*
 * Starts cell c's room from the narrowed box the raster gave, when that is
 * much smaller than the cell: no place lies outside it, and fewer no-fit
 * polygons reach it.  The placements so far showed it, so a rewind past
 * them makes the cell whole again (cut_by).  False on a GEOS failure.
 */
static bool narrow_cell(nester *n, room_grid *grid, size_t c, const double *cell,
                        const double *narrowed)
{
    double whole = (cell[2] - cell[0]) * (cell[3] - cell[1]);
    double part = (narrowed[2] - narrowed[0]) * (narrowed[3] - narrowed[1]);
    if (!(part < 0.8 * whole))
        return true;
    GEOSGeometry *room =
        nest_rectangle_polygon(n->geos, narrowed[0], narrowed[1], narrowed[2], narrowed[3]);
    if (!room)
        return false;
    GEOSGeom_destroy_r(n->geos, grid->free[c]);
    grid->free[c] = room;
    if (n->placed_count > 0)
        note_cut_by(&grid->cut_by[c], n->placed_count - 1);
    return true;
}

/* The leftmost, then lowest, vertex of a region's rings; false when it has none. */
static bool leftmost(GEOSContextHandle_t geos, const GEOSGeometry *region, ur_vec2 *best)
{
    bool found = false;
    int parts = GEOSGetNumGeometries_r(geos, region);
    for (int k = 0; k < parts; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(geos, region, k);
        if (GEOSGeomTypeId_r(geos, part) != GEOS_POLYGON || GEOSisEmpty_r(geos, part))
            continue;
        int holes = GEOSGetNumInteriorRings_r(geos, part);
        for (int r = -1; r < holes; r++) {
            const GEOSGeometry *ring =
                r < 0 ? GEOSGetExteriorRing_r(geos, part) : GEOSGetInteriorRingN_r(geos, part, r);
            const GEOSCoordSequence *sequence = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
            unsigned size = 0;
            if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size))
                continue;
            for (unsigned i = 0; i < size; i++) {
                ur_vec2 p;
                GEOSCoordSeq_getXY_r(geos, sequence, i, &p.x, &p.y);
                if (!found || p.x < best->x - 1e-9 || (p.x <= best->x + 1e-9 && p.y < best->y)) {
                    *best = p;
                    found = true;
                }
            }
        }
    }
    return found;
}

/* Whether p is left of best, or as far left and lower. */
static bool further_left(ur_vec2 p, ur_vec2 best)
{
    return p.x < best.x - 1e-9 || (p.x <= best.x + 1e-9 && p.y < best.y);
}

/*
 * Whether piece's rooms will be asked again once it is placed: by another
 * part of its class, or by a search after the first layout.  When not,
 * they are dropped then (drop_finished_rooms), and a cell need not be cut
 * for a place that cannot win.
 */
static bool rooms_asked_again(const nester *n, size_t piece)
{
    return !n->first_run || n->class_left[n->class_of[piece]] > 1 ||
           nest_search_follows(n, nest_seconds_now());
}

/*
 * Whether no place in a cell whose places lie at x = left or further
 * right can beat *at, found lower in the same column: such a place would
 * have to lie further left, since it lies higher.  A small net beside a
 * large one on the bench's 48 x 24 sphere found its place at the foot of
 * the first column, and cutting the cells above it took two thirds of the
 * time of each of its turns.
 */
static bool cannot_beat(double left, ur_vec2 at)
{
    return left >= at.x - 1e-9;
}

/*
 * The best place for piece at turn on sheet: the leftmost, then lowest,
 * feasible one.  Columns of cells are looked at from the left; the first
 * with room holds it (the columns after it lie further right).  A column
 * where the part's box would start right of beyond (another turn's place
 * already lies further left) is not looked at: false then, without
 * marking the room full.  Cells are looked at from the foot of their
 * column; once a place is found, a cell higher up that cannot beat it is
 * left as it is when the room will not be asked again.
 */
static bool place_on(nester *n, size_t sheet, size_t piece, size_t turn, double beyond, ur_vec2 *at)
{
    double fit[4];
    if (sheet >= n->sheet_count) { /* empty: the inner-fit rectangle's lower left corner */
        if (!nest_inner_fit_box(n, sheet, nest_shape_of(n, piece, turn), fit))
            return false;
        *at = ur_vec2_make(fit[0], fit[1]);
        return true;
    }
    sheet_state *state = &n->sheets[sheet];
    if (!state->rooms && !rooms_make(n, state))
        return false;
    size_t slot = shape_slot(n, piece, turn);
    room_grid *grid = &state->rooms[slot];
    if (state->full[slot])
        return false;
    bool fresh = !grid->cols;
    if (fresh && !grid_make(n, sheet, piece, turn, grid))
        return false; /* it does not fit the sheet, or no memory: no place */
    double whole[4] = {grid->x0, grid->y0, grid->x1, grid->y1};
    if (fresh && nest_raster_room(n, sheet, piece, turn, whole, NULL) == RASTER_NONE) {
        state->full[slot] = true;
        return false;
    }
    double left = nest_shape_of(n, piece, turn)->box.min.x;
    bool last_ask = !rooms_asked_again(n, piece);
    for (size_t i = 0; i < grid->cols; i++) {
        if (grid->x0 + (double)i * n->cell_size + left > beyond)
            return false;
        bool found = false;
        for (size_t c = i * grid->rows; c < (i + 1) * grid->rows; c++) {
            if (!grid->free[c])
                continue;
            double cell[4];
            nest_cell_box(n, grid, c, cell);
            if (found && last_ask && cannot_beat(cell[0], *at))
                continue;
            /*
             * A cell not cut yet would be cut by every placement near it:
             * the raster may show it full, or its places in a corner of it,
             * first.  One cut already is brought up to date by the few
             * placed since, which costs less than a raster made again
             * (copies of a part).
             */
            if (grid->applied[c] == 0) {
                double narrowed[4];
                raster_verdict seen = nest_raster_room(n, sheet, piece, turn, cell, narrowed);
                if (seen == RASTER_NONE)
                    continue; /* left as it is: no place there, whatever its cuts */
                if (seen == RASTER_NARROWED && found && last_ask && cannot_beat(narrowed[0], *at))
                    continue;
                if (seen == RASTER_NARROWED && !narrow_cell(n, grid, c, cell, narrowed)) {
                    nest_grid_free(n->geos, grid);
                    return false;
                }
            }
            if (!cell_update(n, sheet, piece, turn, grid, c)) {
                nest_grid_free(n->geos, grid); /* GEOS failed: better no place than an overlap */
                return false;
            }
            ur_vec2 p = {0, 0};
            if (grid->free[c] && leftmost(n->geos, grid->free[c], &p) &&
                (!found || further_left(p, *at))) {
                *at = p;
                found = true;
            }
        }
        if (found)
            return true;
    }
    state->full[slot] = true;
    return false;
}

/* How far the parts placed so far reach along the roll (the stock sheet). */
double nest_roll_length(const nester *n)
{
    double length = 0;
    for (size_t k = 0; k < n->placed_count; k++) {
        if (n->sheet_of[k] < n->remnant_count)
            continue;
        const placed *p = &n->placements[k];
        length = fmax(length, p->at.x + nest_shape_of(n, p->piece, p->turn)->box.max.x);
    }
    return length;
}

/*
 * Refuses a piece that fits no empty sheet, giving its size turned level
 * (a square drawn at 45 degrees is its side across, not its diagonal), or
 * its box as drawn when that cannot be had.
 */
static ur_status refuse_piece(nester *n, size_t piece)
{
    const ur_piece *p = &n->pieces[piece];
    double length = ur_box_width(p->box), width = ur_box_height(p->box);
    ur_error ignored;
    if (p->path_count > 0 && ur_outline_level_size(p->paths[0].points, p->paths[0].count, &length,
                                                   &width, &ignored) != UR_OK) {
        length = ur_box_width(p->box);
        width = ur_box_height(p->box);
    }
    ur_error_set(n->error, UR_ERROR_INPUT,
                 "piece %s (%.1f x %.1f mm) does not fit in any allowed turn: give a larger "
                 "sheet than %.1f x %.1f mm (%.1f mm margin)",
                 p->name, length, width, n->options->sheet_width, n->options->sheet_height,
                 n->options->margin);
    return ur_error_set_setting(n->error, "sheet");
}

/*
 * Frees the rooms of piece's class on every sheet once the first layout,
 * with no search after it, has placed all its parts: a mesh unfolded into
 * 1,616 different nets kept a room per net, turn and sheet, 1.77 GB, of
 * which nothing would ask again.  No search follows when the budget is 0,
 * nor once the first layout has taken longer than the budget (nest.c).
 */
static void drop_finished_rooms(nester *n, size_t piece)
{
    if (!n->first_run)
        return;
    size_t c = n->class_of[piece];
    bool again = rooms_asked_again(n, piece); /* another of its class, or a search, takes them up */
    n->class_left[c]--;
    if (again)
        return;
    for (size_t s = 0; s < n->sheet_slots; s++)
        for (size_t t = 0; n->sheets[s].rooms && t < n->turn_count; t++)
            nest_grid_free(n->geos, &n->sheets[s].rooms[c * n->turn_count + t]);
}

/*
 * Places one piece: the first sheet it fits, at its best turn there (or at
 * turn held, unless that is ANY_TURN); a new sheet otherwise.
 */
ur_status nest_place_piece(nester *n, size_t piece, size_t held)
{
    for (size_t sheet = 0; sheet <= n->sheet_count; sheet++) {
        if (sheet == n->sheet_count && n->options->max_sheets &&
            n->sheet_count - n->remnant_count >= n->options->max_sheets)
            return UR_OK; /* not placed: the caller lists it */
        bool found = false;
        ur_vec2 best = {0, 0};
        size_t best_turn = 0;
        double width, height;
        nest_sheet_size(n, sheet, &width, &height);
        double room = (width - 2 * n->options->margin) * (height - 2 * n->options->margin);
        if (sheet < n->sheet_count &&
            n->sheet_area[sheet] + nest_shape_of(n, piece, 0)->area > room)
            continue; /* not enough area left on it, whatever the shapes */
        ur_vec2 best_key = {0, 0};
        double best_reach = 0, length = nest_roll_length(n);
        size_t turns = n->classes[n->class_of[piece]].turn_count;
        /* A held turn is tried alone: a cheaper try, and one the greedy choice would not make. */
        size_t first = held < turns ? held : 0, last = held < turns ? held + 1 : turns;
        for (size_t t = first; t < last; t++) {
            ur_vec2 at = {0, 0};
            /*
             * On sheets a turn can win only left of the best so far (ties
             * go to the earlier turn), so its columns beyond are spared.
             */
            double beyond = found && n->options->roll_width <= 0 ? best_key.x + 1e-3 : INFINITY;
            if (!place_on(n, sheet, piece, t, beyond, &at)) {
                if (n->out_of_memory)
                    return ur_error_out_of_memory(n->error);
                continue;
            }
            /*
             * Turns compare by where the part itself lies (its box's lower
             * left corner), not by its origin, which sits elsewhere in each.
             */
            const nest_shape *shape = nest_shape_of(n, piece, t);
            ur_vec2 key = {at.x + shape->box.min.x, at.y + shape->box.min.y};
            /*
             * On a roll, first the turn that lengthens the strip least (as
             * far as the strip or the part reaches): a long part laid
             * across it rather than along.
             */
            double reach = n->options->roll_width > 0 ? fmax(length, at.x + shape->box.max.x) : 0;
            /* Ties (to a micrometre: rounding) go to the earlier turn. */
            if (!found || reach < best_reach - 1e-3 ||
                (reach <= best_reach + 1e-3 &&
                 (key.x < best_key.x - 1e-3 ||
                  (key.x <= best_key.x + 1e-3 && key.y < best_key.y - 1e-3)))) {
                found = true;
                best = at;
                best_key = key;
                best_reach = reach;
                best_turn = t;
            }
        }
        if (found) {
            n->placements[n->placed_count] = (placed){piece, best_turn, best};
            n->sheet_of[n->placed_count++] = sheet;
            if (sheet == n->sheet_count)
                n->sheet_count++;
            n->sheet_area[sheet] += nest_shape_of(n, piece, 0)->area;
            if (!nest_index_add(n, n->placed_count - 1))
                return ur_error_out_of_memory(n->error);
            n->sheets[sheet].version++;
            drop_finished_rooms(n, piece);
            return UR_OK;
        }
        if (sheet == n->sheet_count) /* it fits no empty sheet either */
            return refuse_piece(n, piece);
    }
    return UR_OK;
}
