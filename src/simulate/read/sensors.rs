//! A `SENSOR` statement's settings: its comparison (EQ, the default, NE,
//! GE, LE) with VALUE within ERROR, and its action (HALT, RETURN or
//! PRINT); the other actions (CODGEN, DT, RESTART, STEPSIZE, YYDUMP,
//! EVALUATE) are refused at their keyword.

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

/// A sensor's comparison, value, tolerance and action, or why it has none.
pub(super) fn settings(
    statement: &Statement,
) -> Result<(Relation, f64, f64, SensorAction), Unread> {
    let label = statement.label();
    for keyword in [
        "CODGEN",
        "DT",
        "RESTART",
        "STEPSIZE",
        "YYDUMP",
        "EVALUATE",
        "EVALUATE_ROUTINE",
        "ROUTINE",
    ] {
        if let Some(argument) = statement
            .arguments
            .iter()
            .find(|argument| argument.keyword.eq_ignore_ascii_case(keyword))
        {
            return Err(Unread::Action {
                reason: format!(
                    "has {keyword}, an action mbexpr does not carry out (its sensors HALT, RETURN or PRINT)"
                ),
                span: argument.span,
            });
        }
    }
    let has = |keyword: &str| statement.argument(keyword, keyword.len()).is_some();
    if ["EQ", "NE", "GE", "LE"]
        .iter()
        .filter(|keyword| has(keyword))
        .count()
        > 1
    {
        return Err(Unread::Setting(
            format!("{label}: give one comparison of EQ, NE, GE and LE"),
            statement.span,
        ));
    }
    let relation = match (has("NE"), has("GE"), has("LE")) {
        (true, _, _) => Relation::NotEqual,
        (_, true, _) => Relation::AtLeast,
        (_, _, true) => Relation::AtMost,
        _ => Relation::Equal,
    };
    let action = if has("HALT") {
        SensorAction::Halt
    } else if has("RETURN") {
        SensorAction::Return
    } else if has("PRINT") {
        SensorAction::Print
    } else {
        return Err(Unread::Setting(
            format!("{label}: give its action: HALT, RETURN or PRINT"),
            statement.span,
        ));
    };
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
    Ok((relation, value, error, action))
}
