//! [`Method::Auto`](super::Method::Auto): DOP853 while the problem is not
//! stiff, Radau5 while it is, as LSODA chooses between Adams and BDF.
//!
//! - **To Radau5**: when DOP853's own stiffness test (Hairer's, run at
//!   every step under Auto) finds its steps near the edge of its stability
//!   region, `h |λ|` beyond half the edge (6.1 / 2: at a tight tolerance
//!   the step controller holds DOP853 well inside the edge, A4 at rtol
//!   1e-11, where Hairer's 6.1 never fires in 2 million steps), in 5 tests with
//!   fewer than 6 within between them ([`STIFF_TESTS`]).
//! - **Back to DOP853**: after each Radau5 step the largest `|λ|` of the
//!   Jacobian is estimated by power iteration on differences of the
//!   right-hand side (one more evaluation a step, the vector kept from step
//!   to step); when the step Radau5 proposes times that estimate is within
//!   a quarter of the explicit method's edge in [`RETURN_TESTS`] steps in a
//!   row, DOP853 could take the same steps without being held by
//!   stability, and it is the cheaper method per step.
//!
//! The gap between the two thresholds and the counts on both sides are the
//! hysteresis that keeps a problem at the border from changing method at
//! every step. A change is decided at the end of a step and made at the
//! start of the next, from the current state, as a restart.

use super::core::Core;
use super::dop853::{STABILITY_EDGE, StiffnessTest};
use super::spectral::SpectralRadius;
use super::{Method, System};

/// DOP853's stiffness test under Auto: at every step, `h |λ|` beyond half
/// the edge of its stability region, in [`STIFF_TESTS`] tests.
pub(super) const STIFFNESS_TEST: StiffnessTest = StiffnessTest {
    every: 1,
    edge: 0.5 * STABILITY_EDGE,
    tests: STIFF_TESTS,
};

/// Stiff tests that take Auto to Radau5: 5, not Hairer's 15. A wrong
/// change costs at most [`RETURN_TESTS`] Radau5 steps before the change
/// back, while each stiff test is a DOP853 step held by stability: on A4
/// at rtol 1e-3 the 15 tests took 1.64 times the instructions of Radau5
/// alone at equal error, 5 take 1.26 (`scripts/work_precision.sh --auto`),
/// and no other scene of the study changes method with either.
const STIFF_TESTS: u32 = 5;

/// Radau5's `h |λ|` below which a step counts as one DOP853 could take:
/// a quarter of the edge of DOP853's stability region.
const RETURN_EDGE: f64 = 0.25 * STABILITY_EDGE;

/// Radau5 steps in a row within the margin that make the problem non-stiff.
pub(super) const RETURN_TESTS: u32 = 5;

/// The choice between the methods and what it rests on.
pub(super) struct Auto {
    /// The change decided at the end of the last step, made at the start
    /// of the next.
    pending: Option<Method>,
    /// Power iteration for `|λ|`.
    spectral: SpectralRadius,
    /// Radau5 steps in a row whose `h |λ|` is within the margin.
    within: u32,
}

impl Auto {
    /// A choice for `n` components.
    pub fn new(n: usize) -> Auto {
        Auto {
            pending: None,
            spectral: SpectralRadius::new(n),
            within: 0,
        }
    }

    /// After an accepted DOP853 step: Radau5 from the next one when the
    /// stiffness test found the problem stiff.
    pub fn after_explicit(&mut self, stiff: bool) {
        if stiff {
            self.pending = Some(Method::Radau5);
        }
    }

    /// After an accepted Radau5 step ending at `core`'s state (its `dy`
    /// valid): one power iteration for `|λ|`, counted against the step
    /// Radau5 proposes next. A state the system refuses says nothing.
    pub fn after_implicit<S: System + ?Sized>(&mut self, core: &mut Core, system: &mut S) {
        let Some(lambda) =
            self.spectral
                .iterate(system, &mut core.stats, core.t, &core.y, &core.dy)
        else {
            self.within = 0;
            return;
        };
        if core.h.min(core.h_max) * lambda <= RETURN_EDGE {
            self.within += 1;
        } else {
            self.within = 0;
        }
        if self.within >= RETURN_TESTS {
            self.pending = Some(Method::Dop853);
        }
    }

    /// The change decided, now made: the method to start.
    pub fn change(&mut self) -> Option<Method> {
        let to = self.pending.take()?;
        self.within = 0;
        Some(to)
    }
}
