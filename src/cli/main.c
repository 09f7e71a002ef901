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
    "  strip     --rail1 C1.csv --rail2 C2.csv [--pairing natural|developable] [--strict]\n"
    "            [--regression EDGE.csv] [--adjust rail1|rail2|both ...]\n"
    "  ruled     --rail1 C1.csv --rail2 C2.csv        (flattened with strain unless developable)\n"
    "  hypar     --corners X,Y,Z:X,Y,Z:X,Y,Z:X,Y,Z   (flattened with strain unless flat)\n"
    "  mesh      FILE.obj|stl|ply|gltf|glb|dae|3mf [--units U] [--scale S] [--seams F.csv]\n"
    "non-developable surfaces and meshes:\n"
    "  --flatten charts|arap|lscm|strips|unfold  how to flatten (default charts for\n"
    "                        a mesh, arap for a surface)\n"
    "  --iterations N --max-strain S --strain-png FILE.png\n"
    "  --assembly FILE.png|pdf  the assembly guide: the mesh from four sides, pieces\n"
    "                         coloured and named, seam labels (--assembly-up auto|y|z)\n"
    "study a surface (SURFACE and its options as above, no -o):\n"
    "  analyze SURFACE ... [--png FILE.png] [--report FILE.json]\n"
    "  compare SURFACE ... [--csv FILE.csv] [--png FILE.png]\n"
    "other:\n"
    "  nest FILE[:N]... -o OUT.svg  nest the closed paths of SVG and DXF files on sheets\n"
    "  job FILE.xml [-o DIR]  a whole build from a job file (unroll-job(5))\n"
    "  profiles [show NAME]   list machine and material profiles, or print one\n"
    "  help [SUBCOMMAND]      this text, or a subcommand's options\n"
    "\n"
    "common options (lengths in mm):\n"
    "  -o, --output FILE.svg  where to write (required); several sheets: FILE-1.svg, ...\n"
    "  --machine NAME         machine profile (default co2-60w)\n"
    "  --material NAME        material profile (default plywood-3mm)\n"
    "  --surface LAYER        the face the surface is: outer, inner, mid or neutral\n"
    "                         (default the material's); the neutral layer is developed\n"
    "  --sheet WxH            sheet size instead of the material's stock\n"
    "  --method M             exact (default), triangle or quad\n"
    "  -n, --parts N          parts for triangle/quad; rulings drawn for all (default 24)\n"
    "  --rulings              draw the rulings as score lines\n"
    "  --tolerance MM         largest distance of an outline chord from the curve (0.01)\n"
    "  --no-split             refuse a net that overlaps itself or fits no sheet\n"
    "                         instead of splitting it\n"
    "  --allowances WHAT      auto (default), none, or a list of tabs, kerfing, overlaps,\n"
    "                         bending, bridges: what the material needs (man unroll)\n"
    "  --bridges auto|N|none  holding bridges (default: as the machine profile says)\n"
    "  --no-kerf-compensation leave outlines where the net puts them\n"
    "  --format svg,dxf,pdf,png  the files to write (default: -o's extension)\n"
    "  --dxf-version 12|2000  DXF dialect (default 12); --dpi N  PNG preview resolution\n"
    "  --job-name NAME        the job the files record (default the subcommand)\n"
    "  --order cut|none       paths in cutting order (default) or as drawn\n"
    "nesting (man unroll, SHEETS):\n"
    "  --rotations N          N turns of 360/N degrees (default 4); --no-holes\n"
    "  --roll W               roll stock W mm wide, as short as it goes\n"
    "  --sheets N             at most N sheets; --remnant WxH  an offcut, filled first\n"
    "  --nest-time S --seed N the search for a better layout (default 1 s, seed 0)\n"
    "  --threads N            roll searches side by side (default one per processor)\n"
    "  --margin MM --spacing MM  free along the sheet's edges and between pieces\n"
    "  --merge-lines          parts may touch; a line two parts share is cut once\n"
    "  --report FILE.json     write a JSON report ('-' for standard output)\n"
    "  --quiet                no summary on standard error\n"
    "\n"
    "exit status: 0 success, 1 internal error, 2 bad usage or input, 3 an output\n"
    "could not be written, 4 out of memory, 130 stopped by SIGINT, 143 stopped by\n"
    "SIGTERM (nothing half-written).\n"
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
    {"strip",
     "unroll strip --rail1 C1.csv --rail2 C2.csv -o FILE.svg [OPTIONS]\n"
     "  The developable strip between two space curves: for each point of rail 1 the\n"
     "  ruling goes to the point of rail 2 where one plane touches both rails.  Parts\n"
     "  of rail 1 where no such ruling exists, or where rulings would cross (the edge\n"
     "  of regression passes between the rails), are reported and left out; each part\n"
     "  that exists becomes its own piece.\n"
     "  --pairing natural|developable  natural joins equal arc-length fractions (a\n"
     "                        general ruled surface, refused unless developable)\n"
     "  --strict              refuse a strip that does not exist along all of rail 1\n"
     "  --regression FILE.csv write the edge of regression (for 'unroll tangent --curve')\n"
     "  --adjust rail1|rail2|both  reshape the rail(s), smoothly and as little as\n"
     "                        possible, for a strip along all of rail 1; ends stay unless\n"
     "                        --adjust-ends; --adjust-direction X,Y,Z moves points along\n"
     "                        X,Y,Z only, --adjust-plane X,Y,Z keeps each point in its\n"
     "                        plane normal to X,Y,Z (0,0,1: on its floor); refused beyond\n"
     "                        --adjust-max MM (a quarter of the rails' distance)\n"
     "  --adjust-rail2        --adjust rail2 --adjust-ends, as before\n"
     "  --adjusted-rail FILE.csv  write the moved rail (rail 2 with both;\n"
     "                        --adjusted-rail1 FILE.csv writes rail 1)\n"},
    {"ruled", "unroll ruled --rail1 C1.csv --rail2 C2.csv -o FILE.svg [OPTIONS]\n"
              "  The ruled surface joining matching points of two rails (the i-th points when\n"
              "  both have as many, else equal arc-length fractions).  In general it is not\n"
              "  developable: then it is flattened with measured strain (--flatten), and the\n"
              "  note says how far it is from developable; see 'unroll analyze ruled ...'.\n"},
    {"hypar", "unroll hypar --corners X,Y,Z:X,Y,Z:X,Y,Z:X,Y,Z -o FILE.svg [OPTIONS]\n"
              "  The hyperbolic paraboloid on a skew quadrilateral, corners in order round it;\n"
              "  rulings join edge 1-2 to edge 4-3.  Not developable (K < 0), so it is\n"
              "  flattened with measured strain (--flatten), unless the corners lie in one\n"
              "  plane, when it is a flat quadrilateral and is developed exactly.\n"},
    {"analyze", "unroll analyze SURFACE SURFACE-OPTIONS [--png FILE.png] [--report FILE.json]\n"
                "  Whether the surface is developable (the angle its tangent plane turns along\n"
                "  a ruling), its Gaussian curvature K (min, max, mean, where), the smallest bend\n"
                "  radius, the area, and for strips the domain of existence and where the edge of\n"
                "  regression runs.  --png draws the surface's parameter domain coloured by K\n"
                "  (green K = 0, blue K < 0); --report writes every ruling's figures as JSON.\n"},
    {"compare", "unroll compare SURFACE SURFACE-OPTIONS [--csv FILE.csv] [--png FILE.png]\n"
                "  The paper's triangle and quad methods against the exact net for n = 8, 16,\n"
                "  ..., 4096 rulings: signed relative area error, largest rail length error and\n"
                "  largest distance to the exact net after the best rigid fit; --png plots them\n"
                "  on log-log axes.\n"},
    {"mesh", "unroll mesh FILE [--units mm|cm|m|in] [--scale S] [--seams PATH.csv] -o FILE.svg\n"
             "  A mesh (OBJ, STL, PLY, glTF, Collada, 3MF; in mm, or in the unit a Collada\n"
             "  or 3MF file declares, unless --units says), welded and repaired, cut into\n"
             "  disks along its groups, the seams given (vertex positions, one path per CSV)\n"
             "  and where needed, and flattened with measured strain.\n"
             "  --flatten charts       (default) cut at sharp edges (over 30 degrees), then\n"
             "                         into charts that each lie flat within the material's\n"
             "                         strain (--max-strain S overrides it)\n"
             "  --flatten arap|lscm    each piece whole: LSCM, then ARAP iterations\n"
             "  --flatten strips       the fewest strips within the material's strain\n"
             "                         (--max-strain S overrides it)\n"
             "  --flatten unfold       along the edges, papercraft style: every face exact,\n"
             "                         folds scored mountain and valley; --fewer-pieces\n"
             "                         joins pieces even where a tab then finds no room;\n"
             "                         --hide-folds DEG: folds gentler than DEG not drawn;\n"
             "                         --unfold-steps N: a longer search, fewer pieces\n"
             "  --iterations N         most ARAP iterations; --strain-png FILE.png the strain\n"
             "  --assembly FILE.png|pdf  where each piece goes: the mesh from four sides,\n"
             "                         pieces coloured and named, seam labels where they lie;\n"
             "                         --assembly-up y|z: the axis up (default auto: y for\n"
             "                         glTF, Collada and Blender's OBJ, z otherwise)\n"},
    {"job", "unroll job FILE.xml [-o DIR] [--quiet]\n"
            "  Runs a job file: machine, material, options, parts (any surface, with a\n"
            "  quantity) nested together, and the outputs; -o DIR overrides its directory.\n"
            "  See unroll-job(5).\n"},
    {"nest", "unroll nest FILE[:N]... -o OUT.svg [OPTIONS]\n"
             "  Nests the closed paths of SVG and DXF files made elsewhere (nested paths are\n"
             "  holes) on sheet stock; see 'unroll nest --help'.\n"},
    {"profiles", "unroll profiles            list machine and material profiles\n"
                 "unroll profiles show NAME  print one profile and the file it comes from\n"
                 "  Profiles are searched beside the command (the installed share directory,\n"
                 "  or the profiles/ of the source tree it was built in), then in\n"
                 "  $UNROLL_PROFILES, then in ./profiles.\n"},
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
                fputs("\ncommon options: see 'unroll --help'; also 'unroll analyze' and "
                      "'unroll compare'.\n",
                      stdout);
            return 0;
        }
    cli_message("help: unknown subcommand '%s'; 'unroll --help' lists them", subcommand);
    return EXIT_USAGE;
}

static int surface_command(int argc, char **argv)
{
    ur_job job;
    int code = cli_parse_job(argc, argv, CLI_DEVELOP, argv[0], &job);
    if (code == -1)
        return 0; /* help was asked for and printed */
    return code ? code : cli_run_job(&job);
}

/* unroll analyze SURFACE ... and unroll compare SURFACE ... */
static int study_command(int argc, char **argv, cli_action action)
{
    const char *command = argv[0];
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        return cli_print_help(command);
    if (argc >= 2 && strcmp(argv[1], "mesh") == 0) {
        cli_message("%s: works on ruled surfaces; a mesh's strain is in 'unroll mesh "
                    "... --report'",
                    command);
        return EXIT_USAGE;
    }
    if (argc < 2 || !cli_is_surface(argv[1])) {
        cli_message("%s: give a surface first, e.g. 'unroll %s helicoid --radius 30 ...' (see "
                    "'unroll help %s')",
                    command, command, command);
        return EXIT_USAGE;
    }
    ur_job job;
    int code = cli_parse_job(argc - 1, argv + 1, action, command, &job);
    if (code == -1)
        return 0;
    if (code)
        return code;
    return action == CLI_ANALYZE ? cli_analyze(&job) : cli_compare(&job);
}

static int dispatch(int argc, char **argv)
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
    if (strcmp(command, "nest") == 0)
        return cli_nest(argc - 1, argv + 1);
    if (strcmp(command, "job") == 0)
        return cli_job_command(argc - 1, argv + 1);
    if (cli_is_surface(command))
        return surface_command(argc - 1, argv + 1);
    if (strcmp(command, "analyze") == 0)
        return study_command(argc - 1, argv + 1, CLI_ANALYZE);
    if (strcmp(command, "compare") == 0)
        return study_command(argc - 1, argv + 1, CLI_COMPARE);
    cli_message("unknown subcommand '%s'; 'unroll --help' lists them", command);
    return EXIT_USAGE;
}

int main(int argc, char **argv)
{
    if (!cli_context_open()) {
        cli_message("out of memory");
        return EXIT_MEMORY;
    }
    ur_context_set_profile_roots(cli_context(), cli_profile_roots());
    if (!cli_catch_signals()) {
        cli_message("cannot install the SIGINT and SIGTERM handlers");
        cli_context_close();
        return EXIT_INTERNAL;
    }
    int code = cli_signal_exit(dispatch(argc, argv));
    cli_context_close();
    return code;
}
