//! Locating branch switches: after each accepted step the switching values
//! of the held branches are looked at on the step's continuous output; the
//! first sign change is bracketed and located by regula falsi to about
//! 1e-13 relative in time. A sign change of a value that is rounding noise
//! (one that moving the state changes only by rounding) is no switch
//! ([`PROBE`]).

use nalgebra::DMatrix;

use crate::eval::OutputError;
use crate::integrate::linalg::Pattern;
use crate::integrate::{Stepper, System};
use crate::laws::branch::Code;
use crate::simulate::equations::Mechanics;

/// A look at the switching values at a time: whether one that is watched
/// is negative there.
type Look<'l> = dyn FnMut(f64, &mut [f64]) -> Result<bool, (f64, OutputError)> + 'l;

/// Points inside each step at which the switching values are looked at
/// (besides its end): a switching function that changes sign twice within
/// one step is caught when one of them falls between its two roots.
const LOOKS_PER_STEP: usize = 4;

/// The look near each end of a step, as a part of the spacing of the
/// looks: it tells whether a switching value falls or rises there.
const EDGE_LOOK: f64 = 1e-3;

/// The most looks spent seeking one switching value's minimum between
/// looks, the width (relative to the first) at which the search stops,
/// and the relative fall of the least value below which it has settled.
const DIP_LOOKS: usize = 40;
const DIP_WIDTH: f64 = 1e-9;
const DIP_SETTLED: f64 = 1e-3;

/// A switching value whose looks on both sides of its least one lie above
/// it by no more than this part of it is flat there to rounding: its
/// minimum between them is sought no further. Switching values
/// worked out from positions far larger than themselves wobble by rounding
/// (1e-15 to 1e-12 of a 5 cm gap between balls 30 to 500 m up), and such a
/// wobble had each of them searched with all [`DIP_LOOKS`] looks, a whole
/// evaluation each; a hidden crossing shows a look at least 5e-5 of the
/// value above it on one side (the random balls of the tests).
const DIP_FLAT: f64 = 1e-9;

/// A switching value that has just gone negative is rounding noise, and
/// its crossing no switch, when moving the state by `PROBE` of each
/// state's size changes it by no more than `LINEAR` times what a move of a
/// hundredth of that does: a smooth value's change grows with the move, a
/// value that is 0 wherever the model is near (a pin's axial force in a
/// planar swing on a skewed axis, read by ABS) changes only by its terms'
/// rounding however the state moves. Rounding crossed such a value back
/// and forth: 18 457 located switches in 2 s of a pendulum, 52 s of run
/// time. A value that does not change at all (a function of time) is no
/// noise, nor is one larger than `LINEAR` times its change: the state's
/// weak hold on a value driven by time (`SIN(TIME) + 1e-12*DX(2)`) is
/// below rounding, but the value's first negative look is not.
const PROBE: f64 = 1e-8;
const LINEAR: f64 = 10.0;

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
    /// The end of the last step without a switch, the time of the look just
    /// before it and the switching values there: where the next step
    /// starts, whether each value was falling or rising.
    pub(super) before_end: Option<(f64, f64, Vec<f64>)>,
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

    fn rounding_floor(
        &mut self,
        t: f64,
        y: &[f64],
        floor: &mut [f64],
        carried: &mut [f64],
    ) -> Result<(), OutputError> {
        self.mechanics
            .rounding_floor(t, y, Some(&self.held), floor, carried)
    }

    fn norm_groups(&mut self) -> Vec<std::ops::Range<usize>> {
        self.mechanics.norm_groups()
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
/// step, and once more a little before its end (and, after a restart, a
/// little after its start), so that each value's trend at the step's ends
/// is known. A switching value can cross zero and come back between two
/// looks (a penetration that passes the end of the damping ramp for a
/// moment): wherever a value's looks have a least one inside the step,
/// its minimum there is sought (parabolic and golden-section steps,
/// [`dip`]) before the step is taken as clean, as event locators do for a
/// double crossing. Once a crossing is located, the stretch before it is
/// looked at again, evenly and crowding towards the crossing: a switch and
/// its return come most often just before another switch (a contact's
/// clamp releases just before the body leaves the stop).
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
    // The look just before the last step's end, when this step continues
    // it on the same branches.
    let carried = system
        .before_end
        .take()
        .filter(|(end, ..)| *end == t0)
        .map(|(_, time, values)| (time, values));
    let mut state = vec![0.0; stepper.y().len()];
    let mut limit = f64::INFINITY;
    // While scanning the step (not while locating a crossing, where the
    // values are small by design), a crossing is first probed for noise.
    // Its scratch room is made at the first crossing a step has.
    let probing = std::cell::Cell::new(true);
    let mut probe: Option<Probe> = None;
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
        if probing.get() {
            let crossed_now: Vec<usize> = crossed(&armed.borrow(), switching).collect();
            if !crossed_now.is_empty() {
                let probe = probe.get_or_insert_with(|| {
                    Probe::new(
                        state.len(),
                        natural.len(),
                        switching.len(),
                        system.tolerance,
                    )
                });
                let noise = probe.noise(system, time, &state, switching, &crossed_now);
                let mut armed = armed.borrow_mut();
                for index in noise {
                    armed[index] = false;
                }
            }
        }
        Ok(crossed(&armed.borrow(), switching).next().is_some())
    };
    let spacing = (t1 - t0) / LOOKS_PER_STEP as f64;
    let edge = EDGE_LOOK * spacing;
    let mut times: Vec<f64> = Vec::with_capacity(LOOKS_PER_STEP + 2);
    if carried.is_none() {
        times.push(t0 + edge);
    }
    times.extend((1..LOOKS_PER_STEP).map(|index| t0 + spacing * index as f64));
    times.extend([t1 - edge, t1]);
    // Every look so far in time order, the one before the step's start
    // first when there is one.
    let mut samples: Vec<(f64, Vec<f64>)> = carried.into_iter().collect();
    samples.push((t0, start.to_vec()));
    let mut crossing = None;
    for time in times {
        let crossed = look(time, switching)?;
        samples.push((time, switching.to_vec()));
        if crossed {
            crossing = Some(time);
            break;
        }
        for (armed, &value) in armed.borrow_mut().iter_mut().zip(switching.iter()) {
            *armed |= value >= 0.0;
        }
    }
    let watched = armed.borrow().clone();
    let dipped = find_dip(&mut look, &watched, &samples, t0, switching)?;
    let (mut left, mut right) = match (dipped, crossing) {
        (Some(bracket), _) => bracket,
        (None, Some(time)) => (samples[samples.len() - 2].0.max(t0), time),
        (None, None) => {
            // The last look was at t1 (or, after a search, is put back).
            let (_, at_end) = &samples[samples.len() - 1];
            switching.copy_from_slice(at_end);
            let (time, values) = &samples[samples.len() - 2];
            system.before_end = Some((t1, *time, values.clone()));
            return Ok(Err(limit));
        }
    };
    loop {
        probing.set(false);
        look(right, switching)?;
        let watched = armed.borrow().clone();
        let located = locate(&mut look, &watched, switching, left, right, t1 - t0)?;
        probing.set(true);
        if located.left <= left {
            return Ok(Ok(located));
        }
        let (clean, earlier) = scan_before(
            left,
            &before_switch(left, located.left),
            &mut look,
            &armed,
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

/// The probe of switching values for rounding noise ([`PROBE`],
/// [`LINEAR`]): scratch room for the moved state and its looks.
struct Probe {
    moved: Vec<f64>,
    natural: Vec<Option<Code>>,
    values: Vec<f64>,
    tolerance: f64,
}

impl Probe {
    fn new(states: usize, sites: usize, switches: usize, tolerance: f64) -> Probe {
        Probe {
            moved: vec![0.0; states],
            natural: vec![None; sites],
            values: vec![0.0; switches],
            tolerance,
        }
    }

    /// Which of the switching values `crossed` (negative in `switching`,
    /// looked at `(time, state)`) are rounding noise ([`PROBE`],
    /// [`LINEAR`]): each one's largest change ([`Probe::changes`]) at two
    /// sizes of the move a hundredfold apart. A look that fails at a moved
    /// state finds none.
    fn noise(
        &mut self,
        system: &mut Held<'_>,
        time: f64,
        state: &[f64],
        switching: &[f64],
        crossed: &[usize],
    ) -> Vec<usize> {
        // The larger move first: a value larger than `LINEAR` times its
        // change is no noise, whatever the smaller move shows (a genuine
        // crossing's first negative look mostly is), and needs no more
        // looks.
        let Some(large) = self.changes(system, time, state, switching, crossed, PROBE) else {
            return Vec::new();
        };
        let suspects: Vec<(usize, f64)> = crossed
            .iter()
            .zip(large)
            .filter(|&(&index, large)| switching[index].abs() <= LINEAR * large)
            .map(|(&index, large)| (index, large))
            .collect();
        if suspects.is_empty() {
            return Vec::new();
        }
        let indices: Vec<usize> = suspects.iter().map(|&(index, _)| index).collect();
        let Some(small) = self.changes(system, time, state, switching, &indices, PROBE * 1e-2)
        else {
            return Vec::new();
        };
        suspects
            .into_iter()
            .zip(small)
            .filter(|&((_, large), small)| large < LINEAR * small)
            .map(|((index, _), _)| index)
            .collect()
    }

    /// The largest change of each switching value `indices` when every
    /// state moves by `size` of its size (the tolerance at least), all one
    /// way, then every other one the other way; `None` when a look fails
    /// at a moved state.
    fn changes(
        &mut self,
        system: &mut Held<'_>,
        time: f64,
        state: &[f64],
        switching: &[f64],
        indices: &[usize],
        size: f64,
    ) -> Option<Vec<f64>> {
        let mut change = vec![0.0_f64; indices.len()];
        for alternate in [false, true] {
            for (k, (moved, &value)) in self.moved.iter_mut().zip(state).enumerate() {
                let sign = if alternate && k % 2 == 1 { -1.0 } else { 1.0 };
                *moved = value + sign * size * value.abs().max(self.tolerance);
            }
            system
                .look(time, &self.moved, &mut self.natural, &mut self.values)
                .ok()?;
            for (largest, &index) in change.iter_mut().zip(indices) {
                *largest = largest.max((self.values[index] - switching[index]).abs());
            }
        }
        Some(change)
    }
}

/// The first look at `times` with a watched switching value negative, and
/// the time of the look before (`from` for the first).
fn scan_before(
    from: f64,
    times: &[f64],
    look: &mut Look<'_>,
    armed: &std::cell::RefCell<Vec<bool>>,
    switching: &mut [f64],
) -> Result<(f64, Option<f64>), (f64, OutputError)> {
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
}

/// A crossing hidden between the looks `samples` (time order; those at
/// or after `t0` on the step's continuous output): wherever a watched
/// switching value is least at a look with a look on either side, its
/// minimum between those two is sought; the first time found at which a
/// watched value is negative, with the look before it (where none is),
/// as a bracket `(left, right)`.
fn find_dip(
    look: &mut Look<'_>,
    watched: &[bool],
    samples: &[(f64, Vec<f64>)],
    t0: f64,
    switching: &mut [f64],
) -> Result<Option<(f64, f64)>, (f64, OutputError)> {
    for at in 1..samples.len().saturating_sub(1) {
        let [(before, low), (_, middle), (after, high)] =
            [&samples[at - 1], &samples[at], &samples[at + 1]];
        for index in (0..watched.len()).filter(|&index| watched[index]) {
            let value = middle[index];
            if !(value >= 0.0 && low[index] > value && high[index] >= value) {
                continue;
            }
            let from = before.max(t0);
            let ends = (
                (
                    from,
                    if *before < t0 {
                        value.max(low[index])
                    } else {
                        low[index]
                    },
                ),
                (*after, high[index]),
            );
            if let Some(negative) = dip(look, switching, index, ends, (samples[at].0, value))? {
                return Ok(Some((from, negative)));
            }
        }
    }
    Ok(None)
}

/// Seeks the minimum of switching value `index` in `(a, b)` from a look
/// `middle` below both ends, by parabolic steps through the three best
/// looks with golden-section steps where a parabola does not help; stops
/// at the first look with a watched value negative (its time) or when the
/// minimum has settled above zero, or its bracket is [`flat`] (`None`).
fn dip(
    look: &mut Look<'_>,
    switching: &mut [f64],
    index: usize,
    ((mut a, mut fa), (mut b, mut fb)): ((f64, f64), (f64, f64)),
    (mut m, mut fm): (f64, f64),
) -> Result<Option<f64>, (f64, OutputError)> {
    const GOLDEN: f64 = 0.381_966_011_250_105_1;
    let width = b - a;
    let mut settled = 0;
    for _ in 0..DIP_LOOKS {
        if b - a <= DIP_WIDTH * width || flat(fa, fm, fb) {
            break;
        }
        let (left, right) = (m - a, b - m);
        let numerator = left * left * (fm - fb) - right * right * (fm - fa);
        let denominator = left * (fm - fb) + right * (fm - fa);
        let parabolic = m - 0.5 * numerator / denominator;
        let guard = 1e-3 * (b - a);
        let u = if parabolic.is_finite()
            && parabolic > a + guard
            && parabolic < b - guard
            && (parabolic - m).abs() > guard
        {
            parabolic
        } else if right > left {
            m + GOLDEN * right
        } else {
            m - GOLDEN * left
        };
        if look(u, switching)? {
            return Ok(Some(u));
        }
        let fu = switching[index];
        if fu < fm {
            settled = if fm - fu <= DIP_SETTLED * fu {
                settled + 1
            } else {
                0
            };
            if u < m {
                (b, fb) = (m, fm);
            } else {
                (a, fa) = (m, fm);
            }
            (m, fm) = (u, fu);
        } else if u < m {
            (a, fa) = (u, fu);
        } else {
            (b, fb) = (u, fu);
        }
        if settled >= 2 {
            break;
        }
    }
    Ok(None)
}

/// Whether the looks `fa` and `fb` either side of the least one `fm` lie
/// above it by no more than [`DIP_FLAT`] of it.
fn flat(fa: f64, fm: f64, fb: f64) -> bool {
    fa.max(fb) - fm <= DIP_FLAT * fm
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
