//! Compile and evaluate: values, derivatives and evaluation errors, one case
//! per line: `EXPRESSION ; name=value ... ; wrt name,name ; order N`.

use mbexpr::{Order, check as check_expr, compile, parse};

/// Evaluates a case line and prints the value, gradient and Hessian, or the error.
fn check(case: &str) -> String {
    let mut parts = case.split(';').map(str::trim);
    let text = parts.next().unwrap_or_default();
    let mut names = Vec::new();
    let mut values = Vec::new();
    let mut wrt_names: Vec<&str> = Vec::new();
    let mut order = Order::Value;
    for part in parts {
        if let Some(list) = part.strip_prefix("wrt ") {
            wrt_names = list.split(',').map(str::trim).collect();
            order = order.max(Order::Gradient);
        } else if let Some(number) = part.strip_prefix("order ") {
            order = Order::from_number(number.parse().unwrap()).unwrap();
        } else {
            for assignment in part.split_whitespace() {
                let (name, value) = assignment.split_once('=').unwrap();
                names.push(name);
                values.push(value.parse::<f64>().unwrap());
            }
        }
    }
    let tree = match parse(text) {
        Ok(tree) => tree,
        Err(error) => return format!("syntax error: {error}"),
    };
    let checked = match check_expr(&tree) {
        Ok(checked) => checked,
        Err(errors) => return format!("check error: {}", errors[0]),
    };
    let program = match compile(&checked, &names) {
        Ok(program) => program,
        Err(errors) => return format!("compile error: {}", errors[0]),
    };
    let wrt: Vec<usize> = wrt_names
        .iter()
        .map(|name| program.input_index(name).unwrap())
        .collect();
    match program.evaluate(&values, &wrt, order) {
        Err(error) => {
            let span = error.span();
            format!("error at `{}`: {error}", &text[span.range()])
        }
        Ok(evaluation) => {
            let tidy = |value: f64| format!("{:.12e}", value + 0.0);
            let mut out = tidy(evaluation.value);
            if let Some(gradient) = evaluation.gradient {
                let entries: Vec<String> = gradient.iter().map(|&g| tidy(g)).collect();
                out += &format!(" | grad [{}]", entries.join(", "));
            }
            if let Some(hessian) = evaluation.hessian {
                let rows: Vec<String> = hessian
                    .row_iter()
                    .map(|row| row.iter().map(|&h| tidy(h)).collect::<Vec<_>>().join(", "))
                    .collect();
                out += &format!(" | hess [{}]", rows.join("; "));
            }
            out
        }
    }
}

fn table(cases: &str) -> String {
    crate::table(cases, check)
}

#[test]
fn arithmetic_and_constants() {
    insta::assert_snapshot!(table(
        r"
        2**3
        2**3**2
        -2**2
        (x-3)**3 ; x=1 ; wrt x ; order 2
        x**-2 ; x=2 ; wrt x ; order 2
        x**0.5 ; x=4 ; wrt x ; order 2
        x**y ; x=2 y=3 ; wrt x,y ; order 2
        PI + DTOR + RTOD
        90D
        MODE
        MODE ; MODE=1
        TIME*2 ; time=3 ; wrt TIME
        a*b ; a=2 b=5 ; wrt a ; order 2
        a*b ; a=2 b=5 ; wrt b,a ; order 2
        "
    ));
}

#[test]
fn every_function() {
    insta::assert_snapshot!(table(
        r"
        ABS(x) ; x=-2 ; wrt x ; order 2
        ABS(x) ; x=0 ; wrt x
        SIN(x)+COS(x)+TAN(x) ; x=0.3 ; wrt x ; order 2
        ASIN(x)+ACOS(x)+ATAN(x) ; x=0.3 ; wrt x ; order 2
        ATAN2(y, x) ; y=1 x=-1 ; wrt y,x ; order 2
        ATAN2(y, x) ; y=0 x=0 ; wrt y,x ; order 2
        SINH(x)+COSH(x)+TANH(x) ; x=0.3 ; wrt x ; order 2
        EXP(x)+LOG(x)+LOG10(x)+SQRT(x) ; x=2 ; wrt x ; order 2
        AINT(x)+ANINT(y) ; x=-2.7 y=2.5 ; wrt x,y
        ANINT(-2.5)
        DIM(a, b) ; a=3 b=1 ; wrt a,b
        DIM(a, b) ; a=1 b=3 ; wrt a,b
        MAX(a, b, c) ; a=1 b=3 c=2 ; wrt a,b,c
        MIN(a, b) ; a=1 b=1 ; wrt a,b
        MOD(a, b) ; a=-7 b=3 ; wrt a,b
        SIGN(a, b) ; a=-2 b=0 ; wrt a
        SIGN(a, b) ; a=2 b=-1 ; wrt a
        STEP(x, 0, 0, 1, 10) ; x=0.5 ; wrt x ; order 2
        STEP(x, 0, 0, 1, 10) ; x=0 ; wrt x ; order 2
        STEP(x, 0, 0, 1, 10) ; x=1 ; wrt x ; order 2
        STEP5(x, 0, 0, 1, 10) ; x=0.25 ; wrt x ; order 2
        HAVSIN(x, 0, 0, 1, 10) ; x=0.25 ; wrt x ; order 2
        SHF(x, 0, 2, 3, 0.5, 1) ; x=0.25 ; wrt x ; order 2
        POLY(x, 1, 1, 2, 3) ; x=2 ; wrt x ; order 2
        CHEBY(x, 0, 1, 2, 3) ; x=0.5 ; wrt x ; order 2
        FORCOS(x, 0, 2, 1, 2, 3) ; x=0.5 ; wrt x ; order 2
        FORSIN(x, 0, 2, 1, 2, 3) ; x=0.5 ; wrt x ; order 2
        SWEEP(x, 2, 1, 1, 3, 5, 0.5) ; x=2 ; wrt x ; order 2
        IF(x: 1, 2, 3) ; x=-1
        IF(x: 1, 2, 3) ; x=0
        IF(x: 1, 2, 3) ; x=1
        IF(x: 1/0, 2, x**2) ; x=3 ; wrt x ; order 2
        "
    ));
}

#[test]
fn contact_branches() {
    insta::assert_snapshot!(table(
        r"
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=0 v=0.7 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=10 v=0.7 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=-10 v=0.7 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=10.05 v=0.7 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=10.1 v=0.7 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=10.5 v=0.7 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=10.05 v=-100 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=-10.05 v=-0.7 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=-10.5 v=0.7 ; wrt x,v ; order 2
        BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) ; x=-10.05 v=100 ; wrt x,v ; order 2
        BISTOP(x, v, -1, 1, 1e3, 1, 10, 0.1) ; x=1.05 v=0 ; wrt x,v ; order 2
        BISTOP(x, v, -1, 1, 1e3, 0.8, 10, 0.1) ; x=1.05 v=0 ; wrt x,v ; order 2
        BISTOP(x, v, -1, 1, 1e3, 1.5, 10, 0.1) ; x=1.05 v=0 ; wrt x,v ; order 2
        BISTOP(x, v, -1, 1, 1e3, e, 10, 0.1) ; x=1.05 v=0 e=1.5 ; wrt x,e ; order 2
        IMPACT(x, v, 1, 1e4, 1.5, 10, 0.1) ; x=2 v=-1 ; wrt x,v ; order 2
        IMPACT(x, v, 1, 1e4, 1.5, 10, 0.1) ; x=1 v=-1 ; wrt x,v ; order 2
        IMPACT(x, v, 1, 1e4, 1.5, 10, 0.1) ; x=0.95 v=-1 ; wrt x,v ; order 2
        IMPACT(x, v, 1, 1e4, 1.5, 10, 0.1) ; x=0.5 v=-1 ; wrt x,v ; order 2
        IMPACT(x, v, 1, 1e4, 1.5, 10, 0.1) ; x=0.95 v=1e6 ; wrt x,v ; order 2
        IMPACT(x, v, 1, 0, 1.5, 10, 0.1) ; x=0.95 v=-1 ; wrt x,v ; order 2
        "
    ));
}

#[test]
fn evaluation_errors_name_the_operation() {
    insta::assert_snapshot!(table(
        r"
        LOG(x) ; x=0
        LOG10(x) ; x=-1
        SQRT(x) ; x=-1
        SQRT(x) ; x=0 ; wrt x
        ASIN(x) ; x=1.5
        ACOS(x) ; x=-1.5
        1/x ; x=0
        x**-1 ; x=0
        x**0.5 ; x=-1
        x**y ; x=-1 y=2 ; wrt y
        MOD(x, y) ; x=1 y=0
        EXP(x) ; x=1000
        x*1e308*10 ; x=1
        STEP(t, a, 0, b, 1) ; t=0 a=2 b=1
        BISTOP(x, v, a, 1, 1e5, 2.2, 100, 0.1) ; x=0 v=0 a=2
        BISTOP(x, v, -1, 1, k, 2.2, 100, 0.1) ; x=0 v=0 k=-1
        IMPACT(x, v, 1, 1e4, e, 10, d) ; x=0 v=0 e=0 d=1
        IMPACT(x, v, 1, 1e4, 1.5, 10, d) ; x=0 v=0 d=0
        IMPACT(x, v, 1, 1e4, 0.5, 10, 0.1) ; x=1e-300 v=0 ; wrt x ; order 2
        x ; x=1 ; wrt x
        SQRT(x) ; x=-1e300
        LOG(x) ; x=-2.5e-310
        ASIN(x) ; x=1e30
        x/y ; x=-1e300 y=0
        x**0.5 ; x=-1.5e-300
        x**y ; x=-1e300 y=0.5 ; wrt y
        STEP(t, a, 0, b, 1) ; t=0 a=1e300 b=-1e300
        IMPACT(x, v, 1, 1e4, 1.5, 10, d) ; x=0 v=0 d=-1e-300
        "
    ));
}

/// Issue 17.2: functions whose plain formula overflows or underflows on the
/// way to a result that is a double.
#[test]
fn intermediates_beyond_the_range_where_the_result_is_not() {
    insta::assert_snapshot!(table(
        r"
        TANH(x) ; x=1000 ; wrt x ; order 2
        TANH(x) ; x=-1000 ; wrt x ; order 2
        TANH(x) ; x=20 ; wrt x ; order 2
        TANH(x) ; x=5e-324 ; wrt x ; order 2
        TANH(BISTOP(v, x, -1.65, 0.03, 8473.3, 1.82, 19.88, 0.641)) ; v=1.047 x=-0.668 ; wrt x,v ; order 2
        SINH(x) ; x=710 ; wrt x ; order 2
        COSH(x) ; x=-710 ; wrt x ; order 2
        ATAN2(y, x) ; y=1e200 x=-1e200 ; wrt y,x ; order 2
        ATAN2(y, x) ; y=1e-200 x=1e-200 ; wrt y,x ; order 1
        ATAN(x) ; x=1e100 ; wrt x ; order 2
        ATAN(x) ; x=1e160 ; wrt x ; order 1
        SQRT(x) ; x=5e-324 ; wrt x
        LOG10(x) ; x=4e-309 ; wrt x
        LOG(x) ; x=1e160 ; wrt x ; order 2
        x/y ; x=1e300 y=1e300 ; wrt x,y ; order 2
        x/y ; x=1e-311 y=1e-310 ; wrt x
        x**y ; x=1e300 y=1.005 ; wrt x,y ; order 2
        x**-1030 ; x=2 ; wrt x
        MOD(x, y) ; x=1e300 y=3e-300 ; wrt x
        IMPACT(x, v, 0, 1e-300, 3, 0, 1) ; x=-1e200 v=0 ; wrt x ; order 2
        IMPACT(x, v, 0, 1, 2, 1, 1e-160) ; x=-5e-161 v=0 ; wrt x,v ; order 2
        IMPACT(x, v, 0, 1, 2, 1, 1e-200) ; x=-5e-201 v=0 ; wrt x,v ; order 1
        BISTOP(x, v, -10, 10, 1e308, 3, 100, 0.1) ; x=12 v=-7e306
        BISTOP(x, v, -10, 10, 1e308, 3, 100, 0.1) ; x=12 v=-1e307
        BISTOP(x, v, -10, 10, 1e308, 3, 100, 0.1) ; x=12 v=-1e306
        BISTOP(x, v, -10, 10, k, e, c, d) ; x=12 v=-7e306 k=1e308 e=3 c=100 d=0.1 ; wrt v,k,c
        STEP(x, 0, -1e308, 1, 1e308) ; x=0.25
        STEP5(x, 0, 0, 1e-300, 1) ; x=5e-301 ; wrt x ; order 2
        HAVSIN(x, 0, -1e308, 1, 1e308) ; x=0.01 ; wrt x
        SHF(x, y, 1, 1e-300, 0, 0) ; x=1e308 y=-1e308 ; wrt x ; order 2
        POLY(x, y, 0, 0.25) ; x=1e308 y=-1e308 ; wrt x
        CHEBY(x, 0, 1, 0, 0) ; x=1e200 ; wrt x ; order 2
        FORCOS(x, 0, 1e300, 1, 1, 1, 1) ; x=100000000 ; wrt x
        SWEEP(x, 1, 0, 1, 1e300, 2, 1) ; x=1e200 ; wrt x ; order 2
        "
    ));
}

#[test]
fn compile_errors_name_what_is_missing() {
    insta::assert_snapshot!(table(
        r"
        x + y ; x=1
        stifness*2 ; stiffness=1
        TIME
        DX(2, 1, 1)
        VARVAL(3)
        ARYVAL(.m.arr, 2)
        FX(12, 3)
        SFORCE(1002, 0, 8, 9006936)
        USER(1, 2)
        "
    ));
}

#[test]
fn a_constant_expression_compiles_to_no_instruction() {
    let checked = check_expr(&parse("2*PI*STEP(0.5, 0, 0, 1, 1) + SIN(90D)").unwrap()).unwrap();
    let program = compile::<&str>(&checked, &[]).unwrap();
    assert!(program.is_empty(), "{program}");
    assert_eq!(program.value(&[]).unwrap(), std::f64::consts::PI + 1.0);
}

#[test]
fn each_subexpression_is_computed_once() {
    let checked = check_expr(&parse("SIN(x)*SIN(x) + SIN(x)").unwrap()).unwrap();
    let program = compile(&checked, &["x"]).unwrap();
    insta::assert_snapshot!(program.to_string());
}

#[test]
fn only_the_chosen_branch_is_run() {
    let checked = check_expr(&parse("IF(x: LOG(x), 0, LOG(x) + SIN(x))").unwrap()).unwrap();
    let program = compile(&checked, &["x"]).unwrap();
    insta::assert_snapshot!(program.to_string());
    assert_eq!(program.value(&[0.0]).unwrap(), 0.0);
    assert!(program.value(&[-1.0]).is_err());
}

#[test]
fn contact_laws_with_constant_parameters_share_their_stops() {
    let text = "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1) + BISTOP(v, x, -10, 10, 1e5, 2.2, 100, 0.1) + IMPACT(x, v, 1, 1e3, 1.5, 10, k)";
    let checked = check_expr(&parse(text).unwrap()).unwrap();
    let program = compile(&checked, &["x", "v", "k"]).unwrap();
    insta::assert_snapshot!(program.to_string());
}

#[test]
fn constant_and_varying_contact_parameters_give_the_same_numbers() {
    // `k` as an input takes the general path; as a literal, the table of stops.
    let varying = "BISTOP(x, v, -10, 10, k, 2.2, 100, 0.1)";
    let constant = "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)";
    let compiled = |text: &str| {
        let checked = check_expr(&parse(text).unwrap()).unwrap();
        compile(&checked, &["x", "v", "k"]).unwrap()
    };
    let (varying, constant) = (compiled(varying), compiled(constant));
    for x in [-10.2, -10.05, -10.0, 0.0, 10.0, 10.01, 10.05, 10.2] {
        for v in [-3.0, -0.7, 0.0, 0.7, 3.0] {
            let point = [x, v, 1e5];
            let a = varying.evaluate(&point, &[0, 1], Order::Hessian).unwrap();
            let b = constant.evaluate(&point, &[0, 1], Order::Hessian).unwrap();
            assert_eq!(a, b, "at x = {x}, v = {v}");
        }
    }
}

#[test]
fn a_reused_evaluator_follows_its_directions_from_call_to_call() {
    use num_dual::DualDVec64;
    let checked = check_expr(&parse("x*x*v + 3*t").unwrap()).unwrap();
    // `unused` is an input the expression does not read.
    let program = compile(&checked, &["x", "v", "t", "unused"]).unwrap();
    let point = [2.0, 5.0, 7.0, 1.0];
    let mut evaluator = program.evaluator::<DualDVec64>();
    let mut gradient = |wrt: &[usize]| match evaluator.derivatives(&point, wrt) {
        Ok(result) => format!("{} {:?}", result.value, result.gradient.unwrap().as_slice()),
        Err(error) => error.to_string(),
    };
    // Each call against a fresh evaluator, which caches nothing.
    let fresh = |wrt: &[usize]| {
        let result = program.evaluate(&point, wrt, Order::Gradient).unwrap();
        format!("{} {:?}", result.value, result.gradient.unwrap().as_slice())
    };
    for wrt in [&[0, 1][..], &[1, 0], &[2], &[], &[3, 0], &[0, 1]] {
        assert_eq!(gradient(wrt), fresh(wrt), "wrt {wrt:?}");
    }
    // A refused list of directions does not disturb the next call.
    assert!(gradient(&[0, 0]).contains("named twice"));
    assert!(gradient(&[4]).contains("only 4 inputs"));
    assert_eq!(gradient(&[2, 1]), fresh(&[2, 1]));
    assert_eq!(gradient(&[2, 1]), "41 [3.0, 4.0]");
}
