//! Joints: constraint equations between two markers' frames, held by
//! Lagrange multipliers on the rigid bodies (Adams Solver's semantics: a
//! joint's I and J markers, its axes their z axes).
//!
//! The formulation is the index-1 one: at each right-hand side the
//! accelerations and the multipliers solve
//!
//! ```text
//! [ M  Gᵀ ] [ u' ]   [ f     ]
//! [ G  0  ] [ λ  ] = [ −bias ]
//! ```
//!
//! (`u` each body's centre-of-mass velocity and angular velocity in
//! ground, `M` their masses and inertias, `f` the applied forces and
//! torques, `G u = Φ'` the constraints' rates, `bias` the part of `Φ''`
//! the accelerations do not reach; [`rows`]), so the equations stay an
//! ODE that both Radau5 and DOP853 integrate, and written over any
//! [`crate::number::Number`] the multipliers carry their exact
//! derivatives into the Jacobian. The positions and velocities drift off
//! the constraints by the integration error; [`project`] puts them back
//! (the mass-weighted least change) whenever a residual passes the
//! absolute tolerance, before the run, after every accepted step and
//! after every located switch.
//!
//! Equations that repeat others (a planar loop of revolute joints, whose
//! out-of-plane equations are dependent) are found once, at the initial
//! state, and left out ([`Joint::redundant`]), as Adams removes them.

mod curve_curve;
mod drives;
mod general;
mod on_curve;
pub(crate) mod quadrature;
mod reactions;
mod rows;
mod solve;

pub(crate) use drives::{CurveSite, Drive, Drives, Imposed, MOTIONS, Pieces, curve_sites};
pub(crate) use general::{GeneralConstraints, bodies_of};
pub(crate) use reactions::{Component, Reactions, component_and_rm, flags, pick};
pub(crate) use rows::BodyMotion;
pub use solve::Residuals;
pub(crate) use solve::{
    Tolerance, Unassembled, Unheld, acceleration_residual, body_quaternion, constraint_loads,
    disagreeing_redundant, find_redundant, first_repeated, held_equations, multiplier_loads,
    project,
};

use nalgebra::Vector3;

use crate::scene::Target;
use crate::simulate::model::{Along, Joint, JointInitial, JointKind};
use rows::{Moving, Row};

/// A marker's frame in motion: its origin and its three axes.
struct Frame<T: crate::number::Number> {
    origin: Moving<T>,
    axes: [Moving<T>; 3],
}

/// The frame of marker `target`, bodies moving as `bodies` say.
fn frame<T: crate::number::Number>(
    model: &super::Model,
    target: &Target,
    bodies: &[BodyMotion<T>],
) -> Frame<T> {
    let (body, position, axes) = match target {
        Target::Ground => (None, Vector3::zeros(), nalgebra::Matrix3::identity()),
        Target::Marker(index) => {
            let marker = &model.scene.markers[*index];
            let axes = marker.orientation.to_rotation_matrix().into_inner();
            match marker.body {
                None => (None, marker.position, axes),
                Some(body) => (
                    Some(body),
                    marker.position - model.masses[body].centre,
                    axes,
                ),
            }
        }
    };
    let moving = body.map(|body| (body, &bodies[body]));
    Frame {
        origin: Moving::point(moving, &position, &position),
        axes: [0, 1, 2].map(|axis| Moving::axis(moving, &axes.column(axis).into_owned())),
    }
}

/// The curves of PTCV or CVCV `joint` (a PTCV's one, a CVCV's ICURVE and
/// JCURVE), each with the parameter of its point of contact at the state
/// `bodies` give (not a number where none is found): a CVCV's with its
/// curves on the pieces `pieces` holds them on, a PTCV's the curve's point
/// nearest its I marker; none for another joint.
pub(crate) fn curve_contacts<'j>(
    model: &super::Model,
    joint: &'j Joint,
    bodies: &[BodyMotion<f64>],
    pieces: Pieces,
) -> Vec<(&'j crate::simulate::curve::Curve, f64)> {
    if let Some(on) = &joint.curve {
        let alpha = on_curve::contact_parameter(model, joint, on, bodies).unwrap_or(f64::NAN);
        return vec![(&on.curve, alpha)];
    }
    let Some(pair) = &joint.pair else {
        return Vec::new();
    };
    let (alpha, beta) = curve_curve::contact_parameters(model, joint, pair, bodies, pieces)
        .unwrap_or((f64::NAN, f64::NAN));
    vec![(&pair.i.curve, alpha), (&pair.j.curve, beta)]
}

/// The equations of `joint` (all of them, redundant ones too), in order;
/// a PTCV's or a CVCV's with its curves on the pieces `pieces` gives.
fn joint_rows<T: crate::number::Number>(
    model: &super::Model,
    joint: &Joint,
    bodies: &[BodyMotion<T>],
    pieces: Pieces,
) -> Vec<Row<T>> {
    if let Some(on) = &joint.curve {
        return on_curve::curve_rows(model, joint, on, bodies, pieces[0]);
    }
    if let Some(pair) = &joint.pair {
        return curve_curve::curve_rows(model, joint, pair, bodies, pieces);
    }
    let i = frame(model, &joint.i, bodies);
    let j = frame(model, &joint.j, bodies);
    let apart = i.origin.minus(&j.origin);
    let [xi, yi, zi] = &i.axes;
    let [xj, yj, zj] = &j.axes;
    let together = || (0..3).map(|axis| apart.component(axis));
    let parallel = || [zi.dot(xj), zi.dot(yj)];
    match joint.kind {
        JointKind::Spherical => together().collect(),
        JointKind::Revolute => together().chain(parallel()).collect(),
        JointKind::Fixed => together().chain(parallel()).chain([xi.dot(yj)]).collect(),
        JointKind::Cylindrical => [xj.dot(&apart), yj.dot(&apart)]
            .into_iter()
            .chain(parallel())
            .collect(),
        JointKind::Translational => [xj.dot(&apart), yj.dot(&apart)]
            .into_iter()
            .chain(parallel())
            .chain([xi.dot(yj)])
            .collect(),
        JointKind::Planar => [zj.dot(&apart)].into_iter().chain(parallel()).collect(),
        JointKind::Universal => together().chain([zi.dot(zj)]).collect(),
        JointKind::Hooke => together().chain([xi.dot(yj)]).collect(),
        JointKind::Convel => together()
            .chain([xi.dot(yj).plus_scaled(yi.dot(xj), 1.0)])
            .collect(),
        JointKind::RackPin => {
            // The pinion's turn about z_i, less a constant: minus the
            // angle of the rack's direction in the pinion's x-y plane.
            let radius = 0.5 * joint.pitch;
            let turned = Row::angle(yi.dot(zj), xi.dot(zj));
            let mut row = zj.dot(&apart).plus_scaled(turned, radius);
            row.wrap(std::f64::consts::TAU * radius);
            vec![row]
        }
        JointKind::Screw => {
            let turned = Row::angle(xi.dot(yj), xi.dot(xj));
            let mut row = zj
                .dot(&apart)
                .plus_scaled(turned, -joint.pitch / std::f64::consts::TAU);
            row.wrap(joint.pitch);
            vec![row]
        }
        JointKind::AtPoint => together().collect(),
        JointKind::InLine => vec![xj.dot(&apart), yj.dot(&apart)],
        JointKind::InPlane => vec![zj.dot(&apart)],
        JointKind::Orientation => parallel().into_iter().chain([xi.dot(yj)]).collect(),
        JointKind::ParallelAxes => parallel().into_iter().collect(),
        JointKind::Perpendicular => vec![zi.dot(zj)],
        JointKind::PointCurve => unreachable!("a PTCV is read with its curve"),
        JointKind::CurveCurve => unreachable!("a CVCV is read with its curves"),
    }
}

/// The displacement of `joint` along (or, `rotation`, about) its J
/// marker's z axis: I's origin from J's along it, or the angle of I's x
/// axis from J's towards J's y axis (a MOTION's, a COUPLER's and an IC's
/// measure).
fn joint_displacement<T: crate::number::Number>(
    model: &super::Model,
    joint: &Joint,
    rotation: bool,
    bodies: &[BodyMotion<T>],
) -> Row<T> {
    let i = frame(model, &joint.i, bodies);
    let j = frame(model, &joint.j, bodies);
    if rotation {
        let [xi, _, _] = &i.axes;
        let [xj, yj, _] = &j.axes;
        Row::angle(xi.dot(yj), xi.dot(xj))
    } else {
        j.axes[2].dot(&i.origin.minus(&j.origin))
    }
}

/// The joints' initial conditions that give a displacement: those with a
/// row in the analysis of the positions, in its order.
pub(super) fn positioned_initials(model: &super::Model) -> impl Iterator<Item = &JointInitial> {
    model
        .joint_initials
        .iter()
        .filter(|initial| initial.displacement.is_some())
}

/// The initial conditions as equations at `bodies`: with `velocities`
/// false, each joint's displacement and each PART's EXACT coordinate (to
/// hold in the analysis of the positions) and each PTCV's DISP; with
/// `velocities` true, each joint's given velocity and each PTCV's VEL,
/// their values zero (to hold in the analysis of the velocities).
fn initial_rows(
    model: &super::Model,
    bodies: &[BodyMotion<f64>],
    velocities: bool,
) -> Vec<Row<f64>> {
    let mut rows = Vec::new();
    for initial in &model.joint_initials {
        let mut row = joint_displacement(
            model,
            &model.joints[initial.joint],
            initial.rotation,
            bodies,
        );
        if velocities {
            let Some(velocity) = initial.velocity else {
                continue;
            };
            row.value = 0.0;
            row.rate -= velocity;
        } else {
            let Some(displacement) = initial.displacement else {
                continue;
            };
            row.value -= displacement;
            if initial.rotation {
                row.wrap(std::f64::consts::TAU);
            }
        }
        rows.push(row);
    }
    if velocities {
        for joint in &model.joints {
            if let Some((on, speed)) = curve_speed(joint) {
                rows.push(on_curve::speed_row(model, joint, on, speed, bodies));
            }
            if let Some(pair) = &joint.pair {
                rows.extend(curve_curve::speed_rows(model, joint, pair, bodies));
            }
        }
    } else {
        for part in &model.exact {
            rows.extend(exact_rows(part, &bodies[part.body]));
        }
        for joint in &model.joints {
            if let Some((on, start)) = curve_start(joint) {
                rows.push(on_curve::start_row(model, joint, on, start, bodies));
            }
            if let Some(pair) = &joint.pair {
                rows.extend(curve_curve::start_rows(model, joint, pair, bodies));
            }
        }
    }
    rows
}

/// The velocity components the PARTs give, as equations at `bodies` whose
/// rates are their residuals (see [`given_velocity_rows`]).
fn given_velocities(model: &super::Model, bodies: &[BodyMotion<f64>]) -> Vec<Row<f64>> {
    model
        .given_velocities
        .iter()
        .flat_map(|given| given_velocity_rows(model, given, &bodies[given.body]))
        .collect()
}

/// The equations that keep the velocity components a PART gives at their
/// values (in the analysis of the velocities, as nearly as the joints let
/// them): `VX, VY, VZ`, the velocity
/// of the VM marker's origin along ground's axes, `v + ω × r` with `r`
/// from the centre of mass; `WX, WY, WZ`, the angular velocity about the
/// WM marker's axes.
fn given_velocity_rows(
    model: &super::Model,
    given: &super::model::GivenVelocity,
    body: &BodyMotion<f64>,
) -> Vec<Row<f64>> {
    let arm = body.rotation * (given.point - model.masses[given.body].centre);
    let axes = body.rotation * given.axes;
    let row = |rate: f64, linear: Vector3<f64>, angular: Vector3<f64>| Row {
        value: 0.0,
        rate,
        bias: 0.0,
        coefficients: vec![(
            given.body,
            [
                linear.x, linear.y, linear.z, angular.x, angular.y, angular.z,
            ],
        )],
    };
    let mut rows = Vec::new();
    for (k, value) in given.values.iter().enumerate() {
        let Some(value) = value else { continue };
        if k < 3 {
            let along = Vector3::ith(k, 1.0);
            let velocity = body.velocity + body.omega.cross(&arm);
            rows.push(row(velocity[k] - value, along, arm.cross(&along)));
        } else {
            let axis = axes.column(k - 3).into_owned();
            rows.push(row(body.omega.dot(&axis) - value, Vector3::zeros(), axis));
        }
    }
    rows
}

/// The equations that keep the coordinates `part` lists at their drawn
/// values (in the analysis of the positions only: their rates and biases
/// are not used). All three angles are kept together through the turn
/// from the drawn axes, well defined at any orientation; one or two of
/// them through the 3-1-3 angles, whose rates `[ψ', θ', φ'] = B⁻¹ ω` with
/// `B = [z | n | z_F]` (`n` the line of nodes), or, for a part drawn at θ
/// = 0 or π (a planar model in ground's x-y plane), where `B` is singular,
/// through its z axis and its turn about it.
fn exact_rows(part: &super::model::ExactPart, body: &BodyMotion<f64>) -> Vec<Row<f64>> {
    let along = |value: f64, linear: [f64; 3], angular: [f64; 3]| Row {
        value,
        rate: 0.0,
        bias: 0.0,
        coefficients: vec![(
            part.body,
            [
                linear[0], linear[1], linear[2], angular[0], angular[1], angular[2],
            ],
        )],
    };
    let mut rows = Vec::new();
    for k in 0..3 {
        if part.coordinates[k] {
            let mut unit = [0.0; 3];
            unit[k] = 1.0;
            rows.push(along(body.centre[k] - part.centre[k], unit, [0.0; 3]));
        }
    }
    let axes = body.rotation * part.cm_axes;
    let angles = &part.coordinates[3..];
    if angles.iter().all(|kept| *kept) {
        let turned =
            nalgebra::Rotation3::from_matrix_unchecked(axes * part.axes.transpose()).scaled_axis();
        for k in 0..3 {
            let mut unit = [0.0; 3];
            unit[k] = 1.0;
            rows.push(along(turned[k], [0.0; 3], unit));
        }
    } else if drawn_level(part) {
        // Drawn with θ at 0 or π, where ψ and φ turn about the same axis:
        // THETA keeps the z axis where it was (its x and y components),
        // PSI or PHI the turn about it (the angle of the x axis in ground's
        // x-y plane, ψ ± φ).
        let z = axes.column(2);
        if angles[1] {
            rows.push(along(
                z[0] - part.axes[(0, 2)],
                [0.0; 3],
                [0.0, z[2], -z[1]],
            ));
            rows.push(along(
                z[1] - part.axes[(1, 2)],
                [0.0; 3],
                [-z[2], 0.0, z[0]],
            ));
        }
        if angles[0] || angles[2] {
            let x = axes.column(0);
            let r2 = x[0] * x[0] + x[1] * x[1];
            let mut change = x[1].atan2(x[0]) - part.axes[(1, 0)].atan2(part.axes[(0, 0)]);
            change -= (change / std::f64::consts::TAU).round() * std::f64::consts::TAU;
            rows.push(along(
                change,
                [0.0; 3],
                [-x[2] * x[0] / r2, -x[2] * x[1] / r2, 1.0],
            ));
        }
    } else if angles.contains(&true) {
        let now = euler_313(&axes);
        let drawn = euler_313(&part.axes);
        let (sin_psi, cos_psi) = now[0].sin_cos();
        let b = nalgebra::Matrix3::from_columns(&[
            Vector3::z(),
            Vector3::new(cos_psi, sin_psi, 0.0),
            axes.column(2).into_owned(),
        ]);
        let inverse = b.try_inverse().unwrap_or_else(nalgebra::Matrix3::zeros);
        for k in 0..3 {
            if angles[k] {
                let mut change = now[k] - drawn[k];
                if k != 1 {
                    change -= (change / std::f64::consts::TAU).round() * std::f64::consts::TAU;
                }
                let row = inverse.row(k);
                rows.push(along(change, [0.0; 3], [row[0], row[1], row[2]]));
            }
        }
    }
    rows
}

/// A PTCV's curve and the parameter its DISP sets at the start, when it
/// gives one.
fn curve_start(joint: &Joint) -> Option<(&super::OnCurve, f64)> {
    let on = joint.curve.as_ref()?;
    Some((on, on.start?))
}

/// A PTCV's curve and the speed along it its VEL gives, if it does.
fn curve_speed(joint: &Joint) -> Option<(&super::OnCurve, f64)> {
    let on = joint.curve.as_ref()?;
    Some((on, on.speed?))
}

/// Whether `part` was drawn with its CM marker's z axis along ground's
/// (θ at 0 or π), where its 3-1-3 angles ψ and φ are not apart.
fn drawn_level(part: &super::model::ExactPart) -> bool {
    part.axes[(2, 2)].abs() > 1.0 - 1e-9
}

/// How many equations [`exact_rows`] gives for `part`.
fn exact_row_count(part: &super::model::ExactPart) -> usize {
    let listed = |coordinates: &[bool]| coordinates.iter().filter(|kept| **kept).count();
    let angles = &part.coordinates[3..];
    let angle_rows = if angles.iter().all(|kept| *kept) || !drawn_level(part) {
        listed(angles)
    } else {
        2 * usize::from(angles[1]) + usize::from(angles[0] || angles[2])
    };
    listed(&part.coordinates[..3]) + angle_rows
}

/// The body 3-1-3 angles `[ψ, θ, φ]` of `axes` (columns in ground): `axes
/// = Rz(ψ) Rx(θ) Rz(φ)`.
fn euler_313(axes: &nalgebra::Matrix3<f64>) -> Vector3<f64> {
    let theta = axes[(2, 2)].clamp(-1.0, 1.0).acos();
    let psi = axes[(0, 2)].atan2(-axes[(1, 2)]);
    let phi = axes[(2, 0)].atan2(axes[(2, 1)]);
    Vector3::new(psi, theta, phi)
}

/// The equation of `motion` at the displacement `drive` gives.
fn motion_row<T: crate::number::Number>(
    model: &super::Model,
    motion: &super::model::Motion,
    drive: &Drive,
    bodies: &[BodyMotion<T>],
) -> Row<T> {
    let mut row = joint_displacement(model, &model.joints[motion.joint], motion.rotation, bodies);
    row.value -= T::from(drive.value);
    if motion.rotation {
        // The angle's value modulo a turn, nearest the displacement.
        row.wrap(std::f64::consts::TAU);
    }
    row.rate -= T::from(drive.rate);
    row.bias -= T::from(drive.acceleration);
    row
}

/// The equation of `motion` between markers at the displacement `drive`
/// gives.
fn marker_motion_row<T: crate::number::Number>(
    model: &super::Model,
    motion: &super::model::MarkerMotion,
    drive: &Drive,
    bodies: &[BodyMotion<T>],
) -> Row<T> {
    let i = frame(model, &motion.i, bodies);
    let j = frame(model, &motion.j, bodies);
    let [xi, yi, zi] = &i.axes;
    let [xj, yj, zj] = &j.axes;
    // Entry (a, b) of the rotation from J's axes to I's is J's axis a
    // dotted with I's axis b.
    let mut row = match motion.along {
        Along::Axis(axis) => j.axes[axis].dot(&i.origin.minus(&j.origin)),
        Along::Angle(0) => Row::angle(yj.dot(zi).scaled(-1.0), zj.dot(zi)),
        Along::Angle(2) => Row::angle(xj.dot(yi).scaled(-1.0), xj.dot(xi)),
        Along::Angle(_) => {
            // sin b2 = R02, less the sine of the displacement.
            let mut row = xj.dot(zi);
            let (sine, cosine) = drive.value.sin_cos();
            row.value -= T::from(sine);
            row.rate -= T::from(cosine * drive.rate);
            row.bias -= T::from(cosine * drive.acceleration - sine * drive.rate * drive.rate);
            return row;
        }
    };
    row.value -= T::from(drive.value);
    if matches!(motion.along, Along::Angle(_)) {
        row.wrap(std::f64::consts::TAU);
    }
    row.rate -= T::from(drive.rate);
    row.bias -= T::from(drive.acceleration);
    row
}

/// The model's equations held in the run (the redundant ones left out),
/// the motions' at the displacements `imposed` gives, the general
/// constraints' last at its time.
fn active_rows<T: crate::number::Number>(
    model: &super::Model,
    bodies: &[BodyMotion<T>],
    imposed: &Imposed<'_>,
) -> Vec<Row<T>> {
    let drives = &imposed.drives;
    let mut rows = Vec::new();
    for (index, joint) in model.joints.iter().enumerate() {
        rows.extend(kept_rows(model, joint, bodies, imposed.pieces(index)));
    }
    for (motion, drive) in model.motions.iter().zip(drives) {
        rows.push(motion_row(model, motion, drive, bodies));
    }
    let marker_drives = drives.get(model.motions.len()..).unwrap_or_default();
    for (motion, drive) in model.marker_motions.iter().zip(marker_drives) {
        rows.push(marker_motion_row(model, motion, drive, bodies));
    }
    for coupler in &model.couplers {
        rows.push(coupler_row(model, coupler, bodies));
    }
    for index in 0..model.general_constraints.len() {
        rows.push(imposed.general.row(model, index, imposed.time, bodies));
    }
    rows
}

/// A holder of equations (a joint, a motion, a coupler, a GCON) as the
/// Jacobian's pattern sees it: how many of the held equations it gives and
/// the bodies they move.
pub(crate) struct Holder {
    /// Its held equations (a joint's without the redundant ones).
    pub(crate) equations: usize,
    /// The bodies its equations move, without repeats (none on ground).
    pub(crate) bodies: Vec<usize>,
}

/// The holders of `model`'s held equations, in [`active_rows`]' order, so
/// that their equations follow one another in it.
pub(crate) fn holders(model: &super::Model) -> Vec<Holder> {
    let body_of = |target: &Target| model.scene.body_of(target);
    let joint_bodies = |joint: &Joint| [body_of(&joint.i), body_of(&joint.j)];
    let holder = |equations: usize, bodies: Vec<Option<usize>>| {
        let mut bodies: Vec<usize> = bodies.into_iter().flatten().collect();
        bodies.sort_unstable();
        bodies.dedup();
        Holder { equations, bodies }
    };
    let joints = model
        .joints
        .iter()
        .map(|joint| holder(joint.held_equations(), joint_bodies(joint).to_vec()));
    let motions = model
        .motions
        .iter()
        .map(|motion| holder(1, joint_bodies(&model.joints[motion.joint]).to_vec()));
    let marker_motions = model
        .marker_motions
        .iter()
        .map(|motion| holder(1, vec![body_of(&motion.i), body_of(&motion.j)]));
    let couplers = model.couplers.iter().map(|coupler| {
        let bodies = coupler
            .joints
            .iter()
            .flat_map(|&(index, _, _)| joint_bodies(&model.joints[index]))
            .collect();
        holder(1, bodies)
    });
    let general = model.general_constraints.iter().map(|constraint| {
        holder(
            1,
            bodies_of(model, constraint).into_iter().map(Some).collect(),
        )
    });
    joints
        .chain(motions)
        .chain(marker_motions)
        .chain(couplers)
        .chain(general)
        .collect()
}

/// The equation of `coupler`, `Σ s q = 0`, held at the level of the
/// velocities: its rate and its bias are the displacements', its value
/// zero. A joint's rotation is known only modulo a turn (and a coupler's
/// scales need not divide one another), so the displacement relation is
/// kept by integrating its rate, not put back by the projection: it drifts
/// by the integration error alone.
fn coupler_row<T: crate::number::Number>(
    model: &super::Model,
    coupler: &super::model::Coupler,
    bodies: &[BodyMotion<T>],
) -> Row<T> {
    let mut sum: Option<Row<T>> = None;
    for &(index, rotation, scale) in &coupler.joints {
        let displacement = joint_displacement(model, &model.joints[index], rotation, bodies);
        sum = Some(match sum {
            None => displacement.scaled(scale),
            Some(sum) => sum.plus_scaled(displacement, scale),
        });
    }
    let mut row = sum.expect("a coupler couples two joints or three");
    row.value = T::zero();
    row
}

/// The joint whose equation is `row` of the held equations
/// ([`active_rows`]' order), when a joint's is.
fn joint_of_row(model: &super::Model, row: usize) -> Option<&Joint> {
    let mut first = 0;
    for joint in &model.joints {
        let held = joint.held_equations();
        if row < first + held {
            return Some(joint);
        }
        first += held;
    }
    None
}

/// Below this [`curve_curve::conformity`] a CVCV's curves are taken to
/// bend alike at their point of contact, when its equations cannot be met.
/// Measured on a roller of 0.01 in a hole (both splines, of 36 and 72
/// points, whose curvatures are a circle's to about 1e-3): a hole 1 %
/// larger (5e-3) runs, 0.4 % larger (2e-3) and closer stop, the point of
/// contact jumping between the splines' wiggles.
const CONFORMING: f64 = 1e-2;

/// A CVCV whose curves bend alike at their point of contact at the state
/// `bodies` give, with why its equations cannot be met there.
fn conforming<'m, T: crate::number::Number>(
    model: &'m super::Model,
    joint: &'m Joint,
    bodies: &[BodyMotion<T>],
) -> Option<(&'m Joint, String)> {
    let pair = joint.pair.as_ref()?;
    let conformity = curve_curve::conformity(model, joint, pair, bodies)?;
    (conformity < CONFORMING).then(|| {
        (joint, format!(
            "CVCV/{}: CURVE/{} and CURVE/{} bend alike at their point of contact (their curvatures {conformity:.1e} apart, relative to their sum), so the point of contact is not unique: a CVCV holds curves that touch at one point (a pin that fills its hole, a flat on a flat); leave the curves a clearance, or hold the parts with a joint",
            joint.id, pair.i.curve.id, pair.j.curve.id
        ))
    })
}

/// Why the held equation `row` (any of them where `None`) cannot be met at
/// state `y` (each body's states from its entry of `offsets`), where that
/// is known: a CVCV whose curves bend alike at their point of contact
/// (with the CVCV's place in the file).
pub(crate) fn why_unmet(
    model: &super::Model,
    y: &[f64],
    offsets: &[usize],
    row: Option<usize>,
) -> Option<(crate::span::Span, String)> {
    let bodies = solve::motions(y, offsets);
    let found = match row {
        Some(row) => conforming(model, joint_of_row(model, row)?, &bodies),
        None => model
            .joints
            .iter()
            .find_map(|joint| conforming(model, joint, &bodies)),
    };
    found.map(|(joint, reason)| (joint.span, reason))
}

/// The statement (`JOINT/3`, `MOTION/1`) whose equation is `row` of the
/// held equations ([`active_rows`]' order; in the initial-conditions
/// analysis, the joints' initial displacements after them), and its place
/// in the file.
pub(crate) fn owner_of_row(
    model: &super::Model,
    row: usize,
) -> (String, Option<crate::span::Span>) {
    if let Some(joint) = joint_of_row(model, row) {
        return (
            format!("{}/{}", joint.kind.statement(), joint.id),
            Some(joint.span),
        );
    }
    let first: usize = model.joints.iter().map(Joint::held_equations).sum();
    let motions = model
        .motions
        .iter()
        .map(|motion| (format!("MOTION/{}", motion.id), motion.span))
        .chain(
            model
                .marker_motions
                .iter()
                .map(|motion| (format!("MOTION/{}", motion.id), motion.span)),
        )
        .chain(model.couplers.iter().map(|coupler| {
            (
                format!("{}/{}", coupler.statement, coupler.id),
                coupler.span,
            )
        }))
        .chain(
            model
                .general_constraints
                .iter()
                .map(|constraint| (format!("GCON/{}", constraint.id), constraint.span)),
        )
        .chain(positioned_initials(model).map(|initial| {
            let joint = &model.joints[initial.joint];
            let which = if initial.rotation {
                "rotation"
            } else {
                "translation"
            };
            (
                format!("the initial {which} of JOINT/{}", joint.id),
                initial.span,
            )
        }))
        .chain(model.exact.iter().flat_map(|part| {
            let name = &model.scene.bodies[part.body].name;
            std::iter::repeat_n(
                (format!("the EXACT coordinates of {name}"), part.span),
                exact_row_count(part),
            )
        }))
        .chain(model.joints.iter().flat_map(|joint| {
            let point = curve_start(joint).map(|_| "the DISP of PTCV");
            let pair = joint.pair.as_deref();
            let first = pair
                .and_then(|pair| pair.i.start)
                .map(|_| "the IDISP of CVCV");
            let second = pair
                .and_then(|pair| pair.j.start)
                .map(|_| "the JDISP of CVCV");
            [point, first, second]
                .into_iter()
                .flatten()
                .map(|what| (format!("{what}/{}", joint.id), joint.span))
        }));
    motions
        .enumerate()
        .find(|(index, _)| first + index == row)
        .map_or_else(
            || ("a joint".to_string(), None),
            |(_, (owner, span))| (owner, Some(span)),
        )
}

/// The equations of `joint` held in the run: its rows but the redundant
/// ones, in order.
fn kept_rows<T: crate::number::Number>(
    model: &super::Model,
    joint: &super::Joint,
    bodies: &[BodyMotion<T>],
    pieces: Pieces,
) -> impl Iterator<Item = Row<T>> {
    joint_rows(model, joint, bodies, pieces)
        .into_iter()
        .enumerate()
        .filter(|(index, _)| !joint.redundant.contains(index))
        .map(|(_, row)| row)
}

/// Finds the equations of `model`'s joints that repeat others at state
/// `y` (its initial state), marks them [`Joint::redundant`] and says so in
/// the model's notes.
pub(crate) fn leave_out_redundant(model: &mut super::Model, y: &[f64], offsets: &[usize]) {
    for (joint, equation) in find_redundant(model, y, offsets) {
        model.joints[joint].redundant.push(equation);
    }
    for joint in &model.joints {
        if joint.redundant.is_empty() {
            continue;
        }
        model.notes.push((
            format!(
                "{}/{}: {} of its {} equations repeat other joints' (the mechanism is over-constrained, as a planar loop is in space): they are left out, as Adams does, and the reactions they would share are not unique",
                joint.kind.statement(),
                joint.id,
                joint.redundant.len(),
                joint.kind.equations()
            ),
            joint.span,
        ));
    }
}

/// The output index an [`OutputError`](crate::eval::OutputError) names
/// when the joints' equations, not an expression, fail.
pub(crate) const JOINTS: usize = usize::MAX;

/// The error of a state where the joints' equations are singular (the
/// multipliers unbounded), or a motion's FUNCTION fails: the integrator
/// rejects the trial step.
pub(crate) fn joints_singular() -> crate::eval::OutputError {
    singular_because("their equations are dependent at this state: a singular configuration")
}

/// The error of joints whose multipliers cannot be solved in `model`: with
/// massless parts, the likelier cause is a freedom the joints leave one of
/// them, which no mass follows.
pub(crate) fn joints_singular_in(model: &super::Model) -> crate::eval::OutputError {
    let massless: Vec<&str> = model
        .masses
        .iter()
        .zip(&model.scene.bodies)
        .filter(|(mass, _)| mass.is_massless())
        .map(|(_, body)| body.name.as_str())
        .collect();
    if massless.is_empty() {
        return joints_singular();
    }
    singular_because(&format!(
        "their equations are singular: the joints leave a massless part ({}) a freedom no mass follows, or the configuration is singular; give the part MASS or hold it",
        massless.join(", ")
    ))
}

/// The error of joints whose multipliers cannot be solved at the state
/// `bodies` give: where an open curve's PTCV has lost its point (I's
/// origin past an end of the curve), or a CVCV its point of contact, or a
/// CVCV's curves bend alike there, that PTCV's or CVCV's, at its
/// statement; otherwise [`joints_singular_in`].
pub(crate) fn joints_failed_in<T: crate::number::Number>(
    model: &super::Model,
    bodies: &[BodyMotion<T>],
) -> crate::eval::OutputError {
    let lost = model.joints.iter().find_map(|joint| {
        let point = joint.curve.as_ref().and_then(|on| {
            on_curve::past_an_end(model, joint, on, bodies).then(|| {
                format!(
                    "PTCV/{}: its I marker has run past an end of CURVE/{}, an OPEN curve: a PTCV holds the point between the curve's ends (lengthen the curve, or close it)",
                    joint.id, on.curve.id
                )
            })
        });
        let pair = joint.pair.as_ref().and_then(|pair| {
            curve_curve::past_an_end(model, joint, pair, bodies).map(|curve| {
                format!(
                    "CVCV/{}: its point of contact has run past an end of CURVE/{curve}, an OPEN curve: a CVCV holds the contact between the curves' ends (lengthen the curve, or close it)",
                    joint.id
                )
            })
        });
        point.or(pair).map(|reason| (joint, reason))
    });
    let known = lost.or_else(|| {
        model
            .joints
            .iter()
            .find_map(|joint| conforming(model, joint, bodies))
    });
    match known {
        Some((joint, reason)) => singular_at(&reason, Some(joint.span)),
        None => joints_singular_in(model),
    }
}

/// The error of joints whose held equation `row` asks for an acceleration
/// beyond a double's range at a state (`ω² r` of a part spun at 1e200), at
/// the statement that holds it.
pub(crate) fn joints_overflow_in(model: &super::Model, row: usize) -> crate::eval::OutputError {
    let (owner, span) = owner_of_row(model, row);
    singular_at(
        &format!(
            "the accelerations that hold {owner} are beyond the range of a double at this state: a part's speed, or a mass, force or gravity, is too large (give smaller initial velocities or loads)"
        ),
        span,
    )
}

/// [`singular_because`], placed at the statement `span` (where known).
fn singular_at(reason: &str, span: Option<crate::span::Span>) -> crate::eval::OutputError {
    let mut error = singular_because(reason);
    if let (crate::eval::EvalError::Law { span: at, .. }, Some(span)) = (&mut error.error, span) {
        *at = span;
    }
    error
}

/// The joints' error for `reason`. Its span is empty, or the place in the
/// file of the statement that fails (the joints' errors are no
/// expression's).
fn singular_because(reason: &str) -> crate::eval::OutputError {
    crate::eval::OutputError {
        output: JOINTS,
        error: crate::eval::EvalError::Law {
            error: crate::laws::LawError::Domain {
                operation: "the joints",
                reason: reason.to_string(),
            },
            span: crate::span::Span::default(),
        },
    }
}
