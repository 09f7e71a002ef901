/*
 * test_properties.c: the geometry fuzzed with a property test.  Random
 * valid surfaces from fixed seeds (helicoids, cones and frustums over
 * circles and over random closed curves, strips between rails on random
 * twisted cubics, random small meshes) go through the library as the
 * command takes them, and every result must keep the invariants of the
 * earlier issues:
 *
 *   - nothing fails and no output point is NaN or infinite;
 *   - an exact development keeps the area: its nets' flat area equals the
 *     surface's area worked out here independently (closed forms for the
 *     helicoid and the circular cone, this file's own quadrature of
 *     |r_u x r_v| otherwise), within what the outline's chords may cut off;
 *   - every net is a simple polygon (a net that would overlap itself is split);
 *   - a flat mesh flattens without strain and keeps its area;
 *   - nested parts never overlap (GEOS intersection area 0), keep the
 *     spacing and stay inside the sheet's margin.
 *
 * The seeds are fixed, so a failure repeats; the message names the case.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <geos_c.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/allow.h"
#include "unroll/develop.h"
#include "unroll/flatten.h"
#include "unroll/mesh.h"
#include "unroll/nest.h"

#include "test_support.h"

/* ---- Random numbers: xorshift64*, so that every run draws the same cases ---- */

typedef struct rng {
    uint64_t state;
} rng;

static double uniform(rng *r, double low, double high)
{
    r->state ^= r->state >> 12;
    r->state ^= r->state << 25;
    r->state ^= r->state >> 27;
    uint64_t bits = r->state * 0x2545F4914F6CDD1DULL;
    return low + (high - low) * (double)(bits >> 11) / 9007199254740992.0;
}

/* ---- Checks on nets ----------------------------------------------------- */

static bool finite2(ur_vec2 p)
{
    return isfinite(p.x) && isfinite(p.y);
}

static double outline_perimeter(const ur_net *net)
{
    double length = 0;
    for (size_t i = 0; i < net->outline_count; i++)
        length += ur_vec2_length(
            ur_vec2_sub(net->outline[(i + 1) % net->outline_count], net->outline[i]));
    return length;
}

/* No NaN anywhere, every outline simple; returns the flat area and the total perimeter. */
static void check_nets(const char *what, const ur_net_list *nets, double *area, double *perimeter)
{
    *area = *perimeter = 0;
    assert_true(nets->count > 0);
    for (size_t k = 0; k < nets->count; k++) {
        const ur_net *net = &nets->nets[k];
        assert_true(net->outline_count >= 3);
        for (size_t i = 0; i < net->outline_count; i++)
            if (!finite2(net->outline[i]))
                fail_msg("%s: net %zu: outline point %zu is not finite", what, k, i);
        for (size_t i = 0; i < net->ruling_count; i++)
            if (!finite2(net->rulings[i].start) || !finite2(net->rulings[i].end))
                fail_msg("%s: net %zu: ruling %zu is not finite", what, k, i);
        if (!ur_outline_is_simple(net->outline, net->outline_count))
            fail_msg("%s: net %zu of %zu overlaps itself", what, k, nets->count);
        if (!(isfinite(net->flat_area) && net->flat_area > 0))
            fail_msg("%s: net %zu: flat area %g", what, k, net->flat_area);
        *area += net->flat_area;
        *perimeter += outline_perimeter(net);
    }
}

/*
 * An exact development keeps the area.  The outline is made of chords within
 * the tolerance of the true boundary: between a chord and its arc lies at
 * most 2/3 of tolerance times the chord (a parabolic segment of that
 * height), so the outline can miss at most 2/3 tolerance times its length.
 * The relative slack 1e-5 covers the integrations (the development's ODE
 * for the geodesic curvature, the area's quadrature), each good to about
 * 1e-7.
 */
static void expect_area(const char *what, const ur_net_list *nets, double expected,
                        double tolerance)
{
    double area, perimeter;
    check_nets(what, nets, &area, &perimeter);
    double allowed = 2.0 / 3.0 * tolerance * perimeter + 1e-5 * expected;
    if (!(fabs(area - expected) <= allowed))
        fail_msg("%s: nets %.9g mm2, surface %.9g mm2: off by %.3g, more than %.3g", what, area,
                 expected, area - expected, allowed);
}

static ur_net_list develop_exact(const char *what, ur_ruled *ruled, double tolerance)
{
    ur_develop_options options;
    ur_develop_options_default(&options);
    options.tolerance = tolerance;
    ur_net_list nets;
    ur_error error;
    if (ur_develop(ruled, &options, &nets, &error) != UR_OK)
        fail_msg("%s: develop: %s", what, error.message);
    return nets;
}

/* ---- The surface's area, independently ---------------------------------- */

/*
 * The area of ruled between u0 and u1: Simpson's rule in u over n (even)
 * intervals, 4-point Gauss-Legendre in v, of |r_u x r_v| with
 * r_u = a' + v (b' - a') and r_v = b - a, from the rails alone.
 */
static double quadrature_area(ur_ruled *ruled, double u0, double u1, size_t n)
{
    static const double nodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                    0.8611363115940526};
    static const double weights[4] = {0.3478548451374538, 0.6521451548625473, 0.6521451548625473,
                                      0.3478548451374538};
    double h = (u1 - u0) / (double)n, sum = 0;
    for (size_t i = 0; i <= n; i++) {
        double u = i == n ? u1 : u0 + h * (double)i;
        ur_vec3 rails[4];
        ur_ruled_rails(ruled, u, rails);
        ur_vec3 across = ur_vec3_sub(rails[2], rails[0]);
        ur_vec3 turn = ur_vec3_sub(rails[3], rails[1]);
        double width = 0;
        for (int g = 0; g < 4; g++) {
            double v = 0.5 * (nodes[g] + 1);
            ur_vec3 r_u = ur_vec3_add(rails[1], ur_vec3_scale(turn, v));
            width += 0.5 * weights[g] * ur_vec3_length(ur_vec3_cross(r_u, across));
        }
        double simpson = i == 0 || i == n ? 1 : (i % 2 ? 4 : 2);
        sum += simpson * width;
    }
    return sum * h / 3;
}

/* ---- Helicoids: closed form ---------------------------------------------- */

/*
 * The tangent developable of a helix of radius R and pitch P = 2 pi c,
 * from offset to offset + width along the tangents: per unit arc length s
 * the area is kappa v dv integrated, kappa = R / (R^2 + c^2), over
 * turns 2 pi sqrt(R^2 + c^2) of arc.
 */
static double helicoid_area(double radius, double pitch, double turns, double offset, double width)
{
    double c = pitch / (2 * M_PI);
    double kappa = radius / (radius * radius + c * c);
    double length = turns * 2 * M_PI * sqrt(radius * radius + c * c);
    double far = offset + width;
    return kappa * (far * far - offset * offset) / 2 * length;
}

/* ---- Nesting -------------------------------------------------------------- */

static GEOSContextHandle_t geos;

/* A placed piece as a GEOS polygon (outline only: the nets have no holes). */
static GEOSGeometry *placed_outline(const ur_piece *piece, ur_transform2 t)
{
    const ur_path *path = &piece->paths[0];
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)path->count + 1, 2);
    assert_non_null(sequence);
    for (size_t i = 0; i <= path->count; i++) {
        ur_vec2 p = ur_transform2_apply(t, path->points[i % path->count]);
        assert_true(finite2(p));
        assert_int_equal(GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, p.x, p.y), 1);
    }
    GEOSGeometry *ring = GEOSGeom_createLinearRing_r(geos, sequence);
    assert_non_null(ring);
    GEOSGeometry *polygon = GEOSGeom_createPolygon_r(geos, ring, NULL, 0);
    assert_non_null(polygon);
    return polygon;
}

/* Every part once, inside the margin, no two closer than the spacing, none overlapping. */
static void check_layout(const char *what, const ur_piece *pieces, size_t count,
                         const ur_layout *layout, const ur_nest_options *o)
{
    size_t placed_count = layout->not_placed_count;
    for (size_t s = 0; s < layout->sheet_count; s++) {
        const ur_sheet *sheet = &layout->sheets[s];
        size_t n = sheet->placement_count;
        placed_count += n;
        GEOSGeometry **placed = calloc(n, sizeof *placed);
        assert_non_null(placed);
        for (size_t p = 0; p < n; p++) {
            const ur_placement *placement = &sheet->placements[p];
            assert_true(placement->piece_index < count);
            placed[p] = placed_outline(&pieces[placement->piece_index], placement->transform);
            double x0, y0, x1, y1;
            GEOSGeom_getXMin_r(geos, placed[p], &x0);
            GEOSGeom_getYMin_r(geos, placed[p], &y0);
            GEOSGeom_getXMax_r(geos, placed[p], &x1);
            GEOSGeom_getYMax_r(geos, placed[p], &y1);
            if (x0 < o->margin - 1e-3 || y0 < o->margin - 1e-3 ||
                x1 > sheet->width - o->margin + 1e-3 || y1 > sheet->height - o->margin + 1e-3)
                fail_msg("%s: sheet %zu: a part (%g..%g, %g..%g) leaves the %g x %g sheet's "
                         "margin %g",
                         what, s, x0, x1, y0, y1, sheet->width, sheet->height, o->margin);
        }
        for (size_t p = 0; p < n; p++)
            for (size_t q = p + 1; q < n; q++) {
                double distance = 0, area = -1;
                assert_int_equal(GEOSDistance_r(geos, placed[p], placed[q], &distance), 1);
                GEOSGeometry *both = GEOSIntersection_r(geos, placed[p], placed[q]);
                assert_non_null(both);
                assert_int_equal(GEOSArea_r(geos, both, &area), 1);
                GEOSGeom_destroy_r(geos, both);
                /* Nesting keeps the spacing to a micrometre (nest.h). */
                if (area != 0 || distance < o->spacing - 1e-3)
                    fail_msg("%s: sheet %zu: parts %zu and %zu overlap by %g mm2, %g mm apart "
                             "(spacing %g)",
                             what, s, p, q, area, distance, o->spacing);
            }
        for (size_t p = 0; p < n; p++)
            GEOSGeom_destroy_r(geos, placed[p]);
        free(placed);
    }
    assert_int_equal(placed_count, count);
}

/*
 * The nets as pieces, each two to four times (so that parts meet), nested
 * on random sheets with random margin, spacing and turns.
 */
static void nest_and_check(const char *what, rng *r, const ur_net_list *nets)
{
    size_t copies = (size_t)uniform(r, 2, 5), count = copies * nets->count;
    ur_piece *pieces = calloc(count, sizeof *pieces);
    assert_non_null(pieces);
    ur_allowance_options allowances = {true};
    ur_error error;
    double largest = 0;
    for (size_t k = 0; k < nets->count; k++) {
        if (ur_piece_from_net(&nets->nets[k], &allowances, &pieces[k], &error) != UR_OK)
            fail_msg("%s: piece %zu: %s", what, k, error.message);
        ur_box box = pieces[k].box;
        largest = fmax(largest, hypot(box.max.x - box.min.x, box.max.y - box.min.y));
        for (size_t c = 1; c < copies; c++)
            assert_int_equal(ur_piece_copy(&pieces[k], &pieces[c * nets->count + k], NULL), UR_OK);
    }
    ur_nest_options o;
    memset(&o, 0, sizeof o);
    o.margin = uniform(r, 0, 10);
    o.spacing = uniform(r, 0.5, 5);
    /* Room for the largest part in any turn, and often for only a few parts a sheet. */
    o.sheet_width = largest + 2 * o.margin + uniform(r, 1, 200);
    o.sheet_height = largest + 2 * o.margin + uniform(r, 1, 200);
    o.rotations = (size_t)uniform(r, 1, 9);
    o.level = uniform(r, 0, 1) < 0.5;
    o.holes = true;
    ur_layout layout;
    if (ur_layout_nest(pieces, count, &o, &layout, &error) != UR_OK)
        fail_msg("%s: nest: %s", what, error.message);
    check_layout(what, pieces, count, &layout, &o);
    ur_layout_free(&layout);
    for (size_t k = 0; k < count; k++)
        ur_piece_free(&pieces[k]);
    free(pieces);
}

/* ---- The properties ------------------------------------------------------- */

static void test_random_helicoids(void **state)
{
    (void)state;
    rng r = {0x9E3779B97F4A7C15ULL};
    for (int i = 0; i < 12; i++) {
        double radius = uniform(&r, 5, 60), pitch = uniform(&r, 10, 150);
        double turns = uniform(&r, 0.2, 2.5), offset = uniform(&r, 0, 10);
        double width = uniform(&r, 3, 40);
        char what[160];
        snprintf(what, sizeof what, "helicoid %d (R %g, P %g, %g turns, offset %g, width %g)", i,
                 radius, pitch, turns, offset, width);
        ur_curve *curve;
        ur_ruled ruled;
        assert_int_equal(ur_curve_new_helix(radius, pitch, 0, 2 * M_PI * turns, &curve, NULL),
                         UR_OK);
        assert_int_equal(ur_ruled_tangent(curve, offset, width, &ruled, NULL), UR_OK);
        ur_net_list nets = develop_exact(what, &ruled, 0.002);
        expect_area(what, &nets, helicoid_area(radius, pitch, turns, offset, width), 0.002);
        nest_and_check(what, &r, &nets);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
}

/* Right circular cones and frustums: lateral area pi (R + r) s. */
static void test_random_circular_cones(void **state)
{
    (void)state;
    rng r = {0xD1B54A32D192ED03ULL};
    for (int i = 0; i < 12; i++) {
        double radius = uniform(&r, 5, 80), height = uniform(&r, 2, 150);
        double cut = uniform(&r, 0, 1) < 0.3 ? 1.0 : uniform(&r, 0.05, 0.95);
        char what[160];
        snprintf(what, sizeof what, "cone %d (R %g, H %g, cut %g)", i, radius, height, cut);
        ur_curve *circle;
        ur_ruled ruled;
        assert_int_equal(ur_curve_new_circle(radius, &circle, NULL), UR_OK);
        assert_int_equal(ur_ruled_cone(circle, ur_vec3_make(0, 0, height), cut, &ruled, NULL),
                         UR_OK);
        double slant = cut * hypot(radius, height), top = radius * (1 - cut);
        ur_net_list nets = develop_exact(what, &ruled, 0.002);
        expect_area(what, &nets, M_PI * (radius + top) * slant, 0.002);
        nest_and_check(what, &r, &nets);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
}

/* A random closed star-shaped curve in the plane z = 0: a wobbly ellipse. */
static ur_curve *random_closed_curve(rng *r)
{
    enum { N = 48 };
    ur_vec3 points[N];
    double a = uniform(r, 20, 60), b = uniform(r, 20, 60);
    double wobble = uniform(r, 0, 0.15), phase = uniform(r, 0, 2 * M_PI);
    int lobes = (int)uniform(r, 2, 6);
    for (int i = 0; i < N; i++) {
        double t = 2 * M_PI * i / N;
        double scale = 1 + wobble * sin(lobes * t + phase);
        points[i] = ur_vec3_make(a * scale * cos(t), b * scale * sin(t), 0);
    }
    ur_curve *curve;
    assert_int_equal(ur_curve_new_interpolating(points, N, true, &curve, NULL), UR_OK);
    return curve;
}

/* Cones and cylinders over random closed curves, against this file's quadrature. */
static void test_random_cones_and_cylinders_over_curves(void **state)
{
    (void)state;
    rng r = {0xA0761D6478BD642FULL};
    for (int i = 0; i < 10; i++) {
        char what[160];
        ur_ruled ruled;
        if (i % 2 == 0) {
            ur_vec3 apex =
                ur_vec3_make(uniform(&r, -10, 10), uniform(&r, -10, 10), uniform(&r, 20, 120));
            double cut = uniform(&r, 0.1, 0.9);
            snprintf(what, sizeof what, "cone %d over a curve (apex %g,%g,%g, cut %g)", i, apex.x,
                     apex.y, apex.z, cut);
            assert_int_equal(ur_ruled_cone(random_closed_curve(&r), apex, cut, &ruled, NULL),
                             UR_OK);
        } else {
            double height = uniform(&r, 5, 100);
            ur_vec3 direction = ur_vec3_make(uniform(&r, -0.3, 0.3), uniform(&r, -0.3, 0.3), 1);
            snprintf(what, sizeof what, "cylinder %d over a curve (height %g)", i, height);
            assert_int_equal(
                ur_ruled_cylinder(random_closed_curve(&r), direction, height, &ruled, NULL), UR_OK);
        }
        double u0 = ur_ruled_start(&ruled), u1 = ur_ruled_end(&ruled);
        double area = quadrature_area(&ruled, u0, u1, 4000);
        ur_net_list nets = develop_exact(what, &ruled, 0.002);
        expect_area(what, &nets, area, 0.002);
        nest_and_check(what, &r, &nets);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
}

/*
 * Strips between two rails that lie on the tangent developable of a random
 * twisted cubic g(t) = (a t, b t^2, c t^3), at two distances along its
 * tangents: the strip exists (the cubic is its edge of regression), but
 * the rails start at different points, so the ends may have gaps.  Each
 * part of the domain is developed on its own, as the command does.
 */
static void test_random_strips(void **state)
{
    (void)state;
    rng r = {0x243F6A8885A308D3ULL};
    for (int i = 0; i < 8; i++) {
        enum { N = 60 };
        double a = uniform(&r, 20, 40), b = uniform(&r, 8, 20), c = uniform(&r, 3, 8);
        double near = uniform(&r, 10, 30), far = near + uniform(&r, 15, 40);
        double t0 = uniform(&r, 0.2, 0.5), t1 = t0 + uniform(&r, 0.6, 1.2);
        double shift = uniform(&r, 0, 0.1);
        ur_vec3 rail1[N], rail2[N];
        for (int k = 0; k < N; k++) {
            for (int side = 0; side < 2; side++) {
                double t = (side ? t0 + shift : t0) + (t1 - t0) * k / (N - 1);
                ur_vec3 g = ur_vec3_make(a * t, b * t * t, c * t * t * t);
                ur_vec3 velocity = ur_vec3_make(a, 2 * b * t, 3 * c * t * t);
                ur_vec3 tangent = ur_vec3_scale(velocity, 1 / ur_vec3_length(velocity));
                ur_vec3 p = ur_vec3_add(g, ur_vec3_scale(tangent, side ? far : near));
                (side ? rail2 : rail1)[k] = p;
            }
        }
        char what[200];
        snprintf(what, sizeof what, "strip %d (cubic %g, %g, %g; t %g..%g; rails at %g and %g)", i,
                 a, b, c, t0, t1, near, far);
        ur_curve *c1, *c2;
        assert_int_equal(ur_curve_new_interpolating(rail1, N, false, &c1, NULL), UR_OK);
        assert_int_equal(ur_curve_new_interpolating(rail2, N, false, &c2, NULL), UR_OK);
        ur_ruled ruled;
        ur_error error;
        if (ur_ruled_strip(c1, c2, &ruled, &error) != UR_OK)
            fail_msg("%s: %s", what, error.message);
        size_t count = ur_ruled_domain(&ruled, NULL, 0);
        assert_true(count >= 1);
        ur_interval *parts = calloc(count, sizeof *parts);
        assert_non_null(parts);
        ur_ruled_domain(&ruled, parts, count);
        for (size_t k = 0; k < count; k++) {
            ur_ruled_restrict(&ruled, parts[k].u_start, parts[k].u_end);
            double area = quadrature_area(&ruled, parts[k].u_start, parts[k].u_end, 4000);
            ur_net_list nets = develop_exact(what, &ruled, 0.002);
            expect_area(what, &nets, area, 0.002);
            nest_and_check(what, &r, &nets);
            ur_net_list_free(&nets);
        }
        free(parts);
        ur_ruled_free(&ruled);
    }
}

/* ---- Random small meshes ------------------------------------------------- */

/*
 * A random grid mesh of nx x ny vertices over a random rectangle, its
 * inner vertices jittered in the plane, lifted by z = height(x, y), and
 * its quads split along a random diagonal.
 */
static ur_mesh random_grid_mesh(rng *r, bool flat)
{
    size_t nx = (size_t)uniform(r, 3, 9), ny = (size_t)uniform(r, 3, 9);
    double w = uniform(r, 20, 200), h = uniform(r, 20, 200);
    double amplitude = flat ? 0 : uniform(r, 1, 0.3 * fmin(w, h));
    double fx = uniform(r, 0.5, 2) * M_PI / w, fy = uniform(r, 0.5, 2) * M_PI / h;
    ur_vec3 *vertices = calloc(nx * ny, sizeof *vertices);
    size_t(*triangles)[3] = calloc(2 * (nx - 1) * (ny - 1), sizeof *triangles);
    assert_true(vertices && triangles);
    double dx = w / (double)(nx - 1), dy = h / (double)(ny - 1);
    for (size_t j = 0; j < ny; j++)
        for (size_t i = 0; i < nx; i++) {
            bool inner = i > 0 && j > 0 && i + 1 < nx && j + 1 < ny;
            double x = dx * (double)i + (inner ? uniform(r, -0.3, 0.3) * dx : 0);
            double y = dy * (double)j + (inner ? uniform(r, -0.3, 0.3) * dy : 0);
            vertices[j * nx + i] = ur_vec3_make(x, y, amplitude * sin(fx * x) * cos(fy * y));
        }
    size_t t = 0;
    for (size_t j = 0; j + 1 < ny; j++)
        for (size_t i = 0; i + 1 < nx; i++) {
            size_t a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
            if (uniform(r, 0, 1) < 0.5) {
                triangles[t][0] = a, triangles[t][1] = b, triangles[t++][2] = c;
                triangles[t][0] = a, triangles[t][1] = c, triangles[t++][2] = d;
            } else {
                triangles[t][0] = a, triangles[t][1] = b, triangles[t++][2] = d;
                triangles[t][0] = b, triangles[t][1] = c, triangles[t++][2] = d;
            }
        }
    ur_mesh mesh;
    assert_int_equal(
        ur_mesh_new(vertices, nx * ny, (const size_t(*)[3])triangles, t, NULL, &mesh, NULL), UR_OK);
    free(vertices);
    free(triangles);
    return mesh;
}

/*
 * Random meshes through clean, cut and ARAP: finite flat points, finite
 * strain, no triangle turned over; a flat mesh flattens isometrically
 * (its area kept, no strain), as its own layout is an exact solution.
 */
static void test_random_meshes(void **state)
{
    (void)state;
    rng r = {0x1234567887654321ULL};
    for (int i = 0; i < 16; i++) {
        bool flat = i % 4 == 0;
        char what[64];
        snprintf(what, sizeof what, "%s mesh %d", flat ? "flat" : "bumpy", i);
        ur_mesh mesh = random_grid_mesh(&r, flat);
        ur_mesh_repairs repairs;
        ur_error error;
        if (ur_mesh_clean(&mesh, 1e-6 * ur_mesh_size(&mesh), &repairs, &error) != UR_OK)
            fail_msg("%s: clean: %s", what, error.message);
        ur_mesh_piece *pieces = NULL;
        size_t count = 0;
        if (ur_mesh_pieces(&mesh, NULL, 0, &pieces, &count, &error) != UR_OK)
            fail_msg("%s: pieces: %s", what, error.message);
        ur_net_list nets = {calloc(count, sizeof(ur_net)), 0};
        assert_non_null(nets.nets);
        for (size_t k = 0; k < count; k++) {
            ur_flat_piece flat_piece;
            if (ur_flatten(&pieces[k].mesh, NULL, &flat_piece, &error) != UR_OK)
                fail_msg("%s: flatten: %s", what, error.message);
            for (size_t v = 0; v < flat_piece.vertex_count; v++)
                if (!finite2(flat_piece.flat[v]))
                    fail_msg("%s: flat vertex %zu is not finite", what, v);
            assert_false(flat_piece.flipped);
            assert_true(isfinite(flat_piece.max_stretch) && isfinite(flat_piece.max_compression));
            if (flat) {
                assert_relative(flat_piece.flat_area, flat_piece.area_3d, 1e-9);
                assert_true(flat_piece.max_stretch < 1e-6 && flat_piece.max_compression < 1e-6);
            }
            if (ur_net_from_flat(&pieces[k].mesh, &flat_piece, "M", &nets.nets[k], &error) != UR_OK)
                fail_msg("%s: net: %s", what, error.message);
            nets.count++;
            ur_flat_piece_free(&flat_piece);
        }
        double area, perimeter;
        check_nets(what, &nets, &area, &perimeter);
        nest_and_check(what, &r, &nets);
        ur_net_list_free(&nets);
        ur_mesh_pieces_free(pieces, count);
        ur_mesh_free(&mesh);
    }
}

static int setup(void **state)
{
    (void)state;
    geos = GEOS_init_r();
    return geos ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    GEOS_finish_r(geos);
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_helicoids),
        cmocka_unit_test(test_random_circular_cones),
        cmocka_unit_test(test_random_cones_and_cylinders_over_curves),
        cmocka_unit_test(test_random_strips),
        cmocka_unit_test(test_random_meshes),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
