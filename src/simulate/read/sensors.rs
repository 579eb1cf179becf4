//! A `SENSOR` statement's settings: its comparison (EQ, the default, NE,
//! GE, LE) with VALUE within ERROR, and its action (HALT, RETURN or
//! PRINT). The actions that steer Adams' integrator at the trip (CODGEN,
//! RESTART, STEPSIZE, YYDUMP: a new pivot order, a restart, a trial step,
//! a dump of the states) leave the answer as it is: they are read and
//! named in a note, the sensor watched (a sensor with no other action
//! only counts its trips). EVALUATE is read by the dataset reader (its
//! expression's value at each trip is `SENVAL`), a sensor with no other
//! action only storing it. DT redefines the time between output steps from
//! each trip on. The user subroutines' ROUTINE and EVALUATE_ROUTINE are
//! refused at their keyword.

use crate::model::Statement;
use crate::model::initial::number;
use crate::simulate::model::{Relation, SensorAction};
use crate::span::Span;

/// Adams' ERROR when a sensor gives none.
const DEFAULT_ERROR: f64 = 1e-3;

/// Why a sensor gives no settings.
pub(super) enum Unread {
    /// An action mbexpr does not carry out (`has EVALUATE: ...`), which the
    /// reader groups with the same refusal of other sensors.
    Action {
        /// Why, after the statement's label.
        reason: String,
        /// The action's keyword.
        span: Span,
    },
    /// Something missing or out of range: the message and its place.
    Setting(String, Span),
}

/// The actions that steer Adams' integrator at a trip and leave the
/// answer as it is.
const STEERING: [&str; 4] = ["CODGEN", "RESTART", "STEPSIZE", "YYDUMP"];

/// What a sensor statement sets.
pub(super) struct Settings {
    /// How its function is compared with `value`.
    pub(super) relation: Relation,
    /// What its function is compared with.
    pub(super) value: f64,
    /// The comparison's tolerance.
    pub(super) error: f64,
    /// What the run does at a trip.
    pub(super) action: SensorAction,
    /// The note on its steering actions, when it has any.
    pub(super) steering: Option<String>,
    /// Its DT: the time between output steps from a trip on.
    pub(super) output_step: Option<f64>,
}

/// A sensor's comparison, value, tolerance and action, or why it has none.
pub(super) fn settings(statement: &Statement) -> Result<Settings, Unread> {
    let label = statement.label();
    for keyword in ["EVALUATE_ROUTINE", "ROUTINE"] {
        if let Some(argument) = statement
            .arguments
            .iter()
            .find(|argument| argument.keyword.eq_ignore_ascii_case(keyword))
        {
            return Err(Unread::Action {
                reason: format!(
                    "has {keyword}, an action mbexpr does not carry out (its sensors HALT, RETURN, PRINT, EVALUATE or change the output step, DT, and read CODGEN, RESTART, STEPSIZE and YYDUMP)"
                ),
                span: argument.span,
            });
        }
    }
    let has = |keyword: &str| statement.argument(keyword, keyword.len()).is_some();
    let steers: Vec<&str> = STEERING
        .into_iter()
        .filter(|keyword| has(keyword))
        .collect();
    if ["EQ", "GE", "LE"]
        .iter()
        .filter(|keyword| has(keyword))
        .count()
        > 1
    {
        return Err(Unread::Setting(
            format!("{label}: give one comparison of EQ, GE and LE"),
            statement.span,
        ));
    }
    let relation = match (has("GE"), has("LE")) {
        (true, _) => Relation::AtLeast,
        (_, true) => Relation::AtMost,
        _ => Relation::Equal,
    };
    let action = if has("HALT") {
        SensorAction::Halt
    } else if has("RETURN") {
        SensorAction::Return
    } else if has("PRINT") {
        SensorAction::Print
    } else if !steers.is_empty() || statement.argument("EVALUATE", 4).is_some() || has("DT") {
        SensorAction::Watch
    } else {
        return Err(Unread::Setting(
            format!("{label}: give its action: HALT, RETURN, PRINT, EVALUATE or DT"),
            statement.span,
        ));
    };
    let steering = (!steers.is_empty()).then(|| {
        let named: Vec<String> = steers
            .iter()
            .map(|keyword| {
                let what = match *keyword {
                    "CODGEN" => "a new pivot order",
                    "RESTART" => "a restart",
                    "STEPSIZE" => "a trial step",
                    _ => "a dump of the states",
                };
                format!("{keyword} ({what})")
            })
            .collect();
        let (verb, rest) = if steers.len() == 1 {
            ("steers", "it is read and changes")
        } else {
            ("steer", "they are read and change")
        };
        format!(
            "{label}: {} {verb} Adams' integrator at a trip; mbexpr's error control chooses its own steps, so {rest} nothing in the answer",
            named.join(", ")
        )
    });
    let refusal = |error: crate::model::initial::ConfigurationError| {
        Unread::Setting(error.to_string(), error.span())
    };
    if statement.argument("VALUE", 2).is_none() {
        return Err(Unread::Setting(
            format!("{label}: give VALUE = what its function is compared with"),
            statement.span,
        ));
    }
    let value = number(statement, "VALUE", f64::NAN).map_err(refusal)?;
    let error = number(statement, "ERROR", DEFAULT_ERROR).map_err(refusal)?;
    if !(value.is_finite() && error.is_finite() && error >= 0.0) {
        return Err(Unread::Setting(
            format!("{label}: VALUE must be a number and ERROR a number not below 0"),
            statement.span,
        ));
    }
    let output_step = match statement.argument("DT", 2) {
        Some(argument) => match number(statement, "DT", f64::NAN).map_err(refusal)? {
            step if step.is_finite() && step > 0.0 => Some(step),
            _ => {
                return Err(Unread::Setting(
                    format!(
                        "{label}: DT, the time between output steps from a trip on, must be a number above 0"
                    ),
                    argument.span,
                ));
            }
        },
        None => None,
    };
    Ok(Settings {
        relation,
        value,
        error,
        action,
        steering,
        output_step,
    })
}
