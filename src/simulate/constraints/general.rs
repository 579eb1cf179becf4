//! General constraints (`GCON`): the equation `FUNCTION = 0`, its FUNCTION
//! an expression of the parts' positions and orientations and of time, or
//! of their velocities too (held at the level of the velocities, as a
//! coupler is: a nonholonomic constraint such as a knife edge's).
//!
//! Each FUNCTION is compiled on its own and evaluated in plain numbers at
//! the bodies' current motion: once with dual numbers in the positions
//! and small rotations of the parts it reads (the row of `G`), and once
//! with second-order dual numbers along the motion the velocities give
//! with no acceleration (the rate `Φ'` and the bias `Φ''`). The row is
//! exact in plain numbers (the projection, the explicit method, the
//! reactions). Over the Jacobian's dual numbers each part of it is carried
//! to first order through the bodies' motion it reads, its slopes by
//! central differences of the plain row (its exact derivatives would need
//! a third order of dual numbers): the Jacobian is right to about 1e-9,
//! not to rounding, where a GCON acts.

use nalgebra::{Const, Matrix3, Vector3};
use num_dual::{Dual2Vec, DualDVec64};

use super::BodyMotion;
use super::rows::Row;
use crate::compile::{Program, compile_outputs};
use crate::number::{Directional, Number};
use crate::scene::StateComponent;
use crate::simulate::{GeneralConstraint, Model};

/// What a FUNCTION's input is at a state.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Input {
    /// `TIME`.
    Time,
    /// A coordinate of a part's origin in ground.
    Position(usize, usize),
    /// A component of a part's small rotation (about ground's axes).
    Rotation(usize, usize),
    /// A component of a part's origin's velocity in ground (read by the
    /// marker frames the measures build; no measure a GCON may call uses
    /// it).
    Velocity(usize, usize),
    /// A component of a part's angular velocity in ground (likewise).
    AngularVelocity(usize, usize),
    /// A value that does not change in the run (a constant of the scene).
    Constant(f64),
}

/// One GCON's FUNCTION, compiled.
struct Compiled {
    program: Program,
    inputs: Vec<Input>,
    /// The FUNCTION reads velocities (`VX` ... `WM`): the equation
    /// `c(q, u, t) = 0` is held at the level of the velocities.
    on_velocities: bool,
}

/// The model's general constraints, compiled.
#[derive(Default)]
pub(crate) struct GeneralConstraints {
    compiled: Vec<Option<Compiled>>,
}

type PathDual = Dual2Vec<f64, Const<1>>;

impl GeneralConstraints {
    /// The FUNCTIONs of `model`'s GCONs, compiled (`None` for one that
    /// does not compile or reads what a GCON may not: its errors are
    /// [`GeneralConstraints::refusals`]).
    pub(crate) fn new(model: &Model) -> GeneralConstraints {
        let compiled = model
            .general_constraints
            .iter()
            .map(|constraint| compile(model, constraint)?.ok())
            .collect();
        GeneralConstraints { compiled }
    }

    /// Why each GCON whose FUNCTION compiles cannot be held: it reads an
    /// acceleration (a constraint on accelerations is not simulated) or a
    /// state of the run other than the parts' motion (a DIFF).
    pub(crate) fn refusals(model: &Model) -> Vec<(u64, crate::span::Span, String)> {
        model
            .general_constraints
            .iter()
            .filter_map(|constraint| {
                let reason = compile(model, constraint)?.err()?;
                Some((constraint.id, constraint.function_span, reason))
            })
            .collect()
    }

    /// The equation of GCON `index` at `time`, the bodies moving as
    /// `bodies` say (its value not a number where its FUNCTION cannot be
    /// evaluated there).
    pub(crate) fn row<T: Number>(
        &self,
        model: &Model,
        index: usize,
        time: f64,
        bodies: &[BodyMotion<T>],
    ) -> Row<T> {
        let failed = || Row {
            value: T::from(f64::NAN),
            rate: T::zero(),
            bias: T::zero(),
            coefficients: Vec::new(),
        };
        let Some(Some(compiled)) = self.compiled.get(index) else {
            return failed();
        };
        let plain: Vec<Motion> = bodies
            .iter()
            .zip(&model.masses)
            .map(|(body, mass)| Motion::of(body, &mass.centre))
            .collect();
        let Some(row) = compiled.row(time, &plain) else {
            return failed();
        };
        let mut lifted = Row {
            value: T::from(row.value),
            rate: T::from(row.rate),
            bias: T::from(row.bias),
            coefficients: row
                .coefficients
                .iter()
                .map(|(body, entries)| (*body, entries.map(T::from)))
                .collect(),
        };
        if T::NDERIV == 0 {
            return lifted;
        }
        // Each scalar of the motion of each body read, with derivative
        // parts: the row's slope in it, by central differences, times its
        // derivative parts.
        for body in compiled.bodies_read() {
            let motion = &bodies[body];
            let scalars = motion
                .centre
                .iter()
                .chain(motion.rotation.iter())
                .chain(motion.velocity.iter())
                .chain(motion.omega.iter());
            for (which, scalar) in scalars.enumerate() {
                if scalar.is_constant() {
                    continue;
                }
                let parts = scalar.clone() - scalar.value();
                let step = 1e-6 * scalar.value().abs().max(1.0);
                let shifted = |by: f64| {
                    let mut moved = plain.clone();
                    moved[body].shift(which, by, &model.masses[body].centre);
                    compiled.row(time, &moved)
                };
                let (Some(up), Some(down)) = (shifted(step), shifted(-step)) else {
                    return failed();
                };
                let slope = |a: f64, b: f64| parts.clone() * ((a - b) / (2.0 * step));
                lifted.value += slope(up.value, down.value);
                lifted.rate += slope(up.rate, down.rate);
                lifted.bias += slope(up.bias, down.bias);
                for ((_, entries), ((_, a), (_, b))) in lifted
                    .coefficients
                    .iter_mut()
                    .zip(up.coefficients.iter().zip(&down.coefficients))
                {
                    for (entry, (a, b)) in entries.iter_mut().zip(a.iter().zip(b)) {
                        *entry += slope(*a, *b);
                    }
                }
            }
        }
        lifted
    }
}

/// The bodies the markers of GCON `constraint`'s FUNCTION are on (ground
/// left out), each once: the parts its equation holds together.
pub(crate) fn bodies_of(model: &Model, constraint: &GeneralConstraint) -> Vec<usize> {
    let mut bodies = Vec::new();
    let tree = &model.expressions[constraint.function].checked;
    crate::check::visit(&tree.root, &mut |node| {
        if let crate::check::NodeKind::Call(_, args) = &node.kind {
            for arg in args {
                if let crate::check::Argument::Marker(reference, _) = arg
                    && let Ok(crate::scene::Target::Marker(index)) =
                        model.scene.find_marker(reference)
                    && let Some(body) = model.scene.markers[index].body
                    && !bodies.contains(&body)
                {
                    bodies.push(body);
                }
            }
        }
    });
    bodies
}

/// GCON `constraint`'s FUNCTION compiled (`None` where it does not
/// compile: the simulation's compile reports why), or why a GCON may not
/// read what it reads.
fn compile(model: &Model, constraint: &GeneralConstraint) -> Option<Result<Compiled, String>> {
    let tree = &model.expressions[constraint.function].checked;
    let program = compile_outputs(&[tree], &["TIME"], Some(&model.scene)).ok()?;
    Some(match (inputs_of(model, &program), rate_reading(tree)) {
        (Err(reason), _) | (Ok(_), Some(reason)) => Err(reason),
        (Ok(inputs), None) => Ok(Compiled {
            program,
            inputs,
            on_velocities: tree.functions().into_iter().any(is_velocity),
        }),
    })
}

/// What each input of `program` is, or why a GCON may not read it.
fn inputs_of(model: &Model, program: &Program) -> Result<Vec<Input>, String> {
    program
        .inputs()
        .iter()
        .map(|name| {
            if name.eq_ignore_ascii_case("TIME") {
                return Ok(Input::Time);
            }
            match model.scene.parse_state_name(name) {
                Some((body, StateComponent::Position(axis))) => Ok(Input::Position(body, axis)),
                Some((body, StateComponent::Rotation(axis))) => Ok(Input::Rotation(body, axis)),
                Some((body, StateComponent::Velocity(axis))) => Ok(Input::Velocity(body, axis)),
                Some((body, StateComponent::AngularVelocity(axis))) => {
                    Ok(Input::AngularVelocity(body, axis))
                }
                None if crate::scene::is_run_state_input(name)
                    || crate::scene::parse_sensor_input(name).is_some() =>
                {
                    Err(format!(
                        "its FUNCTION reads {name}, a value of the run: a GCON keeps a function of the parts' places and of time at 0"
                    ))
                }
                None => model
                    .scene
                    .value_of(name)
                    .map(Input::Constant)
                    .map_err(|error| error.to_string()),
            }
        })
        .collect()
}

/// Whether `function` measures a velocity: a GCON reading one is held at
/// the level of the velocities.
fn is_velocity(function: crate::catalog::Function) -> bool {
    use crate::catalog::Function as F;
    matches!(
        function,
        F::Vx | F::Vy | F::Vz | F::Vm | F::Vr | F::Wx | F::Wy | F::Wz | F::Wm
    )
}

/// Why a GCON's FUNCTION `tree` cannot be held, when it reads an
/// acceleration (a constraint on accelerations is not simulated) or a value
/// that may (a VARIABLE, a DIFF).
fn rate_reading(tree: &crate::Checked) -> Option<String> {
    use crate::catalog::Function as F;
    let read = tree.functions().into_iter().find(|function| {
        matches!(
            function,
            F::Accx
                | F::Accy
                | F::Accz
                | F::Accm
                | F::Wdtx
                | F::Wdty
                | F::Wdtz
                | F::Wdtm
                | F::Varval
                | F::Dif
                | F::Dif1
        )
    })?;
    Some(format!(
        "its FUNCTION reads {}: a GCON keeps a function of the parts' places and velocities and of time at 0 (a constraint on accelerations is not simulated)",
        read.name()
    ))
}

/// A body's motion in plain numbers, and its origin's.
#[derive(Clone)]
struct Motion {
    centre: Vector3<f64>,
    rotation: Matrix3<f64>,
    velocity: Vector3<f64>,
    omega: Vector3<f64>,
    /// From the centre of mass to the body frame's origin, in ground.
    to_origin: Vector3<f64>,
}

impl Motion {
    /// Scalar `which` of the centre (0–2), the rotation (3–11, by
    /// columns), the velocity (12–14) and the angular velocity (15–17)
    /// moved by `by`.
    fn shift(&mut self, which: usize, by: f64, centre_in_body: &Vector3<f64>) {
        match which {
            0..=2 => self.centre[which] += by,
            3..=11 => {
                self.rotation[which - 3] += by;
                self.to_origin = -(self.rotation * centre_in_body);
            }
            12..=14 => self.velocity[which - 12] += by,
            _ => self.omega[which - 15] += by,
        }
    }

    fn of<T: Number>(body: &BodyMotion<T>, centre_in_body: &Vector3<f64>) -> Motion {
        let rotation = body.rotation.map(|entry| entry.value());
        Motion {
            centre: body.centre.map(|entry| entry.value()),
            velocity: body.velocity.map(|entry| entry.value()),
            omega: body.omega.map(|entry| entry.value()),
            to_origin: -(rotation * centre_in_body),
            rotation,
        }
    }
}

impl Compiled {
    /// The bodies whose state the FUNCTION reads, each once.
    fn bodies_read(&self) -> Vec<usize> {
        let mut bodies: Vec<usize> = self
            .inputs
            .iter()
            .filter_map(|input| match *input {
                Input::Position(body, _)
                | Input::Rotation(body, _)
                | Input::Velocity(body, _)
                | Input::AngularVelocity(body, _) => Some(body),
                Input::Time | Input::Constant(_) => None,
            })
            .collect();
        bodies.sort_unstable();
        bodies.dedup();
        bodies
    }

    /// The row in plain numbers, or `None` where the FUNCTION fails.
    ///
    /// On velocities the equation `c(q, u, t) = 0` is held as a coupler's
    /// is: its value zero (the positions' projection leaves it alone), its
    /// rate `c`, its row of `G` the gradient `∂c/∂u`, its bias `dc/dt`
    /// along the motion with no acceleration.
    fn row(&self, time: f64, bodies: &[Motion]) -> Option<Row<f64>> {
        // The directions of the gradient: each position and rotation
        // input, or each velocity one.
        let directions: Vec<usize> = (0..self.inputs.len())
            .filter(|&k| match self.inputs[k] {
                Input::Position(..) | Input::Rotation(..) => !self.on_velocities,
                Input::Velocity(..) | Input::AngularVelocity(..) => self.on_velocities,
                Input::Time | Input::Constant(_) => false,
            })
            .collect();
        let count = directions.len();
        let value_of = |input: &Input| match *input {
            Input::Time => time,
            Input::Position(body, axis) => bodies[body].centre[axis] + bodies[body].to_origin[axis],
            Input::Rotation(..) => 0.0,
            Input::Velocity(body, axis) => {
                let motion = &bodies[body];
                (motion.velocity + motion.omega.cross(&motion.to_origin))[axis]
            }
            Input::AngularVelocity(body, axis) => bodies[body].omega[axis],
            Input::Constant(value) => value,
        };
        let seeded: Vec<DualDVec64> = self
            .inputs
            .iter()
            .enumerate()
            .map(|(k, input)| match directions.iter().position(|&d| d == k) {
                Some(direction) => DualDVec64::variable(value_of(input), direction, count),
                None => DualDVec64::from(value_of(input)),
            })
            .collect();
        let gradient = evaluate(&self.program, &seeded, bodies)?;
        let slopes = gradient.gradient(count);
        // Along the motion with no acceleration: each centre moves at its
        // velocity, each body turns at its angular velocity, so its origin
        // is at `o + (v + ω × d) s + ω × (ω × d) s²/2` (`d` from the
        // centre to the origin) and its small rotation is `ω s`.
        let s = PathDual::variable(0.0, 0, 1);
        let along: Vec<PathDual> = self
            .inputs
            .iter()
            .map(|input| match *input {
                Input::Time => PathDual::from(time) + s,
                Input::Position(body, axis) => {
                    let motion = &bodies[body];
                    let arm = motion.to_origin;
                    let rate = motion.velocity + motion.omega.cross(&arm);
                    let curve = motion.omega.cross(&motion.omega.cross(&arm));
                    PathDual::from(value_of(input)) + s * rate[axis] + s * s * (0.5 * curve[axis])
                }
                Input::Rotation(body, axis) => s * bodies[body].omega[axis],
                // With no acceleration the origin's velocity `v + ω × d`
                // turns with `d`: its rate is `ω × (ω × d)`.
                Input::Velocity(body, axis) => {
                    let motion = &bodies[body];
                    let turn = motion.omega.cross(&motion.omega.cross(&motion.to_origin));
                    PathDual::from(value_of(input)) + s * turn[axis]
                }
                _ => PathDual::from(value_of(input)),
            })
            .collect();
        let path = evaluate(&self.program, &along, bodies)?;
        // The row of G: on v the gradient in the origin's place, on ω the
        // gradient in the small rotation plus the origin's turn about the
        // centre (`δo = δc + δθ × d`).
        let mut coefficients: Vec<(usize, [f64; 6])> = Vec::new();
        for (direction, &k) in directions.iter().enumerate() {
            let (body, entries) = match self.inputs[k] {
                // `δ(v + ω × d) = δv + δω × d`, as a place's `δc + δθ × d`.
                Input::Position(body, axis) | Input::Velocity(body, axis) => {
                    let mut entries = [0.0; 6];
                    entries[axis] = slopes[direction];
                    let mut unit = Vector3::zeros();
                    unit[axis] = slopes[direction];
                    let turn = bodies[body].to_origin.cross(&unit);
                    entries[3..].copy_from_slice(turn.as_slice());
                    (body, entries)
                }
                Input::Rotation(body, axis) | Input::AngularVelocity(body, axis) => {
                    let mut entries = [0.0; 6];
                    entries[3 + axis] = slopes[direction];
                    (body, entries)
                }
                _ => continue,
            };
            match coefficients.iter_mut().find(|(b, _)| *b == body) {
                Some((_, sum)) => sum.iter_mut().zip(entries).for_each(|(a, b)| *a += b),
                None => coefficients.push((body, entries)),
            }
        }
        let row = if self.on_velocities {
            Row {
                value: 0.0,
                rate: path.re,
                bias: path.gradient(1)[0],
                coefficients,
            }
        } else {
            Row {
                value: path.re,
                rate: path.gradient(1)[0],
                bias: path.hessian(1).map_or(0.0, |hessian| hessian[(0, 0)]),
                coefficients,
            }
        };
        [row.value, row.rate, row.bias]
            .iter()
            .all(|value| value.is_finite())
            .then_some(row)
    }
}

/// The program's one output over `inputs`, its bodies turned as `bodies`
/// say.
fn evaluate<T: Number>(program: &Program, inputs: &[T], bodies: &[Motion]) -> Option<T> {
    let mut evaluator = program.evaluator::<T>();
    evaluator.reorient(|body| bodies[body].rotation);
    let mut outputs = vec![T::zero(); 1];
    evaluator.outputs(inputs, None, &mut outputs).ok()?;
    outputs.pop()
}
