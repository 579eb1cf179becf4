//! `PART ..., EXACT = X:Y:Z:PSI:THETA:PHI`: the part coordinates the
//! initial-conditions analysis must not change; and `PART ..., VX = ...,
//! WZ = ...`: the part velocities it keeps where the joints leave them
//! free. A `POINT_MASS` gives them alike, its coordinates X, Y, Z and its
//! velocities VX, VY, VZ.

use nalgebra::{Matrix3, Vector3};

use crate::model::initial::number;
use crate::model::{Dataset, Value, is_kind};
use crate::scene::Scene;
use crate::simulate::error::SimulateError;
use crate::simulate::model::{ExactPart, GivenVelocity, MassProperties};

/// The coordinates `EXACT` may name, in Adams' order.
const COORDINATES: [&str; 6] = ["X", "Y", "Z", "PSI", "THETA", "PHI"];

/// The parts and point masses of `dataset` with `EXACT`, their bodies in `scene` (drawn at
/// time 0) and `masses`; what cannot be read is added to `errors` at its
/// place.
pub(super) fn exact_parts(
    dataset: &Dataset,
    scene: &Scene,
    masses: &[MassProperties],
    errors: &mut Vec<SimulateError>,
) -> Vec<ExactPart> {
    let mut parts = Vec::new();
    for statement in &dataset.statements {
        let point_mass = is_kind(&statement.name, "POINT_MASS");
        if !point_mass && !is_kind(&statement.name, "PART") {
            continue;
        }
        let Some(argument) = statement.argument("EXACT", 5) else {
            continue;
        };
        let label = statement.label();
        let Some(body) = scene.bodies.iter().position(|body| body.name == label) else {
            continue;
        };
        let mut coordinates = [false; 6];
        let mut unknown = Vec::new();
        if let Value::List(items) = &argument.value {
            for name in items.iter().flat_map(|item| item.text.split(':')) {
                let name = name.trim().to_ascii_uppercase();
                match COORDINATES.iter().position(|known| *known == name) {
                    Some(k) => coordinates[k] = true,
                    None => unknown.push(name),
                }
            }
        }
        if point_mass && coordinates[3..].contains(&true) {
            errors.push(SimulateError::Model {
                message: format!(
                    "{label}: EXACT lists a POINT_MASS's coordinates among X, Y, Z: a point mass has no angles"
                ),
                span: argument.span,
            });
            continue;
        }
        if !unknown.is_empty() || !coordinates.contains(&true) {
            errors.push(SimulateError::Model {
                message: format!(
                    "{label}: EXACT lists part coordinates among X, Y, Z, PSI, THETA, PHI, joined by ':'{}",
                    if unknown.is_empty() {
                        String::new()
                    } else {
                        format!(" ({} is none of them)", unknown.join(", "))
                    }
                ),
                span: argument.span,
            });
            continue;
        }
        let drawn = &scene.bodies[body];
        let rotation = drawn.orientation.to_rotation_matrix().into_inner();
        let centre = drawn.position + rotation * masses[body].centre;
        // The angles are those of the CM marker's axes (the body's when
        // the CM marker is not found).
        let cm_axes = number(statement, "CM", f64::NAN)
            .ok()
            .and_then(|id| {
                scene
                    .markers
                    .iter()
                    .find(|marker| marker.id.is_some_and(|marker_id| marker_id as f64 == id))
            })
            .map_or_else(Matrix3::identity, |marker| {
                marker.orientation.to_rotation_matrix().into_inner()
            });
        let axes = rotation * cm_axes;
        parts.push(ExactPart {
            body,
            coordinates,
            centre,
            axes,
            cm_axes,
            span: argument.span,
        });
    }
    parts
}

/// The velocity keywords of a PART, in [`GivenVelocity::values`]' order.
const VELOCITIES: [&str; 6] = ["VX", "VY", "VZ", "WX", "WY", "WZ"];

/// The parts of `dataset` that give any of `VX ... WZ`, with their VM and
/// WM markers (the CM marker's when left out) in `scene`'s bodies, and the
/// point masses that give any of `VX, VY, VZ`. A value
/// or a marker that cannot be read is reported where the scene is read.
pub(super) fn given_velocities(dataset: &Dataset, scene: &Scene) -> Vec<GivenVelocity> {
    let mut given = Vec::new();
    for statement in &dataset.statements {
        let point_mass = is_kind(&statement.name, "POINT_MASS");
        let part = is_kind(&statement.name, "PART") && statement.argument("GROUND", 3).is_none();
        if !point_mass && !part {
            continue;
        }
        let values = VELOCITIES.map(|keyword| {
            statement
                .argument(keyword, 2)
                .and_then(|_| number(statement, keyword, f64::NAN).ok())
                .filter(|value| value.is_finite())
        });
        if values.iter().all(Option::is_none) {
            continue;
        }
        let label = statement.label();
        let Some(body) = scene.bodies.iter().position(|body| body.name == label) else {
            continue;
        };
        let marker = |keyword: &str| {
            let id = number(statement, keyword, f64::NAN).ok()?;
            (id.fract() == 0.0 && id >= 0.0).then_some(())?;
            scene.marker_on(id as u64, body)
        };
        let cm = marker("CM");
        if point_mass {
            // A point mass gives VX, VY, VZ of its CM marker's origin (its
            // own origin without one), which its axes carry unturned.
            given.push(GivenVelocity {
                body,
                point: cm.map_or_else(Vector3::zeros, |marker| marker.position),
                axes: Matrix3::identity(),
                values,
            });
            continue;
        }
        let (Some(at), Some(about)) = (marker("VM").or(cm), marker("WM").or(cm)) else {
            continue;
        };
        given.push(GivenVelocity {
            body,
            point: at.position,
            axes: about.orientation.to_rotation_matrix().into_inner(),
            values,
        });
    }
    given
}
