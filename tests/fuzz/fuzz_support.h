/*
 * fuzz_support.h: what the fuzz targets in tests/fuzz/ share, header-only.
 *
 * Every reader of the library takes a file path (it names the file in its
 * messages and knows the format by the extension), so a target writes the
 * fuzzer's bytes to a file of the right name in a private temporary
 * directory and hands the reader that path.  The directory is made on first
 * use and removed when the process exits normally; each target uses one or
 * a few fixed names, rewritten for every input.
 *
 * FUZZ_CHECK turns a broken promise of the library's (a NaN in an accepted
 * file's points, an index out of range) into a crash the fuzzer reports,
 * so that a target checks more than "did not crash".
 */
#ifndef UNROLL_FUZZ_SUPPORT_H
#define UNROLL_FUZZ_SUPPORT_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FUZZ_CHECK(condition)                                                                      \
    do {                                                                                           \
        if (!(condition)) {                                                                        \
            fprintf(stderr, "%s:%d: broken: %s\n", __FILE__, __LINE__, #condition);                \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

/* File names a target may use in its directory, so that exit can remove them. */
#define FUZZ_MAX_NAMES 8

static char fuzz_directory[512];
static const char *fuzz_names[FUZZ_MAX_NAMES];
static size_t fuzz_name_count;

static inline void fuzz_remove_directory(void)
{
    char path[1024];
    for (size_t i = 0; i < fuzz_name_count; i++) {
        snprintf(path, sizeof path, "%s/%s", fuzz_directory, fuzz_names[i]);
        unlink(path);
    }
    rmdir(fuzz_directory);
}

/* Makes the directory once; aborts if it cannot: a fuzz run without it tests nothing. */
static inline void fuzz_make_directory(void)
{
    if (fuzz_directory[0])
        return;
    const char *tmp = getenv("TMPDIR");
    int length = snprintf(fuzz_directory, sizeof fuzz_directory, "%s/unroll-fuzz-XXXXXX",
                          tmp ? tmp : "/tmp");
    FUZZ_CHECK(length > 0 && (size_t)length < sizeof fuzz_directory);
    FUZZ_CHECK(mkdtemp(fuzz_directory) != NULL);
    FUZZ_CHECK(atexit(fuzz_remove_directory) == 0);
}

static inline void fuzz_remember_name(const char *name)
{
    for (size_t i = 0; i < fuzz_name_count; i++)
        if (strcmp(fuzz_names[i], name) == 0)
            return;
    FUZZ_CHECK(fuzz_name_count < FUZZ_MAX_NAMES);
    fuzz_names[fuzz_name_count++] = name;
}

/*
 * Writes data to the file NAME (a string literal: it is kept for the clean-up)
 * in the target's directory and puts its path into path.
 */
static inline void fuzz_write_file(const char *name, const uint8_t *data, size_t size, char *path,
                                   size_t path_size)
{
    fuzz_make_directory();
    fuzz_remember_name(name);
    int length = snprintf(path, path_size, "%s/%s", fuzz_directory, name);
    FUZZ_CHECK(length > 0 && (size_t)length < path_size);
    FILE *file = fopen(path, "wb");
    FUZZ_CHECK(file != NULL);
    FUZZ_CHECK(size == 0 || fwrite(data, 1, size, file) == size);
    FUZZ_CHECK(fclose(file) == 0);
}

#endif
