//! The compiled form: a flat program of instructions over numbered slots.

use std::borrow::Cow;
use std::collections::HashMap;
use std::fmt;

use crate::catalog::Function;
use crate::ops::{Op, Slot, Tables};
use crate::span::Span;

/// An input the program uses, placed in its slot before the first instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InputSlot {
    /// Index into the program's inputs.
    pub input: u32,
    /// The slot it is placed in.
    pub slot: Slot,
    /// Where the expression first uses it.
    pub span: Span,
}

/// Input names in order, with a case-insensitive index: finding a name
/// costs the same for 100 000 inputs as for two.
#[derive(Clone, Debug, Default)]
pub(crate) struct InputNames {
    pub(crate) names: Vec<String>,
    /// Each name in upper case to its first position.
    positions: HashMap<String, usize>,
}

impl InputNames {
    /// The position of `name` (case-insensitive), the first when it is given twice.
    pub(crate) fn position(&self, name: &str) -> Option<usize> {
        self.positions.get(&name.to_ascii_uppercase()).copied()
    }

    /// Adds `name` at the end (a name given twice keeps its first position).
    pub(crate) fn push(&mut self, name: String) -> usize {
        self.positions
            .entry(name.to_ascii_uppercase())
            .or_insert(self.names.len());
        self.names.push(name);
        self.names.len() - 1
    }
}

impl std::ops::Deref for InputNames {
    type Target = [String];

    fn deref(&self) -> &[String] {
        &self.names
    }
}

/// One step of a program. The four operations that cannot fail are
/// instructions of their own, so that the evaluator dispatches them with a
/// single `match`; [`Instruction::Compute`] holds every other op.
#[derive(Clone, Debug, PartialEq)]
pub enum Instruction {
    /// `slots[dst] = -slots[a]`
    Neg {
        /// Destination slot.
        dst: Slot,
        /// The operand.
        a: Slot,
    },
    /// `slots[dst] = slots[a] + slots[b]`
    Add {
        /// Destination slot.
        dst: Slot,
        /// The left operand.
        a: Slot,
        /// The right operand.
        b: Slot,
    },
    /// `slots[dst] = slots[a] - slots[b]`
    Sub {
        /// Destination slot.
        dst: Slot,
        /// The left operand.
        a: Slot,
        /// The right operand.
        b: Slot,
    },
    /// `slots[dst] = slots[a] * slots[b]`
    Mul {
        /// Destination slot.
        dst: Slot,
        /// The left operand.
        a: Slot,
        /// The right operand.
        b: Slot,
    },
    /// `slots[dst] = op(slots)`
    Compute {
        /// Destination slot.
        dst: Slot,
        /// What to compute.
        op: Op,
    },
    /// The arithmetic IF: continue with the next instruction when
    /// `slots[condition] < 0`, jump to `zero` when it is 0, to `positive` when greater.
    Branch {
        /// The condition's slot.
        condition: Slot,
        /// First instruction of the zero branch.
        zero: u32,
        /// First instruction of the positive branch.
        positive: u32,
    },
    /// `slots[dst] = slots[src]` (a branch's result into the IF's slot).
    Copy {
        /// Destination slot.
        dst: Slot,
        /// Source slot.
        src: Slot,
    },
    /// Continue at instruction `target`.
    Jump {
        /// The next instruction to run.
        target: u32,
    },
}

impl Instruction {
    /// The instruction that computes `op` into `dst`.
    pub fn compute(dst: Slot, op: Op) -> Instruction {
        match op {
            Op::Neg(a) => Instruction::Neg { dst, a },
            Op::Add(a, b) => Instruction::Add { dst, a, b },
            Op::Sub(a, b) => Instruction::Sub { dst, a, b },
            Op::Mul(a, b) => Instruction::Mul { dst, a, b },
            op => Instruction::Compute { dst, op },
        }
    }

    /// The destination and the op of an instruction that computes a value
    /// (the inverse of [`Instruction::compute`]); `None` for the branches,
    /// copies and jumps of the arithmetic IF.
    pub fn computed(&self) -> Option<(Slot, Cow<'_, Op>)> {
        let (dst, op) = match *self {
            Instruction::Neg { dst, a } => (dst, Op::Neg(a)),
            Instruction::Add { dst, a, b } => (dst, Op::Add(a, b)),
            Instruction::Sub { dst, a, b } => (dst, Op::Sub(a, b)),
            Instruction::Mul { dst, a, b } => (dst, Op::Mul(a, b)),
            Instruction::Compute { dst, ref op } => return Some((dst, Cow::Borrowed(op))),
            Instruction::Branch { .. } | Instruction::Copy { .. } | Instruction::Jump { .. } => {
                return None;
            }
        };
        Some((dst, Cow::Owned(op)))
    }

    /// The name of the operation in messages: `STEP`, `` `*` ``, and `IF`
    /// for the branches, copies and jumps of the arithmetic IF.
    pub fn name(&self) -> String {
        self.computed()
            .map_or_else(|| "IF".to_string(), |(_, op)| op.name())
    }
}

/// A piecewise instruction of a program (a STEP, IMPACT, BISTOP, ABS, MIN,
/// ... call or an arithmetic IF), which a simulation holds on one branch
/// through a step: see [`crate::laws::branch`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Site {
    /// The instruction's index.
    pub instruction: u32,
    /// Its first switching value among the program's.
    pub first: u32,
    /// How many switching values it has.
    pub count: u32,
}

/// What a piecewise instruction is, for messages and event lists.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SiteKind {
    /// A call of this function.
    Call(Function),
    /// An arithmetic IF.
    If,
}

/// The sites of `code`, and each instruction's site (`NO_SITE` for none).
pub(crate) fn find_sites(code: &[Instruction]) -> (Vec<Site>, Vec<u32>) {
    let mut sites = Vec::new();
    let mut site_of = Vec::with_capacity(code.len());
    let mut first = 0;
    for (index, instruction) in code.iter().enumerate() {
        let count = match instruction {
            Instruction::Branch { .. } => Some(2),
            Instruction::Compute {
                op: Op::Contact { .. },
                ..
            } => Some(3),
            Instruction::Compute {
                op: Op::Delay { .. },
                ..
            } => Some(1),
            Instruction::Compute {
                op: Op::Call { function, args, .. },
                ..
            } => crate::laws::branch::switch_count(*function, args.len()),
            _ => None,
        };
        match count {
            Some(count) => {
                let count = u32::try_from(count).expect("fewer than 2^32 arguments");
                site_of.push(u32::try_from(sites.len()).expect("fewer than 2^32 sites"));
                sites.push(Site {
                    instruction: u32::try_from(index).expect("fewer than 2^32 instructions"),
                    first,
                    count,
                });
                first += count;
            }
            None => site_of.push(NO_SITE),
        }
    }
    (sites, site_of)
}

/// The entry of an instruction that is no site in [`Program`]'s `site_of`.
pub(crate) const NO_SITE: u32 = u32::MAX;

/// A checked expression compiled for a given list of inputs: ready to be
/// evaluated over `f64` or dual numbers, any number of times.
#[derive(Clone, Debug)]
pub struct Program {
    pub(crate) inputs: InputNames,
    pub(crate) slot_count: usize,
    pub(crate) constants: Vec<(Slot, f64)>,
    pub(crate) code: Vec<Instruction>,
    /// The span of the expression text each instruction comes from.
    pub(crate) spans: Vec<Span>,
    /// Which output's text each instruction comes from (its index among the
    /// trees compiled together; 0 for a program of one expression).
    pub(crate) origins: Vec<u32>,
    /// The slot of each output's value (one for a single expression).
    pub(crate) results: Vec<Slot>,
    /// The marker frames and splines the instructions refer to.
    pub(crate) tables: Tables,
    /// The inputs used, and their slots.
    pub(crate) loads: Vec<InputSlot>,
    /// The piecewise instructions.
    pub(crate) sites: Vec<Site>,
    /// Each instruction's index in `sites`, or [`NO_SITE`].
    pub(crate) site_of: Vec<u32>,
}

impl Program {
    /// The input names, in the order their values are passed.
    pub fn inputs(&self) -> &[String] {
        &self.inputs.names
    }

    /// The index of input `name` (case-insensitive).
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.inputs.position(name)
    }

    /// The inputs the program reads (indices into [`Program::inputs`]), in
    /// the order of their first use: none for a constant expression.
    pub fn used_inputs(&self) -> impl Iterator<Item = usize> + '_ {
        self.loads.iter().map(|load| load.input as usize)
    }

    /// Each `DELAY` of a program compiled for a running solver, in the
    /// order of their records ([`crate::ops::Op::Delay`]'s `site`): the
    /// slots of `TIME`, of the time looked back to and of the expression
    /// delayed.
    pub(crate) fn delays(&self) -> Vec<[Slot; 3]> {
        let mut delays = Vec::new();
        for instruction in &self.code {
            if let Instruction::Compute {
                op:
                    Op::Delay {
                        time,
                        at,
                        delayed,
                        site,
                        ..
                    },
                ..
            } = instruction
            {
                let site = *site as usize;
                if delays.len() <= site {
                    delays.resize(site + 1, [0; 3]);
                }
                delays[site] = [*time, *at, *delayed];
            }
        }
        delays
    }

    /// The number of instructions (a constant expression has none).
    pub fn len(&self) -> usize {
        self.code.len()
    }

    /// Whether the program is a constant (no instruction at all).
    pub fn is_empty(&self) -> bool {
        self.code.is_empty()
    }

    /// How many values the program computes: one for [`crate::compile()`],
    /// one per tree for [`crate::compile::compile_outputs`].
    pub fn output_count(&self) -> usize {
        self.results.len()
    }

    /// Whether the program reads input `index` (an expression may not use
    /// every input it was compiled for).
    pub fn uses_input(&self, index: usize) -> bool {
        self.loads.iter().any(|load| load.input as usize == index)
    }

    /// The piecewise instructions, in program order.
    pub fn sites(&self) -> &[Site] {
        &self.sites
    }

    /// How many switching values the sites have in all.
    pub fn switch_count(&self) -> usize {
        self.sites
            .last()
            .map_or(0, |site| (site.first + site.count) as usize)
    }

    /// What a site is.
    pub fn site_kind(&self, site: &Site) -> SiteKind {
        match &self.code[site.instruction as usize] {
            Instruction::Compute {
                op: Op::Call { function, .. } | Op::Contact { function, .. },
                ..
            } => SiteKind::Call(*function),
            Instruction::Compute {
                op: Op::Delay { .. },
                ..
            } => SiteKind::Call(Function::Delay),
            _ => SiteKind::If,
        }
    }

    /// The span of the text instruction `index` comes from (in the text of
    /// output [`Program::origin`]`(index)`).
    pub fn span(&self, index: usize) -> Span {
        self.spans[index]
    }

    /// The inputs each output reads (indices into [`Program::inputs`],
    /// increasing), through either branch of every arithmetic IF: where its
    /// derivatives can be nonzero.
    pub fn inputs_of_outputs(&self) -> Vec<Vec<usize>> {
        let mut reads: Vec<Vec<usize>> = vec![Vec::new(); self.slot_count];
        for load in &self.loads {
            reads[load.slot as usize] = vec![load.input as usize];
        }
        let mut operands = Vec::new();
        for instruction in &self.code {
            operands.clear();
            let dst = match instruction {
                // An IF's result takes its branches' reads together.
                Instruction::Copy { dst, src } => {
                    operands.extend([*src, *dst]);
                    *dst
                }
                Instruction::Branch { .. } | Instruction::Jump { .. } => continue,
                _ => {
                    let (dst, op) = instruction.computed().expect("a value");
                    op.for_each_operand(|slot| operands.push(slot));
                    dst
                }
            };
            let mut union: Vec<usize> = operands
                .iter()
                .flat_map(|&slot| reads[slot as usize].iter().copied())
                .collect();
            union.sort_unstable();
            union.dedup();
            reads[dst as usize] = union;
        }
        self.results
            .iter()
            .map(|&slot| reads[slot as usize].clone())
            .collect()
    }

    /// The output whose text instruction `index` comes from (a subexpression
    /// that several outputs share comes from the first of them).
    pub fn origin(&self, index: usize) -> usize {
        self.origins.get(index).map_or(0, |&origin| origin as usize)
    }
}

/// One instruction per line, `s3 = BISTOP(s0, s1, ...)`, constants first.
impl fmt::Display for Program {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (slot, value) in &self.constants {
            writeln!(f, "s{slot} = {value}")?;
        }
        for (index, stops) in self.tables.contacts.iter().enumerate() {
            writeln!(f, "stops{index} = {stops}")?;
        }
        for load in &self.loads {
            writeln!(
                f,
                "s{} = input {}",
                load.slot, self.inputs[load.input as usize]
            )?;
        }
        for (index, instruction) in self.code.iter().enumerate() {
            write!(f, "{index:>3}: ")?;
            let Some((dst, op)) = instruction.computed() else {
                match instruction {
                    Instruction::Branch {
                        condition,
                        zero,
                        positive,
                    } => writeln!(f, "if s{condition} = 0 goto {zero}; if > 0 goto {positive}")?,
                    Instruction::Copy { dst, src } => writeln!(f, "s{dst} = s{src}")?,
                    Instruction::Jump { target } => writeln!(f, "goto {target}")?,
                    // The others compute a value, written below.
                    _ => {}
                }
                continue;
            };
            writeln!(f, "s{dst} = {op}")?;
        }
        let results: Vec<String> = self.results.iter().map(|slot| format!("s{slot}")).collect();
        let label = if results.len() == 1 {
            "result"
        } else {
            "results"
        };
        write!(f, "{label} {}", results.join(", "))
    }
}
