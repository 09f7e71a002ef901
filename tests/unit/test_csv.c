/*
 * test_csv.c: the curve CSV reader and writer: accepted syntax, closed-curve
 * detection, every refusal with its line number, and an exact round trip.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "unroll/io.h"

/* Every test writes its files into one temporary directory. */
static char directory[64];
static char input_path[128];
static char output_path[128];

static int make_directory(void **state)
{
    (void)state;
    strcpy(directory, "/tmp/unroll-test-csv-XXXXXX");
    if (!mkdtemp(directory))
        return -1;
    snprintf(input_path, sizeof input_path, "%s/curve.csv", directory);
    snprintf(output_path, sizeof output_path, "%s/out.csv", directory);
    return 0;
}

static int remove_directory(void **state)
{
    (void)state;
    unlink(input_path);
    unlink(output_path);
    return rmdir(directory);
}

static void write_text(const char *path, const char *text)
{
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_int_equal(fwrite(text, 1, strlen(text), file), strlen(text));
    assert_int_equal(fclose(file), 0);
}

/* Reads text as a curve file; the caller frees *points. */
static ur_status read_text(const char *text, ur_vec3 **points, size_t *count, bool *closed,
                           ur_error *error)
{
    write_text(input_path, text);
    return ur_curve_csv_read(input_path, points, count, closed, error);
}

/* Expects text to be refused with "FILE:LINE: ..." containing fragment. */
static void expect_refusal(const char *text, const char *location, const char *fragment)
{
    ur_vec3 *points = NULL;
    size_t count = 99;
    bool closed = true;
    ur_error error = {0};
    assert_int_equal(read_text(text, &points, &count, &closed, &error), UR_ERROR_INPUT);
    assert_int_equal(error.status, UR_ERROR_INPUT);
    assert_null(points);
    assert_int_equal(count, 0);
    char prefix[256];
    snprintf(prefix, sizeof prefix, "%s%s: ", input_path, location);
    if (strncmp(error.message, prefix, strlen(prefix)) != 0 || !strstr(error.message, fragment))
        fail_msg("message '%s' lacks '%s' or '%s'", error.message, prefix, fragment);
}

static void test_reads_plain_points(void **state)
{
    (void)state;
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = true;
    ur_error error = {0};
    assert_int_equal(
        read_text("0,0,0\n1,0,0\n1,2.5,0\n-3e2,4,0.125\n", &points, &count, &closed, &error),
        UR_OK);
    assert_int_equal(count, 4);
    assert_false(closed);
    assert_true(points[2].y == 2.5);
    assert_true(points[3].x == -300.0);
    assert_true(points[3].z == 0.125);
    free(points);
}

static void test_comments_blanks_spaces_crlf(void **state)
{
    (void)state;
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = true;
    ur_error error = {0};
    const char *text = "# a helix\r\n"
                       "\r\n"
                       "  1 , 2 ,3   # first\r\n"
                       "\t\n"
                       "2,3,4\r\n"
                       "   # indented comment\n"
                       "3,4,5\r\n"
                       "4 ,5, 6"; /* no final newline */
    assert_int_equal(read_text(text, &points, &count, &closed, &error), UR_OK);
    assert_int_equal(count, 4);
    assert_false(closed);
    for (size_t i = 0; i < 4; i++) {
        assert_true(points[i].x == 1.0 + (double)i);
        assert_true(points[i].y == 2.0 + (double)i);
        assert_true(points[i].z == 3.0 + (double)i);
    }
    free(points);
}

static void test_closed_curve_drops_last_point(void **state)
{
    (void)state;
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = false;
    ur_error error = {0};
    assert_int_equal(
        read_text("0,0,0\n1,0,0\n1,1,0\n0,1,0\n0,0,0\n", &points, &count, &closed, &error), UR_OK);
    assert_true(closed);
    assert_int_equal(count, 4);
    assert_true(points[3].x == 0.0 && points[3].y == 1.0);
    free(points);
}

static void test_field_count(void **state)
{
    (void)state;
    expect_refusal("0,0,0\n1,0\n", ":2", "expected 3 fields");
    expect_refusal("# header\n0,0,0\n\n1,0,0,0\n", ":4", "found 4");
    expect_refusal("0,0,0\n1,1,1\n2,2,2\n3 3 3\n", ":4", "found 1");
}

static void test_non_numeric_field_is_quoted(void **state)
{
    (void)state;
    expect_refusal("0,0,0\n1,0,0\n1,abc,0\n", ":3", "'abc' is not a number");
    expect_refusal("0,0,0\n1,0,0\n1,2x,0\n", ":3", "'2x' is not a number");
    expect_refusal("0,0,0\n1,,0\n", ":2", "empty field");
}

static void test_nan_and_infinity(void **state)
{
    (void)state;
    expect_refusal("0,0,0\n1,0,0\n1,1,nan\n", ":3", "'nan' is not a finite number");
    expect_refusal("0,0,0\n-inf,0,0\n", ":2", "not a finite number");
    expect_refusal("0,0,0\n1,0,0\n1,1,1\n1e999,0,0\n", ":4", "not a finite number");
}

static void test_repeated_point(void **state)
{
    (void)state;
    expect_refusal("0,0,0\n# comment\n1,0,0\n\n1.0, 0 ,0e3\n2,0,0\n", ":5",
                   "repeats the point on line 3");
}

static void test_too_few_points(void **state)
{
    (void)state;
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = false;
    ur_error error = {0};
    assert_int_equal(read_text("0,0,0\n1,0,0\n1,1,0\n", &points, &count, &closed, &error),
                     UR_ERROR_INPUT);
    char expected[256];
    snprintf(expected, sizeof expected, "%s: a curve needs at least 4 points, found 3", input_path);
    assert_string_equal(error.message, expected);
    /* A closed triangle has 4 lines but only 3 distinct points. */
    assert_int_equal(read_text("0,0,0\n1,0,0\n1,1,0\n0,0,0\n", &points, &count, &closed, &error),
                     UR_ERROR_INPUT);
    assert_string_equal(error.message, expected);
    assert_int_equal(read_text("# nothing\n", &points, &count, &closed, &error), UR_ERROR_INPUT);
    snprintf(expected, sizeof expected, "%s: a curve needs at least 4 points, found 0", input_path);
    assert_string_equal(error.message, expected);
    assert_null(points);
}

static void test_missing_file(void **state)
{
    (void)state;
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = false;
    ur_error error = {0};
    char path[160];
    snprintf(path, sizeof path, "%s/no-such-file.csv", directory);
    assert_int_equal(ur_curve_csv_read(path, &points, &count, &closed, &error), UR_ERROR_INPUT);
    char expected[256];
    snprintf(expected, sizeof expected, "%s: cannot open: No such file or directory", path);
    assert_string_equal(error.message, expected);
}

static void test_write_then_read_round_trip(void **state)
{
    (void)state;
    /* Values whose decimal form is not exact: only %.17g brings them back. */
    const ur_vec3 written[5] = {
        {0.1, 0.2, 0.3},
        {1.0 / 3.0, -2.0 / 3.0, 1e-300},
        {3.141592653589793, 2.718281828459045, -987654321.0123456},
        {123456789.123456789, -0.0, 5e-324},
        {0.1, 0.2, 0.3}, /* closes the curve */
    };
    ur_error error = {0};
    assert_int_equal(ur_curve_csv_write(output_path, written, 5, NULL, &error), UR_OK);
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = false;
    assert_int_equal(ur_curve_csv_read(output_path, &points, &count, &closed, &error), UR_OK);
    assert_int_equal(count, 4);
    assert_true(closed);
    for (size_t i = 0; i < count; i++)
        assert_memory_equal(&points[i], &written[i], sizeof points[i]);
    free(points);
    /* The temporary ".out.csv.XXXXXX" is gone after the rename. */
    DIR *listing = opendir(directory);
    assert_non_null(listing);
    for (struct dirent *entry = readdir(listing); entry; entry = readdir(listing))
        if (strncmp(entry->d_name, ".out.csv.", 9) == 0)
            fail_msg("temporary file %s left behind", entry->d_name);
    closedir(listing);
}

static void test_write_into_missing_directory(void **state)
{
    (void)state;
    const ur_vec3 written[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    char path[160];
    snprintf(path, sizeof path, "%s/missing/out.csv", directory);
    ur_error error = {0};
    assert_int_equal(ur_curve_csv_write(path, written, 4, NULL, &error), UR_ERROR_IO);
    assert_non_null(strstr(error.message, path));
    assert_non_null(strstr(error.message, "does not exist"));
}

static void test_write_refuses_nan(void **state)
{
    (void)state;
    const ur_vec3 written[4] = {{0, 0, 0}, {1, 0, 0}, {NAN, 1, 0}, {0, 1, 0}};
    ur_error error = {0};
    unlink(output_path);
    assert_int_not_equal(ur_curve_csv_write(output_path, written, 4, NULL, &error), UR_OK);
    assert_non_null(strstr(error.message, "point 3 is not finite"));
    assert_int_not_equal(access(output_path, F_OK), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reads_plain_points),
        cmocka_unit_test(test_comments_blanks_spaces_crlf),
        cmocka_unit_test(test_closed_curve_drops_last_point),
        cmocka_unit_test(test_field_count),
        cmocka_unit_test(test_non_numeric_field_is_quoted),
        cmocka_unit_test(test_nan_and_infinity),
        cmocka_unit_test(test_repeated_point),
        cmocka_unit_test(test_too_few_points),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_write_then_read_round_trip),
        cmocka_unit_test(test_write_into_missing_directory),
        cmocka_unit_test(test_write_refuses_nan),
    };
    return cmocka_run_group_tests(tests, make_directory, remove_directory);
}
