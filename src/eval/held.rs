//! Evaluation with the piecewise instructions held on given branches, for
//! a simulator: within a step each STEP, IMPACT, BISTOP, ABS, MIN, ... and
//! arithmetic IF stays on the branch it started on (continued smoothly past
//! its boundary), and after the step its switching values tell whether and
//! where it must switch (see [`crate::laws::branch`]).

use super::{EvalError, Evaluator, delay};
use crate::compile::{NO_SITE, Program};
use crate::laws::LawError;
use crate::laws::branch::{self, Code};
use crate::laws::contact::ContactBranch;
use crate::number::Number;
use crate::ops::{Op, Tables, execute, with_arguments};

/// How the piecewise instructions of a run choose their branch.
pub(super) trait Branching<T> {
    /// The result of instruction `index`, computing `op`, when this way of
    /// branching computes it; `None` to compute it as usual.
    fn compute(
        &mut self,
        program: &Program,
        index: usize,
        op: &Op,
        slots: &[T],
    ) -> Option<Result<T, LawError>>;

    /// The branch an arithmetic IF at instruction `index` takes (0 for
    /// `e1 < 0`, 1 for 0, 2 for `e1 > 0`) when its condition is `e1`.
    fn choose(&mut self, program: &Program, index: usize, e1: f64) -> Code;

    /// The branch a DELAY at instruction `index` takes (0: its history, 1:
    /// its record; [`super::delay::natural_branch`]) when it looks back to
    /// the time `at`.
    fn delay(&mut self, program: &Program, index: usize, at: f64) -> Code;
}

/// Every branch as the values decide (SPEC 5): the plain evaluation.
pub(super) struct Natural;

impl<T: Number> Branching<T> for Natural {
    #[inline(always)]
    fn compute(&mut self, _: &Program, _: usize, _: &Op, _: &[T]) -> Option<Result<T, LawError>> {
        None
    }

    #[inline(always)]
    fn choose(&mut self, _: &Program, _: usize, e1: f64) -> Code {
        if e1 < 0.0 {
            0
        } else if e1 == 0.0 {
            1
        } else {
            2
        }
    }

    fn delay(&mut self, _: &Program, _: usize, at: f64) -> Code {
        delay::natural_branch(at)
    }
}

/// Each site on the branch `held` gives it (`None`: as the values decide).
struct Held<'h> {
    held: &'h [Option<Code>],
}

impl<T: Number> Branching<T> for Held<'_> {
    fn compute(
        &mut self,
        program: &Program,
        index: usize,
        op: &Op,
        slots: &[T],
    ) -> Option<Result<T, LawError>> {
        let site = program.site_of[index];
        if site == NO_SITE {
            return None;
        }
        let code = self.held[site as usize]?;
        Some(compute_held(op, slots, &program.tables, code))
    }

    fn choose(&mut self, program: &Program, index: usize, e1: f64) -> Code {
        let site = program.site_of[index] as usize;
        self.held[site].unwrap_or_else(|| Branching::<T>::choose(&mut Natural, program, index, e1))
    }

    fn delay(&mut self, program: &Program, index: usize, at: f64) -> Code {
        let site = program.site_of[index] as usize;
        self.held[site].unwrap_or_else(|| delay::natural_branch(at))
    }
}

/// `op` on branch `code`.
fn compute_held<T: Number>(
    op: &Op,
    slots: &[T],
    tables: &Tables,
    code: Code,
) -> Result<T, LawError> {
    let slot = |index: u32| &slots[index as usize];
    match op {
        Op::Contact { table, x, v, .. } => Ok(tables.contacts[*table as usize].force_held(
            slot(*x),
            slot(*v),
            ContactBranch::from_code(code),
        )),
        Op::Call {
            function,
            args,
            check_rules,
        } => with_arguments(*function, args, *check_rules, slots, |values| {
            branch::held(*function, values, code)
        })?,
        _ => execute(op, slots, tables),
    }
}

/// [`Held`], recording at each site that runs its natural branch and its
/// switching values for the branch it is evaluated on.
struct Observe<'o> {
    held: Option<&'o [Option<Code>]>,
    natural: &'o mut [Option<Code>],
    switching: &'o mut [f64],
    /// The least step limit of the sites that ran.
    step_limit: f64,
    /// The absolute error in a displacement that the step limits allow;
    /// `None`: no step limit is worked out.
    tolerance: Option<f64>,
    /// A call's argument values (kept to spare an allocation per call).
    arguments: Vec<f64>,
}

impl Observe<'_> {
    fn held(&self, site: usize) -> Option<Code> {
        self.held.and_then(|held| held[site])
    }
}

impl Branching<f64> for Observe<'_> {
    fn compute(
        &mut self,
        program: &Program,
        index: usize,
        op: &Op,
        slots: &[f64],
    ) -> Option<Result<f64, LawError>> {
        let site_index = program.site_of[index];
        if site_index == NO_SITE {
            return None;
        }
        let site = program.sites[site_index as usize];
        let held = self.held(site_index as usize);
        let out = &mut self.switching[site.first as usize..(site.first + site.count) as usize];
        let slot = |index: u32| slots[index as usize];
        let natural = match op {
            Op::Contact { table, x, v, .. } => {
                let stops = &program.tables.contacts[*table as usize];
                let (x, v) = (slot(*x), slot(*v));
                let seen = stops.switching(x, v, held.map(ContactBranch::from_code));
                out.copy_from_slice(&seen.values);
                if let Some(tolerance) = self.tolerance {
                    let on = held.map_or(seen.natural, ContactBranch::from_code);
                    self.step_limit = self.step_limit.min(stops.step_limit(x, v, on, tolerance));
                }
                self.natural[site_index as usize] = Some(seen.natural.code());
                // The force on the held branch comes with the switching values.
                return Some(Ok(seen.force));
            }
            Op::Call { function, args, .. } => {
                let values = &mut self.arguments;
                values.clear();
                values.extend(args.iter().map(|&arg| slot(arg)));
                let natural = branch::switching(*function, values, held, out);
                if let Some(tolerance) = self.tolerance {
                    let on = held.unwrap_or(natural);
                    let limit = branch::step_limit(*function, values, on, tolerance);
                    self.step_limit = self.step_limit.min(limit);
                }
                natural
            }
            _ => return None,
        };
        self.natural[site_index as usize] = Some(natural);
        Some(compute_held(
            op,
            slots,
            &program.tables,
            held.unwrap_or(natural),
        ))
    }

    fn choose(&mut self, program: &Program, index: usize, e1: f64) -> Code {
        let site_index = program.site_of[index] as usize;
        let site = program.sites[site_index];
        let held = self.held(site_index);
        let (natural, values) = branch::arithmetic_if(e1, held);
        self.switching[site.first as usize..(site.first + site.count) as usize]
            .copy_from_slice(&values);
        self.natural[site_index] = Some(natural);
        held.unwrap_or(natural)
    }

    fn delay(&mut self, program: &Program, index: usize, at: f64) -> Code {
        let site_index = program.site_of[index] as usize;
        let site = program.sites[site_index];
        let held = self.held(site_index);
        let natural = delay::natural_branch(at);
        let on = held.unwrap_or(natural);
        // On the history the time looked back to is below 0, on the
        // record above it.
        self.switching[site.first as usize] = if on == 0 { -at } else { at };
        self.natural[site_index] = Some(natural);
        on
    }
}

/// An evaluation error with the output whose text it speaks of.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{error}")]
pub struct OutputError {
    /// The output (an index among the trees compiled together).
    pub output: usize,
    /// What went wrong, with its span in that output's text.
    pub error: EvalError,
}

impl<T: Number> Evaluator<'_, T> {
    /// Evaluates every output of the program at `inputs` given as numbers
    /// (with whatever derivative parts the caller gave them), each site on
    /// the branch `held` gives it (`None` for the natural branch; no `held`
    /// at all: every branch natural), into `outputs`.
    pub fn outputs(
        &mut self,
        inputs: &[T],
        held: Option<&[Option<Code>]>,
        outputs: &mut [T],
    ) -> Result<(), OutputError> {
        self.load_numbers(inputs.len(), |index| inputs[index].clone())
            .map_err(|error| OutputError { output: 0, error })?;
        let last = match held {
            Some(held) => self.run_with(&mut Held { held }),
            None => self.run_with(&mut Natural),
        };
        self.collect(last, outputs)
    }

    /// The outputs after a run that returned `last`.
    fn collect(
        &mut self,
        last: Result<T, (usize, EvalError)>,
        outputs: &mut [T],
    ) -> Result<(), OutputError> {
        let program = self.program;
        let last = last.map_err(|(index, error)| OutputError {
            output: program.origin(index),
            error,
        })?;
        if let [only] = outputs {
            *only = last;
            return Ok(());
        }
        for (output, &slot) in outputs.iter_mut().zip(&program.results) {
            *output = self.slots[slot as usize].clone();
        }
        Ok(())
    }
}

impl Evaluator<'_, f64> {
    /// [`Evaluator::outputs`] over `f64`, recording at every site that runs
    /// its natural branch (in `natural`, one entry per site; `None` where
    /// the site did not run) and its switching values for the branch it was
    /// evaluated on (in `switching`, [`Program::switch_count`] entries;
    /// 1, which is no switch, for sites that did not run). Returns the
    /// largest step the sites allow a simulator that accepts an absolute
    /// error `tolerance` in a displacement (see [`branch::step_limit`];
    /// infinity for none, and when `tolerance` is `None`: then no limit is
    /// worked out).
    pub fn observe(
        &mut self,
        inputs: &[f64],
        held: Option<&[Option<Code>]>,
        (natural, switching): (&mut [Option<Code>], &mut [f64]),
        outputs: &mut [f64],
        tolerance: Option<f64>,
    ) -> Result<f64, OutputError> {
        natural.fill(None);
        switching.fill(1.0);
        self.load_numbers(inputs.len(), |index| inputs[index])
            .map_err(|error| OutputError { output: 0, error })?;
        let mut observer = Observe {
            held,
            natural,
            switching,
            step_limit: f64::INFINITY,
            tolerance,
            arguments: Vec::new(),
        };
        let last = self.run_with(&mut observer);
        let step_limit = observer.step_limit;
        self.collect(last, outputs)?;
        Ok(step_limit)
    }
}
