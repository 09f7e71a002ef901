/*
 * surface_internal.h: what the files of the surface module share.
 */
#ifndef UNROLL_SURFACE_INTERNAL_H
#define UNROLL_SURFACE_INTERNAL_H

#include "unroll/surface.h"

/*
 * sigma(u) and sigma'(u) of a two-rail surface (strip.c), on the branch of
 * the part [low, high] in use where the pairing jumps.
 */
void pairing_eval(ur_pairing *pairing, double u, double low, double high, double *sigma,
                  double *slope);

void pairing_free(ur_pairing *pairing);

/* The gaps of a strip's domain of existence (none for a given pairing). */
size_t pairing_gaps(const ur_pairing *pairing, const ur_interval **gaps);

/* Rail 2 at sigma, unwrapped when rail 2 is closed. */
void pairing_rail2(ur_pairing *pairing, double sigma, ur_vec3 d[3]);

/* The determinant det(x, y, z) = x . (y x z). */
double determinant3(ur_vec3 x, ur_vec3 y, ur_vec3 z);

/* "near point 12 (x, y, z), 34.5 mm along the curve" for a place on rail 1. */
void describe_place(ur_ruled *ruled, double u, char *text, size_t size);

/* The first gap of the domain of existence inside the part in use, or NULL (ruled.c). */
const ur_interval *ruled_gap_in_use(ur_ruled *ruled);

/*
 * The strip between rails through the given points (open curves through
 * them, as the command reads rails); the caller frees it with
 * ur_ruled_free.  Shared by the local and the global rail repairs.
 */
ur_status surface_strip_of_points(const ur_vec3 *rail1, size_t count1, const ur_vec3 *rail2,
                                  size_t count2, ur_ruled *strip, ur_error *error);

#endif
