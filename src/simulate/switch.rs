//! Locating branch switches: after each accepted step the switching values
//! of the held branches are looked at on the step's continuous output; the
//! first sign change is bracketed and located by regula falsi to about
//! 1e-13 relative in time.

use nalgebra::DMatrix;

use super::mechanics::Mechanics;
use crate::eval::OutputError;
use crate::integrate::linalg::Pattern;
use crate::integrate::{Stepper, System};
use crate::laws::branch::Code;

/// A look at the switching values at a time: whether one that is watched
/// is negative there.
type Look<'l> = dyn FnMut(f64, &mut [f64]) -> Result<bool, (f64, OutputError)> + 'l;

/// Points inside each step at which the switching values are looked at
/// (besides its end): a switching function that changes sign twice within
/// one step is caught when one of them falls between its two roots.
const LOOKS_PER_STEP: usize = 4;

/// Looks at the stretch of a step before a located switch: evenly spaced,
/// and crowding towards it.
const LOOKS_BEFORE_SWITCH: usize = 8;
const LOOKS_CROWDING: usize = 14;

/// The equations with the sites held on their branches: what the
/// integrator sees.
pub(super) struct Held<'m> {
    pub(super) mechanics: Mechanics<'m>,
    pub(super) held: Vec<Option<Code>>,
    /// The absolute error in a state the run accepts (its `atol`), which
    /// bounds how far the sites' step limits shrink.
    pub(super) tolerance: f64,
}

impl System for Held<'_> {
    type Error = OutputError;

    fn dimension(&self) -> usize {
        self.mechanics.dimension()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), OutputError> {
        self.mechanics.rates(t, y, Some(&self.held), dy)
    }

    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        _dy: &[f64],
        jacobian: &mut DMatrix<f64>,
    ) -> Result<(), OutputError> {
        self.mechanics.jacobian(t, y, Some(&self.held), jacobian)
    }

    fn jacobian_pattern(&mut self) -> Option<Pattern> {
        Some(self.mechanics.pattern().clone())
    }

    fn sparse_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        _dy: &[f64],
        _pattern: &Pattern,
        values: &mut [f64],
    ) -> Result<(), OutputError> {
        self.mechanics
            .sparse_jacobian(t, y, Some(&self.held), values)
    }
}

impl Held<'_> {
    /// The switching values at `(t, y)` for the held branches, and the
    /// natural branches into `natural`.
    pub(super) fn look(
        &mut self,
        t: f64,
        y: &[f64],
        natural: &mut [Option<Code>],
        switching: &mut [f64],
    ) -> Result<(), OutputError> {
        self.mechanics
            .observe(t, y, Some(&self.held), (natural, switching), None)
            .map(|_| ())
    }

    /// [`Held::look`], and the largest step the sites allow from `t`.
    pub(super) fn look_and_limit(
        &mut self,
        t: f64,
        y: &[f64],
        natural: &mut [Option<Code>],
        switching: &mut [f64],
    ) -> Result<f64, OutputError> {
        let tolerance = Some(self.tolerance);
        self.mechanics
            .observe(t, y, Some(&self.held), (natural, switching), tolerance)
    }
}

/// The first switch in the last step `[t0, t1]`: `Err(limit)` when there
/// is none (`limit`: the largest next step the sites allow at `t1`), or the
/// located time as `(left, right)`, a bracket no wider than about 1e-13
/// relative with every held branch still valid at `left` and some
/// switching value negative at `right`.
///
/// The switching values are looked at [`LOOKS_PER_STEP`] times across the
/// step. Once a crossing is located, the stretch before it is looked at
/// again, evenly and crowding towards the crossing: a switch and its
/// return can lie between two looks, and they come most often just before
/// another switch (a contact's clamp releases just before the body leaves
/// the stop).
pub(super) fn find_switch(
    system: &mut Held<'_>,
    stepper: &Stepper,
    t0: f64,
    t1: f64,
    start: &[f64],
    natural: &mut [Option<Code>],
    switching: &mut [f64],
) -> Result<Result<Switch, f64>, (f64, OutputError)> {
    // A switching value negative at the step's start (the state a switch
    // restarts from can lie a rounding error on the old side) is watched
    // from the first look at which it is positive.
    let armed = std::cell::RefCell::new(
        start
            .iter()
            .map(|&value| value >= 0.0)
            .collect::<Vec<bool>>(),
    );
    let mut state = vec![0.0; stepper.y().len()];
    let mut limit = f64::INFINITY;
    // The step limit is worked out only at the step's end, the one place
    // it is read.
    let mut look = |time: f64, switching: &mut [f64]| -> Result<bool, (f64, OutputError)> {
        if time == t1 {
            state.copy_from_slice(stepper.y());
            limit = system
                .look_and_limit(time, &state, natural, switching)
                .map_err(|error| (time, error))?;
        } else {
            stepper.dense(time, &mut state);
            system
                .look(time, &state, natural, switching)
                .map_err(|error| (time, error))?;
        }
        Ok(crossed(&armed.borrow(), switching).next().is_some())
    };
    // The first look at `times` with a negative switching value, and the
    // time of the look before.
    let scan = |from: f64,
                times: &[f64],
                look: &mut Look<'_>,
                switching: &mut [f64]|
     -> Result<(f64, Option<f64>), (f64, OutputError)> {
        let mut clean = from;
        for &time in times {
            if look(time, switching)? {
                return Ok((clean, Some(time)));
            }
            for (armed, &value) in armed.borrow_mut().iter_mut().zip(switching.iter()) {
                *armed |= value >= 0.0;
            }
            clean = time;
        }
        Ok((clean, None))
    };
    let across: Vec<f64> = (1..=LOOKS_PER_STEP)
        .map(|index| {
            if index == LOOKS_PER_STEP {
                t1
            } else {
                t0 + (t1 - t0) * index as f64 / LOOKS_PER_STEP as f64
            }
        })
        .collect();
    let (mut left, crossing) = scan(t0, &across, &mut look, switching)?;
    let Some(mut right) = crossing else {
        return Ok(Err(limit));
    };
    loop {
        look(right, switching)?;
        let watched = armed.borrow().clone();
        let located = locate(&mut look, &watched, switching, left, right, t1 - t0)?;
        if located.left <= left {
            return Ok(Ok(located));
        }
        let (clean, earlier) = scan(
            left,
            &before_switch(left, located.left),
            &mut look,
            switching,
        )?;
        match earlier {
            Some(earlier) => {
                left = clean;
                right = earlier;
            }
            None => return Ok(Ok(located)),
        }
    }
}

/// Times in `(from, to)` to look at before a switch located at `to`:
/// evenly spaced, and crowding towards `to` (halving the distance each
/// time), where a switch that is undone by the located one begins.
fn before_switch(from: f64, to: f64) -> Vec<f64> {
    let width = to - from;
    let mut times: Vec<f64> = (1..LOOKS_BEFORE_SWITCH)
        .map(|index| from + width * index as f64 / LOOKS_BEFORE_SWITCH as f64)
        .chain((1..=LOOKS_CROWDING).map(|halvings| to - width * 0.5f64.powi(halvings as i32)))
        .filter(|&time| time > from && time < to)
        .collect();
    times.sort_by(f64::total_cmp);
    times.dedup();
    times
}

/// The switching values that are negative among those `armed`.
fn crossed<'v>(armed: &'v [bool], values: &'v [f64]) -> impl Iterator<Item = usize> + 'v {
    (0..values.len()).filter(|&index| values[index] < 0.0 && armed[index])
}

/// Locates the first time in `[left, right]` where one of the switching
/// values negative at `right` (in `switching` on entry) crosses zero, by
/// regula falsi (Illinois) on the least of them: a bracket no wider than
/// 1e-13 relative.
fn locate(
    look: &mut Look<'_>,
    armed: &[bool],
    switching: &mut [f64],
    mut left: f64,
    mut right: f64,
    step: f64,
) -> Result<Switch, (f64, OutputError)> {
    let crossed: Vec<usize> = crossed(armed, switching).collect();
    let least = |values: &[f64]| {
        crossed
            .iter()
            .map(|&index| values[index])
            .fold(f64::INFINITY, f64::min)
    };
    let mut g_right = least(switching);
    look(left, switching)?;
    let mut g_left = least(switching).max(0.0);
    let tolerance = 1e-13 * right.abs().max(step);
    let mut side = 0i8;
    for _ in 0..200 {
        if right - left <= tolerance {
            break;
        }
        let mut middle = right - g_right * (right - left) / (g_right - g_left);
        if !(middle > left && middle < right) {
            middle = 0.5 * (left + right);
        }
        look(middle, switching)?;
        let g = least(switching);
        if g < 0.0 {
            right = middle;
            g_right = g;
            if side == -1 {
                g_left *= 0.5;
            }
            side = -1;
        } else {
            left = middle;
            g_left = g;
            if side == 1 {
                g_right *= 0.5;
            }
            side = 1;
        }
    }
    look(right, switching)?;
    let index = crossed
        .iter()
        .copied()
        .min_by(|&a, &b| switching[a].total_cmp(&switching[b]))
        .unwrap_or(0);
    Ok(Switch { left, right, index })
}

/// The rate of change in time of the switching value that crossed at
/// `located`, on the step's continuous output.
pub(super) fn switching_slope(
    system: &mut Held<'_>,
    stepper: &Stepper,
    located: Switch,
    natural: &mut [Option<Code>],
    switching: &mut [f64],
) -> Result<f64, (f64, OutputError)> {
    let width = 1e-6 * (stepper.t() - stepper.t_previous());
    let mut state = vec![0.0; stepper.y().len()];
    let mut value = |time: f64| -> Result<f64, (f64, OutputError)> {
        stepper.dense(time, &mut state);
        system
            .look(time, &state, natural, switching)
            .map_err(|error| (time, error))?;
        Ok(switching[located.index])
    };
    let before = value(located.right - width)?;
    let after = value(located.right + width)?;
    Ok((after - before) / (2.0 * width))
}

/// A located switch: a bracket of its time, and the switching value that
/// crossed zero there.
#[derive(Clone, Copy, Debug)]
pub(super) struct Switch {
    /// Every held branch is valid here.
    pub(super) left: f64,
    /// The switching value `index` is negative here.
    pub(super) right: f64,
    /// The switching value that crossed.
    pub(super) index: usize,
}
