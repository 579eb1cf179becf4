//! The syntax tree: owned, spanned, and exactly what was written.
//!
//! Names are kept as text; what a name means (a function, a constant, a
//! marker, a variable) is decided by [`crate::check`].

use std::fmt;

use compact_str::CompactString;

use crate::span::Span;

/// An expression node with the byte span of its text.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What the node is.
    pub kind: ExprKind,
    /// Where it was written.
    pub span: Span,
}

/// The kinds of expression node.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// A number literal.
    Number(Number),
    /// A name: constant, variable, marker or object path, as written.
    Name(CompactString),
    /// A unary sign applied to an operand.
    Unary(UnaryOp, Box<Expr>),
    /// A binary operator applied to two operands.
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    /// A function call `NAME(arg, ...)` (never `IF`).
    Call(Call),
    /// The arithmetic `IF(condition: negative, zero, positive)`.
    If(Box<If>),
}

/// A number literal: its value and the text it was written as.
#[derive(Clone, Debug, PartialEq)]
pub struct Number {
    /// The value, already multiplied by pi/180 when written with the degree suffix.
    pub value: f64,
    /// The literal exactly as written (`1E+07`, `90D`, `.5`).
    pub text: CompactString,
}

impl Number {
    /// Whether the literal is a plain integer (`12`, `0201`), which can name an id.
    pub fn is_integer_literal(&self) -> bool {
        self.text.bytes().all(|byte| byte.is_ascii_digit())
    }
}

/// `NAME(arg, ...)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    /// The function name as written.
    pub name: CompactString,
    /// Where the name was written.
    pub name_span: Span,
    /// The arguments in order.
    pub args: Vec<Expr>,
}

/// The arithmetic IF: `negative` when `condition < 0`, `zero` when it is 0,
/// `positive` when it is greater.
#[derive(Clone, Debug, PartialEq)]
pub struct If {
    /// The expression whose sign chooses the branch.
    pub condition: Expr,
    /// The value when the condition is negative.
    pub negative: Expr,
    /// The value when the condition is zero.
    pub zero: Expr,
    /// The value when the condition is positive.
    pub positive: Expr,
}

/// Unary signs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    /// `-a`
    Neg,
    /// `+a`
    Plus,
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinaryOp {
    /// `a + b`
    Add,
    /// `a - b`
    Sub,
    /// `a * b`
    Mul,
    /// `a / b`
    Div,
    /// `a ** b`
    Pow,
}

impl BinaryOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Pow => "**",
        }
    }
}

/// A compact S-expression: `(+ 1 (* x (neg y)))`, calls as `(STEP x 0 0 1 1)`,
/// the arithmetic IF as `(IF c : n z p)`. Numbers and names print as written.
impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            ExprKind::Number(number) => f.write_str(&number.text),
            ExprKind::Name(name) => f.write_str(name),
            ExprKind::Unary(UnaryOp::Neg, operand) => write!(f, "(neg {operand})"),
            ExprKind::Unary(UnaryOp::Plus, operand) => write!(f, "(plus {operand})"),
            ExprKind::Binary(op, lhs, rhs) => write!(f, "({} {lhs} {rhs})", op.symbol()),
            ExprKind::Call(call) => {
                write!(f, "({}", call.name)?;
                for arg in &call.args {
                    write!(f, " {arg}")?;
                }
                f.write_str(")")
            }
            ExprKind::If(branches) => {
                let If {
                    condition,
                    negative,
                    zero,
                    positive,
                } = branches.as_ref();
                write!(f, "(IF {condition} : {negative} {zero} {positive})")
            }
        }
    }
}
