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
            return;
        }
        for argument in &command.arguments {
            let keyword = argument.keyword.as_str();
            if !matches!(
                keyword,
                "PART_NAME"
                    | "MASS"
                    | "CENTER_OF_MASS_MARKER"
                    | "INERTIA_MARKER"
                    | "IXX"
                    | "IYY"
                    | "IZZ"
                    | "IXY"
                    | "IZX"
                    | "IYZ"
            ) {
                self.refuse_unread(command, argument);
            }
        }
        let value = |reader: &mut Self, keyword: &str| {
            reader
                .numbers(index, keyword, false)
                .and_then(|values| values.first().copied())
                .unwrap_or(0.0)
        };
        let mass = value(self, "MASS");
        let moments =
            ["IXX", "IYY", "IZZ", "IXY", "IZX", "IYZ"].map(|keyword| value(self, keyword));
        numbers_argument(statement, "MASS", &[mass], span);
        if let Some(id) = self.marker_id(index, "CENTER_OF_MASS_MARKER") {
            ids_argument(statement, "CM", id, span);
            self.parts[part].centre_marker = Some(id);
        }
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
        if refused {
            return;
        }
        if total.volume <= 0.0 {
            self.wrong(
                "the part's mass comes from its geometry (material_type or density), but it has no solid whose volume mbexpr computes (block, cylinder, frustum, ellipsoid, torus, link)".into(),
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
    /// across (y) with semicircular ends, and `depth` thick (z), centred on
    /// the xy plane.
    fn link(length: f64, width: f64, depth: f64) -> Moments {
        let radius = width / 2.0;
        let bar = length * width * depth;
        let half_disc = PI * radius * radius * depth / 2.0;
        // Each half disc's centroid lies 4r/3π beyond its end.
        let out = 4.0 * radius / (3.0 * PI);
        let xx = bar * length * length / 3.0
            + half_disc * radius * radius / 4.0
            + half_disc * (radius * radius / 4.0 + 2.0 * length * out + length * length);
        let yy = bar * width * width / 12.0 + 2.0 * half_disc * radius * radius / 4.0;
        let zz = (bar + 2.0 * half_disc) * depth * depth / 12.0;
        let volume = bar + 2.0 * half_disc;
        Moments {
            volume,
            first: Vector3::new(volume * length / 2.0, 0.0, 0.0),
            second: Matrix3::from_diagonal(&Vector3::new(xx, yy, zz)),
        }
    }
}
