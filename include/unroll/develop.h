/*
 * unroll/develop.h: laying a developable ruled surface flat.
 *
 * The exact method integrates the geodesic curvature of the base curve (an
 * adaptive high-order ODE integrator from GSL) to lay the curve flat with its
 * arc length, then lays each ruling off at its 3D angle and length.  The two
 * discrete methods are those of the seed paper ([Seed2018] in
 * docs/bibliography.md; docs/algorithms.md, section 5): the triangle method
 * keeps the triangles A_i A_i+1 P_i+1 between consecutive rulings and
 * neglects the thin sliver P_i P_i+1 A_i (the net comes out smaller than the
 * surface); the quad method flattens each twisted quadrilateral
 * P_i P_i+1 A_i+1 A_i hinged on its longer diagonal (the net comes out
 * larger).
 *
 * A net that would overlap itself is split into the fewest pieces that do
 * not; the cut rulings are recorded as seams.
 */
#ifndef UNROLL_DEVELOP_H
#define UNROLL_DEVELOP_H

#include "unroll/core.h"
#include "unroll/geom.h"
#include "unroll/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum ur_method { UR_METHOD_EXACT, UR_METHOD_TRIANGLE, UR_METHOD_QUAD } ur_method;

/* "exact", "triangle", "quad"; ur_method_from_name returns -1 when unknown. */
UR_API const char *ur_method_name(ur_method method);
UR_API int ur_method_from_name(const char *name);

typedef struct ur_develop_options {
    ur_method method;
    size_t rulings;   /* n: parts for the discrete methods, rulings drawn for all */
    double tolerance; /* largest distance of an outline chord from the true curve, mm */
    bool split;       /* split a net that overlaps itself (otherwise refuse it) */
    /*
     * The room a piece must fit in some turn, mm (0: no limit): a net too
     * long for the sheet is split at rulings into the fewest pieces that
     * fit (a long strip on sheet stock), as one that overlaps itself is.
     */
    double fit_length, fit_width;
} ur_develop_options;

UR_API void ur_develop_options_default(ur_develop_options *options);

/* Develops the surface into one or more nets; free them with ur_net_list_free. */
UR_API ur_status ur_develop(ur_ruled *ruled, const ur_develop_options *options, ur_net_list *nets,
                            ur_error *error);

/*
 * Finds the seams between nets that carry outline_3d (meshes): an outline
 * edge from P to Q pairs with an edge from Q to P of another net, or of the
 * same net elsewhere along its outline.  Runs of paired edges that follow
 * each other on both sides become one seam side each, the two numbered
 * alike from first_seam on (a run stops where the cut folds back on itself,
 * as at the end of a slit); *next_seam receives the next free number.
 * Replaces the seam sides of those nets; nets without outline_3d are left
 * alone.  Points pair when they are equal, as the flattening leaves them:
 * one mesh vertex, one 3D point.
 */
UR_API ur_status ur_net_list_find_seams(ur_net_list *nets, int first_seam, int *next_seam,
                                        ur_error *error);

/* The largest seam number of the list's nets, 0 when there is none. */
UR_API int ur_net_list_last_seam(const ur_net_list *nets);

/* Whether a closed ring (first point not repeated) is a simple polygon (GEOS). */
UR_API bool ur_outline_is_simple(const ur_vec2 *ring, size_t count);

/*
 * The seed paper's observation ([Seed2018]), measured: the triangle and
 * quad methods against the exact net as the number of parts n grows.
 * Method k of every array is 0 triangle, 1 quad, 2 exact
 * (UR_COMPARE_TRIANGLE, ...).
 */
enum { UR_COMPARE_TRIANGLE, UR_COMPARE_QUAD, UR_COMPARE_EXACT, UR_COMPARE_METHODS };

typedef struct ur_compare_row {
    size_t n;
    /* signed (flat area - 3D area) / 3D area */
    double area_error[UR_COMPARE_METHODS];
    /* largest relative error of a flat rail length against its 3D arc length */
    double edge_error[UR_COMPARE_METHODS];
    /*
     * Largest distance, mm, between a boundary point of the method's net and
     * the same point of the exact net after the least-squares rigid fit of
     * one to the other (a mirror image counts as the same net: a piece can
     * be turned over); 0 for the exact method itself.
     */
    double distance[UR_COMPARE_METHODS];
    /* the triangle method applies only to tangent developables; NAN figures otherwise */
    bool available[UR_COMPARE_METHODS];
} ur_compare_row;

typedef struct ur_compare_table {
    ur_compare_row *rows; /* owned: free with ur_compare_table_free */
    size_t count;
    double area_3d; /* 3D area of the surface (quadrature) */
} ur_compare_table;

/*
 * One row for each n = n_min, 2 n_min, 4 n_min, ... up to n_max
 * (1 <= n_min <= n_max).  A discrete net is measured on its strip, the flat
 * ends of its n + 1 rulings, against the exact development evaluated at the
 * same rulings; its flat area is that of the strip's outline.  Strips are
 * never split, so a surface whose net overlaps itself (a helicoid of a turn
 * or more) is compared all the same: the outline's area counts the overlap
 * as often as the net covers it, which is the area of the pieces it would
 * be cut into.  A rail that is a single point (a cone's apex) has no length
 * to compare.  The exact net's own errors are measured on ur_develop's net
 * (splitting allowed) at a tolerance of 1e-8 of the surface's size (the
 * larger of rail a's length and the longest ruling); it is developed once
 * and its figures repeated in every row, since it does not depend on n.
 */
UR_API ur_status ur_compare(ur_ruled *ruled, size_t n_min, size_t n_max, ur_compare_table *table,
                            ur_error *error);

UR_API void ur_compare_table_free(ur_compare_table *table);

#ifdef __cplusplus
}
#endif

#endif
