/*
 * test_geos.h: what the unit tests that check geometry with GEOS share,
 * header-only as test_support.h is: the one GEOS context of a test
 * program, opened and closed round its group of tests (pass
 * geos_start and geos_finish to cmocka_run_group_tests), and a ring as
 * a GEOS polygon.  Included after test_support.h, which brings cmocka.
 */
#ifndef UNROLL_TEST_GEOS_H
#define UNROLL_TEST_GEOS_H

#include <geos_c.h>

#include "unroll/geom.h"

static GEOSContextHandle_t geos;

static inline int geos_start(void **state)
{
    (void)state;
    geos = GEOS_init_r();
    return geos ? 0 : -1;
}

static inline int geos_finish(void **state)
{
    (void)state;
    GEOS_finish_r(geos);
    return 0;
}

/* The closed ring (count points, the first not repeated) as a polygon; never NULL. */
static inline GEOSGeometry *polygon(const ur_vec2 *ring, size_t count)
{
    GEOSCoordSequence *sequence = GEOSCoordSeq_create_r(geos, (unsigned)count + 1, 2);
    assert_non_null(sequence);
    for (size_t i = 0; i <= count; i++)
        GEOSCoordSeq_setXY_r(geos, sequence, (unsigned)i, ring[i % count].x, ring[i % count].y);
    GEOSGeometry *shell = GEOSGeom_createLinearRing_r(geos, sequence);
    assert_non_null(shell);
    GEOSGeometry *result = GEOSGeom_createPolygon_r(geos, shell, NULL, 0);
    assert_non_null(result);
    return result;
}

#endif
