//! The integrators against published answers, their orders of convergence,
//! hostile right-hand sides, and the stepper's contract (landing on an end
//! time, restarts, a maximum step).

use mbexpr::integrate::{
    AbsoluteTolerance, IntegrateError, Method, Options, Stepper, System, finite_difference_jacobian,
};
use nalgebra::DMatrix;

use crate::integrate_problems::{Equations, Problem, Refused, problem};

/// Runs one case: `solve PROBLEM METHOD [key=value ...]` integrates to the
/// problem's end and reports the error and the cost; `order PROBLEM METHOD
/// h=H [key=value ...]` integrates with the fixed steps H, H/2, H/4 and
/// reports the observed orders at the step ends and inside the steps.
/// Keys: `rtol`, `atol` (one value, or values split by `/`), `h_init`,
/// `h_max`, `max_steps`, `newton`, `reuse` (`jacobian_reuse`), `y0` (split by `/`), `t_end`.
fn check(case: &str) -> String {
    let words: Vec<&str> = case.split_whitespace().collect();
    let [action, name, method, settings @ ..] = words.as_slice() else {
        panic!("a case is `action problem method settings...`");
    };
    let method: Method = method.parse().unwrap();
    let mut problem = problem(name);
    let mut options = Options::default();
    for setting in settings {
        let (key, value) = setting.split_once('=').unwrap();
        let numbers = || -> Vec<f64> { value.split('/').map(|v| v.parse().unwrap()).collect() };
        let number = || numbers()[0];
        match key {
            "rtol" => options.rtol = number(),
            "atol" => options.atol = AbsoluteTolerance::Each(numbers()),
            "h_init" => options.h_init = Some(number()),
            "h_max" | "h" => options.h_max = number(),
            "max_steps" => options.max_steps = number() as usize,
            "newton" => options.newton_tolerance = Some(number()),
            "reuse" => options.jacobian_reuse = number(),
            "y0" => problem.y0 = numbers(),
            "t_end" => problem.t_end = number(),
            _ => panic!("unknown setting {key}"),
        }
    }
    if let Some(exact) = problem.exact {
        problem.reference = exact(problem.t_end);
    }
    if let AbsoluteTolerance::Each(atol) = &options.atol
        && atol.len() == 1
    {
        options.atol = AbsoluteTolerance::All(atol[0]);
    }
    match *action {
        "solve" => solve(&mut problem, method, options),
        "order" => order(&mut problem, method, options),
        _ => panic!("unknown action {action}"),
    }
}

/// Error and cost of a run to the problem's end, or why it stopped.
fn solve(problem: &mut Problem, method: Method, options: Options) -> String {
    match run(problem, method, options, &mut |_| {}) {
        Ok(stepper) => format!(
            "error {:.1e}, {}",
            error(&problem.reference, stepper.y(), &problem.scale),
            stepper.stats()
        ),
        Err(error) => format!("error: {error}"),
    }
}

/// Integrates to the problem's end, calling `each` after every step.
fn run(
    problem: &mut Problem,
    method: Method,
    options: Options,
    each: &mut dyn FnMut(&Stepper),
) -> Result<Stepper, IntegrateError<Refused>> {
    let system = &mut problem.system;
    let mut stepper = Stepper::new(method, options, 0.0, &problem.y0, system)?;
    while stepper.t() < problem.t_end {
        stepper.step_to(system, problem.t_end)?;
        each(&stepper);
    }
    Ok(stepper)
}

/// The largest scaled difference.
fn error(reference: &[f64], y: &[f64], scale: &[f64]) -> f64 {
    reference
        .iter()
        .zip(y)
        .zip(scale)
        .map(|((r, y), s)| (r - y).abs() / s)
        .fold(0.0, f64::max)
}

/// Observed orders with steps of H, H/2 and H/4 (set as the first and the
/// largest step, the tolerance loose enough never to reject them): at the
/// end, and on the dense output at 0.37 of every step.
fn order(problem: &mut Problem, method: Method, options: Options) -> String {
    let exact = problem.exact.expect("a closed-form solution");
    let scale = problem.scale.clone();
    let mut errors = Vec::new();
    let mut counts = Vec::new();
    for halvings in 0..3 {
        let h = options.h_max / f64::from(1 << halvings);
        let options = Options {
            h_init: Some(h),
            h_max: h,
            ..options.clone()
        };
        let mut inside = 0.0_f64;
        let mut point = vec![0.0; problem.y0.len()];
        let stepper = run(problem, method, options, &mut |stepper| {
            let t = stepper.t_previous() + 0.37 * (stepper.t() - stepper.t_previous());
            stepper.dense(t, &mut point);
            inside = inside.max(error(&exact(t), &point, &scale));
        });
        let stepper = match stepper {
            Ok(stepper) => stepper,
            Err(error) => return format!("error: {error}"),
        };
        let stats = stepper.stats();
        counts.push(format!("{}+{}", stats.steps, stats.rejected));
        errors.push((
            error(&problem.reference, stepper.y(), &problem.scale),
            inside,
        ));
    }
    let orders = |pick: fn(&(f64, f64)) -> f64| {
        errors
            .windows(2)
            .map(|pair| format!("{:.1}", (pick(&pair[0]) / pick(&pair[1])).log2()))
            .collect::<Vec<_>>()
            .join(" ")
    };
    format!(
        "ends {}, inside {} (steps {}; errors {:.1e} and {:.1e} at H/4)",
        orders(|e| e.0),
        orders(|e| e.1),
        counts.join(" "),
        errors[2].0,
        errors[2].1,
    )
}

#[test]
fn published_problems() {
    insta::assert_snapshot!(crate::table(
        "
        solve arenstorf dop853 rtol=1e-10 atol=1e-10
        solve arenstorf dop853 rtol=1e-13 atol=1e-13
        solve arenstorf radau rtol=1e-10 atol=1e-10
        solve van-der-pol radau rtol=1e-6 atol=1e-6 h_init=1e-6
        solve van-der-pol radau rtol=1e-10 atol=1e-10 h_init=1e-6
        solve robertson radau rtol=1e-8 atol=1e-20 h_init=1e-6
        solve van-der-pol radau rtol=1e-6 atol=1e-6
        solve robertson radau rtol=1e-10 atol=1e-22
        ",
        check
    ));
}

#[test]
fn orders_of_convergence() {
    insta::assert_snapshot!(crate::table(
        "
        order limit-cycle dop853 h=0.5 rtol=1e-3 atol=1e-3
        order limit-cycle radau h=0.1 rtol=1e-3 atol=1e-3 newton=1e-10
        ",
        check
    ));
}

#[test]
fn hostile_right_hand_sides() {
    insta::assert_snapshot!(crate::table(
        "
        solve decay dop853 rtol=1e-3 atol=1e-3 t_end=1000
        solve decay radau rtol=1e-3 atol=1e-3
        solve draining-tank radau rtol=1e-8 atol=1e-8 h_init=4
        solve refused-after-1 dop853
        solve refused-after-1 radau
        solve nan-beyond dop853
        solve nan-beyond radau
        solve draining-tank dop853 y0=-1
        solve no-jacobian radau
        solve no-jacobian dop853
        solve arenstorf dop853 max_steps=50
        solve arenstorf dop853 rtol=0
        solve arenstorf radau atol=1e-6/1e-6
        solve arenstorf dop853 h_max=-1
        solve arenstorf radau newton=0
        solve arenstorf radau reuse=1
        solve arenstorf radau reuse=NaN
        solve arenstorf radau reuse=0.1 rtol=1e-10 atol=1e-10
        solve empty dop853
        ",
        check
    ));
}

/// A stepper at the problem's start with `rtol = atol = tolerance`, and the
/// problem's system.
fn start(problem: &mut Problem, method: Method, tolerance: f64) -> (Stepper, &mut Equations) {
    let options = Options {
        rtol: tolerance,
        atol: tolerance.into(),
        ..Options::default()
    };
    let system = &mut problem.system;
    let stepper = Stepper::new(method, options, 0.0, &problem.y0, system).unwrap();
    (stepper, system)
}

#[test]
fn steps_land_on_end_times_and_respect_the_maximum_step() {
    for method in [Method::Dop853, Method::Radau5] {
        let mut arenstorf = problem("arenstorf");
        let (mut stepper, system) = start(&mut arenstorf, method, 1e-8);
        for end in [0.5, 1.0, 1.25] {
            while stepper.t() < end {
                stepper.step_to(system, end).unwrap();
            }
            assert_eq!(stepper.t(), end, "{method}");
        }
        stepper.set_h_max(0.01);
        let mut ends = [[0.0; 4]; 2];
        while stepper.t() < 2.0 {
            let before = stepper.y().to_vec();
            stepper.step_to(system, 2.0).unwrap();
            // The dense output meets the states at both ends of the step.
            stepper.dense(stepper.t_previous(), &mut ends[0]);
            stepper.dense(stepper.t(), &mut ends[1]);
            assert!(error(&before, &ends[0], &[1.0; 4]) < 1e-13, "{method}");
            assert!(error(stepper.y(), &ends[1], &[1.0; 4]) < 1e-13, "{method}");
            assert!(
                stepper.t() - stepper.t_previous() <= 0.01 * (1.0 + 1e-9),
                "{method}"
            );
        }
        assert_eq!(stepper.t(), 2.0);
        let refused = stepper.step_to(system, 2.0).unwrap_err().to_string();
        assert_eq!(refused, "the end time 2 is not after t = 2");
    }
}

#[test]
fn a_restart_at_an_event_continues_on_the_solution() {
    for method in [Method::Dop853, Method::Radau5] {
        let mut cycle = problem("limit-cycle");
        let exact = cycle.exact.unwrap();
        let (mut stepper, system) = start(&mut cycle, method, 1e-10);
        // The event: the first component falls through 0.25 (near t = 1.2).
        let mut y = [0.0; 2];
        while stepper.y()[0] > 0.25 {
            stepper.step(system).unwrap();
        }
        let (mut low, mut high) = (stepper.t_previous(), stepper.t());
        for _ in 0..60 {
            let middle = 0.5 * (low + high);
            stepper.dense(middle, &mut y);
            if y[0] > 0.25 {
                low = middle
            } else {
                high = middle
            }
        }
        stepper.dense(high, &mut y);
        stepper.restart(high, &y);
        assert_eq!((stepper.t(), stepper.t_previous()), (high, high));
        let mut same = [0.0; 2];
        stepper.dense(0.0, &mut same);
        assert_eq!(same, y, "dense output after a restart is the state");
        while stepper.t() < 3.0 {
            stepper.step_to(system, 3.0).unwrap();
        }
        assert!(
            (error(&exact(3.0), stepper.y(), &[1.0, 1.0])) < 1e-8,
            "{method}"
        );
        assert!(
            (exact(high)[0] - 0.25).abs() < 1e-9,
            "{method} event at {high}"
        );
    }
}

#[test]
fn methods_by_name() {
    let parsed: Vec<String> = ["radau", "radau5", "dop853", "rk4"]
        .iter()
        .map(|name| match name.parse::<Method>() {
            Ok(method) => format!("{method} ({method:?})"),
            Err(error) => error.to_string(),
        })
        .collect();
    assert_eq!(
        parsed,
        [
            "radau (Radau5)",
            "radau (Radau5)",
            "dop853 (Dop853)",
            "unknown integration method `rk4`: expected auto, radau (radau5) or dop853"
        ]
    );
}

#[test]
fn the_finite_difference_jacobian_holds_half_the_digits() {
    let mut cycle = problem("limit-cycle");
    let (y, mut dy) = ([0.3, -0.8], [0.0; 2]);
    let system = &mut cycle.system;
    system.rhs(0.0, &y, &mut dy).unwrap();
    let mut exact = DMatrix::zeros(2, 2);
    let mut approximate = DMatrix::zeros(2, 2);
    system.jacobian(0.0, &y, &dy, &mut exact).unwrap();
    finite_difference_jacobian(system, 0.0, &y, &dy, &mut approximate).unwrap();
    assert!((exact - approximate).amax() < 1e-7);
}

#[test]
fn dop853_tells_a_stiff_problem() {
    // Problem, tolerance, and whether Hairer's stiffness test fires before
    // the problem's end (or 100 000 steps).
    let cases = [
        ("van-der-pol", 1e-6, true),
        ("robertson", 1e-6, true),
        ("arenstorf", 1e-8, false),
        ("limit-cycle", 1e-8, false),
    ];
    for (name, tolerance, stiff) in cases {
        let mut problem = problem(name);
        let t_end = problem.t_end;
        let (mut stepper, system) = start(&mut problem, Method::Dop853, tolerance);
        while stepper.t() < t_end && stepper.stiff_from().is_none() {
            if stepper.step_to(system, t_end).is_err() {
                break;
            }
        }
        assert_eq!(
            stepper.stiff_from().is_some(),
            stiff,
            "{name}: {}",
            stepper.stats()
        );
    }
}

/// A Jacobian with algebraic unknowns after the states (the index-1
/// form's, `f_y f_z; g_y g_z`) factorises, sparse and dense alike, to the
/// ODE's own iteration matrices `σ I − (f_y − f_z g_z⁻¹ g_y)`: drawn at
/// random, each solve agrees with the dense solve of the Schur complement,
/// with and without blocks of states eliminated ahead of the sparse LU.
#[test]
fn a_jacobian_with_algebraic_unknowns_solves_as_its_schur_complement() {
    use mbexpr::integrate::linalg::{DenseLu, Factorisation, Jacobian, Pattern, SparseLu};
    use nalgebra::{Complex, DVector};
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    let sizes = (1usize..60, 1usize..20, 0usize..400, any::<u64>());
    TestRunner::new(Config::with_cases(40))
        .run(&sizes, |(n, m, extra, seed)| {
            // A generator of its own, so the values follow from the seed.
            let mut state = seed | 1;
            let mut next = move || {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
            };
            let dimension = n + m;
            // Each algebraic unknown coupled to a state both ways (so that
            // `g_z` with a dominant diagonal is regular), and entries
            // anywhere else.
            let mut entries: Vec<(usize, usize)> = (0..m)
                .flat_map(|k| [(k % n, n + k), (n + k, k % n)])
                .collect();
            for _ in 0..extra {
                let row = ((next() + 1.0) / 2.0 * dimension as f64) as usize;
                let column = ((next() + 1.0) / 2.0 * dimension as f64) as usize;
                entries.push((row.min(dimension - 1), column.min(dimension - 1)));
            }
            // Blocks of states to eliminate (every other run of 1 to 7
            // states), with no entry between two of them.
            let mut blocks = Vec::new();
            let mut start = 0;
            while start < n {
                let end = (start + 1 + (next().abs() * 7.0) as usize).min(n);
                if next() > 0.0 {
                    blocks.push(start..end);
                }
                start = end;
            }
            let block_of =
                |unknown: usize| blocks.iter().position(|block| block.contains(&unknown));
            entries.retain(|&(row, column)| match (block_of(row), block_of(column)) {
                (Some(a), Some(b)) => a == b,
                _ => true,
            });
            let pattern = std::rc::Rc::new(Pattern::new(dimension, entries));
            let eliminated = pattern.as_ref().clone().with_eliminated(blocks.clone());
            let values: Vec<f64> = pattern
                .entries()
                .map(|(row, column)| {
                    let value = next();
                    if row == column && row >= n {
                        value + 4.0
                    } else {
                        value
                    }
                })
                .collect();
            let mut full = DMatrix::zeros(dimension, dimension);
            for ((row, column), value) in pattern.entries().zip(&values) {
                full[(row, column)] = *value;
            }
            let schur = full.view((0, 0), (n, n))
                - full.view((0, n), (n, m))
                    * full
                        .view((n, n), (m, m))
                        .into_owned()
                        .lu()
                        .solve(&full.view((n, 0), (m, n)).into_owned())
                        .expect("g_z is regular");
            let (real_shift, complex_shift) = (20.0 + next(), Complex::new(18.0, 10.0 + next()));
            let rhs: Vec<f64> = (0..n).map(|_| next()).collect();
            let mut real_matrix = -schur.clone();
            let mut complex_matrix = schur.map(|value| Complex::new(-value, 0.0));
            for i in 0..n {
                real_matrix[(i, i)] += real_shift;
                complex_matrix[(i, i)] += complex_shift;
            }
            let real_expected = real_matrix.lu().solve(&DVector::from_column_slice(&rhs));
            let complex_rhs: Vec<Complex<f64>> = rhs
                .iter()
                .map(|&value| Complex::new(value, -value))
                .collect();
            let complex_expected = complex_matrix
                .lu()
                .solve(&DVector::from_column_slice(&complex_rhs));
            let (Some(real_expected), Some(complex_expected)) = (real_expected, complex_expected)
            else {
                return Ok(());
            };
            let jacobian = Jacobian::Sparse {
                pattern: pattern.clone(),
                values,
            };
            let factorisations: [Box<dyn Factorisation>; 3] = [
                Box::new(SparseLu::new(&pattern, n)),
                Box::new(SparseLu::new(&eliminated, n)),
                Box::new(DenseLu::new(dimension, n)),
            ];
            let scale = 1e-9 * (1.0 + real_expected.amax() + complex_expected.camax());
            for mut factorisation in factorisations {
                prop_assert!(factorisation.factorise(&jacobian, real_shift, complex_shift));
                let mut real = rhs.clone();
                factorisation.solve_real(&mut real);
                let mut complex = complex_rhs.clone();
                factorisation.solve_complex(&mut complex);
                for (got, expected) in real.iter().zip(real_expected.iter()) {
                    prop_assert!((got - expected).abs() <= scale, "{got} against {expected}");
                }
                for (got, expected) in complex.iter().zip(complex_expected.iter()) {
                    prop_assert!((got - expected).norm() <= scale, "{got} against {expected}");
                }
            }
            Ok(())
        })
        .expect("every drawn system");
}

/// An eliminated block whose iteration matrix is singular (`J_kk = σ I`)
/// makes the factorisation fail, as a singular LU does; at another shift
/// it factorises and solves.
#[test]
fn an_eliminated_block_that_is_singular_fails_the_factorisation() {
    use mbexpr::integrate::linalg::{Factorisation, Jacobian, Pattern, SparseLu};
    use nalgebra::Complex;
    // Eight 7-state blocks and eight 6-state rows (a body's layout), each
    // block's rows reading its own states, each kept row its body's.
    let bodies = 8;
    let n = 13 * bodies;
    let entries: Vec<(usize, usize)> = (0..bodies)
        .flat_map(|body| {
            let own = 13 * body..13 * body + 13;
            own.clone()
                .flat_map(move |row| (13 * body..13 * body + 13).map(move |column| (row, column)))
        })
        .collect();
    let blocks: Vec<std::ops::Range<usize>> =
        (0..bodies).map(|body| 13 * body..13 * body + 7).collect();
    let pattern = std::rc::Rc::new(Pattern::new(n, entries).with_eliminated(blocks));
    let shift = 5.0;
    // The identity times the real shift on the first block's diagonal, a
    // diagonally dominant matrix elsewhere.
    let values: Vec<f64> = pattern
        .entries()
        .map(|(row, column)| match (row == column, row < 7) {
            (true, true) => shift,
            (true, false) => -20.0,
            (false, true) => 0.0,
            (false, false) => 0.1,
        })
        .collect();
    let jacobian = Jacobian::Sparse {
        pattern: pattern.clone(),
        values,
    };
    let mut lu = SparseLu::new(&pattern, n);
    assert!(!lu.factorise(&jacobian, shift, Complex::new(3.0, 2.0)));
    assert!(lu.factorise(&jacobian, shift + 1.0, Complex::new(3.0, 2.0)));
    // Solved: the first block's rows are (σ − 5) x = r.
    let mut rhs = vec![1.0; n];
    lu.solve_real(&mut rhs);
    assert!((rhs[0] - 1.0).abs() < 1e-14, "{}", rhs[0]);
}

/// A fast lag following a slow oscillator, `y₀' = λ (y₀ − y₁)`, `y₁' = ω
/// y₂`, `y₂' = −ω y₁`, started on its particular solution so that the lag's
/// own mode `e^(λt)` is barely excited.
struct ForcedLag {
    lambda: f64,
    omega: f64,
}

impl ForcedLag {
    /// The closed form from `y = (B, 0, 1)`: `y₁ = sin ωt`, `y₀ = A sin ωt
    /// + B cos ωt` with `A = λ² / (λ² + ω²)`, `B = λ ω / (λ² + ω²)`.
    fn exact(&self, t: f64) -> [f64; 3] {
        let (lambda, omega) = (self.lambda, self.omega);
        let denominator = lambda * lambda + omega * omega;
        let (a, b) = (lambda * lambda / denominator, lambda * omega / denominator);
        let (sin, cos) = (omega * t).sin_cos();
        [a * sin + b * cos, sin, cos]
    }
}

impl System for ForcedLag {
    type Error = Refused;

    fn dimension(&self) -> usize {
        3
    }

    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
        dy[0] = self.lambda * (y[0] - y[1]);
        dy[1] = self.omega * y[2];
        dy[2] = -self.omega * y[1];
        Ok(())
    }

    fn jacobian(
        &mut self,
        _t: f64,
        _y: &[f64],
        _dy: &[f64],
        jac: &mut DMatrix<f64>,
    ) -> Result<(), Refused> {
        jac.fill(0.0);
        jac[(0, 0)] = self.lambda;
        jac[(0, 1)] = -self.lambda;
        jac[(1, 2)] = self.omega;
        jac[(2, 1)] = -self.omega;
        Ok(())
    }
}

/// DOP853's steps on a problem with a stiff mode are held by stability, near
/// the edge of its region (`h |λ|` = 6.1), where its dense output (a
/// polynomial in `h λ`) amplifies the mode 10 to 30 times inside the step
/// while the step's ends are right: rows between the ends were off by up to
/// 2 000 × rtol (a sensor lag in a controlled lift). Drawn at random (`λ`
/// from −20 to −2 000, `ω` from 0.3 to 3, rtol from 1e-9 to 1e-5), the rows
/// at 400 times over three periods follow the closed form as closely as
/// the step ends do.
#[test]
fn dop853s_rows_inside_its_steps_follow_a_stiff_mode_it_steps_over() {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, TestRunner};
    let cases = (-3.3f64..-1.3, 0.3f64..3.0, -9.0f64..-5.0);
    let mut runner = TestRunner::new(Config {
        cases: 24,
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(&cases, |(lambda_exponent, omega, rtol_exponent)| {
            let mut lag = ForcedLag {
                lambda: -(10f64.powf(-lambda_exponent)),
                omega,
            };
            let rtol = 10f64.powf(rtol_exponent);
            let t_end = 3.0 * std::f64::consts::TAU / omega;
            {
                let options = Options {
                    rtol,
                    ..Options::default()
                };
                let start = lag.exact(0.0);
                let mut stepper =
                    Stepper::new(Method::Dop853, options, 0.0, &start, &mut lag).unwrap();
                let (mut worst_row, mut worst_end) = (0.0f64, 0.0f64);
                let mut y = [0.0; 3];
                let mut next = 1;
                while stepper.t() < t_end {
                    stepper.step_to(&mut lag, t_end).unwrap();
                    let end = lag.exact(stepper.t());
                    worst_end = worst_end.max((stepper.y()[0] - end[0]).abs());
                    while next <= 400 && f64::from(next) * t_end / 400.0 <= stepper.t() {
                        let t = f64::from(next) * t_end / 400.0;
                        stepper.dense(t, &mut y);
                        worst_row = worst_row.max((y[0] - lag.exact(t)[0]).abs());
                        next += 1;
                    }
                }
                prop_assert!(
                    worst_row <= 3.0 * worst_end.max(rtol),
                    "λ = {} ω = {omega} rtol = {rtol}: rows {worst_row:.2e}, step ends {worst_end:.2e} ({})",
                    lag.lambda,
                    stepper.stats()
                );
            }
            Ok(())
        })
        .unwrap();
}

/// Radau5 keeps its Jacobian through a restart: the event driver goes back
/// to a step's start to cut the step at a switch, on the same system, and
/// a Jacobian and LU per cut made Radau5 cost 6 times DOP853 on a chain of
/// balls meeting 225 times. After a fresh start (the system may have
/// changed at the event) it evaluates a new one.
#[test]
fn radau5_keeps_its_jacobian_through_a_restart_but_not_a_fresh_start() {
    let mut lag = ForcedLag {
        lambda: -500.0,
        omega: 2.0,
    };
    let options = Options {
        rtol: 1e-8,
        atol: 1e-8.into(),
        ..Options::default()
    };
    let mut stepper = Stepper::new(
        Method::Radau5,
        options.clone(),
        0.0,
        &lag.exact(0.0),
        &mut lag,
    )
    .unwrap();
    for _ in 0..5 {
        stepper.step(&mut lag).unwrap();
    }
    let (t0, y0) = (stepper.t(), stepper.y().to_vec());
    stepper.step(&mut lag).unwrap();
    let jacobians = stepper.stats().jacobian_evaluations;
    let middle = 0.5 * (t0 + stepper.t());
    stepper.restart(t0, &y0);
    while stepper.t() < middle {
        stepper.step_to(&mut lag, middle).unwrap();
    }
    assert_eq!(stepper.stats().jacobian_evaluations, jacobians);
    let scale = [1.0; 3];
    assert!(error(&lag.exact(middle), stepper.y(), &scale) < 1e-7);
    let y = stepper.y().to_vec();
    let mut fresh = stepper.fresh_start(options, middle, &y, &mut lag).unwrap();
    fresh.step(&mut lag).unwrap();
    assert_eq!(fresh.stats().jacobian_evaluations, 1);
    assert!(error(&lag.exact(fresh.t()), fresh.y(), &scale) < 1e-7);
}

/// [`ForcedLag`] with the error norm's groups given.
struct GroupedLag {
    lag: ForcedLag,
    groups: Vec<std::ops::Range<usize>>,
}

impl System for GroupedLag {
    type Error = Refused;

    fn dimension(&self) -> usize {
        3
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Refused> {
        self.lag.rhs(t, y, dy)
    }

    fn norm_groups(&mut self) -> Vec<std::ops::Range<usize>> {
        self.groups.clone()
    }
}

/// The error norm's groups must cover the states in order, each not empty:
/// any other set is refused when a stepper starts, with both methods (a
/// second group that went back over the first was taken and read past the
/// states); groups that do cover them run.
#[test]
#[expect(
    clippy::single_range_in_vec_init,
    reason = "a list of one range is one group of states"
)]
fn norm_groups_that_do_not_cover_the_states_in_order_are_refused() {
    let cases: [(&[std::ops::Range<usize>], bool); 8] = [
        (&[0..3], true),
        (&[0..3, 2..4], false),
        (&[0..1, 1..3], true),
        (&[0..1, 1..2, 2..3], true),
        (&[0..2, 1..3], false),
        (&[0..2], false),
        (&[0..1, 1..1, 1..3], false),
        (&[], false),
    ];
    for (groups, covers) in cases {
        for method in [Method::Radau5, Method::Dop853] {
            let mut system = GroupedLag {
                lag: ForcedLag {
                    lambda: -10.0,
                    omega: 1.0,
                },
                groups: groups.to_vec(),
            };
            let started = Stepper::new(
                method,
                Options::default(),
                0.0,
                &[0.0, 0.0, 1.0],
                &mut system,
            );
            match started {
                Ok(mut stepper) => {
                    assert!(covers, "{method} {groups:?} was taken");
                    stepper.step_to(&mut system, 1.0).expect("steps");
                }
                Err(IntegrateError::Settings(message)) => {
                    assert!(!covers, "{method} {groups:?}: {message}");
                    assert!(message.contains("do not cover its 3 states"), "{message}");
                }
                Err(other) => panic!("{method} {groups:?}: {other}"),
            }
        }
    }
}
