//! Implicit DIFFs (`DIFF/id, IMPLICIT, FUNCTION = F(DIF1(id), ...)`): the
//! rate is the root of the FUNCTION, found with the motion at every state.
//! Checked against a quadrature of the root worked out here (a nonlinear
//! residual), and against the same lag written as an explicit DIFF, with
//! the residual scaled by factors drawn at random.

use mbexpr::model::{self, FileKind};

use super::joints::method;
use super::simulate::{run, settings};

/// The root `z` of `z³ + z = c` by Newton's iterations (one root: the
/// left side increases).
fn cubic_root(c: f64) -> f64 {
    let mut z = c / 2.0;
    for _ in 0..60 {
        z -= (z * z * z + z - c) / (3.0 * z * z + 1.0);
    }
    z
}

/// `∫₀ᵗ cubic_root(cos s) ds` by Simpson's rule on 20 000 intervals.
fn cubic_root_integral(end: f64) -> f64 {
    let intervals = 20_000;
    let h = end / f64::from(intervals);
    let sum: f64 = (0..=intervals)
        .map(|index| {
            let weight = match index {
                0 => 1.0,
                i if i == intervals => 1.0,
                i if i % 2 == 1 => 4.0,
                _ => 2.0,
            };
            weight * cubic_root((f64::from(index) * h).cos())
        })
        .sum();
    sum * h / 3.0
}

/// `DIF1(1)³ + DIF1(1) = cos t`: the state against the quadrature of the
/// root at each row, and `DIF1(1)`'s column against the root itself, with
/// both methods.
#[test]
fn a_nonlinear_residual_gives_its_root_as_the_rate() {
    let text = "implicit cubic
DIFF/1, IC = 0, 0.5, IMPLICIT, FUNCTION = DIF1(1)**3 + DIF1(1) - COS(TIME)
VARIABLE/2, FUNCTION = DIF1(1)
";
    for name in ["radau", "dop853"] {
        let mut run_settings = settings(3.0, 6, 1e-9);
        run_settings.method = method(name);
        let run = run(text, &run_settings).expect("runs");
        for row in &run.rows {
            let (time, state, rate) = (row[0], row[1], row[2]);
            let expected = cubic_root_integral(time);
            assert!(
                (state - expected).abs() < 1e-8,
                "{name} at t = {time}: {state} against {expected}"
            );
            let root = cubic_root(time.cos());
            assert!(
                (rate - root).abs() < 1e-11,
                "{name} at t = {time}: DIF1 {rate} against {root}"
            );
        }
    }
}

/// A part on a spring whose force reads a lag of its stretch, the lag an
/// implicit DIFF with its residual scaled by `scale`, or the explicit DIFF
/// of the same equation.
fn lagged_spring(lag: &str) -> String {
    format!(
        "lagged spring
PART/1, GROUND
MARKER/10, PART = 1, QP = 0, 0, -1
PART/2, MASS = 2, CM = 20, IP = 1, 1, 1
MARKER/20, PART = 2, QP = 0, 0, 1
SFORCE/1, TRANSLATIONAL, I = 20, J = 10, FUNCTION = -100*(DIF(1) - 1.5) - 20*VR(20, 10)
{lag}
VARIABLE/3, FUNCTION = DIF1(1)
"
    )
}

/// The lag `0.05 y' + y = DM` as an implicit DIFF scaled by factors from
/// 1e-6 to 1e2 (drawn from a fixed seed) follows the explicit DIFF to the
/// tolerance, with both methods: the scale changes neither the root nor
/// the steps' error.
#[test]
fn an_implicit_lag_follows_its_explicit_form_whatever_its_scale() {
    let explicit = lagged_spring("DIFF/1, IC = 2, FUNCTION = (DM(20, 10) - DIF(1))/0.05");
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    for name in ["radau", "dop853"] {
        let mut run_settings = settings(2.0, 8, 1e-8);
        run_settings.method = method(name);
        let reference = run(&explicit, &run_settings).expect("the explicit form runs");
        for _ in 0..3 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let scale = 10f64.powf((seed % 8001) as f64 / 1000.0 - 6.0);
            let implicit = lagged_spring(&format!(
                "DIFF/1, IC = 2, IMPLICIT, FUNCTION = {scale:e}*(0.05*DIF1(1) + DIF(1) - DM(20, 10))"
            ));
            let lagged = run(&implicit, &run_settings).expect("the implicit form runs");
            for (row, expected) in lagged.rows.iter().zip(&reference.rows) {
                for (value, wanted) in row.iter().zip(expected) {
                    assert!(
                        (value - wanted).abs() < 1e-5 * (1.0 + wanted.abs()),
                        "{name}, scale {scale:e}, t = {}: {row:?} against {expected:?}",
                        row[0]
                    );
                }
            }
        }
    }
}

/// Outside a run (`eval`, `check`), `DIF1(id)` of an implicit DIFF is the
/// IC's second value, and of an explicit one its FUNCTION at the state.
#[test]
fn outside_a_run_an_implicit_rate_is_the_second_initial_value() {
    let text = "rates at the start
DIFF/1, IC = 2, 0.7, IMPLICIT, FUNCTION = DIF1(1) + DIF(1)
DIFF/2, IC = 3, FUNCTION = -2*DIF(2)
VARIABLE/3, FUNCTION = DIF1(1) + 10*DIF1(2)
";
    let dataset = model::read(text, FileKind::Adm);
    let report = model::check_model(text, &dataset);
    let scene = model::initial_scene(&dataset, &report).expect("the scene builds");
    let found = report
        .expressions
        .iter()
        .find(|found| dataset.statements[found.statement].label() == "VARIABLE/3")
        .expect("VARIABLE/3 is found");
    let checked = found.checked.as_ref().expect("it checks");
    let inputs = scene.input_names();
    let program = mbexpr::compile_in_scene(checked, &inputs, &scene).expect("it compiles");
    let values = scene
        .values(program.inputs())
        .expect("the scene gives every input");
    let value = program
        .evaluate(&values, &[], mbexpr::Order::Value)
        .expect("it evaluates");
    assert_eq!(value.value, 0.7 - 60.0);
}
