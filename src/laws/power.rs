//! Arithmetic that can fail: division and powers. Constant exponents use
//! integer or real powers with their own derivative rules (never the
//! dual-exponent power, and never a formula that overflows for a tiny base).

use super::range::{moderate, power_product, quotient};
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
    Ok(quotient(a, b))
}

/// `x^n` for a whole `n`: `powi`, or `powf` where repeated multiplication
/// leaves the range of a double on the way (`2^-1030` as `1 / 2^1030`).
#[inline]
fn integer_power(x: f64, n: i32) -> f64 {
    let power = match n {
        2 => x * x,
        _ => x.powi(n),
    };
    if power.is_normal() || x == 0.0 {
        power
    } else {
        x.powf(f64::from(n))
    }
}

/// `c x^e` for a constant `c` and `e`, with `whole` = [`as_integer`]`(e)`
/// worked out by the caller (once, when `e` is a constant of the program):
/// integer powers for a whole `e` (any sign of `x`), else the real power
/// (`x >= 0`). Where `c` and `x` are `moderate` and `|e| <= 8` (the usual
/// case: every power and product is then a normal double), plain products;
/// otherwise the value and both derivatives are formed by
/// `power_product`, so `c` small and `x^e` beyond the range of a double
/// (or the reverse) still give their representable product.
#[inline]
pub fn scaled_power<T: Number>(c: f64, x: &T, e: f64, whole: Option<i32>, shift: i32) -> T {
    let x0 = x.value();
    let power = match whole {
        Some(n) => integer_power(x0, n),
        None => x0.powf(e),
    };
    let plain = shift == 0 && x0 != 0.0 && e.abs() <= 8.0 && moderate(&[c, x0]);
    let value = if plain {
        power * c
    } else {
        power_product(&[c], x0, e, power, shift)
    };
    x.chain(value, || slopes(c, x0, e, whole, power, shift, plain))
}

/// `x^e` for a constant `e` (see [`scaled_power`]).
#[inline]
pub fn constant_power<T: Number>(x: &T, e: f64, whole: Option<i32>) -> T {
    scaled_power(1.0, x, e, whole, 0)
}

/// The first and second derivative of `c x^e 2^-shift` at `x`, given
/// `power = x^e`: `c e x^(e-1)` and `c e (e-1) x^(e-2)`, as plain products
/// when `plain` (see [`scaled_power`]).
///
/// A normal `power` gives the two powers without another call of `powf`
/// (`x^(e-1) = x^e / x`, one rounding more); otherwise they take their own.
#[inline]
fn slopes(
    c: f64,
    x: f64,
    e: f64,
    whole: Option<i32>,
    power: f64,
    shift: i32,
    plain: bool,
) -> (f64, f64) {
    match whole {
        Some(0) => return (0.0, 0.0),
        Some(1) => return (power_product(&[c], x, 0.0, 1.0, shift), 0.0),
        _ => {}
    }
    let (first_power, second_power) = if power.is_normal() {
        let first_power = power / x;
        (first_power, first_power / x)
    } else {
        (x.powf(e - 1.0), x.powf(e - 2.0))
    };
    if plain {
        return (first_power * c * e, second_power * c * e * (e - 1.0));
    }
    (
        power_product(&[c, e], x, e - 1.0, first_power, shift),
        power_product(&[c, e, e - 1.0], x, e - 2.0, second_power, shift),
    )
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
    let y0 = y.value();
    let power = x0.powf(y0);
    let ln = x0.ln();
    Ok(x.chain2(
        y,
        power,
        || {
            [
                power_product(&[y0], x0, y0 - 1.0, x0.powf(y0 - 1.0), 0),
                power_product(&[ln], x0, y0, power, 0),
            ]
        },
        || {
            [
                power_product(&[y0, y0 - 1.0], x0, y0 - 2.0, x0.powf(y0 - 2.0), 0),
                power_product(&[1.0 + y0 * ln], x0, y0 - 1.0, x0.powf(y0 - 1.0), 0),
                power_product(&[ln, ln], x0, y0, power, 0),
            ]
        },
    ))
}
