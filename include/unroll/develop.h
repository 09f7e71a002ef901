/*
 * unroll/develop.h: laying a developable ruled surface flat.
 *
 * The exact method integrates the geodesic curvature of the base curve (an
 * adaptive high-order ODE integrator from GSL) to lay the curve flat with its
 * arc length, then lays each ruling off at its 3D angle and length.  The two
 * discrete methods are those of the paper: the triangle method keeps the
 * triangles A_i A_i+1 P_i+1 between consecutive rulings and neglects the thin
 * sliver P_i P_i+1 A_i (the net comes out smaller than the surface); the quad
 * method flattens each twisted quadrilateral P_i P_i+1 A_i+1 A_i hinged on
 * its longer diagonal (the net comes out larger).
 *
 * A net that would overlap itself is split into the fewest pieces that do
 * not; the cut rulings are recorded as seams.
 */
#ifndef UNROLL_DEVELOP_H
#define UNROLL_DEVELOP_H

#include "unroll/geom.h"
#include "unroll/surface.h"

typedef enum ur_method { UR_METHOD_EXACT, UR_METHOD_TRIANGLE, UR_METHOD_QUAD } ur_method;

/* "exact", "triangle", "quad"; ur_method_from_name returns -1 when unknown. */
const char *ur_method_name(ur_method method);
int ur_method_from_name(const char *name);

typedef struct ur_segment {
    ur_vec2 start, end;
} ur_segment;

/* One flat piece.  All arrays are owned by the net. */
typedef struct ur_net {
    char name[32];
    ur_vec2 *outline; /* closed ring, counter-clockwise, first point not repeated */
    size_t outline_count;
    ur_segment *rulings; /* rulings to draw (fold or score lines) */
    size_t ruling_count;
    ur_segment seams[2]; /* outline edges cut from a neighbouring piece */
    size_t seam_count;
    double u_start, u_end; /* the part of the surface this piece covers */
    double area_3d;        /* 3D area of that part (quadrature) */
    double flat_area;      /* area enclosed by the outline */
    double edge_error;     /* largest relative error of a flat boundary length */
} ur_net;

typedef struct ur_net_list {
    ur_net *nets;
    size_t count;
} ur_net_list;

typedef struct ur_develop_options {
    ur_method method;
    size_t rulings;   /* n: parts for the discrete methods, rulings drawn for all */
    double tolerance; /* largest distance of an outline chord from the true curve, mm */
    bool split;       /* split a net that overlaps itself (otherwise refuse it) */
} ur_develop_options;

void ur_develop_options_default(ur_develop_options *options);

/* Develops the surface into one or more nets; free them with ur_net_list_free. */
ur_status ur_develop(ur_ruled *ruled, const ur_develop_options *options, ur_net_list *nets,
                     ur_error *error);

void ur_net_list_free(ur_net_list *nets);

#endif
