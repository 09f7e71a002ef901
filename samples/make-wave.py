#!/usr/bin/env python3
"""Writes the rails of the wavy wall that `make demo` and the tests use.

    samples/make-wave.py          # rewrites the files below, in samples/

wave-rail1.csv   the foot of a wavy wall: a sine wave y = 10 sin(2 pi x / 250)
                 in z = 0, x from 0 to 500 mm in 101 points (every 5 mm), two
                 whole waves; it bends one way, then the other, with
                 inflections at x = 0, 125, 250, 375 and 500 (points 1, 26,
                 51, 76 and 101), and bends no tighter than 250^2 / (4 pi^2
                 10) = 158.3 mm, which 3 mm plywood takes without grooves
wave-rail2.csv   its top: the same wave lifted straight up by 100 mm

The strip between them is a general cylinder (its rulings vertical, 100 mm
long) whose net is a rectangle 100 mm by the length of the wave.  Only the
standard library is used.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))

LENGTH, WAVELENGTH, AMPLITUDE, HEIGHT, POINTS = 500.0, 250.0, 10.0, 100.0, 101


def wave(z):
    """The wave's points at height z."""
    return [(LENGTH * i / (POINTS - 1),
             AMPLITUDE * math.sin(2 * math.pi * (LENGTH * i / (POINTS - 1)) / WAVELENGTH), z)
            for i in range(POINTS)]


def write(name, header, points):
    with open(os.path.join(HERE, name), "w") as f:
        for line in header:
            f.write("# %s\n" % line)
        for point in points:
            f.write("%.9f,%.9f,%.9f\n" % tuple(0.0 if abs(c) < 5e-10 else c for c in point))


def main():
    about = "y = %g sin(2 pi x / %g), x from 0 to %g mm in %d points" % (AMPLITUDE, WAVELENGTH,
                                                                       LENGTH, POINTS)
    write("wave-rail1.csv", ["Rail 1 of a wavy wall (samples/make-wave.py): the sine wave",
                             about + ", z = 0.",
                             "Inflections at x = 0, 125, 250, 375 and 500. x,y,z in mm."],
          wave(0.0))
    write("wave-rail2.csv", ["Rail 2 of a wavy wall (samples/make-wave.py): the same wave",
                             "lifted straight up by %g mm: the wall is a general cylinder." % HEIGHT,
                             "x,y,z in mm."],
          wave(HEIGHT))


if __name__ == "__main__":
    main()
