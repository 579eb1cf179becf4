//! MOTIONs given as a VELOCITY or an ACCELERATION, integrated from their
//! `ICDISP` (and `ICVEL`): the displacement and the motion's reaction
//! against closed forms.

use std::f64::consts::{PI, TAU};

use super::joints::pendulum;
use super::reactions::{CRANK, crank_angle_and_torque};
use super::simulate::{run, settings};
use mbexpr::integrate::Method;
use mbexpr::simulate::Settings;

const G: f64 = 9.80665;

/// A slider on a TRANSLATIONAL joint along ground z (gravity along −z)
/// driven by `VELOCITY = velocity` from `ICDISP = 0.1`.
fn slider(m: f64, velocity: &str) -> String {
    format!(
        "slider
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = {m}, CM = 20, IP = 1, 2, 3, QG = 0, 0, 0.1
MARKER/20, PART = 2, QP = 0.3, 0.1, 0
MARKER/21, PART = 2
JOINT/1, TRANSLATIONAL, I = 21, J = 1
MOTION/1, JOINT = 1, TRANSLATION, VELOCITY, ICDISP = 0.1, FUNCTION = {velocity}
REQUEST/1, F1 = MOTION(1,0,4,0), F2 = VZ(21, 1)
ACCGRAV/KGRAV = -{G}
END
"
    )
}

/// The slider at `VELOCITY = 2·t`: it is at `0.1 + t²`, and the motion's
/// force on it along z, `MOTION(1, 0, 4, 0)`, is Newton's `m (2 + g)`.
#[test]
fn a_velocity_motion_reaches_the_integral_of_its_function() {
    let m = 1.5;
    let text = slider(m, "2 * TIME");
    for method in [Method::Radau5, Method::Dop853] {
        let mut settings = settings(2.0, 20, 1e-9);
        settings.method = method;
        let run = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let mut worst: f64 = 0.0;
        for row in &run.rows {
            let t = row[0];
            worst = worst
                .max((row[3] - (0.1 + t * t)).abs())
                .max((row[14] - m * (2.0 + G)).abs())
                .max((row[15] - 2.0 * t).abs());
        }
        println!("{method:?}: largest difference {worst:.2e}");
        assert!(worst < 1e-7, "{method:?}: {worst:e}");
    }
}

/// The slider at `VELOCITY = STEP(TIME, 1, 0, 2, 3)`, Adams' cubic blend
/// `3 Δ² (3 − 2Δ)` for `Δ = t − 1` in [0, 1], its second derivative
/// jumping at both ends: the displacement is `0.1` until 1, `0.1 + 3 (Δ³
/// − Δ⁴/2)` on the blend and `1.6 + 3 (t − 2)` after it (the integral of
/// the cubic, by hand), which the quadrature reaches across the kinks.
#[test]
fn a_velocity_motion_integrates_a_step_across_its_kinks() {
    let text = slider(1.5, "STEP(TIME, 1, 0, 2, 3)");
    let run = run(&text, &settings(3.0, 60, 1e-9)).unwrap_or_else(|error| panic!("{error}"));
    let mut worst: f64 = 0.0;
    for row in &run.rows {
        let t: f64 = row[0];
        let delta = (t - 1.0).clamp(0.0, 1.0);
        let exact = 0.1 + 3.0 * (delta.powi(3) - delta.powi(4) / 2.0) + 3.0 * (t - 2.0).max(0.0);
        worst = worst.max((row[3] - exact).abs());
    }
    println!("step: largest difference {worst:.2e}");
    assert!(worst < 1e-8, "{worst:e}");
}

/// The reactions tests' crank driven by `ACCELERATION = −1.6 sin 2t` from
/// `ICDISP = 0`, `ICVEL = 1.1`: its angle and the motion's torque are
/// those of the displacement form `0.3 t + 0.4 sin 2t`.
#[test]
fn an_acceleration_motion_turns_a_crank_as_its_double_integral() {
    let (m, d, izz) = CRANK;
    let text = pendulum(m, d, izz).replace(
        "END",
        "MOTION/1, JOINT = 1, ROTATION, ACCELERATION, ICDISP = 0, ICVEL = 1.1
, FUNCTION = -1.6 * SIN(2 * TIME)
REQUEST/1, F1 = MOTION(1,0,8,0), F2 = AZ(21, 1)
END",
    );
    let run = run(&text, &settings(4.0, 40, 1e-9)).unwrap_or_else(|error| panic!("{error}"));
    let mut worst: f64 = 0.0;
    for row in &run.rows {
        let (theta, torque) = crank_angle_and_torque(row[0]);
        let wrapped = (theta + PI).rem_euclid(TAU) - PI;
        worst = worst
            .max((row[14] - torque).abs())
            .max((row[15] - wrapped).abs());
    }
    println!("crank: largest difference {worst:.2e}");
    assert!(worst < 1e-6, "{worst:e}");
}

/// A part held in x by a MOTION between markers, `X` given as `VELOCITY =
/// 0.6 cos 2t` from `ICDISP = 0.2`: its marker is at `0.2 + 0.3 sin 2t`
/// along x; nothing else moves it.
#[test]
fn a_velocity_motion_between_markers_moves_its_marker() {
    let text = "held
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, QG = 0.2, 0, 0
MARKER/20, PART = 2
MOTION/1, I = 20, J = 1, X, VELOCITY, ICDISP = 0.2, FUNCTION = 0.6 * COS(2 * TIME)
END
";
    let run = run(text, &settings(3.0, 30, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
    let worst = run
        .rows
        .iter()
        .map(|row| (row[1] - (0.2 + 0.3 * (2.0 * row[0]).sin())).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-8, "{worst:e}");
}

/// A displacement motion whose velocity jumps (an ABS's kink, a STEP that
/// starts late, a ramp of a hundredth of a second) turns a pendulum as its
/// FUNCTION says at every output, with both methods: the integrator sees
/// no acceleration before the jump, so the motion's switches are located
/// as events (before, a step crossed the kink and the rows between kept
/// the part still), and AZ keeps no spurious turns across the events'
/// nearly coincident states. Left: Radau5 at rtol 1e-8 cannot step onto
/// the ramp of a hundredth of a second (its acceleration jumps to 1.2e5
/// rad/s², and the drives, unlike the forces, are not held on their
/// branch through a step), and stops with "step size too small".
#[test]
fn a_motion_that_jumps_in_velocity_turns_its_joint_as_written() {
    let both = [Method::Dop853, Method::Radau5];
    let functions: [DrivenCase; 4] = [
        (
            "TIME - 0.5 + ABS(TIME - 0.5)",
            |t| t - 0.5 + (t - 0.5).abs(),
            &both,
        ),
        (
            "STEP(TIME, 0.5, 0, 0.6, 2)",
            |t| step(t, 0.5, 0.6) * 2.0,
            &both,
        ),
        (
            "STEP(TIME, 0.5, 0, 0.51, 2)",
            |t| step(t, 0.5, 0.51) * 2.0,
            &both,
        ),
        (
            "HAVSIN(TIME, 0.3, 0, 0.32, 1)",
            |t| (1.0 - (std::f64::consts::PI * ((t - 0.3) / 0.02).clamp(0.0, 1.0)).cos()) / 2.0,
            &both,
        ),
    ];
    for (function, exact, methods) in functions {
        for gravity in ["", "ACCGRAV/JGRAV = -9.8\n"] {
            let text = driven_pendulum(function, gravity);
            for (&method, rtol) in methods.iter().flat_map(|m| [(m, 1e-8), (m, 1e-11)]) {
                let run = run_at(&text, method, rtol);
                let az = run.rows[0].len() - 1;
                for row in &run.rows {
                    let (t, expected) = (row[0], exact(row[0]));
                    let turned = 2.0 * row[7].atan2(row[4]);
                    assert!(
                        (turned - expected).abs() < 1e-6 && (row[az] - expected).abs() < 1e-6,
                        "{function} {gravity} {method} {rtol}: at t = {t} the part is at {turned} (AZ {}), not {expected}",
                        row[az]
                    );
                }
            }
        }
    }
}

/// A pendulum on a REVOLUTE joint turned by a MOTION of FUNCTION
/// `function`, its AZ the last column, with `gravity` (an ACCGRAV line or
/// nothing).
fn driven_pendulum(function: &str, gravity: &str) -> String {
    format!(
        "driven pendulum
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, IP = 1, 1, 1, CM = 20
MARKER/20, PART = 2, QP = 1, 0, 0
MARKER/21, PART = 2
JOINT/1, REVOLUTE, I = 21, J = 1
MOTION/1, JOINT = 1, ROTATION, FUNCTION = {function}
REQUEST/1, F2 = AZ(21, 1)
{gravity}END
"
    )
}

/// `text` run to t = 1 with 40 outputs by `method` at `rtol`.
fn run_at(text: &str, method: Method, rtol: f64) -> super::simulate::Run {
    run(
        text,
        &Settings {
            method,
            ..settings(1.0, 40, rtol)
        },
    )
    .unwrap_or_else(|error| panic!("{method} {rtol}: {error}"))
}

/// A motion's FUNCTION, its value by hand, and the methods it is run with.
type DrivenCase<'a> = (&'a str, fn(f64) -> f64, &'a [Method]);

/// Adams' cubic STEP from 0 to 1 between `x0` and `x1`.
fn step(x: f64, x0: f64, x1: f64) -> f64 {
    let delta = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    delta * delta * (3.0 - 2.0 * delta)
}

/// AZ keeps its turns across a switch where the angle's acceleration
/// jumps (a ramp's end): the extrapolation that settles its turns takes
/// no parabola through both sides of a switch (before, at rtol 1e-4 a
/// parabola through the end of a 0.1 s ramp to 1.771 rad, taken 0.13 s
/// past it, chose AZ = 1.771 - 2π while the part stood at 1.771).
#[test]
fn az_keeps_its_turns_past_the_end_of_a_ramp_at_loose_tolerances() {
    let function = "STEP(TIME, 0.517, 0, 0.617, 1.771) + STEP(TIME, 0.757, 0, 0.762, 0.681)";
    let exact = |t: f64| 1.771 * step(t, 0.517, 0.617) + 0.681 * step(t, 0.757, 0.762);
    let text = driven_pendulum(function, "");
    for method in [Method::Dop853, Method::Radau5] {
        for rtol in [1e-3, 1e-4] {
            let run = run_at(&text, method, rtol);
            let az = run.rows[0].len() - 1;
            for row in &run.rows {
                let off = (row[az] - exact(row[0])).abs();
                assert!(
                    off < 1e-2,
                    "{method} {rtol}: AZ at t = {} is {off} off",
                    row[0]
                );
            }
        }
    }
}
