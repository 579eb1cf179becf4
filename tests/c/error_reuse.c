/* One mbexpr_error passed to failing call after failing call without being
 * freed between them: each failure frees the message the error held before
 * writing its own, and a success leaves the error as it was, so the error
 * is freed once, at the end. Run under valgrind, which finds no byte lost. */
#include <stdio.h>

#include "mbexpr.h"

static void show(const char *what, int code, const mbexpr_error *error) {
  printf("%s: %s", what, code == MBEXPR_OK ? "ok" : "error");
  if (error->message != NULL)
    printf(", %zu:%zu: %s", error->line, error->column, error->message);
  printf("\n");
}

int main(void) {
  mbexpr_error error = {0};
  mbexpr_program *program = NULL;
  mbexpr_model *model = NULL;
  const char *inputs[] = {"x"};
  const char *broken[] = {"1 +", "STEP(x, 0, 0, 1)", "LOG(y)"};
  for (size_t i = 0; i < 3; i++)
    show(broken[i], mbexpr_compile(broken[i], inputs, 1, &program, &error),
         &error);
  show("missing.adm", mbexpr_model_load("missing.adm", &model, &error),
       &error);
  show("2 * x", mbexpr_compile("2 * x", inputs, 1, &program, &error), &error);
  mbexpr_program_free(program);
  program = NULL;
  double point[] = {-1.0}, value = 0.0;
  show("LOG(x) at -1",
       mbexpr_compile("LOG(x)", inputs, 1, &program, &error) == MBEXPR_OK
           ? mbexpr_value(program, point, &value, &error)
           : MBEXPR_OK,
       &error);
  mbexpr_program_free(program);
  const char *ball = "A1\nDIFF/1, IC = 0, FUNCTION = DIF(2)\n"
                     "DIFF/2, IC = 5, FUNCTION = -DIF(1)\nEND\n";
  if (mbexpr_model_from_text(ball, MBEXPR_DATASET, &model, &error) ==
      MBEXPR_OK) {
    mbexpr_settings settings = mbexpr_settings_default();
    settings.end = 1.0;
    settings.steps = 10;
    settings.rtol = -1.0;
    show("rtol -1", mbexpr_simulate(model, &settings, NULL, NULL, NULL, NULL,
                                    &error),
         &error);
    settings.rtol = 0.0;
    settings.end = -1.0;
    show("end -1", mbexpr_simulate(model, &settings, NULL, NULL, NULL, NULL,
                                   &error),
         &error);
    mbexpr_model_free(model);
  }
  mbexpr_error_free(&error);
  printf("freed once: the message is %s\n",
         error.message == NULL ? "NULL" : "still set");
  return 0;
}
