//! `SHF`, `POLY`, `CHEBY`, `FORCOS`, `FORSIN` and `SWEEP` (SPEC 3.4).

use std::f64::consts::TAU;

use super::steps::{Shape, step};
use crate::number::Number;

/// `SHF(x, x0, a, w, phi, b) = a*sin(w*(x - x0) - phi) + b`.
pub fn shf<T: Number>(x: &T, x0: &T, a: &T, w: &T, phi: &T, b: &T) -> T {
    let angle = w.clone() * (x.clone() - x0.clone()) - phi.clone();
    a.clone() * angle.sin() + b.clone()
}

/// `POLY(x, x0, a0, ..., an) = sum a_j (x - x0)^j`, by Horner's rule.
pub fn poly<T: Number>(x: &T, x0: &T, coefficients: &[&T]) -> T {
    let u = x.clone() - x0.clone();
    let mut sum = T::zero();
    for coefficient in coefficients.iter().rev() {
        sum = sum * u.clone() + (*coefficient).clone();
    }
    sum
}

/// `CHEBY(x, x0, a0, ..., an) = sum a_j T_j(x - x0)`.
pub fn cheby<T: Number>(x: &T, x0: &T, coefficients: &[&T]) -> T {
    let u = x.clone() - x0.clone();
    let (mut previous, mut current) = (T::one(), u.clone());
    let mut sum = coefficients[0].clone();
    for coefficient in &coefficients[1..] {
        sum += (*coefficient).clone() * current.clone();
        let next = u.clone() * current.clone() * 2.0 - previous;
        previous = current;
        current = next;
    }
    sum
}

/// Which Fourier series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wave {
    /// `FORCOS`
    Cosine,
    /// `FORSIN`
    Sine,
}

/// `FORCOS`/`FORSIN(x, x0, w, a0, a1, ...) = a0 + sum_(j>=1) a_j cos|sin(j w (x - x0))`.
pub fn fourier<T: Number>(wave: Wave, x: &T, x0: &T, w: &T, coefficients: &[&T]) -> T {
    let angle = w.clone() * (x.clone() - x0.clone());
    let mut sum = coefficients[0].clone();
    for (j, coefficient) in coefficients.iter().enumerate().skip(1) {
        let harmonic = angle.clone() * j as f64;
        let term = match wave {
            Wave::Cosine => harmonic.cos(),
            Wave::Sine => harmonic.sin(),
        };
        sum += (*coefficient).clone() * term;
    }
    sum
}

/// `SWEEP(x, a, x0, f0, x1, f1, dx)`: a sine whose frequency rises linearly
/// from `f0` at `x0` to `f1` at `x1`, faded in by `STEP5(x, x0, 0, x0 + dx, 1)`.
pub fn sweep<T: Number>(x: &T, a: &T, x0: &T, f0: &T, x1: &T, f1: &T, dx: &T) -> T {
    let phase = if x.value() <= x0.value() {
        f0.clone() * x.clone()
    } else if x.value() < x1.value() {
        let from_start = x.clone() - x0.clone();
        f0.clone() * x.clone()
            + (f1.clone() - f0.clone()) * from_start.clone() * from_start
                / ((x1.clone() - x0.clone()) * 2.0)
    } else {
        f1.clone() * x.clone() - (f1.clone() - f0.clone()) * (x1.clone() + x0.clone()) * 0.5
    };
    let fade = step(
        Shape::Quintic,
        x,
        x0,
        &T::zero(),
        &(x0.clone() + dx.clone()),
        &T::one(),
    );
    fade * a.clone() * (phase * TAU).sin()
}
