//! Joint friction (`FRICTION`), checked against references worked out
//! here: a block on a slope held by stiction (its creep bounded by the
//! MAX_STICTION_DEFORMATION) or sliding with the closed-form acceleration
//! `g (sin θ − μd cos θ)` once past the transition band; a pendulum with
//! pin friction against RK4 of `θ''` written by hand (the reaction found
//! with `θ''`); energy that never grows for random pendulums; and every bad
//! input refused at its place.

use mbexpr::simulate::Settings;

use super::joints::{angle, method, pendulum};
use super::loop_values::rk4;
use super::simulate::{model_of, run, settings};

const G: f64 = 9.80665;

/// A 2 kg block on a translational joint along ground's z axis, gravity
/// tilted `slope` radians from −y towards −z, with `friction` (the
/// FRICTION statement's arguments after `JOINT = 1`).
fn block(slope: f64, friction: &str) -> String {
    let (sin, cos) = slope.sin_cos();
    format!(
        "block on a slope
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 2, CM = 20, IP = 0.1, 0.1, 0.1
MARKER/20, PART = 2
JOINT/1, TRANSLATIONAL, I = 20, J = 1
FRICTION/1, JOINT = 1, {friction}
ACCGRAV/JGRAV = {}, KGRAV = {}
END
",
        -G * cos,
        -G * sin
    )
}

/// Columns of the block's run: the creep state, then the part's z and vz.
const CREEP: usize = 1;
const Z: usize = 4;
const VZ: usize = 11;

/// `tan θ < μs`: stiction holds the block; it gives only the creep, which
/// settles at `δ·tan θ/μs` (the load `μs N s/δ` equal to `m g sin θ`).
#[test]
fn a_block_whose_slope_is_below_static_friction_stays() {
    let slope = 15_f64.to_radians();
    let text = block(slope, "MU_STATIC = 0.5, MU_DYNAMIC = 0.3");
    for name in ["dop853", "radau"] {
        let settings = Settings {
            method: method(name),
            ..settings(3.0, 30, 1e-8)
        };
        let run = run(&text, &settings).unwrap_or_else(|error| panic!("{name}: {error}"));
        let largest = run.rows.iter().map(|row| row[Z].abs()).fold(0.0, f64::max);
        let last = run.rows.last().expect("rows");
        let creep = 0.01 * slope.tan() / 0.5;
        println!(
            "{name}: largest travel {largest:.6}, creep {:.9} against {creep:.9}, vz {:.3e}",
            last[CREEP], last[VZ]
        );
        assert!(largest < 0.01, "{name}: travel {largest}");
        assert!((last[CREEP] + creep).abs() < 1e-6, "{name}: {last:?}");
        assert!(last[VZ].abs() < 1e-6, "{name}: {last:?}");
    }
}

/// `tan θ > μs`: the block slides; past `β·vs` its acceleration is
/// `g (sin θ − μd cos θ)` exactly (the velocity gained from t = 1 to 2),
/// and its travel is the closed form's to within what the transition band
/// explains (at most the band's time `β·vs/a_s` at the least acceleration
/// `a_s = g (sin θ − μs cos θ)`, times the end speed).
#[test]
fn a_block_whose_slope_is_beyond_static_friction_slides_at_the_dynamic_acceleration() {
    let slope = 30_f64.to_radians();
    let (mu_static, mu_dynamic) = (0.5, 0.3);
    let text = block(
        slope,
        &format!("MU_STATIC = {mu_static}, MU_DYNAMIC = {mu_dynamic}"),
    );
    let sliding = G * (slope.sin() - mu_dynamic * slope.cos());
    let least = G * (slope.sin() - mu_static * slope.cos());
    for name in ["dop853", "radau", "auto"] {
        let settings = Settings {
            method: method(name),
            ..settings(2.0, 2, 1e-9)
        };
        let run = run(&text, &settings).unwrap_or_else(|error| panic!("{name}: {error}"));
        let (middle, last) = (&run.rows[1], &run.rows[2]);
        let gained = middle[VZ] - last[VZ];
        let closed = 0.5 * sliding * 4.0;
        let band = 1.5 * 0.1 / least * sliding * 2.0;
        println!(
            "{name}: acceleration {gained:.10} against {sliding:.10}; travel {:.6} against {closed:.6} (band {band:.4})",
            -last[Z]
        );
        assert!((gained - sliding).abs() < 1e-6, "{name}: {gained}");
        assert!(
            -last[Z] < closed && closed + last[Z] < band,
            "{name}: {last:?}"
        );
    }
}

/// `STEP(x, x0, h0, x1, h1)`, the cubic.
fn step(x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> f64 {
    let u = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    h0 + (h1 - h0) * u * u * (3.0 - 2.0 * u)
}

/// The pendulum of [`pendulum`] (`m`, `d`, `izz`, released level) with pin
/// friction, sliding only: `Jp θ'' = −m g d cos θ − μ(Rp θ')·Rp·|R|`, `μ(v)
/// = STEP(v, −vs, −μd, vs, μd)`, `R = m (a − g)` the joint's force on the
/// pendulum, `a = d θ'' (−sin θ, cos θ) − d θ'² (cos θ, sin θ)`: θ'' found
/// with `R` by fixed-point iteration, then RK4 at a fine step.
fn pin_friction_reference(m: f64, d: f64, izz: f64, friction: [f64; 3], end: f64) -> (f64, f64) {
    let [mu, radius, vs] = friction;
    let inertia = izz + m * d * d;
    let acceleration = |theta: f64, omega: f64| {
        let mut alpha = 0.0;
        let (s, co) = theta.sin_cos();
        for _ in 0..60 {
            let a = (
                -d * alpha * s - d * omega * omega * co,
                d * alpha * co - d * omega * omega * s,
            );
            let reaction = m * a.0.hypot(a.1 + G);
            let torque = -step(radius * omega, -vs, -mu, vs, mu) * radius * reaction;
            alpha = (-m * G * d * co + torque) / inertia;
        }
        alpha
    };
    rk4(acceleration, (0.0, 0.0), end, 40_000)
}

/// The pendulum with a FRICTION of `arguments` on its revolute joint.
fn pendulum_with(m: f64, d: f64, izz: f64, arguments: &str) -> String {
    pendulum(m, d, izz).replace("END", &format!("FRICTION/1, JOINT = 1, {arguments}\nEND"))
}

/// Pin friction, sliding only, against the hand-written reference: the
/// angle and angular velocity after 2 s, with both methods; the friction
/// matters far more than the error.
#[test]
fn pin_friction_on_a_revolute_joint_agrees_with_the_equation_by_hand() {
    let (m, d, izz, end) = (2.0, 0.5, 0.03, 2.0);
    let friction = [0.3, 0.05, 0.01];
    let text = pendulum_with(
        m,
        d,
        izz,
        "MU_STATIC = 0.5, MU_DYNAMIC = 0.3, EFFECT = SLIDING, PIN_RADIUS = 0.05, STICTION_TRANSITION_VELOCITY = 0.01",
    );
    let (theta, w) = pin_friction_reference(m, d, izz, friction, end);
    let without = pin_friction_reference(m, d, izz, [0.0, 0.05, 0.01], end);
    for name in ["dop853", "radau"] {
        let settings = Settings {
            method: method(name),
            ..settings(end, 40, 1e-10)
        };
        let run = run(&text, &settings).unwrap_or_else(|error| panic!("{name}: {error}"));
        let mut turned = 0.0;
        for row in &run.rows {
            turned = angle(row, 4, turned);
        }
        let last = run.rows.last().expect("rows");
        println!(
            "{name}: angle {turned:.12} against {theta:.12}, ω {:.12} against {w:.12} (without friction {:.6}, {:.6})",
            last[13], without.0, without.1
        );
        assert!((turned - theta).abs() < 1e-7, "{name}: {turned} {theta}");
        assert!((last[13] - w).abs() < 1e-6, "{name}: {} {w}", last[13]);
        assert!((without.0 - theta).abs() + (without.1 - w).abs() > 1e-2);
    }
}

/// The energy `Jp ω²/2 + m g d sin θ` of a pendulum run, row by row.
fn energies(m: f64, d: f64, izz: f64, rows: &[Vec<f64>]) -> Vec<f64> {
    let mut turned = 0.0;
    rows.iter()
        .map(|row| {
            turned = angle(row, 4, turned);
            0.5 * (izz + m * d * d) * row[13] * row[13] + m * G * d * turned.sin()
        })
        .collect()
}

/// A seeded generator of numbers in `[0, 1)` (xorshift64*), so that the
/// random cases are the same at every run.
struct Seeded(u64);

impl Seeded {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn within(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.next()
    }
}

/// Friction never adds energy: sliding friction on pendulums of random
/// mass, size, coefficients, pin radius and spin loses energy at every
/// output step (to the integration's accuracy). The rod-like inertia
/// (`izz = m d²`) and a spin that cannot carry the bob over the top keep
/// the joint's reaction away from 0, where its magnitude has a kink that
/// the loop values' Newton's iterations do not settle (a light pendulum
/// in near free fall stops the run there, unsettled).
#[test]
fn pin_friction_never_adds_energy() {
    let mut random = Seeded(0x5EED_F00D);
    for case in 0..8 {
        let m = random.within(0.5, 5.0);
        let d = random.within(0.1, 1.0);
        let mu = random.within(0.05, 0.6);
        let radius = random.within(0.01, 0.2);
        let spin = random.within(-0.9, 0.9) * (G / d).sqrt();
        let izz = m * d * d;
        let text = pendulum_with(
            m,
            d,
            izz,
            &format!(
                "MU_STATIC = {}, MU_DYNAMIC = {mu}, EFFECT = SLIDING, PIN_RADIUS = {radius}",
                1.2 * mu
            ),
        )
        .replace(
            &format!("IP = {izz}, {izz}, {izz}"),
            &format!("IP = {izz}, {izz}, {izz}, WZ = {spin}"),
        );
        let run = run(&text, &settings(2.0, 100, 1e-9))
            .unwrap_or_else(|error| panic!("case {case}: {error}"));
        let energy = energies(m, d, izz, &run.rows);
        let scale = m * G * d + 0.5 * (izz + m * d * d) * spin * spin;
        let lost = (energy[0] - energy[energy.len() - 1]) / scale;
        println!(
            "case {case}: m {m:.3} d {d:.3} μ {mu:.3} Rp {radius:.3} ω {spin:.3}: lost {lost:.4} of the energy"
        );
        for pair in energy.windows(2) {
            assert!(pair[1] <= pair[0] + 1e-7 * scale, "case {case}: {energy:?}");
        }
        assert!(lost > 0.0);
    }
}

/// What a model with this FRICTION (after `FRICTION/1,`) on a joint of
/// each type reports: `kind | arguments`.
fn check(case: &str) -> String {
    let (kind, arguments) = case.split_once('|').expect("kind | arguments");
    let text = format!(
        "friction
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 1, 1, 1
MARKER/20, PART = 2
JOINT/1, {}, I = 20, J = 1
FRICTION/1, {}
ACCGRAV/JGRAV = -9.80665
END
",
        kind.trim(),
        arguments.trim().replace("\\n", "\n")
    );
    match model_of(&text) {
        Ok(model) => format!(
            "read: forces {}, states {}",
            model.forces.len(),
            model.diffs.len()
        ),
        Err(errors) => errors.trim_end().replace('\n', "\n     "),
    }
}

#[test]
fn bad_friction_is_refused_at_its_place() {
    let cases = "
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, EFFECT = SLIDING
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, EFFECT = STICTION, INPUTS = (PRELOAD:REACTION_FORCE), FRICTION_TORQUE_PRELOAD = 2, MAX_FRICTION_TORQUE = 5
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, INPUTS = NONE, INACTIVE = STATIC, OVERLAP_DELTA = CONSTANT
        TRANSLATIONAL | MU_STATIC = 0.5, MU_DYNAMIC = 0.3
        TRANSLATIONAL | JOINT = 7, MU_STATIC = 0.5, MU_DYNAMIC = 0.3
        TRANSLATIONAL | JOINT = 1.5, MU_STATIC = 0.5, MU_DYNAMIC = 0.3
        TRANSLATIONAL | JOINT = 1, MU_DYNAMIC = 0.3
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5
        TRANSLATIONAL | JOINT = 1, MU_STATIC = -0.5, MU_DYNAMIC = 0.3
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = -1
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, STICTION_TRANSITION_VELOCITY = 0
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, TRANSITION_VELOCITY_COEFFICIENT = 1
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, MAX_STICTION_DEFORMATION = -0.01
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, FRICTION_FORCE_PRELOAD = -3
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, INITIAL_OVERLAP = 0
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, REACTION_ARM = 0
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, MAX_FRICTION_FORCE = 0
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, EFFECT = STICKY
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, INPUTS = (PRELOAD:FORCE)
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, INACTIVE = DYNAMIC
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, OVERLAP_DELTA = INCREASE
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, OVERLAP_DELTA = SIDEWAYS
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, FRICTION_MODEL = LUGRE
        TRANSLATIONAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, FRICTION_MODEL = OTHER
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, PIN_RADIUS = 0
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, FRICTION_ARM = -1
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, BENDING_REACTION_ARM = 0
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, FRICTION_TORQUE_PRELOAD = -1
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, MAX_FRICTION_TORQUE = -2
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, INPUTS = TORSIONAL_MOMENT
        FIXED | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3
        PLANAR | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3
        CYLINDRICAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3
        SPHERICAL | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3
        HOOKE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3, I_YOKE = 20, J_YOKE = 1
        REVOLUTE | JOINT = 1, MU_STATIC = 0.5, MU_DYNAMIC = 0.3\\nFRICTION/2, JOINT = 1, MU_STATIC = 0.2, MU_DYNAMIC = 0.1
    ";
    insta::assert_snapshot!(super::table(cases, check));
}

/// `examples/simulate/m_friction_on_a_slope.adm`: the block held by
/// stiction stays within 2·MAX_STICTION_DEFORMATION of its start; the one
/// that slides gains `g (sin 20° − 0.2 cos 20°)` each second once past the
/// transition band (of the dataset's gravity, rounded: KGRAV − 0.2·JGRAV).
#[test]
fn the_friction_example_holds_one_block_and_slides_the_other() {
    let text = include_str!("../examples/simulate/m_friction_on_a_slope.adm");
    let run = run(text, &settings(4.0, 4, 1e-9)).expect("the example runs");
    // Time, three creep states, three parts of 13 columns, then F2 F3 F4.
    let (held, speed) = (1 + 3 + 3 * 13, 1 + 3 + 3 * 13 + 2);
    let sliding = 3.35407 - 0.2 * 9.21524;
    let (before, last) = (&run.rows[3], &run.rows[4]);
    let gained = before[speed] - last[speed];
    println!(
        "held block's travel {:.6}; sliding block gains {gained:.10} against {sliding:.10}",
        last[held]
    );
    assert!(run.rows.iter().all(|row| row[held].abs() < 0.02));
    assert!((gained - sliding).abs() < 1e-6, "{gained}");
}
