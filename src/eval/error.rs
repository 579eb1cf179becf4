//! What can go wrong while evaluating.

use thiserror::Error;

use crate::Shown;
use crate::laws::LawError;
use crate::span::Span;

/// An evaluation failure: a domain error, a broken argument rule, or a value
/// or derivative that is not a finite number. Evaluation never returns NaN
/// or an infinity.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum EvalError {
    /// A function or operator outside its domain, or a broken argument rule.
    #[error("{error}")]
    Law {
        /// What is wrong.
        error: LawError,
        /// The call or operation.
        span: Span,
    },
    /// The value of an operation is not a finite number (an overflow).
    #[error("{operation} gives {}: the value is beyond the range of a double", Shown(*value))]
    NotFinite {
        /// The function or operator.
        operation: String,
        /// The value computed.
        value: f64,
        /// The operation.
        span: Span,
    },
    /// A derivative of an operation is not a finite number.
    #[error(
        "a derivative of {operation} is not a finite number here (the function is not differentiable at this point, or its slope passes the range of a double)"
    )]
    DerivativeNotFinite {
        /// The function or operator.
        operation: String,
        /// The operation.
        span: Span,
    },
    /// An input value that is NaN or infinite.
    #[error("the value of {name} is not a finite number ({})", Shown(*value))]
    InputNotFinite {
        /// The input's name.
        name: String,
        /// The value given.
        value: f64,
        /// Where the input is first used.
        span: Span,
    },
    /// The caller passed the wrong number of input values (a programming error).
    #[error("{} were given for {}", crate::Counted(*found, "input value"), crate::Counted(*expected, "input"))]
    InputCount {
        /// The number of inputs the program was compiled for.
        expected: usize,
        /// The number of values given.
        found: usize,
    },
    /// A derivative direction that is not an input, or is named twice (a programming error).
    #[error("derivative direction {direction}: {reason}")]
    BadDirection {
        /// The input index given.
        direction: usize,
        /// What is wrong with it.
        reason: String,
    },
}

impl EvalError {
    /// The place in the text the error speaks of (empty for the programming errors).
    pub fn span(&self) -> Span {
        match self {
            EvalError::Law { span, .. }
            | EvalError::NotFinite { span, .. }
            | EvalError::DerivativeNotFinite { span, .. }
            | EvalError::InputNotFinite { span, .. } => *span,
            EvalError::InputCount { .. } | EvalError::BadDirection { .. } => Span::default(),
        }
    }
}
