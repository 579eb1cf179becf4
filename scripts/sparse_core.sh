#!/usr/bin/env bash
# The sparse-core benchmark (issue 24): the stack of N balls and the chain of
# free balls in mbexpr simulate (both methods), and the stack as DIFFs in
# mbexpr beside scipy's BDF and Radau with jac_sparsity. Prints markdown
# tables for BENCHMARKS.md; one run per configuration (about 10 minutes).
#
#   scripts/sparse_core.sh [MAIN_MBEXPR]   with a binary built from main,
#                                          also its "before" rows (N = 8, 16)
#
# Installs scipy itself in a virtual environment (target/sparse_core/venv).
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/sparse_core
mkdir -p "$out"
if [ ! -x "$out/venv/bin/python" ]; then
    echo "creating $out/venv with scipy" >&2
    python3 -m venv "$out/venv"
    "$out/venv/bin/pip" install -q scipy
fi
nice cargo build --release --quiet --bin mbexpr
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
"$out/venv/bin/python" scripts/sparse_core.py target/release/mbexpr "$@"
