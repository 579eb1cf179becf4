//! Point-to-curve constraints (`PTCV` on a `CURVE` of a `MATRIX`'s
//! points): a bead on a parabolic wire, fixed and turning, moves as the
//! GCON of the parabola's equation with an INPLANE primitive does, with
//! the same reaction; a bead on a closed spline keeps its energy and its
//! curve; a block on a straight curve slides as the closed form says;
//! what cannot be read, and a point run off an open curve, are refused at
//! their place.

use mbexpr::integrate::Method;
use mbexpr::simulate::Curve;
use nalgebra::Vector3;

use super::simulate::{run, settings};

const G: f64 = 9.81;

/// A bead (mass 0.5, its centre at marker 20) on the parabola `y = x²` of
/// the x-y plane of marker 31 on part 3, which turns about ground's
/// vertical y axis at `spin` rad/s (a REVOLUTE joint and a MOTION). The
/// parabola is the quadratic B-spline of control points `(−2, 4), (0,
/// −4), (2, 4)` (a Bézier curve: exactly `y = x²` for `|x| ≤ 2`), held by
/// `holder`: the PTCV, or the GCON of its equation and an INPLANE
/// primitive. REQUEST/1 gives the bead's place and the force on it.
fn wire(spin: f64, holder: &str, force: [&str; 3]) -> String {
    format!(
        "bead on a parabolic wire
PART/1, GROUND
MARKER/12, PART = 1, REULER = 0, -90D, 0
PART/3, MASS = 1, CM = 32, IP = 1, 1, 1
MARKER/30, PART = 3, REULER = 0, -90D, 0
MARKER/31, PART = 3
MARKER/32, PART = 3, QP = 0, 1, 0
MARKER/33, PART = 3, FLOATING
JOINT/1, REVOLUTE, I = 30, J = 12
MOTION/1, JOINT = 1, ROTATION, FUNCTION = {spin}*TIME
PART/2, MASS = 0.5, CM = 20, IP = 0.01, 0.02, 0.03
MARKER/20, PART = 2, QP = 1, 1, 0
MATRIX/1, FULL = RORDER, ROWS = 3, COLUMNS = 3
, VALUES = -2, 4, 0, 0, -4, 0, 2, 4, 0
CURVE/1, OPEN, MATRIX = 1, ORDER = 3
{holder}
ACCGRAV/JGRAV = -9.81
REQUEST/1, F2 = DX(20), F3 = DY(20), F4 = DZ(20), F6 = {}, F7 = {}, F8 = {}
END
",
        force[0], force[1], force[2]
    )
}

/// The bead on the parabola, fixed and turning at 2 rad/s (where the
/// bias of the PTCV's equations carries the Coriolis terms of the turning
/// curve), by the PTCV and by the GCON of `y = x²` in the turning axes
/// with an INPLANE primitive: with both methods, the same places and the
/// same force on the bead (the PTCV's reaction against the net force of
/// the GCON and the primitive), within a small factor of the tolerance.
#[test]
fn a_bead_on_a_parabolic_curve_moves_as_the_gcon_of_its_equation() {
    let curve = "PTCV/1, I = 20, JFLOAT = 33, RM = 31, CURVE = 1";
    let reaction = ["PTCV(1, 0, 2, 0)", "PTCV(1, 0, 3, 0)", "PTCV(1, 0, 4, 0)"];
    let gcon = "GCON/1, I = 20, FUNCTION = DY(20, 31, 31) - DX(20, 31, 31)**2
JPRIM/2, INPLANE, I = 20, J = 31";
    let net = ["FX(20)", "FY(20)", "FZ(20)"];
    for spin in [0.0, 2.0] {
        for (method, rtol) in [(Method::Dop853, 1e-10), (Method::Radau5, 1e-9)] {
            let mut settings = settings(3.0, 12, rtol);
            settings.method = method;
            let ran =
                |text: String| run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
            let on_curve = ran(wire(spin, curve, reaction));
            let by_gcon = ran(wire(spin, gcon, net));
            let mut worst = [0.0f64; 2];
            for (a, b) in on_curve.rows.iter().zip(&by_gcon.rows) {
                let n = a.len();
                for k in n - 6..n {
                    let which = usize::from(k >= n - 3);
                    worst[which] = worst[which].max((a[k] - b[k]).abs());
                }
            }
            println!(
                "spin {spin}, {method:?} rtol {rtol:e}: places {:.1e}, forces {:.1e}",
                worst[0], worst[1]
            );
            assert!(worst[0] < 1e3 * rtol, "places off by {}", worst[0]);
            assert!(worst[1] < 1e4 * rtol, "forces off by {}", worst[1]);
            // The bead has moved (from x = 1, y = 1, z = 0) and stays on
            // the parabola.
            let last = on_curve.rows.last().unwrap();
            let n = last.len();
            assert!((last[n - 6] - 1.0).abs() > 0.05);
        }
    }
}

/// A bead (mass 2, its centre at marker 20 placed at `start`, its initial
/// velocity `velocity`, `VX = -3`) held by a PTCV on a closed cubic
/// through `points` in ground's axes, under gravity; REQUEST/1 gives its
/// place and velocity.
fn bead_on_a_loop(points: &[[f64; 3]], start: [f64; 3], velocity: &str) -> String {
    let values: Vec<String> = points
        .iter()
        .map(|p| format!("{}, {}, {}", p[0], p[1], p[2]))
        .collect();
    format!(
        "bead on a loop
PART/1, GROUND
MARKER/10, PART = 1
MARKER/11, PART = 1, FLOATING
PART/2, MASS = 2, CM = 20, IP = 0.1, 0.1, 0.1, {velocity}
MARKER/20, PART = 2, QP = {}, {}, {}
MATRIX/1, FULL = RORDER, ROWS = {}, COLUMNS = 3, VALUES = {}
CURVE/1, CLOSED, CURVE_POINTS, MATRIX = 1
PTCV/1, I = 20, JFLOAT = 11, RM = 10, CURVE = 1
ACCGRAV/JGRAV = -9.81
REQUEST/1, F2 = DX(20), F3 = DY(20), F4 = DZ(20), F6 = VX(20), F7 = VY(20), F8 = VZ(20)
END
",
        start[0],
        start[1],
        start[2],
        points.len(),
        values.join(", ")
    )
}

/// The largest difference of two rows, entry by entry.
fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

/// A bead on a closed cubic spline through 16 points of an ellipse
/// (semi-axes 2 and 1) standing in ground's x-y plane, under gravity,
/// started at the top at 3 m/s: no force but gravity and the curve's does
/// work, so its energy keeps to the tolerance; it stays on the curve (its
/// distance from the curve, found by the same `Curve` the library builds,
/// to the tolerance); and both methods agree.
#[test]
fn a_bead_on_a_closed_spline_keeps_its_energy_and_its_curve() {
    let points: Vec<[f64; 3]> = (0..16)
        .map(|k| {
            let angle = f64::from(k) * std::f64::consts::TAU / 16.0;
            [2.0 * angle.cos(), angle.sin(), 0.0]
        })
        .collect();
    let text = bead_on_a_loop(&points, [0.0, 1.0, 0.0], "VX = -3");
    let curve = Curve::new(
        1,
        &points.iter().map(|p| Vector3::from(*p)).collect::<Vec<_>>(),
        4,
        true,
        true,
    )
    .unwrap();
    let mut ends = Vec::new();
    for (method, rtol) in [(Method::Dop853, 1e-10), (Method::Radau5, 1e-9)] {
        let mut settings = settings(4.0, 40, rtol);
        settings.method = method;
        let looped = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let energy = |row: &[f64]| {
            let n = row.len();
            let speed2 = row[n - 3].powi(2) + row[n - 2].powi(2) + row[n - 1].powi(2);
            0.5 * 2.0 * speed2 + 2.0 * G * row[n - 5]
        };
        let start = energy(&looped.rows[0]);
        let mut drift = 0.0f64;
        let mut off = 0.0f64;
        for row in &looped.rows {
            drift = drift.max((energy(row) - start).abs() / start);
            let n = row.len();
            let place = Vector3::new(row[n - 6], row[n - 5], row[n - 4]);
            let alpha = curve.nearest(&place).unwrap();
            off = off.max((curve.at(&alpha).place - place).norm());
        }
        println!("{method:?} rtol {rtol:e}: energy drift {drift:.1e}, off the curve {off:.1e}");
        assert!(drift < 1e3 * rtol, "{method:?}: energy drift {drift}");
        assert!(off < 1e3 * rtol, "{method:?}: off the curve by {off}");
        // It goes round: its x takes both signs.
        assert!(looped.rows.iter().any(|row| row[row.len() - 6] > 1.0));
        assert!(looped.rows.iter().any(|row| row[row.len() - 6] < -1.0));
        ends.push(looped.rows.last().unwrap().clone());
    }
    let apart = largest_difference(&ends[0], &ends[1]);
    assert!(apart < 1e-6, "the methods end {apart} apart");
}

/// A block 8 up a straight two-point curve (ORDER = 2) that slopes at
/// `theta` (its parameter rising up the ramp), the PTCV with `extra`,
/// its REQUEST DX, DY, DZ and the PTCV's force along x.
fn block_on_a_ramp(theta: f64, extra: &str) -> String {
    let (c, s) = (theta.cos(), theta.sin());
    format!(
        "block on a ramp
PART/1, GROUND
MARKER/10, PART = 1
MARKER/11, PART = 1, FLOATING
PART/2, MASS = 3, CM = 20, IP = 0.1, 0.2, 0.3
MARKER/20, PART = 2, QP = {}, {}, 0
MATRIX/1, FULL = CORDER, ROWS = 2, COLUMNS = 3, VALUES = {}, {}, {}, {}, 0, 0
CURVE/1, MATRIX = 1, ORDER = 2
PTCV/1, I = 20, JFLOAT = 11, RM = 10, CURVE = 1{extra}
ACCGRAV/JGRAV = -9.81
REQUEST/1, F2 = DX(20), F3 = DY(20), F4 = DZ(20), F6 = PTCV(1, 0, 1, 0)
END
",
        8.0 * c,
        8.0 * s,
        -10.0 * c,
        10.0 * c,
        -10.0 * s,
        10.0 * s,
    )
}

/// The rows of a block started 8 up a ramp sloping at 0.4, with `VEL =
/// speed` when given (at rest without), with DOP853 and with Radau5, each
/// checked to slide as `s = 8 + speed t − g sin θ t² / 2` (its DX and DY
/// along the ramp to 1e-8).
fn slides_along_the_ramp(vel: Option<f64>) -> Vec<(Method, Vec<Vec<f64>>)> {
    let theta: f64 = 0.4;
    let (c, s) = (theta.cos(), theta.sin());
    let text = block_on_a_ramp(
        theta,
        &vel.map_or_else(String::new, |v| format!(", VEL = {v}")),
    );
    let speed = vel.unwrap_or(0.0);
    [Method::Dop853, Method::Radau5]
        .into_iter()
        .map(|method| {
            let mut settings = settings(1.5, 3, 1e-10);
            settings.method = method;
            let slid = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
            for row in &slid.rows {
                let t = row[0];
                let along = 8.0 + speed * t - 0.5 * G * s * t * t;
                let n = row.len();
                assert!(
                    (row[n - 4] - along * c).abs() < 1e-8,
                    "{method:?} at {t}: {row:?}"
                );
                assert!(
                    (row[n - 3] - along * s).abs() < 1e-8,
                    "{method:?} at {t}: {row:?}"
                );
            }
            (method, slid.rows)
        })
        .collect()
}

/// A block on a straight two-point curve (ORDER = 2) sloping at `θ`
/// slides from rest as `s = g sin θ t² / 2`, and the curve holds it with
/// the normal force `m g cos θ`.
#[test]
fn a_block_on_a_straight_curve_slides_as_the_closed_form() {
    let c = 0.4_f64.cos();
    for (method, rows) in slides_along_the_ramp(None) {
        for row in &rows {
            let n = row.len();
            assert!(row[n - 2].abs() < 1e-12);
            assert!(
                (row[n - 1] - 3.0 * G * c).abs() < 1e-8,
                "{method:?} at {}: {row:?}",
                row[0]
            );
        }
    }
}

/// `VEL` starts the point of contact along its curve: a block on a
/// straight ramp sloping at `θ` (its parameter rising up the ramp) given
/// `VEL = 2` climbs as `s = 8 + 2 t − g sin θ t² / 2`; on a rail turned
/// at 1 rad/s about ground's z by a MOTION, `VEL = 0.5` is the speed
/// relative to the rail, so the bead, 1 from the axis on the rail's x,
/// starts at `(0.5, 1, 0)` in ground, and `VEL = -0.5` at `(-0.5, 1, 0)`.
#[test]
fn vel_starts_the_point_along_its_curve_relative_to_the_curve() {
    slides_along_the_ramp(Some(2.0));
    for speed in [0.5, -0.5] {
        let rail = format!(
            "bead on a turning rail
PART/1, GROUND
MARKER/10, PART = 1
PART/3, MASS = 1, CM = 30, IP = 0.1, 0.1, 0.1
MARKER/30, PART = 3
MARKER/31, PART = 3, FLOATING
JOINT/1, REVOLUTE, I = 30, J = 10
MOTION/1, JOINT = 1, ROTATION, FUNCTION = TIME
PART/2, MASS = 1, CM = 20, IP = 0.01, 0.01, 0.01
MARKER/20, PART = 2, QP = 1, 0, 0
MATRIX/1, FULL = CORDER, ROWS = 2, COLUMNS = 3, VALUES = -3, 3, 0, 0, 0, 0
CURVE/1, MATRIX = 1, ORDER = 2
PTCV/1, I = 20, JFLOAT = 31, RM = 30, CURVE = 1, VEL = {speed}
REQUEST/1, F2 = VX(20), F3 = VY(20), F4 = VZ(20)
END
"
        );
        let turned = run(&rail, &settings(0.1, 1, 1e-8)).unwrap_or_else(|error| panic!("{error}"));
        let first = &turned.rows[0];
        let n = first.len();
        let velocity = [first[n - 3], first[n - 2], first[n - 1]];
        let expected = [speed, 1.0, 0.0];
        for (got, want) in velocity.iter().zip(expected) {
            assert!((got - want).abs() < 1e-9, "VEL = {speed}: {velocity:?}");
        }
    }
}

/// What a PTCV cannot be read with, and a bead that runs past an open
/// curve's end, each at its place.
#[test]
fn what_a_point_curve_refuses_names_its_place() {
    let model = |curve: &str, holder: &str, velocity: f64| {
        format!(
            "refusals
PART/1, GROUND
MARKER/10, PART = 1
MARKER/11, PART = 1, FLOATING
PART/2, MASS = 1, CM = 20, IP = 0.1, 0.1, 0.1, VX = {velocity}
MARKER/20, PART = 2
MARKER/21, PART = 2, FLOATING
MATRIX/1, FULL = RORDER, ROWS = 3, COLUMNS = 3, VALUES = -2, 4, 0, 0, -4, 0, 2, 4, 0
{curve}
{holder}
ACCGRAV/JGRAV = -9.81
END
"
        )
    };
    let curve = "CURVE/1, OPEN, MATRIX = 1, ORDER = 3";
    let holder = "PTCV/1, I = 20, JFLOAT = 11, RM = 10, CURVE = 1";
    let cases = [
        ("fast enough to leave the parabola", model(curve, holder, 12.0)),
        (
            "a user curve under two PTCVs: the curve is named once",
            model(
                "CURVE/1, FUNCTION = USER(1, 2)",
                &format!("{holder}\nPTCV/2, I = 20, JFLOAT = 11, RM = 10, CURVE = 1"),
                0.0,
            ),
        ),
        (
            "a MATRIX of the wrong size",
            model("CURVE/1, MATRIX = 1, ORDER = 3\nMATRIX/2, FULL = RORDER, ROWS = 3, COLUMNS = 3, VALUES = 1, 2", "PTCV/1, I = 20, JFLOAT = 11, RM = 10, CURVE = 1", 0.0)
                .replace("MATRIX = 1, ORDER", "MATRIX = 2, ORDER"),
        ),
        (
            "too few points for the ORDER",
            model("CURVE/1, MATRIX = 1, ORDER = 5", holder, 0.0),
        ),
        (
            "no such curve, and a VEL that is not a number",
            model(curve, "PTCV/1, I = 20, JFLOAT = 11, RM = 10, CURVE = 7, VEL = fast", 0.0),
        ),
        (
            "DISP beyond the curve's end",
            model(curve, "PTCV/1, I = 20, JFLOAT = 11, RM = 10, CURVE = 1, DISP = 5, 25, 0", 0.0),
        ),
        (
            "JFLOAT on the point's part",
            model(curve, "PTCV/1, I = 20, JFLOAT = 21, RM = 10, CURVE = 1", 0.0),
        ),
    ];
    let table: String = cases
        .iter()
        .map(|(name, text)| {
            let outcome = match run(text, &settings(2.0, 4, 1e-8)) {
                Ok(ran) => format!("ran: {} rows", ran.rows.len()),
                Err(errors) => errors.trim_end().replace('\n', "\n     "),
            };
            format!("{name}\n  => {outcome}\n")
        })
        .collect();
    insta::assert_snapshot!(table);
}

/// A bead going round a closed cubic spline of 60 points (a three-lobed
/// loop): each knot it crosses (where the curve's third derivative
/// jumps) is a located switch of the PTCV, so that no step straddles one,
/// and the error at the end is the tolerance asked for, within a small
/// factor, with both methods (against DOP853 at 1e-12).
#[test]
fn a_bead_crossing_many_knots_keeps_its_tolerance() {
    let points: Vec<[f64; 3]> = (0..60)
        .map(|k| {
            let angle = f64::from(k) * std::f64::consts::TAU / 60.0;
            let radius = 1.0 + 0.2 * (3.0 * angle).cos();
            [2.0 * radius * angle.cos(), radius * angle.sin(), 0.0]
        })
        .collect();
    let text = bead_on_a_loop(&points, [2.4, 0.0, 0.0], "VY = 3");
    let end_of = |method: Method, rtol: f64| {
        let mut settings = settings(5.0, 1, rtol);
        settings.method = method;
        let ran = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let crossings = ran
            .events
            .iter()
            .filter(|event| event.function == "PTCV")
            .count();
        let last = ran.rows.last().unwrap().clone();
        (last, crossings)
    };
    let (reference, crossings) = end_of(Method::Dop853, 1e-12);
    assert!(crossings > 60, "{crossings} knots crossed");
    for method in [Method::Dop853, Method::Radau5] {
        for rtol in [1e-6, 1e-9] {
            let (last, _) = end_of(method, rtol);
            let n = last.len();
            let error = (last[n - 6] - reference[n - 6])
                .abs()
                .max((last[n - 5] - reference[n - 5]).abs());
            println!("{method:?} rtol {rtol:e}: {error:.1e} off at t = 5");
            assert!(error < 20.0 * rtol, "{method:?} rtol {rtol:e}: {error}");
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(8))]

    /// The Jacobian of a bead on a PTCV of a turning parabola (the
    /// curve's parameter carried over the dual numbers by a Newton step,
    /// the normals' turn and the curvature in the bias) agrees with
    /// central differences of the rates, off the curve too.
    #[test]
    fn the_jacobian_with_a_ptcv_agrees_with_finite_differences(
        shifts in proptest::collection::vec(-0.02f64..0.02, 26),
        time in 0.0f64..3.0,
    ) {
        let text = wire(
            2.0,
            "PTCV/1, I = 20, JFLOAT = 33, RM = 31, CURVE = 1",
            ["PTCV(1, 0, 2, 0)", "PTCV(1, 0, 3, 0)", "PTCV(1, 0, 4, 0)"],
        );
        super::simulate::the_jacobian_agrees_with_finite_differences(&text, &shifts, time)?;
    }
}

/// `examples/simulate/k_cam_follower.adm`: a point follower on a
/// translational joint held by a PTCV on an eccentric circular cam (a
/// closed cubic through 72 points of the circle) turned by a MOTION: the
/// tip's height is `e sin θ + sqrt(R² − e² cos² θ)` to the spline's
/// accuracy, with both methods, over two turns.
#[test]
fn the_cam_follower_example_rises_as_the_eccentric_circle_says() {
    let text = include_str!("../examples/simulate/k_cam_follower.adm");
    let (e, radius) = (0.02f64, 0.05f64);
    for method in [Method::Dop853, Method::Radau5] {
        let mut settings = settings(2.0, 40, 1e-9);
        settings.method = method;
        let turned = run(text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let mut worst = 0.0f64;
        for row in &turned.rows {
            let theta = std::f64::consts::TAU * row[0];
            let height = e * theta.sin() + (radius * radius - (e * theta.cos()).powi(2)).sqrt();
            worst = worst.max((row[row.len() - 3] - height).abs());
        }
        println!("{method:?}: the tip's height within {worst:.1e} of the closed form");
        assert!(worst < 1e-7, "{method:?}: {worst}");
        assert!(turned.events.iter().any(|event| event.function == "PTCV"));
    }
}

/// DISP places the point of contact where it says, as Adams does (the
/// curve's point nearest it, here `(−0.5, 0.25)` of the parabola, given in
/// RM's axes and in those of an ICM marker turned a quarter turn about z
/// and moved to (1, 0)), not where the I marker is drawn (at `(1, 1)`, or
/// past the curve's end at `(2.5, 6)`).
#[test]
fn disp_places_the_point_of_contact() {
    for (holder, extra) in [
        ("CURVE = 1, DISP = -0.5, 0.25, 0", ""),
        (
            "CURVE = 1, DISP = 0.25, 1.5, 0, ICM = 34",
            "MARKER/34, PART = 3, QP = 1, 0, 0, REULER = 90D, 0, 0\n",
        ),
    ] {
        let text = wire(
            0.0,
            &format!("{extra}PTCV/1, I = 20, JFLOAT = 33, RM = 31, {holder}"),
            ["PTCV(1, 0, 2, 0)", "PTCV(1, 0, 3, 0)", "PTCV(1, 0, 4, 0)"],
        );
        // Drawn past the parabola's end (x = 2) too: outside a run's step
        // the curve's end pieces are continued, so the point is put back.
        let past_the_end = text.replace("QP = 1, 1, 0", "QP = 2.5, 6, 0");
        for text in [text, past_the_end] {
            let ran = run(&text, &settings(0.1, 1, 1e-9)).unwrap_or_else(|error| panic!("{error}"));
            let first = &ran.rows[0];
            let n = first.len();
            assert!((first[n - 6] + 0.5).abs() < 1e-9, "{holder}: {first:?}");
            assert!((first[n - 5] - 0.25).abs() < 1e-9, "{holder}: {first:?}");
        }
    }
}

/// A bead on a closed cubic through 60 points of a trefoil knot, a curve
/// in three dimensions whose tangent turns through every direction (the
/// normals of each piece start from the axis least along that piece):
/// its energy keeps to the tolerance and both methods end together.
#[test]
fn a_bead_on_a_trefoil_keeps_its_energy() {
    let points: Vec<[f64; 3]> = (0..60)
        .map(|k| {
            let t = f64::from(k) * std::f64::consts::TAU / 60.0;
            [
                t.sin() + 2.0 * (2.0 * t).sin(),
                t.cos() - 2.0 * (2.0 * t).cos(),
                -(3.0 * t).sin(),
            ]
        })
        .collect();
    let text = bead_on_a_loop(&points, [0.0, -1.0, 0.0], "VX = 4");
    let mut ends = Vec::new();
    for method in [Method::Dop853, Method::Radau5] {
        let mut settings = settings(5.0, 20, 1e-9);
        settings.method = method;
        let ran = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let energy = |row: &[f64]| {
            let n = row.len();
            0.5 * (row[n - 3].powi(2) + row[n - 2].powi(2) + row[n - 1].powi(2)) + G * row[n - 5]
        };
        let start = energy(&ran.rows[0]);
        let drift = ran
            .rows
            .iter()
            .map(|row| (energy(row) - start).abs())
            .fold(0.0, f64::max);
        println!("{method:?}: energy drift {drift:.1e}");
        assert!(drift < 1e-7, "{method:?}: {drift}");
        ends.push(ran.rows.last().unwrap().clone());
    }
    let apart = largest_difference(&ends[0], &ends[1]);
    assert!(apart < 1e-6, "the methods end {apart} apart");
}
