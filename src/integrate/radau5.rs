//! Radau IIA of order 5 (Hairer, Wanner II, IV.8; `radau5.f`).
//!
//! The stage increments `z_i = Y_i − y` solve `z = h (A ⊗ I) F(z)`. With
//! `A⁻¹ = T Λ T⁻¹` (one real eigenvalue `γ`, a complex pair `α ± iβ`) and
//! `w = (T⁻¹ ⊗ I) z`, a simplified Newton step is one real solve with
//! `γ/h − J` and one complex solve with `(α + iβ)/h − J`.

use std::rc::Rc;

use nalgebra::Complex;

use super::core::{Core, evaluate, grouped_rms};
use super::linalg::{Factorisation, Jacobian, Pattern, factorisation_for};
use super::{IntegrateError, Options, Rejection, System};
use crate::Shown;

/// The order the first step size is chosen for (the error estimate's).
pub(super) const ORDER: i32 = 4;

/// The nodes `(4 ∓ √6)/10` (the third is 1) and their distances to 1.
#[allow(clippy::excessive_precision)]
const C1: f64 = 0.155051025721682190180271592529;
#[allow(clippy::excessive_precision)]
const C2: f64 = 0.644948974278317809819728407471;
const C1M1: f64 = C1 - 1.0;
const C2M1: f64 = C2 - 1.0;
const C1MC2: f64 = C1 - C2;
/// The eigenvalues of `A⁻¹`: `γ` and `α ± iβ`.
#[allow(clippy::excessive_precision)]
const GAMMA: f64 = 3.63783425274449573220841851358;
#[allow(clippy::excessive_precision)]
const ALPHA: f64 = 2.68108287362775213389579074321;
#[allow(clippy::excessive_precision)]
const BETA: f64 = 3.05043019924741056942637762479;
/// The error estimate's weights on `z`: `−(13 + 7√6)/3`, `(−13 + 7√6)/3`,
/// `−1/3`.
#[allow(clippy::excessive_precision)]
const ERROR_WEIGHTS: [f64; 3] = [
    -10.0488093998274155624603295076,
    1.38214273316074889579366284098,
    -1.0 / 3.0,
];
/// `T` (its last row is `(T31, 1, 0)`) and `T⁻¹`, from `radau5.f`.
#[allow(clippy::excessive_precision)]
const T: [[f64; 3]; 3] = [
    [
        9.1232394870892942792e-02,
        -0.14125529502095420843,
        -3.0029194105147424492e-02,
    ],
    [
        0.24171793270710701896,
        0.20412935229379993199,
        0.38294211275726193779,
    ],
    [0.96604818261509293619, 1.0, 0.0],
];
#[allow(clippy::excessive_precision)]
const T_INVERSE: [[f64; 3]; 3] = [
    [
        4.3255798900631553510,
        0.33919925181580986954,
        0.54177053993587487119,
    ],
    [
        -4.1787185915519047273,
        -0.32768282076106238708,
        0.47662355450055045196,
    ],
    [
        -0.50287263494578687595,
        2.5719269498556054292,
        -0.59603920482822492497,
    ],
];

/// Newton iterations allowed per step.
const MAX_NEWTON: usize = 7;
/// A Newton increment is measured against at least this many times its
/// rate's rounding floor over the step (the joints' solve amplifies the
/// rounding of the loads by the conditioning of its matrix).
const FLOOR_MARGIN: f64 = 1000.0;
/// Safety factor of the step size control.
const SAFETY: f64 = 0.9;
/// Bounds of `h / h_new`: a step changes by a factor between 1/5 and 8.
const SHRINK_MOST: f64 = 5.0;
const GROW_MOST: f64 = 1.0 / 8.0;
/// A proposal between 1 and 1.2 times the step keeps the step (and its
/// factorisations).
const KEEP_STEP: std::ops::RangeInclusive<f64> = 1.0..=1.2;
/// Step factor after a refused trial state, a singular matrix or a
/// diverging Newton iteration; and after a first step fails its error test.
const FAILURE_SHRINK: f64 = 0.5;
const FIRST_STEP_SHRINK: f64 = 0.1;

/// The Newton iteration's tolerance: the options', or by default
/// `max(10 ε / rtol, min(√rtol, 0.03))`.
fn newton_tolerance<E>(options: &Options) -> Result<f64, IntegrateError<E>> {
    let rtol = options.rtol;
    match options.newton_tolerance {
        None => Ok((10.0 * f64::EPSILON / rtol).max(rtol.sqrt().min(0.03))),
        Some(tolerance) if tolerance > 0.0 && tolerance.is_finite() => Ok(tolerance),
        Some(tolerance) => Err(IntegrateError::Settings(format!(
            "newton_tolerance must be positive, not {}",
            Shown(tolerance)
        ))),
    }
}

/// [`Options::jacobian_reuse`], checked.
fn jacobian_reuse<E>(options: &Options) -> Result<f64, IntegrateError<E>> {
    if (0.0..1.0).contains(&options.jacobian_reuse) {
        Ok(options.jacobian_reuse)
    } else {
        Err(IntegrateError::Settings(format!(
            "jacobian_reuse must be at least 0 and below 1, not {}",
            Shown(options.jacobian_reuse)
        )))
    }
}

/// How a Newton iteration ended well.
struct Converged {
    iterations: usize,
    theta: f64,
}

/// Radau5's working storage, its Jacobian and factorisations, and the last
/// step's collocation polynomial.
pub(super) struct Radau5 {
    n: usize,
    newton_tolerance: f64,
    /// [`Options::jacobian_reuse`].
    jacobian_reuse: f64,
    /// `atol + rtol |y|` at the start of the step.
    scale: Vec<f64>,
    /// The system's Jacobian: dense, or on the system's pattern.
    jacobian: Jacobian,
    /// The Jacobian may be used at the current state.
    jacobian_valid: bool,
    /// The Jacobian was evaluated at the current state.
    jacobian_current: bool,
    /// A Jacobian has been evaluated (at some earlier state, perhaps of
    /// the system before an event).
    jacobian_evaluated: bool,
    /// The real and the complex iteration matrix, factorised (dense or
    /// sparse: chosen from the pattern; this code does not know which).
    matrices: Box<dyn Factorisation>,
    /// The step size the factorisations are for (NaN: none).
    factorised_for: f64,
    /// Stage increments `z`, transformed increments `w`, stage rates.
    z: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    rates: [Vec<f64>; 3],
    stage_y: Vec<f64>,
    real_rhs: Vec<f64>,
    complex_rhs: Vec<Complex<f64>>,
    /// The last step's collocation polynomial about its end (divided
    /// differences), and that step's size.
    polynomial: [Vec<f64>; 3],
    /// The state at the last step's start, where its polynomial's first
    /// half is read from (see [`Radau5::dense`]).
    y_before: Vec<f64>,
    h_last: f64,
    /// No step accepted since the start: no polynomial to start Newton from.
    first: bool,
    after_rejection: bool,
    /// Hairer's `faccon`: the contraction estimate carried between steps.
    contraction: f64,
    /// The last accepted step's size and error, for Gustafsson's controller.
    last_accepted: Option<(f64, f64)>,
}

impl Radau5 {
    /// Working storage for a system of `n` states whose Jacobian has
    /// `pattern` (`None`: dense). The tolerances are the options' (the
    /// core's), unchanged: not Hairer's `0.1 rtol^(2/3)`, which assumes a
    /// step's true error far below its estimate; near a contact's touch it
    /// is not.
    pub fn new<E>(
        options: &Options,
        n: usize,
        pattern: Option<Pattern>,
    ) -> Result<Self, IntegrateError<E>> {
        let newton_tolerance = newton_tolerance(options)?;
        let zeros = || vec![0.0; n];
        let matrices = factorisation_for(n, pattern.as_ref());
        Ok(Radau5 {
            n,
            newton_tolerance,
            jacobian_reuse: jacobian_reuse(options)?,
            scale: zeros(),
            jacobian: Jacobian::zeros(n, pattern.map(Rc::new)),
            jacobian_valid: false,
            jacobian_current: false,
            jacobian_evaluated: false,
            matrices,
            factorised_for: f64::NAN,
            z: [zeros(), zeros(), zeros()],
            w: [zeros(), zeros(), zeros()],
            rates: [zeros(), zeros(), zeros()],
            stage_y: zeros(),
            real_rhs: zeros(),
            complex_rhs: vec![Complex::new(0.0, 0.0); n],
            polynomial: [zeros(), zeros(), zeros()],
            y_before: zeros(),
            h_last: 0.0,
            first: true,
            after_rejection: false,
            contraction: 1.0,
            last_accepted: None,
        })
    }

    /// Forgets the past but for the Jacobian: no polynomial, no step
    /// history. The Jacobian (and the factorisations, while the step size
    /// stays) is kept as one of an earlier state, which Newton's iteration
    /// may use: where it does not converge with it, the step is tried
    /// again with a new one, as after any step. A restart is the event
    /// driver's cut, which integrates the same system again from a step's
    /// start to place a switch inside it (or its projection's small move),
    /// where the step's Jacobian holds; a new one at each cut made Radau5
    /// cost 6 times DOP853 on a chain of balls meeting 225 times. A
    /// changed system takes [`Radau5::renewed`].
    pub fn restart(&mut self) {
        self.first = true;
        self.after_rejection = false;
        self.jacobian_valid = self.jacobian_evaluated;
        self.jacobian_current = false;
        self.contraction = 1.0;
        self.last_accepted = None;
    }

    /// Goes on from a state moved slightly from the last one reached
    /// ([`Stepper::nudge`](super::Stepper::nudge)): the Jacobian becomes one
    /// of an earlier state.
    pub fn nudged(&mut self) {
        self.jacobian_current = false;
    }

    /// Starts again after an event, which may have changed the system:
    /// as [`Radau5::restart`], but with a new Jacobian (one of the system
    /// before the event let Newton's iteration stop on iterates far from
    /// the new stages: at a softening contact's touch, 70 times the error
    /// at rtol 1e-12) and the options' Newton tolerance. The storage and
    /// the factorisations' symbolic analysis stay when the system's
    /// Jacobian has the same `pattern` (a sparse LU's ordering and fill
    /// are worked out once per pattern, not once per event); `None` when
    /// it has not, and a new [`Radau5`] is needed.
    pub fn renewed<E>(
        mut self: Box<Self>,
        options: &Options,
        pattern: Option<&Pattern>,
    ) -> Result<Option<Box<Self>>, IntegrateError<E>> {
        let same_pattern = match (&self.jacobian, pattern) {
            (Jacobian::Dense(_), None) => true,
            (Jacobian::Sparse { pattern: old, .. }, Some(new)) => **old == *new,
            _ => false,
        };
        if !same_pattern {
            return Ok(None);
        }
        self.newton_tolerance = newton_tolerance(options)?;
        self.jacobian_reuse = jacobian_reuse(options)?;
        self.restart();
        self.jacobian_valid = false;
        Ok(Some(self))
    }

    /// One accepted step that does not pass `t_end`.
    pub fn step<S: System + ?Sized>(
        &mut self,
        core: &mut Core,
        system: &mut S,
        t_end: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        for (scale, (y, atol)) in self.scale.iter_mut().zip(core.y.iter().zip(&core.atol)) {
            *scale = atol + core.rtol * y.abs();
        }
        let mut cause = None;
        loop {
            let (h, lands) = core.trial(t_end, &mut cause)?;
            if !self.jacobian_valid {
                self.update_jacobian(core, system)?;
            }
            if self.factorised_for != h && !self.factorise(h, core) {
                self.reject(core, h * FAILURE_SHRINK, Rejection::Singular, &mut cause);
                continue;
            }
            let newton = match self.newton(core, system, h) {
                Ok(newton) => newton,
                Err((factor, why)) => {
                    self.reject(core, h * factor, why, &mut cause);
                    continue;
                }
            };
            let err = self.error_estimate(core, system, h);
            let safety = SAFETY.min(
                SAFETY * (1 + 2 * MAX_NEWTON) as f64 / (newton.iterations + 2 * MAX_NEWTON) as f64,
            );
            let mut quotient = (err.powf(0.25) / safety).clamp(GROW_MOST, SHRINK_MOST);
            if err >= 1.0 {
                let h_next = if self.first {
                    FIRST_STEP_SHRINK * h
                } else {
                    h / quotient
                };
                self.reject(core, h_next, Rejection::Tolerance, &mut cause);
                continue;
            }
            // The new state, which the system must accept.
            for (value, (y, z)) in self.stage_y.iter_mut().zip(core.y.iter().zip(&self.z[2])) {
                *value = y + z;
            }
            let t_new = if lands { t_end } else { core.t + h };
            if let Err(why) = evaluate(
                system,
                &mut core.stats,
                t_new,
                &self.stage_y,
                &mut self.rates[0],
            ) {
                self.reject(core, h * FAILURE_SHRINK, why, &mut cause);
                continue;
            }
            if let Some((h_accepted, err_accepted)) = self.last_accepted {
                let predicted = h_accepted / h * (err * err / err_accepted).powf(0.25) / SAFETY;
                quotient = quotient.max(predicted.clamp(GROW_MOST, SHRINK_MOST));
            }
            core.count_rounding_limited(self.error_against_tolerance(core));
            self.last_accepted = Some((h, err.max(1e-2)));
            let mut h_new = h / quotient;
            if self.after_rejection {
                h_new = h_new.min(h);
            }
            self.accept(core, h);
            // A small change keeps the step and its factorisations.
            let h_next = if newton.theta <= self.jacobian_reuse && KEEP_STEP.contains(&(h_new / h))
            {
                h
            } else {
                h_new
            };
            core.h = if lands { h_next.max(core.h) } else { h_next };
            self.jacobian_valid = newton.theta <= self.jacobian_reuse;
            core.advance(h, lands, t_end);
            return Ok(());
        }
    }

    /// Makes the trial step the current state: `y + z3`, its rate (in
    /// `rates[0]`), and the collocation polynomial.
    fn accept(&mut self, core: &mut Core, h: f64) {
        let [z1, z2, z3] = &self.z;
        let [p1, p2, p3] = &mut self.polynomial;
        for i in 0..self.n {
            p1[i] = (z2[i] - z3[i]) / C2M1;
            let slope = (z1[i] - z2[i]) / C1MC2;
            let curvature = (slope - z1[i] / C1) / C2;
            p2[i] = (slope - p1[i]) / C1M1;
            p3[i] = p2[i] - curvature;
        }
        self.y_before.copy_from_slice(&core.y);
        std::mem::swap(&mut core.y, &mut self.stage_y);
        std::mem::swap(&mut core.dy, &mut self.rates[0]);
        self.h_last = h;
        self.first = false;
        self.after_rejection = false;
        self.jacobian_current = false;
    }

    /// Counts a rejected trial; a Jacobian from an earlier state is renewed.
    fn reject<E>(
        &mut self,
        core: &mut Core,
        h_next: f64,
        why: Rejection<E>,
        cause: &mut Option<Rejection<E>>,
    ) {
        core.reject(h_next, why, cause);
        self.after_rejection = true;
        if !self.jacobian_current {
            self.jacobian_valid = false;
        }
    }

    fn update_jacobian<S: System + ?Sized>(
        &mut self,
        core: &mut Core,
        system: &mut S,
    ) -> Result<(), IntegrateError<S::Error>> {
        core.stats.jacobian_evaluations += 1;
        self.jacobian.clear();
        match &mut self.jacobian {
            Jacobian::Dense(matrix) => system.jacobian(core.t, &core.y, &core.dy, matrix),
            Jacobian::Sparse { pattern, values } => {
                system.sparse_jacobian(core.t, &core.y, &core.dy, pattern, values)
            }
        }
        .map_err(|error| IntegrateError::Jacobian { t: core.t, error })?;
        if !self.jacobian.values().iter().all(|entry| entry.is_finite()) {
            return Err(IntegrateError::JacobianNotFinite { t: core.t });
        }
        core.update_floor(system);
        self.jacobian_valid = true;
        self.jacobian_current = true;
        self.jacobian_evaluated = true;
        self.factorised_for = f64::NAN;
        Ok(())
    }

    /// LU factorisations of `γ/h − J` and `(α + iβ)/h − J`; false when one
    /// is singular.
    fn factorise(&mut self, h: f64, core: &mut Core) -> bool {
        core.stats.lu_decompositions += 1;
        let invertible =
            self.matrices
                .factorise(&self.jacobian, GAMMA / h, Complex::new(ALPHA / h, BETA / h));
        self.factorised_for = if invertible { h } else { f64::NAN };
        invertible
    }

    /// Newton's starting values: the last step's collocation polynomial
    /// extrapolated, or zero after a start.
    fn starting_values(&mut self, h: f64) {
        let [z1, z2, z3] = &mut self.z;
        if self.first {
            for values in [z1, z2, z3].into_iter().chain(&mut self.w) {
                values.fill(0.0);
            }
            return;
        }
        let c3q = h / self.h_last;
        let (c1q, c2q) = (C1 * c3q, C2 * c3q);
        let [p1, p2, p3] = &self.polynomial;
        let at = |s: f64, i: usize| s * (p1[i] + (s - C2M1) * (p2[i] + (s - C1M1) * p3[i]));
        for i in 0..self.n {
            let z = [at(c1q, i), at(c2q, i), at(c3q, i)];
            (z1[i], z2[i], z3[i]) = (z[0], z[1], z[2]);
            for (row, w) in T_INVERSE.iter().zip(&mut self.w) {
                w[i] = row[0] * z[0] + row[1] * z[1] + row[2] * z[2];
            }
        }
    }

    /// The simplified Newton iteration for the stages of a step of size
    /// `h`. A failure gives the factor to shrink the step by and why.
    fn newton<S: System + ?Sized>(
        &mut self,
        core: &mut Core,
        system: &mut S,
        h: f64,
    ) -> Result<Converged, (f64, Rejection<S::Error>)> {
        self.starting_values(h);
        if self.factorised_for != h {
            return Err((FAILURE_SHRINK, Rejection::Singular));
        }
        let n = self.n;
        let (gamma, alpha, beta) = (GAMMA / h, ALPHA / h, BETA / h);
        self.contraction = self.contraction.max(f64::EPSILON).powf(0.8);
        let mut theta = self.jacobian_reuse;
        let (mut previous_norm, mut previous_ratio) = (0.0, 0.0);
        for iteration in 1..=MAX_NEWTON {
            for ((c, z), rate) in [C1, C2, 1.0].iter().zip(&self.z).zip(&mut self.rates) {
                for (value, (y, z)) in self.stage_y.iter_mut().zip(core.y.iter().zip(z)) {
                    *value = y + z;
                }
                evaluate(system, &mut core.stats, core.t + c * h, &self.stage_y, rate)
                    .map_err(|why| (FAILURE_SHRINK, why))?;
            }
            let [w1, w2, w3] = &self.w;
            for i in 0..n {
                let rates = [self.rates[0][i], self.rates[1][i], self.rates[2][i]];
                let [r1, r2, r3] =
                    T_INVERSE.map(|row| row[0] * rates[0] + row[1] * rates[1] + row[2] * rates[2]);
                self.real_rhs[i] = r1 - gamma * w1[i];
                self.complex_rhs[i] = Complex::new(
                    r2 - alpha * w2[i] + beta * w3[i],
                    r3 - alpha * w3[i] - beta * w2[i],
                );
            }
            self.matrices.solve_real(&mut self.real_rhs);
            self.matrices.solve_complex(&mut self.complex_rhs);
            // An increment is measured against the tolerance, or against
            // what the rounding of its rate leaves in it over the step
            // where that is larger: a velocity that is rounding noise of
            // a joints' solve cannot contract below it.
            let norm = grouped_rms(&core.groups, 3, |i| {
                let (dw1, dw2) = (self.real_rhs[i], self.complex_rhs[i]);
                let scale = self.scale[i].max(FLOOR_MARGIN * h * core.floor[i]);
                [dw1, dw2.re, dw2.im]
                    .map(|dw| (dw / scale).powi(2))
                    .iter()
                    .sum()
            });
            if !norm.is_finite() {
                return Err((FAILURE_SHRINK, Rejection::NonFinite));
            }
            if iteration > 1 && iteration < MAX_NEWTON {
                let ratio = norm / previous_norm;
                theta = if iteration == 2 {
                    ratio
                } else {
                    (ratio * previous_ratio).sqrt()
                };
                previous_ratio = ratio;
                if theta >= 0.99 {
                    return Err((FAILURE_SHRINK, Rejection::Newton));
                }
                self.contraction = theta / (1.0 - theta);
                let remaining = (MAX_NEWTON - 1 - iteration) as i32;
                let predicted =
                    self.contraction * norm * theta.powi(remaining) / self.newton_tolerance;
                if predicted >= 1.0 {
                    let factor = 0.8
                        * predicted
                            .clamp(1e-4, 20.0)
                            .powf(-1.0 / (4.0 + f64::from(remaining)));
                    return Err((factor, Rejection::Newton));
                }
            }
            previous_norm = norm.max(f64::EPSILON);
            let [w1, w2, w3] = &mut self.w;
            let [z1, z2, z3] = &mut self.z;
            for i in 0..n {
                w1[i] += self.real_rhs[i];
                w2[i] += self.complex_rhs[i].re;
                w3[i] += self.complex_rhs[i].im;
                let w = [w1[i], w2[i], w3[i]];
                [z1[i], z2[i], z3[i]] = T.map(|row| row[0] * w[0] + row[1] * w[1] + row[2] * w[2]);
            }
            if self.contraction * norm <= self.newton_tolerance {
                return Ok(Converged {
                    iterations: iteration,
                    theta,
                });
            }
        }
        Err((FAILURE_SHRINK, Rejection::Newton))
    }

    /// The error of the step in units of the tolerance:
    /// `(γ/h − J)⁻¹ (f(y) + Σ d_i z_i / h)`, refined once through `f` at a
    /// first or rejected step when it fails the test.
    fn error_estimate<S: System + ?Sized>(
        &mut self,
        core: &mut Core,
        system: &mut S,
        h: f64,
    ) -> f64 {
        if self.factorised_for != h {
            return f64::INFINITY;
        }
        let [z1, z2, z3] = &self.z;
        let [d1, d2, d3] = ERROR_WEIGHTS.map(|d| d / h);
        let (combination, rest) = self.rates.split_at_mut(1);
        let combination = &mut combination[0];
        for i in 0..self.n {
            combination[i] = d1 * z1[i] + d2 * z2[i] + d3 * z3[i];
            self.real_rhs[i] = combination[i] + core.dy[i];
        }
        self.matrices.solve_real(&mut self.real_rhs);
        let size = |core: &Core, estimate: &[f64]| {
            let err = grouped_rms(&core.groups, 1, |i| {
                (estimate[i] / core.error_scale(i, h).scale).powi(2)
            });
            if err.is_nan() {
                f64::INFINITY
            } else {
                err.max(1e-10)
            }
        };
        let err = size(core, &self.real_rhs);
        if err < 1.0 || !(self.first || self.after_rejection) {
            return err;
        }
        for (value, (y, e)) in self
            .stage_y
            .iter_mut()
            .zip(core.y.iter().zip(self.real_rhs.iter()))
        {
            *value = y + e;
        }
        let refined = &mut rest[0];
        if evaluate(system, &mut core.stats, core.t, &self.stage_y, refined).is_err() {
            return err;
        }
        for i in 0..self.n {
            self.real_rhs[i] = refined[i] + combination[i];
        }
        self.matrices.solve_real(&mut self.real_rhs);
        size(core, &self.real_rhs)
    }

    /// The last error estimate (in `real_rhs`) against the tolerance alone
    /// (`scale`), with no allowance for rounding.
    fn error_against_tolerance(&self, core: &Core) -> f64 {
        grouped_rms(&core.groups, 1, |i| {
            (self.real_rhs[i] / self.scale[i]).powi(2)
        })
    }

    /// The last step's collocation polynomial at `t`: in the step's second
    /// half from its end, `y₁ + f(s)`, in its first half from its start,
    /// `y₀ + (f(s) − f(−1))` (`s` from −1 at the start to 0 at the end),
    /// so that near either end the rounding is that of the change from it,
    /// not of the state. Read from the end only, a state of velocities of
    /// 60 m/s came back from a point just after the start 7e-15 off, and a
    /// switching value with a damping of 1.5e6 1e-8 off where it was 6e-12:
    /// a crossing right after a located switch that the states never
    /// showed, 100 times over.
    pub fn dense(&self, core: &Core, t: f64, out: &mut [f64]) {
        let s = (t - core.t) / self.h_last;
        let [p1, p2, p3] = &self.polynomial;
        let change = |i: usize, s: f64| s * (p1[i] + (s - C2M1) * (p2[i] + (s - C1M1) * p3[i]));
        if s < -0.5 {
            for (i, value) in out.iter_mut().enumerate() {
                *value = self.y_before[i] + (change(i, s) - change(i, -1.0));
            }
        } else {
            for (i, value) in out.iter_mut().enumerate() {
                *value = core.y[i] + change(i, s);
            }
        }
    }
}
