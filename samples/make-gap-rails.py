#!/usr/bin/env python3
"""Writes the rails whose strip has a gap, for `--adjust` in `make demo` and the tests.

    samples/make-gap-rails.py     # rewrites the files below, in samples/

gap-rail1.csv    half an ellipse, 60 by 40 mm semi-axes, in z = 0:
                 (60 cos t, 40 sin t, 0), t from 0 to pi in 200 points
gap-rail2.csv    a wavy curve above it (issue 25):
                 (35 cos t, 20 sin t + 4 sin 3t, 45 + 6 sin 2t), the same t

The developable strip between them folds back about 103.5 mm along rail 1
(two roots of the tangency condition merge and the next ruling lands on rail
2 far away) and is missing at the end of rail 1: rail 2's 4 mm and 6 mm
waves are in the way.  `unroll strip --adjust rail2` reshapes rail 2 so that
the strip exists along all of rail 1.  Only the standard library is used.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))

POINTS = 200


def curve(point):
    return [point(math.pi * i / (POINTS - 1)) for i in range(POINTS)]


def ellipse(t):
    return (60 * math.cos(t), 40 * math.sin(t), 0.0)


def wavy(t):
    return (35 * math.cos(t), 20 * math.sin(t) + 4 * math.sin(3 * t), 45 + 6 * math.sin(2 * t))


def write(name, header, points):
    with open(os.path.join(HERE, name), "w") as f:
        for line in header:
            f.write("# %s\n" % line)
        for point in points:
            f.write("%.9f,%.9f,%.9f\n" % tuple(0.0 if abs(c) < 5e-10 else c for c in point))


def main():
    write("gap-rail1.csv", ["Rail 1 of a strip with a gap (samples/make-gap-rails.py): half an",
                            "ellipse (60 cos t, 40 sin t, 0), t from 0 to pi in %d points." % POINTS,
                            "x,y,z in mm."], curve(ellipse))
    write("gap-rail2.csv", ["Rail 2 of a strip with a gap (samples/make-gap-rails.py): the wavy",
                            "curve (35 cos t, 20 sin t + 4 sin 3t, 45 + 6 sin 2t), t from 0 to pi",
                            "in %d points. x,y,z in mm." % POINTS], curve(wavy))


if __name__ == "__main__":
    main()
