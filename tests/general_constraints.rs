//! General constraints (`GCON`): a point mass held at a distance by
//! `DM(i, j) - L` swings with the simple pendulum's elliptic-integral
//! period; three GCONs written as a spherical joint's equations move a
//! heavy top as the SPHERICAL joint does, with the same reaction; a GCON
//! of time drives a slider as the MOTION of the same displacement does;
//! what a GCON may not read is refused at its place.

use std::f64::consts::PI;

use mbexpr::integrate::Method;
use mbexpr::simulate::Settings;

use super::joints::elliptic_k;
use super::simulate::{run, settings};

const G: f64 = 9.80665;

/// A point mass (its inertia about its centre plays no part: the GCON's
/// pull goes through the centre) held `L = 2` from ground's origin by
/// `DM(20, 1) - 2`, released level: a simple pendulum of period `4 K(sin
/// π/4) / ω0`, `ω0² = g / L`. At half the period its centre is level on
/// the other side, at the period back where it started; each for both
/// methods, within a small factor of the tolerance.
#[test]
fn a_distance_gcon_swings_with_the_simple_pendulums_period() {
    let text = "distance
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1.5, CM = 20, IP = 0.2, 0.3, 0.4
MARKER/20, PART = 2, QP = 2, 0, 0
GCON/1, I = 1, FUNCTION = DM(20, 1) - 2
ACCGRAV/JGRAV = -9.80665
REQUEST/1, F2 = DX(20), F3 = DY(20)
END
";
    let period = 4.0 * elliptic_k((PI / 4.0).sin()) / (G / 2.0).sqrt();
    for (method, rtol) in [(Method::Dop853, 1e-9), (Method::Radau5, 1e-8)] {
        let mut settings = settings(period, 2, rtol);
        settings.method = method;
        let swung = run(text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let at = |row: usize| {
            let columns = &swung.rows[row];
            (columns[columns.len() - 2], columns[columns.len() - 1])
        };
        let (half, whole) = (at(1), at(2));
        let error = [
            (half.0 + 2.0).abs(),
            half.1.abs(),
            (whole.0 - 2.0).abs(),
            whole.1.abs(),
        ]
        .into_iter()
        .fold(0.0, f64::max);
        println!(
            "{method:?} rtol {rtol:e}: off the period's places by {error:.2e}; residuals {:?}",
            swung.summary.residuals
        );
        assert!(error < 100.0 * rtol, "{method:?}: {error}");
    }
}

/// A heavy top on a SPHERICAL joint, and the same top held by three GCONs
/// that are the joint's equations (`DX DY DZ` of its tip from the pivot):
/// the same motion to 1e-9 and the same reaction at the pivot (the
/// joint's `JOINT(1, 0, c, 0)` against the GCONs' net force `FX(1, 21)`
/// ... on the ground marker).
#[test]
fn gcons_written_as_a_spherical_joint_move_a_top_as_the_joint_does() {
    let top = |holder: &str| {
        format!(
            "top
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2, CM = 20, IP = 0.3, 0.3, 0.1, REULER = 0.3, 0.5, 0, WZ = 12, WX = 0.4
MARKER/20, PART = 2, QP = 0, 0, 0.8
MARKER/21, PART = 2
{holder}
ACCGRAV/KGRAV = -9.80665
REQUEST/1, F2 = FX(1, 21), F3 = FY(1, 21), F4 = FZ(1, 21)
END
"
        )
    };
    let settings = settings(2.0, 40, 1e-10);
    let joint = run(&top("JOINT/1, SPHERICAL, I = 1, J = 21"), &settings)
        .unwrap_or_else(|error| panic!("{error}"));
    let gcons = run(
        &top(
            "GCON/1, I = 1, FUNCTION = DX(21, 1)\nGCON/2, I = 1, FUNCTION = DY(21, 1)\nGCON/3, I = 1, FUNCTION = DZ(21, 1)",
        ),
        &settings,
    )
    .unwrap_or_else(|error| panic!("{error}"));
    let (mut states, mut forces): (f64, f64) = (0.0, 0.0);
    for (a, b) in joint.rows.iter().zip(&gcons.rows) {
        let split = a.len() - 3;
        for (x, y) in a[..split].iter().zip(&b[..split]) {
            states = states.max((x - y).abs());
        }
        for (x, y) in a[split..].iter().zip(&b[split..]) {
            forces = forces.max((x - y).abs());
        }
    }
    let scale = joint.rows[0][joint.rows[0].len() - 1].abs();
    println!("top: states differ by {states:.2e}, the pivot's force by {forces:.2e} of {scale:.2}");
    assert!(states < 1e-8, "{states}");
    assert!(forces < 1e-7 * scale.max(1.0), "{forces}");
}

/// A slider on a TRANSLATIONAL joint along ground x under gravity along
/// x, its place `0.3 + 0.1 sin 2t` set by a GCON of time, and by the
/// MOTION between markers of the same displacement: the same motion, and
/// the GCON's and the motion's reactions on the slider (the net force at
/// its marker from ground less the joint's; the motion's `MOTION(1, 0, 4,
/// 1)` along its J marker's z) the force Newton's law asks, `m (x'' - g)`.
#[test]
fn a_gcon_of_time_drives_as_the_motion_of_the_same_displacement() {
    let slider = |driver: &str, force: &str| {
        format!(
            "slider
PART/1, GROUND
MARKER/1, PART = 1, REULER = 90D, 90D, 0
PART/2, MASS = 3, CM = 20, IP = 1, 1, 1
MARKER/20, PART = 2, QP = 0.3, 0, 0
MARKER/21, PART = 2, QP = 0.3, 0, 0, REULER = 90D, 90D, 0
JOINT/1, TRANSLATIONAL, I = 21, J = 1
{driver}
ACCGRAV/IGRAV = -9.80665
REQUEST/1, F2 = DX(21, 1){force}
END
"
        )
    };
    let settings = settings(3.0, 30, 1e-10);
    let motion = run(
        &slider(
            "MOTION/1, I = 21, J = 1, Z, FUNCTION = 0.3 + 0.1 * SIN(2 * TIME)",
            ", F3 = FX(21, 1) - JOINT(1, 0, 2, 0), F4 = MOTION(1, 0, 4, 1)",
        ),
        &settings,
    )
    .unwrap_or_else(|error| panic!("{error}"));
    let gcon = run(
        &slider(
            "GCON/1, I = 21, FUNCTION = DX(21, 1) - 0.3 - 0.1 * SIN(2 * TIME)",
            ", F3 = FX(21, 1) - JOINT(1, 0, 2, 0)",
        ),
        &settings,
    )
    .unwrap_or_else(|error| panic!("{error}"));
    let mut worst: f64 = 0.0;
    for (a, b) in motion.rows.iter().zip(&gcon.rows) {
        let t = a[0];
        let place = 0.3 + 0.1 * (2.0 * t).sin();
        let (driven, held) = (a[a.len() - 3], b[b.len() - 2]);
        worst = worst.max((driven - place).abs()).max((held - place).abs());
        // The force that drives it: m (x'' - g) along x, with x'' = -0.4 sin 2t;
        // the motion's along its J marker's z axis (ground's x).
        let needed = 3.0 * (-0.4 * (2.0 * t).sin() + G);
        for force in [b[b.len() - 1], a[a.len() - 2], a[a.len() - 1]] {
            worst = worst.max((force - needed).abs() / needed.abs().max(1.0));
        }
    }
    println!("slider: off the driven place and force by {worst:.2e}");
    assert!(worst < 1e-7, "{worst}");
}

/// What a GCON may not read, refused at its place (one with no I runs, its
/// reaction reported at ground's origin, as Adams View writes it); a
/// GCON whose FUNCTION cannot be evaluated where the parts start, named;
/// a GCON on velocities (held at their level) that runs, and one whose
/// velocities do not move it (`0 * WZ`: no row of `G`), named.
#[test]
fn what_a_gcon_cannot_hold_is_refused_at_its_place() {
    let model = |gcon: &str| {
        format!(
            "refused
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1
MARKER/20, PART = 2, QP = 1, 0, 0
{gcon}
END
"
        )
    };
    let cases = "
        GCON/1, I = 1, FUNCTION = VX(20)
        GCON/1, I = 1, FUNCTION = DM(20) - 1 + 0 * WZ(20)
        GCON/1, FUNCTION = DM(20) - 1
        GCON/1, I = 1, FUNCTION = DM(20) - 1 + DIF(3)
        GCON/1, I = 1, FUNCTION = DM(20) - 1 + ACCX(20)
        GCON/1, I = 1
        GCON/1, I = 1, FUNCTION = SQRT(DX(20) - 2.5) - 0.1
    ";
    let report = super::table(cases, |case| {
        match run(&model(&case.replace(" | ", "\n")), &settings(1.0, 2, 1e-6)) {
            Ok(_) => "runs".to_string(),
            Err(error) => error.trim().to_string(),
        }
    });
    insta::assert_snapshot!(report);
}

/// A part on a distance GCON and a second one on a GCON of time that reads
/// both parts' places and turns, under a spring.
const TWO_GCONS: &str = "two gcons
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1.5, CM = 20, IP = 0.2, 0.3, 0.4, WZ = 0.5, VY = 0.3
MARKER/20, PART = 2, QP = 2, 0, 0
MARKER/21, PART = 2, QP = 2.5, 0.2, 0
PART/3, MASS = 0.7, CM = 30, IP = 0.1, 0.1, 0.1, QG = 0, 0, 1
MARKER/30, PART = 3, QP = 3, 0, 0
GCON/1, I = 1, FUNCTION = DM(20, 1) - 2
GCON/2, I = 21, FUNCTION = DX(30, 21, 21) - 0.5 - 0.1 * SIN(TIME) + 0.2 * AZ(30, 21)
SFORCE/1, TRANSLATIONAL, I = 30, J = 1, FUNCTION = -5 * (DM(30, 1) - 3)
ACCGRAV/JGRAV = -9.80665
END
";

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(8))]

    /// The Jacobian of parts held by GCONs (their rows carried through the
    /// bodies' motion by differences of the plain row) agrees with central
    /// differences of the rates.
    #[test]
    fn the_jacobian_with_gcons_agrees_with_finite_differences(
        shifts in proptest::collection::vec(-0.02f64..0.02, 26),
        time in 0.0f64..3.0,
    ) {
        super::simulate::the_jacobian_agrees_with_finite_differences(TWO_GCONS, &shifts, time)?;
    }
}

/// A knife edge: a part turning at `ω` about z whose centre may not slide
/// sideways, `VY(20, 1, 20) = 0` (its velocity along its own y axis), a
/// GCON on velocities. Nothing else acts, so the centre runs round a circle
/// of radius `v₀/ω` at its start speed: `x = v₀/ω sin ωt`,
/// `y = v₀/ω (1 − cos ωt)`, with both methods.
const KNIFE_EDGE: &str = "knife edge
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, VX = 2, WZ = 0.5
MARKER/20, PART = 2
GCON/1, I = 20, FUNCTION = VY(20, 1, 20)
ACCGRAV/JGRAV = 0
END
";

#[test]
fn a_knife_edge_gcon_on_velocities_runs_round_its_circle() {
    let (speed, turn) = (2.0, 0.5);
    for method in [Method::Dop853, Method::Radau5] {
        let settings = Settings {
            method,
            ..settings(6.0, 6, 1e-9)
        };
        let run = run(KNIFE_EDGE, &settings).expect("it runs");
        let mut worst: f64 = 0.0;
        for row in &run.rows {
            let t = row[0];
            let x = speed / turn * (turn * t).sin();
            let y = speed / turn * (1.0 - (turn * t).cos());
            worst = worst.max((row[1] - x).abs()).max((row[2] - y).abs());
        }
        println!("{method:?}: off the circle by {worst:.2e}");
        assert!(worst < 1e-7, "{method:?}: {worst}");
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(16))]
    #[test]
    fn the_jacobian_of_a_gcon_on_velocities_agrees_with_finite_differences(
        shifts in proptest::collection::vec(-0.3..0.3_f64, 13),
        time in 0.0..2.0_f64,
    ) {
        super::simulate::the_jacobian_agrees_with_finite_differences(KNIFE_EDGE, &shifts, time)?;
    }
}
