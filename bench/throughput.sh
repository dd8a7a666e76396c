#!/usr/bin/env bash
# Throughput of the batch verbs on this machine, three ways:
#   one process        the verb as it is (PoCL already spreads each kernel over every core),
#   two processes      --shard 1/2 and --shard 2/2 at once (the whole machine, by hand),
#   2-task Slurm array --slurm --tasks 2 (submission, following and merge included), on the
#                      cluster sbatch reaches, or else a private single-node cluster when root
#                      with Debian's slurm packages (tests/cluster/private_cluster.sh); skipped
#                      otherwise, and said so.
# synth in bins per hour, detect in images per second (one image per bin), medians of RUNS runs,
# each from scratch. Sizes from the environment: BINS (8), OBJECTS (100), WIDTH (1600), HEIGHT (900).
# usage: bench/throughput.sh BINPICK OUT [RUNS]   writes OUT/throughput.md (and prints it)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
given=$(readlink -f "${1:?usage: throughput.sh BINPICK OUT [RUNS]}")
OUT=${2:?usage: throughput.sh BINPICK OUT [RUNS]}
RUNS=${3:-3}
BINS=${BINS:-8} OBJECTS=${OBJECTS:-100} WIDTH=${WIDTH:-1600} HEIGHT=${HEIGHT:-900}
mkdir -p "$OUT"
OUT=$(readlink -f "$OUT")
WORK=$OUT/throughput
rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK"
# A copy: a rebuild during the runs must not change or remove the binary being measured.
cp "$given" "$WORK/binpick"
BINPICK=$WORK/binpick
export BINPICK_QUIET=1

synth_args=(--model builtin:bracket --bins "$BINS" --objects "$OBJECTS" --width "$WIDTH"
            --height "$HEIGHT" --no-cloud --cache-dir "$WORK/cache")
detect_args=(--model "$WORK/bracket.ppfm" --dataset "$WORK/dataset" --hypotheses 5)

now() { date +%s.%N; }
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# Seconds of one run of "$@" (a mode and a verb); the outputs are removed first.
timed() {
  local start
  rm -rf synth_out detect_out.* detect_out.csv*
  start=$(now)
  "$@" >/dev/null || { echo "throughput: $* failed" >&2; return 1; }
  awk -v a="$start" -v b="$(now)" 'BEGIN { printf "%.3f\n", b - a }'
}
# The median seconds of RUNS runs of "$@"; exits if one fails.
median_of_runs() {
  local times="" t
  for _ in $(seq "$RUNS"); do
    t=$(timed "$@") || exit 1
    times+="$t"$'\n'
  done
  printf '%s' "$times" | median
}
one() {
  case $1 in
    synth) "$BINPICK" synth "${synth_args[@]}" --out synth_out ;;
    detect) "$BINPICK" detect "${detect_args[@]}" --out detect_out.csv ;;
  esac
}
two() {
  local k pids=()
  for k in 1 2; do
    case $1 in
      synth) "$BINPICK" synth "${synth_args[@]}" --out synth_out --shard "$k/2" & ;;
      detect) "$BINPICK" detect "${detect_args[@]}" --out detect_out.csv --shard "$k/2" & ;;
    esac
    pids+=($!)
  done
  local status=0
  for k in "${pids[@]}"; do wait "$k" || status=1; done
  return $status
}
array() {
  case $1 in
    synth) "$BINPICK" synth "${synth_args[@]}" --out synth_out --slurm --tasks 2 ;;
    detect) "$BINPICK" detect "${detect_args[@]}" --out detect_out.csv --slurm --tasks 2 ;;
  esac
}

# A Slurm cluster: the one sbatch reaches, else a private one.
cluster=""
if command -v sbatch >/dev/null && sinfo -h >/dev/null 2>&1; then
  cluster="the cluster sbatch reaches"
else
  # shellcheck source=../tests/cluster/private_cluster.sh
  . "$here/../tests/cluster/private_cluster.sh"
  reason=$(private_cluster_skip_reason)
  if [ -z "$reason" ]; then
    private_cluster_install
    CLUSTER_DIR=$(mktemp -d /tmp/binpick_bench_slurm.XXXXXX)
    trap 'private_cluster_stop "$CLUSTER_DIR"; rm -rf "$CLUSTER_DIR"' EXIT
    private_cluster_start "$CLUSTER_DIR" && cluster="a private single-node cluster"
  else
    echo "throughput: no Slurm array measured: $reason"
  fi
fi

echo "throughput: $BINS bins of $OBJECTS parts at ${WIDTH}x$HEIGHT, medians of $RUNS runs"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
"$BINPICK" synth "${synth_args[@]}" --out dataset >/dev/null  # detect's input, untimed
"$BINPICK" train --model builtin:bracket --out bracket.ppfm >/dev/null

rows=""
for mode in one two array; do
  label=$(case $mode in one) echo "one process" ;; two) echo "2 processes (--shard 1/2, 2/2)" ;;
                         array) echo "2-task Slurm array" ;; esac)
  if [ "$mode" = array ] && [ -z "$cluster" ]; then
    rows+="| $label | not measured: no Slurm cluster | |"$'\n'
    continue
  fi
  synth_s=$(median_of_runs "$mode" synth) || exit 1
  detect_s=$(median_of_runs "$mode" detect) || exit 1
  row=$(awk -v b="$BINS" -v s="$synth_s" -v d="$detect_s" -v l="$label" \
    'BEGIN { printf "| %s | %.0f (%.1f s) | %.2f (%.1f s) |", l, b * 3600 / s, s, b / d, d }')
  echo "$row"
  rows+="$row"$'\n'
done

{
  echo "# Throughput"
  echo
  echo "$BINS bins of $OBJECTS parts (builtin:bracket) at ${WIDTH}x$HEIGHT; detect with 5 hypotheses"
  echo "per image; medians of $RUNS runs from scratch; $(nproc) CPUs${cluster:+; Slurm: $cluster}."
  echo "Load average (1, 5, 15 min) before: $load_before; after: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "(other work on the machine takes cores from every mode alike)."
  echo
  echo "| mode | synth: bins per hour (run) | detect: images per second (run) |"
  echo "|---|---|---|"
  printf '%s' "$rows"
} > "$OUT/throughput.md"
echo "throughput: $OUT/throughput.md"
