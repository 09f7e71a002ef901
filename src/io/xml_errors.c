/*
 * xml_errors.c: libxml2's messages caught for one call and its handlers
 * restored (xml_errors.h says why).
 */
#include "xml_errors.h"

#include <ctype.h>
#include <limits.h>
#include <string.h>

#include <libxml/parser.h>

#include "../base/c_locale.h"

static void strip_trailing_space(char *text)
{
    size_t length = strlen(text);
    while (length > 0 && isspace((unsigned char)text[length - 1]))
        text[--length] = '\0';
}

void io_xml_collect_error(void *context, io_xml_error *xml_error)
{
    io_xml_report *report = context;
    if (report->have || !xml_error || xml_error->level == XML_ERR_WARNING)
        return;
    report->have = true;
    report->line = xml_error->line;
    c_snprintf(report->file, sizeof report->file, "%s", xml_error->file ? xml_error->file : "");
    const char *message = xml_error->message ? xml_error->message : "unknown XML error";
    xmlNodePtr node = xml_error->node;
    /* Validity messages do not always say which element: add it, as xmllint does. */
    if (xml_error->domain == XML_FROM_RELAXNGV && node && node->type == XML_ELEMENT_NODE &&
        !strstr(message, (const char *)node->name))
        c_snprintf(report->message, sizeof report->message, "element %s: %s",
                   (const char *)node->name, message);
    else
        c_snprintf(report->message, sizeof report->message, "%s", message);
    strip_trailing_space(report->message);
}

/* What libxml2 prints besides its structured errors: nothing of it is wanted. */
static void ignore_generic_error(void *context, const char *format, ...)
{
    (void)context;
    (void)format;
}

void io_xml_capture_begin(io_xml_capture *capture)
{
    memset(&capture->report, 0, sizeof capture->report);
    capture->structured = xmlStructuredError;
    capture->structured_context = xmlStructuredErrorContext;
    capture->generic = xmlGenericError;
    capture->generic_context = xmlGenericErrorContext;
    xmlSetStructuredErrorFunc(&capture->report, io_xml_collect_error);
    xmlSetGenericErrorFunc(NULL, ignore_generic_error);
}

void io_xml_capture_end(io_xml_capture *capture)
{
    xmlSetStructuredErrorFunc(capture->structured_context, capture->structured);
    xmlSetGenericErrorFunc(capture->generic_context, capture->generic);
}

ur_status io_xml_refuse_file(const io_xml_report *report, const char *path, const char *what,
                             ur_error *error)
{
    if (report->line > 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s:%d: %s: %s", path, report->line, what,
                            report->message);
    return ur_error_set(error, UR_ERROR_INPUT, "%s: %s: %s", path, what, report->message);
}

ur_status io_xml_report_error(const io_xml_report *report, const char *name, ur_status status,
                              const char *fallback, ur_error *error)
{
    if (!report->have)
        return ur_error_set(error, status, "%s: %s", name, fallback);
    const char *file = report->file[0] ? report->file : name;
    if (report->line > 0)
        return ur_error_set(error, status, "%s:%d: %s", file, report->line, report->message);
    return ur_error_set(error, status, "%s: %s", file, report->message);
}

ur_status io_xml_parse(const char *name, const char *text, size_t size, int options,
                       const char *fallback, xmlDocPtr *doc, ur_error *error)
{
    *doc = NULL;
    /* xmlReadMemory refuses no bytes without a word: say what xmlReadFile says of an empty file. */
    if (size == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "%s:1: Document is empty", name);
    if (size > INT_MAX)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: %zu bytes: too large for libxml2", name,
                            size);
    io_xml_capture capture;
    io_xml_capture_begin(&capture);
    *doc = xmlReadMemory(text, (int)size, name, NULL, options | XML_PARSE_NONET);
    io_xml_capture_end(&capture);
    /* Namespace errors leave a document behind: refuse it all the same. */
    if (*doc && !capture.report.have)
        return UR_OK;
    xmlFreeDoc(*doc);
    *doc = NULL;
    return io_xml_report_error(&capture.report, name, UR_ERROR_INPUT, fallback, error);
}
