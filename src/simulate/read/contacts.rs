//! The `CONTACT` statements between solids (`TYPE = SOLID_TO_SOLID`, or
//! `SPHERE_TO_PLANE` and `SPHERE_TO_SPHERE` with those shapes) with
//! the IMPACT normal force and optional Coulomb friction, and the GRAPHICS
//! statements that give their solids: a sphere (`ELLIPSOID` of equal
//! scales, which are diameters), a `BOX`, a `CYLINDER`, a `FRUSTUM` (a
//! cone when a radius is 0) and a `PLANE` (two planes, a frustum against
//! a round solid and two cylinders whose axes are not parallel are
//! refused). A
//! contact that lists several solids on a side is one contact for each
//! pair.

use std::collections::HashMap;

use nalgebra::{UnitQuaternion, Vector3};

use crate::model::initial::{number, number_list};
use crate::model::{Dataset, Statement, Value, is_kind};
use crate::scene::{Scene, Target};
use crate::simulate::error::SimulateError;
use crate::simulate::model::{Contact, Friction, Shape, Solid};

/// What a refused contact meets, said once for all the contacts it stops
/// (the grouped summary counts them).
const SHAPES: &str =
    "mbexpr meets spheres (ELLIPSOID of equal scales), BOXes, CYLINDERs, FRUSTUMs and PLANEs";

/// The contact types mbexpr simulates: between solids, and the sphere's
/// two Adams View types, which are solid contacts of particular shapes.
const TYPES: [&str; 3] = ["SOLID_TO_SOLID", "SPHERE_TO_PLANE", "SPHERE_TO_SPHERE"];

/// The sine of the largest angle between two cylinders' axes that are
/// taken for parallel (the equations of the contact hold them within it,
/// [`crate::simulate::equations`]' contact geometry).
const PARALLEL: f64 = crate::simulate::model::PARALLEL_AXES;

/// The most pairs of solids one contact may list (each is a force the run
/// evaluates at every step).
const MOST_PAIRS: usize = 10_000;

/// The contacts of `dataset`, each pair of its solids one [`Contact`];
/// what cannot be read is recorded in `errors` at its place.
pub(super) fn contacts(
    dataset: &Dataset,
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Vec<Contact> {
    let graphics: HashMap<u64, &Statement> = dataset
        .statements
        .iter()
        .filter(|statement| is_kind(&statement.name, "GRAPHICS"))
        .filter_map(|statement| Some((statement.id?, statement)))
        .collect();
    let mut contacts = Vec::new();
    for statement in &dataset.statements {
        if !is_kind(&statement.name, "CONTACT") {
            continue;
        }
        match contact(statement, &graphics, scene) {
            Ok(pairs) => contacts.extend(pairs),
            Err(error) => errors.push(error),
        }
    }
    contacts
}

/// A refusal of `statement` for `reason` at `span`.
fn refused(statement: &Statement, reason: String, span: crate::span::Span) -> SimulateError {
    SimulateError::Unsupported {
        statement: statement.label(),
        reason,
        span,
    }
}

/// The word a keyword is set to (`TYPE = SOLID_TO_SOLID`), upper case.
fn word(statement: &Statement, keyword: &str) -> Option<String> {
    Some(super::word_of(statement.argument(keyword, keyword.len().min(6))?).unwrap_or_default())
}

fn contact(
    statement: &Statement,
    graphics: &HashMap<u64, &Statement>,
    scene: &Scene,
) -> Result<Vec<Contact>, SimulateError> {
    let label = statement.label();
    for keyword in [
        "NORMAL_FUNCTION",
        "NORMAL_ROUTINE",
        "FRICTION_FUNCTION",
        "FRICTION_ROUTINE",
        "POISSON",
        "AUGMENTED_LAGRANGIAN_FORMULATION",
        "IFLEX",
        "JFLEX",
        "IEDGE",
        "JEDGE",
        "IFLIP_GEOMETRY",
        "JFLIP_GEOMETRY",
        "IFLIP_NORMAL",
        "JFLIP_NORMAL",
    ] {
        if let Some(argument) = statement.argument(keyword, keyword.len()) {
            return Err(refused(
                statement,
                format!(
                    "has {keyword}, which mbexpr does not simulate (it simulates solid-to-solid contacts with the IMPACT normal force and Coulomb friction)"
                ),
                argument.span,
            ));
        }
    }
    let kind = word(statement, "TYPE").unwrap_or_else(|| "SOLID_TO_SOLID".to_string());
    let type_span = statement.place_of("TYPE", 4);
    if !TYPES.contains(&kind.as_str()) {
        return Err(refused(
            statement,
            "is not TYPE = SOLID_TO_SOLID, SPHERE_TO_PLANE or SPHERE_TO_SPHERE, the contacts mbexpr simulates (curves, points and flexible bodies are not)".to_string(),
            type_span,
        ));
    }
    let positive = |keyword: &str, what: &str| -> Result<f64, SimulateError> {
        let value = number(statement, keyword, f64::NAN).unwrap_or(f64::NAN);
        if value > 0.0 && value.is_finite() {
            return Ok(value);
        }
        Err(SimulateError::Model {
            message: format!("{label}: give {keyword} = a positive number ({what})"),
            span: statement.place_of(keyword, keyword.len().min(4)),
        })
    };
    let stiffness = positive("STIFFNESS", "the force per depth to the EXPONENT")?;
    let damping = number(statement, "DAMPING", 0.0)
        .ok()
        .filter(|damping| *damping >= 0.0 && damping.is_finite())
        .ok_or_else(|| SimulateError::Model {
            message: format!("{label}: DAMPING is a number, zero or more"),
            span: statement.place_of("DAMPING", 4),
        })?;
    let exponent = positive(
        "EXPONENT",
        "the power of the depth; Adams suggests 2.2 for metals",
    )?;
    let damping_depth = positive("DMAX", "the depth at which the damping is full")?;
    let friction = friction(statement)?;
    let [i_solids, j_solids] =
        ["IGEOM", "JGEOM"].map(|keyword| solids(statement, keyword, graphics, scene));
    let (i_solids, j_solids) = (i_solids?, j_solids?);
    let count = i_solids.len() * j_solids.len();
    if count > MOST_PAIRS {
        return Err(SimulateError::Model {
            message: format!(
                "{label}: IGEOM and JGEOM list {} × {} = {count} pairs of solids; mbexpr holds at most {MOST_PAIRS} in one contact: split it, or merge solids",
                i_solids.len(),
                j_solids.len()
            ),
            span: statement.span,
        });
    }
    let mut pairs = Vec::new();
    for i in &i_solids {
        for j in &j_solids {
            check_pair(statement, i, j, scene)?;
            let sphere = |solid: &Solid| matches!(solid.shape, Shape::Sphere { .. });
            let fits = match kind.as_str() {
                "SPHERE_TO_PLANE" => {
                    sphere(&i.0) && matches!(j.0.shape, Shape::HalfSpace)
                        || sphere(&j.0) && matches!(i.0.shape, Shape::HalfSpace)
                }
                "SPHERE_TO_SPHERE" => sphere(&i.0) && sphere(&j.0),
                _ => true,
            };
            if !fits {
                return Err(SimulateError::Model {
                    message: format!(
                        "{label}: TYPE = {kind} needs {}",
                        if kind == "SPHERE_TO_PLANE" {
                            "a sphere (an ELLIPSOID of equal scales) and a PLANE"
                        } else {
                            "two spheres (ELLIPSOIDs of equal scales)"
                        }
                    ),
                    span: type_span,
                });
            }
            pairs.push(Contact {
                i: i.0.clone(),
                j: j.0.clone(),
                stiffness,
                exponent,
                damping,
                damping_depth,
                friction,
                id: statement.id.unwrap_or(0),
                span: statement.span,
            });
        }
    }
    Ok(pairs)
}

/// The friction a contact asks for: `COULOMB_FRICTION = ON` (or
/// `DYNAMICS_ONLY`, the same in a dynamic run: the coefficient is zero at
/// zero slip), or on by default when the coefficients are given.
fn friction(statement: &Statement) -> Result<Option<Friction>, SimulateError> {
    let label = statement.label();
    let given = ["MU_STATIC", "MU_DYNAMIC"]
        .iter()
        .any(|keyword| statement.argument(keyword, keyword.len()).is_some());
    let on = match word(statement, "COULOMB_FRICTION").as_deref() {
        None => given,
        Some("OFF") => false,
        Some("ON" | "DYNAMICS_ONLY" | "DYNAMICSONLY") => true,
        Some(_) => {
            let span = statement.place_of("COULOMB_FRICTION", 7);
            return Err(SimulateError::Model {
                message: format!("{label}: COULOMB_FRICTION is ON, OFF or DYNAMICS_ONLY"),
                span,
            });
        }
    };
    if !on {
        return Ok(None);
    }
    let value = |keyword: &str, what: &str, zero_allowed: bool| {
        let value = number(statement, keyword, f64::NAN).unwrap_or(f64::NAN);
        if value.is_finite() && (value > 0.0 || (zero_allowed && value == 0.0)) {
            return Ok(value);
        }
        Err(SimulateError::Model {
            message: format!("{label}: with friction on, give {keyword} = {what}"),
            span: statement.place_of(keyword, keyword.len()),
        })
    };
    let static_coefficient = value("MU_STATIC", "the static coefficient, 0 or more", true)?;
    let dynamic_coefficient = value("MU_DYNAMIC", "the dynamic coefficient, 0 or more", true)?;
    let stiction_velocity = value(
        "STICTION_TRANSITION_VELOCITY",
        "the slip speed of full static friction, above 0",
        false,
    )?;
    let friction_velocity = value(
        "FRICTION_TRANSITION_VELOCITY",
        "the slip speed of full dynamic friction, above STICTION_TRANSITION_VELOCITY",
        false,
    )?;
    if friction_velocity <= stiction_velocity {
        return Err(SimulateError::Model {
            message: format!(
                "{label}: FRICTION_TRANSITION_VELOCITY must exceed STICTION_TRANSITION_VELOCITY"
            ),
            span: statement.place_of("FRICTION_TRANSITION_VELOCITY", 8),
        });
    }
    Ok(Some(Friction {
        static_coefficient,
        dynamic_coefficient,
        stiction_velocity,
        friction_velocity,
    }))
}

/// The solids a side of a contact lists (`IGEOM = 3, 4`), each with the
/// place it is named at.
fn solids(
    statement: &Statement,
    keyword: &str,
    graphics: &HashMap<u64, &Statement>,
    scene: &Scene,
) -> Result<Vec<(Solid, crate::span::Span)>, SimulateError> {
    let missing = || SimulateError::Model {
        message: format!(
            "{}: give {keyword} = the ids of GRAPHICS statements of one part",
            statement.label()
        ),
        span: statement.place_of(keyword, keyword.len()),
    };
    let argument = statement
        .argument(keyword, keyword.len())
        .ok_or_else(missing)?;
    let ids = number_list(statement, argument).map_err(|_| missing())?;
    let mut solids = Vec::new();
    for id in ids {
        let found = (id.fract() == 0.0 && id > 0.0)
            .then(|| graphics.get(&(id as u64)))
            .flatten();
        let Some(graphic) = found else {
            return Err(SimulateError::Model {
                message: format!(
                    "{}: {keyword} names GRAPHICS/{id}, which the model does not have",
                    statement.label()
                ),
                span: argument.span,
            });
        };
        let solid = solid(graphic, scene).map_err(|reason| {
            refused(
                statement,
                format!("meets {reason}; {SHAPES}"),
                argument.span,
            )
        })?;
        solids.push((solid, argument.span));
    }
    Ok(solids)
}

/// The solid a GRAPHICS statement draws, or what it is that a contact
/// cannot meet (said without its id, so that the contacts it stops are
/// counted together; the place names it).
fn solid(graphic: &Statement, scene: &Scene) -> Result<Solid, String> {
    let has = |keyword: &str| graphic.argument(keyword, keyword.len()).is_some();
    let value = |keyword: &str| {
        number(graphic, keyword, f64::NAN)
            .ok()
            .filter(|value| value.is_finite())
    };
    let marker = |keyword: &str| {
        super::named_marker(graphic, keyword, scene)
            .ok_or_else(|| format!("a GRAPHICS whose {keyword} names no MARKER"))
    };
    let bad = |what: &str| what.to_string();
    if has("ELLIPSOID") {
        let scales = ["XSCALE", "YSCALE", "ZSCALE"].map(value);
        let [Some(x), Some(y), Some(z)] = scales else {
            return Err(bad("an ELLIPSOID without its three scales"));
        };
        if x <= 0.0 || y <= 0.0 || z <= 0.0 {
            return Err(bad("an ELLIPSOID whose scales are not all positive"));
        }
        if x != y || y != z {
            return Err(bad("an ELLIPSOID of unequal scales (not a sphere)"));
        }
        return Ok(Solid {
            marker: marker("CM")?,
            shape: Shape::Sphere { radius: x / 2.0 },
        });
    }
    if has("BOX") {
        let sizes = ["X", "Y", "Z"].map(value);
        let [Some(x), Some(y), Some(z)] = sizes else {
            return Err(bad("a BOX without its X, Y and Z"));
        };
        let size = Vector3::new(x, y, z);
        if size.iter().any(|length| *length == 0.0) {
            return Err(bad("a flat BOX (an edge of length 0)"));
        }
        return Ok(Solid {
            marker: marker("CORNER")?,
            shape: Shape::Block {
                lower: size.map(|length| length.min(0.0)),
                upper: size.map(|length| length.max(0.0)),
            },
        });
    }
    if has("CYLINDER") {
        let (Some(length), Some(radius)) = (value("LENGTH"), value("RADIUS")) else {
            return Err(bad("a CYLINDER without its LENGTH and RADIUS"));
        };
        if has("RANGLE") {
            return Err(bad("a part of a CYLINDER (RANGLE)"));
        }
        if length == 0.0 || radius <= 0.0 {
            return Err(bad("a CYLINDER of no length or radius"));
        }
        return Ok(Solid {
            marker: marker("CM")?,
            shape: round(length, [radius, radius]),
        });
    }
    if has("FRUSTUM") {
        let (Some(length), Some(bottom), Some(top)) =
            (value("LENGTH"), value("BOTTOM"), value("TOP"))
        else {
            return Err(bad("a FRUSTUM without its LENGTH, BOTTOM and TOP"));
        };
        if has("RANGLE") {
            return Err(bad("a part of a FRUSTUM (RANGLE)"));
        }
        if length == 0.0 || bottom < 0.0 || top < 0.0 || bottom.max(top) == 0.0 {
            return Err(bad(
                "a FRUSTUM of no length, a negative radius or two radii of 0",
            ));
        }
        return Ok(Solid {
            marker: marker("CM")?,
            shape: round(length, [bottom, top]),
        });
    }
    if has("PLANE") {
        return Ok(Solid {
            marker: marker("RM")?,
            shape: Shape::HalfSpace,
        });
    }
    let kind = graphic
        .arguments
        .iter()
        .find(|argument| matches!(argument.value, Value::Flag))
        .map_or("a shape", |argument| argument.keyword.as_str());
    if kind == "EXTERNAL" {
        return Err(bad(
            "a solid read from a file (EXTERNAL), which mbexpr does not read",
        ));
    }
    Err(format!("a {kind}"))
}

/// A round solid `length` along its marker's z from its origin, of radius
/// `radii[0]` there and `radii[1]` at its other end (a negative length
/// puts that end below the marker).
fn round(length: f64, [at_marker, at_end]: [f64; 2]) -> Shape {
    Shape::Frustum {
        radii: if length > 0.0 {
            [at_marker, at_end]
        } else {
            [at_end, at_marker]
        },
        bottom: length.min(0.0),
        top: length.max(0.0),
    }
}

/// Refuses a pair the contact geometry does not meet: solids on one part,
/// two planes, a frustum against a round solid, two cylinders whose axes
/// are not parallel where the model is drawn.
fn check_pair(
    statement: &Statement,
    (i, i_span): &(Solid, crate::span::Span),
    (j, _): &(Solid, crate::span::Span),
    scene: &Scene,
) -> Result<(), SimulateError> {
    let body = |solid: &Solid| scene.body_of(&solid.marker);
    if body(i) == body(j) {
        return Err(SimulateError::Model {
            message: format!(
                "{}: IGEOM and JGEOM are solids of one part, which cannot touch each other",
                statement.label()
            ),
            span: *i_span,
        });
    }
    let round = |solid: &Solid| matches!(solid.shape, Shape::Frustum { .. });
    let cylinder =
        |solid: &Solid| matches!(solid.shape, Shape::Frustum { radii, .. } if radii[0] == radii[1]);
    let plane = |solid: &Solid| matches!(solid.shape, Shape::HalfSpace);
    // A solid's z axis in ground, where the model is drawn.
    let axis = |solid: &Solid| match solid.marker {
        Target::Ground => Vector3::z(),
        Target::Marker(index) => {
            let marker = &scene.markers[index];
            let turn = marker.body.map_or_else(UnitQuaternion::identity, |body| {
                scene.bodies[body].orientation
            });
            turn * marker.orientation * Vector3::z()
        }
    };
    let reason = if plane(i) && plane(j) {
        Some(format!("meets two PLANEs; {SHAPES}"))
    } else if round(i) && round(j) && !(cylinder(i) && cylinder(j)) {
        Some(
            "meets two round solids, one a FRUSTUM; mbexpr meets a frustum with a sphere, a BOX or a PLANE, and two CYLINDERs with parallel axes"
                .to_string(),
        )
    } else if round(i) && round(j) && axis(i).cross(&axis(j)).norm() > PARALLEL {
        Some(
            "meets two CYLINDERs whose axes are not parallel; mbexpr meets two cylinders side by side (rollers, pins), their axes parallel"
                .to_string(),
        )
    } else {
        None
    };
    match reason {
        Some(reason) => Err(refused(statement, reason, *i_span)),
        None => Ok(()),
    }
}
