#!/usr/bin/env bash
# Installs mbexpr's C API under PREFIX (default /usr/local): the static and
# shared libraries in PREFIX/lib, the headers (mbexpr.h, mbexpr.hpp, and the
# FORTRAN modules' sources mbexpr.f90, mbexpr_c.f90) in PREFIX/include, and
# PREFIX/lib/pkgconfig/mbexpr.pc, so that
#   cc prog.c $(pkg-config --cflags --libs mbexpr)
# links against the shared library (add --static for the static one).
set -euo pipefail
cd "$(dirname "$0")/.."
prefix=${1:-/usr/local}
cargo build --release --lib
version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)
mkdir -p "$prefix/lib/pkgconfig" "$prefix/include"
release="${CARGO_TARGET_DIR:-target}/release"
cp "$release/libmbexpr.a" "$release/libmbexpr.so" "$prefix/lib/"
cp include/mbexpr.h include/mbexpr.hpp include/mbexpr.f90 include/mbexpr_c.f90 "$prefix/include/"
sed -e "s|@PREFIX@|$prefix|" -e "s|@VERSION@|$version|" include/mbexpr.pc.in \
  >"$prefix/lib/pkgconfig/mbexpr.pc"
echo "installed mbexpr $version under $prefix"
