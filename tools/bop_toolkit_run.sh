#!/usr/bin/env bash
# Runs the BOP toolkit's own scripts (github.com/thodan/bop_toolkit, not vendored) on `binpick run`
# output and compares their numbers with binpick's (docs/parameters.md, "BOP's scores, next to the paper's"):
#   scripts/check_results_bop19.py  on every results CSV;
#   scripts/eval_bop19_pose.py      VSD (the toolkit's vispy renderer), MSSD, MSPD;
#   scripts/calc_gt_info.py         on a copy of every dataset, against binpick's scene_gt_info.json.
#
#   tools/bop_toolkit_run.sh --toolkit DIR --python PY --work DIR [--binpick BIN]
#                            [--models "shaft bracket bolt"] [--steps data,check,eval,gtinfo,compare]
#
# --toolkit: a checkout (the directory holding bop_toolkit_lib/ and scripts/); it is copied into
#   WORK/toolkit and only the copy is changed: the datasets' registration
#   (tools/bop_toolkit_register.py), nothing else.
# --python: an interpreter with the toolkit's requirements (numpy, scipy, imageio, vispy,
#   PyOpenGL...). Without a display, vispy renders through EGL: EGL_PLATFORM=surfaceless (set
#   here) and Mesa's EGL (libegl-mesa0).
# Steps (default all): data (binpick run: 2 bins of 60 parts, noise 0 and 0.02, seed 3, then
# detect --instances 20 and 60 and eval), check, eval (about 3 min a results file on 2 idle
# cores, 18 files), gtinfo (a minute a dataset), compare (tools/bop_toolkit_compare.py: tables
# on stdout and WORK/compare.json; what was not run is left out).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
toolkit="" py="" work="" bin="$here/../build/binpick" models="shaft bracket bolt" steps=data,check,eval,gtinfo,compare
while [[ $# -gt 0 ]]; do
  case $1 in
    --toolkit) toolkit=$2; shift 2;;
    --python) py=$2; shift 2;;
    --work) work=$2; shift 2;;
    --binpick) bin=$2; shift 2;;
    --models) models=$2; shift 2;;
    --steps) steps=$2; shift 2;;
    -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0;;
    *) echo "bop_toolkit_run.sh: unknown argument $1 (--help)" >&2; exit 2;;
  esac
done
[[ -n $toolkit && -n $py && -n $work ]] || { echo "bop_toolkit_run.sh: --toolkit, --python and --work are needed (--help)" >&2; exit 2; }
[[ -d $toolkit/bop_toolkit_lib && -f $toolkit/scripts/eval_bop19_pose.py ]] ||
  { echo "bop_toolkit_run.sh: $toolkit is not a bop_toolkit checkout (no bop_toolkit_lib/, scripts/)" >&2; exit 2; }
[[ -x $bin ]] || { echo "bop_toolkit_run.sh: no binpick at $bin (--binpick)" >&2; exit 2; }
mkdir -p "$work"
work=$(cd "$work" && pwd) py=$(command -v "$py") bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
step() { [[ ,$steps, == *,$1,* ]]; }
noises="000 002"
level() { case $1 in 000) echo 0.00;; 002) echo 0.02;; esac; }

if step data; then
  for m in $models; do
    echo "== binpick run $m"
    "$bin" run --model builtin:$m --bins 2 --objects 60 --noise 0,0.02 --out "$work/run-$m" --seed 3 \
      > "$work/run-$m.log" 2>&1 || { tail "$work/run-$m.log"; exit 1; }
    for k in 20 60; do
      mkdir -p "$work/run-$m/results-i$k"
      for n in $noises; do
        "$bin" detect --model "$work/run-$m/model.ppfm" --dataset "$work/run-$m/noise_$(level $n)" \
          --instances $k --out "$work/run-$m/results-i$k/binpick_noise$n-test.csv" \
          > "$work/run-$m/results-i$k/detect_noise$n.log" 2>&1
      done
      "$bin" eval --dataset "$work/run-$m/noise_0.00" --results "$work/run-$m/results-i$k/binpick_noise000-test.csv" \
        --dataset "$work/run-$m/noise_0.02" --results "$work/run-$m/results-i$k/binpick_noise002-test.csv" \
        --out "$work/run-$m/report-i$k" --pictures 0 > "$work/run-$m/report-i$k.log" 2>&1
    done
  done
fi

if step check || step eval || step gtinfo; then
  # The datasets (OUT/bop/noiseDDD of every model) share names: one registration serves all.
  rm -rf "$work/toolkit" && cp -r "$toolkit" "$work/toolkit"
  size=$(python3 -c "import json,sys; c=json.load(open(sys.argv[1])); print('%d,%d' % (c['width'], c['height']))" \
         "$(ls -d "$work"/run-*/noise_0.00 | head -1)/camera.json")
  "$py" "$here/bop_toolkit_register.py" "$work/toolkit" noise000,noise002 --scenes 2 --size "$size"
  export PYTHONPATH=$work/toolkit EGL_PLATFORM=surfaceless
  # The toolkit's scripts start "python" subprocesses: the interpreter given comes first.
  export PATH=$(dirname "$py"):$PATH
  cd "$work/toolkit"
  for m in $models; do
    for s in results results-i20 results-i60; do
      for n in $noises; do
        f=binpick_noise$n-test.csv
        if step check; then
          echo "== check_results_bop19 $m $s $f"
          BOP_RESULTS_PATH=$work/run-$m/$s "$py" scripts/check_results_bop19.py --result_filenames=$f 2>&1 |
            tee "$work/run-$m/$s/check_results_noise$n.log" | grep "Check msg"
        fi
        step eval || continue
        e=$work/eval/$m/$s
        mkdir -p "$e"
        echo "== eval_bop19_pose $m $s $f"
        BOP_PATH=$work/run-$m/bop BOP_RESULTS_PATH=$work/run-$m/$s BOP_EVAL_PATH=$e \
          "$py" scripts/eval_bop19_pose.py --renderer_type=vispy --results_path="$work/run-$m/$s" \
          --eval_path="$e" --num_workers=1 --result_filenames=$f > "$e/log_noise$n.txt" 2>&1 ||
          { echo "eval_bop19_pose failed: $e/log_noise$n.txt" >&2; exit 1; }
      done
    done
    for n in $noises; do
      step gtinfo || continue
      g=$work/gtinfo/$m
      rm -rf "$g/noise$n" && mkdir -p "$g"
      cp -rL "$work/run-$m/bop/noise$n" "$g/noise$n"  # a copy: calc_gt_info.py overwrites scene_gt_info.json
      echo "== calc_gt_info $m noise$n"
      BOP_PATH=$g "$py" scripts/calc_gt_info_noise$n.py > "$g/calc_gt_info_noise$n.log" 2>&1 ||
        { echo "calc_gt_info failed: $g/calc_gt_info_noise$n.log" >&2; exit 1; }
    done
  done
fi

if step compare; then
  "$py" "$here/bop_toolkit_compare.py" "$work"
fi
