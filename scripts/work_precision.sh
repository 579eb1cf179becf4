#!/usr/bin/env bash
# Work-precision report of the simulation study's five scenes (issue 16) and
# issue 22's variant ball:
# mbexpr simulate (radau, dop853), scipy's solve_ivp (RK45, DOP853, Radau,
# BDF, LSODA), SUNDIALS CVODE from C with hand-coded roots, and the
# hand-written Rust, at rtol 1e-3 .. 1e-12, timed on this machine in one run.
#
#   scripts/work_precision.sh               the sweep: tables into BENCHMARKS.md,
#                                           plots into docs/work-precision/
#   scripts/work_precision.sh --references  first regenerate tests/data/simulate/
#   scripts/work_precision.sh --fresh       forget the results of an earlier run
#                                           (target/work_precision/results.json)
#   scripts/work_precision.sh --auto        only --method auto against the better
#                                           method, in instructions (cachegrind)
#
# Installs what it needs itself: Debian's libsundials-dev and a C compiler
# (apt-get), a Python virtual environment with scipy and matplotlib
# (target/work_precision/venv). Takes about an hour on a 2-core machine:
# each configuration runs 5 times; one whose run takes over 30 s is skipped
# with its tighter tolerances, and the table says so.
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/work_precision
mkdir -p "$out"

if [ ! -f /usr/include/cvode/cvode.h ] || ! command -v cc >/dev/null; then
    echo "installing libsundials-dev and a C compiler with apt-get" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libsundials-dev gcc >/dev/null
fi
if [ ! -x "$out/venv/bin/python" ]; then
    echo "creating $out/venv with scipy and matplotlib" >&2
    python3 -m venv "$out/venv"
    "$out/venv/bin/pip" install -q scipy matplotlib
fi

echo "building mbexpr and the hand-written scenes (release)" >&2
nice cargo build --release --quiet --bin mbexpr --example hand_scenes
echo "building benches/anchors/cvode_scenes.c" >&2
cc -O2 -o "$out/cvode_scenes" benches/anchors/cvode_scenes.c \
    -lsundials_cvode -lsundials_nvecserial -lsundials_sunmatrixdense \
    -lsundials_sunlinsoldense -lm

# One core: no threaded BLAS under scipy.
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
python="$out/venv/bin/python"
for argument in "$@"; do
    case "$argument" in
        --references) "$python" scripts/work_precision.py references ;;
        --auto)
            if ! command -v valgrind >/dev/null; then
                apt-get update -qq
                DEBIAN_FRONTEND=noninteractive apt-get install -y -qq valgrind >/dev/null
            fi
            "$python" scripts/work_precision.py auto
            exit 0 ;;
        --fresh) ;;
        *) echo "unknown argument $argument" >&2; exit 2 ;;
    esac
done
fresh=""
for argument in "$@"; do [ "$argument" = --fresh ] && fresh=--fresh; done
"$python" scripts/work_precision.py sweep $fresh
echo "versions: $("$python" -c 'import scipy, matplotlib, sys; print("python", sys.version.split()[0], "scipy", scipy.__version__, "matplotlib", matplotlib.__version__)'), sundials $(dpkg-query -W -f='${Version}' libsundials-dev 2>/dev/null || echo '?')" >&2
