//! AX, AY, AZ keep their whole turns over a run (SPEC 4), whatever the
//! steps: a part spun fast on a torsion spring, at loose tolerances with
//! both methods, against its exact sine; a free spinning part read by a
//! REQUEST far apart in time; a rotational SPRINGDAMPER as its SFORCE.

use mbexpr::integrate::Method;
use mbexpr::simulate::Settings;

use super::simulate::run;

/// The first REQUEST column: after the time and 13 of the part.
const FIRST: usize = 14;

/// A part (Izz 0.25) spun at `spin` rad/s about ground's z on a torsion
/// spring of stiffness 9 held by `spring` (a statement between markers 20
/// and 1), its angle read by REQUEST/1.
fn spun(spring: &str, spin: f64) -> String {
    format!(
        "spun
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 0.25, WZ = {spin}
MARKER/20, PART = 2
JOINT/1, REVOLUTE, I = 20, J = 1
{spring}
REQUEST/1, F1 = AZ(20, 1)
END
"
    )
}

/// The largest distance of a run's AZ from the torsion pendulum's exact
/// `spin/6 · sin 6t` (natural frequency √(9/0.25) = 6).
fn off(text: &str, spin: f64, method: Method, rtol: f64) -> f64 {
    let settings = Settings {
        method,
        end: 3.0,
        steps: 30,
        rtol,
        atol: rtol * 1e-3,
        ..Settings::default()
    };
    let run = run(text, &settings).expect("it spins");
    run.rows
        .iter()
        .map(|row| (row[FIRST] - spin / 6.0 * (6.0 * row[0]).sin()).abs())
        .fold(0.0, f64::max)
}

#[test]
fn a_part_wound_several_turns_on_a_torsion_spring_keeps_its_turns() {
    let springs = [
        "SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = -9*AZ(20, 1)",
        "SPRINGDAMPER/1, ROTATIONAL, I = 20, J = 1, KT = 9",
    ];
    for spring in springs {
        for spin in [120.0, 300.0] {
            let text = spun(spring, spin);
            for (method, rtol, bound) in [
                (Method::Dop853, 1e-3, 1.0),
                (Method::Dop853, 1e-4, 0.5),
                (Method::Radau5, 1e-3, 1.0),
                (Method::Radau5, 1e-4, 0.5),
                (Method::Dop853, 1e-8, 1e-4),
                (Method::Radau5, 1e-8, 1e-4),
            ] {
                let off = off(&text, spin, method, rtol);
                println!("{spring:.12} spin {spin} {method} rtol {rtol:e}: off by {off:.2e} rad");
                // A lost turn is 6.28 rad off.
                assert!(off < bound, "{spring}, {spin}, {method}, {rtol}: {off}");
            }
        }
    }
}

/// A free part spinning at 50 rad/s about z, read every half second (25
/// rad apart): AZ is 50 t.
#[test]
fn a_request_far_apart_in_time_keeps_a_free_spins_turns() {
    let text = "free spin
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, WZ = 50
MARKER/20, PART = 2
REQUEST/1, F1 = AZ(20, 1)
END
";
    for method in [Method::Dop853, Method::Radau5] {
        let settings = Settings {
            method,
            end: 4.0,
            steps: 8,
            rtol: 1e-6,
            atol: 1e-9,
            ..Settings::default()
        };
        let run = run(text, &settings).expect("it spins");
        let off = run
            .rows
            .iter()
            .map(|row| (row[FIRST] - 50.0 * row[0]).abs())
            .fold(0.0, f64::max);
        println!("{method}: off by {off:.2e}");
        // A lost turn is 6.28 rad; the integration error over 200 rad is
        // about 1e-7 of them.
        assert!(off < 1e-3, "{method}: {off}");
    }
}
