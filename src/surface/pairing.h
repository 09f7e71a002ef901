/*
 * pairing.h: the pairing sigma(u) of a two-rail surface, shared by strip.c
 * (building the surfaces, answering sigma(u)) and tracking.c (solving it for
 * a developable strip).  Private to src/surface.
 */
#ifndef UNROLL_SURFACE_PAIRING_H
#define UNROLL_SURFACE_PAIRING_H

#include <gsl/gsl_interp.h>
#include <gsl/gsl_roots.h>

#include "surface_internal.h"

/*
 * Rails are interpolated, so a ruling meant to end exactly on an end of a
 * rail misses it by about the interpolation error: closer than this
 * fraction of a rail counts as on it.
 */
#define ROUNDING 1e-5

struct ur_pairing {
    bool solved;             /* developable strip: sigma is a root of F */
    ur_curve *rail1, *rail2; /* borrowed from the surface */
    double s0, s1;           /* rail 2's parameter range */
    bool wrap;               /* rail 2 closed: sigma runs on past s1 */
    double end_slack;        /* ROUNDING, or 0 while locating a gap's end exactly */
    size_t count;
    double *u, *sigma, *slope;
    unsigned char *state; /* per sample: a sample_state */
    bool *joined;         /* samples i and i + 1 lie on one branch */
    bool *bridged;        /* ... and between them sigma is the table's Hermite interpolation */
    double step;          /* rail 2 scan step */
    /* given pairing */
    gsl_interp *interp;
    gsl_interp_accel *accel;
    /* solved pairing */
    gsl_root_fsolver *solver;
    ur_vec3 *scan_position, *scan_tangent; /* rail 2 at the scan samples */
    size_t scan_count;
    ur_interval *gaps;
    size_t gap_count;
    size_t hint;
};

enum sample_state { SAMPLE_GOOD, SAMPLE_NO_ROOT, SAMPLE_CROSS };

/* Allocates the table of count samples evenly spaced along rail 1. */
ur_status pairing_table_alloc(ur_pairing *pairing, size_t count, ur_error *error);

/*
 * Solves the pairing of a developable strip (tracking.c): the root table,
 * which samples have a ruling, and the gaps of the domain of existence
 * (their parameters only).
 */
ur_status pairing_track(ur_pairing *pairing, ur_error *error);

/*
 * sigma at u by Newton's method from the table, on the branch of [low, high]
 * (tracking.c); *on_table when it is the table's interpolation instead (at
 * or next to a double root).
 */
double pairing_solved_sigma(ur_pairing *pairing, double u, double low, double high,
                            const ur_vec3 c1[3], bool *on_table);

/*
 * sigma'(u) at the root sigma of a solved pairing: the implicit slope, or at
 * a double root (an inflection of the rails) the slope of the table's branch.
 */
double pairing_solved_slope(ur_pairing *pairing, double u, const ur_vec3 c1[3], const ur_vec3 d2[3],
                            bool on_table);

/* sigma' = -F_u / F_sigma, with rail 1's derivatives c1 and rail 2's d2 at sigma. */
double pairing_implicit_slope(const ur_vec3 c1[3], const ur_vec3 d2[3]);

#endif
