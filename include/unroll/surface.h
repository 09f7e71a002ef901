/*
 * unroll/surface.h: space curves and the ruled surfaces built on them.
 *
 * A curve is either analytic (circle, helix) or interpolates points with a
 * cubic spline per coordinate (GSL), parameterised by chord length so that u
 * is close to arc length.  A ruled surface has two rails,
 *     r(u, v) = a(u) + v (b(u) - a(u)),  u in [u0, u1], v in [0, 1],
 * and this module knows three developable kinds: cylinders, cones and
 * tangent developables.  It answers what the development needs at each u
 * (the intrinsic quantities of the ruling) and the 3D area by quadrature,
 * independently of any net.
 */
#ifndef UNROLL_SURFACE_H
#define UNROLL_SURFACE_H

#include <stdbool.h>
#include <stddef.h>

#include "unroll/base.h"
#include "unroll/geom.h"

typedef struct ur_curve ur_curve;

/* (R cos t, R sin t, pitch t / 2 pi) for t in [t_start, t_end]. */
ur_status ur_curve_new_helix(double radius, double pitch, double t_start, double t_end,
                             ur_curve **curve, ur_error *error);

/* (R cos t, R sin t, 0), t in [0, 2 pi], closed. */
ur_status ur_curve_new_circle(double radius, ur_curve **curve, ur_error *error);

/*
 * Interpolates points (count >= 4) with C2 cubic splines.  A closed curve is
 * periodic.  An open curve gets its end conditions from a cubic through the
 * last four points rather than the "natural" zero second derivative, which
 * would put a false inflection at each end.
 */
ur_status ur_curve_new_interpolating(const ur_vec3 *points, size_t count, bool closed,
                                     ur_curve **curve, ur_error *error);

void ur_curve_free(ur_curve *curve);

/* Position, first and second derivative with respect to u. */
void ur_curve_eval(ur_curve *curve, double u, ur_vec3 derivatives[3]);

double ur_curve_start(const ur_curve *curve);
double ur_curve_end(const ur_curve *curve);
bool ur_curve_is_closed(const ur_curve *curve);

/* For interpolating curves, the parameter of input point index; else NAN. */
double ur_curve_point_parameter(const ur_curve *curve, size_t index);
size_t ur_curve_point_count(const ur_curve *curve);

/* Curvature |c' x c''| / |c'|^3 at u. */
double ur_curve_curvature(ur_curve *curve, double u);

/* Arc length between u_start and u_end by adaptive quadrature. */
ur_status ur_curve_length(ur_curve *curve, double u_start, double u_end, double *length,
                          ur_error *error);

typedef enum ur_ruled_kind {
    UR_RULED_CYLINDER, /* b = a + height * direction */
    UR_RULED_CONE,     /* b = a + cut * (apex - a) */
    UR_RULED_TANGENT,  /* a = g + offset t, b = g + (offset + width) t */
} ur_ruled_kind;

typedef struct ur_ruled {
    ur_ruled_kind kind;
    ur_curve *curve; /* owned: base curve, or the edge of regression g */
    ur_vec3 direction;
    double height;
    ur_vec3 apex;
    double cut;
    double offset, width;
} ur_ruled;

/* Each takes ownership of curve, also on failure. */
ur_status ur_ruled_cylinder(ur_curve *curve, ur_vec3 direction, double height, ur_ruled *ruled,
                            ur_error *error);
ur_status ur_ruled_cone(ur_curve *curve, ur_vec3 apex, double cut, ur_ruled *ruled,
                        ur_error *error);
ur_status ur_ruled_tangent(ur_curve *curve, double offset, double width, ur_ruled *ruled,
                           ur_error *error);

void ur_ruled_free(ur_ruled *ruled);

double ur_ruled_start(const ur_ruled *ruled);
double ur_ruled_end(const ur_ruled *ruled);
bool ur_ruled_is_closed(const ur_ruled *ruled);

/* rails[0] = a(u), rails[1] = a'(u), rails[2] = b(u), rails[3] = b'(u). */
void ur_ruled_rails(ur_ruled *ruled, double u, ur_vec3 rails[4]);

/*
 * What the development needs at u, all intrinsic (unchanged by bending).
 * The base curve c is rail a for cylinders and cones and the edge of
 * regression for tangent developables.  The ruling starts at c(u) + near e
 * and ends at c(u) + far e, e its unit direction, at angle `angle` from c'
 * measured in the tangent plane; c has speed |c'| and geodesic curvature
 * geodesic_curvature, both with the same orientation of the tangent plane.
 */
typedef struct ur_ruling_intrinsics {
    double speed;
    double geodesic_curvature;
    double angle;
    double near, far;
} ur_ruling_intrinsics;

void ur_ruled_intrinsics(ur_ruled *ruled, double u, ur_ruling_intrinsics *intrinsics);

/*
 * Checks that the surface is regular where it will be developed: a tangent
 * developable needs an edge of regression without inflections (curvature
 * zero), a cylinder a base curve never tangent to its direction, a cone a
 * base curve never heading for its apex.  The message says where and why.
 */
ur_status ur_ruled_check(ur_ruled *ruled, ur_error *error);

/* 3D area of the part u in [u_start, u_end]: adaptive quadrature of |r_u x r_v|. */
ur_status ur_ruled_area(ur_ruled *ruled, double u_start, double u_end, double *area,
                        ur_error *error);

/* Length of rail a (rail = 0) or rail b (rail = 1) between u_start and u_end. */
ur_status ur_ruled_rail_length(ur_ruled *ruled, int rail, double u_start, double u_end,
                               double *length, ur_error *error);

#endif
