//! The project's own integrators of ordinary differential equations
//! `dy/dt = f(t, y)`: Radau IIA of order 5 for stiff systems, with the
//! caller's exact Jacobian, and the explicit Dormand–Prince pair DOP853,
//! both with continuous (dense) output over each step.
//!
//! A [`Stepper`] makes one accepted step at a time, so that a caller can look
//! inside each step (on the dense output) for events, cut the step short
//! there and [`restart`](Stepper::restart). A trial state at which the
//! [`System`] fails (a domain error, an overflow, a NaN) rejects the trial
//! step, which is retried smaller; a run ends only when the step size falls
//! below [`smallest_step`] or the step budget is spent.
//!
//! # Formulation
//!
//! Both methods follow Hairer and Wanner's codes (`dop853.f`, `radau5.f`):
//!
//! - **DOP853** (Hairer, Nørsett, Wanner I; `dop853.f`): 12 stages of
//!   order 8, the first stage of the next step being the last evaluation of
//!   this one (FSAL). The error of the step is estimated from a 5th-order and
//!   a 3rd-order embedded solution combined as `err5² / sqrt(err5² + 0.01
//!   err3²)` (by `err5` alone on the first step of a start and where the
//!   caller says the solution is not smooth: [`Stepper::set_smooth`]), and
//!   the step size follows `h_new = h / clamp(err^(1/8) / 0.9,
//!   1/6, 1/0.333)`. Three more stages give the 7th-order dense output.
//!   The steps are also held to `h |λ| ≤ 3`, `|λ|` the largest of the
//!   Jacobian by power iteration on differences of `f` (one more
//!   evaluation a step while `h |λ|` passes 2, every eighth step below):
//!   beyond, up to the edge of stability (6.1) where the error control
//!   holds a stiff problem's steps, the step's ends are right but the
//!   dense output's polynomial in `h λ` departs from the mode inside the
//!   step, by up to 10 to 30 times the mode at the edge.
//! - **Radau IIA of order 5** (Hairer, Wanner II, IV.8): the three-stage
//!   collocation method at the Radau points `(4 ∓ √6)/10, 1`. The stage
//!   equations are solved by simplified Newton iterations on the system
//!   transformed by the eigenvectors of the method's matrix, which splits it
//!   into one real `n×n` system `(γ/h − J)` and one complex `(α + iβ)/h − J`,
//!   each factorised once per step size (dense or sparse: [`linalg`]). The Jacobian is kept while the
//!   Newton contraction `θ` stays below 0.001; the error estimate is
//!   filtered through `(I − h γ₀ J)⁻¹` (and refined once more at a first or
//!   rejected step); the step size is chosen by Gustafsson's predictive
//!   controller. The Newton iterations start from the last step's
//!   collocation polynomial, which is also the dense output (order 3 inside
//!   the step, 5 at its end). The tolerances are the caller's, unchanged,
//!   as in scipy's `Radau` and CVODE: Hairer's code works to `0.1
//!   rtol^(2/3)` instead, which assumes a step's true error far below its
//!   order-3 estimate; at the touch of a contact with a non-whole exponent
//!   (a weak singularity) the two are alike, and the error was up to 300
//!   times rtol at rtol 1e-10.
//!
//! **Architecture Invariant:** this module knows only `f64` slices, nalgebra
//! matrices, its [`linalg`] patterns and its [`System`] trait; nothing of expressions, models or
//! scenes.
//!
//! # References
//!
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential
//!   Equations I: Nonstiff Problems*, 2nd ed., Springer 1993.
//! - E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II:
//!   Stiff and Differential-Algebraic Problems*, 2nd ed., Springer 1996.
//! - K. Gustafsson, Control-theoretic techniques for stepsize selection in
//!   implicit Runge–Kutta methods, *ACM TOMS* 20 (1994) 496–517.
//!
//! ```
//! use mbexpr::integrate::{Method, Options, Stepper, System};
//! use nalgebra::DMatrix;
//!
//! /// y'' = -y as a first-order system.
//! struct Oscillator;
//!
//! impl System for Oscillator {
//!     type Error = std::convert::Infallible;
//!     fn dimension(&self) -> usize {
//!         2
//!     }
//!     fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Self::Error> {
//!         dy[0] = y[1];
//!         dy[1] = -y[0];
//!         Ok(())
//!     }
//!     fn jacobian(&mut self, _t: f64, _y: &[f64], _dy: &[f64], jac: &mut DMatrix<f64>) -> Result<(), Self::Error> {
//!         jac.copy_from_slice(&[0.0, -1.0, 1.0, 0.0]); // column-major
//!         Ok(())
//!     }
//! }
//!
//! let options = Options { rtol: 1e-10, atol: 1e-10.into(), ..Options::default() };
//! let mut stepper = Stepper::new(Method::Radau5, options, 0.0, &[1.0, 0.0], &mut Oscillator)?;
//! while stepper.t() < 3.0 {
//!     stepper.step_to(&mut Oscillator, 3.0)?;
//! }
//! assert_eq!(stepper.t(), 3.0);
//! assert!((stepper.y()[0] - 3.0f64.cos()).abs() < 1e-9);
//! // The collocation polynomial of the last step, between its ends:
//! let mut y = [0.0; 2];
//! let between = 0.5 * (stepper.t_previous() + stepper.t());
//! stepper.dense(between, &mut y);
//! assert!((y[0] - between.cos()).abs() < 1e-7);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod auto;
mod core;
mod dop853;
mod error;
pub mod linalg;
mod radau5;
mod spectral;

use std::fmt;
use std::ops::Range;
use std::str::FromStr;

use nalgebra::DMatrix;

use crate::Counted;

use self::auto::Auto;
pub(crate) use self::core::CAP_SLACK;
use self::core::Core;
pub use self::core::smallest_step;
use self::dop853::Dop853;
pub use self::error::{IntegrateError, Rejection, UnknownMethod};
use self::linalg::Pattern;
use self::radau5::Radau5;

/// A system of ordinary differential equations `dy/dt = f(t, y)`.
pub trait System {
    /// The caller's error, for a state at which `f` cannot be evaluated.
    type Error;

    /// The number of components of `y`.
    fn dimension(&self) -> usize;

    /// `dy/dt` at `(t, y)`, written into `dy`. An error means that the state
    /// is not admissible (an overflow, a domain error, a NaN): the
    /// integrator rejects the trial step and retries a smaller one, it does
    /// not stop. So does a non-finite component of `dy`.
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Self::Error>;

    /// `d(dy/dt)/dy` at `(t, y)` as a dense `n×n` matrix (row `i`, column
    /// `j`: `∂f_i/∂y_j`), where `dy` is `f(t, y)`; `jac` arrives zeroed.
    /// Only the implicit method asks for it, always at an accepted state.
    /// The default is [`finite_difference_jacobian`], as `radau5.f` does
    /// without a Jacobian; give the exact one where it is known.
    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &[f64],
        jac: &mut DMatrix<f64>,
    ) -> Result<(), Self::Error> {
        finite_difference_jacobian(self, t, y, dy, jac)
    }

    /// The rounding floor of each rate at `(t, y)` into `floor`: how far
    /// below its size rounding leaves a rate (an acceleration whose loads
    /// cancel); and into `carried`, the floor each rate takes from the
    /// states it reads, per unit of time: a position's rate is a velocity,
    /// which a step of size `h` leaves `h` times its own rate's floor off.
    /// Radau5 measures its Newton increments against no less than a
    /// multiple of `floor`, since an increment cannot contract below the
    /// noise of its rate, and both methods measure a step's error against
    /// no less than a multiple of `h floor + h² carried`, since no step
    /// size brings the error below what rounding puts in it. The default
    /// is zero: no floor.
    fn rounding_floor(
        &mut self,
        t: f64,
        y: &[f64],
        floor: &mut [f64],
        carried: &mut [f64],
    ) -> Result<(), Self::Error> {
        let _ = (t, y);
        floor.fill(0.0);
        carried.fill(0.0);
        Ok(())
    }

    /// Where the Jacobian's entries can be nonzero, when the system knows
    /// (asked once, when a stepper of the implicit method starts; the
    /// pattern must hold for every state of the run). With a pattern, the
    /// integrator asks for [`System::sparse_jacobian`] instead of
    /// [`System::jacobian`] and may factorise sparse (see [`linalg`]).
    /// A pattern larger than the system has algebraic unknowns after the
    /// states: the system's equations are then `y' = f(y, z)` with `z`
    /// solving `0 = g(y, z)`, and [`System::sparse_jacobian`] gives the
    /// Jacobian of `(f, g)` in `(y, z)` ([`linalg`]'s module documentation);
    /// [`System::jacobian`] stays the ODE's.
    /// The default, `None`, is a dense Jacobian.
    fn jacobian_pattern(&mut self) -> Option<Pattern> {
        None
    }

    /// The Jacobian's entries on `pattern` (the one
    /// [`System::jacobian_pattern`] gave), in its storage order, into
    /// `values` (which arrive zeroed). The default gathers them from
    /// [`System::jacobian`]; a system with a pattern should fill them
    /// directly, at a cost that grows with the entries, not with `n²`.
    fn sparse_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &[f64],
        pattern: &Pattern,
        values: &mut [f64],
    ) -> Result<(), Self::Error> {
        let n = y.len();
        let mut dense = DMatrix::zeros(n, n);
        self.jacobian(t, y, dy, &mut dense)?;
        for (value, entry) in values.iter_mut().zip(pattern.entries()) {
            *value = dense[entry];
        }
        Ok(())
    }

    /// The groups of states whose errors are measured together: a step's
    /// error (and a Newton increment's size) is the largest over the
    /// groups of the root mean square of the scaled errors within each.
    /// The groups are consecutive ranges that cover the states in order
    /// (asked at every start and fresh start of a stepper). The default is one group, the
    /// root mean square over all states as in Hairer's codes; a system of
    /// many similar parts gives one group a part, so that parts at rest do
    /// not dilute the error of the one that moves.
    fn norm_groups(&mut self) -> Vec<Range<usize>> {
        std::iter::once(0..self.dimension()).collect()
    }
}

/// The Jacobian of `system` at `(t, y)` by forward differences of its
/// right-hand side (`dy` is `f(t, y)`), each component shifted by
/// `sqrt(ε max(|y_j|, 1e-5))` as in `radau5.f`: about half the digits of
/// the exact one.
pub fn finite_difference_jacobian<S: System + ?Sized>(
    system: &mut S,
    t: f64,
    y: &[f64],
    dy: &[f64],
    jac: &mut DMatrix<f64>,
) -> Result<(), S::Error> {
    let mut shifted = y.to_vec();
    let mut column = vec![0.0; y.len()];
    for j in 0..y.len() {
        let delta = (f64::EPSILON * y[j].abs().max(1e-5)).sqrt();
        shifted[j] = y[j] + delta;
        system.rhs(t, &shifted, &mut column)?;
        shifted[j] = y[j];
        for (i, (shifted_rate, rate)) in column.iter().zip(dy).enumerate() {
            jac[(i, j)] = (shifted_rate - rate) / delta;
        }
    }
    Ok(())
}

/// The integration method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Radau IIA of order 5 (`radau5.f`): implicit, for stiff systems; uses
    /// [`System::jacobian`].
    Radau5,
    /// Dormand and Prince's explicit pair of order 8 (`dop853.f`) with its
    /// 7th-order dense output.
    Dop853,
    /// DOP853 while the problem is not stiff, Radau5 while it is (LSODA's
    /// idea): to Radau5 when DOP853's stiffness test fires, back when the
    /// step Radau5 takes is within DOP853's stability region again (the
    /// largest `|λ|` of the Jacobian by power iteration); each change a
    /// restart from the current state ([`Stepper::method`] says which
    /// method made the last step).
    Auto,
}

impl Method {
    /// Whether the method may ask the system for its Jacobian.
    pub fn uses_jacobian(self) -> bool {
        self != Method::Dop853
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Method::Radau5 => "radau",
            Method::Dop853 => "dop853",
            Method::Auto => "auto",
        })
    }
}

impl FromStr for Method {
    type Err = UnknownMethod;

    /// `radau` (or `radau5`), `dop853` and `auto`, as the command line
    /// spells them, in any case.
    fn from_str(name: &str) -> Result<Self, UnknownMethod> {
        match name.to_ascii_lowercase().as_str() {
            "radau" | "radau5" => Ok(Method::Radau5),
            "dop853" => Ok(Method::Dop853),
            "auto" => Ok(Method::Auto),
            _ => Err(UnknownMethod(name.to_owned())),
        }
    }
}

/// The absolute tolerance: one for every component, or one each.
#[derive(Clone, Debug, PartialEq)]
pub enum AbsoluteTolerance {
    /// The same for every component.
    All(f64),
    /// One per component of the state.
    Each(Vec<f64>),
}

impl From<f64> for AbsoluteTolerance {
    fn from(atol: f64) -> Self {
        AbsoluteTolerance::All(atol)
    }
}

/// The settings of a run. The error of a step is measured component by
/// component against `atol_i + rtol |y_i|`.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Relative tolerance (positive).
    pub rtol: f64,
    /// Absolute tolerance (positive).
    pub atol: AbsoluteTolerance,
    /// Largest step size (positive; infinity for none). See also
    /// [`Stepper::set_h_max`].
    pub h_max: f64,
    /// The first step size; chosen from the problem (Hairer's `hinit`) when
    /// `None`.
    pub h_init: Option<f64>,
    /// Largest number of steps tried, accepted and rejected, over the
    /// stepper's life.
    pub max_steps: usize,
    /// Radau5 only: the Newton iteration stops when its estimated error,
    /// in units of the tolerance, is below this (Hairer's `fnewt`; by
    /// default `max(10 ε / rtol, min(0.03, rtol^(1/2)))`).
    pub newton_tolerance: Option<f64>,
    /// Radau5 only: the Jacobian is kept for the next step while the
    /// Newton iteration contracts by at most this factor (Hairer's `thet`:
    /// by default 0.001, for a Jacobian that costs a few right-hand sides;
    /// more where it costs more; from 0 to below 1).
    pub jacobian_reuse: f64,
    /// The solution is smooth to the method's order (the default). See
    /// [`Stepper::set_smooth`].
    pub smooth: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            rtol: 1e-6,
            atol: AbsoluteTolerance::All(1e-6),
            h_max: f64::INFINITY,
            h_init: None,
            max_steps: 100_000,
            newton_tolerance: None,
            jacobian_reuse: 0.001,
            smooth: true,
        }
    }
}

/// What a run has cost so far.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected trial steps, for any reason.
    pub rejected: usize,
    /// Calls of [`System::rhs`] (not counting those of the default
    /// finite-difference Jacobian).
    pub rhs_evaluations: usize,
    /// Calls of [`System::rhs`] that failed or gave a non-finite value.
    pub rhs_failures: usize,
    /// Calls of [`System::jacobian`].
    pub jacobian_evaluations: usize,
    /// LU decompositions of the iteration matrices (a real and a complex
    /// one counted together as one).
    pub lu_decompositions: usize,
    /// Accepted steps whose error passed its test only when measured
    /// against what rounding leaves in the rates
    /// ([`System::rounding_floor`]): there the solution is as accurate as
    /// double precision allows, not as the tolerance asks.
    pub rounding_limited: usize,
    /// The start of the first such step.
    pub rounding_limited_from: Option<f64>,
}

impl fmt::Display for Stats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ({} rejected), {} ({} failed), {}, {}",
            Counted(self.steps, "step"),
            self.rejected,
            Counted(self.rhs_evaluations, "right-hand side"),
            self.rhs_failures,
            Counted(self.jacobian_evaluations, "jacobian"),
            Counted(self.lu_decompositions, "lu decomposition")
        )
    }
}

/// The method's own state.
enum Scheme {
    Radau5(Box<Radau5>),
    Dop853(Box<Dop853>),
}

/// An integration in progress: one accepted step per call of
/// [`step`](Stepper::step) or [`step_to`](Stepper::step_to), after which
/// [`t_previous`](Stepper::t_previous), [`t`](Stepper::t),
/// [`y`](Stepper::y) and [`dense`](Stepper::dense) describe the step.
///
/// The system is passed to each call rather than held, so that the caller
/// may change it between steps (a branch switch at an event, then
/// [`restart`](Stepper::restart)). Time runs forwards.
pub struct Stepper {
    core: Core,
    scheme: Scheme,
    options: Options,
    /// Under [`Method::Auto`], the choice between the methods.
    auto: Option<Auto>,
}

impl Stepper {
    /// Starts at `(t0, y0)`: checks the options, evaluates `f(t0, y0)` and
    /// chooses the first step size unless `options.h_init` gives it.
    /// [`Method::Auto`] starts with DOP853.
    pub fn new<S: System + ?Sized>(
        method: Method,
        options: Options,
        t0: f64,
        y0: &[f64],
        system: &mut S,
    ) -> Result<Self, IntegrateError<S::Error>> {
        let first = match method {
            Method::Auto => Method::Dop853,
            fixed => fixed,
        };
        Self::start(method, first, options, t0, y0, system, None)
    }

    /// A new stepper from `(t, y)` with this one's method (under
    /// [`Method::Auto`], starting with the one in use now), its first step
    /// chosen anew and its counts from zero: a fresh start after the caller
    /// has changed the system at an event. DOP853's stiffness test goes on
    /// where it stood, and its estimate of the stiffest mode holds the
    /// first step. Radau5 evaluates a new Jacobian, keeping its storage
    /// and its sparse LU's symbolic analysis where the system's pattern is
    /// the same.
    pub fn fresh_start<S: System + ?Sized>(
        self,
        options: Options,
        t: f64,
        y: &[f64],
        system: &mut S,
    ) -> Result<Self, IntegrateError<S::Error>> {
        let choice = if self.auto.is_some() {
            Method::Auto
        } else {
            self.method()
        };
        let method = self.method();
        Self::start(choice, method, options, t, y, system, Some(self.scheme))
    }

    /// Starts `choice` (a method or Auto) at `(t0, y0)` with `first`,
    /// continuing from `previous`, the state of the method in use before a
    /// fresh start.
    fn start<S: System + ?Sized>(
        choice: Method,
        first: Method,
        options: Options,
        t0: f64,
        y0: &[f64],
        system: &mut S,
        previous: Option<Scheme>,
    ) -> Result<Self, IntegrateError<S::Error>> {
        let mut core = Core::new(&options, t0, y0, system.dimension())?;
        let auto = (choice == Method::Auto).then(|| Auto::new(y0.len()));
        let scheme = Self::continued(previous, first, &options, &core, auto.is_some(), system)?;
        core.start(system)?;
        core.h = match options.h_init {
            Some(h) => h,
            None => {
                let order = match &scheme {
                    Scheme::Radau5(_) => radau5::ORDER,
                    Scheme::Dop853(_) => dop853::ORDER,
                };
                core::initial_step(
                    system,
                    &mut core.stats,
                    core.t,
                    &core.y,
                    &core.dy,
                    core.h_max,
                    core.rtol,
                    &core.atol,
                    order,
                )
            }
        };
        Ok(Stepper {
            core,
            scheme,
            options,
            auto,
        })
    }

    /// The working state of `first` after `previous` (none at a start):
    /// Radau5's storage and symbolic analysis kept where the Jacobian's
    /// pattern is the same, DOP853's stiffness test and estimate of the
    /// stiffest mode carried over.
    fn continued<S: System + ?Sized>(
        previous: Option<Scheme>,
        first: Method,
        options: &Options,
        core: &Core,
        auto: bool,
        system: &mut S,
    ) -> Result<Scheme, IntegrateError<S::Error>> {
        match previous {
            Some(Scheme::Radau5(radau)) if first == Method::Radau5 => {
                let pattern = system.jacobian_pattern();
                if let Some(radau) = radau.renewed(options, pattern.as_ref())? {
                    return Ok(Scheme::Radau5(radau));
                }
            }
            Some(Scheme::Dop853(old)) => {
                let mut scheme = Self::scheme(first, options, core, auto, system)?;
                if let Scheme::Dop853(new) = &mut scheme {
                    new.continue_from(&old);
                }
                return Ok(scheme);
            }
            _ => {}
        }
        Self::scheme(first, options, core, auto, system)
    }

    /// The working state of `method` (Radau5 or DOP853; DOP853 runs its
    /// stiffness test at every step when `auto` decides on it). Radau5
    /// factorises on the system's Jacobian pattern, when it gives one.
    fn scheme<S: System + ?Sized>(
        method: Method,
        options: &Options,
        core: &Core,
        auto: bool,
        system: &mut S,
    ) -> Result<Scheme, IntegrateError<S::Error>> {
        Ok(match method {
            Method::Radau5 => {
                let pattern = system.jacobian_pattern();
                Scheme::Radau5(Box::new(Radau5::new(options, core.atol.len(), pattern)?))
            }
            Method::Dop853 | Method::Auto => {
                let test = if auto {
                    auto::STIFFNESS_TEST
                } else {
                    dop853::HAIRER_TEST
                };
                Scheme::Dop853(Box::new(Dop853::new(core.y.len(), test)))
            }
        })
    }

    /// One accepted step, as long as the method chooses.
    pub fn step<S: System + ?Sized>(
        &mut self,
        system: &mut S,
    ) -> Result<(), IntegrateError<S::Error>> {
        self.step_to(system, f64::INFINITY)
    }

    /// One accepted step that does not pass `t_end`: when `t_end` is within
    /// reach the step ends exactly on it (`t() == t_end`).
    pub fn step_to<S: System + ?Sized>(
        &mut self,
        system: &mut S,
        t_end: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        if t_end <= self.core.t || t_end.is_nan() {
            return Err(IntegrateError::EndNotAhead {
                t: self.core.t,
                t_end,
            });
        }
        if let Some(to) = self.auto.as_mut().and_then(Auto::change) {
            self.scheme = Self::scheme(to, &self.options, &self.core, true, system)?;
            let (t, y) = (self.core.t, self.core.y.clone());
            self.core.restart(t, &y);
        }
        if self.core.fresh {
            self.core.start(system)?;
        }
        self.core.reach(t_end);
        match &mut self.scheme {
            Scheme::Radau5(radau) => radau.step(&mut self.core, system, t_end)?,
            Scheme::Dop853(dop) => dop.step(&mut self.core, system, t_end)?,
        }
        if let Some(auto) = &mut self.auto {
            match &self.scheme {
                Scheme::Radau5(_) => auto.after_implicit(&mut self.core, system),
                Scheme::Dop853(dop) => auto.after_explicit(dop.stiff_from().is_some()),
            }
        }
        Ok(())
    }

    /// Continues from `(t, y)` afresh, as at a start: the caller has cut the
    /// last step short at an event and perhaps changed the system. The
    /// method forgets its history (Radau5 keeps its Jacobian as one of an
    /// earlier state, renewed where Newton's iteration fails with it); the step
    /// size is the last proposal, within the maximum step. `f(t, y)` is
    /// evaluated by the next step.
    ///
    /// # Panics
    ///
    /// When `y` has not the system's dimension.
    pub fn restart(&mut self, t: f64, y: &[f64]) {
        self.go_on_from(t, y);
        match &mut self.scheme {
            Scheme::Radau5(radau) => radau.restart(),
            Scheme::Dop853(dop) => dop.restart(),
        }
    }

    /// Goes on from `(t, y)`, a state moved from the current one by less
    /// than the tolerance (put back on constraints it drifted from): as
    /// [`Stepper::restart`], but the method keeps its step size control's
    /// history and Radau5 its last step's polynomial for Newton's starting
    /// values, as for a state it had reached itself (after a restart its
    /// first step's error test is stricter, which cost a model projected
    /// at most steps a fifth more evaluations).
    ///
    /// # Panics
    ///
    /// When `y` has not the system's dimension.
    pub fn nudge(&mut self, t: f64, y: &[f64]) {
        self.go_on_from(t, y);
        if let Scheme::Radau5(radau) = &mut self.scheme {
            radau.nudged();
        }
    }

    /// The current state replaced by `(t, y)`, which must have the system's
    /// dimension: what [`Stepper::restart`] and [`Stepper::nudge`] share.
    fn go_on_from(&mut self, t: f64, y: &[f64]) {
        assert_eq!(
            y.len(),
            self.core.y.len(),
            "a state of another dimension to go on from"
        );
        self.core.restart(t, y);
    }

    /// Caps the step size from the next step on (positive; infinity lifts
    /// the cap).
    pub fn set_h_max(&mut self, h_max: f64) {
        self.core.h_max = h_max;
    }

    /// Says whether the solution is smooth to the method's order over the
    /// next steps. Near a weak singularity (a force `p^e` with a non-whole
    /// `e` at a contact's touch and release) it is not: DOP853 then
    /// measures a step's error by its 5th-order estimate alone, since
    /// Hairer's blend with the 3rd-order one, `err5² / sqrt(err5² + 0.01
    /// err3²)`, assumes a smooth solution and there finds the error far
    /// below what it is (a ball between walls with `e = 1.24`: 500 x rtol
    /// at rtol 1e-9 blended, 1.6 x with the 5th-order estimate). Radau5's
    /// estimate is of one order already.
    pub fn set_smooth(&mut self, smooth: bool) {
        self.core.smooth = smooth;
    }

    /// The solution at `t` from the method's continuous output over the last
    /// step, `[t_previous(), t()]` (extrapolated outside it), written into
    /// `out`. Before the first step and after a restart it is `y()`.
    ///
    /// # Panics
    ///
    /// When `out` has not the system's dimension.
    pub fn dense(&self, t: f64, out: &mut [f64]) {
        assert_eq!(
            out.len(),
            self.core.y.len(),
            "dense output of another dimension"
        );
        if self.core.t_previous == self.core.t {
            out.copy_from_slice(&self.core.y);
            return;
        }
        match &self.scheme {
            Scheme::Radau5(radau) => radau.dense(&self.core, t, out),
            Scheme::Dop853(dop) => dop.dense(&self.core, t, out),
        }
    }

    /// The time at the end of the last step.
    pub fn t(&self) -> f64 {
        self.core.t
    }

    /// The time at the start of the last step (`t()` before the first step
    /// and after a restart).
    pub fn t_previous(&self) -> f64 {
        self.core.t_previous
    }

    /// The state at [`t`](Stepper::t).
    pub fn y(&self) -> &[f64] {
        &self.core.y
    }

    /// The step size the next step will try (before the maximum step and
    /// the end time bound it).
    pub fn h(&self) -> f64 {
        self.core.h
    }

    /// What the run has cost so far.
    pub fn stats(&self) -> Stats {
        self.core.stats
    }

    /// DOP853: the time from which Hairer's stiffness test finds the
    /// problem stiff (its steps held to the edge of the stability region,
    /// not by accuracy: a stiff method would take far fewer). Radau5 and
    /// Auto (which changes method there): `None`.
    pub fn stiff_from(&self) -> Option<f64> {
        match &self.scheme {
            Scheme::Dop853(dop) if self.auto.is_none() => dop.stiff_from(),
            _ => None,
        }
    }

    /// Whether the stepper chooses its method ([`Method::Auto`]).
    pub fn is_auto(&self) -> bool {
        self.auto.is_some()
    }

    /// The method that makes the steps: Radau5 or DOP853 (under
    /// [`Method::Auto`], the one chosen for the last step).
    pub fn method(&self) -> Method {
        match self.scheme {
            Scheme::Radau5(_) => Method::Radau5,
            Scheme::Dop853(_) => Method::Dop853,
        }
    }
}
