/*
 * bench_sheets.c: the sheet search against the area bound, on the sets of
 * tests/unit/nest_sets.h: 32 irregular parts (66 % of a 300 x 200
 * sheet), 36 crescents alike (70 % of 600 x 400) and 40 curved strips
 * alike (62 % of 600 x 400), each with a 5 mm margin and 1 mm spacing, 4
 * turns: sets that the first layout puts on two sheets and a roll as wide
 * as the sheet is tall packs into one sheet's length.  For each: the sheets the first layout uses,
 * the length a roll as wide as the sheet is tall takes with the same budget (a length within the
 * sheet's shows one sheet possible), the sheets the search uses against the bound ceil(parts' area
 * / area inside the margin), the last sheet's offcut and the time.  NEST_SECONDS sets the budget of
 * each run (default 20, as `unroll nest --nest-time 20`).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../tests/unit/nest_sets.h"
#include "unroll/nest.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

typedef struct bench_set {
    const char *name;
    size_t count;
    double share, width, height;
} bench_set;

/* The set's parts, scaled to its share of the sheet. */
static void make_set(const bench_set *set, ur_piece *pieces)
{
    bool made = strcmp(set->name, "irregular") == 0   ? nest_set_irregular(pieces, set->count, 1)
                : strcmp(set->name, "crescents") == 0 ? nest_set_crescents(pieces, set->count)
                                                      : nest_set_strips(pieces, set->count);
    if (!made)
        exit(1);
    nest_set_fill(pieces, set->count, set->share, set->width, set->height);
}

/* Nests the pieces; exits on a failure. */
static void nest(const ur_piece *pieces, size_t count, const ur_nest_options *o, ur_layout *layout)
{
    ur_error error;
    if (ur_layout_nest(pieces, count, o, layout, &error) != UR_OK) {
        fprintf(stderr, "bench_sheets: %s\n", error.message);
        exit(1);
    }
}

static void run_set(const bench_set *set, double budget)
{
    ur_piece pieces[64];
    make_set(set, pieces);
    ur_nest_options o;
    memset(&o, 0, sizeof o);
    o.sheet_width = set->width;
    o.sheet_height = set->height;
    o.margin = 5;
    o.spacing = 1;
    o.rotations = 4;
    o.holes = true;
    o.seed = 1;
    double area = 0;
    for (size_t k = 0; k < set->count; k++)
        area += pieces[k].measures.flat_area;
    double bound = ceil(area / ((set->width - 10) * (set->height - 10)));
    ur_layout first, roll, searched;
    nest(pieces, set->count, &o, &first);
    ur_nest_options r = o;
    r.roll_width = set->height;
    r.time_budget = budget;
    nest(pieces, set->count, &r, &roll);
    o.time_budget = budget;
    double start = now();
    nest(pieces, set->count, &o, &searched);
    double seconds = now() - start;
    const ur_sheet *last = &searched.sheets[searched.sheet_count - 1];
    printf("%-10s %2zu parts on %g x %g: first layout %zu sheets, roll %.1f mm, searched %zu "
           "sheets (bound %.0f), offcut %.0f x %g mm, %.1f s\n",
           set->name, set->count, set->width, set->height, first.sheet_count, roll.sheets[0].width,
           searched.sheet_count, bound, last->offcut_width, last->height, seconds);
    ur_layout_free(&first);
    ur_layout_free(&roll);
    ur_layout_free(&searched);
    for (size_t k = 0; k < set->count; k++)
        ur_piece_free(&pieces[k]);
}

int main(void)
{
    const char *seconds = getenv("NEST_SECONDS");
    double budget = seconds ? atof(seconds) : 20;
    if (!(budget >= 0)) {
        fprintf(stderr, "bench_sheets: NEST_SECONDS must be a number of seconds\n");
        return 2;
    }
    static const bench_set sets[] = {
        {"irregular", 32, 0.66, 300, 200},
        {"crescents", 36, 0.70, 600, 400},
        {"strips", 40, 0.62, 600, 400},
    };
    printf("bench_sheets: sheets against the area bound, %g s each\n", budget);
    for (size_t k = 0; k < sizeof sets / sizeof sets[0]; k++)
        run_set(&sets[k], budget);
    return 0;
}
