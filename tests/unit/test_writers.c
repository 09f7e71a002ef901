/*
 * test_writers.c: the DXF, PDF and PNG writers and ur_write_outputs,
 * checked with real readers run through system(): Python's ezdxf (the
 * Debian package, /usr/bin/python3) reads every DXF back, audits it and
 * compares layers, colours and geometry; qpdf checks the PDF and pdfinfo
 * measures its pages; cairo decodes the PNG.  The layout is built by hand:
 * a panel with a hole and a fold, turned a quarter turn; a triangle with an
 * engraved mark, turned half a turn; on a second sheet a square shaded by
 * strain.  Files go to a fresh directory under /tmp.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <cairo.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/out.h"

#include "test_support.h"

#define PI 3.14159265358979323846

enum { PIECES = 3 };

typedef struct fixture {
    char dir[64];
    ur_piece pieces[PIECES];
    ur_placement placements[3];
    ur_sheet sheets[2];
    ur_layout layout;
    ur_machine machine;
    ur_output_options options;
    ur_format_options formats;
    ur_vec2 triangles[2][3]; /* the square's shading */
    double strain[2];
} fixture;

/* The ezdxf checker: reads a DXF and what it should hold, exits 0 when all is there. */
static const char check_dxf_py[] =
    "import sys, ezdxf\n"
    "from ezdxf.colors import DXF_DEFAULT_COLORS as PALETTE\n"
    "def nearest(rgb):\n"
    "    if rgb in (0, 0xFFFFFF): return 7\n"
    "    best, least = 1, None\n"
    "    for i in range(1, 256):\n"
    "        p = PALETTE[i]\n"
    "        d = sum((((rgb >> s) & 255) - ((p >> s) & 255)) ** 2 for s in (16, 8, 0))\n"
    "        if least is None or d < least: best, least = i, d\n"
    "    return best\n"
    "def fail(msg):\n"
    "    print('check_dxf: ' + msg); sys.exit(1)\n"
    "path, expected = sys.argv[1], sys.argv[2]\n"
    "doc = ezdxf.readfile(path)\n"
    "auditor = doc.audit()\n"
    "if auditor.has_errors: fail('audit: %s' % [str(e.message) for e in auditor.errors])\n"
    "if auditor.has_fixes: fail('audit fixed: %s' % [str(e.message) for e in auditor.fixes])\n"
    "paths = []\n"
    "for line in open(expected):\n"
    "    f = line.split()\n"
    "    if f[0] == 'version':\n"
    "        if doc.dxfversion != f[1]: fail('version %s' % doc.dxfversion)\n"
    "    elif f[0] == 'extents':\n"
    "        w, h = float(f[1]), float(f[2])\n"
    "        if tuple(doc.header['$EXTMIN'])[:2] != (0, 0): fail('extmin')\n"
    "        if abs(doc.header['$EXTMAX'][0] - w) > 1e-9 or abs(doc.header['$EXTMAX'][1] - h) > "
    "1e-9: fail('extmax')\n"
    "    elif f[0] == 'layer':\n"
    "        name, rgb = f[1].replace('~', ' '), int(f[2], 16)\n"
    "        if not doc.layers.has_entry(name): fail('no layer ' + name)\n"
    "        layer = doc.layers.get(name)\n"
    "        if layer.dxf.name != name: fail('layer name %r' % layer.dxf.name)\n"
    "        if layer.color != nearest(rgb): fail('layer %s colour %d' % (name, layer.color))\n"
    "        if doc.dxfversion != 'AC1009' and layer.rgb != ((rgb >> 16) & 255, (rgb >> 8) & 255, "
    "rgb & 255):\n"
    "            fail('layer %s true colour %s' % (name, layer.rgb))\n"
    "    elif f[0] == 'path':\n"
    "        n = int(f[3]); v = [float(x) for x in f[4:]]\n"
    "        paths.append((f[1].replace('~', ' '), f[2] == '1', [(v[2*i], v[2*i+1]) for i in "
    "range(n)]))\n"
    "if doc.header.get('$INSUNITS') != 4: fail('$INSUNITS %s' % doc.header.get('$INSUNITS'))\n"
    "if doc.header.get('$MEASUREMENT') != 1: fail('$MEASUREMENT')\n"
    "read = []\n"
    "for e in doc.modelspace():\n"
    "    t = e.dxftype()\n"
    "    if t == 'LINE':\n"
    "        read.append((e.dxf.layer, False, [tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]], t))\n"
    "    elif t == 'POLYLINE':\n"
    "        read.append((e.dxf.layer, e.is_closed, [tuple(p.dxf.location)[:2] for p in "
    "e.vertices], t))\n"
    "    elif t == 'LWPOLYLINE':\n"
    "        read.append((e.dxf.layer, e.closed, [tuple(p) for p in e.get_points('xy')], t))\n"
    "    else:\n"
    "        fail('unexpected entity ' + t)\n"
    "if len(read) != len(paths): fail('%d entities, expected %d' % (len(read), len(paths)))\n"
    "for layer, closed, points in paths:\n"
    "    want = 'LINE' if len(points) == 2 and not closed else ('POLYLINE' if doc.dxfversion == "
    "'AC1009' else 'LWPOLYLINE')\n"
    "    match = [r for r in read if r[0] == layer and r[1] == closed and r[3] == want and "
    "len(r[2]) == len(points)\n"
    "             and all(abs(a[0]-b[0]) <= 1e-6 and abs(a[1]-b[1]) <= 1e-6 for a, b in zip(r[2], "
    "points))]\n"
    "    if not match: fail('no %s %s on %s from %s' % ('closed' if closed else 'open', want, "
    "layer, points[0]))\n"
    "    read.remove(match[0])\n"
    "print('ok', path)\n";

/* ---- building the layout ----------------------------------------------- */

static void add_path(ur_piece *piece, ur_op op, const ur_vec2 *points, size_t count, bool closed)
{
    ur_error error;
    assert_int_equal(ur_piece_add_path(piece, op, points, count, closed, &error), UR_OK);
}

static void make_pieces(fixture *f)
{
    ur_piece *pieces = f->pieces;
    memset(pieces, 0, PIECES * sizeof *pieces);
    const ur_vec2 panel[] = {{0, 0}, {100, 0}, {100, 50}, {0, 50}};
    const ur_vec2 hole[] = {{70, 20}, {80, 20}, {80, 30.123456789}, {70, 30}};
    const ur_vec2 fold[] = {{50, 0}, {50, 50}};
    const ur_vec2 valley[] = {{20, 0}, {25, 25}, {20, 50}};
    snprintf(pieces[0].name, sizeof pieces[0].name, "panel");
    add_path(&pieces[0], UR_OP_CUT, panel, 4, true);
    add_path(&pieces[0], UR_OP_CUT, hole, 4, true);
    add_path(&pieces[0], UR_OP_SCORE, fold, 2, false);
    add_path(&pieces[0], UR_OP_SCORE_VALLEY, valley, 3, false);

    const ur_vec2 triangle[] = {{0, 0}, {40, 0}, {0, 30}};
    const ur_vec2 mark[] = {{5, 5}, {15, 5}};
    const ur_vec2 zone[] = {{2, 2}, {8, 2}, {2, 8}};
    snprintf(pieces[1].name, sizeof pieces[1].name, "tab");
    add_path(&pieces[1], UR_OP_CUT, triangle, 3, true);
    add_path(&pieces[1], UR_OP_ENGRAVE, mark, 2, false);
    add_path(&pieces[1], UR_OP_MARK, zone, 3, true);

    const ur_vec2 square[] = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    const ur_vec2 slit[] = {{50, 10}, {50, 40}};
    snprintf(pieces[2].name, sizeof pieces[2].name, "spare");
    add_path(&pieces[2], UR_OP_CUT, square, 4, true);
    add_path(&pieces[2], UR_OP_KERF, slit, 2, false);
    /* Shading the test owns (the piece does not free what it did not allocate). */
    const ur_vec2 t[2][3] = {{{0, 0}, {100, 0}, {100, 100}}, {{0, 0}, {100, 100}, {0, 100}}};
    memcpy(f->triangles, t, sizeof t);
    f->strain[0] = 0.02;
    f->strain[1] = -0.01;
}

static void set_style(ur_machine *machine, ur_op op, const char *layer, const char *colour,
                      double width, const char *dash)
{
    snprintf(machine->styles[op].layer, sizeof machine->styles[op].layer, "%s", layer);
    snprintf(machine->styles[op].colour, sizeof machine->styles[op].colour, "%s", colour);
    snprintf(machine->styles[op].dash, sizeof machine->styles[op].dash, "%s", dash);
    machine->styles[op].line_width = width;
}

/* The LightBurn palette of docs/design.md section 8, hairlines but for engraving. */
static void make_machine(ur_machine *machine)
{
    memset(machine, 0, sizeof *machine);
    snprintf(machine->name, sizeof machine->name, "test-laser");
    set_style(machine, UR_OP_CUT, "Cut", "#FF0000", 0.025, "");
    set_style(machine, UR_OP_SCORE, "Score", "#0000FF", 0.025, "");
    set_style(machine, UR_OP_SCORE_VALLEY, "Score valley", "#00E0E0", 0.025, "3 1.5");
    set_style(machine, UR_OP_KERF, "Kerf", "#00E000", 0.025, "");
    set_style(machine, UR_OP_ENGRAVE, "Engrave", "#000000", 0.1, "");
    set_style(machine, UR_OP_MARK, "Mark", "#FF00FF", 0.05, "");
}

/*
 * Sheet 1 (600 x 400): the panel a quarter turn, moved to (150, 20); the
 * triangle half a turn, moved to (300, 100).  Sheet 2 (300 x 200): the
 * square moved to (10, 10).  One sheet unless a test says two.
 */
static void make_layout(fixture *f)
{
    f->placements[0] = (ur_placement){0, ur_transform2_make(PI / 2, ur_vec2_make(150, 20))};
    f->placements[1] = (ur_placement){1, ur_transform2_make(PI, ur_vec2_make(300, 100))};
    f->placements[2] = (ur_placement){2, ur_transform2_make(0, ur_vec2_make(10, 10))};
    f->sheets[0] = (ur_sheet){
        .width = 600, .height = 400, .placements = &f->placements[0], .placement_count = 2};
    f->sheets[1] = (ur_sheet){
        .width = 300, .height = 200, .placements = &f->placements[2], .placement_count = 1};
    f->layout = (ur_layout){f->sheets, 1, NULL, 0};
}

static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (!f)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/unroll-test-writers-XXXXXX");
    if (!mkdtemp(f->dir)) {
        free(f);
        return -1;
    }
    make_pieces(f);
    f->pieces[2].shading = (ur_shading){f->triangles, f->strain, NULL, 2};
    make_machine(&f->machine);
    make_layout(f);
    f->options.title = "unroll test";
    f->formats.job_name = "writers-job";
    f->formats.drawing_order = true; /* the checks compare paths point by point, as drawn */
    *state = f;
    return 0;
}

/* Removes what a test left, subdirectories (made to provoke failures) too. */
static int remove_entry(const char *path)
{
    if (unlink(path) == 0)
        return 0;
    return rmdir(path);
}

static int teardown(void **state)
{
    fixture *f = *state;
    each_entry(f->dir, remove_entry);
    rmdir(f->dir);
    f->pieces[2].shading = (ur_shading){0};
    for (int i = 0; i < PIECES; i++)
        ur_piece_free(&f->pieces[i]);
    free(f);
    return 0;
}

/* ---- readers ------------------------------------------------------------ */

static int run(const char *format, ...)
{
    char command[2048];
    va_list arguments;
    va_start(arguments, format);
    int length = vsnprintf(command, sizeof command, format, arguments);
    va_end(arguments);
    assert_true(length > 0 && (size_t)length < sizeof command);
    return system(command);
}

static bool have_ezdxf(void)
{
    return run("/usr/bin/python3 -c 'import ezdxf' >/dev/null 2>&1") == 0;
}

static bool have_tool(const char *name)
{
    return run("command -v %s >/dev/null 2>&1", name) == 0;
}

/* Every layer with its colour, every placed path of sheet, for the checker. */
static void write_expected(const fixture *f, const ur_sheet *sheet, const char *version,
                           const char *path)
{
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    fprintf(file, "version %s\nextents %.17g %.17g\n", version, sheet->width, sheet->height);
    for (int op = 0; op < UR_OP_COUNT; op++) {
        char name[64];
        snprintf(name, sizeof name, "%s", f->machine.styles[op].layer);
        for (char *c = name; *c; c++)
            if (*c == ' ')
                *c = '~'; /* one word for the checker */
        fprintf(file, "layer %s %s\n", name, f->machine.styles[op].colour + 1);
    }
    for (size_t p = 0; p < sheet->placement_count; p++) {
        const ur_piece *piece = &f->pieces[sheet->placements[p].piece_index];
        for (size_t i = 0; i < piece->path_count; i++) {
            const ur_path *path_ = &piece->paths[i];
            char name[64];
            snprintf(name, sizeof name, "%s", f->machine.styles[path_->op].layer);
            for (char *c = name; *c; c++)
                if (*c == ' ')
                    *c = '~';
            fprintf(file, "path %s %d %zu", name, path_->closed, path_->count);
            for (size_t k = 0; k < path_->count; k++) {
                ur_vec2 q = ur_transform2_apply(sheet->placements[p].transform, path_->points[k]);
                fprintf(file, " %.17g %.17g", q.x, q.y);
            }
            fprintf(file, "\n");
        }
    }
    assert_int_equal(fclose(file), 0);
}

/* The DXF at dxf holds sheet as ezdxf reads it, its audit clean. */
static void check_dxf(const fixture *f, const ur_sheet *sheet, const char *version, const char *dxf)
{
    char script[256], expected[256];
    path_in(f->dir, "check_dxf.py", script, sizeof script);
    path_in(f->dir, "expected.txt", expected, sizeof expected);
    FILE *file = fopen(script, "w");
    assert_non_null(file);
    assert_true(fputs(check_dxf_py, file) >= 0);
    assert_int_equal(fclose(file), 0);
    write_expected(f, sheet, version, expected);
    assert_int_equal(run("/usr/bin/python3 %s %s %s", script, dxf, expected), 0);
    unlink(script);
    unlink(expected);
}

/* One line of pdfinfo's output starting with key, into value; false when there is none. */
static bool pdfinfo(const char *pdf, const char *key, char *value, size_t size)
{
    char command[512];
    snprintf(command, sizeof command, "pdfinfo -f 1 -l 99 '%s' 2>/dev/null", pdf);
    FILE *pipe = popen(command, "r");
    assert_non_null(pipe);
    char line[512];
    bool found = false;
    while (fgets(line, sizeof line, pipe))
        if (!found && strncmp(line, key, strlen(key)) == 0) {
            const char *at = line + strlen(key);
            while (*at == ' ')
                at++;
            snprintf(value, size, "%s", at);
            value[strcspn(value, "\n")] = '\0';
            found = true;
        }
    pclose(pipe);
    return found;
}

/* Page page (from 1) is width x height mm within 0.01 mm. */
static void assert_page_size(const char *pdf, int page, double width, double height)
{
    char key[32], value[256];
    snprintf(key, sizeof key, "Page %4d size:", page);
    assert_true(pdfinfo(pdf, key, value, sizeof value));
    double w, h;
    assert_int_equal(sscanf(value, "%lf x %lf pts", &w, &h), 2);
    assert_true(fabs(w * 25.4 / 72 - width) <= 0.01);
    assert_true(fabs(h * 25.4 / 72 - height) <= 0.01);
}

/* The PNG decodes and is the sheet at dpi; returns it for pixel checks. */
static cairo_surface_t *read_png(const char *png, double width, double height, double dpi)
{
    cairo_surface_t *surface = cairo_image_surface_create_from_png(png);
    assert_int_equal(cairo_surface_status(surface), CAIRO_STATUS_SUCCESS);
    assert_int_equal(cairo_image_surface_get_width(surface), (int)lround(width * dpi / 25.4));
    assert_int_equal(cairo_image_surface_get_height(surface), (int)lround(height * dpi / 25.4));
    return surface;
}

/* The red, green and blue (0..255) of a pixel x, y of an RGB24 or ARGB32 image. */
static void pixel(cairo_surface_t *surface, int x, int y, int rgb[3])
{
    cairo_surface_flush(surface);
    const unsigned char *data = cairo_image_surface_get_data(surface);
    uint32_t value;
    memcpy(&value, data + y * cairo_image_surface_get_stride(surface) + 4 * x, 4);
    rgb[0] = (int)(value >> 16 & 0xFF);
    rgb[1] = (int)(value >> 8 & 0xFF);
    rgb[2] = (int)(value & 0xFF);
}

/* ---- DXF ---------------------------------------------------------------- */

static void test_dxf_r12_reads_back(void **state)
{
    fixture *f = *state;
    if (!have_ezdxf())
        skip();
    char path[256];
    path_in(f->dir, "net.dxf", path, sizeof path);
    ur_error error;
    assert_int_equal(
        ur_write_dxf(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    check_dxf(f, &f->sheets[0], "AC1009", path);
    assert_int_equal(entries_in(f->dir), 1);
}

static void test_dxf_r2000_reads_back(void **state)
{
    fixture *f = *state;
    if (!have_ezdxf())
        skip();
    char path[256];
    path_in(f->dir, "net.dxf", path, sizeof path);
    f->formats.dxf_version = UR_DXF_R2000;
    f->layout.sheet_count = 2;
    ur_error error;
    assert_int_equal(
        ur_write_dxf(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    char one[256], two[256];
    path_in(f->dir, "net-1.dxf", one, sizeof one);
    path_in(f->dir, "net-2.dxf", two, sizeof two);
    check_dxf(f, &f->sheets[0], "AC1015", one);
    check_dxf(f, &f->sheets[1], "AC1015", two);
    assert_int_equal(entries_in(f->dir), 2);
}

/* Text of the DXF at path. */
static char *read_all(const char *path)
{
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    char *text = calloc(1, 1 << 20);
    assert_non_null(text);
    size_t length = fread(text, 1, (1 << 20) - 1, file);
    text[length] = '\0';
    fclose(file);
    return text;
}

/* R12 by hand: POLYLINE closed by 70=1, LINE for two points, $INSUNITS 4, no LWPOLYLINE. */
static void test_dxf_r12_entities(void **state)
{
    fixture *f = *state;
    char path[256];
    path_in(f->dir, "net.dxf", path, sizeof path);
    ur_error error;
    assert_int_equal(
        ur_write_dxf(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    char *text = read_all(path);
    assert_non_null(strstr(text, "  9\n$ACADVER\n  1\nAC1009\n"));
    assert_non_null(strstr(text, "  9\n$INSUNITS\n 70\n4\n"));
    assert_non_null(strstr(text, "  9\n$MEASUREMENT\n 70\n1\n"));
    assert_non_null(strstr(text, "  9\n$EXTMAX\n 10\n600.0\n 20\n400.0\n"));
    assert_non_null(strstr(text, "  0\nLAYER\n  2\nCut\n 70\n0\n 62\n1\n"));
    assert_non_null(strstr(text, "  0\nLAYER\n  2\nEngrave\n 70\n0\n 62\n7\n"));
    assert_non_null(strstr(text, "  0\nPOLYLINE\n  8\nCut\n 66\n1\n"));
    assert_non_null(strstr(text, " 70\n1\n  0\nVERTEX\n"));
    assert_non_null(strstr(text, "  0\nLINE\n  8\nScore\n"));
    assert_null(strstr(text, "LWPOLYLINE"));
    assert_non_null(strstr(text, "  0\nEOF\n"));
    free(text);
}

/* ---- PDF ---------------------------------------------------------------- */

static void test_pdf_pages(void **state)
{
    fixture *f = *state;
    if (!have_tool("qpdf") || !have_tool("pdfinfo"))
        skip();
    char path[256];
    path_in(f->dir, "net.pdf", path, sizeof path);
    f->layout.sheet_count = 2;
    ur_error error;
    assert_int_equal(
        ur_write_pdf(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    assert_int_equal(entries_in(f->dir), 1); /* one file for every sheet */
    assert_int_equal(run("qpdf --check '%s' >/dev/null 2>&1", path), 0);
    char value[256];
    assert_true(pdfinfo(path, "Pages:", value, sizeof value));
    assert_string_equal(value, "2");
    assert_page_size(path, 1, 600, 400);
    assert_page_size(path, 2, 300, 200);
    assert_true(pdfinfo(path, "Title:", value, sizeof value));
    assert_string_equal(value, "unroll test");
    assert_true(pdfinfo(path, "Creator:", value, sizeof value));
    assert_string_equal(value, "unroll " UR_VERSION);
    assert_true(pdfinfo(path, "Subject:", value, sizeof value));
    assert_string_equal(value, "writers-job");
}

/* The page is drawn: pdftoppm of page 2 shows the square's red outline where it is. */
static void test_pdf_draws_paths(void **state)
{
    fixture *f = *state;
    if (!have_tool("pdftoppm"))
        skip();
    char path[256], image[256], stem[256];
    path_in(f->dir, "net.pdf", path, sizeof path);
    path_in(f->dir, "page", stem, sizeof stem);
    path_in(f->dir, "page.png", image, sizeof image);
    f->layout.sheets = &f->sheets[1];
    f->machine.styles[UR_OP_CUT].line_width = 1.0; /* wide enough to hit a pixel */
    ur_error error;
    assert_int_equal(
        ur_write_pdf(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    /* 25.4 dpi: one pixel a millimetre, y down from the top of the 200 mm page */
    assert_int_equal(run("pdftoppm -r 25.4 -png -singlefile '%s' '%s'", path, stem), 0);
    cairo_surface_t *surface = cairo_image_surface_create_from_png(image);
    assert_int_equal(cairo_surface_status(surface), CAIRO_STATUS_SUCCESS);
    assert_true(abs(cairo_image_surface_get_height(surface) - 200) <= 1); /* pdftoppm rounds up */
    int rgb[3];
    pixel(surface, 60, 200 - 10, rgb); /* on the bottom edge, y = 10 mm */
    assert_true(rgb[0] > 200 && rgb[1] < 80 && rgb[2] < 80);
    pixel(surface, 60, 200 - 60, rgb); /* inside: white */
    assert_true(rgb[0] > 240 && rgb[1] > 240 && rgb[2] > 240);
    cairo_surface_destroy(surface);
}

/* ---- PNG ---------------------------------------------------------------- */

static void test_png_size_and_fill(void **state)
{
    fixture *f = *state;
    char path[256], one[256], two[256];
    path_in(f->dir, "net.png", path, sizeof path);
    path_in(f->dir, "net-1.png", one, sizeof one);
    path_in(f->dir, "net-2.png", two, sizeof two);
    f->layout.sheet_count = 2;
    f->formats.dpi = 50;
    ur_error error;
    assert_int_equal(
        ur_write_png(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    cairo_surface_destroy(read_png(one, 600, 400, 50));
    cairo_surface_t *surface = read_png(two, 300, 200, 50);
    /* The square at (10, 10)-(110, 110): its lower right triangle stretched (red), upper left
       compressed (blue); away from the name in the middle. */
    double scale = 50 / 25.4;
    int rgb[3];
    pixel(surface, (int)(95 * scale), (int)((200 - 25) * scale), rgb);
    assert_true(rgb[0] > rgb[2] + 40);
    pixel(surface, (int)(25 * scale), (int)((200 - 95) * scale), rgb);
    assert_true(rgb[2] > rgb[0] + 40);
    cairo_surface_destroy(surface);
}

static void test_png_default_dpi(void **state)
{
    fixture *f = *state;
    char path[256];
    path_in(f->dir, "net.png", path, sizeof path);
    ur_error error;
    assert_int_equal(
        ur_write_png(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    cairo_surface_destroy(read_png(path, 600, 400, 96));
    f->formats.dpi = -3;
    assert_int_equal(
        ur_write_png(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_ERROR_INPUT);
    f->formats.dpi = 2000; /* 47244 pixels wide: too many */
    assert_int_equal(
        ur_write_png(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_ERROR_INPUT);
    assert_int_equal(entries_in(f->dir), 1);
}

/* ---- Several formats at once -------------------------------------------- */

static void test_formats_by_name(void **state)
{
    (void)state;
    assert_int_equal(ur_format_from_path("out/net.svg"), UR_FORMAT_SVG);
    assert_int_equal(ur_format_from_path("NET.DXF"), UR_FORMAT_DXF);
    assert_int_equal(ur_format_from_path("a.b/net.pdf"), UR_FORMAT_PDF);
    assert_int_equal(ur_format_from_path("net.png"), UR_FORMAT_PNG);
    assert_int_equal(ur_format_from_path("dir.svg/net"), 0);
    assert_int_equal(ur_format_from_path(".svg"), 0);
    assert_int_equal(ur_format_from_path("net.eps"), 0);
    unsigned formats;
    ur_error error;
    assert_int_equal(ur_formats_parse("svg,dxf,PDF,png", &formats, &error), UR_OK);
    assert_int_equal(formats, UR_FORMAT_ALL);
    assert_int_equal(ur_formats_parse("dxf", &formats, &error), UR_OK);
    assert_int_equal(formats, UR_FORMAT_DXF);
    assert_int_equal(ur_formats_parse("svg,,dxf", &formats, &error), UR_ERROR_INPUT);
    assert_int_equal(ur_formats_parse("svg,eps", &formats, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "eps"));
    assert_int_equal(ur_formats_parse("", &formats, &error), UR_ERROR_INPUT);
    assert_string_equal(ur_format_name(UR_FORMAT_PDF), "pdf");
}

/* Every format, two sheets: NAME-N.ext per sheet, one PDF; all of them readable. */
static void test_outputs_every_format(void **state)
{
    fixture *f = *state;
    char path[256], name[256];
    path_in(f->dir, "net.svg", path, sizeof path);
    f->layout.sheet_count = 2;
    ur_error error;
    assert_int_equal(ur_write_outputs(path, UR_FORMAT_ALL, &f->layout, f->pieces, &f->machine,
                                      &f->options, &f->formats, &error),
                     UR_OK);
    const char *names[] = {"net-1.svg", "net-2.svg", "net-1.dxf", "net-2.dxf",
                           "net.pdf",   "net-1.png", "net-2.png"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        path_in(f->dir, names[i], name, sizeof name);
        if (!exists(name))
            fail_msg("%s was not written", names[i]);
    }
    assert_int_equal(entries_in(f->dir), 7);
    if (have_ezdxf()) {
        path_in(f->dir, "net-2.dxf", name, sizeof name);
        check_dxf(f, &f->sheets[1], "AC1009", name);
    }
    if (have_tool("qpdf")) {
        path_in(f->dir, "net.pdf", name, sizeof name);
        assert_int_equal(run("qpdf --check '%s' >/dev/null 2>&1", name), 0);
    }
    /* No extension: each format's own */
    path_in(f->dir, "plain", path, sizeof path);
    f->layout.sheet_count = 1;
    assert_int_equal(ur_write_outputs(path, UR_FORMAT_DXF | UR_FORMAT_PDF, &f->layout, f->pieces,
                                      &f->machine, &f->options, &f->formats, &error),
                     UR_OK);
    path_in(f->dir, "plain.dxf", name, sizeof name);
    assert_true(exists(name));
    path_in(f->dir, "plain.pdf", name, sizeof name);
    assert_true(exists(name));
}

static void test_outputs_format_from_extension(void **state)
{
    fixture *f = *state;
    char path[256];
    ur_error error;
    path_in(f->dir, "net.dxf", path, sizeof path);
    assert_int_equal(ur_write_outputs(path, 0, &f->layout, f->pieces, &f->machine, &f->options,
                                      &f->formats, &error),
                     UR_OK);
    assert_true(exists(path));
    assert_int_equal(entries_in(f->dir), 1);
    /* An extension no format has, or one not asked for: refused, nothing written */
    path_in(f->dir, "net.eps", path, sizeof path);
    assert_int_equal(ur_write_outputs(path, 0, &f->layout, f->pieces, &f->machine, &f->options,
                                      &f->formats, &error),
                     UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "net.eps"));
    path_in(f->dir, "other.svg", path, sizeof path);
    assert_int_equal(ur_write_outputs(path, UR_FORMAT_DXF, &f->layout, f->pieces, &f->machine,
                                      &f->options, &f->formats, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(entries_in(f->dir), 1);
}

/*
 * A directory where the second sheet's DXF should go: nothing is written,
 * no temporary stays, and a file already there keeps what it had.
 */
static void test_outputs_all_or_nothing(void **state)
{
    fixture *f = *state;
    char path[256], blocker[256], old[256];
    path_in(f->dir, "net.svg", path, sizeof path);
    path_in(f->dir, "net-2.dxf", blocker, sizeof blocker);
    path_in(f->dir, "net-1.svg", old, sizeof old);
    assert_int_equal(mkdir(blocker, 0755), 0);
    FILE *file = fopen(old, "w");
    assert_non_null(file);
    fputs("old", file);
    fclose(file);
    f->layout.sheet_count = 2;
    ur_error error;
    assert_int_equal(ur_write_outputs(path, UR_FORMAT_ALL, &f->layout, f->pieces, &f->machine,
                                      &f->options, &f->formats, &error),
                     UR_ERROR_IO);
    assert_non_null(strstr(error.message, "net-2.dxf"));
    assert_int_equal(entries_in(f->dir), 2); /* the directory and the old file */
    char *text = read_all(old);
    assert_string_equal(text, "old");
    free(text);
    /* The last format failing (PNG) removes the SVG, DXF and PDF already complete. */
    assert_int_equal(rmdir(blocker), 0);
    path_in(f->dir, "net-2.png", blocker, sizeof blocker);
    assert_int_equal(mkdir(blocker, 0755), 0);
    assert_int_equal(ur_write_outputs(path, UR_FORMAT_ALL, &f->layout, f->pieces, &f->machine,
                                      &f->options, &f->formats, &error),
                     UR_ERROR_IO);
    assert_int_equal(entries_in(f->dir), 2);
    /* A failure inside a writer (a bad machine colour) also leaves nothing. */
    assert_int_equal(rmdir(blocker), 0);
    snprintf(f->machine.styles[UR_OP_MARK].colour, 8, "red");
    assert_int_equal(ur_write_outputs(path, UR_FORMAT_DXF | UR_FORMAT_PDF, &f->layout, f->pieces,
                                      &f->machine, &f->options, &f->formats, &error),
                     UR_ERROR_INPUT);
    assert_int_equal(entries_in(f->dir), 1);
}

/*
 * The circle checker: a DXF and an SVG of the piece test_exact_circles
 * builds, placed turned 30 degrees and moved by (100, 50) on a 300 x 200
 * sheet.  The expected numbers are worked out here from the piece's own
 * (the hole about (30, 30) of radius 10, a counter-clockwise arc of radius
 * 20 from 0 to 90 degrees, a clockwise one of radius 15 from 180 to 90).
 */
static const char check_circles_py[] =
    "import sys, math, re, ezdxf\n"
    "import xml.etree.ElementTree as ET\n"
    "def fail(msg):\n"
    "    print('check_circles: ' + msg); sys.exit(1)\n"
    "t = math.radians(30)\n"
    "def place(x, y): return (x * math.cos(t) - y * math.sin(t) + 100, x * math.sin(t) + y * "
    "math.cos(t) + 50)\n"
    "c = place(30, 30)\n"
    "def near(a, b, what):\n"
    "    if abs(a - b) > 1e-6: fail('%s %r, expected %r' % (what, a, b))\n"
    "doc = ezdxf.readfile(sys.argv[1])\n"
    "if doc.audit().has_errors: fail('audit')\n"
    "circles = [e for e in doc.modelspace() if e.dxftype() == 'CIRCLE']\n"
    "arcs = sorted((e for e in doc.modelspace() if e.dxftype() == 'ARC'), key=lambda e: "
    "e.dxf.radius)\n"
    "if len(circles) != 1 or len(arcs) != 2: fail('%d circles, %d arcs' % (len(circles), "
    "len(arcs)))\n"
    "e = circles[0]\n"
    "near(e.dxf.center[0], c[0], 'circle x'); near(e.dxf.center[1], c[1], 'circle y')\n"
    "near(e.dxf.radius, 10, 'circle radius')\n"
    "if e.dxf.layer != 'Cut': fail('circle on ' + e.dxf.layer)\n"
    "for e, r, start, end, layer in ((arcs[0], 15, 120, 210, 'Engrave'), (arcs[1], 20, 30, 120, "
    "'Kerf')):\n"
    "    near(e.dxf.center[0], c[0], 'arc x'); near(e.dxf.center[1], c[1], 'arc y')\n"
    "    near(e.dxf.radius, r, 'arc radius'); near(e.dxf.start_angle, start, 'start angle')\n"
    "    near(e.dxf.end_angle, end, 'end angle')\n"
    "    if e.dxf.layer != layer: fail('arc of %g on %s' % (r, e.dxf.layer))\n"
    "S = '{http://www.w3.org/2000/svg}'\n"
    "root = ET.parse(sys.argv[2]).getroot()\n"
    "[svg_circle] = root.iter(S + 'circle')\n"
    "near(float(svg_circle.get('cx')), c[0], 'svg cx'); near(float(svg_circle.get('cy')), 200 - "
    "c[1], 'svg cy')\n"
    "near(float(svg_circle.get('r')), 10, 'svg r')\n"
    "for layer, r, a, b, sweep in (('kerf', 20, 0, 90, '0'), ('engrave', 15, 180, 90, '1')):\n"
    "    [path] = root.find(\"%sg[@id='%s']\" % (S, layer)).iter(S + 'path')\n"
    "    n = re.fullmatch(r'M (\\S+) (\\S+) A (\\S+) (\\S+) 0 0 ([01]) (\\S+) (\\S+)', "
    "path.get('d'))\n"
    "    if not n: fail('svg arc %r' % path.get('d'))\n"
    "    p, q = place(30 + r * math.cos(math.radians(a)), 30 + r * math.sin(math.radians(a))), "
    "place(30 + r * math.cos(math.radians(b)), 30 + r * math.sin(math.radians(b)))\n"
    "    for got, want in zip((n[1], n[2], n[3], n[4], n[6], n[7]), (p[0], 200 - p[1], r, r, "
    "q[0], 200 - q[1])):\n"
    "        near(float(got), want, 'svg arc on ' + layer)\n"
    "    if n[5] != sweep: fail('svg sweep flag %s on %s' % (n[5], layer))\n"
    "print('ok')\n";

/* n + 1 points on the circle about (30, 30) of radius r from angle a to b (radians). */
static void arc_points(ur_vec2 *p, size_t n, double r, double a, double b)
{
    for (size_t k = 0; k <= n; k++) {
        double angle = a + (b - a) * (double)k / (double)n;
        p[k] = ur_vec2_make(30 + r * cos(angle), 30 + r * sin(angle));
    }
}

/*
 * Exact circles and arcs through a turned placement: the hole a CIRCLE,
 * the arcs ARCs (the clockwise one written the other way round) in both
 * DXF versions, a <circle> and A commands in the SVG, all where the
 * placement puts them.
 */
static void test_exact_circles(void **state)
{
    fixture *f = *state;
    if (!have_ezdxf())
        skip();
    ur_piece piece;
    memset(&piece, 0, sizeof piece);
    snprintf(piece.name, sizeof piece.name, "round");
    const ur_vec2 square[] = {{0, 0}, {60, 0}, {60, 60}, {0, 60}};
    ur_vec2 hole[64], kerf[9], engrave[5];
    arc_points(hole, 63, 10, 0, -2 * PI * 63 / 64); /* clockwise, as holes are */
    arc_points(kerf, 8, 20, 0, PI / 2);
    arc_points(engrave, 4, 15, PI, PI / 2);
    add_path(&piece, UR_OP_CUT, square, 4, true);
    add_path(&piece, UR_OP_CUT, hole, 64, true);
    add_path(&piece, UR_OP_KERF, kerf, 9, false);
    add_path(&piece, UR_OP_ENGRAVE, engrave, 5, false);
    piece.paths[1].circle = (ur_path_circle){{30, 30}, 10, 0};
    piece.paths[2].circle = (ur_path_circle){{30, 30}, 20, PI / 2};
    piece.paths[3].circle = (ur_path_circle){{30, 30}, 15, -PI / 2};
    ur_placement placement = {0, ur_transform2_make(PI / 6, ur_vec2_make(100, 50))};
    ur_sheet sheet = {.width = 300, .height = 200, .placements = &placement, .placement_count = 1};
    ur_layout layout = {&sheet, 1, NULL, 0};
    char script[256];
    path_in(f->dir, "check_circles.py", script, sizeof script);
    FILE *file = fopen(script, "w");
    assert_non_null(file);
    assert_true(fputs(check_circles_py, file) >= 0);
    assert_int_equal(fclose(file), 0);
    const char *names[] = {"r12", "r2000"};
    for (int version = 0; version < 2; version++) {
        char path[256], svg[256], dxf[256], stem[32];
        snprintf(stem, sizeof stem, "%s.svg", names[version]);
        path_in(f->dir, stem, path, sizeof path);
        f->formats.dxf_version = version ? UR_DXF_R2000 : UR_DXF_R12;
        f->formats.drawing_order = version == 0; /* cutting order moves no circle */
        ur_error error;
        assert_int_equal(ur_write_outputs(path, UR_FORMAT_SVG | UR_FORMAT_DXF, &layout, &piece,
                                          &f->machine, &f->options, &f->formats, &error),
                         UR_OK);
        snprintf(stem, sizeof stem, "%s.dxf", names[version]);
        path_in(f->dir, stem, dxf, sizeof dxf);
        memcpy(svg, path, sizeof svg);
        assert_int_equal(run("/usr/bin/python3 %s %s %s", script, dxf, svg), 0);
    }
    ur_piece_free(&piece);
}

/*
 * One linetype per distinct dash pattern, in both versions: the kerf layer
 * dashed as the valley folds shares theirs; a single length is a dash and
 * a gap of that length, as SVG's stroke-dasharray repeats an odd list.
 */
static void test_dxf_linetypes(void **state)
{
    fixture *f = *state;
    if (!have_ezdxf())
        skip();
    snprintf(f->machine.styles[UR_OP_KERF].dash, sizeof f->machine.styles[UR_OP_KERF].dash,
             "3, 1.5");
    snprintf(f->machine.styles[UR_OP_MARK].dash, sizeof f->machine.styles[UR_OP_MARK].dash, "2");
    for (int version = 0; version < 2; version++) {
        char path[256];
        path_in(f->dir, version ? "lt2000.dxf" : "lt12.dxf", path, sizeof path);
        f->formats.dxf_version = version ? UR_DXF_R2000 : UR_DXF_R12;
        ur_error error;
        assert_int_equal(ur_write_dxf(path, &f->layout, f->pieces, &f->machine, &f->options,
                                      &f->formats, &error),
                         UR_OK);
        assert_int_equal(
            run("/usr/bin/python3 -c \"import ezdxf,sys; d=ezdxf.readfile('%s'); "
                "assert not d.audit().has_errors; L=lambda n: d.layers.get(n).dxf.linetype; "
                "P=lambda n: tuple(d.linetypes.get(L(n)).simplified_line_pattern()); "
                "assert L('Kerf') == L('Score valley') == 'DASH_3_1P5', L('Kerf'); "
                "assert P('Kerf') == (3, 1.5), P('Kerf'); "
                "assert L('Mark') == 'DASH_2' and P('Mark') == (2, 2), P('Mark'); "
                "assert L('Cut').lower() == 'continuous'; "
                "assert len([t for t in d.linetypes if t.dxf.name.startswith('DASH')]) == 2\"",
                path),
            0);
    }
}

/* A machine that puts two operations on one layer gets it once; odd characters become '_'. */
static void test_dxf_shared_and_odd_layer_names(void **state)
{
    fixture *f = *state;
    snprintf(f->machine.styles[UR_OP_SCORE_VALLEY].layer, 64, "score");
    snprintf(f->machine.styles[UR_OP_KERF].layer, 64, "Kerf: 1/2");
    char path[256];
    path_in(f->dir, "net.dxf", path, sizeof path);
    ur_error error;
    assert_int_equal(
        ur_write_dxf(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    char *text = read_all(path);
    assert_non_null(strstr(text, "  2\nLAYER\n 70\n6\n")); /* 0, Cut, Score, Kerf, Engrave, Mark */
    assert_non_null(strstr(text, "  2\nKerf_ 1_2\n"));
    free(text);
    if (have_ezdxf())
        assert_int_equal(run("/usr/bin/python3 -c \"import ezdxf,sys; d=ezdxf.readfile('%s'); "
                             "sys.exit(len(d.audit().errors))\"",
                             path),
                         0);
}

/* "-": one sheet to standard output, as a file would hold it; several sheets refused. */
static void test_outputs_to_stdout(void **state)
{
    fixture *f = *state;
    char path[256];
    path_in(f->dir, "stdout.dxf", path, sizeof path);
    fflush(stdout);
    int saved = dup(STDOUT_FILENO);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    assert_true(saved >= 0 && fd >= 0);
    assert_int_equal(dup2(fd, STDOUT_FILENO), STDOUT_FILENO);
    close(fd);
    ur_error error;
    ur_status one = ur_write_outputs("-", UR_FORMAT_DXF, &f->layout, f->pieces, &f->machine,
                                     &f->options, &f->formats, &error);
    f->layout.sheet_count = 2;
    ur_status two = ur_write_outputs("-", UR_FORMAT_DXF, &f->layout, f->pieces, &f->machine,
                                     &f->options, &f->formats, &error);
    ur_status both = ur_write_outputs("-", UR_FORMAT_DXF | UR_FORMAT_SVG, &f->layout, f->pieces,
                                      &f->machine, &f->options, &f->formats, &error);
    fflush(stdout);
    assert_int_equal(dup2(saved, STDOUT_FILENO), STDOUT_FILENO);
    close(saved);
    assert_int_equal(one, UR_OK);
    assert_int_equal(two, UR_ERROR_INPUT);
    assert_int_equal(both, UR_ERROR_INPUT);
    if (have_ezdxf())
        check_dxf(f, &f->sheets[0], "AC1009", path);
}

/* Text libharu cannot write in the document information becomes '?', never garbage. */
static void test_pdf_non_ascii_title(void **state)
{
    fixture *f = *state;
    if (!have_tool("pdfinfo"))
        skip();
    char path[256], value[256];
    path_in(f->dir, "net.pdf", path, sizeof path);
    f->options.title = "Lampe \xc3\xa9t\xc3\xa9";
    ur_error error;
    assert_int_equal(
        ur_write_pdf(path, &f->layout, f->pieces, &f->machine, &f->options, &f->formats, &error),
        UR_OK);
    assert_true(pdfinfo(path, "Title:", value, sizeof value));
    assert_string_equal(value, "Lampe ?t?");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_dxf_r12_reads_back, setup, teardown),
        cmocka_unit_test_setup_teardown(test_dxf_r2000_reads_back, setup, teardown),
        cmocka_unit_test_setup_teardown(test_dxf_r12_entities, setup, teardown),
        cmocka_unit_test_setup_teardown(test_dxf_shared_and_odd_layer_names, setup, teardown),
        cmocka_unit_test_setup_teardown(test_exact_circles, setup, teardown),
        cmocka_unit_test_setup_teardown(test_dxf_linetypes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_pdf_pages, setup, teardown),
        cmocka_unit_test_setup_teardown(test_pdf_draws_paths, setup, teardown),
        cmocka_unit_test_setup_teardown(test_png_size_and_fill, setup, teardown),
        cmocka_unit_test_setup_teardown(test_png_default_dpi, setup, teardown),
        cmocka_unit_test(test_formats_by_name),
        cmocka_unit_test_setup_teardown(test_outputs_every_format, setup, teardown),
        cmocka_unit_test_setup_teardown(test_outputs_format_from_extension, setup, teardown),
        cmocka_unit_test_setup_teardown(test_outputs_all_or_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_outputs_to_stdout, setup, teardown),
        cmocka_unit_test_setup_teardown(test_pdf_non_ascii_title, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
