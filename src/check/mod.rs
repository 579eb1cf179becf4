//! Stage 2, check: resolve every name of a syntax tree, count arguments,
//! sort them into values, markers, model objects and flags, and enforce the
//! rules of constant arguments — all before anything is evaluated.

mod error;
mod tree;

pub use error::CheckError;
pub use tree::{Argument, Node, NodeKind, Reference};

use crate::catalog::{
    self, ArgKind, Constant, Family, Function, SystemVariable, check_rules_with, closest,
    did_you_mean,
};
use crate::errors::Errors;
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
        visit(&self.root, &mut |node| {
            if let NodeKind::Variable(name) = &node.kind
                && !names.iter().any(|seen| seen.eq_ignore_ascii_case(name))
            {
                names.push(name);
            }
        });
        names
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
    let mut errors = Vec::new();
    let root = check_expr(expr, &mut errors);
    if errors.is_empty() {
        Ok(Checked { root })
    } else {
        errors.sort_by_key(|error| error.span().start);
        Err(Errors(errors))
    }
}

/// Checks one node; errors are collected and a placeholder node returned so
/// that the rest of the tree is still checked.
fn check_expr(expr: &Expr, errors: &mut Vec<CheckError>) -> Node {
    let span = expr.span;
    let kind = match &expr.kind {
        ExprKind::Number(number) => NodeKind::Number(number.value),
        ExprKind::Name(name) => resolve_name(name, span, errors),
        ExprKind::Unary(UnaryOp::Plus, operand) => return check_expr(operand, errors),
        ExprKind::Unary(UnaryOp::Neg, operand) => {
            NodeKind::Neg(Box::new(check_expr(operand, errors)))
        }
        ExprKind::Chain(first, rest) => NodeKind::Chain(
            Box::new(check_expr(first, errors)),
            rest.iter()
                .map(|(op, operand)| (*op, check_expr(operand, errors)))
                .collect(),
        ),
        ExprKind::Power(base, exponent) => NodeKind::Power(
            Box::new(check_expr(base, errors)),
            Box::new(check_expr(exponent, errors)),
        ),
        ExprKind::Call(call) => check_call(call, span, errors),
        ExprKind::If(branches) => {
            let If {
                condition,
                negative,
                zero,
                positive,
            } = branches.as_ref();
            NodeKind::If(Box::new(
                [condition, negative, zero, positive].map(|branch| check_expr(branch, errors)),
            ))
        }
    };
    Node { kind, span }
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
    NodeKind::Variable(name.to_string())
}

fn check_call(call: &Call, span: Span, errors: &mut Vec<CheckError>) -> NodeKind {
    let placeholder = NodeKind::Number(0.0);
    let Some(function) = Function::lookup(&call.name) else {
        let what = if Constant::lookup(&call.name).is_some() {
            Some("a constant")
        } else {
            SystemVariable::lookup(&call.name).map(|_| "a system variable")
        };
        errors.push(match what {
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
            check_expr(arg, errors);
        }
        return placeholder;
    };
    let signature = function.signature();
    let count = call.args.len();
    if count < signature.min || count > signature.max {
        errors.push(CheckError::Arity {
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
    let args: Vec<Argument> = call
        .args
        .iter()
        .enumerate()
        .map(|(position, arg)| check_argument(function, position, arg, errors))
        .collect();
    if function.family() != Family::User {
        check_constant_rules(function, &args, errors);
    }
    NodeKind::Call(function, args)
}

fn expected_count(min: usize, max: usize) -> String {
    match (min, max) {
        (1, 1) => "1 argument".to_string(),
        (min, max) if min == max => format!("{min} arguments"),
        (min, catalog::MANY) => format!("{min} or more arguments"),
        (min, max) => format!("{min} to {max} arguments"),
    }
}

fn check_argument(
    function: Function,
    position: usize,
    arg: &Expr,
    errors: &mut Vec<CheckError>,
) -> Argument {
    let span = arg.span;
    let param = || function.param_name(position);
    match function.signature().kind(position) {
        ArgKind::Value => Argument::Value(check_expr(arg, errors)),
        kind @ (ArgKind::Marker | ArgKind::Object) => {
            let reference = reference(arg).unwrap_or_else(|| {
                let (function, param) = (function.name().to_string(), param());
                errors.push(if kind == ArgKind::Marker {
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
                Reference::Id(0)
            });
            if kind == ArgKind::Marker {
                Argument::Marker(reference, span)
            } else {
                Argument::Object(reference, span)
            }
        }
        ArgKind::Flag => {
            let value = constant_value(&check_expr(arg, errors));
            match value.filter(|v| v.fract() == 0.0 && v.abs() < 1e15) {
                Some(flag) => Argument::Flag(flag as i64, span),
                None => {
                    errors.push(CheckError::FlagExpected {
                        function: function.name().to_string(),
                        param: param(),
                        span,
                    });
                    Argument::Flag(0, span)
                }
            }
        }
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

/// Reports the first broken rule among the arguments that are constants.
fn check_constant_rules(function: Function, args: &[Argument], errors: &mut Vec<CheckError>) {
    // Only the arguments a rule names are looked at (most functions have none).
    let value = |position: usize| match args.get(position) {
        Some(Argument::Value(node)) => constant_value(node),
        _ => None,
    };
    if let Err(violation) = check_rules_with(function, value) {
        let span = violation
            .rule
            .positions()
            .into_iter()
            .map(|position| args[position].span())
            .reduce(Span::to)
            .unwrap_or_default();
        errors.push(CheckError::RuleBroken { violation, span });
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
