//! Control elements: TFSISO and LSE (with their ARRAYs and MATRIXes) as
//! states of the run, against closed forms and against the same system
//! written as DIFFs, and what they refuse at their place.

use super::simulate::{model_of, run, settings};

/// `4 / (s^2 + 2 s + 4)` driven by a unit step: `wn = 2`, `zeta = 1/2`,
/// `y = 1 - e^-t (cos(√3 t) + sin(√3 t)/√3)`; the output read by ARYVAL
/// of the Y array in a VARIABLE, and again through a second transfer
/// function `(1 + s) / (1 + s)` that passes it through (a proper one: its
/// numerator of the denominator's degree).
#[test]
fn a_transfer_function_follows_its_step_response() {
    let text = "transfer functions
PART/1, GROUND
VARIABLE/1, FUNCTION = 1
ARRAY/1, U, VARIABLES = 1
ARRAY/2, X, SIZE = 2
ARRAY/3, Y, SIZE = 1
TFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 4, DENOMINATOR = 4, 2, 1
VARIABLE/2, FUNCTION = ARYVAL(3, 1)
ARRAY/4, U, VARIABLES = 2
ARRAY/5, X, SIZE = 1
ARRAY/6, Y, SIZE = 1
TFSISO/2, U = 4, X = 5, Y = 6, NUMERATOR = 1, 1, DENOMINATOR = 1, 1
VARIABLE/3, FUNCTION = ARYVAL(6, 1)
";
    let run = run(text, &settings(6.0, 60, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
    let root = 3f64.sqrt();
    for row in &run.rows {
        let t = row[0];
        let exact = 1.0 - (-t).exp() * ((root * t).cos() + (root * t).sin() / root);
        // time, ARYVAL(2, 1), ARYVAL(2, 2), ARYVAL(5, 1), VARIABLE/1..3
        assert!(
            (row[5] - exact).abs() < 1e-8,
            "{} against {exact} at {t}",
            row[5]
        );
        assert!(
            (row[6] - exact).abs() < 1e-8,
            "{} against {exact} at {t}",
            row[6]
        );
    }
}

/// `x' = A x + B u`, `y = C x + D u` with `A = [0 1; -1 0]`, `B = [0; 1]`,
/// `u = 1`, `x(0) = (2, 0)`: `x1 = 1 + cos t`, `x2 = -sin t`; `C = [1 0;
/// 0 2]`, `D = [3; 0]`: `y1 = 4 + cos t`, `y2 = -2 sin t`. A by rows, B
/// sparse, C by columns (the default order).
#[test]
fn state_equations_follow_their_closed_form() {
    let text = "state equations
PART/1, GROUND
VARIABLE/1, FUNCTION = 1
ARRAY/1, U, VARIABLES = 1
ARRAY/2, X, SIZE = 2
ARRAY/3, Y, SIZE = 2
ARRAY/4, IC, NUMBERS = 2, 0
MATRIX/1, FULL = RORDER, ROWS = 2, COLUMNS = 2, VALUES = 0, 1, -1, 0
MATRIX/2, SPARSE, ROWS = 2, COLUMNS = 1, I = 2, J = 1, VALUES = 1
MATRIX/3, FULL = CORDER, ROWS = 2, COLUMNS = 2, VALUES = 1, 0, 0, 2
MATRIX/4, FULL = RORDER, ROWS = 2, COLUMNS = 1, VALUES = 3, 0
LSE/1, X = 2, U = 1, Y = 3, A = 1, B = 2, C = 3, D = 4, IC = 4
VARIABLE/2, FUNCTION = ARYVAL(3, 1)
VARIABLE/3, FUNCTION = ARYVAL(3, 2)
";
    let run = run(text, &settings(7.0, 70, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
    for row in &run.rows {
        let t = row[0];
        let expected = [1.0 + t.cos(), -t.sin(), 1.0, 4.0 + t.cos(), -2.0 * t.sin()];
        for (got, want) in row[1..].iter().zip(expected) {
            assert!(
                (got - want).abs() < 1e-8,
                "{:?} against {expected:?} at {t}",
                &row[1..]
            );
        }
    }
}

/// A slider held by a controller, as Adams Controls writes one: its place
/// through a first-order lag `1 / (1 + 0.1 s)` (a TFSISO) into a PD force;
/// the same loop with the lag as a DIFF (`y' = (z - y) / 0.1`) gives the
/// same motion, with both methods.
#[test]
fn a_controlled_slider_moves_as_its_diff_form() {
    let controlled = |lag: &str, reading: &str| {
        format!(
            "controlled slider
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 3, IP = 1, 1, 1, QG = 0, 0, 1
MARKER/3, PART = 2
JOINT/1, TRANSLATIONAL, I = 3, J = 1
VARIABLE/1, FUNCTION = DZ(3, 1)
{lag}
SFORCE/1, TRANSLATIONAL, I = 3, J = 1, ACTIONONLY, FUNCTION = -40 * {reading} - 4 * VZ(3, 1)
"
        )
    };
    let tfsiso = controlled(
        "ARRAY/1, U, VARIABLES = 1\nARRAY/2, X, SIZE = 1\nARRAY/3, Y, SIZE = 1\nTFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 0.1",
        "ARYVAL(3, 1)",
    );
    let diff = controlled(
        "DIFF/1, IC = 0, FUNCTION = (VARVAL(1) - DIF(1)) / 0.1",
        "DIF(1)",
    );
    for method in [
        mbexpr::integrate::Method::Radau5,
        mbexpr::integrate::Method::Dop853,
    ] {
        let settings = mbexpr::simulate::Settings {
            method,
            ..settings(3.0, 30, 1e-10)
        };
        let by_tfsiso = run(&tfsiso, &settings).unwrap_or_else(|error| panic!("{error}"));
        let by_diff = run(&diff, &settings).unwrap_or_else(|error| panic!("{error}"));
        let moved = by_tfsiso.rows.last().unwrap()[4];
        assert!(moved < 0.9, "the slider should have moved: z = {moved}");
        for (a, b) in by_tfsiso.rows.iter().zip(&by_diff.rows) {
            // The same columns: the time, the lag's state (the TFSISO's is
            // the output over 10, its numerator over the leading 0.1),
            // then the part and the VARIABLE.
            assert!((a[1] * 10.0 - b[1]).abs() < 1e-8, "{a:?}\n{b:?}");
            for (x, y) in a.iter().zip(b).skip(2) {
                assert!((x - y).abs() < 1e-8, "{a:?}\n{b:?}");
            }
        }
    }
}

/// What the control elements refuse, each at its statement.
#[test]
fn what_control_elements_refuse() {
    let base = "refusals\nPART/1, GROUND\nVARIABLE/1, FUNCTION = TIME\nARRAY/1, U, VARIABLES = 1\nARRAY/2, X, SIZE = 2\nARRAY/3, Y, SIZE = 1\nARRAY/4, IC, NUMBERS = 1\nMATRIX/1, FULL = RORDER, ROWS = 2, COLUMNS = 3, VALUES = 1, 2, 3, 4, 5, 6\nMATRIX/2, FILE = a.mtx, NAME = A\n";
    let cases = [
        "TFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 1, 2, 3, 4, DENOMINATOR = 1, 1, 1",
        "TFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 1, 0",
        "TFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 1",
        "TFSISO/1, U = 1, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 1, 1",
        "TFSISO/1, U = 1, X = 3, Y = 2, NUMERATOR = 1, DENOMINATOR = 1, 1, 1",
        "TFSISO/1, U = 1, X = 9, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 1, 1",
        "TFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 1, 1, IC = 4",
        "LSE/1, X = 2, A = 1",
        "LSE/1, X = 2, A = 2",
        "LSE/1, X = 2, A = 7",
        "TFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 1, 1, 1, DENOMINATOR = 1, 1, 1\nVARIABLE/2, FUNCTION = ARYVAL(3, 2) + ARYVAL(2, 3)",
        "TFSISO/1, U = 5, X = 2, Y = 3, NUMERATOR = 1, 1, 1, DENOMINATOR = 1, 1, 1\nARRAY/5, U, VARIABLES = 2\nVARIABLE/2, FUNCTION = ARYVAL(3, 1)",
        "ARRAY/5, IC, SIZE = -1, NUMBERS = 1, 2",
        "ARRAY/5, IC, SIZE = 2.5, NUMBERS = 1, 2",
        "ARRAY/5, IC, SIZE = 1, NUMBERS = 1, 2, 3",
        "ARRAY/5, IC, SIZE = 4, NUMBERS = 1, 2, 3",
        "TFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 1, 1\nTFSISO/2, U = 1, X = 2, NUMERATOR = 1, DENOMINATOR = 1, 2, 1",
        "TFSISO/1, U = 1, X = 2, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 1, 1\nARRAY/5, X, SIZE = 2\nTFSISO/2, U = 1, X = 5, Y = 3, NUMERATOR = 1, DENOMINATOR = 1, 2, 1",
    ];
    let table: String = cases
        .iter()
        .map(|case| {
            let text = format!("{base}{case}\n");
            let outcome = match model_of(&text) {
                Err(error) => error,
                Ok(_) => match run(&text, &settings(1.0, 2, 1e-6)) {
                    Ok(_) => "runs".to_string(),
                    Err(error) => error,
                },
            };
            format!("{case}\n  => {}\n", outcome.trim_end())
        })
        .collect();
    insta::assert_snapshot!(table);
}

/// `examples/simulate/l_controlled_lift.adm`: a PI controller (a TFSISO
/// with a pure integrator) holds a 50 kg cage at its set point through a
/// sensor lag (another TFSISO); at rest the error is gone and the
/// integrator's state times its gain carries the weight, `m g`, which a
/// proportional controller alone could not.
#[test]
fn the_lift_example_settles_at_its_set_point() {
    let text = include_str!("../examples/simulate/l_controlled_lift.adm");
    let model = model_of(text).unwrap_or_else(|error| panic!("{error}"));
    let columns = mbexpr::simulate::columns(&model);
    let at = |name: &str| columns.iter().position(|column| column == name).unwrap();
    let run = run(text, &settings(10.0, 200, 1e-8)).unwrap_or_else(|error| panic!("{error}"));
    let last = run.rows.last().unwrap();
    assert!((last[at("PART/2.z")] - 1.0).abs() < 1e-6, "{last:?}");
    let carried = 4000.0 * last[at("TFSISO/1.x1")];
    assert!((carried - 50.0 * 9.80665).abs() < 1e-3, "{carried}");
    assert!((last[at("REQUEST/1.F4")] - 1.0).abs() < 1e-6, "{last:?}");
}

/// `--statics` with the lift of the example before its set point moves:
/// without STATIC_HOLD the controller's integrator is a state of the
/// equilibrium too, and comes to carry the weight with the cage at 0
/// (`4000 x = m g`); with STATIC_HOLD on the PI controller its state stays
/// at 0, and the proportional part alone carries the cage, which sags to
/// `z = -m g / 3000` (the lag, not held, settles on it: `x = 0.02 z`).
#[test]
fn static_hold_keeps_a_state_out_of_the_equilibrium() {
    let free = include_str!("../examples/simulate/l_controlled_lift.adm");
    let held = free.replace("DENOMINATOR = 0, 1\n", "DENOMINATOR = 0, 1, STATIC_HOLD\n");
    assert_ne!(free, held);
    let weight = 50.0 * 9.80665;
    let statics = mbexpr::simulate::Settings {
        statics: true,
        ..settings(0.2, 1, 1e-10)
    };
    for (text, sag, integral) in [
        (free, 0.0, weight / 4000.0),
        (held.as_str(), -weight / 3000.0, 0.0),
    ] {
        let model = model_of(text).unwrap_or_else(|error| panic!("{error}"));
        let columns = mbexpr::simulate::columns(&model);
        let at = |name: &str| columns.iter().position(|column| column == name).unwrap();
        let run = run(text, &statics).unwrap_or_else(|error| panic!("{error}"));
        let start = &run.rows[0];
        assert!((start[at("PART/2.z")] - sag).abs() < 1e-9, "{start:?}");
        assert!(
            (start[at("TFSISO/1.x1")] - integral).abs() < 1e-9,
            "{start:?}"
        );
        assert!(
            (start[at("TFSISO/2.x1")] - 0.02 * sag).abs() < 1e-9,
            "{start:?}"
        );
    }
}

/// The lift's sensor lag (`λ = −50`) is barely excited once the cage
/// moves, and DOP853 (alone or under Auto) steps over it near the edge of
/// its stability; its rows between the step ends, inside steps of 0.2 s,
/// were 2 000 × rtol off Radau5's (the lag's output 2.6e-3 at rtol 1e-6).
/// Every row of every method now meets a tight Radau5 run within a few
/// times rtol.
#[test]
fn the_lifts_rows_between_step_ends_meet_a_tight_run() {
    use mbexpr::integrate::Method;
    let text = include_str!("../examples/simulate/l_controlled_lift.adm");
    let with = |method, rtol| {
        let settings = mbexpr::simulate::Settings {
            method,
            ..settings(10.0, 1000, rtol)
        };
        run(text, &settings)
            .unwrap_or_else(|error| panic!("{error}"))
            .rows
    };
    let reference = with(Method::Radau5, 1e-11);
    let scales: Vec<f64> = (1..reference[0].len())
        .map(|column| {
            reference
                .iter()
                .map(|row| row[column].abs())
                .fold(1e-3, f64::max)
        })
        .collect();
    for method in [Method::Dop853, Method::Auto, Method::Radau5] {
        let rows = with(method, 1e-6);
        let worst = rows
            .iter()
            .zip(&reference)
            .flat_map(|(row, exact)| {
                scales
                    .iter()
                    .enumerate()
                    .map(move |(i, scale)| (row[i + 1] - exact[i + 1]).abs() / scale)
            })
            .fold(0.0, f64::max);
        assert!(worst < 5e-6, "{method}: {worst:.2e}");
    }
}
