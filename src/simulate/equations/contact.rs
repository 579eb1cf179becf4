//! CONTACT: where two solids overlap, how deep, along which normal, and the
//! force that follows (Adams' IMPACT normal force and its velocity-based
//! Coulomb friction), generic over the number type so that the Jacobian
//! comes from the same code.
//!
//! The geometry follows Adams' account of its solid-to-solid contact: the
//! overlap's centroid, the closest point of each solid's surface to it,
//! the depth the distance between those two points. The normal is the
//! surfaces' common one: a plane's or a block face's where a solid meets
//! it (a rim, an edge or a tip has none of its own), for two blocks the
//! axis their shadows overlap least on (a struck face's normal, or the
//! cross product of two crossing edges), and otherwise the direction
//! between those two points. A sphere's overlap with a sphere, a plane, a
//! block or a round solid has its depth in closed form (the depth along the
//! line of the centroid is the distance from the sphere's deepest point to
//! the other surface); two blocks, or a block and a plane, overlap in a
//! convex polyhedron whose centroid is computed exactly by clipping; a
//! round solid's (a cylinder's, a frustum's or a cone's) overlap with a
//! plane (or a block's face) is integrated across its axis, each slice a
//! disk cut in a circular segment.

use nalgebra::{Matrix3, Vector3};

use super::bodies::Kinematics;
use super::forces::{Action, axes, place};
use crate::laws::contact::ContactBranch;
use crate::laws::steps::{Shape as StepShape, step};
use crate::number::Number;
use crate::simulate::constraints::quadrature::{KRONROD, NODES};
use crate::simulate::model::{Contact, Friction, Model, Shape, Solid};

/// A solid placed in ground: its marker's origin and axes, and its shape.
struct Placed<'s, T: Number> {
    origin: Vector3<T>,
    axes: Matrix3<T>,
    shape: &'s Shape,
    body: Option<usize>,
}

impl<'s, T: Number> Placed<'s, T> {
    /// The solid placed where it is, in plain numbers.
    fn values(&self) -> Placed<'s, f64> {
        Placed {
            origin: self.origin.map(|c| c.value()),
            axes: self.axes.map(|c| c.value()),
            shape: self.shape,
            body: self.body,
        }
    }

    /// A point of ground in the marker's axes.
    fn local(&self, point: &Vector3<T>) -> Vector3<T> {
        self.axes.tr_mul(&(point - &self.origin))
    }

    /// A point in the marker's axes, in ground.
    fn ground(&self, local: &Vector3<T>) -> Vector3<T> {
        &self.origin + &self.axes * local
    }

    /// The centre of a bounded solid in ground (`None` for a half-space):
    /// a sphere's, a block's, the middle of a round solid's axis.
    fn centre(&self) -> Option<Vector3<T>> {
        let local = match *self.shape {
            Shape::Sphere { .. } => return Some(self.origin.clone()),
            Shape::Block { lower, upper } => (lower + upper) / 2.0,
            Shape::Frustum { bottom, top, .. } => Vector3::new(0.0, 0.0, (bottom + top) / 2.0),
            Shape::HalfSpace => return None,
        };
        Some(self.ground(&local.map(T::from)))
    }

    /// A point well inside the solid, which the normal points away from:
    /// its centre, or a unit below `near` in a half-space.
    fn inside(&self, near: &Vector3<T>) -> Vector3<T> {
        self.centre()
            .unwrap_or_else(|| near - self.axes.column(2).into_owned())
    }
}

/// `solid` where its marker stands in `kinematics`.
fn placed<'s, T: Number>(
    model: &Model,
    solid: &'s Solid,
    kinematics: &[Kinematics<T>],
) -> Placed<'s, T> {
    let marker = place(model, &solid.marker, kinematics);
    Placed {
        origin: marker.origin,
        axes: axes(model, &solid.marker, kinematics),
        shape: &solid.shape,
        body: marker.body,
    }
}

/// Where two solids overlap: the point the force acts at, the unit normal
/// along which it pushes I's solid away from J's, and the depth.
struct Touch<T: Number> {
    point: Vector3<T>,
    normal: Vector3<T>,
    depth: T,
}

/// What a contact applies on I's part and on J's, its normal force on
/// branch `held` of its law (the natural branch when `None`): nothing
/// while the solids are apart, unless a branch in touch is held there.
pub(super) fn actions<T: Number>(
    model: &Model,
    contact: &Contact,
    kinematics: &[Kinematics<T>],
    held: Option<ContactBranch>,
) -> [Option<Action<T>>; 2] {
    let (i, j) = (
        placed(model, &contact.i, kinematics),
        placed(model, &contact.j, kinematics),
    );
    let Some(touch) = touch(&i, &j) else {
        return [None, None];
    };
    if touch.depth.value() <= 0.0 && held.is_none_or(|branch| branch == ContactBranch::Free) {
        return [None, None];
    }
    let relative = relative_velocity(kinematics, &i, &j, &touch.point);
    let push = force(contact, &touch, &relative, held);
    let on = |body, force: Vector3<T>| Action {
        body,
        point: touch.point.clone(),
        force: Some(force),
        torque: None,
    };
    [Some(on(i.body, push.clone())), Some(on(j.body, -push))]
}

/// The velocity of I's solid's point at `point` relative to J's.
fn relative_velocity<T: Number>(
    kinematics: &[Kinematics<T>],
    i: &Placed<T>,
    j: &Placed<T>,
    point: &Vector3<T>,
) -> Vector3<T> {
    let velocity = |body: Option<usize>| match body {
        None => Vector3::zeros(),
        Some(body) => {
            let state = &kinematics[body];
            &state.velocity + state.omega_ground.cross(&(point - &state.centre))
        }
    };
    velocity(i.body) - velocity(j.body)
}

/// The sine of the angle between the axes of two cylinders, when the
/// solids are two, they have turned further apart than the geometry takes
/// for parallel (a thousandth of a radian, [`TILT`]) and they are near
/// enough to touch (their bounding spheres meet).
fn cylinders_tilted(i: &Placed<f64>, j: &Placed<f64>) -> Option<f64> {
    if !matches!(
        (i.shape, j.shape),
        (Shape::Frustum { .. }, Shape::Frustum { .. })
    ) {
        return None;
    }
    let sine = i.axes.column(2).cross(&j.axes.column(2)).norm();
    (sine > TILT && bounding_gap(i, j) <= 0.0).then_some(sine)
}

/// How far the centre of a block or a round solid has gone below a plane,
/// when it has. Beyond there the depth Adams measures (between the
/// surfaces' points closest to the overlap's centroid) runs to the
/// solid's far faces, jumps between them on rounding, and no longer
/// pushes the solid out (a box started under a plane stalled every method;
/// a cone sunk on its tip sank through).
fn sunk_past_centre(i: &Placed<f64>, j: &Placed<f64>) -> Option<f64> {
    let (solid, plane) = match (i.shape, j.shape) {
        (Shape::Block { .. } | Shape::Frustum { .. }, Shape::HalfSpace) => (i, j),
        (Shape::HalfSpace, Shape::Block { .. } | Shape::Frustum { .. }) => (j, i),
        _ => return None,
    };
    let height = plane.local(&solid.centre()?).z;
    (height < 0.0).then_some(-height)
}

/// Whether a round solid and a block whose overlap was not found overlap
/// where the geometry does not look: a block's corner or a point of its
/// edges inside the round solid, or a point of the round solid's rims
/// inside the block (mbexpr meets a round solid with the block face it
/// stands beyond only).
fn block_edge_unseen(i: &Placed<f64>, j: &Placed<f64>) -> bool {
    let (round, block) = match (i.shape, j.shape) {
        (Shape::Frustum { .. }, Shape::Block { .. }) => (i, j),
        (Shape::Block { .. }, Shape::Frustum { .. }) => (j, i),
        _ => return false,
    };
    let Shape::Frustum { radii, bottom, top } = *round.shape else {
        return false;
    };
    // Deeper than rounding and than an overlap too thin to integrate at
    // the first touch.
    let margin = 1e-5 * (radii[0].max(radii[1]) + top - bottom);
    let in_round = |point: &Vector3<f64>| {
        let local = round.local(point);
        let radius = radii[0] + (radii[1] - radii[0]) * (local.z - bottom) / (top - bottom);
        local.z > bottom + margin
            && local.z < top - margin
            && local.x.hypot(local.y) < radius - margin
    };
    let corners = corners(block);
    // Each edge once, from a corner to the one a bit above it, at nine
    // points.
    let mut on_edges = Vec::new();
    for (a, start) in corners.iter().enumerate() {
        for bit in (0..3).filter(|bit| a >> bit & 1 == 0) {
            let end = corners[a | 1 << bit];
            on_edges.extend((0..=8).map(|k| start + (end - start) * (f64::from(k) / 8.0)));
        }
    }
    let planes = half_spaces(block);
    let in_block = |point: &Vector3<f64>| {
        planes
            .iter()
            .all(|(normal, offset)| normal.dot(point) < offset - margin)
    };
    let on_rims = [(bottom, radii[0]), (top, radii[1])]
        .into_iter()
        .flat_map(|(at, radius)| {
            (0..32).map(move |k| {
                let angle = f64::from(k) * std::f64::consts::TAU / 32.0;
                Vector3::new(radius * angle.cos(), radius * angle.sin(), at)
            })
        })
        .map(|local| round.ground(&local));
    on_edges.iter().any(in_round) || on_rims.into_iter().any(|point| in_block(&point))
}

/// The distance between two bounded solids' bounding spheres (a lower
/// bound on theirs).
fn bounding_gap(i: &Placed<f64>, j: &Placed<f64>) -> f64 {
    let ((centre_i, radius_i), (centre_j, radius_j)) = (bounding_sphere(i), bounding_sphere(j));
    (centre_i - centre_j).norm() - radius_i - radius_j
}

/// How far two cylinders' axes may turn apart in a run (the sine of the
/// angle) while their contact is taken for one of parallel cylinders.
const TILT: f64 = 1e-3;

/// Why a run stops at a contact whose solids have gone where its geometry
/// does not follow them: the operation and the reason.
pub(super) struct Refusal {
    /// What the geometry could not do.
    pub operation: &'static str,
    /// Why, and what to write instead.
    pub reason: String,
}

/// The separation of a contact's solids (the negative of their depth:
/// the first argument of its `IMPACT` law) and its rate at a state, which
/// the run watches to switch the law's branches; while two solids of flat
/// faces are apart, a lower bound on their distance and no rate. A
/// refusal where the geometry does not follow the solids: two cylinders
/// turned apart, a solid's centre below a plane, a round solid and a block
/// overlapping where the geometry does not look (a block's edge or corner
/// in the round solid).
pub(super) fn separation(
    model: &Model,
    contact: &Contact,
    kinematics: &[Kinematics<f64>],
) -> Result<(f64, f64), Refusal> {
    let (i, j) = (
        placed(model, &contact.i, kinematics),
        placed(model, &contact.j, kinematics),
    );
    if let Some(sine) = cylinders_tilted(&i, &j) {
        return Err(Refusal {
            operation: "a contact of two cylinders",
            reason: format!(
                "their axes have turned {:.3} rad apart; mbexpr meets two cylinders side by side, their axes parallel: hold them so with joints",
                sine.asin()
            ),
        });
    }
    if let Some(below) = sunk_past_centre(&i, &j) {
        return Err(Refusal {
            operation: "a contact with a plane",
            reason: format!(
                "the solid's centre has gone {} below the plane; past there the depth Adams measures (between the surfaces' points closest to the overlap's centroid) runs to the solid's far faces and no longer pushes it out: start the solid above the plane, or make the contact stiffer so that it stays shallow",
                crate::shown::Shown(below)
            ),
        });
    }
    Ok(match touch(&i, &j) {
        Some(touch) => {
            let relative = relative_velocity(kinematics, &i, &j, &touch.point);
            (-touch.depth, touch.normal.dot(&relative))
        }
        None if block_edge_unseen(&i, &j) => {
            return Err(Refusal {
                operation: "a contact of a block and a round solid",
                reason: "a block's edge or corner has gone into the round solid, or its rim into the block away from the face it stands beyond; mbexpr meets a round solid with a block's face only (a wheel on a table): write the block's face as a PLANE, or the edge as a thin CYLINDER side by side with the round one".to_string(),
            });
        }
        None => {
            let bound = distance_bound(&i, &j).unwrap_or(0.0);
            // Against a plane the distance is exact, and below zero where
            // the overlap is too thin to integrate: the touch is located
            // where the solids meet, not where their overlap shows.
            let exact = matches!(
                (i.shape, j.shape),
                (_, Shape::HalfSpace) | (Shape::HalfSpace, _)
            );
            (if exact { bound } else { bound.max(0.0) }, 0.0)
        }
    })
}

/// The force on I's solid: the contact's `IMPACT` law of the separation
/// and its rate on branch `held`, along the normal, and friction against
/// the slip.
fn force<T: Number>(
    contact: &Contact,
    touch: &Touch<T>,
    relative: &Vector3<T>,
    held: Option<ContactBranch>,
) -> Vector3<T> {
    let approach = touch.normal.dot(relative);
    let separation = -touch.depth.clone();
    let law = contact.law();
    let normal_force = match held {
        None => law.force(&separation, &approach),
        Some(branch) => law.force_held(&separation, &approach, branch),
    };
    let mut push = &touch.normal * normal_force.clone();
    if let Some(friction) = &contact.friction {
        let slip = relative - &touch.normal * approach;
        let per_slip = friction_per_slip(friction, &slip);
        push += slip * (-normal_force * per_slip);
    }
    push
}

/// The friction coefficient divided by the slip speed `v`, which stays
/// finite as `v` goes to zero (the stiction ramp is odd in `v`).
fn friction_per_slip<T: Number>(friction: &Friction, slip: &Vector3<T>) -> T {
    let &Friction {
        static_coefficient: mu_s,
        dynamic_coefficient: mu_d,
        stiction_velocity: v_s,
        friction_velocity: v_d,
    } = friction;
    let squared = slip.dot(slip);
    if squared.value() <= (1e-9 * v_s).powi(2) {
        // STEP(v, -vs, -μs, vs, μs)/v at v = 0: the ramp's slope, 3μs/(2vs).
        return T::from(1.5 * mu_s / v_s);
    }
    let speed = squared.sqrt();
    let c = T::from;
    let stiction = step(
        StepShape::Cubic,
        &speed,
        &c(-v_s),
        &c(-mu_s),
        &c(v_s),
        &c(mu_s),
    );
    let sliding = step(
        StepShape::Cubic,
        &speed,
        &c(v_s),
        &c(0.0),
        &c(v_d),
        &c(mu_d - mu_s),
    );
    (stiction + sliding) / speed
}

/// Where `i` and `j` overlap, if they do.
fn touch<T: Number>(i: &Placed<T>, j: &Placed<T>) -> Option<Touch<T>> {
    match (i.shape, j.shape) {
        (Shape::Sphere { radius }, _) => sphere_touch(&i.origin, *radius, j),
        (_, Shape::Sphere { radius }) => sphere_touch(&j.origin, *radius, i).map(|touch| Touch {
            normal: -touch.normal,
            ..touch
        }),
        _ => overlap_touch(i, j).or_else(|| thin_touch(i, j)),
    }
}

/// A solid's overlap with a plane too thin to integrate (a cone's tip or
/// a rim a millionth of the size in): the touch at the solid's lowest
/// point, its depth the plane's height above it, along the plane's
/// normal, so that no depth is too small to push back.
fn thin_touch<T: Number>(i: &Placed<T>, j: &Placed<T>) -> Option<Touch<T>> {
    let (solid, plane, plane_is_i) = match (i.shape, j.shape) {
        (_, Shape::HalfSpace) => (i, j, false),
        (Shape::HalfSpace, _) => (j, i, true),
        _ => return None,
    };
    let up = plane.axes.column(2).into_owned();
    let lowest = lowest_point(solid, &up)?;
    let depth = up.dot(&(&plane.origin - &lowest));
    if depth.value() <= 0.0 {
        return None;
    }
    let on_plane = &lowest + &up * depth.clone();
    Some(Touch {
        point: (lowest + on_plane) * T::from(0.5),
        normal: if plane_is_i { -up } else { up },
        depth,
    })
}

/// The point of a block or a round solid lowest along `up` (a corner, a
/// point of a rim; `None` for another shape).
fn lowest_point<T: Number>(solid: &Placed<T>, up: &Vector3<T>) -> Option<Vector3<T>> {
    let candidates: Vec<Vector3<T>> = match *solid.shape {
        Shape::Block { .. } => corners(solid),
        Shape::Frustum { radii, bottom, top } => {
            let axis = solid.axes.column(2).into_owned();
            let across = up - &axis * up.dot(&axis);
            let length = across.norm();
            [(bottom, radii[0]), (top, radii[1])]
                .into_iter()
                .map(|(at, radius)| {
                    let centre = solid.ground(&Vector3::new(0.0, 0.0, at).map(T::from));
                    if length.value() > 0.0 && radius > 0.0 {
                        centre - &across * (T::from(radius) / length.clone())
                    } else {
                        centre
                    }
                })
                .collect()
        }
        Shape::Sphere { .. } | Shape::HalfSpace => return None,
    };
    candidates
        .into_iter()
        .min_by(|a, b| up.dot(a).value().total_cmp(&up.dot(b).value()))
}

/// A sphere about `centre` against `other`: the normal points from the
/// other solid into the sphere, the depth is the radius less the
/// distance from the centre to the other solid's surface (plus that
/// distance when the centre is inside), and the force acts midway between
/// the two surfaces. The depth is negative while they are apart (the
/// contact's switching value, and its force continued on a held branch).
fn sphere_touch<T: Number>(
    centre: &Vector3<T>,
    radius: f64,
    other: &Placed<T>,
) -> Option<Touch<T>> {
    let (surface, outward) = closest_surface(other, centre)?;
    let depth = T::from(radius) - (centre - &surface).dot(&outward);
    let deepest = centre - &outward * T::from(radius);
    Some(Touch {
        point: (deepest + surface) * T::from(0.5),
        normal: outward,
        depth,
    })
}

/// The point of `solid`'s surface closest to `point` and the surface's
/// outward unit normal there (towards `point` when it is outside, the
/// nearest face's when inside); `None` where they are not defined (a
/// point at a sphere's centre).
fn closest_surface<T: Number>(
    solid: &Placed<T>,
    point: &Vector3<T>,
) -> Option<(Vector3<T>, Vector3<T>)> {
    let local = solid.local(point);
    let (surface, outward) = match *solid.shape {
        Shape::Sphere { radius } => {
            let length = local.norm();
            if length.value() == 0.0 {
                return None;
            }
            let outward = local / length;
            (&outward * T::from(radius), outward)
        }
        Shape::HalfSpace => {
            let mut surface = local;
            surface.z = T::from(0.0);
            (surface, Vector3::z().map(T::from))
        }
        Shape::Block { lower, upper } => block_surface(&local, &lower, &upper),
        Shape::Frustum { radii, bottom, top } => frustum_surface(&local, radii, bottom, top)?,
    };
    Some((solid.ground(&surface), &solid.axes * outward))
}

/// The closest point of a block's surface to `local` and the outward
/// normal there.
fn block_surface<T: Number>(
    local: &Vector3<T>,
    lower: &Vector3<f64>,
    upper: &Vector3<f64>,
) -> (Vector3<T>, Vector3<T>) {
    let clamped = Vector3::from_fn(|axis, _| {
        let x = &local[axis];
        if x.value() < lower[axis] {
            T::from(lower[axis])
        } else if x.value() > upper[axis] {
            T::from(upper[axis])
        } else {
            x.clone()
        }
    });
    let gap = local - &clamped;
    let length = gap.norm();
    if length.value() > 0.0 {
        return (clamped, gap / length);
    }
    // Inside: out through the nearest face.
    let mut nearest = (f64::INFINITY, 0, 1.0);
    for axis in 0..3 {
        let x = local[axis].value();
        for (distance, side) in [(x - lower[axis], -1.0), (upper[axis] - x, 1.0)] {
            if distance < nearest.0 {
                nearest = (distance, axis, side);
            }
        }
    }
    let (_, axis, side) = nearest;
    let mut surface = local.clone();
    surface[axis] = T::from(if side > 0.0 { upper[axis] } else { lower[axis] });
    let mut outward = Vector3::zeros();
    outward[axis] = T::from(side);
    (surface, outward)
}

/// The closest point of a round solid's surface (about z, between
/// `bottom` and `top`, of radius `radii[0]` at the bottom and `radii[1]`
/// at the top) to `local` and the outward normal there. In the half-plane
/// of the axis and `local` the solid is a trapezoid; its surface is the
/// two ends and the side, each a segment of that plane.
fn frustum_surface<T: Number>(
    local: &Vector3<T>,
    radii: [f64; 2],
    bottom: f64,
    top: f64,
) -> Option<(Vector3<T>, Vector3<T>)> {
    let c = T::from;
    let across = (local.x.clone() * local.x.clone() + local.y.clone() * local.y.clone()).sqrt();
    let (rho, z) = (across.value(), local.z.value());
    // The unit vector away from the axis towards `local`.
    let radial = || {
        (rho > 0.0).then(|| {
            (
                local.x.clone() / across.clone(),
                local.y.clone() / across.clone(),
            )
        })
    };
    let (height, flare) = (top - bottom, radii[1] - radii[0]);
    let radius_at = |z: f64| radii[0] + flare * (z - bottom) / height;
    let inside = (bottom..=top).contains(&z) && rho <= radius_at(z);
    // The side's closest point, by its parameter along the side (0 at the
    // bottom edge, 1 at the top), and its distance in the half-plane.
    let side_length = flare.hypot(height);
    let along_side = ((across.clone() - c(radii[0])) * c(flare)
        + (local.z.clone() - c(bottom)) * c(height))
        / c(side_length * side_length);
    let along_side = if along_side.value() < 0.0 {
        c(0.0)
    } else if along_side.value() > 1.0 {
        c(1.0)
    } else {
        along_side
    };
    let side_rho = c(radii[0]) + along_side.clone() * c(flare);
    let side_z = c(bottom) + along_side * c(height);
    let side_gap = (across.clone() - side_rho.clone())
        .value()
        .hypot((local.z.clone() - side_z.clone()).value());
    // An end's closest point: below `local`, or at its rim.
    let end_gap = |end: f64, radius: f64| {
        let beyond = (rho - radius).max(0.0);
        beyond.hypot(z - end)
    };
    let gaps = [end_gap(bottom, radii[0]), side_gap, end_gap(top, radii[1])];
    // A cone's tip is an end of no size: its side is nearer.
    let mut nearest = (0..3)
        .filter(|&k| k == 1 || radii[k / 2] > 0.0)
        .min_by(|&a, &b| gaps[a].total_cmp(&gaps[b]))?;
    let on_axis = rho <= 1e-12 * (radii[0].max(radii[1]) + height.abs());
    if nearest == 1 && on_axis {
        // On the axis the side is equally near all round, and no one of
        // its points is the closest: the nearer end along the axis (a
        // cone's tip included) is taken, which keeps the closest point and
        // the normal on the axis, where the symmetry puts them. Within
        // rounding of the axis counts as on it (a solid turned by 180D is
        // off its axis by 1e-16, and the side's normal would swing round
        // with the rounding).
        nearest = if (z - bottom).abs() <= (top - z).abs() {
            0
        } else {
            2
        };
    }
    let lift = |r: T, z: T| -> Option<Vector3<T>> {
        if r.value() == 0.0 {
            return Some(Vector3::new(c(0.0), c(0.0), z));
        }
        let (x, y) = radial()?;
        Some(Vector3::new(x * r.clone(), y * r, z))
    };
    let surface = match nearest {
        1 => lift(side_rho, side_z)?,
        _ => {
            let (end, radius) = if nearest == 0 {
                (bottom, radii[0])
            } else {
                (top, radii[1])
            };
            if rho <= radius {
                Vector3::new(local.x.clone(), local.y.clone(), c(end))
            } else {
                lift(c(radius), c(end))?
            }
        }
    };
    if !inside {
        let gap = local - &surface;
        let length = gap.norm();
        return (length.value() > 0.0).then(|| (surface, gap / length));
    }
    // Inside: out through the nearest of the ends and the side.
    let outward = match nearest {
        0 => Vector3::new(c(0.0), c(0.0), c(-1.0)),
        2 => Vector3::new(c(0.0), c(0.0), c(1.0)),
        _ => {
            let (x, y) = radial()?;
            let (out, up) = (height / side_length, -flare / side_length);
            Vector3::new(x * c(out), y * c(out), c(up))
        }
    };
    Some((surface, outward))
}

/// Two solids of flat faces (blocks, planes): their overlap, a convex
/// polyhedron, clipped exactly; or a round solid and a plane or a block:
/// the overlap with the plane (or the block's face the solid stands
/// beyond), integrated slice by slice. The force acts at the overlap's
/// centroid, the depth the distance between the two surfaces' points
/// closest to it (Adams' definition). The normal is the common one of the
/// surfaces where one is flat there (a plane's, the block face's a round
/// solid meets: an edge or a rim has no normal of its own), otherwise the
/// line between those two points.
fn overlap_touch<T: Number>(i: &Placed<T>, j: &Placed<T>) -> Option<Touch<T>> {
    // The flat face's outward normal, and whether the face is I's.
    let (centroid, face) = match (i.shape, j.shape) {
        (Shape::Frustum { .. }, Shape::Frustum { .. }) => (cylinders_overlap(i, j)?, None),
        (Shape::Frustum { .. }, _) => {
            let (centroid, normal) = frustum_overlap(i, j)?;
            (centroid, Some((normal, false)))
        }
        (_, Shape::Frustum { .. }) => {
            let (centroid, normal) = frustum_overlap(j, i)?;
            (centroid, Some((normal, true)))
        }
        _ => {
            // Clip the bounded one by the other's faces (two planes have
            // no bounded overlap, and the reader refuses that pair).
            let (bounded, other) = match (i.shape, j.shape) {
                (Shape::HalfSpace, _) => (j, i),
                _ => (i, j),
            };
            let mut faces = block_faces(bounded)?;
            for (normal, offset) in half_spaces(other) {
                faces = clip(faces, &normal, &offset);
                if faces.len() < 4 {
                    return None;
                }
            }
            let plane = match (i.shape, j.shape) {
                (Shape::HalfSpace, _) => Some((i.axes.column(2).into_owned(), true)),
                (_, Shape::HalfSpace) => Some((j.axes.column(2).into_owned(), false)),
                _ => Some((blocks_normal(i, j)?, false)),
            };
            (centroid(&faces)?, plane)
        }
    };
    let (on_i, _) = closest_surface(i, &centroid)?;
    let (on_j, _) = closest_surface(j, &centroid)?;
    let between = &on_j - &on_i;
    let depth = between.norm();
    if depth.value() == 0.0 {
        return None;
    }
    let normal = match face {
        // It pushes I away from J: out of J's face, into I's.
        Some((outward, of_i)) => {
            if of_i {
                -outward
            } else {
                outward
            }
        }
        None => {
            let normal = between / depth.clone();
            // Towards I's inside.
            let away = i.inside(&centroid) - j.inside(&centroid);
            if normal.dot(&away).value() < 0.0 {
                -normal
            } else {
                normal
            }
        }
    };
    Some(Touch {
        point: centroid,
        normal,
        depth,
    })
}

/// A round solid's radii (at its bottom and top) and its ends along its
/// axis, and the middle of its axis in ground (`None` for another shape).
fn frustum_parts<T: Number>(round: &Placed<T>) -> Option<([f64; 4], Vector3<T>)> {
    let Shape::Frustum { radii, bottom, top } = *round.shape else {
        return None;
    };
    Some(([radii[0], radii[1], bottom, top], round.centre()?))
}

/// The centroid of a round solid's overlap with `other`, a plane or a
/// block, and the outward normal of the face it meets: with a block, the
/// overlap with the face the solid's centre stands farthest beyond, kept
/// while its centroid lies within the block's other faces.
fn frustum_overlap<T: Number>(
    round: &Placed<T>,
    other: &Placed<T>,
) -> Option<(Vector3<T>, Vector3<T>)> {
    let (size, middle) = frustum_parts(round)?;
    let planes = half_spaces(other);
    let (face, (normal, offset)) = planes.iter().enumerate().max_by(|(_, a), (_, b)| {
        let beyond =
            |(normal, offset): &(Vector3<T>, T)| (normal.dot(&middle) - offset.clone()).value();
        beyond(a).total_cmp(&beyond(b))
    })?;
    let centroid = frustum_under(round, size, normal, offset)?;
    // Within the other faces, a rounding error beyond them counted in.
    let [r0, r1, bottom, top] = size;
    let tolerance = 1e-12 * (r0.max(r1) + top - bottom);
    let inside = planes.iter().enumerate().all(|(index, (normal, offset))| {
        index == face || (normal.dot(&centroid) - offset.clone()).value() <= tolerance
    });
    inside.then(|| (centroid, normal.clone()))
}

/// The centroid of the overlap of two cylinders whose axes are parallel
/// (the reader refuses other pairs): across the axes, the lens where their
/// circles overlap (each circle's segment beyond the common chord), along
/// them, the middle of the stretch both cover, measured along I's axis
/// (the run stops where the axes turn apart: [`cylinders_tilted`]).
fn cylinders_overlap<T: Number>(i: &Placed<T>, j: &Placed<T>) -> Option<Vector3<T>> {
    let c = T::from;
    let (
        Shape::Frustum {
            radii: [r1, _],
            bottom: b1,
            top: t1,
        },
        Shape::Frustum {
            radii: [r2, _],
            bottom: b2,
            top: t2,
        },
    ) = (*i.shape, *j.shape)
    else {
        return None;
    };
    let axis = i.axes.column(2).into_owned();
    // The stretch along I's axis that both cover.
    let along = |origin: &Vector3<T>| axis.dot(origin);
    let ends = |placed: &Placed<T>, bottom: f64, top: f64| {
        let base = along(&placed.origin);
        let direction = axis.dot(&placed.axes.column(2).into_owned());
        let (a, b) = (
            base.clone() + direction.clone() * c(bottom),
            base + direction * c(top),
        );
        if a.value() <= b.value() {
            (a, b)
        } else {
            (b, a)
        }
    };
    let (low_i, high_i) = ends(i, b1, t1);
    let (low_j, high_j) = ends(j, b2, t2);
    let low = if low_i.value() >= low_j.value() {
        low_i
    } else {
        low_j
    };
    let high = if high_i.value() <= high_j.value() {
        high_i
    } else {
        high_j
    };
    if high.value() <= low.value() {
        return None;
    }
    // The axes' places across them.
    let across = |origin: &Vector3<T>| origin - &axis * axis.dot(origin);
    let (centre_i, centre_j) = (across(&i.origin), across(&j.origin));
    let between = &centre_j - &centre_i;
    let distance = between.norm();
    if distance.value() >= r1 + r2 {
        return None;
    }
    let lens = if distance.value() <= (r1 - r2).abs() {
        // One circle within the other: the smaller one.
        if r1 <= r2 { centre_i } else { centre_j }
    } else {
        // The chord at `a` from I's centre towards J's.
        let toward = &between / distance.clone();
        let a = (distance.clone() * distance.clone() + c(r1 * r1 - r2 * r2))
            / (distance.clone() * c(2.0));
        let b = distance - a.clone();
        let part = |rho: T, radius: f64| {
            let theta = (-rho / c(radius)).acos();
            let (area, first_moment) = segment(&theta);
            (area * c(radius * radius), first_moment * c(radius.powi(3)))
        };
        let chord_middle = &centre_i + &toward * a.clone();
        let (area_i, moment_i) = part(a, r1);
        let (area_j, moment_j) = part(b, r2);
        let area = area_i.clone() + area_j.clone();
        // A lens too thin for its area to be told from rounding (the
        // circles just touch) is its chord's middle.
        if area.value() <= 1e-9 * r1.min(r2).powi(2) {
            chord_middle
        } else {
            (centre_i * area_i + &toward * moment_i + centre_j * area_j - &toward * moment_j) / area
        }
    };
    Some(lens + axis * ((low + high) * c(0.5)))
}

/// A round solid cut in slices across its axis: the disk at `s` along
/// the axis is centred at `origin + s axis` with radius `R(s)`.
struct Slices<'a, T: Number> {
    /// The marker's origin (where `s = 0`), in ground.
    origin: &'a Vector3<T>,
    /// The axis (the marker's z), in ground.
    axis: &'a Vector3<T>,
    /// `R(s) = radius.0 + radius.1 s`.
    radius: (f64, f64),
}

impl<T: Number> Slices<'_, T> {
    fn radius(&self, s: &T) -> T {
        T::from(self.radius.0) + s.clone() * T::from(self.radius.1)
    }

    fn point(&self, s: &T) -> Vector3<T> {
        self.origin + self.axis * s.clone()
    }

    /// Adds the volume and first moment (about ground's origin) of the
    /// whole disks from `s0` to `s1` (nothing when `s1 <= s0`): Simpson's
    /// rule, exact since the integrands are cubic in `s`.
    fn whole(&self, s0: T, s1: T, volume: &mut T, moment: &mut Vector3<T>) {
        if s1.value() <= s0.value() {
            return;
        }
        let c = T::from;
        let middle = (s0.clone() + s1.clone()) * c(0.5);
        let weight = (s1.clone() - s0.clone()) * c(std::f64::consts::PI / 6.0);
        for (s, factor) in [(s0, 1.0), (middle, 4.0), (s1, 1.0)] {
            let area = self.radius(&s).powi(2) * weight.clone() * c(factor);
            *moment += self.point(&s) * area.clone();
            *volume += area;
        }
    }
}

/// The area of the part of a unit disk beyond a chord at angle `θ`
/// (`cos θ = −ρ`, `ρ` the chord's distance from the centre, signed away
/// from the part), and that part's first moment along the direction away
/// from it.
fn segment<T: Number>(theta: &T) -> (T, T) {
    let c = T::from;
    let (sin, cos) = (theta.clone().sin(), theta.clone().cos());
    let area = c(std::f64::consts::PI) - theta.clone() + sin.clone() * cos;
    (area, sin.powi(3) * c(2.0 / 3.0))
}

/// The part of `[lo, hi]` where `a + b s <= 0`, as `(start, end)` (empty
/// when `end <= start`).
fn where_not_positive<T: Number>(a: &T, b: &T, lo: f64, hi: f64) -> (T, T) {
    let c = T::from;
    let (a_value, b_value) = (a.value(), b.value());
    if b_value == 0.0 {
        return if a_value <= 0.0 {
            (c(lo), c(hi))
        } else {
            (c(lo), c(lo))
        };
    }
    let root = -a.clone() / b.clone();
    let clamp = |s: T| {
        if s.value() < lo {
            c(lo)
        } else if s.value() > hi {
            c(hi)
        } else {
            s
        }
    };
    if b_value > 0.0 {
        (c(lo), clamp(root))
    } else {
        (clamp(root), c(hi))
    }
}

/// The centroid of the part of a round solid (radii `r0` at `bottom` and
/// `r1` at `top` along its marker's z) in the half-space
/// `normal · x <= offset`, `None` when that part has no volume. Each slice
/// across the axis is a disk the plane cuts in a circular segment, whose
/// area and centroid are known. The disk's radius `R(s)` and its centre's
/// distance `ρ(s)` from the cut are linear along the axis, so the axis
/// splits into slices that are whole (`ρ <= −R`), cut and untouched
/// (`ρ >= R`). The cut ones are integrated in the angle `θ` with
/// `cos θ = −ρ/R` (the segment's area `R² (π − θ + sin θ cos θ)`, its first
/// moment `2/3 R³ sin³ θ`): `ρ/R` is a ratio of linear functions, so `s` is
/// one of `cos θ`, and the integrands are smooth in `θ` for the 15-point
/// Kronrod rule where they have square-root ends in `s`.
fn frustum_under<T: Number>(
    round: &Placed<T>,
    [r0, r1, bottom, top]: [f64; 4],
    normal: &Vector3<T>,
    offset: &T,
) -> Option<Vector3<T>> {
    let c = T::from;
    let axis = round.axes.column(2).into_owned();
    let flare = (r1 - r0) / (top - bottom);
    let slices = Slices {
        origin: &round.origin,
        axis: &axis,
        radius: (r0 - flare * bottom, flare),
    };
    let (radius_at_0, radius_slope) = (c(slices.radius.0), c(slices.radius.1));
    let height = normal.dot(&round.origin) - offset.clone();
    let along = normal.dot(&axis);
    let across = normal - &axis * along.clone();
    let tilt = across.norm();
    let mut volume = c(0.0);
    let mut moment = Vector3::zeros();
    if tilt.value() <= 1e-12 * along.value().abs() {
        // Standing on an end: whole disks below the plane.
        let (s0, s1) = where_not_positive(&height, &along, bottom, top);
        slices.whole(s0, s1, &mut volume, &mut moment);
    } else {
        let outward = &across / tilt.clone();
        // ρ(s) = p0 + p1 s.
        let (p0, p1) = (height / tilt.clone(), along / tilt);
        // Whole where ρ + R <= 0.
        let (s0, s1) = where_not_positive(
            &(p0.clone() + radius_at_0.clone()),
            &(p1.clone() + radius_slope.clone()),
            bottom,
            top,
        );
        slices.whole(s0, s1, &mut volume, &mut moment);
        // Cut where ρ + R > 0 and ρ − R < 0.
        let (not_whole_lo, not_whole_hi) = where_not_positive(
            &-(p0.clone() + radius_at_0.clone()),
            &-(p1.clone() + radius_slope.clone()),
            bottom,
            top,
        );
        let (cut_lo, cut_hi) = where_not_positive(
            &(p0.clone() - radius_at_0.clone()),
            &(p1.clone() - radius_slope.clone()),
            not_whole_lo.value(),
            not_whole_hi.value(),
        );
        // The ends of the cut carry their derivatives from the bounds
        // they came from.
        let low = if cut_lo.value() == not_whole_lo.value() {
            not_whole_lo
        } else {
            cut_lo
        };
        let high = if cut_hi.value() == not_whole_hi.value() {
            not_whole_hi
        } else {
            cut_hi
        };
        if high.value() > low.value() {
            let cosine_at = |s: &T| {
                let cosine = -(p0.clone() + p1.clone() * s.clone()) / slices.radius(s);
                // At an end of the cut slices θ is 0 or π whatever the
                // state (and acos has no slope there).
                if cosine.value() >= 1.0 {
                    c(1.0)
                } else if cosine.value() <= -1.0 {
                    c(-1.0)
                } else {
                    cosine
                }
            };
            let (theta0, theta1) = (cosine_at(&low).acos(), cosine_at(&high).acos());
            let mut add = |s: T, theta: &T, weight: T| {
                let radius = slices.radius(&s);
                let (area, first_moment) = segment(theta);
                let area = area * radius.clone().powi(2) * weight.clone();
                let first_moment = first_moment * radius.powi(3) * weight;
                moment += slices.point(&s) * area.clone() - &outward * first_moment;
                volume += area;
            };
            // s(θ) = −(p0 + r cos θ)/(p1 + k cos θ) with R = r + k s, and
            // ds/dθ = (r p1 − p0 k) sin θ / (p1 + k cos θ)².
            let turn = radius_at_0.clone() * p1.clone() - p0.clone() * radius_slope.clone();
            let scale = radius_at_0.value().abs() * p1.value().abs()
                + p0.value().abs() * radius_slope.value().abs();
            if turn.value().abs() <= 1e-12 * scale || (theta1.value() - theta0.value()).abs() < 1e-9
            {
                // The ratio ρ/R (so θ) barely changes along the axis: the
                // integrands are smooth in s.
                let (centre, half) = ((low.clone() + high.clone()) * c(0.5), (high - low) * c(0.5));
                for (&node, &weight) in NODES.iter().zip(&KRONROD) {
                    let sides: &[f64] = if node == 0.0 { &[0.0] } else { &[-node, node] };
                    for &side in sides {
                        let s = centre.clone() + half.clone() * c(side);
                        let theta = cosine_at(&s).acos();
                        add(s, &theta, half.clone() * c(weight));
                    }
                }
            } else {
                let (centre, half) = (
                    (theta0.clone() + theta1.clone()) * c(0.5),
                    (theta1 - theta0) * c(0.5),
                );
                for (&node, &weight) in NODES.iter().zip(&KRONROD) {
                    let sides: &[f64] = if node == 0.0 { &[0.0] } else { &[-node, node] };
                    for &side in sides {
                        let theta = centre.clone() + half.clone() * c(side);
                        let cos = theta.clone().cos();
                        let denominator = p1.clone() + radius_slope.clone() * cos.clone();
                        let s = -(p0.clone() + radius_at_0.clone() * cos) / denominator.clone();
                        let rate = turn.clone() * theta.clone().sin() / denominator.powi(2);
                        add(s, &theta, half.clone() * rate * c(weight));
                    }
                }
            }
        }
    }
    let scale = r0.max(r1).powi(2) * (top - bottom);
    (volume.value().abs() > 1e-15 * scale).then(|| moment / volume)
}

/// A face: its corners in order round it.
type Face<T> = Vec<Vector3<T>>;

/// The six faces of a block, in ground (`None` for another shape).
fn block_faces<T: Number>(solid: &Placed<T>) -> Option<Vec<Face<T>>> {
    let Shape::Block { lower, upper } = *solid.shape else {
        return None;
    };
    let corner = |x: bool, y: bool, z: bool| {
        let pick = |axis: usize, high: bool| if high { upper[axis] } else { lower[axis] };
        solid.ground(&Vector3::new(pick(0, x), pick(1, y), pick(2, z)).map(T::from))
    };
    let face = |axis: usize, high: bool| {
        // The four corners with this coordinate, in order round the face.
        let order = [(false, false), (true, false), (true, true), (false, true)];
        order
            .iter()
            .map(|&(a, b)| match axis {
                0 => corner(high, a, b),
                1 => corner(a, high, b),
                _ => corner(a, b, high),
            })
            .collect()
    };
    Some(
        (0..3)
            .flat_map(|axis| [face(axis, false), face(axis, true)])
            .collect(),
    )
}

/// The half-spaces `normal · x <= offset` whose intersection is `solid`
/// (a block's six, a plane's one), in ground.
fn half_spaces<T: Number>(solid: &Placed<T>) -> Vec<(Vector3<T>, T)> {
    let mut planes = Vec::new();
    let mut add = |axis: usize, sign: f64, at: f64| {
        let normal = solid.axes.column(axis).into_owned() * T::from(sign);
        let mut point = Vector3::zeros();
        point[axis] = T::from(at);
        let offset = normal.dot(&solid.ground(&point));
        planes.push((normal, offset));
    };
    match *solid.shape {
        Shape::Block { lower, upper } => {
            for axis in 0..3 {
                add(axis, -1.0, lower[axis]);
                add(axis, 1.0, upper[axis]);
            }
        }
        Shape::HalfSpace => add(2, 1.0, 0.0),
        Shape::Sphere { .. } | Shape::Frustum { .. } => {}
    }
    planes
}

/// A convex polyhedron cut by the half-space `normal · x <= offset`: each
/// face clipped, and the cut closed by a new face (unless a face already
/// lies in the cutting plane). Heights within a trillionth of the scale
/// count as on the plane, so that flush faces are met as such.
fn clip<T: Number>(faces: Vec<Face<T>>, normal: &Vector3<T>, offset: &T) -> Vec<Face<T>> {
    let height = |point: &Vector3<T>| normal.dot(point) - offset.clone();
    let scale = faces
        .iter()
        .flatten()
        .map(|point| normal.dot(point).value().abs())
        .fold(offset.value().abs(), f64::max);
    let tolerance = 1e-12 * scale.max(f64::MIN_POSITIVE);
    let side = |height: &T| {
        if height.value() > tolerance {
            1
        } else if height.value() < -tolerance {
            -1
        } else {
            0
        }
    };
    let mut kept = Vec::new();
    let mut cut: Vec<Vector3<T>> = Vec::new();
    let mut flush = false;
    for face in faces {
        let mut clipped = Vec::new();
        let mut on_plane = 0;
        for (index, point) in face.iter().enumerate() {
            let next = &face[(index + 1) % face.len()];
            let (here, there) = (height(point), height(next));
            let (here_side, there_side) = (side(&here), side(&there));
            if here_side <= 0 {
                clipped.push(point.clone());
            }
            if here_side == 0 {
                on_plane += 1;
                cut.push(point.clone());
            } else if here_side * there_side < 0 {
                let fraction = here.clone() / (here - there);
                let crossing = point + (next - point) * fraction;
                cut.push(crossing.clone());
                clipped.push(crossing);
            }
        }
        flush |= on_plane == face.len();
        if clipped.len() >= 3 {
            kept.push(clipped);
        }
    }
    if !flush && let Some(face) = ordered(cut, normal) {
        kept.push(face);
    }
    kept
}

/// The points of a cut (each met twice) in order round their mean, in the
/// plane of `normal`; `None` for fewer than three distinct points.
fn ordered<T: Number>(points: Vec<Vector3<T>>, normal: &Vector3<T>) -> Option<Face<T>> {
    let mut distinct: Vec<Vector3<T>> = Vec::new();
    let scale = points
        .iter()
        .map(|point| point.map(|c| c.value()).norm())
        .fold(1.0, f64::max);
    for point in points {
        let near = |other: &Vector3<T>| (other - &point).map(|c| c.value()).norm() <= 1e-12 * scale;
        if !distinct.iter().any(near) {
            distinct.push(point);
        }
    }
    if distinct.len() < 3 {
        return None;
    }
    let count = T::from(distinct.len() as f64);
    let mean = distinct
        .iter()
        .fold(Vector3::zeros(), |sum, point| sum + point)
        / count;
    let n = normal.map(|c| c.value());
    let first = (&distinct[0] - &mean).map(|c| c.value());
    let second = n.cross(&first);
    let angle = |point: &Vector3<T>| {
        let offset = (point - &mean).map(|c| c.value());
        offset.dot(&second).atan2(offset.dot(&first))
    };
    distinct.sort_by(|a, b| angle(a).total_cmp(&angle(b)));
    Some(distinct)
}

/// The centroid of a convex polyhedron, by tetrahedra from its corners'
/// mean; `None` when it has no volume.
fn centroid<T: Number>(faces: &[Face<T>]) -> Option<Vector3<T>> {
    let corners: Vec<&Vector3<T>> = faces.iter().flatten().collect();
    let apex = corners
        .iter()
        .fold(Vector3::zeros(), |sum, point| sum + *point)
        / T::from(corners.len() as f64);
    let mut volume = T::from(0.0);
    let mut moment = Vector3::zeros();
    for face in faces {
        for index in 1..face.len() - 1 {
            let (a, b, c) = (&face[0], &face[index], &face[index + 1]);
            let signed = (a - &apex).dot(&(b - &apex).cross(&(c - &apex))) / T::from(6.0);
            let size = if signed.value() < 0.0 {
                -signed
            } else {
                signed
            };
            moment += (&apex + a + b + c) * (size.clone() / T::from(4.0));
            volume += size;
        }
    }
    let extent = corners
        .iter()
        .map(|point| (*point - &apex).map(|c| c.value()).norm())
        .fold(0.0, f64::max);
    (volume.value() > 1e-15 * extent.powi(3)).then(|| moment / volume)
}

/// The part of the way to a solid's surface (plus the allowed first
/// depth) that one step may close ([`step_limit`]).
const APPROACH_FRACTION: f64 = 0.5;

/// The largest step after which the solids of `contact`, apart now, can
/// overlap by no more than the depth its force first meets with
/// (`DMAX`, or a tenth of the thinner solid's least size when that is
/// less), so that the run's looks inside the step see the touch (and
/// locate it): the contact's [`separation`] and its rate (a lower bound on
/// the distance, and no rate, for solids of flat faces) against upper
/// bounds on their closing speed and its rate (`accelerations`: each
/// body's centre acceleration and angular acceleration, in size). An
/// error-controlled step that sees no force would otherwise step a falling
/// body through a thin plate. Infinite when they overlap (the force is
/// then in the equations) or do not approach.
pub(super) fn step_limit(
    model: &Model,
    contact: &Contact,
    kinematics: &[Kinematics<f64>],
    accelerations: &[(f64, f64)],
    (distance, rate): (f64, f64),
) -> f64 {
    if distance <= 0.0 {
        return f64::INFINITY;
    }
    let (i, j) = (
        placed(model, &contact.i, kinematics),
        placed(model, &contact.j, kinematics),
    );
    let allowed = contact
        .damping_depth
        .min(0.1 * least_size(&i).min(least_size(&j)));
    // Points of the two solids lie within `reach` of `middle`.
    let (bounded, other) = if matches!(i.shape, Shape::HalfSpace) {
        (&j, &i)
    } else {
        (&i, &j)
    };
    let (centre, radius) = bounding_sphere(bounded);
    let (middle, reach) = match bounding_sphere_of(other) {
        Some((other_centre, other_radius)) => {
            let middle = (centre + other_centre) / 2.0;
            let half = (centre - other_centre).norm() / 2.0;
            (middle, half + radius.max(other_radius))
        }
        None => (centre, radius),
    };
    // Each body's velocity at `middle`, its angular velocity, and a bound
    // on the acceleration of its points within `reach` of `middle`.
    let motion = |body: Option<usize>| match body {
        None => (Vector3::zeros(), Vector3::zeros(), 0.0),
        Some(body) => {
            let state = &kinematics[body];
            let arm = middle - state.centre;
            let at_middle = state.velocity + state.omega_ground.cross(&arm);
            let (linear, angular) = accelerations[body];
            let spin = state.omega_ground.norm_squared();
            let acceleration = linear + (angular + spin) * (arm.norm() + reach);
            (at_middle, state.omega_ground, acceleration)
        }
    };
    let ((v_i, w_i, a_i), (v_j, w_j, a_j)) = (motion(i.body), motion(j.body));
    // A sphere's distance to a solid has an exact rate (the relative
    // velocity at the closest points along their normal): only its
    // approach counts, so a ball rolling fast past a wall is not held to
    // short steps. Otherwise any relative motion of the solids' points.
    let sphere = matches!(i.shape, Shape::Sphere { .. }) || matches!(j.shape, Shape::Sphere { .. });
    let speed = if sphere {
        (-rate).max(0.0)
    } else {
        (v_i - v_j).norm() + (w_i - w_j).norm() * reach
    };
    let acceleration = a_i + a_j;
    // The step in which `speed h + acceleration h²/2` reaches the way.
    let way = APPROACH_FRACTION * (distance + allowed);
    let root = speed.hypot((2.0 * acceleration * way).sqrt());
    if speed + root == 0.0 {
        return f64::INFINITY;
    }
    2.0 * way / (speed + root)
}

/// A sphere that holds a bounded solid: its centre and radius in ground.
fn bounding_sphere(solid: &Placed<f64>) -> (Vector3<f64>, f64) {
    bounding_sphere_of(solid).unwrap_or((solid.origin, 0.0))
}

/// [`bounding_sphere`], `None` for a half-space.
fn bounding_sphere_of(solid: &Placed<f64>) -> Option<(Vector3<f64>, f64)> {
    let radius = match *solid.shape {
        Shape::Sphere { radius } => radius,
        Shape::Block { lower, upper } => (upper - lower).norm() / 2.0,
        Shape::Frustum { radii, bottom, top } => radii[0].max(radii[1]).hypot((top - bottom) / 2.0),
        Shape::HalfSpace => return None,
    };
    Some((solid.centre()?, radius))
}

/// A solid's least size (infinite for a half-space).
fn least_size(solid: &Placed<f64>) -> f64 {
    match *solid.shape {
        Shape::Sphere { radius } => radius,
        Shape::Block { lower, upper } => (upper - lower).min(),
        Shape::Frustum { radii, bottom, top } => radii[0].max(radii[1]).min(top - bottom),
        Shape::HalfSpace => f64::INFINITY,
    }
}

/// A lower bound on the distance between two solids (negative or zero
/// when they may overlap): exact for a sphere against anything and for a
/// block or a cylinder against a plane; for two blocks, the widest gap
/// between their shadows on the fifteen axes that separate boxes; for a
/// round solid and a block, the farthest it stands beyond one of the block's
/// faces.
fn distance_bound(i: &Placed<f64>, j: &Placed<f64>) -> Option<f64> {
    match (i.shape, j.shape) {
        (Shape::Sphere { radius }, _) => sphere_distance(&i.origin, *radius, j),
        (_, Shape::Sphere { radius }) => sphere_distance(&j.origin, *radius, i),
        (Shape::Frustum { .. }, Shape::Frustum { .. }) => Some(cylinders_gap(i, j)),
        (Shape::Frustum { .. }, _) => Some(frustum_gap(i, j)),
        (_, Shape::Frustum { .. }) => Some(frustum_gap(j, i)),
        (Shape::HalfSpace, _) => Some(lowest_height(j, i)),
        (_, Shape::HalfSpace) => Some(lowest_height(i, j)),
        _ => Some(shadow_gap(i, j)),
    }
}

/// How far a round solid stands beyond the farthest of `other`'s faces (a
/// plane's one, a block's six): a lower bound on their distance, exact
/// for a plane (the solid's lowest point towards a face lies on the rim of
/// one of its ends).
fn frustum_gap(round: &Placed<f64>, other: &Placed<f64>) -> f64 {
    half_spaces(other)
        .iter()
        .filter_map(|(normal, offset)| Some(normal.dot(&lowest_point(round, normal)?) - offset))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// How far apart two cylinders with parallel axes stand: the larger of
/// the gap between their round sides (the axes' distance less the radii)
/// and the gap between their ends along the axes, a lower bound on their
/// distance (their bounding spheres' distance when the axes have turned
/// apart).
fn cylinders_gap(i: &Placed<f64>, j: &Placed<f64>) -> f64 {
    let (Some(([r1, _, b1, t1], middle_i)), Some(([r2, _, b2, t2], middle_j))) =
        (frustum_parts(i), frustum_parts(j))
    else {
        return 0.0;
    };
    let axis = i.axes.column(2).into_owned();
    if axis.cross(&j.axes.column(2)).norm() > TILT {
        return bounding_gap(i, j);
    }
    let apart = middle_j - middle_i;
    let along = axis.dot(&apart);
    let across = (apart - axis * along).norm();
    let side_gap = across - r1 - r2;
    let end_gap = along.abs() - (t1 - b1) / 2.0 - (t2 - b2) / 2.0;
    side_gap.max(end_gap)
}

/// How far a sphere's surface is from `other` (negative inside it).
fn sphere_distance(centre: &Vector3<f64>, radius: f64, other: &Placed<f64>) -> Option<f64> {
    let (surface, outward) = closest_surface(other, centre)?;
    Some((centre - surface).dot(&outward) - radius)
}

/// How high a block's lowest corner stands above a plane.
fn lowest_height(block: &Placed<f64>, plane: &Placed<f64>) -> f64 {
    let up = plane.axes.column(2).into_owned();
    lowest_point(block, &up).map_or(f64::INFINITY, |corner| up.dot(&(corner - plane.origin)))
}

/// A block's eight corners in ground.
fn corners<T: Number>(block: &Placed<T>) -> Vec<Vector3<T>> {
    let Shape::Block { lower, upper } = *block.shape else {
        return Vec::new();
    };
    (0..8)
        .map(|bits: usize| {
            let pick = |axis: usize| {
                if bits >> axis & 1 == 1 {
                    upper[axis]
                } else {
                    lower[axis]
                }
            };
            block.ground(&Vector3::new(pick(0), pick(1), pick(2)).map(T::from))
        })
        .collect()
}

/// An axis two blocks' shadows are compared on: a face normal of I's or
/// of J's block, or the cross product of an edge of each.
#[derive(Clone, Copy)]
enum ShadowAxis {
    OfI(usize),
    OfJ(usize),
    Edges(usize, usize),
}

impl ShadowAxis {
    /// The unit axis, from the blocks' axes (`None` for the cross
    /// product of parallel edges).
    fn direction<T: Number>(self, i: &Placed<T>, j: &Placed<T>) -> Option<Vector3<T>> {
        match self {
            ShadowAxis::OfI(k) => Some(i.axes.column(k).into_owned()),
            ShadowAxis::OfJ(k) => Some(j.axes.column(k).into_owned()),
            ShadowAxis::Edges(k, l) => {
                let cross = i.axes.column(k).cross(&j.axes.column(l));
                let length = cross.norm();
                (length.value() > 1e-9).then(|| cross / length)
            }
        }
    }
}

/// The gap between the shadows of two blocks on each of their face
/// normals and the cross products of their edges (negative where the
/// shadows overlap).
fn shadow_gaps(i: &Placed<f64>, j: &Placed<f64>) -> Vec<(ShadowAxis, f64)> {
    let (a, b) = (corners(i), corners(j));
    let shadow = |points: &[Vector3<f64>], axis: &Vector3<f64>| {
        points
            .iter()
            .map(|point| axis.dot(point))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), x| {
                (low.min(x), high.max(x))
            })
    };
    let faces = (0..3).flat_map(|k| [ShadowAxis::OfI(k), ShadowAxis::OfJ(k)]);
    let edges = (0..3).flat_map(|k| (0..3).map(move |l| ShadowAxis::Edges(k, l)));
    faces
        .chain(edges)
        .filter_map(|kind| {
            let axis = kind.direction(i, j)?;
            let ((a_low, a_high), (b_low, b_high)) = (shadow(&a, &axis), shadow(&b, &axis));
            Some((kind, (a_low - b_high).max(b_low - a_high)))
        })
        .collect()
}

/// The widest gap between the shadows of two blocks on their face normals
/// and the cross products of their edges.
fn shadow_gap(i: &Placed<f64>, j: &Placed<f64>) -> f64 {
    shadow_gaps(i, j)
        .iter()
        .map(|&(_, gap)| gap)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The common normal of two overlapping blocks: the axis their shadows
/// overlap least on (a face's normal where an edge or a corner strikes
/// it, the cross product of two edges that cross), pointing from J's
/// block to I's. A face is preferred to a pair of edges that overlap
/// almost as little, so that blocks face to face keep a face's normal.
fn blocks_normal<T: Number>(i: &Placed<T>, j: &Placed<T>) -> Option<Vector3<T>> {
    let (i_values, j_values) = (i.values(), j.values());
    let gaps = shadow_gaps(&i_values, &j_values);
    let least = |edges: bool| {
        gaps.iter()
            .filter(|(kind, _)| matches!(kind, ShadowAxis::Edges(..)) == edges)
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .copied()
    };
    let (face, edge) = (least(false)?, least(true));
    let (kind, _) = match edge {
        Some(edge) if edge.1 > 0.95 * face.1 + 1e-12 * face.1.abs().max(1.0) => edge,
        _ => face,
    };
    let normal = kind.direction(i, j)?;
    let apart = i_values.centre()? - j_values.centre()?;
    let along = normal.map(|c| c.value()).dot(&apart);
    Some(if along < 0.0 { -normal } else { normal })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    /// A round solid placed at `origin` with its axis turned by `turn`.
    fn round(shape: &Shape, origin: Vector3<f64>, turn: Rotation3<f64>) -> Placed<'_, f64> {
        Placed {
            origin,
            axes: turn.into_inner(),
            shape,
            body: None,
        }
    }

    /// The volume and centroid of a round solid's part below the plane
    /// `normal · x = offset`, summed over `slices` thin disks, each cut
    /// area integrated across the chord in `strips` strips: a reference
    /// that shares no formula with the code.
    fn brute_force(
        solid: &Placed<f64>,
        [r0, r1, bottom, top]: [f64; 4],
        normal: &Vector3<f64>,
        offset: f64,
    ) -> (f64, Vector3<f64>) {
        let (slices, strips) = (1500, 1500);
        let (mut volume, mut moment) = (0.0, Vector3::zeros());
        let ds = (top - bottom) / slices as f64;
        for k in 0..slices {
            let s = bottom + (k as f64 + 0.5) * ds;
            let radius = r0 + (r1 - r0) * (s - bottom) / (top - bottom);
            let dx = 2.0 * radius / strips as f64;
            for m in 0..strips {
                let x = -radius + (m as f64 + 0.5) * dx;
                let half = (radius * radius - x * x).sqrt();
                // The strip from y = -half to half at x: the part below.
                let at = |y: f64| solid.ground(&Vector3::new(x, y, s));
                let height = |y: f64| normal.dot(&at(y)) - offset;
                let (h0, h1) = (height(-half), height(half));
                let (y0, y1) = if h0 <= 0.0 && h1 <= 0.0 {
                    (-half, half)
                } else if h0 > 0.0 && h1 > 0.0 {
                    continue;
                } else {
                    let cross = -half + 2.0 * half * h0 / (h0 - h1);
                    if h0 <= 0.0 {
                        (-half, cross)
                    } else {
                        (cross, half)
                    }
                };
                let size = (y1 - y0) * dx * ds;
                volume += size;
                moment += at((y0 + y1) / 2.0) * size;
            }
        }
        (volume, moment / volume)
    }

    #[test]
    fn a_frustum_cut_by_a_plane_has_the_centroid_slices_give() {
        let cases = [
            // radii, ends, the axis's turn (roll, pitch), the plane's height.
            ([0.3, 0.1], [0.0, 0.5], (0.4, 0.9), 0.05),
            ([0.2, 0.0], [-0.4, 0.0], (1.3, -0.2), -0.1),
            ([0.0, 0.25], [0.0, 0.3], (0.0, 1.2), 0.12),
            ([0.15, 0.15], [0.0, 0.4], (0.7, 0.5), 0.08),
            ([0.3, 0.2], [0.0, 0.2], (0.0, 0.0), 0.07),
            (
                [0.3, 0.1],
                [0.0, 0.5],
                (std::f64::consts::FRAC_PI_2, 0.0),
                0.0,
            ),
        ];
        for (radii, [bottom, top], (roll, pitch), offset) in cases {
            let shape = Shape::Frustum { radii, bottom, top };
            let solid = round(
                &shape,
                Vector3::new(0.1, -0.2, 0.0),
                Rotation3::from_euler_angles(roll, pitch, 0.3),
            );
            let normal = Vector3::z();
            let size = [radii[0], radii[1], bottom, top];
            let centroid = frustum_under(&solid, size, &normal, &offset).expect("a part below");
            let (_, reference) = brute_force(&solid, size, &normal, offset);
            let error = (centroid - reference).norm();
            assert!(
                error < 2e-5 * (top - bottom),
                "{radii:?} {roll} {pitch}: {centroid} against {reference}"
            );
        }
    }

    #[test]
    fn the_closest_point_of_a_frustum_is_nearer_than_any_point_of_its_surface() {
        let (radii, bottom, top) = ([0.3, 0.1], -0.1, 0.4);
        let radius_at = |z: f64| radii[0] + (radii[1] - radii[0]) * (z - bottom) / (top - bottom);
        // The surface sampled: the ends' disks and the side.
        let mut samples = Vec::new();
        for k in 0..=200 {
            let f = k as f64 / 200.0;
            for m in 0..72 {
                let angle = m as f64 * std::f64::consts::TAU / 72.0;
                let (c, s) = (angle.cos(), angle.sin());
                let z = bottom + f * (top - bottom);
                samples.push(Vector3::new(radius_at(z) * c, radius_at(z) * s, z));
                samples.push(Vector3::new(radii[0] * f * c, radii[0] * f * s, bottom));
                samples.push(Vector3::new(radii[1] * f * c, radii[1] * f * s, top));
            }
        }
        let points = [
            [0.5, 0.2, 0.1],
            [0.0, 0.05, 0.6],
            [0.05, 0.0, -0.5],
            [0.4, 0.4, 0.5],
            [0.1, 0.05, 0.0],
            [0.2, 0.0, 0.35],
            [0.01, 0.02, -0.09],
            [0.15, -0.1, 0.15],
            [0.35, 0.0, -0.15],
        ];
        for point in points {
            let local = Vector3::from(point);
            let (surface, outward) = frustum_surface(&local, radii, bottom, top).expect("defined");
            let found = (local - surface).norm();
            let nearest = samples
                .iter()
                .map(|sample| (local - sample).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                found <= nearest + 1e-12,
                "{point:?}: {found} against {nearest}"
            );
            assert!(
                nearest - found < 1e-2,
                "{point:?}: {found} against {nearest}"
            );
            assert!((outward.norm() - 1.0).abs() < 1e-12);
            // On the surface: on an end within its rim, or on the side.
            let rho = surface.xy().norm();
            let on_end = ((surface.z - bottom).abs() < 1e-12 && rho <= radii[0] + 1e-12)
                || ((surface.z - top).abs() < 1e-12 && rho <= radii[1] + 1e-12);
            let on_side = (rho - radius_at(surface.z)).abs() < 1e-12;
            assert!(on_end || on_side, "{point:?}: {surface}");
            // The normal points out: a step along it leaves the solid.
            let out = surface + outward * 1e-6;
            let inside = (bottom..=top).contains(&out.z) && out.xy().norm() <= radius_at(out.z);
            assert!(!inside, "{point:?}: {surface} {outward}");
        }
    }
}
