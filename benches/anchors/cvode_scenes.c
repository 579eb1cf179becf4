/*
 * The five scenes of the simulation study (issue 15's table) and issue 22's
 * variant with SUNDIALS
 * CVODE: BDF, Newton iterations with a dense analytic Jacobian, hand-coded
 * root functions at the branch switches of BISTOP and a restart
 * (CVodeReInit) at each root: what a careful engineer writes by hand.
 *
 * Each scene is x' = v, v' = BISTOP(x, v, x1, x2, k, e, cmax, d)
 * + spring x - gravity (m = 1), BISTOP as SPEC 3.3 defines it, held on one
 * branch between roots exactly as benches/hand/mod.rs does: in the gap; on
 * a side with the damping ramp, full damping, or clamped. p is the
 * penetration (x1 - x below, x - x2 above), p' its rate, c(p) the damping
 * and q = k p^e + c(p) p' the push; BISTOP is q below, -q above, 0 where
 * the clamp holds.
 *
 * Output as `mbexpr simulate --format csv` writes it: `time,DIF(1),DIF(2)`
 * rows at STEPS + 1 equally spaced times on standard output, one line of
 * statistics on standard error (the wall time covers the integration and
 * the rows, not the start of the process).
 *
 *   cc -O2 -o cvode_scenes benches/anchors/cvode_scenes.c \
 *      -lsundials_cvode -lsundials_nvecserial -lsundials_sunmatrixdense \
 *      -lsundials_sunlinsoldense -lm
 *   ./cvode_scenes a1_ball 1e-9 1e-12 199 [--events]
 *
 * Written for SUNDIALS 6 (Debian bookworm's libsundials-dev 6.4.1).
 */

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

typedef struct {
  const char *name;
  double x1, x2, k, e, cmax, d, spring, gravity, x0, v0, end;
} Scene;

static const Scene SCENES[] = {
    {"a1_ball", -1, 1, 1e5, 1.5, 50, 0.01, 0, 0, 0, 5, 10},
    {"a2_stiff_ball", -1, 1, 1e8, 2.2, 1e3, 1e-3, 0, 0, 0, 5, 10},
    {"a3_softening_ball", -1, 1, 1e6, 0.8, 10, 1e-3, 0, 0, 0, 5, 10},
    {"a4_dropped_ball", -1, 1, 1e8, 1.5, 1e6, 1e-5, 0, 9.81, 0, 0, 10},
    {"b_slider", -0.5, 0.5, 1e6, 1.5, 100, 0.005, 4, 0, 0.1, 0, 5},
    {"v_variant_ball", -0.7, 0.9, 3e5, 1.3, 80, 0.02, 0, 0, 0.1, -4, 8},
};

enum Piece { RAMP, FULL, CLAMPED };

/* The branch: side 0 is the gap, -1 the lower stop, +1 the upper. */
typedef struct {
  const Scene *scene;
  int side;
  enum Piece piece;
} Ball;

static const char *branch_name(int side, enum Piece piece) {
  static const char *names[2][3] = {
      {"lower stop, damping ramp", "lower stop, full damping", "lower stop, clamped"},
      {"upper stop, damping ramp", "upper stop, full damping", "upper stop, clamped"}};
  return side == 0 ? "free" : names[side > 0][piece];
}

/* Penetration p, its rate, the force's sign, k sign(p)|p|^e and its slope. */
typedef struct {
  double sign, p, rate, stiffness, slope;
} Contact;

static Contact contact(const Ball *ball, double x, double v) {
  const Scene *s = ball->scene;
  Contact c;
  c.sign = ball->side < 0 ? 1.0 : -1.0;
  c.p = c.sign * ((ball->side < 0 ? s->x1 : s->x2) - x);
  c.rate = -c.sign * v;
  double depth = fabs(c.p);
  c.stiffness = copysign(s->k * pow(depth, s->e), c.p);
  /* unbounded at p = 0 when e < 1: the smallest normal depth keeps it finite */
  c.slope = s->k * s->e * pow(fmax(depth, DBL_MIN), s->e - 1.0);
  return c;
}

/* Damping on a piece (the ramp's cubic continued past 0 and d) and dc/dp. */
static void damping(const Scene *s, enum Piece piece, double p, double *c, double *slope) {
  if (piece == RAMP) {
    double u = p / s->d;
    *c = s->cmax * u * u * (3.0 - 2.0 * u);
    *slope = s->cmax * 6.0 * u * (1.0 - u) / s->d;
  } else {
    *c = s->cmax;
    *slope = 0.0;
  }
}

static double acceleration(const Ball *ball, double x, double v) {
  const Scene *s = ball->scene;
  double a = s->spring * x - s->gravity;
  if (ball->side != 0 && ball->piece != CLAMPED) {
    Contact k = contact(ball, x, v);
    double c, slope;
    damping(s, ball->piece, k.p, &c, &slope);
    a += k.sign * (k.stiffness + c * k.rate);
  }
  return a;
}

static int rhs(sunrealtype t, N_Vector y, N_Vector dy, void *data) {
  (void)t;
  const Ball *ball = data;
  double x = NV_Ith_S(y, 0), v = NV_Ith_S(y, 1);
  NV_Ith_S(dy, 0) = v;
  NV_Ith_S(dy, 1) = acceleration(ball, x, v);
  return 0;
}

static int jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix jac, void *data,
                    N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t, (void)fy, (void)t1, (void)t2, (void)t3;
  const Ball *ball = data;
  double x = NV_Ith_S(y, 0), v = NV_Ith_S(y, 1);
  double dadx = ball->scene->spring, dadv = 0.0;
  if (ball->side != 0 && ball->piece != CLAMPED) {
    Contact k = contact(ball, x, v);
    double c, slope;
    damping(ball->scene, ball->piece, k.p, &c, &slope);
    dadx -= k.slope + slope * k.rate;
    dadv = -c;
  }
  SM_ELEMENT_D(jac, 0, 0) = 0.0;
  SM_ELEMENT_D(jac, 0, 1) = 1.0;
  SM_ELEMENT_D(jac, 1, 0) = dadx;
  SM_ELEMENT_D(jac, 1, 1) = dadv;
  return 0;
}

/* The switching values of the held branch, each positive while it holds. */
static int roots(sunrealtype t, N_Vector y, sunrealtype *g, void *data) {
  (void)t;
  const Ball *ball = data;
  const Scene *s = ball->scene;
  double x = NV_Ith_S(y, 0), v = NV_Ith_S(y, 1);
  g[2] = 1.0;
  if (ball->side == 0) {
    g[0] = x - s->x1;
    g[1] = s->x2 - x;
    return 0;
  }
  Contact k = contact(ball, x, v);
  double c, slope;
  g[0] = k.p;
  if (ball->piece == CLAMPED) {
    /* the push the law itself gives */
    if (k.p <= 0.0)
      c = 0.0;
    else
      damping(s, k.p < s->d ? RAMP : FULL, k.p, &c, &slope);
    g[1] = -(k.stiffness + c * k.rate);
  } else {
    damping(s, ball->piece, k.p, &c, &slope);
    g[1] = ball->piece == RAMP ? s->d - k.p : k.p - s->d;
    g[2] = k.stiffness + c * k.rate;
  }
  return 0;
}

/* The branch after root `index` of the held one. */
static void switch_branch(Ball *ball, int index, double x, double v) {
  if (ball->side == 0) {
    ball->side = index == 0 ? -1 : 1;
    ball->piece = RAMP;
  } else if (index == 0) {
    ball->side = 0;
  } else if (ball->piece == CLAMPED) {
    double p = contact(ball, x, v).p;
    ball->piece = p < ball->scene->d ? RAMP : FULL;
  } else if (index == 1) {
    ball->piece = ball->piece == RAMP ? FULL : RAMP;
  } else {
    ball->piece = CLAMPED;
  }
}

typedef struct {
  long steps, rejected, rhs, jacobians, setups;
} Counts;

static void add_counts(void *mem, Counts *total) {
  long steps, error_fails, newton_fails, rhs, jacobians, setups;
  CVodeGetNumSteps(mem, &steps);
  CVodeGetNumErrTestFails(mem, &error_fails);
  CVodeGetNumNonlinSolvConvFails(mem, &newton_fails);
  CVodeGetNumRhsEvals(mem, &rhs);
  CVodeGetNumJacEvals(mem, &jacobians);
  CVodeGetNumLinSolvSetups(mem, &setups);
  total->steps += steps;
  total->rejected += error_fails + newton_fails;
  total->rhs += rhs;
  total->jacobians += jacobians;
  total->setups += setups;
}

static int check(int flag, const char *what) {
  if (flag < 0) {
    fprintf(stderr, "error: %s failed with flag %d\n", what, flag);
    exit(1);
  }
  return flag;
}

int main(int argc, char **argv) {
  if (argc < 5) {
    fprintf(stderr, "usage: cvode_scenes SCENE RTOL ATOL STEPS [--events]\n");
    return 2;
  }
  const Scene *scene = NULL;
  for (size_t i = 0; i < sizeof SCENES / sizeof SCENES[0]; i++)
    if (strcmp(SCENES[i].name, argv[1]) == 0) scene = &SCENES[i];
  if (!scene) {
    fprintf(stderr, "error: no scene `%s`\n", argv[1]);
    return 2;
  }
  double rtol = atof(argv[2]), atol = atof(argv[3]);
  long steps = strtol(argv[4], NULL, 10);
  int list_events = argc > 5 && strcmp(argv[5], "--events") == 0;
  static char buffer[1 << 16];
  setvbuf(stdout, buffer, _IOFBF, sizeof buffer);
  printf("time,DIF(1),DIF(2)\n");

  struct timespec started, finished;
  clock_gettime(CLOCK_MONOTONIC, &started);
  SUNContext context;
  check(SUNContext_Create(NULL, &context), "SUNContext_Create");
  N_Vector y = N_VNew_Serial(2, context);
  NV_Ith_S(y, 0) = scene->x0;
  NV_Ith_S(y, 1) = scene->v0;
  Ball ball = {scene, 0, RAMP};
  void *mem = CVodeCreate(CV_BDF, context);
  check(CVodeInit(mem, rhs, 0.0, y), "CVodeInit");
  check(CVodeSStolerances(mem, rtol, atol), "CVodeSStolerances");
  check(CVodeSetUserData(mem, &ball), "CVodeSetUserData");
  check(CVodeSetMaxNumSteps(mem, -1), "CVodeSetMaxNumSteps");
  SUNMatrix matrix = SUNDenseMatrix(2, 2, context);
  SUNLinearSolver solver = SUNLinSol_Dense(y, matrix, context);
  check(CVodeSetLinearSolver(mem, solver, matrix), "CVodeSetLinearSolver");
  check(CVodeSetJacFn(mem, jacobian), "CVodeSetJacFn");
  check(CVodeRootInit(mem, 3, roots), "CVodeRootInit");
  int directions[3] = {-1, -1, -1}; /* from holding (+) to left (-) */
  check(CVodeSetRootDirection(mem, directions), "CVodeSetRootDirection");

  Counts counts = {0, 0, 0, 0, 0};
  long events = 0;
  printf("0,%.17g,%.17g\n", scene->x0, scene->v0);
  double t = 0.0;
  for (long output = 1; output <= steps;) {
    double t_out = scene->end * (double)output / (double)steps;
    int flag = check(CVode(mem, t_out, y, &t, CV_NORMAL), "CVode");
    if (flag == CV_ROOT_RETURN) {
      int found[3];
      check(CVodeGetRootInfo(mem, found), "CVodeGetRootInfo");
      int index = found[0] ? 0 : found[1] ? 1 : 2; /* leaving the stop first */
      const char *from = branch_name(ball.side, ball.piece);
      switch_branch(&ball, index, NV_Ith_S(y, 0), NV_Ith_S(y, 1));
      if (list_events)
        fprintf(stderr, "event t = %.17g: %s -> %s\n", t, from, branch_name(ball.side, ball.piece));
      events++;
      add_counts(mem, &counts);
      check(CVodeReInit(mem, t, y), "CVodeReInit");
      if (t < t_out) continue;
    }
    printf("%.17g,%.17g,%.17g\n", t_out, NV_Ith_S(y, 0), NV_Ith_S(y, 1));
    output++;
  }
  add_counts(mem, &counts);
  fflush(stdout);
  clock_gettime(CLOCK_MONOTONIC, &finished);
  double wall = (double)(finished.tv_sec - started.tv_sec) + 1e-9 * (double)(finished.tv_nsec - started.tv_nsec);
  fprintf(stderr,
          "%s: t = 0 .. %g, cvode-bdf: %ld steps (%ld rejected), %ld right-hand sides, %ld jacobians, "
          "%ld lu decompositions, %ld events, %.6f s\n",
          scene->name, scene->end, counts.steps, counts.rejected, counts.rhs, counts.jacobians, counts.setups,
          events, wall);
  CVodeFree(&mem);
  SUNLinSolFree(solver);
  SUNMatDestroy(matrix);
  N_VDestroy(y);
  SUNContext_Free(&context);
  return 0;
}
