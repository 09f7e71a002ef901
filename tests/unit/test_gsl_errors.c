/*
 * test_gsl_errors.c: the library turns GSL's error handler off only while
 * it calls GSL: a host program's own handler is neither called by the
 * library's GSL errors nor replaced after them.
 */
#include "test_support.h"

#include <gsl/gsl_errno.h>

#include "unroll/surface.h"

static int host_errors;

static void host_handler(const char *reason, const char *file, int line, int gsl_errno)
{
    (void)reason;
    (void)file;
    (void)line;
    (void)gsl_errno;
    host_errors++;
}

static ur_curve *line_through(double y, double z)
{
    const ur_vec3 points[] = {{0, y, z}, {10, y, z}, {20, y, z}, {30, y, z}};
    ur_curve *curve = NULL;
    ur_error error;
    assert_int_equal(ur_curve_new_interpolating(points, 4, false, &curve, &error), UR_OK);
    return curve;
}

static void test_host_handler_is_kept(void **state)
{
    (void)state;
    gsl_error_handler_t *before = gsl_set_error_handler(host_handler);
    ur_ruled ruled;
    ur_error error;
    assert_int_equal(
        ur_ruled_general(line_through(0, 0), line_through(20, 5), UR_PAIR_POINTS, &ruled, &error),
        UR_OK);
    /* Outside the pairing's table GSL's interpolation fails: by its status, not the handler. */
    double sigma, slope;
    ur_ruled_pairing(&ruled, 1e6, &sigma, &slope);
    assert_true(isnan(sigma));
    /* A plane strip 30 x sqrt(20^2 + 5^2) mm */
    double area;
    assert_int_equal(ur_ruled_area(&ruled, ur_curve_start(ruled.curve), ur_curve_end(ruled.curve),
                                   &area, &error),
                     UR_OK);
    assert_relative(area, 30 * sqrt(425.0), 1e-9);
    ur_ruled_free(&ruled);
    assert_int_equal(host_errors, 0);
    assert_ptr_equal(gsl_set_error_handler(before), host_handler);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_host_handler_is_kept),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
