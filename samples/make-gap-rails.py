#!/usr/bin/env python3
"""Writes the rails whose strip has gaps, for `--adjust` in `make demo` and the tests.

    samples/make-gap-rails.py     # rewrites the files below, in samples/

gap-rail1.csv    half an ellipse, 60 by 40 mm semi-axes, in z = 0:
                 (60 cos t, 40 sin t, 0), t from 0 to pi in 200 points
gap-rail2.csv    a wavy curve above it (issue 25):
                 (35 cos t, 20 sin t + 4 sin 3t, 45 + 6 sin 2t), the same t

The developable strip between them folds back about 103.5 mm along rail 1
(two roots of the tangency condition merge and the next ruling lands on rail
2 far away) and is missing at the end of rail 1: rail 2's 4 mm and 6 mm
waves are in the way.  `unroll strip --adjust rail2` reshapes rail 2 so that
the strip exists along all of rail 1.

arc-rail1.csv    half a circle of radius 50 mm in z = 0, t from 0 to pi in
                 120 points: rail 1 of the two below
bump-rail2.csv   half a circle of radius 30 mm in z = 40 with a bump 6 mm
                 high in its middle: z = 40 + 6 exp(-((t - pi/2) / 0.2)^2)
dent-rail2.csv   half a circle of radius 30 mm in z = 40 with a dent 2 mm
                 deep toward the centre in its middle, radius
                 30 - 2 exp(-((t - pi/2) / 0.15)^2): it stays in z = 40, for
                 --adjust-plane 0,0,1

Without the bump or the dent the strip is a frustum of a cone; with them it
has gaps.

twist-rail1.csv  an arc of radius 150 mm in z = 0, 150 mm long, in 120 points:
                 (150 sin(s/150), 150 (1 - cos(s/150)), 0), s from 0 to 150
twist-rail2.csv  rail 1 lifted by 40 mm and twisted against it about its
                 tangent: rail 1 + 40 (sin a n + cos a z), n the arc's unit
                 normal toward its centre, a = 1.2 exp(-((s - 75) / 20)^2):
                 the twist moves rail 2 sideways by up to 40 sin 1.2 =
                 37.3 mm in the middle

Without the twist the strip is a general cylinder, its rulings upright;
with it the strip is missing round the twist.  Only the standard library is
used.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))

POINTS = 200
ARC_POINTS = 120


def curve(point, points=POINTS):
    return [point(math.pi * i / (points - 1)) for i in range(points)]


def ellipse(t):
    return (60 * math.cos(t), 40 * math.sin(t), 0.0)


def wavy(t):
    return (35 * math.cos(t), 20 * math.sin(t) + 4 * math.sin(3 * t), 45 + 6 * math.sin(2 * t))


def arc(t):
    return (50 * math.cos(t), 50 * math.sin(t), 0.0)


def bump(t):
    return (30 * math.cos(t), 30 * math.sin(t), 40 + 6 * math.exp(-((t - math.pi / 2) / 0.2) ** 2))


def dent(t):
    radius = 30 - 2 * math.exp(-((t - math.pi / 2) / 0.15) ** 2)
    return (radius * math.cos(t), radius * math.sin(t), 40.0)


TWIST_RADIUS, TWIST_LENGTH, TWIST_HEIGHT, TWIST_POINTS = 150.0, 150.0, 40.0, 120


def twist_rail1(s):
    t = s / TWIST_RADIUS
    return (TWIST_RADIUS * math.sin(t), TWIST_RADIUS * (1 - math.cos(t)), 0.0)


def twist_rail2(s):
    x, y, _ = twist_rail1(s)
    a = 1.2 * math.exp(-((s - TWIST_LENGTH / 2) / 20) ** 2)
    t = s / TWIST_RADIUS
    sideways = TWIST_HEIGHT * math.sin(a)
    return (x - sideways * math.sin(t), y + sideways * math.cos(t), TWIST_HEIGHT * math.cos(a))


def along_twist(point):
    return [point(TWIST_LENGTH * i / (TWIST_POINTS - 1)) for i in range(TWIST_POINTS)]


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
    write("arc-rail1.csv", ["Rail 1 of the bump and dent rails (samples/make-gap-rails.py): half a",
                            "circle (50 cos t, 50 sin t, 0), t from 0 to pi in %d points." % ARC_POINTS,
                            "x,y,z in mm."], curve(arc, ARC_POINTS))
    write("bump-rail2.csv", ["Rail 2 with a bump (samples/make-gap-rails.py): (30 cos t, 30 sin t,",
                             "40 + 6 exp(-((t - pi/2) / 0.2)^2)), t from 0 to pi in %d points."
                             % ARC_POINTS, "x,y,z in mm."], curve(bump, ARC_POINTS))
    write("dent-rail2.csv", ["Rail 2 with a dent (samples/make-gap-rails.py): radius",
                             "30 - 2 exp(-((t - pi/2) / 0.15)^2) in z = 40, t from 0 to pi in %d"
                             % ARC_POINTS, "points. x,y,z in mm."], curve(dent, ARC_POINTS))
    write("twist-rail1.csv", ["Rail 1 of the twisted rails (samples/make-gap-rails.py): an arc",
                              "(150 sin(s/150), 150 (1 - cos(s/150)), 0), s from 0 to 150 mm in",
                              "%d points. x,y,z in mm." % TWIST_POINTS], along_twist(twist_rail1))
    write("twist-rail2.csv", ["Rail 2 twisted against rail 1 (samples/make-gap-rails.py): rail 1",
                              "+ 40 (sin a n + cos a z), n its normal toward its centre,",
                              "a = 1.2 exp(-((s - 75) / 20)^2), s from 0 to 150 mm in %d points."
                              % TWIST_POINTS, "x,y,z in mm."], along_twist(twist_rail2))


if __name__ == "__main__":
    main()
