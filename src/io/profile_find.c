/*
 * profile_find.c: where the profiles are: the roots the caller gives,
 * finding a profile or a schema by name in them, loading a profile by
 * name, and listing every profile found (profile.c reads one).
 */
#include "unroll/io.h"

#include "io_internal.h"
#include "xml_errors.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <libxml/parser.h>
#include <libxml/relaxng.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include "../base/c_locale.h"

#define PROFILE_PATH_MAX 1024

static const char *profile_kind_folder(ur_profile_kind kind)
{
    return kind == UR_PROFILE_MACHINE ? "machines" : "materials";
}

const char *profile_kind_word(ur_profile_kind kind)
{
    return kind == UR_PROFILE_MACHINE ? "machine" : "material";
}

/* ---- Search path ------------------------------------------------------- */

/*
 * The caller's roots, in search order: a NULL-terminated list (NULL for
 * none).  A root that does not exist is simply empty.  The library reads no
 * environment variable and no directory of its own: the command decides
 * where profiles are (unroll(1), PROFILES).
 */

/* "DIR1, DIR2, ...", for "not found" messages. */
static void describe_roots(const char *const *roots, char *text, size_t size)
{
    size_t used = 0;
    text[0] = '\0';
    for (const char *const *root = roots; root && *root && used < size; root++) {
        int length = c_snprintf(text + used, size - used, "%s%s", used ? ", " : "", *root);
        if (length < 0)
            break;
        used += (size_t)length;
    }
    if (!text[0])
        c_snprintf(text, size, "no profile directory given");
}

static ur_status join_path(char *out, size_t size, const char *root, const char *folder,
                           const char *file, ur_error *error)
{
    int length = c_snprintf(out, size, "%s/%s/%s", root, folder, file);
    if (length < 0 || (size_t)length >= size)
        return ur_error_set(error, UR_ERROR_INPUT, "%s/%s: path too long", root, folder);
    return UR_OK;
}

/* [A-Za-z0-9._-]+ not starting with '.': no way out of the profile folder. */
static bool valid_name(const char *name)
{
    size_t length = strlen(name);
    if (length == 0 || length >= sizeof(((ur_machine *)0)->name) || name[0] == '.')
        return false;
    for (size_t i = 0; i < length; i++) {
        char c = name[i];
        bool allowed = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                       c == '.' || c == '_' || c == '-';
        if (!allowed)
            return false;
    }
    return true;
}

static ur_status check_name(ur_profile_kind kind, const char *name, ur_error *error)
{
    if (valid_name(name))
        return UR_OK;
    return ur_error_set(error, UR_ERROR_INPUT,
                        "bad %s name '%.64s': use up to 63 letters, digits, '.', '_' and '-', "
                        "not starting with '.'",
                        profile_kind_word(kind), name);
}

ur_status ur_profile_find(const char *const *roots, ur_profile_kind kind, const char *name,
                          char *path, size_t path_size, ur_error *error)
{
    ur_status status = check_name(kind, name, error);
    if (status != UR_OK)
        return status;
    char file[80];
    c_snprintf(file, sizeof file, "%s.xml", name);
    for (const char *const *root = roots; root && *root; root++) {
        char candidate[PROFILE_PATH_MAX];
        status =
            join_path(candidate, sizeof candidate, *root, profile_kind_folder(kind), file, error);
        if (status != UR_OK)
            return status;
        struct stat info;
        if (stat(candidate, &info) == 0) {
            if (strlen(candidate) >= path_size)
                return ur_error_set(error, UR_ERROR_INPUT, "%s: path too long", candidate);
            strcpy(path, candidate);
            return UR_OK;
        }
        /* Anything but "not there" would hide a profile: say so. */
        if (errno != ENOENT && errno != ENOTDIR)
            return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot open: %s", candidate,
                                strerror(errno));
    }
    char searched[PROFILE_PATH_MAX];
    describe_roots(roots, searched, sizeof searched);
    return ur_error_set(error, UR_ERROR_INPUT,
                        "unknown %s '%s' (searched %s); 'unroll profiles' lists them",
                        profile_kind_word(kind), name, searched);
}

/* ROOT/schema/KIND.rng from the first root that has it. */
ur_status profile_find_schema(const char *const *roots, const char *word, char *path, size_t size,
                              ur_error *error)
{
    char file[32];
    c_snprintf(file, sizeof file, "%s.rng", word);
    for (const char *const *root = roots; root && *root; root++) {
        ur_status status = join_path(path, size, *root, "schema", file, error);
        if (status != UR_OK)
            return status;
        if (access(path, R_OK) == 0)
            return UR_OK;
    }
    char searched[PROFILE_PATH_MAX];
    describe_roots(roots, searched, sizeof searched);
    /* The schemas ship with unroll: without them the installation is broken. */
    return ur_error_set(error, UR_ERROR_INTERNAL, "no schema/%s in any profile root (searched %s)",
                        file, searched);
}

/* ---- Loading by name --------------------------------------------------- */

ur_status ur_machine_load(const char *const *roots, const char *name, ur_machine *machine,
                          ur_error *error)
{
    char path[PROFILE_PATH_MAX];
    ur_status status = ur_profile_find(roots, UR_PROFILE_MACHINE, name, path, sizeof path, error);
    if (status != UR_OK)
        return status;
    return ur_machine_read(roots, path, machine, error);
}

ur_status ur_material_load(const char *const *roots, const char *name, ur_material *material,
                           ur_error *error)
{
    char path[PROFILE_PATH_MAX];
    ur_status status = ur_profile_find(roots, UR_PROFILE_MATERIAL, name, path, sizeof path, error);
    if (status != UR_OK)
        return status;
    return ur_material_read(roots, path, material, error);
}

double ur_effective_kerf(const ur_machine *machine, const ur_material *material)
{
    if (material) {
        double kerf =
            machine->kind == UR_MACHINE_LASER ? material->kerf_laser : material->kerf_router;
        if (kerf > 0.0)
            return kerf;
    }
    return machine->kerf;
}

/* ---- Listing ----------------------------------------------------------- */

typedef struct entry_list {
    ur_profile_entry *items;
    size_t count, capacity;
} entry_list;

static bool entry_listed(const entry_list *list, ur_profile_kind kind, const char *name)
{
    for (size_t i = 0; i < list->count; i++)
        if (list->items[i].kind == kind && strcmp(list->items[i].name, name) == 0)
            return true;
    return false;
}

static ur_status entry_list_grow(entry_list *list, ur_error *error)
{
    if (list->count < list->capacity)
        return UR_OK;
    size_t capacity = list->capacity ? 2 * list->capacity : 16;
    if (capacity > SIZE_MAX / sizeof(ur_profile_entry))
        return ur_error_out_of_memory(error);
    ur_profile_entry *items = realloc(list->items, capacity * sizeof *items);
    if (!items)
        return ur_error_out_of_memory(error);
    list->items = items;
    list->capacity = capacity;
    return UR_OK;
}

/* "(invalid: MESSAGE)", shortened with "..." to fit the description. */
static void describe_invalid(char *out, size_t size, const char *message)
{
    static const char head[] = "(invalid: ", tail[] = ")", dots[] = "...";
    size_t room = size - sizeof head - sizeof tail - sizeof dots + 2;
    size_t length = strlen(message);
    bool shortened = length > room;
    if (shortened)
        length = room;
    memcpy(out, head, sizeof head - 1);
    memcpy(out + sizeof head - 1, message, length);
    char *end = out + sizeof head - 1 + length;
    if (shortened) {
        memcpy(end, dots, sizeof dots - 1);
        end += sizeof dots - 1;
    }
    memcpy(end, tail, sizeof tail);
}

/* Reads a profile only for its description; a bad file is listed, not hidden. */
static void describe_entry(const char *const *roots, ur_profile_entry *entry)
{
    ur_error error = {0};
    ur_status status;
    if (entry->kind == UR_PROFILE_MACHINE) {
        ur_machine machine;
        status = ur_machine_read(roots, entry->source, &machine, &error);
        if (status == UR_OK)
            strcpy(entry->description, machine.description);
    } else {
        ur_material material;
        status = ur_material_read(roots, entry->source, &material, &error);
        if (status == UR_OK)
            strcpy(entry->description, material.description);
    }
    if (status != UR_OK)
        describe_invalid(entry->description, sizeof entry->description, error.message);
}

static ur_status add_entry(const char *const *roots, entry_list *list, ur_profile_kind kind,
                           const char *folder, const char *file, size_t stem_length,
                           ur_error *error)
{
    char name[sizeof list->items[0].name];
    if (stem_length >= sizeof name)
        stem_length = sizeof name - 1;
    memcpy(name, file, stem_length);
    name[stem_length] = '\0';
    /* An earlier root has this name: that one hides this one. */
    if (entry_listed(list, kind, name))
        return UR_OK;
    ur_status status = entry_list_grow(list, error);
    if (status != UR_OK)
        return status;
    ur_profile_entry *entry = &list->items[list->count];
    memset(entry, 0, sizeof *entry);
    entry->kind = kind;
    strcpy(entry->name, name);
    int length = c_snprintf(entry->source, sizeof entry->source, "%s/%s", folder, file);
    if (length < 0 || (size_t)length >= sizeof entry->source)
        return ur_error_set(error, UR_ERROR_INPUT, "%s/%s: path too long", folder, file);
    if (valid_name(entry->name) && strlen(file) == stem_length + 4)
        describe_entry(roots, entry);
    else
        describe_invalid(entry->description, sizeof entry->description,
                         "the file name is not a usable profile name");
    list->count++;
    return UR_OK;
}

/* Adds every ROOT/FOLDER/NAME.xml; dot files are hidden, as ls does. */
static ur_status list_folder(const char *const *roots, const char *root, ur_profile_kind kind,
                             entry_list *list, ur_error *error)
{
    char folder[PROFILE_PATH_MAX];
    int length = c_snprintf(folder, sizeof folder, "%s/%s", root, profile_kind_folder(kind));
    if (length < 0 || (size_t)length >= sizeof folder)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: path too long", root);
    DIR *dir = opendir(folder);
    if (!dir) {
        if (errno == ENOENT || errno == ENOTDIR)
            return UR_OK;
        return ur_error_set(error, UR_ERROR_INPUT, "%s: cannot list: %s", folder, strerror(errno));
    }
    ur_status status = UR_OK;
    for (struct dirent *item = readdir(dir); item && status == UR_OK; item = readdir(dir)) {
        size_t name_length = strlen(item->d_name);
        if (item->d_name[0] == '.' || name_length <= 4 ||
            strcmp(item->d_name + name_length - 4, ".xml") != 0)
            continue;
        status = add_entry(roots, list, kind, folder, item->d_name, name_length - 4, error);
    }
    closedir(dir);
    return status;
}

static int compare_entries(const void *a, const void *b)
{
    const ur_profile_entry *left = a, *right = b;
    if (left->kind != right->kind)
        return left->kind < right->kind ? -1 : 1;
    return strcmp(left->name, right->name);
}

ur_status ur_profile_list(const char *const *roots, ur_profile_entry **entries, size_t *count,
                          ur_error *error)
{
    *entries = NULL;
    *count = 0;
    entry_list list = {0};
    static const ur_profile_kind kinds[] = {UR_PROFILE_MACHINE, UR_PROFILE_MATERIAL};
    for (size_t k = 0; k < 2; k++) {
        for (const char *const *root = roots; root && *root; root++) {
            ur_status status = list_folder(roots, *root, kinds[k], &list, error);
            if (status != UR_OK) {
                free(list.items);
                return status;
            }
        }
    }
    if (list.count > 1)
        qsort(list.items, list.count, sizeof *list.items, compare_entries);
    *entries = list.items;
    *count = list.count;
    return UR_OK;
}
