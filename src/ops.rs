//! The operations of a compiled program on plain slots, and how each is
//! computed over any [`Number`]: the one place an operation's meaning is
//! written. The checker folds constants with [`execute`], the compiler
//! folds them and emits [`Op`]s, and the evaluator runs them, so all three
//! agree by construction.

use std::fmt;

use crate::catalog::{Function, check_rules_with};
use crate::kinematics::{self, Frame, FrameData, Selector};
use crate::laws::contact::Stops;
use crate::laws::spline::Spline;
use crate::laws::{self, LawError, power};
use crate::number::Number;

/// The index of a slot: an input, a constant or an instruction's result.
pub type Slot = u32;

/// A computation of one value from slots.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// `-a`
    Neg(Slot),
    /// `a + b`
    Add(Slot, Slot),
    /// `a - b`
    Sub(Slot, Slot),
    /// `a * b`
    Mul(Slot, Slot),
    /// `a / b`
    Div(Slot, Slot),
    /// `a ** n` for a constant whole `n`.
    PowInt(Slot, i32),
    /// `a ** e` for a constant real `e`, kept as its bits so ops can be hashed.
    PowReal(Slot, u64),
    /// `a ** b` for a varying `b`.
    Pow(Slot, Slot),
    /// A kinematic measure between marker frames (SPEC 4), in a scene.
    Measure {
        /// The measure.
        function: Function,
        /// One frame per marker of the signature, omitted ones as ground.
        frames: Box<[FrameArg]>,
        /// ORIENT's orientation system and component, INCANG's axis.
        selector: Selector,
    },
    /// `AKISPL` or `CUBSPL`: the derivative of order `order` in `x` of a
    /// fitted spline of the program's table at `(x, z)`.
    Spline {
        /// The function, for messages.
        function: Function,
        /// Index into the program's spline table.
        table: u32,
        /// The slot of `x`.
        x: Slot,
        /// The slot of `z`.
        z: Slot,
        /// 0, 1 or 2.
        order: u8,
    },
    /// `IMPACT` or `BISTOP` with constant stops and parameters, which
    /// passed the law's rules when the program was compiled.
    Contact {
        /// The function, for messages.
        function: Function,
        /// Index into the program's table of stops.
        table: u32,
        /// The slot of `x`.
        x: Slot,
        /// The slot of `x'`.
        v: Slot,
    },
    /// `DELAY(e, delay, history)` in a simulation: the value `e` had at the
    /// time in slot `at` (`TIME − max(delay, 0)`), `history` before time 0.
    /// The evaluator reads it from its record of `delayed` at the run's
    /// accepted states (entry `site` of the evaluator's `DelayRecord`);
    /// `execute`, with no record, takes the value `e` has now.
    Delay {
        /// The slot of `TIME`.
        time: Slot,
        /// The slot of the time looked back to.
        at: Slot,
        /// The slot of `e` now.
        delayed: Slot,
        /// The slot of the history at the time looked back to.
        history: Slot,
        /// The DELAY's index among the program's.
        site: u32,
    },
    /// A function of the intrinsic, step, contact or series family.
    Call {
        /// The function.
        function: Function,
        /// Its argument slots.
        args: Box<[Slot]>,
        /// Whether the function's argument rules must be checked at run time
        /// (some of the arguments they speak of are not constants).
        check_rules: bool,
    },
}

/// A marker frame as a measure's argument: the constants of the marker (an
/// index into the program's frame table) and, for a marker on a body, the
/// slots of the body's twelve state inputs (`x y z rx ry rz vx vy vz wx wy wz`).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct FrameArg {
    /// Index into the program's frame table.
    pub data: u32,
    /// The body's state slots; `None` for a marker on ground.
    pub state: Option<[Slot; 12]>,
}

impl FrameArg {
    /// The frame at the state in `slots`.
    fn frame<T: Number>(&self, slots: &[T], tables: &Tables) -> Frame<T> {
        let data = &tables.frames[self.data as usize];
        match &self.state {
            Some(state) => Frame::on_body(data, state.map(|index| &slots[index as usize])),
            None => Frame::fixed(data),
        }
    }
}

/// The Euler parameters of the rotation of frame `args[1]`'s axes to
/// `args[0]`'s at the state in `slots` (`e0` not negative), in plain
/// numbers.
pub(crate) fn euler_parameters<T: Number>(
    args: &[FrameArg],
    slots: &[T],
    tables: &Tables,
) -> [f64; 4] {
    let [i, j] = [0, 1].map(|position| {
        args[position.min(args.len() - 1)]
            .frame(slots, tables)
            .axes
            .map(|entry| entry.value())
    });
    kinematics::euler_parameters(&(j.transpose() * i))
}

/// The marker frames one run of a program has worked out, by index in the
/// frame table: each is computed once per run (from the body's state
/// inputs, which a run does not change) and shared by every measure that
/// reads it, as `DM(i, j)` and `VR(i, j)` of one contact do.
pub struct SharedFrames<T> {
    frames: Vec<Option<Known<T>>>,
}

/// A frame worked out in a run, with the state slots it was worked out
/// from.
type Known<T> = (Option<[Slot; 12]>, Frame<T>);

impl<T: Number> SharedFrames<T> {
    /// No frame worked out.
    pub fn new() -> SharedFrames<T> {
        SharedFrames { frames: Vec::new() }
    }

    /// Forgets every frame: the state inputs or the bodies' orientations
    /// are about to change.
    pub fn clear(&mut self) {
        self.frames.iter_mut().for_each(|frame| *frame = None);
    }

    /// The value of measure `function` of the frames `args`, each worked
    /// out at most once between two [`clear`](SharedFrames::clear)s.
    pub fn measure(
        &mut self,
        function: Function,
        selector: Selector,
        args: &[FrameArg],
        slots: &[T],
        tables: &Tables,
    ) -> Result<T, LawError> {
        if self.frames.len() < tables.frames.len() {
            self.frames.resize_with(tables.frames.len(), || None);
        }
        for arg in args {
            let entry = &mut self.frames[arg.data as usize];
            if !matches!(entry, Some((state, _)) if *state == arg.state) {
                *entry = Some((arg.state, arg.frame(slots, tables)));
            }
        }
        let frame = |position: usize| {
            let arg = &args[position.min(args.len() - 1)];
            match &self.frames[arg.data as usize] {
                Some((_, frame)) => frame,
                None => unreachable!("worked out above"),
            }
        };
        // A measure reads at most four frames (i, j, k, l).
        let frames: [&Frame<T>; 4] = std::array::from_fn(frame);
        kinematics::measure(function, selector, &frames[..args.len().min(4)])
    }
}

impl<T: Number> Default for SharedFrames<T> {
    fn default() -> SharedFrames<T> {
        SharedFrames::new()
    }
}

/// The data instructions refer to by index: the constants of the marker
/// frames the measures use, the splines fitted for `AKISPL`/`CUBSPL`, and
/// the constant stops of contact laws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tables {
    /// Marker frames, for [`Op::Measure`].
    pub frames: Vec<FrameData>,
    /// Fitted splines, for [`Op::Spline`].
    pub splines: Vec<Spline>,
    /// Stops and parameters, for [`Op::Contact`].
    pub contacts: Vec<Stops>,
}

/// Computes `op` from the slots. The checker and the compiler fold constants with
/// it, the evaluator runs every computing instruction through it.
#[inline]
pub fn execute<T: Number>(op: &Op, slots: &[T], tables: &Tables) -> Result<T, LawError> {
    let slot = |index: Slot| &slots[index as usize];
    Ok(match op {
        Op::Neg(a) => -slot(*a).clone(),
        Op::Add(a, b) => slot(*a).clone() + slot(*b).clone(),
        Op::Sub(a, b) => slot(*a).clone() - slot(*b).clone(),
        Op::Mul(a, b) => slot(*a).clone() * slot(*b).clone(),
        Op::Div(a, b) => power::divide(slot(*a), slot(*b))?,
        Op::PowInt(a, n) => power::powi(slot(*a), *n)?,
        Op::PowReal(a, bits) => power::powf(slot(*a), f64::from_bits(*bits))?,
        Op::Pow(a, b) => power::pow(slot(*a), slot(*b))?,
        Op::Measure {
            function,
            frames: args,
            selector,
        } => {
            let frames: Vec<Frame<T>> = args.iter().map(|arg| arg.frame(slots, tables)).collect();
            let frames: Vec<&Frame<T>> = frames.iter().collect();
            kinematics::measure(*function, *selector, &frames)?
        }
        Op::Spline {
            table, x, z, order, ..
        } => tables.splines[*table as usize].at(slot(*x), slot(*z), usize::from(*order)),
        Op::Contact { table, x, v, .. } => {
            tables.contacts[*table as usize].force(slot(*x), slot(*v))
        }
        Op::Delay {
            at,
            delayed,
            history,
            ..
        } => {
            if slot(*at).value() < 0.0 {
                slot(*history).clone()
            } else {
                slot(*delayed).clone()
            }
        }
        Op::Call {
            function,
            args,
            check_rules,
        } => with_arguments(*function, args, *check_rules, slots, |values| {
            laws::apply(*function, values)
        })??,
    })
}

/// Runs `body` on the values of a call's argument slots, after checking the
/// function's argument rules when `check_rules` says they are not known to
/// hold.
#[inline]
pub fn with_arguments<T: Number, R>(
    function: Function,
    args: &[Slot],
    check_rules: bool,
    slots: &[T],
    body: impl FnOnce(&[&T]) -> R,
) -> Result<R, LawError> {
    let slot = |index: Slot| &slots[index as usize];
    if check_rules {
        check_rules_with(function, |position| {
            args.get(position).map(|&index| slot(index).value())
        })
        .map_err(LawError::Rule)?;
    }
    // Up to eight arguments (all but the longest series) stay on the stack.
    const INLINE: usize = 8;
    Ok(if let [arg] = *args {
        body(&[slot(arg)])
    } else if args.len() <= INLINE {
        let values: [&T; INLINE] =
            std::array::from_fn(|position| slot(args[position.min(args.len() - 1)]));
        body(&values[..args.len()])
    } else {
        let values: Vec<&T> = args.iter().map(|&index| slot(index)).collect();
        body(&values)
    })
}

impl fmt::Display for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Op::Neg(a) => write!(f, "-s{a}"),
            Op::Add(a, b) => write!(f, "s{a} + s{b}"),
            Op::Sub(a, b) => write!(f, "s{a} - s{b}"),
            Op::Mul(a, b) => write!(f, "s{a} * s{b}"),
            Op::Div(a, b) => write!(f, "s{a} / s{b}"),
            Op::PowInt(a, n) => write!(f, "s{a} ** {n}"),
            Op::PowReal(a, bits) => write!(f, "s{a} ** {}", f64::from_bits(*bits)),
            Op::Pow(a, b) => write!(f, "s{a} ** s{b}"),
            Op::Call { function, args, .. } => {
                let args: Vec<String> = args.iter().map(|slot| format!("s{slot}")).collect();
                write!(f, "{function}({})", args.join(", "))
            }
            Op::Spline {
                function,
                table,
                x,
                z,
                order,
            } => write!(f, "{function}(s{x}, s{z}, spline{table}, {order})"),
            Op::Contact {
                function,
                table,
                x,
                v,
            } => write!(f, "{function}(s{x}, s{v}, stops{table})"),
            Op::Delay {
                time,
                at,
                delayed,
                history,
                site,
            } => write!(
                f,
                "DELAY(s{delayed} at s{at}, now s{time}, history s{history}, record{site})"
            ),
            Op::Measure {
                function, frames, ..
            } => {
                let frames: Vec<String> = frames
                    .iter()
                    .map(|frame| match frame.state {
                        Some(state) => {
                            format!("frame{}[s{}..s{}]", frame.data, state[0], state[11])
                        }
                        None => format!("frame{}", frame.data),
                    })
                    .collect();
                write!(f, "{function}({})", frames.join(", "))
            }
        }
    }
}

impl Op {
    /// Calls `visit` with each slot the operation reads.
    pub fn for_each_operand(&self, mut visit: impl FnMut(Slot)) {
        match self {
            Op::Neg(a) | Op::PowInt(a, _) | Op::PowReal(a, _) => visit(*a),
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) | Op::Pow(a, b) => {
                visit(*a);
                visit(*b);
            }
            Op::Call { args, .. } => args.iter().copied().for_each(visit),
            Op::Spline { x, z, .. } => {
                visit(*x);
                visit(*z);
            }
            Op::Contact { x, v, .. } => {
                visit(*x);
                visit(*v);
            }
            Op::Delay {
                time,
                at,
                delayed,
                history,
                ..
            } => [*time, *at, *delayed, *history].into_iter().for_each(visit),
            Op::Measure { frames, .. } => {
                for state in frames.iter().filter_map(|frame| frame.state) {
                    state.into_iter().for_each(&mut visit);
                }
            }
        }
    }

    /// The operation's name in messages: `STEP`, `` `*` ``.
    pub fn name(&self) -> String {
        match self {
            Op::Neg(_) => "`-`".to_string(),
            Op::Add(..) => "`+`".to_string(),
            Op::Sub(..) => "`-`".to_string(),
            Op::Mul(..) => "`*`".to_string(),
            Op::Div(..) => "`/`".to_string(),
            Op::PowInt(..) | Op::PowReal(..) | Op::Pow(..) => "`**`".to_string(),
            Op::Call { function, .. }
            | Op::Measure { function, .. }
            | Op::Spline { function, .. }
            | Op::Contact { function, .. } => function.name().to_string(),
            Op::Delay { .. } => "DELAY".to_string(),
        }
    }
}
