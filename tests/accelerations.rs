//! Accelerations during a run: `ACCX ... ACCM` and `WDTX ... WDTM` read in
//! REQUESTs and VARIABLEs, checked against closed forms worked out here
//! (free fall with the Coriolis and centrifugal terms of a spinning frame,
//! a pendulum's centripetal and tangential parts by hand, a spun-up body's
//! marker off its centre of mass seen from ground and from the body), and
//! refused in a motion.

use nalgebra::{UnitQuaternion, Vector3};

use super::joints::pendulum;
use super::simulate::{run, settings};

const G: f64 = 9.80665;

/// The columns after the time: 13 of the part, then the outputs.
const FIRST: usize = 14;

/// The part's orientation and angular velocity in ground from a row.
fn turned(row: &[f64]) -> (UnitQuaternion<f64>, Vector3<f64>) {
    let q =
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(row[4], row[5], row[6], row[7]));
    (q, Vector3::new(row[11], row[12], row[13]))
}

/// The largest difference between the outputs of each row (the columns
/// after one part's) and what `expected` gives for the row, each over the
/// scale it gives with them.
pub(super) fn worst<const N: usize>(
    rows: &[Vec<f64>],
    expected: impl Fn(&[f64]) -> ([f64; N], f64),
) -> f64 {
    let mut worst: f64 = 0.0;
    for row in rows {
        let (expected, scale) = expected(row);
        for (found, expected) in row[FIRST..].iter().zip(expected) {
            worst = worst.max((found - expected).abs() / scale);
        }
    }
    worst
}

/// The pendulum's centre of mass from the pivot, its angular velocity and
/// its angular acceleration `r × m g / (Izz + m d²)` (the moment of gravity
/// along −y about the pivot), from a row's state columns.
fn swing(row: &[f64], m: f64, d: f64, izz: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let (q, omega) = turned(row);
    let r = q * Vector3::new(d, 0.0, 0.0);
    let alpha = r.cross(&Vector3::new(0.0, -G * m, 0.0)) / (izz + m * d * d);
    (r, omega, alpha)
}

/// A ball thrown from ground's origin at (3, 4, 0) m/s under gravity along
/// −y, spinning at ω = (1, 0, 2) rad/s (a sphere's inertia: ω stays).
/// Its centre accelerates at `g` in ground, with no angular acceleration;
/// derived in the ball's own spinning frame its position `p = (3t, 4t −
/// g t²/2, 0)` has the acceleration `p'' − 2 ω × p' + ω × (ω × p)`
/// (Coriolis and centrifugal), along ground's y (F7) and the ball's (F8).
/// VARIABLE/1 = ACCY(20) is a column too.
#[test]
fn a_falling_spinning_ball_accelerates_at_g_and_feels_its_frames_terms() {
    let text = "ball
PART/1, GROUND
PART/2, MASS = 2, CM = 20, IP = 0.1, 0.1, 0.1, VX = 3, VY = 4, WX = 1, WZ = 2
MARKER/20, PART = 2
ACCGRAV/JGRAV = -9.80665
REQUEST/1, F1 = ACCM(20), F2 = ACCX(20), F3 = ACCY(20), F4 = ACCZ(20)
, F5 = WDTM(20), F6 = WDTX(20, 0, 20), F7 = ACCY(20, 0, 0, 20), F8 = ACCY(20, 0, 20, 20)
VARIABLE/1, FUNCTION = ACCY(20)
END
";
    let run = run(text, &settings(1.0, 10, 1e-11)).expect("the ball flies");
    let omega = Vector3::new(1.0, 0.0, 2.0);
    let g = Vector3::new(0.0, -G, 0.0);
    let worst = worst(&run.rows, |row| {
        let t = row[0];
        let (q, _) = turned(row);
        let p = Vector3::new(3.0 * t, 4.0 * t - G * t * t / 2.0, 0.0);
        let v = Vector3::new(3.0, 4.0 - G * t, 0.0);
        let spinning = g - 2.0 * omega.cross(&v) + omega.cross(&omega.cross(&p));
        let expected = [
            G,
            0.0,
            -G,
            0.0,
            0.0,
            0.0,
            spinning.y,
            spinning.dot(&(q * Vector3::y())),
            -G,
        ];
        (expected, 1.0)
    });
    println!("falling ball: largest difference {worst:.2e} m/s²");
    assert!(worst < 1e-8, "{worst}");
}

/// The joints tests' pendulum (mass 2 kg, centre of mass 0.5 m from its
/// revolute pivot at ground's origin, Izz 0.03) released horizontal under
/// gravity along −y: its centre accelerates at `α × r + ω × (ω × r)` with
/// `α = r × m g / (Izz + m d²)` from the moment about the pivot; along the
/// part's own axes (x along r) that is `−ω² d` (centripetal, F3) and `α d`
/// (tangential, F4); WDTZ is α; and marker 20 against marker 21 of the
/// same part, derived in the part, does not accelerate (F7).
#[test]
fn a_pendulums_centre_accelerates_centripetally_and_tangentially() {
    let (m, d, izz) = (2.0, 0.5, 0.03);
    let text = pendulum(m, d, izz).replace(
        "END",
        "REQUEST/1, F1 = ACCX(20), F2 = ACCY(20), F3 = ACCX(20, 0, 20), F4 = ACCY(20, 0, 20)
, F5 = WDTZ(20), F6 = ACCM(20), F7 = ACCM(20, 21, 20), F8 = WDTZ(20, 0, 0, 20)
END",
    );
    let run = run(&text, &settings(2.0, 40, 1e-10)).expect("the pendulum swings");
    let worst = worst(&run.rows, |row| {
        let (r, omega, alpha) = swing(row, m, d, izz);
        let a = alpha.cross(&r) + omega.cross(&omega.cross(&r));
        let expected = [
            a.x,
            a.y,
            -omega.norm_squared() * d,
            alpha.z * d,
            alpha.z,
            a.norm(),
            0.0,
            alpha.z,
        ];
        (expected, 1.0 + a.norm())
    });
    println!("pendulum accelerations: worst relative difference {worst:.2e}");
    assert!(worst < 1e-7, "{worst}");
}

/// A free part turning about its z axis (a principal axis) at 1 rad/s,
/// spun up by a constant torque of 0.5 N·m about z (Izz = 0.2): its angular
/// acceleration, read as the slope of its angular velocity between the
/// first and last rows, is ±2.5 rad/s² and is WDTZ; marker 30, 0.5 m off
/// the centre of mass, accelerates at `α × r + ω × (ω × r)` in ground
/// (against the centre, F1 F2, and against ground, F3), and not at all
/// derived in the part's own frame (F4, F5).
#[test]
fn a_marker_off_a_spun_up_parts_centre_accelerates_as_the_rigid_body_says() {
    let text = "spun
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 3, CM = 20, IP = 0.1, 0.1, 0.2, WZ = 1
MARKER/20, PART = 2
MARKER/30, PART = 2, QP = 0.5, 0, 0
SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = 0.5
REQUEST/1, F1 = ACCX(30, 20), F2 = ACCY(30, 20), F3 = ACCM(30), F4 = ACCM(30, 0, 20)
, F5 = ACCX(30, 0, 20, 20), F6 = WDTZ(20), F7 = WDTM(30, 20)
END
";
    let duration = 2.0;
    let run = run(text, &settings(duration, 20, 1e-11)).expect("the part spins up");
    let first = turned(&run.rows[0]).1.z;
    let last = turned(&run.rows[run.rows.len() - 1]).1.z;
    let alpha = (last - first) / duration;
    assert!((alpha.abs() - 2.5).abs() < 1e-8, "{alpha}");
    let worst = worst(&run.rows, |row| {
        let (q, omega) = turned(row);
        let r = q * Vector3::new(0.5, 0.0, 0.0);
        let a = Vector3::new(0.0, 0.0, alpha).cross(&r) + omega.cross(&omega.cross(&r));
        ([a.x, a.y, a.norm(), 0.0, 0.0, alpha, 0.0], 1.0 + a.norm())
    });
    println!("spun-up part: worst relative difference {worst:.2e}");
    assert!(worst < 1e-8, "{worst}");
}

/// A MOTION reading an acceleration is refused at the call, before the
/// run, with the reason: its constraint must hold before the forces are
/// known (a force reading one is solved with it: `tests/loop_values.rs`).
#[test]
fn a_motion_reading_an_acceleration_is_refused_at_the_call() {
    let (m, d, izz) = (2.0, 0.5, 0.03);
    let text = pendulum(m, d, izz).replace(
        "END",
        "MOTION/1, JOINT = 1, ROTATION, FUNCTION = -0.1 * ACCX(20)\nEND",
    );
    let error = run(&text, &settings(1.0, 1, 1e-8)).err().expect("refused");
    assert!(
        error.contains("ACCX(20,0,0,0): a MOTION or GCON that reads a value of the running solver"),
        "{error}"
    );
}

/// A REQUEST of ACCELERATION gives Adams' columns `ACCM ACCX ACCY ACCZ
/// WDTM WDTX WDTY WDTZ` of I against J (derivatives in ground) along RM's
/// axes: the pendulum's centre against the pivot, along the part's own
/// axes, is `(−ω² d, α d, 0)` with `α` from the moment about the pivot.
#[test]
fn a_request_of_acceleration_gives_adams_columns() {
    let (m, d, izz) = (2.0, 0.5, 0.03);
    let text = pendulum(m, d, izz).replace(
        "END",
        "REQUEST/1, ACCELERATION, I = 20, J = 1, RM = 20\nEND",
    );
    let model = super::simulate::model_of(&text).expect("the pendulum reads");
    insta::assert_snapshot!(mbexpr::simulate::columns(&model)[FIRST..].join(" "));
    let run = run(&text, &settings(2.0, 40, 1e-10)).expect("the pendulum swings");
    let worst = worst(&run.rows, |row| {
        let (_, omega, alpha) = swing(row, m, d, izz);
        let (radial, tangential) = (-omega.norm_squared() * d, alpha.z * d);
        let expected = [
            radial.hypot(tangential),
            radial,
            tangential,
            0.0,
            alpha.z.abs(),
            0.0,
            0.0,
            alpha.z,
        ];
        (expected, 1.0)
    });
    println!("REQUEST of ACCELERATION: largest difference {worst:.2e}");
    assert!(worst < 1e-9, "{worst}");
}

/// `DIF1(id)` in a run is the rate the right-hand side computes for the
/// DIFF: a DIFF `2 t + DX(20)` beside a part moving at 3 m/s along x
/// integrates to `2.5 t²`, and VARIABLE/1 = DIF1(1) is `5 t`.
#[test]
fn dif1_in_a_run_is_the_diffs_rate() {
    let text = "rate
PART/1, GROUND
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, VX = 3
MARKER/20, PART = 2
DIFF/1, IC = 0, FUNCTION = 2 * TIME + DX(20)
VARIABLE/1, FUNCTION = DIF1(1)
END
";
    let run = run(text, &settings(2.0, 20, 1e-11)).expect("the DIFF runs");
    let mut worst: f64 = 0.0;
    for row in &run.rows {
        let t = row[0];
        // time, DIF(1), 13 of the part, VARIABLE/1.
        worst = worst
            .max((row[1] - 2.5 * t * t).abs())
            .max((row[15] - 5.0 * t).abs());
    }
    println!("DIF1: largest difference {worst:.2e}");
    assert!(worst < 1e-9, "{worst}");
}
