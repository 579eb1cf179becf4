//! The `COUPLER` statements: two or three joints' displacements tied by
//! their scales, `s₁ q₁ + s₂ q₂ (+ s₃ q₃) = 0`, each `q` a REVOLUTE's
//! rotation, a TRANSLATIONAL's translation, or either of a CYLINDRICAL's as
//! its `TYPE` says.

use crate::model::initial::number_list;
use crate::model::{Argument, Dataset, Statement, Value, is_kind};
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
    let scaled = required(
        statement,
        "SCALES",
        "one number for each joint (s1 q1 + s2 q2 = 0)",
    )?;
    let scales = number_list(statement, scaled).unwrap_or_default();
    if scales.len() != ids.len() || scales.iter().any(|scale| !scale.is_finite()) {
        return Err((
            format!(
                "{label}: SCALES needs {} numbers, one for each joint",
                ids.len()
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
        let index = joints
            .iter()
            .position(|joint| joint.id as f64 == id)
            .ok_or_else(|| {
                (
                    format!("{label}: JOINT/{id} is not a joint of the model"),
                    listed.span,
                )
            })?;
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
        id: statement.id.unwrap_or(0),
        joints: coupled,
        span: statement.span,
    })
}
