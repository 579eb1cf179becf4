//! Reading a scene from TOML. The format, with a commented example, is in
//! `examples/scenes/README.md`.

use std::f64::consts::PI;

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde::Deserialize;

use super::{Body, Marker, Scene, SceneError, SceneKind};
use crate::catalog::SystemVariable;
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
    body: Option<String>,
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

/// The numbers of the table `what` of the file `text`.
fn number_table(
    text: &str,
    table: &toml::Table,
    what: &str,
) -> Result<Vec<(String, f64)>, SceneError> {
    table
        .iter()
        .map(|(name, value)| match value {
            toml::Value::Float(number) => Ok((name.clone(), *number)),
            toml::Value::Integer(number) => Ok((name.clone(), *number as f64)),
            _ => Err(entry_error(
                text,
                [what, name],
                format!("{what}.{name} must be a number"),
            )),
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

/// The first number of the file that is not finite (TOML writes `nan` and
/// `inf`), as an error at its line: no scene value may be one.
fn refuse_non_finite(text: &str) -> Result<(), SceneError> {
    use toml::de::{DeTable, DeValue};
    type Entry<'a, 'i> = (String, &'a toml::Spanned<DeValue<'i>>);
    let Ok(root) = DeTable::parse(text) else {
        // The reader proper explains a file that does not parse.
        return Ok(());
    };
    // Depth first, in file order: the first bad number is reported.
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
                    return Err(file_error(
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
    Ok(())
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

impl Scene {
    /// Reads a scene from the text of a TOML file.
    pub fn from_toml(text: &str) -> Result<Scene, SceneError> {
        let file: SceneFile = toml::from_str(text).map_err(|error| SceneError::File {
            message: error.message().trim_end().to_string(),
            span: error.span().map(Span::from),
        })?;
        refuse_non_finite(text)?;
        if let Some(mode) = &file.mode
            && let Some(message) = SystemVariable::mode_error(*mode.get_ref())
        {
            return Err(file_error(message, mode.span()));
        }
        let variables = number_table(text, &file.variables, "variables")?;
        let expressions = file
            .expressions
            .iter()
            .map(|(name, value)| match value {
                toml::Value::String(expression) => Ok((name.clone(), expression.clone())),
                _ => Err(entry_error(
                    text,
                    ["expressions", name],
                    format!("expressions.{name} must be a string holding an expression"),
                )),
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut scene = Scene {
            time: file.time,
            mode: file.mode.map(toml::Spanned::into_inner),
            variables,
            expressions,
            bodies: Vec::new(),
            markers: Vec::new(),
            kind: SceneKind::Scene,
            ..Scene::default()
        };
        for spanned in &file.bodies {
            let (body, span) = (spanned.get_ref(), spanned.span());
            if scene.find_body(&body.name).is_some() || body.name.eq_ignore_ascii_case("ground") {
                return Err(file_error(
                    format!("body {} is defined twice", body.name),
                    span,
                ));
            }
            scene.bodies.push(Body {
                name: body.name.clone(),
                position: body.position.into(),
                orientation: body
                    .orientation
                    .read(&format!("body {}", body.name), span)?,
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
                    return Err(file_error(
                        "a marker needs a name or an id".to_string(),
                        span,
                    ));
                }
            };
            if marker.id == Some(0) {
                return Err(file_error(
                    format!("{owner}: id 0 is the ground frame"),
                    span,
                ));
            }
            let body = match marker.body.as_deref() {
                None => None,
                Some(name) if name.eq_ignore_ascii_case("ground") => None,
                Some(name) => Some(scene.find_body(name).ok_or_else(|| {
                    file_error(format!("{owner}: there is no body {name}"), span.clone())
                })?),
            };
            scene.markers.push(Marker {
                id: marker.id,
                name: marker.name.clone(),
                body,
                position: marker.position.into(),
                orientation: marker.orientation.read(&owner, span.clone())?,
            });
        }
        scene.index();
        Ok(scene)
    }
}
