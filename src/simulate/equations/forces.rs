//! Force elements: where each acts (its markers placed in ground) and what
//! it applies to the bodies.

use nalgebra::{Matrix3, Vector3};

use super::bodies::{Kinematics, Loads};
use crate::kinematics::times_constant;
use crate::number::Number;
use crate::scene::Target;
use crate::simulate::model::{Force, Model};

/// A marker's origin in ground and the body it is on.
struct Placed<T: Number> {
    origin: Vector3<T>,
    body: Option<usize>,
}

/// A marker's origin in ground and its body.
fn place<T: Number>(model: &Model, target: &Target, kinematics: &[Kinematics<T>]) -> Placed<T> {
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
    match target {
        Target::Marker(index) => model.scene.markers[*index].body,
        Target::Ground => None,
    }
}

/// A marker's axes in ground (worked out only for the elements that read
/// them: most forces act along the line between their markers).
fn axes<T: Number>(model: &Model, target: &Target, kinematics: &[Kinematics<T>]) -> Matrix3<T> {
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

/// Adds what `force` applies to the bodies.
pub(super) fn apply<T: Number>(
    model: &Model,
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
            let magnitude = value(Some(*magnitude));
            if *action_only {
                let along = axes(model, j, kinematics).column(2).into_owned() * magnitude;
                let i = place(model, i, kinematics);
                loads.push(i.body, &i.origin, &along, kinematics);
                return;
            }
            let (i, j) = (place(model, i, kinematics), place(model, j, kinematics));
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
            let torque =
                axes(model, j, kinematics).column(2).into_owned() * value(Some(*magnitude));
            let (i, j) = (body_of(model, i), body_of(model, j));
            loads.turn(i, &torque);
            if !*action_only {
                loads.turn(j, &-torque);
            }
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
            loads.push(i.body, &i.origin, &push, kinematics);
            loads.turn(i.body, &turn);
            if reaction.is_some() {
                loads.push(*reaction, &i.origin, &-push, kinematics);
                loads.turn(*reaction, &-turn);
            }
        }
    }
}
