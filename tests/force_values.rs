//! Force elements' values during a run: `SFORCE(id, jflag, comp, rm)`,
//! `SPDP(...)` and `BUSH(...)` read in REQUESTs, checked against closed
//! forms (a spring's `−k (x − L)` on its I marker and Newton's third law
//! on J, a spring-damper's `−k (x − L) − c ẋ`; a bushing's
//! `−K d` and the moment arm `−(I − J) × F` of its reaction on J), and
//! refused in a force.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use super::accelerations::worst;
use super::simulate::{run, settings};

/// The first REQUEST column: after the time and 13 of the part.
const FIRST: usize = 14;

/// A 1 kg part on a spring of stiffness 10 and free length 1 to ground's
/// origin, released at x = 1.5: it oscillates as `x = 1 + 0.5 cos √10 t`.
/// SFORCE(1, 0, 2, 0) is the spring's pull on I, `−k (x − L)`; on J it is
/// the opposite; |F| is its size; the line of action passes through J,
/// so neither takes a torque about its own marker.
#[test]
fn a_springs_sforce_is_its_pull_and_j_takes_the_opposite() {
    let text = "spring
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, QG = 1.5, 0, 0
MARKER/20, PART = 2
SFORCE/1, TRANSLATIONAL, I = 20, J = 1, FUNCTION = -10 * (DM(20, 1) - 1)
REQUEST/1, F1 = SFORCE(1,0,1,0), F2 = SFORCE(1,0,2,0), F3 = DX(20, 1), F4 = SFORCE(1,1,2,0)
, F5 = SFORCE(1,0,8,0), F6 = SFORCE(1,1,8,0), F7 = SFORCE(1,1,3,0), F8 = SFORCE(1,1,2,20)
END
";
    let run = run(text, &settings(2.0, 40, 1e-11)).expect("the spring runs");
    let worst = worst(&run.rows, |row| {
        let x = 1.0 + 0.5 * (10f64.sqrt() * row[0]).cos();
        let pull = -10.0 * (x - 1.0);
        // The part does not turn: its marker's x is ground's.
        ([pull.abs(), pull, x, -pull, 0.0, 0.0, 0.0, -pull], 1.0)
    });
    println!("spring: largest difference {worst:.2e} N");
    assert!(worst < 1e-8, "{worst}");
}

/// A SPRINGDAMPER's `SPDP(id, jflag, comp, rm)` is its pull on I, `−k (x
/// − L) − c ẋ` along the line from J, and the opposite on J: the part of
/// 1 kg released at x = 1.5 on a spring of stiffness 10, damping 0.4 and
/// free length 1 moves as `x = 1 + e^(−0.2 t)(0.5 cos ω t + 0.1/ω sin ω
/// t)`, `ω = √(10 − 0.04)`.
#[test]
fn a_springdampers_spdp_is_its_pull_and_j_takes_the_opposite() {
    let text = "spring-damper
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, QG = 1.5, 0, 0
MARKER/20, PART = 2
SPRINGDAMPER/1, TRANSLATIONAL, I = 20, J = 1, K = 10, C = 0.4, LENGTH = 1
REQUEST/1, F1 = SPDP(1,0,1,0), F2 = SPDP(1,0,2,0), F3 = DX(20, 1), F4 = SPDP(1,1,2,0)
, F5 = SPDP(1,0,8,0), F6 = SPDP(1,1,8,0), F7 = SPDP(1,1,3,0), F8 = SPDP(1,1,2,20)
END
";
    let run = run(text, &settings(2.0, 40, 1e-11)).expect("the spring-damper runs");
    let omega = (10.0f64 - 0.04).sqrt();
    let worst = worst(&run.rows, |row| {
        let t = row[0];
        let decay = (-0.2 * t).exp();
        let (sin, cos) = (omega * t).sin_cos();
        let x = 1.0 + decay * (0.5 * cos + 0.1 / omega * sin);
        let v = decay
            * (-0.2 * (0.5 * cos + 0.1 / omega * sin) + omega * (-0.5 * sin + 0.1 / omega * cos));
        let pull = -10.0 * (x - 1.0) - 0.4 * v;
        ([pull.abs(), pull, x, -pull, 0.0, 0.0, 0.0, -pull], 1.0)
    });
    println!("spring-damper: largest difference {worst:.2e} N");
    assert!(worst < 1e-8, "{worst}");
}

/// A part held by a BUSHING of stiffness (100, 200, 300) between its
/// centre of mass (I) and ground's origin (J), released at (0.3, 0.2, 0):
/// on I the bushing pushes `F = −K d` with `d` the displacement of I from
/// J in J's axes; on J it pushes `−F` and turns it by `−d × F`, the moment
/// arm Adams gives the reaction; I takes no torque (no KT).
#[test]
fn a_bushings_force_on_j_carries_the_moment_arm() {
    let text = "bushing
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2, CM = 20, IP = 1, 1, 1, QG = 0.3, 0.2, 0
MARKER/20, PART = 2
BUSHING/1, I = 20, J = 1, K = 100, 200, 300
REQUEST/1, F1 = DX(20, 1, 1), F2 = DY(20, 1, 1), F3 = BUSH(1,0,2,0), F4 = BUSH(1,0,3,0)
, F5 = BUSH(1,1,2,0), F6 = BUSH(1,1,3,0), F7 = BUSH(1,1,8,0), F8 = BUSH(1,0,8,0)
END
";
    let run = run(text, &settings(2.0, 40, 1e-11)).expect("the bushing runs");
    let worst = worst(&run.rows, |row| {
        let (dx, dy) = (row[FIRST], row[FIRST + 1]);
        let (fx, fy) = (-100.0 * dx, -200.0 * dy);
        ([dx, dy, fx, fy, -fx, -fy, -(dx * fy - dy * fx), 0.0], 1.0)
    });
    println!("bushing: largest difference {worst:.2e}");
    assert!(worst < 1e-9, "{worst}");
    // It moves in the plane: the moment arm is not zero along the way.
    assert!(run.rows.iter().any(|row| row[FIRST + 6].abs() > 1.0));
}

/// What cannot be read is refused before the run, at its place: an
/// element the model does not have, a flag out of range.
#[test]
fn force_values_that_cannot_be_had_are_refused_before_the_run() {
    let model = "spring
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, QG = 1.5, 0, 0
MARKER/20, PART = 2
SFORCE/1, TRANSLATIONAL, I = 20, J = 1, FUNCTION = -10 * (DM(20, 1) - 1)
LINE
END
";
    let cases = [
        ("REQUEST/1, F1 = SFORCE(1,2,2,0)", "jflag must be 0"),
        ("REQUEST/1, F1 = SFORCE(1,0,9,0)", "comp must be 1 to 8"),
        ("REQUEST/1, F1 = GFORCE(1,0,2,0)", "GFORCE/1"),
    ];
    for (line, expected) in cases {
        let text = model.replace("LINE", line);
        let error = run(&text, &settings(1.0, 1, 1e-8)).err().expect("refused");
        assert!(error.contains(expected), "{line}: {error}");
    }
}

/// The joints tests' pendulum (2 kg, centre 0.5 m from its revolute pivot,
/// Izz 0.03, gravity along −y) turned by a constant torque of 0.3 N·m
/// about z (SFORCE/1, ROTATIONAL, I = 21 on the pendulum at the pivot, J =
/// 1 on ground): the net force at 21 from 1 (the joint's and the torque's)
/// is Newton's `m (a − g)` with `α = (r × m g + 0.3) / (Izz + m d²)`, its
/// torque about z the applied 0.3 (the revolute takes none about its
/// axis); at 1 from 21 the opposite; FM(21) with J left out sums all at 21.
/// REQUEST/2, FORCE gives the same at 21 from 1 in Adams' columns `FM FX
/// FY FZ TM TX TY TZ` (the motion is planar: no force along z, no torque
/// across it).
#[test]
fn the_net_force_between_markers_sums_the_joint_and_the_torque() {
    let (m, d, izz) = (2.0, 0.5, 0.03);
    let text = super::joints::pendulum(m, d, izz).replace(
        "END",
        "SFORCE/1, ROTATIONAL, I = 21, J = 1, FUNCTION = 0.3
REQUEST/1, F1 = FX(21, 1), F2 = FY(21, 1), F3 = TZ(21, 1), F4 = FX(1, 21)
, F5 = FY(1, 21), F6 = TZ(1, 21), F7 = FM(21), F8 = TM(21, 1)
REQUEST/2, FORCE, I = 21, J = 1
END",
    );
    let model = super::simulate::model_of(&text).expect("the pendulum reads");
    insta::assert_snapshot!(mbexpr::simulate::columns(&model)[FIRST + 8..].join(" "));
    let swinging = run(&text, &settings(2.0, 40, 1e-10)).expect("the pendulum swings");
    let gravity = Vector3::new(0.0, -9.80665, 0.0);
    let worst = worst(&swinging.rows, |row| {
        let q = UnitQuaternion::from_quaternion(Quaternion::new(row[4], row[5], row[6], row[7]));
        let omega = Vector3::new(row[11], row[12], row[13]);
        let r = q * Vector3::new(d, 0.0, 0.0);
        let alpha = (r.cross(&(gravity * m)) + Vector3::new(0.0, 0.0, 0.3)) / (izz + m * d * d);
        let a = alpha.cross(&r) + omega.cross(&omega.cross(&r));
        let joint = (a - gravity) * m;
        let expected = [
            joint.x,
            joint.y,
            0.3,
            -joint.x,
            -joint.y,
            -0.3,
            joint.norm(),
            0.3,
            joint.norm(),
            joint.x,
            joint.y,
            0.0,
            0.3,
            0.0,
            0.0,
            0.3,
        ];
        (expected, 1.0 + joint.norm())
    });
    println!("net force: worst relative difference {worst:.2e}");
    assert!(worst < 1e-7, "{worst}");
    // A torque that reads the net force is solved with it: at every row
    // the torque column is what the function gives of the force column.
    let reading = text.replace("FUNCTION = 0.3", "FUNCTION = 0.3 + 0.01 * FX(21, 1)");
    let swinging = run(&reading, &settings(1.0, 10, 1e-10)).expect("the torque reads FX");
    for row in &swinging.rows {
        let (fx, tz) = (row[FIRST], row[FIRST + 2]);
        assert!((tz - (0.3 + 0.01 * fx)).abs() < 1e-10, "{row:?}");
    }
}
