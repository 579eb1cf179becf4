//! `UNITS`: the units a dataset's numbers are in, and the units
//! consistency factor (Adams' UCF) that Newton's and Euler's laws carry
//! when they are not a consistent set.
//!
//! With force, mass, length and time units worth `f` N, `m` kg, `l` m and
//! `t` s, `F = m a` in the dataset's units reads `F = UCF m a` with
//! `UCF = m l / (f t²)`: one pound force on one pound mass gives 386.09
//! inch/s². Every other number (stiffness, gravity, a FUNCTION's value) is
//! in the dataset's units already, so the simulator multiplies each mass
//! and inertia by UCF and changes nothing else.

use crate::model::{Dataset, Statement, is_kind};
use crate::simulate::error::SimulateError;

/// Units of force, in newton.
const FORCES: [(&str, f64); 9] = [
    ("NEWTON", 1.0),
    ("KNEWTON", 1e3),
    ("MILLINEWTON", 1e-3),
    ("CENTINEWTON", 1e-2),
    ("DYNE", 1e-5),
    ("POUND_FORCE", 4.448_221_615_260_5),
    ("KPOUND_FORCE", 4_448.221_615_260_5),
    ("KILOGRAM_FORCE", 9.806_65),
    ("OUNCE_FORCE", 0.278_013_850_953_781_2),
];

/// Units of mass, in kilogram.
const MASSES: [(&str, f64); 7] = [
    ("KILOGRAM", 1.0),
    ("GRAM", 1e-3),
    ("MEGAGRAM", 1e3),
    ("POUND_MASS", 0.453_592_37),
    ("KPOUND_MASS", 453.592_37),
    ("SLUG", 14.593_902_937_206_364),
    ("OUNCE_MASS", 0.028_349_523_125),
];

/// Units of length, in metre.
const LENGTHS: [(&str, f64); 7] = [
    ("METER", 1.0),
    ("MILLIMETER", 1e-3),
    ("CENTIMETER", 1e-2),
    ("KILOMETER", 1e3),
    ("INCH", 0.0254),
    ("FOOT", 0.3048),
    ("MILE", 1_609.344),
];

/// Units of time, in second.
const TIMES: [(&str, f64); 4] = [
    ("SECOND", 1.0),
    ("MILLISECOND", 1e-3),
    ("MINUTE", 60.0),
    ("HOUR", 3_600.0),
];

/// The units consistency factor of `dataset`'s `UNITS` statement (1 when
/// it has none, or its units are consistent), with a note saying which
/// units make it when it is not 1.
pub(super) fn consistency_factor(
    dataset: &Dataset,
) -> Result<(f64, Option<String>), SimulateError> {
    let mut statements = dataset
        .statements
        .iter()
        .filter(|statement| is_kind(&statement.name, "UNITS"));
    let Some(statement) = statements.next() else {
        return Ok((1.0, None));
    };
    if let Some(again) = statements.next() {
        return Err(SimulateError::Model {
            message: "UNITS given again: a model has one system of units (give it in one UNITS statement)".to_string(),
            span: again.span,
        });
    }
    if let Some(argument) = statement.argument("UCF", 3) {
        let factor = crate::model::initial::number(statement, "UCF", f64::NAN)
            .ok()
            .filter(|factor| *factor > 0.0 && factor.is_finite())
            .ok_or_else(|| SimulateError::Model {
                message: "UNITS: UCF must be a positive number".to_string(),
                span: argument.span,
            })?;
        return Ok((
            factor,
            Some(format!(
                "UNITS: the units consistency factor is UCF = {factor}"
            )),
        ));
    }
    if let Some(argument) = statement.argument("SYSTEM", 3) {
        let system = word(statement, "SYSTEM").unwrap_or_default();
        if !["MKS", "CGS", "NONE"].contains(&system.as_str()) {
            return Err(SimulateError::Model {
                message: format!(
                    "UNITS: SYSTEM = {system} is not read by mbexpr (MKS and CGS are): give FORCE, MASS, LENGTH and TIME instead"
                ),
                span: argument.span,
            });
        }
        return Ok((1.0, None));
    }
    let force = unit(statement, "FORCE", &FORCES)?;
    let mass = unit(statement, "MASS", &MASSES)?;
    let length = unit(statement, "LENGTH", &LENGTHS)?;
    let time = unit(statement, "TIME", &TIMES)?;
    let factor = mass * length / (force * time * time);
    if (factor - 1.0).abs() <= 1e-12 {
        return Ok((1.0, None));
    }
    let named =
        |keyword: &str, default: &str| word(statement, keyword).unwrap_or(default.to_string());
    Ok((
        factor,
        Some(format!(
            "UNITS: {} force, {} mass, {} length and {} time are not a consistent set: each mass and inertia carries the units consistency factor UCF = {}",
            named("FORCE", "NEWTON").to_ascii_lowercase(),
            named("MASS", "KILOGRAM").to_ascii_lowercase(),
            named("LENGTH", "METER").to_ascii_lowercase(),
            named("TIME", "SECOND").to_ascii_lowercase(),
            crate::Shown(factor)
        )),
    ))
}

/// The word given to `keyword` (`INCH`), upper-case.
fn word(statement: &Statement, keyword: &str) -> Option<String> {
    super::word_of(statement.argument(keyword, keyword.len().min(3))?)
}

/// The size of the unit given to `keyword` in SI, from `units` (the
/// first SI unit when the keyword is missing); a word may be shortened to
/// what names one unit only.
fn unit(statement: &Statement, keyword: &str, units: &[(&str, f64)]) -> Result<f64, SimulateError> {
    let Some(argument) = statement.argument(keyword, keyword.len().min(3)) else {
        return Ok(1.0);
    };
    let given = word(statement, keyword).unwrap_or_default();
    let matching: Vec<&(&str, f64)> = units
        .iter()
        .filter(|(name, _)| *name == given || (given.len() >= 3 && name.starts_with(&given)))
        .collect();
    let exact = units.iter().find(|(name, _)| *name == given);
    match (exact, matching.as_slice()) {
        (Some((_, size)), _) | (None, [(_, size)]) => Ok(*size),
        _ => Err(SimulateError::Model {
            message: format!(
                "UNITS: {keyword} = {given} is not a unit mbexpr knows: give one of {}",
                units
                    .iter()
                    .map(|(name, _)| *name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            span: argument.span,
        }),
    }
}
