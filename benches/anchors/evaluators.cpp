// mbexpr's C API beside muparser (bulk Eval, Diff) and ExprTk (value(),
// exprtk::derivative) on the same three expressions over a million
// points: a spring-damper, a polynomial, and BISTOP (mbexpr's built-in
// law; written out with if/min/max in the others' languages). Built and
// run by scripts/evaluators.sh; prints one Markdown table row per case.
//
//   evaluators THREADS   (THREADS: mbexpr's threads, 0 = every core;
//                         muparser's OpenMP follows OMP_NUM_THREADS)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <muParser.h>

#ifdef WITH_EXPRTK
#include "exprtk.hpp"
#endif

#include "mbexpr.h"

namespace {

constexpr int N = 1000000;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A case: the expression in each language, and its exact gradient in
// (x, v) in long double for the error of the derivatives.
struct Case {
  const char *name;
  std::string mbexpr, muparser, exprtk;
  long double (*dx)(long double x, long double v);
  long double (*dv)(long double x, long double v);
};

// -k x - c v with k = 1e4, c = 20.
long double spring_dx(long double, long double) { return -1e4L; }
long double spring_dv(long double, long double) { return -20.0L; }

// ((((0.5x - 1.2)x + 3.1)x - 0.7)x + 2)x - 4 + v
long double poly_dx(long double x, long double) {
  return (((2.5L * x - 4.8L) * x + 9.3L) * x - 1.4L) * x + 2.0L;
}
long double poly_dv(long double, long double) { return 1.0L; }

// BISTOP(x, v, -1, 1, 1e5, 1.5, 50, 0.01), by hand in long double.
long double ramp(long double s) { return s * s * (3 - 2 * s); }
long double ramp_slope(long double s) { return 6 * s * (1 - s); }
long double clamp01(long double s) { return s < 0 ? 0 : (s > 1 ? 1 : s); }
long double bistop_dx(long double x, long double v) {
  if (x < -1) {
    long double p = -1 - x, s = clamp01((x + 1.01L) / 0.01L);
    long double c = 50 * (1 - ramp(s));
    long double f = 1e5L * powl(p, 1.5L) - c * v;
    if (f <= 0) return 0;
    long double dc = (s > 0 && s < 1) ? -50 * ramp_slope(s) / 0.01L : 0;
    return -1.5e5L * powl(p, 0.5L) - dc * v;
  }
  if (x > 1) {
    long double p = x - 1, s = clamp01((x - 1) / 0.01L);
    long double c = 50 * ramp(s);
    long double f = -1e5L * powl(p, 1.5L) - c * v;
    if (f >= 0) return 0;
    long double dc = (s > 0 && s < 1) ? 50 * ramp_slope(s) / 0.01L : 0;
    return -1.5e5L * powl(p, 0.5L) - dc * v;
  }
  return 0;
}
long double bistop_dv(long double x, long double v) {
  if (x < -1) {
    long double p = -1 - x, c = 50 * (1 - ramp(clamp01((x + 1.01L) / 0.01L)));
    return 1e5L * powl(p, 1.5L) - c * v > 0 ? -c : 0;
  }
  if (x > 1) {
    long double p = x - 1, c = 50 * ramp(clamp01((x - 1) / 0.01L));
    return -1e5L * powl(p, 1.5L) - c * v < 0 ? -c : 0;
  }
  return 0;
}

const std::string lower_s = "min(max((x+1.01)/0.01,0),1)";
const std::string upper_s = "min(max((x-1)/0.01,0),1)";
const std::string lower_force =
    "max(1e5*(-1-x)^1.5 - 50*(1-" + lower_s + "^2*(3-2*" + lower_s + "))*v, 0)";
const std::string upper_force =
    "min(-1e5*(x-1)^1.5 - 50*" + upper_s + "^2*(3-2*" + upper_s + ")*v, 0)";

std::vector<Case> cases() {
  const std::string poly = "((((0.5*x - 1.2)*x + 3.1)*x - 0.7)*x + 2)*x - 4 + v";
  return {
      {"spring-damper", "-1e4*x - 20*v", "-1e4*x - 20*v", "-1e4*x - 20*v", spring_dx, spring_dv},
      {"polynomial (degree 5)", poly, poly, poly, poly_dx, poly_dv},
      {"BISTOP", "BISTOP(x, v, -1, 1, 1e5, 1.5, 50, 0.01)",
       "x < -1 ? " + lower_force + " : (x > 1 ? " + upper_force + " : 0)",
       "if(x < -1, " + lower_force + ", if(x > 1, " + upper_force + ", 0))", bistop_dx,
       bistop_dv},
  };
}

// The largest relative error of `got` against the reference `want` (where
// the reference is not below 1e-12 of its largest magnitude).
double worst(const std::vector<double> &got, const std::vector<long double> &want) {
  long double scale = 0;
  for (long double w : want) scale = std::fmax(scale, fabsl(w));
  double error = 0;
  for (std::size_t p = 0; p < got.size(); p++) {
    long double w = want[p];
    long double floor = scale * 1e-12L;
    long double denominator = fabsl(w) > floor ? fabsl(w) : floor;
    if (denominator == 0) continue;
    error = std::fmax(error, static_cast<double>(fabsl(got[p] - w) / denominator));
  }
  return error;
}

}  // namespace

int main(int argc, char **argv) {
  std::size_t threads = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 0;
  std::vector<double> xs(N), vs(N);
  for (int p = 0; p < N; p++) {
    xs[p] = -1.02 + 2.04 * (p + 0.5) / N;  // across both walls and their ramps
    vs[p] = std::sin(0.001 * p) * 3.0;
  }
  std::printf("| expression | mbexpr value (ns/point) | muparser bulk Eval | ExprTk value() | "
              "mbexpr exact gradient (ns/point, max rel. error) | muparser Diff | ExprTk derivative |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Case &c : cases()) {
    // mbexpr through its C API, bulk.
    const char *names[] = {"x", "v"};
    mbexpr_program *program = nullptr;
    mbexpr_error error = {};
    if (mbexpr_compile(c.mbexpr.c_str(), names, 2, &program, &error) != MBEXPR_OK) {
      std::fprintf(stderr, "%s: %s\n", c.name, error.message);
      return 1;
    }
    std::vector<double> mb(N), mb_grad(2 * N), grad_values(N);
    std::vector<int> status(N);
    const double *columns[] = {xs.data(), vs.data()};
    std::size_t failed = 0;
    mbexpr_value_bulk(program, columns, N, mb.data(), status.data(), threads, &failed, nullptr);
    auto start = std::chrono::steady_clock::now();
    mbexpr_value_bulk(program, columns, N, mb.data(), status.data(), threads, &failed, nullptr);
    double mb_time = seconds_since(start);
    std::size_t wrt[] = {0, 1};
    start = std::chrono::steady_clock::now();
    mbexpr_gradient_bulk(program, columns, N, wrt, 2, grad_values.data(), mb_grad.data(),
                         status.data(), threads, &failed, nullptr);
    double mb_grad_time = seconds_since(start);
    mbexpr_program_free(program);

    std::vector<long double> want_dx(N), want_dv(N);
    for (int p = 0; p < N; p++) {
      want_dx[p] = c.dx(xs[p], vs[p]);
      want_dv[p] = c.dv(xs[p], vs[p]);
    }
    std::vector<double> got_dx(N), got_dv(N);
    for (int p = 0; p < N; p++) {
      got_dx[p] = mb_grad[2 * p];
      got_dv[p] = mb_grad[2 * p + 1];
    }
    double mb_error = std::fmax(worst(got_dx, want_dx), worst(got_dv, want_dv));

    // muparser: bulk variables and Eval(results, n); Diff per point.
    mu::Parser parser;
    std::vector<double> mu(N);
    parser.DefineVar("x", xs.data());
    parser.DefineVar("v", vs.data());
    parser.SetExpr(c.muparser);
    parser.Eval(mu.data(), N);
    start = std::chrono::steady_clock::now();
    parser.Eval(mu.data(), N);
    double mu_time = seconds_since(start);
    double mu_agree = 0;
    for (int p = 0; p < N; p++)
      mu_agree = std::fmax(mu_agree, std::fabs(mu[p] - mb[p]) / (std::fabs(mb[p]) + 1e-300 + 1));
    double x = 0, v = 0;
    mu::Parser scalar;
    scalar.DefineVar("x", &x);
    scalar.DefineVar("v", &v);
    scalar.SetExpr(c.muparser);
    start = std::chrono::steady_clock::now();
    for (int p = 0; p < N; p++) {
      x = xs[p];
      v = vs[p];
      got_dx[p] = scalar.Diff(&x, xs[p]);
      got_dv[p] = scalar.Diff(&v, vs[p]);
    }
    double mu_diff_time = seconds_since(start);
    double mu_error = std::fmax(worst(got_dx, want_dx), worst(got_dv, want_dv));

    std::string exprtk_value = "not built", exprtk_diff = "not built";
#ifdef WITH_EXPRTK
    {
      exprtk::symbol_table<double> symbols;
      symbols.add_variable("x", x);
      symbols.add_variable("v", v);
      exprtk::expression<double> expression;
      expression.register_symbol_table(symbols);
      exprtk::parser<double> exprtk_parser;
      if (!exprtk_parser.compile(c.exprtk, expression)) {
        std::fprintf(stderr, "%s: ExprTk: %s\n", c.name, exprtk_parser.error().c_str());
        return 1;
      }
      std::vector<double> et(N);
      start = std::chrono::steady_clock::now();
      for (int p = 0; p < N; p++) {
        x = xs[p];
        v = vs[p];
        et[p] = expression.value();
      }
      double et_time = seconds_since(start);
      double et_agree = 0;
      for (int p = 0; p < N; p++)
        et_agree = std::fmax(et_agree, std::fabs(et[p] - mb[p]) / (std::fabs(mb[p]) + 1));
      start = std::chrono::steady_clock::now();
      for (int p = 0; p < N; p++) {
        x = xs[p];
        v = vs[p];
        got_dx[p] = exprtk::derivative(expression, x);
        got_dv[p] = exprtk::derivative(expression, v);
      }
      double et_diff_time = seconds_since(start);
      double et_error = std::fmax(worst(got_dx, want_dx), worst(got_dv, want_dv));
      char text[200];
      std::snprintf(text, sizeof text, "%.1f (agrees to %.0e)", 1e9 * et_time / N, et_agree);
      exprtk_value = text;
      std::snprintf(text, sizeof text, "%.1f, %.1e", 1e9 * et_diff_time / N, et_error);
      exprtk_diff = text;
    }
#endif
    std::printf("| %s | %.1f | %.1f (agrees to %.0e) | %s | %.1f, %.1e | %.1f, %.1e | %s |\n",
                c.name, 1e9 * mb_time / N, 1e9 * mu_time / N, mu_agree, exprtk_value.c_str(),
                1e9 * mb_grad_time / N, mb_error, 1e9 * mu_diff_time / N, mu_error,
                exprtk_diff.c_str());
  }
  return 0;
}
