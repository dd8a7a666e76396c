#!/usr/bin/env python3
"""Removes depth in blobs from a BOP dataset's depth images, like a structured-light sensor on
shiny sheet metal (the real scene binpick is judged on has 25-30 % of its pixels valid, lost in
patches, not pixel by pixel). For measuring detection under missing depth:

  tools/blob_dropout.py SRC DST [--valid 0.29] [--blob 40] [--seed 5]

copies the BOP dataset SRC (a directory with test/NNNNNN/depth/*.png) to DST and, in each depth
image, keeps only the pixels where a smooth random field (bilinear over a grid of --blob pixels)
lies above the quantile that leaves about --valid of the pixels with depth valid. Seeded.
Needs numpy and pillow (pip install numpy pillow).

For new data, `binpick synth --sensor-model structured-light --dropout-share S` does this inside
the sensor model, with patches of a size in mm fixed to the surfaces (docs/sensor_model.md);
this tool stays for datasets already made."""
import argparse
import glob
import os
import shutil
import sys

try:
    import numpy as np
    from PIL import Image
except ImportError:
    sys.exit("blob_dropout.py: needs numpy and pillow (pip install numpy pillow)")


def blob_field(rng, h, w, blob):
    """A field in [0, 1]: uniform values on a grid `blob` pixels apart, bilinear between."""
    g = rng.random((h // blob + 2, w // blob + 2))
    ys = np.linspace(0, g.shape[0] - 1.001, h)
    xs = np.linspace(0, g.shape[1] - 1.001, w)
    y0, x0 = ys.astype(int), xs.astype(int)
    fy, fx = (ys - y0)[:, None], (xs - x0)[None, :]
    return (g[y0][:, x0] * (1 - fy) * (1 - fx) + g[y0 + 1][:, x0] * fy * (1 - fx)
            + g[y0][:, x0 + 1] * (1 - fy) * fx + g[y0 + 1][:, x0 + 1] * fy * fx)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("src")
    ap.add_argument("dst")
    ap.add_argument("--valid", type=float, default=0.29, help="share of all pixels left with depth")
    ap.add_argument("--blob", type=int, default=40, help="blob grid spacing, pixels")
    ap.add_argument("--seed", type=int, default=5)
    a = ap.parse_args()
    if not 0 < a.valid <= 1 or a.blob < 2:
        sys.exit("blob_dropout.py: --valid must be in (0, 1] and --blob at least 2")
    depths = sorted(glob.glob(os.path.join(a.src, "test", "*", "depth", "*.png")))
    if not depths:
        sys.exit(f"blob_dropout.py: no depth images in {a.src}/test/*/depth/")
    if os.path.exists(a.dst):
        sys.exit(f"blob_dropout.py: {a.dst} exists; give a new directory")
    shutil.copytree(a.src, a.dst)
    rng = np.random.default_rng(a.seed)
    for f in sorted(glob.glob(os.path.join(a.dst, "test", "*", "depth", "*.png"))):
        d = np.array(Image.open(f)).astype(np.uint16)
        valid = d > 0
        field = blob_field(rng, *d.shape, a.blob)
        share = min(1.0, a.valid / max(valid.mean(), 1e-9))  # of the valid pixels, to keep
        keep = field >= np.quantile(field[valid], 1 - share) if valid.any() else valid
        out = np.where(keep & valid, d, 0).astype(np.uint16)
        Image.fromarray(out).save(f)
        print(f"{os.path.relpath(f, a.dst)}: {valid.mean():.3f} -> {(out > 0).mean():.3f} valid")


if __name__ == "__main__":
    main()
