/*
 * depth_index.c: a no-fit polygon as the edges of its rings, cut into bands
 * (for the inside test) and a grid of cells (for the nearest edge), so that
 * a penetration depth costs a few edges instead of all of them
 * (depth_index.h).
 */
#include "depth_index.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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

void depth_index_free(depth_index *f)
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
static bool add_ring(GEOSContextHandle_t geos, const GEOSGeometry *ring, depth_index *f)
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
static size_t band_of(const depth_index *f, double y)
{
    double b = floor((y - f->box[1]) / f->band_height);
    return b < 0 ? 0 : b >= (double)f->band_count ? f->band_count - 1 : (size_t)b;
}

/* The bands of f's edges (edges and box made); false on a failure. */
static bool make_bands(depth_index *f)
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
static inline bool inside_of(const depth_index *f, ur_vec2 p)
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
static size_t cell_of(const depth_index *f, ur_vec2 p)
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
static bool add_cell_edge(depth_index *f, cell_lists *lists, size_t edge)
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
static bool fill_cell(depth_index *f, size_t c, cell_lists *lists)
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
static bool make_cells(depth_index *f)
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
bool depth_index_make(GEOSContextHandle_t geos, const GEOSGeometry *g, depth_index *f)
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
 * The edge of f's rings nearest to p, a point in the given cell, among
 * those the cell lists (the only ones that can be nearest); its squared
 * distance in *distance2.
 */
static inline const flat_edge *nearest_edge(const depth_index *f, size_t cell, ur_vec2 p,
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
double depth_index_depth(const depth_index *f, ur_vec2 p)
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
ur_vec2 depth_index_way_out(const depth_index *f, ur_vec2 p)
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
