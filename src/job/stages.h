/*
 * stages.h: what the files of the job module share: one run's state that
 * every stage reports through (job_run), and the stages of a job from the
 * surface to the files (run.c, surfaces.c, domain.c, meshes.c,
 * unfolding.c, allowances.c, outputs.c, memory.c).
 */
#ifndef UNROLL_JOB_STAGES_H
#define UNROLL_JOB_STAGES_H

#include <stdbool.h>

#include "unroll/allow.h"
#include "unroll/develop.h"
#include "unroll/geom.h"
#include "unroll/io.h"
#include "unroll/job.h"
#include "unroll/nest.h"
#include "unroll/out.h"

#include "../base/c_locale.h"

/*
 * One run of a job: the job (a copy, so that a stage may run a variant of
 * it; its context takes the warnings), where its progress goes, and where a stage that fails
 * leaves its message (job_fail).
 */
typedef struct job_run {
    ur_job job;
    ur_job_callbacks callbacks; /* all NULL when the caller gave none */
    ur_error *error;
} job_run;

/* A run of job reporting to callbacks (may be NULL), failing into error. */
job_run job_run_make(const ur_job *job, const ur_job_callbacks *callbacks, ur_error *error);

/*
 * Hands a warning (UR_MESSAGE_WARNING), or a note of what was chosen or
 * done (UR_MESSAGE_NOTE), formatted, to the message handler of the job's
 * context.
 */
void job_warn(const job_run *run, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void job_note(const job_run *run, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* The same for a sentence that names settings, listed in setting as ur_error's. */
void job_warn_about(const job_run *run, const char *setting, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
void job_note_about(const job_run *run, const char *setting, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Sets the run's error to status and the formatted message; returns status. */
ur_status job_fail(const job_run *run, ur_status status, const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* The same, naming settings: setting lists them as ur_error's does ("max-strain"). */
ur_status job_fail_about(const job_run *run, ur_status status, const char *setting,
                         const char *format, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Fails with a stage's error, its message after the job's command, its setting kept. */
ur_status job_fail_from(const job_run *run, const ur_error *cause);

/* Hands a progress report to the progress callback, unless quiet. */
void job_progress(const job_run *run, const ur_job_progress *progress);

/* Whether progress reports are wanted: a progress callback, and not quiet. */
bool job_shows_progress(const job_run *run);

/* The UR_ALLOW_* bits the job gets: allowances_auto decides from the profiles. */
unsigned job_allowances_chosen(const job_run *run, const ur_machine *machine);

/* Whether the job puts joints on the seams (the same on every machine). */
bool job_makes_joints(const job_run *run);

/*
 * The smallest radius the material bends to: bending happens across the
 * rulings, and the profile says which of its two radii applies by its
 * grain rule (rulings across the grain bend with it).
 */
double job_smallest_bend_radius(const ur_material *material);

/* The thinnest web between grooves or slits: the profile's, else three laser kerfs. */
double job_min_web(const ur_machine *machine, const ur_material *material);

/*
 * The room a piece may take on the largest sheet the job may use (run.c):
 * inside the margin, less the kerf and a joint at each end of its length
 * (the joints go on the seams a split makes).  0 x 0 on roll stock, or
 * when the sheet leaves no room.
 */
typedef struct job_room {
    double length, width;
} job_room;

job_room job_fit_room(const job_run *run, const ur_machine *machine, const ur_material *material);

/*
 * Whether the piece, kerf compensated as it will be, fits an empty stock
 * sheet of one of the sizes the job may use in one of its allowed turns,
 * with nesting's margin, spacing and grain rule (run.c: nesting it alone
 * there).  False on roll stock: a roll is as long as a part needs.
 */
ur_status job_piece_fits_stock(const job_run *run, const ur_machine *machine,
                               const ur_material *material, const ur_piece *piece, bool *fits,
                               ur_error *error);

/*
 * The nets of a mesh's pieces, flattened with their strain (meshes.c);
 * UR_OK or a status with the run's error set.
 */
ur_status job_mesh_nets(const job_run *run, const job_room *room, const ur_material *material,
                        ur_net_list *nets, double *area);

/* How far a joint (tab or lap) stands out from its seam, with the stock's thickness (meshes.c). */
double job_joint_reach(const ur_material *material);

/* The end of a flattening's or an unfolding's progress (meshes.c). */
void job_end_flattening(const job_run *run);

/*
 * --flatten unfold: the mesh (cleaned, with the user's seams) unfolded
 * along its edges into nets that fit the room with their joints
 * (unfolding.c); UR_OK or a status with the run's error set.
 */
ur_status job_unfold_mesh(const job_run *run, const job_room *room, const ur_material *material,
                          const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                          ur_net_list *nets, double *area);

/* The nets of a non-developable ruled surface, flattened with strain (meshes.c). */
ur_status job_flatten_ruled(const job_run *run, const job_room *room, const ur_material *material,
                            ur_ruled *ruled, ur_net_list *nets, double *area);

/*
 * The allowances that go on the pieces before they are placed: relief
 * (kerfing, overlaps), bending kerfs, labels and joints, then kerf
 * compensation (allowances.c).  (*pieces)[k] was made from nets->nets[k],
 * developed from surfaces[k] (surfaces NULL, or an entry NULL, for meshes
 * and flattenings).  Splice pieces for seams no joint fits on are
 * appended to *pieces (reallocated), *count growing by as many.
 */
ur_status job_allowances_before_placing(const job_run *run, const ur_machine *machine,
                                        const ur_material *material, const ur_net_list *nets,
                                        ur_ruled *const *surfaces, ur_piece **pieces, size_t *count,
                                        ur_error *error);

/*
 * Shared lines of placed parts cut once (after bridges, which it may cut
 * through where they lie on a shared line); a note of the length saved
 * unless quiet.
 */
ur_status job_merge_lines(const job_run *run, const ur_layout *layout, ur_piece *pieces,
                          size_t count, ur_error *error);

/*
 * Joints and labels on the seams of the nets, as the material asks
 * (pieces[k] from nets[k]); splice pieces into splices where no joint fits
 * (NULL: a warning instead).  With a machine, laps carry the kerf lines of
 * the zone they lie on (kept a hinge's margin inside on a laser).  On a
 * terminal, its progress is shown (UR_JOB_JOINING).
 */
ur_status job_add_joints(const job_run *run, const ur_machine *machine, const ur_material *material,
                         const ur_net_list *nets, ur_piece *pieces, ur_splice_list *splices,
                         ur_error *error);

/*
 * How many stretches of the nets' seams the material's joints find no room
 * on, by putting them on (no labels) to pieces made for the count and
 * freed after it.  The nets' seams are paired for it and forgotten again.
 */
ur_status job_count_untabbed(const job_run *run, const ur_material *material, ur_net_list *nets,
                             size_t *untabbed, ur_error *error);

/* Once the pieces are placed: labels turned upright on the sheet, then holding bridges. */
ur_status job_allowances_after_placing(const job_run *run, const ur_machine *machine,
                                       const ur_layout *layout, ur_piece *pieces, size_t count,
                                       ur_error *error);

/*
 * Places the pieces on the first sheet size they all fit (the job's sheet,
 * else the material's stock that fits the machine's bed, else the bed),
 * margin and spacing from the job or the machine (run.c).
 */
ur_status job_place_pieces(const job_run *run, const ur_machine *machine,
                           const ur_material *material, const ur_piece *pieces, size_t count,
                           ur_layout *layout, ur_error *error);

/*
 * What the layout uses, for the summary: "2 sheets of 600 x 400 mm", ...
 * (outputs.c).
 */
void job_describe_sheets(const ur_layout *layout, char *text, size_t size);

/*
 * ", utilisation 21.2 %, cut 3.54 m in about 4 min 6 s" for a summary:
 * the pieces' share of the sheets' area, and the cut length and machine
 * time of the report (ur_sheet_cut_plan) summed over the sheets; empty
 * when the plan fails (the report says why).
 */
void job_describe_cutting(const job_run *run, const ur_machine *machine, const ur_layout *layout,
                          const ur_piece *pieces, char *text, size_t size);

/* A warning naming the pieces that found no room on the sheets allowed (outputs.c). */
void job_not_placed_warning(const job_run *run, const ur_layout *layout, const ur_piece *pieces);

/*
 * The fewest stock sheets any layout needs: ceil(sum of the pieces' flat
 * areas, less the room inside the remnants' margins, / the room inside a
 * stock sheet's margin); 0 when the stock sheets are of several sizes or
 * materials, or there are none.
 */
double job_sheets_lower_bound(const ur_piece *pieces, size_t count, const ur_layout *layout,
                              double margin);

/*
 * Writes the cut files in every format asked for, all or nothing, and the
 * report naming them all (outputs.c).  context is filled but for its
 * outputs, which this sets.
 */
ur_status job_write_outputs(const job_run *run, const ur_machine *machine, const ur_layout *layout,
                            const ur_piece *pieces, size_t count, ur_report_context *context,
                            ur_error *error);

/* The pieces of one surface job, ready to place (run.c, job_pieces). */
typedef struct job_pieces_made {
    ur_machine machine;
    ur_material material;
    ur_piece *pieces; /* owned: free each with ur_piece_free, then the array */
    size_t count;
    double surface_area;
    int last_seam; /* the highest seam number of the pieces, 0 without seams */
} job_pieces_made;

/*
 * Develops or flattens the job's surface into pieces with their
 * allowances (but for bridges, which come after placing), without placing
 * or writing them.
 */
ur_status job_pieces(const job_run *run, job_pieces_made *out);

/* The warnings the allowances recorded ("piece P2: ..."). */
void job_allowance_warnings(const job_run *run, const ur_piece *pieces, size_t count);

/*
 * UR_OK when `needed` bytes fit in what this process may still use (the
 * system's available memory and its ulimit -v); otherwise the run's error
 * names `what` (memory.c).
 */
ur_status job_check_memory(const job_run *run, const char *what, size_t needed);

#endif
