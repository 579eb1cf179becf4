//! The math rules of the language, each written once, generic over
//! [`Number`] so that one definition serves values,
//! gradients and Hessians, the expression evaluator and the utility
//! subroutines alike. Piecewise rules branch on the real part, exactly as
//! SPEC section 5 says.

pub mod branch;
pub mod contact;
pub mod intrinsics;
pub mod power;
pub(crate) mod range;
pub mod series;
pub mod spline;
pub mod steps;

use thiserror::Error;

use crate::catalog::{Function, RuleViolation};
use crate::number::Number;

/// A value outside a function's domain, or a broken argument rule.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum LawError {
    /// The argument is outside the domain (`LOG(0)`, `SQRT(-1)`, `x/0`).
    #[error("{operation}: {reason}")]
    Domain {
        /// The function or operator, as written in messages.
        operation: &'static str,
        /// What is wrong, with the values involved.
        reason: String,
    },
    /// An argument rule of SPEC 3 is broken (`x1 >= x2`, `d <= 0`).
    #[error("{0}")]
    Rule(RuleViolation),
}

/// Shorthand for a domain error.
pub(crate) fn domain<T>(operation: &'static str, reason: String) -> Result<T, LawError> {
    Err(LawError::Domain { operation, reason })
}

/// Applies a function of the intrinsic, step, contact or series family to
/// evaluated arguments (already checked against the function's rules).
///
/// # Panics
/// When `function` belongs to another family (measures, model data, solver
/// results): the compiler never emits those as calls.
#[inline]
pub fn apply<T: Number>(function: Function, args: &[&T]) -> Result<T, LawError> {
    use Function as F;
    let arg = |position: usize| args[position];
    Ok(match function {
        F::Step | F::Step5 | F::Havsin => steps::step(
            steps::Shape::of(function),
            arg(0),
            arg(1),
            arg(2),
            arg(3),
            arg(4),
        ),
        F::Impact => contact::impact(arg(0), arg(1), arg(2), arg(3), arg(4), arg(5), arg(6)),
        F::Bistop => contact::bistop(
            arg(0),
            arg(1),
            arg(2),
            arg(3),
            arg(4),
            arg(5),
            arg(6),
            arg(7),
        ),
        F::Shf => series::shf(arg(0), arg(1), arg(2), arg(3), arg(4), arg(5)),
        F::Poly => series::poly(arg(0), arg(1), &args[2..]),
        F::Cheby => series::cheby(arg(0), arg(1), &args[2..]),
        F::Forcos => series::fourier(series::Wave::Cosine, arg(0), arg(1), arg(2), &args[3..]),
        F::Forsin => series::fourier(series::Wave::Sine, arg(0), arg(1), arg(2), &args[3..]),
        F::Sweep => series::sweep(arg(0), arg(1), arg(2), arg(3), arg(4), arg(5), arg(6)),
        _ => return intrinsics::apply(function, args),
    })
}
