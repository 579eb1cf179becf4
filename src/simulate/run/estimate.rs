//! A run's global error estimated the way a user without a reference
//! would: the same model run again at a hundredth of the tolerances, over
//! the same output times, and the rows compared.

use super::{SMALLEST_RTOL, Settings};
use crate::simulate::{SimulateError, Simulation};

/// How far a run's rows lie from a run at a hundredth of its tolerances
/// ([`Simulation::estimate_error`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorEstimate {
    /// The relative tolerance of the run compared with (a hundredth of the
    /// run's, and no less than [`SMALLEST_RTOL`]).
    pub rtol: f64,
    /// Its absolute tolerance (a hundredth of the run's, scaled as `rtol`).
    pub atol: f64,
    /// Per column after `time`, the largest difference over the rows.
    pub largest: Vec<f64>,
}

impl Simulation<'_> {
    /// The estimated global error of `rows`, the rows a run with
    /// `settings` gave (time first; fewer than `settings.steps + 1` when it
    /// stopped early, more with a PRINT sensor's): the model is run again at a hundredth of the
    /// tolerances over the same output times, and each column's largest
    /// difference is its estimate. The error of the tighter run is about a
    /// hundredth of the other's wherever the error follows the tolerance,
    /// so the difference is the run's own error within a few percent.
    pub fn estimate_error(
        &self,
        settings: &Settings,
        rows: &[Vec<f64>],
    ) -> Result<ErrorEstimate, SimulateError> {
        let rtol = (settings.rtol / 100.0).max(SMALLEST_RTOL);
        let tighter = Settings {
            rtol,
            atol: settings.atol * rtol / settings.rtol,
            ..settings.clone()
        };
        let columns = rows.first().map_or(0, |row| row.len().saturating_sub(1));
        let mut largest = vec![0.0_f64; columns];
        // The rows are compared where their times agree: the grid's. A
        // PRINT sensor's row sits at its trip, which the tighter run finds
        // a little elsewhere; such rows of either run are passed over.
        let mut next = 0;
        self.run(&tighter, |time, values| {
            while rows.get(next).is_some_and(|row| row[0] < time) {
                next += 1;
            }
            let Some(row) = rows.get(next) else {
                return false;
            };
            if row[0] == time {
                for (largest, (value, tight)) in largest.iter_mut().zip(row[1..].iter().zip(values))
                {
                    *largest = largest.max((value - tight).abs());
                }
                next += 1;
            }
            next < rows.len()
        })?;
        Ok(ErrorEstimate {
            rtol,
            atol: tighter.atol,
            largest,
        })
    }
}
