//! The checked tree: names resolved to enums, arguments sorted into values,
//! markers, model objects and flags.

use std::fmt;

use compact_str::CompactString;

use crate::Shown;
use crate::catalog::{Constant, Function, SystemVariable};
use crate::span::Span;
use crate::syntax::ast::{BinaryOp, write_chain};

/// A checked expression node.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// What the node computes.
    pub kind: NodeKind,
    /// Where it was written.
    pub span: Span,
}

/// The kinds of checked node.
#[derive(Clone, Debug, PartialEq)]
pub enum NodeKind {
    /// A number (degrees already converted).
    Number(f64),
    /// `PI`, `DTOR`, `RTOD`.
    Constant(Constant),
    /// `TIME`, `MODE`.
    System(SystemVariable),
    /// A name the context must bind (a user variable, an Adams View measure),
    /// held inline up to 24 bytes (a call of 25 million names is checked).
    Variable(CompactString),
    /// `-a` (a unary `+` leaves no node).
    Neg(Box<Node>),
    /// A left-associative run of `+ -` or of `* /` (see
    /// [`ExprKind::Chain`](crate::syntax::ast::ExprKind::Chain)).
    Chain(Box<Node>, Vec<(BinaryOp, Node)>),
    /// `base ** exponent`.
    Power(Box<Node>, Box<Node>),
    /// A call of a known function.
    Call(Function, Vec<Argument>),
    /// `IF(condition: negative, zero, positive)`, in that order.
    If(Box<[Node; 4]>),
}

/// One argument of a call, sorted by what the function expects there.
#[derive(Clone, Debug, PartialEq)]
pub enum Argument {
    /// An expression.
    Value(Node),
    /// A marker reference.
    Marker(Reference, Span),
    /// A model statement reference (`VARVAL(3)`, `SFORCE(.m.sf, ...)`).
    Object(Reference, Span),
    /// A constant whole number.
    Flag(i64, Span),
}

impl Argument {
    /// Where the argument was written.
    pub fn span(&self) -> Span {
        match self {
            Argument::Value(node) => node.span,
            Argument::Marker(_, span) | Argument::Object(_, span) | Argument::Flag(_, span) => {
                *span
            }
        }
    }
}

/// A reference to a marker or model statement.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Reference {
    /// A numeric id; as a marker, `0` is the ground frame.
    Id(u64),
    /// A name, as written (case is not significant).
    Name(String),
}

impl fmt::Display for Reference {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Reference::Id(id) => write!(f, "{id}"),
            Reference::Name(name) => f.write_str(name),
        }
    }
}

/// S-expression like the syntax tree's, with canonical names.
impl fmt::Display for Node {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            NodeKind::Number(value) => write!(f, "{}", Shown(*value)),
            NodeKind::Constant(constant) => f.write_str(constant.name()),
            NodeKind::System(variable) => f.write_str(variable.name()),
            NodeKind::Variable(name) => write!(f, "${name}"),
            NodeKind::Neg(operand) => write!(f, "(neg {operand})"),
            NodeKind::Chain(first, rest) => write_chain(f, first, rest),
            NodeKind::Power(base, exponent) => write!(f, "(** {base} {exponent})"),
            NodeKind::Call(function, args) => {
                write!(f, "({function}")?;
                for arg in args {
                    match arg {
                        Argument::Value(node) => write!(f, " {node}")?,
                        Argument::Marker(reference, _) => write!(f, " @{reference}")?,
                        Argument::Object(reference, _) => write!(f, " #{reference}")?,
                        Argument::Flag(flag, _) => write!(f, " {flag}")?,
                    }
                }
                f.write_str(")")
            }
            NodeKind::If(branches) => {
                let [condition, negative, zero, positive] = branches.as_ref();
                write!(f, "(IF {condition} : {negative} {zero} {positive})")
            }
        }
    }
}
