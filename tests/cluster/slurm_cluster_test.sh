#!/usr/bin/env bash
# A real Slurm cluster for `--slurm`: brings up a private single-node cluster (munged, slurmctld,
# slurmd from Debian, no systemd; its own config, ports, munge socket and state under a temporary
# directory, so it touches nothing of the machine's), then
#   - a 2-task synth array makes the dataset a single process makes (scene_gt.json, depth PNGs),
#   - a 4-task detect array gives the single process's results CSV (time column aside),
#   - a detect array with one task cancelled while it runs fails naming that shard; the same
#     command again resubmits only it and then gives the same CSV,
#   - a rerun while the array of an interrupted follower still runs follows it, not resubmits,
#   - a 2-task run array writes the single process's report.json (paths and timing aside),
#   - a tune whose round is a 2-task array measures the single process's points (tune.csv, times
#     aside) and picks the same best.json,
# and stops the daemons by their pid files.
# usage: slurm_cluster_test.sh BINPICK      (exit 77: skipped, with the reason on stdout)
#        slurm_cluster_test.sh --check      (says whether it would run or skip, exits 0)
set -euo pipefail

# shellcheck source=private_cluster.sh
. "$(dirname "$0")/private_cluster.sh"

if [ "${1:-}" = "--check" ]; then
  reason=$(private_cluster_skip_reason)
  if [ -n "$reason" ]; then
    echo "cluster test (slurm_cluster): SKIPPED: $reason"
  else
    echo "cluster test (slurm_cluster): runs a private single-node Slurm cluster"
  fi
  exit 0
fi

BINPICK=$(readlink -f "${1:?usage: slurm_cluster_test.sh BINPICK}")
reason=$(private_cluster_skip_reason)
if [ -n "$reason" ]; then
  echo "SKIPPED: the Slurm cluster test needs root and Debian's ${PRIVATE_CLUSTER_PACKAGES[*]}: $reason"
  exit 77
fi
private_cluster_install

DIR=$(mktemp -d /tmp/binpick_slurm.XXXXXX)
export BINPICK_QUIET=1
fail() { echo "FAIL: $*"; exit 1; }
cleanup() {
  local status=$?
  private_cluster_stop "$DIR"
  if [ $status -ne 0 ] && [ $status -ne 77 ]; then
    echo "--- logs ($DIR)"
    tail -n 20 "$DIR"/*.log "$DIR"/work/*.out 2>/dev/null || true
  fi
  rm -rf "$DIR"
}
trap cleanup EXIT

# ---- the cluster ---------------------------------------------------------------------------------
private_cluster_start "$DIR" || fail "no cluster"
mkdir -p "$DIR/work"
echo "cluster up: node $(hostname -s), $(nproc) CPUs, ${SECONDS} s"

# ---- the work ------------------------------------------------------------------------------------
cd "$DIR/work"
synth_args=(--model builtin:bracket --objects 8 --width 480 --height 270 --no-cloud
            --bin-size 300,200,150 --camera-height 600
            --cache-dir "$DIR/work/cache" --bins 4)
"$BINPICK" synth "${synth_args[@]}" --out single >/dev/null
"$BINPICK" synth "${synth_args[@]}" --out array --slurm --tasks 2 > synth.out \
  || fail "synth --slurm: $(cat synth.out)"
grep -q "all 4 bins present" synth.out || fail "synth --slurm did not check the bins: $(cat synth.out)"
for b in 000000 000001 000002 000003; do
  for f in scene_gt.json depth/000000.png; do
    cmp -s "single/test/$b/$f" "array/test/$b/$f" || fail "synth: $b/$f differs from the single process's"
  done
done
echo "synth: a 2-task array made the single process's 4 bins (${SECONDS} s)"

"$BINPICK" train --model builtin:bracket --out bracket.ppfm >/dev/null
detect_args=(--model bracket.ppfm --dataset single --hypotheses 3)
"$BINPICK" detect "${detect_args[@]}" --out single.csv >/dev/null
without_time() { sed 's/,[^,]*$//' "$1"; }
"$BINPICK" detect "${detect_args[@]}" --out array.csv --slurm --tasks 4 > detect.out \
  || fail "detect --slurm: $(cat detect.out)"
[ "$(without_time single.csv)" = "$(without_time array.csv)" ] || fail "detect: array.csv differs"
cmp -s single.details.csv array.details.csv || fail "detect: array.details.csv differs"
echo "detect: a 4-task array gave the single process's $(($(wc -l < single.csv) - 1)) rows (${SECONDS} s)"

# One task killed while it runs (state R, not a pending one): the array ends without that shard's
# work; the same command again resubmits only that shard. A task can finish between squeue
# seeing it run and scancel reaching it: then the whole array succeeded, and the case is tried
# again on a fresh output (at most 3 times).
for attempt in 1 2 3; do
  rm -rf cancel.csv cancel.csv.parts cancel.details.csv
  "$BINPICK" detect "${detect_args[@]}" --out cancel.csv --slurm --tasks 4 > cancel.out 2> cancel.err &
  follower=$!
  job=""
  for _ in $(seq 100); do
    job=$(sed -n 's/^job \([0-9]*\);.*/\1/p' cancel.out)
    [ -n "$job" ] && break
    sleep 0.1
  done
  [ -n "$job" ] || fail "detect --slurm printed no job id: $(cat cancel.out cancel.err)"
  task=""
  for _ in $(seq 300); do
    task=$(squeue -h -r -j "$job" -t RUNNING -o %K 2>/dev/null | head -n 1)
    [ -n "$task" ] && break
    sleep 0.05
  done
  [ -n "$task" ] || fail "no task of job $job was seen running"
  scancel "${job}_${task}"
  shard="$((task + 1))/4"
  status=0
  wait $follower || status=$?
  if [ $status -eq 0 ]; then
    echo "detect: task $task finished before scancel reached it (attempt $attempt)"
    continue
  fi
  break
done
[ $status -eq 2 ] || fail "a task killed while running: exit $status, expected 2: $(cat cancel.err)"
grep -q "shards $shard ended without their work" cancel.err \
  || fail "no message naming only shard $shard (task $task killed while running): $(cat cancel.err)"
[ ! -e cancel.csv ] || fail "cancel.csv merged without shard $shard"
"$BINPICK" detect "${detect_args[@]}" --out cancel.csv --slurm --tasks 4 > rerun.out \
  || fail "the rerun failed: $(cat rerun.out)"
grep -q "submitting shards $shard as" rerun.out || fail "the rerun did not submit only shard $shard: $(cat rerun.out)"
[ "$(without_time single.csv)" = "$(without_time cancel.csv)" ] || fail "detect: cancel.csv differs after the rerun"
echo "detect: task $task killed while running; its shard $shard alone was resubmitted and completed the results (${SECONDS} s)"
# The follower interrupted while its array runs: the same command follows that array again.
"$BINPICK" detect "${detect_args[@]}" --out follow.csv --slurm --tasks 4 > follow.out 2>&1 &
follower=$!
for _ in $(seq 100); do grep -q "^job " follow.out && break; sleep 0.1; done
kill $follower
wait $follower || true
"$BINPICK" detect "${detect_args[@]}" --out follow.csv --slurm --tasks 4 > refollow.out \
  || fail "following the earlier array failed: $(cat refollow.out)"
grep -q "still in the queue: following it" refollow.out \
  || fail "the rerun did not follow the running array: $(cat refollow.out)"
[ "$(without_time single.csv)" = "$(without_time follow.csv)" ] || fail "detect: follow.csv differs"
echo "detect: an interrupted follower's array was followed again, not resubmitted (${SECONDS} s)"

# The whole experiment as a 2-task array: the report of a single process, timing and paths aside.
run_args=(--model builtin:bracket --bins 3 --objects 8 --width 480 --height 270 --hypotheses 3
          --noise 0,0.02 --pictures 1)
"$BINPICK" run "${run_args[@]}" --out run_single >/dev/null
"$BINPICK" run "${run_args[@]}" --out run_array --slurm --tasks 2 > run.out \
  || fail "run --slurm: $(cat run.out)"
comparable() { grep -v -E '"(dataset|results|ms_per_hypothesis)":' "$1"; }
[ "$(comparable run_single/report/report.json)" = "$(comparable run_array/report/report.json)" ] \
  || fail "run: report.json differs from the single process's"
echo "run: a 2-task array wrote the single process's report.json (${SECONDS} s)"

# Tuning: one round's candidates (the start and 2 values) as a 2-task array.
tune_args=(--model builtin:bracket --bins 1 --objects 8 --width 480 --height 270 --hypotheses 3
           --rounds 1 --max-evals 3 --budget-ms 100000)
"$BINPICK" tune "${tune_args[@]}" --out tune_single >/dev/null
"$BINPICK" tune "${tune_args[@]}" --out tune_array --slurm --tasks 2 > tune.out \
  || fail "tune --slurm: $(cat tune.out)"
grep -q "^3 points to measure" tune.out || fail "tune --slurm did not measure 3 points in one array: $(cat tune.out)"
[ "$(grep -c "^submitting shards" tune.out)" = 1 ] || fail "tune --slurm submitted more than one array: $(cat tune.out)"
measured() { cut -d, -f1-13 "$1"; }  # without ms_per_hypothesis, within_budget, best
[ "$(measured tune_single/tune.csv)" = "$(measured tune_array/tune.csv)" ] \
  || fail "tune: the array's tune.csv differs: $(cat tune_single/tune.csv tune_array/tune.csv)"
best_row() { awk -F, '$16 == 1 { print $1 }' "$1"; }
precisions() { awk -F, -v row="$2" '$1 == row { print $10, $11, $12, $13 }' "$1"; }
if [ "$(best_row tune_single/tune.csv)" = "$(best_row tune_array/tune.csv)" ]; then
  cmp -s tune_single/best.json tune_array/best.json || fail "tune: best.json differs"
else
  # Points equal in every precision are told apart by their measured time alone.
  [ "$(precisions tune_single/tune.csv "$(best_row tune_single/tune.csv)")" = \
    "$(precisions tune_array/tune.csv "$(best_row tune_array/tune.csv)")" ] \
    || fail "tune: a different best point, not a tie in precision"
fi
"$BINPICK" tune "${tune_args[@]}" --out tune_array --slurm --tasks 2 > tune_again.out \
  || fail "tune --slurm again: $(cat tune_again.out)"
! grep -q "^submitting" tune_again.out || fail "tune --slurm again submitted work: $(cat tune_again.out)"
echo "tune: a round as a 2-task array measured the single process's points (${SECONDS} s)"
echo "PASS"
