"""binpick from Python (python/binpick_module.cpp): the same detections as the command line on a
fixed-seed dataset, the same parameters by the same names, and bad input refused with one
message (ValueError)."""
import csv
import json
import os
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

import binpick

EXE = os.environ["BINPICK_EXE"]


def run(*args):
    subprocess.run([EXE, *map(str, args)], check=True, capture_output=True, text=True)


@pytest.fixture(scope="module")
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


def test_the_same_detections_as_the_command_line(bins):
    model = binpick.Model.load(str(bins / "bracket.ppfm"))
    assert model.diameter > 0
    for name, params in (("r.csv", {}), ("two.csv", {"hypotheses": 2, "more_hypotheses": 0})):
        detector = binpick.Detector(model, **params)
        rows = cli_rows(bins / name)
        compared = 0
        for scene, im, depth, K, scale in images(bins / "data"):
            found = detector.detect(depth, K, scale)
            assert_same(found, rows[(scene, im)])
            assert all(0 <= d.score <= d.fit <= 1 for d in found)
            assert found[0].factors["agreement"] > 0
            compared += 1
        assert compared == 2 and len(rows) == 2
        # The premise: the two settings' rows differ (2 against 5 or more an image).
        assert all(len(r) == 2 for r in rows.values()) == (name == "two.csv")


def test_float_depth_in_mm_gives_the_same_detections(bins):
    detector = binpick.Detector(binpick.Model.load(str(bins / "bracket.ppfm")))
    rows = cli_rows(bins / "r.csv")
    for scene, im, depth, K, scale in images(bins / "data"):
        assert scale == pytest.approx(0.1)  # what synth writes: float mm steps back to the same raw
        found = detector.detect((depth * np.float32(scale)).astype(np.float32), K)
        assert_same(found, rows[(scene, im)])


def test_threads_detecting_at_once_give_the_same_results(bins):
    model = binpick.Model.load(str(bins / "bracket.ppfm"))
    work = list(images(bins / "data"))
    alone = [binpick.Detector(model).detect(depth, K, s) for _, _, depth, K, s in work]
    together = [None] * len(work)

    def detect(i):
        together[i] = binpick.Detector(model).detect(work[i][2], work[i][3], work[i][4])

    threads = [threading.Thread(target=detect, args=(i,)) for i in range(len(work))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, together):
        assert [d.score for d in a] == [d.score for d in b]


def test_bad_input_is_refused_with_one_message(bins):
    model = binpick.Model.load(str(bins / "bracket.ppfm"))
    detector = binpick.Detector(model)
    K = np.array([[500.0, 0, 320], [0, 500, 180], [0, 0, 1]])
    good = np.full((360, 640), 10000, np.uint16)
    cases = [
        (np.zeros((360, 640), np.int32), "uint16"),
        (np.zeros((2, 360, 640), np.uint16), "2-D"),
        (np.zeros((0, 0), np.uint16), "empty"),
        (np.full((360, 640), np.nan, np.float32), "NaN"),
        (np.full((360, 640), -1.0, np.float32), "negative"),
        (np.zeros((360, 640), np.uint16), "no valid pixel"),
    ]
    for depth, message in cases:
        with pytest.raises(ValueError, match=message):
            detector.detect(depth, K, 0.1)
    with pytest.raises(ValueError, match="K"):
        detector.detect(good, np.zeros((3, 3)), 0.1)
    with pytest.raises(ValueError, match="depth_scale"):
        detector.detect(good, K, -1.0)
    with pytest.raises(ValueError, match="nope"):
        binpick.Detector(model, nope=1)
    with pytest.raises(ValueError, match="ref-ratio"):
        binpick.Detector(model, ref_ratio=2.0)
    with pytest.raises(ValueError, match="no_such.ppfm"):
        binpick.Model.load(str(bins / "no_such.ppfm"))
    assert binpick.Detector(model, bin="none").params["bin"] == "none"


def test_the_example_writes_the_command_lines_results_csv(bins):
    """examples/detect_dataset.py: the command line's results CSV byte for byte but the time."""
    example = Path(__file__).resolve().parents[2] / "examples" / "detect_dataset.py"
    out = bins / "example.csv"
    subprocess.run([sys.executable, str(example), str(bins / "bracket.ppfm"), str(bins / "data"),
                    str(out), "hypotheses=2", "more_hypotheses=0"], check=True, capture_output=True)

    def without_time(path):
        return [line.rsplit(",", 1)[0] for line in Path(path).read_text().splitlines()]

    assert without_time(out) == without_time(bins / "two.csv")
    assert len(without_time(out)) == 1 + 2 * 2
    bad = subprocess.run([sys.executable, str(example), str(bins / "bracket.ppfm"),
                          str(bins / "data"), str(out), "nope=1"], capture_output=True, text=True)
    assert bad.returncode == 2 and "nope" in bad.stderr and bad.stderr.count("\n") == 1


def test_a_model_trained_from_python_is_the_command_lines_file(bins, tmp_path):
    model = binpick.Model.train("builtin:bracket")
    model.save(str(tmp_path / "py.ppfm"))
    assert (tmp_path / "py.ppfm").read_bytes() == (bins / "bracket.ppfm").read_bytes()
    with pytest.raises(ValueError, match="voxel-ratio"):
        binpick.Model.train("builtin:bracket", voxel_ratio=0)
    with pytest.raises(ValueError, match="no_such.stl"):
        binpick.Model.train(str(tmp_path / "no_such.stl"))


def test_a_cloud_gives_the_command_lines_detections(bins, tmp_path):
    """The first image's points (with depth) as a PLY cloud: `detect --cloud` and detect_cloud."""
    _, _, depth, K, scale = next(images(bins / "data"))
    v, u = np.nonzero(depth)
    z = depth[v, u].astype(np.float64) * scale
    points = np.stack([(u - K[0, 2]) * z / K[0, 0], (v - K[1, 2]) * z / K[1, 1], z], axis=1)
    points = points[::7].astype(np.float32)  # a sparser cloud: quicker, still the parts
    ply = tmp_path / "cloud.ply"
    with open(ply, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(points)}\n"
                "property float x\nproperty float y\nproperty float z\nend_header\n")
        f.writelines(f"{x!r} {y!r} {w!r}\n" for x, y, w in points.tolist())
    run("detect", "--model", bins / "bracket.ppfm", "--cloud", ply, "--out", tmp_path / "c.csv")
    found = binpick.Detector(binpick.Model.load(str(bins / "bracket.ppfm"))).detect_cloud(points)
    assert found
    assert_same(found, cli_rows(tmp_path / "c.csv")[(0, 0)])
    detector = binpick.Detector(binpick.Model.load(str(bins / "bracket.ppfm")))
    for bad, message in ((np.zeros((5, 2), np.float32), r"\(N, 3\)"),
                         (np.zeros((0, 3), np.float32), "empty"),
                         (np.full((5, 3), np.nan, np.float32), "NaN")):
        with pytest.raises(ValueError, match=message):
            detector.detect_cloud(bad)
    with pytest.raises(ValueError, match="one per point"):
        detector.detect_cloud(points, np.zeros((3, 3), np.float32))


def test_the_stubs_name_what_the_module_has():
    """python/binpick.pyi (for editors and type checkers) lists the module's names, no more."""
    import ast
    stub = ast.parse((Path(__file__).resolve().parents[1] / "binpick.pyi").read_text())
    for node in stub.body:
        if isinstance(node, ast.ClassDef):
            assert hasattr(binpick, node.name), node.name
            for item in node.body:
                if isinstance(item, (ast.FunctionDef, ast.AnnAssign)):
                    name = item.name if isinstance(item, ast.FunctionDef) else item.target.id
                    assert hasattr(getattr(binpick, node.name), name), f"{node.name}.{name}"
        elif isinstance(node, ast.FunctionDef):
            assert hasattr(binpick, node.name), node.name
    public = {n for n in dir(binpick) if not n.startswith("_")}
    named = {getattr(n, "name", None) or getattr(getattr(n, "target", None), "id", None)
             for n in stub.body}
    assert public <= named, public - named
