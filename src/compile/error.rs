//! What keeps a checked expression from being compiled for a context.

use thiserror::Error;

use crate::scene::SceneError;
use crate::span::Span;

/// A reference the evaluation context cannot provide.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CompileError {
    /// A variable with no value.
    #[error("{name} has no value{suggestions}")]
    UnboundVariable {
        /// The name as written.
        name: String,
        /// " (did you mean x?)" or nothing.
        suggestions: String,
        /// Where it is used.
        span: Span,
    },
    /// A kinematic measure outside a scene.
    #[error(
        "{function} is a kinematic measure between markers: evaluating it needs a scene with those markers"
    )]
    NeedsScene {
        /// The measure's name.
        function: &'static str,
        /// The call.
        span: Span,
    },
    /// A function whose value comes from a model statement.
    #[error(
        "{function}({id}) needs {statement} of a model: not available when evaluating an expression on its own"
    )]
    NeedsModel {
        /// The function's name.
        function: &'static str,
        /// The statement id or name, as written.
        id: String,
        /// The statement kind that would provide the data, e.g. `VARIABLE/3`.
        statement: String,
        /// The call.
        span: Span,
    },
    /// A model-data function whose statement the scene (or model) lacks.
    #[error("{function}({id}) needs {statement}, which this model does not define")]
    MissingStatement {
        /// The function's name.
        function: &'static str,
        /// The statement id or name, as written.
        id: String,
        /// The statement that would provide the data, e.g. `SPLINE/3`.
        statement: String,
        /// The call.
        span: Span,
    },
    /// A state or signal that a running solver computes (`DIF`, `SENVAL`, ...).
    #[error(
        "{function}({id}) is a value of {statement} that a running solver computes: it has no value outside a simulation"
    )]
    NeedsSolverState {
        /// The function's name.
        function: &'static str,
        /// The statement id or name, as written.
        id: String,
        /// The statement, e.g. `DIFF/3`.
        statement: String,
        /// The call.
        span: Span,
    },
    /// A result of a running solver.
    #[error("{function} is a result of a running solver: it has no value outside a simulation")]
    NeedsSolver {
        /// The function's name.
        function: &'static str,
        /// The call.
        span: Span,
    },
    /// A reaction of a running solver that this run cannot give (an id no
    /// statement has, a flag out of range, a force reading a reaction).
    #[error("{message}")]
    Reaction {
        /// Why.
        message: String,
        /// The call.
        span: Span,
    },
    /// A marker the scene does not have.
    #[error("{error}")]
    Scene {
        /// What the scene said.
        error: SceneError,
        /// The marker reference.
        span: Span,
    },
    /// An acceleration measure on a body whose accelerations the scene does not give.
    #[error(
        "{function} needs the acceleration and angular acceleration of body {body}, which {place} does not give"
    )]
    NoAcceleration {
        /// "the scene" or "the model".
        place: &'static str,
        /// The measure.
        function: &'static str,
        /// The body.
        body: String,
        /// The marker on that body.
        span: Span,
    },
    /// A measure that scenes do not evaluate.
    #[error("{function} is recognised but not evaluated in {place}")]
    NotInScene {
        /// "scenes" or "models".
        place: &'static str,
        /// The measure.
        function: &'static str,
        /// The call.
        span: Span,
    },
    /// ORIENT's orientation system or component out of its range.
    #[error("ORIENT: {message}")]
    Orientation {
        /// What is wrong.
        message: String,
        /// The call.
        span: Span,
    },
    /// A tree that nests too deep once what it reads is compiled in place.
    #[error(
        "this expression, with the VARIABLEs, DIFFs and outputs it reads written in place, nests deeper than {limit} levels: read fewer of them through one another (a chain of VARIABLEs each nesting the last)"
    )]
    TooDeep {
        /// The most levels.
        limit: usize,
        /// The expression, or its call of the outermost tree compiled in
        /// place.
        span: Span,
    },
    /// VARIABLE (or DIFF) functions that read each other in a loop.
    #[error("VARVAL loops: {cycle}")]
    VariableLoop {
        /// `VARIABLE/1 -> VARIABLE/2 -> VARIABLE/1`.
        cycle: String,
        /// The VARVAL that closes the loop.
        span: Span,
    },
    /// `ARYVAL(id, i)` (or `PINVAL`, `POUVAL`) beyond the array.
    #[error("{function}({id}, {entry}): {statement}/{id} has {}", crate::Counted(*count, "entry"))]
    ArrayEntry {
        /// The function: ARYVAL, PINVAL or POUVAL.
        function: &'static str,
        /// The statement it reads: ARRAY, PINPUT or POUTPUT.
        statement: &'static str,
        /// The array.
        id: u64,
        /// The entry asked for.
        entry: i64,
        /// How many there are.
        count: usize,
        /// The call.
        span: Span,
    },
    /// A spline's derivative order other than 0, 1 or 2.
    #[error("{function}: iord ({order}) must be 0, 1 or 2")]
    SplineOrder {
        /// `AKISPL` or `CUBSPL`.
        function: &'static str,
        /// The order written.
        order: i64,
        /// The order argument.
        span: Span,
    },
    /// `USER(...)`, which only passes constants to a user subroutine.
    #[error(
        "USER(...) passes its constants to a user subroutine, which is not part of mbexpr: there is no value to compute"
    )]
    UserSubroutine {
        /// The call.
        span: Span,
    },
}

impl CompileError {
    /// Whether nothing is wrong with the expression, only its value is not
    /// to be had here: a solver result or state, a user subroutine, or a
    /// measure scenes do not evaluate.
    pub fn is_unavailable(&self) -> bool {
        matches!(
            self,
            CompileError::NeedsSolver { .. }
                | CompileError::NeedsSolverState { .. }
                | CompileError::UserSubroutine { .. }
                | CompileError::NotInScene { .. }
        )
    }

    /// The place in the text the error speaks of.
    pub fn span(&self) -> Span {
        match self {
            CompileError::UnboundVariable { span, .. }
            | CompileError::NeedsScene { span, .. }
            | CompileError::NeedsModel { span, .. }
            | CompileError::MissingStatement { span, .. }
            | CompileError::NeedsSolver { span, .. }
            | CompileError::Reaction { span, .. }
            | CompileError::NeedsSolverState { span, .. }
            | CompileError::Scene { span, .. }
            | CompileError::VariableLoop { span, .. }
            | CompileError::TooDeep { span, .. }
            | CompileError::ArrayEntry { span, .. }
            | CompileError::SplineOrder { span, .. }
            | CompileError::NoAcceleration { span, .. }
            | CompileError::NotInScene { span, .. }
            | CompileError::Orientation { span, .. }
            | CompileError::UserSubroutine { span } => *span,
        }
    }
}
