//! The number types the evaluator runs on: `f64` for values, and num-dual's
//! forward-mode dual numbers for gradients (`DualVec`) and Hessians
//! (`Dual2Vec`), with any number of directions.
//!
//! Every math rule in [`crate::laws`] is written once, generic over
//! [`Number`], and branches on the real part.

use nalgebra::allocator::Allocator;
use nalgebra::{DMatrix, DVector, DefaultAllocator, Dim, OMatrix, U1};
use num_dual::{Derivative, Dual2Vec, DualNum, DualVec};

/// A real number with optional derivative parts.
pub trait Number: DualNum<Primitive = f64> + nalgebra::RealField + Clone + 'static {
    /// The real part.
    fn value(&self) -> f64 {
        self.re()
    }

    /// `f(self)` for a scalar function `f` whose value at `self.value()` is
    /// `f0` and whose first two derivatives there `derivatives` gives: the
    /// chain rule, with no arithmetic on derivative parts that are absent
    /// (and `derivatives` not even called for a plain `f64`).
    fn chain(&self, f0: f64, derivatives: impl FnOnce() -> (f64, f64)) -> Self;

    /// `f(self, other)` for a scalar function of two arguments whose value
    /// is `f0`, whose first partial derivatives `first` gives as `[f_a,
    /// f_b]` and whose second ones `second` gives as `[f_aa, f_ab, f_bb]`
    /// (`a` is `self`, `b` is `other`); each is called only where a
    /// derivative of that order is carried.
    fn chain2(
        &self,
        other: &Self,
        f0: f64,
        first: impl FnOnce() -> [f64; 2],
        second: impl FnOnce() -> [f64; 3],
    ) -> Self;

    /// Whether the number carries no derivative part (a constant).
    fn is_constant(&self) -> bool;

    /// Whether the value and every derivative part are finite.
    fn is_all_finite(&self) -> bool;
}

impl Number for f64 {
    fn chain(&self, f0: f64, _: impl FnOnce() -> (f64, f64)) -> Self {
        f0
    }

    fn chain2(
        &self,
        _: &Self,
        f0: f64,
        _: impl FnOnce() -> [f64; 2],
        _: impl FnOnce() -> [f64; 3],
    ) -> Self {
        f0
    }

    fn is_constant(&self) -> bool {
        true
    }

    fn is_all_finite(&self) -> bool {
        self.is_finite()
    }
}

/// `derivative * factor`, where a zero entry stays zero even if `factor` is
/// infinite: a direction in which the argument does not move contributes
/// nothing, however steep the function (no `0 * inf = NaN`).
fn times<R: Dim, C: Dim>(derivative: &Derivative<f64, R, C>, factor: f64) -> Derivative<f64, R, C>
where
    DefaultAllocator: Allocator<R, C>,
{
    if factor.is_finite() {
        return derivative * factor;
    }
    Derivative::new(
        derivative
            .0
            .as_ref()
            .map(|matrix| matrix.map(|entry| if entry == 0.0 { 0.0 } else { entry * factor })),
    )
}

/// `factor * a^T b` (a Hessian term of the chain rule) formed as
/// `(factor * a)^T b`, so that a zero `factor` contributes nothing even
/// where `a^T b` would overflow (a ramp of width 1e-200 at its inflection),
/// and a huge `factor` meets a tiny `a` before `b`. An infinite `factor`
/// keeps the entries of `a^T b` that are zero at zero.
fn outer<D: Dim>(
    a: &Derivative<f64, U1, D>,
    b: &Derivative<f64, U1, D>,
    factor: f64,
) -> Derivative<f64, D, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
{
    if factor == 0.0 {
        Derivative::none()
    } else if factor.is_finite() {
        (a * factor).tr_mul(b)
    } else {
        times(&a.tr_mul(b), factor)
    }
}

fn all_finite<R: Dim, C: Dim>(derivative: &Derivative<f64, R, C>) -> bool
where
    DefaultAllocator: Allocator<R, C>,
{
    derivative
        .0
        .as_ref()
        .is_none_or(|matrix| matrix.iter().all(|entry| entry.is_finite()))
}

impl<D: Dim> Number for DualVec<f64, D>
where
    DefaultAllocator: Allocator<D>,
    <DefaultAllocator as Allocator<D>>::Buffer<f64>: Send + Sync,
{
    fn chain(&self, f0: f64, derivatives: impl FnOnce() -> (f64, f64)) -> Self {
        if self.eps.0.is_none() {
            return DualVec::from_re(f0);
        }
        let (f1, _) = derivatives();
        DualVec::new(f0, times(&self.eps, f1))
    }

    fn chain2(
        &self,
        other: &Self,
        f0: f64,
        first: impl FnOnce() -> [f64; 2],
        _: impl FnOnce() -> [f64; 3],
    ) -> Self {
        if self.is_constant() && other.is_constant() {
            return DualVec::from_re(f0);
        }
        let [fa, fb] = first();
        DualVec::new(f0, times(&self.eps, fa) + times(&other.eps, fb))
    }

    fn is_constant(&self) -> bool {
        self.eps.0.is_none()
    }

    fn is_all_finite(&self) -> bool {
        self.re.is_finite() && all_finite(&self.eps)
    }
}

impl<D: Dim> Number for Dual2Vec<f64, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
    <DefaultAllocator as Allocator<U1, D>>::Buffer<f64>: Send + Sync,
    <DefaultAllocator as Allocator<D, D>>::Buffer<f64>: Send + Sync,
{
    fn chain(&self, f0: f64, derivatives: impl FnOnce() -> (f64, f64)) -> Self {
        if self.is_constant() {
            return Dual2Vec::from_re(f0);
        }
        let (f1, f2) = derivatives();
        let gradient = times(&self.v1, f1);
        let hessian = times(&self.v2, f1) + outer(&self.v1, &self.v1, f2);
        Dual2Vec::new(f0, gradient, hessian)
    }

    fn chain2(
        &self,
        other: &Self,
        f0: f64,
        first: impl FnOnce() -> [f64; 2],
        second: impl FnOnce() -> [f64; 3],
    ) -> Self {
        if self.is_constant() && other.is_constant() {
            return Dual2Vec::from_re(f0);
        }
        let [fa, fb] = first();
        let [faa, fab, fbb] = second();
        let (a, b) = (&self.v1, &other.v1);
        let gradient = times(a, fa) + times(b, fb);
        let hessian = times(&self.v2, fa)
            + times(&other.v2, fb)
            + outer(a, a, faa)
            + outer(a, b, fab)
            + outer(b, a, fab)
            + outer(b, b, fbb);
        Dual2Vec::new(f0, gradient, hessian)
    }

    fn is_constant(&self) -> bool {
        self.v1.0.is_none() && self.v2.0.is_none()
    }

    fn is_all_finite(&self) -> bool {
        self.re.is_finite() && all_finite(&self.v1) && all_finite(&self.v2)
    }
}

/// A number type that carries derivatives in `count` directions: how to seed
/// an input and how to read the result.
pub trait Directional: Number {
    /// The highest order of derivative carried (1 or 2).
    const ORDER: usize;

    /// An input with value `value` that is derivative direction `direction`
    /// of `count`.
    fn variable(value: f64, direction: usize, count: usize) -> Self;

    /// The gradient (zeros where no derivative part is present).
    fn gradient(&self, count: usize) -> DVector<f64>;

    /// The Hessian, for second-order numbers.
    fn hessian(&self, count: usize) -> Option<DMatrix<f64>>;
}

/// Entry `index` of the unit vector of `direction`. Writing the seed whole,
/// entry by entry, rather than storing a 1 at a varying index of a zeroed
/// vector, keeps the processor from reloading a value it has not finished
/// storing (a failed store-to-load forward, a fifth of a Hessian's time).
#[inline]
fn unit(index: usize, direction: usize) -> f64 {
    if index == direction { 1.0 } else { 0.0 }
}

impl<D: Dim> Directional for DualVec<f64, D>
where
    DefaultAllocator: Allocator<D>,
    <DefaultAllocator as Allocator<D>>::Buffer<f64>: Send + Sync,
{
    const ORDER: usize = 1;

    fn variable(value: f64, direction: usize, count: usize) -> Self {
        let seed =
            OMatrix::from_fn_generic(D::from_usize(count), U1, |row, _| unit(row, direction));
        DualVec::new(value, Derivative::some(seed))
    }

    fn gradient(&self, count: usize) -> DVector<f64> {
        match &self.eps.0 {
            Some(eps) => DVector::from_iterator(count, eps.iter().copied()),
            None => DVector::zeros(count),
        }
    }

    fn hessian(&self, _: usize) -> Option<DMatrix<f64>> {
        None
    }
}

impl<D: Dim> Directional for Dual2Vec<f64, D>
where
    DefaultAllocator: Allocator<U1, D> + Allocator<D, D>,
    <DefaultAllocator as Allocator<U1, D>>::Buffer<f64>: Send + Sync,
    <DefaultAllocator as Allocator<D, D>>::Buffer<f64>: Send + Sync,
{
    const ORDER: usize = 2;

    fn variable(value: f64, direction: usize, count: usize) -> Self {
        let seed = OMatrix::from_fn_generic(U1, D::from_usize(count), |_, column| {
            unit(column, direction)
        });
        Dual2Vec::new(value, Derivative::some(seed), Derivative::none())
    }

    fn gradient(&self, count: usize) -> DVector<f64> {
        match &self.v1.0 {
            Some(v1) => DVector::from_iterator(count, v1.iter().copied()),
            None => DVector::zeros(count),
        }
    }

    fn hessian(&self, count: usize) -> Option<DMatrix<f64>> {
        Some(match &self.v2.0 {
            Some(v2) => DMatrix::from_iterator(count, count, v2.iter().copied()),
            None => DMatrix::zeros(count, count),
        })
    }
}
