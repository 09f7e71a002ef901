/*
 * bench_nest.c: true-shape nesting of 100 mixed pieces on 600 x 400 sheets
 * (the target: sheets used at most the lower bound + 1, within 10 s).
 *
 * The pieces are what unroll's jobs make: 40 curved strips (annular
 * sectors, as a helicoid's nets), 30 rectangles of assorted sizes, 20 L
 * shapes and 10 rings with a hole (polygons of 64 sides), 5 mm margin and
 * 3 mm spacing, 4 turns.  Prints sheets used against the lower bound
 * ceil(sum of areas / usable sheet area), the mean utilisation and the time.
 *
 * Then the first layout alone (no search) of 500 different stars of 5 to
 * 11 points on A3 sheets: many parts each of a shape of its own, as a mesh
 * unfolded into many small nets gives, where every part's room is cut
 * from scratch on every sheet (sheet_raster.c).  And the same stars on one
 * sheet of 2000 x 2000 mm (a router's), where each new part's rooms are cut
 * from scratch among all the parts placed before it; and there again with
 * a budget of 1 s, which that first layout alone exceeds (no search may
 * follow it then).  Prints sheets and time.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "unroll/nest.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void add(ur_piece *piece, const char *name, const ur_vec2 *ring, size_t count)
{
    memset(piece, 0, sizeof *piece);
    snprintf(piece->name, sizeof piece->name, "%s", name);
    if (ur_piece_add_path(piece, UR_OP_CUT, ring, count, true, NULL) != UR_OK)
        exit(1);
    piece->measures.flat_area = fabs(ur_polygon_signed_area(ring, count));
}

/* An annular sector: radii r0 < r1, angle a, n steps per arc. */
static void strip(ur_piece *piece, double r0, double r1, double a)
{
    enum { STEPS = 60 };
    ur_vec2 ring[2 * (STEPS + 1)];
    for (int k = 0; k <= STEPS; k++) {
        double t = a * k / STEPS;
        ring[k] = ur_vec2_make(r1 * cos(t), r1 * sin(t));
        ring[2 * STEPS + 1 - k] = ur_vec2_make(r0 * cos(t), r0 * sin(t));
    }
    add(piece, "strip", ring, 2 * (STEPS + 1));
}

static void rectangle(ur_piece *piece, double w, double h)
{
    ur_vec2 ring[4] = {{0, 0}, {w, 0}, {w, h}, {0, h}};
    add(piece, "rectangle", ring, 4);
}

static void l_shape(ur_piece *piece, double s, double arm)
{
    ur_vec2 ring[6] = {{0, 0}, {s, 0}, {s, arm}, {arm, arm}, {arm, s}, {0, s}};
    add(piece, "L", ring, 6);
}

static void ring_piece(ur_piece *piece, double r0, double r1)
{
    enum { SIDES = 64 };
    ur_vec2 outer[SIDES], inner[SIDES];
    for (int k = 0; k < SIDES; k++) {
        double t = 2 * M_PI * k / SIDES;
        outer[k] = ur_vec2_make(r1 * cos(t), r1 * sin(t));
        inner[SIDES - 1 - k] = ur_vec2_make(r0 * cos(t), r0 * sin(t));
    }
    add(piece, "ring", outer, SIDES);
    if (ur_piece_add_path(piece, UR_OP_CUT, inner, SIDES, true, NULL) != UR_OK)
        exit(1);
    piece->measures.flat_area -= M_PI * r0 * r0;
}

/* Sheets of width x height with a 5 mm margin, the spacing given and 4 turns. */
static ur_nest_options sheet_options(double width, double height, double spacing)
{
    ur_nest_options options;
    memset(&options, 0, sizeof options);
    options.sheet_width = width;
    options.sheet_height = height;
    options.margin = 5;
    options.spacing = spacing;
    options.rotations = 4;
    return options;
}

/* A star of n points about its centre, radii drawn from the seed, as nest --nest-time 0 takes. */
static void star(ur_piece *piece, int n, unsigned *seed)
{
    ur_vec2 ring[22];
    for (int i = 0; i < n; i++) {
        *seed = *seed * 1103515245u + 12345u;
        double r = 6 + 10 * (double)(*seed >> 16 & 0x7fff) / 0x7fff * (0.5 + i % 2);
        double a = 2 * M_PI * i / n;
        ring[i] = ur_vec2_make(r * cos(a), r * sin(a));
    }
    add(piece, "star", ring, (size_t)n);
}

/*
 * The layout of 500 different stars on sheets of width x height: the
 * first alone (budget 0), or with the search the budget (s) allows.
 */
static int many_different_parts(double width, double height, double budget)
{
    enum { STARS = 500 };
    ur_piece *pieces = calloc(STARS, sizeof *pieces);
    if (!pieces)
        return 1;
    unsigned seed = 5;
    for (int k = 0; k < STARS; k++)
        star(&pieces[k], 5 + k % 7, &seed);
    ur_nest_options options = sheet_options(width, height, 2);
    options.time_budget = budget;
    ur_layout layout;
    ur_error error;
    double start = now();
    if (ur_layout_nest(pieces, STARS, &options, &layout, &error) != UR_OK) {
        fprintf(stderr, "bench_nest: %s\n", error.message);
        return 1;
    }
    char search[48] = "first layout only";
    if (budget > 0)
        snprintf(search, sizeof search, "a budget of %g s", budget);
    printf("nest 500 different stars on %g x %g, %s: %zu sheets, %.2f s\n", width, height, search,
           layout.sheet_count, now() - start);
    ur_layout_free(&layout);
    for (size_t k = 0; k < STARS; k++)
        ur_piece_free(&pieces[k]);
    free(pieces);
    return 0;
}

int main(void)
{
    enum { COUNT = 100 };
    ur_piece pieces[COUNT];
    size_t n = 0;
    for (int k = 0; k < 40; k++)
        strip(&pieces[n++], 60 + 5 * (k % 4), 90 + 5 * (k % 4), 1.2 + 0.1 * (k % 3));
    for (int k = 0; k < 30; k++)
        rectangle(&pieces[n++], 40 + 13 * (k % 6), 25 + 9 * (k % 5));
    for (int k = 0; k < 20; k++)
        l_shape(&pieces[n++], 60 + 10 * (k % 3), 15);
    for (int k = 0; k < 10; k++)
        ring_piece(&pieces[n++], 25, 40);
    ur_nest_options options = sheet_options(600, 400, 3);
    options.holes = true;
    double area = 0;
    for (size_t k = 0; k < n; k++)
        area += pieces[k].measures.flat_area;
    double bound = ceil(area / ((600 - 10) * (400 - 10)));
    ur_layout layout;
    ur_error error;
    double start = now();
    if (ur_layout_nest(pieces, n, &options, &layout, &error) != UR_OK) {
        fprintf(stderr, "bench_nest: %s\n", error.message);
        return 1;
    }
    double seconds = now() - start;
    double used = 0;
    for (size_t s = 0; s < layout.sheet_count; s++)
        used += ur_sheet_utilisation(&layout.sheets[s], pieces);
    printf("nest 100 mixed pieces on 600 x 400: %zu sheets (lower bound %.0f, target <= %.0f), "
           "mean utilisation %.1f %%, %.2f s (target 10 s)\n",
           layout.sheet_count, bound, bound + 1, 100 * used / (double)layout.sheet_count, seconds);
    ur_layout_free(&layout);
    for (size_t k = 0; k < n; k++)
        ur_piece_free(&pieces[k]);
    return many_different_parts(420, 297, 0) || many_different_parts(2000, 2000, 0) ||
           many_different_parts(2000, 2000, 1);
}
