/*
 * depth_index.h (internal to src/nest/): a no-fit polygon indexed for the
 * one question the overlap search (compact.c) asks millions of times: how
 * far does a point lie inside it, and where is the nearest way out.
 */
#ifndef UNROLL_NEST_DEPTH_INDEX_H
#define UNROLL_NEST_DEPTH_INDEX_H

#include <geos_c.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "unroll/geom.h"

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
typedef struct depth_index {
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
} depth_index;

/*
 * Indexes the rings of a GEOS polygon or multipolygon into f (zeroed
 * before); false when out of memory, f then to be freed all the same.
 */
bool depth_index_make(GEOSContextHandle_t geos, const GEOSGeometry *g, depth_index *f);

/* Frees what f holds and zeroes it. */
void depth_index_free(depth_index *f);

/*
 * How far p lies inside the no-fit polygon (0 outside): the penetration
 * depth, the distance to the nearest edge of its rings.
 */
double depth_index_depth(const depth_index *f, ur_vec2 p);

/*
 * The nearest place outside f from p, which lies inside: p taken across
 * the nearest edge of f's rings, a hair beyond it.
 */
ur_vec2 depth_index_way_out(const depth_index *f, ur_vec2 p);

#endif
