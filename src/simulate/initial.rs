//! Initial conditions: the state a run starts from, from the model's DIFF
//! initial values and its bodies' placements and velocities.

use super::Model;

/// The initial state of the model.
pub(super) fn initial_state(model: &Model) -> Vec<f64> {
    let mut y: Vec<f64> = model.diffs.iter().map(|diff| diff.initial).collect();
    for (body, state) in model.scene.bodies.iter().enumerate() {
        let rotation = state.orientation;
        let arm = rotation * model.masses[body].centre;
        let centre = state.position + arm;
        let velocity = state.velocity + state.angular_velocity.cross(&arm);
        let omega = rotation.inverse() * state.angular_velocity;
        let q = rotation.quaternion();
        y.extend(centre.iter());
        y.extend([q.w, q.i, q.j, q.k]);
        y.extend(velocity.iter());
        y.extend(omega.iter());
    }
    y
}
