//! `SHF`, `POLY`, `CHEBY`, `FORCOS`, `FORSIN` and `SWEEP` (SPEC 3.4).

use std::f64::consts::TAU;

use super::intrinsics::{cos, sin};
use super::range::{difference, fraction, scale, times_difference};
use super::steps::{Shape, step};
use crate::number::Number;

/// `SHF(x, x0, a, w, phi, b) = a*sin(w*(x - x0) - phi) + b`.
pub fn shf<T: Number>(x: &T, x0: &T, a: &T, w: &T, phi: &T, b: &T) -> T {
    let angle = times_difference(w, x, x0) - phi.clone();
    wave(Wave::Sine, a, &angle) + b.clone()
}

/// `a cos(angle)` or `a sin(angle)`. A constant `a` (the usual case) is
/// part of one function of the angle, so that it meets the wave's slopes
/// before the angle's derivative parts do: an amplitude of 1e300 on a
/// frequency of 1e-300 gives the curvature `a w^2` that is a double, where
/// `w^2` alone underflows.
fn wave<T: Number>(wave: Wave, a: &T, angle: &T) -> T {
    if !a.is_constant() {
        return a.clone()
            * match wave {
                Wave::Cosine => cos(angle),
                Wave::Sine => sin(angle),
            };
    }
    let (a, theta) = (a.value(), angle.value());
    let (sin, cos) = theta.sin_cos();
    match wave {
        Wave::Cosine => angle.chain(a * cos, || (-(a * sin), -(a * cos))),
        Wave::Sine => angle.chain(a * sin, || (a * cos, -(a * sin))),
    }
}

/// `POLY(x, x0, a0, ..., an) = sum a_j (x - x0)^j`, by Horner's rule (in
/// `(x - x0)/2` with `a_j 2^j` where `x - x0` passes the range of a double).
pub fn poly<T: Number>(x: &T, x0: &T, coefficients: &[&T]) -> T {
    let (u, halved) = difference(x, x0);
    let mut sum = T::zero();
    for (j, coefficient) in coefficients.iter().enumerate().rev() {
        let coefficient = (*coefficient).clone();
        let coefficient = if halved {
            scale(coefficient, j as i32)
        } else {
            coefficient
        };
        sum = sum * u.clone() + coefficient;
    }
    sum
}

/// `CHEBY(x, x0, a0, ..., an) = sum a_j T_j(x - x0)`, by Clenshaw's
/// recurrence: no `T_j` is formed on its own, so a high `T_j` beyond the
/// range of a double with a zero coefficient adds nothing (the direct sum
/// gave `0 * inf`).
pub fn cheby<T: Number>(x: &T, x0: &T, coefficients: &[&T]) -> T {
    let u = x.clone() - x0.clone();
    let twice = u.clone() * 2.0;
    // b_j = a_j + 2u b_(j+1) - b_(j+2), down to j = 1.
    let (mut next, mut after) = (T::zero(), T::zero());
    for coefficient in coefficients[1..].iter().rev() {
        let current = (*coefficient).clone() + twice.clone() * next.clone() - after;
        after = next;
        next = current;
    }
    coefficients[0].clone() + u * next - after
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
///
/// Each harmonic from its own angle `j w (x - x0)`; where the highest of
/// those passes the range of a double, all of them from `cos` and `sin` of
/// the first by the multiple-angle recurrences instead.
pub fn fourier<T: Number>(kind: Wave, x: &T, x0: &T, w: &T, coefficients: &[&T]) -> T {
    let angle = times_difference(w, x, x0);
    let highest = (coefficients.len() - 1) as f64;
    let mut sum = coefficients[0].clone();
    if (angle.value() * highest).is_finite() {
        for (j, coefficient) in coefficients.iter().enumerate().skip(1) {
            sum += wave(kind, *coefficient, &(angle.clone() * j as f64));
        }
        return sum;
    }
    // cos(jt) = 2 cos(t) cos((j-1)t) - cos((j-2)t), and the same for sin.
    let (cosine, sine) = (cos(&angle), sin(&angle));
    let twice = cosine.clone() * 2.0;
    let (mut previous, mut current) = match kind {
        Wave::Cosine => (T::one(), cosine),
        Wave::Sine => (T::zero(), sine),
    };
    for coefficient in &coefficients[1..] {
        sum += (*coefficient).clone() * current.clone();
        let next = twice.clone() * current.clone() - previous;
        previous = current;
        current = next;
    }
    sum
}

/// `SWEEP(x, a, x0, f0, x1, f1, dx)`: a sine whose frequency rises linearly
/// from `f0` at `x0` to `f1` at `x1`, faded in by `STEP5(x, x0, 0, x0 + dx, 1)`.
///
/// The ramp's phase term `(f1 - f0)(x - x0)^2 / (2(x1 - x0))` is formed as
/// `(f1 - f0)(x - x0) u / 2` with `u` the place of `x` in `[x0, x1]` (the
/// square overflows from `x - x0 = 1e154` on), and the sine takes the
/// phase's fraction of a turn, so that a phase beyond `2^53` turns (whose
/// sine is 0) does not overflow `2 pi phase`.
pub fn sweep<T: Number>(x: &T, a: &T, x0: &T, f0: &T, x1: &T, f1: &T, dx: &T) -> T {
    if x.value() <= x0.value() {
        // The fade's constant branch, 0: so is the sweep, with every
        // derivative (no 0 times a steep sine's parts).
        return T::zero();
    }
    let rise = f1.clone() - f0.clone();
    let phase = if x.value() < x1.value() {
        f0.clone() * x.clone() + times_difference(&rise, x, x0) * fraction(x, x0, x1) * 0.5
    } else {
        let middle = match difference(x1, &-x0.clone()) {
            (sum, false) => sum * 0.5,
            (half_sum, true) => half_sum,
        };
        f1.clone() * x.clone() - rise * middle
    };
    let fade = step(
        Shape::Quintic,
        x,
        x0,
        &T::zero(),
        &(x0.clone() + dx.clone()),
        &T::one(),
    );
    let turns = phase.clone() - phase.value().trunc();
    fade * wave(Wave::Sine, a, &(turns * TAU))
}
