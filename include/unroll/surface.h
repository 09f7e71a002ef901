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

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ur_curve ur_curve;

/* (R cos t, R sin t, pitch t / 2 pi) for t in [t_start, t_end]. */
UR_API ur_status ur_curve_new_helix(double radius, double pitch, double t_start, double t_end,
                                    ur_curve **curve, ur_error *error);

/* (R cos t, R sin t, 0), t in [0, 2 pi], closed. */
UR_API ur_status ur_curve_new_circle(double radius, ur_curve **curve, ur_error *error);

/*
 * Interpolates points (count >= 4) with C2 cubic splines.  A closed curve is
 * periodic.  An open curve gets its end conditions from a cubic through the
 * last four points rather than the "natural" zero second derivative, which
 * would put a false inflection at each end.
 */
UR_API ur_status ur_curve_new_interpolating(const ur_vec3 *points, size_t count, bool closed,
                                            ur_curve **curve, ur_error *error);

UR_API void ur_curve_free(ur_curve *curve);

/* Position, first and second derivative with respect to u. */
UR_API void ur_curve_eval(ur_curve *curve, double u, ur_vec3 derivatives[3]);

UR_API double ur_curve_start(const ur_curve *curve);
UR_API double ur_curve_end(const ur_curve *curve);
UR_API bool ur_curve_is_closed(const ur_curve *curve);

/* For interpolating curves, the parameter of input point index; else NAN. */
UR_API double ur_curve_point_parameter(const ur_curve *curve, size_t index);
UR_API size_t ur_curve_point_count(const ur_curve *curve);

/* Curvature |c' x c''| / |c'|^3 at u. */
UR_API double ur_curve_curvature(ur_curve *curve, double u);

/* Arc length between u_start and u_end by adaptive quadrature. */
UR_API ur_status ur_curve_length(ur_curve *curve, double u_start, double u_end, double *length,
                                 ur_error *error);

typedef enum ur_ruled_kind {
    UR_RULED_CYLINDER, /* b = a + height * direction */
    UR_RULED_CONE,     /* b = a + cut * (apex - a) */
    UR_RULED_TANGENT,  /* a = g + offset t, b = g + (offset + width) t */
    UR_RULED_STRIP,    /* a = c1, b = c2(sigma(u)), sigma solved: developable */
    UR_RULED_GENERAL,  /* a = c1, b = c2(sigma(u)), sigma given: in general not */
} ur_ruled_kind;

typedef struct ur_pairing ur_pairing; /* sigma(u) of the two-rail kinds (strip.c) */

/* Why a part of rail 1 has no strip: see ur_ruled_strip. */
typedef enum ur_gap_reason { UR_GAP_NO_RULING, UR_GAP_RULINGS_CROSS } ur_gap_reason;

/* A part of rail 1 (the base curve), by parameter, arc length and end points. */
typedef struct ur_interval {
    double u_start, u_end;
    double arc_start, arc_end;
    ur_vec3 start, end;
    ur_gap_reason reason; /* for gaps */
} ur_interval;

typedef struct ur_ruled {
    ur_ruled_kind kind;
    ur_curve *curve; /* owned: base curve, the edge of regression g, or rail 1 */
    ur_vec3 direction;
    double height;
    ur_vec3 apex;
    double cut;
    double offset, width;
    ur_curve *rail2;     /* owned, two-rail kinds only */
    ur_pairing *pairing; /* owned, two-rail kinds only */
    /* The part of the surface in use (ur_ruled_restrict); the whole by default. */
    bool restricted;
    double u_min, u_max;
} ur_ruled;

/* Each takes ownership of curve, also on failure. */
UR_API ur_status ur_ruled_cylinder(ur_curve *curve, ur_vec3 direction, double height,
                                   ur_ruled *ruled, ur_error *error);
UR_API ur_status ur_ruled_cone(ur_curve *curve, ur_vec3 apex, double cut, ur_ruled *ruled,
                               ur_error *error);
UR_API ur_status ur_ruled_tangent(ur_curve *curve, double offset, double width, ur_ruled *ruled,
                                  ur_error *error);

/*
 * The developable strip between rail 1 and rail 2 (both owned from here on,
 * also on failure).  For each u on rail 1 the pairing finds sigma on rail 2
 * with det(c1'(u), c2'(sigma), c2(sigma) - c1(u)) = 0 by bracketed root
 * finding, tracked so that sigma never decreases.  Where there is no such
 * sigma, or where consecutive rulings would cross inside the strip (its edge
 * of regression passes between the rails), rail 1 has a gap: see
 * ur_ruled_gaps.  Fails only when no part of rail 1 has a strip.
 */
UR_API ur_status ur_ruled_strip(ur_curve *rail1, ur_curve *rail2, ur_ruled *ruled, ur_error *error);

/* How a general ruled surface pairs its rails. */
typedef enum ur_pairing_rule {
    UR_PAIR_ARC_LENGTH, /* equal fractions of each rail's arc length */
    UR_PAIR_POINTS,     /* the i-th input point of each rail (same counts) */
} ur_pairing_rule;

/*
 * The ruled surface joining rail 1 and rail 2 by the given rule (both rails
 * owned from here on, also on failure); in general not developable.
 */
UR_API ur_status ur_ruled_general(ur_curve *rail1, ur_curve *rail2, ur_pairing_rule rule,
                                  ur_ruled *ruled, ur_error *error);

/*
 * Moves the points of an open rail 2 as little as needed for the strip
 * between rail 1 and rail 2 to exist along the whole of rail 1 (see
 * adjust.c for how), along direction only when it is not NULL.  rail2 is
 * changed in place (left as it was on failure); *largest is the largest
 * distance a point moved.  The caller checks the result with ur_ruled_strip.
 */
UR_API ur_status ur_strip_adjust_rail2(const ur_vec3 *rail1, size_t count1, ur_vec3 *rail2,
                                       size_t count2, const ur_vec3 *direction, double *largest,
                                       ur_error *error);

/* Which rails ur_rails_repair may move. */
enum { UR_REPAIR_RAIL1 = 1, UR_REPAIR_RAIL2 = 2, UR_REPAIR_BOTH = 3 };

typedef struct ur_rail_repair_options {
    unsigned rails;              /* UR_REPAIR_RAIL1, _RAIL2 or _BOTH */
    bool move_ends;              /* the rails' end points may move too */
    const ur_vec3 *direction;    /* each point moves along this only, or NULL */
    const ur_vec3 *plane_normal; /* each point stays in the plane through it normal to this */
    double max_displacement;     /* mm; 0: a quarter of the rails' distance */
    const ur_context *context;   /* its cancel flag stops the repair; NULL: never */
} ur_rail_repair_options;

typedef struct ur_rail_repair_report {
    bool everywhere;          /* the strip exists along all of rail 1 (before or after) */
    double largest, mean;     /* displacement of the moving rails' points, mm */
    int largest_rail;         /* 1 or 2: where the largest is */
    size_t largest_point;     /* its point, from 0 */
    double largest_along;     /* mm along that rail (its polyline, as given) */
    ur_vec3 largest_position; /* where that point was, as given */
    double limit;             /* the largest displacement allowed, mm (0: nothing to repair) */
    size_t iterations;        /* of the least-squares solver, all rounds */
    bool from_local_repair;   /* started from ur_strip_adjust_rail2's result */
    bool used_local_repair;   /* ... and kept it: it moved rail 2 less */
    bool edge_too_close;      /* the edge of regression stays near a rail: a sharp bend */
    bool smoothed;            /* the repair is the rails partly smoothed (the solver found none) */
} ur_rail_repair_report;

/*
 * Reshapes open rails as little as possible so that the developable strip
 * between them exists along the whole of rail 1, with no fold, no gap and
 * its edge of regression outside the strip (rail_repair.c says how): a
 * smooth displacement of every point of the moving rails, each keeping its
 * number of points, the ends fixed unless options->move_ends, made larger
 * where that helps until the strip bends no tighter than 1.5 % of the
 * rails' distance (else report->edge_too_close when its edge of regression
 * stays near a rail).  Rails that
 * already have a strip everywhere come back unchanged (report->largest 0).
 * UR_ERROR_INPUT, with the rails unchanged, when the repair would move a
 * point by more than the limit (the message names the part of rail 1 and
 * the displacement needed) or none is found.
 */
UR_API ur_status ur_rails_repair(ur_vec3 *rail1, size_t count1, ur_vec3 *rail2, size_t count2,
                                 const ur_rail_repair_options *options,
                                 ur_rail_repair_report *report, ur_error *error);

/* The pairing at u: the parameter on rail 2 and its derivative. */
UR_API void ur_ruled_pairing(ur_ruled *ruled, double u, double *sigma, double *slope);

UR_API void ur_ruled_free(ur_ruled *ruled);

/*
 * The gaps in the domain of existence of a strip, in order along rail 1
 * (none for the other kinds).  The array belongs to the surface.
 */
UR_API size_t ur_ruled_gaps(const ur_ruled *ruled, const ur_interval **gaps);

/*
 * The parts of the whole of rail 1 that have a surface, in order: the
 * complement of the gaps (ur_ruled_restrict does not change them).  Writes
 * at most capacity intervals and returns how many there are.
 */
UR_API size_t ur_ruled_domain(ur_ruled *ruled, ur_interval *parts, size_t capacity);

/* Uses only u in [u_start, u_end] from now on (start, end, closed, check). */
UR_API void ur_ruled_restrict(ur_ruled *ruled, double u_start, double u_end);

/* Fills the arc length and end point of an interval from its parameters. */
UR_API void ur_ruled_describe_interval(ur_ruled *ruled, ur_interval *interval);

/*
 * Developability residual at u: the angle (radians, in [0, pi/2]) by which
 * the tangent plane turns between the two ends of the ruling.  Zero on a
 * developable surface.
 */
UR_API double ur_ruled_residual(ur_ruled *ruled, double u);

/* The largest residual (radians) still called developable. */
#define UR_DEVELOPABLE_RESIDUAL 1e-6

/*
 * The point where the ruling at u meets its neighbours (the striction point,
 * which on a developable is the edge of regression), as r(u, v) with v its
 * position along the ruling (0 on rail a, 1 on rail b).  False when the
 * neighbouring rulings are parallel (a cylinder): the edge is at infinity.
 */
UR_API bool ur_ruled_regression(ur_ruled *ruled, double u, ur_vec3 *point, double *v);

UR_API double ur_ruled_start(const ur_ruled *ruled);
UR_API double ur_ruled_end(const ur_ruled *ruled);
UR_API bool ur_ruled_is_closed(const ur_ruled *ruled);

/* rails[0] = a(u), rails[1] = a'(u), rails[2] = b(u), rails[3] = b'(u). */
UR_API void ur_ruled_rails(ur_ruled *ruled, double u, ur_vec3 rails[4]);

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

UR_API void ur_ruled_intrinsics(ur_ruled *ruled, double u, ur_ruling_intrinsics *intrinsics);

/*
 * Checks that the surface is regular where it will be developed: a tangent
 * developable needs an edge of regression without inflections (curvature
 * zero), a cylinder a base curve never tangent to its direction, a cone a
 * base curve never heading for its apex.  The message says where and why.
 */
UR_API ur_status ur_ruled_check(ur_ruled *ruled, ur_error *error);

/* 3D area of the part u in [u_start, u_end]: adaptive quadrature of |r_u x r_v|. */
UR_API ur_status ur_ruled_area(ur_ruled *ruled, double u_start, double u_end, double *area,
                               ur_error *error);

/* Length of rail a (rail = 0) or rail b (rail = 1) between u_start and u_end. */
UR_API ur_status ur_ruled_rail_length(ur_ruled *ruled, int rail, double u_start, double u_end,
                                      double *length, ur_error *error);

/*
 * The parallel surface at `distance` mm toward the inside of the bend
 * (negative: away from it), for the part in use (offset.c): each ruling
 * moves along the unit normal, which on a developable is the same all
 * along it, so the result is developable again and its net exact.  The
 * inside is the side of the centre of curvature of the section across the
 * rulings; on a surface that bends both ways, the side the integral of that
 * curvature over the area favours.  A cylinder stays a cylinder, a general
 * ruled surface stays one paired by points, other developables become the
 * strip between the two new rails.  UR_ERROR_INPUT when the distance
 * toward a side reaches the bend radius there (the result would fold over
 * itself; the message says where) or the part in use has a gap.  *offset
 * is new (free it with ur_ruled_free); ruled is not changed.
 */
UR_API ur_status ur_ruled_offset(ur_ruled *ruled, double distance, ur_ruled *offset,
                                 ur_error *error);

#ifdef __cplusplus
}
#endif

#endif
