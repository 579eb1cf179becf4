//! The multipliers: the reactions that hold the joints at each right-hand
//! side, the projection of a state onto the constraints, and the search
//! for redundant equations.

use nalgebra::{DMatrix, DVector, Matrix3, UnitQuaternion, Vector3};

use super::rows::{BodyMotion, Row};
use super::{Imposed, active_rows, given_velocities, initial_rows, joint_rows};
use crate::number::Number;
use crate::simulate::Model;
use crate::simulate::model::Joint;

/// The joints' equations are singular at a state (the mechanism is at a
/// singular configuration, or its equations are dependent there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Singular;

/// Why the joints' reactions cannot be found at a state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Unheld {
    /// The equations are singular there.
    Singular,
    /// Held equation `row` ([`active_rows`]' order) asks for an
    /// acceleration beyond a double's range: the parts' speeds, masses or
    /// loads are too large for it.
    Overflow {
        /// The equation's index among the held equations.
        row: usize,
    },
}

impl From<Singular> for Unheld {
    fn from(_: Singular) -> Unheld {
        Unheld::Singular
    }
}

/// A body's inverse mass: of its centre of mass, and its inverse inertia
/// in ground axes.
struct Inverse<T: Number> {
    linear: f64,
    angular: Matrix3<T>,
}

/// The bodies' inverse masses. A massless part weighs, in the metric of
/// the least change (projection, redundancy), as the heaviest part of the
/// model with the largest inertia; in the dynamics (`massless_free`
/// false) it weighs nothing: [`constraint_loads`] solves its
/// accelerations with the multipliers.
fn inverses<T: Number>(
    model: &Model,
    bodies: &[BodyMotion<T>],
    inverse_inertia: &[Matrix3<f64>],
    massless_free: bool,
) -> Vec<Inverse<T>> {
    let stand_in = massless_free.then(|| stand_in(model));
    bodies
        .iter()
        .zip(&model.masses)
        .zip(inverse_inertia)
        .map(|((body, mass), inverse)| {
            let (linear, inverse) = match (mass.is_massless(), &stand_in) {
                (false, _) => (1.0 / mass.mass, *inverse),
                (true, Some((linear, angular))) => (*linear, *angular),
                (true, None) => (0.0, Matrix3::zeros()),
            };
            Inverse {
                linear,
                angular: &body.rotation * inverse.map(T::from) * body.rotation.transpose(),
            }
        })
        .collect()
}

/// The inverse mass and inertia a massless part has in the metric of the
/// least change: the heaviest part's mass, the largest principal inertia
/// (1 when every part is massless).
fn stand_in(model: &Model) -> (f64, Matrix3<f64>) {
    let heaviest = model
        .masses
        .iter()
        .map(|mass| mass.mass)
        .fold(0.0_f64, f64::max);
    let inertia = model
        .masses
        .iter()
        .map(|mass| mass.inertia.symmetric_eigenvalues().max())
        .fold(0.0_f64, f64::max);
    let linear = if heaviest > 0.0 { 1.0 / heaviest } else { 1.0 };
    let angular = if inertia > 0.0 { 1.0 / inertia } else { 1.0 };
    (linear, Matrix3::identity() * angular)
}

/// `M⁻¹ c` for one row's coefficients `c` on one body.
fn weighted<T: Number>(inverse: &Inverse<T>, c: &[T; 6]) -> [T; 6] {
    let angular = &inverse.angular * Vector3::new(c[3].clone(), c[4].clone(), c[5].clone());
    [
        c[0].clone() * inverse.linear,
        c[1].clone() * inverse.linear,
        c[2].clone() * inverse.linear,
        angular[0].clone(),
        angular[1].clone(),
        angular[2].clone(),
    ]
}

fn dot6<T: Number>(a: &[T; 6], b: &[T; 6]) -> T {
    a.iter()
        .zip(b)
        .map(|(a, b)| a.clone() * b.clone())
        .fold(T::zero(), |sum, term| sum + term)
}

/// The entries of `W = G M⁻¹ Gᵀ` of the held equations `rows` that can be
/// nonzero: `(k, l, W_kl)` for each pair of equations that move a common
/// body, both `(k, l)` and `(l, k)`. Each joint moves one or two bodies,
/// so a chain's `W` has a few entries a row, found through each body's
/// equations rather than by trying every pair.
fn schur_entries<T: Number>(rows: &[Row<T>], inverse: &[Inverse<T>]) -> Vec<(usize, usize, T)> {
    let mut rows_of_body: Vec<Vec<usize>> = vec![Vec::new(); inverse.len()];
    let weighted_rows: Vec<Vec<(usize, [T; 6])>> = rows
        .iter()
        .enumerate()
        .map(|(k, row)| {
            row.coefficients
                .iter()
                .map(|(body, c)| {
                    if rows_of_body[*body].last() != Some(&k) {
                        rows_of_body[*body].push(k);
                    }
                    (*body, weighted(&inverse[*body], c))
                })
                .collect()
        })
        .collect();
    let mut entries = Vec::new();
    let mut sums: Vec<(usize, T)> = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        sums.clear();
        for (body, c) in &row.coefficients {
            for &l in rows_of_body[*body].iter().filter(|&&l| l >= k) {
                let Some((_, mc)) = weighted_rows[l].iter().find(|(b, _)| b == body) else {
                    continue;
                };
                let term = dot6(c, mc);
                match sums.iter_mut().find(|(other, _)| *other == l) {
                    Some((_, sum)) => *sum += term,
                    None => sums.push((l, term)),
                }
            }
        }
        for (l, sum) in sums.drain(..) {
            if l != k {
                entries.push((l, k, sum.clone()));
            }
            entries.push((k, l, sum));
        }
    }
    entries
}

/// `W = G M⁻¹ Gᵀ` of the held equations `rows`, dense.
fn schur<T: Number>(rows: &[Row<T>], inverse: &[Inverse<T>]) -> DMatrix<T> {
    dense(rows.len(), schur_entries(rows, inverse))
}

/// The `m × m` matrix of `entries`.
fn dense<T: Number>(m: usize, entries: Vec<(usize, usize, T)>) -> DMatrix<T> {
    let mut matrix = DMatrix::<T>::zeros(m, m);
    for (k, l, value) in entries {
        matrix[(k, l)] = value;
    }
    matrix
}

/// From how many held equations `W λ = rhs` is solved by a sparse LU when
/// no derivatives ride on it: a chain's `W` is banded, and a dense LU
/// costs the cube of its size (a chain of 200 links on revolute joints
/// holds 1 000 equations: 0.1 s simulated with DOP853 took 11 s with the
/// dense LU, 1.4 s with the sparse one, the rest of which was the dense
/// Gram-Schmidt [`independent`] replaced). The sparse LU analyses the
/// pattern at every solve: chains of 16 links (80 equations) cost 34 ms
/// sparse against 30 ms dense for 2 s simulated, of 25 links (125) 67
/// against 85 ms.
const SPARSE_FROM: usize = 100;

/// The solution of `W x = rhs`, `W` given by its `entries` (of size `m`),
/// by faer's sparse LU; `None` when it is singular.
fn sparse_solved(m: usize, entries: &[(usize, usize, f64)], rhs: &[f64]) -> Option<Vec<f64>> {
    use faer::linalg::solvers::SolveCore;
    let triplets: Vec<faer::sparse::Triplet<usize, usize, f64>> = entries
        .iter()
        .map(|&(row, col, val)| faer::sparse::Triplet { row, col, val })
        .collect();
    let matrix =
        faer::sparse::SparseColMat::<usize, f64>::try_new_from_triplets(m, m, &triplets).ok()?;
    let lu = matrix.sp_lu().ok()?;
    let mut solution = rhs.to_vec();
    lu.solve_in_place_with_conj(
        faer::Conj::No,
        faer::MatMut::from_column_major_slice_mut(&mut solution, m, 1),
    );
    solution
        .iter()
        .all(|value| value.is_finite())
        .then_some(solution)
}

/// The solution of `matrix x = rhs`, when it is regular. (Over dual
/// numbers the LU carries the derivatives; no run takes that path: the
/// run's Jacobian keeps the multipliers as unknowns, `multiplier_loads`.)
fn solved<T: Number>(matrix: DMatrix<T>, rhs: DVector<T>) -> Result<DVector<T>, Singular> {
    if matrix.is_empty() {
        // No equation held (every one left out as redundant).
        return Ok(rhs);
    }
    let solution = matrix.lu().solve(&rhs).ok_or(Singular)?;
    if solution.iter().all(|value| value.value().is_finite()) {
        Ok(solution)
    } else {
        Err(Singular)
    }
}

/// The multipliers `λ` of `W λ = rhs`, `W = G M⁻¹ Gᵀ`.
fn multipliers<T: Number>(
    rows: &[Row<T>],
    inverse: &[Inverse<T>],
    rhs: DVector<T>,
) -> Result<DVector<T>, Singular> {
    let m = rows.len();
    let entries = schur_entries(rows, inverse);
    let constant = || {
        entries.iter().all(|(_, _, value)| value.is_constant())
            && rhs.iter().all(Number::is_constant)
    };
    if m >= SPARSE_FROM && constant() {
        let values: Vec<(usize, usize, f64)> = entries
            .iter()
            .map(|(k, l, value)| (*k, *l, value.value()))
            .collect();
        let rhs: Vec<f64> = rhs.iter().map(Number::value).collect();
        let solution = sparse_solved(m, &values, &rhs).ok_or(Singular)?;
        return Ok(DVector::from_iterator(m, solution.into_iter().map(T::from)));
    }
    solved(dense(m, entries), rhs)
}

/// `Gᵀ λ` on each body: a force and a torque (about its centre of mass), in
/// ground.
fn generalised<T: Number>(rows: &[Row<T>], multipliers: &DVector<T>, bodies: usize) -> Vec<[T; 6]> {
    let mut loads = vec![std::array::from_fn(|_| T::zero()); bodies];
    for (row, lambda) in rows.iter().zip(multipliers.iter()) {
        for (body, c) in &row.coefficients {
            for (load, c) in loads[*body].iter_mut().zip(c) {
                *load += c.clone() * lambda.clone();
            }
        }
    }
    loads
}

/// What holding the joints gives: the multipliers `λ`, one for each held
/// equation in the order of [`active_rows`], and the accelerations of the
/// massless parts the equations reach (`[v' | ω']` of the centre, in
/// ground), which no mass gives.
pub(crate) struct Held<T: Number> {
    /// `λ`.
    pub(crate) multipliers: DVector<T>,
    /// Each massless part's index and accelerations.
    pub(crate) massless: Vec<(usize, [T; 6])>,
}

/// Adds the joints' reactions to the applied `force` and `torque` (about
/// each body's centre of mass, in ground): the loads `−Gᵀ λ` whose
/// accelerations keep every held equation's second derivative zero.
///
/// A massless part's six equations are a balance, `f₀ − G₀ᵀ λ = 0`, and
/// its accelerations `a₀` are unknowns beside `λ`:
///
/// ```text
/// [ W   −G₀ ] [ λ  ]   [ G a_free + bias ]
/// [ G₀ᵀ  0  ] [ a₀ ] = [ f₀              ]
/// ```
///
/// (`W` over the parts with mass); singular when the joints leave a
/// massless part a freedom no mass follows.
pub(crate) fn constraint_loads<T: Number>(
    model: &Model,
    bodies: &[BodyMotion<T>],
    imposed: &Imposed<'_>,
    inverse_inertia: &[Matrix3<f64>],
    force: &mut [Vector3<T>],
    torque: &mut [Vector3<T>],
) -> Result<Held<T>, Unheld> {
    let rows = active_rows(model, bodies, imposed);
    if rows.is_empty() {
        return Ok(Held {
            multipliers: DVector::zeros(0),
            massless: Vec::new(),
        });
    }
    let inverse = inverses(model, bodies, inverse_inertia, false);
    // The accelerations under the applied loads alone (none for a
    // massless part).
    let free: Vec<[T; 6]> = bodies
        .iter()
        .enumerate()
        .map(|(index, body)| {
            let mass = &model.masses[index];
            if mass.is_massless() {
                return std::array::from_fn(|_| T::zero());
            }
            let linear =
                &force[index] * T::from(inverse[index].linear) + model.gravity.map(T::from);
            let inertia = mass.inertia.map(T::from);
            let omega = body.rotation.transpose() * &body.omega;
            let spin = inverse_inertia[index].map(T::from)
                * (body.rotation.transpose() * &torque[index] - omega.cross(&(&inertia * &omega)));
            let angular = &body.rotation * spin;
            [0, 1, 2, 3, 4, 5].map(|k| {
                if k < 3 {
                    linear[k].clone()
                } else {
                    angular[k - 3].clone()
                }
            })
        })
        .collect();
    let rhs = DVector::from_iterator(
        rows.len(),
        rows.iter().map(|row| acceleration_residual(row, &free)),
    );
    if let Some(row) = rhs.iter().position(|value| !value.value().is_finite()) {
        return Err(Unheld::Overflow { row });
    }
    let mut massless: Vec<usize> = rows
        .iter()
        .flat_map(|row| row.coefficients.iter().map(|(body, _)| *body))
        .filter(|&body| model.masses[body].is_massless())
        .collect();
    massless.sort_unstable();
    massless.dedup();
    let held = if massless.is_empty() {
        Held {
            multipliers: multipliers(&rows, &inverse, rhs)?,
            massless: Vec::new(),
        }
    } else {
        balanced(&rows, &inverse, rhs, &massless, force, torque)?
    };
    for (body, load) in generalised(&rows, &held.multipliers, bodies.len())
        .into_iter()
        .enumerate()
    {
        for k in 0..3 {
            force[body][k] -= load[k].clone();
            torque[body][k] -= load[k + 3].clone();
        }
    }
    Ok(held)
}

/// Adds the loads `−Gᵀ λ` of the given `multipliers` (one for each held
/// equation, in [`active_rows`]' order) to the applied `force` and
/// `torque`, and gives the held equations: each one's `G u' + bias`
/// ([`acceleration_residual`]) is zero at the multipliers
/// [`constraint_loads`] finds. Over dual numbers seeded in the states and
/// the multipliers, these are the index-1 form's equations in `(y, λ)`,
/// whose Jacobian is as sparse as the joints are (the ODE's, with the
/// multipliers eliminated, is dense along a chain).
pub(crate) fn multiplier_loads<T: Number>(
    model: &Model,
    bodies: &[BodyMotion<T>],
    imposed: &Imposed<'_>,
    multipliers: &[T],
    force: &mut [Vector3<T>],
    torque: &mut [Vector3<T>],
) -> Vec<Row<T>> {
    let rows = active_rows(model, bodies, imposed);
    let multipliers = DVector::from_column_slice(multipliers);
    for (body, load) in generalised(&rows, &multipliers, bodies.len())
        .into_iter()
        .enumerate()
    {
        for k in 0..3 {
            force[body][k] -= load[k].clone();
            torque[body][k] -= load[k + 3].clone();
        }
    }
    rows
}

/// `G u' + bias` of `row` at the bodies' `accelerations` (`[v' | ω']` of
/// each centre, in ground): zero where the accelerations keep the equation.
pub(crate) fn acceleration_residual<T: Number>(row: &Row<T>, accelerations: &[[T; 6]]) -> T {
    row.coefficients
        .iter()
        .fold(row.bias.clone(), |sum, (body, c)| {
            sum + dot6(c, &accelerations[*body])
        })
}

/// The multipliers and the accelerations of the `massless` parts, from the
/// system of [`constraint_loads`].
fn balanced<T: Number>(
    rows: &[Row<T>],
    inverse: &[Inverse<T>],
    rhs: DVector<T>,
    massless: &[usize],
    force: &[Vector3<T>],
    torque: &[Vector3<T>],
) -> Result<Held<T>, Singular> {
    let m = rows.len();
    let size = m + 6 * massless.len();
    let mut matrix = DMatrix::<T>::zeros(size, size);
    matrix
        .view_mut((0, 0), (m, m))
        .copy_from(&schur(rows, inverse));
    for (r, row) in rows.iter().enumerate() {
        for (body, c) in &row.coefficients {
            let Ok(slot) = massless.binary_search(body) else {
                continue;
            };
            for (k, c) in c.iter().enumerate() {
                let column = m + 6 * slot + k;
                matrix[(r, column)] = -c.clone();
                matrix[(column, r)] = c.clone();
            }
        }
    }
    let applied = massless.iter().flat_map(|&body| {
        (0..6).map(move |k| {
            if k < 3 {
                force[body][k].clone()
            } else {
                torque[body][k - 3].clone()
            }
        })
    });
    let rhs = DVector::from_iterator(size, rhs.iter().cloned().chain(applied));
    let solution = solved(matrix, rhs)?;
    let accelerations = massless
        .iter()
        .enumerate()
        .map(|(slot, &body)| {
            (
                body,
                std::array::from_fn(|k| solution[m + 6 * slot + k].clone()),
            )
        })
        .collect();
    Ok(Held {
        multipliers: solution.rows(0, m).into_owned(),
        massless: accelerations,
    })
}

/// The largest constraint residuals of a state: of the positions (`Φ`)
/// and of the velocities (`Φ' = G u`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Residuals {
    /// The largest `|Φ|` (a length, or the cosine of an angle).
    pub position: f64,
    /// The largest `|Φ'|`.
    pub velocity: f64,
}

impl Residuals {
    fn of(rows: &[Row<f64>]) -> Residuals {
        rows.iter()
            .fold(Residuals::default(), |most, row| Residuals {
                position: most.position.max(row.value.abs()),
                velocity: most.velocity.max(row.rate.abs()),
            })
    }

    /// The larger of each residual of `self` and `other`.
    pub fn max(self, other: Residuals) -> Residuals {
        Residuals {
            position: self.position.max(other.position),
            velocity: self.velocity.max(other.velocity),
        }
    }
}

/// The held equations at state `y`: each one's value `Φ` and its row of
/// `G` over the bodies' `[δc | δθ]` (a displacement of the centre and a
/// turn, in ground), six columns a body.
pub(crate) fn held_equations(
    model: &Model,
    y: &[f64],
    offsets: &[usize],
    imposed: &Imposed<'_>,
) -> (DVector<f64>, DMatrix<f64>) {
    let bodies = motions(y, offsets);
    let rows = active_rows(model, &bodies, imposed);
    let values = DVector::from_iterator(rows.len(), rows.iter().map(|row| row.value));
    (values, dense_rows(&rows, offsets.len()))
}

/// The rows of `G` of `rows` over `bodies` bodies' `[δc | δθ]`, dense.
fn dense_rows(rows: &[Row<f64>], bodies: usize) -> DMatrix<f64> {
    let mut g = DMatrix::zeros(rows.len(), 6 * bodies);
    for (r, row) in rows.iter().enumerate() {
        for (body, c) in &row.coefficients {
            for (k, c) in c.iter().enumerate() {
                g[(r, 6 * body + k)] += c;
            }
        }
    }
    g
}

/// The bodies' motions at state `y`, where each body's states start at
/// its entry of `offsets` (its centre of mass, quaternion `w x y z`,
/// velocity and angular velocity in its own axes).
pub(super) fn motions(y: &[f64], offsets: &[usize]) -> Vec<BodyMotion<f64>> {
    offsets
        .iter()
        .map(|&offset| {
            let s = &y[offset..];
            let rotation = body_quaternion(s).to_rotation_matrix().into_inner();
            BodyMotion {
                centre: Vector3::new(s[0], s[1], s[2]),
                velocity: Vector3::new(s[7], s[8], s[9]),
                omega: rotation * Vector3::new(s[10], s[11], s[12]),
                rotation,
            }
        })
        .collect()
}

/// The orientation of the body whose states start at `s` (its quaternion
/// `w x y z` at 3 to 6), normalised.
pub(crate) fn body_quaternion(s: &[f64]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(s[3], s[4], s[5], s[6]))
}

/// The least change (weighted by the masses and inertias) `−M⁻¹ Gᵀ W⁻¹ r`
/// that takes the residuals `r` of `rows` to zero at first order.
fn least_change(
    model: &Model,
    rows: &[Row<f64>],
    bodies: &[BodyMotion<f64>],
    inverse_inertia: &[Matrix3<f64>],
    residual: impl Fn(&Row<f64>) -> f64,
) -> Result<Vec<[f64; 6]>, Singular> {
    let residuals = DVector::from_iterator(rows.len(), rows.iter().map(residual));
    least_change_for(model, rows, bodies, inverse_inertia, residuals)
}

/// The least change that takes `residuals` to zero at first order, the
/// Jacobian `rows`' (as [`least_change`]).
fn least_change_for(
    model: &Model,
    rows: &[Row<f64>],
    bodies: &[BodyMotion<f64>],
    inverse_inertia: &[Matrix3<f64>],
    residuals: DVector<f64>,
) -> Result<Vec<[f64; 6]>, Singular> {
    let inverse = inverses(model, bodies, inverse_inertia, true);
    let lambda = multipliers(rows, &inverse, residuals)?;
    Ok(generalised(rows, &lambda, bodies.len())
        .iter()
        .zip(&inverse)
        .map(|(load, inverse)| weighted(inverse, load).map(|change| -change))
        .collect())
}

/// The change of the velocities at `bodies` in the initial-conditions
/// analysis when PARTs give velocities: it holds the equations `held`
/// (the joints', motions' and their initial velocities'), comes as near as
/// they let it to the velocities the PARTs give (`given`, least squares of
/// their residuals: a given velocity the joints leave free is kept
/// exactly), and is otherwise the least in the metric of the masses and
/// inertias. Worked out in coordinates scaled by `M^(1/2)`, where that
/// metric is Euclidean: `x₁ = −H⁺ r` holds the equations with the least
/// change, `P = I − H⁺H` spans what they leave free, and `x = x₁ + P w`
/// with `w = −(A P)⁺ (r_A + A x₁)` the least-norm least-squares fit of
/// the given rows `A` (pseudo-inverses from the singular values, below
/// `1e-10` of `H`'s and `A`'s largest taken as zero: nearly dependent rows
/// are not amplified).
fn given_velocity_change(
    model: &Model,
    held: &[Row<f64>],
    given: &[Row<f64>],
    bodies: &[BodyMotion<f64>],
    inverse_inertia: &[Matrix3<f64>],
) -> Vec<[f64; 6]> {
    let width = 6 * bodies.len();
    // The inverse square root of the metric, body by body.
    let mut root = DMatrix::zeros(width, width);
    for (body, inverse) in inverses(model, bodies, inverse_inertia, true)
        .iter()
        .enumerate()
    {
        let linear = inverse.linear.sqrt();
        let eigen = nalgebra::SymmetricEigen::new(inverse.angular);
        let angular = eigen.eigenvectors
            * Matrix3::from_diagonal(&eigen.eigenvalues.map(|value| value.max(0.0).sqrt()))
            * eigen.eigenvectors.transpose();
        for k in 0..3 {
            root[(6 * body + k, 6 * body + k)] = linear;
        }
        root.view_mut((6 * body + 3, 6 * body + 3), (3, 3))
            .copy_from(&angular);
    }
    let scaled_rows = |rows: &[Row<f64>]| {
        let residuals = DVector::from_iterator(rows.len(), rows.iter().map(|row| row.rate));
        (dense_rows(rows, bodies.len()) * &root, residuals)
    };
    // The pseudo-inverse of `matrix`, its singular values below `1e-10`
    // of `scale`'s largest taken as zero.
    let pseudo_inverse = |matrix: &DMatrix<f64>, scale: &DMatrix<f64>| {
        if matrix.is_empty() {
            return DMatrix::zeros(matrix.ncols(), matrix.nrows());
        }
        let largest = scale.clone().singular_values().max();
        let floor = (1e-10 * largest).max(f64::MIN_POSITIVE);
        matrix
            .clone()
            .svd(true, true)
            .pseudo_inverse(floor)
            .unwrap_or_else(|_| DMatrix::zeros(matrix.ncols(), matrix.nrows()))
    };
    let (h, r) = scaled_rows(held);
    let (a, r_a) = scaled_rows(given);
    let h_plus = pseudo_inverse(&h, &h);
    let x1 = -(&h_plus * r);
    let free = DMatrix::identity(width, width) - &h_plus * &h;
    // What the equations fix leaves rounding in `A P`: measured against
    // `A`'s own scale, not amplified.
    let fit = &a * &free;
    let w = -(pseudo_inverse(&fit, &a) * (r_a + &a * &x1));
    let change = &root * (x1 + &free * w);
    (0..bodies.len())
        .map(|body| std::array::from_fn(|k| change[6 * body + k]))
        .collect()
}

/// Newton iterations on the positions at most.
const POSITION_ITERATIONS: usize = 40;

/// Halvings of a Newton step that does not lower the residual, at most.
const STEP_HALVINGS: usize = 12;

/// The largest turn of a part in one Newton step on the positions: Adams'
/// ALIMIT, 30°.
const TURN_LIMIT: f64 = std::f64::consts::PI / 6.0;

/// The tolerance a state assembled with a zero tolerance must meet in the
/// end: `ASSEMBLED · (1 + |largest coordinate|)` on each state's least
/// change (rounding leaves about 1e-15 of it).
const ASSEMBLED: f64 = 1e-10;

/// Why a state could not be put on the constraints.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Unassembled {
    /// The equations are dependent at the state (a singular
    /// configuration): equation `row` (in the order of [`active_rows`]),
    /// where it is known, is the first that repeats those before it.
    Singular {
        /// The first dependent equation's index among the held equations.
        row: Option<usize>,
    },
    /// Newton's iterations ended with equation `row` (in the order of
    /// [`active_rows`]) still off by `residual`: the parts cannot be
    /// placed as the joints and motions ask.
    Apart {
        /// The equation's index among the held equations.
        row: usize,
        /// Its value `Φ` left (not a number where it cannot be
        /// evaluated).
        residual: f64,
    },
}

impl From<Singular> for Unassembled {
    fn from(_: Singular) -> Unassembled {
        Unassembled::Singular { row: None }
    }
}

/// The dependence of `rows` on `bodies` bodies, with the first row that
/// repeats those before it (its part of `G` in the span of theirs, or
/// zero: an equation the parts' places do not move), by Gram–Schmidt.
/// Only when the joints cannot be solved, so on dense rows: its bound,
/// [`DEPENDENT`], is a remainder of 1e-9 of a row's length, whose square
/// is below the rounding of the squared lengths that [`independent`]'s
/// Cholesky factorisation subtracts (its bound of 1e-6 squares to 1e-12,
/// well above it).
fn dependence(rows: &[Row<f64>], bodies: usize) -> Unassembled {
    dependence_from(rows, bodies, 0)
}

/// [`dependence`], with the rows before `from` that repeat those before
/// them passed over (left out of the span, not reported): the first row
/// from `from` on that repeats the rows kept before it.
fn dependence_from(rows: &[Row<f64>], bodies: usize, from: usize) -> Unassembled {
    let mut basis: Vec<DVector<f64>> = Vec::new();
    for (index, row) in rows.iter().enumerate() {
        let mut left = DVector::zeros(6 * bodies);
        for (body, coefficients) in &row.coefficients {
            for (k, coefficient) in coefficients.iter().enumerate() {
                left[6 * body + k] += coefficient;
            }
        }
        let size = left.norm();
        // Twice, so that rounding leaves no part of the basis behind.
        for _ in 0..2 {
            for direction in &basis {
                let along = direction.dot(&left);
                left -= direction * along;
            }
        }
        let remaining = left.norm();
        // A row of NaN (an equation out of its domain) counts as dependent.
        if remaining.is_nan() || remaining <= DEPENDENT * size {
            if index < from {
                continue;
            }
            return Unassembled::Singular { row: Some(index) };
        }
        basis.push(left / remaining);
    }
    Unassembled::Singular { row: None }
}

/// A row of `G` whose part outside the rows before it is at most this much
/// of its size repeats them.
const DEPENDENT: f64 = 1e-9;

/// The integrator's error tolerance on a state: `atol + rtol |y|` for
/// each component (zero: put every state on the constraints).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tolerance {
    pub(crate) rtol: f64,
    pub(crate) atol: f64,
}

/// The size of `change` (per body, `[position | rotation]` or `[velocity |
/// angular velocity]`) against the tolerance on the body states from
/// `first` (0: the positions, 7: the velocities) of `y`: above 1, the
/// change is larger than the error the integrator allows those states.
fn scaled(
    y: &[f64],
    offsets: &[usize],
    change: &[[f64; 6]],
    first: usize,
    tolerance: Tolerance,
) -> f64 {
    let mut most: f64 = 0.0;
    for (change, &offset) in change.iter().zip(offsets) {
        let s = &y[offset..];
        let rotation_size = if first == 0 {
            s[3..7].iter().fold(0.0_f64, |most, q| most.max(q.abs()))
        } else {
            s[10..13].iter().fold(0.0_f64, |most, w| most.max(w.abs()))
        };
        for k in 0..3 {
            let linear_scale = tolerance.atol + tolerance.rtol * s[first + k].abs();
            let angular_scale = tolerance.atol + tolerance.rtol * rotation_size;
            most = most
                .max(change[k].abs() / linear_scale)
                .max(change[k + 3].abs() / angular_scale);
        }
    }
    most
}

/// Puts state `y` back on the constraints when the least change that does
/// it is larger than `tolerance` allows: the positions by Newton's method
/// on the least change, each step turning no part by more than 30° and
/// halved until the change asked for at the trial state shrinks (a large
/// correction, a part turned by tens of degrees, is not linear), until
/// the change is a thousandth of the tolerance or rounding stops it from
/// shrinking; then the velocities by one least
/// change. The residuals found before; an error when the positions end
/// further off than the tolerance (with a zero tolerance, than
/// [`ASSEMBLED`] of the state's size).
///
/// `initial` asks for the initial-conditions analysis: the joints' initial
/// displacements are held beside the equations while the positions are
/// found, and their initial velocities while the velocities are.
pub(crate) fn project(
    model: &Model,
    y: &mut [f64],
    offsets: &[usize],
    imposed: &Imposed<'_>,
    inverse_inertia: &[Matrix3<f64>],
    tolerance: Tolerance,
    initial: bool,
) -> Result<Residuals, Unassembled> {
    let bodies = motions(y, offsets);
    let active = active_rows(model, &bodies, imposed);
    let before = Residuals::of(&active);
    // The initial conditions the equations leave free, found at the state
    // as given (an EXACT coordinate a joint already fixes yields to it).
    let free = |velocities: bool| {
        if initial {
            independent(&active, &initial_rows(model, &bodies, velocities))
        } else {
            Vec::new()
        }
    };
    let (free_positions, free_velocities) = (free(false), free(true));
    // `rows` with the free initial conditions of the positions' or the
    // velocities' analysis.
    let with_initial = |mut rows: Vec<Row<f64>>, bodies: &[BodyMotion<f64>], velocities: bool| {
        if initial {
            let free = if velocities {
                &free_velocities
            } else {
                &free_positions
            };
            rows.extend(
                initial_rows(model, bodies, velocities)
                    .into_iter()
                    .zip(free)
                    .filter(|(_, free)| **free)
                    .map(|(row, _)| row),
            );
        }
        rows
    };
    let held = |bodies: &[BodyMotion<f64>], velocities: bool| {
        with_initial(active_rows(model, bodies, imposed), bodies, velocities)
    };
    let rows = with_initial(active, &bodies, false);
    let mut residual = Residuals::of(&rows).position;
    // An equation that cannot be evaluated here (a GCON's FUNCTION out of
    // its domain) is named, not taken for a singular configuration.
    if let Some(row) = rows.iter().position(|row| !row.value.is_finite()) {
        return Err(Unassembled::Apart {
            row,
            residual: f64::NAN,
        });
    }
    let off_positions = least_change(model, &rows, &bodies, inverse_inertia, |row| row.value)
        .map_err(|_| dependence(&rows, bodies.len()))?;
    // The least change of the velocities at `bodies`, whose positions'
    // equations are `rows`: outside the initial analysis the velocities
    // hold the same equations.
    let velocity_change = |bodies: &[BodyMotion<f64>], rows: &[Row<f64>]| {
        if initial && !model.given_velocities.is_empty() {
            let given = given_velocities(model, bodies);
            return Ok(given_velocity_change(
                model,
                &held(bodies, true),
                &given,
                bodies,
                inverse_inertia,
            ));
        }
        let velocity_rows = initial.then(|| held(bodies, true));
        least_change(
            model,
            velocity_rows.as_deref().unwrap_or(rows),
            bodies,
            inverse_inertia,
            |row| row.rate,
        )
    };
    let off_velocities = velocity_change(&bodies, &rows)?;
    if scaled(y, offsets, &off_positions, 0, tolerance) <= 1.0
        && scaled(y, offsets, &off_velocities, 7, tolerance) <= 1.0
    {
        return Ok(before);
    }
    let fine = Tolerance {
        rtol: 1e-3 * tolerance.rtol,
        atol: 1e-3 * tolerance.atol,
    };
    let largest_residual = |y: &[f64]| {
        let bodies = motions(y, offsets);
        Residuals::of(&held(&bodies, false)).position
    };
    for _ in 0..POSITION_ITERATIONS {
        if residual == 0.0 {
            break;
        }
        let bodies = motions(y, offsets);
        let rows = held(&bodies, false);
        let change = least_change(model, &rows, &bodies, inverse_inertia, |row| row.value)?;
        if scaled(y, offsets, &change, 0, fine) <= 1.0 {
            break;
        }
        let start = y.to_vec();
        let size = scaled(&start, offsets, &change, 0, fine);
        // No part turned by more than ALIMIT in one step.
        let turn = change.iter().fold(0.0_f64, |most, change| {
            most.max(Vector3::new(change[3], change[4], change[5]).norm())
        });
        let mut fraction = (TURN_LIMIT / turn).min(1.0);
        let mut lowered = false;
        for _ in 0..STEP_HALVINGS {
            moved(y, &start, offsets, &change, fraction);
            // The natural monotonicity test (Deuflhard): the change the
            // step's Jacobian asks for at the trial state, its simplified
            // Newton correction, is smaller than the step's own. Unlike
            // the residuals, it weighs lengths and angles alike, so a part
            // turned about a far point is not held back by the
            // second-order error of its markers' places.
            let trial = held(&motions(y, offsets), false);
            let accepted = if trial.len() == rows.len() {
                let residuals =
                    DVector::from_iterator(trial.len(), trial.iter().map(|row| row.value));
                least_change_for(model, &rows, &bodies, inverse_inertia, residuals).is_ok_and(
                    |simplified| {
                        scaled(&start, offsets, &simplified, 0, fine)
                            <= (1.0 - 0.25 * fraction) * size
                    },
                )
            } else {
                largest_residual(y) < residual
            };
            if accepted {
                residual = Residuals::of(&trial).position;
                lowered = true;
                break;
            }
            fraction *= 0.5;
        }
        if !lowered {
            // Rounding (or a fold of the equations) stops the residual
            // from falling: the state as it was.
            y.copy_from_slice(&start);
            break;
        }
    }
    let bodies = motions(y, offsets);
    let rows = held(&bodies, false);
    let change = least_change(model, &rows, &bodies, inverse_inertia, |row| row.value)?;
    let size = 1.0 + y.iter().fold(0.0_f64, |most, value| most.max(value.abs()));
    let allowed = Tolerance {
        rtol: tolerance.rtol,
        atol: tolerance.atol.max(ASSEMBLED * size),
    };
    if scaled(y, offsets, &change, 0, allowed) > 1.0 {
        let (row, residual) = rows.iter().map(|row| row.value.abs()).enumerate().fold(
            (0, 0.0),
            |most, (index, value)| {
                if value > most.1 { (index, value) } else { most }
            },
        );
        return Err(Unassembled::Apart { row, residual });
    }
    if initial {
        // A joint's initial displacement the other equations fix must
        // agree with them.
        let active = rows.len() - free_positions.iter().filter(|free| **free).count();
        let joint_rows = super::positioned_initials(model).count();
        if let Some((index, row)) = initial_rows(model, &bodies, false)
            .iter()
            .enumerate()
            .take(joint_rows)
            .find(|(index, row)| !free_positions[*index] && row.value.abs() > 1e-9 * size)
        {
            return Err(Unassembled::Apart {
                row: active + index,
                residual: row.value.abs(),
            });
        }
    }
    let change = velocity_change(&bodies, &rows)?;
    for ((change, motion), &offset) in change.iter().zip(&bodies).zip(offsets) {
        let s = &mut y[offset..];
        for k in 0..3 {
            s[7 + k] += change[k];
        }
        let omega = motion.omega + Vector3::new(change[3], change[4], change[5]);
        let in_body = motion.rotation.transpose() * omega;
        s[10..13].copy_from_slice(in_body.as_slice());
    }
    Ok(before)
}

/// Which of `extra` are independent of `rows` and of the `extra` before
/// them (their rows of `G`; as [`find_redundant`] decides: the part of a
/// row outside the span of the rows kept before it is below a millionth of
/// its length).
///
/// That part's squared length is the pivot of the Cholesky factorisation
/// of `G Gᵀ` in the rows' order (Gram-Schmidt on the rows is that
/// factorisation), taken here within each row's envelope: from the first
/// row that moves one of its bodies. A chain's rows meet their
/// neighbours' only, so the cost grows as the number of rows, where
/// Gram-Schmidt on dense rows grows as its cube (a chain of 200 links
/// spent 0.7 s here before its first step).
fn independent(rows: &[Row<f64>], extra: &[Row<f64>]) -> Vec<bool> {
    let all: Vec<&Row<f64>> = rows.iter().chain(extra).collect();
    let bodies = all
        .iter()
        .flat_map(|row| row.coefficients.iter().map(|(body, _)| body + 1))
        .max()
        .unwrap_or(0);
    let mut first_of_body = vec![usize::MAX; bodies];
    // The first row of each row's envelope.
    let first: Vec<usize> = all
        .iter()
        .enumerate()
        .map(|(k, row)| {
            row.coefficients
                .iter()
                .map(|(body, _)| {
                    let first = &mut first_of_body[*body];
                    *first = (*first).min(k);
                    *first
                })
                .min()
                .unwrap_or(k)
        })
        .collect();
    let product = |a: &Row<f64>, b: &Row<f64>| {
        a.coefficients
            .iter()
            .filter_map(|(body, c)| {
                b.coefficients
                    .iter()
                    .find(|(other, _)| other == body)
                    .map(|(_, d)| dot6(c, d))
            })
            .sum::<f64>()
    };
    // Row k of the factor over columns first[k]..k, and its pivot (zero
    // for a row left out).
    let mut factor: Vec<Vec<f64>> = Vec::with_capacity(all.len());
    let mut pivots: Vec<f64> = Vec::with_capacity(all.len());
    let mut independent = Vec::new();
    for (k, row) in all.iter().enumerate() {
        let start = first[k];
        let mut entries = vec![0.0; k - start];
        for j in start..k {
            if pivots[j] == 0.0 {
                continue;
            }
            let overlap = start.max(first[j]);
            let mut value = product(row, all[j]);
            for i in overlap..j {
                value -= entries[i - start] * factor[j][i - first[j]];
            }
            entries[j - start] = value / pivots[j];
        }
        let squared = product(row, row);
        let rest = squared - entries.iter().map(|entry| entry * entry).sum::<f64>();
        let free = squared > 0.0 && rest > 1e-12 * squared;
        pivots.push(if free { rest.sqrt() } else { 0.0 });
        if !free {
            entries.iter_mut().for_each(|entry| *entry = 0.0);
        }
        factor.push(entries);
        if k >= rows.len() {
            independent.push(free);
        }
    }
    independent
}

/// `y` set to `start` moved by `fraction` of the positions' `change` (per
/// body, `[displacement | small rotation]` in ground).
fn moved(y: &mut [f64], start: &[f64], offsets: &[usize], change: &[[f64; 6]], fraction: f64) {
    y.copy_from_slice(start);
    for (change, &offset) in change.iter().zip(offsets) {
        let s = &mut y[offset..];
        for k in 0..3 {
            s[k] += fraction * change[k];
        }
        let turn = UnitQuaternion::from_scaled_axis(
            fraction * Vector3::new(change[3], change[4], change[5]),
        );
        let q = turn * body_quaternion(s);
        s[3..7].copy_from_slice(&[q.w, q.i, q.j, q.k]);
    }
}

/// The equations, each as (joint, equation), that repeat earlier ones at
/// state `y`: a row of `G` whose part outside the span of the rows kept
/// before it is below a millionth of its length (Gram-Schmidt, in the
/// order of the joints).
pub(crate) fn find_redundant(model: &Model, y: &[f64], offsets: &[usize]) -> Vec<(usize, usize)> {
    let bodies = motions(y, offsets);
    let mut labels = Vec::new();
    let mut rows = Vec::new();
    for (joint_index, joint) in model.joints.iter().enumerate() {
        for (equation, row) in joint_rows(model, joint, &bodies, [None; 2])
            .into_iter()
            .enumerate()
        {
            labels.push((joint_index, equation));
            rows.push(row);
        }
    }
    // An equation that cannot be evaluated here (a GCON's FUNCTION out of
    // its domain) is no repetition: the assembly names it.
    independent(&[], &rows)
        .into_iter()
        .zip(labels)
        .zip(&rows)
        .filter(|((independent, _), row)| !independent && is_finite(row))
        .map(|((_, label), _)| label)
        .collect()
}

/// The first held equation ([`active_rows`]' order) that repeats those
/// before it at state `y` with the motions as `imposed` gives them, once
/// the joints' redundant equations are left out: a motion, coupler or
/// GCON that sets a freedom the joints and the equations before it set
/// already (a joint's own repetitions were left out by
/// [`find_redundant`]). Equations that cannot be evaluated here are
/// passed over: the assembly names them.
pub(crate) fn first_repeated(
    model: &Model,
    y: &[f64],
    offsets: &[usize],
    imposed: &Imposed<'_>,
) -> Option<usize> {
    let bodies = motions(y, offsets);
    let mut rows = active_rows(model, &bodies, imposed);
    // Turns are measured as the motions they give at the model's length,
    // so that the test does not depend on the unit of length (a crank of
    // 5 000 mm is the crank of 5 m); only a repetition to rounding counts.
    let length = model_length(model);
    for row in &mut rows {
        for (_, coefficients) in &mut row.coefficients {
            for turn in &mut coefficients[3..] {
                *turn /= length;
            }
        }
    }
    // The joints' equations come first, and a repetition among them is
    // find_redundant's to leave out (its test, in the joints' own lengths,
    // may keep one that repeats here to rounding: it agrees with the
    // others, and the run holds it). Of the rows after them, the banded
    // factorisation finds the candidates; Gram-Schmidt on the dense rows,
    // whose bound is a thousand times tighter than its own, confirms one
    // (a repetition to rounding, not a mechanism near a toggle), only
    // where there is one to confirm.
    let joint_rows: usize = model.joints.iter().map(Joint::held_equations).sum();
    let suspect = independent(&[], &rows)
        .into_iter()
        .zip(&rows)
        .skip(joint_rows)
        .any(|(independent, row)| !independent && is_finite(row));
    if !suspect {
        return None;
    }
    match dependence_from(&rows, bodies.len(), joint_rows) {
        Unassembled::Singular { row: Some(row) } if is_finite(&rows[row]) => Some(row),
        _ => None,
    }
}

/// The model's length: the farthest a marker stands from its part's centre
/// of mass (1 where every marker is at one).
fn model_length(model: &Model) -> f64 {
    let farthest = model
        .scene
        .markers
        .iter()
        .filter_map(|marker| {
            marker
                .body
                .map(|body| (marker.position - model.masses[body].centre).norm())
        })
        .fold(0.0_f64, f64::max);
    if farthest.is_finite() && farthest > 0.0 {
        farthest
    } else {
        1.0
    }
}

/// Whether an equation's value and coefficients are finite numbers.
fn is_finite(row: &Row<f64>) -> bool {
    row.value.is_finite()
        && row
            .coefficients
            .iter()
            .all(|(_, entries)| entries.iter().all(|entry| entry.is_finite()))
}

/// How far a left-out equation may stay from zero, as a fraction of the
/// state's size, before its joint disagrees with the others: the data's
/// own precision, not the assembly's. View writes 10 significant digits
/// (an angle of `66.99486285d` to 1e-8 degrees), and that rounding,
/// carried through a loop of parts, leaves a repeated equation off by
/// about 1e-9 of the model (a user's SolidWorks-made parallel robot: 1.07e-9
/// m in a model a metre across, which Adams assembles without a word). A
/// marker in the wrong place is off by far more.
const REDUNDANT_AGREEMENT: f64 = 1e-7;

/// The left-out equation (see [`find_redundant`]) furthest from zero at
/// state `y`, when it is further than [`REDUNDANT_AGREEMENT`] of the
/// state's size:
/// its joint (an index into the model's joints) and its value. An
/// equation that repeats others to first order must also agree with them:
/// a pin 0.4 m from where a second pin holds the same part is no
/// redundancy but a model that cannot be assembled.
pub(crate) fn disagreeing_redundant(
    model: &Model,
    y: &[f64],
    offsets: &[usize],
) -> Option<(usize, f64)> {
    let bodies = motions(y, offsets);
    let size = 1.0 + y.iter().fold(0.0_f64, |most, value| most.max(value.abs()));
    model
        .joints
        .iter()
        .enumerate()
        .filter(|(_, joint)| !joint.redundant.is_empty())
        .flat_map(|(index, joint)| {
            let rows = joint_rows(model, joint, &bodies, [None; 2]);
            joint
                .redundant
                .iter()
                .map(move |&equation| (index, rows[equation].value.abs()))
                .collect::<Vec<_>>()
        })
        .filter(|(_, value)| *value > REDUNDANT_AGREEMENT * size)
        .fold(
            None,
            |most: Option<(usize, f64)>, (joint, value)| match most {
                Some((_, largest)) if largest >= value => most,
                _ => Some((joint, value)),
            },
        )
}
