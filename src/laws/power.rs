//! Arithmetic that can fail: division and powers. Constant exponents use
//! integer or real powers with their own derivative rules (never the
//! dual-exponent power, and never a formula that overflows for a tiny base).

use super::{LawError, domain};
use crate::Shown;
use crate::number::Number;

/// `a / b`.
pub fn divide<T: Number>(a: &T, b: &T) -> Result<T, LawError> {
    if b.value() == 0.0 {
        return domain(
            "`/`",
            format!("division by zero ({} / 0)", Shown(a.value())),
        );
    }
    Ok(a.clone() / b.clone())
}

/// `x^n` for a whole `n`.
#[inline]
fn integer_power(x: f64, n: i32) -> f64 {
    match n {
        2 => x * x,
        _ => x.powi(n),
    }
}

/// First and second derivative of `x^n` at `x` for a whole `n`.
fn integer_slopes(x: f64, n: i32) -> (f64, f64) {
    match n {
        0 => (0.0, 0.0),
        1 => (1.0, 0.0),
        2 => (2.0 * x, 2.0),
        _ => {
            let n_f = f64::from(n);
            (n_f * x.powi(n - 1), n_f * (n_f - 1.0) * x.powi(n - 2))
        }
    }
}

/// `x^e` for a constant `e`, with `whole` = [`as_integer`]`(e)` worked out
/// by the caller (once, when `e` is a constant of the program): integer
/// powers for a whole `e` (any sign of `x`), else the real power (`x >= 0`).
#[inline]
pub fn constant_power<T: Number>(x: &T, e: f64, whole: Option<i32>) -> T {
    let x0 = x.value();
    match whole {
        Some(n) => x.chain(integer_power(x0, n), || integer_slopes(x0, n)),
        None => {
            let power = x0.powf(e);
            x.chain(power, || real_slopes(x0, e, power))
        }
    }
}

/// First and second derivative of `x^e` at `x >= 0` for a real `e` that is
/// not whole, given `power = x^e`.
///
/// A normal `power` gives both without another call of `powf`:
/// `e x^(e-1) = e (x^e / x)`, one division more and the same digits. A
/// `power` that underflowed to a subnormal or to 0 has lost digits, so the
/// slopes then take their own powers.
fn real_slopes(x: f64, e: f64, power: f64) -> (f64, f64) {
    if x == 0.0 {
        return (e * x.powf(e - 1.0), e * (e - 1.0) * x.powf(e - 2.0));
    }
    let slope = if power.is_normal() {
        e * (power / x)
    } else {
        e * x.powf(e - 1.0)
    };
    // x^(e-2) = x^(e-1) / x (one more rounding).
    (slope, (e - 1.0) * slope / x)
}

/// `e` as an `i32` when it is a whole number in range.
#[inline]
pub fn as_integer(e: f64) -> Option<i32> {
    // A saturating cast and a comparison: no call to `trunc` on a hot path.
    let n = e as i32;
    (f64::from(n) == e && n != i32::MIN && n != i32::MAX).then_some(n)
}

/// `x ** n` for a constant whole `n`: any sign of `x`, exact for small `n`.
pub fn powi<T: Number>(x: &T, n: i32) -> Result<T, LawError> {
    let x0 = x.value();
    if x0 == 0.0 && n < 0 {
        return domain("`**`", format!("0 to the negative power {n} is infinite"));
    }
    if n == 2 {
        return Ok(x.clone() * x.clone());
    }
    Ok(constant_power(x, f64::from(n), Some(n)))
}

/// `x ** e` for a constant real `e` (a whole `e` goes to [`powi`]).
pub fn powf<T: Number>(x: &T, e: f64) -> Result<T, LawError> {
    if let Some(n) = as_integer(e) {
        return powi(x, n);
    }
    let x0 = x.value();
    if x0 < 0.0 {
        return domain(
            "`**`",
            format!(
                "a negative base ({}) to the non-integer power {} is not a real number",
                Shown(x0),
                Shown(e)
            ),
        );
    }
    if x0 == 0.0 && e < 0.0 {
        return domain(
            "`**`",
            format!("0 to the negative power {} is infinite", Shown(e)),
        );
    }
    Ok(constant_power(x, e, None))
}

/// `x ** y` for any `y`: a constant exponent takes [`powf`]; a varying one
/// needs a positive base.
pub fn pow<T: Number>(x: &T, y: &T) -> Result<T, LawError> {
    if y.is_constant() {
        return powf(x, y.value());
    }
    let x0 = x.value();
    if x0 <= 0.0 {
        return domain(
            "`**`",
            format!(
                "the base ({}) must be positive when the exponent varies (the derivative in the exponent is x**y*LOG(x))",
                Shown(x0)
            ),
        );
    }
    Ok((x.ln() * y.clone()).exp())
}
