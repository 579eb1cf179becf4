//! The `COUPLER` statements: two or three joints' displacements tied by
//! their scales, `s₁ q₁ + s₂ q₂ (+ s₃ q₃) = 0`, each `q` a REVOLUTE's
//! rotation, a TRANSLATIONAL's translation, or either of a CYLINDRICAL's as
//! its `TYPE` says; and the `GEAR` statements, couplers whose scales the
//! place of their common-velocity marker gives.

use nalgebra::{Matrix3, Vector3};

use crate::model::initial::number_list;
use crate::model::{Argument, Dataset, Statement, Value, is_kind};
use crate::scene::{Scene, Target};
use crate::simulate::error::SimulateError;
use crate::simulate::model::{Coupler, Joint, JointKind};
use crate::span::Span;

/// The couplers of `dataset` among `joints`; what cannot be read is
/// recorded in `errors` at its place.
pub(super) fn couplers(
    dataset: &Dataset,
    joints: &[Joint],
    errors: &mut Vec<SimulateError>,
) -> Vec<Coupler> {
    dataset
        .statements
        .iter()
        .filter(|statement| is_kind(&statement.name, "COUPLER"))
        .filter_map(|statement| match coupler(statement, joints) {
            Ok(coupler) => Some(coupler),
            Err((message, span)) => {
                errors.push(SimulateError::Model { message, span });
                None
            }
        })
        .collect()
}

/// Argument `keyword` of `statement`, or the message that asks for it.
fn required<'s>(
    statement: &'s Statement,
    keyword: &str,
    what: &str,
) -> Result<&'s Argument, (String, Span)> {
    statement.argument(keyword, 2).ok_or_else(|| {
        (
            format!("{}: give {keyword} = {what}", statement.label()),
            statement.span,
        )
    })
}

/// The index among `joints` of the joint `id` that `listed` names in the
/// statement `label`, or the message that it names none.
fn joint_index(
    joints: &[Joint],
    id: f64,
    label: &str,
    listed: &Argument,
) -> Result<usize, (String, Span)> {
    joints
        .iter()
        .position(|joint| joint.id as f64 == id)
        .ok_or_else(|| {
            (
                format!("{label}: JOINT/{id} is not a joint of the model"),
                listed.span,
            )
        })
}

/// The coupler `statement` gives among `joints`, or why it gives none.
fn coupler(statement: &Statement, joints: &[Joint]) -> Result<Coupler, (String, Span)> {
    let label = statement.label();
    if let Some(argument) = statement.argument("FUNCTION", 2) {
        return Err((
            format!(
                "{label}: a COUPLER given by a FUNCTION (COUSUB) is not simulated: give JOINTS, TYPE and SCALES"
            ),
            argument.span,
        ));
    }
    let listed = required(statement, "JOINTS", "the two or three joints it couples")?;
    let ids = number_list(statement, listed).unwrap_or_default();
    if !(2..=3).contains(&ids.len()) {
        return Err((
            format!("{label}: JOINTS names two or three joints"),
            listed.span,
        ));
    }
    if named_twice(&ids) {
        return Err((
            format!("{label}: JOINTS names one joint twice: a COUPLER ties different joints"),
            listed.span,
        ));
    }
    let scaled = required(
        statement,
        "SCALES",
        "one number for each joint (s1 q1 + s2 q2 = 0)",
    )?;
    let mut scales = number_list(statement, scaled).unwrap_or_default();
    // Adams' short form: one number fewer than the joints gives r2 (and
    // r3), r1 being 1.
    if scales.len() + 1 == ids.len() {
        scales.insert(0, 1.0);
    }
    if scales.len() != ids.len() || scales.iter().any(|scale| !scale.is_finite()) {
        return Err((
            format!(
                "{label}: SCALES needs {} numbers, one for each joint (or {}, the first being 1)",
                ids.len(),
                ids.len() - 1
            ),
            scaled.span,
        ));
    }
    // TYPE = R:T ... (the dataset reads it as one word).
    let types: Vec<String> = match statement
        .argument("TYPE", 2)
        .map(|argument| &argument.value)
    {
        Some(Value::List(items)) => items
            .iter()
            .flat_map(|item| {
                item.text
                    .split(':')
                    .map(|kind| kind.trim().to_ascii_uppercase())
                    .collect::<Vec<_>>()
            })
            .collect(),
        _ => Vec::new(),
    };
    let mut coupled = Vec::new();
    for (k, (&id, &scale)) in ids.iter().zip(&scales).enumerate() {
        let index = joint_index(joints, id, &label, listed)?;
        let written = types.get(k).map(String::as_str);
        let rotation = match (joints[index].kind, written) {
            (JointKind::Revolute, None | Some("R")) | (JointKind::Cylindrical, Some("R")) => true,
            (JointKind::Translational, None | Some("T")) | (JointKind::Cylindrical, Some("T")) => {
                false
            }
            (kind, _) => {
                let keyword = JointKind::ALL
                    .iter()
                    .chain(&JointKind::PRIMITIVES)
                    .find(|(known, _)| *known == kind)
                    .map_or("", |(_, keyword)| *keyword);
                return Err((
                    format!(
                        "{label}: couples JOINT/{id}, a {keyword} joint, by {}: a COUPLER couples a REVOLUTE's rotation (R), a TRANSLATIONAL's translation (T) or a CYLINDRICAL's, as TYPE says",
                        written.unwrap_or("no TYPE")
                    ),
                    statement.span,
                ));
            }
        };
        coupled.push((index, rotation, scale));
    }
    Ok(Coupler {
        statement: "COUPLER",
        id: statement.id.unwrap_or(0),
        joints: coupled,
        contact: None,
        span: statement.span,
    })
}

/// The `GEAR` statements of `dataset` among `joints`, as couplers; what
/// cannot be read is recorded in `errors` at its place.
pub(super) fn gears(
    dataset: &Dataset,
    joints: &[Joint],
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Vec<Coupler> {
    dataset
        .statements
        .iter()
        .filter(|statement| is_kind(&statement.name, "GEAR"))
        .filter_map(|statement| match gear(statement, joints, scene) {
            Ok(gear) => Some(gear),
            Err((message, span)) => {
                errors.push(SimulateError::Model { message, span });
                None
            }
        })
        .collect()
}

/// `target`'s body, its origin and its axes (columns) in ground, where the
/// scene draws it.
fn drawn(scene: &Scene, target: Target) -> (Option<usize>, Vector3<f64>, Matrix3<f64>) {
    match target {
        Target::Ground => (None, Vector3::zeros(), Matrix3::identity()),
        Target::Marker(index) => {
            let marker = &scene.markers[index];
            let own = marker.orientation.to_rotation_matrix().into_inner();
            let axes = marker.body.map_or(own, |body| {
                scene.bodies[body]
                    .orientation
                    .to_rotation_matrix()
                    .into_inner()
                    * own
            });
            (marker.body, scene.origin(target), axes)
        }
    }
}

/// The gear `statement` gives among `joints`, or why it gives none.
///
/// Adams' GEAR: two joints (REVOLUTE, TRANSLATIONAL or CYLINDRICAL) that
/// share a part, the carrier, which holds the common-velocity marker CV at
/// the teeth's contact, its z axis along their motion; the contact point
/// moves alike along that axis as a point of either gear. Relative to the
/// carrier a joint's rotation `q̇` moves it at `q̇ z × (c − o)` and its
/// translation at `q̇ z` (`o`, `z`: the joint's J origin and axis, `c`:
/// CV's origin), all fixed in the carrier: so `k₁ q̇₁ = k₂ q̇₂` with `k =
/// ±(z × (c − o))·z_CV` or `±z·z_CV` (the sign − for a joint whose I
/// marker is on the carrier), a coupler with scales `k₁, −k₂`.
fn gear(statement: &Statement, joints: &[Joint], scene: &Scene) -> Result<Coupler, (String, Span)> {
    let label = statement.label();
    let listed = required(statement, "JOINTS", "the two joints it gears")?;
    let ids = number_list(statement, listed).unwrap_or_default();
    if ids.len() != 2 || named_twice(&ids) {
        return Err((format!("{label}: JOINTS names two joints"), listed.span));
    }
    let cv_argument = required(
        statement,
        "CV",
        "the common-velocity marker, at the teeth's contact, its z axis along their motion",
    )?;
    let cv = super::named_marker(statement, "CV", scene)
        .filter(|target| matches!(target, Target::Marker(_)))
        .ok_or_else(|| {
            (
                format!("{label}: CV must name a MARKER of the model"),
                cv_argument.span,
            )
        })?;
    let (carrier, contact, cv_axes) = drawn(scene, cv);
    let along = cv_axes.column(2).into_owned();
    let body_of = |target: Target| drawn(scene, target).0;
    let mut coupled = Vec::new();
    for (k, &id) in ids.iter().enumerate() {
        let index = joint_index(joints, id, &label, listed)?;
        let joint = &joints[index];
        let (turns, slides) = match joint.kind {
            JointKind::Revolute => (true, false),
            JointKind::Translational => (false, true),
            JointKind::Cylindrical => (true, true),
            _ => {
                return Err((
                    format!(
                        "{label}: gears JOINT/{id}, which is not a REVOLUTE, TRANSLATIONAL or CYLINDRICAL joint"
                    ),
                    listed.span,
                ));
            }
        };
        let sign = if body_of(joint.j) == carrier {
            1.0
        } else if body_of(joint.i) == carrier {
            -1.0
        } else {
            return Err((
                format!(
                    "{label}: the CV marker must be on the part both joints hold (the carrier), and JOINT/{id} does not hold the CV marker's part"
                ),
                cv_argument.span,
            ));
        };
        // The first gear's contact velocity equals the second's.
        let side = if k == 0 { sign } else { -sign };
        let (_, origin, axes) = drawn(scene, joint.j);
        let axis = axes.column(2).into_owned();
        let arm = contact - origin;
        let size = 1.0 + arm.norm();
        let mut moves = false;
        if turns {
            let scale = axis.cross(&arm).dot(&along);
            if scale.abs() > 1e-9 * size {
                coupled.push((index, true, side * scale));
                moves = true;
            }
        }
        if slides {
            let scale = axis.dot(&along);
            if scale.abs() > 1e-9 {
                coupled.push((index, false, side * scale));
                moves = true;
            }
        }
        if !moves {
            return Err((
                format!(
                    "{label}: JOINT/{id} does not move the contact point along the CV marker's z axis (point CV's z along the teeth's motion, at their contact)"
                ),
                cv_argument.span,
            ));
        }
    }
    Ok(Coupler {
        statement: "GEAR",
        id: statement.id.unwrap_or(0),
        joints: coupled,
        contact: Some(cv),
        span: statement.span,
    })
}

/// Whether `ids` names one joint twice.
fn named_twice(ids: &[f64]) -> bool {
    ids.iter()
        .enumerate()
        .any(|(index, id)| ids[..index].contains(id))
}
