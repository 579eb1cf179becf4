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
        F::Sin => sin(a),
        F::Cos => cos(a),
        F::Tan => {
            let tan = x.tan();
            // 1 + tan^2 stays below 1e33 for every double.
            a.chain(tan, || {
                let slope = 1.0 + tan * tan;
                (slope, 2.0 * tan * slope)
            })
        }
        F::Asin | F::Acos => {
            if !(-1.0..=1.0).contains(&x) {
                let name = if function == F::Asin { "ASIN" } else { "ACOS" };
                return domain(
                    name,
                    format!("the argument ({}) must be between -1 and 1", Shown(x)),
                );
            }
            // 1 - x^2 as (1 - x)(1 + x): exact digits near +-1.
            let (sign, value) = if function == F::Asin {
                (1.0, x.asin())
            } else {
                (-1.0, x.acos())
            };
            a.chain(value, || {
                let room = (1.0 - x) * (1.0 + x);
                let slope = 1.0 / room.sqrt();
                (sign * slope, sign * (x * slope / room))
            })
        }
        F::Atan => a.chain(x.atan(), || {
            // 1 / (1 + x^2), as (1/x)^2 / (1 + (1/x)^2) beyond 1, where x^2
            // would overflow while the result is still a double.
            let slope = if x.abs() <= 1.0 {
                1.0 / (1.0 + x * x)
            } else {
                let r = 1.0 / x;
                r * r / (1.0 + r * r)
            };
            (slope, -2.0 * (x * slope) * slope)
        }),
        F::Atan2 => atan2(a, args[1]),
        F::Sinh => a.chain(x.sinh(), || (x.cosh(), x.sinh())),
        F::Cosh => a.chain(x.cosh(), || (x.sinh(), x.cosh())),
        F::Tanh => {
            let tanh = x.tanh();
            // sech^2 = 1 / cosh^2, not 1 - tanh^2 (which is 0 from |x| = 19
            // on, and num-dual's sinh/cosh is NaN from 710 on).
            a.chain(tanh, || {
                let sech = 1.0 / x.cosh();
                let slope = sech * sech;
                (slope, -2.0 * tanh * slope)
            })
        }
        F::Exp => {
            let exp = x.exp();
            a.chain(exp, || (exp, exp))
        }
        F::Log | F::Log10 => {
            if x <= 0.0 {
                let name = if function == F::Log { "LOG" } else { "LOG10" };
                return domain(
                    name,
                    format!("the argument ({}) must be positive", Shown(x)),
                );
            }
            // The slope as a quotient, never 1/x times a constant (1/x
            // overflows from x = 5.6e-309 on, log10(e)/x only from 2.4e-309).
            let (value, numerator) = if function == F::Log {
                (x.ln(), 1.0)
            } else {
                (x.log10(), std::f64::consts::LOG10_E)
            };
            a.chain(value, || {
                let slope = numerator / x;
                (slope, -(slope / x))
            })
        }
        F::Sqrt => {
            if x < 0.0 {
                return domain(
                    "SQRT",
                    format!("the argument ({}) must not be negative", Shown(x)),
                );
            }
            sqrt(a)
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
            let divisor = b.value();
            if divisor == 0.0 {
                return domain("MOD", format!("the divisor is 0 (MOD({}, 0))", Shown(x)));
            }
            // The remainder exactly (`%` is C's fmod), not a - AINT(a/b)*b,
            // whose a/b overflows for MOD(1e300, 1e-300); its slopes are 1
            // in a and -AINT(a/b) in b.
            let remainder = x % divisor;
            a.chain2(
                b,
                remainder,
                || [1.0, -((x - remainder) / divisor).round()],
                || [0.0; 3],
            )
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

/// `SIN(a)`, through [`Number::chain`] like every intrinsic (num-dual's own
/// chain rule forms the Hessian term as `(a'^T a') f''`, which overflows to
/// NaN where `f''` is 0 and `a'` beyond 1e154).
pub fn sin<T: Number>(a: &T) -> T {
    let x = a.value();
    a.chain(x.sin(), || {
        let (sin, cos) = x.sin_cos();
        (cos, -sin)
    })
}

/// `COS(a)` (see [`sin`]).
pub fn cos<T: Number>(a: &T) -> T {
    let x = a.value();
    a.chain(x.cos(), || {
        let (sin, cos) = x.sin_cos();
        (-sin, -cos)
    })
}

/// `SQRT(a)` for `a >= 0`: the slope `1 / (2 sqrt(a))` from the root, never
/// as `sqrt(a) / a` (which overflows for a subnormal `a` whose slope is a
/// double), and the curvature `-slope / (2a)`.
pub fn sqrt<T: Number>(a: &T) -> T {
    let x = a.value();
    let root = x.sqrt();
    a.chain(root, || {
        let slope = 0.5 / root;
        (slope, -0.5 * slope / x)
    })
}

/// `ATAN2(y, x)`, 0 with zero derivatives at the origin. The derivatives
/// `x / r^2`, `-y / r^2`, ... are formed from the coordinates divided by
/// the larger of them, `s`, and then divided by `s` once or twice: `r^2`
/// and `r^4` themselves overflow from 1e154 and 1e77 on, and underflow
/// below their reciprocals.
pub fn atan2<T: Number>(y: &T, x: &T) -> T {
    let (y0, x0) = (y.value(), x.value());
    if y0 == 0.0 && x0 == 0.0 {
        return T::zero();
    }
    // The coordinates over the larger, and r^2 over its square (1 to 2).
    let scaled = || {
        let s = x0.abs().max(y0.abs());
        let (xs, ys) = (x0 / s, y0 / s);
        (s, xs, ys, xs * xs + ys * ys)
    };
    y.chain2(
        x,
        y0.atan2(x0),
        || {
            let (s, xs, ys, r2) = scaled();
            [xs / r2 / s, -ys / r2 / s]
        },
        || {
            let (s, xs, ys, r2) = scaled();
            let r4 = r2 * r2;
            [
                -2.0 * xs * ys / r4 / s / s,
                (ys * ys - xs * xs) / r4 / s / s,
                2.0 * xs * ys / r4 / s / s,
            ]
        },
    )
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
