#!/usr/bin/env bash
# `eval --points` end to end: rows per second for the value, the gradient
# and the Hessian of a BISTOP over 1 000 000 rows of x,v, and peak memory
# at 10 000 000 rows, for each binary given (an older build first, to
# compare). Best wall time of RUNS runs; CPU time and peak memory from
# /usr/bin/time. The figures are in BENCHMARKS.md.
#
#   scripts/points_bench.sh BEFORE_BINARY target/release/mbexpr
#
# Environment: RUNS (3), DIR (a scratch folder, /tmp/mbexpr-points-bench).
set -euo pipefail

runs=${RUNS:-3}
dir=${DIR:-/tmp/mbexpr-points-bench}
mkdir -p "$dir"
expression='BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)'

# x in [-11, 11], v in [-2, 2] from a fixed linear congruential sequence.
points() {
    awk -v rows="$1" 'BEGIN {
        print "x,v"; s = 12345
        for (i = 0; i < rows; i++) {
            s = (s * 1103515245 + 12345) % 2147483648; x = s / 2147483648 * 22 - 11
            s = (s * 1103515245 + 12345) % 2147483648; v = s / 2147483648 * 4 - 2
            printf "%.17g,%.17g\n", x, v
        }
    }'
}
[ -s "$dir/1m.csv" ] || points 1000000 > "$dir/1m.csv"
[ -s "$dir/10m.csv" ] || points 10000000 > "$dir/10m.csv"

# best BINARY FILE FORMAT ORDER RUNS: "wall cpu peak_kb" of the fastest run.
best() {
    local binary=$1 file=$2 format=$3 order=$4 count=$5 wrt=()
    [ "$order" -gt 0 ] && wrt=(--wrt x,v)
    for _ in $(seq "$count"); do
        /usr/bin/time -f '%e %U %S %M' "$binary" eval "$expression" --points "$file" \
            "${wrt[@]}" --order "$order" --format "$format" 2>&1 >/dev/null | tail -1
    done | awk '{ cpu = $2 + $3; print $1, cpu, $4 }' | sort -n | head -1
}

printf '%-28s %-6s %-5s %10s %8s %8s %12s\n' binary format order 'rows/s' wall cpu 'peak KB'
for binary in "$@"; do
    for format in jsonl text; do
        for order in 0 1 2; do
            read -r wall cpu peak < <(best "$binary" "$dir/1m.csv" "$format" "$order" "$runs")
            printf '%-28s %-6s %-5s %10.0f %8s %8s %12s\n' "$(basename "$binary")" "$format" \
                "$order" "$(echo "1000000 / $wall" | bc -l)" "$wall" "$cpu" "$peak"
        done
    done
    read -r wall cpu peak < <(best "$binary" "$dir/10m.csv" jsonl 2 1)
    printf '%-28s 10 000 000 rows, Hessian, jsonl: %s s, peak %s KB\n' "$(basename "$binary")" "$wall" "$peak"
done
