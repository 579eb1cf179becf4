//! Joints: closed forms (a compound pendulum's period from the complete
//! elliptic integral and its energy over many periods; a body on a
//! translational joint under a spring, an exact sine), conserved
//! quantities of 3-D joints (a heavy top on a spherical joint), the exact
//! Jacobian of jointed bodies against finite differences, and the
//! constraint residuals below the tolerance all run long.

use std::f64::consts::PI;

use mbexpr::integrate::Method;
use mbexpr::simulate::Settings;

use super::simulate::{Run, run, settings, the_jacobian_agrees_with_finite_differences};

/// The complete elliptic integral of the first kind `K(k)`, by the
/// arithmetic-geometric mean.
pub(super) fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
    // Quadratic convergence: ten rounds reach the rounding of a double.
    for _ in 0..10 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// A compound pendulum: mass `m`, centre of mass `d` from a revolute
/// pivot at the ground's origin, moment `izz` about the centre of mass,
/// released at rest with its centre of mass level with the pivot.
pub(super) fn pendulum(m: f64, d: f64, izz: f64) -> String {
    format!(
        "pendulum
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = {m}, CM = 20, IP = {izz}, {izz}, {izz}
MARKER/20, PART = 2, QP = {d}, 0, 0
MARKER/21, PART = 2
JOINT/1, REVOLUTE, I = 21, J = 1
ACCGRAV/JGRAV = -9.80665
END
"
    )
}

/// The rotation angle about z of a body's quaternion columns `q0 .. q3`
/// starting at `column`, unwrapped against `previous`.
pub(super) fn angle(row: &[f64], column: usize, previous: f64) -> f64 {
    let raw = 2.0 * row[column + 3].atan2(row[column]);
    raw + 2.0 * PI * ((previous - raw) / (2.0 * PI)).round()
}

pub(super) fn method(name: &str) -> Method {
    match name {
        "radau" => Method::Radau5,
        "dop853" => Method::Dop853,
        _ => Method::Auto,
    }
}

/// `m d izz rtol method`: the pendulum over one exact period `T = 4 K(k)
/// / ω0` (`k = sin(π/4)`, `ω0² = m g d / (izz + m d²)`): the angle at
/// `T/2` (−π: the centre of mass level on the other side) and at `T`
/// (back to 0), as errors relative to `rtol`.
fn period_error(case: &str) -> (f64, f64, Run) {
    let fields: Vec<&str> = case.split_whitespace().collect();
    let number = |index: usize| fields[index].parse::<f64>().expect("a number");
    let (m, d, izz, rtol) = (number(0), number(1), number(2), number(3));
    let omega0 = (m * 9.80665 * d / (izz + m * d * d)).sqrt();
    let period = 4.0 * elliptic_k((PI / 4.0).sin()) / omega0;
    let mut settings = settings(period, 2, rtol);
    settings.method = method(fields[4]);
    let run = run(&pendulum(m, d, izz), &settings).expect("the pendulum runs");
    let half = angle(&run.rows[1], 4, -PI);
    let whole = angle(&run.rows[2], 4, 0.0);
    ((half + PI).abs() / rtol, whole.abs() / rtol, run)
}

#[test]
fn a_pendulum_on_a_revolute_joint_keeps_the_elliptic_integrals_period() {
    let cases = "
        1 2 0.1 1e-6 dop853
        1 2 0.1 1e-9 dop853
        1 2 0.1 1e-6 radau
        1 2 0.1 1e-9 radau
        3.5 0.4 0.02 1e-8 auto
        0.2 1.5 0.7 1e-8 radau
        0.2 1.5 0.7 1e-11 dop853
    ";
    for case in cases.lines().map(str::trim).filter(|case| !case.is_empty()) {
        let (half, whole, run) = period_error(case);
        println!(
            "{case}: angle error at T/2 {half:.2} rtol, at T {whole:.2} rtol; residuals {:?}, {} projections",
            run.summary.residuals, run.summary.projections
        );
        assert!(half < 50.0 && whole < 50.0, "{case}: {half} {whole}");
    }
}

/// A body of mass `m` on a translational joint along ground z, pulled
/// back by a spring `k` (an action-only SFORCE along the joint), its
/// centre of mass off the axis and gravity across it (the joint takes
/// both): `z = z0 cos ωt + v0/ω sin ωt`, `ω² = k / m`.
fn slider(m: f64, k: f64, z0: f64, v0: f64) -> String {
    format!(
        "slider
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = {m}, CM = 20, IP = 1, 2, 3, QG = 0, 0, {z0}, VZ = {v0}
MARKER/20, PART = 2, QP = 0.3, 0.1, 0
MARKER/21, PART = 2
JOINT/1, TRANSLATIONAL, I = 21, J = 1
SFORCE/1, TRANSLATIONAL, I = 21, J = 1, ACTIONONLY, FUNCTION = -{k} * DZ(21, 1)
ACCGRAV/IGRAV = 3, JGRAV = -9.80665
END
"
    )
}

#[test]
fn a_body_on_a_translational_joint_under_a_spring_moves_as_the_exact_sine() {
    // m k z0 v0 rtol method
    let cases = "
        1 100 0.5 0 1e-8 dop853
        2 30 -0.2 3 1e-8 radau
        0.3 500 0.1 -2 1e-10 auto
        5 1 1 1 1e-6 radau
    ";
    for case in cases.lines().map(str::trim).filter(|case| !case.is_empty()) {
        let fields: Vec<&str> = case.split_whitespace().collect();
        let number = |index: usize| fields[index].parse::<f64>().expect("a number");
        let (m, k, z0, v0, rtol) = (number(0), number(1), number(2), number(3), number(4));
        let omega = (k / m).sqrt();
        let mut settings = settings(20.0 * PI / omega, 200, rtol);
        settings.method = method(fields[5]);
        let run = run(&slider(m, k, z0, v0), &settings).expect("the slider runs");
        let scale = z0.abs().max(v0.abs() / omega);
        let mut worst: f64 = 0.0;
        for row in &run.rows {
            let t = row[0];
            let exact = z0 * (omega * t).cos() + v0 / omega * (omega * t).sin();
            worst = worst.max((row[3] - exact).abs() / scale);
            // It neither leaves the axis nor turns.
            let off = row[1].abs().max(row[2].abs()).max((row[4] - 1.0).abs());
            worst = worst.max(off / scale);
        }
        println!(
            "{case}: largest error {:.2} rtol over 10 periods; residuals {:?}, {} projections",
            worst / rtol,
            run.summary.residuals,
            run.summary.projections
        );
        assert!(worst < 100.0 * rtol, "{case}: {} rtol", worst / rtol);
    }
}

/// A heavy top: a body of inertia `0.3, 0.5, 0.7` (mass 2) on a spherical
/// joint at the ground's origin, its centre of mass `h` up its own z axis,
/// tilted by `theta` and spun at `spin` about its axis.
fn top(h: f64, theta: f64, spin: f64) -> String {
    format!(
        "top
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2, CM = 20, IP = 0.3, 0.5, 0.7, REULER = 0.4, {theta}, 0, WZ = {spin}, WX = 0.3
MARKER/20, PART = 2, QP = 0, 0, {h}
MARKER/21, PART = 2
JOINT/1, SPHERICAL, I = 21, J = 1
ACCGRAV/KGRAV = -9.80665
END
"
    )
}

/// The energy and the angular momentum about the vertical through the
/// pivot of the top in `row` (its columns from 1: origin, quaternion,
/// origin velocity, angular velocity in ground).
fn top_invariants(row: &[f64], h: f64) -> (f64, f64) {
    use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
    let q = UnitQuaternion::from_quaternion(Quaternion::new(row[4], row[5], row[6], row[7]));
    let rotation = q.to_rotation_matrix().into_inner();
    let origin = Vector3::new(row[1], row[2], row[3]);
    let omega = Vector3::new(row[11], row[12], row[13]);
    let arm = rotation * Vector3::new(0.0, 0.0, h);
    let centre = origin + arm;
    let velocity = Vector3::new(row[8], row[9], row[10]) + omega.cross(&arm);
    let inertia =
        rotation * Matrix3::from_diagonal(&Vector3::new(0.3, 0.5, 0.7)) * rotation.transpose();
    let energy = 0.5 * 2.0 * velocity.norm_squared()
        + 0.5 * omega.dot(&(inertia * omega))
        + 2.0 * 9.80665 * centre.z;
    let momentum = (inertia * omega + centre.cross(&velocity) * 2.0).z;
    (energy, momentum)
}

#[test]
fn a_heavy_top_on_a_spherical_joint_keeps_its_energy_and_vertical_momentum() {
    // h theta spin end rtol method
    let cases = "
        0.5 0.3 20 10 1e-9 dop853
        0.5 0.3 20 10 1e-9 radau
        1.2 1.1 5 20 1e-10 auto
        0.2 0.05 40 5 1e-8 dop853
    ";
    for case in cases.lines().map(str::trim).filter(|case| !case.is_empty()) {
        let fields: Vec<&str> = case.split_whitespace().collect();
        let number = |index: usize| fields[index].parse::<f64>().expect("a number");
        let (h, theta, spin, end, rtol) = (number(0), number(1), number(2), number(3), number(4));
        let mut settings: Settings = settings(end, 100, rtol);
        settings.method = method(fields[5]);
        let run = run(&top(h, theta, spin), &settings).expect("the top runs");
        let (energy0, momentum0) = top_invariants(&run.rows[0], h);
        let energy_scale = 0.5 * 0.7 * spin * spin + 2.0 * 9.80665 * h;
        let momentum_scale = 0.7 * spin;
        let mut worst: f64 = 0.0;
        for row in &run.rows {
            let (energy, momentum) = top_invariants(row, h);
            worst = worst
                .max((energy - energy0).abs() / energy_scale)
                .max((momentum - momentum0).abs() / momentum_scale);
            // The pivot stays at the origin.
            worst = worst.max(row[1].abs().max(row[2].abs()).max(row[3].abs()) / h);
        }
        println!(
            "{case}: largest drift {:.2} rtol; residuals {:?}, {} projections; {} steps",
            worst / rtol,
            run.summary.residuals,
            run.summary.projections,
            run.summary.stats.steps
        );
        assert!(worst < 100.0 * rtol, "{case}: {} rtol", worst / rtol);
    }
}

/// Two bodies on a spherical and a revolute joint, a spring between them
/// that reads their motion, off the constraints (the shifts), so that every
/// part of the index-1 right-hand side is differentiated.
const DOUBLE: &str = "double pendulum
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 0.1, 0.2, 0.3, WX = 1
MARKER/20, PART = 2, QP = 1, 0, 0
MARKER/21, PART = 2
MARKER/22, PART = 2, QP = 2, 0, 0
PART/3, MASS = 0.5, CM = 30, IP = 0.05, 0.05, 0.08, WZ = 2
MARKER/30, PART = 3, QP = 2.5, 0.5, 0
MARKER/31, PART = 3, QP = 2, 0, 0
JOINT/1, SPHERICAL, I = 21, J = 1
JOINT/2, REVOLUTE, I = 31, J = 22
SFORCE/1, TRANSLATIONAL, I = 30, J = 1, FUNCTION = -3 * (DM(30, 1) - 2) - 0.2 * VR(30, 1)
ACCGRAV/JGRAV = -9.80665
END
";

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(16))]

    /// The Jacobian of jointed bodies (their multipliers through the
    /// solve) from dual numbers agrees with central differences.
    #[test]
    fn the_exact_jacobian_of_jointed_bodies_agrees_with_finite_differences(
        shifts in proptest::collection::vec(-0.05f64..0.05, 26),
        time in 0.0f64..3.0,
    ) {
        the_jacobian_agrees_with_finite_differences(DOUBLE, &shifts, time)?;
    }
}

/// Andrews' squeezing mechanism (`examples/simulate/d_andrews.adm`,
/// written by `scripts/andrews_dataset.py` from the Test Set for IVP
/// Solvers' definition): 7 parts on 10 revolute joints in space (9 of
/// their equations redundant), its spring and driving torque.
const ANDREWS: &str = include_str!("../examples/simulate/d_andrews.adm");

/// The angles `β Θ γ Φ δ Ω ε` at t = 0 (the test set's consistent initial
/// values, to a double's precision) and the published reference at t = 0.03 (PSIDE at rtol = atol
/// = 1e-14; Test Set for IVP Solvers, release 2.3, `andsoln`).
const ANDREWS_START: [f64; 7] = [
    -0.061_713_890_014_276_45,
    0.0,
    0.455_279_819_163_070_37,
    0.222_668_390_165_885_88,
    0.487_364_979_543_842_56,
    -0.222_668_390_165_885_88,
    1.230_547_444_549_821_2,
];
const ANDREWS_REFERENCE: [f64; 7] = [
    0.1581077119629904e+2,
    -0.1575637105984298e+2,
    0.4082224013073101e-1,
    -0.5347301163226948e+0,
    0.5244099658805304e+0,
    0.5347301163226948e+0,
    0.1048080741042263e+1,
];

/// `method rtol`: the seven angles at t = 0.03 read from the parts'
/// turns (unwrapped over 300 rows: the crank turns 2.5 times), and the
/// test set's "mixed error significant digits" of the worst one,
/// `−log10 max |y − ref| / (1 + |ref|)`.
fn andrews_digits(case: &str) -> (f64, Run) {
    let fields: Vec<&str> = case.split_whitespace().collect();
    let mut settings = settings(0.03, 300, fields[1].parse().expect("a tolerance"));
    settings.method = method(fields[0]);
    let run = run(ANDREWS, &settings).expect("Andrews' mechanism runs");
    // Each part's turn about z (parts 2 ... 8: bodies 1 ... 7).
    let mut turn = [0.0; 7];
    for row in &run.rows {
        for (body, turned) in turn.iter_mut().enumerate() {
            *turned = angle(row, 1 + 13 * body + 3, *turned);
        }
    }
    let [b0, t0, g0, p0, d0, o0, e0] = ANDREWS_START;
    let beta = b0 + turn[0];
    let theta = b0 + t0 + turn[1] - beta;
    let gamma = g0 + turn[2];
    let delta = d0 + turn[4];
    let phi = p0 + d0 + turn[3] - delta;
    let epsilon = e0 + turn[6];
    let omega = o0 + e0 + turn[5] - epsilon;
    let angles = [beta, theta, gamma, phi, delta, omega, epsilon];
    let worst = angles
        .iter()
        .zip(ANDREWS_REFERENCE)
        .map(|(angle, reference)| (angle - reference).abs() / (1.0 + reference.abs()))
        .fold(0.0, f64::max);
    (-worst.log10(), run)
}

#[test]
fn andrews_squeezing_mechanism_meets_the_published_reference() {
    // method rtol: the least significant digits
    let cases = "
        dop853 1e-8: 8
        dop853 1e-10: 9.5
        auto 1e-9: 9
        radau 1e-8: 8.5
    ";
    for case in cases.lines().map(str::trim).filter(|case| !case.is_empty()) {
        let (run_case, least) = case.split_once(':').expect("method rtol: digits");
        let least: f64 = least.trim().parse().expect("a number");
        let (digits, run) = andrews_digits(run_case);
        println!(
            "{run_case}: {digits:.2} digits; {} steps ({} rejected), {} jacobians, {} lu; residuals {:?}, {} projections",
            run.summary.stats.steps,
            run.summary.stats.rejected,
            run.summary.stats.jacobian_evaluations,
            run.summary.stats.lu_decompositions,
            run.summary.residuals,
            run.summary.projections
        );
        assert!(digits >= least, "{run_case}: {digits} digits");
    }
}

/// DOP853 is not symplectic: the energy drifts by a little each step, so
/// the drift over 100 periods grows with the steps (at rtol 1e-10 it is
/// 9e-10 of `m g d`, at 1e-11 1.5e-11, at 1e-12 1e-12, measured with
/// `examples/simulate/c_pendulum.adm`); the issue asks for 1e-9.
#[test]
fn a_pendulum_keeps_its_energy_over_a_hundred_periods() {
    // m d izz rtol method
    let cases = "
        1 2 0.1 1e-11 dop853
        1 2 0.1 1e-12 dop853
        0.4 0.7 0.05 1e-11 auto
    ";
    for case in cases.lines().map(str::trim).filter(|case| !case.is_empty()) {
        let fields: Vec<&str> = case.split_whitespace().collect();
        let number = |index: usize| fields[index].parse::<f64>().expect("a number");
        let (m, d, izz, rtol) = (number(0), number(1), number(2), number(3));
        let omega0 = (m * 9.80665 * d / (izz + m * d * d)).sqrt();
        let period = 4.0 * elliptic_k((PI / 4.0).sin()) / omega0;
        let mut settings = settings(100.0 * period, 1000, rtol);
        settings.method = method(fields[4]);
        let run = run(&pendulum(m, d, izz), &settings).expect("the pendulum runs");
        let mut worst: f64 = 0.0;
        let mut turned = 0.0;
        for row in &run.rows {
            turned = angle(row, 4, turned);
            let spin = row[13];
            let energy = 0.5 * (izz + m * d * d) * spin * spin + m * 9.80665 * d * turned.sin();
            worst = worst.max(energy.abs() / (m * 9.80665 * d));
        }
        println!(
            "{case}: energy drift {worst:.2e} of m g d over 100 periods; {} steps, {} projections",
            run.summary.stats.steps, run.summary.projections
        );
        assert!(worst < 1e-9, "{case}: {worst}");
    }
}

/// A chain of `links` unit bars on revolute joints, hanging from ground
/// along x, under gravity along -y.
fn chain(links: usize) -> String {
    let mut text = format!("chain of {links} links\nPART/1, GROUND\nMARKER/1, PART = 1\n");
    let mut previous = 1;
    for part in 2..links + 2 {
        let x = (part - 2) as f64;
        text += &format!(
            "PART/{part}, MASS = 1, IP = 0.1, 0.1, 0.1, CM = {0}0\nMARKER/{part}0, PART = {part}, QP = {1}, 0, 0\nMARKER/{part}1, PART = {part}, QP = {x}, 0, 0\nMARKER/{part}2, PART = {part}, QP = {2}, 0, 0\nJOINT/{part}, REVOLUTE, I = {part}1, J = {previous}\n",
            part,
            x + 0.5,
            x + 1.0
        );
        previous = part * 10 + 2;
    }
    text + "ACCGRAV/JGRAV = -9.8\n"
}

/// A chain long enough that its joints' multipliers are solved by the
/// sparse LU (20 links, 100 equations) and whose redundancy and initial
/// conditions are found within each equation's envelope keeps its energy
/// with both methods, and the two agree: the sparse and dense paths and
/// the faster independence test change no answer.
#[test]
fn a_long_chain_keeps_its_energy_with_both_methods() {
    let links = 20;
    // Each part's state is of its frame, at the origin (the parts have no
    // QG), turning about z; its centre of mass is `link + 0.5` along its x.
    let energy = |row: &[f64]| {
        (0..links)
            .map(|link| {
                let s = &row[1 + 13 * link..1 + 13 * (link + 1)];
                let (turned, arm, spin) = (2.0 * s[6].atan2(s[3]), link as f64 + 0.5, s[12]);
                let (sin, cos) = turned.sin_cos();
                let (vx, vy) = (s[7] - spin * sin * arm, s[8] + spin * cos * arm);
                0.5 * (vx * vx + vy * vy) + 0.05 * spin * spin + 9.8 * (s[1] + sin * arm)
            })
            .sum::<f64>()
    };
    let mut ends = Vec::new();
    for method in [Method::Dop853, Method::Radau5] {
        let settings = Settings {
            method,
            ..settings(0.3, 3, 1e-9)
        };
        let run = run(&chain(links), &settings).expect("the chain runs");
        let start = energy(&run.rows[0]);
        for row in &run.rows {
            let drift = (energy(row) - start).abs();
            assert!(
                drift < 1e-6,
                "{method}: t = {}: energy off by {drift:e}",
                row[0]
            );
        }
        ends.push(run.rows.last().expect("rows").clone());
    }
    let apart = ends[0]
        .iter()
        .zip(&ends[1])
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(apart < 1e-6, "the methods end {apart:e} apart");
}

#[test]
fn a_pendulum_bouncing_on_a_conservative_stop_keeps_its_energy_through_the_switches() {
    // A rotational IMPACT stop with no damping at 1.2 rad below level: the
    // energy, with the stop's potential k p^(e+1) / (e+1), stays; each
    // touch and release is a located switch after which the state is put
    // back on the joint.
    let text = pendulum(1.0, 2.0, 0.1).replace(
        "ACCGRAV",
        "SFORCE/1, ROTATIONAL, I = 21, J = 1, FUNCTION = IMPACT(AZ(21, 1), WZ(21, 1), -1.2, 1e4, 1.5, 0, 0.01)\nACCGRAV",
    );
    for case in ["dop853 1e-9", "radau 1e-9"] {
        let fields: Vec<&str> = case.split_whitespace().collect();
        let rtol: f64 = fields[1].parse().expect("a tolerance");
        let mut settings = settings(10.0, 2000, rtol);
        settings.method = method(fields[0]);
        let run = run(&text, &settings).expect("the pendulum runs");
        let mut worst: f64 = 0.0;
        let mut turned = 0.0;
        for row in &run.rows {
            turned = angle(row, 4, turned);
            let penetration = (-1.2 - turned).max(0.0);
            let energy = 0.5 * 4.1 * row[13] * row[13]
                + 9.80665 * 2.0 * turned.sin()
                + 1e4 * penetration.powf(2.5) / 2.5;
            worst = worst.max(energy.abs() / (9.80665 * 2.0));
        }
        println!(
            "{case}: {} events, energy drift {worst:.2e} of m g d; residuals {:?}, {} projections",
            run.events.len(),
            run.summary.residuals,
            run.summary.projections
        );
        assert!(run.events.len() >= 4, "{case}: {} events", run.events.len());
        assert!(worst < 100.0 * rtol, "{case}: {worst}");
    }
}

/// The study's slider in a slot turning at 2 rad/s, as joints
/// (`examples/simulate/e_slider_in_slot.adm`: a REVOLUTE joint driven by a
/// MOTION, a TRANSLATIONAL joint, a BISTOP) and as its DIFF form
/// (`b_slider.adm`, s'' = w² s + BISTOP(...)): the slider's place along the
/// slot agrees at every output time, within a small factor of the
/// tolerance; the slot turns as its MOTION says.
#[test]
fn the_slider_in_a_turning_slot_moves_as_its_diff_form() {
    let joints = include_str!("../examples/simulate/e_slider_in_slot.adm");
    let diffs = include_str!("../examples/simulate/b_slider.adm");
    // method rtol
    for case in ["dop853 1e-8", "radau 1e-8", "auto 1e-10"] {
        let fields: Vec<&str> = case.split_whitespace().collect();
        let rtol: f64 = fields[1].parse().expect("a tolerance");
        let mut settings = settings(5.0, 200, rtol);
        settings.method = method(fields[0]);
        let jointed = run(joints, &settings).expect("the jointed slider runs");
        let mut reference_settings = settings.clone();
        reference_settings.rtol = 1e-12;
        reference_settings.atol = 1e-15;
        reference_settings.method = method("dop853");
        let reference = run(diffs, &reference_settings).expect("the DIFF form runs");
        let (mut worst, mut slot_worst): (f64, f64) = (0.0, 0.0);
        let mut slot_angle = 0.0;
        for (row, exact) in jointed.rows.iter().zip(&reference.rows) {
            // The slider's place along the slot is REQUEST/1.F1, the last column.
            worst = worst.max((row[row.len() - 1] - exact[1]).abs());
            slot_angle = angle(row, 4, slot_angle);
            slot_worst = slot_worst.max((slot_angle - 2.0 * row[0]).abs());
        }
        println!(
            "{case}: largest difference {worst:.2e}, slot angle off by {slot_worst:.1e}; {} events against {}; residuals {:?}, {} projections",
            jointed.events.len(),
            reference.events.len(),
            jointed.summary.residuals,
            jointed.summary.projections
        );
        assert_eq!(jointed.events.len(), reference.events.len(), "{case}");
        // Each switch reports how far its located state was off the joints
        // before it was assembled again: within the tolerance.
        for event in &jointed.events {
            let residuals = event
                .residuals
                .expect("a jointed model's event has residuals");
            assert!(
                residuals.position.max(residuals.velocity) < 100.0 * rtol,
                "{case}: t = {}: {residuals:?}",
                event.time
            );
        }
        assert!(worst < 100.0 * rtol, "{case}: {worst}");
        assert!(slot_worst < 10.0 * rtol, "{case}: {slot_worst}");
    }
}

/// Joint primitives (`JPRIM`) against closed forms: a part held by one
/// primitive to ground (J's axes those of ground, I at the part's centre
/// of mass) under gravity moves as the free directions allow, exactly.
#[test]
fn joint_primitives_leave_exactly_their_free_motions() {
    let g = 9.80665;
    let part = |primitive: &str, placement: &str| {
        format!(
            "primitive
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2, CM = 20, IP = 0.3, 0.5, 0.7, {placement}
MARKER/20, PART = 2
{primitive}
ACCGRAV/KGRAV = -{g}
END
"
        )
    };
    // Each case: the model, and at a row its measured values beside the exact ones.
    type Exact<'c> = &'c dyn Fn(f64, &[f64]) -> Vec<(f64, f64)>;
    let cases: [(String, Exact); 4] = [
        (
            // On the line (z): falls freely along it, turning as it likes.
            part(
                "JPRIM/1, INLINE, I = 20, J = 1",
                "QG = 0, 0, 2, WX = 0.3, WZ = 2",
            ),
            &|t, row| {
                vec![
                    (row[1], 0.0),
                    (row[2], 0.0),
                    (row[3], 2.0 - 0.5 * g * t * t),
                ]
            },
        ),
        (
            // In the plane (x-y): slides uniformly, gravity held by the plane.
            part("JPRIM/1, INPLANE, I = 20, J = 1", "VX = 1.5, VY = -0.5"),
            &|t, row| vec![(row[1], 1.5 * t), (row[2], -0.5 * t), (row[3], 0.0)],
        ),
        (
            // Axes held: falls and moves without turning.
            part(
                "JPRIM/1, ORIENTATION, I = 20, J = 1",
                "QG = 0, 0, 3, VX = 0.7",
            ),
            &|t, row| {
                vec![
                    (row[1], 0.7 * t),
                    (row[3], 3.0 - 0.5 * g * t * t),
                    (row[4], 1.0),
                ]
            },
        ),
        (
            // z axes parallel: falls freely, turning about z only at its rate.
            part(
                "JPRIM/1, PARALLEL_AXES, I = 20, J = 1",
                "QG = 0, 0, 3, WZ = 3",
            ),
            &|t, row| vec![(row[3], 3.0 - 0.5 * g * t * t), (row[4], (1.5 * t).cos())],
        ),
    ];
    for (text, exact) in &cases {
        let run = run(text, &settings(1.0, 20, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
        for row in &run.rows {
            for (measured, expected) in exact(row[0], row) {
                assert!(
                    (measured - expected).abs() < 1e-7,
                    "{}: t = {}: {measured} against {expected}",
                    text.lines().nth(4).unwrap(),
                    row[0]
                );
            }
        }
    }
}

/// A top on ATPOINT and PERPENDICULAR primitives (its axis held
/// horizontal, J's z vertical): the constraint torques are horizontal
/// and do no work, so the energy and the vertical angular momentum about
/// the pivot stay what they were.
#[test]
fn a_top_held_by_primitives_keeps_its_energy_and_vertical_momentum() {
    let text = top(0.5, std::f64::consts::FRAC_PI_2, 6.0).replace(
        "JOINT/1, SPHERICAL, I = 21, J = 1",
        "JPRIM/1, ATPOINT, I = 21, J = 1\nJPRIM/2, PERPENDICULAR, I = 21, J = 1",
    );
    let run = run(&text, &settings(5.0, 50, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
    let (energy, momentum) = top_invariants(&run.rows[0], 0.5);
    for row in &run.rows {
        let (now_energy, now_momentum) = top_invariants(row, 0.5);
        assert!(
            (now_energy - energy).abs() < 1e-7,
            "t = {}: energy {now_energy} against {energy}",
            row[0]
        );
        assert!(
            (now_momentum - momentum).abs() < 1e-7,
            "t = {}: momentum drifts",
            row[0]
        );
    }
    assert!(
        run.summary.residuals.position <= 1e-8,
        "{:?}",
        run.summary.residuals
    );
}

/// The spatial linkage G (`examples/simulate/g_spatial_linkage.adm`: a
/// SPHERICAL joint, a REVOLUTE on a skewed axis, a TRANSLATIONAL joint
/// with a preloaded SPRINGDAMPER) against Exudyn, an independent multibody
/// code: its three centres of mass over 21 times, the converged limit of
/// Exudyn's fixed steps (Richardson's extrapolation at the observed order
/// 2.00 of h = 2.5e-4 and 1.25e-4; `scripts/exudyn_check.sh` writes it and
/// says how). mbexpr at rtol 1e-12 agrees with it to 8e-11 m.
#[test]
fn a_spatial_linkage_moves_as_exudyn_computes_it() {
    let text = include_str!("../examples/simulate/g_spatial_linkage.adm");
    let reference = super::simulate::reference("g_spatial_linkage_exudyn");
    let model = super::simulate::model_of(text).unwrap_or_else(|error| panic!("{error}"));
    let columns = mbexpr::simulate::columns(&model);
    let at = |name: &str| {
        columns
            .iter()
            .position(|column| column == name)
            .expect(name)
    };
    let centres: Vec<usize> = (1..=3)
        .flat_map(|request| ["DX", "DY", "DZ"].map(|axis| at(&format!("REQUEST/{request}.{axis}"))))
        .collect();
    // method rtol: the largest difference allowed (m)
    let cases = "
        dop853 1e-7: 5e-7
        radau 1e-7: 5e-8
        auto 1e-10: 1e-9
    ";
    for case in cases.lines().map(str::trim).filter(|case| !case.is_empty()) {
        let (run_case, allowed) = case.split_once(':').expect("method rtol: allowed");
        let allowed: f64 = allowed.trim().parse().expect("a number");
        let fields: Vec<&str> = run_case.split_whitespace().collect();
        let mut settings = settings(2.0, 20, fields[1].parse().expect("a tolerance"));
        settings.method = method(fields[0]);
        let run = run(text, &settings).unwrap_or_else(|error| panic!("{error}"));
        assert_eq!(run.rows.len(), reference.len(), "{run_case}: rows");
        let worst = run
            .rows
            .iter()
            .zip(&reference)
            .flat_map(|(row, expected)| {
                assert!((row[0] - expected[0]).abs() < 1e-12, "{run_case}: times");
                centres
                    .iter()
                    .zip(&expected[1..])
                    .map(|(&column, value)| (row[column] - value).abs())
            })
            .fold(0.0, f64::max);
        println!("{run_case}: {worst:.1e} m from Exudyn's limit");
        assert!(
            worst <= allowed,
            "{run_case}: {worst:.1e} m from Exudyn's limit"
        );
    }
}

/// A part drawn 30° and 50 mm from where its joint and MOTION put it (its
/// frame placed by QG and REULER, mm units) is assembled there exactly at
/// the start: Newton's steps on the least change are halved until they
/// lower the residual, since so large a correction is not linear.
#[test]
fn a_part_drawn_far_from_its_joint_is_assembled_exactly() {
    let text = "a part drawn off its joint
UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = MILLIMETER, TIME = SECOND
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2.5, CM = 3, IP = 2000, 3000, 4000, QG = 100, 0, 0, REULER = 30D, 0D, 0D
MARKER/3, PART = 2, QP = 200, 0, 0
MARKER/4, PART = 2, QP = -100, 0, 0
JOINT/1, REVOLUTE, I = 4, J = 1
MOTION/1, JOINT = 1, ROTATION, FUNCTION = 30D * TIME
ACCGRAV/JGRAV = -9806.65
END
";
    let run = run(text, &settings(1.0, 4, 1e-8)).unwrap_or_else(|error| panic!("{error}"));
    for row in &run.rows {
        // The part turns by 30° a second from the MOTION's zero, about the
        // pin at ground's origin 100 mm from the part's origin.
        let angle = (30.0 * row[0]).to_radians();
        let origin = [100.0 * angle.cos(), 100.0 * angle.sin()];
        let turned = 2.0 * row[7].atan2(row[4]);
        assert!((turned - angle).abs() < 1e-8, "t = {}: {turned}", row[0]);
        for (k, expected) in origin.iter().enumerate() {
            assert!(
                (row[1 + k] - expected).abs() < 1e-6,
                "t = {}: {row:?}",
                row[0]
            );
        }
    }
}

/// A model whose joints cannot all hold stops before the run, naming the
/// joint and how far off it is: a second pin 0.4 m from where the part's
/// hole is (its equation along the bar repeats the first pin's to first
/// order, so it is left out, but it does not hold).
#[test]
fn a_model_that_cannot_be_assembled_names_the_joint_and_how_far() {
    let text = "two pins 1 m apart, their holes 0.6 m apart
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 1, 0, 0
PART/2, MASS = 1, CM = 3, IP = 1, 1, 1
MARKER/3, PART = 2, QP = 0.3, 0, 0
MARKER/4, PART = 2
MARKER/5, PART = 2, QP = 0.6, 0, 0
JOINT/1, SPHERICAL, I = 4, J = 1
JOINT/2, SPHERICAL, I = 5, J = 2
END
";
    let error = run(text, &settings(1.0, 4, 1e-6))
        .err()
        .expect("the model cannot run");
    assert!(
        error.contains("cannot be assembled: JOINT/2") && error.contains("4.000e-1"),
        "{error}"
    );
    // Turned so that no equation repeats another, the same disagreement is
    // left after Newton's iterations.
    let skewed = text.replace("QP = 0.6, 0, 0", "QP = 0.6, 0.1, 0.2");
    let error = run(&skewed, &settings(1.0, 4, 1e-6))
        .err()
        .expect("the model cannot run");
    assert!(error.contains("cannot be assembled"), "{error}");
    // Holes placed as a file rounded to 10 digits places them (3e-10 short
    // of the pins' metre) are no disagreement: the data's precision, which
    // Adams assembles; 1e-5 short is one.
    let rounded = text.replace("QP = 0.6, 0, 0", "QP = 0.9999999997, 0, 0");
    let rounded = run(&rounded, &settings(1.0, 4, 1e-6)).expect("rounding assembles");
    assert_eq!(rounded.rows.len(), 5);
    let short = text.replace("QP = 0.6, 0, 0", "QP = 0.99999, 0, 0");
    let error = run(&short, &settings(1.0, 4, 1e-6))
        .err()
        .expect("the model cannot run");
    assert!(
        error.contains("cannot be assembled: JOINT/2") && error.contains("1.000e-5"),
        "{error}"
    );
}

/// A part of 2 kg spun on a hinge about ground z (its centre of mass 0.5
/// m out), under gravity across the hinge and a load of `along` m/s²
/// along it, which the hinge's reaction takes whole and which does no
/// work: the part swings as without it.
fn hinge_loaded_along_its_axis(along: f64) -> String {
    format!(
        "a hinge loaded along its axis
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2, CM = 3, IP = 0.01, 0.2, 0.2, WZ = 1.5707963267948966
MARKER/2, PART = 2
MARKER/3, PART = 2, QP = 0.5, 0, 0
JOINT/1, REVOLUTE, I = 2, J = 1
ACCGRAV/JGRAV = -9.80665, KGRAV = {along}
END
"
    )
}

/// `along method`: the hinge's turn at t = 0.2 with a load of `along`
/// along its axis against the turn without it, at rtol 1e-6. A reaction
/// of 2e9 N turns with any tilt of the hinge the tolerance allows and
/// pushes the part along its swing: held on the joint to the tolerance
/// alone, the turn was 2e-5 to 2.6e-4 rad off (Radau5, DOP853, auto);
/// the joints are now held tighter where the reactions push that hard.
#[test]
fn a_hinge_loaded_along_its_axis_swings_as_unloaded() {
    let turn = |along: f64, method_name: &str| {
        let mut settings = settings(0.2, 1, 1e-6);
        settings.method = method(method_name);
        let run = run(&hinge_loaded_along_its_axis(along), &settings).expect("the hinge runs");
        let last = run.rows.last().expect("a row at the end");
        (angle(last, 4, 0.0), run)
    };
    for case in [
        "1e6 radau",
        "1e6 dop853",
        "1e9 radau",
        "1e9 dop853",
        "1e9 auto",
    ] {
        let (along, method_name) = case.split_once(' ').expect("two fields");
        let along: f64 = along.parse().expect("a number");
        let (unloaded, _) = turn(0.0, method_name);
        let (loaded, run) = turn(along, method_name);
        println!(
            "{case}: turn {loaded:.12} against {unloaded:.12}, {} projections",
            run.summary.projections
        );
        assert!(
            (loaded - unloaded).abs() < 1e-6,
            "{case}: {loaded} {unloaded}"
        );
    }
}

/// A load of 1e15 along the hinge leaves rounding of about 0.1 m/s² in the
/// part's accelerations along the axis, which no step size brings below
/// the tolerance: the steps shrank to 1e-9 s and the run stopped at its
/// budget after 0.4 ms (a mutation fuzz's View file). Those rates are now
/// measured against their rounding where the tolerance would take more
/// than a million steps, and the run says so.
#[test]
fn a_load_far_past_the_doubles_precision_runs_and_says_rounding_held_it() {
    let mut settings = settings(0.01, 1, 1e-6);
    settings.method = Method::Dop853;
    settings.max_steps = 150_000;
    let run = run(&hinge_loaded_along_its_axis(1e15), &settings)
        .expect("the hinge runs within the budget");
    let stats = run.summary.stats;
    println!("{stats}: {} limited by rounding", stats.rounding_limited);
    assert!(stats.rounding_limited > 0 && stats.rounding_limited_from.is_some());
    let unloaded = super::simulate::run(&hinge_loaded_along_its_axis(0.0), &settings)
        .expect("the unloaded hinge runs");
    let (turn, expected) = (
        angle(run.rows.last().expect("a row"), 4, 0.0),
        angle(unloaded.rows.last().expect("a row"), 4, 0.0),
    );
    println!("turn {turn:.12} against {expected:.12}");
    assert!(
        (turn - expected).abs() < 1e-3 * expected.abs(),
        "{turn} {expected}"
    );
}
