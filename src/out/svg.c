/*
 * svg.c: the SVG format behind writer.h, written with libxml2's xmlTextWriter.
 *
 * What laser software expects (docs/design.md, sections 6 and 8): physical
 * width and height in mm with a viewBox in mm, so 1 user unit = 1 mm; one
 * Inkscape layer group per operation with the machine's label, colour and
 * hairline width (LightBurn assigns layers by stroke colour alone); no fill;
 * every path on its own with absolute coordinates, since some cutter
 * programs mishandle relative ones.
 * SVG's y axis points down, so y is flipped against the sheet height.
 *
 * The XML goes to a memory buffer that is copied to the file after each
 * layer: libxml2 never touches the FILE, so every I/O error is ours to see
 * and none is printed by libxml2.
 */
#include "writer.h"

#include <errno.h>
#include <libxml/xmlstring.h>
#include <libxml/xmlwriter.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

#define SVG_NAMESPACE "http://www.w3.org/2000/svg"
#define INKSCAPE_NAMESPACE "http://www.inkscape.org/namespaces/inkscape"
#define RDF_NAMESPACE "http://www.w3.org/1999/02/22-rdf-syntax-ns#"
#define DC_NAMESPACE "http://purl.org/dc/elements/1.1/"

/* Enough for "%.6f" of any finite double (DBL_MAX has 309 digits). */
enum { NUMBER_SIZE = 400 };

typedef struct svg_sheet {
    FILE *file;                /* the caller's */
    xmlBufferPtr buffer;       /* owned: XML not yet copied to file */
    xmlTextWriterPtr writer;   /* owned: writes into buffer */
    double height;             /* for the y flip */
    const ur_machine *machine; /* the caller's */
    char *data;                /* owned: the d attribute being built, reused */
    size_t length, capacity;
} svg_sheet;

/*
 * Millimetres to the nanometre, without trailing zeros.  Sheets hold hundreds
 * of thousands of coordinates and printf's exact decimal conversion was half
 * the writing time, so values of ordinary size are written from a rounded
 * integer count of nanometres (the last digit may differ from printf's on an
 * exact tie, a nanometre at most).
 */
static void format_coordinate(double value, char text[NUMBER_SIZE])
{
    if (!(fabs(value) < 1e12)) {
        c_snprintf(text, NUMBER_SIZE, "%.6f", value);
    } else {
        long long nanometres = llround(value * 1e6);
        unsigned long long magnitude =
            nanometres < 0 ? -(unsigned long long)nanometres : (unsigned long long)nanometres;
        char digits[32];
        int n = 0;
        for (int place = 0; place < 7 || magnitude > 0; place++) {
            if (place == 6)
                digits[n++] = '.';
            digits[n++] = (char)('0' + magnitude % 10);
            magnitude /= 10;
        }
        char *out = text;
        if (nanometres < 0)
            *out++ = '-';
        while (n > 0)
            *out++ = digits[--n];
        *out = '\0';
    }
    char *end = text + strlen(text);
    while (end[-1] == '0')
        *--end = '\0';
    if (end[-1] == '.')
        *--end = '\0';
    if (strcmp(text, "-0") == 0)
        strcpy(text, "0");
}

static ur_status xml_failed(ur_error *error, const char *what)
{
    return ur_error_set(error, UR_ERROR_INTERNAL, "SVG writer failed: %s", what);
}

/* Writes attributes given as name, value pairs, stopping at the first failure. */
static ur_status write_attributes(xmlTextWriterPtr writer, const char *const (*pairs)[2],
                                  size_t count, ur_error *error)
{
    for (size_t i = 0; i < count; i++)
        if (xmlTextWriterWriteAttribute(writer, BAD_CAST pairs[i][0], BAD_CAST pairs[i][1]) < 0)
            return xml_failed(error, pairs[i][0]);
    return UR_OK;
}

/* Copies what libxml2 has produced so far to the file and empties the buffer. */
static ur_status flush_to_file(svg_sheet *sheet, ur_error *error)
{
    if (xmlTextWriterFlush(sheet->writer) < 0)
        return xml_failed(error, "flush");
    size_t length = (size_t)xmlBufferLength(sheet->buffer);
    if (length > 0 && fwrite(xmlBufferContent(sheet->buffer), 1, length, sheet->file) != length)
        return ur_error_set(error, UR_ERROR_IO, "cannot write the SVG file: %s", strerror(errno));
    xmlBufferEmpty(sheet->buffer);
    return UR_OK;
}

/* Text from the user must be UTF-8 without control characters to be XML 1.0. */
static ur_status check_text(const char *what, const char *text, ur_error *error)
{
    bool usable = xmlCheckUTF8(BAD_CAST text) != 0;
    for (const unsigned char *c = (const unsigned char *)text; usable && *c; c++)
        if (*c < 0x20 && *c != '\t' && *c != '\n' && *c != '\r')
            usable = false;
    if (!usable)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "%s is not UTF-8 text without control characters", what);
    return UR_OK;
}

/* A machine filled by hand may carry anything: refuse what SVG cannot show. */
static ur_status check_style(const ur_machine *machine, ur_op op, ur_error *error)
{
    ur_status status = style_check(machine, op, error);
    return status == UR_OK ? check_text("the layer name", machine->styles[op].layer, error)
                           : status;
}

static ur_status write_root(svg_sheet *sheet, double width, double height, ur_error *error)
{
    char width_text[NUMBER_SIZE], height_text[NUMBER_SIZE];
    char width_mm[NUMBER_SIZE + 2], height_mm[NUMBER_SIZE + 2], view_box[2 * NUMBER_SIZE + 8];
    format_coordinate(width, width_text);
    format_coordinate(height, height_text);
    c_snprintf(width_mm, sizeof width_mm, "%smm", width_text);
    c_snprintf(height_mm, sizeof height_mm, "%smm", height_text);
    c_snprintf(view_box, sizeof view_box, "0 0 %s %s", width_text, height_text);
    const char *const attributes[][2] = {
        {"xmlns", SVG_NAMESPACE}, {"xmlns:inkscape", INKSCAPE_NAMESPACE},
        {"version", "1.1"},       {"width", width_mm},
        {"height", height_mm},    {"viewBox", view_box},
    };
    if (xmlTextWriterStartDocument(sheet->writer, NULL, "UTF-8", NULL) < 0 ||
        xmlTextWriterStartElement(sheet->writer, BAD_CAST "svg") < 0)
        return xml_failed(error, "svg");
    return write_attributes(sheet->writer, attributes, sizeof attributes / sizeof *attributes,
                            error);
}

static ur_status write_element(svg_sheet *sheet, const char *name, const char *text,
                               ur_error *error)
{
    if (xmlTextWriterWriteElement(sheet->writer, BAD_CAST name, BAD_CAST text) < 0)
        return xml_failed(error, name);
    return UR_OK;
}

/*
 * Dublin Core in RDF, where Inkscape keeps a drawing's title and creator:
 * the title, the program that made it, the job it comes from and, as its
 * description, the kerf its cut paths were compensated for (kerf_note).
 */
static ur_status write_metadata(svg_sheet *sheet, const write_settings *options,
                                const char *kerf_note, ur_error *error)
{
    const char *const rdf[][2] = {{"xmlns:rdf", RDF_NAMESPACE}, {"xmlns:dc", DC_NAMESPACE}};
    const char *const about[][2] = {{"rdf:about", ""}};
    if (xmlTextWriterStartElement(sheet->writer, BAD_CAST "metadata") < 0 ||
        xmlTextWriterStartElement(sheet->writer, BAD_CAST "rdf:RDF") < 0)
        return xml_failed(error, "metadata");
    ur_status status = write_attributes(sheet->writer, rdf, 2, error);
    if (status == UR_OK && xmlTextWriterStartElement(sheet->writer, BAD_CAST "rdf:Description") < 0)
        status = xml_failed(error, "rdf:Description");
    if (status == UR_OK)
        status = write_attributes(sheet->writer, about, 1, error);
    if (status == UR_OK && options->title)
        status = write_element(sheet, "dc:title", options->title, error);
    if (status == UR_OK)
        status = write_element(sheet, "dc:creator", "unroll " UR_VERSION, error);
    if (status == UR_OK && options->job_name)
        status = write_element(sheet, "dc:source", options->job_name, error);
    if (status == UR_OK && kerf_note[0])
        status = write_element(sheet, "dc:description", kerf_note, error);
    for (int i = 0; status == UR_OK && i < 3; i++) /* rdf:Description, rdf:RDF, metadata */
        if (xmlTextWriterEndElement(sheet->writer) < 0)
            status = xml_failed(error, "end of metadata");
    return status;
}

static ur_status write_title_and_desc(svg_sheet *sheet, const write_settings *options,
                                      const char *kerf_note, ur_error *error)
{
    ur_status status = UR_OK;
    if (options->title)
        status = check_text("the title", options->title, error);
    if (status == UR_OK && options->job_name)
        status = check_text("the job name", options->job_name, error);
    if (status == UR_OK && options->title)
        status = write_element(sheet, "title", options->title, error);
    if (status == UR_OK)
        status = write_element(sheet, "desc", "made by unroll " UR_VERSION "; 1 user unit = 1 mm",
                               error);
    return status == UR_OK ? write_metadata(sheet, options, kerf_note, error) : status;
}

static void free_sheet(svg_sheet *sheet)
{
    if (sheet->writer)
        xmlFreeTextWriter(sheet->writer);
    if (sheet->buffer)
        xmlBufferFree(sheet->buffer);
    free(sheet->data);
    free(sheet);
}

static ur_status svg_begin_sheet(void **state, void *document, FILE *file, size_t index,
                                 const write_job *job, ur_error *error)
{
    (void)document;
    const ur_sheet *page = &job->layout->sheets[index];
    double width = page->width, height = page->height;
    const ur_machine *machine = job->machine;
    const write_settings *options = job->options;
    *state = NULL;
    svg_sheet *sheet = calloc(1, sizeof *sheet);
    if (!sheet)
        return ur_error_out_of_memory(error);
    sheet->file = file;
    sheet->height = height;
    sheet->machine = machine;
    sheet->buffer = xmlBufferCreate();
    sheet->writer = sheet->buffer ? xmlNewTextWriterMemory(sheet->buffer, 0) : NULL;
    ur_status status = sheet->writer ? UR_OK : ur_error_out_of_memory(error);
    if (status == UR_OK && xmlTextWriterSetIndent(sheet->writer, 1) < 0)
        status = xml_failed(error, "indent");
    if (status == UR_OK)
        status = write_root(sheet, width, height, error);
    char kerf_note[WRITE_KERF_NOTE_SIZE];
    write_kerf_note(job, index, kerf_note);
    if (status == UR_OK)
        status = write_title_and_desc(sheet, options, kerf_note, error);
    if (status != UR_OK) {
        free_sheet(sheet);
        return status;
    }
    *state = sheet;
    return UR_OK;
}

static ur_status svg_begin_layer(void *state, ur_op op, ur_error *error)
{
    svg_sheet *sheet = state;
    ur_status status = check_style(sheet->machine, op, error);
    if (status != UR_OK)
        return status;
    const ur_op_style *style = &sheet->machine->styles[op];
    char width[NUMBER_SIZE];
    c_snprintf(width, sizeof width, "%.6g", style->line_width); /* %g: never rounds to 0 */
    const char *const attributes[][2] = {
        {"id", ur_op_name(op)},
        {"inkscape:groupmode", "layer"},
        {"inkscape:label", style->layer[0] ? style->layer : ur_op_name(op)},
        {"fill", "none"},
        {"stroke", style->colour},
        {"stroke-width", width},
        {"stroke-linecap", "round"},
        {"stroke-linejoin", "round"},
    };
    if (xmlTextWriterStartElement(sheet->writer, BAD_CAST "g") < 0)
        return xml_failed(error, "g");
    status =
        write_attributes(sheet->writer, attributes, sizeof attributes / sizeof *attributes, error);
    const char *const dash[][2] = {{"stroke-dasharray", style->dash}};
    if (status == UR_OK && style->dash[0])
        status = write_attributes(sheet->writer, dash, 1, error);
    return status;
}

static ur_status append(svg_sheet *sheet, const char *text, ur_error *error)
{
    size_t length = strlen(text);
    if (sheet->length + length + 1 > sheet->capacity) {
        size_t capacity = sheet->capacity ? sheet->capacity : 256;
        while (capacity < sheet->length + length + 1)
            capacity *= 2;
        char *data = realloc(sheet->data, capacity);
        if (!data)
            return ur_error_out_of_memory(error);
        sheet->data = data;
        sheet->capacity = capacity;
    }
    memcpy(sheet->data + sheet->length, text, length + 1);
    sheet->length += length;
    return UR_OK;
}

/* Appends "M x y" or " L x y" for a sheet point, y flipped to point down. */
static ur_status append_point(svg_sheet *sheet, const char *command, ur_vec2 point, ur_error *error)
{
    char x[NUMBER_SIZE], y[NUMBER_SIZE];
    format_coordinate(point.x, x);
    format_coordinate(sheet->height - point.y, y);
    ur_status status = append(sheet, command, error);
    if (status == UR_OK)
        status = append(sheet, " ", error);
    if (status == UR_OK)
        status = append(sheet, x, error);
    if (status == UR_OK)
        status = append(sheet, " ", error);
    return status == UR_OK ? append(sheet, y, error) : status;
}

/* An exact circle as SVG's own element, centre y flipped. */
static ur_status write_circle(svg_sheet *sheet, const ur_path_circle *circle, ur_error *error)
{
    char x[NUMBER_SIZE], y[NUMBER_SIZE], r[NUMBER_SIZE];
    format_coordinate(circle->centre.x, x);
    format_coordinate(sheet->height - circle->centre.y, y);
    format_coordinate(circle->radius, r);
    const char *const attributes[][2] = {{"cx", x}, {"cy", y}, {"r", r}};
    if (xmlTextWriterStartElement(sheet->writer, BAD_CAST "circle") < 0)
        return xml_failed(error, "circle");
    ur_status status = write_attributes(sheet->writer, attributes, 3, error);
    if (status == UR_OK && xmlTextWriterEndElement(sheet->writer) < 0)
        status = xml_failed(error, "circle");
    return status;
}

/*
 * " A r r 0 large sweep x y": the exact arc to the last point.  With y
 * flipped a counter-clockwise arc turns the way SVG calls negative, so its
 * sweep flag is 0.
 */
static ur_status append_arc(svg_sheet *sheet, const ur_path_circle *circle, ur_vec2 last,
                            ur_error *error)
{
    char r[NUMBER_SIZE], flags[16];
    format_coordinate(circle->radius, r);
    c_snprintf(flags, sizeof flags, " 0 %d %d", fabs(circle->sweep) > M_PI, circle->sweep < 0);
    const char *const parts[] = {" A ", r, " ", r, flags};
    ur_status status = UR_OK;
    for (size_t i = 0; status == UR_OK && i < sizeof parts / sizeof *parts; i++)
        status = append(sheet, parts[i], error);
    return status == UR_OK ? append_point(sheet, "", last, error) : status;
}

static ur_status svg_path(void *state, ur_op op, const ur_vec2 *points, size_t count, bool closed,
                          const ur_path_circle *circle, ur_error *error)
{
    (void)op; /* the enclosing layer group carries it */
    svg_sheet *sheet = state;
    if (circle && closed)
        return write_circle(sheet, circle, error);
    sheet->length = 0;
    ur_status status = append(sheet, "", error);
    if (circle && count >= 2) {
        status = append_point(sheet, "M", points[0], error);
        if (status == UR_OK)
            status = append_arc(sheet, circle, points[count - 1], error);
        count = 0; /* the points between lie on the arc */
    }
    for (size_t i = 0; status == UR_OK && i < count; i++)
        status = append_point(sheet, i == 0 ? "M" : " L", points[i], error);
    if (status == UR_OK && closed)
        status = append(sheet, " Z", error);
    if (status != UR_OK)
        return status;
    if (xmlTextWriterStartElement(sheet->writer, BAD_CAST "path") < 0 ||
        xmlTextWriterWriteAttribute(sheet->writer, BAD_CAST "d", BAD_CAST sheet->data) < 0 ||
        xmlTextWriterEndElement(sheet->writer) < 0)
        return xml_failed(error, "path");
    return UR_OK;
}

static ur_status svg_end_layer(void *state, ur_op op, ur_error *error)
{
    (void)op;
    svg_sheet *sheet = state;
    if (xmlTextWriterEndElement(sheet->writer) < 0)
        return xml_failed(error, "end of g");
    return flush_to_file(sheet, error);
}

static ur_status svg_end_sheet(void *state, ur_error *error)
{
    svg_sheet *sheet = state;
    ur_status status = UR_OK;
    if (xmlTextWriterEndDocument(sheet->writer) < 0) /* closes <svg> too */
        status = xml_failed(error, "end of document");
    if (status == UR_OK)
        status = flush_to_file(sheet, error);
    free_sheet(sheet);
    return status;
}

static void svg_discard_sheet(void *state)
{
    free_sheet(state);
}

const format_writer svg_writer = {
    .format = "SVG",
    .extension = "svg",
    .begin_sheet = svg_begin_sheet,
    .begin_layer = svg_begin_layer,
    .end_layer = svg_end_layer,
    .path = svg_path,
    .end_sheet = svg_end_sheet,
    .discard_sheet = svg_discard_sheet,
};
