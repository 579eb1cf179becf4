//! The utility subroutines through their C and FORTRAN calling sequences:
//! programs written as user subroutines would be, compiled against the
//! static library and run; and the Rust API against the expression evaluator.

use std::path::{Path, PathBuf};
use std::process::Command;

use mbexpr::{Order, utility};
use proptest::prelude::*;

/// `target/<profile>`, where the binary and `libmbexpr.a` are built.
fn build_dir() -> PathBuf {
    Path::new(env!("CARGO_BIN_EXE_mbexpr"))
        .parent()
        .expect("the binary is in a folder")
        .to_path_buf()
}

/// Compiles `source` with `compiler` against the static library and runs
/// it; `None` (with a note) when the compiler is not installed.
fn compile_and_run(compiler: &str, source: &str, extra: &[&str]) -> Option<String> {
    if Command::new(compiler).arg("--version").output().is_err() {
        eprintln!(
            "note: {compiler} is not installed; the {source} test is skipped (.ci/run installs it)"
        );
        return None;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    // `cargo test` builds the static library beside the test binaries.
    let library = build_dir().join("deps/libmbexpr.a");
    assert!(
        library.exists(),
        "{} is built with the library",
        library.display()
    );
    let scratch =
        std::env::temp_dir().join(format!("mbexpr-ffi-{}-{compiler}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let program = scratch.join("user_sub");
    let status = Command::new(compiler)
        .current_dir(&scratch)
        .args(extra)
        .arg(root.join(source))
        .arg("-I")
        .arg(root.join("include"))
        .arg(&library)
        .args(["-lpthread", "-ldl", "-lm", "-o"])
        .arg(&program)
        .status()
        .expect("the compiler runs");
    assert!(status.success(), "{compiler} failed on {source}");
    let output = Command::new(&program).output().expect("the program runs");
    std::fs::remove_dir_all(&scratch).unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    Some(String::from_utf8(output.stdout).unwrap())
}

#[test]
fn a_c_user_subroutine_calls_the_library() {
    if let Some(output) = compile_and_run("cc", "tests/c/user_sub.c", &[]) {
        insta::assert_snapshot!(output);
    }
}

#[test]
fn a_fortran_user_subroutine_calls_the_library() {
    let module = Path::new(env!("CARGO_MANIFEST_DIR")).join("include/mbexpr.f90");
    let module = module.to_str().unwrap();
    if let Some(output) = compile_and_run("gfortran", "tests/fortran/user_sub.f90", &[module]) {
        insta::assert_snapshot!(output);
    }
}

#[test]
fn vector_across_every_branch() {
    let points = [
        ("gap", 0.0, 0.7),
        ("contact", 10.0, 0.7),
        ("ramp", 10.05, 0.7),
        ("ramp end", 10.125, 0.7),
        ("beyond", 10.5, 0.7),
        ("clamped", 10.05, -100.0),
        ("lower ramp", -10.05, -0.7),
        ("lower beyond", -10.5, 0.7),
    ];
    let mut table = String::new();
    for (branch, x, v) in points {
        for iord in 0..=2 {
            let vector = utility::bistop(x, v, -10.0, 10.0, 1e5, 2.2, 100.0, 0.125, iord).unwrap();
            table += &format!(
                "BISTOP {branch:<13} iord {iord}: [{:.12e}, {:.12e}, {:.12e}]\n",
                vector[0], vector[1], vector[2]
            );
        }
    }
    for (x, v) in [(1.5, -1.0), (0.95, -1.0), (0.5, -1.0), (0.95, 1e6)] {
        for iord in 0..=2 {
            let vector = utility::impact(x, v, 1.0, 1e4, 1.5, 10.0, 0.1, iord).unwrap();
            table += &format!(
                "IMPACT x={x} v={v} iord {iord}: [{:.12e}, {:.12e}, {:.12e}]\n",
                vector[0], vector[1], vector[2]
            );
        }
    }
    for (x, iord) in [(-1.0, 0), (0.25, 0), (0.25, 1), (0.25, 2), (2.0, 1)] {
        table += &format!(
            "STEP x={x} iord {iord}: {:.12e}\n",
            utility::step(x, 0.0, 0.0, 1.0, 10.0, iord).unwrap()
        );
    }
    let errors = [
        utility::bistop(0.0, 0.0, 1.0, 1.0, 1e5, 2.2, 100.0, 0.1, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, -1.0, 2.2, 100.0, 0.1, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, 1e5, 0.0, 100.0, 0.1, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, 1e5, 2.2, -1.0, 0.1, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, 1e5, 2.2, 100.0, 0.0, 0).unwrap_err(),
        utility::bistop(0.0, 0.0, -1.0, 1.0, 1e5, 2.2, 100.0, 0.1, 3).unwrap_err(),
        utility::bistop(f64::NAN, 0.0, -1.0, 1.0, 1e5, 2.2, 100.0, 0.1, 0).unwrap_err(),
        utility::impact(0.0, f64::INFINITY, 1.0, 1e5, 2.2, 100.0, 0.1, 0).unwrap_err(),
        utility::step(0.0, 1.0, 0.0, 1.0, 1.0, 0).unwrap_err(),
    ];
    for error in errors {
        table += &format!("error: {error}\n");
    }
    insta::assert_snapshot!(table);
}

#[test]
fn never_nan_and_infinities_of_the_right_sign() {
    // k p^e beyond the largest double: +inf (lower stop pushes up), -inf above.
    let huge = utility::bistop(-1e200, 0.0, -1.0, 1.0, 1e12, 3.0, 0.0, 1e-9, 0).unwrap();
    assert_eq!(huge, [f64::INFINITY, 0.0, 0.0]);
    let huge = utility::bistop(1e200, 0.0, -1.0, 1.0, 1e12, 3.0, 0.0, 1e-9, 0).unwrap();
    assert_eq!(huge, [f64::NEG_INFINITY, 0.0, 0.0]);
    // A penetration of 1e-300 with e = 0.1: d2F/dx2 passes the largest
    // double, while d2F/dx dx' stays 0 (no 0 * inf).
    let steep = utility::impact(-1e-300, 0.0, 0.0, 1e12, 0.1, 0.0, 1e-9, 2).unwrap();
    assert_eq!(steep[0], f64::NEG_INFINITY, "{steep:?}");
    assert_eq!(steep[1], 0.0);
    for iord in 0..=2 {
        for x in [-1e300, -1.0 - 1e-300, -1.0, 0.0, 1.0 + 1e-12, 1e300] {
            for v in [-1e300, -1.0, 0.0, 1.0, 1e300] {
                let vector = utility::bistop(x, v, -1.0, 1.0, 1e12, 0.1, 1e6, 1e-9, iord).unwrap();
                assert!(
                    vector.iter().all(|entry| !entry.is_nan()),
                    "NaN at x={x} v={v} iord={iord}: {vector:?}"
                );
            }
        }
    }
}

#[test]
fn extreme_inputs_keep_their_digits() {
    // Gap at 1e6, d = 1e-9, penetrations of a few ulps: against the formula
    // evaluated in penetration coordinates by hand.
    let ulp = 1e6f64.next_up() - 1e6;
    for (steps, e, k) in [
        (1.0, 1.5, 1e12),
        (3.0, 0.1, 1e3),
        (5.0, 3.0, 0.0),
        (8.0, 1.0, 1e12),
    ] {
        let x = 1e6 - steps * ulp;
        let p = 1e6 - x;
        let (cmax, d, v) = (1e3, 1e-9, -2.0);
        let w = p / d;
        let c = cmax * w * w * (3.0 - 2.0 * w);
        let dc = cmax * 6.0 * w * (1.0 - w) / d;
        let want = [k * p.powf(e) - c * v, -k * e * p.powf(e - 1.0) + dc * v, -c];
        let value = utility::impact(x, v, 1e6, k, e, cmax, d, 0).unwrap()[0];
        let slopes = utility::impact(x, v, 1e6, k, e, cmax, d, 1).unwrap();
        let scale = k * p.powf(e) + c * v.abs();
        assert!(
            (value - want[0]).abs() <= 1e-12 * scale,
            "value {value} vs {}",
            want[0]
        );
        let slope_scale = (k * e * p.powf(e - 1.0)).abs() + (dc * v).abs();
        assert!(
            (slopes[0] - want[1]).abs() <= 1e-9 * slope_scale,
            "dF/dx {} vs {}",
            slopes[0],
            want[1]
        );
        assert!(
            (slopes[1] - want[2]).abs() <= 1e-12 * c.max(1e-300),
            "dF/dv {} vs {}",
            slopes[1],
            want[2]
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The utility and the expression `BISTOP(x, v, ...)` are one law.
    #[test]
    fn the_utility_agrees_with_the_expression(
        x in -3.0f64..3.0, v in -5.0f64..5.0, x1 in -1.5f64..-0.5, x2 in 0.5f64..1.5,
        k in 0.0f64..1e6, e in 0.1f64..3.0, cmax in 0.0f64..1e3, d in 1e-6f64..1.0,
    ) {
        let text = format!("BISTOP(x, v, {x1:?}, {x2:?}, {k:?}, {e:?}, {cmax:?}, {d:?})");
        let checked = mbexpr::check(&mbexpr::parse(&text).unwrap()).unwrap();
        let program = mbexpr::compile(&checked, &["x", "v"]).unwrap();
        let expression = program.evaluate(&[x, v], &[0, 1], Order::Hessian);
        let values = utility::bistop(x, v, x1, x2, k, e, cmax, d, 0).unwrap();
        let slopes = utility::bistop(x, v, x1, x2, k, e, cmax, d, 1).unwrap();
        let curvatures = utility::bistop(x, v, x1, x2, k, e, cmax, d, 2).unwrap();
        if let Ok(expression) = expression {
            let gradient = expression.gradient.unwrap();
            let hessian = expression.hessian.unwrap();
            prop_assert_eq!(values[0], expression.value + 0.0);
            prop_assert_eq!([slopes[0], slopes[1]], [gradient[0] + 0.0, gradient[1] + 0.0]);
            prop_assert_eq!([curvatures[0], curvatures[1]], [hessian[(0, 0)] + 0.0, hessian[(0, 1)] + 0.0]);
        }
    }
}
