//! What both methods share: the current state, the step size and its
//! bounds, counted evaluations of the right-hand side, and the first step
//! size (Hairer's `hinit`).

use std::ops::Range;

use super::{AbsoluteTolerance, IntegrateError, Options, Rejection, Stats, System};
use crate::Shown;

/// A step may overshoot the end time by this factor before it is stretched
/// to land on it (rather than leave a sliver of a step).
const LANDING_STRETCH: f64 = 1.01;

/// A landing step may exceed the maximum step by this relative amount: the
/// rounding of a time reached by many steps of the maximum size.
pub(crate) const CAP_SLACK: f64 = 1e-9;

/// Smallest step size relative to `max(|t|, 1)`.
const SMALLEST_RELATIVE_STEP: f64 = 1e-14;

/// The smallest step size tried at time `t`: `1e-14 max(|t|, 1)`. A run
/// whose steps keep being rejected below it stops with
/// [`IntegrateError::StepSizeTooSmall`].
pub fn smallest_step(t: f64) -> f64 {
    SMALLEST_RELATIVE_STEP * t.abs().max(1.0)
}

/// The accepted steps over which a run must advance by [`STALL_ADVANCE`].
const STALL_WINDOW: usize = 10_000;

/// The least advance over [`STALL_WINDOW`] accepted steps, relative to the
/// time's scale `max(|t|, t - t0)`: steps averaging below `1e-9` of it, a
/// billion steps for each unit of time at `t = 1`.
const STALL_ADVANCE: f64 = 1e-5;

/// A step's error is measured against at least this many times what the
/// rounding of the rates leaves in each state over the step: the error
/// estimate of a state whose rate is rounding noise (an acceleration
/// whose loads cancel) is of that size whatever the step, and a tolerance
/// below it would shrink the steps without end.
const ERROR_FLOOR_MARGIN: f64 = 10.0;

/// A state is noise-limited ([`Core::error_scale`]) when the rounding of
/// its rate exceeds its tolerance over steps of this fraction of the run's
/// span: ten million steps for the run, where without the floor its steps
/// would shrink without end (a hinge under a load of 1e15 N along its axis
/// took 200 000 steps for 0.3 ms).
const NOISE_LIMITED_STEP: f64 = 1e-6;

/// The accepted steps after which a method without Jacobians asks for the
/// rounding floor again ([`Core::floor_due`]): one solve of the joints'
/// multipliers each 32 steps of twelve evaluations of the right-hand side
/// (nothing in a model without joints).
const FLOOR_EVERY: usize = 32;

/// A state's error scale over a step ([`Core::error_scale`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct ErrorScale {
    /// `atol + rtol |y|`.
    pub tolerance: f64,
    /// The tolerance, or the rounding over the step where that is larger.
    pub scale: f64,
}

/// Greater than zero (NaN is not).
fn positive(value: f64) -> bool {
    value > 0.0
}

/// The state of a run that does not depend on the method.
pub(super) struct Core {
    pub t: f64,
    pub t_previous: f64,
    pub y: Vec<f64>,
    /// `f(t, y)`, valid unless `fresh`.
    pub dy: Vec<f64>,
    /// `f(t, y)` has still to be evaluated (at the start, after a restart).
    pub fresh: bool,
    /// The step size to try next.
    pub h: f64,
    pub h_max: f64,
    pub rtol: f64,
    pub atol: Vec<f64>,
    pub max_steps: usize,
    /// The groups of states of the error norm ([`System::norm_groups`]).
    pub groups: Vec<Range<usize>>,
    /// The solution is smooth to the method's order ([`Options::smooth`]).
    pub smooth: bool,
    pub stats: Stats,
    /// The rounding floor of each rate and the floor it carries from the
    /// states it reads ([`System::rounding_floor`]), the time they were
    /// asked at (`None`: to be asked) and the accepted steps by then.
    pub floor: Vec<f64>,
    pub carried: Vec<f64>,
    pub floor_at: Option<f64>,
    floor_steps: usize,
    /// The run's span so far: the largest of `|t|` and the distance from
    /// the start to any time it was asked to reach.
    span: f64,
    /// The time at the start.
    t0: f64,
    /// The accepted steps and the time at the start of the window over
    /// which the run must advance ([`STALL_WINDOW`]).
    window: (usize, f64),
    /// The advance over the last window, where it was too small.
    stalled: Option<f64>,
}

impl Core {
    /// Checks the options against the system's dimension.
    pub fn new<E>(
        options: &Options,
        t0: f64,
        y0: &[f64],
        dimension: usize,
    ) -> Result<Self, IntegrateError<E>> {
        let invalid = |reason: String| Err(IntegrateError::Settings(reason));
        if dimension == 0 {
            return invalid("the system has no state to integrate".to_owned());
        }
        if y0.len() != dimension {
            return invalid(format!(
                "the initial state has {}, the system {dimension}",
                crate::Counted(y0.len(), "component")
            ));
        }
        let atol = match &options.atol {
            AbsoluteTolerance::All(atol) => vec![*atol; dimension],
            AbsoluteTolerance::Each(atol) if atol.len() == dimension => atol.clone(),
            AbsoluteTolerance::Each(atol) => {
                return invalid(format!(
                    "{} for {}",
                    crate::Counted(atol.len(), "absolute tolerance"),
                    crate::Counted(dimension, "component")
                ));
            }
        };
        if !(options.rtol > 0.0 && options.rtol.is_finite()) {
            return invalid(format!(
                "rtol must be positive, not {}",
                Shown(options.rtol)
            ));
        }
        if let Some(atol) = atol.iter().find(|atol| !(**atol > 0.0 && atol.is_finite())) {
            return invalid(format!("atol must be positive, not {}", Shown(*atol)));
        }
        if !positive(options.h_max) {
            return invalid(format!(
                "h_max must be positive, not {}",
                Shown(options.h_max)
            ));
        }
        if let Some(h) = options.h_init.filter(|h| !(*h > 0.0 && h.is_finite())) {
            return invalid(format!("h_init must be positive, not {}", Shown(h)));
        }
        if !t0.is_finite() {
            return invalid(format!(
                "the initial time must be finite, not {}",
                Shown(t0)
            ));
        }
        Ok(Core {
            t: t0,
            t_previous: t0,
            y: y0.to_vec(),
            dy: vec![0.0; dimension],
            fresh: true,
            h: 0.0,
            h_max: options.h_max,
            rtol: options.rtol,
            atol,
            max_steps: options.max_steps,
            groups: std::iter::once(0..dimension).collect(),
            smooth: options.smooth,
            stats: Stats::default(),
            floor: vec![0.0; dimension],
            carried: vec![0.0; dimension],
            floor_at: None,
            floor_steps: 0,
            span: 0.0,
            t0,
            window: (0, t0),
            stalled: None,
        })
    }

    /// Asks the system for the rounding floor of the rates at the current
    /// state ([`System::rounding_floor`]); a floor it cannot give is none.
    pub fn update_floor<S: System + ?Sized>(&mut self, system: &mut S) {
        if system
            .rounding_floor(self.t, &self.y, &mut self.floor, &mut self.carried)
            .is_err()
        {
            self.floor.fill(0.0);
            self.carried.fill(0.0);
        }
        self.floor_at = Some(self.t);
        self.floor_steps = self.stats.steps;
    }

    /// Whether a method that asks for no Jacobian should ask for the
    /// rounding floor before its next trial step: at the first step, at a
    /// new state once a step from it was rejected (`after_rejection`), and
    /// every [`FLOOR_EVERY`] accepted steps.
    pub fn floor_due(&self, after_rejection: bool) -> bool {
        match self.floor_at {
            None => true,
            Some(at) => {
                (after_rejection && at != self.t)
                    || self.stats.steps >= self.floor_steps + FLOOR_EVERY
            }
        }
    }

    /// Notes that the run is asked to reach `t_end` ([`Core::error_scale`]
    /// measures steps against its span).
    pub fn reach(&mut self, t_end: f64) {
        self.span = self.span.max(self.t.abs()).max((t_end - self.t0).abs());
    }

    /// What rounding leaves in state `i` over a step of size `h`: `h floor
    /// + h² carried` ([`System::rounding_floor`]).
    fn rounding(&self, i: usize, h: f64) -> f64 {
        h * (self.floor[i] + h * self.carried[i])
    }

    /// State `i`'s error scale over a step of size `h`: the tolerance
    /// `atol + rtol |y|` at the step's start; or, for a state whose
    /// tolerance rounding alone would hold to steps shorter than
    /// [`NOISE_LIMITED_STEP`] of the run's span, [`ERROR_FLOOR_MARGIN`]
    /// times what rounding leaves in it over the step where that is
    /// larger. Widened only there: an error the floor lets through in a
    /// joint's tilt is pushed into the motion the joint leaves free by its
    /// reaction (a pendulum's hinge loaded along its axis by 1e6 N ran 100
    /// times its rtol of 1e-8 off under DOP853 when every step was
    /// measured so).
    pub fn error_scale(&self, i: usize, h: f64) -> ErrorScale {
        let tolerance = self.atol[i] + self.rtol * self.y[i].abs();
        let noise_limited = self.rounding(i, NOISE_LIMITED_STEP * self.span) > tolerance;
        let scale = if noise_limited {
            tolerance.max(ERROR_FLOOR_MARGIN * self.rounding(i, h))
        } else {
            tolerance
        };
        ErrorScale { tolerance, scale }
    }

    /// Counts an accepted step that passed its error test only against
    /// the rounding floor: `plain`, its error against the tolerance alone,
    /// fails it.
    pub fn count_rounding_limited(&mut self, plain: f64) {
        if plain > 1.0 {
            self.stats.rounding_limited += 1;
            self.stats.rounding_limited_from.get_or_insert(self.t);
        }
    }

    /// Evaluates `f(t, y)` at the current state, which must succeed.
    pub fn start<S: System + ?Sized>(
        &mut self,
        system: &mut S,
    ) -> Result<(), IntegrateError<S::Error>> {
        let groups = system.norm_groups();
        let covered = groups.iter().try_fold(0, |next, group| {
            (group.start == next && group.end > group.start).then_some(group.end)
        });
        if covered != Some(self.y.len()) {
            return Err(IntegrateError::Settings(format!(
                "the system's norm groups {groups:?} do not cover its {} states in order",
                self.y.len()
            )));
        }
        self.groups = groups;
        let (t, y, dy) = (self.t, &self.y, &mut self.dy);
        evaluate(system, &mut self.stats, t, y, dy)
            .map_err(|cause| IntegrateError::Start { t, cause })?;
        self.fresh = false;
        Ok(())
    }

    /// Continues from `(t, y)` with no past, the step size kept.
    pub fn restart(&mut self, t: f64, y: &[f64]) {
        self.t = t;
        self.t_previous = t;
        self.y.copy_from_slice(y);
        self.fresh = true;
        // A restart back in time (a switch being located) measures the
        // advance from there.
        if t < self.window.1 {
            self.window = (self.stats.steps, t);
        }
    }

    /// The next trial step `(h, lands)`: the proposal within the maximum
    /// step, stretched or shortened to land exactly on `t_end` when that is
    /// within reach. Errors when the budget of steps is spent, the run
    /// stalls, or the step is too small (with `cause`, the last rejection).
    pub fn trial<E>(
        &self,
        t_end: f64,
        cause: &mut Option<Rejection<E>>,
    ) -> Result<(f64, bool), IntegrateError<E>> {
        if self.stats.steps + self.stats.rejected >= self.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: self.t,
                max_steps: self.max_steps,
            });
        }
        if let Some(advance) = self.stalled {
            return Err(IntegrateError::Stalled {
                t: self.t,
                steps: STALL_WINDOW,
                advance,
            });
        }
        if !positive(self.h_max) {
            return Err(IntegrateError::Settings(format!(
                "h_max must be positive, not {}",
                Shown(self.h_max)
            )));
        }
        let h = self.h.min(self.h_max);
        let remaining = t_end - self.t;
        let within_cap = remaining <= self.h_max * (1.0 + CAP_SLACK);
        if remaining <= h || (remaining <= LANDING_STRETCH * h && within_cap) {
            return Ok((remaining, true));
        }
        if h < smallest_step(self.t) {
            return Err(IntegrateError::StepSizeTooSmall {
                t: self.t,
                h,
                cause: cause.take().unwrap_or(Rejection::Tolerance),
            });
        }
        Ok((h, false))
    }

    /// Makes the step `(h, lands)` from `t`, that is accepted, the current
    /// state (its `y` and `dy` already swapped in by the method), and counts
    /// it.
    pub fn advance(&mut self, h: f64, lands: bool, t_end: f64) {
        self.t_previous = self.t;
        self.t = if lands { t_end } else { self.t + h };
        self.stats.steps += 1;
        let (start, t_start) = self.window;
        if self.stats.steps >= start + STALL_WINDOW {
            let advance = self.t - t_start;
            let scale = self.t.abs().max(self.t - self.t0);
            if advance < STALL_ADVANCE * scale {
                self.stalled = Some(advance);
            }
            self.window = (self.stats.steps, self.t);
        }
    }

    /// Counts a rejected trial step and sets the step size to try next.
    ///
    /// `cause` keeps the step's latest reason, but a failure of the system
    /// or a state that is not finite is not replaced by a tolerance
    /// rejection after it: when the step size runs out, the reason given
    /// is the one that shrank it first (a rate that overflows, not the
    /// error estimates of the smaller trials after it).
    pub fn reject<E>(&mut self, h_next: f64, why: Rejection<E>, cause: &mut Option<Rejection<E>>) {
        self.stats.rejected += 1;
        self.h = h_next;
        let keeps = matches!(why, Rejection::Tolerance)
            && cause
                .as_ref()
                .is_some_and(|earlier| !matches!(earlier, Rejection::Tolerance));
        if !keeps {
            *cause = Some(why);
        }
    }
}

/// `f(t, y)` into `dy`, counted. A non-finite component of `y` or `dy`, or
/// the system's error, rejects the trial state.
pub(super) fn evaluate<S: System + ?Sized>(
    system: &mut S,
    stats: &mut Stats,
    t: f64,
    y: &[f64],
    dy: &mut [f64],
) -> Result<(), Rejection<S::Error>> {
    if !y.iter().all(|value| value.is_finite()) {
        return Err(Rejection::NonFinite);
    }
    stats.rhs_evaluations += 1;
    let outcome = match system.rhs(t, y, dy) {
        Err(error) => Err(Rejection::System(error)),
        Ok(()) if dy.iter().all(|rate| rate.is_finite()) => return Ok(()),
        Ok(()) => Err(Rejection::NonFinite),
    };
    stats.rhs_failures += 1;
    outcome
}

/// The root mean square of `values` (an empty list gives 0).
pub(super) fn rms(values: impl Iterator<Item = f64>, n: usize) -> f64 {
    (values.map(|value| value * value).sum::<f64>() / n.max(1) as f64).sqrt()
}

/// The error norm over `groups` ([`System::norm_groups`]): the largest over
/// the groups of the root mean square within each, where `squares(i)` is
/// the sum of the squares of state `i`'s `per_state` scaled values.
pub(super) fn grouped_rms(
    groups: &[Range<usize>],
    per_state: usize,
    squares: impl Fn(usize) -> f64,
) -> f64 {
    groups
        .iter()
        .map(|group| {
            let sum: f64 = group.clone().map(&squares).sum();
            (sum / (per_state * group.len()).max(1) as f64).sqrt()
        })
        .fold(0.0, |largest: f64, norm| {
            if largest.is_nan() || norm.is_nan() {
                f64::NAN
            } else {
                largest.max(norm)
            }
        })
}

/// A first step size for a method of local error `O(h^order)` (Hairer's
/// `hinit`): one explicit Euler step of size `0.01 |y| / |f|` estimates the
/// second derivative, and the step is the one whose error it predicts to be
/// `0.01`, bounded by 100 times the first guess and by `h_max`.
#[allow(clippy::too_many_arguments)]
pub(super) fn initial_step<S: System + ?Sized>(
    system: &mut S,
    stats: &mut Stats,
    t: f64,
    y: &[f64],
    f0: &[f64],
    h_max: f64,
    rtol: f64,
    atol: &[f64],
    order: i32,
) -> f64 {
    let n = y.len();
    let scale = |i: usize, value: f64| atol[i] + rtol * value.abs();
    // The Euclidean norm of the scaled values, scaled by the largest so
    // that values near the largest double do not overflow its squares.
    let size_of = |values: &[f64]| {
        let scaled = || {
            values
                .iter()
                .enumerate()
                .map(|(i, value)| value / scale(i, y[i]))
        };
        let largest = scaled().fold(0.0_f64, |largest, value| largest.max(value.abs()));
        if largest == 0.0 || !largest.is_finite() {
            return largest;
        }
        largest
            * scaled()
                .map(|value| (value / largest).powi(2))
                .sum::<f64>()
                .sqrt()
    };
    let (norm_f, norm_y) = (size_of(f0), size_of(y));
    let mut h = if norm_f <= 1e-5 || norm_y <= 1e-5 {
        1e-6
    } else {
        0.01 * norm_y / norm_f
    };
    let first_guess = positive_or(h.min(h_max), 1e-6_f64.min(h_max));
    h = first_guess;
    let mut euler = vec![0.0; n];
    let mut f1 = vec![0.0; n];
    // A trial the system refuses is retried closer to the start; if none
    // succeeds, the first step finds out why.
    for _ in 0..10 {
        for i in 0..n {
            euler[i] = y[i] + h * f0[i];
        }
        if evaluate(system, stats, t + h, &euler, &mut f1).is_ok() {
            let change: Vec<f64> = f1.iter().zip(f0).map(|(f1, f0)| f1 - f0).collect();
            let second = size_of(&change) / h;
            let largest = second.max(norm_f);
            let h_order = if largest <= 1e-15 {
                (h * 1e-3).max(1e-6)
            } else {
                (0.01 / largest).powf(1.0 / f64::from(order))
            };
            return positive_or((100.0 * h).min(h_order).min(h_max), first_guess);
        }
        h *= 0.1;
    }
    first_guess
}

/// `h` where it is a positive number, else `fallback` (the sizes of a
/// system whose rates are near the largest double give a first step of 0:
/// trials of a small step find out what is wrong with it instead).
fn positive_or(h: f64, fallback: f64) -> f64 {
    if h > 0.0 && h.is_finite() {
        h
    } else {
        fallback
    }
}
