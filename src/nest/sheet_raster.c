/*
 * sheet_raster.c: a quick proof that a part has no place in a region of a
 * sheet, before its room there is cut exactly (room.c).  Each sheet keeps
 * a raster: the centres of pixels that lie inside a placed part (deeper
 * than CORE_DEPTH) are blocked, and every pixel holds its distance to the
 * nearest blocked centre.  A part whose shape holds a disc of radius r
 * about c cannot have its origin at x when a blocked centre lies within r
 * of c + x: the two would overlap there.  So a cell of the part's room
 * where every pixel the disc's centre can reach lies nearer than r to a
 * blocked centre (less the half diagonal of a pixel, for the points
 * between centres) is full, and its no-fit polygons need not be cut; a
 * cell with a few such pixels left has its places within their box.
 *
 * Nesting a thousand different small nets spent nearly all its time
 * proving cells of full sheets full, one difference of polygons at a time.
 */
#include "nest_internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/*
 * How far inside a placed part a blocked centre lies at least, and how
 * much smaller than a part's inscribed disc the disc used is (mm): far
 * beyond the overlap the no-fit polygons allow (NEST_EXACT_FIT), so that
 * a place ruled out here is ruled out there too.
 */
#define CORE_DEPTH 0.01
/* The most pixels of a sheet's raster, and the smallest pixel (mm). */
#define RASTER_PIXELS 250000
#define SMALLEST_PIXEL 0.5

/* The shape of (class, turn)'s core and inscribed disc, made when first asked for. */
static raster_shape *shape_for(nester *n, size_t piece, size_t turn)
{
    raster_shape *r = &n->raster_shapes[n->class_of[piece] * n->turn_count + turn];
    if (r->made)
        return r;
    r->made = true;
    const nest_shape *shape = nest_shape_of(n, piece, turn);
    r->core = GEOSBuffer_r(n->geos, shape->polygon, -CORE_DEPTH, 2);
    double area = 0;
    GEOSArea_r(n->geos, shape->polygon, &area);
    GEOSGeometry *line =
        GEOSMaximumInscribedCircle_r(n->geos, shape->polygon, fmax(1e-3, 1e-3 * sqrt(area)));
    double length = 0, x = 0, y = 0;
    /* The line's length is the centre's own distance to the outline: a disc the shape holds. */
    if (line && GEOSGeomGetLength_r(n->geos, line, &length)) {
        const GEOSCoordSequence *points = GEOSGeom_getCoordSeq_r(n->geos, line);
        if (points && GEOSCoordSeq_getXY_r(n->geos, points, 0, &x, &y)) {
            r->centre = ur_vec2_make(x, y);
            r->radius = length - CORE_DEPTH;
        }
    }
    if (line)
        GEOSGeom_destroy_r(n->geos, line);
    return r;
}

/* The crossings of one ring with the row of centres at height y, shifted by at. */
static size_t ring_crossings(GEOSContextHandle_t geos, const GEOSGeometry *ring, ur_vec2 at,
                             double y, double *crossings, size_t count, size_t room)
{
    const GEOSCoordSequence *points = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
    unsigned size = 0;
    if (!points || !GEOSCoordSeq_getSize_r(geos, points, &size) || size < 2)
        return count;
    double x0, y0;
    GEOSCoordSeq_getXY_r(geos, points, 0, &x0, &y0);
    x0 += at.x, y0 += at.y;
    for (unsigned i = 1; i < size && count < room; i++) {
        double x1, y1;
        GEOSCoordSeq_getXY_r(geos, points, i, &x1, &y1);
        x1 += at.x, y1 += at.y;
        if ((y0 <= y) != (y1 <= y))
            crossings[count++] = x0 + (y - y0) * (x1 - x0) / (y1 - y0);
        x0 = x1, y0 = y1;
    }
    return count;
}

static int smaller_first(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The rings of a polygon or multipolygon, for crossing counts: ring r of part p. */
static const GEOSGeometry *ring_of(GEOSContextHandle_t geos, const GEOSGeometry *part, int r)
{
    return r < 0 ? GEOSGetExteriorRing_r(geos, part) : GEOSGetInteriorRingN_r(geos, part, r);
}

/*
 * Blocks the pixels whose centres lie inside a polygon or multipolygon
 * (even-odd over all its rings) shifted by at; crossings is scratch for
 * room crossings of a row.
 */
static void fill_rings(nester *n, sheet_raster *raster, const GEOSGeometry *polygon, ur_vec2 at,
                       double *crossings, size_t room)
{
    GEOSContextHandle_t geos = n->geos;
    double box[4];
    if (!nest_box_of(geos, polygon, box))
        return;
    double h = raster->pixel;
    long j0 = (long)ceil((box[1] + at.y) / h - 0.5), j1 = (long)floor((box[3] + at.y) / h - 0.5);
    for (long j = j0 < 0 ? 0 : j0; j <= j1 && j < (long)raster->rows; j++) {
        double y = (j + 0.5) * h;
        size_t count = 0;
        int parts = GEOSGetNumGeometries_r(geos, polygon);
        for (int p = 0; p < parts; p++) {
            const GEOSGeometry *part = GEOSGetGeometryN_r(geos, polygon, p);
            if (GEOSGeomTypeId_r(geos, part) != GEOS_POLYGON)
                continue;
            int holes = GEOSGetNumInteriorRings_r(geos, part);
            for (int r = -1; r < holes; r++)
                count = ring_crossings(geos, ring_of(geos, part, r), at, y, crossings, count, room);
        }
        if (count == room)
            continue; /* more crossings than expected: leave the row unblocked, which is safe */
        qsort(crossings, count, sizeof *crossings, smaller_first);
        for (size_t c = 0; c + 1 < count; c += 2) {
            long i0 = (long)ceil(crossings[c] / h - 0.5),
                 i1 = (long)floor(crossings[c + 1] / h - 0.5);
            for (long i = i0 < 0 ? 0 : i0; i <= i1 && i < (long)raster->columns; i++)
                raster->distance[(size_t)j * raster->columns + (size_t)i] = 0;
        }
    }
}

/*
 * One line of the squared Euclidean distance transform (Felzenszwalb and
 * Huttenlocher, the lower envelope of parabolas): f (count values, step
 * apart) becomes, in place, min over q of f[q] + (p - q)^2.  v, z and d
 * are scratch of count + 1 each.
 */
static void distance_line(float *f, size_t count, size_t step, size_t *v, double *z, float *d)
{
    size_t k = 0;
    v[0] = 0;
    z[0] = -DBL_MAX, z[1] = DBL_MAX;
    for (size_t q = 1; q < count; q++) {
        double fq = (double)f[q * step] + (double)q * (double)q, s;
        for (;;) {
            double fv = (double)f[v[k] * step] + (double)v[k] * (double)v[k];
            s = (fq - fv) / (2.0 * ((double)q - (double)v[k]));
            if (s > z[k])
                break;
            k--; /* z[0] is below every s: k stays a place */
        }
        k++;
        v[k] = q;
        z[k] = s;
        z[k + 1] = DBL_MAX;
    }
    k = 0;
    for (size_t q = 0; q < count; q++) {
        while (z[k + 1] < (double)q)
            k++;
        double gap = (double)q - (double)v[k];
        d[q] = (float)(gap * gap + (double)f[v[k] * step]);
    }
    for (size_t q = 0; q < count; q++)
        f[q * step] = d[q];
}

/* Turns the raster's blocked marks (0, others FLT_MAX) into distances (mm); false out of memory. */
static bool distance_transform(sheet_raster *raster)
{
    size_t w = raster->columns, h = raster->rows, most = w > h ? w : h;
    size_t *v = malloc((most + 1) * sizeof *v);
    double *z = malloc((most + 2) * sizeof *z);
    float *d = malloc((most + 1) * sizeof *d);
    if (!v || !z || !d) {
        free(v), free(z), free(d);
        return false;
    }
    /* Squared distances in pixels; the unblocked start far beyond the sheet but finite. */
    float far = (float)(4.0 * (double)most * (double)most);
    for (size_t p = 0; p < w * h; p++)
        if (raster->distance[p] != 0)
            raster->distance[p] = far;
    for (size_t i = 0; i < w; i++)
        distance_line(raster->distance + i, h, w, v, z, d);
    for (size_t j = 0; j < h; j++)
        distance_line(raster->distance + j * w, w, 1, v, z, d);
    for (size_t p = 0; p < w * h; p++)
        raster->distance[p] = (float)(sqrt(raster->distance[p]) * raster->pixel);
    free(v), free(z), free(d);
    return true;
}

/* Makes sheet's raster anew from the placements on it; false out of memory. */
static bool raster_make(nester *n, size_t sheet, sheet_raster *raster)
{
    if (!raster->distance) {
        double width, height;
        nest_sheet_size(n, sheet, &width, &height);
        raster->pixel = fmax(SMALLEST_PIXEL, sqrt(width * height / RASTER_PIXELS));
        raster->columns = (size_t)ceil(width / raster->pixel);
        raster->rows = (size_t)ceil(height / raster->pixel);
        raster->distance = malloc(raster->columns * raster->rows * sizeof *raster->distance);
        if (!raster->distance)
            return false;
    }
    for (size_t p = 0; p < raster->columns * raster->rows; p++)
        raster->distance[p] = FLT_MAX;
    enum { CROSSINGS = 4096 };
    double *crossings = malloc(CROSSINGS * sizeof *crossings);
    if (!crossings)
        return false;
    for (size_t k = 0; k < n->placed_count; k++) {
        if (n->sheet_of[k] != sheet)
            continue;
        const placed *p = &n->placements[k];
        const raster_shape *shape = shape_for(n, p->piece, p->turn);
        if (shape->core)
            fill_rings(n, raster, shape->core, p->at, crossings, CROSSINGS);
    }
    free(crossings);
    return distance_transform(raster);
}

/* The sheet's raster, made again if the sheet changed since; NULL when it cannot be had. */
static const sheet_raster *raster_of(nester *n, size_t sheet)
{
    sheet_raster *raster = &n->sheets[sheet].raster;
    if (raster->version != n->sheets[sheet].version || !raster->distance) {
        if (!raster_make(n, sheet, raster)) {
            free(raster->distance);
            memset(raster, 0, sizeof *raster);
            return NULL;
        }
        raster->version = n->sheets[sheet].version;
    }
    return raster;
}

raster_verdict nest_raster_room(nester *n, size_t sheet, size_t piece, size_t turn,
                                const double *box, double *narrowed)
{
    /*
     * Only while the first layout is made: there every part meets its
     * rooms for the first time.  The search's runs find most cells cut
     * already, and a raster made again after each placement (a few
     * milliseconds) would cost them more than it saves.
     */
    if (!n->first_run || !n->raster_shapes || sheet >= n->sheet_count)
        return RASTER_UNKNOWN;
    const raster_shape *shape = shape_for(n, piece, turn);
    const sheet_raster *raster = shape->radius > 0 ? raster_of(n, sheet) : NULL;
    if (!raster)
        return RASTER_UNKNOWN;
    double h = raster->pixel, reach = shape->radius - h * M_SQRT1_2;
    double x0 = box[0] + shape->centre.x, x1 = box[2] + shape->centre.x;
    double y0 = box[1] + shape->centre.y, y1 = box[3] + shape->centre.y;
    if (!(reach > 0) || x0 < 0 || y0 < 0 || x1 >= (double)raster->columns * h ||
        y1 >= (double)raster->rows * h)
        return RASTER_UNKNOWN;
    /*
     * The pixels whose squares meet the region; a place may lie only where
     * the disc's centre falls in a pixel as far from every blocked centre
     * as the disc is wide: the box of those, less the centre, holds them.
     */
    size_t i0 = (size_t)(x0 / h), i1 = (size_t)(x1 / h), j0 = (size_t)(y0 / h),
           j1 = (size_t)(y1 / h);
    size_t low_i = SIZE_MAX, high_i = 0, low_j = SIZE_MAX, high_j = 0;
    for (size_t j = j0; j <= j1; j++)
        for (size_t i = i0; i <= i1; i++)
            if (raster->distance[j * raster->columns + i] >= reach) {
                if (!narrowed)
                    return RASTER_UNKNOWN; /* a place may be there: that is all asked */
                low_i = i < low_i ? i : low_i, high_i = i > high_i ? i : high_i;
                low_j = j < low_j ? j : low_j, high_j = j > high_j ? j : high_j;
            }
    if (low_i == SIZE_MAX)
        return RASTER_NONE;
    narrowed[0] = fmax(box[0], (double)low_i * h - shape->centre.x);
    narrowed[1] = fmax(box[1], (double)low_j * h - shape->centre.y);
    narrowed[2] = fmin(box[2], (double)(high_i + 1) * h - shape->centre.x);
    narrowed[3] = fmin(box[3], (double)(high_j + 1) * h - shape->centre.y);
    return RASTER_NARROWED;
}

void nest_raster_free(nester *n)
{
    for (size_t k = 0; n->raster_shapes && k < n->class_count * n->turn_count; k++)
        if (n->raster_shapes[k].core)
            GEOSGeom_destroy_r(n->geos, n->raster_shapes[k].core);
    free(n->raster_shapes);
    n->raster_shapes = NULL;
    for (size_t s = 0; n->sheets && s < n->sheet_slots; s++)
        free(n->sheets[s].raster.distance);
}
