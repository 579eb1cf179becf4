//! Marker frames and the kinematic measures of SPEC section 4, generic over
//! [`Number`] so that derivatives flow from the body states through the
//! frames (nalgebra over num-dual scalars).

use nalgebra::{Matrix3, SMatrix, Vector3};
use num_dual::DualNum;

use crate::Shown;
use crate::catalog::Function;
use crate::laws::intrinsics::atan2;
use crate::laws::{LawError, domain, range};
use crate::number::Number;

/// What a program keeps of one marker: the constants of its body and of its
/// place on the body. The body's state comes from the program's inputs.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameData {
    /// The marker's name or id, for messages.
    pub label: String,
    /// The index of the body it is on in [`crate::Scene::bodies`]; `None`
    /// for ground.
    pub body: Option<usize>,
    /// The body's orientation at the scene's time (identity for ground).
    pub body_orientation: Matrix3<f64>,
    /// The marker's origin in the body frame.
    pub offset: Vector3<f64>,
    /// The marker's axes relative to the body frame.
    pub axes: Matrix3<f64>,
    /// The body's acceleration, when the scene gives it (zero on ground).
    pub acceleration: Option<Vector3<f64>>,
    /// The body's angular acceleration, when the scene gives it (zero on ground).
    pub angular_acceleration: Option<Vector3<f64>>,
}

impl FrameData {
    /// The ground frame itself.
    pub fn ground() -> FrameData {
        FrameData {
            label: "ground".to_string(),
            body: None,
            body_orientation: Matrix3::identity(),
            offset: Vector3::zeros(),
            axes: Matrix3::identity(),
            acceleration: Some(Vector3::zeros()),
            angular_acceleration: Some(Vector3::zeros()),
        }
    }
}

/// A marker frame at the current state, in ground.
#[derive(Clone, Debug)]
pub struct Frame<T> {
    /// Origin.
    pub origin: Vector3<T>,
    /// Axes as columns.
    pub axes: Matrix3<T>,
    /// Velocity of the origin.
    pub velocity: Vector3<T>,
    /// Angular velocity.
    pub omega: Vector3<T>,
    /// Acceleration of the body's reference point (zero where the scene
    /// gives none); [`Frame::acceleration`] is that of the origin.
    pub body_acceleration: Vector3<T>,
    /// From the body's reference point to the origin, in ground.
    pub arm: Vector3<T>,
    /// Angular acceleration (zero where the scene gives none).
    pub alpha: Vector3<T>,
}

fn lift_vector<T: Number>(vector: &Vector3<f64>) -> Vector3<T> {
    vector.map(T::from)
}

fn lift_matrix<T: Number>(matrix: &Matrix3<f64>) -> Matrix3<T> {
    matrix.map(T::from)
}

fn skew<T: Number>(v: &Vector3<T>) -> Matrix3<T> {
    let zero = T::zero();
    Matrix3::new(
        zero.clone(),
        -v[2].clone(),
        v[1].clone(),
        v[2].clone(),
        zero.clone(),
        -v[0].clone(),
        -v[1].clone(),
        v[0].clone(),
        zero,
    )
}

/// `a * b` for a constant `b` (a matrix or a vector): each entry a sum of
/// numbers times `f64`s, with no dual products of constants.
pub(crate) fn times_constant<T: Number, const C: usize>(
    a: &Matrix3<T>,
    b: &SMatrix<f64, 3, C>,
) -> SMatrix<T, 3, C> {
    SMatrix::from_fn(|row, column| {
        (0..3)
            .map(|k| a[(row, k)].clone() * b[(k, column)])
            .reduce(|sum, term| sum + term)
            .expect("three terms")
    })
}

/// The rotation by the rotation vector `r` (Rodrigues). Below an angle of
/// 1e-3, `I + a S + b S²` with `a = sin t / t` and `b = (1 - cos t) / t²`
/// as series in `t² = r.r` (to `t⁴`, exact to rounding there): no square
/// root, whose slope is infinite at `r = 0`, and no `t²` that underflows
/// to a subnormal beneath a division (an angle of 1e-160 gave NaN).
fn rotation<T: Number>(r: &Vector3<T>) -> Matrix3<T> {
    let s = skew(r);
    let angle = r.map(|component| component.value()).norm();
    if angle == 0.0 && T::NDERIV <= 1 {
        // At a zero rotation `S²` and `t²` vanish with their first
        // derivatives: `I + S` is exact to first order (a simulation's
        // small rotations are all zero, seeded in their derivative parts).
        return Matrix3::identity() + s;
    }
    let s2 = &s * &s;
    if angle < 1e-3 {
        let t2 = r.dot(r);
        let a = T::one() - t2.clone() * (1.0 / 6.0) + t2.clone() * t2.clone() * (1.0 / 120.0);
        let b = T::from(0.5) - t2.clone() * (1.0 / 24.0) + t2.clone() * t2 * (1.0 / 720.0);
        return Matrix3::identity() + s * a + s2 * b;
    }
    let theta = DualNum::sqrt(&r.dot(r));
    let a = DualNum::sin(&theta) / theta.clone();
    let b = (T::one() - DualNum::cos(&theta)) / (theta.clone() * theta);
    Matrix3::identity() + s * a + s2 * b
}

impl<T: Number> Frame<T> {
    /// The frame of a marker on ground.
    pub fn fixed(data: &FrameData) -> Frame<T> {
        Frame {
            origin: lift_vector(&data.offset),
            axes: lift_matrix(&data.axes),
            velocity: Vector3::zeros(),
            omega: Vector3::zeros(),
            body_acceleration: Vector3::zeros(),
            arm: Vector3::zeros(),
            alpha: Vector3::zeros(),
        }
    }

    /// The frame of a marker on a body whose state is `state`: position,
    /// small rotation, velocity and angular velocity, three each.
    pub fn on_body(data: &FrameData, state: [&T; 12]) -> Frame<T> {
        let vector = |first: usize| {
            Vector3::new(
                state[first].clone(),
                state[first + 1].clone(),
                state[first + 2].clone(),
            )
        };
        let (position, small_rotation, velocity, omega) =
            (vector(0), vector(3), vector(6), vector(9));
        // A rotation that is no derivative direction (the usual case) turns
        // the body in plain f64: no dual products of constants.
        let (arm, axes) = if small_rotation.iter().all(Number::is_constant) {
            let turn = small_rotation.map(|component| component.value());
            let turned = if turn == Vector3::zeros() {
                data.body_orientation
            } else {
                rotation(&turn) * data.body_orientation
            };
            (
                lift_vector(&(turned * data.offset)),
                lift_matrix(&(turned * data.axes)),
            )
        } else {
            let turned = times_constant(&rotation(&small_rotation), &data.body_orientation);
            (
                times_constant(&turned, &data.offset),
                times_constant(&turned, &data.axes),
            )
        };
        let body_acceleration = data
            .acceleration
            .map_or_else(Vector3::zeros, |a| lift_vector(&a));
        let alpha = data
            .angular_acceleration
            .map_or_else(Vector3::zeros, |a| lift_vector(&a));
        Frame {
            origin: position + &arm,
            axes,
            velocity: velocity + omega.cross(&arm),
            body_acceleration,
            arm,
            omega,
            alpha,
        }
    }

    /// The acceleration of the origin (computed only for the measures
    /// that need it).
    pub fn acceleration(&self) -> Vector3<T> {
        &self.body_acceleration
            + self.alpha.cross(&self.arm)
            + self.omega.cross(&self.omega.cross(&self.arm))
    }

    fn axis(&self, index: usize) -> Vector3<T> {
        self.axes.column(index).into_owned()
    }
}

/// `|v|` (its derivative is infinite where `v` is 0, which the evaluator
/// reports), with no overflow of the squares for components beyond 1e154.
fn length<T: Number>(v: &Vector3<T>) -> T {
    range::length(v.as_slice())
}

/// The value of `measure` for frames `i, j, k, l` as its signature orders
/// them (omitted markers already replaced by ground; INCANG's three are
/// `i, j, j, k`), with the constants `selector` gives ORIENT and INCANG.
pub fn measure<T: Number>(
    function: Function,
    selector: Selector,
    frames: &[&Frame<T>],
) -> Result<T, LawError> {
    use Function as F;
    let i = frames[0];
    let j = frames[1];
    let d = &i.origin - &j.origin;
    // Time derivative of d in frame `l`: d' = (v_i - v_j) - w_l x d.
    let rate_in = |l: &Frame<T>| (&i.velocity - &j.velocity) - l.omega.cross(&d);
    let acceleration_in = |l: &Frame<T>| {
        let rate = rate_in(l);
        (i.acceleration() - j.acceleration())
            - l.alpha.cross(&d)
            - l.omega.cross(&rate) * T::from(2.0)
            - l.omega.cross(&l.omega.cross(&d))
    };
    let omega = &i.omega - &j.omega;
    let omega_rate_in = |l: &Frame<T>| (&i.alpha - &j.alpha) - l.omega.cross(&omega);
    Ok(match function {
        F::Dx | F::Dy | F::Dz => d.dot(&frames[2].axis(axis_of(function))),
        F::Dm => length(&d),
        F::Vx | F::Vy | F::Vz => rate_in(frames[3]).dot(&frames[2].axis(axis_of(function))),
        F::Vm => length(&rate_in(frames[2])),
        F::Vr => {
            let distance = length(&d);
            if distance.value() == 0.0 {
                return domain(
                    "VR",
                    "the markers coincide: the radial direction is not defined".to_string(),
                );
            }
            range::quotient(&d.dot(&rate_in(frames[2])), &distance)
        }
        F::Accx | F::Accy | F::Accz => {
            acceleration_in(frames[3]).dot(&frames[2].axis(axis_of(function)))
        }
        F::Accm => length(&acceleration_in(frames[2])),
        F::Wx | F::Wy | F::Wz => omega.dot(&frames[2].axis(axis_of(function))),
        F::Wm => length(&omega),
        F::Wdtx | F::Wdty | F::Wdtz => {
            omega_rate_in(frames[3]).dot(&frames[2].axis(axis_of(function)))
        }
        F::Wdtm => length(&omega_rate_in(frames[2])),
        F::Ax | F::Ay | F::Az => {
            // The rotation of i about one axis of j, as Adams computes it:
            // an axis of i seen in the plane of j's other two axes. AX
            // follows i's z axis in j's y-z plane (from z towards -y), AY
            // i's z axis in j's z-x plane, AZ i's x axis in j's x-y plane.
            let (moved, sine, cosine) = match function {
                F::Ax => (2, 1, 2),
                F::Ay => (2, 0, 2),
                _ => (0, 1, 0),
            };
            let moved = i.axis(moved);
            let sine = moved.dot(&j.axis(sine));
            let sine = if function == F::Ax { -sine } else { sine };
            atan2(&sine, &moved.dot(&j.axis(cosine)))
        }
        F::Psi | F::Theta | F::Phi | F::Yaw | F::Pitch | F::Roll => {
            let relative = j.axes.transpose() * &i.axes;
            let c = |row: usize, column: usize| relative[(row, column)].clone();
            // At gimbal lock (THETA = 0 or pi; PITCH = +-90 degrees) the
            // first and third angles turn about one axis: the first takes the
            // whole turn and the third is 0.
            let zero = |row: usize, column: usize| c(row, column).value() == 0.0;
            let euler_locked = zero(0, 2) && zero(1, 2);
            let cardan_locked = zero(0, 0) && zero(1, 0);
            match function {
                F::Psi if euler_locked => atan2(&c(1, 0), &c(0, 0)),
                F::Psi => atan2(&c(0, 2), &-c(1, 2)),
                F::Theta => DualNum::acos(&within_unit("THETA", c(2, 2))?),
                F::Phi if euler_locked => T::zero(),
                F::Phi => atan2(&c(2, 0), &c(2, 1)),
                F::Yaw if cardan_locked => T::zero(),
                F::Yaw => atan2(&c(1, 0), &c(0, 0)),
                F::Pitch => DualNum::asin(&within_unit("PITCH", c(2, 0))?),
                _ if cardan_locked => atan2(&-c(1, 2), &c(1, 1)),
                _ => atan2(&c(2, 1), &c(2, 2)),
            }
        }
        F::Orient => match selector {
            Selector::Orientation(orientation) => orientation.of(&(j.axes.transpose() * &i.axes))?,
            _ => unreachable!("ORIENT is compiled with its orientation system"),
        },
        F::Incang => {
            let first = d;
            let second = &frames[3].origin - &frames[2].origin;
            let normal = match selector {
                Selector::Normal(bits) => Vector3::from(bits.map(f64::from_bits)),
                _ => Vector3::zeros(),
            };
            let across = first.cross(&second);
            let sine = if normal == Vector3::zeros() {
                length(&across)
            } else {
                across.dot(&lift_vector(&normal))
            };
            let cosine = first.dot(&second);
            if sine.value() == 0.0 && cosine.value() == 0.0 {
                return domain(
                    "INCANG",
                    "a line has no length: two of its markers coincide".to_string(),
                );
            }
            atan2(&sine, &cosine)
        }
        _ => unreachable!("{function} is not a measure a scene evaluates"),
    })
}

/// The constants a measure reads besides its marker frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Selector {
    /// Nothing (every measure but ORIENT and INCANG).
    #[default]
    Plain,
    /// ORIENT's orientation system and component.
    Orientation(Orientation),
    /// INCANG's axis: the unit normal of its two lines where the model is
    /// drawn (the bits of its components), the angle measured about it with
    /// the right-hand rule; zero where the lines are drawn parallel.
    Normal([u64; 3]),
}

/// Which value `ORIENT(system, component, i, j)` gives, checked when the
/// expression is compiled: an angle of one of the twelve body-fixed (1 to
/// 12) or space-fixed (13 to 24) Euler sequences, an Euler parameter (27),
/// a Rodriguez parameter (28) or a direction cosine (29) of the rotation
/// of `i`'s axes from `j`'s.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Orientation {
    system: u8,
    component: u8,
}

/// The body-fixed sequences of ORIENT's systems 1 to 12 (13 to 24 are the
/// same sequences about space-fixed axes), as axis indices.
const SEQUENCES: [[usize; 3]; 12] = [
    [0, 1, 2],
    [1, 2, 0],
    [2, 0, 1],
    [0, 2, 1],
    [1, 0, 2],
    [2, 1, 0],
    [0, 1, 0],
    [0, 2, 0],
    [1, 0, 1],
    [1, 2, 1],
    [2, 0, 2],
    [2, 1, 2],
];

impl Orientation {
    /// The orientation system and component as written, or what is wrong
    /// with them.
    pub fn new(system: i64, component: i64) -> Result<Orientation, String> {
        let components = match system {
            1..=24 | 28 => 3,
            27 => 4,
            29 => 9,
            _ => {
                return Err(format!(
                    "orientation system {system} is not one mbexpr evaluates: 1 to 12 are body-fixed Euler sequences, 13 to 24 space-fixed ones, 27 Euler parameters, 28 Rodriguez parameters, 29 direction cosines"
                ));
            }
        };
        if !(1..=components).contains(&component) {
            return Err(format!(
                "orientation system {system} has components 1 to {components}, not {component}"
            ));
        }
        Ok(Orientation {
            system: system as u8,
            component: component as u8,
        })
    }

    /// Whether it is an Euler parameter (system 27).
    pub fn is_euler_parameter(self) -> bool {
        self.system == 27
    }

    /// The component of the rotation `relative` (`i`'s axes as columns in
    /// `j`'s).
    fn of<T: Number>(self, relative: &Matrix3<T>) -> Result<T, LawError> {
        let component = usize::from(self.component) - 1;
        match self.system {
            system @ 1..=12 => euler_angle(relative, SEQUENCES[usize::from(system) - 1], component),
            system @ 13..=24 => {
                // About fixed axes p, q, r by a, b, c: the body-fixed
                // sequence r, q, p by c, b, a.
                let [p, q, r] = SEQUENCES[usize::from(system) - 13];
                euler_angle(relative, [r, q, p], 2 - component)
            }
            27 => Ok(euler_parameters(relative)[component].clone()),
            28 => {
                let parameters = euler_parameters(relative);
                if parameters[0].value() == 0.0 {
                    return domain(
                        "ORIENT",
                        "Rodriguez parameters are not defined for a half turn".to_string(),
                    );
                }
                Ok(parameters[component + 1].clone() / parameters[0].clone())
            }
            _ => Ok(relative[(component % 3, component / 3)].clone()),
        }
    }
}

/// Angle `which` (0, 1, 2) of the body-fixed sequence of rotations about
/// axes `p, q, r` that gives `relative`. Where the sequence is locked (the
/// second angle makes the first and third turn about one axis) the first
/// takes the whole turn and the third is 0, as for PSI and PHI.
fn euler_angle<T: Number>(
    relative: &Matrix3<T>,
    [p, q, r]: [usize; 3],
    which: usize,
) -> Result<T, LawError> {
    let c = |row: usize, column: usize| relative[(row, column)].clone();
    let zero = |row: usize, column: usize| relative[(row, column)].value() == 0.0;
    // The third axis, and the sign of e_p x e_q along it.
    let other = 3 - p - q;
    let sign = if (p + 1) % 3 == q { 1.0 } else { -1.0 };
    let locked_first = || atan2(&(c(other, q) * sign), &c(q, q));
    Ok(if p != r {
        let locked = zero(q, r) && zero(r, r);
        match which {
            0 if locked => locked_first(),
            0 => atan2(&(c(q, r) * -sign), &c(r, r)),
            1 => DualNum::asin(&within_unit("ORIENT", c(p, r) * sign)?),
            _ if locked => T::zero(),
            _ => atan2(&(c(p, q) * -sign), &c(p, p)),
        }
    } else {
        let locked = zero(q, p) && zero(other, p);
        match which {
            0 if locked => locked_first(),
            0 => atan2(&c(q, p), &(c(other, p) * -sign)),
            1 => DualNum::acos(&within_unit("ORIENT", c(p, p))?),
            _ if locked => T::zero(),
            _ => atan2(&c(p, q), &(c(p, other) * sign)),
        }
    })
}

/// The Euler parameters `e0 e1 e2 e3` of the rotation `a` (Shepperd's
/// method: the square root taken of the largest, so no division by a small
/// one), `e0` not negative.
pub(crate) fn euler_parameters<T: Number>(a: &Matrix3<T>) -> [T; 4] {
    let c = |row: usize, column: usize| a[(row, column)].clone();
    let trace = c(0, 0) + c(1, 1) + c(2, 2);
    let diagonal = [a[(0, 0)].value(), a[(1, 1)].value(), a[(2, 2)].value()];
    let largest = (0..3).fold(None, |best: Option<usize>, k| match best {
        Some(b) if diagonal[b] >= diagonal[k] => Some(b),
        _ => Some(k),
    });
    let half_root = |squared: T| DualNum::sqrt(&squared) * 0.5;
    let parameters = match largest {
        Some(k) if diagonal[k] > trace.value() => {
            let (m, n) = ((k + 1) % 3, (k + 2) % 3);
            let big = half_root(T::one() + c(k, k) * 2.0 - trace);
            let quarter = big.clone() * 4.0;
            let mut e = [T::zero(), T::zero(), T::zero(), T::zero()];
            e[0] = (c(n, m) - c(m, n)) / quarter.clone();
            e[m + 1] = (c(m, k) + c(k, m)) / quarter.clone();
            e[n + 1] = (c(n, k) + c(k, n)) / quarter;
            e[k + 1] = big;
            e
        }
        _ => {
            let e0 = half_root(T::one() + trace);
            let quarter = e0.clone() * 4.0;
            [
                e0,
                (c(2, 1) - c(1, 2)) / quarter.clone(),
                (c(0, 2) - c(2, 0)) / quarter.clone(),
                (c(1, 0) - c(0, 1)) / quarter,
            ]
        }
    };
    if parameters[0].value() < 0.0 {
        parameters.map(|e| -e)
    } else {
        parameters
    }
}

/// A cosine or sine from rotation matrices, clamped to [-1, 1] against
/// rounding (a value beyond it by more than rounding is an error).
fn within_unit<T: Number>(name: &'static str, value: T) -> Result<T, LawError> {
    let v = value.value();
    if v.abs() > 1.0 + 1e-12 {
        return domain(
            name,
            format!("the orientation is not a rotation ({})", Shown(v)),
        );
    }
    if v.abs() > 1.0 {
        return Ok(T::from(v.signum()));
    }
    Ok(value)
}

/// 0, 1, 2 for the x, y, z variant of a measure.
fn axis_of(function: Function) -> usize {
    let name = function.name();
    match name.as_bytes()[name.len() - 1] {
        b'X' => 0,
        b'Y' => 1,
        _ => 2,
    }
}
