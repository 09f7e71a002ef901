/*
 * profiles.c: where the command finds its profiles, whatever the working
 * directory; "unroll profiles" lists the profiles found there and "unroll
 * profiles show NAME" prints one with the file it comes from.
 */
#include "cli.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unroll/io.h"

/*
 * The root beside the executable, made absolute: PREFIX/share/unroll/profiles
 * for PREFIX/bin/unroll, installed; else the repository's profiles/ for
 * build/release/unroll (or build/sanitize/unroll), built.  Each must hold a
 * schema/ folder to count.  False when neither does.
 */
static bool root_beside_executable(char *root, size_t size)
{
    char directory[PATH_MAX];
    ssize_t length = readlink("/proc/self/exe", directory, sizeof directory - 1);
    if (length <= 0)
        return false;
    directory[length] = '\0';
    char *slash = strrchr(directory, '/');
    if (!slash)
        return false;
    *slash = '\0';
    static const char *const beside[] = {"../share/unroll/profiles", "../../profiles"};
    for (size_t k = 0; k < sizeof beside / sizeof beside[0]; k++) {
        char candidate[PATH_MAX + 64], resolved[PATH_MAX];
        snprintf(candidate, sizeof candidate, "%s/%s/schema", directory, beside[k]);
        struct stat info;
        if (!realpath(candidate, resolved) || stat(resolved, &info) != 0 || !S_ISDIR(info.st_mode))
            continue;
        resolved[strlen(resolved) - strlen("/schema")] = '\0';
        if (strlen(resolved) >= size)
            continue;
        strcpy(root, resolved);
        return true;
    }
    return false;
}

const char *const *cli_profile_roots(void)
{
    static char beside[PATH_MAX];
    static const char *roots[4];
    static bool found;
    if (found)
        return roots;
    found = true;
    size_t count = 0;
    if (root_beside_executable(beside, sizeof beside))
        roots[count++] = beside;
    const char *environment = getenv("UNROLL_PROFILES");
    if (environment && *environment)
        roots[count++] = environment;
    roots[count++] = "./profiles";
    roots[count] = NULL;
    return roots;
}

static int list_profiles(void)
{
    ur_profile_entry *entries = NULL;
    size_t count = 0;
    ur_error error;
    if (ur_profile_list(cli_profile_roots(), &entries, &count, &error) != UR_OK) {
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
    const char *const *roots = cli_profile_roots();
    ur_status status = ur_profile_find(roots, UR_PROFILE_MACHINE, name, path, sizeof path, &error);
    if (status != UR_OK)
        status = ur_profile_find(roots, UR_PROFILE_MATERIAL, name, path, sizeof path, &error);
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
