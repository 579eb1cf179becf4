//! `AKISPL` and `CUBSPL` (SPEC 3.7): interpolation of the points of a model's
//! SPLINE statement, cubic in `x` and linear in `z` across a family of curves.
//!
//! - `AKISPL` fits Akima's piecewise cubic (local: each piece depends on
//!   six points; its second derivative jumps at the points).
//! - `CUBSPL` fits the natural cubic spline (second derivative zero at both
//!   ends; value, first and second derivative continuous everywhere).
//! - Beyond the first or last x the end piece's cubic goes on; with the
//!   statement's `LINEAR_EXTRAPOLATE` the tangent line at the end point does.
//! - At a data point the piece to its right gives the derivatives (the last
//!   point takes the last piece): the branch rule of SPEC 5.
//! - Between curves of a family the result is linear in `z`; beyond the
//!   first or last z, the line through the two nearest curves goes on.
//! - `iord` 1 or 2 gives the first or second derivative in `x`, also for a
//!   family (interpolated in `z` like the value).

use thiserror::Error;

use super::range::{fraction, interpolate, ratio};
use crate::Shown;
use crate::number::Number;

/// The fitting method of a spline function.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Akima's local cubic (`AKISPL`).
    Akima,
    /// The natural cubic spline (`CUBSPL`).
    Cubic,
}

/// Why a SPLINE statement's points cannot be interpolated.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SplineDataError {
    /// Fewer than four x values.
    #[error("a spline needs at least four x values; found {0}")]
    TooFewPoints(usize),
    /// The x values do not increase.
    #[error(
        "x values must increase: x{position} = {} follows {}",
        Shown(*value),
        Shown(*previous)
    )]
    XNotIncreasing {
        /// Position of the offending value, from 1.
        position: usize,
        /// The value.
        value: f64,
        /// The value before it.
        previous: f64,
    },
    /// The z values of a family do not increase.
    #[error(
        "the z values of the curves must increase: {} follows {}",
        Shown(*value),
        Shown(*previous)
    )]
    ZNotIncreasing {
        /// The offending z.
        value: f64,
        /// The z before it.
        previous: f64,
    },
    /// A curve with another number of y values than there are x values.
    #[error("curve {curve} has {} for {}", crate::Counted(*found, "y value"), crate::Counted(*expected, "x value"))]
    CurveLength {
        /// The curve, from 1.
        curve: usize,
        /// How many y values it has.
        found: usize,
        /// How many x values there are.
        expected: usize,
    },
    /// A value that is not a finite number.
    #[error("the spline's values must be finite numbers")]
    NotFinite,
    /// No Y values at all.
    #[error("a spline needs Y values")]
    NoCurve,
}

/// The points of a SPLINE statement: the x values and one curve of y values,
/// or a family of curves, each at its own z.
#[derive(Clone, Debug, PartialEq)]
pub struct SplineData {
    x: Vec<f64>,
    curves: Vec<(f64, Vec<f64>)>,
    linear_extrapolation: bool,
}

impl SplineData {
    /// Checked spline data: at least four increasing finite x values, each
    /// curve `(z, y values)` as long as `x`, the z values increasing (a
    /// single curve's z is not used).
    pub fn new(
        x: Vec<f64>,
        curves: Vec<(f64, Vec<f64>)>,
        linear_extrapolation: bool,
    ) -> Result<SplineData, SplineDataError> {
        if x.len() < 4 {
            return Err(SplineDataError::TooFewPoints(x.len()));
        }
        if curves.is_empty() {
            return Err(SplineDataError::NoCurve);
        }
        let all_values = x
            .iter()
            .chain(curves.iter().flat_map(|(z, y)| std::iter::once(z).chain(y)));
        if !all_values.into_iter().all(|value| value.is_finite()) {
            return Err(SplineDataError::NotFinite);
        }
        if let Some(position) = x.windows(2).position(|pair| pair[0] >= pair[1]) {
            return Err(SplineDataError::XNotIncreasing {
                position: position + 2,
                value: x[position + 1],
                previous: x[position],
            });
        }
        for (index, (_, y)) in curves.iter().enumerate() {
            if y.len() != x.len() {
                return Err(SplineDataError::CurveLength {
                    curve: index + 1,
                    found: y.len(),
                    expected: x.len(),
                });
            }
        }
        if curves.len() > 1
            && let Some(pair) = curves.windows(2).find(|pair| pair[0].0 >= pair[1].0)
        {
            return Err(SplineDataError::ZNotIncreasing {
                value: pair[1].0,
                previous: pair[0].0,
            });
        }
        Ok(SplineData {
            x,
            curves,
            linear_extrapolation,
        })
    }

    /// The number of curves (1, or the size of the family).
    pub fn curve_count(&self) -> usize {
        self.curves.len()
    }
}

/// One curve fitted through its points: a cubic per interval, in the
/// interval's own coordinate `s = (x - x[i]) / (x[i+1] - x[i])`.
///
/// The fit works on the points scaled to about unit size (x by half the
/// span, y by the largest |y|, each rounded to a power of two), and each piece keeps its coefficients in units of y
/// over `s` in `[0, 1]`: so points 1e300 or 1e-300 apart give the same
/// curve, scaled, as points 1 apart (coefficients per unit of x, with
/// `1/h^2` for the cubic term, underflowed to 0 for such points).
#[derive(Clone, Debug, PartialEq)]
struct Curve {
    /// The x values (the pieces' left ends, and the last point).
    x: Vec<f64>,
    /// `[a, b, c, d]` of `a + b s + c s^2 + d s^3` per interval.
    pieces: Vec<[f64; 4]>,
    /// The y of the last point, exactly.
    end_value: f64,
    linear_extrapolation: bool,
}

impl Curve {
    fn fit(method: Method, x: &[f64], y: &[f64], linear_extrapolation: bool) -> Curve {
        let n = x.len();
        // Units of x and y: powers of two near half the span (finite for
        // any finite x) and the largest |y|, so that scaling by them is exact
        // and the fit rounds as it would on the points as given.
        let unit_x = power_of_two_near(x[n - 1] * 0.5 - x[0] * 0.5);
        let height = power_of_two_near(y.iter().fold(0.0f64, |largest, y| largest.max(y.abs())));
        // Widths in units of x (halved: exact, and finite), rises in units of y.
        let widths: Vec<f64> = x
            .windows(2)
            .map(|pair| (pair[1] * 0.5 - pair[0] * 0.5) / unit_x)
            .collect();
        let rises: Vec<f64> = y
            .windows(2)
            .map(|pair| pair[1] / height - pair[0] / height)
            .collect();
        let slopes: Vec<f64> = rises.iter().zip(&widths).map(|(r, w)| r / w).collect();
        // Each piece in units of the height: [rise part b, c, d] over s.
        let unit_pieces: Vec<[f64; 3]> = match method {
            Method::Akima => {
                let tangents = akima_tangents(&slopes);
                (0..slopes.len())
                    .map(|i| {
                        // In slopes, then times the width: a line stays exact.
                        let (t0, t1, m, h) = (tangents[i], tangents[i + 1], slopes[i], widths[i]);
                        [
                            t0 * h,
                            (3.0 * m - 2.0 * t0 - t1) * h,
                            (t0 + t1 - 2.0 * m) * h,
                        ]
                    })
                    .collect()
            }
            Method::Cubic => {
                let curvatures = natural_curvatures(&widths, &slopes);
                (0..slopes.len())
                    .map(|i| {
                        let h = widths[i];
                        let (m0, m1) = (curvatures[i], curvatures[i + 1]);
                        [
                            (slopes[i] - h * (2.0 * m0 + m1) / 6.0) * h,
                            m0 * h * h / 2.0,
                            (m1 - m0) * h * h / 6.0,
                        ]
                    })
                    .collect()
            }
        };
        let pieces = unit_pieces
            .iter()
            .zip(y)
            .map(|([b, c, d], &a)| [a, b * height, c * height, d * height])
            .collect();
        Curve {
            x: x.to_vec(),
            pieces,
            end_value: y[n - 1],
            linear_extrapolation,
        }
    }

    /// The value and the first four derivatives at `x`.
    fn derivatives(&self, x: f64) -> [f64; 5] {
        let last = self.pieces.len() - 1;
        let piece = self.x.partition_point(|&knot| knot <= x).saturating_sub(1);
        let piece = piece.min(last);
        // The cubic of `piece` at x, and its derivatives in x (1/h per order).
        let cubic = |piece: usize, x: f64| {
            let [a, b, c, d] = self.pieces[piece];
            let (left, right) = (self.x[piece], self.x[piece + 1]);
            let s = ratio(x, left, right, left);
            let width = right - left;
            [
                a + s * (b + s * (c + s * d)),
                (b + s * (2.0 * c + s * 3.0 * d)) / width,
                (2.0 * c + 6.0 * d * s) / width / width,
                6.0 * d / width / width / width,
                0.0,
            ]
        };
        let (first, end) = (self.x[0], self.x[last + 1]);
        if self.linear_extrapolation && (x < first || x > end) {
            // The end point's value and slope per unit of s (s = 0 on the
            // first piece, 1 on the last), times the distance in widths: no
            // slope per unit of x (which underflows for points 1e300 apart
            // of heights 1e-300) meets a distance in x.
            let (piece, anchor) = if x < first { (0, first) } else { (last, end) };
            let [a, b, c, d] = self.pieces[piece];
            let (value, slope) = if x < first {
                (a, b)
            } else {
                (self.end_value, b + 2.0 * c + 3.0 * d)
            };
            let (left, right) = (self.x[piece], self.x[piece + 1]);
            let widths = ratio(x, anchor, right, left);
            return [
                value + slope * widths,
                slope / (right - left),
                0.0,
                0.0,
                0.0,
            ];
        }
        let mut derivatives = cubic(piece, x);
        if x == end {
            derivatives[0] = self.end_value;
        }
        derivatives
    }
}

/// The power of two at or below `value` (1 for 0).
fn power_of_two_near(value: f64) -> f64 {
    if value == 0.0 {
        1.0
    } else {
        2f64.powi(value.log2().floor() as i32)
    }
}

/// Akima's tangent at each point from the interval slopes, with two
/// extrapolated slopes at each end.
fn akima_tangents(slopes: &[f64]) -> Vec<f64> {
    let n = slopes.len();
    let mut extended = Vec::with_capacity(n + 4);
    let (m0, m1) = (slopes[0], slopes[1.min(n - 1)]);
    let before = 2.0 * m0 - m1;
    extended.extend([2.0 * before - m0, before]);
    extended.extend_from_slice(slopes);
    let (last, previous) = (slopes[n - 1], slopes[n.saturating_sub(2)]);
    let after = 2.0 * last - previous;
    extended.extend([after, 2.0 * after - last]);
    // Point i sits between extended[i + 1] (left slope) and extended[i + 2].
    (0..=n)
        .map(|i| {
            let [far_left, left, right, far_right] = [
                extended[i],
                extended[i + 1],
                extended[i + 2],
                extended[i + 3],
            ];
            let weight_left = (far_right - right).abs();
            let weight_right = (left - far_left).abs();
            if weight_left + weight_right == 0.0 {
                (left + right) / 2.0
            } else {
                (weight_left * left + weight_right * right) / (weight_left + weight_right)
            }
        })
        .collect()
}

/// The second derivatives at the points of the natural cubic spline
/// (zero at both ends) for interval widths `h`, by the tridiagonal (Thomas)
/// solve.
fn natural_curvatures(h: &[f64], slopes: &[f64]) -> Vec<f64> {
    let n = h.len() + 1;
    let mut curvatures = vec![0.0; n];
    if n < 3 {
        return curvatures;
    }
    // Rows 1..n-1: h[i-1] M[i-1] + 2 (h[i-1] + h[i]) M[i] + h[i] M[i+1] = 6 (m[i] - m[i-1]).
    let mut diagonal = vec![0.0; n];
    let mut right = vec![0.0; n];
    for i in 1..n - 1 {
        diagonal[i] = 2.0 * (h[i - 1] + h[i]);
        right[i] = 6.0 * (slopes[i] - slopes[i - 1]);
        if i > 1 {
            let factor = h[i - 1] / diagonal[i - 1];
            diagonal[i] -= factor * h[i - 1];
            right[i] -= factor * right[i - 1];
        }
    }
    for i in (1..n - 1).rev() {
        curvatures[i] = (right[i] - h[i] * curvatures[i + 1]) / diagonal[i];
    }
    curvatures
}

/// A SPLINE statement's data fitted by one method, ready to evaluate.
#[derive(Clone, Debug, PartialEq)]
pub struct Spline {
    /// The z of each curve (one entry for a single curve).
    z: Vec<f64>,
    curves: Vec<Curve>,
}

impl Spline {
    /// Fits every curve of `data` by `method`.
    pub fn fit(data: &SplineData, method: Method) -> Spline {
        Spline {
            z: data.curves.iter().map(|(z, _)| *z).collect(),
            curves: data
                .curves
                .iter()
                .map(|(_, y)| Curve::fit(method, &data.x, y, data.linear_extrapolation))
                .collect(),
        }
    }

    /// The spline's derivative of order `order` (0, 1 or 2) in `x` at
    /// `(x, z)`; `z` matters only for a family of curves.
    pub fn at<T: Number>(&self, x: &T, z: &T, order: usize) -> T {
        let curve = |index: usize| {
            let derivatives = self.curves[index].derivatives(x.value());
            x.chain(derivatives[order], || {
                (derivatives[order + 1], derivatives[order + 2])
            })
        };
        if self.curves.len() == 1 {
            return curve(0);
        }
        let below = self
            .z
            .partition_point(|&knot| knot <= z.value())
            .saturating_sub(1)
            .min(self.curves.len() - 2);
        let (z0, z1) = (self.z[below], self.z[below + 1]);
        let fraction = fraction(z, &T::from(z0), &T::from(z1));
        interpolate(&curve(below), &curve(below + 1), fraction)
    }
}
