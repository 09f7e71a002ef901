/*
 * atomic.h (library-internal, used by every writer: src/out/ and the CSV
 * writer in src/io/): writing a file so that it appears complete or not at
 * all.
 *
 * The data goes to a temporary file ".NAME.XXXXXX" next to the final name
 * (same directory, hence same file system, so rename() is atomic), is flushed
 * to disk, and is renamed into place only when the caller commits.  Writers
 * of several files open them all, write them all, and commit them only once
 * every one is complete; any failure before that discards every temporary
 * and leaves what was on disk untouched.
 *
 * Life of a file: atomic_open, write to ->stream, atomic_close, then
 * atomic_commit; atomic_discard at any point undoes what is not yet
 * committed and frees everything.  A zeroed atomic_file is "nothing yet",
 * safe to discard.  A file belongs to the context it was opened in (which
 * may be NULL): inside that context's output set (ur_output_set_begin,
 * unroll/base.h) atomic_commit only hands the temporary to the set,
 * which renames everything at its end.  In a cancelled context nothing is
 * renamed: atomic_commit_all and atomic_write then fail with
 * UR_ERROR_CANCELLED.  The context's write budget
 * (ur_context_fail_writes_after) applies to every file opened in it.
 */
#ifndef UNROLL_OUT_ATOMIC_H
#define UNROLL_OUT_ATOMIC_H

#include <stdbool.h>
#include <stdio.h>

#include "unroll/base.h"

typedef struct atomic_file {
    char *path;          /* owned: the final name */
    char *temp_path;     /* owned: the temporary; NULL once renamed or removed */
    FILE *stream;        /* open between atomic_open and atomic_close */
    int fd;              /* the temporary's descriptor, under stream, for fsync */
    ur_context *context; /* not owned; NULL for none */
} atomic_file;

/*
 * Creates the temporary for path, readable as a newly created file would be
 * (0666 less the umask).  Fails with UR_ERROR_INPUT, naming the directory,
 * when the directory does not exist.
 */
ur_status atomic_open(atomic_file *file, const char *path, ur_context *context, ur_error *error);

/* Flushes, syncs and closes the stream; the temporary stays until commit. */
ur_status atomic_close(atomic_file *file, ur_error *error);

/* Renames the closed temporary to the final name and frees the names. */
ur_status atomic_commit(atomic_file *file, ur_error *error);

/*
 * Commits files[0 .. count - 1], all closed, in order; fails before the
 * first rename, renaming none, when the run was cancelled.
 */
ur_status atomic_commit_all(atomic_file *files, size_t count, ur_error *error);

/* Closes and removes whatever is not committed and frees everything. */
void atomic_discard(atomic_file *file);

/* Writes a whole document to stream; false on a write error (errno may say why). */
typedef bool (*atomic_emitter)(FILE *stream, const void *data);

/*
 * Writes what emit produces to path: to standard output for "-", else
 * atomically (nothing left behind on failure, an existing file untouched).
 * what names the document in messages ("plot", "report").
 */
ur_status atomic_write(const char *path, atomic_emitter emit, const void *data, const char *what,
                       ur_context *context, ur_error *error);

/* Removes every temporary context's output set holds and forgets them (context.c's free). */
void atomic_set_discard(ur_context *context);

/*
 * Writes what emit produces to a stream the caller owns (and closes), and
 * flushes it: the writers' FILE * versions, and "-".
 */
ur_status atomic_stream_write(FILE *stream, atomic_emitter emit, const void *data, const char *what,
                              ur_error *error);

#endif
