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
#include "unroll/nest.h"
#include "unroll/out.h"

enum { EXIT_INTERNAL = 1, EXIT_USAGE = 2 };

/* What is done with the surface. */
typedef enum cli_action { CLI_DEVELOP, CLI_ANALYZE, CLI_COMPARE } cli_action;

/* Everything the command line can say about a surface job. */
/* The most --remnant options a command takes. */
#define CLI_MAX_REMNANTS 64

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
    unsigned adjust_rails; /* --adjust: 0, or UR_REPAIR_RAIL1, _RAIL2 or _BOTH */
    ur_vec3 adjust_direction, adjust_plane;
    bool has_adjust_direction, has_adjust_plane;
    bool adjust_ends;
    double adjust_max; /* NAN when not given */
    const char *adjusted_rail_path, *adjusted_rail1_path;
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
    const char *assembly_path;   /* --assembly FILE.png|pdf: the assembly guide */
    bool assembly_y_up;          /* --assembly-up y: the model's up is +y, not +z */
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
    /* fabrication allowances (allowances.c) */
    unsigned allowances;  /* CLI_ALLOW_* bits */
    bool allowances_auto; /* --allowances auto (the default): what the job needs */
    long bridges; /* --bridges: -1 auto count, 0 none, N; CLI_BRIDGES_UNSET when not given */
    bool no_kerf_compensation; /* --no-kerf-compensation */
    /* placement: -1 when not given (the machine's) */
    double margin, spacing;
    /* output formats (--format; 0: from -o's extension), --dxf-version, --dpi (0: 96) */
    unsigned formats;
    int dxf_version;
    double dpi;
    bool drawing_order; /* --order none */
    long rotations;     /* --rotations N; 0: 4, or 2 under a grain rule */
    bool no_holes;      /* --no-holes: no part inside another's hole */
    bool merge_lines;   /* --merge-lines: touching parts, shared lines cut once */
    bool level;         /* turns start from the level one (surfaces), not as drawn (nest) */
    double roll_width;  /* --roll W: nest on roll stock this wide; 0 for sheets */
    long max_sheets;    /* --sheets N: at most N sheets; 0 for as many as needed */
    ur_remnant remnants[CLI_MAX_REMNANTS]; /* --remnant WxH, in the order given */
    size_t remnant_count;
    double nest_time;         /* --nest-time S: the search's budget; NAN for the default */
    size_t threads;           /* --threads N: searches side by side on a roll; 0: per processor */
    int seam_offset;          /* seams are numbered from this on (a job file's later parts) */
    const char *piece_prefix; /* pieces are named PREFIX-P1, ... (a job file's part); NULL */
    unsigned long long seed;  /* --seed N */
    const char *job_name;     /* --job-name, or a job file's name; NULL: the surface's */
} cli_job;

enum {
    CLI_ALLOW_TABS = 1u << 0, /* joints on seams (tabs or laps, per material) and labels */
    CLI_ALLOW_KERFING = 1u << 1,
    CLI_ALLOW_OVERLAPS = 1u << 2,
    CLI_ALLOW_BENDING = 1u << 3,
    CLI_ALLOW_BRIDGES = 1u << 4,
};

#define CLI_BRIDGES_UNSET (-2L)

/* The CLI_ALLOW_* bits the job gets: --allowances auto decides from the profiles. */
unsigned cli_allowances_chosen(const cli_job *job, const ur_machine *machine);

/* Whether the job puts joints on the seams (the same on every machine). */
bool cli_makes_joints(const cli_job *job);

/*
 * The smallest radius the material bends to: bending happens across the
 * rulings, and the profile says which of its two radii applies by its
 * grain rule (rulings across the grain bend with it).
 */
double cli_smallest_bend_radius(const ur_material *material);

/* The thinnest web between grooves or slits: the profile's, else three laser kerfs. */
double cli_min_web(const ur_machine *machine, const ur_material *material);

/* --allowances auto|none|LIST and --bridges auto|N|none (allowances.c); false after a message. */
bool cli_parse_allowances(cli_job *job, const char *value);
bool cli_parse_bridges(cli_job *job, const char *value);

/*
 * Messages from now on say where the words came from, as "FILE:LINE"
 * ("unroll: FILE:LINE: message"); NULL or "" for the command line.
 */
void cli_message_context(const char *context);

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
/*
 * The room a piece may take on the largest sheet the job may use (run.c):
 * inside the margin, less the kerf and a joint at each end of its length
 * (the joints go on the seams a split makes).  0 x 0 on roll stock, or
 * when the sheet leaves no room.
 */
typedef struct cli_room {
    double length, width;
} cli_room;

cli_room cli_fit_room(const cli_job *job, const ur_machine *machine, const ur_material *material);

/*
 * Whether the piece, kerf compensated as it will be, fits an empty stock
 * sheet of one of the sizes the job may use in one of its allowed turns,
 * with nesting's margin, spacing and grain rule (run.c: nesting it alone
 * there).  False on roll stock: a roll is as long as a part needs.
 */
ur_status cli_piece_fits_stock(const cli_job *job, const ur_machine *machine,
                               const ur_material *material, const ur_piece *piece, bool *fits,
                               ur_error *error);

int cli_mesh_nets(const cli_job *job, const cli_room *room, const ur_material *material,
                  ur_net_list *nets, double *area);

/* The nets of a non-developable ruled surface, flattened with strain (meshes.c). */
int cli_flatten_ruled(const cli_job *job, const cli_room *room, const ur_material *material,
                      ur_ruled *ruled, ur_net_list *nets, double *area);

/*
 * The allowances that go on the pieces before they are placed: relief
 * (kerfing, overlaps), bending kerfs, labels and joints, then kerf
 * compensation (allowances.c).  (*pieces)[k] was made from nets->nets[k],
 * developed from surfaces[k] (surfaces NULL, or an entry NULL, for meshes
 * and flattenings).  Splice pieces for seams no joint fits on are
 * appended to *pieces (reallocated), *count growing by as many.
 */
ur_status cli_allowances_before_placing(const cli_job *job, const ur_machine *machine,
                                        const ur_material *material, const ur_net_list *nets,
                                        ur_ruled *const *surfaces, ur_piece **pieces, size_t *count,
                                        ur_error *error);

/*
 * Once the pieces are placed: labels turned to read upright on the sheet,
 * then holding bridges (allowances.c).
 */
/*
 * --merge-lines: the lines placed parts share are cut once (after bridges,
 * which it may cut through where they lie on a shared line); a note of
 * the length saved unless quiet.
 */
ur_status cli_merge_lines(const cli_job *job, const ur_layout *layout, ur_piece *pieces,
                          size_t count, ur_error *error);

/*
 * Joints and labels on the seams of the nets, as the material asks
 * (pieces[k] from nets[k]); splice pieces into splices where no joint fits
 * (NULL: a warning instead).  With a machine, laps carry the kerf lines of
 * the zone they lie on (kept a hinge's margin inside on a laser).
 */
ur_status cli_add_joints(const ur_machine *machine, const ur_material *material,
                         const ur_net_list *nets, ur_piece *pieces, ur_splice_list *splices,
                         ur_error *error);

ur_status cli_allowances_after_placing(const cli_job *job, const ur_machine *machine,
                                       const ur_layout *layout, ur_piece *pieces, size_t count,
                                       ur_error *error);

/*
 * Places the pieces on the first sheet size they all fit (--sheet, else the
 * material's stock that fits the machine's bed, else the bed), margin and
 * spacing from the job or the machine (run.c).
 */
ur_status cli_place_pieces(const cli_job *job, const ur_machine *machine,
                           const ur_material *material, const ur_piece *pieces, size_t count,
                           ur_layout *layout, ur_error *error);

/*
 * --format LIST, --dxf-version 12|2000, --dpi N (outputs.c): false after a
 * message naming the option.
 */
bool cli_parse_formats(cli_job *job, const char *value);
bool cli_parse_dxf_version(cli_job *job, const char *value);
bool cli_parse_dpi(cli_job *job, const char *value);
bool cli_parse_order(cli_job *job, const char *value);
bool cli_parse_rotations(cli_job *job, const char *value);
bool cli_parse_roll(cli_job *job, const char *value);
bool cli_parse_sheet_count(cli_job *job, const char *value);
bool cli_parse_remnant(cli_job *job, const char *value);
void cli_describe_sheets(const ur_layout *layout, char *text, size_t size);

/*
 * ", utilisation 21.2 %, cut 3.54 m in about 4 min 6 s" for a summary line:
 * the pieces' share of the sheets' area, and the cut length and machine
 * time of the report (ur_sheet_cut_plan) summed over the sheets; empty
 * when the plan fails (the report says why).
 */
void cli_describe_cutting(const cli_job *job, const ur_machine *machine, const ur_layout *layout,
                          const ur_piece *pieces, char *text, size_t size);
bool cli_parse_nest_time(cli_job *job, const char *value);
bool cli_parse_seed(cli_job *job, const char *value);
bool cli_parse_threads(cli_job *job, const char *value);
/* --job-name NAME: the name the files record (outputs.c); false after a message. */
bool cli_parse_job_name(cli_job *job, const char *value);

/* A warning naming the pieces that found no room on the --sheets allowed (outputs.c). */
void cli_not_placed_warning(const cli_job *job, const ur_layout *layout, const ur_piece *pieces);

/* Whether -o and --format say which files to write; false after a message (outputs.c). */
bool cli_check_output(const cli_job *job);

/*
 * Writes the cut files in every format asked for, all or nothing, and the
 * report naming them all (outputs.c).  context is filled but for its
 * outputs, which this sets.
 */
/*
 * The fewest stock sheets any layout needs: ceil(sum of the pieces' flat
 * areas, less the room inside the remnants' margins, / the room inside a
 * stock sheet's margin); 0 when the stock sheets are of several sizes or
 * materials, or there are none.
 */
double cli_sheets_lower_bound(const ur_piece *pieces, size_t count, const ur_layout *layout,
                              double margin);

ur_status cli_write_outputs(const cli_job *job, const ur_machine *machine, const ur_layout *layout,
                            const ur_piece *pieces, size_t count, ur_report_context *context,
                            ur_error *error);

/* The pieces of one surface job, ready to place (run.c, cli_job_pieces). */
typedef struct cli_pieces {
    ur_machine machine;
    ur_material material;
    ur_piece *pieces; /* owned: free each with ur_piece_free, then the array */
    size_t count;
    double surface_area;
    int last_seam; /* the highest seam number of the pieces, 0 without seams */
} cli_pieces;

/*
 * Develops or flattens the job's surface into pieces with their
 * allowances (but for bridges, which come after placing), without placing
 * or writing them; 0 or an exit status after a message.
 */
int cli_job_pieces(const cli_job *job, cli_pieces *out);

/* unroll job FILE.xml [-o DIR] (job.c) */
int cli_job_command(int argc, char **argv);

/* unroll nest FILE... -o OUT (nest.c) */
int cli_nest(int argc, char **argv);

/* The warnings the allowances recorded, on stderr ("piece P2: ..."). */
void cli_allowance_warnings(const cli_job *job, const ur_piece *pieces, size_t count);

/*
 * 0 when `needed` bytes fit in what this process may still use (the
 * system's available memory and its ulimit -v); otherwise a message naming
 * `what`, and EXIT_INTERNAL (memory.c).
 */
int cli_check_memory(const cli_job *job, const char *what, size_t needed);

/* Installs the SIGINT and SIGTERM handlers (signals.c); false if the system refuses. */
bool cli_catch_signals(void);

/*
 * The exit status: code, or 128 + the signal's number when SIGINT or
 * SIGTERM arrived, said on stderr.
 */
int cli_signal_exit(int code);

/* unroll profiles [show NAME] */
int cli_profiles(int argc, char **argv);

/* Help texts. */
void cli_print_usage(void);
int cli_print_help(const char *subcommand);
bool cli_is_surface(const char *name);

#endif
