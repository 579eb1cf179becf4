//! Why an integration stops, and why a trial step was rejected.

use crate::Shown;
use thiserror::Error;

/// Why an integration cannot go on. `E` is the system's error.
#[derive(Debug, Error, PartialEq)]
pub enum IntegrateError<E> {
    /// The options or a state handed in cannot be used.
    #[error("invalid integration settings: {0}")]
    Settings(String),
    /// The right-hand side fails at the initial state (or at a restart).
    #[error("cannot start at t = {}: {cause}", Shown(*t))]
    Start {
        /// The time of the initial state.
        t: f64,
        /// What went wrong there.
        cause: Rejection<E>,
    },
    /// Trial steps kept being rejected until the step size fell below
    /// [`smallest_step`](super::smallest_step).
    #[error("step size too small at t = {} (h = {}): {cause}", Shown(*t), Shown(*h))]
    StepSizeTooSmall {
        /// The time of the last accepted state.
        t: f64,
        /// The step size that was about to be tried.
        h: f64,
        /// Why the last trial step was rejected.
        cause: Rejection<E>,
    },
    /// The last `steps` accepted steps advanced the time by less than a
    /// hundred-thousandth of its scale `max(|t|, t - t0)`: the solution is nearly
    /// singular there (it approaches a pole), or far stiffer than an
    /// explicit method can follow.
    #[error(
        "the run stalls at t = {}: its last {steps} accepted steps advanced it by {}",
        Shown(*t),
        Shown(*advance)
    )]
    Stalled {
        /// The time of the last accepted state.
        t: f64,
        /// The accepted steps counted.
        steps: usize,
        /// The time they advanced the run by.
        advance: f64,
    },
    /// [`Options::max_steps`](super::Options::max_steps) steps have been
    /// tried.
    #[error("too many steps: {max_steps} tried by t = {}", Shown(*t))]
    TooManySteps {
        /// The time of the last accepted state.
        t: f64,
        /// The budget.
        max_steps: usize,
    },
    /// The system's Jacobian fails at an accepted state.
    #[error("the jacobian fails at t = {}: {error}", Shown(*t))]
    Jacobian {
        /// The time of the state.
        t: f64,
        /// The system's error.
        error: E,
    },
    /// The system's Jacobian has an infinite or NaN entry at an accepted
    /// state.
    #[error("the jacobian is not finite at t = {}", Shown(*t))]
    JacobianNotFinite {
        /// The time of the state.
        t: f64,
    },
    /// [`Stepper::step_to`](super::Stepper::step_to) was asked to end at
    /// or before the current time.
    #[error("the end time {} is not after t = {}", Shown(*t_end), Shown(*t))]
    EndNotAhead {
        /// The current time.
        t: f64,
        /// The end time asked for.
        t_end: f64,
    },
}

/// Why a trial step was rejected. `E` is the system's error.
#[derive(Debug, Error, PartialEq)]
pub enum Rejection<E> {
    /// The estimated local error exceeds the tolerance.
    #[error("the local error estimate exceeds the tolerance")]
    Tolerance,
    /// The right-hand side fails at a trial state.
    #[error("the right-hand side fails: {0}")]
    System(E),
    /// A trial state or its rate of change is infinite or NaN.
    #[error("a trial state or its rate of change is not finite")]
    NonFinite,
    /// Radau5's Newton iteration diverges or converges too slowly.
    #[error("the newton iteration does not converge")]
    Newton,
    /// Radau5's iteration matrix is singular.
    #[error("the iteration matrix is singular")]
    Singular,
}

/// A method name that is neither `radau` nor `dop853`.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("unknown integration method `{0}`: expected auto, radau (radau5) or dop853")]
pub struct UnknownMethod(pub String);
