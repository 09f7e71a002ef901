/*
 * unroll/nest.h: placing pieces on sheets of stock.
 *
 * Sheet coordinates are millimetres with the origin at the sheet's lower left
 * corner, x to the right and y up.  A placement is a rigid motion taking piece
 * coordinates to sheet coordinates.  For now pieces go in rows (shelves); true
 * shape nesting comes later behind the same types.
 */
#ifndef UNROLL_NEST_H
#define UNROLL_NEST_H

#include "unroll/allow.h"
#include "unroll/geom.h"

typedef struct ur_placement {
    size_t piece_index;
    ur_transform2 transform;
} ur_placement;

typedef struct ur_sheet {
    double width, height;
    ur_placement *placements; /* owned */
    size_t placement_count;
} ur_sheet;

typedef struct ur_layout {
    ur_sheet *sheets; /* owned */
    size_t sheet_count;
} ur_layout;

typedef struct ur_layout_options {
    double sheet_width, sheet_height;
    double margin;  /* kept free along every sheet edge */
    double spacing; /* kept free between pieces */
} ur_layout_options;

/*
 * Places every piece on as many sheets as needed, row by row.  Each piece is
 * first turned so that its smallest enclosing rectangle lies flat, then a
 * quarter turn more if that is what makes it fit.  Fails with UR_ERROR_INPUT,
 * naming both sizes, when a piece fits no sheet.
 */
ur_status ur_layout_rows(const ur_piece *pieces, size_t piece_count,
                         const ur_layout_options *options, ur_layout *layout, ur_error *error);

/* Share of the sheet's area covered by the outlines placed on it, 0..1. */
double ur_sheet_utilisation(const ur_sheet *sheet, const ur_piece *pieces);

void ur_layout_free(ur_layout *layout);

#endif
