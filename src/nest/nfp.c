/*
 * nfp.c: pieces as nesting sees them and their no-fit polygons.
 *
 * The no-fit polygon of a moving part B around a fixed part A is the set of
 * positions of B's origin where B would overlap A: the Minkowski sum
 * A + (-B).  For convex polygons that sum is the convex hull of the sums of
 * their vertices; a concave part (or one with holes) is split into convex
 * parts, and the no-fit polygon is the union of the pairwise sums, exact
 * for any shape.  Holes of A come out as holes of the no-fit polygon: the
 * places where B fits inside A.
 *
 * The parts come from GEOS's constrained Delaunay triangulation of the
 * polygon, its triangles merged while the merge stays convex.  Outlines are
 * simplified first (pieces can have hundreds of thousands of points) and
 * grown by the simplification's tolerance, so that nothing the
 * simplification cut off can overlap.
 *
 * The convex parts are then shrunk by half of NEST_EXACT_FIT, a millionth
 * of a millimetre, before their sums are made.  Where B fits A exactly (a
 * part in a notch of its own width) the sums only touch: the places where
 * B fits form a line or a point, and their union would close it, as if B
 * could never go there.  Shrunk, the sums leave a corridor a millionth of
 * a millimetre wide there, where the nester and compact.c's search can
 * find the fit.
 */
#include "nest_internal.h"

#include "../geom/hull.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Pieces with more points than this are simplified before their no-fit polygons. */
#define SIMPLIFY_ABOVE 64

/*
 * And closed by this share of their size: the notches between a papercraft
 * net's glue tabs and the slits between its flaps, which no other part
 * could use, filled, so that the net is a few convex parts, not hundreds.
 */
#define CLOSING 0.01

/*
 * A shape with more convex parts than this is simplified and closed again,
 * twice as coarsely each time, up to COARSEST of its size (four times the
 * first tolerance): a pair's no-fit polygon is made of one sum per pair of
 * their parts, and a papercraft net's curved, tabbed strips came out in up
 * to 140 parts (20,000 sums for a pair: 35 s of a 2,000-face sphere's 36,
 * and 400 MB).
 */
#define MOST_PARTS 32
#define COARSEST 0.008

/* The ring of a path turned by angle, as a GEOS linear ring; NULL on failure. */
static GEOSGeometry *turned_ring(GEOSContextHandle_t geos, const ur_path *path, double angle)
{
    ur_transform2 turn = ur_transform2_make(angle, ur_vec2_make(0, 0));
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)path->count + 1, 2);
    if (!sequence)
        return NULL;
    for (size_t i = 0; i <= path->count; i++) {
        ur_vec2 p = ur_transform2_apply(turn, path->points[i % path->count]);
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, p.x, p.y);
    }
    return GEOSGeom_createLinearRing_r(geos, sequence);
}

static bool is_hole(const ur_path *path)
{
    return path->op == UR_OP_CUT && path->closed && path->count >= 3;
}

/* The piece's outline and (with holes) its holes as one turned polygon, in *polygon. */
static ur_status piece_polygon(GEOSContextHandle_t geos, const ur_piece *piece, double angle,
                               bool holes, GEOSGeometry **polygon, ur_error *error)
{
    *polygon = NULL;
    GEOSGeometry *shell = turned_ring(geos, &piece->paths[0], angle);
    size_t hole_count = 0;
    GEOSGeometry **rings = calloc(piece->path_count + 1, sizeof *rings);
    if (!shell || !rings) {
        if (shell)
            GEOSGeom_destroy_r(geos, shell);
        free(rings);
        return shell ? ur_error_out_of_memory(error)
                     : ur_error_set(error, UR_ERROR_INTERNAL,
                                    "GEOS could not prepare a piece to nest");
    }
    for (size_t k = 1; holes && k < piece->path_count; k++)
        if (is_hole(&piece->paths[k])) {
            GEOSGeometry *ring = turned_ring(geos, &piece->paths[k], angle);
            if (ring)
                rings[hole_count++] = ring;
        }
    *polygon = GEOSGeom_createPolygon_r(geos, shell, rings, (unsigned)hole_count);
    /*
     * In normal form, its rings starting at their least points: simplifying
     * a ring keeps its first point, so where an outline happened to start
     * decided its convex parts (a sphere's net: 25 or 67, and the search's
     * no-fit polygons a third slower).
     */
    if (*polygon && GEOSNormalize_r(geos, *polygon) != 0) {
        GEOSGeom_destroy_r(geos, *polygon);
        *polygon = NULL;
    }
    free(rings);
    return *polygon
               ? UR_OK
               : ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not prepare a piece to nest");
}

/* The polygon made valid, simplified by tolerance and grown by grow + tolerance (mitred). */
/*
 * The polygon closed by radius (grown by it, then shrunk by as much, mitred):
 * notches and slits narrower than about twice the radius filled, nothing
 * else moved.  It contains the polygon.  NULL on failure.
 */
static GEOSGeometry *closed(GEOSContextHandle_t geos, const GEOSGeometry *polygon,
                            GEOSBufferParams *params, double radius)
{
    GEOSGeometry *out = GEOSBufferWithParams_r(geos, polygon, params, radius);
    GEOSGeometry *back = out ? GEOSBufferWithParams_r(geos, out, params, -radius) : NULL;
    if (out)
        GEOSGeom_destroy_r(geos, out);
    if (back && (GEOSGeomTypeId_r(geos, back) != GEOS_POLYGON || GEOSisEmpty_r(geos, back))) {
        GEOSGeom_destroy_r(geos, back);
        return GEOSGeom_clone_r(geos, polygon); /* it fell apart: keep it as it was */
    }
    return back;
}

/* The valid polygon simplified, grown and closed; NULL on failure. */
static GEOSGeometry *grown(GEOSContextHandle_t geos, const GEOSGeometry *valid, double grow,
                           double tolerance, double closing)
{
    GEOSGeometry *simple = GEOSTopologyPreserveSimplify_r(geos, valid, tolerance);
    GEOSBufferParams *params = GEOSBufferParams_create_r(geos);
    GEOSGeometry *out = NULL;
    if (simple && params) {
        GEOSBufferParams_setJoinStyle_r(geos, params, GEOSBUF_JOIN_MITRE);
        GEOSBufferParams_setMitreLimit_r(geos, params, 4.0);
        out = GEOSBufferWithParams_r(geos, simple, params, grow + tolerance);
    }
    if (out && closing > 0) {
        GEOSGeometry *filled = closed(geos, out, params, closing);
        GEOSGeom_destroy_r(geos, out);
        out = filled;
    }
    if (params)
        GEOSBufferParams_destroy_r(geos, params);
    if (simple)
        GEOSGeom_destroy_r(geos, simple);
    return out;
}

static double area_of(GEOSContextHandle_t geos, const GEOSGeometry *g)
{
    double area = 0.0;
    return g && GEOSArea_r(geos, g, &area) ? area : 0.0;
}

/* Whether two boxes (x0, y0, x1, y1) touch or overlap, with a little slack. */
static bool boxes_touch(const double *a, const double *b)
{
    const double slack = 1e-9;
    return a[0] <= b[2] + slack && b[0] <= a[2] + slack && a[1] <= b[3] + slack &&
           b[1] <= a[3] + slack;
}

bool nest_box_of(GEOSContextHandle_t geos, const GEOSGeometry *g, double *box)
{
    return GEOSGeom_getXMin_r(geos, g, &box[0]) && GEOSGeom_getYMin_r(geos, g, &box[1]) &&
           GEOSGeom_getXMax_r(geos, g, &box[2]) && GEOSGeom_getYMax_r(geos, g, &box[3]);
}

/* The exterior vertices of a polygon (last not repeated), allocated; how many (0 on failure). */
static size_t vertices(GEOSContextHandle_t geos, const GEOSGeometry *polygon, ur_vec2 **points,
                       bool *out_of_memory)
{
    *points = NULL;
    const GEOSGeometry *ring = GEOSGetExteriorRing_r(geos, polygon);
    const GEOSCoordSequence *sequence = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size) || size < 2)
        return 0;
    *points = malloc((size - 1) * sizeof **points);
    if (!*points) {
        *out_of_memory = true;
        return 0;
    }
    for (unsigned i = 0; i + 1 < size; i++)
        GEOSCoordSeq_getXY_r(geos, sequence, i, &(*points)[i].x, &(*points)[i].y);
    return size - 1;
}

/* The area of a convex polygon (counter-clockwise: positive). */
static double convex_area(const ur_vec2 *points, size_t count)
{
    double twice = 0;
    for (size_t i = 0; i < count; i++)
        twice += ur_vec2_cross(points[i], points[(i + 1) % count]);
    return 0.5 * twice;
}

/* How far convex_area's rounding may stray, for count points no farther than reach from 0. */
static double area_rounding(size_t count, double reach)
{
    double n = (double)count + 2;
    return 16 * n * n * DBL_EPSILON * reach * reach;
}

/*
 * Whether the convex hull of a and b surely has more area than limit,
 * worked out on their vertices (geom_convex_hull) far more cheaply than
 * GEOS's hull of a collection of their clones: most pairs that
 * merge_parts tries do not merge (six in seven of a 48 x 24 sphere's
 * nets), and for them GEOS is not asked.  "Surely": by more than the
 * rounding of either area (of the same hull, summed in another order;
 * GEOS may keep a point within rounding of a hull's edge, which changes
 * its area by less still) and a millionth besides, so that GEOS's hull
 * would fail convex_merge's test too.  False when unsure or when memory
 * is short (GEOS then decides, as it would have).
 */
static bool hull_surely_larger(GEOSContextHandle_t geos, const GEOSGeometry *a,
                               const GEOSGeometry *b, double limit)
{
    bool out_of_memory = false;
    ur_vec2 *pa, *pb;
    size_t na = vertices(geos, a, &pa, &out_of_memory);
    size_t nb = vertices(geos, b, &pb, &out_of_memory);
    size_t count = na + nb;
    ur_vec2 *points = na && nb ? malloc(count * sizeof *points) : NULL;
    ur_vec2 *hull = points ? malloc((count + 1) * sizeof *hull) : NULL;
    bool larger = false;
    if (hull) {
        memcpy(points, pa, na * sizeof *points);
        memcpy(points + na, pb, nb * sizeof *points);
        double reach = 0;
        for (size_t i = 0; i < count; i++)
            reach = fmax(reach, fmax(fabs(points[i].x), fabs(points[i].y)));
        size_t corners = geom_convex_hull(points, count, hull);
        double area = convex_area(hull, corners);
        larger = area > limit * (1 + 1e-6) + area_rounding(count, reach);
    }
    free(pa);
    free(pb);
    free(points);
    free(hull);
    return larger;
}

/*
 * The convex hull of a and b when it adds no area to them: then they share
 * an edge and their union is convex.  NULL otherwise.
 */
static GEOSGeometry *convex_merge(GEOSContextHandle_t geos, const GEOSGeometry *a,
                                  const GEOSGeometry *b)
{
    double sum = area_of(geos, a) + area_of(geos, b), limit = sum * (1 + 1e-9) + 1e-12;
    if (hull_surely_larger(geos, a, b, limit))
        return NULL;
    GEOSGeometry *pair[2] = {GEOSGeom_clone_r(geos, a), GEOSGeom_clone_r(geos, b)};
    GEOSGeometry *both =
        pair[0] && pair[1] ? GEOSGeom_createCollection_r(geos, GEOS_MULTIPOLYGON, pair, 2) : NULL;
    if (!both) {
        for (int k = 0; k < 2; k++)
            if (pair[k])
                GEOSGeom_destroy_r(geos, pair[k]);
        return NULL;
    }
    GEOSGeometry *hull = GEOSConvexHull_r(geos, both);
    GEOSGeom_destroy_r(geos, both);
    if (hull && area_of(geos, hull) <= limit)
        return hull;
    if (hull)
        GEOSGeom_destroy_r(geos, hull);
    return NULL;
}

/*
 * Merges convex parts two at a time while any two that touch make a convex
 * whole (Hertel and Mehlhorn's idea, greedily): a curved band of triangles
 * becomes about one quadrilateral per stretch of its arcs.  Each pair is
 * tried once per pass; passes repeat until none merges.  The parts' boxes
 * are kept beside them in boxes (room for every part), not asked of GEOS
 * for every pair.
 */
static void merge_parts(GEOSContextHandle_t geos, nest_shape *shape, double (*boxes)[4])
{
    for (size_t i = 0; i < shape->convex_count; i++)
        nest_box_of(geos, shape->convex[i], boxes[i]);
    bool merged = true;
    while (merged) {
        merged = false;
        for (size_t i = 0; i < shape->convex_count; i++) {
            for (size_t j = i + 1; j < shape->convex_count; j++) {
                if (!boxes_touch(boxes[i], boxes[j]))
                    continue;
                GEOSGeometry *hull = convex_merge(geos, shape->convex[i], shape->convex[j]);
                if (!hull)
                    continue;
                GEOSGeom_destroy_r(geos, shape->convex[i]);
                GEOSGeom_destroy_r(geos, shape->convex[j]);
                shape->convex[i] = hull;
                nest_box_of(geos, hull, boxes[i]);
                shape->convex[j] = shape->convex[--shape->convex_count];
                memcpy(boxes[j], boxes[shape->convex_count], sizeof boxes[j]);
                merged = true;
                j = i; /* the grown part may now merge with one already passed */
            }
        }
    }
}

/*
 * Shrinks each convex part by half of NEST_EXACT_FIT (mitred, so it keeps
 * its corners); a part too thin to shrink is kept as it is.  False when
 * GEOS fails.
 */
static bool shrink_parts(GEOSContextHandle_t geos, nest_shape *shape)
{
    GEOSBufferParams *params = GEOSBufferParams_create_r(geos);
    if (!params)
        return false;
    GEOSBufferParams_setJoinStyle_r(geos, params, GEOSBUF_JOIN_MITRE);
    GEOSBufferParams_setMitreLimit_r(geos, params, 10.0);
    bool shrunk = true;
    for (size_t k = 0; shrunk && k < shape->convex_count; k++) {
        GEOSGeometry *in =
            GEOSBufferWithParams_r(geos, shape->convex[k], params, -0.5 * NEST_EXACT_FIT);
        shrunk = in != NULL;
        if (in && GEOSGeomTypeId_r(geos, in) == GEOS_POLYGON && !GEOSisEmpty_r(geos, in)) {
            GEOSGeom_destroy_r(geos, shape->convex[k]);
            shape->convex[k] = in;
        } else if (in) {
            GEOSGeom_destroy_r(geos, in);
        }
    }
    GEOSBufferParams_destroy_r(geos, params);
    return shrunk;
}

/* Appends the triangles of a triangulation to the shape's convex parts (room made by the caller).
 */
static void take_triangles(GEOSContextHandle_t geos, const GEOSGeometry *triangles,
                           nest_shape *shape)
{
    int count = GEOSGetNumGeometries_r(geos, triangles);
    for (int k = 0; k < count; k++) {
        GEOSGeometry *triangle = GEOSGeom_clone_r(geos, GEOSGetGeometryN_r(geos, triangles, k));
        if (triangle)
            shape->convex[shape->convex_count++] = triangle;
    }
}

static bool grow_parts(nest_shape *shape, size_t more, size_t *room)
{
    if (shape->convex_count + more <= *room)
        return true;
    size_t wanted = 2 * (shape->convex_count + more);
    GEOSGeometry **grown = realloc(shape->convex, wanted * sizeof *grown);
    if (!grown)
        return false;
    shape->convex = grown;
    *room = wanted;
    return true;
}

/* Halves of a polygon's box beyond which a failed triangulation gives up. */
#define MOST_HALVINGS 12

/*
 * The polygon's triangles added to the shape's parts.  GEOS 3.11's
 * triangulation fails on some valid polygons ("unable to find a convex
 * corner", on long zigzag outlines such as a papercraft net's); cut in two
 * across its longer side, each half triangulates, and merge_parts joins
 * the triangles across the cut again.  UR_ERROR_INTERNAL (with no message)
 * when GEOS fails.
 */
static ur_status triangulate(GEOSContextHandle_t geos, const GEOSGeometry *polygon, int halvings,
                             nest_shape *shape, size_t *room, ur_error *error)
{
    GEOSGeometry *triangles = GEOSConstrainedDelaunayTriangulation_r(geos, polygon);
    if (triangles) {
        int count = GEOSGetNumGeometries_r(geos, triangles);
        bool grown = grow_parts(shape, count > 0 ? (size_t)count : 0, room);
        if (grown)
            take_triangles(geos, triangles, shape);
        GEOSGeom_destroy_r(geos, triangles);
        return grown ? UR_OK : ur_error_out_of_memory(error);
    }
    if (halvings >= MOST_HALVINGS)
        return UR_ERROR_INTERNAL;
    double box[4];
    nest_box_of(geos, polygon, box);
    bool across_x = box[2] - box[0] >= box[3] - box[1];
    double middle = across_x ? (box[0] + box[2]) / 2 : (box[1] + box[3]) / 2;
    ur_status status = UR_OK;
    for (int half = 0; status == UR_OK && half < 2; half++) {
        double x0 = box[0], y0 = box[1], x1 = box[2], y1 = box[3];
        if (across_x)
            *(half ? &x0 : &x1) = middle;
        else
            *(half ? &y0 : &y1) = middle;
        GEOSGeometry *part = GEOSClipByRect_r(geos, polygon, x0, y0, x1, y1);
        int count = part ? GEOSGetNumGeometries_r(geos, part) : -1;
        status = count >= 0 ? UR_OK : UR_ERROR_INTERNAL;
        for (int k = 0; status == UR_OK && k < count; k++) {
            const GEOSGeometry *piece = GEOSGetGeometryN_r(geos, part, k);
            if (GEOSGeomTypeId_r(geos, piece) == GEOS_POLYGON && !GEOSisEmpty_r(geos, piece))
                status = triangulate(geos, piece, halvings + 1, shape, room, error);
        }
        if (part)
            GEOSGeom_destroy_r(geos, part);
    }
    return status;
}

/* The polygon without its holes; NULL on failure. */
static GEOSGeometry *filled_shell(GEOSContextHandle_t geos, const GEOSGeometry *polygon)
{
    const GEOSGeometry *ring = GEOSGetExteriorRing_r(geos, polygon);
    GEOSGeometry *shell = ring ? GEOSGeom_clone_r(geos, ring) : NULL;
    GEOSGeometry *filled = shell ? GEOSGeom_createPolygon_r(geos, shell, NULL, 0) : NULL;
    if (shell && !filled)
        GEOSGeom_destroy_r(geos, shell);
    return filled;
}

/*
 * The polygon's triangles (GEOS's constrained Delaunay triangulation),
 * merged into convex parts (shrunk later: see coarseness).
 */
static ur_status convex_parts(GEOSContextHandle_t geos, const GEOSGeometry *polygon,
                              nest_shape *shape, ur_error *error)
{
    size_t room = 0;
    ur_status status = triangulate(geos, polygon, 0, shape, &room, error);
    if (status == UR_ERROR_INTERNAL && GEOSGetNumInteriorRings_r(geos, polygon) > 0) {
        /*
         * GEOS cannot always join holes that touch the shell to it, as
         * growing a piece makes of the gaps between its glue tabs; then the
         * parts cover the holes too, which only keeps other pieces out of
         * them.
         */
        for (size_t k = 0; k < shape->convex_count; k++) /* what the first try made */
            GEOSGeom_destroy_r(geos, shape->convex[k]);
        shape->convex_count = 0;
        GEOSGeometry *filled = filled_shell(geos, polygon);
        status = filled ? triangulate(geos, filled, 0, shape, &room, error) : UR_ERROR_INTERNAL;
        if (filled)
            GEOSGeom_destroy_r(geos, filled);
    }
    if (status == UR_ERROR_INTERNAL)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not triangulate a piece");
    if (status != UR_OK)
        return status;
    double(*boxes)[4] = malloc((shape->convex_count + 1) * sizeof *boxes);
    if (!boxes)
        return ur_error_out_of_memory(error);
    merge_parts(geos, shape, boxes);
    free(boxes);
    return UR_OK;
}

/* Frees a shape's polygon and convex parts, keeping the rest. */
static void drop_parts(GEOSContextHandle_t geos, nest_shape *shape)
{
    for (size_t k = 0; k < shape->convex_count; k++)
        GEOSGeom_destroy_r(geos, shape->convex[k]);
    free(shape->convex);
    shape->convex = NULL;
    shape->convex_count = 0;
    if (shape->polygon)
        GEOSGeom_destroy_r(geos, shape->polygon);
    shape->polygon = NULL;
}

/*
 * The shape's polygon (the piece's, made valid, then grown, simplified
 * and closed) and its convex parts, made again; not shrunk yet.
 */
static ur_status shape_parts(GEOSContextHandle_t geos, const GEOSGeometry *valid, double grow,
                             double tolerance, double closing, nest_shape *shape, ur_error *error)
{
    drop_parts(geos, shape);
    shape->polygon = valid ? grown(geos, valid, grow, tolerance, closing) : NULL;
    if (!shape->polygon)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not prepare a piece to nest");
    return convex_parts(geos, shape->polygon, shape, error);
}

/* The shape's convex parts shrunk, once they are the ones kept. */
static ur_status shrunk(GEOSContextHandle_t geos, nest_shape *shape, ur_error *error)
{
    if (!shrink_parts(geos, shape))
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not shrink a piece's parts");
    return UR_OK;
}

/*
 * How coarsely the piece is simplified and closed: first as
 * nest_shape_make says, then coarser while its unturned shape (made here
 * into shape) has more than MOST_PARTS convex parts.
 */
static ur_status coarseness(GEOSContextHandle_t geos, const ur_piece *piece, double grow,
                            bool holes, nest_shape *shape, ur_error *error)
{
    ur_box unturned = ur_box_empty();
    for (size_t i = 0; i < piece->paths[0].count; i++)
        ur_box_add(&unturned, piece->paths[0].points[i]);
    double size = hypot(ur_box_width(unturned), ur_box_height(unturned));
    size_t points = 0;
    for (size_t k = 0; k < piece->path_count; k++)
        points += piece->paths[k].count;
    double tolerance = points > SIMPLIFY_ABOVE ? fmax(0.05, 2e-3 * size) : 0.0;
    double closing = points > SIMPLIFY_ABOVE ? CLOSING * size : 0.0;
    GEOSGeometry *exact;
    ur_status status = piece_polygon(geos, piece, 0.0, holes, &exact, error);
    shape->area = area_of(geos, exact);
    /* made valid once for every coarseness tried */
    GEOSGeometry *valid = status == UR_OK && exact ? GEOSMakeValid_r(geos, exact) : NULL;
    if (status == UR_OK)
        status = shape_parts(geos, valid, grow, tolerance, closing, shape, error);
    while (status == UR_OK && shape->convex_count > MOST_PARTS && tolerance > 0 &&
           2 * tolerance <= COARSEST * size) {
        tolerance *= 2;
        closing *= 2;
        status = shape_parts(geos, valid, grow, tolerance, closing, shape, error);
    }
    if (valid)
        GEOSGeom_destroy_r(geos, valid);
    if (exact)
        GEOSGeom_destroy_r(geos, exact);
    shape->tolerance = tolerance;
    shape->closing = closing;
    return status;
}

int nest_turn_xy(double *x, double *y, void *cosine_sine)
{
    const double *cs = cosine_sine;
    double tx = cs[0] * *x - cs[1] * *y, ty = cs[1] * *x + cs[0] * *y;
    *x = tx;
    *y = ty;
    return 1;
}

/*
 * Another turn of the same piece: like's polygon and shrunk parts turned
 * to angle.  Making them again from the turned piece cost as much as the
 * first turn and gave the same shape to rounding, since every turn is
 * simplified alike.
 */
static ur_status turned_copy(GEOSContextHandle_t geos, const nest_shape *like, double angle,
                             nest_shape *shape, ur_error *error)
{
    shape->area = like->area;
    shape->tolerance = like->tolerance;
    shape->closing = like->closing;
    double cs[2] = {cos(angle - like->angle), sin(angle - like->angle)};
    shape->convex = calloc(like->convex_count ? like->convex_count : 1, sizeof *shape->convex);
    if (!shape->convex)
        return ur_error_out_of_memory(error);
    shape->polygon = GEOSGeom_transformXY_r(geos, like->polygon, nest_turn_xy, cs);
    bool turned = shape->polygon != NULL;
    for (size_t k = 0; turned && k < like->convex_count; k++) {
        shape->convex[k] = GEOSGeom_transformXY_r(geos, like->convex[k], nest_turn_xy, cs);
        turned = shape->convex[k] != NULL;
        shape->convex_count += turned;
    }
    if (!turned) {
        drop_parts(geos, shape);
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not turn a piece's shape");
    }
    return UR_OK;
}

/*
 * The shape of a piece's first turn: its coarseness decided unturned, the
 * parts made so turned to angle (as turned_copy turns them: making them
 * again from the turned piece cost as much again, a twentieth of a
 * papercraft sphere's run, for the same shape to rounding), then shrunk.
 * Only the parts kept are shrunk (each on its own, so the same whenever it
 * is done): the shapes coarseness gives up have a hundred parts or more,
 * and shrinking each is a GEOS buffer.
 */
static ur_status first_turn(GEOSContextHandle_t geos, const ur_piece *piece, double angle,
                            double grow, bool holes, nest_shape *shape, ur_error *error)
{
    ur_status status = coarseness(geos, piece, grow, holes, shape, error);
    if (status == UR_OK && angle != 0.0) {
        nest_shape unturned = *shape; /* its parts taken over */
        unturned.angle = 0.0;
        shape->polygon = NULL;
        shape->convex = NULL;
        shape->convex_count = 0;
        status = turned_copy(geos, &unturned, angle, shape, error);
        drop_parts(geos, &unturned);
    }
    return status == UR_OK ? shrunk(geos, shape, error) : status;
}

/* A closed ring of points moved by at, as a GEOS polygon; NULL on failure. */
static GEOSGeometry *polygon_of(GEOSContextHandle_t geos, const ur_vec2 *points, size_t count,
                                ur_vec2 at)
{
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)count + 1, 2);
    if (!sequence)
        return NULL;
    for (size_t i = 0; i <= count; i++)
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, points[i % count].x + at.x,
                             points[i % count].y + at.y);
    GEOSGeometry *ring = GEOSGeom_createLinearRing_r(geos, sequence);
    return ring ? GEOSGeom_createPolygon_r(geos, ring, NULL, 0) : NULL;
}

/*
 * Which half of the turn an edge's direction lies in, counting from
 * straight down: 0 for (-90, 90] degrees, 1 for (90, 270].  Edges of a
 * convex polygon walked counter-clockwise from its lowest-leftmost vertex
 * come in that order, and within a half two directions compare by their
 * cross product.
 */
static int half_turn(ur_vec2 d)
{
    return d.x > 0 || (d.x == 0 && d.y > 0) ? 0 : 1;
}

/* Whether direction d comes before e, both walked from straight down. */
static bool turns_before(ur_vec2 d, ur_vec2 e, bool *parallel)
{
    int hd = half_turn(d), he = half_turn(e);
    double cross = ur_vec2_cross(d, e);
    *parallel = hd == he && cross == 0;
    return hd != he ? hd < he : cross > 0;
}

/*
 * The sum of two convex polygons (each counter-clockwise from its leftmost,
 * then lowest, vertex, as geom_convex_hull gives them) by merging their
 * edges in the order of their directions, into sum (room for na + nb);
 * its count.  Each vertex is a sum of one vertex of each, as the hull of
 * all such sums would have it, in time linear in na + nb.
 */
static size_t merge_edges(const ur_vec2 *a, size_t na, const ur_vec2 *b, size_t nb, ur_vec2 *sum)
{
    size_t i = 0, j = 0, count = 0;
    while (i < na || j < nb) {
        sum[count++] = ur_vec2_make(a[i % na].x + b[j % nb].x, a[i % na].y + b[j % nb].y);
        if (count > na + nb)
            return 0; /* not convex after all: cannot happen with hulls, but never loop */
        bool parallel = false;
        ur_vec2 da = ur_vec2_sub(a[(i + 1) % na], a[i % na]);
        ur_vec2 db = ur_vec2_sub(b[(j + 1) % nb], b[j % nb]);
        bool take_a = j == nb || (i < na && turns_before(da, db, &parallel));
        if (take_a || parallel)
            i++;
        if (!take_a || parallel)
            j++;
    }
    return count;
}

/* The hull of every sum of a point of a and one of b, into sum (room for na * nb); its count. */
static size_t hull_of_sums(const ur_vec2 *a, size_t na, const ur_vec2 *b, size_t nb, ur_vec2 *sum,
                           bool *out_of_memory)
{
    ur_vec2 *all = malloc((na * nb + 1) * sizeof *all);
    if (!all) {
        *out_of_memory = true;
        return 0;
    }
    for (size_t i = 0; i < na; i++)
        for (size_t j = 0; j < nb; j++)
            all[i * nb + j] = ur_vec2_make(a[i].x + b[j].x, a[i].y + b[j].y);
    size_t count = geom_convex_hull(all, na * nb, sum);
    free(all);
    return count;
}

static void hulls_free(nest_hull *hulls, size_t count)
{
    for (size_t k = 0; hulls && k < count; k++)
        free(hulls[k].points);
    free(hulls);
}

/*
 * The hulls of a shape's convex parts, each turned half round first when
 * negated (b's parts in a + (-b)).  NULL when memory runs out.
 */
static nest_hull *part_hulls(GEOSContextHandle_t geos, const nest_shape *shape, bool negated)
{
    nest_hull *hulls = calloc(shape->convex_count + 1, sizeof *hulls);
    bool out_of_memory = !hulls;
    for (size_t k = 0; hulls && k < shape->convex_count && !out_of_memory; k++) {
        ur_vec2 *points;
        size_t count = vertices(geos, shape->convex[k], &points, &out_of_memory);
        for (size_t i = 0; negated && i < count; i++)
            points[i] = ur_vec2_make(-points[i].x, -points[i].y);
        hulls[k].points = count ? malloc((count + 1) * sizeof *hulls[k].points) : NULL;
        if (count && !hulls[k].points)
            out_of_memory = true;
        else if (count)
            hulls[k].count = geom_convex_hull(points, count, hulls[k].points);
        free(points);
    }
    if (out_of_memory) {
        hulls_free(hulls, shape->convex_count);
        return NULL;
    }
    return hulls;
}

static ur_status make_hulls(GEOSContextHandle_t geos, nest_shape *shape, ur_error *error)
{
    shape->hulls = part_hulls(geos, shape, false);
    shape->negated = shape->hulls ? part_hulls(geos, shape, true) : NULL;
    return shape->negated ? UR_OK : ur_error_out_of_memory(error);
}

ur_status nest_shape_make(GEOSContextHandle_t geos, const ur_piece *piece, double angle,
                          double grow, bool holes, const nest_shape *like, nest_shape *shape,
                          ur_error *error)
{
    memset(shape, 0, sizeof *shape);
    shape->angle = angle;
    ur_transform2 turn = ur_transform2_make(angle, ur_vec2_make(0, 0));
    shape->box = ur_box_empty();
    for (size_t i = 0; i < piece->paths[0].count; i++)
        ur_box_add(&shape->box, ur_transform2_apply(turn, piece->paths[0].points[i]));
    /*
     * Outlines of a few dozen points are nested as they are, so exact fits
     * stay exact; longer ones (curves) are simplified to 2 per mille of
     * their size, at least 0.05 mm, and grown by as much: a curved band
     * splits into a few dozen convex parts instead of thousands, at the
     * cost of that much more room round it.  The size is the unturned
     * outline's, so that every turn is simplified alike and the shapes of
     * a piece's turns are one shape turned (nest.c turns no-fit polygons):
     * the first turn decides it (coarseness), the others are its shape
     * turned.
     */
    ur_status status = like ? turned_copy(geos, like, angle, shape, error)
                            : first_turn(geos, piece, angle, grow, holes, shape, error);
    if (status == UR_OK)
        status = make_hulls(geos, shape, error);
    if (status != UR_OK)
        return status;
    double reach[4];
    nest_box_of(geos, shape->polygon, reach);
    shape->reach = (ur_box){{reach[0], reach[1]}, {reach[2], reach[3]}};
    return UR_OK;
}

void nest_shape_free(GEOSContextHandle_t geos, nest_shape *shape)
{
    hulls_free(shape->hulls, shape->convex_count);
    hulls_free(shape->negated, shape->convex_count);
    for (size_t k = 0; k < shape->convex_count; k++)
        GEOSGeom_destroy_r(geos, shape->convex[k]);
    free(shape->convex);
    if (shape->polygon)
        GEOSGeom_destroy_r(geos, shape->polygon);
    memset(shape, 0, sizeof *shape);
}

/*
 * The convex hull of a + (-b) for two convex polygons (their hulls, b's
 * negated), into sum (room for max(na * nb, na + nb)): the sum of their
 * hulls, edge by edge (the hull of all the sums of their vertices took an
 * eighth of a papercraft sphere's nesting, and GEOS's hull of them more).
 * Its count: below 3 when it has no area.
 */
static size_t convex_sum(const nest_hull *a, const nest_hull *b, ur_vec2 *sum, bool *out_of_memory)
{
    size_t ha = a->count, hb = b->count;
    if (!ha || !hb)
        return 0;
    return ha >= 3 && hb >= 3 ? merge_edges(a->points, ha, b->points, hb, sum)
                              : hull_of_sums(a->points, ha, b->points, hb, sum, out_of_memory);
}

void nest_sum_list_free(nest_sum_list *sums)
{
    if (!sums)
        return;
    free(sums->first);
    free(sums->points);
    free(sums->area);
    free(sums->box);
    free(sums);
}

/* A list with room for count sums of points in all; NULL without memory. */
static nest_sum_list *sum_list_new(size_t count, size_t points)
{
    nest_sum_list *sums = calloc(1, sizeof *sums);
    if (!sums)
        return NULL;
    sums->first = malloc((count + 1) * sizeof *sums->first);
    sums->points = malloc((points ? points : 1) * sizeof *sums->points);
    sums->area = malloc((count ? count : 1) * sizeof *sums->area);
    sums->box = malloc((count ? count : 1) * sizeof *sums->box);
    if (!sums->first || !sums->points || !sums->area || !sums->box) {
        nest_sum_list_free(sums);
        return NULL;
    }
    sums->first[0] = 0;
    return sums;
}

/* Fills in sum k's area and box from its points. */
static void measure_sum(nest_sum_list *sums, size_t k)
{
    const ur_vec2 *points = sums->points + sums->first[k];
    size_t count = sums->first[k + 1] - sums->first[k];
    sums->area[k] = convex_area(points, count);
    sums->box[k] = ur_box_empty();
    for (size_t i = 0; i < count; i++)
        ur_box_add(&sums->box[k], points[i]);
}

int nest_larger_first(const void *a, const void *b)
{
    const nest_sized *x = a, *y = b; /* each element begins with its nest_sized */
    if (x->area != y->area)
        return x->area > y->area ? -1 : 1;
    return (x->index > y->index) - (x->index < y->index);
}

/*
 * The sums, largest first: room.c cuts the sums out of a room largest
 * first (with those of other pairs, ties in this order) and skips those
 * that no longer meet it, and a large sum cut early leaves more of the
 * smaller ones nothing to take.  NULL without memory.
 */
static nest_sum_list *largest_first(const nest_sum_list *sums)
{
    nest_sum_list *sorted = sum_list_new(sums->count, sums->first[sums->count]);
    nest_sized *sized = malloc((sums->count + 1) * sizeof *sized);
    if (!sorted || !sized) {
        free(sized);
        nest_sum_list_free(sorted);
        return NULL;
    }
    for (size_t k = 0; k < sums->count; k++)
        sized[k] = (nest_sized){sums->area[k], k};
    qsort(sized, sums->count, sizeof *sized, nest_larger_first);
    for (size_t k = 0; k < sums->count; k++) {
        size_t from = sized[k].index, n = sums->first[from + 1] - sums->first[from];
        memcpy(sorted->points + sorted->first[k], sums->points + sums->first[from],
               n * sizeof *sorted->points);
        sorted->first[k + 1] = sorted->first[k] + n;
        sorted->area[k] = sums->area[from];
        sorted->box[k] = sums->box[from];
    }
    sorted->count = sums->count;
    free(sized);
    return sorted;
}

/* The most points any sum of a's part i and b's part j can have. */
static size_t sum_room(const nest_hull *a, const nest_hull *b)
{
    size_t ha = a->count, hb = b->count;
    return ha * hb > ha + hb ? ha * hb : ha + hb;
}

/* Every sum of a's hulls and b's negated hulls, in the order made; NULL without memory. */
static nest_sum_list *all_sums(const nest_shape *a, const nest_shape *b, bool *out_of_memory)
{
    size_t most = 0, widest = 0;
    for (size_t i = 0; i < a->convex_count; i++)
        for (size_t j = 0; j < b->convex_count; j++) {
            size_t room = sum_room(&a->hulls[i], &b->negated[j]);
            most += room;
            widest = room > widest ? room : widest;
        }
    nest_sum_list *sums = sum_list_new(a->convex_count * b->convex_count, most);
    ur_vec2 *sum = malloc((widest + 1) * sizeof *sum);
    *out_of_memory = !sums || !sum;
    for (size_t i = 0; !*out_of_memory && i < a->convex_count; i++)
        for (size_t j = 0; !*out_of_memory && j < b->convex_count; j++) {
            size_t count = convex_sum(&a->hulls[i], &b->negated[j], sum, out_of_memory);
            if (count < 3) /* no area (two parts' edges in line): nothing to add */
                continue;
            size_t k = sums->count++;
            memcpy(sums->points + sums->first[k], sum, count * sizeof *sum);
            sums->first[k + 1] = sums->first[k] + count;
            measure_sum(sums, k);
        }
    free(sum);
    if (*out_of_memory) {
        nest_sum_list_free(sums);
        return NULL;
    }
    return sums;
}

nest_sum_list *nest_sums(const nest_shape *a, const nest_shape *b, bool *out_of_memory)
{
    nest_sum_list *made = all_sums(a, b, out_of_memory);
    nest_sum_list *sorted = made ? largest_first(made) : NULL;
    nest_sum_list_free(made);
    *out_of_memory = *out_of_memory || !sorted;
    return sorted;
}

nest_sum_list *nest_sums_turned(const nest_sum_list *sums, const double cs[2])
{
    nest_sum_list *turned = sum_list_new(sums->count, sums->first[sums->count]);
    if (!turned)
        return NULL;
    memcpy(turned->first, sums->first, (sums->count + 1) * sizeof *turned->first);
    for (size_t i = 0; i < sums->first[sums->count]; i++) {
        ur_vec2 p = sums->points[i];
        turned->points[i] = ur_vec2_make(cs[0] * p.x - cs[1] * p.y, cs[1] * p.x + cs[0] * p.y);
    }
    turned->count = sums->count;
    for (size_t k = 0; k < sums->count; k++)
        measure_sum(turned, k);
    return turned;
}

GEOSGeometry *nest_sum_polygon(GEOSContextHandle_t geos, const nest_sum_list *sums, size_t k,
                               ur_vec2 at)
{
    return polygon_of(geos, sums->points + sums->first[k], sums->first[k + 1] - sums->first[k], at);
}

GEOSGeometry *nest_union_of_sums(GEOSContextHandle_t geos, const nest_sum_list *sums)
{
    ur_vec2 origin = {0, 0};
    if (sums->count == 1) /* one convex sum: nothing to unite */
        return nest_sum_polygon(geos, sums, 0, origin);
    GEOSGeometry **parts = calloc(sums->count + 1, sizeof *parts);
    bool failed = !parts;
    for (size_t k = 0; !failed && k < sums->count; k++)
        failed = !(parts[k] = nest_sum_polygon(geos, sums, k, origin));
    GEOSGeometry *all = failed ? NULL
                               : GEOSGeom_createCollection_r(geos, GEOS_GEOMETRYCOLLECTION, parts,
                                                             (unsigned)sums->count);
    if (!all)
        for (size_t k = 0; parts && k < sums->count; k++)
            if (parts[k])
                GEOSGeom_destroy_r(geos, parts[k]);
    free(parts);
    GEOSGeometry *united = all ? GEOSUnaryUnion_r(geos, all) : NULL;
    if (all)
        GEOSGeom_destroy_r(geos, all);
    return united;
}
