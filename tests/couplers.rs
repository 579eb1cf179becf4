//! COUPLER: joints' displacements tied by their scales, `Σ s q = 0`. Two
//! wheels on revolute joints geared 1 : 2.7 under a torque on the first,
//! and a pinion driving a rack, turn several times as the one freedom
//! left under the reflected inertia says (closed forms written here); the
//! coupling holds to the integration error (it is kept at the level of the
//! velocities). GEAR: the same coupling with the scales its CV marker's
//! place gives (spur wheels and a rack and pinion, closed forms).

use super::simulate::{run, settings};

/// The first REQUEST column: after the time and 13 states of each of the
/// two parts.
const FIRST: usize = 27;

/// The largest difference, relative to the first wheel's turn (at least
/// 1), of the rows' `AZ1` and `AZ2` from the closed form of two geared
/// wheels: `AZ1 = ½ α t²` (α the torque over the reflected inertia),
/// `AZ2 = −ratio AZ1`.
fn geared_difference(rows: &[Vec<f64>], alpha: f64, ratio: f64) -> f64 {
    rows.iter()
        .map(|row| {
            let t = row[0];
            let first = 0.5 * alpha * t * t;
            let (az1, az2) = (row[FIRST], row[FIRST + 1]);
            (az1 - first).abs().max((az2 + first * ratio).abs()) / first.abs().max(1.0)
        })
        .fold(0.0, f64::max)
}

/// Two wheels (Izz `i1`, `i2`) on revolute joints at their own pivots on
/// ground, coupled `AZ1 + ratio·AZ2 = 0`, a torque `torque` on the first,
/// and a REQUEST of the columns `request`.
fn geared_wheels((i1, i2, ratio, torque): (f64, f64, f64, f64), request: &str) -> String {
    format!(
        "gears
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 1, 0, 0
PART/2, MASS = 1, CM = 20, IP = 1, 1, {i1}
MARKER/20, PART = 2
PART/3, MASS = 1, CM = 30, IP = 1, 1, {i2}, QG = 1, 0, 0
MARKER/30, PART = 3
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, REVOLUTE, I = 30, J = 2
COUPLER/1, JOINTS = 1, 2, TYPE = R:R, SCALES = 1, {ratio}
SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = {torque}
REQUEST/1, {request}
END
"
    )
}

/// Adams' short form of SCALES, the first scale left out (it is 1),
/// couples the wheels as the full form does.
#[test]
fn scales_without_the_first_take_it_as_1() {
    let full = geared_wheels((0.5, 0.2, 2.7, 3.0), "F1 = AZ(20, 1), F2 = AZ(30, 2)");
    let short = full.replace("SCALES = 1, 2.7", "SCALES = 2.7");
    assert_ne!(full, short);
    let settings = settings(1.0, 10, 1e-9);
    let (full, short) = (run(&full, &settings), run(&short, &settings));
    assert_eq!(
        full.expect("the full form runs").rows,
        short.expect("the short form runs").rows
    );
}

/// Two wheels (Izz `i1`, `i2`) turning about ground's z at their own
/// pivots, `AZ1 + ratio·AZ2 = 0`, a torque `torque` on the first:
/// `AZ1 = ½ τ/(I1 + I2/ratio²) t²`.
#[test]
fn two_geared_wheels_turn_as_their_reflected_inertia_says() {
    for (i1, i2, ratio, torque) in [
        (0.5, 0.2, 2.7, 3.0),
        (1.0, 4.0, -0.6, 30.0),
        (0.1, 0.1, 1.0, 2.0),
    ] {
        let text = geared_wheels((i1, i2, ratio, torque), "F1 = AZ(20, 1), F2 = AZ(30, 2)");
        let run = run(&text, &settings(4.0, 40, 1e-9)).expect("the gears turn");
        let reflected = i1 + i2 / (ratio * ratio);
        let worst = geared_difference(&run.rows, torque / reflected, 1.0 / ratio);
        let turns = run.rows.last().unwrap()[FIRST] / std::f64::consts::TAU;
        println!(
            "I {i1} {i2} ratio {ratio}: {turns:.1} turns, largest relative difference {worst:.2e}"
        );
        assert!(turns.abs() > 1.0, "{turns}");
        assert!(worst < 1e-6, "{worst}");
    }
}

/// The net torque at each wheel's joint markers, `TZ(i, j, j)` (and with
/// j = 0, everything at I), counts what the coupler applies through that
/// joint: with no other torque about z on a wheel but the SFORCE on the
/// first, it is each wheel's `Izz α` (the revolute joint's own reaction
/// has no z torque), `α1 = τ/(I1 + I2/ratio²)`, `α2 = −α1/ratio`.
#[test]
fn the_net_torque_at_a_coupled_joint_is_what_turns_its_wheel() {
    for (i1, i2, ratio, torque) in [(0.5, 0.2, 2.7, 3.0), (1.0, 4.0, -0.6, 30.0)] {
        let text = geared_wheels(
            (i1, i2, ratio, torque),
            "F1 = TZ(20, 1, 1), F2 = TZ(30, 2, 2), F3 = TZ(30, 0, 2), F4 = TZ(2, 30, 2)",
        );
        let run = run(&text, &settings(1.0, 10, 1e-9)).expect("the gears turn");
        let alpha1 = torque / (i1 + i2 / (ratio * ratio));
        let expected = [i1 * alpha1, -i2 * alpha1 / ratio];
        let worst = run
            .rows
            .iter()
            .map(|row| {
                let columns = &row[FIRST..FIRST + 4];
                let off = [
                    columns[0] - expected[0],
                    columns[1] - expected[1],
                    columns[2] - expected[1],
                    // On the other side of the joint, the opposite.
                    columns[3] + expected[1],
                ];
                off.iter().map(|d| d.abs()).fold(0.0, f64::max) / torque
            })
            .fold(0.0, f64::max);
        println!("I {i1} {i2} ratio {ratio}: net torques off by {worst:.2e} of the torque");
        assert!(worst < 1e-7, "{worst}");
    }
}

/// A pinion (radius 0.25, Izz 0.05) on a revolute joint and a rack (mass
/// 2) on a translational joint along ground's x, `0.25·θ − x = 0`, a force
/// of 4 on the rack: `x = ½ F/(m + I/r²) t²`.
#[test]
fn a_pinion_drives_a_rack_as_the_reflected_mass_says() {
    let text = "rack and pinion
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 0, -0.25, 0, REULER = 90D, 90D, 0D
PART/2, MASS = 1, CM = 20, IP = 1, 1, 0.05
MARKER/20, PART = 2
PART/3, MASS = 2, CM = 30, IP = 1, 1, 1, QG = 0, -0.25, 0
MARKER/30, PART = 3, REULER = 90D, 90D, 0D
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, TRANSLATIONAL, I = 30, J = 2
COUPLER/1, JOINTS = 1, 2, TYPE = R:T, SCALES = 0.25, -1
SFORCE/1, TRANSLATIONAL, ACTIONONLY, I = 30, J = 2, FUNCTION = 4
REQUEST/1, F1 = AZ(20, 1), F2 = DZ(30, 2, 2)
END
";
    let run = run(text, &settings(3.0, 30, 1e-9)).expect("the rack moves");
    let reflected = 2.0 + 0.05 / (0.25 * 0.25);
    let worst = run
        .rows
        .iter()
        .map(|row| {
            let x = 0.5 * 4.0 / reflected * row[0] * row[0];
            (row[FIRST + 1] - x)
                .abs()
                .max((0.25 * row[FIRST] - x).abs())
        })
        .fold(0.0, f64::max);
    println!("rack: largest difference {worst:.2e}");
    assert!(worst < 1e-7, "{worst}");
}

/// Geared wheels on a torsion spring and a damper: the bodies a coupler
/// ties share their multipliers in the Jacobian's pattern.
const SPRUNG: &str = "sprung gears
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 1, 0, 0
PART/2, MASS = 1, CM = 20, IP = 1, 1, 0.5
MARKER/20, PART = 2
PART/3, MASS = 1, CM = 30, IP = 1, 1, 0.2, QG = 1, 0, 0, WZ = 3
MARKER/30, PART = 3
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, REVOLUTE, I = 30, J = 2
COUPLER/1, JOINTS = 1, 2, TYPE = R:R, SCALES = 1, 2.7
SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = -4*AZ(20, 1) - 0.3*WZ(20, 1, 1)
END
";

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(12))]

    /// The Jacobian through a coupler's multiplier agrees with central
    /// differences.
    #[test]
    fn the_jacobian_of_coupled_joints_agrees_with_finite_differences(
        shifts in proptest::collection::vec(-0.05f64..0.05, 26),
        time in 0.0f64..3.0,
    ) {
        super::simulate::the_jacobian_agrees_with_finite_differences(SPRUNG, &shifts, time)?;
    }
}

/// What a coupler statement that cannot be held reports.
fn check(coupler: &str) -> String {
    let text = format!(
        "refused
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1
MARKER/20, PART = 2
PART/3, MASS = 1, CM = 30, IP = 1, 1, 1
MARKER/30, PART = 3
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, SPHERICAL, I = 30, J = 1
{coupler}
END
"
    );
    match run(&text, &settings(1.0, 1, 1e-6)) {
        Ok(_) => "ran".to_string(),
        Err(error) => error.trim_end().to_string(),
    }
}

#[test]
fn couplers_that_cannot_be_held_are_refused_at_their_place() {
    let cases = "
        COUPLER/1, JOINTS = 1, 2, SCALES = 1, 1
        COUPLER/1, JOINTS = 1, 3, SCALES = 1, 1
        COUPLER/1, JOINTS = 1, SCALES = 1
        COUPLER/1, JOINTS = 1, 2, SCALES = 1, 2, 3
        COUPLER/1, JOINTS = 1, 2
        COUPLER/1, FUNCTION = USER(1, 2)
        COUPLER/1, JOINTS = 1, 1, SCALES = 1, -1
    ";
    insta::assert_snapshot!(super::table(cases, check));
}

/// GEAR: two spur wheels of pitch radii `r1`, `r2` on revolute joints to
/// ground (the carrier), their contact at CV on the line of centres, CV's
/// z along the teeth's motion (ground's y): external gears turn opposite,
/// `r1 AZ1 = −r2 AZ2`, as the COUPLER with scales `r1, r2` does, so under
/// a torque on the first `AZ1 = ½ τ/(I1 + I2 (r1/r2)²) t²`. The second
/// joint is written both ways round (its I marker on the wheel, or on
/// ground), and CV's z both ways: the same motion. The teeth push along
/// ground's y at the contact, as Adams' GEAR does, `F = I2 α2 / r2` on the
/// second wheel, so each joint holds that force and no torque (a coupler
/// would put a torque on each wheel, and no force on its joint).
#[test]
fn a_gear_turns_its_wheels_as_their_pitch_radii_say() {
    let (i1, i2, torque) = (0.5, 0.2, 3.0);
    for (r1, r2) in [(0.1, 0.27), (0.3, 0.15)] {
        for (second, cv) in [
            ("I = 30, J = 2", "REULER = 0, -90D, 0"),
            ("I = 2, J = 30", "REULER = 0, -90D, 0"),
            ("I = 30, J = 2", "REULER = 0, 90D, 0"),
        ] {
            let text = format!(
                "spur gears
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = {centre}, 0, 0
MARKER/3, PART = 1, QP = {r1}, 0, 0, {cv}
PART/2, MASS = 1, CM = 20, IP = 1, 1, {i1}
MARKER/20, PART = 2
PART/3, MASS = 1, CM = 30, IP = 1, 1, {i2}, QG = {centre}, 0, 0
MARKER/30, PART = 3
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, REVOLUTE, {second}
GEAR/1, JOINTS = 1, 2, CV = 3
SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = {torque}
REQUEST/1, F1 = AZ(20, 1), F2 = AZ(30, 2), F3 = JOINT(1, 0, 3, 0), F4 = JOINT(2, 0, 3, 0)
REQUEST/2, F1 = JOINT(1, 0, 8, 0), F2 = JOINT(2, 0, 8, 0), F3 = JOINT(2, 1, 3, 0)
END
",
                centre = r1 + r2
            );
            let run = run(&text, &settings(3.0, 30, 1e-9))
                .unwrap_or_else(|error| panic!("{second} {cv}: {error}"));
            let ratio = r1 / r2;
            let reflected = i1 + i2 * ratio * ratio;
            // The tooth's push along y on the second wheel, and the second
            // joint's on the wheel (on its I marker, or its J).
            let push = i2 * ratio * (torque / reflected) / r2;
            let on_wheel = if second.starts_with("I = 30") {
                [FIRST + 3, FIRST + 6]
            } else {
                [FIRST + 6, FIRST + 3]
            };
            for row in &run.rows {
                let expected = [
                    (FIRST + 2, push),
                    (on_wheel[0], -push),
                    (on_wheel[1], push),
                    (FIRST + 4, 0.0),
                    (FIRST + 5, 0.0),
                ];
                for (column, value) in expected {
                    assert!(
                        (row[column] - value).abs() < 1e-8,
                        "{second} {cv}: column {column} {} against {value}",
                        row[column]
                    );
                }
            }
            let worst = geared_difference(&run.rows, torque / reflected, ratio);
            println!(
                "GEAR r {r1} {r2}, {second}, CV {cv}: largest relative difference {worst:.2e}"
            );
            assert!(worst < 1e-6, "{second} {cv}: {worst}");
        }
    }
}

/// A GEAR of a pinion (pitch radius 0.05, on a revolute joint to ground)
/// and a rack (mass 3, on a translational joint along ground's x, the
/// contact below the pinion): the pinion's bottom moves along +x as it
/// turns counterclockwise, so the rack is at `x = r θ`, and under a torque
/// `θ = ½ τ/(Ip + m r²) t²`.
#[test]
fn a_gear_drives_a_rack_from_its_pinion() {
    let (r, ip, m, torque) = (0.05, 0.01, 3.0, 0.2);
    let text = format!(
        "rack and pinion
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, REULER = 90D, 90D, 0
MARKER/3, PART = 1, QP = 0, -{r}, 0, REULER = 90D, 90D, 0
PART/2, MASS = 1, CM = 20, IP = 1, 1, {ip}
MARKER/20, PART = 2
PART/3, MASS = {m}, CM = 30, IP = 1, 1, 1, QG = 0, -0.2, 0
MARKER/30, PART = 3
MARKER/31, PART = 3, REULER = 90D, 90D, 0
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, TRANSLATIONAL, I = 31, J = 2
GEAR/1, JOINTS = 1, 2, CV = 3
SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = {torque}
REQUEST/1, F1 = AZ(20, 1), F2 = DX(30)
END
"
    );
    let run = run(&text, &settings(2.0, 20, 1e-10)).expect("the rack moves");
    let worst = run
        .rows
        .iter()
        .map(|row| {
            let t = row[0];
            let theta = 0.5 * torque / (ip + m * r * r) * t * t;
            (row[FIRST] - theta)
                .abs()
                .max((row[FIRST + 1] - r * theta).abs() / r)
        })
        .fold(0.0, f64::max);
    println!("rack and pinion: largest difference {worst:.2e}");
    assert!(worst < 1e-7, "{worst}");
}

/// What a GEAR cannot be is refused at its place: a CV marker on a part
/// neither joint holds, a CV whose z axis the joints do not move the
/// contact along, a joint that is not a REVOLUTE, TRANSLATIONAL or
/// CYLINDRICAL one.
#[test]
fn gears_that_cannot_be_are_refused_at_their_place() {
    let model = "gears
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 1, 0, 0
MARKER/3, PART = 1, QP = 0.4, 0, 0, REULER = 0, -90D, 0
MARKER/4, PART = 1, QP = 0.4, 0, 0
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1
MARKER/20, PART = 2
PART/3, MASS = 1, CM = 30, IP = 1, 1, 1, QG = 1, 0, 0
MARKER/30, PART = 3
MARKER/31, PART = 3, QP = -0.6, 0, 0, REULER = 0, -90D, 0
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, REVOLUTE, I = 30, J = 2
JOINT/3, SPHERICAL, I = 30, J = 2
LINE
END
";
    let cases = [
        (
            "GEAR/1, JOINTS = 1, 2, CV = 31",
            "does not hold the CV marker's part",
        ),
        (
            "GEAR/1, JOINTS = 1, 2, CV = 4",
            "does not move the contact point",
        ),
        (
            "GEAR/1, JOINTS = 1, 3, CV = 3",
            "not a REVOLUTE, TRANSLATIONAL or CYLINDRICAL",
        ),
        ("GEAR/1, JOINTS = 1, CV = 3", "JOINTS names two joints"),
        ("GEAR/1, JOINTS = 1, 2, CV = 99", "CV must name a MARKER"),
    ];
    for (line, expected) in cases {
        let text = model.replace("LINE", line);
        let error = run(&text, &settings(1.0, 1, 1e-8)).err().expect("refused");
        assert!(error.contains(expected), "{line}: {error}");
    }
}
