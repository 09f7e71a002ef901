/*
 * job.c: job files, a whole build in one file (unroll-job(5)): machine and
 * material, options for every part, the parts (any surface the command
 * line can describe, with a quantity), and the output.  The file is
 * validated against schema/job.rng; this file turns the tree into an
 * ur_job_file and makes its paths relative to where unroll runs.
 */
#include "unroll/io.h"

#include "io_internal.h"

#include <libxml/tree.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

static bool is_element(xmlNodePtr node, const char *name)
{
    return node && node->type == XML_ELEMENT_NODE && xmlStrEqual(node->name, BAD_CAST name);
}

/* An attribute's text into out (size), "" when absent; false when it does not fit. */
static bool attribute(xmlNodePtr node, const char *name, char *out, size_t size)
{
    out[0] = '\0';
    xmlChar *text = xmlGetProp(node, BAD_CAST name);
    if (!text)
        return true;
    int length = c_snprintf(out, size, "%s", (const char *)text);
    xmlFree(text);
    return length >= 0 && (size_t)length < size;
}

static bool element_text(xmlNodePtr node, char *out, size_t size)
{
    xmlChar *text = xmlNodeGetContent(node);
    int length = c_snprintf(out, size, "%s", text ? (const char *)text : "");
    xmlFree(text);
    return length >= 0 && (size_t)length < size;
}

/* The job file's directory and a path in it, as seen from the working directory. */
static bool relative_to(const char *job_path, const char *path, char *out, size_t size)
{
    const char *slash = strrchr(job_path, '/');
    int length = path[0] == '/' || !slash
                     ? c_snprintf(out, size, "%s", path)
                     : c_snprintf(out, size, "%.*s/%s", (int)(slash - job_path), job_path, path);
    return length >= 0 && (size_t)length < size;
}

static ur_status too_long(const char *path, xmlNodePtr node, ur_error *error)
{
    return ur_error_set(error, UR_ERROR_INPUT, "%s:%ld: a name or path is too long", path,
                        xmlGetLineNo(node));
}

static ur_status read_option(const char *path, xmlNodePtr node, ur_job_file_option **options,
                             size_t *count, ur_error *error)
{
    ur_job_file_option *grown = realloc(*options, (*count + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    *options = grown;
    ur_job_file_option *option = &grown[*count];
    memset(option, 0, sizeof *option);
    option->line = (int)xmlGetLineNo(node);
    char file[sizeof option->value];
    if (!attribute(node, "name", option->name, sizeof option->name) ||
        !attribute(node, "value", option->value, sizeof option->value) ||
        !attribute(node, "path", file, sizeof file))
        return too_long(path, node, error);
    option->has_value = xmlHasProp(node, BAD_CAST "value") || file[0];
    if (file[0] && !relative_to(path, file, option->value, sizeof option->value))
        return too_long(path, node, error);
    (*count)++;
    return UR_OK;
}

static ur_status read_part(const char *path, xmlNodePtr node, ur_job_file *job, ur_error *error)
{
    ur_job_file_part *grown = realloc(job->parts, (job->part_count + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    job->parts = grown;
    ur_job_file_part *part = &grown[job->part_count++];
    memset(part, 0, sizeof *part);
    part->line = (int)xmlGetLineNo(node);
    char quantity[32], file[sizeof part->file];
    if (!attribute(node, "surface", part->surface, sizeof part->surface) ||
        !attribute(node, "name", part->name, sizeof part->name) ||
        !attribute(node, "quantity", quantity, sizeof quantity) ||
        !attribute(node, "material", part->material, sizeof part->material) ||
        !attribute(node, "file", file, sizeof file))
        return too_long(path, node, error);
    part->quantity = quantity[0] ? strtol(quantity, NULL, 10) : 1;
    if (file[0] && !relative_to(path, file, part->file, sizeof part->file))
        return too_long(path, node, error);
    for (size_t k = 0; part->name[0] && k + 1 < job->part_count; k++)
        if (strcmp(job->parts[k].name, part->name) == 0)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "%s:%d: a second part named '%s' (the first is on line %d)", path,
                                part->line, part->name, job->parts[k].line);
    ur_status status = UR_OK;
    for (xmlNodePtr child = node->children; status == UR_OK && child; child = child->next)
        if (is_element(child, "option"))
            status = read_option(path, child, &part->options, &part->option_count, error);
    return status;
}

static ur_status read_output(const char *path, xmlNodePtr node, ur_job_file *job, ur_error *error)
{
    char directory[sizeof job->output_directory];
    job->output_line = (int)xmlGetLineNo(node);
    if (!attribute(node, "name", job->output_name, sizeof job->output_name) ||
        !attribute(node, "directory", directory, sizeof directory) ||
        !attribute(node, "formats", job->formats, sizeof job->formats) ||
        !attribute(node, "report", job->report, sizeof job->report) ||
        !relative_to(path, directory[0] ? directory : ".", job->output_directory,
                     sizeof job->output_directory))
        return too_long(path, node, error);
    return UR_OK;
}

static ur_status read_job(const char *path, xmlNodePtr root, ur_job_file *job, ur_error *error)
{
    if (!attribute(root, "name", job->name, sizeof job->name))
        return too_long(path, root, error);
    ur_status status = UR_OK;
    for (xmlNodePtr node = root->children; status == UR_OK && node; node = node->next) {
        if (is_element(node, "machine") && !element_text(node, job->machine, sizeof job->machine))
            status = too_long(path, node, error);
        else if (is_element(node, "material") &&
                 !element_text(node, job->material, sizeof job->material))
            status = too_long(path, node, error);
        else if (is_element(node, "option"))
            status = read_option(path, node, &job->options, &job->option_count, error);
        else if (is_element(node, "part"))
            status = read_part(path, node, job, error);
        else if (is_element(node, "output"))
            status = read_output(path, node, job, error);
    }
    return status;
}

/* Either the file at path (text NULL) or size bytes of text named path. */
static ur_status read_job_from(const char *const *roots, const char *path, const char *text,
                               size_t size, ur_job_file *job, ur_error *error)
{
    memset(job, 0, sizeof *job);
    if (c_snprintf(job->source, sizeof job->source, "%s", path) >= (int)sizeof job->source)
        return ur_error_set(error, UR_ERROR_INPUT, "%s: path too long", path);
    xmlDocPtr doc = NULL;
    ur_status status = text ? io_xml_load_buffer(roots, "job", path, text, size, &doc, error)
                            : io_xml_load(roots, "job", path, &doc, error);
    if (status == UR_OK)
        status = read_job(path, xmlDocGetRootElement(doc), job, error);
    xmlFreeDoc(doc);
    if (status != UR_OK)
        ur_job_file_free(job);
    return status;
}

ur_status ur_job_file_read(const char *const *roots, const char *path, ur_job_file *job,
                           ur_error *error)
{
    return read_job_from(roots, path, NULL, 0, job, error);
}

ur_status ur_job_file_read_buffer(const char *const *roots, const char *name, const void *data,
                                  size_t size, ur_job_file *job, ur_error *error)
{
    return read_job_from(roots, name, data, size, job, error);
}

void ur_job_file_free(ur_job_file *job)
{
    for (size_t k = 0; k < job->part_count; k++)
        free(job->parts[k].options);
    free(job->parts);
    free(job->options);
    job->parts = NULL;
    job->options = NULL;
    job->part_count = job->option_count = 0;
}
