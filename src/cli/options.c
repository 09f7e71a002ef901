/*
 * options.c: parsing a surface subcommand's options with getopt_long.
 *
 * Every value is checked here, where the option's name is known, so that a
 * message can always name it: "unroll helicoid: --radius: 'x' is not a number".
 */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    OPT_MACHINE,
    OPT_MATERIAL,
    OPT_SHEET,
    OPT_METHOD,
    OPT_RULINGS,
    OPT_REPORT,
    OPT_TOLERANCE,
    OPT_NO_SPLIT,
    OPT_QUIET,
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
    {"output", required_argument, NULL, 'o'},
    {"machine", required_argument, NULL, OPT_MACHINE},
    {"material", required_argument, NULL, OPT_MATERIAL},
    {"sheet", required_argument, NULL, OPT_SHEET},
    {"method", required_argument, NULL, OPT_METHOD},
    {"parts", required_argument, NULL, 'n'},
    {"rulings", no_argument, NULL, OPT_RULINGS},
    {"report", required_argument, NULL, OPT_REPORT},
    {"tolerance", required_argument, NULL, OPT_TOLERANCE},
    {"no-split", no_argument, NULL, OPT_NO_SPLIT},
    {"quiet", no_argument, NULL, OPT_QUIET},
    {"help", no_argument, NULL, 'h'},
    {NULL, 0, NULL, 0},
};

/* The surface options each subcommand accepts (common options apply to all). */
static const struct {
    const char *surface;
    const char *options;
} accepted[] = {
    {"cylinder", " radius height curve direction "},
    {"cone", " radius height top-radius curve apex cut "},
    {"helicoid", " radius pitch turns width offset "},
    {"tangent", " curve width offset "},
};

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

void cli_message(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fputs("unroll: ", stderr);
    vfprintf(stderr, format, args);
    fputc('\n', stderr);
    va_end(args);
}

static const char *option_name(int id)
{
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
    return true;
}

static bool parse_vector(const char *surface, int id, const char *text, ur_vec3 *v)
{
    char *end;
    double c[3];
    const char *p = text;
    for (int k = 0; k < 3; k++) {
        errno = 0;
        c[k] = strtod(p, &end);
        bool separator_ok = k < 2 ? *end == ',' : *end == '\0';
        if (end == p || !separator_ok || errno == ERANGE || !isfinite(c[k])) {
            cli_message("%s: --%s: '%s' is not three finite numbers X,Y,Z", surface,
                        option_name(id), text);
            return false;
        }
        p = end + 1;
    }
    *v = ur_vec3_make(c[0], c[1], c[2]);
    return true;
}

static bool parse_sheet(const char *surface, const char *text, cli_job *job)
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
    if (!ok || !(job->sheet_width > 0) || !(job->sheet_height > 0) || !isfinite(job->sheet_width) ||
        !isfinite(job->sheet_height)) {
        cli_message("%s: --sheet: '%s' is not WIDTHxHEIGHT in mm, e.g. 600x400", surface, text);
        return false;
    }
    return true;
}

static bool parse_count(const char *surface, const char *text, size_t *count)
{
    char *end;
    errno = 0;
    long value = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno || value < 1 || value > 10000000) {
        cli_message("%s: -n/--parts: '%s' is not a whole number from 1 to 10000000", surface, text);
        return false;
    }
    *count = (size_t)value;
    return true;
}

static double *number_slot(cli_job *job, int id)
{
    switch (id) {
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
static bool take_option(cli_job *job, int id, const char *value)
{
    const char *surface = job->surface;
    if (id >= OPT_RADIUS && id <= OPT_OFFSET && !accepts(surface, option_name(id))) {
        cli_message("%s: --%s does not apply to a %s (see 'unroll help %s')", surface,
                    option_name(id), surface, surface);
        return false;
    }
    double *slot = number_slot(job, id);
    if (slot)
        return parse_number(surface, id, value, slot);
    switch (id) {
    case OPT_CURVE:
        job->curve_path = value;
        return true;
    case OPT_DIRECTION:
        return job->has_direction = parse_vector(surface, id, value, &job->direction);
    case OPT_APEX:
        return job->has_apex = parse_vector(surface, id, value, &job->apex);
    case 'o':
        job->output_path = value;
        return true;
    case OPT_MACHINE:
        job->machine_name = value;
        return true;
    case OPT_MATERIAL:
        job->material_name = value;
        return true;
    case OPT_SHEET:
        return parse_sheet(surface, value, job);
    case OPT_RULINGS:
        job->draw_rulings = true;
        return true;
    case OPT_REPORT:
        job->report_path = value;
        return true;
    case OPT_NO_SPLIT:
        job->develop.split = false;
        return true;
    case OPT_QUIET:
        job->quiet = true;
        return true;
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

static void job_defaults(cli_job *job, const char *surface)
{
    memset(job, 0, sizeof *job);
    job->surface = surface;
    job->radius = job->height = job->top_radius = job->pitch = NAN;
    job->turns = job->width = job->offset = job->cut = NAN;
    job->machine_name = "co2-60w";
    job->material_name = "plywood-3mm";
    ur_develop_options_default(&job->develop);
}

int cli_parse_job(int argc, char **argv, cli_job *job)
{
    job_defaults(job, argv[0]);
    opterr = 0;
    optind = 1;
    int id;
    while ((id = getopt_long(argc, argv, ":o:n:h", long_options, NULL)) != -1) {
        if (id == 'h')
            return cli_print_help(job->surface) == 0 ? -1 : EXIT_USAGE;
        if (id == '?' || id == ':') {
            const char *word = argv[optind - 1];
            cli_message(id == ':' ? "%s: option %s needs a value"
                                  : "%s: unknown option '%s' (see 'unroll help %s')",
                        job->surface, word, job->surface);
            return EXIT_USAGE;
        }
        if (!take_option(job, id, optarg))
            return EXIT_USAGE;
    }
    if (optind < argc) {
        cli_message("%s: unexpected argument '%s'", job->surface, argv[optind]);
        return EXIT_USAGE;
    }
    if (!job->output_path) {
        cli_message("%s: no output file: give -o FILE.svg", job->surface);
        return EXIT_USAGE;
    }
    if (!(job->develop.tolerance > 0)) {
        cli_message("%s: --tolerance must be positive", job->surface);
        return EXIT_USAGE;
    }
    return 0;
}
