/*
 * fuzz_support.h: what the fuzz targets in tests/fuzz/ share, header-only.
 *
 * Every reader of the library takes a memory buffer as well as a path,
 * with a name that stands for the file (it names the file in messages and
 * tells the format by its extension): a target hands the fuzzer's bytes
 * straight to the reader's buffer version, which shares all its code with
 * the path version but the reading of the file.
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

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FUZZ_CHECK(condition)                                                                      \
    do {                                                                                           \
        if (!(condition)) {                                                                        \
            fprintf(stderr, "%s:%d: broken: %s\n", __FILE__, __LINE__, #condition);                \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

#endif
