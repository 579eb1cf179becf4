//! The equations of motion of a [`Model`], written once over any
//! [`Number`]: over `f64` they are the right-hand side `dy/dt = f(t, y)`,
//! over dual numbers seeded in the states they give its exact Jacobian.
//!
//! The state is, in order: the value of each DIFF; then for each body its
//! centre of mass in ground (3), its orientation as a quaternion `w x y z`
//! (4), the velocity of its centre of mass in ground (3) and its angular
//! velocity in its own axes (3). A body moves by Newton's and Euler's
//! equations about its centre of mass:
//!
//! ```text
//! p' = v          q' = q ⊗ (0, ω) / 2          (R from q/|q|)
//! v' = F/m + g    ω' = I⁻¹ (Rᵀ τ − ω × I ω)
//! ```
//!
//! where `F` and `τ` (about the centre of mass, in ground) sum the force
//! elements acting on the body. The expressions see each body through its
//! state inputs `BODY.x` ... `BODY.wz` (the origin of the body frame, a
//! small rotation about the current orientation, the origin's velocity, the
//! angular velocity in ground): they are computed from the state here, with
//! their derivative parts, so the program's derivatives flow into the
//! Jacobian by the chain rule with no hand-written derivative.

mod accelerations;
mod bodies;
mod contact;
mod element_values;
mod forces;
mod sparsity;

use std::sync::{Arc, RwLock};

use nalgebra::{DMatrix, Matrix3, Vector3};
use num_dual::{DualDVec64, DualSVec64};

use crate::compile::{Program, RunCall};
use crate::eval::EvalError;
use crate::eval::{DelayRecord, Evaluator, OutputError, SharedRecord};
use crate::integrate::linalg::Pattern;
use crate::laws::branch::Code;
use crate::laws::contact::ContactBranch;
use crate::number::{Directional, Number};
use crate::scene::{StateComponent, is_run_state_input, parse_sensor_input};
use crate::simulate::constraints::{
    BodyMotion, Component, CurveSite, Drives, Holder, Reactions, Unheld, acceleration_residual,
    body_quaternion, constraint_loads, curve_contacts, curve_sites, holders, joints_failed_in,
    joints_overflow_in, joints_singular_in, multiplier_loads,
};
use crate::simulate::model::{Contact, Force, Model};
use accelerations::{Accelerations, Measure};
pub(crate) use bodies::{BODY_STATES, KINEMATIC_RATES, body_offset};
use bodies::{Kinematics, Loads};
use element_values::{ELEMENT_FUNCTIONS, ElementComponent, NetForce};
use sparsity::Sparsity;

/// Where a program input's value comes from.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Source {
    /// `TIME`.
    Time,
    /// A constant (a user variable of the scene).
    Constant(f64),
    /// The state component at this index (a DIFF).
    State(usize),
    /// A body's state input.
    Body(usize, StateComponent),
    /// A value of the running solver (a reaction, a measure of
    /// accelerations), the one at this index of [`Mechanics::solver_calls`]
    /// (only in the programs of output columns, which have no Jacobian).
    Solver(usize),
    /// `SENVAL` of the sensor at this index of the model's sensors: its
    /// EVALUATE's value at its last trip (0 before the first).
    Sensor(usize),
}

/// The equations of motion of a model, with its compiled expressions.
pub(crate) struct Mechanics<'m> {
    equations: Equations<'m>,
    values: Evaluator<'m, f64>,
    buffers: Buffers<f64>,
    /// The Jacobian's pattern and evaluator, built when first asked for.
    /// The count is the number of directions the evaluator seeds.
    jacobian: Option<(Sparsity, DualEvaluator<'m>, usize)>,
    /// The Jacobian is the index-1 form's in the states, the joints'
    /// multipliers and the massless parts' accelerations (algebraic
    /// unknowns after the states), as sparse as the joints, rather than the
    /// ODE's with them eliminated (dense along a chain): for a constrained
    /// model without loop values.
    bordered: bool,
    /// The values of the running solver the program itself reads (a
    /// force that reads a joint's reaction, as joint friction does), each
    /// solved with the motion it acts on ([`Mechanics::settle`]).
    loop_values: Vec<RunValue>,
    /// The loop values at the last state settled: the next state's first
    /// guess.
    settled: Vec<f64>,
    /// `I − ∂g/∂z` of the last settling, factorised: Newton's matrix of the
    /// map `g` from the loop values the forces read to those they give,
    /// kept from state to state while Newton's iterations contract with it.
    settling_matrix: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    /// The run's record of the program's DELAYs, shared by its evaluators
    /// (`None`: the program has none).
    delays: Option<SharedRecord>,
    /// Each part's joints' reactions per unit of mass and of inertia
    /// (`|R| / m` and `(|τ_R| + |R| a) ‖I⁻¹‖`), where the rounding floor was
    /// last taken ([`Mechanics::rounding_floor`]): how hard they push the
    /// part along its free path per radian its joints drift.
    reaction_push: Vec<[f64; 2]>,
}

/// At most this many of Newton's iterations settle the loop values at one
/// state.
const SETTLING_ITERATIONS: usize = 30;

/// The evaluator of the Jacobian's dual numbers: a size fixed at compile
/// time for up to 4 directions (DIFFs only), for one, two and three body
/// colours (13, 26 and 39: the unused directions of a smaller count stay
/// zero) and for bodies with the joints' multipliers (72: a chain of
/// revolute joints needs four body colours and three of the multipliers,
/// 67 directions), so that no dual operation allocates; dynamic beyond.
enum DualEvaluator<'m> {
    One(Evaluator<'m, DualSVec64<1>>),
    Two(Evaluator<'m, DualSVec64<2>>),
    Three(Evaluator<'m, DualSVec64<3>>),
    Four(Evaluator<'m, DualSVec64<4>>),
    OneBody(Evaluator<'m, DualSVec64<13>>),
    TwoBodies(Evaluator<'m, DualSVec64<26>>),
    ThreeBodies(Evaluator<'m, DualSVec64<39>>),
    Joined(Evaluator<'m, DualSVec64<72>>),
    Many(Evaluator<'m, DualDVec64>),
}

/// `$body` with `$evaluator` bound to the evaluator `$duals` holds,
/// whatever its size: one arm per variant.
macro_rules! with_evaluator {
    ($duals:expr, $evaluator:ident => $body:expr) => {
        match $duals {
            DualEvaluator::One($evaluator) => $body,
            DualEvaluator::Two($evaluator) => $body,
            DualEvaluator::Three($evaluator) => $body,
            DualEvaluator::Four($evaluator) => $body,
            DualEvaluator::OneBody($evaluator) => $body,
            DualEvaluator::TwoBodies($evaluator) => $body,
            DualEvaluator::ThreeBodies($evaluator) => $body,
            DualEvaluator::Joined($evaluator) => $body,
            DualEvaluator::Many($evaluator) => $body,
        }
    };
}

impl<'m> DualEvaluator<'m> {
    /// The evaluator for `directions` directions, and the count it seeds,
    /// reading the run's record of the program's DELAYs when it has one.
    fn for_directions(
        program: &'m Program,
        directions: usize,
        delays: Option<&SharedRecord>,
    ) -> (DualEvaluator<'m>, usize) {
        let (mut duals, count) = Self::of_size(program, directions);
        if let Some(record) = delays {
            with_evaluator!(&mut duals, evaluator => evaluator.share_delays(record.clone()));
        }
        (duals, count)
    }

    /// The evaluator for `directions` directions, and the count it seeds.
    fn of_size(program: &'m Program, directions: usize) -> (DualEvaluator<'m>, usize) {
        match directions {
            0 | 1 => (DualEvaluator::One(program.evaluator()), 1),
            2 => (DualEvaluator::Two(program.evaluator()), 2),
            3 => (DualEvaluator::Three(program.evaluator()), 3),
            4 => (DualEvaluator::Four(program.evaluator()), 4),
            5..=13 => (DualEvaluator::OneBody(program.evaluator()), 13),
            14..=26 => (DualEvaluator::TwoBodies(program.evaluator()), 26),
            27..=39 => (DualEvaluator::ThreeBodies(program.evaluator()), 39),
            40..=72 => (DualEvaluator::Joined(program.evaluator()), 72),
            _ => (DualEvaluator::Many(program.evaluator()), directions),
        }
    }
}

impl<'m> Mechanics<'m> {
    /// The equations of `model`, whose DIFF functions and force components
    /// `program` computes (output `k` is the expression `computed[k]`).
    pub(crate) fn new(model: &'m Model, program: &'m Program, computed: &[usize]) -> Mechanics<'m> {
        let mut output_of = vec![None; model.expressions.len()];
        for (output, &expression) in computed.iter().enumerate() {
            output_of[expression] = Some(output);
        }
        let mut solver_calls = Vec::new();
        let sources: Vec<Source> = program
            .inputs()
            .iter()
            .map(|name| {
                if let Some(call) = RunCall::parse(name) {
                    solver_calls.push(call);
                    Source::Solver(solver_calls.len() - 1)
                } else if name.eq_ignore_ascii_case("TIME") {
                    Source::Time
                } else if let Some(id) = parse_sensor_input(name) {
                    model
                        .sensors
                        .iter()
                        .position(|sensor| sensor.id == id && sensor.evaluate.is_some())
                        .map_or(Source::Constant(0.0), Source::Sensor)
                } else if is_run_state_input(name) {
                    let index = model.diffs.iter().position(|diff| diff.input() == *name);
                    Source::State(index.expect("the compiler binds only states of the model"))
                } else if let Some((body, component)) = model.scene.parse_state_name(name) {
                    Source::Body(body, component)
                } else {
                    Source::Constant(model.scene.value_of(name).unwrap_or(0.0))
                }
            })
            .collect();
        let diff_outputs = model
            .diffs
            .iter()
            .map(|diff| output_of[diff.function])
            .collect();
        let state_free = program
            .inputs_of_outputs()
            .iter()
            .map(|inputs| {
                inputs.iter().all(|&input| {
                    matches!(
                        sources[input],
                        Source::Time | Source::Constant(_) | Source::Sensor(_)
                    )
                })
            })
            .collect();
        let implicit_rates = model
            .diffs
            .iter()
            .map(|diff| {
                diff.implicit?;
                let name = crate::scene::diff_rate_input(diff.id);
                let input = program.inputs().iter().position(|input| *input == name)?;
                match sources[input] {
                    Source::Solver(index) => Some((input, index)),
                    _ => None,
                }
            })
            .collect();
        let inverse_inertia = model.inverse_inertia();
        let loop_values: Vec<RunValue> = solver_calls
            .iter()
            .map(|call| RunValue::of(model, call).expect("checked when compiled"))
            .collect();
        let delay_count = program.delays().len();
        let delays =
            (delay_count > 0).then(|| Arc::new(RwLock::new(DelayRecord::new(delay_count))));
        let mut values = program.evaluator();
        if let Some(record) = &delays {
            values.share_delays(record.clone());
        }
        let bordered = model.is_constrained() && loop_values.is_empty();
        Mechanics {
            bordered,
            equations: Equations {
                model,
                program,
                sources,
                state_free,
                diff_outputs,
                implicit_rates,
                rate_scales: vec![None; model.diffs.len()],
                output_of,
                inverse_inertia,
                joint_arms: joint_arms(model),
                drives: Drives::held_by(model, program, computed),
                solver_calls,
                contacts: model
                    .forces
                    .iter()
                    .filter_map(|force| match force {
                        Force::Contact(contact) => Some(&**contact),
                        _ => None,
                    })
                    .collect(),
                curves: curve_sites(model),
                sensed: vec![0.0; model.sensors.len()],
                massless: (0..model.masses.len())
                    .filter(|&body| model.masses[body].is_massless())
                    .collect(),
            },
            values,
            buffers: Buffers::new(program),
            jacobian: None,
            settled: loop_values
                .iter()
                .map(|value| match value {
                    RunValue::ImplicitRate(diff) => model.diffs[*diff].implicit.unwrap_or(0.0),
                    _ => 0.0,
                })
                .collect(),
            loop_values,
            settling_matrix: None,
            delays,
            reaction_push: vec![[0.0; 2]; model.scene.bodies.len()],
        }
    }

    /// Stores `value` as `SENVAL` of the model's sensor `sensor` (its
    /// EVALUATE's value at a trip), which the program reads from then on.
    pub(crate) fn store_sensor_value(&mut self, sensor: usize, value: f64) {
        self.equations.sensed[sensor] = value;
    }

    /// Whether the program has DELAYs, whose expressions the run records.
    pub(crate) fn has_delays(&self) -> bool {
        self.delays.is_some()
    }

    /// Evaluates the program at `(t, y)` and records its DELAYs'
    /// expressions there (`starts`: the state begins a new piece of the
    /// record, at a kink of this level: [`DelayRecord::record`]).
    pub(crate) fn record_delays(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        starts: Option<u8>,
    ) -> Result<(), OutputError> {
        if self.delays.is_none() {
            return Ok(());
        }
        let mut rates = vec![0.0; y.len()];
        self.rates(t, y, held, &mut rates)?;
        self.sample_delays(t, starts);
        Ok(())
    }

    /// Records the DELAYs' expressions as the last evaluation, at `t`,
    /// left them ([`Mechanics::record_delays`]).
    pub(crate) fn sample_delays(&mut self, t: f64, starts: Option<u8>) {
        let Some(record) = &self.delays else {
            return;
        };
        let (mut values, mut delays) = (Vec::new(), Vec::new());
        self.values.delay_samples(&mut values, &mut delays);
        record
            .write()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
            .record(t, &values, &delays, starts);
    }

    /// The first time more than `gap` after `t` at which a DELAY reads
    /// across a kink in its record, and the kink's level
    /// ([`DelayRecord::next_kink`]).
    pub(crate) fn next_delay_kink(&self, t: f64, gap: f64) -> Option<(f64, u8)> {
        self.read_delays(|record| record.next_kink(t, gap))
    }

    /// The lowest level of the kinks a DELAY reads across within `gap` of
    /// `t` ([`DelayRecord::kink_at`]).
    pub(crate) fn delay_kink_at(&self, t: f64, gap: f64) -> Option<u8> {
        self.read_delays(|record| record.kink_at(t, gap))
    }

    /// What `read` finds in the DELAYs' record (`None` without DELAYs).
    fn read_delays<R>(&self, read: impl FnOnce(&DelayRecord) -> Option<R>) -> Option<R> {
        self.delays.as_ref().and_then(|record| {
            read(
                &record
                    .read()
                    .unwrap_or_else(|poisoned| poisoned.into_inner()),
            )
        })
    }

    /// The smallest positive delay of the program's DELAYs at the last
    /// state recorded (infinity for none): the run's steps are held below
    /// it, so that the values a DELAY reads lie in the record.
    pub(crate) fn smallest_delay(&self) -> f64 {
        self.delays.as_ref().map_or(f64::INFINITY, |record| {
            record
                .read()
                .unwrap_or_else(|poisoned| poisoned.into_inner())
                .smallest_delay()
        })
    }

    /// The number of sites whose branches a run holds: the program's, then
    /// one for each contact's law, then one for each curve of a PTCV or a
    /// CVCV (its piece).
    pub(crate) fn site_count(&self) -> usize {
        let equations = &self.equations;
        equations.program.sites().len() + equations.contacts.len() + equations.curves.len()
    }

    /// The number of switching values [`Mechanics::observe`] gives: the
    /// program's, then three for each contact, then two for each curve of
    /// a PTCV or a CVCV.
    pub(crate) fn switch_count(&self) -> usize {
        let equations = &self.equations;
        equations.program.switch_count() + 3 * equations.contacts.len() + 2 * equations.curves.len()
    }

    /// The PTCV or CVCV of site `site`, when it is one of their curves,
    /// with the curve's side ([`CurveSite::side`]).
    pub(crate) fn curve_of_site(&self, site: usize) -> Option<(&'m crate::simulate::Joint, usize)> {
        let equations = &self.equations;
        let first = equations.program.sites().len() + equations.contacts.len();
        let index = site.checked_sub(first)?;
        let site = equations.curves.get(index)?;
        Some((&equations.model.joints[site.joint], site.side))
    }

    /// The contact of site `site`, when it is one (its index among the
    /// contacts).
    pub(crate) fn contact_of_site(&self, site: usize) -> Option<&'m Contact> {
        let program_sites = self.equations.program.sites().len();
        let index = site.checked_sub(program_sites)?;
        self.equations.contacts.get(index).copied()
    }

    /// The number of states.
    pub(crate) fn dimension(&self) -> usize {
        let model = self.equations.model;
        model.diffs.len() + BODY_STATES * model.scene.bodies.len()
    }

    /// The groups of the integrators' error norm: the DIFFs' states
    /// together (as one system of equations), and each body's 13 on their
    /// own, so that the error of a body that moves is not diluted by the
    /// states of the many that may be at rest or fixed.
    pub(crate) fn norm_groups(&self) -> Vec<std::ops::Range<usize>> {
        let model = self.equations.model;
        let diffs = model.diffs.len();
        let bodies = (0..model.scene.bodies.len()).map(|body| {
            let offset = body_offset(model, body);
            offset..offset + BODY_STATES
        });
        (diffs > 0)
            .then_some(0..diffs)
            .into_iter()
            .chain(bodies)
            .collect()
    }

    /// `dy/dt` at `(t, y)` with the sites on the branches `held`.
    pub(crate) fn rates(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        rates: &mut [f64],
    ) -> Result<(), OutputError> {
        self.settle(t, y, held)?;
        self.values.at_time(t);
        let fixed = Fixed::new(held, &self.settled);
        self.equations
            .rates(&mut self.values, t, y, fixed, rates, &mut self.buffers)
    }

    /// The rounding floor of each rate at `(t, y)` with the sites on
    /// `held`, into `floor`: for a part's accelerations, the rounding of
    /// the loads summed in each component, with `R`, `τ_R` the joints'
    /// reactions, which can cancel the elements' loads and gravity to
    /// rounding (a part at rest on a slope): `ε (|F_c| + |R_c| + m |g_c|) /
    /// m` along each ground axis `c`, and for the angular accelerations
    /// (in the part's axes) `ε (|τ_c| + |τ_R,c| + a Σ_{d≠c} |R_d|)` carried
    /// through the part's turn and `I⁻¹` in sizes, with `a` the largest arm
    /// from the centre of mass to a joint's marker; zero elsewhere and in a
    /// model without joints. Taken component by component, a hinge loaded
    /// along its axis has rounding in the loads along that axis only, not
    /// in the motion it leaves free. Into `carried`, what each position's
    /// rate takes from them per unit of time: its velocity's floor, and
    /// for the quaternion's rate `q ⊗ (0, ω) / 2` the angular floor carried
    /// through `q` in sizes.
    pub(crate) fn rounding_floor(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        floor: &mut [f64],
        carried: &mut [f64],
    ) -> Result<(), OutputError> {
        floor.fill(0.0);
        carried.fill(0.0);
        let model = self.equations.model;
        if !model.is_constrained() {
            return Ok(());
        }
        self.settle(t, y, held)?;
        self.values.at_time(t);
        let fixed = Fixed {
            keep_applied: true,
            ..Fixed::new(held, &self.settled)
        };
        let solved = self
            .equations
            .solve(&mut self.values, t, y, fixed, &mut self.buffers)?;
        let Some(applied) = &solved.applied else {
            return Ok(());
        };
        let sizes = |vector: &Vector3<f64>| vector.map(f64::abs);
        for (body, mass) in model.masses.iter().enumerate() {
            if mass.is_massless() {
                continue;
            }
            let (force, torque) = (&applied.force[body], &applied.torque[body]);
            let reaction = solved.loads.force[body] - force;
            let reaction_torque = solved.loads.torque[body] - torque;
            let arm = self.equations.joint_arms[body];
            // The reactions' torques about the centre are the sum of each
            // equation's force times its arm, which can cancel: their
            // sizes are those of the net force at the joints' markers, each
            // component from the force's other two.
            let across = Vector3::from_fn(|c, _| {
                (0..3)
                    .filter(|&d| d != c)
                    .map(|d| reaction[d].abs())
                    .sum::<f64>()
                    * arm
            });
            let inverse_inertia = self.equations.inverse_inertia[body];
            self.reaction_push[body] = [
                reaction.norm() / mass.mass,
                (reaction_torque.norm() + reaction.norm() * arm) * inverse_inertia.norm(),
            ];
            let linear = (sizes(force) + sizes(&reaction) + sizes(&model.gravity) * mass.mass)
                * (f64::EPSILON / mass.mass);
            let offset = body_offset(model, body);
            let quaternion = &y[offset + 3..offset + 7];
            let turn = body_quaternion(&y[offset..])
                .to_rotation_matrix()
                .into_inner();
            let in_ground = (sizes(torque) + sizes(&reaction_torque) + across) * f64::EPSILON;
            let angular =
                inverse_inertia.map(f64::abs) * (turn.transpose().map(f64::abs) * in_ground);
            for c in 0..3 {
                floor[offset + 7 + c] = linear[c];
                floor[offset + 10 + c] = angular[c];
                carried[offset + c] = linear[c];
            }
            // q' = (−v·ω, w ω + v × ω) / 2 for q = (w, v), in sizes.
            let scalar = quaternion[0].abs();
            let vector = Vector3::new(quaternion[1], quaternion[2], quaternion[3]).map(f64::abs);
            carried[offset + 3] = 0.5 * vector.dot(&angular);
            for c in 0..3 {
                let (d, e) = ((c + 1) % 3, (c + 2) % 3);
                carried[offset + 4 + c] =
                    0.5 * (scalar * angular[c] + vector[d] * angular[e] + vector[e] * angular[d]);
            }
        }
        Ok(())
    }

    /// Each part's joints' reactions per unit of mass and of inertia where
    /// the rounding floor was last taken (zeros before, and for a massless
    /// part): how hard they push it along its free path per radian its
    /// joints drift.
    pub(crate) fn reaction_push(&self) -> &[[f64; 2]] {
        &self.reaction_push
    }

    /// Solves the loop values at `(t, y)` with the sites on `held` into
    /// [`settled`](Mechanics::settled): the values `z` of the running
    /// solver the program's forces read are those the forces give, `z =
    /// g(z)`, where `g` evaluates the forces with `z`, solves the joints'
    /// multipliers and takes the reactions (accelerations, net forces ...)
    /// the forces read. Newton's iterations on `z − g(z)`, the matrix `I −
    /// ∂g/∂z` by forward differences of `g` (a few values: one column per
    /// value read), kept from state to state while the iterations contract
    /// with it. A force linear in the reactions settles in one iteration.
    fn settle(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
    ) -> Result<(), OutputError> {
        if self.loop_values.is_empty() {
            return Ok(());
        }
        let calls = std::mem::take(&mut self.loop_values);
        if calls.iter().any(|call| {
            matches!(call, &RunValue::ImplicitRate(diff) if self.equations.rate_scales[diff].is_none())
        }) {
            let scaled = self.scale_implicit_rates(t, y, held, &calls);
            if let Err(error) = scaled {
                self.loop_values = calls;
                return Err(error);
            }
        }
        let settled = self.settle_values(t, y, held, &calls);
        self.loop_values = calls;
        self.settled = settled?;
        Ok(())
    }

    /// Sets [`Equations::rate_scales`] at `(t, y)` from the last settled
    /// values: each implicit DIFF's FUNCTION's derivative in its own DIF1,
    /// by a forward difference (left unset where it is zero, to be set at
    /// a later state).
    fn scale_implicit_rates(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        calls: &[RunValue],
    ) -> Result<(), OutputError> {
        let guess = self.settled.clone();
        let given = self.values_at(t, y, held, &guess, calls)?;
        let mut moved = guess.clone();
        for (index, call) in calls.iter().enumerate() {
            let &RunValue::ImplicitRate(diff) = call else {
                continue;
            };
            if self.equations.rate_scales[diff].is_some() {
                continue;
            }
            let step = 1e-7 * guess[index].abs().max(1e-3);
            moved[index] = guess[index] + step;
            let changed = self.values_at(t, y, held, &moved, calls)?;
            moved[index] = guess[index];
            // g = z − F: ∂F/∂z = 1 − ∂g/∂z.
            let derivative = 1.0 - (changed[index] - given[index]) / step;
            if derivative.is_finite() && derivative.abs() > 1e-300 {
                self.equations.rate_scales[diff] = Some(derivative.abs());
                // The matrix of the FUNCTION divided by 1 no longer holds.
                self.settling_matrix = None;
            }
        }
        Ok(())
    }

    /// The loop values `calls` settled at `(t, y)` (see
    /// [`settle`](Mechanics::settle)), from the last state's.
    fn settle_values(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        calls: &[RunValue],
    ) -> Result<Vec<f64>, OutputError> {
        let mut guess = self.settled.clone();
        // An implicit DIFF's rate is settled to 1e-12 of its state (of 1 at
        // least) whatever its own size: a rate near zero is known only to
        // the rounding of its FUNCTION's terms, which can be far larger.
        let floors: Vec<f64> = calls
            .iter()
            .map(|call| match call {
                &RunValue::ImplicitRate(diff) => 1e-12 * y[diff].abs().max(1.0),
                _ => 0.0,
            })
            .collect();
        let mut last_size = f64::INFINITY;
        let mut first_size = None;
        for iteration in 0..SETTLING_ITERATIONS {
            // Past the first guess, a value the program cannot take is where
            // Newton's iterations went, not the state's.
            let given = match self.values_at(t, y, held, &guess, calls) {
                Err(_) if iteration > 0 => return Err(self.equations.unsettled()),
                given => given?,
            };
            let residual = nalgebra::DVector::from_iterator(
                guess.len(),
                given.iter().zip(&guess).map(|(g, z)| g - z),
            );
            let scale = given
                .iter()
                .chain(&guess)
                .fold(0.0_f64, |largest, value| largest.max(value.abs()));
            let settled = residual
                .iter()
                .zip(given.iter().zip(&guess))
                .zip(&floors)
                .all(|((r, (g, z)), floor)| {
                    r.abs() <= 1e-13 * (g.abs() + z.abs()) + 1e-15 * scale + floor
                });
            let size = residual.amax();
            let (first, first_scale) = *first_size.get_or_insert((size, scale));
            // Below a billionth of the values, and a millionth of where it
            // started (or there from the start), a residual that stops
            // shrinking is the rounding of the joints' solve (or of an
            // implicit DIFF's FUNCTION, whose terms can be far larger than
            // a rate near zero); below a hundred-billionth of the values it
            // is, wherever it started (a small reaction beside large ones,
            // through a loop's redundant joints, swings between two guesses
            // 3e-13 of the largest apart).
            let stalled = size >= last_size
                && (size <= 1e-11 * scale
                    || size <= 1e-9 * scale
                        && (size <= 1e-6 * first || first <= 1e-9 * first_scale));
            if settled || stalled {
                return Ok(given);
            }
            // A matrix that does not contract the residual tenfold is
            // worked out again at this guess, at every guess where it does
            // not: one worked out where a magnitude the forces read has its
            // kink (a joint's reaction at 0, as the first state's guess
            // is) has the wrong slope there, and kept, its iterations can
            // diverge however small the gain.
            if self.settling_matrix.is_none() || size > 0.1 * last_size {
                self.settling_matrix =
                    Some(self.settling_matrix_at(t, y, held, &guess, &given, calls)?);
            }
            last_size = size;
            let matrix = self.settling_matrix.as_ref().expect("worked out above");
            let step = matrix
                .solve(&residual)
                .ok_or_else(|| self.equations.unsettled())?;
            for (value, change) in guess.iter_mut().zip(step.iter()) {
                *value += change;
            }
        }
        Err(self.equations.unsettled())
    }

    /// `I − ∂g/∂z` at `guess`, where `g(guess) = given`, by forward
    /// differences, factorised.
    fn settling_matrix_at(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        guess: &[f64],
        given: &[f64],
        calls: &[RunValue],
    ) -> Result<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>, OutputError> {
        let count = guess.len();
        let mut matrix = DMatrix::identity(count, count);
        let mut moved = guess.to_vec();
        // Each value moved by a ten-millionth of its size, taken no less
        // than a thousandth of the largest value's (a value at zero beside
        // large ones), or by 1e-7 when all are zero.
        let largest = guess
            .iter()
            .chain(given)
            .fold(0.0_f64, |largest, value| largest.max(value.abs()));
        let floor = if largest > 0.0 { 1e-3 * largest } else { 1.0 };
        for column in 0..count {
            let step = 1e-7 * (guess[column].abs() + given[column].abs()).max(floor);
            moved[column] = guess[column] + step;
            let changed = self.values_at(t, y, held, &moved, calls)?;
            moved[column] = guess[column];
            for row in 0..count {
                matrix[(row, column)] -= (changed[row] - given[row]) / step;
            }
        }
        // `I − ∂g/∂z` is of the size of 1: a pivot a millionth of that is
        // a gain of 1 (a force that reads itself with it), which no value
        // settles.
        let lu = matrix.lu();
        let smallest = lu
            .u()
            .diagonal()
            .iter()
            .fold(f64::INFINITY, |smallest: f64, pivot: &f64| {
                smallest.min(pivot.abs())
            });
        if smallest.is_nan() || smallest < 1e-6 {
            return Err(self.equations.unsettled());
        }
        Ok(lu)
    }

    /// `(t, y)` is an accepted state of the run: the program's AX, AY, AZ
    /// evaluated there settle their whole turns
    /// ([`Evaluator::accept_angles`]). Nothing to do for a program
    /// without them.
    pub(crate) fn accept(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        starts_piece: bool,
    ) -> Result<(), OutputError> {
        if self.values.continues_angles() {
            let mut rates = vec![0.0; y.len()];
            self.rates(t, y, held, &mut rates)?;
            self.values.accept_angles(t, starts_piece);
        }
        Ok(())
    }

    /// Whether the program has an AX, AY or AZ, whose turns the run
    /// settles at its accepted states.
    pub(crate) fn continues_angles(&self) -> bool {
        self.values.continues_angles()
    }

    /// The program's AX, AY, AZ evaluated last were at an accepted state
    /// at `t` ([`Mechanics::accept`] for a program evaluated otherwise).
    pub(crate) fn accept_angles(&mut self, t: f64, starts_piece: bool) {
        self.values.accept_angles(t, starts_piece);
    }

    /// The natural branch of every site and their switching values at
    /// `(t, y)`, with the sites held on `held`, and the largest step they
    /// allow for an absolute error `tolerance` (infinity when `None`; see
    /// [`Evaluator::observe`]).
    pub(crate) fn observe(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        branches: (&mut [Option<Code>], &mut [f64]),
        tolerance: Option<f64>,
    ) -> Result<f64, OutputError> {
        self.settle(t, y, held)?;
        self.values.at_time(t);
        let equations = &self.equations;
        let kinematics = equations.kinematics(y);
        let buffers = &mut self.buffers;
        equations.fill_inputs(t, y, &kinematics, &self.settled, &mut buffers.inputs);
        reorient(&mut self.values, &kinematics);
        let (natural, switching) = branches;
        let (program_sites, program_switches) = (
            equations.program.sites().len(),
            equations.program.switch_count(),
        );
        let (natural, contact_natural) = natural.split_at_mut(program_sites);
        let (switching, contact_switching) = switching.split_at_mut(program_switches);
        let mut limit = self.values.observe(
            &buffers.inputs,
            held.map(|sites| &sites[..program_sites]),
            (natural, switching),
            &mut buffers.outputs,
            tolerance,
        )?;
        let model = equations.model;
        // Each contact's law is a site after the program's, with the three
        // switching values of an IMPACT.
        let mut apart = Vec::new();
        for (index, &contact) in equations.contacts.iter().enumerate() {
            let (separation, rate) = contact::separation(model, contact, &kinematics)
                .map_err(|refusal| contact_refused(contact, refusal))?;
            let held = held
                .and_then(|sites| sites[program_sites + index])
                .map(ContactBranch::from_code);
            let law = contact.law();
            let observed = law.switching(separation, rate, held);
            contact_natural[index] = Some(observed.natural.code());
            contact_switching[3 * index..3 * index + 3].copy_from_slice(&observed.values);
            if let Some(tolerance) = tolerance {
                let branch = held.unwrap_or(observed.natural);
                limit = limit.min(law.step_limit(separation, rate, branch, tolerance));
                if separation > 0.0 {
                    apart.push((contact, separation, rate));
                }
            }
        }
        // Each curve of a PTCV or a CVCV is a site after the contacts', its
        // branch the piece of its point of contact, with two switching
        // values: the distances to the held piece's ends.
        if !equations.curves.is_empty() {
            let contacts = equations.contacts.len();
            let first_site = program_sites + contacts;
            let bodies = body_motions(&kinematics);
            let held_piece = |k: usize| {
                held.and_then(|sites| sites.get(first_site + k).copied().flatten())
                    .and_then(|code| usize::try_from(code).ok())
            };
            let mut found = Vec::new();
            for (k, site) in equations.curves.iter().enumerate() {
                // A joint's curves are consecutive sites, side 0 first:
                // its points of contact are found once, at its first.
                if site.side == 0 {
                    let joint = &model.joints[site.joint];
                    let second = equations.curves.get(k + 1);
                    let pieces = [
                        held_piece(k),
                        second
                            .filter(|next| next.joint == site.joint)
                            .and_then(|_| held_piece(k + 1)),
                    ];
                    found = curve_contacts(model, joint, &bodies, pieces);
                }
                let Some(&(curve, parameter)) = found.get(site.side) else {
                    continue;
                };
                let natural = curve.piece_of(parameter);
                let piece = held_piece(k).unwrap_or(natural);
                contact_natural[contacts + k] = Some(natural as Code);
                let values = curve.switching(parameter, piece);
                let first_switch = 3 * contacts + 2 * k;
                contact_switching[first_switch..first_switch + 2].copy_from_slice(&values);
            }
        }
        // Solids apart bound the step by their approach, which needs the
        // bodies' accelerations.
        if apart.is_empty() {
            return Ok(limit);
        }
        let mut rates = vec![0.0; y.len()];
        self.rates(t, y, held, &mut rates)?;
        let accelerations: Vec<(f64, f64)> = (0..model.scene.bodies.len())
            .map(|body| {
                let offset = body_offset(model, body);
                let rate = |first: usize| {
                    Vector3::from_column_slice(&rates[offset + first..offset + first + 3]).norm()
                };
                (rate(7), rate(10))
            })
            .collect();
        Ok(apart
            .into_iter()
            .map(|(contact, separation, rate)| {
                contact::step_limit(
                    model,
                    contact,
                    &kinematics,
                    &accelerations,
                    (separation, rate),
                )
            })
            .fold(limit, f64::min))
    }

    /// The values of the running solver the program reads, in the order
    /// their values are given to [`outputs`](Mechanics::outputs).
    pub(crate) fn solver_calls(&self) -> &[RunCall] {
        &self.equations.solver_calls
    }

    /// Every output of the program at `(t, y)`, all branches natural, the
    /// solver's reactions it reads being `solved` (one for each of
    /// [`solver_calls`](Mechanics::solver_calls)).
    pub(crate) fn outputs(
        &mut self,
        t: f64,
        y: &[f64],
        solved: &[f64],
        outputs: &mut [f64],
    ) -> Result<(), OutputError> {
        self.values.at_time(t);
        let equations = &self.equations;
        let kinematics = equations.kinematics(y);
        let inputs = &mut self.buffers.inputs;
        equations.fill_inputs(t, y, &kinematics, solved, inputs);
        reorient(&mut self.values, &kinematics);
        self.values.outputs(inputs, None, outputs)
    }

    /// The values `values` of the running solver at `(t, y)`, all branches
    /// natural, the loop values settled.
    pub(crate) fn run_values(
        &mut self,
        t: f64,
        y: &[f64],
        values: &[RunValue],
    ) -> Result<Vec<f64>, OutputError> {
        self.settle(t, y, None)?;
        let settled = self.settled.clone();
        self.values_at(t, y, None, &settled, values)
    }

    /// The values `values` of the running solver at `(t, y)` with the
    /// sites on `held`, the program reading the loop values `solved`: the
    /// reactions solved and the accelerations of the right-hand side worked
    /// out once each, when some value needs them.
    fn values_at(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        solved: &[f64],
        values: &[RunValue],
    ) -> Result<Vec<f64>, OutputError> {
        self.values.at_time(t);
        let reactions = if values
            .iter()
            .any(|value| matches!(value, RunValue::Reaction(_) | RunValue::NetForce(_)))
        {
            Some(self.reactions(t, y, held, solved)?)
        } else {
            None
        };
        let accelerations = if values
            .iter()
            .any(|value| matches!(value, RunValue::Acceleration(_)))
        {
            let mut rates = vec![0.0; self.dimension()];
            let fixed = Fixed::new(held, solved);
            self.equations
                .rates(&mut self.values, t, y, fixed, &mut rates, &mut self.buffers)?;
            let model = self.equations.model;
            let offsets = (0..model.scene.bodies.len()).map(|body| body_offset(model, body));
            Some(Accelerations::new(
                &self.equations.kinematics(y),
                &rates,
                offsets,
            ))
        } else {
            None
        };
        // The force elements' values: the program's outputs at (t, y).
        let equations = &self.equations;
        let kinematics = equations.kinematics(y);
        if values.iter().any(|value| {
            matches!(
                value,
                RunValue::Element(_) | RunValue::NetForce(_) | RunValue::ImplicitRate(_)
            )
        }) {
            let inputs = &mut self.buffers.inputs;
            equations.fill_inputs(t, y, &kinematics, solved, inputs);
            reorient(&mut self.values, &kinematics);
            let program_sites = equations.program.sites().len();
            let held = held.map(|sites| &sites[..program_sites]);
            self.values
                .outputs(inputs, held, &mut self.buffers.outputs)?;
        }
        let outputs = &self.buffers.outputs;
        let expression_value = |expression| equations.value_of(outputs, expression);
        let model = equations.model;
        values
            .iter()
            .map(|value| match (value, &reactions, &accelerations) {
                (RunValue::Element(component), _, _) => {
                    Ok(component.value(model, &kinematics, &expression_value))
                }
                (RunValue::NetForce(net), Some(reactions), _) => {
                    Ok(net.value(model, &kinematics, reactions, &expression_value))
                }
                (RunValue::Reaction(component), Some(reactions), _) => {
                    Ok(reactions.value(model, component))
                }
                // The rate less the residual its FUNCTION leaves: the rate
                // itself where the FUNCTION is zero, so that Newton's
                // iterations on the loop values find its root.
                (&RunValue::ImplicitRate(diff), _, _) => {
                    let (_, index) = equations.implicit_rates[diff]
                        .expect("an implicit rate is read as a loop value");
                    let residual = expression_value(Some(model.diffs[diff].function));
                    Ok(solved[index] - residual / equations.rate_scales[diff].unwrap_or(1.0))
                }
                (RunValue::Acceleration(measure), _, Some(accelerations)) => accelerations
                    .value(model, measure)
                    .map_err(|error| OutputError {
                        output: 0,
                        error: EvalError::Law {
                            error,
                            span: crate::Span::default(),
                        },
                    }),
                _ => unreachable!("worked out above for each kind asked for"),
            })
            .collect()
    }

    /// The reactions of the joints, primitives and motions at `(t, y)`, with
    /// the sites on `held` and the program reading the loop values `solved`.
    fn reactions(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        solved: &[f64],
    ) -> Result<Reactions, OutputError> {
        let equations = &self.equations;
        let fixed = Fixed::new(held, solved);
        let solved = equations.solve(&mut self.values, t, y, fixed, &mut self.buffers)?;
        let drives = equations.drives.at(t, held)?;
        let multipliers = solved.multipliers.unwrap_or_default();
        Ok(Reactions::new(
            equations.model,
            &body_motions(&solved.kinematics),
            &drives,
            multipliers.as_slice(),
        ))
    }

    /// Where the Jacobian's entries can be nonzero (the same on every
    /// branch); worked out on the first call.
    pub(crate) fn pattern(&mut self) -> &Pattern {
        &self.sparsity().pattern
    }

    /// The Jacobian's pattern and its evaluator, built once.
    fn sparsity(&mut self) -> &Sparsity {
        let equations = &self.equations;
        let bordered = self.bordered;
        // A program that reads loop values is differentiated by
        // differences: its evaluator over duals is the smallest.
        let differenced = !self.loop_values.is_empty();
        &self
            .jacobian
            .get_or_insert_with(|| {
                // The joints' multipliers, then the massless parts'
                // accelerations, each part's six moved by its own.
                let holders = bordered.then(|| {
                    let mut holders = holders(equations.model);
                    holders.extend(equations.massless.iter().map(|&body| Holder {
                        equations: 6,
                        bodies: vec![body],
                    }));
                    holders
                });
                let sparsity = Sparsity::new(
                    equations.model,
                    equations.program,
                    (&equations.sources, &equations.output_of),
                    holders.as_deref(),
                );
                let directions = if differenced { 1 } else { sparsity.directions };
                let (duals, count) = DualEvaluator::for_directions(
                    equations.program,
                    directions,
                    self.delays.as_ref(),
                );
                (sparsity, duals, count)
            })
            .0
    }

    /// `d(dy/dt)/dy` at `(t, y)` with the sites on `held`: the values of
    /// the [`pattern`](Mechanics::pattern)'s entries, in its order, into
    /// `values`, from one evaluation over dual numbers. In the bordered
    /// form the pattern has the joints' multipliers and the massless
    /// parts' accelerations after the states, and the values are the
    /// index-1 form's Jacobian in them and `y`, at their values at `(t, y)`.
    pub(crate) fn sparse_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        values: &mut [f64],
    ) -> Result<(), OutputError> {
        self.sparsity();
        if !self.loop_values.is_empty() {
            return self.differenced_jacobian(t, y, held, values);
        }
        let multipliers = if self.bordered {
            let fixed = Fixed::new(held, &[]);
            let solved = self
                .equations
                .solve(&mut self.values, t, y, fixed, &mut self.buffers)?;
            let mut unknowns: Vec<f64> = solved.multipliers.unwrap_or_default().as_slice().to_vec();
            for body in &self.equations.massless {
                let found = solved.massless.iter().find(|(other, _)| other == body);
                unknowns.extend(found.map_or([0.0; 6], |(_, accelerations)| *accelerations));
            }
            Some(unknowns)
        } else {
            None
        };
        let multipliers = multipliers.as_deref();
        let Some((sparsity, duals, count)) = &mut self.jacobian else {
            unreachable!("built above");
        };
        let equations = &self.equations;
        let at = JacobianAt {
            t,
            y,
            multipliers,
            held,
        };
        with_evaluator!(duals, evaluator => equations.fill(evaluator, at, sparsity, *count, values))
    }

    /// The Jacobian of a program that reads loop values, by central
    /// differences of the rates (each settling its loop values; the
    /// pattern is dense): exact derivatives would need the joints' solve and
    /// the reactions over dual numbers. Right to about `1e-8` of the
    /// entries, which Radau5's Newton iterations only need roughly.
    fn differenced_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        values: &mut [f64],
    ) -> Result<(), OutputError> {
        let n = y.len();
        let centre = self.settled.clone();
        let mut moved = y.to_vec();
        let mut ahead = vec![0.0; n];
        let mut behind = vec![0.0; n];
        let mut columns = DMatrix::zeros(n, n);
        for column in 0..n {
            let step = f64::EPSILON.cbrt() * y[column].abs().max(1.0);
            moved[column] = y[column] + step;
            self.rates(t, &moved, held, &mut ahead)?;
            self.settled.clone_from(&centre);
            moved[column] = y[column] - step;
            self.rates(t, &moved, held, &mut behind)?;
            self.settled.clone_from(&centre);
            moved[column] = y[column];
            for row in 0..n {
                columns[(row, column)] = (ahead[row] - behind[row]) / (2.0 * step);
            }
        }
        for (value, entry) in values.iter_mut().zip(self.pattern().entries()) {
            *value = columns[entry];
        }
        Ok(())
    }

    /// `d(dy/dt)/dy` at `(t, y)` with the sites on `held`, into the dense
    /// `jacobian` (the entries outside the pattern set to zero); in the
    /// bordered form the Schur complement `f_y − f_λ g_λ⁻¹ g_y` of the
    /// index-1 form's Jacobian.
    pub(crate) fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        jacobian: &mut DMatrix<f64>,
    ) -> Result<(), OutputError> {
        let pattern = self.pattern().clone();
        let mut values = vec![0.0; pattern.len()];
        self.sparse_jacobian(t, y, held, &mut values)?;
        let mut full = DMatrix::zeros(pattern.dimension(), pattern.dimension());
        for (entry, value) in pattern.entries().zip(values) {
            full[entry] = value;
        }
        let n = y.len();
        let m = pattern.dimension() - n;
        if m == 0 {
            jacobian.copy_from(&full);
            return Ok(());
        }
        let eliminated = full
            .view((n, n), (m, m))
            .into_owned()
            .lu()
            .solve(&full.view((n, 0), (m, n)).into_owned())
            .ok_or_else(|| joints_singular_in(self.equations.model))?;
        jacobian.copy_from(&(full.view((0, 0), (n, n)) - full.view((0, n), (n, m)) * eliminated));
        Ok(())
    }
}

/// A value of the running solver an output reads, found in the model.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum RunValue {
    /// A reaction of a joint, primitive or motion.
    Reaction(Component),
    /// A measure of accelerations.
    Acceleration(Measure),
    /// A force element's force or torque.
    Element(ElementComponent),
    /// The net force between markers.
    NetForce(NetForce),
    /// The time derivative of the implicit DIFF at this index of the
    /// model's DIFFs: the root of its FUNCTION.
    ImplicitRate(usize),
}

impl RunValue {
    /// The value `call` asks of `model`, or why it has none.
    pub(crate) fn of(model: &Model, call: &RunCall) -> Result<RunValue, String> {
        match call {
            RunCall::Reaction(call)
                if ELEMENT_FUNCTIONS
                    .iter()
                    .any(|(function, _)| *function == call.function) =>
            {
                ElementComponent::of(model, call).map(RunValue::Element)
            }
            RunCall::Reaction(call) => Component::of(model, call).map(RunValue::Reaction),
            RunCall::Acceleration(call) => Measure::of(model, call).map(RunValue::Acceleration),
            RunCall::NetForce(call) => NetForce::of(model, call).map(RunValue::NetForce),
            RunCall::ImplicitRate(id) => model
                .diffs
                .iter()
                .position(|diff| diff.id == *id && diff.linear.is_none() && diff.implicit.is_some())
                .map(RunValue::ImplicitRate)
                .ok_or_else(|| format!("DIFF/{id} is not an implicit DIFF of the model")),
        }
    }
}

/// The largest distance from each body's centre of mass to a joint's
/// marker on it (0 for a body no joint holds).
fn joint_arms(model: &Model) -> Vec<f64> {
    let mut arms = vec![0.0_f64; model.masses.len()];
    for joint in &model.joints {
        for target in [&joint.i, &joint.j] {
            if let crate::scene::Target::Marker(index) = target {
                let marker = &model.scene.markers[*index];
                if let Some(body) = marker.body {
                    let arm = (marker.position - model.masses[body].centre).norm();
                    arms[body] = arms[body].max(arm);
                }
            }
        }
    }
    arms
}

/// The bodies as the constraint rows see them.
fn body_motions<T: Number>(kinematics: &[Kinematics<T>]) -> Vec<BodyMotion<T>> {
    kinematics
        .iter()
        .map(|state| BodyMotion {
            centre: state.centre.clone(),
            rotation: state.rotation.clone(),
            velocity: state.velocity.clone(),
            omega: state.omega_ground.clone(),
        })
        .collect()
}

/// What [`Equations::solve`] finds at a state.
struct Solved<T: Number> {
    kinematics: Vec<Kinematics<T>>,
    loads: Loads<T>,
    /// The joints' multipliers (`None`: the model has no joint).
    multipliers: Option<nalgebra::DVector<T>>,
    /// The accelerations of the massless parts, which the joints' solve
    /// gives (`[v' | ω']` of the centre, in ground).
    massless: Vec<(usize, [T; 6])>,
    /// The force elements' loads alone, before the joints' reactions
    /// were added (when [`Fixed::keep_applied`] asks).
    applied: Option<Loads<T>>,
}

/// What one evaluation of the equations holds fixed: the branch of each
/// site (`None`: every branch natural) and the loop values the program
/// reads ([`Mechanics::settle`]).
#[derive(Clone, Copy)]
struct Fixed<'a> {
    sites: Option<&'a [Option<Code>]>,
    loop_values: &'a [f64],
    /// Keep the elements' loads apart from the joints' reactions
    /// ([`Solved::applied`]).
    keep_applied: bool,
}

impl<'a> Fixed<'a> {
    /// The sites on `sites` and the program reading `loop_values`, the
    /// loads not kept apart.
    fn new(sites: Option<&'a [Option<Code>]>, loop_values: &'a [f64]) -> Fixed<'a> {
        Fixed {
            sites,
            loop_values,
            keep_applied: false,
        }
    }
}

/// Where a Jacobian is taken: the time, the states, the joints'
/// multipliers there (for the bordered form) and the sites held.
#[derive(Clone, Copy)]
struct JacobianAt<'a> {
    t: f64,
    y: &'a [f64],
    multipliers: Option<&'a [f64]>,
    held: Option<&'a [Option<Code>]>,
}

/// The program's inputs and outputs, kept from call to call.
struct Buffers<T> {
    inputs: Vec<T>,
    outputs: Vec<T>,
}

impl<T: Number> Buffers<T> {
    fn new(program: &Program) -> Buffers<T> {
        Buffers {
            inputs: Vec::with_capacity(program.inputs().len()),
            outputs: vec![T::zero(); program.output_count()],
        }
    }
}

/// Turns the program's bodies to the orientations of `kinematics`.
fn reorient<T: Number, U: Number>(evaluator: &mut Evaluator<'_, U>, kinematics: &[Kinematics<T>]) {
    if kinematics.is_empty() {
        return;
    }
    evaluator.reorient(|body| kinematics[body].rotation.map(|entry| entry.value()));
}

/// A run stopped at a translational force of `size` whose markers
/// coincide, at its FUNCTION, the program's output `output`.
fn no_line_of_action(output: usize, size: f64) -> OutputError {
    OutputError {
        output,
        error: EvalError::Law {
            error: crate::laws::LawError::Domain {
                operation: "a translational force",
                reason: format!(
                    "its I and J markers coincide while it is {}: it acts along the line from J to I, which is not defined here (place the markers apart, or make the force 0 where they meet)",
                    crate::shown::Shown(size)
                ),
            },
            span: crate::Span::default(),
        },
    }
}

/// The equations: the model, where each program input comes from, and
/// what the program's outputs are.
struct Equations<'m> {
    model: &'m Model,
    program: &'m Program,
    sources: Vec<Source>,
    /// Whether each output of the program reads no state of the model
    /// (only TIME, constants and the sensors' values): its value is exact,
    /// not a state's rounding.
    state_free: Vec<bool>,
    /// The output of the program that is each DIFF's function (`None` in
    /// a program that computes only output columns).
    diff_outputs: Vec<Option<usize>>,
    /// Of each implicit DIFF, the program's input that holds its rate,
    /// `DIF1(id)`, and that input's index among the loop values (`None`
    /// for an explicit DIFF, whose rate is its function's output).
    implicit_rates: Vec<Option<(usize, usize)>>,
    /// Of each implicit DIFF, what its FUNCTION is divided by in its loop
    /// value, `DIF1 − FUNCTION / scale`: the FUNCTION's derivative in its
    /// DIF1 at the first state where that is not zero (`None` before, when
    /// the FUNCTION is divided by 1), so that
    /// Newton's iterations and their test of convergence see the rate
    /// whatever the FUNCTION's scale (`1e-7·DIF1(1) − ...`).
    rate_scales: Vec<Option<f64>>,
    /// The program's output of each expression it computes, by expression.
    output_of: Vec<Option<usize>>,
    /// The inverse inertia of each body.
    inverse_inertia: Vec<Matrix3<f64>>,
    /// The largest distance from each body's centre of mass to a joint's
    /// marker on it ([`Mechanics::rounding_floor`]).
    joint_arms: Vec<f64>,
    /// The motions' displacements in time.
    drives: Drives,
    /// The values of the running solver the program reads.
    solver_calls: Vec<RunCall>,
    /// The model's contacts, in the order of their sites (after the
    /// program's).
    contacts: Vec<&'m Contact>,
    /// The curves of the model's PTCVs and CVCVs, in the order of their
    /// sites (after the contacts'): each is held on one piece within a
    /// step.
    curves: Vec<CurveSite>,
    /// `SENVAL` of each of the model's sensors: its EVALUATE's value at its
    /// last trip (0 before the first, and for a sensor without one).
    sensed: Vec<f64>,
    /// The massless parts, in order: in the bordered form their
    /// accelerations are algebraic unknowns after the multipliers.
    massless: Vec<usize>,
}

impl Equations<'_> {
    /// The error of loop values that Newton's iterations do not settle: at
    /// the first output of the program that reads one.
    fn unsettled(&self) -> OutputError {
        let output = self
            .program
            .inputs_of_outputs()
            .iter()
            .position(|inputs| {
                inputs
                    .iter()
                    .any(|&input| matches!(self.sources[input], Source::Solver(_)))
            })
            .unwrap_or(0);
        let implicit = self
            .diff_outputs
            .iter()
            .zip(&self.implicit_rates)
            .any(|(diff_output, rate)| *diff_output == Some(output) && rate.is_some());
        let (operation, reason) = if implicit {
            (
                "an implicit DIFF",
                "FUNCTION = 0 has no root in the DIF1s near their last values at this state: Newton's iterations on them diverge (the FUNCTION has no real root in DIF1 here, or its derivative in DIF1 is zero)",
            )
        } else {
            (
                "a force that reads the running solver's values",
                "the values it reads (reactions, accelerations, forces) and those the motion gives do not settle to one at this state: Newton's iterations on them diverge, as at a joint that friction locks, or where a force reads its own value with a gain of 1",
            )
        };
        OutputError {
            output,
            error: EvalError::Law {
                error: crate::laws::LawError::Domain {
                    operation,
                    reason: reason.to_string(),
                },
                span: crate::Span::default(),
            },
        }
    }

    /// The value of `expression` among the program's `outputs` (zero for
    /// no expression).
    fn value_of<T: Number>(&self, outputs: &[T], expression: Option<usize>) -> T {
        expression
            .and_then(|expression| self.output_of[expression])
            .map_or_else(T::zero, |output| outputs[output].clone())
    }

    /// The program's inputs at `(t, y)`, the bodies moving as
    /// `kinematics` say, the loop values at `solved`.
    fn fill_inputs<T: Number>(
        &self,
        t: f64,
        y: &[T],
        kinematics: &[Kinematics<T>],
        solved: &[f64],
        inputs: &mut Vec<T>,
    ) {
        inputs.clear();
        inputs.extend(self.sources.iter().map(|source| match *source {
            Source::Time => T::from(t),
            Source::Constant(value) => T::from(value),
            Source::State(index) => y[index].clone(),
            Source::Body(body, component) => kinematics[body].input(component),
            Source::Solver(index) => T::from(solved[index]),
            Source::Sensor(index) => T::from(self.sensed[index]),
        }));
    }

    fn kinematics<T: Number>(&self, y: &[T]) -> Vec<Kinematics<T>> {
        if self.model.scene.bodies.is_empty() {
            return Vec::new();
        }
        (0..self.model.scene.bodies.len())
            .map(|body| {
                let offset = body_offset(self.model, body);
                Kinematics::of(
                    &y[offset..offset + BODY_STATES],
                    &self.model.masses[body].centre,
                )
            })
            .collect()
    }

    /// `dy/dt` over `T`.
    fn rates<T: Number>(
        &self,
        evaluator: &mut Evaluator<'_, T>,
        t: f64,
        y: &[T],
        fixed: Fixed<'_>,
        rates: &mut [T],
        buffers: &mut Buffers<T>,
    ) -> Result<(), OutputError> {
        let solved = self.solve(evaluator, t, y, fixed, buffers)?;
        self.fill_rates(&solved.kinematics, &solved.loads, buffers, rates);
        for (body, accelerations) in &solved.massless {
            self.set_massless_rates(&solved.kinematics, *body, accelerations, rates);
        }
        Ok(())
    }

    /// The rates of massless part `body`'s velocities from its
    /// `accelerations` (`[v' | ω']` of its centre, in ground), which no
    /// mass gives.
    fn set_massless_rates<T: Number>(
        &self,
        kinematics: &[Kinematics<T>],
        body: usize,
        accelerations: &[T],
        rates: &mut [T],
    ) {
        // The angular acceleration in the body's axes: `ω_b = Rᵀ ω` and
        // `Ṙᵀ ω = −ω_b × ω_b = 0`.
        let angular = kinematics[body].rotation.transpose()
            * Vector3::new(
                accelerations[3].clone(),
                accelerations[4].clone(),
                accelerations[5].clone(),
            );
        let offset = body_offset(self.model, body);
        let given = accelerations[..3]
            .iter()
            .cloned()
            .chain(angular.iter().cloned());
        for (rate, value) in rates[offset + 7..offset + BODY_STATES]
            .iter_mut()
            .zip(given)
        {
            *rate = value;
        }
    }

    /// The DIFFs' rates from the program's outputs in `buffers` and the
    /// bodies' from their `loads`.
    fn fill_rates<T: Number>(
        &self,
        kinematics: &[Kinematics<T>],
        loads: &Loads<T>,
        buffers: &Buffers<T>,
        rates: &mut [T],
    ) {
        let model = self.model;
        let outputs = &buffers.outputs;
        for ((rate, output), implicit) in rates
            .iter_mut()
            .zip(&self.diff_outputs)
            .zip(&self.implicit_rates)
        {
            *rate = match implicit {
                Some((input, _)) => buffers.inputs[*input].clone(),
                None => output.map_or_else(T::zero, |output| outputs[output].clone()),
            };
        }
        for (body, state) in kinematics.iter().enumerate() {
            let offset = body_offset(model, body);
            state.rates(
                &model.masses[body],
                &self.inverse_inertia[body],
                &model.gravity,
                &loads.force[body],
                &loads.torque[body],
                &mut rates[offset..offset + BODY_STATES],
            );
        }
    }

    /// The index-1 form's equations at the states `y` and the algebraic
    /// unknowns `multipliers` (the joints' `λ`, then each massless part's
    /// accelerations `a₀`, `[v' | ω']` in ground): `dy/dt` under the loads
    /// `−Gᵀ λ` (a massless part's velocities' rates `a₀`) into `rates`, and
    /// into `residuals` each held equation's `G u' + bias`, then each
    /// massless part's balance `f₀ − G₀ᵀ λ` (force, torque), all zero at
    /// the unknowns [`Equations::solve`] finds. For a model without loop
    /// values.
    #[allow(clippy::too_many_arguments)]
    fn bordered_rates<T: Number>(
        &self,
        evaluator: &mut Evaluator<'_, T>,
        t: f64,
        (y, multipliers): (&[T], &[T]),
        fixed: Fixed<'_>,
        rates: &mut [T],
        residuals: &mut [T],
        buffers: &mut Buffers<T>,
    ) -> Result<(), OutputError> {
        let model = self.model;
        let (kinematics, mut loads) = self.loaded(evaluator, t, y, (fixed.sites, &[]), buffers)?;
        let motions = body_motions(&kinematics);
        let drives = self.drives.at(t, fixed.sites)?;
        let held = multipliers.len() - 6 * self.massless.len();
        let (multipliers, massless) = multipliers.split_at(held);
        let rows = multiplier_loads(
            model,
            &motions,
            &drives,
            multipliers,
            &mut loads.force,
            &mut loads.torque,
        );
        self.fill_rates(&kinematics, &loads, buffers, rates);
        for (&body, accelerations) in self.massless.iter().zip(massless.chunks(6)) {
            self.set_massless_rates(&kinematics, body, accelerations, rates);
        }
        // `[v' | ω']` of each centre, in ground: `ω' = R ω_b'`.
        let accelerations: Vec<[T; 6]> = kinematics
            .iter()
            .enumerate()
            .map(|(body, state)| {
                let offset = body_offset(model, body);
                let rate = |k: usize| rates[offset + k].clone();
                let angular = &state.rotation * Vector3::new(rate(10), rate(11), rate(12));
                [
                    rate(7),
                    rate(8),
                    rate(9),
                    angular[0].clone(),
                    angular[1].clone(),
                    angular[2].clone(),
                ]
            })
            .collect();
        let (held_residuals, balances) = residuals.split_at_mut(held);
        for (residual, row) in held_residuals.iter_mut().zip(&rows) {
            *residual = acceleration_residual(row, &accelerations);
        }
        for (&body, balance) in self.massless.iter().zip(balances.chunks_mut(6)) {
            let (force, torque) = (&loads.force[body], &loads.torque[body]);
            for (k, residual) in balance.iter_mut().enumerate() {
                *residual = if k < 3 {
                    force[k].clone()
                } else {
                    torque[k - 3].clone()
                };
            }
        }
        Ok(())
    }

    /// The bodies' kinematics at `(t, y)` and the loads the force elements
    /// put on them, the program's sites on `sites` (its outputs left in
    /// `buffers`).
    fn loaded<T: Number>(
        &self,
        evaluator: &mut Evaluator<'_, T>,
        t: f64,
        y: &[T],
        (sites, loop_values): (Option<&[Option<Code>]>, &[f64]),
        buffers: &mut Buffers<T>,
    ) -> Result<(Vec<Kinematics<T>>, Loads<T>), OutputError> {
        let model = self.model;
        let kinematics = self.kinematics(y);
        self.fill_inputs(t, y, &kinematics, loop_values, &mut buffers.inputs);
        reorient(evaluator, &kinematics);
        let program_sites = self.program.sites().len();
        let program_held = sites.map(|sites| &sites[..program_sites]);
        evaluator.outputs(&buffers.inputs, program_held, &mut buffers.outputs)?;
        let outputs = &buffers.outputs;
        let bodies = model.scene.bodies.len();
        let mut loads = Loads {
            force: vec![Vector3::zeros(); bodies],
            torque: vec![Vector3::zeros(); bodies],
        };
        let value = |expression: Option<usize>| self.value_of(outputs, expression);
        let mut contacts = 0;
        for force in &model.forces {
            // A contact's branch: its site after the program's.
            let branch = match force {
                Force::Contact(_) => {
                    contacts += 1;
                    sites
                        .and_then(|sites| sites[program_sites + contacts - 1])
                        .map(ContactBranch::from_code)
                }
                _ => None,
            };
            if let Err(magnitude) =
                forces::apply(model, force, &kinematics, (&value, branch), &mut loads)
            {
                // A force read from the states (a spring of length 0,
                // `-k*DM(i, j)`) is 0 at the meeting up to rounding; one of
                // TIME alone pushes along no line.
                if let Some(output) =
                    self.output_of[magnitude].filter(|&output| self.state_free[output])
                {
                    return Err(no_line_of_action(output, value(Some(magnitude)).value()));
                }
            }
        }
        Ok((kinematics, loads))
    }

    /// The bodies' kinematics at `(t, y)` and the loads on them, the joints'
    /// reactions among them, with the joints' multipliers (the program's
    /// outputs left in `buffers`), with what `fixed` holds.
    fn solve<T: Number>(
        &self,
        evaluator: &mut Evaluator<'_, T>,
        t: f64,
        y: &[T],
        fixed: Fixed<'_>,
        buffers: &mut Buffers<T>,
    ) -> Result<Solved<T>, OutputError> {
        let model = self.model;
        let (kinematics, mut loads) =
            self.loaded(evaluator, t, y, (fixed.sites, fixed.loop_values), buffers)?;
        let mut multipliers = None;
        let mut massless = Vec::new();
        let applied = fixed.keep_applied.then(|| Loads {
            force: loads.force.clone(),
            torque: loads.torque.clone(),
        });
        if model.is_constrained() {
            let motions = body_motions(&kinematics);
            let drives = self.drives.at(t, fixed.sites)?;
            let held = constraint_loads(
                model,
                &motions,
                &drives,
                &self.inverse_inertia,
                &mut loads.force,
                &mut loads.torque,
            )
            .map_err(|unheld| match unheld {
                Unheld::Overflow { row } => joints_overflow_in(model, row),
                Unheld::Singular => joints_failed_in(model, &motions),
            })?;
            multipliers = Some(held.multipliers);
            massless = held.massless;
        }
        Ok(Solved {
            kinematics,
            loads,
            multipliers,
            massless,
            applied,
        })
    }

    /// The Jacobian's entries into `values`, by one evaluation over dual
    /// numbers of `count` directions seeded as `sparsity` says, at `(t,
    /// y)` with the sites on `held`; with `multipliers`, the index-1
    /// form's in the states and those multipliers
    /// ([`Equations::bordered_rates`]).
    fn fill<T: Directional>(
        &self,
        evaluator: &mut Evaluator<'_, T>,
        JacobianAt {
            t,
            y,
            multipliers,
            held,
        }: JacobianAt<'_>,
        sparsity: &Sparsity,
        count: usize,
        values: &mut [f64],
    ) -> Result<(), OutputError> {
        let seed = |(&value, &direction): (&f64, &usize)| T::variable(value, direction, count);
        let seeded: Vec<T> = y.iter().zip(&sparsity.direction).map(seed).collect();
        let mut rates = vec![T::zero(); y.len()];
        let mut buffers = Buffers::new(self.program);
        // Programs that read loop values are differentiated by differences
        // instead (`Mechanics::sparse_jacobian`).
        let fixed = Fixed::new(held, &[]);
        let mut residuals = Vec::new();
        match multipliers {
            None => self.rates(evaluator, t, &seeded, fixed, &mut rates, &mut buffers)?,
            Some(multipliers) => {
                let seeded_multipliers: Vec<T> = multipliers
                    .iter()
                    .zip(&sparsity.direction[y.len()..])
                    .map(seed)
                    .collect();
                residuals = vec![T::zero(); multipliers.len()];
                self.bordered_rates(
                    evaluator,
                    t,
                    (&seeded, &seeded_multipliers),
                    fixed,
                    &mut rates,
                    &mut residuals,
                    &mut buffers,
                )?;
            }
        }
        for (row, rate) in rates.iter().chain(&residuals).enumerate() {
            let gradient = rate.gradient(count);
            for &(position, direction) in sparsity.row(row) {
                values[position] = gradient[direction];
            }
        }
        Ok(())
    }
}

/// A run stopped at a contact whose solids have gone where its geometry
/// does not follow them, at the contact's statement.
fn contact_refused(
    contact: &crate::simulate::model::Contact,
    refusal: contact::Refusal,
) -> OutputError {
    let contact::Refusal { operation, reason } = refusal;
    OutputError {
        output: crate::simulate::constraints::JOINTS,
        error: crate::eval::EvalError::Law {
            error: crate::laws::LawError::Domain { operation, reason },
            span: contact.span,
        },
    }
}
