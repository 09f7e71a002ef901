/*
 * nest.c: unroll nest FILE... -o OUT: parts drawn elsewhere (SVG, DXF)
 * placed on sheet stock, with the same machine and material profiles, kerf
 * compensation, writers and report as a surface job.
 *
 * A file's closed paths become parts (ur_parts_import); FILE:N or --copies
 * N asks for N of each.  Units come from the file, or --units when it says
 * nothing.
 */
#include "cli.h"
/* The stages a nest shares with a surface job; to become public API (see job.h). */
#include "../job/stages.h"

#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/out.h"

enum nest_option {
    NEST_MACHINE = 256,
    NEST_MATERIAL,
    NEST_SHEET,
    NEST_UNITS,
    NEST_COPIES,
    NEST_MARGIN,
    NEST_SPACING,
    NEST_REPORT,
    NEST_QUIET,
    NEST_NO_KERF,
    NEST_FORMAT,
    NEST_DXF_VERSION,
    NEST_DPI,
    NEST_JOB_NAME,
    NEST_ORDER,
    NEST_ROTATIONS,
    NEST_NO_HOLES,
    NEST_MERGE_LINES,
    NEST_NO_SPLIT,
    NEST_ROLL,
    NEST_SHEETS,
    NEST_REMNANT,
    NEST_NEST_TIME,
    NEST_SEED,
    NEST_THREADS,
    NEST_STRICT,
};

static const struct option nest_options[] = {
    {"output", required_argument, NULL, 'o'},
    {"machine", required_argument, NULL, NEST_MACHINE},
    {"material", required_argument, NULL, NEST_MATERIAL},
    {"sheet", required_argument, NULL, NEST_SHEET},
    {"units", required_argument, NULL, NEST_UNITS},
    {"copies", required_argument, NULL, NEST_COPIES},
    {"margin", required_argument, NULL, NEST_MARGIN},
    {"spacing", required_argument, NULL, NEST_SPACING},
    {"report", required_argument, NULL, NEST_REPORT},
    {"quiet", no_argument, NULL, NEST_QUIET},
    {"no-kerf-compensation", no_argument, NULL, NEST_NO_KERF},
    {"format", required_argument, NULL, NEST_FORMAT},
    {"dxf-version", required_argument, NULL, NEST_DXF_VERSION},
    {"dpi", required_argument, NULL, NEST_DPI},
    {"job-name", required_argument, NULL, NEST_JOB_NAME},
    {"order", required_argument, NULL, NEST_ORDER},
    {"rotations", required_argument, NULL, NEST_ROTATIONS},
    {"no-holes", no_argument, NULL, NEST_NO_HOLES},
    {"merge-lines", no_argument, NULL, NEST_MERGE_LINES},
    {"no-split", no_argument, NULL, NEST_NO_SPLIT},
    {"roll", required_argument, NULL, NEST_ROLL},
    {"sheets", required_argument, NULL, NEST_SHEETS},
    {"remnant", required_argument, NULL, NEST_REMNANT},
    {"nest-time", required_argument, NULL, NEST_NEST_TIME},
    {"seed", required_argument, NULL, NEST_SEED},
    {"threads", required_argument, NULL, NEST_THREADS},
    {"strict", no_argument, NULL, NEST_STRICT},
    {"help", no_argument, NULL, 'h'},
    {NULL, 0, NULL, 0},
};

/* What the command line says beyond what a surface job holds. */
typedef struct nest_job {
    ur_job job;     /* output, profiles, sheet, margin, spacing, report, quiet */
    job_run run;    /* the library's stages run job, reporting through the command */
    ur_error error; /* where the stages leave a failure */
    double unit_mm; /* --units: mm per unit of a file that gives none; 0 when not given */
    long copies;    /* --copies: of every part, unless FILE:N says otherwise */
    char **files;   /* argv's file arguments, FILE or FILE:N */
    size_t file_count;
    bool no_split; /* --no-split: a part longer than any sheet is an error, not cut */
    bool strict;   /* --strict: a file with open shapes (or lines no part holds) is refused */
} nest_job;

static bool parse_positive_count(const char *what, const char *value, long most, long *count)
{
    if (!cli_whole_number(value, 1, most, count)) {
        cli_message("nest: %s: '%s' is not a count from 1 to %ld", what, value, most);
        return false;
    }
    return true;
}

static bool parse_length(const char *what, const char *value, double *length)
{
    char *end = NULL;
    double parsed = strtod(value, &end);
    if (end == value || *end != '\0' || !(parsed >= 0) || !(parsed <= UR_LENGTH_MAX)) {
        cli_message("nest: %s: '%s' is not a length from 0 to %g mm", what, value, UR_LENGTH_MAX);
        return false;
    }
    *length = parsed;
    return true;
}

static bool parse_sheet_size(const char *value, ur_job *job)
{
    char *end = NULL;
    double width = strtod(value, &end);
    double height = end && *end == 'x' ? strtod(end + 1, &end) : NAN;
    if (!end || *end != '\0' || !(width > 0) || !(height > 0) || !(width <= UR_LENGTH_MAX) ||
        !(height <= UR_LENGTH_MAX)) {
        cli_message("nest: --sheet: '%s' is not WxH in mm up to %g, e.g. 600x400", value,
                    UR_LENGTH_MAX);
        return false;
    }
    job->sheet_width = width;
    job->sheet_height = height;
    return true;
}

static bool take_nest_option(nest_job *n, int id, const char *value)
{
    ur_job *job = &n->job;
    switch (id) {
    case 'o':
        job->output_path = value;
        return true;
    case NEST_NO_SPLIT:
        n->no_split = true;
        return true;
    case NEST_STRICT:
        n->strict = true;
        return true;
    case NEST_MACHINE:
        job->machine_name = value;
        return true;
    case NEST_MATERIAL:
        job->material_name = value;
        return true;
    case NEST_SHEET:
        return parse_sheet_size(value, job);
    case NEST_UNITS:
        n->unit_mm = ur_parts_unit_mm(value);
        if (n->unit_mm > 0)
            return true;
        cli_message("nest: --units: '%s' is not one of mm, cm, m, in, ft, pt, pc, px", value);
        return false;
    case NEST_COPIES:
        return parse_positive_count("--copies", value, 10000, &n->copies);
    case NEST_MARGIN:
        return parse_length("--margin", value, &job->margin);
    case NEST_SPACING:
        return parse_length("--spacing", value, &job->spacing);
    case NEST_REPORT:
        job->report_path = value;
        return true;
    case NEST_QUIET:
        job->quiet = true;
        return true;
    case NEST_NO_KERF:
        job->no_kerf_compensation = true;
        return true;
    case NEST_FORMAT:
        return cli_parse_formats(job, value);
    case NEST_DXF_VERSION:
        return cli_parse_dxf_version(job, value);
    case NEST_DPI:
        return cli_parse_dpi(job, value);
    case NEST_JOB_NAME:
        return cli_parse_job_name(job, value);
    case NEST_ORDER:
        return cli_parse_order(job, value);
    case NEST_ROTATIONS:
        return cli_parse_rotations(job, value);
    case NEST_NO_HOLES:
        job->no_holes = true;
        return true;
    case NEST_MERGE_LINES:
        job->merge_lines = true;
        return true;
    case NEST_ROLL:
        return cli_parse_roll(job, value);
    case NEST_SHEETS:
        return cli_parse_sheet_count(job, value);
    case NEST_REMNANT:
        return cli_parse_remnant(job, value);
    case NEST_NEST_TIME:
        return cli_parse_nest_time(job, value);
    case NEST_SEED:
        return cli_parse_seed(job, value);
    case NEST_THREADS:
        return cli_parse_threads(job, value);
    default:
        return false;
    }
}

static const char nest_help[] =
    "unroll nest FILE[:N]... -o OUT.svg [OPTIONS]\n"
    "  Nests the closed paths of SVG and DXF files made elsewhere (nested paths are\n"
    "  holes) on sheet stock.  Units come from the file (SVG width/height and viewBox,\n"
    "  DXF $INSUNITS); --units mm|cm|m|in|ft|pt|pc|px when it says nothing.\n"
    "  Score, engrave, mark and kerf lines (and open paths) inside a part go with it;\n"
    "  open shapes outside every part are left out with a warning (--strict refuses).\n"
    "  FILE:N or --copies N: that many of each part.\n"
    "  --machine NAME --material NAME --sheet WxH --margin MM --spacing MM\n"
    "  --report FILE.json --quiet --no-kerf-compensation\n"
    "  --format svg,dxf,pdf,png --dxf-version 12|2000 --dpi N --order cut|none\n"
    "  --job-name NAME (recorded in the files; default nest)\n"
    "  --rotations N (turns of 360/N degrees from the part as drawn; default 4)\n"
    "  --no-holes (no part inside another's hole)\n"
    "  --merge-lines  parts may touch; a line two parts share is cut once\n"
    "  --no-split     refuse a part longer than any sheet instead of cutting it\n"
    "  --strict       refuse a file with open shapes instead of leaving them out\n"
    "  --roll W   nest on roll stock W mm wide, as short as it goes\n"
    "  --sheets N at most N sheets; what does not fit is named, not placed\n"
    "  --remnant WxH  a remnant sheet at hand, filled before stock (repeatable)\n"
    "  --nest-time S  search for a better layout for up to S seconds (default 2)\n"
    "  --seed N       the search's orders (the same seed, the same layout)\n"
    "  --threads N    roll searches side by side (default one per processor)\n";

/* Parses argv (argv[0] is "nest"); 0, -1 after help, or an exit status. */
static int parse_nest(int argc, char **argv, nest_job *n)
{
    memset(n, 0, sizeof *n);
    n->copies = 1;
    ur_job *job = &n->job;
    job->command = "nest";
    job->surface = "nest";
    job->machine_name = "co2-60w";
    job->material_name = "plywood-3mm";
    job->margin = job->spacing = -1;
    job->nest_time = 2.0;
    opterr = 0;
    optind = 1;
    int id;
    while ((id = getopt_long(argc, argv, ":o:h", nest_options, NULL)) != -1) {
        if (id == 'h') {
            fputs(nest_help, stdout);
            return -1;
        }
        if (id == '?' || id == ':') {
            cli_message(id == ':' ? "nest: option %s needs a value"
                                  : "nest: unknown option '%s' (see 'unroll help nest')",
                        argv[optind - 1]);
            return EXIT_USAGE;
        }
        if (!take_nest_option(n, id, optarg))
            return EXIT_USAGE;
    }
    n->files = argv + optind;
    n->file_count = (size_t)(argc - optind);
    if (n->file_count == 0 || !job->output_path) {
        cli_message("nest: give the files to nest and -o OUT.svg: unroll nest FILE... -o OUT.svg");
        return EXIT_USAGE;
    }
    if (!cli_check_output(job))
        return EXIT_USAGE;
    return 0;
}

/* FILE:N: the path (into path) and the count; the count is n->copies without ":N". */
static bool split_count(const nest_job *n, const char *argument, char *path, size_t size,
                        long *copies)
{
    const char *colon = strrchr(argument, ':');
    *copies = n->copies;
    size_t length = strlen(argument);
    if (colon && colon[1] != '\0' && strspn(colon + 1, "0123456789") == strlen(colon + 1)) {
        if (!parse_positive_count(argument, colon + 1, 10000, copies))
            return false;
        length = (size_t)(colon - argument);
    }
    if (length >= size) {
        cli_message("nest: %s: path too long", argument);
        return false;
    }
    memcpy(path, argument, length);
    path[length] = '\0';
    return true;
}

/* Appends `copies` of every part of parts to the list, numbering the copies. */
static ur_status add_parts(const ur_parts *parts, long copies, ur_piece **pieces, size_t *count,
                           ur_error *error)
{
    size_t more = parts->count * (size_t)copies;
    ur_piece *grown = realloc(*pieces, (*count + more) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    *pieces = grown;
    for (size_t k = 0; k < parts->count; k++)
        for (long c = 0; c < copies; c++) {
            ur_piece *piece = &(*pieces)[*count];
            ur_status status = ur_piece_copy(&parts->pieces[k], piece, error);
            if (status != UR_OK)
                return status;
            if (copies > 1) { /* copies are at most 10000: "#" and 5 digits fit after 24 */
                char number[24];
                snprintf(number, sizeof number, "#%ld", c + 1);
                size_t keep = strnlen(parts->pieces[k].name, 24);
                memcpy(piece->name, parts->pieces[k].name, keep);
                memcpy(piece->name + keep, number, strlen(number) + 1);
            }
            (*count)++;
        }
    return UR_OK;
}

static int read_files(const nest_job *n, ur_piece **pieces, size_t *count)
{
    ur_parts_import_options options;
    ur_parts_import_options_default(&options);
    options.unit = n->unit_mm;
    options.strict = n->strict;
    for (size_t f = 0; f < n->file_count; f++) {
        char path[4096];
        long copies;
        if (!split_count(n, n->files[f], path, sizeof path, &copies))
            return EXIT_USAGE;
        ur_parts parts;
        ur_error error;
        ur_status status = ur_parts_import(path, &options, &parts, &error);
        if (status != UR_OK) {
            cli_message("nest: %s", error.message);
            return cli_exit_status(&error);
        }
        for (size_t w = 0; !n->job.quiet && w < parts.warning_count; w++)
            cli_message("nest: warning: %s", parts.warnings[w]);
        status = add_parts(&parts, copies, pieces, count, &error);
        ur_parts_free(&parts);
        if (status != UR_OK) {
            cli_message("nest: %s", error.message);
            return cli_exit_status(&error);
        }
    }
    return 0;
}

static const char *plural(size_t count)
{
    return count == 1 ? "" : "s";
}

static void print_nest_summary(const nest_job *n, const ur_machine *machine, const ur_piece *pieces,
                               size_t count, const ur_layout *layout)
{
    if (n->job.quiet || layout->sheet_count == 0)
        return;
    double margin = n->job.margin >= 0 ? n->job.margin : machine->margin;
    char cutting[256];
    job_describe_cutting(&n->run, machine, layout, pieces, cutting, sizeof cutting);
    const ur_sheet *stock = NULL; /* the first stock sheet, the roll on roll stock */
    for (size_t s = 0; s < layout->sheet_count; s++) {
        const ur_sheet *sheet = &layout->sheets[s];
        if (!sheet->remnant && !stock)
            stock = sheet;
        if (sheet->remnant)
            cli_message("nest: sheet %zu (remnant %g x %g mm): %zu part%s, utilisation %.1f %%",
                        s + 1, sheet->width, sheet->height, sheet->placement_count,
                        plural(sheet->placement_count), 100 * ur_sheet_utilisation(sheet, pieces));
        else
            cli_message("nest: sheet %zu: %zu part%s, utilisation %.1f %%", s + 1,
                        sheet->placement_count, plural(sheet->placement_count),
                        100 * ur_sheet_utilisation(sheet, pieces));
    }
    if (n->job.roll_width > 0) {
        cli_message("nest: %zu part%s on %.1f mm of the %g mm roll%s%s -> %s", count, plural(count),
                    stock ? stock->width : 0.0, n->job.roll_width,
                    layout->sheet_count > (stock != NULL) ? " and remnants" : "", cutting,
                    n->job.output_path);
        return;
    }
    char used[1024];
    job_describe_sheets(layout, used, sizeof used);
    size_t placed = count - layout->not_placed_count;
    double bound = job_sheets_lower_bound(pieces, count, layout, margin);
    if (stock)
        cli_message("nest: %zu part%s on %s (lower bound %.0f stock sheet%s)%s -> %s", placed,
                    plural(placed), used, bound, bound == 1 ? "" : "s", cutting,
                    n->job.output_path);
    else
        cli_message("nest: %zu part%s on %s%s -> %s", placed, plural(placed), used, cutting,
                    n->job.output_path);
}

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
static ur_status split_long_parts(const nest_job *n, const ur_machine *machine,
                                  const ur_material *material, ur_piece **pieces, size_t *count,
                                  ur_error *error)
{
    job_room room = job_fit_room(&n->run, machine, material);
    if (n->no_split || room.length <= 0)
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
        status = job_piece_fits_stock(&n->run, machine, material, &(*pieces)[k], &fits, error);
        if (status != UR_OK || fits)
            continue;
        size_t before = split.nets.count;
        status = ur_part_split(&(*pieces)[k], room.length, room.width, (double)k, &split, error);
        cut[k] = status == UR_OK;
        if (status == UR_OK && !n->job.quiet)
            cli_message("nest: part %s (%.0f x %.0f mm) fits no sheet in any allowed turn: cut "
                        "into %zu to fit the %.0f x %.0f mm a sheet leaves a part with joints "
                        "(--no-split refuses instead)",
                        (*pieces)[k].name, length, width, split.nets.count - before, room.length,
                        room.width);
    }
    int next_seam = 0;
    if (status == UR_OK && split.nets.count > 0)
        status = ur_net_list_find_seams(&split.nets, 1, &next_seam, error);
    if (status == UR_OK && split.nets.count > 0)
        status = job_add_joints(NULL, material, &split.nets, split.pieces, NULL, error);
    if (status == UR_OK && split.nets.count > 0)
        status = replace_split(&split, cut, pieces, count, error);
    ur_split_parts_free(&split);
    free(cut);
    return status;
}

static ur_status compensate(const nest_job *n, const ur_machine *machine,
                            const ur_material *material, ur_piece *pieces, size_t count,
                            ur_error *error)
{
    double kerf = ur_effective_kerf(machine, material);
    ur_status status = UR_OK;
    for (size_t k = 0; status == UR_OK && !n->job.no_kerf_compensation && k < count; k++)
        status = ur_piece_compensate_kerf(&pieces[k], kerf, error);
    return status;
}

static ur_status write_nest(const nest_job *n, const ur_machine *machine,
                            const ur_material *material, const ur_piece *pieces, size_t count,
                            const ur_layout *layout, ur_error *error)
{
    ur_report_context context = {.surface = "nest",
                                 .method = "nest",
                                 .machine = machine,
                                 .material = material,
                                 .sheet_path = n->job.output_path};
    for (size_t k = 0; k < count; k++)
        context.surface_area += pieces[k].measures.flat_area;
    return job_write_outputs(&n->run, machine, layout, pieces, count, &context, error);
}

/* Reads, compensates, places and writes; the pieces and layout are the caller's to free. */
static int run_nest(const nest_job *n, ur_piece **pieces, size_t *count, ur_layout *layout)
{
    ur_machine machine;
    ur_material material;
    ur_error error;
    if (ur_machine_load(n->job.machine_name, &machine, &error) != UR_OK ||
        ur_material_load(n->job.material_name, &material, &error) != UR_OK) {
        cli_message("%s", error.message);
        return cli_exit_status(&error);
    }
    int code = read_files(n, pieces, count);
    if (code)
        return code;
    ur_status status = split_long_parts(n, &machine, &material, pieces, count, &error);
    if (status == UR_OK)
        status = compensate(n, &machine, &material, *pieces, *count, &error);
    if (status == UR_OK)
        status = job_place_pieces(&n->run, &machine, &material, *pieces, *count, layout, &error);
    if (status == UR_OK)
        status = job_merge_lines(&n->run, layout, *pieces, *count, &error);
    if (status == UR_OK) {
        job_allowance_warnings(&n->run, *pieces, *count);
        job_not_placed_warning(&n->run, layout, *pieces);
        status = write_nest(n, &machine, &material, *pieces, *count, layout, &error);
    }
    if (status != UR_OK) {
        cli_message("nest: %s", error.message);
        return cli_exit_status(&error);
    }
    print_nest_summary(n, &machine, *pieces, *count, layout);
    return 0;
}

int cli_nest(int argc, char **argv)
{
    nest_job n;
    int code = parse_nest(argc, argv, &n);
    if (code == -1)
        return 0;
    if (code)
        return code;
    if ((strcmp(n.job.output_path, "-") != 0 && !cli_directory_exists("-o", n.job.output_path)) ||
        (n.job.report_path && strcmp(n.job.report_path, "-") != 0 &&
         !cli_directory_exists("--report", n.job.report_path)))
        return EXIT_USAGE;
    ur_job_callbacks callbacks = cli_callbacks(&n.job);
    n.run = job_run_make(&n.job, &callbacks, &n.error);
    ur_piece *pieces = NULL;
    size_t count = 0;
    ur_layout layout = {NULL, 0, NULL, 0};
    code = run_nest(&n, &pieces, &count, &layout);
    for (size_t k = 0; k < count; k++)
        ur_piece_free(&pieces[k]);
    free(pieces);
    ur_layout_free(&layout);
    return code;
}
