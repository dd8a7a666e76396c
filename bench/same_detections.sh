#!/usr/bin/env bash
# Whether two runs of bench/realistic_sets.sh detected the same: for every set of TAG_A, its
# results CSV against TAG_B's row for row with the time column left out, and its details CSV on
# the columns both have (a change of form may add columns, never change a value).
#
#   bench/same_detections.sh WORK TAG_A TAG_B
#
# Prints one line per set (same, or the first differing rows) and exits 1 if any set differs or
# is missing from TAG_B. -h, --help: this text.
set -euo pipefail
if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 0
fi
usage="usage: bench/same_detections.sh WORK TAG_A TAG_B"
WORK=${1:?$usage}
A=$WORK/${2:?$usage}
B=$WORK/${3:?$usage}
[ -d "$A" ] || { echo "same_detections: no $A" >&2; exit 2; }
[ -d "$B" ] || { echo "same_detections: no $B" >&2; exit 2; }
status=0
for csv in "$A"/*.csv; do
  case $csv in *.details.csv) continue ;; esac
  set=$(basename "$csv" .csv)
  other=$B/$set.csv
  if [ ! -f "$other" ]; then
    echo "$set: missing in $B"; status=1; continue
  fi
  if python3 - "$csv" "$other" "${csv%.csv}.details.csv" "${other%.csv}.details.csv" <<'PY'
import csv, os, sys
def rows(path, drop=("time",), keep=None):
    with open(path, newline="") as f:
        r = list(csv.reader(f))
    head, body = r[0], r[1:]
    cols = [i for i, h in enumerate(head) if h not in drop and (keep is None or h in keep)]
    return [head[i] for i in cols], [[row[i] for i in cols] for row in body]
ha, ra = rows(sys.argv[1]); hb, rb = rows(sys.argv[2])
bad = []
if ha != hb or ra != rb:
    bad.append("results differ")
    for i, (x, y) in enumerate(zip(ra, rb)):
        if x != y:
            bad.append(f"  row {i + 1}: {','.join(x)}\n      vs {','.join(y)}"); break
    if len(ra) != len(rb): bad.append(f"  {len(ra)} rows vs {len(rb)}")
if os.path.exists(sys.argv[3]) and os.path.exists(sys.argv[4]):
    with open(sys.argv[3]) as f: da = f.readline().strip().split(",")
    with open(sys.argv[4]) as f: db = f.readline().strip().split(",")
    common = [h for h in da if h in db and "ms" not in h and h != "time"]
    missing = [h for h in da if h not in db]
    if missing: bad.append("details columns gone: " + " ".join(missing))
    _, xa = rows(sys.argv[3], drop=(), keep=common); _, xb = rows(sys.argv[4], drop=(), keep=common)
    if xa != xb:
        bad.append("details differ")
        for i, (x, y) in enumerate(zip(xa, xb)):
            if x != y:
                diff = [f"{c}: {p} vs {q}" for c, p, q in zip(common, x, y) if p != q]
                bad.append(f"  row {i + 1}: " + "; ".join(diff[:6])); break
if bad: print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
  then
    echo "$set: same"
  else
    echo "$set: DIFFERENT"; status=1
  fi
done
exit $status
