#!/usr/bin/env bash
# Builds the Python package (python/) as a user would, `pip install
# ./python` in a fresh virtual environment (maturin fetched by pip's build
# isolation), and runs its pytest suite. Called by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."

venv=target/python-venv
if ! python3 -m venv --help >/dev/null 2>&1 || ! python3 -c 'import ensurepip' 2>/dev/null; then
  apt-get update -qq && apt-get install -y -qq python3-venv >/dev/null
fi
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/pip" install -q --upgrade pip
"$venv/bin/pip" install -q maturin pytest numpy "dask[distributed]"
"$venv/bin/pip" install -q ./python

# pytest exits 5 when it collects no test: that is a broken suite here,
# never a pass.
status=0
"$venv/bin/python" -m pytest -q python/tests || status=$?
if [ "$status" -eq 5 ]; then
  echo "error: pytest collected no tests from python/tests" >&2
  exit 1
fi
exit "$status"
