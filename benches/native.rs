//! What the evaluation benchmarks compare mbexpr against, shared by
//! `eval.rs` and `counts.rs`: the hand-written laws, fasteval on the
//! linear expression, and the floor of a tape interpreter.

use num_dual::DualNum;

/// BISTOP written out by hand for these parameters (SPEC 3.3), generic so
/// that num-dual gives its derivatives: what a hand-coded force would be.
pub fn native_bistop<D: DualNum<Primitive = f64> + Copy>(x: D, v: D) -> D {
    let (x1, x2, k, e, cmax, d) = (-10.0, 10.0, 1e5, 2.2, 100.0, 0.1);
    let damping = |p: D| {
        if p.re() >= d {
            D::from(cmax)
        } else {
            let w = p / d;
            w * w * (w * -2.0 + 3.0) * cmax
        }
    };
    if x.re() < x1 {
        let p = -x + x1;
        let raw = p.powf(e) * k - damping(p) * v;
        if raw.re() > 0.0 { raw } else { D::zero() }
    } else if x.re() > x2 {
        let p = x - x2;
        let raw = -(p.powf(e) * k) - damping(p) * v;
        if raw.re() < 0.0 { raw } else { D::zero() }
    } else {
        D::zero()
    }
}

/// `-1E4*(x-50)-10*v + 3*sin(2*pi*t)` by hand.
pub fn native_linear(x: f64, v: f64, t: f64) -> f64 {
    -1e4 * (x - 50.0) - 10.0 * v + 3.0 * (2.0 * std::f64::consts::PI * t).sin()
}

/// The linear expression as fasteval reads it (its π is `pi()`).
pub const FASTEVAL_LINEAR: &str = "-1E4*(x-50)-10*v + 3*sin(2*pi()*t)";

/// [`FASTEVAL_LINEAR`] compiled by fasteval into `slab`.
pub fn fasteval_linear(slab: &mut fasteval::Slab) -> fasteval::Instruction {
    use fasteval::Compiler;
    fasteval::Parser::new()
        .parse(FASTEVAL_LINEAR, &mut slab.ps)
        .unwrap()
        .from(&slab.ps)
        .compile(&slab.ps, &mut slab.cs)
}

/// The value of [`fasteval_linear`]'s program at `[x, v, t]`.
pub fn fasteval_linear_value(
    compiled: &fasteval::Instruction,
    slab: &fasteval::Slab,
    [x, v, t]: [f64; 3],
) -> f64 {
    use fasteval::Evaler;
    let mut namespace = |name: &str, _: Vec<f64>| match name {
        "x" => Some(x),
        "v" => Some(v),
        "t" => Some(t),
        _ => None,
    };
    compiled.eval(slab, &mut namespace).unwrap()
}

/// One step of [`BareTape`].
#[derive(Clone, Copy)]
enum BareStep {
    Sub(usize, usize, usize),
    Mul(usize, usize, usize),
    Add(usize, usize, usize),
    Sin(usize, usize),
}

/// The floor of any tape interpreter for [`native_linear`]: the eight steps
/// of mbexpr's program for it (`-1E4*(x-50)-10*v + 3*sin(2*pi*t)`, constants
/// folded), over slots, with none of the checks an evaluator owes its
/// caller (no finiteness, no error spans; only Rust's bounds checks).
pub struct BareTape {
    code: [BareStep; 8],
    slots: [f64; 12],
}

impl BareTape {
    /// The tape, with its constants in their slots.
    pub fn linear() -> BareTape {
        use BareStep::{Add, Mul, Sin, Sub};
        // Slots: 0-2 inputs x, v, t; 3-7 constants; 8-11 results.
        let mut slots = [0.0; 12];
        slots[3..8].copy_from_slice(&[-1e4, 50.0, 10.0, 3.0, 2.0 * std::f64::consts::PI]);
        BareTape {
            code: [
                Sub(8, 0, 4),
                Mul(8, 3, 8),
                Mul(9, 5, 1),
                Sub(8, 8, 9),
                Mul(10, 7, 2),
                Sin(10, 10),
                Mul(10, 6, 10),
                Add(11, 8, 10),
            ],
            slots,
        }
    }

    /// The value at `[x, v, t]`.
    pub fn value(&mut self, inputs: [f64; 3]) -> f64 {
        let BareTape { code, slots } = self;
        slots[..3].copy_from_slice(&inputs);
        for &step in code.iter() {
            match step {
                BareStep::Sub(dst, a, b) => slots[dst] = slots[a] - slots[b],
                BareStep::Mul(dst, a, b) => slots[dst] = slots[a] * slots[b],
                BareStep::Add(dst, a, b) => slots[dst] = slots[a] + slots[b],
                BareStep::Sin(dst, a) => slots[dst] = slots[a].sin(),
            }
        }
        slots[11]
    }
}
