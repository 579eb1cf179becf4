//! Properties over random input: nothing panics, nothing returns NaN, and
//! dual derivatives agree with finite differences.

use mbexpr::catalog::Function;
use mbexpr::{Order, Program};
use proptest::prelude::*;

/// Parse, check, compile (with inputs x, v, t) and evaluate with a Hessian:
/// whatever happens, no panic, and every error's span lies in the text.
pub(crate) fn run_everything(text: &str) {
    let in_text = |span: mbexpr::Span| span.start <= span.end && span.end <= text.len();
    let tree = match mbexpr::parse(text) {
        Ok(tree) => tree,
        Err(error) => {
            assert!(in_text(error.span()), "{error:?} in {text:?}");
            assert!(
                !error.to_string().is_empty() && !error.to_string().ends_with('.'),
                "{error} in {text:?}"
            );
            return;
        }
    };
    let checked = match mbexpr::check(&tree) {
        Ok(checked) => checked,
        Err(errors) => {
            assert!(
                errors.iter().all(|error| in_text(error.span())),
                "{errors:?}"
            );
            return;
        }
    };
    let program = match mbexpr::compile(&checked, &["x", "v", "t"]) {
        Ok(program) => program,
        Err(errors) => {
            assert!(
                errors.iter().all(|error| in_text(error.span())),
                "{errors:?}"
            );
            return;
        }
    };
    if let Ok(evaluation) = program.evaluate(&[0.3, -1.2, 2.0], &[0, 1], Order::Hessian) {
        assert!(evaluation.value.is_finite());
        assert!(evaluation.gradient.unwrap().iter().all(|g| g.is_finite()));
        assert!(evaluation.hessian.unwrap().iter().all(|h| h.is_finite()));
    }
}

/// Tokens of the language and a few that are not.
fn token() -> impl Strategy<Value = String> {
    let names: Vec<String> = Function::ALL
        .iter()
        .map(|function| function.name().to_string())
        .collect();
    prop_oneof![
        prop::sample::select(names),
        prop::sample::select(vec![
            "x",
            "v",
            "t",
            "PI",
            "TIME",
            "MODE",
            "RTOD",
            ".m.part.mar",
            "IF",
            "0",
            "1",
            "2.5",
            "1e5",
            ".5",
            "90D",
            "1.0D3",
            "1E400",
            "+",
            "-",
            "*",
            "/",
            "**",
            "^",
            "<",
            "(",
            ")",
            ",",
            ":",
            " ",
            "{",
            "\n",
            "0201",
        ])
        .prop_map(str::to_string),
        (-1e6f64..1e6).prop_map(|value| format!("{value}")),
    ]
}

/// A random well-formed expression over x, v, t.
fn expression() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        prop::sample::select(vec!["x", "v", "t", "PI", "2", "0.5", "-3", "1e3"])
            .prop_map(str::to_string),
        (-10.0f64..10.0).prop_map(|value| format!("({value})")),
    ];
    leaf.prop_recursive(5, 48, 4, |inner| {
        prop_oneof![
            (
                inner.clone(),
                prop::sample::select(vec!["+", "-", "*", "/"]),
                inner.clone()
            )
                .prop_map(|(a, op, b)| format!("({a} {op} {b})")),
            (inner.clone(), 0i32..4).prop_map(|(a, n)| format!("({a})**{n}")),
            inner.clone().prop_map(|a| format!("SIN({a})")),
            inner.clone().prop_map(|a| format!("EXP({a})")),
            inner.clone().prop_map(|a| format!("LOG({a})")),
            inner.clone().prop_map(|a| format!("SQRT({a})")),
            inner.clone().prop_map(|a| format!("ABS({a})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("ATAN2({a}, {b})")),
            inner
                .clone()
                .prop_map(|a| format!("STEP({a}, -1, 0, 1, 5)")),
            (inner.clone(), inner.clone())
                .prop_map(|(a, b)| format!("BISTOP({a}, {b}, -1, 1, 1e4, 1.5, 50, 0.1)")),
            (inner.clone(), inner.clone())
                .prop_map(|(a, b)| format!("IMPACT({a}, {b}, 0.5, 1e4, 2.2, 50, 0.1)")),
            (inner.clone(), inner.clone(), inner.clone(), inner)
                .prop_map(|(a, b, c, d)| format!("IF({a}: {b}, {c}, {d})")),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        run_everything(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn token_soup_never_panics(tokens in prop::collection::vec(token(), 0..40)) {
        run_everything(&tokens.concat());
    }

    /// A call's argument takes one of two paths through the grammar (a lone
    /// number or name, or a whole `expr`); either way it must build the tree
    /// the same text builds alone.
    #[test]
    fn an_argument_parses_as_the_same_text_alone(
        body in prop_oneof![expression(), prop::collection::vec(token(), 1..10).prop_map(|tokens| tokens.concat())],
        sign in prop::sample::select(vec!["", "-", "+ ", "- -"]),
    ) {
        let text = format!("{sign}{body}");
        if let Ok(alone) = mbexpr::parse(&text) {
            let call = mbexpr::parse(&format!("F({text}, {text})")).unwrap();
            prop_assert_eq!(call.to_string(), format!("(F {alone} {alone})"));
        }
    }

    #[test]
    fn evaluation_never_returns_nan_or_infinity(text in expression(), x in -3.0f64..3.0, v in -3.0f64..3.0) {
        // A constant part that fails whenever it runs is refused by the checker.
        let checked = match mbexpr::check(&mbexpr::parse(&text).unwrap()) {
            Ok(checked) => checked,
            Err(errors) => {
                prop_assert!(errors.iter().all(|error| matches!(error, mbexpr::CheckError::ConstantFails { .. })), "{text}: {errors}");
                return Ok(());
            }
        };
        let program = mbexpr::compile(&checked, &["x", "v", "t"]).unwrap();
        for order in [Order::Value, Order::Gradient, Order::Hessian] {
            if let Ok(evaluation) = program.evaluate(&[x, v, 0.7], &[0, 1, 2], order) {
                prop_assert!(evaluation.value.is_finite(), "{text}");
                prop_assert!(evaluation.gradient.iter().flatten().all(|g| g.is_finite()), "{text}");
                prop_assert!(evaluation.hessian.iter().flatten().all(|h| h.is_finite()), "{text}");
            }
        }
    }
}

/// The value at `x` (input 0) with the other inputs at `rest`.
fn value_at(program: &Program, x: f64, rest: &[f64]) -> f64 {
    let mut inputs = vec![x];
    inputs.extend_from_slice(rest);
    program.value(&inputs).unwrap()
}

/// First and second derivative in input 0 by an eighth-order central difference.
fn finite_differences(program: &Program, x: f64, rest: &[f64]) -> (f64, f64) {
    let h = 1e-3 * x.abs().max(1.0);
    let f = |k: f64| value_at(program, x + k * h, rest);
    let first = (4.0 / 5.0 * (f(1.0) - f(-1.0)) - 1.0 / 5.0 * (f(2.0) - f(-2.0))
        + 4.0 / 105.0 * (f(3.0) - f(-3.0))
        - 1.0 / 280.0 * (f(4.0) - f(-4.0)))
        / h;
    let second = (-205.0 / 72.0 * f(0.0) + 8.0 / 5.0 * (f(1.0) + f(-1.0))
        - 1.0 / 5.0 * (f(2.0) + f(-2.0))
        + 8.0 / 315.0 * (f(3.0) + f(-3.0))
        - 1.0 / 560.0 * (f(4.0) + f(-4.0)))
        / (h * h);
    (first, second)
}

/// Expressions in `x` (and `v`), with ranges of `x` that stay at least the
/// stencil's width (8e-3) away from every kink.
fn smooth_cases() -> Vec<(&'static str, std::ops::Range<f64>)> {
    vec![
        ("STEP(x, -1, 2, 1, 5)", -0.99..0.99),
        ("STEP5(x, -1, 2, 1, 5)", -0.99..0.99),
        ("HAVSIN(x, -1, 2, 1, 5)", -0.99..0.99),
        ("SHF(x, 0.2, 2, 3, 0.5, 1)", -2.0..2.0),
        ("POLY(x, 0.5, 1, -2, 3, 0.25)", -2.0..2.0),
        ("CHEBY(x, 0.1, 1, -2, 3, 0.25)", -1.0..1.0),
        ("FORCOS(x, 0, 2, 1, 2, 3)", -2.0..2.0),
        ("FORSIN(x, 0, 2, 1, 2, 3)", -2.0..2.0),
        ("SWEEP(x, 2, 1, 1, 3, 5, 0.5)", 1.01..1.49),
        ("SWEEP(x, 2, 1, 1, 3, 5, 0.5)", 1.51..2.98),
        // Lower stop inside the ramp, and beyond it; x' = v = -0.3 approaches.
        ("BISTOP(x, v, -1, 1, 1e3, 1.5, 20, 0.2)", -1.19..-1.01),
        ("BISTOP(x, v, -1, 1, 1e3, 2.2, 20, 0.2)", -2.0..-1.21),
        ("IMPACT(x, v, 1, 1e3, 1.5, 20, 0.2)", 0.81..0.99),
        ("-1E4*(x-50)-10*v + 3*SIN(2*PI*x)", -5.0..5.0),
        (
            "ATAN2(x, 1.5) + SQRT(x**2 + 1) + EXP(x/3) + LOG(x + 4)",
            -3.0..3.0,
        ),
        ("x**2.5 + x**-1.5 + (x-3)**3", 0.5..3.0),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn dual_derivatives_agree_with_finite_differences(case in 0usize..16, fraction in 0.0f64..1.0) {
        let (text, range) = &smooth_cases()[case];
        let x = range.start + fraction * (range.end - range.start);
        let checked = mbexpr::check(&mbexpr::parse(text).unwrap()).unwrap();
        let program = mbexpr::compile(&checked, &["x", "v"]).unwrap();
        let evaluation = program.evaluate(&[x, -0.3], &[0], Order::Hessian).unwrap();
        let (first, second) = finite_differences(&program, x, &[-0.3]);
        let scale = evaluation.value.abs().max(1.0);
        let gradient = evaluation.gradient.unwrap()[0];
        let hessian = evaluation.hessian.unwrap()[(0, 0)];
        prop_assert!((gradient - first).abs() <= 1e-7 * scale.max(gradient.abs()), "{text} at {x}: dual {gradient}, differences {first}");
        prop_assert!((hessian - second).abs() <= 1e-4 * scale.max(hessian.abs()), "{text} at {x}: dual {hessian}, differences {second}");
    }

    #[test]
    fn bistop_is_zero_with_zero_derivatives_in_the_gap(
        x1 in -5.0f64..0.0, width in 0.0f64..5.0, fraction in 0.0f64..=1.0, v in -100.0f64..100.0,
        k in 0.0f64..1e8, e in 0.1f64..3.0, cmax in 0.0f64..1e4, d in 1e-9f64..1.0,
    ) {
        let x2 = x1 + width + 1e-9;
        let x = x1 + fraction * (x2 - x1);
        let text = format!("BISTOP(x, v, {x1:?}, {x2:?}, {k:?}, {e:?}, {cmax:?}, {d:?})");
        // A constant part that fails whenever it runs is refused by the checker.
        let checked = match mbexpr::check(&mbexpr::parse(&text).unwrap()) {
            Ok(checked) => checked,
            Err(errors) => {
                prop_assert!(errors.iter().all(|error| matches!(error, mbexpr::CheckError::ConstantFails { .. })), "{text}: {errors}");
                return Ok(());
            }
        };
        let program = mbexpr::compile(&checked, &["x", "v"]).unwrap();
        let evaluation = program.evaluate(&[x.clamp(x1, x2), v], &[0, 1], Order::Hessian).unwrap();
        prop_assert_eq!(evaluation.value, 0.0);
        prop_assert!(evaluation.gradient.unwrap().iter().all(|g| *g == 0.0));
        prop_assert!(evaluation.hessian.unwrap().iter().all(|h| *h == 0.0));
    }

    #[test]
    fn step_and_its_slope_are_continuous_at_both_ends(x0 in -10.0f64..10.0, width in 0.01f64..10.0, h0 in -5.0f64..5.0, h1 in -5.0f64..5.0) {
        let x1 = x0 + width;
        let text = format!("STEP(x, {x0:?}, {h0:?}, {x1:?}, {h1:?})");
        // A constant part that fails whenever it runs is refused by the checker.
        let checked = match mbexpr::check(&mbexpr::parse(&text).unwrap()) {
            Ok(checked) => checked,
            Err(errors) => {
                prop_assert!(errors.iter().all(|error| matches!(error, mbexpr::CheckError::ConstantFails { .. })), "{text}: {errors}");
                return Ok(());
            }
        };
        let program = mbexpr::compile(&checked, &["x"]).unwrap();
        let at = |x: f64| program.evaluate(&[x], &[0], Order::Gradient).unwrap();
        let step = 1e-9 * width;
        // The bound on the change over `step`: the second derivative is at most 6|h1 - h0|/width^2.
        let bound = 6.0 * (h1 - h0).abs() / (width * width) * step + 1e-12 * (h0.abs() + h1.abs() + 1.0);
        for end in [x0, x1] {
            let (before, after) = (at(end - step), at(end + step));
            prop_assert!((before.value - after.value).abs() <= bound * width + 1e-12, "{text}: value jumps at {end}");
            let (slope_before, slope_after) = (before.gradient.unwrap()[0], after.gradient.unwrap()[0]);
            prop_assert!((slope_before - slope_after).abs() <= 2.0 * bound, "{text}: slope jumps at {end}: {slope_before} vs {slope_after}");
        }
    }
}

/// A line of a View script: the blocks of its language, variables set
/// and read, and values in brackets made of View's expression tokens.
fn script_line() -> impl Strategy<Value = String> {
    let piece = prop::sample::select(vec![
        "i", "k", ".m.n", "1", "2.5", "-", "+", "*", "/", "**", "//", "(", ")", ",", "==", "<",
        "&&", "!", "\"a\"", "eval(", "RTOI(", "MOD(", "SQRT(", "1e308", "0", "PI", "$x", "{",
    ]);
    let value =
        prop::collection::vec(piece, 0..8).prop_map(|pieces| format!("({})", pieces.concat()));
    prop_oneof![
        value
            .clone()
            .prop_map(|v| format!("for variable_name = i start_value = 1 end_value = {v}")),
        value.clone().prop_map(|v| format!("while condition = {v}")),
        value.clone().prop_map(|v| format!("if condition = {v}")),
        value
            .clone()
            .prop_map(|v| format!("elseif condition = {v}")),
        Just("else".to_string()),
        Just("end".to_string()),
        Just("break".to_string()),
        Just("continue".to_string()),
        value
            .clone()
            .prop_map(|v| format!("variable set variable_name = k real_value = {v}")),
        value
            .clone()
            .prop_map(|v| format!("variable set variable_name = .m.n string_value = {v}")),
        value
            .clone()
            .prop_map(|v| format!("marker create marker_name = .m.ground.A location = {v}, 0, 0")),
        value.prop_map(|v| format!(
            "part create rigid_body name_and_position part_name = {v} adams_id = {v}"
        )),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// View's command language carried out on random scripts: no panic,
    /// no hang, every problem at a place in the text.
    #[test]
    fn random_view_scripts_never_panic(lines in prop::collection::vec(script_line(), 0..24)) {
        let text = format!("model create model_name = m\n{}\n", lines.join("\n"));
        let dataset = mbexpr::model::read(&text, mbexpr::model::FileKind::Cmd);
        for problem in &dataset.problems {
            prop_assert!(problem.span().end <= text.len());
        }
        let _ = mbexpr::simulate::from_text(&text, mbexpr::simulate::ModelFormat::Dataset, mbexpr::model::FileKind::Cmd);
    }
}
