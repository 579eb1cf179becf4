//! Bulk values of straight-line arithmetic (a program of `+`, `-`, `*`,
//! negation and copies only: no function, no branch), a block of points
//! at a time: each instruction runs over every point of the block, so its
//! dispatch, slot look-ups and bounds checks are paid once per block
//! instead of once per point, and its loop is the processor's vector
//! arithmetic. Each point's value is the same operations in the same
//! order as [`Evaluator::value`](super::Evaluator::value) there, and a
//! point fails where any input or intermediate is not finite, as there.

use crate::compile::{Instruction, Program, Slot};

/// The points of a block.
const LANES: usize = 64;

/// The most slots a program may have for its blocks (a block of slots is
/// `8 * LANES * slots` bytes: 512 KiB here).
const MOST_SLOTS: usize = 1024;

/// One instruction of straight-line arithmetic, its slots as indices.
#[derive(Clone, Copy)]
enum Lanewise {
    Neg(usize, usize),
    Add(usize, usize, usize),
    Sub(usize, usize, usize),
    Mul(usize, usize, usize),
    Copy(usize, usize),
}

/// The program's instructions as lanewise ones, or `None` when it has a
/// function, a branch, or too many slots.
fn lanewise(program: &Program) -> Option<Vec<Lanewise>> {
    if program.slot_count > MOST_SLOTS {
        return None;
    }
    let index = |slot: &Slot| *slot as usize;
    program
        .code
        .iter()
        .map(|instruction| match instruction {
            Instruction::Neg { dst, a } => Some(Lanewise::Neg(index(dst), index(a))),
            Instruction::Add { dst, a, b } => Some(Lanewise::Add(index(dst), index(a), index(b))),
            Instruction::Sub { dst, a, b } => Some(Lanewise::Sub(index(dst), index(a), index(b))),
            Instruction::Mul { dst, a, b } => Some(Lanewise::Mul(index(dst), index(a), index(b))),
            Instruction::Copy { dst, src } => Some(Lanewise::Copy(index(dst), index(src))),
            Instruction::Compute { .. } | Instruction::Branch { .. } | Instruction::Jump { .. } => {
                None
            }
        })
        .collect()
}

/// `f` of each lane of `a` and `b`.
#[inline(always)]
fn each(a: &[f64; LANES], b: &[f64; LANES], f: impl Fn(f64, f64) -> f64) -> [f64; LANES] {
    let mut result = [0.0; LANES];
    for lane in 0..LANES {
        result[lane] = f(a[lane], b[lane]);
    }
    result
}

/// Adds `x - x` of each lane of `values` to `sums`: 0 for a finite number,
/// NaN for an infinity or a NaN, so a lane's sum stays 0 while every
/// number it saw was finite (a plain sum, which the processor vectorises).
#[inline(always)]
fn watch(sums: &mut [f64; LANES], values: &[f64; LANES]) {
    for lane in 0..LANES {
        let value = values[lane];
        // Not zero for an infinity or a NaN: that is the point.
        #[allow(clippy::eq_op)]
        let change = value - value;
        sums[lane] += change;
    }
}

/// The values at points `start ..` of `columns`, as
/// `Evaluator::values_of_columns`, when `program` is straight-line
/// arithmetic; `None` (nothing written) when it is not.
pub(super) fn values(
    program: &Program,
    columns: &[&[f64]],
    start: usize,
    values: &mut [f64],
    status: &mut [i32],
) -> Option<usize> {
    let code = lanewise(program)?;
    let mut slots = vec![[0.0; LANES]; program.slot_count];
    for &(slot, value) in &program.constants {
        slots[slot as usize] = [value; LANES];
    }
    let mut failed = 0;
    let blocks = values.chunks_mut(LANES).zip(status.chunks_mut(LANES));
    for (block, (values, status)) in blocks.enumerate() {
        let first = start + block * LANES;
        let mut sums = [0.0; LANES];
        for load in &program.loads {
            let column = &columns[load.input as usize][first..first + values.len()];
            let lanes = &mut slots[load.slot as usize];
            lanes[..column.len()].copy_from_slice(column);
            watch(&mut sums, lanes);
        }
        for &instruction in &code {
            let (dst, result) = match instruction {
                Lanewise::Neg(dst, a) => (dst, each(&slots[a], &slots[a], |x, _| -x)),
                Lanewise::Add(dst, a, b) => (dst, each(&slots[a], &slots[b], |x, y| x + y)),
                Lanewise::Sub(dst, a, b) => (dst, each(&slots[a], &slots[b], |x, y| x - y)),
                Lanewise::Mul(dst, a, b) => (dst, each(&slots[a], &slots[b], |x, y| x * y)),
                Lanewise::Copy(dst, src) => (dst, slots[src]),
            };
            watch(&mut sums, &result);
            slots[dst] = result;
        }
        let result = program
            .results
            .first()
            .map_or([0.0; LANES], |&slot| slots[slot as usize]);
        for (lane, (value, status)) in values.iter_mut().zip(status.iter_mut()).enumerate() {
            let finite = sums[lane] == 0.0;
            *value = if finite { result[lane] } else { 0.0 };
            *status = i32::from(!finite);
            failed += usize::from(!finite);
        }
    }
    Some(failed)
}
