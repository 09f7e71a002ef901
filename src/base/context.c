/*
 * context.c: the context a run happens in (unroll/base.h): its cancel
 * flag, its message handler and its test hook.  Its output set is kept by
 * atomic.c, which writes the files.
 */
#include "context.h"

#include "atomic.h"
#include "c_locale.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

ur_context *ur_context_new(void)
{
    ur_context *context = calloc(1, sizeof *context);
    if (!context)
        return NULL;
    atomic_init(&context->cancelled, 0);
    context->write_budget = -1;
    return context;
}

void ur_context_free(ur_context *context)
{
    if (!context)
        return;
    atomic_set_discard(context);
    free(context);
}

void ur_context_cancel(ur_context *context)
{
    if (context)
        atomic_store(&context->cancelled, 1);
}

void ur_context_cancel_clear(ur_context *context)
{
    if (context)
        atomic_store(&context->cancelled, 0);
}

bool ur_context_cancelled(const ur_context *context)
{
    /* atomic_load takes a pointer to non-const in C11 before DR 459. */
    return context && atomic_load((atomic_int *)&context->cancelled) != 0;
}

ur_status ur_context_check(const ur_context *context, ur_error *error)
{
    if (!ur_context_cancelled(context))
        return UR_OK;
    return ur_error_set(error, UR_ERROR_CANCELLED, "cancelled");
}

void ur_context_set_message_handler(ur_context *context, ur_message_handler handler, void *data)
{
    if (!context)
        return;
    context->message_handler = handler;
    context->message_data = data;
}

void ur_context_message_handler(const ur_context *context, ur_message_handler *handler, void **data)
{
    *handler = context ? context->message_handler : NULL;
    *data = context ? context->message_data : NULL;
}

static void message_about(const ur_context *context, ur_message_kind kind, const char *setting,
                          const char *format, va_list args)
{
    char message[8192]; /* a warning may name many pieces and paths */
    c_vsnprintf(message, sizeof message, format, args);
    context->message_handler(context->message_data, kind, message, setting ? setting : "");
}

void ur_context_message(const ur_context *context, ur_message_kind kind, const char *format, ...)
{
    if (!context || !context->message_handler)
        return;
    va_list args;
    va_start(args, format);
    message_about(context, kind, "", format, args);
    va_end(args);
}

void ur_context_message_about(const ur_context *context, ur_message_kind kind, const char *setting,
                              const char *format, ...)
{
    if (!context || !context->message_handler)
        return;
    va_list args;
    va_start(args, format);
    message_about(context, kind, setting, format, args);
    va_end(args);
}

void ur_context_set_profile_roots(ur_context *context, const char *const *roots)
{
    if (context)
        context->profile_roots = roots;
}

const char *const *ur_context_profile_roots(const ur_context *context)
{
    static const char *const none[] = {NULL};
    return context && context->profile_roots ? context->profile_roots : none;
}

void ur_context_fail_writes_after(ur_context *context, long long bytes)
{
    if (context)
        context->write_budget = bytes < 0 ? -1 : bytes;
}
