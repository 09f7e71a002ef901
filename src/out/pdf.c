/*
 * pdf.c: the PDF format behind writer.h, written with libharu (libhpdf).
 *
 * For print-driver lasers (Epilog, ULS) and Glowforge (docs/design.md,
 * sections 6 and 8): one page per sheet, the page exactly the sheet
 * (1 mm = 72 / 25.4 pt), every path a vector stroke in its operation's
 * colour and line width as the machine gives them, so hairlines stay the
 * hairlines the driver cuts.
 *
 * libharu takes dash lengths only as whole units of user space, at most
 * 100 of them, and writes every number with five decimals, clamped to
 * +-32767.  So solid layers draw in points (coordinates to about 4e-6 mm)
 * and a dashed layer in a unit of its own, between GSave and GRestore: the
 * finest of 0.01, 0.02, 0.05, 0.1, ... pt (numbers five decimals hold
 * exactly) in which the longest dash is at most 100 units and the page at
 * most 32000.  Dashes are then exact to that unit (0.1 pt, 0.035 mm, for a
 * 3 mm dash on a 600 mm sheet).
 *
 * libharu reports errors through a handler; the default one prints and
 * exits, so a handler that only records the error is installed and every
 * call's result looked at.  The document is built in memory and written
 * to the file at the end.
 */
#include "writer.h"

#include <errno.h>
#include <hpdf.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define POINTS_PER_MM (72.0 / 25.4)

/* libharu's longest dash and our largest coordinate, in units. */
#define LONGEST_DASH 100.0
#define LARGEST_NUMBER 32000.0

/* At most this many dash lengths (libharu's limit). */
enum { MAX_DASHES = 8 };

typedef struct pdf_document {
    HPDF_Doc pdf;
    HPDF_STATUS error_no, detail_no; /* the first error libharu reported; 0 for none */
    const ur_machine *machine;
} pdf_document;

typedef struct pdf_sheet {
    pdf_document *document;
    HPDF_Page page;
    size_t index;
    double largest; /* the sheet's longer side, pt */
    double unit;    /* points per user space unit in the current layer */
} pdf_sheet;

/* Records libharu's first error instead of printing it and exiting. */
static void record_error(HPDF_STATUS error_no, HPDF_STATUS detail_no, void *user_data)
{
    pdf_document *document = user_data;
    if (document->error_no == 0) {
        document->error_no = error_no;
        document->detail_no = detail_no;
    }
}

/* UR_OK, or the error libharu recorded (or returned) in what it was doing. */
static ur_status check(pdf_document *document, HPDF_STATUS result, const char *what,
                       ur_error *error)
{
    if (result == HPDF_OK && document->error_no == 0)
        return UR_OK;
    HPDF_STATUS code = document->error_no ? document->error_no : result;
    if (code == HPDF_FAILD_TO_ALLOC_MEM)
        return ur_error_out_of_memory(error);
    return ur_error_set(error, UR_ERROR_INTERNAL, "PDF writer failed: %s (libharu error 0x%04X/%u)",
                        what, (unsigned)code, (unsigned)document->detail_no);
}

/* ---- Document ----------------------------------------------------------- */

/*
 * libharu writes an information string as the bytes given, which readers
 * take for PDFDocEncoding, and has no way to write UTF-16 there: only
 * printable ASCII reads back as written, so each other character (a whole
 * UTF-8 sequence) becomes '?' rather than garbage.
 */
static ur_status set_info(pdf_document *document, HPDF_InfoType type, const char *what,
                          const char *text, ur_error *error)
{
    if (!text)
        return UR_OK;
    char *ascii = malloc(strlen(text) + 1);
    if (!ascii)
        return ur_error_out_of_memory(error);
    char *out = ascii;
    for (const unsigned char *c = (const unsigned char *)text; *c; c++)
        if (*c >= 0x20 && *c <= 0x7E)
            *out++ = (char)*c;
        else if (*c < 0x80 || *c >= 0xC0) /* not a continuation byte */
            *out++ = '?';
    *out = '\0';
    ur_status status = check(document, HPDF_SetInfoAttr(document->pdf, type, ascii), what, error);
    free(ascii);
    return status;
}

static ur_status set_metadata(pdf_document *document, const write_job *job, ur_error *error)
{
    const write_settings *options = job->options;
    char kerf_note[WRITE_KERF_NOTE_SIZE];
    write_kerf_note(job, WRITE_ALL_SHEETS, kerf_note);
    ur_status status = set_info(document, HPDF_INFO_TITLE, "title", options->title, error);
    if (status == UR_OK)
        status = set_info(document, HPDF_INFO_CREATOR, "creator", "unroll " UR_VERSION, error);
    if (status == UR_OK)
        status = set_info(document, HPDF_INFO_SUBJECT, "job name", options->job_name, error);
    if (status == UR_OK && kerf_note[0])
        status = set_info(document, HPDF_INFO_KEYWORDS, "keywords", kerf_note, error);
    return status;
}

static void free_document(pdf_document *document)
{
    if (document->pdf)
        HPDF_Free(document->pdf);
    free(document);
}

static ur_status pdf_begin_document(void **state, const write_job *job, ur_error *error)
{
    *state = NULL;
    pdf_document *document = calloc(1, sizeof *document);
    if (!document)
        return ur_error_out_of_memory(error);
    document->machine = job->machine;
    document->pdf = HPDF_New(record_error, document);
    ur_status status = document->pdf ? UR_OK : ur_error_out_of_memory(error);
    if (status == UR_OK && HPDF_SetCompressionMode(document->pdf, HPDF_COMP_ALL) != HPDF_OK) {
        /* a libharu built without zlib: the PDF is only larger */
        HPDF_ResetError(document->pdf);
        document->error_no = document->detail_no = 0;
    }
    if (status == UR_OK)
        status = set_metadata(document, job, error);
    for (int op = 0; status == UR_OK && op < UR_OP_COUNT; op++)
        status = style_check(job->machine, (ur_op)op, error);
    if (status != UR_OK) {
        free_document(document);
        return status;
    }
    *state = document;
    return UR_OK;
}

/* Copies the finished document from libharu's memory stream to file. */
static ur_status copy_to_file(pdf_document *document, FILE *file, ur_error *error)
{
    HPDF_BYTE buffer[65536];
    for (;;) {
        HPDF_UINT32 size = sizeof buffer;
        HPDF_STATUS result = HPDF_ReadFromStream(document->pdf, buffer, &size);
        if (size > 0 && fwrite(buffer, 1, size, file) != size)
            return ur_error_set(error, UR_ERROR_IO, "cannot write the PDF file: %s",
                                strerror(errno));
        if (result == HPDF_STREAM_EOF)
            return UR_OK;
        if (result != HPDF_OK)
            return check(document, result, "reading the document back", error);
    }
}

static ur_status pdf_end_document(void *state, FILE *file, ur_error *error)
{
    pdf_document *document = state;
    ur_status status = check(document, HPDF_SaveToStream(document->pdf), "saving", error);
    if (status == UR_OK) {
        HPDF_ResetError(document->pdf); /* the EOF of reading back is no error */
        status = copy_to_file(document, file, error);
    }
    free_document(document);
    return status;
}

static void pdf_discard_document(void *state)
{
    free_document(state);
}

/* ---- Pages -------------------------------------------------------------- */

static ur_status check_page_size(double width, double height, size_t index, ur_error *error)
{
    double largest = HPDF_MAX_PAGE_SIZE / POINTS_PER_MM,
           smallest = HPDF_MIN_PAGE_SIZE / POINTS_PER_MM;
    if (width > largest || height > largest || width < smallest || height < smallest)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "sheet %zu (%g x %g mm) does not fit a PDF page, which is %.0f to "
                            "%.0f mm a side",
                            index + 1, width, height, ceil(smallest), floor(largest));
    return UR_OK;
}

static ur_status pdf_begin_sheet(void **state, void *document_state, FILE *file, size_t index,
                                 const write_job *job, ur_error *error)
{
    (void)file;
    *state = NULL;
    pdf_document *document = document_state;
    const ur_sheet *sheet = &job->layout->sheets[index];
    ur_status status = check_page_size(sheet->width, sheet->height, index, error);
    if (status != UR_OK)
        return status;
    pdf_sheet *page = calloc(1, sizeof *page);
    if (!page)
        return ur_error_out_of_memory(error);
    page->document = document;
    page->index = index;
    page->largest = fmax(sheet->width, sheet->height) * POINTS_PER_MM;
    page->page = HPDF_AddPage(document->pdf);
    status = check(document, page->page ? HPDF_OK : HPDF_FAILD_TO_ALLOC_MEM, "new page", error);
    if (status == UR_OK)
        status = check(document,
                       HPDF_Page_SetWidth(page->page, (HPDF_REAL)(sheet->width * POINTS_PER_MM)),
                       "page width", error);
    if (status == UR_OK)
        status = check(document,
                       HPDF_Page_SetHeight(page->page, (HPDF_REAL)(sheet->height * POINTS_PER_MM)),
                       "page height", error);
    if (status != UR_OK) {
        free(page);
        return status;
    }
    *state = page;
    return UR_OK;
}

/*
 * Points per unit: 1 for a solid layer; for a dashed one the finest 1, 2 or
 * 5 times a power of ten from 0.01 up in which every dash and the page fit.
 */
static double layer_unit(const pdf_sheet *sheet, const double *dashes, size_t count)
{
    if (count == 0)
        return 1.0;
    double least = sheet->largest / LARGEST_NUMBER;
    for (size_t i = 0; i < count; i++)
        least = fmax(least, dashes[i] * POINTS_PER_MM / LONGEST_DASH);
    static const double steps[3] = {1, 2, 5};
    for (double magnitude = 0.01;; magnitude *= 10)
        for (int k = 0; k < 3; k++)
            if (steps[k] * magnitude >= least * (1 - 1e-12))
                return steps[k] * magnitude;
}

/* A point on the sheet, mm, in the layer's units. */
static HPDF_REAL units(const pdf_sheet *sheet, double millimetres)
{
    return (HPDF_REAL)(millimetres * POINTS_PER_MM / sheet->unit);
}

/* The operation's colour, width and dashes, in the layer's own unit. */
static ur_status pdf_begin_layer(void *state, ur_op op, ur_error *error)
{
    pdf_sheet *sheet = state;
    HPDF_Page page = sheet->page;
    const ur_op_style *style = &sheet->document->machine->styles[op];
    unsigned long rgb = style_rgb(style);
    double dashes[MAX_DASHES];
    size_t count = style_dashes(style, dashes, MAX_DASHES);
    sheet->unit = layer_unit(sheet, dashes, count);
    HPDF_UINT16 pattern[MAX_DASHES];
    for (size_t i = 0; i < count; i++)
        pattern[i] = (HPDF_UINT16)fmax(1.0, fmin(LONGEST_DASH, round(units(sheet, dashes[i]))));
    HPDF_Page_GSave(page);
    if (sheet->unit != 1.0)
        HPDF_Page_Concat(page, (HPDF_REAL)sheet->unit, 0, 0, (HPDF_REAL)sheet->unit, 0, 0);
    HPDF_Page_SetRGBStroke(page, (HPDF_REAL)((rgb >> 16 & 0xFF) / 255.0),
                           (HPDF_REAL)((rgb >> 8 & 0xFF) / 255.0),
                           (HPDF_REAL)((rgb & 0xFF) / 255.0));
    HPDF_Page_SetLineWidth(page, units(sheet, style->line_width));
    HPDF_Page_SetLineCap(page, HPDF_ROUND_END);
    HPDF_Page_SetLineJoin(page, HPDF_ROUND_JOIN);
    if (count > 0)
        HPDF_Page_SetDash(page, pattern, (HPDF_UINT)count, 0);
    return check(sheet->document, HPDF_OK, "line style", error);
}

static ur_status pdf_end_layer(void *state, ur_op op, ur_error *error)
{
    (void)op;
    pdf_sheet *sheet = state;
    return check(sheet->document, HPDF_Page_GRestore(sheet->page), "end of layer", error);
}

static ur_status pdf_path(void *state, ur_op op, const ur_vec2 *points, size_t count, bool closed,
                          const ur_path_circle *circle, ur_error *error)
{
    (void)circle; /* the points lie on it, within the flattening's tolerance */
    (void)op;     /* begin_layer set its style */
    pdf_sheet *sheet = state;
    HPDF_Page page = sheet->page;
    HPDF_Page_MoveTo(page, units(sheet, points[0].x), units(sheet, points[0].y));
    for (size_t i = 1; i < count; i++)
        HPDF_Page_LineTo(page, units(sheet, points[i].x), units(sheet, points[i].y));
    if (count == 1) /* a dot: a round cap on a line of no length */
        HPDF_Page_LineTo(page, units(sheet, points[0].x), units(sheet, points[0].y));
    if (closed)
        HPDF_Page_ClosePathStroke(page);
    else
        HPDF_Page_Stroke(page);
    return check(sheet->document, HPDF_OK, "path", error);
}

static ur_status pdf_end_sheet(void *state, ur_error *error)
{
    pdf_sheet *sheet = state;
    ur_status status = check(sheet->document, HPDF_OK, "page", error);
    free(sheet);
    return status;
}

static void pdf_discard_sheet(void *state)
{
    free(state);
}

const format_writer pdf_writer = {
    .format = "PDF",
    .extension = "pdf",
    .one_file = true,
    .begin_document = pdf_begin_document,
    .begin_sheet = pdf_begin_sheet,
    .begin_layer = pdf_begin_layer,
    .end_layer = pdf_end_layer,
    .path = pdf_path,
    .end_sheet = pdf_end_sheet,
    .discard_sheet = pdf_discard_sheet,
    .end_document = pdf_end_document,
    .discard_document = pdf_discard_document,
};
