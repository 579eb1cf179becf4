//! COUPLER: joints' displacements tied by their scales, `Σ s q = 0`. Two
//! wheels on revolute joints geared 1 : 2.7 under a torque on the first,
//! and a pinion driving a rack, turn several times as the one freedom
//! left under the reflected inertia says (closed forms written here); the
//! coupling holds to the integration error (it is kept at the level of the
//! velocities).

use super::simulate::{run, settings};

/// The first REQUEST column: after the time and 13 states of each of the
/// two parts.
const FIRST: usize = 27;

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
        let text = format!(
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
REQUEST/1, F1 = AZ(20, 1), F2 = AZ(30, 2)
END
"
        );
        let run = run(&text, &settings(4.0, 40, 1e-9)).expect("the gears turn");
        let reflected = i1 + i2 / (ratio * ratio);
        let worst = run
            .rows
            .iter()
            .map(|row| {
                let t = row[0];
                let first = 0.5 * torque / reflected * t * t;
                let (az1, az2) = (row[FIRST], row[FIRST + 1]);
                (az1 - first).abs().max((az2 + first / ratio).abs()) / first.abs().max(1.0)
            })
            .fold(0.0, f64::max);
        let turns = run.rows.last().unwrap()[FIRST] / std::f64::consts::TAU;
        println!(
            "I {i1} {i2} ratio {ratio}: {turns:.1} turns, largest relative difference {worst:.2e}"
        );
        assert!(turns.abs() > 1.0, "{turns}");
        assert!(worst < 1e-6, "{worst}");
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
        COUPLER/1, JOINTS = 1, 1, SCALES = 1
        COUPLER/1, JOINTS = 1, 1
        COUPLER/1, FUNCTION = USER(1, 2)
    ";
    insta::assert_snapshot!(super::table(cases, check));
}
