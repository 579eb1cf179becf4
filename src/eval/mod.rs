//! Stage 4, evaluate: run a [`Program`] over `f64` (the value) or over dual
//! numbers (the value with its gradient, or with gradient and Hessian) in
//! any number of derivative directions.
//!
//! Only the inputs named as derivative directions are seeded; every other
//! number carries no derivative part at all, and order 0 runs on plain `f64`.

mod delay;
mod error;
mod held;
mod lanes;

pub(crate) use delay::{DelayRecord, SharedRecord};
pub use error::EvalError;
pub use held::OutputError;

use held::{Branching, Natural};

use nalgebra::{DMatrix, DVector};
use num_dual::{Dual2DVec64, Dual2SVec64, DualDVec64, DualSVec64};

use crate::compile::{Instruction, Program, Slot};
use crate::number::{Directional, Number};
use crate::ops::{Op, SharedFrames, Tables, execute};

/// How many orders of derivatives to compute.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Order {
    /// The value only.
    Value,
    /// The value and the gradient.
    Gradient,
    /// The value, the gradient and the Hessian.
    Hessian,
}

impl Order {
    /// The order for 0, 1 or 2.
    pub fn from_number(order: u8) -> Option<Order> {
        match order {
            0 => Some(Order::Value),
            1 => Some(Order::Gradient),
            2 => Some(Order::Hessian),
            _ => None,
        }
    }
}

/// A value with the derivatives that were asked for, in the order of the
/// derivative directions.
#[derive(Clone, Debug, PartialEq)]
pub struct Evaluation {
    /// The value.
    pub value: f64,
    /// First derivatives, for [`Order::Gradient`] and [`Order::Hessian`].
    pub gradient: Option<DVector<f64>>,
    /// Second derivatives, for [`Order::Hessian`].
    pub hessian: Option<DMatrix<f64>>,
}

/// Evaluates one program over one number type, reusing its buffers from
/// call to call: the way to evaluate in a loop. Its calls are a run: AX, AY,
/// AZ and INCANG stay continuous through ±π from one call to the next (see
/// [`Run`]).
pub struct Evaluator<'p, T> {
    program: &'p Program,
    /// The program's tables with the bodies turned to their current
    /// orientations ([`Evaluator::reorient`]); `None`: the program's own.
    turned: Option<Box<Tables>>,
    slots: Vec<T>,
    /// The last value of each AX, AY, AZ, INCANG instruction (empty until
    /// one runs).
    angles: Vec<Option<f64>>,
    /// The last Euler parameters of each `ORIENT(27, ...)` instruction, as
    /// worked out (`e0` not negative) and as given (empty until one runs).
    parameters: Vec<Option<Continued>>,
    /// In a simulation, their values at the last accepted states, which
    /// settle their whole turns ([`Evaluator::accept_angles`]).
    turns: Option<Box<Turns>>,
    /// The marker frames of the current run, shared by its measures.
    frames: SharedFrames<T>,
    /// In a simulation, the run's record of the program's DELAYs (`None`:
    /// a DELAY takes its expression's value now, or its history before
    /// time 0).
    delays: Option<SharedRecord>,
}

/// The values of AX, AY, AZ, INCANG at a simulation's last accepted states: an
/// evaluation anywhere inside a step (a stage, a rejected try, a look for
/// a switch) takes the whole turns nearest the value extrapolated from
/// them to its time, so a part that turns several radians a step keeps its
/// turns, however its steps' trial evaluations fall.
#[derive(Clone, Debug, Default)]
struct Turns {
    /// The time of the evaluation under way.
    time: f64,
    /// Per instruction, up to [`ACCEPTED_ANGLES`] `(time, value)` at
    /// accepted states, oldest first.
    accepted: Vec<Vec<(f64, f64)>>,
    /// Per instruction, how many of its accepted values are of the piece of
    /// the run under way (since its start or its last switch).
    in_piece: Vec<usize>,
}

/// The accepted values an angle's extrapolation passes through: three, a
/// parabola.
const ACCEPTED_ANGLES: usize = 3;

/// An angle's extrapolation by a line, then by a parabola, reaches at
/// most this many times the spread of the accepted values it passes
/// through (a line's error grows as the reach, a parabola's as its square).
const EXTRAPOLATION_REACH: [f64; ACCEPTED_ANGLES - 1] = [20.0, 4.0];

/// Accepted angles closer in time than this (relative to the time, at
/// least 1) are one point of the extrapolation.
const ANGLE_TIME_GAP: f64 = 1e-9;

impl Turns {
    /// The value of instruction `index` extrapolated to the time under way
    /// from its accepted values (Newton's divided differences), if any.
    fn expected(&self, index: usize) -> Option<f64> {
        let points = self.accepted.get(index)?;
        // A parabola only through values of the piece under way: across a
        // switch the angle's acceleration jumps (a motion's ramp ends),
        // and a parabola through both sides, taken past it, bends off by
        // turns; a line through the last value before the switch keeps
        // the velocity, which a switch leaves whole.
        let in_piece = self.in_piece.get(index).copied().unwrap_or(points.len());
        let points = &points[points.len() - points.len().min(in_piece.max(2))..];
        let &(last_time, last) = points.last()?;
        // The newest points whose spread the time lies within a few times
        // of: a polynomial through points close together, taken far past
        // them, amplifies their rounding (after a restart's tiny steps).
        let reach = (self.time - last_time).abs();
        let used = (1..points.len())
            .rev()
            .find(|&degree| {
                let spread = last_time - points[points.len() - 1 - degree].0;
                reach <= EXTRAPOLATION_REACH[degree - 1] * spread
            })
            .map_or(1, |degree| degree + 1);
        let points = &points[points.len() - used..];
        let mut table: Vec<f64> = points.iter().map(|&(_, value)| value).collect();
        let times: Vec<f64> = points.iter().map(|&(time, _)| time).collect();
        // The divided differences, in place: table[k] = f[t_0 .. t_k].
        for order in 1..table.len() {
            for k in (order..table.len()).rev() {
                table[k] = (table[k] - table[k - 1]) / (times[k] - times[k - order]);
            }
        }
        let mut value = table[table.len() - 1];
        for k in (0..table.len() - 1).rev() {
            value = value * (self.time - times[k]) + table[k];
        }
        Some(if value.is_finite() { value } else { last })
    }
}

/// Evaluations of one program at a sequence of points, in order (the steps
/// of a simulation, the samples of a plot). SPEC 4 keeps AX, AY and AZ (and
/// INCANG) continuous through ±π over a run: each takes the whole turns that
/// bring it nearest to its value at the previous point (the derivatives are
/// those of the principal value). [`Program::evaluate`] alone gives the
/// principal value, in (-π, π].
pub struct Run<'p> {
    program: &'p Program,
    angles: Vec<Option<f64>>,
    parameters: Vec<Option<Continued>>,
}

/// The Euler parameters an `ORIENT(27, ...)` instruction gave last: as
/// worked out, `e0` not negative, and whether they were given with their
/// sign turned (so that they run on continuously through `e0 = 0`, as
/// Adams gives them).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Continued {
    worked_out: [f64; 4],
    turned: bool,
}

/// A function that evaluates a program at a point (its inputs).
pub type EvaluateAt<'e> = dyn FnMut(&[f64]) -> Result<Evaluation, EvalError> + 'e;

impl Run<'_> {
    /// Like [`Program::evaluate`], continuing the angles of the run.
    pub fn evaluate(
        &mut self,
        inputs: &[f64],
        wrt: &[usize],
        order: Order,
    ) -> Result<Evaluation, EvalError> {
        self.with_evaluator(wrt, order, |evaluate| evaluate(inputs))
    }

    /// Runs `body` with a function that evaluates at the next point of the
    /// run as [`Run::evaluate`] does, on one evaluator of the number type
    /// for `wrt` and `order`, its buffers reused from point to point: the
    /// way to evaluate at many points.
    pub fn with_evaluator<R>(
        &mut self,
        wrt: &[usize],
        order: Order,
        body: impl FnOnce(&mut EvaluateAt<'_>) -> R,
    ) -> R {
        let (program, angles) = (self.program, (&mut self.angles, &mut self.parameters));
        macro_rules! with {
            ($number:ty) => {
                program.continuing::<$number, _>(angles, |evaluator| {
                    body(&mut |inputs| evaluator.derivatives(inputs, wrt))
                })
            };
        }
        match (order, wrt.len()) {
            (Order::Value, _) | (_, 0) => program.continuing::<f64, _>(angles, |evaluator| {
                body(&mut |inputs| {
                    Ok(Evaluation {
                        value: evaluator.value(inputs)?,
                        gradient: (order >= Order::Gradient).then(|| DVector::zeros(0)),
                        hessian: (order >= Order::Hessian).then(|| DMatrix::zeros(0, 0)),
                    })
                })
            }),
            (Order::Gradient, 1) => with!(DualSVec64<1>),
            (Order::Gradient, 2) => with!(DualSVec64<2>),
            (Order::Gradient, 3) => with!(DualSVec64<3>),
            (Order::Gradient, 4) => with!(DualSVec64<4>),
            (Order::Gradient, _) => with!(DualDVec64),
            (Order::Hessian, 1) => with!(Dual2SVec64<1>),
            (Order::Hessian, 2) => with!(Dual2SVec64<2>),
            (Order::Hessian, 3) => with!(Dual2SVec64<3>),
            (Order::Hessian, 4) => with!(Dual2SVec64<4>),
            (Order::Hessian, _) => with!(Dual2DVec64),
        }
    }
}

impl Program {
    /// An evaluator over number type `T` (`f64`, or a dual number from num-dual
    /// such as `DualSVec64<2>` or `Dual2SVec64<2>`).
    pub fn evaluator<T: Number>(&self) -> Evaluator<'_, T> {
        let mut slots = vec![T::zero(); self.slot_count];
        for &(slot, value) in &self.constants {
            slots[slot as usize] = T::from(value);
        }
        Evaluator {
            program: self,
            turned: None,
            slots,
            angles: Vec::new(),
            parameters: Vec::new(),
            turns: None,
            frames: SharedFrames::new(),
            delays: None,
        }
    }

    /// Whether a result of a [`Run`] can depend on the points before it (an
    /// AX, AY, AZ or INCANG, continuous through ±π, an Euler parameter
    /// continuous through `e0 = 0`): if not, the points of a run may
    /// be evaluated in any order, or in parallel, each on its own.
    pub fn continues_from_point_to_point(&self) -> bool {
        self.code.iter().any(|instruction| {
            matches!(
                instruction,
                Instruction::Compute { op, .. }
                    if continues_through_turns(op) || continues_by_sign(op)
            )
        })
    }

    /// A [`Run`]: evaluations at a sequence of points, in order.
    pub fn run(&self) -> Run<'_> {
        Run {
            program: self,
            angles: Vec::new(),
            parameters: Vec::new(),
        }
    }

    /// The value at `inputs` (in the order of [`Program::inputs`]).
    pub fn value(&self, inputs: &[f64]) -> Result<f64, EvalError> {
        self.evaluator::<f64>().value(inputs)
    }

    /// The value and, for [`Order::Gradient`] and [`Order::Hessian`], its
    /// derivatives in the directions `wrt` (indices into [`Program::inputs`]).
    pub fn evaluate(
        &self,
        inputs: &[f64],
        wrt: &[usize],
        order: Order,
    ) -> Result<Evaluation, EvalError> {
        self.run().evaluate(inputs, wrt, order)
    }

    /// Runs `body` on an evaluator that carries on the history `angles`
    /// (the angles' values, the Euler parameters' signs) and hands it back.
    fn continuing<T: Number, R>(
        &self,
        (angles, parameters): (&mut Vec<Option<f64>>, &mut Vec<Option<Continued>>),
        body: impl FnOnce(&mut Evaluator<'_, T>) -> R,
    ) -> R {
        let mut evaluator = self.evaluator::<T>();
        evaluator.angles = std::mem::take(angles);
        evaluator.parameters = std::mem::take(parameters);
        let result = body(&mut evaluator);
        *parameters = evaluator.parameters;
        *angles = evaluator.angles;
        result
    }
}

impl<T: Number> Evaluator<'_, T> {
    /// Places each input the program uses in its slot, input `i` as
    /// `seed(i, value)`.
    fn load(&mut self, inputs: &[f64], seed: impl Fn(usize, f64) -> T) -> Result<(), EvalError> {
        self.load_numbers(inputs.len(), |index| seed(index, inputs[index]))
    }

    /// Places each input the program uses in its slot, input `i` as
    /// `input(i)`, of the `count` given; each must be finite.
    fn load_numbers(&mut self, count: usize, input: impl Fn(usize) -> T) -> Result<(), EvalError> {
        let program = self.program;
        if count != program.inputs.len() {
            return Err(EvalError::InputCount {
                expected: program.inputs.len(),
                found: count,
            });
        }
        for load in &program.loads {
            let index = load.input as usize;
            let value = input(index);
            if !value.is_all_finite() {
                return Err(EvalError::InputNotFinite {
                    name: program.inputs[index].clone(),
                    value: value.value(),
                    span: load.span,
                });
            }
            self.slots[load.slot as usize] = value;
        }
        Ok(())
    }

    /// The result with the value of every input given as a number of this
    /// type: a dual number brings the derivatives of an input that was
    /// itself computed (a model's VARIABLE, evaluated before the
    /// expressions that read it), so that they flow on by the chain rule.
    pub fn evaluate_numbers(&mut self, inputs: &[T]) -> Result<T, EvalError> {
        self.load_numbers(inputs.len(), |index| inputs[index].clone())?;
        self.run()
    }

    /// Turns every body the program's markers are on to the orientation
    /// `orientation` gives for its index in the scene, in place of its
    /// orientation when the program was compiled (a simulation's bodies
    /// turn; the small-rotation inputs `BODY.rx` ... stay perturbations of
    /// the current orientation).
    pub fn reorient(&mut self, orientation: impl Fn(usize) -> nalgebra::Matrix3<f64>) {
        let program = self.program;
        let tables = self
            .turned
            .get_or_insert_with(|| Box::new(program.tables.clone()));
        for frame in &mut tables.frames {
            if let Some(body) = frame.body {
                frame.body_orientation = orientation(body);
            }
        }
    }

    /// Runs the program over the loaded slots.
    fn run(&mut self) -> Result<T, EvalError> {
        self.run_with(&mut Natural).map_err(|(_, error)| error)
    }

    /// Runs the program over the loaded slots, the piecewise instructions
    /// branching as `branching` says; an error comes with the index of the
    /// instruction that failed.
    fn run_with<B: Branching<T>>(&mut self, branching: &mut B) -> Result<T, (usize, EvalError)> {
        let program = self.program;
        let code = &program.code;
        self.frames.clear();
        let mut pc = 0;
        while let Some(instruction) = code.get(pc) {
            pc += 1;
            let slots = &self.slots;
            let slot = |index: &Slot| slots[*index as usize].clone();
            let (dst, result) = match instruction {
                Instruction::Neg { dst, a } => (dst, -slot(a)),
                Instruction::Add { dst, a, b } => (dst, slot(a) + slot(b)),
                Instruction::Sub { dst, a, b } => (dst, slot(a) - slot(b)),
                Instruction::Mul { dst, a, b } => (dst, slot(a) * slot(b)),
                Instruction::Compute { dst, op } => {
                    let tables = self.turned.as_deref().unwrap_or(&program.tables);
                    let frames = &mut self.frames;
                    let computed = match op {
                        Op::Delay {
                            time,
                            at,
                            delayed,
                            history,
                            site,
                        } if let Some(record) = &self.delays => {
                            let on = branching.delay(program, pc - 1, slots[*at as usize].value());
                            let record = record
                                .read()
                                .unwrap_or_else(|poisoned| poisoned.into_inner());
                            Ok(delay::delayed_value(
                                &record,
                                *site as usize,
                                on,
                                [time, at, delayed, history].map(|&slot| &slots[slot as usize]),
                            ))
                        }
                        _ => branching
                            .compute(program, pc - 1, op, slots)
                            .unwrap_or_else(|| match op {
                                Op::Measure {
                                    function,
                                    frames: args,
                                    selector,
                                } => frames.measure(*function, *selector, args, slots, tables),
                                _ => execute(op, slots, tables),
                            }),
                    };
                    match computed {
                        Ok(result) if matches!(op, Op::Measure { .. }) => {
                            let result = self.continue_angle(op, pc - 1, result);
                            (dst, self.continue_sign(op, pc - 1, result))
                        }
                        Ok(result) => (dst, result),
                        Err(error) => {
                            let span = program.spans[pc - 1];
                            return Err((pc - 1, EvalError::Law { error, span }));
                        }
                    }
                }
                Instruction::Branch {
                    condition,
                    zero,
                    positive,
                } => {
                    let e1 = self.slots[*condition as usize].value();
                    match branching.choose(program, pc - 1, e1) {
                        0 => {}
                        1 => pc = *zero as usize,
                        _ => pc = *positive as usize,
                    }
                    continue;
                }
                Instruction::Copy { dst, src } => {
                    self.slots[*dst as usize] = self.slots[*src as usize].clone();
                    continue;
                }
                Instruction::Jump { target } => {
                    pc = *target as usize;
                    continue;
                }
            };
            if !result.is_all_finite() {
                return Err((
                    pc - 1,
                    not_finite(instruction, &result, program.spans[pc - 1]),
                ));
            }
            if pc == code.len() && program.results.len() == 1 && *dst == program.results[0] {
                // The program's last step: its result is returned as it is,
                // not stored and read back at once (which stalls the
                // processor on a wide dual number).
                return Ok(result);
            }
            self.slots[*dst as usize] = result;
        }
        Ok(program
            .results
            .first()
            .map_or_else(T::zero, |&slot| self.slots[slot as usize].clone()))
    }

    /// Reads the program's DELAYs from `record` (a simulation's, shared by
    /// its evaluators of the program) from now on.
    pub(crate) fn share_delays(&mut self, record: SharedRecord) {
        self.delays = Some(record);
    }

    /// The last evaluation's value of each DELAY's expression and its delay
    /// (`TIME` less the time looked back to), for the run's record.
    pub(crate) fn delay_samples(&self, values: &mut Vec<f64>, delays: &mut Vec<f64>) {
        values.clear();
        delays.clear();
        let program = self.program;
        for [time, at, delayed] in program.delays() {
            let slot = |index: Slot| self.slots[index as usize].value();
            values.push(slot(delayed));
            delays.push(slot(time) - slot(at));
        }
    }

    /// Whether the program has an AX, AY, AZ or INCANG, whose turns a simulation
    /// settles at its accepted states.
    pub(crate) fn continues_angles(&self) -> bool {
        self.program.continues_from_point_to_point()
    }

    /// The time of the evaluations that follow, in a simulation (the
    /// angles' turns are extrapolated to it).
    pub(crate) fn at_time(&mut self, time: f64) {
        if let Some(turns) = &mut self.turns {
            turns.time = time;
        }
    }

    /// The last evaluation was at a simulation's accepted state at `time`:
    /// its AX, AY, AZ, INCANG values settle their turns from there on. A
    /// state that `starts_piece` (the start, a switch) begins a piece of
    /// the run: the extrapolation takes no parabola across it.
    pub(crate) fn accept_angles(&mut self, time: f64, starts_piece: bool) {
        let turns = self.turns.get_or_insert_with(Box::default);
        turns.time = time;
        turns.accepted.resize(self.angles.len(), Vec::new());
        turns.in_piece.resize(self.angles.len(), 0);
        for ((points, in_piece), angle) in turns
            .accepted
            .iter_mut()
            .zip(&mut turns.in_piece)
            .zip(&self.angles)
        {
            let Some(value) = angle else { continue };
            // A state accepted again at (nearly) the same time (a switch's
            // cut, a restart) replaces the last: divided differences over
            // a gap of rounding size would throw the extrapolation far off.
            let gap = ANGLE_TIME_GAP * time.abs().max(1.0);
            while points.last().is_some_and(|&(at, _)| at >= time - gap) {
                points.pop();
                *in_piece = in_piece.saturating_sub(1);
            }
            if points.len() == ACCEPTED_ANGLES {
                points.remove(0);
            }
            points.push((time, *value));
            *in_piece = if starts_piece {
                1
            } else {
                (*in_piece + 1).min(ACCEPTED_ANGLES)
            };
        }
    }

    /// `result` of instruction `index`, its sign turned when `op` is an
    /// Euler parameter (`ORIENT(27, ...)`) whose parameters, worked out
    /// with `e0` not negative, jumped to their opposite since the last
    /// evaluation (`e0` passed 0): the parameters run on continuously, as
    /// Adams gives them.
    fn continue_sign(&mut self, op: &Op, index: usize, result: T) -> T {
        let Op::Measure { frames: args, .. } = op else {
            return result;
        };
        if !continues_by_sign(op) {
            return result;
        }
        let tables = self.turned.as_deref().unwrap_or(&self.program.tables);
        let worked_out = crate::ops::euler_parameters(args, &self.slots, tables);
        if self.parameters.is_empty() {
            self.parameters = vec![None; self.program.code.len()];
        }
        let turned = match self.parameters[index] {
            Some(last) => {
                let dot: f64 = (0..4).map(|k| last.worked_out[k] * worked_out[k]).sum();
                last.turned != (dot < 0.0)
            }
            None => false,
        };
        self.parameters[index] = Some(Continued { worked_out, turned });
        if turned { -result } else { result }
    }

    /// `result` of instruction `index`, moved by whole turns to the value
    /// nearest its last one when `op` is AX, AY, AZ or INCANG.
    fn continue_angle(&mut self, op: &Op, index: usize, result: T) -> T {
        if !continues_through_turns(op) || !result.value().is_finite() {
            return result;
        }
        if self.angles.is_empty() {
            self.angles = vec![None; self.program.code.len()];
        }
        let turn = std::f64::consts::TAU;
        let reference = self
            .turns
            .as_ref()
            .and_then(|turns| turns.expected(index))
            .or(self.angles[index]);
        let result = match reference {
            Some(previous) => {
                let turns = ((previous - result.value()) / turn).round();
                if turns == 0.0 {
                    result
                } else {
                    result + turns * turn
                }
            }
            None => result,
        };
        self.angles[index] = Some(result.value());
        result
    }
}

/// Whether `op` is `ORIENT(27, ...)`, an Euler parameter, which a [`Run`]
/// keeps continuous through `e0 = 0` by its sign.
fn continues_by_sign(op: &Op) -> bool {
    matches!(
        op,
        Op::Measure {
            selector: crate::kinematics::Selector::Orientation(orientation),
            ..
        } if orientation.is_euler_parameter()
    )
}

/// Whether `op` is AX, AY, AZ or INCANG, which a [`Run`] keeps continuous
/// through ±π.
fn continues_through_turns(op: &Op) -> bool {
    use crate::catalog::Function as F;
    matches!(
        op,
        Op::Measure {
            function: F::Ax | F::Ay | F::Az | F::Incang,
            ..
        }
    )
}

/// The error for a result that is not a finite number.
#[cold]
fn not_finite<T: Number>(
    instruction: &Instruction,
    result: &T,
    span: crate::span::Span,
) -> EvalError {
    let operation = instruction.name();
    if result.value().is_finite() {
        EvalError::DerivativeNotFinite { operation, span }
    } else {
        EvalError::NotFinite {
            operation,
            value: result.value(),
            span,
        }
    }
}

impl Evaluator<'_, f64> {
    /// The value at `inputs`.
    pub fn value(&mut self, inputs: &[f64]) -> Result<f64, EvalError> {
        self.load(inputs, |_, value| value)?;
        self.run()
    }

    /// The values at points `start ..` of `columns` (one per input of the
    /// program, `columns[i][p]` input `i` at point `p`), one a slot of
    /// `values`: `status[p]` is 0, or 1 where the point cannot be evaluated
    /// (its value then 0; [`Evaluator::value`] at the point says why).
    /// Returns how many failed. Straight-line arithmetic runs a block of
    /// points an instruction (`lanes.rs`); any other program a point at a
    /// time, each input read from its column into its slot (no point
    /// gathered first) and a failure only counted.
    pub(crate) fn values_of_columns(
        &mut self,
        columns: &[&[f64]],
        start: usize,
        values: &mut [f64],
        status: &mut [i32],
    ) -> usize {
        let program = self.program;
        if let Some(failed) = lanes::values(program, columns, start, values, status) {
            return failed;
        }
        let mut failed = 0;
        for (p, (value, status)) in values.iter_mut().zip(status.iter_mut()).enumerate() {
            let mut finite = true;
            for load in &program.loads {
                let input = columns[load.input as usize][start + p];
                finite &= input.is_finite();
                self.slots[load.slot as usize] = input;
            }
            let result = if finite {
                self.run_with(&mut Natural).ok()
            } else {
                None
            };
            *value = result.unwrap_or(0.0);
            *status = i32::from(result.is_none());
            failed += usize::from(result.is_none());
        }
        failed
    }
}

impl<T: Directional> Evaluator<'_, T> {
    /// The result as a dual number, with input `wrt[j]` seeded as direction `j`.
    pub fn dual(&mut self, inputs: &[f64], wrt: &[usize]) -> Result<T, EvalError> {
        let count = wrt.len();
        for (position, &direction) in wrt.iter().enumerate() {
            let reason = if direction >= inputs.len() {
                format!("there are only {}", crate::Counted(inputs.len(), "input"))
            } else if wrt[..position].contains(&direction) {
                "named twice".to_string()
            } else {
                continue;
            };
            return Err(EvalError::BadDirection { direction, reason });
        }
        self.load(inputs, |index, value| {
            match wrt.iter().position(|&direction| direction == index) {
                Some(position) => T::variable(value, position, count),
                None => T::from(value),
            }
        })?;
        self.run()
    }

    /// The value and its derivatives in the directions `wrt`.
    pub fn derivatives(&mut self, inputs: &[f64], wrt: &[usize]) -> Result<Evaluation, EvalError> {
        let result = self.dual(inputs, wrt)?;
        Ok(Evaluation {
            value: result.value(),
            gradient: Some(result.gradient(wrt.len())),
            hessian: result.hessian(wrt.len()),
        })
    }
}
