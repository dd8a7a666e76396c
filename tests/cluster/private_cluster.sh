# A private single-node Slurm cluster from Debian's munge, slurmctld and slurmd, without systemd:
# its own config, ports, munge socket and state under one directory, so it touches nothing of the
# machine's. Sourced by tests/cluster/slurm_cluster_test.sh and bench/throughput.sh.
#   private_cluster_skip_reason      why it cannot run here (nothing if it can)
#   private_cluster_install          installs the missing packages (root, apt-get)
#   private_cluster_start DIR        starts it in DIR (made 0755), exports SLURM_CONF; non-zero
#                                    with a message if the node does not come up
#   private_cluster_stop DIR         stops the daemons by their pid files

PRIVATE_CLUSTER_PACKAGES=(slurmctld slurmd slurm-client munge)

private_cluster_missing_packages() {
  local p
  for p in "${PRIVATE_CLUSTER_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}

private_cluster_skip_reason() {
  local missing
  missing=$(private_cluster_missing_packages | tr '\n' ' ')
  if [ "$(id -u)" -ne 0 ]; then
    echo "not root (slurmd runs jobs as root here)${missing:+, and $missing not installed}"
  elif [ -n "$missing" ] && ! command -v apt-get >/dev/null; then
    echo "$missing not installed and no apt-get"
  fi
}

private_cluster_install() {
  local missing
  missing=$(private_cluster_missing_packages)
  [ -z "$missing" ] && return 0
  echo "installing" $missing
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing >/dev/null
}

private_cluster_stop() {
  local dir=$1 name pid
  for name in slurmd slurmctld munged; do
    [ -f "$dir/$name.pid" ] || continue
    pid=$(cat "$dir/$name.pid")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  done
}

private_cluster_start() {
  local dir=$1 host port memory state=""
  chmod 0755 "$dir"  # munged refuses a socket directory others cannot search
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool"
  chmod 0755 "$dir/munge"
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chmod 0600 "$dir/munge/munge.key"
  munged --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed" \
    --force
  host=$(hostname -s)
  # Ports from the process id, so two runs (or a real cluster) on one machine do not collide.
  port=$((20000 + ($$ % 20000)))
  memory=$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
  export SLURM_CONF=$dir/slurm.conf
  cat > "$SLURM_CONF" <<CONF
ClusterName=binpicktest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
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
    case "$state" in idle*|mixed*|allocated*) return 0 ;; esac
    sleep 0.2
  done
  echo "the node did not come up (state '$state')"
  return 1
}
