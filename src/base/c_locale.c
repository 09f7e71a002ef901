/*
 * c_locale.c: printf and strtod in the "C" locale, one call at a time
 * (c_locale.h says why).
 */
#include "c_locale.h"

#include <errno.h>
#include <locale.h>
#include <stdlib.h>

/*
 * The calling thread's locale becomes "C"; returns what to hand to
 * leave_c_locale.  When the "C" locale cannot be made (out of memory, which
 * glibc never is here: it hands out a static object), the call runs in the
 * caller's locale, as it did before.
 */
typedef struct locale_switch {
    locale_t c_locale; /* (locale_t)0 when not switched */
    locale_t previous;
} locale_switch;

static locale_switch enter_c_locale(void)
{
    locale_switch s = {newlocale(LC_ALL_MASK, "C", (locale_t)0), (locale_t)0};
    if (s.c_locale)
        s.previous = uselocale(s.c_locale);
    return s;
}

static void leave_c_locale(locale_switch s)
{
    if (s.c_locale) {
        uselocale(s.previous);
        freelocale(s.c_locale);
    }
}

int c_vsnprintf(char *text, size_t size, const char *format, va_list arguments)
{
    locale_switch s = enter_c_locale();
    int written = vsnprintf(text, size, format, arguments);
    leave_c_locale(s);
    return written;
}

int c_snprintf(char *text, size_t size, const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    int written = c_vsnprintf(text, size, format, arguments);
    va_end(arguments);
    return written;
}

int c_fprintf(FILE *stream, const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    locale_switch s = enter_c_locale();
    int written = vfprintf(stream, format, arguments);
    leave_c_locale(s);
    va_end(arguments);
    return written;
}

double c_strtod(const char *text, char **end)
{
    locale_switch s = enter_c_locale();
    double value = strtod(text, end);
    int strtod_errno = errno; /* ERANGE, which callers may check */
    leave_c_locale(s);
    errno = strtod_errno;
    return value;
}
