//! FORTRAN intrinsics and the other functions of SPEC 3.1.

use super::{LawError, domain};
use crate::Shown;
use crate::catalog::Function;
use crate::number::Number;

/// Applies an intrinsic to its evaluated arguments.
#[inline]
pub(super) fn apply<T: Number>(function: Function, args: &[&T]) -> Result<T, LawError> {
    use Function as F;
    let a = args[0];
    let x = a.value();
    Ok(match function {
        F::Abs => abs(a),
        F::Sin => a.sin(),
        F::Cos => a.cos(),
        F::Tan => a.tan(),
        F::Asin | F::Acos => {
            if !(-1.0..=1.0).contains(&x) {
                let name = if function == F::Asin { "ASIN" } else { "ACOS" };
                return domain(
                    name,
                    format!("the argument ({}) must be between -1 and 1", Shown(x)),
                );
            }
            if function == F::Asin {
                a.asin()
            } else {
                a.acos()
            }
        }
        F::Atan => a.atan(),
        F::Atan2 => atan2(a, args[1]),
        F::Sinh => a.sinh(),
        F::Cosh => a.cosh(),
        F::Tanh => a.tanh(),
        F::Exp => a.exp(),
        F::Log | F::Log10 => {
            if x <= 0.0 {
                let name = if function == F::Log { "LOG" } else { "LOG10" };
                return domain(
                    name,
                    format!("the argument ({}) must be positive", Shown(x)),
                );
            }
            if function == F::Log {
                a.ln()
            } else {
                a.log10()
            }
        }
        F::Sqrt => {
            if x < 0.0 {
                return domain(
                    "SQRT",
                    format!("the argument ({}) must not be negative", Shown(x)),
                );
            }
            a.sqrt()
        }
        F::Aint => T::from(x.trunc()),
        F::Anint => T::from(x.round()),
        F::Dim => {
            if x > args[1].value() {
                a.clone() - args[1].clone()
            } else {
                T::zero()
            }
        }
        F::Max => extreme(args, |candidate, best| candidate > best),
        F::Min => extreme(args, |candidate, best| candidate < best),
        F::Mod => {
            let b = args[1];
            if b.value() == 0.0 {
                return domain("MOD", format!("the divisor is 0 (MOD({}, 0))", Shown(x)));
            }
            let quotient = (x / b.value()).trunc();
            a.clone() - b.clone() * quotient
        }
        F::Sign => {
            if args[1].value() >= 0.0 {
                abs(a)
            } else {
                -abs(a)
            }
        }
        _ => unreachable!("{function} is not an intrinsic"),
    })
}

/// `ABS(a)`: at 0 the derivative is the one of `a` itself (the `a >= 0` branch).
pub fn abs<T: Number>(a: &T) -> T {
    if a.value() < 0.0 {
        -a.clone()
    } else {
        a.clone()
    }
}

/// `ATAN2(y, x)`, 0 with zero derivatives at the origin. The derivatives
/// come from `x / r^2` and `-y / r^2`, finite wherever `(x, y) != (0, 0)`.
pub fn atan2<T: Number>(y: &T, x: &T) -> T {
    let (y0, x0) = (y.value(), x.value());
    if y0 == 0.0 && x0 == 0.0 {
        return T::zero();
    }
    y.chain2(x, y0.atan2(x0), || {
        let r2 = x0 * x0 + y0 * y0;
        let r4 = r2 * r2;
        [
            x0 / r2,
            -y0 / r2,
            -2.0 * x0 * y0 / r4,
            (y0 * y0 - x0 * x0) / r4,
            2.0 * x0 * y0 / r4,
        ]
    })
}

/// The argument that `better` prefers to all others; the first on a tie.
fn extreme<T: Number>(args: &[&T], better: impl Fn(f64, f64) -> bool) -> T {
    let mut best = args[0];
    for &candidate in &args[1..] {
        if better(candidate.value(), best.value()) {
            best = candidate;
        }
    }
    best.clone()
}
