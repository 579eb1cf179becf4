//! `STEP`, `STEP5` and `HAVSIN` (SPEC 3.2): `h0` for `x <= x0`, `h1` for
//! `x >= x1`, a smooth ramp between. The rule `x0 < x1` is checked by the caller.

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

/// `STEP(x, x0, h0, x1, h1)` and its siblings.
pub fn step<T: Number>(shape: Shape, x: &T, x0: &T, h0: &T, x1: &T, h1: &T) -> T {
    let branch = StepBranch::of(x.value(), x0.value(), x1.value());
    step_on(branch, shape, x, x0, h0, x1, h1)
}

/// The step on `branch`; the ramp's polynomial (or cosine) continues past
/// `[x0, x1]` when the simulator holds it there.
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
    let u = (x.clone() - x0.clone()) / (x1.clone() - x0.clone());
    let rise = h1.clone() - h0.clone();
    match shape {
        Shape::Cubic => h0.clone() + rise * u.clone() * u.clone() * (-u * 2.0 + 3.0),
        Shape::Quintic => {
            let cube = u.clone() * u.clone() * u.clone();
            h0.clone() + rise * cube * ((u.clone() * 6.0 - 15.0) * u + 10.0)
        }
        Shape::Haversine => {
            let mean = (h0.clone() + h1.clone()) * 0.5;
            mean - rise * 0.5 * (u * std::f64::consts::PI).cos()
        }
    }
}
