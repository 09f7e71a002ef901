/*
 * parts_internal.h: what the SVG and DXF part readers share with
 * parts_import.c: growing point lists, flattening curves, and the rings a
 * reader collects before they are sorted into parts and holes.
 *
 * A reader turns every closed shape into a ring in millimetres (y up) and
 * names where it came from; parts_assemble does the rest (validity,
 * containment, orientation) the same way for every format.
 */
#ifndef UNROLL_PARTS_INTERNAL_H
#define UNROLL_PARTS_INTERNAL_H

#include "unroll/io.h"

#include <stdbool.h>
#include <stddef.h>

/* More points than this for one curve is a runaway, not a drawing. */
#define PARTS_MAX_CURVE_SEGMENTS 100000

/* Nesting deeper than this (SVG groups) is refused rather than overflow the stack. */
#define PARTS_MAX_DEPTH 200

typedef struct parts_points {
    ur_vec2 *items;
    size_t count, capacity;
} parts_points;

/* Appends p unless it equals the last point (a zero-length edge). */
ur_status parts_points_push(parts_points *points, ur_vec2 p, ur_error *error);
void parts_points_free(parts_points *points);

/*
 * Flattening.  Each appends the curve's points after its start (which the
 * caller has pushed already) up to and including its end, so that the
 * chord of every segment stays within tolerance of the curve.
 */
ur_status parts_flatten_quadratic(parts_points *points, ur_vec2 p0, ur_vec2 p1, ur_vec2 p2,
                                  double tolerance, ur_error *error);
ur_status parts_flatten_cubic(parts_points *points, ur_vec2 p0, ur_vec2 p1, ur_vec2 p2, ur_vec2 p3,
                              double tolerance, ur_error *error);

/* An elliptical arc: centre, radii, x axis turned by rotation, from angle start by sweep (radians,
 * positive counter-clockwise). */
typedef struct parts_arc {
    ur_vec2 centre;
    double rx, ry, rotation;
    double start, sweep;
} parts_arc;

ur_vec2 parts_arc_point(const parts_arc *arc, double angle);
ur_status parts_flatten_arc(parts_points *points, const parts_arc *arc, double tolerance,
                            ur_error *error);

/* One closed shape as a reader found it. */
typedef struct parts_ring {
    ur_vec2 *points; /* owned; mm, y up, first point not repeated */
    size_t count;
    int line;              /* where it starts in the file; 0 when unknown */
    char what[96];         /* 'path id="a"', "LWPOLYLINE": for messages */
    char id[32];           /* the SVG id, empty otherwise */
    int sub;               /* 1 for the first ring of an element, 2 for the next ... */
    ur_path_circle circle; /* the circle the ring exactly is, mm; radius 0 for none */
} parts_ring;

typedef struct parts_collection {
    const char *path;
    double tolerance; /* mm */
    double unit;      /* options->unit */
    parts_ring *rings;
    size_t count, capacity;
    char (*warnings)[256];
    size_t warning_count;
} parts_collection;

/*
 * Takes points (left empty) as a new ring; circle (NULL for none) is the
 * circle, in mm, the ring exactly is, the points all on it.
 */
ur_status parts_add_ring(parts_collection *collection, parts_points *points, int line,
                         const char *what, const char *id, int sub, const ur_path_circle *circle,
                         ur_error *error);

/* Adds a warning, formatted like an error message. */
ur_status parts_warn(parts_collection *collection, ur_error *error, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Turns the rings into parts with holes; the collection's warnings move to parts. */
ur_status parts_assemble(parts_collection *collection, ur_parts *parts, ur_error *error);

void parts_collection_free(parts_collection *collection);

/* The readers: each fills collection with rings and warnings. */
ur_status parts_read_svg(parts_collection *collection, ur_error *error);
ur_status parts_read_dxf(parts_collection *collection, ur_error *error);

#endif
