/*
 * profiles.c: "unroll profiles" lists the profiles on the search path and
 * "unroll profiles show NAME" prints one with the file it comes from.
 */
#include "cli.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/io.h"

static int list_profiles(void)
{
    ur_profile_entry *entries = NULL;
    size_t count = 0;
    ur_error error;
    if (ur_profile_list(&entries, &count, &error) != UR_OK) {
        cli_message("profiles: %s", error.message);
        return cli_exit_status(&error);
    }
    for (size_t k = 0; k < count; k++)
        printf("%-9s %-22s %s\n          %s\n",
               entries[k].kind == UR_PROFILE_MACHINE ? "machine" : "material", entries[k].name,
               entries[k].description, entries[k].source);
    free(entries);
    return 0;
}

static int copy_to_stdout(const char *path)
{
    FILE *file = fopen(path, "r");
    if (!file) {
        cli_message("profiles: cannot open '%s': %s", path, strerror(errno));
        return EXIT_USAGE;
    }
    char buffer[8192];
    size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, file)) > 0)
        fwrite(buffer, 1, n, stdout);
    int failed = ferror(file);
    fclose(file);
    return failed ? EXIT_INTERNAL : 0;
}

static int show_profile(const char *name)
{
    char path[4096];
    ur_error error;
    ur_status status = ur_profile_find(UR_PROFILE_MACHINE, name, path, sizeof path, &error);
    if (status != UR_OK)
        status = ur_profile_find(UR_PROFILE_MATERIAL, name, path, sizeof path, &error);
    if (status != UR_OK) {
        cli_message("profiles: no machine or material profile named '%s'; 'unroll profiles' "
                    "lists them",
                    name);
        return EXIT_USAGE;
    }
    printf("<!-- %s -->\n", path);
    return copy_to_stdout(path);
}

int cli_profiles(int argc, char **argv)
{
    if (argc == 1)
        return list_profiles();
    if (argc == 3 && strcmp(argv[1], "show") == 0)
        return show_profile(argv[2]);
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        return cli_print_help("profiles");
    cli_message("profiles: usage: unroll profiles [show NAME]");
    return EXIT_USAGE;
}
