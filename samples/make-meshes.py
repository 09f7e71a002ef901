#!/usr/bin/env python3
"""Writes the sample meshes that `make demo` and tests/unit/test_import.c use.

    samples/make-meshes.py          # rewrites the files below, in samples/

icosphere.obj        a closed low-poly sphere (radius 40 mm, 80 triangles)
lampshade.obj        a frustum of a cone (radii 100 and 60 mm, 120 mm high) in
                     two OBJ groups, front and back, exported the way a
                     modeller does: quads, vt and vn lines, s lines
lampshade-ascii.stl  the same surface, one solid per half
lampshade-binary.stl the same surface, one binary solid
lampshade.ply        the same surface, ASCII PLY with quad faces
lampshade.gltf       the same surface, buffer embedded; the back half is
                     stored 10 mm lower and turned half a turn, and its node
                     turns it back (node transforms must be applied)
lampshade.glb        the same surface, one half-mesh used by two nodes, the
                     second mirrored (scale 1,-1,1): the importer must apply
                     it and turn the mirrored triangles round
cube.obj             a cube of side 100 mm, six quads (papercraft: six squares)
uvsphere.obj         a UV sphere of radius 50 mm, 32 segments and 16 rings, as
                     a modeller makes one: quads, triangle fans at the poles
torus.obj            a torus (radii 60 and 20 mm, 24 by 12) of planar quads
grid-hole.obj        a 3 x 3 grid of 20 mm quads, its centre quad a group of
                     its own, and a 2 x 2 frame of quads around a square hole
                     beside it: seams that are closed loops
pocket.obj           a 30 x 30 x 15 mm block with a star-shaped pocket, in
                     triangles as OpenSCAD's CSG makes them: a flat top
                     round a hole
head.obj             a closed head-like mesh (about 120 mm tall): a smooth
                     skull and cheeks, a nose, a flat base meeting the sides
                     at a sharp edge

Every coordinate is rounded to a 32-bit float first, because that is what
assimp reads: the formats then hold exactly the same numbers.  Triangles run
counter-clockwise seen from outside.  Only the standard library is used.
"""
import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

SEGMENTS = 24  # around the axis; the first half is the front group
ROWS = 3  # quads up the side
BOTTOM_RADIUS, TOP_RADIUS, HEIGHT = 100.0, 60.0, 120.0


def f32(value):
    """The nearest 32-bit float, as a Python float."""
    return struct.unpack("<f", struct.pack("<f", value))[0]


def number(value):
    """Shortest text that reads back as the same 32-bit float."""
    value = f32(value)
    for digits in range(6, 10):
        text = "%.*f" % (digits, value)
        if f32(float(text)) == value:
            return text[1:] if text.startswith("-") and float(text) == 0 else text
    raise AssertionError(value)


def point(p):
    return " ".join(number(c) for c in p)


# ---- The lampshade ---------------------------------------------------------


def shade_vertex(row, segment):
    """Vertex on row (0 at the bottom) and segment (angle 360/SEGMENTS each)."""
    t = row / ROWS
    radius = BOTTOM_RADIUS + (TOP_RADIUS - BOTTOM_RADIUS) * t
    angle = 2 * math.pi * (segment % SEGMENTS) / SEGMENTS
    # Rounded so that 1e-15 is written 0.000000, as a modeller would.
    return tuple(f32(round(c, 6)) for c in (radius * math.cos(angle), radius * math.sin(angle),
                                            HEIGHT * t))


def shade_normal(segment):
    angle = 2 * math.pi * (segment % SEGMENTS) / SEGMENTS
    slope = BOTTOM_RADIUS - TOP_RADIUS
    length = math.hypot(HEIGHT, slope)
    return (HEIGHT * math.cos(angle) / length, HEIGHT * math.sin(angle) / length, slope / length)


def shade_quads(first, last):
    """Quads (bottom-left, bottom-right, top-right, top-left) as (row, segment)."""
    for segment in range(first, last):
        for row in range(ROWS):
            yield ((row, segment), (row, segment + 1), (row + 1, segment + 1), (row + 1, segment))


HALVES = (("front", 0, SEGMENTS // 2), ("back", SEGMENTS // 2, SEGMENTS))


def index_of(row, segment):
    return row * SEGMENTS + segment % SEGMENTS


def triangles_of(quad):
    a, b, c, d = quad
    return ((a, b, c), (a, c, d))


def cross(u, v):
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def facet_normal(p, q, r):
    n = cross(tuple(q[i] - p[i] for i in range(3)), tuple(r[i] - p[i] for i in range(3)))
    length = math.sqrt(sum(c * c for c in n))
    return tuple(c / length for c in n)


def write_lampshade_obj(path):
    lines = [
        "# Lampshade: frustum of a cone, radii 100 and 60 mm, 120 mm high (mm).",
        "# Exported as a modeller would: shared positions, texture coordinates and",
        "# normals, quads, one group per half.  Written by samples/make-meshes.py.",
        "o lampshade",
    ]
    for row in range(ROWS + 1):
        for segment in range(SEGMENTS):
            lines.append("v " + point(shade_vertex(row, segment)))
    for row in range(ROWS + 1):
        for segment in range(SEGMENTS + 1):
            lines.append("vt %.6f %.6f" % (segment / SEGMENTS, row / ROWS))
    for segment in range(SEGMENTS):
        lines.append("vn %.6f %.6f %.6f" % shade_normal(segment))
    for name, first, last in HALVES:
        lines.append("g " + name)
        lines.append("s 1")
        for quad in shade_quads(first, last):
            corners = []
            for row, segment in quad:
                v = index_of(row, segment) + 1
                vt = row * (SEGMENTS + 1) + segment + 1
                vn = segment % SEGMENTS + 1
                corners.append("%d/%d/%d" % (v, vt, vn))
            lines.append("f " + " ".join(corners))
    write_text(path, lines)


def shade_triangles(first, last):
    for quad in shade_quads(first, last):
        for triangle in triangles_of(quad):
            yield tuple(shade_vertex(*corner) for corner in triangle)


def write_lampshade_ascii_stl(path):
    lines = []
    for name, first, last in HALVES:
        lines.append("solid " + name)
        for p, q, r in shade_triangles(first, last):
            lines.append("  facet normal " + point(facet_normal(p, q, r)))
            lines.append("    outer loop")
            for corner in (p, q, r):
                lines.append("      vertex " + point(corner))
            lines.append("    endloop")
            lines.append("  endfacet")
        lines.append("endsolid " + name)
    write_text(path, lines)


def write_lampshade_binary_stl(path):
    triangles = list(shade_triangles(0, SEGMENTS))
    header = b"unroll sample: lampshade, mm, samples/make-meshes.py"
    data = bytearray(header.ljust(80, b" "))
    data += struct.pack("<I", len(triangles))
    for p, q, r in triangles:
        data += struct.pack("<12fH", *facet_normal(p, q, r), *p, *q, *r, 0)
    write_bytes(path, data)


def write_lampshade_ply(path):
    quads = list(shade_quads(0, SEGMENTS))
    lines = [
        "ply",
        "format ascii 1.0",
        "comment unroll sample: lampshade, mm, written by samples/make-meshes.py",
        "element vertex %d" % ((ROWS + 1) * SEGMENTS),
        "property float x",
        "property float y",
        "property float z",
        "element face %d" % len(quads),
        "property list uchar int vertex_indices",
        "end_header",
    ]
    for row in range(ROWS + 1):
        for segment in range(SEGMENTS):
            lines.append(point(shade_vertex(row, segment)))
    for quad in quads:
        lines.append("4 " + " ".join(str(index_of(*corner)) for corner in quad))
    write_text(path, lines)


# ---- glTF --------------------------------------------------------------------


def half_buffer(z_offset):
    """Positions and indices of the front half, moved z_offset along z."""
    rows = range(ROWS + 1)
    columns = range(SEGMENTS // 2 + 1)
    positions = bytearray()
    low = [math.inf] * 3
    high = [-math.inf] * 3
    for row in rows:
        for segment in columns:
            x, y, z = shade_vertex(row, segment)
            p = (x, y, f32(z + z_offset))
            positions += struct.pack("<3f", *p)
            low = [min(a, b) for a, b in zip(low, p)]
            high = [max(a, b) for a, b in zip(high, p)]
    indices = bytearray()
    count = 0
    for quad in shade_quads(0, SEGMENTS // 2):
        for triangle in triangles_of(quad):
            for row, segment in triangle:
                indices += struct.pack("<H", row * len(columns) + segment)
                count += 1
    return positions, indices, count, low, high


def gltf_document(halves, nodes, buffer_uri):
    """One buffer holding each half's positions then indices, 4-byte aligned."""
    data = bytearray()
    views, accessors, meshes = [], [], []
    for name, (positions, indices, count, low, high) in halves:
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(positions),
                      "target": 34962})
        data += positions
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(indices),
                      "target": 34963})
        data += indices
        while len(data) % 4:
            data.append(0)
        accessors.append({"bufferView": len(views) - 2, "componentType": 5126,
                          "count": len(positions) // 12, "type": "VEC3", "min": low,
                          "max": high})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": count,
                          "type": "SCALAR"})
        meshes.append({"name": name, "primitives": [
            {"attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1,
             "mode": 4}]})
    buffer = {"byteLength": len(data)}
    if buffer_uri:
        buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    document = {
        "asset": {"version": "2.0", "generator": "unroll samples/make-meshes.py",
                  "extras": {"note": "lampshade in millimetres, not the metres glTF expects"}},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": nodes,
        "meshes": meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [buffer],
    }
    return document, data


def write_lampshade_gltf(path):
    # The back half turned half a turn about z is the front half: store it so,
    # 10 mm lower, and let its node turn and lift it back into place.
    halves = [("front", half_buffer(0.0)), ("back", half_buffer(-10.0))]
    nodes = [
        {"name": "lampshade", "children": [1, 2]},
        {"name": "front", "mesh": 0},
        {"name": "back", "mesh": 1, "rotation": [0, 0, 1, 0], "translation": [0, 0, 10]},
    ]
    document, _ = gltf_document(halves, nodes, True)
    write_text(path, [json.dumps(document, indent=1)])


def write_lampshade_glb(path):
    # One half, used twice: the second node mirrors it (y -> -y) into the back.
    halves = [("half", half_buffer(0.0))]
    nodes = [
        {"name": "lampshade", "children": [1, 2]},
        {"name": "front", "mesh": 0},
        {"name": "back", "mesh": 0, "scale": [1, -1, 1]},
    ]
    document, data = gltf_document(halves, nodes, False)
    text = json.dumps(document, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    body = struct.pack("<I4s", len(text), b"JSON") + text
    body += struct.pack("<I4s", len(data), b"BIN\0") + data
    write_bytes(path, struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body)


# ---- The icosphere -----------------------------------------------------------


def icosphere(radius, subdivisions):
    """Vertices and outward counter-clockwise triangles of a subdivided icosahedron."""
    g = (1 + math.sqrt(5)) / 2
    vertices = [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g),
                (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]

    def on_sphere(p):
        length = math.sqrt(sum(c * c for c in p))
        return tuple(c / length for c in p)

    vertices = [on_sphere(v) for v in vertices]
    for _ in range(subdivisions):
        middles = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in middles:
                vertices.append(on_sphere(tuple((p + q) / 2 for p, q in
                                                zip(vertices[a], vertices[b]))))
                middles[key] = len(vertices) - 1
            return middles[key]

        refined = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            refined += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = refined
    return [tuple(f32(round(radius * c, 6)) for c in v) for v in vertices], faces


def write_icosphere_obj(path):
    vertices, faces = icosphere(40.0, 1)
    lines = ["# Icosphere: a closed low-poly sphere of radius 40 mm (mm), %d triangles."
             % len(faces), "# Written by samples/make-meshes.py.", "o icosphere"]
    lines += ["v " + point(v) for v in vertices]
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in faces]
    write_text(path, lines)


# ---- Papercraft meshes ---------------------------------------------------------


def write_faces_obj(path, comment, vertices, groups):
    """An OBJ of vertices (mm) and groups [(name or None, faces)], faces 0-based."""
    lines = ["# " + line for line in comment] + ["# Written by samples/make-meshes.py."]
    lines += ["v " + point(tuple(round(c, 6) + 0.0 for c in v)) for v in vertices]
    for name, faces in groups:
        if name:
            lines.append("g " + name)
        lines += ["f " + " ".join(str(i + 1) for i in face) for face in faces]
    write_text(path, lines)


def cube(side):
    h = side / 2
    vertices = [(x, y, z) for z in (-h, h) for y in (-h, h) for x in (-h, h)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return vertices, faces


def uv_sphere(radius, segments, rings):
    """Blender's UV sphere: a vertex at each pole, quads between rings, fans at the poles."""
    vertices = [(0.0, 0.0, radius)]
    for ring in range(1, rings):
        polar = math.pi * ring / rings
        for s in range(segments):
            a = 2 * math.pi * s / segments
            vertices.append((radius * math.sin(polar) * math.cos(a),
                             radius * math.sin(polar) * math.sin(a), radius * math.cos(polar)))
    vertices.append((0.0, 0.0, -radius))
    bottom = len(vertices) - 1

    def at(ring, s):
        return 1 + (ring - 1) * segments + s % segments

    faces = [(0, at(1, s), at(1, s + 1)) for s in range(segments)]
    for ring in range(1, rings - 1):
        faces += [(at(ring, s), at(ring + 1, s), at(ring + 1, s + 1), at(ring, s + 1))
                  for s in range(segments)]
    faces += [(at(rings - 1, s), bottom, at(rings - 1, s + 1)) for s in range(segments)]
    return vertices, faces


def torus(major, minor, around, across):
    vertices = []
    for i in range(around):
        a = 2 * math.pi * i / around
        for j in range(across):
            b = 2 * math.pi * j / across
            r = major + minor * math.cos(b)
            vertices.append((r * math.cos(a), r * math.sin(a), minor * math.sin(b)))

    def at(i, j):
        return (i % around) * across + j % across

    faces = [(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1))
             for i in range(around) for j in range(across)]
    return vertices, faces


def grid_with_hole():
    """A 3 x 3 grid (centre quad grouped apart) and, beside it, a frame round a hole."""
    size = 20.0
    vertices = [(x * size, y * size, 0.0) for y in range(4) for x in range(4)]

    def at(x, y):
        return y * 4 + x

    quads = {(x, y): (at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y + 1))
             for x in range(3) for y in range(3)}
    rim = [quads[k] for k in sorted(quads) if k != (1, 1)]
    # The frame: a 3 x 3 block of quads 100 mm to the right, its centre left open.
    first = len(vertices)
    vertices += [(100.0 + x * size, y * size, 0.0) for y in range(4) for x in range(4)]
    frame = [(first + at(x, y), first + at(x + 1, y), first + at(x + 1, y + 1),
              first + at(x, y + 1)) for x in range(3) for y in range(3) if (x, y) != (1, 1)]
    return vertices, [("rim", rim), ("centre", [quads[(1, 1)]]), ("frame", frame)]


def head(segments=32, rings=20):
    """A closed head-like mesh: an egg-shaped skull, a nose, cheeks, a flat base."""
    vertices, faces = uv_sphere(1.0, segments, rings)
    base = -0.72  # the sphere is cut flat here: the base meets the sides at a sharp edge
    shaped = []
    for x, y, z in vertices:
        z = max(z, base)
        # Nose: a bump towards -y, just below the middle.
        nose = 0.32 * math.exp(-((x / 0.16) ** 2 + ((z + 0.05) / 0.22) ** 2)) if y < 0 else 0.0
        # Cheeks and jaw: narrower at the bottom, a wider skull at the top.
        width = 0.85 + 0.12 * z
        shaped.append((60 * width * x, 60 * (y * 0.95 - nose), 60 * 1.05 * z))
    return shaped, faces


def pocket_block(size=30.0, height=15.0, depth=10.0, points=3, turn=1.0):
    """A block with a star-shaped pocket, as CSG makes one (OpenSCAD's
    difference of a cube and an extruded shape): the top a flat face round
    a hole, fanned from the hole to the square, the pocket's walls and its
    floor."""
    star = []
    for k in range(2 * points):
        a = turn + math.pi * k / points
        r = 9.0 if k % 2 else 5.4
        star.append((r * math.cos(a), r * math.sin(a)))
    square = [(-size / 2, -size / 2), (size / 2, -size / 2), (size / 2, size / 2),
              (-size / 2, size / 2)]
    vertices = [(x, y, height) for x, y in square] + [(x, y, height) for x, y in star]
    vertices += [(x, y, height - depth) for x, y in star] + [(0.0, 0.0, height - depth)]
    vertices += [(x, y, 0.0) for x, y in square]
    n = len(star)
    top, rim, floor, centre, bottom = 0, 4, 4 + n, 4 + 2 * n, 5 + 2 * n

    def angle(p):
        return math.atan2(p[1], p[0]) % (2 * math.pi)

    # The top: walk round the square and the star together by angle.
    outer = sorted(range(4), key=lambda i: angle(square[i]))
    inner = sorted(range(n), key=lambda i: angle(star[i]))
    faces, o, i = [], 0, 0
    while o < 4 or i < n:
        next_outer = angle(square[outer[(o + 1) % 4]]) + (2 * math.pi if o + 1 >= 4 else 0)
        next_inner = angle(star[inner[(i + 1) % n]]) + (2 * math.pi if i + 1 >= n else 0)
        if i >= n or (o < 4 and next_outer < next_inner):
            faces.append((top + outer[o % 4], top + outer[(o + 1) % 4], rim + inner[i % n]))
            o += 1
        else:
            faces.append((rim + inner[i % n], top + outer[o % 4], rim + inner[(i + 1) % n]))
            i += 1
    for k in range(n):  # the walls face into the pocket, the floor up
        a, b = k, (k + 1) % n
        faces += [(rim + a, rim + b, floor + b), (rim + a, floor + b, floor + a)]
        faces.append((floor + a, floor + b, centre))
    for k in range(4):  # the sides and the bottom
        a, b = k, (k + 1) % 4
        faces += [(bottom + a, bottom + b, top + b), (bottom + a, top + b, top + a)]
    faces += [(bottom, bottom + 2, bottom + 1), (bottom, bottom + 3, bottom + 2)]
    return vertices, faces


def write_papercraft_meshes():
    write_faces_obj(os.path.join(HERE, "cube.obj"), ["Cube of side 100 mm (mm), six quads."],
                    *cube_groups(100.0))
    v, f = uv_sphere(50.0, 32, 16)
    write_faces_obj(os.path.join(HERE, "uvsphere.obj"),
                    ["UV sphere of radius 50 mm (mm), 32 segments, 16 rings."], v, [("sphere", f)])
    v, f = torus(60.0, 20.0, 24, 12)
    write_faces_obj(os.path.join(HERE, "torus.obj"),
                    ["Torus, radii 60 and 20 mm (mm), 24 x 12 planar quads."], v, [("torus", f)])
    v, groups = grid_with_hole()
    write_faces_obj(os.path.join(HERE, "grid-hole.obj"),
                    ["A 3 x 3 grid of 20 mm quads, its centre quad a group of its own,",
                     "and a frame of 8 quads round a square hole (mm)."], v, groups)
    v, f = pocket_block()
    write_faces_obj(os.path.join(HERE, "pocket.obj"),
                    ["A 30 x 30 x 15 mm block with a star-shaped pocket 10 mm deep (mm),",
                     "triangles as CSG makes them: its top a flat face round a hole."],
                    v, [("block", f)])
    v, f = head()
    write_faces_obj(os.path.join(HERE, "head.obj"),
                    ["A closed head-like mesh (mm): a smooth skull, a nose, a flat base",
                     "meeting the sides at a sharp edge."], v, [("head", f)])


def cube_groups(side):
    v, f = cube(side)
    return v, [("cube", f)]


# ---- Files -------------------------------------------------------------------


def write_text(path, lines):
    with open(path, "w", encoding="ascii", newline="\n") as file:
        file.write("\n".join(lines) + "\n")


def write_bytes(path, data):
    with open(path, "wb") as file:
        file.write(data)


def main():
    write_icosphere_obj(os.path.join(HERE, "icosphere.obj"))
    write_lampshade_obj(os.path.join(HERE, "lampshade.obj"))
    write_lampshade_ascii_stl(os.path.join(HERE, "lampshade-ascii.stl"))
    write_lampshade_binary_stl(os.path.join(HERE, "lampshade-binary.stl"))
    write_lampshade_ply(os.path.join(HERE, "lampshade.ply"))
    write_lampshade_gltf(os.path.join(HERE, "lampshade.gltf"))
    write_lampshade_glb(os.path.join(HERE, "lampshade.glb"))
    write_papercraft_meshes()


if __name__ == "__main__":
    main()
