/*
 * parts.c: several parts nested together, as a job file's: each part's
 * pieces made as its own job would make them, as many copies as asked,
 * then all nested at once, each kind of stock on sheets of its own, and
 * written once, with one report.
 */
#include "stages.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/*
 * The stock a job's parts go on, in the order first used, and each
 * piece's: a material and how it is nested (sheet size or roll, margin,
 * spacing, holes, remnants ...; a part's turns go with its pieces).  Parts
 * of one material with the job's nesting options share sheets; a part
 * with its own material, or its own options for the sheets, goes on
 * sheets of its own.  Remnants given for the whole job go to the first
 * stock only, so that no offcut is used twice.
 */
enum { MOST_MATERIALS = 32 };

typedef struct job_materials {
    ur_material list[MOST_MATERIALS];
    ur_job placing[MOST_MATERIALS]; /* the first part's options, for placing only */
    size_t count;
    size_t *of_piece; /* owned: each piece's index in list */
} job_materials;

static bool same_remnants(const ur_job *a, const ur_job *b)
{
    return a->remnant_count == b->remnant_count &&
           (a->remnant_count == 0 ||
            memcmp(a->remnants, b->remnants, a->remnant_count * sizeof *a->remnants) == 0);
}

/* Whether two parts' options nest them alike. */
static bool same_placing(const ur_job *a, const ur_job *b)
{
    return a->sheet_width == b->sheet_width && a->sheet_height == b->sheet_height &&
           a->roll_width == b->roll_width && a->margin == b->margin && a->spacing == b->spacing &&
           a->no_holes == b->no_holes && a->merge_lines == b->merge_lines &&
           a->max_sheets == b->max_sheets && same_remnants(a, b);
}

/* Notes that pieces first .. first + count - 1 are of material, placed as placing says. */
static ur_status note_material(job_materials *materials, const ur_material *material,
                               const ur_job *placing, size_t first, size_t count, ur_error *error)
{
    size_t k = 0;
    while (k < materials->count && (strcmp(materials->list[k].name, material->name) != 0 ||
                                    !same_placing(&materials->placing[k], placing)))
        k++;
    if (k == MOST_MATERIALS)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "more than %d kinds of stock (materials and sheet options) in one job",
                            MOST_MATERIALS);
    if (k == materials->count) {
        materials->list[k] = *material;
        materials->placing[k] = *placing;
        materials->placing[k].command = "job"; /* the part's words are gone by then */
        materials->count++;
    }
    size_t *grown = realloc(materials->of_piece, (first + count + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    materials->of_piece = grown;
    for (size_t p = first; p < first + count; p++)
        grown[p] = k;
    return UR_OK;
}

struct ur_job_parts {
    ur_machine machine;   /* the first part's */
    ur_material material; /* the first part's */
    ur_piece *pieces;     /* owned */
    size_t count;
    double surface_area;
    int last_seam; /* the highest seam number so far: later parts number theirs on */
    job_materials materials;
};

ur_job_parts *ur_job_parts_new(void)
{
    return calloc(1, sizeof(ur_job_parts));
}

void ur_job_parts_free(ur_job_parts *parts)
{
    if (!parts)
        return;
    for (size_t k = 0; k < parts->count; k++)
        ur_piece_free(&parts->pieces[k]);
    free(parts->pieces);
    free(parts->materials.of_piece);
    free(parts);
}

/* Appends quantity copies of the part's pieces, numbered #k when there are several. */
static ur_status add_copies(long quantity, const job_pieces_made *made, ur_piece **all,
                            size_t *count, ur_error *error)
{
    size_t more = made->count * (size_t)quantity;
    ur_piece *grown = realloc(*all, (*count + more + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    *all = grown;
    for (long copy = 0; copy < quantity; copy++)
        for (size_t k = 0; k < made->count; k++) {
            ur_piece *piece = &grown[*count];
            ur_status status = ur_piece_copy(&made->pieces[k], piece, error);
            if (status != UR_OK)
                return status;
            (*count)++;
            if (quantity == 1)
                continue; /* the names the part's pieces were made with */
            char name[160];
            c_snprintf(name, sizeof name, "%s#%ld", made->pieces[k].name, copy + 1);
            c_snprintf(piece->name, sizeof piece->name, "%.31s", name);
        }
    return UR_OK;
}

static void free_made(job_pieces_made *made)
{
    for (size_t k = 0; k < made->count; k++)
        ur_piece_free(&made->pieces[k]);
    free(made->pieces);
    memset(made, 0, sizeof *made);
}

ur_status ur_job_parts_add(ur_job_parts *parts, const ur_job *job, long quantity,
                           const ur_job_callbacks *callbacks, ur_error *error)
{
    if (ur_job_check(job, error) != UR_OK)
        return error->status;
    job_run run = job_run_make(job, callbacks, error);
    run.job.quiet = true;
    run.job.seam_offset = parts->last_seam; /* labels stay unique across the parts */
    job_pieces_made made;
    ur_status status = job_pieces(&run, &made);
    if (status != UR_OK)
        return status;
    if (made.last_seam > parts->last_seam)
        parts->last_seam = made.last_seam;
    if (parts->materials.count == 0) {
        parts->machine = made.machine;
        parts->material = made.material;
    }
    parts->surface_area += made.surface_area * (double)quantity;
    size_t first = parts->count;
    for (size_t k = 0; job->rotations > 0 && k < made.count; k++)
        made.pieces[k].rotations = (size_t)job->rotations; /* the part's turns, on shared sheets */
    status = add_copies(quantity, &made, &parts->pieces, &parts->count, error);
    if (status == UR_OK)
        status = note_material(&parts->materials, &made.material, job, first, parts->count - first,
                               error);
    free_made(&made);
    return status;
}

/*
 * Moves the pieces of each material together, the first used first, in
 * their order within one; starts[g] is where material g's begin.
 */
static ur_status group_by_material(ur_job_parts *all, job_materials *materials, size_t *starts,
                                   ur_error *error)
{
    ur_piece *sorted = malloc((all->count + 1) * sizeof *sorted);
    size_t *of_piece = malloc((all->count + 1) * sizeof *of_piece);
    if (!sorted || !of_piece) {
        free(sorted);
        free(of_piece);
        return ur_error_out_of_memory(error);
    }
    size_t n = 0;
    for (size_t g = 0; g < materials->count; g++) {
        starts[g] = n;
        for (size_t p = 0; p < all->count; p++)
            if (materials->of_piece[p] == g) {
                of_piece[n] = g;
                sorted[n++] = all->pieces[p];
            }
    }
    starts[materials->count] = n;
    free(all->pieces);
    free(materials->of_piece);
    all->pieces = sorted;
    materials->of_piece = of_piece;
    return UR_OK;
}

/*
 * Moves part's sheets and left-out pieces to the end of layout, their piece
 * indices offset, each sheet marked with the material's name.
 */
static ur_status append_layout(ur_layout *layout, ur_layout *part, size_t offset,
                               const char *material, ur_error *error)
{
    ur_sheet *sheets =
        realloc(layout->sheets, (layout->sheet_count + part->sheet_count + 1) * sizeof *sheets);
    if (sheets)
        layout->sheets = sheets;
    size_t *left = realloc(layout->not_placed,
                           (layout->not_placed_count + part->not_placed_count + 1) * sizeof *left);
    if (left)
        layout->not_placed = left;
    if (!sheets || !left)
        return ur_error_out_of_memory(error);
    for (size_t s = 0; s < part->sheet_count; s++) {
        ur_sheet *sheet = &sheets[layout->sheet_count++];
        *sheet = part->sheets[s];
        c_snprintf(sheet->material, sizeof sheet->material, "%s", material);
        for (size_t k = 0; k < sheet->placement_count; k++)
            sheet->placements[k].piece_index += offset;
    }
    part->sheet_count = 0; /* the sheets' placements are layout's now */
    for (size_t k = 0; k < part->not_placed_count; k++)
        left[layout->not_placed_count++] = part->not_placed[k] + offset;
    return UR_OK;
}

/* Nests the pieces of each kind of stock on sheets of their own. */
static ur_status place_by_material(const job_run *run, ur_job_parts *all, ur_layout *layout,
                                   ur_error *error)
{
    job_materials *materials = &all->materials;
    if (materials->count <= 1)
        return job_place_pieces(run, &all->machine, &all->material, all->pieces, all->count, layout,
                                error);
    size_t starts[MOST_MATERIALS + 1];
    ur_status status = group_by_material(all, materials, starts, error);
    for (size_t g = 0; status == UR_OK && g < materials->count; g++) {
        ur_layout part = {NULL, 0, NULL, 0};
        if (g > 0 && same_remnants(&materials->placing[g], &materials->placing[0]))
            materials->placing[g].remnant_count = 0; /* the job's offcuts: the first stock's */
        job_run placing = job_run_make(&materials->placing[g], &run->callbacks, error);
        placing.job.quiet = run->job.quiet;
        status = job_place_pieces(&placing, &all->machine, &materials->list[g],
                                  all->pieces + starts[g], starts[g + 1] - starts[g], &part, error);
        if (status == UR_OK)
            status = append_layout(layout, &part, starts[g], materials->list[g].name, error);
        ur_layout_free(&part);
    }
    return status;
}

/* The figures of the run: pieces, sheets and cutting. */
static void fill_result(const job_run *run, const ur_job_parts *parts, const ur_layout *layout,
                        ur_job_result *result)
{
    memset(result, 0, sizeof *result);
    result->method = "job";
    result->piece_count = parts->count;
    result->surface_area = parts->surface_area;
    for (size_t k = 0; k < parts->count; k++)
        result->flat_area += parts->pieces[k].measures.flat_area;
    result->sheet_count = layout->sheet_count;
    c_snprintf(result->machine, sizeof result->machine, "%s", parts->machine.name);
    c_snprintf(result->material, sizeof result->material, "%s", parts->material.name);
    job_describe_sheets(layout, result->sheets, sizeof result->sheets);
    c_snprintf(result->first_file, sizeof result->first_file, "%s", run->job.output_path);
    job_describe_cutting(run, &parts->machine, layout, parts->pieces, result->cutting,
                         sizeof result->cutting);
}

static ur_status place_and_write(job_run *run, ur_job_parts *parts, const char *surface,
                                 const char *name, ur_job_result *result)
{
    ur_layout layout = {NULL, 0, NULL, 0};
    ur_error *error = run->error;
    bool quiet = run->job.quiet;
    run->job.quiet = true; /* no progress while the parts are placed */
    ur_status status = place_by_material(run, parts, &layout, error);
    if (status == UR_OK)
        status = job_allowances_after_placing(run, &parts->machine, &layout, parts->pieces,
                                              parts->count, error);
    run->job.quiet = quiet;
    if (status == UR_OK) {
        job_allowance_warnings(run, parts->pieces, parts->count);
        job_not_placed_warning(run, &layout, parts->pieces);
        ur_report_context context = {.surface = surface,
                                     .method = name,
                                     .machine = &parts->machine,
                                     .material = &parts->material,
                                     .surface_area = parts->surface_area,
                                     .sheet_path = run->job.output_path};
        status = job_write_outputs(run, &parts->machine, &layout, parts->pieces, parts->count,
                                   &context, error);
    }
    if (status == UR_OK)
        fill_result(run, parts, &layout, result);
    ur_layout_free(&layout);
    return status;
}

ur_status ur_job_parts_run(ur_job_parts *parts, const ur_job *job, const char *surface,
                           const char *name, const ur_job_callbacks *callbacks,
                           ur_job_result *result, ur_error *error)
{
    job_run *run = malloc(sizeof *run);
    if (!run)
        return ur_error_out_of_memory(error);
    *run = job_run_make(job, callbacks, error);
    ur_job_result unused;
    ur_status status = place_and_write(run, parts, surface, name, result ? result : &unused);
    free(run);
    return status;
}
