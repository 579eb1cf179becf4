//! Force elements: where each acts (its markers placed in ground) and what
//! it applies to the bodies.

use nalgebra::{Matrix3, Vector3};

use super::bodies::{Kinematics, Loads};
use crate::number::Number;
use crate::scene::Target;
use crate::simulate::model::{Force, Model};

/// A marker's origin and axes in ground.
struct Placed<T: Number> {
    origin: Vector3<T>,
    axes: Matrix3<T>,
    body: Option<usize>,
}

/// A marker's origin and axes in ground.
fn place<T: Number>(model: &Model, target: &Target, kinematics: &[Kinematics<T>]) -> Placed<T> {
    let Target::Marker(index) = target else {
        return Placed {
            origin: Vector3::zeros(),
            axes: Matrix3::identity(),
            body: None,
        };
    };
    let marker = &model.scene.markers[*index];
    let axes_in_body = marker.orientation.to_rotation_matrix().into_inner();
    match marker.body {
        None => Placed {
            origin: marker.position.map(T::from),
            axes: axes_in_body.map(T::from),
            body: None,
        },
        Some(body) => {
            let state = &kinematics[body];
            let offset = marker.position - model.masses[body].centre;
            Placed {
                origin: &state.centre + &state.rotation * offset.map(T::from),
                axes: &state.rotation * axes_in_body.map(T::from),
                body: Some(body),
            }
        }
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
            let (i, j) = (place(model, i, kinematics), place(model, j, kinematics));
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
            let (i, j) = (place(model, i, kinematics), place(model, j, kinematics));
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
            let i = place(model, i, kinematics);
            let axes = place(model, axes, kinematics).axes;
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
