/*
 * test_support.h: what several unit tests share, header-only.
 *
 * The Makefile builds each tests/unit/test_*.c as a program of its own, so
 * there is no test library to link: everything here is a macro or a static
 * inline function, and a test that leaves one unused still builds with
 * -Werror.  It includes cmocka itself, so it may come before or after it.
 */
#ifndef UNROLL_TEST_SUPPORT_H
#define UNROLL_TEST_SUPPORT_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unroll/develop.h"

/* actual within tolerance * |expected| of expected; the message names the expression. */
#define assert_relative(actual, expected, tolerance)                                               \
    do {                                                                                           \
        double a_ = (actual), e_ = (expected);                                                     \
        if (!(fabs(a_ - e_) <= (tolerance)*fabs(e_)))                                              \
            fail_msg("%s = %.12g, expected %.12g within %g", #actual, a_, e_,                      \
                     (double)(tolerance));                                                         \
    } while (0)

/* The nets of ruled by method with n parts (rulings drawn for the exact method); fails on error. */
static inline ur_net_list develop(ur_ruled *ruled, ur_method method, size_t n, double tolerance)
{
    ur_develop_options options;
    ur_develop_options_default(&options);
    options.method = method;
    options.rulings = n;
    options.tolerance = tolerance;
    ur_net_list nets;
    ur_error error;
    if (ur_develop(ruled, &options, &nets, &error) != UR_OK)
        fail_msg("develop: %s", error.message);
    return nets;
}

/* ---- A test directory under /tmp ---------------------------------------- */

/* directory/name into path; fails the test rather than cut it short. */
static inline void path_in(const char *directory, const char *name, char *path, size_t size)
{
    int length = snprintf(path, size, "%s/%s", directory, name);
    assert_true(length > 0 && (size_t)length < size);
}

/* Whether anything, file or directory, is at path. */
static inline bool exists(const char *path)
{
    struct stat info;
    return stat(path, &info) == 0;
}

/*
 * Calls f (unless NULL) on each entry of directory but . and .., hidden
 * ones included; returns how many there are, -1 if it cannot be read.
 */
static inline int each_entry(const char *directory, int (*f)(const char *path))
{
    DIR *dir = opendir(directory);
    if (!dir)
        return -1;
    int count = 0;
    struct dirent *entry;
    char path[512];
    while ((entry = readdir(dir)) != NULL) {
        if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0)
            continue;
        count++;
        snprintf(path, sizeof path, "%s/%s", directory, entry->d_name);
        if (f)
            f(path);
    }
    closedir(dir);
    return count;
}

/* How many entries directory holds: temporaries a writer left behind count too. */
static inline int entries_in(const char *directory)
{
    int count = each_entry(directory, NULL);
    assert_true(count >= 0);
    return count;
}

/* Removes directory and the files in it (tests write no subdirectories); 0 on success. */
static inline int remove_test_directory(const char *directory)
{
    each_entry(directory, unlink);
    return rmdir(directory);
}

#endif
