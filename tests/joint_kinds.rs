//! The joints that couple two motions or hold two shafts: UNIVERSAL and
//! HOOKE (the cross of a Cardan joint: the output shaft's pin and speed
//! from the geometry of the cross, `tan θ2 = tan θ1 / cos β`), CONVEL (a
//! constant-velocity joint: the output turns at the input's rate),
//! RACKPIN and SCREW (one degree of freedom shared by a turn and a
//! translation: the closed form of a constant torque and force on it).

use std::f64::consts::{PI, TAU};

use nalgebra::{Unit, UnitQuaternion, Vector3};

use super::joints::angle;
use super::simulate::{run, settings};

/// `REULER = ψ, θ, φ` (Adams' body 3-1-3 angles) of a marker whose z axis
/// is `z` and x axis `x` in its part's axes: the rotation's third row is
/// `(sin θ sin φ, sin θ cos φ, cos θ)`, its third column `(sin ψ sin θ,
/// −cos ψ sin θ, cos θ)`.
fn reuler(z: Vector3<f64>, x: Vector3<f64>) -> String {
    let y = z.cross(&x);
    let theta = z.z.clamp(-1.0, 1.0).acos();
    let psi = z.x.atan2(-z.y);
    let phi = x.z.atan2(y.z);
    format!("REULER = {psi:.17}, {theta:.17}, {phi:.17}")
}

/// A body's rotation from its quaternion columns starting at `column`.
fn rotation(row: &[f64], column: usize) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        row[column],
        row[column + 1],
        row[column + 2],
        row[column + 3],
    ))
}

/// Two shafts through the ground's origin on revolute joints: the input
/// (PART/2) along x, turned at 1 rad/s by a MOTION; the output (PART/3)
/// along `(cos β, sin β, 0)`; `cross` the joint between them, its I
/// marker 31 on the output and J marker 21 on the input, placed by the
/// REULERs given.
fn shafts(beta: f64, cross: &str, i: &str, j: &str) -> String {
    let x = Vector3::x();
    let output = Vector3::new(beta.cos(), beta.sin(), 0.0);
    let across = Vector3::z();
    format!(
        "shafts
PART/1, GROUND
MARKER/1, PART = 1, {ground_in}
MARKER/2, PART = 1, {ground_out}
PART/2, MASS = 1, CM = 20, IP = 0.5, 0.3, 0.3
MARKER/20, PART = 2, {ground_in}
MARKER/21, PART = 2, {j}
PART/3, MASS = 2, CM = 30, IP = 0.2, 0.7, 0.4
MARKER/30, PART = 3, {ground_out}
MARKER/31, PART = 3, {i}
JOINT/1, REVOLUTE, I = 20, J = 1
MOTION/1, JOINT = 1, ROTATION, FUNCTION = TIME
JOINT/2, REVOLUTE, I = 30, J = 2
JOINT/3, {cross}, I = 31, J = 21
ACCGRAV/JGRAV = -9.80665
END
",
        ground_in = reuler(x, Vector3::y()),
        ground_out = reuler(output, across),
    )
}

/// UNIVERSAL (the z axes the arms of the cross) and HOOKE (I's x axis and
/// J's y axis the arms): the input's pin `p1 = (0, cos t, sin t)` starts
/// in the plane of the shafts, so the output's pin is `p2 ∥ a2 × p1`
/// (perpendicular to its shaft `a2` and to `p1`) and the output turns at
/// `cos β / (1 − sin²β cos²t)` times the input's rate.
#[test]
fn a_cardan_joint_turns_its_output_by_the_cosine_law() {
    let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
    for beta in [0.3, 0.9] {
        let a2 = Vector3::new(f64::cos(beta), f64::sin(beta), 0.0);
        let cases = [
            // kind, I (its arm), J (its arm), the output's arm in its axes
            ("UNIVERSAL", reuler(z, a2.cross(&z)), reuler(y, z), z),
            ("HOOKE", reuler(a2, z), reuler(-x, z), z),
        ];
        for (kind, i, j, arm) in cases {
            let text = shafts(beta, kind, &i, &j);
            let run =
                run(&text, &settings(4.0, 40, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
            let (mut pin_worst, mut rate_worst): (f64, f64) = (0.0, 0.0);
            for row in &run.rows {
                let t = row[0];
                let p1 = Vector3::new(0.0, t.cos(), t.sin());
                let expected = a2.cross(&p1).normalize();
                let pin = rotation(row, 17) * arm;
                pin_worst = pin_worst.max((pin - expected).norm());
                let omega = rotation(row, 17) * Vector3::new(row[24], row[25], row[26]);
                let rate = beta.cos() / (1.0 - (beta.sin() * t.cos()).powi(2));
                rate_worst = rate_worst.max((omega.dot(&a2) - rate).abs());
            }
            println!(
                "{kind} β = {beta}: pin off by {pin_worst:.1e}, rate by {rate_worst:.1e}; residuals {:?}",
                run.summary.residuals
            );
            assert!(pin_worst < 1e-7 && rate_worst < 1e-7, "{kind} β = {beta}");
        }
    }
}

/// CONVEL: the z axes down the shafts away from the centre (J's along −x
/// on the input, I's along the output), the x axes parallel at the start;
/// the output turns about its shaft exactly as the input does about its.
#[test]
fn a_constant_velocity_joint_turns_its_output_at_the_inputs_rate() {
    let (x, z) = (Vector3::x(), Vector3::z());
    for beta in [0.4, 1.0] {
        let a2 = Vector3::new(f64::cos(beta), f64::sin(beta), 0.0);
        let text = shafts(beta, "CONVEL", &reuler(a2, z), &reuler(-x, z));
        let run = run(&text, &settings(4.0, 40, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
        let mut worst: f64 = 0.0;
        for row in &run.rows {
            let turned = rotation(row, 17) * UnitQuaternion::identity();
            let expected = UnitQuaternion::from_axis_angle(&Unit::new_normalize(a2), row[0]);
            worst = worst.max(turned.angle_to(&expected));
            let omega = rotation(row, 17) * Vector3::new(row[24], row[25], row[26]);
            worst = worst.max((omega - a2).norm());
        }
        println!(
            "CONVEL β = {beta}: output off by {worst:.1e}; residuals {:?}",
            run.summary.residuals
        );
        assert!(worst < 1e-7, "β = {beta}: {worst}");
    }
}

/// How far the first body's turn about z in `rows` is from `½ a t²` and
/// column `column` from `ratio` times that turn (the largest), and the
/// last turn.
fn off_uniform_turn(rows: &[Vec<f64>], a: f64, column: usize, ratio: f64) -> (f64, f64) {
    let (mut worst, mut turn) = (0.0_f64, 0.0);
    for row in rows {
        let exact = 0.5 * a * row[0] * row[0];
        turn = angle(row, 4, turn);
        worst = worst
            .max((turn - exact).abs())
            .max((row[column] - ratio * exact).abs());
    }
    (worst, turn)
}

/// A pinion (PART/2, about ground z, moment `ip`) turned by a torque `t`
/// drives a rack (PART/3, mass `m`, sliding along x on the side `z × x =
/// y` of the pinion, PD = 2 r): one degree of freedom, `(ip + m r²) α'' =
/// t`, the rack at `x = −r α` (it rolls on the pinion's pitch circle).
#[test]
fn a_rack_and_pinion_rolls_under_a_torque_as_the_closed_form() {
    // ip m r t
    for case in ["0.3 2 0.5 1.5", "1 0.1 2 -4"] {
        let values: Vec<f64> = case
            .split_whitespace()
            .map(|field| field.parse().expect("a number"))
            .collect();
        let (ip, m, r, t) = (values[0], values[1], values[2], values[3]);
        let along_x = reuler(Vector3::x(), Vector3::y());
        let text = format!(
            "rack and pinion
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 0, {r}, 0, {along_x}
PART/2, MASS = 1, CM = 20, IP = 0.1, 0.1, {ip}
MARKER/20, PART = 2
PART/3, MASS = {m}, CM = 30, IP = 1, 1, 1, QG = 0, {r}, 0
MARKER/30, PART = 3
MARKER/31, PART = 3, {along_x}
JOINT/1, REVOLUTE, I = 20, J = 1
JOINT/2, TRANSLATIONAL, I = 31, J = 2
JOINT/3, RACKPIN, I = 20, J = 31, PD = {pd}
SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = {t}
ACCGRAV/JGRAV = -9.80665
END
",
            pd = 2.0 * r
        );
        let end = 3.0;
        let run = run(&text, &settings(end, 30, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
        let acceleration = t / (ip + m * r * r);
        let (worst, turn) = off_uniform_turn(&run.rows, acceleration, 14, -r);
        println!(
            "RACKPIN {case}: off by {worst:.1e} over {:.1} turns",
            turn / TAU
        );
        assert!(worst < 1e-7 && turn.abs() > PI, "{case}: {worst}");
    }
}

/// A nut (PART/2) on a screw along ground z (a CYLINDRICAL joint and a
/// SCREW of pitch `p`), a torque `t` about z and a force `f` along it:
/// one degree of freedom, `(izz + m k²) θ'' = t + f k` (`k = p / 2π`),
/// `z = k θ`, over several turns.
#[test]
fn a_screw_advances_its_pitch_per_turn_under_a_torque_and_a_force() {
    // izz m p t f
    for case in ["0.2 3 0.1 0.5 -2", "0.05 1 -0.3 -0.2 1", "1 0.5 2 0.3 0"] {
        let values: Vec<f64> = case
            .split_whitespace()
            .map(|field| field.parse().expect("a number"))
            .collect();
        let (izz, m, p, t, f) = (values[0], values[1], values[2], values[3], values[4]);
        let text = format!(
            "screw
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = {m}, CM = 20, IP = 0.4, 0.4, {izz}
MARKER/20, PART = 2
JOINT/1, CYLINDRICAL, I = 20, J = 1
JOINT/2, SCREW, I = 20, J = 1, PITCH = {p}
SFORCE/1, ROTATIONAL, I = 20, J = 1, FUNCTION = {t}
SFORCE/2, TRANSLATIONAL, I = 20, J = 1, ACTIONONLY, FUNCTION = {f}
ACCGRAV/IGRAV = -9.80665
END
"
        );
        let k = p / TAU;
        let acceleration = (t + f * k) / (izz + m * k * k);
        let end = (2.0 * 6.0 * TAU / acceleration.abs()).sqrt();
        let run = run(&text, &settings(end, 40, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
        let (worst, turn) = off_uniform_turn(&run.rows, acceleration, 3, k);
        println!(
            "SCREW {case}: off by {worst:.1e} over {:.1} turns; residuals {:?}",
            turn / TAU,
            run.summary.residuals
        );
        assert!(worst < 1e-7 && turn.abs() > 5.0 * TAU, "{case}: {worst}");
    }
}

/// RACKPIN and SCREW need their lengths: without them, or with a pitch
/// diameter not above zero, the joint is refused at the argument.
#[test]
fn a_rack_and_pinion_and_a_screw_need_their_lengths() {
    let joint = |line: &str| {
        format!(
            "joint\nPART/1, GROUND\nMARKER/1, PART = 1\nPART/2, MASS = 1, CM = 3, IP = 1, 1, 1\nMARKER/3, PART = 2\n{line}\n"
        )
    };
    for line in [
        "JOINT/1, SCREW, I = 3, J = 1",
        "JOINT/1, SCREW, I = 3, J = 1, PITCH = 0",
        "JOINT/1, RACKPIN, I = 3, J = 1, PD = -1",
    ] {
        let Err(error) = run(&joint(line), &settings(1.0, 2, 1e-6)) else {
            panic!("{line} runs");
        };
        assert!(error.contains("this joint needs"), "{line}: {error}");
        assert!(error.starts_with("6:"), "{line}: {error}");
    }
}

/// `examples/simulate/f_crank_slider.adm`: a crank turned by a MOTION at
/// `ω = 2π`, a rod and a slider; the slider's place (REQUEST/1's F1, the
/// last column) and velocity are the mechanism's closed form, `x = r cos
/// θ + √(l² − r² sin² θ)` and its derivative, whatever the masses.
#[test]
fn a_crank_slider_driven_by_a_motion_follows_its_closed_form() {
    let text = include_str!("../examples/simulate/f_crank_slider.adm");
    let (r, l, omega) = (0.2_f64, 0.7_f64, TAU);
    for case in ["dop853 1e-8", "radau 1e-8", "auto 1e-10"] {
        let fields: Vec<&str> = case.split_whitespace().collect();
        let rtol: f64 = fields[1].parse().expect("a tolerance");
        let mut settings = settings(2.0, 200, rtol);
        settings.method = super::joints::method(fields[0]);
        let run = run(text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let (mut place, mut speed): (f64, f64) = (0.0, 0.0);
        for row in &run.rows {
            let theta = omega * row[0];
            let root = (l * l - (r * theta.sin()).powi(2)).sqrt();
            let x = r * theta.cos() + root;
            let v = -r * omega * theta.sin() - r * r * omega * theta.sin() * theta.cos() / root;
            place = place.max((row[row.len() - 1] - x).abs());
            speed = speed.max((row[1 + 13 * 2 + 7] - v).abs());
        }
        println!(
            "{case}: place off by {place:.1e}, velocity by {speed:.1e}; residuals {:?}, {} projections",
            run.summary.residuals, run.summary.projections
        );
        assert!(place < 100.0 * rtol && speed < 1000.0 * rtol, "{case}");
    }
}

/// A PART's VX, VY, VZ are the velocity of its VM marker's origin along
/// ground's axes and WX, WY, WZ its angular velocity about its WM marker's
/// axes (the CM marker's when they are left out): a free part (no gravity)
/// given them at a marker 1 m out along its x and about a marker turned a
/// quarter turn about z starts with the centre's velocity `v - ω × r` and
/// `ω` in ground turned by the marker, against the run's own first row.
/// Naming the CM changes nothing; a marker on another part is refused at
/// the argument.
#[test]
fn velocities_given_at_another_marker_are_carried_to_the_centre() {
    let part = |extra: &str| {
        format!(
            "part\nPART/1, GROUND\nMARKER/1, PART = 1\nPART/2, MASS = 1, CM = 3, IP = 1, 1, 1, VX = 1, VY = 0.5, WX = 2, WZ = 3{extra}\nMARKER/3, PART = 2\nMARKER/4, PART = 2, QP = 1, 0, 0, REULER = 90D, 0, 0\n"
        )
    };
    let first_row = |extra: &str| {
        let run = run(&part(extra), &settings(1.0, 2, 1e-6))
            .unwrap_or_else(|error| panic!("{extra}: {error}"));
        run.rows[0].clone()
    };
    // The columns after the time: x y z, q0 q1 q2 q3, vx vy vz, wx wy wz.
    let close = |row: &[f64], velocity: [f64; 3], omega: [f64; 3]| {
        for k in 0..3 {
            assert!((row[8 + k] - velocity[k]).abs() < 1e-12, "{row:?}");
            assert!((row[11 + k] - omega[k]).abs() < 1e-12, "{row:?}");
        }
    };
    close(&first_row(""), [1.0, 0.5, 0.0], [2.0, 0.0, 3.0]);
    assert_eq!(first_row(", VM = 3, WM = 3"), first_row(""));
    // At marker 4, (1, 0, 0) from the centre: v_centre = v - ω × r, with
    // ω = (2, 0, 3): ω × r = (0, 3, 0).
    close(&first_row(", VM = 4"), [1.0, -2.5, 0.0], [2.0, 0.0, 3.0]);
    // About marker 4's axes, a quarter turn about z: (2, 0, 3) is (0, 2, 3)
    // in ground, and ω × r = (0, 3, -2) at marker 4.
    close(&first_row(", WM = 4"), [1.0, 0.5, 0.0], [0.0, 2.0, 3.0]);
    close(
        &first_row(", VM = 4, WM = 4"),
        [1.0, -2.5, 2.0],
        [0.0, 2.0, 3.0],
    );
    for keyword in ["VM", "WM"] {
        let text = part(&format!(", {keyword} = 1"));
        let line = text.lines().nth(3).expect("the PART line");
        let column = line.find(keyword).expect("the keyword") + 1;
        let Err(error) = run(&text, &settings(1.0, 2, 1e-6)) else {
            panic!("{keyword} on ground runs");
        };
        assert!(
            error.starts_with(&format!(
                "4:{column}: PART/2: {keyword} must name a MARKER on the part"
            )),
            "{keyword}: {error}"
        );
    }
}

/// A part driven in all six directions by MOTIONs between its marker and
/// a ground marker (turned, so the directions are J's): its origin is at
/// X, Y, Z along J's axes and its axes are J's turned by `Rx(b1) Ry(b2)
/// Rz(b3)` (the body 1-2-3 angles), at every output time.
#[test]
fn motions_between_markers_place_a_part_by_their_displacements() {
    let j = reuler(
        Vector3::new(0.0, 1.0, 1.0).normalize(),
        Vector3::new(1.0, 0.0, 0.0),
    );
    let text = format!(
        "driven
PART/1, GROUND
MARKER/1, PART = 1, QP = 0.5, -1, 2, {j}
PART/2, MASS = 2, CM = 20, IP = 0.3, 0.5, 0.7, QG = 0.5, -1, 2, {j}
MARKER/20, PART = 2
MOTION/1, I = 20, J = 1, X, FUNCTION = 0.3 * SIN(2 * TIME)
MOTION/2, I = 20, J = 1, Y, FUNCTION = TIME * TIME
MOTION/3, I = 20, J = 1, Z, FUNCTION = -0.5 * TIME
MOTION/4, I = 20, J = 1, B1, FUNCTION = 0.4 * SIN(TIME)
MOTION/5, I = 20, J = 1, B2, FUNCTION = 0.7 * SIN(3 * TIME)
MOTION/6, I = 20, J = 1, B3, FUNCTION = 2.5 * TIME
ACCGRAV/KGRAV = -9.80665
END
"
    );
    let run = run(&text, &settings(3.0, 30, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
    let ground = UnitQuaternion::from_basis_unchecked(&{
        let z = Vector3::new(0.0, 1.0, 1.0).normalize();
        let x = Vector3::x();
        [x, z.cross(&x), z]
    });
    let mut worst: f64 = 0.0;
    for row in &run.rows {
        let t = row[0];
        let offset = Vector3::new(0.3 * (2.0 * t).sin(), t * t, -0.5 * t);
        let place = Vector3::new(0.5, -1.0, 2.0) + ground * offset;
        let turn = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.4 * t.sin())
            * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 0.7 * (3.0 * t).sin())
            * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 2.5 * t);
        let axes = ground * turn;
        worst = worst
            .max((Vector3::new(row[1], row[2], row[3]) - place).norm())
            .max(rotation(row, 4).angle_to(&axes));
    }
    println!(
        "marker motions: off by {worst:.1e}; residuals {:?}",
        run.summary.residuals
    );
    assert!(worst < 1e-8, "{worst}");
}
