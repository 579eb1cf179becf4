#!/usr/bin/env bash
# An independent reference for a ball between two BISTOP walls (issue 22):
# see scripts/ball_reference.py. Installs scipy in its own virtual
# environment (target/ball_reference/venv) the first time.
#
#   scripts/ball_reference.sh X1 X2 K E CMAX D X0 V0 END STEPS > ref.csv
#   scripts/ball_reference.sh -0.7 0.9 3e5 1.3 80 0.02 0.1 -4 8 199   # the variant of BENCHMARKS.md
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/ball_reference/venv
if [ ! -x "$venv/bin/python" ]; then
    echo "creating $venv with scipy" >&2
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q scipy
fi
exec "$venv/bin/python" scripts/ball_reference.py "$@"
