//! Arithmetic whose intermediates stay within the range of a double wherever
//! its result does: the building blocks the laws use where a plain formula
//! would overflow or underflow on the way to a representable result
//! (`(h1 - h0)` for heights of ±1e308, `k * p^e` for a `p^e` beyond 1e308,
//! `1/d^2` for a ramp of width 1e-200 multiplied by a rate of 0).
//!
//! Each works directly in the usual case and takes a slower path (halves,
//! mantissas and exponents, logarithms) only when the direct result or a
//! partial one is not a normal double.

use super::intrinsics::sqrt;
use crate::number::Number;

/// `factors[0] * factors[1] * ... * x^p * 2^-shift`, given `power = x^p`
/// as the caller computed it (by `powi` or `powf`).
///
/// Where the power is a normal double, the [`product`] of it and the
/// factors: a power just beyond or below the range times a factor that
/// brings it back gives the representable product exactly. Where the power
/// itself is beyond the range (or below the normal doubles), through
/// logarithms, accurate to about `1e-13` relative (where a direct product
/// had no digits at all); a product truly beyond the range is an infinity
/// of the right sign. `x` may be negative only when `p` is a whole number.
#[inline]
pub fn power_product(factors: &[f64], x: f64, p: f64, power: f64, shift: i32) -> f64 {
    if power.is_normal() {
        // The power first, then the factors (as a plain product would).
        return scaled_product(power, factors, 1.0, 1.0, 0, shift);
    }
    beyond_the_normal_powers(factors, x, p, power, shift)
}

/// [`power_product`] where `x^p` itself is not a normal double.
#[cold]
#[inline(never)]
fn beyond_the_normal_powers(factors: &[f64], x: f64, p: f64, power: f64, shift: i32) -> f64 {
    if factors.contains(&0.0) {
        // Nothing times 0 (however steep the power) is 0.
        return 0.0;
    }
    if x == 0.0 || power.is_nan() {
        return scale(
            factors
                .iter()
                .fold(power, |product, factor| product * factor),
            -shift,
        );
    }
    // x^p's sign: negative for a negative x to an odd whole power.
    let odd = x < 0.0 && p % 2.0 != 0.0;
    let negative = factors.iter().filter(|factor| **factor < 0.0).count() % 2 == 1;
    let log = factors.iter().map(|factor| factor.abs().ln()).sum::<f64>() + p * x.abs().ln()
        - f64::from(shift) * std::f64::consts::LN_2;
    let magnitude = log.exp();
    if odd != negative {
        -magnitude
    } else {
        magnitude
    }
}

/// `factors[0] * ... * factors[n-1] / divisor^count`, given `per_divisor
/// = 1/divisor` (multiplied where it is a normal double, else `divisor`
/// divides). With `checked`, directly where every partial product is a
/// normal double and otherwise by mantissas and exponents, so that no
/// partial product over- or underflows where the whole does not (`cmax 6
/// (1 - 2w) rate / d^2` with `d = 1e-242` and `cmax = 1e-300`, or `2 p^2 /
/// d^2` with `p` and `d` near 1e-160), with one rounding per factor; 0 when
/// a factor is 0. Without, the plain product: for factors that are
/// [`moderate`], whose partial products cannot leave the normal doubles.
#[inline(always)]
pub fn product(factors: &[f64], divisor: f64, per_divisor: f64, count: i32, checked: bool) -> f64 {
    if !checked {
        let product = factors.iter().product::<f64>();
        return (0..count).fold(product, |product, _| product * per_divisor);
    }
    scaled_product(1.0, factors, divisor, per_divisor, count, 0)
}

/// Whether every value is 0 or of a magnitude from `2^-120` to `2^120`:
/// then a [`product`] of up to eight such factors and divisors stays a
/// normal double (or is exactly 0), and the reciprocal of each is normal.
#[inline]
pub fn moderate(values: &[f64]) -> bool {
    values.iter().all(|value| {
        // The biased exponent from 1023 - 120 to 1023 + 119, or a zero.
        let bits = value.to_bits();
        ((bits >> 52) & 0x7ff).wrapping_sub(903) < 240 || bits << 1 == 0
    })
}

/// `first` times [`product`] times `2^-shift`.
#[inline]
fn scaled_product(
    first: f64,
    factors: &[f64],
    divisor: f64,
    per_divisor: f64,
    count: i32,
    shift: i32,
) -> f64 {
    let mut direct = first;
    let mut normal = true;
    for factor in factors {
        direct *= factor;
        normal &= direct.is_normal();
    }
    if per_divisor.is_normal() {
        for _ in 0..count {
            direct *= per_divisor;
            normal &= direct.is_normal();
        }
    } else {
        for _ in 0..count {
            direct /= divisor;
            normal &= direct.is_normal();
        }
    }
    if shift != 0 {
        direct = scale(direct, -shift);
        normal &= direct.is_normal();
    }
    if normal {
        return direct;
    }
    by_exponents(first, factors, divisor, count, shift, direct)
}

/// [`scaled_product`] where a partial product left the normal doubles:
/// each factor as `m 2^e` with `|m|` in `[0.5, 1)`, so that the mantissas'
/// product stays near 1 and the exponents add up exactly.
#[cold]
#[inline(never)]
fn by_exponents(
    first: f64,
    factors: &[f64],
    divisor: f64,
    count: i32,
    shift: i32,
    direct: f64,
) -> f64 {
    let all = || std::iter::once(&first).chain(factors);
    if all().any(|factor| *factor == 0.0) {
        return 0.0;
    }
    if !all().all(|factor| factor.is_finite()) || !divisor.is_normal() {
        return direct;
    }
    let mut mantissa = 1.0;
    let mut exponent = -shift;
    for factor in all() {
        let (m, e) = split(*factor);
        mantissa *= m;
        exponent += e;
    }
    let (m, e) = split(divisor);
    for _ in 0..count {
        mantissa /= m;
        exponent -= e;
    }
    scale(mantissa, exponent)
}

/// A finite non-zero `value` as `m * 2^e` with `|m|` in `[0.5, 1)`.
fn split(value: f64) -> (f64, i32) {
    // A subnormal first into the normal range (2^54 is exact).
    let (normal, offset) = if value.is_normal() {
        (value, 0)
    } else {
        (value * 2f64.powi(54), -54)
    };
    let bits = normal.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i32 - 1022;
    let mantissa = f64::from_bits((bits & !(0x7ff << 52)) | (1022 << 52));
    (mantissa, exponent + offset)
}

/// `value * 2^shift`, in steps that neither overflow nor underflow on the
/// way (a single `2^shift` would for `|shift|` beyond about 1000).
pub fn scale<T: Number>(mut value: T, mut shift: i32) -> T {
    while shift != 0 {
        let step = shift.clamp(-1000, 1000);
        value *= 2f64.powi(step);
        shift -= step;
    }
    value
}

/// `a - b`, or `a/2 - b/2` when the difference passes the range of a
/// double (halving is exact there: both are then beyond about 1e307); the
/// flag says which.
pub fn difference<T: Number>(a: &T, b: &T) -> (T, bool) {
    let difference = a.clone() - b.clone();
    if difference.value().is_finite() {
        (difference, false)
    } else {
        (a.clone() * 0.5 - b.clone() * 0.5, true)
    }
}

/// `(x - x0) / (x1 - x0)`, the place of `x` in `[x0, x1]`, also when the
/// differences pass the range of a double (then both are taken in halves).
pub fn fraction<T: Number>(x: &T, x0: &T, x1: &T) -> T {
    let (above, length) = (x.clone() - x0.clone(), x1.clone() - x0.clone());
    if above.value().is_finite() && length.value().is_finite() {
        return quotient(&above, &length);
    }
    quotient(
        &(x.clone() * 0.5 - x0.clone() * 0.5),
        &(x1.clone() * 0.5 - x0.clone() * 0.5),
    )
}

/// `(a - b) / (c - d)` in plain doubles, like [`fraction`].
pub fn ratio(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let (above, length) = (a - b, c - d);
    if above.is_finite() && length.is_finite() {
        above / length
    } else {
        (a * 0.5 - b * 0.5) / (c * 0.5 - d * 0.5)
    }
}

/// `h0 + (h1 - h0) * s`: from `h0` at `s = 0` to `h1` at `s = 1`, also when
/// `h1 - h0` passes the range of a double (heights of -1e308 and 1e308).
pub fn interpolate<T: Number>(h0: &T, h1: &T, s: T) -> T {
    match difference(h1, h0) {
        (rise, false) => h0.clone() + rise * s,
        (half_rise, true) => (h0.clone() * 0.5 + half_rise * s) * 2.0,
    }
}

/// `w * (a - b)`, also when `a - b` passes the range of a double but the
/// product does not (`w` small).
pub fn times_difference<T: Number>(w: &T, a: &T, b: &T) -> T {
    match difference(a, b) {
        (difference, false) => w.clone() * difference,
        (half, true) => w.clone() * half * 2.0,
    }
}

/// `a / b` for `b != 0`, with the quotient rule's partial derivatives
/// (`1/b`, `-q/b`, `-1/b^2`, `2q/b^2`) each formed so that it overflows only
/// where it is beyond a double itself: num-dual's division multiplies by
/// `1/b` and `1/b^2`, which overflow for a subnormal `b` (so
/// `1e-311 / 1e-310` became an infinity) and underflow for a large one.
pub fn quotient<T: Number>(a: &T, b: &T) -> T {
    let (a0, b0) = (a.value(), b.value());
    let q = a0 / b0;
    if b.is_constant() {
        // Every part divided by b: exact where 1/b would overflow.
        return a.clone() / b0;
    }
    a.chain2(
        b,
        q,
        || [1.0 / b0, -(q / b0)],
        || [0.0, -(1.0 / b0 / b0), 2.0 * (q / b0 / b0)],
    )
}

/// `|v|` of the components `v`, scaled by a power of two near the largest
/// so that their squares neither overflow (components beyond 1e154) nor
/// underflow (below 1e-154).
pub fn length<T: Number>(components: &[T]) -> T {
    let largest = components.iter().fold(0.0f64, |largest, component| {
        largest.max(component.value().abs())
    });
    let unit = if largest == 0.0 || (1e-150..1e150).contains(&largest) {
        1.0
    } else {
        2f64.powi(largest.log2().floor() as i32)
    };
    let squares = components.iter().fold(T::zero(), |sum, component| {
        let scaled = component.clone() / unit;
        sum + scaled.clone() * scaled
    });
    let length = sqrt(&squares);
    if unit == 1.0 { length } else { length * unit }
}
