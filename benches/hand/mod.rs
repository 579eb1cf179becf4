//! The five scenes of the simulation study (issue 15's table), written by
//! hand: what an engineer who knows the equations would write without
//! mbexpr, and what mbexpr's simulator is checked and timed against.
//!
//! Each scene is `x' = v`, `v' = BISTOP(x, v, x1, x2, k, e, cmax, d) +
//! spring x - gravity` (m = 1), with BISTOP as SPEC 3.3 defines it, in
//! penetration coordinates: on the side of the stop that is touched, `p`
//! is the penetration (`x1 - x` below, `x - x2` above), `p'` its rate,
//! `c(p)` the damping (`cmax s(p/d)` with the smooth step `s(u) = u²(3 -
//! 2u)` for `0 < p < d`, `cmax` from `p = d` on) and the *push* `q = k p^e
//! + c(p) p'` pushes the ball out while it is positive; BISTOP is `q`
//! below and `-q` above, and 0 where the clamp holds (`q <= 0`).
//!
//! Everything here is independent of `mbexpr::simulate` and
//! `mbexpr::laws`: the right-hand side, its Jacobian, the switching
//! functions and the event driver are written out by hand. Only the
//! integrators (`mbexpr::integrate`) are shared, so that the same methods
//! drive both programs.
//!
//! The driver holds the contact law on one branch through each step (gap;
//! on a side: damping ramp, full damping or clamped), each branch continued
//! smoothly past its boundaries (`p^e` as the odd `sign(p) |p|^e`, the
//! ramp's cubic as it is), so that the right-hand side is smooth within
//! every step. After each accepted step it looks at the branch's switching
//! values at four points of the step's continuous output; between two looks
//! at which a value is positive but its rate goes from falling to rising,
//! it looks at the value's minimum too (A1's clamp releases for 0.2 ms just
//! before the ball leaves the wall: both sign changes of the clamp's value
//! can fall inside one step). A sign change is located by the Illinois
//! method, the step is integrated again from its start to the switch, the
//! branch changes and a fresh integrator starts there.

use std::convert::Infallible;

use mbexpr::integrate::{IntegrateError, Method, Options, Stats, Stepper, System};
use nalgebra::DMatrix;

/// One scene: `x'' = BISTOP(x, x', x1, x2, k, e, cmax, d) + spring x -
/// gravity` for a unit mass, from `(x0, v0)` at time 0 to `end`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scene {
    /// The dataset's name, `examples/simulate/NAME.adm`.
    pub name: &'static str,
    /// The lower end of the gap.
    pub x1: f64,
    /// The upper end of the gap.
    pub x2: f64,
    /// Stiffness.
    pub k: f64,
    /// Exponent of the penetration.
    pub e: f64,
    /// Full damping coefficient.
    pub cmax: f64,
    /// Penetration at which the damping is full.
    pub d: f64,
    /// A spring term `spring x` (B: the centrifugal `w² s`).
    pub spring: f64,
    /// A constant downward acceleration (A4).
    pub gravity: f64,
    /// Initial position.
    pub x0: f64,
    /// Initial velocity.
    pub v0: f64,
    /// End time.
    pub end: f64,
}

/// The five scenes of issue 15's table, in its order, and the variant of
/// issue 22 (other walls, exponent, damping and start) that no method was
/// tuned to.
pub const SCENES: [Scene; 6] = [
    Scene {
        name: "a1_ball",
        x1: -1.0,
        x2: 1.0,
        k: 1e5,
        e: 1.5,
        cmax: 50.0,
        d: 0.01,
        spring: 0.0,
        gravity: 0.0,
        x0: 0.0,
        v0: 5.0,
        end: 10.0,
    },
    Scene {
        name: "a2_stiff_ball",
        x1: -1.0,
        x2: 1.0,
        k: 1e8,
        e: 2.2,
        cmax: 1e3,
        d: 1e-3,
        spring: 0.0,
        gravity: 0.0,
        x0: 0.0,
        v0: 5.0,
        end: 10.0,
    },
    Scene {
        name: "a3_softening_ball",
        x1: -1.0,
        x2: 1.0,
        k: 1e6,
        e: 0.8,
        cmax: 10.0,
        d: 1e-3,
        spring: 0.0,
        gravity: 0.0,
        x0: 0.0,
        v0: 5.0,
        end: 10.0,
    },
    Scene {
        name: "a4_dropped_ball",
        x1: -1.0,
        x2: 1.0,
        k: 1e8,
        e: 1.5,
        cmax: 1e6,
        d: 1e-5,
        spring: 0.0,
        gravity: 9.81,
        x0: 0.0,
        v0: 0.0,
        end: 10.0,
    },
    Scene {
        name: "b_slider",
        x1: -0.5,
        x2: 0.5,
        k: 1e6,
        e: 1.5,
        cmax: 100.0,
        d: 0.005,
        spring: 4.0,
        gravity: 0.0,
        x0: 0.1,
        v0: 0.0,
        end: 5.0,
    },
    Scene {
        name: "v_variant_ball",
        x1: -0.7,
        x2: 0.9,
        k: 3e5,
        e: 1.3,
        cmax: 80.0,
        d: 0.02,
        spring: 0.0,
        gravity: 0.0,
        x0: 0.1,
        v0: -4.0,
        end: 8.0,
    },
];

/// The side of the gap a contact is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    Lower,
    Upper,
}

/// The piece of the contact law in force on a side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Piece {
    /// `0 < p < d`: the damping ramps up with the penetration.
    Ramp,
    /// `p >= d`: full damping.
    Full,
    /// The push is not positive: no force.
    Clamped,
}

/// The branch the contact law is held on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Branch {
    Gap,
    Contact(Side, Piece),
}

impl Branch {
    /// Its name in event lists, as `mbexpr simulate --events` writes it.
    fn name(self) -> &'static str {
        match self {
            Branch::Gap => "free",
            Branch::Contact(Side::Lower, Piece::Ramp) => "lower stop, damping ramp",
            Branch::Contact(Side::Lower, Piece::Full) => "lower stop, full damping",
            Branch::Contact(Side::Lower, Piece::Clamped) => "lower stop, clamped",
            Branch::Contact(Side::Upper, Piece::Ramp) => "upper stop, damping ramp",
            Branch::Contact(Side::Upper, Piece::Full) => "upper stop, full damping",
            Branch::Contact(Side::Upper, Piece::Clamped) => "upper stop, clamped",
        }
    }
}

/// How many switching values each branch has (unused ones stay at 1).
const SWITCHES: usize = 3;

/// The least depth, relative to `d`, at which the stiffness's slope is
/// taken.
const SLOPE_DEPTH: f64 = 1e-6;

/// The steps near release, and near touch on a softening stop, relative
/// to the time the ball takes to cover its penetration (see
/// `Ball::step_cap`).
const GRADING: f64 = 0.5;

/// The least penetration, relative to `d`, to which the steps of a clamped
/// ball are graded.
const CLAMP_FLOOR: f64 = 1e-6;

/// Points of each step at which the switching values are looked at.
const LOOKS: usize = 4;

/// The ball of `scene` with its contact law held on `branch`: the system
/// the integrators see.
struct Ball<'s> {
    scene: &'s Scene,
    branch: Branch,
}

/// The contact law's quantities on one side at one state.
struct Contact {
    /// `+1` below (the force pushes towards `+x`), `-1` above.
    sign: f64,
    /// Penetration and its rate.
    p: f64,
    rate: f64,
    /// `k sign(p) |p|^e` and its derivative in `p`.
    stiffness: f64,
    stiffness_slope: f64,
}

impl Ball<'_> {
    fn contact(&self, side: Side, x: f64, v: f64) -> Contact {
        let scene = self.scene;
        let (sign, wall) = match side {
            Side::Lower => (1.0, scene.x1),
            Side::Upper => (-1.0, scene.x2),
        };
        let p = sign * (wall - x);
        let depth = p.abs();
        // The slope k e |p|^(e-1) is unbounded at p = 0 when e < 1. It is
        // taken no steeper than at a depth of SLOPE_DEPTH d: Radau5's
        // Newton iteration uses it across a step, in which the ball goes
        // deeper than that, and a far too steep one makes the first
        // increment so small that the iteration stops there and a wrong
        // step is accepted (A3 stuck at the wall).
        Contact {
            sign,
            p,
            rate: -sign * v,
            stiffness: (scene.k * depth.powf(scene.e)).copysign(p),
            stiffness_slope: scene.k
                * scene.e
                * depth.max(SLOPE_DEPTH * scene.d).powf(scene.e - 1.0),
        }
    }

    /// The damping coefficient on `piece` at penetration `p`, and its
    /// derivative in `p`; the ramp's cubic is continued past `0` and `d`.
    fn damping(&self, piece: Piece, p: f64) -> (f64, f64) {
        let (cmax, d) = (self.scene.cmax, self.scene.d);
        match piece {
            Piece::Ramp => {
                let u = p / d;
                (
                    cmax * u * u * (3.0 - 2.0 * u),
                    cmax * 6.0 * u * (1.0 - u) / d,
                )
            }
            Piece::Full | Piece::Clamped => (cmax, 0.0),
        }
    }

    /// The damping SPEC 3.3 gives at penetration `p` (none outside the
    /// stop, the ramp below `d`, full from `d` on) and its derivative.
    fn natural_damping(&self, p: f64) -> (f64, f64) {
        if p <= 0.0 {
            (0.0, 0.0)
        } else {
            self.damping(self.damping_piece(p), p)
        }
    }

    /// The piece SPEC 3.3 chooses for the damping at penetration `p > 0`.
    fn damping_piece(&self, p: f64) -> Piece {
        if p < self.scene.d {
            Piece::Ramp
        } else {
            Piece::Full
        }
    }

    /// The push `q = k p^e + c(p) p'` with damping `(c, dc/dp)`, and its
    /// rate of change, where `acceleration` is `v'`.
    fn push(&self, contact: &Contact, damping: (f64, f64), acceleration: f64) -> (f64, f64) {
        let (c, slope) = damping;
        let push = contact.stiffness + c * contact.rate;
        let rate = contact.stiffness_slope * contact.rate + slope * contact.rate * contact.rate
            - c * contact.sign * acceleration;
        (push, rate)
    }

    /// `v'` on the held branch.
    fn acceleration(&self, x: f64, v: f64) -> f64 {
        let scene = self.scene;
        let free = scene.spring * x - scene.gravity;
        match self.branch {
            Branch::Gap | Branch::Contact(_, Piece::Clamped) => free,
            Branch::Contact(side, piece) => {
                let contact = self.contact(side, x, v);
                let (c, _) = self.damping(piece, contact.p);
                free + contact.sign * (contact.stiffness + c * contact.rate)
            }
        }
    }

    /// The switching values of the held branch at `(x, v)` into `values`
    /// (each positive while the branch holds) and their rates of change
    /// into `rates`.
    fn switching(&self, x: f64, v: f64, values: &mut [f64], rates: &mut [f64]) {
        let scene = self.scene;
        let acceleration = self.acceleration(x, v);
        let (g, dg) = match self.branch {
            Branch::Gap => ([x - scene.x1, scene.x2 - x, 1.0], [v, -v, 0.0]),
            Branch::Contact(side, piece) => {
                let contact = self.contact(side, x, v);
                let (p, rate) = (contact.p, contact.rate);
                match piece {
                    Piece::Ramp | Piece::Full => {
                        let damping = self.damping(piece, p);
                        let (push, push_rate) = self.push(&contact, damping, acceleration);
                        let to_d = if piece == Piece::Ramp { 1.0 } else { -1.0 };
                        (
                            [p, to_d * (scene.d - p), push],
                            [rate, -to_d * rate, push_rate],
                        )
                    }
                    Piece::Clamped => {
                        // The push the law itself would give.
                        let damping = self.natural_damping(p);
                        let (push, push_rate) = self.push(&contact, damping, acceleration);
                        ([p, -push, 1.0], [rate, -push_rate, 0.0])
                    }
                }
            }
        };
        values.copy_from_slice(&g);
        rates.copy_from_slice(&dg);
    }

    /// The largest step at `(x, v)`, where a held branch would step over
    /// what it must see:
    /// - clamped, the ball moves freely out of the stop, and just before it
    ///   leaves the push turns positive again for a moment (A1: 0.2 ms):
    ///   each step covers at most `GRADING` of the remaining penetration
    ///   (down to `CLAMP_FLOOR d`), so that no step jumps that window;
    /// - on a softening stop (`e < 1`) the solution goes as `|t -
    ///   t_touch|^(e + 2)` near the times of touch and release, which no
    ///   step of polynomial order resolves: the steps shrink with the
    ///   penetration (`GRADING p / |p'|`) down to the step `h0` over which
    ///   that term stays below `atol`, `k |p'|^e h0^(e + 2) / ((e + 1)(e +
    ///   2)) = atol`.
    ///
    /// Unbounded elsewhere.
    fn step_cap(&self, x: f64, v: f64, atol: f64) -> f64 {
        let scene = self.scene;
        let Branch::Contact(side, piece) = self.branch else {
            return f64::INFINITY;
        };
        let contact = self.contact(side, x, v);
        let speed = contact.rate.abs();
        let graded = GRADING * contact.p.max(0.0) / speed;
        if piece == Piece::Clamped {
            graded.max(CLAMP_FLOOR * scene.d / speed)
        } else if scene.e < 1.0 {
            let e = scene.e;
            let h0 =
                (atol * (e + 1.0) * (e + 2.0) / (scene.k * speed.powf(e))).powf(1.0 / (e + 2.0));
            graded.max(h0)
        } else {
            f64::INFINITY
        }
    }

    /// The branch SPEC 3.3 chooses at `(x, v)`: `x1 <= x <= x2` is the
    /// gap, a push `q <= 0` the clamp.
    fn natural_branch(&self, x: f64, v: f64) -> Branch {
        let scene = self.scene;
        let side = if x < scene.x1 {
            Side::Lower
        } else if x > scene.x2 {
            Side::Upper
        } else {
            return Branch::Gap;
        };
        let contact = self.contact(side, x, v);
        let (c, _) = self.natural_damping(contact.p);
        if contact.stiffness + c * contact.rate <= 0.0 {
            Branch::Contact(side, Piece::Clamped)
        } else {
            Branch::Contact(side, self.damping_piece(contact.p))
        }
    }

    /// The branch after switching value `index` of the held branch has
    /// changed sign at `(x, v)`.
    fn next_branch(&self, index: usize, x: f64, v: f64) -> Branch {
        match (self.branch, index) {
            (Branch::Gap, 0) => Branch::Contact(Side::Lower, Piece::Ramp),
            (Branch::Gap, _) => Branch::Contact(Side::Upper, Piece::Ramp),
            (Branch::Contact(..), 0) => Branch::Gap,
            (Branch::Contact(side, Piece::Ramp), 1) => Branch::Contact(side, Piece::Full),
            (Branch::Contact(side, Piece::Full), 1) => Branch::Contact(side, Piece::Ramp),
            (Branch::Contact(side, Piece::Clamped), _) => {
                let p = self.contact(side, x, v).p;
                Branch::Contact(side, self.damping_piece(p))
            }
            (Branch::Contact(side, _), _) => Branch::Contact(side, Piece::Clamped),
        }
    }
}

impl System for Ball<'_> {
    type Error = Infallible;

    fn dimension(&self) -> usize {
        2
    }

    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        dy[0] = y[1];
        dy[1] = self.acceleration(y[0], y[1]);
        Ok(())
    }

    fn jacobian(
        &mut self,
        _t: f64,
        y: &[f64],
        _dy: &[f64],
        jac: &mut DMatrix<f64>,
    ) -> Result<(), Infallible> {
        let (x, v) = (y[0], y[1]);
        jac[(0, 1)] = 1.0;
        jac[(1, 0)] = self.scene.spring;
        if let Branch::Contact(side, piece) = self.branch
            && piece != Piece::Clamped
        {
            // v' = sign q(p, p') with p = sign (wall - x), p' = -sign v.
            let contact = self.contact(side, x, v);
            let (c, slope) = self.damping(piece, contact.p);
            jac[(1, 0)] -= contact.stiffness_slope + slope * contact.rate;
            jac[(1, 1)] = -c;
        }
        Ok(())
    }
}

/// A located branch switch: its time, the branch left and the branch taken.
pub type Event = (f64, &'static str, &'static str);

/// What a run cost and found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cost {
    /// The integrators' counts, over every restart.
    pub stats: Stats,
    /// The branch switches, in time order.
    pub events: Vec<Event>,
}

impl Cost {
    fn add(&mut self, stats: Stats) {
        let total = &mut self.stats;
        total.steps += stats.steps;
        total.rejected += stats.rejected;
        total.rhs_evaluations += stats.rhs_evaluations;
        total.rhs_failures += stats.rhs_failures;
        total.jacobian_evaluations += stats.jacobian_evaluations;
        total.lu_decompositions += stats.lu_decompositions;
    }
}

/// The switching values of `ball` on the step's continuous output at `t`,
/// with their rates.
struct Look {
    t: f64,
    values: [f64; SWITCHES],
    rates: [f64; SWITCHES],
}

fn look(ball: &Ball<'_>, stepper: &Stepper, t: f64) -> Look {
    let mut y = [0.0; 2];
    if t == stepper.t() {
        y.copy_from_slice(stepper.y());
    } else {
        stepper.dense(t, &mut y);
    }
    let mut values = [0.0; SWITCHES];
    let mut rates = [0.0; SWITCHES];
    ball.switching(y[0], y[1], &mut values, &mut rates);
    Look { t, values, rates }
}

/// A root of `f` in `[left, right]` where `f(left) >= 0 > f(right)`, by
/// the Illinois method, to about 1e-14 relative in time: the bracket's
/// right end (just past the sign change).
fn illinois(mut f: impl FnMut(f64) -> f64, mut left: f64, mut right: f64) -> f64 {
    let (mut f_left, mut f_right) = (f(left), f(right));
    let tolerance = 1e-14 * right.abs().max(1.0);
    let mut side = 0;
    for _ in 0..200 {
        if right - left <= tolerance {
            break;
        }
        let mut middle = right - f_right * (right - left) / (f_right - f_left);
        if !(middle > left && middle < right) {
            middle = 0.5 * (left + right);
        }
        let value = f(middle);
        if value < 0.0 {
            (right, f_right) = (middle, value);
            if side == -1 {
                f_left *= 0.5;
            }
            side = -1;
        } else {
            (left, f_left) = (middle, value);
            if side == 1 {
                f_right *= 0.5;
            }
            side = 1;
        }
    }
    right
}

/// The first sign change of an armed switching value in the last step of
/// `stepper`: its time and index. A value negative at the step's start (a
/// restart can lie a rounding error on the old side) is armed once it has
/// been seen non-negative.
fn first_switch(ball: &Ball<'_>, stepper: &Stepper, armed: &mut [bool]) -> Option<(f64, usize)> {
    let (t0, t1) = (stepper.t_previous(), stepper.t());
    let mut previous = look(ball, stepper, t0);
    for index in 1..=LOOKS {
        let t = if index == LOOKS {
            t1
        } else {
            t0 + (t1 - t0) * index as f64 / LOOKS as f64
        };
        let current = look(ball, stepper, t);
        let mut first: Option<(f64, usize)> = None;
        for (switch, _) in armed.iter().enumerate().filter(|(_, armed)| **armed) {
            let value = |t: f64| look(ball, stepper, t).values[switch];
            let past = if current.values[switch] < 0.0 {
                Some(current.t)
            } else if previous.rates[switch] < 0.0 && current.rates[switch] > 0.0 {
                // A minimum between the looks: is the value negative there?
                let lowest = illinois(
                    |t| -look(ball, stepper, t).rates[switch],
                    previous.t,
                    current.t,
                );
                (value(lowest) < 0.0).then_some(lowest)
            } else {
                None
            };
            if let Some(past) = past {
                let time = illinois(value, previous.t, past);
                // Leaving the stop (value 0) and the push reaching 0 come
                // together at p = 0: a tie goes to the lower index.
                let tie = 1e-12 * time.abs().max(1.0);
                if first.is_none_or(|(earliest, _)| time < earliest - tie) {
                    first = Some((time, switch));
                }
            }
        }
        if first.is_some() {
            return first;
        }
        for (armed, value) in armed.iter_mut().zip(current.values) {
            *armed |= value >= 0.0;
        }
        previous = current;
    }
    None
}

/// Integrates `scene` with `method` at `rtol`, `atol` from 0 to its end,
/// and hands `row` the state at `steps + 1` equally spaced times, from
/// each step's continuous output (the steps do not depend on the output
/// times), as `mbexpr simulate` does.
pub fn simulate(
    scene: &Scene,
    method: Method,
    rtol: f64,
    atol: f64,
    steps: usize,
    mut row: impl FnMut(f64, f64, f64),
) -> Result<Cost, IntegrateError<Infallible>> {
    let mut ball = Ball {
        scene,
        branch: Branch::Gap,
    };
    assert!(
        (scene.x1..=scene.x2).contains(&scene.x0),
        "the scenes start in the gap"
    );
    let options = Options {
        rtol,
        atol: atol.into(),
        max_steps: usize::MAX,
        ..Options::default()
    };
    let output_time = |index: usize| scene.end * index as f64 / steps as f64;
    let mut stepper = Stepper::new(
        method,
        options.clone(),
        0.0,
        &[scene.x0, scene.v0],
        &mut ball,
    )?;
    let mut cost = Cost::default();
    let mut armed = [true; SWITCHES];
    let mut next_output = 1;
    let mut state = [0.0; 2];
    row(0.0, scene.x0, scene.v0);
    while stepper.t() < scene.end {
        let start = [stepper.y()[0], stepper.y()[1]];
        stepper.set_h_max(ball.step_cap(start[0], start[1], atol));
        stepper.step_to(&mut ball, scene.end)?;
        let switch = first_switch(&ball, &stepper, &mut armed);
        let reached = switch.map_or(stepper.t(), |(time, _)| time);
        while next_output <= steps && output_time(next_output) <= reached {
            let time = output_time(next_output);
            if time == stepper.t() {
                state.copy_from_slice(stepper.y());
            } else {
                stepper.dense(time, &mut state);
            }
            row(time, state[0], state[1]);
            next_output += 1;
        }
        let Some((time, switch)) = switch else {
            continue;
        };
        // The step again, from its start to the switch, on the old branch.
        let t0 = stepper.t_previous();
        stepper.restart(t0, &start);
        while stepper.t() < time {
            stepper.step_to(&mut ball, time)?;
        }
        let (x, v) = (stepper.y()[0], stepper.y()[1]);
        // Where the integrated state is still on the held branch, the
        // switch was seen on a continuous output that strays from the
        // states (DOP853 at loose tolerances inside a stiff stop): go on
        // from there on the same branch. A switch located right at the
        // start of its step is the state lying a rounding error away from
        // the boundary: it is taken.
        let at_start = time - t0 <= 1e-10 * time.abs().max(1.0);
        if at_start || ball.natural_branch(x, v) != ball.branch {
            let next = ball.next_branch(switch, x, v);
            cost.events.push((time, ball.branch.name(), next.name()));
            ball.branch = next;
        }
        cost.add(stepper.stats());
        stepper = Stepper::new(method, options.clone(), time, &[x, v], &mut ball)?;
        let mut rates = [0.0; SWITCHES];
        let mut values = [0.0; SWITCHES];
        ball.switching(x, v, &mut values, &mut rates);
        armed = values.map(|value| value >= 0.0);
    }
    cost.add(stepper.stats());
    Ok(cost)
}
