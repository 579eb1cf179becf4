//! Initial conditions: joints' (`IC` of a REVOLUTE or TRANSLATIONAL joint,
//! `ICTRAN` and `ICROT` of a CYLINDRICAL one) and parts' `EXACT`. The
//! initial-conditions analysis puts a joint at its displacement and
//! velocity, then the run leaves it free; it keeps the coordinates EXACT
//! lists where they were drawn. Checked against the same models drawn at
//! that state (PART places and velocities), closed forms, and a
//! crank-slider whose slider must follow the crank's initial angle.

use super::simulate::{model_of, run, settings};

/// A pendulum (mass 2, its centre 0.8 below the pivot when drawn) on a
/// revolute joint about ground's z, under gravity along −y; `joint` the
/// joint's extra arguments, `part` the pendulum's.
fn pendulum(joint: &str, part: &str) -> String {
    format!(
        "pendulum
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2, CM = 20, IP = 0.1, 0.1, 0.1{part}
MARKER/20, PART = 2, QP = 0, -0.8, 0
MARKER/21, PART = 2
JOINT/1, REVOLUTE, I = 21, J = 1{joint}
ACCGRAV/JGRAV = -9.81
REQUEST/1, F1 = AZ(21, 1), F2 = WZ(21, 1)
END
"
    )
}

/// The first REQUEST column: after the time and one part's 13 states.
const FIRST: usize = 14;

/// A pendulum drawn hanging with `IC = ω0, θ0` (the velocity first, as
/// Adams reads it) swings as the same pendulum
/// drawn at θ0 with its angular velocity ω0 given on the PART.
#[test]
fn a_revolute_ic_starts_the_pendulum_where_its_part_would() {
    for (angle, rate) in [(0.3, 1.5), (-1.2, 0.0), (2.5, -4.0)] {
        let with_ic = run(
            &pendulum(&format!(", IC = {rate}, {angle}"), ""),
            &settings(2.0, 20, 1e-10),
        )
        .expect("the pendulum with its IC runs");
        // Drawn turned, its centre moving on its circle.
        let (sin, cos) = f64::sin_cos(angle);
        let drawn = pendulum(
            "",
            &format!(
                ", REULER = {angle}, 0, 0, WZ = {rate}, VX = {}, VY = {}",
                0.8 * rate * cos,
                0.8 * rate * sin
            ),
        );
        let drawn_run = run(&drawn, &settings(2.0, 20, 1e-10)).expect("the drawn pendulum");
        let first = &with_ic.rows[0];
        assert!((first[FIRST] - angle).abs() < 1e-12, "{first:?}");
        assert!((first[FIRST + 1] - rate).abs() < 1e-12, "{first:?}");
        let worst = with_ic
            .rows
            .iter()
            .zip(&drawn_run.rows)
            .map(|(a, b)| {
                (a[FIRST] - b[FIRST])
                    .abs()
                    .max((a[FIRST + 1] - b[FIRST + 1]).abs())
            })
            .fold(0.0, f64::max);
        println!("IC {angle}, {rate}: largest difference {worst:.2e}");
        assert!(worst < 1e-7, "{worst}");
    }
}

/// With only a displacement (`IC = , θ0`), the velocity is the least
/// change from the PART's (here none): the pendulum starts at rest at θ0.
/// With only a velocity (`IC = ω0`), the pendulum starts where it is drawn,
/// turning at ω0.
#[test]
fn an_ic_without_a_velocity_leaves_the_velocity_to_the_parts() {
    let spun = run(&pendulum(", IC = 0.7", ""), &settings(0.5, 5, 1e-9)).expect("it runs");
    let first = &spun.rows[0];
    assert!(first[FIRST].abs() < 1e-12, "{first:?}");
    assert!((first[FIRST + 1] - 0.7).abs() < 1e-12, "{first:?}");
    let run = run(&pendulum(", IC = , 0.7", ""), &settings(0.5, 5, 1e-9)).expect("it runs");
    let first = &run.rows[0];
    assert!((first[FIRST] - 0.7).abs() < 1e-12, "{first:?}");
    assert!(first[FIRST + 1].abs() < 1e-12, "{first:?}");
    // It swings back toward the bottom.
    assert!(run.rows.last().unwrap()[FIRST] < 0.7);
}

/// A PART's given velocities are kept where the joint leaves them free,
/// the others follow (Adams' "inexact 0" for those left out): the
/// pendulum (centre 0.8 below the pivot) given `WZ = 5` turns at 5, its
/// centre moving at `ω × r = (4, 0)`; given `VX = 2` its centre moves at 2
/// and it turns at 2.5; given `VX = 2, VY = 1`, which the joint cannot
/// both keep (the centre moves along x), VX is kept and VY goes (the
/// least squares of the given); with an IC's velocity too, the IC's wins.
#[test]
fn a_parts_given_velocities_are_kept_where_the_joint_leaves_them_free() {
    let cases = [
        ("", ", WZ = 5", 5.0),
        ("", ", VX = 2", 2.5),
        ("", ", VX = 2, VY = 1", 2.5),
        ("", ", VX = 2, WZ = 2.5", 2.5),
        (", IC = -1, 0", ", WZ = 5", -1.0),
    ];
    for (joint, part, rate) in cases {
        let run = run(&pendulum(joint, part), &settings(0.1, 1, 1e-10))
            .unwrap_or_else(|error| panic!("{part}: {error}"));
        let first = &run.rows[0];
        assert!((first[FIRST + 1] - rate).abs() < 1e-12, "{part}: {first:?}");
        // The part's origin, at the pivot, stays (its centre moves at ω × r).
        assert!((first[13] - rate).abs() < 1e-12, "{part}: {first:?}");
        assert!(
            first[8].abs() < 1e-12 && first[9].abs() < 1e-12,
            "{part}: {first:?}"
        );
    }
}

/// A slider (mass 2) on a translational joint along ground's x under a
/// spring of stiffness 50 from its drawn place: `IC = v0, x0` gives `x =
/// x0 cos ωt + v0/ω sin ωt`.
#[test]
fn a_translational_ic_starts_the_oscillator() {
    let text = "slider
PART/1, GROUND
MARKER/1, PART = 1, REULER = 90D, 90D, 0D
PART/2, MASS = 2, CM = 20, IP = 1, 1, 1
MARKER/20, PART = 2, REULER = 90D, 90D, 0D
JOINT/1, TRANSLATIONAL, I = 20, J = 1, IC = -1.0, 0.2
SFORCE/1, TRANSLATIONAL, ACTIONONLY, I = 20, J = 1, FUNCTION = -50*DZ(20, 1, 1)
REQUEST/1, F1 = DZ(20, 1, 1), F2 = DX(20, 1)
END
";
    let run = run(text, &settings(2.0, 40, 1e-10)).expect("the slider runs");
    let omega = 5.0_f64;
    let worst = run
        .rows
        .iter()
        .map(|row| {
            let t = row[0];
            let exact = 0.2 * (omega * t).cos() - 1.0 / omega * (omega * t).sin();
            (row[FIRST] - exact)
                .abs()
                .max((row[FIRST + 1] - exact).abs())
        })
        .fold(0.0, f64::max);
    println!("largest error {worst:.2e}");
    assert!(worst < 1e-8, "{worst}");
}

/// A free body on a cylindrical joint along ground's z: `ICTRAN = v, d`
/// and `ICROT = w, r` give `d + v t` and `r + w t`.
#[test]
fn a_cylindrical_joint_takes_ictran_and_icrot() {
    let text = "cylinder
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 3, CM = 20, IP = 1, 1, 0.5
MARKER/20, PART = 2
JOINT/1, CYLINDRICAL, I = 20, J = 1, ICTRAN = 0.25, 0.5, ICROT = -3, 0.4
REQUEST/1, F1 = DZ(20, 1), F2 = AZ(20, 1)
END
";
    let run = run(text, &settings(1.0, 10, 1e-10)).expect("it runs");
    let worst = run
        .rows
        .iter()
        .map(|row| {
            let t = row[0];
            (row[FIRST] - (0.5 + 0.25 * t))
                .abs()
                .max((row[FIRST + 1] - (0.4 - 3.0 * t)).abs())
        })
        .fold(0.0, f64::max);
    assert!(worst < 1e-9, "{worst}");
}

/// A crank (0.2) and rod (0.7) drive a slider along ground's x; the
/// crank's `IC = ω0, θ0` sets the whole loop: the slider at `r cos θ0 +
/// √(l² − r² sin² θ0)` and moving at that expression's rate.
#[test]
fn a_crank_ic_places_the_whole_loop() {
    for (angle, rate) in [(0.6, 2.0), (2.0_f64, -1.0)] {
        let text = format!(
            "crank-slider
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, REULER = 90D, 90D, 0D
PART/2, MASS = 1, CM = 20, IP = 0.01, 0.01, 0.01
MARKER/20, PART = 2, QP = 0.1, 0, 0
MARKER/21, PART = 2
MARKER/22, PART = 2, QP = 0.2, 0, 0
PART/3, MASS = 1, CM = 30, IP = 0.05, 0.05, 0.05
MARKER/30, PART = 3, QP = 0.55, 0, 0
MARKER/31, PART = 3, QP = 0.2, 0, 0
MARKER/32, PART = 3, QP = 0.9, 0, 0
PART/4, MASS = 1, CM = 40, IP = 0.01, 0.01, 0.01
MARKER/40, PART = 4, QP = 0.9, 0, 0
MARKER/41, PART = 4, QP = 0.9, 0, 0, REULER = 90D, 90D, 0D
JOINT/1, REVOLUTE, I = 21, J = 1, IC = {rate}, {angle}
JOINT/2, REVOLUTE, I = 31, J = 22
JOINT/3, REVOLUTE, I = 40, J = 32
JOINT/4, TRANSLATIONAL, I = 41, J = 2
REQUEST/1, F1 = DX(40), F2 = VX(40), F3 = AZ(21, 1)
END
"
        );
        let run = run(&text, &settings(0.01, 1, 1e-10)).expect("the crank-slider runs");
        let first = &run.rows[0];
        let (r, l) = (0.2, 0.7);
        let (sin, cos) = angle.sin_cos();
        let root = (l * l - r * r * sin * sin).sqrt();
        let x = r * cos + root;
        let v = -r * sin * rate - r * r * sin * cos * rate / root;
        println!(
            "θ0 {angle}: x {} ({x}), v {} ({v}), θ {}",
            first[40], first[41], first[42]
        );
        assert!((first[42] - angle).abs() < 1e-12);
        assert!((first[40] - x).abs() < 1e-10, "{} {x}", first[40]);
        assert!((first[41] - v).abs() < 1e-9, "{} {v}", first[41]);
    }
}

/// What is refused or left aside, at its place.
#[test]
fn misplaced_ics_are_refused_at_their_place() {
    let spherical = pendulum("", "").replace("REVOLUTE", "SPHERICAL, IC = 1, 2");
    let error = model_of(&spherical).expect_err("an IC on a spherical joint");
    assert!(
        error.contains("IC is not an argument of this joint"),
        "{error}"
    );
    let three = pendulum(", IC = 1, 2, 3", "");
    let error = model_of(&three).expect_err("three numbers");
    assert!(error.contains("one or two numbers"), "{error}");
    let driven =
        pendulum(", IC = 1, 2", "").replace("END", "MOTION/1, JOINT = 1, FUNCTION = TIME\nEND");
    let model = model_of(&driven).expect("a motion on the joint");
    assert!(model.joint_initials.is_empty());
    assert!(
        model
            .notes
            .iter()
            .any(|(note, _)| note.contains("IC is left aside: MOTION/1")),
        "{:?}",
        model.notes
    );
}

/// Two links on revolute joints about ground's z, the first drawn turned
/// by 0.5, the second drawn (-0.05, -0.03) off the first's tip; `a` and `b`
/// are the parts' extra arguments.
fn two_links(a: &str, b: &str) -> String {
    let (sin, cos) = f64::sin_cos(0.5);
    let (x, y) = (cos - 0.05, sin - 0.03);
    format!(
        "two links
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 10, IP = 0.1, 0.1, 0.1, REULER = 0.5, 0, 0{a}
MARKER/10, PART = 2, QP = 0.5, 0, 0
MARKER/11, PART = 2
MARKER/12, PART = 2, QP = 1, 0, 0
PART/3, MASS = 1, CM = 20, IP = 0.1, 0.1, 0.1, QG = {x}, {y}, 0{b}
MARKER/20, PART = 3, QP = 0.5, 0, 0
MARKER/21, PART = 3
JOINT/1, REVOLUTE, I = 11, J = 1
JOINT/2, REVOLUTE, I = 21, J = 12
REQUEST/1, F1 = DX(21, 12), F2 = DY(21, 12), F3 = DX(20), F4 = DY(20)
END
"
    )
}

/// The state at time 0 of `text` (assembled), after the time: each part's
/// centre, quaternion, velocity, angular velocity.
fn assembled(text: &str) -> Vec<f64> {
    let run = run(text, &settings(0.01, 1, 1e-8)).expect("the links assemble");
    let first = run.rows[0].clone();
    // The joint holds in every case.
    assert!(
        first[27].abs() < 1e-10 && first[28].abs() < 1e-10,
        "{first:?}"
    );
    first
}

/// EXACT keeps the coordinates it lists where they were drawn; the
/// others move to assemble the joints.
#[test]
fn exact_keeps_the_coordinates_it_lists() {
    let free = assembled(&two_links("", ""));
    // Without EXACT both links move (the least change weighs both): the
    // first turns about its pivot.
    let drawn_turn = 0.25_f64.sin();
    assert!((free[7] - drawn_turn).abs() > 1e-3, "{free:?}");
    for kept in ["X:Y:Z:PSI:THETA:PHI", "PSI", "PHI", "psi:theta", "Y"] {
        let state = assembled(&two_links(&format!(", EXACT = {kept}"), ""));
        // The first link is on its pivot: keeping its centre's y (or its
        // turn) keeps all of it (its origin, the pivot, and its quaternion).
        println!("EXACT = {kept} on the first link: {:?}", &state[1..8]);
        let drawn = [0.0, 0.0, 0.0, 0.25_f64.cos(), 0.0, 0.0, drawn_turn];
        for (k, drawn) in drawn.iter().enumerate() {
            assert!((state[1 + k] - drawn).abs() < 1e-12, "{kept}: {state:?}");
        }
    }
    let state = assembled(&two_links("", ", EXACT = X:Y"));
    // Its centre stays (REQUEST columns 3 and 4); the first link turned to
    // meet it.
    println!(
        "EXACT = X:Y on the second link: centre {:?}",
        &state[29..31]
    );
    let (sin, cos) = f64::sin_cos(0.5);
    let centre = (cos + 0.45, sin - 0.03);
    assert!((state[29] - centre.0).abs() < 1e-12 && (state[30] - centre.1).abs() < 1e-12);
    assert!((state[7] - drawn_turn).abs() > 1e-3, "{state:?}");
}

/// A part drawn turned out of ground's plane, its spherical joint apart,
/// keeps the one 3-1-3 angle EXACT names.
#[test]
fn exact_keeps_one_angle_of_a_tilted_part() {
    let text = |exact: &str| {
        format!(
            "tilted
PART/1, GROUND
MARKER/1, PART = 1, QP = 0, 0, 0.05
PART/2, MASS = 1, CM = 10, IP = 0.1, 0.2, 0.3, REULER = 0.3, 0.5, 0.7{exact}
MARKER/10, PART = 2
MARKER/11, PART = 2, QP = 0.3, 0, 0
JOINT/1, SPHERICAL, I = 11, J = 1
REQUEST/1, F1 = PSI(10), F2 = THETA(10), F3 = PHI(10), F4 = DM(11, 1)
END
"
        )
    };
    for (exact, kept) in [("PSI", 0), ("THETA", 1), ("PHI", 2)] {
        let run = run(
            &text(&format!(", EXACT = {exact}")),
            &settings(0.01, 1, 1e-8),
        )
        .expect("it assembles");
        let first = &run.rows[0];
        let angles = [first[FIRST], first[FIRST + 1], first[FIRST + 2]];
        println!("EXACT = {exact}: {angles:?}");
        assert!(
            (angles[kept] - [0.3, 0.5, 0.7][kept]).abs() < 1e-12,
            "{angles:?}"
        );
        assert!(first[FIRST + 3] < 1e-12, "{first:?}");
    }
}

/// EXACT that names no coordinate, or one it does not know, is refused at
/// its place.
#[test]
fn exact_names_coordinates() {
    let error = model_of(&two_links(", EXACT = X:W", "")).expect_err("W is no coordinate");
    assert!(error.contains("W is none of them"), "{error}");
}

/// Parts drawn far from where their joints hold them assemble to the
/// joints, as Adams' assembly does (each Newton step turning a part by
/// ALIMIT = 30° at most): a part on a REVOLUTE, TRANSLATIONAL,
/// CYLINDRICAL, FIXED or PLANAR joint to ground, its I marker turned from
/// the J marker by up to 85° about a random axis and moved up to 0.5 off
/// it, its centre of mass up to 2 from the marker. After the assembly the
/// joint's equations hold (I's place along J's x and y, or the whole of
/// it, and its z axis along J's, not against it: AX and AY are 0, not π).
/// A part turned by 56° about a marker 150 away (a real Adams View file)
/// stopped 0.5 off before.
#[test]
fn parts_drawn_far_off_their_joints_assemble() {
    use super::joints_random::{DrawShapes, euler_of};
    use super::simulate_variants::Draw;
    use nalgebra::{Rotation3, Unit, Vector3};
    // The joints, and which of DX, DY, DZ (along J's axes), AX, AY, AZ each
    // holds at zero.
    let kinds: [(&str, [bool; 6]); 5] = [
        ("REVOLUTE", [true, true, true, true, true, false]),
        ("TRANSLATIONAL", [true, true, false, true, true, true]),
        ("CYLINDRICAL", [true, true, false, true, true, false]),
        ("FIXED", [true; 6]),
        ("PLANAR", [false, false, true, true, true, false]),
    ];
    let mut draw = Draw(31);
    for case in 0..40 {
        let (kind, held) = kinds[case % kinds.len()];
        let j_euler = draw.euler();
        let j_axes = Rotation3::from_axis_angle(&Vector3::z_axis(), j_euler[0])
            * Rotation3::from_axis_angle(&Vector3::x_axis(), j_euler[1])
            * Rotation3::from_axis_angle(&Vector3::z_axis(), j_euler[2]);
        let axis = Unit::new_normalize(draw.vector(1.0));
        let turn = Rotation3::from_axis_angle(&axis, draw.uniform(0.0, 85_f64.to_radians()));
        let i_axes = turn * j_axes;
        let j_place = draw.vector(1.0);
        let i_place = j_place + draw.vector(0.5);
        let centre = i_place + draw.vector(2.0);
        let [a, b, c] = j_euler;
        let [d, e, f] = euler_of(i_axes.matrix());
        let text = format!(
            "a part drawn off its {kind} joint
PART/1, GROUND
MARKER/1, PART = 1, QP = {}, {}, {}, REULER = {a}, {b}, {c}
PART/2, MASS = 2, CM = 3, IP = 0.3, 0.5, 0.7
MARKER/2, PART = 2, QP = {}, {}, {}, REULER = {d}, {e}, {f}
MARKER/3, PART = 2, QP = {}, {}, {}
JOINT/1, {kind}, I = 2, J = 1
REQUEST/1, F1 = DX(2, 1, 1), F2 = DY(2, 1, 1), F3 = DZ(2, 1, 1), F4 = AX(2, 1), F5 = AY(2, 1), F6 = AZ(2, 1)
END
",
            j_place.x, j_place.y, j_place.z, i_place.x, i_place.y, i_place.z, centre.x, centre.y, centre.z
        );
        let run = run(&text, &settings(0.01, 1, 1e-8))
            .unwrap_or_else(|errors| panic!("case {case}: {errors}\n{text}"));
        let first = &run.rows[0];
        for (k, held) in held.iter().enumerate() {
            let value: f64 = first[14 + k];
            assert!(
                !held || value.abs() < 1e-8,
                "case {case}: column {} is {value} after the assembly\n{text}",
                k + 1
            );
        }
    }
}
