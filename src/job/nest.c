/*
 * nest.c: parts drawn elsewhere (read from SVG or DXF) nested on sheet
 * stock with the machine and material of a job: a part too long for any
 * sheet cut to fit, kerf compensation, nesting, shared lines merged, and
 * the same writers and report as a surface job.
 */
#include "stages.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Puts the split parts' pieces at the end of the list instead of the parts marked cut. */
static ur_status replace_split(ur_split_parts *split, const bool *cut, ur_piece **pieces,
                               size_t *count, ur_error *error)
{
    ur_piece *all = malloc((*count + split->nets.count + 1) * sizeof *all);
    if (!all)
        return ur_error_out_of_memory(error);
    size_t kept = 0;
    for (size_t k = 0; k < *count; k++)
        if (cut[k])
            ur_piece_free(&(*pieces)[k]);
        else
            all[kept++] = (*pieces)[k];
    for (size_t k = 0; k < split->nets.count; k++) {
        all[kept++] = split->pieces[k];
        memset(&split->pieces[k], 0, sizeof split->pieces[k]); /* all's now */
    }
    free(*pieces);
    *pieces = all;
    *count = kept;
    return UR_OK;
}

/*
 * A part that fits no empty stock sheet in any allowed turn, and is
 * longer than the room a sheet leaves (inside the margin, less the kerf
 * and a joint at each end), is cut into the fewest parts that fit the
 * room, each cut joined again with a joint and matching labels; --no-split
 * leaves it for nesting to refuse.  A part that fits some sheet whole
 * stays whole, however the room compares.
 */
static ur_status split_long_parts(const job_run *run, const ur_machine *machine,
                                  const ur_material *material, ur_piece **pieces, size_t *count,
                                  ur_error *error)
{
    job_room room = job_fit_room(run, machine, material);
    if (room.length <= 0)
        return UR_OK;
    ur_split_parts split = {{NULL, 0}, NULL};
    bool *cut = calloc(*count + 1, sizeof *cut);
    ur_status status = cut ? UR_OK : ur_error_out_of_memory(error);
    for (size_t k = 0; status == UR_OK && k < *count; k++) {
        const ur_path *outline = &(*pieces)[k].paths[0];
        double length, width;
        status = ur_outline_level_size(outline->points, outline->count, &length, &width, error);
        if (status != UR_OK || (length <= room.length && width <= room.width) ||
            width > room.width) /* too wide for cuts across it to help: nesting says so */
            continue;
        bool fits = false;
        status = job_piece_fits_stock(run, machine, material, &(*pieces)[k], &fits, error);
        if (status != UR_OK || fits)
            continue;
        size_t before = split.nets.count;
        status = ur_part_split(&(*pieces)[k], room.length, room.width, (double)k, &split, error);
        cut[k] = status == UR_OK;
        /* What its file said of its outline holds for theirs (their cuts across it are new). */
        for (size_t i = before; status == UR_OK && i < split.nets.count; i++)
            split.pieces[i].kerf_compensated = (*pieces)[k].kerf_compensated;
        if (status == UR_OK && !run->job.quiet)
            job_note_about(run, "no-split",
                           "%s: part %s (%.0f x %.0f mm) fits no sheet in any allowed turn: cut "
                           "into %zu to fit the %.0f x %.0f mm a sheet leaves a part with joints "
                           "(no-split refuses instead)",
                           run->job.command, (*pieces)[k].name, length, width,
                           split.nets.count - before, room.length, room.width);
    }
    int next_seam = 0;
    if (status == UR_OK && split.nets.count > 0)
        status = ur_net_list_find_seams(&split.nets, 1, &next_seam, error);
    if (status == UR_OK && split.nets.count > 0)
        status = job_add_joints(run, NULL, material, &split.nets, split.pieces, NULL, error);
    if (status == UR_OK && split.nets.count > 0)
        status = replace_split(&split, cut, pieces, count, error);
    ur_split_parts_free(&split);
    free(cut);
    return status;
}

/* Parts whose files said they were compensated already: how many, and for what kerf. */
typedef struct compensated_before {
    size_t same, less, more; /* than the kerf now */
    double first_less, first_more;
    const char *name_less, *name_more;
} compensated_before;

static void note_compensated_before(const job_run *run, const compensated_before *before,
                                    double kerf)
{
    if (run->job.quiet)
        return;
    if (before->same > 0)
        job_note(run,
                 "%s: %zu part%s already compensated for this kerf of %g mm (as %s say%s): "
                 "not compensated again",
                 run->job.command, before->same, before->same == 1 ? " was" : "s were", kerf,
                 before->same == 1 ? "its file" : "their files", before->same == 1 ? "s" : "");
    if (before->less > 0)
        job_note(run,
                 "%s: %zu part%s compensated for a smaller kerf (%s: %g mm): moved out by half "
                 "the difference to this kerf of %g mm",
                 run->job.command, before->less, before->less == 1 ? " was" : "s were",
                 before->name_less, before->first_less, kerf);
    if (before->more > 0)
        job_warn(run,
                 "%s: %zu part%s compensated for a larger kerf (%s: %g mm) than this machine "
                 "and material cut (%g mm): left as read, %g mm too large all round; nest the "
                 "drawing from before the compensation instead",
                 run->job.command, before->more, before->more == 1 ? " was" : "s were",
                 before->name_more, before->first_more, kerf, (before->first_more - kerf) / 2);
}

/*
 * Each part moved out by half the kerf, less what its file says it was
 * compensated for already (unroll's own cut files say so): a cut file
 * nested again keeps its size.  A part compensated for a larger kerf is
 * left with a warning: its paths were moved and are not moved back.
 */
static ur_status compensate(const job_run *run, const ur_machine *machine,
                            const ur_material *material, ur_piece *pieces, size_t count,
                            ur_error *error)
{
    double kerf = ur_effective_kerf(machine, material);
    compensated_before before = {0};
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && !run->job.no_kerf_compensation && k < count; k++) {
        double done = pieces[k].kerf_compensated, more = kerf - done;
        if (done > 0 && fabs(more) <= 1e-6) { /* the files keep 6 digits: a micron is none */
            before.same++;
            continue;
        }
        if (done > 0 && more < 0) {
            if (before.more++ == 0) {
                before.first_more = done;
                before.name_more = pieces[k].name;
            }
            continue;
        }
        if (done > 0 && before.less++ == 0) {
            before.first_less = done;
            before.name_less = pieces[k].name;
        }
        status = ur_piece_compensate_kerf(&pieces[k], more, error);
    }
    if (status == UR_OK)
        note_compensated_before(run, &before, kerf);
    return status;
}

static ur_status write_nest(const job_run *run, const ur_machine *machine,
                            const ur_material *material, const ur_piece *pieces, size_t count,
                            const ur_layout *layout, ur_error *error)
{
    ur_report_context context = {.surface = "nest",
                                 .method = "nest",
                                 .machine = machine,
                                 .material = material,
                                 .sheet_path = run->job.output_path};
    for (size_t k = 0; k < count; k++)
        context.surface_area += pieces[k].measures.flat_area;
    return job_write_outputs(run, machine, layout, pieces, count, &context, error);
}

/* The figures of the run, and the fewest stock sheets any layout needs. */
static void fill_result(const job_run *run, const ur_machine *machine, const ur_piece *pieces,
                        size_t count, const ur_layout *layout, ur_job_result *result)
{
    memset(result, 0, sizeof *result);
    result->method = "nest";
    result->piece_count = count;
    for (size_t k = 0; k < count; k++)
        result->flat_area += pieces[k].measures.flat_area;
    result->surface_area = result->flat_area;
    result->sheet_count = layout->sheet_count;
    job_describe_sheets(layout, result->sheets, sizeof result->sheets);
    job_describe_cutting(run, machine, layout, pieces, result->cutting, sizeof result->cutting);
    double margin = run->job.margin >= 0 ? run->job.margin : machine->margin;
    result->sheets_lower_bound = job_sheets_lower_bound(pieces, count, layout, margin);
    c_snprintf(result->first_file, sizeof result->first_file, "%s", run->job.output_path);
}

static ur_status nest_pieces(const job_run *run, bool split, ur_piece **pieces, size_t *count,
                             ur_layout *layout, ur_job_result *result, ur_error *error)
{
    const ur_machine *machine = run->job.machine;
    const ur_material *material = run->job.material;
    ur_status status = UR_OK;
    if (split)
        status = split_long_parts(run, machine, material, pieces, count, error);
    if (status == UR_OK)
        status = compensate(run, machine, material, *pieces, *count, error);
    if (status == UR_OK)
        status = job_place_pieces(run, machine, material, *pieces, *count, layout, error);
    if (status == UR_OK)
        status = job_merge_lines(run, layout, *pieces, *count, error);
    if (status == UR_OK) {
        job_allowance_warnings(run, *pieces, *count);
        job_not_placed_warning(run, layout, *pieces);
        status = write_nest(run, machine, material, *pieces, *count, layout, error);
    }
    if (status == UR_OK)
        fill_result(run, machine, *pieces, *count, layout, result);
    return status;
}

ur_status ur_job_nest(const ur_job *job, const ur_job_callbacks *callbacks, bool split,
                      ur_piece **pieces, size_t *count, ur_layout *layout, ur_job_result *result,
                      ur_error *error)
{
    if (!job->machine || !job->material)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "nesting needs the machine and material profiles loaded");
    job_run *run = malloc(sizeof *run);
    if (!run)
        return ur_error_out_of_memory(error);
    *run = job_run_make(job, callbacks, error);
    ur_job_result unused;
    ur_status status =
        nest_pieces(run, split, pieces, count, layout, result ? result : &unused, error);
    free(run);
    return status;
}
