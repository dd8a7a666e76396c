#!/usr/bin/env python3
"""Side by side: binpick eval's BOP scores (report.json) and the BOP toolkit's eval_bop19_pose.py
(scores_bop19.json and the per-threshold scores_*.json of eval_calc_scores.py), and binpick's
scene_gt_info.json against the toolkit's calc_gt_info.py, for the work directory of
tools/bop_toolkit_run.sh. Prints the tables and writes WORK/compare.json.

  tools/bop_toolkit_compare.py WORK

Needs numpy.
"""
import glob
import json
import os
import sys

import numpy as np

B = sys.argv[1] if len(sys.argv) > 1 else sys.exit(__doc__)
MODELS = sorted(os.path.basename(d)[4:] for d in glob.glob(os.path.join(B, "run-*")) if os.path.isdir(d))
SETS = {"results": "report", "results-i20": "report-i20", "results-i60": "report-i60"}
SET_LABEL = {"results": "run (5/img)", "results-i20": "detect --instances 20",
             "results-i60": "detect --instances 60"}
NOISES = {"000": 0.0, "002": 0.02}
TH = {"mssd": [float(t) for t in np.arange(0.05, 0.51, 0.05)],
      "mspd": [float(t) for t in np.arange(5, 51, 5)]}
TAUS = [float(t) for t in np.arange(0.05, 0.51, 0.05)]


def load(p):
    with open(p) as f:
        return json.load(f)


def score_sign(th):
    return "th={:.3f}_min-visib={:.3f}".format(th, -1)


def toolkit(m, s, n):
    d = os.path.join(B, "eval", m, s, "binpick_noise%s-test" % n)
    p = os.path.join(d, "scores_bop19.json")
    if not os.path.exists(p):
        return None
    out = {"final": load(p)}
    for e in ("mssd", "mspd"):
        rec, tgt, tp = [], [], []
        for th in TH[e]:
            sc = load(os.path.join(d, "error=%s_ntop=-1" % e, "scores_%s.json" % score_sign(th)))
            rec.append(sc["recall"]); tgt.append(sc["targets_count"]); tp.append(sc["tp_count"])
        out[e] = {"recall": rec, "targets": tgt, "tp": tp}
    vsd = []
    for tau in TAUS:
        row = []
        for th in TAUS:
            sc = load(os.path.join(d, "error=vsd_ntop=-1_delta=15.000_tau=%.3f" % tau,
                                   "scores_%s.json" % score_sign(th)))
            row.append(sc["recall"])
        vsd.append(row)
    out["vsd"] = {"recall": vsd}
    return out


def binpick(m, s, n):
    r = load(os.path.join(B, "run-" + m, SETS[s], "report.json"))
    for d in r["datasets"]:
        if abs(float(d["noise"]) - NOISES[n]) < 1e-9:
            return d["bop"]
    raise KeyError((m, s, n))


def load_gt_info(ds):
    out = {}
    for d in sorted(glob.glob(os.path.join(ds, "test", "[0-9]" * 6))):
        sid = int(os.path.basename(d))
        with open(os.path.join(d, "scene_gt_info.json")) as f:
            j = json.load(f)
        for im, lst in j.items():
            for gi, e in enumerate(lst):
                out[(sid, int(im), gi)] = e
    return out



def compare_gt_info(binpick_ds, toolkit_ds):
    """Field by field: how many instances differ and by how much."""
    a = load_gt_info(binpick_ds)
    b = load_gt_info(toolkit_ds)
    assert a.keys() == b.keys(), (len(a), len(b))
    fields = ["px_count_all", "px_count_valid", "px_count_visib", "visib_fract", "bbox_obj", "bbox_visib"]
    res = {"instances": len(a), "fields": {}}
    for f in fields:
        ndiff, maxd, worst = 0, 0.0, None
        diffs = []
        for k in sorted(a):
            x, y = a[k][f], b[k][f]
            if isinstance(x, list):
                d = max(abs(p - q) for p, q in zip(x, y))
            else:
                d = abs(x - y)
            if d != 0:
                ndiff += 1
                diffs.append(d)
                if d > maxd:
                    maxd, worst = d, (k, x, y)
        rel = None
        if f.startswith("px_count"):
            rels = [abs(a[k][f] - b[k][f]) / max(b[k][f], 1) for k in a]
            rel = max(rels)
        res["fields"][f] = {"instances_differing": ndiff, "max_abs_diff": maxd,
                            "max_rel_diff": rel, "worst": worst,
                            "mean_abs_diff_over_differing": (sum(diffs) / len(diffs)) if diffs else 0}
    # targets: visib_fract >= 0.1 both sides
    ta = sum(1 for k in a if a[k]["visib_fract"] >= 0.1)
    tb = sum(1 for k in b if b[k]["visib_fract"] >= 0.1)
    flip = [k for k in a if (a[k]["visib_fract"] >= 0.1) != (b[k]["visib_fract"] >= 0.1)]
    res["targets_visib_ge_0.1"] = {"binpick": ta, "toolkit": tb, "differing_instances": flip}

    return res

rows = []
worst = 0.0
for m in MODELS:
    for s in SETS:
        for n in NOISES:
            t = toolkit(m, s, n)
            if t is None:
                continue
            b = binpick(m, s, n)
            f = t["final"]
            row = {"model": m, "set": s, "noise": NOISES[n],
                   "binpick": {"ar_vsd": b["ar_vsd"], "ar_mssd": b["ar_mssd"],
                               "ar_mspd": b["ar_mspd"], "ar": b["ar"], "targets": b["targets"],
                               "estimates": b["estimates"]},
                   "toolkit": {"ar_vsd": f["bop19_average_recall_vsd"],
                               "ar_mssd": f["bop19_average_recall_mssd"],
                               "ar_mspd": f["bop19_average_recall_mspd"],
                               "ar": f["bop19_average_recall"],
                               "targets": t["mssd"]["targets"][0]}}
            for e in ("mssd", "mspd"):
                dd = np.abs(np.array(b[e]["recall"]) - np.array(t[e]["recall"]))
                row["max_threshold_diff_" + e] = float(dd.max())
                row["binpick_recall_" + e] = b[e]["recall"]
                row["toolkit_recall_" + e] = t[e]["recall"]
            if b.get("vsd") and b["vsd"].get("recall"):
                dv = np.abs(np.array(b["vsd"]["recall"]) - np.array(t["vsd"]["recall"]))
                row["max_threshold_diff_vsd"] = float(dv.max())
                row["vsd_cells_differing"] = int((dv > 1e-12).sum())
                row["binpick_recall_vsd"] = b["vsd"]["recall"]
                row["toolkit_recall_vsd"] = t["vsd"]["recall"]
            for k in ("ar_vsd", "ar_mssd", "ar_mspd", "ar"):
                if row["binpick"][k] is not None:
                    worst = max(worst, abs(row["binpick"][k] - row["toolkit"][k]))
            rows.append(row)

print("BOP scores, binpick eval (b) vs the toolkit's eval_bop19_pose.py (t); d = |b - t|")
print("%-8s %-22s %5s | %-19s | %-19s | %-19s | %-19s | %s" % (
    "model", "results", "noise", "AR_VSD b/t", "AR_MSSD b/t", "AR_MSPD b/t", "AR b/t",
    "max |d| per threshold MSSD/MSPD/VSD"))
for r in rows:
    b, t = r["binpick"], r["toolkit"]
    cells = []
    for k in ("ar_vsd", "ar_mssd", "ar_mspd", "ar"):
        cells.append("%.4f/%.4f%s" % (b[k], t[k], " !" if abs(b[k] - t[k]) > 0.01 else "  "))
    print("%-8s %-22s %5.2f | %s | %s | %s | %s | %.4f/%.4f/%.4f" % (
        r["model"], SET_LABEL[r["set"]], r["noise"], *cells, r["max_threshold_diff_mssd"],
        r["max_threshold_diff_mspd"], r.get("max_threshold_diff_vsd", float("nan"))))
print("largest |AR difference|: %.5f" % worst)

# calc_gt_info
print()
print("scene_gt_info.json: binpick vs the toolkit's calc_gt_info.py (vispy renderer)")
gt = []
for m in MODELS:
    for n in NOISES:
        tdir = os.path.join(B, "gtinfo", m, "noise" + n)
        if not os.path.exists(tdir):
            continue
        res = compare_gt_info(os.path.join(B, "run-" + m, "bop", "noise" + n), tdir)
        res["model"], res["noise"] = m, NOISES[n]
        gt.append(res)
        f = res["fields"]
        print("%-8s noise %.2f: %d instances; " % (m, NOISES[n], res["instances"]) + "; ".join(
            "%s %d differ, max |d| %s%s" % (
                k, v["instances_differing"],
                ("%.4g" % v["max_abs_diff"]),
                (" (%.1f %%)" % (100 * v["max_rel_diff"])) if v["max_rel_diff"] is not None else "")
            for k, v in f.items())
              + "; targets (visib_fract >= 0.1) b/t %d/%d" % (
                  res["targets_visib_ge_0.1"]["binpick"], res["targets_visib_ge_0.1"]["toolkit"]))

with open(os.path.join(B, "compare.json"), "w") as fo:
    json.dump({"scores": rows, "gt_info": gt}, fo, indent=1, default=str)
