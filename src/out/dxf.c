/*
 * dxf.c: the DXF format behind writer.h, ASCII, R12 or R2000.
 *
 * R12 (AC1009) is what every cutter program reads: some Ruida/RDWorks and
 * LaserWeb versions read nothing newer (docs/design.md, section 8), so it
 * is the default, with the fewest sections a reader needs: HEADER, TABLES
 * (LTYPE, LAYER), ENTITIES.  R2000 (AC1015) is for CAD programs that want
 * LWPOLYLINE and true colour; it has to carry handles, owners, subclass
 * markers, the standard tables and blocks and an OBJECTS section with the
 * layouts, or AutoCAD and ezdxf's audit complain.
 *
 * Both write $INSUNITS = 4 (mm) and $MEASUREMENT = 1 (metric), even R12,
 * which predates them: a file without them is scaled differently by
 * different programs.  Each operation is a layer named as the machine names
 * it with the nearest ACI colour (programs like LightBurn map by colour)
 * and, when the machine dashes it, a linetype of the same dashes (LTYPE),
 * so a fold line shows dashed in a CAD program too.  Each path is one
 * entity, so every outline is one closed polyline, never several loops in
 * one; a path that is exactly a circle is a CIRCLE, exactly an arc an ARC
 * (the driver says so; nothing is fitted here), a two-point open path a
 * LINE.  The job's name goes into a 999 comment: neither version has a
 * header variable for it ($PROJECTNAME came with R2004); so does the kerf
 * the cut paths were compensated for (UR_KERF_NOTE), for unroll to read.
 *
 * The header must hold $HANDSEED, above every handle used, so the entities
 * of a sheet are gathered in memory and the file written at end_sheet.
 */
#include "writer.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include "../base/c_locale.h"

/* Enough for "%.9f" of any finite double. */
enum { NUMBER_SIZE = 400 };

/* At most one layer per operation, plus "0", which every drawing has. */
enum { MAX_LAYERS = UR_OP_COUNT + 1 };

/*
 * The most dash lengths a pattern keeps (style_dashes), and elements of
 * a DXF linetype: an odd list is said twice, as SVG and PDF repeat it.
 */
enum { MAX_DASHES = 16, MAX_ELEMENTS = 2 * MAX_DASHES };

/* Fixed handles of the R2000 skeleton; layers and entities follow. */
enum {
    H_BLOCK_RECORDS = 0x1,
    H_LAYERS = 0x2,
    H_STYLES = 0x3,
    H_LTYPES = 0x5,
    H_VIEWS = 0x6,
    H_UCS = 0x7,
    H_VPORTS = 0x8,
    H_APPIDS = 0x9,
    H_DIMSTYLES = 0xA,
    H_ROOT = 0xC,
    H_GROUPS = 0xD,
    H_STANDARD = 0x11,
    H_ACAD = 0x12,
    H_BYBLOCK = 0x14,
    H_BYLAYER = 0x15,
    H_CONTINUOUS = 0x16,
    H_LAYOUTS = 0x1A,
    H_PAPER_RECORD = 0x1B,
    H_PAPER_BLOCK = 0x1C,
    H_PAPER_END = 0x1D,
    H_PAPER_LAYOUT = 0x1E,
    H_MODEL_RECORD = 0x1F,
    H_MODEL_BLOCK = 0x20,
    H_MODEL_END = 0x21,
    H_MODEL_LAYOUT = 0x22,
    H_FIRST_LTYPE = 0x23, /* the dashed linetypes, at most one per operation */
    H_FIRST_LAYER = 0x30,
    H_FIRST_ENTITY = 0x100,
};

/*
 * The ACI palette (ACI 0 .. 255 as 0xRRGGBB) as ezdxf has it
 * (ezdxf.colors.DXF_DEFAULT_COLORS); 0 is BYBLOCK and is never chosen.
 */
static const unsigned long aci_palette[256] = {
    0x000000, 0xFF0000, 0xFFFF00, 0x00FF00, 0x00FFFF, 0x0000FF, 0xFF00FF, 0xFFFFFF, 0x808080,
    0xC0C0C0, 0xFF0000, 0xFF7F7F, 0xA50000, 0xA55252, 0x7F0000, 0x7F3F3F, 0x4C0000, 0x4C2626,
    0x260000, 0x261313, 0xFF3F00, 0xFF9F7F, 0xA52900, 0xA56752, 0x7F1F00, 0x7F4F3F, 0x4C1300,
    0x4C2F26, 0x260900, 0x261713, 0xFF7F00, 0xFFBF7F, 0xA55200, 0xA57C52, 0x7F3F00, 0x7F5F3F,
    0x4C2600, 0x4C3926, 0x261300, 0x261C13, 0xFFBF00, 0xFFDF7F, 0xA57C00, 0xA59152, 0x7F5F00,
    0x7F6F3F, 0x4C3900, 0x4C4226, 0x261C00, 0x262113, 0xFFFF00, 0xFFFF7F, 0xA5A500, 0xA5A552,
    0x7F7F00, 0x7F7F3F, 0x4C4C00, 0x4C4C26, 0x262600, 0x262613, 0xBFFF00, 0xDFFF7F, 0x7CA500,
    0x91A552, 0x5F7F00, 0x6F7F3F, 0x394C00, 0x424C26, 0x1C2600, 0x212613, 0x7FFF00, 0xBFFF7F,
    0x52A500, 0x7CA552, 0x3F7F00, 0x5F7F3F, 0x264C00, 0x394C26, 0x132600, 0x1C2613, 0x3FFF00,
    0x9FFF7F, 0x29A500, 0x67A552, 0x1F7F00, 0x4F7F3F, 0x134C00, 0x2F4C26, 0x092600, 0x172613,
    0x00FF00, 0x7FFF7F, 0x00A500, 0x52A552, 0x007F00, 0x3F7F3F, 0x004C00, 0x264C26, 0x002600,
    0x132613, 0x00FF3F, 0x7FFF9F, 0x00A529, 0x52A567, 0x007F1F, 0x3F7F4F, 0x004C13, 0x264C2F,
    0x002609, 0x135817, 0x00FF7F, 0x7FFFBF, 0x00A552, 0x52A57C, 0x007F3F, 0x3F7F5F, 0x004C26,
    0x264C39, 0x002613, 0x13581C, 0x00FFBF, 0x7FFFDF, 0x00A57C, 0x52A591, 0x007F5F, 0x3F7F6F,
    0x004C39, 0x264C42, 0x00261C, 0x135858, 0x00FFFF, 0x7FFFFF, 0x00A5A5, 0x52A5A5, 0x007F7F,
    0x3F7F7F, 0x004C4C, 0x264C4C, 0x002626, 0x135858, 0x00BFFF, 0x7FDFFF, 0x007CA5, 0x5291A5,
    0x005F7F, 0x3F6F7F, 0x00394C, 0x26427E, 0x001C26, 0x135858, 0x007FFF, 0x7FBFFF, 0x0052A5,
    0x527CA5, 0x003F7F, 0x3F5F7F, 0x00264C, 0x26397E, 0x001326, 0x131C58, 0x003FFF, 0x7F9FFF,
    0x0029A5, 0x5267A5, 0x001F7F, 0x3F4F7F, 0x00134C, 0x262F7E, 0x000926, 0x131758, 0x0000FF,
    0x7F7FFF, 0x0000A5, 0x5252A5, 0x00007F, 0x3F3F7F, 0x00004C, 0x26267E, 0x000026, 0x131358,
    0x3F00FF, 0x9F7FFF, 0x2900A5, 0x6752A5, 0x1F007F, 0x4F3F7F, 0x13004C, 0x2F267E, 0x090026,
    0x171358, 0x7F00FF, 0xBF7FFF, 0x5200A5, 0x7C52A5, 0x3F007F, 0x5F3F7F, 0x26004C, 0x39267E,
    0x130026, 0x1C1358, 0xBF00FF, 0xDF7FFF, 0x7C00A5, 0x9152A5, 0x5F007F, 0x6F3F7F, 0x39004C,
    0x42264C, 0x1C0026, 0x581358, 0xFF00FF, 0xFF7FFF, 0xA500A5, 0xA552A5, 0x7F007F, 0x7F3F7F,
    0x4C004C, 0x4C264C, 0x260026, 0x581358, 0xFF00BF, 0xFF7FDF, 0xA5007C, 0xA55291, 0x7F005F,
    0x7F3F6F, 0x4C0039, 0x4C2642, 0x26001C, 0x581358, 0xFF007F, 0xFF7FBF, 0xA50052, 0xA5527C,
    0x7F003F, 0x7F3F5F, 0x4C0026, 0x4C2639, 0x260013, 0x58131C, 0xFF003F, 0xFF7F9F, 0xA50029,
    0xA55267, 0x7F001F, 0x7F3F4F, 0x4C0013, 0x4C262F, 0x260009, 0x581317, 0x000000, 0x656565,
    0x666666, 0x999999, 0xCCCCCC, 0xFFFFFF,
};

/*
 * The ACI nearest to rgb.  Black and white are ACI 7, the foreground colour
 * every program draws black on white and white on black, as CAD users and
 * laser software expect of lines meant to be black.
 */
static int nearest_aci(unsigned long rgb)
{
    if (rgb == 0x000000 || rgb == 0xFFFFFF)
        return 7;
    int best = 1;
    long least = -1;
    for (int i = 1; i < 256; i++) {
        long dr = (long)(rgb >> 16 & 0xFF) - (long)(aci_palette[i] >> 16 & 0xFF);
        long dg = (long)(rgb >> 8 & 0xFF) - (long)(aci_palette[i] >> 8 & 0xFF);
        long db = (long)(rgb & 0xFF) - (long)(aci_palette[i] & 0xFF);
        long distance = dr * dr + dg * dg + db * db;
        if (least < 0 || distance < least) {
            least = distance;
            best = i;
        }
    }
    return best;
}

_Static_assert(H_FIRST_LTYPE + UR_OP_COUNT <= H_FIRST_LAYER, "room for a linetype per operation");

/* A dash pattern as a linetype: dashes positive, gaps negative, mm. */
typedef struct dxf_linetype {
    char name[64];
    double elements[MAX_ELEMENTS];
    size_t count;
} dxf_linetype;

typedef struct dxf_layer {
    char name[64]; /* as DXF allows it */
    int aci;
    unsigned long rgb;
    size_t linetype; /* index into the sheet's linetypes; LINETYPE_SOLID for none */
} dxf_layer;

#define LINETYPE_SOLID SIZE_MAX

typedef struct dxf_sheet {
    FILE *file; /* the caller's */
    bool r2000;
    double width, height;
    dxf_layer layers[MAX_LAYERS]; /* layers[0] is "0" unless the machine names it */
    size_t layer_count;
    size_t layer_of[UR_OP_COUNT];        /* index into layers */
    dxf_linetype linetypes[UR_OP_COUNT]; /* one per distinct dash pattern */
    size_t linetype_count;
    const char *job_name;                 /* the caller's; NULL for none */
    char kerf_note[WRITE_KERF_NOTE_SIZE]; /* "" for none */
    FILE *body;                           /* owned: the entities, in memory until end_sheet */
    char *body_data;                      /* owned: what body wrote */
    size_t body_size;
    unsigned long next_handle;
} dxf_sheet;

/* ---- Numbers and groups ------------------------------------------------- */

/* Nanometre resolution with a decimal point ("100.0"), as strict readers want for reals. */
static void format_real(double value, char text[NUMBER_SIZE])
{
    c_snprintf(text, NUMBER_SIZE, "%.9f", value);
    char *end = text + strlen(text);
    while (end[-1] == '0' && end[-2] != '.')
        *--end = '\0';
    if (strcmp(text, "-0.0") == 0)
        strcpy(text, "0.0");
}

static void group(FILE *file, int code, const char *value)
{
    c_fprintf(file, "%3d\n%s\n", code, value);
}

static void group_int(FILE *file, int code, long value)
{
    c_fprintf(file, "%3d\n%ld\n", code, value);
}

static void group_real(FILE *file, int code, double value)
{
    char text[NUMBER_SIZE];
    format_real(value, text);
    group(file, code, text);
}

static void group_handle(FILE *file, int code, unsigned long handle)
{
    c_fprintf(file, "%3d\n%lX\n", code, handle);
}

/* A point's x, y, z under codes base, base + 10, base + 20. */
static void group_point(FILE *file, int base, double x, double y)
{
    group_real(file, base, x);
    group_real(file, base + 10, y);
    group_real(file, base + 20, 0.0);
}

/* An R2000 object's handle, owner and first subclass; nothing in R12. */
static void group_object(const dxf_sheet *sheet, FILE *file, unsigned long handle,
                         unsigned long owner, const char *subclass)
{
    if (!sheet->r2000)
        return;
    group_handle(file, 5, handle);
    group_handle(file, 330, owner);
    if (subclass)
        group(file, 100, subclass);
}

static void subclass(const dxf_sheet *sheet, FILE *file, const char *name)
{
    if (sheet->r2000)
        group(file, 100, name);
}

/* ---- Layers ------------------------------------------------------------- */

/* Characters no DXF name may hold become '_'; an empty name takes the operation's. */
static void layer_name(const ur_op_style *style, ur_op op, char name[64])
{
    c_snprintf(name, 64, "%s", style->layer[0] ? style->layer : ur_op_name(op));
    for (char *c = name; *c; c++)
        if ((unsigned char)*c < 0x20 || strchr("<>/\\\":;?*|=`,", *c))
            *c = '_';
}

static size_t find_layer(const dxf_sheet *sheet, const char *name)
{
    for (size_t i = 0; i < sheet->layer_count; i++)
        if (strcasecmp(sheet->layers[i].name, name) == 0) /* DXF names ignore case */
            return i;
    return sheet->layer_count;
}

/*
 * A linetype name R12 takes too: letters, digits, '_' and '-' only, so a
 * decimal point is written P ("DASH_3_1P5"); false when that cannot be.
 */
static bool plain_name(char *name)
{
    for (char *c = name; *c; c++) {
        if (*c == '.')
            *c = 'P';
        else if (!(isalnum((unsigned char)*c) || *c == '_' || *c == '-'))
            return false;
    }
    return true;
}

/*
 * The linetype of a style's dashes (LINETYPE_SOLID when it has none), made
 * the first time a pattern is seen: DASH_3_1P5 for "3 1.5", its elements
 * dash, gap, dash, gap ... in mm (an odd list said twice).
 */
static size_t find_linetype(dxf_sheet *sheet, const ur_op_style *style)
{
    double dashes[MAX_DASHES];
    size_t count = style_dashes(style, dashes, MAX_DASHES);
    if (count == 0)
        return LINETYPE_SOLID;
    dxf_linetype made = {"DASH", {0}, 0};
    size_t used = strlen(made.name);
    for (size_t i = 0; i < count && used < sizeof made.name; i++)
        used += (size_t)c_snprintf(made.name + used, sizeof made.name - used, "_%g", dashes[i]);
    for (size_t round = 0; round < (count % 2 ? 2 : 1); round++)
        for (size_t i = 0; i < count; i++, made.count++)
            made.elements[made.count] = made.count % 2 ? -dashes[i] : dashes[i];
    for (size_t i = 0; i < sheet->linetype_count; i++) {
        const dxf_linetype *known = &sheet->linetypes[i];
        if (known->count == made.count &&
            memcmp(known->elements, made.elements, made.count * sizeof *made.elements) == 0)
            return i;
    }
    /* A name too long for its buffer, odd, or cut to another's, is numbered instead. */
    if (used >= sizeof made.name || !plain_name(made.name))
        c_snprintf(made.name, sizeof made.name, "DASH%zu", sheet->linetype_count + 1);
    for (size_t i = 0; i < sheet->linetype_count; i++)
        if (strcasecmp(sheet->linetypes[i].name, made.name) == 0)
            c_snprintf(made.name, sizeof made.name, "DASH%zu", sheet->linetype_count + 1);
    sheet->linetypes[sheet->linetype_count] = made;
    return sheet->linetype_count++;
}

/* One layer per distinct name; two operations the machine puts on one layer share it. */
static ur_status make_layers(dxf_sheet *sheet, const ur_machine *machine, ur_error *error)
{
    sheet->layers[0] = (dxf_layer){"0", 7, 0xFFFFFF, LINETYPE_SOLID};
    sheet->layer_count = 1;
    for (int op = 0; op < UR_OP_COUNT; op++) {
        ur_status status = style_check(machine, (ur_op)op, error);
        if (status != UR_OK)
            return status;
        const ur_op_style *style = &machine->styles[op];
        char name[64];
        layer_name(style, (ur_op)op, name);
        size_t index = find_layer(sheet, name);
        if (index == sheet->layer_count || index == 0) {
            /* a machine layer called "0" takes over the default one */
            dxf_layer *layer = &sheet->layers[index];
            if (index == sheet->layer_count)
                sheet->layer_count++;
            memcpy(layer->name, name, sizeof layer->name);
            layer->rgb = style_rgb(style);
            layer->aci = nearest_aci(layer->rgb);
            layer->linetype = find_linetype(sheet, style);
        }
        sheet->layer_of[op] = index;
    }
    return UR_OK;
}

/* ---- Sections ----------------------------------------------------------- */

static void begin_section(FILE *file, const char *name)
{
    group(file, 0, "SECTION");
    group(file, 2, name);
}

static void end_section(FILE *file)
{
    group(file, 0, "ENDSEC");
}

/*
 * A 999 comment line: what follows is one line of text, which readers skip.
 * A control character would end the line early and is written as a space;
 * anything beyond ASCII (a whole UTF-8 sequence) as '?', as the PDF's
 * information strings have it, since the file declares no code page.
 */
static void write_comment(FILE *file, const char *label, const char *text)
{
    c_fprintf(file, "999\n%s", label);
    for (const unsigned char *c = (const unsigned char *)text; *c; c++)
        if (*c >= 0x20 && *c <= 0x7E)
            fputc(*c, file);
        else if (*c < 0x20 || *c == 0x7F)
            fputc(' ', file);
        else if (*c >= 0xC0) /* the first byte of a sequence; the rest are left out */
            fputc('?', file);
    fputc('\n', file);
}

static void write_header(const dxf_sheet *sheet)
{
    FILE *file = sheet->file;
    if (sheet->job_name)
        write_comment(file, "job: ", sheet->job_name);
    if (sheet->kerf_note[0])
        write_comment(file, "", sheet->kerf_note);
    begin_section(file, "HEADER");
    group(file, 9, "$ACADVER");
    group(file, 1, sheet->r2000 ? "AC1015" : "AC1009");
    if (sheet->r2000) {
        group(file, 9, "$HANDSEED");
        group_handle(file, 5, sheet->next_handle);
    }
    group(file, 9, "$INSBASE");
    group_point(file, 10, 0, 0);
    group(file, 9, "$EXTMIN");
    group_point(file, 10, 0, 0);
    group(file, 9, "$EXTMAX");
    group_point(file, 10, sheet->width, sheet->height);
    group(file, 9, "$LIMMIN");
    group_real(file, 10, 0);
    group_real(file, 20, 0);
    group(file, 9, "$LIMMAX");
    group_real(file, 10, sheet->width);
    group_real(file, 20, sheet->height);
    group(file, 9, "$INSUNITS");
    group_int(file, 70, 4);
    group(file, 9, "$MEASUREMENT");
    group_int(file, 70, 1);
    end_section(file);
}

static void begin_table(const dxf_sheet *sheet, const char *name, unsigned long handle, long count)
{
    FILE *file = sheet->file;
    group(file, 0, "TABLE");
    group(file, 2, name);
    group_object(sheet, file, handle, 0, "AcDbSymbolTable");
    group_int(file, 70, count);
}

static void end_table(FILE *file)
{
    group(file, 0, "ENDTAB");
}

/* A table entry's start: type, handle, owner, subclasses, name, flags. */
static void begin_entry(const dxf_sheet *sheet, const char *type, unsigned long handle,
                        unsigned long table, const char *record, const char *name)
{
    FILE *file = sheet->file;
    group(file, 0, type);
    group_object(sheet, file, handle, table, "AcDbSymbolTableRecord");
    subclass(sheet, file, record);
    group(file, 2, name);
    group_int(file, 70, 0);
}

/* A linetype: its elements in mm, dashes positive and gaps negative (none: solid). */
static void write_linetype(const dxf_sheet *sheet, unsigned long handle, const char *name,
                           const char *description, const double *elements, size_t count)
{
    FILE *file = sheet->file;
    begin_entry(sheet, "LTYPE", handle, H_LTYPES, "AcDbLinetypeTableRecord", name);
    group(file, 3, description);
    group_int(file, 72, 65); /* 'A': alignment, the only one there is */
    group_int(file, 73, (long)count);
    double total = 0;
    for (size_t i = 0; i < count; i++)
        total += fabs(elements[i]);
    group_real(file, 40, total);
    for (size_t i = 0; i < count; i++) {
        group_real(file, 49, elements[i]);
        if (sheet->r2000)
            group_int(file, 74, 0); /* a plain dash or gap: no shape or text in it */
    }
}

static const char *linetype_name(const dxf_sheet *sheet, size_t linetype)
{
    if (linetype != LINETYPE_SOLID)
        return sheet->linetypes[linetype].name;
    return sheet->r2000 ? "Continuous" : "CONTINUOUS";
}

static void write_linetypes(const dxf_sheet *sheet)
{
    begin_table(sheet, "LTYPE", H_LTYPES, (sheet->r2000 ? 3 : 1) + (long)sheet->linetype_count);
    if (sheet->r2000) {
        write_linetype(sheet, H_BYBLOCK, "ByBlock", "", NULL, 0);
        write_linetype(sheet, H_BYLAYER, "ByLayer", "", NULL, 0);
    }
    write_linetype(sheet, H_CONTINUOUS, linetype_name(sheet, LINETYPE_SOLID), "Solid line", NULL,
                   0);
    for (size_t i = 0; i < sheet->linetype_count; i++) {
        const dxf_linetype *linetype = &sheet->linetypes[i];
        char description[128] = "Dashes (mm):";
        size_t used = strlen(description);
        for (size_t k = 0; k < linetype->count && used < sizeof description; k++)
            used += (size_t)c_snprintf(description + used, sizeof description - used, " %g",
                                       fabs(linetype->elements[k]));
        write_linetype(sheet, H_FIRST_LTYPE + i, linetype->name, description, linetype->elements,
                       linetype->count);
    }
    end_table(sheet->file);
}

static void write_layers(const dxf_sheet *sheet)
{
    FILE *file = sheet->file;
    begin_table(sheet, "LAYER", H_LAYERS, (long)sheet->layer_count);
    for (size_t i = 0; i < sheet->layer_count; i++) {
        const dxf_layer *layer = &sheet->layers[i];
        begin_entry(sheet, "LAYER", H_FIRST_LAYER + i, H_LAYERS, "AcDbLayerTableRecord",
                    layer->name);
        group_int(file, 62, layer->aci);
        if (sheet->r2000)
            group_int(file, 420, (long)layer->rgb);
        group(file, 6, linetype_name(sheet, layer->linetype));
        if (sheet->r2000)
            group_int(file, 370, -3); /* line weight: default */
    }
    end_table(file);
}

/* The tables R2000 readers expect to find, most of them empty. */
static void write_r2000_tables(const dxf_sheet *sheet)
{
    FILE *file = sheet->file;
    begin_table(sheet, "VPORT", H_VPORTS, 0);
    end_table(file);
    begin_table(sheet, "STYLE", H_STYLES, 1);
    begin_entry(sheet, "STYLE", H_STANDARD, H_STYLES, "AcDbTextStyleTableRecord", "Standard");
    group_real(file, 40, 0.0);
    group_real(file, 41, 1.0);
    group_real(file, 50, 0.0);
    group_int(file, 71, 0);
    group_real(file, 42, 2.5);
    group(file, 3, "txt");
    group(file, 4, "");
    end_table(file);
    begin_table(sheet, "VIEW", H_VIEWS, 0);
    end_table(file);
    begin_table(sheet, "UCS", H_UCS, 0);
    end_table(file);
    begin_table(sheet, "APPID", H_APPIDS, 1);
    begin_entry(sheet, "APPID", H_ACAD, H_APPIDS, "AcDbRegAppTableRecord", "ACAD");
    end_table(file);
    group(file, 0, "TABLE");
    group(file, 2, "DIMSTYLE");
    group_object(sheet, file, H_DIMSTYLES, 0, "AcDbSymbolTable");
    group_int(file, 70, 0);
    group(file, 100, "AcDbDimStyleTable");
    end_table(file);
    begin_table(sheet, "BLOCK_RECORD", H_BLOCK_RECORDS, 2);
    begin_entry(sheet, "BLOCK_RECORD", H_MODEL_RECORD, H_BLOCK_RECORDS, "AcDbBlockTableRecord",
                "*Model_Space");
    group_handle(file, 340, H_MODEL_LAYOUT);
    begin_entry(sheet, "BLOCK_RECORD", H_PAPER_RECORD, H_BLOCK_RECORDS, "AcDbBlockTableRecord",
                "*Paper_Space");
    group_handle(file, 340, H_PAPER_LAYOUT);
    end_table(file);
}

static void write_tables(const dxf_sheet *sheet)
{
    begin_section(sheet->file, "TABLES");
    write_linetypes(sheet);
    write_layers(sheet);
    if (sheet->r2000)
        write_r2000_tables(sheet);
    end_section(sheet->file);
}

static void write_block(const dxf_sheet *sheet, const char *name, unsigned long record,
                        unsigned long begin, unsigned long end, bool paper)
{
    FILE *file = sheet->file;
    group(file, 0, "BLOCK");
    group_object(sheet, file, begin, record, "AcDbEntity");
    if (paper)
        group_int(file, 67, 1);
    group(file, 8, "0");
    group(file, 100, "AcDbBlockBegin");
    group(file, 2, name);
    group_int(file, 70, 0);
    group_point(file, 10, 0, 0);
    group(file, 3, name);
    group(file, 1, "");
    group(file, 0, "ENDBLK");
    group_object(sheet, file, end, record, "AcDbEntity");
    if (paper)
        group_int(file, 67, 1);
    group(file, 8, "0");
    group(file, 100, "AcDbBlockEnd");
}

static void write_blocks(const dxf_sheet *sheet)
{
    begin_section(sheet->file, "BLOCKS");
    write_block(sheet, "*Model_Space", H_MODEL_RECORD, H_MODEL_BLOCK, H_MODEL_END, false);
    write_block(sheet, "*Paper_Space", H_PAPER_RECORD, H_PAPER_BLOCK, H_PAPER_END, true);
    end_section(sheet->file);
}

static void write_dictionary_entry(FILE *file, const char *name, unsigned long handle)
{
    group(file, 3, name);
    group_handle(file, 350, handle);
}

/* A layout: its plot settings left at their defaults, its limits the sheet. */
static void write_layout(const dxf_sheet *sheet, const char *name, unsigned long handle,
                         unsigned long record, int order)
{
    FILE *file = sheet->file;
    group(file, 0, "LAYOUT");
    group_object(sheet, file, handle, H_LAYOUTS, "AcDbPlotSettings");
    group(file, 1, "");
    group_int(file, 70, 0);
    group(file, 100, "AcDbLayout");
    group(file, 1, name);
    group_int(file, 70, 1);
    group_int(file, 71, order);
    group_real(file, 10, 0.0);
    group_real(file, 20, 0.0);
    group_real(file, 11, sheet->width);
    group_real(file, 21, sheet->height);
    group_point(file, 12, 0, 0);
    group_point(file, 14, 0, 0);
    group_point(file, 15, sheet->width, sheet->height);
    group_real(file, 146, 0.0);
    group_point(file, 13, 0, 0);
    group_point(file, 16, 1, 0);
    group_point(file, 17, 0, 1);
    group_int(file, 76, 0);
    group_handle(file, 330, record);
}

static void write_objects(const dxf_sheet *sheet)
{
    FILE *file = sheet->file;
    begin_section(file, "OBJECTS");
    group(file, 0, "DICTIONARY");
    group_object(sheet, file, H_ROOT, 0, "AcDbDictionary");
    group_int(file, 281, 1);
    write_dictionary_entry(file, "ACAD_GROUP", H_GROUPS);
    write_dictionary_entry(file, "ACAD_LAYOUT", H_LAYOUTS);
    group(file, 0, "DICTIONARY");
    group_object(sheet, file, H_GROUPS, H_ROOT, "AcDbDictionary");
    group_int(file, 281, 1);
    group(file, 0, "DICTIONARY");
    group_object(sheet, file, H_LAYOUTS, H_ROOT, "AcDbDictionary");
    group_int(file, 281, 1);
    write_dictionary_entry(file, "Model", H_MODEL_LAYOUT);
    write_dictionary_entry(file, "Layout1", H_PAPER_LAYOUT);
    write_layout(sheet, "Model", H_MODEL_LAYOUT, H_MODEL_RECORD, 0);
    write_layout(sheet, "Layout1", H_PAPER_LAYOUT, H_PAPER_RECORD, 1);
    end_section(file);
}

/* ---- Entities ----------------------------------------------------------- */

/* An entity's start: type, handle and owner (R2000), layer, subclass. */
static void begin_entity(dxf_sheet *sheet, const char *type, ur_op op, const char *kind)
{
    FILE *file = sheet->body;
    group(file, 0, type);
    group_object(sheet, file, sheet->next_handle++, H_MODEL_RECORD, "AcDbEntity");
    group(file, 8, sheet->layers[sheet->layer_of[op]].name);
    subclass(sheet, file, kind);
}

static void write_line(dxf_sheet *sheet, ur_op op, ur_vec2 a, ur_vec2 b)
{
    begin_entity(sheet, "LINE", op, "AcDbLine");
    group_point(sheet->body, 10, a.x, a.y);
    group_point(sheet->body, 11, b.x, b.y);
}

/* An exact circle (type CIRCLE), or the start of an ARC: centre and radius. */
static void write_circle(dxf_sheet *sheet, const char *type, ur_op op, const ur_path_circle *circle)
{
    begin_entity(sheet, type, op, "AcDbCircle");
    group_point(sheet->body, 10, circle->centre.x, circle->centre.y);
    group_real(sheet->body, 40, circle->radius);
}

/* The direction of point from the centre, degrees in [0, 360). */
static double degrees_at(ur_vec2 centre, ur_vec2 point)
{
    double degrees = atan2(point.y - centre.y, point.x - centre.x) * 180 / M_PI;
    return degrees < 0 ? degrees + 360 : degrees;
}

/*
 * An exact arc from first to last.  A DXF ARC always runs counter-clockwise
 * from its start angle to its end angle, so a clockwise one is written
 * from its last point to its first: the same arc, cut the other way.
 */
static void write_arc(dxf_sheet *sheet, ur_op op, const ur_path_circle *circle, ur_vec2 first,
                      ur_vec2 last)
{
    double start = degrees_at(circle->centre, circle->sweep >= 0 ? first : last);
    double end = degrees_at(circle->centre, circle->sweep >= 0 ? last : first);
    write_circle(sheet, "ARC", op, circle);
    subclass(sheet, sheet->body, "AcDbArc");
    group_real(sheet->body, 50, start);
    group_real(sheet->body, 51, end);
}

static void write_lwpolyline(dxf_sheet *sheet, ur_op op, const ur_vec2 *points, size_t count,
                             bool closed)
{
    FILE *file = sheet->body;
    begin_entity(sheet, "LWPOLYLINE", op, "AcDbPolyline");
    group_int(file, 90, (long)count);
    group_int(file, 70, closed ? 1 : 0);
    group_real(file, 43, 0.0);
    for (size_t i = 0; i < count; i++) {
        group_real(file, 10, points[i].x);
        group_real(file, 20, points[i].y);
    }
}

/* R12's polyline: a POLYLINE header, one VERTEX per point, a SEQEND. */
static void write_polyline(dxf_sheet *sheet, ur_op op, const ur_vec2 *points, size_t count,
                           bool closed)
{
    FILE *file = sheet->body;
    const char *layer = sheet->layers[sheet->layer_of[op]].name;
    begin_entity(sheet, "POLYLINE", op, NULL);
    group_int(file, 66, 1);
    group_point(file, 10, 0, 0);
    group_int(file, 70, closed ? 1 : 0);
    for (size_t i = 0; i < count; i++) {
        group(file, 0, "VERTEX");
        group(file, 8, layer);
        group_point(file, 10, points[i].x, points[i].y);
    }
    group(file, 0, "SEQEND");
    group(file, 8, layer);
}

/* ---- The writer --------------------------------------------------------- */

static void free_sheet(dxf_sheet *sheet)
{
    if (sheet->body)
        fclose(sheet->body);
    free(sheet->body_data);
    free(sheet);
}

static ur_status dxf_begin_sheet(void **state, void *document, FILE *file, size_t index,
                                 const write_job *job, ur_error *error)
{
    (void)document;
    *state = NULL;
    dxf_sheet *sheet = calloc(1, sizeof *sheet);
    if (!sheet)
        return ur_error_out_of_memory(error);
    sheet->file = file;
    sheet->r2000 = job->options->dxf_version == UR_DXF_R2000;
    sheet->width = job->layout->sheets[index].width;
    sheet->height = job->layout->sheets[index].height;
    sheet->next_handle = H_FIRST_ENTITY;
    sheet->job_name = job->options->job_name;
    write_kerf_note(job, index, sheet->kerf_note);
    ur_status status = make_layers(sheet, job->machine, error);
    if (status == UR_OK) {
        sheet->body = open_memstream(&sheet->body_data, &sheet->body_size);
        if (!sheet->body)
            status = ur_error_out_of_memory(error);
    }
    if (status != UR_OK) {
        free_sheet(sheet);
        return status;
    }
    *state = sheet;
    return UR_OK;
}

static ur_status dxf_path(void *state, ur_op op, const ur_vec2 *points, size_t count, bool closed,
                          const ur_path_circle *circle, ur_error *error)
{
    dxf_sheet *sheet = state;
    if (circle && closed)
        write_circle(sheet, "CIRCLE", op, circle);
    else if (circle && count >= 2)
        write_arc(sheet, op, circle, points[0], points[count - 1]);
    else if (count <= 2 && !closed)
        write_line(sheet, op, points[0], points[count - 1]);
    else if (sheet->r2000)
        write_lwpolyline(sheet, op, points, count, closed);
    else
        write_polyline(sheet, op, points, count, closed);
    if (ferror(sheet->body))
        return ur_error_out_of_memory(error);
    return UR_OK;
}

/* The whole file: the header now that the handles are known, then the entities. */
static ur_status dxf_end_sheet(void *state, ur_error *error)
{
    dxf_sheet *sheet = state;
    ur_status status = UR_OK;
    if (fclose(sheet->body) != 0)
        status = ur_error_out_of_memory(error);
    sheet->body = NULL;
    FILE *file = sheet->file;
    errno = 0;
    if (status == UR_OK) {
        write_header(sheet);
        if (sheet->r2000) {
            begin_section(file, "CLASSES");
            end_section(file);
        }
        write_tables(sheet);
        if (sheet->r2000)
            write_blocks(sheet);
        begin_section(file, "ENTITIES");
        if (sheet->body_size > 0)
            fwrite(sheet->body_data, 1, sheet->body_size, file);
        end_section(file);
        if (sheet->r2000)
            write_objects(sheet);
        group(file, 0, "EOF");
        if (ferror(file))
            status = ur_error_set(error, UR_ERROR_IO, "cannot write the DXF file: %s",
                                  errno ? strerror(errno) : "write error");
    }
    free_sheet(sheet);
    return status;
}

static void dxf_discard_sheet(void *state)
{
    free_sheet(state);
}

const format_writer dxf_writer = {
    .format = "DXF",
    .extension = "dxf",
    .begin_sheet = dxf_begin_sheet,
    .path = dxf_path,
    .end_sheet = dxf_end_sheet,
    .discard_sheet = dxf_discard_sheet,
};
