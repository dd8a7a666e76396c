"""Detect one model in every image of a BOP dataset and write BOP's results CSV, as
`binpick detect --dataset` does (the same rows; the time column is this script's).

    PYTHONPATH=build/python python3 examples/detect_dataset.py MODEL.ppfm DATASET OUT.csv [name=value ...]

name=value: detection parameters, as the command line's options without the dashes
(e.g. hypotheses=10 bin=none ref_ratio=0.2).
"""
import json
import sys
import time
from pathlib import Path

import numpy as np

import binpick


def value(text):
    """A parameter's value: true/false, a number, or the text itself."""
    if text in ("true", "false"):
        return text == "true"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def main(model_path, dataset, out, *params):
    detector = binpick.Detector(binpick.Model.load(model_path),
                                **{k: value(v) for k, v in (p.split("=", 1) for p in params)})
    lines = [binpick.RESULTS_CSV_HEADER]
    for scene in sorted(p for p in (Path(dataset) / "test").iterdir() if p.is_dir()):
        cameras = json.loads((scene / "scene_camera.json").read_text())
        for im in sorted(cameras, key=int):
            cam = cameras[im]
            depth = binpick.read_depth_png(str(scene / "depth" / f"{int(im):06d}.png"))
            start = time.perf_counter()
            found = detector.detect(depth, np.reshape(cam["cam_K"], (3, 3)), cam["depth_scale"])
            seconds = time.perf_counter() - start
            lines += [binpick.results_csv_row(int(scene.name), int(im), d, seconds)
                      for d in found]
            print(f"scene {scene.name} image {im}: {len(found)} detections", file=sys.stderr)
    Path(out).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    try:
        main(*sys.argv[1:])
    except ValueError as e:  # binpick's InputError: one line, exit 2 as the command line
        print(f"detect_dataset.py: error: {e}", file=sys.stderr)
        sys.exit(2)
