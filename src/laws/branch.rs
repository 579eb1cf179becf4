//! The branches of the piecewise functions, for a simulator that holds
//! each call on one branch through a step (so that the right-hand side is
//! smooth within the step) and locates where it must switch.
//!
//! For every piecewise call this module gives three things, from the same
//! rules as the plain evaluation:
//! - its *natural* branch at given argument values (the one SPEC 3 and 5
//!   choose), as a [`Code`];
//! - its *switching values* for a held branch: a fixed number of numbers,
//!   each positive (or zero) while the call may stay on that branch and
//!   negative once it has left it, continuous in the arguments, so that a
//!   sign change can be located in time;
//! - its value on a held branch, the branch's formula continued smoothly
//!   past the branch's boundaries.
//!
//! `SWEEP`, the splines and the measures are smooth enough where they are
//! used (continuous first derivatives) and are not held.

use super::contact::{self, ContactBranch};
use super::steps::{self, Shape, StepBranch};
use super::{LawError, domain};
use crate::Shown;
use crate::catalog::Function;
use crate::number::Number;

/// A branch of a piecewise call: a small code per function (the part of a
/// STEP, the side and piece of a contact law, the chosen argument of MAX),
/// or the whole number that AINT, ANINT and MOD hold.
pub type Code = i64;

/// How many switching values a call of `function` with `count` arguments
/// has; `None` for a function that is not held.
pub fn switch_count(function: Function, count: usize) -> Option<usize> {
    use Function as F;
    Some(match function {
        F::Step | F::Step5 | F::Havsin | F::Sign | F::Aint | F::Anint | F::Mod => 2,
        F::Impact | F::Bistop => 3,
        F::Abs | F::Dim => 1,
        F::Max | F::Min => count.saturating_sub(1).max(1),
        _ => return None,
    })
}

/// The natural branch of a call of `function` at `args`, and in `out` its
/// switching values for `held` (for the natural branch when `held` is
/// `None`). `out` has [`switch_count`] entries.
pub fn switching(function: Function, args: &[f64], held: Option<Code>, out: &mut [f64]) -> Code {
    use Function as F;
    let arg = |position: usize| args[position];
    match function {
        F::Step | F::Step5 | F::Havsin => {
            let (x, x0, x1) = (arg(0), arg(1), arg(3));
            let natural = StepBranch::of(x, x0, x1);
            let values = match held.map_or(natural, step_branch) {
                StepBranch::Before => [x0 - x, 1.0],
                StepBranch::Ramp => [x - x0, x1 - x],
                StepBranch::After => [x - x1, 1.0],
            };
            out.copy_from_slice(&values);
            step_code(natural)
        }
        F::Impact | F::Bistop => {
            let (x2, rest) = if function == F::Bistop {
                (Some(arg(3)), &args[4..8])
            } else {
                (None, &args[3..7])
            };
            let parameters = [rest[0], rest[1], rest[2], rest[3]];
            let seen = contact::switching(
                arg(0),
                arg(1),
                arg(2),
                x2,
                parameters,
                held.map(ContactBranch::from_code),
            );
            out.copy_from_slice(&seen.values);
            seen.natural.code()
        }
        F::Abs => {
            let natural = Code::from(arg(0) < 0.0);
            out[0] = if held.unwrap_or(natural) == 1 {
                -arg(0)
            } else {
                arg(0)
            };
            natural
        }
        F::Dim => {
            let natural = Code::from(arg(0) > arg(1));
            out[0] = if held.unwrap_or(natural) == 1 {
                arg(0) - arg(1)
            } else {
                arg(1) - arg(0)
            };
            natural
        }
        F::Sign => {
            let natural = Code::from(arg(1) < 0.0) | (Code::from(arg(0) < 0.0) << 1);
            let branch = held.unwrap_or(natural);
            let oriented = |value: f64, negative: bool| if negative { -value } else { value };
            out[0] = oriented(arg(1), branch & 1 == 1);
            out[1] = oriented(arg(0), branch & 2 == 2);
            natural
        }
        F::Max | F::Min => {
            let better = |candidate: f64, best: f64| {
                if function == F::Max {
                    candidate > best
                } else {
                    candidate < best
                }
            };
            let mut natural = 0;
            for (index, &candidate) in args.iter().enumerate().skip(1) {
                if better(candidate, args[natural]) {
                    natural = index;
                }
            }
            let chosen = held.map_or(natural, |code| usize::try_from(code).unwrap_or(0));
            let chosen_value = args.get(chosen).copied().unwrap_or(args[0]);
            let others = args
                .iter()
                .enumerate()
                .filter(|&(index, _)| index != chosen);
            for (slot, (_, &other)) in out.iter_mut().zip(others) {
                *slot = if function == F::Max {
                    chosen_value - other
                } else {
                    other - chosen_value
                };
            }
            natural as Code
        }
        F::Aint | F::Anint | F::Mod => {
            let (ratio, rounding) = match function {
                F::Aint => (arg(0), Whole::Truncated),
                F::Anint => (arg(0), Whole::Nearest),
                _ => (arg(0) / arg(1), Whole::Truncated),
            };
            let natural = rounding.of(ratio);
            let whole = held.map_or(natural, |code| code as f64);
            let (low, high) = rounding.interval(whole);
            out[0] = ratio - low;
            out[1] = high - ratio;
            natural as Code
        }
        _ => 0,
    }
}

/// The largest step a simulator should take with a call of `function` at
/// `args` held on `held`, for an absolute error `tolerance` in the
/// displacement (see [`contact::step_limit`]); unbounded for all but the
/// contact laws whose exponent is not a whole number.
pub fn step_limit(function: Function, args: &[f64], held: Code, tolerance: f64) -> f64 {
    let branch = ContactBranch::from_code(held);
    match function {
        Function::Impact => {
            let stiffness = [args[3], args[4]];
            contact::step_limit(
                args[0], args[1], args[2], None, stiffness, branch, tolerance,
            )
        }
        Function::Bistop => {
            let (x2, stiffness) = (Some(args[3]), [args[4], args[5]]);
            contact::step_limit(args[0], args[1], args[2], x2, stiffness, branch, tolerance)
        }
        _ => f64::INFINITY,
    }
}

/// The value of a call of `function` on branch `held`, continued past the
/// branch's boundaries. The argument rules are checked by the caller.
pub fn held<T: Number>(function: Function, args: &[&T], held: Code) -> Result<T, LawError> {
    use Function as F;
    let arg = |position: usize| args[position];
    Ok(match function {
        F::Step | F::Step5 | F::Havsin => steps::step_on(
            step_branch(held),
            Shape::of(function),
            arg(0),
            arg(1),
            arg(2),
            arg(3),
            arg(4),
        ),
        F::Impact => contact::held(
            arg(0),
            arg(1),
            arg(2),
            None,
            [arg(3), arg(4), arg(5), arg(6)],
            ContactBranch::from_code(held),
        ),
        F::Bistop => contact::held(
            arg(0),
            arg(1),
            arg(2),
            Some(arg(3)),
            [arg(4), arg(5), arg(6), arg(7)],
            ContactBranch::from_code(held),
        ),
        F::Abs => {
            if held == 1 {
                -arg(0).clone()
            } else {
                arg(0).clone()
            }
        }
        F::Dim => {
            if held == 1 {
                arg(0).clone() - arg(1).clone()
            } else {
                T::zero()
            }
        }
        F::Sign => {
            let magnitude = if held & 2 == 2 {
                -arg(0).clone()
            } else {
                arg(0).clone()
            };
            if held & 1 == 1 { -magnitude } else { magnitude }
        }
        F::Max | F::Min => usize::try_from(held)
            .ok()
            .and_then(|index| args.get(index))
            .map_or_else(|| arg(0).clone(), |&chosen| chosen.clone()),
        F::Aint | F::Anint => T::from(held as f64),
        F::Mod => {
            if arg(1).value() == 0.0 {
                return domain(
                    "MOD",
                    format!("the divisor is 0 (MOD({}, 0))", Shown(arg(0).value())),
                );
            }
            arg(0).clone() - arg(1).clone() * (held as f64)
        }
        _ => return super::apply(function, args),
    })
}

/// A short name of branch `code` of `function`, for event lists.
pub fn describe(function: Function, code: Code) -> String {
    use Function as F;
    match function {
        F::Step | F::Step5 | F::Havsin => match step_branch(code) {
            StepBranch::Before => "x <= x0".to_string(),
            StepBranch::Ramp => "ramp".to_string(),
            StepBranch::After => "x >= x1".to_string(),
        },
        F::Impact | F::Bistop => ContactBranch::from_code(code).name().to_string(),
        F::Abs => if code == 1 {
            "negative"
        } else {
            "not negative"
        }
        .to_string(),
        F::Dim => if code == 1 { "a > b" } else { "a <= b" }.to_string(),
        F::Sign => format!(
            "{} a, b {}",
            if code & 2 == 2 {
                "negative"
            } else {
                "non-negative"
            },
            if code & 1 == 1 { "< 0" } else { ">= 0" }
        ),
        F::Max | F::Min => format!("argument {}", code + 1),
        F::Aint | F::Anint | F::Mod => format!("whole part {code}"),
        F::Delay => if code == 0 { "history" } else { "record" }.to_string(),
        _ => code.to_string(),
    }
}

/// The natural branch of an arithmetic IF with condition `e1` (0 negative,
/// 1 zero, 2 positive) and its two switching values for `held`.
pub fn arithmetic_if(e1: f64, held: Option<Code>) -> (Code, [f64; 2]) {
    let natural = if e1 < 0.0 {
        0
    } else if e1 == 0.0 {
        1
    } else {
        2
    };
    let values = match held.unwrap_or(natural) {
        0 => [-e1, 1.0],
        1 => [e1, -e1],
        _ => [e1, 1.0],
    };
    (natural, values)
}

/// A short name of an arithmetic IF's branch.
pub fn describe_if(code: Code) -> &'static str {
    match code {
        0 => "e1 < 0",
        1 => "e1 = 0",
        _ => "e1 > 0",
    }
}

fn step_branch(code: Code) -> StepBranch {
    match code {
        0 => StepBranch::Before,
        1 => StepBranch::Ramp,
        _ => StepBranch::After,
    }
}

fn step_code(branch: StepBranch) -> Code {
    match branch {
        StepBranch::Before => 0,
        StepBranch::Ramp => 1,
        StepBranch::After => 2,
    }
}

/// How AINT and MOD (toward zero) and ANINT (nearest, halves away from
/// zero) take a whole number.
#[derive(Clone, Copy)]
enum Whole {
    Truncated,
    Nearest,
}

impl Whole {
    fn of(self, value: f64) -> f64 {
        match self {
            Whole::Truncated => value.trunc(),
            Whole::Nearest => value.round(),
        }
    }

    /// The interval of values that give `whole` (its ends may belong to
    /// the next whole number: a tie is not a sign change).
    fn interval(self, whole: f64) -> (f64, f64) {
        match self {
            Whole::Truncated if whole > 0.0 => (whole, whole + 1.0),
            Whole::Truncated if whole < 0.0 => (whole - 1.0, whole),
            Whole::Truncated => (-1.0, 1.0),
            Whole::Nearest => (whole - 0.5, whole + 0.5),
        }
    }
}
