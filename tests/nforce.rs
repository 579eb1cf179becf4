//! NFORCE, the multi-point linear force: against FIELDs of its diagonal
//! blocks, a two-mass chain's normal modes in closed form, CRATIO's
//! damping, the reaction on J (through `NFORCE(id, at_marker, comp, rm)`)
//! and its errors at their places.

use nalgebra::{DMatrix, Matrix6};

use super::contacts::with_method;
use super::simulate::{run, settings, the_jacobian_agrees_with_finite_differences};
use mbexpr::simulate::Settings;

/// The first REQUEST column: after the time and 13 for each of `parts`.
fn first(parts: usize) -> usize {
    1 + 13 * parts
}

/// `MATRIX/id` of `matrix`, column by column.
fn matrix(id: u64, matrix: &DMatrix<f64>) -> String {
    let values: Vec<String> = matrix.iter().map(f64::to_string).collect();
    format!(
        "MATRIX/{id}, FULL = CORDER, ROWS = {}, COLUMNS = {}, VALUES = {}",
        matrix.nrows(),
        matrix.ncols(),
        values.join(", ")
    )
}

/// A 6 × 6 block, not symmetric, of stiffness `scale`.
fn block(scale: f64) -> Matrix6<f64> {
    let mut k = Matrix6::from_diagonal(&nalgebra::Vector6::new(4.0, 5.0, 6.0, 0.5, 0.6, 0.7));
    k[(1, 0)] = 0.8;
    k[(0, 2)] = -0.4;
    k[(5, 1)] = 0.2;
    k[(2, 4)] = 0.15;
    k * scale
}

/// Three free parts: J on part 2, the I markers on parts 3 and 4, each
/// moving and turning at the start; `elements` the forces between them.
fn three_parts(elements: &str, request: &str) -> String {
    format!(
        "three parts
PART/1, GROUND
PART/2, MASS = 2, CM = 20, IP = 0.3, 0.4, 0.5, QG = 0, 0, 0, VX = 0.1, WZ = 0.3
MARKER/20, PART = 2
MARKER/21, PART = 2, QP = 0.1, -0.2, 0.05, REULER = 10D, 20D, 30D
PART/3, MASS = 1, CM = 30, IP = 0.1, 0.2, 0.15, QG = 1, 0.1, 0, VY = 0.3, WX = 0.5
MARKER/30, PART = 3
MARKER/31, PART = 3, QP = 0.9, 0.2, 0.1
PART/4, MASS = 1.5, CM = 40, IP = 0.2, 0.1, 0.25, QG = -0.5, 0.8, 0.2, VZ = -0.2, WY = 0.4
MARKER/40, PART = 4
MARKER/41, PART = 4, QP = -0.4, 0.7, 0.3
{elements}
{request}
END
"
    )
}

/// An NFORCE whose stiffness and damping are block diagonal is the FIELDs
/// of its blocks: the parts move alike, and its force at each I marker
/// and its reaction at J are the FIELDs' (their reactions summed).
#[test]
fn a_block_diagonal_nforce_moves_as_the_fields_of_its_blocks() {
    let (k1, k2) = (block(400.0), block(250.0));
    let (c1, c2) = (block(2.0), block(1.0));
    let mut k = DMatrix::zeros(12, 12);
    let mut c = DMatrix::zeros(12, 12);
    k.view_mut((0, 0), (6, 6)).copy_from(&k1);
    k.view_mut((6, 6), (6, 6)).copy_from(&k2);
    c.view_mut((0, 0), (6, 6)).copy_from(&c1);
    c.view_mut((6, 6), (6, 6)).copy_from(&c2);
    let free = [0.9, 0.3, 0.0, 0.05, -0.02, 0.01];
    let free2 = [-0.6, 0.5, 0.2, 0.0, 0.03, -0.04];
    let preload = [1.0, -2.0, 0.5, 0.1, 0.2, -0.3];
    let preload2 = [0.0, 1.5, -1.0, -0.2, 0.0, 0.1];
    let column = |a: &[f64; 6], b: &[f64; 6]| {
        DMatrix::from_iterator(12, 1, a.iter().chain(b.iter()).copied())
    };
    let list = |values: &[f64]| {
        values
            .iter()
            .map(f64::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let nforce = format!(
        "NFORCE/1, I = 31, 41, J = 21, KMATRIX = 1, CMATRIX = 2, LENGTH = 3, FORCE = 4\n{}\n{}\n{}\n{}",
        matrix(1, &k),
        matrix(2, &c),
        matrix(3, &column(&free, &free2)),
        matrix(4, &column(&preload, &preload2))
    );
    let field = |id: u64,
                 i: u64,
                 k: &Matrix6<f64>,
                 c: &Matrix6<f64>,
                 l: &[f64; 6],
                 f: &[f64; 6]| {
        format!(
            "FIELD/{id}, I = {i}, J = 21, KMATRIX = {}\n, CMATRIX = {}\n, LENGTH = {}, FORCE = {}",
            list(k.as_slice()),
            list(c.as_slice()),
            list(l),
            list(f)
        )
    };
    let fields = format!(
        "{}\n{}",
        field(1, 31, &k1, &c1, &free, &preload),
        field(2, 41, &k2, &c2, &free2, &preload2)
    );
    let components = |at: &str| {
        (2..=8)
            .filter(|comp| *comp != 5)
            .map(|comp| format!("F{comp} = {}", at.replace("COMP", &comp.to_string())))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let nforce_request = format!(
        "REQUEST/1, {}\nREQUEST/2, {}\nREQUEST/3, {}",
        components("NFORCE(1, 31, COMP, 0)"),
        components("NFORCE(1, 41, COMP, 21)"),
        components("NFORCE(1, 21, COMP, 0)")
    );
    let field_request = format!(
        "REQUEST/1, {}\nREQUEST/2, {}\nREQUEST/3, {}",
        components("FIELD(1, 0, COMP, 0)"),
        components("FIELD(2, 0, COMP, 21)"),
        components("FIELD(1, 1, COMP, 0) + FIELD(2, 1, COMP, 0)")
    );
    let a = three_parts(&nforce, &nforce_request);
    let b = three_parts(&fields, &field_request);
    for name in ["radau", "dop853"] {
        let settings = with_method(name, 1.0, 20, 1e-10);
        let a = run(&a, &settings).unwrap_or_else(|e| panic!("{e}"));
        let b = run(&b, &settings).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(a.rows.len(), b.rows.len());
        let worst = a
            .rows
            .iter()
            .zip(&b.rows)
            .flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
            .fold(0.0, f64::max);
        println!("{name}: NFORCE against FIELDs, largest difference {worst:.1e}");
        assert!(worst < 1e-9, "{name}: {worst}");
        // The parts moved and the forces are not small.
        let last = a.rows.last().unwrap();
        assert!(last[first(3)..].iter().any(|value| value.abs() > 1.0));
    }
    the_jacobian_agrees_with_finite_differences(&a, &[0.01, -0.02, 0.015, 0.0, 0.03], 0.2)
        .expect("exact jacobian");
}

/// Two masses on ground's x axis, tied to J at ground's origin through a
/// 2-DOF chain: ground–mass 1 `k1`, mass 1–mass 2 `k2`, so the NFORCE's
/// x rows are `[[k1 + k2, −k2], [−k2, k2]]` (off the diagonal blocks);
/// `LENGTH` the masses' places at rest, a stiffness of 10 holding each
/// other freedom; started `amplitude` along the mode. `line` is `m1 m2 k1
/// k2 mode cratio`.
fn chain(line: &str, amplitude: f64) -> (String, [f64; 4]) {
    let numbers: Vec<f64> = line
        .split_whitespace()
        .map(|n| n.parse().unwrap())
        .collect();
    let [m1, m2, k1, k2, mode, cratio] = numbers[..] else {
        panic!("{line}")
    };
    // ω² of det(K − ω² M) = 0, and the mode's shape (1, r).
    let (a, b) = ((k1 + k2) / m1 + k2 / m2, k1 * k2 / (m1 * m2));
    let sign = if mode == 1.0 { -1.0 } else { 1.0 };
    let omega2 = (a + sign * (a * a - 4.0 * b).sqrt()) / 2.0;
    let ratio = (k1 + k2 - omega2 * m1) / k2;
    let (l1, l2) = (1.0, 2.0);
    let text = format!(
        "chain
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = {m1}, CM = 20, IP = 1, 1, 1, QG = {}, 0, 0
MARKER/20, PART = 2
PART/3, MASS = {m2}, CM = 30, IP = 1, 1, 1, QG = {}, 0, 0
MARKER/30, PART = 3
NFORCE/1, IMARKERS = 20, 30, J = 1, KMATRIX = 1, CRATIO = {cratio}, LENGTH = 2
MATRIX/1, SPARSE, ROWS = 12, COLUMNS = 12, I = 1, 1, 7, 7, 2, 3, 4, 5, 6, 8, 9, 10, 11, 12
, J = 1, 7, 1, 7, 2, 3, 4, 5, 6, 8, 9, 10, 11, 12
, VALUES = {}, {}, {}, {k2}, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10
MATRIX/2, SPARSE, ROWS = 12, COLUMNS = 1, I = 1, 7, J = 1, 1, VALUES = {l1}, {l2}
REQUEST/1, F2 = NFORCE(1, 20, 2, 0), F3 = NFORCE(1, 30, 2, 0), F4 = NFORCE(1, 1, 2, 0)
END
",
        l1 + amplitude,
        l2 + amplitude * ratio,
        k1 + k2,
        -k2,
        -k2
    );
    (text, [omega2.sqrt(), amplitude, ratio, l1])
}

/// Started in one of its normal modes, the chain stays in it: each mass
/// moves as `L + a φ cos ω t` with `ω` and `φ` in closed form.
#[test]
fn a_two_mass_chain_moves_in_its_closed_form_normal_modes() {
    // m1 m2 k1 k2 mode cratio
    let cases = "
        1 2 100 50 1 0
        1 2 100 50 2 0
        3 1 40 90 1 0
        3 1 40 90 2 0
    ";
    for line in cases.lines().map(str::trim).filter(|line| !line.is_empty()) {
        let (text, [omega, amplitude, ratio, _]) = chain(line, 0.05);
        for name in ["radau", "dop853"] {
            let run =
                run(&text, &with_method(name, 2.0, 40, 1e-11)).unwrap_or_else(|e| panic!("{e}"));
            let mut worst: f64 = 0.0;
            for row in &run.rows {
                let swing = amplitude * (omega * row[0]).cos();
                worst = worst.max((row[1] - 1.0 - swing).abs());
                worst = worst.max((row[14] - 2.0 - ratio * swing).abs());
                // The reaction at J is the opposite of the two forces.
                let reaction = row[first(2) + 2] + row[first(2)] + row[first(2) + 1];
                worst = worst.max(reaction.abs());
            }
            println!("{line} {name}: largest difference {worst:.1e}");
            assert!(worst < 1e-7, "{line} {name}: {worst}");
        }
    }
}

/// With `CRATIO`, the chain's energy (kinetic, and `½ (x − L)ᵀ K (x −
/// L)`) never grows and falls off; with none, it holds.
#[test]
fn cratio_damping_takes_the_chains_energy_monotonically() {
    for (line, falls) in [("1 2 100 50 2 0.02", true), ("1 2 100 50 2 0", false)] {
        let (text, _) = chain(line, 0.05);
        let (m1, m2, k1, k2) = (1.0, 2.0, 100.0, 50.0);
        for name in ["radau", "dop853"] {
            let run =
                run(&text, &with_method(name, 3.0, 300, 1e-10)).unwrap_or_else(|e| panic!("{e}"));
            let energy: Vec<f64> = run
                .rows
                .iter()
                .map(|row| {
                    let (x1, x2) = (row[1] - 1.0, row[14] - 2.0);
                    let (v1, v2) = (row[8], row[21]);
                    0.5 * (m1 * v1 * v1 + m2 * v2 * v2)
                        + 0.5 * (k1 * x1 * x1 + k2 * (x2 - x1) * (x2 - x1))
                })
                .collect();
            let start = energy[0];
            let rise = energy
                .windows(2)
                .map(|pair| (pair[1] - pair[0]) / start)
                .fold(f64::MIN, f64::max);
            let end = energy.last().unwrap() / start;
            println!(
                "{line} {name}: largest rise {rise:.1e}, energy at the end {end:.3} of the start"
            );
            assert!(rise < 1e-8, "{line} {name}: {rise}");
            if falls {
                assert!(end < 0.5, "{line} {name}: {end}");
            } else {
                assert!((end - 1.0).abs() < 1e-6, "{line} {name}: {end}");
            }
        }
    }
}

/// The element applies no net force or moment: the forces at its I
/// markers and the reaction at J (`NFORCE(id, at_marker, comp, 0)`) sum
/// to zero, and so do their moments about ground's origin, along a run
/// of a full (coupled) stiffness and damping.
#[test]
fn the_reaction_on_j_balances_the_forces_on_the_i_markers() {
    let k = DMatrix::from_fn(12, 12, |row, column| {
        let (a, b) = (row.min(column) as f64, row.max(column) as f64);
        if row == column {
            300.0 + 10.0 * a
        } else {
            20.0 * ((a + 1.0) * (b + 2.0)).sin()
        }
    });
    let nforce = format!(
        "NFORCE/1, I = 31, 41, J = 21, KMATRIX = 1, CRATIO = 0.01\n{}",
        matrix(1, &k)
    );
    let at = |marker: u64| {
        format!(
            "F2 = NFORCE(1, {marker}, 2, 0), F3 = NFORCE(1, {marker}, 3, 0), F4 = NFORCE(1, {marker}, 4, 0)\n, F6 = NFORCE(1, {marker}, 6, 0), F7 = NFORCE(1, {marker}, 7, 0), F8 = NFORCE(1, {marker}, 8, 0)"
        )
    };
    let place = |marker: u64| {
        format!("F2 = DX({marker}, 0, 0), F3 = DY({marker}, 0, 0), F4 = DZ({marker}, 0, 0)")
    };
    let request = format!(
        "REQUEST/1, {}\nREQUEST/2, {}\nREQUEST/3, {}\nREQUEST/4, {}\nREQUEST/5, {}\nREQUEST/6, {}",
        at(31),
        at(41),
        at(21),
        place(31),
        place(41),
        place(21)
    );
    let text = three_parts(&nforce, &request);
    for name in ["radau", "dop853"] {
        let run = run(&text, &with_method(name, 1.0, 20, 1e-10)).unwrap_or_else(|e| panic!("{e}"));
        let (mut worst, mut scale): (f64, f64) = (0.0, 0.0);
        for row in &run.rows {
            let values = &row[first(3)..];
            let vector = |start: usize| {
                nalgebra::Vector3::new(values[start], values[start + 1], values[start + 2])
            };
            let (mut force, mut moment) = (nalgebra::Vector3::zeros(), nalgebra::Vector3::zeros());
            for marker in 0..3 {
                let (f, t, r) = (
                    vector(6 * marker),
                    vector(6 * marker + 3),
                    vector(18 + 3 * marker),
                );
                force += f;
                moment += t + r.cross(&f);
                scale = scale.max(f.norm()).max(t.norm());
            }
            worst = worst.max(force.norm()).max(moment.norm());
        }
        println!("{name}: largest net force or moment {worst:.1e}, the forces up to {scale:.1}");
        assert!(scale > 1.0, "{scale}");
        assert!(worst < 1e-9 * scale, "{name}: {worst}");
    }
}

/// `FORCE` is what the element applies with its I markers at `LENGTH`
/// (Adams' definition of the preload), and a static equilibrium of the
/// chain with no other load sits at `X = L + K⁻¹ F₀`.
#[test]
fn preload_and_length_give_the_documented_static_offset() {
    let (k1, k2, f1, f2) = (100.0, 50.0, 3.0, -2.0);
    // At rest at LENGTH, then FORCE added.
    let (text, _) = chain("1 2 100 50 1 0.05", 0.0);
    let text = text.replace(
            "LENGTH = 2",
            &format!("LENGTH = 2, FORCE = 3\nMATRIX/3, SPARSE, ROWS = 12, COLUMNS = 1, I = 1, 7, J = 1, 1, VALUES = {f1}, {f2}"),
        );
    let start = run(&text, &settings(0.1, 1, 1e-10)).unwrap_or_else(|e| panic!("{e}"));
    let row = &start.rows[0];
    assert_eq!((row[1], row[14]), (1.0, 2.0), "{text}");
    assert_eq!(
        (row[first(2)], row[first(2) + 1], row[first(2) + 2]),
        (f1, f2, -f1 - f2)
    );
    let statics = Settings {
        statics: true,
        ..settings(0.1, 1, 1e-10)
    };
    let settled = run(&text, &statics).unwrap_or_else(|e| panic!("{e}"));
    let row = &settled.rows[0];
    let d1 = (f1 + f2) / k1;
    let d2 = d1 + f2 / k2;
    let offset = [row[1] - 1.0 - d1, row[14] - 2.0 - d2];
    println!("static offset: {d1}, {d2}; differences {offset:?}");
    assert!(offset.iter().all(|d| d.abs() < 1e-9), "{offset:?}");
}

/// Each bad NFORCE, MATRIX or NFORCE call is refused at its place: one
/// line per case, the chain's text with `from` replaced by `to`.
#[test]
fn bad_nforces_are_refused_at_their_place() {
    let (base, _) = chain("1 2 100 50 1 0", 0.05);
    let cases = [
        ("no IMARKERS", "IMARKERS = 20, 30, J = 1", "J = 1"),
        (
            "I (IMARKERS abbreviated) lists a non-marker",
            "IMARKERS = 20, 30,",
            "I = 20, 31,",
        ),
        (
            "IMARKERS lists a marker twice",
            "IMARKERS = 20, 30,",
            "IMARKERS = 20, 20,",
        ),
        ("no J", "IMARKERS = 20, 30, J = 1,", "IMARKERS = 20, 30,"),
        ("J among the I markers", "J = 1,", "J = 30,"),
        ("no KMATRIX", "KMATRIX = 1,", ""),
        ("KMATRIX names no MATRIX", "KMATRIX = 1,", "KMATRIX = 9,"),
        ("KMATRIX of the wrong shape", "KMATRIX = 1,", "KMATRIX = 2,"),
        ("LENGTH of the wrong shape", "LENGTH = 2", "LENGTH = 1"),
        ("CMATRIX of the wrong shape", "CRATIO = 0", "CMATRIX = 2"),
        (
            "CMATRIX and CRATIO",
            "CRATIO = 0",
            "CRATIO = 0.1, CMATRIX = 1",
        ),
        ("a negative CRATIO", "CRATIO = 0", "CRATIO = -0.1"),
        (
            "a MATRIX from a FILE",
            "MATRIX/2, SPARSE,",
            "MATRIX/2, FILE = a.mtx, SPARSE,",
        ),
        (
            "NFORCE at a marker it does not join",
            "NFORCE(1, 1, 2, 0)",
            "NFORCE(1, 99, 2, 0)",
        ),
        (
            "NFORCE of no NFORCE",
            "NFORCE(1, 1, 2, 0)",
            "NFORCE(2, 1, 2, 0)",
        ),
        (
            "NFORCE of a component past 8",
            "NFORCE(1, 1, 2, 0)",
            "NFORCE(1, 1, 9, 0)",
        ),
    ];
    let table: String = cases
        .iter()
        .map(|(name, from, to)| {
            assert!(base.contains(from), "{name}: {from}");
            let text = base.replacen(from, to, 1);
            let outcome = match run(&text, &settings(0.1, 1, 1e-8)) {
                Ok(_) => "ran".to_string(),
                Err(errors) => errors.trim_end().replace('\n', "\n     "),
            };
            format!("{name}\n  => {outcome}\n")
        })
        .collect();
    insta::assert_snapshot!(table);
}
