//! Reactions during a run: `JOINT`, `MOTION` (and `JPRIM`) read in
//! REQUESTs, checked against closed forms computed here from the run's own
//! states (Newton's and Euler's laws written by hand for each body), and
//! the research note's measured sign check.

use nalgebra::Vector3;

use super::joints::pendulum;
use super::simulate::{run, settings};

const G: f64 = 9.80665;

/// A 1 kg pendulum (centre of mass 2 m from a revolute pivot at ground's
/// origin, Izz = 0.1 kg·m²) released horizontal, swinging in the x-z plane
/// under gravity along −z; the joint's I marker on ground. REQUEST/1's F1
/// ... F8: JOINT(1, 0, c, 0) for c = 1 ... 8.
const PENDULUM: &str = "pendulum
PART/1, GROUND
MARKER/1, PART = 1, REULER = 0, 90D, 0
PART/2, MASS = 1, CM = 20, IP = 0.1, 0.1, 0.1
MARKER/20, PART = 2, QP = 2, 0, 0
MARKER/21, PART = 2, REULER = 0, 90D, 0
JOINT/1, REVOLUTE, I = 1, J = 21
ACCGRAV/KGRAV = -9.80665
REQUEST/1, F1 = JOINT(1,0,1,0), F2 = JOINT(1,0,2,0), F3 = JOINT(1,0,3,0), F4 = JOINT(1,0,4,0)
, F5 = JOINT(1,0,5,0), F6 = JOINT(1,0,6,0), F7 = JOINT(1,0,7,0), F8 = JOINT(1,1,4,0)
END
";

/// The columns after the time: 13 of the part, then the REQUEST's.
const FIRST: usize = 14;

/// The pendulum's centre of mass from the pivot `r`, its angular velocity
/// in ground and its orientation, from a row's state columns.
fn swing(row: &[f64]) -> (Vector3<f64>, Vector3<f64>, nalgebra::UnitQuaternion<f64>) {
    let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        row[4], row[5], row[6], row[7],
    ));
    let r = q * Vector3::new(2.0, 0.0, 0.0);
    (r, Vector3::new(row[11], row[12], row[13]), q)
}

/// The research note's measured value: `JOINT(1,0,4,0) = −0.239187` at t =
/// 0 (the pull on the ground, `−m (g − a)` with `a = g m d² / (Izz + m d²)`),
/// and along the swing the force on the ground is `−m (a − g)` of the
/// centre of mass, `a = α × r + ω × (ω × r)` with `α` from the gravity's
/// moment about the pivot: no torque about the pivot.
#[test]
fn a_pendulum_pulls_its_pivot_as_newtons_law_says_with_adams_sign() {
    let run = run(PENDULUM, &settings(3.0, 30, 1e-10)).expect("the pendulum runs");
    let first = &run.rows[0];
    let measured = -0.239187;
    assert!(
        (first[FIRST + 3] - measured).abs() < 5e-7,
        "{}",
        first[FIRST + 3]
    );
    assert!((first[FIRST + 3] + G * 0.1 / 4.1).abs() < 1e-12);
    let mut worst: f64 = 0.0;
    for row in &run.rows {
        let (r, omega, _) = swing(row);
        let gravity = Vector3::new(0.0, 0.0, -G);
        // About the pivot: (Izz + m d²) α = r × m g.
        let alpha = r.cross(&gravity) / (0.1 + 4.0);
        let a = alpha.cross(&r) + omega.cross(&omega.cross(&r));
        let on_ground = -(a - gravity);
        let columns = &row[FIRST..];
        let scale = 1.0 + on_ground.norm();
        worst = worst
            .max((columns[0] - on_ground.norm()).abs() / scale)
            .max((columns[1] - on_ground.x).abs() / scale)
            .max((columns[2] - on_ground.y).abs() / scale)
            .max((columns[3] - on_ground.z).abs() / scale)
            .max(columns[4].abs() / scale)
            .max(columns[5].abs() / scale)
            .max(columns[6].abs() / scale)
            .max((columns[7] + columns[3]).abs() / scale);
    }
    println!("pendulum reaction: worst relative difference {worst:.2e}");
    assert!(worst < 1e-7, "{worst}");
}

/// A joint that holds its origins together pushes its ground marker at
/// that marker's origin, as Adams applies it: the torque a spherical joint
/// (and a revolute joint about its axis) puts on its ground marker is zero,
/// however far the markers drift apart within the run's tolerance (Adams
/// writes 1e-15 where mbexpr wrote 3e-5, the drift's moment, before).
#[test]
fn a_joint_holding_its_origins_together_puts_no_torque_on_ground() {
    let spherical = PENDULUM
        .replace("REVOLUTE", "SPHERICAL")
        .replace("PART/2, MASS = 1", "PART/2, MASS = 1, WX = 1.5, WZ = 0.5");
    for (model, free) in [
        (spherical.as_str(), [true, true]),
        (PENDULUM, [false, true]),
    ] {
        let run = run(model, &settings(3.0, 30, 1e-5)).expect("the pendulum runs");
        for row in &run.rows {
            // JOINT(1,0,6,0) and (1,0,7,0): the torque's x and y; the
            // revolute's axis is ground's y here (its markers' z turned
            // 90° about x).
            let torque = [row[FIRST + 5], row[FIRST + 6]];
            for (component, free) in torque.iter().zip(&free) {
                if *free {
                    assert!(component.abs() < 1e-13, "{model}: {row:?}");
                }
            }
        }
    }
}

/// The driven crank's mass, arm and moment about its centre of mass.
pub(super) const CRANK: (f64, f64, f64) = (2.5, 0.4, 0.03);

/// The driven crank's angle `θ = 0.3 t + 0.4 sin 2t` at `t` and the torque
/// that turns it so, `(Izz + m d²) θ'' + m g d cos θ`.
pub(super) fn crank_angle_and_torque(t: f64) -> (f64, f64) {
    let (m, d, izz) = CRANK;
    let theta = 0.3 * t + 0.4 * (2.0 * t).sin();
    let acceleration = -1.6 * (2.0 * t).sin();
    (
        theta,
        (izz + m * d * d) * acceleration + m * G * d * theta.cos(),
    )
}

/// The joints tests' compound pendulum as a crank on its revolute joint
/// (gravity along −y) driven by a MOTION `θ = 0.3 t + 0.4 sin 2t`,
/// gravity along −y: the MOTION's reaction torque on the crank about z,
/// `MOTION(1, 0, 8, 0)`, is the inverse dynamics `(Izz + m d²) θ'' + m g d
/// cos θ`, and the joint's torque about z is zero.
#[test]
fn a_driven_cranks_motion_torque_is_its_inverse_dynamics() {
    let (m, d, izz) = CRANK;
    let text = pendulum(m, d, izz).replace(
        "END",
        "MOTION/1, JOINT = 1, ROTATION, FUNCTION = 0.3 * TIME + 0.4 * SIN(2 * TIME)
REQUEST/1, F1 = MOTION(1,0,8,0), F2 = JOINT(1,0,8,0), F3 = MOTION(1,1,8,0), F4 = MOTION(1,0,8,21)
END",
    );
    for method in ["radau", "dop853"] {
        let mut settings = settings(4.0, 40, 1e-9);
        settings.method = if method == "radau" {
            mbexpr::integrate::Method::Radau5
        } else {
            mbexpr::integrate::Method::Dop853
        };
        let run = run(&text, &settings).expect("the crank runs");
        let mut worst: f64 = 0.0;
        for row in &run.rows {
            let (_, torque) = crank_angle_and_torque(row[0]);
            let columns = &row[FIRST..];
            worst = worst
                .max((columns[0] - torque).abs())
                .max(columns[1].abs())
                .max((columns[2] + torque).abs())
                .max((columns[3] - torque).abs());
        }
        println!("{method}: crank torque, largest difference {worst:.2e} N·m");
        assert!(worst < 1e-6, "{method}: {worst}");
    }
}

/// The slider of the joints tests: a body on a TRANSLATIONAL joint along
/// ground z, an action-only spring `−k z` at its I marker, its centre of
/// mass at (0.3, 0.1, 0) from I and gravity (3, −9.80665, 0) across the
/// joint. It moves as `z = z0 cos ωt`, does not turn, so the joint's force
/// on it is `−m g` across the axis and nothing along, and its torque about
/// I balances the moments of the spring and the joint's force about the
/// centre of mass: `T = −(p − c) × (F + F_spring)`.
#[test]
fn a_slider_on_a_translational_joint_feels_the_weight_and_the_moments() {
    let (m, k, z0): (f64, f64, f64) = (2.0, 30.0, 0.2);
    let text = format!(
        "slider
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = {m}, CM = 20, IP = 1, 2, 3, QG = 0, 0, {z0}
MARKER/20, PART = 2, QP = 0.3, 0.1, 0
MARKER/21, PART = 2
JOINT/1, TRANSLATIONAL, I = 21, J = 1
SFORCE/1, TRANSLATIONAL, I = 21, J = 1, ACTIONONLY, FUNCTION = -{k} * DZ(21, 1)
ACCGRAV/IGRAV = 3, JGRAV = -9.80665
REQUEST/1, F2 = JOINT(1,0,2,0), F3 = JOINT(1,0,3,0), F4 = JOINT(1,0,4,0)
, F6 = JOINT(1,0,6,0), F7 = JOINT(1,0,7,0), F8 = JOINT(1,0,8,0)
END
"
    );
    let omega = (k / m).sqrt();
    let run = run(&text, &settings(2.0, 40, 1e-10)).expect("the slider runs");
    let mut worst: f64 = 0.0;
    for row in &run.rows {
        let z = z0 * (omega * row[0]).cos();
        let force = Vector3::new(-3.0 * m, G * m, 0.0);
        let spring = Vector3::new(0.0, 0.0, -k * z);
        let torque = -Vector3::new(-0.3, -0.1, 0.0).cross(&(force + spring));
        let columns = &row[FIRST..];
        for axis in 0..3 {
            worst = worst
                .max((columns[axis] - force[axis]).abs())
                .max((columns[3 + axis] - torque[axis]).abs());
        }
    }
    println!("slider reaction: largest difference {worst:.2e}");
    assert!(worst < 1e-7, "{worst}");
}

/// What cannot be read is an error before the run, at its place: a joint
/// the model does not have, a flag out of range, and a motion reading a
/// reaction.
#[test]
fn reactions_that_cannot_be_had_are_refused_before_the_run() {
    let cases = [
        ("F1 = JOINT(7,0,4,0)", "JOINT/7, which is not defined"),
        ("F1 = JOINT(1,2,4,0)", "jflag must be 0"),
        ("F1 = JOINT(1,0,9,0)", "comp must be 1 to 8"),
        ("F1 = JPRIM(1,0,4,0)", "JPRIM/1, which is not defined"),
        ("F1 = MOTION(1,0,4,0)", "MOTION/1, which is not defined"),
    ];
    for (request, expected) in cases {
        let text = PENDULUM.replace(
            "REQUEST/1, F1 = JOINT(1,0,1,0)",
            &format!("REQUEST/2, {request}\nREQUEST/1, F1 = JOINT(1,0,1,0)"),
        );
        let error = run(&text, &settings(1.0, 1, 1e-8)).err().expect("refused");
        assert!(error.contains(expected), "{request}: {error}");
    }
    let friction = PENDULUM.replace(
        "ACCGRAV",
        "SFORCE/1, ROTATIONAL, I = 21, J = 1, FUNCTION = -0.1 * JOINT(1,0,1,0) * SIGN(1, WY(21, 1))\nACCGRAV",
    );
    // Friction that reads the joint's reaction is solved with it
    // (`tests/loop_values.rs`); a motion that reads one is refused.
    run(&friction, &settings(1.0, 1, 1e-8)).expect("friction reads the reaction");
    let driven = PENDULUM.replace(
        "ACCGRAV",
        "MOTION/1, JOINT = 1, ROTATION, FUNCTION = 0.1 * JOINT(1,0,1,0)\nACCGRAV",
    );
    let error = run(&driven, &settings(1.0, 1, 1e-8))
        .err()
        .expect("refused");
    assert!(
        error.contains("a MOTION or GCON that reads a value"),
        "{error}"
    );
}

/// Adams' cubic STEP from `h0` at `x0` to `h1` at `x1`, written here.
fn step(x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> f64 {
    let s = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    h0 + (h1 - h0) * s * s * (3.0 - 2.0 * s)
}

/// The corpus's spiked model: a crank driven at 30°/s by MOTION/1 (its
/// I marker on ground) with a connecting rod and an INLINE slider, and a
/// 10 lbf·in torque pulse (SFORCE/1) on the crank about ground z in t = 1
/// ... 1.02. `VARIABLE/1 = MOTION(1,0,8,0)` is written with the rows, and
/// since the motion fixes the mechanism's path, the pulse changes nothing
/// but the torque the motion applies: VARIABLE/1 minus its value in a copy
/// without the pulse is the pulse itself, `(STEP(t, 1, 0, 1.01, 1) −
/// STEP(t, 1.01, 0, 1.02, 1)) · 10` (the torque the crank takes from the
/// motion falls by the pulse; the ground's, jflag 0, rises by it).
#[test]
fn the_spiked_models_motion_torque_takes_the_pulse() {
    let Some(path) =
        crate::corpus::corpus_path("models/bthornton191__adamspy__test_analysis_with_spikes.adm")
    else {
        return;
    };
    let text = std::fs::read_to_string(path).expect("the corpus model reads");
    let pulse = ", FUNCTION = (step(time, 1, 0, 1.01, 1) - step(time, 1.01, 0, 1.02, 1))*10";
    assert!(text.contains(pulse));
    let quiet = text.replace(pulse, ", FUNCTION = 0");
    let settings = settings(2.0, 400, 1e-9);
    let spiked = run(&text, &settings).expect("the spiked model runs");
    let unspiked = run(&quiet, &settings).expect("its copy runs");
    let mut worst: f64 = 0.0;
    for (row, quiet_row) in spiked.rows.iter().zip(&unspiked.rows) {
        let t = row[0];
        let expected = (step(t, 1.0, 0.0, 1.01, 1.0) - step(t, 1.01, 0.0, 1.02, 1.0)) * 10.0;
        let variable = row[row.len() - 1];
        worst = worst.max((variable - quiet_row[quiet_row.len() - 1] - expected).abs());
    }
    let peak = spiked.rows[202][spiked.rows[202].len() - 1];
    println!(
        "spikes: VARIABLE/1 at t = 1.01 is {peak}; largest difference from the pulse {worst:.2e} lbf·in"
    );
    assert!(worst < 1e-6, "{worst}");
}

/// REQUESTs of the standard kinds give Adams' columns from the measures:
/// the pendulum's centre-of-mass marker against the pivot (DISPLACEMENT:
/// `r = R (2, 0, 0)`) and against ground along its own axes (VELOCITY:
/// `v = ω × r` turned into the marker's axes), checked against the run's
/// own state columns. The kinds are read from their first letter too, as
/// Adams View writes them (`REQUEST/1, D, I = 2, J = 1`).
#[test]
fn standard_requests_write_adams_columns() {
    let text = PENDULUM.replace(
        "REQUEST/1",
        "REQUEST/2, DISPLACEMENT, I = 20, J = 1\nREQUEST/3, VELOCITY, I = 20, RM = 20\nREQUEST/1",
    );
    let swinging = run(&text, &settings(2.0, 20, 1e-10)).expect("the pendulum runs");
    let abbreviated = text
        .replace("DISPLACEMENT, I", "D, I")
        .replace("VELOCITY, I", "V, I");
    let short = run(&abbreviated, &settings(2.0, 20, 1e-10)).expect("the pendulum runs");
    assert_eq!(short.rows, swinging.rows);
    let mut worst: f64 = 0.0;
    for row in &swinging.rows {
        let (r, omega, q) = swing(row);
        let v = q.inverse() * omega.cross(&r);
        let w = q.inverse() * omega;
        let columns = &row[FIRST..];
        let expected = [
            r.norm(),
            r.x,
            r.y,
            r.z,
            v.norm(),
            v.x,
            v.y,
            v.z,
            w.norm(),
            w.x,
            w.y,
            w.z,
        ];
        let found = [
            columns[0],
            columns[1],
            columns[2],
            columns[3],
            columns[7],
            columns[8],
            columns[9],
            columns[10],
            columns[11],
            columns[12],
            columns[13],
            columns[14],
        ];
        for (found, expected) in found.iter().zip(expected) {
            worst = worst.max((found - expected).abs());
        }
    }
    assert!(worst < 1e-9, "{worst}");
}
