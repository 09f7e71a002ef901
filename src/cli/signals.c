/*
 * signals.c: the command's one library context, whose message handler
 * prints the library's warnings and notes, and SIGINT and SIGTERM
 * stopping a run cleanly.  The handler only cancels the context
 * (ur_context_cancel): the long loops notice at their
 * next check and every writer removes its temporary files, so nothing is
 * left half-written; the command then exits with 128 + the signal's number.
 * The handler is installed for one signal only (SA_RESETHAND): a second
 * SIGINT kills at once, for a run that does not reach a check soon enough.
 */
#include "cli.h"

#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static volatile sig_atomic_t caught = 0;

/* Read by the handler, which may only touch lock-free atomics. */
static _Atomic(ur_context *) run_context = NULL;

#if ATOMIC_POINTER_LOCK_FREE != 2
#error "the signal handler needs a lock-free atomic pointer"
#endif

static void on_signal(int number)
{
    caught = number;
    ur_context_cancel(atomic_load(&run_context));
}

/*
 * For the tests only: UNROLL_TEST_FAIL_WRITE_AFTER=N makes every write of
 * the run fail once N bytes in all were written, as on a full disk.
 */
static void set_test_hooks(ur_context *context)
{
    const char *value = getenv("UNROLL_TEST_FAIL_WRITE_AFTER");
    char *end = NULL;
    long long bytes = value ? strtoll(value, &end, 10) : -1;
    if (value && end != value && *end == '\0' && bytes >= 0)
        ur_context_fail_writes_after(context, bytes);
}

/*
 * Every warning and note of the library, as it words them, its settings
 * as flags: "unroll: strip: warning: ... (--no-split refuses instead)".
 */
static void print_message(void *data, ur_message_kind kind, const char *message,
                          const char *setting)
{
    (void)data;
    (void)kind;
    char flagged[8192];
    cli_with_flags(message, setting, flagged, sizeof flagged);
    cli_message("%s", flagged);
}

bool cli_context_open(void)
{
    ur_context *context = ur_context_new();
    if (!context)
        return false;
    ur_context_set_message_handler(context, print_message, NULL);
    set_test_hooks(context);
    atomic_store(&run_context, context);
    return true;
}

ur_context *cli_context(void)
{
    return atomic_load(&run_context);
}

void cli_context_close(void)
{
    ur_context_free(atomic_exchange(&run_context, NULL));
}

bool cli_catch_signals(void)
{
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = on_signal;
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    if (sigemptyset(&action.sa_mask) != 0)
        return false;
    return sigaction(SIGINT, &action, NULL) == 0 && sigaction(SIGTERM, &action, NULL) == 0;
}

int cli_signal_exit(int code)
{
    int number = caught;
    if (number == 0)
        return code;
    const char *name = number == SIGINT ? "SIGINT" : "SIGTERM";
    if (code == 0)
        cli_message("stopped by %s after the work was done: what was written is complete", name);
    else
        cli_message("stopped by %s: no file was left half-written", name);
    return 128 + number;
}
