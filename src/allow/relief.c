/*
 * relief.c: kerfing cuts where a net under-covers its surface and overlap
 * allowances where it over-covers it (docs/algorithms.md, section 12; the
 * seed paper, [Seed2018] in docs/bibliography.md: "in the first case
 * overlaps must be provided, in the second case we have to cut (kerfing)").
 *
 * Which is which.  The strain of a flattening is that of the map from the
 * 3D surface to the flat net (flatten.h): sigma < 1 means the flat net is
 * shorter than the surface in that direction, so the material must stretch
 * to take the 3D shape again: the net UNDER-covers there and needs KERFING
 * slits, which open up.  sigma > 1 means the flat net is longer: the
 * material must shrink, the net OVER-covers there and needs OVERLAPS, which
 * let the excess lap over itself.  So, per triangle of the shading
 * (develop.h, ur_shading: strain s, direction d):
 *
 *   kerfing  where s < 0 and -s = 1 - sigma2 > max_stretch,
 *   overlap  where s > 0 and  s = sigma1 - 1 > max_compression,
 *
 * the material's stretch limit against the flattening's compression and
 * its compression limit against the flattening's stretch.  (The material
 * strain measured on the flat length is 1 / sigma2 - 1 and 1 - 1 / sigma1;
 * the triggers use the figures the report shows, equal to first order.)
 * A triangle whose dominant strain is below RELIEF_NEGLIGIBLE (0.01 %)
 * is never relieved, whatever the limits: no material is that exact, and an
 * exact development meets its 3D lengths to quadrature accuracy only.
 *
 * Flattened nets.  Triangles of one kind that share an edge make a region,
 * as long as their directions fall in the same sector of 45 degrees
 * (centred on 0, 45, 90 and 135 degrees, directions being axes), each
 * direction first smoothed over its neighbours of the same kind (four
 * passes adding the neighbours' doubled-angle vectors weighted by area and
 * strain, so that nearly isotropic strain, whose axis is noise, follows its
 * neighbours): a ring of strain around a piece, whose direction turns with
 * it, becomes arcs, each with its own slits across it.  Per region: the axis D, the area-weighted
 * mean of the triangles' directions (as axes: doubled angles averaged), and across it N.  The
 * length the region's material is missing (kerfing) or has too much
 * (overlap) along D, on the line parallel to D at offset w across:
 *
 *   L(w) = sum over the region's triangles of  c_t * e_t * cos^2(a_t),
 *
 * c_t the chord of triangle t on that line, a_t the angle between its own
 * direction and D, and e_t = (|s| - limit) / (1 + s): for kerfing the 3D
 * length minus the flat length per flat length (1 / sigma2 - 1 when the
 * limit is 0), for overlaps the flat minus the 3D (1 - 1 / sigma1), less
 * what the material takes by itself (its limit).  The deficit (or excess)
 * is the largest L(w) over 64 lines spread evenly across the region's
 * width; under a quarter of `opening` the region needs nothing.  Then
 *
 *   n = ceil(deficit / opening)  slits,
 *
 * at most one per `opening` of the region's length along D, placed at the
 * middles of n equal parts of that length, each across D (along N):
 *
 *   kerfing: a KERF line clipped to the region and to the outline buffered
 *   inward by `margin` (GEOS), so it stops `margin` from the outline; parts
 *   shorter than `opening` are dropped.  A slit through the material opens
 *   by up to `opening` and every line along D crosses one of each.
 *
 *   overlap: the chord of the slit's line across the piece that meets the
 *   region; the slit runs from the end of the chord nearer to the region
 *   through the region, its inner end moved (along the chord) to the
 *   nearest point at least `margin` from the outline.  Beside it, on the +D
 *   side, a MARK overlap zone (a closed thin rectangle, clipped to the
 *   outline) over the slit's part in the region, of width
 *
 *     w = excess / n  (<= opening),
 *
 *   where the flap on the other side laps over and is glued: the zones
 *   crossed by a line along D add up to the excess.  With darts instead
 *   (limits->darts) each slit is a thin open V of KERF from the outline to
 *   the slit's inner end, its base w wide at the outline: the triangle
 *   drops out, its sides are joined, and no zone is marked.
 *
 * Developed nets (no shading).  The discrete methods' nets are a strip of
 * rulings; the triangle method under-covers (it neglects the slivers
 * between rulings), the quad method over-covers.  With coverage = flat area
 * / 3D area of the net:
 *
 *   kerfing  when 1 - coverage > max_stretch,
 *   overlap  when coverage - 1 > max_compression,
 *
 * the area missing or in excess lying between the rulings, so the stretch
 * is across them and the slits go along them.  The length across the
 * rulings the net misses (or has too much) is measured as the area
 * difference over the mean flat length of the net's drawn rulings:
 *
 *   deficit = (area_3d - flat_area) / mean ruling length,
 *   excess  = (flat_area - area_3d) / mean ruling length,
 *
 * the mean over the rulings' length (the triangle method's slivers are
 * widest at the edge of regression, so lines across the strip there miss
 * more than that, and lines near the far rail less).  n = ceil(deficit /
 * opening) slits, as above; their positions f_k count in drawn rulings
 * (0 the first, R - 1 the last): f_k = (k + 1/2) R / n - 1/2 when n <= R,
 * else k (R - 1) / (n - 1), a slit at a fractional position lying between
 * the two rulings it falls between (their ends interpolated).  Kerfing
 * slits are clipped as above; overlap slits run from the ruling's start
 * (on the outline) to `margin` short of the outline at its other end, each
 * with a zone (or as a dart) of width w = excess / n.  An exact net
 * (coverage 1 within RELIEF_NEGLIGIBLE) gets neither.
 *
 * Slits never cross.  Overlap regions are relieved first, then kerfing
 * regions; once a region is done its cuts, buffered by `margin`, are kept
 * out of: a later slit is clipped where it would come nearer (an overlap
 * slit shortened, and dropped when it no longer reaches its region or its
 * new end is nearer the outline than margin).  Two crossing cuts that both
 * reach the outline would cut a part of the piece loose.
 *
 * One record per region (per net for a development): kind KERFING or
 * OVERLAP, count the slits cut, value the largest strain that triggered it
 * (1 - sigma2 or sigma1 - 1; 1 - coverage or coverage - 1), limit the
 * material's, where the region's centre; a warning when fewer slits fit
 * than the formula asks for.
 *
 * This file lays the slits out over regions and rulings; relief_slits.c
 * cuts them and records each region.
 */
#include "relief_internal.h"

#include "../base/union_find.h"

#include <geos_c.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/*
 * A region whose length to take up, beyond what the material takes by
 * itself, is under this share of a slit's opening needs no slit: the
 * material's own give absorbs it with room to spare.
 */
#define RELIEF_UNNOTICED 0.25

#define RELIEF_NEGLIGIBLE 1e-4
#define RELIEF_LINES 64    /* lines across a region on which its deficit is measured */
#define RELIEF_SMOOTHING 4 /* passes smoothing the axes before they are sorted into sectors */

/* ---- Flattened nets: regions of the shading --------------------------- */

typedef struct flat_edge {
    ur_vec2 p, q; /* p before q in (x, y) order */
    size_t triangle;
} flat_edge;

static bool point_before(ur_vec2 a, ur_vec2 b)
{
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

static int compare_points(ur_vec2 a, ur_vec2 b)
{
    return point_before(a, b) ? -1 : point_before(b, a) ? 1 : 0;
}

static int compare_edges(const void *x, const void *y)
{
    const flat_edge *a = x, *b = y;
    int order = compare_points(a->p, b->p);
    return order ? order : compare_points(a->q, b->q);
}

/* The pairs of triangles of one kind (not none) that share an edge (equal flat corners). */
static ur_status neighbour_pairs(const ur_shading *shading, const relief_kind *kind,
                                 size_t (**pairs)[2], size_t *pair_count, ur_error *error)
{
    size_t count = shading->count;
    flat_edge *edges = ur_alloc_array(3 * count, sizeof *edges, error);
    *pairs = ur_alloc_array(3 * count, sizeof **pairs, error);
    *pair_count = 0;
    if (!edges || !*pairs) {
        free(edges);
        return UR_ERROR_MEMORY;
    }
    for (size_t t = 0; t < count; t++)
        for (int k = 0; k < 3; k++) {
            ur_vec2 a = shading->triangles[t][k], b = shading->triangles[t][(k + 1) % 3];
            flat_edge e = {point_before(a, b) ? a : b, point_before(a, b) ? b : a, t};
            edges[3 * t + (size_t)k] = e;
        }
    qsort(edges, 3 * count, sizeof *edges, compare_edges);
    for (size_t i = 0; i + 1 < 3 * count; i++) {
        size_t s = edges[i].triangle, t = edges[i + 1].triangle;
        if (compare_edges(&edges[i], &edges[i + 1]) != 0 || kind[s] != kind[t] ||
            kind[s] == RELIEF_NONE)
            continue;
        (*pairs)[*pair_count][0] = s;
        (*pairs)[(*pair_count)++][1] = t;
    }
    free(edges);
    return UR_OK;
}

static double triangle_area(const ur_vec2 *c)
{
    return 0.5 * fabs(ur_vec2_cross(ur_vec2_sub(c[1], c[0]), ur_vec2_sub(c[2], c[0])));
}

/* The length of the chord of triangle c on the line {p : p . n = w}, measured along d. */
static double chord(const ur_vec2 *c, ur_vec2 n, ur_vec2 d, double w)
{
    double low = INFINITY, high = -INFINITY;
    for (int k = 0; k < 3; k++) {
        ur_vec2 a = c[k], b = c[(k + 1) % 3];
        double sa = ur_vec2_dot(a, n) - w, sb = ur_vec2_dot(b, n) - w;
        if ((sa < 0) == (sb < 0) || sa == sb)
            continue;
        double along = ur_vec2_dot(ur_vec2_lerp(a, b, sa / (sa - sb)), d);
        low = fmin(low, along);
        high = fmax(high, along);
    }
    return high > low ? high - low : 0;
}

/* One region: its triangles (indices into the shading) and what it needs. */
typedef struct region {
    size_t *triangles;
    size_t count;
    ur_vec2 d, n;            /* the axis of its strain and across it */
    double low, high;        /* its extent along d */
    double across0, across1; /* its extent along n */
} region;

/*
 * e_t: missing (kerfing) or excess (overlap) length per flat length along
 * the triangle's own axis, beyond what the material takes itself (limit):
 * only that part needs slits.
 */
static double excess_per_length(double strain, double limit)
{
    return fmax(0.0, fabs(strain) - limit) / (1 + strain);
}

/* The region's axis, extent, value and centre. */
static void region_shape(const ur_shading *shading, region *r, relief_need *need)
{
    double c2 = 0, s2 = 0, area = 0;
    ur_vec2 centre = {0, 0};
    need->value = 0;
    for (size_t i = 0; i < r->count; i++) {
        size_t t = r->triangles[i];
        double a = triangle_area(shading->triangles[t]);
        ur_vec2 d = shading->direction[t];
        c2 += a * (d.x * d.x - d.y * d.y);
        s2 += a * 2 * d.x * d.y;
        ur_vec2 middle = ur_vec2_scale(
            ur_vec2_add(shading->triangles[t][0],
                        ur_vec2_add(shading->triangles[t][1], shading->triangles[t][2])),
            1.0 / 3);
        centre = ur_vec2_add_scaled(centre, middle, a);
        area += a;
        need->value = fmax(need->value, fabs(shading->strain[t]));
    }
    double angle = 0.5 * atan2(s2, c2);
    r->d = ur_vec2_make(cos(angle), sin(angle));
    r->n = relief_perpendicular(r->d);
    need->where =
        area > 0 ? ur_vec2_scale(centre, 1 / area) : shading->triangles[r->triangles[0]][0];
    r->low = r->across0 = INFINITY;
    r->high = r->across1 = -INFINITY;
    for (size_t i = 0; i < r->count; i++)
        for (int k = 0; k < 3; k++) {
            ur_vec2 p = shading->triangles[r->triangles[i]][k];
            r->low = fmin(r->low, ur_vec2_dot(p, r->d));
            r->high = fmax(r->high, ur_vec2_dot(p, r->d));
            r->across0 = fmin(r->across0, ur_vec2_dot(p, r->n));
            r->across1 = fmax(r->across1, ur_vec2_dot(p, r->n));
        }
}

/* The largest missing (or excess) length along d over RELIEF_LINES lines across the region. */
static double region_length(const ur_shading *shading, const region *r, double limit)
{
    double largest = 0;
    for (int j = 0; j < RELIEF_LINES; j++) {
        double w = r->across0 + (j + 0.5) * (r->across1 - r->across0) / RELIEF_LINES;
        double sum = 0;
        for (size_t i = 0; i < r->count; i++) {
            size_t t = r->triangles[i];
            double c = chord(shading->triangles[t], r->n, r->d, w);
            if (c <= 0)
                continue;
            double along = ur_vec2_dot(shading->direction[t], r->d);
            sum += c * excess_per_length(shading->strain[t], limit) * along * along;
        }
        largest = fmax(largest, sum);
    }
    return largest;
}

/* The region as one GEOS geometry in *area: the union of its triangles. */
static ur_status region_geometry(relief_job *job, const ur_shading *shading, const region *r,
                                 GEOSGeometry **area)
{
    *area = NULL;
    GEOSGeometry **polygons = ur_alloc_array(r->count, sizeof *polygons, job->error);
    if (!polygons)
        return UR_ERROR_MEMORY;
    size_t made = 0;
    for (; made < r->count; made++) {
        const ur_vec2 *c = shading->triangles[r->triangles[made]];
        ur_vec2 ring[3] = {c[0], c[1], c[2]};
        if (ur_polygon_signed_area(ring, 3) < 0) {
            ring[1] = c[2];
            ring[2] = c[1];
        }
        polygons[made] = geos_polygon_of_ring(job->geos, ring, 3);
        if (!polygons[made])
            break;
    }
    GEOSGeometry *collection = NULL, *uni = NULL;
    if (made == r->count)
        collection =
            GEOSGeom_createCollection_r(job->geos, GEOS_MULTIPOLYGON, polygons, (unsigned)made);
    else
        for (size_t i = 0; i < made; i++)
            GEOSGeom_destroy_r(job->geos, polygons[i]);
    free(polygons);
    if (collection) {
        uni = GEOSUnaryUnion_r(job->geos, collection);
        GEOSGeom_destroy_r(job->geos, collection);
    }
    *area = uni;
    return uni ? UR_OK : relief_geos_failed(job, "join a region's triangles");
}

/* The ends of the line across the region at distance c along d, reaching past it. */
static void line_across(const region *r, double c, double pad, ur_vec2 *a, ur_vec2 *b)
{
    ur_vec2 at = ur_vec2_scale(r->d, c);
    *a = ur_vec2_add_scaled(at, r->n, r->across0 - pad);
    *b = ur_vec2_add_scaled(at, r->n, r->across1 + pad);
}

static ur_status region_kerfing(relief_job *job, const region *r, const GEOSGeometry *area,
                                relief_need *need)
{
    GEOSGeometry *clip = GEOSIntersection_r(job->geos, area, job->inner);
    if (!clip)
        return relief_geos_failed(job, "clip a region to the margin");
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < need->wanted; k++) {
        ur_vec2 a, b;
        line_across(r, r->low + (k + 0.5) * (r->high - r->low) / need->wanted, 1, &a, &b);
        bool cut = false;
        status = relief_kerfing_slit(job, a, b, clip, &cut);
        need->cut += cut;
    }
    GEOSGeom_destroy_r(job->geos, clip);
    return status;
}

/* Each chord of the piece on the line a b that meets the region gets an overlap slit. */
static ur_status overlap_line(relief_job *job, ur_vec2 a, ur_vec2 b, const GEOSGeometry *area,
                              double w, ur_vec2 side, bool *cut)
{
    ur_points chords = {0};
    ur_status status = relief_clip_segment(job, a, b, job->outline, NULL, &chords);
    *cut = false;
    for (size_t i = 0; status == UR_OK && i + 1 < chords.count; i += 2) {
        ur_vec2 p = chords.items[i], q = chords.items[i + 1];
        double length = ur_vec2_distance(p, q);
        if (!(length > 0))
            continue;
        ur_vec2 u = ur_vec2_scale(ur_vec2_sub(q, p), 1 / length);
        ur_points parts = {0};
        status = relief_clip_segment(job, p, q, area, NULL, &parts);
        double low = INFINITY, high = -INFINITY;
        for (size_t j = 0; j < parts.count; j++) {
            double along = ur_vec2_dot(ur_vec2_sub(parts.items[j], p), u);
            low = fmin(low, along);
            high = fmax(high, along);
        }
        ur_points_free(&parts);
        bool one = false;
        if (status == UR_OK && high > low)
            status = relief_overlap_on_chord(job, p, q, low, high, w, side, &one);
        *cut = *cut || one;
    }
    ur_points_free(&chords);
    return status;
}

static ur_status region_overlaps(relief_job *job, const region *r, const GEOSGeometry *area,
                                 relief_need *need)
{
    double w = need->length / (double)need->wanted;
    ur_status status = UR_OK;
    double pad = job->size;
    for (size_t k = 0; status == UR_OK && k < need->wanted; k++) {
        ur_vec2 a, b;
        line_across(r, r->low + (k + 0.5) * (r->high - r->low) / need->wanted, pad, &a, &b);
        bool cut = false;
        status = overlap_line(job, a, b, area, w, r->d, &cut);
        need->cut += cut;
    }
    return status;
}

/* Measures one region and cuts what it needs. */
static ur_status relieve_region(relief_job *job, region *r, relief_kind kind)
{
    const ur_shading *shading = &job->net->shading;
    relief_need need = {kind, 0, 0, 0, {0, 0}, 0, 0};
    region_shape(shading, r, &need);
    need.limit = kind == RELIEF_KERFING ? job->limits->max_stretch : job->limits->max_compression;
    need.length = region_length(shading, r, need.limit);
    /* A quarter of a slit's opening the material takes by itself: no slit, nothing to say. */
    if (!(need.length > RELIEF_UNNOTICED * job->limits->opening))
        return UR_OK;
    need.wanted = relief_slit_count(need.length, job->limits->opening, r->high - r->low);
    GEOSGeometry *area;
    ur_status status = region_geometry(job, shading, r, &area);
    if (status != UR_OK)
        return status;
    size_t first = job->piece->path_count;
    status = kind == RELIEF_KERFING ? region_kerfing(job, r, area, &need)
                                    : region_overlaps(job, r, area, &need);
    GEOSGeom_destroy_r(job->geos, area);
    if (status == UR_OK)
        status = relief_keep_out_since(job, first);
    return status == UR_OK ? relief_record_need(job, &need, "across this region") : status;
}

/* Which relief each triangle asks for, by its dominant strain. */
static relief_kind triangle_kind(const ur_relief_limits *limits, double strain)
{
    if (limits->kerfing && -strain > fmax(limits->max_stretch, RELIEF_NEGLIGIBLE))
        return RELIEF_KERFING;
    if (limits->overlaps && strain > fmax(limits->max_compression, RELIEF_NEGLIGIBLE))
        return RELIEF_OVERLAP;
    return RELIEF_NONE;
}

/*
 * Each triangle's axis smoothed over its neighbours of the same kind, as
 * doubled-angle vectors weighted by area and strain, RELIEF_SMOOTHING
 * times: where the strain is nearly the same in every direction its axis is
 * noise, and neighbours would otherwise fall in different sectors.
 */
static ur_status smooth_axes(const ur_shading *shading, const size_t (*pairs)[2], size_t pair_count,
                             ur_vec2 *axes, ur_error *error)
{
    size_t count = shading->count;
    ur_vec2 *next = ur_alloc_array(count, sizeof *next, error);
    if (!next)
        return UR_ERROR_MEMORY;
    for (size_t t = 0; t < count; t++) {
        ur_vec2 d = shading->direction[t];
        double weight = triangle_area(shading->triangles[t]) * fabs(shading->strain[t]);
        axes[t] = ur_vec2_make(weight * (d.x * d.x - d.y * d.y), weight * 2 * d.x * d.y);
    }
    for (int pass = 0; pass < RELIEF_SMOOTHING; pass++) {
        memcpy(next, axes, count * sizeof *next);
        for (size_t i = 0; i < pair_count; i++) {
            size_t s = pairs[i][0], t = pairs[i][1];
            next[s] = ur_vec2_add(next[s], axes[t]);
            next[t] = ur_vec2_add(next[t], axes[s]);
        }
        memcpy(axes, next, count * sizeof *next);
    }
    free(next);
    return UR_OK;
}

/*
 * Which of four sectors of 45 degrees, centred on 0, 45, 90 and 135
 * degrees, the axis whose doubled angle points along v falls in.
 */
static int axis_sector(ur_vec2 v)
{
    double angle = 0.5 * atan2(v.y, v.x) + M_PI / 2 + M_PI / 8; /* 0 .. 9 pi / 8 */
    int sector = (int)floor(angle / (M_PI / 4));
    return sector % 4;
}

/* Joins the pairs whose triangles have the same kind and sector. */
static void join_regions(const ur_vec2 *axes, const size_t (*pairs)[2], size_t pair_count,
                         size_t count, size_t *parent)
{
    union_find_init(parent, count);
    for (size_t i = 0; i < pair_count; i++) {
        size_t s = pairs[i][0], t = pairs[i][1];
        if (axis_sector(axes[s]) == axis_sector(axes[t]))
            union_find_join(parent, s, t);
    }
}

typedef struct member {
    size_t root, triangle;
} member;

static int compare_members(const void *x, const void *y)
{
    const member *a = x, *b = y;
    if (a->root != b->root)
        return a->root < b->root ? -1 : 1;
    return a->triangle < b->triangle ? -1 : a->triangle > b->triangle;
}

/* Sorts the triangles that need relief by region and relieves each region. */
static ur_status relieve_regions(relief_job *job, const relief_kind *kind, size_t *parent)
{
    size_t count = job->net->shading.count, used = 0;
    member *members = ur_alloc_array(count, sizeof *members, job->error);
    size_t *triangles = ur_alloc_array(count, sizeof *triangles, job->error);
    ur_status status = members && triangles ? UR_OK : UR_ERROR_MEMORY;
    for (size_t t = 0; status == UR_OK && t < count; t++)
        if (kind[t] != RELIEF_NONE)
            members[used++] = (member){union_find_root(parent, t), t};
    if (status == UR_OK)
        qsort(members, used, sizeof *members, compare_members);
    /* Overlaps first: their slits reach the outline, kerfing slits keep clear of them. */
    for (int pass = 0; pass < 2; pass++) {
        relief_kind wanted = pass == 0 ? RELIEF_OVERLAP : RELIEF_KERFING;
        for (size_t i = 0; status == UR_OK && i < used;) {
            size_t j = i;
            for (; j < used && members[j].root == members[i].root; j++)
                triangles[j - i] = members[j].triangle;
            region r = {triangles, j - i, {0, 0}, {0, 0}, 0, 0, 0, 0};
            if (kind[members[i].triangle] == wanted)
                status = relieve_region(job, &r, wanted);
            i = j;
        }
    }
    free(members);
    free(triangles);
    return status;
}

static ur_status relieve_flattened(relief_job *job)
{
    const ur_shading *shading = &job->net->shading;
    if (!shading->triangles || !shading->strain || !shading->direction)
        return ur_error_set(job->error, UR_ERROR_INTERNAL,
                            "net '%s' has %zu shaded triangles but no strain directions",
                            job->net->name, shading->count);
    size_t count = shading->count, (*pairs)[2] = NULL, pair_count = 0;
    relief_kind *kind = ur_alloc_array(count, sizeof *kind, job->error);
    ur_vec2 *axes = ur_alloc_array(count, sizeof *axes, job->error);
    size_t *parent = ur_alloc_array(count, sizeof *parent, job->error);
    ur_status status = kind && axes && parent ? UR_OK : UR_ERROR_MEMORY;
    for (size_t t = 0; status == UR_OK && t < count; t++)
        kind[t] = triangle_kind(job->limits, shading->strain[t]);
    if (status == UR_OK)
        status = neighbour_pairs(shading, kind, &pairs, &pair_count, job->error);
    if (status == UR_OK)
        status = smooth_axes(shading, (const size_t(*)[2])pairs, pair_count, axes, job->error);
    if (status == UR_OK) {
        join_regions(axes, (const size_t(*)[2])pairs, pair_count, count, parent);
        status = relieve_regions(job, kind, parent);
    }
    free(pairs);
    free(kind);
    free(axes);
    free(parent);
    return status;
}

/* ---- Developed nets: along the rulings -------------------------------- */

/* The drawn ruling at fractional position f (0 the first, R - 1 the last), ends interpolated. */
static ur_segment ruling_at(const ur_net *net, double f)
{
    size_t i = (size_t)floor(f);
    if (i + 1 >= net->ruling_count)
        return net->rulings[net->ruling_count - 1];
    double t = f - (double)i;
    ur_segment s = {ur_vec2_lerp(net->rulings[i].start, net->rulings[i + 1].start, t),
                    ur_vec2_lerp(net->rulings[i].end, net->rulings[i + 1].end, t)};
    return s;
}

/* Slit k of n among R drawn rulings (relief.c header). */
static double ruling_position(size_t k, size_t n, size_t rulings)
{
    if (n <= rulings)
        return (k + 0.5) * (double)rulings / (double)n - 0.5;
    return n > 1 ? (double)k * (double)(rulings - 1) / (double)(n - 1) : 0;
}

static ur_vec2 outline_centre(const ur_net *net)
{
    double area = 0;
    ur_vec2 sum = {0, 0};
    for (size_t i = 0; i < net->outline_count; i++) {
        ur_vec2 a = net->outline[i], b = net->outline[(i + 1) % net->outline_count];
        double cross = ur_vec2_cross(a, b);
        area += cross;
        sum = ur_vec2_add_scaled(sum, ur_vec2_add(a, b), cross);
    }
    return area != 0 ? ur_vec2_scale(sum, 1 / (3 * area)) : net->outline[0];
}

/* One slit along the ruling at f: kerfing clipped to the margin, or overlap from its start. */
static ur_status ruling_slit(relief_job *job, const relief_need *need, double f, bool *cut)
{
    ur_segment s = ruling_at(job->net, f);
    double length = ur_vec2_distance(s.start, s.end);
    *cut = false;
    if (!(length > 0))
        return UR_OK;
    ur_vec2 u = ur_vec2_scale(ur_vec2_sub(s.end, s.start), 1 / length);
    if (need->kind == RELIEF_KERFING)
        return relief_kerfing_slit(job, ur_vec2_add_scaled(s.start, u, -1),
                                   ur_vec2_add_scaled(s.end, u, 1), job->inner, cut);
    /* The chord of the piece through the ruling: from its start (on the outline) across. */
    ur_points chords = {0};
    ur_status status = relief_clip_segment(job, ur_vec2_add_scaled(s.start, u, -0.01 * length),
                                           ur_vec2_add_scaled(s.end, u, 0.01 * length),
                                           job->outline, NULL, &chords);
    size_t best = SIZE_MAX;
    double nearest = INFINITY;
    for (size_t i = 0; status == UR_OK && i + 1 < chords.count; i += 2) {
        double gap = ur_vec2_distance(chords.items[i], s.start);
        if (gap < nearest) {
            nearest = gap;
            best = i;
        }
    }
    if (status == UR_OK && best != SIZE_MAX) {
        ur_vec2 a = chords.items[best], b = chords.items[best + 1];
        double chord_length = ur_vec2_distance(a, b);
        double w = need->length / (double)need->wanted;
        status =
            relief_overlap_on_chord(job, a, b, 0, chord_length, w, relief_perpendicular(u), cut);
    }
    ur_points_free(&chords);
    return status;
}

static ur_status relieve_rulings(relief_job *job, relief_need *need)
{
    const ur_net *net = job->net;
    double total = 0;
    for (size_t i = 0; i < net->ruling_count; i++)
        total += ur_vec2_distance(net->rulings[i].start, net->rulings[i].end);
    double mean = net->ruling_count ? total / (double)net->ruling_count : 0;
    need->length = mean > 0 ? fabs(net->area_3d - net->flat_area) / mean : 0;
    need->where = outline_centre(net);
    need->wanted = mean > 0 ? relief_slit_count(need->length, job->limits->opening, INFINITY) : 1;
    size_t placed = need->wanted;
    if (net->ruling_count < 2 && placed > net->ruling_count)
        placed = net->ruling_count; /* one ruling or none: no room between rulings */
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < placed; k++) {
        bool cut = false;
        status = ruling_slit(job, need, ruling_position(k, placed, net->ruling_count), &cut);
        need->cut += cut;
    }
    return status == UR_OK ? relief_record_need(job, need, "across its rulings") : status;
}

/*
 * What a developed net needs, from its coverage: kerfing, overlaps or
 * nothing (kind RELIEF_NONE), known before any geometry is made (an exact
 * development, a mesh's unfolded net, needs nothing).
 */
static relief_need developed_need(const ur_net *net, const ur_relief_limits *limits)
{
    relief_need need = {RELIEF_NONE, 0, 0, 0, {0, 0}, 0, 0};
    if (!(net->area_3d > 0) || !(net->flat_area > 0))
        return need;
    double coverage = net->flat_area / net->area_3d;
    if (limits->kerfing && 1 - coverage > fmax(limits->max_stretch, RELIEF_NEGLIGIBLE))
        need = (relief_need){RELIEF_KERFING, 1 - coverage, limits->max_stretch, 0, {0, 0}, 0, 0};
    else if (limits->overlaps && coverage - 1 > fmax(limits->max_compression, RELIEF_NEGLIGIBLE))
        need =
            (relief_need){RELIEF_OVERLAP, coverage - 1, limits->max_compression, 0, {0, 0}, 0, 0};
    return need;
}

/* ---- Entry ------------------------------------------------------------ */

static ur_status check_limits(const ur_piece *piece, const ur_relief_limits *limits,
                              ur_error *error)
{
    if (!limits || !(limits->max_stretch >= 0) || !(limits->max_compression >= 0) ||
        !(limits->opening > 0) || !(limits->margin >= 0) || !isfinite(limits->opening) ||
        !isfinite(limits->margin))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "piece '%s': the kerfing and overlap limits must be numbers >= 0 "
                            "and the opening > 0",
                            piece->name);
    return UR_OK;
}

static ur_status open_job(relief_job *job)
{
    const ur_net *net = job->net;
    job->geos = GEOS_init_r();
    if (!job->geos)
        return ur_error_out_of_memory(job->error);
    ur_box box = ur_box_of_points(net->outline, net->outline_count);
    job->size = hypot(ur_box_width(box), ur_box_height(box));
    job->outline = geos_polygon_of_ring(job->geos, net->outline, net->outline_count);
    if (job->outline)
        job->inner =
            job->limits->margin > 0
                ? allow_inside(job->geos, net->outline, net->outline_count, job->limits->margin, 8)
                : GEOSGeom_clone_r(job->geos, job->outline);
    return job->outline && job->inner ? UR_OK : relief_geos_failed(job, "buffer the outline");
}

static void close_job(relief_job *job)
{
    if (job->keepout)
        GEOSGeom_destroy_r(job->geos, job->keepout);
    if (job->inner)
        GEOSGeom_destroy_r(job->geos, job->inner);
    if (job->outline)
        GEOSGeom_destroy_r(job->geos, job->outline);
    if (job->geos)
        GEOS_finish_r(job->geos);
}

ur_status ur_piece_add_relief(ur_piece *piece, const ur_net *net, const ur_relief_limits *limits,
                              ur_error *error)
{
    ur_status status = check_limits(piece, limits, error);
    if (status != UR_OK || !(limits->kerfing || limits->overlaps))
        return status;
    if (!net || net->outline_count < 3)
        return ur_error_set(error, UR_ERROR_INPUT, "piece '%s' has no outline to relieve",
                            piece->name);
    bool flattened = net->shading.count > 0;
    relief_need need = developed_need(net, limits); /* a flattened net's is per triangle */
    if (!flattened && need.kind == RELIEF_NONE)
        return UR_OK;
    relief_job job = {NULL, piece, net, limits, NULL, NULL, NULL, 0, error};
    status = open_job(&job);
    if (status == UR_OK)
        status = flattened ? relieve_flattened(&job) : relieve_rulings(&job, &need);
    close_job(&job);
    return status;
}
