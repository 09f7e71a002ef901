/*
 * layout.c: layouts (core.h): how much of a sheet its pieces use, and
 * freeing.  Making them is src/nest's.
 */
#include "unroll/core.h"

#include <math.h>
#include <stdlib.h>

double ur_sheet_utilisation(const ur_sheet *sheet, const ur_piece *pieces)
{
    double used = 0.0;
    for (size_t k = 0; k < sheet->placement_count; k++) {
        const ur_piece *piece = &pieces[sheet->placements[k].piece_index];
        if (piece->bridged) /* the outline is open: what it enclosed before */
            used += piece->outline_area;
        else if (piece->path_count > 0)
            used += fabs(ur_polygon_signed_area(piece->paths[0].points, piece->paths[0].count));
    }
    return used / (sheet->width * sheet->height);
}

void ur_layout_free(ur_layout *layout)
{
    for (size_t s = 0; s < layout->sheet_count; s++)
        free(layout->sheets[s].placements);
    free(layout->sheets);
    layout->sheets = NULL;
    layout->sheet_count = 0;
    free(layout->not_placed);
    layout->not_placed = NULL;
    layout->not_placed_count = 0;
}
