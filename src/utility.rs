//! The solver's utility subroutines (SPEC section 6) for Rust callers:
//! `BISTOP`, `IMPACT` and `STEP` with the calling sequence of user
//! subroutines, returning the force or its partial derivatives as the
//! three-entry `VECTOR`. The arithmetic is the expression evaluator's own
//! ([`crate::laws`]); `src/ffi.rs` exposes the same to C and FORTRAN.
//!
//! | VECTOR | iord = 0 | iord = 1 | iord = 2 |
//! |---|---|---|---|
//! | 1 | F | dF/dx | d2F/dx2 |
//! | 2 | 0 | dF/dx' | d2F/dx dx' |
//! | 3 | 0 | 0 | d2F/dx'2 (always 0) |
//!
//! Every entry returned is a finite number: where the force, or a
//! derivative asked for, is beyond the range of a double, the call fails
//! ([`UtilityError::BeyondRange`]; ERRFLG from C and FORTRAN), as the
//! evaluator reports the same expression as an error. The laws are
//! computed so that no intermediate passes the range where the result
//! does not (`docs/contact.md`).
//!
//! ```
//! // 0.05 beyond the upper wall, moving outwards: a restoring force.
//! let force = mbexpr::utility::bistop(10.05, 0.7, -10.0, 10.0, 1e5, 2.2, 100.0, 0.1, 0).unwrap();
//! assert!(force[0] < 0.0 && force[1] == 0.0);
//! let slopes = mbexpr::utility::bistop(10.05, 0.7, -10.0, 10.0, 1e5, 2.2, 100.0, 0.1, 1).unwrap();
//! assert!((slopes[1] - -50.0).abs() < 1e-9); // dF/dx' = -c, half of cmax mid-ramp
//! ```

use num_dual::{Dual2SVec64, DualSVec64};
use thiserror::Error;

use crate::Shown;
use crate::catalog::{Function, RuleViolation, check_rules_with};
use crate::laws::{contact, steps};
use crate::number::{Directional, Number};

/// Why a utility call has no result (ERRFLG is set).
#[derive(Clone, Debug, Error, PartialEq)]
pub enum UtilityError {
    /// An argument rule of SPEC 3.3 (or 3.2) is broken.
    #[error("{0}")]
    Rule(RuleViolation),
    /// IORD is not 0, 1 or 2.
    #[error("iord ({0}) must be 0, 1 or 2")]
    Order(i32),
    /// An input is NaN or infinite.
    #[error("{function}: {argument} ({}) is not a finite number", Shown(*value))]
    NotFinite {
        /// The subroutine.
        function: &'static str,
        /// The argument's name.
        argument: &'static str,
        /// Its value.
        value: f64,
    },
    /// An entry of the result is beyond the range of a double.
    #[error("{function}: {quantity} is beyond the range of a double here")]
    BeyondRange {
        /// The subroutine.
        function: &'static str,
        /// The entry, as `F`, `dF/dx`, `d2F/dx dx'`, ...
        quantity: &'static str,
    },
}

/// Checks finiteness and the function's rules, in argument order.
fn validate(
    function: Function,
    names: &[&'static str],
    values: &[f64],
    iord: i32,
) -> Result<(), UtilityError> {
    for (&argument, &value) in names.iter().zip(values) {
        if !value.is_finite() {
            return Err(UtilityError::NotFinite {
                function: function.name(),
                argument,
                value,
            });
        }
    }
    check_rules_with(function, |position| values.get(position).copied())
        .map_err(UtilityError::Rule)?;
    if !(0..=2).contains(&iord) {
        return Err(UtilityError::Order(iord));
    }
    Ok(())
}

/// A law of (x, x') with its parameters, evaluable over any number type.
trait Law {
    fn at<T: Number>(&self, x: &T, v: &T) -> T;
}

/// BISTOP's parameters.
struct Bistop([f64; 6]);

impl Law for Bistop {
    fn at<T: Number>(&self, x: &T, v: &T) -> T {
        let [x1, x2, k, e, cmax, d] = self.0.map(T::from);
        contact::bistop(x, v, &x1, &x2, &k, &e, &cmax, &d)
    }
}

/// IMPACT's parameters.
struct Impact([f64; 5]);

impl Law for Impact {
    fn at<T: Number>(&self, x: &T, v: &T) -> T {
        let [x1, k, e, cmax, d] = self.0.map(T::from);
        contact::impact(x, v, &x1, &k, &e, &cmax, &d)
    }
}

/// `values` with `-0` as `+0`, or the error naming the first entry that is
/// not a finite number (`quantities` names the entries).
fn finite<const N: usize>(
    function: Function,
    values: [f64; N],
    quantities: [&'static str; N],
) -> Result<[f64; N], UtilityError> {
    match values.iter().position(|value| !value.is_finite()) {
        Some(position) => Err(UtilityError::BeyondRange {
            function: function.name(),
            quantity: quantities[position],
        }),
        None => Ok(values.map(|value| value + 0.0)),
    }
}

/// The VECTOR of `law` at (x, x') for `iord` (already checked to be 0, 1
/// or 2), or the error for an entry beyond the range of a double.
fn vector(
    function: Function,
    law: &impl Law,
    x: f64,
    v: f64,
    iord: i32,
) -> Result<[f64; 3], UtilityError> {
    fn seeded<T: Directional>(law: &impl Law, x: f64, v: f64) -> T {
        law.at(&T::variable(x, 0, 2), &T::variable(v, 1, 2))
    }
    let [first, second] = match iord {
        0 => {
            let [force] = finite(function, [law.at(&x, &v)], ["the force"])?;
            [force, 0.0]
        }
        1 => {
            let gradient = seeded::<DualSVec64<2>>(law, x, v).gradient(2);
            finite(function, [gradient[0], gradient[1]], ["dF/dx", "dF/dx'"])?
        }
        _ => {
            let hessian = seeded::<Dual2SVec64<2>>(law, x, v)
                .hessian(2)
                .expect("second-order numbers carry a Hessian");
            finite(
                function,
                [hessian[(0, 0)], hessian[(0, 1)]],
                ["d2F/dx2", "d2F/dx dx'"],
            )?
        }
    };
    Ok([first, second, 0.0])
}

/// `CALL BISTOP(X, XD, X1, X2, K, E, CMAX, D, IORD, VECTOR, ERRFLG)`: the
/// two-sided contact force (SPEC 3.3) or its derivatives, as VECTOR.
#[expect(clippy::too_many_arguments, reason = "the solver's calling sequence")]
pub fn bistop(
    x: f64,
    xd: f64,
    x1: f64,
    x2: f64,
    k: f64,
    e: f64,
    cmax: f64,
    d: f64,
    iord: i32,
) -> Result<[f64; 3], UtilityError> {
    let values = [x, xd, x1, x2, k, e, cmax, d];
    let names = ["x", "x'", "x1", "x2", "k", "e", "cmax", "d"];
    validate(Function::Bistop, &names, &values, iord)?;
    vector(
        Function::Bistop,
        &Bistop([x1, x2, k, e, cmax, d]),
        x,
        xd,
        iord,
    )
}

/// `CALL IMPACT(X, XD, X1, K, E, CMAX, D, IORD, VECTOR, ERRFLG)`: the
/// one-sided contact force (SPEC 3.3) or its derivatives, as VECTOR.
#[expect(clippy::too_many_arguments, reason = "the solver's calling sequence")]
pub fn impact(
    x: f64,
    xd: f64,
    x1: f64,
    k: f64,
    e: f64,
    cmax: f64,
    d: f64,
    iord: i32,
) -> Result<[f64; 3], UtilityError> {
    let values = [x, xd, x1, k, e, cmax, d];
    let names = ["x", "x'", "x1", "k", "e", "cmax", "d"];
    validate(Function::Impact, &names, &values, iord)?;
    vector(Function::Impact, &Impact([x1, k, e, cmax, d]), x, xd, iord)
}

/// `CALL STEP(X, X0, H0, X1, H1, IORD, VALUE, ERRFLG)`: the cubic step
/// (SPEC 3.2) or its first or second derivative in `x`.
pub fn step(x: f64, x0: f64, h0: f64, x1: f64, h1: f64, iord: i32) -> Result<f64, UtilityError> {
    let values = [x, x0, h0, x1, h1];
    validate(
        Function::Step,
        &["x", "x0", "h0", "x1", "h1"],
        &values,
        iord,
    )?;
    let law = |x: &Dual2SVec64<1>| {
        let [x0, h0, x1, h1] = [x0, h0, x1, h1].map(Dual2SVec64::<1>::from);
        steps::step(steps::Shape::Cubic, x, &x0, &h0, &x1, &h1)
    };
    let result = law(&Dual2SVec64::<1>::variable(x, 0, 1));
    let [value] = match iord {
        0 => finite(Function::Step, [result.value()], ["the value"]),
        1 => finite(Function::Step, [result.gradient(1)[0]], ["d/dx"]),
        _ => finite(
            Function::Step,
            [result
                .hessian(1)
                .expect("second-order numbers carry a Hessian")[(0, 0)]],
            ["d2/dx2"],
        ),
    }?;
    Ok(value)
}
