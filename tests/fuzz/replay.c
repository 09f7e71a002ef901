/*
 * replay.c: runs a fuzz target without libFuzzer, on given files: linked
 * with one tests/fuzz/fuzz_*.c by the ordinary compiler, it is how
 * `make check` passes every seed and every regression input through the
 * same code the fuzzer ran (under ASan and UBSan with SANITIZE=1).
 *
 *     replay DIR_OR_FILE...
 *
 * A crash or a broken check aborts the program; otherwise it prints how
 * many inputs it ran and exits 0.  Exits 2 when an argument cannot be read
 * or names no input at all (an empty corpus tests nothing).
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The whole file; NULL when it cannot be read. */
static uint8_t *read_input(const char *path, size_t *size)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return NULL;
    uint8_t *data = NULL;
    size_t length = 0, capacity = 0;
    for (;;) {
        if (length == capacity) {
            capacity = capacity ? 2 * capacity : 4096;
            uint8_t *grown = realloc(data, capacity);
            if (!grown) {
                free(data);
                fclose(file);
                return NULL;
            }
            data = grown;
        }
        size_t got = fread(data + length, 1, capacity - length, file);
        length += got;
        if (got == 0)
            break;
    }
    int failed = ferror(file);
    fclose(file);
    if (failed) {
        free(data);
        return NULL;
    }
    *size = length;
    return data;
}

static int run_file(const char *path, size_t *count)
{
    size_t size = 0;
    uint8_t *data = read_input(path, &size);
    if (!data) {
        fprintf(stderr, "replay: %s: cannot read\n", path);
        return 2;
    }
    LLVMFuzzerTestOneInput(data, size);
    free(data);
    (*count)++;
    return 0;
}

/* Every regular file of the directory, in name order so that runs repeat. */
static int run_directory(const char *directory, size_t *count)
{
    struct dirent **entries = NULL;
    int n = scandir(directory, &entries, NULL, alphasort);
    if (n < 0) {
        fprintf(stderr, "replay: %s: cannot read\n", directory);
        return 2;
    }
    int status = 0;
    for (int i = 0; i < n; i++) {
        char path[4096];
        struct stat info;
        int length = snprintf(path, sizeof path, "%s/%s", directory, entries[i]->d_name);
        if (status == 0 && length > 0 && (size_t)length < sizeof path && stat(path, &info) == 0 &&
            S_ISREG(info.st_mode))
            status = run_file(path, count);
        free(entries[i]);
    }
    free(entries);
    return status;
}

int main(int argc, char **argv)
{
    size_t count = 0;
    for (int i = 1; i < argc; i++) {
        struct stat info;
        if (stat(argv[i], &info) != 0) {
            fprintf(stderr, "replay: %s: cannot read\n", argv[i]);
            return 2;
        }
        int status =
            S_ISDIR(info.st_mode) ? run_directory(argv[i], &count) : run_file(argv[i], &count);
        if (status)
            return status;
    }
    if (count == 0) {
        fprintf(stderr, "replay: no input\n");
        return 2;
    }
    printf("replay: %zu inputs ran\n", count);
    return 0;
}
