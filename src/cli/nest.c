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

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/out.h"

/* nest's own options, about the files it reads; the library's settings follow them. */
enum nest_option {
    NEST_UNITS = 256,
    NEST_COPIES,
    NEST_STRICT,
};

static const struct option nest_options[] = {
    {"units", required_argument, NULL, NEST_UNITS},
    {"copies", required_argument, NULL, NEST_COPIES},
    {"strict", no_argument, NULL, NEST_STRICT},
    {"help", no_argument, NULL, 'h'},
    {NULL, 0, NULL, 0},
};

/* What the command line says beyond what a surface job holds. */
typedef struct nest_job {
    ur_job job;     /* output, profiles, sheet, margin, spacing, split, report, quiet */
    double unit_mm; /* --units: mm per unit of a file that gives none; 0 when not given */
    long copies;    /* --copies: of every part, unless FILE:N says otherwise */
    char **files;   /* argv's file arguments, FILE or FILE:N */
    size_t file_count;
    bool strict; /* --strict: a file with open shapes (or lines no part holds) is refused */
} nest_job;

static bool parse_positive_count(const char *what, const char *value, long most, long *count)
{
    if (!cli_whole_number(value, 1, most, count)) {
        cli_message("nest: %s: '%s' is not a count from 1 to %ld", what, value, most);
        return false;
    }
    return true;
}

static bool take_nest_option(nest_job *n, int id, const char *value)
{
    ur_job *job = &n->job;
    if (id == 'o')
        return cli_set_option(job, "output", value);
    if (id >= CLI_SHARED_OPTION)
        return cli_set_option(job, ur_job_option_name((size_t)(id - CLI_SHARED_OPTION), NULL),
                              value);
    switch (id) {
    case NEST_STRICT:
        n->strict = true;
        return true;
    case NEST_UNITS:
        n->unit_mm = ur_parts_unit_mm(value);
        if (n->unit_mm > 0)
            return true;
        cli_message("nest: --units: '%s' is not one of mm, cm, m, in, ft, pt, pc, px", value);
        return false;
    case NEST_COPIES:
        return parse_positive_count("--copies", value, 10000, &n->copies);
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
    job->context = cli_context();
    job->command = "nest";
    job->surface = "nest";
    job->machine_name = "co2-60w";
    job->material_name = "plywood-3mm";
    job->margin = job->spacing = -1;
    job->develop.split = true;
    job->nest_time = 2.0;
    opterr = 0;
    optind = 1;
    int id;
    struct option table[sizeof nest_options / sizeof nest_options[0] + 32];
    cli_option_table(nest_options, false, table, sizeof table / sizeof table[0]);
    while ((id = getopt_long(argc, argv, ":o:h", table, NULL)) != -1) {
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
            cli_error("nest", &error);
            return cli_exit_status(&error);
        }
        for (size_t w = 0; !n->job.quiet && w < parts.warning_count; w++)
            cli_message("nest: warning: %s", parts.warnings[w]);
        status = add_parts(&parts, copies, pieces, count, &error);
        ur_parts_free(&parts);
        if (status != UR_OK) {
            cli_error("nest", &error);
            return cli_exit_status(&error);
        }
    }
    return 0;
}

static const char *plural(size_t count)
{
    return count == 1 ? "" : "s";
}

static void print_nest_summary(const nest_job *n, const ur_job_result *result,
                               const ur_piece *pieces, size_t count, const ur_layout *layout)
{
    if (n->job.quiet || layout->sheet_count == 0)
        return;
    const char *cutting = result->cutting;
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
    const char *used = result->sheets;
    size_t placed = count - layout->not_placed_count;
    double bound = result->sheets_lower_bound;
    if (stock)
        cli_message("nest: %zu part%s on %s (lower bound %.0f stock sheet%s)%s -> %s", placed,
                    plural(placed), used, bound, bound == 1 ? "" : "s", cutting,
                    n->job.output_path);
    else
        cli_message("nest: %zu part%s on %s%s -> %s", placed, plural(placed), used, cutting,
                    n->job.output_path);
}

/* Reads, compensates, places and writes; the pieces and layout are the caller's to free. */
static int run_nest(nest_job *n, ur_piece **pieces, size_t *count, ur_layout *layout)
{
    ur_machine machine;
    ur_material material;
    ur_error error;
    if (ur_machine_load(cli_profile_roots(), n->job.machine_name, &machine, &error) != UR_OK ||
        ur_material_load(cli_profile_roots(), n->job.material_name, &material, &error) != UR_OK) {
        cli_error(NULL, &error);
        return cli_exit_status(&error);
    }
    int code = read_files(n, pieces, count);
    if (code)
        return code;
    n->job.machine = &machine;
    n->job.material = &material;
    ur_job_callbacks callbacks = cli_callbacks(&n->job);
    ur_job_result result;
    if (ur_job_nest(&n->job, &callbacks, n->job.develop.split, pieces, count, layout, &result,
                    &error) != UR_OK) {
        cli_error("nest", &error);
        return cli_exit_status(&error);
    }
    print_nest_summary(n, &result, *pieces, *count, layout);
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
        return EXIT_IO;
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
