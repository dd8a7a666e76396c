#!/usr/bin/env python3
"""Writes three parts binpick was never tuned on, as ASCII STL in mm, for measuring on shapes
other than the built-in ones (docs/contributing.md, "Measuring on parts nobody tuned for"):

  washer.stl      a flat washer, 40 mm across, 3 mm thick: a thin part with a continuous symmetry
  hexnut.stl      a hex nut, 30 mm across the flats, 16 mm tall, origin on a face: discrete
                  symmetries whose axes miss the origin
  bentsheet.stl   an L of 2 mm sheet, legs 80 and 50 mm, 60 mm wide: sheet metal that is not flat

  tools/unseen_parts.py OUT_DIR

Every mesh is closed and wound outward (binpick refuses an inside-out one)."""
import math
import os
import sys


def write_stl(path, triangles):
    with open(path, "w") as f:
        f.write("solid part\n")
        for a, b, c in triangles:
            u = [b[i] - a[i] for i in range(3)]
            v = [c[i] - a[i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            length = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write(" facet normal %g %g %g\n  outer loop\n" % tuple(x / length for x in n))
            for p in (a, b, c):
                f.write("   vertex %.6f %.6f %.6f\n" % tuple(p))
            f.write("  endloop\n endfacet\n")
        f.write("endsolid part\n")


def ring(outer, inner, height):
    """The region between two counter-clockwise polygons with as many vertices, z from 0 to
    height: caps as strips between them, walls facing away from the material."""
    tris = []
    for i in range(len(outer)):
        j = (i + 1) % len(outer)
        o0, o1, i0, i1 = outer[i], outer[j], inner[i], inner[j]
        h = height
        tris += [((*o0, h), (*o1, h), (*i1, h)), ((*o0, h), (*i1, h), (*i0, h))]  # top
        tris += [((*o0, 0), (*i1, 0), (*o1, 0)), ((*o0, 0), (*i0, 0), (*i1, 0))]  # bottom
        tris += [((*o0, 0), (*o1, 0), (*o1, h)), ((*o0, 0), (*o1, h), (*o0, h))]  # outer wall
        tris += [((*i0, 0), (*i1, h), (*i1, 0)), ((*i0, 0), (*i0, h), (*i1, h))]  # bore
    return tris


def extrude(polygon, height, fan):
    """A counter-clockwise polygon, star-shaped about vertex `fan`, extruded from z 0 to height."""
    tris = []
    p = polygon[fan:] + polygon[:fan]
    for k in range(1, len(p) - 1):
        tris += [((*p[0], height), (*p[k], height), (*p[k + 1], height)),
                 ((*p[0], 0), (*p[k + 1], 0), (*p[k], 0))]
    for i in range(len(polygon)):
        a, b = polygon[i], polygon[(i + 1) % len(polygon)]
        tris += [((*a, 0), (*b, 0), (*b, height)), ((*a, 0), (*b, height), (*a, height))]
    return tris


def circle(radius, n):
    return [(radius * math.cos(2 * math.pi * k / n), radius * math.sin(2 * math.pi * k / n))
            for k in range(n)]


def hexagon(across_flats, per_side):
    r = across_flats / math.sqrt(3)
    corners = [(r * math.cos(math.pi / 3 * k), r * math.sin(math.pi / 3 * k)) for k in range(6)]
    out = []
    for k in range(6):
        a, b = corners[k], corners[(k + 1) % 6]
        out += [(a[0] + (b[0] - a[0]) * s / per_side, a[1] + (b[1] - a[1]) * s / per_side)
                for s in range(per_side)]
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    write_stl(os.path.join(out, "washer.stl"), ring(circle(20, 96), circle(10.5, 96), 3))
    write_stl(os.path.join(out, "hexnut.stl"), ring(hexagon(30, 16), circle(10, 96), 16))
    sheet = 2.0
    profile = [(0, 0), (80, 0), (80, sheet), (sheet, sheet), (sheet, 50), (0, 50)]
    write_stl(os.path.join(out, "bentsheet.stl"), extrude(profile, 60, fan=3))


if __name__ == "__main__":
    main()
