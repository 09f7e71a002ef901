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
 * per sheet and shape in a grid of cells (room_grid, room.c), so that placing a part cuts only the
 * cells its no-fit polygon reaches.  A search over orders and turns follows (order_search.c); on a
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
#include <threads.h>
#include <time.h>

/*
 * The budget's shares: the search over orders has the first fifth; on
 * sheets the search for fewer sheets goes on to four fifths (or until it
 * reaches the bound), then the last sheet's parts are pushed to one end.
 */
#define ORDER_SHARE 0.2
#define FEWER_SHEETS_SHARE 0.8

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

/* Whether the outline, turned by angle, fits inside the sheet's margin. */
static bool fits_sheet_at(const nester *n, const ur_path *outline, double angle)
{
    ur_transform2 turn = ur_transform2_make(angle, ur_vec2_make(0, 0));
    ur_box box = ur_box_empty();
    for (size_t i = 0; i < outline->count; i++)
        ur_box_add(&box, ur_transform2_apply(turn, outline->points[i]));
    return ur_box_width(box) <= n->options->sheet_width - 2 * n->options->margin &&
           ur_box_height(box) <= n->options->sheet_height - 2 * n->options->margin;
}

/*
 * The turn a piece's turns start from: the level one, unless the sheet
 * takes it neither level nor a quarter turn from level but does at a turn
 * between (a long net with wings at both ends, diagonally): then that turn,
 * its longer extent along the sheet's longer side.  On a roll the level one.
 */
static ur_status start_angle(const nester *n, GEOSContextHandle_t geos, const ur_piece *p,
                             double *angle, ur_error *error)
{
    const ur_path *outline = &p->paths[0];
    *angle = nest_level_angle(geos, outline);
    if (n->options->roll_width > 0 || fits_sheet_at(n, outline, *angle) ||
        fits_sheet_at(n, outline, *angle + M_PI / 2))
        return UR_OK;
    double width = n->options->sheet_width - 2 * n->options->margin;
    double height = n->options->sheet_height - 2 * n->options->margin;
    bool fits;
    double turn;
    ur_status status =
        ur_outline_fit_turn(outline->points, outline->count, width, height, &fits, &turn, error);
    if (status == UR_OK && fits)
        *angle = width >= height ? turn : turn + M_PI / 2;
    return status;
}

/* A class for the piece, its shapes not made yet. */
static ur_status add_class(nester *n, size_t piece)
{
    nest_class *c = &n->classes[n->class_count];
    c->representative = piece;
    c->turn_count = turns_of(n->options, &n->pieces[piece]);
    c->turns = calloc(c->turn_count, sizeof *c->turns);
    if (!c->turns)
        return ur_error_out_of_memory(n->error);
    n->class_count++;
    return UR_OK;
}

/* The shapes of class c at its turns, made with GEOS context geos. */
static ur_status make_shapes(const nester *n, nest_class *c, GEOSContextHandle_t geos,
                             ur_error *error)
{
    const ur_piece *p = &n->pieces[c->representative];
    double base = 0.0;
    if (n->options->level) {
        ur_status status = start_angle(n, geos, p, &base, error);
        if (status != UR_OK)
            return status;
    }
    bool grain = n->options->grain && p->has_rulings;
    for (size_t t = 0; t < c->turn_count; t++) {
        double angle = base + 2 * M_PI * (double)t / (double)c->turn_count;
        if (grain) /* the rulings at the grain's angle, end for end, then either way off it */
            angle = grain_turn(n->options, p->ruling_angle, t);
        ur_status status =
            nest_shape_make(geos, p, angle, n->options->spacing / 2, n->options->holes,
                            t > 0 ? &c->turns[0] : NULL, &c->turns[t], error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/*
 * The classes' shapes are made side by side, each class's in one of
 * SHAPE_THREADS threads taking every SHAPE_THREADS-th class, each with a
 * GEOS context of its own (GEOS makes every context's geometries with
 * one factory, so that the nester's context may use them after).  A
 * papercraft sphere's six nets took half the time its nesting took to
 * shape.  Which thread makes a class does not change its shape.
 */
enum { SHAPE_THREADS = 2 };

typedef struct shape_worker {
    const nester *n;
    size_t first; /* makes classes first, first + SHAPE_THREADS, ... */
    ur_status status;
    ur_error error;
} shape_worker;

static int make_every_other(void *data)
{
    shape_worker *w = data;
    GEOSContextHandle_t geos = GEOS_init_r();
    w->status = geos ? UR_OK : ur_error_set(&w->error, UR_ERROR_INTERNAL, "GEOS could not start");
    for (size_t c = w->first; w->status == UR_OK && c < w->n->class_count; c += SHAPE_THREADS)
        w->status = make_shapes(w->n, &w->n->classes[c], geos, &w->error);
    if (geos)
        GEOS_finish_r(geos);
    return 0;
}

/* Every class's shapes; the first failure's error, if any. */
static ur_status make_all_shapes(nester *n)
{
    shape_worker workers[SHAPE_THREADS];
    thrd_t threads[SHAPE_THREADS];
    bool started[SHAPE_THREADS] = {false};
    for (size_t k = 0; k < SHAPE_THREADS; k++)
        workers[k] = (shape_worker){.n = n, .first = k, .status = UR_OK};
    for (size_t k = 1; k < SHAPE_THREADS && k < n->class_count; k++)
        started[k] = thrd_create(&threads[k], make_every_other, &workers[k]) == thrd_success;
    make_every_other(&workers[0]);
    for (size_t k = 1; k < SHAPE_THREADS; k++) {
        if (started[k])
            thrd_join(threads[k], NULL);
        else if (k < n->class_count) /* no thread: made here, in turn */
            make_every_other(&workers[k]);
    }
    for (size_t k = 0; k < SHAPE_THREADS; k++)
        if (workers[k].status != UR_OK) {
            *n->error = workers[k].error;
            return workers[k].status;
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
            ur_status status = add_class(n, p);
            if (status != UR_OK)
                return status;
        }
        n->class_of[p] = c;
    }
    return make_all_shapes(n);
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

size_t nest_pair_key(const nester *n, size_t a, size_t ta, size_t b, size_t tb)
{
    size_t ca = n->class_of[a], cb = n->class_of[b], t = n->turn_count;
    return ((ca * t + ta) * n->class_count + cb) * t + tb;
}

/*
 * The most points the cached convex sums may hold together (64 MB).  Each
 * pair of detailed nets has up to a thousand sums: the 127 nets of
 * Blender's subdivided monkey head made 27,000 of them with 35 million
 * points in one first-fit layout.  A first-fit layout uses a pair's sums
 * only while it places the second part, and the search over orders their
 * unions, which are kept.
 */
#define NEST_SUMS_POINTS 4000000

/* Drops every pair's sums but those of keep (a key, or SIZE_MAX for none). */
static void drop_sums(nester *n, size_t keep)
{
    for (size_t s = 0; s < n->pairs.capacity; s++) {
        pair_entry *entry = &n->pairs.slots[s];
        if (entry->key != keep && entry->sums) {
            nest_sum_list_free(entry->sums);
            entry->sums = NULL;
        }
    }
}

/*
 * Counts the points of the sums just made for key; past NEST_SUMS_POINTS
 * every other pair's sums are dropped, to be made again (the same) if
 * asked for, unless the sums are held.
 */
static void keep_sums_small(nester *n, size_t key, const nest_sum_list *sums)
{
    size_t count = sums->first[sums->count];
    if (!n->sums_held && n->sums_points + count > NEST_SUMS_POINTS) {
        drop_sums(n, key);
        n->sums_points = 0;
    }
    n->sums_points += count;
}

void nest_hold_sums(nester *n, bool hold)
{
    n->sums_held = hold;
    if (!hold && n->sums_points > NEST_SUMS_POINTS) {
        drop_sums(n, SIZE_MAX);
        n->sums_points = 0;
    }
}

/*
 * The entry of the pair's key, for something just made (taken over, or
 * freed with free_made when there is no memory for the entry); NULL then.
 * Looked up again after making: making the pair may have added others,
 * and moved this one.
 */
static pair_entry *entry_for(nester *n, size_t key, void *made, void (*free_made)(nester *, void *))
{
    pair_entry *entry = made ? pair_table_add(&n->pairs, key) : NULL;
    if (!entry && made) {
        free_made(n, made);
        n->out_of_memory = true;
    }
    return entry;
}

static void free_sums(nester *n, void *sums)
{
    (void)n;
    nest_sum_list_free(sums);
}

static void free_geometry(nester *n, void *geometry)
{
    GEOSGeom_destroy_r(n->geos, geometry);
}

const nest_sum_list *nest_sums_of(nester *n, size_t a, size_t ta, size_t b, size_t tb)
{
    size_t key = nest_pair_key(n, a, ta, b, tb), first;
    pair_entry *entry = pair_table_find(&n->pairs, key);
    if (entry && entry->sums)
        return entry->sums;
    double cs[2];
    nest_sum_list *made;
    if (turned_pair(n, a, ta, b, tb, &first, cs)) {
        const nest_sum_list *base = nest_sums_of(n, a, 0, b, first);
        made = base ? nest_sums_turned(base, cs) : NULL;
        n->out_of_memory = n->out_of_memory || (base && !made);
    } else {
        made = nest_sums(nest_shape_of(n, a, ta), nest_shape_of(n, b, tb), &n->out_of_memory);
    }
    entry = entry_for(n, key, made, free_sums);
    if (!entry)
        return NULL;
    entry->sums = made;
    keep_sums_small(n, key, made);
    return made;
}

const GEOSGeometry *nest_nfp_of(nester *n, size_t a, size_t ta, size_t b, size_t tb)
{
    size_t key = nest_pair_key(n, a, ta, b, tb), first;
    pair_entry *entry = pair_table_find(&n->pairs, key);
    if (entry && entry->nfp)
        return entry->nfp;
    double cs[2];
    GEOSGeometry *made;
    if (turned_pair(n, a, ta, b, tb, &first, cs)) {
        const GEOSGeometry *base = nest_nfp_of(n, a, 0, b, first);
        made = base ? GEOSGeom_transformXY_r(n->geos, base, nest_turn_xy, cs) : NULL;
    } else {
        const nest_sum_list *sums = nest_sums_of(n, a, ta, b, tb);
        made = sums ? nest_union_of_sums(n->geos, sums) : NULL;
    }
    entry = entry_for(n, key, made, free_geometry);
    if (!entry)
        return NULL;
    entry->nfp = made;
    return made;
}

void nest_sheet_size(const nester *n, size_t sheet, double *width, double *height)
{
    const ur_nest_options *o = n->options;
    bool remnant = sheet < n->remnant_count;
    *width = remnant ? o->remnants[sheet].width : o->sheet_width;
    *height = remnant ? o->remnants[sheet].height : o->sheet_height;
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
    nest_raster_free(n); /* before the sheets that hold the rasters */
    size_t slots = n->class_count * n->turn_count;
    for (size_t s = 0; n->sheets && s < n->sheet_slots; s++) {
        for (size_t k = 0; n->sheets[s].rooms && k < slots; k++)
            nest_grid_free(n->geos, &n->sheets[s].rooms[k]);
        free(n->sheets[s].rooms);
        free(n->sheets[s].full);
        nest_index_free(&n->sheets[s]);
    }
    free(n->sheets);
    free(n->near);
    free(n->run_piece);
    free(n->run_held);
    free(n->run_placed);
    free(n->sheet_area);
    free(n->class_left);
    pair_table_free(n->geos, &n->pairs);
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
 * The size of the rooms' cells: the mean part's larger side, so that a
 * no-fit polygon (about two parts across) reaches a few cells and a cell
 * holds a few parts' edges.  Twice that cost more: each placement of a
 * part unlike any before it cuts its rooms anew, and a larger cell's
 * room has more to be cut out of it, each cut costing more the more it
 * holds (313 small nets on a 2 x 2 m sheet: 44 s, 29 s so; bench_nest's
 * 500 stars 2.9 s, 2.6 s).  At most a third of the sheet's shorter side:
 * parts nearly as large as the sheet (a papercraft net's) would otherwise
 * make the whole sheet one cell, whose room grows more complex with each
 * part cut out of it, and each cut costs more the more it holds (a 2,208
 * triangle sphere's 15 nets: 9.7 s of CPU, 5.5 s with this cap).  A sixth
 * saved that sphere's 13 nets a few per cent but cost test_nest's large
 * parts a third more.
 */
static double cell_size_of(const ur_nest_options *options, const ur_piece *pieces, size_t count)
{
    double sum = 0;
    for (size_t k = 0; k < count; k++)
        sum += fmax(ur_box_width(pieces[k].box), ur_box_height(pieces[k].box)) + options->spacing;
    double size = count ? sum / (double)count : 0;
    double most = fmin(options->sheet_width, options->sheet_height) / 3;
    if (most > 0 && size > most)
        size = most;
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
    return nest_roll_length(n) + n->options->margin;
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
    n.cell_size = cell_size_of(options, pieces, count);
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
    if (status == UR_OK) {
        n.sheets = calloc(n.sheet_slots, sizeof *n.sheets);
        n.raster_shapes = calloc(n.class_count * n.turn_count + 1, sizeof *n.raster_shapes);
        n.sheet_area = calloc(n.sheet_slots, sizeof *n.sheet_area);
        n.run_piece = calloc(count + 1, sizeof *n.run_piece);
        n.run_held = calloc(count + 1, sizeof *n.run_held);
        n.run_placed = calloc(count + 1, sizeof *n.run_placed);
        if (!n.sheets || !n.raster_shapes || !n.sheet_area || !n.run_piece || !n.run_held ||
            !n.run_placed)
            status = ur_error_out_of_memory(error);
    }
    if (status == UR_OK) {
        n.class_left = calloc(n.class_count + 1, sizeof *n.class_left);
        if (!n.class_left)
            status = ur_error_out_of_memory(error);
        for (size_t p = 0; status == UR_OK && p < count; p++)
            n.class_left[n.class_of[p]]++;
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
    n.first_start = nest_seconds_now();
    if (status == UR_OK)
        status = nest_run_order(&n, order, NULL);
    n.first_run = false;
    double start = nest_seconds_now(), budget = options->time_budget;
    /*
     * No search follows a first layout that took longer than the whole
     * budget: each of its tries places parts again, cutting the whole
     * no-fit polygons of the pairs met out of their rooms, and checks the
     * clock only between tries (313 small nets on one 2 x 2 m sheet: a
     * first layout of 25 s, then a single try of the 0.2 s search ran for
     * 7 minutes and took 1.9 GB).
     */
    if (!nest_search_follows(&n, start))
        budget = 0.0;
    /*
     * The search over orders has a share of the budget; shortening the
     * strip, or fewer sheets and then the last one's parts pushed to one
     * end, the rest.
     */
    if (status == UR_OK)
        status = nest_search_orders(&n, order, ORDER_SHARE * budget);
    if (status == UR_OK && options->roll_width > 0 && budget > 0)
        status = nest_compact_roll(&n, start + budget);
    if (status == UR_OK && options->roll_width <= 0 && budget > 0)
        status = nest_sheets_search(&n, start + FEWER_SHEETS_SHARE * budget, start + budget);
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
        nest_measure_offcut(&n, layout);
    if (status != UR_OK)
        ur_layout_free(layout);
    free(keys);
    nester_free(&n);
    return status;
}
