//! The special points SPEC 3.3 and 5 decide, each pinned.

use mbexpr::{Evaluation, Order};

/// Value, gradient and Hessian of `text` in its inputs `names` at `values`
/// (every input a direction).
fn at(text: &str, names: &[&str], values: &[f64]) -> Result<Evaluation, String> {
    let checked = mbexpr::check(&mbexpr::parse(text).map_err(|e| e.to_string())?)
        .map_err(|e| e.to_string())?;
    let program = mbexpr::compile(&checked, names).map_err(|e| e.to_string())?;
    let wrt: Vec<usize> = (0..names.len()).collect();
    program
        .evaluate(values, &wrt, Order::Hessian)
        .map_err(|e| e.to_string())
}

fn bistop(x: f64, v: f64, tail: &str) -> Evaluation {
    at(&format!("BISTOP(x, v, {tail})"), &["x", "v"], &[x, v]).unwrap()
}

fn gradient(evaluation: &Evaluation) -> Vec<f64> {
    evaluation
        .gradient
        .clone()
        .unwrap()
        .iter()
        .copied()
        .collect()
}

fn is_zero(evaluation: &Evaluation) -> bool {
    evaluation.value == 0.0
        && evaluation.gradient.iter().flatten().all(|g| *g == 0.0)
        && evaluation.hessian.iter().flatten().all(|h| *h == 0.0)
}

const STOP: &str = "-1, 1, 1e4, 1.5, 50, 0.1";

#[test]
fn at_contact_the_force_and_its_derivatives_are_zero() {
    // x == x1 and x == x2 belong to the free gap.
    assert!(is_zero(&bistop(-1.0, -3.0, STOP)));
    assert!(is_zero(&bistop(1.0, 3.0, STOP)));
    // Just inside: tiny, continuous, and the damping has not started.
    let inside = bistop(1.0 + 1e-12, 3.0, STOP);
    assert!(inside.value < 0.0 && inside.value > -1e-10);
    assert!(gradient(&inside)[1].abs() < 1e-18);
}

#[test]
fn at_the_end_of_the_ramp_the_damping_is_cmax_with_zero_slope() {
    // Penetration exactly d (x1 - x == 0.125, a binary fraction): damping cmax,
    // dF/dv = -cmax, d2F/dx dv = 0 (the STEP's constant branch).
    let evaluation = at(
        "BISTOP(x, v, -1, 1, 1e4, 1.5, 50, 0.125)",
        &["x", "v"],
        &[-1.125, -2.0],
    )
    .unwrap();
    assert_eq!(gradient(&evaluation)[1], -50.0);
    assert_eq!(evaluation.hessian.unwrap()[(0, 1)], 0.0);
    // Mid-ramp (w = 1/2): damping cmax/2, slope of the damping 1.5 cmax/d.
    let mid = at(
        "BISTOP(x, v, -1, 1, 1e4, 1.5, 50, 0.125)",
        &["x", "v"],
        &[-1.0625, -2.0],
    )
    .unwrap();
    assert_eq!(gradient(&mid)[1], -25.0);
    assert!((mid.hessian.unwrap()[(0, 1)] - 1.5 * 50.0 / 0.125).abs() < 1e-9);
}

#[test]
fn a_raw_force_of_exactly_zero_takes_the_clamped_branch() {
    // k p^e - c v == 0 exactly: k = 1, e = 1, p = 0.5 (beyond the ramp, c = cmax = 1), v = 0.5.
    let tie = at(
        "BISTOP(x, v, -1, 1, 1, 1, 1, 0.25)",
        &["x", "v"],
        &[-1.5, 0.5],
    )
    .unwrap();
    assert!(is_zero(&tie));
    // A little less separation speed: the raw force is positive again.
    assert!(
        at(
            "BISTOP(x, v, -1, 1, 1, 1, 1, 0.25)",
            &["x", "v"],
            &[-1.5, 0.25]
        )
        .unwrap()
        .value
            > 0.0
    );
    // Fast separation: clamped to zero, not pulling the bodies together.
    assert!(is_zero(&bistop(1.05, -100.0, STOP)));
}

#[test]
fn exponents_below_one_two_and_at_one() {
    // e < 1: dF/dx grows without bound near contact, but stays finite at p = 1e-6.
    let soft = at(
        "IMPACT(x, v, 0, 1e3, 0.5, 0, 0.1)",
        &["x", "v"],
        &[-1e-6, 0.0],
    )
    .unwrap();
    assert!((gradient(&soft)[0] - -1e3 * 0.5 * 1e-6f64.powf(-0.5)).abs() < 1e-6);
    // ... and where its second derivative overflows, evaluation says so instead of returning inf.
    let error = at(
        "IMPACT(x, v, 0, 1e3, 0.1, 0, 0.1)",
        &["x", "v"],
        &[-1e-300, 0.0],
    )
    .unwrap_err();
    assert!(
        error.contains("derivative of IMPACT is not a finite number"),
        "{error}"
    );
    // e = 1: dF/dx jumps from 0 to -k at contact.
    let linear = at(
        "IMPACT(x, v, 0, 1e3, 1, 0, 0.1)",
        &["x", "v"],
        &[-1e-9, 0.0],
    )
    .unwrap();
    assert_eq!(gradient(&linear)[0], -1e3);
    // 1 < e < 2: the second derivative grows without bound at contact.
    let hertz = at(
        "IMPACT(x, v, 0, 1e3, 1.5, 0, 0.1)",
        &["x", "v"],
        &[-1e-12, 0.0],
    )
    .unwrap();
    assert!(hertz.hessian.unwrap()[(0, 0)] > 1e8);
}

#[test]
fn stiff_contacts_and_tiny_damping_depths_keep_their_digits() {
    // x1 = 1e6 with d = 1e-9: the penetration is a few ulps of 1e6, and the
    // damping ramp is resolved in p/d, not in x - (x1 - d).
    let ulp = 1e6f64.next_up() - 1e6;
    let x = 1e6 - 3.0 * ulp;
    let p = 1e6 - x;
    let evaluation = at(
        "IMPACT(x, v, 1e6, 1e12, 1.5, 1e3, 1e-9)",
        &["x", "v"],
        &[x, -1.0],
    )
    .unwrap();
    let w = p / 1e-9;
    let damping = 1e3 * w * w * (3.0 - 2.0 * w);
    let want = 1e12 * p.powf(1.5) + damping;
    assert!(
        (evaluation.value - want).abs() <= 1e-12 * want,
        "{} vs {want}",
        evaluation.value
    );
    assert!((gradient(&evaluation)[1] - -damping).abs() <= 1e-12 * damping);
    // A penetration of 1e-300 with e = 1.5: finite, and the value exact.
    let tiny = at(
        "IMPACT(x, v, 0, 1e12, 1.5, 0, 1e-9)",
        &["x", "v"],
        &[-1e-300, 0.0],
    );
    match tiny {
        Ok(evaluation) => assert_eq!(evaluation.value, 1e12 * 1e-300f64.powf(1.5)),
        Err(error) => assert!(error.contains("not a finite number"), "{error}"),
    }
}

#[test]
fn kinks_take_the_branch_the_value_came_from() {
    // MAX and MIN on a tie: the first argument.
    assert_eq!(
        gradient(&at("MAX(a, b)", &["a", "b"], &[1.0, 1.0]).unwrap()),
        [1.0, 0.0]
    );
    assert_eq!(
        gradient(&at("MIN(a, b)", &["a", "b"], &[1.0, 1.0]).unwrap()),
        [1.0, 0.0]
    );
    // ABS at 0: the a >= 0 branch.
    assert_eq!(gradient(&at("ABS(a)", &["a"], &[0.0]).unwrap()), [1.0]);
    // STEP at x0 belongs to the constant part: zero slope and curvature.
    let step = at("STEP(x, 0, 0, 1, 1)", &["x"], &[0.0]).unwrap();
    assert!(is_zero(&step));
    // IF with a zero condition takes the zero branch and runs no other.
    assert_eq!(
        at("IF(x: 1/0, 7, LOG(-1))", &["x"], &[0.0]).unwrap().value,
        7.0
    );
    // ATAN2(0, 0) is 0 with zero derivatives.
    assert!(is_zero(
        &at("ATAN2(y, x)", &["y", "x"], &[0.0, 0.0]).unwrap()
    ));
}

#[test]
fn powers_with_constant_exponents() {
    assert_eq!(at("2**3", &[], &[]).unwrap().value, 8.0);
    let cube = at("(x-3)**3", &["x"], &[1.0]).unwrap();
    assert_eq!(
        (
            cube.value,
            gradient(&cube)[0],
            cube.hessian.unwrap()[(0, 0)]
        ),
        (-8.0, 12.0, -12.0)
    );
    // A tiny base to a whole power stays exact (no 0 * inf).
    let tiny = at("x**2", &["x"], &[1e-300]).unwrap();
    assert_eq!((tiny.value, gradient(&tiny)[0]), (0.0, 2e-300));
    assert!(
        at("x**0.5", &["x"], &[-1.0])
            .unwrap_err()
            .contains("negative base")
    );
    assert!(
        at("x**-1", &["x"], &[0.0])
            .unwrap_err()
            .contains("infinite")
    );
}
