#!/usr/bin/env bash
# Detection quality on a fixed list of small realistic sets: varied parts (thin plates, a
# symmetric shaft, blocks, a bent sheet nobody tuned for), the paper's unrendered bins, bins
# with a structured-light sensor and distractors, and wire-mesh baskets like the real scene
# binpick is judged on (2064 x 1544 at 2 m, tilted, depth lost in patches, a robot arm).
# For telling whether a change helps beyond the case it was made for (docs/contributing.md).
#
#   bench/realistic_sets.sh BINPICK WORK TAG [SET...]
#   bench/realistic_sets.sh BINPICK WORK TAG @held-out
#
# makes each set once (WORK/data/SET, kept between runs: same seeds, same bins), trains its
# model once per binary (WORK/models/SET-MD5.ppfm, MD5 of the binary), detects into
# WORK/TAG/SET.csv with the options in $DETECT (extra `binpick detect` options, e.g.
# DETECT="--plane-search 0"; the word @binpose stands for the set's true bin as a --bin-pose
# file, WORK/data/SET/bin_pose.json) and scores it with
# `binpick eval --no-vsd`. Prints per set: images, top-ranked right (loose: 10 % of the diameter
# and 15 degrees), top-ranked strict (5 %, 5 degrees), all hypotheses right, ms per hypothesis,
# images a bin was found in; then the totals. Writes the same to WORK/TAG/summary.tsv. Detections already made for TAG are
# kept (resumable); remove WORK/TAG to redo them. Without SETs, every set of the main list;
# `--list` lists them. A second list, held out, is run only when asked (`@held-out`, or its sets
# by name; `--list-held-out` lists them): five more parts of tools/unseen_parts.py (a gear shaft,
# a cap screw, a flange, an angle bar, a stepped block). Run it after tuning on the main list, to
# see whether a gain carries over; never tune on it. A third, `@tilted` (`--list-tilted`): nine
# sets seen by a camera tilted 20-40 degrees, six in solid bins and three in baskets. A fourth,
# `@far` (`--list-far`): three baskets seen through a wider lens, the ground all around them.
# `@cell` (`--list-cell`): three baskets small in the view and turned, in a cluttered cell. And
# `@paper` (`--list-paper`): the paper's bins of every built-in part at noise 0, 2 and 5 %
# (bench/same_detections.sh compares two tags of it row for row).
# BINS=N (default 4) makes and runs N images a set instead: 4-image sets move by an image or two
# under small perturbations, so a change whose gain is that size wants more. The sets are the
# same bins, extended (each bin has its own seed): WORK/data/SET-bN holds them, so WORK/data/SET
# stays the 4-image set; use another TAG for each BINS.
# Needs python3 with numpy for the baskets (tools/wire_basket.py). -h, --help: this text.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tools=$here/../tools

# name | binpick synth options (the sought part first; basket files are made below)
SETS=(
  "plate_paper|--model builtin:plate --bins 4 --objects 350 --noise 0.02 --bin-render none --seed 21"
  "plate_paper_n5|--model builtin:plate --bins 4 --objects 350 --noise 0.05 --bin-render none --seed 22"
  "plate_sl|--model builtin:plate --bins 4 --objects 100 --seed 31 --distractors builtin:bracket:0.125,builtin:bolt:0.125 --sensor-model structured-light --noise 0.02"
  "plate_sl_n5|--model builtin:plate --bins 4 --objects 100 --seed 32 --distractors builtin:bracket:0.125,builtin:bolt:0.125 --sensor-model structured-light --noise 0.05"
  "plate_mesh|--model builtin:plate --diameter 150 --bins 4 --objects 60 --seed 101 --distractors builtin:bracket,builtin:bolt,builtin:tee --sensor-model structured-light --specular-cone 8 --dropout-share 0.55 --bin-mesh @basket --width 2064 --height 1544 --camera-height 2000 --camera-tilt 20"
  "plate_mesh_arm|--model builtin:plate --diameter 150 --bins 4 --objects 60 --seed 102 --distractors builtin:bracket,builtin:bolt,builtin:tee --sensor-model structured-light --specular-cone 8 --dropout-share 0.55 --bin-mesh @basket_arm --width 2064 --height 1544 --camera-height 2200 --camera-tilt 25"
  "plate_mesh_armhi|--model builtin:plate --diameter 150 --bins 4 --objects 60 --seed 103 --distractors builtin:bracket,builtin:bolt,builtin:tee --sensor-model structured-light --specular-cone 8 --dropout-share 0.55 --bin-mesh @basket_armhi --width 2064 --height 1544 --camera-height 2000 --camera-tilt 20"
  "bracket_mesh_t30|--model builtin:bracket --bins 4 --objects 60 --seed 104 --distractors builtin:plate,builtin:bolt --sensor-model structured-light --specular-cone 8 --dropout-share 0.55 --bin-mesh @basket_arm --width 2064 --height 1544 --camera-height 2400 --camera-tilt 30"
  "bracket_sl_n3|--model builtin:bracket --bins 4 --objects 100 --seed 105 --distractors builtin:bolt,builtin:tee --sensor-model structured-light --noise 0.03"
  "shaft_sl_n3|--model builtin:shaft --bins 4 --objects 60 --seed 106 --distractors builtin:bolt,builtin:plate --sensor-model structured-light --noise 0.03"
  "bolt_sl_n5|--model builtin:bolt --bins 4 --objects 100 --seed 107 --distractors builtin:tee,builtin:shaft --sensor-model structured-light --noise 0.05"
  "tee_paper_n5|--model builtin:tee --bins 4 --objects 350 --noise 0.05 --bin-render none --seed 108"
  "bentsheet_sl_n3|--model @bentsheet --bins 4 --objects 100 --seed 109 --distractors builtin:bolt,builtin:plate --sensor-model structured-light --noise 0.03"
  "washer_sl|--model @washer --bins 4 --objects 100 --seed 110 --distractors builtin:bolt,builtin:bracket --sensor-model structured-light --specular-cone 8 --dropout-share 0.5"
)
# Tilted cameras (20-40 degrees): solid bins, where the near side is nearest the camera, and
# baskets, where it is seen through the near wall (docs/detect/bin.md, "Seen through a wall").
TILTED=(
  "tee_t30|--model builtin:tee --bins 4 --objects 100 --seed 301 --distractors builtin:bolt,builtin:plate --sensor-model structured-light --noise 0.02 --camera-tilt 30 --camera-height 1400"
  "shaft_t35|--model builtin:shaft --bins 4 --objects 100 --seed 302 --distractors builtin:bracket --sensor-model structured-light --camera-tilt 35 --camera-height 1400"
  "plate_t30|--model builtin:plate --bins 4 --objects 100 --seed 303 --distractors builtin:bracket:0.125,builtin:bolt:0.125 --sensor-model structured-light --noise 0.02 --camera-tilt 30 --camera-height 1400"
  "bolt_t20_n5|--model builtin:bolt --bins 4 --objects 150 --seed 304 --sensor-model structured-light --noise 0.05 --camera-tilt 20 --camera-height 1200"
  "anglebar_t30|--model @anglebar --bins 4 --objects 60 --seed 305 --distractors builtin:tee --sensor-model structured-light --noise 0.02 --camera-tilt 30 --camera-height 1400"
  "flange_t40|--model @flange --bins 4 --objects 60 --seed 306 --distractors builtin:plate,builtin:bolt --sensor-model structured-light --camera-tilt 40 --camera-height 1500"
  "plate_basket_t35|--model builtin:plate --diameter 150 --bins 4 --objects 60 --seed 401 --distractors builtin:bracket,builtin:bolt,builtin:tee --sensor-model structured-light --specular-cone 8 --dropout-share 0.55 --bin-mesh @basket --width 2064 --height 1544 --camera-height 2200 --camera-tilt 35"
  "tee_basket_t25|--model builtin:tee --bins 4 --objects 60 --seed 402 --distractors builtin:plate,builtin:bolt --sensor-model structured-light --specular-cone 8 --dropout-share 0.5 --bin-mesh @basket_arm --width 2064 --height 1544 --camera-height 2200 --camera-tilt 25"
  "anglebar_basket_t30|--model @anglebar --bins 4 --objects 60 --seed 403 --distractors builtin:bracket,builtin:plate --sensor-model structured-light --noise 0.02 --bin-mesh @basket --width 2064 --height 1544 --camera-height 2400 --camera-tilt 30"
)
# Farther off: baskets seen through a wider lens (the focal length about half the default's,
# which shows just the interior), so that the ground shows all around them
# (docs/detect/bin.md, "The ground all around").
FAR=(
  "plate_basket_far|--model builtin:plate --diameter 150 --bins 4 --objects 60 --seed 501 --distractors builtin:bracket,builtin:bolt,builtin:tee --sensor-model structured-light --specular-cone 8 --dropout-share 0.55 --bin-mesh @basket --width 2064 --height 1544 --camera-height 2400 --camera-tilt 25 --intrinsics 3000,3000,1031.5,771.5"
  "bracket_basket_far|--model builtin:bracket --bins 4 --objects 60 --seed 502 --distractors builtin:plate,builtin:bolt --sensor-model structured-light --specular-cone 8 --dropout-share 0.5 --bin-mesh @basket_arm --width 2064 --height 1544 --camera-height 2200 --intrinsics 3200,3200,1031.5,771.5"
  "tee_basket_far_t35|--model builtin:tee --bins 4 --objects 60 --seed 503 --distractors builtin:plate,builtin:bolt --sensor-model structured-light --noise 0.02 --bin-mesh @basket --width 2064 --height 1544 --camera-height 2600 --camera-tilt 35 --intrinsics 2800,2800,1031.5,771.5"
)
# In a cluttered cell, like the real scene: the basket small in the view (about a third of its
# width), turned in the image (--camera-roll), 0.7 m in front of a fence, beside a robot, a crate,
# a tray and cables on a wide floor (tools/wire_basket.py --cell).
CELL=(
  "plate_cell|--model builtin:plate --diameter 150 --bins 4 --objects 60 --seed 701 --distractors builtin:bracket,builtin:bolt,builtin:tee --sensor-model structured-light --specular-cone 8 --dropout-share 0.55 --bin-mesh @cell --width 2064 --height 1544 --camera-height 2400 --camera-tilt 25 --camera-roll 25 --intrinsics 2750,2750,1031.5,771.5"
  "bracket_cell|--model builtin:bracket --bins 4 --objects 60 --seed 702 --distractors builtin:plate,builtin:bolt --sensor-model structured-light --specular-cone 8 --dropout-share 0.5 --bin-mesh @cell --width 2064 --height 1544 --camera-height 2200 --camera-tilt 30 --camera-roll -20 --intrinsics 2600,2600,1231.5,771.5"
  "tee_cell|--model builtin:tee --bins 4 --objects 60 --seed 703 --distractors builtin:plate,builtin:bolt --sensor-model structured-light --noise 0.02 --bin-mesh @cell --width 2064 --height 1544 --camera-height 2600 --camera-tilt 20 --camera-roll 40 --intrinsics 3000,3000,1031.5,871.5"
)
# The paper's bins (unrendered bin, 350 parts, Gaussian noise) of every built-in part at noise 0,
# 2 and 5 % of the diameter, two bins each: for checking that a change of form detects the same.
PAPER=()
for part in bracket bolt tee plate shaft; do
  for noise in 0 0.02 0.05; do
    PAPER+=("paper_${part}_n${noise#0.0}|--model builtin:$part --bins 2 --noise $noise --bin-render none --seed 601")
  done
done
# Held out: parts and sets nobody tuned for (the same form).
HELD_OUT=(
  "gearshaft_sl|--model @gearshaft --bins 4 --objects 60 --seed 201 --distractors builtin:bolt,builtin:plate --sensor-model structured-light --noise 0.02"
  "capscrew_paper_n3|--model @capscrew --bins 4 --objects 200 --noise 0.03 --bin-render none --seed 202"
  "capscrew_sl|--model @capscrew --bins 4 --objects 100 --seed 203 --distractors builtin:bolt,builtin:shaft --sensor-model structured-light"
  "flange_sl|--model @flange --bins 4 --objects 60 --seed 204 --distractors builtin:plate,builtin:tee --sensor-model structured-light --noise 0.02"
  "anglebar_sl|--model @anglebar --bins 4 --objects 60 --seed 205 --distractors builtin:bracket --sensor-model structured-light --specular-cone 8 --dropout-share 0.5"
  "stepblock_paper_n5|--model @stepblock --bins 4 --objects 150 --noise 0.05 --bin-render none --seed 206"
)

if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 0
fi
if [ "${1:-}" = "--list" ]; then
  for s in "${SETS[@]}"; do echo "${s%%|*}"; done
  exit 0
fi
if [ "${1:-}" = "--list-held-out" ]; then
  for s in "${HELD_OUT[@]}"; do echo "${s%%|*}"; done
  exit 0
fi
if [ "${1:-}" = "--list-tilted" ]; then
  for s in "${TILTED[@]}"; do echo "${s%%|*}"; done
  exit 0
fi
if [ "${1:-}" = "--list-far" ]; then
  for s in "${FAR[@]}"; do echo "${s%%|*}"; done
  exit 0
fi
if [ "${1:-}" = "--list-cell" ]; then
  for s in "${CELL[@]}"; do echo "${s%%|*}"; done
  exit 0
fi
if [ "${1:-}" = "--list-paper" ]; then
  for s in "${PAPER[@]}"; do echo "${s%%|*}"; done
  exit 0
fi
usage="usage: bench/realistic_sets.sh BINPICK WORK TAG [SET...|@held-out|@tilted|@far|@cell|@paper] | --list | --list-held-out | --list-tilted | --list-far | --list-cell | --list-paper"
BINPICK=$(readlink -f "${1:?$usage}")
WORK=${2:?$usage}
TAG=${3:?$usage}
shift 3
mkdir -p "$WORK"
WORK=$(readlink -f "$WORK")
export BINPICK_QUIET=1

wanted=()
for w in "$@"; do
  if [ "$w" = "@held-out" ]; then
    for s in "${HELD_OUT[@]}"; do wanted+=("${s%%|*}"); done
  elif [ "$w" = "@tilted" ]; then
    for s in "${TILTED[@]}"; do wanted+=("${s%%|*}"); done
  elif [ "$w" = "@far" ]; then
    for s in "${FAR[@]}"; do wanted+=("${s%%|*}"); done
  elif [ "$w" = "@cell" ]; then
    for s in "${CELL[@]}"; do wanted+=("${s%%|*}"); done
  elif [ "$w" = "@paper" ]; then
    for s in "${PAPER[@]}"; do wanted+=("${s%%|*}"); done
  else
    wanted+=("$w")
  fi
done
if [ $# -eq 0 ]; then
  for s in "${SETS[@]}"; do wanted+=("${s%%|*}"); done
fi

# The files that @NAME stands for in a set's options, made on first use.
asset() {
  local f
  case $1 in
    basket) f=$WORK/assets/basket.stl
      [ -f "$f" ] || python3 "$tools/wire_basket.py" "$f" >/dev/null ;;
    basket_arm) f=$WORK/assets/basket_arm.stl
      [ -f "$f" ] || python3 "$tools/wire_basket.py" "$f" --arm >/dev/null ;;
    basket_armhi) f=$WORK/assets/basket_armhi.stl
      [ -f "$f" ] || python3 "$tools/wire_basket.py" "$f" --arm --arm-top 150 >/dev/null ;;
    cell) f=$WORK/assets/cell.stl
      [ -f "$f" ] || python3 "$tools/wire_basket.py" "$f" --cell >/dev/null ;;
    bentsheet|washer|hexnut|gearshaft|capscrew|flange|anglebar|stepblock) f=$WORK/assets/$1.stl
      [ -f "$f" ] || python3 "$tools/unseen_parts.py" "$WORK/assets" >/dev/null ;;
    *) echo "realistic_sets: unknown asset @$1" >&2; exit 2 ;;
  esac
  [ -f "$f" ] || { echo "realistic_sets: could not make $f" >&2; exit 1; }
  echo "$f"
}

options_of() {
  local s
  for s in "${SETS[@]}" "${HELD_OUT[@]}" "${TILTED[@]}" "${FAR[@]}" "${CELL[@]}" "${PAPER[@]}"; do
    if [ "${s%%|*}" = "$1" ]; then
      local word file out=()
      for word in ${s#*|}; do
        # Checked here: set -e does not apply inside `options_of ... || exit`, and a failed
        # asset would otherwise leave an empty word in the options.
        if [[ $word == @* ]]; then
          file=$(asset "${word#@}") || return 1
          out+=("$file")
        else
          out+=("$word")
        fi
      done
      echo "${out[@]}"
      return 0
    fi
  done
  echo "realistic_sets: no set named $1 (--list, --list-held-out, --list-tilted, --list-far and --list-cell list them)" >&2
  exit 2
}

BINS=${BINS:-4}
[[ $BINS =~ ^[1-9][0-9]*$ ]] || { echo "realistic_sets: BINS must be a positive whole number, not '$BINS'" >&2; exit 2; }
mkdir -p "$WORK/assets" "$WORK/data" "$WORK/models" "$WORK/$TAG"
stamp=$(md5sum "$BINPICK" | cut -c1-12)  # a model per binary: a new build retrains
summary=$WORK/$TAG/summary.tsv
printf 'set\timages\ttop\tstrict\tall\thypotheses\tms_per_hypothesis\tbin_found\tpicks\n' >"$summary"
for set in "${wanted[@]}"; do
  opts=$(options_of "$set") || exit 1
  read -r -a synth_opts <<<"$opts"
  data=$WORK/data/$set
  if [ "$BINS" != 4 ]; then
    data=$WORK/data/$set-b$BINS
    for i in "${!synth_opts[@]}"; do
      [ "${synth_opts[$i]}" = --bins ] && synth_opts[$((i + 1))]=$BINS
    done
  fi
  # synth resumes: a finished dataset costs nothing; an interrupted one is completed.
  "$BINPICK" synth "${synth_opts[@]}" --no-cloud --out "$data" --cache-dir "$WORK/cache" >/dev/null
  # The part's model options among the synth options (every option of a set takes one value).
  model_opts=()
  i=0
  while [ $i -lt ${#synth_opts[@]} ]; do
    case ${synth_opts[$i]} in
      --model|--diameter|--unit-scale) model_opts+=("${synth_opts[$i]}" "${synth_opts[$((i + 1))]}") ;;
    esac
    i=$((i + 2))
  done
  model=$WORK/models/$set-$stamp.ppfm
  [ -f "$model" ] || "$BINPICK" train "${model_opts[@]}" --out "$model" >/dev/null
  csv=$WORK/$TAG/$set.csv
  # @binpose in $DETECT: the set's own bin, as a calibrated cell gives it (its synth world frame
  # is the bin's: scene_camera.json's cam_R_w2c and cam_t_w2c, and the set's --bin-size).
  detect_opts=${DETECT:-}
  if [[ " $detect_opts " == *" @binpose "* ]]; then
    size=600,400,300
    for i in "${!synth_opts[@]}"; do
      [ "${synth_opts[$i]}" = --bin-size ] && size=${synth_opts[$((i + 1))]}
    done
    python3 - "$data/test/000000/scene_camera.json" "$size" "$data/bin_pose.json" <<'PY'
import json, sys
cam = json.load(open(sys.argv[1]))["0"]
json.dump({"cam_R_bin": cam["cam_R_w2c"], "cam_t_bin": cam["cam_t_w2c"],
           "interior_mm": [float(v) for v in sys.argv[2].split(",")]}, open(sys.argv[3], "w"), indent=2)
PY
    detect_opts=${detect_opts//@binpose/$data/bin_pose.json}
  fi
  # shellcheck disable=SC2086
  "$BINPICK" detect --model "$model" --dataset "$data" --out "$csv" $detect_opts >"$WORK/$TAG/$set.detect.log"
  [ -s "$csv" ] || { echo "realistic_sets: $set: detect wrote nothing" >&2; exit 1; }
  "$BINPICK" eval --dataset "$data" --results "$csv" --out "$WORK/$TAG/$set.report" --no-vsd \
    --pictures 0 --json >"$WORK/$TAG/$set.json"
  python3 - "$WORK/$TAG/$set.json" "$set" "$WORK/$TAG/$set.detect.log" >>"$summary" <<'PY'
import json, re, sys
row = json.load(open(sys.argv[1]))["datasets"][0]
found = re.search(r"a bin found in (\d+) of (\d+) images", open(sys.argv[3]).read())
loose, strict = row["precision"]["loose"], row["precision"]["strict"]
n, h = row["images"], row["hypotheses"]
ms = row["ms_per_hypothesis"]
# With --picks in $DETECT: the images whose first pick succeeds (docs/picks.md).
picks = row.get("picks")
print("\t".join(str(x) for x in (sys.argv[2], n, round(loose["top"] * n), round(strict["top"] * n),
                                 round(loose["all"] * h), h, "-" if ms is None else round(ms),
                                 found.group(1) if found else "-",
                                 picks["success"] if picks else "-")))
PY
  tail -1 "$summary"
done
python3 - "$summary" <<'PY'
import sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1])][1:]
tot = [sum(int(r[i]) for r in rows) for i in range(1, 6)]
line = "total\t%d images\ttop %d\tstrict %d\tall %d of %d" % tuple(tot)
if rows and all(r[8] != "-" for r in rows):
    line += "\tpicks %d" % sum(int(r[8]) for r in rows)
print(line)
PY
