"""Andrews' squeezing mechanism, error against run time (issue 25 item 7).

Run by scripts/joints_precision.sh, which installs what this needs. For
rtol = 1e-4 ... 1e-11 (atol = rtol * 1e-3):

- mbexpr `simulate examples/simulate/d_andrews.adm --end 0.03` with auto,
  radau and dop853 (the joints as Lagrange multipliers on 7 rigid parts in
  space, 10 revolute joints, 9 equations redundant); its wall time from its
  statistics (`--stats json`), the seven angles at t = 0.03 read from the
  parts' quaternions, their turns unwrapped over 300 output rows;
- scipy's solve_ivp Radau, BDF and DOP853 on the index-1 form of the test
  set's own equations (7 angles: q' = v, M(q) w + G(q)^T lam = f(q, v),
  G(q) w = -(G v)_q v, solved for w and lam at each right-hand side; G and
  the last term exact, from sympy; no projection), timed by perf_counter
  around solve_ivp.

The figure is the test set's mixed significant digits of the seven angles
against its published reference (PSIDE at 1e-14):
-log10 max |y - ref| / (1 + |ref|). Each time is the median of 3 runs.
Writes target/joints_precision/section.md.
"""

import json
import math
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import sympy
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import andrews_dataset as a  # noqa: E402  (the test set's constants)

OUT = ROOT / "target" / "joints_precision"
MBEXPR = Path(os.environ.get("MBEXPR", ROOT / "target" / "release" / "mbexpr"))
DATASET = ROOT / "examples" / "simulate" / "d_andrews.adm"
END = 0.03
ROWS = 300
REPEATS = 3
TOLERANCES = [10.0 ** -n for n in range(4, 12)]
START = [a.b, a.th, a.g, a.ph, a.de, a.om, a.ep]
REFERENCE = [0.1581077119629904e+2, -0.1575637105984298e+2, 0.4082224013073101e-1,
             -0.5347301163226948e+0, 0.5244099658805304e+0, 0.5347301163226948e+0,
             0.1048080741042263e+1]


def digits(angles):
    return -math.log10(max(abs(y - r) / (1 + abs(r)) for y, r in zip(angles, REFERENCE)))


# ---------------------------------------------------------------- mbexpr


def mbexpr_run(method, rtol):
    done = subprocess.run([str(MBEXPR), "simulate", str(DATASET), "--end", repr(END), "--steps", str(ROWS),
                           "--rtol", repr(rtol), "--atol", repr(rtol * 1e-3), "--method", method,
                           "--format", "csv", "--stats", "json"], capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        raise RuntimeError(done.stderr.strip().splitlines()[-1])
    stats = json.loads(done.stderr.strip().splitlines()[-1])
    lines = done.stdout.strip().splitlines()
    header = lines[0].split(",")
    turn = [0.0] * 7
    for line in lines[1:]:
        row = [float(cell) for cell in line.split(",")]
        for body in range(7):
            q0 = row[header.index(f"PART/{body + 2}.q0")]
            q3 = row[header.index(f"PART/{body + 2}.q3")]
            raw = 2 * math.atan2(q3, q0)
            turn[body] = raw + 2 * math.pi * round((turn[body] - raw) / (2 * math.pi))
    b0, t0, g0, p0, d0, o0, e0 = START
    beta = b0 + turn[0]
    delta = d0 + turn[4]
    epsilon = e0 + turn[6]
    angles = [beta, b0 + t0 + turn[1] - beta, g0 + turn[2], p0 + d0 + turn[3] - delta, delta,
              o0 + e0 + turn[5] - epsilon, epsilon]
    return angles, stats["wall_time"], stats["steps"], stats["rhs_evaluations"]


# ---------------------------------------------------------------- scipy, index 1


def index_one():
    """The right-hand side of the index-1 form of Ex_andrews.f's equations."""
    q = sympy.symbols("q0:7")
    v = sympy.symbols("v0:7")
    b, th, g, ph, de, om, ep = q
    bd, thd, gd, phd, ded, omd, epd = v
    m, i = a.m, a.i
    M = sympy.zeros(7, 7)
    M[0, 0] = m[0] * a.ra ** 2 + m[1] * (a.rr ** 2 - 2 * a.da * a.rr * sympy.cos(th) + a.da ** 2) + i[0] + i[1]
    M[1, 0] = M[0, 1] = m[1] * (a.da ** 2 - a.da * a.rr * sympy.cos(th)) + i[1]
    M[1, 1] = m[1] * a.da ** 2 + i[1]
    M[2, 2] = m[2] * (a.sa ** 2 + a.sb ** 2) + i[2]
    M[3, 3] = m[3] * (a.e - a.ea) ** 2 + i[3]
    M[4, 3] = M[3, 4] = m[3] * ((a.e - a.ea) ** 2 + a.zt * (a.e - a.ea) * sympy.sin(ph)) + i[3]
    M[4, 4] = (m[3] * (a.zt ** 2 + 2 * a.zt * (a.e - a.ea) * sympy.sin(ph) + (a.e - a.ea) ** 2)
               + m[4] * (a.ta ** 2 + a.tb ** 2) + i[3] + i[4])
    M[5, 5] = m[5] * (a.zf - a.fa) ** 2 + i[5]
    M[6, 5] = M[5, 6] = m[5] * ((a.zf - a.fa) ** 2 - a.u * (a.zf - a.fa) * sympy.sin(om)) + i[5]
    M[6, 6] = (m[5] * ((a.zf - a.fa) ** 2 - 2 * a.u * (a.zf - a.fa) * sympy.sin(om) + a.u ** 2)
               + m[6] * (a.ua ** 2 + a.ub ** 2) + i[5] + i[6])
    xd = a.sd * sympy.cos(g) + a.sc * sympy.sin(g) + a.xb
    yd = a.sd * sympy.sin(g) - a.sc * sympy.cos(g) + a.yb
    length = sympy.sqrt((xd - a.xc) ** 2 + (yd - a.yc) ** 2)
    force = -a.c0 * (length - a.l0) / length
    fx, fy = force * (xd - a.xc), force * (yd - a.yc)
    f = sympy.Matrix([
        a.mom - m[1] * a.da * a.rr * thd * (thd + 2 * bd) * sympy.sin(th),
        m[1] * a.da * a.rr * bd ** 2 * sympy.sin(th),
        fx * (a.sc * sympy.cos(g) - a.sd * sympy.sin(g)) + fy * (a.sd * sympy.cos(g) + a.sc * sympy.sin(g)),
        m[3] * a.zt * (a.e - a.ea) * ded ** 2 * sympy.cos(ph),
        -m[3] * a.zt * (a.e - a.ea) * phd * (phd + 2 * ded) * sympy.cos(ph),
        -m[5] * a.u * (a.zf - a.fa) * epd ** 2 * sympy.cos(om),
        m[5] * a.u * (a.zf - a.fa) * omd * (omd + 2 * epd) * sympy.cos(om),
    ])
    cos, sin = sympy.cos, sympy.sin
    constraints = sympy.Matrix([
        a.rr * cos(b) - a.d * cos(b + th) - a.ss * sin(g) - a.xb,
        a.rr * sin(b) - a.d * sin(b + th) + a.ss * cos(g) - a.yb,
        a.rr * cos(b) - a.d * cos(b + th) - a.e * sin(ph + de) - a.zt * cos(de) - a.xa,
        a.rr * sin(b) - a.d * sin(b + th) + a.e * cos(ph + de) - a.zt * sin(de) - a.ya,
        a.rr * cos(b) - a.d * cos(b + th) - a.zf * cos(om + ep) - a.u * sin(ep) - a.xa,
        a.rr * sin(b) - a.d * sin(b + th) - a.zf * sin(om + ep) + a.u * cos(ep) - a.ya,
    ])
    G = constraints.jacobian(q)
    curvature = -(G * sympy.Matrix(v)).jacobian(q) * sympy.Matrix(v)
    numeric = sympy.lambdify([q, v], [M, f, G, curvature], "numpy")

    def rhs(_t, y):
        position, velocity = y[:7], y[7:]
        mass, forces, jacobian, gamma = (np.asarray(x, dtype=float) for x in numeric(position, velocity))
        system = np.block([[mass, jacobian.T], [jacobian, np.zeros((6, 6))]])
        solved = np.linalg.solve(system, np.concatenate([forces.ravel(), gamma.ravel()]))
        return np.concatenate([velocity, solved[:7]])

    return rhs


def scipy_run(rhs, method, rtol):
    started = time.perf_counter()
    solution = solve_ivp(rhs, (0.0, END), START + [0.0] * 7, method=method, rtol=rtol, atol=rtol * 1e-3)
    elapsed = time.perf_counter() - started
    if not solution.success:
        raise RuntimeError(solution.message)
    return list(solution.y[:7, -1]), elapsed, solution.t.size - 1, solution.nfev


# ---------------------------------------------------------------- report


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    rhs = index_one()
    tools = [(f"mbexpr {method}", lambda rtol, method=method: mbexpr_run(method, rtol))
             for method in ("auto", "radau", "dop853")]
    tools += [(f"scipy {method} (index 1)", lambda rtol, method=method: scipy_run(rhs, method, rtol))
              for method in ("Radau", "BDF", "DOP853")]
    lines = [
        "| tool, method | rtol | digits | time (ms) | steps | rhs |",
        "|---|---|---|---|---|---|",
    ]
    for label, run in tools:
        for rtol in TOLERANCES:
            try:
                angles, first, steps, rhs_count = run(rtol)
                times = [first] + [run(rtol)[1] for _ in range(REPEATS - 1)]
            except (RuntimeError, subprocess.TimeoutExpired, np.linalg.LinAlgError) as error:
                lines.append(f"| {label} | {rtol:.0e} | fails: {error} | | | |")
                print(lines[-1], flush=True)
                continue
            lines.append(f"| {label} | {rtol:.0e} | {digits(angles):.2f} | {statistics.median(times) * 1e3:.3g} "
                         f"| {steps} | {rhs_count} |")
            print(lines[-1], flush=True)
    (OUT / "section.md").write_text("\n".join(lines) + "\n")
    print(f"written to {OUT / 'section.md'}")


if __name__ == "__main__":
    main()
