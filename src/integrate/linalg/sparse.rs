//! The sparse path: faer's supernodal LU, its fill-reducing ordering and
//! symbolic analysis computed once per pattern, only the numbers
//! refactorised.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::lu::{LuSymbolicParams, NumericLu, SymbolicLu, factorize_symbolic_lu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par};
use nalgebra::Complex;

use super::{Factorisation, Jacobian, Pattern};

/// Sparse LU factorisations of the two iteration matrices, on one pattern.
pub struct SparseLu {
    /// The matrices' dimension: the states, then the algebraic unknowns.
    dimension: usize,
    /// How many of the unknowns are states (shifted on the diagonal).
    states: usize,
    structure: SymbolicSparseColMat<usize>,
    /// Where each diagonal entry is among the entries.
    diagonal: Vec<usize>,
    symbolic: SymbolicLu<usize>,
    real: NumericLu<usize, f64>,
    complex: NumericLu<usize, Complex<f64>>,
    real_values: Vec<f64>,
    complex_values: Vec<Complex<f64>>,
    /// Both matrices factorised without a zero pivot.
    factorised: bool,
    scratch: MemBuffer,
    /// A right-hand side extended with zeros for the algebraic unknowns.
    real_work: Vec<f64>,
    complex_work: Vec<Complex<f64>>,
}

impl SparseLu {
    /// The symbolic analysis of `pattern` (its column ordering and fill),
    /// whose first `states` unknowns are states, the rest algebraic (see
    /// [`Pattern`]).
    ///
    /// # Panics
    ///
    /// When the analysis runs out of memory.
    pub fn new(pattern: &Pattern, states: usize) -> SparseLu {
        let n = pattern.dimension();
        let structure = SymbolicSparseColMat::new_checked(
            n,
            n,
            pattern.starts.clone(),
            None,
            pattern.rows.clone(),
        );
        // Supernodal always: a body's 13 states make dense blocks, which
        // faer's supernodal LU factorises as blocks, where the simplicial
        // one searches each column's reach again at every factorisation
        // (the stack of 32 balls: 8.6 s against 6.9 s CPU; BENCHMARKS.md).
        let params = LuSymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_lu(structure.as_ref(), params)
            .expect("memory for the symbolic analysis of a sparse LU");
        let scratch = StackReq::any_of(&[
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.factorize_numeric_lu_scratch::<Complex<f64>>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
            symbolic.solve_in_place_scratch::<Complex<f64>>(1, Par::Seq),
        ]);
        SparseLu {
            dimension: n,
            states,
            diagonal: pattern.diagonal.clone(),
            real_values: vec![0.0; pattern.len()],
            complex_values: vec![Complex::new(0.0, 0.0); pattern.len()],
            structure,
            symbolic,
            real: NumericLu::new(),
            complex: NumericLu::new(),
            factorised: false,
            scratch: MemBuffer::new(scratch),
            real_work: vec![0.0; n],
            complex_work: vec![Complex::new(0.0, 0.0); n],
        }
    }
}

impl Factorisation for SparseLu {
    fn factorise(
        &mut self,
        jacobian: &Jacobian,
        real_shift: f64,
        complex_shift: Complex<f64>,
    ) -> bool {
        let Jacobian::Sparse { values, .. } = jacobian else {
            unreachable!("a sparse factorisation is made only for a pattern");
        };
        for ((real, complex), value) in self
            .real_values
            .iter_mut()
            .zip(&mut self.complex_values)
            .zip(values)
        {
            *real = -value;
            *complex = Complex::new(-value, 0.0);
        }
        for &at in &self.diagonal[..self.states] {
            self.real_values[at] += real_shift;
            self.complex_values[at] += complex_shift;
        }
        let structure = self.structure.as_ref();
        let stack = MemStack::new(&mut self.scratch);
        let real = self.symbolic.factorize_numeric_lu(
            &mut self.real,
            SparseColMatRef::new(structure, &self.real_values),
            Par::Seq,
            stack,
            Default::default(),
        );
        let real_ok = real.is_ok();
        let stack = MemStack::new(&mut self.scratch);
        let complex = self.symbolic.factorize_numeric_lu(
            &mut self.complex,
            SparseColMatRef::new(structure, &self.complex_values),
            Par::Seq,
            stack,
            Default::default(),
        );
        self.factorised = real_ok && complex.is_ok();
        self.factorised
    }

    fn solve_real(&mut self, rhs: &mut [f64]) {
        if !self.factorised {
            return;
        }
        let lu = faer::sparse::linalg::lu::LuRef::new_unchecked(&self.symbolic, &self.real);
        let work = bordered(&mut self.real_work, rhs);
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(work, self.dimension, 1),
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
        rhs.copy_from_slice(&work[..rhs.len()]);
    }

    fn solve_complex(&mut self, rhs: &mut [Complex<f64>]) {
        if !self.factorised {
            return;
        }
        let lu = faer::sparse::linalg::lu::LuRef::new_unchecked(&self.symbolic, &self.complex);
        let work = bordered(&mut self.complex_work, rhs);
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(work, self.dimension, 1),
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
        rhs.copy_from_slice(&work[..rhs.len()]);
    }
}

/// `work` holding `rhs` (the states' part) and zeros for the algebraic
/// unknowns.
fn bordered<'w, T: Copy + Default>(work: &'w mut [T], rhs: &[T]) -> &'w mut [T] {
    work[..rhs.len()].copy_from_slice(rhs);
    work[rhs.len()..].fill(T::default());
    work
}
