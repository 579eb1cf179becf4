//! What the checker refuses.

use thiserror::Error;

use crate::Shown;
use crate::catalog::RuleViolation;
use crate::laws::LawError;
use crate::span::Span;

/// A name, arity or argument problem found before any evaluation.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CheckError {
    /// A call of a name that is no function of the language.
    #[error("unknown function {name}{suggestions}")]
    UnknownFunction {
        /// The name as written.
        name: String,
        /// " (did you mean STEP?)" or nothing.
        suggestions: String,
        /// The name.
        span: Span,
    },
    /// A constant or system variable written as a call.
    #[error("{name} is {what}, not a function: write it without parentheses")]
    NotAFunction {
        /// The canonical name.
        name: String,
        /// "a constant" or "a system variable".
        what: &'static str,
        /// The call.
        span: Span,
    },
    /// A function name used as a value.
    #[error("{name} is a function: call it with its arguments, {usage}")]
    FunctionWithoutCall {
        /// The canonical name.
        name: String,
        /// `STEP(x, x0, h0, x1, h1)`.
        usage: String,
        /// The name.
        span: Span,
    },
    /// The wrong number of arguments.
    #[error("{function} takes {expected}, but {found} given: {usage}")]
    Arity {
        /// The canonical name.
        function: String,
        /// "5 arguments", "1 to 3 arguments", "2 or more arguments".
        expected: String,
        /// "6 were", "1 was".
        found: String,
        /// `STEP(x, x0, h0, x1, h1)`.
        usage: String,
        /// The call.
        span: Span,
    },
    /// An argument that must be a marker is something else.
    #[error("{param} of {function} is a marker: write its id (0 for ground) or its name")]
    MarkerExpected {
        /// The canonical name.
        function: String,
        /// The parameter name.
        param: String,
        /// The argument.
        span: Span,
    },
    /// An argument that must name a model statement is something else.
    #[error("{param} of {function} names a model statement: write its id or its name")]
    ObjectExpected {
        /// The canonical name.
        function: String,
        /// The parameter name.
        param: String,
        /// The argument.
        span: Span,
    },
    /// An argument that must be a whole-number constant is something else.
    #[error("{param} of {function} must be a whole number written as a constant")]
    FlagExpected {
        /// The canonical name.
        function: String,
        /// The parameter name.
        param: String,
        /// The argument.
        span: Span,
    },
    /// A part made of constants that fails whenever it is evaluated: a
    /// domain error (`LOG(0)`, `1/0`) or an overflow, as evaluation says it.
    #[error("{failure}")]
    ConstantFails {
        /// What evaluation would report.
        failure: ConstantFailure,
        /// The failing operation.
        span: Span,
    },
    /// Constant arguments that break a rule of the function (SPEC 3.3).
    #[error("{violation}")]
    RuleBroken {
        /// The rule and the values.
        violation: RuleViolation,
        /// The offending argument(s).
        span: Span,
    },
}

impl CheckError {
    /// The place in the text the error speaks of.
    pub fn span(&self) -> Span {
        match self {
            CheckError::UnknownFunction { span, .. }
            | CheckError::NotAFunction { span, .. }
            | CheckError::FunctionWithoutCall { span, .. }
            | CheckError::Arity { span, .. }
            | CheckError::MarkerExpected { span, .. }
            | CheckError::ObjectExpected { span, .. }
            | CheckError::FlagExpected { span, .. }
            | CheckError::RuleBroken { span, .. }
            | CheckError::ConstantFails { span, .. } => *span,
        }
    }
}

/// Why an operation on constants fails, in the words evaluation uses for
/// the same failure at run time.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ConstantFailure {
    /// A function or operator outside its domain, or a broken argument rule.
    #[error("{0}")]
    Law(LawError),
    /// A division whose divisor is a constant 0.
    #[error("`/` divides by a constant 0, which fails at every evaluation")]
    DivisorZero,
    /// The value is not a finite number (an overflow).
    #[error("{operation} gives {}: the value is beyond the range of a double", Shown(*value))]
    NotFinite {
        /// The function or operator.
        operation: String,
        /// The value computed.
        value: f64,
    },
}
