//! Parse stage: trees and syntax errors, one case per line.

use mbexpr::{Location, parse};

/// The tree as an S-expression, or `error LINE:COL: message`.
fn check(input: &str) -> String {
    match parse(input) {
        Ok(tree) => tree.to_string(),
        Err(error) => {
            let at = Location::of(input, error.span().start);
            format!("error {at}: {error}")
        }
    }
}

fn table(cases: &str) -> String {
    crate::table(cases, check)
}

#[test]
fn numbers() {
    insta::assert_snapshot!(table(
        r"
        1
        1.
        .5
        2.25
        1e5
        1E+07
        3.582e-09
        1.0E+007
        0.00000000000000000e+000
        90D
        -40d
        1.5D
        0.0d
        .5D
        0201
        1.0D3
        2D-5
        2d+3*x
        1E400
        20E0301
        "
    ));
}

#[test]
fn operators_and_precedence() {
    insta::assert_snapshot!(table(
        r"
        a + b - c
        a - b - c
        a / b * c
        a + b * c
        (a + b) * c
        2**3**2
        -2**2
        - -8.3E-03*RTOD
        + -0.5
        +-1.0515424217E+06*WZ(1)
        a*-b
        x**-2
        x**-y**2
        -a*b
        -(a)**2
        a/-b/c
        "
    ));
}

#[test]
fn names_and_calls() {
    insta::assert_snapshot!(table(
        r"
        step(time, 0, 0, 1, 10)
        STEP (TIME, 0, 0, 1, 10)
        .model_1.PART_2.MAR_3
        Body1.Marker2
        DX(.m.a, .m.b, .m.b)
        ORIENT(27,1,0201,0101)
        k_stop*x_1
        WZ( 99)
        VR()
        IF(TIME-2: 0, 0, 1)
        IF (TIME-2 : 0, 0, 1)
        IF(IF(x: -1, 0, 1): a, b, IF(y: 1, 2, 3))
        BISTOP(DX(2,1,1), VX(2,1,1,1), -5, 5, 1e5, 2.2, 100, 0.1)
        F(-x, +y, - -2, -.5D, 3D)
        F(1 + 2, x*y, -x**2, 2 ** -x, (a), -(b), -G(1))
        F( x , 1 )
        IF(-x: +1, -2, 3)
        "
    ));
}

#[test]
fn refusals() {
    insta::assert_snapshot!(table(
        r"
        x^2
        x < 3
        x >= 3
        a == b
        a && b
        IF(a, b, c, d)
        IF(a: b, c)
        IF(a: b, c, d, e)
        IF(a, b: c, d)
        STEP(x: 0, 0, 1, 1)
        5*DELAY(DIF(2), DIF(1)-3*DIF(2), 0.95))
        (DELAY(DIFF1, 1,1,777)
        STEP(x, 0, 0, 1 1)
        STEP(x,)
        ()
        a +
        * a
        2 x
        x,y
        a : b
        -AZ({j_st_wheel.i.id, %d})*RTOD
        a $ b
        a # b
        1.0D3 + 2
        (((x)
        STEP(x, 0, 0, 1, 1
        AZ.(9000200,9000201()*TO
        .m.PART_2.(x
        "
    ));
}

#[test]
fn an_empty_input_is_refused() {
    assert_eq!(check(""), "error 1:1: the expression is empty");
    assert_eq!(check("   \n  "), "error 2:3: the expression is empty");
}

#[test]
fn spans_cover_the_text_of_each_node() {
    let text = "STEP(TIME, 0, 0, 1, 10) + 2*x";
    let tree = parse(text).unwrap();
    assert_eq!(tree.span, mbexpr::Span::new(0, text.len()));
    let mbexpr::syntax::ast::ExprKind::Chain(call, rest) = &tree.kind else {
        panic!("a sum")
    };
    let [(_, product)] = rest.as_slice() else {
        panic!("of two terms")
    };
    assert_eq!(&text[call.span.range()], "STEP(TIME, 0, 0, 1, 10)");
    assert_eq!(&text[product.span.range()], "2*x");
}

#[test]
fn an_argument_spans_its_signs_and_no_blank_after_it() {
    let text = "F(- 10 , x\t,-G( 2 ) )";
    let tree = parse(text).unwrap();
    let mbexpr::syntax::ast::ExprKind::Call(call) = &tree.kind else {
        panic!("a call")
    };
    let args: Vec<&str> = call
        .args
        .iter()
        .map(|arg| &text[arg.span.range()])
        .collect();
    assert_eq!(args, ["- 10", "x", "-G( 2 )"]);
}

#[test]
fn nesting_at_the_limit_parses_and_past_it_is_refused() {
    let limit = mbexpr::syntax::MAX_NESTING;
    let deep = |depth: usize| format!("{}x{}", "(".repeat(depth), ")".repeat(depth));
    let at_limit = deep(limit - 1);
    // Run where the stack is smallest: a test thread has 2 MiB.
    assert!(parse(&at_limit).is_ok());
    let refused = check(&deep(100_000));
    assert!(refused.contains("nests deeper than"), "{refused}");
    let signs = format!("{}x", "-".repeat(100_000));
    assert!(check(&signs).contains("nests deeper than"));
    let powers = format!("x{}", "**x".repeat(100_000));
    assert!(check(&powers).contains("nests deeper than"));
    // Many operators in many short groups: over the quick bound, within the limit.
    let groups = format!("MAX({}x)", "x-1, ".repeat(2 * limit));
    assert!(parse(&groups).is_ok());
}

#[test]
fn a_tree_at_the_depth_limit_goes_through_every_stage() {
    let limit = mbexpr::syntax::MAX_NESTING;
    let nested = format!(
        "{}x{}",
        "SIN(-".repeat(limit / 2 - 1),
        ")".repeat(limit / 2 - 1)
    );
    let checked = mbexpr::check(&parse(&nested).unwrap()).unwrap();
    assert!(checked.root.to_string().starts_with("(SIN (neg (SIN"));
    let powers = format!("x{}", "**1".repeat(limit - 1));
    let checked = mbexpr::check(&parse(&powers).unwrap()).unwrap();
    let program = mbexpr::compile(&checked, &["x"]).unwrap();
    assert_eq!(program.value(&[3.0]).unwrap(), 3.0);
}

/// The value of `text` with every name bound to `x`, or the error.
fn value_at(text: &str, x: f64) -> String {
    let tree = match parse(text) {
        Ok(tree) => tree,
        Err(error) => return error.to_string(),
    };
    let checked = mbexpr::check(&tree).unwrap();
    let program = mbexpr::compile(&checked, &["x"]).unwrap();
    program.value(&[x]).unwrap().to_string()
}

#[test]
fn a_long_flat_run_of_operators_is_not_nesting() {
    let limit = mbexpr::syntax::MAX_NESTING;
    // Each case: the text, its value at x = 1. A run of `+ -` or `* /`
    // is one level however long; signs and powers nest.
    let cases = [
        ("x+".repeat(600) + "x", "601"),
        ("x*".repeat(100_000) + "x", "1"),
        ("x-".repeat(limit + 1) + "x", &(-(limit as f64)).to_string()),
        (format!("({})*2", "x+".repeat(2 * limit) + "x"), "2002"),
        ("2*x+".repeat(2 * limit) + "-x", "1999"),
        ("x+-".repeat(2 * limit) + "x", "-999"),
        (format!("{}x", "-".repeat(limit - 1)), "-1"),
        (format!("{}x", "-".repeat(limit + 1)), "nests"),
        (format!("x{}", "**x".repeat(limit + 1)), "nests"),
        (format!("x**{}x", "-".repeat(limit)), "nests"),
    ];
    for (text, want) in cases {
        let got = value_at(&text, 1.0);
        assert!(
            got.starts_with(want) || got.contains("nests deeper") && want == "nests",
            "{}...: {got}",
            &text[..40.min(text.len())]
        );
    }
    // The tree prints as the binary operations the run folds to.
    assert_eq!(
        check("a - b + c * d / e - f"),
        "(- (+ (- a b) (/ (* c d) e)) f)"
    );
    assert_eq!(check("(a + b) + (c + d)"), "(+ (+ a b) (+ c d))");
}

#[test]
fn a_ten_megabyte_input_is_parsed_or_refused() {
    // A sum of a million terms goes through every stage.
    let long_sum = "x+".repeat(1024 * 1024) + "x";
    assert_eq!(value_at(&long_sum, 1.0), (1024 * 1024 + 1).to_string());
    // Ten megabytes of arguments parse and check.
    let arguments = "MAX(".to_string() + &"x, ".repeat(3 * 1024 * 1024) + "x)";
    let tree = parse(&arguments).expect("a long argument list parses");
    assert_eq!(tree.span.len(), arguments.len());
    assert!(mbexpr::check(&tree).is_ok());
}

#[test]
fn blanks_are_spaces_tabs_and_line_breaks() {
    for text in [
        "a\t+\tb",
        "a\n+\r\nb",
        "a\u{b}+\u{c}b",
        " a + b ",
        "F (a ,\tb )",
    ] {
        let expected = if text.starts_with('F') {
            "(F a b)"
        } else {
            "(+ a b)"
        };
        assert_eq!(check(text), expected, "{text:?}");
    }
    // A no-break space (as pasted from a document) is refused where it stands.
    assert_eq!(
        check("a\u{a0}+ b"),
        "error 1:2: unexpected character `\u{a0}`"
    );
    // So are the control characters between the line breaks and the space,
    // which the grammar's one range of blanks holds (the pre-check refuses
    // them), wherever they stand; the characters around them are blanks.
    for control in ['\u{e}', '\u{1b}', '\u{1f}'] {
        for (text, column) in [
            (format!("{control}a + b"), 1),
            (format!("a +{control}b"), 4),
            (format!("F(a,\t{control})"), 6),
        ] {
            assert_eq!(
                check(&text),
                format!("error 1:{column}: unexpected character `{control}`"),
                "{text:?}"
            );
        }
    }
    assert_eq!(check("\u{8}a"), "error 1:1: unexpected character `\u{8}`");
    assert!(check("a\u{21}").starts_with("error 1:2: `!` is not an operator"));
}
