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

use nalgebra::{DMatrix, Matrix3, Vector3};
use num_dual::{DualDVec64, DualSVec64};

use super::constraints::{BodyMotion, constraint_loads, joints_singular};
use super::model::{Force, Model};
use super::sparsity::Sparsity;
use crate::compile::Program;
use crate::eval::{Evaluator, OutputError};
use crate::integrate::linalg::Pattern;
use crate::laws::branch::Code;
use crate::number::{Directional, Number};
use crate::scene::{StateComponent, Target, parse_diff_input};

/// Components of a body's state.
pub(crate) const BODY_STATES: usize = 13;

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
}

/// A body's state as the expressions and the force elements see it.
struct Kinematics<T: Number> {
    centre: Vector3<T>,
    /// The quaternion as integrated (not normalised).
    quaternion: [T; 4],
    rotation: Matrix3<T>,
    /// A small rotation about the current orientation, with value 0 and the
    /// derivative parts of the orientation.
    turn: Vector3<T>,
    velocity: Vector3<T>,
    /// Angular velocity in the body's axes.
    omega: Vector3<T>,
    /// Angular velocity in ground.
    omega_ground: Vector3<T>,
    /// The body frame's origin and its velocity, in ground: the state
    /// inputs, worked out once per call for every expression that reads them.
    origin: Vector3<T>,
    origin_velocity: Vector3<T>,
}

impl<T: Number> Kinematics<T> {
    fn of(state: &[T], centre_in_body: &Vector3<f64>) -> Kinematics<T> {
        let vector = |first: usize| {
            Vector3::new(
                state[first].clone(),
                state[first + 1].clone(),
                state[first + 2].clone(),
            )
        };
        let quaternion = [
            state[3].clone(),
            state[4].clone(),
            state[5].clone(),
            state[6].clone(),
        ];
        let length = quaternion
            .iter()
            .map(|part| part.clone() * part.clone())
            .reduce(|sum, term| sum + term)
            .expect("four parts")
            .sqrt();
        let [w, x, y, z] = quaternion.clone().map(|part| part / length.clone());
        let rotation = rotation_matrix(&w, &x, &y, &z);
        // vec(n ⊗ n0*) = w0 v − w v0 − v × v0, twice, is the small rotation
        // whose derivative parts are the orientation's.
        let (w0, v0) = (w.value(), Vector3::new(x.value(), y.value(), z.value()));
        let v = Vector3::new(x, y, z);
        let cross = v.cross(&v0.map(T::from));
        let turn = (v.clone() * T::from(w0) - v0.map(|c| w.clone() * c) - cross) * T::from(2.0);
        let turn = turn.map(|component| component.clone() - component.value());
        let omega = vector(10);
        let omega_ground = &rotation * &omega;
        let to_origin = -(&rotation * centre_in_body.map(T::from));
        let (centre, velocity) = (vector(0), vector(7));
        let origin = &centre + &to_origin;
        let origin_velocity = &velocity + omega_ground.cross(&to_origin);
        Kinematics {
            centre,
            quaternion,
            rotation,
            turn,
            velocity,
            omega,
            omega_ground,
            origin,
            origin_velocity,
        }
    }

    /// The value of state input `component` (of the body frame's origin).
    fn input(&self, component: StateComponent) -> T {
        match component {
            StateComponent::Position(axis) => self.origin[axis].clone(),
            StateComponent::Rotation(axis) => self.turn[axis].clone(),
            StateComponent::Velocity(axis) => self.origin_velocity[axis].clone(),
            StateComponent::AngularVelocity(axis) => self.omega_ground[axis].clone(),
        }
    }
}

/// The rotation matrix of the unit quaternion `w x y z`.
fn rotation_matrix<T: Number>(w: &T, x: &T, y: &T, z: &T) -> Matrix3<T> {
    let two = |a: &T, b: &T| a.clone() * b.clone() * 2.0;
    let one = T::one();
    Matrix3::new(
        one.clone() - two(y, y) - two(z, z),
        two(x, y) - two(w, z),
        two(x, z) + two(w, y),
        two(x, y) + two(w, z),
        one.clone() - two(x, x) - two(z, z),
        two(y, z) - two(w, x),
        two(x, z) - two(w, y),
        two(y, z) + two(w, x),
        one - two(x, x) - two(y, y),
    )
}

/// A marker's origin and axes in ground.
struct Placed<T: Number> {
    origin: Vector3<T>,
    axes: Matrix3<T>,
    body: Option<usize>,
}

/// The force and the torque about the centre of mass, in ground, that the
/// force elements apply to each body.
struct Loads<T: Number> {
    force: Vec<Vector3<T>>,
    torque: Vec<Vector3<T>>,
}

impl<T: Number> Loads<T> {
    /// `force` at `point` on `body` (nothing on ground).
    fn push(
        &mut self,
        body: Option<usize>,
        point: &Vector3<T>,
        force: &Vector3<T>,
        kinematics: &[Kinematics<T>],
    ) {
        if let Some(body) = body {
            let arm = point - &kinematics[body].centre;
            self.torque[body] += arm.cross(force);
            self.force[body] += force;
        }
    }

    /// `torque` on `body` (nothing on ground).
    fn turn(&mut self, body: Option<usize>, torque: &Vector3<T>) {
        if let Some(body) = body {
            self.torque[body] += torque;
        }
    }
}

/// The equations of motion of a model, with its compiled expressions.
pub(crate) struct Mechanics<'m> {
    equations: Equations<'m>,
    values: Evaluator<'m, f64>,
    buffers: Buffers<f64>,
    /// The Jacobian's pattern and evaluator, built when first asked for.
    jacobian: Option<(Sparsity, DualEvaluator<'m>)>,
}

/// The evaluator of the Jacobian's dual numbers: a size fixed at compile
/// time for up to 4 directions (DIFFs only) and for one, two and three body
/// colours (13, 26 and 39: the unused directions of a smaller count stay
/// zero), so that no dual operation allocates; dynamic beyond.
enum DualEvaluator<'m> {
    One(Evaluator<'m, DualSVec64<1>>),
    Two(Evaluator<'m, DualSVec64<2>>),
    Three(Evaluator<'m, DualSVec64<3>>),
    Four(Evaluator<'m, DualSVec64<4>>),
    OneBody(Evaluator<'m, DualSVec64<13>>),
    TwoBodies(Evaluator<'m, DualSVec64<26>>),
    ThreeBodies(Evaluator<'m, DualSVec64<39>>),
    Many(Evaluator<'m, DualDVec64>),
}

impl<'m> DualEvaluator<'m> {
    /// The evaluator for `directions` directions, and the count it seeds.
    fn for_directions(program: &'m Program, directions: usize) -> (DualEvaluator<'m>, usize) {
        match directions {
            0 | 1 => (DualEvaluator::One(program.evaluator()), 1),
            2 => (DualEvaluator::Two(program.evaluator()), 2),
            3 => (DualEvaluator::Three(program.evaluator()), 3),
            4 => (DualEvaluator::Four(program.evaluator()), 4),
            5..=13 => (DualEvaluator::OneBody(program.evaluator()), 13),
            14..=26 => (DualEvaluator::TwoBodies(program.evaluator()), 26),
            27..=39 => (DualEvaluator::ThreeBodies(program.evaluator()), 39),
            _ => (DualEvaluator::Many(program.evaluator()), directions),
        }
    }
}

/// The state index of the first component of body `body`.
pub(crate) fn body_offset(model: &Model, body: usize) -> usize {
    model.diffs.len() + BODY_STATES * body
}

impl<'m> Mechanics<'m> {
    /// The equations of `model`, whose DIFF functions and force components
    /// `program` computes (output `k` is the expression `computed[k]`).
    pub(crate) fn new(model: &'m Model, program: &'m Program, computed: &[usize]) -> Mechanics<'m> {
        let mut output_of = vec![None; model.expressions.len()];
        for (output, &expression) in computed.iter().enumerate() {
            output_of[expression] = Some(output);
        }
        let sources: Vec<Source> = program
            .inputs()
            .iter()
            .map(|name| {
                if name.eq_ignore_ascii_case("TIME") {
                    Source::Time
                } else if let Some(id) = parse_diff_input(name) {
                    let index = model.diffs.iter().position(|diff| diff.id == id);
                    Source::State(index.expect("the compiler binds only DIFFs of the model"))
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
        let inverse_inertia = model
            .masses
            .iter()
            .map(|mass| mass.inertia.try_inverse().unwrap_or_else(Matrix3::zeros))
            .collect();
        Mechanics {
            equations: Equations {
                model,
                program,
                sources,
                diff_outputs,
                output_of,
                inverse_inertia,
            },
            values: program.evaluator(),
            buffers: Buffers::new(program),
            jacobian: None,
        }
    }

    /// The number of states.
    pub(crate) fn dimension(&self) -> usize {
        let model = self.equations.model;
        model.diffs.len() + BODY_STATES * model.scene.bodies.len()
    }

    /// `dy/dt` at `(t, y)` with the sites on the branches `held`.
    pub(crate) fn rates(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        rates: &mut [f64],
    ) -> Result<(), OutputError> {
        self.equations
            .rates(&mut self.values, t, y, held, rates, &mut self.buffers)
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
        let equations = &self.equations;
        let kinematics = equations.kinematics(y);
        let buffers = &mut self.buffers;
        fill_inputs(&equations.sources, t, y, &kinematics, &mut buffers.inputs);
        reorient(&mut self.values, &kinematics);
        self.values.observe(
            &buffers.inputs,
            held,
            branches,
            &mut buffers.outputs,
            tolerance,
        )
    }

    /// Every output of the program at `(t, y)`, all branches natural.
    pub(crate) fn outputs(
        &mut self,
        t: f64,
        y: &[f64],
        outputs: &mut [f64],
    ) -> Result<(), OutputError> {
        let equations = &self.equations;
        let kinematics = equations.kinematics(y);
        let inputs = &mut self.buffers.inputs;
        fill_inputs(&equations.sources, t, y, &kinematics, inputs);
        reorient(&mut self.values, &kinematics);
        self.values.outputs(inputs, None, outputs)
    }

    /// Where the Jacobian's entries can be nonzero (the same on every
    /// branch); worked out on the first call.
    pub(crate) fn pattern(&mut self) -> &Pattern {
        &self.sparsity().pattern
    }

    /// The Jacobian's pattern and its evaluator, built once.
    fn sparsity(&mut self) -> &Sparsity {
        let equations = &self.equations;
        &self
            .jacobian
            .get_or_insert_with(|| {
                let sparsity = Sparsity::new(
                    equations.model,
                    equations.program,
                    &equations.sources,
                    &equations.output_of,
                );
                let (duals, _) =
                    DualEvaluator::for_directions(equations.program, sparsity.directions);
                (sparsity, duals)
            })
            .0
    }

    /// `d(dy/dt)/dy` at `(t, y)` with the sites on `held`: the values of
    /// the [`pattern`](Mechanics::pattern)'s entries, in its order, into
    /// `values`, from one evaluation over dual numbers.
    pub(crate) fn sparse_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        values: &mut [f64],
    ) -> Result<(), OutputError> {
        self.sparsity();
        let Some((sparsity, duals)) = &mut self.jacobian else {
            unreachable!("built above");
        };
        let equations = &self.equations;
        let count = |size: usize| size.max(sparsity.directions);
        match duals {
            DualEvaluator::One(evaluator) => {
                equations.fill(evaluator, t, y, held, sparsity, count(1), values)
            }
            DualEvaluator::Two(evaluator) => {
                equations.fill(evaluator, t, y, held, sparsity, count(2), values)
            }
            DualEvaluator::Three(evaluator) => {
                equations.fill(evaluator, t, y, held, sparsity, count(3), values)
            }
            DualEvaluator::Four(evaluator) => {
                equations.fill(evaluator, t, y, held, sparsity, count(4), values)
            }
            DualEvaluator::OneBody(evaluator) => {
                equations.fill(evaluator, t, y, held, sparsity, count(13), values)
            }
            DualEvaluator::TwoBodies(evaluator) => {
                equations.fill(evaluator, t, y, held, sparsity, count(26), values)
            }
            DualEvaluator::ThreeBodies(evaluator) => {
                equations.fill(evaluator, t, y, held, sparsity, count(39), values)
            }
            DualEvaluator::Many(evaluator) => {
                equations.fill(evaluator, t, y, held, sparsity, count(0), values)
            }
        }
    }

    /// `d(dy/dt)/dy` at `(t, y)` with the sites on `held`, into the dense
    /// `jacobian` (the entries outside the pattern set to zero).
    pub(crate) fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        jacobian: &mut DMatrix<f64>,
    ) -> Result<(), OutputError> {
        let mut values = vec![0.0; self.pattern().len()];
        self.sparse_jacobian(t, y, held, &mut values)?;
        jacobian.fill(0.0);
        for (entry, value) in self.pattern().entries().zip(values) {
            jacobian[entry] = value;
        }
        Ok(())
    }
}

/// The program input values from the state, into `inputs`.
fn fill_inputs<T: Number>(
    sources: &[Source],
    t: f64,
    y: &[T],
    kinematics: &[Kinematics<T>],
    inputs: &mut Vec<T>,
) {
    inputs.clear();
    inputs.extend(sources.iter().map(|source| match *source {
        Source::Time => T::from(t),
        Source::Constant(value) => T::from(value),
        Source::State(index) => y[index].clone(),
        Source::Body(body, component) => kinematics[body].input(component),
    }));
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

/// The equations: the model, where each program input comes from, and
/// what the program's outputs are.
struct Equations<'m> {
    model: &'m Model,
    program: &'m Program,
    sources: Vec<Source>,
    /// The output of the program that is each DIFF's function (`None` in
    /// a program that computes only output columns).
    diff_outputs: Vec<Option<usize>>,
    /// The program's output of each expression it computes, by expression.
    output_of: Vec<Option<usize>>,
    /// The inverse inertia of each body.
    inverse_inertia: Vec<Matrix3<f64>>,
}

impl Equations<'_> {
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
        held: Option<&[Option<Code>]>,
        rates: &mut [T],
        buffers: &mut Buffers<T>,
    ) -> Result<(), OutputError> {
        let model = self.model;
        let kinematics = self.kinematics(y);
        fill_inputs(&self.sources, t, y, &kinematics, &mut buffers.inputs);
        reorient(evaluator, &kinematics);
        evaluator.outputs(&buffers.inputs, held, &mut buffers.outputs)?;
        let outputs = &buffers.outputs;
        for (rate, output) in rates.iter_mut().zip(&self.diff_outputs) {
            *rate = output.map_or_else(T::zero, |output| outputs[output].clone());
        }
        let bodies = model.scene.bodies.len();
        let mut loads = Loads {
            force: vec![Vector3::zeros(); bodies],
            torque: vec![Vector3::zeros(); bodies],
        };
        let value = |expression: Option<usize>| {
            expression
                .and_then(|expression| self.output_of[expression])
                .map_or_else(T::zero, |output| outputs[output].clone())
        };
        for force in &model.forces {
            self.apply(force, &kinematics, &value, &mut loads);
        }
        if !model.joints.is_empty() {
            let motions: Vec<BodyMotion<T>> = kinematics
                .iter()
                .map(|state| BodyMotion {
                    centre: state.centre.clone(),
                    rotation: state.rotation.clone(),
                    velocity: state.velocity.clone(),
                    omega: state.omega_ground.clone(),
                })
                .collect();
            constraint_loads(
                model,
                &motions,
                &self.inverse_inertia,
                &mut loads.force,
                &mut loads.torque,
            )
            .map_err(|_| joints_singular())?;
        }
        for (body, state) in kinematics.iter().enumerate() {
            let offset = body_offset(model, body);
            self.body_rates(
                body,
                state,
                &loads.force[body],
                &loads.torque[body],
                &mut rates[offset..offset + BODY_STATES],
            );
        }
        Ok(())
    }

    /// A marker's origin and axes in ground.
    fn place<T: Number>(&self, target: &Target, kinematics: &[Kinematics<T>]) -> Placed<T> {
        let Target::Marker(index) = target else {
            return Placed {
                origin: Vector3::zeros(),
                axes: Matrix3::identity(),
                body: None,
            };
        };
        let marker = &self.model.scene.markers[*index];
        let axes_in_body = marker.orientation.to_rotation_matrix().into_inner();
        match marker.body {
            None => Placed {
                origin: marker.position.map(T::from),
                axes: axes_in_body.map(T::from),
                body: None,
            },
            Some(body) => {
                let state = &kinematics[body];
                let offset = marker.position - self.model.masses[body].centre;
                Placed {
                    origin: &state.centre + &state.rotation * offset.map(T::from),
                    axes: &state.rotation * axes_in_body.map(T::from),
                    body: Some(body),
                }
            }
        }
    }

    /// Adds what `force` applies to the bodies.
    fn apply<T: Number>(
        &self,
        force: &Force,
        kinematics: &[Kinematics<T>],
        value: &impl Fn(Option<usize>) -> T,
        loads: &mut Loads<T>,
    ) {
        match force {
            Force::Translational {
                i,
                j,
                magnitude,
                action_only,
            } => {
                let (i, j) = (self.place(i, kinematics), self.place(j, kinematics));
                let magnitude = value(Some(*magnitude));
                if *action_only {
                    let along = j.axes.column(2).into_owned() * magnitude;
                    loads.push(i.body, &i.origin, &along, kinematics);
                    return;
                }
                let line = &i.origin - &j.origin;
                let length = line.dot(&line).sqrt();
                if length.value() == 0.0 {
                    // Coincident markers: no line of action, no force.
                    return;
                }
                let push = line / length * magnitude;
                loads.push(i.body, &i.origin, &push, kinematics);
                loads.push(j.body, &j.origin, &-push, kinematics);
            }
            Force::Rotational {
                i,
                j,
                magnitude,
                action_only,
            } => {
                let (i, j) = (self.place(i, kinematics), self.place(j, kinematics));
                let torque = j.axes.column(2).into_owned() * value(Some(*magnitude));
                loads.turn(i.body, &torque);
                if !*action_only {
                    loads.turn(j.body, &-torque);
                }
            }
            Force::Vector {
                i,
                reaction,
                axes,
                force,
                torque,
            } => {
                let i = self.place(i, kinematics);
                let axes = self.place(axes, kinematics).axes;
                let along = |components: &[Option<usize>; 3]| {
                    let local = Vector3::new(
                        value(components[0]),
                        value(components[1]),
                        value(components[2]),
                    );
                    &axes * local
                };
                let (push, turn) = (along(force), along(torque));
                loads.push(i.body, &i.origin, &push, kinematics);
                loads.turn(i.body, &turn);
                if reaction.is_some() {
                    loads.push(*reaction, &i.origin, &-push, kinematics);
                    loads.turn(*reaction, &-turn);
                }
            }
        }
    }

    /// The rates of one body's 13 states under `force` and `torque` (about
    /// its centre of mass, in ground).
    fn body_rates<T: Number>(
        &self,
        body: usize,
        state: &Kinematics<T>,
        force: &Vector3<T>,
        torque: &Vector3<T>,
        rates: &mut [T],
    ) {
        let mass = &self.model.masses[body];
        let inertia = mass.inertia.map(T::from);
        let acceleration = force / T::from(mass.mass) + self.model.gravity.map(T::from);
        let omega = &state.omega;
        let body_torque = state.rotation.transpose() * torque;
        let angular = self.inverse_inertia[body].map(T::from)
            * (body_torque - omega.cross(&(&inertia * omega)));
        let [w, x, y, z] = &state.quaternion;
        let v = Vector3::new(x.clone(), y.clone(), z.clone());
        let spin_w = -v.dot(omega) * 0.5;
        let spin_v = (omega * w.clone() + v.cross(omega)) * T::from(0.5);
        let rows: [T; 13] = [
            state.velocity[0].clone(),
            state.velocity[1].clone(),
            state.velocity[2].clone(),
            spin_w,
            spin_v[0].clone(),
            spin_v[1].clone(),
            spin_v[2].clone(),
            acceleration[0].clone(),
            acceleration[1].clone(),
            acceleration[2].clone(),
            angular[0].clone(),
            angular[1].clone(),
            angular[2].clone(),
        ];
        for (rate, row) in rates.iter_mut().zip(rows) {
            *rate = row;
        }
    }

    /// The Jacobian's entries into `values`, by one evaluation over dual
    /// numbers of `count` directions seeded as `sparsity` says.
    #[allow(clippy::too_many_arguments)]
    fn fill<T: Directional>(
        &self,
        evaluator: &mut Evaluator<'_, T>,
        t: f64,
        y: &[f64],
        held: Option<&[Option<Code>]>,
        sparsity: &Sparsity,
        count: usize,
        values: &mut [f64],
    ) -> Result<(), OutputError> {
        let seeded: Vec<T> = y
            .iter()
            .zip(&sparsity.direction)
            .map(|(&value, &direction)| T::variable(value, direction, count))
            .collect();
        let mut rates = vec![T::zero(); y.len()];
        let mut buffers = Buffers::new(self.program);
        self.rates(evaluator, t, &seeded, held, &mut rates, &mut buffers)?;
        for (row, rate) in rates.iter().enumerate() {
            let gradient = rate.gradient(count);
            for &(position, direction) in sparsity.row(row) {
                values[position] = gradient[direction];
            }
        }
        Ok(())
    }
}
