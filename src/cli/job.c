/*
 * job.c: unroll job FILE.xml [-o DIR]: a whole build from one file
 * (unroll-job(5)).  Each part is turned into the command line it stands
 * for (its surface, the job's options, its own) and made into pieces as a
 * surface job would; the pieces of every part, as many of each as its
 * quantity, are then nested together and written once, with one report.
 * A job with one part of quantity 1 writes what the same command line
 * writes, byte for byte.
 */
#include "cli.h"
/* The stages a job file shares with a surface job; to become public API (see job.h). */
#include "../job/stages.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Room for the words of one part's command line, and for each word. */
enum { MOST_WORDS = 512, WORD_SIZE = 4400 };

typedef struct words {
    char *items[MOST_WORDS];
    size_t count;
    char text[MOST_WORDS][WORD_SIZE]; /* each word's own copy */
} words;

static bool add_word(words *w, const char *word)
{
    if (w->count == MOST_WORDS || strlen(word) >= WORD_SIZE)
        return false;
    memcpy(w->text[w->count], word, strlen(word) + 1);
    w->items[w->count] = w->text[w->count];
    w->count++;
    return true;
}

static bool add_options(words *w, const ur_job_file_option *options, size_t count)
{
    for (size_t k = 0; k < count; k++) {
        char flag[80];
        snprintf(flag, sizeof flag, "--%s", options[k].name);
        if (!add_word(w, flag) || (options[k].has_value && !add_word(w, options[k].value)))
            return false;
    }
    return true;
}

/* The output files' path: DIRECTORY/NAME with the first format's extension. */
static void output_path(const ur_job_file *job, char *path, size_t size)
{
    char first[16] = "svg";
    if (job->formats[0])
        sscanf(job->formats, "%15[a-z]", first);
    snprintf(path, size, "%s/%s.%s", job->output_directory, job->output_name, first);
}

/*
 * The command line a part stands for: surface, file, the job's profiles and
 * options, then the part's own material and options (the last word wins, so
 * a part's own override the job's), formats, -o.
 */
static bool part_words(const ur_job_file *job, const ur_job_file_part *part, const char *out,
                       words *w)
{
    bool ok = add_word(w, part->surface) && (!part->file[0] || add_word(w, part->file));
    if (ok && job->machine[0])
        ok = add_word(w, "--machine") && add_word(w, job->machine);
    if (ok && job->material[0])
        ok = add_word(w, "--material") && add_word(w, job->material);
    ok = ok && add_options(w, job->options, job->option_count);
    if (ok && part->material[0])
        ok = add_word(w, "--material") && add_word(w, part->material);
    ok = ok && add_options(w, part->options, part->option_count);
    if (ok && job->formats[0])
        ok = add_word(w, "--format") && add_word(w, job->formats);
    return ok && add_word(w, "-o") && add_word(w, out);
}

/* Appends quantity copies of the part's pieces, numbered #k when there are several. */
static ur_status add_copies(const ur_job_file_part *part, const job_pieces_made *made,
                            ur_piece **all, size_t *count, ur_error *error)
{
    size_t more = made->count * (size_t)part->quantity;
    ur_piece *grown = realloc(*all, (*count + more + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    *all = grown;
    for (long copy = 0; copy < part->quantity; copy++)
        for (size_t k = 0; k < made->count; k++) {
            ur_piece *piece = &grown[*count];
            ur_status status = ur_piece_copy(&made->pieces[k], piece, error);
            if (status != UR_OK)
                return status;
            (*count)++;
            if (part->quantity == 1)
                continue; /* the names the part's pieces were made with */
            char name[160];
            snprintf(name, sizeof name, "%s#%ld", made->pieces[k].name, copy + 1);
            snprintf(piece->name, sizeof piece->name, "%.31s", name);
        }
    return UR_OK;
}

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

static void free_made(job_pieces_made *made)
{
    for (size_t k = 0; k < made->count; k++)
        ur_piece_free(&made->pieces[k]);
    free(made->pieces);
    memset(made, 0, sizeof *made);
}

/*
 * Parses one part's command line into job (whose strings point into w, to
 * be kept as long as job is used) and makes its pieces.
 */
static int make_part(const ur_job_file *file, size_t index, const char *out, words *w,
                     char *command, size_t command_size, int seam_offset, ur_job *job,
                     job_pieces_made *made)
{
    const ur_job_file_part *part = &file->parts[index];
    if (!part_words(file, part, out, w)) {
        cli_message("%s:%d: the part has too many options", file->source, part->line);
        return EXIT_USAGE;
    }
    snprintf(command, command_size, "%s:%d", file->source, part->line);
    cli_message_context(command);
    snprintf(command, command_size, "%s", part->surface);
    int code = cli_parse_job((int)w->count, w->items, CLI_DEVELOP, command, job);
    if (code == -1)
        code = EXIT_USAGE;             /* --help in a job file */
    if (!code && job->assembly_path) { /* the parts share sheets, not one model */
        cli_message("%s: --assembly is not taken in a job file: draw a part's guide with its own "
                    "command line ('unroll %s ... --assembly FILE')",
                    command, part->surface);
        code = EXIT_USAGE;
    }
    if (!code) {
        job->quiet = true;
        job->seam_offset = seam_offset; /* labels stay unique across the parts */
        job->piece_prefix = part->name[0] ? part->name : NULL;
        ur_job_callbacks callbacks = cli_callbacks(job);
        ur_error error;
        job_run run = job_run_make(job, &callbacks, &error);
        if (job_pieces(&run, made) != UR_OK) {
            cli_message("%s", error.message);
            code = cli_exit_status(&error);
        }
    }
    cli_message_context(NULL);
    return code;
}

/* The job's pieces, every part's, as many as asked; *layout_job describes the sheets and files. */
static int all_pieces(const ur_job_file *file, const char *out, words *first_words,
                      ur_job *layout_job, char *command, size_t command_size, job_pieces_made *all,
                      job_materials *materials)
{
    words *w = calloc(1, sizeof *w);
    if (!w) {
        cli_message("job: out of memory");
        return EXIT_INTERNAL;
    }
    int code = 0, seams = 0;
    ur_error error;
    for (size_t p = 0; !code && p < file->part_count; p++) {
        char part_command[1200];
        ur_job job;
        job_pieces_made made;
        words *use = p == 0 ? first_words : w;
        memset(use, 0, sizeof *use);
        code = make_part(file, p, out, use, p == 0 ? command : part_command,
                         p == 0 ? command_size : sizeof part_command, seams, &job, &made);
        if (code)
            break;
        if (made.last_seam > seams)
            seams = made.last_seam;
        if (p == 0) {
            *layout_job = job;
            all->machine = made.machine;
            all->material = made.material;
        }
        all->surface_area += made.surface_area * (double)file->parts[p].quantity;
        size_t first = all->count;
        for (size_t k = 0; job.rotations > 0 && k < made.count; k++)
            made.pieces[k].rotations =
                (size_t)job.rotations; /* the part's turns, on shared sheets */
        if (add_copies(&file->parts[p], &made, &all->pieces, &all->count, &error) != UR_OK ||
            note_material(materials, &made.material, &job, first, all->count - first, &error) !=
                UR_OK) {
            cli_message("%s: %s", file->source, error.message);
            code = cli_exit_status(&error);
        }
        free_made(&made);
    }
    free(w);
    return code;
}

/*
 * Moves the pieces of each material together, the first used first, in
 * their order within one; starts[g] is where material g's begin.
 */
static ur_status group_by_material(job_pieces_made *all, job_materials *materials, size_t *starts,
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
        snprintf(sheet->material, sizeof sheet->material, "%s", material);
        for (size_t k = 0; k < sheet->placement_count; k++)
            sheet->placements[k].piece_index += offset;
    }
    part->sheet_count = 0; /* the sheets' placements are layout's now */
    for (size_t k = 0; k < part->not_placed_count; k++)
        left[layout->not_placed_count++] = part->not_placed[k] + offset;
    return UR_OK;
}

/* Nests the pieces of each kind of stock on sheets of their own. */
static ur_status place_by_material(const ur_job *job, job_pieces_made *all,
                                   job_materials *materials, ur_layout *layout, ur_error *error)
{
    ur_job_callbacks callbacks = cli_callbacks(job);
    job_run run = job_run_make(job, &callbacks, error);
    if (materials->count <= 1)
        return job_place_pieces(&run, &all->machine, &all->material, all->pieces, all->count,
                                layout, error);
    size_t starts[MOST_MATERIALS + 1];
    ur_status status = group_by_material(all, materials, starts, error);
    for (size_t g = 0; status == UR_OK && g < materials->count; g++) {
        ur_layout part = {NULL, 0, NULL, 0};
        if (g > 0 && same_remnants(&materials->placing[g], &materials->placing[0]))
            materials->placing[g].remnant_count = 0; /* the job's offcuts: the first stock's */
        job_run placing = job_run_make(&materials->placing[g], &callbacks, error);
        status = job_place_pieces(&placing, &all->machine, &materials->list[g],
                                  all->pieces + starts[g], starts[g + 1] - starts[g], &part, error);
        if (status == UR_OK)
            status = append_layout(layout, &part, starts[g], materials->list[g].name, error);
        ur_layout_free(&part);
    }
    return status;
}

static int place_and_write(const ur_job_file *file, ur_job *job, job_pieces_made *all,
                           job_materials *materials, bool quiet)
{
    ur_layout layout = {NULL, 0, NULL, 0};
    ur_error error;
    ur_status status = place_by_material(job, all, materials, &layout, &error);
    ur_job_callbacks callbacks = cli_callbacks(job);
    job_run run = job_run_make(job, &callbacks, &error);
    if (status == UR_OK)
        status = job_allowances_after_placing(&run, &all->machine, &layout, all->pieces, all->count,
                                              &error);
    if (status == UR_OK) {
        job->quiet = quiet;
        run = job_run_make(job, &callbacks, &error);
        job_allowance_warnings(&run, all->pieces, all->count);
        job_not_placed_warning(&run, &layout, all->pieces);
        ur_report_context context = {.surface =
                                         file->part_count == 1 ? file->parts[0].surface : "job",
                                     .method = file->name,
                                     .machine = &all->machine,
                                     .material = &all->material,
                                     .surface_area = all->surface_area,
                                     .sheet_path = job->output_path};
        status = job_write_outputs(&run, &all->machine, &layout, all->pieces, all->count, &context,
                                   &error);
    }
    int code = 0;
    if (status != UR_OK) {
        cli_message("%s: %s", file->source, error.message);
        code = cli_exit_status(&error);
    } else if (!quiet) {
        char cutting[256];
        job_describe_cutting(&run, &all->machine, &layout, all->pieces, cutting, sizeof cutting);
        cli_message("job %s: %zu piece%s on %zu sheet%s%s -> %s", file->name, all->count,
                    all->count == 1 ? "" : "s", layout.sheet_count,
                    layout.sheet_count == 1 ? "" : "s", cutting, job->output_path);
    }
    ur_layout_free(&layout);
    return code;
}

/* unroll job FILE.xml [-o DIR] [--quiet] */
static int parse_job_command(int argc, char **argv, const char **path, const char **directory,
                             bool *quiet)
{
    *path = NULL;
    *directory = NULL;
    *quiet = false;
    for (int k = 1; k < argc; k++) {
        if (strcmp(argv[k], "-o") == 0 && k + 1 < argc)
            *directory = argv[++k];
        else if (strcmp(argv[k], "--quiet") == 0)
            *quiet = true;
        else if (argv[k][0] != '-' && !*path)
            *path = argv[k];
        else {
            cli_message("job: '%s' is not FILE.xml, -o DIR or --quiet (see unroll-job(5))",
                        argv[k]);
            return EXIT_USAGE;
        }
    }
    if (!*path) {
        cli_message("job: give the job file: unroll job FILE.xml [-o DIR]");
        return EXIT_USAGE;
    }
    return 0;
}

int cli_job_command(int argc, char **argv)
{
    const char *path, *directory;
    bool quiet;
    int code = parse_job_command(argc, argv, &path, &directory, &quiet);
    if (code)
        return code;
    ur_job_file file;
    ur_error error;
    if (ur_job_file_read(path, &file, &error) != UR_OK) {
        cli_message("%s", error.message);
        return cli_exit_status(&error);
    }
    if (directory)
        snprintf(file.output_directory, sizeof file.output_directory, "%s", directory);

    char out[4200], report[4200], command[1200];
    output_path(&file, out, sizeof out);
    snprintf(report, sizeof report, "%s/%s", file.output_directory, file.report);
    words *first = calloc(1, sizeof *first);
    ur_job job;
    job_pieces_made all;
    memset(&all, 0, sizeof all);
    job_materials *materials = calloc(1, sizeof *materials);
    if (first && materials)
        code = all_pieces(&file, out, first, &job, command, sizeof command, &all, materials);
    else {
        cli_message("job: out of memory");
        code = EXIT_INTERNAL;
    }
    /* The output directory is made when missing (its parent must exist), only now. */
    bool made_directory = false;
    if (!code) {
        made_directory = mkdir(file.output_directory, 0777) == 0;
        if (!made_directory && errno != EEXIST) {
            cli_message("%s: cannot make the output directory %s: %s", file.source,
                        file.output_directory, strerror(errno));
            code = EXIT_USAGE;
        }
    }
    if (!code) {
        /* One part alone writes as its command line would: its own name and title. */
        job.command = file.part_count == 1 ? file.parts[0].surface : "job";
        if (!job.job_name) /* <option name="job-name"> says otherwise */
            job.job_name = file.name;
        job.report_path = file.report[0] ? report : NULL;
        code = place_and_write(&file, &job, &all, materials, quiet);
    }
    if (code && made_directory)
        rmdir(file.output_directory); /* nothing is left behind */
    free_made(&all);
    if (materials)
        free(materials->of_piece);
    free(materials);
    free(first);
    ur_job_file_free(&file);
    return code;
}
