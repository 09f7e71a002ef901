/*
 * main.c: the unroll command: dispatch to a subcommand, help and version.
 */
#include "cli.h"

#include <stdio.h>
#include <string.h>

static const char usage[] =
    "usage: unroll SUBCOMMAND [OPTIONS]\n"
    "\n"
    "Develops a surface into a flat net and writes it as an SVG cut file.\n"
    "\n"
    "surfaces:\n"
    "  cylinder  --radius R --height H | --curve BASE.csv --height H [--direction X,Y,Z]\n"
    "  cone      --radius R --height H [--top-radius r] | --curve BASE.csv --apex X,Y,Z [--cut T]\n"
    "  helicoid  --radius R --pitch P --turns T --width L [--offset D]\n"
    "  tangent   --curve EDGE.csv --width L [--offset D]\n"
    "other:\n"
    "  profiles [show NAME]   list machine and material profiles, or print one\n"
    "  help [SUBCOMMAND]      this text, or a subcommand's options\n"
    "\n"
    "common options (lengths in mm):\n"
    "  -o, --output FILE.svg  where to write (required); several sheets: FILE-1.svg, ...\n"
    "  --machine NAME         machine profile (default co2-60w)\n"
    "  --material NAME        material profile (default plywood-3mm)\n"
    "  --sheet WxH            sheet size instead of the material's stock\n"
    "  --method M             exact (default), triangle or quad\n"
    "  -n, --parts N          parts for triangle/quad; rulings drawn for all (default 24)\n"
    "  --rulings              draw the rulings as score lines\n"
    "  --tolerance MM         largest distance of an outline chord from the curve (0.01)\n"
    "  --no-split             refuse a net that overlaps itself instead of splitting it\n"
    "  --report FILE.json     write a JSON report ('-' for standard output)\n"
    "  --quiet                no summary on standard error\n"
    "\n"
    "exit status: 0 success, 1 internal error, 2 bad usage or input.\n"
    "See unroll(1) and unroll-profile(5).\n";

static const struct {
    const char *name;
    const char *text;
} subcommand_help[] = {
    {"cylinder",
     "unroll cylinder --radius R --height H -o FILE.svg [OPTIONS]\n"
     "unroll cylinder --curve BASE.csv --height H [--direction X,Y,Z] -o FILE.svg [OPTIONS]\n"
     "  A right circular cylinder, or the cylinder over any base curve (CSV x,y,z per\n"
     "  line, open or closed) along a direction (default 0,0,1).  Develops to a\n"
     "  rectangle for a right section; in general the base curve develops with its\n"
     "  geodesic curvature.\n"},
    {"cone", "unroll cone --radius R --height H [--top-radius r] -o FILE.svg [OPTIONS]\n"
             "unroll cone --curve BASE.csv --apex X,Y,Z [--cut T] -o FILE.svg [OPTIONS]\n"
             "  A right circular cone (a sector of radius the slant height) or frustum (an\n"
             "  annular sector); or the cone joining any base curve to an apex, keeping each\n"
             "  ruling from the base to fraction T of the way to the apex (default 1).\n"},
    {"helicoid",
     "unroll helicoid --radius R --pitch P --turns T --width L [--offset D] -o FILE.svg\n"
     "  The developable helicoid: tangents of the helix (R cos t, R sin t, P t / 2 pi),\n"
     "  each kept from distance D to D + L from the helix.  It develops to an annular\n"
     "  sector of inner radius (R^2 + c^2) / R, c = P / 2 pi; nets that would overlap\n"
     "  themselves (about one turn or more) are split into pieces.\n"},
    {"tangent", "unroll tangent --curve EDGE.csv --width L [--offset D] -o FILE.svg [OPTIONS]\n"
                "  The tangent developable of any space curve (the edge of regression), given as\n"
                "  points and interpolated with C2 cubic splines.  The curve must bend one way\n"
                "  only: an inflection makes the surface singular and is refused.\n"},
    {"profiles", "unroll profiles            list machine and material profiles\n"
                 "unroll profiles show NAME  print one profile and the file it comes from\n"
                 "  Profiles are searched in ./profiles, then $UNROLL_PROFILES, then the\n"
                 "  installed share directory.\n"},
};

void cli_print_usage(void)
{
    fputs(usage, stdout);
}

int cli_print_help(const char *subcommand)
{
    for (size_t k = 0; k < sizeof subcommand_help / sizeof subcommand_help[0]; k++)
        if (strcmp(subcommand_help[k].name, subcommand) == 0) {
            fputs(subcommand_help[k].text, stdout);
            if (cli_is_surface(subcommand))
                fputs("\ncommon options: see 'unroll --help'.\n", stdout);
            return 0;
        }
    cli_message("help: unknown subcommand '%s'; 'unroll --help' lists them", subcommand);
    return EXIT_USAGE;
}

static int surface_command(int argc, char **argv)
{
    cli_job job;
    int code = cli_parse_job(argc, argv, &job);
    if (code == -1)
        return 0; /* help was asked for and printed */
    return code ? code : cli_run_job(&job);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage, stderr);
        return EXIT_USAGE;
    }
    const char *command = argv[1];
    if (strcmp(command, "--help") == 0 || strcmp(command, "-h") == 0) {
        cli_print_usage();
        return 0;
    }
    if (strcmp(command, "--version") == 0) {
        printf("unroll %s\n", UR_VERSION);
        return 0;
    }
    if (strcmp(command, "help") == 0) {
        if (argc == 2) {
            cli_print_usage();
            return 0;
        }
        return cli_print_help(argv[2]);
    }
    if (strcmp(command, "profiles") == 0)
        return cli_profiles(argc - 1, argv + 1);
    if (cli_is_surface(command))
        return surface_command(argc - 1, argv + 1);
    cli_message("unknown subcommand '%s'; 'unroll --help' lists them", command);
    return EXIT_USAGE;
}
