#!/usr/bin/env python3
"""The sparse-core benchmark (issue 24): run by scripts/sparse_core.sh.

mbexpr simulate on the stack of N balls and the chain of free balls
(scripts/stack_models.py), both methods: CPU time, wall time, steps, time per
step and peak memory, one run each. Beside it, the stack as 2N DIFFs in
mbexpr and in scipy's BDF and Radau with jac_sparsity, each with its error
at t = 2 against a reference run (mbexpr radau at rtol 1e-10 on the DIFF
form), so that times are compared at equal error.

Usage: sparse_core.py MBEXPR [MAIN_MBEXPR]  (prints markdown tables)
"""

import os
import re
import resource
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import stack_models  # noqa: E402

END = 2.0
STATS = re.compile(r"(\d+) steps \((\d+) rejected\).*?(\d+) jacobians, (\d+) lu decompositions")


def run(binary, kind, n, method, rtol=1e-6, timeout=900, extra=()):
    """One run: (cpu s, wall s, steps, jacobians, lus, peak MB, last row) or None."""
    text = {"stack": stack_models.stack, "chain": stack_models.chain, "diff-stack": stack_models.diff_stack}[kind](n)
    with tempfile.NamedTemporaryFile("w", suffix=".adm", delete=False) as model:
        model.write(text)
    command = [binary, "simulate", model.name, "--end", str(END), "--steps", "1",
               "--method", method, "--rtol", str(rtol), "--format", "csv", *extra]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None
    finally:
        os.unlink(model.name)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    found = STATS.search(done.stderr)
    if done.returncode != 0 or not found:
        return {"failed": done.stderr.strip().splitlines()[-1] if done.stderr.strip() else "failed"}
    steps, _, jacobians, lus = map(int, found.groups())
    last = [float(x) for x in done.stdout.strip().splitlines()[-1].split(",")]
    return {"cpu": cpu, "wall": wall, "steps": steps, "jacobians": jacobians, "lus": lus,
            "memory": after.ru_maxrss / 1024.0, "last": last}


def impact(x, v, x1, k, e, cmax, d):
    """SPEC 3.3's IMPACT on plain floats (numpy arrays)."""
    import numpy as np
    p = np.maximum(x1 - x, 0.0)
    w = np.clip(p / d, 0.0, 1.0)
    damping = cmax * w * w * (3.0 - 2.0 * w)
    force = k * p ** e - damping * v
    return np.where(x < x1, np.maximum(force, 0.0), 0.0)


def scipy_stack(n, method, rtol):
    """The DIFF stack in scipy's solve_ivp with a sparse Jacobian pattern."""
    import numpy as np
    from scipy.integrate import solve_ivp
    from scipy.sparse import lil_matrix

    def rates(_t, y):
        z, v = y[:n], y[n:]
        gap = np.empty(n)
        speed = np.empty(n)
        gap[0], speed[0] = z[0], v[0]
        gap[1:], speed[1:] = z[1:] - z[:-1], v[1:] - v[:-1]
        free = np.full(n, 1.0)
        free[0] = 0.5
        push = impact(gap, speed, free, 1e6, 1.5, 1e5, 1e-3)
        a = push - 9.81
        a[:-1] -= push[1:]
        return np.concatenate([v, a])

    pattern = lil_matrix((2 * n, 2 * n))
    for k in range(n):
        pattern[k, n + k] = 1
        for j in range(max(0, k - 1), min(n, k + 2)):
            pattern[n + k, j] = 1
            pattern[n + k, n + j] = 1
    y0 = np.concatenate([[0.5 + stack_models.GAP + k * (1.0 + stack_models.GAP) for k in range(n)], np.zeros(n)])
    start = time.process_time()
    solution = solve_ivp(rates, (0.0, END), y0, method=method, rtol=rtol, atol=rtol * 1e-3,
                         jac_sparsity=pattern.tocsc())
    cpu = time.process_time() - start
    return {"cpu": cpu, "steps": int(solution.t.size - 1), "last": solution.y[:, -1], "ok": solution.success}


def ms(seconds, steps):
    return f"{1e3 * seconds / steps:.3g}"


def main():
    binary = sys.argv[1]
    main_binary = sys.argv[2] if len(sys.argv) > 2 else None
    print("| model | N | states | method | steps | jacobians | LUs | CPU s | wall s | ms/step | peak MB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    cases = [("stack", n, "radau") for n in (8, 32, 128, 512)]
    cases += [("stack", n, "dop853") for n in (8,)]
    cases += [("chain", n, method) for n in (32, 128) for method in ("radau", "dop853")]
    if main_binary:
        cases = [("main: stack", n, "radau") for n in (8, 16)] + cases
    for kind, n, method in cases:
        binary_here = main_binary if kind.startswith("main") else binary
        result = run(binary_here, kind.replace("main: ", ""), n, method)
        states = 13 * n
        if result is None:
            print(f"| {kind} | {n} | {states} | {method} | timed out | | | | | | |")
            continue
        if "failed" in result:
            print(f"| {kind} | {n} | {states} | {method} | {result['failed']} | | | | | | |")
            continue
        r = result
        print(f"| {kind} | {n} | {states} | {method} | {r['steps']} | {r['jacobians']} | {r['lus']} | "
              f"{r['cpu']:.3g} | {r['wall']:.3g} | {ms(r['cpu'], r['steps'])} | {r['memory']:.0f} |", flush=True)

    print()
    print("| the stack as 2N DIFFs | N | rtol | steps | CPU s | error in z at t = 2 |")
    print("|---|---|---|---|---|---|")
    for n in (32, 128):
        reference = run(binary, "diff-stack", n, "radau", rtol=1e-10)
        z_ref = reference["last"][1:1 + n]
        for rtol in (1e-4, 1e-6, 1e-8):
            r = run(binary, "diff-stack", n, "radau", rtol=rtol)
            error = max(abs(a - b) for a, b in zip(r["last"][1:1 + n], z_ref))
            print(f"| mbexpr radau | {n} | {rtol:g} | {r['steps']} | {r['cpu']:.3g} | {error:.2g} |", flush=True)
            for method in ("BDF", "Radau"):
                s = scipy_stack(n, method, rtol)
                error = max(abs(a - b) for a, b in zip(s["last"][:n], z_ref))
                ok = "" if s["ok"] else " (failed)"
                print(f"| scipy {method} | {n} | {rtol:g} | {s['steps']} | {s['cpu']:.3g} | {error:.2g}{ok} |", flush=True)


if __name__ == "__main__":
    main()
