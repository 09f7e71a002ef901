#!/usr/bin/env python3
"""Writes the ESICUP strip-packing instances in the form 'unroll nest' reads.

Input: the instances as JSON (the common format of Gardeyn's conversion,
e.g. the assets of the jagua-rs repository or Oliveira's OR-Datasets), one
file per instance, given on the command line.  Output, next to this script:
one directory per instance holding one SVG per quantity (qN.svg: every part
type that is needed N times, one closed path each, 1 unit = 1 mm, y up as
in the data), and one line per instance in instances.txt is written by hand
(widths there are the original ones, see README.md).

Usage: convert.py DIR_WITH_JSON NAME...
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def number(value):
    text = f"{value:.6f}".rstrip("0").rstrip(".")
    return text if text not in ("-0", "") else "0"


def write_instance(source, name):
    with open(os.path.join(source, name + ".json")) as f:
        data = json.load(f)
    by_quantity = {}
    for item in data["items"]:
        shape = item["shape"]
        if shape["type"] != "simple_polygon":
            raise SystemExit(f"{name}: item {item['id']}: {shape['type']} is not handled")
        ring = [tuple(p) for p in shape["data"]]
        if ring[0] == ring[-1]:
            ring.pop()
        by_quantity.setdefault(item["demand"], []).append((item["id"], ring))
    folder = os.path.join(HERE, name)
    os.makedirs(folder, exist_ok=True)
    for old in os.listdir(folder):
        if old.endswith(".svg"):
            os.remove(os.path.join(folder, old))
    for quantity, parts in sorted(by_quantity.items()):
        xs = [x for _, ring in parts for x, _ in ring]
        ys = [y for _, ring in parts for _, y in ring]
        # The parts are laid side by side so that the drawing can be looked at;
        # where they are in the file does not matter to the nesting.
        lines, shift = [], 0.0
        top = max(ys) - min(ys)
        for ident, ring in parts:
            x0 = min(x for x, _ in ring)
            y0 = min(y for _, y in ring)
            points = " ".join(
                f"{number(x - x0 + shift)},{number(top - (y - y0))}" for x, y in ring)
            lines.append(f'  <path id="{name}-{ident}" d="M {points} Z"/>')
            shift += max(x for x, _ in ring) - x0 + 0.1 * top
        width = number(shift)
        height = number(top)
        with open(os.path.join(folder, f"q{quantity}.svg"), "w") as f:
            f.write('<?xml version="1.0" encoding="UTF-8"?>\n')
            f.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}mm" '
                    f'height="{height}mm" viewBox="0 0 {width} {height}" '
                    'fill="none" stroke="black" stroke-width="0.1">\n')
            f.write("\n".join(lines) + "\n</svg>\n")


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    for name in sys.argv[2:]:
        write_instance(sys.argv[1], name)


if __name__ == "__main__":
    main()
