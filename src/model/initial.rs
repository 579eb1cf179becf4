//! The initial configuration of a solver dataset as a [`Scene`]: PART and
//! MARKER statements give bodies and markers (REULER is body-fixed 3-1-3,
//! radians unless written with `D`), VARIABLE functions give `VARVAL`, ARRAY
//! NUMBERS give `ARYVAL`, SPLINE points give `AKISPL` and `CUBSPL`, DIFF
//! initial values (`IC`, 0 when not given) give `DIF`; the time is 0.

use nalgebra::{UnitQuaternion, Vector3};
use thiserror::Error;

use super::{Argument, ModelCheck, Statement, Value, is_statement};
use crate::laws::spline::{SplineData, SplineDataError};
use std::collections::HashSet;

use crate::scene::{Body, DiffData, Marker, Scene, SceneKind, euler_313};
use crate::span::Span;

/// A statement whose data cannot make a scene.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ConfigurationError {
    /// A value list that is not the numbers it should be.
    #[error("{statement}: {keyword} needs {count} number{}", if *count == 1 { "" } else { "s" })]
    Numbers {
        /// `PART/3`.
        statement: String,
        /// `QG`.
        keyword: String,
        /// How many numbers.
        count: usize,
        /// The argument.
        span: Span,
    },
    /// A number written beyond the range of a double (`1e400`), or as
    /// `inf` or `nan`.
    #[error(
        "{statement}: {keyword} = {text} is not a finite number (a double reaches about 1.8e308)"
    )]
    NotFinite {
        /// `DIFF/3`.
        statement: String,
        /// `IC`.
        keyword: String,
        /// The number as written.
        text: String,
        /// The number.
        span: Span,
    },
    /// Axes that points or angles cannot give.
    #[error("{statement}: {reason}")]
    Axes {
        /// `MARKER/3`.
        statement: String,
        /// What is wrong.
        reason: String,
        /// The statement.
        span: Span,
    },
    /// A marker on a part (or point mass) that is not defined.
    #[error("{statement}: there is no {kind}/{part}")]
    UnknownPart {
        /// `MARKER/12`.
        statement: String,
        /// `PART` or `POINT_MASS`.
        kind: &'static str,
        /// The part id.
        part: u64,
        /// The statement.
        span: Span,
    },
    /// A control element (TFSISO, LSE, their ARRAYs and MATRIXes) that
    /// does not give a linear system.
    #[error("{statement}: {reason}")]
    Control {
        /// `LSE/2`.
        statement: String,
        /// What is wrong.
        reason: String,
        /// The statement.
        span: Span,
    },
    /// SPLINE points that cannot be interpolated.
    #[error("{statement}: {error}")]
    Spline {
        /// `SPLINE/5`.
        statement: String,
        /// What is wrong.
        error: SplineDataError,
        /// The statement.
        span: Span,
    },
}

impl ConfigurationError {
    /// The place in the file.
    pub fn span(&self) -> Span {
        match self {
            ConfigurationError::Numbers { span, .. }
            | ConfigurationError::NotFinite { span, .. }
            | ConfigurationError::Axes { span, .. }
            | ConfigurationError::UnknownPart { span, .. }
            | ConfigurationError::Control { span, .. }
            | ConfigurationError::Spline { span, .. } => *span,
        }
    }
}

/// The numbers of argument `keyword` (`count` of them), or `default`.
pub(crate) fn numbers<const N: usize>(
    statement: &Statement,
    keyword: &str,
    default: [f64; N],
) -> Result<[f64; N], ConfigurationError> {
    let Some(argument) = statement.argument(keyword, keyword.len().min(2)) else {
        return Ok(default);
    };
    let error = || ConfigurationError::Numbers {
        statement: statement.label(),
        keyword: keyword.to_string(),
        count: N,
        span: argument.span,
    };
    let values = number_list(statement, argument).map_err(|failed| match failed {
        ConfigurationError::NotFinite { .. } => failed,
        _ => error(),
    })?;
    values.try_into().map_err(|_| error())
}

/// The error of the first number of `argument`'s value list written beyond
/// the range of a double (`1e309`), or as `inf` or `nan`.
pub(crate) fn not_finite(statement: &Statement, argument: &Argument) -> Option<ConfigurationError> {
    let Value::List(items) = &argument.value else {
        return None;
    };
    let item = items.iter().find(|item| {
        let digits = item.text.trim().trim_end_matches(['d', 'D']);
        digits.parse::<f64>().is_ok_and(|value| !value.is_finite())
    })?;
    Some(ConfigurationError::NotFinite {
        statement: statement.label(),
        keyword: argument.keyword.to_string(),
        text: item.text.to_string(),
        span: item.span,
    })
}

/// All the numbers of `argument`, a value list.
pub(crate) fn number_list(
    statement: &Statement,
    argument: &Argument,
) -> Result<Vec<f64>, ConfigurationError> {
    let items = match &argument.value {
        Value::List(items) => items.as_slice(),
        _ => &[],
    };
    let values: Vec<f64> = items.iter().filter_map(|item| item.number()).collect();
    if let Some(error) = not_finite(statement, argument) {
        return Err(error);
    }
    if values.is_empty() || values.len() != items.len() {
        return Err(ConfigurationError::Numbers {
            statement: statement.label(),
            keyword: argument.keyword.to_string(),
            count: items.len().max(1),
            span: argument.span,
        });
    }
    Ok(values)
}

/// The points of a SPLINE statement: `X=` and one `Y=` (a curve), or several
/// `Y = z, y1, ...` (a family); `None` when it has no `X=` (its points are
/// in a file).
fn spline_data(statement: &Statement) -> Result<Option<SplineData>, ConfigurationError> {
    let Some(x_argument) = statement.argument("X", 1) else {
        return Ok(None);
    };
    let x = number_list(statement, x_argument)?;
    let y_arguments: Vec<&Argument> = statement
        .arguments
        .iter()
        .filter(|argument| argument.keyword == "Y")
        .collect();
    let mut curves = Vec::new();
    for argument in &y_arguments {
        let values = number_list(statement, argument)?;
        if y_arguments.len() == 1 {
            curves.push((0.0, values));
        } else {
            curves.push((values[0], values[1..].to_vec()));
        }
    }
    let linear = statement.argument("LINEAR_EXTRAPOLATE", 3).is_some();
    SplineData::new(x, curves, linear)
        .map(Some)
        .map_err(|error| ConfigurationError::Spline {
            statement: statement.label(),
            error,
            span: statement.span,
        })
}

/// One number, `keyword = value`, or `default`.
pub(crate) fn number(
    statement: &Statement,
    keyword: &str,
    default: f64,
) -> Result<f64, ConfigurationError> {
    numbers(statement, keyword, [default]).map(|[value]| value)
}

/// A PART's or MARKER's axes: `REULER` (body-fixed 3-1-3), or the points
/// `ZG`/`ZP` on its z axis and `XG`/`XP` in its xz plane (with its origin
/// `QG`/`QP`, in the same axes). With a z point alone, x is the part's x
/// axis made square to z (its y axis where z lies along x); with an x point
/// alone, z is the part's.
/// A PART's or POINT_MASS's place (QG), axes (REULER, or ZG and XG) and
/// velocity (VX, VY, VZ) into `body`.
fn place(body: &mut Body, statement: &Statement) -> Result<(), ConfigurationError> {
    body.position = Vector3::from(numbers(statement, "QG", [0.0; 3])?);
    body.orientation = orientation(statement)?;
    body.velocity = Vector3::new(
        number(statement, "VX", 0.0)?,
        number(statement, "VY", 0.0)?,
        number(statement, "VZ", 0.0)?,
    );
    Ok(())
}

/// The VARIABLE ids a statement's `VARIABLES = ...` lists (an ARRAY of
/// type U, a PINPUT, a POUTPUT), whole positive numbers only.
fn listed_variables(statement: &Statement) -> Option<Vec<u64>> {
    let argument = statement.argument("VARIABLES", 3)?;
    let Value::List(items) = &argument.value else {
        return None;
    };
    Some(
        items
            .iter()
            .filter_map(|item| item.number())
            .filter(|id| id.fract() == 0.0 && *id > 0.0)
            .map(|id| id as u64)
            .collect(),
    )
}

fn orientation(statement: &Statement) -> Result<UnitQuaternion<f64>, ConfigurationError> {
    let (origin, z_point, x_point) = if is_statement(statement, "PART") {
        ("QG", "ZG", "XG")
    } else {
        ("QP", "ZP", "XP")
    };
    let given = |keyword: &str| statement.argument(keyword, keyword.len()).is_some();
    if !given(z_point) && !given(x_point) {
        let [psi, theta, phi] = numbers(statement, "REULER", [0.0; 3])?;
        return Ok(euler_313(psi, theta, phi));
    }
    let wrong = |reason: String| ConfigurationError::Axes {
        statement: statement.label(),
        reason,
        span: statement.span,
    };
    if given("REULER") {
        return Err(wrong(format!(
            "give its axes by REULER or by {z_point} and {x_point}, not both"
        )));
    }
    let at = Vector3::from(numbers(statement, origin, [0.0; 3])?);
    let z = if given(z_point) {
        let toward = Vector3::from(numbers(statement, z_point, [0.0; 3])?) - at;
        toward
            .try_normalize(1e-12 * toward.amax().max(at.amax()).max(1.0))
            .ok_or_else(|| {
                wrong(format!(
                    "{z_point} is the origin {origin}: it must lie on the z axis, away from it"
                ))
            })?
    } else {
        Vector3::z()
    };
    let toward_x = if given(x_point) {
        Vector3::from(numbers(statement, x_point, [0.0; 3])?) - at
    } else if z.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let x = (toward_x - z * z.dot(&toward_x))
        .try_normalize(1e-9 * toward_x.norm().max(f64::MIN_POSITIVE))
        .ok_or_else(|| {
            wrong(format!(
                "{x_point} lies on the z axis: it must give the xz plane, off the axis"
            ))
        })?;
    let axes = nalgebra::Matrix3::from_columns(&[x, z.cross(&x), z]);
    Ok(UnitQuaternion::from_rotation_matrix(
        &nalgebra::Rotation3::from_matrix_unchecked(axes),
    ))
}

/// The scene of a dataset's initial configuration, from the statements of
/// `dataset` and the expressions `report` checked.
pub fn initial_scene(
    dataset: &super::Dataset,
    report: &ModelCheck,
) -> Result<Scene, Vec<ConfigurationError>> {
    let mut scene = Scene {
        kind: SceneKind::Model,
        ..Scene::default()
    };
    let mut errors = Vec::new();
    let mut ground_parts = HashSet::new();
    // PART id -> (body index, CM marker id, VM marker id, WM marker id).
    let mut parts = std::collections::HashMap::new();
    for statement in dataset
        .statements
        .iter()
        .filter(|s| is_statement(s, "PART"))
    {
        let Some(id) = statement.id else { continue };
        if statement.argument("GROUND", 3).is_some() {
            ground_parts.insert(id);
            continue;
        }
        let mut body = Body::new(statement.label());
        let read = (|| {
            place(&mut body, statement)?;
            body.angular_velocity = Vector3::new(
                number(statement, "WX", 0.0)?,
                number(statement, "WY", 0.0)?,
                number(statement, "WZ", 0.0)?,
            );
            let cm = number(statement, "CM", 0.0)?;
            let markers = [
                cm,
                number(statement, "VM", cm)?,
                number(statement, "WM", cm)?,
            ];
            number(statement, "MASS", 0.0)?;
            Ok(markers)
        })();
        // A part whose data has an error still exists for its markers (no
        // second error at each of them).
        let [cm, vm, wm] = read.unwrap_or_else(|error| {
            errors.push(error);
            [0.0; 3]
        });
        parts.insert(id, (scene.bodies.len(), cm as u64, vm as u64, wm as u64));
        scene.bodies.push(body);
    }
    // Point masses follow the parts (the simulator's masses keep that
    // order): bodies that translate only, their axes fixed as placed.
    let mut point_masses = std::collections::HashMap::new();
    for statement in dataset
        .statements
        .iter()
        .filter(|s| is_statement(s, "POINT_MASS"))
    {
        let Some(id) = statement.id else { continue };
        let mut body = Body::new(statement.label());
        if let Err(error) =
            place(&mut body, statement).and_then(|()| number(statement, "MASS", 0.0).map(drop))
        {
            errors.push(error);
        }
        point_masses.insert(id, scene.bodies.len());
        scene.bodies.push(body);
    }
    for statement in dataset
        .statements
        .iter()
        .filter(|s| is_statement(s, "MARKER"))
    {
        let Some(id) = statement.id else { continue };
        if statement.argument("FLOATING", 3).is_some() {
            continue;
        }
        let on_point_mass = statement.argument("POINT_MASS", 10).is_some();
        let keyword = if on_point_mass { "POINT_MASS" } else { "PART" };
        let part = match number(statement, keyword, 0.0) {
            Ok(part) => part as u64,
            Err(error) => {
                errors.push(error);
                continue;
            }
        };
        // `Some(None)`: on ground; `None`: on nothing defined.
        let found = if on_point_mass {
            point_masses.get(&part).map(|&index| Some(index))
        } else if ground_parts.contains(&part) {
            Some(None)
        } else {
            parts.get(&part).map(|&(index, ..)| Some(index))
        };
        let Some(body) = found else {
            errors.push(ConfigurationError::UnknownPart {
                statement: statement.label(),
                kind: keyword,
                part,
                span: statement.span,
            });
            continue;
        };
        let mut marker = Marker::new(body);
        marker.id = Some(id);
        match (numbers(statement, "QP", [0.0; 3]), orientation(statement)) {
            (Ok(position), Ok(rotation)) => {
                marker.position = Vector3::from(position);
                marker.orientation = rotation;
                scene.markers.push(marker);
            }
            (Err(error), _) | (_, Err(error)) => errors.push(error),
        }
    }
    scene.index();
    // A part's VX, VY, VZ are the velocity of its VM marker's origin (its
    // CM marker's when VM is left out) along ground's axes, and WX, WY, WZ
    // its angular velocity about its WM marker's axes (the CM marker's):
    // carry them to the part's origin. A VM or WM on another part is
    // refused by the simulator; the CM marker stands in for it here.
    for &(index, cm, vm, wm) in parts.values() {
        let on_part = |id: u64| scene.marker_on(id, index);
        let (Some(at), Some(about)) = (
            on_part(vm).or_else(|| on_part(cm)),
            on_part(wm).or_else(|| on_part(cm)),
        ) else {
            continue;
        };
        let (arm, axes) = (at.position, about.orientation);
        let body = &mut scene.bodies[index];
        body.angular_velocity = body.orientation * axes * body.angular_velocity;
        let arm = body.orientation * arm;
        body.velocity -= body.angular_velocity.cross(&arm);
    }
    for found in &report.expressions {
        let statement = &dataset.statements[found.statement];
        if is_statement(statement, "VARIABLE")
            && "FUNCTION".starts_with(found.keyword.as_str())
            && let (Some(id), Some(checked)) = (statement.id, &found.checked)
        {
            scene.statements.variables.insert(id, checked.clone());
        }
    }
    for statement in dataset
        .statements
        .iter()
        .filter(|s| is_statement(s, "ARRAY"))
    {
        if let (Some(id), Some(argument)) = (statement.id, statement.argument("NUMBERS", 2))
            && let Value::List(items) = &argument.value
        {
            let values: Vec<f64> = items.iter().filter_map(|item| item.number()).collect();
            scene.statements.arrays.insert(id, values);
        }
        if let (Some(id), Some(variables)) = (statement.id, listed_variables(statement))
            && statement.argument("U", 1).is_some()
        {
            scene.statements.input_arrays.insert(id, variables);
        }
    }
    for statement in &dataset.statements {
        let lists = if is_statement(statement, "PINPUT") {
            &mut scene.statements.plant_inputs
        } else if is_statement(statement, "POUTPUT") {
            &mut scene.statements.plant_outputs
        } else {
            continue;
        };
        if let (Some(id), Some(variables)) = (statement.id, listed_variables(statement)) {
            lists.insert(id, variables);
        }
    }
    for (index, statement) in dataset
        .statements
        .iter()
        .enumerate()
        .filter(|(_, s)| is_statement(s, "DIFF"))
    {
        if let Some(id) = statement.id {
            let [initial, initial_rate] = match statement.argument("IC", 2) {
                Some(argument) => match number_list(statement, argument) {
                    Ok(values) => [values[0], values.get(1).copied().unwrap_or(0.0)],
                    Err(error) => {
                        errors.push(error);
                        continue;
                    }
                },
                None => [0.0; 2],
            };
            let function = report
                .expressions
                .iter()
                .find(|found| {
                    found.statement == index && "FUNCTION".starts_with(found.keyword.as_str())
                })
                .and_then(|found| found.checked.clone());
            scene.statements.diffs.insert(
                id,
                DiffData {
                    initial,
                    function,
                    implicit: statement.argument("IMPLICIT", 3).is_some(),
                    initial_rate,
                },
            );
        }
    }
    for statement in dataset
        .statements
        .iter()
        .filter(|s| is_statement(s, "SENSOR"))
    {
        if let Some(id) = statement.id
            && statement.argument("EVALUATE", 4).is_some()
        {
            scene.statements.evaluated_sensors.insert(id);
        }
    }
    let (systems, problems) = super::linear_systems::linear_systems(dataset);
    scene.statements.linear_systems = systems;
    errors.extend(problems);
    for statement in dataset
        .statements
        .iter()
        .filter(|s| is_statement(s, "SPLINE"))
    {
        let Some(id) = statement.id else { continue };
        match spline_data(statement) {
            Ok(Some(data)) => {
                scene.statements.splines.insert(id, data);
            }
            Ok(None) => {}
            Err(error) => errors.push(error),
        }
    }
    if errors.is_empty() {
        Ok(scene)
    } else {
        Err(errors)
    }
}
