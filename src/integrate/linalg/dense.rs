//! The dense path: nalgebra's LU with partial pivoting.

use nalgebra::{Complex, DMatrix, DVectorViewMut, Dyn, LU};

use super::{Factorisation, Jacobian};

/// Dense LU factorisations of the two iteration matrices.
pub struct DenseLu {
    n: usize,
    real: Option<LU<f64, Dyn, Dyn>>,
    complex: Option<LU<Complex<f64>, Dyn, Dyn>>,
}

impl DenseLu {
    /// For `n×n` matrices.
    pub fn new(n: usize) -> DenseLu {
        DenseLu {
            n,
            real: None,
            complex: None,
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
                let mut matrix = DMatrix::zeros(self.n, self.n);
                for ((row, column), value) in pattern.entries().zip(values) {
                    matrix[(row, column)] = -value;
                }
                matrix
            }
        };
        let mut complex = real.map(|value| Complex::new(value, 0.0));
        for i in 0..self.n {
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
            lu.solve_mut(&mut DVectorViewMut::from_slice(rhs, self.n));
        }
    }

    fn solve_complex(&mut self, rhs: &mut [Complex<f64>]) {
        if let Some(lu) = &self.complex {
            lu.solve_mut(&mut DVectorViewMut::from_slice(rhs, self.n));
        }
    }
}
