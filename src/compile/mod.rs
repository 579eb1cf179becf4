//! Stage 3, compile: a checked tree to a flat [`Program`] for a given list of
//! inputs. Constants are folded, every subexpression is computed once, and
//! only the branch an `IF` chooses is run.

mod error;
mod program;
mod solver;

use std::collections::{HashMap, HashSet};

pub(crate) use crate::ops::Tables;
pub use crate::ops::{FrameArg, Op, Slot};
pub use error::CompileError;
pub(crate) use program::{InputNames, NO_SITE};
pub use program::{InputSlot, Instruction, Program, Site, SiteKind};
pub use solver::{MarkerCall, RunCall, SolverCall};

use crate::catalog::{Family, Function, SystemVariable, check_rules, closest, did_you_mean};
use crate::check::{Argument, Checked, Node, NodeKind, Reference};
use crate::errors::Errors;
use crate::kinematics::{FrameData, Orientation, Selector};
use crate::laws::contact::Stops;
use crate::laws::power::as_integer;
use crate::laws::spline::{Method, Spline};
use crate::ops::execute;
use crate::scene::{Scene, SceneKind, StateComponent, Target};
use crate::span::Span;
use crate::syntax::ast::BinaryOp;

/// Compiles `checked` for inputs named `inputs` (case-insensitive; `TIME`
/// and `MODE` may be among them; `MODE` is 4 when not). The values of the
/// inputs are later passed in this order.
///
/// Every name the expression uses must be an input; every problem is
/// reported, in source order.
pub fn compile<S: AsRef<str>>(
    checked: &Checked,
    inputs: &[S],
) -> Result<Program, Errors<CompileError>> {
    compile_with(checked, inputs, None, false)
}

/// Compiles `checked` in `scene`: like [`compile`], and the kinematic
/// measures are evaluated between the scene's markers. The states of the
/// bodies the measures use become further inputs, named `BODY.x` ...
/// `BODY.wz` (see [`Program::inputs`]); [`Scene::values`] gives their values.
/// Nothing of the scene that the expression does not use is kept.
pub fn compile_in_scene<S: AsRef<str>>(
    checked: &Checked,
    inputs: &[S],
    scene: &Scene,
) -> Result<Program, Errors<CompileError>> {
    compile_with(checked, inputs, Some(scene), false)
}

/// Compiles `checked` in the scene of a model whose VARIABLEs are evaluated
/// one by one in dependency order: like [`compile_in_scene`], except that
/// `VARVAL(id)` of a VARIABLE the scene defines is the input named
/// [`variable_input`]`(id)`, whose value (with its derivatives) the caller
/// gives, rather than the VARIABLE's expression compiled in place.
pub fn compile_in_model<S: AsRef<str>>(
    checked: &Checked,
    inputs: &[S],
    scene: &Scene,
) -> Result<Program, Errors<CompileError>> {
    compile_with(checked, inputs, Some(scene), true)
}

/// The name of the input that holds VARIABLE `id` in a program of
/// [`compile_in_model`]: `VARVAL(7)` (no name of the language has a parenthesis).
pub fn variable_input(id: u64) -> String {
    format!("VARVAL({id})")
}

/// Compiles several trees into one program with one output each (the
/// forces and DIFF functions of a model, for a simulation): a subexpression
/// they share is computed once, and [`Program::origin`] tells which tree an
/// instruction's span belongs to. On failure, each tree's errors with its
/// index.
pub fn compile_outputs<S: AsRef<str>>(
    trees: &[&Checked],
    inputs: &[S],
    scene: Option<&Scene>,
) -> Result<Program, Vec<(usize, Errors<CompileError>)>> {
    compile_all(trees, inputs, scene, false, None)
}

/// Whether a program may read a value of a running solver (a reaction, a
/// measure of accelerations): `Ok`, or why not (the message of the error
/// at the call).
pub type Reactions<'r> = &'r dyn Fn(&RunCall) -> Result<(), String>;

/// Compiles several trees into one program like [`compile_outputs`], for
/// a running solver: each call of `JOINT`, `JPRIM` or `MOTION`, and each
/// measure of accelerations on a body the scene gives none for, that
/// `reactions` accepts becomes the input named by
/// [`RunCall::input_name`], whose value the solver gives; one it refuses
/// is an error at the call with its message.
pub fn compile_run_outputs<S: AsRef<str>>(
    trees: &[&Checked],
    inputs: &[S],
    scene: &Scene,
    reactions: Reactions<'_>,
) -> Result<Program, Vec<(usize, Errors<CompileError>)>> {
    compile_all(trees, inputs, Some(scene), false, Some(reactions))
}

fn compile_all<S: AsRef<str>>(
    trees: &[&Checked],
    inputs: &[S],
    scene: Option<&Scene>,
    variables_as_inputs: bool,
    reactions: Option<Reactions<'_>>,
) -> Result<Program, Vec<(usize, Errors<CompileError>)>> {
    let mut compiler = Compiler {
        scene,
        reactions,
        delays: 0,
        history_time: None,
        origin: 0,
        inlining: Vec::new(),
        inlining_set: HashSet::new(),
        inlining_diffs: Vec::new(),
        inlining_outputs: Vec::new(),
        tables: Tables::default(),
        frame_of: HashMap::new(),
        spline_of: HashMap::new(),
        inputs: InputNames::default(),
        variable_slots: Vec::new(),
        constant_values: Vec::new(),
        known_values: Vec::new(),
        constant_slots: HashMap::new(),
        constants: Vec::new(),
        code: Vec::new(),
        spans: Vec::new(),
        origins: Vec::new(),
        memo: vec![HashMap::new()],
        loads: Vec::new(),
        load_of: HashMap::new(),
        errors: Vec::new(),
        depth: 0,
        inlined_at: None,
        variables_as_inputs,
    };
    for name in inputs {
        compiler.inputs.push(name.as_ref().to_string());
    }
    compiler.variable_slots.push(HashMap::new());
    let mut results = Vec::with_capacity(trees.len());
    let mut failures = Vec::new();
    for (index, tree) in trees.iter().enumerate() {
        compiler.origin = u32::try_from(index).expect("fewer than 2^32 outputs");
        results.push(compiler.node(&tree.root));
        let mut errors = std::mem::take(&mut compiler.errors);
        if !errors.is_empty() {
            errors.sort_by_key(|error| error.span().start);
            failures.push((index, Errors(errors)));
        }
    }
    if !failures.is_empty() {
        return Err(failures);
    }
    let (sites, site_of) = program::find_sites(&compiler.code);
    Ok(Program {
        slot_count: compiler.constant_values.len(),
        inputs: compiler.inputs,
        constants: compiler.constants,
        code: compiler.code,
        spans: compiler.spans,
        origins: compiler.origins,
        results,
        tables: compiler.tables,
        loads: compiler.loads,
        sites,
        site_of,
    })
}

fn compile_with<S: AsRef<str>>(
    checked: &Checked,
    inputs: &[S],
    scene: Option<&Scene>,
    variables_as_inputs: bool,
) -> Result<Program, Errors<CompileError>> {
    compile_all(&[checked], inputs, scene, variables_as_inputs, None)
        .map_err(|mut failures| failures.swap_remove(0).1)
}

struct Compiler<'s> {
    scene: Option<&'s Scene>,
    /// Which solver reactions are inputs (`None`: none, every solver
    /// result is refused).
    reactions: Option<Reactions<'s>>,
    /// The number of DELAY calls compiled (each its own record).
    delays: u32,
    /// The slot `TIME` stands for while a DELAY's history is compiled (the
    /// time it looks back to); `None` elsewhere.
    history_time: Option<Slot>,
    /// The index of the tree being compiled, recorded with each instruction.
    origin: u32,
    /// The VARIABLEs being compiled in place, outermost first.
    inlining: Vec<u64>,
    /// The same, to look up.
    inlining_set: HashSet<u64>,
    /// The DIFFs whose FUNCTION is being compiled in place for `DIF1`.
    inlining_diffs: Vec<u64>,
    /// The Y arrays of the linear systems whose outputs are being compiled
    /// in place, to refuse a loop (an output that reads itself through
    /// an input).
    inlining_outputs: Vec<u64>,
    /// The marker frames and fitted splines used, and where each went.
    tables: Tables,
    frame_of: HashMap<Target, u32>,
    spline_of: HashMap<(u64, Method), u32>,
    inputs: InputNames,
    /// The slot of each VARIABLE compiled in place, by IF scope like `memo`.
    variable_slots: Vec<HashMap<u64, Slot>>,
    /// Whether `VARVAL(id)` is the input `VARVAL(id)` rather than the
    /// VARIABLE's expression compiled in place.
    variables_as_inputs: bool,
    /// The value of each slot when it is a compile-time constant.
    constant_values: Vec<Option<f64>>,
    /// The same values with 0 for the slots that are not constants, as the
    /// evaluator's `execute` reads them when folding.
    known_values: Vec<f64>,
    /// The slot of each constant, by its bits.
    constant_slots: HashMap<u64, Slot>,
    constants: Vec<(Slot, f64)>,
    code: Vec<Instruction>,
    spans: Vec<Span>,
    origins: Vec<u32>,
    /// Computed ops by scope: the outer scopes' entries hold inside an IF
    /// branch, a branch's own entries are dropped when it ends.
    memo: Vec<HashMap<Op, Slot>>,
    /// Where each input used is placed, and where it is first used.
    loads: Vec<InputSlot>,
    /// The slot of each input used, by its index.
    load_of: HashMap<usize, Slot>,
    errors: Vec<CompileError>,
    /// How deep the tree being compiled nests here, the trees compiled in
    /// place (VARIABLEs, DIFFs, outputs) counting with the tree that reads
    /// them.
    depth: usize,
    /// The call in the tree being compiled that the outermost tree
    /// compiled in place stands for (where an error inside it is shown).
    inlined_at: Option<Span>,
}

/// How deep a tree may nest once the VARIABLEs, DIFFs and outputs it reads
/// are compiled in place: twice the parser's limit for one expression, so
/// that the compiler's recursion stays well inside a thread's stack.
const MAX_INLINED_NESTING: usize = 2 * crate::syntax::MAX_NESTING;

/// The stack the compiler's recursion keeps in hand before it grows a new
/// segment ([`Compiler::node`]), and the size of a segment.
const STACK_RED_ZONE: usize = 64 * 1024;
const STACK_SEGMENT: usize = 1024 * 1024;

impl Compiler<'_> {
    fn new_slot(&mut self, constant: Option<f64>) -> Slot {
        self.constant_values.push(constant);
        self.known_values.push(constant.unwrap_or(0.0));
        Slot::try_from(self.constant_values.len() - 1).expect("fewer than 2^32 slots")
    }

    fn constant(&mut self, value: f64) -> Slot {
        let bits = value.to_bits();
        if let Some(&slot) = self.constant_slots.get(&bits) {
            return slot;
        }
        let slot = self.new_slot(Some(value));
        self.constant_slots.insert(bits, slot);
        self.constants.push((slot, value));
        slot
    }

    fn emit(&mut self, instruction: Instruction, span: Span) -> u32 {
        self.code.push(instruction);
        self.spans.push(span);
        self.origins.push(self.origin);
        u32::try_from(self.code.len() - 1).expect("fewer than 2^32 instructions")
    }

    /// The slot input `index` is placed in before the program runs.
    fn input(&mut self, index: usize, span: Span) -> Slot {
        if let Some(&slot) = self.load_of.get(&index) {
            return slot;
        }
        let slot = self.new_slot(None);
        let input = u32::try_from(index).expect("fewer than 2^32 inputs");
        self.loads.push(InputSlot { input, slot, span });
        self.load_of.insert(index, slot);
        slot
    }

    /// The slot of `op`: folded when its operands are constants, reused when
    /// it was computed before in scope, else a new instruction.
    fn compute(&mut self, op: Op, span: Span) -> Slot {
        if let Some(slot) = self.memo.iter().rev().find_map(|scope| scope.get(&op)) {
            return *slot;
        }
        if let Some(value) = self.fold(&op) {
            return self.constant(value);
        }
        let dst = self.new_slot(None);
        self.emit(Instruction::compute(dst, op.clone()), span);
        self.memo.last_mut().expect("a scope").insert(op, dst);
        dst
    }

    /// The value of `op` when all its operands are constants and it has one.
    fn fold(&self, op: &Op) -> Option<f64> {
        let operands: Vec<Slot> = match op {
            Op::Neg(a) | Op::PowInt(a, _) | Op::PowReal(a, _) => vec![*a],
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) | Op::Pow(a, b) => {
                vec![*a, *b]
            }
            Op::Call { args, .. } => args.to_vec(),
            Op::Spline { x, z, .. } | Op::Contact { x, v: z, .. } => vec![*x, *z],
            // It reads the run's record: never folded.
            Op::Delay { .. } => return None,
            Op::Measure { frames, .. } => frames
                .iter()
                .flat_map(|frame| frame.state.into_iter().flatten())
                .collect(),
        };
        if operands
            .iter()
            .any(|&slot| self.constant_values[slot as usize].is_none())
        {
            return None;
        }
        execute(op, &self.known_values, &self.tables)
            .ok()
            .filter(|value| value.is_finite())
    }

    fn node(&mut self, node: &Node) -> Slot {
        if self.depth >= MAX_INLINED_NESTING {
            let span = self.inlined_at.unwrap_or(node.span);
            if !self
                .errors
                .iter()
                .any(|error| matches!(error, CompileError::TooDeep { .. }))
            {
                self.errors.push(CompileError::TooDeep {
                    limit: MAX_INLINED_NESTING,
                    span,
                });
            }
            return self.constant(0.0);
        }
        self.depth += 1;
        // Each level takes a few hundred bytes of stack: where less than
        // STACK_RED_ZONE is left, the rest of the tree goes on a new
        // segment of STACK_SEGMENT on the heap.
        let slot = stacker::maybe_grow(STACK_RED_ZONE, STACK_SEGMENT, || self.node_kind(node));
        self.depth -= 1;
        slot
    }

    fn node_kind(&mut self, node: &Node) -> Slot {
        let span = node.span;
        match &node.kind {
            NodeKind::Number(value) => self.constant(*value),
            NodeKind::Constant(constant) => self.constant(constant.value()),
            NodeKind::System(variable) => self.system(*variable, span),
            NodeKind::Variable(name) => self.variable(name, span),
            NodeKind::Neg(operand) => {
                let a = self.node(operand);
                self.compute(Op::Neg(a), span)
            }
            NodeKind::Chain(first, rest) => self.chain(first, rest),
            NodeKind::Power(base, exponent) => self.power(base, exponent, span),
            NodeKind::Call(function, args) => self.call(*function, args, span),
            NodeKind::If(branches) => self.arithmetic_if(branches, span),
        }
    }

    fn system(&mut self, variable: SystemVariable, span: Span) -> Slot {
        if variable == SystemVariable::Time
            && let Some(at) = self.history_time
        {
            return at;
        }
        match self.input_index(variable.name()) {
            Some(index) => self.input(index, span),
            None if variable == SystemVariable::Mode => self.constant(SystemVariable::DEFAULT_MODE),
            None => self.unbound(variable.name(), span),
        }
    }

    fn input_index(&self, name: &str) -> Option<usize> {
        self.inputs.position(name)
    }

    fn variable(&mut self, name: &str, span: Span) -> Slot {
        match self.input_index(name) {
            Some(index) => self.input(index, span),
            None => self.unbound(name, span),
        }
    }

    fn unbound(&mut self, name: &str, span: Span) -> Slot {
        let suggestions = did_you_mean(&closest(name, self.inputs.iter().map(String::as_str)));
        self.errors.push(CompileError::UnboundVariable {
            name: name.to_string(),
            suggestions,
            span,
        });
        self.constant(0.0)
    }

    /// A run of `+ -` or `* /`, folded from the left; each step takes the
    /// span from the chain's first operand to its right operand.
    fn chain(&mut self, first: &Node, rest: &[(BinaryOp, Node)]) -> Slot {
        let mut a = self.node(first);
        for (op, operand) in rest {
            let b = self.node(operand);
            let op = match op {
                BinaryOp::Add => Op::Add(a, b),
                BinaryOp::Sub => Op::Sub(a, b),
                BinaryOp::Mul => Op::Mul(a, b),
                BinaryOp::Div => Op::Div(a, b),
            };
            a = self.compute(op, first.span.to(operand.span));
        }
        a
    }

    fn power(&mut self, base: &Node, exponent: &Node, span: Span) -> Slot {
        let a = self.node(base);
        let b = self.node(exponent);
        let op = match self.constant_values[b as usize] {
            Some(exponent) => match as_integer(exponent) {
                Some(n) => Op::PowInt(a, n),
                None => Op::PowReal(a, exponent.to_bits()),
            },
            None => Op::Pow(a, b),
        };
        self.compute(op, span)
    }

    fn call(&mut self, function: Function, args: &[Argument], span: Span) -> Slot {
        if function == Function::Delay && self.reactions.is_some() {
            return match self.delay(args, span) {
                Ok(slot) => slot,
                Err(error) => {
                    self.errors.push(error);
                    self.constant(0.0)
                }
            };
        }
        let error = match function.family() {
            Family::Intrinsic | Family::Step | Family::Contact | Family::Series => None,
            Family::Measure => match self.scene {
                Some(scene) => return self.measure(scene, function, args, span),
                None => Some(CompileError::NeedsScene {
                    function: function.name(),
                    span,
                }),
            },
            Family::ModelData => match self.scene {
                Some(scene) => match self.statement_data(scene, function, args, span) {
                    Ok(slot) => return slot,
                    Err(error) => Some(error),
                },
                None => Some(model_data_error(function, args, span, None)),
            },
            Family::Solver
                if MarkerCall::NET_FORCES.contains(&function)
                    && let Some(reactions) = self.reactions =>
            {
                let call = RunCall::NetForce(MarkerCall::of(function, args));
                match reactions(&call) {
                    Ok(()) => return self.reaction(&call, span),
                    Err(message) => Some(CompileError::Reaction { message, span }),
                }
            }
            Family::Solver => match (self.reactions, SolverCall::of(function, args)) {
                (Some(reactions), Some(call)) => {
                    let call = RunCall::Reaction(call);
                    match reactions(&call) {
                        Ok(()) => return self.reaction(&call, span),
                        Err(message) => Some(CompileError::Reaction { message, span }),
                    }
                }
                _ => Some(CompileError::NeedsSolver {
                    function: function.name(),
                    span,
                }),
            },
            Family::User => Some(CompileError::UserSubroutine { span }),
        };
        if let Some(error) = error {
            self.errors.push(error);
            return self.constant(0.0);
        }
        let slots: Box<[Slot]> = args
            .iter()
            .map(|arg| match arg {
                Argument::Value(node) => self.node(node),
                _ => unreachable!("the checker gives {function} only value arguments"),
            })
            .collect();
        let constants: Vec<Option<f64>> = slots
            .iter()
            .map(|&slot| self.constant_values[slot as usize])
            .collect();
        // Rules whose arguments are all constants are checked once, here;
        // the others at every evaluation.
        let all_known = function.rules().iter().all(|rule| {
            rule.positions()
                .into_iter()
                .all(|position| constants[position].is_some())
        });
        let check_rules = !(all_known && check_rules(function, &constants).is_ok());
        if function.family() == Family::Contact
            && !check_rules
            && let Some(stops) = constants.get(2..).and_then(constant_stops)
        {
            let table = self.stops(stops);
            let (x, v) = (slots[0], slots[1]);
            return self.compute(
                Op::Contact {
                    function,
                    table,
                    x,
                    v,
                },
                span,
            );
        }
        self.compute(
            Op::Call {
                function,
                args: slots,
                check_rules,
            },
            span,
        )
    }

    /// `DELAY(e, delay, history [, id])` for a running solver: `e` computed
    /// now (the run records it at its accepted states), the time looked
    /// back to, `TIME − max(delay, 0)` (Adams takes a negative delay as
    /// zero), and the history, a function of TIME compiled with TIME
    /// standing for the time looked back to; the fourth argument (Adams'
    /// array of interpolation settings) must be 0 or absent.
    fn delay(&mut self, args: &[Argument], span: Span) -> Result<Slot, CompileError> {
        let value = |compiler: &mut Self, position: usize| match args.get(position) {
            Some(Argument::Value(node)) => Some(compiler.node(node)),
            _ => None,
        };
        let refuse = |message: &str| CompileError::Reaction {
            message: format!("DELAY: {message}"),
            span,
        };
        let no_array = match args.get(3) {
            None => true,
            Some(Argument::Flag(flag, _)) => *flag == 0,
            Some(Argument::Value(node)) => {
                matches!(node.kind, NodeKind::Number(value) if value == 0.0)
            }
            Some(_) => false,
        };
        if !no_array {
            return Err(refuse(
                "its fourth argument (the id of an ARRAY of interpolation settings) is not read by mbexpr: give 0 or leave it out",
            ));
        }
        let (Some(delayed), Some(delay)) = (value(self, 0), value(self, 1)) else {
            return Err(refuse("give the expression, the delay and the history"));
        };
        let time = self.system(SystemVariable::Time, span);
        let zero = self.constant(0.0);
        let delay = self.compute(
            Op::Call {
                function: Function::Max,
                args: Box::new([delay, zero]),
                check_rules: false,
            },
            span,
        );
        let at = self.compute(Op::Sub(time, delay), span);
        // The history is a function of TIME (or a constant), taken at the
        // time looked back to.
        let outer = self.history_time.replace(at);
        let history = value(self, 2);
        self.history_time = outer;
        let Some(history) = history else {
            return Err(refuse("give the expression, the delay and the history"));
        };
        let site = self.delays;
        self.delays += 1;
        Ok(self.compute(
            Op::Delay {
                time,
                at,
                delayed,
                history,
                site,
            },
            span,
        ))
    }

    /// The input that holds the value of the solver's `call`, added when new.
    fn reaction(&mut self, call: &RunCall, span: Span) -> Slot {
        let name = call.input_name();
        let index = self
            .input_index(&name)
            .unwrap_or_else(|| self.inputs.push(name));
        self.input(index, span)
    }

    /// The index of `stops` in the program's table, added when new.
    fn stops(&mut self, stops: Stops) -> u32 {
        let contacts = &mut self.tables.contacts;
        let index = match contacts.iter().position(|known| *known == stops) {
            Some(index) => index,
            None => {
                contacts.push(stops);
                contacts.len() - 1
            }
        };
        u32::try_from(index).expect("fewer than 2^32 contact laws")
    }

    /// The input named `name` (added at its first use).
    fn named_input(&mut self, name: String, span: Span) -> Slot {
        let index = self
            .input_index(&name)
            .unwrap_or_else(|| self.inputs.push(name));
        self.input(index, span)
    }

    /// `VARVAL(id)` as the VARIABLE's own expression, compiled in place (so
    /// its derivatives flow), `ARYVAL(id, i)` as a constant, and `DIF(id)`
    /// and `SENVAL(id)` as inputs, from the scene's statement data.
    fn statement_data(
        &mut self,
        scene: &Scene,
        function: Function,
        args: &[Argument],
        span: Span,
    ) -> Result<Slot, CompileError> {
        let id = args.iter().find_map(|arg| match arg {
            Argument::Object(Reference::Id(id), _) => Some(*id),
            _ => None,
        });
        if function == Function::Dif1
            && let Some(id) = id
            && let Some(diff) = scene.statements.diffs.get(&id)
        {
            if diff.implicit {
                return self.implicit_rate(id, span);
            }
            if let Some(tree) = &diff.function {
                return self.inline_diff(id, tree, span);
            }
        }
        match (function, id) {
            (Function::Varval, Some(id)) if scene.statements.variables.contains_key(&id) => {
                self.model_variable(scene, id, span)
            }
            (Function::Aryval, Some(id)) if scene.statements.input_arrays.contains_key(&id) => {
                let list = &scene.statements.input_arrays[&id];
                self.listed_variable(scene, ("ARYVAL", "ARRAY"), (id, list), args, span)
            }
            (Function::Pinval, Some(id)) if scene.statements.plant_inputs.contains_key(&id) => {
                let list = &scene.statements.plant_inputs[&id];
                self.listed_variable(scene, ("PINVAL", "PINPUT"), (id, list), args, span)
            }
            (Function::Friction, Some(id))
                if scene.statements.friction_outputs.contains_key(&id) =>
            {
                let list = &scene.statements.friction_outputs[&id];
                self.listed_variable(scene, ("FRICTION", "FRICTION"), (id, list), args, span)
            }
            (Function::Pouval, Some(id)) if scene.statements.plant_outputs.contains_key(&id) => {
                let list = &scene.statements.plant_outputs[&id];
                self.listed_variable(scene, ("POUVAL", "POUTPUT"), (id, list), args, span)
            }
            (Function::Aryval, Some(id)) if scene.statements.system_with_states(id).is_some() => {
                let system = scene.statements.system_with_states(id).expect("found");
                let index = entry_index(("ARYVAL", "ARRAY"), id, system.initial.len(), args, span)?;
                Ok(self.named_input(crate::scene::array_state_input(id, index + 1), span))
            }
            (Function::Aryval, Some(id)) if scene.statements.system_with_outputs(id).is_some() => {
                let system = scene.statements.system_with_outputs(id).expect("found");
                let (_, tree) = array_entry(
                    ("ARYVAL", "ARRAY"),
                    id,
                    &system.output_expressions,
                    args,
                    span,
                )?;
                self.inline_output((id, &system.statement), tree, span)
            }
            (Function::Aryval, Some(id)) if scene.statements.arrays.contains_key(&id) => {
                let value = *array_entry(
                    ("ARYVAL", "ARRAY"),
                    id,
                    &scene.statements.arrays[&id],
                    args,
                    span,
                )?;
                Ok(self.constant(value))
            }
            (Function::Dif, Some(id)) if scene.statements.diffs.contains_key(&id) => {
                Ok(self.named_input(crate::scene::diff_input(id), span))
            }
            (Function::Senval, Some(id)) if scene.statements.evaluated_sensors.contains(&id) => {
                Ok(self.named_input(crate::scene::sensor_input(id), span))
            }
            (Function::Akispl | Function::Cubspl, Some(id))
                if scene.statements.splines.contains_key(&id) =>
            {
                self.spline(scene, function, id, args, span)
            }
            _ => Err(model_data_error(function, args, span, Some(scene))),
        }
    }

    /// Entry `i` of a list of VARIABLEs (a U ARRAY's, a PINPUT's or a
    /// POUTPUT's: `ARYVAL(id, i)`, `PINVAL(id, i)`, `POUVAL(id, i)`), as
    /// [`Self::model_variable`] compiles it.
    fn listed_variable(
        &mut self,
        scene: &Scene,
        names: (&'static str, &'static str),
        (id, list): (u64, &[u64]),
        args: &[Argument],
        span: Span,
    ) -> Result<Slot, CompileError> {
        match *array_entry(names, id, list, args, span)? {
            variable if scene.statements.variables.contains_key(&variable) => {
                self.model_variable(scene, variable, span)
            }
            variable => Err(CompileError::MissingStatement {
                function: "VARVAL",
                id: variable.to_string(),
                statement: format!("VARIABLE/{variable}"),
                span,
            }),
        }
    }

    /// `VARVAL(id)`: VARIABLE `id`'s FUNCTION, compiled in place (once per
    /// scope) so that its derivatives flow, or an input where variables
    /// are inputs.
    fn model_variable(&mut self, scene: &Scene, id: u64, span: Span) -> Result<Slot, CompileError> {
        if self.variables_as_inputs {
            let name = variable_input(id);
            let index = self
                .input_index(&name)
                .unwrap_or_else(|| self.inputs.push(name));
            return Ok(self.input(index, span));
        }
        if let Some(&slot) = self
            .variable_slots
            .iter()
            .rev()
            .find_map(|scope| scope.get(&id))
        {
            return Ok(slot);
        }
        if self.inlining_set.contains(&id) {
            let mut cycle: Vec<String> = self
                .inlining
                .iter()
                .map(|id| format!("VARIABLE/{id}"))
                .collect();
            cycle.push(format!("VARIABLE/{id}"));
            return Err(CompileError::VariableLoop {
                cycle: cycle.join(" -> "),
                span,
            });
        }
        self.inlining.push(id);
        self.inlining_set.insert(id);
        let slot = self.inline_tree(&scene.statements.variables[&id].root, span);
        self.inlining.pop();
        self.inlining_set.remove(&id);
        self.variable_slots
            .last_mut()
            .expect("a scope")
            .insert(id, slot);
        Ok(slot)
    }

    /// A tree whose text is elsewhere (a VARIABLE's FUNCTION for VARVAL, a
    /// DIFF's for DIF1, a linear system's output for ARYVAL), compiled in
    /// place: its instructions take the span of the call, `span`.
    fn inline_tree(&mut self, root: &Node, span: Span) -> Slot {
        let spans_before = self.spans.len();
        let outermost = self.inlined_at.is_none();
        if outermost {
            self.inlined_at = Some(span);
        }
        let slot = self.node(root);
        if outermost {
            self.inlined_at = None;
        }
        for instruction_span in &mut self.spans[spans_before..] {
            *instruction_span = span;
        }
        slot
    }

    /// `DIF1(id)`: the FUNCTION of DIFF `id`, compiled in place so that its
    /// derivatives flow.
    fn inline_diff(&mut self, id: u64, tree: &Checked, span: Span) -> Result<Slot, CompileError> {
        if self.inlining_diffs.contains(&id) {
            let mut cycle: Vec<String> = self
                .inlining_diffs
                .iter()
                .map(|id| format!("DIFF/{id}"))
                .collect();
            cycle.push(format!("DIFF/{id}"));
            return Err(CompileError::VariableLoop {
                cycle: cycle.join(" -> "),
                span,
            });
        }
        self.inlining_diffs.push(id);
        let slot = self.inline_tree(&tree.root, span);
        self.inlining_diffs.pop();
        Ok(slot)
    }

    /// `DIF1(id)` of an implicit DIFF: for a running solver the root of
    /// its FUNCTION, a value it gives (when `reactions` accepts it), and
    /// otherwise the input of that name (the IC's second value by default).
    fn implicit_rate(&mut self, id: u64, span: Span) -> Result<Slot, CompileError> {
        let call = RunCall::ImplicitRate(id);
        match self.reactions {
            Some(reactions) => match reactions(&call) {
                Ok(()) => Ok(self.reaction(&call, span)),
                Err(message) => Err(CompileError::Reaction { message, span }),
            },
            None => Ok(self.named_input(call.input_name(), span)),
        }
    }

    /// `ARYVAL(y, i)` of a linear system's Y array `y`: its output `C x +
    /// D u`, compiled in place so that its derivatives flow.
    fn inline_output(
        &mut self,
        (array, statement): (u64, &str),
        tree: &Checked,
        span: Span,
    ) -> Result<Slot, CompileError> {
        if self.inlining_outputs.contains(&array) {
            return Err(CompileError::VariableLoop {
                cycle: format!(
                    "{statement}'s output ARRAY/{array} reads itself through its inputs"
                ),
                span,
            });
        }
        self.inlining_outputs.push(array);
        let slot = self.inline_tree(&tree.root, span);
        self.inlining_outputs.pop();
        Ok(slot)
    }

    /// `AKISPL(x, z, id [, iord])` or `CUBSPL(...)` over SPLINE `id`, fitted
    /// once per program and method.
    fn spline(
        &mut self,
        scene: &Scene,
        function: Function,
        id: u64,
        args: &[Argument],
        span: Span,
    ) -> Result<Slot, CompileError> {
        let order = match args.get(3) {
            Some(Argument::Flag(order @ 0..=2, _)) => *order as u8,
            Some(Argument::Flag(order, order_span)) => {
                return Err(CompileError::SplineOrder {
                    function: function.name(),
                    order: *order,
                    span: *order_span,
                });
            }
            _ => 0,
        };
        let method = if function == Function::Akispl {
            Method::Akima
        } else {
            Method::Cubic
        };
        let table = match self.spline_of.get(&(id, method)) {
            Some(&table) => table,
            None => {
                let fitted = Spline::fit(&scene.statements.splines[&id], method);
                self.tables.splines.push(fitted);
                let table =
                    u32::try_from(self.tables.splines.len() - 1).expect("fewer than 2^32 splines");
                self.spline_of.insert((id, method), table);
                table
            }
        };
        let mut value = |position: usize| match args.get(position) {
            Some(Argument::Value(node)) => self.node(node),
            _ => unreachable!("the checker gives {function} a value at {position}"),
        };
        let (x, z) = (value(0), value(1));
        Ok(self.compute(
            Op::Spline {
                function,
                table,
                x,
                z,
                order,
            },
            span,
        ))
    }

    /// A measure between the scene's markers; omitted markers are ground.
    fn measure(
        &mut self,
        scene: &Scene,
        function: Function,
        args: &[Argument],
        span: Span,
    ) -> Slot {
        // ORIENT's two flags come first; INCANG's second line starts at j
        // when it has three markers.
        let (selector, markers): (Selector, Vec<usize>) = match function {
            Function::Orient => {
                let flag = |position: usize| match args.get(position) {
                    Some(Argument::Flag(value, _)) => *value,
                    _ => 0,
                };
                match Orientation::new(flag(0), flag(1)) {
                    Ok(orientation) => (Selector::Orientation(orientation), vec![2, 3]),
                    Err(message) => {
                        self.errors
                            .push(CompileError::Orientation { message, span });
                        return self.constant(0.0);
                    }
                }
            }
            Function::Incang if args.len() == 3 => (Selector::Plain, vec![0, 1, 1, 2]),
            _ => (Selector::Plain, (0..function.signature().max).collect()),
        };
        let needs_accelerations = matches!(
            function,
            Function::Accx
                | Function::Accy
                | Function::Accz
                | Function::Accm
                | Function::Wdtx
                | Function::Wdty
                | Function::Wdtz
                | Function::Wdtm
        );
        let mut frames = Vec::new();
        let mut targets = Vec::new();
        for position in markers {
            let (target, marker_span) = match args.get(position) {
                Some(Argument::Marker(reference, marker_span)) => {
                    match scene.find_marker(reference) {
                        Ok(target) => (target, *marker_span),
                        Err(error) => {
                            self.errors.push(CompileError::Scene {
                                error,
                                span: *marker_span,
                            });
                            return self.constant(0.0);
                        }
                    }
                }
                _ => (Target::Ground, span),
            };
            if needs_accelerations
                && let Target::Marker(index) = target
                && let Some(body) = scene.markers[index].body.map(|body| &scene.bodies[body])
                && (body.acceleration.is_none() || body.angular_acceleration.is_none())
            {
                if let Some(reactions) = self.reactions {
                    return self.run_acceleration(reactions, function, args, span);
                }
                self.errors.push(CompileError::NoAcceleration {
                    place: scene.kind.noun(),
                    function: function.name(),
                    body: body.name.clone(),
                    span: marker_span,
                });
                return self.constant(0.0);
            }
            frames.push(self.frame(scene, target, marker_span));
            targets.push(target);
        }
        let selector = match function {
            Function::Incang => Selector::Normal(drawn_normal(scene, &targets)),
            _ => selector,
        };
        self.compute(
            Op::Measure {
                function,
                frames: frames.into(),
                selector,
            },
            span,
        )
    }

    /// A measure of accelerations as the input a running solver gives, when
    /// `reactions` accepts it; an error at the call when not.
    fn run_acceleration(
        &mut self,
        reactions: Reactions<'_>,
        function: Function,
        args: &[Argument],
        span: Span,
    ) -> Slot {
        let call = RunCall::Acceleration(MarkerCall::of(function, args));
        match reactions(&call) {
            Ok(()) => self.reaction(&call, span),
            Err(message) => {
                self.errors.push(CompileError::Reaction { message, span });
                self.constant(0.0)
            }
        }
    }

    /// The frame argument of a marker: its constants once per program, and
    /// its body's state inputs.
    fn frame(&mut self, scene: &Scene, target: Target, span: Span) -> FrameArg {
        let data = match self.frame_of.get(&target) {
            Some(&data) => data,
            None => {
                let data = match target {
                    Target::Ground => FrameData::ground(),
                    Target::Marker(index) => {
                        let marker = &scene.markers[index];
                        let body = marker.body.map(|body| &scene.bodies[body]);
                        FrameData {
                            label: marker.label(),
                            body: marker.body,
                            body_orientation: body
                                .map_or_else(nalgebra::Matrix3::identity, |body| {
                                    body.orientation.to_rotation_matrix().into_inner()
                                }),
                            offset: marker.position,
                            axes: marker.orientation.to_rotation_matrix().into_inner(),
                            acceleration: body
                                .map_or(Some(nalgebra::Vector3::zeros()), |body| body.acceleration),
                            angular_acceleration: body
                                .map_or(Some(nalgebra::Vector3::zeros()), |body| {
                                    body.angular_acceleration
                                }),
                        }
                    }
                };
                self.tables.frames.push(data);
                let index =
                    u32::try_from(self.tables.frames.len() - 1).expect("fewer than 2^32 frames");
                self.frame_of.insert(target, index);
                index
            }
        };
        let body = scene.body_of(&target);
        let state = body.map(|body| {
            StateComponent::ALL.map(|component| {
                let name = scene.state_name(body, component);
                let index = self
                    .input_index(&name)
                    .unwrap_or_else(|| self.inputs.push(name));
                self.input(index, span)
            })
        });
        FrameArg { data, state }
    }

    fn arithmetic_if(&mut self, branches: &[Node; 4], span: Span) -> Slot {
        let [condition, negative, zero, positive] = branches;
        let condition_slot = self.node(condition);
        if let Some(value) = self.constant_values[condition_slot as usize] {
            let chosen = if value < 0.0 {
                negative
            } else if value == 0.0 {
                zero
            } else {
                positive
            };
            return self.node(chosen);
        }
        let result = self.new_slot(None);
        let branch = self.emit(
            Instruction::Branch {
                condition: condition_slot,
                zero: 0,
                positive: 0,
            },
            span,
        );
        let mut starts = Vec::new();
        let mut jumps = Vec::new();
        for (index, node) in [negative, zero, positive].into_iter().enumerate() {
            starts.push(u32::try_from(self.code.len()).expect("fewer than 2^32 instructions"));
            self.memo.push(HashMap::new());
            self.variable_slots.push(HashMap::new());
            let value = self.node(node);
            self.variable_slots.pop();
            self.memo.pop();
            self.emit(
                Instruction::Copy {
                    dst: result,
                    src: value,
                },
                node.span,
            );
            if index < 2 {
                jumps.push(self.emit(Instruction::Jump { target: 0 }, span));
            }
        }
        let end = u32::try_from(self.code.len()).expect("fewer than 2^32 instructions");
        self.code[branch as usize] = Instruction::Branch {
            condition: condition_slot,
            zero: starts[1],
            positive: starts[2],
        };
        for jump in jumps {
            self.code[jump as usize] = Instruction::Jump { target: end };
        }
        result
    }
}

/// "scenes" or "models", as `scene` is one or made from one.
fn scene_plural(scene: &Scene) -> &'static str {
    match scene.kind {
        SceneKind::Scene => "scenes",
        SceneKind::Model => "models",
    }
}

/// The stops of a contact law from its arguments after `x` and `x'`, when
/// all are constants: `x1 k e cmax d` for IMPACT, `x1 x2 k e cmax d` for BISTOP.
fn constant_stops(arguments: &[Option<f64>]) -> Option<Stops> {
    let values: Vec<f64> = arguments.iter().copied().collect::<Option<_>>()?;
    let (lower, upper, parameters) = match values[..] {
        [x1, k, e, cmax, d] => (x1, None, [k, e, cmax, d]),
        [x1, x2, k, e, cmax, d] => (x1, Some(x2), [k, e, cmax, d]),
        _ => return None,
    };
    Some(Stops::new(lower, upper, parameters))
}

/// Entry `i` (from 1) of ARRAY `id`'s `entries` that `ARYVAL(id, i)` (or
/// `PINVAL`, `POUVAL`: `names` are the function and its statement) asks
/// for with `args`, or the error of an entry it does not have.
fn array_entry<'e, V>(
    names: (&'static str, &'static str),
    id: u64,
    entries: &'e [V],
    args: &[Argument],
    span: Span,
) -> Result<&'e V, CompileError> {
    Ok(&entries[entry_index(names, id, entries.len(), args, span)?])
}

/// The index (from 0) of the entry `i` that `ARYVAL(id, i)` asks for with
/// `args` of a list of `count`, or the error of an entry it does not have.
fn entry_index(
    (function, statement): (&'static str, &'static str),
    id: u64,
    count: usize,
    args: &[Argument],
    span: Span,
) -> Result<usize, CompileError> {
    let entry = match args.get(1) {
        Some(Argument::Flag(entry, _)) => *entry,
        _ => 0,
    };
    usize::try_from(entry)
        .ok()
        .and_then(|entry| entry.checked_sub(1))
        .filter(|index| *index < count)
        .ok_or(CompileError::ArrayEntry {
            function,
            statement,
            id,
            entry,
            count,
            span,
        })
}

/// The error for a model-data function: which statement would provide it
/// (missing from `scene` when there is one), that only a running solver has
/// its value, or that scenes do not evaluate it.
fn model_data_error(
    function: Function,
    args: &[Argument],
    span: Span,
    scene: Option<&Scene>,
) -> CompileError {
    let object = args.iter().find_map(|arg| match arg {
        Argument::Object(reference, _) => Some(reference),
        _ => None,
    });
    let id = object.map_or_else(String::new, Reference::to_string);
    if function == Function::Senval && scene.is_some() {
        // The model's sensors with an EVALUATE are bound; this one has none.
        return CompileError::MissingStatement {
            function: function.name(),
            statement: format!(
                "SENSOR/{id} with an EVALUATE (whose value at each trip SENVAL returns)"
            ),
            id,
            span,
        };
    }
    let solver_state = match function {
        Function::Dif | Function::Dif1 => Some("DIFF"),
        Function::Pinval => Some("PINPUT"),
        Function::Pouval => Some("POUTPUT"),
        Function::Senval => Some("SENSOR"),
        Function::Friction => Some("FRICTION"),
        _ => None,
    };
    if let Some(kind) = solver_state {
        return CompileError::NeedsSolverState {
            function: function.name(),
            statement: format!("{kind}/{id}"),
            id,
            span,
        };
    }
    let statement = match function {
        Function::Varval => format!("VARIABLE/{id}"),
        Function::Aryval if scene.is_some() => {
            format!("ARRAY/{id} of NUMBERS (or a U array of VARIABLES)")
        }
        Function::Aryval => format!("ARRAY/{id}"),
        Function::Curve => format!("CURVE/{id}"),
        Function::Interp => "a data table".to_string(),
        _ => format!("SPLINE/{id}"),
    };
    if let Some(scene) = scene {
        return match function {
            Function::Curve | Function::Interp => CompileError::NotInScene {
                place: scene_plural(scene),
                function: function.name(),
                span,
            },
            _ => CompileError::MissingStatement {
                function: function.name(),
                id,
                statement,
                span,
            },
        };
    }
    CompileError::NeedsModel {
        function: function.name(),
        id,
        statement,
        span,
    }
}

/// INCANG's axis: the unit normal of its lines `targets[1] -> targets[0]`
/// and `targets[2] -> targets[3]` where the scene places them (the angle is
/// positive there and measured about it after), as bits; zero where they
/// are parallel.
fn drawn_normal(scene: &Scene, targets: &[Target]) -> [u64; 3] {
    let origin = |position: usize| scene.origin(targets[position]);
    let across = (origin(0) - origin(1)).cross(&(origin(3) - origin(2)));
    let length = across.norm();
    let normal = if length > 0.0 && length.is_finite() {
        across / length
    } else {
        nalgebra::Vector3::zeros()
    };
    normal.map(f64::to_bits).into()
}
