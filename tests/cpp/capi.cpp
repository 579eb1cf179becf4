// The C API through the RAII wrappers of mbexpr.hpp: compiled and run by
// tests/ffi.rs.
#include <cstdio>
#include <stdexcept>
#include <thread>
#include <vector>

#include "mbexpr.hpp"

int main() {
  // A spring-damper with exact derivatives in (x, v).
  const mbexpr::program force("-k*x - c*v + STEP(x, 0, 0, 0.1, 5)",
                              {"x", "v", "k", "c"});
  auto result = force.derivatives({0.03, 2.0, 100.0, 3.0}, {0, 1}, true);
  std::printf("value %.12g gradient %.12g %.12g hessian %.12g %.12g %.12g %.12g\n",
              result.value, result.gradient[0], result.gradient[1],
              result.hessian[0], result.hessian[1], result.hessian[2],
              result.hessian[3]);

  // Bulk, from two threads at once, each the same as the single calls.
  std::vector<double> x(1000), v(1000), k(1000, 100.0), c(1000, 3.0);
  for (std::size_t p = 0; p < x.size(); p++) {
    x[p] = -0.2 + 0.4 * p / 999.0;
    v[p] = 1.0 - 0.002 * p;
  }
  std::vector<const double *> columns{x.data(), v.data(), k.data(), c.data()};
  mbexpr::bulk results[2];
  std::thread threads[2];
  for (int t = 0; t < 2; t++)
    threads[t] = std::thread(
        [&, t] { results[t] = force.evaluate(columns, x.size(), {0}, 1, 1); });
  for (auto &thread : threads) thread.join();
  bool agree = true;
  for (std::size_t p = 0; p < x.size(); p++) {
    auto one = force.derivatives({x[p], v[p], 100.0, 3.0}, {0});
    for (const auto &bulk : results)
      agree = agree && bulk.values[p] == one.value &&
              bulk.gradients[p] == one.gradient[0] && bulk.status[p] == 0;
  }
  std::printf("two threads agree with the single calls: %s\n",
              agree ? "yes" : "no");

  // Errors are exceptions with their place.
  try {
    mbexpr::program broken("1 +\n  SQRT(x, 2)", {"x"});
  } catch (const mbexpr::error &e) {
    std::printf("error at %zu:%zu: %s\n", e.line, e.column, e.what());
  }
  try {
    mbexpr::program broken("spped * x +\n  LOG(y)", {"x"});
  } catch (const mbexpr::error &e) {
    std::printf("%zu errors, the first at %zu:%zu; what():\n%s\n",
                e.errors.size(), e.line, e.column, e.what());
  }
  const mbexpr::program root("SQRT(x)", {"x"});
  try {
    root.value({-4.0});
  } catch (const mbexpr::error &e) {
    std::printf("error at %zu:%zu: %s\n", e.line, e.column, e.what());
  }
  // A point shorter than the inputs is refused, not read past its end.
  try {
    force.value({0.03});
  } catch (const mbexpr::error &e) {
    std::printf("%s\n", e.what());
  }

  // A simulation: rows into a lambda, which stops it after three rows;
  // an exception from the lambda comes back out of simulate.
  const mbexpr::model ball(
      "ball\nDIFF/1, IC = 0, FUNCTION = DIF(2)\n"
      "DIFF/2, IC = 5, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e5, 1.5, 50, "
      "0.01)\nEND\n",
      MBEXPR_DATASET);
  mbexpr_settings settings = mbexpr_settings_default();
  settings.end = 0.4;
  settings.steps = 8;
  settings.method = MBEXPR_DOP853;
  settings.rtol = 1e-9;
  int rows = 0;
  auto run = ball.simulate(settings, [&](double t, const double *values,
                                         std::size_t count) {
    std::printf("  t = %.2f x = %.9f v = %.9f (%zu columns)\n", t, values[0],
                values[1], count);
    return ++rows < 3;
  });
  std::printf("stopped %d after %d rows; %zu events\n", run.summary.stopped,
              rows, run.events.size());
  try {
    ball.simulate(settings, [](double, const double *, std::size_t) -> bool {
      throw std::runtime_error("thrown by the row callback");
    });
  } catch (const std::runtime_error &e) {
    std::printf("caught: %s\n", e.what());
  }
  settings.steps = 200;
  run = ball.simulate(settings, [](double, const double *, std::size_t) {
    return true;
  });
  std::printf("first event: %s %s -> %s at t = %.6f, line %zu column %zu\n",
              run.events[0].function.c_str(), run.events[0].from.c_str(),
              run.events[0].to.c_str(), run.events[0].time, run.events[0].line,
              run.events[0].column);

  // The default method is auto: A4's ball turns stiff where it lands in
  // its damped stop (t = 0.45), and auto takes Radau5 there.
  const mbexpr::model dropped(
      "A4\nDIFF/1, IC = 0, FUNCTION = DIF(2)\n"
      "DIFF/2, IC = 0, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e8, 1.5, "
      "1e6, 1e-5) - 9.81\nEND\n",
      MBEXPR_DATASET);
  settings = mbexpr_settings_default();
  settings.end = 1.0;
  settings.steps = 10;
  auto landed = dropped.simulate(settings, [](double, const double *,
                                              std::size_t) { return true; });
  std::printf("A4 with the default settings: %zu method change(s)\n",
              landed.summary.method_changes);
  try {
    dropped.simulate([](double, const double *, std::size_t) { return true; });
  } catch (const mbexpr::error &e) {
    std::printf("no end time: %s\n", e.what());
  }
  return 0;
}
