//! The values of force elements during a run, as the functions
//! `SFORCE(id, jflag, comp, rm)`, `VFORCE`, `VTORQ`, `GFORCE` and `BUSH`
//! give them (Adams' convention): the force and the torque the element
//! applies on its I marker (jflag 0) or its J marker (jflag 1, the floating
//! marker of a VFORCE, VTORQUE or GFORCE, which sits at I), the torque
//! about that marker's origin, along the axes of marker `rm` (ground's
//! when 0); comp 1 `|F|`, 2–4 `Fx Fy Fz`, 5 `|T|`, 6–8 `Tx Ty Tz`.
//!
//! What the element applies is [`super::forces::actions`], the one place
//! its geometry is written: so a BUSHING's torque on J carries the moment
//! arm of the deformation, `−T − (I − J) × F`, and an action-only
//! element's J side is zero.

use nalgebra::Vector3;

use super::bodies::Kinematics;
use super::forces::{actions, axes, place};
use crate::catalog::Function;
use crate::compile::SolverCall;
use crate::scene::Target;
use crate::simulate::constraints::{flags, pick};
use crate::simulate::model::{Force, Model};

/// The force elements' functions and the statements they read.
pub(crate) const ELEMENT_FUNCTIONS: [(Function, &str); 5] = [
    (Function::Sforce, "SFORCE"),
    (Function::Vforce, "VFORCE"),
    (Function::Vtorq, "VTORQUE"),
    (Function::Gforce, "GFORCE"),
    (Function::Bush, "BUSHING"),
];

/// A force element's component a model's expression asks for, found in
/// the model.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ElementComponent {
    /// The element's index in [`Model::forces`].
    force: usize,
    /// On the J marker (jflag 1) rather than the I marker.
    on_j: bool,
    /// The marker about whose origin the torque is.
    marker: Target,
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
        let Some(force) = model
            .force_statements
            .iter()
            .position(|&(statement, id)| statement == kind && id == call.id)
        else {
            return Err(format!(
                "{written}: the model has no {kind}/{} that is simulated",
                call.id
            ));
        };
        let (on_j, component, rm) = flags(model, call, "force")?;
        let marker = match &model.forces[force] {
            Force::Translational { i, j, .. } | Force::Rotational { i, j, .. } => {
                if on_j {
                    *j
                } else {
                    *i
                }
            }
            // A BUSHING's J is the marker of its axes; a floating marker
            // sits at I.
            Force::Vector { i, axes, .. } => {
                if on_j && kind == "BUSHING" {
                    *axes
                } else {
                    *i
                }
            }
        };
        Ok(ElementComponent {
            force,
            on_j,
            marker,
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
        let [on_i, on_j] = actions(model, &model.forces[self.force], kinematics, value);
        let action = if self.on_j { on_j } else { on_i };
        let (mut force, mut torque) = (Vector3::zeros(), Vector3::zeros());
        if let Some(action) = action {
            force = action.force.unwrap_or_else(Vector3::zeros);
            let origin = place(model, &self.marker, kinematics).origin;
            torque = action.torque.unwrap_or_else(Vector3::zeros)
                + (action.point - origin).cross(&force);
        }
        let along = axes(model, &self.rm, kinematics).transpose();
        let (force, torque) = (along * force, along * torque);
        pick(&force, &torque, self.component)
    }
}
