//! Jointed models the code was never tuned to: open chains of two to
//! four parts hanging from ground, each on a joint drawn at random
//! (SPHERICAL, REVOLUTE, UNIVERSAL, HOOKE, CONVEL, CYLINDRICAL,
//! TRANSLATIONAL, PLANAR, SCREW on a CYLINDRICAL) with random places, axes, masses,
//! inertias and initial velocities, the sliding ones held by a spring.
//! Nothing dissipates, and ideal joints do no work, so two checks need no
//! reference:
//!
//! - the energy (kinetic, gravity's and the springs') stays what it was at
//!   the start, within a small factor of the tolerance;
//! - DOP853 and Radau5 agree on the parts' centres of mass;
//!
//! and the joints' residuals stay below the tolerance. `MBEXPR_CHAINS=N`
//! draws N chains instead of the few a test run affords.

use std::fmt::Write;

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

use mbexpr::integrate::Method;
use mbexpr::simulate::Settings;

use super::simulate::{Run, run};
use super::simulate_variants::Draw;

const GRAVITY: f64 = 9.80665;
const END: f64 = 2.0;
const ROWS: usize = 40;

/// What a chain draws beyond numbers: vectors and axes.
pub(super) trait DrawShapes {
    /// A vector of components uniform in `[-size, size)`.
    fn vector(&mut self, size: f64) -> Vector3<f64>;
    /// Body 3-1-3 angles away from the degenerate `θ = 0, π`.
    fn euler(&mut self) -> [f64; 3];
}

impl DrawShapes for Draw {
    fn vector(&mut self, size: f64) -> Vector3<f64> {
        Vector3::new(
            self.uniform(-size, size),
            self.uniform(-size, size),
            self.uniform(-size, size),
        )
    }

    fn euler(&mut self) -> [f64; 3] {
        [
            self.uniform(0.0, std::f64::consts::TAU),
            self.uniform(0.3, 2.8),
            self.uniform(0.0, std::f64::consts::TAU),
        ]
    }
}

/// The joints drawn, with whether the part slides along or across the
/// joint (and so hangs on a spring).
const KINDS: [(&str, bool); 9] = [
    ("SPHERICAL", false),
    ("REVOLUTE", false),
    ("UNIVERSAL", false),
    ("HOOKE", false),
    ("CONVEL", false),
    ("CYLINDRICAL", true),
    ("TRANSLATIONAL", true),
    ("PLANAR", true),
    ("SCREW", true),
];

/// The rotation of Adams' body 3-1-3 angles: `Rz(ψ) Rx(θ) Rz(φ)`.
fn rotation([psi, theta, phi]: [f64; 3]) -> Matrix3<f64> {
    let z = |angle| *Rotation3::from_axis_angle(&Vector3::z_axis(), angle).matrix();
    let x = |angle| *Rotation3::from_axis_angle(&Vector3::x_axis(), angle).matrix();
    z(psi) * x(theta) * z(phi)
}

/// The body 3-1-3 angles of a rotation (`θ` away from 0 and π).
pub(super) fn euler_of(r: &Matrix3<f64>) -> [f64; 3] {
    [
        r[(0, 2)].atan2(-r[(1, 2)]),
        r[(2, 2)].clamp(-1.0, 1.0).acos(),
        r[(2, 0)].atan2(r[(2, 1)]),
    ]
}

/// A part of a chain: its mass, principal inertias (about its CM marker,
/// whose axes are the part's), its centre of mass in ground (the part's
/// frame is ground's at the start).
struct Part {
    mass: f64,
    inertia: [f64; 3],
    centre: Vector3<f64>,
}

/// A spring between a point of part `child` (index into the chain's parts)
/// and a point of its parent (`None`: ground), both given in ground at the
/// start (the parts' frames are ground's then).
struct Spring {
    child: usize,
    parent: Option<usize>,
    on_child: Vector3<f64>,
    on_parent: Vector3<f64>,
    stiffness: f64,
    length: f64,
}

/// A chain as a dataset, and what the energy needs of it.
struct Chain {
    text: String,
    parts: Vec<Part>,
    springs: Vec<Spring>,
    kinds: Vec<&'static str>,
}

fn marker(text: &mut String, id: usize, part: usize, at: &Vector3<f64>, euler: Option<[f64; 3]>) {
    write!(
        text,
        "MARKER/{id}, PART = {part}, QP = {}, {}, {}",
        at.x, at.y, at.z
    )
    .unwrap();
    if let Some([psi, theta, phi]) = euler {
        write!(text, ", REULER = {psi}, {theta}, {phi}").unwrap();
    }
    text.push('\n');
}

fn chain(draw: &mut Draw) -> Chain {
    let count = 2 + (draw.next() % 3) as usize;
    let mut text = String::from("a chain drawn at random\nPART/1, GROUND\nMARKER/1, PART = 1\n");
    let mut parts: Vec<Part> = Vec::new();
    let mut springs = Vec::new();
    let mut kinds = Vec::new();
    let mut point = Vector3::zeros();
    for index in 0..count {
        let part = index + 2;
        let (kind, slides) = KINDS[(draw.next() % KINDS.len() as u64) as usize];
        kinds.push(kind);
        let mass = draw.uniform(0.5, 3.0);
        let sides = [0; 3].map(|_| draw.uniform(0.1, 0.6));
        let inertia = [
            mass / 12.0 * (sides[1].powi(2) + sides[2].powi(2)),
            mass / 12.0 * (sides[0].powi(2) + sides[2].powi(2)),
            mass / 12.0 * (sides[0].powi(2) + sides[1].powi(2)),
        ];
        let centre = point + draw.vector(0.4);
        let [vx, vy, vz, wx, wy, wz] = [0; 6].map(|_| draw.uniform(-1.0, 1.0));
        writeln!(
            text,
            "PART/{part}, MASS = {mass}, CM = {cm}, IP = {}, {}, {}, VX = {vx}, VY = {vy}, VZ = {vz}, WX = {wx}, WY = {wy}, WZ = {wz}",
            inertia[0],
            inertia[1],
            inertia[2],
            cm = 100 * part
        )
        .unwrap();
        marker(&mut text, 100 * part, part, &centre, None);
        // The joint: I on this part, J on the one before (or ground), at
        // `point`, J's axes drawn, I's the same but for UNIVERSAL (its z
        // along J's x: the cross's arms perpendicular).
        let j_euler = draw.euler();
        let j_axes = rotation(j_euler);
        let i_euler = if kind == "UNIVERSAL" {
            euler_of(
                &(j_axes
                    * Rotation3::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2)
                        .matrix()),
            )
        } else {
            j_euler
        };
        let (i_id, j_id) = (100 * part + 1, 100 * part + 2);
        let parent = if index == 0 { 1 } else { part - 1 };
        marker(&mut text, i_id, part, &point, Some(i_euler));
        marker(&mut text, j_id, parent, &point, Some(j_euler));
        let pitch = draw.uniform(0.1, 0.5);
        if kind == "SCREW" {
            // A screw only couples the turn to the slide: it rides on a
            // CYLINDRICAL joint, as in Adams models.
            writeln!(
                text,
                "JOINT/{}, CYLINDRICAL, I = {i_id}, J = {j_id}",
                part + 50
            )
            .unwrap();
            writeln!(
                text,
                "JOINT/{part}, SCREW, I = {i_id}, J = {j_id}, PITCH = {pitch}"
            )
            .unwrap();
        } else {
            writeln!(text, "JOINT/{part}, {kind}, I = {i_id}, J = {j_id}").unwrap();
        }
        if slides {
            // A spring from the joint's place on this part to a point of
            // the parent 0.3 off it across the joint's axis (so its length
            // never vanishes), preloaded.
            let on_parent = point + j_axes.column(0) * 0.3;
            let stiffness = draw.uniform(200.0, 800.0);
            let length = 0.25;
            let (spring_i, spring_j) = (100 * part + 3, 100 * part + 4);
            marker(&mut text, spring_i, part, &point, None);
            marker(&mut text, spring_j, parent, &on_parent, None);
            writeln!(
                text,
                "SPRINGDAMPER/{part}, TRANSLATIONAL, I = {spring_i}, J = {spring_j}, K = {stiffness}, C = 0, LENGTH = {length}"
            )
            .unwrap();
            springs.push(Spring {
                child: index,
                parent: index.checked_sub(1),
                on_child: point,
                on_parent,
                stiffness,
                length,
            });
        }
        parts.push(Part {
            mass,
            inertia,
            centre,
        });
        point = centre + draw.vector(0.4);
    }
    writeln!(text, "ACCGRAV/JGRAV = -{GRAVITY}\nEND").unwrap();
    Chain {
        text,
        parts,
        springs,
        kinds,
    }
}

/// Part `index`'s frame at a row: its origin, rotation, origin velocity
/// and angular velocity (both in ground).
pub(super) fn frame(
    row: &[f64],
    index: usize,
) -> (Vector3<f64>, Matrix3<f64>, Vector3<f64>, Vector3<f64>) {
    let s = &row[1 + 13 * index..1 + 13 * (index + 1)];
    let rotation =
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(s[3], s[4], s[5], s[6]));
    (
        Vector3::new(s[0], s[1], s[2]),
        *rotation.to_rotation_matrix().matrix(),
        Vector3::new(s[7], s[8], s[9]),
        Vector3::new(s[10], s[11], s[12]),
    )
}

/// A point of part `index` given in ground at the start, where it is at
/// `row` (the part's frame was ground's at the start).
fn placed(row: &[f64], index: usize, start: &Vector3<f64>) -> Vector3<f64> {
    let (origin, rotation, _, _) = frame(row, index);
    origin + rotation * start
}

/// The chain's energy at a row: the parts' kinetic energy, gravity's
/// potential and the springs'.
fn energy(chain: &Chain, row: &[f64]) -> f64 {
    let mut total = 0.0;
    for (index, part) in chain.parts.iter().enumerate() {
        let (origin, rotation, velocity, omega) = frame(row, index);
        let arm = rotation * part.centre;
        let centre_velocity = velocity + omega.cross(&arm);
        let body_omega = rotation.transpose() * omega;
        let spin: f64 = (0..3)
            .map(|k| part.inertia[k] * body_omega[k].powi(2))
            .sum();
        total += 0.5 * part.mass * centre_velocity.norm_squared() + 0.5 * spin;
        total += part.mass * GRAVITY * (origin + arm).y;
    }
    for spring in &chain.springs {
        let i = placed(row, spring.child, &spring.on_child);
        let j = spring.parent.map_or(spring.on_parent, |parent| {
            placed(row, parent, &spring.on_parent)
        });
        total += 0.5 * spring.stiffness * ((i - j).norm() - spring.length).powi(2);
    }
    total
}

fn settings(method: Method, rtol: f64) -> Settings {
    Settings {
        method,
        end: END,
        steps: ROWS,
        rtol,
        atol: rtol * 1e-3,
        ..Settings::default()
    }
}

/// The centres of mass of every part at every row.
fn centres(chain: &Chain, run: &Run) -> Vec<Vector3<f64>> {
    run.rows
        .iter()
        .flat_map(|row| {
            chain
                .parts
                .iter()
                .enumerate()
                .map(|(index, part)| placed(row, index, &part.centre))
        })
        .collect()
}

#[test]
fn random_chains_keep_their_energy_and_both_methods_agree() {
    let count: u64 = std::env::var("MBEXPR_CHAINS")
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(6);
    let mut draw = Draw(0x6a6f_696e_7473);
    let mut report = String::new();
    let mut failed = false;
    for draw_index in 0..count {
        let chain = chain(&mut draw);
        let runs: Vec<(&str, f64, Run)> = [
            ("dop853", Method::Dop853, 1e-10),
            ("radau", Method::Radau5, 1e-9),
        ]
        .into_iter()
        .map(|(name, method, rtol)| {
            let run = run(&chain.text, &settings(method, rtol))
                .unwrap_or_else(|error| panic!("draw {draw_index}: {error}\n{}", chain.text));
            (name, rtol, run)
        })
        .collect();
        // The scale of the energies that trade: each part's fall over the
        // chain's reach, and the start's kinetic energy.
        let scale: f64 = chain
            .parts
            .iter()
            .map(|part| part.mass * GRAVITY)
            .sum::<f64>()
            * 2.0
            + energy(&chain, &runs[0].2.rows[0]).abs();
        let mut line = format!("draw {draw_index} {:?}:", chain.kinds);
        for (name, rtol, run) in &runs {
            let start = energy(&chain, &run.rows[0]);
            let drift = run
                .rows
                .iter()
                .map(|row| (energy(&chain, row) - start).abs())
                .fold(0.0, f64::max)
                / scale;
            write!(
                line,
                " {name} {rtol:.0e}: energy drift {drift:.1e}, residuals {:.1e} {:.1e};",
                run.summary.residuals.position, run.summary.residuals.velocity
            )
            .unwrap();
            failed |= drift > 100.0 * rtol || run.summary.residuals.position > 100.0 * rtol;
        }
        let apart = centres(&chain, &runs[0].2)
            .iter()
            .zip(centres(&chain, &runs[1].2))
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        write!(line, " methods apart {apart:.1e} m").unwrap();
        failed |= apart > 1e-5;
        println!("{line}");
        report += &line;
        report.push('\n');
        if failed {
            println!("{}", chain.text);
        }
    }
    assert!(!failed, "{report}");
}

/// The exact Jacobian of random chains (every joint kind above, the
/// multipliers as unknowns beside the states and eliminated by their
/// Schur complement) agrees with finite differences of the right-hand
/// side, at the drawn state moved off it a little.
#[test]
fn the_jacobian_of_random_chains_agrees_with_finite_differences() {
    let mut draw = Draw(0x6a61_636f_6269);
    for draw_index in 0..12 {
        let chain = chain(&mut draw);
        let shifts: Vec<f64> = (0..7).map(|_| 0.02 * draw.uniform(-1.0, 1.0)).collect();
        println!("draw {draw_index}: {:?}", chain.kinds);
        if let Err(error) =
            super::simulate::the_jacobian_agrees_with_finite_differences(&chain.text, &shifts, 0.0)
        {
            panic!(
                "draw {draw_index} {:?}: {error}\n{}",
                chain.kinds, chain.text
            );
        }
    }
}
