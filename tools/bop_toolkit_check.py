#!/usr/bin/env python3
"""Compares `binpick eval`'s BOP recalls (report.json) with the BOP toolkit's own functions.

The toolkit (github.com/thodan/bop_toolkit) is not vendored: point --toolkit at a checkout (the
directory holding bop_toolkit_lib/). Its scripts (eval_calc_errors.py, eval_calc_scores.py) only
run on datasets it knows by name, so this script does their bookkeeping the way they do (targets,
the inst_count best estimates per image and object, normalisation by the diameter and by
640 / image width) and calls the toolkit's library for everything else:
misc.get_symmetry_transformations, pose_error.mssd / mspd, pose_matching.match_poses_scene and
score.calc_localization_scores, with the settings of scripts/eval_bop19_pose.py
(max_sym_disc_step 0.01, n_top -1, visib_gt_min -1).

  tools/bop_toolkit_check.py --toolkit DIR --dataset DS --results CSV --report report.json

Prints both sets of numbers and exits 1 if an AR differs by more than --tolerance (0.01), 77 if
numpy or the toolkit is missing (a skip for ctest).

VSD renders the model, which the toolkit does with OpenGL; what binpick must match exactly is
the comparison of the rendered depth images, so that is checked on its own:

  tools/bop_toolkit_check.py --vsd-cases cases.json

recomputes the VSD errors of each case (depth images as binpick hands them to its vsd_errors, and
its errors; tests/eval/test_bop_vsd.cpp writes them) with a transcription of the toolkit's
pose_error.vsd, visibility.estimate_visib_mask_gt / _est ("bop19") and
misc.depth_im_to_dist_im_fast, and exits 1 if any differs by more than 1e-6.
"""
import argparse
import json
import os
import sys
import types

SKIP = 77


def stub_missing(name, **attrs):
    """Imports the toolkit needs only for functions not used here (scipy, pytz, rendering)."""
    try:
        __import__(name)
    except ImportError:
        module = types.ModuleType(name)
        for k, v in attrs.items():
            setattr(module, k, v)
        sys.modules[name] = module
        parent, _, child = name.rpartition(".")
        if parent:
            setattr(sys.modules[parent], child, module)


def load_toolkit(path):
    sys.path.insert(0, path)
    stub_missing("scipy")
    stub_missing("scipy.spatial", distance=None, cKDTree=None)
    stub_missing("scipy.spatial.distance")
    stub_missing("pytz")
    try:
        from bop_toolkit_lib import misc, pose_error, pose_matching, score  # noqa: F401
    except ImportError as e:
        print(f"skipped: the BOP toolkit is not importable from {path}: {e}")
        sys.exit(SKIP)
    return misc, pose_error, pose_matching, score


def read_ply_vertices(path, np):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header") + len(b"end_header")
    end = data.index(b"\n", end) + 1
    header = data[:end].decode("ascii").splitlines()
    fmt = next(l.split()[1] for l in header if l.startswith("format"))
    types_np = {"float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
                "uchar": "u1", "uint8": "u1", "char": "i1", "int8": "i1", "short": "i2",
                "int16": "i2", "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4",
                "uint": "u4", "uint32": "u4"}
    count, props, in_vertex = 0, [], False
    for line in header:
        w = line.split()
        if w[0] == "element":
            in_vertex = w[1] == "vertex"
            if in_vertex:
                count = int(w[2])
        elif w[0] == "property" and in_vertex:
            props.append((w[-1], types_np[w[1]]))
    body = data[end:]
    if fmt == "ascii":
        rows = body.decode("ascii").split("\n")[:count]
        table = np.array([[float(x) for x in r.split()[:len(props)]] for r in rows])
        cols = {name: table[:, i] for i, (name, _) in enumerate(props)}
    else:
        order = "<" if fmt == "binary_little_endian" else ">"
        dtype = np.dtype([(name, order + t) for name, t in props])
        table = np.frombuffer(body, dtype=dtype, count=count)
        cols = {name: table[name].astype(np.float64) for name, _ in props}
    return np.stack([cols["x"], cols["y"], cols["z"]], axis=1).astype(np.float64)


def load_json(path):
    with open(path) as f:
        return json.load(f)


def targets_of(dataset, split, scene_gts, scene_infos):
    path = os.path.join(dataset, "test_targets_bop19.json")
    if os.path.exists(path):
        return load_json(path)
    targets = []  # instances with visib_fract >= 0.1, as BOP's published targets
    for scene_id, gts in scene_gts.items():
        for im_id, im_gts in gts.items():
            counts = {}
            for gt_id, gt in enumerate(im_gts):
                info = scene_infos.get(scene_id, {}).get(im_id)
                if info is None or info[gt_id]["visib_fract"] >= 0.1:
                    counts[gt["obj_id"]] = counts.get(gt["obj_id"], 0) + 1
            targets += [{"scene_id": scene_id, "im_id": im_id, "obj_id": o, "inst_count": c}
                        for o, c in counts.items()]
    return targets


# Transcription of bop_toolkit_lib/misc.py depth_im_to_dist_im_fast (without its cache).
def depth_im_to_dist_im_fast(depth_im, K, np):
    xs, ys = np.meshgrid(np.arange(depth_im.shape[1]), np.arange(depth_im.shape[0]))
    pre_Xs = (xs - K[0, 2]) / np.float64(K[0, 0])
    pre_Ys = (ys - K[1, 2]) / np.float64(K[1, 1])
    return np.sqrt(np.multiply(pre_Xs, depth_im) ** 2 + np.multiply(pre_Ys, depth_im) ** 2
                   + depth_im.astype(np.float64) ** 2)


# Transcription of bop_toolkit_lib/visibility.py _estimate_visib_mask, visib_mode "bop19".
def estimate_visib_mask(d_test, d_model, delta, np):
    d_diff = d_model.astype(np.float32) - d_test.astype(np.float32)
    return np.logical_and(np.logical_or(d_diff <= delta, d_test == 0), d_model > 0)


# Transcription of bop_toolkit_lib/pose_error.py vsd, cost "step", from the rendered depths.
def vsd(depth_est, depth_gt, depth_test, K, delta, taus, normalized_by_diameter, diameter, np):
    dist_test = depth_im_to_dist_im_fast(depth_test, K, np)
    dist_gt = depth_im_to_dist_im_fast(depth_gt, K, np)
    dist_est = depth_im_to_dist_im_fast(depth_est, K, np)
    visib_gt = estimate_visib_mask(dist_test, dist_gt, delta, np)
    visib_est = estimate_visib_mask(dist_test, dist_est, delta, np)
    visib_est = np.logical_or(visib_est, np.logical_and(visib_gt, dist_est > 0))
    visib_inter = np.logical_and(visib_gt, visib_est)
    visib_union = np.logical_or(visib_gt, visib_est)
    visib_union_count = visib_union.sum()
    visib_comp_count = visib_union_count - visib_inter.sum()
    dists = np.abs(dist_gt[visib_inter] - dist_est[visib_inter])
    if normalized_by_diameter:
        dists /= diameter
    if visib_union_count == 0:
        return [1.0] * len(taus)
    return [(np.sum(dists >= tau) + visib_comp_count) / float(visib_union_count) for tau in taus]


def check_vsd_cases(path, np):
    worst, count = 0.0, 0
    for i, c in enumerate(load_json(path)):
        w, h = c["width"], c["height"]
        fx, cx, fy, cy = c["K"]
        K = np.array([[fx, 0, cx], [0, fy, cy], [0, 0, 1]], dtype=np.float64)
        depth_test = np.array(c["depth_raw"], dtype=np.float32).reshape(h, w)  # inout.load_depth
        depth_test *= c["depth_scale"]
        depth_est = np.array(c["depth_est"], dtype=np.float32).reshape(h, w)
        depth_gt = np.array(c["depth_gt"], dtype=np.float32).reshape(h, w)
        ours = c["errors"]
        theirs = vsd(depth_est, depth_gt, depth_test, K, float(c["delta"]),
                     [float(t) for t in c["taus"]], c["normalized_by_diameter"],
                     float(c["diameter"]), np)
        for a, b in zip(ours, theirs):
            worst = max(worst, abs(a - b))
        count += 1
        if len(ours) != len(theirs) or any(abs(a - b) > 1e-6 for a, b in zip(ours, theirs)):
            print(f"case {i}: binpick {ours}\n        toolkit {theirs}")
    print(f"VSD: {count} cases, largest difference {worst:.3g}")
    return 0 if worst <= 1e-6 else 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--vsd-cases", help="check binpick's VSD errors of these cases, then exit")
    ap.add_argument("--toolkit")
    ap.add_argument("--dataset")
    ap.add_argument("--results")
    ap.add_argument("--report")
    ap.add_argument("--split", default="test")
    ap.add_argument("--tolerance", type=float, default=0.01)
    a = ap.parse_args()
    try:
        import numpy as np
    except ImportError:
        print("skipped: numpy is missing")
        return SKIP
    if a.vsd_cases:
        return check_vsd_cases(a.vsd_cases, np)
    for name in ("toolkit", "dataset", "results", "report"):
        if getattr(a, name) is None:
            ap.error(f"--{name} is required (or --vsd-cases)")
    misc, pose_error, pose_matching, score = load_toolkit(a.toolkit)

    models_info = {int(k): v for k, v in
                   load_json(os.path.join(a.dataset, "models", "models_info.json")).items()}
    split_dir = os.path.join(a.dataset, a.split)
    scene_gts, scene_infos, scene_cams = {}, {}, {}
    for name in sorted(os.listdir(split_dir)):
        d = os.path.join(split_dir, name)
        if not name.isdigit() or not os.path.exists(os.path.join(d, "scene_gt.json")):
            continue
        sid = int(name)
        to_int = lambda j: {int(k): v for k, v in j.items()}
        scene_gts[sid] = to_int(load_json(os.path.join(d, "scene_gt.json")))
        scene_cams[sid] = to_int(load_json(os.path.join(d, "scene_camera.json")))
        if os.path.exists(os.path.join(d, "scene_gt_info.json")):
            scene_infos[sid] = to_int(load_json(os.path.join(d, "scene_gt_info.json")))
    camera_json = os.path.join(a.dataset, "camera.json")
    im_width = load_json(camera_json)["width"] if os.path.exists(camera_json) else 640

    targets = targets_of(a.dataset, a.split, scene_gts, scene_infos)
    targets_org = {}
    for t in targets:
        targets_org.setdefault(t["scene_id"], {}).setdefault(t["im_id"], {})[t["obj_id"]] = t
    obj_ids = sorted({t["obj_id"] for t in targets})
    model_dir = os.path.join(a.dataset, "models_eval")
    if not obj_ids or not os.path.exists(os.path.join(model_dir, f"obj_{obj_ids[0]:06d}.ply")):
        model_dir = os.path.join(a.dataset, "models")
    pts = {o: read_ply_vertices(os.path.join(model_dir, f"obj_{o:06d}.ply"), np) for o in obj_ids}
    syms = {o: misc.get_symmetry_transformations(models_info[o], 0.01) for o in obj_ids}

    ests = {}
    with open(a.results) as f:
        next(f)
        for line in f:
            c = line.strip().split(",")
            if len(c) < 7:
                continue
            e = {"scene_id": int(c[0]), "im_id": int(c[1]), "obj_id": int(c[2]),
                 "score": float(c[3]),
                 "R": np.array([float(x) for x in c[4].split()]).reshape(3, 3),
                 "t": np.array([float(x) for x in c[5].split()]).reshape(3, 1)}
            ests.setdefault(e["scene_id"], {}).setdefault(e["im_id"], {}).setdefault(
                e["obj_id"], []).append(e)

    # eval_calc_errors.py (n_top = -1: the inst_count best estimates per image and object).
    errors = {"mssd": {}, "mspd": {}}
    for scene_id, scene_targets in targets_org.items():
        for kind in errors:
            errors[kind][scene_id] = []
        for im_id, im_targets in scene_targets.items():
            K = np.array(scene_cams[scene_id][im_id]["cam_K"]).reshape(3, 3)
            im_gt = scene_gts[scene_id][im_id]
            for obj_id, target in im_targets.items():
                obj_ests = ests.get(scene_id, {}).get(im_id, {}).get(obj_id, [])
                chosen = sorted(enumerate(obj_ests), key=lambda x: x[1]["score"], reverse=True)
                chosen = chosen[slice(0, target["inst_count"])]
                for est_id, est in chosen:
                    errs = {"mssd": {}, "mspd": {}}
                    for gt_id, gt in enumerate(im_gt):
                        if gt["obj_id"] != obj_id:
                            continue
                        R_g = np.array(gt["cam_R_m2c"]).reshape(3, 3)
                        t_g = np.array(gt["cam_t_m2c"]).reshape(3, 1)
                        errs["mssd"][gt_id] = [pose_error.mssd(
                            est["R"], est["t"], R_g, t_g, pts[obj_id], syms[obj_id])]
                        errs["mspd"][gt_id] = [pose_error.mspd(
                            est["R"], est["t"], R_g, t_g, K, pts[obj_id], syms[obj_id])]
                    for kind in errors:
                        errors[kind][scene_id].append(
                            {"im_id": im_id, "obj_id": obj_id, "est_id": est_id,
                             "score": est["score"], "errors": errs[kind], "scene_id": scene_id,
                             "gt_visib_fracts": {g: 1.0 for g in errs[kind]}})

    # eval_calc_scores.py (localization, visib_gt_min = -1) for each threshold.
    thresholds = {"mssd": list(np.arange(0.05, 0.51, 0.05)), "mspd": list(np.arange(5, 51, 5))}
    ar = {}
    for kind in ("mssd", "mspd"):
        recalls = []
        for th in thresholds[kind]:
            th = float(str(th))  # the scripts pass thresholds as text
            matches = []
            for scene_id, scene_targets in targets_org.items():
                gt_curr, info_curr, valid = {}, {}, {}
                for im_id, im_targets in scene_targets.items():
                    im_gt = scene_gts[scene_id][im_id]
                    info = scene_infos.get(scene_id, {}).get(
                        im_id, [{"visib_fract": 1.0}] * len(im_gt))
                    gt_curr[im_id], info_curr[im_id] = im_gt, info
                    order = sorted(range(len(im_gt)), key=lambda g: info[g]["visib_fract"],
                                   reverse=True)
                    to_add = {o: t["inst_count"] for o, t in im_targets.items()}
                    valid[im_id] = [False] * len(im_gt)
                    for g in order:
                        o = im_gt[g]["obj_id"]
                        if to_add.get(o, 0) > 0:
                            valid[im_id][g] = True
                            to_add[o] -= 1
                scene_errs = []
                for e in errors[kind][scene_id]:
                    e = dict(e)
                    if kind == "mssd":
                        d = float(models_info[e["obj_id"]]["diameter"])
                        e["errors"] = {g: [x / d for x in v] for g, v in e["errors"].items()}
                    else:
                        f = 640.0 / im_width
                        e["errors"] = {g: [f * x for x in v] for g, v in e["errors"].items()}
                    e["gt_visib_fracts"] = {g: info_curr[e["im_id"]][g]["visib_fract"]
                                            for g in e["errors"]}
                    scene_errs.append(e)
                matches += pose_matching.match_poses_scene(
                    scene_id, gt_curr, info_curr, valid, scene_errs, [th], -1)
            s = score.calc_localization_scores(sorted(targets_org), obj_ids, matches, -1,
                                               do_print=False)
            recalls.append(s["recall"])
        ar[kind] = float(np.mean(recalls))
        print(f"toolkit {kind}: recall per threshold {[round(r, 4) for r in recalls]}")

    report = load_json(a.report)
    ours = report["datasets"][0]["bop"]
    worst = 0.0
    for kind in ("mssd", "mspd"):
        diff = abs(ar[kind] - ours["ar_" + kind])
        worst = max(worst, diff)
        print(f"AR_{kind.upper()}: toolkit {ar[kind]:.4f}  binpick {ours['ar_' + kind]:.4f}  "
              f"difference {diff:.4f}")
    return 0 if worst <= a.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
