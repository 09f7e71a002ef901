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
#include "unroll/io.h"

enum { EXIT_INTERNAL = 1, EXIT_USAGE = 2 };

/* What is done with the surface. */
typedef enum cli_action { CLI_DEVELOP, CLI_ANALYZE, CLI_COMPARE } cli_action;

/* Everything the command line can say about a surface job. */
typedef struct cli_job {
    cli_action action;
    const char *command; /* "strip", or "analyze" for 'unroll analyze strip ...' */
    const char *surface; /* the surface subcommand */
    /* surface parameters; NAN when not given */
    double radius, height, top_radius, pitch, turns, width, offset, cut;
    const char *curve_path;
    ur_vec3 direction, apex;
    bool has_direction, has_apex;
    /* two rails (strip, ruled) and the hypar's corners */
    const char *rail_paths[2];
    bool natural_pairing; /* strip --pairing natural */
    bool strict;
    const char *regression_path;
    bool adjust_rail2;
    ur_vec3 adjust_direction;
    bool has_adjust_direction;
    const char *adjusted_rail_path;
    ur_vec3 corners[4];
    bool has_corners;
    /* meshes, and non-developable surfaces flattened with strain */
    const char *mesh_path;
    const char *unit_name; /* NULL: mm */
    double scale;          /* NAN when not given */
    const char *seam_paths[16];
    size_t seam_count;
    int flatten;                 /* ur_flatten_method, or -1 for the default */
    bool unfold;                 /* --flatten unfold: along the mesh's edges, every face exact */
    bool strips;                 /* --flatten strips: the fewest strips within the strain allowed */
    double max_strain;           /* --max-strain, or NAN for the material's */
    size_t iterations;           /* 0: the default */
    const char *strain_png_path; /* --strain-png */
    /* analyze and compare */
    const char *png_path, *csv_path;
    /* output */
    const char *output_path;
    const char *report_path;
    const char *machine_name;
    const char *material_name;
    double sheet_width, sheet_height; /* 0 when not given */
    bool draw_rulings;
    bool quiet;
    int surface_layer; /* --surface: a ur_surface_layer, or -1 for the material's */
    ur_develop_options develop;
} cli_job;

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
int cli_parse_job(int argc, char **argv, cli_action action, const char *command, cli_job *job);

/* Runs a parsed surface job end to end; returns the exit status. */
int cli_run_job(const cli_job *job);

/* unroll analyze SURFACE ... and unroll compare SURFACE ... (analyze.c) */
int cli_analyze(const cli_job *job);
int cli_compare(const cli_job *job);

/* Refuses early, before any work, when a file could not be written there. */
bool cli_directory_exists(const char *option, const char *path);

/* The exit status for a library error. */
int cli_exit_status(const ur_error *error);

/*
 * unroll mesh FILE (meshes.c): the nets of a mesh's pieces, flattened with
 * their strain; returns 0 or an exit status after a message.
 */
int cli_mesh_nets(const cli_job *job, const ur_material *material, ur_net_list *nets, double *area);

/* The nets of a non-developable ruled surface, flattened with strain (meshes.c). */
int cli_flatten_ruled(const cli_job *job, const ur_material *material, ur_ruled *ruled,
                      ur_net_list *nets, double *area);

/* unroll profiles [show NAME] */
int cli_profiles(int argc, char **argv);

/* Help texts. */
void cli_print_usage(void);
int cli_print_help(const char *subcommand);
bool cli_is_surface(const char *name);

#endif
