//! `STEP`, `STEP5` and `HAVSIN` (SPEC 3.2): `h0` for `x <= x0`, `h1` for
//! `x >= x1`, a smooth ramp between. The rule `x0 < x1` is checked by the caller.

use std::f64::consts::{FRAC_PI_2, PI};

use super::range::{difference, fraction, interpolate, product, ratio};
use crate::catalog::Function;
use crate::number::Number;

/// Which ramp.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// `STEP`: cubic, continuous first derivative.
    Cubic,
    /// `STEP5`: quintic, continuous second derivative.
    Quintic,
    /// `HAVSIN`: half a cosine wave, continuous first derivative.
    Haversine,
}

impl Shape {
    /// The shape of `STEP`, `STEP5` or `HAVSIN`.
    pub fn of(function: Function) -> Shape {
        match function {
            Function::Step5 => Shape::Quintic,
            Function::Havsin => Shape::Haversine,
            _ => Shape::Cubic,
        }
    }
}

/// Which part of a step applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepBranch {
    /// `x <= x0`: `h0`.
    Before,
    /// `x0 < x < x1`: the ramp.
    Ramp,
    /// `x >= x1`: `h1`.
    After,
}

impl StepBranch {
    /// The branch at `x` (SPEC 5: `x <= x0` is before, `x >= x1` after).
    pub fn of(x: f64, x0: f64, x1: f64) -> StepBranch {
        if x <= x0 {
            StepBranch::Before
        } else if x >= x1 {
            StepBranch::After
        } else {
            StepBranch::Ramp
        }
    }
}

/// `STEP(x, x0, h0, x1, h1)` and its siblings: the branch from the real
/// part of `x` (SPEC 5), then [`step_on`] that branch.
pub fn step<T: Number>(shape: Shape, x: &T, x0: &T, h0: &T, x1: &T, h1: &T) -> T {
    let branch = StepBranch::of(x.value(), x0.value(), x1.value());
    step_on(branch, shape, x, x0, h0, x1, h1)
}

/// The step on `branch`: `h0`, `h1`, or on the ramp `h0 + (h1 - h0) s(u)`
/// with `u = (x - x0)/(x1 - x0)`, whose polynomial (or cosine) continues
/// past `[x0, x1]` when the simulator holds it there.
///
/// `u` and the rise are taken in halves where `x1 - x0` or `h1 - h0` passes
/// the range of a double, and the shape `s(u)` has its own derivatives (in
/// `1 - u` computed from `x1`, so that they keep their digits near `x1`).
/// With constant ends and heights (the usual case, and the utility's) the
/// step is one function of `x` whose slopes `(h1 - h0) s'(u) / L` and
/// `(h1 - h0) s''(u) / L^2` are each one `product`, so a ramp
/// 1e-300 wide or 1e308 high gives every value and derivative that is a
/// double (and a zero rise contributes nothing however steep the ramp).
pub fn step_on<T: Number>(
    branch: StepBranch,
    shape: Shape,
    x: &T,
    x0: &T,
    h0: &T,
    x1: &T,
    h1: &T,
) -> T {
    match branch {
        StepBranch::Before => return h0.clone(),
        StepBranch::After => return h1.clone(),
        StepBranch::Ramp => {}
    }
    let [x_, x0_, h0_, x1_, h1_] = [x, x0, h0, x1, h1].map(Number::value);
    let rest = || ratio(x1_, x_, x1_, x0_);
    if [x0, h0, x1, h1].iter().all(|end| end.is_constant()) {
        let u = ratio(x_, x0_, x1_, x0_);
        return x.chain(interpolate(&h0_, &h1_, shape.value(u)), || {
            let (slope, curvature) = shape.slopes(u, rest());
            // (h1 - h0) and L, each as (a finite part, the factor it stands for).
            let (rise, rise_factor) = match difference(&h1_, &h0_) {
                (rise, false) => (rise, 1.0),
                (half, true) => (half, 2.0),
            };
            let (length, length_factor) = match difference(&x1_, &x0_) {
                (length, false) => (length, 1.0),
                (half, true) => (half, 0.5),
            };
            let per_length = 1.0 / length;
            let factor = rise_factor * length_factor;
            (
                product(&[rise, slope, factor], length, per_length, 1, true),
                product(
                    &[rise, curvature, factor * length_factor],
                    length,
                    per_length,
                    2,
                    true,
                ),
            )
        });
    }
    let u = fraction(x, x0, x1);
    let u0 = u.value();
    let shape = u.chain(shape.value(u0), || shape.slopes(u0, rest()));
    interpolate(h0, h1, shape)
}

impl Shape {
    /// `s(u)`.
    fn value(self, u: f64) -> f64 {
        match self {
            Shape::Cubic => u * u * (3.0 - 2.0 * u),
            Shape::Quintic => u * u * u * ((6.0 * u - 15.0) * u + 10.0),
            Shape::Haversine => {
                let half = (FRAC_PI_2 * u).sin();
                half * half
            }
        }
    }

    /// `s'(u)` and `s''(u)`, with `r = 1 - u` computed on its own.
    fn slopes(self, u: f64, r: f64) -> (f64, f64) {
        match self {
            Shape::Cubic => (6.0 * u * r, 6.0 * (r - u)),
            Shape::Quintic => (30.0 * u * u * r * r, 60.0 * u * r * (r - u)),
            Shape::Haversine => {
                // sin(pi u) = sin(pi (1 - u)): from the nearer end.
                let sine = (PI * u.min(r)).sin();
                let cosine = if u <= r {
                    (PI * u).cos()
                } else {
                    -(PI * r).cos()
                };
                (FRAC_PI_2 * sine, FRAC_PI_2 * PI * cosine)
            }
        }
    }
}
