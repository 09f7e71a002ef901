/*
 * atomic.c: temporary file next to the final name, flushed to disk, renamed
 * into place on commit.  Shared by every writer in src/out/ so there is one
 * copy of the fiddly part (see atomic.h for the life of a file).
 *
 * Failures of the file system (missing directory, no permission, disk full)
 * are UR_ERROR_IO; only a path that names a directory ("out/") is bad input.
 *
 * The tests need to see a disk fill up at any point of a multi-file output:
 * a context's write budget (ur_context_fail_writes_after) puts every
 * temporary behind a stdio stream of our own (fopencookie) that lets that
 * many bytes through in all, then fails each write with EIO.  Without one
 * the streams are plain fdopen streams.
 *
 * The context's output set lives here too: its held files are atomic files.
 */
#define _GNU_SOURCE /* fopencookie, for the test-only failure injection */
#include "atomic.h"

#include "context.h"

#include <fcntl.h>
#include <time.h>

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
        return UR_ERROR_MEMORY;
    struct stat info;
    ur_status status = UR_OK;
    if (stat(directory, &info) != 0) {
        if (errno == ENOENT || errno == ENOTDIR)
            status =
                ur_error_set(error, UR_ERROR_IO, "cannot write '%s': directory '%s' does not exist",
                             path, directory);
        else
            status = ur_error_set(error, UR_ERROR_IO, "cannot write '%s': %s: %s", path, directory,
                                  strerror(errno));
    } else if (!S_ISDIR(info.st_mode)) {
        status = ur_error_set(error, UR_ERROR_IO, "cannot write '%s': '%s' is not a directory",
                              path, directory);
    } else if (stat(path, &info) == 0 && S_ISDIR(info.st_mode)) {
        /* found now, before any file of the output is renamed into place */
        status = ur_error_set(error, UR_ERROR_IO, "cannot write '%s': it is a directory", path);
    }
    free(directory);
    return status;
}

/*
 * "DIR/.BASE.XXXXXX": hidden, and in the same directory as path.  The six
 * X are replaced by create_temp, which makes the name unique.
 */
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

/* ---- Test-only failure injection ---------------------------------------- */

/* What a limited stream writes to and the budget it shares with its context's other files. */
typedef struct limited_sink {
    int fd;
    long long *budget; /* the context's write_budget, counted down */
} limited_sink;

static ssize_t limited_write(void *cookie, const char *data, size_t size)
{
    limited_sink *sink = cookie;
    long long left = *sink->budget;
    size_t allowed = (unsigned long long)left >= size ? size : (size_t)left;
    size_t done = 0;
    while (done < allowed) {
        ssize_t written = write(sink->fd, data + done, allowed - done);
        if (written < 0)
            return -1;
        done += (size_t)written;
    }
    *sink->budget -= (long long)done;
    if (done < size) {
        errno = EIO;
        return -1; /* what got through stays in the temporary, as on a full disk */
    }
    return (ssize_t)size;
}

static int limited_close(void *cookie)
{
    limited_sink *sink = cookie;
    int result = close(sink->fd);
    free(sink);
    return result;
}

/* A stream on fd that fails once the context's budget is spent; plain when it has none. */
static FILE *open_stream(int fd, ur_context *context)
{
    if (!context || context->write_budget < 0)
        return fdopen(fd, "w");
    limited_sink *sink = malloc(sizeof *sink);
    if (!sink) {
        errno = ENOMEM;
        return NULL;
    }
    sink->fd = fd;
    sink->budget = &context->write_budget;
    cookie_io_functions_t functions = {.write = limited_write, .close = limited_close};
    FILE *stream = fopencookie(sink, "w", functions);
    if (!stream)
        free(sink);
    return stream;
}

/* ---- The files ----------------------------------------------------------- */

/*
 * Writes six letters from seed over the XXXXXX at the end of name; seed is
 * then moved on, so the next try gets another name.
 */
static void fill_in_name(char *name, unsigned long long *seed)
{
    static const char letters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    char *end = name + strlen(name);
    for (char *place = end - 6; place < end; place++) {
        *seed = *seed * 6364136223846793005ULL + 1442695040888963407ULL;
        *place = letters[(*seed >> 33) % (sizeof letters - 1)];
    }
}

/*
 * Opens a new temporary of a name no file has.  Created with mode 0666 and
 * O_EXCL, as mkstemp would but without its 0600, so that the umask gives
 * the file the mode any newly created file gets (asking for the umask
 * would change it for the whole process, if only for a moment).
 */
static int open_unique(char *name)
{
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    unsigned long long seed =
        (unsigned long long)now.tv_nsec ^ ((unsigned long long)now.tv_sec << 20) ^
        ((unsigned long long)getpid() << 40) ^ (unsigned long long)(uintptr_t)name;
    for (int attempt = 0; attempt < 100; attempt++) {
        fill_in_name(name, &seed);
        int fd = open(name, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST)
            return fd;
    }
    return -1; /* errno is EEXIST */
}

/* Creates the temporary and opens a stream on it; removes it on failure. */
static ur_status create_temp(atomic_file *file, ur_error *error)
{
    int fd = open_unique(file->temp_path);
    if (fd < 0) {
        ur_status status =
            ur_error_set(error, UR_ERROR_IO, "cannot write '%s': %s", file->path, strerror(errno));
        free(file->temp_path); /* nothing was created */
        file->temp_path = NULL;
        return status;
    }
    file->fd = fd;
    file->stream = open_stream(fd, file->context);
    if (!file->stream) {
        ur_status status = errno == ENOMEM
                               ? ur_error_out_of_memory(error)
                               : ur_error_set(error, UR_ERROR_IO, "cannot write '%s': %s",
                                              file->path, strerror(errno));
        close(fd);
        return status;
    }
    return UR_OK;
}

ur_status atomic_open(atomic_file *file, const char *path, ur_context *context, ur_error *error)
{
    memset(file, 0, sizeof *file);
    file->context = context;
    ur_status status = check_directory(path, error);
    if (status != UR_OK)
        return status;
    file->path = copy_string(path, error);
    if (!file->path)
        return UR_ERROR_MEMORY;
    file->temp_path = temp_template(path, error);
    if (!file->temp_path) {
        atomic_discard(file);
        return UR_ERROR_MEMORY;
    }
    status = create_temp(file, error);
    if (status != UR_OK)
        atomic_discard(file);
    return status;
}

ur_status atomic_close(atomic_file *file, ur_error *error)
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
        return ur_error_set(error, UR_ERROR_IO, "cannot write '%s': %s", file->path,
                            strerror(cause));
    return UR_OK;
}

/* ---- Output sets ---------------------------------------------------------- */

void ur_output_set_begin(ur_context *context)
{
    if (context)
        context->output_set.depth++;
}

void atomic_set_discard(ur_context *context)
{
    for (size_t i = 0; i < context->output_set.count; i++)
        atomic_discard(&context->output_set.held[i]);
    free(context->output_set.held);
    context->output_set.held = NULL;
    context->output_set.count = context->output_set.capacity = 0;
}

ur_status ur_output_set_end(ur_context *context, bool commit, ur_error *error)
{
    if (!context)
        return UR_OK;
    if (context->output_set.depth == 0)
        return ur_error_set(error, UR_ERROR_INTERNAL, "an output set ended that was not begun");
    if (!commit)
        context->output_set.refused = true;
    if (--context->output_set.depth > 0)
        return UR_OK;
    ur_status status = UR_OK;
    if (!context->output_set.refused) {
        status = ur_context_check(context, error);
        for (size_t i = 0; status == UR_OK && i < context->output_set.count; i++) {
            context->output_set.held[i].context = NULL; /* renamed now, not held again */
            status = atomic_commit(&context->output_set.held[i], error);
        }
    }
    atomic_set_discard(context); /* removes what was not renamed */
    context->output_set.refused = false;
    return status;
}

/* Takes over a closed temporary until the set ends; file is left empty. */
static ur_status set_hold(ur_context *context, atomic_file *file, ur_error *error)
{
    if (context->output_set.count == context->output_set.capacity) {
        atomic_file *held = ur_array_grow(context->output_set.held, &context->output_set.capacity,
                                          context->output_set.count, sizeof *held, 8, error);
        if (!held)
            return UR_ERROR_MEMORY;
        context->output_set.held = held;
    }
    context->output_set.held[context->output_set.count++] = *file;
    memset(file, 0, sizeof *file);
    return UR_OK;
}

ur_status atomic_commit(atomic_file *file, ur_error *error)
{
    if (file->stream || !file->temp_path)
        return ur_error_set(error, UR_ERROR_INTERNAL, "'%s' is not ready to commit",
                            file->path ? file->path : "(null)");
    if (file->context && file->context->output_set.depth > 0)
        return set_hold(file->context, file, error);
    if (rename(file->temp_path, file->path) != 0)
        return ur_error_set(error, UR_ERROR_IO, "cannot write '%s': %s", file->path,
                            strerror(errno));
    free(file->temp_path);
    file->temp_path = NULL;
    free(file->path);
    file->path = NULL;
    return UR_OK;
}

ur_status atomic_commit_all(atomic_file *files, size_t count, ur_error *error)
{
    ur_status status = count > 0 ? ur_context_check(files[0].context, error) : UR_OK;
    for (size_t i = 0; status == UR_OK && i < count; i++)
        status = atomic_commit(&files[i], error);
    return status;
}

void atomic_discard(atomic_file *file)
{
    if (file->stream)
        (void)fclose(file->stream); /* the data is thrown away: errors do not matter */
    if (file->temp_path)
        unlink(file->temp_path);
    free(file->temp_path);
    free(file->path);
    memset(file, 0, sizeof *file);
}

ur_status atomic_stream_write(FILE *stream, atomic_emitter emit, const void *data, const char *what,
                              ur_error *error)
{
    errno = 0;
    if (!emit(stream, data) || fflush(stream) != 0 || ferror(stream))
        return ur_error_set(error, UR_ERROR_IO, "cannot write the %s to %s: %s", what,
                            stream == stdout ? "standard output" : "its stream",
                            errno ? strerror(errno) : "write error");
    return UR_OK;
}

ur_status atomic_write(const char *path, atomic_emitter emit, const void *data, const char *what,
                       ur_context *context, ur_error *error)
{
    if (strcmp(path, "-") == 0)
        return atomic_stream_write(stdout, emit, data, what, error);
    atomic_file file;
    ur_status status = atomic_open(&file, path, context, error);
    if (status != UR_OK)
        return status;
    errno = 0;
    if (!emit(file.stream, data))
        status = ur_error_set(error, UR_ERROR_IO, "cannot write '%s': %s", path,
                              errno ? strerror(errno) : "write error");
    if (status == UR_OK)
        status = atomic_close(&file, error);
    if (status == UR_OK)
        status = atomic_commit_all(&file, 1, error);
    atomic_discard(&file); /* after a commit there is nothing left to remove */
    return status;
}
