//! `DELAY(e, delay, history)` in a run (issue 25 item 2: every function of
//! SPEC with a value during a simulation has it): delay equations against
//! their closed forms by the method of steps, a state-dependent delay, a
//! delayed force on a part against the same equations as DIFFs, and the
//! arguments mbexpr refuses.

use super::joints::method;
use super::simulate::{run, settings};
use super::simulate_variants::Draw;
use mbexpr::simulate::Settings;

/// `x' = a x(t − τ) + b x`, `x = h` before 0 and `x(0) = x0`, by the
/// method of steps computed another way: the pieces `y_k(u) = x(kτ + u)`,
/// `u` in `[0, τ]`, solve the linear system `y_0' = b y_0 + a h`,
/// `y_k' = b y_k + a y_(k−1)`, each from the end of the one before, which
/// the matrix exponential gives exactly.
struct Steps {
    tau: f64,
    /// The system's matrix, the constant `1` as its last state.
    matrix: nalgebra::DMatrix<f64>,
    /// The pieces' starting values, then 1.
    start: nalgebra::DVector<f64>,
}

impl Steps {
    fn new([a, b, tau, h, x0]: [f64; 5], count: usize) -> Steps {
        let n = count + 1;
        let mut matrix = nalgebra::DMatrix::zeros(n, n);
        matrix[(0, 0)] = b;
        matrix[(0, count)] = a * h;
        for k in 1..count {
            matrix[(k, k)] = b;
            matrix[(k, k - 1)] = a;
        }
        let mut start = nalgebra::DVector::zeros(n);
        start[0] = x0;
        start[count] = 1.0;
        let over_tau = (&matrix * tau).exp();
        for k in 1..count {
            let end = &over_tau * &start;
            start[k] = end[k - 1];
        }
        Steps { tau, matrix, start }
    }

    fn at(&self, t: f64) -> f64 {
        let pieces = self.start.len() - 1;
        let k = ((t / self.tau).floor() as usize).min(pieces - 1);
        let u = t - k as f64 * self.tau;
        ((&self.matrix * u).exp() * &self.start)[k]
    }
}

/// Delay equations drawn at random (`x' = a x(t − τ) + b x`) follow the
/// method of steps within a small factor of the tolerance, with both
/// methods: the record's polynomials read the past to the accuracy of the
/// steps, the jump from the history to the record is located, and the
/// steps land where the delay reads across a kink.
#[test]
fn delay_equations_follow_the_method_of_steps() {
    let mut draw = Draw(25);
    let mut report = String::new();
    let mut worst: f64 = 0.0;
    for _ in 0..6 {
        let a = draw.uniform(-2.0, 1.0);
        let b = draw.uniform(-1.5, 0.5);
        let tau = draw.uniform(0.3, 1.5);
        let h = draw.uniform(-1.0, 2.0);
        let x0 = draw.uniform(-1.0, 2.0);
        let text = format!(
            "a delay equation\nDIFF/1, IC = {x0}, FUNCTION = {a} * DELAY(DIF(1), {tau}, {h}) + {b} * DIF(1)\nEND\n"
        );
        let end = 4.5 * tau;
        let exact = Steps::new([a, b, tau, h, x0], 5);
        for name in ["dop853", "radau"] {
            for rtol in [1e-6, 1e-9] {
                let ran = run(
                    &text,
                    &Settings {
                        method: method(name),
                        ..settings(end, 45, rtol)
                    },
                )
                .unwrap_or_else(|error| panic!("{text}: {error}"));
                let error = ran
                    .rows
                    .iter()
                    .map(|row| (row[1] - exact.at(row[0])).abs() / (1.0 + row[1].abs()))
                    .fold(0.0, f64::max);
                worst = worst.max(error / rtol);
                if error > 10.0 * rtol {
                    report += &format!("{name} rtol {rtol:e}: {error:.2e} for {text}");
                }
            }
        }
    }
    assert!(report.is_empty(), "{report}");
    assert!(
        worst > 1e-4,
        "the runs differ from the closed form somewhere"
    );
}

/// `x' = DELAY(TIME, x, 0)`: the time looked back to depends on the
/// state. `x = x0` while `t < x0` (the history, 0), then `x' = t − x`, so
/// `x = t − 1 + exp(x0 − t)`. Radau5's Jacobian carries the delay's
/// derivative through the record (`∂x'/∂x = −1`).
#[test]
fn a_state_dependent_delay_follows_its_closed_form() {
    for x0 in [0.4, 1.0, 1.7] {
        let text = format!(
            "a state-dependent delay\nDIFF/1, IC = {x0}, FUNCTION = DELAY(TIME, DIF(1), 0)\nEND\n"
        );
        let exact = |t: f64| {
            if t <= x0 {
                x0
            } else {
                t - 1.0 + (x0 - t).exp()
            }
        };
        for name in ["dop853", "radau"] {
            let rtol = 1e-9;
            let ran = run(
                &text,
                &Settings {
                    method: method(name),
                    ..settings(4.0, 40, rtol)
                },
            )
            .unwrap_or_else(|error| panic!("{error}"));
            for row in &ran.rows {
                let expected = exact(row[0]);
                assert!(
                    (row[1] - expected).abs() < 10.0 * rtol * (1.0 + expected.abs()),
                    "{name}, x0 = {x0}, t = {}: {} against {expected}",
                    row[0],
                    row[1]
                );
            }
        }
    }
}

/// `x'' = −k x(t − τ) − c x'(t − τ)`, `x = h`, `x' = 0` before 0 and
/// from rest at `h`, by the method of steps: the pieces `(x_j, v_j)(u) =
/// (x, x')(jτ + u)`, `u` in `[0, τ]`, solve `x_j' = v_j`, `v_j' = −k
/// x_(j−1) − c v_(j−1)` (the history's constants for the first), each from
/// the end of the one before, which the matrix exponential gives exactly.
struct DelayedCart {
    tau: f64,
    /// The system's matrix, the constant `1` as its last state.
    matrix: nalgebra::DMatrix<f64>,
    /// The pieces' starting values, then 1.
    start: nalgebra::DVector<f64>,
}

impl DelayedCart {
    fn new([k, c, tau, h]: [f64; 4], count: usize) -> DelayedCart {
        let n = 2 * count + 1;
        let mut matrix = nalgebra::DMatrix::zeros(n, n);
        for j in 0..count {
            matrix[(2 * j, 2 * j + 1)] = 1.0;
            if j == 0 {
                matrix[(1, n - 1)] = -k * h;
            } else {
                matrix[(2 * j + 1, 2 * j - 2)] = -k;
                matrix[(2 * j + 1, 2 * j - 1)] = -c;
            }
        }
        let mut start = nalgebra::DVector::zeros(n);
        start[0] = h;
        start[n - 1] = 1.0;
        let over_tau = (&matrix * tau).exp();
        for j in 1..count {
            let end = &over_tau * &start;
            start[2 * j] = end[2 * j - 2];
            start[2 * j + 1] = end[2 * j - 1];
        }
        DelayedCart { tau, matrix, start }
    }

    /// `(x, x')` at `t`.
    fn at(&self, t: f64) -> (f64, f64) {
        let pieces = (self.start.len() - 1) / 2;
        let j = ((t / self.tau).floor() as usize).min(pieces - 1);
        let u = t - j as f64 * self.tau;
        let state = (&self.matrix * u).exp() * &self.start;
        (state[2 * j], state[2 * j + 1])
    }
}

/// The two carts of `examples/simulate/j_delayed_control.adm` (delays 0.1
/// and 0.5 s in one record) follow the method of steps within a small
/// factor of the tolerance, at every tolerance and with both methods.
/// The steps held to the shorter delay add up to a time a few ulps from
/// the longer delay's kinks: a step that ends there has landed on the
/// kink, and begins a piece of the record (it once did not, and DOP853
/// read the past across the kink, 2e-8 off at every tolerance).
#[test]
fn delayed_carts_follow_the_method_of_steps() {
    let carts = include_str!("../examples/simulate/j_delayed_control.adm");
    let near = DelayedCart::new([10.0, 4.0, 0.1, 0.2], 51);
    let far = DelayedCart::new([10.0, 4.0, 0.5, 0.2], 11);
    let mut report = String::new();
    for name in ["dop853", "radau"] {
        for rtol in [1e-6, 1e-8, 1e-10] {
            let settings = Settings {
                method: method(name),
                ..settings(5.0, 100, rtol)
            };
            let ran = run(carts, &settings).unwrap_or_else(|error| panic!("{error}"));
            let mut worst: f64 = 0.0;
            for row in &ran.rows {
                let (x, vx) = near.at(row[0]);
                let (twin_x, twin_vx) = far.at(row[0]);
                for (value, exact) in [
                    (row[1], x),
                    (row[8], vx),
                    (row[14], twin_x),
                    (row[21], twin_vx),
                ] {
                    worst = worst.max((value - exact).abs() / (1.0 + exact.abs()));
                }
            }
            if worst > 10.0 * rtol {
                report += &format!("{name} rtol {rtol:e}: {worst:.2e} off\n");
            }
        }
    }
    assert!(report.is_empty(), "{report}");
    assert!(far.at(5.0).0.abs() > 10.0, "the twin swings out");
}

/// `examples/simulate/j_delayed_control.adm`: two carts on TRANSLATIONAL
/// joints, each pulled to its set point by a controller that reads it
/// late (0.1 s, stable; 0.5 s, unstable), against the same equations
/// written as DIFFs, `x'' = −10 x(t − T) − 4 x'(t − T)` with the history
/// `x = 0.2`, `x' = 0`; the REQUEST's DELAYs read what the controllers saw,
/// and DELAYs of TIME with a constant history and with one of TIME.
#[test]
fn delayed_controllers_on_jointed_carts_agree_with_their_diffs() {
    let carts = include_str!("../examples/simulate/j_delayed_control.adm");
    let diffs = "the carts as DIFFs
DIFF/1, IC = 0.2, FUNCTION = DIF(2)
DIFF/2, IC = 0, FUNCTION = -10 * DELAY(DIF(1), 0.1, 0.2) - 4 * DELAY(DIF(2), 0.1, 0)
DIFF/3, IC = 0.2, FUNCTION = DIF(4)
DIFF/4, IC = 0, FUNCTION = -10 * DELAY(DIF(3), 0.5, 0.2) - 4 * DELAY(DIF(4), 0.5, 0)
REQUEST/1, F2 = DELAY(DIF(1), 0.1, 0.2), F3 = DELAY(DIF(3), 0.5, 0.2)
REQUEST/2, F2 = DELAY(TIME, 0.5, -1), F3 = DELAY(TIME, 0.5, 2 * TIME)
END
";
    for name in ["dop853", "radau"] {
        let settings = Settings {
            method: method(name),
            ..settings(5.0, 50, 1e-10)
        };
        let bodies = run(carts, &settings).unwrap_or_else(|error| panic!("{error}"));
        let reference = run(diffs, &settings).unwrap_or_else(|error| panic!("{error}"));
        for (row, expected) in bodies.rows.iter().zip(&reference.rows) {
            let t = row[0];
            let close = |value: f64, expected: f64, what: &str| {
                assert!(
                    (value - expected).abs() < 1e-8 * expected.abs().max(1.0),
                    "{name} {what} at {t}: {value} against {expected}"
                );
            };
            // The carts' x and vx, then the REQUEST: x, seen, x, seen.
            close(row[1], expected[1], "x");
            close(row[8], expected[2], "vx");
            close(row[14], expected[3], "the twin's x");
            close(row[21], expected[4], "the twin's vx");
            let [.., seen, _, seen_by_twin] = row[..] else {
                panic!("the request's columns");
            };
            close(seen, expected[5], "what the controller saw");
            close(seen_by_twin, expected[6], "what the twin's saw");
            let [.., constant, of_time] = expected[..] else {
                panic!("the request's columns");
            };
            let delayed_time = if t < 0.5 { -1.0 } else { t - 0.5 };
            assert!(
                (constant - delayed_time).abs() < 1e-12,
                "at {t}: {constant}"
            );
            // A history of TIME, taken at the time looked back to.
            let of_time_expected = if t < 0.5 { 2.0 * (t - 0.5) } else { t - 0.5 };
            assert!(
                (of_time - of_time_expected).abs() < 1e-12,
                "at {t}: {of_time}"
            );
        }
        let last = bodies.rows.last().expect("rows");
        assert!(last[1].abs() < 1e-3, "the cart read 0.1 s late settles");
        assert!(last[14].abs() > 10.0, "the one read 0.5 s late swings out");
    }
}

#[test]
fn what_a_delay_cannot_take_is_refused_at_its_place() {
    let refused = |function: &str| {
        let text = format!("refused\nDIFF/1, IC = 1, FUNCTION = {function}\nEND\n");
        match run(&text, &settings(1.0, 1, 1e-6)) {
            Ok(_) => "ran".to_string(),
            Err(error) => error,
        }
    };
    insta::assert_snapshot!(
        [
            refused("DELAY(DIF(1), 1, 0, 7)"),
            refused("DELAY(DIF(1), 1, 0, 0)"),
        ]
        .join("\n")
    );
}

/// `x' = a x(t − τ₁) + b x(t − τ₂)` with constant histories, by the method
/// of steps done exactly: with no undelayed term the solution is a
/// polynomial on each piece between the breakpoints `k₁ τ₁ + k₂ τ₂`, each
/// piece's rate the earlier pieces' polynomials shifted by the delays, and
/// each piece the integral of its rate from the end of the one before.
struct TwoDelays {
    /// Each piece's start and its polynomial in the time from there
    /// (coefficients from the constant up).
    pieces: Vec<(f64, Vec<f64>)>,
}

impl TwoDelays {
    fn new([a, b, first, second, history, second_history, x0, end]: [f64; 8]) -> TwoDelays {
        let mut grid = Vec::new();
        for k1 in 0..=(end / first) as usize {
            for k2 in 0..=(end / second) as usize {
                let point = k1 as f64 * first + k2 as f64 * second;
                if point <= end {
                    grid.push(point);
                }
            }
        }
        grid.sort_by(f64::total_cmp);
        grid.dedup_by(|later, earlier| *later - *earlier <= 1e-12);
        let mut solution = TwoDelays { pieces: Vec::new() };
        let mut x = x0;
        for (index, &start) in grid.iter().enumerate() {
            let mut rate = Vec::new();
            for (coefficient, delay, before) in [(a, first, history), (b, second, second_history)] {
                let back = start - delay;
                let term = if back < -1e-12 {
                    vec![before]
                } else {
                    let (from, polynomial) = &solution.pieces[solution.piece(back)];
                    shifted(polynomial, back - from)
                };
                rate.resize(rate.len().max(term.len()), 0.0);
                for (sum, value) in rate.iter_mut().zip(term) {
                    *sum += coefficient * value;
                }
            }
            let mut polynomial = vec![x];
            polynomial.extend(rate.iter().enumerate().map(|(k, c)| c / (k + 1) as f64));
            let next = grid.get(index + 1).copied().unwrap_or(end);
            x = value(&polynomial, next - start);
            solution.pieces.push((start, polynomial));
        }
        solution
    }

    /// The piece that holds `t`.
    fn piece(&self, t: f64) -> usize {
        self.pieces
            .partition_point(|(start, _)| *start <= t + 1e-12)
            - 1
    }

    fn at(&self, t: f64) -> f64 {
        let (start, polynomial) = &self.pieces[self.piece(t)];
        value(polynomial, t - start)
    }
}

/// `p(u + c)` from `p(u)` (Taylor's shift, coefficients from the constant
/// up).
fn shifted(polynomial: &[f64], c: f64) -> Vec<f64> {
    let mut shifted = polynomial.to_vec();
    for i in 0..shifted.len() {
        for j in (i..shifted.len() - 1).rev() {
            shifted[j] += c * shifted[j + 1];
        }
    }
    shifted
}

/// `p(u)` by Horner's rule.
fn value(polynomial: &[f64], u: f64) -> f64 {
    polynomial.iter().rev().fold(0.0, |sum, c| sum * u + c)
}

/// Two delays near a multiple of each other (0.1 and 0.2 + ε) read across
/// kinks close together (0.3 and 0.3 + ε): each begins a piece of the
/// record, however short, so that no polynomial reads across the other
/// (they were once merged into one start, and the runs were up to 5e4 ×
/// rtol off with both methods); against the exact method of steps.
#[test]
fn near_multiple_delays_follow_the_method_of_steps() {
    let mut report = String::new();
    for second in [0.2, 0.200001, 0.20001, 0.2001, 0.201] {
        let (a, b, first, history, second_history, x0, end) = (1.2, 2.0, 0.1, 0.5, -1.0, 0.5, 1.0);
        let exact = TwoDelays::new([a, b, first, second, history, second_history, x0, end]);
        let text = format!(
            "two delays\nDIFF/1, IC = {x0}, FUNCTION = {a} * DELAY(DIF(1), {first}, {history}) + {b} * DELAY(DIF(1), {second}, {second_history})\nEND\n"
        );
        for name in ["dop853", "radau"] {
            for rtol in [1e-8, 1e-10] {
                let settings = Settings {
                    method: method(name),
                    ..settings(end, 100, rtol)
                };
                let ran = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
                let worst = ran
                    .rows
                    .iter()
                    .map(|row| (row[1] - exact.at(row[0])).abs() / (1.0 + exact.at(row[0]).abs()))
                    .fold(0.0, f64::max);
                if worst > 2.0 * rtol {
                    report +=
                        &format!("second delay {second}, {name} rtol {rtol:e}: {worst:.2e} off\n");
                }
            }
        }
    }
    assert!(report.is_empty(), "{report}");
}
