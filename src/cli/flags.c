/*
 * flags.c: the library's messages in the command's words.  The library
 * names a setting by its name ("cone: top-radius must be ...") and lists
 * the names a message uses in ur_error's setting (or the message
 * handler's); the command writes each as its flag, "--top-radius".
 */
#include "cli.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* A character that may be part of a setting's name, or of a path or a file's name. */
static bool in_word(const char *at)
{
    return isalnum((unsigned char)*at) || *at == '-' || *at == '_' || *at == '/' ||
           (*at == '.' && isalnum((unsigned char)at[1]));
}

/*
 * The index among setting's names (space-separated) of the one message
 * holds at at as a whole word, not yet flagged (bit k of *flagged); -1
 * for none.
 */
static int setting_at(const char *message, const char *at, const char *setting, unsigned *flagged,
                      size_t *length)
{
    if (at > message && in_word(at - 1))
        return -1;
    const char *name = setting;
    for (int k = 0; *name && k < 32; k++) {
        *length = strcspn(name, " ");
        if (*length > 0 && !(*flagged & 1u << k) && strncmp(at, name, *length) == 0 &&
            !in_word(at + *length)) {
            *flagged |= 1u << k;
            return k;
        }
        name += *length;
        name += strspn(name, " ");
    }
    return -1;
}

/*
 * Where the flags go of the settings the message does not name as words:
 * after "COMMAND: " and "warning: " or "note: ", else in front.
 */
static size_t flag_place(const char *message)
{
    size_t place = 0;
    size_t word = strcspn(message, " :");
    if (message[word] == ':' && message[word + 1] == ' ')
        place = word + 2;
    if (strncmp(message + place, "warning: ", 9) == 0)
        place += 9;
    else if (strncmp(message + place, "note: ", 6) == 0)
        place += 6;
    return place;
}

/* Appends what format says to text at *used, counting what did not fit too. */
static void append(char *text, size_t size, size_t *used, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    int written = vsnprintf(text + *used, *used < size ? size - *used : 0, format, args);
    va_end(args);
    if (written > 0)
        *used += (size_t)written;
}

/* The flags of the names of setting whose bit is clear in named, each with ": " after it. */
static void append_unnamed(char *text, size_t size, size_t *used, const char *setting,
                           unsigned named)
{
    const char *name = setting;
    for (int k = 0; *name && k < 32; k++) {
        size_t length = strcspn(name, " ");
        if (length > 0 && !(named & 1u << k))
            append(text, size, used, "--%.*s: ", (int)length, name);
        name += length;
        name += strspn(name, " ");
    }
}

void cli_with_flags(const char *message, const char *setting, char *text, size_t size)
{
    unsigned named = 0;
    size_t length = 0;
    for (const char *at = message; *at; at++)
        setting_at(message, at, setting, &named, &length);
    size_t place = flag_place(message);
    unsigned flagged = 0;
    size_t used = 0;
    text[0] = '\0';
    for (const char *at = message;; at++) {
        if ((size_t)(at - message) == place)
            append_unnamed(text, size, &used, setting, named);
        if (!*at)
            break;
        if (setting_at(message, at, setting, &flagged, &length) >= 0) {
            append(text, size, &used, "--%.*s", (int)length, at);
            at += length - 1;
        } else {
            append(text, size, &used, "%c", *at);
        }
    }
}

void cli_error(const char *command, const ur_error *error)
{
    char message[sizeof error->message + 64];
    snprintf(message, sizeof message, "%s%s%s", command ? command : "", command ? ": " : "",
             error->message);
    char text[sizeof message + 256];
    cli_with_flags(message, error->setting, text, sizeof text);
    cli_message("%s", text);
}
