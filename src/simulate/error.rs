//! Why a model cannot be simulated, or why a run stops.

use thiserror::Error;

use crate::Shown;
use crate::compile::CompileError;
use crate::eval::EvalError;
use crate::span::Span;

/// Where a problem is: a place in the model's file, or in one of its
/// expressions (which [`crate::simulate::Expression::file_span`] takes to
/// the file).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// A span of the model's file.
    File(Span),
    /// A span of the text of expression `expression` of the model.
    Expression {
        /// An index into [`crate::simulate::Model::expressions`].
        expression: usize,
        /// The span in that expression's text.
        span: Span,
    },
    /// Nowhere in the file (a setting given on the command line).
    None,
}

/// Why a model cannot be simulated, or why a run stops.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SimulateError {
    /// A statement that needs a constraint solver.
    #[error(
        "not simulated: {statement} is a constraint mbexpr does not hold yet (it simulates JOINTs: FIXED, REVOLUTE, TRANSLATIONAL, SPHERICAL, CYLINDRICAL, PLANAR, and MOTIONs on them)"
    )]
    Constraint {
        /// `JOINT/3`.
        statement: String,
        /// The statement.
        span: Span,
    },
    /// A statement the simulator does not integrate.
    #[error("not simulated: {statement} {reason}")]
    Unsupported {
        /// `BUSHING/4`.
        statement: String,
        /// Why, and what is simulated instead.
        reason: String,
        /// The statement.
        span: Span,
    },
    /// Data the simulation needs that is missing or wrong: a mass that is
    /// not positive, a singular inertia, a marker that does not exist.
    #[error("{message}")]
    Model {
        /// What is wrong and what to do.
        message: String,
        /// Where.
        span: Span,
    },
    /// An expression that reads what mbexpr's simulator does not compute
    /// (an element's or a joint's force, a user subroutine, a sensor).
    #[error(
        "not simulated: {error} (mbexpr's simulator computes the DIFFs, the parts' states and the expressions of its force elements)"
    )]
    Unavailable {
        /// An index into [`crate::simulate::Model::expressions`].
        expression: usize,
        /// What it reads, with its span in the expression.
        error: CompileError,
    },
    /// An expression that does not compile for a simulation.
    #[error("{error}")]
    Compile {
        /// An index into [`crate::simulate::Model::expressions`].
        expression: usize,
        /// What is wrong, with its span in the expression.
        error: CompileError,
    },
    /// Settings that cannot make a run (an end time that is not positive,
    /// no output step, a tolerance out of range).
    #[error("{message}")]
    Settings {
        /// What is wrong.
        message: String,
        /// Where the file gives the setting, if it does.
        span: Option<Span>,
    },
    /// An expression cannot be evaluated at an accepted state.
    #[error("the run stops at t = {}: {error}", Shown(*time))]
    Evaluation {
        /// The time of the state.
        time: f64,
        /// The expression, an index into [`crate::simulate::Model::expressions`].
        expression: usize,
        /// What went wrong, with its span in the expression.
        error: EvalError,
    },
    /// The integrator cannot go on (its step size fell below the smallest
    /// it takes, or the step budget is spent).
    #[error("the run stops at t = {}: {message}", Shown(*time))]
    Integration {
        /// The time of the last accepted state.
        time: f64,
        /// Why, in words.
        message: String,
        /// The expression whose evaluation failed at the last trial state,
        /// when that was the cause, and its span there.
        cause: Option<(usize, Span)>,
    },
    /// A piecewise function switches branch over and over in a vanishing
    /// interval (a sliding contact, a force that balances on a kink).
    #[error(
        "the run stops at t = {}: {function} switches branch {count} times within {} s (chattering); loosen the model at this kink (a damping ramp, a smooth STEP) or end the run before it",
        Shown(*time),
        Shown(*window)
    )]
    Chattering {
        /// The time of the last switch.
        time: f64,
        /// The function that switches.
        function: String,
        /// How many switches.
        count: usize,
        /// Over how long.
        window: f64,
        /// The expression it is in.
        expression: usize,
        /// Its span there.
        span: Span,
    },
}

impl SimulateError {
    /// Where the problem is.
    pub fn place(&self) -> Place {
        match self {
            SimulateError::Constraint { span, .. }
            | SimulateError::Unsupported { span, .. }
            | SimulateError::Model { span, .. } => Place::File(*span),
            SimulateError::Settings { span, .. } => span.map_or(Place::None, Place::File),
            SimulateError::Compile { expression, error }
            | SimulateError::Unavailable { expression, error } => Place::Expression {
                expression: *expression,
                span: error.span(),
            },
            SimulateError::Evaluation {
                expression, error, ..
            } => Place::Expression {
                expression: *expression,
                span: error.span(),
            },
            SimulateError::Integration { cause, .. } => {
                cause.map_or(Place::None, |(expression, span)| Place::Expression {
                    expression,
                    span,
                })
            }
            SimulateError::Chattering {
                expression, span, ..
            } => Place::Expression {
                expression: *expression,
                span: *span,
            },
        }
    }
}
