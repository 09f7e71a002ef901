/*
 * xml_errors.h: libxml2's messages caught, never printed, for one call at a
 * time (profiles, job files and SVG drawings share it).
 *
 * libxml2 reports problems through callbacks that, left alone, print on
 * stderr.  io_xml_capture_begin puts ours in place for the calling thread
 * (libxml2 keeps its handlers per thread) and io_xml_capture_end puts the
 * caller's back, so a host program's own handlers are untouched after any
 * call into the library.  The first error becomes "FILE:LINE: message".
 */
#ifndef UNROLL_IO_XML_ERRORS_H
#define UNROLL_IO_XML_ERRORS_H

#include <stdbool.h>
#include <stddef.h>

#include <libxml/tree.h>
#include <libxml/xmlerror.h>

#include "unroll/base.h"

/* libxml2 2.12 made the structured error callback take a const error. */
#if LIBXML_VERSION >= 21200
typedef const xmlError io_xml_error;
#else
typedef xmlError io_xml_error;
#endif

/* The first error (not warning) libxml2 reported. */
typedef struct io_xml_report {
    bool have;
    char file[1024]; /* "" when libxml2 named none */
    int line;        /* 0 when it gave none */
    char message[512];
} io_xml_report;

/* Our handlers in place of the caller's, which are kept here to be put back. */
typedef struct io_xml_capture {
    io_xml_report report;
    xmlStructuredErrorFunc structured;
    void *structured_context;
    xmlGenericErrorFunc generic;
    void *generic_context;
} io_xml_capture;

void io_xml_capture_begin(io_xml_capture *capture);
void io_xml_capture_end(io_xml_capture *capture);

/*
 * The structured handler itself, context an io_xml_report: for libxml2's
 * objects that take handlers of their own (RelaxNG parsers and validators).
 */
void io_xml_collect_error(void *context, io_xml_error *xml_error);

/*
 * "path:LINE: what: message" from report, libxml2's first error in the
 * file at path (a Collada document), or "path: what: message" when it
 * gave no line.
 */
ur_status io_xml_refuse_file(const io_xml_report *report, const char *path, const char *what,
                             ur_error *error);

/* "FILE:LINE: message" from report (FILE: its own, else name), or "name: fallback". */
ur_status io_xml_report_error(const io_xml_report *report, const char *name, ur_status status,
                              const char *fallback, ur_error *error);

/*
 * Parses size bytes of text as XML (without network access, with
 * libxml2's options besides), name standing for the file in messages; the
 * caller frees *doc with xmlFreeDoc.  A document with any error, even one
 * libxml2 recovers from, is refused with UR_ERROR_INPUT, "name:LINE:
 * libxml2's message", or "name: fallback" when libxml2 said nothing.
 */
ur_status io_xml_parse(const char *name, const char *text, size_t size, int options,
                       const char *fallback, xmlDocPtr *doc, ur_error *error);

#endif
