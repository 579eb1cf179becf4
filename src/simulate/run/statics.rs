//! A static equilibrium before the dynamics (`SIMULATE/STATICS`,
//! `--statics`): the parts at rest where every force balances, as Adams'
//! static analysis finds it from the initial conditions.
//!
//! With every velocity zero, the unknowns are each part's place (its
//! centre's displacement and a turn, in ground) and the DIFFs' states, and
//! the equations are the parts' accelerations and the DIFFs' rates, all
//! zero, with the joints held. Newton's method: the exact Jacobian of the
//! rates (the integrator's) in those unknowns, stacked with the joints'
//! rows `G`, solved in the least-squares sense (the accelerations of a
//! jointed part are dependent); each step halved until the largest
//! acceleration falls, and put back on the joints. An unstable equilibrium
//! is found as well as a stable one, as Newton finds it.

use nalgebra::{DMatrix, DVector, UnitQuaternion, Vector3};

use super::super::Model;
use super::super::constraints::{Imposed, body_quaternion, held_equations};
use super::super::equations::{BODY_STATES, Mechanics};
use super::super::error::SimulateError;
use crate::eval::OutputError;

/// How the static equilibrium was found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equilibrium {
    /// Newton's iterations.
    pub iterations: usize,
    /// The largest acceleration (of a part's centre, its angular one, or a
    /// DIFF's rate) left at the equilibrium.
    pub residual: f64,
}

/// Newton's iterations at most.
const ITERATIONS: usize = 100;

/// Sweeps of the singular value decomposition of Newton's matrix at most
/// (it converges in a few dozen; past this it is not going to).
const SVD_SWEEPS: usize = 10_000;

/// Halvings of a step that does not lower the largest acceleration.
const HALVINGS: usize = 20;

/// Settled: the largest acceleration at most this much of the scale (the
/// largest of gravity and the accelerations at the start).
const SETTLED: f64 = 1e-10;

/// A Newton step at most this much of the state's size that does not lower
/// the accelerations: rounding has the last word.
const STALLED: f64 = 1e-9;

/// A stalled Newton's iteration ends at an equilibrium only with the
/// accelerations at most this much of the scale.
const ROUNDED: f64 = 1e-6;

/// Why no equilibrium was found.
pub(super) enum Unsettled {
    /// The rates cannot be evaluated at a state.
    Evaluation(OutputError),
    /// The joints cannot be assembled at a state.
    Assembly(SimulateError),
    /// The accelerations' derivatives in the places are not finite numbers
    /// (forces or gravity beyond the floating-point range).
    NotFinite,
    /// Newton's iterations ended with state `state` still accelerating by
    /// `residual`.
    Moving { state: usize, residual: f64 },
}

/// The unknowns of the equilibrium and their equations.
struct Layout {
    diffs: usize,
    /// The DIFFs held at their values (`STATIC_HOLD`): their rates are no
    /// equations and their states no unknowns.
    held: Vec<bool>,
    offsets: Vec<usize>,
}

impl Layout {
    fn unknowns(&self) -> usize {
        self.diffs + 6 * self.offsets.len()
    }

    /// The rates that must vanish: the DIFFs', then each part's
    /// accelerations (`v'` in ground, `ω'` in its axes).
    fn residual(&self, rates: &[f64]) -> DVector<f64> {
        let parts = self
            .offsets
            .iter()
            .flat_map(|&offset| rates[offset + 7..offset + BODY_STATES].iter().copied());
        let diffs = rates[..self.diffs]
            .iter()
            .zip(&self.held)
            .map(|(rate, held)| if *held { 0.0 } else { *rate });
        DVector::from_iterator(self.unknowns(), diffs.chain(parts))
    }

    /// The state row of residual entry `entry`.
    fn state_of(&self, entry: usize) -> usize {
        if entry < self.diffs {
            entry
        } else {
            let part = (entry - self.diffs) / 6;
            self.offsets[part] + 7 + (entry - self.diffs) % 6
        }
    }

    /// `dy/dz`: how the states move with the unknowns (a turn `δθ` in
    /// ground moves the quaternion by `½ (0, δθ) ⊗ q`).
    fn tangent(&self, y: &[f64]) -> DMatrix<f64> {
        let mut tangent = DMatrix::zeros(y.len(), self.unknowns());
        for diff in (0..self.diffs).filter(|diff| !self.held[*diff]) {
            tangent[(diff, diff)] = 1.0;
        }
        for (part, &offset) in self.offsets.iter().enumerate() {
            let column = self.diffs + 6 * part;
            let (w, v) = (
                y[offset + 3],
                Vector3::new(y[offset + 4], y[offset + 5], y[offset + 6]),
            );
            for k in 0..3 {
                tangent[(offset + k, column + k)] = 1.0;
                let axis = Vector3::ith(k, 1.0);
                let turned = axis * w + axis.cross(&v);
                tangent[(offset + 3, column + 3 + k)] = -0.5 * v[k];
                for i in 0..3 {
                    tangent[(offset + 4 + i, column + 3 + k)] = 0.5 * turned[i];
                }
            }
        }
        tangent
    }

    /// The unknowns' way the `residual` accelerates them: each DIFF along
    /// its rate, each part's centre along its acceleration and its turn
    /// about its angular acceleration (in ground).
    fn accelerated(&self, y: &[f64], residual: &DVector<f64>) -> DVector<f64> {
        let mut along = residual.clone();
        for (part, &offset) in self.offsets.iter().enumerate() {
            let column = self.diffs + 6 * part;
            let q = body_quaternion(&y[offset..]);
            let in_body = Vector3::new(
                residual[column + 3],
                residual[column + 4],
                residual[column + 5],
            );
            along.rows_mut(column + 3, 3).copy_from(&(q * in_body));
        }
        along
    }

    /// `y` moved by `step` of the unknowns, the velocities zero.
    fn moved(&self, y: &[f64], step: &DVector<f64>) -> Vec<f64> {
        let mut moved = y.to_vec();
        for diff in 0..self.diffs {
            moved[diff] += step[diff];
        }
        for (part, &offset) in self.offsets.iter().enumerate() {
            let column = self.diffs + 6 * part;
            for k in 0..3 {
                moved[offset + k] += step[column + k];
            }
            let turn = Vector3::new(step[column + 3], step[column + 4], step[column + 5]);
            let q = body_quaternion(&y[offset..]);
            let turned = UnitQuaternion::from_scaled_axis(turn) * q;
            moved[offset + 3] = turned.w;
            moved[offset + 4] = turned.i;
            moved[offset + 5] = turned.j;
            moved[offset + 6] = turned.k;
        }
        rest(&mut moved, &self.offsets);
        moved
    }
}

/// Every part's velocities zero.
fn rest(y: &mut [f64], offsets: &[usize]) {
    for &offset in offsets {
        y[offset + 7..offset + BODY_STATES].fill(0.0);
    }
}

fn largest(vector: &DVector<f64>) -> f64 {
    vector
        .iter()
        .fold(0.0_f64, |most, value| most.max(value.abs()))
}

/// Puts `y` at a static equilibrium of `model` at time 0: its parts at
/// rest, their places and the DIFFs' states where every acceleration
/// vanishes; `assemble` puts a state back on the joints.
pub(super) fn settle(
    model: &Model,
    mechanics: &mut Mechanics<'_>,
    y: &mut Vec<f64>,
    offsets: &[usize],
    imposed: &Imposed<'_>,
    assemble: &mut dyn FnMut(&mut [f64]) -> Result<(), SimulateError>,
) -> Result<Equilibrium, Unsettled> {
    let layout = Layout {
        diffs: model.diffs.len(),
        held: model.diffs.iter().map(|diff| diff.static_hold).collect(),
        offsets: offsets.to_vec(),
    };
    let n = y.len();
    let mut rates = vec![0.0; n];
    let mut residual_at = |mechanics: &mut Mechanics<'_>, y: &[f64]| {
        mechanics
            .rates(0.0, y, None, &mut rates)
            .map_err(Unsettled::Evaluation)?;
        Ok(layout.residual(&rates))
    };
    rest(y, offsets);
    assemble(y).map_err(Unsettled::Assembly)?;
    rest(y, offsets);
    let mut residual = residual_at(mechanics, y)?;
    let scale = largest(&residual)
        .max(model.gravity.amax())
        .max(f64::MIN_POSITIVE);
    let mut jacobian = DMatrix::zeros(n, n);
    let mut stalled = false;
    let mut iterations = 0;
    for iteration in 0..ITERATIONS {
        iterations = iteration;
        if largest(&residual) <= SETTLED * scale {
            return Ok(Equilibrium {
                iterations: iteration,
                residual: largest(&residual),
            });
        }
        mechanics
            .jacobian(0.0, y, None, &mut jacobian)
            .map_err(Unsettled::Evaluation)?;
        let tangent = layout.tangent(y);
        let rows: Vec<usize> = (0..layout.unknowns())
            .map(|entry| layout.state_of(entry))
            .collect();
        let mut accelerations = jacobian.select_rows(&rows) * &tangent;
        // A held DIFF's rate is no equation.
        for diff in (0..layout.diffs).filter(|diff| layout.held[*diff]) {
            accelerations.row_mut(diff).fill(0.0);
        }
        let (held, g) = held_equations(model, y, offsets, imposed);
        // The joints' rows, weighed as the accelerations' so that the
        // least squares keep them.
        let weight = accelerations.amax().max(1.0) / g.amax().max(f64::MIN_POSITIVE);
        let m = held.len();
        let unknowns = layout.unknowns();
        let mut stacked = DMatrix::zeros(unknowns + m, unknowns);
        stacked
            .view_mut((0, 0), (unknowns, unknowns))
            .copy_from(&accelerations);
        let mut target = DVector::zeros(unknowns + m);
        target.rows_mut(0, unknowns).copy_from(&(-&residual));
        for r in 0..m {
            for part in 0..offsets.len() {
                for k in 0..6 {
                    stacked[(unknowns + r, layout.diffs + 6 * part + k)] =
                        weight * g[(r, 6 * part + k)];
                }
            }
            target[unknowns + r] = -weight * held[r];
        }
        if !stacked
            .iter()
            .chain(target.iter())
            .all(|value| value.is_finite())
        {
            return Err(Unsettled::NotFinite);
        }
        let newton = nalgebra::SVD::try_new(stacked, true, true, f64::EPSILON, SVD_SWEEPS)
            .and_then(|svd| {
                let tiny = 1e-12 * svd.singular_values.amax();
                svd.solve(&target, tiny).ok()
            })
            .unwrap_or_else(|| DVector::zeros(unknowns));
        let before = largest(&residual);
        let size = y.iter().fold(1.0_f64, |most, value| most.max(value.abs()));
        // Newton's step, each halved until the largest acceleration falls;
        // where it does not (its Jacobian singular, as a pendulum's at the
        // top of its swing), the way the parts accelerate, as far as a
        // tenth of the model's size, halved likewise.
        let along = layout.accelerated(y, &residual);
        let relaxation = &along * (0.1 * size / largest(&along).max(f64::MIN_POSITIVE));
        let mut accepted = false;
        for step in [&newton, &relaxation] {
            let mut fraction = 1.0;
            for _ in 0..HALVINGS {
                let mut trial = layout.moved(y, &(step * fraction));
                if assemble(&mut trial).is_ok() {
                    rest(&mut trial, offsets);
                    if let Ok(after) = residual_at(mechanics, &trial)
                        && after.norm() < residual.norm()
                    {
                        *y = trial;
                        residual = after;
                        accepted = true;
                        break;
                    }
                }
                fraction *= 0.5;
            }
            if accepted {
                break;
            }
        }
        let step = newton;
        if !accepted {
            // Rounding: a step too small to move the parts is the end.
            stalled = largest(&step) <= STALLED * size && before <= ROUNDED * scale;
            break;
        }
    }
    let (entry, most) =
        residual
            .iter()
            .enumerate()
            .fold((0, 0.0_f64), |(at, most), (entry, value)| {
                if value.abs() > most {
                    (entry, value.abs())
                } else {
                    (at, most)
                }
            });
    if most <= SETTLED * scale || stalled {
        return Ok(Equilibrium {
            iterations,
            residual: most,
        });
    }
    Err(Unsettled::Moving {
        state: layout.state_of(entry),
        residual: most,
    })
}
