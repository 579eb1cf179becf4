//! Where a piecewise function changes branch along one input of a compiled
//! program, so that a plot or a sampling of an expression does not step
//! over a kink.
//!
//! The break points are found through the program, not the text: every
//! piecewise instruction (STEP, STEP5, HAVSIN, IMPACT, BISTOP with its
//! clamp, ABS, SIGN, DIM, MAX, MIN, MOD, AINT, ANINT, the arithmetic IF)
//! reports its branch as the program runs ([`crate::Evaluator::observe`],
//! the rules of [`crate::laws::branch`] that the simulator uses too), and
//! where one differs between two samples the change is found by bisection.
//! So the input may be `TIME`, a scene's state seen through a measure, or
//! any expression of the plotted variable.

use crate::compile::Program;
use crate::laws::branch::Code;

/// The values of input `along` at which a piecewise function of `program`
/// changes branch, between the first and last of `samples` (sorted), the
/// other inputs at `inputs`. Each is found between two neighbouring samples
/// whose branches differ, down to neighbouring doubles, so a branch
/// entered and left again between two samples is not seen. Sorted, each
/// once.
pub fn breakpoints(program: &Program, inputs: &[f64], along: usize, samples: &[f64]) -> Vec<f64> {
    let mut evaluator = program.evaluator::<f64>();
    let mut point = inputs.to_vec();
    let mut natural = vec![None; program.sites().len()];
    let mut switching = vec![0.0; program.switch_count()];
    let mut outputs = vec![0.0; program.output_count()];
    // The branch of every site that runs at `x` (a failed evaluation still
    // shows the sites before the failure).
    let mut at = |x: f64| -> Vec<Option<Code>> {
        point[along] = x;
        let branches = (&mut natural[..], &mut switching[..]);
        let _ = evaluator.observe(&point, None, branches, &mut outputs, None);
        natural.clone()
    };
    let mut found = Vec::new();
    let mut previous: Option<(f64, Vec<Option<Code>>)> = None;
    for &x in samples {
        let current = at(x);
        if let Some((before, seen)) = &previous {
            for (site, (a, b)) in seen.iter().zip(&current).enumerate() {
                if let (Some(a), Some(b)) = (a, b)
                    && a != b
                {
                    found.push(change_between(*before, x, |x| at(x)[site] == Some(*a)));
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

/// The first point after `a` where `unchanged` stops holding, between `a`
/// (where it holds) and `b` (where it does not), by bisection down to
/// neighbouring doubles.
fn change_between(mut a: f64, mut b: f64, mut unchanged: impl FnMut(f64) -> bool) -> f64 {
    loop {
        let middle = a + (b - a) / 2.0;
        if middle == a || middle == b {
            return b;
        }
        if unchanged(middle) {
            a = middle;
        } else {
            b = middle;
        }
    }
}

/// `count` evenly spaced values from `start` to `end`, with each break point
/// inside the range added together with the double below it (each once),
/// sorted: a break point of [`breakpoints`] is the first double on the new
/// branch, the one below it the last on the old, so both sides of every
/// kink are sampled alike, whichever way the branch changes.
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
            .flat_map(|&point| [point.next_down(), point])
            .filter(|point| (low..=high).contains(point)),
    );
    values.sort_by(f64::total_cmp);
    values.dedup();
    values
}
