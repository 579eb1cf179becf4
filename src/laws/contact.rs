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

use super::power::{as_integer, constant_power};
use crate::number::Number;

/// A parameter of a contact law: a plain `f64` when the expression gives a
/// constant (the usual case, and the cheap one), a [`Constant`] when it is
/// a constant of a program, or a number with derivative parts when the
/// parameter itself is a derivative direction. The law is written once over
/// this trait; the provided methods are those of a constant.
trait Parameter<T: Number> {
    /// The real value.
    fn value(&self) -> f64;
    /// `1 / value`.
    fn reciprocal(&self) -> f64 {
        self.value().recip()
    }
    /// Whether it carries no derivative part.
    fn is_constant(&self) -> bool {
        true
    }
    /// `self * t`.
    fn times(&self, t: T) -> T {
        t * self.value()
    }
    /// `t / self`.
    fn divides(&self, t: T) -> T {
        t / self.value()
    }
    /// `base^self` for `base > 0`.
    fn power_of(&self, base: &T) -> T {
        constant_power(base, self.value(), as_integer(self.value()))
    }
    /// `self - t`.
    fn minus(&self, t: &T) -> T {
        -(t.clone() - self.value())
    }
    /// `t - self`.
    fn from(&self, t: &T) -> T {
        t.clone() - self.value()
    }
}

impl<T: Number> Parameter<T> for f64 {
    fn value(&self) -> f64 {
        *self
    }
}

/// A constant parameter of a program, with what the law would otherwise
/// work out from it at every call: whether it is a whole number (an
/// exponent then takes integer powers) and its reciprocal (the ramp's `1/d`).
#[derive(Clone, Copy, Debug)]
struct Constant {
    value: f64,
    whole: Option<i32>,
    reciprocal: f64,
}

impl Constant {
    fn new(value: f64) -> Constant {
        Constant {
            value,
            whole: as_integer(value),
            reciprocal: value.recip(),
        }
    }
}

impl<T: Number> Parameter<T> for Constant {
    fn value(&self) -> f64 {
        self.value
    }
    fn reciprocal(&self) -> f64 {
        self.reciprocal
    }
    #[inline]
    fn power_of(&self, base: &T) -> T {
        constant_power(base, self.value, self.whole)
    }
}

/// A parameter that may carry derivative parts.
struct Varying<'a, T>(&'a T);

impl<T: Number> Parameter<T> for Varying<'_, T> {
    fn value(&self) -> f64 {
        self.0.value()
    }
    fn is_constant(&self) -> bool {
        self.0.is_constant()
    }
    fn times(&self, t: T) -> T {
        self.0.clone() * t
    }
    fn divides(&self, t: T) -> T {
        t / self.0.clone()
    }
    fn power_of(&self, base: &T) -> T {
        if self.0.is_constant() {
            return self.0.value().power_of(base);
        }
        (base.ln() * self.0.clone()).exp()
    }
    fn minus(&self, t: &T) -> T {
        self.0.clone() - t.clone()
    }
    fn from(&self, t: &T) -> T {
        t.clone() - self.0.clone()
    }
}

/// The damping ramp `s(w) = w^2 (3 - 2w)` of `w = p/d`, 1 for `p >= d`.
#[inline]
fn ramp<T: Number, P: Parameter<T>>(p: &T, d: &P) -> T {
    let (p0, d0) = (p.value(), d.value());
    if p0 >= d0 {
        return T::one();
    }
    // One division: p/d and (d - p)/d each round once more, harmlessly.
    let per_d = d.reciprocal();
    let w0 = p0 * per_d;
    let r0 = (d0 - p0) * per_d;
    let w = d.divides(p.clone());
    w.chain(w0 * w0 * (1.0 + 2.0 * r0), || {
        (6.0 * w0 * r0, 6.0 * (d0 - 2.0 * p0) * per_d)
    })
}

/// One stop: `max(k p^e + c(p) * rate, 0)` for penetration `p > 0` growing
/// at `rate`; `None` on the clamped branch. A constant zero `k` or `cmax`
/// leaves its term out (no `0 * inf` from a steep power).
#[inline]
fn stop<T: Number, P: Parameter<T>>(p: &T, rate: T, [k, e, cmax, d]: [&P; 4]) -> Option<T> {
    let stiffness = if k.value() == 0.0 && k.is_constant() {
        T::zero()
    } else {
        k.times(e.power_of(p))
    };
    let raw = if cmax.value() == 0.0 && cmax.is_constant() {
        stiffness
    } else {
        stiffness + cmax.times(ramp(p, d) * rate)
    };
    (raw.value() > 0.0).then_some(raw)
}

/// The lower stop (`x < x1`, penetration `x1 - x`) or the upper one
/// (`x > x2`, penetration `x - x2`), with the parameters as `P`.
#[inline]
fn stops<T: Number, P: Parameter<T>>(
    x: &T,
    v: &T,
    x1: &P,
    x2: Option<&P>,
    parameters: [&P; 4],
) -> T {
    if x.value() < x1.value() {
        return stop(&x1.minus(x), -v.clone(), parameters).unwrap_or_else(T::zero);
    }
    if let Some(x2) = x2
        && x.value() > x2.value()
    {
        return stop(&x2.from(x), v.clone(), parameters).map_or_else(T::zero, |force| -force);
    }
    T::zero()
}

/// The stops and parameters of a contact law given as constants (the usual
/// case, and the cheap one): the law then runs on them as plain `f64`s,
/// with the exponent's kind and `1/d` worked out once. The compiler checks
/// them against the law's rules once and keeps them with the program.
#[derive(Clone, Copy, Debug)]
pub struct Stops {
    lower: Constant,
    upper: Option<Constant>,
    /// `k`, `e`, `cmax` and `d`.
    parameters: [Constant; 4],
}

impl Stops {
    /// The stops `x1` and (for BISTOP) `x2`, and `[k, e, cmax, d]`.
    pub fn new(lower: f64, upper: Option<f64>, [k, e, cmax, d]: [f64; 4]) -> Stops {
        Stops {
            lower: Constant::new(lower),
            upper: upper.map(Constant::new),
            parameters: [k, e, cmax, d].map(Constant::new),
        }
    }

    /// The force at `x` moving at `v`.
    #[inline]
    pub fn force<T: Number>(&self, x: &T, v: &T) -> T {
        let [k, e, cmax, d] = &self.parameters;
        stops(x, v, &self.lower, self.upper.as_ref(), [k, e, cmax, d])
    }

    /// `x1`, `x2` and `[k, e, cmax, d]`, as given.
    pub(crate) fn values(&self) -> (f64, Option<f64>, [f64; 4]) {
        let upper = self.upper.map(|upper| upper.value);
        (self.lower.value, upper, self.parameters.map(|p| p.value))
    }
}

/// Stops are equal when they were given equal numbers (what a program's
/// table of stops shares entries by).
impl PartialEq for Stops {
    fn eq(&self, other: &Stops) -> bool {
        self.values() == other.values()
    }
}

/// `x1 -10, x2 10, k 100000, e 2.2, cmax 100, d 0.1`
impl std::fmt::Display for Stops {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (lower, upper, [k, e, cmax, d]) = self.values();
        write!(f, "x1 {lower}")?;
        if let Some(upper) = upper {
            write!(f, ", x2 {upper}")?;
        }
        write!(f, ", k {k}, e {e}, cmax {cmax}, d {d}")
    }
}

/// The law with constant parameters as plain `f64`s, else as numbers.
#[inline]
fn contact<T: Number>(x: &T, v: &T, x1: &T, x2: Option<&T>, [k, e, cmax, d]: [&T; 4]) -> T {
    let constant =
        [x1, k, e, cmax, d].iter().all(|t| t.is_constant()) && x2.is_none_or(Number::is_constant);
    if constant {
        let x2 = x2.map(Number::value);
        let [k, e, cmax, d] = [k, e, cmax, d].map(Number::value);
        return stops(x, v, &x1.value(), x2.as_ref(), [&k, &e, &cmax, &d]);
    }
    let x2 = x2.map(Varying);
    let parameters = [&Varying(k), &Varying(e), &Varying(cmax), &Varying(d)];
    stops(x, v, &Varying(x1), x2.as_ref(), parameters)
}

/// `IMPACT(x, x', x1, k, e, cmax, d)`: pushes `x` back up when it is below `x1`.
#[inline]
pub fn impact<T: Number>(x: &T, v: &T, x1: &T, k: &T, e: &T, cmax: &T, d: &T) -> T {
    contact(x, v, x1, None, [k, e, cmax, d])
}

/// `BISTOP(x, x', x1, x2, k, e, cmax, d)`: free in `[x1, x2]`, pushed back
/// up below `x1` and down above `x2`.
#[expect(clippy::too_many_arguments, reason = "the solver's calling sequence")]
#[inline]
pub fn bistop<T: Number>(x: &T, v: &T, x1: &T, x2: &T, k: &T, e: &T, cmax: &T, d: &T) -> T {
    contact(x, v, x1, Some(x2), [k, e, cmax, d])
}
