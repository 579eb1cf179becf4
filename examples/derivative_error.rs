//! What the dual numbers buy: dF/dx and dF/dv of BISTOP at points in each
//! branch, by dual numbers and by central finite differences at steps from
//! 1e-2 to 1e-12, against the analytic derivatives of SPEC 3.3, with the
//! time each method takes per gradient.
//!
//! `cargo run --release --example derivative_error`

use std::hint::black_box;
use std::time::Instant;

use mbexpr::Order;
use num_dual::DualSVec64;

const TEXT: &str = "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)";
const X1: f64 = -10.0;
const X2: f64 = 10.0;
const K: f64 = 1e5;
const E: f64 = 2.2;
const CMAX: f64 = 100.0;
const D: f64 = 0.1;

/// The damping STEP of penetration `p` and its slope in `p`.
fn damping(p: f64) -> (f64, f64) {
    if p >= D {
        return (CMAX, 0.0);
    }
    let w = p / D;
    (
        CMAX * w * w * (3.0 - 2.0 * w),
        CMAX * 6.0 * w * (1.0 - w) / D,
    )
}

/// dF/dx and dF/dv from the table of SPEC 3.3 (zero where clamped or free).
fn analytic(x: f64, v: f64) -> (f64, f64) {
    if x < X1 {
        let p = X1 - x;
        let (c, dc_dp) = damping(p);
        if K * p.powf(E) - c * v <= 0.0 {
            return (0.0, 0.0);
        }
        // c(x) = c(p(x)), dp/dx = -1.
        (-K * E * p.powf(E - 1.0) + dc_dp * v, -c)
    } else if x > X2 {
        let p = x - X2;
        let (c, dc_dp) = damping(p);
        if -K * p.powf(E) - c * v >= 0.0 {
            return (0.0, 0.0);
        }
        (-K * E * p.powf(E - 1.0) - dc_dp * v, -c)
    } else {
        (0.0, 0.0)
    }
}

fn relative(got: f64, want: f64) -> f64 {
    (got - want).abs() / want.abs().max(1e-300)
}

fn main() {
    let checked = mbexpr::check(&mbexpr::parse(TEXT).expect("parses")).expect("checks");
    let program = mbexpr::compile(&checked, &["x", "v"]).expect("compiles");
    let points = [
        ("lower stop, beyond the ramp", -10.5, 0.7),
        ("lower stop, inside the ramp", -10.05, -0.7),
        ("upper stop, inside the ramp", 10.05, 0.7),
        ("upper stop, beyond the ramp", 10.5, 0.7),
        ("upper stop, ramp, slow separation", 10.05, -0.1),
    ];
    let repetitions = 200_000u32;
    println!("| branch | method | step | rel. error dF/dx | rel. error dF/dv | ns per gradient |");
    println!("|---|---|---|---|---|---|");
    for (branch, x, v) in points {
        let (want_x, want_v) = analytic(x, v);
        let mut evaluator = program.evaluator::<DualSVec64<2>>();
        let start = Instant::now();
        let mut gradient = [0.0; 2];
        for _ in 0..repetitions {
            let result = evaluator
                .derivatives(black_box(&[x, v]), &[0, 1])
                .expect("evaluates");
            let g = result.gradient.expect("a gradient");
            gradient = [g[0], g[1]];
        }
        let nanoseconds = start.elapsed().as_nanos() as f64 / f64::from(repetitions);
        println!(
            "| {branch} | dual numbers | — | {:.1e} | {:.1e} | {nanoseconds:.0} |",
            relative(gradient[0], want_x),
            relative(gradient[1], want_v)
        );
        for step in [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
            let mut values = program.evaluator::<f64>();
            let start = Instant::now();
            let mut gradient = [0.0; 2];
            for _ in 0..repetitions {
                let mut f = |x: f64, v: f64| values.value(black_box(&[x, v])).expect("evaluates");
                let dx = (f(x + step, v) - f(x - step, v)) / (2.0 * step);
                let dv = (f(x, v + step) - f(x, v - step)) / (2.0 * step);
                gradient = [dx, dv];
            }
            let nanoseconds = start.elapsed().as_nanos() as f64 / f64::from(repetitions);
            println!(
                "| {branch} | central differences | {step:.0e} | {:.1e} | {:.1e} | {nanoseconds:.0} |",
                relative(gradient[0], want_x),
                relative(gradient[1], want_v)
            );
        }
        // The duals agree with the analytic derivatives to rounding.
        let exact = program
            .evaluate(&[x, v], &[0, 1], Order::Gradient)
            .expect("evaluates");
        let exact = exact.gradient.expect("a gradient");
        assert!(relative(exact[0], want_x) < 1e-12 && relative(exact[1], want_v) < 1e-12);
    }
}
