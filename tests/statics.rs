//! Static equilibrium (`SIMULATE/STATICS`, `--statics`): the run starts
//! with its parts at rest where the forces balance, found by Newton's
//! method from the initial conditions; checked against equilibria solved
//! here another way (closed forms, a bisection), and a model with no
//! balance refused with the part that keeps moving.

use mbexpr::simulate::Settings;

use super::simulate::run;

/// The first row of a run of `text` from a static equilibrium, and how
/// many Newton iterations found it; or the error.
fn settled(text: &str) -> Result<(Vec<f64>, usize), String> {
    let settings = Settings {
        end: 1e-3,
        steps: 1,
        rtol: 1e-10,
        atol: 1e-13,
        statics: true,
        ..Settings::default()
    };
    let run = run(text, &settings)?;
    let equilibrium = run.summary.equilibrium.expect("a static equilibrium");
    Ok((run.rows[0].clone(), equilibrium.iterations))
}

/// A part of mass `m` hung from ground by two springs in series with a
/// part of mass `m2` between them (stiffness `k1` above, `k2` below, free
/// lengths 1), under gravity along −y: the springs stretch by the weights
/// they carry, `(m + m2) g / k1` and `m g / k2`.
#[test]
fn two_parts_hung_on_springs_settle_where_the_springs_carry_the_weights() {
    for (m, m2, k1, k2) in [
        (1.0, 1.0, 100.0, 50.0),
        (3.0, 0.5, 1e4, 2e3),
        (0.2, 2.0, 10.0, 40.0),
    ] {
        let text = format!(
            "springs
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = {m2}, CM = 20, IP = 1, 1, 1, QG = 0, -1, 0
MARKER/20, PART = 2
PART/3, MASS = {m}, CM = 30, IP = 1, 1, 1, QG = 0, -2, 0
MARKER/30, PART = 3
SFORCE/1, TRANSLATIONAL, I = 20, J = 1, FUNCTION = -{k1}*(DM(20, 1) - 1)
SFORCE/2, TRANSLATIONAL, I = 30, J = 20, FUNCTION = -{k2}*(DM(30, 20) - 1)
ACCGRAV/JGRAV = -9.81
END
"
        );
        let (row, iterations) = settled(&text).expect("it settles");
        let upper = -1.0 - (m + m2) * 9.81 / k1;
        let lower = upper - 1.0 - m * 9.81 / k2;
        // time, then the parts' 13 states each: y is the second.
        let (y2, y3) = (row[2], row[1 + 13 + 1]);
        println!(
            "{m} {m2} {k1} {k2}: {iterations} iterations, {:.2e} {:.2e}",
            y2 - upper,
            y3 - lower
        );
        assert!(
            (y2 - upper).abs() < 1e-10 && (y3 - lower).abs() < 1e-10,
            "{y2} {y3}"
        );
        // At rest.
        assert!(
            row[8..14]
                .iter()
                .chain(&row[21..27])
                .all(|v| v.abs() < 1e-12)
        );
    }
}

/// A bar (mass `m`, its centre `d` from the pivot) on a revolute joint
/// about ground's z, under gravity along −y, held by a torsion spring
/// `−k·AZ` (no torque with the bar along x): it settles where the spring
/// carries the weight's moment, `k θ = −m g d cos θ`, the root a bisection
/// finds here.
#[test]
fn a_bar_on_a_torsion_spring_settles_where_the_moments_balance() {
    for (m, d, k) in [(1.0, 0.5, 20.0), (2.0, 1.0, 5.0), (0.3, 2.0, 100.0)] {
        let text = format!(
            "bar
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = {m}, CM = 20, IP = 0.1, 0.1, 0.1
MARKER/20, PART = 2, QP = {d}, 0, 0
MARKER/21, PART = 2
JOINT/1, REVOLUTE, I = 21, J = 1
SFORCE/1, ROTATIONAL, I = 21, J = 1, FUNCTION = -{k}*AZ(21, 1)
ACCGRAV/JGRAV = -9.81
REQUEST/1, F1 = AZ(21, 1)
END
"
        );
        let (row, iterations) = settled(&text).expect("it settles");
        let moment = |theta: f64| k * theta + m * 9.81 * d * theta.cos();
        let (mut low, mut high) = (-std::f64::consts::FRAC_PI_2, 0.0);
        for _ in 0..200 {
            let middle = 0.5 * (low + high);
            if moment(middle) > 0.0 {
                high = middle;
            } else {
                low = middle;
            }
        }
        let angle = row[14];
        println!("{m} {d} {k}: {iterations} iterations, angle {angle} against {low}");
        assert!((angle - low).abs() < 1e-9, "{angle} {low}");
    }
}

/// A DIFF settles where its rate vanishes: `y' = −2 (y − 3)` rests at 3.
#[test]
fn a_diff_settles_where_its_rate_vanishes() {
    let (row, _) =
        settled("diff\nDIFF/1, IC = 0, FUNCTION = -2*(DIF(1) - 3)\nEND\n").expect("it settles");
    assert!((row[1] - 3.0).abs() < 1e-12, "{}", row[1]);
}

/// A part that nothing holds against gravity has no equilibrium: the
/// error names it.
#[test]
fn a_falling_part_has_no_static_equilibrium() {
    let error = settled(
        "falling
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1
MARKER/20, PART = 2
ACCGRAV/JGRAV = -9.81
END
",
    )
    .err()
    .unwrap_or_default();
    insta::assert_snapshot!(error.trim_end(), @"4:1: the run stops at t = 0: no static equilibrium found from the initial conditions: Newton's iterations end with PART/2's linear acceleration at 9.810e0 (the forces may have no balance near the start, or a freedom no force holds: start the dynamics from the initial conditions without SIMULATE/STATICS or --statics)");
}
