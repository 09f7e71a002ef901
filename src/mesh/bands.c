/*
 * bands.c: cutting a mesh into bands between parallel planes, for
 * flattening it in strips (flatten/strips.c): the direction across which it
 * bends most, planes that make bands of about equal width on the surface,
 * and the cut itself, which splits every triangle a plane crosses so that
 * the edges of the bands are the plane sections.
 *
 * Offsets along the direction d are s = p . d.  A point where a plane
 * crosses an edge is computed from the edge's lower-numbered vertex, so
 * both triangles on the edge agree on it to the last bit and the bands stay
 * joined to each other; such points are numbered once, by (edge, plane).
 */
#include "mesh_internal.h"

#include <gsl/gsl_eigen.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../base/gsl_errors.h"

/*
 * Below this (a fraction of the area, normals being unit vectors) the
 * normals do not vary: the mesh is flat and is cut across its longest
 * extent instead.
 */
#define FLAT_VARIATION 1e-12

/* Bins of offsets in which the band planes measure the surface's width. */
#define WIDTH_BINS 1024

/*
 * A triangle steeper than this to the planes (sine of its angle to them)
 * counts as this steep: a face lying in a plane has no width across it to
 * measure, and would otherwise take all the planes.
 */
#define LEAST_SLOPE 0.1

/*
 * A vertex closer to a plane than this fraction of the mesh's extent along
 * d is taken to lie on it, so that no sliver triangle comes out of the cut.
 * A plane at a distance h from a corner of angle a cuts off a triangle of
 * area about h^2 tan(a / 2), and flattening refuses one below
 * UR_MESH_ZERO_AREA (1e-12) of the size squared: at a millionth a corner
 * of 11 degrees came out too small (the sample head cut to fit a sheet at
 * 25 x); at this, only corners under about a degree can.
 */
#define ON_PLANE 1e-5

/* Twice the area vector of triangle t (its normal, as long as twice its area). */
static ur_vec3 area_vector(const ur_mesh *mesh, size_t t)
{
    const size_t *c = mesh->triangles[t];
    ur_vec3 p = mesh->vertices[c[0]];
    return ur_vec3_cross(ur_vec3_sub(mesh->vertices[c[1]], p),
                         ur_vec3_sub(mesh->vertices[c[2]], p));
}

static ur_vec3 centroid(const ur_mesh *mesh, size_t t)
{
    const size_t *c = mesh->triangles[t];
    ur_vec3 sum = ur_vec3_add(mesh->vertices[c[0]], mesh->vertices[c[1]]);
    return ur_vec3_scale(ur_vec3_add(sum, mesh->vertices[c[2]]), 1.0 / 3.0);
}

static ur_status check_mesh(const ur_mesh *mesh, ur_error *error)
{
    if (mesh->triangle_count == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "the mesh has no triangles");
    ur_status status = ur_mesh_check_vertices(mesh->vertices, mesh->vertex_count, error);
    if (status == UR_OK)
        status = mesh_check_triangles((const size_t(*)[3])mesh->triangles, mesh->triangle_count,
                                      mesh->vertex_count, error);
    return status;
}

static ur_status unit_direction(ur_vec3 direction, ur_vec3 *unit, ur_error *error)
{
    double length = ur_vec3_length(direction);
    if (!(length > 0) || !isfinite(length))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the direction of the bands (%g, %g, %g) must be a vector of finite, "
                            "non-zero length",
                            direction.x, direction.y, direction.z);
    *unit = ur_vec3_scale(direction, 1.0 / length);
    return UR_OK;
}

/* ---- The direction ------------------------------------------------------- */

/* A symmetric 3 x 3 matrix, a sum of weighted outer products. */
typedef struct outer_sum {
    double m[3][3];
} outer_sum;

static void outer_add(outer_sum *sum, ur_vec3 v, double weight)
{
    double c[3] = {v.x, v.y, v.z};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            sum->m[i][j] += weight * c[i] * c[j];
}

/*
 * The unit eigenvector of the largest eigenvalue (GSL), turned so that its
 * largest component is positive, which makes it the same on every machine.
 */
static ur_status largest_axis(const outer_sum *sum, ur_vec3 *axis, double *value, ur_error *error)
{
    double entries[9], vectors[9], values[3];
    memcpy(entries, sum->m, sizeof entries);
    gsl_matrix_view matrix = gsl_matrix_view_array(entries, 3, 3);
    gsl_matrix_view evec = gsl_matrix_view_array(vectors, 3, 3);
    gsl_vector_view eval = gsl_vector_view_array(values, 3);
    gsl_errors_off();
    gsl_eigen_symmv_workspace *work = gsl_eigen_symmv_alloc(3);
    bool allocated = work != NULL;
    int failed = allocated ? gsl_eigen_symmv(&matrix.matrix, &eval.vector, &evec.matrix, work) : 0;
    if (allocated)
        gsl_eigen_symmv_free(work);
    gsl_errors_restore();
    if (!allocated)
        return ur_error_out_of_memory(error);
    if (failed)
        return ur_error_set(error, UR_ERROR_INTERNAL, "no eigenvectors of the normals' spread");
    gsl_eigen_symmv_sort(&eval.vector, &evec.matrix, GSL_EIGEN_SORT_VAL_DESC);
    ur_vec3 v = ur_vec3_make(vectors[0], vectors[3], vectors[6]); /* column 0 */
    double largest = fabs(v.x) >= fabs(v.y) && fabs(v.x) >= fabs(v.z) ? v.x
                     : fabs(v.y) >= fabs(v.z)                         ? v.y
                                                                      : v.z;
    *axis = ur_vec3_scale(v, largest < 0 ? -1.0 : 1.0);
    *value = values[0];
    return UR_OK;
}

/* The axis along which the triangles (by area) spread most: a flat mesh's longest extent. */
static ur_status longest_extent(const ur_mesh *mesh, ur_vec3 *axis, ur_error *error)
{
    ur_vec3 mean = {0, 0, 0};
    double total = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        double area = 0.5 * ur_vec3_length(area_vector(mesh, t));
        mean = ur_vec3_add_scaled(mean, centroid(mesh, t), area);
        total += area;
    }
    mean = ur_vec3_scale(mean, 1.0 / total);
    outer_sum spread = {{{0}}};
    for (size_t t = 0; t < mesh->triangle_count; t++)
        outer_add(&spread, ur_vec3_sub(centroid(mesh, t), mean),
                  0.5 * ur_vec3_length(area_vector(mesh, t)));
    double value;
    return largest_axis(&spread, axis, &value, error);
}

/*
 * The normals' spread about their mean, sum of area (n - m)(n - m)^T:
 * its largest eigenvector is the direction in which the normals turn
 * most.  Centred, so that the mean normal of a shallow shell, which does
 * not vary, does not count.
 */
ur_status ur_mesh_bending_direction(const ur_mesh *mesh, ur_vec3 *direction, ur_error *error)
{
    ur_status status = check_mesh(mesh, error);
    if (status != UR_OK)
        return status;
    ur_vec3 mean = {0, 0, 0};
    double total = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        ur_vec3 twice = area_vector(mesh, t);
        mean = ur_vec3_add_scaled(mean, twice, 0.5); /* area times unit normal */
        total += 0.5 * ur_vec3_length(twice);
    }
    if (!(total > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "the mesh has no area");
    mean = ur_vec3_scale(mean, 1.0 / total);
    outer_sum spread = {{{0}}};
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        ur_vec3 twice = area_vector(mesh, t);
        double length = ur_vec3_length(twice);
        if (length > 0)
            outer_add(&spread, ur_vec3_sub(ur_vec3_scale(twice, 1.0 / length), mean), 0.5 * length);
    }
    double value;
    status = largest_axis(&spread, direction, &value, error);
    if (status == UR_OK && !(value > FLAT_VARIATION * total))
        status = longest_extent(mesh, direction, error);
    return status;
}

/* ---- The planes ---------------------------------------------------------- */

/* The least and greatest offset of a triangle corner along d. */
static void extent(const ur_mesh *mesh, ur_vec3 d, double *low, double *high)
{
    *low = INFINITY;
    *high = -INFINITY;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            double s = ur_vec3_dot(mesh->vertices[mesh->triangles[t][k]], d);
            *low = fmin(*low, s);
            *high = fmax(*high, s);
        }
}

double mesh_fraction_below(const double s[3], double x)
{
    if (x <= s[0])
        return 0.0;
    if (x >= s[2])
        return 1.0;
    if (x <= s[1])
        return (x - s[0]) * (x - s[0]) / ((s[1] - s[0]) * (s[2] - s[0]));
    return 1.0 - (s[2] - x) * (s[2] - x) / ((s[2] - s[1]) * (s[2] - s[0]));
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Where the surface's width is measured: WIDTH_BINS bins of offsets from low. */
typedef struct width_bins {
    double low, step;
    double area[WIDTH_BINS];   /* surface area in each bin */
    double across[WIDTH_BINS]; /* sum of area times slope: section length times step */
} width_bins;

static size_t bin_of(const width_bins *bins, double s)
{
    double i = floor((s - bins->low) / bins->step);
    return i <= 0 ? 0 : i >= WIDTH_BINS - 1 ? WIDTH_BINS - 1 : (size_t)i;
}

/*
 * Shares triangle t's area out among the bins it spans, exactly for a
 * triangle (the area below an offset is quadratic in it).  The outer bins
 * reach to infinity and the range starts a bin early and ends a bin late,
 * so that rounding loses no area.
 */
static void bin_triangle(const ur_mesh *mesh, size_t t, ur_vec3 d, width_bins *bins)
{
    ur_vec3 twice = area_vector(mesh, t);
    double area = 0.5 * ur_vec3_length(twice);
    if (!(area > 0))
        return;
    double normal_d = ur_vec3_dot(twice, d) / (2 * area);
    double slope = fmax(sqrt(fmax(0.0, 1 - normal_d * normal_d)), LEAST_SLOPE);
    double s[3];
    for (int k = 0; k < 3; k++)
        s[k] = ur_vec3_dot(mesh->vertices[mesh->triangles[t][k]], d);
    qsort(s, 3, sizeof s[0], compare_doubles);
    size_t first = bin_of(bins, s[0]), last = bin_of(bins, s[2]);
    first = first > 0 ? first - 1 : 0;
    last = last < WIDTH_BINS - 1 ? last + 1 : last;
    double below = first == 0 ? 0.0 : mesh_fraction_below(s, bins->low + first * bins->step);
    for (size_t i = first; i <= last; i++) {
        double up =
            i == WIDTH_BINS - 1 ? 1.0 : mesh_fraction_below(s, bins->low + (i + 1) * bins->step);
        bins->area[i] += area * (up - below);
        bins->across[i] += area * (up - below) * slope;
        below = up;
    }
}

/*
 * Plane j of count - 1 where the cumulative width reaches j / count of the
 * whole.  A bin's width on the surface is its area over its section length
 * (step * area / across); an empty bin, a gap in the mesh, has none.
 */
static void place_planes(const width_bins *bins, size_t count, double *planes)
{
    double width[WIDTH_BINS], total = 0;
    for (size_t i = 0; i < WIDTH_BINS; i++) {
        width[i] = bins->area[i] > 0 ? bins->step * bins->area[i] / bins->across[i] : 0.0;
        total += width[i];
    }
    double before = 0; /* width of the bins before bin i */
    size_t i = 0;
    for (size_t j = 1; j < count; j++) {
        double target = total * (double)j / (double)count;
        while (i < WIDTH_BINS - 1 && before + width[i] < target)
            before += width[i++];
        double fraction = width[i] > 0 ? fmin(1.0, (target - before) / width[i]) : 0.0;
        planes[j - 1] = bins->low + ((double)i + fraction) * bins->step;
    }
}

static ur_status check_planes(const double *planes, size_t count, ur_error *error)
{
    for (size_t j = 0; j < count; j++)
        if (!isfinite(planes[j]) || (j > 0 && !(planes[j] > planes[j - 1])))
            return ur_error_set(error, UR_ERROR_INPUT,
                                "the offsets of the planes between bands must be finite and "
                                "increase (plane %zu is at %g)",
                                j + 1, planes[j]);
    return UR_OK;
}

ur_status ur_mesh_band_planes(const ur_mesh *mesh, ur_vec3 direction, size_t count, double *planes,
                              ur_error *error)
{
    ur_vec3 d;
    ur_status status = check_mesh(mesh, error);
    if (status == UR_OK)
        status = unit_direction(direction, &d, error);
    if (status == UR_OK && count == 0)
        status = ur_error_set(error, UR_ERROR_INPUT, "a mesh is cut into 1 band or more, not 0");
    if (status != UR_OK || count == 1)
        return status;
    width_bins *bins = ur_alloc_array(1, sizeof *bins, error);
    if (!bins)
        return UR_ERROR_MEMORY;
    double high;
    extent(mesh, d, &bins->low, &high);
    bins->step = (high - bins->low) / WIDTH_BINS;
    if (!(bins->step > 0))
        status = ur_error_set(error, UR_ERROR_INPUT,
                              "the mesh has no extent along (%g, %g, %g) to cut into bands", d.x,
                              d.y, d.z);
    for (size_t t = 0; status == UR_OK && t < mesh->triangle_count; t++)
        bin_triangle(mesh, t, d, bins);
    if (status == UR_OK)
        place_planes(bins, count, planes);
    free(bins);
    if (status == UR_OK && check_planes(planes, count - 1, NULL) != UR_OK)
        status = ur_error_set(error, UR_ERROR_INPUT,
                              "the mesh is too thin along (%g, %g, %g) to cut into %zu bands", d.x,
                              d.y, d.z, count);
    return status;
}

/* ---- The cut ------------------------------------------------------------- */

/* The point where plane j crosses the edge between vertices a < b. */
typedef struct crossing {
    size_t a, b, plane;
} crossing;

static int compare_crossings(const void *x, const void *y)
{
    const crossing *p = x, *q = y;
    if (p->a != q->a)
        return (p->a > q->a) - (p->a < q->a);
    if (p->b != q->b)
        return (p->b > q->b) - (p->b < q->b);
    return (p->plane > q->plane) - (p->plane < q->plane);
}

typedef struct band_cut {
    const ur_mesh *mesh;
    const double *planes;
    size_t plane_count;
    double *s;           /* offset of each vertex, snapped onto a plane it nearly lies on */
    crossing *crossings; /* sorted, each once */
    size_t crossing_count;
} band_cut;

/* How many planes lie below x (strictly, or also at x). */
static size_t planes_below(const band_cut *c, double x, bool at_too)
{
    size_t low = 0, high = c->plane_count;
    while (low < high) {
        size_t mid = low + (high - low) / 2;
        if (c->planes[mid] < x || (at_too && c->planes[mid] == x))
            low = mid + 1;
        else
            high = mid;
    }
    return low;
}

/* Each vertex's offset from the field, snapped onto a plane it nearly lies on. */
static void snap_offsets(band_cut *c, const double *field)
{
    const ur_mesh *mesh = c->mesh;
    double low = INFINITY, high = -INFINITY;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            low = fmin(low, field[mesh->triangles[t][k]]);
            high = fmax(high, field[mesh->triangles[t][k]]);
        }
    double near = ON_PLANE * (high - low);
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        double s = field[v];
        size_t j = planes_below(c, s, false); /* planes[j - 1] < s <= planes[j] */
        if (j < c->plane_count && c->planes[j] - s <= near)
            s = c->planes[j];
        else if (j > 0 && s - c->planes[j - 1] <= near)
            s = c->planes[j - 1];
        c->s[v] = s;
    }
}

/* Lists (or counts, list NULL) the crossings of every triangle's edges: each edge's twice. */
static size_t list_crossings(const band_cut *c, crossing *list)
{
    size_t count = 0;
    for (size_t t = 0; t < c->mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            size_t p = c->mesh->triangles[t][k], q = c->mesh->triangles[t][(k + 1) % 3];
            size_t a = p < q ? p : q, b = p < q ? q : p;
            double low = fmin(c->s[a], c->s[b]), high = fmax(c->s[a], c->s[b]);
            size_t first = planes_below(c, low, true), end = planes_below(c, high, false);
            for (size_t j = first; j < end; j++, count++)
                if (list)
                    list[count] = (crossing){a, b, j};
        }
    return count;
}

static ur_status find_crossings(band_cut *c, ur_error *error)
{
    size_t count = list_crossings(c, NULL);
    c->crossings = ur_alloc_array(count, sizeof *c->crossings, error);
    if (!c->crossings)
        return UR_ERROR_MEMORY;
    list_crossings(c, c->crossings);
    qsort(c->crossings, count, sizeof *c->crossings, compare_crossings);
    size_t kept = 0;
    for (size_t i = 0; i < count; i++)
        if (kept == 0 || compare_crossings(&c->crossings[i], &c->crossings[kept - 1]) != 0)
            c->crossings[kept++] = c->crossings[i];
    c->crossing_count = kept;
    return UR_OK;
}

/* The vertex of the banded mesh where plane j crosses the edge p q (listed, so found). */
static size_t crossing_vertex(const band_cut *c, size_t p, size_t q, size_t j)
{
    crossing key = {p < q ? p : q, p < q ? q : p, j};
    const crossing *found =
        bsearch(&key, c->crossings, c->crossing_count, sizeof key, compare_crossings);
    return c->mesh->vertex_count + (size_t)(found - c->crossings);
}

static ur_vec3 crossing_point(const band_cut *c, const crossing *x)
{
    ur_vec3 pa = c->mesh->vertices[x->a], pb = c->mesh->vertices[x->b];
    double t = (c->planes[x->plane] - c->s[x->a]) / (c->s[x->b] - c->s[x->a]);
    return ur_vec3_add_scaled(pa, ur_vec3_sub(pb, pa), t);
}

/* The bands a triangle has area in: first to last; both the same for one in a plane. */
static void triangle_bands(const band_cut *c, size_t t, size_t *first, size_t *last)
{
    const size_t *v = c->mesh->triangles[t];
    double low = fmin(c->s[v[0]], fmin(c->s[v[1]], c->s[v[2]]));
    double high = fmax(c->s[v[0]], fmax(c->s[v[1]], c->s[v[2]]));
    *first = planes_below(c, low, true);
    *last = low < high ? planes_below(c, high, false) : *first;
}

/*
 * The part of triangle t in band b, a convex polygon: walking round the
 * triangle, its corners inside the band and the points where the band's
 * two planes cross its edges, in order.  A corner on a plane belongs to
 * both bands; crossings are strict, so no point comes twice.
 */
static size_t band_polygon(const band_cut *c, size_t t, size_t b, size_t polygon[9])
{
    double low = b > 0 ? c->planes[b - 1] : -INFINITY;
    double high = b < c->plane_count ? c->planes[b] : INFINITY;
    size_t n = 0;
    for (int k = 0; k < 3; k++) {
        size_t p = c->mesh->triangles[t][k], q = c->mesh->triangles[t][(k + 1) % 3];
        double sp = c->s[p], sq = c->s[q];
        if (low <= sp && sp <= high)
            polygon[n++] = p;
        bool up = sp < sq;
        double first = up ? low : high, second = up ? high : low;
        size_t first_plane = up ? b - 1 : b, second_plane = up ? b : b - 1;
        if (fmin(sp, sq) < first && first < fmax(sp, sq))
            polygon[n++] = crossing_vertex(c, p, q, first_plane);
        if (fmin(sp, sq) < second && second < fmax(sp, sq))
            polygon[n++] = crossing_vertex(c, p, q, second_plane);
    }
    return n;
}

/* How well shaped a triangle is: 4 sqrt(3) area over the sum of squared sides (1 equilateral). */
static double shape(const ur_vec3 *vertices, size_t a, size_t b, size_t c)
{
    ur_vec3 ab = ur_vec3_sub(vertices[b], vertices[a]), ac = ur_vec3_sub(vertices[c], vertices[a]);
    ur_vec3 bc = ur_vec3_sub(vertices[c], vertices[b]);
    double sides = ur_vec3_dot(ab, ab) + ur_vec3_dot(ac, ac) + ur_vec3_dot(bc, bc);
    return sides > 0 ? 2 * sqrt(3.0) * ur_vec3_length(ur_vec3_cross(ab, ac)) / sides : 0.0;
}

/* The corner to fan a convex polygon from so that its worst triangle is the best it can be. */
static size_t fan_apex(const ur_vec3 *vertices, const size_t *polygon, size_t n)
{
    size_t best = 0;
    double best_worst = -1;
    for (size_t apex = 0; apex < n; apex++) {
        double worst = INFINITY;
        for (size_t i = 1; i + 1 < n; i++)
            worst = fmin(worst, shape(vertices, polygon[apex], polygon[(apex + i) % n],
                                      polygon[(apex + i + 1) % n]));
        if (worst > best_worst) {
            best_worst = worst;
            best = apex;
        }
    }
    return best;
}

/*
 * Writes (or counts, when banded has no arrays) the triangles of the
 * banded mesh: band by band, each triangle's part in the band fanned from
 * its best corner.  Group g of the input becomes b * group_count + g.
 */
static size_t emit_triangles(const band_cut *c, ur_mesh *banded)
{
    const ur_mesh *mesh = c->mesh;
    size_t groups = mesh->group_count > 0 ? mesh->group_count : 1, count = 0;
    for (size_t b = 0; b <= c->plane_count; b++)
        for (size_t t = 0; t < mesh->triangle_count; t++) {
            size_t first, last, polygon[9];
            triangle_bands(c, t, &first, &last);
            if (b < first || b > last)
                continue;
            size_t n = band_polygon(c, t, b, polygon);
            size_t apex = n >= 3 && banded->triangles ? fan_apex(banded->vertices, polygon, n) : 0;
            for (size_t i = 1; i + 1 < n; i++, count++) {
                if (!banded->triangles)
                    continue;
                size_t *out = banded->triangles[count];
                out[0] = polygon[apex];
                out[1] = polygon[(apex + i) % n];
                out[2] = polygon[(apex + i + 1) % n];
                banded->groups[count] = b * groups + (mesh->groups ? mesh->groups[t] : 0);
            }
        }
    return count;
}

static ur_status build_banded(const band_cut *c, ur_mesh *banded, ur_error *error)
{
    const ur_mesh *mesh = c->mesh;
    size_t vertex_count = mesh->vertex_count + c->crossing_count;
    size_t triangle_count = emit_triangles(c, banded); /* counts: no arrays yet */
    banded->vertices = ur_alloc_array(vertex_count, sizeof *banded->vertices, error);
    banded->triangles = ur_alloc_array(triangle_count, sizeof *banded->triangles, error);
    banded->groups = ur_alloc_array(triangle_count, sizeof *banded->groups, error);
    if (!banded->vertices || !banded->triangles || !banded->groups)
        return UR_ERROR_MEMORY;
    memcpy(banded->vertices, mesh->vertices, mesh->vertex_count * sizeof *mesh->vertices);
    for (size_t i = 0; i < c->crossing_count; i++)
        banded->vertices[mesh->vertex_count + i] = crossing_point(c, &c->crossings[i]);
    emit_triangles(c, banded);
    banded->vertex_count = vertex_count;
    banded->triangle_count = triangle_count;
    banded->group_count = (c->plane_count + 1) * (mesh->group_count > 0 ? mesh->group_count : 1);
    return UR_OK;
}

ur_status ur_mesh_bands(const ur_mesh *mesh, ur_vec3 direction, const double *planes, size_t count,
                        ur_mesh *banded, ur_error *error)
{
    memset(banded, 0, sizeof *banded);
    ur_vec3 d;
    ur_status status = check_mesh(mesh, error);
    if (status == UR_OK)
        status = unit_direction(direction, &d, error);
    if (status != UR_OK)
        return status;
    double *field = ur_alloc_array(mesh->vertex_count + 1, sizeof *field, error);
    if (!field)
        return UR_ERROR_MEMORY;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        field[v] = ur_vec3_dot(mesh->vertices[v], d);
    status = mesh_bands_of_field(mesh, field, planes, count, banded, error);
    free(field);
    return status;
}

ur_status mesh_bands_of_field(const ur_mesh *mesh, const double *field, const double *planes,
                              size_t count, ur_mesh *banded, ur_error *error)
{
    memset(banded, 0, sizeof *banded);
    ur_status status = check_mesh(mesh, error);
    if (status == UR_OK && count == 0)
        status = ur_error_set(error, UR_ERROR_INPUT, "a mesh is cut into 1 band or more, not 0");
    if (status == UR_OK)
        status = check_planes(planes, count - 1, error);
    if (status != UR_OK)
        return status;
    band_cut c = {.mesh = mesh, .planes = planes, .plane_count = count - 1};
    c.s = ur_alloc_array(mesh->vertex_count, sizeof *c.s, error);
    if (!c.s)
        return UR_ERROR_MEMORY;
    snap_offsets(&c, field);
    status = find_crossings(&c, error);
    if (status == UR_OK)
        status = build_banded(&c, banded, error);
    if (status != UR_OK)
        ur_mesh_free(banded);
    free(c.crossings);
    free(c.s);
    return status;
}
