/*
 * nest.c: true-shape nesting (ur_layout_nest).
 *
 * Parts go largest first.  Each tries every allowed turn on every sheet
 * already open, then on a new one: the positions its origin may take are
 * the inner-fit rectangle (the sheet inside its margin, less the part's own
 * extent) minus the no-fit polygons of the parts already on the sheet
 * (nfp.c).  The part goes to the leftmost, then lowest, such position (a
 * vertex of that region), at the turn whose box lies furthest left, then
 * lowest (on a roll, first the turn that lengthens the strip least; the
 * search may hold a part at one turn instead): sheets used first, then how little of the last
 * sheet's length is used.  Remnant sheets come before the stock sheets.  No-fit polygons are worked
 * out once per pair of shapes and turns: copies of a part share them.  The positions left are kept
 * per sheet and shape in a grid of cells (room_grid), so that placing a part cuts only the cells
 * its no-fit polygon reaches.  A search over orders and turns follows; on a
 * roll, compact.c then shortens the strip; on sheets, it looks for a
 * layout on fewer sheets (from the area bound up) and pushes the last
 * sheet's parts to one end, leaving one offcut there.
 *
 * Parts are grown by half the spacing before the no-fit polygons are made,
 * so parts that touch there keep the spacing between them; the no-fit
 * polygons are a millionth of a millimetre smaller (NEST_EXACT_FIT) so
 * that a part that fits exactly (a tile in a row of tiles) still finds the
 * place where it fits.
 */
#include "nest_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static bool same_shape(const ur_piece *a, const ur_piece *b)
{
    if (a->path_count != b->path_count || a->rotations != b->rotations)
        return false;
    for (size_t k = 0; k < a->path_count; k++) {
        const ur_path *p = &a->paths[k], *q = &b->paths[k];
        if (p->count != q->count || p->op != q->op ||
            memcmp(p->points, q->points, p->count * sizeof *p->points) != 0)
            return false;
    }
    return true;
}

/*
 * Turn t of a part whose rulings lie at ruling_angle, under a grain rule:
 * turns 0 and 1 lay the rulings exactly at the rule's angle (the second end
 * for end), turns 2 to 5 at the tolerance either side.
 */
static double grain_turn(const ur_nest_options *o, double ruling_angle, size_t t)
{
    static const double off[6] = {0, 0, -1, 1, -1, 1}, end_for_end[6] = {0, 1, 0, 0, 1, 1};
    return o->grain_angle - ruling_angle + end_for_end[t % 6] * M_PI +
           off[t % 6] * o->grain_tolerance;
}

/*
 * How many turns a piece may take: under a grain rule, a piece with
 * rulings 2 (the rulings along the rule's angle, end for end) or 6 (and
 * the tolerance either side); otherwise its own rotations, or the
 * nesting's, in equal steps.
 */
static size_t turns_of(const ur_nest_options *options, const ur_piece *piece)
{
    if (options->grain && piece->has_rulings)
        return options->grain_tolerance > 0 ? 6 : 2;
    size_t rotations = piece->rotations ? piece->rotations : options->rotations;
    return rotations > 1 ? rotations : 1;
}

/* The most turns any piece may take: the stride of the tables kept per turn. */
static size_t most_turns(const ur_nest_options *options, const ur_piece *pieces, size_t count)
{
    size_t most = 1;
    for (size_t k = 0; k < count; k++)
        if (turns_of(options, &pieces[k]) > most)
            most = turns_of(options, &pieces[k]);
    return most;
}

static ur_status make_class(nester *n, size_t piece)
{
    nest_class *c = &n->classes[n->class_count];
    const ur_piece *p = &n->pieces[piece];
    c->representative = piece;
    c->turn_count = turns_of(n->options, p);
    c->turns = calloc(c->turn_count, sizeof *c->turns);
    if (!c->turns)
        return ur_error_out_of_memory(n->error);
    n->class_count++;
    double base = n->options->level ? nest_level_angle(n->geos, &p->paths[0]) : 0.0;
    bool grain = n->options->grain && p->has_rulings;
    for (size_t t = 0; t < c->turn_count; t++) {
        double angle = base + 2 * M_PI * (double)t / (double)c->turn_count;
        if (grain) /* the rulings at the grain's angle, end for end, then either way off it */
            angle = grain_turn(n->options, p->ruling_angle, t);
        ur_status status =
            nest_shape_make(n->geos, &n->pieces[piece], angle, n->options->spacing / 2,
                            n->options->holes, t > 0 ? &c->turns[0] : NULL, &c->turns[t], n->error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status sort_classes(nester *n)
{
    for (size_t p = 0; p < n->count; p++) {
        size_t c = 0;
        while (c < n->class_count &&
               !same_shape(&n->pieces[n->classes[c].representative], &n->pieces[p]))
            c++;
        if (c == n->class_count) {
            ur_status status = make_class(n, p);
            if (status != UR_OK)
                return status;
        }
        n->class_of[p] = c;
    }
    size_t pairs = n->class_count * n->turn_count * n->class_count * n->turn_count;
    n->nfps = calloc(pairs ? pairs : 1, sizeof *n->nfps);
    n->sums = calloc(pairs ? pairs : 1, sizeof *n->sums);
    n->pair_met = calloc(pairs ? pairs : 1, sizeof *n->pair_met);
    return n->nfps && n->sums && n->pair_met ? UR_OK : ur_error_out_of_memory(n->error);
}

const nest_shape *nest_shape_of(const nester *n, size_t piece, size_t turn)
{
    return &n->classes[n->class_of[piece]].turns[turn];
}

/* Whether two angles (radians) are the same turn, to a nanoradian. */
static bool same_angle(double a, double b)
{
    double d = remainder(a - b, 2 * M_PI);
    return fabs(d) < 1e-9;
}

/* Turns a point about the origin by the angle whose cosine and sine userdata holds. */
static int turn_xy(double *x, double *y, void *userdata)
{
    const double *cs = userdata;
    double tx = cs[0] * *x - cs[1] * *y, ty = cs[1] * *x + cs[0] * *y;
    *x = tx;
    *y = ty;
    return 1;
}

/*
 * The turn of class c whose angle is angle (mod a whole turn); the class's
 * turn count when it has none.
 */
static size_t turn_at(const nester *n, size_t c, double angle)
{
    const nest_class *k = &n->classes[c];
    for (size_t t = 0; t < k->turn_count; t++)
        if (same_angle(k->turns[t].angle, angle))
            return t;
    return k->turn_count;
}

/*
 * Whether the no-fit polygon of piece b (turn tb) around piece a (turn ta)
 * at the origin is that of a pair at a's first turn, turned.  Turning both
 * parts by the same angle turns their no-fit polygon by it, so with a at a
 * turn other than its first, and b having a turn that makes the same angle
 * with a's first turn as tb makes with ta (equal steps always do), it is
 * that pair's no-fit polygon turned: a quarter of the (costly) sums with 4
 * turns.  The shapes of a class's turns are, to rounding, its first
 * turn's shape turned (nest_shape_make simplifies every turn alike), and
 * each contains the part itself grown by half the spacing, so a turned
 * no-fit polygon keeps parts apart just as well.  *first is b's turn in
 * that pair, cs the cosine and sine of the angle.
 */
static bool turned_pair(const nester *n, size_t a, size_t ta, size_t b, size_t tb, size_t *first,
                        double cs[2])
{
    if (ta == 0)
        return false;
    double by = nest_shape_of(n, a, ta)->angle - nest_shape_of(n, a, 0)->angle;
    size_t cb = n->class_of[b];
    *first = turn_at(n, cb, nest_shape_of(n, b, tb)->angle - by);
    cs[0] = cos(by);
    cs[1] = sin(by);
    return *first < n->classes[cb].turn_count;
}

static size_t pair_key(const nester *n, size_t a, size_t ta, size_t b, size_t tb)
{
    size_t ca = n->class_of[a], cb = n->class_of[b], t = n->turn_count;
    return ((ca * t + ta) * n->class_count + cb) * t + tb;
}

/* What a cache of pairs holds, made for a pair at a's first turn (or one not turned). */
typedef GEOSGeometry *(*pair_maker)(nester *n, size_t a, size_t ta, size_t b, size_t tb);

/* The cache's entry for the pair: made, or turned from its first turn's, once. */
static const GEOSGeometry *cached_pair(nester *n, GEOSGeometry **cache, pair_maker make, size_t a,
                                       size_t ta, size_t b, size_t tb)
{
    size_t key = pair_key(n, a, ta, b, tb), first;
    double cs[2];
    if (cache[key])
        return cache[key];
    if (turned_pair(n, a, ta, b, tb, &first, cs)) {
        const GEOSGeometry *base = cached_pair(n, cache, make, a, 0, b, first);
        cache[key] = base ? GEOSGeom_transformXY_r(n->geos, base, turn_xy, cs) : NULL;
    } else {
        cache[key] = make(n, a, ta, b, tb);
    }
    return cache[key];
}

static GEOSGeometry *make_sums(nester *n, size_t a, size_t ta, size_t b, size_t tb)
{
    return nest_sums(n->geos, nest_shape_of(n, a, ta), nest_shape_of(n, b, tb));
}

static GEOSGeometry *make_union(nester *n, size_t a, size_t ta, size_t b, size_t tb)
{
    const GEOSGeometry *sums = nest_sums_of(n, a, ta, b, tb);
    return sums ? nest_union_of_sums(n->geos, sums) : NULL;
}

const GEOSGeometry *nest_sums_of(nester *n, size_t a, size_t ta, size_t b, size_t tb)
{
    return cached_pair(n, n->sums, make_sums, a, ta, b, tb);
}

const GEOSGeometry *nest_nfp_of(nester *n, size_t a, size_t ta, size_t b, size_t tb)
{
    return cached_pair(n, n->nfps, make_union, a, ta, b, tb);
}

void nest_sheet_size(const nester *n, size_t sheet, double *width, double *height)
{
    const ur_nest_options *o = n->options;
    bool remnant = sheet < n->remnant_count;
    *width = remnant ? o->remnants[sheet].width : o->sheet_width;
    *height = remnant ? o->remnants[sheet].height : o->sheet_height;
}

/*
 * The rectangle where the shape's origin may go on the empty sheet (x0, y0,
 * x1, y1); false when it does not fit.
 */
static bool inner_fit_box(const nester *n, size_t sheet, const nest_shape *shape, double *box)
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
static GEOSGeometry *rectangle_polygon(GEOSContextHandle_t geos, double x0, double y0, double x1,
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

/* The cache slot of (sheet, piece's class, turn). */
static size_t taken_slot(const nester *n, size_t sheet, size_t piece, size_t turn)
{
    return (sheet * n->class_count + n->class_of[piece]) * n->turn_count + turn;
}

static void grid_free(GEOSContextHandle_t geos, room_grid *grid)
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
static void cell_box(const nester *n, const room_grid *grid, size_t c, double *box)
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
    if (!inner_fit_box(n, sheet, nest_shape_of(n, piece, turn), fit))
        return false;
    grid->x0 = fit[0], grid->y0 = fit[1], grid->x1 = fit[2], grid->y1 = fit[3];
    grid->cols = (size_t)fmax(1.0, ceil((fit[2] - fit[0]) / n->cell_size - 1e-9));
    grid->rows = (size_t)fmax(1.0, ceil((fit[3] - fit[1]) / n->cell_size - 1e-9));
    size_t cells = grid->cols * grid->rows;
    grid->free = calloc(cells, sizeof *grid->free);
    grid->applied = calloc(cells, sizeof *grid->applied);
    grid->cut_by = calloc(cells, sizeof *grid->cut_by);
    if (!grid->free || !grid->applied || !grid->cut_by) {
        grid_free(n->geos, grid);
        return false;
    }
    for (size_t c = 0; c < cells; c++) {
        double box[4];
        cell_box(n, grid, c, box);
        grid->free[c] = rectangle_polygon(n->geos, box[0], box[1], box[2], box[3]);
        if (!grid->free[c]) {
            grid_free(n->geos, grid);
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
    double slack =
        1e-3 + 1e-3 * (ur_box_width(*a) + ur_box_height(*a) + ur_box_width(*b) + ur_box_height(*b));
    double x0 = p->at.x + a->min.x - b->max.x - slack, x1 = p->at.x + a->max.x - b->min.x + slack;
    double y0 = p->at.y + a->min.y - b->max.y - slack, y1 = p->at.y + a->max.y - b->min.y + slack;
    return x0 < cell[2] && x1 > cell[0] && y0 < cell[3] && y1 > cell[1];
}

/* Whether a geometry's box, shifted by at, reaches into a cell (x0, y0, x1, y1). */
static bool reaches(GEOSContextHandle_t geos, const GEOSGeometry *g, ur_vec2 at, const double *cell)
{
    double x0, y0, x1, y1;
    if (!GEOSGeom_getXMin_r(geos, g, &x0) || !GEOSGeom_getYMin_r(geos, g, &y0) ||
        !GEOSGeom_getXMax_r(geos, g, &x1) || !GEOSGeom_getYMax_r(geos, g, &y1))
        return true; /* no box: cut it out and let GEOS say */
    return x0 + at.x < cell[2] && x1 + at.x > cell[0] && y0 + at.y < cell[3] && y1 + at.y > cell[1];
}

/* Cuts a polygon shifted by at out of the cell's room; false on a GEOS failure. */
static bool cut_out(GEOSContextHandle_t geos, GEOSGeometry **room, const GEOSGeometry *polygon,
                    ur_vec2 at)
{
    GEOSGeometry *shifted = GEOSGeom_transformXY_r(geos, polygon, shift_xy, &at);
    GEOSGeometry *left = shifted ? GEOSDifference_r(geos, *room, shifted) : NULL;
    if (shifted)
        GEOSGeom_destroy_r(geos, shifted);
    if (!left)
        return false;
    GEOSGeom_destroy_r(geos, *room);
    *room = left;
    if (GEOSisEmpty_r(geos, left) == 1) {
        GEOSGeom_destroy_r(geos, left);
        *room = NULL; /* full: nothing placed later can free it */
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
    size_t key = pair_key(n, a, ta, b, tb);
    size_t meeting = n->runs * (n->count + 1) + k + 1;
    if (n->nfps[key] || (n->pair_met[key] && n->pair_met[key] != meeting))
        return true;
    n->pair_met[key] = meeting;
    return false;
}

/*
 * Cuts out of cell c the no-fit polygons (with piece at turn) of the parts
 * placed on the sheet since it was last brought up to date, those whose
 * box reaches into it.  False on a GEOS failure.
 */
static bool cell_update(nester *n, size_t sheet, size_t piece, size_t turn, room_grid *grid,
                        size_t c)
{
    double box[4];
    cell_box(n, grid, c, box);
    for (size_t k = grid->applied[c]; grid->free[c] && k < n->placed_count; k++) {
        if (n->sheet_of[k] != sheet)
            continue;
        placed *p = &n->placements[k];
        if (!nfp_may_reach(n, p, piece, turn, box))
            continue; /* too far away to matter: its no-fit polygon is never made */
        if (by_union(n, p->piece, p->turn, piece, turn, k)) {
            const GEOSGeometry *nfp = nest_nfp_of(n, p->piece, p->turn, piece, turn);
            if (!nfp || (reaches(n->geos, nfp, p->at, box) &&
                         !cut_out(n->geos, &grid->free[c], nfp, p->at)))
                return false;
            grid->cut_by[c] = k + 1;
            continue;
        }
        const GEOSGeometry *sums = nest_sums_of(n, p->piece, p->turn, piece, turn);
        int count = sums ? GEOSGetNumGeometries_r(n->geos, sums) : -1;
        if (count < 0)
            return false;
        for (int q = 0; q < count && grid->free[c]; q++) {
            const GEOSGeometry *sum = GEOSGetGeometryN_r(n->geos, sums, q);
            if (!reaches(n->geos, sum, p->at, box))
                continue;
            if (!cut_out(n->geos, &grid->free[c], sum, p->at))
                return false;
            grid->cut_by[c] = k + 1;
        }
    }
    grid->applied[c] = n->placed_count;
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
 * The best place for piece at turn on sheet: the leftmost, then lowest,
 * feasible one.  Columns of cells are looked at from the left; the first
 * with room holds it (the columns after it lie further right).
 */
static bool place_on(nester *n, size_t sheet, size_t piece, size_t turn, ur_vec2 *at)
{
    double fit[4];
    if (sheet >= n->sheet_count) { /* empty: the inner-fit rectangle's lower left corner */
        if (!inner_fit_box(n, sheet, nest_shape_of(n, piece, turn), fit))
            return false;
        *at = ur_vec2_make(fit[0], fit[1]);
        return true;
    }
    size_t slot = taken_slot(n, sheet, piece, turn);
    room_grid *grid = &n->rooms[slot];
    if (n->full[slot])
        return false;
    if (!grid->cols && !grid_make(n, sheet, piece, turn, grid))
        return false; /* it does not fit the sheet, or no memory: no place */
    for (size_t i = 0; i < grid->cols; i++) {
        bool found = false;
        for (size_t c = i * grid->rows; c < (i + 1) * grid->rows; c++) {
            if (!grid->free[c])
                continue;
            if (!cell_update(n, sheet, piece, turn, grid, c)) {
                grid_free(n->geos, grid); /* GEOS failed: better no place than an overlap */
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
    n->full[slot] = true;
    return false;
}

/* How far the parts placed so far reach along the roll (the stock sheet). */
static double roll_length(const nester *n)
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

/* A piece the search leaves free to take its best turn (see place_piece). */
#define ANY_TURN SIZE_MAX

/*
 * Places one piece: the first sheet it fits, at its best turn there (or at
 * turn held, unless that is ANY_TURN); a new sheet otherwise.
 */
static ur_status place_piece(nester *n, size_t piece, size_t held)
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
        double best_reach = 0, length = roll_length(n);
        size_t turns = n->classes[n->class_of[piece]].turn_count;
        /* A held turn is tried alone: a cheaper try, and one the greedy choice would not make. */
        size_t first = held < turns ? held : 0, last = held < turns ? held + 1 : turns;
        for (size_t t = first; t < last; t++) {
            ur_vec2 at = {0, 0};
            if (!place_on(n, sheet, piece, t, &at))
                continue;
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
            return UR_OK;
        }
        if (sheet == n->sheet_count) /* it fits no empty sheet either */
            return ur_error_set(n->error, UR_ERROR_INPUT,
                                "piece %s (%.1f x %.1f mm) does not fit the %.1f x %.1f mm sheet "
                                "(%.1f mm margin) in any allowed turn; give a larger sheet with "
                                "--sheet WxH",
                                n->pieces[piece].name, ur_box_width(n->pieces[piece].box),
                                ur_box_height(n->pieces[piece].box), n->options->sheet_width,
                                n->options->sheet_height, n->options->margin);
    }
    return UR_OK;
}

/* Largest first; equal areas keep their order (the sort is made stable by index). */
typedef struct order_key {
    double area;
    size_t index;
} order_key;

static int compare_keys(const void *a, const void *b)
{
    const order_key *x = a, *y = b;
    if (x->area != y->area)
        return x->area > y->area ? -1 : 1;
    return (x->index > y->index) - (x->index < y->index);
}

/* The layout's sheets: the remnants that took parts, then the stock sheets, in order. */
static ur_status build_layout(nester *n, ur_layout *layout)
{
    size_t *index = malloc((n->sheet_count + 1) * sizeof *index); /* per sheet: in the layout */
    bool *used = calloc(n->sheet_count + 1, sizeof *used);
    layout->sheets = calloc(n->sheet_count ? n->sheet_count : 1, sizeof *layout->sheets);
    if (!index || !used || !layout->sheets) {
        free(index);
        free(used);
        return ur_error_out_of_memory(n->error);
    }
    for (size_t k = 0; k < n->placed_count; k++)
        used[n->sheet_of[k]] = true;
    for (size_t s = 0; s < n->sheet_count; s++) {
        if (s < n->remnant_count && !used[s])
            continue;
        index[s] = layout->sheet_count;
        ur_sheet *sheet = &layout->sheets[layout->sheet_count++];
        nest_sheet_size(n, s, &sheet->width, &sheet->height);
        sheet->remnant = s < n->remnant_count;
        sheet->placements =
            calloc(n->placed_count ? n->placed_count : 1, sizeof *sheet->placements);
        if (!sheet->placements) {
            free(index);
            free(used);
            return ur_error_out_of_memory(n->error);
        }
    }
    free(used);
    for (size_t k = 0; k < n->placed_count; k++) {
        const placed *p = &n->placements[k];
        ur_sheet *sheet = &layout->sheets[index[n->sheet_of[k]]];
        double angle = nest_shape_of(n, p->piece, p->turn)->angle;
        sheet->placements[sheet->placement_count++] =
            (ur_placement){p->piece, ur_transform2_make(angle, p->at)};
    }
    free(index);
    return UR_OK;
}

/* The pieces that found no room on the sheets allowed, in the caller's order. */
static ur_status list_not_placed(const nester *n, ur_layout *layout)
{
    if (n->placed_count == n->count)
        return UR_OK;
    bool *placed_piece = calloc(n->count, sizeof *placed_piece);
    layout->not_placed = calloc(n->count - n->placed_count, sizeof *layout->not_placed);
    if (!placed_piece || !layout->not_placed) {
        free(placed_piece);
        return ur_error_out_of_memory(n->error);
    }
    for (size_t k = 0; k < n->placed_count; k++)
        placed_piece[n->placements[k].piece] = true;
    for (size_t p = 0; p < n->count; p++)
        if (!placed_piece[p])
            layout->not_placed[layout->not_placed_count++] = p;
    free(placed_piece);
    return UR_OK;
}

static void nester_free(nester *n)
{
    size_t slots = n->sheet_slots * (n->class_count + 1) * n->turn_count;
    for (size_t k = 0; n->rooms && k < slots; k++)
        grid_free(n->geos, &n->rooms[k]);
    free(n->rooms);
    free(n->full);
    free(n->run_piece);
    free(n->run_held);
    free(n->run_placed);
    free(n->sheet_area);
    size_t pairs = n->class_count * n->turn_count * n->class_count * n->turn_count;
    for (size_t k = 0; k < pairs; k++) {
        if (n->nfps && n->nfps[k])
            GEOSGeom_destroy_r(n->geos, n->nfps[k]);
        if (n->sums && n->sums[k])
            GEOSGeom_destroy_r(n->geos, n->sums[k]);
    }
    free(n->nfps);
    free(n->sums);
    free(n->pair_met);
    for (size_t c = 0; c < n->class_count; c++) {
        for (size_t t = 0; n->classes[c].turns && t < n->classes[c].turn_count; t++)
            nest_shape_free(n->geos, &n->classes[c].turns[t]);
        free(n->classes[c].turns);
    }
    free(n->classes);
    free(n->class_of);
    free(n->placements);
    free(n->sheet_of);
    if (n->geos)
        GEOS_finish_r(n->geos);
}

/*
 * The size of the rooms' cells: twice the mean part's larger side, so that
 * a no-fit polygon (about two parts across) reaches a few cells and a cell
 * holds a few parts' edges.
 */
static double cell_size_of(const ur_piece *pieces, size_t count, double spacing)
{
    double sum = 0;
    for (size_t k = 0; k < count; k++)
        sum += fmax(ur_box_width(pieces[k].box), ur_box_height(pieces[k].box)) + spacing;
    double size = count ? 2 * sum / (double)count : 0;
    return size > 0 && isfinite(size) ? size : 1.0;
}

/* A roll as one sheet long enough for every part in a row; cut to length afterwards. */
static ur_nest_options roll_sheet(const ur_nest_options *o, const ur_piece *pieces, size_t count)
{
    ur_nest_options sheet = *o;
    sheet.sheet_height = o->roll_width;
    sheet.sheet_width = 2 * o->margin;
    for (size_t k = 0; k < count; k++)
        sheet.sheet_width +=
            hypot(ur_box_width(pieces[k].box), ur_box_height(pieces[k].box)) + o->spacing;
    sheet.max_sheets = 1;
    return sheet;
}

/* The length of roll (the stock sheet) used: as far as its parts reach, and the margin. */
static double used_length(const nester *n)
{
    return roll_length(n) + n->options->margin;
}

static ur_status check_nest_options(const ur_nest_options *o, ur_error *error)
{
    if (!(o->sheet_width > 0) || !(o->sheet_height > 0) || !(o->margin >= 0) ||
        !(o->spacing >= 0) || !isfinite(o->sheet_width) || !isfinite(o->sheet_height))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "nesting needs a sheet of positive size and a "
                            "margin and spacing of 0 mm or more");
    if (2 * o->margin >= o->sheet_width || 2 * o->margin >= o->sheet_height)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the margin (%g mm) leaves no room on the %g x %g mm sheet", o->margin,
                            o->sheet_width, o->sheet_height);
    for (size_t k = 0; k < o->remnant_count; k++)
        if (!(o->remnants[k].width > 0) || !(o->remnants[k].height > 0) ||
            !isfinite(o->remnants[k].width) || !isfinite(o->remnants[k].height))
            return ur_error_set(error, UR_ERROR_INPUT,
                                "remnant %zu: a remnant needs a positive width and height", k + 1);
    return UR_OK;
}

/* ---- The search over orders ------------------------------------------------- */

/*
 * Makes a cell of a grid whole again (no placement cut from it yet); on a
 * GEOS failure the whole grid goes, to be made again when next asked for.
 */
static void cell_renew(nester *n, room_grid *grid, size_t c)
{
    double box[4];
    cell_box(n, grid, c, box);
    if (grid->free[c])
        GEOSGeom_destroy_r(n->geos, grid->free[c]);
    grid->free[c] = rectangle_polygon(n->geos, box[0], box[1], box[2], box[3]);
    grid->applied[c] = grid->cut_by[c] = 0;
    if (!grid->free[c])
        grid_free(n->geos, grid);
}

/*
 * Forgets all placements but the first kept (maybe none), as if only those
 * had been made: a cell that a later one cut is made whole again, the
 * others only forget having looked at the later ones.  Rooms thus kept are
 * what a run placing just the first kept would have made, cut for cut; the
 * no-fit polygons stay, they hold for any run.
 */
static void rewind_run(nester *n, size_t kept)
{
    size_t slots = n->sheet_slots * (n->class_count + 1) * n->turn_count;
    for (size_t k = 0; k < slots; k++) {
        room_grid *grid = &n->rooms[k];
        n->full[k] = false; /* a later placement may have filled it */
        for (size_t c = 0; grid->cols && c < grid->cols * grid->rows; c++) {
            if (grid->cut_by[c] > kept)
                cell_renew(n, grid, c);
            else if (grid->applied[c] > kept)
                grid->applied[c] = kept;
        }
    }
    memset(n->sheet_area, 0, n->sheet_slots * sizeof *n->sheet_area);
    n->sheet_count = n->remnant_count;
    for (size_t k = 0; k < kept; k++) {
        n->sheet_area[n->sheet_of[k]] += nest_shape_of(n, n->placements[k].piece, 0)->area;
        if (n->sheet_of[k] >= n->sheet_count)
            n->sheet_count = n->sheet_of[k] + 1;
    }
    n->placed_count = kept;
}

/*
 * Places the pieces in order, each at its held turn (per piece; NULL: all
 * free).  Where the order and turns begin as the last run's did, that
 * run's placements stand: a placement depends only on those before it.
 */
static ur_status run_order(nester *n, const size_t *order, const size_t *held)
{
    size_t same = 0;
    while (same < n->run_length && n->run_piece[same] == order[same] &&
           n->run_held[same] == (held ? held[order[same]] : ANY_TURN))
        same++;
    rewind_run(n, n->run_placed[same]); /* run_placed[0] is 0: a run from the start */
    n->runs++;
    n->run_length = same;
    ur_status status = UR_OK;
    for (size_t k = same; status == UR_OK && k < n->count; k++) {
        n->run_piece[k] = order[k];
        n->run_held[k] = held ? held[order[k]] : ANY_TURN;
        n->run_placed[k] = n->placed_count;
        status = place_piece(n, order[k], n->run_held[k]);
        n->run_length = status == UR_OK ? k + 1 : 0;
        if (n->first_run && n->options->placing)
            n->options->placing(n->options->progress_context, k + 1, n->count);
    }
    n->run_placed[n->count] = n->placed_count; /* an order the same throughout keeps them all */
    return status;
}

/*
 * A layout's score: parts placed, stock sheets used, then how tightly the
 * last sheet is packed: the length of it used (up to its rightmost part),
 * then how far its parts reach on average (the mean of their right edges),
 * which tells apart layouts of the same length, some closer to freeing room
 * at the end than others, so that the search has somewhere to go.
 */
typedef struct score {
    size_t placed, sheets; /* sheets: stock sheets */
    double length, reach;
} score;

static score score_of(const nester *n)
{
    score s = {n->placed_count, n->sheet_count - n->remnant_count, 0.0, 0.0};
    size_t on_last = 0;
    for (size_t k = 0; k < n->placed_count; k++)
        if (n->sheet_of[k] + 1 == n->sheet_count) {
            const placed *p = &n->placements[k];
            double right = p->at.x + nest_shape_of(n, p->piece, p->turn)->box.max.x;
            s.length = fmax(s.length, right);
            s.reach += right;
            on_last++;
        }
    s.reach = on_last ? s.reach / (double)on_last : 0.0;
    return s;
}

/* Whether a is better than b (1), as good (0) or worse (-1). */
static int compare_scores(score a, score b)
{
    if (a.placed != b.placed)
        return a.placed > b.placed ? 1 : -1;
    if (a.sheets != b.sheets)
        return a.sheets < b.sheets ? 1 : -1;
    if (fabs(a.length - b.length) > 1e-9)
        return a.length < b.length ? 1 : -1;
    if (fabs(a.reach - b.reach) > 1e-9)
        return a.reach < b.reach ? 1 : -1;
    return 0;
}

uint64_t nest_next_random(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return *state * 2685821657736338717ULL;
}

/* Two parts swapped, or one moved elsewhere in the order. */
static void mutate(size_t *order, size_t count, uint64_t *state)
{
    size_t i = nest_next_random(state) % count, j = nest_next_random(state) % count;
    if (nest_next_random(state) & 1) {
        size_t swap = order[i];
        order[i] = order[j];
        order[j] = swap;
        return;
    }
    size_t moved = order[i];
    if (i < j)
        memmove(order + i, order + i + 1, (j - i) * sizeof *order);
    else
        memmove(order + j + 1, order + j, (i - j) * sizeof *order);
    order[j] = moved;
}

/*
 * Whether piece may be held at turn: only at turns that fit an empty stock
 * sheet, so that a held part always has a place (the first layout found
 * one for it at some turn) and never makes a try fail.
 */
static bool may_hold(const nester *n, size_t piece, size_t turn)
{
    double fit[4];
    return inner_fit_box(n, n->remnant_count, nest_shape_of(n, piece, turn), fit);
}

/*
 * A part's turn changed: held at another of its turns, or freed to take
 * its best again.  False when the part drawn has no other choice (one
 * turn, or the others do not fit).
 */
static bool turn_move(const nester *n, size_t *held, uint64_t *state)
{
    size_t piece = nest_next_random(state) % n->count;
    size_t turns = n->classes[n->class_of[piece]].turn_count;
    if (turns < 2)
        return false;
    /* Choice turns stands for free; the part's present choice is not drawn. */
    size_t now = held[piece] < turns ? held[piece] : turns;
    size_t choice = nest_next_random(state) % turns;
    if (choice >= now)
        choice++;
    if (choice < turns && !may_hold(n, piece, choice))
        return false;
    held[piece] = choice < turns ? choice : ANY_TURN;
    return true;
}

double nest_seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/*
 * Improves on order (run and placed already, every part free to take its
 * best turn) within the options' budget; leaves the best placed.  A hill
 * climb over orders and turns that also takes sideways steps (a layout as
 * good as the current one replaces it), so that it wanders across the many
 * layouts of equal score instead of stopping at the first.  A step either
 * changes the order (mutate) or, one time in NEST_TURN_MOVES, one part's
 * turn (turn_move): the greedy choice of each part's turn is often not the
 * one that leaves the best room for the parts after it, and a part held at
 * one turn is tried at that turn alone.  It gives up after a run of tries
 * without a new best: NEST_PATIENCE, or NEST_PATIENCE_PER_SECOND per second
 * of budget if that is more.
 */
#define NEST_TURN_MOVES 3
static ur_status search(nester *n, size_t *order, double budget)
{
    const ur_nest_options *o = n->options;
    if (!(budget > 0) || n->count < 2)
        return UR_OK;
    size_t bytes = n->count * sizeof *order;
    size_t *current = malloc(bytes), *candidate = malloc(bytes);
    /* Per piece: the turn it is held at, or ANY_TURN; for the current, candidate and best. */
    size_t *current_held = malloc(bytes), *candidate_held = malloc(bytes);
    size_t *best_held = malloc(bytes);
    if (!current || !candidate || !current_held || !candidate_held || !best_held) {
        free(current);
        free(candidate);
        free(current_held);
        free(candidate_held);
        free(best_held);
        return ur_error_out_of_memory(n->error);
    }
    memcpy(current, order, bytes);
    for (size_t p = 0; p < n->count; p++)
        current_held[p] = best_held[p] = ANY_TURN;
    bool turns = n->turn_count > 1; /* some part has a choice of turns */
    uint64_t state = o->seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL;
    score best = score_of(n), now = best;
    double start = nest_seconds_now();
    double patience = fmax(NEST_PATIENCE, NEST_PATIENCE_PER_SECOND * budget);
    ur_status status = UR_OK;
    size_t since_better = 0;
    for (size_t tries = 1; status == UR_OK && tries <= NEST_TRIES &&
                           (double)since_better < patience && nest_seconds_now() - start < budget;
         tries++) {
        status = ur_context_check(n->options->context, n->error);
        if (status != UR_OK)
            break;
        memcpy(candidate, current, bytes);
        memcpy(candidate_held, current_held, bytes);
        bool turned = turns && nest_next_random(&state) % NEST_TURN_MOVES == 0 &&
                      turn_move(n, candidate_held, &state);
        if (!turned)
            mutate(candidate, n->count, &state);
        status = run_order(n, candidate, candidate_held);
        score s = score_of(n);
        since_better++;
        if (status != UR_OK || compare_scores(s, now) < 0)
            continue;
        now = s;
        memcpy(current, candidate, bytes);
        memcpy(current_held, candidate_held, bytes);
        if (compare_scores(s, best) > 0) {
            best = s;
            memcpy(order, candidate, bytes);
            memcpy(best_held, candidate_held, bytes);
            since_better = 0;
            if (o->progress)
                o->progress(o->progress_context, s.sheets, s.length, tries);
        }
    }
    if (status == UR_OK)
        status = run_order(n, order, best_held); /* the best, placed again */
    free(current);
    free(candidate);
    free(current_held);
    free(candidate_held);
    free(best_held);
    return status;
}

/* ---- Fewer sheets, and the last one's offcut --------------------------------- */

/*
 * The budget's shares: the search over orders has the first fifth; on
 * sheets the search for fewer sheets goes on to four fifths (or until it
 * reaches the bound), then the last sheet's parts are pushed to one end.
 */
#define ORDER_SHARE 0.2
#define FEWER_SHEETS_SHARE 0.8

/*
 * The fewest stock sheets any layout needs by area: the parts' area less
 * the room inside the remnants' margins, over the room inside a stock
 * sheet's, rounded up.
 */
static size_t stock_sheets_bound(const nester *n)
{
    const ur_nest_options *o = n->options;
    double area = 0;
    for (size_t p = 0; p < n->count; p++)
        area += nest_shape_of(n, p, 0)->area;
    for (size_t s = 0; s < n->remnant_count; s++) {
        double width, height;
        nest_sheet_size(n, s, &width, &height);
        area -= fmax(0, (width - 2 * o->margin) * (height - 2 * o->margin));
    }
    double room = (o->sheet_width - 2 * o->margin) * (o->sheet_height - 2 * o->margin);
    double bound = area > 0 ? ceil(area / room - 1e-9) : 0;
    return bound < (double)n->count ? (size_t)bound : n->count;
}

/* A stock sheet and the area of its parts, to sort the fullest first. */
typedef struct sheet_fill {
    double area;
    size_t sheet;
} sheet_fill;

static int fuller_first(const void *a, const void *b)
{
    const sheet_fill *x = a, *y = b;
    if (x->area != y->area)
        return x->area > y->area ? -1 : 1;
    return (x->sheet > y->sheet) - (x->sheet < y->sheet);
}

/*
 * Numbers the stock sheets anew, the fullest first (the remnants keep
 * theirs): the sheet search drops the last ones, and the last is the one
 * whose parts are pushed to one end.  Only once the nester's rooms are no
 * longer needed: they are kept per sheet number.
 */
static ur_status number_fullest_first(nester *n)
{
    size_t stock = n->sheet_count - n->remnant_count;
    sheet_fill *fills = calloc(stock + 1, sizeof *fills);
    size_t *renumbered = calloc(n->sheet_count + 1, sizeof *renumbered);
    if (!fills || !renumbered) {
        free(fills);
        free(renumbered);
        return ur_error_out_of_memory(n->error);
    }
    for (size_t k = 0; k < stock; k++)
        fills[k] = (sheet_fill){n->sheet_area[n->remnant_count + k], n->remnant_count + k};
    qsort(fills, stock, sizeof *fills, fuller_first);
    for (size_t s = 0; s < n->remnant_count; s++)
        renumbered[s] = s;
    for (size_t k = 0; k < stock; k++) {
        renumbered[fills[k].sheet] = n->remnant_count + k;
        n->sheet_area[n->remnant_count + k] = fills[k].area;
    }
    for (size_t p = 0; p < n->placed_count; p++)
        n->sheet_of[p] = renumbered[n->sheet_of[p]];
    free(fills);
    free(renumbered);
    return UR_OK;
}

/*
 * The most parts, and shapes at their turns, the searches on sheets take
 * on: each keeps tables of every pair of parts (32 bytes a pair) and of
 * every pair of shapes at their turns (a flattened no-fit polygon's
 * header, near 200 bytes a pair), which for thousands would be
 * gigabytes.  A layout of more stays as the search over orders left it.
 */
#define SEARCH_PARTS_MOST 1000
#define SEARCH_SHAPE_TURNS_MOST 600

/* Whether the searches on sheets take on count parts of the nester's. */
static bool searchable(const nester *n, size_t count)
{
    return count <= SEARCH_PARTS_MOST && n->class_count * n->turn_count <= SEARCH_SHAPE_TURNS_MOST;
}

/* The parts on a sheet of the nester. */
static size_t parts_on(const nester *n, size_t sheet)
{
    size_t count = 0;
    for (size_t p = 0; p < n->placed_count; p++)
        count += n->sheet_of[p] == sheet;
    return count;
}

/*
 * After the search over orders, on sheets with every part placed: fewer
 * stock sheets, from the area bound up (nest_fewer_sheets), until
 * fewer_until; then the last stock sheet's parts pushed to its left end
 * until deadline.
 */
static ur_status fewer_sheets(nester *n, double fewer_until, double deadline)
{
    if (n->placed_count < n->count || n->sheet_count <= n->remnant_count)
        return UR_OK;
    ur_status status = number_fullest_first(n);
    if (status == UR_OK && searchable(n, n->placed_count))
        status = nest_fewer_sheets(n, stock_sheets_bound(n), fewer_until);
    if (status == UR_OK)
        status = number_fullest_first(n);
    if (status == UR_OK && n->sheet_count > n->remnant_count &&
        searchable(n, parts_on(n, n->sheet_count - 1)))
        status = nest_push_to_one_end(n, n->sheet_count - 1, deadline);
    return status;
}

/*
 * The last stock sheet's offcut: from its parts' right edges and the
 * spacing to the sheet's right edge.
 */
static void measure_offcut(const nester *n, ur_layout *layout)
{
    if (n->sheet_count <= n->remnant_count || layout->sheet_count == 0)
        return;
    size_t last = n->sheet_count - 1;
    double reach = 0;
    for (size_t p = 0; p < n->placed_count; p++) {
        const placed *part = &n->placements[p];
        if (n->sheet_of[p] == last)
            reach = fmax(reach, part->at.x + nest_shape_of(n, part->piece, part->turn)->box.max.x);
    }
    ur_sheet *sheet = &layout->sheets[layout->sheet_count - 1];
    sheet->offcut_width = fmax(0, sheet->width - reach - n->options->spacing);
}

ur_status ur_layout_nest(const ur_piece *pieces, size_t count, const ur_nest_options *options,
                         ur_layout *layout, ur_error *error)
{
    memset(layout, 0, sizeof *layout);
    ur_nest_options roll;
    if (options->roll_width > 0) {
        roll = roll_sheet(options, pieces, count);
        options = &roll;
    }
    ur_status status = check_nest_options(options, error);
    if (status != UR_OK)
        return status;
    nester n = {.geos = GEOS_init_r(),
                .pieces = pieces,
                .count = count,
                .options = options,
                .turn_count = most_turns(options, pieces, count),
                .remnant_count = options->remnants ? options->remnant_count : 0,
                .first_run = true,
                .error = error};
    n.sheet_count = n.remnant_count;
    n.cell_size = cell_size_of(pieces, count, options->spacing);
    n.sheet_slots = n.remnant_count + count + 1;
    n.class_of = calloc(count + 1, sizeof *n.class_of);
    n.classes = calloc(count + 1, sizeof *n.classes);
    n.placements = calloc(count + 1, sizeof *n.placements);
    n.sheet_of = calloc(count + 1, sizeof *n.sheet_of);
    order_key *keys = calloc(count + 1, sizeof *keys);
    if (!n.geos || !n.class_of || !n.classes || !n.placements || !n.sheet_of || !keys)
        status = ur_error_out_of_memory(error);
    if (status == UR_OK)
        status = sort_classes(&n);
    size_t slots = n.sheet_slots * (n.class_count + 1) * n.turn_count;
    if (status == UR_OK) {
        n.rooms = calloc(slots, sizeof *n.rooms);
        n.full = calloc(slots, sizeof *n.full);
        n.sheet_area = calloc(n.sheet_slots, sizeof *n.sheet_area);
        n.run_piece = calloc(count + 1, sizeof *n.run_piece);
        n.run_held = calloc(count + 1, sizeof *n.run_held);
        n.run_placed = calloc(count + 1, sizeof *n.run_placed);
        if (!n.rooms || !n.full || !n.sheet_area || !n.run_piece || !n.run_held || !n.run_placed)
            status = ur_error_out_of_memory(error);
    }
    for (size_t p = 0; status == UR_OK && p < count; p++)
        keys[p] = (order_key){nest_shape_of(&n, p, 0)->area, p};
    if (status == UR_OK)
        qsort(keys, count, sizeof *keys, compare_keys);
    size_t *order = calloc(count + 1, sizeof *order);
    if (status == UR_OK && !order)
        status = ur_error_out_of_memory(error);
    for (size_t k = 0; status == UR_OK && k < count; k++)
        order[k] = keys[k].index;
    if (status == UR_OK)
        status = run_order(&n, order, NULL);
    n.first_run = false;
    double start = nest_seconds_now(), budget = options->time_budget;
    /*
     * The search over orders has a share of the budget; shortening the
     * strip, or fewer sheets and then the last one's parts pushed to one
     * end, the rest.
     */
    if (status == UR_OK)
        status = search(&n, order, ORDER_SHARE * budget);
    if (status == UR_OK && options->roll_width > 0 && budget > 0)
        status = nest_compact_roll(&n, start + budget);
    if (status == UR_OK && options->roll_width <= 0 && budget > 0)
        status = fewer_sheets(&n, start + FEWER_SHEETS_SHARE * budget, start + budget);
    free(order);
    if (status == UR_OK && options->roll_width > 0 && n.placed_count < count)
        status = ur_error_set(error, UR_ERROR_INPUT,
                              "a part does not fit across the %g mm roll in any allowed turn",
                              options->roll_width);
    if (status == UR_OK)
        status = build_layout(&n, layout);
    if (status == UR_OK)
        status = list_not_placed(&n, layout);
    if (status == UR_OK && options->roll_width > 0 && layout->sheet_count > 0 &&
        !layout->sheets[layout->sheet_count - 1].remnant)
        layout->sheets[layout->sheet_count - 1].width = used_length(&n);
    if (status == UR_OK && options->roll_width <= 0)
        measure_offcut(&n, layout);
    if (status != UR_OK)
        ur_layout_free(layout);
    free(keys);
    nester_free(&n);
    return status;
}
