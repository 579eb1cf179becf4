//! Scenes: the world a kinematic measure is evaluated in — ground, rigid
//! bodies with their states, markers fixed on them, the time, the mode, user
//! variables and named expressions.
//!
//! A scene is read from TOML ([`Scene::from_toml`], format in
//! `examples/scenes/README.md`) or built in code. Compiling an expression
//! against a scene ([`crate::compile::compile_in_scene`]) keeps only the
//! markers and bodies it uses; their state components become inputs named
//! `BODY.x` ... `BODY.wz` that can be derivative directions.

mod file;

pub use file::euler_313;

use std::collections::HashMap;

use nalgebra::{UnitQuaternion, Vector3};
use thiserror::Error;

use crate::catalog::{SystemVariable, closest, did_you_mean};
use crate::check::{Checked, Reference};
use crate::laws::spline::SplineData;
use crate::span::Span;

/// A rigid body and its state at the scene's time.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// The body's name (state inputs are `NAME.x` ...).
    pub name: String,
    /// Position of the body frame's origin in ground.
    pub position: Vector3<f64>,
    /// Orientation of the body frame relative to ground.
    pub orientation: UnitQuaternion<f64>,
    /// Velocity of the origin, in ground.
    pub velocity: Vector3<f64>,
    /// Angular velocity, in ground.
    pub angular_velocity: Vector3<f64>,
    /// Acceleration of the origin, in ground, when known.
    pub acceleration: Option<Vector3<f64>>,
    /// Angular acceleration, in ground, when known.
    pub angular_acceleration: Option<Vector3<f64>>,
}

impl Body {
    /// A body named `name` at rest at the origin, aligned with ground.
    pub fn new(name: impl Into<String>) -> Body {
        Body {
            name: name.into(),
            position: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
            velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
            acceleration: None,
            angular_acceleration: None,
        }
    }
}

/// A coordinate frame fixed on a body (or on ground).
#[derive(Clone, Debug, PartialEq)]
pub struct Marker {
    /// The marker's id, when it has one.
    pub id: Option<u64>,
    /// The marker's name, when it has one.
    pub name: Option<String>,
    /// Index of the body it is fixed on in [`Scene::bodies`]; `None` for ground.
    pub body: Option<usize>,
    /// Position of the marker's origin in the body frame.
    pub position: Vector3<f64>,
    /// Orientation of the marker relative to the body frame.
    pub orientation: UnitQuaternion<f64>,
}

impl Marker {
    /// A marker at the origin of `body` (`None`: ground), aligned with it.
    pub fn new(body: Option<usize>) -> Marker {
        Marker {
            id: None,
            name: None,
            body,
            position: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
        }
    }

    /// The marker's name, or its id as text.
    pub fn label(&self) -> String {
        match (&self.name, self.id) {
            (Some(name), _) => name.clone(),
            (None, Some(id)) => id.to_string(),
            (None, None) => "(unnamed)".to_string(),
        }
    }
}

/// The components of a body's state that can be derivative directions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StateComponent {
    /// Position along ground x, y, z (index 0 to 2).
    Position(usize),
    /// A small rotation about ground x, y, z at the current orientation.
    Rotation(usize),
    /// Velocity along ground x, y, z.
    Velocity(usize),
    /// Angular velocity about ground x, y, z.
    AngularVelocity(usize),
}

impl StateComponent {
    /// All twelve, in input order: x y z rx ry rz vx vy vz wx wy wz.
    pub const ALL: [StateComponent; 12] = [
        StateComponent::Position(0),
        StateComponent::Position(1),
        StateComponent::Position(2),
        StateComponent::Rotation(0),
        StateComponent::Rotation(1),
        StateComponent::Rotation(2),
        StateComponent::Velocity(0),
        StateComponent::Velocity(1),
        StateComponent::Velocity(2),
        StateComponent::AngularVelocity(0),
        StateComponent::AngularVelocity(1),
        StateComponent::AngularVelocity(2),
    ];

    /// `x`, `rx`, `vx`, `wx` ...
    pub fn suffix(self) -> String {
        let (prefix, axis) = match self {
            StateComponent::Position(axis) => ("", axis),
            StateComponent::Rotation(axis) => ("r", axis),
            StateComponent::Velocity(axis) => ("v", axis),
            StateComponent::AngularVelocity(axis) => ("w", axis),
        };
        format!("{prefix}{}", ["x", "y", "z"][axis])
    }

    /// The component named by `suffix` (case-insensitive).
    pub fn parse(suffix: &str) -> Option<StateComponent> {
        StateComponent::ALL
            .into_iter()
            .find(|component| component.suffix().eq_ignore_ascii_case(suffix))
    }
}

/// What a scene cannot provide.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SceneError {
    /// A marker reference that matches no marker.
    #[error("there is no marker {reference} in {place}{suggestions}")]
    UnknownMarker {
        /// "the scene" or "the model".
        place: &'static str,
        /// The reference as written.
        reference: String,
        /// " (did you mean ...?)" or nothing.
        suggestions: String,
    },
    /// A name that is neither a variable, a system variable nor a state component.
    #[error("{place} has no value for {name}{suggestions}")]
    UnknownName {
        /// "the scene" or "the model".
        place: &'static str,
        /// The name.
        name: String,
        /// " (did you mean ...?)" or nothing.
        suggestions: String,
    },
    /// A scene file that cannot be read or understood.
    #[error("{message}")]
    File {
        /// What is wrong, and what to write instead.
        message: String,
        /// Where in the file (`None`: the file as a whole).
        span: Option<Span>,
    },
}

impl SceneError {
    /// The place in the scene file of an error in reading it.
    pub fn file_span(&self) -> Option<Span> {
        match self {
            SceneError::File { span, .. } => *span,
            _ => None,
        }
    }
}

/// Ground, bodies, markers, time, mode, variables and named expressions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// The current time.
    pub time: f64,
    /// The analysis mode; 4 (dynamics) when not given.
    pub mode: Option<f64>,
    /// User variables and their values.
    pub variables: Vec<(String, f64)>,
    /// Named expressions, in the order given.
    pub expressions: Vec<(String, String)>,
    /// Where the text of each named expression starts in the scene file
    /// ([`Scene::expression_start`]).
    pub expression_starts: HashMap<String, usize>,
    /// The rigid bodies (ground is implicit).
    pub bodies: Vec<Body>,
    /// The markers.
    pub markers: Vec<Marker>,
    /// Whether it was read from a scene file or made from a model, for messages.
    pub kind: SceneKind,
    /// Marker ids and body names to their indices, built by
    /// [`Scene::index`] for scenes as large as a model; a marker or body
    /// added after that is still found, by a search.
    pub lookup: Lookup,
    /// The data of a model's statements that expressions read: VARIABLE
    /// functions (for `VARVAL`), ARRAY values (for `ARYVAL`) and SPLINE
    /// points (for `AKISPL` and `CUBSPL`).
    pub statements: StatementData,
}

/// The indices of markers by id and bodies by name (upper case), which
/// [`Scene::index`] builds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Lookup {
    markers: HashMap<u64, usize>,
    bodies: HashMap<String, usize>,
}

/// Where a scene comes from, as its messages name it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SceneKind {
    /// A scene file or one built in code: "the scene".
    #[default]
    Scene,
    /// The initial configuration of a model file: "the model".
    Model,
}

impl SceneKind {
    /// "the scene" or "the model".
    pub fn noun(self) -> &'static str {
        match self {
            SceneKind::Scene => "the scene",
            SceneKind::Model => "the model",
        }
    }
}

/// What a model's data statements give expressions evaluated in its scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StatementData {
    /// VARIABLE id to its checked FUNCTION: `VARVAL(id)` is that expression,
    /// evaluated in the same scene (so derivatives flow through it).
    pub variables: HashMap<u64, Checked>,
    /// ARRAY id to its NUMBERS: `ARYVAL(id, i)` is entry `i` (from 1).
    pub arrays: HashMap<u64, Vec<f64>>,
    /// ARRAY id (of type U, a system's inputs) to its VARIABLES:
    /// `ARYVAL(id, i)` is `VARVAL` of the `i`-th.
    pub input_arrays: HashMap<u64, Vec<u64>>,
    /// PINPUT id to its VARIABLES: `PINVAL(id, i)` is `VARVAL` of the
    /// `i`-th (a plant's inputs, which a controller outside sets in a
    /// co-simulation and their own FUNCTIONs give here).
    pub plant_inputs: HashMap<u64, Vec<u64>>,
    /// POUTPUT id to its VARIABLES: `POUVAL(id, i)` is `VARVAL` of the
    /// `i`-th.
    pub plant_outputs: HashMap<u64, Vec<u64>>,
    /// FRICTION id to the hidden VARIABLEs (ids past the model's) of its
    /// outputs: `FRICTION(id, i)` is `VARVAL` of the `i`-th (a simulation
    /// writes them; elsewhere FRICTION has no value).
    pub friction_outputs: HashMap<u64, Vec<u64>>,
    /// SPLINE id to its points: `AKISPL(x, z, id)` and `CUBSPL(x, z, id)`
    /// interpolate them.
    pub splines: HashMap<u64, SplineData>,
    /// DIFF id to its differential state: `DIF(id)` is an input named
    /// [`diff_input`]`(id)` (the initial condition outside a simulation),
    /// `DIF1(id)` the DIFF's FUNCTION, evaluated in place.
    pub diffs: HashMap<u64, DiffData>,
    /// The ids of the SENSORs with an EVALUATE expression: `SENVAL(id)` is
    /// an input named [`sensor_input`]`(id)`, the value that expression
    /// had at the sensor's last trip (0 before the first, and outside a
    /// simulation).
    pub evaluated_sensors: std::collections::HashSet<u64>,
    /// The linear systems of the TFSISO and LSE statements.
    pub linear_systems: Vec<LinearSystem>,
}

impl StatementData {
    /// The linear system whose X array is `array`.
    pub fn system_with_states(&self, array: u64) -> Option<&LinearSystem> {
        self.linear_systems
            .iter()
            .find(|system| system.states == array)
    }

    /// The linear system whose Y array is `array`.
    pub fn system_with_outputs(&self, array: u64) -> Option<&LinearSystem> {
        self.linear_systems
            .iter()
            .find(|system| system.outputs == Some(array))
    }
}

/// A control element's linear system (TFSISO, LSE): `x' = A x + B u`,
/// `y = C x + D u`, its states `ARYVAL(states, k)` (inputs named
/// [`array_state_input`]), its inputs the VARIABLEs of its U array, its
/// outputs `ARYVAL(outputs, k)`, each an expression compiled in place.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearSystem {
    /// `TFSISO/3`.
    pub statement: String,
    /// The statement in the file.
    pub span: crate::Span,
    /// The X array of its states.
    pub states: u64,
    /// The U array of its inputs.
    pub inputs: Option<u64>,
    /// The Y array of its outputs.
    pub outputs: Option<u64>,
    /// The states' initial values.
    pub initial: Vec<f64>,
    /// Each state's rate, `A x + B u` in `ARYVAL`s of its arrays, as text
    /// and checked.
    pub rates: Vec<(String, Checked)>,
    /// Each output, `C x + D u`, as text and checked.
    pub output_expressions: Vec<(String, Checked)>,
    /// `STATIC_HOLD`: a static equilibrium keeps its states as they are.
    pub static_hold: bool,
}

/// A differential state `DIFF/id` (explicit form: `d DIF(id)/dt = FUNCTION`).
#[derive(Clone, Debug, PartialEq)]
pub struct DiffData {
    /// The initial condition `IC` (0 when not given).
    pub initial: f64,
    /// The checked FUNCTION: the state's time derivative (`None` when it
    /// does not check, or is a user subroutine's); of an implicit DIFF, the
    /// residual whose zero defines the derivative.
    pub function: Option<Checked>,
    /// `IMPLICIT`: FUNCTION = 0 defines the state's time derivative, which
    /// `DIF1(id)` then reads as the input [`diff_rate_input`] (the solver's
    /// root of the FUNCTION), not as the FUNCTION compiled in place.
    pub implicit: bool,
    /// The second value of `IC`, the time derivative to start from (0 when
    /// not given): the value of `DIF1(id)` of an implicit DIFF outside a
    /// run.
    pub initial_rate: f64,
}

/// The name of the input that holds `DIF(id)`: `DIF(3)`.
pub fn diff_input(id: u64) -> String {
    format!("DIF({id})")
}

/// The name of the input that holds `DIF1(id)` of an implicit DIFF:
/// `DIF1(3)`.
pub fn diff_rate_input(id: u64) -> String {
    format!("DIF1({id})")
}

/// The id of an implicit DIFF's rate input named by [`diff_rate_input`].
pub fn parse_diff_rate_input(name: &str) -> Option<u64> {
    let inner = name.strip_prefix("DIF1(")?.strip_suffix(')')?;
    inner.parse().ok()
}

/// The name of the input that holds state `entry` (from 1) of the linear
/// system whose X array is `array`: `ARYVAL(4, 2)`.
pub fn array_state_input(array: u64, entry: usize) -> String {
    format!("ARYVAL({array}, {entry})")
}

/// The X array and entry of an [`array_state_input`] name (in any case,
/// with any blanks: `aryval(4,2)`).
pub fn parse_array_state_input(name: &str) -> Option<(u64, usize)> {
    let name = name.trim();
    let head = name.get(..7)?;
    if !head.eq_ignore_ascii_case("ARYVAL(") {
        return None;
    }
    let inner = name[7..].strip_suffix(')')?;
    let (array, entry) = inner.split_once(',')?;
    Some((array.trim().parse().ok()?, entry.trim().parse().ok()?))
}

/// Whether `name` is the input of a state of the run that is no part's:
/// a DIFF's (`DIF(3)`) or a linear system's (`ARYVAL(4, 2)`).
pub fn is_run_state_input(name: &str) -> bool {
    parse_diff_input(name).is_some() || parse_array_state_input(name).is_some()
}

/// The name of the input that holds `SENVAL(id)`: `SENVAL(3)`.
pub fn sensor_input(id: u64) -> String {
    format!("SENVAL({id})")
}

/// The SENSOR id of an input named `SENVAL(3)` (as [`sensor_input`]
/// writes it).
pub fn parse_sensor_input(name: &str) -> Option<u64> {
    name.strip_prefix("SENVAL(")?
        .strip_suffix(')')?
        .parse()
        .ok()
}

/// The DIFF id of an input named `DIF(3)` (as [`diff_input`] writes it).
pub fn parse_diff_input(name: &str) -> Option<u64> {
    let inner = name.strip_prefix("DIF(")?.strip_suffix(')')?;
    inner.parse().ok()
}

/// Where a marker reference leads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Target {
    /// The ground frame itself (`0`).
    Ground,
    /// The marker at this index of [`Scene::markers`].
    Marker(usize),
}

impl Scene {
    /// The body marker `target` is on (`None`: ground, or a marker on it).
    pub fn body_of(&self, target: &Target) -> Option<usize> {
        match target {
            Target::Ground => None,
            Target::Marker(index) => self.markers[*index].body,
        }
    }

    /// The marker of id `id` when it is fixed on body `body`.
    pub fn marker_on(&self, id: u64, body: usize) -> Option<&Marker> {
        match self.find_marker(&Reference::Id(id)) {
            Ok(Target::Marker(index)) if self.markers[index].body == Some(body) => {
                Some(&self.markers[index])
            }
            _ => None,
        }
    }

    /// The marker `reference` names: `0` is ground, other ids and names
    /// (case-insensitive) are looked up among the markers.
    pub fn find_marker(&self, reference: &Reference) -> Result<Target, SceneError> {
        let found = match reference {
            Reference::Id(0) => return Ok(Target::Ground),
            Reference::Id(id) => self
                .lookup
                .markers
                .get(id)
                .copied()
                .filter(|&index| self.markers.get(index).is_some_and(|m| m.id == Some(*id)))
                .or_else(|| {
                    self.markers
                        .iter()
                        .position(|marker| marker.id == Some(*id))
                }),
            Reference::Name(name) => self.markers.iter().position(|marker| {
                marker
                    .name
                    .as_deref()
                    .is_some_and(|marker_name| marker_name.eq_ignore_ascii_case(name))
            }),
        };
        found.map(Target::Marker).ok_or_else(|| {
            let labels: Vec<String> = self.markers.iter().map(Marker::label).collect();
            let suggestions = did_you_mean(&closest(
                &reference.to_string(),
                labels.iter().map(String::as_str),
            ));
            SceneError::UnknownMarker {
                place: self.kind.noun(),
                reference: reference.to_string(),
                suggestions,
            }
        })
    }

    /// Where the origin of `target` is in ground, with its body where the
    /// scene places it.
    pub fn origin(&self, target: Target) -> Vector3<f64> {
        match target {
            Target::Ground => Vector3::zeros(),
            Target::Marker(index) => {
                let marker = &self.markers[index];
                match marker.body.map(|body| &self.bodies[body]) {
                    Some(body) => body.position + body.orientation * marker.position,
                    None => marker.position,
                }
            }
        }
    }

    /// The index of the body named `name` (case-insensitive).
    pub fn find_body(&self, name: &str) -> Option<usize> {
        self.lookup
            .bodies
            .get(&name.to_ascii_uppercase())
            .copied()
            .filter(|&index| {
                self.bodies
                    .get(index)
                    .is_some_and(|body| body.name.eq_ignore_ascii_case(name))
            })
            .or_else(|| {
                self.bodies
                    .iter()
                    .position(|body| body.name.eq_ignore_ascii_case(name))
            })
    }

    /// Indexes the markers by id and the bodies by name, so that finding
    /// one costs the same in a scene of 100 000 as in one of two.
    pub fn index(&mut self) {
        self.lookup.markers = self
            .markers
            .iter()
            .enumerate()
            .filter_map(|(index, marker)| Some((marker.id?, index)))
            .collect();
        self.lookup.bodies = self
            .bodies
            .iter()
            .enumerate()
            .map(|(index, body)| (body.name.to_ascii_uppercase(), index))
            .collect();
    }

    /// The input name of a body's state component: `ball.vx`.
    pub fn state_name(&self, body: usize, component: StateComponent) -> String {
        format!("{}.{}", self.bodies[body].name, component.suffix())
    }

    /// The body and component an input name such as `ball.vx` stands for.
    pub fn parse_state_name(&self, name: &str) -> Option<(usize, StateComponent)> {
        let (body, suffix) = name.rsplit_once('.')?;
        Some((self.find_body(body)?, StateComponent::parse(suffix)?))
    }

    /// The value the scene gives the input `name`: `TIME`, `MODE`, a user
    /// variable, or a state component (`ball.x`; rotations are 0, since they
    /// are perturbations of the current orientation).
    pub fn value_of(&self, name: &str) -> Result<f64, SceneError> {
        match SystemVariable::lookup(name) {
            Some(SystemVariable::Time) => return Ok(self.time),
            Some(SystemVariable::Mode) => {
                return Ok(self.mode.unwrap_or(SystemVariable::DEFAULT_MODE));
            }
            None => {}
        }
        if let Some((_, value)) = self
            .variables
            .iter()
            .find(|(variable, _)| variable.eq_ignore_ascii_case(name))
        {
            return Ok(*value);
        }
        if let Some(diff) = parse_diff_input(name).and_then(|id| self.statements.diffs.get(&id)) {
            return Ok(diff.initial);
        }
        if let Some(diff) = parse_diff_rate_input(name)
            .and_then(|id| self.statements.diffs.get(&id))
            .filter(|diff| diff.implicit)
        {
            return Ok(diff.initial_rate);
        }
        if let Some(initial) = parse_array_state_input(name).and_then(|(array, entry)| {
            let system = self.statements.system_with_states(array)?;
            system.initial.get(entry.checked_sub(1)?).copied()
        }) {
            return Ok(initial);
        }
        if parse_sensor_input(name)
            .is_some_and(|id| self.statements.evaluated_sensors.contains(&id))
        {
            return Ok(0.0);
        }
        if let Some((index, component)) = self.parse_state_name(name) {
            let body = &self.bodies[index];
            return Ok(match component {
                StateComponent::Position(axis) => body.position[axis],
                StateComponent::Rotation(_) => 0.0,
                StateComponent::Velocity(axis) => body.velocity[axis],
                StateComponent::AngularVelocity(axis) => body.angular_velocity[axis],
            });
        }
        let mut known: Vec<String> = self
            .variables
            .iter()
            .map(|(name, _)| name.clone())
            .collect();
        known.extend(["TIME".to_string(), "MODE".to_string()]);
        for index in 0..self.bodies.len() {
            known.extend(StateComponent::ALL.map(|component| self.state_name(index, component)));
        }
        Err(SceneError::UnknownName {
            place: self.kind.noun(),
            name: name.to_string(),
            suggestions: did_you_mean(&closest(name, known.iter().map(String::as_str))),
        })
    }

    /// The values of `names` (a program's inputs), each by [`Scene::value_of`].
    pub fn values(&self, names: &[String]) -> Result<Vec<f64>, SceneError> {
        names.iter().map(|name| self.value_of(name)).collect()
    }

    /// The names a program over this scene may bind without further input:
    /// `TIME`, `MODE` and the user variables.
    pub fn input_names(&self) -> Vec<String> {
        let mut names = vec!["TIME".to_string(), "MODE".to_string()];
        names.extend(self.variables.iter().map(|(name, _)| name.clone()));
        names
    }
}
