#!/usr/bin/env python3
"""Writes eight parts binpick was never tuned on, as ASCII STL in mm, for measuring on shapes
other than the built-in ones (docs/contributing.md, "Measuring on parts nobody tuned for"):

  washer.stl      a flat washer, 40 mm across, 3 mm thick: a thin part with a continuous symmetry
  hexnut.stl      a hex nut, 30 mm across the flats, 16 mm tall, origin on a face: discrete
                  symmetries whose axes miss the origin
  bentsheet.stl   an L of 2 mm sheet, legs 80 and 50 mm, 60 mm wide: sheet metal that is not flat

and five more for the held-out sets of bench/realistic_sets.sh (never tuned on):

  gearshaft.stl   a shaft 100 mm long, 20 mm across, with a 14-tooth spur gear 40 mm across the
                  tips and 12 mm wide from 30 mm along it: a symmetry of order 14 about the axis
  capscrew.stl    an M8 socket head cap screw: a plain 40 mm shank, a head 13 mm across and 8 mm
                  tall with a hexagonal socket 6 mm across the flats, 4 mm deep: 6-fold, a hole
  flange.stl      a flange 90 mm across, 10 mm thick, a 30 mm bore, a hub 40 mm across standing
                  15 mm out of one face, six 9 mm bolt holes on a 70 mm circle
  anglebar.stl    an angle bar, legs 40 x 40 mm, 4 mm thick, 120 mm long
  stepblock.stl   a block 60 x 40 x 30 mm with a 60 x 20 x 15 mm step cut along a long edge: only
                  a mirror symmetry

  tools/unseen_parts.py OUT_DIR

Every mesh is closed and wound outward (binpick refuses an inside-out one)."""
import math
import os
import sys


def write_stl(path, triangles):
    # Written aside and renamed: a run reading the file meanwhile sees the old one or the new one.
    with open(path + ".part", "w") as f:
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
    os.replace(path + ".part", path)


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


def polar(radius, degrees):
    return (radius * math.cos(math.radians(degrees)), radius * math.sin(math.radians(degrees)))


def wall(loop, z0, z1):
    """The side of a prism over a polygon from z0 to z1: outward for a counter-clockwise loop,
    into the hole for a clockwise one."""
    tris = []
    for i in range(len(loop)):
        a, b = loop[i], loop[(i + 1) % len(loop)]
        tris += [((*a, z0), (*b, z0), (*b, z1)), ((*a, z0), (*b, z1), (*a, z1))]
    return tris


def flat(tris2d, z, up):
    return [((*a, z), (*b, z), (*c, z)) if up else ((*a, z), (*c, z), (*b, z)) for a, b, c in tris2d]


def cap(outer, inner, z, up, centre=(0, 0)):
    """The face at height z between two loops that both go once counter-clockwise around centre,
    zipped together in order of angle about it (both star-shaped about it)."""
    def from_least_angle(loop):
        a = [math.atan2(p[1] - centre[1], p[0] - centre[0]) % (2 * math.pi) for p in loop]
        k = a.index(min(a))
        return loop[k:] + loop[:k + 1], a[k:] + a[:k] + [a[k] + 2 * math.pi]
    (o, ao), (h, ah) = from_least_angle(outer), from_least_angle(inner)
    tris, i, j = [], 0, 0
    while i + 1 < len(o) or j + 1 < len(h):
        if j + 1 == len(h) or (i + 1 < len(o) and ao[i + 1] <= ah[j + 1]):
            tris.append((o[i], o[i + 1], h[j]))
            i += 1
        else:
            tris.append((o[i], h[j + 1], h[j]))
            j += 1
    return flat(tris, z, up)


def disk(loop, z, up):
    """The face at height z inside a loop star-shaped about the origin, a fan from the origin."""
    return flat([((0, 0), loop[i], loop[(i + 1) % len(loop)]) for i in range(len(loop))], z, up)


def gearshaft():
    shaft, pitch = circle(10, 42), 360 / 14
    gear = []
    for k in range(14):
        c = pitch * k
        gear += [polar(14.5, c - 7.5), polar(20, c - 3.2), polar(20, c + 3.2), polar(14.5, c + 7.5),
                 polar(14.5, c + pitch / 2)]
    return (disk(shaft, 0, False) + wall(shaft, 0, 30) + cap(gear, shaft, 30, False)
            + wall(gear, 30, 42) + cap(gear, shaft, 42, True) + wall(shaft, 42, 100)
            + disk(shaft, 100, True))


def capscrew():
    shank, head, socket = circle(4, 48), circle(6.5, 48), hexagon(6, 8)
    return (disk(shank, 0, False) + wall(shank, 0, 40) + cap(head, shank, 40, False)
            + wall(head, 40, 48) + cap(head, socket, 48, True) + wall(socket[::-1], 44, 48)
            + disk(socket, 44, True))


def flange():
    n = 48
    bore, hub, rim = circle(15, n), circle(20, n), circle(45, n)
    tris = (cap(hub, bore, 0, False) + wall(rim, 0, 10) + wall(hub, 10, 25)
            + cap(hub, bore, 25, True) + wall(bore[::-1], 0, 25))
    for s in range(6):
        # The plate between two spokes through circle vertices a and b, around one bolt hole.
        a, b = 8 * s, 8 * s + 8
        def spoke(k):
            return [polar(20 + 25 * t / 4, 360 / n * (k % n)) for t in (1, 2, 3)]
        sector = (spoke(a) + [rim[k % n] for k in range(a, b + 1)] + spoke(b)[::-1]
                  + [hub[k % n] for k in range(b, a - 1, -1)])
        centre = polar(35, 60 * s + 30)
        hole = [(centre[0] + x, centre[1] + y) for x, y in circle(4.5, 24)]
        tris += (cap(sector, hole, 0, False, centre) + cap(sector, hole, 10, True, centre)
                 + wall(hole[::-1], 0, 10))
    return tris


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
    write_stl(os.path.join(out, "gearshaft.stl"), gearshaft())
    write_stl(os.path.join(out, "capscrew.stl"), capscrew())
    write_stl(os.path.join(out, "flange.stl"), flange())
    leg = 4.0
    profile = [(0, 0), (40, 0), (40, leg), (leg, leg), (leg, 40), (0, 40)]
    write_stl(os.path.join(out, "anglebar.stl"), extrude(profile, 120, fan=3))
    # The step's L across the block (y, z), extruded along x: 60 long, 40 deep, 30 tall.
    profile = [(0, 0), (40, 0), (40, 15), (20, 15), (20, 30), (0, 30)]
    block = [tuple((p[2], p[0], p[1]) for p in t) for t in extrude(profile, 60, fan=3)]
    write_stl(os.path.join(out, "stepblock.stl"), block)


if __name__ == "__main__":
    main()
