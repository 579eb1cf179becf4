//! Why a model cannot be simulated, or why a run stops.

use std::collections::HashSet;

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

impl Place {
    /// The span of the model's file this place is at (`None`: nowhere).
    pub fn file_span(self, model: &crate::simulate::Model) -> Option<Span> {
        match self {
            Place::File(span) => Some(span),
            Place::Expression { expression, span } => model
                .expressions
                .get(expression)
                .map(|expression| expression.file_span(span)),
            Place::None => None,
        }
    }
}

/// Why a model cannot be simulated, or why a run stops.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SimulateError {
    /// A statement that needs a constraint solver.
    #[error(
        "not simulated: {statement} is a constraint mbexpr does not hold yet (it holds JOINTs of every type, JPRIMs, PTCVs, CVCVs, COUPLERs, GEARs, GCONs on places, and MOTIONs on joints and between markers)"
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
    /// A `FUNCTION = USER(...)`: the user subroutine an Adams solver
    /// would call for the statement, which mbexpr does not have.
    #[error(
        "not simulated: USER(...) calls {subroutine}, the user subroutine an Adams solver loads for {statement} from the user's library, which mbexpr cannot call: write the function as an expression"
    )]
    UserSubroutine {
        /// An index into [`crate::simulate::Model::expressions`].
        expression: usize,
        /// `GFOSUB`.
        subroutine: &'static str,
        /// The statement's kind, `GFORCE`.
        statement: String,
        /// The `USER(...)` call in the expression.
        span: Span,
    },
    /// Statements refused for the same reason as `first`, of its kind:
    /// one error for them all, placed at the first.
    #[error("{first}; so are {} ({} in all)", listed(others), others.len() + 1)]
    Grouped {
        /// The first statement's refusal.
        first: Box<SimulateError>,
        /// The labels of the others (`JOINT/4`), in file order.
        others: Vec<String>,
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
        /// What caused it, where that is known: the expression whose
        /// evaluation failed at the last trial state, or the statement
        /// whose equations cannot be met.
        place: Place,
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
        /// Where it is written.
        place: Place,
    },
}

/// `labels` as a sentence: all of them up to eight, else the first six and
/// how many more.
fn listed(labels: &[String]) -> String {
    const SHOWN: usize = 6;
    if labels.len() <= SHOWN + 2 {
        return labels.join(", ");
    }
    format!(
        "{} and {} more",
        labels[..SHOWN].join(", "),
        labels.len() - SHOWN
    )
}

/// The user subroutine an Adams solver calls for a `FUNCTION = USER(...)`
/// of a statement of `kind` (MotionSolve names the same ones).
fn user_subroutine(kind: &str) -> &'static str {
    const SUBROUTINES: [(&str, &str); 16] = [
        ("SFORCE", "SFOSUB"),
        ("VFORCE", "VFOSUB"),
        ("VTORQUE", "VTOSUB"),
        ("GFORCE", "GFOSUB"),
        ("VARIABLE", "VARSUB"),
        ("DIFF", "DIFSUB"),
        ("MOTION", "MOTSUB"),
        ("REQUEST", "REQSUB"),
        ("SENSOR", "SENSUB"),
        ("GCON", "GCOSUB"),
        ("UCON", "UCOSUB"),
        ("COUPLER", "COUSUB"),
        ("FIELD", "FIESUB"),
        ("CURVE", "CURSUB"),
        ("SURFACE", "SURSUB"),
        ("MFORCE", "MFOSUB"),
    ];
    SUBROUTINES
        .iter()
        .find(|(statement, _)| crate::model::is_kind(kind, statement))
        .map_or("a user subroutine", |(_, subroutine)| subroutine)
}

impl SimulateError {
    /// The error of expression `expression` (labelled `STATEMENT/ID
    /// KEYWORD`) whose compilation fails with `error`.
    pub(crate) fn of_expression(
        expression: usize,
        label: &str,
        error: CompileError,
    ) -> SimulateError {
        if let CompileError::UserSubroutine { span } = error {
            let statement = label
                .split(['/', ' '])
                .next()
                .unwrap_or(label)
                .to_ascii_uppercase();
            return SimulateError::UserSubroutine {
                expression,
                subroutine: user_subroutine(&statement),
                statement,
                span,
            };
        }
        if error.is_unavailable() {
            SimulateError::Unavailable { expression, error }
        } else {
            SimulateError::Compile { expression, error }
        }
    }

    /// `errors` with the refusals of statements of one kind for one reason
    /// made one [`SimulateError::Grouped`] at the first, in file order
    /// (those placed in the file first).
    pub(crate) fn grouped(errors: Vec<SimulateError>) -> Vec<SimulateError> {
        // Each kept error, the others of its group in file order, and
        // their labels as a set (a file of 60 000 refusals of one kind).
        type Group = (SimulateError, Vec<String>, HashSet<String>);
        let mut kept: Vec<Group> = Vec::new();
        for error in errors {
            let Some((kind, label)) = error.refused_statement() else {
                kept.push((error, Vec::new(), HashSet::new()));
                continue;
            };
            let same = |(first, _, _): &&mut Group| {
                first
                    .refused_statement()
                    .is_some_and(|(first_kind, _)| first_kind == kind)
                    && std::mem::discriminant(first) == std::mem::discriminant(&error)
                    && first.reason() == error.reason()
            };
            match kept.iter_mut().find(same) {
                // One statement refused again for the same reason (a
                // CURVE for each PTCV on it) is named once.
                Some((first, others, named)) => {
                    let again = first
                        .refused_statement()
                        .is_some_and(|(_, first_label)| first_label == label);
                    if !again && named.insert(label.clone()) {
                        others.push(label);
                    }
                }
                None => kept.push((error, Vec::new(), HashSet::new())),
            }
        }
        let mut grouped: Vec<SimulateError> = kept
            .into_iter()
            .map(|(first, others, _)| {
                if others.is_empty() {
                    first
                } else {
                    SimulateError::Grouped {
                        first: Box::new(first),
                        others,
                    }
                }
            })
            .collect();
        grouped.sort_by_key(|error| match error.place() {
            Place::File(span) => span.start,
            _ => usize::MAX,
        });
        grouped
    }

    /// The kind (`JOINT`) and label (`JOINT/3`) of a refused statement.
    fn refused_statement(&self) -> Option<(String, String)> {
        match self {
            SimulateError::Constraint { statement, .. }
            | SimulateError::Unsupported { statement, .. } => {
                let kind = statement.split('/').next().unwrap_or(statement);
                Some((kind.to_ascii_uppercase(), statement.clone()))
            }
            _ => None,
        }
    }

    /// Why a statement is refused, when it is.
    fn reason(&self) -> Option<&str> {
        match self {
            SimulateError::Unsupported { reason, .. } => Some(reason),
            _ => None,
        }
    }

    /// Where the problem is.
    pub fn place(&self) -> Place {
        match self {
            SimulateError::Grouped { first, .. } => first.place(),
            SimulateError::UserSubroutine {
                expression, span, ..
            } => Place::Expression {
                expression: *expression,
                span: *span,
            },
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
            SimulateError::Integration { place, .. } | SimulateError::Chattering { place, .. } => {
                *place
            }
        }
    }
}
