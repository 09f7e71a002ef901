/*
 * gsl_errors.c: GSL's error handler off while the library calls GSL
 * (gsl_errors.h says why).
 *
 * GSL keeps one handler for the whole process, so bracketing must count
 * across threads: were each bracket to save and restore on its own, one
 * thread leaving could put back the aborting handler while another is
 * still inside GSL.  The first bracket to open saves the caller's handler
 * and turns GSL's off; the last to close puts it back.  This count is the
 * one piece of process-wide state here, as GSL's handler itself is.
 */
#include "gsl_errors.h"

#include <pthread.h>
#include <stddef.h>

#include <gsl/gsl_errno.h>

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static size_t open_brackets;               /* guarded by lock */
static gsl_error_handler_t *saved_handler; /* guarded by lock: the caller's, while open */

void gsl_errors_off(void)
{
    pthread_mutex_lock(&lock);
    if (open_brackets++ == 0)
        saved_handler = gsl_set_error_handler_off();
    pthread_mutex_unlock(&lock);
}

void gsl_errors_restore(void)
{
    pthread_mutex_lock(&lock);
    if (open_brackets > 0 && --open_brackets == 0)
        gsl_set_error_handler(saved_handler);
    pthread_mutex_unlock(&lock);
}
