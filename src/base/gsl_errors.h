/*
 * gsl_errors.h: GSL's error handler turned off for the calls into GSL, and
 * the caller's put back after them.
 *
 * GSL's default handler aborts the program on any error (a spline through
 * repeated knots, a quadrature that does not converge, an allocation that
 * fails).  The library checks the status of every GSL call instead, so each
 * function that calls GSL brackets those calls with gsl_errors_off and
 * gsl_errors_restore: a host program's own handler (or GSL's default)
 * is back in place once the library returns.
 */
#ifndef UNROLL_BASE_GSL_ERRORS_H
#define UNROLL_BASE_GSL_ERRORS_H

/* GSL's handler off; pairs with one gsl_errors_restore.  Brackets may nest. */
void gsl_errors_off(void);

/* Puts back the handler the outermost gsl_errors_off found. */
void gsl_errors_restore(void);

#endif
