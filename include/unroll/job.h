/*
 * job.h: a whole job in one call: a surface (or mesh) developed or
 * flattened into pieces, its allowances added, nested on the machine's
 * sheets and written out, with a report.  This is what 'unroll SURFACE'
 * does; a program fills a ur_job (ur_job_init gives the defaults) and
 * calls ur_job_run.
 *
 * The library never prints: warnings and notes go to the message handler
 * of the job's context (ur_context_set_message_handler, unroll/base.h),
 * progress and the summary to the callbacks, the figures of the run into
 * a ur_job_result.  Messages name no command-line flag; the settings they
 * are about have the names of the job's settings (ur_job_option_name),
 * and an error about one says which in its setting field.
 */
#ifndef UNROLL_JOB_H
#define UNROLL_JOB_H

#include <stdbool.h>
#include <stddef.h>

#include "unroll/base.h"
#include "unroll/develop.h"
#include "unroll/geom.h"
#include "unroll/io.h"
#include "unroll/nest.h"
#include "unroll/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The most remnant sheets a job names. */
#define UR_JOB_MAX_REMNANTS 64

/* Allowances (ur_job.allowances): which the pieces get. */
enum {
    UR_ALLOW_TABS = 1u << 0, /* joints on seams (tabs or laps, per material) and labels */
    UR_ALLOW_KERFING = 1u << 1,
    UR_ALLOW_OVERLAPS = 1u << 2,
    UR_ALLOW_BENDING = 1u << 3,
    UR_ALLOW_BRIDGES = 1u << 4,
};

/* ur_job.bridges when the job does not say: as the allowances decide. */
#define UR_JOB_BRIDGES_UNSET (-2L)

/*
 * Everything a job says.  Strings are borrowed: they must outlive the
 * job's use (ur_job_free frees nothing the caller set).
 */
typedef struct ur_job {
    /*
     * The context the job runs in (unroll/base.h): its cancel flag stops
     * the run, its output set holds the files back until all are written,
     * its profile roots are where machine_name and material_name are
     * found, its message handler gets the warnings and notes.  NULL:
     * never cancelled, no output set, no roots (the profiles must then be
     * given loaded, machine and material), messages dropped.
     */
    ur_context *context;
    /* The word messages start with: the surface, or "job" for a job file. */
    const char *command;
    /* What to make: cylinder, cone, helicoid, tangent, strip, ruled, hypar or mesh. */
    const char *surface;
    /* surface parameters; NAN when not given */
    double radius, height, top_radius, pitch, turns, width, offset, cut;
    const char *curve_path;
    ur_vec3 direction, apex;
    bool has_direction, has_apex;
    /* two rails (strip, ruled) and the hypar's corners */
    const char *rail_paths[2];
    bool natural_pairing; /* a strip's rulings pair points naturally, not developably */
    bool strict;          /* a strip's domain must be the whole of rail 1 */
    const char *regression_path;
    /* the rails a strip reshapes (ur_rails_repair): 0, or UR_REPAIR_RAIL1, _RAIL2 or _BOTH */
    unsigned adjust_rails;
    ur_vec3 adjust_direction, adjust_plane; /* moves along a direction, or within planes */
    bool has_adjust_direction, has_adjust_plane;
    bool adjust_ends;  /* the rails' end points may move too */
    double adjust_max; /* the largest move allowed, mm; NAN: a quarter of the rails' distance */
    /* where the moved rail goes (rail 2 when both move), and rail 1 when both move; NULL */
    const char *adjusted_rail_path, *adjusted_rail1_path;
    ur_vec3 corners[4];
    bool has_corners;
    /* meshes, and non-developable surfaces flattened with strain */
    const char *mesh_path;
    const char *unit_name; /* NULL: mm */
    double scale;          /* NAN when not given */
    const char *seam_paths[16];
    size_t seam_count;
    int flatten;         /* ur_flatten_method, or -1 for the default */
    bool unfold;         /* along the mesh's edges, every face exact */
    bool strips;         /* the fewest strips within the strain allowed */
    bool fewer_pieces;   /* unfold: join pieces where a tab then finds no room */
    double hide_folds;   /* unfold: folds turning less (degrees) are not drawn; 0 */
    double max_strain;   /* NAN for the material's */
    size_t iterations;   /* 0: the default */
    size_t unfold_steps; /* unfold: the search's steps with the room level; 0: as the mesh asks */
    const char *strain_png_path; /* the strain preview; NULL for none */
    const char *assembly_path;   /* the assembly guide (.png or .pdf); NULL for none */
    ur_up_axis assembly_up;      /* the model's up; UR_UP_AUTO (default): the file's guess */
    /* analyze and compare (the command's other actions) */
    const char *png_path, *csv_path;
    /* output */
    const char *output_path; /* the cut file (or "-"), NAME-1.EXT ... for several sheets */
    const char *report_path; /* the JSON report; NULL for none */
    const char *machine_name;
    const char *material_name;
    /* Profiles already loaded, used in place of the names when not NULL. */
    const ur_machine *machine;
    const ur_material *material;
    double sheet_width, sheet_height; /* 0 when not given */
    bool draw_rulings;
    bool quiet; /* no progress, no notes, and of the warnings only pieces left off the sheets */
    int surface_layer; /* a ur_surface_layer, or -1 for the material's */
    ur_develop_options develop;
    /* fabrication allowances */
    unsigned allowances;  /* UR_ALLOW_* bits */
    bool allowances_auto; /* what the job needs (the default) */
    long bridges;         /* -1 auto count, 0 none, N; UR_JOB_BRIDGES_UNSET when not given */
    bool no_kerf_compensation;
    /* placement: -1 when not given (the machine's) */
    double margin, spacing;
    /* output formats (0: from output_path's extension), DXF version, preview dpi (0: 96) */
    unsigned formats;
    int dxf_version;
    double dpi;
    bool drawing_order; /* the files keep the drawing order, not the cutting order */
    long rotations;     /* turns tried; 0: 4, or 2 under a grain rule */
    bool no_holes;      /* no part inside another's hole */
    bool merge_lines;   /* touching parts, shared lines cut once */
    bool level;         /* turns start from the level one (surfaces), not as drawn (nest) */
    double roll_width;  /* nest on roll stock this wide; 0 for sheets */
    long max_sheets;    /* at most this many sheets; 0 for as many as needed */
    ur_remnant remnants[UR_JOB_MAX_REMNANTS]; /* offcuts filled before stock, in order */
    size_t remnant_count;
    double nest_time;         /* the search's budget in seconds; NAN for the default */
    size_t threads;           /* searches side by side on a roll; 0: per processor */
    int seam_offset;          /* seams are numbered from this on (a job file's later parts) */
    const char *piece_prefix; /* pieces are named PREFIX-P1, ... (a job file's part); NULL */
    unsigned long long seed;
    const char *job_name; /* the name the files record; NULL: the surface's */
} ur_job;

/*
 * The settings a job takes by name (a command line's options, a job
 * file's <option name="..." value="..."/>): the surface and its
 * parameters, how it becomes pieces, how they are nested, which files are
 * written, on which profiles.  A setting without a value is a flag.
 * ur_job_option_name gives the name of setting index ("radius", "format",
 * "nest-time", ...) and whether it takes a value; NULL past the last.
 */
UR_API size_t ur_job_option_count(void);
UR_API const char *ur_job_option_name(size_t index, bool *takes_value);

/* Which jobs a setting is for. */
typedef enum ur_job_option_kind {
    /* profiles, stock, nesting and files: every job that writes cut files (ur_job_run,
       ur_job_nest) */
    UR_JOB_OPTION_OUTPUT,
    /* the surface and how it becomes pieces (ur_job_run), on the surfaces ur_job_option_applies
       names */
    UR_JOB_OPTION_SURFACE,
    /* the pictures and tables of a surface's analysis (png, csv), which no run writes */
    UR_JOB_OPTION_ANALYSIS,
} ur_job_option_kind;

/* The kind of setting index (UR_JOB_OPTION_OUTPUT past the last). */
UR_API ur_job_option_kind ur_job_option_kind_at(size_t index);

/*
 * Whether the named setting applies to a surface ("cylinder", ..., "mesh"):
 * "pitch" to a helicoid, not to a cylinder.  False for an unknown name.
 */
UR_API bool ur_job_option_applies(const char *name, const char *surface);

/*
 * Sets the named setting (one of ur_job_option_name's) from its value (NULL
 * for a flag); the value is borrowed.  UR_ERROR_INPUT with a message
 * saying what is wrong with the value, not naming the setting (the
 * caller says where it came from): a value that is not one, a flag given
 * a value, a setting that does not apply to job->surface.
 */
UR_API ur_status ur_job_option_set(ur_job *job, const char *name, const char *value,
                                   ur_error *error);

/*
 * Whether the job's settings go together (max-strain with a flattening by
 * strips or charts, the adjust- settings with adjust, ...): UR_ERROR_INPUT
 * with a message starting with job->command otherwise.  ur_job_run and
 * ur_job_parts_add check it first.
 */
UR_API ur_status ur_job_check(const ur_job *job, ur_error *error);

/* The defaults: co2-60w, plywood-3mm, the allowances the job needs, every number unset. */
UR_API void ur_job_init(ur_job *job, const char *surface);

/* What a progress report is about. */
typedef enum ur_job_progress_kind {
    UR_JOB_NESTING,         /* the search's best so far: sheets, length, tries */
    UR_JOB_NESTING_DONE,    /* no more nesting reports */
    UR_JOB_PLACING,         /* the first layout: placed of count parts */
    UR_JOB_FLATTENING,      /* ARAP: iteration, energy */
    UR_JOB_UNFOLDING,       /* a mesh unfolded: phase, fraction done */
    UR_JOB_FLATTENING_DONE, /* no more flattening or unfolding reports */
    UR_JOB_JOINING,         /* labels, then tabs or laps, on the seams: phase, fraction done */
    UR_JOB_JOINING_DONE,    /* no more joining reports */
} ur_job_progress_kind;

typedef struct ur_job_progress {
    ur_job_progress_kind kind;
    size_t sheets;     /* NESTING: sheets of the best layout so far */
    double length;     /* NESTING: mm of the last sheet it uses */
    size_t tries;      /* NESTING */
    size_t placed;     /* PLACING */
    size_t count;      /* PLACING */
    size_t iteration;  /* FLATTENING */
    double energy;     /* FLATTENING */
    const char *phase; /* UNFOLDING, JOINING */
    double fraction;   /* UNFOLDING, JOINING */
} ur_job_progress;

/*
 * Where a run reports as it goes; any callback may be NULL.  progress is
 * called only when the job is not quiet, often, from the thread that runs
 * the job.  Warnings and notes are not here: they go to the message
 * handler of the job's context, as a sentence ("strip: warning: piece P2:
 * ...") of kind UR_MESSAGE_WARNING or UR_MESSAGE_NOTE.
 */
typedef struct ur_job_result ur_job_result;

typedef struct ur_job_callbacks {
    void *user;
    void (*progress)(void *user, const ur_job_progress *progress);
    /* Once the cut files are written (before the curves a strip job writes), unless quiet. */
    void (*summary)(void *user, const ur_job_result *result);
} ur_job_callbacks;

/* The figures of a finished run. */
struct ur_job_result {
    const char *method; /* how the nets were made: exact, triangle, quad, arap, lscm, strips,
                           unfold, charts (a static string) */
    size_t piece_count;
    double surface_area; /* mm2 of the 3D surface */
    double flat_area;    /* mm2 of the pieces laid flat */
    size_t sheet_count;
    char machine[64], material[64]; /* the profiles' names */
    char sheets[1024];     /* "2 sheets of 600 x 400 mm, the last leaving an offcut of ..." */
    char cutting[256];     /* ", utilisation 21.2 %, cut 3.54 m in about 4 min 6 s"; "" unknown */
    char first_file[4200]; /* the first cut file, "NAME-1.svg ... -3" for several */
    /* ur_job_nest: the fewest stock sheets any layout needs; 0 unknown */
    double sheets_lower_bound;
};

/*
 * Runs the job end to end: surface or mesh, nets, pieces with their
 * allowances, nesting, the cut files and the report, all written or none.
 * callbacks and result may be NULL.  UR_ERROR_INPUT for a job that cannot
 * be made as given (the message says why), UR_ERROR_INTERNAL otherwise.
 */
UR_API ur_status ur_job_run(const ur_job *job, const ur_job_callbacks *callbacks,
                            ur_job_result *result, ur_error *error);

/*
 * The ruled surface the job describes (any surface but a mesh), rail 2
 * adjusted when the job asks; free with ur_ruled_free.
 */
UR_API ur_status ur_job_surface(const ur_job *job, const ur_job_callbacks *callbacks,
                                ur_ruled *ruled, ur_error *error);

/*
 * The same, with a strip's checks and curves: a domain with gaps refused
 * when the job is strict, and the edge of regression and the adjusted
 * rail 2 written to the files the job names.
 */
UR_API ur_status ur_job_surface_with_curves(const ur_job *job, const ur_job_callbacks *callbacks,
                                            ur_ruled *ruled, ur_error *error);

/* ---- Several parts nested together (a job file) -------------------------- */

typedef struct ur_job_parts ur_job_parts;

/* An empty set of parts (NULL when out of memory); free with ur_job_parts_free. */
UR_API ur_job_parts *ur_job_parts_new(void);
UR_API void ur_job_parts_free(ur_job_parts *parts);

/*
 * Makes one part's pieces as job would (quietly; its seams numbered on
 * from the earlier parts', its pieces named after job->piece_prefix), and
 * adds quantity copies of them, named NAME#1, NAME#2 ... when several.
 * The part goes on the sheets of the earlier parts of its material and
 * nesting options, else on stock of its own.  The first part's machine
 * and material are the whole job's.
 */
UR_API ur_status ur_job_parts_add(ur_job_parts *parts, const ur_job *job, long quantity,
                                  const ur_job_callbacks *callbacks, ur_error *error);

/*
 * Nests every part's pieces, each kind of stock on sheets of its own, and
 * writes them once as job says (output, formats, report; the report names
 * surface and, as its method, name).  result: the pieces, sheets and
 * cutting of the whole job (method "job", first_file the output path).
 */
UR_API ur_status ur_job_parts_run(ur_job_parts *parts, const ur_job *job, const char *surface,
                                  const char *name, const ur_job_callbacks *callbacks,
                                  ur_job_result *result, ur_error *error);

/* ---- A job file ---------------------------------------------------------- */

/*
 * Runs a job file (read with ur_job_file_read, unroll-job(5)) as the
 * parts above: each part a job of its surface and file, the job's
 * machine, material and settings (<option>), then the part's own material
 * and settings (so that the part's win), the file's formats; its pieces
 * made and added as many times as its quantity, named after the part.
 * Then all are nested together and written once, with one report, into
 * output_directory (NULL: the file's), which is made when missing (not its
 * parents) and removed again when the run fails.  The jobs run in context
 * (as ur_job.context).  quiet: no notes and no progress.  A part's
 * warnings and failure name the job file and the part's line
 * ("lamp.xml:7: helicoid: ..."); a setting a part's job refuses,
 * UR_ERROR_INPUT with nothing written.  result (may be NULL): as
 * ur_job_parts_run's, first_file the cut files' path.
 */
UR_API ur_status ur_job_file_run(const ur_job_file *file, ur_context *context,
                                 const char *output_directory, bool quiet,
                                 const ur_job_callbacks *callbacks, ur_job_result *result,
                                 ur_error *error);

/* ---- Parts drawn elsewhere (unroll nest) --------------------------------- */

/*
 * Nests pieces already cut out (read with ur_parts_import) as job says,
 * on the machine and material it gives loaded (job->machine and
 * job->material, required): with split, a part that fits no sheet in any
 * turn and is longer than the room a sheet leaves is cut into parts that
 * fit, joined again with joints; then kerf compensation (unless
 * no_kerf_compensation), nesting, shared lines merged (merge_lines), and
 * the cut files and report.  *pieces may be reallocated (split parts);
 * layout receives the sheets for the caller's summary; both are the
 * caller's to free.
 */
UR_API ur_status ur_job_nest(const ur_job *job, const ur_job_callbacks *callbacks, bool split,
                             ur_piece **pieces, size_t *count, ur_layout *layout,
                             ur_job_result *result, ur_error *error);

#ifdef __cplusplus
}
#endif

#endif
