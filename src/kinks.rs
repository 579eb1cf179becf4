//! Where a piecewise function changes branch, so that a plot or a sampling
//! of an expression does not step over a kink.

use crate::catalog::Function;
use crate::check::{Argument, Checked, Node, NodeKind, constant_value, visit};

/// The values of `variable` at which a `STEP`, `STEP5`, `HAVSIN`, `IMPACT`,
/// `BISTOP`, `ABS`, `DIM`, `SIGN` or arithmetic `IF` in `checked` changes
/// branch, where the function's first argument is `variable` itself (or
/// `variable` plus or minus a constant) and the break points are constants.
/// Sorted, each once.
pub fn breakpoints(checked: &Checked, variable: &str) -> Vec<f64> {
    let mut points = Vec::new();
    visit(&checked.root, &mut |node| {
        let (function, args) = match &node.kind {
            NodeKind::Call(function, args) => (*function, args.as_slice()),
            NodeKind::If(branches) => {
                if let Some(shift) = offset_of(&branches[0], variable) {
                    points.push(-shift);
                }
                return;
            }
            _ => return,
        };
        let value = |position: usize| match args.get(position) {
            Some(Argument::Value(node)) => constant_value(node),
            _ => None,
        };
        let Some(Argument::Value(first)) = args.first() else {
            return;
        };
        let Some(shift) = offset_of(first, variable) else {
            return;
        };
        // Break points in the argument, carried back to the variable.
        let at = |argument: Option<f64>| argument.map(|point| point - shift);
        let found: Vec<Option<f64>> = match function {
            Function::Step | Function::Step5 | Function::Havsin => vec![at(value(1)), at(value(3))],
            Function::Impact => vec![
                at(value(2)),
                at(value(2).zip(value(6)).map(|(x1, d)| x1 - d)),
            ],
            Function::Bistop => vec![
                at(value(2)),
                at(value(3)),
                at(value(2).zip(value(7)).map(|(x1, d)| x1 - d)),
                at(value(3).zip(value(7)).map(|(x2, d)| x2 + d)),
            ],
            Function::Abs | Function::Sign => vec![at(Some(0.0))],
            Function::Dim => vec![at(value(1))],
            _ => Vec::new(),
        };
        points.extend(found.into_iter().flatten());
    });
    points.retain(|point| point.is_finite());
    points.sort_by(f64::total_cmp);
    points.dedup();
    points
}

/// `c` when `node` is `variable + c` (or `variable`, `variable - c`, `c + variable`).
fn offset_of(node: &Node, variable: &str) -> Option<f64> {
    use crate::syntax::ast::BinaryOp;
    match &node.kind {
        NodeKind::Variable(name) if name.eq_ignore_ascii_case(variable) => Some(0.0),
        NodeKind::Chain(first, rest) => match rest.as_slice() {
            [(BinaryOp::Add, rhs)] => offset_of(first, variable)
                .zip(constant_value(rhs))
                .or_else(|| offset_of(rhs, variable).zip(constant_value(first)))
                .map(|(shift, constant)| shift + constant),
            [(BinaryOp::Sub, rhs)] => offset_of(first, variable)
                .zip(constant_value(rhs))
                .map(|(shift, constant)| shift - constant),
            _ => None,
        },
        _ => None,
    }
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
