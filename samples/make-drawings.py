#!/usr/bin/env python3
"""Writes the sample drawing that `make demo` nests the way a CAD program draws one.

    samples/make-drawings.py        # rewrites samples/brackets.dxf
    samples/make-drawings.py DIR    # writes it in DIR instead

brackets.dxf    an ASCII DXF (millimetres) of shelf brackets built from blocks:
                "hole", a 5 mm screw hole (CIRCLE); "bracket", an 80 mm
                right-angled plate whose inner edge is a cubic SPLINE, drawn
                with LINEs to chain, four "hole" INSERTs and an engraved
                arrow on layer Engrave (it goes with the plate when nested);
                "tab", a 30 x 12 mm slotted tab with rounded ends (an
                LWPOLYLINE with bulges).  The drawing inserts "bracket" twice
                (as drawn, and turned 90 degrees at 1.25 times the size) and
                mirrored by an extrusion of (0, 0, -1); "tab" in an array of
                4 columns by 2 rows, turned 15 degrees; and a disc: a circle
                of radius 25 mm as a rational quadratic NURBS (nine control
                points, weights 1 and 1/sqrt 2) with a "hole" in its
                middle.  A centre line on layer Construction is an open
                line outside every part: nesting leaves it out, saying so.

Only the standard library is used.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def pairs(*items):
    """DXF group code and value pairs, one per line each."""
    return "".join("%s\n%s\n" % (code, value) for code, value in items)


def line(layer, a, b):
    return pairs((0, "LINE"), (8, layer), (10, a[0]), (20, a[1]), (11, b[0]), (21, b[1]))


def spline(layer, degree, points, knots, weights=None):
    """A SPLINE by its control points (flag 8: planar; 4 when rational)."""
    text = pairs((0, "SPLINE"), (8, layer), (70, 8 + (4 if weights else 0)), (71, degree),
                 (72, len(knots)), (73, len(points)))
    text += "".join(pairs((40, k)) for k in knots)
    text += "".join(pairs((41, "%.17g" % w)) for w in weights or [])
    text += "".join(pairs((10, x), (20, y), (30, 0)) for x, y in points)
    return text


def insert(block, at, layer="0", turn=0, scale=1, extra=()):
    return pairs((0, "INSERT"), (8, layer), (2, block), (10, at[0]), (20, at[1]), (41, scale),
                 (42, scale), (50, turn), *extra)


def block(name, base, entities):
    return pairs((0, "BLOCK"), (8, "0"), (2, name), (70, 0), (10, base[0]), (20, base[1]),
                 (3, name)) + entities + pairs((0, "ENDBLK"), (8, "0"))


def bracket():
    """The plate: two straight edges, ends 8 mm wide, and a cubic spline between them."""
    corners = [(0, 0), (80, 0), (80, 8)]
    text = "".join(line("0", p, q) for p, q in zip(corners, corners[1:]))
    text += spline("0", 3, [(80, 8), (40, 12), (12, 40), (8, 80)], [0, 0, 0, 0, 1, 1, 1, 1])
    text += line("0", (8, 80), (0, 80)) + line("0", (0, 80), (0, 0))
    for at in [(4, 20), (4, 60), (20, 4), (60, 4)]:
        text += insert("hole", at)
    arrow = [(16, 30), (16, 16), (30, 16)]
    text += pairs((0, "LWPOLYLINE"), (8, "Engrave"), (90, len(arrow)), (70, 0))
    text += "".join(pairs((10, x), (20, y)) for x, y in arrow)
    return text


def tab():
    """A 30 x 12 mm tab with half-round ends and a 3 mm slot along it."""
    outline = [(0, 0, 0), (24, 0, 1), (24, 12, 0), (0, 12, 1)]
    slot = [(6, 4.5, 0), (18, 4.5, 1), (18, 7.5, 0), (6, 7.5, 1)]
    text = ""
    for ring in (outline, slot):
        text += pairs((0, "LWPOLYLINE"), (8, "0"), (90, len(ring)), (70, 1))
        text += "".join(pairs((10, x), (20, y), (42, bulge)) for x, y, bulge in ring)
    return text


def disc():
    """A circle of radius 25 mm about (260, 60), exactly, as a rational quadratic NURBS."""
    corners = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
    points = [(260 + 25 * x, 60 + 25 * y) for x, y in corners]
    weights = [1 if i % 2 == 0 else math.sqrt(0.5) for i in range(9)]
    return spline("0", 2, points, [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4], weights)


def write_brackets(path):
    header = pairs((0, "SECTION"), (2, "HEADER"), (9, "$INSUNITS"), (70, 4), (0, "ENDSEC"))
    blocks = pairs((0, "SECTION"), (2, "BLOCKS"))
    blocks += block("hole", (0, 0), pairs((0, "CIRCLE"), (8, "0"), (10, 0), (20, 0), (40, 2.5)))
    blocks += block("bracket", (0, 0), bracket())
    blocks += block("tab", (12, 6), tab())
    blocks += pairs((0, "ENDSEC"))
    entities = pairs((0, "SECTION"), (2, "ENTITIES"))
    entities += insert("bracket", (0, 0))
    entities += insert("bracket", (200, 0), turn=90, scale=1.25)
    entities += insert("bracket", (40, 0), extra=[(230, -1)])  # mirrored: at x = -40, turned over
    entities += insert("tab", (20, 120), turn=15, extra=[(70, 4), (71, 2), (44, 40), (45, 20)])
    entities += disc() + insert("hole", (260, 60))
    entities += line("Construction", (-120, 105), (320, 105))
    entities += pairs((0, "ENDSEC"), (0, "EOF"))
    with open(path, "w") as f:
        f.write(header + blocks + entities)


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else HERE
    write_brackets(os.path.join(directory, "brackets.dxf"))


if __name__ == "__main__":
    main()
