#!/usr/bin/env bash
# binpick's entry point: ./run.sh demo | test [--sanitize] | bench | fuzz [SECONDS | --runs N]
# Each command installs the Debian packages it needs (only the missing ones), configures and
# builds Release into build/, then does its job.
set -euo pipefail
cd "$(dirname "$0")"

BUILD_PACKAGES=(
  cmake g++ make pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  mesa-vulkan-drivers libvulkan-dev vulkan-tools vulkan-validationlayers glslang-tools
  libbullet-dev libbullet-extras-dev libeigen3-dev libtinygltf-dev nlohmann-json3-dev
  libtinyobjloader-dev libcli11-dev libspdlog-dev libpng-dev libmeshoptimizer-dev libgtest-dev
  libbenchmark-dev
  gnuplot-nox fonts-dejavu-core
  python3-dev pybind11-dev python3-numpy python3-pytest python3-venv python3-matplotlib
)
BENCH_PACKAGES=(libopencv-contrib-dev)
FUZZ_PACKAGES=(clang)  # libFuzzer and its sanitizers come with Debian's clang

usage() {
  cat <<TXT
usage: ./run.sh demo | test [--sanitize] | bench | fuzz [SECONDS | --runs N]
  demo   build, then run 'binpick demo' (the whole loop on a built-in part)
  test   build, then run the test suite with ctest; --sanitize: build with AddressSanitizer
         and UndefinedBehaviorSanitizer into build-sanitize/ and run the suite there
  bench  build (with OpenCV for the comparison), then run the benchmarks:
         build/bench/bench.md and bench.json; extra arguments go to 'binpick bench';
         then bench/throughput.sh: build/bench/throughput.md
  fuzz   build the libFuzzer targets with clang into build-fuzz/ and run each for SECONDS
         (default 60) from its seed corpus fuzz/corpus/NAME, FUZZ_JOBS (default: the cores) at
         a time; prints CPU seconds per target and in total; fails if any input crashes.
         --runs N: each target replays its corpus and regressions, then tries N inputs mutated
         from them with a fixed seed, from a fresh work directory (what CI runs)
TXT
}

missing_packages() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}

install_packages() {
  local missing
  missing=$(missing_packages "$@")
  [ -z "$missing" ] && return 0
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "run.sh: installing Debian packages:" $missing
  $sudo apt-get update -qq
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $missing >/dev/null
}

build() {
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build build -j"$(nproc)"
}

cmd=${1:-}
case "$cmd" in
  demo)
    install_packages "${BUILD_PACKAGES[@]}"
    build
    shift
    exec build/binpick demo "$@"
    ;;
  test)
    install_packages "${BUILD_PACKAGES[@]}"
    if [ "${2:-}" = "--sanitize" ]; then
      # Debug info and -O1 keep the sanitized suite's reports readable and its run time bearable.
      cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBINPICK_SANITIZE=ON >/dev/null
      cmake --build build-sanitize -j"$(nproc)"
      ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} \
        ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)"
    elif [ -n "${2:-}" ]; then
      usage >&2; exit 2
    else
      build
      tests/cluster/slurm_cluster_test.sh --check  # says plainly whether the cluster test runs
      ctest --test-dir build --output-on-failure -j"$(nproc)"
    fi
    ;;
  bench)
    install_packages "${BUILD_PACKAGES[@]}" "${BENCH_PACKAGES[@]}"
    build
    shift
    mkdir -p build/bench/micro
    # The report a user reads: build/bench/bench.md and bench.json (binpick bench --help).
    build/binpick bench --out build/bench "$@"
    # Batch throughput: one process, two shards at once, a 2-task Slurm array (build/bench/throughput.md).
    bench/throughput.sh build/binpick build/bench 3
    # Micro-benchmarks of single stages (Google Benchmark), medians of 5 repetitions.
    for b in build/bench_*; do
      [ -x "$b" ] || continue
      name=$(basename "$b")
      echo "== $name"
      "$b" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
           --benchmark_out="build/bench/micro/$name.json" --benchmark_out_format=json
    done
    echo "run.sh: report in build/bench/bench.md (and bench.json), build/bench/throughput.md; micro-benchmarks in build/bench/micro/"
    ;;
  fuzz)
    # A time budget per target (SECONDS) or, with --runs N, a fixed number of mutated inputs
    # after the corpus replay, from a fresh work directory and a fixed seed: the same inputs
    # every time (CI).
    limit=()
    fresh=0
    if [ "${2:-}" = "--runs" ]; then
      runs=${3:-}
      [[ "$runs" =~ ^[0-9]+$ ]] || { echo "run.sh fuzz: --runs needs a whole number" >&2; exit 2; }
      limit=(-runs="$runs" -seed=1)
      fresh=1
      label="$runs runs"
    else
      seconds=${2:-60}
      [[ "$seconds" =~ ^[1-9][0-9]*$ ]] || { echo "run.sh fuzz: SECONDS must be a positive integer" >&2; exit 2; }
      limit=(-max_total_time="$seconds")
      label="${seconds} s"
    fi
    jobs=${FUZZ_JOBS:-$(nproc)}
    [[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "run.sh fuzz: FUZZ_JOBS must be a positive integer" >&2; exit 2; }
    install_packages "${BUILD_PACKAGES[@]}" "${FUZZ_PACKAGES[@]}"
    cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBINPICK_FUZZ=ON \
          -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ >/dev/null
    targets=$(cd fuzz && ls fuzz_*.cpp | sed 's/\.cpp$//')
    # shellcheck disable=SC2086
    cmake --build build-fuzz -j"$(nproc)" --target $targets
    mkdir -p build-fuzz/logs
    # One target: its log, its CPU seconds (user + system: what "an hour of fuzzing" means on a
    # shared machine) and its exit status in build-fuzz/logs/NAME.{log,cpu,status}.
    fuzz_one() {
      local target=$1 name=${1#fuzz_}
      local work=build-fuzz/corpus-work/$name crashes=build-fuzz/crashes/$name
      local log=build-fuzz/logs/$name.log
      [ "$fresh" = 1 ] && rm -rf "$work"
      mkdir -p "$work" "$crashes"
      local corpora=("$work" "fuzz/corpus/$name")  # new inputs go to work, not the repository
      [ -d "fuzz/regressions/$name" ] && corpora+=("fuzz/regressions/$name")
      # A leak, a hang (-timeout, seconds per input) or an allocation over 2 GB is a crash too.
      local TIMEFORMAT='%3U %3S'
      { time { status=0; "build-fuzz/$target" "${limit[@]}" \
        -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$crashes/" \
        "${corpora[@]}" >"$log" 2>&1 || status=$?; echo "$status" >"$log.status"; }; } 2>"$log.cpu"
    }
    # FUZZ_JOBS targets at a time (default: one per core).
    running=0
    for target in $targets; do
      echo "== $target: $label"
      fuzz_one "$target" &
      running=$((running + 1))
      if [ "$running" -ge "$jobs" ]; then wait -n; running=$((running - 1)); fi
    done
    wait
    failed=()
    summary=""
    cpu_total=0
    for target in $targets; do
      name=${target#fuzz_}
      log=build-fuzz/logs/$name.log
      status=$(cat "$log.status")
      cpu=$(awk '{printf "%.0f", $1 + $2}' "$log.cpu")
      cpu_total=$((cpu_total + cpu))
      # A target that crashed on its first inputs printed no coverage line: say "?" rather than
      # let the failed grep end the script before it names the crash.
      runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1 || true)
      cov=$(grep -Eo 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
      if [ "$status" -ne 0 ]; then
        failed+=("$name")
        echo "   $name: CRASH (exit $status); log: $log; input: $(ls "build-fuzz/crashes/$name" | head -1)"
        grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error)' "$log" | head -3 | sed 's/^/   /' || true
      fi
      summary+=$(printf '%-15s %12s executions %6s CPU s  %s\n' "$name" "${runs:-?}" "$cpu" "${cov:-cov: ?}")$'\n'
    done
    echo "== per target: executions, CPU seconds, coverage (libFuzzer cov: edges, ft: features)"
    printf '%s' "$summary"
    echo "== total: ${cpu_total} CPU s of fuzzing"
    if [ "${#failed[@]}" -gt 0 ]; then
      echo "run.sh fuzz: crashes in: ${failed[*]} (inputs in build-fuzz/crashes/NAME/)" >&2
      exit 1
    fi
    ;;
  -h|--help|help) usage ;;
  *) usage >&2; exit 2 ;;
esac
