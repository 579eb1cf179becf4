//! Force elements: where each acts (its markers placed in ground) and what
//! it applies to the bodies.

use nalgebra::{Matrix3, Vector3};

use super::bodies::{Kinematics, Loads};
use crate::kinematics::times_constant;
use crate::laws::contact::ContactBranch;
use crate::number::Number;
use crate::scene::Target;
use crate::simulate::model::{Force, Model};

/// A marker's origin in ground and the body it is on.
pub(super) struct Placed<T: Number> {
    pub(super) origin: Vector3<T>,
    pub(super) body: Option<usize>,
}

/// A marker's origin in ground and its body.
pub(super) fn place<T: Number>(
    model: &Model,
    target: &Target,
    kinematics: &[Kinematics<T>],
) -> Placed<T> {
    let Target::Marker(index) = target else {
        return Placed {
            origin: Vector3::zeros(),
            body: None,
        };
    };
    let marker = &model.scene.markers[*index];
    match marker.body {
        None => Placed {
            origin: marker.position.map(T::from),
            body: None,
        },
        Some(body) => {
            let state = &kinematics[body];
            let offset = marker.position - model.masses[body].centre;
            Placed {
                origin: &state.centre + times_constant(&state.rotation, &offset),
                body: Some(body),
            }
        }
    }
}

/// The body a marker is on (`None`: ground).
pub(super) fn body_of(model: &Model, target: &Target) -> Option<usize> {
    model.scene.body_of(target)
}

/// A marker's axes in ground (worked out only for the elements that read
/// them: most forces act along the line between their markers).
pub(super) fn axes<T: Number>(
    model: &Model,
    target: &Target,
    kinematics: &[Kinematics<T>],
) -> Matrix3<T> {
    let Target::Marker(index) = target else {
        return Matrix3::identity();
    };
    let marker = &model.scene.markers[*index];
    let axes_in_body = marker.orientation.to_rotation_matrix().into_inner();
    match marker.body {
        None => axes_in_body.map(T::from),
        Some(body) => times_constant(&kinematics[body].rotation, &axes_in_body),
    }
}

/// What a force element applies on one side: `force` at `point` and a
/// free `torque`, in ground, on `body` (`None`: ground).
pub(super) struct Action<T: Number> {
    pub(super) body: Option<usize>,
    pub(super) point: Vector3<T>,
    pub(super) force: Option<Vector3<T>>,
    pub(super) torque: Option<Vector3<T>>,
}

/// Adds what `force` applies to the bodies (a contact's normal force on
/// the branch `branch` of its law, the natural one when `None`). A
/// translational force between I and J markers on two bodies that pushes
/// or pulls while they coincide, where its line of action is not defined,
/// applies nothing and gives its magnitude's expression as the error (a
/// force of zero there is none, and one within a body does nothing).
pub(super) fn apply<T: Number>(
    model: &Model,
    force: &Force,
    kinematics: &[Kinematics<T>],
    (value, branch): (&impl Fn(Option<usize>) -> T, Option<ContactBranch>),
    loads: &mut Loads<T>,
) -> Result<(), usize> {
    let sides = actions(model, force, kinematics, value, branch);
    if let (
        [None, None],
        Force::Translational {
            i,
            j,
            magnitude,
            action_only: false,
        },
    ) = (&sides, force)
        && body_of(model, i) != body_of(model, j)
        && value(Some(*magnitude)).value() != 0.0
    {
        return Err(*magnitude);
    }
    for action in sides.into_iter().flatten() {
        if let Some(push) = &action.force {
            loads.push(action.body, &action.point, push, kinematics);
        }
        if let Some(turn) = &action.torque {
            loads.turn(action.body, turn);
        }
    }
    Ok(())
}

/// What `force` applies on its I marker's side and on its other side (J's
/// body, or the floating marker's; ground's too, which takes nothing),
/// `None` where it applies nothing (an action-only element's other side, a
/// translational force between coincident markers).
pub(super) fn actions<T: Number>(
    model: &Model,
    force: &Force,
    kinematics: &[Kinematics<T>],
    value: &impl Fn(Option<usize>) -> T,
    branch: Option<ContactBranch>,
) -> [Option<Action<T>>; 2] {
    match force {
        Force::Translational {
            i,
            j,
            magnitude,
            action_only,
        } => {
            let magnitude = value(Some(*magnitude));
            if *action_only {
                let along = axes(model, j, kinematics).column(2).into_owned() * magnitude;
                let i = place(model, i, kinematics);
                return [Some(Action::at(i, along)), None];
            }
            let (i, j) = (place(model, i, kinematics), place(model, j, kinematics));
            let line = &i.origin - &j.origin;
            let length = line.dot(&line).sqrt();
            if length.value() == 0.0 {
                // Coincident markers: no line of action, no force.
                return [None, None];
            }
            let push = line / length * magnitude;
            let pull = -push.clone();
            [Some(Action::at(i, push)), Some(Action::at(j, pull))]
        }
        Force::Rotational {
            i,
            j,
            magnitude,
            action_only,
        } => {
            let torque =
                axes(model, j, kinematics).column(2).into_owned() * value(Some(*magnitude));
            let turn = |target: &Target, torque: Vector3<T>| Action {
                body: body_of(model, target),
                point: place(model, target, kinematics).origin,
                force: None,
                torque: Some(torque),
            };
            let reaction = (!*action_only).then(|| turn(j, -torque.clone()));
            [Some(turn(i, torque)), reaction]
        }
        Force::Vector {
            i,
            reaction,
            axes,
            force,
            torque,
        } => {
            let i = place(model, i, kinematics);
            let axes = self::axes(model, axes, kinematics);
            let along = |components: &[Option<usize>; 3]| {
                let local = Vector3::new(
                    value(components[0]),
                    value(components[1]),
                    value(components[2]),
                );
                &axes * local
            };
            let (push, turn) = (along(force), along(torque));
            let other = Action {
                body: *reaction,
                point: i.origin.clone(),
                force: Some(-push.clone()),
                torque: Some(-turn.clone()),
            };
            let on_i = Action {
                body: i.body,
                point: i.origin,
                force: Some(push),
                torque: Some(turn),
            };
            [Some(on_i), Some(other)]
        }
        Force::Contact(contact) => super::contact::actions(model, contact, kinematics, branch),
    }
}

impl<T: Number> Action<T> {
    /// `force` at the placed marker, on its body.
    fn at(marker: Placed<T>, force: Vector3<T>) -> Action<T> {
        Action {
            body: marker.body,
            point: marker.origin,
            force: Some(force),
            torque: None,
        }
    }
}
