//! One call of the BISTOP utility per IORD against a plain Rust transcription
//! of the manual's formula and its hand-derived derivatives.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};

const X1: f64 = -10.0;
const X2: f64 = 10.0;
const K: f64 = 1e5;
const E: f64 = 2.2;
const CMAX: f64 = 100.0;
const D: f64 = 0.1;

/// The manual's formula written out (upper stop only, as the point is there):
/// `min(-k (x - x2)^e - STEP(x, x2, 0, x2 + d, cmax) x', 0)` and its partials.
fn transcription(x: f64, v: f64, iord: i32) -> [f64; 3] {
    if x <= X2 {
        return [0.0; 3];
    }
    let u = ((x - X2) / D).min(1.0);
    let c = CMAX * u * u * (3.0 - 2.0 * u);
    let dc = if u < 1.0 {
        CMAX * 6.0 * u * (1.0 - u) / D
    } else {
        0.0
    };
    let ddc = if u < 1.0 {
        CMAX * 6.0 * (1.0 - 2.0 * u) / (D * D)
    } else {
        0.0
    };
    let p = x - X2;
    let force = -K * p.powf(E) - c * v;
    if force >= 0.0 {
        return [0.0; 3];
    }
    match iord {
        0 => [force, 0.0, 0.0],
        1 => [-K * E * p.powf(E - 1.0) - dc * v, -c, 0.0],
        _ => [-K * E * (E - 1.0) * p.powf(E - 2.0) - ddc * v, -dc, 0.0],
    }
}

fn utility(c: &mut Criterion) {
    let mut group = c.benchmark_group("utility");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for iord in 0..=2 {
        group.bench_function(format!("iord {iord}: plain Rust transcription"), |b| {
            b.iter(|| transcription(black_box(10.05), black_box(0.7), iord))
        });
        group.bench_function(format!("iord {iord}: mbexpr::utility::bistop"), |b| {
            b.iter(|| {
                mbexpr::utility::bistop(
                    black_box(10.05),
                    black_box(0.7),
                    X1,
                    X2,
                    K,
                    E,
                    CMAX,
                    D,
                    iord,
                )
                .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, utility);
criterion_main!(benches);
