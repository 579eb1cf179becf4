//! The linear algebra of an implicit step, behind one trait: the
//! integrator asks for the iteration matrices `σ I − J` (one real shift,
//! one complex) to be factorised and solved with, and does not know
//! whether they are dense or sparse.
//!
//! A system that knows where its Jacobian's nonzero entries can be gives
//! a [`Pattern`] (compressed sparse columns, every diagonal entry
//! included) and fills only those entries. The stepper
//! then chooses the factorisation ([`factorisation_for`]): a dense LU (nalgebra's, partial
//! pivoting) for small or dense systems, a sparse LU (faer's, a
//! fill-reducing column ordering and the symbolic analysis computed once
//! per pattern, only the numbers refactorised) beyond
//! [`SPARSE_FROM`] states. A system without a pattern gets the dense path.
//!
//! A pattern may be larger than the system: its trailing unknowns are then
//! algebraic. A system `y' = f(y, z)` whose `z` solves `0 = g(y, z)` (the
//! multipliers of a constrained mechanism) gives the Jacobian of `(f, g)`
//! in `(y, z)`, and the iteration matrices are
//!
//! ```text
//! [ σ I − f_y   −f_z ]
//! [   −g_y      −g_z ]
//! ```
//!
//! whose Schur complement on the states is `σ I − (f_y − f_z g_z⁻¹ g_y)`,
//! the ODE's own. A right-hand side gets zeros in the algebraic rows and
//! only the states' part of the solution is read, so the integrator sees
//! the ODE's matrices; they stay as sparse as `f` and `g` are, where the
//! ODE's Jacobian `f_y − f_z g_z⁻¹ g_y` is dense (a chain's every body
//! moves every other through the multipliers). An algebraic row's zero
//! diagonal is an entry of the pattern, and both LUs pivot, so it is no
//! breakdown.

mod dense;
mod elimination;
mod sparse;

use std::ops::Range;
use std::rc::Rc;

use nalgebra::{Complex, DMatrix};

pub use self::dense::DenseLu;
pub use self::sparse::SparseLu;

/// From this many states on, a system with a pattern no denser than
/// [`SPARSE_DENSITY`] is factorised sparse. Measured by `benches/linalg.rs`
/// on the stack of balls' pattern (`BENCHMARKS.md`, "The dense and sparse
/// crossover"): the dense LU is the faster at 39 states (3 bodies), the
/// sparse one from 52 (4 bodies: 1.6 times).
pub const SPARSE_FROM: usize = 48;

/// The largest fraction of nonzero entries a pattern may have and still be
/// factorised sparse: the stack of 4 bodies, density 0.62, is factorised
/// faster sparse; denser patterns were not measured.
pub const SPARSE_DENSITY: f64 = 2.0 / 3.0;

/// Where the entries of an `n×n` matrix may be nonzero, by columns: the
/// rows of column `j` are `rows[starts[j]..starts[j + 1]]`, increasing.
/// Every diagonal entry is in the pattern. A system of fewer than `n`
/// states gives a pattern of `n` for a Jacobian with algebraic unknowns
/// after its states (see the module's documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Pattern {
    n: usize,
    starts: Vec<usize>,
    rows: Vec<usize>,
    /// The position of each diagonal entry among the entries.
    diagonal: Vec<usize>,
    /// Blocks of states the sparse LU eliminates first
    /// ([`Pattern::with_eliminated`]).
    eliminated: Vec<Range<usize>>,
}

impl Pattern {
    /// The pattern of an `n×n` matrix with entries at `(row, column)`
    /// (in any order, repeats allowed) and on the diagonal.
    ///
    /// # Panics
    ///
    /// When an entry is outside the matrix.
    pub fn new(n: usize, entries: impl IntoIterator<Item = (usize, usize)>) -> Pattern {
        let mut columns: Vec<Vec<usize>> = (0..n).map(|column| vec![column]).collect();
        for (row, column) in entries {
            assert!(row < n && column < n, "an entry outside the matrix");
            columns[column].push(row);
        }
        let mut starts = Vec::with_capacity(n + 1);
        let mut rows = Vec::new();
        let mut diagonal = Vec::with_capacity(n);
        starts.push(0);
        for (column, mut column_rows) in columns.into_iter().enumerate() {
            column_rows.sort_unstable();
            column_rows.dedup();
            let at = column_rows
                .binary_search(&column)
                .expect("the diagonal is in");
            diagonal.push(rows.len() + at);
            rows.extend(column_rows);
            starts.push(rows.len());
        }
        Pattern {
            n,
            starts,
            rows,
            diagonal,
            eliminated: Vec::new(),
        }
    }

    /// The same pattern with `blocks` of states to be eliminated ahead of
    /// the sparse LU: disjoint ranges of states, in increasing order, with
    /// no entry between two of them, each of whose iteration matrices
    /// `σ I − J_kk` is regular for every shift of a step (a body's
    /// position and orientation, whose rates read only its own states).
    /// The LU then factorises the other unknowns' Schur complement (see
    /// the `elimination` module); blocks that do not meet these conditions
    /// are all ignored.
    pub fn with_eliminated(mut self, blocks: Vec<Range<usize>>) -> Pattern {
        self.eliminated = blocks;
        self
    }

    /// The blocks of states eliminated ahead of the sparse LU.
    pub fn eliminated(&self) -> &[Range<usize>] {
        &self.eliminated
    }

    /// The dimension `n`.
    pub fn dimension(&self) -> usize {
        self.n
    }

    /// The number of entries.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether the pattern has no entry (a `0×0` matrix).
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The position of entry `(row, column)` among the entries, if it is
    /// in the pattern.
    pub fn position(&self, row: usize, column: usize) -> Option<usize> {
        let start = self.starts[column];
        self.rows[start..self.starts[column + 1]]
            .binary_search(&row)
            .ok()
            .map(|at| start + at)
    }

    /// The entries `(row, column)` in storage order.
    pub fn entries(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.n).flat_map(move |column| {
            self.rows[self.starts[column]..self.starts[column + 1]]
                .iter()
                .map(move |&row| (row, column))
        })
    }

    /// The fraction of the `n²` entries that are in the pattern.
    pub fn density(&self) -> f64 {
        self.len() as f64 / (self.n as f64 * self.n as f64).max(1.0)
    }
}

/// A system's Jacobian as the integrator holds it: every entry, or the
/// values of a pattern's entries in its storage order (with the algebraic
/// unknowns' rows and columns when the pattern has them).
#[derive(Clone, Debug)]
pub enum Jacobian {
    /// An `n×n` matrix.
    Dense(DMatrix<f64>),
    /// Values on a pattern.
    Sparse {
        /// Where the entries are.
        pattern: Rc<Pattern>,
        /// One value per entry of the pattern.
        values: Vec<f64>,
    },
}

impl Jacobian {
    /// Zeros, dense (no pattern: `n×n`) or on `pattern`.
    pub fn zeros(n: usize, pattern: Option<Rc<Pattern>>) -> Jacobian {
        match pattern {
            None => Jacobian::Dense(DMatrix::zeros(n, n)),
            Some(pattern) => Jacobian::Sparse {
                values: vec![0.0; pattern.len()],
                pattern,
            },
        }
    }

    /// Every value held (all `n²` of a dense one).
    pub fn values(&self) -> &[f64] {
        match self {
            Jacobian::Dense(matrix) => matrix.as_slice(),
            Jacobian::Sparse { values, .. } => values,
        }
    }

    /// Sets every value held to zero.
    pub fn clear(&mut self) {
        match self {
            Jacobian::Dense(matrix) => matrix.fill(0.0),
            Jacobian::Sparse { values, .. } => values.fill(0.0),
        }
    }
}

/// The iteration matrices of an implicit step: `real_shift I − J` and
/// `complex_shift I − J`, factorised together and then solved with many
/// times. The integrator sees only this trait.
pub trait Factorisation {
    /// Factorises both matrices from `jacobian`; false when either is
    /// singular (then nothing may be solved until a factorisation succeeds).
    fn factorise(
        &mut self,
        jacobian: &Jacobian,
        real_shift: f64,
        complex_shift: Complex<f64>,
    ) -> bool;

    /// Overwrites `rhs` (the states' part) with the solution of the real
    /// system (its states' part; the algebraic unknowns' right-hand side
    /// is zero).
    fn solve_real(&mut self, rhs: &mut [f64]);

    /// Overwrites `rhs` with the solution of the complex system, as
    /// [`Factorisation::solve_real`] does.
    fn solve_complex(&mut self, rhs: &mut [Complex<f64>]);
}

/// The factorisation for a system of `n` states whose Jacobian has
/// `pattern` (`None`: dense; a pattern of more than `n` unknowns: the
/// algebraic ones after the states): sparse from [`SPARSE_FROM`] unknowns
/// when the pattern is no denser than [`SPARSE_DENSITY`], dense otherwise.
///
/// # Panics
///
/// When the pattern is smaller than the system.
pub fn factorisation_for(n: usize, pattern: Option<&Pattern>) -> Box<dyn Factorisation> {
    match pattern {
        Some(pattern) => {
            let dimension = pattern.dimension();
            assert!(dimension >= n, "a pattern smaller than the system");
            if dimension >= SPARSE_FROM && pattern.density() <= SPARSE_DENSITY {
                Box::new(SparseLu::new(pattern, n))
            } else {
                Box::new(DenseLu::new(dimension, n))
            }
        }
        None => Box::new(DenseLu::new(n, n)),
    }
}
