//! The run a command file (`.acf`) asks for: its `SIMULATE` commands in
//! order, as one run from time 0 with equally spaced outputs.

use crate::model::initial::number;
use crate::model::vocabulary::{COMMANDS, statement_name};
use crate::model::{Dataset, Value};
use crate::shown::Shown;
use crate::span::Span;

/// The most output steps a command file may ask for (a hundred million
/// rows; DTOUT = 1e-300 would otherwise ask for a run without end).
pub const MOST_OUTPUT_STEPS: usize = 100_000_000;

/// The commands that change the model (or hand it to a user subroutine)
/// between analyses; mbexpr runs the dataset as it is, so a command file
/// that changes it before a `SIMULATE` asks for a run mbexpr does not make.
const MODEL_CHANGES: [&str; 29] = [
    "ACCGRAV",
    "ACTIVATE",
    "ARRAY",
    "BEAM",
    "BUSHING",
    "CONTROL",
    "DEACTIVATE",
    "DIFF",
    "FIELD",
    "FLEX_BODY",
    "FRICTION",
    "GCON",
    "GFORCE",
    "GSE",
    "JOINT",
    "MARKER",
    "MOTION",
    "NFORCE",
    "PART",
    "RELOAD",
    "SENSOR",
    "SFORCE",
    "SPLINE",
    "SPRINGDAMPER",
    "STRING",
    "UCON",
    "VARIABLE",
    "VFORCE",
    "VTORQUE",
];

/// `INTEGRATOR`'s settings that must be positive numbers (Adams refuses
/// others; mbexpr keeps its own error control, `--rtol` and `--hmax`).
const POSITIVE_SETTINGS: [&str; 4] = ["ERROR", "HMAX", "HMIN", "HINIT"];

/// A command file's run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunCommands {
    /// The end time.
    pub end: f64,
    /// The number of output steps.
    pub steps: usize,
    /// Whether a static equilibrium comes first (`SIMULATE/STATICS`
    /// before the dynamic commands).
    pub statics: bool,
    /// Whether Radau5 steps onto each output time
    /// (`INTEGRATOR/INTERPOLATE = OFF`; by default, and with `ON`, the rows
    /// come from the steps' continuous output).
    pub land_on_outputs: bool,
    /// The span of the last SIMULATE command.
    pub span: Span,
}

/// The end time and the number of output steps of a command file's
/// `SIMULATE/DYNAMIC` (or `TRANSIENT`, `KINEMATIC`) commands, with the span
/// of the last: `END = t` or `DURATION = d` (from the end of the command
/// before), and `STEPS = n` or `DTOUT = dt`. Several commands run on one
/// after the other, so they make one run when their outputs are equally
/// spaced; a `SIMULATE/STATICS` before them starts the run from a static
/// equilibrium. `Ok(None)` when no command gives a run; an error, with the
/// command's place, for a command mbexpr does not carry out:
/// `SIMULATE/STATICS` after a dynamic command or alone, commands whose
/// output steps differ, or a command without its end or its steps.
pub fn run_settings(commands: &Dataset) -> Result<Option<RunCommands>, (String, Span)> {
    let mut end = 0.0;
    let mut interval: Option<f64> = None;
    let mut last = None;
    let mut statics = None;
    let mut land_on_outputs = false;
    let mut changed: Option<(&str, Span)> = None;
    for statement in &commands.statements {
        let name = statement_name(&statement.name, COMMANDS);
        if name == Some("STOP") {
            // The command file ends here: Adams reads nothing after it.
            break;
        }
        if let Some(name) = name.filter(|name| MODEL_CHANGES.contains(name)) {
            changed = changed.or(Some((name, statement.span)));
            continue;
        }
        if name == Some("INTEGRATOR") {
            integrator_settings_are_positive(statement)?;
        }
        if name == Some("INTEGRATOR")
            && let Some(argument) = statement.argument("INTERPOLATE", 3)
        {
            land_on_outputs = match &argument.value {
                Value::List(items) => items
                    .first()
                    .is_some_and(|item| item.text.eq_ignore_ascii_case("OFF")),
                _ => false,
            };
        }
        if statement_name(&statement.name, COMMANDS) != Some("SIMULATE") {
            continue;
        }
        let label = "SIMULATE";
        if statement.argument("STATICS", 4).is_some() || statement.argument("STATIC", 4).is_some() {
            if last.is_some() {
                return Err((
                    format!(
                        "{label}/STATICS after a dynamic command: mbexpr computes a static equilibrium only at the start of a run (put it before the dynamic commands, or give --end and --steps)"
                    ),
                    statement.span,
                ));
            }
            statics = Some(statement.span);
            continue;
        }
        let dynamic = ["DYNAMIC", "TRANSIENT", "KINEMATIC"]
            .iter()
            .any(|kind| statement.argument(kind, 3).is_some());
        if !dynamic {
            // SIMULATE/INITIAL_CONDITIONS: mbexpr assembles the start anyway.
            continue;
        }
        if let Some((name, span)) = changed {
            return Err((
                format!(
                    "{name} changes the model before a SIMULATE command: mbexpr runs the dataset as it is written (make the change in the dataset, or run the part before it with --end and --steps)"
                ),
                span,
            ));
        }
        let given = |keyword: &str| {
            statement
                .argument(keyword, keyword.len())
                .and_then(|_| number(statement, keyword, f64::NAN).ok())
        };
        for (one, other) in [("END", "DURATION"), ("STEPS", "DTOUT")] {
            if given(one).is_some() && given(other).is_some() {
                return Err((
                    format!("{label}: give {one} or {other}, not both"),
                    statement.span,
                ));
            }
        }
        let segment_end = match (given("END"), given("DURATION")) {
            (Some(at), _) => at,
            (None, Some(duration)) => end + duration,
            (None, None) => {
                return Err((
                    format!("{label}: give END = the end time (or DURATION = how long)"),
                    statement.span,
                ));
            }
        };
        let length = segment_end - end;
        if !segment_end.is_finite() {
            return Err((
                format!(
                    "{label}: the command ends past the largest double (END = {}, from {}): give an earlier END or a shorter DURATION",
                    Shown(segment_end),
                    Shown(end)
                ),
                statement.span,
            ));
        }
        if !(length > 0.0 && length.is_finite()) {
            return Err((
                format!(
                    "{label}: the command must end after it starts (END = {}, from {}): give a later END or a positive DURATION",
                    Shown(segment_end),
                    Shown(end)
                ),
                statement.span,
            ));
        }
        let step = match (given("STEPS"), given("DTOUT")) {
            (Some(steps), _) if steps >= 1.0 && steps.fract() == 0.0 && length > 0.0 => {
                length / steps
            }
            (None, Some(dtout)) if dtout > 0.0 && length > 0.0 => {
                let steps = length / dtout;
                if (steps - steps.round()).abs() > 1e-9 * steps.max(1.0) {
                    return Err((
                        format!(
                            "{label}: DTOUT = {dtout} does not divide the command's {length} s into whole output steps (mbexpr writes a run's outputs equally spaced: give a DTOUT that divides it, or STEPS)"
                        ),
                        statement.span,
                    ));
                }
                dtout
            }
            _ => {
                return Err((
                    format!(
                        "{label}: give STEPS = a whole number of output steps (or DTOUT = the time between outputs), and an END after the last command's"
                    ),
                    statement.span,
                ));
            }
        };
        if let Some(before) = interval
            && (step - before).abs() > 1e-9 * before
        {
            return Err((
                format!(
                    "{label}: its outputs are {step} apart, the commands' before it {before}: mbexpr writes one run's outputs equally spaced (give the commands one output step, or --end and --steps)"
                ),
                statement.span,
            ));
        }
        interval = Some(step);
        end = segment_end;
        last = Some(statement.span);
    }
    let (Some(step), Some(span)) = (interval, last) else {
        if let Some(span) = statics {
            return Err((
                "SIMULATE/STATICS alone: mbexpr computes a static equilibrium as the start of a dynamic run (add a SIMULATE/DYNAMIC command after it, or give --end, --steps and --statics)".to_string(),
                span,
            ));
        }
        return Ok(None);
    };
    let steps = (end / step).round();
    if steps > MOST_OUTPUT_STEPS as f64 {
        return Err((
            format!(
                "SIMULATE: {steps:.3e} output steps to END = {} (at most {MOST_OUTPUT_STEPS}: give fewer STEPS or a larger DTOUT)",
                Shown(end)
            ),
            span,
        ));
    }
    Ok(Some(RunCommands {
        end,
        steps: steps as usize,
        statics: statics.is_some(),
        land_on_outputs,
        span,
    }))
}

/// An error, at the setting, for an `INTEGRATOR` setting of
/// [`POSITIVE_SETTINGS`] that is not a positive number.
fn integrator_settings_are_positive(
    statement: &crate::model::Statement,
) -> Result<(), (String, Span)> {
    for keyword in POSITIVE_SETTINGS {
        let Some(argument) = statement.argument(keyword, keyword.len()) else {
            continue;
        };
        let value = number(statement, keyword, f64::NAN).unwrap_or(f64::NAN);
        if !(value > 0.0 && value.is_finite()) {
            return Err((
                format!("INTEGRATOR: {keyword} must be a positive number"),
                argument.span,
            ));
        }
    }
    Ok(())
}
