//! A [`Model`] from a scene file: the scene itself ([`Scene::from_toml`]),
//! and the tables a simulation adds — `mass`, `inertia` and `centre` on a
//! body, `gravity`, `[[diff]]`, `[[force]]` and `[simulate]` (format in
//! `examples/scenes/README.md`). Named expressions become output columns.

use std::collections::HashMap;

use nalgebra::{Matrix3, Vector3};
use serde::Deserialize;
use toml::Spanned;

use crate::Errors;
use crate::Shown;
use crate::check::Reference;
use crate::model::Embedded;
use crate::scene::{DiffData, Scene, SceneError, Target};
use crate::simulate::error::SimulateError;
use crate::simulate::model::{Diff, Expression, Force, MassProperties, Model, Output};
use crate::span::Span;

#[derive(Deserialize)]
struct DynamicsFile {
    gravity: Option<Spanned<[f64; 3]>>,
    #[serde(default, rename = "body")]
    bodies: Vec<BodyFile>,
    #[serde(default, rename = "diff")]
    diffs: Vec<DiffFile>,
    #[serde(default, rename = "force")]
    forces: Vec<ForceFile>,
    #[serde(default)]
    expressions: HashMap<String, Spanned<String>>,
    simulate: Option<Spanned<RunFile>>,
}

#[derive(Deserialize)]
struct BodyFile {
    name: Spanned<String>,
    mass: Option<Spanned<f64>>,
    inertia: Option<Spanned<Vec<f64>>>,
    #[serde(default)]
    centre: [f64; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DiffFile {
    id: u64,
    #[serde(default)]
    ic: f64,
    function: Spanned<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ForceFile {
    name: String,
    kind: Spanned<String>,
    i: Spanned<String>,
    j: Option<Spanned<String>>,
    function: Option<Spanned<String>>,
    #[serde(default)]
    action_only: bool,
    axes: Option<Spanned<String>>,
    reaction: Option<Spanned<String>>,
    fx: Option<Spanned<String>>,
    fy: Option<Spanned<String>>,
    fz: Option<Spanned<String>>,
    tx: Option<Spanned<String>>,
    ty: Option<Spanned<String>>,
    tz: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RunFile {
    end: f64,
    steps: usize,
}

/// The model of the scene file `text`. Every problem is reported at its
/// place in the file.
pub fn from_scene(text: &str) -> Result<Model, Vec<SimulateError>> {
    let file_error = |error: toml::de::Error| {
        vec![SimulateError::Model {
            message: error.message().to_string(),
            span: error
                .span()
                .map_or_else(Span::default, |span| Span::new(span.start, span.end)),
        }]
    };
    let scene = Scene::from_toml(text);
    let file: DynamicsFile = toml::from_str(text).map_err(file_error)?;
    let scene = match scene {
        Ok(scene) => scene,
        // The scene's problems, and those of the masses, which need no
        // scene: all at once (forces and DIFFs name the scene's markers).
        Err(errors) => {
            let mut reader = Reader {
                text,
                scene: Scene::default(),
                expressions: Vec::new(),
                errors: scene_errors(errors),
            };
            reader.masses(&file.bodies);
            reader.errors.sort_by_key(|error| match error {
                SimulateError::Model { span, .. } => span.start,
                _ => 0,
            });
            return Err(reader.errors);
        }
    };
    let mut reader = Reader {
        text,
        scene,
        expressions: Vec::new(),
        errors: Vec::new(),
    };
    let masses = reader.masses(&file.bodies);
    let diffs = reader.diffs(&file.diffs);
    let forces = reader.forces(&file.forces);
    let mut notes = Vec::new();
    if reader.scene.time != 0.0 {
        notes.push((
            format!(
                "time = {} is the scene's time for eval; a simulation starts at 0",
                Shown(reader.scene.time)
            ),
            Span::default(),
        ));
    }
    let mut outputs = Vec::new();
    for (name, _) in reader.scene.expressions.clone() {
        if let Some(text) = file.expressions.get(&name)
            && let Some(expression) = reader.expression(format!("expression {name}"), text)
        {
            outputs.push(Output { name, expression });
        }
    }
    let gravity = file
        .gravity
        .map_or_else(Vector3::zeros, |gravity| Vector3::from(*gravity.get_ref()));
    let run = file
        .simulate
        .map(|run| (run.get_ref().end, run.get_ref().steps));
    if !reader.errors.is_empty() {
        return Err(reader.errors);
    }
    Ok(Model {
        joints: Vec::new(),
        motions: Vec::new(),
        marker_motions: Vec::new(),
        couplers: Vec::new(),
        general_constraints: Vec::new(),
        joint_initials: Vec::new(),
        exact: Vec::new(),
        given_velocities: Vec::new(),
        sensors: Vec::new(),
        scene: reader.scene,
        masses,
        diffs,
        forces,
        force_statements: Vec::new(),
        gravity,
        expressions: reader.expressions,
        outputs,
        notes,
        run,
        statics: false,
        land_on_outputs: false,
    })
}

/// The errors of reading a scene, as the simulation's.
fn scene_errors(errors: Errors<SceneError>) -> Vec<SimulateError> {
    errors
        .into_iter()
        .map(|error| SimulateError::Model {
            message: error.to_string(),
            span: error.file_span().unwrap_or_default(),
        })
        .collect()
}

struct Reader<'t> {
    text: &'t str,
    scene: Scene,
    expressions: Vec<Expression>,
    errors: Vec<SimulateError>,
}

fn span_of<T>(value: &Spanned<T>) -> Span {
    let span = value.span();
    Span::new(span.start, span.end)
}

impl Reader<'_> {
    fn fail(&mut self, message: String, span: Span) {
        self.errors.push(SimulateError::Model { message, span });
    }

    /// The expression written in the string `value`, checked and added to
    /// the model; its spans map back into the file.
    fn expression(&mut self, label: String, value: &Spanned<String>) -> Option<usize> {
        let span = span_of(value);
        let source = value.get_ref();
        // A plain string `"..."` or `'...'` holds the text as written, one
        // byte after its opening quote; one with escapes maps to its start.
        let written = self.text.get(span.start..span.end).unwrap_or("");
        let start = if written.len() > source.len()
            && written.get(1..=source.len()) == Some(source.as_str())
        {
            span.start + 1
        } else {
            span.start
        };
        let mut text = Embedded::default();
        text.push(source, start);
        let checked = match crate::parse(source) {
            Err(error) => {
                self.fail(format!("{label}: {error}"), text.file_span(error.span()));
                return None;
            }
            Ok(tree) => match crate::check(&tree) {
                Err(errors) => {
                    for error in errors {
                        self.fail(format!("{label}: {error}"), text.file_span(error.span()));
                    }
                    return None;
                }
                Ok(checked) => checked,
            },
        };
        self.expressions.push(Expression {
            label,
            checked,
            text,
        });
        Some(self.expressions.len() - 1)
    }

    fn marker(&mut self, owner: &str, name: &Spanned<String>) -> Option<Target> {
        let reference = Reference::Name(name.get_ref().clone());
        match self.scene.find_marker(&reference) {
            Ok(target) => Some(target),
            Err(error) => {
                self.fail(format!("{owner}: {error}"), span_of(name));
                None
            }
        }
    }

    fn masses(&mut self, bodies: &[BodyFile]) -> Vec<MassProperties> {
        bodies
            .iter()
            .map(|body| {
                let name = body.name.get_ref();
                let span = span_of(&body.name);
                let mass = match &body.mass {
                    None => {
                        self.fail(
                            format!("body {name} has no mass: give mass = ... (a positive number) to simulate it"),
                            span,
                        );
                        f64::NAN
                    }
                    Some(mass) => {
                        let value = *mass.get_ref();
                        if !(value > 0.0 && value.is_finite()) {
                            self.fail(
                                format!("body {name}: mass must be a positive number (it is {}): give mass = ... to simulate it", Shown(value)),
                                span_of(mass),
                            );
                        }
                        value
                    }
                };
                let inertia = match body.inertia.as_ref().map(|inertia| inertia.get_ref().as_slice()) {
                    Some(&[xx, yy, zz]) => Matrix3::from_diagonal(&Vector3::new(xx, yy, zz)),
                    Some(&[xx, yy, zz, xy, xz, yz]) => {
                        Matrix3::new(xx, -xy, -xz, -xy, yy, -yz, -xz, -yz, zz)
                    }
                    _ => Matrix3::zeros(),
                };
                if inertia.cholesky().is_none() {
                    let at = body.inertia.as_ref().map_or(span, span_of);
                    self.fail(
                        format!("body {name}: the inertia is singular or not positive definite: give inertia = [xx, yy, zz] (or with xy, xz, yz, products as positive integrals) about the centre of mass"),
                        at,
                    );
                }
                MassProperties {
                    mass,
                    centre: Vector3::from(body.centre),
                    inertia,
                    span,
                }
            })
            .collect()
    }

    fn diffs(&mut self, diffs: &[DiffFile]) -> Vec<Diff> {
        let mut read = Vec::new();
        for diff in diffs {
            let Some(function) = self.expression(format!("DIFF/{}", diff.id), &diff.function)
            else {
                continue;
            };
            self.scene.statements.diffs.insert(
                diff.id,
                DiffData {
                    initial: diff.ic,
                    function: Some(self.expressions[function].checked.clone()),
                    implicit: false,
                    initial_rate: 0.0,
                },
            );
            read.push(Diff {
                id: diff.id,
                initial: diff.ic,
                function,
                linear: None,
                static_hold: false,
                implicit: None,
                creep: None,
            });
        }
        read
    }

    fn forces(&mut self, forces: &[ForceFile]) -> Vec<Force> {
        let mut read = Vec::new();
        for force in forces {
            let owner = format!("force {}", force.name);
            // Every part of a force is read, so that all its problems are
            // reported at once; it is kept when all are right.
            let i = self.marker(&owner, &force.i);
            let component =
                |reader: &mut Reader<'_>, key: &str, value: &Option<Spanned<String>>| {
                    value
                        .as_ref()
                        .and_then(|value| reader.expression(format!("{owner} {key}"), value))
                };
            let kind = force.kind.get_ref().as_str();
            match kind {
                "translational" | "rotational" => {
                    let (Some(j), Some(function)) = (&force.j, &force.function) else {
                        self.fail(
                            format!("{owner}: a {kind} force needs j = \"MARKER\" and function = \"...\""),
                            span_of(&force.kind),
                        );
                        continue;
                    };
                    let j = self.marker(&owner, j);
                    let magnitude = self.expression(format!("{owner} function"), function);
                    let (Some(i), Some(j), Some(magnitude)) = (i, j, magnitude) else {
                        continue;
                    };
                    let rotational = kind == "rotational";
                    read.push(Force::single(rotational, i, j, magnitude, force.action_only));
                }
                "vector" | "torque" | "general" => {
                    let axes = match &force.axes {
                        Some(axes) => self.marker(&owner, axes),
                        None => Some(Target::Ground),
                    };
                    let reaction = match &force.reaction {
                        None => Some(None),
                        Some(name) if name.get_ref().eq_ignore_ascii_case("ground") => Some(None),
                        Some(name) => match self.scene.find_body(name.get_ref()) {
                            Some(body) => Some(Some(body)),
                            None => {
                                self.fail(
                                    format!("{owner}: there is no body {}", name.get_ref()),
                                    span_of(name),
                                );
                                None
                            }
                        },
                    };
                    let force_part = kind != "torque";
                    let torque_part = kind != "vector";
                    let pick = |wanted: bool, value: &Option<Spanned<String>>| {
                        if wanted { value.clone() } else { None }
                    };
                    let sources = [
                        ("fx", pick(force_part, &force.fx)),
                        ("fy", pick(force_part, &force.fy)),
                        ("fz", pick(force_part, &force.fz)),
                        ("tx", pick(torque_part, &force.tx)),
                        ("ty", pick(torque_part, &force.ty)),
                        ("tz", pick(torque_part, &force.tz)),
                    ];
                    let mut indices = [None; 6];
                    let mut read_all = true;
                    for (slot, (key, value)) in indices.iter_mut().zip(&sources) {
                        *slot = component(self, key, value);
                        read_all &= value.is_none() || slot.is_some();
                    }
                    let (Some(i), Some(axes), Some(reaction), true) = (i, axes, reaction, read_all)
                    else {
                        continue;
                    };
                    read.push(Force::Vector {
                        i,
                        reaction,
                        axes,
                        force: [indices[0], indices[1], indices[2]],
                        torque: [indices[3], indices[4], indices[5]],
                    });
                }
                other => self.fail(
                    format!("{owner}: kind = \"{other}\": write \"translational\", \"rotational\", \"vector\", \"torque\" or \"general\""),
                    span_of(&force.kind),
                ),
            }
        }
        read
    }
}
