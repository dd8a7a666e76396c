#!/usr/bin/env bash
# A real Slurm cluster for `--slurm`: brings up a private single-node cluster (munged, slurmctld,
# slurmd from Debian, no systemd; its own config, ports, munge socket and state under a temporary
# directory, so it touches nothing of the machine's), then
#   - a 2-task synth array makes the dataset a single process makes (scene_gt.json, depth PNGs),
#   - a 4-task detect array gives the single process's results CSV (time column aside),
#   - a detect array with one task cancelled fails naming that shard; the same command again
#     resubmits only it and then gives the same CSV,
#   - a rerun while the array of an interrupted follower still runs follows it, not resubmits,
#   - a 2-task run array writes the single process's report.json (paths and timing aside),
# and stops the daemons by their pid files.
# usage: slurm_cluster_test.sh BINPICK      (exit 77: skipped, with the reason on stdout)
#        slurm_cluster_test.sh --check      (says whether it would run or skip, exits 0)
set -euo pipefail

PACKAGES=(slurmctld slurmd slurm-client munge)

missing_packages() {
  local p
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}

# Prints why the test cannot run here; nothing if it can.
skip_reason() {
  local missing
  missing=$(missing_packages | tr '\n' ' ')
  if [ "$(id -u)" -ne 0 ]; then
    echo "not root (slurmd runs jobs as root here)${missing:+, and $missing not installed}"
  elif [ -n "$missing" ] && ! command -v apt-get >/dev/null; then
    echo "$missing not installed and no apt-get"
  fi
}

if [ "${1:-}" = "--check" ]; then
  reason=$(skip_reason)
  if [ -n "$reason" ]; then
    echo "cluster test (slurm_cluster): SKIPPED: $reason"
  else
    echo "cluster test (slurm_cluster): runs a private single-node Slurm cluster"
  fi
  exit 0
fi

BINPICK=$(readlink -f "${1:?usage: slurm_cluster_test.sh BINPICK}")
reason=$(skip_reason)
if [ -n "$reason" ]; then
  echo "SKIPPED: the Slurm cluster test needs root and Debian's ${PACKAGES[*]}: $reason"
  exit 77
fi
missing=$(missing_packages)
if [ -n "$missing" ]; then
  echo "installing" $missing
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

DIR=$(mktemp -d /tmp/binpick_slurm.XXXXXX)
chmod 0755 "$DIR"  # munged refuses a socket directory others cannot search
export SLURM_CONF=$DIR/slurm.conf
export BINPICK_QUIET=1
fail() { echo "FAIL: $*"; exit 1; }

stop_daemons() {
  local name pid
  for name in slurmd slurmctld munged; do
    [ -f "$DIR/$name.pid" ] || continue
    pid=$(cat "$DIR/$name.pid")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  done
}
cleanup() {
  local status=$?
  stop_daemons
  if [ $status -ne 0 ] && [ $status -ne 77 ]; then
    echo "--- logs ($DIR)"
    tail -n 20 "$DIR"/*.log "$DIR"/work/*.out 2>/dev/null || true
  fi
  rm -rf "$DIR"
}
trap cleanup EXIT

# ---- the cluster ---------------------------------------------------------------------------------
mkdir -p "$DIR/munge" "$DIR/state" "$DIR/spool" "$DIR/work"
chmod 0755 "$DIR/munge"
dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none
chmod 0600 "$DIR/munge/munge.key"
munged --socket="$DIR/munge/munge.socket" --key-file="$DIR/munge/munge.key" \
  --pid-file="$DIR/munged.pid" --log-file="$DIR/munged.log" --seed-file="$DIR/munge/seed" \
  --force

host=$(hostname -s)
# Ports from the process id, so two runs (or a real cluster) on one machine do not collide.
port=$((20000 + ($$ % 20000)))
memory=$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
cat > "$SLURM_CONF" <<CONF
ClusterName=binpicktest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$DIR/munge/munge.socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$memory State=UNKNOWN
PartitionName=binpick Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -i
slurmd
for _ in $(seq 100); do
  state=$(sinfo -h -o %T 2>/dev/null || true)
  case "$state" in idle*|mixed*|allocated*) break ;; esac
  sleep 0.2
done
case "$state" in idle*|mixed*|allocated*) ;; *) fail "the node did not come up (state '$state')" ;; esac
echo "cluster up: node $host, $(nproc) CPUs, ${SECONDS} s"

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

# One task cancelled: the last (pending while the first ones hold both CPUs, or running).
"$BINPICK" detect "${detect_args[@]}" --out cancel.csv --slurm --tasks 4 > cancel.out 2> cancel.err &
follower=$!
job=""
for _ in $(seq 100); do
  job=$(sed -n 's/^job \([0-9]*\);.*/\1/p' cancel.out)
  [ -n "$job" ] && break
  sleep 0.1
done
[ -n "$job" ] || fail "detect --slurm printed no job id: $(cat cancel.out cancel.err)"
scancel "${job}_3"
status=0
wait $follower || status=$?
[ $status -eq 2 ] || fail "a cancelled task: exit $status, expected 2: $(cat cancel.err)"
grep -q "shards 4/4 ended without their work" cancel.err || fail "no message naming shard 4/4: $(cat cancel.err)"
[ ! -e cancel.csv ] || fail "cancel.csv merged without shard 4/4"
"$BINPICK" detect "${detect_args[@]}" --out cancel.csv --slurm --tasks 4 > rerun.out \
  || fail "the rerun failed: $(cat rerun.out)"
grep -q "submitting shards 4/4 as" rerun.out || fail "the rerun did not submit only shard 4/4: $(cat rerun.out)"
[ "$(without_time single.csv)" = "$(without_time cancel.csv)" ] || fail "detect: cancel.csv differs after the rerun"
echo "detect: a cancelled task's shard alone was resubmitted and completed the results (${SECONDS} s)"
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
echo "PASS"
