//! A rigid body's state and its equations: the kinematics the expressions
//! and force elements see, the loads summed on it, and Newton's and Euler's
//! equations about its centre of mass (see [`super`] for the state layout).

use nalgebra::{Matrix3, Vector3};

use crate::kinematics::times_constant;
use crate::number::Number;
use crate::scene::StateComponent;
use crate::simulate::model::{MassProperties, Model};

/// Components of a body's state.
pub(crate) const BODY_STATES: usize = 13;

/// The body's first components, its position and orientation, whose rates
/// are its own velocity and spin ([`Kinematics::rates`]).
pub(crate) const KINEMATIC_RATES: usize = 7;

/// The state index of the first component of body `body`.
pub(crate) fn body_offset(model: &Model, body: usize) -> usize {
    model.diffs.len() + BODY_STATES * body
}

/// A body's state as the expressions and the force elements see it.
pub(super) struct Kinematics<T: Number> {
    pub(super) centre: Vector3<T>,
    /// The quaternion as integrated (not normalised).
    pub(super) quaternion: [T; 4],
    pub(super) rotation: Matrix3<T>,
    /// A small rotation about the current orientation, with value 0 and the
    /// derivative parts of the orientation.
    pub(super) turn: Vector3<T>,
    pub(super) velocity: Vector3<T>,
    /// Angular velocity in the body's axes.
    pub(super) omega: Vector3<T>,
    /// Angular velocity in ground.
    pub(super) omega_ground: Vector3<T>,
    /// The body frame's origin and its velocity, in ground: the state
    /// inputs, worked out once per call for every expression that reads them.
    pub(super) origin: Vector3<T>,
    pub(super) origin_velocity: Vector3<T>,
}

impl<T: Number> Kinematics<T> {
    pub(super) fn of(state: &[T], centre_in_body: &Vector3<f64>) -> Kinematics<T> {
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
        let omega_ground = times(&rotation, &omega);
        let to_origin = -times_constant(&rotation, centre_in_body);
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

    /// The rates of one body's 13 states under `force` and `torque` (about
    /// its centre of mass, in ground).
    pub(super) fn rates(
        &self,
        mass: &MassProperties,
        inverse_inertia: &Matrix3<f64>,
        gravity: &Vector3<f64>,
        force: &Vector3<T>,
        torque: &Vector3<T>,
        rates: &mut [T],
    ) {
        // A massless part's accelerations are the joints' solve's
        // (`Mechanics::rates` puts them in); none here.
        let acceleration = if mass.is_massless() {
            Vector3::zeros()
        } else {
            force / T::from(mass.mass) + gravity.map(T::from)
        };
        let omega = &self.omega;
        let body_torque = transpose_times(&self.rotation, torque);
        let momentum = constant_times(&mass.inertia, omega);
        let angular = constant_times(inverse_inertia, &(body_torque - omega.cross(&momentum)));
        let [w, x, y, z] = &self.quaternion;
        let v = Vector3::new(x.clone(), y.clone(), z.clone());
        let spin_w = -v.dot(omega) * 0.5;
        let spin_v = (omega * w.clone() + v.cross(omega)) * T::from(0.5);
        let rows: [T; 13] = [
            self.velocity[0].clone(),
            self.velocity[1].clone(),
            self.velocity[2].clone(),
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

    /// The value of state input `component` (of the body frame's origin).
    pub(super) fn input(&self, component: StateComponent) -> T {
        match component {
            StateComponent::Position(axis) => self.origin[axis].clone(),
            StateComponent::Rotation(axis) => self.turn[axis].clone(),
            StateComponent::Velocity(axis) => self.origin_velocity[axis].clone(),
            StateComponent::AngularVelocity(axis) => self.omega_ground[axis].clone(),
        }
    }
}

/// `a v`, summed in the order of nalgebra's product (so that plain numbers
/// come out the same), without its copies of the numbers.
fn times<T: Number>(a: &Matrix3<T>, v: &Vector3<T>) -> Vector3<T> {
    Vector3::from_fn(|row, _| {
        a[(row, 0)].clone() * v[0].clone()
            + a[(row, 1)].clone() * v[1].clone()
            + a[(row, 2)].clone() * v[2].clone()
    })
}

/// `aᵀ v`, as [`times`], without the transposed copy.
fn transpose_times<T: Number>(a: &Matrix3<T>, v: &Vector3<T>) -> Vector3<T> {
    Vector3::from_fn(|row, _| {
        a[(0, row)].clone() * v[0].clone()
            + a[(1, row)].clone() * v[1].clone()
            + a[(2, row)].clone() * v[2].clone()
    })
}

/// `a v` for a constant `a`: no product with a constant's zero derivative
/// parts.
fn constant_times<T: Number>(a: &Matrix3<f64>, v: &Vector3<T>) -> Vector3<T> {
    Vector3::from_fn(|row, _| {
        v[0].clone() * a[(row, 0)] + v[1].clone() * a[(row, 1)] + v[2].clone() * a[(row, 2)]
    })
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

/// The force and the torque about the centre of mass, in ground, that the
/// force elements apply to each body.
pub(super) struct Loads<T: Number> {
    pub(super) force: Vec<Vector3<T>>,
    pub(super) torque: Vec<Vector3<T>>,
}

impl<T: Number> Loads<T> {
    /// `force` at `point` on `body` (nothing on ground).
    pub(super) fn push(
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
    pub(super) fn turn(&mut self, body: Option<usize>, torque: &Vector3<T>) {
        if let Some(body) = body {
            self.torque[body] += torque;
        }
    }
}
