//! Simulation: a model's DIFF equations and free rigid bodies under
//! expression forces, integrated in time with the exact Jacobian from dual
//! numbers and every branch switch of STEP, IMPACT, BISTOP ... located as an
//! event.
//!
//! A [`Model`] comes from a solver dataset ([`from_dataset`]) or a scene
//! file ([`from_scene`]). [`Simulation::new`] compiles its DIFF functions
//! and force components into one program with several outputs (and its
//! output columns into another); [`Simulation::run`] integrates it with
//! one of the methods of [`crate::integrate`]:
//!
//! - within a step, every piecewise function stays on the branch it
//!   started on, continued smoothly past its boundary
//!   ([`crate::laws::branch`]), so the right-hand side is smooth there and
//!   the Jacobian is the exact one of what is integrated;
//! - after each accepted step the switching values of every piecewise call
//!   are looked at on the step's continuous output (at points inside the
//!   step too, so a switch and its return within one step are seen); a
//!   sign change is located to about 1e-13 relative in time by regula falsi
//!   on the continuous output, the step is cut there, the branches switch
//!   and the method starts afresh;
//! - an overflow, a domain error or a NaN at a trial state rejects the trial
//!   step (the integrator tries a smaller one), not the run; many switches
//!   in a vanishing interval stop the run with an error (chattering).
//!
//! ```
//! use mbexpr::simulate::{self, Settings};
//!
//! // A ball between two walls, as a DIFF pair: x' = v, v' = BISTOP(...).
//! let text = "ball\n\
//!     DIFF/1, IC = 0, FUNCTION = DIF(2)\n\
//!     DIFF/2, IC = 5, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e5, 1.5, 50, 0.01)\n";
//! let dataset = mbexpr::model::read(text, mbexpr::model::FileKind::Adm);
//! let report = mbexpr::model::check_model(text, &dataset);
//! let model = simulate::from_dataset(&dataset, &report).map_err(|errors| errors[0].clone())?;
//! let simulation = simulate::Simulation::new(&model).map_err(|errors| errors[0].clone())?;
//! let settings = Settings { end: 1.0, steps: 10, rtol: 1e-8, atol: 1e-10, ..Settings::default() };
//! let mut last = Vec::new();
//! let summary = simulation.run(&settings, |_time, row| {
//!     last = row.to_vec();
//!     true
//! })?;
//! assert_eq!(simulate::columns(&model), ["time", "DIF(1)", "DIF(2)"]);
//! assert!(last[0].abs() <= 1.0 + 0.01); // the ball stays between the walls
//! assert!(summary.events.iter().any(|event| event.function == "BISTOP"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod constraints;
mod curve;
mod equations;
mod error;
mod initial;
mod model;
mod read;
mod run;

pub use constraints::Residuals;
pub use curve::{Curve, CurvePoint};
pub use error::{Place, SimulateError};
pub use model::{
    Along, Contact, CurvePair, Diff, ExactPart, Expression, Force, Friction, GeneralConstraint,
    Given, Joint, JointInitial, JointKind, LinearState, MarkerMotion, MassProperties, Model,
    Motion, OnCurve, Output, Shape, Solid,
};
pub use read::{
    CommandFileError, ModelFormat, RunCommands, Unread, format_of_path, from_scene, is_scene_path,
    run_settings, run_settings_beside,
};
pub use run::{
    DEFAULT_MAX_STEPS, Equations, ErrorEstimate, Event, MethodChange, SMALLEST_RTOL, SensorTrip,
    Settings, Sink, Summary,
};

use crate::compile::{Program, compile_run_outputs};

/// The model of a dataset that [`crate::model::check_model`] has checked
/// (`report`). Every statement that cannot be simulated is reported. The
/// equations of its joints that repeat others at the initial state are
/// left out of the run, each joint that loses some named in the model's
/// notes.
pub fn from_dataset(
    dataset: &crate::model::Dataset,
    report: &crate::model::ModelCheck,
) -> Result<Model, Vec<SimulateError>> {
    let mut model = read::from_dataset(dataset, report)?;
    if model.is_constrained() {
        let y = initial::initial_state(&model);
        let offsets = run::body_offsets(&model);
        constraints::leave_out_redundant(&mut model, &y, &offsets);
    }
    Ok(model)
}

/// The model of `text`: a scene file, or a solver dataset read as `kind`
/// that checks; an Adams View command file (`kind` [`FileKind::Cmd`](crate::model::FileKind::Cmd))
/// is read as the dataset it stands for, with the run of its last
/// transient simulation.
pub fn from_text(
    text: &str,
    format: ModelFormat,
    kind: crate::model::FileKind,
) -> Result<Model, Unread> {
    // The dataset's check, its problems the error when it has any.
    let checked = |dataset: &crate::model::Dataset| {
        let report = crate::model::check_model(text, dataset);
        if report.problems.is_empty() {
            Ok(report)
        } else {
            Err(Unread::Unchecked(report.problems))
        }
    };
    match format {
        ModelFormat::Scene => read::from_scene(text).map_err(Unread::Refused),
        ModelFormat::Dataset if kind == crate::model::FileKind::Cmd => {
            let view = crate::model::read(text, kind);
            let report = checked(&view)?;
            let read = read::solver_dataset(&view, &report).map_err(Unread::Refused)?;
            let report = checked(&read.dataset)?;
            let mut model = from_dataset(&read.dataset, &report).map_err(Unread::Refused)?;
            model.notes.extend(read.notes);
            if let Some(run) = read.run {
                model.run = Some((run.end, run.steps));
                model.statics = run.statics;
            }
            Ok(model)
        }
        ModelFormat::Dataset => {
            let dataset = crate::model::read(text, kind);
            let report = checked(&dataset)?;
            from_dataset(&dataset, &report).map_err(Unread::Refused)
        }
    }
}

/// The solver dataset the Adams View command file `text` is read as, as
/// text (the dataset View's File > Export > Adams Solver Dataset writes for
/// it), with what the reading noted, each at its place in `text`.
pub fn view_dataset_text(text: &str) -> Result<(String, Vec<(String, crate::span::Span)>), Unread> {
    let view = crate::model::read(text, crate::model::FileKind::Cmd);
    let report = crate::model::check_model(text, &view);
    if !report.problems.is_empty() {
        return Err(Unread::Unchecked(report.problems));
    }
    let read = read::solver_dataset(&view, &report).map_err(Unread::Refused)?;
    Ok((read.dataset.to_text(), read.notes))
}

/// A model compiled for simulation: its DIFF functions and force
/// components as one program with an output each, and its output columns
/// as another.
pub struct Simulation<'m> {
    model: &'m Model,
    dynamics: Program,
    /// The expression each output of `dynamics` computes.
    computed: Vec<usize>,
    outputs: Program,
    /// The expression each output of `outputs` computes.
    output_expressions: Vec<usize>,
}

impl<'m> Simulation<'m> {
    /// Compiles `model`'s expressions; every expression that does not
    /// compile is reported.
    pub fn new(model: &'m Model) -> Result<Simulation<'m>, Vec<SimulateError>> {
        let mut computed: Vec<usize> = model.diffs.iter().map(|diff| diff.function).collect();
        for force in &model.forces {
            let used: Vec<usize> = match force {
                Force::Translational { magnitude, .. } | Force::Rotational { magnitude, .. } => {
                    vec![*magnitude]
                }
                Force::Vector { force, torque, .. } => {
                    force.iter().chain(torque).flatten().copied().collect()
                }
                Force::Contact(_) => Vec::new(),
            };
            for expression in used {
                if !computed.contains(&expression) {
                    computed.push(expression);
                }
            }
        }
        // The output columns, then the sensors' functions, then their
        // EVALUATEs.
        let output_expressions: Vec<usize> = model
            .outputs
            .iter()
            .map(|output| output.expression)
            .chain(model.sensors.iter().map(|sensor| sensor.function))
            .chain(model.sensors.iter().filter_map(|sensor| sensor.evaluate))
            .collect();
        let mut errors = Vec::new();
        let functions: Vec<usize> = model.motion_functions().collect();
        if !functions.is_empty() && compile(model, &functions, &no_reaction, &mut errors).is_some()
        {
            let mut read: Vec<String> = constraints::Drives::states_read(model)
                .into_iter()
                .map(|name| name.split('.').next().unwrap_or_default().to_string())
                .collect();
            read.dedup();
            if !read.is_empty() {
                errors.extend(model.motion_statements().map(|(id, span)| SimulateError::Model {
                    message: format!(
                        "MOTION/{id}: a motion's FUNCTION must be a function of time only (the motions read the state of {})",
                        read.join(", ")
                    ),
                    span,
                }));
            }
        }
        let general: Vec<usize> = model
            .general_constraints
            .iter()
            .map(|constraint| constraint.function)
            .collect();
        if !general.is_empty() && compile(model, &general, &no_reaction, &mut errors).is_some() {
            errors.extend(
                constraints::GeneralConstraints::refusals(model)
                    .into_iter()
                    .map(|(id, span, reason)| SimulateError::Model {
                        message: format!("GCON/{id}: {reason}"),
                        span,
                    }),
            );
        }
        // The motions' FUNCTIONs join the forces' program too: their values
        // come from the drives, but their switches (a STEP's ends, an ABS's
        // kink) are located as the forces' are, so that no step crosses a
        // jump in a motion's velocity or acceleration.
        for &function in &functions {
            if !computed.contains(&function) {
                computed.push(function);
            }
        }
        // Forces and DIFFs may read the running solver's values: they are
        // settled with the motion at each state (`Mechanics::settle`).
        let reaction =
            |call: &crate::compile::RunCall| equations::RunValue::of(model, call).map(|_| ());
        let dynamics = compile(model, &computed, &reaction, &mut errors);
        let outputs = compile(model, &output_expressions, &reaction, &mut errors);
        if let Some(dynamics) = &dynamics {
            errors.extend(unread_implicit_rates(model, dynamics));
        }
        match (dynamics, outputs) {
            (Some(dynamics), Some(outputs)) if errors.is_empty() => Ok(Simulation {
                model,
                dynamics,
                computed,
                outputs,
                output_expressions,
            }),
            _ => Err(errors),
        }
    }

    /// The model.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    /// The program of the DIFF functions and force components (for
    /// inspection: `mbexpr simulate --program`).
    pub fn program(&self) -> &Program {
        &self.dynamics
    }
}

/// The implicit DIFFs whose rate `DIF1(id)` no FUNCTION of `dynamics`
/// reads: FUNCTION = 0 then does not define the rate but the state itself,
/// an algebraic equation, which is not simulated.
fn unread_implicit_rates<'a>(
    model: &'a Model,
    dynamics: &'a Program,
) -> impl Iterator<Item = SimulateError> + 'a {
    model
        .diffs
        .iter()
        .filter(|diff| diff.implicit.is_some())
        .filter(move |diff| {
            let name = crate::scene::diff_rate_input(diff.id);
            !dynamics.inputs().contains(&name)
        })
        .map(move |diff| {
            let expression = &model.expressions[diff.function];
            SimulateError::Model {
                message: format!(
                    "DIFF/{0} is implicit but no FUNCTION reads DIF1({0}): FUNCTION = 0 then defines the state, not its rate (an algebraic equation), which mbexpr does not simulate; write the equation with DIF1({0}), or the state as a VARIABLE",
                    diff.id
                ),
                span: expression.file_span(crate::Span::new(0, expression.text.text.len())),
            }
        })
}

/// Refuses a value of the running solver (a reaction, a force element's
/// value, a net force, an acceleration) read by a MOTION's or a GCON's
/// FUNCTION: the constraints they are must hold before the forces are
/// known.
fn no_reaction(call: &crate::compile::RunCall) -> Result<(), String> {
    Err(format!(
        "{}: a MOTION or GCON that reads a value of the running solver (a reaction, a force, an acceleration, an implicit DIFF's rate) is not simulated: its constraint must hold before the forces are known; forces, DIFFs, REQUESTs and VARIABLEs read them",
        call.input_name()
    ))
}

/// `expressions` of `model` compiled together, the reactions `reactions`
/// accepts as inputs, their errors added to `errors`.
fn compile(
    model: &Model,
    expressions: &[usize],
    reactions: crate::compile::Reactions<'_>,
    errors: &mut Vec<SimulateError>,
) -> Option<Program> {
    let trees: Vec<&crate::Checked> = expressions
        .iter()
        .map(|&expression| &model.expressions[expression].checked)
        .collect();
    let mut inputs = vec!["TIME".to_string()];
    inputs.extend(model.scene.variables.iter().map(|(name, _)| name.clone()));
    match compile_run_outputs(&trees, &inputs, &model.scene, reactions) {
        Ok(program) => Some(program),
        Err(failures) => {
            for (output, output_errors) in failures {
                let expression = expressions[output];
                let label = &model.expressions[expression].label;
                errors.extend(
                    output_errors
                        .into_iter()
                        .map(|error| SimulateError::of_expression(expression, label, error)),
                );
            }
            None
        }
    }
}

/// The names of a run's columns: `time`, `DIF(id)` for each DIFF and
/// `TFSISO/id.x1 ...` for each state of a control element, then
/// for each body `BODY.x BODY.y BODY.z` (the origin of its frame in
/// ground), `BODY.q0 ... BODY.q3` (its orientation as a unit quaternion,
/// `w x y z`), `BODY.vx BODY.vy BODY.vz` (the origin's velocity) and
/// `BODY.wx BODY.wy BODY.wz` (angular velocity, in ground), then the
/// model's outputs.
pub fn columns(model: &Model) -> Vec<String> {
    let mut names = vec!["time".to_string()];
    names.extend(model.diffs.iter().map(Diff::column));
    for body in &model.scene.bodies {
        for suffix in [
            "x", "y", "z", "q0", "q1", "q2", "q3", "vx", "vy", "vz", "wx", "wy", "wz",
        ] {
            names.push(format!("{}.{suffix}", body.name));
        }
    }
    names.extend(model.outputs.iter().map(|output| output.name.clone()));
    names
}
