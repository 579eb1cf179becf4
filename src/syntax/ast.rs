//! The syntax tree: owned, spanned, and exactly what was written.
//!
//! Names are kept as text; what a name means (a function, a constant, a
//! marker, a variable) is decided by [`crate::check()`].

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
    /// A left-associative run of operators of one precedence level, `+ -`
    /// or `* /`: `a - b + c` is `a` followed by `[(-, b), (+, c)]` and means
    /// `(a - b) + c`. A run of any length is one node, so a flat sum of
    /// thousands of terms nests no deeper than `a + b`.
    Chain(Box<Expr>, Vec<(BinaryOp, Expr)>),
    /// `base ** exponent`; right-associative, so `a**b**c` nests.
    Power(Box<Expr>, Box<Expr>),
    /// A function call `NAME(arg, ...)` (never `IF`), boxed so that a
    /// node is no larger than a number's.
    Call(Box<Call>),
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

/// The left-associative binary operators (a power is [`ExprKind::Power`]).
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
}

impl BinaryOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
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
            ExprKind::Chain(first, rest) => write_chain(f, first, rest),
            ExprKind::Power(base, exponent) => write!(f, "(** {base} {exponent})"),
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

/// A chain as the binary operations it folds to, `(+ (- a b) c)`, written
/// without recursion along the chain.
pub(crate) fn write_chain<T: fmt::Display>(
    f: &mut fmt::Formatter<'_>,
    first: &impl fmt::Display,
    rest: &[(BinaryOp, T)],
) -> fmt::Result {
    for (op, _) in rest.iter().rev() {
        write!(f, "({} ", op.symbol())?;
    }
    write!(f, "{first}")?;
    for (_, operand) in rest {
        write!(f, " {operand})")?;
    }
    Ok(())
}
