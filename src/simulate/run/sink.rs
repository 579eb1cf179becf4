//! Where a run's results go as they are computed: each row, each located
//! switch and each change of method is handed over at once, and the
//! receiver may stop the run at any step. This is the face a caller
//! embedding the simulator (the command line, a C or Python binding)
//! builds on.

use std::ops::ControlFlow;

use super::Event;
use crate::integrate::Method;

/// A change of method under [`Method::Auto`].
#[derive(Clone, Debug, PartialEq)]
pub struct MethodChange {
    /// When: the start of the first step the new method makes.
    pub time: f64,
    /// The method left.
    pub from: Method,
    /// The method taken.
    pub to: Method,
}

/// Receives a run's results as they are computed
/// ([`Simulation::run_into`](super::Simulation::run_into)). Only
/// [`row`](Sink::row) must be written.
pub trait Sink {
    /// A row: the time and the values of the columns after `time`
    /// ([`columns`](crate::simulate::columns)). [`ControlFlow::Break`] stops the run
    /// there.
    fn row(&mut self, time: f64, values: &[f64]) -> ControlFlow<()>;

    /// A located branch switch, once the run has moved past it.
    /// [`ControlFlow::Break`] stops the run there.
    fn event(&mut self, event: &Event) -> ControlFlow<()> {
        let _ = event;
        ControlFlow::Continue(())
    }

    /// A change of method under [`Method::Auto`].
    fn method_changed(&mut self, change: &MethodChange) {
        let _ = change;
    }

    /// Asked before every step: `true` ends the run there (a cancellation:
    /// an interrupt, a closed window), with
    /// [`Summary::stopped`](super::Summary::stopped) set.
    fn stop_requested(&mut self) -> bool {
        false
    }
}

/// A sink of rows only: a closure that returns `false` to stop.
pub(super) struct RowsOnly<F>(pub F);

impl<F: FnMut(f64, &[f64]) -> bool> Sink for RowsOnly<F> {
    fn row(&mut self, time: f64, values: &[f64]) -> ControlFlow<()> {
        if (self.0)(time, values) {
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(())
        }
    }
}
