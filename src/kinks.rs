//! Where a piecewise function changes branch along one input of a compiled
//! program, so that a plot or a sampling of an expression does not step
//! over a kink.
//!
//! The break points are found through the program, not the text: each
//! branching instruction (STEP, STEP5, HAVSIN, IMPACT, BISTOP, ABS, SIGN,
//! DIM, two-argument MAX and MIN, the arithmetic IF) has switch values, the
//! differences between its argument and its break points, whose sign says
//! the branch. They are observed as the program runs at each sample, and
//! where one changes sign between two samples its zero is found by
//! bracketing. So the input may be `TIME`, a scene's state seen through a
//! measure, or any expression of the plotted variable.

use crate::catalog::Function;
use crate::compile::{Instruction, Op, Program, Tables};

/// Up to four switch values of one instruction (BISTOP has four).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Switches {
    values: [f64; 4],
    count: usize,
}

impl Switches {
    fn of(values: &[f64]) -> Switches {
        let mut switches = Switches {
            values: [0.0; 4],
            count: values.len(),
        };
        switches.values[..values.len()].copy_from_slice(values);
        switches
    }
}

/// The switch values of `instruction` over `slots`, when it branches.
fn switches(instruction: &Instruction, slots: &[f64], tables: &Tables) -> Option<Switches> {
    let Instruction::Compute { op, .. } = instruction else {
        return match instruction {
            Instruction::Branch { condition, .. } => {
                Some(Switches::of(&[slots[*condition as usize]]))
            }
            _ => None,
        };
    };
    match op {
        Op::Call { function, args, .. } => {
            let arg = |position: usize| slots[args[position] as usize];
            let values: &[f64] = &match (function, args.len()) {
                (Function::Step | Function::Step5 | Function::Havsin, _) => {
                    vec![arg(0) - arg(1), arg(0) - arg(3)]
                }
                (Function::Impact, _) => vec![arg(0) - arg(2), arg(0) - (arg(2) - arg(6))],
                (Function::Bistop, _) => vec![
                    arg(0) - arg(2),
                    arg(0) - arg(3),
                    arg(0) - (arg(2) - arg(7)),
                    arg(0) - (arg(3) + arg(7)),
                ],
                (Function::Abs, _) => vec![arg(0)],
                (Function::Sign, _) => vec![arg(0), arg(1)],
                (Function::Dim | Function::Max | Function::Min, 2) => vec![arg(0) - arg(1)],
                _ => return None,
            };
            Some(Switches::of(values))
        }
        Op::Contact { table, x, .. } => {
            let x = slots[*x as usize];
            let (lower, upper, [.., d]) = tables.contacts[*table as usize].values();
            let mut values = vec![x - lower, x - (lower - d)];
            if let Some(upper) = upper {
                values.extend([x - upper, x - (upper + d)]);
            }
            Some(Switches::of(&values))
        }
        _ => None,
    }
}

/// The switch values of every branching instruction that runs at `inputs`
/// (by instruction index); an instruction that does not run (a branch not
/// taken, or evaluation failed before it) has none.
fn observe(program: &Program, inputs: &[f64]) -> Vec<Option<Switches>> {
    let mut seen = vec![None; program.code.len()];
    let mut evaluator = program.evaluator::<f64>();
    // A failed evaluation still shows the instructions before the failure.
    let _ = evaluator.trace(inputs, |index, slots| {
        seen[index] = switches(&program.code[index], slots, &program.tables);
    });
    seen
}

/// Whether `value` is on the upper side of a switch.
fn side(value: f64) -> bool {
    value > 0.0
}

/// The values of input `along` at which a piecewise function of `program`
/// changes branch, between the first and last of `samples` (sorted), the
/// other inputs at `inputs`. Each is found between two neighbouring samples
/// whose switch values lie on either side of a break point, so a branch
/// entered and left again between two samples is not seen. Sorted, each
/// once.
pub fn breakpoints(program: &Program, inputs: &[f64], along: usize, samples: &[f64]) -> Vec<f64> {
    let mut point = inputs.to_vec();
    let mut at = |x: f64| {
        point[along] = x;
        observe(program, &point)
    };
    let mut found = Vec::new();
    let mut previous: Option<(f64, Vec<Option<Switches>>)> = None;
    for &x in samples {
        let current = at(x);
        if let Some((before, seen)) = &previous {
            for (index, (a, b)) in seen.iter().zip(&current).enumerate() {
                let (Some(a), Some(b)) = (a, b) else {
                    continue;
                };
                for switch in 0..a.count.min(b.count) {
                    let (ga, gb) = (a.values[switch], b.values[switch]);
                    if ga.is_finite() && gb.is_finite() && side(ga) != side(gb) {
                        let value = |x: f64| at(x)[index].map(|seen| seen.values[switch]);
                        found.push(zero_between((*before, ga), (x, gb), value));
                    }
                }
            }
        }
        previous = Some((x, current));
    }
    found.retain(|point| point.is_finite());
    found.sort_by(f64::total_cmp);
    found.dedup();
    found
}

/// Where `value` (finite, on different sides at `a` and `b`) crosses zero:
/// regula falsi with the Illinois halving, down to neighbouring doubles or
/// an exact zero. Where the function stops having a value, the best point
/// so far is kept.
fn zero_between(
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
    mut value: impl FnMut(f64) -> Option<f64>,
) -> f64 {
    let mut kept = 0i8;
    for _ in 0..200 {
        if ga == 0.0 {
            return a;
        }
        if gb == 0.0 {
            return b;
        }
        let secant = b - gb * (b - a) / (gb - ga);
        let (low, high) = (a.min(b), a.max(b));
        // Where the secant leaves the bracket or stalls, bisect.
        let mut x = if secant > low && secant < high {
            secant
        } else {
            low + (high - low) / 2.0
        };
        if x <= low || x >= high {
            x = low + (high - low) / 2.0;
            if x <= low || x >= high {
                break;
            }
        }
        let Some(gx) = value(x).filter(|gx| gx.is_finite()) else {
            break;
        };
        if side(gx) == side(gb) {
            (b, gb) = (x, gx);
            if kept == 1 {
                ga /= 2.0;
            }
            kept = 1;
        } else {
            (a, ga) = (x, gx);
            if kept == -1 {
                gb /= 2.0;
            }
            kept = -1;
        }
    }
    if ga.abs() <= gb.abs() { a } else { b }
}

/// `count` evenly spaced values from `start` to `end`, with the break points
/// inside the range added (each once), sorted.
pub fn samples(start: f64, end: f64, count: usize, breakpoints: &[f64]) -> Vec<f64> {
    let count = count.max(2);
    let step = (end - start) / (count - 1) as f64;
    let mut values: Vec<f64> = (0..count)
        .map(|index| start + step * index as f64)
        .collect();
    let (low, high) = (start.min(end), start.max(end));
    values.extend(
        breakpoints
            .iter()
            .copied()
            .filter(|point| (low..=high).contains(point)),
    );
    values.sort_by(f64::total_cmp);
    values.dedup();
    values
}
