"""What the Python tests share: the command line, two fixed-seed bins made and detected in by it,
and readers of BOP's files."""
import csv
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import binpick

EXE = os.environ["BINPICK_EXE"]


def run(*args):
    subprocess.run([EXE, *map(str, args)], check=True, capture_output=True, text=True)


@pytest.fixture(scope="session")
def bins(tmp_path_factory):
    """Two fixed-seed bins of 35 brackets, the bracket's model, and the command line's results
    at the defaults and with two hypotheses."""
    d = tmp_path_factory.mktemp("bins")
    run("synth", "--model", "builtin:bracket", "--out", d / "data", "--bins", "2", "--objects", "35",
        "--width", "640", "--height", "360")
    run("train", "--model", "builtin:bracket", "--out", d / "bracket.ppfm")
    run("detect", "--model", d / "bracket.ppfm", "--dataset", d / "data", "--out", d / "r.csv")
    run("detect", "--model", d / "bracket.ppfm", "--dataset", d / "data", "--out", d / "two.csv",
        "--hypotheses", "2", "--more-hypotheses", "0")
    return d


def images(data):
    """(scene, image, depth, K, depth_scale) of every image, as BOP stores them."""
    for scene in sorted((data / "test").iterdir()):
        cams = json.loads((scene / "scene_camera.json").read_text())
        for im, cam in sorted(cams.items(), key=lambda kv: int(kv[0])):
            depth = binpick.read_depth_png(str(scene / "depth" / f"{int(im):06d}.png"))
            yield int(scene.name), int(im), depth, np.array(cam["cam_K"]).reshape(3, 3), cam["depth_scale"]


def cli_rows(csv_path):
    rows = {}
    with open(csv_path) as f:
        for r in csv.DictReader(f):
            rows.setdefault((int(r["scene_id"]), int(r["im_id"])), []).append(r)
    return rows


def assert_same(found, rows):
    assert len(found) == len(rows)
    for d, r in zip(found, rows):
        assert d.score == pytest.approx(float(r["score"]), rel=1e-12, abs=1e-15)
        assert np.allclose(d.R, np.array(r["R"].split(), dtype=float).reshape(3, 3), rtol=0, atol=1e-12)
        assert np.allclose(d.t, np.array(r["t"].split(), dtype=float), rtol=0, atol=1e-9)
