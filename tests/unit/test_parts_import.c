/*
 * test_parts_import.c: parts from SVG and DXF files made elsewhere.  The
 * same 100 x 50 mm plate with a 20 mm round hole, written as SVG in mm, in
 * px, with a viewBox scale and transforms, and as DXF in inches and in mm,
 * must come out the same; nesting of rings, bulges, chained loops, path
 * syntax, an Inkscape-like file, the kerf a file says it was compensated
 * for, and every refusal with its file and line.
 */
#include "test_support.h"

static char directory[64];

static int make_directory(void **state)
{
    (void)state;
    strcpy(directory, "/tmp/unroll-test-parts-XXXXXX");
    return mkdtemp(directory) ? 0 : -1;
}

static int remove_directory(void **state)
{
    (void)state;
    return remove_test_directory(directory);
}

/* Writes text to directory/name; path receives the file's path. */
static void write_file(const char *name, const char *text, char *path, size_t size)
{
    path_in(directory, name, path, size);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_int_equal(fwrite(text, 1, strlen(text), file), strlen(text));
    assert_int_equal(fclose(file), 0);
}

/* Imports text written as name; fails on error. */
static ur_parts import_text(const char *name, const char *text, double unit)
{
    char path[256];
    write_file(name, text, path, sizeof path);
    ur_parts_import_options options;
    ur_parts_import_options_default(&options);
    options.unit = unit;
    ur_parts parts;
    ur_error error = {0};
    if (ur_parts_import(path, &options, &parts, &error) != UR_OK)
        fail_msg("%s: %s", name, error.message);
    return parts;
}

/* The settings the last refusal's error named (ur_error's setting). */
static char refused_setting[64];

/* Expects text written as name to be refused with a message "PATH<location>: ...fragment...". */
static void expect_refusal_of(const char *name, const char *text, double unit, bool strict,
                              const char *location, const char *fragment)
{
    char path[256];
    write_file(name, text, path, sizeof path);
    ur_parts_import_options options;
    ur_parts_import_options_default(&options);
    options.unit = unit;
    options.strict = strict;
    ur_parts parts;
    ur_error error = {0};
    assert_int_equal(ur_parts_import(path, &options, &parts, &error), UR_ERROR_INPUT);
    assert_null(parts.pieces);
    assert_int_equal(parts.count, 0);
    char prefix[300];
    snprintf(prefix, sizeof prefix, "%s%s: ", path, location);
    if (strncmp(error.message, prefix, strlen(prefix)) != 0 || !strstr(error.message, fragment))
        fail_msg("message '%s' lacks '%s' or '%s'", error.message, prefix, fragment);
    snprintf(refused_setting, sizeof refused_setting, "%s", error.setting);
}

static void expect_refusal(const char *name, const char *text, double unit, const char *location,
                           const char *fragment)
{
    expect_refusal_of(name, text, unit, false, location, fragment);
}

/* Refused with strict only: without, what is open is left out with a warning. */
static void expect_strict_refusal(const char *name, const char *text, const char *location,
                                  const char *fragment)
{
    expect_refusal_of(name, text, 0, true, location, fragment);
}

static double path_area(const ur_path *path)
{
    return ur_polygon_signed_area(path->points, path->count);
}

/* ---- The same plate in five files -------------------------------------------- */

static const double plate_hole_area = M_PI * 100; /* r = 10 mm */

/* The plate x 10..110, y 30..80 mm, hole centred (60, 55): as each file must give it. */
static void check_plate(const ur_parts *parts, const char *name)
{
    assert_int_equal(parts->count, 1);
    const ur_piece *piece = &parts->pieces[0];
    if (name)
        assert_string_equal(piece->name, name);
    assert_int_equal(piece->path_count, 2);
    for (size_t i = 0; i < 2; i++) {
        assert_true(piece->paths[i].closed);
        assert_int_equal(piece->paths[i].op, UR_OP_CUT);
    }
    double outline = path_area(&piece->paths[0]), hole = -path_area(&piece->paths[1]);
    assert_true(fabs(outline - 5000) < 1e-6);
    /* A flattened circle lies inside it, short by less than tolerance x perimeter. */
    double slack = 0.01 * 2 * M_PI * 10;
    if (!(hole <= plate_hole_area + 1e-9 && hole > plate_hole_area - slack))
        fail_msg("hole area %.9g, expected %.9g less under %g", hole, plate_hole_area, slack);
    assert_true(fabs(piece->measures.flat_area - (outline - hole)) < 1e-9);
    assert_true(fabs(piece->box.min.x - 10) < 1e-6 && fabs(piece->box.max.x - 110) < 1e-6);
    assert_true(fabs(piece->box.min.y - 30) < 1e-6 && fabs(piece->box.max.y - 80) < 1e-6);
    ur_box hole_box = ur_box_of_points(piece->paths[1].points, piece->paths[1].count);
    assert_true(fabs((hole_box.min.x + hole_box.max.x) / 2 - 60) < 0.01);
    assert_true(fabs((hole_box.min.y + hole_box.max.y) / 2 - 55) < 0.01);
    assert_true(hole_box.max.x - hole_box.min.x > 20 - 0.02);
}

static void test_svg_in_mm(void **state)
{
    (void)state;
    /* y = 20..70 down from the top of a 100 mm page is 30..80 up from its bottom. */
    ur_parts parts = import_text("mm.svg",
                                 "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200mm\" "
                                 "height=\"100mm\" viewBox=\"0 0 200 100\">\n"
                                 "  <rect id=\"plate\" x=\"10\" y=\"20\" width=\"100\" "
                                 "height=\"50\"/>\n"
                                 "  <circle id=\"hole\" cx=\"60\" cy=\"45\" r=\"10\"/>\n"
                                 "</svg>\n",
                                 0);
    check_plate(&parts, "plate");
    assert_int_equal(parts.warning_count, 0);
    ur_parts_free(&parts);
}

static void test_svg_in_px(void **state)
{
    (void)state;
    /* 96 px to the inch, no viewBox: user units are px. */
    ur_parts parts =
        import_text("px.svg",
                    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"755.90551181px\" "
                    "height=\"377.95275591px\">\n"
                    "  <rect x=\"37.795275591\" y=\"75.590551181\" width=\"377.95275591\" "
                    "height=\"188.97637795\"/>\n"
                    "  <circle cx=\"226.77165354\" cy=\"170.07874016\" r=\"37.795275591\"/>\n"
                    "</svg>\n",
                    0);
    check_plate(&parts, "px-1");
    ur_parts_free(&parts);
}

static void test_svg_viewbox_and_transforms(void **state)
{
    (void)state;
    /* One user unit is 0.1 mm; the group moves and doubles; the circle turns about itself. */
    ur_parts parts = import_text(
        "scaled.svg",
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20cm\" height=\"10cm\" "
        "viewBox=\"0 0 2000 1000\">\n"
        "  <g transform=\"translate(100,200) scale(2)\">\n"
        "    <g transform=\"matrix(1 0 0 1 0 0)\">\n"
        "      <path id=\"outline\" d=\"M0,0 H500 V250 H0 Z\"/>\n"
        "      <circle transform=\"rotate(30 250 125)\" cx=\"250\" cy=\"125\" r=\"50\"/>\n"
        "    </g>\n"
        "  </g>\n"
        "</svg>\n",
        0);
    check_plate(&parts, "outline");
    ur_parts_free(&parts);
}

static void test_svg_skew_and_rotate(void **state)
{
    (void)state;
    /* skewX keeps the area of a square; rotate(90) turns 100 x 50 into 50 x 100. */
    ur_parts parts =
        import_text("skew.svg",
                    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" "
                    "viewBox=\"0 0 100 100\">\n"
                    "  <rect id=\"skewed\" transform=\"skewX(45)\" x=\"0\" y=\"0\" width=\"10\" "
                    "height=\"10\"/>\n"
                    "  <rect id=\"turned\" transform=\"translate(300 0) rotate(90) scale(1,0.5) "
                    "skewY(0)\" x=\"0\" y=\"0\" width=\"100\" height=\"100\"/>\n"
                    "</svg>\n",
                    0);
    assert_int_equal(parts.count, 2);
    assert_string_equal(parts.pieces[0].name, "skewed");
    assert_true(fabs(path_area(&parts.pieces[0].paths[0]) - 100) < 1e-9);
    ur_box box = parts.pieces[0].box;
    assert_true(fabs(box.max.x - box.min.x - 20) < 1e-9);
    box = parts.pieces[1].box;
    assert_true(fabs(box.max.x - box.min.x - 50) < 1e-9);
    assert_true(fabs(box.max.y - box.min.y - 100) < 1e-9);
    ur_parts_free(&parts);
}

/* The plate as DXF: an LWPOLYLINE and a CIRCLE, in the unit $INSUNITS gives. */
static const char *plate_dxf(char *text, size_t size, int insunits, double unit)
{
    snprintf(text, size,
             "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n%d\n0\nENDSEC\n"
             "0\nSECTION\n2\nENTITIES\n"
             "0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n"
             "10\n%.17g\n20\n%.17g\n10\n%.17g\n20\n%.17g\n"
             "10\n%.17g\n20\n%.17g\n10\n%.17g\n20\n%.17g\n"
             "0\nCIRCLE\n8\n0\n10\n%.17g\n20\n%.17g\n40\n%.17g\n"
             "0\nTEXT\n8\n0\n10\n0\n20\n0\n1\nplate\n"
             "0\nENDSEC\n0\nEOF\n",
             insunits, 10 / unit, 30 / unit, 110 / unit, 30 / unit, 110 / unit, 80 / unit,
             10 / unit, 80 / unit, 60 / unit, 55 / unit, 10 / unit);
    return text;
}

static void test_dxf_in_inches_and_mm(void **state)
{
    (void)state;
    char text[2048];
    ur_parts parts = import_text("inches.dxf", plate_dxf(text, sizeof text, 1, 25.4), 0);
    check_plate(&parts, "inches-1");
    /* The TEXT is left out with a note naming its line. */
    assert_int_equal(parts.warning_count, 1);
    assert_non_null(strstr(parts.warnings[0], "TEXT"));
    ur_parts_free(&parts);
    parts = import_text("mm.dxf", plate_dxf(text, sizeof text, 4, 1), 0);
    check_plate(&parts, "mm-1");
    ur_parts_free(&parts);
    /* No unit in the file: the caller's. */
    parts = import_text("unitless.dxf", plate_dxf(text, sizeof text, 0, 25.4), 25.4);
    check_plate(&parts, NULL);
    ur_parts_free(&parts);
}

/* The kerf an SVG says it was compensated for, with description as its Dublin Core description. */
static double svg_kerf(const char *description)
{
    char text[1024];
    snprintf(text, sizeof text,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" "
             "viewBox=\"0 0 100 100\"><metadata><rdf:RDF "
             "xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\" "
             "xmlns:dc=\"http://purl.org/dc/elements/1.1/\"><rdf:Description rdf:about=\"\">"
             "<dc:description>%s</dc:description></rdf:Description></rdf:RDF></metadata>"
             "<rect x=\"10\" y=\"10\" width=\"20\" height=\"20\"/>"
             "<rect x=\"40\" y=\"10\" width=\"20\" height=\"20\"/></svg>\n",
             description);
    ur_parts parts = import_text("kerf.svg", text, 0);
    assert_int_equal(parts.count, 2);
    /* Every part takes what the file says. */
    assert_true(parts.pieces[0].kerf_compensated == parts.kerf_compensated);
    assert_true(parts.pieces[1].kerf_compensated == parts.kerf_compensated);
    double kerf = parts.kerf_compensated;
    ur_parts_free(&parts);
    return kerf;
}

static void test_kerf_note(void **state)
{
    (void)state;
    assert_true(svg_kerf(UR_KERF_NOTE "0.1 mm") == 0.1);
    assert_true(svg_kerf("\n   " UR_KERF_NOTE "0.25 mm\n  ") == 0.25);
    /* Anything else says nothing: compensated in full, as a drawing from elsewhere. */
    const char *not_notes[] = {UR_KERF_NOTE "0.1",
                               UR_KERF_NOTE "0.1 inch",
                               UR_KERF_NOTE "-0.1 mm",
                               UR_KERF_NOTE "0 mm",
                               UR_KERF_NOTE "nan mm",
                               UR_KERF_NOTE "0.1 mm, and more",
                               "paths compensated for a kerf of 0.1 mm",
                               ""};
    for (size_t i = 0; i < sizeof not_notes / sizeof not_notes[0]; i++)
        assert_true(svg_kerf(not_notes[i]) == 0);
    /* Where Inkscape keeps its own metadata, in a cc:Work, it is found too. */
    ur_parts work = import_text("work.svg",
                                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" "
                                "height=\"100mm\" viewBox=\"0 0 100 100\"><metadata><rdf:RDF "
                                "xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\" "
                                "xmlns:cc=\"http://creativecommons.org/ns#\" "
                                "xmlns:dc=\"http://purl.org/dc/elements/1.1/\"><cc:Work "
                                "rdf:about=\"\"><dc:description>" UR_KERF_NOTE "0.3 mm"
                                "</dc:description></cc:Work></rdf:RDF></metadata>"
                                "<rect x=\"10\" y=\"10\" width=\"20\" height=\"20\"/></svg>\n",
                                0);
    assert_true(work.kerf_compensated == 0.3);
    ur_parts_free(&work);
    /* A description in another namespace is not Dublin Core's. */
    ur_parts parts = import_text("other.svg",
                                 "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" "
                                 "height=\"100mm\" viewBox=\"0 0 100 100\"><metadata>"
                                 "<description>" UR_KERF_NOTE "0.1 mm</description></metadata>"
                                 "<rect x=\"10\" y=\"10\" width=\"20\" height=\"20\"/></svg>\n",
                                 0);
    assert_true(parts.kerf_compensated == 0);
    ur_parts_free(&parts);
    /* DXF: a 999 comment, anywhere before the entities; a CRLF file too. */
    char plate[2048], text[2400];
    plate_dxf(plate, sizeof plate, 4, 1);
    snprintf(text, sizeof text, "999\njob: nest\n999\n" UR_KERF_NOTE "0.15 mm\n%s", plate);
    parts = import_text("kerf.dxf", text, 0);
    assert_true(parts.kerf_compensated == 0.15 && parts.pieces[0].kerf_compensated == 0.15);
    ur_parts_free(&parts);
    snprintf(text, sizeof text, "999\r\n" UR_KERF_NOTE "0.2 mm\r\n%s", plate);
    parts = import_text("crlf.dxf", text, 0);
    assert_true(parts.kerf_compensated == 0.2);
    ur_parts_free(&parts);
    parts = import_text("plain.dxf", plate, 0);
    assert_true(parts.kerf_compensated == 0 && parts.pieces[0].kerf_compensated == 0);
    ur_parts_free(&parts);
}

/* ---- Units, nesting, curves ----------------------------------------------------- */

static void test_units_required(void **state)
{
    (void)state;
    const char *svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 10 10\">\n"
                      "<rect x=\"0\" y=\"0\" width=\"4\" height=\"2\"/></svg>\n";
    /* The message names the setting that gives the unit, as the library names it, no flag. */
    expect_refusal("nounits.svg", svg, 0, ":1", "give its unit with units");
    assert_string_equal(refused_setting, "units");
    ur_parts parts = import_text("nounits.svg", svg, 25.4);
    assert_true(fabs(path_area(&parts.pieces[0].paths[0]) - 8 * 25.4 * 25.4) < 1e-6);
    ur_parts_free(&parts);
    /* A width without a unit is in the caller's unit too: 20 cm over a 10-unit viewBox. */
    parts = import_text("unitless.svg",
                        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20\" height=\"20\" "
                        "viewBox=\"0 0 10 10\"><rect width=\"4\" height=\"2\"/></svg>\n",
                        10);
    assert_true(fabs(path_area(&parts.pieces[0].paths[0]) - 8 * 400) < 1e-6);
    ur_parts_free(&parts);
    char text[2048];
    plate_dxf(text, sizeof text, 0, 1);
    expect_refusal("nounits.dxf", text, 0, ":7", "give its unit with units");
    assert_string_equal(refused_setting, "units");
    /* No $INSUNITS at all. */
    expect_refusal("noheader.dxf",
                   "0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\n0\n20\n0\n40\n1\n0\nENDSEC\n0\nEOF\n",
                   0, "", "give its unit with units");
    assert_string_equal(refused_setting, "units");
}

static void test_nesting(void **state)
{
    (void)state;
    /* A ring (r 50 with a hole of r 40), a part in its hole, and a hole in that part. */
    ur_parts parts =
        import_text("nested.svg",
                    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200mm\" height=\"200mm\" "
                    "viewBox=\"0 0 200 200\">\n"
                    "<circle id=\"ring\" cx=\"100\" cy=\"100\" r=\"50\"/>\n"
                    "<circle cx=\"100\" cy=\"100\" r=\"40\"/>\n"
                    "<rect id=\"inner\" x=\"80\" y=\"80\" width=\"40\" height=\"40\"/>\n"
                    "<rect x=\"95\" y=\"95\" width=\"10\" height=\"10\"/>\n"
                    "<rect id=\"beside\" x=\"160\" y=\"0\" width=\"10\" height=\"10\"/>\n"
                    "</svg>\n",
                    0);
    assert_int_equal(parts.count, 3);
    assert_string_equal(parts.pieces[0].name, "ring");
    assert_int_equal(parts.pieces[0].path_count, 2);
    assert_true(path_area(&parts.pieces[0].paths[0]) > 0);
    assert_true(path_area(&parts.pieces[0].paths[1]) < 0);
    assert_string_equal(parts.pieces[1].name, "inner");
    assert_int_equal(parts.pieces[1].path_count, 2);
    assert_true(fabs(parts.pieces[1].measures.flat_area - 1500) < 1e-9);
    assert_string_equal(parts.pieces[2].name, "beside");
    assert_int_equal(parts.pieces[2].path_count, 1);
    ur_parts_free(&parts);
}

static void test_path_syntax(void **state)
{
    (void)state;
    ur_parts parts =
        import_text("syntax.svg",
                    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"300mm\" height=\"300mm\" "
                    "viewBox=\"0 0 300 300\">\n"
                    /* implicit lineto after M, 1e1, "-10-0" */
                    "<path id=\"bar\" d=\"M0,0 1e1,0l0 5-10-0z\"/>\n"
                    /* "-.5.5" and "-.5-.5": a house of area 1.25 */
                    "<path id=\"house\" d=\"M20 0l1 0 0 1-.5.5-.5-.5z\"/>\n"
                    /* a parabolic segment: 2/3 of its control triangle, 3333.33 */
                    "<path id=\"q\" d=\"M0,100 Q50,200 100,100 Z\"/>\n"
                    /* C then S reflecting it: 2 x 0.6 w h = 6000 */
                    "<path id=\"s\" d=\"M150,50 c0,50 100,50 100,0 S150,0 150,50 z\"/>\n"
                    /* T after Q: a bump out, its reflection in: the 100 x 40 rectangle's area */
                    "<path id=\"t\" d=\"M0,250 q25,-40 50,0 t50,0 v40 h-100 z\"/>\n"
                    /* arcs with flags run together: a 10 mm circle in two halves */
                    "<path id=\"a\" d=\"M150,250a10,10 0 1020,0a10 10 0 10-20 0Z\"/>\n"
                    "</svg>\n",
                    0);
    assert_int_equal(parts.count, 6);
    double expected[6] = {50, 1.25, 10000.0 / 3, 6000, 4000, M_PI * 100};
    double slack[6] = {1e-9, 1e-9, 0.01 * 250, 0.01 * 400, 0.01 * 250, 0.01 * 2 * M_PI * 10};
    for (size_t i = 0; i < 6; i++) {
        double area = parts.pieces[i].measures.flat_area;
        if (!(fabs(area - expected[i]) <= slack[i]))
            fail_msg("%s: area %.9g, expected %.9g within %g", parts.pieces[i].name, area,
                     expected[i], slack[i]);
    }
    ur_parts_free(&parts);
}

static void test_dxf_bulges(void **state)
{
    (void)state;
    /* 100 x 60 with a half circle of r 50 on top: bulge 1 out, -1 in. */
    const char *format = "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n"
                         "0\nSECTION\n2\nENTITIES\n"
                         "0\nLWPOLYLINE\n90\n4\n70\n1\n10\n0\n20\n0\n10\n100\n20\n0\n"
                         "10\n100\n20\n60\n42\n%s\n10\n0\n20\n60\n"
                         "0\nENDSEC\n0\nEOF\n";
    char text[1024];
    double half = M_PI * 2500 / 2, slack = 0.01 * M_PI * 50;
    snprintf(text, sizeof text, format, "1");
    ur_parts parts = import_text("bulge.dxf", text, 0);
    double area = parts.pieces[0].measures.flat_area;
    if (!(area <= 6000 + half + 1e-9 && area > 6000 + half - slack))
        fail_msg("bulge 1: area %.9g, expected %.9g", area, 6000 + half);
    assert_true(fabs(parts.pieces[0].box.max.y - 110) < 0.01);
    ur_parts_free(&parts);
    snprintf(text, sizeof text, format, "-1.0");
    parts = import_text("bulge.dxf", text, 0);
    area = parts.pieces[0].measures.flat_area;
    if (!(area >= 6000 - half - 1e-9 && area < 6000 - half + slack))
        fail_msg("bulge -1: area %.9g, expected %.9g", area, 6000 - half);
    ur_parts_free(&parts);
}

static void test_dxf_chained_loop(void **state)
{
    (void)state;
    /* The D shape from loose LINEs (one backwards) and an ARC; an old-style POLYLINE; an ELLIPSE.
     */
    ur_parts parts = import_text("chain.dxf",
                                 "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n"
                                 "0\nSECTION\n2\nENTITIES\n"
                                 "0\nLINE\n10\n0\n20\n0\n11\n100\n21\n0\n"
                                 "0\nARC\n10\n50\n20\n50\n40\n50\n50\n0\n51\n180\n"
                                 "0\nLINE\n10\n0\n20\n0\n11\n0\n21\n50.001\n"
                                 "0\nLINE\n10\n100\n20\n0\n11\n100\n21\n50\n"
                                 "0\nPOLYLINE\n66\n1\n70\n1\n"
                                 "0\nVERTEX\n10\n200\n20\n0\n0\nVERTEX\n10\n210\n20\n0\n"
                                 "0\nVERTEX\n10\n210\n20\n10\n42\n1\n0\nVERTEX\n10\n200\n20\n10\n"
                                 "0\nSEQEND\n"
                                 "0\nELLIPSE\n10\n300\n20\n0\n11\n0\n21\n20\n40\n0.5\n"
                                 "0\nENDSEC\n0\nEOF\n",
                                 0);
    assert_int_equal(parts.count, 3);
    double area = parts.pieces[0].measures.flat_area, exact = 5000 + M_PI * 1250;
    if (!(fabs(area - exact) < 0.01 * M_PI * 50 + 0.01))
        fail_msg("chained: area %.9g, expected %.9g", area, exact);
    area = parts.pieces[1].measures.flat_area;
    exact = 100 + M_PI * 25 / 2;
    if (!(fabs(area - exact) < 0.01 * M_PI * 5 + 1e-9))
        fail_msg("polyline: area %.9g, expected %.9g", area, exact);
    /* The ELLIPSE: major axis 20 along y, minor 10. */
    area = parts.pieces[2].measures.flat_area;
    exact = M_PI * 20 * 10;
    if (!(area <= exact && area > exact - 0.01 * 2 * M_PI * 20))
        fail_msg("ellipse: area %.9g, expected %.9g", area, exact);
    assert_true(fabs(parts.pieces[2].box.max.y - 20) < 1e-9);
    assert_true(fabs(parts.pieces[2].box.max.x - 310) < 0.01);
    ur_parts_free(&parts);
}

static void test_inkscape_like(void **state)
{
    (void)state;
    ur_parts parts = import_text(
        "drawing.svg",
        "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n"
        "<!-- Created with Inkscape (http://www.inkscape.org/) -->\n"
        "<svg\n"
        "   width=\"210mm\"\n   height=\"297mm\"\n   viewBox=\"0 0 210 297\"\n"
        "   version=\"1.1\"\n   id=\"svg5\"\n"
        "   inkscape:version=\"1.2.2 (b0a8486541, 2022-12-01)\"\n"
        "   sodipodi:docname=\"drawing.svg\"\n"
        "   xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\"\n"
        "   xmlns:sodipodi=\"http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd\"\n"
        "   xmlns=\"http://www.w3.org/2000/svg\"\n"
        "   xmlns:svg=\"http://www.w3.org/2000/svg\"\n"
        "   xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\"\n"
        "   xmlns:dc=\"http://purl.org/dc/elements/1.1/\">\n"
        "  <sodipodi:namedview id=\"namedview7\" pagecolor=\"#ffffff\" "
        "inkscape:document-units=\"mm\" />\n"
        "  <defs id=\"defs2\"><rect id=\"unused\" width=\"5\" height=\"5\"/></defs>\n"
        "  <metadata><rdf:RDF><dc:title>x</dc:title></rdf:RDF></metadata>\n"
        "  <g inkscape:label=\"Layer 1\" inkscape:groupmode=\"layer\" id=\"layer1\"\n"
        "     transform=\"translate(-20,-30)\">\n"
        "    <path style=\"fill:none;stroke:#000000;stroke-width:0.264583\"\n"
        "       d=\"m 30,50 h 100 v 50 H 30 Z m 40,25 a 10,10 0 0 1 10,-10 10,10 0 0 1 10,10 "
        "10,10 0 0 1 -10,10 10,10 0 0 1 -10,-10 z\"\n"
        "       id=\"path1\" sodipodi:nodetypes=\"ccccc\" />\n"
        "    <text x=\"40\" y=\"60\" id=\"text1\"><tspan>plate</tspan></text>\n"
        "  </g>\n"
        "  <g inkscape:label=\"hidden\" inkscape:groupmode=\"layer\" id=\"layer2\" "
        "style=\"display:none\">\n"
        "    <path d=\"M 0,0 L 10,10\" id=\"open-but-hidden\"/>\n"
        "  </g>\n"
        "</svg>\n",
        0);
    /* x 10..110; y 20..70 from the top of a 297 mm page. */
    assert_int_equal(parts.count, 1);
    const ur_piece *piece = &parts.pieces[0];
    assert_string_equal(piece->name, "path1");
    assert_int_equal(piece->path_count, 2);
    assert_true(fabs(path_area(&piece->paths[0]) - 5000) < 1e-6);
    assert_true(fabs(-path_area(&piece->paths[1]) - plate_hole_area) < 0.01 * 2 * M_PI * 10);
    assert_true(fabs(piece->box.min.x - 10) < 1e-6 && fabs(piece->box.max.y - 277) < 1e-6);
    assert_int_equal(parts.warning_count, 1);
    assert_non_null(strstr(parts.warnings[0], "text id=\"text1\""));
    ur_parts_free(&parts);
}

static void test_self_crossing(void **state)
{
    (void)state;
    /* A square with a spike drawn out and back: repaired to the square, with a warning. */
    ur_parts parts =
        import_text("spike.svg",
                    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" "
                    "viewBox=\"0 0 100 100\">\n"
                    "<polygon id=\"spiky\" points=\"0,0 10,0 10,5 15,5 10,5 10,10 0,10\"/>\n"
                    "</svg>\n",
                    0);
    assert_int_equal(parts.count, 1);
    assert_true(fabs(parts.pieces[0].measures.flat_area - 100) < 1e-9);
    assert_true(fabs(parts.pieces[0].box.max.x - 10) < 1e-9);
    assert_int_equal(parts.warning_count, 1);
    assert_non_null(strstr(parts.warnings[0], "polygon id=\"spiky\""));
    ur_parts_free(&parts);
    /* A bow tie is two shapes: refused, naming it. */
    expect_refusal("bowtie.svg",
                   "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" "
                   "viewBox=\"0 0 100 100\">\n\n"
                   "<polygon id=\"bow\" points=\"0,0 10,10 10,0 0,10\"/>\n"
                   "</svg>\n",
                   0, ":3: polygon id=\"bow\"", "crosses itself");
}

#define SVG_HEAD                                                                                   \
    "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" "                  \
    "viewBox=\"0 0 100 100\">\n"

/* ---- Lines that go with their part ----------------------------------------------- */

static size_t paths_of(const ur_piece *piece, ur_op op, bool closed)
{
    size_t n = 0;
    for (size_t i = 0; i < piece->path_count; i++)
        n += piece->paths[i].op == op && piece->paths[i].closed == closed;
    return n;
}

static void test_lines_go_with_their_part(void **state)
{
    (void)state;
    /*
     * Two plates: a fold (score group, as unroll writes) across the first,
     * a label (engrave) and an open cut slit inside the second, a closed
     * mark inside the first; an open line and an engraving outside both
     * are left out, one warning naming the first one's line and the count.
     */
    ur_parts parts = import_text(
        "lines.svg",
        SVG_HEAD
        "<g id=\"cut\"><rect id=\"a\" width=\"20\" height=\"10\"/>\n"
        "<rect id=\"b\" x=\"30\" width=\"20\" height=\"10\"/>\n"
        "<path d=\"M 35 2 L 45 2\"/>\n"
        "<path d=\"M 60 0 L 70 0\"/></g>\n"
        "<g id=\"score\"><path d=\"M 10 0 L 10 10\"/></g>\n"
        "<g inkscape:label=\"Engrave\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/"
        "inkscape\"><path d=\"M 35 5 L 40 8 L 45 5\"/><path d=\"M 80 5 L 90 5\"/></g>\n"
        "<g id=\"mark\"><rect x=\"2\" y=\"2\" width=\"3\" height=\"3\"/></g></svg>\n",
        0);
    assert_int_equal(parts.count, 2);
    const ur_piece *a = &parts.pieces[0], *b = &parts.pieces[1];
    assert_string_equal(a->name, "a");
    assert_int_equal(a->path_count, 3);
    assert_int_equal(paths_of(a, UR_OP_SCORE, false), 1);
    assert_int_equal(paths_of(a, UR_OP_MARK, true), 1);
    assert_int_equal(b->path_count, 3);
    assert_int_equal(paths_of(b, UR_OP_ENGRAVE, false), 1);
    assert_int_equal(paths_of(b, UR_OP_CUT, false), 1);
    /* The holes and areas are the rings' alone. */
    assert_true(fabs(a->measures.flat_area - 200) < 1e-9);
    assert_int_equal(parts.warning_count, 1);
    assert_non_null(strstr(parts.warnings[0], ":5: 2 shapes left out"));
    assert_non_null(strstr(parts.warnings[0], "lines 5, 7"));
    ur_parts_free(&parts);
}

static void test_ends_within_the_tolerance(void **state)
{
    (void)state;
    /*
     * A path closed in relative coordinates whose last point lands 1e-15
     * from its start: a square, neither crossing itself nor repaired.
     */
    ur_parts parts = import_text("relative.svg",
                                 SVG_HEAD "<path d=\"m 0.1 0.1 l 10 0 l 0 10 l -10 0 "
                                          "l 1e-15 -10 z\"/></svg>\n",
                                 0);
    assert_int_equal(parts.count, 1);
    assert_int_equal(parts.warning_count, 0);
    assert_int_equal(parts.pieces[0].paths[0].count, 4);
    assert_true(fabs(parts.pieces[0].measures.flat_area - 100) < 1e-9);
    ur_parts_free(&parts);
    /*
     * LibreCAD's full ellipse: its end parameter 2 pi rounded to
     * 6.28318530718.  Radii 2 and 1: area within the flattening's loss of
     * 2 pi (the chords stray at most 0.01 mm inside the curve).
     */
    char text[1024];
    snprintf(text, sizeof text,
             "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n"
             "0\nELLIPSE\n8\n0\n10\n5\n20\n5\n11\n9.18485099361e-017\n21\n2\n40\n0.5\n41\n0\n"
             "42\n6.28318530718\n0\nARC\n8\n0\n10\n20\n20\n5\n40\n1\n50\n0\n51\n359.9999999999\n"
             "0\nENDSEC\n0\nEOF\n");
    parts = import_text("ellipse.dxf", text, 0);
    assert_int_equal(parts.count, 2);
    assert_int_equal(parts.warning_count, 0);
    double ellipse = parts.pieces[0].measures.flat_area,
           circle = parts.pieces[1].measures.flat_area;
    double perimeter = 2 * M_PI * 2; /* more than the ellipse's */
    assert_true(ellipse <= 2 * M_PI && ellipse >= 2 * M_PI - perimeter * 0.01);
    assert_true(circle <= M_PI && circle >= M_PI - 2 * M_PI * 0.01);
    ur_parts_free(&parts);
}

/* ---- Blocks, splines, use ------------------------------------------------------- */

#define DXF_UNITS_MM "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n"

/* A 10 mm square block with its base point at its centre, and one that inserts it twice. */
#define DXF_BLOCKS                                                                                 \
    "0\nSECTION\n2\nBLOCKS\n"                                                                      \
    "0\nBLOCK\n2\nsq\n10\n5\n20\n5\n"                                                              \
    "0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n10\n20\n0\n10\n10\n20\n10\n10\n0\n20\n1" \
    "0\n"                                                                                          \
    "0\nENDBLK\n"                                                                                  \
    "0\nBLOCK\n2\npair\n10\n0\n20\n0\n"                                                            \
    "0\nINSERT\n8\n0\n2\nsq\n10\n0\n20\n0\n41\n2\n42\n0.5\n50\n30\n"                               \
    "0\nINSERT\n8\n0\n2\nsq\n10\n40\n20\n0\n50\n-45\n"                                             \
    "0\nENDBLK\n0\nENDSEC\n"

static ur_vec2 centroid(const ur_path *path)
{
    ur_vec2 sum = {0, 0};
    for (size_t i = 0; i < path->count; i++)
        sum = ur_vec2_add(sum, path->points[i]);
    return ur_vec2_scale(sum, 1.0 / (double)path->count);
}

static bool has_centroid(const ur_parts *parts, ur_vec2 expected)
{
    for (size_t k = 0; k < parts->count; k++)
        if (ur_vec2_distance(centroid(&parts->pieces[k].paths[0]), expected) < 1e-9)
            return true;
    return false;
}

static void test_dxf_blocks(void **state)
{
    (void)state;
    /*
     * pair at (100, 100), turned 15 degrees, scaled 1.5: its squares are
     * 2 x 0.5 then 1.5 times larger (225 mm2) and 1.5 times (225 mm2); sq
     * in 3 columns 20 apart and 2 rows 30 apart, turned 10 degrees at
     * (0, 200): 6 squares of 100 mm2 whose centres are the insertion point
     * plus the turned column and row offsets (the base point is the centre).
     */
    ur_parts parts =
        import_text("blocks.dxf",
                    DXF_UNITS_MM DXF_BLOCKS
                    "0\nSECTION\n2\nENTITIES\n"
                    "0\nINSERT\n8\n0\n2\npair\n10\n100\n20\n100\n41\n1.5\n42\n1.5\n50\n15\n"
                    "0\nINSERT\n8\n0\n2\nsq\n10\n0\n20\n200\n50\n10\n70\n3\n71\n2\n44\n20\n45\n30\n"
                    "0\nENDSEC\n0\nEOF\n",
                    0);
    assert_int_equal(parts.count, 8);
    double areas[8];
    for (size_t k = 0; k < 8; k++)
        areas[k] = parts.pieces[k].measures.flat_area;
    assert_true(fabs(areas[0] - 225) < 1e-9 && fabs(areas[1] - 225) < 1e-9);
    for (size_t k = 2; k < 8; k++)
        assert_true(fabs(areas[k] - 100) < 1e-9);
    double c = cos(10 * M_PI / 180), s = sin(10 * M_PI / 180);
    for (int row = 0; row < 2; row++)
        for (int column = 0; column < 3; column++) {
            double dx = 20.0 * column, dy = 30.0 * row;
            assert_true(has_centroid(&parts, ur_vec2_make(c * dx - s * dy, 200 + s * dx + c * dy)));
        }
    /* The second square of pair: at (40, 0) in pair, so at (100, 100) + 1.5 (40, 0) turned 15. */
    double c15 = cos(15 * M_PI / 180), s15 = sin(15 * M_PI / 180);
    assert_true(has_centroid(&parts, ur_vec2_make(100 + 60 * c15, 100 + 60 * s15)));
    ur_parts_free(&parts);
}

static void test_dxf_splines(void **state)
{
    (void)state;
    /*
     * A circle of radius 10 about (50, 50) as a rational quadratic NURBS
     * (nine control points, weights 1 and 1/sqrt 2, double interior knots):
     * every flattened point on the circle, the area within the flattening's
     * loss (chords within 0.01 mm) of 100 pi.  A cubic Bezier from (0, 0)
     * over (0, 10) and (10, 10) to (10, 0), closed by a LINE: its area is
     * 60 exactly (the integral of y dx over the curve).
     */
    char text[4096];
    int n = snprintf(text, sizeof text,
                     DXF_UNITS_MM
                     "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n8\n0\n70\n12\n71\n2\n72\n12\n73\n9\n");
    static const double knots[] = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
    for (int i = 0; i < 12; i++)
        n += snprintf(text + n, sizeof text - (size_t)n, "40\n%g\n", knots[i]);
    static const double corners[9][2] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                                         {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    for (int i = 0; i < 9; i++)
        n += snprintf(text + n, sizeof text - (size_t)n, "41\n%.17g\n", i % 2 ? sqrt(0.5) : 1.0);
    for (int i = 0; i < 9; i++)
        n += snprintf(text + n, sizeof text - (size_t)n, "10\n%g\n20\n%g\n30\n0\n",
                      50 + 10 * corners[i][0], 50 + 10 * corners[i][1]);
    snprintf(
        text + n, sizeof text - (size_t)n,
        "0\nSPLINE\n8\n0\n70\n8\n71\n3\n72\n8\n73\n4\n40\n0\n40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n"
        "40\n1\n40\n1\n10\n0\n20\n0\n10\n0\n20\n10\n10\n10\n20\n10\n10\n10\n20\n0\n"
        "0\nLINE\n8\n0\n10\n10\n20\n0\n11\n0\n21\n0\n0\nENDSEC\n0\nEOF\n");
    ur_parts parts = import_text("splines.dxf", text, 0);
    assert_int_equal(parts.count, 2);
    const ur_path *circle = &parts.pieces[0].paths[0];
    assert_true(circle->count > 100);
    for (size_t i = 0; i < circle->count; i++)
        assert_true(fabs(ur_vec2_distance(circle->points[i], ur_vec2_make(50, 50)) - 10) < 1e-9);
    double area = parts.pieces[0].measures.flat_area;
    assert_true(area <= 100 * M_PI && area >= 100 * M_PI - 20 * M_PI * 0.01);
    double bezier = parts.pieces[1].measures.flat_area;
    assert_true(bezier <= 60 && bezier >= 60 - 40 * 0.01);
    assert_true(bezier > 60 - 0.1);
    ur_parts_free(&parts);
}

static void test_svg_use(void **state)
{
    (void)state;
    /*
     * A plate with a round hole (a group in defs), drawn through use twice
     * inside a group that is used twice again, once scaled 1.5; a symbol
     * of a 10 mm triangle with a viewBox, used 40 mm wide: 16 times its area.
     */
    ur_parts parts = import_text(
        "use.svg",
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
        "width=\"200mm\" height=\"200mm\" viewBox=\"0 0 200 200\">\n"
        "<defs><g id=\"plate\"><rect width=\"20\" height=\"10\"/>"
        "<polygon points=\"4,4 6,4 6,6 4,6\"/></g>\n"
        "<symbol id=\"sym\" viewBox=\"0 0 10 10\"><path d=\"M0,0 L10,0 L0,10 Z\"/></symbol>\n"
        "<g id=\"two\"><use href=\"#plate\"/><use xlink:href=\"#plate\" x=\"30\" "
        "transform=\"rotate(10)\"/></g></defs>\n"
        "<use href=\"#two\" x=\"10\" y=\"10\"/>\n"
        "<use href=\"#sym\" x=\"100\" y=\"100\" width=\"40\" height=\"40\"/>\n"
        "<use href=\"#two\" transform=\"translate(0,100) scale(1.5)\"/>\n</svg>\n",
        0);
    assert_int_equal(parts.count, 5);
    int small = 0, large = 0, triangle = 0;
    for (size_t k = 0; k < parts.count; k++) {
        double area = parts.pieces[k].measures.flat_area;
        small += fabs(area - 196) < 1e-9;
        large += fabs(area - 196 * 2.25) < 1e-9;
        triangle += fabs(area - 800) < 1e-9;
        /* Copies are numbered, not named by the id they copy. */
        assert_non_null(strstr(parts.pieces[k].name, "use-"));
    }
    assert_int_equal(small, 2);
    assert_int_equal(large, 2);
    assert_int_equal(triangle, 1);
    ur_parts_free(&parts);
}

/* A line drawn twice chains into a loop of no area: an open shape, not a refusal of the file. */
static void test_chain_of_no_shape(void **state)
{
    (void)state;
    const char *text =
        DXF_UNITS_MM "0\nSECTION\n2\nENTITIES\n"
                     "0\nLWPOLYLINE\n8\n0\n90\n4\n70\n1\n10\n0\n20\n0\n10\n10\n20\n0\n10\n10\n20\n1"
                     "0\n10\n0\n20\n10\n"
                     "0\nLINE\n8\n0\n10\n20\n20\n0\n11\n30\n21\n0\n"
                     "0\nLINE\n8\n0\n10\n30\n20\n0\n11\n20\n21\n0\n0\nENDSEC\n0\nEOF\n";
    ur_parts parts = import_text("twice.dxf", text, 0);
    assert_int_equal(parts.count, 1);
    assert_int_equal(parts.warning_count, 1);
    assert_non_null(strstr(parts.warnings[0], "1 open shape left out (LINE"));
    ur_parts_free(&parts);
    expect_strict_refusal("twice.dxf", text, ":40: LINE", "encloses no area");
}

static void test_block_spline_use_refusals(void **state)
{
    (void)state;
    expect_refusal("self.dxf",
                   DXF_UNITS_MM
                   "0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nA\n10\n0\n20\n0\n"
                   "0\nINSERT\n8\n0\n2\nA\n0\nENDBLK\n0\nENDSEC\n"
                   "0\nSECTION\n2\nENTITIES\n0\nINSERT\n8\n0\n2\nA\n0\nENDSEC\n0\nEOF\n",
                   0, ":24: INSERT", "block 'A' refers to itself");
    expect_refusal("loop.dxf",
                   DXF_UNITS_MM
                   "0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nA\n0\nINSERT\n2\nB\n0\nENDBLK\n"
                   "0\nBLOCK\n2\nB\n0\nINSERT\n2\nA\n0\nENDBLK\n0\nENDSEC\n"
                   "0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nA\n0\nENDSEC\n0\nEOF\n",
                   0, ":30: INSERT", "block 'A' refers to itself");
    expect_refusal("undefined.dxf",
                   DXF_UNITS_MM "0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nnone\n0\nENDSEC\n0\nEOF\n",
                   0, ":16: INSERT", "block 'none' is not defined");
    expect_refusal("degree.dxf",
                   DXF_UNITS_MM
                   "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n71\n0\n40\n0\n40\n1\n10\n0\n20\n0"
                   "\n0\nENDSEC\n0\nEOF\n",
                   0, ":16: SPLINE", "degree 0");
    expect_refusal("knots.dxf",
                   DXF_UNITS_MM
                   "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n71\n1\n40\n0\n40\n0\n40\n2\n40\n1"
                   "\n10\n0\n20\n0\n10\n1\n20\n0\n0\nENDSEC\n0\nEOF\n",
                   0, ":16: SPLINE", "knots decrease");
    expect_refusal("fit.dxf",
                   DXF_UNITS_MM
                   "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n71\n3\n11\n0\n21\n0\n11\n1\n21\n1"
                   "\n0\nENDSEC\n0\nEOF\n",
                   0, ":16: SPLINE", "fit points");
    expect_refusal("self.svg", SVG_HEAD "\n<use id=\"u\" href=\"#u\"/></svg>\n", 0,
                   ":3: use id=\"u\"", "refers to itself");
    expect_refusal("group.svg",
                   SVG_HEAD
                   "<g id=\"g\"><rect width=\"5\" height=\"5\"/>\n<use href=\"#g\"/></g></svg>\n",
                   0, ":3: use", "refers to itself");
    expect_refusal("nowhere.svg", SVG_HEAD "<use href=\"#none\"/></svg>\n", 0, ":2: use",
                   "points at no element");
    expect_refusal("outside.svg", SVG_HEAD "<use href=\"other.svg#a\"/></svg>\n", 0, ":2: use",
                   "outside the file");
}

/* ---- Refusals -------------------------------------------------------------------- */

static void test_svg_refusals(void **state)
{
    (void)state;
    expect_strict_refusal("open.svg",
                          SVG_HEAD "<rect width=\"5\" height=\"5\"/>\n"
                                   "<path id=\"cut1\" d=\"M 0 0 L 10 0 L 10 10\"/>\n</svg>\n",
                          ":3: path id=\"cut1\"", "open");
    expect_strict_refusal("line.svg",
                          SVG_HEAD "\n<rect width=\"5\" height=\"5\"/>"
                                   "<line x1=\"10\" y1=\"0\" x2=\"15\" y2=\"5\"/></svg>\n",
                          ":3: line", "only closed shapes");
    expect_strict_refusal("polyline.svg",
                          SVG_HEAD "<polyline id=\"pl\" points=\"0,0 5,0 5,5\"/></svg>\n",
                          ":2: polyline id=\"pl\"", "open");
    /* Without strict, a file of open shapes only has no part, and says where the first is. */
    expect_refusal("only-open.svg",
                   SVG_HEAD "\n<line x1=\"0\" y1=\"0\" x2=\"5\" y2=\"5\"/></svg>\n", 0, ":3",
                   "no closed shape: nothing to use as a part (1 open shape: line first)");
    expect_refusal("xml.svg", SVG_HEAD "<rect width=\"5\" height=\"5\">\n</svg>\n", 0, ":3", "");
    expect_refusal("data.svg", SVG_HEAD "<path id=\"p\" d=\"M 0 0 L 5 nan Z\"/></svg>\n", 0,
                   ":2: path id=\"p\"", "bad path data at \"nan Z\"");
    expect_refusal("start.svg", SVG_HEAD "<path d=\"L 5 5 Z\"/></svg>\n", 0, ":2: path",
                   "bad path data");
    expect_refusal("transform.svg",
                   SVG_HEAD "<rect transform=\"spin(3)\" width=\"5\" height=\"5\"/></svg>\n", 0,
                   ":2: rect", "not a transform");
    expect_refusal("zero.svg", SVG_HEAD "<polygon points=\"0,0 5,5 10,10\"/></svg>\n", 0,
                   ":2: polygon", "no area");
    expect_refusal("huge.svg", SVG_HEAD "<rect width=\"1e12\" height=\"5\"/></svg>\n", 0,
                   ":2: rect", "beyond");
    expect_refusal("width.svg", SVG_HEAD "<rect width=\"0\" height=\"5\"/></svg>\n", 0, ":2: rect",
                   "width must be positive");
    expect_refusal("cross.svg",
                   SVG_HEAD "<rect width=\"10\" height=\"10\"/>\n"
                            "<rect id=\"r\" x=\"5\" y=\"5\" width=\"10\" height=\"10\"/></svg>\n",
                   0, ":3: rect id=\"r\"", "crosses");
    /* Two holes side by side that fill the plate: no material (found by fuzz_dxf). */
    expect_refusal("holes.svg",
                   SVG_HEAD "<rect id=\"plate\" width=\"20\" height=\"10\"/>\n"
                            "<rect width=\"10\" height=\"10\"/>\n"
                            "<rect x=\"10\" width=\"10\" height=\"10\"/></svg>\n",
                   0, ":2: rect id=\"plate\"", "its holes leave nothing of it");
    expect_refusal("empty.svg", SVG_HEAD "<text>hello</text></svg>\n", 0, "", "no closed shape");
    expect_refusal("root.svg", "<html/>\n", 0, ":1", "not svg");
    expect_refusal("empty-file.svg", "", 0, "", "empty");
}

#define DXF_HEAD "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n"

static void test_dxf_refusals(void **state)
{
    (void)state;
    /* Lines 11..: the entities. */
    expect_strict_refusal("open.dxf",
                          DXF_HEAD "0\nLINE\n10\n0\n20\n0\n11\n10\n21\n0\n"
                                   "0\nLINE\n10\n10\n20\n0\n11\n10\n21\n10\n0\nENDSEC\n0\nEOF\n",
                          ":26: LINE", "open");
    expect_refusal("code.dxf", DXF_HEAD "0\nCIRCLE\nten\n0\n0\nENDSEC\n0\nEOF\n", 0, ":17",
                   "\"ten\" is not a group code");
    expect_refusal("value.dxf", DXF_HEAD "0\nCIRCLE\n10", 0, ":17", "group code 10 has no value");
    expect_refusal("number.dxf", DXF_HEAD "0\nCIRCLE\n10\n1x\n20\n0\n40\n1\n0\nENDSEC\n0\nEOF\n", 0,
                   ":18", "\"1x\" is not a finite number");
    expect_refusal("nan.dxf", DXF_HEAD "0\nCIRCLE\n10\nnan\n20\n0\n40\n1\n0\nENDSEC\n0\nEOF\n", 0,
                   ":18", "not a finite number");
    expect_refusal("huge.dxf", DXF_HEAD "0\nCIRCLE\n10\n1e300\n20\n0\n40\n1\n0\nENDSEC\n0\nEOF\n",
                   0, ":16: CIRCLE", "beyond");
    expect_refusal("radius.dxf", DXF_HEAD "0\nCIRCLE\n10\n0\n20\n0\n40\n0\n0\nENDSEC\n0\nEOF\n", 0,
                   ":16: CIRCLE", "radius 0");
    expect_refusal("units.dxf", "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n3\n0\nENDSEC\n0\nEOF\n",
                   0, ":7", "$INSUNITS 3");
    expect_refusal("nothing.dxf", DXF_HEAD "0\nTEXT\n1\nhi\n0\nENDSEC\n0\nEOF\n", 0, "",
                   "no closed shape");
    expect_refusal("binary.dxf", "AutoCAD Binary DXF\r\n\x1a", 0, "", "binary");
}

static void test_file_refusals(void **state)
{
    (void)state;
    ur_parts parts;
    ur_error error = {0};
    char path[256];
    path_in(directory, "missing.svg", path, sizeof path);
    assert_int_equal(ur_parts_import(path, NULL, &parts, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "missing.svg: cannot open"));
    write_file("parts.txt", "x", path, sizeof path);
    assert_int_equal(ur_parts_import(path, NULL, &parts, &error), UR_ERROR_INPUT);
    assert_non_null(strstr(error.message, "parts.txt: unknown kind of file"));
    assert_true(ur_parts_unit_mm("in") == 25.4 && ur_parts_unit_mm("px") == 25.4 / 96);
    assert_true(ur_parts_unit_mm("furlong") == 0);
}

/* The part named name's outline. */
static const ur_path *outline_of(const ur_parts *parts, const char *name)
{
    for (size_t k = 0; k < parts->count; k++)
        if (strcmp(parts->pieces[k].name, name) == 0)
            return &parts->pieces[k].paths[0];
    fail_msg("no part %s", name);
    return NULL;
}

/* path is exactly the circle about (x, y) of radius r, every point on it. */
static void assert_circle(const ur_path *path, double x, double y, double r)
{
    if (!(fabs(path->circle.radius - r) <= 1e-9 && fabs(path->circle.centre.x - x) <= 1e-9 &&
          fabs(path->circle.centre.y - y) <= 1e-9))
        fail_msg("circle (%.12g, %.12g) r %.12g, expected (%.12g, %.12g) r %.12g",
                 path->circle.centre.x, path->circle.centre.y, path->circle.radius, x, y, r);
    for (size_t k = 0; k < path->count; k++)
        assert_true(fabs(ur_vec2_distance(path->points[k], path->circle.centre) - r) <= 1e-9);
}

/*
 * Circles stay circles exactly when the file says so: a circle turned and
 * scaled alike both ways (radius 5 x 2 about its turned centre), a path of
 * two half arcs of one circle; not an ellipse scaled more one way, nor a
 * half disc closed by a line.  A DXF CIRCLE keeps its own, mirrored by an
 * extrusion of (0, 0, -1) as its points are.
 */
static void test_circles_kept(void **state)
{
    (void)state;
    ur_parts parts = import_text(
        "round.svg",
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"100mm\" height=\"100mm\" "
        "viewBox=\"0 0 100 100\">\n"
        "<circle id=\"a\" cx=\"20\" cy=\"20\" r=\"5\" transform=\"rotate(30 50 50) scale(2)\"/>\n"
        "<ellipse id=\"b\" cx=\"80\" cy=\"20\" rx=\"5\" ry=\"5\" transform=\"scale(1 1.5)\"/>\n"
        "<path id=\"c\" d=\"M10,80 a5,5 0 0,1 10,0 a5,5 0 0,1 -10,0 Z\"/>\n"
        "<path id=\"d\" d=\"M60,80 a5,5 0 0,1 10,0 L60,80 Z\"/>\n"
        "</svg>\n",
        0);
    assert_int_equal(parts.count, 4);
    /* (40, 40) turned 30 degrees about (50, 50), SVG's y down; then y up from the bottom. */
    double c = cos(M_PI / 6), s = sin(M_PI / 6);
    double x = 50 - 10 * c + 10 * s, y = 50 - 10 * s - 10 * c;
    assert_circle(outline_of(&parts, "a"), x, 100 - y, 10);
    assert_true(outline_of(&parts, "b")->circle.radius == 0);
    assert_circle(outline_of(&parts, "c"), 15, 20, 5);
    assert_true(outline_of(&parts, "d")->circle.radius == 0);
    ur_parts_free(&parts);

    char text[2048];
    parts = import_text("plate.dxf", plate_dxf(text, sizeof text, 1, 25.4), 0);
    assert_int_equal(parts.pieces[0].path_count, 2);
    assert_true(parts.pieces[0].paths[0].circle.radius == 0);
    assert_circle(&parts.pieces[0].paths[1], 60, 55, 10);
    ur_parts_free(&parts);
    parts = import_text("mirrored.dxf",
                        "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n"
                        "0\nSECTION\n2\nENTITIES\n"
                        "0\nCIRCLE\n8\n0\n10\n10\n20\n5\n30\n0\n40\n3\n210\n0\n220\n0\n230\n-1\n"
                        "0\nENDSEC\n0\nEOF\n",
                        0);
    assert_circle(&parts.pieces[0].paths[0], -10, 5, 3);
    ur_parts_free(&parts);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_svg_in_mm),
        cmocka_unit_test(test_svg_in_px),
        cmocka_unit_test(test_svg_viewbox_and_transforms),
        cmocka_unit_test(test_svg_skew_and_rotate),
        cmocka_unit_test(test_dxf_in_inches_and_mm),
        cmocka_unit_test(test_units_required),
        cmocka_unit_test(test_nesting),
        cmocka_unit_test(test_path_syntax),
        cmocka_unit_test(test_dxf_bulges),
        cmocka_unit_test(test_dxf_chained_loop),
        cmocka_unit_test(test_inkscape_like),
        cmocka_unit_test(test_self_crossing),
        cmocka_unit_test(test_svg_refusals),
        cmocka_unit_test(test_dxf_refusals),
        cmocka_unit_test(test_file_refusals),
        cmocka_unit_test(test_circles_kept),
        cmocka_unit_test(test_lines_go_with_their_part),
        cmocka_unit_test(test_ends_within_the_tolerance),
        cmocka_unit_test(test_dxf_blocks),
        cmocka_unit_test(test_dxf_splines),
        cmocka_unit_test(test_svg_use),
        cmocka_unit_test(test_chain_of_no_shape),
        cmocka_unit_test(test_block_spline_use_refusals),
        cmocka_unit_test(test_kerf_note),
    };
    return cmocka_run_group_tests(tests, make_directory, remove_directory);
}
