//! A [`Model`] from a solver dataset: PART and MARKER statements give the
//! bodies (MASS, CM, IP, IM) and their initial states, DIFF the
//! differential states, SFORCE, VFORCE, VTORQUE and GFORCE the forces,
//! ACCGRAV gravity, REQUEST's `F1` ... `F8` and each VARIABLE the output
//! columns. Statements
//! that need a constraint solver, and force elements the simulator does
//! not integrate, are refused at their place.

use std::collections::HashMap;

use nalgebra::{DMatrix, Matrix3, Vector3};

use super::{frictions, linear, motions, nforce, units};
use crate::Shown;
use crate::check::Reference;
use crate::model::initial::{number, numbers};
use crate::model::{
    ConfigurationError, Dataset, Embedded, ModelCheck, Statement, Value, initial_scene, is_kind,
};
use crate::scene::{Scene, Target};
use crate::simulate::error::SimulateError;
use crate::simulate::model::{
    Along, Diff, Expression, Force, GeneralConstraint, Given, Joint, JointKind, LinearState,
    MarkerMotion, MassProperties, Model, Motion, Output, Sensor,
};
use crate::span::Span;

/// The largest ratio of two masses that joints link (see
/// `Reader::refuse_masses_apart`).
const MASS_SPREAD: f64 = 1e14;

/// Statements that need a constraint solver.
const CONSTRAINTS: [&str; 3] = ["UCON", "FLEX_BODY", "CONSTRAINT"];

/// Statements that take no part in the motion (output, graphics, units,
/// solver settings and data read by elements that are refused anyway).
const LEFT_ASIDE: [&str; 20] = [
    "ADAMS",
    "TITLE",
    "END",
    "GRAPHICS",
    "OUTPUT",
    "RESULTS",
    "UNITS",
    "MATERIAL",
    "STRING",
    "PREFERENCES",
    "EQUILIBRIUM",
    "KINEMATICS",
    "DEBUG",
    "LIST",
    "NOLIST",
    "SECTION",
    "IC",
    "MATRIX",
    "CURVE",
    "FEMDATA",
];

/// Solver settings that the simulator's own settings replace.
const SOLVER_SETTINGS: [&str; 5] = [
    "INTEGRATOR",
    "DYNAMICS",
    "SIMULATE",
    "LSOLVER",
    "ENVIRONMENT",
];

/// The force elements' statements, as the model names them.
const FORCE_ELEMENTS: [&str; 9] = [
    "SFORCE",
    "VFORCE",
    "VTORQUE",
    "GFORCE",
    "BUSHING",
    "SPRINGDAMPER",
    "BEAM",
    "FIELD",
    "NFORCE",
];

/// The statements the simulator reads besides [`FORCE_ELEMENTS`] (PINPUT
/// and POUTPUT list the VARIABLEs that `PINVAL` and `POUVAL` read).
const SIMULATED: [&str; 24] = [
    "FRICTION",
    "PART",
    "MARKER",
    "DIFF",
    "ACCGRAV",
    "VARIABLE",
    "ARRAY",
    "SPLINE",
    "REQUEST",
    "JOINT",
    "JPRIM",
    "PTCV",
    "CVCV",
    "MOTION",
    "COUPLER",
    "GEAR",
    "GCON",
    "SENSOR",
    "CONTACT",
    "PINPUT",
    "POUTPUT",
    "TFSISO",
    "LSE",
    "POINT_MASS",
];

/// The model of a dataset that [`crate::model::check_model`] has checked
/// (`report`). Every statement that cannot be simulated is reported.
pub fn from_dataset(dataset: &Dataset, report: &ModelCheck) -> Result<Model, Vec<SimulateError>> {
    let mut errors = Vec::new();
    let mut notes = Vec::new();
    for statement in &dataset.statements {
        let kind = |kinds: &[&str]| kinds.iter().any(|kind| is_kind(&statement.name, kind));
        if kind(&CONSTRAINTS) {
            errors.push(SimulateError::Constraint {
                statement: statement.label(),
                span: statement.span,
            });
        } else if kind(&SOLVER_SETTINGS) {
            notes.push((
                format!(
                    "{} is a solver setting: the simulation uses its own (--method, --rtol, --end, --steps)",
                    statement.label()
                ),
                statement.span,
            ));
        } else if !kind(&SIMULATED) && !kind(&FORCE_ELEMENTS) && !kind(&LEFT_ASIDE) {
            errors.push(SimulateError::Unsupported {
                statement: statement.label(),
                reason: why_not_simulated(&statement.name),
                span: statement.span,
            });
        }
    }
    let scene = match initial_scene(dataset, report) {
        Ok(scene) => scene,
        Err(problems) => {
            errors.extend(problems.into_iter().map(|problem| SimulateError::Model {
                message: problem.to_string(),
                span: problem.span(),
            }));
            return Err(SimulateError::grouped(errors));
        }
    };
    let mut reader = Reader {
        dataset,
        report,
        scene,
        expressions: Vec::new(),
        errors,
    };
    let units = units::consistency_factor(dataset);
    let mut model = reader.model(notes);
    reader.refuse_loose_massless_parts(&model);
    reader.refuse_masses_apart(&model);
    note_unphysical_inertias(&mut model);
    match units {
        Ok((factor, note)) => {
            for mass in &mut model.masses {
                mass.mass /= factor;
                mass.inertia /= factor;
            }
            if let Some(note) = note {
                let span = dataset
                    .statements
                    .iter()
                    .find(|statement| is_kind(&statement.name, "UNITS"))
                    .map_or(Span::new(0, 0), |statement| statement.span);
                model.notes.push((note, span));
            }
        }
        Err(error) => reader.errors.push(error),
    }
    if reader.errors.is_empty() {
        Ok(model)
    } else {
        Err(SimulateError::grouped(reader.errors))
    }
}

/// A number as the language reads it back exactly (parenthesised when
/// negative).
pub(super) fn literal(value: f64) -> String {
    if value < 0.0 {
        format!("({value:?})")
    } else {
        format!("{value:?}")
    }
}

/// `Σ coefficient·term` as expression text, the terms whose coefficient
/// is zero left out (an empty term is the constant itself); `0` when none
/// is left.
pub(super) fn linear_sum(terms: &[(f64, String)]) -> String {
    let written: Vec<String> = terms
        .iter()
        .filter(|(coefficient, _)| *coefficient != 0.0)
        .map(|(coefficient, term)| {
            if term.is_empty() {
                literal(*coefficient)
            } else {
                format!("{}*{term}", literal(*coefficient))
            }
        })
        .collect();
    if written.is_empty() {
        "0".to_string()
    } else {
        written.join(" + ")
    }
}

/// Notes each part whose principal moments break the triangle inequality
/// (the largest more than the sum of the other two): no body has them,
/// though the run goes on with them.
fn note_unphysical_inertias(model: &mut Model) {
    for (mass, body) in model.masses.iter().zip(&model.scene.bodies) {
        if mass.mass <= 0.0 {
            continue;
        }
        let mut moments: Vec<f64> = mass
            .inertia
            .symmetric_eigenvalues()
            .iter()
            .copied()
            .collect();
        moments.sort_by(f64::total_cmp);
        if let [smallest, middle, largest] = moments[..]
            && largest > (smallest + middle) * (1.0 + 1e-9)
        {
            model.notes.push((
                format!(
                    "{}: the principal moments of inertia about the centre of mass ({}, {}, {}) break the triangle inequality (the largest is more than the sum of the others), which no body's do: check IP",
                    body.name,
                    Shown(smallest),
                    Shown(middle),
                    Shown(largest)
                ),
                mass.span,
            ));
        }
    }
}

struct Reader<'d> {
    dataset: &'d Dataset,
    report: &'d ModelCheck,
    scene: Scene,
    expressions: Vec<Expression>,
    errors: Vec<SimulateError>,
}

impl Reader<'_> {
    /// Refuses parts that joints link (directly or through other parts)
    /// whose masses are more than [`MASS_SPREAD`] apart: the joints'
    /// equations weigh each part by its mass, and the light part's law is
    /// lost in the heavy one's rounding (a crank of 1e15 kg on a slider of
    /// 1 kg ran 91 000 steps to stay on its joints; at 1e16 it cannot be
    /// assembled). Free parts that only forces join (a planet and its
    /// moon) are let be.
    fn refuse_masses_apart(&mut self, model: &Model) {
        let links = model.joints.iter().filter_map(|joint| {
            let body = |target| model.scene.body_of(target);
            Some((body(&joint.i)?, body(&joint.j)?))
        });
        for group in crate::simulate::model::linked_groups(model.masses.len(), links) {
            let massive: Vec<usize> = group
                .into_iter()
                .filter(|&body| model.masses[body].mass > 0.0)
                .collect();
            let by_mass =
                |a: &&usize, b: &&usize| model.masses[**a].mass.total_cmp(&model.masses[**b].mass);
            let (Some(&light), Some(&heavy)) = (
                massive.iter().min_by(by_mass),
                massive.iter().max_by(by_mass),
            ) else {
                continue;
            };
            let (small, large) = (model.masses[light].mass, model.masses[heavy].mass);
            if large > MASS_SPREAD * small {
                let name = |body: usize| model.scene.bodies[body].name.clone();
                self.errors.push(SimulateError::Model {
                    message: format!(
                        "{}: its MASS ({}) is {} times that of {} ({}), which joints link it to: a double keeps 16 digits, so the joints' equations cannot be solved for both (the light part's motion is lost in the heavy one's rounding): hold a part that should not move with a FIXED joint, or give the masses within a factor of {MASS_SPREAD:e} of each other",
                        name(heavy),
                        Shown(large),
                        Shown(large / small),
                        name(light),
                        Shown(small),
                    ),
                    span: model.masses[heavy].span,
                });
            }
        }
    }

    /// Refuses each massless part no joint, primitive or motion holds: no
    /// force can move it.
    fn refuse_loose_massless_parts(&mut self, model: &Model) {
        let body = |target: &Target| match target {
            Target::Marker(marker) => model.scene.markers[*marker].body,
            Target::Ground => None,
        };
        let held: Vec<usize> = model
            .joints
            .iter()
            .flat_map(|joint| [body(&joint.i), body(&joint.j)])
            .chain(
                model
                    .marker_motions
                    .iter()
                    .flat_map(|motion| [body(&motion.i), body(&motion.j)]),
            )
            .flatten()
            .collect();
        for (index, mass) in model.masses.iter().enumerate() {
            // A part refused for an inertia without mass is not named twice.
            let massless = mass.is_massless() && mass.inertia == Matrix3::zeros();
            if massless && !held.contains(&index) {
                let label = self
                    .dataset
                    .statements
                    .iter()
                    .find(|statement| statement.span == mass.span)
                    .map_or_else(|| "a PART".to_string(), Statement::label);
                self.refuse(
                    format!(
                        "{label} has no MASS and no joint, primitive or motion holds it: give MASS = a positive number (a massless part moves only as the joints take it)"
                    ),
                    mass.span,
                );
            }
        }
    }

    /// Records what is wrong with the model at `span`.
    fn refuse(&mut self, message: String, span: Span) {
        self.errors.push(SimulateError::Model { message, span });
    }

    fn statements(&self, kind: &'static str) -> impl Iterator<Item = (usize, &Statement)> {
        self.dataset
            .statements
            .iter()
            .enumerate()
            .filter(move |(_, statement)| is_kind(&statement.name, kind))
    }

    fn model(&mut self, mut notes: Vec<(String, Span)>) -> Model {
        let masses = self.masses();
        let mut diffs = self.diffs();
        let floating = self.floating_markers();
        let (mut forces, mut force_statements) = self.forces(&floating);
        for contact in super::contacts::contacts(self.dataset, &self.scene, &mut self.errors) {
            force_statements.push(("CONTACT", contact.id));
            forces.push(Force::Contact(Box::new(contact)));
        }
        let mut joints = super::joints::joints(self.dataset, &self.scene, &mut self.errors);
        joints.extend(super::curves::point_curves(
            self.dataset,
            &self.scene,
            &floating,
            &mut self.errors,
        ));
        joints.extend(super::curves::curve_pairs(
            self.dataset,
            &self.scene,
            &floating,
            &mut self.errors,
        ));
        self.point_masses_turn_freely(&joints, &masses);
        self.frictions(&joints, &mut forces, &mut force_statements, &mut diffs);
        let (motions, marker_motions) = self.motions(&joints);
        let mut couplers = super::couplers::couplers(self.dataset, &joints, &mut self.errors);
        couplers.extend(super::couplers::gears(
            self.dataset,
            &joints,
            &self.scene,
            &mut self.errors,
        ));
        let general_constraints = self.general_constraints();
        let joint_initials = super::joints::initials(
            self.dataset,
            &joints,
            &motions,
            &mut notes,
            &mut self.errors,
        );
        let exact = super::exact::exact_parts(self.dataset, &self.scene, &masses, &mut self.errors);
        let given_velocities = super::exact::given_velocities(self.dataset, &self.scene);
        let gravity = self.gravity();
        let outputs = self.outputs(&mut notes);
        let sensors = self.sensors(&mut notes);
        Model {
            scene: std::mem::take(&mut self.scene),
            masses,
            diffs,
            forces,
            force_statements,
            joints,
            motions,
            marker_motions,
            couplers,
            general_constraints,
            joint_initials,
            exact,
            given_velocities,
            sensors,
            gravity,
            expressions: std::mem::take(&mut self.expressions),
            outputs,
            notes,
            run: None,
            statics: false,
            land_on_outputs: false,
        }
    }

    /// The FRICTION statements on `joints` ([`frictions`]): each a force
    /// and torque along its joint's J axes added to `forces`, and the
    /// states of its creep, one per direction of its slip, when it has
    /// stiction, to `diffs`, their inputs `DIF`s of ids past every DIFF of
    /// the dataset.
    fn frictions(
        &mut self,
        joints: &[Joint],
        forces: &mut Vec<Force>,
        force_statements: &mut Vec<(&'static str, u64)>,
        diffs: &mut Vec<Diff>,
    ) {
        let read = frictions::frictions(self.dataset, joints, &self.scene, &mut self.errors);
        let mut next_id = self
            .scene
            .statements
            .diffs
            .keys()
            .max()
            .map_or(1, |id| id + 1);
        let mut next_variable = self
            .scene
            .statements
            .variables
            .keys()
            .max()
            .map_or(1, |id| id + 1);
        'frictions: for friction in read {
            let directions = friction.creep_rates.len();
            let inputs: Vec<String> = (0..directions)
                .map(|k| crate::scene::diff_input(next_id + k as u64))
                .collect();
            let with_creep = |text: &str| {
                inputs
                    .iter()
                    .enumerate()
                    .fold(text.to_string(), |text, (k, input)| {
                        text.replace(&frictions::creep(k), input)
                    })
            };
            let first_id = next_id;
            next_id += directions as u64;
            for (k, rate) in friction.creep_rates.iter().enumerate() {
                let Some(function) =
                    self.written(friction.statement, "creep rate", &with_creep(rate))
                else {
                    continue 'frictions;
                };
                let creep_id = first_id + k as u64;
                self.scene.statements.diffs.insert(
                    creep_id,
                    crate::scene::DiffData {
                        initial: 0.0,
                        function: Some(self.expressions[function].checked.clone()),
                        implicit: false,
                        initial_rate: 0.0,
                    },
                );
                diffs.push(Diff {
                    id: creep_id,
                    initial: 0.0,
                    function,
                    linear: None,
                    static_hold: true,
                    implicit: None,
                    creep: Some((friction.id, if directions == 1 { 0 } else { k + 1 })),
                });
            }
            let mut written = [None; 6];
            for (slot, text) in friction.components.iter().enumerate() {
                let Some(text) = text else { continue };
                let what = if slot < 3 { "force" } else { "torque" };
                let Some(component) = self.written(friction.statement, what, &with_creep(text))
                else {
                    continue 'frictions;
                };
                written[slot] = Some(component);
            }
            // FRICTION(id, index): each output a hidden VARIABLE.
            let mut outputs = Vec::new();
            for text in &friction.outputs {
                let Some(checked) = self.checked(friction.statement, "output", &with_creep(text))
                else {
                    continue 'frictions;
                };
                self.scene
                    .statements
                    .variables
                    .insert(next_variable, checked);
                outputs.push(next_variable);
                next_variable += 1;
            }
            self.scene
                .statements
                .friction_outputs
                .insert(friction.id, outputs);
            let joint = &joints[friction.joint];
            forces.push(Force::Vector {
                i: joint.i,
                reaction: self.scene.body_of(&joint.j),
                axes: joint.j,
                force: [written[0], written[1], written[2]],
                torque: [written[3], written[4], written[5]],
            });
            force_statements.push(("FRICTION", friction.id));
        }
    }

    /// The GCON statements: each an I marker and a FUNCTION.
    fn general_constraints(&mut self) -> Vec<GeneralConstraint> {
        let indices: Vec<usize> = self.statements("GCON").map(|(index, _)| index).collect();
        let dataset = self.dataset;
        let mut constraints = Vec::new();
        for index in indices {
            let statement = &dataset.statements[index];
            let label = statement.label();
            // Without I (as Adams View writes a general constraint made
            // without its marker), the reaction is reported at ground's
            // origin.
            let i = if statement.argument("I", 1).is_none() {
                Some(Target::Ground)
            } else {
                self.marker(statement, "I")
            };
            let function = self.expression(index, "FUNCTION");
            let Some(written) = statement.argument("FUNCTION", 4) else {
                self.refuse(
                    format!("{label}: give FUNCTION = the expression the constraint keeps at 0"),
                    statement.span,
                );
                continue;
            };
            if let (Some(i), Some(function)) = (i, function) {
                constraints.push(GeneralConstraint {
                    id: statement.id.unwrap_or(0),
                    i,
                    function,
                    function_span: written.span,
                    span: statement.span,
                });
            }
        }
        constraints
    }

    /// The MOTION statements: those on one of `joints`, and those between
    /// markers.
    fn motions(&mut self, joints: &[Joint]) -> (Vec<Motion>, Vec<MarkerMotion>) {
        let indices: Vec<usize> = self.statements("MOTION").map(|(index, _)| index).collect();
        let dataset = self.dataset;
        let mut motions = Vec::new();
        let mut marker_motions = Vec::new();
        for index in indices {
            let statement = &dataset.statements[index];
            let label = statement.label();
            let refuse = |errors: &mut Vec<SimulateError>, reason: &str| {
                errors.push(SimulateError::Unsupported {
                    statement: label.clone(),
                    reason: reason.to_string(),
                    span: statement.span,
                });
            };
            let Some(given) = motions::given(statement, &mut self.errors) else {
                continue;
            };
            if statement.argument("I", 1).is_some() || statement.argument("J", 1).is_some() {
                marker_motions.extend(self.marker_motion(index, given));
                continue;
            }
            let id = number(statement, "JOINT", f64::NAN).unwrap_or(f64::NAN);
            let Some(joint) = joints
                .iter()
                .position(|joint| joint.id as f64 == id && joint.kind.statement() == "JOINT")
            else {
                self.refuse(
                    format!("{label}: JOINT must name a JOINT of the model"),
                    statement.place_of("JOINT", 2),
                );
                continue;
            };
            let asks_rotation = statement.argument("ROTATION", 3).is_some();
            let asks_translation = statement.argument("TRANSLATION", 3).is_some();
            let rotation = match joints[joint].kind {
                JointKind::Revolute if !asks_translation => true,
                JointKind::Translational if !asks_rotation => false,
                JointKind::Cylindrical if asks_rotation != asks_translation => asks_rotation,
                _ => {
                    refuse(
                        &mut self.errors,
                        "must turn a REVOLUTE joint (ROTATION), slide a TRANSLATIONAL one (TRANSLATION) or do either to a CYLINDRICAL one (say which)",
                    );
                    continue;
                }
            };
            let Some(function) = self.expression(index, "FUNCTION") else {
                if statement.argument("FUNCTION", 4).is_none() {
                    refuse(
                        &mut self.errors,
                        "needs FUNCTION = the displacement, a function of time",
                    );
                }
                continue;
            };
            motions.push(Motion {
                id: statement.id.unwrap_or(0),
                joint,
                rotation,
                function,
                given,
                span: statement.span,
            });
        }
        (motions, marker_motions)
    }

    /// A MOTION between its I and J markers (J ground when not given):
    /// one of X, Y, Z, B1, B2, B3, its FUNCTION the displacement.
    fn marker_motion(&mut self, index: usize, kind: Given) -> Option<MarkerMotion> {
        let dataset = self.dataset;
        let statement = &dataset.statements[index];
        let components = ["X", "Y", "Z", "B1", "B2", "B3"];
        let given: Vec<usize> = components
            .iter()
            .enumerate()
            .filter(|(_, name)| {
                statement
                    .arguments
                    .iter()
                    .any(|argument| argument.keyword.eq_ignore_ascii_case(name))
            })
            .map(|(k, _)| k)
            .collect();
        let i = self.marker(statement, "I");
        let j = match statement.argument("J", 1) {
            Some(_) => self.marker(statement, "J"),
            None => Some(Target::Ground),
        };
        if statement.argument("I", 1).is_none() {
            self.refuse(
                format!(
                    "{}: a MOTION between markers needs I = the id of a MARKER",
                    statement.label()
                ),
                statement.span,
            );
        }
        let [component] = given[..] else {
            self.refuse(
                format!(
                    "{}: a MOTION between markers sets one of {}",
                    statement.label(),
                    components.join(", ")
                ),
                statement.span,
            );
            return None;
        };
        let function = self.expression(index, "FUNCTION");
        if function.is_none() && statement.argument("FUNCTION", 4).is_none() {
            self.refuse(
                format!(
                    "{}: a MOTION needs FUNCTION = the displacement, a function of time",
                    statement.label()
                ),
                statement.span,
            );
        }
        let body = |target: Option<Target>| match target? {
            Target::Ground => Some(None),
            Target::Marker(marker) => Some(self.scene.markers[marker].body),
        };
        if let (Some(on_i), Some(on_j)) = (body(i), body(j))
            && on_i == on_j
        {
            self.refuse(
                format!(
                    "{}: its I and J markers are on one part: a MOTION moves one part against another, so give markers of two parts",
                    statement.label()
                ),
                statement.span,
            );
            return None;
        }
        Some(MarkerMotion {
            id: statement.id.unwrap_or(0),
            i: i?,
            j: j?,
            along: if component < 3 {
                Along::Axis(component)
            } else {
                Along::Angle(component - 3)
            },
            function: function?,
            given: kind,
            span: statement.span,
        })
    }

    /// The expression `keyword` of statement `index`, added to the model's
    /// expressions (its checked tree from the report).
    fn expression(&mut self, index: usize, keyword: &str) -> Option<usize> {
        let dataset = self.dataset;
        let statement = &dataset.statements[index];
        let argument = statement.argument(keyword, keyword.len().min(4))?;
        let Value::Expression { text, .. } = &argument.value else {
            self.refuse(
                format!(
                    "{}: {keyword} must be a function expression",
                    statement.label()
                ),
                argument.span,
            );
            return None;
        };
        let found = self
            .report
            .expressions
            .iter()
            .find(|found| found.statement == index && found.keyword == argument.keyword)?;
        // An expression that does not check is reported by the check.
        let checked = found.checked.clone()?;
        self.expressions.push(Expression {
            label: format!("{} {keyword}", statement.label()),
            checked,
            text: text.clone(),
        });
        Some(self.expressions.len() - 1)
    }

    fn marker(&mut self, statement: &Statement, keyword: &str) -> Option<Target> {
        let argument = statement.argument(keyword, keyword.len())?;
        let found = number(statement, keyword, f64::NAN)
            .ok()
            .filter(|id| id.fract() == 0.0 && *id >= 0.0)
            .and_then(|id| self.scene.find_marker(&Reference::Id(id as u64)).ok());
        if found.is_none() {
            let message = format!(
                "{}: {keyword} must name a MARKER of the model (a floating marker only as JFLOAT)",
                statement.label()
            );
            self.refuse(message, argument.span);
        }
        found
    }

    fn masses(&mut self) -> Vec<MassProperties> {
        let mut masses = Vec::new();
        let parts: Vec<usize> = self
            .statements("PART")
            .filter(|(_, statement)| statement.argument("GROUND", 3).is_none())
            .map(|(index, _)| index)
            .collect();
        let dataset = self.dataset;
        for index in parts {
            masses.push(self.mass(&dataset.statements[index]));
        }
        // The point masses follow the parts, as their bodies do.
        let point_masses: Vec<usize> = self
            .statements("POINT_MASS")
            .map(|(index, _)| index)
            .collect();
        for index in point_masses {
            masses.push(self.point_mass(&dataset.statements[index]));
        }
        masses
    }

    /// Refuses a joint that holds the turning of a POINT_MASS, which has
    /// no rotation: only SPHERICAL, ATPOINT, INLINE, INPLANE and PTCV hold
    /// a point mass (they hold its place alone).
    fn point_masses_turn_freely(&mut self, joints: &[Joint], masses: &[MassProperties]) {
        for joint in joints {
            let places_only = matches!(
                joint.kind,
                JointKind::Spherical
                    | JointKind::AtPoint
                    | JointKind::InLine
                    | JointKind::InPlane
                    | JointKind::PointCurve
            );
            let held = [joint.i, joint.j]
                .iter()
                .filter_map(|target| self.scene.body_of(target))
                .find(|&body| masses.get(body).is_some_and(MassProperties::is_point_mass));
            if let (false, Some(body)) = (places_only, held) {
                self.errors.push(SimulateError::Model {
                    message: format!(
                        "{}/{} holds the turning of {}, a point mass, which has no rotation: hold a point mass by its place only (SPHERICAL, or a JPRIM ATPOINT, INLINE or INPLANE), or make it a PART",
                        joint.kind.statement(),
                        joint.id,
                        self.scene.bodies[body].name
                    ),
                    span: joint.span,
                });
            }
        }
    }

    /// A POINT_MASS: a positive MASS at its CM marker (its origin when
    /// left out), no inertia. Its inverse inertia is zero, so no torque
    /// turns it: its axes stay as placed, as Adams keeps them.
    fn point_mass(&mut self, statement: &Statement) -> MassProperties {
        // A MASS that is not a number stopped the scene (`initial_scene`).
        let mass = number(statement, "MASS", f64::NAN).unwrap_or(f64::NAN);
        let wrong = match statement.argument("MASS", 2) {
            None => Some(("MASS must be a positive number".to_string(), statement.span)),
            Some(argument) => (mass <= 0.0).then(|| {
                (
                    format!("MASS must be a positive number, not {}", Shown(mass)),
                    argument.span,
                )
            }),
        };
        if let Some((problem, span)) = wrong {
            self.errors.push(SimulateError::Model {
                message: format!("{}: {problem}", statement.label()),
                span,
            });
        }
        self.markers_on_the_part(statement);
        let centre = marker_named(statement, "CM", &self.scene)
            .map_or_else(Vector3::zeros, |marker| marker.position);
        MassProperties {
            mass,
            centre,
            inertia: Matrix3::zeros(),
            span: statement.span,
        }
    }

    /// Refuses a PART's CM, IM, VM or WM (its centre of mass, the axes of
    /// its IP, the marker whose origin's velocity VX, VY, VZ give, or
    /// about whose axes WX, WY, WZ turn) that names no marker on the part.
    fn markers_on_the_part(&mut self, statement: &Statement) {
        const ROLES: [(&str, &str); 4] = [
            ("CM", "its centre of mass"),
            ("IM", "the marker whose axes IP is given in"),
            ("VM", "the point whose velocity VX, VY, VZ give"),
            ("WM", "the axes WX, WY, WZ turn about"),
        ];
        for (keyword, role) in ROLES {
            let Some(argument) = statement.argument(keyword, 2) else {
                continue;
            };
            let part = self.scene.find_body(&statement.label());
            let on_part = number(statement, keyword, f64::NAN)
                .ok()
                .filter(|id| id.fract() == 0.0 && *id >= 0.0)
                .and_then(|id| self.scene.find_marker(&Reference::Id(id as u64)).ok())
                .is_some_and(|target| match target {
                    Target::Marker(index) => {
                        part.is_some() && self.scene.markers[index].body == part
                    }
                    Target::Ground => false,
                });
            if !on_part {
                self.errors.push(SimulateError::Model {
                    message: format!(
                        "{}: {keyword} must name a MARKER on the part ({role})",
                        statement.label()
                    ),
                    span: argument.span,
                });
            }
        }
    }

    fn mass(&mut self, statement: &Statement) -> MassProperties {
        let label = statement.label();
        let fail = |errors: &mut Vec<SimulateError>, message: String| {
            errors.push(SimulateError::Model {
                message,
                span: statement.span,
            });
        };
        // No MASS, or MASS = 0: a massless part, which joints must hold.
        // A MASS that is not a number stopped the scene (`initial_scene`).
        let mass = number(statement, "MASS", 0.0).unwrap_or(f64::NAN);
        if !(mass >= 0.0 && mass.is_finite()) {
            fail(
                &mut self.errors,
                format!(
                    "{label}: MASS must be a positive number, or 0 for a massless part, not {}",
                    Shown(mass)
                ),
            );
        }
        self.markers_on_the_part(statement);
        let marker_of = |keyword: &str| marker_named(statement, keyword, &self.scene);
        let centre = marker_of("CM").map_or_else(Vector3::zeros, |marker| marker.position);
        let inertia_marker = marker_of("IM").or_else(|| marker_of("CM"));
        let [xx, yy, zz, xy, xz, yz] = match numbers(statement, "IP", [0.0; 6]) {
            Ok(values) => values,
            Err(_) => match numbers(statement, "IP", [0.0; 3]) {
                Ok([xx, yy, zz]) => [xx, yy, zz, 0.0, 0.0, 0.0],
                Err(error) => {
                    self.errors.push(SimulateError::Model {
                        message: error.to_string(),
                        span: error.span(),
                    });
                    [0.0; 6]
                }
            },
        };
        // Adams gives the products as positive integrals (Ixy = ∫xy dm).
        let in_marker = Matrix3::new(xx, -xy, -xz, -xy, yy, -yz, -xz, -yz, zz);
        let (axes, origin) = inertia_marker.map_or((Matrix3::identity(), centre), |marker| {
            (
                marker.orientation.to_rotation_matrix().into_inner(),
                marker.position,
            )
        });
        let about_origin = axes * in_marker * axes.transpose();
        // Parallel axes: from the inertia marker's origin to the centre of mass.
        let d = origin - centre;
        let shift = (Matrix3::identity() * d.dot(&d) - d * d.transpose()) * mass;
        let inertia = about_origin - shift;
        if mass == 0.0 && inertia.iter().any(|entry| *entry != 0.0) {
            fail(
                &mut self.errors,
                format!(
                    "{label} has no MASS but an inertia: give MASS = a positive number, or leave IP out for a massless part"
                ),
            );
        } else if mass > 0.0 && !positive_definite(&inertia) {
            // At IP where it is given (a View file's `ixx ...`, on its
            // mass command), the statement where it is not.
            self.errors.push(SimulateError::Model {
                message: format!(
                    "{label}: the inertia is singular or not positive definite about the centre of mass: give IP = xx, yy, zz (and products) with positive moments"
                ),
                span: statement.argument("IP", 2).map_or(statement.span, |ip| ip.span),
            });
        }
        MassProperties {
            mass,
            centre,
            inertia,
            span: statement.span,
        }
    }

    fn diffs(&mut self) -> Vec<Diff> {
        let indices: Vec<usize> = self.statements("DIFF").map(|(index, _)| index).collect();
        let mut diffs = Vec::new();
        let dataset = self.dataset;
        for index in indices {
            let statement = &dataset.statements[index];
            let Some(id) = statement.id else { continue };
            let [initial, initial_rate] = self.diff_initial_values(statement);
            let Some(function) = self.expression(index, "FUNCTION") else {
                if statement.argument("FUNCTION", 4).is_none() {
                    self.refuse(
                        format!(
                            "{}: a DIFF needs FUNCTION = its time derivative",
                            statement.label()
                        ),
                        statement.span,
                    );
                }
                continue;
            };
            diffs.push(Diff {
                id,
                initial,
                function,
                linear: None,
                static_hold: statement.argument("STATIC_HOLD", 8).is_some(),
                implicit: statement
                    .argument("IMPLICIT", 3)
                    .is_some()
                    .then_some(initial_rate),
                creep: None,
            });
        }
        diffs.extend(self.linear_states());
        diffs
    }

    /// A DIFF's `IC = value [, rate]`: its initial value and the time
    /// derivative an implicit one starts from (each 0 when not given).
    fn diff_initial_values(&mut self, statement: &Statement) -> [f64; 2] {
        let Some(argument) = statement.argument("IC", 2) else {
            return [0.0; 2];
        };
        match crate::model::initial::number_list(statement, argument) {
            Ok(values) if values.len() <= 2 => [values[0], values.get(1).copied().unwrap_or(0.0)],
            Ok(_) => {
                self.refuse(
                    format!(
                        "{}: IC takes the initial value and, for an implicit DIFF, its time derivative, not more",
                        statement.label()
                    ),
                    argument.span,
                );
                [0.0; 2]
            }
            Err(error) => {
                self.refuse(error.to_string(), error.span());
                [0.0; 2]
            }
        }
    }

    /// The states of the control elements' linear systems (TFSISO, LSE),
    /// each with its rate `A x + B u` as an expression of the statement.
    fn linear_states(&mut self) -> Vec<Diff> {
        let mut states = Vec::new();
        for system in self.scene.statements.linear_systems.clone() {
            for (index, (text, checked)) in system.rates.iter().enumerate() {
                self.expressions.push(Expression {
                    label: format!("{}'s state {} rate", system.statement, index + 1),
                    checked: checked.clone(),
                    text: Embedded::pinned(text, system.span.start),
                });
                states.push(Diff {
                    id: 0,
                    initial: system.initial[index],
                    function: self.expressions.len() - 1,
                    linear: Some(LinearState {
                        statement: system.statement.clone(),
                        array: system.states,
                        entry: index + 1,
                    }),
                    static_hold: system.static_hold,
                    implicit: None,
                    creep: None,
                });
            }
        }
        states
    }

    /// The force elements, with the statement (its kind as
    /// [`FORCE_ELEMENTS`] spells it) and id of each; `floating` the
    /// floating markers a JFLOAT may name, with their bodies.
    fn forces(
        &mut self,
        floating: &HashMap<u64, Option<usize>>,
    ) -> (Vec<Force>, Vec<(&'static str, u64)>) {
        let mut forces = Vec::new();
        let elements: Vec<(usize, &'static str)> = self
            .dataset
            .statements
            .iter()
            .enumerate()
            .filter_map(|(index, statement)| {
                FORCE_ELEMENTS
                    .into_iter()
                    .find(|kind| is_kind(&statement.name, kind))
                    .map(|kind| (index, kind))
            })
            .collect();
        // The statement of each force, filled as the next element starts.
        let mut statements = Vec::new();
        let mut current = ("", 0);
        for (index, kind) in elements {
            statements.resize(forces.len(), current);
            let dataset = self.dataset;
            current = (kind, dataset.statements[index].id.unwrap_or(0));
            let statement = &dataset.statements[index];
            if is_kind(&statement.name, "NFORCE") {
                forces.extend(self.multipoint(index));
                continue;
            }
            let Some(i) = self.marker(statement, "I") else {
                continue;
            };
            if let Some(span) = one_marker_line(statement) {
                let message = format!(
                    "{}: I and J name one marker: a translational {} acts along the line between two markers, so give another J",
                    statement.label(),
                    kind
                );
                self.refuse(message, span);
                continue;
            }
            if ["BUSHING", "SPRINGDAMPER", "BEAM", "FIELD"]
                .iter()
                .any(|kind| is_kind(&statement.name, kind))
            {
                let Some(j) = self.marker(statement, "J") else {
                    continue;
                };
                forces.extend(self.linear_element(index, i, j));
                continue;
            }
            if is_kind(&statement.name, "SFORCE") {
                let Some(j) = self.marker(statement, "J") else {
                    continue;
                };
                let Some(magnitude) = self.expression(index, "FUNCTION") else {
                    continue;
                };
                let action_only = statement.argument("ACTIONONLY", 3).is_some();
                let rotational = statement.argument("ROTATIONAL", 3).is_some();
                forces.push(Force::single(rotational, i, j, magnitude, action_only));
                continue;
            }
            let reaction = match statement.argument("JFLOAT", 2) {
                None => None,
                Some(argument) => {
                    match super::whole_id(statement, "JFLOAT").and_then(|id| floating.get(&id)) {
                        Some(body) => *body,
                        None => {
                            let message = format!(
                                "{}: JFLOAT must name a floating MARKER (MARKER/id, PART = ..., FLOATING)",
                                statement.label()
                            );
                            self.refuse(message, argument.span);
                            continue;
                        }
                    }
                }
            };
            let axes = match statement.argument("RM", 2) {
                Some(_) => match self.marker(statement, "RM") {
                    Some(axes) => axes,
                    None => continue,
                },
                None => Target::Ground,
            };
            let force_keywords = if is_kind(&statement.name, "VTORQUE") {
                [None; 3]
            } else {
                [Some("FX"), Some("FY"), Some("FZ")]
            };
            let torque_keywords = if is_kind(&statement.name, "VFORCE") {
                [None; 3]
            } else {
                [Some("TX"), Some("TY"), Some("TZ")]
            };
            let force =
                force_keywords.map(|keyword| keyword.and_then(|k| self.expression(index, k)));
            let torque =
                torque_keywords.map(|keyword| keyword.and_then(|k| self.expression(index, k)));
            forces.push(Force::Vector {
                i,
                reaction,
                axes,
                force,
                torque,
            });
        }
        statements.resize(forces.len(), current);
        (forces, statements)
    }

    /// A BUSHING, BEAM, FIELD or SPRINGDAMPER between markers `i` and `j`
    /// of statement `index`, as the force element its Adams definition is,
    /// with the expressions of its components written out:
    ///
    /// - BUSHING, BEAM, FIELD: on I, in J's axes, `F = −K (X − L) − C V +
    ///   F₀` with the matrices of [`linear`] (a BUSHING's
    ///   `-K·(DX, DY, DZ)(I,J,J) - C·(VX, VY, VZ)(I,J,J,J) + FORCE` and
    ///   `-KT·(AX, AY, AZ)(I,J) - CT·(WX, WY, WZ)(I,J,J) + TORQUE`, the
    ///   projected angles), the reaction on J's part at I's origin, which is
    ///   Adams' torque on J with the moment arm of the deformation; a FIELD
    ///   given by `FUNCTION = USER(...)` is refused as its subroutine;
    /// - SPRINGDAMPER, TRANSLATIONAL: along the line from J to I, repelling
    ///   when positive, `-C·VR(I,J) - K·(DM(I,J) - LENGTH) + FORCE`;
    /// - SPRINGDAMPER, ROTATIONAL: about J's z axis, on I and the opposite
    ///   on J, `-CT·WZ(I,J,J) - KT·(AZ(I,J) - ANGLE) + TORQUE`, AZ wound
    ///   through its whole turns over the run.
    fn linear_element(&mut self, index: usize, i: Target, j: Target) -> Option<Force> {
        let statement = &self.dataset.statements[index];
        let ids = [number(statement, "I", 0.0), number(statement, "J", 0.0)];
        let [Ok(i_id), Ok(j_id)] = ids else {
            return None;
        };
        let (i_id, j_id) = (i_id as u64, j_id as u64);
        let value = |keyword: &str| number(statement, keyword, 0.0);
        if is_kind(&statement.name, "SPRINGDAMPER") {
            // A rotational one's AZ keeps its whole turns over the run: a
            // spring wound several turns pulls back by all of them.
            let rotational = statement.argument("ROTATIONAL", 3).is_some();
            let (keywords, rate, place, what) = if rotational {
                (
                    ["CT", "KT", "ANGLE", "TORQUE"],
                    format!("WZ({i_id},{j_id},{j_id})"),
                    format!("AZ({i_id},{j_id})"),
                    "torque",
                )
            } else {
                (
                    ["C", "K", "LENGTH", "FORCE"],
                    format!("VR({i_id},{j_id})"),
                    format!("DM({i_id},{j_id})"),
                    "force",
                )
            };
            let read = keywords.map(value);
            let [c, k, free, preload] = match read {
                [Ok(c), Ok(k), Ok(free), Ok(preload)] => [c, k, free, preload],
                _ => return self.refuse_numbers(read.into_iter().find_map(Result::err)),
            };
            let text = linear_sum(&[
                (-c, rate),
                (-k, format!("({place} - {})", literal(free))),
                (preload, String::new()),
            ]);
            let magnitude = self.written(index, what, &text)?;
            return Some(Force::single(rotational, i, j, magnitude, false));
        }
        if is_kind(&statement.name, "FIELD") && statement.argument("FUNCTION", 4).is_some() {
            // Its USER(...) is refused where the expression compiles.
            self.expression(index, "FUNCTION");
            return None;
        }
        if is_kind(&statement.name, "BEAM")
            && let Some((span, reason)) = linear::nonlinear_beam(statement)
        {
            self.errors.push(SimulateError::Unsupported {
                statement: statement.label(),
                reason,
                span,
            });
            return None;
        }
        let matrices = if is_kind(&statement.name, "BEAM") {
            linear::beam(statement)
        } else if is_kind(&statement.name, "FIELD") {
            linear::field(statement)
        } else {
            linear::bushing(statement)
        };
        let linear = match matrices {
            Ok(linear) => linear,
            Err((message, span)) => {
                self.refuse(message, span);
                return None;
            }
        };
        let square =
            |matrix: &linear::Matrix6| DMatrix::from_fn(6, 6, |row, column| matrix[row][column]);
        let forces = self.linear_forces(
            index,
            &[(i_id, i)],
            (j_id, j),
            [&square(&linear.stiffness), &square(&linear.damping)],
            &linear.free,
            &linear.preload,
        )?;
        forces.into_iter().next()
    }

    /// The forces of the linear element of statement `index` (a BUSHING,
    /// BEAM or FIELD: one I marker; an NFORCE: several) between its I
    /// markers `i` and its J marker `j` (ids and places): on I marker `n`,
    /// along J's axes, `Fₙ = −Σₘ Kₙₘ (Xₘ − Lₘ) − Σₘ Cₙₘ Vₘ + F₀ₙ`, `Xₘ`
    /// the displacement of I marker `m` from J (`DX DY DZ (Iₘ,J,J)`, then
    /// the angles `AX AY AZ (Iₘ,J)`) and `Vₘ` its rate (`VX VY VZ
    /// (Iₘ,J,J,J)`, then `WX WY WZ (Iₘ,J,J)`), each marker's six rows and
    /// columns of `[K, C]`, `free` (`L`) and `preload` (`F₀`) in turn; each
    /// component written out as an expression, the reaction on J's part
    /// at I's origin.
    fn linear_forces(
        &mut self,
        index: usize,
        i: &[(u64, Target)],
        (j_id, j): (u64, Target),
        [stiffness, damping]: [&DMatrix<f64>; 2],
        free: &[f64],
        preload: &[f64],
    ) -> Option<Vec<Force>> {
        let mut displacement = Vec::with_capacity(6 * i.len());
        let mut rate = Vec::with_capacity(6 * i.len());
        for (i_id, _) in i {
            let measures = ["DX", "DY", "DZ"]
                .map(|name| format!("{name}({i_id},{j_id},{j_id})"))
                .into_iter()
                .chain(["AX", "AY", "AZ"].map(|name| format!("{name}({i_id},{j_id})")));
            displacement.extend(measures.zip(&free[displacement.len()..]).map(
                |(measure, free)| {
                    if *free == 0.0 {
                        measure
                    } else {
                        format!("({measure} - {})", literal(*free))
                    }
                },
            ));
            rate.extend(
                ["VX", "VY", "VZ"]
                    .map(|name| format!("{name}({i_id},{j_id},{j_id},{j_id})"))
                    .into_iter()
                    .chain(["WX", "WY", "WZ"].map(|name| format!("{name}({i_id},{j_id},{j_id})"))),
            );
        }
        let reaction = match j {
            Target::Marker(marker) => self.scene.markers[marker].body,
            _ => None,
        };
        let mut forces = Vec::with_capacity(i.len());
        for (n, (i_id, place)) in i.iter().enumerate() {
            let mut components = [None; 6];
            for (offset, name) in ["FX", "FY", "FZ", "TX", "TY", "TZ"].iter().enumerate() {
                let row = 6 * n + offset;
                let terms: Vec<(f64, String)> = [(stiffness, &displacement), (damping, &rate)]
                    .into_iter()
                    .flat_map(|(matrix, measures)| {
                        measures
                            .iter()
                            .enumerate()
                            .filter(move |(column, _)| matrix[(row, *column)] != 0.0)
                            .map(move |(column, measure)| (-matrix[(row, column)], measure.clone()))
                    })
                    .chain([(preload[row], String::new())])
                    .collect();
                let what = if i.len() == 1 {
                    (*name).to_string()
                } else {
                    format!("{name} on MARKER/{i_id}")
                };
                components[offset] = Some(self.written(index, &what, &linear_sum(&terms))?);
            }
            forces.push(Force::Vector {
                i: *place,
                reaction,
                axes: j,
                force: [components[0], components[1], components[2]],
                torque: [components[3], components[4], components[5]],
            });
        }
        Some(forces)
    }

    /// An NFORCE of statement `index` ([`nforce`] reads its markers and
    /// matrices): one force on each of its I markers, the reactions on
    /// its J marker's part.
    fn multipoint(&mut self, index: usize) -> Vec<Force> {
        let statement = &self.dataset.statements[index];
        match nforce::multipoint(self.dataset, statement, &self.scene) {
            Ok(read) => self
                .linear_forces(
                    index,
                    &read.i,
                    read.j,
                    [&read.stiffness, &read.damping],
                    &read.free,
                    &read.preload,
                )
                .unwrap_or_default(),
            Err((message, span)) => {
                self.refuse(message, span);
                Vec::new()
            }
        }
    }

    /// Records a statement's numbers that cannot be read.
    fn refuse_numbers(&mut self, error: Option<ConfigurationError>) -> Option<Force> {
        if let Some(error) = error {
            self.refuse(error.to_string(), error.span());
        }
        None
    }

    /// `text`, written for statement `index`'s `what`, parsed and checked;
    /// `None`, with the statement refused, when its numbers make no
    /// expression.
    fn checked(&mut self, index: usize, what: &str, text: &str) -> Option<crate::Checked> {
        let checked = crate::parse(text)
            .ok()
            .and_then(|tree| crate::check(&tree).ok());
        if checked.is_none() {
            let statement = &self.dataset.statements[index];
            self.refuse(
                format!(
                    "{}: its {what} cannot be written as an expression ({text}): check its numbers",
                    statement.label()
                ),
                statement.span,
            );
        }
        checked
    }

    /// An expression mbexpr writes for statement `index` (`what`: `FX`,
    /// `force`), added to the model's expressions with every place in it at
    /// the statement.
    fn written(&mut self, index: usize, what: &str, text: &str) -> Option<usize> {
        let statement = &self.dataset.statements[index];
        let checked = self.checked(index, what, text)?;
        self.expressions.push(Expression {
            label: format!("{} {what}", statement.label()),
            checked,
            text: Embedded::pinned(text, statement.span.start),
        });
        Some(self.expressions.len() - 1)
    }

    /// The SENSOR statements ([`super::sensors`] reads their settings),
    /// the notes on their steering actions added to `notes`.
    fn sensors(&mut self, notes: &mut Vec<(String, Span)>) -> Vec<Sensor> {
        let indices: Vec<usize> = self.statements("SENSOR").map(|(index, _)| index).collect();
        let mut sensors = Vec::new();
        for index in indices {
            let statement = &self.dataset.statements[index];
            let settings = match super::sensors::settings(statement) {
                Ok(settings) => settings,
                Err(super::sensors::Unread::Setting(message, span)) => {
                    self.refuse(message, span);
                    continue;
                }
                Err(super::sensors::Unread::Action { reason, span }) => {
                    self.errors.push(SimulateError::Unsupported {
                        statement: statement.label(),
                        reason,
                        span,
                    });
                    continue;
                }
            };
            let function = if statement.argument("FUNCTION", 4).is_some() {
                self.expression(index, "FUNCTION")
            } else {
                match number(statement, "VARIABLE", f64::NAN) {
                    Ok(id) if id.is_finite() && id > 0.0 => {
                        self.written(index, "VARIABLE", &format!("VARVAL({})", id as u64))
                    }
                    _ => {
                        let label = statement.label();
                        self.refuse(
                            format!(
                                "{label}: give FUNCTION = what it watches (or VARIABLE = its id)"
                            ),
                            statement.span,
                        );
                        None
                    }
                }
            };
            let Some(function) = function else { continue };
            let evaluate = if statement.argument("EVALUATE", 4).is_some() {
                let Some(evaluate) = self.expression(index, "EVALUATE") else {
                    continue;
                };
                Some(evaluate)
            } else {
                None
            };
            if let Some(note) = settings.steering {
                notes.push((note, statement.span));
            }
            sensors.push(Sensor {
                id: statement.id.unwrap_or(0),
                function,
                relation: settings.relation,
                value: settings.value,
                error: settings.error,
                action: settings.action,
                evaluate,
                output_step: settings.output_step,
                span: statement.span,
            });
        }
        sensors
    }

    /// Floating markers by id, with the body they are on (`None`: ground).
    fn floating_markers(&self) -> HashMap<u64, Option<usize>> {
        let mut bodies = HashMap::new();
        let mut index = 0;
        for (_, part) in self.statements("PART") {
            let Some(id) = part.id else { continue };
            if part.argument("GROUND", 3).is_some() {
                bodies.insert(id, None);
            } else {
                bodies.insert(id, Some(index));
                index += 1;
            }
        }
        self.statements("MARKER")
            .filter(|(_, marker)| marker.argument("FLOATING", 3).is_some())
            .filter_map(|(_, marker)| {
                let part = number(marker, "PART", f64::NAN).ok()? as u64;
                Some((marker.id?, *bodies.get(&part)?))
            })
            .collect()
    }

    fn gravity(&mut self) -> Vector3<f64> {
        let mut gravity = Vector3::zeros();
        let dataset = self.dataset;
        let statements: Vec<&Statement> = dataset
            .statements
            .iter()
            .filter(|statement| is_kind(&statement.name, "ACCGRAV"))
            .collect();
        for again in statements.iter().skip(1) {
            self.refuse(
                "ACCGRAV given again: a model has one gravity (give it in one ACCGRAV statement)"
                    .to_string(),
                again.span,
            );
        }
        for statement in statements {
            for (axis, keyword) in ["IGRAV", "JGRAV", "KGRAV"].into_iter().enumerate() {
                match number(statement, keyword, 0.0) {
                    Ok(value) => gravity[axis] = value,
                    Err(error) => self.refuse(error.to_string(), error.span()),
                }
            }
        }
        gravity
    }

    /// The columns of REQUEST `index` when it is of a standard kind, as
    /// Adams lists them for the I marker against the J marker (ground when
    /// 0 or left out), the vectors along RM's axes (ground's when 0 or left
    /// out): DISPLACEMENT `DM DX DY DZ PSI THETA PHI` (the body-fixed 3-1-3
    /// angles of I from J, in radians), VELOCITY `VM VX VY VZ WM WX WY WZ`
    /// (derivatives in ground), ACCELERATION `ACCM ACCX ACCY ACCZ WDTM WDTX
    /// WDTY WDTZ` (derivatives in ground), FORCE `FM FX FY FZ TM TX TY TZ`
    /// (the net force at I from J, the torque about I's origin). `false`
    /// when it is of no standard kind.
    fn standard_request(&mut self, index: usize, outputs: &mut Vec<Output>) -> bool {
        let dataset = self.dataset;
        let statement = &dataset.statements[index];
        // Adams reads these kinds from their first letter (Adams View
        // writes `REQUEST/1, D, I = 2, J = 1`).
        let kind = ["DISPLACEMENT", "VELOCITY", "ACCELERATION", "FORCE"]
            .into_iter()
            .find(|kind| statement.argument(kind, 1).is_some());
        let Some(kind) = kind else {
            return false;
        };
        let id = |keyword: &str| match number(statement, keyword, 0.0) {
            Ok(id) if id.fract() == 0.0 && id >= 0.0 => Some(Shown(id).to_string()),
            _ => None,
        };
        let (Some(i), Some(j), Some(rm)) = (id("I"), id("J"), id("RM")) else {
            self.refuse(
                format!("{}: I, J and RM must be marker ids", statement.label()),
                statement.span,
            );
            return true;
        };
        // Each measure, and whether it is resolved along RM's axes.
        let measures: &[(&str, bool)] = match kind {
            "DISPLACEMENT" => &[
                ("DM", false),
                ("DX", true),
                ("DY", true),
                ("DZ", true),
                ("PSI", false),
                ("THETA", false),
                ("PHI", false),
            ],
            "VELOCITY" => &[
                ("VM", false),
                ("VX", true),
                ("VY", true),
                ("VZ", true),
                ("WM", false),
                ("WX", true),
                ("WY", true),
                ("WZ", true),
            ],
            "ACCELERATION" => &[
                ("ACCM", false),
                ("ACCX", true),
                ("ACCY", true),
                ("ACCZ", true),
                ("WDTM", false),
                ("WDTX", true),
                ("WDTY", true),
                ("WDTZ", true),
            ],
            _ => &[
                ("FM", false),
                ("FX", true),
                ("FY", true),
                ("FZ", true),
                ("TM", false),
                ("TX", true),
                ("TY", true),
                ("TZ", true),
            ],
        };
        let columns = measures.iter().map(|&(heading, along_rm)| {
            let text = if along_rm {
                format!("{heading}({i}, {j}, {rm})")
            } else {
                format!("{heading}({i}, {j})")
            };
            (heading, text)
        });
        for (heading, text) in columns {
            if let Some(expression) = self.written(index, heading, &text) {
                outputs.push(Output {
                    name: format!("{}.{heading}", statement.label()),
                    expression,
                });
            }
        }
        true
    }

    fn outputs(&mut self, notes: &mut Vec<(String, Span)>) -> Vec<Output> {
        let requests: Vec<usize> = self.statements("REQUEST").map(|(index, _)| index).collect();
        let mut outputs = Vec::new();
        let dataset = self.dataset;
        for index in requests {
            let statement = &dataset.statements[index];
            let label = statement.label();
            let mut any = false;
            for keyword in ["F1", "F2", "F3", "F4", "F5", "F6", "F7", "F8"] {
                if statement.argument(keyword, 2).is_none() {
                    continue;
                }
                any = true;
                if let Some(expression) = self.expression(index, keyword) {
                    outputs.push(Output {
                        name: format!("{label}.{keyword}"),
                        expression,
                    });
                }
            }
            if !any && !self.standard_request(index, &mut outputs) {
                notes.push((
                    format!("{label} is not computed: simulate writes a REQUEST's F1 ... F8 expressions, or its DISPLACEMENT, VELOCITY, ACCELERATION or FORCE (write DX(i, j), VX(i, j) ... there)"),
                    statement.span,
                ));
            }
        }
        // Each VARIABLE's value, as Adams writes it with the results.
        let variables: Vec<usize> = self
            .statements("VARIABLE")
            .map(|(index, _)| index)
            .collect();
        for index in variables {
            if let Some(expression) = self.expression(index, "FUNCTION") {
                outputs.push(Output {
                    name: dataset.statements[index].label(),
                    expression,
                });
            }
        }
        outputs
    }
}

/// The J argument of a translational SFORCE or SPRINGDAMPER whose I and J
/// name one marker: its line of action is not defined.
fn one_marker_line(statement: &Statement) -> Option<Span> {
    let translational = ["SFORCE", "SPRINGDAMPER"]
        .iter()
        .any(|kind| is_kind(&statement.name, kind))
        && statement.argument("ROTATIONAL", 3).is_none();
    let i = number(statement, "I", f64::NAN).ok()?;
    let j = number(statement, "J", f64::NAN).ok()?;
    (translational && i == j)
        .then(|| statement.argument("J", 1).map(|argument| argument.span))
        .flatten()
}

/// The marker a statement's `keyword = id` names, `None` for ground or a
/// marker not in the scene.
fn marker_named<'s>(
    statement: &Statement,
    keyword: &str,
    scene: &'s Scene,
) -> Option<&'s crate::scene::Marker> {
    match super::named_marker(statement, keyword, scene)? {
        Target::Marker(index) => Some(&scene.markers[index]),
        Target::Ground => None,
    }
}

/// Whether `inertia` is positive definite beyond rounding: its least
/// principal moment above `1e-12` of its largest (a zero moment turned by
/// a marker's orientation is a rounding error away from zero, which a
/// Cholesky factorisation alone takes as positive).
fn positive_definite(inertia: &Matrix3<f64>) -> bool {
    let moments = inertia.symmetric_eigenvalues();
    let (least, largest) = (moments.min(), moments.max());
    least.is_finite() && largest.is_finite() && least > 1e-12 * largest
}

/// Why a statement of kind `name` is not simulated, and what to write
/// instead where there is something.
fn why_not_simulated(name: &str) -> String {
    let is = |kind: &str| is_kind(name, kind);
    if is("GSE") {
        "is defined by user subroutines (GSE_DERIV, GSE_OUTPUT ...), which mbexpr does not call: write its states as DIFFs, or as an LSE or a TFSISO where it is linear".to_string()
    } else if is("MFORCE") {
        "is a load on a flexible body, which mbexpr does not simulate".to_string()
    } else {
        "is not among the elements mbexpr integrates (PART, POINT_MASS, JOINT, JPRIM, PTCV, CVCV, MOTION, COUPLER, GEAR, GCON, SENSOR, DIFF, TFSISO, LSE, SFORCE, VFORCE, VTORQUE, GFORCE, BUSHING, SPRINGDAMPER, BEAM, FIELD, NFORCE, CONTACT, ACCGRAV)".to_string()
    }
}
