//! Every function at arguments of magnitude 1e3, 1e30, 1e300 and 5e-324
//! (issue 17.2): the value and the derivatives are finite wherever the
//! mathematical ones are, an error only where one of them is beyond the
//! range of a double, and they agree with `f64`'s own function where there
//! is one.
//!
//! The references are independent of the laws' code: for the intrinsics
//! and powers, the derivatives in closed form as logarithms of their
//! magnitudes (which exist beyond the range of a double); for the laws
//! with many parameters (steps, contact, series, splines), the law at unit
//! scale, where it is checked against mpmath (`tests/reference.rs`), and
//! the exact scaling of the law by powers of two: `STEP(s x, s x0, H h0,
//! s x1, H h1) = H STEP(x, x0, h0, x1, h1)`, with `d/dx` scaled by `H/s`.

use std::f64::consts::{LN_2, LN_10};

use mbexpr::laws::spline::{Method, Spline, SplineData};
use mbexpr::number::{Directional, Number};
use mbexpr::{Evaluation, Order};
use num_dual::Dual2SVec64;
use proptest::prelude::*;

/// The value and derivatives of `text` in its inputs `names` at `values`,
/// with derivatives in the inputs `wrt`.
fn evaluate(
    text: &str,
    names: &[&str],
    values: &[f64],
    wrt: &[usize],
) -> Result<Evaluation, String> {
    let checked = mbexpr::check(&mbexpr::parse(text).unwrap()).unwrap();
    let program = mbexpr::compile(&checked, names).unwrap();
    program
        .evaluate(values, wrt, Order::Hessian)
        .map_err(|error| error.to_string())
}

/// A number with the sign and the natural logarithm of its magnitude: the
/// exact value of a derivative even where it is beyond the range of a double.
#[derive(Clone, Copy, Debug)]
struct Logarithmic {
    sign: f64,
    log: f64,
}

impl Logarithmic {
    fn of(value: f64) -> Logarithmic {
        Logarithmic {
            sign: if value == 0.0 { 0.0 } else { value.signum() },
            log: value.abs().ln(),
        }
    }

    fn new(sign: f64, log: f64) -> Logarithmic {
        Logarithmic { sign, log }
    }

    /// Beyond the largest double (allowing for rounding at the edge).
    fn overflows(self) -> bool {
        self.sign != 0.0 && self.log > f64::MAX.ln() + 1e-12
    }

    /// Below the smallest normal double, where digits are lost anyway.
    fn is_subnormal(self) -> bool {
        self.sign == 0.0 || self.log < f64::MIN_POSITIVE.ln() + 1e-9
    }

    fn near_the_edge(self) -> bool {
        self.sign != 0.0 && (self.log - f64::MAX.ln()).abs() < 1e-9
    }
}

/// How `got` compares with the exact `want`: `None` if they agree.
fn disagreement(got: f64, want: Logarithmic, what: &str) -> Option<String> {
    if !got.is_finite() {
        return Some(format!("{what} is {got}"));
    }
    if want.overflows() {
        return Some(format!(
            "{what} is {got}, but exactly it is beyond the range"
        ));
    }
    if want.is_subnormal() {
        return (got.abs() > 1.01 * f64::MIN_POSITIVE)
            .then(|| format!("{what} is {got}, exactly e^{} (below 2.2e-308)", want.log));
    }
    let exact = want.sign * want.log.exp();
    let relative = (got - exact).abs() / exact.abs();
    // The reference's own rounding: exp of a logarithm of up to 745.
    (relative > 1e-11)
        .then(|| format!("{what} is {got}, exactly {exact} (relative error {relative:e})"))
}

/// Whether the spring's and the damper's parts of a contact law at `base`
/// cancel in some entry (value, gradient or Hessian in `x` and `v`) to less
/// than a fiftieth of their sizes. At the extreme scales each part is exact
/// only to about 2e-13 (the power `p^e` formed through logarithms of up to
/// 745), and their sum to that times how much they cancel, which passes the
/// 1e-11 a scaling is held to: a draw with the spring's second derivative
/// at -829 and the damper's at 840 summed to 11 to 1e-11.
fn spring_and_damper_cancel(text: &str, names: &[&str], base: &[f64], two_sided: bool) -> bool {
    let (stiffness, damping) = if two_sided { (4, 6) } else { (3, 5) };
    let part = |zeroed: usize| {
        let mut values = base.to_vec();
        values[zeroed] = 0.0;
        evaluate(text, names, &values, &[0, 1]).ok()
    };
    let entries = |evaluation: &Evaluation| -> Vec<f64> {
        let mut entries = vec![evaluation.value];
        entries.extend(evaluation.gradient.as_ref().unwrap().iter());
        entries.extend(evaluation.hessian.as_ref().unwrap().iter());
        entries
    };
    let (Some(whole), Some(spring), Some(damper)) = (
        evaluate(text, names, base, &[0, 1]).ok(),
        part(damping),
        part(stiffness),
    ) else {
        return false;
    };
    let (whole, spring, damper) = (entries(&whole), entries(&spring), entries(&damper));
    // A sum clamped to zero is exact.
    (0..whole.len())
        .any(|i| whole[i] != 0.0 && 50.0 * whole[i].abs() < spring[i].abs() + damper[i].abs())
}

/// Checks an evaluation against exact entries (value, gradient, Hessian in
/// the order of the evaluation's directions): an error only where one of
/// them is beyond the range of a double, else every entry within rounding.
fn agrees(
    got: &Result<Evaluation, String>,
    value: Logarithmic,
    gradient: &[Logarithmic],
    hessian: &[Logarithmic],
) -> Result<(), String> {
    let all = || {
        std::iter::once(value)
            .chain(gradient.iter().copied())
            .chain(hessian.iter().copied())
    };
    match got {
        Err(error) => {
            if all().any(|entry| entry.overflows() || entry.near_the_edge()) {
                Ok(())
            } else {
                Err(format!("error `{error}` where every entry is a double"))
            }
        }
        Ok(evaluation) => {
            let mut problems = Vec::new();
            problems.extend(disagreement(evaluation.value, value, "the value"));
            let got_gradient = evaluation.gradient.as_ref().unwrap();
            for (index, want) in gradient.iter().enumerate() {
                problems.extend(disagreement(
                    got_gradient[index],
                    *want,
                    &format!("gradient[{index}]"),
                ));
            }
            let got_hessian = evaluation.hessian.as_ref().unwrap();
            for (index, want) in hessian.iter().enumerate() {
                problems.extend(disagreement(
                    got_hessian.as_slice()[index],
                    *want,
                    &format!("hessian[{index}]"),
                ));
            }
            if problems.is_empty() {
                Ok(())
            } else {
                Err(problems.join("; "))
            }
        }
    }
}

/// `ln cosh x` for any x, `ln |sinh x|` for x != 0.
fn ln_cosh(x: f64) -> f64 {
    let a = x.abs();
    a + (-2.0 * a).exp().ln_1p() - LN_2
}

fn ln_sinh(x: f64) -> f64 {
    let a = x.abs();
    a + (-(-2.0 * a).exp_m1()).ln() - LN_2
}

/// `ln (1 + x^2)` without overflow.
fn ln_one_plus_square(x: f64) -> f64 {
    if x.abs() <= 1.0 {
        (x * x).ln_1p()
    } else {
        2.0 * x.abs().ln() + (1.0 / (x * x)).ln_1p()
    }
}

/// f64's own function and the exact first and second derivatives of the
/// intrinsic `name` at `x`; `None` outside its domain.
fn intrinsic(name: &str, x: f64) -> Option<(f64, Logarithmic, Logarithmic)> {
    let l = Logarithmic::new;
    let ln = x.abs().ln();
    Some(match name {
        "SIN" => (x.sin(), Logarithmic::of(x.cos()), Logarithmic::of(-x.sin())),
        "COS" => (
            x.cos(),
            Logarithmic::of(-x.sin()),
            Logarithmic::of(-x.cos()),
        ),
        // 1/cos^2 and 2 tan / cos^2.
        "TAN" => {
            let ln_cos = x.cos().abs().ln();
            (
                x.tan(),
                l(1.0, -2.0 * ln_cos),
                l(x.tan().signum(), LN_2 + x.tan().abs().ln() - 2.0 * ln_cos),
            )
        }
        "ASIN" | "ACOS" if x.abs() <= 1.0 => {
            // 1/sqrt(1 - x^2) and x/(1 - x^2)^1.5, for |x| far below 1 here.
            let room = ((1.0 - x) * (1.0 + x)).ln();
            let sign = if name == "ASIN" { 1.0 } else { -1.0 };
            let value = if name == "ASIN" { x.asin() } else { x.acos() };
            (
                value,
                l(sign, -0.5 * room),
                l(sign * x.signum(), ln - 1.5 * room),
            )
        }
        "ASIN" | "ACOS" => return None,
        "ATAN" => {
            let ln_slope = -ln_one_plus_square(x);
            (
                x.atan(),
                l(1.0, ln_slope),
                l(-x.signum(), LN_2 + ln + 2.0 * ln_slope),
            )
        }
        "SINH" => (x.sinh(), l(1.0, ln_cosh(x)), l(x.signum(), ln_sinh(x))),
        "COSH" => (x.cosh(), l(x.signum(), ln_sinh(x)), l(1.0, ln_cosh(x))),
        // sech^2 and -2 tanh sech^2.
        "TANH" => (
            x.tanh(),
            l(1.0, -2.0 * ln_cosh(x)),
            l(-x.signum(), LN_2 + x.tanh().abs().ln() - 2.0 * ln_cosh(x)),
        ),
        "EXP" => (x.exp(), l(1.0, x), l(1.0, x)),
        "LOG" if x > 0.0 => (x.ln(), l(1.0, -ln), l(-1.0, -2.0 * ln)),
        "LOG10" if x > 0.0 => (
            x.log10(),
            l(1.0, -ln - LN_10.ln()),
            l(-1.0, -2.0 * ln - LN_10.ln()),
        ),
        "SQRT" if x > 0.0 => (
            x.sqrt(),
            l(1.0, -LN_2 - 0.5 * ln),
            l(-1.0, -2.0 * LN_2 - 1.5 * ln),
        ),
        "LOG" | "LOG10" | "SQRT" => return None,
        "ABS" => (
            x.abs(),
            l(if x < 0.0 { -1.0 } else { 1.0 }, 0.0),
            Logarithmic::of(0.0),
        ),
        _ => unreachable!("{name}"),
    })
}

const INTRINSICS: [&str; 15] = [
    "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SINH", "COSH", "TANH", "EXP", "LOG", "LOG10",
    "SQRT", "ABS", "ATAN2",
];

/// A double of magnitude 1e3, 1e30, 1e300 (times 1 to 10), or a small
/// multiple of 5e-324, of either sign.
fn magnitude() -> impl Strategy<Value = f64> {
    let sign = prop::sample::select(vec![1.0, -1.0]);
    let normal = (prop::sample::select(vec![1e3, 1e30, 1e300]), 1.0f64..10.0)
        .prop_map(|(power, mantissa)| power * mantissa);
    let tiny = (1u32..1000).prop_map(|multiple| 5e-324 * f64::from(multiple));
    (sign, prop_oneof![normal, tiny]).prop_map(|(sign, magnitude)| sign * magnitude)
}

/// The exact partial derivatives of ATAN2(y, x): `[f_y, f_x]` and the
/// Hessian `[f_yy, f_yx, f_xy, f_xx]`.
fn atan2_slopes(y: f64, x: f64) -> ([Logarithmic; 2], [Logarithmic; 4]) {
    let l = Logarithmic::new;
    let (big, small) = (x.abs().max(y.abs()), x.abs().min(y.abs()));
    let ln_r2 = 2.0 * big.ln() + (small / big * (small / big)).ln_1p();
    let (ln_x, ln_y) = (x.abs().ln(), y.abs().ln());
    let sign = |value: f64| if value == 0.0 { 0.0 } else { value.signum() };
    let cross = l(sign(-x * y), LN_2 + ln_x + ln_y - 2.0 * ln_r2);
    // (y^2 - x^2) / r^4 = (|y| - |x|)(|y| + |x|) / r^4.
    let mixed = l(
        sign(y.abs() - x.abs()),
        (y.abs() - x.abs()).abs().ln() + (y.abs() + x.abs()).ln() - 2.0 * ln_r2,
    );
    let opposite = l(-cross.sign, cross.log);
    (
        [l(sign(x), ln_x - ln_r2), l(sign(-y), ln_y - ln_r2)],
        [cross, mixed, mixed, opposite],
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn intrinsics_at_every_magnitude(function in prop::sample::select(INTRINSICS.to_vec()), x in magnitude(), y in magnitude()) {
        if function == "ATAN2" {
            let got = evaluate("ATAN2(y, x)", &["y", "x"], &[y, x], &[0, 1]);
            let (gradient, hessian) = atan2_slopes(y, x);
            let result = agrees(&got, Logarithmic::of(y.atan2(x)), &gradient, &hessian);
            prop_assert!(result.is_ok(), "ATAN2({y:e}, {x:e}): {}", result.unwrap_err());
            if let Ok(evaluation) = got {
                prop_assert_eq!(evaluation.value, y.atan2(x));
            }
            return Ok(());
        }
        let text = format!("{function}(x)");
        let got = evaluate(&text, &["x"], &[x], &[0]);
        match intrinsic(function, x) {
            None => prop_assert!(got.as_ref().is_err_and(|error| error.contains("must")), "{text} at {x:e}: {got:?}"),
            Some((value, first, second)) => {
                let result = agrees(&got, Logarithmic::of(value), &[first], &[second]);
                prop_assert!(result.is_ok(), "{text} at {x:e}: {}", result.unwrap_err());
                if let Ok(evaluation) = got {
                    // f64's own function, to the bit.
                    prop_assert_eq!(evaluation.value, value + 0.0, "{} at {:e}", text, x);
                }
            }
        }
    }

    #[test]
    fn powers_at_every_magnitude(
        x in magnitude(),
        e in prop::sample::select(vec![2.0f64, 3.0, 7.0, -1.0, -2.0, 0.5, 1.5, 2.5, -0.5, 1.02, 0.1]),
        varying in any::<bool>(),
    ) {
        let whole = e == e.trunc();
        let got = if varying {
            evaluate("x**y", &["x", "y"], &[x, e], &[0, 1])
        } else {
            evaluate(&format!("x**{e:?}"), &["x"], &[x], &[0])
        };
        if x < 0.0 && (varying || !whole) {
            prop_assert!(got.is_err(), "{x:e}**{e}");
            return Ok(());
        }
        // e x^(e-1) and e (e-1) x^(e-2), signed for a negative x to a whole power.
        let ln = x.abs().ln();
        let sign = |power: f64| if x < 0.0 && power % 2.0 != 0.0 { -1.0 } else { 1.0 };
        let value = Logarithmic::new(sign(e), e * ln);
        let first = Logarithmic::new(e.signum() * sign(e - 1.0), e.abs().ln() + (e - 1.0) * ln);
        let second = Logarithmic::new((e * (e - 1.0)).signum() * sign(e - 2.0), (e * (e - 1.0)).abs().ln() + (e - 2.0) * ln);
        let result = if varying {
            // x^y ln x, x^(y-1) (1 + y ln x), x^y ln^2 x.
            let ln_ln = ln.abs().ln();
            let in_y = Logarithmic::new(ln.signum(), e * ln + ln_ln);
            let mixed_factor = 1.0 + e * ln;
            let mixed = Logarithmic::new(mixed_factor.signum(), (e - 1.0) * ln + mixed_factor.abs().ln());
            let in_y_twice = Logarithmic::new(1.0, e * ln + 2.0 * ln_ln);
            agrees(&got, value, &[first, in_y], &[second, mixed, mixed, in_y_twice])
        } else {
            agrees(&got, value, &[first], &[second])
        };
        prop_assert!(result.is_ok(), "{x:e}**{e} (varying {varying}): {}", result.unwrap_err());
        if let Ok(evaluation) = got {
            // f64's powf, to within the rounding of integer powers.
            let want = x.powf(e);
            prop_assert!((evaluation.value - want).abs() <= 4.0 * f64::EPSILON * want.abs(), "{x:e}**{e}: {} vs powf {want}", evaluation.value);
        }
    }
}

/// 2^n for the magnitudes: about 1e3, 1e30, 1e300, 1e-300 (exact scalings).
fn scale() -> impl Strategy<Value = f64> {
    prop::sample::select(vec![10, 100, 996, -996, -100]).prop_map(|n: i32| 2f64.powi(n))
}

/// A law at unit scale and scaled: `scaled` at the scaled inputs must be
/// `height` times `base` at the base inputs, each derivative in direction
/// `i` divided by `widths[i]` (the scale of that input), exactly where that
/// is a double, an error where it is not.
fn scales_exactly(
    text: &str,
    names: &[&str],
    base: &[f64],
    scaled: &[f64],
    wrt: &[usize],
    height: f64,
    widths: &[f64],
) -> Result<(), String> {
    let Ok(reference) = evaluate(text, names, base, wrt) else {
        return Ok(());
    };
    // Inputs that the scaling took out of the normal doubles say nothing.
    if base
        .iter()
        .zip(scaled)
        .any(|(base, scaled)| *base != 0.0 && !scaled.is_normal())
    {
        return Ok(());
    }
    let times = |value: f64, divisors: &[f64]| {
        let divisor: f64 = divisors.iter().map(|divisor| divisor.abs().ln()).sum();
        let sign =
            value.signum() * height.signum() * divisors.iter().map(|d| d.signum()).product::<f64>();
        if value == 0.0 {
            Logarithmic::of(0.0)
        } else {
            Logarithmic::new(sign, value.abs().ln() + height.abs().ln() - divisor)
        }
    };
    let gradient = reference.gradient.as_ref().unwrap();
    let hessian = reference.hessian.as_ref().unwrap();
    let n = wrt.len();
    let want_gradient: Vec<Logarithmic> =
        (0..n).map(|i| times(gradient[i], &[widths[i]])).collect();
    // Column-major, as the evaluation's matrix.
    let want_hessian: Vec<Logarithmic> = (0..n * n)
        .map(|index| {
            let (row, column) = (index % n, index / n);
            times(hessian[(row, column)], &[widths[row], widths[column]])
        })
        .collect();
    let got = evaluate(text, names, scaled, wrt);
    agrees(
        &got,
        times(reference.value, &[]),
        &want_gradient,
        &want_hessian,
    )
    .map_err(|problem| format!("{text} at {scaled:?} (unit scale {base:?}): {problem}"))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn steps_scale_exactly(
        shape in prop::sample::select(vec!["STEP", "STEP5", "HAVSIN"]),
        s in scale(), h in scale(), x in -0.5f64..1.5, x0 in -0.25f64..0.25, h0 in -2.0f64..2.0, h1 in -2.0f64..2.0,
    ) {
        let text = format!("{shape}(x, x0, h0, x1, h1)");
        let names = ["x", "x0", "h0", "x1", "h1"];
        let base = [x, x0, h0, 1.0, h1];
        let scaled = [s * x, s * x0, h * h0, s, h * h1];
        let result = scales_exactly(&text, &names, &base, &scaled, &[0], h, &[s]);
        prop_assert!(result.is_ok(), "{}", result.unwrap_err());
        // Heights of opposite sign near the largest double, whose rise
        // overflows. (Not with widths of 1e300: the second derivative, about
        // 1e-291 there, is the shape's curvature times 1/L^2, which
        // underflows before the rise multiplies it.)
        if s < 1e100 {
            let huge = 0.75 * f64::MAX;
            let result = scales_exactly(&text, &names, &[x, x0, -1.0, 1.0, 1.0], &[s * x, s * x0, -huge, s, huge], &[0], huge, &[s]);
            prop_assert!(result.is_ok(), "{}", result.unwrap_err());
        }
    }

    #[test]
    fn contact_laws_scale_exactly(
        s in prop::sample::select(vec![10, 100, 996, -996, -100]).prop_map(|n: i32| 4f64.powi(n / 2)),
        h in scale(), x in -1.5f64..0.0, v in -3.0f64..3.0, k in 0.0f64..1e3,
        e in prop::sample::select(vec![0.5, 1.0, 1.5, 2.0, 2.5, 3.0]), cmax in 0.0f64..1e3, d in 0.01f64..1.0,
        two_sided in any::<bool>(),
    ) {
        // s is a power of 4, so s^e is a power of 2 for these e: k s^-e exact.
        let text = if two_sided { "BISTOP(x, v, x1, x2, k, e, c, d)" } else { "IMPACT(x, v, x1, k, e, c, d)" };
        let names: &[&str] = if two_sided { &["x", "v", "x1", "x2", "k", "e", "c", "d"] } else { &["x", "v", "x1", "k", "e", "c", "d"] };
        let stiffness = h * k * s.powf(-e);
        prop_assume!(k == 0.0 || stiffness.is_normal());
        let (base, scaled): (Vec<f64>, Vec<f64>) = if two_sided {
            (vec![x, v, -0.5, 0.5, k, e, cmax, d], vec![s * x, h * v, -0.5 * s, 0.5 * s, stiffness, e, cmax, s * d])
        } else {
            (vec![x, v, -0.5, k, e, cmax, d], vec![s * x, h * v, -0.5 * s, stiffness, e, cmax, s * d])
        };
        prop_assume!(!spring_and_damper_cancel(text, names, &base, two_sided));
        // F(s x, h v) = h F(x, v) with k h s^-e: d/dx scales by h/s, d/dv by 1.
        let result = scales_exactly(text, names, &base, &scaled, &[0, 1], h, &[s, h]);
        prop_assert!(result.is_ok(), "{}", result.unwrap_err());
    }

    #[test]
    fn series_scale_exactly(
        s in scale(), h in scale(), x in -2.0f64..2.0, x0 in -1.0f64..1.0, w in 0.1f64..3.0,
        a in prop::collection::vec(-2.0f64..2.0, 4),
        which in 0usize..5,
    ) {
        // SWEEP's amplitude stays 1: the sweep is a product of the fade (whose
        // second derivative is below 1e-308 for widths of 1e300) and the
        // amplitude, and dual numbers multiply the factors' parts as they
        // are, so an amplitude of 1e300 cannot lift what underflowed.
        let h = if which == 4 { 1.0 } else { h };
        let per = |j: i32| s.powi(-j);
        let (text, names, base, scaled): (&str, Vec<&str>, Vec<f64>, Vec<f64>) = match which {
            0 => ("POLY(x, x0, a0, a1, a2, a3)", vec!["x", "x0", "a0", "a1", "a2", "a3"],
                  vec![x, x0, a[0], a[1], a[2], a[3]],
                  vec![s * x, s * x0, h * a[0], h * a[1] * per(1), h * a[2] * per(2), h * a[3] * per(3)]),
            1 => ("FORCOS(x, x0, w, a0, a1, a2, a3)", vec!["x", "x0", "w", "a0", "a1", "a2", "a3"],
                  vec![x, x0, w, a[0], a[1], a[2], a[3]],
                  vec![s * x, s * x0, w / s, h * a[0], h * a[1], h * a[2], h * a[3]]),
            2 => ("FORSIN(x, x0, w, a0, a1, a2, a3)", vec!["x", "x0", "w", "a0", "a1", "a2", "a3"],
                  vec![x, x0, w, a[0], a[1], a[2], a[3]],
                  vec![s * x, s * x0, w / s, h * a[0], h * a[1], h * a[2], h * a[3]]),
            3 => ("SHF(x, x0, a, w, phase, b)", vec!["x", "x0", "a", "w", "phase", "b"],
                  vec![x, x0, a[0], w, a[1], a[2]],
                  vec![s * x, s * x0, h * a[0], w / s, a[1], h * a[2]]),
            _ => ("SWEEP(x, a, x0, f0, x1, f1, fade)", vec!["x", "a", "x0", "f0", "x1", "f1", "fade"],
                  vec![x, a[0], -1.0, w, 1.5, 2.0 * w, 0.5],
                  vec![s * x, h * a[0], -s, w / s, 1.5 * s, 2.0 * w / s, 0.5 * s]),
        };
        let result = scales_exactly(text, &names, &base, &scaled, &[0], h, &[s]);
        prop_assert!(result.is_ok(), "{}", result.unwrap_err());
        // CHEBY is no function of x / s, but scales with its coefficients.
        let result = scales_exactly("CHEBY(x, x0, a0, a1, a2, a3)", &["x", "x0", "a0", "a1", "a2", "a3"],
            &[x, x0, a[0], a[1], a[2], a[3]], &[x, x0, h * a[0], h * a[1], h * a[2], h * a[3]], &[0], h, &[1.0]);
        prop_assert!(result.is_ok(), "{}", result.unwrap_err());
    }

    #[test]
    fn splines_scale_exactly(
        s in scale(), h in scale(), x in -0.5f64..4.5,
        y in prop::collection::vec(-2.0f64..2.0, 5),
        method in prop::sample::select(vec![Method::Akima, Method::Cubic]),
        linear in any::<bool>(),
    ) {
        let knots = [0.0, 1.0, 1.5, 3.0, 4.0];
        let fit = |width: f64, height: f64| {
            let data = SplineData::new(
                knots.iter().map(|knot| knot * width).collect(),
                vec![(0.0, y.iter().map(|value| value * height).collect())],
                linear,
            ).unwrap();
            Spline::fit(&data, method)
        };
        let (unit, scaled) = (fit(1.0, 1.0), fit(s, h));
        for order in 0..=2 {
            let at = |spline: &Spline, x: f64| {
                let jet = spline.at(&Dual2SVec64::<1>::variable(x, 0, 1), &Dual2SVec64::from(0.0), order);
                [jet.value(), jet.gradient(1)[0], jet.hessian(1).unwrap()[(0, 0)]]
            };
            let (want, got) = (at(&unit, x), at(&scaled, s * x));
            for (derivative, (want, got)) in want.iter().zip(got).enumerate() {
                // Order `order` of the spline, then `derivative` more by the duals: x^-(order + derivative).
                let power = (order + derivative) as i32;
                let exact = if *want == 0.0 {
                    Logarithmic::of(0.0)
                } else {
                    Logarithmic::new(want.signum(), want.abs().ln() + h.ln() - f64::from(power) * s.ln())
                };
                if exact.overflows() || exact.near_the_edge() {
                    continue;
                }
                let problem = disagreement(got, exact, &format!("order {order} + {derivative}"));
                prop_assert!(problem.is_none(), "{method:?} spline scaled by {s:e}, {h:e} at {x}: {}", problem.unwrap());
            }
        }
    }
}
