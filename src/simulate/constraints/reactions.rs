//! The reactions of the joints, joint primitives and motions, as the
//! functions `JOINT(id, jflag, comp, rm)`, `JPRIM(...)` and `MOTION(...)`
//! give them: the force and the torque a holder applies on its I marker's
//! body (jflag 0) or its J marker's (jflag 1), the torque about that
//! marker's origin, both resolved in the axes of marker `rm` (ground's
//! when 0).
//!
//! A held equation with multiplier `λ` and row `c` of `G` on a body puts
//! the load `−c λ` on it (a force at its centre of mass and a torque, in
//! ground; [`super::constraint_loads`]); a holder's reaction on a body sums
//! the loads of its equations. A marker on ground takes the opposite of
//! what the other marker's body takes (Newton's third law), moved to the
//! marker's origin. So for a pendulum hanging from ground by a revolute
//! joint whose I marker is on ground, `JOINT(id, 0, ...)` is the pull of
//! the pendulum on the ground: Adams' convention (the research note's
//! "Sign convention").

use nalgebra::{Matrix3, Vector3};

use super::rows::BodyMotion;
use super::{Imposed, active_rows};
use crate::catalog::Function;
use crate::compile::SolverCall;
use crate::scene::Target;
use crate::simulate::Model;

/// What holds: a joint or primitive, or a motion, by its index in the
/// model.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Holder {
    Joint(usize),
    Motion(usize),
    MarkerMotion(usize),
    /// A coupler through one of the joints it couples: the coupler's
    /// index, and the joint's place among its joints.
    Coupler(usize, usize),
}

/// A reaction component a model's expression asks for, found in the model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Component {
    holder: Holder,
    /// On the J marker (jflag 1) rather than the I marker.
    on_j: bool,
    /// 1 `|F|`, 2–4 `Fx Fy Fz`, 5 `|T|`, 6–8 `Tx Ty Tz`.
    component: usize,
    /// The marker whose axes the components are along.
    rm: Target,
}

impl Component {
    /// The component `call` asks of `model`, or why it has none.
    pub(crate) fn of(model: &Model, call: &SolverCall) -> Result<Component, String> {
        let written = call.input_name();
        let holder = match call.function {
            Function::Motion => model
                .motions
                .iter()
                .position(|motion| motion.id == call.id)
                .map(Holder::Motion)
                .or_else(|| {
                    model
                        .marker_motions
                        .iter()
                        .position(|motion| motion.id == call.id)
                        .map(Holder::MarkerMotion)
                }),
            function => model
                .joints
                .iter()
                .position(|joint| joint.id == call.id && joint.kind.statement() == function.name())
                .map(Holder::Joint),
        };
        let Some(holder) = holder else {
            return Err(format!(
                "{written}: the model has no {}/{} that is simulated",
                call.function.name(),
                call.id
            ));
        };
        let (on_j, component, rm) = flags(model, call, "reaction")?;
        Ok(Component {
            holder,
            on_j,
            component,
            rm,
        })
    }
}

/// The side (`true` for jflag 1, the J marker), component and `rm` marker
/// of `call` in `model`, or why they cannot be had; `what` is what is on
/// the marker ("reaction", "force").
pub(crate) fn flags(
    model: &Model,
    call: &SolverCall,
    what: &str,
) -> Result<(bool, usize, Target), String> {
    let written = call.input_name();
    let on_j = match call.jflag {
        0 => false,
        1 => true,
        other => {
            return Err(format!(
                "{written}: jflag must be 0 (the {what} on the I marker) or 1 (on the J marker), not {other}"
            ));
        }
    };
    let (component, rm) = component_and_rm(model, call)?;
    Ok((on_j, component, rm))
}

/// The component (1 to 8) and `rm` marker of `call` in `model`, or why
/// they cannot be had.
pub(crate) fn component_and_rm(
    model: &Model,
    call: &SolverCall,
) -> Result<(usize, Target), String> {
    let written = call.input_name();
    let component = match usize::try_from(call.component) {
        Ok(component @ 1..=8) => component,
        _ => {
            return Err(format!(
                "{written}: comp must be 1 to 8 (|F|, Fx, Fy, Fz, |T|, Tx, Ty, Tz), not {}",
                call.component
            ));
        }
    };
    let Some(rm) = call.rm_in(&model.scene) else {
        return Err(format!(
            "{written}: the model has no marker {} (rm)",
            call.rm
        ));
    };
    Ok((component, rm))
}

/// Component `component` (1 `|F|`, 2–4 `Fx Fy Fz`, 5 `|T|`, 6–8 `Tx Ty
/// Tz`) of `force` and `torque`.
pub(crate) fn pick(force: &Vector3<f64>, torque: &Vector3<f64>, component: usize) -> f64 {
    match component {
        1 => force.norm(),
        5 => torque.norm(),
        component @ 2..=4 => force[component - 2],
        component => torque[component - 6],
    }
}

/// A holder's loads on the bodies it holds: each body's index and `[force
/// | torque about the centre of mass]`, in ground.
type BodyLoads = Vec<(usize, [f64; 6])>;

/// The reactions at one state: each holder's loads on the bodies.
pub(crate) struct Reactions {
    /// For each joint, its load on each body it holds: `[force | torque
    /// about the centre of mass]`, in ground.
    joints: Vec<BodyLoads>,
    /// The same for each motion on a joint.
    motions: Vec<BodyLoads>,
    /// The same for each motion between markers.
    marker_motions: Vec<BodyLoads>,
    /// For each coupler, for each joint it couples, the loads its
    /// equation puts on that joint's bodies through that joint's
    /// displacement (the equation is the sum of the joints' terms).
    couplers: Vec<Vec<BodyLoads>>,
    /// For each general constraint, its load on each body it holds.
    general: Vec<BodyLoads>,
    /// Each body's centre of mass and rotation to ground.
    bodies: Vec<(Vector3<f64>, Matrix3<f64>)>,
    /// For each joint that is a CVCV, its point of contact in ground (where
    /// its floating markers sit), when one is found.
    contacts: Vec<Option<Vector3<f64>>>,
}

/// The loads `−c λ` of the next `count` rows of `rows` with the next
/// multipliers of `multipliers`.
fn take_loads(
    rows: &mut impl Iterator<Item = super::rows::Row<f64>>,
    multipliers: &mut impl Iterator<Item = f64>,
    count: usize,
) -> BodyLoads {
    let mut loads = Vec::new();
    add_loads(rows.take(count), multipliers, &mut loads);
    loads
}

/// Adds the loads `−c λ` of the rows `rows` with multipliers from
/// `multipliers` (taken in order) to `loads`.
fn add_loads(
    rows: impl Iterator<Item = super::rows::Row<f64>>,
    multipliers: &mut impl Iterator<Item = f64>,
    loads: &mut BodyLoads,
) {
    for row in rows {
        let Some(lambda) = multipliers.next() else {
            return;
        };
        for (body, c) in &row.coefficients {
            let mut load = [0.0; 6];
            for (load, c) in load.iter_mut().zip(c) {
                *load = -c * lambda;
            }
            add_load(loads, *body, load);
        }
    }
}

/// Adds `load` on `body` to `loads`.
fn add_load(loads: &mut BodyLoads, body: usize, load: [f64; 6]) {
    let index = match loads.iter().position(|(held, _)| *held == body) {
        Some(index) => index,
        None => {
            loads.push((body, [0.0; 6]));
            loads.len() - 1
        }
    };
    for (sum, load) in loads[index].1.iter_mut().zip(load) {
        *sum += load;
    }
}

impl Reactions {
    /// The reactions with the held equations' `multipliers` (in the order
    /// of the run's rows: the joints' kept equations, the motions', the
    /// couplers', the general constraints'), the bodies moving as `bodies`
    /// say and the motions and general constraints as `imposed` gives.
    pub(crate) fn new(
        model: &Model,
        bodies: &[BodyMotion<f64>],
        imposed: &Imposed<'_>,
        multipliers: &[f64],
    ) -> Reactions {
        // The held equations in the run's order, each holder taking as many
        // as it holds, with their multipliers.
        let mut rows = active_rows(model, bodies, imposed).into_iter();
        let mut multipliers = multipliers.iter().copied();
        let mut loads_of = |count: usize| take_loads(&mut rows, &mut multipliers, count);
        let joints = model
            .joints
            .iter()
            .map(|joint| loads_of(joint.held_equations()))
            .collect();
        let motions = model.motions.iter().map(|_| loads_of(1)).collect();
        let marker_motions = model.marker_motions.iter().map(|_| loads_of(1)).collect();
        // A coupler's equation `Σ s q = 0` puts on each joint's bodies the
        // load of its own term `s q` (the equation's whole load is their
        // sum).
        let mut coupler_multipliers = Vec::new();
        let couplers = model
            .couplers
            .iter()
            .map(|coupler| {
                let whole = rows.next();
                let lambda = multipliers.next().filter(|_| whole.is_some());
                coupler_multipliers.push(lambda);
                coupler
                    .joints
                    .iter()
                    .map(|&(joint, rotation, scale)| {
                        let mut loads = Vec::new();
                        if let Some(lambda) = lambda {
                            let term = super::joint_displacement(
                                model,
                                &model.joints[joint],
                                rotation,
                                bodies,
                            )
                            .scaled(scale);
                            add_loads(
                                std::iter::once(term),
                                &mut std::iter::once(lambda),
                                &mut loads,
                            );
                        }
                        loads
                    })
                    .collect()
            })
            .collect();
        let general = model
            .general_constraints
            .iter()
            .map(|_| take_loads(&mut rows, &mut multipliers, 1))
            .collect();
        let mut reactions = Reactions {
            joints,
            motions,
            marker_motions,
            couplers,
            general,
            bodies: bodies
                .iter()
                .map(|body| (body.centre, body.rotation))
                .collect(),
            contacts: model
                .joints
                .iter()
                .map(|joint| {
                    let pair = joint.pair.as_ref()?;
                    super::curve_curve::contact_point(model, joint, pair, bodies)
                })
                .collect(),
        };
        for (index, lambda) in coupler_multipliers.into_iter().enumerate() {
            if let Some(lambda) = lambda {
                reactions.gear_teeth(model, index, lambda);
            }
        }
        reactions
    }

    /// A GEAR's loads as Adams applies them: the teeth push each other at
    /// the contact (CV's origin) along CV's z, so each gear's joint holds
    /// the tooth force, not a torque. The coupler's equation `Σ s q̇ = 0`
    /// is the contact's velocities along CV's z, first gear's less the
    /// second's, up to the joints' rows: with its multiplier `λ` the teeth
    /// put `−λ z` at the contact on the first gear and `λ z` on the second.
    /// Each gear's whole load (its joint's and the coupler's) is the same
    /// either way, so its joint's becomes that less the tooth's, and the
    /// carrier's side the opposite; the coupler's own terms are then
    /// nothing.
    fn gear_teeth(&mut self, model: &Model, index: usize, lambda: f64) {
        let coupler = &model.couplers[index];
        let Some(cv) = &coupler.contact else {
            return;
        };
        let (contact, axes) = self.place(model, cv);
        let along = axes.column(2).into_owned();
        let carrier = body_of(model, cv);
        let mut geared: Vec<usize> = coupler.joints.iter().map(|&(joint, _, _)| joint).collect();
        geared.dedup();
        for (k, &joint_index) in geared.iter().enumerate() {
            let joint = &model.joints[joint_index];
            let (i, j) = (body_of(model, &joint.i), body_of(model, &joint.j));
            let gear = if i == carrier { j } else { i };
            // The coupler's loads through this joint, on each body.
            let mut through = BodyLoads::new();
            for (term, &(coupled, _, _)) in coupler.joints.iter().enumerate() {
                if coupled == joint_index {
                    for &(body, load) in &self.couplers[index][term] {
                        add_load(&mut through, body, load);
                    }
                    self.couplers[index][term].clear();
                }
            }
            let tooth = along * if k == 0 { -lambda } else { lambda };
            let tooth_on = |body: usize| {
                let arm = contact - self.bodies[body].0;
                let torque = arm.cross(&tooth);
                [tooth.x, tooth.y, tooth.z, torque.x, torque.y, torque.z]
            };
            let loads = &mut self.joints[joint_index];
            for (body, load) in through {
                // The gear loses the tooth force the joint no longer carries;
                // the carrier takes it back.
                let sign = if Some(body) == gear { -1.0 } else { 1.0 };
                let mut moved = load;
                for (moved, tooth) in moved.iter_mut().zip(tooth_on(body)) {
                    *moved += sign * tooth;
                }
                add_load(loads, body, moved);
            }
        }
    }

    /// The origin and axes of marker `target` in ground.
    fn place(&self, model: &Model, target: &Target) -> (Vector3<f64>, Matrix3<f64>) {
        let Target::Marker(index) = target else {
            return (Vector3::zeros(), Matrix3::identity());
        };
        let marker = &model.scene.markers[*index];
        let axes = marker.orientation.to_rotation_matrix().into_inner();
        match marker.body {
            None => (marker.position, axes),
            Some(body) => {
                let (centre, rotation) = &self.bodies[body];
                (
                    centre + rotation * (marker.position - model.masses[body].centre),
                    rotation * axes,
                )
            }
        }
    }

    /// The value of `component` of `model`.
    pub(crate) fn value(&self, model: &Model, component: &Component) -> f64 {
        let (force, torque) = self.load(model, component.holder, component.on_j);
        let axes = self.place(model, &component.rm).1;
        pick(
            &(axes.transpose() * force),
            &(axes.transpose() * torque),
            component.component,
        )
    }

    /// The force and the torque about the marker's origin, in ground, that
    /// `holder` applies on its I marker (J when `on_j`).
    fn load(&self, model: &Model, holder: Holder, on_j: bool) -> (Vector3<f64>, Vector3<f64>) {
        let (loads, i, j) = match holder {
            Holder::Joint(index) => {
                let joint = &model.joints[index];
                (&self.joints[index], &joint.i, &joint.j)
            }
            Holder::Motion(index) => {
                let joint = &model.joints[model.motions[index].joint];
                (&self.motions[index], &joint.i, &joint.j)
            }
            Holder::MarkerMotion(index) => {
                let motion = &model.marker_motions[index];
                (&self.marker_motions[index], &motion.i, &motion.j)
            }
            Holder::Coupler(index, term) => {
                let joint = &model.joints[model.couplers[index].joints[term].0];
                (&self.couplers[index][term], &joint.i, &joint.j)
            }
        };
        let (marker, other) = if on_j { (j, i) } else { (i, j) };
        // On ground, the opposite of what the other marker's body takes.
        let (sign, body) = match body_of(model, marker) {
            Some(body) => (1.0, Some(body)),
            None => (-1.0, body_of(model, other)),
        };
        // A PTCV's J side is its floating marker, at the point of contact:
        // I's origin; both sides of a CVCV are, at the point of contact.
        let origin = match holder {
            Holder::Joint(index) if model.joints[index].curve.is_some() => self.place(model, i).0,
            Holder::Joint(index) if model.joints[index].pair.is_some() => {
                self.contacts[index].unwrap_or_else(|| Vector3::repeat(f64::NAN))
            }
            // A joint that holds its origins together pushes each body at
            // its own marker's origin, as Adams applies it: on ground, the
            // other body's torque is taken about the other marker's origin,
            // so the markers' drift apart (1e-6 of a length) adds no moment
            // (a spherical joint's torque stays 0, a revolute's about its
            // axis too).
            Holder::Joint(index) if sign < 0.0 && holds_origins_together(&model.joints[index]) => {
                self.place(model, other).0
            }
            _ => self.place(model, marker).0,
        };
        let mut force = Vector3::zeros();
        let mut torque = Vector3::zeros();
        if let Some(body) = body {
            for (_, load) in loads.iter().filter(|(held, _)| *held == body) {
                force += Vector3::new(load[0], load[1], load[2]);
                torque += Vector3::new(load[3], load[4], load[5]);
            }
            torque += (self.bodies[body].0 - origin).cross(&force);
        }
        (force * sign, torque * sign)
    }

    /// The force and the torque about `marker`'s origin, in ground, that
    /// general constraint `index` applies on `marker`'s body; on ground,
    /// the opposite of what it applies on every part it holds.
    fn general_load(
        &self,
        model: &Model,
        index: usize,
        marker: &Target,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let origin = self.place(model, marker).0;
        let on = body_of(model, marker);
        let mut force = Vector3::zeros();
        let mut torque = Vector3::zeros();
        for (body, load) in &self.general[index] {
            if on.is_some_and(|on| on != *body) {
                continue;
            }
            let f = Vector3::new(load[0], load[1], load[2]);
            force += f;
            torque +=
                Vector3::new(load[3], load[4], load[5]) + (self.bodies[*body].0 - origin).cross(&f);
        }
        if on.is_none() {
            (-force, -torque)
        } else {
            (force, torque)
        }
    }

    /// The force and the torque about `i`'s origin, in ground, that the
    /// joints, primitives, motions and couplers (through the joints they
    /// couple) between markers `i` and `j` (every other marker when `j` is
    /// ground, id 0) apply on `i`.
    pub(crate) fn between(
        &self,
        model: &Model,
        i: &Target,
        j: &Target,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let holders = model
            .joints
            .iter()
            .enumerate()
            .map(|(index, joint)| (Holder::Joint(index), &joint.i, &joint.j))
            .chain(model.motions.iter().enumerate().map(|(index, motion)| {
                let joint = &model.joints[motion.joint];
                (Holder::Motion(index), &joint.i, &joint.j)
            }))
            .chain(
                model
                    .marker_motions
                    .iter()
                    .enumerate()
                    .map(|(index, motion)| (Holder::MarkerMotion(index), &motion.i, &motion.j)),
            )
            .chain(
                model
                    .couplers
                    .iter()
                    .enumerate()
                    .flat_map(|(index, coupler)| {
                        coupler
                            .joints
                            .iter()
                            .enumerate()
                            .map(move |(term, &(joint, _, _))| {
                                let joint = &model.joints[joint];
                                (Holder::Coupler(index, term), &joint.i, &joint.j)
                            })
                    }),
            );
        let mut sum = (Vector3::zeros(), Vector3::zeros());
        for (holder, holder_i, holder_j) in holders {
            for (on_j, marker, other) in [(false, holder_i, holder_j), (true, holder_j, holder_i)] {
                if marker == i && (*j == Target::Ground || other == j) {
                    let (force, torque) = self.load(model, holder, on_j);
                    sum.0 += force;
                    sum.1 += torque;
                }
            }
        }
        // A general constraint acts between its I marker and the parts its
        // FUNCTION reads.
        for (index, constraint) in model.general_constraints.iter().enumerate() {
            // Ground is a party to every general constraint.
            let holds = |target: &Target| {
                body_of(model, target)
                    .is_none_or(|body| self.general[index].iter().any(|(held, _)| *held == body))
            };
            let applies = if *i == constraint.i {
                *j == Target::Ground || holds(j)
            } else {
                *j == constraint.i && body_of(model, i).is_some() && holds(i)
            };
            if applies {
                let (force, torque) = self.general_load(model, index, i);
                sum.0 += force;
                sum.1 += torque;
            }
        }
        sum
    }
}

/// Whether `joint`'s equations hold its I and J origins together (in
/// ground's components, so each body's share acts at its own origin).
fn holds_origins_together(joint: &crate::simulate::model::Joint) -> bool {
    use crate::simulate::model::JointKind;
    joint.curve.is_none()
        && joint.pair.is_none()
        && matches!(
            joint.kind,
            JointKind::Fixed
                | JointKind::Revolute
                | JointKind::Spherical
                | JointKind::Universal
                | JointKind::Hooke
                | JointKind::Convel
                | JointKind::AtPoint
        )
}

/// The body `target` is on (`None`: ground).
fn body_of(model: &Model, target: &Target) -> Option<usize> {
    model.scene.body_of(target)
}
