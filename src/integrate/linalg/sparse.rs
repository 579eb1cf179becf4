//! The sparse path: the pattern's eliminated blocks first (see
//! `elimination`), then faer's supernodal LU of the kept unknowns, its
//! fill-reducing ordering and symbolic analysis computed once per
//! pattern, only the numbers refactorised.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::lu::{LuSymbolicParams, NumericLu, SymbolicLu, factorize_symbolic_lu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par};
use nalgebra::Complex;

use super::elimination::{BlockNumbers, Elimination};
use super::{Factorisation, Jacobian, Pattern};

/// Sparse LU factorisations of the two iteration matrices, on one pattern
/// (its eliminated blocks first, see [`Pattern::with_eliminated`]).
pub struct SparseLu {
    /// The eliminated blocks and the kept unknowns' pattern.
    elimination: Elimination,
    /// The kept unknowns' pattern, as faer reads it.
    structure: SymbolicSparseColMat<usize>,
    symbolic: SymbolicLu<usize>,
    real: NumericLu<usize, f64>,
    complex: NumericLu<usize, Complex<f64>>,
    /// The kept unknowns' Schur complements, on the reduced pattern.
    real_values: Vec<f64>,
    complex_values: Vec<Complex<f64>>,
    real_blocks: BlockNumbers<f64>,
    complex_blocks: BlockNumbers<Complex<f64>>,
    /// Both matrices factorised without a zero pivot.
    factorised: bool,
    scratch: MemBuffer,
    /// A right-hand side extended with zeros for the algebraic unknowns,
    /// and its kept unknowns' part.
    real_work: Vec<f64>,
    complex_work: Vec<Complex<f64>>,
    real_reduced: Vec<f64>,
    complex_reduced: Vec<Complex<f64>>,
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
        let elimination = Elimination::new(pattern, states, pattern.eliminated());
        let reduced = &elimination.pattern;
        let kept = reduced.dimension();
        let structure = SymbolicSparseColMat::new_checked(
            kept,
            kept,
            reduced.starts.clone(),
            None,
            reduced.rows.clone(),
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
        let n = elimination.dimension();
        SparseLu {
            real_values: vec![0.0; reduced.len()],
            complex_values: vec![Complex::new(0.0, 0.0); reduced.len()],
            real_blocks: BlockNumbers::default(),
            complex_blocks: BlockNumbers::default(),
            structure,
            symbolic,
            real: NumericLu::new(),
            complex: NumericLu::new(),
            factorised: false,
            scratch: MemBuffer::new(scratch),
            real_work: vec![0.0; n],
            complex_work: vec![Complex::new(0.0, 0.0); n],
            real_reduced: vec![0.0; kept],
            complex_reduced: vec![Complex::new(0.0, 0.0); kept],
            elimination,
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
        self.factorised = false;
        if !self.elimination.eliminate(
            values,
            real_shift,
            &mut self.real_values,
            &mut self.real_blocks,
        ) || !self.elimination.eliminate(
            values,
            complex_shift,
            &mut self.complex_values,
            &mut self.complex_blocks,
        ) {
            return false;
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
        let work = bordered(&mut self.real_work, rhs);
        let reduced = &mut self.real_reduced;
        let kept = reduced.len();
        self.elimination
            .forward(&mut self.real_blocks, work, reduced);
        let lu = faer::sparse::linalg::lu::LuRef::new_unchecked(&self.symbolic, &self.real);
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(reduced, kept, 1),
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
        self.elimination.back(&self.real_blocks, work, reduced);
        rhs.copy_from_slice(&work[..rhs.len()]);
    }

    fn solve_complex(&mut self, rhs: &mut [Complex<f64>]) {
        if !self.factorised {
            return;
        }
        let work = bordered(&mut self.complex_work, rhs);
        let reduced = &mut self.complex_reduced;
        let kept = reduced.len();
        self.elimination
            .forward(&mut self.complex_blocks, work, reduced);
        let lu = faer::sparse::linalg::lu::LuRef::new_unchecked(&self.symbolic, &self.complex);
        lu.solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(reduced, kept, 1),
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
        self.elimination.back(&self.complex_blocks, work, reduced);
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
