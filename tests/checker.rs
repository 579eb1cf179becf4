//! Check stage: resolved trees and every kind of refusal, one case per line.

use mbexpr::{Location, check as check_tree, parse};

/// The checked tree (`$name` variables, `@marker`, `#object`), or every error
/// as `LINE:COL: message`.
fn check(input: &str) -> String {
    let tree = match parse(input) {
        Ok(tree) => tree,
        Err(error) => return format!("syntax error: {error}"),
    };
    match check_tree(&tree) {
        Ok(checked) => checked.root.to_string(),
        Err(errors) => errors
            .iter()
            .map(|error| format!("{}: {error}", Location::of(input, error.span().start)))
            .collect::<Vec<_>>()
            .join("\n     "),
    }
}

fn table(cases: &str) -> String {
    crate::table(cases, check)
}

#[test]
fn names_resolve_to_functions_constants_and_references() {
    insta::assert_snapshot!(table(
        r"
        step(time, 0, 0, 1, 10)
        Pi*dtor*RTOD + mode
        k_stop*x
        DX(2, 1, 1) + DM(.m.a, .m.b) + VX(i, 0, 0, j)
        ORIENT(27, 1, 0201, 0101)
        SFORCE(1002, 0, 8, 9006936)
        VARVAL(3) + ARYVAL(.m.arr, 2) + DIF(1) + DIF1(1)
        CUBSPL(time, 0, .robot_arm.PR1_spline, 0)
        DELAY(DZ(30102030), 1, 0)
        USER(1.05, 0.005, 1.0208)
        MAX(a, b, c, d, e)
        POLY(x, 0, 1, 2, 3)
        +x
        "
    ));
}

#[test]
fn refusals() {
    insta::assert_snapshot!(table(
        r"
        STPE(x, 0, 0, 1, 1)
        COSIN(X)+TAN(X)*EXP(X)
        59*US(18,81)*COS(A)
        PI(2)
        TIME(1)
        STEP + 1
        IF(VR: 1, 2, 3)
        STEP(x, 0, 0, 1)
        MAX(a)
        POLY(x, 0)
        DX()
        DX(1, 2, 3, 4)
        DX(1.5, 2)
        DX(a + b)
        DX(-1)
        VARVAL(x + 1)
        SFORCE(1, x, 8, 2)
        SFORCE(1, 0.5, 8, 2)
        ARYVAL(3, i)
        STEP(x, 2, 0, 1, 1)
        STEP5(x, 1, 0, 1, 1)
        HAVSIN(x, 1, 0, -1, 1)
        BISTOP(x, v, 5, -5, 1e5, 2.2, 100, 0.1)
        BISTOP(x, v, -5, 5, 1e5, 2.2, 100, 0)
        BISTOP(x, v, -5, 5, -1, 2.2, 100, 0.1)
        IMPACT(x, v, 1, 1e4, 0, 10, 0.1)
        IMPACT(x, v, 1, 1e4, -2*1.5, 10, 0.1)
        IMPACT(x, v, 1, 1e4, 1.5, -10, 0.1)
        IMPACT(x, v, 1, 1e4, 1.5, 10, -0.1)
        MOD(x, 0)
        SWEEP(x, 1, 2, 1, 1, 5, 0.5)
        STPE(x) + DX(1.5) + BISTOP(x, v, 1, 1, 1, 1, 1, 1)
        STEP(x, 1e300, 0, -1e300, 1)
        IMPACT(x, v, 1, 1e4, 1.5, 10, -1e-300)
        BISTOP(x, v, 0.1 + 0.2, 0.1, 1e5, 2.2, 100, 0.1)
        "
    ));
}

#[test]
fn every_function_is_found_by_its_name_in_any_case() {
    use mbexpr::catalog::Function;
    for &function in Function::ALL {
        let name = function.name();
        assert_eq!(Function::lookup(name), Some(function), "{name}");
        assert_eq!(
            Function::lookup(&name.to_lowercase()),
            Some(function),
            "{name}"
        );
    }
    for unknown in ["", "NOSUCH", "SIN ", "ſin", "ΣIN"] {
        assert_eq!(Function::lookup(unknown), None, "{unknown:?}");
    }
    assert_eq!(Function::lookup(&"STEP".repeat(20)), None);
}

/// Constants that fail whenever they are evaluated are refused by the check,
/// with the message evaluation would give (issue 19.5); a branch of an IF
/// that a constant condition does not choose, or that a varying one may not,
/// is not evaluated, so it may hold them.
#[test]
fn constants_that_always_fail() {
    insta::assert_snapshot!(table(
        r"
        LOG(0)
        1/0
        SQRT(-1)
        x + 2*LOG10(-1)
        STEP(x, 0/0, 0, 1, 1)
        IMPACT(x, v, 0, 1, SQRT(-1), 1, 1)
        EXP(1000)
        10**400
        0**-1
        (-8)**(1/3)
        ASIN(1.5) + ACOS(2)
        MOD(5, 0)
        MAX(1, 2, LOG(0))
        IF(-1: 1, 1/0, 2)
        IF(1: 1, 1/0, 2)
        IF(x: 1, 1/0, 2)
        IF(1/0: 1, 2, 3)
        STEP(x, LOG(1), 0, EXP(0), 1)
        STEP(x, 1 - 1, 0, 2 - 2, 1)
        x/0
        2*x/(1 - 1)*3
        IF(x: x/0, 1, 2)
        x/0.5
        "
    ));
}
