//! `IMPACT` and `BISTOP` (SPEC 3.3), computed in penetration coordinates.
//!
//! Each stop works with the penetration `p` (`x1 - x` below, `x - x2` above),
//! which is exact near contact, and with the damping ramp in `w = p/d` and
//! `r = (d - p)/d`, never `x - (x1 - d)`: so a gap at `1e6` with `d = 1e-9`,
//! or a penetration of `1e-300`, keeps its digits.
//!
//! What happens at the special points (SPEC 5 decides the branches):
//! - `x1 <= x <= x2` (contact and the gap itself): 0, all derivatives 0.
//! - `0 < p < d`: damping `cmax*w^2*(3 - 2w)`; at `p >= d` it is `cmax`
//!   with zero derivative (the constant branch of the STEP).
//! - the clamp: when `k*p^e + damping*rate <= 0` (fast separation) the
//!   force and all its derivatives are 0 (a tie is the clamped branch).
//! - `e < 1`: `dF/dx` grows without bound as `p -> 0+`; `1 < e < 2`: the
//!   second derivative does. Where a derivative passes the largest double it
//!   is an infinity, which the evaluator reports as an error.

use super::power::{real_power, real_slopes};
use crate::number::Number;

/// The damping ramp `s(w) = w^2 (3 - 2w)` of `w = p/d`, 1 for `p >= d`.
#[inline]
fn ramp<T: Number>(p: &T, d: &T) -> T {
    let (p0, d0) = (p.value(), d.value());
    if p0 >= d0 {
        return T::one();
    }
    // One division: p/d and (d - p)/d each round once more, harmlessly.
    let per_d = d0.recip();
    let w0 = p0 * per_d;
    let r0 = (d0 - p0) * per_d;
    let w = p.clone() / d.clone();
    w.chain(w0 * w0 * (1.0 + 2.0 * r0), || {
        (6.0 * w0 * r0, 6.0 * (d0 - 2.0 * p0) * per_d)
    })
}

/// `k * p^e` for `p > 0`; exactly 0 when `k` is a constant 0.
#[inline]
fn stiffness<T: Number>(p: &T, k: &T, e: &T) -> T {
    if k.value() == 0.0 && k.is_constant() {
        return T::zero();
    }
    let power = if e.is_constant() {
        let (p0, e0) = (p.value(), e.value());
        p.chain(real_power(p0, e0), || real_slopes(p0, e0))
    } else {
        (p.ln() * e.clone()).exp()
    };
    k.clone() * power
}

/// One stop: `max(k p^e + c(p) * rate, 0)` for penetration `p > 0` growing
/// at `rate`; `None` on the clamped branch.
#[inline]
fn stop<T: Number>(p: &T, rate: &T, k: &T, e: &T, cmax: &T, d: &T) -> Option<T> {
    let damping = if cmax.value() == 0.0 && cmax.is_constant() {
        T::zero()
    } else {
        cmax.clone() * ramp(p, d) * rate.clone()
    };
    let raw = stiffness(p, k, e) + damping;
    (raw.value() > 0.0).then_some(raw)
}

/// `IMPACT(x, x', x1, k, e, cmax, d)`: pushes `x` back up when it is below `x1`.
#[inline]
pub fn impact<T: Number>(x: &T, v: &T, x1: &T, k: &T, e: &T, cmax: &T, d: &T) -> T {
    if x.value() < x1.value() {
        let p = x1.clone() - x.clone();
        return stop(&p, &-v.clone(), k, e, cmax, d).unwrap_or_else(T::zero);
    }
    T::zero()
}

/// `BISTOP(x, x', x1, x2, k, e, cmax, d)`: free in `[x1, x2]`, pushed back
/// up below `x1` and down above `x2`.
#[expect(clippy::too_many_arguments, reason = "the solver's calling sequence")]
#[inline]
pub fn bistop<T: Number>(x: &T, v: &T, x1: &T, x2: &T, k: &T, e: &T, cmax: &T, d: &T) -> T {
    if x.value() < x1.value() {
        let p = x1.clone() - x.clone();
        return stop(&p, &-v.clone(), k, e, cmax, d).unwrap_or_else(T::zero);
    }
    if x.value() > x2.value() {
        let p = x.clone() - x2.clone();
        return stop(&p, v, k, e, cmax, d).map_or_else(T::zero, |force| -force);
    }
    T::zero()
}
