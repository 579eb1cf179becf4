//! `FRICTION` statements of a dataset: joint friction, written out as the
//! expressions of a force element and of a stiction state, so that the
//! friction reads its joint's reactions at the state it acts at (the
//! loop values of `JOINT(id, 0, comp, rm)`, solved with the motion).
//!
//! What Adams documents (Adams Solver C++ `FRICTION` statement,
//! <https://adams.thisaray.com/adams_solver/state_friction.html>, and the
//! Adams/Solver friction pages of
//! <http://www.kxcad.net/MSC_Software/Adams_MD_R2/standalones/view_standalones/friction_regime.htm>
//! and `.../solver_standalones/joint_types_translational.htm>`):
//!
//! - the keywords, their defaults and ranges: `MU_STATIC` and
//!   `MU_DYNAMIC` (required), `STICTION_TRANSITION_VELOCITY` 0.1 (> 0),
//!   `TRANSITION_VELOCITY_COEFFICIENT` 1.5 (> 1), `MAX_STICTION_DEFORMATION`
//!   0.01 (> 0), `FRICTION_FORCE_PRELOAD` and `FRICTION_TORQUE_PRELOAD` 0,
//!   `FRICTION_ARM`, `BENDING_REACTION_ARM`, `REACTION_ARM`, `PIN_RADIUS`,
//!   `BALL_RADIUS` 1 (> 0), `INITIAL_OVERLAP` 1000 (> 0), `EFFECT = ALL`,
//!   `INPUTS = ALL`;
//! - the friction regimes: dynamic friction (`μd`) above `β·vs` (`β` the
//!   TRANSITION_VELOCITY_COEFFICIENT, `vs` the STICTION_TRANSITION_VELOCITY),
//!   a STEP from `μs` to `μd` between `vs` and `β·vs`, and static friction
//!   below `vs`, where the coefficient comes from the joint's creep, its
//!   velocity and `μs`, the creep at most MAX_STICTION_DEFORMATION;
//! - a translational joint's friction force along its axis from its
//!   reaction force, its bending moment over the overlap, its torsional
//!   moment over an arm and its force preload, each of which INPUTS can
//!   turn off; a revolute joint's friction torque from its radial force at
//!   the pin radius, its axial force at the friction arm, its bending
//!   moment through the bending reaction arm and its torque preload.
//!
//! Where the pages leave the formula to a block diagram this reader could
//! not see, mbexpr chooses (each choice its own reading, not Adams'
//! documented formula):
//!
//! - the load `N` sums the inputs, the preload among them, and the
//!   friction is `μ·N` (a translational joint's
//!   `N = P + |(Fx, Fy)| + |(Tx, Ty)|/INITIAL_OVERLAP + |Tz|/REACTION_ARM`,
//!   a revolute joint's torque load
//!   `N = P + PIN_RADIUS·(|(Fx, Fy)| + |(Tx, Ty)|/BENDING_REACTION_ARM) + FRICTION_ARM·|Fz|`,
//!   the reactions those of `JOINT(id, 0, comp, J)` on the I marker along
//!   J's axes), at most MAX_FRICTION_FORCE (or TORQUE) when given;
//! - the slip speed `v` is `VZ(I, J, J, J)` for a translational joint and
//!   `PIN_RADIUS·WZ(I, J, J)` on a revolute joint's pin;
//! - the sliding coefficient `STEP(v, −vs, −μ₁, vs, μ₁) + STEP(v, vs, 0,
//!   β·vs, μ₂ − μ₁) + STEP(v, −β·vs, μ₁ − μ₂, −vs, 0)`, odd in `v`: with
//!   `EFFECT = ALL` `μ₁ = μs`, `μ₂ = μd` (the documented regimes above
//!   `vs`); `STICTION` `μ₁ = μs`, `μ₂ = 0`; `SLIDING` `μ₁ = μ₂ = μd`;
//! - the creep is a state `s` of the joint (a bristle, Dahl's model),
//!   `ds/dt = v − |v|·s/δ` with `δ` the MAX_STICTION_DEFORMATION (so `|s| ≤
//!   δ`), and the coefficient with stiction
//!   `(1 − w)·μs·(s/δ + (ds/dt)/vs) + w·(sliding)`, `w = STEP(|v|, 0, 0,
//!   vs, 1)`: at rest the joint holds up to `μs·N` as a spring that gives
//!   at most `δ`, damped as a ramp to `μs` at `vs` would (the damping
//!   vanishes where the creep is full; both terms take energy, never give
//!   it); `SLIDING` has no creep state;
//! - a static equilibrium keeps the creep at its value (no stiction in
//!   statics, as `INACTIVE = STATIC` asks; sliding friction is 0 at rest).
//!
//! Refused at their place: the CYLINDRICAL, HOOKE, UNIVERSAL and SPHERICAL
//! joints' friction (their slip is two-dimensional), the LuGre model,
//! `OVERLAP_DELTA = INCREASE` or `DECREASE`; a joint of another type, a
//! missing or unknown JOINT and every bad value are errors.

use super::dataset::{linear_sum, literal};
use crate::model::initial::number;
use crate::model::{Dataset, Statement, Value, is_kind};
use crate::scene::{Scene, Target};
use crate::simulate::SimulateError;
use crate::simulate::model::{Joint, JointKind};
use crate::span::Span;

/// A FRICTION statement read: the expressions its force and its creep
/// state are written as.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointFriction {
    /// The statement id.
    pub id: u64,
    /// Its index among the dataset's statements.
    pub statement: usize,
    /// The joint, an index into the model's joints.
    pub joint: usize,
    /// A torque about J's z axis (revolute) rather than a force along it.
    pub rotational: bool,
    /// The friction force or torque on I, along or about J's z axis.
    pub magnitude: String,
    /// The creep's rate, `ds/dt`, when stiction is on; `{creep}` stands
    /// for the state's input in it and in [`JointFriction::magnitude`].
    pub creep_rate: Option<String>,
}

/// What stands for the creep state's input in the written expressions.
pub(crate) const CREEP: &str = "{creep}";

/// The FRICTION statements of `dataset` on `joints` (their markers in
/// `scene`); every problem added to `errors` at its place.
pub(crate) fn frictions(
    dataset: &Dataset,
    joints: &[Joint],
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Vec<JointFriction> {
    let mut frictions = Vec::new();
    for (index, statement) in dataset.statements.iter().enumerate() {
        if !is_kind(&statement.name, "FRICTION") {
            continue;
        }
        match friction(statement, joints, scene) {
            Ok((joint, _, _, _))
                if let Some(first) = frictions
                    .iter()
                    .find(|friction: &&JointFriction| friction.joint == joint) =>
            {
                errors.push(SimulateError::Model {
                    message: format!(
                        "{}: JOINT/{} has its friction already (FRICTION/{}): give a joint one FRICTION",
                        statement.label(),
                        joints[joint].id,
                        first.id
                    ),
                    span: statement.place_of("JOINT", 5),
                });
            }
            Ok((joint, magnitude, creep_rate, rotational)) => frictions.push(JointFriction {
                id: statement.id.unwrap_or(0),
                statement: index,
                joint,
                rotational,
                magnitude,
                creep_rate,
            }),
            Err(error) => errors.push(error),
        }
    }
    frictions
}

/// A keyword of one word: the words simulated, those refused (with the
/// reason) and what it can be.
struct Switch {
    keyword: &'static str,
    shortest: usize,
    taken: &'static [&'static str],
    refused: &'static [&'static str],
    reason: &'static str,
    words: &'static str,
}

/// The FRICTION's keywords of one word.
const SWITCHES: [Switch; 3] = [
    Switch {
        keyword: "FRICTION_MODEL",
        shortest: 10,
        taken: &["DEFAULT", "STICK_SLIP"],
        refused: &["LUGRE"],
        reason: "uses the LuGre model, which mbexpr does not simulate: it simulates the stick-slip model (FRICTION_MODEL = DEFAULT)",
        words: "DEFAULT or LUGRE",
    },
    Switch {
        keyword: "OVERLAP_DELTA",
        shortest: 7,
        taken: &["CONSTANT"],
        refused: &["INCREASE", "DECREASE"],
        reason: "has an overlap that changes with the joint's travel, which mbexpr does not simulate: give OVERLAP_DELTA = CONSTANT",
        words: "CONSTANT, INCREASE or DECREASE",
    },
    Switch {
        keyword: "INACTIVE",
        shortest: 4,
        taken: &["STATIC"],
        refused: &[],
        reason: "",
        words: "STATIC",
    },
];

/// The joint, force, creep rate and kind of one FRICTION.
type Read = (usize, String, Option<String>, bool);

fn friction(statement: &Statement, joints: &[Joint], scene: &Scene) -> Result<Read, SimulateError> {
    let label = statement.label();
    let model = |message: String, span: Span| SimulateError::Model {
        message: format!("{label}: {message}"),
        span,
    };
    let unsupported = |reason: String, span: Span| SimulateError::Unsupported {
        statement: label.clone(),
        reason,
        span,
    };
    let Some(argument) = statement.argument("JOINT", 5) else {
        return Err(model(
            "give JOINT = the id of the joint it acts in".to_string(),
            statement.span,
        ));
    };
    let id = super::whole_id(statement, "JOINT").ok_or_else(|| {
        model(
            "JOINT must be a whole id above 0".to_string(),
            argument.span,
        )
    })?;
    let Some(joint) = joints
        .iter()
        .position(|joint| joint.id == id && joint.kind.statement() == "JOINT")
    else {
        return Err(model(
            format!("JOINT = {id} names no JOINT of the model"),
            argument.span,
        ));
    };
    let kind = joints[joint].kind;
    let name = JointKind::ALL
        .iter()
        .find(|(each, _)| *each == kind)
        .map_or("", |(_, name)| *name);
    match kind {
        JointKind::Translational | JointKind::Revolute => {}
        JointKind::Cylindrical | JointKind::Hooke | JointKind::Universal | JointKind::Spherical => {
            return Err(unsupported(
                format!(
                    "is friction in a {name} joint, which mbexpr does not simulate (its slip has two directions): it simulates the friction of TRANSLATIONAL and REVOLUTE joints"
                ),
                argument.span,
            ));
        }
        _ => {
            return Err(model(
                format!(
                    "JOINT/{id} is a {name} joint: friction acts in TRANSLATIONAL, REVOLUTE, CYLINDRICAL, HOOKE, UNIVERSAL and SPHERICAL joints"
                ),
                argument.span,
            ));
        }
    }
    for switch in SWITCHES {
        let Some(argument) = statement.argument(switch.keyword, switch.shortest) else {
            continue;
        };
        match word(statement, switch.keyword, switch.shortest) {
            Some(word) if switch.taken.contains(&word.as_str()) => {}
            Some(word) if switch.refused.contains(&word.as_str()) => {
                return Err(unsupported(switch.reason.to_string(), argument.span));
            }
            _ => {
                let message = format!("{} is {}", switch.keyword, switch.words);
                return Err(model(message, argument.span));
            }
        }
    }
    // A number of the statement, `default` when left out, above `least`
    // (or equal to it when `or_equal`).
    let value = |keyword: &str, default: f64, least: f64, or_equal: bool| {
        let span = statement.place_of(keyword, keyword.len());
        let what = match (least, or_equal) {
            (0.0, true) => "a number, 0 or more".to_string(),
            (least, _) => format!("a number above {least}"),
        };
        number(statement, keyword, default)
            .ok()
            .filter(|value| value.is_finite() && (*value > least || (or_equal && *value == least)))
            .ok_or_else(|| model(format!("{keyword} must be {what}"), span))
    };
    let required = |keyword: &str| {
        if statement.argument(keyword, keyword.len()).is_none() {
            return Err(model(
                format!("give {keyword} = the coefficient, 0 or more"),
                statement.span,
            ));
        }
        value(keyword, 0.0, 0.0, true)
    };
    let mu_static = required("MU_STATIC")?;
    let mu_dynamic = required("MU_DYNAMIC")?;
    let vs = value("STICTION_TRANSITION_VELOCITY", 0.1, 0.0, false)?;
    let beta = value("TRANSITION_VELOCITY_COEFFICIENT", 1.5, 1.0, false)?;
    let deformation = value("MAX_STICTION_DEFORMATION", 0.01, 0.0, false)?;
    let positive = |keyword: &str, default: f64| value(keyword, default, 0.0, false);
    let or_more = |keyword: &str| value(keyword, 0.0, 0.0, true);
    let largest = |keyword: &str| -> Result<Option<f64>, SimulateError> {
        match statement.argument(keyword, keyword.len()) {
            None => Ok(None),
            Some(_) => positive(keyword, 0.0).map(Some),
        }
    };
    let listed = |message: &'static str| move |span: Span| model(message.to_string(), span);
    let effect = effect(statement).map_err(listed(
        "EFFECT is ALL, STICTION, SLIDING or STICTION:SLIDING",
    ))?;
    let rotational = kind == JointKind::Revolute;
    let inputs = inputs(statement, rotational).map_err(listed(
        "INPUTS is ALL, NONE or a list of PRELOAD, REACTION_FORCE, BENDING_MOMENT and TORSIONAL_MOMENT",
    ))?;
    let [i, j] = [joints[joint].i, joints[joint].j].map(|target| marker_id(scene, target));
    let reaction = |comp: u8| format!("JOINT({id},0,{comp},{j})");
    let magnitude_of = |a: u8, b: u8| format!("SQRT({}**2 + {}**2)", reaction(a), reaction(b));
    // Each input with whether INPUTS takes it, its factor and its term.
    let (inputs_terms, slip, limit) = if rotational {
        if inputs.torsion {
            return Err(model(
                "TORSIONAL_MOMENT is an input of a translational joint's friction".to_string(),
                statement.place_of("INPUTS", 6),
            ));
        }
        let pin = positive("PIN_RADIUS", 1.0)?;
        let arm = positive("FRICTION_ARM", 1.0)?;
        let bending_arm = positive("BENDING_REACTION_ARM", 1.0)?;
        let terms = vec![
            (
                inputs.preload,
                or_more("FRICTION_TORQUE_PRELOAD")?,
                String::new(),
            ),
            (inputs.force, pin, magnitude_of(2, 3)),
            (inputs.force, arm, format!("ABS({})", reaction(4))),
            (inputs.bending, pin / bending_arm, magnitude_of(6, 7)),
        ];
        let slip = format!("{}*WZ({i},{j},{j})", literal(pin));
        (terms, slip, largest("MAX_FRICTION_TORQUE")?)
    } else {
        let overlap = positive("INITIAL_OVERLAP", 1000.0)?;
        let arm = positive("REACTION_ARM", 1.0)?;
        let terms = vec![
            (
                inputs.preload,
                or_more("FRICTION_FORCE_PRELOAD")?,
                String::new(),
            ),
            (inputs.force, 1.0, magnitude_of(2, 3)),
            (inputs.bending, 1.0 / overlap, magnitude_of(6, 7)),
            (inputs.torsion, 1.0 / arm, format!("ABS({})", reaction(8))),
        ];
        let slip = format!("VZ({i},{j},{j},{j})");
        (terms, slip, largest("MAX_FRICTION_FORCE")?)
    };
    let load: Vec<(f64, String)> = inputs_terms
        .into_iter()
        .filter(|(taken, _, _)| *taken)
        .map(|(_, factor, term)| (factor, term))
        .collect();
    let (peak, end) = match effect {
        Effect::All => (mu_static, mu_dynamic),
        Effect::Stiction => (mu_static, 0.0),
        Effect::Sliding => (mu_dynamic, mu_dynamic),
    };
    let v = format!("({slip})");
    let mut coefficient = sum(&[
        step(&v, -vs, -peak, vs, peak),
        step(&v, vs, 0.0, beta * vs, end - peak),
        step(&v, -beta * vs, peak - end, -vs, 0.0),
    ]);
    let creep_rate = (effect != Effect::Sliding).then(|| {
        let rate = format!("{v} - ABS{v}*{CREEP}/{}", literal(deformation));
        let weight = format!("STEP(ABS{v}, 0, 0, {}, 1)", literal(vs));
        coefficient = format!(
            "(1 - {weight})*({}*{CREEP} + {}*({rate})) + {weight}*({coefficient})",
            literal(mu_static / deformation),
            literal(mu_static / vs)
        );
        rate
    });
    let mut magnitude = format!("-({coefficient})*({})", linear_sum(&load));
    if let Some(limit) = limit {
        magnitude = format!(
            "MIN(MAX({magnitude}, {}), {})",
            literal(-limit),
            literal(limit)
        );
    }
    Ok((joint, magnitude, creep_rate, rotational))
}

/// `STEP(v, x0, h0, x1, h1)` as text, `""` (left out of a sum) when it
/// is 0 throughout.
fn step(v: &str, x0: f64, h0: f64, x1: f64, h1: f64) -> String {
    if h0 == 0.0 && h1 == 0.0 {
        return String::new();
    }
    format!(
        "STEP({v}, {}, {}, {}, {})",
        literal(x0),
        literal(h0),
        literal(x1),
        literal(h1)
    )
}

/// The terms' sum as text, empty terms left out; `0` when none is left.
fn sum(terms: &[String]) -> String {
    let written: Vec<&str> = terms
        .iter()
        .map(String::as_str)
        .filter(|term| !term.is_empty())
        .collect();
    if written.is_empty() {
        "0".to_string()
    } else {
        written.join(" + ")
    }
}

/// The frictional effects (`EFFECT`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Effect {
    /// Stiction and sliding (`ALL`, `STICTION:SLIDING`).
    All,
    /// Stiction alone.
    Stiction,
    /// Sliding alone: no creep state.
    Sliding,
}

/// The words of a keyword's list (`INPUTS = (PRELOAD:REACTION_FORCE)`),
/// upper case, parentheses and blanks taken off; `None` when it is not
/// given.
fn words(statement: &Statement, keyword: &str, shortest: usize) -> Option<(Vec<String>, Span)> {
    let argument = statement.argument(keyword, shortest)?;
    let words = match &argument.value {
        Value::List(items) => items
            .iter()
            .flat_map(|item| {
                item.text
                    .split([':', ',', '(', ')'])
                    .map(|word| word.trim().to_ascii_uppercase())
                    .filter(|word| !word.is_empty())
                    .collect::<Vec<_>>()
            })
            .collect(),
        _ => Vec::new(),
    };
    Some((words, argument.span))
}

/// The one word a keyword is set to (`FRICTION_MODEL = LUGRE`).
fn word(statement: &Statement, keyword: &str, shortest: usize) -> Option<String> {
    statement
        .argument(keyword, shortest)
        .and_then(super::word_of)
}

/// `EFFECT`: ALL when left out; the span of a value that is none of its
/// words.
fn effect(statement: &Statement) -> Result<Effect, Span> {
    let Some((words, span)) = words(statement, "EFFECT", 6) else {
        return Ok(Effect::All);
    };
    let has = |name: &str| words.iter().any(|word| word == name);
    if words.is_empty()
        || words
            .iter()
            .any(|word| !["ALL", "STICTION", "SLIDING"].contains(&word.as_str()))
    {
        return Err(span);
    }
    Ok(match (has("ALL"), has("STICTION"), has("SLIDING")) {
        (false, true, false) => Effect::Stiction,
        (false, false, true) => Effect::Sliding,
        _ => Effect::All,
    })
}

/// The inputs of the friction's load (`INPUTS`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Inputs {
    /// `PRELOAD`.
    preload: bool,
    /// `REACTION_FORCE`.
    force: bool,
    /// `BENDING_MOMENT`.
    bending: bool,
    /// `TORSIONAL_MOMENT`.
    torsion: bool,
}

/// `INPUTS`: ALL when left out (a revolute joint has no torsional
/// moment: ALL leaves it out there); the span of a value that is none of
/// its words.
fn inputs(statement: &Statement, rotational: bool) -> Result<Inputs, Span> {
    let Some((words, span)) = words(statement, "INPUTS", 6) else {
        return Ok(Inputs {
            preload: true,
            force: true,
            bending: true,
            torsion: !rotational,
        });
    };
    const NAMES: [&str; 6] = [
        "ALL",
        "NONE",
        "PRELOAD",
        "REACTION_FORCE",
        "BENDING_MOMENT",
        "TORSIONAL_MOMENT",
    ];
    if words.is_empty() || words.iter().any(|word| !NAMES.contains(&word.as_str())) {
        return Err(span);
    }
    let has = |name: &str| words.iter().any(|word| word == name || word == "ALL");
    Ok(Inputs {
        preload: has("PRELOAD"),
        force: has("REACTION_FORCE"),
        bending: has("BENDING_MOMENT"),
        torsion: has("TORSIONAL_MOMENT") && !(rotational && words.iter().any(|word| word == "ALL")),
    })
}

/// The id a joint's marker has in expressions (`0` for ground itself).
fn marker_id(scene: &Scene, target: Target) -> u64 {
    match target {
        Target::Ground => 0,
        Target::Marker(index) => scene.markers[index].id.unwrap_or(0),
    }
}
