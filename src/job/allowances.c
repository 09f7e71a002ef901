/*
 * allowances.c: what the material needs besides the net's outline, as the
 * job asks for it (allowances, bridges, kerf compensation) and sized from
 * the material and machine profiles.  allow.h adds each allowance; this
 * file decides which, in what order, and warns of what could not be done.
 */
#include "stages.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

unsigned job_allowances_chosen(const job_run *run, const ur_machine *machine)
{
    unsigned set = run->job.allowances;
    if (run->job.allowances_auto) {
        set = UR_ALLOW_TABS | UR_ALLOW_KERFING | UR_ALLOW_OVERLAPS | UR_ALLOW_BENDING;
        if (machine->bridges_by_default)
            set |= UR_ALLOW_BRIDGES;
    }
    if (run->job.bridges == 0)
        set &= ~(unsigned)UR_ALLOW_BRIDGES;
    else if (run->job.bridges != UR_JOB_BRIDGES_UNSET)
        set |= UR_ALLOW_BRIDGES;
    return set;
}

bool job_makes_joints(const job_run *run)
{
    return run->job.allowances_auto || (run->job.allowances & UR_ALLOW_TABS);
}

static ur_status add_relief(unsigned set, const ur_material *material, const ur_net_list *nets,
                            ur_piece *pieces, size_t count, ur_error *error)
{
    ur_relief_limits limits = {
        .max_stretch = material->max_stretch,
        .max_compression = material->max_compression,
        .opening = material->kerfing_opening,
        .margin = material->kerfing_margin,
        .darts = material->overlap == UR_OVERLAP_DART,
        .kerfing = (set & UR_ALLOW_KERFING) != 0,
        .overlaps = (set & UR_ALLOW_OVERLAPS) != 0,
    };
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < count; k++)
        status = ur_piece_add_relief(&pieces[k], &nets->nets[k], &limits, error);
    return status;
}

double job_smallest_bend_radius(const ur_material *material)
{
    return material->grain == UR_GRAIN_ALONG ? material->bend_radius_with_grain
                                             : material->bend_radius_across_grain;
}

/*
 * The thinnest web to leave between grooves or slits: the profile's, or
 * three kerfs of the laser (in this material; 0.2 mm when it gives none),
 * the usual rule for what survives the cut and the bending.
 */
double job_min_web(const ur_machine *machine, const ur_material *material)
{
    if (material->min_web > 0)
        return material->min_web;
    if (machine->kind == UR_MACHINE_LASER)
        return 3 * ur_effective_kerf(machine, material);
    return 3 * (material->kerf_laser > 0 ? material->kerf_laser : 0.2);
}

static ur_status add_bending(const ur_machine *machine, const ur_material *material,
                             const ur_net_list *nets, ur_ruled *const *surfaces, ur_piece *pieces,
                             size_t count, ur_error *error)
{
    ur_bending_options options = {
        .min_radius = job_smallest_bend_radius(material),
        .router = machine->kind == UR_MACHINE_ROUTER,
        .groove_width = ur_effective_kerf(machine, material),
        .groove_depth = material->thickness - material->groove_skin,
        .hinge_cut_length = material->hinge_cut_length,
        .hinge_connection = material->hinge_connection,
        .hinge_distance = material->hinge_distance,
        .facet_angle = material->facet_angle,
        .min_web = job_min_web(machine, material),
        .kerf = machine->kind == UR_MACHINE_LASER ? ur_effective_kerf(machine, material) : 0.0,
        .thickness = material->thickness,
    };
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && k < count; k++)
        if (surfaces[k])
            status = ur_piece_add_bending_kerfs(&pieces[k], &nets->nets[k], surfaces[k], &options,
                                                error);
    return status;
}

static void report_joining(void *context, const char *phase, double fraction)
{
    ur_job_progress progress = {.kind = UR_JOB_JOINING, .phase = phase, .fraction = fraction};
    job_progress(context, &progress);
}

/* The joints the material asks for, as options with no labels and no splices. */
static ur_joint_options joints_of(const job_run *run, const ur_material *material)
{
    return (ur_joint_options){
        .lap = material->joint == UR_JOINT_LAP,
        .tab_depth = material->tab_depth,
        .tab_angle = material->tab_angle,
        .lap_width = material->lap_width,
        .thickness = material->thickness,
        .context = run->job.context,
    };
}

ur_status job_add_joints(const job_run *run, const ur_machine *machine, const ur_material *material,
                         const ur_net_list *nets, ur_piece *pieces, ur_splice_list *splices,
                         ur_error *error)
{
    ur_font *font = NULL;
    ur_status status = ur_font_open(NULL, &font, error);
    if (status != UR_OK)
        return status;
    ur_joint_options options = joints_of(run, material);
    options.font = font;
    options.label_height = material->label_height;
    options.name_pieces = true;
    options.splices = splices;
    options.lap_kerfs = machine != NULL;
    options.lap_kerf_margin =
        machine && machine->kind == UR_MACHINE_LASER ? material->hinge_connection : 0.0;
    options.progress = job_shows_progress(run) ? report_joining : NULL;
    options.progress_context = (void *)run;
    status = ur_pieces_add_joints(pieces, nets, &options, error);
    ur_job_progress done = {.kind = UR_JOB_JOINING_DONE};
    job_progress(run, &done);
    ur_font_close(font);
    return status;
}

/* The seam sides of every net gone, for the run to pair and number afresh. */
static void forget_seams(ur_net_list *nets)
{
    for (size_t k = 0; k < nets->count; k++) {
        free(nets->nets[k].seam_sides);
        nets->nets[k].seam_sides = NULL;
        nets->nets[k].seam_side_count = 0;
    }
}

/* The joint warnings of the pieces: each a stretch of a seam with no room for its joint. */
static size_t joint_warnings(const ur_piece *pieces, size_t count)
{
    size_t warnings = 0;
    for (size_t k = 0; k < count; k++)
        for (size_t r = 0; r < pieces[k].record_count; r++)
            warnings +=
                pieces[k].records[r].kind == UR_ALLOWANCE_JOINT && pieces[k].records[r].warning;
    return warnings;
}

ur_status job_count_untabbed(const job_run *run, const ur_material *material, ur_net_list *nets,
                             size_t *untabbed, ur_error *error)
{
    *untabbed = 0;
    int next_seam;
    ur_status status = ur_net_list_find_seams(nets, 1, &next_seam, error);
    ur_piece *pieces = NULL;
    if (status == UR_OK) {
        pieces = ur_alloc_array(nets->count ? nets->count : 1, sizeof *pieces, error);
        status = pieces ? UR_OK : UR_ERROR_MEMORY;
    }
    size_t made = 0;
    while (status == UR_OK && made < nets->count) {
        status = ur_piece_from_net(&nets->nets[made], NULL, &pieces[made], error);
        made += status == UR_OK;
    }
    ur_joint_options options = joints_of(run, material);
    if (status == UR_OK)
        status = ur_pieces_add_joints(pieces, nets, &options, error);
    if (status == UR_OK)
        *untabbed = joint_warnings(pieces, made);
    for (size_t k = 0; k < made; k++)
        ur_piece_free(&pieces[k]);
    free(pieces);
    forget_seams(nets);
    return status;
}

/*
 * No kerf line touches a fold or mark line of the joints: each keeps half
 * its own width (the bit, or the laser's kerf) and the minimum web from
 * them, and what is left shorter than the web goes.
 */
static ur_status keep_kerfs_off_joints(const ur_machine *machine, const ur_material *material,
                                       ur_piece *piece, size_t first, ur_error *error)
{
    double web = job_min_web(machine, material);
    double clearance = 0.5 * ur_effective_kerf(machine, material) + web;
    size_t trimmed = 0;
    return ur_piece_keep_kerfs_off_joints(piece, first, clearance, web, &trimmed, error);
}

/* The splice pieces the joints made go after the nets' pieces, to be nested with them. */
static ur_status append_splices(ur_splice_list *splices, ur_piece **pieces, size_t *count,
                                ur_error *error)
{
    if (splices->count == 0)
        return UR_OK;
    ur_piece *grown = realloc(*pieces, (*count + splices->count) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    *pieces = grown;
    memcpy(grown + *count, splices->pieces, splices->count * sizeof *grown);
    *count += splices->count;
    free(splices->pieces); /* the pieces' own arrays moved with them */
    splices->pieces = NULL;
    splices->count = 0;
    return UR_OK;
}

ur_status job_allowances_before_placing(const job_run *run, const ur_machine *machine,
                                        const ur_material *material, const ur_net_list *nets,
                                        ur_ruled *const *surfaces, ur_piece **pieces, size_t *count,
                                        ur_error *error)
{
    unsigned set = job_allowances_chosen(run, machine);
    ur_status status = UR_OK;
    if (set & (UR_ALLOW_KERFING | UR_ALLOW_OVERLAPS))
        status = add_relief(set, material, nets, *pieces, *count, error);
    if (status == UR_OK && surfaces && (set & UR_ALLOW_BENDING))
        status = add_bending(machine, material, nets, surfaces, *pieces, *count, error);
    if (status == UR_OK && (set & UR_ALLOW_TABS)) {
        ur_splice_list splices = {NULL, 0};
        size_t *first = ur_alloc_array(*count ? *count : 1, sizeof *first, error);
        for (size_t k = 0; first && k < *count; k++)
            first[k] = (*pieces)[k].path_count;
        /*
         * A mesh's seams are many and short: where its tabs miss, a splice
         * strip for each would be hundreds of pieces (a 100,000-face
         * sphere: 955), so they are said, to join by hand, as in papercraft.
         */
        bool mesh = strcmp(run->job.command, "mesh") == 0;
        status = first ? job_add_joints(run, machine, material, nets, *pieces,
                                        mesh ? NULL : &splices, error)
                       : UR_ERROR_MEMORY;
        for (size_t k = 0; status == UR_OK && k < *count; k++)
            status = keep_kerfs_off_joints(machine, material, &(*pieces)[k], first[k], error);
        free(first);
        if (status == UR_OK)
            status = append_splices(&splices, pieces, count, error);
        ur_splice_list_free(&splices);
    }
    double kerf = ur_effective_kerf(machine, material);
    for (size_t k = 0; status == UR_OK && !run->job.no_kerf_compensation && k < *count; k++)
        status = ur_piece_compensate_kerf(&(*pieces)[k], kerf, error);
    return status;
}

ur_status job_allowances_after_placing(const job_run *run, const ur_machine *machine,
                                       const ur_layout *layout, ur_piece *pieces, size_t count,
                                       ur_error *error)
{
    for (size_t s = 0; s < layout->sheet_count; s++)
        for (size_t p = 0; p < layout->sheets[s].placement_count; p++) {
            const ur_placement *placement = &layout->sheets[s].placements[p];
            if (placement->piece_index < count)
                ur_piece_turn_labels(&pieces[placement->piece_index],
                                     atan2(placement->transform.sine, placement->transform.cosine));
        }
    ur_status status = UR_OK;
    if (job_allowances_chosen(run, machine) & UR_ALLOW_BRIDGES) {
        size_t bridges = run->job.bridges > 0 ? (size_t)run->job.bridges : 0;
        bool router = machine->kind == UR_MACHINE_ROUTER;
        for (size_t k = 0; status == UR_OK && k < count; k++)
            status =
                ur_piece_add_bridges(&pieces[k], bridges, machine->bridge_width, router, error);
    }
    return status == UR_OK ? job_merge_lines(run, layout, pieces, count, error) : status;
}

/*
 * At most this many lines of allowance warnings; the rest are counted in
 * one line.  A mesh unfolded into a thousand small nets had 1,500 lines
 * (a glue tab or a label without room on most pieces), which buried the
 * summary and every other message.
 */
#define ALLOWANCE_WARNING_LINES 20

/* The first warning of a kind on a piece, and how many more of it there are. */
static const ur_allowance_record *first_warning(const ur_piece *piece, int kind, size_t *more)
{
    const ur_allowance_record *first = NULL;
    *more = 0;
    for (size_t r = 0; r < piece->record_count; r++) {
        const ur_allowance_record *record = &piece->records[r];
        if (!record->warning || record->kind != (ur_allowance_kind)kind)
            continue;
        if (first)
            (*more)++;
        else
            first = record;
    }
    return first;
}

/*
 * One line per piece and kind of allowance: the first warning's reason,
 * and how many more there are (all are in the report), so that a strongly
 * strained piece does not bury the summary; after ALLOWANCE_WARNING_LINES
 * lines, one that counts the rest.
 */
void job_allowance_warnings(const job_run *run, const ur_piece *pieces, size_t count)
{
    if (run->job.quiet)
        return;
    size_t lines = 0, unsaid = 0, unsaid_pieces = 0;
    for (size_t k = 0; k < count; k++) {
        bool piece_unsaid = false;
        for (int kind = 0; kind < UR_ALLOWANCE_KIND_COUNT; kind++) {
            size_t more;
            const ur_allowance_record *first = first_warning(&pieces[k], kind, &more);
            if (!first)
                continue;
            if (lines++ >= ALLOWANCE_WARNING_LINES) {
                unsaid += 1 + more;
                piece_unsaid = true;
            } else if (more) {
                job_warn(run, "%s: warning: piece %s: %s (and %zu more %s warning%s in the report)",
                         run->job.command, pieces[k].name, first->reason, more,
                         ur_allowance_kind_name((ur_allowance_kind)kind), more == 1 ? "" : "s");
            } else {
                job_warn(run, "%s: warning: piece %s: %s", run->job.command, pieces[k].name,
                         first->reason);
            }
        }
        unsaid_pieces += piece_unsaid;
    }
    if (unsaid && run->job.report_path)
        job_warn(run, "%s: warning: and %zu more allowance warning%s on %zu piece%s, in the report",
                 run->job.command, unsaid, unsaid == 1 ? "" : "s", unsaid_pieces,
                 unsaid_pieces == 1 ? "" : "s");
    else if (unsaid)
        job_warn_about(run, "report",
                       "%s: warning: and %zu more allowance warning%s on %zu piece%s: a report "
                       "lists them all",
                       run->job.command, unsaid, unsaid == 1 ? "" : "s", unsaid_pieces,
                       unsaid_pieces == 1 ? "" : "s");
}
