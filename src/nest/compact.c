/*
 * compact.c: shortening a roll layout by overlap minimisation, and the
 * same search on sheets: fewer sheets, and the last one's parts pushed to
 * one end.
 *
 * The first layout (nest.c) places each part where it fits; this search
 * lets parts overlap on the way to a shorter strip, as the best strip
 * packers do (guided local search, after Egeblad et al. 2007, Umetani et
 * al. 2009 and Gardeyn and Wauters 2025).  From the shortest layout found
 * so far it cuts the strip a little shorter, taking a slice out of it at a
 * random place (the parts beyond it move back, now overlapping those
 * before it), and then separates them: each overlapping part
 * in turn moves to the place and turn where it overlaps the others least
 * (random places across the strip at random turns, and near its own, the
 * best refined by smaller and smaller steps, then pushed out of the part
 * it overlaps most, to touch it exactly).  Overlap is the penetration
 * depth: how far a part must move to leave another, read off their no-fit
 * polygon (the distance from the one's origin to that polygon's edge when
 * it lies inside).  A part's cost at a place is the sum over the parts it
 * overlaps of the depth plus a floor, scaled by the pair's size and
 * weighted (see pair_cost).  Pairs that keep overlapping weigh more each
 * round (guided local search), so the parts make room for each other
 * instead of stopping at the first crowded layout.
 *
 * Exploration (most of the time) cuts 0.3% at a time; when the parts cannot
 * be separated it keeps the least overlapping layout among its near misses
 * at that length, jolts one of the best of them (two parts trade places)
 * and tries the same length again.  Compression (the rest) cuts
 * less and less from the best, once each.  Only layouts with no overlap
 * left are kept, so what the nester writes never overlaps.
 *
 * On sheets the parts may move between the nester's sheets as well
 * (random places on any of them): to put a layout on fewer sheets, the
 * parts of the sheets to drop go at the end of the last sheet kept, as if
 * it were a roll that long, and that strip is shortened as a roll is until
 * it is no longer than the sheet (search_fewer).  To leave the last
 * sheet's offcut whole, that sheet alone is shortened (push_to_one_end).
 *
 * Several searches may run side by side, one per thread, each with its own
 * random steps and copies of the no-fit polygons; they share the shortest
 * layout found (each goes on from it as soon as it sees it), and take
 * turns with the nester, whose GEOS context is not theirs to share.
 */
#include "nest_internal.h"

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>
#include <unistd.h>

/* Depths below this count as touching (mm): the rounding of points on a no-fit polygon's edge. */
#define TOUCHING 1e-9
/*
 * How far past a no-fit polygon's edge a part pushed out of it goes, as a
 * fraction of the point's coordinates: past the rounding of the push, so
 * that GEOS too sees it outside.
 */
#define OUT_BEYOND 1e-12
/*
 * Cells of a no-fit polygon's grid per edge, and at most: more cells make
 * shorter lists of the edges that may be nearest, and cost more to make.
 */
#define CELLS_PER_EDGE 4
#define CELLS_MOST 1024
/* Random places tried across the strip, and near the part, when a part moves. */
#define PLACES_ACROSS 60
#define PLACES_NEAR 20
/* The finest step of a move's refinement, as a fraction of the part's size. */
#define REFINE_FINEST 1e-4
/* Pushes out of the part a move overlaps most, at most. */
#define PUSHES_OUT 4
/*
 * Rounds of moves without a gain before a separation tries again from its
 * least overlapping layout: ROUNDS_PER_PART per part on the roll, at least
 * ROUNDS_WITHOUT_GAIN.  A round moves each overlapping part once, and the
 * more parts, the more rounds a gain takes to show (at 30 s, 50 rounds
 * did best with 25 parts, 200 with 99).  A gain is a fall of the total
 * overlap by GAIN below its least: smaller falls would keep a separation
 * that is going nowhere creeping on.
 */
#define ROUNDS_WITHOUT_GAIN 50
#define ROUNDS_PER_PART 2
#define GAIN 0.02
/* Tries in a row without a gain before a separation gives up. */
#define STRIKES 3
/*
 * The floor of an overlap's cost, as a fraction of the larger part's size
 * (sparrow's 1%): any overlap, however shallow, then costs something.
 */
#define OVERLAP_FLOOR 0.01
/*
 * Exploration's share of the time, and its cut of the strip (a fraction of
 * its length): small steps let the layout change bit by bit (with 1%,
 * jakobs2 stayed at the length of its first layout; 0.1%, sparrow's, was
 * slow on shirts' 99 parts at 60 s).
 */
#define EXPLORE_SHARE 0.8
#define EXPLORE_CUT 0.003
/*
 * The least overlapping layouts exploration keeps at one length, at most,
 * and how it picks the one to jolt next: the k-th best with k a fraction
 * of them drawn from a half-normal spread (Gardeyn and Wauters's 0.25), so
 * mostly among the best few but now and then a worse one.
 */
#define NEAR_MISSES 32
#define NEAR_MISS_SPREAD 0.25
/* Compression's first and last cut, and the failed cuts in a row that end it. */
#define COMPRESS_FIRST 0.005
#define COMPRESS_LAST 0.0001
#define COMPRESS_PATIENCE 200

/*
 * An edge of a no-fit polygon's rings: from a, along d, to a height of by;
 * inverse: of d's squared length (or 0).  The end's height is kept as it
 * was read, not as ay + dy, so that an edge and the next compare a point's
 * height with the very same number at the vertex they share: the inside
 * test's crossings then always pair up.
 */
typedef struct flat_edge {
    double ax, ay, by, dx, dy, inverse;
} flat_edge;

/* Where a cell of a no-fit polygon's grid lies: outside it, inside, or across its edges. */
typedef enum cell_kind { CELL_OUTSIDE, CELL_INSIDE, CELL_ACROSS } cell_kind;

/*
 * A no-fit polygon as the edges of its rings, for fast depth queries.  It
 * is cut across into bands of equal height, each listing the edges that
 * reach into it: a point's inside test needs only its band's edges.  And
 * its box is cut into a grid of cells, each knowing whether it lies
 * outside, inside or across the rings, and listing the few edges that can
 * be the nearest to a point in it: a depth needs only those.
 */
typedef struct flat_nfp {
    double box[4]; /* x0, y0, x1, y1 */
    flat_edge *edges;
    size_t edge_count;
    double band_height;
    size_t band_count;
    size_t *band_start; /* band b: band_edges[band_start[b]] to band_edges[band_start[b + 1] - 1] */
    size_t *band_edges;
    double cell_width, cell_height;
    double per_width, per_height; /* 1 / cell_width, 1 / cell_height */
    size_t columns, rows;
    unsigned char *cell_kind; /* per cell, row by row: a cell_kind */
    uint32_t *cell_start;     /* cell c: cell_edges[cell_start[c] to cell_start[c + 1] - 1] */
    uint32_t *cell_edges;     /* 32 bits: the lists take much of a search's memory */
    bool made;
} flat_nfp;

/* Where the parts are: one state of the search. */
typedef struct state {
    size_t *turn;
    ur_vec2 *at;
    size_t *sheet; /* the nester's sheet each is on */
} state;

/*
 * The least overlapping layouts the separations at one length ended with,
 * least overlap first: exploration jolts one of them when a separation
 * fails, so that it goes on from a good layout, not just the last one.
 */
typedef struct near_misses {
    state layout[NEAR_MISSES]; /* each owned */
    double total[NEAR_MISSES]; /* each one's total overlap */
    size_t count;
} near_misses;

/*
 * What the searches running side by side share: the shortest verified
 * layout any of them has found, and the nester, whose GEOS context and
 * no-fit polygons only one may use at a time.
 */
typedef struct shared_best {
    mtx_t lock;                /* held to use the nester, or to read or write the fields below */
    double length;             /* of best (reach_of) */
    state best;                /* owned */
    atomic_uint version;       /* one more with each new best: read without the lock */
    atomic_size_t separations; /* tried by all the searches: the progress line's count */
} shared_best;

typedef struct compactor {
    nester *n;
    shared_best *shared;
    unsigned seen;  /* the shared version this search has caught up with */
    ur_error error; /* its own, copied to the nester's when it fails */
    ur_status status;
    /*
     * The parts keep within length of the nester's sheet strip_sheet (from
     * its margin): a roll, or a sheet whose parts are pushed to one end
     * (to_one_end), every part on it.  Or, across_sheets, a sheet search:
     * every part, on the nester's sheets 0 to sheet_count - 1, whole ones
     * but for the last, strip_sheet, which the parts of the sheets dropped
     * lengthen at first (see search_fewer); sheet_length is its own.
     */
    bool across_sheets, to_one_end;
    size_t strip_sheet, sheet_count;
    double sheet_length;
    size_t stock_sheets; /* stock sheets of the layout: what progress tells */
    size_t count;        /* parts searched over */
    size_t *index;       /* per part: its placement in the nester */
    size_t *piece;       /* per part */
    state now, best;
    double *depth;      /* count x count: how far each pair overlaps */
    double *weight;     /* count x count: guided local search's weight of each pair */
    double *pair_scale; /* count x count: each pair's size (pair_cost) */
    double *pair_floor; /* count x count: each pair's least overlap (pair_cost) */
    flat_nfp *nfps;     /* per (class, turn, class, turn), as the nester keys them */
    double length;      /* a strip: the length the parts must keep within, from the margin (mm) */
    double deadline;    /* on nest_seconds_now's clock */
    uint64_t random;
    const flat_nfp **row; /* scratch: per turn and part, the no-fit polygon a moving part meets */
    size_t *order;        /* scratch: the order parts move in during a round */
    state least;          /* scratch: a separation's least overlapping layout */
    near_misses misses;   /* exploration's, at its current length */
} compactor;

/* A uniform random number in [0, 1). */
static double uniform(uint64_t *seed)
{
    return (double)(nest_next_random(seed) >> 11) * 0x1.0p-53;
}

static void flat_free(flat_nfp *f)
{
    free(f->edges);
    free(f->band_start);
    free(f->band_edges);
    free(f->cell_kind);
    free(f->cell_start);
    free(f->cell_edges);
    memset(f, 0, sizeof *f);
}

/* Adds a ring's edges to f (edges allocated for them); false on a failure. */
static bool add_ring(GEOSContextHandle_t geos, const GEOSGeometry *ring, flat_nfp *f)
{
    const GEOSCoordSequence *sequence = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size))
        return false;
    double x0 = 0, y0 = 0;
    for (unsigned i = 0; i < size; i++) {
        double x, y;
        GEOSCoordSeq_getXY_r(geos, sequence, i, &x, &y);
        f->box[0] = fmin(f->box[0], x), f->box[1] = fmin(f->box[1], y);
        f->box[2] = fmax(f->box[2], x), f->box[3] = fmax(f->box[3], y);
        if (i > 0) {
            double dx = x - x0, dy = y - y0, length2 = dx * dx + dy * dy;
            f->edges[f->edge_count++] =
                (flat_edge){x0, y0, y, dx, dy, length2 > 0 ? 1 / length2 : 0};
        }
        x0 = x, y0 = y;
    }
    return true;
}

/* The number of points in a polygon's rings. */
static size_t ring_points(GEOSContextHandle_t geos, const GEOSGeometry *polygon)
{
    size_t points = 0;
    int holes = GEOSGetNumInteriorRings_r(geos, polygon);
    for (int r = -1; r < holes; r++) {
        const GEOSGeometry *ring =
            r < 0 ? GEOSGetExteriorRing_r(geos, polygon) : GEOSGetInteriorRingN_r(geos, polygon, r);
        int size = ring ? GEOSGetNumCoordinates_r(geos, ring) : 0;
        points += size > 0 ? (size_t)size : 0;
    }
    return points;
}

/* The band a height falls in, clamped to the bands there are. */
static size_t band_of(const flat_nfp *f, double y)
{
    double b = floor((y - f->box[1]) / f->band_height);
    return b < 0 ? 0 : b >= (double)f->band_count ? f->band_count - 1 : (size_t)b;
}

/* The bands of f's edges (edges and box made); false on a failure. */
static bool make_bands(flat_nfp *f)
{
    f->band_count = f->edge_count / 2 + 1;
    f->band_height = (f->box[3] - f->box[1]) / (double)f->band_count;
    if (!(f->band_height > 0)) {
        f->band_count = 1;
        f->band_height = 1;
    }
    f->band_start = calloc(f->band_count + 1, sizeof *f->band_start);
    if (!f->band_start)
        return false;
    /* Counted first, then filled: band_start[b + 1] counts band b's edges, then runs over them. */
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            for (size_t b = 0; b < f->band_count; b++)
                f->band_start[b + 1] += f->band_start[b];
            f->band_edges = calloc(f->band_start[f->band_count] + 1, sizeof *f->band_edges);
            if (!f->band_edges)
                return false;
        }
        size_t *fill = calloc(f->band_count, sizeof *fill);
        if (!fill)
            return false;
        for (size_t i = 0; i < f->edge_count; i++) {
            const flat_edge *e = &f->edges[i];
            size_t low = band_of(f, fmin(e->ay, e->by));
            size_t high = band_of(f, fmax(e->ay, e->by));
            for (size_t b = low; b <= high; b++) {
                if (pass == 0)
                    f->band_start[b + 1]++;
                else
                    f->band_edges[f->band_start[b] + fill[b]++] = i;
            }
        }
        free(fill);
    }
    return true;
}

/* Whether p lies inside f's rings: a ray to the right crosses an odd number of its band's edges. */
static inline bool inside_of(const flat_nfp *f, ur_vec2 p)
{
    size_t band = band_of(f, p.y);
    bool inside = false;
    for (size_t k = f->band_start[band]; k < f->band_start[band + 1]; k++) {
        const flat_edge *e = &f->edges[f->band_edges[k]];
        if ((e->ay > p.y) != (e->by > p.y) &&
            ((p.x - e->ax) * e->dy < (p.y - e->ay) * e->dx) == (e->dy > 0))
            inside = !inside;
    }
    return inside;
}

/* How far along an edge (0 to 1) its point nearest to p lies. */
static inline double edge_fraction(const flat_edge *e, ur_vec2 p)
{
    double s = ((p.x - e->ax) * e->dx + (p.y - e->ay) * e->dy) * e->inverse;
    return s < 0 ? 0 : s > 1 ? 1 : s;
}

/* The squared distance from p to an edge. */
static inline double edge_distance2(const flat_edge *e, ur_vec2 p)
{
    double s = edge_fraction(e, p);
    double ex = p.x - e->ax - s * e->dx, ey = p.y - e->ay - s * e->dy;
    return ex * ex + ey * ey;
}

/* The cell a point inside f's box falls in. */
static size_t cell_of(const flat_nfp *f, ur_vec2 p)
{
    /* Not below 0 inside the box; the far edge is rounded into the last cell. */
    size_t column = (size_t)((p.x - f->box[0]) * f->per_width);
    size_t row = (size_t)((p.y - f->box[1]) * f->per_height);
    column = column < f->columns ? column : f->columns - 1;
    row = row < f->rows ? row : f->rows - 1;
    return row * f->columns + column;
}

/*
 * The cells' lists as they are filled: entries used so far, and room for
 * how many.
 */
typedef struct cell_lists {
    size_t used, capacity;
} cell_lists;

/* Appends edge to the list of the cell being filled (grown as needed); false when out of memory. */
static bool add_cell_edge(flat_nfp *f, cell_lists *lists, size_t edge)
{
    if (lists->used == lists->capacity) {
        size_t more = lists->capacity ? 2 * lists->capacity : 64;
        if (more > UINT32_MAX)
            return false;
        uint32_t *grown = realloc(f->cell_edges, more * sizeof *grown);
        if (!grown)
            return false;
        f->cell_edges = grown;
        lists->capacity = more;
    }
    f->cell_edges[lists->used++] = (uint32_t)edge;
    return true;
}

/*
 * Fills cell c of f's grid.  Every point of the cell lies within radius of
 * its centre, and within reach of some edge, reach being the least over
 * the edges of their farthest distance from the cell (at a corner, the
 * distance to a segment being convex).  So a point's nearest edge lies
 * within reach + radius of the centre: those edges are the cell's list.
 * When no edge comes within radius of the centre, none crosses the cell,
 * which then lies wholly on the centre's side.  False when out of memory.
 */
static bool fill_cell(flat_nfp *f, size_t c, cell_lists *lists)
{
    double x0 = f->box[0] + (double)(c % f->columns) * f->cell_width;
    double y0 = f->box[1] + (double)(c / f->columns) * f->cell_height;
    ur_vec2 centre = {x0 + 0.5 * f->cell_width, y0 + 0.5 * f->cell_height};
    /* A little over half the diagonal: points rounded into the cell from just outside it. */
    double radius = 0.5 * hypot(f->cell_width, f->cell_height) * (1 + 1e-6);
    double reach = INFINITY, closest = INFINITY;
    for (size_t i = 0; i < f->edge_count; i++) {
        double farthest = 0;
        for (int k = 0; k < 4; k++) {
            ur_vec2 corner = {x0 + (k & 1) * f->cell_width, y0 + (k >> 1) * f->cell_height};
            farthest = fmax(farthest, edge_distance2(&f->edges[i], corner));
        }
        reach = fmin(reach, sqrt(farthest));
        closest = fmin(closest, edge_distance2(&f->edges[i], centre));
    }
    closest = sqrt(closest);
    f->cell_kind[c] =
        closest > radius ? (inside_of(f, centre) ? CELL_INSIDE : CELL_OUTSIDE) : CELL_ACROSS;
    f->cell_start[c] = (uint32_t)lists->used;
    if (f->cell_kind[c] == CELL_OUTSIDE)
        return true; /* no depth is ever wanted there */
    double within = (reach + radius) * (reach + radius);
    for (size_t i = 0; i < f->edge_count; i++)
        if (edge_distance2(&f->edges[i], centre) <= within && !add_cell_edge(f, lists, i))
            return false;
    return true;
}

/* The grid of f's cells (edges, box and bands made); false when out of memory. */
static bool make_cells(flat_nfp *f)
{
    double width = f->box[2] - f->box[0], height = f->box[3] - f->box[1];
    if (f->edge_count > UINT32_MAX)
        return false; /* far beyond any memory: the lists number edges in 32 bits */
    size_t wanted = CELLS_PER_EDGE * f->edge_count;
    wanted = wanted < CELLS_MOST ? wanted : CELLS_MOST;
    f->columns = f->rows = 1;
    if (width > 0 && height > 0) {
        double columns = ceil(sqrt((double)wanted * width / height));
        f->columns = columns < 1 ? 1 : columns > (double)wanted ? wanted : (size_t)columns;
        f->rows = (wanted + f->columns - 1) / f->columns;
    }
    f->cell_width = width > 0 ? width / (double)f->columns : 1;
    f->cell_height = height > 0 ? height / (double)f->rows : 1;
    f->per_width = 1 / f->cell_width;
    f->per_height = 1 / f->cell_height;
    size_t cells = f->columns * f->rows;
    cell_lists lists = {0, 0};
    f->cell_kind = calloc(cells, sizeof *f->cell_kind);
    f->cell_start = calloc(cells + 1, sizeof *f->cell_start);
    if (!f->cell_kind || !f->cell_start)
        return false;
    for (size_t c = 0; c < cells; c++)
        if (!fill_cell(f, c, &lists))
            return false;
    f->cell_start[cells] = (uint32_t)lists.used;
    return true;
}

/* The rings of a GEOS polygon or multipolygon, flattened into f; false on failure. */
static bool flatten(GEOSContextHandle_t geos, const GEOSGeometry *g, flat_nfp *f)
{
    int parts = GEOSGetNumGeometries_r(geos, g);
    size_t points = 0;
    for (int k = 0; k < parts; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(geos, g, k);
        if (GEOSGeomTypeId_r(geos, part) == GEOS_POLYGON && !GEOSisEmpty_r(geos, part))
            points += ring_points(geos, part);
    }
    f->edges = calloc(points ? points : 1, sizeof *f->edges);
    if (!f->edges)
        return false;
    f->box[0] = f->box[1] = INFINITY;
    f->box[2] = f->box[3] = -INFINITY;
    for (int k = 0; k < parts; k++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(geos, g, k);
        if (GEOSGeomTypeId_r(geos, part) != GEOS_POLYGON || GEOSisEmpty_r(geos, part))
            continue;
        int holes = GEOSGetNumInteriorRings_r(geos, part);
        for (int r = -1; r < holes; r++)
            if (!add_ring(geos,
                          r < 0 ? GEOSGetExteriorRing_r(geos, part)
                                : GEOSGetInteriorRingN_r(geos, part, r),
                          f))
                return false;
    }
    /* An empty no-fit polygon (parts too small to overlap) has an empty box: depth 0 everywhere. */
    return f->edge_count == 0 || (make_bands(f) && make_cells(f));
}

/*
 * The no-fit polygon of part b at turn tb around part a at turn ta,
 * flattened; NULL on a failure.
 */
static const flat_nfp *nfp_between(compactor *c, size_t a, size_t ta, size_t b, size_t tb)
{
    nester *n = c->n;
    size_t pa = c->piece[a], pb = c->piece[b], t = n->turn_count;
    size_t key = ((n->class_of[pa] * t + ta) * n->class_count + n->class_of[pb]) * t + tb;
    flat_nfp *f = &c->nfps[key];
    if (f->made)
        return f;
    mtx_lock(&c->shared->lock);
    const GEOSGeometry *g = nest_nfp_of(n, pa, ta, pb, tb);
    bool made = g && flatten(n->geos, g, f);
    mtx_unlock(&c->shared->lock);
    if (!made) {
        flat_free(f);
        return NULL;
    }
    f->made = true;
    return f;
}

/*
 * The edge of f's rings nearest to p, a point in the given cell, among
 * those the cell lists (the only ones that can be nearest); its squared
 * distance in *distance2.
 */
static inline const flat_edge *nearest_edge(const flat_nfp *f, size_t cell, ur_vec2 p,
                                            double *distance2)
{
    const flat_edge *nearest = NULL;
    *distance2 = INFINITY;
    for (size_t k = f->cell_start[cell]; k < f->cell_start[cell + 1]; k++) {
        const flat_edge *e = &f->edges[f->cell_edges[k]];
        double d2 = edge_distance2(e, p);
        if (d2 < *distance2) {
            *distance2 = d2;
            nearest = e;
        }
    }
    return nearest;
}

/*
 * How far p lies inside the no-fit polygon (0 outside): the penetration
 * depth, the distance to the nearest edge of its rings.
 */
static double depth_in(const flat_nfp *f, ur_vec2 p)
{
    if (p.x <= f->box[0] || p.x >= f->box[2] || p.y <= f->box[1] || p.y >= f->box[3])
        return 0;
    size_t cell = cell_of(f, p);
    if (f->cell_kind[cell] == CELL_OUTSIDE ||
        (f->cell_kind[cell] == CELL_ACROSS && !inside_of(f, p)))
        return 0;
    double nearest;
    (void)nearest_edge(f, cell, p, &nearest);
    double depth = sqrt(nearest);
    return depth > TOUCHING ? depth : 0;
}

/*
 * The nearest place outside f from p, which lies inside: p taken across
 * the nearest edge of f's rings, a hair beyond it.
 */
static ur_vec2 way_out(const flat_nfp *f, ur_vec2 p)
{
    double nearest;
    const flat_edge *e = nearest_edge(f, cell_of(f, p), p, &nearest);
    double s = e ? edge_fraction(e, p) : 0;
    ur_vec2 edge_point = e ? ur_vec2_make(e->ax + s * e->dx, e->ay + s * e->dy) : p;
    double dx = edge_point.x - p.x, dy = edge_point.y - p.y, length = hypot(dx, dy);
    if (length == 0)
        return p;
    double beyond = OUT_BEYOND * (1 + fabs(edge_point.x) + fabs(edge_point.y));
    return ur_vec2_make(edge_point.x + dx / length * beyond, edge_point.y + dy / length * beyond);
}

/* How far parts i and j overlap where they are now (0 on different sheets); -1 on a failure. */
static double pair_depth(compactor *c, size_t i, size_t j)
{
    if (c->now.sheet[i] != c->now.sheet[j])
        return 0;
    const flat_nfp *f = nfp_between(c, j, c->now.turn[j], i, c->now.turn[i]);
    if (!f)
        return -1;
    return depth_in(f,
                    ur_vec2_make(c->now.at[i].x - c->now.at[j].x, c->now.at[i].y - c->now.at[j].y));
}

/* Brings the depth of the pair i, j up to date (both ways); false on a failure. */
static bool refresh_pair(compactor *c, size_t i, size_t j)
{
    double d = pair_depth(c, i, j);
    if (d < 0)
        return false;
    c->depth[i * c->count + j] = c->depth[j * c->count + i] = d;
    return true;
}

/* Brings part i's row and column of depths up to date; false on a failure. */
static bool update_depths(compactor *c, size_t i)
{
    for (size_t j = 0; j < c->count; j++)
        if (j != i && !refresh_pair(c, i, j))
            return false;
    return true;
}

static double total_depth(const compactor *c)
{
    double total = 0;
    for (size_t i = 0; i < c->count; i++)
        for (size_t j = i + 1; j < c->count; j++)
            total += c->depth[i * c->count + j];
    return total;
}

static bool overlaps_any(const compactor *c, size_t i)
{
    for (size_t j = 0; j < c->count; j++)
        if (c->depth[i * c->count + j] > 0)
            return true;
    return false;
}

/*
 * Where part i's origin may go at turn t on sheet (x0, y0, x1, y1), inside
 * the margin and, on the strip's sheet, within c->length of it; false when
 * it does not fit there at that turn.
 */
static bool inner_fit(const compactor *c, size_t sheet, size_t i, size_t t, double *box)
{
    const nester *n = c->n;
    const ur_nest_options *o = n->options;
    const nest_shape *shape = nest_shape_of(n, c->piece[i], t);
    double width, height;
    nest_sheet_size(n, sheet, &width, &height);
    box[0] = o->margin - shape->box.min.x;
    box[1] = o->margin - shape->box.min.y;
    box[2] =
        (sheet == c->strip_sheet ? o->margin + c->length : width - o->margin) - shape->box.max.x;
    box[3] = height - o->margin - shape->box.max.y;
    return box[2] >= box[0] && box[3] >= box[1];
}

/* Where part i may go at turn t on the sheet it is on now (inner_fit). */
static bool fits_where_it_is(const compactor *c, size_t i, size_t t, double *box)
{
    return inner_fit(c, c->now.sheet[i], i, t, box);
}

/* A candidate: part i at turn t, its origin at p on sheet, and its weighted overlap there. */
typedef struct candidate {
    size_t turn;
    ur_vec2 at;
    double cost;
    size_t sheet;
} candidate;

/*
 * Fills c->row (per turn, per part) with the no-fit polygons part i meets
 * at each of its turns; false on a failure.
 */
static bool fill_rows(compactor *c, size_t i, size_t turns)
{
    for (size_t t = 0; t < turns; t++)
        for (size_t j = 0; j < c->count; j++) {
            if (j == i)
                continue;
            c->row[t * c->count + j] = nfp_between(c, j, c->now.turn[j], i, t);
            if (!c->row[t * c->count + j])
                return false;
        }
    return true;
}

/*
 * What parts i and j overlapping by depth d (> 0) cost: the depth plus a
 * floor, times the pair's size and weight, as in sparrow (Gardeyn and
 * Wauters 2025: the square root of an overlap area, plus a floor, times
 * the geometric mean of the parts' square-rooted areas).  The floor makes
 * every overlap count, however shallow, so that a move clears overlaps
 * rather than spreading them thin; the size makes large parts' overlaps
 * count more, so they settle first and the small ones fill in around them.
 * With squared depths and no size, most 60 s runs of jakobs2 ended in its
 * two-column layout (24.00); with this cost, none of 8 did (see
 * bench/esicup/README.md).
 */
static double pair_cost(const compactor *c, size_t i, size_t j, double d)
{
    size_t k = i * c->count + j;
    return c->weight[k] * (d + c->pair_floor[k]) * c->pair_scale[k];
}

/* Part i's cost (pair_cost) at turn t and p on sheet, given up once above limit. */
static double cost_at(const compactor *c, size_t i, size_t t, size_t sheet, ur_vec2 p, double limit)
{
    const flat_nfp *const *row = c->row + t * c->count;
    double cost = 0;
    for (size_t j = 0; j < c->count && cost < limit; j++) {
        if (j == i || c->now.sheet[j] != sheet)
            continue;
        double d = depth_in(row[j], ur_vec2_make(p.x - c->now.at[j].x, p.y - c->now.at[j].y));
        if (d > 0)
            cost += pair_cost(c, i, j, d);
    }
    return cost;
}

static ur_vec2 clamp_to(ur_vec2 p, const double *box)
{
    return ur_vec2_make(fmin(fmax(p.x, box[0]), box[2]), fmin(fmax(p.y, box[1]), box[3]));
}

/* Tries part i at turn t and p on sheet: the new best candidate when it overlaps less. */
static void try_place(const compactor *c, size_t i, size_t t, size_t sheet, ur_vec2 p,
                      candidate *best)
{
    double cost = cost_at(c, i, t, sheet, p, best->cost);
    if (cost < best->cost)
        *best = (candidate){t, p, cost, sheet};
}

/*
 * Refines a candidate by steps in eight directions, halving the step when
 * none helps, down to REFINE_FINEST of the part's size.
 */
static void refine(const compactor *c, size_t i, const double *box, double size, candidate *best)
{
    static const double dx[8] = {1, -1, 0, 0, 0.7071, -0.7071, 0.7071, -0.7071};
    static const double dy[8] = {0, 0, 1, -1, 0.7071, 0.7071, -0.7071, -0.7071};
    for (double step = 0.05 * size; step > REFINE_FINEST * size && best->cost > 0;) {
        bool better = false;
        for (int k = 0; k < 8 && !better; k++) {
            double before = best->cost;
            ur_vec2 p = {best->at.x + step * dx[k], best->at.y + step * dy[k]};
            try_place(c, i, best->turn, best->sheet, clamp_to(p, box), best);
            better = best->cost < before;
        }
        if (!better)
            step *= 0.5;
    }
}

/*
 * Pushes a candidate out of the part it overlaps most (pair_cost), across
 * the nearest edge of their no-fit polygon, while that lowers its cost.
 * Refinement only comes near a contact; this reaches it exactly, as a part
 * between two others or in a notch of its own width must.
 */
static void push_out(const compactor *c, size_t i, const double *box, candidate *best)
{
    const flat_nfp *const *row = c->row + best->turn * c->count;
    for (int push = 0; push < PUSHES_OUT && best->cost > 0; push++) {
        size_t most = i;
        double most_cost = 0;
        for (size_t j = 0; j < c->count; j++) {
            double d = j == i || c->now.sheet[j] != best->sheet
                           ? 0
                           : depth_in(row[j], ur_vec2_make(best->at.x - c->now.at[j].x,
                                                           best->at.y - c->now.at[j].y));
            double cost = d > 0 ? pair_cost(c, i, j, d) : 0;
            if (cost > most_cost) {
                most_cost = cost;
                most = j;
            }
        }
        if (most == i)
            return;
        ur_vec2 from = c->now.at[most];
        ur_vec2 out = way_out(row[most], ur_vec2_make(best->at.x - from.x, best->at.y - from.y));
        ur_vec2 p = ur_vec2_make(out.x + from.x, out.y + from.y);
        if (p.x < box[0] || p.x > box[2] || p.y < box[1] || p.y > box[3])
            return;
        double before = best->cost;
        try_place(c, i, best->turn, best->sheet, p, best);
        if (best->cost >= before)
            return;
    }
}

/* Part i's size: the longer side of its box at turn 0. */
static double part_size(const compactor *c, size_t i)
{
    const nest_shape *shape = nest_shape_of(c->n, c->piece[i], 0);
    return fmax(ur_box_width(shape->box), ur_box_height(shape->box));
}

/* A sheet for a random place: the strip's, or in a sheet search any. */
static size_t random_sheet(compactor *c)
{
    if (!c->across_sheets)
        return c->strip_sheet;
    return c->sheet_count > 1 ? nest_next_random(&c->random) % c->sheet_count : 0;
}

/*
 * Moves part i to where it overlaps the others least (weighted): random
 * places across the strip (or the sheets) at random turns and near where
 * it is, the best refined.  False on a failure.
 */
static bool move_part(compactor *c, size_t i)
{
    nester *n = c->n;
    size_t turns = n->classes[n->class_of[c->piece[i]]].turn_count;
    double size = part_size(c, i);
    double box[4];
    size_t turn = c->now.turn[i], sheet = c->now.sheet[i];
    if (!fill_rows(c, i, turns))
        return false;
    /* Left outside a shorter strip, or on a sheet no longer used, it may go anywhere inside. */
    bool fits = inner_fit(c, sheet, i, turn, box);
    candidate best = {turn, c->now.at[i],
                      fits ? cost_at(c, i, turn, sheet, c->now.at[i], INFINITY) : INFINITY, sheet};
    for (int k = 0; fits && k < PLACES_NEAR; k++) {
        ur_vec2 p = {c->now.at[i].x + (2 * uniform(&c->random) - 1) * 0.25 * size,
                     c->now.at[i].y + (2 * uniform(&c->random) - 1) * 0.25 * size};
        try_place(c, i, turn, sheet, clamp_to(p, box), &best);
    }
    for (int k = 0; k < PLACES_ACROSS; k++) {
        size_t t = nest_next_random(&c->random) % turns, s = random_sheet(c);
        if (!inner_fit(c, s, i, t, box))
            continue;
        ur_vec2 p = {box[0] + uniform(&c->random) * (box[2] - box[0]),
                     box[1] + uniform(&c->random) * (box[3] - box[1])};
        try_place(c, i, t, s, p, &best);
    }
    if (!isfinite(best.cost))
        return true; /* no turn fits the strip: the caller keeps it longer */
    (void)inner_fit(c, best.sheet, i, best.turn, box); /* it fits: best was found inside it */
    refine(c, i, box, size, &best);
    push_out(c, i, box, &best);
    c->now.turn[i] = best.turn;
    c->now.at[i] = best.at;
    c->now.sheet[i] = best.sheet;
    return update_depths(c, i);
}

/*
 * Guided local search's weights: pairs that overlap weigh more, the more
 * their depth times size (pair_cost's) against the worst pair's, and the
 * others fall back toward 1.
 */
static void update_weights(compactor *c)
{
    size_t pairs = c->count * c->count;
    double worst = 0;
    for (size_t k = 0; k < pairs; k++)
        worst = fmax(worst, c->depth[k] * c->pair_scale[k]);
    for (size_t k = 0; k < pairs; k++)
        c->weight[k] = c->depth[k] > 0
                           ? c->weight[k] * (1.2 + 0.8 * c->depth[k] * c->pair_scale[k] / worst)
                           : fmax(1.0, 0.95 * c->weight[k]);
}

static void copy_state(const compactor *c, state *to, const state *from)
{
    memcpy(to->turn, from->turn, c->count * sizeof *to->turn);
    memcpy(to->at, from->at, c->count * sizeof *to->at);
    memcpy(to->sheet, from->sheet, c->count * sizeof *to->sheet);
}

static bool recompute_depths(compactor *c)
{
    for (size_t i = 0; i < c->count; i++)
        for (size_t j = i + 1; j < c->count; j++)
            if (!refresh_pair(c, i, j))
                return false;
    return true;
}

/* Shuffles the first count entries of order. */
static void shuffle(size_t *order, size_t count, uint64_t *random)
{
    for (size_t k = count; k > 1; k--) {
        size_t j = nest_next_random(random) % k, swap = order[k - 1];
        order[k - 1] = order[j];
        order[j] = swap;
    }
}

/* One round: each overlapping part, in random order, moves once; false on a failure. */
static bool move_overlapping(compactor *c)
{
    for (size_t k = 0; k < c->count; k++)
        c->order[k] = k;
    shuffle(c->order, c->count, &c->random);
    for (size_t k = 0; k < c->count; k++)
        if (overlaps_any(c, c->order[k]) && !move_part(c, c->order[k]))
            return false;
    return true;
}

/*
 * Separates the parts in the strip of c->length: rounds of moves of every
 * overlapping part, weights updated after each.  A try ends after a run of
 * rounds (patience) that did not bring the total overlap GAIN below its
 * least so far, and the next starts from the least overlapping layout; a
 * try that brought no such gain at all is a strike, and STRIKES in a row
 * end the separation.  True when no overlap is left (c->now holds that
 * layout); false when it gives up (c->now is then its least overlapping
 * layout) or time runs out, *status set on a failure.
 */
static bool separate(compactor *c, ur_status *status)
{
    atomic_fetch_add(&c->shared->separations, 1);
    size_t patience = c->count * ROUNDS_PER_PART;
    if (patience < ROUNDS_WITHOUT_GAIN)
        patience = ROUNDS_WITHOUT_GAIN;
    for (size_t k = 0; k < c->count * c->count; k++)
        c->weight[k] = 1.0;
    double least_total = total_depth(c);
    copy_state(c, &c->least, &c->now);
    for (int strikes = 0; strikes < STRIKES;) {
        double try_start = least_total;
        for (size_t idle = 0; idle < patience;) {
            *status = ur_context_check(c->n->options->context, &c->error);
            if (*status != UR_OK || nest_seconds_now() > c->deadline)
                return false;
            if (!move_overlapping(c)) {
                *status = ur_error_out_of_memory(&c->error);
                return false;
            }
            double total = total_depth(c);
            if (total == 0)
                return true;
            idle = total < least_total * (1 - GAIN) ? 0 : idle + 1;
            if (total < least_total) {
                least_total = total;
                copy_state(c, &c->least, &c->now);
            }
            update_weights(c);
        }
        strikes = least_total < try_start * (1 - GAIN) ? 0 : strikes + 1;
        copy_state(c, &c->now, &c->least);
        if (!recompute_depths(c)) {
            *status = ur_error_out_of_memory(&c->error);
            return false;
        }
    }
    return false;
}

/* How far along the strip the parts on it reach now, from the margin. */
static double reach_of(const compactor *c)
{
    double reach = 0;
    for (size_t i = 0; i < c->count; i++)
        if (c->now.sheet[i] == c->strip_sheet)
            reach = fmax(reach, c->now.at[i].x +
                                    nest_shape_of(c->n, c->piece[i], c->now.turn[i])->box.max.x);
    return reach - c->n->options->margin;
}

/*
 * The shortest strip any layout can have: the longest of the parts' least
 * lengths over their turns, and the parts' area over the strip's width
 * (a roll's or a sheet's, every part on it).
 */
static double shortest_possible(const compactor *c)
{
    const ur_nest_options *o = c->n->options;
    double area = 0, longest = 0;
    for (size_t i = 0; i < c->count; i++) {
        const nest_class *k = &c->n->classes[c->n->class_of[c->piece[i]]];
        double least = INFINITY;
        for (size_t t = 0; t < k->turn_count; t++)
            least = fmin(least, ur_box_width(k->turns[t].box));
        longest = fmax(longest, least);
        area += k->turns[0].area;
    }
    double width, height;
    nest_sheet_size(c->n, c->strip_sheet, &width, &height);
    return fmax(longest, area / (height - 2 * o->margin));
}

/*
 * The parts that no longer fit where they are (outside a shorter strip, on
 * a sheet no longer used) move to where they overlap the others least,
 * the depths and weights made afresh first.  False on a failure.
 */
static bool move_in(compactor *c)
{
    if (!recompute_depths(c))
        return false;
    for (size_t k = 0; k < c->count * c->count; k++)
        c->weight[k] = 1.0;
    for (size_t i = 0; i < c->count; i++) {
        double box[4];
        if (!fits_where_it_is(c, i, c->now.turn[i], box) && !move_part(c, i))
            return false;
    }
    return true;
}

/*
 * Cuts the strip to length: a slice as wide as the cut comes out at a
 * random place along it, the parts beyond moving back by as much, so that
 * the overlap the cut makes is spread along one line across the strip
 * rather than piled at its end; parts still outside (those the slice went
 * through) then move in, overlapping.  False on a failure.
 */
static bool cut_to(compactor *c, double length)
{
    double reach = reach_of(c);
    double slice = c->n->options->margin + uniform(&c->random) * reach;
    for (size_t i = 0; i < c->count; i++) {
        const ur_box *box = &nest_shape_of(c->n, c->piece[i], c->now.turn[i])->box;
        if (c->now.sheet[i] == c->strip_sheet &&
            c->now.at[i].x + 0.5 * (box->min.x + box->max.x) > slice)
            c->now.at[i].x -= reach - length;
    }
    c->length = length;
    for (size_t i = 0; i < c->count; i++) {
        double box[4];
        if (fits_where_it_is(c, i, c->now.turn[i], box))
            c->now.at[i] = clamp_to(c->now.at[i], box);
    }
    return move_in(c);
}

/*
 * A jolt out of a crowded layout: two parts of different shapes trade
 * places (their boxes' centres), the larger parts more often.  False on a
 * failure.
 */
static bool disrupt(compactor *c)
{
    size_t i = 0, j = 0;
    for (int tries = 0; tries < 20; tries++) {
        i = nest_next_random(&c->random) % c->count;
        j = nest_next_random(&c->random) % c->count;
        /* Of two drawn parts, the larger: a bias toward large parts. */
        size_t k = nest_next_random(&c->random) % c->count,
               l = nest_next_random(&c->random) % c->count;
        if (nest_shape_of(c->n, c->piece[k], 0)->area > nest_shape_of(c->n, c->piece[i], 0)->area)
            i = k;
        if (nest_shape_of(c->n, c->piece[l], 0)->area > nest_shape_of(c->n, c->piece[j], 0)->area)
            j = l;
        if (c->n->class_of[c->piece[i]] != c->n->class_of[c->piece[j]])
            break;
    }
    if (c->n->class_of[c->piece[i]] == c->n->class_of[c->piece[j]])
        return true; /* all one shape: nothing to trade */
    /* Where each part's box centre lies from its origin. */
    const ur_box *bi = &nest_shape_of(c->n, c->piece[i], c->now.turn[i])->box;
    const ur_box *bj = &nest_shape_of(c->n, c->piece[j], c->now.turn[j])->box;
    ur_vec2 oi = ur_vec2_make(0.5 * (bi->min.x + bi->max.x), 0.5 * (bi->min.y + bi->max.y));
    ur_vec2 oj = ur_vec2_make(0.5 * (bj->min.x + bj->max.x), 0.5 * (bj->min.y + bj->max.y));
    ur_vec2 ci = ur_vec2_add(c->now.at[i], oi), cj = ur_vec2_add(c->now.at[j], oj);
    size_t si = c->now.sheet[i], sj = c->now.sheet[j];
    double box_i[4], box_j[4];
    if (!inner_fit(c, sj, i, c->now.turn[i], box_i) || !inner_fit(c, si, j, c->now.turn[j], box_j))
        return true; /* one does not fit the other's sheet (a remnant): no trade */
    c->now.at[i] = clamp_to(ur_vec2_sub(cj, oi), box_i);
    c->now.at[j] = clamp_to(ur_vec2_sub(ci, oj), box_j);
    c->now.sheet[i] = sj;
    c->now.sheet[j] = si;
    return recompute_depths(c);
}

/*
 * Whether the layout in c->now truly has no overlap and keeps within the
 * strip: every pair's relative place checked against GEOS's own no-fit
 * polygon, not the flattened copies the search reads, so that an error in
 * those can never reach a cut file.  False on a GEOS failure too.  The
 * caller holds the shared lock (the nester's GEOS context).
 */
static bool verified(compactor *c)
{
    nester *n = c->n;
    for (size_t i = 0; i < c->count; i++) {
        double box[4];
        ur_vec2 at = c->now.at[i];
        if (!fits_where_it_is(c, i, c->now.turn[i], box) || at.x < box[0] - 1e-9 ||
            at.x > box[2] + 1e-9 || at.y < box[1] - 1e-9 || at.y > box[3] + 1e-9)
            return false;
        for (size_t j = 0; j < i; j++) {
            if (c->now.sheet[j] != c->now.sheet[i])
                continue;
            const GEOSGeometry *nfp =
                nest_nfp_of(n, c->piece[j], c->now.turn[j], c->piece[i], c->now.turn[i]);
            GEOSGeometry *point =
                GEOSGeom_createPointFromXY_r(n->geos, at.x - c->now.at[j].x, at.y - c->now.at[j].y);
            char inside = nfp && point ? GEOSContains_r(n->geos, nfp, point) : 2;
            if (point)
                GEOSGeom_destroy_r(n->geos, point);
            if (inside != 0)
                return false;
        }
    }
    return true;
}

/* Tells the caller's progress of a new best (the shared lock held). */
static void tell_progress(const compactor *c, double best)
{
    const ur_nest_options *o = c->n->options;
    if (!o->progress)
        return;
    size_t tried = atomic_load(&c->shared->separations);
    size_t sheets = c->across_sheets ? c->sheet_count - c->n->remnant_count : c->stock_sheets;
    o->progress(o->progress_context, sheets, best + o->margin, tried);
}

/*
 * A layout with no overlap in a shorter strip than this search's best:
 * its new best, once verified, and everyone's if no other search has
 * found a shorter one meanwhile.  False when it is not verified.
 */
static bool keep_best(compactor *c, double *best_length)
{
    shared_best *shared = c->shared;
    mtx_lock(&shared->lock);
    bool kept = verified(c);
    if (kept) {
        *best_length = reach_of(c);
        copy_state(c, &c->best, &c->now);
    }
    if (kept && *best_length < shared->length) {
        shared->length = *best_length;
        copy_state(c, &shared->best, &c->now);
        c->seen = atomic_fetch_add(&shared->version, 1) + 1;
        tell_progress(c, *best_length);
    }
    mtx_unlock(&shared->lock);
    return kept;
}

/* Whether another search has found a new best since this one last looked. */
static bool overtaken(const compactor *c)
{
    return atomic_load(&c->shared->version) != c->seen;
}

/*
 * Takes up the shared best when it is shorter than this search's own;
 * true when it did.
 */
static bool catch_up(compactor *c, double *best_length)
{
    if (!overtaken(c))
        return false;
    shared_best *shared = c->shared;
    mtx_lock(&shared->lock);
    c->seen = atomic_load(&shared->version);
    bool shorter = shared->length < *best_length;
    if (shorter) {
        *best_length = shared->length;
        copy_state(c, &c->best, &shared->best);
    }
    mtx_unlock(&shared->lock);
    return shorter;
}

/*
 * Keeps the layout in c->now, whose total overlap is total, among the near
 * misses if it is among the NEAR_MISSES least; the most overlapping one
 * drops out when they are full.
 */
static void keep_near_miss(compactor *c, double total)
{
    near_misses *m = &c->misses;
    size_t at = m->count;
    while (at > 0 && m->total[at - 1] > total)
        at--;
    if (at == NEAR_MISSES)
        return;
    size_t last = m->count < NEAR_MISSES ? m->count++ : NEAR_MISSES - 1;
    state spare = m->layout[last]; /* its arrays are reused for the new one */
    for (size_t k = last; k > at; k--) {
        m->layout[k] = m->layout[k - 1];
        m->total[k] = m->total[k - 1];
    }
    m->layout[at] = spare;
    m->total[at] = total;
    copy_state(c, &m->layout[at], &c->now);
}

/* One of the near misses (there is one at least), the least overlapping most often. */
static const state *pick_near_miss(compactor *c)
{
    double u = uniform(&c->random), v = uniform(&c->random);
    double spread = fabs(sqrt(-2 * log(1 - u)) * cos(2 * M_PI * v)) * NEAR_MISS_SPREAD;
    size_t k = (size_t)(fmin(spread, 0.999) * (double)c->misses.count);
    return &c->misses.layout[k < c->misses.count ? k : c->misses.count - 1];
}

/*
 * Exploration: the strip cut to length (by EXPLORE_CUT from the best), or
 * the parts put on that many sheets, and separated again and again, each time from one of the near
 * misses so far, jolted, until a layout fits, the phase's time is up or another search gets ahead.
 * False when it stops without a layout (or *status says why).
 */
static bool explore_once(compactor *c, double length, double until, size_t tries, ur_status *status)
{
    c->misses.count = 0;
    copy_state(c, &c->now, &c->best);
    if (!cut_to(c, length)) {
        *status = ur_error_out_of_memory(&c->error);
        return false;
    }
    double saved = c->deadline;
    c->deadline = until;
    bool fits = false;
    for (size_t tried = 0;
         !fits && *status == UR_OK && tried < tries && nest_seconds_now() < until && !overtaken(c);
         tried++) {
        fits = separate(c, status);
        if (!fits && *status == UR_OK) {
            keep_near_miss(c, total_depth(c)); /* separate left its least in c->now */
            copy_state(c, &c->now, pick_near_miss(c));
            if (!disrupt(c))
                *status = ur_error_out_of_memory(&c->error);
        }
    }
    c->deadline = saved;
    return fits;
}

/*
 * One search, c set up: exploration (EXPLORE_SHARE of the time), then
 * compression, which cuts the best strip by less and less (from
 * COMPRESS_FIRST to COMPRESS_LAST of its length as time runs out) and
 * separates once per cut.  Each step starts from the shortest layout any
 * search has found; the best ends in c->shared.
 */
static ur_status search_shorter(compactor *c)
{
    ur_status status = UR_OK;
    double best_length = reach_of(c), floor = shortest_possible(c);
    copy_state(c, &c->best, &c->now);
    double start = nest_seconds_now(), span = c->deadline - start;
    double until = start + EXPLORE_SHARE * span;
    while (status == UR_OK && nest_seconds_now() < until) {
        (void)catch_up(c, &best_length);
        double length = best_length * (1 - EXPLORE_CUT);
        if (length < floor)
            break;
        if (explore_once(c, length, until, SIZE_MAX, &status))
            (void)keep_best(c, &best_length); /* or, not verified, the same cut again */
    }
    double compress_start = nest_seconds_now();
    for (int failures = 0; status == UR_OK && failures < COMPRESS_PATIENCE;) {
        double now = nest_seconds_now();
        if (now > c->deadline)
            break;
        if (catch_up(c, &best_length))
            failures = 0;
        double done = (now - compress_start) / fmax(1e-9, c->deadline - compress_start);
        double cut = COMPRESS_FIRST + (COMPRESS_LAST - COMPRESS_FIRST) * done;
        double length = best_length * (1 - cut);
        if (length < floor)
            break;
        copy_state(c, &c->now, &c->best);
        if (!cut_to(c, length))
            return ur_error_out_of_memory(&c->error);
        bool fits = separate(c, &status);
        if (fits && reach_of(c) < best_length && keep_best(c, &best_length)) {
            failures = 0;
        } else {
            failures++;
        }
    }
    return status;
}

/*
 * A sheet search's cut while cuts go through: doubled after each layout
 * found at the first separation, up to FEWER_CUT_MOST, and back to
 * EXPLORE_CUT after FEWER_TRIES separations fail.  The lengthened sheet
 * has much slack at first (the first layout's, and the sheets dropped
 * end to end), which small cuts would take long to take up.
 */
#define FEWER_CUT_MOST 0.05
#define FEWER_TRIES 2

/*
 * A sheet search at one count of sheets, c set up (compactor_make): the
 * last sheet, lengthened at first by the parts of the sheets dropped, is
 * shortened as a roll is, to its own length; parts move between all the
 * sheets on the way.  It ends when the parts fit (the shared best is then
 * within sheet_length), at the deadline, or when another search has done
 * it.
 */
static ur_status search_fewer(compactor *c)
{
    ur_status status = UR_OK;
    double best_length = reach_of(c), cut = EXPLORE_CUT;
    copy_state(c, &c->best, &c->now);
    while (status == UR_OK && best_length > c->sheet_length && nest_seconds_now() < c->deadline) {
        (void)catch_up(c, &best_length);
        if (best_length <= c->sheet_length)
            break;
        double length = fmax(c->sheet_length, best_length * (1 - cut));
        size_t tries = cut > EXPLORE_CUT ? FEWER_TRIES : SIZE_MAX;
        if (!explore_once(c, length, c->deadline, tries, &status))
            cut = EXPLORE_CUT;
        else if (keep_best(c, &best_length)) /* or, not verified, the same cut again */
            cut = fmin(FEWER_CUT_MOST, 2 * cut);
    }
    return status;
}

/*
 * push_to_one_end's cuts: the first, the most and the least (a fraction
 * of the strip's length), and the separations it tries at each length.
 */
#define END_CUT_FIRST 0.01
#define END_CUT_MOST 0.04
#define END_CUT_LEAST 0.0005
#define END_TRIES 2

/*
 * A sheet's parts pushed to one end (c a strip over that sheet), so that
 * what is left at the other is one piece of stock: the strip is cut and
 * separated as a roll is, the cut doubled after each layout found and
 * halved after END_TRIES separations fail, until it falls below
 * END_CUT_LEAST.  It stops then, not only at the deadline, so that one
 * search (the caller runs one) gives the same layout every time.
 */
static ur_status push_to_one_end(compactor *c)
{
    ur_status status = UR_OK;
    double best_length = reach_of(c), floor = shortest_possible(c);
    copy_state(c, &c->best, &c->now);
    for (double cut = END_CUT_FIRST;
         status == UR_OK && cut >= END_CUT_LEAST && nest_seconds_now() < c->deadline;) {
        double length = best_length * (1 - cut);
        if (length >= floor && explore_once(c, length, c->deadline, END_TRIES, &status) &&
            keep_best(c, &best_length))
            cut = fmin(END_CUT_MOST, 2 * cut);
        else
            cut *= 0.5;
    }
    return status;
}

static void state_free(state *s)
{
    free(s->turn);
    free(s->at);
    free(s->sheet);
}

static bool state_make(state *s, size_t count)
{
    *s = (state){calloc(count, sizeof(size_t)), calloc(count, sizeof(ur_vec2)),
                 calloc(count, sizeof(size_t))};
    return s->turn && s->at && s->sheet;
}

static void compactor_free(compactor *c)
{
    size_t keys = c->n->class_count * c->n->turn_count * c->n->class_count * c->n->turn_count;
    for (size_t k = 0; c->nfps && k < keys; k++)
        flat_free(&c->nfps[k]);
    free(c->nfps);
    free(c->index);
    free(c->piece);
    state_free(&c->now);
    state_free(&c->best);
    state_free(&c->least);
    free(c->depth);
    free(c->weight);
    free(c->pair_scale);
    free(c->pair_floor);
    free(c->row);
    free(c->order);
    for (size_t k = 0; k < NEAR_MISSES; k++)
        state_free(&c->misses.layout[k]);
}

/* Each pair's size and floor for pair_cost, from the parts' areas and sizes at turn 0. */
static void size_pairs(compactor *c)
{
    for (size_t i = 0; i < c->count; i++) {
        double area_i = nest_shape_of(c->n, c->piece[i], 0)->area;
        for (size_t j = 0; j < c->count; j++) {
            double area_j = nest_shape_of(c->n, c->piece[j], 0)->area;
            c->pair_scale[i * c->count + j] = sqrt(sqrt(area_i) * sqrt(area_j));
            c->pair_floor[i * c->count + j] =
                OVERLAP_FLOOR * fmax(part_size(c, i), part_size(c, j));
        }
    }
}

/*
 * What a search works on: the parts on one sheet as a strip (sheets 0:
 * a roll, or to_one_end), or every part on the first sheets (a sheet
 * search: the parts of the others put at the end of the last).
 */
typedef struct search_kind {
    size_t sheet;  /* the strip's sheet (a sheet search: the last it keeps) */
    size_t sheets; /* a sheet search: how many sheets it keeps (remnants too); 0 otherwise */
    bool to_one_end;
} search_kind;

/* Whether the nester's placement p is one the search works on. */
static bool searched(const nester *n, const search_kind *kind, size_t p)
{
    return kind->sheets > 0 || n->sheet_of[p] == kind->sheet;
}

/* The stock sheets the nester's layout uses. */
static size_t stock_sheets_of(const nester *n)
{
    return n->sheet_count > n->remnant_count ? n->sheet_count - n->remnant_count : 0;
}

/*
 * A sheet search's first layout: the parts of each sheet past the last
 * kept go on the last, a sheet's length (and the spacing) further along
 * for each sheet past it, so that the last sheet is a strip as long as
 * all of them, to be shortened to its own length.
 */
static void lengthen_last_sheet(compactor *c)
{
    double step = c->sheet_length + c->n->options->spacing;
    for (size_t i = 0; i < c->count; i++)
        if (c->now.sheet[i] > c->strip_sheet) {
            c->now.at[i].x += step * (double)(c->now.sheet[i] - c->strip_sheet);
            c->now.sheet[i] = c->strip_sheet;
        }
}

/*
 * Sets up search number k (its own random steps) over the count parts the
 * kind says, from the nester's layout; false when out of memory.
 */
static bool compactor_make(compactor *c, nester *n, const search_kind *kind, size_t count,
                           shared_best *shared, size_t k)
{
    size_t keys = n->class_count * n->turn_count * n->class_count * n->turn_count;
    double width, height;
    nest_sheet_size(n, kind->sheet, &width, &height);
    *c = (compactor){.n = n,
                     .shared = shared,
                     .count = count,
                     .across_sheets = kind->sheets > 0,
                     .to_one_end = kind->to_one_end,
                     .strip_sheet = kind->sheet,
                     .sheet_count = kind->sheets,
                     .sheet_length = width - 2 * n->options->margin,
                     .stock_sheets = stock_sheets_of(n)};
    c->random = (n->options->seed + k) * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL;
    c->index = calloc(count, sizeof *c->index);
    c->piece = calloc(count, sizeof *c->piece);
    bool states =
        state_make(&c->now, count) && state_make(&c->best, count) && state_make(&c->least, count);
    c->depth = calloc(count * count, sizeof *c->depth);
    c->weight = calloc(count * count, sizeof *c->weight);
    c->pair_scale = calloc(count * count, sizeof *c->pair_scale);
    c->pair_floor = calloc(count * count, sizeof *c->pair_floor);
    c->row = calloc(count * n->turn_count, sizeof *c->row);
    c->nfps = calloc(keys, sizeof *c->nfps);
    c->order = calloc(count, sizeof *c->order);
    if (!c->index || !c->piece || !states || !c->depth || !c->weight || !c->pair_scale ||
        !c->pair_floor || !c->row || !c->nfps || !c->order)
        return false;
    for (size_t m = 0; m < NEAR_MISSES; m++)
        if (!state_make(&c->misses.layout[m], count))
            return false;
    for (size_t p = 0, i = 0; p < n->placed_count; p++)
        if (searched(n, kind, p)) {
            c->index[i] = p;
            c->piece[i] = n->placements[p].piece;
            c->now.turn[i] = n->placements[p].turn;
            c->now.sheet[i] = n->sheet_of[p];
            c->now.at[i++] = n->placements[p].at;
        }
    if (c->across_sheets)
        lengthen_last_sheet(c);
    c->length = reach_of(c);
    size_pairs(c);
    return true;
}

/*
 * A search in a thread of its own: the depths of its first layout, then
 * the search.  If rounding makes a pair of the first layout's parts look
 * a nanometre deep, the search clears that on the way.
 */
static int run_search(void *context)
{
    compactor *c = context;
    if (!recompute_depths(c))
        c->status = ur_error_out_of_memory(&c->error);
    else
        c->status = c->across_sheets ? search_fewer(c)
                    : c->to_one_end  ? push_to_one_end(c)
                                     : search_shorter(c);
    return 0;
}

/* Searches run side by side: options->threads, or one per processor. */
static size_t search_count(const ur_nest_options *o)
{
    if (o->threads > 0)
        return o->threads < NEST_MAX_THREADS ? o->threads : NEST_MAX_THREADS;
    long processors = sysconf(_SC_NPROCESSORS_ONLN);
    return processors < 1                  ? 1
           : processors < NEST_MAX_THREADS ? (size_t)processors
                                           : NEST_MAX_THREADS;
}

/*
 * Runs the searches (the first in this thread, the others in threads of
 * their own: fewer if a thread cannot start) and waits for them all; the
 * first failure's status, its message in the nester's error.
 */
static ur_status run_searches(compactor *searches, size_t count)
{
    thrd_t threads[NEST_MAX_THREADS];
    bool started[NEST_MAX_THREADS] = {false};
    for (size_t k = 1; k < count; k++)
        started[k] = thrd_create(&threads[k], run_search, &searches[k]) == thrd_success;
    run_search(&searches[0]);
    for (size_t k = 1; k < count; k++)
        if (started[k])
            thrd_join(threads[k], NULL);
    for (size_t k = 0; k < count; k++)
        if ((k == 0 || started[k]) && searches[k].status != UR_OK) {
            if (searches[0].n->error)
                *searches[0].n->error = searches[k].error;
            return searches[k].status;
        }
    return UR_OK;
}

/*
 * Writes the best layout back into the nester: the parts' turns and
 * places, and after a sheet search, their sheets and the sheets' count
 * and areas.
 */
static void write_back(nester *n, const compactor *c, const shared_best *shared)
{
    for (size_t i = 0; i < c->count; i++) {
        n->placements[c->index[i]].turn = shared->best.turn[i];
        n->placements[c->index[i]].at = shared->best.at[i];
        n->sheet_of[c->index[i]] = shared->best.sheet[i];
    }
    if (!c->across_sheets)
        return;
    n->sheet_count = c->sheet_count;
    memset(n->sheet_area, 0, n->sheet_slots * sizeof *n->sheet_area);
    for (size_t p = 0; p < n->placed_count; p++)
        n->sheet_area[n->sheet_of[p]] += nest_shape_of(n, n->placements[p].piece, 0)->area;
}

/*
 * Sets up and runs the searches of a kind over count parts until deadline,
 * and keeps what they found: a shorter strip, or a sheet search's layout
 * if its last sheet is no longer than itself (*done then).
 */
static ur_status run_kind(nester *n, const search_kind *kind, size_t count, double deadline,
                          bool *done)
{
    shared_best shared = {.length = 0};
    atomic_init(&shared.version, 0);
    atomic_init(&shared.separations, 0);
    bool lock_made = mtx_init(&shared.lock, mtx_plain) == thrd_success;
    size_t search_total = kind->to_one_end ? 1 : search_count(n->options), made = 0;
    compactor searches[NEST_MAX_THREADS];
    ur_status status =
        state_make(&shared.best, count) && lock_made ? UR_OK : ur_error_out_of_memory(n->error);
    for (; status == UR_OK && made < search_total; made++)
        if (!compactor_make(&searches[made], n, kind, count, &shared, made)) {
            status = ur_error_out_of_memory(n->error);
            made++; /* freed below */
            break;
        }
    if (status == UR_OK) {
        /* The first layout is everyone's best until a better one is separated and verified. */
        shared.length = reach_of(&searches[0]);
        copy_state(&searches[0], &shared.best, &searches[0].now);
        for (size_t k = 0; k < made; k++)
            searches[k].deadline = deadline;
        status = run_searches(searches, made);
    }
    *done = status == UR_OK && (kind->sheets == 0 || shared.length <= searches[0].sheet_length);
    if (*done)
        write_back(n, &searches[0], &shared);
    for (size_t k = 0; k < made; k++)
        compactor_free(&searches[k]);
    if (lock_made)
        mtx_destroy(&shared.lock);
    state_free(&shared.best);
    return status;
}

/* Runs a strip search over the parts on sheet: the roll's, or one end's (to_one_end). */
static ur_status compact_strip(nester *n, size_t sheet, bool to_one_end, double deadline)
{
    size_t count = 0;
    for (size_t k = 0; k < n->placed_count; k++)
        count += n->sheet_of[k] == sheet;
    if (count < 2 || nest_seconds_now() > deadline)
        return UR_OK;
    search_kind kind = {.sheet = sheet, .to_one_end = to_one_end};
    bool done;
    return run_kind(n, &kind, count, deadline, &done);
}

ur_status nest_compact_roll(nester *n, double deadline)
{
    return compact_strip(n, n->remnant_count, false, deadline);
}

ur_status nest_push_to_one_end(nester *n, size_t sheet, double deadline)
{
    return compact_strip(n, sheet, true, deadline);
}

ur_status nest_fewer_sheets(nester *n, size_t least, double deadline)
{
    size_t stock = stock_sheets_of(n);
    least = least > 1 ? least : 1;
    if (n->placed_count < 2 || stock <= least)
        return UR_OK;
    double start = nest_seconds_now(), share = (deadline - start) / (double)(stock - least);
    bool done = false;
    ur_status status = UR_OK;
    for (size_t k = least; status == UR_OK && !done && k < stock; k++) {
        double until = start + share * (double)(k - least + 1);
        if (nest_seconds_now() >= until)
            continue;
        search_kind kind = {.sheet = n->remnant_count + k - 1, .sheets = n->remnant_count + k};
        status = run_kind(n, &kind, n->placed_count, until, &done);
    }
    return status;
}
