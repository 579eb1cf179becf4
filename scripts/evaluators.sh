#!/usr/bin/env bash
# mbexpr's C API against the C++ evaluators solver writers embed: muparser
# (Debian's libmuparser-dev) and ExprTk (its single header, taken from the
# cexprtk sdist on PyPI: ExprTk is in neither Debian nor crates.io as a
# header). Builds benches/anchors/evaluators.cpp against the release
# libmbexpr.a and runs it on one thread and on every core; the tables go
# into BENCHMARKS.md.
set -euo pipefail
cd "$(dirname "$0")/.."
work=target/evaluators
mkdir -p "$work"

if ! dpkg -s libmuparser-dev >/dev/null 2>&1; then
  apt-get update -qq && apt-get install -y -qq libmuparser-dev >/dev/null
fi
exprtk=()
if [ ! -f "$work/exprtk.hpp" ]; then
  python3 -m pip download -q --no-binary :all: --no-deps cexprtk==0.4.2 -d "$work" || true
  sdist=$(ls "$work"/cexprtk-*.tar.gz 2>/dev/null | head -1)
  if [ -n "$sdist" ]; then
    tar -xzf "$sdist" -C "$work" --wildcards '*/exprtk.hpp'
    find "$work" -name exprtk.hpp -path '*cexprtk*' -exec cp {} "$work/exprtk.hpp" \;
  fi
fi
if [ -f "$work/exprtk.hpp" ]; then
  exprtk=(-DWITH_EXPRTK -I "$work")
else
  echo "note: ExprTk's header is not available; muparser only" >&2
fi

cargo build --release --lib  # into $CARGO_TARGET_DIR when set
# ExprTk's header takes minutes and over a gigabyte to compile: nice it.
nice g++ -O2 -std=c++17 "${exprtk[@]}" benches/anchors/evaluators.cpp -I include \
  $(pkg-config --cflags muparser 2>/dev/null || true) \
  "${CARGO_TARGET_DIR:-target}/release/libmbexpr.a" -lmuparser -lpthread -ldl -lm -o "$work/evaluators"

echo "one thread (OMP_NUM_THREADS=1, mbexpr threads = 1):"
OMP_NUM_THREADS=1 "$work/evaluators" 1
echo
echo "every core (muparser's OpenMP default, mbexpr threads = 0):"
"$work/evaluators" 0
