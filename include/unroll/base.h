/*
 * unroll/base.h: the vocabulary every module shares: status codes, error
 * messages and the cutting operations.
 *
 * The library never prints and never exits.  Every function that can fail
 * returns a ur_status and, when it fails, fills a caller-owned ur_error with
 * one sentence the caller can show as it is.
 */
#ifndef UNROLL_BASE_H
#define UNROLL_BASE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define UR_VERSION "0.1.0"

/*
 * Marks the public API: the library is built with -fvisibility=hidden, so
 * that libunroll.so exports only what is declared with UR_API (and the
 * static archive keeps the rest local too).
 */
#if defined(__GNUC__)
#define UR_API __attribute__((visibility("default")))
#else
#define UR_API
#endif

/*
 * The largest coordinate or length, in mm, taken from any input (1000 km):
 * far beyond any sheet or part, and small enough that squares, cross
 * products and areas of such numbers never overflow.
 */
#define UR_LENGTH_MAX 1e9

/*
 * What went wrong.  The command maps each to an exit status of its own
 * (unroll(1), EXIT STATUS); the numbers are not exit statuses.
 */
typedef enum ur_status {
    UR_OK = 0,
    UR_ERROR_INTERNAL = 1,  /* a library failure, a computation that failed, a bug */
    UR_ERROR_INPUT = 2,     /* bad input: a file, a line, a value, a missing input file */
    UR_ERROR_CANCELLED = 3, /* the context was cancelled */
    UR_ERROR_IO = 4,        /* the system refused an output: no such directory, no
                               permission, a full disk, a failed write */
    UR_ERROR_MEMORY = 5     /* out of memory */
} ur_status;

/*
 * A failure: its status, one sentence, and the settings it is about.
 * Messages name no command-line flag.  They name a job's settings by
 * their names, the ones a job file's <option name="..."/> and
 * ur_job_option_name use ("cone: top-radius must be zero or positive";
 * "give units m"), and setting lists those names, separated by spaces,
 * the one the failure is about first ("top-radius"; "apex cut curve radius
 * top-radius"), so that a caller can point at them in its own terms: the
 * command writes the first use of each as its flag, "--top-radius" (a name
 * listed twice, its first two uses), and puts a listed name the sentence
 * does not use as a word in front ("--sheet: piece P1 does not fit ...").
 * "" when the message is about no setting.
 */
typedef struct ur_error {
    ur_status status;
    char message[1024];
    char setting[64];
} ur_error;

/*
 * Fills error (which may be NULL) with a printf-style message and no
 * setting; returns status.
 */
UR_API ur_status ur_error_set(ur_error *error, ur_status status, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/*
 * Says which settings error's message names (see ur_error: their names,
 * space-separated, the one it is about first), after ur_error_set;
 * returns error's status, or UR_ERROR_INPUT when error is NULL (a message
 * naming a setting is one about bad input).
 */
UR_API ur_status ur_error_set_setting(ur_error *error, const char *setting);

/* Prefixes an existing message with more context, e.g. a file's name; keeps the setting. */
UR_API ur_status ur_error_prefix(ur_error *error, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

UR_API void ur_error_clear(ur_error *error);

/* Out-of-memory (UR_ERROR_MEMORY) in one place so every caller words it the same. */
UR_API ur_status ur_error_out_of_memory(ur_error *error);

/*
 * The context a run happens in, like lua_State or GEOS's handle: it holds
 * everything that would otherwise be state of the whole process.
 *
 * - Cancelling.  Long computations (the nesting search, ARAP iterations,
 *   charts, tabs) poll their context's flag, found in their options, and
 *   return UR_ERROR_CANCELLED at their next check once it is set; the
 *   writers check it once more before renaming any file into place, so that
 *   a cancelled run leaves no output.  ur_context_cancel only stores to a
 *   lock-free atomic, so a signal handler may call it, and worker threads
 *   read the flag without a data race.
 * - The output set (ur_output_set_begin): the files of a run held back so
 *   that they appear together or not at all.
 * - Messages: the warnings and notes of every computation in the context
 *   (a job's among them: unroll/job.h) go to the handler set here, the one
 *   route they take; with no handler they are dropped.
 * - A test hook that makes the writers fail as a full disk would.
 *
 * A NULL context is allowed wherever one is taken: never cancelled, no
 * output set (files are renamed into place as each is complete), messages
 * dropped.  One context may serve one run at a time; runs in several
 * threads each need their own.
 */
typedef struct ur_context ur_context;

typedef enum ur_message_kind {
    UR_MESSAGE_WARNING = 0, /* the run goes on, but the user should know */
    UR_MESSAGE_NOTE         /* what was chosen or done, for a verbose caller */
} ur_message_kind;

/*
 * Gets each message as the sentence to show, whole, with no newline
 * ("strip: warning: piece P2: ...", "hypar: note: ..."), from the thread
 * that runs the computation; data is what was given with the handler.
 * setting lists the settings the sentence names, as ur_error's does
 * ("no-split"; "" for none).
 */
typedef void (*ur_message_handler)(void *data, ur_message_kind kind, const char *message,
                                   const char *setting);

/* A new context, or NULL when out of memory.  Freed with ur_context_free. */
UR_API ur_context *ur_context_new(void);

/* Removes the files of an output set still open (as an end refusing them) and frees. */
UR_API void ur_context_free(ur_context *context);

/* Asks every computation running in context to stop; safe from a signal handler. */
UR_API void ur_context_cancel(ur_context *context);

/* Clears the request, for a caller that runs again after a cancelled run. */
UR_API void ur_context_cancel_clear(ur_context *context);

UR_API bool ur_context_cancelled(const ur_context *context);

/* UR_OK, or UR_ERROR_CANCELLED with error saying so once context was cancelled. */
UR_API ur_status ur_context_check(const ur_context *context, ur_error *error);

UR_API void ur_context_set_message_handler(ur_context *context, ur_message_handler handler,
                                           void *data);

/* The handler and data set (NULL for both when none), to wrap or restore it. */
UR_API void ur_context_message_handler(const ur_context *context, ur_message_handler *handler,
                                       void **data);

/* Passes a printf-style message that names no setting to context's handler, if it has one. */
UR_API void ur_context_message(const ur_context *context, ur_message_kind kind, const char *format,
                               ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The same for a message that names the settings listed in setting (as ur_error's). */
UR_API void ur_context_message_about(const ur_context *context, ur_message_kind kind,
                                     const char *setting, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/*
 * Where profiles are searched: a NULL-terminated list of directories,
 * borrowed (it must outlive the context's use), as ur_profile_find takes
 * it; NULL for none.  The library reads no environment and no working
 * directory of its own: the caller says where.
 */
UR_API void ur_context_set_profile_roots(ur_context *context, const char *const *roots);
UR_API const char *const *ur_context_profile_roots(const ur_context *context);

/*
 * For tests only: every write to a file the library writes in this context
 * fails with EIO once bytes bytes in all have gone to such files, as on a
 * full disk; a negative count lifts the limit.
 */
UR_API void ur_context_fail_writes_after(ur_context *context, long long bytes);

/*
 * Output sets: between ur_output_set_begin and ur_output_set_end every file
 * a writer completes in context (cut files, reports, pictures, curves)
 * stays a hidden temporary next to its name; ur_output_set_end renames
 * them all into place when commit is true, else removes them all, so the
 * files of a whole run appear together or not at all.  Sets nest: only the
 * outermost end renames, and a set that any end refused (commit false) is
 * removed.  ur_output_set_end fails, renaming nothing, when context was
 * cancelled.  With a NULL context there is no set: each file is renamed
 * into place as it is complete, and both calls do nothing.
 */
UR_API void ur_output_set_begin(ur_context *context);
UR_API ur_status ur_output_set_end(ur_context *context, bool commit, ur_error *error);

/* What the cutter does with a path.  Writers map each to a layer. */
typedef enum ur_op {
    UR_OP_CUT = 0,      /* through cut */
    UR_OP_SCORE,        /* fold line: partial power or dashed (a mountain fold) */
    UR_OP_SCORE_VALLEY, /* a valley fold, told apart from mountains by its own layer */
    UR_OP_KERF,         /* kerf-bending and relief cuts */
    UR_OP_ENGRAVE,      /* labels */
    UR_OP_MARK,         /* glue and overlap zones, alignment marks */
    UR_OP_COUNT
} ur_op;

/* "cut", "score", "kerf", "engrave", "mark". */
UR_API const char *ur_op_name(ur_op op);

/* Inverse of ur_op_name; returns UR_OP_COUNT for an unknown name. */
UR_API ur_op ur_op_from_name(const char *name);

/* Allocation helpers that fill error on failure and return NULL. */
UR_API void *ur_alloc_array(size_t count, size_t size, ur_error *error);

/*
 * Room for one more item in a growing array of count items: when count has
 * reached *capacity, doubles *capacity (from first) and reallocates items.
 * Returns the array (moved or not), or NULL with error set, items then
 * untouched.
 */
UR_API void *ur_array_grow(void *items, size_t *capacity, size_t count, size_t item_size,
                           size_t first, ur_error *error);

#ifdef __cplusplus
}
#endif

#endif
