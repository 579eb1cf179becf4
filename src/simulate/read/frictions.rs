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
//!   moment through the bending reaction arm and its torque preload; a
//!   cylindrical joint's from its force and torque preloads, PIN_RADIUS and
//!   INITIAL_OVERLAP (the bending moment divided by the overlap), a
//!   spherical joint's from its torque preload and BALL_RADIUS, a Hooke or
//!   universal joint's as a revolute joint's (the keywords of each joint,
//!   as MotionSolve's `Force_JointFriction` lists them too:
//!   <https://2021.help.altair.com/2021.2/hwsolvers/ms/topics/solvers/ms/xml-format_11.htm>).
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
//! - a cylindrical joint's load `N = P + Pt/PIN_RADIUS + |(Fx, Fy)| +
//!   |(Tx, Ty)|/INITIAL_OVERLAP` (a force on the pin's surface, `P` the
//!   FRICTION_FORCE_PRELOAD, `Pt` the FRICTION_TORQUE_PRELOAD); a spherical
//!   joint's torque load `N = Pt + BALL_RADIUS·|(Fx, Fy, Fz)|`;
//! - a Hooke or universal joint is two revolute pins on a massless cross:
//!   a UNIVERSAL joint's turn about I's z axis (fixed in I's part) and
//!   about J's z axis, a HOOKE joint's about I's x and J's y axes. Each
//!   pin's friction is a revolute joint's, from the joint's reaction
//!   force across and along that pin (`JOINT(id, 0, comp, I)` in I's axes
//!   for I's pin) and its whole reaction torque as the bending moment
//!   (the cross carries it across both pins); its slip
//!   `PIN_RADIUS·WZ(I, J, I)` (I's pin) or `PIN_RADIUS·WZ(I, J, J)` (J's),
//!   the pins' axes being perpendicular; each pin its own law and creep
//!   (`.creep1` I's pin, `.creep2` J's). The torque on I is the two pins'
//!   frictions about their axes, I's axis turned into J's by
//!   `ORIENT(29, ...)`: the cross, massless, passes each pin's friction on
//!   through the other pin. Adams' statement has `I_YOKE` and `J_YOKE`
//!   (the interfaces that write it, NX's `FrictionYokeType` and
//!   MotionView's `rot_constraint`, offer one yoke or the other): given
//!   one, the friction acts in that yoke's pin alone (`.creep` its creep);
//!   given neither, in both;
//! - the slip speed `v` is `VZ(I, J, J, J)` for a translational joint and
//!   `PIN_RADIUS·WZ(I, J, J)` on a revolute joint's pin; a cylindrical
//!   joint's slip has two directions, `(VZ(I, J, J, J), PIN_RADIUS·WZ(I,
//!   J, J))`, its friction `−μₖ·N` along z and `−μₖ·N·PIN_RADIUS` about
//!   it; a spherical joint's three, `BALL_RADIUS·(WX, WY, WZ)(I, J, J)` on
//!   the ball's surface, its friction the torque `−μₖ·N` about J's axes;
//! - a slip of more directions takes its coefficient from its speed,
//!   `|v|` smoothed to `√(|v|² + ε²) − ε` with `ε = vs/1000`, and the
//!   sliding coefficient along direction `k` is `μ(|v|)·vₖ/√(|v|² + ε²)`
//!   (`μ` the STEPs below at `|v| ≥ 0`), so that the friction opposes the
//!   slip, is 0 at rest with no NaN, and dissipates (its power `−μ N
//!   |v|²/√(|v|² + ε²) ≤ 0`); MAX_FRICTION_FORCE and TORQUE bound each
//!   component;
//! - the sliding coefficient `STEP(v, −vs, −μ₁, vs, μ₁) + STEP(v, vs, 0,
//!   β·vs, μ₂ − μ₁) + STEP(v, −β·vs, μ₁ − μ₂, −vs, 0)`, odd in `v`: with
//!   `EFFECT = ALL` `μ₁ = μs`, `μ₂ = μd` (the documented regimes above
//!   `vs`); `STICTION` `μ₁ = μs`, `μ₂ = 0`; `SLIDING` `μ₁ = μ₂ = μd`;
//! - the creep is a state `s` of the joint (a bristle, Dahl's model), one
//!   per direction of the slip (columns `FRICTION/id.creep`, or
//!   `.creep1` .. `.creep3` along the directions above),
//!   `ds/dt = v − |v|·s/δ` with `δ` the MAX_STICTION_DEFORMATION (so `|s| ≤
//!   δ`, the vector's length too), and the coefficient with stiction
//!   `(1 − w)·μs·(s/δ + (ds/dt)/vs) + w·(sliding)`, `w = STEP(|v|, 0, 0,
//!   vs, 1)`, along each direction: at rest the joint holds up to `μs·N`
//!   as a spring that gives at most `δ`, damped as a ramp to `μs` at `vs`
//!   would (the damping vanishes where the creep is full; both terms take
//!   energy, never give it); `SLIDING` has no creep state;
//! - a static equilibrium keeps the creep at its value (no stiction in
//!   statics, as `INACTIVE = STATIC` asks, or `INACTIVE_DURING = STATIC` as
//!   Adams View 2015 writes it; sliding friction is 0 at rest).
//!
//! - `FRICTION_MODEL = LUGRE`: the creep is the bristles' deflection `z`
//!   of the LuGre model (Canudas de Wit, Olsson, Åström, Lischinsky,
//!   1995), written per unit of the load as MotionSolve documents its
//!   coefficients (`σ0` per length, `σ1` and `σ2` time per length):
//!   `dz/dt = v − σ0·|v|·z/g(|v|)`, `g(s) = μd + (μs − μd)·e^(−(s/vs)²)`,
//!   the coefficient `σ0·z + σ1·dz/dt + σ2·v` along each direction of the
//!   slip (its speed smoothed as above where it has more than one); the
//!   coefficients STIFFNESS_COEFFICIENT, DAMPING_COEFFICIENT and
//!   VISCOUS_COEFFICIENT default to MotionSolve's 100, 0.316 and 0.0004
//!   (Adams' were not found); EFFECT = STICTION or SLIDING, which the
//!   model has no place for, is refused, and so is a coefficient of 0
//!   (the deflection's rate divides by `g`);
//! - `OVERLAP_DELTA = INCREASE` (`DECREASE`): the overlap is
//!   INITIAL_OVERLAP plus (less) the travel `DZ(I, J, J)` since the joint
//!   as the dataset draws it, at least INITIAL_OVERLAP/1000.
//!
//! A joint of another type, a missing or unknown JOINT, an input the joint
//! has not (a revolute or cylindrical joint's TORSIONAL_MOMENT, a
//! spherical joint's BENDING_MOMENT) and every bad value are errors.

use super::dataset::{linear_sum, literal};
use nalgebra::{UnitQuaternion, Vector3};

use crate::model::initial::number;
use crate::model::{Dataset, Statement, Value, is_kind};
use crate::scene::{Scene, Target};
use crate::simulate::SimulateError;
use crate::simulate::model::{Joint, JointKind};
use crate::span::Span;

/// A FRICTION statement read: the expressions its force and torque
/// components and its creep states are written as.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointFriction {
    /// The statement id.
    pub id: u64,
    /// Its index among the dataset's statements.
    pub statement: usize,
    /// The joint, an index into the model's joints.
    pub joint: usize,
    /// The friction on I along J's axes: force x, y, z, then torque x, y,
    /// z, `None` where it has none.
    pub components: [Option<String>; 6],
    /// Each creep's rate, `ds/dt`, one per direction of the slip, when
    /// stiction is on; [`creep`] stands for a state's input in them and in
    /// [`JointFriction::components`].
    pub creep_rates: Vec<String>,
    /// What `FRICTION(id, index)` gives, indices 1 to 22 (Adams Solver's
    /// FRICTION function), along or about the joint's J axes: 1–6 the
    /// force and torque on I (the components), 7–12 the coefficients (the
    /// friction over its load, signed as the friction), 13 the static
    /// coefficient's size while the slip is below
    /// STICTION_TRANSITION_VELOCITY (0 above it, and with EFFECT =
    /// SLIDING), 14–16 `VX VY VZ(I, J, J, J)`, 17–19 `WX WY WZ(I, J, J)`,
    /// 20–22 the creep along J's x, y and z axes (0 along an axis it has
    /// none: a turning joint's creep is the state's column only).
    pub outputs: Vec<String>,
}

/// What stands for the input of creep state `k` (from 0) in the written
/// expressions.
pub(crate) fn creep(k: usize) -> String {
    format!("{{creep{k}}}")
}

/// The FRICTION statements of `dataset` on `joints` (their markers in
/// `scene`); every problem added to `errors` at its place.
pub(crate) fn frictions(
    dataset: &Dataset,
    joints: &[Joint],
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Vec<JointFriction> {
    let mut frictions: Vec<JointFriction> = Vec::new();
    for (index, statement) in dataset.statements.iter().enumerate() {
        if !is_kind(&statement.name, "FRICTION") {
            continue;
        }
        match friction(statement, joints, scene) {
            Ok((joint, _, _, _))
                if let Some(first) = frictions.iter().find(|friction| friction.joint == joint) =>
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
            Ok((joint, components, creep_rates, outputs)) => frictions.push(JointFriction {
                id: statement.id.unwrap_or(0),
                statement: index,
                joint,
                components,
                creep_rates,
                outputs,
            }),
            Err(error) => errors.push(error),
        }
    }
    frictions
}

/// A keyword of one word: the words it can be, and how to say them.
struct Switch {
    keyword: &'static str,
    shortest: usize,
    taken: &'static [&'static str],
    words: &'static str,
}

/// The FRICTION's keywords of one word.
const SWITCHES: [Switch; 4] = [
    Switch {
        keyword: "FRICTION_MODEL",
        shortest: 10,
        taken: &["DEFAULT", "STICK_SLIP", "LUGRE"],
        words: "DEFAULT, STICK_SLIP or LUGRE",
    },
    Switch {
        keyword: "OVERLAP_DELTA",
        shortest: 7,
        taken: &["CONSTANT", "INCREASE", "DECREASE"],
        words: "CONSTANT, INCREASE or DECREASE",
    },
    Switch {
        keyword: "INACTIVE",
        shortest: 4,
        taken: &["STATIC"],
        words: "STATIC",
    },
    // The same, as Adams View 2015 writes it (and Adams Solver reads it).
    Switch {
        keyword: "INACTIVE_DURING",
        shortest: 10,
        taken: &["STATIC"],
        words: "STATIC",
    },
];

/// The joint, the components, the creep rates and the outputs of one
/// FRICTION.
type Read = (usize, [Option<String>; 6], Vec<String>, Vec<String>);

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
    // The inputs each joint's friction has: preload, reaction force,
    // bending moment, torsional moment.
    let available = match kind {
        JointKind::Translational => [true; 4],
        JointKind::Revolute | JointKind::Cylindrical | JointKind::Hooke | JointKind::Universal => {
            [true, true, true, false]
        }
        JointKind::Spherical => [true, true, false, false],
        _ => {
            return Err(model(
                format!(
                    "JOINT/{id} is a {name} joint: friction acts in TRANSLATIONAL, REVOLUTE, CYLINDRICAL, HOOKE, UNIVERSAL and SPHERICAL joints"
                ),
                argument.span,
            ));
        }
    };
    for switch in SWITCHES {
        let Some(argument) = statement.argument(switch.keyword, switch.shortest) else {
            continue;
        };
        match word(statement, switch.keyword, switch.shortest) {
            Some(word) if switch.taken.contains(&word.as_str()) => {}
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
    let or_more_than = |keyword: &str, default: f64| value(keyword, default, 0.0, true);
    let or_more = |keyword: &str| or_more_than(keyword, 0.0);
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
    let lugre = if word(statement, "FRICTION_MODEL", 10).as_deref() == Some("LUGRE") {
        if effect != Effect::All {
            return Err(unsupported(
                "takes EFFECT = STICTION or SLIDING with the LuGre model, which has both in its bristles: the effects apply to the stick-slip model (give EFFECT = ALL, or FRICTION_MODEL = DEFAULT)".to_string(),
                statement.place_of("EFFECT", 6),
            ));
        }
        if mu_static <= 0.0 || mu_dynamic <= 0.0 {
            let keyword = if mu_static <= 0.0 {
                "MU_STATIC"
            } else {
                "MU_DYNAMIC"
            };
            return Err(model(
                format!(
                    "the LuGre model divides by the Stribeck curve μd + (μs − μd)·e^(−(v/vs)²): give {keyword} above 0"
                ),
                statement.place_of(keyword, keyword.len()),
            ));
        }
        Some(LuGre {
            stiffness: positive("STIFFNESS_COEFFICIENT", LUGRE_DEFAULTS.stiffness)?,
            damping: or_more_than("DAMPING_COEFFICIENT", LUGRE_DEFAULTS.damping)?,
            viscous: or_more_than("VISCOUS_COEFFICIENT", LUGRE_DEFAULTS.viscous)?,
        })
    } else {
        None
    };
    let inputs = match inputs(statement).map_err(listed(
        "INPUTS is ALL, NONE or a list of PRELOAD, REACTION_FORCE, BENDING_MOMENT and TORSIONAL_MOMENT",
    ))? {
        Named::All => available,
        Named::These(named) => {
            if let Some(index) = (0..4).find(|&index| named[index] && !available[index]) {
                let has: Vec<&str> = (0..4)
                    .filter(|&index| available[index])
                    .map(|index| INPUT_NAMES[index])
                    .collect();
                return Err(model(
                    format!(
                        "{} is not an input of a {name} joint's friction: it has {}",
                        INPUT_NAMES[index],
                        has.join(", ")
                    ),
                    statement.place_of("INPUTS", 6),
                ));
            }
            named
        }
    };
    let [preload, force, bending, torsion] = inputs;
    let [i, j] = [joints[joint].i, joints[joint].j].map(|target| marker_id(scene, target));
    let reaction = |comp: u8, rm: u64| format!("JOINT({id},0,{comp},{rm})");
    // A load's magnitude, of one component too, is `SQRT` of the squares,
    // not `ABS`: a component that is 0 wherever the joint holds (a pin's
    // axial force in a planar swing on a skewed axis) is rounding noise,
    // and ABS's kink, a located switch, was crossed back and forth by it
    // (a pendulum on a skewed revolute pin with friction: 18 457 switches
    // and 52 s in 2 s with Radau5, against 24 and 0.4 s).
    let magnitude_of = |comps: &[u8], rm: u64| {
        let squares: Vec<String> = comps
            .iter()
            .map(|&comp| format!("{}**2", reaction(comp, rm)))
            .collect();
        format!("SQRT({})", squares.join(" + "))
    };
    // The load's terms INPUTS takes, each with its factor.
    let taken = |terms: Vec<(bool, f64, String)>| -> Vec<(f64, String)> {
        terms
            .into_iter()
            .filter(|(taken, _, _)| *taken)
            .map(|(_, factor, term)| (factor, term))
            .collect()
    };
    let scaled = |load: &[(f64, String)], by: f64| -> Vec<(f64, String)> {
        load.iter()
            .map(|(factor, term)| (factor * by, term.clone()))
            .collect()
    };
    let turning =
        |axis: char, radius: f64, rm: u64| format!("{}*W{axis}({i},{j},{rm})", literal(radius));
    let sliding = format!("VZ({i},{j},{j},{j})");
    // The bending moment's term of a sliding joint's load, the moment over
    // the overlap: INITIAL_OVERLAP throughout, or that plus or less the
    // travel along J's z axis since the joint as drawn (OVERLAP_DELTA =
    // INCREASE or DECREASE), held at a thousandth of INITIAL_OVERLAP where
    // the slider has all but left the joint (below it the term would grow
    // without bound, then turn negative).
    let over_overlap = |moment: String| -> Result<(f64, String), SimulateError> {
        let overlap = positive("INITIAL_OVERLAP", 1000.0)?;
        let sign = match word(statement, "OVERLAP_DELTA", 7).as_deref() {
            Some("INCREASE") => 1.0,
            Some("DECREASE") => -1.0,
            _ => return Ok((1.0 / overlap, moment)),
        };
        let [i_target, j_target] = [joints[joint].i, joints[joint].j];
        let at_start = overlap - sign * drawn_travel(scene, i_target, j_target);
        let travel = if sign > 0.0 { " + " } else { " - " };
        Ok((
            1.0,
            format!(
                "{moment}/MAX({}{travel}DZ({i},{j},{j}), {})",
                literal(at_start),
                literal(overlap / 1000.0)
            ),
        ))
    };
    // A revolute joint's pin turning about axis `axis` (0, 1, 2) of marker
    // `rm` (I or J): its torque load and its slip.
    let pin_of = |axis: usize, rm: u64, along: Along| -> Result<Slip, SimulateError> {
        let pin = positive("PIN_RADIUS", 1.0)?;
        let arm = positive("FRICTION_ARM", 1.0)?;
        let bending_arm = positive("BENDING_REACTION_ARM", 1.0)?;
        let across: Vec<u8> = (0..3u8)
            .filter(|&k| usize::from(k) != axis)
            .map(|k| k + 2)
            .collect();
        let bending_comps: &[u8] = if kind == JointKind::Revolute {
            &[6, 7]
        } else {
            &[6, 7, 8]
        };
        let load = taken(vec![
            (preload, or_more("FRICTION_TORQUE_PRELOAD")?, String::new()),
            (force, pin, magnitude_of(&across, rm)),
            (force, arm, magnitude_of(&[axis as u8 + 2], rm)),
            (bending, pin / bending_arm, magnitude_of(bending_comps, j)),
        ]);
        let letter = ['X', 'Y', 'Z'][axis];
        Ok(Slip {
            speed: turning(letter, pin, rm),
            load,
            along,
            limit: largest("MAX_FRICTION_TORQUE")?,
        })
    };
    // The friction's directions of slip, in groups that share one speed
    // (a cylindrical joint's slide and spin, a spherical joint's three
    // turns) and so one law; a Hooke or universal joint's two pins are two
    // groups.
    let groups: Vec<Vec<Slip>> = match kind {
        JointKind::Revolute => vec![vec![pin_of(2, j, Along::Component(5))?]],
        JointKind::Universal | JointKind::Hooke => {
            let [i_yoke, j_yoke] = yokes(statement, name)?;
            let ([i_axis, j_axis], j_slot) = if kind == JointKind::Universal {
                ([2, 2], 5)
            } else {
                ([0, 1], 4)
            };
            let mut pins = Vec::new();
            if i_yoke {
                pins.push(vec![pin_of(i_axis, i, Along::AxisOfI(i_axis))?]);
            }
            if j_yoke {
                pins.push(vec![pin_of(j_axis, j, Along::Component(j_slot))?]);
            }
            pins
        }
        JointKind::Cylindrical => {
            let pin = positive("PIN_RADIUS", 1.0)?;
            let (per_bending, bending_term) = over_overlap(magnitude_of(&[6, 7], j))?;
            let load = taken(vec![
                (
                    preload,
                    or_more("FRICTION_FORCE_PRELOAD")? + or_more("FRICTION_TORQUE_PRELOAD")? / pin,
                    String::new(),
                ),
                (force, 1.0, magnitude_of(&[2, 3], j)),
                (bending, per_bending, bending_term),
            ]);
            vec![vec![
                Slip {
                    speed: sliding,
                    load: load.clone(),
                    along: Along::Component(2),
                    limit: largest("MAX_FRICTION_FORCE")?,
                },
                Slip {
                    speed: turning('Z', pin, j),
                    load: scaled(&load, pin),
                    along: Along::Component(5),
                    limit: largest("MAX_FRICTION_TORQUE")?,
                },
            ]]
        }
        JointKind::Spherical => {
            let ball = positive("BALL_RADIUS", 1.0)?;
            let load = taken(vec![
                (preload, or_more("FRICTION_TORQUE_PRELOAD")?, String::new()),
                (force, ball, magnitude_of(&[2, 3, 4], j)),
            ]);
            let limit = largest("MAX_FRICTION_TORQUE")?;
            let turns = [('X', 3), ('Y', 4), ('Z', 5)].map(|(axis, slot)| Slip {
                speed: turning(axis, ball, j),
                load: load.clone(),
                along: Along::Component(slot),
                limit,
            });
            vec![turns.into()]
        }
        _ => {
            let (per_bending, bending_term) = over_overlap(magnitude_of(&[6, 7], j))?;
            let arm = positive("REACTION_ARM", 1.0)?;
            let load = taken(vec![
                (preload, or_more("FRICTION_FORCE_PRELOAD")?, String::new()),
                (force, 1.0, magnitude_of(&[2, 3], j)),
                (bending, per_bending, bending_term),
                (torsion, 1.0 / arm, magnitude_of(&[8], j)),
            ]);
            vec![vec![Slip {
                speed: sliding,
                load,
                along: Along::Component(2),
                limit: largest("MAX_FRICTION_FORCE")?,
            }]]
        }
    };
    let law = Law {
        effect,
        mu_static,
        mu_dynamic,
        vs,
        beta,
        deformation,
        lugre,
    };
    let mut components: [Option<String>; 6] = Default::default();
    let mut creep_rates = Vec::new();
    // For FRICTION(id, index): the coefficients along J's axes, their
    // squares, the groups' speeds and the creep along each axis.
    let mut along_axes: [Vec<String>; 6] = Default::default();
    let (mut squares, mut speeds) = (Vec::new(), Vec::new());
    let mut creep_along: [Option<usize>; 3] = [None; 3];
    for group in groups {
        let slips: Vec<String> = group.iter().map(|slip| slip.speed.clone()).collect();
        let first_creep = creep_rates.len();
        let written = law.coefficients(&slips, first_creep);
        let has_creep = !written.rates.is_empty();
        creep_rates.extend(written.rates);
        speeds.push(written.speed);
        for (k, (slip, coefficient)) in group.into_iter().zip(written.along).enumerate() {
            squares.push(format!("({coefficient})**2"));
            match slip.along {
                Along::Component(slot) => {
                    along_axes[slot].push(format!("-({coefficient})"));
                    if slot < 3 && has_creep {
                        creep_along[slot] = Some(first_creep + k);
                    }
                }
                Along::AxisOfI(axis) => {
                    for row in 0..3 {
                        along_axes[3 + row].push(format!(
                            "-({coefficient})*ORIENT(29,{},{i},{j})",
                            3 * axis + row + 1
                        ));
                    }
                }
            }
            let mut magnitude = format!("-({coefficient})*({})", linear_sum(&slip.load));
            if let Some(limit) = slip.limit {
                magnitude = format!(
                    "MIN(MAX({magnitude}, {}), {})",
                    literal(-limit),
                    literal(limit)
                );
            }
            let parts: Vec<(usize, String)> = match slip.along {
                Along::Component(slot) => vec![(slot, magnitude)],
                // I's axis in J's axes: a column of the direction cosines.
                Along::AxisOfI(axis) => (0..3)
                    .map(|row| {
                        let cosine = format!("ORIENT(29,{},{i},{j})", 3 * axis + row + 1);
                        (3 + row, format!("({magnitude})*{cosine}"))
                    })
                    .collect(),
            };
            for (slot, part) in parts {
                components[slot] = Some(match components[slot].take() {
                    Some(before) => format!("{before} + {part}"),
                    None => part,
                });
            }
        }
    }
    // FRICTION(id, index), indices 1 to 22 (Adams Solver's FRICTION
    // function).
    let speed = speeds
        .into_iter()
        .reduce(|one, other| format!("MAX({one}, {other})"))
        .unwrap_or_else(|| "0".to_string());
    let static_coefficient = match effect {
        Effect::Sliding => "0".to_string(),
        _ => format!(
            "IF({speed} - {}: SQRT({}), 0, 0)",
            literal(vs),
            squares.join(" + ")
        ),
    };
    let mut outputs: Vec<String> = components
        .iter()
        .map(|component| component.clone().unwrap_or_else(|| "0".to_string()))
        .collect();
    outputs.extend(along_axes.iter().map(|terms| sum(terms)));
    outputs.push(static_coefficient);
    outputs.extend(['X', 'Y', 'Z'].map(|axis| format!("V{axis}({i},{j},{j},{j})")));
    outputs.extend(['X', 'Y', 'Z'].map(|axis| format!("W{axis}({i},{j},{j})")));
    outputs.extend(creep_along.map(|k| k.map_or_else(|| "0".to_string(), creep)));
    Ok((joint, components, creep_rates, outputs))
}

/// One direction of a joint's slip: its speed on the surface of contact
/// (as text), the load its friction is the coefficient times (each term
/// with its factor), the direction the friction acts along, and its
/// largest size (MAX_FRICTION_FORCE or TORQUE) when given.
struct Slip {
    speed: String,
    load: Vec<(f64, String)>,
    along: Along,
    limit: Option<f64>,
}

/// The direction a friction acts along, in J's axes.
#[derive(Clone, Copy)]
enum Along {
    /// One of [`JointFriction::components`] (force x, y, z, torque x, y,
    /// z).
    Component(usize),
    /// A torque about axis 0, 1 or 2 of the I marker (a Hooke or universal
    /// joint's pin fixed in I's part), which turns in J's axes.
    AxisOfI(usize),
}

/// The pins of a Hooke or universal joint a FRICTION acts in, I's and
/// J's: the one its `I_YOKE` or `J_YOKE` names (a bare keyword, or with a
/// value, which is not read), both when it names neither, an error when it
/// names both.
fn yokes(statement: &Statement, name: &str) -> Result<[bool; 2], SimulateError> {
    let named = ["I_YOKE", "J_YOKE"].map(|keyword| statement.argument(keyword, 3).is_some());
    match named {
        [false, false] => Ok([true, true]),
        [true, true] => Err(SimulateError::Model {
            message: format!(
                "{}: give one of I_YOKE and J_YOKE (the yoke whose pin the friction acts in), or neither for both pins of the {name} joint",
                statement.label(),
            ),
            span: statement.place_of("J_YOKE", 3),
        }),
        one => Ok(one),
    }
}

/// The friction law of a FRICTION: its effects, coefficients, stiction
/// transition velocity `vs`, transition velocity coefficient `β`, largest
/// creep `δ`, and the LuGre model's coefficients when it takes that model.
struct Law {
    effect: Effect,
    mu_static: f64,
    mu_dynamic: f64,
    vs: f64,
    beta: f64,
    deformation: f64,
    lugre: Option<LuGre>,
}

/// The LuGre coefficients a FRICTION leaves out: MotionSolve's documented
/// defaults for its joint friction (`bristle_stiffness` 100,
/// `damping_effects` 0.316, `viscous_effects` 0.0004: Canudas de Wit's
/// example divided by a load of 1 000); Adams' own were not found.
const LUGRE_DEFAULTS: LuGre = LuGre {
    stiffness: 100.0,
    damping: 0.316,
    viscous: 0.0004,
};

/// The coefficients of the LuGre model (`FRICTION_MODEL = LUGRE`), each
/// per unit of the load: the bristles' stiffness `σ0`
/// (STIFFNESS_COEFFICIENT, per length), their damping `σ1`
/// (DAMPING_COEFFICIENT, time per length) and the viscous coefficient `σ2`
/// (VISCOUS_COEFFICIENT, time per length).
#[derive(Clone, Copy)]
struct LuGre {
    stiffness: f64,
    damping: f64,
    viscous: f64,
}

impl Law {
    /// The coefficient of friction along each direction of the slip whose
    /// speeds are `slips` (the friction is `−coefficient·N`), and the
    /// creep states' rates (none without stiction). One direction: the
    /// coefficient odd in the slip `v`, its speed `|v|`; more: the speed
    /// `|v|` smoothed to `√(|v|² + ε²) − ε`, `ε = vs/1000`, and each
    /// sliding coefficient `μ(|v|)·vₖ/√(|v|² + ε²)`, so that the friction
    /// opposes the slip and is 0 (no NaN) at rest. The creep states are
    /// numbered from `first_creep` (a joint's earlier groups have theirs).
    fn coefficients(&self, slips: &[String], first_creep: usize) -> Coefficients {
        let (vs, beta) = (self.vs, self.beta);
        let (peak, end) = match self.effect {
            Effect::All => (self.mu_static, self.mu_dynamic),
            Effect::Stiction => (self.mu_static, 0.0),
            Effect::Sliding => (self.mu_dynamic, self.mu_dynamic),
        };
        // The sliding coefficient at `x`, odd in `x` (its negative half
        // left out for a speed, which is never below 0).
        let sliding_at = |x: &str, odd: bool| {
            sum(&[
                step(x, -vs, -peak, vs, peak),
                step(x, vs, 0.0, beta * vs, end - peak),
                if odd {
                    step(x, -beta * vs, peak - end, -vs, 0.0)
                } else {
                    String::new()
                },
            ])
        };
        let v: Vec<String> = slips.iter().map(|slip| format!("({slip})")).collect();
        let (speed, sliding) = if let [one] = v.as_slice() {
            (format!("ABS{one}"), vec![sliding_at(one, true)])
        } else {
            let epsilon = vs / 1000.0;
            let squares: Vec<String> = v.iter().map(|each| format!("{each}**2")).collect();
            let norm = format!(
                "SQRT({} + {})",
                squares.join(" + "),
                literal(epsilon * epsilon)
            );
            let speed = format!("({norm} - {})", literal(epsilon));
            let mu = sliding_at(&speed, false);
            let sliding = v
                .iter()
                .map(|each| format!("({mu})*{each}/{norm}"))
                .collect();
            (speed, sliding)
        };
        if let Some(lugre) = self.lugre {
            let (along, rates) = self.lugre_coefficients(lugre, &v, &speed, first_creep);
            return Coefficients {
                along,
                rates,
                speed,
            };
        }
        if self.effect == Effect::Sliding {
            return Coefficients {
                along: sliding,
                rates: Vec::new(),
                speed,
            };
        }
        let weight = format!("STEP({speed}, 0, 0, {}, 1)", literal(vs));
        let (mut coefficients, mut rates) = (Vec::new(), Vec::new());
        for (k, (each, sliding)) in v.iter().zip(sliding).enumerate() {
            let creep = creep(first_creep + k);
            let rate = format!("{each} - {speed}*{creep}/{}", literal(self.deformation));
            coefficients.push(format!(
                "(1 - {weight})*({}*{creep} + {}*({rate})) + {weight}*({sliding})",
                literal(self.mu_static / self.deformation),
                literal(self.mu_static / vs)
            ));
            rates.push(rate);
        }
        Coefficients {
            along: coefficients,
            rates,
            speed,
        }
    }
}

/// What [`Law::coefficients`] writes for one group of slip directions.
struct Coefficients {
    /// The coefficient along each direction (the friction is
    /// `−coefficient·N`).
    along: Vec<String>,
    /// The creep states' rates, none without stiction.
    rates: Vec<String>,
    /// The slip's speed.
    speed: String,
}

impl Law {
    /// The LuGre model's coefficient along each direction of the slip
    /// (velocities `v`, speed `speed`) and its bristles' rates: the
    /// deflection `z` along each direction (a creep state) moves as
    /// `dz/dt = v − σ0·|v|·z/g(|v|)`, `g(s) = μd + (μs − μd)·e^(−(s/vs)²)`
    /// (the Stribeck curve), and the coefficient is `σ0·z + σ1·dz/dt +
    /// σ2·v` (Canudas de Wit et al., 1995, per unit of the load): at a
    /// steady slip `g(|v|) + σ2·|v|` against it, at rest a spring of
    /// stiffness `σ0` per unit of the load that gives way at `μs`.
    fn lugre_coefficients(
        &self,
        lugre: LuGre,
        v: &[String],
        speed: &str,
        first_creep: usize,
    ) -> (Vec<String>, Vec<String>) {
        let stribeck = format!(
            "({} + {}*EXP(-({speed}/{})**2))",
            literal(self.mu_dynamic),
            literal(self.mu_static - self.mu_dynamic),
            literal(self.vs)
        );
        let (mut coefficients, mut rates) = (Vec::new(), Vec::new());
        for (k, each) in v.iter().enumerate() {
            let deflection = creep(first_creep + k);
            let rate = format!(
                "{each} - {}*{speed}*{deflection}/{stribeck}",
                literal(lugre.stiffness)
            );
            coefficients.push(format!(
                "{}*{deflection} + {}*({rate}) + {}*{each}",
                literal(lugre.stiffness),
                literal(lugre.damping),
                literal(lugre.viscous)
            ));
            rates.push(rate);
        }
        (coefficients, rates)
    }
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

/// The inputs of a friction's load, in the order of [`INPUT_NAMES`].
type Inputs = [bool; 4];

/// The inputs' names.
const INPUT_NAMES: [&str; 4] = [
    "PRELOAD",
    "REACTION_FORCE",
    "BENDING_MOMENT",
    "TORSIONAL_MOMENT",
];

/// The inputs INPUTS names.
enum Named {
    /// `ALL` (or INPUTS left out): all the joint's inputs.
    All,
    /// These (`NONE`: none).
    These(Inputs),
}

/// `INPUTS`: ALL when left out; the span of a value that is none of its
/// words.
fn inputs(statement: &Statement) -> Result<Named, Span> {
    let Some((words, span)) = words(statement, "INPUTS", 6) else {
        return Ok(Named::All);
    };
    let known =
        |word: &String| word == "ALL" || word == "NONE" || INPUT_NAMES.contains(&word.as_str());
    if words.is_empty() || !words.iter().all(known) {
        return Err(span);
    }
    if words.iter().any(|word| word == "ALL") {
        return Ok(Named::All);
    }
    Ok(Named::These(
        INPUT_NAMES.map(|name| words.iter().any(|word| word == name)),
    ))
}

/// The id a joint's marker has in expressions (`0` for ground itself).
/// `DZ(I, J, J)` with the parts where the dataset draws them: the travel
/// of I's origin from J's along J's z axis.
fn drawn_travel(scene: &Scene, i: Target, j: Target) -> f64 {
    let z_of_j = match j {
        Target::Ground => Vector3::z(),
        Target::Marker(index) => {
            let marker = &scene.markers[index];
            let body = marker.body.map(|body| scene.bodies[body].orientation);
            body.unwrap_or_else(UnitQuaternion::identity) * marker.orientation * Vector3::z()
        }
    };
    (scene.origin(i) - scene.origin(j)).dot(&z_of_j)
}

fn marker_id(scene: &Scene, target: Target) -> u64 {
    match target {
        Target::Ground => 0,
        Target::Marker(index) => scene.markers[index].id.unwrap_or(0),
    }
}
