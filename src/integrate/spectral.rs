//! The largest `|λ|` of the right-hand side's Jacobian, estimated by power
//! iteration on differences of `f`: one more evaluation an iteration, the
//! vector kept from one call to the next, so that it settles on the
//! dominant mode over the steps of a run.

use super::core::{evaluate, rms};
use super::{Stats, System};

/// Power iteration's state.
#[derive(Clone)]
pub(super) struct SpectralRadius {
    /// The iteration's vector (not normalised).
    direction: Vec<f64>,
    /// A shifted state and its rates, working storage.
    shifted: Vec<f64>,
    rates: Vec<f64>,
    /// The growth of the vector at the last iteration.
    last_growth: Option<f64>,
    /// The last two estimates agree within [`SETTLED`].
    settled: bool,
    /// The last estimate.
    last_estimate: Option<f64>,
}

/// The relative change between two estimates within which the iteration
/// has settled on its mode.
const SETTLED: f64 = 0.1;

impl SpectralRadius {
    /// An iteration over `n` components.
    pub fn new(n: usize) -> SpectralRadius {
        SpectralRadius {
            direction: (0..n).map(start_component).collect(),
            shifted: vec![0.0; n],
            rates: vec![0.0; n],
            last_growth: None,
            settled: false,
            last_estimate: None,
        }
    }

    /// One iteration at `(t, y)`, whose rates are `dy`: the estimate of
    /// `|λ|`, the geometric mean of this iteration's growth and the last's
    /// (a stiff spring's `[[0, 1], [−ω², 0]]` grows a vector by `ω²` and by
    /// 1 in turn; its `|λ|` is `ω`). `None` where the system refuses the
    /// shifted state, which says nothing.
    pub fn iterate<S: System + ?Sized>(
        &mut self,
        system: &mut S,
        stats: &mut Stats,
        t: f64,
        y: &[f64],
        dy: &[f64],
    ) -> Option<f64> {
        let n = y.len();
        let mut size = rms(self.direction.iter().copied(), n);
        if !(size > 0.0 && size.is_finite()) {
            self.direction.copy_from_slice(dy);
            size = rms(self.direction.iter().copied(), n);
            if !(size > 0.0 && size.is_finite()) {
                for (i, component) in self.direction.iter_mut().enumerate() {
                    *component = start_component(i);
                }
                size = rms(self.direction.iter().copied(), n);
            }
        }
        // A shift of about half the digits of the state.
        let delta = f64::EPSILON.sqrt() * (1.0 + rms(y.iter().copied(), n));
        for (shifted, (y, direction)) in self.shifted.iter_mut().zip(y.iter().zip(&self.direction))
        {
            *shifted = y + delta * direction / size;
        }
        if evaluate(system, stats, t, &self.shifted, &mut self.rates).is_err() {
            self.last_growth = None;
            self.settled = false;
            return None;
        }
        for (direction, (shifted_rate, rate)) in
            self.direction.iter_mut().zip(self.rates.iter().zip(dy))
        {
            *direction = (shifted_rate - rate) / delta;
        }
        let growth = rms(self.direction.iter().copied(), n);
        let estimate = match self.last_growth {
            Some(last) => (growth * last).sqrt(),
            None => growth,
        };
        self.last_growth = Some(growth);
        if !estimate.is_finite() {
            self.settled = false;
            return None;
        }
        self.settled = self
            .last_estimate
            .is_some_and(|last| (estimate - last).abs() <= SETTLED * last);
        self.last_estimate = Some(estimate);
        Some(estimate)
    }

    /// The last two estimates agree: the vector has settled on its mode.
    pub fn settled(&self) -> bool {
        self.settled
    }
}

/// The start vector's component `i`: of varied sizes and signs, so that no
/// structure of the system (a rigid motion, states that only differ
/// between bodies) hides a mode from it, as a vector of ones can.
fn start_component(i: usize) -> f64 {
    let fraction = (i as f64 * 0.618_033_988_749_895).fract();
    if i.is_multiple_of(2) {
        0.5 + fraction
    } else {
        -(0.5 + fraction)
    }
}
