/*
 * relief_internal.h (internal to src/allow/): what the two halves of the
 * relief share: the job, a region's need, and the slits and records of
 * relief_slits.c that relief.c lays out over regions and rulings.
 */
#ifndef UNROLL_ALLOW_RELIEF_INTERNAL_H
#define UNROLL_ALLOW_RELIEF_INTERNAL_H

#include "allow_internal.h"

#include <geos_c.h>

#define RELIEF_MAX_SLITS 512 /* per region: beyond this the limits make no sense */

typedef enum relief_kind { RELIEF_NONE, RELIEF_KERFING, RELIEF_OVERLAP } relief_kind;

/* What every step needs: the piece, the limits and the net's outline in GEOS. */
typedef struct relief_job {
    GEOSContextHandle_t geos;
    ur_piece *piece;
    const ur_net *net;
    const ur_relief_limits *limits;
    GEOSGeometry *outline; /* the net's outline as a polygon */
    GEOSGeometry *inner;   /* the outline buffered inward by margin (maybe empty) */
    GEOSGeometry *keepout; /* the relief cut so far buffered by margin; NULL for none */
    double size;           /* the diagonal of the outline's box */
    ur_error *error;
} relief_job;

/* What a region (or a whole development) needs relieved, and where. */
typedef struct relief_need {
    relief_kind kind;
    double value, limit; /* the largest strain, the material's limit */
    double length;       /* deficit or excess, mm */
    ur_vec2 where;
    size_t wanted, cut; /* slits the formula asks for, slits cut */
} relief_need;

/* Fails the job (UR_ERROR_INTERNAL) saying what GEOS could not do, naming the piece. */
ur_status relief_geos_failed(relief_job *job, const char *what);

/* The ends of the parts of segment a b inside area and, unless avoid is NULL, outside avoid. */
ur_status relief_clip_segment(relief_job *job, ur_vec2 a, ur_vec2 b, const GEOSGeometry *area,
                              const GEOSGeometry *avoid, ur_points *ends);

/*
 * Adds the relief cuts of one region, the piece's KERF paths from first on,
 * to the keep-out once the region is done: its own slits are parallel and
 * may lie closer than margin to each other.
 */
ur_status relief_keep_out_since(relief_job *job, size_t first);

/* One KERF slit: the parts of segment a b inside area, those shorter than opening dropped. */
ur_status relief_kerfing_slit(relief_job *job, ur_vec2 a, ur_vec2 b, const GEOSGeometry *area,
                              bool *cut);

/*
 * An overlap slit on the chord a b (both on the outline) whose part in the
 * region lies between distances low and high from a: from the nearer end
 * of the chord through that part.
 */
ur_status relief_overlap_on_chord(relief_job *job, ur_vec2 a, ur_vec2 b, double low, double high,
                                  double w, ur_vec2 side, bool *cut);

/* v turned a quarter turn counter-clockwise. */
ur_vec2 relief_perpendicular(ur_vec2 v);

/*
 * Records on the piece what a region needed and what was cut (a warning
 * when fewer slits fit than wanted); across names the slits' direction.
 */
ur_status relief_record_need(relief_job *job, const relief_need *need, const char *across);

/* n = ceil(length / opening), at least 1, at most one per opening of span and RELIEF_MAX_SLITS. */
size_t relief_slit_count(double length, double opening, double span);

#endif
