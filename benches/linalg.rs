//! The dense and the sparse LU of Radau5's iteration matrices side by side
//! (issue 24 item 3): one factorisation of both matrices (`σ I − J`, real
//! and complex) on the pattern of the stack of N balls of
//! `scripts/stack_models.py` (a body's 7 position and orientation rows read
//! its own 13 states, its 6 velocity rows its own and its two neighbours'),
//! for N from 2 to 128, the sparse LU with and without those 7 rows a body
//! eliminated first (`Pattern::with_eliminated`). Where the sparse one
//! becomes the faster is the crossover `SPARSE_FROM` in `integrate::linalg`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use mbexpr::integrate::linalg::{DenseLu, Factorisation, Jacobian, Pattern, SparseLu};
use nalgebra::{Complex, DMatrix};

/// States of one body.
const BODY: usize = 13;

/// A body's position and orientation states, whose rates read only its own.
const KINEMATIC: usize = 7;

/// The stack's pattern for `bodies` bodies.
fn stack_pattern(bodies: usize) -> Pattern {
    let n = BODY * bodies;
    let entries = (0..bodies).flat_map(move |body| {
        (0..BODY).flat_map(move |row| {
            let read = if row < KINEMATIC {
                body..body + 1
            } else {
                body.saturating_sub(1)..(body + 2).min(bodies)
            };
            read.flat_map(move |other| {
                (0..BODY).map(move |column| (BODY * body + row, BODY * other + column))
            })
        })
    });
    Pattern::new(n, entries)
}

/// Values in (-1, 1) from a fixed sequence (no randomness between runs).
fn values(count: usize) -> Vec<f64> {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    (0..count)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

fn factorise(c: &mut Criterion) {
    let mut group = c.benchmark_group("factorise");
    group
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(800))
        .sample_size(20);
    let (real, complex) = (20.0, Complex::new(18.0, 10.0));
    for bodies in [2, 3, 4, 5, 6, 8, 12, 16, 32, 128] {
        let pattern = std::rc::Rc::new(stack_pattern(bodies));
        let n = pattern.dimension();
        let sparse = Jacobian::Sparse {
            values: values(pattern.len()),
            pattern: pattern.clone(),
        };
        let mut matrix = DMatrix::zeros(n, n);
        for (entry, value) in pattern.entries().zip(sparse.values()) {
            matrix[entry] = *value;
        }
        let dense = Jacobian::Dense(matrix);
        let mut sparse_lu = SparseLu::new(&pattern, n);
        group.bench_with_input(BenchmarkId::new("sparse", n), &sparse, |b, jacobian| {
            b.iter(|| black_box(sparse_lu.factorise(jacobian, real, complex)));
        });
        let kinematic = (0..bodies).map(|body| BODY * body..BODY * body + KINEMATIC);
        let eliminated = pattern
            .as_ref()
            .clone()
            .with_eliminated(kinematic.collect());
        let mut eliminated_lu = SparseLu::new(&eliminated, n);
        group.bench_with_input(BenchmarkId::new("eliminated", n), &sparse, |b, jacobian| {
            b.iter(|| black_box(eliminated_lu.factorise(jacobian, real, complex)));
        });
        if bodies <= 32 {
            let mut dense_lu = DenseLu::new(n, n);
            group.bench_with_input(BenchmarkId::new("dense", n), &dense, |b, jacobian| {
                b.iter(|| black_box(dense_lu.factorise(jacobian, real, complex)));
            });
        }
    }
    group.finish();
}

criterion_group!(benches, factorise);
criterion_main!(benches);
