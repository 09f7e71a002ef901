/*
 * unroll/analyze.h: what a ruled surface is like before it is cut: how far it
 * is from developable, its Gaussian curvature, and how tightly the material
 * must bend, ruling by ruling, with a PNG map of it all (`unroll analyze`).
 *
 * Everything is closed form on the two rails of r(u, v) = a(u) + v (b(u) - a(u)):
 * with r_u = a' + v (b' - a'), r_v = b - a and n = r_u x r_v,
 *
 *     K = -det(a', b', b - a)^2 / |n|^4                (K <= 0 on a ruled surface)
 *
 * and, since r_vv = 0, the second fundamental form has L = r_uu . N,
 * M = r_uv . N = -det(a', b', b - a) / |n|, N2 = 0, so the mean curvature is
 * H = (G L - 2 F M) / (2 |n|^2) and the principal curvatures H +- sqrt(H^2 - K).
 * The bend radius is 1 / max |kappa|: on a developable (K = 0) the curvature
 * across the ruling, the one the material has to take.  r_uu needs a'' and
 * b'', which ur_ruled_rails does not give: they are central differences of a'
 * and b' with a step of 1e-5 of the u range, one-sided (also of second order)
 * at the ends of the surface and of each part of a strip's domain; bend radii
 * come out within about 1e-9 relative.
 *
 * Units are those of the surface (mm): K in 1/mm^2, radii in mm.
 */
#ifndef UNROLL_ANALYZE_H
#define UNROLL_ANALYZE_H

#include <stdbool.h>
#include <stddef.h>

#include "unroll/base.h"
#include "unroll/geom.h"
#include "unroll/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The curvature at one point r(u, v).  A point where r_u x r_v vanishes (a
 * cone's apex, the edge of regression of a tangent developable with no
 * offset) has no tangent plane: it is singular, its K is NAN and its bend
 * radius 0, the limit the material would have to reach there.  A triple
 * product below 1e-12 of |a'| |b'| |b - a| is rounding and counts as 0, so
 * that a developable reads K = 0 even next to a singular point.
 */
typedef struct ur_point_curvature {
    ur_vec3 point;       /* r(u, v) */
    ur_vec3 normal;      /* unit r_u x r_v; zero when singular */
    double area_element; /* |r_u x r_v|: dA = area_element du dv */
    bool singular;       /* no tangent plane */
    double gaussian;     /* K, 1/mm^2; NAN when singular */
    double mean;         /* H, 1/mm, sign from normal; NAN when singular */
    double bend_radius;  /* 1 / max |kappa|, mm; INFINITY where flat, 0 when singular */
} ur_point_curvature;

UR_API void ur_analyze_point(ur_ruled *ruled, double u, double v, ur_point_curvature *curvature);

/*
 * The bend radius of the ruling at u, as ur_analyze gives it for each of
 * its rulings: the smallest over `across` points evenly spaced from rail a
 * to rail b (ends included; fewer than 2 counts as 2) of 1 / max |kappa|,
 * mm: INFINITY where flat, 0 at a singular point.  *v (may be NULL)
 * receives where along the ruling it is smallest (0 rail a, 1 rail b).
 * On a developable the curvature across a ruling varies as 1 / (distance
 * from the edge of regression), so the smallest radius is at an end or at
 * a singular point and a few samples find it.
 */
UR_API double ur_analyze_bend_radius(ur_ruled *ruled, double u, size_t across, double *v);

typedef struct ur_ruling_analysis {
    double u, arc;     /* parameter and arc length along rail a from the start */
    ur_vec3 near, far; /* the ruling's ends */
    /*
     * Inside a gap of the domain of existence (ur_ruled_gaps) there is no
     * surface: the ruling is listed for its place, its numbers are NAN and
     * no summary counts it.
     */
    bool in_gap;
    double residual;                   /* ur_ruled_residual */
    double gaussian_min, gaussian_max; /* K over the ruling (K <= 0 on a ruled surface) */
    /* smallest radius of normal curvature across the ruling, mm; INFINITY where flat */
    double bend_radius;
    double bend_v; /* where along the ruling (0 rail a, 1 rail b) it is smallest */
    /* The striction point (the edge of regression on a developable) as a
       position along the ruling, maybe outside [0, 1]; NAN for a cylinder. */
    double striction_v;
} ur_ruling_analysis;

typedef struct ur_analysis_options {
    size_t rulings; /* rulings, evenly spaced in u from start to end; default 256, >= 2 */
    size_t across;  /* samples along each ruling, ends included; default 17, >= 2 */
    /* largest residual (radians) still called developable; default
       UR_DEVELOPABLE_RESIDUAL (1e-6) */
    double tolerance;
} ur_analysis_options;

/*
 * The whole surface.  Statistics over points come from the rulings x across
 * samples, singular points left out of K (not out of the bend radius, which is
 * 0 there).  gaussian_mean is the integral of K dA over the area, both by the
 * trapezoid rule on the same samples so that a constant K comes out exact.
 * area_3d is ur_ruled_area summed over the domain of existence.
 */
typedef struct ur_analysis {
    ur_ruling_analysis *rulings; /* owned: ruling_count of them */
    size_t ruling_count;
    size_t across; /* the samples per ruling the statistics came from */
    double area_3d;
    bool developable; /* max_residual <= tolerance */
    double max_residual;
    size_t worst_ruling;                              /* index of max_residual */
    double gaussian_min, gaussian_max, gaussian_mean; /* mean = integral of K dA / area */
    ur_vec3 gaussian_min_at, gaussian_max_at;
    double min_bend_radius; /* INFINITY for a plane, 0 at a singular point */
    ur_vec3 min_bend_at;
} ur_analysis;

UR_API void ur_analysis_options_default(ur_analysis_options *options);

/*
 * Analyses ruled (options NULL for the defaults) into analysis, which the
 * caller frees with ur_analysis_free, also after a failure.  Options out of
 * range are UR_ERROR_INPUT.
 */
UR_API ur_status ur_analyze(ur_ruled *ruled, const ur_analysis_options *options,
                            ur_analysis *analysis, ur_error *error);

UR_API void ur_analysis_free(ur_analysis *analysis);

/* The picture ur_analysis_png_write draws: this wide, as tall as the map needs, at most this. */
enum { UR_ANALYSIS_PNG_WIDTH = 1000, UR_ANALYSIS_PNG_MAX_HEIGHT = 720 };

/*
 * A PNG map of the analysis of ruled (the same surface it was made from):
 * the surface's parameter domain in millimetres, x the arc length along rail
 * a and y the distance along the ruling from rail a, each ruling at its own
 * length and both axes at the same scale, so the map has the surface's
 * proportions along rail a and across it; the picture is as tall as that
 * map needs.  Cells are coloured by K: green where K = 0 (|K| below 1e-9 of
 * the largest |K|, or everywhere on a surface found developable), else blue
 * on a log scale of |K|, pale for the smallest and dark for the largest.
 * Gaps of the domain of existence are hatched grey and labelled, the
 * striction line is drawn where it runs inside the surface and the smallest
 * bend radius is marked; a colour bar, a scale bar and the title (may be
 * NULL) complete it.  The file is written atomically: on failure nothing is
 * left and an existing file is untouched.
 */
UR_API ur_status ur_analysis_png_write(const char *path, ur_ruled *ruled,
                                       const ur_analysis *analysis, const char *title,
                                       ur_context *context, ur_error *error);

#ifdef __cplusplus
}
#endif

#endif
