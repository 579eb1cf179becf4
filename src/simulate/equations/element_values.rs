//! The values of force elements during a run, as the functions
//! `SFORCE(id, jflag, comp, rm)`, `VFORCE`, `VTORQ`, `GFORCE`, `BUSH`,
//! `BEAM`, `FIELD`, `NFORCE` and `CONTACT`
//! give them (Adams' convention): the force and the torque the element
//! applies on its I marker (jflag 0) or its J marker (jflag 1, the floating
//! marker of a VFORCE, VTORQUE or GFORCE, which sits at I), the torque
//! about that marker's origin, along the axes of marker `rm` (ground's
//! when 0); comp 1 `|F|`, 2–4 `Fx Fy Fz`, 5 `|T|`, 6–8 `Tx Ty Tz`. A
//! CONTACT's value sums its pairs of solids, on the part of its I (or J)
//! solid, the torque about that part's centre of mass. An NFORCE's second
//! argument is a marker, `NFORCE(id, at_marker, comp, rm)` (Adams
//! Solver's function): one of its I markers, its force there, or its J
//! marker, the reactions of all its forces, about J's origin.
//!
//! What the element applies is [`super::forces::actions`], the one place
//! its geometry is written: so a BUSHING's torque on J carries the moment
//! arm of the deformation, `−T − (I − J) × F`, and an action-only
//! element's J side is zero.

use nalgebra::Vector3;

use super::bodies::Kinematics;
use super::forces::{Action, actions, axes, body_of, place};
use crate::catalog::Function;
use crate::check::Reference;
use crate::compile::{MarkerCall, SolverCall};
use crate::scene::Target;
use crate::simulate::constraints::Reactions;
use crate::simulate::constraints::{component_and_rm, flags, pick};
use crate::simulate::model::{Force, Model};

/// The force elements' functions and the statements they read.
pub(crate) const ELEMENT_FUNCTIONS: [(Function, &str); 10] = [
    (Function::Sforce, "SFORCE"),
    (Function::Vforce, "VFORCE"),
    (Function::Vtorq, "VTORQUE"),
    (Function::Gforce, "GFORCE"),
    (Function::Bush, "BUSHING"),
    (Function::Beam, "BEAM"),
    (Function::Field, "FIELD"),
    (Function::Nforce, "NFORCE"),
    (Function::Contact, "CONTACT"),
    (Function::Spdp, "SPRINGDAMPER"),
];

/// A force element's component a model's expression asks for, found in
/// the model.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ElementComponent {
    /// The element's indices in [`Model::forces`]: one, or a CONTACT's
    /// pairs of solids (their forces summed).
    forces: Vec<usize>,
    /// On the J marker (jflag 1) rather than the I marker.
    on_j: bool,
    /// The point the torque is about.
    about: About,
    /// 1 `|F|`, 2–4 `Fx Fy Fz`, 5 `|T|`, 6–8 `Tx Ty Tz`.
    component: usize,
    /// The marker whose axes the components are along.
    rm: Target,
}

impl ElementComponent {
    /// The component `call` asks of `model`, or why it has none.
    pub(crate) fn of(model: &Model, call: &SolverCall) -> Result<ElementComponent, String> {
        let written = call.input_name();
        let kind = ELEMENT_FUNCTIONS
            .iter()
            .find(|(function, _)| *function == call.function)
            .map_or("", |(_, kind)| *kind);
        let forces: Vec<usize> = model
            .force_statements
            .iter()
            .enumerate()
            .filter(|(_, (statement, id))| *statement == kind && *id == call.id)
            .map(|(index, _)| index)
            .collect();
        let Some(&force) = forces.first() else {
            return Err(format!(
                "{written}: the model has no {kind}/{} that is simulated",
                call.id
            ));
        };
        if call.function == Function::Nforce {
            return multipoint(model, call, forces);
        }
        let (on_j, component, rm) = flags(model, call, "force")?;
        let (i, j) = markers(model, force);
        // A floating marker sits at I; a contact's force is about the
        // centre of mass of its I (or J) solid's part.
        let marker = if on_j { j.unwrap_or(i) } else { i };
        let about = match &model.forces[force] {
            Force::Contact(_) => About::Centre(body_of(model, &marker)),
            _ => About::Marker(marker),
        };
        Ok(ElementComponent {
            forces,
            on_j,
            about,
            component,
            rm,
        })
    }

    /// The value of this component with the bodies at `kinematics` and the
    /// model's expressions' values `value`.
    pub(super) fn value(
        &self,
        model: &Model,
        kinematics: &[Kinematics<f64>],
        value: &impl Fn(Option<usize>) -> f64,
    ) -> f64 {
        let origin = match self.about {
            About::Marker(marker) => place(model, &marker, kinematics).origin,
            About::Centre(body) => body.map_or_else(Vector3::zeros, |body| kinematics[body].centre),
        };
        let (mut force, mut torque) = (Vector3::zeros(), Vector3::zeros());
        for &index in &self.forces {
            let [on_i, on_j] = actions(model, &model.forces[index], kinematics, value, None);
            let action = if self.on_j { on_j } else { on_i };
            let (push, turn) = about(action, &origin);
            force += push;
            torque += turn;
        }
        let along = axes(model, &self.rm, kinematics).transpose();
        let (force, torque) = (along * force, along * torque);
        pick(&force, &torque, self.component)
    }
}

/// The I marker of force element `index` of `model` and its J marker: the
/// J of an SFORCE, the J of a BUSHING, BEAM, FIELD or NFORCE (the marker of its axes); `None` for
/// the floating marker of a VFORCE, VTORQUE or GFORCE (and any vector
/// force of a scene), which the model does not keep.
fn markers(model: &Model, index: usize) -> (Target, Option<Target>) {
    match &model.forces[index] {
        Force::Translational { i, j, .. } | Force::Rotational { i, j, .. } => (*i, Some(*j)),
        Force::Vector { i, axes, .. } => {
            let bushing = model
                .force_statements
                .get(index)
                .is_some_and(|(kind, _)| ["BUSHING", "BEAM", "FIELD", "NFORCE"].contains(kind));
            (*i, bushing.then_some(*axes))
        }
        Force::Contact(contact) => (contact.i.marker, Some(contact.j.marker)),
    }
}

/// The component `NFORCE(id, at_marker, comp, rm)` asks of `model`, whose
/// forces `forces` are the NFORCE's (one on each I marker, in I's order):
/// at one of its I markers, that marker's force; at its J marker, the
/// reactions of them all, the torque about J's origin.
fn multipoint(
    model: &Model,
    call: &SolverCall,
    forces: Vec<usize>,
) -> Result<ElementComponent, String> {
    let (component, rm) = component_and_rm(model, call)?;
    let at = u64::try_from(call.jflag)
        .ok()
        .filter(|id| *id > 0)
        .and_then(|id| model.scene.find_marker(&Reference::Id(id)).ok());
    let (i, j) = markers(model, forces[0]);
    let j = j.unwrap_or(i);
    let (forces, on_j, marker) = match at {
        Some(at) if at == j => (forces, true, j),
        Some(at) => match forces.iter().find(|&&force| markers(model, force).0 == at) {
            Some(&force) => (vec![force], false, at),
            None => return Err(not_connected(call)),
        },
        None => return Err(not_connected(call)),
    };
    Ok(ElementComponent {
        forces,
        on_j,
        about: About::Marker(marker),
        component,
        rm,
    })
}

/// The error of an NFORCE call whose marker is not one the NFORCE joins.
fn not_connected(call: &SolverCall) -> String {
    format!(
        "{}: at_marker must be one of the markers NFORCE/{} joins (its I markers or its J), not {}",
        call.input_name(),
        call.id,
        call.jflag
    )
}

/// The force of `action` and its torque about `origin`, in ground (zero
/// for no action).
fn about(action: Option<Action<f64>>, origin: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let Some(action) = action else {
        return (Vector3::zeros(), Vector3::zeros());
    };
    let force = action.force.unwrap_or_else(Vector3::zeros);
    let torque =
        action.torque.unwrap_or_else(Vector3::zeros) + (action.point - origin).cross(&force);
    (force, torque)
}

/// The point an element's torque is about.
#[derive(Clone, Copy, Debug, PartialEq)]
enum About {
    /// A marker's origin.
    Marker(Target),
    /// The centre of mass of a part (`None`: ground's origin).
    Centre(Option<usize>),
}

/// The net force between two markers, `FX FY FZ FM TX TY TZ TM (i, j,
/// k)`, found in the model: the sum at marker I of what the force elements
/// and the joints, primitives, motions and couplers (through the joints they
/// couple) between I and J apply on it (all that act at I when J is 0), the
/// torque about I's origin, along K's axes.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct NetForce {
    function: Function,
    i: Target,
    j: Target,
    k: Target,
}

impl NetForce {
    /// The net force `call` asks of `model`, or why it has none.
    pub(crate) fn of(model: &Model, call: &MarkerCall) -> Result<NetForce, String> {
        let markers = call
            .markers_in(&model.scene)
            .map_err(|why| format!("{}: {why}", call.input_name()))?;
        let marker = |position: usize| markers.get(position).copied().unwrap_or(Target::Ground);
        let (i, j) = (marker(0), marker(1));
        Ok(NetForce {
            function: call.function,
            i,
            j,
            k: marker(2),
        })
    }

    /// Its value with the bodies at `kinematics`, the joints' `reactions`
    /// and the model's expressions' values `value`.
    pub(super) fn value(
        &self,
        model: &Model,
        kinematics: &[Kinematics<f64>],
        reactions: &Reactions,
        value: &impl Fn(Option<usize>) -> f64,
    ) -> f64 {
        let (mut force, mut torque) = reactions.between(model, &self.i, &self.j);
        let origin = place(model, &self.i, kinematics).origin;
        let any = self.j == Target::Ground;
        for index in 0..model.forces.len() {
            let (i, j) = markers(model, index);
            let [on_i, on_j] = actions(model, &model.forces[index], kinematics, value, None);
            let mut add = |action| {
                let (push, turn) = about(action, &origin);
                force += push;
                torque += turn;
            };
            if i == self.i && (any || j == Some(self.j)) {
                add(on_i);
            }
            if j == Some(self.i) && (any || i == self.j) {
                add(on_j);
            }
        }
        let along = axes(model, &self.k, kinematics).transpose();
        let (force, torque) = (along * force, along * torque);
        match self.function {
            Function::Fx => force.x,
            Function::Fy => force.y,
            Function::Fz => force.z,
            Function::Fm => force.norm(),
            Function::Tx => torque.x,
            Function::Ty => torque.y,
            Function::Tz => torque.z,
            _ => torque.norm(),
        }
    }
}
