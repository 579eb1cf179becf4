//! The two equations of a `CVCV`: a curve drawn in the x-y plane of the
//! IRM marker (ICURVE) kept in contact with, and tangent to, a curve drawn
//! in the x-y plane of the JRM marker (JCURVE).
//!
//! What Adams documents (the CVCV statement,
//! <https://adams.thisaray.com/adams_solver/fstate_cvcv.html>): the two
//! planar curves stay in contact and tangent at the point of contact; they
//! must lie in the same plane, though their parts may move in three
//! dimensions; each curve's z coordinates are zero in its marker's axes;
//! IDISP and JDISP give the initial point of contact on each curve (the
//! curve's point nearest the one given), and without them the contact
//! starts at the point of ICURVE nearest JCURVE; IVEL and JVEL give the
//! speed of the point of contact along each curve at the start; the
//! floating markers IFLOAT and JFLOAT sit at the point of contact, and the
//! reaction `CVCV(id, jflag, comp, rm)` is the load on IFLOAT (jflag 0) or
//! JFLOAT (jflag 1).
//!
//! What mbexpr chose: the two curves' parameters `α` (ICURVE) and `β`
//! (JCURVE) are not unknowns of the run but found, at each state, where the
//! tangents are parallel and the points face each other across the normal
//! of ICURVE, both measured in IRM's x-y plane (JCURVE, drawn through JRM's
//! axes, seen in IRM's: `P(β) = o + A s_J(β)`):
//!
//! ```text
//! F₁ = s_I'(α) × P'(β) · z = 0        (the tangents parallel)
//! F₂ = s_I'(α) · (s_I(α) − P(β)) = 0  (the points across the normal)
//! ```
//!
//! and the equations are the gap across the normal `n = z × s_I'/|s_I'|`
//! and the plane:
//!
//! ```text
//! g₁ = n(α) · (s_I(α) − P(β))         (the curves touch)
//! g₂ = z_IRM · (o_JRM − o_IRM)        (JRM's origin, so JCURVE, in IRM's plane)
//! ```
//!
//! Where `F = 0`, `∂g₁/∂α = n' · (s_I − P) = 0` and `∂g₁/∂β = −n · P' = 0`
//! (the common normal's gap is stationary in the contact's parameters), so
//! `g₁`'s rate and row of `G` are those of `g₁` at fixed parameters; its
//! bias adds `2 (∂²g₁/∂α∂u · u) α' + 2 (∂²g₁/∂β∂u · u) β' + g_αα α'² +
//! 2 g_αβ α' β' + g_ββ β'²` (`g_αα = −g₁ |n'|² + 2 n' · s_I' + n · s_I''`,
//! `g_αβ = −n' · P'`, `g_ββ = −n · P''`), with `(α', β')` from `F' = 0`.
//! The parameters are found in plain numbers (the nearest pair of the two
//! curves' samples, refined by Newton's iterations on `F`) and carried
//! over dual numbers by one Newton step, so the rows carry their exact
//! derivatives. So a CVCV removes two freedoms, as a PTCV does: the gap in
//! the plane and the plane's offset; Adams' documentation does not count
//! them, and the second repeats what a cam's revolute and a follower's
//! translational joint hold already, where it is left out as redundant.
//! JCURVE's plane is held parallel to ICURVE's by the model's other joints
//! (read checks that it is at the start; a JCURVE that tilts is met as its
//! shadow on ICURVE's plane).
//!
//! The contact's knots are located switches, as a PTCV's are: within a
//! step each curve is held on the piece its point of contact was on at
//! the step's start (its polynomial continued past the piece's ends), and
//! the run locates the point's crossing of a knot, where the curve's third
//! derivative jumps (its points, tangents and bends are continuous there
//! on the curves of ORDER 4 and more a CVCV takes). Where the point of
//! contact runs past an end of an open curve, the equations fail and the
//! run stops at that CVCV, at that time.

use nalgebra::Vector3;

use super::drives::Pieces;
use super::on_curve::{failed, off_the_ends, sped, started};
use super::rows::{BodyMotion, Moving, Row};
use crate::number::Number;
use crate::simulate::curve::{Curve, CurvePoint};
use crate::simulate::model::{CurvePair, Joint, Model, OnCurve};

/// The two equations of CVCV `joint` on `pair`, bodies moving as `bodies`
/// say, each curve on the piece `pieces` holds it on where it does (their
/// values not a number where no point of contact is found, or where it
/// has run past an end of an open curve).
pub(super) fn curve_rows<T: Number>(
    model: &Model,
    joint: &Joint,
    pair: &CurvePair,
    bodies: &[BodyMotion<T>],
    pieces: Pieces,
) -> Vec<Row<T>> {
    let seen = Seen::new(model, joint, bodies);
    let Some(contact) = Contact::find(pair, &seen, pieces) else {
        return vec![failed(), failed()];
    };
    let gap = contact.gap(&seen);
    let [_, _, plane] = seen.origin;
    vec![gap, plane]
}

/// The equations that put CVCV `joint`'s point of contact at the
/// parameters its IDISP and JDISP set (those given, in that order), in the
/// initial analysis of the positions.
pub(super) fn start_rows(
    model: &Model,
    joint: &Joint,
    pair: &CurvePair,
    bodies: &[BodyMotion<f64>],
) -> Vec<Row<f64>> {
    parameter_rows(model, joint, pair, bodies, |on| on.start, started)
}

/// The equations that give CVCV `joint`'s point of contact the speeds its
/// IVEL and JVEL give along each curve (those given, in that order), in
/// the initial analysis of the velocities.
pub(super) fn speed_rows(
    model: &Model,
    joint: &Joint,
    pair: &CurvePair,
    bodies: &[BodyMotion<f64>],
) -> Vec<Row<f64>> {
    parameter_rows(model, joint, pair, bodies, |on| on.speed, sped)
}

/// For each curve that `given` gives a number, `make` of the curve's
/// parameter row (its value 0, its rate the parameter's), the parameter,
/// the number and the curve; rows that fail where no point of contact is
/// found.
fn parameter_rows(
    model: &Model,
    joint: &Joint,
    pair: &CurvePair,
    bodies: &[BodyMotion<f64>],
    given: fn(&OnCurve) -> Option<f64>,
    make: fn(Row<f64>, f64, f64, &Curve) -> Row<f64>,
) -> Vec<Row<f64>> {
    let sides = [&pair.i, &pair.j];
    let seen = Seen::new(model, joint, bodies);
    let Some(contact) = Contact::find(pair, &seen, [None; 2]) else {
        return sides
            .iter()
            .filter(|on| given(on).is_some())
            .map(|_| failed())
            .collect();
    };
    sides
        .into_iter()
        .zip(contact.parameter_rows())
        .zip([contact.alpha, contact.beta])
        .filter_map(|((on, row), parameter)| {
            given(on).map(|number| make(row, parameter, number, &on.curve))
        })
        .collect()
}

/// The point of contact of CVCV `joint` in ground at the state `bodies`
/// give (where IFLOAT and JFLOAT sit), when one is found.
pub(super) fn contact_point(
    model: &Model,
    joint: &Joint,
    pair: &CurvePair,
    bodies: &[BodyMotion<f64>],
) -> Option<Vector3<f64>> {
    let seen = Seen::new(model, joint, bodies);
    let (alpha, _) = parameters(pair, &seen.placement().plain(), [None; 2])?;
    let local = pair.i.curve.at(&alpha).place;
    let irm = super::frame(model, &joint.i, bodies);
    let axis = |k: usize| Vector3::from_fn(|m, _| irm.axes[k].component(m).value);
    let origin = Vector3::from_fn(|m, _| irm.origin.component(m).value);
    Some(origin + axis(0) * local.x + axis(1) * local.y + axis(2) * local.z)
}

/// The id of the open curve whose end CVCV `joint`'s point of contact has
/// run past at the state `bodies` give, if it has.
pub(super) fn past_an_end<T: Number>(
    model: &Model,
    joint: &Joint,
    pair: &CurvePair,
    bodies: &[BodyMotion<T>],
) -> Option<u64> {
    let seen = Seen::new(model, joint, bodies);
    let (alpha, beta) = parameters(pair, &seen.placement().plain(), [None; 2])?;
    [(&pair.i.curve, alpha), (&pair.j.curve, beta)]
        .into_iter()
        .find(|(curve, parameter)| off_the_ends(curve, *parameter))
        .map(|(curve, _)| curve.id)
}

/// How far CVCV `joint`'s curves are from bending alike at their point of
/// contact at the state `bodies` give: the difference of their curvatures
/// there (JCURVE's taken along ICURVE's direction) over the sum of their
/// sizes, 0 where they conform (a pin filling its hole, a flat on a flat),
/// where the point of contact is not unique and `∂F/∂(α, β)`, whose
/// determinant is `|s_I'|⁵ λ² (κ_I − sign(λ) κ_J)` (`P' = λ s_I'`), is
/// singular. The point is the curves' nearest samples refined by Newton's
/// iterations as far as they go; `None` where the curves have no samples.
pub(super) fn conformity<T: Number>(
    model: &Model,
    joint: &Joint,
    pair: &CurvePair,
    bodies: &[BodyMotion<T>],
) -> Option<f64> {
    let placement = Seen::new(model, joint, bodies).placement().plain();
    let ((alpha, beta), _) = iterated(pair, &placement, [None; 2])?;
    let i = pair.i.curve.at(&alpha);
    let j = pair.j.curve.at(&beta);
    let tangent = placement.direction(&j.tangent);
    let bend = placement.direction(&j.bend);
    let curvature =
        |tangent: &Vector3<f64>, bend: &Vector3<f64>| cross(tangent, bend) / tangent.norm().powi(3);
    let ours = curvature(&i.tangent, &i.bend);
    let theirs = curvature(&tangent, &bend) * i.tangent.dot(&tangent).signum();
    let size = ours.abs() + theirs.abs();
    Some(if size > 0.0 {
        (ours - theirs).abs() / size
    } else {
        0.0
    })
}

/// JRM seen from IRM: its origin (from IRM's) and its x and y axes, each
/// component along IRM's axes a [`Row`].
struct Seen<T: Number> {
    origin: [Row<T>; 3],
    x: [Row<T>; 3],
    y: [Row<T>; 3],
}

impl<T: Number> Seen<T> {
    /// JRM (`joint`'s J marker) seen from IRM (its I marker), bodies
    /// moving as `bodies` say.
    fn new(model: &Model, joint: &Joint, bodies: &[BodyMotion<T>]) -> Seen<T> {
        let irm = super::frame(model, &joint.i, bodies);
        let jrm = super::frame(model, &joint.j, bodies);
        let along = |vector: &Moving<T>| [0, 1, 2].map(|k| irm.axes[k].dot(vector));
        Seen {
            origin: along(&jrm.origin.minus(&irm.origin)),
            x: along(&jrm.axes[0]),
            y: along(&jrm.axes[1]),
        }
    }

    /// Its values.
    fn placement(&self) -> Placement<T> {
        let value = |rows: &[Row<T>; 3]| Vector3::from_fn(|k, _| rows[k].value.clone());
        Placement {
            origin: value(&self.origin),
            x: value(&self.x),
            y: value(&self.y),
        }
    }

    /// The row of `weights · (o + A s)` (`o` JRM's origin, `A s` the
    /// vector `s` of JRM's axes, both in IRM's), `o` left out unless
    /// `with_origin`: `s` and `weights` held still.
    fn along(&self, weights: &Vector3<T>, s: &Vector3<T>, with_origin: bool) -> Row<T> {
        let mut row = Row::zero();
        for k in 0..3 {
            row = row
                .plus_times(&self.x[k], &(weights[k].clone() * s.x.clone()))
                .plus_times(&self.y[k], &(weights[k].clone() * s.y.clone()));
            if with_origin {
                row = row.plus_times(&self.origin[k], &weights[k]);
            }
        }
        row
    }
}

/// JRM's origin and x and y axes in IRM's axes (values only).
struct Placement<T: Number> {
    origin: Vector3<T>,
    x: Vector3<T>,
    y: Vector3<T>,
}

impl<T: Number> Placement<T> {
    /// Its values in plain numbers.
    fn plain(&self) -> Placement<f64> {
        Placement {
            origin: self.origin.map(|v| v.value()),
            x: self.x.map(|v| v.value()),
            y: self.y.map(|v| v.value()),
        }
    }

    /// The vector `s` of JRM's axes (its z part zero) in IRM's.
    fn direction(&self, s: &Vector3<T>) -> Vector3<T> {
        &self.x * s.x.clone() + &self.y * s.y.clone()
    }

    /// The point `s` of JRM's axes in IRM's, from IRM's origin.
    fn point(&self, s: &Vector3<T>) -> Vector3<T> {
        &self.origin + self.direction(s)
    }
}

/// The z component of `a × b`.
fn cross<T: Number>(a: &Vector3<T>, b: &Vector3<T>) -> T {
    a.x.clone() * b.y.clone() - a.y.clone() * b.x.clone()
}

/// The equations `F = (F₁, F₂)` of the contact at `(α, β)` and their
/// derivatives in `(α, β)`, row by row.
fn equations<T: Number>(
    i: &CurvePoint<T>,
    j: &CurvePoint<T>,
    placement: &Placement<T>,
) -> ([T; 2], [[T; 2]; 2]) {
    let tangent = placement.direction(&j.tangent);
    let bend = placement.direction(&j.bend);
    let apart = &i.place - placement.point(&j.place);
    (
        [cross(&i.tangent, &tangent), i.tangent.dot(&apart)],
        [
            [cross(&i.bend, &tangent), cross(&i.tangent, &bend)],
            [
                i.bend.dot(&apart) + i.tangent.norm_squared(),
                -i.tangent.dot(&tangent),
            ],
        ],
    )
}

/// The inverse of the 2 × 2 matrix `m`, `None` where it is singular.
fn inverse<T: Number>(m: &[[T; 2]; 2]) -> Option<[[T; 2]; 2]> {
    let det = m[0][0].clone() * m[1][1].clone() - m[0][1].clone() * m[1][0].clone();
    if det.value() == 0.0 || !det.value().is_finite() {
        return None;
    }
    Some([
        [
            m[1][1].clone() / det.clone(),
            -m[0][1].clone() / det.clone(),
        ],
        [-m[1][0].clone() / det.clone(), m[0][0].clone() / det],
    ])
}

/// One Newton step on `F = 0` from `(alpha, beta)`, each curve on the
/// piece `pieces` holds it on where it does.
fn newton<T: Number>(
    pair: &CurvePair,
    placement: &Placement<T>,
    (alpha, beta): (T, T),
    pieces: Pieces,
) -> Option<(T, T)> {
    let i = pair.i.curve.at_on(&alpha, pieces[0]);
    let j = pair.j.curve.at_on(&beta, pieces[1]);
    let (f, m) = equations(&i, &j, placement);
    let inverse = inverse(&m)?;
    let step = |row: &[T; 2]| -(row[0].clone() * f[0].clone() + row[1].clone() * f[1].clone());
    Some((alpha + step(&inverse[0]), beta + step(&inverse[1])))
}

/// How many samples each piece of a curve gives the search for the
/// contact's start.
const SAMPLES_PER_PIECE: usize = 4;

/// How Newton's iterations on `F` ended ([`iterated`]).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Ending {
    /// The last step moved the parameters by rounding only.
    Settled,
    /// A singular matrix or a step to no number stopped them.
    Stopped,
    /// They ran out of iterations.
    Unsettled,
}

/// Newton's iterations on `F` from the nearest pair (in IRM's plane) of
/// the curves' samples (of the held pieces), each curve on the piece
/// `pieces` holds it on where it does: their last finite iterate and how
/// they ended; `None` where the curves have no samples.
fn iterated(
    pair: &CurvePair,
    placement: &Placement<f64>,
    pieces: Pieces,
) -> Option<((f64, f64), Ending)> {
    let (mut alpha, mut beta) = nearest_samples(pair, placement, pieces)?;
    for _ in 0..50 {
        let Some((next_alpha, next_beta)) = newton(pair, placement, (alpha, beta), pieces)
            .filter(|(alpha, beta)| alpha.is_finite() && beta.is_finite())
        else {
            return Some(((alpha, beta), Ending::Stopped));
        };
        let settled = (next_alpha - alpha).abs() <= 1e-13 * (1.0 + alpha.abs())
            && (next_beta - beta).abs() <= 1e-13 * (1.0 + beta.abs());
        (alpha, beta) = (next_alpha, next_beta);
        if settled {
            return Some(((alpha, beta), Ending::Settled));
        }
    }
    Some(((alpha, beta), Ending::Unsettled))
}

/// The contact's parameters `(α, β)` at `placement`, each curve on the
/// piece `pieces` holds it on where it does: [`iterated`]'s, where they
/// settle or end with `F` within 1e-10 of 0; `None` otherwise.
fn parameters(pair: &CurvePair, placement: &Placement<f64>, pieces: Pieces) -> Option<(f64, f64)> {
    let ((alpha, beta), ending) = iterated(pair, placement, pieces)?;
    match ending {
        Ending::Settled => return Some((alpha, beta)),
        Ending::Stopped => return None,
        Ending::Unsettled => {}
    }
    let (f, _) = equations(
        &pair.i.curve.at_on(&alpha, pieces[0]),
        &pair.j.curve.at_on(&beta, pieces[1]),
        placement,
    );
    (f[0].abs() + f[1].abs() <= 1e-10).then_some((alpha, beta))
}

/// CVCV `joint`'s contact parameters `(α, β)` at the state `bodies` give,
/// each curve on the piece `pieces` holds it on where it does, when they
/// are found.
pub(super) fn contact_parameters(
    model: &Model,
    joint: &Joint,
    pair: &CurvePair,
    bodies: &[BodyMotion<f64>],
    pieces: Pieces,
) -> Option<(f64, f64)> {
    let seen = Seen::new(model, joint, bodies);
    parameters(pair, &seen.placement(), pieces)
}

/// The nearest pair (in IRM's plane) of the curves' samples, `SAMPLES_PER_PIECE`
/// a piece evenly in each curve's parameter, the first in the order of the
/// parameters among equals, only the held piece's of a curve `pieces`
/// holds. Only the samples of pieces whose bounding
/// balls come as near each other as the nearest pair of balls' far sides
/// are looked at: no pair of the other pieces' samples can be nearer, so
/// the pair is the one all the samples give.
fn nearest_samples(
    pair: &CurvePair,
    placement: &Placement<f64>,
    pieces: Pieces,
) -> Option<(f64, f64)> {
    // The pieces looked at: the held one of a curve `pieces` holds, every
    // piece of the other.
    let looked_at = |side: usize, count: usize| -> Vec<usize> {
        pieces[side].map_or_else(|| (0..count).collect(), |held| vec![held])
    };
    // In IRM's plane (JCURVE's shadow on it is no larger than the curve).
    let planar =
        |a: &Vector3<f64>, b: &Vector3<f64>| ((a.x - b.x).powi(2) + (a.y - b.y).powi(2)).sqrt();
    let ours: Vec<(Vector3<f64>, f64)> = pair.i.curve.piece_balls().collect();
    let theirs: Vec<(Vector3<f64>, f64)> = pair
        .j
        .curve
        .piece_balls()
        .map(|(centre, radius)| (placement.point(&centre), radius))
        .collect();
    let (our_pieces, their_pieces) = (looked_at(0, ours.len()), looked_at(1, theirs.len()));
    // The least and most each pair of balls' points can be apart.
    let (theirs_seen, their_pieces_seen) = (&theirs, &their_pieces);
    let bounds: Vec<(f64, f64)> = our_pieces
        .iter()
        .flat_map(|&a| {
            let (centre, ra) = ours[a];
            their_pieces_seen.iter().map(move |&b| {
                let (other, rb) = theirs_seen[b];
                let between = planar(&centre, &other);
                (between - ra - rb, between + ra + rb)
            })
        })
        .collect();
    let reach = bounds
        .iter()
        .map(|&(_, most)| most)
        .fold(f64::INFINITY, f64::min);
    if !reach.is_finite() {
        return None;
    }
    // Each piece's samples `(index along the curve, α)`, and their points
    // in IRM's axes once a pair of pieces near enough needs them.
    let by_piece = |curve: &Curve| {
        let count = SAMPLES_PER_PIECE * curve.piece_count();
        let mut pieces = vec![Vec::new(); curve.piece_count()];
        for k in 0..=count {
            let alpha = -1.0 + 2.0 * k as f64 / count as f64;
            pieces[curve.piece_of(alpha)].push((k, alpha));
        }
        pieces
    };
    let placed =
        |curve: &Curve, samples: &[(usize, f64)], place: &dyn Fn(&Vector3<f64>) -> Vector3<f64>| {
            samples
                .iter()
                .map(|&(k, alpha)| (k, alpha, place(&curve.at(&alpha).place)))
                .collect::<Vec<_>>()
        };
    let (our_samples, their_samples) = (by_piece(&pair.i.curve), by_piece(&pair.j.curve));
    let mut our_points = vec![None; ours.len()];
    let mut their_points = vec![None; theirs.len()];
    let mut nearest: Option<(f64, usize, usize, f64, f64)> = None;
    for (x, &a) in our_pieces.iter().enumerate() {
        for (y, &b) in their_pieces.iter().enumerate() {
            if bounds[x * their_pieces.len() + y].0 > reach {
                continue;
            }
            let our_points: &Vec<_> = our_points[a]
                .get_or_insert_with(|| placed(&pair.i.curve, &our_samples[a], &|p| *p));
            let their_points: &Vec<_> = their_points[b].get_or_insert_with(|| {
                placed(&pair.j.curve, &their_samples[b], &|p| placement.point(p))
            });
            for &(k, alpha, p) in our_points {
                for &(l, beta, q) in their_points {
                    let apart = (p.x - q.x).powi(2) + (p.y - q.y).powi(2);
                    let candidate = (apart, k, l, alpha, beta);
                    let better = nearest.is_none_or(|best| {
                        (candidate.0, candidate.1, candidate.2)
                            .partial_cmp(&(best.0, best.1, best.2))
                            == Some(std::cmp::Ordering::Less)
                    });
                    if better {
                        nearest = Some(candidate);
                    }
                }
            }
        }
    }
    nearest.map(|(_, _, _, alpha, beta)| (alpha, beta))
}

/// The point of contact at a state: the parameters, each curve's point
/// there, and what the gap's rows need.
struct Contact<T: Number> {
    /// ICURVE's parameter.
    alpha: f64,
    /// JCURVE's parameter.
    beta: f64,
    /// ICURVE's point at `α` (in IRM's axes).
    i: CurvePoint<T>,
    /// JCURVE's point at `β` (in JRM's axes).
    j: CurvePoint<T>,
    /// JCURVE's tangent `P'` and bend `P''` at `β`, in IRM's axes.
    tangent: Vector3<T>,
    bend: Vector3<T>,
    /// ICURVE's unit normal `n` in IRM's plane and its derivative in `α`.
    normal: Vector3<T>,
    normal_turn: Vector3<T>,
    /// The inverse of `∂F/∂(α, β)`.
    inverse: [[T; 2]; 2],
    /// The rows whose rates are `F`'s at fixed parameters.
    moving: [Row<T>; 2],
}

impl<T: Number> Contact<T> {
    /// The contact at the state `seen` gives, each curve on the piece
    /// `pieces` holds it on where it does; `None` where none is found or
    /// it lies past an end of an open curve.
    fn find(pair: &CurvePair, seen: &Seen<T>, pieces: Pieces) -> Option<Contact<T>> {
        let placement = seen.placement();
        let (alpha, beta) = parameters(pair, &placement.plain(), pieces)?;
        if off_the_ends(&pair.i.curve, alpha) || off_the_ends(&pair.j.curve, beta) {
            return None;
        }
        // One Newton step carries the parameters' derivatives.
        let (alpha_carried, beta_carried) =
            newton(pair, &placement, (T::from(alpha), T::from(beta)), pieces)?;
        let i = pair.i.curve.at_on(&alpha_carried, pieces[0]);
        let j = pair.j.curve.at_on(&beta_carried, pieces[1]);
        let (_, m) = equations(&i, &j, &placement);
        let inverse = inverse(&m)?;
        let speed = i.tangent.norm();
        let unit = &i.tangent / speed.clone();
        let unit_turn = (&i.bend - &unit * unit.dot(&i.bend)) / speed.clone();
        let square = |v: &Vector3<T>| Vector3::new(-v.y.clone(), v.x.clone(), T::zero());
        let normal = square(&unit);
        let normal_turn = square(&unit_turn);
        let moving = [
            seen.along(&(&normal * speed), &j.tangent, false),
            seen.along(&(-&i.tangent), &j.place, true),
        ];
        Some(Contact {
            alpha,
            beta,
            tangent: placement.direction(&j.tangent),
            bend: placement.direction(&j.bend),
            i,
            j,
            normal,
            normal_turn,
            inverse,
            moving,
        })
    }

    /// The parameters' rates `(α', β') = −(∂F/∂(α, β))⁻¹ F'` (`F'` at fixed
    /// parameters).
    fn rates(&self) -> [T; 2] {
        let [first, second] = &self.moving;
        self.inverse.clone().map(|row| {
            -(row[0].clone() * first.rate.clone() + row[1].clone() * second.rate.clone())
        })
    }

    /// The rows of the parameters `α, β`: their values 0, their rates `α'`
    /// and `β'`.
    fn parameter_rows(&self) -> [Row<T>; 2] {
        let [first, second] = &self.moving;
        self.inverse
            .clone()
            .map(|row| {
                Row::zero()
                    .plus_times(first, &-row[0].clone())
                    .plus_times(second, &-row[1].clone())
            })
            .map(|mut row| {
                row.value = T::zero();
                row.bias = T::zero();
                row
            })
    }

    /// The gap `g₁` across ICURVE's normal, with its rate, bias and row.
    fn gap(&self, seen: &Seen<T>) -> Row<T> {
        let (n, turn) = (&self.normal, &self.normal_turn);
        let mut row = seen.along(&-n, &self.j.place, true);
        row.value += n.dot(&self.i.place);
        let [alpha_rate, beta_rate] = self.rates();
        let turn_rate = seen.along(&-turn, &self.j.place, true).rate;
        let tangent_rate = seen.along(&-n, &self.j.tangent, false).rate;
        let two = T::from(2.0);
        let g_aa = -row.value.clone() * turn.norm_squared()
            + turn.dot(&self.i.tangent) * two.clone()
            + n.dot(&self.i.bend);
        let g_ab = -turn.dot(&self.tangent);
        let g_bb = -n.dot(&self.bend);
        row.bias += (turn_rate * alpha_rate.clone() + tangent_rate * beta_rate.clone())
            * two.clone()
            + g_aa * alpha_rate.clone() * alpha_rate.clone()
            + g_ab * alpha_rate.clone() * beta_rate.clone() * two
            + g_bb * beta_rate.clone() * beta_rate;
        row
    }
}
