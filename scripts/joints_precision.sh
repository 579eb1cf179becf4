#!/usr/bin/env bash
# Andrews' squeezing mechanism, error against run time (issue 25 item 7):
# mbexpr simulate (auto, radau, dop853) on examples/simulate/d_andrews.adm
# beside scipy's Radau, BDF and DOP853 on the index-1 form of the test set's
# own equations, rtol 1e-4 .. 1e-11; the table into
# target/joints_precision/section.md (scripts/joints_precision.py says how
# each figure is made).
#
# Installs what it needs itself: a Python virtual environment with scipy
# and sympy (target/joints_precision/venv). Takes a few minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/joints_precision
mkdir -p "$out"
if [ ! -x "$out/venv/bin/python" ]; then
    echo "creating $out/venv with scipy and sympy" >&2
    python3 -m venv "$out/venv"
    "$out/venv/bin/pip" install -q scipy sympy
fi
echo "building mbexpr (release)" >&2
nice cargo build --release --quiet --bin mbexpr
# One core: no threaded BLAS under scipy.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
"$out/venv/bin/python" scripts/joints_precision.py
