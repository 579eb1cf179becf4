#!/usr/bin/env python3
"""Generate the reference table tests/data/reference.tsv for mbexpr.

The table checks the evaluator's value, gradient and Hessian for every function of
SPEC sections 3.1 to 3.5 (FORTRAN intrinsics, steps, IMPACT/BISTOP, series and
signals, arithmetic IF), the power operator and the constants PI, DTOR, RTOD.

How the numbers are made
------------------------
* Every function is written out below with mpmath, plainly, following SPEC.md (the
  section is named on each one), at 50 significant digits (``mp.dps = 50``).
* Each case carries BOTH the Adams expression text (what the Rust side parses) AND a
  Python lambda over mpmath numbers that computes the same thing with the functions
  below. The expression text is never parsed or evaluated here. Number literals are
  written identically in both, so both sides start from the same binary doubles;
  variable values are exact doubles too (written with Python's float repr).
* The power operator is Python's ``**`` on mpmath numbers, which has the same
  precedence and associativity as the Adams ``**`` (right-associative, binds tighter
  than unary minus: ``-x**2`` is ``-(x**2)``). mpmath raises a negative base to an
  integer-valued exponent exactly (``x**2.0`` is ``x*x`` for x < 0, as SPEC 3.1 asks of
  integer-valued constant exponents); a negative base to a non-integer power gives a
  complex number, which this script rejects as a domain error.
* Gradient and Hessian are computed by mpmath's high-precision numerical
  differentiation (``mpmath.diff``: central differences with a step of about 2**-176
  at several hundred bits of working precision), which gives far more than the 17
  printed digits for a function that is smooth around the point. Every case is
  therefore chosen a comfortable distance from kinks and branch switches, so that the
  result is the derivative of the active branch (SPEC 5).
  The one exception is the block of "kink" cases, placed exactly at a branch point to
  test the SPEC 5 rule "the derivative returned is the one of the branch the value was
  computed from". Such a case names the active branch explicitly (``branch=``, a lambda
  for the formula of that branch alone); the script checks that the full function and
  the branch give the same value and differentiates the branch.
* Self-checks: for the IMPACT/BISTOP cases with constant parameters and for STEP, the
  numerical derivatives are compared with the analytic formulas of SPEC 3.2/3.3 (the
  derivative table), to 1e-30; a mismatch aborts the run.

Tolerances (last column)
------------------------
The Rust test compares every entry as ``|got - want| <= tol * max(1, |want|)``. An f64
evaluator cannot do better than the conditioning of the problem allows, so for each case
the script measures it: each variable in turn is moved by one relative ulp (2**-52) up
and down, the value, gradient and Hessian are recomputed exactly, and the largest change
of an entry, measured as ``|change| / max(1, |want|)``, is the case's sensitivity ``s``.
The tolerance is ``max(floor, 16 * s)`` rounded up to one significant digit, where
``floor`` is 1e-13 unless the case says otherwise. The factor 16 leaves room for the
evaluator's own intermediate roundings (which act like such perturbations: ``x1 - d``,
``x2 + d``, ``2*pi*t`` are rounded in f64), so that a correct evaluator never fails.
Outcome: plain smooth cases get 1e-13; conditioning loosens it where it must, e.g.
  * TAN near pi/2, ASIN near 1, ``-1E4*(x-50)-10*v + ...``: 3e-13 .. 9e-13;
  * BISTOP in the damping ramp where the two Hessian terms ``k e (e-1) p^(e-2)`` and
    ``c''(x) x'`` nearly cancel (upper stop, e = 1.5, x = 1.06): 2e-11;
  * a penetration of 1e-8 with e = 0.8 (d2F/dx2 ~ p^(e-2) ~ 6e14): 5e-9;
  * the stiff/extreme cases with free length 1e6 and d = 1e-3: one ulp of x (1.2e-10)
    is 1e-7 of the damping ramp, and ``x1 - d`` itself is rounded by up to 6e-11 in
    f64, so the damping terms (c', c'') are only good to ~1e-7 .. 1e-6 of their size;
    the tolerance comes out 4e-6 .. 3e-5. It is relative to each entry's own size
    (max(1, |want|)), and in these rows every entry is dominated by its largest term,
    so this is a tolerance relative to the scale of the terms.
The measurement is skipped for the kink cases (a perturbation would cross the branch
point); they keep their floor.

Output
------
Tab-separated, one case per line, after a ``#`` comment block and a header line::

    expression  variables  wrt  value  gradient  hessian  tolerance

``variables`` is ``x=10.05;v=0.7``; ``wrt`` is ``x,v``; ``gradient`` is ``;``-separated in
wrt order; ``hessian`` has rows separated by ``|`` and entries by ``;`` (row-major, wrt
order). Numbers are the Python float repr of the exact result rounded to the nearest
double (17 significant digits or fewer). Lines starting with ``#`` are comments.

Requirements and regeneration
-----------------------------
Needs Python 3 and mpmath (``pip install mpmath``). The output is deterministic.
From the repository root::

    python3 scripts/reference_values.py > tests/data/reference.tsv
"""

import math
import sys

import mpmath
from mpmath import mp, mpf

mp.dps = 50


class DomainError(Exception):
    """An argument outside a function's domain (SPEC 3.1: an evaluation error)."""


def _require(ok, message):
    if not ok:
        raise DomainError(message)


# ---------------------------------------------------------------------------
# SPEC 2: constants. PI is mpmath's lazy constant (exact at any precision); DTOR and
# RTOD are fixed at 50 digits, which is far below anything printed.
# ---------------------------------------------------------------------------
PI = mp.pi
DTOR = mp.pi / 180
RTOD = 180 / mp.pi

# ---------------------------------------------------------------------------
# SPEC 3.1: FORTRAN intrinsics
# ---------------------------------------------------------------------------


def ABS(a):
    return abs(mpf(a))


def SIN(a):
    return mp.sin(a)


def COS(a):
    return mp.cos(a)


def TAN(a):
    return mp.tan(a)


def ASIN(a):
    _require(-1 <= a <= 1, "ASIN: argument outside [-1, 1]")
    return mp.asin(a)


def ACOS(a):
    _require(-1 <= a <= 1, "ACOS: argument outside [-1, 1]")
    return mp.acos(a)


def ATAN(a):
    return mp.atan(a)


def ATAN2(y, x):
    if y == 0 and x == 0:
        return mpf(0)  # [decided] ATAN2(0, 0) = 0 with zero partials
    return mp.atan2(y, x)


def SINH(a):
    return mp.sinh(a)


def COSH(a):
    return mp.cosh(a)


def TANH(a):
    return mp.tanh(a)


def EXP(a):
    return mp.exp(a)


def LOG(a):
    _require(a > 0, "LOG: argument must be positive")
    return mp.log(a)


def LOG10(a):
    _require(a > 0, "LOG10: argument must be positive")
    return mp.log10(a)


def SQRT(a):
    _require(a >= 0, "SQRT: negative argument")
    return mp.sqrt(a)


def AINT(a):
    """Truncation toward zero."""
    a = mpf(a)
    return mp.floor(a) if a >= 0 else mp.ceil(a)


def ANINT(a):
    """Nearest integer, halves away from zero."""
    a = mpf(a)
    r = mp.floor(abs(a) + mpf(1) / 2)
    return r if a >= 0 else -r


def DIM(a, b):
    """a - b if a > b, else 0."""
    return mpf(a) - b if a > b else mpf(0)


def MAX(*args):
    """Two or more arguments. (A tie keeps the first; no case here has a tie.)"""
    _require(len(args) >= 2, "MAX: needs at least two arguments")
    best = args[0]
    for a in args[1:]:
        if a > best:
            best = a
    return mpf(best)


def MIN(*args):
    _require(len(args) >= 2, "MIN: needs at least two arguments")
    best = args[0]
    for a in args[1:]:
        if a < best:
            best = a
    return mpf(best)


def MOD(a, b):
    """a - AINT(a/b)*b (sign of a)."""
    _require(b != 0, "MOD: b = 0")
    return a - AINT(mpf(a) / b) * b


def SIGN(a, b):
    """ABS(a) if b >= 0, else -ABS(a)."""
    return ABS(a) if b >= 0 else -ABS(a)


# ---------------------------------------------------------------------------
# SPEC 3.2: steps
# ---------------------------------------------------------------------------


def _check_step(name, x0, x1):
    _require(x0 < x1, f"{name}: x0 ({x0}) must be less than x1 ({x1})")


def STEP(x, x0, h0, x1, h1):
    _check_step("STEP", x0, x1)
    if x <= x0:
        return mpf(h0)
    if x >= x1:
        return mpf(h1)
    a = mpf(h1) - h0
    u = (x - mpf(x0)) / (mpf(x1) - x0)
    return h0 + a * u * u * (3 - 2 * u)


def STEP5(x, x0, h0, x1, h1):
    _check_step("STEP5", x0, x1)
    if x <= x0:
        return mpf(h0)
    if x >= x1:
        return mpf(h1)
    a = mpf(h1) - h0
    u = (x - mpf(x0)) / (mpf(x1) - x0)
    return h0 + a * u**3 * (10 - 15 * u + 6 * u**2)


def HAVSIN(x, x0, h0, x1, h1):
    _check_step("HAVSIN", x0, x1)
    if x <= x0:
        return mpf(h0)
    if x >= x1:
        return mpf(h1)
    u = (x - mpf(x0)) / (mpf(x1) - x0)
    return (mpf(h0) + h1) / 2 - (mpf(h1) - h0) / 2 * mp.cos(mp.pi * u)


# ---------------------------------------------------------------------------
# SPEC 3.3: IMPACT and BISTOP
# ---------------------------------------------------------------------------


def _check_contact(name, k, e, cmax, d):
    _require(k >= 0, f"{name}: k must be >= 0")
    _require(e > 0, f"{name}: e must be > 0")
    _require(cmax >= 0, f"{name}: cmax must be >= 0")
    _require(d > 0, f"{name}: d must be > 0")


def IMPACT(x, xd, x1, k, e, cmax, d):
    _check_contact("IMPACT", k, e, cmax, d)
    if x < x1:
        p = mpf(x1) - x  # penetration
        raw = k * p**e - STEP(x, x1 - mpf(d), cmax, x1, 0) * xd
        # max(raw, 0); raw == 0 belongs to the clamped branch (SPEC 5)
        return raw if raw > 0 else mpf(0)
    return mpf(0)  # x >= x1


def BISTOP(x, xd, x1, x2, k, e, cmax, d):
    _check_contact("BISTOP", k, e, cmax, d)
    _require(x1 < x2, "BISTOP: x1 must be less than x2")
    if x < x1:
        p = mpf(x1) - x
        raw = k * p**e - STEP(x, x1 - mpf(d), cmax, x1, 0) * xd
        return raw if raw > 0 else mpf(0)  # max(raw, 0)
    if x > x2:
        p = x - mpf(x2)
        raw = -k * p**e - STEP(x, x2, 0, x2 + mpf(d), cmax) * xd
        return raw if raw < 0 else mpf(0)  # min(raw, 0)
    return mpf(0)  # free gap x1 <= x <= x2 (x == x1 and x == x2 included, SPEC 5)


# ---------------------------------------------------------------------------
# SPEC 3.4: series and signals
# ---------------------------------------------------------------------------


def SHF(x, x0, a, w, phi, b):
    return a * mp.sin(w * (x - mpf(x0)) - phi) + b


def POLY(x, x0, *a):
    _require(1 <= len(a) <= 31, "POLY: 1 to 31 coefficients")
    u = x - mpf(x0)
    return mp.fsum(aj * u**j for j, aj in enumerate(a))


def CHEBY(x, x0, *a):
    _require(1 <= len(a) <= 31, "CHEBY: 1 to 31 coefficients")
    u = x - mpf(x0)
    t_prev, t = mpf(1), u  # T0, T1
    total = a[0] * t_prev
    for aj in a[1:]:
        total += aj * t
        t_prev, t = t, 2 * u * t - t_prev
    return total


def FORCOS(x, x0, w, a0, *a):
    _require(len(a) <= 30, "FORCOS: up to 31 coefficients")
    return a0 + mp.fsum(aj * mp.cos(j * w * (x - mpf(x0))) for j, aj in enumerate(a, start=1))


def FORSIN(x, x0, w, a0, *a):
    _require(len(a) <= 30, "FORSIN: up to 31 coefficients")
    return a0 + mp.fsum(aj * mp.sin(j * w * (x - mpf(x0))) for j, aj in enumerate(a, start=1))


def SWEEP(x, a, x0, f0, x1, f1, dx):
    _require(x0 < x1, "SWEEP: x0 must be less than x1")
    _require(dx > 0, "SWEEP: dx must be positive")
    x0, x1 = mpf(x0), mpf(x1)
    if x <= x0:
        phase = f0 * x
    elif x < x1:
        phase = f0 * x + (f1 - f0) * (x - x0) ** 2 / (2 * (x1 - x0))
    else:
        phase = f1 * x - (f1 - f0) * (x1 + x0) / 2
    return STEP5(x, x0, 0, x0 + dx, 1) * a * mp.sin(2 * mp.pi * phase)


# ---------------------------------------------------------------------------
# SPEC 3.5: arithmetic IF. The branches are passed as thunks: only the chosen one is
# evaluated, so the others may hold a domain error.
# ---------------------------------------------------------------------------


def IF(e1, negative, zero, positive):
    if e1 < 0:
        return negative()
    if e1 == 0:
        return zero()
    return positive()


# ---------------------------------------------------------------------------
# The cases
# ---------------------------------------------------------------------------


class Case:
    def __init__(self, expr, variables, fn, wrt=None, branch=None, floor=1e-13):
        self.expr = expr
        # "x=0.5 v=-1" -> ordered [(name, float)]
        self.variables = [(n, float(v)) for n, v in (p.split("=") for p in variables.split())]
        names = [n for n, _ in self.variables]
        self.wrt = wrt.split(",") if wrt else names
        assert all(w in names for w in self.wrt), expr
        self.fn = fn
        self.branch = branch
        self.floor = floor


CASES = []
SECTIONS = []  # (index into CASES, comment)


def section(comment):
    SECTIONS.append((len(CASES), comment))


def C(expr, variables, fn, **kw):
    CASES.append(Case(expr, variables, fn, **kw))


# ---- 3.1 intrinsics ---------------------------------------------------------
section("3.1 FORTRAN intrinsics")
for x in ("-2.5", "3.25"):
    C("ABS(x)", f"x={x}", lambda x: ABS(x))
C("ABS(x*v)", "x=-1.5 v=0.75", lambda x, v: ABS(x * v))

for x in ("0.5", "-2.0", "10.0"):
    C("SIN(x)", f"x={x}", lambda x: SIN(x))
C("SIN(x*y)", "x=0.3 y=1.7", lambda x, y: SIN(x * y))
for x in ("0.5", "-7.0"):
    C("COS(x)", f"x={x}", lambda x: COS(x))
C("COS(x)*SIN(y)", "x=0.4 y=-1.1", lambda x, y: COS(x) * SIN(y))
for x in ("0.3", "-1.2", "1.5"):
    C("TAN(x)", f"x={x}", lambda x: TAN(x))
for x in ("0.3", "0.99"):
    C("ASIN(x)", f"x={x}", lambda x: ASIN(x))
C("ASIN(x/y)", "x=0.5 y=2.0", lambda x, y: ASIN(x / y))
for x in ("0.2", "-0.7", "0.95"):
    C("ACOS(x)", f"x={x}", lambda x: ACOS(x))
for x in ("0.5", "-3.0", "100.0"):
    C("ATAN(x)", f"x={x}", lambda x: ATAN(x))
# ATAN2 in all four quadrants, on the positive x axis and on the positive y axis
# (not on the negative x axis, where atan2 jumps between pi and -pi).
for y, x in (("1.0", "2.0"), ("1.0", "-2.0"), ("-1.0", "-2.0"), ("-1.0", "2.0"), ("0.0", "3.0"), ("0.5", "0.0")):
    C("ATAN2(y, x)", f"y={y} x={x}", lambda y, x: ATAN2(y, x))
C("ATAN2(y, x)*RTOD", "y=-0.25 x=0.75", lambda y, x: ATAN2(y, x) * RTOD)
for x in ("0.5", "-2.0", "10.0"):
    C("SINH(x)", f"x={x}", lambda x: SINH(x))
for x in ("0.5", "-2.0", "10.0"):
    C("COSH(x)", f"x={x}", lambda x: COSH(x))
for x in ("0.5", "-2.0", "5.0"):
    C("TANH(x)", f"x={x}", lambda x: TANH(x))
for x in ("0.5", "20.0"):
    C("EXP(x)", f"x={x}", lambda x: EXP(x))
C("EXP(-x*x)", "x=0.8", lambda x: EXP(-x * x))
for x in ("0.5", "1000.0"):
    C("LOG(x)", f"x={x}", lambda x: LOG(x))
C("LOG(x*y)", "x=0.5 y=7.0", lambda x, y: LOG(x * y))
for x in ("0.5", "2.0", "12345.6"):
    C("LOG10(x)", f"x={x}", lambda x: LOG10(x))
for x in ("0.25", "10000.0"):
    C("SQRT(x)", f"x={x}", lambda x: SQRT(x))
C("SQRT(x*x + y*y)", "x=3.0 y=-4.0", lambda x, y: SQRT(x * x + y * y))
for x in ("2.7", "-2.7"):
    C("AINT(x)", f"x={x}", lambda x: AINT(x))
C("AINT(x*y) + x", "x=1.5 y=-3.1", lambda x, y: AINT(x * y) + x)
for x in ("2.4", "2.6", "-2.6"):
    C("ANINT(x)", f"x={x}", lambda x: ANINT(x))
C("DIM(x, y)", "x=3.0 y=1.0", lambda x, y: DIM(x, y))
C("DIM(x, y)", "x=1.0 y=3.0", lambda x, y: DIM(x, y))
C("DIM(x*x, 2.5)", "x=-2.0", lambda x: DIM(x * x, 2.5))
C("MAX(x, y)", "x=1.0 y=2.0", lambda x, y: MAX(x, y))
C("MAX(x, y)", "x=3.0 y=-1.0", lambda x, y: MAX(x, y))
for x, y, z in (("1.0", "2.0", "0.5"), ("-1.0", "-2.0", "-0.5")):
    C("MAX(x, y, z)", f"x={x} y={y} z={z}", lambda x, y, z: MAX(x, y, z))
C("MAX(x, 0.5, y*y)", "x=0.2 y=1.5", lambda x, y: MAX(x, 0.5, y * y))
C("MIN(x, y)", "x=1.0 y=2.0", lambda x, y: MIN(x, y))
C("MIN(x, y)", "x=3.0 y=-1.0", lambda x, y: MIN(x, y))
for x, y, z in (("1.0", "2.0", "0.5"), ("1.0", "-2.0", "0.5")):
    C("MIN(x, y, z)", f"x={x} y={y} z={z}", lambda x, y, z: MIN(x, y, z))
C("MIN(0, -1000*x - 10*v)", "x=-0.002 v=0.5", lambda x, v: MIN(0, -1000 * x - 10 * v))
for a, b in (("7.5", "2.0"), ("-7.5", "2.0"), ("7.5", "-2.0"), ("-7.5", "-2.0")):
    C("MOD(a, b)", f"a={a} b={b}", lambda a, b: MOD(a, b))
C("MOD(x, 2*PI)", "x=20.0", lambda x: MOD(x, 2 * PI))
for a, b in (("3.0", "2.0"), ("3.0", "-2.0"), ("-3.0", "2.0"), ("-3.0", "-2.0")):
    C("SIGN(a, b)", f"a={a} b={b}", lambda a, b: SIGN(a, b))
C("SIGN(x*x - 1, y)", "x=0.5 y=-0.1", lambda x, y: SIGN(x * x - 1, y))

# ---- power, constants, syntax details ----------------------------------------
section("power operator, constants, number syntax")
C("x**2", "x=-1.5", lambda x: x**2)
C("x**2.0", "x=-1.5", lambda x: x**2.0)  # integer-valued constant exponent: integer power
C("x**3", "x=0.7", lambda x: x**3)
C("x**-2", "x=0.5", lambda x: x**-2)
C("x**-2", "x=-2.0", lambda x: x**-2)
C("-x**2", "x=3.0", lambda x: -x**2)
C("(x-3)**3", "x=1.5", lambda x: (x - 3) ** 3)
C("(x-3)**3", "x=2.9", lambda x: (x - 3) ** 3)
C("x**0.5", "x=2.0", lambda x: x**0.5)
C("x**1.5", "x=0.3", lambda x: x**1.5)
C("x**y", "x=1.7 y=2.3", lambda x, y: x**y)
C("2**x", "x=-0.5", lambda x: 2**x)
C("x**y**2", "x=1.3 y=1.2", lambda x, y: x ** y**2)  # right-assoc: x**(y**2)
C("x*2**3**2", "x=0.25", lambda x: x * 2**3**2)  # 2**9
C("a*-x + - -y", "a=2.0 x=0.5 y=3.0", lambda a, x, y: a * -x + - -y)
C("+ -0.5*x**-1", "x=4.0", lambda x: + -0.5 * x**-1)
C("x/y/2", "x=3.0 y=0.25", lambda x, y: x / y / 2)
C("PI*x", "x=0.5", lambda x: PI * x)
C("DTOR*x", "x=45.0", lambda x: DTOR * x)
C("RTOD*x", "x=0.5", lambda x: RTOD * x)
C("SIN(x + 30D)", "x=0.1", lambda x: SIN(x + 30 * DTOR))
C("x*1.5D - -8.3E-03*RTOD", "x=2.0", lambda x: x * (1.5 * DTOR) - -8.3e-03 * RTOD)
C("sin(x) + Cos (x) + TaN(x)", "x=0.6", lambda x: SIN(x) + COS(x) + TAN(x))

# ---- 3.2 steps ----------------------------------------------------------------
section("3.2 STEP, STEP5, HAVSIN: before, inside and after the ramp")
for name, f in (("STEP", STEP), ("STEP5", STEP5), ("HAVSIN", HAVSIN)):
    for x in ("0.5", "1.25", "1.5", "2.5"):
        C(f"{name}(x, 1, 0, 2, 1)", f"x={x}", lambda x, f=f: f(x, 1, 0, 2, 1))
    # falling step with a negative start
    C(f"{name}(x, -1.0, 5.0, 3.0, -2.0)", "x=0.3", lambda x, f=f: f(x, -1.0, 5.0, 3.0, -2.0))
    # every argument a direction
    C(f"{name}(x, a, b, c, h)", "x=0.35 a=0.1 b=-2.0 c=0.9 h=3.0",
      lambda x, a, b, c, h, f=f: f(x, a, b, c, h))
    # parameters as variables, but x before / after the ramp: value is h0 / h1
    C(f"{name}(x, a, b, c, h)", "x=-0.5 a=0.1 b=-2.0 c=0.9 h=3.0",
      lambda x, a, b, c, h, f=f: f(x, a, b, c, h))
    C(f"{name}(x, a, b, c, h)", "x=1.5 a=0.1 b=-2.0 c=0.9 h=3.0",
      lambda x, a, b, c, h, f=f: f(x, a, b, c, h))
C("STEP(t, 0, 0, 0.1, 100)*SIN(x)", "t=0.04 x=0.7", lambda t, x: STEP(t, 0, 0, 0.1, 100) * SIN(x))
C("STEP (x, 1, 0, 2, 1)", "x=1.6", lambda x: STEP(x, 1, 0, 2, 1))

# ---- 3.3 IMPACT and BISTOP ---------------------------------------------------
# IMPACT(x, v, 1.0, 1000.0, e, 50.0, 0.1): free length 1, damping ramp over [0.9, 1].
# BISTOP(x, v, -1.0, 1.0, 1000.0, e, 50.0, 0.1): gap [-1, 1], ramps [-1.1, -1], [1, 1.1].
# (x, v) points, each far from x1, x1 - d and from raw == 0 for every e used:
IMPACT_POINTS = [
    ("free gap", "1.3", "-0.5"),
    ("ramp, approaching", "0.96", "-0.5"),
    ("beyond ramp, approaching", "0.7", "-0.3"),
    ("beyond ramp, separating slowly (raw > 0)", "0.75", "0.2"),
    ("ramp, fast separation: clamped", "0.97", "10.0"),
    ("beyond ramp, fast separation: clamped", "0.8", "40.0"),
]
BISTOP_POINTS = [
    ("gap", "0.2", "3.0"),
    ("lower ramp, approaching", "-1.04", "-0.5"),
    ("lower beyond ramp, approaching", "-1.3", "-0.3"),
    ("lower beyond ramp, separating slowly", "-1.25", "0.2"),
    ("lower ramp, fast separation: clamped", "-1.03", "10.0"),
    ("lower beyond ramp, fast separation: clamped", "-1.2", "40.0"),
    ("upper ramp, approaching", "1.06", "0.5"),
    ("upper beyond ramp, approaching", "1.3", "0.3"),
    ("upper beyond ramp, separating slowly", "1.25", "-0.2"),
    ("upper ramp, fast separation: clamped", "1.03", "-10.0"),
    ("upper beyond ramp, fast separation: clamped", "1.2", "-40.0"),
]
EXPONENTS = (1.0, 1.5, 2.2, 0.8)
# (expression, lambda, analytic) triples filled below; the analytic check is in selfcheck()
CONTACT_GRID = []

section("3.3 IMPACT: every branch, e = 1.0, 1.5, 2.2, 0.8")
for e in EXPONENTS:
    for _, x, v in IMPACT_POINTS:
        args = (1.0, 1000.0, e, 50.0, 0.1)
        C(f"IMPACT(x, v, 1.0, 1000.0, {e!r}, 50.0, 0.1)", f"x={x} v={v}",
          lambda x, v, e=e: IMPACT(x, v, 1.0, 1000.0, e, 50.0, 0.1))
        CONTACT_GRID.append((CASES[-1], "IMPACT", args))
section("3.3 BISTOP: every branch, e = 1.0, 1.5, 2.2, 0.8")
for e in EXPONENTS:
    for _, x, v in BISTOP_POINTS:
        args = (-1.0, 1.0, 1000.0, e, 50.0, 0.1)
        C(f"BISTOP(x, v, -1.0, 1.0, 1000.0, {e!r}, 50.0, 0.1)", f"x={x} v={v}",
          lambda x, v, e=e: BISTOP(x, v, -1.0, 1.0, 1000.0, e, 50.0, 0.1))
        CONTACT_GRID.append((CASES[-1], "BISTOP", args))

section("3.3 stiff and extreme contact cases")
# k = 1e6, d = 1e-3, penetration 2e-4 (inside the ramp), free length 0 as in real models
C("IMPACT(x, v, 0, 1e6, 1.5, 100.0, 1e-3)", "x=-0.0002 v=-0.1",
  lambda x, v: IMPACT(x, v, 0, 1e6, 1.5, 100.0, 1e-3))
C("IMPACT(x, v, 0, 1e6, 1.5, 100.0, 1e-3)", "x=-0.0015 v=-0.1",
  lambda x, v: IMPACT(x, v, 0, 1e6, 1.5, 100.0, 1e-3))
# free length x1 = 1e6, d = 1e-3: x1 - d and x - x1 lose ~7 digits in f64 (see docstring)
C("IMPACT(x, v, 1e6, 1e8, 2.2, 1000.0, 1e-3)", "x=999999.9996 v=-0.05",
  lambda x, v: IMPACT(x, v, 1e6, 1e8, 2.2, 1000.0, 1e-3))
C("IMPACT(x, v, 1e6, 1e8, 1.5, 1000.0, 1e-3)", "x=999999.9985 v=-0.05",
  lambda x, v: IMPACT(x, v, 1e6, 1e8, 1.5, 1000.0, 1e-3))
C("BISTOP(x, v, -1e6, 1e6, 1e7, 1.5, 500.0, 1e-3)", "x=1000000.0003 v=0.02",
  lambda x, v: BISTOP(x, v, -1e6, 1e6, 1e7, 1.5, 500.0, 1e-3))
# very small penetration with a softening exponent: dF/dx ~ p^(e-1) is large
C("BISTOP(x, v, -0.01, 0.01, 1e6, 0.8, 10.0, 1e-3)", "x=-0.01000001 v=-0.001",
  lambda x, v: BISTOP(x, v, -0.01, 0.01, 1e6, 0.8, 10.0, 1e-3))
C("BISTOP(x, v, -0.01, 0.01, 1e6, 1.5, 10.0, 1e-3)", "x=0.0100001 v=0.001",
  lambda x, v: BISTOP(x, v, -0.01, 0.01, 1e6, 1.5, 10.0, 1e-3))

section("3.3 contact parameters as derivative directions")
C("IMPACT(x, v, 1.0, k, e, c, 0.1)", "x=0.94 v=-0.4 k=2000.0 e=1.5 c=30.0",
  lambda x, v, k, e, c: IMPACT(x, v, 1.0, k, e, c, 0.1))
C("IMPACT(x, v, 1.0, k, e, c, 0.1)", "x=0.8 v=-0.4 k=2000.0 e=2.2 c=30.0",
  lambda x, v, k, e, c: IMPACT(x, v, 1.0, k, e, c, 0.1))
C("BISTOP(x, v, a, b, k, e, c, s)", "x=1.04 v=0.3 a=-0.5 b=1.0 k=500.0 e=1.5 c=20.0 s=0.1",
  lambda x, v, a, b, k, e, c, s: BISTOP(x, v, a, b, k, e, c, s))
C("BISTOP(x, v, a, b, k, e, c, s)", "x=-0.56 v=-0.3 a=-0.5 b=1.0 k=500.0 e=0.8 c=20.0 s=0.1",
  lambda x, v, a, b, k, e, c, s: BISTOP(x, v, a, b, k, e, c, s))
C("BISTOP(x, v, a, b, k, e, c, s)", "x=0.3 v=-0.3 a=-0.5 b=1.0 k=500.0 e=0.8 c=20.0 s=0.1",
  lambda x, v, a, b, k, e, c, s: BISTOP(x, v, a, b, k, e, c, s))
# only some variables are directions
C("IMPACT(x, v, 1.0, k, e, 50.0, 0.1)", "x=0.93 v=-0.2 k=1000.0 e=1.5", wrt="k,e",
  fn=lambda x, v, k, e: IMPACT(x, v, 1.0, k, e, 50.0, 0.1))

section("3.3 composed arguments (nested STEP, deformation from two coordinates)")
C("BISTOP(x, v, -1.0, 1.0, STEP(t, 0, 1E3, 1, 2E3), 1.5, STEP(t, 0, 0, 1, 50), 0.1)",
  "x=1.06 v=0.4 t=0.3",
  lambda x, v, t: BISTOP(x, v, -1.0, 1.0, STEP(t, 0, 1e3, 1, 2e3), 1.5, STEP(t, 0, 0, 1, 50), 0.1))
C("BISTOP(x, v, -1.0, 1.0, STEP(t, 0, 1E3, 1, 2E3), 1.5, STEP(t, 0, 0, 1, 50), 0.1)",
  "x=-1.2 v=-0.4 t=0.6",
  lambda x, v, t: BISTOP(x, v, -1.0, 1.0, STEP(t, 0, 1e3, 1, 2e3), 1.5, STEP(t, 0, 0, 1, 50), 0.1))
C("IMPACT(x - y, v - w, 0.5, 1E4, 2.2, 20, 0.05)", "x=1.0 y=0.53 v=0.1 w=0.4",
  lambda x, y, v, w: IMPACT(x - y, v - w, 0.5, 1e4, 2.2, 20, 0.05))
C("-IMPACT(x, v, 0, 1E5, 1.5, 10, 0.01) + STEP(x, -0.02, 0, 0, 1)", "x=-0.004 v=-0.3",
  lambda x, v: -IMPACT(x, v, 0, 1e5, 1.5, 10, 0.01) + STEP(x, -0.02, 0, 0, 1))

# ---- 3.4 series and signals ----------------------------------------------------
section("3.4 SHF, POLY, CHEBY, FORCOS, FORSIN, SWEEP")
for x in ("0.0", "0.9", "-2.3"):
    C("SHF(x, 0.5, 2.0, 3.0, 0.25, 1.0)", f"x={x}", lambda x: SHF(x, 0.5, 2.0, 3.0, 0.25, 1.0))
C("SHF(t, q, a, w, h, b)", "t=0.7 q=0.1 a=1.5 w=6.0 h=0.4 b=-0.2",
  lambda t, q, a, w, h, b: SHF(t, q, a, w, h, b))
C("SHF(t, 0, 0.01, 2*PI*50, 0, 0)", "t=0.0123", lambda t: SHF(t, 0, 0.01, 2 * PI * 50, 0, 0))
for x in ("0.0", "1.5", "-1.25"):
    C("POLY(x, 1.0, 2, -3, 0.5, 1.25)", f"x={x}", lambda x: POLY(x, 1.0, 2, -3, 0.5, 1.25))
C("POLY(x, 0, 7)", "x=3.0", lambda x: POLY(x, 0, 7))
C("POLY(x, y, a, b, c)", "x=2.0 y=0.5 a=1.0 b=-2.0 c=0.75", lambda x, y, a, b, c: POLY(x, y, a, b, c))
_c31 = [(-1) ** j / (j + 1) for j in range(31)]  # 1, -1/2, 1/3, ... (31 coefficients)
_c31_text = ", ".join(repr(c) for c in _c31)
C(f"POLY(x, 0.1, {_c31_text})", "x=0.6", lambda x: POLY(x, 0.1, *_c31))
for x in ("0.25", "1.0", "2.5"):
    C("CHEBY(x, 0.5, 1, 2, 3, 4)", f"x={x}", lambda x: CHEBY(x, 0.5, 1, 2, 3, 4))
C("CHEBY(x, y, a, b, c)", "x=0.8 y=0.1 a=1.0 b=-2.0 c=0.75", lambda x, y, a, b, c: CHEBY(x, y, a, b, c))
C(f"CHEBY(x, 0.1, {_c31_text})", "x=0.6", lambda x: CHEBY(x, 0.1, *_c31))
for x in ("0.0", "0.3", "-1.1"):
    C("FORCOS(x, 0.2, 2.0, 1.0, 0.5, 0.25, 0.125)", f"x={x}", lambda x: FORCOS(x, 0.2, 2.0, 1.0, 0.5, 0.25, 0.125))
C("FORCOS(t, 0, w, a, b, c)", "t=0.4 w=3.0 a=0.5 b=-1.0 c=2.0", lambda t, w, a, b, c: FORCOS(t, 0, w, a, b, c))
for x in ("0.0", "0.3", "-1.1"):
    C("FORSIN(x, 0.2, 2.0, 1.0, 0.5, 0.25, 0.125)", f"x={x}", lambda x: FORSIN(x, 0.2, 2.0, 1.0, 0.5, 0.25, 0.125))
C("FORSIN(t, 0, w, a, b, c)", "t=0.4 w=3.0 a=0.5 b=-1.0 c=2.0", lambda t, w, a, b, c: FORSIN(t, 0, w, a, b, c))
# SWEEP(x, a, x0, f0, x1, f1, dx): before x0 (0), in the amplitude ramp, mid sweep, after x1
for t in ("0.5", "1.2", "2.0", "4.1"):
    C("SWEEP(t, 2.0, 1.0, 0.5, 3.0, 2.0, 0.5)", f"t={t}", lambda t: SWEEP(t, 2.0, 1.0, 0.5, 3.0, 2.0, 0.5))
# amplitude ramp longer than the sweep: past x1 but still ramping
C("SWEEP(t, 1, 0, 1, 1, 5, 2)", "t=1.6", lambda t: SWEEP(t, 1, 0, 1, 1, 5, 2))
C("SWEEP(t, a, 0, 1, 2, g, 0.25)", "t=0.9 a=0.3 g=4.0", lambda t, a, g: SWEEP(t, a, 0, 1, 2, g, 0.25))

# ---- 3.5 IF ------------------------------------------------------------------
section("3.5 arithmetic IF (the branches not taken may hold domain errors)")
C("IF(x-1: a*x**2, 0, SQRT(x))", "x=0.5 a=3.0",
  lambda x, a: IF(x - 1, lambda: a * x**2, lambda: mpf(0), lambda: SQRT(x)))
C("IF(x-1: a*x**2, 0, SQRT(x))", "x=-2.0 a=3.0",
  lambda x, a: IF(x - 1, lambda: a * x**2, lambda: mpf(0), lambda: SQRT(x)))
C("IF(x-1: a*x**2, 0, SQRT(x))", "x=4.0 a=3.0",
  lambda x, a: IF(x - 1, lambda: a * x**2, lambda: mpf(0), lambda: SQRT(x)))
C("IF(x: SQRT(-x), 0, SQRT(x))", "x=-4.0", lambda x: IF(x, lambda: SQRT(-x), lambda: mpf(0), lambda: SQRT(x)))
C("IF(x: SQRT(-x), 0, SQRT(x))", "x=9.0", lambda x: IF(x, lambda: SQRT(-x), lambda: mpf(0), lambda: SQRT(x)))
C("IF (t-2: 0, 0, 1)*x", "t=1.0 x=3.0", lambda t, x: IF(t - 2, lambda: mpf(0), lambda: mpf(0), lambda: mpf(1)) * x)
C("IF(x: -x, 0, IF(x-2: x**2, 4, 4 + LOG(x-1)))", "x=1.5",
  lambda x: IF(x, lambda: -x, lambda: mpf(0),
               lambda: IF(x - 2, lambda: x**2, lambda: mpf(4), lambda: 4 + LOG(x - 1))))
C("IF(x: -x, 0, IF(x-2: x**2, 4, 4 + LOG(x-1)))", "x=3.0",
  lambda x: IF(x, lambda: -x, lambda: mpf(0),
               lambda: IF(x - 2, lambda: x**2, lambda: mpf(4), lambda: 4 + LOG(x - 1))))

# ---- composed --------------------------------------------------------------------
section("composed expressions")
C("-1E4*(x-50)-10*v + 3*sin(2*pi*t)", "x=50.25 v=0.7 t=0.3",
  lambda x, v, t: -1e4 * (x - 50) - 10 * v + 3 * SIN(2 * PI * t))
C("-1E4*(x-50)-10*v + 3*sin(2*pi*t)", "x=49.8 v=-1.2 t=1.7",
  lambda x, v, t: -1e4 * (x - 50) - 10 * v + 3 * SIN(2 * PI * t))
C("EXP(-t/0.5)*COS(2*PI*t)", "t=0.35", lambda t: EXP(-t / 0.5) * COS(2 * PI * t))
C("k*(x-y)**2/2 + c*ABS(v)*v", "k=200.0 x=0.3 y=-0.1 c=4.0 v=-0.6",
  lambda k, x, y, c, v: k * (x - y) ** 2 / 2 + c * ABS(v) * v)
C("STEP(x, 0, 0, 1, 1)*SIN(t) + STEP5(t, 0, 1, 2, 3)*HAVSIN(x, 0, -1, 1, 1)", "x=0.4 t=0.9",
  lambda x, t: STEP(x, 0, 0, 1, 1) * SIN(t) + STEP5(t, 0, 1, 2, 3) * HAVSIN(x, 0, -1, 1, 1))
C("MAX(0, -1E3*x - 10*v) + MIN(x, v)**2", "x=-0.05 v=0.2",
  lambda x, v: MAX(0, -1e3 * x - 10 * v) + MIN(x, v) ** 2)
C("ATAN2(SIN(x), COS(x)*y) + SQRT(1 + x**2)", "x=2.0 y=0.5",
  lambda x, y: ATAN2(SIN(x), COS(x) * y) + SQRT(1 + x**2))
C("LOG10(1 + x**2)/TANH(y) - ACOS(x/2)", "x=0.8 y=1.3",
  lambda x, y: LOG10(1 + x**2) / TANH(y) - ACOS(x / 2))
# a bound variable that the expression does not use has derivative 0 (SPEC 5)
C("SIN(x)", "x=0.5 y=2.0", lambda x, y: SIN(x))

# ---- kinks ------------------------------------------------------------------------
section("at a kink: derivatives of the branch the value was computed from (SPEC 5)")
C("STEP(x, 1, 0, 2, 1)", "x=1.0", lambda x: STEP(x, 1, 0, 2, 1), branch=lambda x: mpf(0))
C("STEP(x, 1, 0, 2, 1)", "x=2.0", lambda x: STEP(x, 1, 0, 2, 1), branch=lambda x: mpf(1))
C("STEP5(x, 1, 0, 2, 1)", "x=1.0", lambda x: STEP5(x, 1, 0, 2, 1), branch=lambda x: mpf(0))
C("HAVSIN(x, 1, 0, 2, 1)", "x=2.0", lambda x: HAVSIN(x, 1, 0, 2, 1), branch=lambda x: mpf(1))
# x == x1 and x == x2 belong to BISTOP's free gap; x == x1 to IMPACT's zero part
C("BISTOP(x, v, -1.0, 1.0, 1000.0, 1.0, 50.0, 0.1)", "x=-1.0 v=-2.0",
  lambda x, v: BISTOP(x, v, -1.0, 1.0, 1000.0, 1.0, 50.0, 0.1), branch=lambda x, v: mpf(0))
C("BISTOP(x, v, -1.0, 1.0, 1000.0, 1.0, 50.0, 0.1)", "x=1.0 v=2.0",
  lambda x, v: BISTOP(x, v, -1.0, 1.0, 1000.0, 1.0, 50.0, 0.1), branch=lambda x, v: mpf(0))
C("IMPACT(x, v, 1.0, 1000.0, 1.0, 50.0, 0.1)", "x=1.0 v=-2.0",
  lambda x, v: IMPACT(x, v, 1.0, 1000.0, 1.0, 50.0, 0.1), branch=lambda x, v: mpf(0))
# raw == 0 exactly (all operations exact in f64): the clamped branch, all zero
C("IMPACT(x, v, 1.0, 2.0, 1.0, 1.0, 0.25)", "x=0.5 v=1.0",
  lambda x, v: IMPACT(x, v, 1.0, 2.0, 1.0, 1.0, 0.25), branch=lambda x, v: mpf(0))
C("BISTOP(x, v, -1.0, 1.0, 2.0, 1.0, 1.0, 0.25)", "x=1.5 v=-1.0",
  lambda x, v: BISTOP(x, v, -1.0, 1.0, 2.0, 1.0, 1.0, 0.25), branch=lambda x, v: mpf(0))
# IF takes the branch of the sign of e1; e1 == 0 here, and the other branches divide by 0
C("IF(x-1: 1/(x-1), 5*x**2, 1/(x-1))", "x=1.0",
  lambda x: IF(x - 1, lambda: 1 / (x - 1), lambda: 5 * x**2, lambda: 1 / (x - 1)),
  branch=lambda x: 5 * x**2)
C("DIM(x, y)", "x=2.0 y=2.0", lambda x, y: DIM(x, y), branch=lambda x, y: mpf(0))
C("SIGN(x, y)", "x=-3.0 y=0.0", lambda x, y: SIGN(x, y), branch=lambda x, y: ABS(x))
C("ATAN2(y, x)", "y=0.0 x=0.0", lambda y, x: ATAN2(y, x), branch=lambda y, x: mpf(0))
C("ANINT(x)", "x=2.5", lambda x: ANINT(x), branch=lambda x: mpf(3))
C("ANINT(x)", "x=-2.5", lambda x: ANINT(x), branch=lambda x: mpf(-3))
C("AINT(x)", "x=-3.0", lambda x: AINT(x), branch=lambda x: mpf(-3))


# ---------------------------------------------------------------------------
# Evaluation
# ---------------------------------------------------------------------------


def _real(r, expr):
    if not isinstance(r, mpmath.mpf):
        raise DomainError(f"{expr}: result is not real ({r!r})")
    if not mp.isfinite(r):
        raise DomainError(f"{expr}: result is not finite")
    return r


def evaluate(case, values, fn):
    """(value, gradient, hessian) of fn at values (dict name -> float), exact to ~40 digits."""
    wrt = case.wrt

    def f(*w):
        args = {n: mpf(x) for n, x in values.items()}
        args.update(zip(wrt, w))
        return _real(fn(**args), case.expr)

    point = [mpf(values[w]) for w in wrt]
    n = len(wrt)

    def order(*idx):
        o = [0] * n
        for i in idx:
            o[i] += 1
        return o

    value = f(*point)
    grad = [_real(mp.diff(f, point, order(i)), case.expr) for i in range(n)]
    hess = [[None] * n for _ in range(n)]
    for i in range(n):
        for j in range(i, n):
            hess[i][j] = hess[j][i] = _real(mp.diff(f, point, order(i, j)), case.expr)
    return value, grad, hess


def _entries(result):
    value, grad, hess = result
    return [value] + grad + [h for row in hess for h in row]


def _round_up_1digit(t):
    exp = math.floor(math.log10(t))
    mant = math.ceil(round(t / 10**exp, 9))
    if mant >= 10:
        mant, exp = 1, exp + 1
    return float(f"{mant}e{exp}")


def tolerance(case, values, result):
    if case.branch is not None:
        return case.floor
    want = _entries(result)
    sens = mpf(0)
    for name, x in values.items():
        if x == 0:
            continue
        for s in (1, -1):
            moved = dict(values)
            moved[name] = mpf(x) * (1 + s * mpf(2) ** -52)
            got = _entries(evaluate(case, moved, case.fn))
            for g, w in zip(got, want):
                sens = max(sens, abs(g - w) / max(1, abs(w)))
    return _round_up_1digit(max(case.floor, 16 * float(sens)))


def _flush(result, expr):
    """Set to exact 0 the entries that are numerical-differentiation noise.

    An entry whose exact value is 0 (e.g. d2/dx2 of ATAN2(y, x) at x = 0, or SWEEP's
    sine at a whole number of periods) comes out of mpmath.diff as something like 1e-63.
    Entries below 1e-35 of the row's largest entry are such noise; the script aborts if
    an entry falls between 1e-35 and 1e-28 of it, where the call would be unclear."""
    value, grad, hess = result
    scale = max([mpf(1)] + [abs(r) for r in _entries(result)])

    def clean(r):
        if abs(r) <= scale * mpf(10) ** -35:
            return mpf(0)
        assert abs(r) > scale * mpf(10) ** -28, (expr, r)
        return r

    return clean(value), [clean(g) for g in grad], [[clean(h) for h in row] for row in hess]


def compute(case):
    values = dict(case.variables)
    result = evaluate(case, values, case.fn)
    if case.branch is not None:
        full_value = result[0]
        result = evaluate(case, values, case.branch)
        assert abs(full_value - result[0]) <= mpf(10) ** -40, case.expr
    result = _flush(result, case.expr)
    return result, tolerance(case, values, result)


# ---------------------------------------------------------------------------
# Self-checks against the analytic formulas of SPEC 3.2 / 3.3
# ---------------------------------------------------------------------------


def _step_derivs(x, x0, h0, x1, h1):
    """STEP value and first/second derivatives in x (SPEC 3.2, cubic)."""
    x, x0, h0, x1, h1 = map(mpf, (x, x0, h0, x1, h1))
    if x <= x0:
        return h0, mpf(0), mpf(0)
    if x >= x1:
        return h1, mpf(0), mpf(0)
    a, L = h1 - h0, x1 - x0
    u = (x - x0) / L
    return h0 + a * u * u * (3 - 2 * u), a * 6 * u * (1 - u) / L, a * 6 * (1 - 2 * u) / L**2


def _contact_analytic(kind, x, v, args):
    """The derivative table of SPEC 3.3, for (x, x')."""
    x, v = mpf(x), mpf(v)
    zero = (mpf(0), [mpf(0)] * 2, [[mpf(0)] * 2 for _ in range(2)])
    if kind == "IMPACT":
        x1, k, e, cmax, d = map(mpf, args)
        x2 = None
    else:
        x1, x2, k, e, cmax, d = map(mpf, args)
    if x < x1:
        p, sgn = x1 - x, 1
        c, c1, c2 = _step_derivs(x, x1 - d, cmax, x1, 0)
    elif x2 is not None and x > x2:
        p, sgn = x - x2, -1
        c, c1, c2 = _step_derivs(x, x2, 0, x2 + d, cmax)
    else:
        return zero
    raw = sgn * k * p**e - c * v
    if (sgn == 1 and raw <= 0) or (sgn == -1 and raw >= 0):
        return zero
    fx = -k * e * p ** (e - 1) - c1 * v
    fxx = sgn * k * e * (e - 1) * p ** (e - 2) - c2 * v
    return raw, [fx, -c], [[fxx, -c1], [-c1, mpf(0)]]


def selfcheck(results):
    tol = mpf(10) ** -30
    for case, kind, args in CONTACT_GRID:
        values = dict(case.variables)
        want = _entries(_contact_analytic(kind, values["x"], values["v"], args))
        got = _entries(results[id(case)][0])
        for g, w in zip(got, want):
            assert abs(g - w) <= tol * max(1, abs(w)), (case.expr, values, got, want)
    # STEP-family cases with a single variable x: compare STEP against the formula
    for case in CASES:
        if case.expr == "STEP(x, 1, 0, 2, 1)" and case.branch is None:
            x = dict(case.variables)["x"]
            v, d1, d2 = _step_derivs(x, 1, 0, 2, 1)
            got = _entries(results[id(case)][0])
            for g, w in zip(got, [v, d1, d2]):
                assert abs(g - w) <= tol * max(1, abs(w)), (case.expr, x, got)


# ---------------------------------------------------------------------------
# Output
# ---------------------------------------------------------------------------


def fmt(x):
    f = float(x)
    if f == 0:
        f = 0.0  # no "-0.0"
    return repr(f)


HEADER_COMMENT = """\
# Reference values for mbexpr: value, gradient and Hessian of expressions covering
# every function of SPEC 3.1-3.5, the power operator and the constants.
# GENERATED FILE - do not edit by hand. Regenerate from the repository root with
#     python3 scripts/reference_values.py > tests/data/reference.tsv
# (needs Python 3 and mpmath; the script's docstring explains the method and the
# choice of the tolerance column).
# Columns are tab-separated. variables: name=value;... ; wrt: derivative directions;
# gradient: ';'-separated in wrt order; hessian: rows '|'-separated, entries
# ';'-separated. Compare each entry as |got - want| <= tolerance * max(1, |want|).
# Lines starting with '#' are comments."""


def main():
    results = {}
    for case in CASES:
        results[id(case)] = compute(case)
    selfcheck(results)

    out = sys.stdout
    out.write(HEADER_COMMENT + "\n")
    out.write("\t".join(["expression", "variables", "wrt", "value", "gradient", "hessian", "tolerance"]) + "\n")
    comments = dict(SECTIONS)
    for i, case in enumerate(CASES):
        if i in comments:
            out.write(f"# --- {comments[i]}\n")
        (value, grad, hess), tol = results[id(case)]
        variables = ";".join(f"{n}={v!r}" for n, v in case.variables)
        row = [
            case.expr,
            variables,
            ",".join(case.wrt),
            fmt(value),
            ";".join(fmt(g) for g in grad),
            "|".join(";".join(fmt(h) for h in r) for r in hess),
            repr(tol),
        ]
        assert all("\t" not in c and "\n" not in c for c in row)
        out.write("\t".join(row) + "\n")
    print(f"{len(CASES)} cases", file=sys.stderr)


if __name__ == "__main__":
    main()
