//! View's library springs: `ude create instance` of `.MDI.Forces.spring`
//! or `.MDI.Forces.torsion_spring`, their values set by `variable modify`
//! on the instance's variables, written as the SFORCE and VARIABLEs View
//! exports for them.
//!
//! A user's export (alino93/HandspringRobot, Adams View 2014) has each
//! translational spring as
//! `SFORCE/n, TRANSLATIONAL, I = i, J = j, FUNCTION = - k*(dm(i,j)-L0) - c*vr(i,j) + preload`,
//! `L0` the markers' distance where the model is drawn (`free_length_mode
//! = Design_Length`), with VARIABLEs `DM(i,j) - L0` (deformation),
//! `VR(i,j)` (its velocity) and the force along the line; a torsion spring
//! with no stiffness as `+ 0 - c*wz(i,j,j) + preload` about J's z, with
//! VARIABLEs `AZ(i,j)`, `WZ(i,j,j)` and `sforce(n, 0, 8, j)`. The torsion
//! spring's stiffness term is written as the translational one's, with
//! `AZ(i,j)` and the design angle, by analogy (no export with it was
//! seen). Spline stiffness and damping, and free lengths and angles other
//! than the design ones, are refused.

use super::super::units;
use super::{Entity, Frame, Reader, key};
use crate::model::{Embedded, GENERAL_MOTION_COMPONENTS, Statement};
use crate::span::Span;

/// The library springs mbexpr writes as SFORCEs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum LibrarySpring {
    /// `.MDI.Forces.spring`: along the line between its markers.
    Translational,
    /// `.MDI.Forces.torsion_spring`: about J's z axis.
    Torsion,
}

impl LibrarySpring {
    /// The spring a library definition's name (keyed) stands for.
    pub(super) fn of_definition(definition: &str) -> Option<LibrarySpring> {
        match definition {
            "MDI.FORCES.SPRING" => Some(LibrarySpring::Translational),
            "MDI.FORCES.TORSION_SPRING" => Some(LibrarySpring::Torsion),
            _ => None,
        }
    }
}

/// A spring instance as the solver writes it: its SFORCE (without its id
/// and function) and the VARIABLEs View makes of it (name, function).
pub(super) struct WrittenSpring {
    /// The SFORCE's I and J marker ids.
    pub(super) markers: [u64; 2],
    /// The terms of its function.
    pub(super) function: String,
    /// Its VARIABLEs: the name View gives each, and its function (the
    /// SFORCE's id left as `{id}`).
    pub(super) variables: Vec<(String, String)>,
}

impl Reader<'_> {
    /// The solver form of the library spring `instance` (its full key
    /// name), or the reason it cannot be written, at the place to show.
    pub(super) fn library_spring(
        &self,
        instance: &str,
        spring: LibrarySpring,
    ) -> Result<WrittenSpring, (String, Option<usize>)> {
        let markers = [
            self.spring_marker(instance, "I_MARKER")?,
            self.spring_marker(instance, "J_MARKER")?,
        ];
        let ids = [markers[0].0, markers[1].0];
        let [i, j] = ids;
        let (frame_i, frame_j) = (markers[0].1, markers[1].1);
        let torsion = spring == LibrarySpring::Torsion;
        let (free_mode, design) = if torsion {
            let angle = frame_i
                .axes
                .column(0)
                .dot(&frame_j.axes.column(1))
                .atan2(frame_i.axes.column(0).dot(&frame_j.axes.column(0)));
            ("FREE_ANGLE_MODE", angle)
        } else {
            let distance = (frame_i.origin - frame_j.origin).norm();
            ("FREE_LENGTH_MODE", distance)
        };
        let free = match self.spring_word(instance, free_mode)?.as_str() {
            "DESIGN_LENGTH" | "DESIGN_ANGLE" => design,
            other => {
                let free = if torsion { "angle" } else { "length" };
                return Err((
                    format!(
                        "sets {} to {other}, a free {free} other than the design one, which mbexpr does not read (no export of it was seen): draw the spring at its free {free}",
                        free_mode.to_ascii_lowercase(),
                    ),
                    self.spring_command(instance, free_mode),
                ));
            }
        };
        let per = if torsion {
            [1, 1, -1, 0]
        } else {
            [1, -1, 0, 0]
        };
        let stiffness = self.spring_term(instance, "STIFFNESS", per)?;
        let damping =
            self.spring_term(instance, "DAMPING", [per[0], per[1], per[2], per[3] + 1])?;
        let preload = self.spring_quantity(
            instance,
            "PRELOAD",
            if torsion { [1, 1, 0, 0] } else { [1, 0, 0, 0] },
        )?;
        if ![Some(free), stiffness, damping, Some(preload)]
            .iter()
            .flatten()
            .all(|value| value.is_finite())
        {
            return Err((
                "has values that reach the doubles' limit (about 1e308) where it is drawn or in its coefficients: give smaller values".into(),
                None,
            ));
        }
        let (measure, rate) = if torsion {
            (format!("AZ({i},{j})"), format!("WZ({i},{j},{j})"))
        } else {
            (format!("DM({i},{j})"), format!("VR({i},{j})"))
        };
        let deformation = if free == 0.0 {
            measure.clone()
        } else {
            format!("{measure} - {free:?}")
        };
        let mut function = String::new();
        match stiffness {
            Some(k) => function.push_str(&format!(" - {k:?}*({deformation})")),
            None => function.push_str(" + 0"),
        }
        if let Some(c) = damping {
            function.push_str(&format!(" - {c:?}*{rate}"));
        }
        function.push_str(&format!(" + {preload:?}"));
        let load = if torsion {
            ("torque", format!("SFORCE({{id}}, 0, 8, {j})"))
        } else {
            let along = ["X", "Y", "Z"]
                .map(|axis| format!("D{axis}({i},{j})*F{axis}({i},{j})"))
                .join(" + ");
            ("force", format!("({along})/DM({i},{j})"))
        };
        Ok(WrittenSpring {
            markers: ids,
            function,
            variables: vec![
                (format!("{instance}.DEFORMATION"), deformation),
                (format!("{instance}.DEFORMATION_VELOCITY"), rate),
                (
                    format!("{instance}.{}", load.0.to_ascii_uppercase()),
                    load.1,
                ),
            ],
        })
    }

    /// The command that sets the instance's variable `parameter` last.
    fn spring_command(&self, instance: &str, parameter: &str) -> Option<usize> {
        self.instance_variables
            .get(&format!("{instance}.{parameter}"))
            .copied()
    }

    /// The command that sets the instance's variable `parameter` last, or
    /// that it is missing (at the instance's command).
    fn spring_variable(
        &self,
        instance: &str,
        parameter: &str,
    ) -> Result<usize, (String, Option<usize>)> {
        self.spring_command(instance, parameter).ok_or_else(|| {
            (
                format!(
                    "has no variable {} (View writes every variable of the instance)",
                    parameter.to_ascii_lowercase()
                ),
                self.user_elements
                    .iter()
                    .find(|(name, _, _)| name == instance)
                    .map(|&(_, index, _)| index),
            )
        })
    }

    /// The word a string variable of the instance holds (`linear`), keyed.
    fn spring_word(
        &self,
        instance: &str,
        parameter: &str,
    ) -> Result<String, (String, Option<usize>)> {
        let index = self.spring_variable(instance, parameter)?;
        Ok(self.word(index, "STRING_VALUE").unwrap_or_default())
    }

    /// The marker an object variable of the instance names, with its id
    /// and frame.
    fn spring_marker(
        &self,
        instance: &str,
        parameter: &str,
    ) -> Result<(u64, Frame), (String, Option<usize>)> {
        let index = self.spring_variable(instance, parameter)?;
        let name = self
            .items(index, "OBJECT_VALUE")
            .and_then(|items| items.first())
            .map(|item| key(item.text.trim_matches(['(', ')', ' '])))
            .unwrap_or_default();
        match self.find(&name) {
            Some(Entity::Marker(marker)) => Ok((
                self.markers[marker].id.unwrap_or(0),
                self.markers[marker].frame,
            )),
            _ => Err((
                format!(
                    "{}: {name} names no marker the file creates",
                    parameter.to_ascii_lowercase()
                ),
                Some(index),
            )),
        }
    }

    /// A stiffness or damping term: `None` when its mode is `none`, its
    /// coefficient in the solver's units (`per`: the powers of force,
    /// length, angle and time) when `linear`.
    fn spring_term(
        &self,
        instance: &str,
        what: &str,
        per: [i32; 4],
    ) -> Result<Option<f64>, (String, Option<usize>)> {
        let mode_name = format!("{what}_MODE");
        match self.spring_word(instance, &mode_name)?.as_str() {
            "NONE" => Ok(None),
            "LINEAR" => self
                .spring_quantity(instance, &format!("{what}_COEFFICIENT"), per)
                .map(Some),
            other => Err((
                format!(
                    "sets {} to {other}: mbexpr reads linear and none (a spline's {} is not read)",
                    mode_name.to_ascii_lowercase(),
                    what.to_ascii_lowercase()
                ),
                self.spring_command(instance, &mode_name),
            )),
        }
    }

    /// A real variable of the instance in the solver's units (radians for
    /// angles), its dimensions `powers` of force, length, angle and time:
    /// a number in the model's units, or a number with its units in
    /// brackets (`(3.0E-004(newton-meter-sec/rad))`).
    fn spring_quantity(
        &self,
        instance: &str,
        parameter: &str,
        powers: [i32; 4],
    ) -> Result<f64, (String, Option<usize>)> {
        let index = self.spring_variable(instance, parameter)?;
        let text = self
            .items(index, "REAL_VALUE")
            .and_then(|items| items.first())
            .map(|item| item.text.trim().to_string())
            .unwrap_or_default();
        let unreadable = || {
            (
                format!(
                    "{}: `{text}` is not a number mbexpr reads (a number, or a number with its units in brackets: give the number)",
                    parameter.to_ascii_lowercase()
                ),
                Some(index),
            )
        };
        let (number, factor) = match text
            .strip_prefix('(')
            .and_then(|inner| inner.strip_suffix("))"))
            .and_then(|inner| inner.split_once('('))
        {
            Some((number, unit)) => {
                let factor = self.unit_factor(unit, powers).ok_or_else(unreadable)?;
                (number.trim(), factor)
            }
            None => {
                // The model's units: only the angle differs from the solver's.
                let per_degree = if self.degrees {
                    (std::f64::consts::PI / 180.0).powi(powers[2])
                } else {
                    1.0
                };
                (text.as_str(), per_degree)
            }
        };
        match number.parse::<f64>() {
            Ok(value) if value.is_finite() => Ok(value * factor),
            _ => Err(unreadable()),
        }
    }

    /// What a value in `unit` (`newton-meter-sec/rad`: names joined by
    /// `-`, one `/` at most) is worth in the solver's units (the model's,
    /// radians for angles), when its dimensions are `powers` (force,
    /// length, angle, time); `None` for units mbexpr does not know or of
    /// other dimensions.
    fn unit_factor(&self, unit: &str, powers: [i32; 4]) -> Option<f64> {
        let (over, under) = unit.split_once('/').unwrap_or((unit, ""));
        let mut factor = 1.0;
        let mut found = [0; 4];
        for (names, sign) in [(over, 1), (under, -1)] {
            for name in names.split('-').filter(|name| !name.trim().is_empty()) {
                let name = name.trim().to_ascii_uppercase();
                let (dimension, worth) = match name.as_str() {
                    "RAD" | "RADIAN" | "RADIANS" => (2, 1.0),
                    "DEG" | "DEGREE" | "DEGREES" => (2, std::f64::consts::PI / 180.0),
                    _ => ["FORCE", "LENGTH", "TIME"]
                        .into_iter()
                        .zip([0, 1, 3])
                        .find_map(|(kind, dimension)| {
                            let unit = super::solver_unit(kind, &name)?;
                            let model = self.units.iter().find(|(k, _)| *k == kind)?.1;
                            Some((dimension, units::worth(unit)? / units::worth(model)?))
                        })?,
                };
                found[dimension] += sign;
                factor *= if sign > 0 { worth } else { 1.0 / worth };
            }
        }
        (found == powers).then_some(factor)
    }
}

/// The SFORCE statement of a written spring with its id.
pub(super) fn spring_statement(
    spring: &WrittenSpring,
    kind: LibrarySpring,
    id: u64,
    span: Span,
) -> Statement {
    use super::write::{flag_argument, function_argument, ids_argument, new_statement};
    let mut statement = new_statement("SFORCE", Some(id), span);
    let flag = match kind {
        LibrarySpring::Translational => "TRANSLATION",
        LibrarySpring::Torsion => "ROTATION",
    };
    flag_argument(&mut statement, flag, span);
    ids_argument(&mut statement, "I", spring.markers[0], span);
    ids_argument(&mut statement, "J", spring.markers[1], span);
    function_argument(
        &mut statement,
        Embedded::pinned(&spring.function, span.start),
        span,
    );
    statement
}

/// A general motion's components, in the order of
/// `GENERAL_MOTION_COMPONENTS`: the MOTION's component, and whether it
/// is a rotation.
const MOTION_COMPONENTS: [(&str, bool); 6] = [
    ("X", false),
    ("Y", false),
    ("Z", false),
    ("B1", true),
    ("B2", true),
    ("B3", true),
];

impl Reader<'_> {
    /// The MOTIONs of the general motion `instance` (its full key name),
    /// made by `command`: one between its I and J markers for each
    /// component its `*_type` drives (1 a displacement, 2 a velocity, 3 an
    /// acceleration, as the exports' functions show; 0, every other
    /// component of the exports seen, free), numbered from `ids`; or the
    /// reason it cannot be written, at the place to show.
    pub(super) fn general_motion(
        &mut self,
        instance: &str,
        command: usize,
        ids: &mut impl Iterator<Item = u64>,
    ) -> Result<Vec<Statement>, (String, Option<usize>)> {
        use super::write::{
            flag_argument, function_argument, ids_argument, new_statement, numbers_argument,
        };
        let span = self.view.statements[command].span;
        let i = self.spring_marker(instance, "I_MARKER")?.0;
        let j = self.spring_marker(instance, "J_MARKER")?.0;
        let mut motions = Vec::new();
        for (prefix, (component, rotation)) in
            GENERAL_MOTION_COMPONENTS.into_iter().zip(MOTION_COMPONENTS)
        {
            let kind_name = format!("{prefix}_TYPE");
            let index = self.spring_variable(instance, &kind_name)?;
            let kind = self
                .items(index, "INTEGER_VALUE")
                .and_then(|items| items.first())
                .and_then(|item| item.text.trim().parse::<i64>().ok());
            let derivative = match kind {
                Some(0) => continue,
                Some(1) => "DISPLACEMENT",
                Some(2) => "VELOCITY",
                Some(3) => "ACCELERATION",
                _ => {
                    return Err((
                        format!(
                            "{} is none of 0 (free), 1 (a displacement), 2 (a velocity) and 3 (an acceleration)",
                            kind_name.to_ascii_lowercase()
                        ),
                        Some(index),
                    ));
                }
            };
            let function_name = format!("{prefix}_FUNC");
            let index = self.spring_variable(instance, &function_name)?;
            let Some(item) = self
                .items(index, "STRING_VALUE")
                .and_then(|items| items.first())
                .cloned()
            else {
                return Err((
                    format!("{} gives no function", function_name.to_ascii_lowercase()),
                    Some(index),
                ));
            };
            // The item's text without its quotes, placed inside them.
            let quotes = (item.span.end - item.span.start).saturating_sub(item.text.len()) / 2;
            let mut text = Embedded::default();
            text.push(&item.text, item.span.start + quotes);
            let checked = crate::syntax::parse(&text.text)
                .map_err(|error| error.to_string())
                .and_then(|parsed| {
                    crate::check::check(&parsed).map_err(|errors| errors.to_string())
                })
                .map_err(|message| {
                    (
                        format!("{}: {message}", function_name.to_ascii_lowercase()),
                        Some(index),
                    )
                })?;
            let Some(function) = self.solver_function(&checked, &text) else {
                continue;
            };
            let id = ids.next();
            if let Some(id) = id {
                // Functions read it by its name in the instance.
                self.name(format!("{instance}.MOTION_{prefix}"), Entity::Written(id));
            }
            let mut motion = new_statement("MOTION", id, span);
            ids_argument(&mut motion, "I", i, span);
            ids_argument(&mut motion, "J", j, span);
            flag_argument(&mut motion, component, span);
            flag_argument(&mut motion, derivative, span);
            function_argument(&mut motion, function, span);
            let constants = [
                ("IC_DISP", "ICDISP", derivative != "DISPLACEMENT"),
                ("IC_VELO", "ICVEL", derivative == "ACCELERATION"),
            ];
            for (suffix, keyword, used) in constants {
                let name = format!("{prefix}_{suffix}");
                let Some(index) = self.spring_command(instance, &name) else {
                    continue;
                };
                let value = self
                    .items(index, "REAL_VALUE")
                    .and_then(|items| items.first())
                    .and_then(|item| item.number())
                    .unwrap_or(0.0);
                if !used || value == 0.0 {
                    continue;
                }
                if rotation && self.degrees {
                    return Err((
                        format!(
                            "sets {} to {value}: whether View gives a general motion's initial angle in degrees or radians in a model in degrees is not known: give 0, or drive the angle itself",
                            name.to_ascii_lowercase()
                        ),
                        Some(index),
                    ));
                }
                numbers_argument(&mut motion, keyword, &[value], span);
            }
            motions.push(motion);
        }
        Ok(motions)
    }
}
