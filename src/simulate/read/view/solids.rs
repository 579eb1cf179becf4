//! A part's mass from its solids: each shape's volume moments in closed
//! form, moved into the ground's axes and added.

use std::f64::consts::PI;

use nalgebra::{Matrix3, Vector3};

use super::write::{ids_argument, numbers_argument};
use super::{Entity, Frame, Reader, words_and_verb};
use crate::model::Statement;
use crate::span::Span;

impl Reader<'_> {
    pub(super) fn mass_properties(&mut self, part: usize, index: usize, statement: &mut Statement) {
        let command = &self.view.statements[index];
        let span = command.span;
        let density = if let Some(material) = self.word(index, "MATERIAL_TYPE") {
            match self.find(&material) {
                Some(Entity::Material(material)) => Some(self.densities[material]),
                _ => {
                    let span = command.place_of("MATERIAL_TYPE", 13);
                    self.wrong(
                        "material_type names no material the file creates (material create material_name = ... density = ...)".into(),
                        span,
                    );
                    return;
                }
            }
        } else {
            self.numbers(index, "DENSITY", false)
                .and_then(|values| values.first().copied())
        };
        if let Some(density) = density {
            if !(density.is_finite() && density > 0.0) {
                self.wrong(
                    "the part's material has no positive density: mbexpr computes its mass from its geometry".into(),
                    span,
                );
                return;
            }
            self.mass_from_solids(part, density, statement, span);
            if self.parts[part].point_mass {
                // A point mass keeps the mass and centre of its solids.
                statement
                    .arguments
                    .retain(|argument| argument.keyword != "IP");
            }
            return;
        }
        // A point mass has a mass and a centre, no inertia.
        let point_mass = self.parts[part].point_mass;
        let (name_keyword, inertia): (&str, &[&str]) = if point_mass {
            ("POINT_MASS_NAME", &[])
        } else {
            (
                "PART_NAME",
                &["INERTIA_MARKER", "IXX", "IYY", "IZZ", "IXY", "IZX", "IYZ"],
            )
        };
        for argument in &command.arguments {
            let keyword = argument.keyword.as_str();
            if !(keyword == name_keyword
                || matches!(keyword, "MASS" | "CENTER_OF_MASS_MARKER")
                || inertia.contains(&keyword))
            {
                self.refuse_unread(command, argument);
            }
        }
        let given = |reader: &mut Self, keyword: &str| {
            reader
                .numbers(index, keyword, false)
                .and_then(|values| values.first().copied())
        };
        // A rigid body's mass left out is 0; a point mass's is left out of
        // the POINT_MASS, which says it needs one.
        let mass = given(self, "MASS").or((!point_mass).then_some(0.0));
        let moments = (!point_mass).then(|| {
            ["IXX", "IYY", "IZZ", "IXY", "IZX", "IYZ"]
                .map(|keyword| given(self, keyword).unwrap_or(0.0))
        });
        if let Some(mass) = mass {
            numbers_argument(statement, "MASS", &[mass], span);
        }
        if let Some(id) = self.marker_id(index, "CENTER_OF_MASS_MARKER") {
            ids_argument(statement, "CM", id, span);
            self.parts[part].centre_marker = Some(id);
        }
        let Some(moments) = moments else {
            return;
        };
        if let Some(id) = self.marker_id(index, "INERTIA_MARKER") {
            ids_argument(statement, "IM", id, span);
        }
        numbers_argument(statement, "IP", &moments, span);
    }

    /// MASS, CM (a marker made at the centre of mass, with the part's
    /// axes) and IP of `part` from its solids at `density`.
    fn mass_from_solids(
        &mut self,
        part: usize,
        density: f64,
        statement: &mut Statement,
        span: Span,
    ) {
        let mut total = Moments::default();
        let mut refused = false;
        for index in self.parts[part].solids.clone() {
            let (words, _) = words_and_verb(&self.view.statements[index]);
            let shape = words.trim_start_matches("GEOMETRY SHAPE ").to_string();
            match self.solid_moments(index, &shape) {
                Ok(Some(moments)) => total.add(&moments),
                Ok(None) => {}
                Err(reason) => {
                    let command = &self.view.statements[index];
                    self.refuse(command, reason, command.span);
                    refused = true;
                }
            }
        }
        for index in self.parts[part].features.clone() {
            let command = &self.view.statements[index];
            self.refuse(
                command,
                "changes its solid's volume (a blend, chamfer or hole), which mbexpr does not compute: give the part's mass, centre of mass and inertia (mass_properties with mass, center_of_mass_marker, ixx ...)".into(),
                command.span,
            );
            refused = true;
        }
        if refused {
            return;
        }
        if total.volume <= 0.0 {
            self.wrong(
                "the part's mass comes from its geometry (material_type or density), but it has no solid whose volume mbexpr computes (block, cylinder, frustum, ellipsoid, torus, link, plate, extrusion)".into(),
                span,
            );
            return;
        }
        let mass = density * total.volume;
        let centre = total.first / total.volume;
        // ∫ r rᵀ dV about the centre, then the inertia tensor.
        let second = total.second - centre * centre.transpose() * total.volume;
        let tensor = (Matrix3::identity() * second.trace() - second) * density;
        let frame = self.parts[part].frame;
        let in_part = frame.axes.transpose() * tensor * frame.axes;
        let at = Frame {
            origin: centre,
            axes: frame.axes,
        };
        let id = self.new_marker(part, at, false, span);
        self.parts[part].centre_marker = Some(id);
        numbers_argument(statement, "MASS", &[mass], span);
        ids_argument(statement, "CM", id, span);
        // Adams' products are the positive integrals (Ixy = ∫xy dm).
        numbers_argument(
            statement,
            "IP",
            &[
                in_part[(0, 0)],
                in_part[(1, 1)],
                in_part[(2, 2)],
                -in_part[(0, 1)],
                -in_part[(0, 2)],
                -in_part[(1, 2)],
            ],
            span,
        );
    }

    /// The volume moments of the solid command `index` in the ground's
    /// axes; `None` for a shape that has no volume.
    fn solid_moments(&mut self, index: usize, shape: &str) -> Result<Option<Moments>, String> {
        let marker_frame = |reader: &mut Self, keyword: &str| -> Result<Frame, String> {
            let name = reader
                .word(index, keyword)
                .ok_or_else(|| format!("has no {}", keyword.to_ascii_lowercase()))?;
            match reader.find(&name) {
                Some(Entity::Marker(marker)) => Ok(reader.markers[marker].frame),
                _ => Err(format!(
                    "{} names no marker the file creates",
                    keyword.to_ascii_lowercase()
                )),
            }
        };
        let number = |reader: &mut Self, keyword: &str, angle: bool| -> Result<f64, String> {
            reader
                .numbers(index, keyword, angle)
                .and_then(|values| values.first().copied())
                .ok_or_else(|| format!("has no {}", keyword.to_ascii_lowercase()))
        };
        let whole_turn = |reader: &mut Self| -> Result<(), String> {
            if reader.argument(index, "ANGLE_EXTENT").is_none() {
                return Ok(());
            }
            let extent = number(reader, "ANGLE_EXTENT", true)?;
            if (extent.abs() - 2.0 * PI).abs() > 1e-9 {
                return Err(
                    "is a part of a turn (angle_extent): mbexpr computes the mass of whole solids of revolution".into(),
                );
            }
            Ok(())
        };
        if self.view.statements[index].name.contains(" MODIFY ") {
            return Err(
                "changes a solid after its creation: mbexpr reads a part's solids as created"
                    .into(),
            );
        }
        let local = match shape {
            "BLOCK" => {
                let frame = marker_frame(self, "CORNER_MARKER")?;
                let corner = self
                    .numbers(index, "DIAG_CORNER_COORDS", false)
                    .filter(|values| values.len() == 3)
                    .ok_or("has no diag_corner_coords")?;
                (
                    frame,
                    Moments::block(Vector3::new(corner[0], corner[1], corner[2])),
                )
            }
            "CYLINDER" => {
                whole_turn(self)?;
                let frame = marker_frame(self, "CENTER_MARKER")?;
                let (length, radius) = (
                    number(self, "LENGTH", false)?,
                    number(self, "RADIUS", false)?,
                );
                (frame, Moments::frustum(length, radius, radius))
            }
            "FRUSTUM" => {
                whole_turn(self)?;
                let frame = marker_frame(self, "CENTER_MARKER")?;
                let length = number(self, "LENGTH", false)?;
                let bottom = number(self, "BOTTOM_RADIUS", false)?;
                let top = number(self, "TOP_RADIUS", false)?;
                (frame, Moments::frustum(length, bottom, top))
            }
            "ELLIPSOID" => {
                let frame = marker_frame(self, "CENTER_MARKER")?;
                let scales = ["X_SCALE_FACTOR", "Y_SCALE_FACTOR", "Z_SCALE_FACTOR"]
                    .map(|keyword| number(self, keyword, false));
                let [x, y, z] = [&scales[0], &scales[1], &scales[2]].map(|scale| scale.clone());
                (frame, Moments::ellipsoid(x? / 2.0, y? / 2.0, z? / 2.0))
            }
            "TORUS" => {
                whole_turn(self)?;
                let frame = marker_frame(self, "CENTER_MARKER")?;
                let major = number(self, "MAJOR_RADIUS", false)?;
                let minor = number(self, "MINOR_RADIUS", false)?;
                (frame, Moments::torus(major, minor))
            }
            "LINK" => {
                let start = marker_frame(self, "I_MARKER")?;
                let end = marker_frame(self, "J_MARKER")?;
                let width = number(self, "WIDTH", false)?;
                let depth = number(self, "DEPTH", false)?;
                let along = end.origin - start.origin;
                let length = along.norm();
                let x = along
                    .try_normalize(1e-12 * start.origin.amax().max(1.0))
                    .ok_or("has its I and J markers at one point")?;
                let z = start.axes.column(2) - x * x.dot(&start.axes.column(2));
                let z = z
                    .try_normalize(1e-9)
                    .ok_or("has its J marker off the I marker's xy plane")?;
                let frame = Frame {
                    origin: start.origin,
                    axes: Matrix3::from_columns(&[x, z.cross(&x), z]),
                };
                (frame, Moments::link(length, width, depth))
            }
            "PLATE" => {
                let names = self.names(index, "MARKER_NAME");
                let mut corners = Vec::new();
                for name in names {
                    match self.find(&name) {
                        Some(Entity::Marker(marker)) => {
                            corners.push(self.markers[marker].frame.origin)
                        }
                        _ => {
                            return Err(format!(
                                "marker_name: {name} is no marker the file creates"
                            ));
                        }
                    }
                }
                let thickness = number(self, "WIDTH", false)?;
                let radius = number(self, "RADIUS", false)?;
                plate(&corners, thickness, radius)?
            }
            "EXTRUSION" => {
                if self.argument(index, "PATH_POINTS").is_some() {
                    return Err(
                        "is extruded along a path: mbexpr computes the mass of straight extrusions"
                            .into(),
                    );
                }
                if self.cylindrical {
                    return Err("is drawn by points, which mbexpr reads in cartesian coordinates only: give the part's mass, centre of mass and inertia, or draw the file in cartesian coordinates".into());
                }
                let frame = marker_frame(self, "REFERENCE_MARKER")?;
                let points = self
                    .numbers(index, "POINTS_FOR_PROFILE", false)
                    .filter(|values| values.len() >= 9 && values.len() % 3 == 0)
                    .ok_or(
                        "has no points_for_profile (three or more points, three numbers each)",
                    )?;
                let length = number(self, "LENGTH_ALONG_Z_AXIS", false)?;
                (frame, extrusion(&points, length)?)
            }
            _ => {
                return Err(
                    "is a shape whose volume mbexpr does not compute: give the part's mass, centre of mass and inertia (mass_properties with mass, center_of_mass_marker, ixx ...)".into(),
                );
            }
        };
        let (frame, moments) = local;
        if !(moments.volume.is_finite() && moments.volume > 0.0) {
            return Err("has no volume: its sizes must be positive".into());
        }
        Ok(Some(moments.moved(&frame)))
    }
}

/// A solid's volume and its first and second volume moments (`∫ r dV`,
/// `∫ r rᵀ dV`) about a point.
#[derive(Clone, Copy, Default)]
struct Moments {
    volume: f64,
    first: Vector3<f64>,
    second: Matrix3<f64>,
}

impl Moments {
    fn add(&mut self, other: &Moments) {
        self.volume += other.volume;
        self.first += other.first;
        self.second += other.second;
    }

    /// These moments (about `frame`'s origin, in its axes) about the
    /// ground's origin in its axes.
    fn moved(&self, frame: &Frame) -> Moments {
        let axes = frame.axes;
        let first = axes * self.first;
        let second = axes * self.second * axes.transpose();
        let origin = frame.origin;
        Moments {
            volume: self.volume,
            first: first + origin * self.volume,
            second: second
                + first * origin.transpose()
                + origin * first.transpose()
                + origin * origin.transpose() * self.volume,
        }
    }

    /// A box from the origin to the corner `d`.
    fn block(d: Vector3<f64>) -> Moments {
        let volume = (d.x * d.y * d.z).abs();
        let mut second = d * d.transpose() * (volume / 4.0);
        for axis in 0..3 {
            second[(axis, axis)] = volume * d[axis] * d[axis] / 3.0;
        }
        Moments {
            volume,
            first: d * (volume / 2.0),
            second,
        }
    }

    /// A frustum along z from the origin (radius `bottom`) to `length`
    /// (radius `top`): a cylinder when they are equal. Gauss–Legendre with
    /// three points is exact for the polynomials of degree 4 in z.
    fn frustum(length: f64, bottom: f64, top: f64) -> Moments {
        let nodes = [
            (-(0.6_f64.sqrt()), 5.0 / 9.0),
            (0.0, 8.0 / 9.0),
            (0.6_f64.sqrt(), 5.0 / 9.0),
        ];
        let mut moments = Moments::default();
        for (node, weight) in nodes {
            let t = 0.5 * (node + 1.0);
            let z = t * length;
            let radius = bottom + (top - bottom) * t;
            let dz = 0.5 * weight * length.abs();
            let area = PI * radius * radius;
            moments.volume += area * dz;
            moments.first.z += z * area * dz;
            let across = area * radius * radius / 4.0 * dz;
            moments.second[(0, 0)] += across;
            moments.second[(1, 1)] += across;
            moments.second[(2, 2)] += z * z * area * dz;
        }
        moments
    }

    /// An ellipsoid about the origin with semi-axes `a`, `b`, `c`.
    fn ellipsoid(a: f64, b: f64, c: f64) -> Moments {
        let volume = 4.0 / 3.0 * PI * (a * b * c).abs();
        Moments {
            volume,
            first: Vector3::zeros(),
            second: Matrix3::from_diagonal(&Vector3::new(a * a, b * b, c * c)) * (volume / 5.0),
        }
    }

    /// A torus about the z axis: its tube of radius `minor` around the
    /// circle of radius `major`.
    fn torus(major: f64, minor: f64) -> Moments {
        let volume = 2.0 * PI * PI * major * minor * minor;
        let across = volume * (major * major / 2.0 + 3.0 * minor * minor / 8.0);
        Moments {
            volume,
            first: Vector3::zeros(),
            second: Matrix3::from_diagonal(&Vector3::new(
                across,
                across,
                volume * minor * minor / 4.0,
            )),
        }
    }

    /// View's link: a bar from the origin along x of `length`, `width`
    /// across (y) with rounded ends, and `depth` thick (z), centred on the
    /// xy plane. View rounds each end by half of a regular 20-gon inscribed
    /// in the end's circle (ten sides, from one corner of the bar to the
    /// other), and so its mass: a user's link of 100 × 10 × 5 mm at 7.801
    /// g/cm³ has mass 0.042018302 and moments 0.4311056795, 40.77766026,
    /// 41.03368968 in View's export, the 20-gon's to ten digits (the exact
    /// semicircles give 0.0420684).
    fn link(length: f64, width: f64, depth: f64) -> Moments {
        let radius = width / 2.0;
        let step = 2.0 * PI / f64::from(LINK_SIDES);
        let mut points = vec![[0.0, -radius], [length, -radius]];
        for k in 1..LINK_SIDES / 2 {
            let angle = -PI / 2.0 + f64::from(k) * step;
            points.push([length + radius * angle.cos(), radius * angle.sin()]);
        }
        points.extend([[length, radius], [0.0, radius]]);
        for k in 1..LINK_SIDES / 2 {
            let angle = PI / 2.0 + f64::from(k) * step;
            points.push([radius * angle.cos(), radius * angle.sin()]);
        }
        prism(Outline::polygon(&points).abs(), -depth / 2.0, depth / 2.0)
    }
}

/// The sides of the regular polygon View draws a link's rounded ends by
/// (half of it at each end).
const LINK_SIDES: u32 = 20;

/// View's plate: the outline around its corners (`corners`, in ground),
/// each corner a circle of `radius` about its marker joined to the next by
/// tangent lines (the convex polygon of the corners widened by `radius`,
/// as a link is about its two markers), `thickness` thick and centred on
/// the corners' plane. Its frame (the first corner, the first side along
/// x, the plane's normal along z) and its moments there.
fn plate(
    corners: &[Vector3<f64>],
    thickness: f64,
    radius: f64,
) -> Result<(Frame, Moments), String> {
    if corners.len() < 3 {
        return Err("has fewer than three corners (marker_name)".into());
    }
    if !(thickness > 0.0 && radius >= 0.0) {
        return Err("has no volume: its width must be positive and its radius not negative".into());
    }
    // The plane's normal by Newell's method, and the corners in it.
    let mut normal = Vector3::zeros();
    for (k, a) in corners.iter().enumerate() {
        let b = corners[(k + 1) % corners.len()];
        normal += Vector3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    let size = corners.iter().fold(0.0_f64, |most, corner| {
        most.max((corner - corners[0]).norm())
    });
    let normal = normal
        .try_normalize(1e-12 * size * size)
        .ok_or("has its corners on one line")?;
    if corners
        .iter()
        .any(|corner| normal.dot(&(corner - corners[0])).abs() > 1e-9 * size)
    {
        return Err("has its corners off one plane".into());
    }
    let x = (corners[1] - corners[0])
        .try_normalize(1e-12 * size)
        .ok_or("has two corners at one point")?;
    let y = normal.cross(&x);
    let points: Vec<[f64; 2]> = corners
        .iter()
        .map(|corner| {
            let d = corner - corners[0];
            [d.dot(&x), d.dot(&y)]
        })
        .collect();
    let outline = Outline::of(&points, radius)?;
    let t = thickness;
    let moments = Moments {
        volume: outline.area * t,
        first: Vector3::new(outline.x, outline.y, 0.0) * t,
        second: Matrix3::new(
            outline.xx * t,
            outline.xy * t,
            0.0, //
            outline.xy * t,
            outline.yy * t,
            0.0, //
            0.0,
            0.0,
            outline.area * t * t * t / 12.0,
        ),
    };
    let frame = Frame {
        origin: corners[0],
        axes: Matrix3::from_columns(&[x, y, normal]),
    };
    Ok((frame, moments))
}

/// View's extrusion: the profile `points` (x, y, z in its reference
/// marker, all at one z) extruded along z by `length` (towards −z when
/// negative), in the marker's frame.
fn extrusion(points: &[f64], length: f64) -> Result<Moments, String> {
    let z0 = points[2];
    if points
        .chunks(3)
        .any(|point| (point[2] - z0).abs() > 1e-9 * (1.0 + z0.abs()))
    {
        return Err("has its profile off one plane of its reference marker's z".into());
    }
    let profile: Vec<[f64; 2]> = points.chunks(3).map(|point| [point[0], point[1]]).collect();
    let outline = Outline::polygon(&profile).abs();
    let (start, end) = if length < 0.0 {
        (z0 + length, z0)
    } else {
        (z0, z0 + length)
    };
    Ok(prism(outline, start, end))
}

/// The moments of the region `outline` of the xy plane swept along z
/// from `start` to `end`.
fn prism(outline: Outline, start: f64, end: f64) -> Moments {
    let depth = end - start;
    let z = (end * end - start * start) / 2.0;
    let zz = (end.powi(3) - start.powi(3)) / 3.0;
    Moments {
        volume: outline.area * depth,
        first: Vector3::new(outline.x * depth, outline.y * depth, outline.area * z),
        second: Matrix3::new(
            outline.xx * depth,
            outline.xy * depth,
            outline.x * z, //
            outline.xy * depth,
            outline.yy * depth,
            outline.y * z, //
            outline.x * z,
            outline.y * z,
            outline.area * zz,
        ),
    }
}

/// A plane region's area and its first and second moments about the
/// origin (`∫x`, `∫y`, `∫x²`, `∫y²`, `∫xy`).
#[derive(Clone, Copy, Default)]
struct Outline {
    area: f64,
    x: f64,
    y: f64,
    xx: f64,
    yy: f64,
    xy: f64,
}

impl Outline {
    /// The convex polygon `points` widened by `radius`: the polygon, a
    /// rectangle outside each side and a sector about each corner.
    fn of(points: &[[f64; 2]], radius: f64) -> Result<Outline, String> {
        let mut points = points.to_vec();
        let mut outline = Outline::polygon(&points);
        if outline.area < 0.0 {
            points.reverse();
            outline = Outline::polygon(&points);
        }
        let n = points.len();
        let side = |k: usize| {
            let [a, b] = [points[k], points[(k + 1) % n]];
            [b[0] - a[0], b[1] - a[1]]
        };
        for k in 0..n {
            let [before, after] = [side((k + n - 1) % n), side(k)];
            if before[0] * after[1] - before[1] * after[0] < -1e-12 * (outline.area.abs() + 1e-300)
            {
                return Err(
                    "has a concave outline (its corners turn both ways): mbexpr computes the mass of convex plates".into(),
                );
            }
        }
        if radius == 0.0 {
            return Ok(outline);
        }
        // The outward normal's angle of each side (counter-clockwise).
        let angle = |k: usize| {
            let [dx, dy] = side(k);
            dy.atan2(dx) - std::f64::consts::FRAC_PI_2
        };
        for k in 0..n {
            let [a, b] = [points[k], points[(k + 1) % n]];
            let theta = angle(k);
            let out = [radius * theta.cos(), radius * theta.sin()];
            outline.add(
                &Outline::polygon(&[
                    a,
                    [a[0] + out[0], a[1] + out[1]],
                    [b[0] + out[0], b[1] + out[1]],
                    b,
                ])
                .abs(),
            );
            let start = angle((k + n - 1) % n);
            let turn = (theta - start).rem_euclid(2.0 * PI);
            outline.add(&Outline::sector(radius, start, start + turn).about(a));
        }
        Ok(outline)
    }

    /// A polygon's (signed by its turn: positive counter-clockwise).
    fn polygon(points: &[[f64; 2]]) -> Outline {
        let mut outline = Outline::default();
        for (k, &[x0, y0]) in points.iter().enumerate() {
            let [x1, y1] = points[(k + 1) % points.len()];
            let cross = x0 * y1 - x1 * y0;
            outline.area += cross / 2.0;
            outline.x += (x0 + x1) * cross / 6.0;
            outline.y += (y0 + y1) * cross / 6.0;
            outline.xx += (x0 * x0 + x0 * x1 + x1 * x1) * cross / 12.0;
            outline.yy += (y0 * y0 + y0 * y1 + y1 * y1) * cross / 12.0;
            outline.xy += (x0 * y1 + 2.0 * x0 * y0 + 2.0 * x1 * y1 + x1 * y0) * cross / 24.0;
        }
        outline
    }

    /// A sector of a disc of `radius` about the origin, from angle `from`
    /// to `to` counter-clockwise.
    fn sector(radius: f64, from: f64, to: f64) -> Outline {
        let (r2, r3, r4) = (radius * radius, radius.powi(3), radius.powi(4));
        let turn = to - from;
        let double = ((2.0 * to).sin() - (2.0 * from).sin()) / 4.0;
        Outline {
            area: r2 * turn / 2.0,
            x: r3 / 3.0 * (to.sin() - from.sin()),
            y: r3 / 3.0 * (from.cos() - to.cos()),
            xx: r4 / 4.0 * (turn / 2.0 + double),
            yy: r4 / 4.0 * (turn / 2.0 - double),
            xy: r4 / 8.0 * (to.sin().powi(2) - from.sin().powi(2)),
        }
    }

    /// These moments of a region moved by `by`.
    fn about(self, [dx, dy]: [f64; 2]) -> Outline {
        Outline {
            area: self.area,
            x: self.x + dx * self.area,
            y: self.y + dy * self.area,
            xx: self.xx + 2.0 * dx * self.x + dx * dx * self.area,
            yy: self.yy + 2.0 * dy * self.y + dy * dy * self.area,
            xy: self.xy + dx * self.y + dy * self.x + dx * dy * self.area,
        }
    }

    /// The region's moments with its area positive.
    fn abs(self) -> Outline {
        let sign = self.area.signum();
        Outline {
            area: self.area * sign,
            x: self.x * sign,
            y: self.y * sign,
            xx: self.xx * sign,
            yy: self.yy * sign,
            xy: self.xy * sign,
        }
    }

    fn add(&mut self, other: &Outline) {
        self.area += other.area;
        self.x += other.x;
        self.y += other.y;
        self.xx += other.xx;
        self.yy += other.yy;
        self.xy += other.xy;
    }
}
