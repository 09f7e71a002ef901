/*
 * cli.h: what the files of the unroll command share.  Only this module talks
 * to the user: messages go to stderr as "unroll: ...", and the exit status is
 * 0 (success), 1 (internal error) or 2 (bad usage or input).
 */
#ifndef UNROLL_CLI_H
#define UNROLL_CLI_H

#include <stdbool.h>

#include "unroll/develop.h"
#include "unroll/geom.h"

enum { EXIT_INTERNAL = 1, EXIT_USAGE = 2 };

/* Everything the command line can say about a surface job. */
typedef struct cli_job {
    const char *surface; /* the subcommand */
    /* surface parameters; NAN when not given */
    double radius, height, top_radius, pitch, turns, width, offset, cut;
    const char *curve_path;
    ur_vec3 direction, apex;
    bool has_direction, has_apex;
    /* output */
    const char *output_path;
    const char *report_path;
    const char *machine_name;
    const char *material_name;
    double sheet_width, sheet_height; /* 0 when not given */
    bool draw_rulings;
    bool quiet;
    ur_develop_options develop;
} cli_job;

/* Prints "unroll: message" on stderr. */
void cli_message(const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Parses the options of a surface subcommand; returns 0 or an exit status. */
int cli_parse_job(int argc, char **argv, cli_job *job);

/* Runs a parsed surface job end to end; returns the exit status. */
int cli_run_job(const cli_job *job);

/* unroll profiles [show NAME] */
int cli_profiles(int argc, char **argv);

/* Help texts. */
void cli_print_usage(void);
int cli_print_help(const char *subcommand);
bool cli_is_surface(const char *name);

#endif
