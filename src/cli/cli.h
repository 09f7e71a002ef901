/*
 * cli.h: what the files of the unroll command share.  Only this module talks
 * to the user: messages go to stderr as "unroll: ...", and the exit status is
 * 0 (success), 1 (internal error) or 2 (bad usage or input), or 128 + N when
 * signal N (SIGINT, SIGTERM) stopped the run.
 */
#ifndef UNROLL_CLI_H
#define UNROLL_CLI_H

#include <stdbool.h>

#include "unroll/allow.h"
#include "unroll/develop.h"
#include "unroll/geom.h"
#include "unroll/io.h"
#include "unroll/job.h"
#include "unroll/nest.h"
#include "unroll/out.h"

/* The exit statuses (unroll(1), EXIT STATUS); cli_exit_status maps ur_status to them. */
enum { EXIT_INTERNAL = 1, EXIT_USAGE = 2, EXIT_IO = 3, EXIT_MEMORY = 4 };

/* What is done with the surface. */
typedef enum cli_action { CLI_DEVELOP, CLI_ANALYZE, CLI_COMPARE } cli_action;

/*
 * Whether text is a whole number from least to most (decimal, nothing
 * after it), stored in *value when it is; no message.
 */
bool cli_whole_number(const char *text, long least, long most, long *value);

/* Prints "unroll: message" on stderr. */
void cli_message(const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/*
 * Parses the options of a surface subcommand (argv[0] is the surface) for
 * the given action; returns 0, -1 after printing help, or an exit status.
 */
int cli_parse_job(int argc, char **argv, cli_action action, const char *command, ur_job *job);

/* Runs a parsed surface job end to end (run.c); returns the exit status. */
int cli_run_job(const ur_job *job);

/* unroll analyze SURFACE ... and unroll compare SURFACE ... (analyze.c) */
int cli_analyze(const ur_job *job);
int cli_compare(const ur_job *job);

/* Refuses early, before any work, when a file could not be written there (then EXIT_IO). */
bool cli_directory_exists(const char *option, const char *path);

/* The exit status for a library error: the one place that maps ur_status to it. */
int cli_exit_status(const ur_error *error);

/*
 * flags.c: a library message with the settings it names (setting: their names,
 * space-separated, as ur_error's) written as the command's flags: each
 * name's first use as a word gets its dashes ("cone: top-radius must be
 * ..." becomes "cone: --top-radius must be ..."; a name listed twice, its
 * first two uses), and a name the message does not use goes in front,
 * after the command and "warning: " ("mesh: --sheet: piece P1 ...").
 * Written into text (size bytes, cut off if longer).
 */
void cli_with_flags(const char *message, const char *setting, char *text, size_t size);

/*
 * Prints a library error, "unroll: COMMAND: message" (command may be
 * NULL), its settings as flags (cli_with_flags).
 */
void cli_error(const char *command, const ur_error *error);

/*
 * Callbacks that print the library's progress on a terminal (one line
 * rewritten in place) and the summary of a surface job (run.c); its
 * warnings and notes go through the context's handler (signals.c).
 */
ur_job_callbacks cli_callbacks(const ur_job *job);

/*
 * The options of the commands that write cut files are the library's
 * settings (ur_job_option_name), in a getopt table with ids
 * CLI_SHARED_OPTION + their index (values.c).
 */
enum { CLI_SHARED_OPTION = 1000 };

/*
 * A getopt table: own's entries (up to its {NULL}), then the library's
 * settings (all of them for a surface job, else those of every job,
 * UR_JOB_OPTION_OUTPUT), then {NULL}, in at most `most` entries; returns
 * the entries before the {NULL}.
 */
struct option;
size_t cli_option_table(const struct option *own, bool surface_jobs, struct option *table,
                        size_t most);

/* Sets the named setting into job (ur_job_option_set); false after a message naming it. */
bool cli_set_option(ur_job *job, const char *name, const char *value);

/* Whether -o and --format say which files to write; false after a message (values.c). */
bool cli_check_output(const ur_job *job);

/* unroll job FILE.xml [-o DIR] (job.c) */
int cli_job_command(int argc, char **argv);

/* unroll nest FILE... -o OUT (nest.c) */
int cli_nest(int argc, char **argv);

/*
 * The run's library context (signals.c): opened once in main, before the
 * signal handlers, which cancel it, with a message handler that prints
 * the library's warnings and notes ("unroll: ..."); false when out of
 * memory.
 */
bool cli_context_open(void);
ur_context *cli_context(void);
void cli_context_close(void);

/* Installs the SIGINT and SIGTERM handlers (signals.c); false if the system refuses. */
bool cli_catch_signals(void);

/*
 * The exit status: code, or 128 + the signal's number when SIGINT or
 * SIGTERM arrived, said on stderr.
 */
int cli_signal_exit(int code);

/* unroll profiles [show NAME] */
int cli_profiles(int argc, char **argv);

/*
 * The profile roots, NULL-terminated, in search order (profiles.c): beside
 * the executable, $UNROLL_PROFILES, ./profiles.  Found on the first call.
 */
const char *const *cli_profile_roots(void);

/* Help texts. */
void cli_print_usage(void);
int cli_print_help(const char *subcommand);
bool cli_is_surface(const char *name);

#endif
