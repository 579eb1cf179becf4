//! BEAM and FIELD: a part hung on one from ground settles where the
//! element's stiffness balances its weight, checked against closed forms
//! written here (a Timoshenko cantilever's tip deflection and slope under
//! a tip load) and against a linear solve of the field's own matrices; the
//! element's value functions read its pull on I and the reaction on J.

use nalgebra::{Matrix6, Vector3, Vector6};

use super::simulate::{run, settings};

/// The first REQUEST column: after the time and 13 of the part.
const FIRST: usize = 14;

/// A beam case: `E G A Ixx Iyy Izz ASY ASZ L gx gy gz`, the beam along
/// ground's x from its origin to the part's centre of mass (mass 1), the
/// gravity `g`.
fn beam_model(numbers: &[f64; 12]) -> String {
    let [e, g, a, ixx, iyy, izz, asy, asz, l, gx, gy, gz] = *numbers;
    format!(
        "cantilever
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 0.01, 0.01, 0.01, QG = {l}, 0, 0
MARKER/20, PART = 2
BEAM/1, I = 20, J = 1, LENGTH = {l}, IXX = {ixx}, IYY = {iyy}, IZZ = {izz}, AREA = {a}
, ASY = {asy}, ASZ = {asz}, EMODULUS = {e}, GMODULUS = {g}, CRATIO = 0.02
ACCGRAV/IGRAV = {gx}, JGRAV = {gy}, KGRAV = {gz}
REQUEST/1, F1 = DX(20, 1, 1), F2 = DY(20, 1, 1), F3 = DZ(20, 1, 1), F4 = AY(20, 1)
, F5 = AZ(20, 1), F6 = BEAM(1,0,3,0), F7 = BEAM(1,1,4,0), F8 = BEAM(1,1,6,0)
END
"
    )
}

/// The largest difference, relative to the deflection's scale, between
/// the settled beam and the cantilever's closed form: the tip of a beam
/// of length `L` under a tip load `P` moves `P L³/(3 E I) + P·AS·L/(G A)`
/// (bending and shear) and turns `P L²/(2 E I)`; along the beam it
/// stretches `P L/(E A)`. The weight's pull on I is `−g`, on J the
/// opposite, turned by the moment arm `−(I − J) × F` about J.
fn check_beam(line: &str) -> f64 {
    let numbers: Vec<f64> = line
        .split_whitespace()
        .map(|n| n.parse().unwrap())
        .collect();
    let numbers: [f64; 12] = numbers.try_into().unwrap();
    let [e, g, a, _, iyy, izz, asy, asz, l, gx, gy, gz] = numbers;
    let run = run(&beam_model(&numbers), &settings(12.0, 12, 1e-9)).expect("the beam runs");
    let row = run.rows.last().unwrap();
    let x = l + gx * l / (e * a);
    let y = gy * (l.powi(3) / (3.0 * e * izz) + asy * l / (g * a));
    let z = gz * (l.powi(3) / (3.0 * e * iyy) + asz * l / (g * a));
    let about_y = -gz * l * l / (2.0 * e * iyy);
    let about_z = gy * l * l / (2.0 * e * izz);
    // On J: the opposite of the pull on I (−g), about J's origin with the
    // arm from J to I.
    let pull = Vector3::new(-gx, -gy, -gz);
    let arm = Vector3::new(x, y, z);
    let torque_on_j = -arm.cross(&pull);
    let expected = [x, y, z, about_y, about_z, -gy, gz, torque_on_j.x];
    let scale = [
        1.0,
        y.abs(),
        z.abs().max(1e-3),
        about_y.abs().max(1e-3),
        about_z.abs(),
    ];
    let mut worst: f64 = 0.0;
    for (index, (found, expected)) in row[FIRST..].iter().zip(expected).enumerate() {
        let scale = scale.get(index).copied().unwrap_or(1.0);
        worst = worst.max((found - expected).abs() / scale);
    }
    worst
}

#[test]
fn a_cantilever_beam_settles_at_its_timoshenko_deflection() {
    // E G A Ixx Iyy Izz ASY ASZ L gx gy gz
    let cases = "
        1e7 4e6 0.01 3e-5 2e-5 1e-5 0 0 1 0 -9.81 0
        1e7 4e6 0.01 3e-5 2e-5 1e-5 1.2 1.2 1 0 -9.81 0
        1e7 4e6 0.01 3e-5 2e-5 1e-5 1.2 10 1 -3 -9.81 4
        2e7 8e6 0.02 3e-5 5e-5 2e-5 1.1111 1.1111 0.7 2 -5 -7
    ";
    for line in cases.lines().map(str::trim).filter(|line| !line.is_empty()) {
        let worst = check_beam(line);
        println!("{line}: largest relative difference {worst:.2e}");
        assert!(worst < 1e-5, "{line}: {worst}");
    }
}

/// A FIELD's matrices are read column by column: a stiffness that is not
/// symmetric, a free position and a preload, and the part (mass 1) settles
/// at `X = L + K⁻¹ (F₀ − g)` (its weight `g` pulls I; the torques balance
/// at zero). The damping is CRATIO times the stiffness.
#[test]
fn a_field_settles_where_its_matrices_balance_the_weight() {
    let mut k = Matrix6::from_diagonal(&Vector6::new(400.0, 500.0, 600.0, 50.0, 60.0, 70.0));
    k[(1, 0)] = 80.0;
    k[(0, 2)] = -40.0;
    k[(5, 1)] = 20.0;
    k[(2, 4)] = 15.0;
    let free = Vector6::new(1.0, 0.1, -0.05, 0.02, -0.01, 0.03);
    let preload = Vector6::new(2.0, -1.0, 3.0, 0.5, -0.2, 0.4);
    let gravity = Vector3::new(1.0, -9.81, 2.0);
    // Column by column, as Adams reads KMATRIX.
    let written: Vec<String> = k.iter().map(|entry| entry.to_string()).collect();
    let list = |v: &Vector6<f64>| v.iter().map(f64::to_string).collect::<Vec<_>>().join(", ");
    let text = format!(
        "field
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 0.01, 0.01, 0.01, QG = 1, 0, 0
MARKER/20, PART = 2
FIELD/1, I = 20, J = 1, KMATRIX = {}, CRATIO = 0.05
, LENGTH = {}, FORCE = {}
ACCGRAV/IGRAV = {}, JGRAV = {}, KGRAV = {}
REQUEST/1, F1 = DX(20, 1, 1), F2 = DY(20, 1, 1), F3 = DZ(20, 1, 1), F4 = AX(20, 1)
, F5 = AY(20, 1), F6 = AZ(20, 1), F7 = FIELD(1,0,3,0), F8 = FIELD(1,1,3,0)
END
",
        written.join(", "),
        list(&free),
        list(&preload),
        gravity.x,
        gravity.y,
        gravity.z
    );
    let run = run(&text, &settings(12.0, 12, 1e-9)).expect("the field runs");
    let row = run.rows.last().unwrap();
    let load = preload + Vector6::new(gravity.x, gravity.y, gravity.z, 0.0, 0.0, 0.0);
    let settled = free + k.lu().solve(&load).unwrap();
    let expected = [
        settled[0], settled[1], settled[2], settled[3], settled[4], settled[5], -gravity.y,
        gravity.y,
    ];
    let worst = row[FIRST..]
        .iter()
        .zip(expected)
        .map(|(found, expected)| (found - expected).abs())
        .fold(0.0, f64::max);
    println!("field: largest difference {worst:.2e}");
    assert!(
        worst < 1e-6,
        "{worst}: {:?} against {expected:?}",
        &row[FIRST..]
    );
}

/// A BEAM's CMATRIX is the lower half of the damping matrix, column by
/// column: along a free swing, its pull on I is `−K (X − L) − C V` at every
/// output, with `K` the Timoshenko stiffness written out here and `C` the
/// 21 numbers placed by hand.
#[test]
fn a_beams_damping_matrix_is_read_by_columns_of_its_lower_half() {
    let (e, g, a, ixx, iyy, izz, asy, l) = (1e5, 4e4, 0.01, 3e-5, 2e-5, 1e-5, 1.2, 1.0_f64);
    let half: Vec<f64> = (1..=21).map(|n| 0.001 * f64::from(n)).collect();
    let text = format!(
        "swinging beam
PART/1, GROUND
MARKER/1, PART = 1
PART/2, MASS = 1, CM = 20, IP = 0.01, 0.01, 0.01, QG = {l}, 0.01, -0.02
, VX = 0.1, VY = -0.2, VZ = 0.3, WX = 0.5, WY = -0.4, WZ = 0.6
MARKER/20, PART = 2
BEAM/1, I = 20, J = 1, LENGTH = {l}, IXX = {ixx}, IYY = {iyy}, IZZ = {izz}, AREA = {a}
, ASY = {asy}, EMODULUS = {e}, GMODULUS = {g}, CMATRIX = {}
REQUEST/1, F1 = DX(20, 1, 1), F2 = DY(20, 1, 1), F3 = DZ(20, 1, 1), F4 = AX(20, 1)
, F5 = AY(20, 1), F6 = AZ(20, 1), F7 = BEAM(1,0,3,0), F8 = BEAM(1,0,7,1)
REQUEST/2, F1 = VX(20, 1, 1, 1), F2 = VY(20, 1, 1, 1), F3 = VZ(20, 1, 1, 1)
, F4 = WX(20, 1, 1), F5 = WY(20, 1, 1), F6 = WZ(20, 1, 1)
END
",
        half.iter()
            .map(f64::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    );
    let py = 12.0 * e * izz * asy / (g * a * l * l);
    let mut k = Matrix6::zeros();
    k[(0, 0)] = e * a / l;
    k[(1, 1)] = 12.0 * e * izz / (l.powi(3) * (1.0 + py));
    k[(1, 5)] = -6.0 * e * izz / (l * l * (1.0 + py));
    k[(5, 1)] = k[(1, 5)];
    k[(2, 2)] = 12.0 * e * iyy / l.powi(3);
    k[(2, 4)] = 6.0 * e * iyy / (l * l);
    k[(4, 2)] = k[(2, 4)];
    k[(3, 3)] = g * ixx / l;
    k[(4, 4)] = 4.0 * e * iyy / l;
    k[(5, 5)] = (4.0 + py) * e * izz / (l * (1.0 + py));
    let mut c = Matrix6::zeros();
    let mut next = half.iter();
    for column in 0..6 {
        for row in column..6 {
            let value = *next.next().unwrap();
            c[(row, column)] = value;
            c[(column, row)] = value;
        }
    }
    let run = run(&text, &settings(1.0, 50, 1e-10)).expect("the beam swings");
    let mut worst: f64 = 0.0;
    for row in &run.rows {
        let x = Vector6::from_iterator(row[FIRST..FIRST + 6].iter().copied())
            - Vector6::new(l, 0.0, 0.0, 0.0, 0.0, 0.0);
        let v = Vector6::from_iterator(row[FIRST + 8..FIRST + 14].iter().copied());
        let pull = -k * x - c * v;
        // Fy along ground's (J's) y, Ty along J's y.
        worst = worst.max((row[FIRST + 6] - pull[1]).abs() / pull[1].abs().max(1e-3));
        worst = worst.max((row[FIRST + 7] - pull[4]).abs() / pull[4].abs().max(1e-3));
    }
    println!("beam damping: largest relative difference {worst:.2e}");
    assert!(worst < 1e-9, "{worst}");
}

/// A BEAM of Adams' LINEAR formulation (written or left out) runs; the
/// STRING and NONLINEAR formulations are refused as one error of their
/// kind, the beams named, not one error a beam (a drill string of 40
/// STRING beams gave 40 errors).
#[test]
fn beams_of_another_formulation_are_refused_as_one_error() {
    let model = beam_model(&[
        2e11, 8e10, 1e-4, 2e-9, 1e-9, 1e-9, 0.0, 0.0, 1.0, 0.0, -9.81, 0.0,
    ]);
    let with = |formulation: &str, count: usize| {
        let mut text = model.replace("CRATIO = 0.02", &format!("CRATIO = 0.02{formulation}"));
        for id in 2..=count {
            text = text.replace(
                "\nACCGRAV",
                &format!(
                    "\nBEAM/{id}, I = 20, J = 1, LENGTH = 1, IXX = 2e-9, IYY = 1e-9, IZZ = 1e-9, AREA = 1e-4\n, EMODULUS = 2e11, GMODULUS = 8e10{formulation}\nACCGRAV"
                ),
            );
        }
        match run(&text, &settings(0.1, 1, 1e-6)) {
            Ok(_) => "ran".to_string(),
            Err(errors) => errors.trim_end().to_string(),
        }
    };
    assert_eq!(with("", 1), "ran");
    assert_eq!(with(", FORMULATION = LINEAR", 2), "ran");
    assert_eq!(
        with(", FORMULATION = STRING", 3),
        "7:85: not simulated: BEAM/1 has FORMULATION = STRING: mbexpr has the LINEAR formulation of a BEAM (Timoshenko) only; so are BEAM/2, BEAM/3 (3 in all)"
    );
    assert_eq!(
        with(", FORMULATION = NONLIN", 1),
        "7:85: not simulated: BEAM/1 has FORMULATION = NONLIN: mbexpr has the LINEAR formulation of a BEAM (Timoshenko) only"
    );
}
