/*
 * atomic.c: temporary file next to the final name, flushed to disk, renamed
 * into place on commit.  Shared by every writer in src/out/ so there is one
 * copy of the fiddly part (see atomic.h for the life of a file).
 *
 * Failures of the file system (missing directory, no permission, disk full)
 * are UR_ERROR_INPUT: they concern the output path the user gave, not a bug.
 *
 * The tests need to see a disk fill up at any point of a multi-file output:
 * UNROLL_TEST_FAIL_WRITE_AFTER=N puts every temporary behind a stdio stream
 * of our own (fopencookie) that lets N bytes through in all, then fails
 * each write with EIO.  Unset, the streams are plain fdopen streams.
 */
#define _GNU_SOURCE /* fopencookie, for the test-only failure injection */
#include "atomic.h"

#include "unroll/out.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char *copy_string(const char *text, ur_error *error)
{
    size_t size = strlen(text) + 1;
    char *copy = malloc(size);
    if (!copy) {
        ur_error_out_of_memory(error);
        return NULL;
    }
    memcpy(copy, text, size);
    return copy;
}

/* The directory part of path: "." for a bare name, "/" for "/name". */
static char *directory_of(const char *path, ur_error *error)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return copy_string(".", error);
    size_t length = slash == path ? 1 : (size_t)(slash - path);
    char *directory = malloc(length + 1);
    if (!directory) {
        ur_error_out_of_memory(error);
        return NULL;
    }
    memcpy(directory, path, length);
    directory[length] = '\0';
    return directory;
}

/* Refuses, with a message naming it, a directory that is not there. */
static ur_status check_directory(const char *path, ur_error *error)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (*base == '\0')
        return ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': it names a directory", path);
    char *directory = directory_of(path, error);
    if (!directory)
        return UR_ERROR_INTERNAL;
    struct stat info;
    ur_status status = UR_OK;
    if (stat(directory, &info) != 0) {
        if (errno == ENOENT || errno == ENOTDIR)
            status =
                ur_error_set(error, UR_ERROR_INPUT,
                             "cannot write '%s': directory '%s' does not exist", path, directory);
        else
            status = ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': %s: %s", path,
                                  directory, strerror(errno));
    } else if (!S_ISDIR(info.st_mode)) {
        status = ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': '%s' is not a directory",
                              path, directory);
    } else if (stat(path, &info) == 0 && S_ISDIR(info.st_mode)) {
        /* found now, before any file of the output is renamed into place */
        status = ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': it is a directory", path);
    }
    free(directory);
    return status;
}

/* "DIR/.BASE.XXXXXX" for mkstemp: hidden, and in the same directory as path. */
static char *temp_template(const char *path, ur_error *error)
{
    const char *slash = strrchr(path, '/');
    size_t directory_length = slash ? (size_t)(slash - path) + 1 : 0;
    const char *base = path + directory_length;
    static const char suffix[] = ".XXXXXX";
    size_t size = directory_length + 1 + strlen(base) + sizeof suffix;
    char *name = malloc(size);
    if (!name) {
        ur_error_out_of_memory(error);
        return NULL;
    }
    memcpy(name, path, directory_length);
    name[directory_length] = '.';
    strcpy(name + directory_length + 1, base);
    strcat(name, suffix);
    return name;
}

/*
 * mkstemp creates 0600; give the file the mode open(2) would have given it.
 * umask() can only be read by setting it, so it is set back at once.
 */
static int newly_created_mode(void)
{
    mode_t mask = umask(0);
    umask(mask);
    return (int)(0666 & ~mask);
}

/* ---- Test-only failure injection ---------------------------------------- */

/* Bytes the writes may still pass; -1 when UNROLL_TEST_FAIL_WRITE_AFTER is unset. */
static long long injection_budget(void)
{
    static bool looked;
    static long long budget = -1;
    if (!looked) {
        looked = true;
        const char *value = getenv("UNROLL_TEST_FAIL_WRITE_AFTER");
        char *end = NULL;
        long long bytes = value ? strtoll(value, &end, 10) : -1;
        if (value && end != value && *end == '\0' && bytes >= 0)
            budget = bytes;
    }
    return budget;
}

static long long injection_left = -1; /* counted down from injection_budget() */

static ssize_t limited_write(void *cookie, const char *data, size_t size)
{
    int fd = (int)(intptr_t)cookie;
    size_t allowed = injection_left < 0 || (unsigned long long)injection_left >= size
                         ? size
                         : (size_t)injection_left;
    size_t done = 0;
    while (done < allowed) {
        ssize_t written = write(fd, data + done, allowed - done);
        if (written < 0)
            return -1;
        done += (size_t)written;
    }
    injection_left -= (long long)done;
    if (done < size) {
        errno = EIO;
        return -1; /* what got through stays in the temporary, as on a full disk */
    }
    return (ssize_t)size;
}

static int limited_close(void *cookie)
{
    return close((int)(intptr_t)cookie);
}

/* A stream on fd that fails once the injected budget is spent; plain when there is none. */
static FILE *open_stream(int fd)
{
    if (injection_budget() < 0)
        return fdopen(fd, "w");
    if (injection_left < 0)
        injection_left = injection_budget();
    cookie_io_functions_t functions = {.write = limited_write, .close = limited_close};
    return fopencookie((void *)(intptr_t)fd, "w", functions);
}

/* ---- The files ----------------------------------------------------------- */

/* Creates the temporary and opens a stream on it; removes it on failure. */
static ur_status create_temp(ur_atomic_file *file, ur_error *error)
{
    int fd = mkstemp(file->temp_path);
    if (fd < 0) {
        ur_status status = ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': %s", file->path,
                                        strerror(errno));
        free(file->temp_path); /* nothing was created */
        file->temp_path = NULL;
        return status;
    }
    if (fchmod(fd, (mode_t)newly_created_mode()) != 0) {
        ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': %s", file->path, strerror(errno));
        close(fd);
        return UR_ERROR_INPUT;
    }
    file->fd = fd;
    file->stream = open_stream(fd);
    if (!file->stream) {
        ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': %s", file->path, strerror(errno));
        close(fd);
        return UR_ERROR_INPUT;
    }
    return UR_OK;
}

ur_status ur_atomic_open(ur_atomic_file *file, const char *path, ur_error *error)
{
    memset(file, 0, sizeof *file);
    ur_status status = check_directory(path, error);
    if (status != UR_OK)
        return status;
    file->path = copy_string(path, error);
    if (!file->path)
        return UR_ERROR_INTERNAL;
    file->temp_path = temp_template(path, error);
    if (!file->temp_path) {
        ur_atomic_discard(file);
        return UR_ERROR_INTERNAL;
    }
    status = create_temp(file, error);
    if (status != UR_OK)
        ur_atomic_discard(file);
    return status;
}

ur_status ur_atomic_close(ur_atomic_file *file, ur_error *error)
{
    if (!file->stream)
        return ur_error_set(error, UR_ERROR_INTERNAL, "'%s' is not open", file->path);
    FILE *stream = file->stream;
    file->stream = NULL;
    /*
     * A write error may surface only here: in the buffer, the sync or the
     * close.  errno is cleared so that an error flag left by an earlier
     * fwrite is not blamed on some unrelated older errno.
     */
    int cause = 0;
    errno = 0;
    if (fflush(stream) != 0 || ferror(stream))
        cause = errno ? errno : EIO;
    else if (fsync(file->fd) != 0)
        cause = errno;
    if (fclose(stream) != 0 && cause == 0)
        cause = errno;
    if (cause != 0)
        return ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': %s", file->path,
                            strerror(cause));
    return UR_OK;
}

/* ---- Output sets ---------------------------------------------------------- */

/* The open set: how deep, whether an end refused it, and the files it holds back. */
static struct {
    size_t depth;
    bool refused;
    ur_atomic_file *held; /* closed temporaries, renamed or removed at the outermost end */
    size_t count, capacity;
} set;

void ur_output_set_begin(void)
{
    set.depth++;
}

/* Removes every temporary the set holds and forgets them. */
static void set_discard(void)
{
    for (size_t i = 0; i < set.count; i++)
        ur_atomic_discard(&set.held[i]);
    free(set.held);
    set.held = NULL;
    set.count = set.capacity = 0;
}

ur_status ur_output_set_end(bool commit, ur_error *error)
{
    if (set.depth == 0)
        return ur_error_set(error, UR_ERROR_INTERNAL, "an output set ended that was not begun");
    if (!commit)
        set.refused = true;
    if (--set.depth > 0)
        return UR_OK;
    ur_status status = UR_OK;
    if (!set.refused) {
        status = ur_cancel_check(error);
        for (size_t i = 0; status == UR_OK && i < set.count; i++)
            status = ur_atomic_commit(&set.held[i], error);
    }
    set_discard(); /* removes what was not renamed */
    set.refused = false;
    return status;
}

/* Takes over a closed temporary until the set ends; file is left empty. */
static ur_status set_hold(ur_atomic_file *file, ur_error *error)
{
    if (set.count == set.capacity) {
        ur_atomic_file *held =
            ur_array_grow(set.held, &set.capacity, set.count, sizeof *held, 8, error);
        if (!held)
            return UR_ERROR_INTERNAL;
        set.held = held;
    }
    set.held[set.count++] = *file;
    memset(file, 0, sizeof *file);
    return UR_OK;
}

ur_status ur_atomic_commit(ur_atomic_file *file, ur_error *error)
{
    if (file->stream || !file->temp_path)
        return ur_error_set(error, UR_ERROR_INTERNAL, "'%s' is not ready to commit",
                            file->path ? file->path : "(null)");
    if (set.depth > 0)
        return set_hold(file, error);
    if (rename(file->temp_path, file->path) != 0)
        return ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': %s", file->path,
                            strerror(errno));
    free(file->temp_path);
    file->temp_path = NULL;
    free(file->path);
    file->path = NULL;
    return UR_OK;
}

ur_status ur_atomic_commit_all(ur_atomic_file *files, size_t count, ur_error *error)
{
    ur_status status = ur_cancel_check(error);
    for (size_t i = 0; status == UR_OK && i < count; i++)
        status = ur_atomic_commit(&files[i], error);
    return status;
}

void ur_atomic_discard(ur_atomic_file *file)
{
    if (file->stream)
        (void)fclose(file->stream); /* the data is thrown away: errors do not matter */
    if (file->temp_path)
        unlink(file->temp_path);
    free(file->temp_path);
    free(file->path);
    memset(file, 0, sizeof *file);
}

ur_status ur_stream_write(FILE *stream, ur_emitter emit, const void *data, const char *what,
                          ur_error *error)
{
    errno = 0;
    if (!emit(stream, data) || fflush(stream) != 0 || ferror(stream))
        return ur_error_set(error, UR_ERROR_INPUT, "cannot write the %s to %s: %s", what,
                            stream == stdout ? "standard output" : "its stream",
                            errno ? strerror(errno) : "write error");
    return UR_OK;
}

ur_status ur_atomic_write(const char *path, ur_emitter emit, const void *data, const char *what,
                          ur_error *error)
{
    if (strcmp(path, "-") == 0)
        return ur_stream_write(stdout, emit, data, what, error);
    ur_atomic_file file;
    ur_status status = ur_atomic_open(&file, path, error);
    if (status != UR_OK)
        return status;
    errno = 0;
    if (!emit(file.stream, data))
        status = ur_error_set(error, UR_ERROR_INPUT, "cannot write '%s': %s", path,
                              errno ? strerror(errno) : "write error");
    if (status == UR_OK)
        status = ur_atomic_close(&file, error);
    if (status == UR_OK)
        status = ur_atomic_commit_all(&file, 1, error);
    ur_atomic_discard(&file); /* after a commit there is nothing left to remove */
    return status;
}
