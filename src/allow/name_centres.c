/*
 * name_centres.c: where each piece's name is sought first (joints.c names
 * the pieces round these points).
 *
 * The centre of the largest circle inside a piece's outline (GEOS) lies
 * well inside the piece whatever its shape, where the centre of its box
 * may lie on a fold (a cube's cross of faces) or off the piece (a ring, a
 * spiral strip); the box's centre is kept where GEOS cannot tell.
 *
 * GEOS's search for the circle is the costliest part of naming: a third
 * of the tabs' and labels' time on a 2,208-triangle sphere's six long
 * pieces.  The circles are found in two threads, each with a GEOS context
 * of its own, taking the pieces one at a time as they come free; each
 * circle depends on its piece alone, so which thread finds it changes
 * nothing.
 */
#include "allow_internal.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <threads.h>

/* The pieces (only read while the threads run) and where their centres go. */
typedef struct centre_work {
    const ur_piece *pieces;
    size_t count;
    ur_vec2 *centres;
    atomic_size_t next; /* the next piece a thread takes */
} centre_work;

/*
 * The centre of the largest circle inside the piece's outline, sought to
 * a thousandth of its box's diagonal; the box's centre if GEOS cannot tell.
 */
static ur_vec2 centre_of(GEOSContextHandle_t geos, const ur_piece *piece)
{
    ur_vec2 centre = ur_vec2_make((piece->box.min.x + piece->box.max.x) / 2,
                                  (piece->box.min.y + piece->box.max.y) / 2);
    const ur_path *outline = &piece->paths[0];
    double diagonal = hypot(ur_box_width(piece->box), ur_box_height(piece->box));
    if (!(diagonal > 0) || !isfinite(diagonal)) /* GEOS's search would not end */
        return centre;
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, outline->points, outline->count);
    GEOSGeometry *radius =
        polygon ? GEOSMaximumInscribedCircle_r(geos, polygon, 1e-3 * diagonal) : NULL;
    const GEOSCoordSequence *ends = radius ? GEOSGeom_getCoordSeq_r(geos, radius) : NULL;
    double x, y;
    if (ends && GEOSCoordSeq_getXY_r(geos, ends, 0, &x, &y) && isfinite(x) && isfinite(y))
        centre = ur_vec2_make(x, y);
    if (radius)
        GEOSGeom_destroy_r(geos, radius);
    if (polygon)
        GEOSGeom_destroy_r(geos, polygon);
    return centre;
}

/* Finds the centres of the pieces not taken yet, one at a time. */
static void take_pieces(centre_work *w, GEOSContextHandle_t geos)
{
    for (;;) {
        size_t k = atomic_fetch_add(&w->next, 1);
        if (k >= w->count)
            return;
        w->centres[k] = centre_of(geos, &w->pieces[k]);
    }
}

/* The second thread: with no GEOS context of its own it takes nothing, and the first does all. */
static int helper(void *data)
{
    centre_work *w = data;
    GEOSContextHandle_t geos = GEOS_init_r();
    if (geos) {
        take_pieces(w, geos);
        GEOS_finish_r(geos);
    }
    return 0;
}

ur_status allow_name_centres(GEOSContextHandle_t geos, const ur_piece *pieces, size_t count,
                             ur_vec2 **centres, ur_error *error)
{
    *centres = ur_alloc_array(count, sizeof **centres, error);
    if (!*centres)
        return UR_ERROR_MEMORY;
    centre_work w = {.pieces = pieces, .count = count, .centres = *centres};
    atomic_init(&w.next, 0);
    thrd_t thread;
    bool beside = count > 1 && thrd_create(&thread, helper, &w) == thrd_success;
    take_pieces(&w, geos);
    if (beside)
        thrd_join(thread, NULL);
    return UR_OK;
}
