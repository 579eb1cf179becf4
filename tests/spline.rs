//! `AKISPL` and `CUBSPL`: the fits' defining properties, their derivatives
//! against finite differences, and SPLINE statements of a dataset evaluated
//! in its initial configuration.

use mbexpr::laws::spline::{Method, Spline, SplineData};
use mbexpr::model::{self, FileKind};
use num_dual::Dual2SVec64;

const X: [f64; 7] = [0.0, 0.5, 1.5, 2.0, 3.5, 4.0, 6.0];
const Y: [f64; 7] = [1.0, 0.2, -0.4, 2.0, 2.5, 1.0, 0.0];

fn curve(x: &[f64], y: &[f64], linear: bool) -> SplineData {
    SplineData::new(x.to_vec(), vec![(0.0, y.to_vec())], linear).unwrap()
}

/// Value, first and second derivative of `spline` at `x` (order 0), read
/// from a second-order dual number.
fn jet(spline: &Spline, x: f64) -> [f64; 3] {
    let seeded = Dual2SVec64::<1>::from_re(x).derivative(0);
    let result = spline.at(&seeded, &Dual2SVec64::from_re(0.0), 0);
    [
        result.re,
        result.v1.unwrap_generic(nalgebra::U1, nalgebra::U1)[0],
        result.v2.unwrap_generic(nalgebra::U1, nalgebra::U1)[(0, 0)],
    ]
}

#[test]
fn both_fits_go_through_the_points_and_keep_a_line() {
    let line: Vec<f64> = X.iter().map(|x| 3.0 * x - 1.0).collect();
    for method in [Method::Akima, Method::Cubic] {
        let through = Spline::fit(&curve(&X, &Y, false), method);
        for (x, y) in X.iter().zip(Y) {
            assert_eq!(through.at(x, &0.0, 0), y, "{method:?} at {x}");
        }
        let straight = Spline::fit(&curve(&X, &line, false), method);
        for x in [-2.0, 0.3, 1.7, 5.9, 8.0] {
            let [value, slope, curvature] = jet(&straight, x);
            assert!((value - (3.0 * x - 1.0)).abs() < 1e-13, "{method:?} at {x}");
            assert!((slope - 3.0).abs() < 1e-13 && curvature.abs() < 1e-12);
        }
    }
}

#[test]
fn natural_spline_matches_its_exact_solution() {
    // y = x^2 at 0..4: the natural spline at 1.5, solved in exact fractions
    // (a full Gaussian elimination, not the tridiagonal sweep).
    let x = [0.0, 1.0, 2.0, 3.0, 4.0];
    let spline = Spline::fit(&curve(&x, &x.map(|x| x * x), false), Method::Cubic);
    let [value, slope, curvature] = jet(&spline, 1.5);
    assert!((value - 125.0 / 56.0).abs() < 1e-15);
    assert!((slope - 85.0 / 28.0).abs() < 1e-15);
    assert!((curvature - 15.0 / 7.0).abs() < 1e-14);
}

#[test]
fn akima_keeps_a_parabola_on_even_points() {
    let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    let y = x.map(|x| x * x);
    let spline = Spline::fit(&curve(&x, &y, false), Method::Akima);
    for at in [0.5, 1.25, 2.0, 3.75, 4.5] {
        let [value, slope, curvature] = jet(&spline, at);
        assert!((value - at * at).abs() < 1e-13);
        assert!((slope - 2.0 * at).abs() < 1e-13);
        assert!((curvature - 2.0).abs() < 1e-12);
    }
}

#[test]
fn continuity_at_the_points() {
    let gap = 1e-9;
    let cubic = Spline::fit(&curve(&X, &Y, false), Method::Cubic);
    let akima = Spline::fit(&curve(&X, &Y, false), Method::Akima);
    for &knot in &X[1..X.len() - 1] {
        let (left, right) = (jet(&cubic, knot - gap), jet(&cubic, knot));
        for order in 0..3 {
            assert!(
                (left[order] - right[order]).abs() < 1e-6,
                "CUBSPL order {order} at {knot}"
            );
        }
        let (left, right) = (jet(&akima, knot - gap), jet(&akima, knot));
        for order in 0..2 {
            assert!(
                (left[order] - right[order]).abs() < 1e-6,
                "AKISPL order {order} at {knot}"
            );
        }
    }
    // The natural spline is straight at both ends.
    assert_eq!(jet(&cubic, X[0])[2], 0.0);
    assert!(jet(&cubic, X[6])[2].abs() < 1e-12);
}

#[test]
fn derivatives_agree_with_finite_differences_and_the_orders() {
    let h = 1e-5;
    for method in [Method::Akima, Method::Cubic] {
        let spline = Spline::fit(&curve(&X, &Y, false), method);
        // Away from the points, where each piece is smooth.
        for x in [-0.7, 0.2, 1.1, 2.6, 3.8, 5.1, 7.3] {
            let [_, slope, curvature] = jet(&spline, x);
            let value = |x: f64| spline.at(&x, &0.0, 0);
            let central = (value(x + h) - value(x - h)) / (2.0 * h);
            let second = (value(x + h) - 2.0 * value(x) + value(x - h)) / (h * h);
            assert!((slope - central).abs() < 1e-7, "{method:?} slope at {x}");
            assert!(
                (curvature - second).abs() < 1e-3,
                "{method:?} curvature at {x}"
            );
            assert_eq!(spline.at(&x, &0.0, 1), slope);
            assert_eq!(spline.at(&x, &0.0, 2), curvature);
        }
    }
}

#[test]
fn linear_extrapolation_follows_the_end_tangents() {
    for method in [Method::Akima, Method::Cubic] {
        let spline = Spline::fit(&curve(&X, &Y, true), method);
        let [y0, s0, _] = jet(&spline, X[0]);
        let [y6, s6, _] = jet(&spline, X[6] - 1e-12);
        let [before, before_slope, before_curvature] = jet(&spline, -2.0);
        assert!((before - (y0 - 2.0 * s0)).abs() < 1e-12);
        assert_eq!((before_slope, before_curvature), (s0, 0.0));
        let [after, after_slope, _] = jet(&spline, 9.0);
        assert!((after - (y6 + 3.0 * s6)).abs() < 1e-9);
        assert!((after_slope - s6).abs() < 1e-9);
    }
}

#[test]
fn a_family_is_linear_in_z() {
    let family = SplineData::new(
        X.to_vec(),
        vec![(1.0, Y.to_vec()), (3.0, Y.map(|y| 2.0 * y + 1.0).to_vec())],
        false,
    )
    .unwrap();
    let spline = Spline::fit(&family, Method::Akima);
    let single = Spline::fit(&curve(&X, &Y, false), Method::Akima);
    for (x, z) in [(0.7, 1.0), (2.2, 2.0), (4.4, 2.5), (1.0, 4.0)] {
        let weight = (z - 1.0) / 2.0;
        let lower = single.at(&x, &0.0, 0);
        let expected = lower + weight * (lower + 1.0);
        assert!(
            (spline.at(&x, &z, 0) - expected).abs() < 1e-12,
            "at ({x}, {z})"
        );
    }
}

#[test]
fn bad_points_are_refused() {
    let cases = [
        SplineData::new(vec![0.0, 1.0, 2.0], vec![(0.0, vec![0.0; 3])], false),
        SplineData::new(vec![0.0, 1.0, 1.0, 2.0], vec![(0.0, vec![0.0; 4])], false),
        SplineData::new(vec![0.0, 1.0, 2.0, 3.0], vec![(0.0, vec![0.0; 5])], false),
        SplineData::new(
            vec![0.0, 1.0, 2.0, 3.0],
            vec![(1.0, vec![0.0; 4]), (1.0, vec![0.0; 4])],
            false,
        ),
        SplineData::new(
            vec![0.0, 1.0, 2.0, f64::NAN],
            vec![(0.0, vec![0.0; 4])],
            false,
        ),
        SplineData::new(vec![0.0, 1.0, 2.0, 3.0], vec![], false),
        SplineData::new(
            vec![0.0, 1e300, 2e300, 1e300],
            vec![(0.0, vec![0.0; 4])],
            false,
        ),
        SplineData::new(
            vec![0.0, 1.0, 2.0, 3.0],
            vec![(1e-300, vec![0.0; 4]), (-1e-300, vec![0.0; 4])],
            false,
        ),
    ];
    let messages: Vec<String> = cases
        .into_iter()
        .map(|case| case.unwrap_err().to_string())
        .collect();
    insta::assert_snapshot!(messages.join("\n"));
}

const SPLINE_MODEL: &str = "splines
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 3, QG = 1.5, 0, 0
MARKER/3, PART = 2
SPLINE/5
, X = 0, 1, 2, 3, 4
, Y = 0, 1, 4, 9, 16
SPLINE/6, LINEAR_EXTRAPOLATE
, X = 0, 1, 2, 3
, Y = 0, 0, 1, 2, 3
, Y = 1, 10, 11, 12, 13
VARIABLE/10, FUNCTION = AKISPL(DX(3, 1), 0, 5)
VARIABLE/11, FUNCTION = CUBSPL(DX(3, 1), 0, 5)
VARIABLE/12, FUNCTION = CUBSPL(DX(3, 1), 0, 5, 1)
VARIABLE/13, FUNCTION = CUBSPL(DX(3, 1), 0, 5, 2)
VARIABLE/14, FUNCTION = AKISPL(DX(3, 1), 0.5, 6) + AKISPL(5 + DX(3, 1), 0.5, 6)
VARIABLE/15, FUNCTION = AKISPL(1, 0, 5, 3)
VARIABLE/16, FUNCTION = CUBSPL(1, 0, 7)
END
";

/// Every expression of `text` at the initial configuration, with its
/// derivatives in `PART/2.x`, or its error.
fn model_table(text: &str) -> String {
    let dataset = model::read(text, FileKind::Adm);
    let report = model::check_model(text, &dataset);
    let scene = match model::initial_scene(&dataset, &report) {
        Ok(scene) => scene,
        Err(errors) => {
            let lines: Vec<String> = errors.iter().map(ToString::to_string).collect();
            return lines.join("\n");
        }
    };
    let mut inputs = scene.input_names();
    inputs.push("PART/2.x".to_string());
    let mut out = String::new();
    for found in &report.expressions {
        let label = dataset.statements[found.statement].label();
        let checked = found.checked.as_ref().expect("the expression checks");
        let row = mbexpr::compile_in_scene(checked, &inputs, &scene)
            .map_err(|errors| errors[0].to_string())
            .and_then(|program| {
                let values = scene.values(program.inputs()).map_err(|e| e.to_string())?;
                let direction = program
                    .input_index("PART/2.x")
                    .into_iter()
                    .collect::<Vec<_>>();
                program
                    .evaluate(&values, &direction, mbexpr::Order::Hessian)
                    .map_err(|error| error.to_string())
            });
        out += &match row {
            Ok(result) => format!(
                "{label}: {:.12} d {:?} dd {:?}\n",
                result.value,
                result.gradient.unwrap().as_slice(),
                result.hessian.unwrap().as_slice()
            ),
            Err(message) => format!("{label}: {message}\n"),
        };
    }
    out
}

#[test]
fn spline_statements_give_akispl_and_cubspl() {
    let bad = SPLINE_MODEL.replace("X = 0, 1, 2, 3\n", "X = 0, 2, 1, 3\n");
    insta::assert_snapshot!(model_table(SPLINE_MODEL) + "\n" + &model_table(&bad));
}

proptest::proptest! {
    #[test]
    fn random_splines_have_the_derivatives_of_their_values(
        steps in proptest::collection::vec(0.1f64..2.0, 4..12),
        heights in proptest::collection::vec(-5.0f64..5.0, 12),
        fraction in 0.05f64..0.95,
        piece in 0usize..12,
        akima in proptest::bool::ANY,
        linear in proptest::bool::ANY,
    ) {
        let x: Vec<f64> = steps.iter().scan(0.0, |at, step| { *at += step; Some(*at) }).collect();
        let y = heights[..x.len()].to_vec();
        let method = if akima { Method::Akima } else { Method::Cubic };
        let spline = Spline::fit(&curve(&x, &y, linear), method);
        // A point inside a piece, or beyond either end.
        let at = match piece % (x.len() + 1) {
            0 => x[0] - 3.0 * fraction,
            p if p == x.len() => x[x.len() - 1] + 3.0 * fraction,
            p => x[p - 1] + fraction * (x[p] - x[p - 1]),
        };
        let h = 1e-6 * (1.0 + at.abs());
        let value = |x: f64| spline.at(&x, &0.0, 0);
        let [exact, slope, curvature] = jet(&spline, at);
        proptest::prop_assert!(exact.is_finite() && slope.is_finite() && curvature.is_finite());
        let central = (value(at + h) - value(at - h)) / (2.0 * h);
        let scale = 1.0 + slope.abs() + exact.abs();
        proptest::prop_assert!((slope - central).abs() < 1e-6 * scale, "{slope} vs {central}");
        let slope_at = |x: f64| spline.at(&x, &0.0, 1);
        let second = (slope_at(at + h) - slope_at(at - h)) / (2.0 * h);
        proptest::prop_assert!((curvature - second).abs() < 1e-5 * (1.0 + curvature.abs() + scale), "{curvature} vs {second}");
    }
}
