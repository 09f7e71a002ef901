/*
 * bending.c: bending kerfs (DESIGN.md section 4) where a developed surface
 * bends tighter than the material's smallest bend radius.
 *
 * The bend radius R at the ruling of parameter u is the one `unroll
 * analyze` reports (ur_analyze_bend_radius): the smallest radius of normal
 * curvature across the ruling, over its length.  A cone bends tightest at
 * the end nearer its apex, and that end decides for the whole ruling, since
 * a kerf runs along all of it.
 *
 * Where across the net.  A position t runs across the rulings along the
 * net: the flat distance between the midpoints of consecutive drawn
 * rulings, summed, and linear in between (a ruling between two drawn ones
 * is the linear blend of their ends, its parameter u the blend of theirs).
 * Beyond the first and last drawn ruling the blend goes on to the net's
 * ends, where the line through the midpoints meets the outline; there u is
 * the net's u_start or u_end.  R is sampled at the drawn rulings, at the
 * net's ends and at SUBSTEPS points between, and a REGION is a longest run
 * of samples with R < min_radius, its ends found by bisection on R.
 *
 * Router (grooves of width w cut to depth d from one side).  A groove that
 * closes up turns the uncut skin by w / d radians, so grooves every
 * s = w R / d bend the part to radius R.  With R varying, the number of
 * grooves a region needs is Phi = integral of dt / s(t) over it, and
 *
 *     n = ceil(Phi) grooves (at least 1), at phi = phi0, phi0 + 1, ...,
 *
 * phi(t) the integral from the region's start and phi0 = (Phi - n + 1) / 2,
 * so the grooves are centred in the region, consecutive ones one local
 * spacing apart (exactly s where R is constant), the end ones at most s / 2
 * from the region's ends.  A groove is a KERF line along its ruling right
 * across the net, from outline to outline: it does not go through the
 * material, so nothing falls apart, and grooves run out over the edges in
 * kerf-bent work so the whole width bends alike.  The CAM cuts the KERF
 * layer to depth d.  Where R < d the grooves would be closer than their
 * own width and merge: there they are placed every w (touching, the region
 * pocketed down to the skin), which bends to radius d only, and the record
 * is a warning saying so.
 *
 * Laser (a through-cut living hinge, the material's pattern).  Rows along
 * the rulings every hinge_distance, placed as the grooves are with
 * s = hinge_distance.  Each row is slits of hinge_cut_length separated by
 * uncut bridges of hinge_connection, period p = cut + connection, measured
 * from the middle of the row across the net: even rows have a slit centred
 * there, odd rows a bridge (half a period along), so that each slit is
 * bridged by the rows beside it.  Slits are clipped to the outline buffered
 * inward by hinge_connection (GEOS), so solid margins at least that wide
 * remain at the ends and the hinge never cuts the part through; what is
 * left of a clipped slit shorter than hinge_connection is dropped (a hole,
 * no slit).
 *
 * One UR_ALLOWANCE_BENDING record per region: count the lines (grooves or
 * slits), value the smallest R in it, limit min_radius.
 */
#include "allow_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/analyze.h"

/* Samples of R between consecutive positions of the net (drawn rulings and ends). */
enum { SUBSTEPS = 8 };

/* Points along each ruling where R is looked for (as ur_analyze's default). */
enum { ACROSS = 17 };

/* Bisections for a region's end: 2^-48 of a sample step is far below any cutter. */
enum { BISECTIONS = 48 };

/* Grooves or rows in one region beyond which the pattern is refused as absurd. */
enum { MAX_ROWS = 100000 };

/* GEOS rounds a buffer's arcs with this many segments per quarter circle. */
enum { QUADRANT_SEGMENTS = 16 };

typedef struct bend_sample {
    double t, u, radius;
} bend_sample;

typedef struct bend_job {
    ur_piece *piece;
    const ur_net *net;
    ur_ruled *ruled;
    const ur_bending_options *options;
    ur_error *error;
    /* Knots: the net's start, each drawn ruling, the net's end. */
    double *knot_t, *knot_u;
    size_t knot_count;
    bend_sample *samples;
    size_t sample_count;
    GEOSContextHandle_t geos;
    GEOSGeometry *inner; /* laser: the outline buffered inward by hinge_connection */
} bend_job;

/* What one region got, for its record. */
typedef struct bend_region {
    double t_start, t_end;
    double smallest, largest; /* R over the region */
    size_t rows;              /* grooves, or hinge rows that got a slit */
    size_t lines;             /* KERF paths added */
    bool merged;              /* router: R < d somewhere, grooves placed every w */
    ur_vec2 where;
} bend_region;

static ur_vec2 midpoint(ur_segment s)
{
    return ur_vec2_lerp(s.start, s.end, 0.5);
}

/* ---- The net's outline ------------------------------------------------- */

/*
 * How far from `from` (inside the outline) the ray along unit `direction`
 * first meets the outline; INFINITY when it does not (rounding at a vertex).
 */
static double ray_to_outline(const ur_net *net, ur_vec2 from, ur_vec2 direction)
{
    double nearest = INFINITY;
    size_t n = net->outline_count;
    for (size_t i = 0; i < n; i++) {
        ur_vec2 p = net->outline[i], edge = ur_vec2_sub(net->outline[(i + 1) % n], p);
        double denominator = ur_vec2_cross(direction, edge);
        if (denominator == 0)
            continue; /* parallel: the neighbouring edges meet the ray instead */
        ur_vec2 to_p = ur_vec2_sub(p, from);
        double along = ur_vec2_cross(to_p, edge) / denominator;
        double on_edge = ur_vec2_cross(to_p, direction) / denominator;
        if (along > 0 && on_edge >= -1e-12 && on_edge <= 1 + 1e-12)
            nearest = fmin(nearest, along);
    }
    return nearest;
}

/*
 * The line through the ruling near-far across the net: the part of it
 * inside the outline that holds the ruling's midpoint.  Falls back on the
 * ruling itself should the outline not be met (it always is, but for
 * rounding at a vertex).
 */
static ur_segment across_net(const ur_net *net, ur_vec2 near, ur_vec2 far)
{
    ur_segment line = {near, far};
    ur_vec2 d = ur_vec2_sub(far, near);
    double length = ur_vec2_length(d);
    if (!(length > 0))
        return line;
    ur_vec2 e = ur_vec2_scale(d, 1.0 / length), m = ur_vec2_lerp(near, far, 0.5);
    double forward = ray_to_outline(net, m, e);
    double back = ray_to_outline(net, m, ur_vec2_scale(e, -1));
    if (isfinite(back))
        line.start = ur_vec2_add_scaled(m, e, -back);
    if (isfinite(forward))
        line.end = ur_vec2_add_scaled(m, e, forward);
    return line;
}

/* ---- Positions across the net ------------------------------------------ */

/* The i in [0, count - 2] with t[i] <= x < t[i + 1], the first or last when x is outside. */
static size_t interval_of(const double *t, size_t count, double x)
{
    size_t low = 0, high = count - 1; /* t[low] <= x < t[high], or x beyond an end */
    while (high - low > 1) {
        size_t mid = low + (high - low) / 2;
        if (t[mid] <= x)
            low = mid;
        else
            high = mid;
    }
    return low;
}

/*
 * The ruling at position t: the blend of the two drawn rulings around it,
 * or beyond the first or last one the blend carried on (extrapolated).
 */
static ur_segment ruling_at(const bend_job *job, double t)
{
    const ur_net *net = job->net;
    const double *drawn_t = job->knot_t + 1; /* drawn ruling k at knot k + 1 */
    size_t i = interval_of(drawn_t, net->ruling_count, t);
    double span = drawn_t[i + 1] - drawn_t[i];
    double f = span > 0 ? (t - drawn_t[i]) / span : 0.0;
    ur_segment a = net->rulings[i], b = net->rulings[i + 1];
    ur_segment s = {ur_vec2_lerp(a.start, b.start, f), ur_vec2_lerp(a.end, b.end, f)};
    return s;
}

/* u at position t: linear between knots. */
static double parameter_at(const bend_job *job, double t)
{
    size_t i = interval_of(job->knot_t, job->knot_count, t);
    double span = job->knot_t[i + 1] - job->knot_t[i];
    double f = span > 0 ? (t - job->knot_t[i]) / span : 0.0;
    return job->knot_u[i] + f * (job->knot_u[i + 1] - job->knot_u[i]);
}

static double radius_at(const bend_job *job, double t)
{
    return ur_analyze_bend_radius(job->ruled, parameter_at(job, t), ACROSS, NULL);
}

/*
 * How far the net goes on beyond drawn ruling `from`, away from drawn
 * ruling `toward`: along the line through their midpoints to the outline.
 */
static double end_band(const ur_net *net, size_t from, size_t toward)
{
    ur_vec2 a = midpoint(net->rulings[from]), b = midpoint(net->rulings[toward]);
    ur_vec2 d = ur_vec2_sub(a, b);
    double length = ur_vec2_length(d);
    if (!(length > 0))
        return 0.0;
    double band = ray_to_outline(net, a, ur_vec2_scale(d, 1.0 / length));
    return isfinite(band) ? band : 0.0;
}

/* The knots: t and u at the net's start, at each drawn ruling and at its end. */
static ur_status place_knots(bend_job *job)
{
    const ur_net *net = job->net;
    size_t count = net->ruling_count;
    job->knot_count = count + 2;
    job->knot_t = ur_alloc_array(job->knot_count, sizeof *job->knot_t, job->error);
    job->knot_u = ur_alloc_array(job->knot_count, sizeof *job->knot_u, job->error);
    if (!job->knot_t || !job->knot_u)
        return UR_ERROR_INTERNAL;
    job->knot_t[1] = 0.0;
    for (size_t k = 0; k < count; k++) {
        if (k > 0)
            job->knot_t[k + 1] = job->knot_t[k] + ur_vec2_distance(midpoint(net->rulings[k - 1]),
                                                                   midpoint(net->rulings[k]));
        job->knot_u[k + 1] = net->ruling_parameters[k];
    }
    job->knot_t[0] = -end_band(net, 0, 1);
    job->knot_u[0] = net->u_start;
    job->knot_t[count + 1] = job->knot_t[count] + end_band(net, count - 1, count - 2);
    job->knot_u[count + 1] = net->u_end;
    return UR_OK;
}

/* R at every knot and SUBSTEPS - 1 points between consecutive ones. */
static ur_status sample_radii(bend_job *job)
{
    job->sample_count = (job->knot_count - 1) * SUBSTEPS + 1;
    job->samples = ur_alloc_array(job->sample_count, sizeof *job->samples, job->error);
    if (!job->samples)
        return UR_ERROR_INTERNAL;
    for (size_t k = 0; k < job->sample_count; k++) {
        size_t knot = k / SUBSTEPS, step = k % SUBSTEPS;
        bend_sample *s = &job->samples[k];
        if (knot + 1 >= job->knot_count) {
            s->t = job->knot_t[knot];
            s->u = job->knot_u[knot];
        } else {
            double f = (double)step / SUBSTEPS;
            s->t = job->knot_t[knot] + f * (job->knot_t[knot + 1] - job->knot_t[knot]);
            s->u = job->knot_u[knot] + f * (job->knot_u[knot + 1] - job->knot_u[knot]);
        }
        s->radius = ur_analyze_bend_radius(job->ruled, s->u, ACROSS, NULL);
    }
    return UR_OK;
}

/* Where R crosses the limit between t_in (below it) and t_out (not). */
static double crossing(const bend_job *job, double t_in, double t_out)
{
    for (int k = 0; k < BISECTIONS; k++) {
        double t = 0.5 * (t_in + t_out);
        if (radius_at(job, t) < job->options->min_radius)
            t_in = t;
        else
            t_out = t;
    }
    return 0.5 * (t_in + t_out);
}

/* ---- Spacing ----------------------------------------------------------- */

/* The spacing wanted at radius R; *merged set where grooves would be closer than wide. */
static double spacing(const ur_bending_options *options, double radius, bool *merged)
{
    if (!options->router)
        return options->hinge_distance;
    double s = options->groove_width * radius / options->groove_depth;
    if (s < options->groove_width) {
        *merged = true;
        return options->groove_width;
    }
    return s;
}

/* One point of a region's quadrature: position, R, 1 / spacing and phi there. */
typedef struct density_point {
    double t, radius, density, phi;
} density_point;

/*
 * The region's points (its ends and the samples inside) with phi, the
 * integral of 1 / s from the region's start (trapezoid rule: exact where R
 * is constant); *count receives how many.  The caller frees the array.
 */
static density_point *region_density(const bend_job *job, bend_region *region, size_t *count)
{
    size_t n = 0;
    density_point *points = ur_alloc_array(job->sample_count + 2, sizeof *points, job->error);
    if (!points)
        return NULL;
    points[n++] = (density_point){region->t_start, radius_at(job, region->t_start), 0, 0};
    for (size_t k = 0; k < job->sample_count; k++) {
        const bend_sample *s = &job->samples[k];
        if (s->t > region->t_start && s->t < region->t_end)
            points[n++] = (density_point){s->t, s->radius, 0, 0};
    }
    points[n++] = (density_point){region->t_end, radius_at(job, region->t_end), 0, 0};
    double limit = job->options->min_radius;
    region->smallest = limit;
    region->largest = 0.0;
    for (size_t k = 0; k < n; k++) {
        /* An end found by bisection has R at the limit, give or take its last step. */
        double radius = fmin(points[k].radius, limit);
        region->smallest = fmin(region->smallest, radius);
        region->largest = fmax(region->largest, radius);
        points[k].density = 1.0 / spacing(job->options, radius, &region->merged);
        if (k > 0)
            points[k].phi = points[k - 1].phi + 0.5 * (points[k].t - points[k - 1].t) *
                                                    (points[k].density + points[k - 1].density);
    }
    *count = n;
    return points;
}

/*
 * The position where phi reaches target, 1 / s linear between points (phi
 * quadratic).  Targets come in increasing order: *cursor, the point the
 * last one was found after, saves searching from the start each time.
 */
static double position_of(const density_point *points, size_t count, double target, size_t *cursor)
{
    size_t k = *cursor;
    while (k + 2 < count && points[k + 1].phi < target)
        k++;
    *cursor = k;
    const density_point *a = &points[k], *b = &points[k + 1];
    double span = b->t - a->t, left = target - a->phi;
    if (!(span > 0))
        return a->t;
    double slope = (b->density - a->density) / span;
    /* a->density tau + slope tau^2 / 2 = left, in the form that keeps its digits. */
    double root = a->density * a->density + 2 * slope * left;
    double tau = 2 * left / (a->density + sqrt(fmax(root, 0.0)));
    return a->t + fmin(fmax(tau, 0.0), span);
}

/* ---- Lines ------------------------------------------------------------- */

static ur_status add_line(bend_job *job, ur_vec2 a, ur_vec2 b, bend_region *region)
{
    ur_vec2 ends[2] = {a, b};
    ur_status status = ur_piece_add_path(job->piece, UR_OP_KERF, ends, 2, false, job->error);
    if (status == UR_OK)
        region->lines++;
    return status;
}

/* The parts of the row line inside the inner outline (GEOS); NULL on a GEOS failure. */
static GEOSGeometry *inner_parts(bend_job *job, ur_segment row)
{
    ur_vec2 ends[2] = {row.start, row.end};
    GEOSGeometry *line = allow_line(job->geos, ends, 2);
    if (!line)
        return NULL;
    GEOSGeometry *parts = GEOSIntersection_r(job->geos, line, job->inner);
    GEOSGeom_destroy_r(job->geos, line);
    return parts;
}

/* The slits of one row that fall in [low, high] along e from the row's middle. */
static ur_status slits_in_part(bend_job *job, ur_vec2 middle, ur_vec2 e, double low, double high,
                               bool odd, bend_region *region)
{
    const ur_bending_options *o = job->options;
    double period = o->hinge_cut_length + o->hinge_connection;
    double shift = odd ? 0.5 * period : 0.0; /* centre of slit j: shift + j period */
    double first = ceil((low - shift - 0.5 * o->hinge_cut_length) / period);
    for (double j = first; shift + j * period - 0.5 * o->hinge_cut_length < high; j++) {
        double centre = shift + j * period;
        double from = fmax(centre - 0.5 * o->hinge_cut_length, low);
        double to = fmin(centre + 0.5 * o->hinge_cut_length, high);
        if (to - from < o->hinge_connection)
            continue; /* a hole, no slit */
        ur_status status = add_line(job, ur_vec2_add_scaled(middle, e, from),
                                    ur_vec2_add_scaled(middle, e, to), region);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* Position along unit e from origin of a GEOS line part's ends: [*low, *high]. */
static bool part_extent(GEOSContextHandle_t geos, const GEOSGeometry *part, ur_vec2 origin,
                        ur_vec2 e, double *low, double *high)
{
    if (GEOSGeomTypeId_r(geos, part) != GEOS_LINESTRING)
        return false; /* a point where the row grazes the margin: no room */
    const GEOSCoordSequence *sequence = GEOSGeom_getCoordSeq_r(geos, part);
    unsigned size = 0;
    if (!sequence || !GEOSCoordSeq_getSize_r(geos, sequence, &size) || size < 2)
        return false;
    *low = INFINITY;
    *high = -INFINITY;
    for (unsigned i = 0; i < size; i++) {
        ur_vec2 p;
        GEOSCoordSeq_getXY_r(geos, sequence, i, &p.x, &p.y);
        double along = ur_vec2_dot(ur_vec2_sub(p, origin), e);
        *low = fmin(*low, along);
        *high = fmax(*high, along);
    }
    return true;
}

/* One row of the living hinge on the ruling line `row` (outline to outline). */
static ur_status hinge_row(bend_job *job, ur_segment row, bool odd, bend_region *region)
{
    ur_vec2 d = ur_vec2_sub(row.end, row.start);
    double length = ur_vec2_length(d);
    if (!(length > 0))
        return UR_OK;
    ur_vec2 e = ur_vec2_scale(d, 1.0 / length), middle = midpoint(row);
    GEOSGeometry *parts = inner_parts(job, row);
    if (!parts)
        return ur_error_set(job->error, UR_ERROR_INTERNAL,
                            "piece '%s': GEOS failed to clip a living-hinge row", job->piece->name);
    ur_status status = UR_OK;
    int count = GEOSGetNumGeometries_r(job->geos, parts);
    for (int k = 0; k < count && status == UR_OK; k++) {
        double low, high;
        const GEOSGeometry *part = GEOSGetGeometryN_r(job->geos, parts, k);
        if (part && part_extent(job->geos, part, middle, e, &low, &high))
            status = slits_in_part(job, middle, e, low, high, odd, region);
    }
    GEOSGeom_destroy_r(job->geos, parts);
    return status;
}

/*
 * The part of the ruling at u (from rail a at v = 0 to rail b at v = 1)
 * that bends tighter than the material allows: [*v_low, *v_high], widened
 * to the samples around it so that nothing tight is left out.  On a
 * tangent developable the radius grows with the distance from the edge of
 * regression, so only the rulings' near ends need the hinge.  False when
 * no sample is tight (the minimum fell between samples): then all of it.
 */
static bool tight_part(const bend_job *job, double u, double *v_low, double *v_high)
{
    int first = -1, last = -1;
    for (int k = 0; k < ACROSS; k++) {
        ur_point_curvature c;
        ur_analyze_point(job->ruled, u, (double)k / (ACROSS - 1), &c);
        if (c.bend_radius < job->options->min_radius) {
            if (first < 0)
                first = k;
            last = k;
        }
    }
    if (first < 0)
        return false;
    *v_low = (double)(first > 0 ? first - 1 : 0) / (ACROSS - 1);
    *v_high = (double)(last < ACROSS - 1 ? last + 1 : ACROSS - 1) / (ACROSS - 1);
    return true;
}

/* A hinge row: the ruling line across the net, cut down to the part that bends too tightly. */
static ur_segment hinge_line(const bend_job *job, double t, ur_segment ruling, ur_segment line)
{
    double v_low, v_high;
    if (!tight_part(job, parameter_at(job, t), &v_low, &v_high))
        return line;
    if (v_low > 0)
        line.start = ur_vec2_lerp(ruling.start, ruling.end, v_low);
    if (v_high < 1)
        line.end = ur_vec2_lerp(ruling.start, ruling.end, v_high);
    return line;
}

/* The grooves or hinge rows of one region. */
static ur_status fill_region(bend_job *job, bend_region *region)
{
    size_t count = 0;
    density_point *points = region_density(job, region, &count);
    if (!points)
        return UR_ERROR_INTERNAL;
    double total = points[count - 1].phi;
    double rows = fmax(1.0, ceil(total - 1e-9));
    if (rows > MAX_ROWS) {
        free(points);
        return ur_error_set(job->error, UR_ERROR_INPUT,
                            "piece '%s': bending kerfs would need %.0f %s in one region; check "
                            "the groove or hinge sizes",
                            job->piece->name, rows, job->options->router ? "grooves" : "rows");
    }
    region->rows = (size_t)rows;
    double first = 0.5 * (total - (rows - 1));
    size_t cut_rows = 0, cursor = 0;
    ur_status status = UR_OK;
    for (size_t k = 0; k < region->rows && status == UR_OK; k++) {
        double t = position_of(points, count, first + (double)k, &cursor);
        ur_segment ruling = ruling_at(job, t);
        ur_segment line = across_net(job->net, ruling.start, ruling.end);
        if (job->options->router)
            status = add_line(job, line.start, line.end, region);
        else {
            size_t before = region->lines;
            status = hinge_row(job, hinge_line(job, t, ruling, line), k % 2 == 1, region);
            cut_rows += region->lines > before;
        }
    }
    if (!job->options->router)
        region->rows = cut_rows; /* rows within the margins of the net's ends have no slit */
    ur_segment centre = ruling_at(job, 0.5 * (region->t_start + region->t_end));
    region->where = midpoint(centre);
    free(points);
    return status;
}

/* ---- Records ----------------------------------------------------------- */

static ur_status record_region(bend_job *job, const bend_region *region)
{
    const ur_bending_options *o = job->options;
    ur_allowance_record record = {0};
    record.kind = UR_ALLOWANCE_BENDING;
    record.count = region->lines;
    record.value = region->smallest;
    record.limit = o->min_radius;
    record.where = region->where;
    record.warning = region->merged || region->lines == 0;
    char reason[512], spacing_text[64];
    bool merged = false;
    double tight = spacing(o, region->smallest, &merged),
           loose = spacing(o, region->largest, &merged);
    if (loose - tight <= 1e-3 * loose)
        snprintf(spacing_text, sizeof spacing_text, "every %.4g mm", tight);
    else
        snprintf(spacing_text, sizeof spacing_text, "every %.4g to %.4g mm", tight, loose);
    if (o->router)
        snprintf(reason, sizeof reason,
                 "bend radius %.4g mm < %.4g mm: %zu grooves %.4g mm wide, "
                 "%.4g mm deep, %s%s",
                 region->smallest, o->min_radius, region->lines, o->groove_width, o->groove_depth,
                 spacing_text,
                 region->merged ? "; where the radius is below the groove depth the grooves "
                                  "would merge: they touch, and bend only to the depth's radius"
                                : "");
    else
        snprintf(reason, sizeof reason,
                 "bend radius %.4g mm < %.4g mm: living hinge, %zu slits %.4g mm long with "
                 "%.4g mm bridges in %zu rows every %.4g mm%s",
                 region->smallest, o->min_radius, region->lines, o->hinge_cut_length,
                 o->hinge_connection, region->rows, o->hinge_distance,
                 region->lines == 0 ? "; no slit fits inside the margins" : "");
    size_t length = strlen(reason); /* at most what the record holds */
    length = length < sizeof record.reason ? length : sizeof record.reason - 1;
    memcpy(record.reason, reason, length);
    record.reason[length] = '\0';
    return ur_piece_record(job->piece, &record, job->error);
}

/* ---- Regions ----------------------------------------------------------- */

static ur_status bend_regions(bend_job *job)
{
    double limit = job->options->min_radius;
    const bend_sample *s = job->samples;
    ur_status status = UR_OK;
    for (size_t k = 0; k < job->sample_count && status == UR_OK;) {
        if (!(s[k].radius < limit)) {
            k++;
            continue;
        }
        size_t last = k;
        while (last + 1 < job->sample_count && s[last + 1].radius < limit)
            last++;
        bend_region region = {0};
        region.t_start = k > 0 ? crossing(job, s[k].t, s[k - 1].t) : s[k].t;
        region.t_end =
            last + 1 < job->sample_count ? crossing(job, s[last].t, s[last + 1].t) : s[last].t;
        status = fill_region(job, &region);
        if (status == UR_OK)
            status = record_region(job, &region);
        k = last + 1;
    }
    return status;
}

/* ---- Checks and the entry point ----------------------------------------- */

static bool positive(double x)
{
    return x > 0 && isfinite(x);
}

static ur_status check_options(const ur_piece *piece, const ur_bending_options *o, ur_error *error)
{
    if (!positive(o->min_radius))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece '%s': bending kerfs need a positive smallest bend radius",
                            piece->name);
    if (o->router && !(positive(o->groove_width) && positive(o->groove_depth)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece '%s': bending grooves need a positive width and depth",
                            piece->name);
    if (!o->router && !(positive(o->hinge_cut_length) && positive(o->hinge_connection) &&
                        positive(o->hinge_distance)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece '%s': a living hinge needs a positive cut length, connection "
                            "and row distance",
                            piece->name);
    return UR_OK;
}

/*
 * Fewer than two drawn rulings give no direction across the net to place
 * kerfs in: a warning if the surface bends too tightly anywhere.
 */
static ur_status too_few_rulings(bend_job *job)
{
    const ur_net *net = job->net;
    double smallest = INFINITY, step = (net->u_end - net->u_start) / SUBSTEPS;
    for (int k = 0; k <= SUBSTEPS; k++) {
        double u = net->u_start + step * k;
        smallest = fmin(smallest, ur_analyze_bend_radius(job->ruled, u, ACROSS, NULL));
    }
    if (!(smallest < job->options->min_radius))
        return UR_OK;
    ur_allowance_record record = {0};
    record.kind = UR_ALLOWANCE_BENDING;
    record.value = smallest;
    record.limit = job->options->min_radius;
    record.where = net->outline_count ? net->outline[0] : ur_vec2_make(0, 0);
    record.warning = true;
    snprintf(record.reason, sizeof record.reason,
             "bend radius %.4g mm < %.4g mm, but the net has fewer than 2 rulings drawn to "
             "place bending kerfs along: develop it with more parts",
             smallest, job->options->min_radius);
    return ur_piece_record(job->piece, &record, job->error);
}

static ur_status open_inner(bend_job *job)
{
    job->geos = GEOS_init_r();
    if (!job->geos)
        return ur_error_out_of_memory(job->error);
    /* Chords of the buffer's arcs cut inside them: widen it so no chord comes nearer. */
    double margin = job->options->hinge_connection / cos(M_PI / (4.0 * QUADRANT_SEGMENTS));
    job->inner = allow_inside(job->geos, job->net->outline, job->net->outline_count, margin,
                              QUADRANT_SEGMENTS);
    if (!job->inner)
        return ur_error_set(job->error, UR_ERROR_INTERNAL,
                            "piece '%s': GEOS failed to buffer the outline for a living hinge",
                            job->piece->name);
    return UR_OK;
}

static void close_job(bend_job *job)
{
    free(job->knot_t);
    free(job->knot_u);
    free(job->samples);
    if (job->inner)
        GEOSGeom_destroy_r(job->geos, job->inner);
    if (job->geos)
        GEOS_finish_r(job->geos);
}

ur_status ur_piece_add_bending_kerfs(ur_piece *piece, const ur_net *net, ur_ruled *ruled,
                                     const ur_bending_options *options, ur_error *error)
{
    ur_status status = check_options(piece, options, error);
    if (status != UR_OK || !net->ruling_parameters)
        return status; /* a flattened mesh has no surface to ask: nothing to do */
    if (!ruled)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece '%s': bending kerfs need the surface it was developed from",
                            piece->name);
    if (net->outline_count < 3)
        return ur_error_set(error, UR_ERROR_INPUT, "piece '%s' has no outline to bend",
                            piece->name);
    bend_job job = {piece, net, ruled, options, error, NULL, NULL, 0, NULL, 0, NULL, NULL};
    if (net->ruling_count < 2)
        status = too_few_rulings(&job);
    else {
        status = place_knots(&job);
        if (status == UR_OK)
            status = sample_radii(&job);
        if (status == UR_OK && !options->router)
            status = open_inner(&job);
        if (status == UR_OK)
            status = bend_regions(&job);
    }
    close_job(&job);
    return status;
}
