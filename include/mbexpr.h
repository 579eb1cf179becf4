/*
 * mbexpr for C and C++: the solver's utility subroutines for user
 * subroutines, then the C API (below).
 *
 * Link with target/release/libmbexpr.a (and -lpthread -ldl -lm) or
 * libmbexpr.so. VECTOR has three entries:
 *
 *   VECTOR | iord = 0 | iord = 1   | iord = 2
 *   [0]    | F        | dF/dx      | d2F/dx2
 *   [1]    | 0        | dF/dx'     | d2F/dx dx'
 *   [2]    | 0        | 0          | d2F/dx'2 (always 0)
 *
 * On a broken argument rule (x1 >= x2, k < 0, e <= 0, cmax < 0, d <= 0),
 * an iord other than 0, 1, 2, an input that is not finite, or an entry
 * asked for that is beyond the range of a double (about 1.8e308), *errflg
 * is set to 1 and VECTOR (or *value) to zeros; otherwise *errflg is 0 and
 * every entry is a finite number: no NaN and no infinity is ever returned.
 * See docs/contact.md.
 */
#ifndef MBEXPR_H
#define MBEXPR_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* BISTOP: free in [x1, x2], pushed back up below x1 and down above x2. */
void c_bistop(double x, double xd, double x1, double x2, double k, double e,
              double cmax, double d, int iord, double *vector, int *errflg);

/* IMPACT: pushed back up when x is below x1. */
void c_impact(double x, double xd, double x1, double k, double e,
              double cmax, double d, int iord, double *vector, int *errflg);

/* STEP: h0 up to x0, h1 from x1, a cubic between; *value is the value or
 * its first or second derivative in x for iord 0, 1, 2. */
void c_step(double x, double x0, double h0, double x1, double h1, int iord,
            double *value, int *errflg);

/*
 * The C API: expressions compiled into programs, evaluated with exact
 * derivatives at a point and in bulk; model files checked and simulated.
 * (`pkg-config --cflags --libs mbexpr` after scripts/install_c.sh; C++:
 * include/mbexpr.hpp; FORTRAN: include/mbexpr_c.f90.)
 *
 * Every call that can fail returns MBEXPR_OK or MBEXPR_ERROR and then
 * fills *error (when error is not NULL): a message allocated by the
 * library, freed with mbexpr_error_free, and the line and column (from 1;
 * 0 when the error speaks of no place) in the expression or the model's
 * file. A call that fills an error frees the message it held first, so
 * one error may be passed to call after call and freed once at the end
 * (a call that succeeds leaves it as it was); it must therefore start
 * zeroed, `mbexpr_error error = {0};`, and hold only NULL or a message of
 * the library. There is no global error state and no panic crosses into C.
 * Every object the library allocates has a _free function.
 */

#define MBEXPR_OK 0
#define MBEXPR_ERROR 1

typedef struct mbexpr_error {
  char *message; /* NULL, or a NUL-terminated message owned by the library */
  size_t line;   /* from 1; 0: no place */
  size_t column; /* from 1; 0: no place */
} mbexpr_error;

/* Frees error->message and sets it to NULL; NULL and an empty error are
 * left alone. Declare errors as `mbexpr_error error = {0};`. */
void mbexpr_error_free(mbexpr_error *error);

/* A compiled expression: immutable, so any number of threads may evaluate
 * one program at once. */
typedef struct mbexpr_program mbexpr_program;

/* Parses, checks and compiles `text` for the inputs named inputs[0 ..
 * input_count-1] (case-insensitive; their values are later given in this
 * order; TIME and MODE may be among them). */
int mbexpr_compile(const char *text, const char *const *inputs,
                   size_t input_count, mbexpr_program **program,
                   mbexpr_error *error);
void mbexpr_program_free(mbexpr_program *program);
size_t mbexpr_program_input_count(const mbexpr_program *program);
/* The name of input `index`, valid while the program lives (NULL beyond). */
const char *mbexpr_program_input(const mbexpr_program *program, size_t index);

/* At one point (one value per input): the value; the value and the exact
 * gradient in the inputs wrt[0 .. wrt_count-1] (indices from 0); and the
 * Hessian too (wrt_count * wrt_count, symmetric). A point where the
 * expression cannot be evaluated (a domain error, an overflow, an input
 * that is not finite) is an error placed at the operation: a result is
 * never NaN or infinite. */
int mbexpr_value(const mbexpr_program *program, const double *point,
                 double *value, mbexpr_error *error);
int mbexpr_gradient(const mbexpr_program *program, const double *point,
                    const size_t *wrt, size_t wrt_count, double *value,
                    double *gradient, mbexpr_error *error);
int mbexpr_hessian(const mbexpr_program *program, const double *point,
                   const size_t *wrt, size_t wrt_count, double *value,
                   double *gradient, double *hessian, mbexpr_error *error);

/* In bulk over n points as one column per input (structure of arrays:
 * columns[i][p] is input i at point p), on `threads` threads (0: every
 * core; 1: the calling thread alone). Point p's gradient is at
 * gradients[p * wrt_count], its Hessian at hessians[p * wrt_count *
 * wrt_count]. status[p] is 0, or 1 where point p cannot be evaluated (its
 * outputs are then 0; mbexpr_value at that point says why); *failed (when
 * not NULL) counts those points. The call itself fails only on bad
 * arguments (a NULL buffer, a direction that is not an input). */
int mbexpr_value_bulk(const mbexpr_program *program,
                      const double *const *columns, size_t n, double *values,
                      int *status, size_t threads, size_t *failed,
                      mbexpr_error *error);
int mbexpr_gradient_bulk(const mbexpr_program *program,
                         const double *const *columns, size_t n,
                         const size_t *wrt, size_t wrt_count, double *values,
                         double *gradients, int *status, size_t threads,
                         size_t *failed, mbexpr_error *error);
int mbexpr_hessian_bulk(const mbexpr_program *program,
                        const double *const *columns, size_t n,
                        const size_t *wrt, size_t wrt_count, double *values,
                        double *gradients, double *hessians, int *status,
                        size_t threads, size_t *failed, mbexpr_error *error);

/* A list of messages at their places: the problems of a checked model
 * file, or every error of a compilation or a model's load (the _all entry
 * points). mbexpr_diagnostic gives the message of entry `index` (valid
 * while the list lives; NULL beyond the last), its line and column (0: no
 * place) written where the pointers are not NULL. */
typedef struct mbexpr_diagnostics mbexpr_diagnostics;
size_t mbexpr_diagnostics_count(const mbexpr_diagnostics *diagnostics);
const char *mbexpr_diagnostic(const mbexpr_diagnostics *diagnostics,
                              size_t index, size_t *line, size_t *column);
void mbexpr_diagnostics_free(mbexpr_diagnostics *diagnostics);

/* As mbexpr_compile, but a failure hands every problem found (in source
 * order) to *errors, a list freed with mbexpr_diagnostics_free (errors may
 * be NULL); *errors is NULL after a success. mbexpr_compile's error is
 * the first, its message saying how many more there are. */
int mbexpr_compile_all(const char *text, const char *const *inputs,
                       size_t input_count, mbexpr_program **program,
                       mbexpr_diagnostics **errors);

/* Checks a model file (.adm, .acf, .cmd, a dataset known by its first
 * lines, or a scene file .toml): one diagnostic per problem, with its
 * line and column; none when it checks. Fails when the file cannot be
 * read or is not a model file. */
int mbexpr_check_model(const char *path, mbexpr_diagnostics **diagnostics,
                       mbexpr_error *error);

/* A model ready to simulate: a solver dataset (with END and STEPS of a
 * SIMULATE/DYNAMIC command in an .acf beside it), an Adams View command
 * file (.cmd, with those of its last transient simulation) or a scene
 * file. A model
 * that does not check, or holds what the simulator does not run
 * (constraints), is an error at its first problem (with how many more
 * there are); the _all forms list every problem as mbexpr_compile_all
 * does. */
typedef struct mbexpr_model mbexpr_model;
#define MBEXPR_DATASET 0
#define MBEXPR_SCENE 1
int mbexpr_model_load(const char *path, mbexpr_model **model,
                      mbexpr_error *error);
int mbexpr_model_from_text(const char *text, int format, mbexpr_model **model,
                           mbexpr_error *error);
int mbexpr_model_load_all(const char *path, mbexpr_model **model,
                          mbexpr_diagnostics **errors);
int mbexpr_model_from_text_all(const char *text, int format,
                               mbexpr_model **model,
                               mbexpr_diagnostics **errors);
/* The columns of a row: time, DIF(id) for each DIFF, the bodies' states,
 * the outputs (valid while the model lives; NULL beyond the last). */
size_t mbexpr_model_column_count(const mbexpr_model *model);
const char *mbexpr_model_column(const mbexpr_model *model, size_t index);
void mbexpr_model_free(mbexpr_model *model);

/* The methods: AUTO takes DOP853 while the model is not stiff and Radau5
 * while it is (the default, as on the command line); RADAU5 is for stiff
 * models throughout, DOP853 for smooth ones. */
#define MBEXPR_RADAU5 0
#define MBEXPR_DOP853 1
#define MBEXPR_AUTO 2

/* How to run: start from mbexpr_settings_default() (MBEXPR_AUTO and
 * zeros). A zero takes the model's own setting or the default: end and
 * steps from the model, rtol 1e-6, atol rtol/1000, no largest step, ten
 * million steps at most. */
typedef struct mbexpr_settings {
  int method; /* MBEXPR_AUTO (the default), MBEXPR_RADAU5 or MBEXPR_DOP853 */
  double end;
  size_t steps; /* output steps: steps + 1 rows */
  double rtol;
  double atol;
  double h_max;
  size_t max_steps;
} mbexpr_settings;
mbexpr_settings mbexpr_settings_default(void);

typedef struct mbexpr_summary {
  size_t steps, rejected, rhs_evaluations, jacobian_evaluations,
      lu_decompositions, events;
  double wall_time;      /* seconds */
  int stopped;           /* 1 when the row callback stopped the run */
  size_t method_changes; /* MBEXPR_AUTO: how many times it changed method */
} mbexpr_summary;

/* One output row: `values` holds the `count` columns after time (valid
 * during the call). Return 0 to go on, anything else to stop the run. */
typedef int (*mbexpr_row_callback)(void *user, double time,
                                   const double *values, size_t count);
/* One located branch switch (called after the run, in time order). */
typedef void (*mbexpr_event_callback)(void *user, double time,
                                      const char *function, const char *from,
                                      const char *to, size_t line,
                                      size_t column);

/* Runs the model from time 0: `row` (if not NULL) at each output time as
 * the run reaches it, then `event` (if not NULL) per branch switch; `user`
 * is passed to both. A run that cannot go on is an error placed at the
 * expression that stopped it (the rows before it delivered). Several
 * threads may simulate one model at once. */
int mbexpr_simulate(const mbexpr_model *model, const mbexpr_settings *settings,
                    mbexpr_row_callback row, mbexpr_event_callback event,
                    void *user, mbexpr_summary *summary, mbexpr_error *error);

#ifdef __cplusplus
}
#endif

#endif /* MBEXPR_H */
