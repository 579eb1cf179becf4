"""An independent reference for a ball between two BISTOP walls (issue 22).

    x'' = BISTOP(x, x', x1, x2, k, e, cmax, d),  m = 1

computed without mbexpr and without stepping over the weak singularity
that a real exponent `e` puts at every touch and release (the force goes
as `p^e`, the motion as `|t - t_touch|^(e + 2)`):

- in the gap the motion is free flight, exact: the touch time is a
  division;
- in contact the penetration `p` and its rate `r` are integrated by
  scipy's DOP853 at rtol 1e-13, on time stretched near the touch
  (`t = t_touch + tau^M`) and, on the way out, on the penetration itself
  stretched (`p = u^M`, integrated down to `u = 0`, the release, with the
  time as a state): `M e > 12`, so the force is smooth to 12 derivatives
  in the stretched variable;
- every branch switch inside a contact (the end of the damping ramp at
  `p = d`, the clamp where the raw force changes sign) is a terminal
  event, and each phase restarts on its new branch.

Prints `time,x,v` at STEPS + 1 equally spaced times from 0 to END, then
(on standard error) the times of touches and releases.

    scripts/ball_reference.sh X1 X2 K E CMAX D X0 V0 END STEPS
"""

import math
import sys

import numpy as np
from scipy.integrate import solve_ivp

RTOL, ATOL = 1e-13, 1e-16


def ramp(p, d):
    if p >= d:
        return 1.0
    w = p / d
    return w * w * (3.0 - 2.0 * w)


class Ball:
    def __init__(self, x1, x2, k, e, cmax, d):
        self.x1, self.x2, self.k, self.e, self.cmax, self.d = x1, x2, k, e, cmax, d
        self.M = max(1, math.ceil(12.5 / e))

    def raw(self, p, r, full):
        """The unclamped force pushing the penetration back, on a piece."""
        s = 1.0 if full else ramp(min(max(p, 0.0), self.d), self.d)
        if not full and p > self.d:
            # the ramp's cubic held past its end
            w = p / self.d
            s = w * w * (3.0 - 2.0 * w)
        return self.k * abs(p) ** self.e * math.copysign(1.0, p) + self.cmax * s * r

    def force(self, p, r, branch):
        full, clamped = branch
        return 0.0 if clamped else self.raw(p, r, full)

    def natural(self, p, r):
        full = p >= self.d and self.cmax != 0.0
        return (full, self.raw(p, r, full) <= 0.0)

    def contact(self, t0, r0, rows):
        """A contact entered at t0 with rate r0 > 0; returns (t_exit, r_exit)
        and appends (t, p, r) samples through `rows(t_from, t_to, fn)`."""
        M = self.M
        branch = self.natural(1e-300, r0)
        # Phase 1: t = t0 + tau^M until the rate has fallen to 0.8 r0 or
        # p has passed d / 2 (p well away from 0), branch switches as events.
        state = np.array([0.0, r0])
        tau = 0.0
        while True:
            def rhs(tau, y, branch=branch):
                jac = M * tau ** (M - 1)
                return [y[1] * jac, -self.force(y[0], y[1], branch) * jac]

            events = self.events(branch)
            done = lambda tau, y: min(y[1] - 0.8 * r0, 0.5 * self.d - y[0])
            done.terminal = True
            sol = solve_ivp(rhs, (tau, 10.0), state, method="DOP853", rtol=RTOL,
                            atol=ATOL, events=events + [done], dense_output=True)
            hit = self.first_event(sol, len(events))
            tau_end = sol.t[-1]
            rows(t0 + tau ** M, t0 + tau_end ** M,
                 lambda t, sol=sol: sol.sol(max(t - t0, 0.0) ** (1.0 / M)))
            tau, state = tau_end, sol.y[:, -1]
            if hit is None or hit == len(events):
                break
            branch = self.natural_after(state, branch, hit)
        # Phase 2: plain time until p < p_out on the way out (r < 0).
        t = t0 + tau ** M
        p_out = min(state[0], 0.25 * self.d)
        while True:
            def rhs(t, y, branch=branch):
                return [y[1], -self.force(y[0], y[1], branch)]

            events = self.events(branch)
            leave = lambda t, y: y[0] - p_out if y[1] < 0 else 1.0
            leave.terminal = True
            sol = solve_ivp(rhs, (t, t + 100.0), state, method="DOP853", rtol=RTOL,
                            atol=ATOL, events=events + [leave], dense_output=True)
            hit = self.first_event(sol, len(events))
            rows(t, sol.t[-1], sol.sol)
            t, state = sol.t[-1], sol.y[:, -1]
            if hit is None:
                raise RuntimeError("the ball stays in contact")
            if hit == len(events):
                break
            branch = self.natural_after(state, branch, hit)
        # Phase 3: p = u^M from u = p_out^(1/M) down to 0, the time a state.
        u = state[0] ** (1.0 / M)
        y = np.array([t, state[1]])
        while True:
            def rhs(u, y, branch=branch):
                jac = M * u ** (M - 1)
                return [jac / y[1], -self.force(u ** M, y[1], branch) / y[1] * jac]

            events = [lambda u, y, g=g: g(0.0, [u ** M, y[1]]) for g in self.events(branch)]
            for g in events:
                g.terminal = True
            sol = solve_ivp(rhs, (u, 0.0), y, method="DOP853", rtol=RTOL,
                            atol=ATOL, events=events, dense_output=True)
            hit = self.first_event(sol, len(events))
            self.rows_by_time(rows, sol, u, sol.t[-1])
            u, y = sol.t[-1], sol.y[:, -1]
            # (at u = 0 the raw force is 0: no switch is left to take)
            if hit is None or u <= 1e-12 * state[0] ** (1.0 / M):
                return y[0], y[1]
            branch = self.natural_after(np.array([u ** M, y[1]]), branch, hit)

    def rows_by_time(self, rows, sol, u_from, u_to):
        """Samples of phase 3 at given times: u found by bisection."""
        def at(t):
            lo, hi = u_to, u_from  # t increases as u decreases
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid == lo or mid == hi:
                    break
                if sol.sol(mid)[0] > t:
                    lo = mid
                else:
                    hi = mid
            uu = 0.5 * (lo + hi)
            y = sol.sol(uu)
            return np.array([uu ** self.M, y[1]])

        rows(sol.sol(u_from)[0], sol.sol(u_to)[0], at)

    def events(self, branch):
        full, clamped = branch
        out = []
        if self.cmax != 0.0:
            out.append(lambda t, y: (y[0] - self.d) if full else (self.d - y[0]))
        out.append(lambda t, y: -self.raw(y[0], y[1], full) if clamped
                   else self.raw(y[0], y[1], full))
        for g in out:
            g.terminal = True
            g.direction = -1
        return out

    def first_event(self, sol, count):
        if sol.status != 1:
            if sol.status < 0:
                raise RuntimeError(sol.message)
            return None
        times = [(te[0], i) for i, te in enumerate(sol.t_events) if len(te)]
        return min(times)[1] if times else None

    def natural_after(self, state, branch, hit):
        full, clamped = branch
        names = (["piece"] if self.cmax != 0.0 else []) + ["clamp"]
        if names[hit] == "piece":
            full = not full
        else:
            clamped = not clamped
        return (full, clamped)


def main():
    x1, x2, k, e, cmax, d, x0, v0, end = map(float, sys.argv[1:10])
    steps = int(sys.argv[10])
    ball = Ball(x1, x2, k, e, cmax, d)
    times = [end * i / steps for i in range(steps + 1)]
    out = {}

    def free(t_from, x, v, t_to):
        for t in times:
            if t_from <= t <= t_to and t not in out:
                out[t] = (x + v * (t - t_from), v)

    t, x, v = 0.0, x0, v0
    touches = []
    while t < end:
        if v < 0:
            wall, side = x1, -1.0
            t_touch = t + (x1 - x) / v
        else:
            wall, side = x2, 1.0
            t_touch = t + (x2 - x) / v
        free(t, x, v, min(t_touch, end))
        if t_touch >= end:
            break
        touches.append(t_touch)

        def rows(t_from, t_to, fn, wall=wall, side=side):
            for time in times:
                if t_from <= time <= t_to and time not in out:
                    p, r = fn(time)
                    out[time] = (wall + side * p, side * r)

        t_exit, r_exit = ball.contact(t_touch, abs(v), rows)
        touches.append(t_exit)
        t, x, v = t_exit, wall, side * r_exit
    print("time,x,v")
    for time in times:
        xv = out[time]
        print(f"{time!r},{float(xv[0])!r},{float(xv[1])!r}")
    print(" ".join(repr(float(t)) for t in touches), file=sys.stderr)


if __name__ == "__main__":
    main()
