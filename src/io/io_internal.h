/*
 * io_internal.h: what the readers of XML files share (profile.c, job.c):
 * reading a file and validating it against its RelaxNG schema, with
 * libxml2's messages turned into "FILE:LINE: message" errors.
 */
#ifndef UNROLL_IO_INTERNAL_H
#define UNROLL_IO_INTERNAL_H

#include <libxml/tree.h>

#include "unroll/base.h"

/*
 * Parses path (no network) and validates it against schema/SCHEMA.rng from
 * the profile roots; the caller frees *doc with xmlFreeDoc.  UR_ERROR_INPUT
 * naming the file and line for a file that is not well formed or valid.
 */
ur_status io_xml_load(const char *const *roots, const char *schema, const char *path,
                      xmlDocPtr *doc, ur_error *error);

/* Trims white space (the '\r' of CRLF files too) at both ends, in place. */
char *io_trim(char *text);

/* "plate" from "dir/plate.svg": the file name without directory and extension. */
void io_file_stem(const char *path, char *stem, size_t size);

#endif
