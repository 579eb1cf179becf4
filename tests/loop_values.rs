//! Forces that read the running solver's values (a joint's reaction, an
//! acceleration, a force element's value): solved with the motion at every
//! state, not lagged a step. Checked against references worked out here:
//! a spinning pendulum whose pin friction reads the joint's reaction (its
//! angular acceleration and the reaction found together by hand, then
//! integrated by RK4 at a fine step), an added mass through `ACCX` whose
//! gain no plain iteration contracts (a closed form), and a force that
//! reads its own value with a gain of 1 (no solution: an error).

use mbexpr::simulate::Settings;

use super::joints::{angle, method, pendulum};
use super::simulate::{run, settings};

const G: f64 = 9.80665;

/// A compound pendulum (`m`, `d`, `izz`) spun at `omega` about its pivot,
/// with a friction torque `c·|R|` against its turning, `R` the force its
/// revolute joint applies: `Jp θ'' = −m g d cos θ − c |R|` with `R = m (a −
/// g)`, `a = d θ'' (−sin θ, cos θ) − d ω² (cos θ, sin θ)`: θ'' is found with
/// `R` by fixed-point iteration (its gain `c m d / Jp` is small).
fn friction_reference(m: f64, d: f64, izz: f64, c: f64, omega: f64, end: f64) -> (f64, f64) {
    let inertia = izz + m * d * d;
    let acceleration = |theta: f64, omega: f64| {
        let mut alpha = 0.0;
        for _ in 0..60 {
            let (s, co) = theta.sin_cos();
            let a = (
                -d * alpha * s - d * omega * omega * co,
                d * alpha * co - d * omega * omega * s,
            );
            let reaction = m * (a.0.hypot(a.1 + G));
            alpha = (-m * G * d * co - c * reaction) / inertia;
        }
        alpha
    };
    let (theta, w) = rk4(acceleration, (0.0, omega), end, 20_000);
    assert!(w > 0.0, "the reference keeps turning one way");
    (theta, w)
}

/// `θ'' = acceleration(θ, θ')` from `start` (θ, θ') to `end` by RK4 in
/// `steps` equal steps: the references' integration.
pub(super) fn rk4(
    acceleration: impl Fn(f64, f64) -> f64,
    start: (f64, f64),
    end: f64,
    steps: u32,
) -> (f64, f64) {
    let h = end / f64::from(steps);
    let (mut theta, mut w) = start;
    for _ in 0..steps {
        let k1 = (w, acceleration(theta, w));
        let k2 = (
            w + 0.5 * h * k1.1,
            acceleration(theta + 0.5 * h * k1.0, w + 0.5 * h * k1.1),
        );
        let k3 = (
            w + 0.5 * h * k2.1,
            acceleration(theta + 0.5 * h * k2.0, w + 0.5 * h * k2.1),
        );
        let k4 = (w + h * k3.1, acceleration(theta + h * k3.0, w + h * k3.1));
        theta += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        w += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
    }
    (theta, w)
}

/// Pin friction that reads the joint's reaction: the run's angle and
/// angular velocity at the end against the reference, with both methods;
/// the friction's reaction column is `c·|R|` of the same state.
#[test]
fn pin_friction_reading_the_joints_reaction_is_solved_with_the_motion() {
    let (m, d, izz, c, omega, end) = (2.0, 0.5, 0.03, 0.01, 12.0, 1.0);
    let text = pendulum(m, d, izz)
        .replace(&format!("IP = {izz}, {izz}, {izz}"), &format!("IP = {izz}, {izz}, {izz}, WZ = {omega}"))
        .replace(
            "END",
            &format!(
                "SFORCE/2, ROTATIONAL, I = 21, J = 1, FUNCTION = -{c} * JOINT(1,0,1,0)\nREQUEST/1, F2 = JOINT(1,0,1,0), F3 = SFORCE(2,0,8,0)\nEND"
            ),
        );
    let (theta, w) = friction_reference(m, d, izz, c, omega, end);
    let without = friction_reference(m, d, izz, 0.0, omega, end);
    for name in ["dop853", "radau"] {
        let settings = Settings {
            method: method(name),
            ..settings(end, 20, 1e-10)
        };
        let run = run(&text, &settings).unwrap_or_else(|error| panic!("{name}: {error}"));
        let mut turned = 0.0;
        for row in &run.rows {
            turned = angle(row, 4, turned);
            // The torque column is the friction of the reaction column.
            assert!(
                (row[15] + c * row[14]).abs() < 1e-9 * row[14],
                "{name}: {row:?}"
            );
        }
        let last = run.rows.last().expect("rows");
        println!(
            "{name}: angle {turned:.12} against {theta:.12}, ω {:.12} against {w:.12} (without friction {:.6})",
            last[13], without.0
        );
        assert!((turned - theta).abs() < 1e-8, "{name}: {turned} {theta}");
        assert!((last[13] - w).abs() < 1e-8, "{name}: {} {w}", last[13]);
        // The friction matters: far more than the error.
        assert!((without.0 - theta).abs() > 1e-2);
    }
}

/// An added mass through the part's own acceleration, `FX = 5 − 6·ACCX`
/// on a free part of mass 2: `2a = 5 − 6a`, `a = 5/8`. The gain 3 makes the
/// plain iteration `a ← (5 − 6a)/2` diverge; Newton's iterations settle it,
/// and the part moves as `x = 5t²/16`.
#[test]
fn an_added_mass_through_the_parts_acceleration_moves_as_the_closed_form() {
    let text = "added mass
PART/1, GROUND
MARKER/1, PART = 1
MARKER/4, PART = 1, FLOATING
PART/2, MASS = 2, CM = 3, IP = 0.4, 0.4, 0.4
MARKER/3, PART = 2
VFORCE/1, I = 3, JFLOAT = 4, RM = 1, FX = 5 - 6 * ACCX(3), FY = 0, FZ = 0
REQUEST/1, F2 = ACCX(3), F3 = VFORCE(1,0,2,0)
END
";
    for name in ["dop853", "radau"] {
        let settings = Settings {
            method: method(name),
            ..settings(2.0, 10, 1e-10)
        };
        let run = run(text, &settings).unwrap_or_else(|error| panic!("{name}: {error}"));
        for row in &run.rows {
            let t = row[0];
            assert!(
                (row[1] - 5.0 * t * t / 16.0).abs() < 1e-10,
                "{name}: {row:?}"
            );
            assert!((row[14] - 0.625).abs() < 1e-12, "{name}: {row:?}");
            assert!((row[15] - 1.25).abs() < 1e-12, "{name}: {row:?}");
        }
    }
}

/// A force that reads its own value with a gain of 1 has no value: the
/// run stops at its start, naming the force, rather than returning one.
#[test]
fn a_force_equal_to_itself_plus_one_stops_with_the_reason() {
    let text = "no solution
PART/1, GROUND
MARKER/1, PART = 1
MARKER/4, PART = 1, FLOATING
PART/2, MASS = 2, CM = 3, IP = 0.4, 0.4, 0.4
MARKER/3, PART = 2
VFORCE/1, I = 3, JFLOAT = 4, RM = 1, FX = 1 + VFORCE(1,0,2,0), FY = 0, FZ = 0
END
";
    let error = run(text, &settings(1.0, 1, 1e-8)).err().expect("no value");
    assert!(error.contains("do not settle"), "{error}");
    // At the VFORCE's FX, line 7.
    assert!(error.starts_with("7:"), "{error}");
}
