/*
 * bending.c: bending kerfs (docs/algorithms.md, section 13) where a
 * developed surface bends tighter than the material's smallest bend radius.
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
 * Facets.  Between two rows (grooves or hinge rows) the sheet stays flat,
 * so each row turns it by the angle between the tangent planes of its
 * neighbours: on a developable the normal is constant along a ruling, so
 * this angle is the normal's turn from one row to the next.  The normal is
 * sampled with R, its turn summed (psi), and the rows get a density (rows
 * per mm across the net)
 *
 *     max(1 / widest, (d psi / dt) / theta),
 *
 * theta the facet angle, the widest spacing w R / d for grooves (there a
 * groove closes completely and turns the sheet by w / d radians: 91
 * degrees for a 3.175 mm bit 2 mm deep, a polygon) and the hinge distance
 * for a laser.  With Phi the integral of the density over a region,
 *
 *     n = ceil(Phi) rows (at least 1), at phi = phi0, phi0 + 1, ...,
 *
 * phi(t) the integral from the region's start and phi0 = (Phi - n + 1) / 2,
 * so the rows are centred in the region, one local spacing apart.  The
 * turn between consecutive rows is then measured, and where the sampled
 * rate fell short the density is scaled up and the rows placed again.
 * Rows never come closer than their width (w, or the laser's kerf) plus the
 * minimum web: where theta would need that, they stay at it and a warning
 * says by how much each turns (thin).
 *
 * Router (grooves of width w cut to depth d from one side).  A groove is a
 * KERF line along its ruling right across the net, from outline to
 * outline: it does not go through the material, so nothing falls apart,
 * and grooves run out over the edges in kerf-bent work so the whole width
 * bends alike.  The CAM cuts the KERF layer to depth d.  Where w R / d is
 * below the narrowest spacing the grooves could not close enough even
 * there: they are placed every w (touching, the region pocketed down to
 * the skin), which bends to radius d only, and the record is a warning.
 * The skin left under a groove bends with the part; thinner than the sheet
 * by skin / thickness it takes a radius that much tighter than the
 * material's smallest, and a warning says where R is tighter still.
 *
 * Converging rulings (a cone's apex, a tangent developable's edge of
 * regression).  Rows that are far enough apart at the middle of the
 * rulings meet where the rulings do.  Each row keeps its web (the
 * narrowest spacing) from the lines of its neighbours, and the rows are
 * fanned out alternately: odd rows keep it from the rows beside them and
 * stop first, every other one of the rest from the rows two along, and so
 * on (neighbours_of), so the rows that go on towards the apex are never
 * closer than the narrowest spacing, and each stops where it would be.
 *
 * Laser (a through-cut living hinge, the material's pattern).  Rows along
 * the rulings, placed as the grooves are.  Each row is slits of
 * hinge_cut_length separated by uncut bridges of hinge_connection, period p = cut + connection,
 * measured from the middle of the row across the net: even rows have a slit centred there, odd rows
 * a bridge (half a period along), so that each slit is bridged by the rows beside it.  Slits are
 * clipped to the outline buffered inward by hinge_connection (GEOS), so solid margins at least that
 * wide remain at the ends and the hinge never cuts the part through; what is left of a clipped slit
 * shorter than hinge_connection is dropped (a hole, no slit).
 *
 * One UR_ALLOWANCE_BENDING record per region: count the lines (grooves or
 * slits), rows the rows, facet_angle the largest turn of one row (degrees),
 * value the smallest R in it, limit min_radius; a warning for thin webs
 * and one for a skin too thick, each saying what to use instead.
 */
#include "allow_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/analyze.h"
#include "../base/c_locale.h"

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
    ur_vec3 normal; /* the surface's unit normal along the ruling (constant on a developable) */
    double turn;    /* radians the normal has turned since the first sample */
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
    bool merged;  /* router: grooves would leave no web that can close, placed every w */
    bool thin;    /* the facet angle would need webs thinner than the minimum */
    double facet; /* radians: the largest turn between consecutive rows */
    double closest, farthest; /* spacing of consecutive rows, mm */
    size_t stopped;           /* rows cut back where rulings converge, to keep their webs */
    double scale;             /* the rows' density over that the spacing rules ask */
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
        return UR_ERROR_MEMORY;
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

/*
 * The surface's normal along the ruling at u, taken half way along it: on
 * a developable it is the same all along, and the middle is clear of a
 * cone's apex and a tangent developable's edge of regression.
 */
static ur_vec3 normal_at(ur_ruled *ruled, double u)
{
    ur_point_curvature c;
    ur_analyze_point(ruled, u, 0.5, &c);
    return c.normal;
}

/* The angle between the tangent planes of two rulings, whichever way their normals point. */
static double turn_between(ur_vec3 a, ur_vec3 b)
{
    return atan2(ur_vec3_length(ur_vec3_cross(a, b)), fabs(ur_vec3_dot(a, b)));
}

/* R at every knot and SUBSTEPS - 1 points between consecutive ones, with the normal's turn. */
static ur_status sample_radii(bend_job *job)
{
    job->sample_count = (job->knot_count - 1) * SUBSTEPS + 1;
    job->samples = ur_alloc_array(job->sample_count, sizeof *job->samples, job->error);
    if (!job->samples)
        return UR_ERROR_MEMORY;
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
        s->normal = normal_at(job->ruled, s->u);
        s->turn =
            k > 0 ? job->samples[k - 1].turn + turn_between(job->samples[k - 1].normal, s->normal)
                  : 0.0;
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

/* The largest turn one row may make, radians. */
static double facet_limit(const ur_bending_options *options)
{
    double degrees = options->facet_angle > 0 ? options->facet_angle : UR_DEFAULT_FACET_ANGLE;
    return degrees * M_PI / 180.0;
}

/* The closest rows may be: a groove's (or slit's) width and the thinnest web left between. */
static double narrowest_spacing(const ur_bending_options *options)
{
    return (options->router ? options->groove_width : options->kerf) + options->min_web;
}

/*
 * How fast the surface turns across the net at position t (radians per
 * mm): the normal's turn over the sample step that holds t.
 */
static double turn_rate_at(const bend_job *job, double t)
{
    const bend_sample *s = job->samples;
    size_t low = 0, high = job->sample_count - 1;
    while (high - low > 1) {
        size_t mid = low + (high - low) / 2;
        if (s[mid].t <= t)
            low = mid;
        else
            high = mid;
    }
    double span = s[high].t - s[low].t;
    return span > 0 ? (s[high].turn - s[low].turn) / span : 0.0;
}

/*
 * Rows per mm wanted at a point of bend radius R turning at `rate`: as
 * many as keep each row's turn within the facet angle, and never fewer
 * than the widest spacing allows (w R / d for grooves, which then close
 * completely; the hinge's own row distance), times the region's scale.
 * Rows closer than the narrowest spacing would leave webs thinner than the
 * minimum: they stay at that spacing and the region is marked thin.
 * Grooves that could not close even at it are placed touching (merged).
 */
static double row_density(const bend_job *job, double radius, double rate, bend_region *region)
{
    const ur_bending_options *o = job->options;
    double widest = o->router ? o->groove_width * radius / o->groove_depth : o->hinge_distance;
    double narrowest = narrowest_spacing(o);
    if (o->router && widest < narrowest) {
        region->merged = true;
        return 1.0 / o->groove_width;
    }
    double wanted = fmax(1.0 / widest, rate / facet_limit(o)) * region->scale;
    if (narrowest > 0 && wanted > 1.0 / narrowest) {
        region->thin = true;
        return 1.0 / narrowest;
    }
    return wanted;
}

/* One point of a region's quadrature: position, R, rows per mm and phi there. */
typedef struct density_point {
    double t, radius, density, phi;
} density_point;

/*
 * The region's points (its ends and the samples inside) with phi, the
 * integral of the row density from the region's start (trapezoid rule:
 * exact where it is constant); *count receives how many.  The caller
 * frees the array.
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
    region->merged = region->thin = false;
    for (size_t k = 0; k < n; k++) {
        /* An end found by bisection has R at the limit, give or take its last step. */
        double radius = fmin(points[k].radius, limit);
        region->smallest = fmin(region->smallest, radius);
        region->largest = fmax(region->largest, radius);
        /* Inside, the turn rate of the steps on both sides; at an end, of the step inside. */
        double before = turn_rate_at(job, points[k].t - 1e-9 * (1 + fabs(points[k].t)));
        double after = turn_rate_at(job, points[k].t + 1e-9 * (1 + fabs(points[k].t)));
        double rate = k == 0 ? after : k + 1 == n ? before : 0.5 * (before + after);
        points[k].density = row_density(job, radius, rate, region);
        if (k > 0)
            points[k].phi = points[k - 1].phi + 0.5 * (points[k].t - points[k - 1].t) *
                                                    (points[k].density + points[k - 1].density);
    }
    *count = n;
    return points;
}

/*
 * The position where phi reaches target, the density linear between
 * points (phi quadratic).  Targets come in increasing order: *cursor, the
 * point the last one was found after, saves searching from the start each
 * time.
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

/*
 * The positions of a region's rows (grooves or hinge rows) into *positions
 * (the caller frees it), *count of them: ceil(phi over the region) rows,
 * one unit of phi apart, centred in it.  Each row then turns the sheet by
 * at most the facet angle, measured between the tangent planes of
 * consecutive rows (region->facet; for one row, that of the region's
 * ends): where the sampled turn rate fell short of it, the density is
 * scaled up and the rows placed again.
 */
static ur_status place_rows(bend_job *job, bend_region *region, double **positions, size_t *count)
{
    const double limit = facet_limit(job->options);
    region->scale = 1.0;
    for (int attempt = 0;; attempt++) {
        size_t n = 0, cursor = 0;
        density_point *points = region_density(job, region, &n);
        if (!points)
            return UR_ERROR_MEMORY;
        double total = points[n - 1].phi;
        double rows = fmax(1.0, ceil(total - 1e-9));
        if (rows > MAX_ROWS) {
            free(points);
            return ur_error_set(job->error, UR_ERROR_INPUT,
                                "piece '%s': bending kerfs would need %.0f %s in one region; "
                                "check the groove or hinge sizes",
                                job->piece->name, rows, job->options->router ? "grooves" : "rows");
        }
        *count = (size_t)rows;
        *positions = ur_alloc_array(*count, sizeof **positions, job->error);
        if (!*positions) {
            free(points);
            return UR_ERROR_MEMORY;
        }
        double first = 0.5 * (total - (rows - 1));
        for (size_t k = 0; k < *count; k++)
            (*positions)[k] = position_of(points, n, first + (double)k, &cursor);
        free(points);
        region->facet =
            *count == 1 ? turn_between(normal_at(job->ruled, parameter_at(job, region->t_start)),
                                       normal_at(job->ruled, parameter_at(job, region->t_end)))
                        : 0.0;
        for (size_t k = 1; k < *count; k++)
            region->facet =
                fmax(region->facet,
                     turn_between(normal_at(job->ruled, parameter_at(job, (*positions)[k - 1])),
                                  normal_at(job->ruled, parameter_at(job, (*positions)[k]))));
        if (region->facet <= limit * (1 + 1e-9) || region->thin || region->merged || attempt == 5)
            return UR_OK;
        region->scale *= region->facet / limit * (1 + 1e-6);
        free(*positions);
        *positions = NULL;
    }
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

/*
 * The neighbouring rows a row must keep its web from, where rulings
 * converge (a cone's apex, a tangent developable's edge of regression).
 */
typedef struct row_neighbours {
    ur_segment lines[2];
    size_t count;
} row_neighbours;

/*
 * Narrows [*low, *high], positions along the line through `middle` along
 * unit e, to where it is at least `gap` from the line through `other`
 * (on the side `middle` is on).  The distance to a line changes linearly
 * along another, so what is left is one interval, possibly empty.
 */
static void keep_clear_of(ur_segment other, ur_vec2 middle, ur_vec2 e, double gap, double *low,
                          double *high)
{
    ur_vec2 d = ur_vec2_sub(other.end, other.start);
    double length = ur_vec2_length(d);
    if (!(length > 0))
        return;
    ur_vec2 f = ur_vec2_scale(d, 1.0 / length);
    double at_middle = ur_vec2_cross(f, ur_vec2_sub(middle, other.start));
    double side = at_middle >= 0 ? 1.0 : -1.0;
    double distance = side * at_middle, slope = side * ur_vec2_cross(f, e);
    if (fabs(slope) < 1e-12) {
        if (distance < gap)
            *high = -INFINITY;
        return;
    }
    double x = (gap - distance) / slope; /* distance + slope x = gap */
    if (slope > 0)
        *low = fmax(*low, x);
    else
        *high = fmin(*high, x);
}

/* [*low, *high] kept clear of every neighbouring row by the narrowest spacing; true if cut. */
static bool keep_webs(const bend_job *job, const row_neighbours *neighbours, ur_vec2 middle,
                      ur_vec2 e, double *low, double *high)
{
    double before_low = *low, before_high = *high;
    /* Rows exactly the narrowest spacing apart (parallel) keep it, give or take rounding. */
    double gap = narrowest_spacing(job->options) * (1 - 1e-6);
    for (size_t k = 0; k < neighbours->count; k++)
        keep_clear_of(neighbours->lines[k], middle, e, gap, low, high);
    return *low > before_low || *high < before_high;
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
static ur_status hinge_row(bend_job *job, ur_segment row, bool odd,
                           const row_neighbours *neighbours, bend_region *region)
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
        if (!part || !part_extent(job->geos, part, middle, e, &low, &high))
            continue;
        region->stopped += keep_webs(job, neighbours, middle, e, &low, &high);
        if (high > low)
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

/* A groove along `line`, cut back where it would come nearer its neighbours than allowed. */
static ur_status groove(bend_job *job, ur_segment line, const row_neighbours *neighbours,
                        bend_region *region)
{
    ur_vec2 d = ur_vec2_sub(line.end, line.start);
    double length = ur_vec2_length(d);
    if (!(length > 0))
        return UR_OK;
    ur_vec2 e = ur_vec2_scale(d, 1.0 / length), middle = midpoint(line);
    double low = -0.5 * length, high = 0.5 * length;
    region->stopped += keep_webs(job, neighbours, middle, e, &low, &high);
    if (!(high - low > job->options->groove_width))
        return UR_OK;
    return add_line(job, ur_vec2_add_scaled(middle, e, low), ur_vec2_add_scaled(middle, e, high),
                    region);
}

/*
 * Where rulings converge, rows would come closer than the narrowest
 * spacing.  They are fanned out alternately: row k, with 2^j the largest
 * power of 2 dividing it, keeps its web from rows k - 2^j and k + 2^j, so
 * odd rows stop first, then every other of the rest, and so on, and the
 * rows that go on are never closer than the narrowest spacing.  Row 0
 * keeps no web from any, since every other keeps it from row 0 or a row
 * between.  A row keeps clear of the lines of its neighbours, which hold
 * their slits.
 */
static row_neighbours neighbours_of(const bend_job *job, const double *positions, size_t count,
                                    size_t k, bool region_merged)
{
    row_neighbours neighbours = {0};
    if (k == 0 || region_merged)
        return neighbours;      /* touching grooves pocket the region: no webs between them */
    size_t step = k & (~k + 1); /* the largest power of 2 dividing k */
    neighbours.lines[neighbours.count++] = ruling_at(job, positions[k - step]);
    if (k + step < count)
        neighbours.lines[neighbours.count++] = ruling_at(job, positions[k + step]);
    return neighbours;
}

/* The grooves or hinge rows of one region. */
static ur_status fill_region(bend_job *job, bend_region *region)
{
    double *positions = NULL;
    size_t count = 0;
    ur_status status = place_rows(job, region, &positions, &count);
    if (status != UR_OK)
        return status;
    region->rows = count;
    region->closest = INFINITY;
    region->farthest = 0.0;
    for (size_t k = 1; k < count; k++) {
        region->closest = fmin(region->closest, positions[k] - positions[k - 1]);
        region->farthest = fmax(region->farthest, positions[k] - positions[k - 1]);
    }
    size_t cut_rows = 0;
    for (size_t k = 0; k < count && status == UR_OK; k++) {
        double t = positions[k];
        ur_segment ruling = ruling_at(job, t);
        ur_segment line = across_net(job->net, ruling.start, ruling.end);
        row_neighbours neighbours = neighbours_of(job, positions, count, k, region->merged);
        if (job->options->router)
            status = groove(job, line, &neighbours, region);
        else {
            size_t before = region->lines;
            status =
                hinge_row(job, hinge_line(job, t, ruling, line), k % 2 == 1, &neighbours, region);
            cut_rows += region->lines > before;
        }
    }
    if (!job->options->router)
        region->rows = cut_rows; /* rows within the margins of the net's ends have no slit */
    ur_segment centre = ruling_at(job, 0.5 * (region->t_start + region->t_end));
    region->where = midpoint(centre);
    free(positions);
    return status;
}

/* ---- Records ----------------------------------------------------------- */

/* Copies text into the record's reason, cut to what it holds. */
static void set_reason(ur_allowance_record *record, const char *text)
{
    size_t length = strlen(text);
    length = length < sizeof record->reason ? length : sizeof record->reason - 1;
    memcpy(record->reason, text, length);
    record->reason[length] = '\0';
}

/* "every 3.49 mm", "every 3.4 to 3.6 mm", or nothing for a single row. */
static void spacing_text(const bend_region *region, char *text, size_t size)
{
    if (region->rows < 2 || !isfinite(region->closest))
        c_snprintf(text, size, "one row");
    else if (region->farthest - region->closest <= 1e-3 * region->farthest)
        c_snprintf(text, size, "every %.4g mm", region->closest);
    else
        c_snprintf(text, size, "every %.4g to %.4g mm", region->closest, region->farthest);
}

static ur_allowance_record region_record(const bend_job *job, const bend_region *region)
{
    ur_allowance_record record = {0};
    record.kind = UR_ALLOWANCE_BENDING;
    record.value = region->smallest;
    record.limit = job->options->min_radius;
    record.where = region->where;
    record.facet_angle = region->facet * 180.0 / M_PI;
    record.rows = region->rows;
    return record;
}

static ur_status record_main(bend_job *job, const bend_region *region)
{
    const ur_bending_options *o = job->options;
    ur_allowance_record record = region_record(job, region);
    record.count = region->lines;
    record.warning = region->merged || region->lines == 0;
    char reason[512], spacing[64], stopped[160] = "";
    spacing_text(region, spacing, sizeof spacing);
    if (region->stopped > 0)
        c_snprintf(stopped, sizeof stopped,
                   "; %zu %s stop short where the rulings converge, fanned out alternately to "
                   "keep webs of %.3g mm",
                   region->stopped, o->router ? "grooves" : "rows", o->min_web);
    if (o->router)
        c_snprintf(reason, sizeof reason,
                   "bend radius %.4g mm < %.4g mm: %zu grooves %.4g mm wide, %.4g mm deep, %s, "
                   "%.2g degrees each%s%s",
                   region->smallest, o->min_radius, region->lines, o->groove_width, o->groove_depth,
                   spacing, record.facet_angle,
                   region->merged ? "; the grooves would merge: they touch, and bend only to "
                                    "about the depth's radius"
                                  : "",
                   stopped);
    else if (region->lines == 0)
        c_snprintf(reason, sizeof reason,
                   "bend radius %.4g mm < %.4g mm: no living-hinge slit (%.4g mm long with "
                   "%.4g mm bridges) fits inside the margins there%s",
                   region->smallest, o->min_radius, o->hinge_cut_length, o->hinge_connection,
                   stopped);
    else
        c_snprintf(reason, sizeof reason,
                   "bend radius %.4g mm < %.4g mm: living hinge, %zu slits %.4g mm long with "
                   "%.4g mm bridges in %zu rows %s, %.2g degrees each%s",
                   region->smallest, o->min_radius, region->lines, o->hinge_cut_length,
                   o->hinge_connection, region->rows, spacing, record.facet_angle, stopped);
    set_reason(&record, reason);
    return ur_piece_record(job->piece, &record, job->error);
}

/*
 * Rows as close as the webs allow still turn by more than the facet angle:
 * the part comes out faceted there.
 */
static ur_status record_thin(bend_job *job, const bend_region *region)
{
    const ur_bending_options *o = job->options;
    ur_allowance_record record = region_record(job, region);
    record.warning = true;
    char reason[512];
    c_snprintf(reason, sizeof reason,
               "bend radius %.4g mm: %s closer than %.4g mm would leave webs under %.4g mm, so "
               "each turns by up to %.2g degrees, more than %.2g: %s",
               region->smallest, o->router ? "grooves" : "hinge rows", narrowest_spacing(o),
               o->min_web, record.facet_angle, facet_limit(o) * 180.0 / M_PI,
               o->router ? "use the laser's living hinge or a thinner material"
                         : "use a thinner material or a larger radius");
    set_reason(&record, reason);
    return ur_piece_record(job->piece, &record, job->error);
}

/*
 * The skin under a groove bends with the part: thinner than the whole
 * sheet by skin / thickness, it takes a radius that much tighter
 * (outer-fibre strain skin / 2R).  A skin too thick for the radius would
 * crack; the groove would have to be deeper than the profile allows.
 */
static ur_status record_skin(bend_job *job, const bend_region *region)
{
    const ur_bending_options *o = job->options;
    if (!o->router || !(o->thickness > o->groove_depth))
        return UR_OK;
    double skin = o->thickness - o->groove_depth;
    double needed = o->thickness * region->smallest / o->min_radius;
    if (skin <= needed * (1 + 1e-9))
        return UR_OK;
    ur_allowance_record record = region_record(job, region);
    record.warning = true;
    char reason[512];
    c_snprintf(reason, sizeof reason,
               "bend radius %.4g mm: the %.4g mm skin under the grooves bends no tighter than "
               "%.4g mm; this radius needs a skin of %.3g mm, grooves deeper than the material "
               "allows: use the laser's living hinge or another material",
               region->smallest, skin, o->min_radius * skin / o->thickness, needed);
    set_reason(&record, reason);
    return ur_piece_record(job->piece, &record, job->error);
}

static ur_status record_region(bend_job *job, const bend_region *region)
{
    ur_status status = record_main(job, region);
    if (status == UR_OK && region->thin && !region->merged)
        status = record_thin(job, region);
    if (status == UR_OK)
        status = record_skin(job, region);
    return status;
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
    if (!(o->facet_angle >= 0 && o->facet_angle <= 90) ||
        !(o->min_web >= 0 && isfinite(o->min_web)) || !(o->kerf >= 0 && isfinite(o->kerf)) ||
        !(o->thickness >= 0 && isfinite(o->thickness)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece '%s': bending kerfs need a facet angle from 0 to 90 degrees "
                            "and a minimum web, kerf and thickness of 0 or more",
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
    c_snprintf(record.reason, sizeof record.reason,
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
