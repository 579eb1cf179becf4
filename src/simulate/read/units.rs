//! `UNITS`: the units a dataset's numbers are in, and the units
//! consistency factor (Adams' UCF) that Newton's and Euler's laws carry
//! when they are not a consistent set.
//!
//! With force, mass, length and time units worth `f` N, `m` kg, `l` m and
//! `t` s, `F = m a` in the dataset's units reads `F UCF = m a` with
//! `UCF = f t² / (m l)`, as Adams defines it ("Force • UCF = Mass •
//! Acceleration"): one pound force on one pound mass gives 386.09 inch/s²
//! (UCF = 386.09). Every other number (stiffness, gravity, a FUNCTION's
//! value) is in the dataset's units already, so the simulator divides each
//! mass and inertia by UCF and changes nothing else.

use crate::model::{Dataset, Statement, is_kind};
use crate::simulate::error::SimulateError;

/// Units of force, in newton.
const FORCES: [(&str, f64); 13] = [
    ("NEWTON", 1.0),
    ("KNEWTON", 1e3),
    ("MEGANEWTON", 1e6),
    ("MILLINEWTON", 1e-3),
    ("CENTINEWTON", 1e-2),
    ("MICRONEWTON", 1e-6),
    ("NANONEWTON", 1e-9),
    ("DYNE", 1e-5),
    // A pound mass at a foot per second squared.
    ("POUNDAL", 0.138_254_954_376),
    ("POUND_FORCE", 4.448_221_615_260_5),
    ("KPOUND_FORCE", 4_448.221_615_260_5),
    ("KILOGRAM_FORCE", 9.806_65),
    ("OUNCE_FORCE", 0.278_013_850_953_781_2),
];

/// Units of mass, in kilogram.
const MASSES: [(&str, f64); 13] = [
    ("KILOGRAM", 1.0),
    ("GRAM", 1e-3),
    ("MILLIGRAM", 1e-6),
    ("MICROGRAM", 1e-9),
    ("NANOGRAM", 1e-12),
    ("MEGAGRAM", 1e3),
    ("TONNE", 1e3),
    ("US_TON", 907.184_74),
    // A pound force's mass at an inch per second squared.
    ("SLINCH", 175.126_835_246_476_4),
    ("POUND_MASS", 0.453_592_37),
    ("KPOUND_MASS", 453.592_37),
    ("SLUG", 14.593_902_937_206_364),
    ("OUNCE_MASS", 0.028_349_523_125),
];

/// Units of length, in metre.
const LENGTHS: [(&str, f64); 14] = [
    ("METER", 1.0),
    ("MILLIMETER", 1e-3),
    ("CENTIMETER", 1e-2),
    ("KILOMETER", 1e3),
    ("MICROMETER", 1e-6),
    ("NANOMETER", 1e-9),
    ("ANGSTROM", 1e-10),
    ("INCH", 0.0254),
    ("MICROINCH", 2.54e-8),
    // A thousandth of an inch (MotionSolve spells it MILLS).
    ("MILS", 2.54e-5),
    ("MILLS", 2.54e-5),
    ("FOOT", 0.3048),
    ("YARD", 0.9144),
    ("MILE", 1_609.344),
];

/// Units of time, in second.
const TIMES: [(&str, f64); 8] = [
    ("SECOND", 1.0),
    // Adams' pages spell it MILLISECONDS, MotionSolve's MILLISECOND.
    ("MILLISECONDS", 1e-3),
    ("MILLISECOND", 1e-3),
    ("MICROSECOND", 1e-6),
    ("NANOSECOND", 1e-9),
    ("MINUTE", 60.0),
    ("HOUR", 3_600.0),
    ("DAY", 86_400.0),
];

/// What one `unit` (a solver unit's name: `NEWTON`, `MILLIMETER` ...) is
/// worth in newton, kilogram, metre or second.
pub(super) fn worth(unit: &str) -> Option<f64> {
    FORCES
        .iter()
        .chain(&MASSES)
        .chain(&LENGTHS)
        .chain(&TIMES)
        .find(|(name, _)| *name == unit)
        .map(|&(_, worth)| worth)
}

/// The predefined systems of `UNITS/SYSTEM`: force, mass, length and time.
const SYSTEMS: [(&str, [&str; 4]); 5] = [
    ("MKS", ["NEWTON", "KILOGRAM", "METER", "SECOND"]),
    ("CGS", ["DYNE", "GRAM", "CENTIMETER", "SECOND"]),
    ("FPS", ["POUND_FORCE", "POUND_MASS", "FOOT", "SECOND"]),
    ("IPS", ["POUND_FORCE", "POUND_MASS", "INCH", "SECOND"]),
    // Written without dimensions: UCF = 1.
    ("NONE", ["NEWTON", "KILOGRAM", "METER", "SECOND"]),
];

/// The units consistency factor of `dataset`'s `UNITS` statement, in
/// Adams' sense (`F UCF = m a`; 1 when it has none, or its units are
/// consistent), with a note saying which units make it when it is not 1.
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
                "UNITS: the units consistency factor is UCF = {factor} (force x UCF = mass x acceleration)"
            )),
        ));
    }
    let (names, [force, mass, length, time]) = match statement.argument("SYSTEM", 3) {
        Some(argument) => {
            let system = word(statement, "SYSTEM").unwrap_or_default();
            let Some((_, names)) = SYSTEMS.iter().find(|(name, _)| *name == system) else {
                return Err(SimulateError::Model {
                    message: format!(
                        "UNITS: SYSTEM = {system} is not a system of units Adams defines: give one of {}, or FORCE, MASS, LENGTH and TIME",
                        SYSTEMS.map(|(name, _)| name).join(", ")
                    ),
                    span: argument.span,
                });
            };
            if system == "NONE" {
                return Ok((1.0, None));
            }
            let size = |units: &[(&str, f64)], name: &str| {
                units
                    .iter()
                    .find(|(unit, _)| *unit == name)
                    .map_or(1.0, |(_, size)| *size)
            };
            let sizes = [
                size(&FORCES, names[0]),
                size(&MASSES, names[1]),
                size(&LENGTHS, names[2]),
                size(&TIMES, names[3]),
            ];
            (names.map(str::to_string), sizes)
        }
        None => (
            [
                ("FORCE", "NEWTON"),
                ("MASS", "KILOGRAM"),
                ("LENGTH", "METER"),
                ("TIME", "SECOND"),
            ]
            .map(|(keyword, default)| word(statement, keyword).unwrap_or(default.to_string())),
            [
                unit(statement, "FORCE", &FORCES)?,
                unit(statement, "MASS", &MASSES)?,
                unit(statement, "LENGTH", &LENGTHS)?,
                unit(statement, "TIME", &TIMES)?,
            ],
        ),
    };
    let factor = force * time * time / (mass * length);
    if (factor - 1.0).abs() <= 1e-12 {
        return Ok((1.0, None));
    }
    let [force, mass, length, time] = names.map(|name| name.to_ascii_lowercase());
    Ok((
        factor,
        Some(format!(
            "UNITS: {force} force, {mass} mass, {length} length and {time} time are not a consistent set: each mass and inertia is divided by the units consistency factor UCF = {} (force x UCF = mass x acceleration)",
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
