/*
 * split_part.c: a flat part from a file (unroll nest) too long for any
 * sheet, cut into the fewest parts that fit (ur_part_split).
 *
 * The part is turned level (its smallest enclosing rectangle along x, as
 * nesting first turns it) and cut by k - 1 straight lines across its
 * length, k = ceil(length / room).  Even shares would leave each part
 * length / k long; the slack k * room - length lets every cut move up to
 * slack / 2k either way, and within that window it goes where it is
 * shortest (where the part is narrowest), so the splice is short.
 *
 * The cuts are noded together with the part's rings and polygonized
 * (GEOS), so that the two sides of a cut share their points exactly: each
 * new net carries its points as 3D points (x, y, id) and
 * ur_net_list_find_seams pairs the sides of every cut, for joints and
 * labels, as it pairs the cuts of a mesh.  Holes not crossed by a cut stay
 * holes of the part they fall in.
 */
#include "unroll/nest.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <geos_c.h>

#include "../geom/geos_polygon.h"
#include "../base/c_locale.h"

/* Positions tried for each cut across its window. */
#define CUT_SAMPLES 41

typedef struct splitter {
    GEOSContextHandle_t geos;
    GEOSGeometry *part;  /* the polygon with its holes, in the part's coordinates */
    ur_transform2 level; /* part coordinates to level ones */
    ur_transform2 back;  /* level coordinates to the part's */
    ur_box box;          /* of the level outline */
    ur_error *error;
} splitter;

static ur_status geos_failed(ur_error *error, const char *what)
{
    return ur_error_set(error, UR_ERROR_INTERNAL, "splitting a part: GEOS failed %s", what);
}

/* The part's polygon: outline and every other closed CUT path inside it as a hole. */
static GEOSGeometry *part_polygon(GEOSContextHandle_t geos, const ur_piece *part)
{
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, part->paths[0].points, part->paths[0].count);
    for (size_t k = 1; polygon && k < part->path_count; k++) {
        const ur_path *path = &part->paths[k];
        if (path->op != UR_OP_CUT || !path->closed || path->count < 3)
            continue;
        GEOSGeometry *hole = geos_polygon_of_ring(geos, path->points, path->count);
        GEOSGeometry *less = hole ? GEOSDifference_r(geos, polygon, hole) : NULL;
        GEOSGeom_destroy_r(geos, hole);
        GEOSGeom_destroy_r(geos, polygon);
        polygon = less;
    }
    return polygon;
}

/* The line across the level part at x, in part coordinates, reaching past it. */
static GEOSGeometry *cut_line(const splitter *s, double x)
{
    double reach = 1 + ur_box_height(s->box);
    ur_vec2 a = ur_transform2_apply(s->back, ur_vec2_make(x, s->box.min.y - reach));
    ur_vec2 b = ur_transform2_apply(s->back, ur_vec2_make(x, s->box.max.y + reach));
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(s->geos, 2, 2);
    if (!sequence)
        return NULL;
    GEOSCoordSeq_setXY_r(s->geos, sequence, 0, a.x, a.y);
    GEOSCoordSeq_setXY_r(s->geos, sequence, 1, b.x, b.y);
    return GEOSGeom_createLineString_r(s->geos, sequence);
}

/* How long a cut at level x would be: the line's length inside the part. */
static double cut_length(const splitter *s, double x)
{
    GEOSGeometry *line = cut_line(s, x);
    GEOSGeometry *inside = line ? GEOSIntersection_r(s->geos, line, s->part) : NULL;
    double length = INFINITY;
    if (!inside || !GEOSLength_r(s->geos, inside, &length))
        length = INFINITY;
    GEOSGeom_destroy_r(s->geos, line);
    GEOSGeom_destroy_r(s->geos, inside);
    return length;
}

/* Where each of the parts - 1 cuts goes, in level x. */
static void place_cuts(const splitter *s, size_t parts, double room, double *cuts)
{
    double length = ur_box_width(s->box);
    double share = length / (double)parts;
    double slack = fmax(0, (double)parts * room - length) / (2 * (double)parts);
    for (size_t j = 1; j < parts; j++) {
        double ideal = s->box.min.x + share * (double)j, best = ideal;
        double shortest = cut_length(s, ideal);
        for (int k = 0; k < CUT_SAMPLES && slack > 0; k++) {
            double x = ideal - slack + 2 * slack * k / (CUT_SAMPLES - 1);
            double here = cut_length(s, x);
            if (here < shortest - 1e-9 ||
                (fabs(here - shortest) <= 1e-9 && fabs(x - ideal) < fabs(best - ideal))) {
                shortest = here;
                best = x;
            }
        }
        cuts[j - 1] = best;
    }
}

/* The part's rings and the cuts, noded into one set of lines and made into faces. */
static GEOSGeometry *faces(const splitter *s, const double *cuts, size_t cut_count)
{
    GEOSGeometry *lines = GEOSBoundary_r(s->geos, s->part);
    for (size_t j = 0; lines && j < cut_count; j++) {
        GEOSGeometry *line = cut_line(s, cuts[j]);
        GEOSGeometry *both = line ? GEOSUnion_r(s->geos, lines, line) : NULL;
        GEOSGeom_destroy_r(s->geos, line);
        GEOSGeom_destroy_r(s->geos, lines);
        lines = both;
    }
    if (!lines)
        return NULL;
    const GEOSGeometry *list[1] = {lines};
    GEOSGeometry *polygons = GEOSPolygonize_r(s->geos, list, 1);
    GEOSGeom_destroy_r(s->geos, lines);
    return polygons;
}

/* A ring of GEOS as a counter-clockwise ring of points, the closing point dropped. */
static ur_status ring_points(GEOSContextHandle_t geos, const GEOSGeometry *ring, bool clockwise,
                             ur_points *out, ur_error *error)
{
    const GEOSCoordSequence *sequence = GEOSGeom_getCoordSeq_r(geos, ring);
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size) || size < 4)
        return geos_failed(error, "reading a ring");
    ur_status status = UR_OK;
    for (unsigned k = 0; status == UR_OK && k + 1 < size; k++) {
        double x, y;
        GEOSCoordSeq_getXY_r(geos, sequence, k, &x, &y);
        status = ur_points_push(out, ur_vec2_make(x, y), error);
    }
    double area = ur_polygon_signed_area(out->items, out->count);
    if (status == UR_OK && (area < 0) != clockwise)
        ur_points_reverse(out->items, out->count);
    return status;
}

/* One face of the cut part as a net (3D points at height id) and a piece with its holes. */
static ur_status face_part(const splitter *s, const GEOSGeometry *face, const ur_piece *part,
                           size_t index, double id, ur_net *net, ur_piece *piece)
{
    memset(net, 0, sizeof *net);
    memset(piece, 0, sizeof *piece);
    ur_points ring = {0};
    const GEOSGeometry *shell = GEOSGetExteriorRing_r(s->geos, face);
    ur_status status = shell ? ring_points(s->geos, shell, false, &ring, s->error)
                             : geos_failed(s->error, "reading a face");
    if (status == UR_OK) {
        c_snprintf(net->name, sizeof net->name, "%.24s.%zu", part->name, index + 1);
        net->outline = ring.items;
        net->outline_count = ring.count;
        ring = (ur_points){0};
        net->outline_3d = ur_alloc_array(net->outline_count, sizeof *net->outline_3d, s->error);
        status = net->outline_3d ? UR_OK : UR_ERROR_MEMORY;
    }
    for (size_t i = 0; status == UR_OK && i < net->outline_count; i++)
        net->outline_3d[i] = (ur_vec3){net->outline[i].x, net->outline[i].y, id};
    if (status == UR_OK) {
        double area = 0;
        GEOSArea_r(s->geos, face, &area);
        net->area_3d = net->flat_area = area;
        ur_allowance_options options = {false};
        status = ur_piece_from_net(net, &options, piece, s->error);
    }
    int holes = status == UR_OK ? GEOSGetNumInteriorRings_r(s->geos, face) : 0;
    for (int h = 0; status == UR_OK && h < holes; h++) {
        ur_points hole = {0};
        status =
            ring_points(s->geos, GEOSGetInteriorRingN_r(s->geos, face, h), true, &hole, s->error);
        if (status == UR_OK)
            status = ur_piece_add_path(piece, UR_OP_CUT, hole.items, hole.count, true, s->error);
        ur_points_free(&hole);
    }
    ur_points_free(&ring);
    return status;
}

/* The faces that are the part's (not its holes), as nets and pieces appended to out. */
static ur_status collect(const splitter *s, const GEOSGeometry *all, const ur_piece *part,
                         double id, ur_split_parts *out)
{
    int count = GEOSGetNumGeometries_r(s->geos, all);
    ur_net *nets = realloc(out->nets.nets, (out->nets.count + (size_t)count + 1) * sizeof *nets);
    if (nets)
        out->nets.nets = nets;
    ur_piece *pieces = realloc(out->pieces, (out->nets.count + (size_t)count + 1) * sizeof *pieces);
    if (pieces)
        out->pieces = pieces;
    if (!nets || !pieces)
        return ur_error_out_of_memory(s->error);
    ur_status status = UR_OK;
    size_t index = 0;
    for (int k = 0; status == UR_OK && k < count; k++) {
        const GEOSGeometry *face = GEOSGetGeometryN_r(s->geos, all, k);
        GEOSGeometry *inner = face ? GEOSPointOnSurface_r(s->geos, face) : NULL;
        char inside = inner ? GEOSCovers_r(s->geos, s->part, inner) : 2;
        GEOSGeom_destroy_r(s->geos, inner);
        if (inside == 2)
            return geos_failed(s->error, "telling a face from a hole");
        if (!inside)
            continue; /* one of the part's holes */
        status =
            face_part(s, face, part, index++, id, &nets[out->nets.count], &pieces[out->nets.count]);
        out->nets.count++; /* freed with the rest, whole or not */
    }
    return status;
}

ur_status ur_part_split(const ur_piece *part, double room_length, double room_width, double id,
                        ur_split_parts *out, ur_error *error)
{
    if (part->path_count == 0 || !part->paths[0].closed || part->paths[0].count < 3 ||
        !(room_length > 0) || !(room_width > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "piece %s cannot be split", part->name);
    double length, width;
    ur_status status =
        ur_outline_level_size(part->paths[0].points, part->paths[0].count, &length, &width, error);
    if (status != UR_OK)
        return status;
    if (width > room_width)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece %s is %.1f mm wide, wider than the %.1f mm a sheet leaves "
                            "it: cutting it across its length cannot make it fit",
                            part->name, width, room_width);
    splitter s = {.geos = GEOS_init_r(), .error = error};
    if (!s.geos)
        return geos_failed(error, "to start");
    double angle = ur_outline_level_angle(part->paths[0].points, part->paths[0].count);
    s.level = ur_transform2_make(angle, ur_vec2_make(0, 0));
    s.back = ur_transform2_make(-angle, ur_vec2_make(0, 0));
    s.box = ur_box_empty();
    for (size_t i = 0; i < part->paths[0].count; i++)
        ur_box_add(&s.box, ur_transform2_apply(s.level, part->paths[0].points[i]));
    s.part = part_polygon(s.geos, part);
    size_t parts = (size_t)fmax(1, ceil(length / room_length - 1e-9));
    double *cuts = calloc(parts, sizeof *cuts);
    GEOSGeometry *all = NULL;
    if (!s.part)
        status = geos_failed(error, "making the part's polygon");
    else if (!cuts)
        status = ur_error_out_of_memory(error);
    if (status == UR_OK) {
        place_cuts(&s, parts, room_length, cuts);
        all = faces(&s, cuts, parts - 1);
        status = all ? collect(&s, all, part, id, out) : geos_failed(error, "cutting the part");
    }
    free(cuts);
    GEOSGeom_destroy_r(s.geos, all);
    GEOSGeom_destroy_r(s.geos, s.part);
    GEOS_finish_r(s.geos);
    return status;
}

void ur_split_parts_free(ur_split_parts *parts)
{
    for (size_t k = 0; k < parts->nets.count; k++)
        ur_piece_free(&parts->pieces[k]);
    free(parts->pieces);
    ur_net_list_free(&parts->nets);
    memset(parts, 0, sizeof *parts);
}
