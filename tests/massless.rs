//! Massless parts: a part without MASS moves as its joints take it, its
//! six equations a balance solved with the multipliers. A bob hung from
//! ground by a massless rod (a revolute joint at the pivot, the bob fixed
//! to the rod's end) swings as the same bob on a revolute joint at the
//! pivot; a massless part the joints leave free is refused, named.

use mbexpr::integrate::Method;

use super::simulate::{run, settings};

/// The bob's centre, from the first REQUEST's columns (after the time and
/// 13 states of each part).
fn bob(text: &str, parts: usize) -> Vec<[f64; 3]> {
    let run = run(text, &settings(3.0, 60, 1e-9)).expect("the pendulum swings");
    let first = 1 + 13 * parts;
    run.rows
        .iter()
        .map(|row| [row[0], row[first], row[first + 1]])
        .collect()
}

/// The bob (mass `m`, inertia `i` about its centre) at `(l, 0, 0)`,
/// turning about ground's z axis at the origin, held directly or by a
/// massless rod.
fn pendulum(m: f64, i: f64, l: f64, rod: bool) -> String {
    let held = if rod {
        "PART/2
MARKER/21, PART = 2
MARKER/22, PART = 2, QP = L, 0, 0
JOINT/1, REVOLUTE, I = 21, J = 1
JOINT/2, FIXED, I = 30, J = 22
"
    } else {
        "JOINT/1, REVOLUTE, I = 31, J = 1
"
    };
    format!(
        "pendulum
PART/1, GROUND
MARKER/1, PART = 1
{held}PART/3, MASS = {m}, CM = 30, IP = {i}, {i}, {i}
MARKER/30, PART = 3, QP = L, 0, 0
MARKER/31, PART = 3
ACCGRAV/JGRAV = -9.81
REQUEST/1, F1 = DX(30, 1), F2 = DY(30, 1)
END
"
    )
    .replace("QP = L", &format!("QP = {l}"))
}

#[test]
fn a_bob_on_a_massless_rod_swings_as_the_bob_on_its_pivot() {
    for (m, i, l) in [(2.0, 0.1, 1.0), (0.5, 0.02, 0.3), (10.0, 3.0, 2.5)] {
        let direct = bob(&pendulum(m, i, l, false), 1);
        let on_rod = bob(&pendulum(m, i, l, true), 2);
        let worst = direct
            .iter()
            .zip(&on_rod)
            .map(|(a, b)| (a[1] - b[1]).abs().max((a[2] - b[2]).abs()) / l)
            .fold(0.0, f64::max);
        // It swings through the bottom: the comparison is not at rest.
        let lowest = on_rod.iter().map(|row| row[2]).fold(0.0, f64::min);
        println!("m {m}, I {i}, l {l}: largest difference {worst:.2e}, lowest {lowest:.3}");
        assert!(lowest < -0.9 * l, "{lowest}");
        assert!(worst < 1e-6, "{worst}");
    }
}

/// What a run of a massless part at `(1, 0, 0)` held by `holder` (a
/// statement, or nothing) and pulled by a spring reports.
fn check(holder: &str) -> String {
    let text = format!(
        "massless
PART/1, GROUND
MARKER/1, PART = 1, REULER = 90D, 90D, 0D
PART/2, CM = 20
MARKER/20, PART = 2, QP = 1, 0, 0, REULER = 90D, 90D, 0D
{holder}
SFORCE/1, TRANSLATIONAL, I = 20, J = 1, FUNCTION = -10*(DM(20, 1) - 1)
END
"
    );
    match run(&text, &settings(1.0, 10, 1e-6)) {
        Ok(run) => format!("ran: {} rows", run.rows.len()),
        Err(error) => error.trim_end().to_string(),
    }
}

#[test]
fn a_massless_part_the_joints_leave_free_is_refused() {
    insta::assert_snapshot!(check("!"), @"4:1: PART/2 has no MASS and no joint, primitive or motion holds it: give MASS = a positive number (a massless part moves only as the joints take it)");
    insta::assert_snapshot!(check("JOINT/1, TRANSLATIONAL, I = 20, J = 1"), @"4:1: the run stops at t = 0: the joints: their equations are singular: the joints leave a massless part (PART/2) a freedom no mass follows, or the configuration is singular; give the part MASS or hold it");
}

/// The rod pendulum with a spring pulling the massless rod's end toward a
/// ground point and a damper on the bob: forces on the massless part enter
/// its balance.
const SPRUNG: &str = "sprung rod
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 0.5, -1, 0.2
PART/2
MARKER/21, PART = 2
MARKER/22, PART = 2, QP = 1, 0, 0
JOINT/1, SPHERICAL, I = 21, J = 1
JOINT/2, FIXED, I = 30, J = 22
PART/3, MASS = 2, CM = 30, IP = 0.1, 0.2, 0.3
MARKER/30, PART = 3, QP = 1, 0, 0
SFORCE/1, TRANSLATIONAL, I = 22, J = 2, FUNCTION = -40*(DM(22, 2) - 0.9)
SFORCE/2, TRANSLATIONAL, I = 30, J = 1, FUNCTION = -3*VR(30, 1)
ACCGRAV/JGRAV = -9.81
END
";

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(12))]

    /// The Jacobian through the balance of a massless part (its
    /// accelerations solved with the multipliers) agrees with central
    /// differences.
    #[test]
    fn the_jacobian_through_a_massless_part_agrees_with_finite_differences(
        shifts in proptest::collection::vec(-0.05f64..0.05, 26),
        time in 0.0f64..3.0,
    ) {
        super::simulate::the_jacobian_agrees_with_finite_differences(SPRUNG, &shifts, time)?;
    }
}

/// The sprung rod runs with both methods to the same answer.
#[test]
fn a_sprung_massless_rod_runs_alike_with_both_methods() {
    let mut rows = Vec::new();
    for method in [Method::Radau5, Method::Dop853] {
        let mut chosen = settings(2.0, 20, 1e-10);
        chosen.method = method;
        let run = run(SPRUNG, &chosen).expect("the sprung rod runs");
        rows.push(run.rows.last().unwrap().clone());
    }
    let worst = rows[0]
        .iter()
        .zip(&rows[1])
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    println!("radau against dop853: {worst:.2e}");
    assert!(worst < 1e-6, "{worst}");
}

/// The a2m sample's copy (`examples/simulate/h_ant_tyre_spring.adm`: four
/// massless parts among seven joints, its USER tyre a spring) through the
/// suspension's compression: Radau5 and DOP853 agree on every state.
#[test]
fn the_motorcycle_suspension_with_massless_parts_runs_alike_with_both_methods() {
    let text = std::fs::read_to_string("examples/simulate/h_ant_tyre_spring.adm")
        .expect("the example is there");
    let mut ends = Vec::new();
    for method in [Method::Radau5, Method::Dop853] {
        let mut chosen = settings(0.12, 12, 1e-8);
        chosen.method = method;
        let run = run(&text, &chosen).expect("the suspension runs");
        ends.push(run.rows.last().unwrap().clone());
    }
    // The leg (PART/11, the second part) has moved toward the road.
    let leg_z = 1 + 13 + 2;
    assert!(ends[0][leg_z] > 0.2, "{}", ends[0][leg_z]);
    let worst = ends[0]
        .iter()
        .zip(&ends[1])
        .map(|(a, b)| (a - b).abs() / a.abs().max(1.0))
        .fold(0.0, f64::max);
    println!("radau against dop853: {worst:.2e}");
    assert!(worst < 1e-5, "{worst}");
}
