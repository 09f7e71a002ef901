/*
 * nest_internal.h: what the placement files share (layout.c: shelves,
 * nfp.c: no-fit polygons, nest.c: true-shape nesting, compact.c:
 * shortening a roll).
 */
#ifndef UNROLL_NEST_INTERNAL_H
#define UNROLL_NEST_INTERNAL_H

#include <geos_c.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "unroll/nest.h"

/*
 * How far two parts may overlap and still count as touching (mm): each
 * part's convex parts are shrunk by half as much before their no-fit
 * polygons are made, so that an exact fit (a tile in a row of tiles, a part
 * in a notch of its own width) is a place of that width, not a point or a
 * line that the union of the sums would close.
 */
#define NEST_EXACT_FIT 1e-6

/*
 * The search after the first layout stops after NEST_PATIENCE tries without
 * a new best (NEST_PATIENCE_PER_SECOND per second of budget when that is
 * more) or after NEST_TRIES tries (ur_nest_options.time_budget).
 */
enum { NEST_PATIENCE = 40, NEST_PATIENCE_PER_SECOND = 20, NEST_TRIES = 100000 };
enum { NEST_MAX_THREADS = UR_NEST_MAX_THREADS };

/* The angle that turns the piece's smallest enclosing rectangle level (layout.c). */
double nest_level_angle(GEOSContextHandle_t geos, const ur_path *outline);

/* A convex polygon's vertices, counter-clockwise from its leftmost, then lowest (geom_convex_hull).
 */
typedef struct nest_hull {
    ur_vec2 *points; /* owned */
    size_t count;    /* 0: the part has no vertices */
} nest_hull;

/*
 * A piece as nesting sees it, turned by one of its allowed angles about its
 * own origin: its polygon (outline and, with holes, its holes) grown by
 * half the spacing and by the simplification's tolerance, the convex parts
 * that polygon splits into (each shrunk by half NEST_EXACT_FIT), and the
 * box of the actual (ungrown) outline.  The parts' hulls, and those of
 * the parts turned half round, are what the no-fit polygons are summed
 * from: made once with the shape, not once per pair.
 */
typedef struct nest_shape {
    GEOSGeometry *polygon;
    GEOSGeometry **convex; /* owned parts */
    size_t convex_count;
    nest_hull *hulls, *negated; /* per convex part */
    ur_box box;                 /* of the turned outline itself */
    ur_box reach;               /* of polygon: the outline grown, as its no-fit polygons see it */
    double angle;
    double area;               /* of the piece itself (outline less holes) */
    double tolerance, closing; /* of its simplification, decided unturned */
} nest_shape;

/*
 * The shape of piece at angle.  like, when not NULL, is another turn of
 * the same piece, whose simplification this one takes instead of deciding
 * it again.
 */
ur_status nest_shape_make(GEOSContextHandle_t geos, const ur_piece *piece, double angle,
                          double grow, bool holes, const nest_shape *like, nest_shape *shape,
                          ur_error *error);
void nest_shape_free(GEOSContextHandle_t geos, nest_shape *shape);

/*
 * The box of a geometry (x0, y0, x1, y1); false when GEOS gives none (an
 * empty one), box then not all set.
 */
bool nest_box_of(GEOSContextHandle_t geos, const GEOSGeometry *g, double *box);

/* Turns (x, y) about the origin by the angle whose cosine and sine are cosine_sine[0, 1]; GEOS's
 * transform callback. */
int nest_turn_xy(double *x, double *y, void *cosine_sine);

/*
 * Convex polygons, counter-clockwise, each with its area and box: the sums
 * of a pair's convex parts, kept as plain points.  A pair's sums are many
 * (a hundred for two small nets with tabs) and most never meet a room
 * that is still free; as GEOS polygons, making, shifting and freeing them
 * took half the time of nesting 313 small nets on one large sheet.  GEOS
 * sees a sum only when it may cut a room (room.c).
 */
typedef struct nest_sum_list {
    size_t count;
    size_t *first;   /* sum k: points[first[k]] to points[first[k + 1] - 1]; count + 1 */
    ur_vec2 *points; /* first[count] of them */
    double *area;
    ur_box *box;
} nest_sum_list;

void nest_sum_list_free(nest_sum_list *sums);

/* Sum k, moved by at, as a GEOS polygon; NULL on failure. */
GEOSGeometry *nest_sum_polygon(GEOSContextHandle_t geos, const nest_sum_list *sums, size_t k,
                               ur_vec2 at);

/*
 * The no-fit polygon of moving shape b around fixed shape a, both at their
 * origins, where b's origin may not go (a + (-b)), as the sums of their
 * convex parts, largest first: they overlap, so together they are no
 * valid polygon.  NULL when memory runs out (then *out_of_memory is set).
 */
nest_sum_list *nest_sums(const nest_shape *a, const nest_shape *b, bool *out_of_memory);

/* The sums turned about the origin by the angle of cosine and sine cs; NULL without memory. */
nest_sum_list *nest_sums_turned(const nest_sum_list *sums, const double cs[2]);

/* The no-fit polygon itself, the union of the sums; NULL when GEOS fails. */
GEOSGeometry *nest_union_of_sums(GEOSContextHandle_t geos, const nest_sum_list *sums);

/* ---- The true-shape nester's state (nest.c), shared with compact.c ---- */

/*
 * What is kept of a pair (shape a at turn ta, shape b at turn tb), under
 * its key (nest_pair_key): the sums of their convex parts and their no-fit
 * polygon (both NULL until made; the sums may be dropped again), and when
 * the pair was first met (room.c, by_union; 0 never).
 */
typedef struct pair_entry {
    size_t key;
    nest_sum_list *sums;
    GEOSGeometry *nfp;
    size_t met;
} pair_entry;

/* The pairs met, by key (pair_table.c). */
typedef struct pair_table {
    pair_entry *slots;
    size_t count, capacity;
} pair_table;

/* The pair's entry, or NULL when it has none. */
pair_entry *pair_table_find(const pair_table *table, size_t key);

/*
 * The pair's entry, made empty when it had none; NULL when memory runs
 * out.  Entries move when the table grows: an entry is good until the
 * next call.
 */
pair_entry *pair_table_add(pair_table *table, size_t key);

/* Frees the table and the geometries it holds. */
void pair_table_free(GEOSContextHandle_t geos, pair_table *table);

/* Parts that are the same shape (copies) share their no-fit polygons. */
typedef struct nest_class {
    size_t representative; /* a piece of this shape */
    nest_shape *turns;     /* one per allowed turn */
    size_t turn_count;     /* its own: at most the nester's turn_count */
} nest_class;

/*
 * Where one part (a class at one turn) may still go on one sheet: the
 * inner-fit rectangle cut into a grid of cells, each less the no-fit
 * polygons of the parts placed so far that reach into it.  A part placed
 * touches only the few cells its no-fit polygon reaches, so each cut is an
 * overlay of a cell's worth of edges, not of the whole sheet's, and cells
 * are brought up to date only when a query reaches them: the leftmost
 * place is in the first column that has room, and the columns after it
 * wait.
 */
typedef struct room_grid {
    GEOSGeometry **free;   /* per cell (column by column): the room left; NULL once none */
    size_t *applied;       /* per cell: placements already cut out of it */
    size_t *cut_by;        /* per cell: 1 + the last placement whose no-fit polygon cut it, or 0 */
    size_t cols, rows;     /* 0 until made */
    double x0, y0, x1, y1; /* the inner-fit rectangle the cells cover */
} room_grid;

typedef struct placed {
    size_t piece, turn;
    ur_vec2 at; /* where its origin went */
} placed;

/* The placements (their numbers, in order placed) whose reach meets one bucket of a sheet. */
typedef struct index_bucket {
    size_t *items;
    size_t count, room;
} index_bucket;

/*
 * A sheet's raster (sheet_raster.c): per pixel, row by row, the distance
 * (mm) from its centre to the nearest centre that lies inside a placed
 * part; made for the sheet's version, again when that changes.
 */
typedef struct sheet_raster {
    float *distance; /* NULL until made */
    size_t columns, rows;
    double pixel; /* its side (mm) */
    size_t version;
    size_t placed; /* the nester's placed_count when it was last brought up to date */
} sheet_raster;

/* The most discs sheet_raster.c keeps of a shape besides its largest. */
enum { RASTER_MORE_DISCS = 48 };

/*
 * What sheet_raster.c keeps per shape at a turn: its polygon less a thin
 * band (what blocks pixels), the largest disc it holds (centre, radius),
 * and more discs it holds elsewhere (more_centres, more_radii).
 */
typedef struct raster_shape {
    GEOSGeometry *core; /* NULL when it could not be made */
    ur_vec2 centre;
    double radius; /* 0 when none was found */
    ur_vec2 more_centres[RASTER_MORE_DISCS];
    double more_radii[RASTER_MORE_DISCS];
    size_t more_count;
    bool made;
} raster_shape;

/*
 * What the nester keeps per sheet, made when the sheet is first looked
 * at: the rooms of the shapes at their turns, and the placements on it
 * in a grid of buckets by the box they reach (placed_index.c), so that
 * bringing a cell of a room up to date looks only at the placements near
 * it, not at every one on every sheet.  Kept per sheet rather than per
 * (sheet, class, turn) in one table, whose size grew with the square of
 * the parts: 1,616 parts of an unfolded mesh, near 600 MB.
 */
typedef struct sheet_state {
    room_grid *rooms; /* per (class, turn); NULL until the sheet is looked at */
    /*
     * Per (class, turn): no room was left for it there.  Sheets only fill
     * up during a run, so it never fits there again in that run.
     */
    bool *full;
    index_bucket *buckets; /* column by column from the sheet's corner; NULL until placed on */
    size_t columns, rows;
    size_t version;      /* changes with every placement made on it or forgotten */
    sheet_raster raster; /* made when first asked for */
} sheet_state;

typedef struct nester {
    GEOSContextHandle_t geos;
    const ur_piece *pieces;
    size_t count;
    const ur_nest_options *options;
    size_t turn_count;
    size_t *class_of; /* per piece */
    nest_class *classes;
    size_t class_count;
    pair_table pairs;   /* per (class a, turn a, class b, turn b) met: sums, no-fit polygon */
    size_t sums_points; /* the points the sums made hold (nest.c, keep_sums_small) */
    bool sums_held;     /* sums given out are in use: none is dropped (nest_hold_sums) */
    size_t runs;        /* runs over an order so far */
    placed *placements; /* per piece, in order placed */
    size_t *sheet_of;   /* per placement */
    /*
     * Sheets 0 to remnant_count - 1 are the remnants, open from the start
     * (maybe empty); stock sheets follow as they are opened.
     */
    size_t placed_count, sheet_count, remnant_count;
    size_t sheet_slots;  /* sheets there can be: remnants, one per part and one more */
    sheet_state *sheets; /* per sheet slot */
    double cell_size;    /* of the rooms' cells and the index's buckets: about two parts (mm) */
    size_t *near;        /* the placements an index query found (placed_index.c) */
    raster_shape *raster_shapes; /* per (class, turn); NULL: no raster tests (sheet_raster.c) */
    size_t near_room;
    /*
     * The last run over an order, for the next to start where the two
     * orders part: per position, the piece placed, the turn it was held at
     * (or ANY_TURN) and the placements made before it (and after the
     * last, at position count); run_length positions hold.
     */
    size_t *run_piece, *run_held, *run_placed;
    size_t run_length;
    double *sheet_area; /* per sheet: area of the parts on it */
    /*
     * Per class: its parts not placed yet in the first layout.  A class
     * with none left has its rooms freed (room.c) when no search follows
     * the first layout: with a budget of 0, or once the first layout has
     * taken longer than the budget (nest.c then starts none).
     */
    size_t *class_left;
    bool first_run;     /* the first layout is being made: options->placing hears of it */
    double first_start; /* when the first layout began (nest_seconds_now) */
    /*
     * Memory ran out making a no-fit polygon or a room: a place not found
     * then says nothing of the part, and placing stops (UR_ERROR_MEMORY).
     */
    bool out_of_memory;
    ur_error *error;
} nester;

/* The shape of piece at one of its turns. */
const nest_shape *nest_shape_of(const nester *n, size_t piece, size_t turn);

/*
 * The no-fit polygon of piece b at turn tb around piece a at turn ta, a's
 * origin at the origin: where b's origin may not go.  Owned by the nester;
 * NULL when GEOS fails.  nest_sums_of gives it as its convex sums
 * (nest_sums), which is all that placing on sheets needs: a place is
 * free when it lies in none of them, and the union is the costly part.
 */
const GEOSGeometry *nest_nfp_of(nester *n, size_t a, size_t ta, size_t b, size_t tb);
const nest_sum_list *nest_sums_of(nester *n, size_t a, size_t ta, size_t b, size_t tb);

/*
 * The head of what is sorted largest first (nfp.c sorts a pair's convex
 * sums so, room.c the polygons it cuts out of a cell): an area and the
 * place before sorting, which settles ties so that the order is the same
 * on every machine.
 */
typedef struct nest_sized {
    double area;
    size_t index;
} nest_sized;

/* qsort's comparison for elements that begin with a nest_sized: larger area first. */
int nest_larger_first(const void *a, const void *b);

/*
 * While held, the sums nest_sums_of gave stay (the cache may grow past its
 * bound); let go, the cache is brought within it again.
 */
void nest_hold_sums(nester *n, bool hold);

/*
 * A lower bound on the bins of the capacity given that items of the sizes
 * given need (Martello and Toth's L2; order_search.c).
 */
size_t nest_bins_bound(double (*size)(const void *items, size_t k), const void *items, size_t count,
                       double capacity);

/* The size of one of the nester's sheets: a remnant's, or the stock's. */
void nest_sheet_size(const nester *n, size_t sheet, double *width, double *height);

/* The key of the pair (piece a at turn ta, piece b at turn tb) in the nester's caches. */
size_t nest_pair_key(const nester *n, size_t a, size_t ta, size_t b, size_t tb);

/* ---- The placements on a sheet by where they reach (placed_index.c) ------ */

/*
 * Indexes placement k (the last made) on its sheet; false when memory
 * runs out (then n->out_of_memory is set).
 */
bool nest_index_add(nester *n, size_t k);

/* Forgets the placements from kept on, as rewinding a run does. */
void nest_index_rewind(nester *n, size_t kept);

/*
 * The placements from `from` on, on sheet, whose reach box (as indexed,
 * widened by its share of the slack) may meet box (x0, y0, x1, y1): in
 * n->near, in the order placed, *count of them; a superset of those that
 * do.  False when memory runs out.
 */
bool nest_index_near(nester *n, size_t sheet, const double *box, size_t from, size_t *count);

/* Frees a sheet's index (the sheet_state itself is the nester's). */
void nest_index_free(sheet_state *sheet);

/* How much one shape's reach box is widened by in the no-fit box tests (mm). */
double nest_reach_slack(const nest_shape *shape);

/* ---- Places ruled out by a raster of each sheet (sheet_raster.c) -------- */

/* What a sheet's raster shows of a region of a part's origins. */
typedef enum raster_verdict {
    RASTER_UNKNOWN,  /* nothing: no raster, or the region reaches past it */
    RASTER_NONE,     /* no place there */
    RASTER_NARROWED, /* the places there, if any, lie in the narrowed box */
} raster_verdict;

/*
 * What sheet's raster shows of the origins of piece at turn in box (x0,
 * y0, x1, y1): none is a place, or those that may be lie in narrowed
 * (when not NULL; within box).  RASTER_UNKNOWN when it cannot tell.
 */
raster_verdict nest_raster_room(nester *n, size_t sheet, size_t piece, size_t turn,
                                const double *box, double *narrowed);

/* Frees the rasters and the shapes' cores. */
void nest_raster_free(nester *n);

/* ---- Placing a part (room.c) ---------------------------------------------- */

/* A piece the search leaves free to take its best turn (see nest_place_piece). */
#define ANY_TURN SIZE_MAX

/* The rectangle where the shape's origin may go on the empty sheet; false when it does not fit. */
bool nest_inner_fit_box(const nester *n, size_t sheet, const nest_shape *shape, double *box);

/* A GEOS rectangle; NULL on a failure. */
GEOSGeometry *nest_rectangle_polygon(GEOSContextHandle_t geos, double x0, double y0, double x1,
                                     double y1);

/* Frees a room grid's cells (the grid itself is the nester's). */
void nest_grid_free(GEOSContextHandle_t geos, room_grid *grid);

/* The box of cell c of a room grid. */
void nest_cell_box(const nester *n, const room_grid *grid, size_t c, double *box);

/* How long the roll is with the parts placed so far (margins included). */
double nest_roll_length(const nester *n);

/*
 * Places piece at its best turn and place on the sheets open or a new one
 * (held: the turn the search holds it at, or ANY_TURN for any).
 */
ur_status nest_place_piece(nester *n, size_t piece, size_t held);

/* ---- The search over orders, and fewer sheets (order_search.c) ---------- */

/* Places the pieces in order (held: per piece, a turn to hold or not) after the kept prefix. */
ur_status nest_run_order(nester *n, const size_t *order, const size_t *held);

/* The search over orders and turns for budget seconds, from order (the best is left in it). */
ur_status nest_search_orders(nester *n, size_t *order, double budget);

/*
 * After the search, on sheets: the layout on fewer stock sheets, tried
 * until fewer_until, then the last sheet's parts pushed to its left end
 * until deadline.
 */
ur_status nest_sheets_search(nester *n, double fewer_until, double deadline);

/* The offcut the layout's last stock sheet leaves, into the layout. */
void nest_measure_offcut(const nester *n, ur_layout *layout);

/*
 * Shortens the roll in a roll layout (compact.c): the parts on it are moved
 * and turned, overlapping on the way, until they fit a shorter strip with
 * no overlap, until deadline (nest_seconds_now's clock) or for want of
 * progress.
 */
ur_status nest_compact_roll(nester *n, double deadline);

/*
 * Puts the parts of a sheet layout (every part placed) on fewer stock
 * sheets by the same search (compact.c): to keep the remnants and the
 * first least stock sheets, the parts of the sheets after them go at the
 * end of the last kept, as if it were a roll that long, and that strip
 * is shortened to the sheet's own length, parts moving between all the
 * sheets kept on the way; if that fails within its share of the time (an
 * equal one per count up to deadline), one stock sheet more, up to one
 * less than the layout has.  The stock sheets dropped are the last:
 * number the fullest first.  A layout kept has no overlap (checked by
 * GEOS); the nester's rooms no longer hold after it, only its
 * placements, sheets and their areas.
 */
ur_status nest_fewer_sheets(nester *n, size_t least, double deadline);

/*
 * Pushes the parts on one sheet toward its left edge by the roll's search
 * (compact.c), so that the sheet's right end is left whole: one search,
 * which stops when its cuts are tried or at deadline.
 */
ur_status nest_push_to_one_end(nester *n, size_t sheet, double deadline);

/* The next number of an xorshift64* sequence (state: not 0). */
uint64_t nest_next_random(uint64_t *state);

/* A monotonic clock, in seconds. */
double nest_seconds_now(void);

/*
 * Whether a search is to follow the first layout, asked at time now: a
 * budget, and the first layout not longer than it (nest.c starts no search
 * after a longer one).
 */
static inline bool nest_search_follows(const nester *n, double now)
{
    double budget = n->options->time_budget;
    return budget > 0 && now - n->first_start <= budget;
}

#endif
