#!/usr/bin/env python3
"""End-to-end tests of the unroll command.

Each test runs the command in a fresh temporary directory and checks what it
wrote with real readers (xmllint, rsvg-convert, Python's XML parser) against
numbers worked out here from closed forms.  Usage: cli_tests.py PATH/TO/unroll
Prints "ok NAME" or "FAIL NAME: why" per test and ends with
"cli: N passed, N failed".
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

UNROLL = os.path.abspath(sys.argv[1])
REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SVG = "{http://www.w3.org/2000/svg}"
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"
FINE = ["--tolerance", "1e-5"]
TESTS = []


def test(function):
    TESTS.append(function)
    return function


class Failure(Exception):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)


def close(actual, expected, relative, what):
    check(abs(actual - expected) <= relative * abs(expected),
          "%s = %.12g, expected %.12g within %g" % (what, actual, expected, relative))


def run(work, *args, status=0):
    result = subprocess.run([UNROLL, *args], cwd=work, capture_output=True, text=True,
                            env=dict(os.environ, UNROLL_PROFILES=os.path.join(REPO, "profiles")))
    check(result.returncode == status, "unroll %s: exit %d, expected %d; stderr: %s"
          % (" ".join(args), result.returncode, status, result.stderr.strip()))
    return result


def paths(svg_file, layer):
    """The paths of one layer group as lists of (x, y) and a closed flag."""
    root = ET.parse(svg_file).getroot()
    group = root.find("%sg[@id='%s']" % (SVG, layer))
    check(group is not None, "%s has no layer %s" % (svg_file, layer))
    found = []
    for element in group.iter(SVG + "path"):
        d = element.get("d")
        closed = d.rstrip().endswith("Z")
        numbers = [float(n) for n in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", d)]
        points = list(zip(numbers[0::2], numbers[1::2]))
        found.append((points, closed))
    return found


def area(points):
    return abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1)
                   in zip(points, points[1:] + points[:1]))) / 2


def perimeter(points):
    return sum(math.dist(p, q) for p, q in zip(points, points[1:] + points[:1]))


def outlines(svg_file):
    found = paths(svg_file, "cut")
    for points, closed in found:
        check(closed, "an outline is not closed with Z")
    return [points for points, _ in found]


def two_longest_edges(points):
    edges = sorted(range(len(points)), key=lambda i: -math.dist(points[i], points[(i + 1) % len(points)]))
    return edges[0], edges[1]


def arcs(points):
    """Splits an outline at its two longest edges into the two curves between them."""
    n = len(points)
    a, b = sorted(two_longest_edges(points))
    first = points[a + 1:b + 1]
    second = points[b + 1:] + points[:a + 1]
    return first, second


def circle_through(p, q, r):
    d = 2 * (p[0] * (q[1] - r[1]) + q[0] * (r[1] - p[1]) + r[0] * (p[1] - q[1]))
    p2, q2, r2 = p[0] ** 2 + p[1] ** 2, q[0] ** 2 + q[1] ** 2, r[0] ** 2 + r[1] ** 2
    return ((p2 * (q[1] - r[1]) + q2 * (r[1] - p[1]) + r2 * (p[1] - q[1])) / d,
            (p2 * (r[0] - q[0]) + q2 * (p[0] - r[0]) + r2 * (q[0] - p[0])) / d)


def lines_meet(p1, p2, q1, q2):
    dx1, dy1 = p2[0] - p1[0], p2[1] - p1[1]
    dx2, dy2 = q2[0] - q1[0], q2[1] - q1[1]
    denominator = dx1 * dy2 - dy1 * dx2
    t = ((q1[0] - p1[0]) * dy2 - (q1[1] - p1[1]) * dx2) / denominator
    return (p1[0] + t * dx1, p1[1] + t * dy1)


def valid_svg(svg_file, width, height):
    check(subprocess.run(["xmllint", "--noout", svg_file]).returncode == 0, "xmllint rejects " + svg_file)
    png = svg_file + ".png"
    check(subprocess.run(["rsvg-convert", "-o", png, svg_file]).returncode == 0,
          "rsvg-convert cannot render " + svg_file)
    os.remove(png)
    root = ET.parse(svg_file).getroot()
    check(root.get("width") == "%gmm" % width and root.get("height") == "%gmm" % height,
          "size %s x %s" % (root.get("width"), root.get("height")))
    check(root.get("viewBox") == "0 0 %g %g" % (width, height), "viewBox " + root.get("viewBox"))
    for layer in ("cut", "score", "kerf", "engrave", "mark"):
        group = root.find("%sg[@id='%s']" % (SVG, layer))
        check(group is not None, "no layer " + layer)
        check(group.get(INKSCAPE + "groupmode") == "layer", "layer %s not an Inkscape layer" % layer)
        check(group.get("fill") == "none", "layer %s is filled" % layer)
    cut = root.find("%sg[@id='cut']" % SVG)
    check(cut.get("stroke") == "#FF0000" and cut.get("stroke-width") == "0.025",
          "cut layer stroke %s %s" % (cut.get("stroke"), cut.get("stroke-width")))


def report(work, name):
    with open(os.path.join(work, name)) as f:
        return json.load(f)


# ---- closed forms on the written SVG -------------------------------------

@test
def cylinder_is_a_rectangle(work):
    run(work, "cylinder", "--radius", "40", "--height", "120", "-o", "c.svg", *FINE)
    valid_svg(os.path.join(work, "c.svg"), 600, 400)
    [outline] = outlines(os.path.join(work, "c.svg"))
    xs, ys = [p[0] for p in outline], [p[1] for p in outline]
    sides = sorted([max(xs) - min(xs), max(ys) - min(ys)])
    close(sides[1], 2 * math.pi * 40, 1e-6, "rectangle length")
    close(sides[0], 120, 1e-6, "rectangle height")
    close(area(outline), 2 * math.pi * 40 * 120, 1e-6, "rectangle area")


@test
def cylinder_over_a_curve_is_a_rectangle(work):
    """An open right section (half an ellipse) unrolls to its arc length x the height."""
    with open(os.path.join(work, "arc.csv"), "w") as f:
        for i in range(201):
            t = math.pi * i / 200
            f.write("%.12f,%.12f,0\n" % (50 * math.cos(t), 50 * math.sin(t)))
    run(work, "cylinder", "--curve", "arc.csv", "--height", "80", "-o", "a.svg", *FINE)
    [outline] = outlines(os.path.join(work, "a.svg"))
    xs, ys = [p[0] for p in outline], [p[1] for p in outline]
    sides = sorted([max(xs) - min(xs), max(ys) - min(ys)])
    close(sides[1], math.pi * 50, 1e-5, "unrolled arc length (spline through 201 points)")
    close(sides[0], 80, 1e-9, "height")
    close(area(outline), sides[1] * 80, 1e-6, "the net is a rectangle")


@test
def right_cone_is_a_sector(work):
    run(work, "cone", "--radius", "60", "--height", "80", "-o", "k.svg", *FINE)
    [outline] = outlines(os.path.join(work, "k.svg"))
    slant = 100.0                       # sqrt(60^2 + 80^2)
    angle = 2 * math.pi * 60 / slant    # 2 pi r / l
    a, b = two_longest_edges(outline)
    shared = {a, (a + 1) % len(outline)} & {b, (b + 1) % len(outline)}
    check(len(shared) == 1, "the two straight edges of the sector do not meet at the apex")
    apex = outline[shared.pop()]
    for p in outline:
        if p != apex:
            close(math.dist(p, apex), slant, 1e-6, "distance from the apex")
    close(area(outline), angle * slant ** 2 / 2, 1e-6, "sector area")
    close(perimeter(outline), 2 * slant + slant * angle, 1e-6, "sector perimeter")


@test
def frustum_is_an_annular_sector(work):
    run(work, "cone", "--radius", "60", "--height", "80", "--top-radius", "30", "-o", "f.svg", *FINE)
    [outline] = outlines(os.path.join(work, "f.svg"))
    outer = math.hypot(60, 160)         # the apex is 80 * 60 / 30 = 160 above the base
    inner = outer / 2
    angle = 2 * math.pi * 60 / outer
    a, b = two_longest_edges(outline)
    n = len(outline)
    centre = lines_meet(outline[a], outline[(a + 1) % n], outline[b], outline[(b + 1) % n])
    for p in outline:
        r = math.dist(p, centre)
        check(abs(r - inner) <= 1e-6 * inner or abs(r - outer) <= 1e-6 * outer,
              "point at %.9g from the centre, expected %.9g or %.9g" % (r, inner, outer))
    close(area(outline), angle * (outer ** 2 - inner ** 2) / 2, 1e-6, "annular sector area")


def helicoid_pieces(work, turns, extra=()):
    run(work, "helicoid", "--radius", "30", "--pitch", repr(20 * math.pi), "--turns", str(turns),
        "--width", "25", "-o", "h.svg", "--report", "h.json", *FINE, *extra)
    return outlines(os.path.join(work, "h.svg")), report(work, "h.json")


@test
def helicoid_is_an_annular_sector(work):
    radius, c, width, turns = 30.0, 10.0, 25.0, 2
    rho = (radius ** 2 + c ** 2) / radius
    outer = math.hypot(rho, width)
    total_angle = turns * 2 * math.pi * radius / math.hypot(radius, c)
    pieces, data = helicoid_pieces(work, turns)
    check(len(pieces) == 2, "%d pieces, expected 2 (one turn develops to 0.95 of a circle)" % len(pieces))
    swept = 0.0
    for outline in pieces:
        first, second = arcs(outline)
        inner_arc = first if len(first) and perimeter(first) < perimeter(second) else second
        outer_arc = second if inner_arc is first else first
        centre = circle_through(inner_arc[0], inner_arc[len(inner_arc) // 2], inner_arc[-1])
        for p in inner_arc:
            close(math.dist(p, centre), rho, 1e-6, "inner radius")
        for p in outer_arc:
            close(math.dist(p, centre), outer, 1e-6, "outer radius")
        turning = 0.0
        for p, q in zip(inner_arc, inner_arc[1:]):
            u = (p[0] - centre[0], p[1] - centre[1])
            v = (q[0] - centre[0], q[1] - centre[1])
            turning += math.atan2(u[0] * v[1] - u[1] * v[0], u[0] * v[0] + u[1] * v[1])
        swept += abs(turning)
    close(swept, total_angle, 1e-6, "angle of the annular sectors")
    close(sum(area(o) for o in pieces), total_angle * (outer ** 2 - rho ** 2) / 2, 1e-6, "area")
    close(data["surface_area_mm2"], total_angle * (outer ** 2 - rho ** 2) / 2, 1e-9, "3D area")


@test
def tangent_developable_is_an_isometry(work):
    """Every flat ruling as long as in 3D, flat area = 3D area."""
    run(work, "tangent", "--curve", os.path.join(REPO, "samples", "spiral.csv"), "--width", "20",
        "--rulings", "-n", "30", "-o", "t.svg", "--report", "t.json", *FINE)
    rulings = paths(os.path.join(work, "t.svg"), "score")
    check(len(rulings) == 29, "%d rulings drawn, expected 29" % len(rulings))
    for points, closed in rulings:
        check(not closed and len(points) == 2, "a ruling is not one open segment")
        close(math.dist(*points), 20.0, 1e-6, "flat ruling length")
    data = report(work, "t.json")
    [piece] = data["pieces"]
    close(piece["flat_area_mm2"], piece["area_3d_mm2"], 1e-6, "flat vs 3D area")
    check(piece["edge_length_error"] < 1e-6, "edge length error %g" % piece["edge_length_error"])
    [outline] = outlines(os.path.join(work, "t.svg"))
    close(area(outline), piece["area_3d_mm2"], 1e-6, "area of the written outline")


@test
def helix_from_points_matches_the_helicoid(work):
    """A helix given as CSV points develops like the analytic helicoid (spline accuracy)."""
    with open(os.path.join(work, "helix.csv"), "w") as f:
        for i in range(481):
            t = 2 * math.pi * 0.75 * i / 480
            f.write("%.12f,%.12f,%.12f\n" % (30 * math.cos(t), 30 * math.sin(t), 10 * t))
    run(work, "tangent", "--curve", "helix.csv", "--width", "25", "-o", "t.svg", "--report", "t.json")
    expected = 0.75 * 2 * math.pi * math.hypot(30, 10) * 0.03 * 25 ** 2 / 2   # s kappa L^2 / 2
    # The spline's end conditions (cubic ghost points) dominate what is left.
    close(report(work, "t.json")["surface_area_mm2"], expected, 5e-5, "3D area of the spline surface")


@test
def seed_triangle_smaller_quad_larger(work):
    areas = {}
    for method in ("triangle", "quad"):
        for n in (16, 64):
            run(work, "helicoid", "--radius", "30", "--pitch", repr(20 * math.pi), "--turns", "0.25",
                "--width", "25", "--method", method, "-n", str(n), "-o", "d.svg", "--report", "d.json")
            data = report(work, "d.json")
            areas[method, n] = sum(p["flat_area_mm2"] for p in data["pieces"])
            surface = data["surface_area_mm2"]
    close(surface, 465.68, 1e-5, "surface area")
    close(areas["triangle", 16], 436.1, 2e-4, "triangle net at n = 16")
    close(areas["quad", 16], 522.8, 2e-4, "quad net at n = 16")
    check(areas["triangle", 16] < areas["triangle", 64] < surface < areas["quad", 64] < areas["quad", 16],
          "expected triangle < surface < quad with errors shrinking: %r" % areas)


@test
def several_sheets_are_numbered(work):
    run(work, "helicoid", "--radius", "30", "--pitch", "62.83", "--turns", "3", "--width", "25",
        "--sheet", "150x150", "-o", "many.svg", "--report", "many.json")
    names = sorted(f for f in os.listdir(work) if f.endswith(".svg"))
    check(names == ["many-1.svg", "many-2.svg", "many-3.svg"], "files: %r" % names)
    for name in names:
        valid_svg(os.path.join(work, name), 150, 150)
    check(len(report(work, "many.json")["sheets"]) == 3, "report sheets")


@test
def report_to_stdout(work):
    result = run(work, "cylinder", "--radius", "10", "--height", "20", "-o", "c.svg", "--report", "-")
    data = json.loads(result.stdout)
    close(data["pieces"][0]["area_3d_mm2"], 2 * math.pi * 10 * 20, 1e-9, "report area")
    check(data["machine"] == "co2-60w" and data["material"] == "plywood-3mm", "default profiles")


@test
def help_version_and_profiles(work):
    check("usage: unroll" in run(work, "--help").stdout, "--help")
    check(re.match(r"unroll \d+\.\d+\.\d+", run(work, "--version").stdout), "--version")
    check("--pitch" in run(work, "help", "helicoid").stdout, "help helicoid")
    listing = run(work, "profiles").stdout
    for name in ("co2-60w", "diode-10w", "router", "plywood-3mm", "plywood-6mm", "mdf-3mm",
                 "cardboard-2mm", "polypropylene-0.8mm", "paper-0.3mm"):
        check(name in listing, "profiles does not list " + name)
    shown = run(work, "profiles", "show", "co2-60w").stdout
    check("co2-60w.xml" in shown and "#FF0000" in shown, "profiles show co2-60w")


@test
def router_and_material_profiles_are_used(work):
    run(work, "cylinder", "--radius", "100", "--height", "300", "--machine", "router",
        "--material", "plywood-6mm", "-o", "r.svg", "--report", "r.json")
    data = report(work, "r.json")
    check(data["machine"] == "router" and data["material"] == "plywood-6mm", "profiles in report")


# ---- bad input: exit 2, a message naming the culprit, no output ------------

BAD_PROFILE = """<?xml version="1.0"?>
<material>
  <description>broken
</material>
"""


def bad(work, pattern, *args):
    before = set(os.listdir(work))
    result = run(work, *args, status=2)
    check(re.search(pattern, result.stderr), "message %r does not match %r" % (result.stderr.strip(), pattern))
    check(result.stderr.count("\n") == 1, "more than one line: %r" % result.stderr)
    after = set(os.listdir(work))
    check(after == before, "files left behind: %r" % sorted(after - before))


def write(work, name, text):
    with open(os.path.join(work, name), "w") as f:
        f.write(text)


HELICOID = ["helicoid", "--radius", "30", "--pitch", "60", "--turns", "1", "--width", "20"]


@test
def bad_inputs(work):
    write(work, "three.csv", "0,0,0\n1,0,0\n2,1,0\n")
    write(work, "word.csv", "0,0,0\n1,0,0\n2,1,zero\n3,3,1\n")
    write(work, "nan.csv", "0,0,0\n1,0,0\n2,1,0\nnan,3,1\n")
    write(work, "inf.csv", "0,0,0\n1,0,inf\n2,1,0\n3,3,1\n")
    write(work, "repeat.csv", "0,0,0\n1,0,0\n1,0,0\n3,3,1\n4,5,2\n")
    write(work, "s.csv", "".join("%g,%g,%g\n" % (20 * t, 10 * t ** 3, 2 * t)
                                  for t in [-2 + 4 * i / 29 for i in range(30)]))
    shutil.copytree(os.path.join(REPO, "profiles"), os.path.join(work, "profiles-bad"))
    write(work, "profiles-bad/materials/broken.xml", BAD_PROFILE)
    tangent = ["tangent", "--width", "10", "-o", "x.svg", "--curve"]
    bad(work, r"missing\.csv", *tangent, "missing.csv")
    bad(work, r"three\.csv.*at least 4 points", *tangent, "three.csv")
    bad(work, r"word\.csv:3", *tangent, "word.csv")
    bad(work, r"nan\.csv:4", *tangent, "nan.csv")
    bad(work, r"inf\.csv:2", *tangent, "inf.csv")
    bad(work, r"repeat\.csv:3", *tangent, "repeat.csv")
    bad(work, r"profiles-bad", *tangent, "profiles-bad")
    bad(work, r"inflection.*near point", *tangent, "s.csv")
    for option in ("--radius", "--pitch", "--turns", "--width"):
        args = list(HELICOID)
        args[args.index(option) + 1] = "-1"
        bad(work, option + " must be positive", *args, "-o", "x.svg")
    bad(work, r"--radius: 'abc'", "cylinder", "--radius", "abc", "--height", "10", "-o", "x.svg")
    bad(work, r"--height must be positive", "cylinder", "--radius", "3", "--height", "0", "-o", "x.svg")
    bad(work, r"unknown subcommand 'sphere'", "sphere")
    bad(work, r"unknown option '--colour'", *HELICOID, "--colour", "red", "-o", "x.svg")
    bad(work, r"--pitch does not apply", "cylinder", "--radius", "3", "--height", "4", "--pitch", "1", "-o", "x.svg")
    bad(work, r"unknown machine 'laser9000'", *HELICOID, "--machine", "laser9000", "-o", "x.svg")
    bad(work, r"unknown material 'balsa'", *HELICOID, "--material", "balsa", "-o", "x.svg")
    bad(work, r"no-such-dir", *HELICOID, "-o", "no-such-dir/x.svg")
    bad(work, r"-o FILE", *HELICOID)
    bad(work, r"does not fit.*--sheet", "cylinder", "--radius", "100", "--height", "300", "-o", "x.svg")
    bad(work, r"--sheet: '12'", *HELICOID, "--sheet", "12", "-o", "x.svg")
    bad(work, r"--method: 'smash'", *HELICOID, "--method", "smash", "-o", "x.svg")
    bad(work, r"triangle", "cylinder", "--radius", "3", "--height", "4", "--method", "triangle", "-o", "x.svg")
    env_result = subprocess.run([UNROLL, *HELICOID, "--material", "broken", "-o", "x.svg"], cwd=work,
                                capture_output=True, text=True,
                                env=dict(os.environ, UNROLL_PROFILES=os.path.join(work, "profiles-bad")))
    check(env_result.returncode == 2, "malformed profile: exit %d" % env_result.returncode)
    check(re.search(r"broken\.xml:\d+:", env_result.stderr), "malformed profile message: " + env_result.stderr)
    check(not os.path.exists(os.path.join(work, "x.svg")), "malformed profile left x.svg")


@test
def failure_leaves_existing_file_untouched(work):
    write(work, "keep.svg", "precious")
    run(work, "cylinder", "--radius", "100", "--height", "300", "-o", "keep.svg", status=2)
    with open(os.path.join(work, "keep.svg")) as f:
        check(f.read() == "precious", "keep.svg was changed")
    check(sorted(os.listdir(work)) == ["keep.svg"], "left behind: %r" % os.listdir(work))


def main():
    passed = failed = 0
    for function in TESTS:
        work = tempfile.mkdtemp(prefix="unroll-test-")
        try:
            function(work)
            print("ok " + function.__name__)
            passed += 1
        except Failure as failure:
            print("FAIL %s: %s" % (function.__name__, failure))
            failed += 1
        except Exception as error:  # a crash in the test is a failure too
            print("FAIL %s: %s: %s" % (function.__name__, type(error).__name__, error))
            failed += 1
        finally:
            shutil.rmtree(work, ignore_errors=True)
    print("cli: %d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
