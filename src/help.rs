//! The reference of the language's functions, constants and system
//! variables, written from the catalog ([`crate::catalog`]): what each
//! means, its arguments, the rules they obey and an example with the value
//! mbexpr gives it. `docs/language.md` holds [`functions_reference`] (a
//! test keeps the two equal, so the page cannot drift from the code), and
//! the REPL's `:help NAME` prints [`topic`].

use std::fmt::Write;

use crate::Shown;
use crate::catalog::{ArgKind, Constant, Family, Function, MANY, Rule, SystemVariable};

/// The families in the order the reference presents them, each with its
/// heading and what its functions share.
const FAMILIES: [(Family, &str, &str); 8] = [
    (
        Family::Intrinsic,
        "FORTRAN intrinsics",
        "Angles are in radians (`30D` is 30 degrees in radians). A domain error (`LOG(0)`, `SQRT(-1)`, `ASIN(1.5)`) is an error that names the function and its place; `AINT` and `ANINT` have derivative 0, and `ABS`, `DIM`, `MAX`, `MIN`, `MOD` and `SIGN` take the derivative of the branch their value comes from.",
    ),
    (
        Family::Step,
        "Steps",
        "With `u = (x - x0)/(x1 - x0)`: the value is `h0` for `x <= x0`, `h1` for `x >= x1`, and the step's polynomial between. `x0 < x1` is required.",
    ),
    (
        Family::Contact,
        "Contact forces",
        "`x` is the deformation (typically `DX(i, j, j)`), `x'` its rate (`VX(i, j, j, j)`), `k` the stiffness, `e` the exponent, `cmax` the largest damping coefficient, reached at penetration `d`. The force is `k p**e` against the penetration `p` plus the damping `STEP(p, 0, 0, d, cmax)` times the rate, clamped so that it never pulls the bodies together; it is computed in penetration coordinates, so it keeps its digits at any size of gap (`docs/contact.md`).",
    ),
    (
        Family::Series,
        "Series and signals",
        "Functions of `x` (most often `TIME`) about the origin `x0`; a series takes up to 31 coefficients.",
    ),
    (
        Family::Measure,
        "Kinematic measures",
        "Between markers (ids or names) of a scene or a model. Trailing markers may be left out and are then the ground frame; `0` written in a place is ground. `i` is measured from `j`, resolved along the axes of `k`, with time derivatives taken in frame `l`. Angles are in radians.",
    ),
    (
        Family::ModelData,
        "Model data",
        "Values from the statements of a model (VARIABLE, ARRAY, DIFF, SPLINE, ...), by id: `eval --model` and `simulate` give them; elsewhere an evaluation says which statement is missing.",
    ),
    (
        Family::Solver,
        "Results of a running solver",
        "Forces of elements and joints, and delayed values: a model that uses them checks cleanly, and evaluating one outside a solver run is an error that says so.",
    ),
    (
        Family::User,
        "User subroutines",
        "Constants passed to a user-written subroutine: checked, never evaluated.",
    ),
];

/// An example of `function`, in the text a user would write.
fn example(function: Function) -> &'static str {
    use Function as F;
    match function {
        F::Abs => "ABS(-2.5)",
        F::Sin => "SIN(30D)",
        F::Cos => "COS(PI/3)",
        F::Tan => "TAN(45D)",
        F::Asin => "ASIN(0.5)*RTOD",
        F::Acos => "ACOS(0.5)*RTOD",
        F::Atan => "ATAN(1)*RTOD",
        F::Atan2 => "ATAN2(1, -1)*RTOD",
        F::Sinh => "SINH(1)",
        F::Cosh => "COSH(1)",
        F::Tanh => "TANH(0.5)",
        F::Exp => "EXP(1)",
        F::Log => "LOG(10)",
        F::Log10 => "LOG10(1000)",
        F::Sqrt => "SQRT(2)",
        F::Aint => "AINT(-2.7)",
        F::Anint => "ANINT(2.5)",
        F::Dim => "DIM(5, 3)",
        F::Max => "MAX(1, 7, 3)",
        F::Min => "MIN(1, 7, 3)",
        F::Mod => "MOD(-7, 3)",
        F::Sign => "SIGN(2, -0.1)",
        F::Step => "STEP(0.25, 0, 0, 1, 10)",
        F::Step5 => "STEP5(0.25, 0, 0, 1, 10)",
        F::Havsin => "HAVSIN(0.25, 0, 0, 1, 10)",
        F::Impact => "IMPACT(0.95, -0.5, 1, 1E5, 1.5, 50, 0.1)",
        F::Bistop => "BISTOP(1.05, 0.3, -1, 1, 1E4, 1.5, 50, 0.2)",
        F::Shf => "SHF(0.1, 0, 2, 2*PI, 0, 1)",
        F::Poly => "POLY(2, 1, 1, 2, 3)",
        F::Cheby => "CHEBY(0.5, 0, 1, 2, 3)",
        F::Forcos => "FORCOS(0.1, 0, 2*PI, 1, 0.5)",
        F::Forsin => "FORSIN(0.1, 0, 2*PI, 1, 0.5)",
        F::Sweep => "SWEEP(0.3, 1, 0, 1, 1, 10, 0.1)",
        F::Dx => "DX(ball, wall, wall)",
        F::Dy => "DY(ball, wall, wall)",
        F::Dz => "DZ(ball, wall, wall)",
        F::Dm => "DM(ball, wall)",
        F::Vx => "VX(ball, wall, wall, wall)",
        F::Vy => "VY(ball, wall, wall, wall)",
        F::Vz => "VZ(ball, wall, wall, wall)",
        F::Vm => "VM(ball, wall)",
        F::Vr => "VR(ball, wall)",
        F::Accx => "ACCX(ball, wall, wall, wall)",
        F::Accy => "ACCY(ball, wall, wall, wall)",
        F::Accz => "ACCZ(ball, wall, wall, wall)",
        F::Accm => "ACCM(ball, wall)",
        F::Wx => "WX(ball, wall, wall)",
        F::Wy => "WY(ball, wall, wall)",
        F::Wz => "WZ(ball, wall, wall)",
        F::Wm => "WM(ball, wall)",
        F::Wdtx => "WDTX(ball, wall, wall, wall)",
        F::Wdty => "WDTY(ball, wall, wall, wall)",
        F::Wdtz => "WDTZ(ball, wall, wall, wall)",
        F::Wdtm => "WDTM(ball, wall)",
        F::Ax => "AX(ball, wall)",
        F::Ay => "AY(ball, wall)",
        F::Az => "AZ(ball, wall)",
        F::Psi => "PSI(ball, wall)",
        F::Theta => "THETA(ball, wall)",
        F::Phi => "PHI(ball, wall)",
        F::Yaw => "YAW(ball, wall)",
        F::Pitch => "PITCH(ball, wall)",
        F::Roll => "ROLL(ball, wall)",
        F::Incang => "INCANG(11, 12, 13)",
        F::Orient => "ORIENT(1, 1, 11, 12)",
        F::Fx => "FX(11, 12)",
        F::Fy => "FY(11, 12)",
        F::Fz => "FZ(11, 12)",
        F::Fm => "FM(11, 12)",
        F::Tx => "TX(11, 12)",
        F::Ty => "TY(11, 12)",
        F::Tz => "TZ(11, 12)",
        F::Tm => "TM(11, 12)",
        F::Sforce => "SFORCE(1, 0, 2, 0)",
        F::Gforce => "GFORCE(1, 0, 2, 0)",
        F::Vforce => "VFORCE(1, 0, 2, 0)",
        F::Vtorq => "VTORQ(1, 0, 6, 0)",
        F::Joint => "JOINT(1, 0, 2, 0)",
        F::Jprim => "JPRIM(1, 0, 2, 0)",
        F::Motion => "MOTION(1, 0, 2, 0)",
        F::Beam => "BEAM(1, 0, 2, 0)",
        F::Bush => "BUSH(1, 0, 2, 0)",
        F::Field => "FIELD(1, 0, 2, 0)",
        F::Nforce => "NFORCE(1, 11, 2, 0)",
        F::Contact => "CONTACT(1, 0, 1, 0)",
        F::Spdp => "SPDP(1, 0, 1, 0)",
        F::Ptcv => "PTCV(1, 0, 2, 0)",
        F::Cvcv => "CVCV(1, 0, 2, 0)",
        F::Delay => "DELAY(DX(11, 12), 0.1, 0)",
        F::Varval => "VARVAL(3)",
        F::Aryval => "ARYVAL(1, 2)",
        F::Dif => "DIF(1)",
        F::Dif1 => "DIF1(1)",
        F::Pinval => "PINVAL(1, 1)",
        F::Pouval => "POUVAL(1, 1)",
        F::Senval => "SENVAL(1)",
        F::Friction => "FRICTION(1, 6)",
        F::Akispl => "AKISPL(TIME, 0, 1)",
        F::Cubspl => "CUBSPL(TIME, 0, 1, 1)",
        F::Curve => "CURVE(0.5, 0, 1, 1)",
        F::Interp => "INTERP(TIME, 1, 1)",
        F::User => "USER(1, 2, 3)",
    }
}

/// What an argument of `kind` is.
fn kind_text(kind: ArgKind) -> &'static str {
    match kind {
        ArgKind::Value => "an expression",
        ArgKind::Marker => "a marker (id or name)",
        ArgKind::Object => "the id (or name) of a statement",
        ArgKind::Flag => "a constant whole number",
    }
}

/// How many arguments `function` takes, in words.
fn count_text(function: Function) -> String {
    let signature = function.signature();
    match (signature.min, signature.max) {
        (min, max) if min == max => format!("{min}"),
        (min, MANY) => format!("{min} or more"),
        (min, max) => format!("{min} to {max}"),
    }
}

/// The rule `rule` of `function` as an inequality of its parameters.
fn rule_text(function: Function, rule: Rule) -> String {
    let name = |position: usize| function.param_name(position);
    match rule {
        Rule::Less(a, b) => format!("`{} < {}`", name(a), name(b)),
        Rule::Positive(a) => format!("`{} > 0`", name(a)),
        Rule::NonNegative(a) => format!("`{} >= 0`", name(a)),
        Rule::NonZero(a) => format!("`{} != 0`", name(a)),
    }
}

/// The value of the constant expression `text`, when it has one outside a
/// scene or model.
fn value_of(text: &str) -> Option<f64> {
    let tree = crate::parse(text).ok()?;
    let checked = crate::check(&tree).ok()?;
    crate::compile::<&str>(&checked, &[]).ok()?.value(&[]).ok()
}

/// The entry of `function`: a heading line `NAME(params)`, then its
/// meaning, arguments, rules and example, one item a line.
fn function_entry(function: Function) -> (String, String) {
    let signature = function.signature();
    let mut body = String::new();
    let mut summary = signature.summary.to_string();
    if let Some(first) = summary.get_mut(..1) {
        first.make_ascii_uppercase();
    }
    let _ = writeln!(body, "{summary}.\n");
    let params: Vec<String> = signature
        .params
        .iter()
        .enumerate()
        .map(|(position, param)| match *param {
            "..." => format!(
                "... more of the same kind ({} in all)",
                count_text(function)
            ),
            param => format!("`{param}`: {}", kind_text(signature.kind(position))),
        })
        .collect();
    let optional = match signature.max {
        MANY => String::new(),
        max if signature.min < max && signature.family == Family::Measure => {
            "; markers left out at the end are the ground frame".to_string()
        }
        max if signature.min < max && !signature.params.contains(&"...") => {
            "; the last ones may be left out".to_string()
        }
        _ => String::new(),
    };
    let _ = writeln!(
        body,
        "- arguments ({}{optional}): {}",
        count_text(function),
        params.join("; ")
    );
    let rules = function.rules();
    if !rules.is_empty() {
        let rules: Vec<String> = rules
            .iter()
            .map(|&rule| rule_text(function, rule))
            .collect();
        let _ = writeln!(
            body,
            "- rules: {} (checked when the expression is, for constant arguments; at evaluation otherwise)",
            rules.join(", ")
        );
    }
    let example = example(function);
    let _ = match signature.family {
        Family::Intrinsic | Family::Step | Family::Contact | Family::Series => {
            match value_of(example) {
                Some(value) => writeln!(body, "- example: `{example}` = {}", Shown(value)),
                None => writeln!(body, "- example: `{example}`"),
            }
        }
        Family::Measure => writeln!(
            body,
            "- example: `{example}`, in a scene with markers `ball` and `wall` (`mbexpr eval \"{example}\" --scene examples/scenes/ball_between_walls.toml`)"
        ),
        Family::ModelData | Family::Solver => {
            writeln!(body, "- example: `{example}`, in a model")
        }
        Family::User => writeln!(body, "- example: `{example}`"),
    };
    (function.usage(), body)
}

/// The reference of every function, by family, in catalog order within
/// each: the generated part of `docs/language.md`.
pub fn functions_reference() -> String {
    let mut text = String::new();
    for (family, heading, intro) in FAMILIES {
        let _ = writeln!(text, "### {heading}\n\n{intro}\n");
        for &function in Function::ALL
            .iter()
            .filter(|function| function.family() == family)
        {
            let (usage, body) = function_entry(function);
            let _ = writeln!(text, "#### `{usage}`\n\n{body}");
        }
    }
    text
}

/// The help text of the function, constant or system variable `name` (in
/// any case), or `None` when the language has none of that name.
pub fn topic(name: &str) -> Option<String> {
    if let Some(function) = Function::lookup(name) {
        let (usage, body) = function_entry(function);
        return Some(format!("{usage}\n\n{}", body.trim_end()));
    }
    if let Some(constant) = Constant::lookup(name) {
        let meaning = match constant {
            Constant::Pi => "pi",
            Constant::Dtor => {
                "pi/180: multiplies degrees into radians (as does a D after a number: 30D)"
            }
            Constant::Rtod => "180/pi: multiplies radians into degrees",
        };
        return Some(format!(
            "{} = {}\n\n{meaning}",
            constant.name(),
            Shown(constant.value())
        ));
    }
    SystemVariable::lookup(name).map(|variable| match variable {
        SystemVariable::Time => "TIME\n\nThe current time: a variable like any other, which can be a derivative direction; 0 unless it is given (--set TIME=1.5, :set TIME = 1.5), as at the start of a run.".to_string(),
        SystemVariable::Mode => "MODE\n\nThe analysis mode: 1 kinematics, 3 initial conditions, 4 dynamics, 5 statics, 6 quasi-statics, 7 linear; 4 unless the host sets it.".to_string(),
    })
}
