//! Reading a scene from TOML. The format, with a commented example, is in
//! `examples/scenes/README.md`.

use std::f64::consts::PI;

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde::Deserialize;

use std::collections::HashMap;

use super::{Body, Marker, Scene, SceneError, SceneKind};
use crate::Errors;
use crate::catalog::{SystemVariable, closest, did_you_mean};
use crate::span::Span;

use toml::Spanned;

/// A scene file error at `span` (a byte range of the file).
fn file_error(message: String, span: std::ops::Range<usize>) -> SceneError {
    SceneError::File {
        message,
        span: Some(Span::from(span)),
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default)]
    time: f64,
    mode: Option<Spanned<f64>>,
    #[serde(default)]
    variables: toml::Table,
    #[serde(default)]
    expressions: toml::Table,
    #[serde(default, rename = "body")]
    bodies: Vec<Spanned<BodyFile>>,
    #[serde(default, rename = "marker")]
    markers: Vec<Spanned<MarkerFile>>,
    /// What a simulation reads ([`crate::simulate::from_scene`]): allowed
    /// here, read there.
    #[serde(default, rename = "force")]
    _forces: Vec<toml::Value>,
    #[serde(default, rename = "diff")]
    _diffs: Vec<toml::Value>,
    #[serde(rename = "gravity")]
    _gravity: Option<toml::Value>,
    #[serde(rename = "simulate")]
    _simulate: Option<toml::Value>,
}

/// How an orientation is written: a quaternion or 3-1-3 Euler angles.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct OrientationFile {
    /// `[w, x, y, z]`, normalised on reading.
    quaternion: Option<[f64; 4]>,
    /// Body-fixed 3-1-3 angles `[psi, theta, phi]`.
    euler: Option<[f64; 3]>,
    /// `"radians"` (the default) or `"degrees"`, for `euler`.
    angles: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyFile {
    name: String,
    #[serde(default)]
    position: [f64; 3],
    #[serde(flatten)]
    orientation: OrientationFile,
    #[serde(default)]
    velocity: [f64; 3],
    #[serde(default)]
    angular_velocity: [f64; 3],
    acceleration: Option<[f64; 3]>,
    angular_acceleration: Option<[f64; 3]>,
    /// A simulation's mass properties ([`crate::simulate::from_scene`]).
    #[serde(rename = "mass")]
    _mass: Option<toml::Value>,
    #[serde(rename = "inertia")]
    _inertia: Option<toml::Value>,
    #[serde(rename = "centre")]
    _centre: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MarkerFile {
    name: Option<String>,
    id: Option<u64>,
    body: Option<Spanned<String>>,
    #[serde(default)]
    position: [f64; 3],
    #[serde(flatten)]
    orientation: OrientationFile,
}

/// The rotation of body-fixed 3-1-3 angles: `Rz(psi) Rx(theta) Rz(phi)`.
pub fn euler_313(psi: f64, theta: f64, phi: f64) -> UnitQuaternion<f64> {
    let z = Vector3::z_axis();
    let x = Vector3::x_axis();
    UnitQuaternion::from_axis_angle(&z, psi)
        * UnitQuaternion::from_axis_angle(&x, theta)
        * UnitQuaternion::from_axis_angle(&z, phi)
}

impl OrientationFile {
    /// The orientation of `owner`, whose table is at `span` in the file.
    fn read(
        &self,
        owner: &str,
        span: std::ops::Range<usize>,
    ) -> Result<UnitQuaternion<f64>, SceneError> {
        let scale = match self.angles.as_deref() {
            None | Some("radians") => 1.0,
            Some("degrees") => PI / 180.0,
            Some(other) => {
                return Err(file_error(
                    format!("{owner}: angles = \"{other}\": write \"radians\" or \"degrees\""),
                    span,
                ));
            }
        };
        match (self.quaternion, self.euler) {
            (Some(_), Some(_)) => Err(file_error(
                format!("{owner}: give either quaternion or euler, not both"),
                span,
            )),
            (Some([w, x, y, z]), None) => {
                let quaternion = Quaternion::new(w, x, y, z);
                let length = quaternion.norm();
                if length == 0.0 || !length.is_finite() {
                    return Err(file_error(
                        format!("{owner}: the quaternion must have a finite, nonzero length"),
                        span,
                    ));
                }
                Ok(UnitQuaternion::from_quaternion(quaternion))
            }
            (None, Some([psi, theta, phi])) => {
                Ok(euler_313(psi * scale, theta * scale, phi * scale))
            }
            (None, None) => Ok(UnitQuaternion::identity()),
        }
    }
}

/// The numbers of the table `what` of the file `text`; an entry that is no
/// number is an error in `errors`.
fn number_table(
    text: &str,
    table: &toml::Table,
    what: &str,
    errors: &mut Vec<SceneError>,
) -> Vec<(String, f64)> {
    table
        .iter()
        .filter_map(|(name, value)| match value {
            toml::Value::Float(number) => Some((name.clone(), *number)),
            toml::Value::Integer(number) => Some((name.clone(), *number as f64)),
            _ => {
                errors.push(entry_error(
                    text,
                    [what, name],
                    format!("{what}.{name} must be a number"),
                ));
                None
            }
        })
        .collect()
}

/// A scene file error at the value of `table.key` in `text` (the file as a
/// whole when it cannot be found).
fn entry_error(text: &str, [table, key]: [&str; 2], message: String) -> SceneError {
    let span = toml::de::DeTable::parse(text).ok().and_then(|root| {
        let table = root.get_ref().get(table)?;
        let toml::de::DeValue::Table(entries) = table.get_ref() else {
            return None;
        };
        entries.get(key).map(|value| Span::from(value.span()))
    });
    SceneError::File { message, span }
}

/// Every number of the file that is not finite (TOML writes `nan` and
/// `inf`), as an error at its place, in file order: no scene value may be
/// one.
fn refuse_non_finite(text: &str, errors: &mut Vec<SceneError>) {
    use toml::de::{DeTable, DeValue};
    type Entry<'a, 'i> = (String, &'a toml::Spanned<DeValue<'i>>);
    let Ok(root) = DeTable::parse(text) else {
        // The reader proper explains a file that does not parse.
        return;
    };
    // Depth first, in file order.
    fn entries<'a, 'i>(prefix: &str, table: &'a DeTable<'i>) -> Vec<Entry<'a, 'i>> {
        let mut entries: Vec<_> = table
            .iter()
            .map(|(key, value)| (join(prefix, key.get_ref()), value))
            .collect();
        entries.reverse();
        entries
    }
    let mut pending: Vec<Entry<'_, '_>> = entries("", root.get_ref());
    while let Some((path, value)) = pending.pop() {
        match value.get_ref() {
            DeValue::Float(float) => {
                let written = float.as_str();
                let number: f64 = written.replace('_', "").parse().unwrap_or(f64::NAN);
                if !number.is_finite() {
                    errors.push(file_error(
                        format!("{path} = {written}: every number of a scene must be finite"),
                        value.span(),
                    ));
                }
            }
            DeValue::Table(table) => pending.extend(entries(&path, table)),
            DeValue::Array(array) => pending.extend(
                array
                    .iter()
                    .enumerate()
                    .rev()
                    .map(|(index, item)| (format!("{path}[{index}]"), item)),
            ),
            _ => {}
        }
    }
}

/// Where the text of the named expression `name` starts in the file `text`
/// (one byte after the quote of a plain string; the string's start when it
/// is written another way), and the errors of its parse and check there.
fn expression_in_file(text: &str, name: &str, expression: &str) -> (usize, Vec<SceneError>) {
    let span = toml::de::DeTable::parse(text).ok().and_then(|root| {
        let table = root.get_ref().get("expressions")?;
        let toml::de::DeValue::Table(entries) = table.get_ref() else {
            return None;
        };
        entries.get(name).map(|value| value.span())
    });
    let Some(span) = span else {
        return (0, Vec::new());
    };
    let written = text.get(span.clone()).unwrap_or("");
    let start = if written.len() > expression.len()
        && written.get(1..=expression.len()) == Some(expression)
    {
        span.start + 1
    } else {
        span.start
    };
    let placed = |at: Span| {
        if start == span.start {
            Span::from(span.clone())
        } else {
            at.shifted(start)
        }
    };
    let error = |at: Span, message: String| {
        file_error(format!("expression {name}: {message}"), placed(at).range())
    };
    let errors = match crate::parse(expression) {
        Err(parse) => vec![error(parse.span(), parse.to_string())],
        Ok(tree) => match crate::check(&tree) {
            Err(checks) => checks
                .iter()
                .map(|check| error(check.span(), check.to_string()))
                .collect(),
            Ok(_) => Vec::new(),
        },
    };
    (start, errors)
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

impl Scene {
    /// Reads a scene from the text of a TOML file: every problem at its
    /// place in the file, all of them at once (a file TOML cannot read is
    /// one), named expressions parsed and checked with the rest.
    pub fn from_toml(text: &str) -> Result<Scene, Errors<SceneError>> {
        let file: SceneFile = toml::from_str(text).map_err(|error| {
            Errors(vec![SceneError::File {
                message: error.message().trim_end().to_string(),
                span: error.span().map(Span::from),
            }])
        })?;
        let mut errors = Vec::new();
        refuse_non_finite(text, &mut errors);
        if let Some(mode) = &file.mode
            && let Some(message) = SystemVariable::mode_error(*mode.get_ref())
        {
            errors.push(file_error(message, mode.span()));
        }
        let variables = number_table(text, &file.variables, "variables", &mut errors);
        let mut expressions = Vec::new();
        let mut expression_starts = HashMap::new();
        for (name, value) in &file.expressions {
            match value {
                toml::Value::String(expression) => {
                    let (start, problems) = expression_in_file(text, name, expression);
                    errors.extend(problems);
                    expression_starts.insert(name.clone(), start);
                    expressions.push((name.clone(), expression.clone()));
                }
                _ => errors.push(entry_error(
                    text,
                    ["expressions", name],
                    format!("expressions.{name} must be a string holding an expression"),
                )),
            }
        }
        let mut scene = Scene {
            time: file.time,
            mode: file.mode.map(toml::Spanned::into_inner),
            variables,
            expressions,
            expression_starts,
            bodies: Vec::new(),
            markers: Vec::new(),
            kind: SceneKind::Scene,
            ..Scene::default()
        };
        for spanned in &file.bodies {
            let (body, span) = (spanned.get_ref(), spanned.span());
            if scene.find_body(&body.name).is_some() || body.name.eq_ignore_ascii_case("ground") {
                errors.push(file_error(
                    format!("body {} is defined twice", body.name),
                    span.clone(),
                ));
            }
            let orientation = body
                .orientation
                .read(&format!("body {}", body.name), span)
                .unwrap_or_else(|error| {
                    errors.push(error);
                    UnitQuaternion::identity()
                });
            scene.bodies.push(Body {
                name: body.name.clone(),
                position: body.position.into(),
                orientation,
                velocity: body.velocity.into(),
                angular_velocity: body.angular_velocity.into(),
                acceleration: body.acceleration.map(Into::into),
                angular_acceleration: body.angular_acceleration.map(Into::into),
            });
        }
        for spanned in &file.markers {
            let (marker, span) = (spanned.get_ref(), spanned.span());
            let owner = match (&marker.name, marker.id) {
                (Some(name), _) => format!("marker {name}"),
                (None, Some(id)) => format!("marker {id}"),
                (None, None) => {
                    errors.push(file_error(
                        "a marker needs a name or an id".to_string(),
                        span,
                    ));
                    continue;
                }
            };
            if marker.id == Some(0) {
                errors.push(file_error(
                    format!("{owner}: id 0 is the ground frame"),
                    span.clone(),
                ));
            }
            let body = match &marker.body {
                None => None,
                Some(name) if name.get_ref().eq_ignore_ascii_case("ground") => None,
                Some(name) => {
                    let body = scene.find_body(name.get_ref());
                    if body.is_none() {
                        errors.push(file_error(
                            format!(
                                "{owner}: there is no body {}{}",
                                name.get_ref(),
                                body_suggestions(&scene, name.get_ref())
                            ),
                            name.span(),
                        ));
                    }
                    body
                }
            };
            let orientation = marker
                .orientation
                .read(&owner, span)
                .unwrap_or_else(|error| {
                    errors.push(error);
                    UnitQuaternion::identity()
                });
            scene.markers.push(Marker {
                id: marker.id,
                name: marker.name.clone(),
                body,
                position: marker.position.into(),
                orientation,
            });
        }
        if !errors.is_empty() {
            errors.sort_by_key(|error| error.file_span().map_or(0, |span| span.start));
            return Err(Errors(errors));
        }
        scene.index();
        Ok(scene)
    }

    /// Where the text of the named expression `name` starts in the scene
    /// file it was read from (`None`: not read from a file, or no such
    /// expression): its messages point into the file with it.
    pub fn expression_start(&self, name: &str) -> Option<usize> {
        self.expression_starts.get(name).copied()
    }
}

/// " (did you mean ...?)" among the bodies of `scene`, or nothing.
fn body_suggestions(scene: &Scene, name: &str) -> String {
    did_you_mean(&closest(
        name,
        scene.bodies.iter().map(|body| body.name.as_str()),
    ))
}
