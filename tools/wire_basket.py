#!/usr/bin/env python3
"""Writes a wire-mesh basket as a binary STL for `binpick synth --bin-mesh`, to measure detection in
a bin like the real scene binpick is judged on (a wire-mesh basket whose rim is the highest thing
in view, the ground seen through its walls and floor, a robot arm partly in view):

  tools/wire_basket.py OUT.stl [--size 600,400,300] [--bar 4] [--pitch 40] [--rim 10] [--arm]
                       [--arm-top -40] [--cell]

The basket is in synth's bin frame (mm, the interior floor's centre at the origin, floor at z = 0,
z up): walls of square bars (vertical every --pitch mm, horizontal every 1.5 --pitch), a floor of
bars every --pitch / 2 both ways with its top at z = 0, a square rim tube of --rim mm on top of the
walls, and the ground 50 mm under the floor. With --arm, a box 160 mm wide, 360 long and 260
thick, turned 35 degrees about x: its top edge runs 60 mm outside the -y wall, --arm-top mm above
the walls' top (default -40: under the rim), and its lower end passes through that wall and
reaches 89 mm into the interior, 213 mm under its top, like an arm reaching into the basket
(something high at the bin's side that is not the rim; parts dropped land on it too). Pass the
same interior to synth: `--bin-mesh OUT.stl --bin-size 600,400,300`.

With --cell, the basket stands in a cluttered cell (in front of a fence, beside a robot, cables
and other bins, the floor all around): the ground 6 x 5 m; a
fence 700 mm behind the +y wall, posts every metre 1.8 m tall with a wire panel (vertical wires
every 50 mm, horizontal every 200 mm); a robot beside the -x wall (a 300 mm column 900 mm tall, a
shoulder box and an upper arm held out above the column, higher than the rim); a closed crate
500 x 350 x 250 beside the +x wall, turned 10 degrees; a second, empty basket-like tray behind
and to the left, 150 mm high; and cables on the ground in front (20 mm rods in long zigzags).
Needs numpy (pip install numpy)."""
import argparse
import os
import struct
import sys

try:
    import numpy as np
except ImportError:
    sys.exit("wire_basket.py: needs numpy (pip install numpy)")

# The six faces of a box by its corners (bit 0: x high, bit 1: y high, bit 2: z high), each
# counter-clockwise seen from outside, so that normals point out.
FACES = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def box(tris, lo, hi, rotation=None, pivot=None):
    """Appends the 12 triangles of the box [lo, hi], turned by rotation about pivot if given."""
    c = np.array([[hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]]
                  for i in range(8)], dtype=float)
    if rotation is not None:
        c = (rotation @ (c - pivot).T).T + pivot
    for a, b, cc, d in FACES:
        tris.append((c[a], c[b], c[cc]))
        tris.append((c[a], c[cc], c[d]))


def turned_z(deg, pivot):
    """A rotation about z by deg, and its pivot, for box()."""
    a = np.radians(deg)
    return np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]]), np.array(pivot, dtype=float)


def add_cell(tris, W, D, H):
    """The clutter of a real cell around the basket (see --cell); ground at z = -50."""
    g = -50.0
    hw, hd = W / 2, D / 2
    fy = hd + 700  # the fence, behind the +y wall
    for x in np.arange(-2500, 2501, 1000):  # posts
        box(tris, (x - 20, fy - 20, g), (x + 20, fy + 20, g + 1800))
    for x in np.arange(-2500, 2500, 50):  # vertical wires
        box(tris, (x - 1.5, fy - 1.5, g + 100), (x + 1.5, fy + 1.5, g + 1750))
    for z in np.arange(g + 100, g + 1751, 200):  # horizontal wires
        box(tris, (-2500, fy - 1.5, z - 1.5), (2500, fy + 1.5, z + 1.5))
    rx = -hw - 650  # the robot, beside the -x wall
    box(tris, (rx - 150, -150, g), (rx + 150, 150, g + 900))  # column
    box(tris, (rx - 120, -180, g + 900), (rx + 180, 180, g + 1150))  # shoulder
    R, pivot = turned_z(-20, (rx, 0, g + 1100))
    box(tris, (rx, -70, g + 1050), (rx + 550, 70, g + 1170), R, pivot)  # upper arm, held out
    cx0 = hw + 500  # a closed crate beside the +x wall, turned
    R, pivot = turned_z(10, (cx0 + 250, 0, g))
    box(tris, (cx0, -175, g), (cx0 + 500, 175, g + 250), R, pivot)
    tx, ty = -hw - 300, hd + 250  # a shallow tray behind and to the left
    box(tris, (tx - 300, ty - 200, g), (tx + 300, ty + 200, g + 10))
    for lo, hi in (((tx - 300, ty - 200, g), (tx + 300, ty - 190, g + 150)),
                   ((tx - 300, ty + 190, g), (tx + 300, ty + 200, g + 150)),
                   ((tx - 300, ty - 200, g), (tx - 290, ty + 200, g + 150)),
                   ((tx + 290, ty - 200, g), (tx + 300, ty + 200, g + 150))):
        box(tris, lo, hi)
    y = -hd - 350  # cables in front: rods on the ground in zigzags
    for k, x in enumerate(np.arange(-1800, 1800, 450)):
        R, pivot = turned_z(25 if k % 2 else -25, (x, y, g))
        box(tris, (x - 250, y - 10, g), (x + 250, y + 10, g + 20), R, pivot)
    for x in (-1200, 900):
        box(tris, (x - 10, -hd - 900, g), (x + 10, -hd - 150, g + 20))


def basket(W, D, H, bar, pitch, rim, arm, arm_top=-40.0, cell=False):
    tris = []
    hw, hd, b = W / 2, D / 2, bar
    for x in np.arange(-hw, hw + 1e-6, pitch / 2):  # floor: bars along y on top, along x below
        box(tris, (x - b / 2, -hd, -b), (x + b / 2, hd, 0))
    for y in np.arange(-hd, hd + 1e-6, pitch / 2):
        box(tris, (-hw, y - b / 2, -2 * b), (hw, y + b / 2, -b))
    for x in np.arange(-hw, hw + 1e-6, pitch):  # walls: vertical bars just outside the interior
        for y0 in (-hd - b, hd):
            box(tris, (x - b / 2, y0, -2 * b), (x + b / 2, y0 + b, H))
    for y in np.arange(-hd, hd + 1e-6, pitch):
        for x0 in (-hw - b, hw):
            box(tris, (x0, y - b / 2, -2 * b), (x0 + b, y + b / 2, H))
    for z in np.arange(0.0, H - 1, 1.5 * pitch):  # and horizontal bars outside those
        for y0 in (-hd - 2 * b, hd + b):
            box(tris, (-hw - 2 * b, y0, z), (hw + 2 * b, y0 + b, z + b))
        for x0 in (-hw - 2 * b, hw + b):
            box(tris, (x0, -hd - 2 * b, z), (x0 + b, hd + 2 * b, z + b))
    box(tris, (-hw - rim, -hd - rim, H), (hw + rim, -hd, H + rim))  # the rim tube
    box(tris, (-hw - rim, hd, H), (hw + rim, hd + rim, H + rim))
    box(tris, (-hw - rim, -hd, H), (-hw, hd, H + rim))
    box(tris, (hw, -hd, H), (hw + rim, hd, H + rim))
    if cell:
        box(tris, (-3000, -2500, -60), (3000, 2500, -50))  # the ground, wide
        add_cell(tris, W, D, H)
    else:
        box(tris, (-1500, -1200, -60), (1500, 1200, -50))  # the ground
    if arm:
        a = np.radians(35)
        R = np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])
        top = H + arm_top
        box(tris, (-80, -hd - 420, top - 260), (80, -hd - 60, top), R, np.array([0.0, -hd - 60, top]))
    return tris


def write_stl(path, tris):
    tmp = path + ".part"
    with open(tmp, "wb") as f:
        f.write(b"binpick wire basket".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            n = np.cross(t[1] - t[0], t[2] - t[0])
            n = n / (np.linalg.norm(n) + 1e-12)
            f.write(struct.pack("<12fH", *n, *t[0], *t[1], *t[2], 0))
    os.replace(tmp, path)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", help="the STL file to write (refused if it exists)")
    p.add_argument("--size", default="600,400,300", help="interior W,D,H in mm (synth's --bin-size)")
    p.add_argument("--bar", type=float, default=4.0, help="bar thickness, mm")
    p.add_argument("--pitch", type=float, default=40.0, help="wall bar spacing, mm")
    p.add_argument("--rim", type=float, default=10.0, help="rim tube size, mm")
    p.add_argument("--arm", action="store_true",
                   help="a turned box through the -y wall, its top outside the basket")
    p.add_argument("--arm-top", type=float, default=-40.0,
                   help="with --arm: its top's height above the walls' top, mm (the rim is --rim above them)")
    p.add_argument("--cell", action="store_true",
                   help="the basket in a cluttered cell: a fence behind it, a robot, a crate, a "
                        "tray, cables, a wide floor")
    a = p.parse_args()
    try:
        W, D, H = (float(v) for v in a.size.split(","))
    except ValueError:
        sys.exit(f"wire_basket.py: --size must be W,D,H in mm, got '{a.size}'")
    if min(W, D, H) <= 0 or not (0 < a.bar < a.pitch / 2) or a.rim <= 0 or abs(a.arm_top) > 2000:
        sys.exit("wire_basket.py: sizes must be positive, --bar under half of --pitch and "
                 "--arm-top within 2000 mm")
    if os.path.exists(a.out):
        sys.exit(f"wire_basket.py: {a.out} exists; not overwritten")
    tris = basket(W, D, H, a.bar, a.pitch, a.rim, a.arm, a.arm_top, a.cell)
    write_stl(a.out, tris)
    print(f"wrote {a.out}: {len(tris)} triangles")


if __name__ == "__main__":
    main()
