//! Curve-to-curve constraints (`CVCV` between two `CURVE`s of `MATRIX`
//! points): an eccentric circular cam turned by a MOTION lifts a roller
//! follower and a flat-faced follower on a translational joint as the
//! closed forms say, with the contact force Newton's law on the follower
//! gives, and so do cams and followers drawn at random; the point of
//! contact crosses the curves' knots as located switches; what cannot be
//! read, a contact run off an open curve and curves that bend alike are
//! refused at their place.

use mbexpr::integrate::Method;

use super::simulate::{run, settings};

const G: f64 = 9.80665;
/// The cam's radius.
const R: f64 = 0.05;
/// The cam's eccentricity.
const E: f64 = 0.02;
/// The roller's radius.
const ROLLER: f64 = 0.01;
/// The follower's mass.
const MASS: f64 = 0.2;
/// The follower's spring's stiffness.
const K: f64 = 50.0;
/// The spring's free length.
const FREE: f64 = 0.05;

/// A MATRIX of `count` points (the first repeated last) of the circle of
/// radius `radius` about `(cx, cy)`.
fn circle(id: u32, count: u32, radius: f64, (cx, cy): (f64, f64)) -> String {
    let values: Vec<String> = (0..=count)
        .map(|k| {
            let angle = std::f64::consts::TAU * f64::from(k % count) / f64::from(count);
            format!(
                "{}, {}, 0",
                cx + radius * angle.cos(),
                cy + radius * angle.sin()
            )
        })
        .collect();
    format!(
        "MATRIX/{id}, FULL = RORDER, ROWS = {}, COLUMNS = 3\n, VALUES = {}",
        count + 1,
        values.join("\n, ")
    )
}

/// A MATRIX of 6 points of the segment of JRM's x axis from `−half` to
/// `half`.
fn segment(id: u32, half: f64) -> String {
    let values: Vec<String> = (0..6)
        .map(|k| format!("{}, 0, 0", -half + 2.0 * half * f64::from(k) / 5.0))
        .collect();
    format!(
        "MATRIX/{id}, FULL = RORDER, ROWS = 6, COLUMNS = 3, VALUES = {}",
        values.join(", ")
    )
}

/// The cam (PART/2: a disc of radius R whose centre is at `centre` from
/// its axis, CURVE/1 in the axes of marker 21) turned about ground z at
/// one turn a second by a MOTION; the follower (PART/3, its centre of mass
/// marker 31 at height `height`) slides along ground y on a TRANSLATIONAL
/// joint, pushed down by a spring to a ground marker 0.1 below the axis,
/// and carries `follower` (CURVE/2 in the axes of marker 33, at its centre
/// of mass); `holder` the CVCV. REQUEST/1: the follower's height, the
/// contact force's y component on the follower and on the cam, the torque
/// on the follower about the point of contact, the follower's
/// acceleration, the cam's angular velocity.
fn cam(centre: (f64, f64), height: f64, follower: &str, holder: &str) -> String {
    format!(
        "cam and follower
PART/1, GROUND
MARKER/1, PART = 1
MARKER/2, PART = 1, QP = 0, 0.2, 0, REULER = 0, -90D, 0
MARKER/3, PART = 1, QP = 0, -0.1, 0
PART/2, MASS = 0.5, CM = 20, IP = 2e-4, 2e-4, 4e-4
MARKER/20, PART = 2, QP = {cx}, {cy}, 0
MARKER/21, PART = 2
MARKER/22, PART = 2
MARKER/23, PART = 2, FLOATING
PART/3, MASS = {MASS}, CM = 31, IP = 1e-4, 1e-4, 1e-5
MARKER/31, PART = 3, QP = 0, {height}, 0
MARKER/32, PART = 3, QP = 0, 0.2, 0, REULER = 0, -90D, 0
MARKER/33, PART = 3, QP = 0, {height}, 0
MARKER/34, PART = 3, FLOATING
JOINT/1, REVOLUTE, I = 22, J = 1
MOTION/1, JOINT = 1, ROTATION, FUNCTION = 2 * PI * TIME
JOINT/2, TRANSLATIONAL, I = 32, J = 2
SFORCE/1, TRANSLATIONAL, I = 31, J = 3, FUNCTION = -{K} * (DM(31, 3) - {FREE})
{profile}
CURVE/1, CLOSED, CURVE_POINTS, MATRIX = 1
{follower}
{holder}
ACCGRAV/JGRAV = -{G}
REQUEST/1, F2 = DY(31), F3 = CVCV(1, 1, 3, 0), F4 = CVCV(1, 0, 3, 0), F6 = CVCV(1, 1, 8, 0)
, F7 = ACCY(31), F8 = WZ(22)
END
",
        cx = centre.0,
        cy = centre.1,
        profile = circle(1, 72, R, centre),
    )
}

const HOLDER: &str = "CVCV/1, ICURVE = 1, IRM = 21, IFLOAT = 23, JCURVE = 2, JRM = 33, JFLOAT = 34";

/// A follower: its name, its CURVE/2 with its MATRIX, its height at the
/// start, and its height and the height's second derivative at a turn
/// `θ` of the cam.
type Follower = (&'static str, String, f64, fn(f64) -> [f64; 2]);

/// The roller (a closed circle of radius ROLLER), the same roller inside
/// the disc's rim (the curves' concave side against the convex one, as in
/// a groove) and the flat face (an open segment of JRM's x axis) as
/// CURVE/2, with the follower's height `y(θ)` and its second derivative in
/// `θ`, the closed forms of the eccentric cam: the roller's centre stays
/// `R + r` from the disc's (`R − r` inside), the face on the disc's top.
fn followers() -> [Follower; 3] {
    fn roller(theta: f64) -> [f64; 2] {
        centre_at(R + ROLLER, theta)
    }
    fn groove(theta: f64) -> [f64; 2] {
        centre_at(R - ROLLER, theta)
    }
    // The height of a point kept `d` from the disc's centre, and its
    // second derivative in `θ`.
    fn centre_at(d: f64, theta: f64) -> [f64; 2] {
        let (sin, cos) = theta.sin_cos();
        let s = (d * d - E * E * cos * cos).sqrt();
        let shear = E * E * cos * sin;
        [
            E * sin + s,
            -E * sin + E * E * (2.0 * theta).cos() / s - shear * shear / (s * s * s),
        ]
    }
    fn flat(theta: f64) -> [f64; 2] {
        [E * theta.sin() + R, -E * theta.sin()]
    }
    [
        (
            "roller",
            format!(
                "{}\nCURVE/2, CLOSED, CURVE_POINTS, MATRIX = 2",
                circle(2, 72, ROLLER, (0.0, 0.0))
            ),
            roller(0.0)[0],
            roller,
        ),
        (
            "roller inside the disc's rim (a groove)",
            format!(
                "{}\nCURVE/2, CLOSED, CURVE_POINTS, MATRIX = 2",
                circle(2, 72, ROLLER, (0.0, 0.0))
            ),
            groove(0.0)[0],
            groove,
        ),
        (
            "flat face",
            format!(
                "{}\nCURVE/2, OPEN, CURVE_POINTS, MATRIX = 2",
                segment(2, 0.05)
            ),
            flat(0.0)[0],
            flat,
        ),
    ]
}

/// The eccentric cam turning at one turn a second lifts each follower as
/// the closed form says (the splines are the circle to about 1e-8), and
/// the CVCV's force on the follower is Newton's: `m (ÿ + g)` less the
/// spring's pull, with the run's acceleration to rounding and with the
/// closed form's to 5e-4 N of 8 N (the splines' curvature is the
/// circle's to `h²`: 1.6e-5 N with 288 points on the cam, where 72 give
/// 2.5e-4 N and 4.5e-4 N), its force on the cam the opposite, its torque
/// about the point of contact none; the constraints' residuals stay below
/// the tolerance; with both methods, over two turns.
#[test]
fn an_eccentric_cam_lifts_its_followers_as_the_closed_form() {
    let omega = std::f64::consts::TAU;
    for (name, follower, height, closed) in followers() {
        let text = cam((E, 0.0), height, &follower, HOLDER);
        for method in [Method::Dop853, Method::Radau5] {
            let mut settings = settings(2.0, 80, 1e-9);
            settings.method = method;
            let turned = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
            let mut worst = [0.0f64; 5];
            for row in &turned.rows {
                let [y, force, reaction, torque, accy, _] = outputs(row);
                let spring = |y: f64| -K * (y + 0.1 - FREE);
                let [y_closed, bend_closed] = closed(omega * row[0]);
                let newton = MASS * (omega * omega * bend_closed + G) - spring(y_closed);
                let measured = MASS * (accy + G) - spring(y);
                for (worst, off) in worst.iter_mut().zip([
                    (y - y_closed).abs(),
                    (force - measured).abs(),
                    (force - newton).abs(),
                    (force + reaction).abs(),
                    torque.abs(),
                ]) {
                    *worst = worst.max(off);
                }
            }
            let [lift, force, closed_force, third, torque] = worst;
            println!(
                "{name}, {method:?}: lift within {lift:.1e} of the closed form; force within {force:.1e} N of Newton's with the \
                 run's acceleration, {closed_force:.1e} N with the closed form's; action and reaction {third:.1e}, torque {torque:.1e}; \
                 residuals {:?}",
                turned.summary.residuals
            );
            assert!(lift < 1e-7, "{name} {method:?}: lift {lift}");
            assert!(force < 1e-9, "{name} {method:?}: force {force}");
            assert!(
                closed_force < 6e-4,
                "{name} {method:?}: force {closed_force}"
            );
            assert!(third < 1e-9, "{name} {method:?}: {third}");
            assert!(torque < 1e-9, "{name} {method:?}: torque {torque}");
            let residuals = turned.summary.residuals;
            // Measured: positions 1.5e-13 to 1.9e-12, velocities (about
            // 0.13 m/s) 1.1e-13 to 1.9e-12. While steps straddled the
            // curves' knots (before they were located switches) the
            // velocities were off by 3e-8 to 1.5e-7.
            assert!(
                residuals.position < 1e-10 && residuals.velocity < 1e-10,
                "{name} {method:?}: {residuals:?}"
            );
        }
    }
}

/// The roller on the cam over two turns: the point of contact crosses
/// each knot of both curves (where a cubic spline's third derivative
/// jumps) as a located switch of the CVCV, so that no step straddles one,
/// and the follower's height is within a small factor of the tolerance
/// asked for of DOP853's at rtol 1e-12, with both methods. While steps
/// straddled the knots DOP853 at rtol 1e-9 rejected more steps than it
/// took (1 062 of 2 045) and was 6.7e-8 off at rtol 1e-6 (BENCHMARKS).
#[test]
fn a_cam_crossing_its_curves_knots_keeps_its_tolerance() {
    let [(_, roller, height, _), ..] = followers();
    let text = cam((E, 0.0), height, &roller, HOLDER);
    let heights = |method: Method, rtol: f64| {
        let mut settings = settings(2.0, 40, rtol);
        settings.method = method;
        let ran = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let crossings = |curve: &str| {
            ran.events
                .iter()
                .filter(|event| event.function == "CVCV" && event.to.ends_with(curve))
                .count()
        };
        let counts = [crossings("CURVE/1"), crossings("CURVE/2")];
        let heights: Vec<f64> = ran.rows.iter().map(|row| outputs(row)[0]).collect();
        let stats = ran.summary.stats;
        (heights, counts, (stats.rejected, stats.steps))
    };
    let (reference, [cam_knots, roller_knots], _) = heights(Method::Dop853, 1e-12);
    // Two turns of a cam of 72 pieces; the roller rocks across a few of
    // its 36 (measured: 144 and 12).
    assert!(
        cam_knots >= 140 && roller_knots >= 4,
        "{cam_knots}, {roller_knots} knots crossed"
    );
    for method in [Method::Dop853, Method::Radau5] {
        for rtol in [1e-6, 1e-9] {
            let (heights, _, (rejected, steps)) = heights(method, rtol);
            let error = heights
                .iter()
                .zip(&reference)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            println!(
                "{method:?} rtol {rtol:e}: {error:.1e} off, {rejected} of {steps} steps rejected"
            );
            // Measured: 1.1e-10 and 1.2e-12 (DOP853), 8.1e-9 and 1.5e-11
            // (Radau5) of heights about 0.06.
            assert!(
                error < 20.0 * rtol * 0.08,
                "{method:?} rtol {rtol:e}: {error}"
            );
            // Measured: at most 123 of 411 (DOP853 at 1e-9).
            assert!(
                2 * rejected < steps,
                "{method:?} rtol {rtol:e}: {rejected} of {steps} rejected"
            );
        }
    }
}

/// REQUEST/1's values in an output row: the follower's height, the
/// contact force's y component on the follower and on the cam, the torque
/// about the point of contact, the follower's acceleration, the cam's
/// angular velocity.
fn outputs(row: &[f64]) -> [f64; 6] {
    let n = row.len();
    std::array::from_fn(|k| row[n - 6 + k])
}

/// IDISP places the point of contact on the cam's profile where it says
/// (the cam free, no MOTION: the point the contact has at a turn of 0.3
/// rad, so the assembly turns the cam there and the roller rises to the
/// closed form's height); IVEL starts the point of contact along the
/// profile at that speed, relative to the cam (the cam's angular velocity
/// `IVEL / (R ψ'(θ))`, `ψ` the point's angle on the disc in the cam's
/// axes), to the spline's accuracy (2e-5 with 72 points, 5e-6 with 288).
#[test]
fn idisp_and_ivel_start_the_point_of_contact_on_the_cam() {
    let [(_, roller, height, closed), _, _] = followers();
    let theta = 0.3f64;
    let d = R + ROLLER;
    let psi = |theta: f64| {
        let y = closed(theta)[0];
        (y - E * theta.sin()).atan2(-E * theta.cos()) - theta
    };
    let angle = psi(theta);
    let point = [E + R * angle.cos(), R * angle.sin()];
    let h = 1e-6;
    let turn = (psi(theta + h) - psi(theta - h)) / (2.0 * h);
    let speed = 0.03;
    let holder = format!(
        "{HOLDER}, IDISP = {}, {}, 0, IVEL = {speed}",
        point[0], point[1]
    );
    let text = cam((E, 0.0), height, &roller, &holder).replace(
        "MOTION/1, JOINT = 1, ROTATION, FUNCTION = 2 * PI * TIME\n",
        "",
    );
    let started = run(&text, &settings(0.01, 1, 1e-10)).unwrap_or_else(|error| panic!("{error}"));
    let [y, .., spin] = outputs(&started.rows[0]);
    let want_spin = speed / (R * turn);
    println!(
        "IDISP: height {y} against {} (R + r = {d}); IVEL: spin {spin} against {want_spin}",
        closed(theta)[0]
    );
    assert!((y - closed(theta)[0]).abs() < 1e-7, "{y}");
    assert!((spin - want_spin).abs() < 1e-4 * want_spin.abs(), "{spin}");
}

/// What a CVCV cannot be read with, and a flat face too short for the
/// cam's throw (the contact runs off its end at t ≈ 0.135), each at its
/// place.
#[test]
fn what_a_curve_pair_refuses_names_its_place() {
    let [(_, roller, height, _), _, (_, flat, _, _)] = followers();
    let short = format!(
        "{}\nCURVE/2, OPEN, CURVE_POINTS, MATRIX = 2",
        segment(2, 0.015)
    );
    let cases = [
        (
            "a flat face too short",
            cam((0.0, E), R + E, &short, HOLDER),
        ),
        (
            "no such JCURVE",
            cam(
                (E, 0.0),
                height,
                &roller,
                &HOLDER.replace("JCURVE = 2", "JCURVE = 9"),
            ),
        ),
        (
            "no ICURVE nor JCURVE",
            cam(
                (E, 0.0),
                height,
                &roller,
                "CVCV/1, IRM = 21, IFLOAT = 23, JRM = 33, JFLOAT = 34",
            ),
        ),
        (
            "both curves on the cam",
            cam(
                (E, 0.0),
                height,
                &roller,
                &HOLDER.replace("JRM = 33, JFLOAT = 34", "JRM = 22, JFLOAT = 23"),
            ),
        ),
        (
            "the planes apart",
            cam((E, 0.0), height, &roller, HOLDER).replace(
                &format!("MARKER/33, PART = 3, QP = 0, {height}, 0"),
                &format!("MARKER/33, PART = 3, QP = 0, {height}, 0, REULER = 0, 30D, 0"),
            ),
        ),
        (
            "a curve out of its plane",
            cam((E, 0.0), R, &flat.replace(", 0, 0,", ", 0, 0.001,"), HOLDER),
        ),
        (
            "straight pieces",
            cam(
                (E, 0.0),
                height,
                &roller.replace("CURVE_POINTS, MATRIX = 2", "MATRIX = 2, ORDER = 2"),
                HOLDER,
            ),
        ),
        (
            "a pin that fills its hole (the cam's profile the roller's circle)",
            cam((0.0, 0.0), 0.0, &roller, HOLDER).replace(
                &circle(1, 72, R, (0.0, 0.0)),
                &circle(1, 72, ROLLER, (0.0, 0.0)),
            ),
        ),
        (
            "IDISP not three numbers, JVEL not a number",
            cam(
                (E, 0.0),
                height,
                &roller,
                &format!("{HOLDER}, IDISP = 1, JVEL = fast"),
            ),
        ),
    ];
    let table: String = cases
        .iter()
        .map(|(name, text)| {
            let outcome = match run(text, &settings(1.0, 4, 1e-8)) {
                Ok(ran) => format!("ran: {} rows", ran.rows.len()),
                Err(errors) => rounded(errors.trim_end()).replace('\n', "\n     "),
            };
            format!("{name}\n  => {outcome}\n")
        })
        .collect();
    insta::assert_snapshot!(table);
}

/// `text` with each number of more than six digits (a time the run
/// stopped at, a step size) rounded to two significant digits, so that
/// the snapshot holds what the message says, not the last bits of where
/// the integration went.
fn rounded(text: &str) -> String {
    let mut out = String::new();
    let mut number = String::new();
    let flush = |number: &mut String, out: &mut String| {
        let digits = number.chars().filter(char::is_ascii_digit).count();
        match number.parse::<f64>() {
            Ok(value) if digits > 6 => out.push_str(&format!("{value:.1e}")),
            _ => out.push_str(number),
        }
        number.clear();
    };
    for c in text.chars() {
        let exponent_sign = (c == '-' || c == '+') && number.ends_with('e');
        if c.is_ascii_digit() || c == '.' || (c == 'e' && !number.is_empty()) || exponent_sign {
            number.push(c);
        } else {
            flush(&mut number, &mut out);
            out.push(c);
        }
    }
    flush(&mut number, &mut out);
    out
}

/// The height of a roller's centre kept `d` from the centre of a disc
/// `e` off its axis, turned `θ` (the follower on the line through the
/// axis, square to the disc's offset at `θ = 0`).
fn kept_at(d: f64, e: f64, theta: f64) -> f64 {
    let (sin, cos) = theta.sin_cos();
    e * sin + (d * d - e * e * cos * cos).sqrt()
}

/// An interpolating cubic spline's distance from the circle of radius
/// `radius` through `points` evenly spaced points of it, bounded by
/// `(5/384) h⁴ max |f''''|` with `h` the points' spacing: `(5/384) (2π /
/// points)⁴ radius`.
fn spline_error(radius: f64, points: u32) -> f64 {
    5.0 / 384.0 * (std::f64::consts::TAU / f64::from(points)).powi(4) * radius
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(8))]

    /// Cams drawn at random (the disc's radius and eccentricity, its
    /// spline's points, its speed; a roller outside it or inside its rim,
    /// of a radius and points drawn too, or a flat face), with either
    /// method: the follower rises as the closed form says, within the two
    /// splines' distance from their circles and the tolerance, over two
    /// seconds, its point of contact crossing the knots as located
    /// switches, the constraints' residuals below the tolerance.
    #[test]
    fn random_cams_lift_their_followers_as_the_closed_form(
        radius in 0.03f64..0.08,
        offset in 0.0f64..0.6,
        roller_part in 0.1f64..0.5,
        kind in 0usize..3,
        cam_points in 40u32..120,
        roller_points in 24u32..80,
        turns in 0.3f64..2.0,
        radau in proptest::bool::ANY,
    ) {
        let r = roller_part * radius;
        // Inside the rim the roller's centre keeps `R − r` from the
        // disc's, so the eccentricity is drawn below that (it was drawn
        // below 0.6 R, and a roller of half the radius met no rim).
        let e = if kind == 1 { offset * (radius - r) } else { offset * radius };
        let omega = std::f64::consts::TAU * turns;
        let (follower, d, bound) = match kind {
            0 | 1 => {
                let d = if kind == 0 { radius + r } else { radius - r };
                let curve = format!(
                    "{}\nCURVE/2, CLOSED, CURVE_POINTS, MATRIX = 2",
                    circle(2, roller_points, r, (0.0, 0.0))
                );
                (curve, Some(d), spline_error(radius, cam_points) + spline_error(r, roller_points))
            }
            _ => {
                let curve = format!(
                    "{}\nCURVE/2, OPEN, CURVE_POINTS, MATRIX = 2",
                    segment(2, e + 0.02)
                );
                (curve, None, spline_error(radius, cam_points))
            }
        };
        let height_at = |theta: f64| match d {
            Some(d) => kept_at(d, e, theta),
            None => e * theta.sin() + radius,
        };
        let text = cam((e, 0.0), height_at(0.0), &follower, HOLDER)
            .replace(&circle(1, 72, R, (e, 0.0)), &circle(1, cam_points, radius, (e, 0.0)))
            .replace("FUNCTION = 2 * PI * TIME", &format!("FUNCTION = {omega} * TIME"));
        let rtol = 1e-9;
        let mut settings = settings(2.0, 40, rtol);
        settings.method = if radau { Method::Radau5 } else { Method::Dop853 };
        let ran = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let worst = ran
            .rows
            .iter()
            .map(|row| (outputs(row)[0] - height_at(omega * row[0])).abs())
            .fold(0.0, f64::max);
        let crossings = ran.events.iter().filter(|event| event.function == "CVCV").count();
        let residuals = ran.summary.residuals;
        println!(
            "kind {kind}, R {radius:.3}, e {e:.3}, r {r:.4}, {cam_points}/{roller_points} points, {turns:.2} turns/s, radau {radau}: \
             {worst:.1e} off (splines {bound:.1e}), {crossings} knots crossed, residuals {:.1e} {:.1e}",
            residuals.position, residuals.velocity
        );
        proptest::prop_assert!(worst < 2.0 * bound + 1e-8, "{worst} against {bound}");
        // Two seconds of at least 0.3 turns a second cross at least 0.6
        // of the cam's pieces (the roller's besides).
        proptest::prop_assert!(crossings as f64 >= 0.5 * f64::from(cam_points), "{crossings} knots crossed");
        proptest::prop_assert!(residuals.position < 1e-9 && residuals.velocity < 1e-8, "{residuals:?}");
    }
}

/// One cam drives three followers side by side, each on its own
/// TRANSLATIONAL joint: the roller (CVCV/1), a flat face (CVCV/2, on a
/// CURVE of its own) and a point (PTCV/1, on the cam's CURVE/1). Each
/// curve's knots are its own sites (one for the PTCV, two for each CVCV,
/// held on their pieces within a step), and each follower rises as its
/// closed form says, with both methods.
#[test]
fn one_cam_lifts_a_roller_a_flat_face_and_a_point_each_as_its_closed_form() {
    let [(_, roller, height, _), ..] = followers();
    let point = kept_at(R, E, 0.0);
    let others = format!(
        "PART/4, MASS = {MASS}, CM = 41, IP = 1e-4, 1e-4, 1e-5
MARKER/41, PART = 4, QP = 0, {R}, 0
MARKER/42, PART = 4, QP = 0, 0.2, 0, REULER = 0, -90D, 0
MARKER/43, PART = 4, QP = 0, {R}, 0
MARKER/44, PART = 4, FLOATING
JOINT/3, TRANSLATIONAL, I = 42, J = 2
{flat}
CURVE/3, OPEN, CURVE_POINTS, MATRIX = 3
CVCV/2, ICURVE = 1, IRM = 21, IFLOAT = 23, JCURVE = 3, JRM = 43, JFLOAT = 44
PART/5, MASS = {MASS}, CM = 51, IP = 1e-4, 1e-4, 1e-5
MARKER/51, PART = 5, QP = 0, {point}, 0
MARKER/52, PART = 5, QP = 0, 0.2, 0, REULER = 0, -90D, 0
JOINT/4, TRANSLATIONAL, I = 52, J = 2
PTCV/1, I = 51, JFLOAT = 23, RM = 21, CURVE = 1
REQUEST/2, F2 = DY(41), F3 = DY(51)
END
",
        flat = segment(3, 0.05),
    );
    let text = cam((E, 0.0), height, &roller, HOLDER).replace("END\n", &others);
    for method in [Method::Dop853, Method::Radau5] {
        let mut settings = settings(2.0, 40, 1e-9);
        settings.method = method;
        let ran = run(&text, &settings).unwrap_or_else(|error| panic!("{error}"));
        let mut worst = [0.0f64; 3];
        for row in &ran.rows {
            let theta = std::f64::consts::TAU * row[0];
            let n = row.len();
            let heights = [row[n - 8], row[n - 2], row[n - 1]];
            let closed = [
                kept_at(R + ROLLER, E, theta),
                E * theta.sin() + R,
                kept_at(R, E, theta),
            ];
            for (worst, (height, closed)) in worst.iter_mut().zip(heights.iter().zip(closed)) {
                *worst = worst.max((height - closed).abs());
            }
        }
        let crossings = |function: &str| {
            ran.events
                .iter()
                .filter(|event| event.label.starts_with(function))
                .count()
        };
        let counts = [
            crossings("CVCV/1"),
            crossings("CVCV/2"),
            crossings("PTCV/1"),
        ];
        println!("{method:?}: roller, flat, point within {worst:?}; knots crossed {counts:?}");
        // The splines' distance from their circles (72 points each):
        // measured 7.0e-9 to 8.5e-9 with either method.
        assert!(worst.iter().all(|off| *off < 2e-8), "{method:?}: {worst:?}");
        assert!(
            counts.iter().all(|count| *count >= 140),
            "{method:?}: {counts:?}"
        );
    }
}
