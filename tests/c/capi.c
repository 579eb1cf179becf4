/* The C API from C: compile, evaluate at a point and in bulk (from four
 * threads sharing one program), errors with their place, a model checked
 * and simulated into a row callback. Compiled and run by tests/ffi.rs. */
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "mbexpr.h"

static void report(const char *what, mbexpr_error *error) {
  printf("%s: %zu:%zu: %s\n", what, error->line, error->column,
         error->message);
  mbexpr_error_free(error);
}

/* Prints every entry of a list of errors, then frees it. */
static void print_list(const char *what, mbexpr_diagnostics *errors) {
  printf("%s: %zu error(s)\n", what, mbexpr_diagnostics_count(errors));
  for (size_t i = 0; i < mbexpr_diagnostics_count(errors); i++) {
    size_t line, column;
    const char *message = mbexpr_diagnostic(errors, i, &line, &column);
    printf("  %zu:%zu: %s\n", line, column, message);
  }
  mbexpr_diagnostics_free(errors);
}

#define POINTS 10000
static double xs[POINTS], vs[POINTS];

struct job {
  const mbexpr_program *program;
  double values[POINTS];
  int status[POINTS];
  size_t failed;
  int code;
};

static void *evaluate_all(void *argument) {
  struct job *job = argument;
  const double *columns[] = {xs, vs};
  job->code = mbexpr_value_bulk(job->program, columns, POINTS, job->values,
                                job->status, 1, &job->failed, NULL);
  return NULL;
}

static int print_row(void *user, double time, const double *values,
                     size_t count) {
  int *rows = user;
  printf("  t = %.3f:", time);
  for (size_t i = 0; i < count; i++) printf(" %.9f", values[i]);
  printf("\n");
  return ++*rows >= 100; /* stop after 100 rows */
}

static void print_event(void *user, double time, const char *function,
                        const char *from, const char *to, size_t line,
                        size_t column) {
  int *events = user;
  if (++*events <= 2)
    printf("  event %.6f %s %s -> %s at %zu:%zu\n", time, function, from, to,
           line, column);
}

int main(void) {
  mbexpr_error error = {0};
  mbexpr_program *program = NULL;
  mbexpr_model *model = NULL;
  const char *inputs[] = {"x", "v"};
  const char *text = "BISTOP(x, v, -1, 1, 1e5, 1.5, 50, 0.01) + 2*x";
  if (mbexpr_compile(text, inputs, 2, &program, &error) != MBEXPR_OK) {
    report("compile", &error);
    return 1;
  }
  printf("inputs: %zu (%s, %s)\n", mbexpr_program_input_count(program),
         mbexpr_program_input(program, 0), mbexpr_program_input(program, 1));

  /* One point, 5 mm into the upper wall, moving out at 0.7 m/s. */
  double point[] = {1.005, 0.7}, value, gradient[2], hessian[4];
  size_t wrt[] = {0, 1};
  mbexpr_value(program, point, &value, &error);
  printf("value %.12g\n", value);
  mbexpr_gradient(program, point, wrt, 2, &value, gradient, &error);
  printf("gradient %.12g %.12g\n", gradient[0], gradient[1]);
  mbexpr_hessian(program, point, wrt, 2, &value, gradient, hessian, &error);
  printf("hessian %.12g %.12g %.12g %.12g\n", hessian[0], hessian[1],
         hessian[2], hessian[3]);

  /* Four threads share the program; every one gets the serial results. */
  for (int p = 0; p < POINTS; p++) {
    xs[p] = -1.02 + 2.04 * p / (POINTS - 1);
    vs[p] = (p % 7) - 3.0;
  }
  static struct job jobs[4];
  pthread_t threads[4];
  for (int t = 0; t < 4; t++) {
    jobs[t].program = program;
    pthread_create(&threads[t], NULL, evaluate_all, &jobs[t]);
  }
  for (int t = 0; t < 4; t++) pthread_join(threads[t], NULL);
  static double serial[POINTS], parallel[POINTS], gradients[2 * POINTS];
  int status[POINTS];
  size_t failed = 9;
  const double *columns[] = {xs, vs};
  mbexpr_value_bulk(program, columns, POINTS, parallel, status, 0, &failed,
                    NULL);
  int agree = 1;
  for (int p = 0; p < POINTS; p++) {
    mbexpr_value(program, (double[]){xs[p], vs[p]}, &serial[p], NULL);
    for (int t = 0; t < 4; t++)
      agree &= jobs[t].code == MBEXPR_OK && jobs[t].values[p] == serial[p];
    agree &= parallel[p] == serial[p] && status[p] == 0;
  }
  printf("4 threads and every core agree with the serial values: %s (%zu failed)\n",
         agree ? "yes" : "no", failed);
  mbexpr_gradient_bulk(program, columns, POINTS, wrt, 2, parallel, gradients,
                       status, 2, &failed, NULL);
  mbexpr_gradient(program, (double[]){xs[9000], vs[9000]}, wrt, 2, &value,
                  gradient, NULL);
  printf("bulk gradient at point 9000 is the single one: %s\n",
         gradients[18000] == gradient[0] && gradients[18001] == gradient[1]
             ? "yes"
             : "no");
  mbexpr_program_free(program);

  /* A status per point: LOG fails at 0 and below. */
  const char *one[] = {"x"};
  mbexpr_compile("LOG(x) * 2", one, 1, &program, &error);
  double x[] = {1.0, 0.0, 2.0, -1.0}, values[4];
  const double *column[] = {x};
  mbexpr_value_bulk(program, column, 4, values, status, 1, &failed, &error);
  printf("bulk LOG: %.6f %.6f %.6f %.6f status %d %d %d %d failed %zu\n",
         values[0], values[1], values[2], values[3], status[0], status[1],
         status[2], status[3], failed);
  if (mbexpr_value(program, &x[1], &value, &error) == MBEXPR_ERROR)
    report("LOG(0)", &error);
  size_t bad[] = {3};
  if (mbexpr_gradient(program, x, bad, 1, &value, gradient, &error) ==
      MBEXPR_ERROR)
    report("direction 3", &error);
  mbexpr_program_free(program);

  /* Errors at their place, in the expression's own lines. */
  if (mbexpr_compile("STEP(x, 0, 0, 1,\n 10", one, 1, &program, &error) ==
      MBEXPR_ERROR)
    report("unclosed", &error);
  if (mbexpr_compile("IMPACT(x, 0, 1, 1e5, 1.5, 10, 0.1) + spped", one, 1,
                     &program, &error) == MBEXPR_ERROR)
    report("unknown name", &error);
  if (mbexpr_compile(NULL, one, 1, &program, &error) == MBEXPR_ERROR)
    report("null text", &error);

  /* Every error, as a list: three unknown names on two lines. */
  mbexpr_diagnostics *errors = NULL;
  if (mbexpr_compile_all("spped * x +\n  LOG(y) + z", one, 1, &program,
                         &errors) == MBEXPR_ERROR)
    print_list("compile_all", errors);
  if (mbexpr_compile_all("x + 1", one, 1, &program, &errors) == MBEXPR_OK)
    printf("compile_all of x + 1: %s\n", errors == NULL ? "no list" : "a list");
  mbexpr_program_free(program);
  if (mbexpr_compile_all("x + 1", one, 1, NULL, NULL) == MBEXPR_ERROR)
    printf("compile_all with no place for the program fails\n");
  if (mbexpr_model_from_text_all(
          "two\nDIFF/1, IC = 0, FUNCTION = STEP(TIME, 0, 0, 1)\n"
          "DIFF/2, IC = 0, FUNCTION = DIF(3) + VARVAL(9)\nEND\n",
          MBEXPR_DATASET, &model, &errors) == MBEXPR_ERROR)
    print_list("model_from_text_all", errors);
  if (mbexpr_model_load_all("missing.adm", &model, &errors) == MBEXPR_ERROR)
    print_list("model_load_all", errors);

  /* A model file checked: its problems with their lines and columns. */
  FILE *file = fopen("broken.adm", "w");
  fputs("broken\nDIFF/1, IC = 0, FUNCTION = STEP(TIME, 0, 0, 1)\n"
        "DIFF/2, IC = 0, FUNCTION = DIF(3) + VARVAL(9)\nEND\n",
        file);
  fclose(file);
  mbexpr_diagnostics *diagnostics = NULL;
  if (mbexpr_check_model("broken.adm", &diagnostics, &error) == MBEXPR_OK) {
    for (size_t i = 0; i < mbexpr_diagnostics_count(diagnostics); i++) {
      size_t line, column;
      const char *message = mbexpr_diagnostic(diagnostics, i, &line, &column);
      printf("broken.adm:%zu:%zu: %s\n", line, column, message);
    }
    mbexpr_diagnostics_free(diagnostics);
  }
  if (mbexpr_check_model("missing.adm", &diagnostics, &error) == MBEXPR_ERROR)
    report("missing", &error);

  /* A1 of the simulation study, simulated into the callbacks. */
  const char *a1 =
      "A1\nDIFF/1, IC = 0, FUNCTION = DIF(2)\n"
      "DIFF/2, IC = 5, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e5, 1.5, "
      "50, 0.01)\nEND\n";
  if (mbexpr_model_from_text(a1, MBEXPR_DATASET, &model, &error) !=
      MBEXPR_OK) {
    report("model", &error);
    return 1;
  }
  printf("columns:");
  for (size_t i = 0; i < mbexpr_model_column_count(model); i++)
    printf(" %s", mbexpr_model_column(model, i));
  printf("\n");
  mbexpr_settings settings = mbexpr_settings_default();
  settings.end = 1.0;
  settings.steps = 4;
  settings.rtol = 1e-8;
  mbexpr_summary summary;
  int counts[2] = {0, 0};
  if (mbexpr_simulate(model, &settings, print_row, NULL, &counts[0], &summary,
                      &error) != MBEXPR_OK)
    report("simulate", &error);
  mbexpr_simulate(model, &settings, NULL, print_event, &counts[1], NULL, NULL);
  printf("rows %d, events %zu (%d called back), steps > 0: %s, stopped %d\n",
         counts[0], summary.events, counts[1], summary.steps > 0 ? "yes" : "no",
         summary.stopped);
  settings.end = -1.0;
  if (mbexpr_simulate(model, &settings, print_row, NULL, &counts[0], NULL,
                      &error) == MBEXPR_ERROR)
    report("end -1", &error);
  mbexpr_model_free(model);

  /* The default method is auto: A4's ball lands in a damped stop at
   * t = 0.45, where the run turns stiff and auto takes Radau5. */
  const char *a4 =
      "A4\nDIFF/1, IC = 0, FUNCTION = DIF(2)\n"
      "DIFF/2, IC = 0, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e8, 1.5, "
      "1e6, 1e-5) - 9.81\nEND\n";
  if (mbexpr_model_from_text(a4, MBEXPR_DATASET, &model, &error) !=
      MBEXPR_OK) {
    report("A4", &error);
    return 1;
  }
  settings = mbexpr_settings_default();
  settings.end = 1.0;
  settings.steps = 10;
  int methods[] = {settings.method, MBEXPR_RADAU5, MBEXPR_DOP853};
  for (int m = 0; m < 3; m++) {
    settings.method = methods[m];
    if (mbexpr_simulate(model, &settings, NULL, NULL, NULL, &summary,
                        &error) != MBEXPR_OK)
      report("A4", &error);
    printf("A4 with method %d%s: %zu method change(s), %s steps\n",
           methods[m], methods[m] == MBEXPR_AUTO ? " (MBEXPR_AUTO)" : "",
           summary.method_changes,
           summary.steps < 2000 ? "fewer than 2000" : "2000 or more");
  }
  settings.method = 7;
  if (mbexpr_simulate(model, &settings, NULL, NULL, NULL, NULL, &error) ==
      MBEXPR_ERROR)
    report("method 7", &error);
  mbexpr_model_free(model);
  if (mbexpr_model_from_text("joint\nPART/1, GROUND\nUCON/1, FUNCTION = USER(1)\nEND\n",
                             MBEXPR_DATASET, &model, &error) == MBEXPR_ERROR)
    report("joint", &error);
  mbexpr_error_free(&error); /* freeing an empty error does nothing */
  return 0;
}
