#!/usr/bin/env python3
"""Re-order the picks of one `bench/realistic_sets.sh` run and let eval judge the first picks.

Each image's picks (rows of WORK/TAG/SET.picks.csv with an order) are sorted by EXPR, a Python
expression in s (the detection's score), c (the clearance over its cap, a quarter of the
part's diameter) and h (the pick's height from 0, the image's lowest pick, to 1, the highest,
along the camera's axis: planning takes it along the bin's up where a bin is found). eval then
judges each image's first pick at the true poses. Prints per set the first picks that succeed.
A variant of the order tried without re-running detection (docs/decisions/2026-12-07-pick-order.md).

usage: bench/reorder_picks.py BINPICK WORK TAG OUTDIR EXPR SET...
       (SUFFIX in the environment: the datasets are WORK/data/SET$SUFFIX)
"""
import csv
import json
import os
import shutil
import subprocess
import sys


def main():
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    binpick, work, tag, out, expr = sys.argv[1:6]
    suffix = os.environ.get("SUFFIX", "")
    total = [0, 0]
    for s in sys.argv[6:]:
        data = f"{work}/data/{s}{suffix}"
        src = f"{work}/{tag}/{s}"
        info = json.load(open(f"{data}/models/models_info.json"))
        rows = list(csv.reader(open(src + ".picks.csv")))
        head, body = rows[0], rows[1:]
        col = {name: k for k, name in enumerate(head)}
        height = lambda r: -float(r[col["t"]].split()[2])
        heights = {}
        for r in body:
            if r[col["order"]]:
                heights.setdefault((r[0], r[1]), []).append(height(r))

        def value(r):
            cap = max(1e-3, 0.25 * info[r[col["obj_id"]]]["diameter"])
            hs = heights[(r[0], r[1])]
            top, bottom = max(hs), min(hs)
            h = (height(r) - bottom) / (top - bottom) if top > bottom else 1.0
            names = {"s": float(r[col["score"]]), "c": float(r[col["clearance"]]) / cap, "h": h}
            return eval(expr, {"min": min, "max": max}, names)

        def key(r):
            return (r[0], r[1], r[2], -value(r) if r[col["order"]] else float("inf"))

        per, new = {}, []
        for r in sorted(body, key=key):
            r = list(r)
            if r[col["order"]]:
                k = (r[0], r[1], r[2])
                per[k] = per.get(k, 0) + 1
                r[col["order"]] = str(per[k])
            new.append(r)
        d = f"{out}/{s}"
        os.makedirs(d, exist_ok=True)
        shutil.copy(src + ".csv", f"{d}/r.csv")
        with open(f"{d}/r.picks.csv", "w") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(head)
            w.writerows(new)
        j = subprocess.run([binpick, "eval", "--dataset", data, "--results", f"{d}/r.csv",
                            "--out", f"{d}/eval", "--pictures", "0", "--no-vsd", "--json"],
                           capture_output=True, text=True)
        if j.returncode:
            sys.exit(f"{s}: eval failed: {j.stderr.strip()}")
        p = json.loads(j.stdout)["datasets"][0]["picks"]
        print(f"{s}\t{p['success']}/{p['images']}", flush=True)
        total[0] += p["success"]
        total[1] += p["images"]
    print(f"total\t{total[0]}/{total[1]}\t{expr}")


if __name__ == "__main__":
    main()
