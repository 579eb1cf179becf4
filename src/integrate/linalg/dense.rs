//! The dense path: nalgebra's LU with partial pivoting.

use nalgebra::{Complex, DMatrix, DVector, Dyn, LU};

use super::{Factorisation, Jacobian};

/// Dense LU factorisations of the two iteration matrices.
pub struct DenseLu {
    /// The matrices' dimension: the states, then the algebraic unknowns.
    dimension: usize,
    /// How many of the unknowns are states (shifted on the diagonal).
    states: usize,
    real: Option<LU<f64, Dyn, Dyn>>,
    complex: Option<LU<Complex<f64>, Dyn, Dyn>>,
    /// A right-hand side extended with zeros for the algebraic unknowns.
    real_work: DVector<f64>,
    complex_work: DVector<Complex<f64>>,
}

impl DenseLu {
    /// For `dimension × dimension` matrices whose first `states` unknowns
    /// are states, the rest algebraic (see [`super::Pattern`]).
    pub fn new(dimension: usize, states: usize) -> DenseLu {
        DenseLu {
            dimension,
            states,
            real: None,
            complex: None,
            real_work: DVector::zeros(dimension),
            complex_work: DVector::zeros(dimension),
        }
    }
}

impl Factorisation for DenseLu {
    fn factorise(
        &mut self,
        jacobian: &Jacobian,
        real_shift: f64,
        complex_shift: Complex<f64>,
    ) -> bool {
        let mut real = match jacobian {
            Jacobian::Dense(matrix) => -matrix,
            Jacobian::Sparse { pattern, values } => {
                let mut matrix = DMatrix::zeros(self.dimension, self.dimension);
                for ((row, column), value) in pattern.entries().zip(values) {
                    matrix[(row, column)] = -value;
                }
                matrix
            }
        };
        let mut complex = real.map(|value| Complex::new(value, 0.0));
        for i in 0..self.states {
            real[(i, i)] += real_shift;
            complex[(i, i)] += complex_shift;
        }
        let (real, complex) = (real.lu(), complex.lu());
        let invertible = real.is_invertible() && complex.is_invertible();
        self.real = Some(real);
        self.complex = Some(complex);
        invertible
    }

    fn solve_real(&mut self, rhs: &mut [f64]) {
        if let Some(lu) = &self.real {
            solve_bordered(lu, &mut self.real_work, rhs);
        }
    }

    fn solve_complex(&mut self, rhs: &mut [Complex<f64>]) {
        if let Some(lu) = &self.complex {
            solve_bordered(lu, &mut self.complex_work, rhs);
        }
    }
}

/// Solves with `lu` for `rhs` (the states' part) extended by zeros in
/// `work`, and writes the states' part of the solution back.
fn solve_bordered<T: nalgebra::ComplexField + Copy>(
    lu: &LU<T, Dyn, Dyn>,
    work: &mut DVector<T>,
    rhs: &mut [T],
) {
    work.fill(T::zero());
    work.rows_mut(0, rhs.len()).copy_from_slice(rhs);
    lu.solve_mut(work);
    rhs.copy_from_slice(work.rows(0, rhs.len()).as_slice());
}
