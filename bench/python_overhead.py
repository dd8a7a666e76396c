"""Python's overhead per image (issue: under 2 % of detection time): the same images detected by
`binpick detect` (its results' time column: detection alone, per image) and by the module
(the wall time of Detector.detect: the depth's conversion, the detection, the results' conversion).
Medians over the images of each of REPEATS runs, then the median of those.

    PYTHONPATH=build/python python3 bench/python_overhead.py BINPICK WORK [REPEATS]

Makes WORK/data (4 bins of 350 brackets, 1600 x 900) and WORK/bracket.ppfm once. Prints a line
per run and the overhead.
"""
import csv
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import binpick


def main(exe, work, repeats="3"):
    work = Path(work)
    if not (work / "data").exists():
        subprocess.run([exe, "synth", "--model", "builtin:bracket", "--out", work / "data",
                        "--bins", "4", "--objects", "350"], check=True, capture_output=True)
    if not (work / "bracket.ppfm").exists():
        subprocess.run([exe, "train", "--model", "builtin:bracket", "--out", work / "bracket.ppfm"],
                       check=True, capture_output=True)
    images = []
    for scene in sorted((work / "data" / "test").iterdir()):
        cams = json.loads((scene / "scene_camera.json").read_text())
        for im, cam in sorted(cams.items(), key=lambda kv: int(kv[0])):
            images.append((binpick.read_depth_png(str(scene / "depth" / f"{int(im):06d}.png")),
                           np.reshape(cam["cam_K"], (3, 3)), cam["depth_scale"]))
    detector = binpick.Detector(binpick.Model.load(str(work / "bracket.ppfm")))
    detector.detect(*images[0])  # the kernels built
    cli, py = [], []
    for r in range(int(repeats)):
        out = work / f"cli_{r}.csv"
        for p in (out, Path(str(out) + ".parts")):
            subprocess.run(["rm", "-rf", str(p)], check=True)
        subprocess.run([exe, "detect", "--model", work / "bracket.ppfm", "--dataset", work / "data",
                        "--out", out], check=True, capture_output=True)
        with open(out) as f:
            per_image = {(row["scene_id"], row["im_id"]): float(row["time"]) for row in csv.DictReader(f)}
        walls = []
        for depth, K, scale in images:
            start = time.perf_counter()
            detector.detect(depth, K, scale)
            walls.append(time.perf_counter() - start)
        cli.append(statistics.median(per_image.values()))
        py.append(statistics.median(walls))
        print(f"run {r}: command line {cli[-1] * 1e3:.1f} ms an image, Python {py[-1] * 1e3:.1f} ms")
    c, p = statistics.median(cli), statistics.median(py)
    print(f"median: command line {c * 1e3:.1f} ms, Python {p * 1e3:.1f} ms an image: "
          f"overhead {(p - c) * 1e3:+.1f} ms ({(p - c) / c * 100:+.1f} %)")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
