/*
 * signals.c: SIGINT and SIGTERM stop a run cleanly.  The handler only asks
 * the library to cancel (ur_cancel_request): the long loops notice at their
 * next check and every writer removes its temporary files, so nothing is
 * left half-written; the command then exits with 128 + the signal's number.
 * The handler is installed for one signal only (SA_RESETHAND): a second
 * SIGINT kills at once, for a run that does not reach a check soon enough.
 */
#include "cli.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>

static volatile sig_atomic_t caught = 0;

static void on_signal(int number)
{
    caught = number;
    ur_cancel_request();
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
