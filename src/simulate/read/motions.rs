//! What a MOTION's FUNCTION gives (`DISPLACEMENT`, `VELOCITY` or
//! `ACCELERATION`) and the constants of integration `ICDISP`, `ICVEL`.

use crate::model::Statement;
use crate::model::initial::number;
use crate::simulate::error::SimulateError;
use crate::simulate::model::Given;

/// The kind of a MOTION statement's FUNCTION, with its initial
/// displacement and velocity (0 when not given, as in Adams); `None`, with
/// the error pushed, when an initial condition is not a number or is given
/// where the kind has no use for it.
pub(super) fn given(statement: &Statement, errors: &mut Vec<SimulateError>) -> Option<Given> {
    let velocity = statement.argument("VELOCITY", 1).is_some();
    let acceleration = statement.argument("ACCELERATION", 1).is_some();
    if velocity && acceleration {
        errors.push(SimulateError::Model {
            message: format!(
                "{}: a MOTION is one of DISPLACEMENT, VELOCITY or ACCELERATION, not both VELOCITY and ACCELERATION",
                statement.label()
            ),
            span: statement.span,
        });
        return None;
    }
    let uses = [
        ("ICDISP", velocity || acceleration),
        ("ICVEL", acceleration),
    ];
    let mut failed = false;
    let mut values = [0.0; 2];
    for ((keyword, used), value) in uses.into_iter().zip(&mut values) {
        let Some(argument) = statement.argument(keyword, keyword.len()) else {
            continue;
        };
        if !used {
            errors.push(SimulateError::Model {
                message: format!(
                    "{}: {keyword} is the constant of integration of {} motion, and this one gives its {}",
                    statement.label(),
                    if keyword == "ICDISP" {
                        "a VELOCITY or ACCELERATION"
                    } else {
                        "an ACCELERATION"
                    },
                    if velocity { "velocity" } else { "displacement" }
                ),
                span: argument.span,
            });
            failed = true;
            continue;
        }
        match number(statement, keyword, 0.0) {
            Ok(read) if read.is_finite() => *value = read,
            _ => {
                errors.push(SimulateError::Model {
                    message: format!("{}: {keyword} must be a number", statement.label()),
                    span: argument.span,
                });
                failed = true;
            }
        }
    }
    let [icdisp, icvel] = values;
    (!failed).then_some(if acceleration {
        Given::Acceleration { icdisp, icvel }
    } else if velocity {
        Given::Velocity { icdisp }
    } else {
        Given::Displacement
    })
}
