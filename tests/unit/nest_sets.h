/*
 * nest_sets.h: the sets of parts the sheet search is tested and measured
 * on (test_nest.c, bench/bench_sheets.c), made here from a seed so that
 * no file is needed: irregular parts (random star-shaped polygons, every
 * one different), identical crescents, and identical curved strips
 * (annular sectors, as a helicoid's nets).  Each set is scaled so that
 * its parts' area is a given share of a sheet's.  Header-only.
 */
#ifndef UNROLL_NEST_SETS_H
#define UNROLL_NEST_SETS_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/nest.h"

/* xorshift64* in [0, 1): the same numbers on every machine. */
static double nest_set_random(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return (double)((*state * 2685821657736338717ULL) >> 11) * 0x1.0p-53;
}

/* A piece of one closed outline; false when it cannot be made. */
static bool nest_set_piece(ur_piece *piece, const char *name, const ur_vec2 *ring, size_t count)
{
    memset(piece, 0, sizeof *piece);
    snprintf(piece->name, sizeof piece->name, "%s", name);
    if (ur_piece_add_path(piece, UR_OP_CUT, ring, count, true, NULL) != UR_OK)
        return false;
    piece->measures.flat_area = fabs(ur_polygon_signed_area(ring, count));
    return true;
}

/* Scales the outline of each of count pieces by s (about the origin). */
static void nest_set_scale(ur_piece *pieces, size_t count, double s)
{
    for (size_t k = 0; k < count; k++) {
        ur_path *outline = &pieces[k].paths[0];
        for (size_t i = 0; i < outline->count; i++)
            outline->points[i] = ur_vec2_scale(outline->points[i], s);
        pieces[k].measures.flat_area *= s * s;
        ur_piece_recompute_box(&pieces[k]);
    }
}

/* Scales the pieces so that their area is share of a width x height sheet. */
static void nest_set_fill(ur_piece *pieces, size_t count, double share, double width, double height)
{
    double area = 0;
    for (size_t k = 0; k < count; k++)
        area += pieces[k].measures.flat_area;
    nest_set_scale(pieces, count, sqrt(share * width * height / area));
}

/*
 * count irregular parts: each a star-shaped polygon of 5 to 12 corners at
 * random angles and radii (from 35 % to 100 % of its size), its size
 * from 1 to 4 times the smallest's (the square of a uniform draw: many
 * small parts and a few large ones).
 */
#define NEST_SET_CORNERS 12
static bool nest_set_irregular(ur_piece *pieces, size_t count, uint64_t seed)
{
    uint64_t state = seed * 0x9E3779B97F4A7C15ULL + 1;
    for (size_t k = 0; k < count; k++) {
        size_t corners = 5 + (size_t)(nest_set_random(&state) * 8);
        double u = nest_set_random(&state), size = 10 * (1 + 3 * u * u);
        double angles[NEST_SET_CORNERS], total = 0;
        for (size_t i = 0; i < corners; i++)
            total += angles[i] = 0.5 + nest_set_random(&state);
        ur_vec2 ring[NEST_SET_CORNERS];
        double angle = 0;
        for (size_t i = 0; i < corners; i++) {
            double radius = size * (0.35 + 0.65 * nest_set_random(&state));
            ring[i] = ur_vec2_make(radius * cos(angle), radius * sin(angle));
            angle += 2 * M_PI * angles[i] / total;
        }
        char name[32];
        snprintf(name, sizeof name, "irregular-%zu", k + 1);
        if (!nest_set_piece(&pieces[k], name, ring, corners))
            return false;
    }
    return true;
}

/*
 * count crescents alike: a disc of radius 1 less a disc of radius 0.8
 * whose centre is 0.45 off, 48 steps along each arc.
 */
#define NEST_SET_ARC 48
static bool nest_set_crescents(ur_piece *pieces, size_t count)
{
    /* The arcs meet where |p| = 1 and |p - (0.45, 0)| = 0.8. */
    double cx = 0.3, r = 0.85, x = (1 + cx * cx - r * r) / (2 * cx), y = sqrt(1 - x * x);
    double outer = atan2(y, x), inner = atan2(y, x - cx);
    ur_vec2 ring[2 * NEST_SET_ARC + 2];
    size_t n = 0;
    for (int i = 0; i <= NEST_SET_ARC; i++) { /* the outer arc, the long way round */
        double t = outer + (2 * M_PI - 2 * outer) * i / NEST_SET_ARC;
        ring[n++] = ur_vec2_make(cos(t), sin(t));
    }
    for (int i = 1; i < NEST_SET_ARC; i++) { /* the inner arc back, inside the disc */
        double t = -inner + 2 * inner * i / NEST_SET_ARC;
        ring[n++] = ur_vec2_make(cx + r * cos(t), r * sin(t));
    }
    for (size_t k = 0; k < count; k++) {
        char name[32];
        snprintf(name, sizeof name, "crescent-%zu", k + 1);
        if (!nest_set_piece(&pieces[k], name, ring, n))
            return false;
    }
    return true;
}

/* count curved strips alike: annular sectors of radii 1 and 1.6 over 1.2 radians. */
static bool nest_set_strips(ur_piece *pieces, size_t count)
{
    ur_vec2 ring[2 * (NEST_SET_ARC + 1)];
    for (int i = 0; i <= NEST_SET_ARC; i++) {
        double t = 1.2 * i / NEST_SET_ARC;
        ring[i] = ur_vec2_make(1.6 * cos(t), 1.6 * sin(t));
        ring[2 * NEST_SET_ARC + 1 - i] = ur_vec2_make(cos(t), sin(t));
    }
    for (size_t k = 0; k < count; k++) {
        char name[32];
        snprintf(name, sizeof name, "strip-%zu", k + 1);
        if (!nest_set_piece(&pieces[k], name, ring, 2 * (NEST_SET_ARC + 1)))
            return false;
    }
    return true;
}

#endif
