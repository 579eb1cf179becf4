// mbexpr for C++: RAII wrappers over the C API of mbexpr.h (C++17).
//
// Errors are thrown as mbexpr::error (a std::runtime_error with the line
// and column); objects free what they own; a program is immutable and
// may be shared between threads (const member functions only).
#ifndef MBEXPR_HPP
#define MBEXPR_HPP

#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mbexpr.h"

namespace mbexpr {

// A message at its place: a problem of a checked model file, or one error
// of a compilation or a model's load.
struct diagnostic {
  std::string message;
  std::size_t line, column;  // from 1; 0: no place
};

// A failed call: the message, and the line and column (from 1; 0: no
// place). A compilation or a model's load that fails has every problem in
// `errors` (the first is `line` and `column`); what() is then the first's
// message, or every problem as "line:column: message", one a line, when
// there are several. Other calls have one entry.
class error : public std::runtime_error {
 public:
  error(const std::string &message, std::size_t line, std::size_t column)
      : std::runtime_error(message),
        line(line),
        column(column),
        errors{{message, line, column}} {}
  explicit error(std::vector<diagnostic> all)
      : std::runtime_error(listed(all)),
        line(all.empty() ? 0 : all[0].line),
        column(all.empty() ? 0 : all[0].column),
        errors(std::move(all)) {}
  std::size_t line;
  std::size_t column;
  std::vector<diagnostic> errors;

 private:
  static std::string listed(const std::vector<diagnostic> &all) {
    if (all.size() == 1) return all[0].message;
    std::string text;
    for (const auto &entry : all) {
      if (!text.empty()) text += "\n";
      text += std::to_string(entry.line) + ":" +
              std::to_string(entry.column) + ": " + entry.message;
    }
    return text;
  }
};

namespace detail {
// Throws the error a C call filled in, after freeing its message.
inline void check(int code, mbexpr_error &failure) {
  if (code == MBEXPR_OK) return;
  std::string message = failure.message ? failure.message : "unknown error";
  std::size_t line = failure.line, column = failure.column;
  mbexpr_error_free(&failure);
  throw error(message, line, column);
}

// The entries of a list, which is freed.
inline std::vector<diagnostic> entries(mbexpr_diagnostics *list) {
  std::vector<diagnostic> result;
  for (std::size_t i = 0; i < mbexpr_diagnostics_count(list); i++) {
    diagnostic entry;
    entry.message = mbexpr_diagnostic(list, i, &entry.line, &entry.column);
    result.push_back(entry);
  }
  mbexpr_diagnostics_free(list);
  return result;
}

// Throws every error an _all call listed (taken by reference: the call
// fills it, and arguments are evaluated in any order).
inline void check_all(int code, mbexpr_diagnostics *&errors) {
  if (code == MBEXPR_OK) return;
  throw error(entries(errors));
}
}  // namespace detail

// The value, gradient and Hessian (row by row) at one point.
struct evaluation {
  double value = 0.0;
  std::vector<double> gradient;
  std::vector<double> hessian;
};

// The results of a bulk evaluation: per point a value, a gradient (k
// entries), a Hessian (k * k) and a status (0, or 1 where it failed).
struct bulk {
  std::vector<double> values, gradients, hessians;
  std::vector<int> status;
  std::size_t failed = 0;
};

// A compiled expression.
class program {
 public:
  program(const std::string &text, const std::vector<std::string> &inputs) {
    std::vector<const char *> names;
    for (const auto &name : inputs) names.push_back(name.c_str());
    mbexpr_diagnostics *errors = nullptr;
    mbexpr_program *compiled = nullptr;
    detail::check_all(mbexpr_compile_all(text.c_str(), names.data(),
                                         names.size(), &compiled, &errors),
                      errors);
    handle_.reset(compiled);
  }

  std::size_t input_count() const {
    return mbexpr_program_input_count(handle_.get());
  }

  // Throws unless `given` values (of `what`) are one for each input: the
  // library reads one from each.
  void check_size(std::size_t given, const char *what) const {
    std::size_t inputs = input_count();
    if (given != inputs) {
      throw error(std::string(what) + " has " + std::to_string(given) +
                      " values for " + std::to_string(inputs) +
                      " inputs: give one for each input",
                  0, 0);
    }
  }

  double value(const std::vector<double> &point) const {
    check_size(point.size(), "the point");
    mbexpr_error failure = {};
    double result = 0.0;
    detail::check(mbexpr_value(handle_.get(), point.data(), &result, &failure),
                  failure);
    return result;
  }

  // The value and gradient in `wrt` (and the Hessian when `hessian`).
  evaluation derivatives(const std::vector<double> &point,
                         const std::vector<std::size_t> &wrt,
                         bool hessian = false) const {
    check_size(point.size(), "the point");
    evaluation result;
    result.gradient.resize(wrt.size());
    mbexpr_error failure = {};
    if (hessian) {
      result.hessian.resize(wrt.size() * wrt.size());
      detail::check(mbexpr_hessian(handle_.get(), point.data(), wrt.data(),
                                   wrt.size(), &result.value,
                                   result.gradient.data(),
                                   result.hessian.data(), &failure),
                    failure);
    } else {
      detail::check(mbexpr_gradient(handle_.get(), point.data(), wrt.data(),
                                    wrt.size(), &result.value,
                                    result.gradient.data(), &failure),
                    failure);
    }
    return result;
  }

  // Over the points of `columns` (one per input, each of n values), with
  // derivatives in `wrt` for order 1 (gradient) or 2 (Hessian), on
  // `threads` threads (0: every core).
  bulk evaluate(const std::vector<const double *> &columns, std::size_t n,
                const std::vector<std::size_t> &wrt = {}, int order = 0,
                std::size_t threads = 0) const {
    check_size(columns.size(), "the columns");
    bulk result;
    std::size_t k = wrt.size();
    result.values.resize(n);
    result.status.resize(n);
    mbexpr_error failure = {};
    int code;
    if (order == 0) {
      code = mbexpr_value_bulk(handle_.get(), columns.data(), n,
                               result.values.data(), result.status.data(),
                               threads, &result.failed, &failure);
    } else if (order == 1) {
      result.gradients.resize(n * k);
      code = mbexpr_gradient_bulk(
          handle_.get(), columns.data(), n, wrt.data(), k,
          result.values.data(), result.gradients.data(), result.status.data(),
          threads, &result.failed, &failure);
    } else {
      result.gradients.resize(n * k);
      result.hessians.resize(n * k * k);
      code = mbexpr_hessian_bulk(
          handle_.get(), columns.data(), n, wrt.data(), k,
          result.values.data(), result.gradients.data(),
          result.hessians.data(), result.status.data(), threads,
          &result.failed, &failure);
    }
    detail::check(code, failure);
    return result;
  }

 private:
  struct free_program {
    void operator()(mbexpr_program *p) const { mbexpr_program_free(p); }
  };
  std::unique_ptr<mbexpr_program, free_program> handle_;
};

// Checks a model file: its problems (none when it checks).
inline std::vector<diagnostic> check_model(const std::string &path) {
  mbexpr_error failure = {};
  mbexpr_diagnostics *found = nullptr;
  detail::check(mbexpr_check_model(path.c_str(), &found, &failure), failure);
  return detail::entries(found);
}

// A located branch switch.
struct event {
  double time;
  std::string function, from, to;
  std::size_t line, column;
};

// What a run found.
struct run {
  mbexpr_summary summary;
  std::vector<event> events;
};

// A model ready to simulate.
class model {
 public:
  // The model of a file (a dataset or a scene file).
  explicit model(const std::string &path) {
    mbexpr_diagnostics *errors = nullptr;
    mbexpr_model *loaded = nullptr;
    detail::check_all(mbexpr_model_load_all(path.c_str(), &loaded, &errors),
                      errors);
    handle_.reset(loaded);
  }

  // The model of a text: MBEXPR_DATASET or MBEXPR_SCENE.
  model(const std::string &text, int format) {
    mbexpr_diagnostics *errors = nullptr;
    mbexpr_model *loaded = nullptr;
    detail::check_all(
        mbexpr_model_from_text_all(text.c_str(), format, &loaded, &errors),
        errors);
    handle_.reset(loaded);
  }

  std::vector<std::string> columns() const {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < mbexpr_model_column_count(handle_.get()); i++)
      names.push_back(mbexpr_model_column(handle_.get(), i));
    return names;
  }

  // Runs the model, calling `row(time, values, count)` at each output
  // time (return false to stop). An exception thrown by `row` stops the
  // run and is thrown again here. Without settings, those of
  // mbexpr_settings_default(): MBEXPR_AUTO and the model's own end and
  // steps.
  using row_function = std::function<bool(double, const double *, std::size_t)>;
  mbexpr::run simulate(const row_function &row) const {
    return simulate(mbexpr_settings_default(), row);
  }
  mbexpr::run simulate(const mbexpr_settings &settings,
                       const row_function &row) const {
    state context{&row, nullptr, {}};
    mbexpr::run result{};
    mbexpr_error failure = {};
    int code = mbexpr_simulate(handle_.get(), &settings, &on_row, &on_event,
                               &context, &result.summary, &failure);
    if (context.thrown) {
      mbexpr_error_free(&failure);
      std::rethrow_exception(context.thrown);
    }
    detail::check(code, failure);
    result.events = std::move(context.events);
    return result;
  }

 private:
  struct state {
    const row_function *row;
    std::exception_ptr thrown;
    std::vector<event> events;
  };
  // No exception may cross into the library: it is kept and thrown later.
  static int on_row(void *user, double time, const double *values,
                    std::size_t count) {
    auto *context = static_cast<state *>(user);
    try {
      return (*context->row)(time, values, count) ? 0 : 1;
    } catch (...) {
      context->thrown = std::current_exception();
      return 1;
    }
  }
  static void on_event(void *user, double time, const char *function,
                       const char *from, const char *to, std::size_t line,
                       std::size_t column) {
    auto *context = static_cast<state *>(user);
    try {
      context->events.push_back({time, function, from, to, line, column});
    } catch (...) {
      context->thrown = std::current_exception();
    }
  }
  struct free_model {
    void operator()(mbexpr_model *m) const { mbexpr_model_free(m); }
  };
  std::unique_ptr<mbexpr_model, free_model> handle_;
};

}  // namespace mbexpr

#endif  // MBEXPR_HPP
