//! The simulation study's five scenes (issue 15 item 9): `mbexpr::simulate`
//! from each scene's text (read, check, compile, run) against the same
//! equations written by hand in Rust (`hand/mod.rs`: hand-coded right-hand
//! side, Jacobian and switching functions, its own event driver), both
//! driven by the same integrators, at rtol 1e-6 and 1e-9 (atol = rtol *
//! 1e-3), 200 output times.
//!
//! DOP853 on A4 is left out: the stiff stop holds the explicit method to
//! steps near 1e-6 s, about 1.5 million of them, seconds per run.
//! `scripts/work_precision.sh` times it once per tolerance instead.

mod hand;

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use mbexpr::integrate::Method;
use mbexpr::model::{self, FileKind};
use mbexpr::simulate::{self, Settings, Simulation};

/// Output steps: 200 rows.
const STEPS: usize = 199;

/// The scene's dataset read, checked, compiled and run by mbexpr; the sum
/// of its rows' x, so that nothing is left unused.
fn mbexpr_run(text: &str, settings: &Settings) -> f64 {
    let dataset = model::read(text, FileKind::Adm);
    let report = model::check_model(text, &dataset);
    let model = simulate::from_dataset(&dataset, &report).expect("the scene reads");
    let simulation = Simulation::new(&model).expect("the scene compiles");
    let mut sum = 0.0;
    simulation
        .run(settings, |_time, row| {
            sum += row[0];
            true
        })
        .expect("the scene runs");
    sum
}

/// The hand-written program, its rows summed the same way.
fn hand_run(scene: &hand::Scene, method: Method, rtol: f64) -> f64 {
    let mut sum = 0.0;
    hand::simulate(scene, method, rtol, rtol * 1e-3, STEPS, |_time, x, _v| {
        sum += x;
    })
    .expect("the scene runs");
    sum
}

fn scenes(c: &mut Criterion) {
    let mut group = c.benchmark_group("simulate");
    group
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
        .sample_size(10);
    for scene in &hand::SCENES {
        let path = format!(
            "{}/examples/simulate/{}.adm",
            env!("CARGO_MANIFEST_DIR"),
            scene.name
        );
        let text = std::fs::read_to_string(&path).expect("the scene's dataset");
        for method in [Method::Radau5, Method::Dop853] {
            if method == Method::Dop853 && scene.name == "a4_dropped_ball" {
                continue;
            }
            for rtol in [1e-6, 1e-9] {
                let settings = Settings {
                    method,
                    end: scene.end,
                    steps: STEPS,
                    rtol,
                    atol: rtol * 1e-3,
                    ..Settings::default()
                };
                let name = format!("{} {method} {rtol:e}", scene.name);
                group.bench_function(format!("{name}: hand-written"), |b| {
                    b.iter(|| hand_run(black_box(scene), method, rtol))
                });
                group.bench_function(format!("{name}: mbexpr from text"), |b| {
                    b.iter(|| mbexpr_run(black_box(&text), &settings))
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, scenes);
criterion_main!(benches);
