#!/usr/bin/env bash
# Crash-safe batches (issue 17, item 3): kills `binpick synth`, `detect` and `run` with SIGKILL at
# random moments, resumes them, and checks that every finished output is byte for byte that of an
# uninterrupted run.
#
#   tests/reliability/kill_resume.sh BINPICK [--cycles N] [--seed S] [--work DIR] [--verbs "synth detect run"]
#
# A cycle of a verb: a fresh output, the command started and SIGKILLed at a moment drawn
# uniformly from [0, T) (T: the uninterrupted reference run's wall time), with probability 1/2
# the resume killed the same way once more, then the same command run to completion, and the
# outputs compared with the reference's. A kill that comes after the process has ended does not
# count: the cycle draws again until its kills hit running processes. Every cycle must end
# byte-identical; the script names the first differing file of each cycle that does not (and
# keeps that output as VERB/failed_cycle_N under --work), and exits 1 if any did not.
#
# Excluded from the byte comparison, because they legitimately differ between two runs:
#   - the lock files (.binpick.lock, .NAME.lock): they hold the pid of the last binpick;
#   - the `time` column of results CSVs (BOP's seconds per image, measured);
#   - in run's report (report.json, report.html): the measured times (ms_per_hypothesis and
#     the other *_ms/_s fields; the ms/hyp cells of the HTML tables), see compare_file below.
# Nothing else: every other file (PNG, JSON, PLY, the model, the curves) must be identical,
# and no temporary file (.NAME.tmpPID_N) or staging directory (.NNNNNN.partial) may be left.
set -euo pipefail

binpick=${1:?usage: kill_resume.sh BINPICK [--cycles N] [--seed S] [--work DIR] [--verbs LIST]}
binpick=$(realpath "$binpick")
shift
cycles=20
seed=17
work=""
verbs="synth detect run"
while [ $# -gt 0 ]; do
  case "$1" in
    --cycles) cycles=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --verbs) verbs=$2; shift 2 ;;
    *) echo "kill_resume.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
if [ -z "$work" ]; then
  work=$(mktemp -d "${TMPDIR:-/tmp}/binpick_kill_resume.XXXXXX")
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
RANDOM=$seed  # the kill moments: the same seed, the same moments (in fractions of T)
export BINPICK_CACHE_DIR="$work/cache"

# The small inputs: bolts, a few parts, small images.
# The bolts fill a small bin, so that they cover enough pixels of a small image to be found.
scene="--model builtin:bolt --objects 12 --bin-size 200,150,100 --grid 3,2 --width 192 --height 144 --seed 5"
synth_cmd() { echo "synth $scene --bins 10 --out $1"; }
detect_cmd() { echo "detect --model $work/bolt.ppfm --dataset $work/detect_input --out $1/results.csv"; }
# run has no --bin-size: the default bin, seen in a larger image.
run_cmd() {
  echo "run --model builtin:bolt --objects 12 --width 480 --height 270 --seed 5 --bins 2"\
       "--noise 0,0.02 --pictures 1 --out $1"
}

# Strips what legitimately differs (see the header) from one file, to stdout.
normalised() {
  local file=$1
  case "$file" in
    *.csv)
      # The measured columns, by their header names: `time` (BOP's results), `ms` (eval's
      # hypotheses.csv). No field of these files holds a comma inside quotes.
      awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) drop[i] = ($i == "time" || $i == "ms") }
                        { line = ""; for (i = 1; i <= NF; ++i) if (!drop[i]) line = line $i OFS; print line }' "$file"
      return ;;
    */report.json)
      python3 -c '
import json, re, sys
def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if not re.search(r"(^|_)(ms|s|seconds|time)($|_)", k)}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v
print(json.dumps(strip(json.load(open(sys.argv[1]))), sort_keys=True))' "$file"
      return ;;
    */report.html) sed -E 's/[0-9.]+ *(ms|s)\b/T/g; s/<td[^>]*class="time"[^>]*>[^<]*</<td>T</g' "$file"; return ;;
  esac
  cat "$file"
}

# Compares output tree $2 with reference $1; prints the first difference and returns 1.
compare_trees() {
  local ref=$1 got=$2
  local ref_list got_list
  ref_list=$(cd "$ref" && find . \( -type f -o -type l \) ! -name '.binpick.lock' ! -name '.*.lock' | sort)
  got_list=$(cd "$got" && find . \( -type f -o -type l \) ! -name '.binpick.lock' ! -name '.*.lock' | sort)
  if [ "$ref_list" != "$got_list" ]; then
    echo "file lists differ (< reference, > resumed):"
    diff <(echo "$ref_list") <(echo "$got_list") | head -20
    return 1
  fi
  local f
  while IFS= read -r f; do
    if [ -L "$ref/$f" ]; then
      [ "$(readlink "$ref/$f")" = "$(readlink "$got/$f")" ] || { echo "link $f differs"; return 1; }
      continue
    fi
    if ! cmp -s <(normalised "$ref/$f") <(normalised "$got/$f"); then
      echo "$f differs"
      return 1
    fi
  done <<< "$ref_list"
  return 0
}

# Runs `binpick ARGS` and SIGKILLs it after `delay` seconds; prints "killed" or "finished".
run_and_kill() {
  local delay=$1 log=$2
  shift 2
  "$binpick" "$@" >> "$log" 2>&1 &
  local pid=$!
  sleep "$delay"
  if kill -9 "$pid" 2>/dev/null; then
    wait "$pid" 2>/dev/null || true
    echo killed
  else
    wait "$pid" 2>/dev/null || true
    echo finished
  fi
}

# A delay uniform in [0, T) from the seeded RANDOM (15 bits).
random_delay() {
  awk -v r="$RANDOM" -v t="$1" 'BEGIN { printf "%.3f", t * r / 32768 }'
}

# Detection's input (a dataset and a model), made once; it also fills the decomposition cache,
# so that no reference time includes the decomposition.
prepare_inputs() {
  [ -f "$work/bolt.ppfm" ] && [ -d "$work/detect_input/test" ] && return
  "$binpick" synth $scene --bins 12 --out "$work/detect_input" > "$work/prepare.log" 2>&1
  "$binpick" train --model builtin:bolt --out "$work/bolt.ppfm" >> "$work/prepare.log" 2>&1
}

failures=0
prepare_inputs
for verb in $verbs; do
  # Every run of a verb writes to the same path (the reference is moved away after its run):
  # the outputs name their own paths (reports, fingerprints).
  out="$work/$verb/out"
  ref="$work/$verb/reference"
  rm -rf "$work/$verb"
  mkdir -p "$out"
  start=$(date +%s.%N)
  # shellcheck disable=SC2046
  "$binpick" $("${verb}_cmd" "$out") > "$work/$verb/reference.log" 2>&1 ||
    { echo "$verb: the reference run failed:"; tail -5 "$work/$verb/reference.log"; exit 1; }
  T=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
  mv "$out" "$ref"
  echo "$verb: reference run ${T} s"
  kills=0 identical=0
  for cycle in $(seq 1 "$cycles"); do
    rm -rf "$out"
    mkdir -p "$out"
    log="$work/$verb/cycle_$cycle.log"
    wanted=$((1 + RANDOM % 2))
    hit=0 moments=""
    while [ $hit -lt $wanted ]; do
      delay=$(random_delay "$T")
      # shellcheck disable=SC2046
      outcome=$(run_and_kill "$delay" "$log" $("${verb}_cmd" "$out"))
      if [ "$outcome" = killed ]; then
        hit=$((hit + 1)); moments="$moments ${delay}s"
      elif [ $hit -eq 0 ]; then
        rm -rf "$out"; mkdir -p "$out"  # finished before the first kill: draw again, afresh
      else
        break  # the resume finished before its kill: the cycle has its kill
      fi
    done
    kills=$((kills + hit))
    # shellcheck disable=SC2046
    if ! "$binpick" $("${verb}_cmd" "$out") >> "$log" 2>&1; then
      echo "$verb cycle $cycle: the resumed run failed (killed at$moments):"; tail -5 "$log"
      failures=$((failures + 1)); continue
    fi
    if diff_text=$(compare_trees "$ref" "$out"); then
      identical=$((identical + 1))
    else
      echo "$verb cycle $cycle (killed at$moments): $diff_text"
      cp -r "$out" "$work/$verb/failed_cycle_$cycle"
      failures=$((failures + 1))
    fi
  done
  echo "$verb: $identical of $cycles kill-and-resume cycles byte-identical ($kills kills)"
done
[ $failures -eq 0 ]
