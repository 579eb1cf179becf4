//! Stage 2, check: resolve every name of a syntax tree, count arguments,
//! sort them into values, markers, model objects and flags, and enforce the
//! rules of constant arguments — all before anything is evaluated.

mod error;
mod tree;

pub use error::{CheckError, ConstantFailure};
pub use tree::{Argument, Node, NodeKind, Reference};

use crate::catalog::{
    self, ArgKind, Constant, Family, Function, SystemVariable, check_rules_with, closest,
    did_you_mean,
};
use crate::errors::Errors;
use crate::ops::{Op, Slot, Tables, execute};
use crate::span::Span;
use crate::syntax::ast::{BinaryOp, Call, Expr, ExprKind, If, UnaryOp};

/// An expression that passed the checker.
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    /// The root of the checked tree.
    pub root: Node,
}

impl Checked {
    /// The names the context must bind, as first written, each once
    /// (case-insensitively), in order of first use.
    pub fn variables(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        visit(&self.root, &mut |node| {
            if let NodeKind::Variable(name) = &node.kind
                && seen.insert(name.to_ascii_uppercase())
            {
                names.push(name);
            }
        });
        names
    }

    /// The system variables the expression reads (`TIME`, `MODE`), each
    /// once, in order of first use.
    pub fn system_variables(&self) -> Vec<SystemVariable> {
        let mut read = Vec::new();
        visit(&self.root, &mut |node| {
            if let NodeKind::System(variable) = node.kind
                && !read.contains(&variable)
            {
                read.push(variable);
            }
        });
        read
    }

    /// Every use of a name the context must bind, with its place, in the
    /// order written.
    pub fn variable_uses(&self) -> Vec<(&str, Span)> {
        let mut uses = Vec::new();
        visit(&self.root, &mut |node| {
            if let NodeKind::Variable(name) = &node.kind {
                uses.push((name.as_str(), node.span));
            }
        });
        uses
    }

    /// The functions called, each once, in catalog order.
    pub fn functions(&self) -> Vec<Function> {
        let mut functions = Vec::new();
        visit(&self.root, &mut |node| {
            if let NodeKind::Call(function, _) = node.kind {
                functions.push(function);
            }
        });
        functions.sort();
        functions.dedup();
        functions
    }
}

/// Calls `f` on every node, parents before children.
pub fn visit<'a>(node: &'a Node, f: &mut impl FnMut(&'a Node)) {
    f(node);
    match &node.kind {
        NodeKind::Neg(operand) => visit(operand, f),
        NodeKind::Chain(first, rest) => {
            visit(first, f);
            rest.iter().for_each(|(_, operand)| visit(operand, f));
        }
        NodeKind::Power(base, exponent) => {
            visit(base, f);
            visit(exponent, f);
        }
        NodeKind::Call(_, args) => {
            for arg in args {
                if let Argument::Value(node) = arg {
                    visit(node, f);
                }
            }
        }
        NodeKind::If(branches) => branches.iter().for_each(|branch| visit(branch, f)),
        NodeKind::Number(_)
        | NodeKind::Constant(_)
        | NodeKind::System(_)
        | NodeKind::Variable(_) => {}
    }
}

/// Checks a syntax tree, reporting every problem found, in source order.
///
/// ```
/// let tree = mbexpr::parse("BISTOP(x, v, 5, -5, 1e5, 2.2, 100, 0.1)").unwrap();
/// let errors = mbexpr::check(&tree).unwrap_err();
/// assert_eq!(errors[0].to_string(), "BISTOP: x1 (5) must be less than x2 (-5)");
/// ```
pub fn check(expr: &Expr) -> Result<Checked, Errors<CheckError>> {
    let (checked, errors) = check_partial(expr);
    if errors.is_empty() {
        Ok(checked)
    } else {
        Err(Errors(errors))
    }
}

/// Checks a syntax tree and keeps the tree whatever it found: every problem,
/// in source order, and the checked tree with a placeholder (the number 0)
/// where a call could not be checked, so that a model's references can still
/// be verified in an expression that has other errors.
pub fn check_partial(expr: &Expr) -> (Checked, Vec<CheckError>) {
    let mut checker = Checker::default();
    let (root, _) = checker.expr(expr);
    let mut errors = checker.errors;
    errors.sort_by_key(|error| error.span().start);
    (Checked { root }, errors)
}

/// The state of one check: the problems found, the values of the constant
/// arguments of the calls being checked, and whether the node at hand may
/// never be evaluated.
#[derive(Default)]
struct Checker {
    errors: Vec<CheckError>,
    /// The value of each argument of the calls being checked that is a
    /// constant, innermost call last.
    arguments: Vec<Option<f64>>,
    /// How many IF branches the node at hand is inside that the condition
    /// does not surely choose: a constant that fails there is no error
    /// (SPEC 3.5: the other branches may hold a division by zero).
    unsure: usize,
}

impl Checker {
    /// Checks one node, returning it and its value when it is a constant;
    /// errors are collected and a placeholder returned so that the rest of
    /// the tree is still checked.
    fn expr(&mut self, expr: &Expr) -> (Node, Option<f64>) {
        let span = expr.span;
        let (kind, value) = match &expr.kind {
            ExprKind::Number(number) => (NodeKind::Number(number.value), Some(number.value)),
            ExprKind::Name(name) => {
                let kind = resolve_name(name, span, &mut self.errors);
                let value = match &kind {
                    NodeKind::Constant(constant) => Some(constant.value()),
                    _ => None,
                };
                (kind, value)
            }
            ExprKind::Unary(UnaryOp::Plus, operand) => return self.expr(operand),
            ExprKind::Unary(UnaryOp::Neg, operand) => {
                let (operand, value) = self.expr(operand);
                let value = value.and_then(|a| self.fold(Op::Neg(0), &[a], span));
                (NodeKind::Neg(Box::new(operand)), value)
            }
            ExprKind::Chain(first, rest) => self.chain(first, rest),
            ExprKind::Power(base, exponent) => {
                let (base, a) = self.expr(base);
                let (exponent, b) = self.expr(exponent);
                let value = match (a, b) {
                    (Some(a), Some(b)) => self.fold(Op::Pow(0, 1), &[a, b], span),
                    _ => None,
                };
                (NodeKind::Power(Box::new(base), Box::new(exponent)), value)
            }
            ExprKind::Call(call) => self.call(call, span),
            ExprKind::If(branches) => self.arithmetic_if(branches.as_ref()),
        };
        (Node { kind, span }, value)
    }

    /// A run of `+ -` or `* /`, folded from the left as the compiler folds
    /// it, each step with the span from the first operand to its own.
    fn chain(&mut self, first: &Expr, rest: &[(BinaryOp, Expr)]) -> (NodeKind, Option<f64>) {
        let (head, mut value) = self.expr(first);
        let mut operands = Vec::with_capacity(rest.len());
        for (op, operand) in rest {
            let (node, b) = self.expr(operand);
            value = match (value, b) {
                (Some(a), Some(b)) => {
                    self.fold(binary_op(*op), &[a, b], first.span.to(operand.span))
                }
                // A division by a constant 0 fails at every evaluation,
                // whatever it divides.
                (None, Some(b)) if *op == BinaryOp::Div && b == 0.0 => {
                    if self.unsure == 0 {
                        self.errors.push(CheckError::ConstantFails {
                            failure: ConstantFailure::DivisorZero,
                            span: first.span.to(operand.span),
                        });
                    }
                    None
                }
                _ => None,
            };
            operands.push((*op, node));
        }
        (NodeKind::Chain(Box::new(head), operands), value)
    }

    /// `IF(condition: negative, zero, positive)`: a constant condition
    /// chooses the one branch that will run, and gives its value.
    fn arithmetic_if(&mut self, branches: &If) -> (NodeKind, Option<f64>) {
        let If {
            condition,
            negative,
            zero,
            positive,
        } = branches;
        let (condition, chosen) = self.expr(condition);
        let chosen = chosen.map(|value| {
            if value < 0.0 {
                0
            } else if value == 0.0 {
                1
            } else {
                2
            }
        });
        let mut value = None;
        let checked: Vec<Node> = [negative, zero, positive]
            .into_iter()
            .enumerate()
            .map(|(index, branch)| {
                let sure = chosen == Some(index);
                self.unsure += usize::from(!sure);
                let (node, branch_value) = self.expr(branch);
                self.unsure -= usize::from(!sure);
                if sure {
                    value = branch_value;
                }
                node
            })
            .collect();
        let [negative, zero, positive]: [Node; 3] = checked.try_into().expect("three branches");
        (
            NodeKind::If(Box::new([condition, negative, zero, positive])),
            value,
        )
    }

    /// The value of `op` over the constants `values` (its slots `0, 1, ...`),
    /// computed as the compiler folds it: a domain error or an overflow is
    /// reported here, where a run would fail every time.
    fn fold(&mut self, op: Op, values: &[f64], span: Span) -> Option<f64> {
        let failure = match execute(&op, values, &Tables::default()) {
            Ok(value) if value.is_finite() => return Some(value),
            Ok(value) => ConstantFailure::NotFinite {
                operation: op.name(),
                value,
            },
            Err(error) => ConstantFailure::Law(error),
        };
        if self.unsure == 0 {
            self.errors
                .push(CheckError::ConstantFails { failure, span });
        }
        None
    }

    fn call(&mut self, call: &Call, span: Span) -> (NodeKind, Option<f64>) {
        let placeholder = (NodeKind::Number(0.0), None);
        let Some(function) = Function::lookup(&call.name) else {
            let what = if Constant::lookup(&call.name).is_some() {
                Some("a constant")
            } else {
                SystemVariable::lookup(&call.name).map(|_| "a system variable")
            };
            self.errors.push(match what {
                Some(what) => CheckError::NotAFunction {
                    name: call.name.as_str().to_uppercase(),
                    what,
                    span,
                },
                None => {
                    let known = Function::ALL.iter().map(|function| function.name());
                    CheckError::UnknownFunction {
                        name: call.name.to_string(),
                        suggestions: did_you_mean(&closest(&call.name, known)),
                        span: call.name_span,
                    }
                }
            });
            for arg in &call.args {
                self.expr(arg);
            }
            return placeholder;
        };
        let signature = function.signature();
        let count = call.args.len();
        if count < signature.min || count > signature.max {
            self.errors.push(CheckError::Arity {
                function: function.name().to_string(),
                expected: expected_count(signature.min, signature.max),
                found: match count {
                    1 => "1 was".to_string(),
                    n => format!("{n} were"),
                },
                usage: function.usage(),
                span,
            });
            return placeholder;
        }
        let base = self.arguments.len();
        let args: Vec<Argument> = call
            .args
            .iter()
            .enumerate()
            .map(|(position, arg)| {
                let (argument, value) = self.argument(function, position, arg);
                self.arguments.push(value);
                argument
            })
            .collect();
        let mut value = None;
        if function.family() != Family::User {
            let broken = self.constant_rules(function, &args, base);
            let foldable = matches!(
                function.family(),
                Family::Intrinsic | Family::Step | Family::Contact | Family::Series
            );
            if !broken
                && foldable
                && let Some(values) = self.arguments[base..]
                    .iter()
                    .copied()
                    .collect::<Option<Vec<f64>>>()
            {
                let slots = (0..values.len())
                    .map(|slot| Slot::try_from(slot).expect("fewer than 2^32 arguments"))
                    .collect();
                value = self.fold(
                    Op::Call {
                        function,
                        args: slots,
                        check_rules: false,
                    },
                    &values,
                    span,
                );
            }
        }
        self.arguments.truncate(base);
        (NodeKind::Call(function, args), value)
    }

    /// One argument, sorted by the kind the function expects there, and its
    /// value when it is a constant.
    fn argument(
        &mut self,
        function: Function,
        position: usize,
        arg: &Expr,
    ) -> (Argument, Option<f64>) {
        let span = arg.span;
        let param = || function.param_name(position);
        match function.signature().kind(position) {
            ArgKind::Value => {
                let (node, value) = self.expr(arg);
                (Argument::Value(node), value)
            }
            kind @ (ArgKind::Marker | ArgKind::Object) => {
                let Some(reference) = reference(arg) else {
                    let (function, param) = (function.name().to_string(), param());
                    self.errors.push(if kind == ArgKind::Marker {
                        CheckError::MarkerExpected {
                            function,
                            param,
                            span,
                        }
                    } else {
                        CheckError::ObjectExpected {
                            function,
                            param,
                            span,
                        }
                    });
                    // Kept as written: no later check reads a reference
                    // from it.
                    let (node, _) = self.expr(arg);
                    return (Argument::Value(node), None);
                };
                let argument = if kind == ArgKind::Marker {
                    Argument::Marker(reference, span)
                } else {
                    Argument::Object(reference, span)
                };
                (argument, None)
            }
            ArgKind::Flag => {
                let (node, value) = self.expr(arg);
                match value.filter(|v| v.fract() == 0.0 && v.abs() < 1e15) {
                    Some(flag) => (Argument::Flag(flag as i64, span), None),
                    None => {
                        self.errors.push(CheckError::FlagExpected {
                            function: function.name().to_string(),
                            param: param(),
                            span,
                        });
                        // Kept as written: no later check reads a number
                        // from it.
                        (Argument::Value(node), None)
                    }
                }
            }
        }
    }

    /// Reports the first broken rule among the arguments that are constants
    /// (their values from `base` on in [`Checker::arguments`]); whether one is.
    fn constant_rules(&mut self, function: Function, args: &[Argument], base: usize) -> bool {
        let values = &self.arguments[base..];
        let Err(violation) =
            check_rules_with(function, |position| values.get(position).copied().flatten())
        else {
            return false;
        };
        let span = violation
            .rule
            .positions()
            .into_iter()
            .map(|position| args[position].span())
            .reduce(Span::to)
            .unwrap_or_default();
        self.errors.push(CheckError::RuleBroken { violation, span });
        true
    }
}

/// The op of a binary operator, over slots 0 and 1.
fn binary_op(op: BinaryOp) -> Op {
    match op {
        BinaryOp::Add => Op::Add(0, 1),
        BinaryOp::Sub => Op::Sub(0, 1),
        BinaryOp::Mul => Op::Mul(0, 1),
        BinaryOp::Div => Op::Div(0, 1),
    }
}

fn resolve_name(name: &str, span: Span, errors: &mut Vec<CheckError>) -> NodeKind {
    if let Some(constant) = Constant::lookup(name) {
        return NodeKind::Constant(constant);
    }
    if let Some(variable) = SystemVariable::lookup(name) {
        return NodeKind::System(variable);
    }
    if let Some(function) = Function::lookup(name) {
        errors.push(CheckError::FunctionWithoutCall {
            name: function.name().to_string(),
            usage: function.usage(),
            span,
        });
    }
    NodeKind::Variable(name.into())
}

fn expected_count(min: usize, max: usize) -> String {
    match (min, max) {
        (1, 1) => "1 argument".to_string(),
        (min, max) if min == max => format!("{min} arguments"),
        (min, catalog::MANY) => format!("{min} or more arguments"),
        (min, max) => format!("{min} to {max} arguments"),
    }
}

/// An id (a plain whole-number literal, leading zeros allowed) or a name.
fn reference(arg: &Expr) -> Option<Reference> {
    match &arg.kind {
        ExprKind::Number(number) if number.is_integer_literal() => {
            number.text.parse().ok().map(Reference::Id)
        }
        ExprKind::Name(name) if Constant::lookup(name).is_none() => {
            Some(Reference::Name(name.to_string()))
        }
        _ => None,
    }
}

/// The value of a node made only of numbers, constants and arithmetic.
pub fn constant_value(node: &Node) -> Option<f64> {
    let value = match &node.kind {
        NodeKind::Number(value) => *value,
        NodeKind::Constant(constant) => constant.value(),
        NodeKind::Neg(operand) => -constant_value(operand)?,
        NodeKind::Chain(first, rest) => {
            rest.iter()
                .try_fold(constant_value(first)?, |a, (op, operand)| {
                    let b = constant_value(operand)?;
                    Some(match op {
                        BinaryOp::Add => a + b,
                        BinaryOp::Sub => a - b,
                        BinaryOp::Mul => a * b,
                        BinaryOp::Div => a / b,
                    })
                })?
        }
        NodeKind::Power(base, exponent) => constant_value(base)?.powf(constant_value(exponent)?),
        _ => return None,
    };
    value.is_finite().then_some(value)
}
