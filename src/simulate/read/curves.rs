//! `PTCV` and `CVCV` statements of a dataset, with the `CURVE` and
//! `MATRIX` statements their curves are made of.

use std::collections::HashMap;

use nalgebra::Vector3;

use crate::model::initial::{number, number_list, numbers};
use crate::model::{Dataset, Statement, Value, is_kind};
use crate::scene::{Scene, Target};
use crate::simulate::SimulateError;
use crate::simulate::curve::{Curve, MAX_ORDER};
use crate::simulate::model::{CurvePair, Joint, JointKind, OnCurve};
use crate::span::Span;

/// The PTCV statements of `dataset` as joints, their markers found in
/// `scene` (the floating ones in `floating`, by id with their bodies),
/// every problem added to `errors` at its place.
pub(crate) fn point_curves(
    dataset: &Dataset,
    scene: &Scene,
    floating: &HashMap<u64, Option<usize>>,
    errors: &mut Vec<SimulateError>,
) -> Vec<Joint> {
    let mut joints = Vec::new();
    for statement in &dataset.statements {
        if is_kind(&statement.name, "PTCV") {
            joints.extend(point_curve(dataset, statement, scene, floating, errors));
        }
    }
    joints
}

fn point_curve(
    dataset: &Dataset,
    statement: &Statement,
    scene: &Scene,
    floating: &HashMap<u64, Option<usize>>,
    errors: &mut Vec<SimulateError>,
) -> Option<Joint> {
    let label = statement.label();
    let model_error = |message: String, span: Span| SimulateError::Model { message, span };
    let speed = given_speed(statement, "VEL", errors);
    let mut marker = |keyword: &str| fixed_marker(statement, keyword, scene, errors);
    let i = marker("I");
    let rm = marker("RM");
    let float = floating_body(statement, "JFLOAT", floating, errors);
    let curve = statement_curve(dataset, statement, "CURVE", errors);
    let (i, rm, float, (curve, _)) = (i?, rm?, float?, curve?);
    if scene.body_of(&rm) != float {
        errors.push(model_error(
            format!(
                "{label}: JFLOAT and RM must be markers of the same part: the curve is drawn in RM's axes and the floating marker moves on that part"
            ),
            statement.place_of("JFLOAT", 2),
        ));
        return None;
    }
    if scene.body_of(&i) == scene.body_of(&rm) {
        errors.push(model_error(
            format!(
                "{label}: its I marker and its curve are on one part: a PTCV holds a point of one part on a curve of another"
            ),
            statement.span,
        ));
        return None;
    }
    let start = start_parameter(statement, ["DISP", "ICM"], scene, rm, &curve, errors)?;
    Some(Joint {
        id: statement.id.unwrap_or(0),
        kind: JointKind::PointCurve,
        i,
        j: rm,
        pitch: 0.0,
        curve: Some(OnCurve {
            curve,
            frame: rm,
            start,
            speed,
        }),
        pair: None,
        redundant: Vec::new(),
        span: statement.span,
    })
}

/// The CVCV statements of `dataset` as joints (I the IRM marker, J the
/// JRM marker), their markers found in `scene` (the floating ones in
/// `floating`), every problem added to `errors` at its place.
pub(crate) fn curve_pairs(
    dataset: &Dataset,
    scene: &Scene,
    floating: &HashMap<u64, Option<usize>>,
    errors: &mut Vec<SimulateError>,
) -> Vec<Joint> {
    dataset
        .statements
        .iter()
        .filter(|statement| is_kind(&statement.name, "CVCV"))
        .filter_map(|statement| curve_pair(dataset, statement, scene, floating, errors))
        .collect()
}

/// One side of a CVCV: `ICURVE`, `IRM`, `IFLOAT`, `IDISP`, `IICM`, `IVEL`
/// (`side` "I") or their J twins.
fn curve_side(
    dataset: &Dataset,
    statement: &Statement,
    side: &str,
    scene: &Scene,
    floating: &HashMap<u64, Option<usize>>,
    errors: &mut Vec<SimulateError>,
) -> Option<OnCurve> {
    let label = statement.label();
    let word = |name: &str| format!("{side}{name}");
    let speed = given_speed(statement, &word("VEL"), errors);
    let frame = fixed_marker(statement, &word("RM"), scene, errors);
    let float = floating_body(statement, &word("FLOAT"), floating, errors);
    let found = statement_curve(dataset, statement, &word("CURVE"), errors);
    let (frame, float, (curve, curve_statement)) = (frame?, float?, found?);
    if scene.body_of(&frame) != float {
        errors.push(SimulateError::Model {
            message: format!(
                "{label}: {side}FLOAT and {side}RM must be markers of the same part: the curve is drawn in {side}RM's axes and the floating marker moves on that part"
            ),
            span: statement.place_of(&word("FLOAT"), 2),
        });
        return None;
    }
    let order = number(curve_statement, "ORDER", 4.0).unwrap_or(4.0);
    let lifted = (0..=64)
        .map(|k| curve.at(&(-1.0 + f64::from(k) / 32.0)).place.z.abs())
        .fold(0.0, f64::max);
    let problem = if order < 4.0 {
        Some(format!(
            "{label}: CURVE/{} has ORDER = {order}: a CVCV's point of contact crosses its curves' knots, so it needs curves whose tangents and bends are continuous there (ORDER 4 or more)",
            curve.id
        ))
    } else if lifted > 0.0 {
        Some(format!(
            "{label}: CURVE/{} leaves the x-y plane of {side}RM (a z coordinate of {lifted:e}): a CVCV's curves are planar, their z coordinates zero",
            curve.id
        ))
    } else {
        None
    };
    if let Some(message) = problem {
        errors.push(SimulateError::Model {
            message,
            span: statement.place_of(&word("CURVE"), 2),
        });
        return None;
    }
    let start = start_parameter(
        statement,
        [&word("DISP"), &word("ICM")],
        scene,
        frame,
        &curve,
        errors,
    )?;
    Some(OnCurve {
        curve,
        frame,
        start,
        speed,
    })
}

fn curve_pair(
    dataset: &Dataset,
    statement: &Statement,
    scene: &Scene,
    floating: &HashMap<u64, Option<usize>>,
    errors: &mut Vec<SimulateError>,
) -> Option<Joint> {
    let label = statement.label();
    let i = curve_side(dataset, statement, "I", scene, floating, errors);
    let j = curve_side(dataset, statement, "J", scene, floating, errors);
    let (i, j) = (i?, j?);
    let refuse = |message: String| SimulateError::Model {
        message: format!("{label}: {message}"),
        span: statement.span,
    };
    if scene.body_of(&i.frame) == scene.body_of(&j.frame) {
        errors.push(refuse(
            "its two curves are on one part: a CVCV holds a curve of one part against a curve of another".to_string(),
        ));
        return None;
    }
    // Each marker's z axis in ground, as drawn.
    let normal = |target: &Target| match target {
        Target::Ground => Vector3::z(),
        Target::Marker(index) => {
            let marker = &scene.markers[*index];
            let body = marker
                .body
                .map_or_else(nalgebra::UnitQuaternion::identity, |body| {
                    scene.bodies[body].orientation
                });
            body * marker.orientation * Vector3::z()
        }
    };
    let tilt = normal(&i.frame).cross(&normal(&j.frame)).norm();
    if tilt > PLANE_TILT {
        errors.push(refuse(format!(
            "its curves are not in one plane: the z axes of IRM and JRM are {:.3} degrees apart, where a CVCV's curves lie in one plane (the z axes parallel)",
            tilt.asin().to_degrees()
        )));
        return None;
    }
    Some(Joint {
        id: statement.id.unwrap_or(0),
        kind: JointKind::CurveCurve,
        i: i.frame,
        j: j.frame,
        pitch: 0.0,
        curve: None,
        pair: Some(Box::new(CurvePair { i, j })),
        redundant: Vec::new(),
        span: statement.span,
    })
}

/// The sine of the largest angle between the planes of a CVCV's curves
/// (the z axes of IRM and JRM) as read: drawing's rounding.
const PLANE_TILT: f64 = 1e-9;

/// The parameter of the curve's point nearest `statement`'s DISP (given
/// in the axes of its ICM marker, or of `rm`), where the initial analysis
/// places the point of contact, as Adams does; `Some(None)` without DISP,
/// `None` when DISP or ICM cannot be read (the error in `errors`). `DISP`
/// and `ICM` are `keywords`' words (a CVCV's IDISP and IICM, JDISP and
/// JICM).
fn start_parameter(
    statement: &Statement,
    [disp, icm]: [&str; 2],
    scene: &Scene,
    rm: Target,
    curve: &Curve,
    errors: &mut Vec<SimulateError>,
) -> Option<Option<f64>> {
    let Some(argument) = statement.argument(disp, disp.len()) else {
        return Some(None);
    };
    let label = statement.label();
    let Ok([x, y, z]) = numbers(statement, disp, [0.0; 3]) else {
        errors.push(SimulateError::Model {
            message: format!("{label}: {disp} = x, y, z: three numbers"),
            span: argument.span,
        });
        return None;
    };
    let place = |target: Target| match target {
        Target::Ground => (Vector3::zeros(), nalgebra::Matrix3::identity()),
        Target::Marker(index) => {
            let marker = &scene.markers[index];
            (
                marker.position,
                marker.orientation.to_rotation_matrix().into_inner(),
            )
        }
    };
    let within = match statement.argument(icm, icm.len()) {
        None => rm,
        Some(argument) => match super::named_marker(statement, icm, scene) {
            Some(target) if scene.body_of(&target) == scene.body_of(&rm) => target,
            _ => {
                errors.push(SimulateError::Model {
                        message: format!(
                            "{label}: {icm} must name a fixed MARKER on the part of the curve's marker ({disp} is given in its axes)"
                        ),
                        span: argument.span,
                    });
                return None;
            }
        },
    };
    let (origin, axes) = place(within);
    let (rm_origin, rm_axes) = place(rm);
    let point = rm_axes.transpose() * (origin + axes * Vector3::new(x, y, z) - rm_origin);
    match curve.nearest(&point) {
        Some(alpha) if curve.closed || alpha.abs() <= 1.0 => Some(Some(alpha)),
        _ => {
            errors.push(SimulateError::Model {
                message: format!(
                    "{label}: {disp} lies beyond an end of CURVE/{}: give a point by the curve",
                    curve.id
                ),
                span: argument.span,
            });
            None
        }
    }
}

/// The body of `statement`'s floating marker `keyword` (JFLOAT, IFLOAT)
/// (`Some(None)` for one on ground), or `None` when it names none.
fn floating_body(
    statement: &Statement,
    keyword: &str,
    floating: &HashMap<u64, Option<usize>>,
    errors: &mut Vec<SimulateError>,
) -> Option<Option<usize>> {
    let id = number(statement, keyword, f64::NAN)
        .ok()
        .filter(|id| id.fract() == 0.0 && *id > 0.0);
    let body = id.and_then(|id| floating.get(&(id as u64)).copied());
    if body.is_none() {
        errors.push(SimulateError::Model {
            message: format!(
                "{}: {keyword} must name a floating MARKER (MARKER/id, PART = ..., FLOATING) on the part of the curve",
                statement.label()
            ),
            span: statement.place_of(keyword, 2),
        });
    }
    body
}

/// The statement of kind `kind` whose id is `keyword`'s value in
/// `statement`.
fn named<'d>(
    dataset: &'d Dataset,
    statement: &Statement,
    keyword: &str,
    kind: &str,
) -> Option<&'d Statement> {
    let id = number(statement, keyword, f64::NAN).unwrap_or(f64::NAN);
    dataset.statements.iter().find(|named| {
        is_kind(&named.name, kind) && named.id.is_some_and(|found| found as f64 == id)
    })
}

/// The curve `statement`'s `keyword` (CURVE, ICURVE, JCURVE) names, and
/// the CURVE statement.
fn statement_curve<'d>(
    dataset: &'d Dataset,
    statement: &Statement,
    keyword: &str,
    errors: &mut Vec<SimulateError>,
) -> Option<(Curve, &'d Statement)> {
    let Some(found) = named(dataset, statement, keyword, "CURVE") else {
        errors.push(SimulateError::Model {
            message: format!(
                "{}: {keyword} must name a CURVE statement of the model",
                statement.label()
            ),
            span: statement.place_of(keyword, 2),
        });
        return None;
    };
    curve(dataset, found)
        .map_err(|error| errors.push(error))
        .ok()
        .map(|curve| (curve, found))
}

/// The speed along the curve `statement`'s `keyword` (VEL, IVEL, JVEL)
/// gives, if it gives one (a problem added to `errors`).
fn given_speed(
    statement: &Statement,
    keyword: &str,
    errors: &mut Vec<SimulateError>,
) -> Option<f64> {
    let argument = statement.argument(keyword, keyword.len())?;
    match number(statement, keyword, f64::NAN) {
        Ok(speed) if speed.is_finite() => Some(speed),
        _ => {
            errors.push(SimulateError::Model {
                message: format!(
                    "{}: {keyword} = the initial speed along the curve: one number",
                    statement.label()
                ),
                span: argument.span,
            });
            None
        }
    }
}

/// The fixed marker `statement`'s `keyword` names (a problem added to
/// `errors` when it names none).
fn fixed_marker(
    statement: &Statement,
    keyword: &str,
    scene: &Scene,
    errors: &mut Vec<SimulateError>,
) -> Option<Target> {
    super::needed_marker(
        statement,
        keyword,
        scene,
        errors,
        &format!("{keyword} must name a fixed MARKER of the model"),
    )
}

/// The curve of CURVE statement `statement`.
fn curve(dataset: &Dataset, statement: &Statement) -> Result<Curve, SimulateError> {
    let label = statement.label();
    let refused = |reason: String, span: Span| SimulateError::Unsupported {
        statement: label.clone(),
        reason,
        span,
    };
    let wrong = |message: String, span: Span| SimulateError::Model {
        message: format!("{label}: {message}"),
        span,
    };
    if let Some(argument) = statement.argument("FUNCTION", 3) {
        return Err(refused(
            "is given by FUNCTION = USER(...), which calls CURSUB, the user subroutine an Adams solver loads from the user's library and mbexpr cannot call: give the curve's points in a MATRIX".to_string(),
            argument.span,
        ));
    }
    let Some(matrix_argument) = statement.argument("MATRIX", 3) else {
        return Err(wrong(
            "needs MATRIX = the id of a MATRIX of its points".to_string(),
            statement.span,
        ));
    };
    let matrix = named(dataset, statement, "MATRIX", "MATRIX").ok_or_else(|| {
        wrong(
            "MATRIX must name a MATRIX statement of the model".to_string(),
            matrix_argument.span,
        )
    })?;
    let points = matrix_points(matrix)?;
    let order = number(statement, "ORDER", 4.0)
        .ok()
        .filter(|order| order.fract() == 0.0 && (2.0..=MAX_ORDER as f64).contains(order));
    let Some(order) = order else {
        return Err(wrong(
            format!("ORDER must be a whole number from 2 (straight pieces) to {MAX_ORDER}"),
            statement.place_of("ORDER", 3),
        ));
    };
    let closed = statement.argument("CLOSED", 3).is_some();
    let through = statement.argument("CURVE_POINTS", 3).is_some();
    Curve::new(
        statement.id.unwrap_or(0),
        &points,
        order as usize,
        closed,
        through,
    )
    .map_err(|reason| wrong(reason, statement.span))
}

/// The rows of MATRIX `statement` as points: three columns (x, y, z in the
/// curve's axes), one row a point.
fn matrix_points(statement: &Statement) -> Result<Vec<Vector3<f64>>, SimulateError> {
    let label = statement.label();
    let wrong = |message: String, span: Span| SimulateError::Model {
        message: format!("{label}: {message}"),
        span,
    };
    if let Some(argument) = statement.argument("FILE", 3) {
        return Err(SimulateError::Unsupported {
            statement: label.clone(),
            reason: "reads its values from a file, which mbexpr does not read: give them as VALUES"
                .to_string(),
            span: argument.span,
        });
    }
    let count = |keyword: &str| {
        number(statement, keyword, f64::NAN)
            .ok()
            .filter(|count| count.fract() == 0.0 && *count >= 1.0 && *count <= 1e6)
            .map(|count| count as usize)
            .ok_or_else(|| {
                wrong(
                    format!("{keyword} must be a whole number from 1 to 1000000"),
                    statement.place_of(keyword, 3),
                )
            })
    };
    let (rows, columns) = (count("ROWS")?, count("COLUMNS")?);
    if columns != 3 {
        return Err(wrong(
            format!("a curve's MATRIX has 3 columns (x, y, z of each point), not {columns}"),
            statement.place_of("COLUMNS", 3),
        ));
    }
    let values_argument = statement
        .argument("VALUES", 3)
        .ok_or_else(|| wrong("needs VALUES".to_string(), statement.span))?;
    let values = number_list(statement, values_argument).map_err(|error| SimulateError::Model {
        message: error.to_string(),
        span: error.span(),
    })?;
    let mut entries = vec![0.0; rows * 3];
    if statement.argument("SPARSE", 3).is_some() {
        let indices = |keyword: &str, limit: usize| -> Result<Vec<usize>, SimulateError> {
            let argument = statement.argument(keyword, keyword.len()).ok_or_else(|| {
                wrong(
                    format!(
                        "a SPARSE matrix needs {keyword} = the entries' {}",
                        if keyword == "I" { "rows" } else { "columns" }
                    ),
                    statement.span,
                )
            })?;
            let listed = number_list(statement, argument).unwrap_or_default();
            listed
                .iter()
                .map(|index| {
                    (index.fract() == 0.0 && *index >= 1.0 && *index <= limit as f64)
                        .then(|| *index as usize - 1)
                        .ok_or_else(|| {
                            wrong(
                                format!("{keyword} lists {index}, outside 1 to {limit}"),
                                argument.span,
                            )
                        })
                })
                .collect()
        };
        let (row_of, column_of) = (indices("I", rows)?, indices("J", 3)?);
        if row_of.len() != values.len() || column_of.len() != values.len() {
            return Err(wrong(
                "I, J and VALUES list one entry each, so they have as many items".to_string(),
                values_argument.span,
            ));
        }
        for ((row, column), value) in row_of.iter().zip(&column_of).zip(&values) {
            entries[row * 3 + column] = *value;
        }
    } else {
        if values.len() != rows * 3 {
            return Err(wrong(
                format!(
                    "VALUES lists {} numbers where ROWS = {rows} and COLUMNS = 3 ask for {}",
                    values.len(),
                    rows * 3
                ),
                values_argument.span,
            ));
        }
        let by_columns = matches!(
            statement.argument("FULL", 3).map(|argument| &argument.value),
            Some(Value::List(items)) if items.len() == 1
                && items[0].text.trim().eq_ignore_ascii_case("CORDER")
        );
        for (k, value) in values.iter().enumerate() {
            let (row, column) = if by_columns {
                (k % rows, k / rows)
            } else {
                (k / 3, k % 3)
            };
            entries[row * 3 + column] = *value;
        }
    }
    Ok(entries
        .chunks(3)
        .map(|point| Vector3::new(point[0], point[1], point[2]))
        .collect())
}
