//! `JOINT` and `JPRIM` statements of a dataset.

use crate::model::initial::{number, number_list};
use crate::model::{Argument, Dataset, Statement, Value, is_kind};
use crate::scene::{Scene, Target};
use crate::simulate::SimulateError;
use crate::simulate::model::{Joint, JointInitial, JointKind, Motion};
use crate::span::Span;

/// The JOINT statements of `dataset`, their markers found in `scene`; every
/// problem added to `errors` at its place.
pub(crate) fn joints(
    dataset: &Dataset,
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Vec<Joint> {
    let mut joints = Vec::new();
    for statement in &dataset.statements {
        let found = if is_kind(&statement.name, "JOINT") {
            joint(statement, scene, errors)
        } else if is_kind(&statement.name, "JPRIM") {
            primitive(statement, scene, errors)
        } else {
            continue;
        };
        joints.extend(found);
    }
    joints
}

fn joint(statement: &Statement, scene: &Scene, errors: &mut Vec<SimulateError>) -> Option<Joint> {
    let label = statement.label();
    let names: Vec<&str> = JointKind::ALL.iter().map(|(_, name)| *name).collect();
    let given: Vec<&(JointKind, &str)> = JointKind::ALL
        .iter()
        .filter(|(_, name)| statement.argument(name, 3).is_some())
        .collect();
    if let [(first, first_name), rest @ ..] = given.as_slice()
        && let Some((_, other_name)) = rest.iter().find(|(kind, _)| kind != first)
    {
        errors.push(SimulateError::Model {
            message: format!("{label}: give one type, not both {first_name} and {other_name}"),
            span: statement.span,
        });
        return None;
    }
    let kind = given.first().map(|(kind, _)| *kind);
    let Some(kind) = kind else {
        errors.push(SimulateError::Unsupported {
            statement: label,
            reason: format!("needs its type: one of {}", names.join(", ")),
            span: statement.span,
        });
        return None;
    };
    if let Some(error) = friction(statement) {
        errors.push(error);
    }
    let pitch = match kind {
        JointKind::RackPin => length(statement, "PD", "the pinion's pitch diameter", errors)?,
        JointKind::Screw => length(statement, "PITCH", "the translation per turn", errors)?,
        _ => 0.0,
    };
    between_markers(statement, kind, scene, errors).map(|joint| Joint { pitch, ..joint })
}

/// The keywords of the joint friction that Adams View writes on a JOINT
/// statement itself, each with the letters that tell it from the others:
/// the coefficients, the largest friction and the preloads, any of which
/// not zero makes a friction force.
const FRICTION_FORCES: [(&str, usize); 10] = [
    ("MU_DYN_ROT", 8),
    ("MU_STAT_ROT", 9),
    ("MU_DYN_TRANS", 8),
    ("MU_STAT_TRANS", 9),
    ("MAX_FRIC_ROT", 10),
    ("MAX_FRIC_TRANS", 10),
    ("PRELOAD_RADIAL", 9),
    ("PRELOAD_AXIAL", 9),
    ("PRELOAD_X", 9),
    ("PRELOAD_Y", 9),
];

/// The refusal of a JOINT's own friction, where it makes a force: a
/// coefficient, largest friction or preload that is not 0, or `FRICTION =
/// ON` (or PRELOAD_ONLY) with no coefficient given; `FRICTION = OFF` has
/// none.
/// `DELTA_V`, `MAXIMUM_DEFORMATION` and the bearing's sizes (INNER_RADIUS,
/// OUTER_RADIUS, HEIGHT, WIDTH) alone shape a friction of no force: Adams
/// View 12 writes the first two on every revolute joint, friction or not.
fn friction(statement: &Statement) -> Option<SimulateError> {
    let switch = statement.argument("FRICTION", 3);
    let word = switch.and_then(super::word_of);
    if word
        .as_deref()
        .is_some_and(|word| word.len() >= 2 && "OFF".starts_with(word))
    {
        return None;
    }
    let refuse = |keyword: &str, span: Span| SimulateError::Unsupported {
        statement: statement.label(),
        reason: format!(
            "sets {keyword}: a JOINT's own friction keywords are not simulated: give the joint a FRICTION statement"
        ),
        span,
    };
    // A coefficient given (as 0 to reach here): without one, a FRICTION
    // that is on takes coefficients the dataset does not show.
    let mut coefficient_given = false;
    for (keyword, shortest) in FRICTION_FORCES {
        let Some(argument) = statement.argument(keyword, shortest) else {
            continue;
        };
        coefficient_given |= keyword.starts_with("MU_");
        if number_list(statement, argument).map_or(true, |values| values != [0.0]) {
            return Some(refuse(keyword, argument.span));
        }
    }
    match switch {
        Some(argument) if !coefficient_given => Some(refuse("FRICTION", argument.span)),
        _ => None,
    }
}

/// The length `keyword` of a RACKPIN or SCREW joint (`what` it is): a
/// number, not zero (a pitch diameter positive).
fn length(
    statement: &Statement,
    keyword: &str,
    what: &str,
    errors: &mut Vec<SimulateError>,
) -> Option<f64> {
    let value = number(statement, keyword, f64::NAN)
        .ok()
        .filter(|value| value.is_finite() && *value != 0.0 && (keyword != "PD" || *value > 0.0));
    if value.is_none() {
        errors.push(SimulateError::Model {
            message: format!(
                "{}: this joint needs {keyword} = {what}, a nonzero number{}",
                statement.label(),
                if keyword == "PD" { " above zero" } else { "" }
            ),
            span: statement.place_of(keyword, keyword.len()),
        });
    }
    value
}

/// A `JPRIM` statement: one of the joint primitives, between its markers.
fn primitive(
    statement: &Statement,
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Option<Joint> {
    let kind = JointKind::PRIMITIVES
        .iter()
        .find(|(_, name)| statement.argument(name, 3).is_some())
        .map(|(kind, _)| *kind);
    let Some(kind) = kind else {
        let names: Vec<&str> = JointKind::PRIMITIVES
            .iter()
            .map(|(_, name)| *name)
            .collect();
        errors.push(SimulateError::Unsupported {
            statement: statement.label(),
            reason: format!("needs its type: one of {}", names.join(", ")),
            span: statement.span,
        });
        return None;
    };
    between_markers(statement, kind, scene, errors)
}

/// The joint of `kind` that `statement` places between its I and J
/// markers.
fn between_markers(
    statement: &Statement,
    kind: JointKind,
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Option<Joint> {
    let i = marker(statement, "I", scene, errors);
    let j = marker(statement, "J", scene, errors);
    let (i, j) = (i?, j?);
    let body = |target: Target| scene.body_of(&target);
    if body(i) == body(j) {
        errors.push(SimulateError::Model {
            message: format!(
                "{}: its I and J markers are on one part ({}): a joint holds one part to another, so give markers of two parts",
                statement.label(),
                match body(i) {
                    None => "the ground".to_string(),
                    Some(body) => scene.bodies[body].name.clone(),
                }
            ),
            span: statement.span,
        });
        return None;
    }
    Some(Joint {
        id: statement.id.unwrap_or(0),
        kind,
        i,
        j,
        pitch: 0.0,
        curve: None,
        pair: None,
        redundant: Vec::new(),
        span: statement.span,
    })
}

/// The marker `keyword` names (a joint needs both of its markers).
fn marker(
    statement: &Statement,
    keyword: &str,
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Option<Target> {
    super::needed_marker(
        statement,
        keyword,
        scene,
        errors,
        &format!("a joint needs {keyword} = the id of a MARKER of the model"),
    )
}

/// The initial conditions of `joints` (`IC` of a REVOLUTE or TRANSLATIONAL
/// joint, `ICTRAN` and `ICROT` of a CYLINDRICAL one: the velocity, then
/// optionally the displacement). A condition on a displacement a MOTION
/// of `motions` drives is left aside with a note in `notes`, as Adams
/// does: the motion sets it.
pub(crate) fn initials(
    dataset: &Dataset,
    joints: &[Joint],
    motions: &[Motion],
    notes: &mut Vec<(String, Span)>,
    errors: &mut Vec<SimulateError>,
) -> Vec<JointInitial> {
    let mut initials = Vec::new();
    for statement in &dataset.statements {
        if !is_kind(&statement.name, "JOINT") {
            continue;
        }
        let id = statement.id.unwrap_or(0);
        let Some(joint) = joints
            .iter()
            .position(|joint| joint.id == id && joint.kind.statement() == "JOINT")
        else {
            continue;
        };
        let kind = joints[joint].kind;
        for (keyword, rotation) in [("IC", None), ("ICTRAN", Some(false)), ("ICROT", Some(true))] {
            let Some(argument) = statement.argument(keyword, keyword.len()) else {
                continue;
            };
            let label = statement.label();
            let rotation = match (kind, rotation) {
                (JointKind::Revolute, None) => true,
                (JointKind::Translational, None) => false,
                (JointKind::Cylindrical, Some(rotation)) => rotation,
                _ => {
                    errors.push(SimulateError::Model {
                        message: format!(
                            "{label}: {keyword} is not an argument of this joint: IC sets a REVOLUTE joint's rotation or a TRANSLATIONAL one's translation, ICROT and ICTRAN a CYLINDRICAL one's"
                        ),
                        span: argument.span,
                    });
                    continue;
                }
            };
            let Some((displacement, velocity)) = initial_values(statement, argument) else {
                errors.push(SimulateError::Model {
                    message: format!(
                        "{label}: {keyword} = the initial velocity [, the initial displacement]: one or two numbers (`{keyword} = , d` gives the displacement alone)"
                    ),
                    span: argument.span,
                });
                continue;
            };
            if let Some(motion) = motions
                .iter()
                .find(|motion| motion.joint == joint && motion.rotation == rotation)
            {
                notes.push((
                    format!(
                        "{label}: {keyword} is left aside: MOTION/{} drives the same displacement",
                        motion.id
                    ),
                    argument.span,
                ));
                continue;
            }
            initials.push(JointInitial {
                joint,
                rotation,
                displacement,
                velocity,
                span: argument.span,
            });
        }
    }
    initials
}

/// An initial condition's displacement and velocity, each when given:
/// `IC = velocity [, displacement]`, the velocity first as Adams reads it
/// (Adams View writes `translational_ic = -146.99, velocity_ic = -0.1815`
/// as `IC = -0.1815, -146.99`, and Adams Solver assembles that model with
/// the joint at -146.99), the velocity left empty (`IC = , 30`) when the
/// displacement alone is given.
fn initial_values(
    statement: &Statement,
    argument: &Argument,
) -> Option<(Option<f64>, Option<f64>)> {
    if let Value::List(items) = &argument.value
        && let [first, second] = items.as_slice()
        && first.text.is_empty()
    {
        let displacement = second.number().filter(|value| value.is_finite())?;
        return Some((Some(displacement), None));
    }
    let values = number_list(statement, argument).ok()?;
    if !(1..=2).contains(&values.len()) || values.iter().any(|value| !value.is_finite()) {
        return None;
    }
    Some((values.get(1).copied(), Some(values[0])))
}
