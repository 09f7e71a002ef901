/*
 * run.c: one surface job end to end (ur_job_run): profiles, surface,
 * development, pieces, sheets, cut files and report, and the figures of
 * the run for the caller's summary.
 */
#include "stages.h"
#include "domain.h"
#include "surfaces.h"

#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>

#include "unroll/allow.h"
#include "unroll/analyze.h"
#include "unroll/flatten.h"
#include "unroll/io.h"
#include "unroll/nest.h"
#include "unroll/out.h"

/*
 * The sheets to try, in order: --sheet alone when given; else the material's
 * stock sizes that fit the machine's bed; else the bed itself.
 */
static size_t sheet_choices(const job_run *run, const ur_machine *machine,
                            const ur_material *material, ur_sheet_size *choices)
{
    if (run->job.sheet_width > 0) {
        choices[0].width = run->job.sheet_width;
        choices[0].height = run->job.sheet_height;
        return 1;
    }
    size_t count = 0;
    for (int k = 0; k < material->stock_count; k++) {
        ur_sheet_size size = material->stock[k];
        if ((size.width <= machine->bed_width && size.height <= machine->bed_height) ||
            (size.height <= machine->bed_width && size.width <= machine->bed_height))
            choices[count++] = size;
    }
    if (count == 0) {
        choices[count].width = machine->bed_width;
        choices[count++].height = machine->bed_height;
        if (!run->job.quiet)
            job_note(run,
                     "note: no stock size of %s fits the %s bed; using sheets cut to the "
                     "bed, %g x %g mm",
                     material->name, machine->name, machine->bed_width, machine->bed_height);
    }
    return count;
}

/*
 * The sheets to try, as sheet_choices, without its note: placing says it
 * when no stock fits the bed, and this is asked before placing.
 */
static size_t quiet_sheet_choices(const job_run *run, const ur_machine *machine,
                                  const ur_material *material, ur_sheet_size *choices)
{
    job_run quiet = *run;
    quiet.job.quiet = true;
    return sheet_choices(&quiet, machine, material, choices);
}

typedef struct job_state {
    ur_machine machine;
    ur_material material;
    ur_ruled ruled;
    bool have_ruled;
    ur_net_list nets;
    ur_piece *pieces;
    size_t piece_count;
    ur_layout layout;
    double surface_area;
    const char *method;     /* how the nets were made: exact, triangle, quad, arap, lscm, strips,
                               unfold, charts */
    ur_surface_layer layer; /* the layer the 3D surface is (--surface, else the material's) */
    double k_factor;        /* where the neutral layer is: the material's, or in a grooved skin */
    bool grooved;           /* bending grooves: the neutral layer is in the uncut skin */
    double layer_offset;    /* mm from it to the neutral layer, toward the inside of the bend */
    /*
     * The surface each net was developed from, parallel to nets (NULL for
     * a mesh or a flattening), for the allowances that ask it about a
     * ruling: the job's surface, or a part of it moved to the neutral
     * layer, kept in moved.
     */
    ur_ruled **net_surfaces;
    ur_ruled *moved;
    size_t moved_count;
    const ur_report_repair *repair; /* what --adjust did, for the report; NULL: nothing asked */
} job_state;

/* What the rails' repair did, as the report gives it. */
static void repair_for_report(const job_run *run, const ur_rail_repair_report *report,
                              ur_report_repair *repair)
{
    static const char *const rails[4] = {"", "rail1", "rail2", "both"};
    *repair = (ur_report_repair){.rails = rails[run->job.adjust_rails & UR_REPAIR_BOTH],
                                 .largest = report->largest,
                                 .mean = report->mean,
                                 .largest_rail = report->largest_rail,
                                 .largest_point = report->largest_point,
                                 .largest_position = report->largest_position,
                                 .largest_along = report->largest_along,
                                 .adjusted_rail = run->job.adjusted_rail_path,
                                 .adjusted_rail1 = run->job.adjusted_rail1_path};
}

static void state_free(job_state *state)
{
    for (size_t k = 0; k < state->piece_count; k++)
        ur_piece_free(&state->pieces[k]);
    free(state->pieces);
    ur_layout_free(&state->layout);
    ur_net_list_free(&state->nets);
    for (size_t k = 0; k < state->moved_count; k++)
        ur_ruled_free(&state->moved[k]);
    free(state->moved);
    free(state->net_surfaces);
    if (state->have_ruled)
        ur_ruled_free(&state->ruled);
}

/* Records that the nets from first on were developed from surface. */
static ur_status note_surface(job_state *state, size_t first, ur_ruled *surface, ur_error *error)
{
    ur_ruled **grown = realloc(state->net_surfaces, (state->nets.count + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    state->net_surfaces = grown;
    for (size_t k = first; k < state->nets.count; k++)
        grown[k] = surface;
    return UR_OK;
}

static ur_status make_pieces(const job_run *run, job_state *state, ur_error *error)
{
    state->pieces = ur_alloc_array(state->nets.count, sizeof *state->pieces, error);
    if (!state->pieces)
        return UR_ERROR_MEMORY;
    ur_allowance_options options = {run->job.draw_rulings};
    for (size_t k = 0; k < state->nets.count; k++) {
        ur_status status =
            ur_piece_from_net(&state->nets.nets[k], &options, &state->pieces[k], error);
        if (status != UR_OK)
            return status;
        state->piece_count++;
        if (run->job.piece_prefix) { /* a job file's part: its name goes first, engraved too */
            char name[96];
            c_snprintf(name, sizeof name, "%s-%s", run->job.piece_prefix, state->nets.nets[k].name);
            c_snprintf(state->pieces[k].name, sizeof state->pieces[k].name, "%.31s", name);
        }
    }
    return UR_OK;
}

/* Moves the nets of one part to the end of the job's list, numbering them on. */
static ur_status append_nets(ur_net_list *all, ur_net_list *part, ur_error *error)
{
    ur_net *grown = realloc(all->nets, (all->count + part->count) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    all->nets = grown;
    int seams_before = ur_net_list_last_seam(all);
    for (size_t k = 0; k < part->count; k++)
        for (size_t j = 0; j < part->nets[k].seam_side_count; j++)
            part->nets[k].seam_sides[j].seam += seams_before;
    for (size_t k = 0; k < part->count; k++) {
        all->nets[all->count] = part->nets[k];
        c_snprintf(all->nets[all->count].name, sizeof all->nets[0].name, "P%zu", all->count + 1);
        all->count++;
    }
    free(part->nets);
    part->nets = NULL;
    part->count = 0;
    return UR_OK;
}

/*
 * The surface to develop or flatten: the part in use moved to the neutral
 * layer (into *moved, which the caller frees when *use points to it), or
 * the surface itself when it is that layer already.
 */
static ur_status neutral_layer(job_state *state, ur_ruled *moved, ur_ruled **use, ur_error *error)
{
    *use = &state->ruled;
    if (state->layer_offset == 0.0)
        return UR_OK;
    ur_status status = ur_ruled_offset(&state->ruled, state->layer_offset, moved, error);
    if (status == UR_OK) {
        *use = moved;
    } else {
        ur_error_prefix(error, "surface %s: ", ur_surface_layer_name(state->layer));
        ur_error_set_setting(error, "surface");
    }
    return status;
}

job_room job_fit_room(const job_run *run, const ur_machine *machine, const ur_material *material)
{
    job_room room = {0, 0};
    if (run->job.roll_width > 0)
        return room;
    ur_sheet_size choices[UR_MAX_STOCK_SIZES + 1];
    size_t count = quiet_sheet_choices(run, machine, material, choices);
    double length = 0, width = 0;
    for (size_t k = 0; k < count; k++) {
        double a = fmax(choices[k].width, choices[k].height);
        double b = fmin(choices[k].width, choices[k].height);
        if (a * b > length * width)
            length = a, width = b;
    }
    const ur_material *m = material;
    double margin = run->job.margin >= 0 ? run->job.margin : machine->margin;
    double kerf = ur_effective_kerf(machine, m);
    double joint = (m->joint == UR_JOINT_LAP ? m->lap_width : m->tab_depth) + m->thickness;
    room.length = length - 2 * margin - 2 * joint - kerf;
    room.width = width - 2 * margin - kerf;
    if (!(room.length > 0) || !(room.width > 0))
        room.length = room.width = 0;
    return room;
}

/* A strip too long for the room is cut at rulings into pieces that fit. */
static void fit_room(const job_run *run, const job_state *state, ur_develop_options *options)
{
    job_room room = job_fit_room(run, &state->machine, &state->material);
    options->fit_length = room.length;
    options->fit_width = room.width;
}

/* Each part of the domain of existence (the whole surface but for strips) on its own. */
static ur_status develop_parts(const job_run *run, job_state *state, ur_error *error)
{
    size_t count = ur_ruled_domain(&state->ruled, NULL, 0);
    ur_interval *parts = ur_alloc_array(count, sizeof *parts, error);
    if (!parts)
        return UR_ERROR_MEMORY;
    ur_ruled_domain(&state->ruled, parts, count);
    const ur_interval *gaps;
    bool whole = ur_ruled_gaps(&state->ruled, &gaps) == 0;
    ur_status status = UR_OK;
    ur_develop_options develop = run->job.develop;
    fit_room(run, state, &develop);
    state->surface_area = 0.0;
    state->moved = ur_alloc_array(count, sizeof *state->moved, error);
    if (!state->moved)
        status = UR_ERROR_MEMORY;
    for (size_t k = 0; k < count && status == UR_OK; k++) {
        if (!whole)
            ur_ruled_restrict(&state->ruled, parts[k].u_start, parts[k].u_end);
        double area = 0.0;
        ur_net_list nets = {NULL, 0};
        ur_ruled *surface;
        size_t first = state->nets.count;
        status = neutral_layer(state, &state->moved[state->moved_count], &surface, error);
        if (surface != &state->ruled)
            state->moved_count++; /* kept: the allowances ask it about its rulings */
        if (status == UR_OK)
            status = ur_ruled_area(surface, ur_ruled_start(surface), ur_ruled_end(surface), &area,
                                   error);
        if (status == UR_OK)
            status = ur_develop(surface, &develop, &nets, error);
        if (status == UR_OK)
            status = append_nets(&state->nets, &nets, error);
        if (status == UR_OK)
            status = note_surface(state, first, surface, error);
        ur_net_list_free(&nets);
        state->surface_area += area;
    }
    free(parts);
    return status;
}

static ur_status place(const job_run *run, job_state *state, ur_error *error)
{
    ur_status status = make_pieces(run, state, error);
    if (status == UR_OK)
        status = job_allowances_before_placing(run, &state->machine, &state->material, &state->nets,
                                               state->net_surfaces, &state->pieces,
                                               &state->piece_count, error);
    if (status != UR_OK)
        return status;
    return job_place_pieces(run, &state->machine, &state->material, state->pieces,
                            state->piece_count, &state->layout, error);
}

/* The search's best so far, to the progress callback. */
static void report_nesting(void *context, size_t sheets, double length, size_t tries)
{
    ur_job_progress progress = {
        .kind = UR_JOB_NESTING, .sheets = sheets, .length = length, .tries = tries};
    job_progress(context, &progress);
}

/* Fewer parts than this are placed too fast for progress reports. */
#define MANY_PARTS 20

/* How many parts the first layout has placed, to the progress callback. */
static void report_placing(void *context, size_t placed, size_t count)
{
    ur_job_progress progress = {.kind = UR_JOB_PLACING, .placed = placed, .count = count};
    job_progress(context, &progress);
}

/*
 * The nesting options of a job (the sheet size left to the caller): margin
 * and spacing, turns, holes, grain rule, remnants, the search and its
 * progress lines.
 */
static ur_nest_options nest_options_of(const job_run *run, const ur_machine *machine,
                                       const ur_material *material, size_t count)
{
    /*
     * The grain runs along the sheet's length (its x axis); the material's
     * rule says whether the rulings, the bending axes, go along it or across.
     */
    size_t rotations = run->job.rotations > 0 ? (size_t)run->job.rotations : 4;
    return (ur_nest_options){
        .margin = run->job.margin >= 0 ? run->job.margin : machine->margin,
        .spacing = run->job.spacing >= 0 ? run->job.spacing
                   : run->job.merge_lines
                       ? 0.0 /* touching parts share their lines */
                       : fmax(machine->spacing, ur_effective_kerf(machine, material)),
        .rotations = rotations,
        .level = run->job.level,
        .holes = !run->job.no_holes,
        .max_sheets = run->job.max_sheets > 0 ? (size_t)run->job.max_sheets : 0,
        .remnants = run->job.remnants,
        .remnant_count = run->job.remnant_count,
        .grain = material->grain != UR_GRAIN_NONE,
        .grain_angle = material->grain == UR_GRAIN_ACROSS ? M_PI / 2 : 0.0,
        .grain_tolerance = material->grain_tolerance * M_PI / 180,
        .time_budget = isnan(run->job.nest_time) ? 1.0 : run->job.nest_time,
        .seed = run->job.seed,
        .threads = run->job.threads,
        .progress = job_shows_progress(run) ? report_nesting : NULL,
        .placing = job_shows_progress(run) && count >= MANY_PARTS ? report_placing : NULL,
        .progress_context = (void *)run,
        .context = run->job.context,
    };
}

ur_status job_piece_fits_stock(const job_run *run, const ur_machine *machine,
                               const ur_material *material, const ur_piece *piece, bool *fits,
                               ur_error *error)
{
    *fits = false;
    if (run->job.roll_width > 0)
        return UR_OK;
    ur_sheet_size choices[UR_MAX_STOCK_SIZES + 1];
    size_t choice_count = quiet_sheet_choices(run, machine, material, choices);
    job_run quiet = *run; /* a trial placing: no progress lines */
    quiet.job.quiet = true;
    ur_nest_options options = nest_options_of(&quiet, machine, material, 1);
    options.remnants = NULL;
    options.remnant_count = 0;
    options.max_sheets = 1;
    options.time_budget = 0;
    ur_piece cut;
    ur_status status = ur_piece_copy(piece, &cut, error);
    if (status == UR_OK && !run->job.no_kerf_compensation)
        status = ur_piece_compensate_kerf(&cut, ur_effective_kerf(machine, material), error);
    for (size_t k = 0; status == UR_OK && !*fits && k < choice_count; k++) {
        options.sheet_width = choices[k].width;
        options.sheet_height = choices[k].height;
        ur_layout layout;
        ur_error refused;
        ur_status placed = ur_layout_nest(&cut, 1, &options, &layout, &refused);
        if (placed == UR_OK)
            *fits = layout.not_placed_count == 0;
        else if (placed != UR_ERROR_INPUT) /* refused: it does not fit that size */
            status = placed, *error = refused;
        ur_layout_free(&layout);
    }
    ur_piece_free(&cut);
    return status;
}

ur_status job_place_pieces(const job_run *run, const ur_machine *machine,
                           const ur_material *material, const ur_piece *pieces, size_t count,
                           ur_layout *layout, ur_error *error)
{
    /*
     * The first sheet every piece fits; otherwise the error of the largest
     * one tried, which names the sheet that came closest.
     */
    ur_sheet_size choices[UR_MAX_STOCK_SIZES + 1];
    size_t choice_count = sheet_choices(run, machine, material, choices);
    ur_nest_options options = nest_options_of(run, machine, material, count);
    ur_status status = UR_OK;
    if (run->job.roll_width > 0) { /* one strip of roll, as short as it goes */
        options.roll_width = run->job.roll_width;
        status = ur_layout_nest(pieces, count, &options, layout, error);
    }
    ur_error largest = {UR_OK, "", ""};
    double largest_area = 0;
    for (size_t k = 0; run->job.roll_width <= 0 && k < choice_count; k++) {
        options.sheet_width = choices[k].width;
        options.sheet_height = choices[k].height;
        if (count > 1 && options.spacing >= fmax(options.sheet_width, options.sheet_height)) {
            /* every part would take a sheet of its own: surely a mistake */
            ur_error_set(error, UR_ERROR_INPUT,
                         "spacing %g mm is not less than the %g x %g mm sheet: no two parts could "
                         "share a sheet",
                         options.spacing, options.sheet_width, options.sheet_height);
            status = ur_error_set_setting(error, "spacing");
            continue;
        }
        status = ur_layout_nest(pieces, count, &options, layout, error);
        if (status != UR_ERROR_INPUT)
            break;
        if (options.sheet_width * options.sheet_height > largest_area) {
            largest_area = options.sheet_width * options.sheet_height;
            largest = *error;
        }
    }
    if (status == UR_ERROR_INPUT && largest.status == UR_ERROR_INPUT)
        *error = largest;
    if (options.progress) {
        ur_job_progress done = {.kind = UR_JOB_NESTING_DONE};
        job_progress(run, &done);
    }
    return status;
}

/*
 * Lines closer than this (mm) are one line: far below any kerf, far above
 * the rounding in placing parts that touch.
 */
#define MERGE_TOLERANCE 0.01

ur_status job_merge_lines(const job_run *run, const ur_layout *layout, ur_piece *pieces,
                          size_t count, ur_error *error)
{
    if (!run->job.merge_lines)
        return UR_OK;
    double saved = 0;
    ur_status status = ur_layout_merge_lines(layout, pieces, count, MERGE_TOLERANCE, &saved, error);
    if (status == UR_OK && !run->job.quiet)
        job_note(run, "%s: merged lines: %.1f mm of shared cuts cut once", run->job.command, saved);
    return status;
}

static ur_status write_outputs(const job_run *run, job_state *state, ur_error *error);

/*
 * Whether the guide draws the model +y up: as asked, or as the mesh file's
 * writer suggests (a note says so when that is +y, the less usual).
 */
static bool assembly_y_up(const job_run *run)
{
    if (run->job.assembly_up != UR_UP_AUTO || !run->job.mesh_path)
        return run->job.assembly_up == UR_UP_Y;
    bool y_up = ur_mesh_file_up_axis(run->job.mesh_path) == UR_UP_Y;
    if (y_up && !run->job.quiet)
        job_note_about(run, "assembly-up",
                       "%s: the assembly guide stands the model +y up, as %s was written "
                       "(assembly-up z stands it +z up)",
                       run->job.command, run->job.mesh_path);
    return y_up;
}

/*
 * The assembly guide: the nets' faces, named as the cut pieces are (a job
 * file's prefix included), under the model's name.
 */
static ur_status write_assembly(const job_run *run, const job_state *state, ur_error *error)
{
    const char **names =
        ur_alloc_array(state->nets.count ? state->nets.count : 1, sizeof *names, error);
    if (!names)
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < state->nets.count; k++)
        names[k] = k < state->piece_count ? state->pieces[k].name : NULL;
    const char *title = run->job.job_name ? run->job.job_name : run->job.surface;
    if (run->job.mesh_path && !run->job.job_name) {
        const char *slash = strrchr(run->job.mesh_path, '/');
        title = slash ? slash + 1 : run->job.mesh_path;
    }
    ur_assembly_options options = {
        .title = title, .names = names, .y_up = assembly_y_up(run), .context = run->job.context};
    ur_status status = ur_assembly_write(&state->nets, run->job.assembly_path, &options, error);
    if (status != UR_OK) {
        ur_error_prefix(error, "assembly %s: ", run->job.assembly_path);
        ur_error_set_setting(error, "assembly");
    }
    free(names);
    return status;
}

/* The SVG and the report (write_outputs), then the strain previews and the assembly guide. */
static ur_status write_all(const job_run *run, job_state *state, ur_error *error)
{
    ur_status status = write_outputs(run, state, error);
    if (status == UR_OK && run->job.strain_png_path) {
        status = ur_strain_png_write(run->job.strain_png_path, &state->layout, state->pieces,
                                     state->piece_count, 0, run->job.context, error);
        if (status != UR_OK) {
            ur_error_prefix(error, "strain-png %s: ", run->job.strain_png_path);
            ur_error_set_setting(error, "strain-png");
        }
    }
    if (status == UR_OK && run->job.assembly_path)
        status = write_assembly(run, state, error);
    return status;
}

static ur_status write_outputs(const job_run *run, job_state *state, ur_error *error)
{
    ur_report_context context = {
        .surface = run->job.surface,
        .method = state->method,
        .machine = &state->machine,
        .material = &state->material,
        .surface_area = state->surface_area,
        .sheet_path = run->job.output_path,
    };
    ur_report_layer layer = {ur_surface_layer_name(state->layer), "neutral", state->layer_offset,
                             state->k_factor, state->material.thickness};
    if (state->have_ruled)
        context.layer = &layer;
    context.gap_count = ur_ruled_gaps(&state->ruled, &context.gaps);
    context.repair = state->repair;
    return job_write_outputs(run, &state->machine, &state->layout, state->pieces,
                             state->piece_count, &context, error);
}

/* The figures of the finished run, for the caller's summary. */
static void fill_result(const job_run *run, const job_state *state, ur_job_result *result)
{
    memset(result, 0, sizeof *result);
    result->method = state->method;
    result->piece_count = state->piece_count;
    result->surface_area = state->surface_area;
    for (size_t k = 0; k < state->piece_count; k++)
        result->flat_area += state->pieces[k].measures.flat_area;
    result->sheet_count = state->layout.sheet_count;
    c_snprintf(result->machine, sizeof result->machine, "%s", state->machine.name);
    c_snprintf(result->material, sizeof result->material, "%s", state->material.name);
    job_describe_sheets(&state->layout, result->sheets, sizeof result->sheets);
    char *first_file = result->first_file;
    size_t size = sizeof result->first_file, sheets = state->layout.sheet_count;
    if (ur_sheet_file_name(run->job.output_path, 0, sheets, first_file, size, NULL))
        c_snprintf(first_file, size, "%s", run->job.output_path);
    if (sheets > 1) /* "net-1.svg ... net-3.svg" */
        c_snprintf(first_file + strlen(first_file), size - strlen(first_file), " ... -%zu", sheets);
    job_describe_cutting(run, &state->machine, &state->layout, state->pieces, result->cutting,
                         sizeof result->cutting);
}

/*
 * A surface that is not developable (a hypar, a general ruled surface) is
 * flattened with strain; the note says by how much it is not developable.
 */
static ur_status flatten_if_needed(const job_run *run, job_state *state, bool *flattened)
{
    *flattened = false;
    if (state->ruled.kind != UR_RULED_GENERAL)
        return UR_OK;
    ur_analysis analysis;
    ur_error error;
    if (ur_analyze(&state->ruled, NULL, &analysis, &error) != UR_OK) {
        ur_analysis_free(&analysis);
        return job_fail_from(run, &error);
    }
    bool developable = analysis.developable;
    if (!developable && !run->job.quiet)
        job_note(run,
                 "%s: not developable (the tangent plane turns by up to %.3g degrees along a "
                 "ruling, K down to %.3g 1/mm2): flattened with %s, with strain",
                 run->job.command, analysis.max_residual * 180 / M_PI, analysis.gaussian_min,
                 run->job.strips ? "ARAP in strips"
                                 : ur_flatten_method_name(run->job.flatten >= 0
                                                              ? (ur_flatten_method)run->job.flatten
                                                              : UR_FLATTEN_ARAP));
    ur_analysis_free(&analysis);
    if (developable)
        return UR_OK;
    *flattened = true;
    ur_ruled moved, *surface;
    if (neutral_layer(state, &moved, &surface, &error) != UR_OK) {
        return job_fail_from(run, &error);
    }
    job_room room = job_fit_room(run, &state->machine, &state->material);
    ur_status code = job_flatten_ruled(run, &room, &state->material, surface, &state->nets,
                                       &state->surface_area);
    if (surface == &moved)
        ur_ruled_free(&moved);
    return code;
}

/* Rulings sampled to tell whether the surface bends tighter than the material. */
enum { BEND_SAMPLES = 128 };

/*
 * Whether the router will cut bending grooves: they go on the inside of
 * the bend, where they close, and leave the skin on the outside to bend.
 */
static bool will_be_grooved(const job_run *run, job_state *state)
{
    if (state->machine.kind != UR_MACHINE_ROUTER ||
        !(job_allowances_chosen(run, &state->machine) & UR_ALLOW_BENDING))
        return false;
    double limit = job_smallest_bend_radius(&state->material);
    double start = ur_ruled_start(&state->ruled), end = ur_ruled_end(&state->ruled);
    for (size_t k = 0; k <= BEND_SAMPLES; k++) {
        double u = start + (end - start) * (double)k / BEND_SAMPLES;
        if (ur_analyze_bend_radius(&state->ruled, u, 5, NULL) < limit)
            return true;
    }
    return false;
}

/*
 * Which layer the surface is, and how far the neutral layer, which is
 * developed, lies from it: K t from the inner face, K the material's; on a
 * grooved part the middle of the uncut skin, K = 1 - skin / (2 t).
 */
static void choose_layer(const job_run *run, job_state *state)
{
    const ur_material *material = &state->material;
    state->layer = run->job.surface_layer >= 0 ? (ur_surface_layer)run->job.surface_layer
                                               : material->surface_layer;
    state->grooved = will_be_grooved(run, state);
    state->k_factor = state->grooved ? 1.0 - material->groove_skin / (2.0 * material->thickness)
                                     : material->k_factor;
    state->layer_offset =
        ur_surface_layer_offset(state->layer, material->thickness, state->k_factor);
}

/* A note when the layer developed is not the one the surface describes. */
static void print_layer(const job_run *run, const job_state *state)
{
    const ur_material *material = &state->material;
    if (state->layer_offset != 0.0 && !run->job.quiet)
        job_note(run,
                 "%s: the surface is the %s face of %g mm %s: developing the neutral layer "
                 "(K %g%s), %.4g mm %s the bend",
                 run->job.command, ur_surface_layer_name(state->layer), material->thickness,
                 material->name, state->k_factor,
                 state->grooved ? ", the middle of the skin the bending grooves leave" : "",
                 fabs(state->layer_offset),
                 state->layer_offset > 0 ? "toward the inside of" : "away from the inside of");
}

/* The nets: a mesh's pieces, or the surface developed (or flattened) part by part. */
static ur_status make_nets(const job_run *run, job_state *state, job_adjusted_rail *adjusted,
                           ur_vec3 **edge, size_t *edge_count)
{
    state->method =
        run->job.strips ? "strips"
        : run->job.unfold
            ? "unfold"
            : ur_flatten_method_name(run->job.flatten >= 0 ? (ur_flatten_method)run->job.flatten
                                                           : UR_FLATTEN_ARAP);
    if (strcmp(run->job.surface, "mesh") == 0) {
        if (run->job.flatten < 0 && !run->job.strips && !run->job.unfold)
            state->method = "charts";
        job_room room = job_fit_room(run, &state->machine, &state->material);
        return job_mesh_nets(run, &room, &state->material, &state->nets, &state->surface_area);
    }
    ur_status code = job_build_surface(run, &state->ruled, adjusted);
    if (code)
        return code;
    state->have_ruled = true;
    choose_layer(run, state);
    code = job_check_domain(run, &state->ruled);
    if (!code && run->job.regression_path)
        code = job_regression_points(run, &state->ruled, edge, edge_count);
    bool flattened = false;
    if (!code)
        code = flatten_if_needed(run, state, &flattened);
    ur_error error;
    if (!flattened)
        state->method = ur_method_name(run->job.develop.method);
    if (!code && !flattened && develop_parts(run, state, &error) != UR_OK) {
        code = job_fail_from(run, &error);
    }
    if (!code)
        print_layer(run, state);
    return code;
}

/* Pairs the seams of mesh nets (developments number their own). */
static ur_status find_seams(const job_run *run, job_state *state)
{
    ur_error error;
    int next_seam;
    /* A job file's later parts number their seams on from the earlier ones'. */
    for (size_t k = 0; run->job.seam_offset && k < state->nets.count; k++)
        for (size_t j = 0; j < state->nets.nets[k].seam_side_count; j++)
            state->nets.nets[k].seam_sides[j].seam += run->job.seam_offset;
    int first = ur_net_list_last_seam(&state->nets) + 1;
    if (first <= run->job.seam_offset)
        first = run->job.seam_offset + 1;
    if (ur_net_list_find_seams(&state->nets, first, &next_seam, &error) != UR_OK) {
        return job_fail_from(run, &error);
    }
    return UR_OK;
}

/* Before the work: the assembly guide needs pieces with 3D faces (a mesh, or a flattening). */
static ur_status check_assembly(const job_run *run, const job_state *state)
{
    if (!run->job.assembly_path)
        return UR_OK;
    for (size_t k = 0; k < state->nets.count; k++)
        if (state->nets.nets[k].face_count > 0)
            return UR_OK;
    return job_fail_about(
        run, UR_ERROR_INPUT, "assembly",
        "%s: assembly is for meshes (and surfaces flattened as meshes): a %s developed "
        "%s has no faces to draw",
        run->job.command, run->job.surface, state->method);
}

/* The job's machine and material: the profiles it gives, else those it names. */
static ur_status load_profiles(const job_run *run, job_state *state, ur_error *error)
{
    ur_status status = UR_OK;
    if (run->job.machine)
        state->machine = *run->job.machine;
    else
        status = ur_machine_load(ur_context_profile_roots(run->job.context), run->job.machine_name,
                                 &state->machine, error);
    if (status == UR_OK && run->job.material)
        state->material = *run->job.material;
    else if (status == UR_OK)
        status = ur_material_load(ur_context_profile_roots(run->job.context),
                                  run->job.material_name, &state->material, error);
    return status;
}

static ur_status run_job(const job_run *run, ur_job_result *result)
{
    job_state state;
    memset(&state, 0, sizeof state);
    ur_error error;
    ur_status status = load_profiles(run, &state, &error);
    if (status != UR_OK) {
        state_free(&state);
        return job_fail(run, error.status, "%s", error.message);
    }
    job_adjusted_rail adjusted = {.rails = {NULL, NULL}};
    ur_vec3 *edge = NULL;
    size_t edge_count = 0;
    ur_status code = make_nets(run, &state, &adjusted, &edge, &edge_count);
    ur_report_repair repair;
    if (!code && adjusted.repaired) {
        repair_for_report(run, &adjusted.report, &repair);
        state.repair = &repair;
    }
    if (!code)
        code = find_seams(run, &state);
    if (!code)
        code = check_assembly(run, &state);
    if (code) {
        free(edge);
        job_adjusted_rail_free(&adjusted);
        state_free(&state);
        return code;
    }
    status = place(run, &state, &error);
    if (status == UR_OK)
        status = job_allowances_after_placing(run, &state.machine, &state.layout, state.pieces,
                                              state.piece_count, &error);
    /* Every file of the run (cut files, report, pictures, curves) appears at the end, or none. */
    ur_output_set_begin(run->job.context);
    if (status == UR_OK) {
        job_allowance_warnings(run, state.pieces, state.piece_count);
        job_not_placed_warning(run, &state.layout, state.pieces);
        status = write_all(run, &state, &error);
    }
    if (status != UR_OK) {
        code = job_fail_from(run, &error);
    } else {
        fill_result(run, &state, result);
        if (!run->job.quiet && run->callbacks.summary)
            run->callbacks.summary(run->callbacks.user, result);
        if (edge)
            code = job_write_regression(run, edge, edge_count);
        if (!code)
            code = job_write_adjusted_rail(run, &adjusted);
    }
    if (ur_output_set_end(run->job.context, code == 0, &error) != UR_OK && code == 0) {
        code = job_fail_from(run, &error);
    }
    free(edge);
    job_adjusted_rail_free(&adjusted);
    state_free(&state);
    return code;
}

ur_status job_pieces(const job_run *run, job_pieces_made *out)
{
    memset(out, 0, sizeof *out);
    job_state state;
    memset(&state, 0, sizeof state);
    ur_error error;
    ur_status status = load_profiles(run, &state, &error);
    if (status != UR_OK) {
        state_free(&state);
        return job_fail_from(run, &error);
    }
    job_adjusted_rail adjusted = {.rails = {NULL, NULL}};
    ur_vec3 *edge = NULL;
    size_t edge_count = 0;
    ur_status code = make_nets(run, &state, &adjusted, &edge, &edge_count);
    free(edge);
    job_adjusted_rail_free(&adjusted);
    if (!code)
        code = find_seams(run, &state);
    if (!code) {
        status = make_pieces(run, &state, &error);
        if (status == UR_OK)
            status = job_allowances_before_placing(run, &state.machine, &state.material,
                                                   &state.nets, state.net_surfaces, &state.pieces,
                                                   &state.piece_count, &error);
        if (status != UR_OK) {
            code = job_fail_from(run, &error);
        }
    }
    if (!code) { /* the pieces leave the state for the caller */
        out->machine = state.machine;
        out->material = state.material;
        out->pieces = state.pieces;
        out->count = state.piece_count;
        out->surface_area = state.surface_area;
        out->last_seam = ur_net_list_last_seam(&state.nets);
        state.pieces = NULL;
        state.piece_count = 0;
    }
    state_free(&state);
    return code;
}

ur_status ur_job_run(const ur_job *job, const ur_job_callbacks *callbacks, ur_job_result *result,
                     ur_error *error)
{
    if (ur_job_check(job, error) != UR_OK)
        return error->status;
    job_run *run = malloc(sizeof *run); /* a job is large: its remnants */
    if (!run)
        return ur_error_out_of_memory(error);
    *run = job_run_make(job, callbacks, error);
    ur_job_result unused;
    ur_status status = run_job(run, result ? result : &unused);
    free(run);
    return status;
}
