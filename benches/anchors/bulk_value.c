/* mbexpr's bulk value path alone, for profiling: the three expressions of
 * benches/anchors/evaluators.cpp over a million points through
 * mbexpr_value_bulk on the calling thread, best of REPS runs. Build and
 * count instructions (BENCHMARKS.md, "Embedded evaluators"):
 *
 *   cargo build --release --lib
 *   cc -O2 benches/anchors/bulk_value.c -I include \
 *     target/release/libmbexpr.a -lpthread -ldl -lm -o bulk_value
 *   ./bulk_value CASE [REPS]        (CASE 0, 1, 2)
 *   valgrind --tool=callgrind ./bulk_value CASE 1
 */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "mbexpr.h"
#define N 1000000
static double x[N], v[N], out[N];
static int status[N];
int main(int argc, char **argv) {
  if (argc < 2) {
    fputs("usage: bulk_value CASE [REPS]\n", stderr);
    return 2;
  }
  const char *texts[] = {"-1e4*x - 20*v",
    "((((0.5*x - 1.2)*x + 3.1)*x - 0.7)*x + 2)*x - 4 + v",
    "BISTOP(x, v, -1, 1, 1e5, 1.5, 50, 0.01)"};
  int which = atoi(argv[1]), reps = argc > 2 ? atoi(argv[2]) : 5;
  const char *inputs[] = {"x", "v"};
  mbexpr_program *p; mbexpr_error e = {0};
  if (mbexpr_compile(texts[which], inputs, 2, &p, &e)) { puts(e.message); return 1; }
  for (int i = 0; i < N; i++) { x[i] = -1.05 + 2.1 * i / (N - 1); v[i] = 0.5 - (i % 7) * 0.1; }
  const double *cols[] = {x, v};
  size_t failed; double best = 1e9, sum = 0;
  for (int r = 0; r < reps; r++) {
    struct timespec a, b; clock_gettime(CLOCK_MONOTONIC, &a);
    mbexpr_value_bulk(p, cols, N, out, status, 1, &failed, &e);
    clock_gettime(CLOCK_MONOTONIC, &b);
    double t = (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec);
    if (t < best) best = t;
  }
  for (int i = 0; i < N; i++) sum += out[i];
  printf("%s: %.1f ns/point (best of %d), sum %.6g, failed %zu\n", texts[which], best * 1e9 / N, reps, sum, failed);
  return 0;
}
