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

/*
 * Affine transforms (SVG transforms, DXF block references): x' = a x + c y
 * + e, y' = b x + d y + f, as SVG writes matrix(a b c d e f).
 */
typedef struct parts_matrix {
    double a, b, c, d, e, f;
} parts_matrix;

static const parts_matrix parts_identity = {1, 0, 0, 1, 0, 0};

/* m after n: (m n) p = m (n p). */
parts_matrix parts_matrix_multiply(parts_matrix m, parts_matrix n);
ur_vec2 parts_matrix_apply(parts_matrix m, ur_vec2 p);
/* The most the matrix stretches a length: its largest singular value. */
double parts_matrix_stretch(parts_matrix m);
/*
 * How much m scales every length when it keeps circles circles (turns,
 * mirrors, moves and scales alike in every direction, to rounding); 0 when
 * it stretches one way more than another or skews, making circles ellipses.
 */
double parts_matrix_similarity_scale(parts_matrix m);

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

/*
 * A NURBS curve: degree >= 1, control_count control points, knots of
 * control_count + degree + 1 non-decreasing values (the reader checks
 * these), weights all > 0 or NULL for a plain B-spline.  Drawn over
 * knots[degree] .. knots[control_count].
 */
typedef struct parts_nurbs {
    int degree;
    const ur_vec2 *points;
    const double *weights;
    size_t control_count;
    const double *knots;
} parts_nurbs;

/* Appends every point of the flattened curve, its start included (unlike the other flatteners). */
ur_status parts_flatten_nurbs(parts_points *points, const parts_nurbs *curve, double tolerance,
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
    bool chained;          /* DXF pieces chained end to end, not one closed entity */
} parts_ring;

/*
 * Any other path: an open shape, or a shape drawn on a score, engrave, mark
 * or kerf layer.  It goes with the part whose outline holds it (unroll's own
 * folds and labels, another program's engraving or slits inside a part) and
 * is left out, with a warning, when no part holds it.
 */
typedef struct parts_line {
    ur_vec2 *points; /* owned; mm, y up */
    size_t count;
    bool closed;
    ur_op op;
    int line;
    char what[96];
} parts_line;

/* Larger than this is not a drawing of parts: refused before it is read. */
#define PARTS_MAX_BYTES (1024L * 1024 * 1024)

typedef struct parts_collection {
    const char *path; /* the file, or the name a buffer goes by: for messages */
    char *text;       /* owned: the whole file, NUL-terminated; the DXF reader cuts it up */
    size_t size;      /* bytes before the NUL */
    double tolerance; /* mm */
    double unit;      /* options->unit */
    bool strict;      /* options->strict: refuse what would be left out */
    parts_ring *rings;
    size_t count, capacity;
    parts_line *lines;
    size_t line_count, line_capacity;
    char (*warnings)[256];
    size_t warning_count;
    double kerf_compensated; /* what the file says (UR_KERF_NOTE); 0 when nothing */
} parts_collection;

/*
 * Takes points (left empty) as a new ring; circle (NULL for none) is the
 * circle, in mm, the ring exactly is, the points all on it.
 */
ur_status parts_add_ring(parts_collection *collection, parts_points *points, int line,
                         const char *what, const char *id, int sub, const ur_path_circle *circle,
                         ur_error *error);

/* Takes points (left empty) as a new line; fewer than two points are dropped. */
ur_status parts_add_line(parts_collection *collection, parts_points *points, bool closed, ur_op op,
                         int line, const char *what, ur_error *error);

/*
 * What a layer's (or an SVG group's) name says its paths are, the names
 * unroll writes and a few more: cut, score, fold(s), score valley, valley,
 * engrave, engraving, kerf, mark(s), marking, in any case, with spaces,
 * hyphens or underscores alike; UR_OP_COUNT for any other name.
 */
ur_op parts_layer_op(const char *name);

/*
 * Whether text is UR_KERF_NOTE with a kerf above 0 and " mm" (spaces
 * round it allowed), and that kerf, in *kerf.
 */
bool parts_read_kerf_note(const char *text, double *kerf);

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
