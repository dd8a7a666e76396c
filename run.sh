#!/usr/bin/env bash
# binpick's entry point: ./run.sh demo | test | bench
# Each command installs the Debian packages it needs (only the missing ones), configures and
# builds Release into build/, then does its job.
set -euo pipefail
cd "$(dirname "$0")"

BUILD_PACKAGES=(
  cmake g++ make pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers clinfo
  mesa-vulkan-drivers libvulkan-dev vulkan-tools vulkan-validationlayers glslang-tools
  libbullet-dev libbullet-extras-dev libeigen3-dev libtinygltf-dev nlohmann-json3-dev
  libtinyobjloader-dev libcli11-dev libspdlog-dev libpng-dev libgtest-dev libbenchmark-dev
  gnuplot-nox fonts-dejavu-core
)
BENCH_PACKAGES=(libopencv-contrib-dev)

usage() {
  cat <<TXT
usage: ./run.sh demo | test | bench
  demo   build, then run 'binpick demo' (the whole loop on a built-in part)
  test   build, then run the test suite with ctest
  bench  build (with OpenCV for the comparison), then run the benchmarks:
         build/bench/bench.md and bench.json; extra arguments go to 'binpick bench'
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
    build
    ctest --test-dir build --output-on-failure -j"$(nproc)"
    ;;
  bench)
    install_packages "${BUILD_PACKAGES[@]}" "${BENCH_PACKAGES[@]}"
    build
    shift
    mkdir -p build/bench/micro
    # The report a user reads: build/bench/bench.md and bench.json (binpick bench --help).
    build/binpick bench --out build/bench "$@"
    # Micro-benchmarks of single stages (Google Benchmark), medians of 5 repetitions.
    for b in build/bench_*; do
      [ -x "$b" ] || continue
      name=$(basename "$b")
      echo "== $name"
      "$b" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
           --benchmark_out="build/bench/micro/$name.json" --benchmark_out_format=json
    done
    echo "run.sh: report in build/bench/bench.md (and bench.json); micro-benchmarks in build/bench/micro/"
    ;;
  -h|--help|help) usage ;;
  *) usage >&2; exit 2 ;;
esac
