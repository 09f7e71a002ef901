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
 *
 * One disc, the largest, proves little for a small net with glue tabs all
 * round: it fits many gaps between the parts placed where the net does
 * not.  So up to RASTER_MORE_DISCS more discs about other points of the
 * part are tested too, and a place is ruled out when any of them meets a
 * blocked centre.  Nesting the 195 charts of Blender's monkey head,
 * subdivided once, in paper took 32 s with the largest disc and 8 s with
 * 48 more, on the same layout.
 */
#include "nest_internal.h"

#include "depth_index.h"

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
/*
 * The most pixels of a sheet's raster, and the smallest pixel (mm).  A
 * roll is one sheet as long as all its parts in a row (metres, for many
 * small nets): its raster may have more pixels, lest they be wider than
 * the small nets' discs (3 mm on a 300 mm roll of 195 small nets).  So
 * may a large sheet's, when RASTER_PIXELS would make its pixels wider
 * than a quarter of the median part's largest disc (DISC_PIXELS): a
 * pixel's diagonal is taken off every disc, and a disc no wider than it
 * proves nothing (313 small nets on a 2 x 2 m sheet, pixels of 4 mm:
 * 168 cells proved full; of 1 mm, 22,271, and a quarter of the time).
 */
#define RASTER_PIXELS 250000
#define RASTER_PIXELS_ON_ROLL 4000000
#define RASTER_PIXELS_LARGE 4000000
#define SMALLEST_PIXEL 0.5
#define DISC_PIXELS 4.0

/*
 * The points of a grid this many to a side over a shape's box are tried
 * as the centres of its other discs, and a disc is kept only if its
 * radius is at least SMALLEST_DISC (mm): the test takes a pixel's
 * diagonal (0.7 to 1 mm on most sheets) off it, and a smaller disc proves
 * next to nothing.
 */
enum { DISC_GRID = 16 };
#define SMALLEST_DISC 1.0

/* Whether a candidate disc's centre lies well inside a disc kept already. */
static bool covered(const raster_shape *r, ur_vec2 centre)
{
    if (ur_vec2_distance(centre, r->centre) < 0.5 * r->radius)
        return true;
    for (size_t k = 0; k < r->more_count; k++)
        if (ur_vec2_distance(centre, r->more_centres[k]) < 0.5 * r->more_radii[k])
            return true;
    return false;
}

/* Ring r of a polygon (part of a multipolygon): -1 its exterior, else hole r. */
static const GEOSGeometry *ring_of(GEOSContextHandle_t geos, const GEOSGeometry *part, int r)
{
    return r < 0 ? GEOSGetExteriorRing_r(geos, part) : GEOSGetInteriorRingN_r(geos, part, r);
}

/* The sides of a polygon's rings, each as its two ends, for fill_rings. */
typedef struct sides {
    ur_vec2 (*ends)[2];
    size_t count;
} sides;

/* Appends the sides of ring (ring r of part: -1 the exterior); false out of memory. */
static bool add_sides(GEOSContextHandle_t geos, const GEOSGeometry *part, int r, sides *s)
{
    const GEOSCoordSequence *points = GEOSGeom_getCoordSeq_r(geos, ring_of(geos, part, r));
    unsigned size = 0;
    if (!points || !GEOSCoordSeq_getSize_r(geos, points, &size) || size < 2)
        return true;
    ur_vec2(*grown)[2] = realloc(s->ends, (s->count + size - 1) * sizeof *grown);
    if (!grown)
        return false;
    s->ends = grown;
    for (unsigned i = 0; i + 1 < size; i++) {
        ur_vec2 *e = s->ends[s->count++];
        GEOSCoordSeq_getXY_r(geos, points, i, &e[0].x, &e[0].y);
        GEOSCoordSeq_getXY_r(geos, points, i + 1, &e[1].x, &e[1].y);
    }
    return true;
}

static bool sides_of(GEOSContextHandle_t geos, const GEOSGeometry *polygon, sides *s)
{
    int parts = GEOSGetNumGeometries_r(geos, polygon);
    for (int p = 0; p < parts; p++) {
        const GEOSGeometry *part = GEOSGetGeometryN_r(geos, polygon, p);
        if (GEOSGeomTypeId_r(geos, part) != GEOS_POLYGON)
            continue;
        int holes = GEOSGetNumInteriorRings_r(geos, part);
        for (int r = -1; r < holes; r++)
            if (!add_sides(geos, part, r, s))
                return false;
    }
    return true;
}

/*
 * More discs the shape holds, besides its largest: one about each point of
 * a grid over its box that lies inside it, as wide as the point's distance
 * to its outline, the widest first, none centred well inside another.  A
 * small net with glue tabs all round holds only a small largest disc, and
 * that disc alone finds room in many gaps between the parts placed where
 * the whole net has none.
 */
static void more_discs(GEOSContextHandle_t geos, const GEOSGeometry *polygon, raster_shape *r)
{
    double box[4];
    depth_index inside = {0};
    if (nest_box_of(geos, polygon, box) && depth_index_make(geos, polygon, &inside)) {
        ur_vec2 centres[DISC_GRID * DISC_GRID];
        double radii[DISC_GRID * DISC_GRID];
        size_t count = 0;
        for (int i = 0; i < DISC_GRID; i++)
            for (int j = 0; j < DISC_GRID; j++) {
                ur_vec2 at = {box[0] + (box[2] - box[0]) * (i + 0.5) / DISC_GRID,
                              box[1] + (box[3] - box[1]) * (j + 0.5) / DISC_GRID};
                double radius = depth_index_depth(&inside, at) - CORE_DEPTH;
                if (radius >= SMALLEST_DISC)
                    centres[count] = at, radii[count++] = radius;
            }
        /* The widest first (selection sort: a few hundred points at most). */
        for (size_t a = 0; a < count && r->more_count < RASTER_MORE_DISCS; a++) {
            size_t widest = a;
            for (size_t b = a + 1; b < count; b++)
                if (radii[b] > radii[widest])
                    widest = b;
            if (!covered(r, centres[widest])) {
                r->more_centres[r->more_count] = centres[widest];
                r->more_radii[r->more_count++] = radii[widest];
            }
            centres[widest] = centres[a], radii[widest] = radii[a];
        }
    }
    depth_index_free(&inside);
}

/* The shape of (class, turn)'s core and discs, made when first asked for. */
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
    if (r->radius > 0)
        more_discs(n->geos, shape->polygon, r);
    return r;
}

static int smaller_first(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/*
 * Blocks the pixels whose centres lie inside a polygon or multipolygon
 * (even-odd over all its rings) shifted by at; crossings is scratch for
 * room crossings of a row.
 */
static void fill_rings(nester *n, sheet_raster *raster, const GEOSGeometry *polygon, ur_vec2 at,
                       double *crossings, size_t room)
{
    double box[4];
    sides s = {NULL, 0};
    if (!nest_box_of(n->geos, polygon, box) || !sides_of(n->geos, polygon, &s)) {
        free(s.ends);
        return; /* nothing blocked, which is safe */
    }
    double h = raster->pixel;
    long j0 = (long)ceil((box[1] + at.y) / h - 0.5), j1 = (long)floor((box[3] + at.y) / h - 0.5);
    for (long j = j0 < 0 ? 0 : j0; j <= j1 && j < (long)raster->rows; j++) {
        double y = (j + 0.5) * h;
        size_t count = 0;
        for (size_t k = 0; k < s.count && count < room; k++) {
            double x0 = s.ends[k][0].x + at.x, y0 = s.ends[k][0].y + at.y;
            double x1 = s.ends[k][1].x + at.x, y1 = s.ends[k][1].y + at.y;
            if ((y0 <= y) != (y1 <= y))
                crossings[count++] = x0 + (y - y0) * (x1 - x0) / (y1 - y0);
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
    free(s.ends);
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
    bool blocked = false;
    for (size_t p = 0; p < w * h; p++) {
        if (raster->distance[p] != 0)
            raster->distance[p] = far;
        else
            blocked = true;
    }
    /*
     * With nothing blocked (a sheet with no part on it yet) every line
     * stays far as it is: each pixel's own parabola is the lowest at it,
     * and far plus the squares of the whole numbers involved is exact.
     */
    for (size_t i = 0; blocked && i < w; i++)
        distance_line(raster->distance + i, h, w, v, z, d);
    for (size_t j = 0; blocked && j < h; j++)
        distance_line(raster->distance + j * w, w, 1, v, z, d);
    for (size_t p = 0; p < w * h; p++)
        raster->distance[p] = (float)(sqrt(raster->distance[p]) * raster->pixel);
    free(v), free(z), free(d);
    return true;
}

enum { CROSSINGS = 4096 }; /* the most crossings of a row of pixels with a part's rings */

/* The median of the parts' largest discs (at their first turns); 0 when none has one. */
static double median_disc(nester *n)
{
    double *radii = malloc((n->class_count + 1) * sizeof *radii);
    size_t count = 0;
    for (size_t c = 0; radii && c < n->class_count; c++) {
        const raster_shape *shape = shape_for(n, n->classes[c].representative, 0);
        if (shape->radius > 0)
            radii[count++] = shape->radius;
    }
    if (count > 1)
        qsort(radii, count, sizeof *radii, smaller_first);
    double median = count ? radii[count / 2] : 0.0;
    free(radii);
    return median;
}

/* The side of a pixel of sheet's raster (mm), width x height. */
static double pixel_size(nester *n, size_t sheet, double width, double height)
{
    double area = width * height;
    if (n->options->roll_width > 0 && sheet >= n->remnant_count)
        return fmax(SMALLEST_PIXEL, sqrt(area / RASTER_PIXELS_ON_ROLL));
    double pixel = fmax(SMALLEST_PIXEL, sqrt(area / RASTER_PIXELS));
    double finest = fmax(SMALLEST_PIXEL, sqrt(area / RASTER_PIXELS_LARGE));
    if (pixel <= finest)
        return pixel;
    double disc = median_disc(n);
    return disc > 0 ? fmax(finest, fmin(pixel, disc / DISC_PIXELS)) : pixel;
}

/* Makes sheet's raster anew from the placements on it; false out of memory. */
static bool raster_make(nester *n, size_t sheet, sheet_raster *raster)
{
    if (!raster->distance) {
        double width, height;
        nest_sheet_size(n, sheet, &width, &height);
        raster->pixel = pixel_size(n, sheet, width, height);
        raster->columns = (size_t)ceil(width / raster->pixel);
        raster->rows = (size_t)ceil(height / raster->pixel);
        raster->distance = malloc(raster->columns * raster->rows * sizeof *raster->distance);
        if (!raster->distance)
            return false;
    }
    for (size_t p = 0; p < raster->columns * raster->rows; p++)
        raster->distance[p] = FLT_MAX;
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

/*
 * The widest any part's disc can be: no wider than the box of the polygon
 * it lies in, at any turn.  No test compares a distance with more.
 */
static double widest_disc(const nester *n)
{
    double widest = 0;
    for (size_t c = 0; c < n->class_count; c++)
        for (size_t t = 0; t < n->classes[c].turn_count; t++) {
            const ur_box *reach = &n->classes[c].turns[t].reach;
            widest = fmax(widest, 0.5 * fmin(ur_box_width(*reach), ur_box_height(*reach)));
        }
    return widest;
}

/*
 * Adds placement k's blocked centres to the raster without making it
 * again: they lie in its core's box, so the distances to them are made
 * in a window about that box (the same transform on a smaller grid) and
 * kept where they are less.  Outside the window, a pixel lies farther
 * from them than any disc is wide, so whatever distance it keeps, every
 * test gives what a raster made anew would.  False out of memory.
 */
static bool raster_add(nester *n, sheet_raster *raster, size_t k, double margin)
{
    const placed *p = &n->placements[k];
    const raster_shape *shape = shape_for(n, p->piece, p->turn);
    double box[4], h = raster->pixel;
    if (!shape->core || !nest_box_of(n->geos, shape->core, box))
        return true; /* nothing blocked */
    double x0 = floor((box[0] + p->at.x - margin) / h), x1 = ceil((box[2] + p->at.x + margin) / h);
    double y0 = floor((box[1] + p->at.y - margin) / h), y1 = ceil((box[3] + p->at.y + margin) / h);
    double last_i = (double)raster->columns - 1, last_j = (double)raster->rows - 1;
    if (x1 < 0 || y1 < 0 || x0 > last_i || y0 > last_j)
        return true; /* off the sheet */
    size_t i0 = x0 > 0 ? (size_t)x0 : 0, j0 = y0 > 0 ? (size_t)y0 : 0;
    size_t i1 = (size_t)fmin(x1, last_i), j1 = (size_t)fmin(y1, last_j);
    sheet_raster window = {.columns = i1 - i0 + 1, .rows = j1 - j0 + 1, .pixel = h};
    window.distance = malloc(window.columns * window.rows * sizeof *window.distance);
    double *crossings = malloc(CROSSINGS * sizeof *crossings);
    bool ok = window.distance && crossings;
    if (ok) {
        for (size_t q = 0; q < window.columns * window.rows; q++)
            window.distance[q] = FLT_MAX;
        ur_vec2 at = {p->at.x - (double)i0 * h, p->at.y - (double)j0 * h};
        fill_rings(n, &window, shape->core, at, crossings, CROSSINGS);
        ok = distance_transform(&window);
    }
    for (size_t j = 0; ok && j < window.rows; j++)
        for (size_t i = 0; i < window.columns; i++) {
            float *d = &raster->distance[(j + j0) * raster->columns + i + i0];
            *d = fminf(*d, window.distance[j * window.columns + i]);
        }
    free(window.distance);
    free(crossings);
    return ok;
}

/*
 * Brings sheet's raster up to date: the placements made on it since, one
 * by one, when nothing was taken off it meanwhile (each placement on it
 * counts one version, as does each one taken off); else made anew.
 */
static bool raster_update(nester *n, size_t sheet, sheet_raster *raster)
{
    size_t version = n->sheets[sheet].version, added = 0;
    for (size_t k = raster->placed; raster->distance && k < n->placed_count; k++)
        added += n->sheet_of[k] == sheet;
    bool ok;
    if (raster->distance && raster->placed <= n->placed_count &&
        added == version - raster->version) {
        double margin = widest_disc(n) + 2 * raster->pixel;
        ok = true;
        for (size_t k = raster->placed; ok && k < n->placed_count; k++)
            if (n->sheet_of[k] == sheet)
                ok = raster_add(n, raster, k, margin);
    } else {
        ok = raster_make(n, sheet, raster);
    }
    raster->version = version;
    raster->placed = n->placed_count;
    return ok;
}

/* The sheet's raster, brought up to date if the sheet changed since; NULL when it cannot be had. */
static const sheet_raster *raster_of(nester *n, size_t sheet)
{
    sheet_raster *raster = &n->sheets[sheet].raster;
    if (raster->version != n->sheets[sheet].version || !raster->distance) {
        if (!raster_update(n, sheet, raster)) {
            free(raster->distance);
            memset(raster, 0, sizeof *raster);
            return NULL;
        }
    }
    return raster;
}

/*
 * Whether another disc of the shape meets a blocked centre wherever the
 * largest disc's centre lies in pixel (i, j).  Other disc k's centre then
 * lies in the same square moved by its offset from the largest's, every
 * point of which is within a pixel's diagonal of the centre of the pixel
 * its middle falls in: that pixel's distance, plus the diagonal, is the
 * farthest a blocked centre can be.
 */
static bool other_disc_blocked(const sheet_raster *raster, const raster_shape *shape, size_t i,
                               size_t j)
{
    double h = raster->pixel;
    for (size_t k = 0; k < shape->more_count; k++) {
        double x = ((double)i + 0.5) * h + shape->more_centres[k].x - shape->centre.x;
        double y = ((double)j + 0.5) * h + shape->more_centres[k].y - shape->centre.y;
        if (!(x >= 0 && y >= 0 && x < (double)raster->columns * h && y < (double)raster->rows * h))
            continue;
        size_t p = (size_t)(y / h) * raster->columns + (size_t)(x / h);
        if (raster->distance[p] + h * M_SQRT2 < shape->more_radii[k])
            return true;
    }
    return false;
}

/* The pixels of a region, and what it takes of one to be a place of the shape's. */
typedef struct pixels {
    const sheet_raster *raster;
    const raster_shape *shape;
    double reach; /* the largest disc's, less half a pixel's diagonal */
    size_t i0, j0, i1, j1;
} pixels;

/* Whether no disc rules out a place with the largest disc's centre in pixel (i, j). */
static bool may_be_place(const pixels *r, size_t i, size_t j)
{
    return r->raster->distance[j * r->raster->columns + i] >= r->reach &&
           !other_disc_blocked(r->raster, r->shape, i, j);
}

static bool row_has_place(const pixels *r, size_t j)
{
    for (size_t i = r->i0; i <= r->i1; i++)
        if (may_be_place(r, i, j))
            return true;
    return false;
}

static bool column_has_place(const pixels *r, size_t i)
{
    for (size_t j = r->j0; j <= r->j1; j++)
        if (may_be_place(r, i, j))
            return true;
    return false;
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
    pixels range = {raster, shape, reach, i0, j0, i1, j1};
    size_t low_j = j0;
    while (low_j <= j1 && !row_has_place(&range, low_j))
        low_j++;
    if (low_j > j1)
        return RASTER_NONE;
    if (!narrowed)
        return RASTER_UNKNOWN; /* a place may be there: that is all asked */
    /* Each edge of the places' box is the first row or column from that side with one. */
    size_t high_j = j1;
    while (!row_has_place(&range, high_j))
        high_j--;
    range.j0 = low_j, range.j1 = high_j;
    size_t low_i = i0, high_i = i1;
    while (!column_has_place(&range, low_i))
        low_i++;
    while (!column_has_place(&range, high_i))
        high_i--;
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
