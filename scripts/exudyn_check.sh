#!/usr/bin/env bash
# Joints in 3-D against Exudyn, an independent multibody code (issue 25 items
# 5 and 7): the spatial linkage G and the driven crank-slider F, mbexpr's
# error against run time beside Exudyn's fixed-step runs; the table into
# target/exudyn_check/section.md (scripts/exudyn_check.py says how each
# figure is made).
#
# Installs what it needs itself: a Python virtual environment with exudyn
# and numpy (target/exudyn_check/venv). Takes a minute or two.
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/exudyn_check
mkdir -p "$out"
if [ ! -x "$out/venv/bin/python" ]; then
    echo "creating $out/venv with exudyn and numpy" >&2
    python3 -m venv "$out/venv"
    "$out/venv/bin/pip" install -q exudyn numpy
fi
if [ -z "${MBEXPR:-}" ]; then
    echo "building mbexpr (release)" >&2
    nice cargo build --release --quiet --bin mbexpr
fi
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
"$out/venv/bin/python" -W ignore::DeprecationWarning scripts/exudyn_check.py
