/*
 * unroll/allow.h: pieces, i.e. what will be cut, and the fabrication
 * allowances that turn a flat net into them.
 *
 * A piece is a set of paths in its own plane coordinates (millimetres, y up),
 * each tagged with the operation the cutter performs on it.  For now a piece
 * is the net's outline (CUT) and, on request, its rulings (SCORE); glue tabs,
 * kerfing and the rest come in later.
 */
#ifndef UNROLL_ALLOW_H
#define UNROLL_ALLOW_H

#include "unroll/develop.h"
#include "unroll/geom.h"

typedef struct ur_path {
    ur_op op;
    bool closed;
    ur_vec2 *points; /* owned by the path */
    size_t count;
} ur_path;

/* What the report says of a piece: copied from its net. */
typedef struct ur_piece_measures {
    double area_3d;                      /* of the part of the surface the piece covers */
    double flat_area;                    /* enclosed by the outline */
    double edge_error;                   /* largest relative error of a flat edge length */
    double max_stretch, max_compression; /* of an approximate flattening; 0 when exact */
} ur_piece_measures;

typedef struct ur_piece {
    char name[32];
    ur_path *paths; /* owned; paths[0] is the outer outline */
    size_t path_count;
    ur_box box; /* of every path, in piece coordinates */
    ur_piece_measures measures;
    /*
     * Per-triangle strain copied from the net, in piece coordinates (those
     * of paths[0]); empty (NULL, 0) for a development.  Owned: ur_piece_free
     * frees it.  Only the strain picture draws it; nothing is cut from it.
     */
    ur_shading shading;
} ur_piece;

typedef struct ur_allowance_options {
    bool draw_rulings; /* rulings as SCORE lines */
} ur_allowance_options;

/* Copies points into a new path of the piece and grows its box. */
ur_status ur_piece_add_path(ur_piece *piece, ur_op op, const ur_vec2 *points, size_t count,
                            bool closed, ur_error *error);

/*
 * Builds the piece for a net, its shading copied; the caller frees it with
 * ur_piece_free.
 */
ur_status ur_piece_from_net(const ur_net *net, const ur_allowance_options *options, ur_piece *piece,
                            ur_error *error);

void ur_piece_free(ur_piece *piece);

#endif
