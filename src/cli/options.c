/*
 * options.c: parsing a surface subcommand's options with getopt_long into
 * a job, each through the library's settings (ur_job_option_set), whose
 * message this prefixes with the option: "unroll helicoid: --radius: 'x'
 * is not a finite number".  Which options an action takes (develop,
 * analyze, compare) is the command's to say.
 */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The command's own options; the library's settings follow them in the getopt table. */
static const struct option own_options[] = {
    {"help", no_argument, NULL, 'h'},
    {NULL, 0, NULL, 0},
};

/* The surfaces, each a subcommand. */
static const char *const surfaces[] = {"cylinder", "cone",  "helicoid", "tangent",
                                       "strip",    "ruled", "hypar",    "mesh"};

/* Options that belong to one action only. */
static const struct {
    cli_action action;
    const char *options;
} action_options[] = {
    {CLI_DEVELOP,
     " output machine material sheet margin spacing method parts rulings no-split report "
     "strain-png assembly assembly-up surface allowances bridges no-kerf-compensation format "
     "dxf-version dpi job-name order rotations no-holes merge-lines roll sheets remnant "
     "nest-time seed threads "},
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
    for (size_t k = 0; k < sizeof surfaces / sizeof surfaces[0]; k++)
        if (strcmp(surfaces[k], name) == 0)
            return true;
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

/*
 * Handles one of the library's settings: whether it applies to the
 * surface and to the action (the messages name the option), then its
 * value; false after a message.
 */
static bool take_option(ur_job *job, cli_action action, const char *name, const char *value)
{
    if (!ur_job_option_applies(name, job->surface)) {
        cli_message("%s: --%s does not apply to a %s (see 'unroll help %s')", job->command, name,
                    job->surface, job->surface);
        return false;
    }
    if (foreign_to_action(action, name)) {
        cli_message("%s: --%s does not apply to '%s' (see 'unroll help %s')", job->command, name,
                    action_name(action), job->command);
        return false;
    }
    return cli_set_option(job, name, value);
}

int cli_parse_job(int argc, char **argv, cli_action action, const char *command, ur_job *job)
{
    ur_job_init(job, argv[0]);
    job->context = cli_context();
    job->command = command;
    opterr = 0;
    optind = 1;
    int id;
    struct option table[128];
    cli_option_table(own_options, true, table, sizeof table / sizeof table[0]);
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
        const char *name = id == 'o'   ? "output"
                           : id == 'n' ? "parts"
                                       : ur_job_option_name((size_t)(id - CLI_SHARED_OPTION), NULL);
        if (!take_option(job, action, name, optarg))
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
    ur_error error;
    if (ur_job_check(job, &error) != UR_OK) {
        cli_error(NULL, &error);
        return EXIT_USAGE;
    }
    return 0;
}
