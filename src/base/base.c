/*
 * base.c: error messages and operation names, shared by every module.
 */
#include "unroll/base.h"

#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "c_locale.h"

ur_status ur_error_set(ur_error *error, ur_status status, const char *format, ...)
{
    if (error) {
        va_list args;
        va_start(args, format);
        c_vsnprintf(error->message, sizeof error->message, format, args);
        va_end(args);
        error->status = status;
        error->setting[0] = '\0';
    }
    return status;
}

ur_status ur_error_set_setting(ur_error *error, const char *setting)
{
    if (!error)
        return UR_ERROR_INPUT;
    c_snprintf(error->setting, sizeof error->setting, "%s", setting ? setting : "");
    return error->status;
}

ur_status ur_error_prefix(ur_error *error, const char *format, ...)
{
    if (!error)
        return UR_ERROR_INTERNAL;
    char combined[sizeof error->message];
    va_list args;
    va_start(args, format);
    c_vsnprintf(combined, sizeof combined, format, args);
    va_end(args);
    /* Messages are short; whatever does not fit is cut off at the end. */
    size_t used = strlen(combined);
    size_t room = sizeof combined - used - 1;
    size_t old_length = strnlen(error->message, sizeof error->message);
    if (old_length > room)
        old_length = room;
    memcpy(combined + used, error->message, old_length);
    combined[used + old_length] = '\0';
    memcpy(error->message, combined, sizeof combined);
    return error->status;
}

void ur_error_clear(ur_error *error)
{
    if (error) {
        error->status = UR_OK;
        error->message[0] = '\0';
        error->setting[0] = '\0';
    }
}

ur_status ur_error_out_of_memory(ur_error *error)
{
    return ur_error_set(error, UR_ERROR_MEMORY, "out of memory");
}

static const char *const op_names[UR_OP_COUNT] = {"cut",  "score",   "score-valley",
                                                  "kerf", "engrave", "mark"};

const char *ur_op_name(ur_op op)
{
    return op < UR_OP_COUNT ? op_names[op] : "unknown";
}

ur_op ur_op_from_name(const char *name)
{
    for (int op = 0; op < UR_OP_COUNT; op++)
        if (strcmp(name, op_names[op]) == 0)
            return (ur_op)op;
    return UR_OP_COUNT;
}

void *ur_array_grow(void *items, size_t *capacity, size_t count, size_t item_size, size_t first,
                    ur_error *error)
{
    if (count < *capacity)
        return items;
    size_t grown = *capacity ? 2 * *capacity : first;
    void *memory = grown <= SIZE_MAX / item_size ? realloc(items, grown * item_size) : NULL;
    if (!memory) {
        ur_error_out_of_memory(error);
        return NULL;
    }
    *capacity = grown;
    return memory;
}

void *ur_alloc_array(size_t count, size_t size, ur_error *error)
{
    if (count == 0)
        count = 1;
    void *memory = calloc(count, size);
    if (!memory)
        ur_error_out_of_memory(error);
    return memory;
}
