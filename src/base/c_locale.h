/*
 * c_locale.h: numbers in files are written and read the same whatever the
 * locale of the program that calls the library.
 *
 * printf and strtod follow the calling thread's LC_NUMERIC: a host program
 * that called setlocale(LC_ALL, "") in a comma-decimal locale (de_DE) would
 * write "1,5" into an SVG and read "1.5" as 1.  Every printf-family call and
 * every strtod of the library goes through these instead: each switches the
 * calling thread to the "C" locale for the one call (POSIX uselocale) and
 * switches back, so it is thread-safe and leaves the caller's locale as it
 * was.
 */
#ifndef UNROLL_BASE_C_LOCALE_H
#define UNROLL_BASE_C_LOCALE_H

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#if defined(__GNUC__)
#define PRINTF_LIKE(format_index, first_argument)                                                  \
    __attribute__((format(printf, format_index, first_argument)))
#else
#define PRINTF_LIKE(format_index, first_argument)
#endif

/* snprintf, vsnprintf and fprintf in the "C" locale. */
int c_snprintf(char *text, size_t size, const char *format, ...) PRINTF_LIKE(3, 4);
int c_vsnprintf(char *text, size_t size, const char *format, va_list arguments) PRINTF_LIKE(3, 0);
int c_fprintf(FILE *stream, const char *format, ...) PRINTF_LIKE(2, 3);

/* strtod in the "C" locale: '.' is the decimal point. */
double c_strtod(const char *text, char **end);

#endif
