/*
 * run.c: one surface job end to end: profiles, surface, development,
 * pieces, sheets, SVG and report, with a short summary on stderr.
 */
#include "cli.h"
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

bool cli_directory_exists(const char *option, const char *path)
{
    char copy[4096];
    snprintf(copy, sizeof copy, "%s", path);
    const char *directory = dirname(copy);
    struct stat info;
    if (stat(directory, &info) != 0) {
        cli_message("%s '%s': directory '%s' does not exist", option, path, directory);
        return false;
    }
    if (!S_ISDIR(info.st_mode)) {
        cli_message("%s '%s': '%s' is not a directory", option, path, directory);
        return false;
    }
    return true;
}

int cli_exit_status(const ur_error *error)
{
    return error->status == UR_ERROR_INPUT ? EXIT_USAGE : EXIT_INTERNAL;
}

/*
 * The sheets to try, in order: --sheet alone when given; else the material's
 * stock sizes that fit the machine's bed; else the bed itself.
 */
static size_t sheet_choices(const cli_job *job, const ur_machine *machine,
                            const ur_material *material, ur_sheet_size *choices)
{
    if (job->sheet_width > 0) {
        choices[0].width = job->sheet_width;
        choices[0].height = job->sheet_height;
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
        if (!job->quiet)
            cli_message("note: no stock size of %s fits the %s bed; using sheets cut to the "
                        "bed, %g x %g mm",
                        material->name, machine->name, machine->bed_width, machine->bed_height);
    }
    return count;
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
} job_state;

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

static ur_status make_pieces(const cli_job *job, job_state *state, ur_error *error)
{
    state->pieces = ur_alloc_array(state->nets.count, sizeof *state->pieces, error);
    if (!state->pieces)
        return UR_ERROR_INTERNAL;
    ur_allowance_options options = {job->draw_rulings};
    for (size_t k = 0; k < state->nets.count; k++) {
        ur_status status =
            ur_piece_from_net(&state->nets.nets[k], &options, &state->pieces[k], error);
        if (status != UR_OK)
            return status;
        state->piece_count++;
        if (job->piece_prefix) { /* a job file's part: its name goes first, engraved too */
            char name[96];
            snprintf(name, sizeof name, "%s-%s", job->piece_prefix, state->nets.nets[k].name);
            snprintf(state->pieces[k].name, sizeof state->pieces[k].name, "%.31s", name);
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
        snprintf(all->nets[all->count].name, sizeof all->nets[0].name, "P%zu", all->count + 1);
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
    if (status == UR_OK)
        *use = moved;
    else
        ur_error_prefix(error, "--surface %s: ", ur_surface_layer_name(state->layer));
    return status;
}

cli_room cli_fit_room(const cli_job *job, const ur_machine *machine, const ur_material *material)
{
    cli_room room = {0, 0};
    if (job->roll_width > 0)
        return room;
    ur_sheet_size choices[UR_MAX_STOCK_SIZES + 1];
    cli_job quiet = *job; /* placing says it when no stock fits the bed */
    quiet.quiet = true;
    size_t count = sheet_choices(&quiet, machine, material, choices);
    double length = 0, width = 0;
    for (size_t k = 0; k < count; k++) {
        double a = fmax(choices[k].width, choices[k].height);
        double b = fmin(choices[k].width, choices[k].height);
        if (a * b > length * width)
            length = a, width = b;
    }
    const ur_material *m = material;
    double margin = job->margin >= 0 ? job->margin : machine->margin;
    double kerf = ur_effective_kerf(machine, m);
    double joint = (m->joint == UR_JOINT_LAP ? m->lap_width : m->tab_depth) + m->thickness;
    room.length = length - 2 * margin - 2 * joint - kerf;
    room.width = width - 2 * margin - kerf;
    if (!(room.length > 0) || !(room.width > 0))
        room.length = room.width = 0;
    return room;
}

/* A strip too long for the room is cut at rulings into pieces that fit. */
static void fit_room(const cli_job *job, const job_state *state, ur_develop_options *options)
{
    cli_room room = cli_fit_room(job, &state->machine, &state->material);
    options->fit_length = room.length;
    options->fit_width = room.width;
}

/* Each part of the domain of existence (the whole surface but for strips) on its own. */
static ur_status develop_parts(const cli_job *job, job_state *state, ur_error *error)
{
    size_t count = ur_ruled_domain(&state->ruled, NULL, 0);
    ur_interval *parts = ur_alloc_array(count, sizeof *parts, error);
    if (!parts)
        return UR_ERROR_INTERNAL;
    ur_ruled_domain(&state->ruled, parts, count);
    const ur_interval *gaps;
    bool whole = ur_ruled_gaps(&state->ruled, &gaps) == 0;
    ur_status status = UR_OK;
    ur_develop_options develop = job->develop;
    fit_room(job, state, &develop);
    state->surface_area = 0.0;
    state->moved = ur_alloc_array(count, sizeof *state->moved, error);
    if (!state->moved)
        status = UR_ERROR_INTERNAL;
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

static ur_status place(const cli_job *job, job_state *state, ur_error *error)
{
    ur_status status = make_pieces(job, state, error);
    if (status == UR_OK)
        status = cli_allowances_before_placing(job, &state->machine, &state->material, &state->nets,
                                               state->net_surfaces, &state->pieces,
                                               &state->piece_count, error);
    if (status != UR_OK)
        return status;
    return cli_place_pieces(job, &state->machine, &state->material, state->pieces,
                            state->piece_count, &state->layout, error);
}

/* On a terminal: the search's best so far, on one line rewritten in place. */
static void show_nest_progress(void *context, size_t sheets, double length, size_t tries)
{
    const cli_job *job = context;
    fprintf(stderr, "\runroll: %s: nesting: %zu sheet%s, %.1f mm of the last used (try %zu)   ",
            job->command, sheets, sheets == 1 ? "" : "s", length, tries);
    fflush(stderr);
}

/* Fewer parts than this are placed too fast for a progress line. */
#define MANY_PARTS 20

/* On a terminal: how many parts the first layout has placed, on the same line. */
static void show_placing(void *context, size_t placed, size_t count)
{
    const cli_job *job = context;
    fprintf(stderr, "\runroll: %s: nesting: placed %zu of %zu parts   ", job->command, placed,
            count);
    fflush(stderr);
}

/*
 * The nesting options of a job (the sheet size left to the caller): margin
 * and spacing, turns, holes, grain rule, remnants, the search and its
 * progress lines.
 */
static ur_nest_options nest_options_of(const cli_job *job, const ur_machine *machine,
                                       const ur_material *material, size_t count)
{
    /*
     * The grain runs along the sheet's length (its x axis); the material's
     * rule says whether the rulings, the bending axes, go along it or across.
     */
    size_t rotations = job->rotations > 0 ? (size_t)job->rotations : 4;
    return (ur_nest_options){
        .margin = job->margin >= 0 ? job->margin : machine->margin,
        .spacing = job->spacing >= 0 ? job->spacing
                   : job->merge_lines
                       ? 0.0 /* touching parts share their lines */
                       : fmax(machine->spacing, ur_effective_kerf(machine, material)),
        .rotations = rotations,
        .level = job->level,
        .holes = !job->no_holes,
        .max_sheets = job->max_sheets > 0 ? (size_t)job->max_sheets : 0,
        .remnants = job->remnants,
        .remnant_count = job->remnant_count,
        .grain = material->grain != UR_GRAIN_NONE,
        .grain_angle = material->grain == UR_GRAIN_ACROSS ? M_PI / 2 : 0.0,
        .grain_tolerance = material->grain_tolerance * M_PI / 180,
        .time_budget = isnan(job->nest_time) ? 1.0 : job->nest_time,
        .seed = job->seed,
        .threads = job->threads,
        .progress = job->quiet || !isatty(STDERR_FILENO) ? NULL : show_nest_progress,
        .placing = job->quiet || !isatty(STDERR_FILENO) || count < MANY_PARTS ? NULL : show_placing,
        .progress_context = (void *)job,
    };
}

ur_status cli_piece_fits_stock(const cli_job *job, const ur_machine *machine,
                               const ur_material *material, const ur_piece *piece, bool *fits,
                               ur_error *error)
{
    *fits = false;
    if (job->roll_width > 0)
        return UR_OK;
    ur_sheet_size choices[UR_MAX_STOCK_SIZES + 1];
    cli_job quiet = *job; /* placing says it when no stock fits the bed */
    quiet.quiet = true;
    size_t choice_count = sheet_choices(&quiet, machine, material, choices);
    ur_nest_options options = nest_options_of(&quiet, machine, material, 1);
    options.remnants = NULL;
    options.remnant_count = 0;
    options.max_sheets = 1;
    options.time_budget = 0;
    ur_piece cut;
    ur_status status = ur_piece_copy(piece, &cut, error);
    if (status == UR_OK && !job->no_kerf_compensation)
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

ur_status cli_place_pieces(const cli_job *job, const ur_machine *machine,
                           const ur_material *material, const ur_piece *pieces, size_t count,
                           ur_layout *layout, ur_error *error)
{
    /*
     * The first sheet every piece fits; otherwise the error of the largest
     * one tried, which names the sheet that came closest.
     */
    ur_sheet_size choices[UR_MAX_STOCK_SIZES + 1];
    size_t choice_count = sheet_choices(job, machine, material, choices);
    ur_nest_options options = nest_options_of(job, machine, material, count);
    ur_status status = UR_OK;
    if (job->roll_width > 0) { /* one strip of roll, as short as it goes */
        options.roll_width = job->roll_width;
        status = ur_layout_nest(pieces, count, &options, layout, error);
    }
    ur_error largest = {UR_OK, ""};
    double largest_area = 0;
    for (size_t k = 0; job->roll_width <= 0 && k < choice_count; k++) {
        options.sheet_width = choices[k].width;
        options.sheet_height = choices[k].height;
        if (count > 1 && options.spacing >= fmax(options.sheet_width, options.sheet_height)) {
            /* every part would take a sheet of its own: surely a mistake */
            status = ur_error_set(error, UR_ERROR_INPUT,
                                  "--spacing %g mm is not less than the %g x %g mm sheet: no two "
                                  "parts could share a sheet",
                                  options.spacing, options.sheet_width, options.sheet_height);
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
    if (options.progress)
        fputc('\n', stderr);
    return status;
}

/*
 * Lines closer than this (mm) are one line: far below any kerf, far above
 * the rounding in placing parts that touch.
 */
#define MERGE_TOLERANCE 0.01

ur_status cli_merge_lines(const cli_job *job, const ur_layout *layout, ur_piece *pieces,
                          size_t count, ur_error *error)
{
    if (!job->merge_lines)
        return UR_OK;
    double saved = 0;
    ur_status status = ur_layout_merge_lines(layout, pieces, count, MERGE_TOLERANCE, &saved, error);
    if (status == UR_OK && !job->quiet)
        cli_message("%s: merged lines: %.1f mm of shared cuts cut once", job->command, saved);
    return status;
}

static ur_status write_outputs(const cli_job *job, job_state *state, ur_error *error);

/*
 * The assembly guide: the nets' faces, named as the cut pieces are (a job
 * file's prefix included), under the model's name.
 */
static ur_status write_assembly(const cli_job *job, const job_state *state, ur_error *error)
{
    const char **names =
        ur_alloc_array(state->nets.count ? state->nets.count : 1, sizeof *names, error);
    if (!names)
        return UR_ERROR_INTERNAL;
    for (size_t k = 0; k < state->nets.count; k++)
        names[k] = k < state->piece_count ? state->pieces[k].name : NULL;
    const char *title = job->job_name ? job->job_name : job->surface;
    if (job->mesh_path && !job->job_name) {
        const char *slash = strrchr(job->mesh_path, '/');
        title = slash ? slash + 1 : job->mesh_path;
    }
    ur_assembly_options options = {.title = title, .names = names, .y_up = job->assembly_y_up};
    ur_status status = ur_assembly_write(&state->nets, job->assembly_path, &options, error);
    if (status != UR_OK)
        ur_error_prefix(error, "--assembly %s: ", job->assembly_path);
    free(names);
    return status;
}

/* The SVG and the report (write_outputs), then the strain previews and the assembly guide. */
static ur_status write_all(const cli_job *job, job_state *state, ur_error *error)
{
    ur_status status = write_outputs(job, state, error);
    if (status == UR_OK && job->strain_png_path) {
        status = ur_strain_png_write(job->strain_png_path, &state->layout, state->pieces,
                                     state->piece_count, 0, error);
        if (status != UR_OK)
            ur_error_prefix(error, "--strain-png %s: ", job->strain_png_path);
    }
    if (status == UR_OK && job->assembly_path)
        status = write_assembly(job, state, error);
    return status;
}

static ur_status write_outputs(const cli_job *job, job_state *state, ur_error *error)
{
    ur_report_context context = {
        .surface = job->surface,
        .method = state->method,
        .machine = &state->machine,
        .material = &state->material,
        .surface_area = state->surface_area,
        .sheet_path = job->output_path,
    };
    ur_report_layer layer = {ur_surface_layer_name(state->layer), "neutral", state->layer_offset,
                             state->k_factor, state->material.thickness};
    if (state->have_ruled)
        context.layer = &layer;
    context.gap_count = ur_ruled_gaps(&state->ruled, &context.gaps);
    return cli_write_outputs(job, &state->machine, &state->layout, state->pieces,
                             state->piece_count, &context, error);
}

static void print_summary(const cli_job *job, const job_state *state)
{
    double flat = 0.0;
    for (size_t k = 0; k < state->piece_count; k++)
        flat += state->pieces[k].measures.flat_area;
    char first_file[4096], used[1024];
    cli_describe_sheets(&state->layout, used, sizeof used);
    size_t sheets = state->layout.sheet_count;
    if (ur_sheet_file_name(job->output_path, 0, sheets, first_file, sizeof first_file, NULL))
        snprintf(first_file, sizeof first_file, "%s", job->output_path);
    if (sheets > 1) /* "net-1.svg ... net-3.svg" */
        snprintf(first_file + strlen(first_file), sizeof first_file - strlen(first_file),
                 " ... -%zu", sheets);
    char cutting[256];
    cli_describe_cutting(job, &state->machine, &state->layout, state->pieces, cutting,
                         sizeof cutting);
    fprintf(stderr,
            "unroll: %s (%s): %zu piece%s, surface %.2f mm2, net %.2f mm2 (coverage %.6f), "
            "%s (%s, %s)%s -> %s\n",
            job->surface, state->method, state->piece_count, state->piece_count == 1 ? "" : "s",
            state->surface_area, flat, flat / state->surface_area, used, state->material.name,
            state->machine.name, cutting, first_file);
}

/*
 * A surface that is not developable (a hypar, a general ruled surface) is
 * flattened with strain; the note says by how much it is not developable.
 */
static int flatten_if_needed(const cli_job *job, job_state *state, bool *flattened)
{
    *flattened = false;
    if (state->ruled.kind != UR_RULED_GENERAL)
        return 0;
    ur_analysis analysis;
    ur_error error;
    if (ur_analyze(&state->ruled, NULL, &analysis, &error) != UR_OK) {
        ur_analysis_free(&analysis);
        cli_message("%s: %s", job->command, error.message);
        return cli_exit_status(&error);
    }
    bool developable = analysis.developable;
    if (!developable && !job->quiet)
        cli_message("%s: not developable (the tangent plane turns by up to %.3g degrees along a "
                    "ruling, K down to %.3g 1/mm2): flattened with %s, with strain",
                    job->command, analysis.max_residual * 180 / M_PI, analysis.gaussian_min,
                    job->strips
                        ? "ARAP in strips"
                        : ur_flatten_method_name(job->flatten >= 0 ? (ur_flatten_method)job->flatten
                                                                   : UR_FLATTEN_ARAP));
    ur_analysis_free(&analysis);
    if (developable)
        return 0;
    *flattened = true;
    ur_ruled moved, *surface;
    if (neutral_layer(state, &moved, &surface, &error) != UR_OK) {
        cli_message("%s: %s", job->command, error.message);
        return cli_exit_status(&error);
    }
    cli_room room = cli_fit_room(job, &state->machine, &state->material);
    int code = cli_flatten_ruled(job, &room, &state->material, surface, &state->nets,
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
static bool will_be_grooved(const cli_job *job, job_state *state)
{
    if (state->machine.kind != UR_MACHINE_ROUTER ||
        !(cli_allowances_chosen(job, &state->machine) & CLI_ALLOW_BENDING))
        return false;
    double limit = cli_smallest_bend_radius(&state->material);
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
static void choose_layer(const cli_job *job, job_state *state)
{
    const ur_material *material = &state->material;
    state->layer =
        job->surface_layer >= 0 ? (ur_surface_layer)job->surface_layer : material->surface_layer;
    state->grooved = will_be_grooved(job, state);
    state->k_factor = state->grooved ? 1.0 - material->groove_skin / (2.0 * material->thickness)
                                     : material->k_factor;
    state->layer_offset =
        ur_surface_layer_offset(state->layer, material->thickness, state->k_factor);
}

/* A note when the layer developed is not the one the surface describes. */
static void print_layer(const cli_job *job, const job_state *state)
{
    const ur_material *material = &state->material;
    if (state->layer_offset != 0.0 && !job->quiet)
        cli_message("%s: the surface is the %s face of %g mm %s: developing the neutral layer "
                    "(K %g%s), %.4g mm %s the bend",
                    job->command, ur_surface_layer_name(state->layer), material->thickness,
                    material->name, state->k_factor,
                    state->grooved ? ", the middle of the skin the bending grooves leave" : "",
                    fabs(state->layer_offset),
                    state->layer_offset > 0 ? "toward the inside of" : "away from the inside of");
}

/* The nets: a mesh's pieces, or the surface developed (or flattened) part by part. */
static int make_nets(const cli_job *job, job_state *state, cli_adjusted_rail *adjusted,
                     ur_vec3 **edge, size_t *edge_count)
{
    state->method = job->strips ? "strips"
                    : job->unfold
                        ? "unfold"
                        : ur_flatten_method_name(job->flatten >= 0 ? (ur_flatten_method)job->flatten
                                                                   : UR_FLATTEN_ARAP);
    if (strcmp(job->surface, "mesh") == 0) {
        if (job->flatten < 0 && !job->strips && !job->unfold)
            state->method = "charts";
        cli_room room = cli_fit_room(job, &state->machine, &state->material);
        return cli_mesh_nets(job, &room, &state->material, &state->nets, &state->surface_area);
    }
    int code = cli_build_surface(job, &state->ruled, adjusted);
    if (code)
        return code;
    state->have_ruled = true;
    choose_layer(job, state);
    code = cli_check_domain(job, &state->ruled);
    if (!code && job->regression_path)
        code = cli_regression_points(job, &state->ruled, edge, edge_count);
    bool flattened = false;
    if (!code)
        code = flatten_if_needed(job, state, &flattened);
    ur_error error;
    if (!flattened)
        state->method = ur_method_name(job->develop.method);
    if (!code && !flattened && develop_parts(job, state, &error) != UR_OK) {
        cli_message("%s: %s", job->command, error.message);
        code = cli_exit_status(&error);
    }
    if (!code)
        print_layer(job, state);
    return code;
}

/* Pairs the seams of mesh nets (developments number their own). */
static int find_seams(const cli_job *job, job_state *state)
{
    ur_error error;
    int next_seam;
    /* A job file's later parts number their seams on from the earlier ones'. */
    for (size_t k = 0; job->seam_offset && k < state->nets.count; k++)
        for (size_t j = 0; j < state->nets.nets[k].seam_side_count; j++)
            state->nets.nets[k].seam_sides[j].seam += job->seam_offset;
    int first = ur_net_list_last_seam(&state->nets) + 1;
    if (first <= job->seam_offset)
        first = job->seam_offset + 1;
    if (ur_net_list_find_seams(&state->nets, first, &next_seam, &error) != UR_OK) {
        cli_message("%s: %s", job->command, error.message);
        return cli_exit_status(&error);
    }
    return 0;
}

/* Before the work: the assembly guide needs pieces with 3D faces (a mesh, or a flattening). */
static int check_assembly(const cli_job *job, const job_state *state)
{
    if (!job->assembly_path)
        return 0;
    for (size_t k = 0; k < state->nets.count; k++)
        if (state->nets.nets[k].face_count > 0)
            return 0;
    cli_message("%s: --assembly is for meshes (and surfaces flattened as meshes): a %s developed "
                "%s has no faces to draw",
                job->command, job->surface, state->method);
    return EXIT_USAGE;
}

int cli_run_job(const cli_job *job)
{
    if ((strcmp(job->output_path, "-") != 0 && !cli_directory_exists("-o", job->output_path)) ||
        (job->report_path && strcmp(job->report_path, "-") != 0 &&
         !cli_directory_exists("--report", job->report_path)) ||
        (job->regression_path && !cli_directory_exists("--regression", job->regression_path)) ||
        (job->adjusted_rail_path &&
         !cli_directory_exists("--adjusted-rail", job->adjusted_rail_path)) ||
        (job->adjusted_rail1_path &&
         !cli_directory_exists("--adjusted-rail1", job->adjusted_rail1_path)) ||
        (job->strain_png_path && strcmp(job->strain_png_path, "-") != 0 &&
         !cli_directory_exists("--strain-png", job->strain_png_path)) ||
        (job->assembly_path && !cli_directory_exists("--assembly", job->assembly_path)))
        return EXIT_USAGE;
    job_state state;
    memset(&state, 0, sizeof state);
    ur_error error;
    ur_status status = ur_machine_load(job->machine_name, &state.machine, &error);
    if (status == UR_OK)
        status = ur_material_load(job->material_name, &state.material, &error);
    if (status != UR_OK) {
        cli_message("%s", error.message);
        return cli_exit_status(&error);
    }
    cli_adjusted_rail adjusted = {{NULL, NULL}, {0, 0}, {0}};
    ur_vec3 *edge = NULL;
    size_t edge_count = 0;
    int code = make_nets(job, &state, &adjusted, &edge, &edge_count);
    if (!code)
        code = find_seams(job, &state);
    if (!code)
        code = check_assembly(job, &state);
    if (code) {
        free(edge);
        cli_adjusted_rail_free(&adjusted);
        state_free(&state);
        return code;
    }
    status = place(job, &state, &error);
    if (status == UR_OK)
        status = cli_allowances_after_placing(job, &state.machine, &state.layout, state.pieces,
                                              state.piece_count, &error);
    /* Every file of the run (cut files, report, pictures, curves) appears at the end, or none. */
    ur_output_set_begin();
    if (status == UR_OK) {
        cli_allowance_warnings(job, state.pieces, state.piece_count);
        cli_not_placed_warning(job, &state.layout, state.pieces);
        status = write_all(job, &state, &error);
    }
    if (status != UR_OK) {
        cli_message("%s: %s", job->command, error.message);
        code = cli_exit_status(&error);
    } else {
        if (!job->quiet)
            print_summary(job, &state);
        if (edge)
            code = cli_write_regression(job, edge, edge_count);
        if (!code)
            code = cli_write_adjusted_rail(job, &adjusted);
    }
    if (ur_output_set_end(code == 0, &error) != UR_OK && code == 0) {
        cli_message("%s: %s", job->command, error.message);
        code = cli_exit_status(&error);
    }
    free(edge);
    cli_adjusted_rail_free(&adjusted);
    state_free(&state);
    return code;
}

int cli_job_pieces(const cli_job *job, cli_pieces *out)
{
    memset(out, 0, sizeof *out);
    job_state state;
    memset(&state, 0, sizeof state);
    ur_error error;
    ur_status status = ur_machine_load(job->machine_name, &state.machine, &error);
    if (status == UR_OK)
        status = ur_material_load(job->material_name, &state.material, &error);
    if (status != UR_OK) {
        cli_message("%s: %s", job->command, error.message);
        return cli_exit_status(&error);
    }
    cli_adjusted_rail adjusted = {{NULL, NULL}, {0, 0}, {0}};
    ur_vec3 *edge = NULL;
    size_t edge_count = 0;
    int code = make_nets(job, &state, &adjusted, &edge, &edge_count);
    free(edge);
    cli_adjusted_rail_free(&adjusted);
    if (!code)
        code = find_seams(job, &state);
    if (!code) {
        status = make_pieces(job, &state, &error);
        if (status == UR_OK)
            status = cli_allowances_before_placing(job, &state.machine, &state.material,
                                                   &state.nets, state.net_surfaces, &state.pieces,
                                                   &state.piece_count, &error);
        if (status != UR_OK) {
            cli_message("%s: %s", job->command, error.message);
            code = cli_exit_status(&error);
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
