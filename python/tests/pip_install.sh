#!/bin/sh
# README's `pip install .` (pyproject.toml): a fresh virtual environment that sees Debian's numpy,
# the wheel built from SOURCE by scikit-build-core (from PyPI), then the installed module imported
# and used from another directory. Exit 77 (ctest: skipped) when PyPI cannot be reached.
set -eu
source_dir=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
/usr/bin/python3 -m venv --system-site-packages "$work/venv"
if ! "$work/venv/bin/pip" download -q --no-deps -d "$work/probe" scikit-build-core >/dev/null 2>&1; then
  echo "PyPI is not reachable: pip install . not tried"
  exit 77
fi
"$work/venv/bin/pip" install -q "$source_dir"
cd "$work"
"$work/venv/bin/python" - <<'PY'
import binpick, numpy as np
model = binpick.Model.train("builtin:bolt")
assert 40 < model.diameter < 70, model.diameter
assert binpick.__file__.startswith(__import__("sys").prefix), binpick.__file__
print("installed:", binpick.__file__)
PY
