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
//!   second derivative does; for every exponent that is not a whole number
//!   some derivative does (the simulator's step limit, `step_limit`). Where a derivative passes the largest double it
//!   is an infinity, which the evaluator reports as an error (and the
//!   utility subroutines with ERRFLG).
//!
//! Beyond the range of a double (see `beyond_range`): the clamp's branch
//! is decided on the terms as they are, never on a sum that overflowed to
//! NaN or a stiffness that underflowed to 0; where a term passes the range,
//! the force is summed at a power-of-two scale, so that `k p^e` and the
//! damping, each beyond 1.8e308, still give their difference when that is a
//! double, and an infinity (an error) when it is not.

use std::f64::consts::LN_2;

use super::power::{as_integer, scaled_power};
use super::range::{moderate, product, quotient, scale};
use crate::Shown;
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
    /// The stiffness term `self * p^e * 2^-shift` (`self` is `k`).
    fn stiffness(&self, e: &Self, p: &T, shift: i32) -> T {
        let e = e.value();
        scaled_power(self.value(), p, e, as_integer(e), shift)
    }
    /// Whether it is [`moderate`] (0, or a magnitude from `2^-120` to
    /// `2^120`).
    fn is_moderate(&self) -> bool {
        moderate(&[self.value()])
    }
    /// The damping term `self * s(p/d) * rate * 2^-shift` (`self` is
    /// `cmax`) on `piece` of the ramp, as one function of `p` and `rate`
    /// with its partial derivatives.
    fn damping(&self, d: &Self, p: &T, rate: &T, piece: Piece, shift: i32) -> T {
        let cmax = scale(self.value(), -shift);
        let moderate = shift == 0 && self.is_moderate() && d.is_moderate();
        constant_damping(cmax, d.value(), d.reciprocal(), moderate, piece, p, rate)
    }
    /// `self - t`.
    fn minus(&self, t: &T) -> T {
        -(t.clone() - self.value())
    }
    /// `t - self`.
    fn subtracted_from(&self, t: &T) -> T {
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
/// exponent then takes integer powers), its reciprocal (the ramp's `1/d`)
/// and whether it is [`moderate`].
#[derive(Clone, Copy, Debug)]
struct Constant {
    value: f64,
    whole: Option<i32>,
    reciprocal: f64,
    moderate: bool,
}

impl Constant {
    fn new(value: f64) -> Constant {
        Constant {
            value,
            whole: as_integer(value),
            reciprocal: value.recip(),
            moderate: moderate(&[value]),
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
    fn is_moderate(&self) -> bool {
        self.moderate
    }
    #[inline]
    fn stiffness(&self, e: &Self, p: &T, shift: i32) -> T {
        scaled_power(self.value, p, e.value, e.whole, shift)
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
    fn stiffness(&self, e: &Self, p: &T, shift: i32) -> T {
        if self.is_constant() && e.is_constant() {
            return self.value().stiffness(&e.value(), p, shift);
        }
        let power = if e.is_constant() {
            let e = e.value();
            scaled_power(1.0, p, e, as_integer(e), shift)
        } else {
            (p.ln() * e.0.clone() - f64::from(shift) * LN_2).exp()
        };
        self.0.clone() * power
    }
    fn damping(&self, d: &Self, p: &T, rate: &T, piece: Piece, shift: i32) -> T {
        if self.is_constant() && d.is_constant() {
            return self.value().damping(&d.value(), p, rate, piece, shift);
        }
        let rate = scale(rate.clone(), -shift);
        self.0.clone() * ramp(p, d.0, piece) * rate
    }
    fn minus(&self, t: &T) -> T {
        self.0.clone() - t.clone()
    }
    fn subtracted_from(&self, t: &T) -> T {
        t.clone() - self.0.clone()
    }
}

/// The part of a stop's damping ramp that applies: the cubic (`p < d`) or
/// the constant `cmax` beyond it (`p >= d`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Piece {
    /// `0 < p < d`: damping `cmax*w^2*(3 - 2w)`, `w = p/d`.
    Ramp,
    /// `p >= d`: damping `cmax`.
    Full,
}

impl Piece {
    /// The piece the penetration `p` is on.
    fn of(p: f64, d: f64) -> Piece {
        if p >= d { Piece::Full } else { Piece::Ramp }
    }
}

/// `cmax * s(p/d) * rate` for constant `cmax` and `d`, with the ramp
/// `s(w) = w^2 (3 - 2w)` (1 on [`Piece::Full`]): one function of `p` and `rate`
/// whose value and partial derivatives are each one [`product`] of their
/// factors (`cmax 6 (1 - 2w) rate / d^2`, ...), so that no partial product
/// overflows or underflows where the whole does not, and a zero rate or
/// slope contributes nothing (no `0 * inf`). `per_d` is `1/d`; `moderate`
/// says that `cmax` and `d` are. On [`Piece::Ramp`] the cubic continues
/// past `[0, d]` when the simulator holds it there.
#[inline]
fn constant_damping<T: Number>(
    cmax: f64,
    d: f64,
    per_d: f64,
    moderate: bool,
    piece: Piece,
    p: &T,
    rate: &T,
) -> T {
    let (p0, rate0) = (p.value(), rate.value());
    if piece == Piece::Full {
        return rate.chain(cmax * rate0, || (cmax, 0.0));
    }
    // s(w) = w^2 (1 + 2r) with w = p/d and r = (d - p)/d, so that
    // s'(p) = 6 r p / d^2 and s''(p) = 6 (d - 2p) / d^3.
    let over_d = |t: f64| {
        if per_d.is_normal() { t * per_d } else { t / d }
    };
    let r = over_d(d - p0);
    // Moderate inputs (the usual case) make every factor moderate too (r
    // and 1 - 2w are 0 or at least 2^-53): plain products.
    let checked = !(moderate && self::moderate(&[p0, rate0]));
    let product = |factors: &[f64]| product(factors, d, per_d, 2, checked);
    p.chain2(
        rate,
        product(&[cmax, 1.0 + 2.0 * r, rate0, p0, p0]),
        || {
            [
                product(&[cmax, 6.0 * r, rate0, p0]),
                product(&[cmax, 1.0 + 2.0 * r, p0, p0]),
            ]
        },
        || {
            let curvature = 6.0 * over_d(d - p0 - p0);
            [
                product(&[cmax, curvature, rate0]),
                product(&[cmax, 6.0 * r, p0]),
                0.0,
            ]
        },
    )
}

/// The damping ramp `s(w) = w^2 (3 - 2w)` of `w = p/d` when `d` carries
/// derivative parts, 1 on [`Piece::Full`].
fn ramp<T: Number>(p: &T, d: &T, piece: Piece) -> T {
    if piece == Piece::Full {
        return T::one();
    }
    let w = quotient(p, d);
    let w0 = w.value();
    w.chain(w0 * w0 * (3.0 - 2.0 * w0), || {
        (6.0 * w0 * (1.0 - w0), 6.0 - 12.0 * w0)
    })
}

/// The stiffness and damping terms of one stop at the scale `2^-shift`,
/// the damping on `piece` of its ramp. A constant zero `k` or `cmax` leaves
/// its term out (no `0 * inf` from a steep power or ramp). A negative `p`
/// (a stop held by the simulator past its contact) takes the odd
/// continuation `-k |p|^e` of a real power, so the force stays smooth
/// through contact.
#[inline]
fn terms<T: Number, P: Parameter<T>>(
    p: &T,
    rate: &T,
    [k, e, cmax, d]: [&P; 4],
    piece: Piece,
    shift: i32,
) -> (T, T) {
    let stiffness = if k.value() == 0.0 && k.is_constant() {
        T::zero()
    } else if p.value() < 0.0 && as_integer(e.value()).is_none() {
        -k.stiffness(e, &-p.clone(), shift)
    } else {
        k.stiffness(e, p, shift)
    };
    let damping = if cmax.value() == 0.0 && cmax.is_constant() {
        T::zero()
    } else {
        cmax.damping(d, p, rate, piece, shift)
    };
    (stiffness, damping)
}

/// The unclamped force of one stop, `k p^e + c(p) * rate`, with the ramp
/// on `piece` (what the simulator evaluates on a held branch).
#[inline]
fn unclamped<T: Number, P: Parameter<T>>(p: &T, rate: T, parameters: [&P; 4], piece: Piece) -> T {
    let (stiffness, damping) = terms(p, &rate, parameters, piece, 0);
    stiffness + damping
}

/// One stop: `max(k p^e + c(p) * rate, 0)` for penetration `p > 0` growing
/// at `rate`; `None` on the clamped branch.
#[inline]
fn stop<T: Number, P: Parameter<T>>(p: &T, rate: T, parameters: [&P; 4]) -> Option<T> {
    let piece = Piece::of(p.value(), parameters[3].value());
    stop_on(p, rate, parameters, piece)
}

/// [`stop`] with the ramp on `piece`. The branch is decided by the sign of
/// the sum where that sum can be trusted, by [`beyond_range`] where a term
/// passed the range of a double.
#[inline]
fn stop_on<T: Number, P: Parameter<T>>(
    p: &T,
    rate: T,
    parameters: [&P; 4],
    piece: Piece,
) -> Option<T> {
    let (stiffness, damping) = terms(p, &rate, parameters, piece, 0);
    let (s, m) = (stiffness.value(), damping.value());
    // A stiffness that underflowed (to 0, or to a subnormal with lost
    // digits) against a damping that does not push: the sum's sign says
    // nothing of k p^e's.
    let underflowed =
        parameters[0].value() != 0.0 && !s.is_normal() && (m < 0.0 || (m == 0.0 && s == 0.0));
    if s.is_finite() && m.is_finite() && !underflowed {
        let raw = stiffness + damping;
        return (raw.value() > 0.0).then_some(raw);
    }
    beyond_range(p, &rate, parameters, piece, stiffness + damping)
}

/// The stop where a term is beyond the range of a double or underflowed:
/// both terms are formed again in plain doubles at a power-of-two scale
/// that brings the larger near `2^64` (the stiffness through logarithms),
/// and the sign of their sum decides the branch. Where the terms were
/// doubles, `unscaled` (their sum) is the force; where one passed the
/// range, the force is the sum at that scale, scaled back: a double when
/// the true difference is one, an infinity (an error) when it is not.
#[cold]
fn beyond_range<T: Number, P: Parameter<T>>(
    p: &T,
    rate: &T,
    parameters: [&P; 4],
    piece: Piece,
    unscaled: T,
) -> Option<T> {
    let [k, e, cmax, d] = parameters.map(|parameter| parameter.value());
    let (p0, rate0) = (p.value(), rate.value());
    // log2 of |k p^e| and of |cmax s(w) rate|.
    let log_stiffness = k.log2() + e * p0.log2();
    let w = if piece == Piece::Full { 1.0 } else { p0 / d };
    let log_damping = cmax.log2() + 2.0 * w.log2() + (3.0 - 2.0 * w).log2() + rate0.abs().log2();
    let larger = log_stiffness.max(log_damping);
    if larger.is_nan() || larger == f64::NEG_INFINITY {
        return None;
    }
    // Terms beyond 2^±3000 are infinite or zero at any scale a double has.
    let shift = larger.floor().clamp(-3000.0, 3000.0) as i32 - 64;
    let (stiffness, damping) = terms(&p0, &rate0, [&k, &e, &cmax, &d], piece, shift);
    // A NaN sum (no term in range even at this scale) is no push either.
    if (stiffness + damping).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    if shift <= 0 {
        return Some(unscaled);
    }
    let (stiffness, damping) = terms(p, rate, parameters, piece, shift);
    Some(scale(stiffness + damping, shift))
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
        return stop(&x2.subtracted_from(x), v.clone(), parameters)
            .map_or_else(T::zero, |force| -force);
    }
    T::zero()
}

/// Where a contact law is, as the simulator holds it through a step: in
/// the gap (or free of IMPACT's stop), or at a stop on a piece of its
/// ramp, or clamped there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactBranch {
    /// `x1 <= x (<= x2)`: no force.
    Free,
    /// Below `x1`, unclamped, on a piece of the ramp.
    Lower(Piece),
    /// Below `x1`, clamped (the raw force is not positive).
    LowerClamped,
    /// Above `x2`, unclamped, on a piece of the ramp.
    Upper(Piece),
    /// Above `x2`, clamped.
    UpperClamped,
}

impl ContactBranch {
    /// All branches, in the order of their codes.
    const ALL: [ContactBranch; 7] = [
        ContactBranch::Free,
        ContactBranch::Lower(Piece::Ramp),
        ContactBranch::Lower(Piece::Full),
        ContactBranch::LowerClamped,
        ContactBranch::Upper(Piece::Ramp),
        ContactBranch::Upper(Piece::Full),
        ContactBranch::UpperClamped,
    ];

    /// The branch's code (its index in a fixed order).
    pub fn code(self) -> i64 {
        Self::ALL
            .iter()
            .position(|&branch| branch == self)
            .unwrap_or(0) as i64
    }

    /// The branch of a code; [`ContactBranch::Free`] for an unknown one.
    pub fn from_code(code: i64) -> ContactBranch {
        usize::try_from(code)
            .ok()
            .and_then(|index| Self::ALL.get(index).copied())
            .unwrap_or(ContactBranch::Free)
    }

    /// A short name for event lists: `gap`, `lower ramp`, `upper clamped`.
    pub fn name(self) -> &'static str {
        match self {
            ContactBranch::Free => "free",
            ContactBranch::Lower(Piece::Ramp) => "lower stop, damping ramp",
            ContactBranch::Lower(Piece::Full) => "lower stop, full damping",
            ContactBranch::LowerClamped => "lower stop, clamped",
            ContactBranch::Upper(Piece::Ramp) => "upper stop, damping ramp",
            ContactBranch::Upper(Piece::Full) => "upper stop, full damping",
            ContactBranch::UpperClamped => "upper stop, clamped",
        }
    }
}

/// What a simulator sees of a contact law at a point: the branch it takes
/// there (SPEC 3.3 and 5), the switching values of the held branch (three
/// numbers, each positive while the law stays on that branch and negative
/// once it has left it: the penetration, the distance to the ramp's end,
/// the unclamped force; 1 where one does not apply), and the force on the
/// held branch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observation {
    /// The branch the law takes at the point.
    pub natural: ContactBranch,
    /// The held branch's switching values.
    pub values: [f64; 3],
    /// The force on the held branch, continued past its boundaries.
    pub force: f64,
}

/// The [`Observation`] of a contact law at `x`, `v` with `held` (the
/// natural branch when `None`). Each unclamped force is computed once.
fn contact_switching<P: Parameter<f64>>(
    x: f64,
    v: f64,
    x1: &P,
    x2: Option<&P>,
    parameters: [&P; 4],
    held: Option<ContactBranch>,
) -> Observation {
    let d = parameters[3].value();
    // Without damping the ramp's pieces give the same force: one branch.
    let piece_of = |p: f64| {
        if parameters[2].value() == 0.0 {
            Piece::Full
        } else {
            Piece::of(p, d)
        }
    };
    let lower = (x1.value() - x, -v);
    let upper = x2.map(|x2| (x - x2.value(), v));
    // The unclamped force of a side (`true`: the upper stop) on a piece,
    // the last one kept.
    let mut kept: Option<((bool, Piece), f64)> = None;
    let mut raw = |upper_side: bool, (p, rate): (f64, f64), piece: Piece| match kept {
        Some((key, value)) if key == (upper_side, piece) => value,
        _ => {
            let value = unclamped(&p, rate, parameters, piece);
            kept = Some(((upper_side, piece), value));
            value
        }
    };
    // The clamp as the evaluation decides it: by the unclamped force's sign
    // where that is a normal double, by `stop_on` where it is not (a term
    // beyond the range of a double, or a stiffness that underflowed).
    let mut pushes = |upper_side: bool, side: (f64, f64), piece: Piece| {
        let force = raw(upper_side, side, piece);
        if force.is_normal() {
            force > 0.0
        } else {
            stop_on(&side.0, side.1, parameters, piece).is_some()
        }
    };
    let natural = if x < x1.value() {
        let piece = piece_of(lower.0);
        if pushes(false, lower, piece) {
            ContactBranch::Lower(piece)
        } else {
            ContactBranch::LowerClamped
        }
    } else if let Some(side) = upper.filter(|&(p, _)| p > 0.0) {
        let piece = piece_of(side.0);
        if pushes(true, side, piece) {
            ContactBranch::Upper(piece)
        } else {
            ContactBranch::UpperClamped
        }
    } else {
        ContactBranch::Free
    };
    let mut at_stop =
        |upper_side: bool, side: (f64, f64), piece: Option<Piece>| -> ([f64; 3], f64) {
            let p = side.0;
            match piece {
                Some(piece) => {
                    // Without damping the pieces are one, and their
                    // meeting no switch.
                    let end = if parameters[2].value() == 0.0 {
                        1.0
                    } else if piece == Piece::Ramp {
                        d - p
                    } else {
                        p - d
                    };
                    let force = raw(upper_side, side, piece);
                    ([p, end, force], if upper_side { -force } else { force })
                }
                None => ([p, -raw(upper_side, side, piece_of(p)), 1.0], 0.0),
            }
        };
    let (values, force) = match held.unwrap_or(natural) {
        ContactBranch::Free => ([x - x1.value(), upper.map_or(1.0, |(p, _)| -p), 1.0], 0.0),
        ContactBranch::Lower(piece) => at_stop(false, lower, Some(piece)),
        ContactBranch::LowerClamped => at_stop(false, lower, None),
        ContactBranch::Upper(piece) => {
            upper.map_or(([1.0; 3], 0.0), |side| at_stop(true, side, Some(piece)))
        }
        ContactBranch::UpperClamped => {
            upper.map_or(([1.0; 3], 0.0), |side| at_stop(true, side, None))
        }
    };
    Observation {
        natural,
        values,
        force,
    }
}

/// The part of a simulator's absolute tolerance that the displacement no
/// polynomial follows may take at each touch and release of a stop whose
/// exponent is not a whole number. On the softening ball of the simulation
/// study (92 touches and releases) DOP853 needs half the right-hand sides of steps graded all
/// the way down, at the same error; with the whole tolerance it needs a
/// quarter fewer again but stalls near 2e-9 (BENCHMARKS.md).
const RESOLUTION_MARGIN: f64 = 1e-3;

/// The largest step a simulator should take with a law held on `held` at
/// `x`, `v`, for every exponent that is not a whole number: the force goes
/// as `p^e` near touch and release, so the motion goes as
/// `|t - t_touch|^(e + 2)`, a weak singularity that no step of polynomial
/// order follows and no embedded error estimate measures (for `e < 1` the
/// slope is unbounded, for `1 < e < 2` the second derivative, for
/// `2 < e < 3` the third, ...). The limit is half the time the
/// penetration takes to double or vanish at its current rate, so that
/// steps grow and shrink geometrically with the penetration and each step
/// lies at least its own length from the singularity, where the error
/// estimate holds; unbounded for whole exponents (a polynomial) and in the
/// gap. The steps shrink no further than `h0`, over which the term no
/// step of polynomial order follows,
/// `k |p'|^e h0^(e + 2) / ((e + 1)(e + 2))` (the displacement the force
/// adds near touch), stays below [`RESOLUTION_MARGIN`] times `tolerance`,
/// the absolute error the caller accepts in `x`: the one step that holds
/// the singularity then makes an error below the tolerance whatever its
/// estimate says.
fn contact_step_limit<P: Parameter<f64>>(
    x: f64,
    v: f64,
    x1: &P,
    x2: Option<&P>,
    [stiffness, exponent]: [&P; 2],
    held: ContactBranch,
    tolerance: f64,
) -> f64 {
    let e = exponent.value();
    if as_integer(e).is_some() {
        return f64::INFINITY;
    }
    let (p, rate) = match held {
        ContactBranch::Lower(_) | ContactBranch::LowerClamped => (x1.value() - x, -v),
        ContactBranch::Upper(_) | ContactBranch::UpperClamped => match x2 {
            Some(x2) => (x - x2.value(), v),
            None => return f64::INFINITY,
        },
        ContactBranch::Free => return f64::INFINITY,
    };
    let speed = rate.abs();
    if speed == 0.0 {
        return f64::INFINITY;
    }
    let graded = 0.5 * p.max(0.0) / speed;
    let resolved = (RESOLUTION_MARGIN * tolerance * (e + 1.0) * (e + 2.0)
        / (stiffness.value() * speed.powf(e)))
    .powf(1.0 / (e + 2.0));
    if resolved.is_nan() {
        graded
    } else {
        graded.max(resolved)
    }
}

/// The force on branch `held`, continued smoothly past the branch's
/// boundaries (the simulator's view within a step).
fn contact_held<T: Number, P: Parameter<T>>(
    x: &T,
    v: &T,
    x1: &P,
    x2: Option<&P>,
    parameters: [&P; 4],
    held: ContactBranch,
) -> T {
    match (held, x2) {
        (ContactBranch::Lower(piece), _) => unclamped(&x1.minus(x), -v.clone(), parameters, piece),
        (ContactBranch::Upper(piece), Some(x2)) => {
            -unclamped(&x2.subtracted_from(x), v.clone(), parameters, piece)
        }
        _ => T::zero(),
    }
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

    /// The force on branch `held`, continued past its boundaries.
    pub fn force_held<T: Number>(&self, x: &T, v: &T, held: ContactBranch) -> T {
        let [k, e, cmax, d] = &self.parameters;
        contact_held(
            x,
            v,
            &self.lower,
            self.upper.as_ref(),
            [k, e, cmax, d],
            held,
        )
    }

    /// What a simulator sees at `x`, `v` with `held` (see [`switching`]).
    pub fn switching(&self, x: f64, v: f64, held: Option<ContactBranch>) -> Observation {
        let [k, e, cmax, d] = &self.parameters;
        contact_switching(
            x,
            v,
            &self.lower,
            self.upper.as_ref(),
            [k, e, cmax, d],
            held,
        )
    }

    /// The largest step to take on branch `held` (see [`step_limit`]).
    pub fn step_limit(&self, x: f64, v: f64, held: ContactBranch, tolerance: f64) -> f64 {
        let [stiffness, exponent, ..] = &self.parameters;
        contact_step_limit(
            x,
            v,
            &self.lower,
            self.upper.as_ref(),
            [stiffness, exponent],
            held,
            tolerance,
        )
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
        write!(f, "x1 {}", Shown(lower))?;
        if let Some(upper) = upper {
            write!(f, ", x2 {}", Shown(upper))?;
        }
        let [k, e, cmax, d] = [k, e, cmax, d].map(Shown);
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

/// What a simulator sees of `IMPACT` (no `x2`) or `BISTOP` at `x`, `v`
/// with the other arguments as plain numbers, held on `held` (the natural
/// branch when `None`): see [`Observation`].
pub fn switching(
    x: f64,
    v: f64,
    x1: f64,
    x2: Option<f64>,
    [k, e, cmax, d]: [f64; 4],
    held: Option<ContactBranch>,
) -> Observation {
    contact_switching(x, v, &x1, x2.as_ref(), [&k, &e, &cmax, &d], held)
}

/// `IMPACT` (no `x2`) or `BISTOP` on branch `held`, continued past its
/// boundaries.
pub fn held<T: Number>(
    x: &T,
    v: &T,
    x1: &T,
    x2: Option<&T>,
    [k, e, cmax, d]: [&T; 4],
    held: ContactBranch,
) -> T {
    let x2 = x2.map(Varying);
    let parameters = [&Varying(k), &Varying(e), &Varying(cmax), &Varying(d)];
    contact_held(x, v, &Varying(x1), x2.as_ref(), parameters, held)
}

/// The largest step a simulator should take with `IMPACT` (no `x2`) or
/// `BISTOP` held on `held`: for an exponent that is not a whole number
/// (the force `p^e` is then a weak singularity at touch and release) half
/// the time the penetration takes to double or vanish at its current rate,
/// but no less than the step over which the displacement no polynomial
/// follows stays below a thousandth of `tolerance`; unbounded otherwise.
pub fn step_limit(
    x: f64,
    v: f64,
    x1: f64,
    x2: Option<f64>,
    [k, e]: [f64; 2],
    held: ContactBranch,
    tolerance: f64,
) -> f64 {
    contact_step_limit(x, v, &x1, x2.as_ref(), [&k, &e], held, tolerance)
}
