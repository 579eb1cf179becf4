//! The two equations of a `PTCV`: the I marker's origin on a curve drawn
//! in the axes of the RM marker.
//!
//! In RM's axes the I marker's origin is at `ρ` (three [`Row`]s, exact
//! with their rates and biases). The point of contact is the curve's point
//! nearest it, at the parameter `α(ρ)` where `s'(α) · (ρ − s(α)) = 0`;
//! the equations are the offset `e = ρ − s(α)` along the two normals `n₁,
//! n₂` square to the tangent there (`n₁` the part of a fixed axis square to
//! the tangent, `n₂ = t × n₁`):
//!
//! ```text
//! g_k(ρ) = n_k(α(ρ)) · (ρ − s(α(ρ)))
//! ∇g_k  = n_k + (n_k' · e) ∂α/∂ρ,        ∂α/∂ρ = s' / (|s'|² − s'' · e)
//! g_k'' = ∇g_k · ρ'' + 2 (n_k' · ρ') α' + (n_k · s'') α'²   (on the curve)
//! ```
//!
//! (`'` on `n` and `s` a derivative in `α`; `α' = ∂α/∂ρ · ρ'`). The
//! parameter is found in plain numbers and carried over dual numbers by one
//! Newton step on its equation, so the rows carry their exact derivatives.

use nalgebra::Vector3;

use super::rows::{BodyMotion, Row};
use crate::number::Number;
use crate::simulate::curve::Curve;
use crate::simulate::model::{Joint, Model, OnCurve};

/// The two equations of PTCV `joint` on `on`, bodies moving as `bodies`
/// say, on piece `piece` of the curve when one is given (their values not
/// a number where the curve has no point near I's origin, or, on a held
/// piece, where I has run past an open curve's end).
pub(super) fn curve_rows<T: Number>(
    model: &Model,
    joint: &Joint,
    on: &OnCurve,
    bodies: &[BodyMotion<T>],
    piece: Option<usize>,
) -> Vec<Row<T>> {
    let i = super::frame(model, &joint.i, bodies);
    let rm = super::frame(model, &on.frame, bodies);
    let apart = i.origin.minus(&rm.origin);
    let local: Vec<Row<T>> = rm.axes.iter().map(|axis| axis.dot(&apart)).collect();
    let vector = |part: fn(&Row<T>) -> &T| {
        Vector3::new(
            part(&local[0]).clone(),
            part(&local[1]).clone(),
            part(&local[2]).clone(),
        )
    };
    let place = vector(|row| &row.value);
    let rate = vector(|row| &row.rate);
    let bias = vector(|row| &row.bias);
    let curve = &on.curve;
    let point = place.map(|v| v.value());
    let nearest = match piece {
        Some(piece) => curve.nearest_on(&point, piece),
        None => curve.nearest(&point),
    };
    // Within a run's step (a piece held) a point past an open curve's end
    // has left the curve; outside one (the assembly, the projections) the
    // end pieces are continued, so that a point drawn past an end can be
    // put back on the curve.
    let alpha = match nearest {
        Some(alpha) if piece.is_none() || !off_the_ends(curve, alpha) => alpha,
        _ => return vec![failed(), failed()],
    };
    // One Newton step on s'(α) · (ρ − s(α)) = 0 carries α's derivatives.
    let at = curve.at_on(&alpha, piece);
    let (offset, tangent, bend) = (
        place.clone() - at.place.map(T::from),
        at.tangent.map(T::from),
        at.bend.map(T::from),
    );
    let slope = tangent.dot(&offset);
    let curvature = bend.dot(&offset).value() - at.tangent.norm_squared();
    let alpha = T::from(alpha) - slope / T::from(curvature);
    let at = curve.at_on(&alpha, piece);
    let offset = place - &at.place;
    let speed = at.tangent.norm();
    let unit = &at.tangent / speed.clone();
    let unit_turn = (&at.bend - &unit * unit.dot(&at.bend)) / speed.clone();
    let reference = curve.reference(alpha.value(), piece).map(T::from);
    let along = reference.dot(&unit);
    let square = &reference - &unit * along.clone();
    let length = square.norm();
    let first = &square / length.clone();
    let square_turn = -(&unit_turn * along) - &unit * reference.dot(&unit_turn);
    let first_turn = (&square_turn - &first * first.dot(&square_turn)) / length;
    let second = unit.cross(&first);
    let second_turn = unit_turn.cross(&first) + unit.cross(&first_turn);
    let alpha_gradient = &at.tangent / (at.tangent.norm_squared() - at.bend.dot(&offset));
    let alpha_rate = alpha_gradient.dot(&rate);
    [(first, first_turn), (second, second_turn)]
        .into_iter()
        .map(|(normal, turn)| {
            let gradient = &normal + &alpha_gradient * turn.dot(&offset);
            let mut row = Row {
                value: normal.dot(&offset),
                rate: gradient.dot(&rate),
                bias: gradient.dot(&bias)
                    + turn.dot(&rate) * alpha_rate.clone() * T::from(2.0)
                    + normal.dot(&at.bend) * alpha_rate.clone() * alpha_rate.clone(),
                coefficients: Vec::new(),
            };
            for (k, component) in local.iter().enumerate() {
                row = row.plus_coefficients(component, &gradient[k]);
            }
            row
        })
        .collect()
}

/// The equation that puts PTCV `joint`'s point of contact at the
/// parameter `start` of its curve (its DISP), in the initial analysis of
/// the positions: the parameter of the curve's point nearest I's origin
/// less `start` (for a closed curve, in the period nearest it), its row
/// that of `α(ρ)`, `∂α/∂ρ = s' / (|s'|² − s'' · e)`, so that Newton's
/// iterations move the point along the curve.
pub(super) fn start_row(
    model: &Model,
    joint: &Joint,
    on: &OnCurve,
    start: f64,
    bodies: &[BodyMotion<f64>],
) -> Row<f64> {
    match parameter_row(model, joint, on, bodies) {
        Some((row, alpha)) => started(row, alpha, start, &on.curve),
        None => failed(),
    }
}

/// The row `row` of a curve's parameter `alpha` (its value 0, its rate
/// `α'`) made the equation that puts the parameter at `start`: its value
/// `alpha − start`, for a closed curve in the period nearest it.
pub(super) fn started(mut row: Row<f64>, alpha: f64, start: f64, curve: &Curve) -> Row<f64> {
    let mut away = alpha - start;
    if curve.closed {
        away -= 2.0 * (away / 2.0).round();
    }
    row.value = away;
    row
}

/// The equation that gives PTCV `joint`'s point of contact the speed
/// `speed` along its curve (its VEL: I's origin relative to an observer
/// on the curve at the point of contact, positive towards the curve's
/// greater parameters), in the initial analysis of the velocities: its
/// rate `|s'| α' − speed`, its row that of `α(ρ)` times `|s'|`.
pub(super) fn speed_row(
    model: &Model,
    joint: &Joint,
    on: &OnCurve,
    speed: f64,
    bodies: &[BodyMotion<f64>],
) -> Row<f64> {
    match parameter_row(model, joint, on, bodies) {
        Some((row, alpha)) => sped(row, alpha, speed, &on.curve),
        None => failed(),
    }
}

/// The row `row` of a curve's parameter `alpha` (its value 0, its rate
/// `α'`) made the equation that gives the point of contact the speed
/// `speed` along the curve: its rate `|s'| α' − speed`, its row times
/// `|s'|`, its value 0.
pub(super) fn sped(row: Row<f64>, alpha: f64, speed: f64, curve: &Curve) -> Row<f64> {
    let length = curve.at(&alpha).tangent.norm();
    let mut row = row.scaled(length);
    row.value = 0.0;
    row.rate -= speed;
    row
}

/// The row of the parameter `α(ρ)` of the curve's point nearest I's
/// origin, `∂α/∂ρ = s' / (|s'|² − s'' · e)` (its value 0, its rate `α'`),
/// and the parameter; `None` where the curve has no point near it.
fn parameter_row(
    model: &Model,
    joint: &Joint,
    on: &OnCurve,
    bodies: &[BodyMotion<f64>],
) -> Option<(Row<f64>, f64)> {
    let i = super::frame(model, &joint.i, bodies);
    let rm = super::frame(model, &on.frame, bodies);
    let apart = i.origin.minus(&rm.origin);
    let local: Vec<Row<f64>> = rm.axes.iter().map(|axis| axis.dot(&apart)).collect();
    let place = Vector3::new(local[0].value, local[1].value, local[2].value);
    let alpha = on.curve.nearest(&place)?;
    let at = on.curve.at(&alpha);
    let gradient = at.tangent / (at.tangent.norm_squared() - at.bend.dot(&(place - at.place)));
    let mut row = Row::zero();
    for (k, component) in local.iter().enumerate() {
        row.rate += component.rate * gradient[k];
        row = row.plus_coefficients(component, &gradient[k]);
    }
    Some((row, alpha))
}

/// The parameter of the point of contact of PTCV `joint` on `on` at the
/// state `bodies` give (`None` where none is found).
pub(super) fn contact_parameter(
    model: &Model,
    joint: &Joint,
    on: &OnCurve,
    bodies: &[BodyMotion<f64>],
) -> Option<f64> {
    on.curve.nearest(&local_place(model, joint, on, bodies))
}

/// I's origin in RM's axes, from RM's origin.
fn local_place<T: Number>(
    model: &Model,
    joint: &Joint,
    on: &OnCurve,
    bodies: &[BodyMotion<T>],
) -> Vector3<f64> {
    let i = super::frame(model, &joint.i, bodies);
    let rm = super::frame(model, &on.frame, bodies);
    let apart = i.origin.minus(&rm.origin);
    Vector3::from_fn(|k, _| rm.axes[k].dot(&apart).value.value())
}

/// Whether PTCV `joint`'s I marker has run past an end of its open curve
/// at the state `bodies` give.
pub(super) fn past_an_end<T: Number>(
    model: &Model,
    joint: &Joint,
    on: &OnCurve,
    bodies: &[BodyMotion<T>],
) -> bool {
    on.curve
        .nearest(&local_place(model, joint, on, bodies))
        .is_some_and(|alpha| off_the_ends(&on.curve, alpha))
}

/// Whether `alpha` lies past an end of `curve`, an open curve, by more than
/// rounding's room: there the point of contact has left the curve.
pub(super) fn off_the_ends(curve: &Curve, alpha: f64) -> bool {
    !curve.closed && alpha.abs() > 1.0 + PAST_END
}

/// How far past ±1 an open curve's parameter may go before the point of
/// contact is off the curve: rounding's room.
const PAST_END: f64 = 1e-9;

/// A row whose value is not a number: the curve has no point of contact.
pub(super) fn failed<T: Number>() -> Row<T> {
    Row {
        value: T::from(f64::NAN),
        rate: T::zero(),
        bias: T::zero(),
        coefficients: Vec::new(),
    }
}
