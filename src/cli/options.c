/*
 * options.c: parsing a surface subcommand's options with getopt_long.
 *
 * Every value is checked here, where the option's name is known, so that a
 * message can always name it: "unroll helicoid: --radius: 'x' is not a number".
 */
#include "cli.h"

#include "unroll/flatten.h"
#include "unroll/io.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

enum option_id {
    OPT_RADIUS = 256,
    OPT_HEIGHT,
    OPT_TOP_RADIUS,
    OPT_CURVE,
    OPT_DIRECTION,
    OPT_APEX,
    OPT_CUT,
    OPT_PITCH,
    OPT_TURNS,
    OPT_WIDTH,
    OPT_OFFSET,
    OPT_RAIL1,
    OPT_RAIL2,
    OPT_PAIRING,
    OPT_STRICT,
    OPT_REGRESSION,
    OPT_ADJUST,
    OPT_ADJUST_RAIL2,
    OPT_ADJUST_DIRECTION,
    OPT_ADJUST_PLANE,
    OPT_ADJUST_ENDS,
    OPT_ADJUST_MAX,
    OPT_ADJUSTED_RAIL,
    OPT_ADJUSTED_RAIL1,
    OPT_CORNERS,
    OPT_SURFACE,
    OPT_UNITS,
    OPT_SCALE,
    OPT_SEAMS,
    OPT_FLATTEN,
    OPT_ITERATIONS,
    OPT_MAX_STRAIN, /* last of the surface options */
    OPT_PNG,
    OPT_CSV,
    OPT_STRAIN_PNG,
    OPT_ASSEMBLY,
    OPT_ASSEMBLY_UP,
    OPT_SHEET,
    OPT_METHOD,
    OPT_RULINGS,
    OPT_TOLERANCE,
    OPT_NO_SPLIT,
    OPT_ALLOWANCES,
    OPT_BRIDGES,
};

static const struct option long_options[] = {
    {"radius", required_argument, NULL, OPT_RADIUS},
    {"height", required_argument, NULL, OPT_HEIGHT},
    {"top-radius", required_argument, NULL, OPT_TOP_RADIUS},
    {"curve", required_argument, NULL, OPT_CURVE},
    {"direction", required_argument, NULL, OPT_DIRECTION},
    {"apex", required_argument, NULL, OPT_APEX},
    {"cut", required_argument, NULL, OPT_CUT},
    {"pitch", required_argument, NULL, OPT_PITCH},
    {"turns", required_argument, NULL, OPT_TURNS},
    {"width", required_argument, NULL, OPT_WIDTH},
    {"offset", required_argument, NULL, OPT_OFFSET},
    {"rail1", required_argument, NULL, OPT_RAIL1},
    {"rail2", required_argument, NULL, OPT_RAIL2},
    {"pairing", required_argument, NULL, OPT_PAIRING},
    {"strict", no_argument, NULL, OPT_STRICT},
    {"regression", required_argument, NULL, OPT_REGRESSION},
    {"adjust", required_argument, NULL, OPT_ADJUST},
    {"adjust-rail2", no_argument, NULL, OPT_ADJUST_RAIL2},
    {"adjust-direction", required_argument, NULL, OPT_ADJUST_DIRECTION},
    {"adjust-plane", required_argument, NULL, OPT_ADJUST_PLANE},
    {"adjust-ends", no_argument, NULL, OPT_ADJUST_ENDS},
    {"adjust-max", required_argument, NULL, OPT_ADJUST_MAX},
    {"adjusted-rail", required_argument, NULL, OPT_ADJUSTED_RAIL},
    {"adjusted-rail1", required_argument, NULL, OPT_ADJUSTED_RAIL1},
    {"corners", required_argument, NULL, OPT_CORNERS},
    {"surface", required_argument, NULL, OPT_SURFACE},
    {"units", required_argument, NULL, OPT_UNITS},
    {"scale", required_argument, NULL, OPT_SCALE},
    {"seams", required_argument, NULL, OPT_SEAMS},
    {"flatten", required_argument, NULL, OPT_FLATTEN},
    {"iterations", required_argument, NULL, OPT_ITERATIONS},
    {"max-strain", required_argument, NULL, OPT_MAX_STRAIN},
    {"png", required_argument, NULL, OPT_PNG},
    {"csv", required_argument, NULL, OPT_CSV},
    {"strain-png", required_argument, NULL, OPT_STRAIN_PNG},
    {"assembly", required_argument, NULL, OPT_ASSEMBLY},
    {"assembly-up", required_argument, NULL, OPT_ASSEMBLY_UP},
    {"output", required_argument, NULL, 'o'},
    {"sheet", required_argument, NULL, OPT_SHEET},
    {"method", required_argument, NULL, OPT_METHOD},
    {"parts", required_argument, NULL, 'n'},
    {"rulings", no_argument, NULL, OPT_RULINGS},
    {"tolerance", required_argument, NULL, OPT_TOLERANCE},
    {"no-split", no_argument, NULL, OPT_NO_SPLIT},
    {"allowances", required_argument, NULL, OPT_ALLOWANCES},
    {"bridges", required_argument, NULL, OPT_BRIDGES},
    {"help", no_argument, NULL, 'h'},
    {NULL, 0, NULL, 0},
};

/* The surface options each subcommand accepts (common options apply to all). */
static const struct {
    const char *surface;
    const char *options;
} accepted[] = {
    {"cylinder", " radius height curve direction surface "},
    {"cone", " radius height top-radius curve apex cut surface "},
    {"helicoid", " radius pitch turns width offset surface "},
    {"tangent", " curve width offset surface "},
    {"strip", " rail1 rail2 pairing strict regression adjust adjust-rail2 adjust-direction "
              "adjust-plane adjust-ends adjust-max adjusted-rail adjusted-rail1 flatten iterations "
              "max-strain surface "},
    {"ruled", " rail1 rail2 flatten iterations max-strain surface "},
    {"hypar", " corners flatten iterations max-strain surface "},
    {"mesh", " units scale seams flatten iterations max-strain "},
};

/* Options that belong to one action only. */
static const struct {
    cli_action action;
    const char *options;
} action_options[] = {
    {CLI_DEVELOP,
     " output machine material sheet method parts rulings no-split report strain-png assembly "
     "assembly-up "
     "allowances bridges no-kerf-compensation format dxf-version dpi job-name order rotations "
     "no-holes merge-lines roll sheets remnant nest-time seed threads "},
    {CLI_ANALYZE, " png report "},
    {CLI_COMPARE, " png csv "},
};

static const char *action_name(cli_action action)
{
    return action == CLI_ANALYZE ? "analyze" : action == CLI_COMPARE ? "compare" : "develop";
}

/* An option that belongs to some action but not to this one. */
static bool foreign_to_action(cli_action action, const char *option)
{
    char word[64];
    snprintf(word, sizeof word, " %s ", option);
    bool someone = false, mine = false;
    for (size_t k = 0; k < sizeof action_options / sizeof action_options[0]; k++)
        if (strstr(action_options[k].options, word)) {
            someone = true;
            mine = mine || action_options[k].action == action;
        }
    return someone && !mine;
}

bool cli_is_surface(const char *name)
{
    for (size_t k = 0; k < sizeof accepted / sizeof accepted[0]; k++)
        if (strcmp(accepted[k].surface, name) == 0)
            return true;
    return false;
}

static bool accepts(const char *surface, const char *option)
{
    char word[64];
    snprintf(word, sizeof word, " %s ", option);
    for (size_t k = 0; k < sizeof accepted / sizeof accepted[0]; k++)
        if (strcmp(accepted[k].surface, surface) == 0)
            return strstr(accepted[k].options, word) != NULL;
    return false;
}

/* Where the words being parsed come from, when not the command line (a job file's line). */
static char message_context[1200];

void cli_message_context(const char *context)
{
    snprintf(message_context, sizeof message_context, "%s", context ? context : "");
}

void cli_message(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fputs("unroll: ", stderr);
    if (message_context[0])
        fprintf(stderr, "%s: ", message_context);
    vfprintf(stderr, format, args);
    fputc('\n', stderr);
    va_end(args);
}

bool cli_whole_number(const char *text, long least, long most, long *value)
{
    char *end = NULL;
    errno = 0;
    long parsed = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || parsed < least || parsed > most)
        return false;
    *value = parsed;
    return true;
}

static const char *option_name(int id)
{
    if (id >= CLI_SHARED_OPTION)
        return ur_job_option_name((size_t)(id - CLI_SHARED_OPTION), NULL);
    for (const struct option *o = long_options; o->name; o++)
        if (o->val == id)
            return o->name;
    return "?";
}

static bool parse_number(const char *surface, int id, const char *text, double *value)
{
    char *end;
    errno = 0;
    *value = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE || !isfinite(*value)) {
        cli_message("%s: --%s: '%s' is not a finite number", surface, option_name(id), text);
        return false;
    }
    if (fabs(*value) > UR_LENGTH_MAX) {
        cli_message("%s: --%s: '%s' is beyond the largest number unroll takes, %g", surface,
                    option_name(id), text, UR_LENGTH_MAX);
        return false;
    }
    return true;
}

/* X,Y,Z ending at `last` (a ':' between corners, or the string's end). */
static const char *scan_vector(const char *p, char last, ur_vec3 *v)
{
    char *end;
    double c[3];
    for (int k = 0; k < 3; k++) {
        errno = 0;
        c[k] = strtod(p, &end);
        bool separator_ok = k < 2 ? *end == ',' : *end == last;
        if (end == p || !separator_ok || errno == ERANGE || !isfinite(c[k]) ||
            fabs(c[k]) > UR_LENGTH_MAX)
            return NULL;
        p = end + 1;
    }
    *v = ur_vec3_make(c[0], c[1], c[2]);
    return p;
}

static bool parse_vector(const char *surface, int id, const char *text, ur_vec3 *v)
{
    if (!scan_vector(text, '\0', v)) {
        cli_message("%s: --%s: '%s' is not three numbers X,Y,Z (each at most %g)", surface,
                    option_name(id), text, UR_LENGTH_MAX);
        return false;
    }
    return true;
}

static bool parse_corners(const char *surface, const char *text, ur_vec3 corners[4])
{
    const char *p = text;
    for (int k = 0; k < 4 && p; k++)
        p = scan_vector(p, k < 3 ? ':' : '\0', &corners[k]);
    if (!p) {
        cli_message("%s: --corners: '%s' is not four corners X,Y,Z:X,Y,Z:X,Y,Z:X,Y,Z (each "
                    "number at most %g)",
                    surface, text, UR_LENGTH_MAX);
        return false;
    }
    return true;
}

static bool parse_sheet(const char *surface, const char *text, ur_job *job)
{
    char *end;
    errno = 0;
    job->sheet_width = strtod(text, &end);
    bool ok = end != text && (*end == 'x' || *end == 'X');
    if (ok) {
        const char *rest = end + 1;
        job->sheet_height = strtod(rest, &end);
        ok = end != rest && *end == '\0' && errno == 0;
    }
    if (!ok || !(job->sheet_width > 0) || !(job->sheet_height > 0) ||
        !(job->sheet_width <= UR_LENGTH_MAX) || !(job->sheet_height <= UR_LENGTH_MAX)) {
        cli_message("%s: --sheet: '%s' is not WIDTHxHEIGHT in mm up to %g, e.g. 600x400", surface,
                    text, UR_LENGTH_MAX);
        return false;
    }
    return true;
}

static bool parse_count(const char *surface, const char *text, size_t *count)
{
    long value;
    if (!cli_whole_number(text, 1, 10000000, &value)) {
        cli_message("%s: -n/--parts: '%s' is not a whole number from 1 to 10000000", surface, text);
        return false;
    }
    *count = (size_t)value;
    return true;
}

static bool parse_iterations(ur_job *job, const char *text)
{
    long value;
    if (!cli_whole_number(text, 1, 100000, &value)) {
        cli_message("%s: --iterations: '%s' is not a whole number from 1 to 100000", job->command,
                    text);
        return false;
    }
    job->iterations = (size_t)value;
    return true;
}

/* --adjust rail1|rail2|both */
static bool parse_adjust(ur_job *job, const char *text)
{
    const char *names[] = {"rail1", "rail2", "both"};
    for (unsigned k = 0; k < 3; k++)
        if (strcmp(text, names[k]) == 0) {
            job->adjust_rails = k + 1;
            return true;
        }
    cli_message("%s: --adjust: '%s' is not one of rail1, rail2, both", job->command, text);
    return false;
}

/* --surface: which layer of the material the 3D surface is; only a development uses it. */
static bool parse_surface_layer(ur_job *job, cli_action action, const char *text)
{
    if (action != CLI_DEVELOP) {
        cli_message("%s: --surface does not apply to '%s' (see 'unroll help %s')", job->command,
                    action_name(action), job->command);
        return false;
    }
    job->surface_layer = ur_surface_layer_from_name(text);
    if (job->surface_layer < 0)
        cli_message("%s: --surface: '%s' is not one of outer, inner, mid, neutral", job->command,
                    text);
    return job->surface_layer >= 0;
}

/* --assembly FILE: its extension says the format, and only two are drawn. */
static bool parse_assembly(ur_job *job, const char *path)
{
    size_t length = strlen(path);
    const char *extension = length > 4 ? path + length - 4 : "";
    if (strcasecmp(extension, ".png") != 0 && strcasecmp(extension, ".pdf") != 0) {
        cli_message("%s: --assembly: '%s' is not a .png or .pdf file name (the assembly guide is "
                    "a picture or a PDF)",
                    job->command, path);
        return false;
    }
    job->assembly_path = path;
    return true;
}

static double *number_slot(ur_job *job, int id)
{
    switch (id) {
    case OPT_SCALE:
        return &job->scale;
    case OPT_MAX_STRAIN:
        return &job->max_strain;
    case OPT_RADIUS:
        return &job->radius;
    case OPT_HEIGHT:
        return &job->height;
    case OPT_TOP_RADIUS:
        return &job->top_radius;
    case OPT_CUT:
        return &job->cut;
    case OPT_PITCH:
        return &job->pitch;
    case OPT_TURNS:
        return &job->turns;
    case OPT_WIDTH:
        return &job->width;
    case OPT_OFFSET:
        return &job->offset;
    case OPT_TOLERANCE:
        return &job->develop.tolerance;
    default:
        return NULL;
    }
}

/* Handles one option; returns false after printing a message. */
static bool take_option(ur_job *job, cli_action action, int id, const char *value)
{
    const char *surface = job->surface;
    if (id >= OPT_RADIUS && id <= OPT_MAX_STRAIN && !accepts(surface, option_name(id))) {
        cli_message("%s: --%s does not apply to a %s (see 'unroll help %s')", job->command,
                    option_name(id), surface, surface);
        return false;
    }
    const char *name = id == 'o' ? "output" : id == 'n' ? "parts" : option_name(id);
    if (foreign_to_action(action, name)) {
        cli_message("%s: --%s does not apply to '%s' (see 'unroll help %s')", job->command, name,
                    action_name(action), job->command);
        return false;
    }
    if (id >= CLI_SHARED_OPTION)
        return cli_take_shared_option(job, id, value);
    double *slot = number_slot(job, id);
    if (slot)
        return parse_number(surface, id, value, slot);
    switch (id) {
    case OPT_CURVE:
        job->curve_path = value;
        return true;
    case OPT_RAIL1:
    case OPT_RAIL2:
        job->rail_paths[id - OPT_RAIL1] = value;
        return true;
    case OPT_PAIRING:
        if (strcmp(value, "natural") != 0 && strcmp(value, "developable") != 0) {
            cli_message("%s: --pairing: '%s' is not one of natural, developable", job->command,
                        value);
            return false;
        }
        job->natural_pairing = strcmp(value, "natural") == 0;
        return true;
    case OPT_STRICT:
        job->strict = true;
        return true;
    case OPT_REGRESSION:
        job->regression_path = value;
        return true;
    case OPT_ADJUST:
        return parse_adjust(job, value);
    case OPT_ADJUST_RAIL2: /* as before --adjust: rail 2's ends move when they must */
        job->adjust_rails = UR_REPAIR_RAIL2;
        job->adjust_ends = true;
        return true;
    case OPT_ADJUST_DIRECTION:
        return job->has_adjust_direction = parse_vector(surface, id, value, &job->adjust_direction);
    case OPT_ADJUST_PLANE:
        return job->has_adjust_plane = parse_vector(surface, id, value, &job->adjust_plane);
    case OPT_ADJUST_ENDS:
        job->adjust_ends = true;
        return true;
    case OPT_ADJUST_MAX:
        return parse_number(surface, id, value, &job->adjust_max);
    case OPT_ADJUSTED_RAIL:
        job->adjusted_rail_path = value;
        return true;
    case OPT_ADJUSTED_RAIL1:
        job->adjusted_rail1_path = value;
        return true;
    case OPT_CORNERS:
        return job->has_corners = parse_corners(surface, value, job->corners);
    case OPT_SURFACE:
        return parse_surface_layer(job, action, value);
    case OPT_UNITS:
        if (ur_length_unit_from_name(value) < 0) {
            cli_message("%s: --units: '%s' is not one of mm, cm, m, in", job->command, value);
            return false;
        }
        job->unit_name = value;
        return true;
    case OPT_SEAMS:
        if (job->seam_count == sizeof job->seam_paths / sizeof job->seam_paths[0]) {
            cli_message("%s: --seams: at most %zu seam files", job->command,
                        sizeof job->seam_paths / sizeof job->seam_paths[0]);
            return false;
        }
        job->seam_paths[job->seam_count++] = value;
        return true;
    case OPT_FLATTEN: {
        /* charts is the mesh's default, flatten -1 as when none is given. */
        bool charts = strcmp(value, "charts") == 0, mesh = strcmp(job->surface, "mesh") == 0;
        job->unfold = strcmp(value, "unfold") == 0;
        job->strips = strcmp(value, "strips") == 0;
        job->flatten =
            job->unfold || job->strips || charts ? -1 : ur_flatten_method_from_name(value);
        if (job->strips)
            return true;
        if (job->flatten < 0 && !job->unfold && !charts)
            cli_message("%s: --flatten: '%s' is not one of charts, arap, lscm, strips, unfold",
                        job->command, value);
        if ((job->unfold || charts) && !mesh)
            cli_message("%s: --flatten %s goes with 'unroll mesh' (it cuts a mesh along its "
                        "edges)",
                        job->command, value);
        return job->flatten >= 0 || ((job->unfold || charts) && mesh);
    }
    case OPT_ITERATIONS:
        return parse_iterations(job, value);
    case OPT_PNG:
        job->png_path = value;
        return true;
    case OPT_CSV:
        job->csv_path = value;
        return true;
    case OPT_STRAIN_PNG:
        job->strain_png_path = value;
        return true;
    case OPT_ASSEMBLY:
        return parse_assembly(job, value);
    case OPT_ASSEMBLY_UP:
        if (strcmp(value, "y") != 0 && strcmp(value, "z") != 0) {
            cli_message("%s: --assembly-up: '%s' is not y or z (the axis that points up)",
                        job->command, value);
            return false;
        }
        job->assembly_y_up = strcmp(value, "y") == 0;
        return true;
    case OPT_DIRECTION:
        return job->has_direction = parse_vector(surface, id, value, &job->direction);
    case OPT_APEX:
        return job->has_apex = parse_vector(surface, id, value, &job->apex);
    case 'o':
        job->output_path = value;
        return true;
    case OPT_SHEET:
        return parse_sheet(surface, value, job);
    case OPT_RULINGS:
        job->draw_rulings = true;
        return true;
    case OPT_NO_SPLIT:
        job->develop.split = false;
        return true;
    case OPT_ALLOWANCES:
        return cli_parse_allowances(job, value);
    case OPT_BRIDGES:
        return cli_parse_bridges(job, value);
    case 'n':
        return parse_count(surface, value, &job->develop.rulings);
    case OPT_METHOD: {
        int method = ur_method_from_name(value);
        if (method < 0) {
            cli_message("%s: --method: '%s' is not one of exact, triangle, quad", surface, value);
            return false;
        }
        job->develop.method = (ur_method)method;
        return true;
    }
    default:
        return false;
    }
}

int cli_parse_job(int argc, char **argv, cli_action action, const char *command, ur_job *job)
{
    ur_job_init(job, argv[0]);
    job->context = cli_context();
    job->command = command;
    opterr = 0;
    optind = 1;
    int id;
    struct option table[sizeof long_options / sizeof long_options[0] + 32];
    cli_option_table(long_options, table, sizeof table / sizeof table[0]);
    while ((id = getopt_long(argc, argv, ":o:n:h", table, NULL)) != -1) {
        if (id == 'h')
            return cli_print_help(job->command) == 0 ? -1 : EXIT_USAGE;
        if (id == '?' || id == ':') {
            const char *word = argv[optind - 1];
            cli_message(id == ':' ? "%s: option %s needs a value"
                                  : "%s: unknown option '%s' (see 'unroll help %s')",
                        job->command, word, job->command);
            return EXIT_USAGE;
        }
        if (!take_option(job, action, id, optarg))
            return EXIT_USAGE;
    }
    if (optind < argc && strcmp(job->surface, "mesh") == 0)
        job->mesh_path = argv[optind++];
    if (optind < argc) {
        cli_message("%s: unexpected argument '%s'", job->command, argv[optind]);
        return EXIT_USAGE;
    }
    if (action == CLI_DEVELOP && !job->output_path) {
        cli_message("%s: no output file: give -o FILE.svg", job->command);
        return EXIT_USAGE;
    }
    if (action == CLI_DEVELOP && !cli_check_output(job))
        return EXIT_USAGE;
    if (!(job->develop.tolerance > 0)) {
        cli_message("%s: --tolerance must be positive", job->command);
        return EXIT_USAGE;
    }
    if (!isnan(job->max_strain) && !(job->max_strain > 0 && job->max_strain < 1)) {
        cli_message("%s: --max-strain must be a fraction between 0 and 1 (0.01 is 1 %%), not %g",
                    job->command, job->max_strain);
        return EXIT_USAGE;
    }
    bool charts = strcmp(job->surface, "mesh") == 0 && job->flatten < 0 && !job->unfold;
    if (!isnan(job->max_strain) && !job->strips && !charts) {
        cli_message("%s: --max-strain goes with --flatten strips or charts", job->command);
        return EXIT_USAGE;
    }
    bool adjusting = job->has_adjust_direction || job->has_adjust_plane || job->adjust_ends ||
                     !isnan(job->adjust_max) || job->adjusted_rail_path || job->adjusted_rail1_path;
    if (adjusting && !job->adjust_rails) {
        cli_message("%s: --adjust-direction, --adjust-plane, --adjust-ends, --adjust-max and "
                    "--adjusted-rail go with --adjust (or --adjust-rail2)",
                    job->command);
        return EXIT_USAGE;
    }
    if (!isnan(job->adjust_max) && !(job->adjust_max > 0)) {
        cli_message("%s: --adjust-max must be positive", job->command);
        return EXIT_USAGE;
    }
    if (job->has_adjust_direction && job->has_adjust_plane) {
        cli_message("%s: give --adjust-direction or --adjust-plane, not both", job->command);
        return EXIT_USAGE;
    }
    if ((job->has_adjust_direction && !(ur_vec3_length(job->adjust_direction) > 0)) ||
        (job->has_adjust_plane && !(ur_vec3_length(job->adjust_plane) > 0))) {
        cli_message("%s: %s must not be zero", job->command,
                    job->has_adjust_direction ? "--adjust-direction" : "--adjust-plane");
        return EXIT_USAGE;
    }
    if (job->adjusted_rail1_path && !(job->adjust_rails & UR_REPAIR_RAIL1)) {
        cli_message("%s: --adjusted-rail1 goes with --adjust rail1 or both", job->command);
        return EXIT_USAGE;
    }
    return 0;
}
