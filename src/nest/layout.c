/*
 * layout.c: places pieces on sheets in rows (shelves), top to bottom.
 *
 * Each piece is turned so that its smallest enclosing rectangle (GEOS) lies
 * with its long side horizontal, or a quarter turn from that when only then
 * it fits.  Pieces go tallest first, left to right, a new row when the row is
 * full and a new sheet when the sheet is.  The command nests true shapes
 * (nest.c); this quick layout stays for callers that want rows, such as
 * bench_develop.
 */
#include "nest_internal.h"

#include "../geom/hull.h"

#include <stdlib.h>
#include <string.h>

/*
 * The hull's edge direction whose enclosing rectangle has the least area
 * (a minimum-area rectangle has a side on the hull), as the angle of its
 * longer side; area gets that area.  GEOS's MinimumRotatedRectangle is the
 * narrowest rectangle before GEOS 3.12, which can be longer than a sheet
 * that the smallest one fits: a Blender cylinder's net 233 x 416 mm
 * against 240 x 372 mm on A3.
 */
static double least_area_angle(GEOSContextHandle_t geos, const GEOSGeometry *points, double *area)
{
    *area = INFINITY;
    GEOSGeometry *hull = GEOSConvexHull_r(geos, points);
    const GEOSGeometry *ring = hull && GEOSGeomTypeId_r(geos, hull) == GEOS_POLYGON
                                   ? GEOSGetExteriorRing_r(geos, hull)
                                   : NULL;
    const GEOSCoordSequence *sequence = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
    unsigned count = 0;
    double best = 0.0;
    if (sequence && GEOSCoordSeq_getSize_r(geos, sequence, &count))
        for (unsigned i = 0; i + 1 < count; i++) {
            double x0, y0, x1, y1;
            GEOSCoordSeq_getXY_r(geos, sequence, i, &x0, &y0);
            GEOSCoordSeq_getXY_r(geos, sequence, i + 1, &x1, &y1);
            double length = hypot(x1 - x0, y1 - y0);
            if (!(length > 0))
                continue;
            double ux = (x1 - x0) / length, uy = (y1 - y0) / length;
            double low = 0, high = 0, across = 0;
            for (unsigned j = 0; j + 1 < count; j++) {
                double x, y;
                GEOSCoordSeq_getXY_r(geos, sequence, j, &x, &y);
                double along = (x - x0) * ux + (y - y0) * uy;
                double side = fabs((x - x0) * uy - (y - y0) * ux);
                low = fmin(low, along), high = fmax(high, along), across = fmax(across, side);
            }
            if ((high - low) * across < *area) {
                *area = (high - low) * across;
                best = atan2(uy, ux) + (high - low >= across ? 0.0 : M_PI / 2);
            }
        }
    if (hull)
        GEOSGeom_destroy_r(geos, hull);
    return best;
}

/* The angle that turns the piece's smallest enclosing rectangle level. */
double nest_level_angle(GEOSContextHandle_t geos, const ur_path *outline)
{
    /*
     * The angle only orients the piece (its box is then measured on every
     * point), so a few thousand points of the outline are enough.
     */
    size_t stride = outline->count / 4000 + 1;
    size_t used = (outline->count + stride - 1) / stride;
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)used, 2);
    if (!sequence)
        return 0.0;
    for (size_t i = 0; i < used; i++)
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, outline->points[i * stride].x,
                             outline->points[i * stride].y);
    GEOSGeometry *points = GEOSGeom_createLineString_r(geos, sequence);
    GEOSGeometry *rectangle = points ? GEOSMinimumRotatedRectangle_r(geos, points) : NULL;
    double angle = 0.0;
    const GEOSGeometry *ring = rectangle ? GEOSGetExteriorRing_r(geos, rectangle) : NULL;
    const GEOSCoordSequence *corners = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
    unsigned corner_count = 0;
    if (corners && GEOSCoordSeq_getSize_r(geos, corners, &corner_count) && corner_count >= 3) {
        double x[3], y[3];
        for (unsigned k = 0; k < 3; k++)
            GEOSCoordSeq_getXY_r(geos, corners, k, &x[k], &y[k]);
        double first = hypot(x[1] - x[0], y[1] - y[0]);
        double second = hypot(x[2] - x[1], y[2] - y[1]);
        angle = first >= second ? atan2(y[1] - y[0], x[1] - x[0]) : atan2(y[2] - y[1], x[2] - x[1]);
        /* The narrowest rectangle unless a smaller one exists (see least_area_angle). */
        double area;
        double least = least_area_angle(geos, points, &area);
        if (area < first * second * (1 - 1e-9))
            angle = least;
    }
    if (rectangle)
        GEOSGeom_destroy_r(geos, rectangle);
    if (points)
        GEOSGeom_destroy_r(geos, points);
    return -angle;
}

static ur_box turned_box(const ur_piece *piece, double angle)
{
    ur_transform2 turn = ur_transform2_make(angle, ur_vec2_make(0, 0));
    ur_box box = ur_box_empty();
    for (size_t p = 0; p < piece->path_count; p++)
        for (size_t i = 0; i < piece->paths[p].count; i++)
            ur_box_add(&box, ur_transform2_apply(turn, piece->paths[p].points[i]));
    return box;
}

typedef struct candidate {
    size_t index;
    double angle;
    ur_box box;
} candidate;

static bool fits(ur_box box, double width, double height)
{
    return ur_box_width(box) <= width && ur_box_height(box) <= height;
}

static ur_status orient(const ur_piece *piece, GEOSContextHandle_t geos,
                        const ur_layout_options *options, candidate *out, ur_error *error)
{
    double width = options->sheet_width - 2 * options->margin;
    double height = options->sheet_height - 2 * options->margin;
    double angle = piece->path_count ? nest_level_angle(geos, &piece->paths[0]) : 0.0;
    for (int quarter = 0; quarter < 2; quarter++) {
        out->angle = angle + quarter * M_PI / 2;
        out->box = turned_box(piece, out->angle);
        if (fits(out->box, width, height))
            return UR_OK;
    }
    out->box = turned_box(piece, angle);
    ur_error_set(error, UR_ERROR_INPUT,
                 "piece %s (%.1f x %.1f mm) does not fit in any orientation: give a larger sheet "
                 "than %.1f x %.1f mm (%.1f x %.1f mm inside its %.1f mm margin) or a material "
                 "with larger stock",
                 piece->name, ur_box_width(out->box), ur_box_height(out->box), options->sheet_width,
                 options->sheet_height, width, height, options->margin);
    return ur_error_set_setting(error, "sheet");
}

static int taller_first(const void *a, const void *b)
{
    const candidate *x = a, *y = b;
    double hx = ur_box_height(x->box), hy = ur_box_height(y->box);
    if (hx != hy)
        return hx < hy ? 1 : -1;
    return (x->index > y->index) - (x->index < y->index);
}

static ur_status new_sheet(ur_layout *layout, const ur_layout_options *options, size_t capacity,
                           ur_error *error)
{
    ur_sheet *sheets = realloc(layout->sheets, (layout->sheet_count + 1) * sizeof *sheets);
    if (!sheets)
        return ur_error_out_of_memory(error);
    layout->sheets = sheets;
    ur_sheet *sheet = &sheets[layout->sheet_count];
    memset(sheet, 0, sizeof *sheet);
    sheet->width = options->sheet_width;
    sheet->height = options->sheet_height;
    sheet->placements = ur_alloc_array(capacity, sizeof *sheet->placements, error);
    if (!sheet->placements)
        return UR_ERROR_MEMORY;
    layout->sheet_count++;
    return UR_OK;
}

/* Shelf packing of oriented candidates, tallest first. */
static ur_status place_rows(candidate *order, size_t count, const ur_layout_options *options,
                            ur_layout *layout, ur_error *error)
{
    double left = options->margin, right = options->sheet_width - options->margin;
    double top = options->sheet_height - options->margin, bottom = options->margin;
    double x = left, row_top = top, row_height = 0.0;
    ur_status status = new_sheet(layout, options, count, error);
    for (size_t k = 0; k < count && status == UR_OK; k++) {
        double w = ur_box_width(order[k].box), h = ur_box_height(order[k].box);
        if (x > left && x + w > right) {
            x = left;
            row_top -= row_height + options->spacing;
            row_height = 0.0;
        }
        if (row_top - h < bottom) {
            status = new_sheet(layout, options, count, error);
            x = left;
            row_top = top;
            row_height = 0.0;
        }
        if (status != UR_OK)
            break;
        ur_sheet *sheet = &layout->sheets[layout->sheet_count - 1];
        ur_vec2 shift = {x - order[k].box.min.x, row_top - order[k].box.max.y};
        ur_placement placement = {order[k].index, ur_transform2_make(order[k].angle, shift)};
        sheet->placements[sheet->placement_count++] = placement;
        x += w + options->spacing;
        row_height = fmax(row_height, h);
    }
    return status;
}

ur_status ur_layout_rows(const ur_piece *pieces, size_t piece_count,
                         const ur_layout_options *options, ur_layout *layout, ur_error *error)
{
    memset(layout, 0, sizeof *layout);
    double width = options->sheet_width - 2 * options->margin;
    double height = options->sheet_height - 2 * options->margin;
    if (!(width > 0) || !(height > 0))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the sheet (%.1f x %.1f mm) leaves no room inside its %.1f mm margin",
                            options->sheet_width, options->sheet_height, options->margin);
    candidate *order = ur_alloc_array(piece_count, sizeof *order, error);
    GEOSContextHandle_t geos = GEOS_init_r();
    ur_status status = order && geos ? UR_OK : ur_error_out_of_memory(error);
    for (size_t k = 0; k < piece_count && status == UR_OK; k++) {
        order[k].index = k;
        status = orient(&pieces[k], geos, options, &order[k], error);
    }
    if (geos)
        GEOS_finish_r(geos);
    if (status == UR_OK) {
        qsort(order, piece_count, sizeof *order, taller_first);
        status = place_rows(order, piece_count, options, layout, error);
    }
    free(order);
    if (status != UR_OK)
        ur_layout_free(layout);
    return status;
}

double ur_outline_level_angle(const ur_vec2 *outline, size_t count)
{
    GEOSContextHandle_t geos = GEOS_init_r();
    if (!geos)
        return 0.0;
    ur_path path = {.op = UR_OP_CUT, .closed = true, .points = (ur_vec2 *)outline, .count = count};
    double angle = count ? nest_level_angle(geos, &path) : 0.0;
    GEOS_finish_r(geos);
    return angle;
}

ur_status ur_outline_level_size(const ur_vec2 *outline, size_t count, double *length, double *width,
                                ur_error *error)
{
    (void)error; /* nothing fails: without GEOS the outline is measured as it lies */
    ur_transform2 turn =
        ur_transform2_make(ur_outline_level_angle(outline, count), ur_vec2_make(0, 0));
    ur_box box = ur_box_empty();
    for (size_t k = 0; k < count; k++)
        ur_box_add(&box, ur_transform2_apply(turn, outline[k]));
    *length = count ? fmax(ur_box_width(box), ur_box_height(box)) : 0;
    *width = count ? fmin(ur_box_width(box), ur_box_height(box)) : 0;
    return UR_OK;
}

ur_status ur_outline_fit_turn(const ur_vec2 *outline, size_t count, double length, double width,
                              bool *fits, double *angle, ur_error *error)
{
    *fits = false;
    *angle = 0.0;
    if (count == 0)
        return UR_OK;
    ur_vec2 *points = ur_alloc_array(count, sizeof *points, error);
    ur_vec2 *hull = ur_alloc_array(count + 1, sizeof *hull, error);
    if (points && hull) {
        memcpy(points, outline, count * sizeof *points);
        size_t corners = geom_convex_hull(points, count, hull);
        double direction;
        *fits = geom_hull_fit_angle(hull, corners, fmax(length, width), fmin(length, width),
                                    &direction);
        *angle = *fits ? -direction : 0.0; /* the turn that lays that direction along x */
    }
    free(points);
    free(hull);
    return points && hull ? UR_OK : UR_ERROR_MEMORY;
}
