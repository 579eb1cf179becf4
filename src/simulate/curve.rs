//! A `CURVE` statement's curve: a B-spline in three dimensions, its
//! parameter `α` running from −1 to 1 as Adams Solver's B-spline curves'
//! does, held as one polynomial piece per knot span so that it is
//! evaluated over any [`Number`] (dual numbers carry their derivatives
//! through it).
//!
//! The points of the curve's MATRIX are its control points, or, with
//! `CURVE_POINTS`, points the curve passes through:
//! - an OPEN curve is clamped (it starts at the first point and ends at the
//!   last); through points, they are met at evenly spaced parameters, the
//!   inner knots the averages of those parameters (de Boor's choice);
//! - a CLOSED curve is periodic with evenly spaced knots (a last point equal
//!   to the first is dropped); through points, they are met at evenly
//!   spaced parameters, at the knots for odd degrees and midway between
//!   them for even ones.
//!
//! At ORDER = 2 (straight pieces) the curve is the polygon through the
//! points whatever the parameters.

use nalgebra::{DMatrix, Vector3};

use crate::number::Number;

/// The highest ORDER (degree + 1) read.
pub const MAX_ORDER: usize = 8;

/// How far, in parts of its piece, a point of contact goes past a knot
/// before the crossing switches pieces ([`Curve::switching`]): far above
/// the rounding of its parameter (1e-13 of it), far below anything the
/// held piece's polynomial continued past the knot changes (its third
/// derivative's jump times the cube of the overshoot).
const KNOT_MARGIN: f64 = 1e-8;

/// A B-spline curve as polynomial pieces in its parameter `α ∈ [−1, 1]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// The statement id.
    pub id: u64,
    /// The pieces in order, covering [−1, 1].
    pieces: Vec<Piece>,
    /// Whether it closes on itself (its parameter wraps around).
    pub closed: bool,
}

/// One piece: `s(α) = Σ c_k (α − start)^k` on `[start, end]`, within
/// `radius` of `centre`.
#[derive(Clone, Debug, PartialEq)]
struct Piece {
    start: f64,
    end: f64,
    coefficients: Vec<Vector3<f64>>,
    centre: Vector3<f64>,
    radius: f64,
    /// The axis (x, y or z of the curve's frame) least along the piece:
    /// the normals of a point of contact on it are taken square to the
    /// tangent starting from it.
    reference: Vector3<f64>,
}

impl Piece {
    /// The piece's point at `alpha` and its first two derivatives (its
    /// polynomial continued past its ends).
    fn at<T: Number>(&self, alpha: &T) -> CurvePoint<T> {
        let local = alpha.clone() - T::from(self.start);
        let lift = |c: &Vector3<f64>| c.map(T::from);
        let mut place = Vector3::zeros();
        let mut tangent = Vector3::zeros();
        let mut bend = Vector3::zeros();
        for (k, c) in self.coefficients.iter().enumerate().rev() {
            place = place * local.clone() + lift(c);
            if k >= 1 {
                tangent = tangent * local.clone() + lift(&(c * k as f64));
            }
            if k >= 2 {
                bend = bend * local.clone() + lift(&(c * (k * (k - 1)) as f64));
            }
        }
        CurvePoint {
            place,
            tangent,
            bend,
        }
    }

    /// `count + 1` parameters evenly along the piece, its ends included.
    fn samples(&self, count: u32) -> impl Iterator<Item = f64> + '_ {
        (0..=count)
            .map(move |k| self.start + (self.end - self.start) * f64::from(k) / f64::from(count))
    }

    /// Sets `centre` and `radius` to a ball that holds the piece: the
    /// samples' mean, their farthest distance from it, and the most the
    /// piece can bulge between samples (`h² max|s''| / 8`, doubled).
    fn bound(&mut self) {
        const SAMPLES: u32 = 32;
        let points: Vec<CurvePoint<f64>> =
            self.samples(SAMPLES).map(|alpha| self.at(&alpha)).collect();
        let centre = points.iter().map(|at| at.place).sum::<Vector3<f64>>() / points.len() as f64;
        let farthest = points
            .iter()
            .map(|at| (at.place - centre).norm())
            .fold(0.0, f64::max);
        let bend = points.iter().map(|at| at.bend.norm()).fold(0.0, f64::max);
        let step = (self.end - self.start) / f64::from(SAMPLES);
        self.centre = centre;
        self.radius = farthest + step * step * bend / 4.0;
    }

    /// Sets `reference` to the axis of x, y and z whose largest cosine
    /// with the piece's tangent, over points along it, is least.
    fn choose_reference(&mut self) {
        let mut worst = [0.0f64; 3];
        for alpha in self.samples(TANGENT_SAMPLES) {
            let Some(unit) = self.at(&alpha).tangent.try_normalize(0.0) else {
                continue;
            };
            for (axis, worst) in worst.iter_mut().enumerate() {
                *worst = worst.max(unit[axis].abs());
            }
        }
        let axis = (0..3)
            .min_by(|&a, &b| worst[a].total_cmp(&worst[b]))
            .unwrap_or(2);
        self.reference = Vector3::ith(axis, 1.0);
    }
}

/// How many steps along a piece its tangent is looked at (for the
/// normals' reference axis, and for a tangent that vanishes).
const TANGENT_SAMPLES: u32 = 12;

/// A point of a curve with its first two derivatives in the parameter.
pub struct CurvePoint<T: Number> {
    /// `s(α)`.
    pub place: Vector3<T>,
    /// `ds/dα`.
    pub tangent: Vector3<T>,
    /// `d²s/dα²`.
    pub bend: Vector3<T>,
}

impl Curve {
    /// The B-spline of `order` (2 for straight pieces, 4 for cubic) whose
    /// control points are `points`, or that passes through them when
    /// `through` is set; closed when `closed` is. The reason it cannot be
    /// made otherwise.
    pub fn new(
        id: u64,
        points: &[Vector3<f64>],
        order: usize,
        closed: bool,
        through: bool,
    ) -> Result<Curve, String> {
        if !(2..=MAX_ORDER).contains(&order) {
            return Err(format!(
                "ORDER must be 2 (straight pieces) to {MAX_ORDER}, not {order}"
            ));
        }
        let mut points = points.to_vec();
        if closed
            && points.len() > 2
            && (points[0] - points[points.len() - 1]).norm()
                <= 1e-12 * points.iter().map(|p| p.amax()).fold(1.0, f64::max)
        {
            points.pop();
        }
        let degree = order - 1;
        let least = if closed { order.max(3) } else { order };
        if points.len() < least {
            return Err(format!(
                "{} curve of ORDER {order} needs at least {least} points, and its MATRIX gives {}",
                if closed { "a CLOSED" } else { "an OPEN" },
                points.len()
            ));
        }
        let (knots, controls) = if closed {
            periodic(&points, degree, through)?
        } else {
            clamped(&points, degree, through)?
        };
        let (low, high) = if closed {
            (knots[degree], knots[degree + points.len()])
        } else {
            (knots[degree], knots[knots.len() - 1 - degree])
        };
        let scale = (high - low) / 2.0;
        let mut pieces = Vec::new();
        for span in degree..controls.len() {
            let (a, b) = (knots[span], knots[span + 1]);
            if b <= a || a < low || b > high {
                continue;
            }
            let derivatives = curve_derivatives(&knots, &controls, degree, span, a);
            let mut factorial = 1.0;
            let mut power = 1.0;
            let coefficients = derivatives
                .iter()
                .enumerate()
                .map(|(k, derivative)| {
                    if k > 0 {
                        factorial *= k as f64;
                        power *= scale;
                    }
                    derivative * (power / factorial)
                })
                .collect();
            pieces.push(Piece {
                start: -1.0 + (a - low) / scale,
                end: -1.0 + (b - low) / scale,
                coefficients,
                centre: Vector3::zeros(),
                radius: 0.0,
                reference: Vector3::z(),
            });
        }
        if let Some(last) = pieces.last_mut() {
            last.end = 1.0;
        }
        for piece in &mut pieces {
            piece.bound();
            piece.choose_reference();
        }
        if pieces.iter().any(|piece| {
            piece
                .coefficients
                .iter()
                .any(|c| !c.iter().all(|v| v.is_finite()))
        }) {
            return Err("its points give no curve (they are not apart)".to_string());
        }
        // A point of contact needs a tangent: a curve that stops (repeated
        // points) has none there.
        let size = points.iter().map(|p| p.amax()).fold(0.0, f64::max);
        let stops = pieces.iter().any(|piece| {
            piece
                .samples(TANGENT_SAMPLES)
                .any(|alpha| piece.at(&alpha).tangent.norm() <= 1e-9 * size.max(f64::MIN_POSITIVE))
        });
        if stops {
            return Err(
                "its points give a curve that stops (its tangent vanishes where points repeat): give points apart".to_string(),
            );
        }
        Ok(Curve { id, pieces, closed })
    }

    /// The axis the normals at `alpha` start from: the least along the
    /// piece `piece`, or along the piece `alpha` falls in.
    pub fn reference(&self, alpha: f64, piece: Option<usize>) -> Vector3<f64> {
        self.pieces[piece.unwrap_or_else(|| self.piece_of(alpha))].reference
    }

    /// `alpha` brought into [−1, 1) for a closed curve (whole periods of
    /// 2 taken off), as it is for an open one.
    fn wrapped<T: Number>(&self, alpha: &T) -> T {
        if !self.closed {
            return alpha.clone();
        }
        let turns = ((alpha.value() + 1.0) / 2.0).floor();
        alpha.clone() - T::from(2.0 * turns)
    }

    /// The number of pieces (one a knot span).
    pub fn piece_count(&self) -> usize {
        self.pieces.len()
    }

    /// Each piece's bounding ball, in order: its centre and a radius that
    /// every point of the piece lies within.
    pub fn piece_balls(&self) -> impl Iterator<Item = (Vector3<f64>, f64)> + '_ {
        self.pieces.iter().map(|piece| (piece.centre, piece.radius))
    }

    /// The index of the piece `alpha` falls in (wrapped for a closed
    /// curve; the first or last for an open curve's `alpha` beyond its
    /// ends).
    pub fn piece_of(&self, alpha: f64) -> usize {
        self.pieces
            .partition_point(|piece| piece.end <= self.wrapped(&alpha))
            .min(self.pieces.len() - 1)
    }

    /// `alpha` moved by whole periods of a closed curve to lie nearest the
    /// middle of piece `piece` (unchanged for an open curve).
    fn near_piece(&self, alpha: f64, piece: usize) -> f64 {
        if !self.closed {
            return alpha;
        }
        let piece = &self.pieces[piece];
        let middle = 0.5 * (piece.start + piece.end);
        alpha - 2.0 * ((alpha - middle) / 2.0).round()
    }

    /// The point at `alpha` and its first two derivatives (an open curve's
    /// end pieces continued beyond its ends).
    pub fn at<T: Number>(&self, alpha: &T) -> CurvePoint<T> {
        self.at_on(alpha, None)
    }

    /// [`Curve::at`], on the polynomial of piece `piece` when one is given
    /// (continued past its ends, `alpha` taken in the period nearest it):
    /// within a step the curve is held on one piece, as a law on one
    /// branch, so that its next knot is crossed as a located switch.
    pub fn at_on<T: Number>(&self, alpha: &T, piece: Option<usize>) -> CurvePoint<T> {
        match piece {
            Some(index) => {
                let shifted = self.near_piece(alpha.value(), index) - alpha.value();
                self.pieces[index].at(&(alpha.clone() + T::from(shifted)))
            }
            None => {
                let alpha = self.wrapped(alpha);
                self.pieces[self.piece_of(alpha.value())].at(&alpha)
            }
        }
    }

    /// The two switching values of piece `piece` at `alpha`: its distance
    /// past the piece's start and short of its end (in the period nearest
    /// the piece), each widened by a hundred-millionth of the piece, one
    /// changing sign where the point of contact crosses a knot; an open
    /// curve's own ends never switch (there the point leaves the curve).
    /// The margin puts a located crossing past the knot by more than the
    /// rounding of a parameter found by Newton's iterations, so that the
    /// piece of the point of contact there is the next one beyond doubt:
    /// without it a crossing located within rounding of a knot found the
    /// point still on the held piece, and the run went on holding a piece
    /// the point had left, its switching value negative from then on.
    pub fn switching(&self, alpha: f64, piece: usize) -> [f64; 2] {
        let alpha = self.near_piece(alpha, piece);
        let span = &self.pieces[piece];
        let margin = KNOT_MARGIN * (span.end - span.start);
        let first = self.closed || piece > 0;
        let last = self.closed || piece + 1 < self.pieces.len();
        [
            if first {
                alpha - span.start + margin
            } else {
                1.0
            },
            if last { span.end - alpha + margin } else { 1.0 },
        ]
    }

    /// The parameter of the curve's point nearest `point` (an open curve's
    /// `α` may fall beyond ±1 where the point has run past an end), or
    /// `None` where no nearest point is found: the pieces' samples nearest
    /// the point, refined by Newton's iterations.
    pub fn nearest(&self, point: &Vector3<f64>) -> Option<f64> {
        // No point of a piece is nearer than its ball's near side, and
        // some point is no farther than the ball's far side.
        let within = self
            .pieces
            .iter()
            .map(|piece| (point - piece.centre).norm() + piece.radius)
            .fold(f64::INFINITY, f64::min);
        let distance = |alpha: f64| (self.at(&alpha).place - point).norm_squared();
        let closest: Vec<(f64, f64)> = self
            .pieces
            .iter()
            .filter(|piece| (point - piece.centre).norm() - piece.radius <= within)
            .map(|piece| closest_sample(piece, point))
            .collect();
        let least = closest
            .iter()
            .map(|(_, d)| *d)
            .fold(f64::INFINITY, f64::min);
        if !least.is_finite() {
            return None;
        }
        // Each piece whose samples come near the nearest one's is a
        // candidate (two arcs of a curve can pass near one point).
        closest
            .iter()
            .filter(|(_, d)| *d <= 4.0 * least + f64::EPSILON)
            .map(|(start, _)| {
                let alpha = self.refine(point, *start, None);
                (alpha, distance(alpha))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(alpha, _)| alpha)
    }

    /// [`Curve::nearest`] on the polynomial of piece `piece` (continued
    /// past its ends), from the piece's sample nearest `point`.
    pub fn nearest_on(&self, point: &Vector3<f64>, piece: usize) -> Option<f64> {
        let (start, _) = closest_sample(&self.pieces[piece], point);
        let alpha = self.refine(point, start, Some(piece));
        alpha.is_finite().then_some(alpha)
    }

    /// Newton's iterations on `s'(α) · (point − s(α)) = 0` from `alpha`
    /// (a closed curve's parameter wrapped into [−1, 1), an open curve's
    /// end pieces continued beyond its ends), on piece `piece`'s
    /// polynomial when one is given (its `α` not wrapped).
    fn refine(&self, point: &Vector3<f64>, mut alpha: f64, piece: Option<usize>) -> f64 {
        for _ in 0..50 {
            let at = self.at_on(&alpha, piece);
            let apart = point - at.place;
            let slope = at.tangent.dot(&apart);
            let curvature = at.bend.dot(&apart) - at.tangent.norm_squared();
            let step = if curvature < 0.0 {
                -slope / curvature
            } else {
                // Not a minimum's basin: a step down the slope.
                let span = &self.pieces[piece.unwrap_or_else(|| self.piece_of(alpha))];
                slope.signum() * 0.25 * (span.end - span.start)
            };
            let next = alpha + step;
            let done = (next - alpha).abs() <= 1e-15 * (1.0 + alpha.abs());
            alpha = next;
            if done || !alpha.is_finite() {
                break;
            }
        }
        if piece.is_some() {
            alpha
        } else {
            self.wrapped(&alpha)
        }
    }
}

/// The parameter of `piece`'s sample nearest `point`, and its squared
/// distance.
fn closest_sample(piece: &Piece, point: &Vector3<f64>) -> (f64, f64) {
    const SAMPLES: u32 = 8;
    piece
        .samples(SAMPLES)
        .map(|alpha| (alpha, (piece.at(&alpha).place - point).norm_squared()))
        .fold((f64::NAN, f64::INFINITY), |best, next| {
            if next.1 < best.1 { next } else { best }
        })
}

/// The knots and control points of an open (clamped) B-spline of `degree`
/// from `points`: its control points, or points it passes through.
fn clamped(
    points: &[Vector3<f64>],
    degree: usize,
    through: bool,
) -> Result<(Vec<f64>, Vec<Vector3<f64>>), String> {
    let n = points.len();
    let parameters: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    let mut knots = vec![0.0; degree + 1];
    for j in 1..n - degree {
        knots.push(if through {
            parameters[j..j + degree].iter().sum::<f64>() / degree as f64
        } else {
            j as f64 / (n - degree) as f64
        });
    }
    knots.extend(std::iter::repeat_n(1.0, degree + 1));
    if !through {
        return Ok((knots, points.to_vec()));
    }
    interpolated(&knots, degree, n, &parameters, points).map(|controls| (knots, controls))
}

/// The knots and control points (wrapped: the first `degree` again at the
/// end) of a closed, periodic B-spline of `degree` from `points`: its
/// control points, or points it passes through.
fn periodic(
    points: &[Vector3<f64>],
    degree: usize,
    through: bool,
) -> Result<(Vec<f64>, Vec<Vector3<f64>>), String> {
    let n = points.len();
    let knots: Vec<f64> = (0..=n + 2 * degree).map(|k| k as f64).collect();
    let wrap = |controls: &[Vector3<f64>]| -> Vec<Vector3<f64>> {
        (0..n + degree).map(|k| controls[k % n]).collect()
    };
    if !through {
        return Ok((knots, wrap(points)));
    }
    let shift = if degree % 2 == 1 { 0.0 } else { 0.5 };
    let parameters: Vec<f64> = (0..n).map(|row| (degree + row) as f64 + shift).collect();
    let controls = interpolated(&knots, degree, n + degree, &parameters, points)?;
    Ok((knots, wrap(&controls)))
}

/// The control points of the B-spline of `knots` and `degree` (with
/// `count` control points, the last beyond `points.len()` wrapped onto the
/// first, as a periodic curve's are) that meets `points` at `parameters`.
fn interpolated(
    knots: &[f64],
    degree: usize,
    count: usize,
    parameters: &[f64],
    points: &[Vector3<f64>],
) -> Result<Vec<Vector3<f64>>, String> {
    let n = points.len();
    let mut system = DMatrix::zeros(n, n);
    for (row, &u) in parameters.iter().enumerate() {
        let span = find_span(knots, degree, count, u);
        let basis = basis_derivatives(knots, degree, span, u, 0);
        for (k, value) in basis[0].iter().enumerate() {
            system[(row, (span - degree + k) % n)] += value;
        }
    }
    let right = DMatrix::from_fn(n, 3, |row, column| points[row][column]);
    let solved = system
        .lu()
        .solve(&right)
        .filter(|solved| solved.iter().all(|v| v.is_finite()))
        .ok_or_else(|| "no curve of this ORDER passes through its points".to_string())?;
    Ok((0..n)
        .map(|row| Vector3::new(solved[(row, 0)], solved[(row, 1)], solved[(row, 2)]))
        .collect())
}

/// The knot span `[knots[span], knots[span + 1])` holding `u`, for `count`
/// control points.
fn find_span(knots: &[f64], degree: usize, count: usize, u: f64) -> usize {
    if u >= knots[count] {
        return count - 1;
    }
    let mut span = degree;
    while span + 1 < count && knots[span + 1] <= u {
        span += 1;
    }
    span
}

/// The curve's value and derivatives up to `degree` at `u` in knot span
/// `span`.
fn curve_derivatives(
    knots: &[f64],
    controls: &[Vector3<f64>],
    degree: usize,
    span: usize,
    u: f64,
) -> Vec<Vector3<f64>> {
    basis_derivatives(knots, degree, span, u, degree)
        .iter()
        .map(|row| {
            row.iter()
                .enumerate()
                .map(|(k, value)| controls[span - degree + k] * *value)
                .sum()
        })
        .collect()
}

/// The nonzero B-spline basis functions of `degree` at `u` in knot span
/// `span` and their derivatives up to order `orders`: row `k` holds the
/// `k`-th derivatives of the `degree + 1` functions (Piegl and Tiller's
/// algorithm A2.3).
fn basis_derivatives(
    knots: &[f64],
    degree: usize,
    span: usize,
    u: f64,
    orders: usize,
) -> Vec<Vec<f64>> {
    let p = degree;
    let mut table = vec![vec![0.0; p + 1]; p + 1];
    let mut left = vec![0.0; p + 1];
    let mut right = vec![0.0; p + 1];
    table[0][0] = 1.0;
    for j in 1..=p {
        left[j] = u - knots[span + 1 - j];
        right[j] = knots[span + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            table[j][r] = right[r + 1] + left[j - r];
            let temp = table[r][j - 1] / table[j][r];
            table[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        table[j][j] = saved;
    }
    let mut derivatives = vec![vec![0.0; p + 1]; orders + 1];
    for j in 0..=p {
        derivatives[0][j] = table[j][p];
    }
    let mut a = [vec![0.0; p + 1], vec![0.0; p + 1]];
    for r in 0..=p {
        let (mut s1, mut s2) = (0, 1);
        a[0][0] = 1.0;
        for k in 1..=orders {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if rk >= 0 {
                let rk = rk as usize;
                a[s2][0] = a[s1][0] / table[pk + 1][rk];
                d = a[s2][0] * table[rk][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if r as isize - 1 <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let row = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / table[pk + 1][row];
                d += a[s2][j] * table[row][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / table[pk + 1][r];
                d += a[s2][k] * table[r][pk];
            }
            derivatives[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for (k, row) in derivatives.iter_mut().enumerate().skip(1) {
        for value in row.iter_mut() {
            *value *= factor;
        }
        factor *= (p - k) as f64;
    }
    derivatives
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(list: &[[f64; 3]]) -> Vec<Vector3<f64>> {
        list.iter().map(|p| Vector3::from(*p)).collect()
    }

    #[test]
    fn a_quadratic_bezier_is_the_parabola_its_control_points_give() {
        // Control points (-1, 1), (0, -1), (1, 1): y = x², x = α.
        let curve = Curve::new(
            1,
            &points(&[[-1.0, 1.0, 0.0], [0.0, -1.0, 0.0], [1.0, 1.0, 0.0]]),
            3,
            false,
            false,
        )
        .unwrap();
        for alpha in [-1.0, -0.3, 0.0, 0.7, 1.0] {
            let at = curve.at(&alpha);
            assert!((at.place - Vector3::new(alpha, alpha * alpha, 0.0)).norm() < 1e-14);
            assert!((at.tangent - Vector3::new(1.0, 2.0 * alpha, 0.0)).norm() < 1e-14);
            assert!((at.bend - Vector3::new(0.0, 2.0, 0.0)).norm() < 1e-14);
        }
        let nearest = curve.nearest(&Vector3::new(0.5, 0.25, 0.0)).unwrap();
        assert!((nearest - 0.5).abs() < 1e-12, "{nearest}");
    }

    #[test]
    fn a_curve_that_stops_is_refused() {
        let repeated = points(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
        ]);
        assert!(Curve::new(1, &repeated, 2, false, false).is_err());
        assert!(Curve::new(1, &repeated, 4, false, false).is_ok());
        let same = points(&[[1.0, 1.0, 1.0]; 4]);
        assert!(Curve::new(1, &same, 2, false, true).is_err());
        assert!(Curve::new(1, &same, 4, true, false).is_err());
    }

    #[test]
    fn curves_through_points_meet_them() {
        let circle: Vec<Vector3<f64>> = (0..12)
            .map(|k| {
                let angle = k as f64 * std::f64::consts::TAU / 12.0;
                Vector3::new(angle.cos(), angle.sin(), 0.0)
            })
            .collect();
        for order in 2..=5 {
            for closed in [false, true] {
                let curve = Curve::new(1, &circle, order, closed, true).unwrap();
                for point in &circle {
                    let alpha = curve.nearest(point).unwrap();
                    let gap = (curve.at(&alpha).place - point).norm();
                    assert!(gap < 1e-12, "order {order} closed {closed}: {gap}");
                }
                // The derivatives agree with central differences.
                let h = 1e-6;
                for alpha in [-0.9, -0.2, 0.35, 0.8] {
                    let at = curve.at(&alpha);
                    let slope =
                        (curve.at(&(alpha + h)).place - curve.at(&(alpha - h)).place) / (2.0 * h);
                    assert!((slope - at.tangent).norm() < 1e-6 * (1.0 + at.tangent.norm()));
                }
            }
        }
        // A closed cubic through the circle's points is round to its
        // sampling's accuracy, and continuous across α = ±1.
        let curve = Curve::new(1, &circle, 4, true, true).unwrap();
        let (end, start) = (curve.at(&(1.0 - 1e-12)), curve.at(&(-1.0)));
        assert!((end.place - start.place).norm() < 1e-10);
        assert!((end.tangent - start.tangent).norm() < 1e-8);
        assert!(
            curve
                .pieces
                .iter()
                .flat_map(|piece| piece.samples(TANGENT_SAMPLES).collect::<Vec<_>>())
                .all(|alpha| (curve.at(&alpha).place.norm() - 1.0).abs() < 2e-3)
        );
        // Held on the first piece, a point just before the wrap at α = 1
        // is just before that piece's start: its first switching value is
        // small and negative, and the held polynomial continues the curve
        // there.
        let last = curve.piece_count() - 1;
        let alpha = 1.0 - 1e-6;
        assert_eq!(curve.piece_of(alpha), last);
        let [before_start, before_end] = curve.switching(alpha, 0);
        assert!(before_start < 0.0 && before_start > -1e-5, "{before_start}");
        assert!(before_end > 0.0);
        let held = curve.at_on(&alpha, Some(0)).place;
        assert!((held - curve.at(&alpha).place).norm() < 1e-9);
        let point = curve.at(&alpha).place;
        let on_first = curve.nearest_on(&point, 0).unwrap();
        assert!((on_first - (-1.0 - 1e-6)).abs() < 1e-9, "{on_first}");
    }
}
