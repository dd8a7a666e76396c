"""Detection from Python (python/module/): the same detections as the command line on a
fixed-seed dataset, the same parameters by the same names, and bad input refused with one
message (ValueError)."""
import json
import csv
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

import binpick
from conftest import assert_same, cli_rows, images, run


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
    """The first image's points (with depth) as a PLY cloud: `detect --cloud` and detect_cloud,
    the bin found on the cloud as on the image, so the top-ranked pose is on a bracket, not on
    the rim."""
    scene, im, depth, K, scale = next(images(bins / "data"))
    v, u = np.nonzero(depth)
    z = depth[v, u].astype(np.float64) * scale
    points = np.stack([(u - K[0, 2]) * z / K[0, 0], (v - K[1, 2]) * z / K[1, 1], z], axis=1)
    points = points.astype(np.float32)
    ply = tmp_path / "cloud.ply"
    with open(ply, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(points)}\n"
                "property float x\nproperty float y\nproperty float z\nend_header\n")
        f.writelines(f"{x!r} {y!r} {w!r}\n" for x, y, w in points.tolist())
    run("detect", "--model", bins / "bracket.ppfm", "--cloud", ply, "--out", tmp_path / "c.csv")
    found = binpick.Detector(binpick.Model.load(str(bins / "bracket.ppfm"))).detect_cloud(points)
    assert found
    assert_same(found, cli_rows(tmp_path / "c.csv")[(0, 0)])
    truth = json.loads((bins / "data" / "test" / f"{scene:06d}" / "scene_gt.json").read_text())
    nearest = min(np.linalg.norm(np.array(found[0].t) - np.array(g["cam_t_m2c"]))
                  for g in truth[str(im)])
    assert nearest < 15  # mm: a tenth of the bracket's diameter
    # Picks on a cloud: detect_cloud with picks=True plans those `detect --cloud --picks` writes.
    run("detect", "--model", bins / "bracket.ppfm", "--cloud", ply, "--out", tmp_path / "p.csv",
        "--picks")
    with open(tmp_path / "p.picks.csv") as f:
        rows = list(csv.DictReader(f))
    picking = binpick.Detector(binpick.Model.load(str(bins / "bracket.ppfm")), picks=True)
    found = picking.detect_cloud(points)
    assert len(found) == len(rows)
    for d, r in zip(found, rows):
        if d.pick is None:
            assert r["order"] == "" and d.pick_reason == r["reason"] != ""
        else:
            assert (d.pick["order"], d.pick["grasp"]) == (int(r["order"]), int(r["grasp"]))
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


def test_several_models_give_the_command_lines_rows_by_obj_id(bins, tmp_path):
    """A dict of models detects as `detect --model A --model B` does: rows by obj_id, then score."""
    run("train", "--model", "builtin:bolt", "--out", tmp_path / "bolt.ppfm")
    run("detect", "--model", bins / "bracket.ppfm", "--obj-id", "3", "--model", tmp_path / "bolt.ppfm",
        "--obj-id", "5", "--dataset", bins / "data", "--out", tmp_path / "both.csv",
        "--hypotheses", "2", "--more-hypotheses", "0")
    detector = binpick.Detector({5: binpick.Model.load(str(tmp_path / "bolt.ppfm")),
                                 3: binpick.Model.load(str(bins / "bracket.ppfm"))},
                                hypotheses=2, more_hypotheses=0)
    assert detector.obj_ids == [3, 5]
    rows = cli_rows(tmp_path / "both.csv")
    for scene, im, depth, K, scale in images(bins / "data"):
        found = detector.detect(depth, K, scale)
        assert [d.obj_id for d in found] == [int(r["obj_id"]) for r in rows[(scene, im)]]
        assert {3, 5} <= {d.obj_id for d in found}
        assert_same(found, rows[(scene, im)])
        line = binpick.results_csv_row(scene, im, found[-1], 0.0)
        assert line.split(",")[:3] == [str(scene), str(im), "5"]
    with pytest.raises(ValueError, match="none given"):
        binpick.Detector([])


def test_an_image_not_in_row_order_gives_the_same_detections(bins):
    """uint16 depth is read in place when C-contiguous; any other layout is the same image."""
    detector = binpick.Detector(binpick.Model.load(str(bins / "bracket.ppfm")))
    _, _, depth, K, scale = next(images(bins / "data"))
    fortran = np.asfortranarray(depth)
    readonly = depth.copy()
    readonly.flags.writeable = False
    expected = [d.score for d in detector.detect(depth, K, scale)]
    assert [d.score for d in detector.detect(fortran, K, scale)] == expected
    assert [d.score for d in detector.detect(readonly, K, scale)] == expected


def test_a_model_trained_from_arrays_is_the_command_lines_file_of_them(tmp_path):
    """vertices and faces train the model `binpick train` makes of the same mesh in a PLY file."""
    x, y, z = 60.0, 40.0, 10.0  # a box
    vertices = np.array([[0, 0, 0], [x, 0, 0], [x, y, 0], [0, y, 0],
                         [0, 0, z], [x, 0, z], [x, y, z], [0, y, z]], dtype=np.float64)
    faces = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                      [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    ply = tmp_path / "slab.ply"
    with open(ply, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
                f"property float z\nelement face 12\nproperty list uchar int vertex_indices\n"
                f"end_header\n")
        f.writelines(" ".join(str(c) for c in v) + "\n" for v in vertices.tolist())
        f.writelines("3 " + " ".join(map(str, t)) + "\n" for t in faces.tolist())
    run("train", "--model", ply, "--out", tmp_path / "cli.ppfm")
    model = binpick.Model.train(vertices=vertices, faces=faces)
    model.save(str(tmp_path / "py.ppfm"))
    assert (tmp_path / "py.ppfm").read_bytes() == (tmp_path / "cli.ppfm").read_bytes()
    # A box's symmetries: three half turns about its axes through its centre.
    assert len(model.symmetries["discrete"]) == 3 and model.symmetries["continuous"] == []
    for S in model.symmetries["discrete"]:
        assert S.shape == (4, 4) and np.allclose(S[:3, :3] @ S[:3, :3].T, np.eye(3), atol=1e-6)
    for bad, message in ((dict(vertices=vertices), "vertices and faces"),
                         (dict(vertices=vertices[:, :2], faces=faces), r"\(N, 3\)"),
                         (dict(vertices=vertices, faces=faces + 8), "vertex index 8"),
                         (dict(vertices=vertices * np.nan, faces=faces), "NaN")):
        with pytest.raises(ValueError, match=message):
            binpick.Model.train(**bad)
    with pytest.raises(ValueError, match="a part file, or vertices"):
        binpick.Model.train("builtin:bolt", vertices=vertices, faces=faces)


def test_a_plates_lookalike_is_its_turn_over():
    model = binpick.Model.train("builtin:plate")
    assert model.lookalikes and all(S.shape == (4, 4) for S in model.lookalikes)
    assert any(np.trace(S[:3, :3]) < -0.9 for S in model.lookalikes)  # a half turn: trace -1
    assert binpick.Model.train("builtin:shaft").symmetries["continuous"]


def test_the_frame_example_draws_the_top_pose(bins, tmp_path):
    """examples/detect_frame.py: the detector's top pose, drawn into a picture."""
    example = Path(__file__).resolve().parents[2] / "examples" / "detect_frame.py"
    out = tmp_path / "top.png"
    done = subprocess.run([sys.executable, str(example), str(bins / "bracket.ppfm"),
                           str(bins / "data" / "test" / "000000"), "0", str(out)],
                          check=True, capture_output=True, text=True)
    _, _, depth, K, scale = next(images(bins / "data"))
    top = binpick.Detector(binpick.Model.load(str(bins / "bracket.ppfm"))).detect(depth, K, scale)[0]
    assert f"score {top.score:.3f}" in done.stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10000


def test_picks_from_python_are_the_command_lines(bins, tmp_path):
    """picks=True plans the picks `detect --picks` writes to OUT.picks.csv."""
    run("detect", "--model", bins / "bracket.ppfm", "--dataset", bins / "data", "--out",
        tmp_path / "p.csv", "--picks")
    rows = {}
    with open(tmp_path / "p.picks.csv") as f:
        for r in csv.DictReader(f):
            rows.setdefault((int(r["scene_id"]), int(r["im_id"])), []).append(r)
    detector = binpick.Detector(binpick.Model.load(str(bins / "bracket.ppfm")), picks=True)
    picked = 0
    for scene, im, depth, K, scale in images(bins / "data"):
        found = detector.detect(depth, K, scale)
        assert len(found) == len(rows[(scene, im)])
        for d, r in zip(found, rows[(scene, im)]):
            if d.pick is None:
                assert r["order"] == "" and d.pick_reason == r["reason"]
                continue
            picked += 1
            assert d.pick_reason == ""
            assert (d.pick["order"], d.pick["grasp"]) == (int(r["order"]), int(r["grasp"]))
            assert np.allclose(d.pick["pose"][:3, 3], np.array(r["t"].split(), dtype=float), atol=1e-3)
            assert np.allclose(d.pick["approach"], np.array(r["approach"].split(), dtype=float), atol=1e-6)
            assert d.pick["clearance"] == pytest.approx(float(r["clearance"]), abs=1e-3)
            assert d.pick["width"] == pytest.approx(float(r["width"]), abs=1e-3)
    assert picked >= 2
