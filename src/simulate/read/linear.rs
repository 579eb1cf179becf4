//! The six-component linear force elements between two markers —
//! BUSHING, BEAM and FIELD — as the matrices of their Adams definitions:
//! on the I marker, along the J marker's axes,
//!
//! ```text
//! F = −K (X − L) − C V + F₀
//! ```
//!
//! with `X` the displacement of I from J (`DX DY DZ (I,J,J)`, then the
//! angles `AX AY AZ (I,J)`), `V` its rate (`VX VY VZ (I,J,J,J)`, then
//! `WX WY WZ (I,J,J)`), `L` the free position and `F₀` the preload (three
//! forces, then three torques). The reader writes each component out as an
//! expression; the reaction on J is the element's opposite at I's origin
//! (Adams' torque on J with the moment arm of the deformation).

use crate::model::initial::{number, numbers};
use crate::model::{Statement, Value};
use crate::span::Span;

/// A 6 × 6 matrix, row by row.
pub(super) type Matrix6 = [[f64; 6]; 6];

/// The matrices of one linear element.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Linear {
    /// `K`: force per displacement, torque per radian.
    pub(super) stiffness: Matrix6,
    /// `C`: force per velocity, torque per radian per time.
    pub(super) damping: Matrix6,
    /// `L`: the displacement at which the element applies its preload.
    pub(super) free: [f64; 6],
    /// `F₀`: three forces along J's axes, then three torques about them.
    pub(super) preload: [f64; 6],
}

/// Why an element's numbers give no matrices: the message and its place.
pub(super) type Refusal = (String, Span);

pub(super) fn refusal(error: crate::model::initial::ConfigurationError) -> Refusal {
    (error.to_string(), error.span())
}

fn diagonal(values: [f64; 3], rotations: [f64; 3]) -> Matrix6 {
    let mut matrix = [[0.0; 6]; 6];
    for axis in 0..3 {
        matrix[axis][axis] = values[axis];
        matrix[axis + 3][axis + 3] = rotations[axis];
    }
    matrix
}

/// `CRATIO`, 0 when it is left out. The dataset grammar reads it as an
/// expression (other statements give it one); here it is a number, at
/// least 0 (a negative ratio pumps energy into the parts).
fn damping_ratio(statement: &Statement) -> Result<f64, Refusal> {
    let Some(argument) = statement.argument("CRATIO", 2) else {
        return Ok(0.0);
    };
    let value = match &argument.value {
        Value::Expression { text, .. } => text.text.trim().parse::<f64>().ok(),
        _ => number(statement, "CRATIO", 0.0).ok(),
    };
    value
        .filter(|ratio| ratio.is_finite() && *ratio >= 0.0)
        .ok_or_else(|| {
            (
                format!(
                    "{}: CRATIO is a number at least 0 here (the damping matrix is CRATIO times the stiffness)",
                    statement.label()
                ),
                argument.span,
            )
        })
}

/// How an element's damping is given: `None` where its `CMATRIX` gives
/// it, else the `CRATIO` that multiplies its stiffness (0, no damping,
/// when neither is given); both given is an error.
pub(super) fn damping_ratio_unless_matrix(statement: &Statement) -> Result<Option<f64>, Refusal> {
    let ratio = damping_ratio(statement)?;
    match statement.argument("CMATRIX", 2) {
        Some(argument) if ratio != 0.0 => Err((
            format!("{}: give CMATRIX or CRATIO, not both", statement.label()),
            argument.span,
        )),
        Some(_) => Ok(None),
        None => Ok(Some(ratio)),
    }
}

/// The damping of an element: its `CMATRIX` as `written` reads it, or
/// `CRATIO` times its `stiffness` (no damping when neither is given).
fn damping(
    statement: &Statement,
    stiffness: &Matrix6,
    written: impl FnOnce() -> Result<Matrix6, Refusal>,
) -> Result<Matrix6, Refusal> {
    match damping_ratio_unless_matrix(statement)? {
        None => written(),
        Some(ratio) => Ok(stiffness.map(|row| row.map(|entry| entry * ratio))),
    }
}

/// A BUSHING's `K, C, FORCE` and `KT, CT, TORQUE`: diagonal matrices, no
/// free position.
pub(super) fn bushing(statement: &Statement) -> Result<Linear, Refusal> {
    let values = |keyword: &str| numbers(statement, keyword, [0.0; 3]).map_err(refusal);
    let [k, c, force, kt, ct, torque] = ["K", "C", "FORCE", "KT", "CT", "TORQUE"].map(values);
    let (k, c, force, kt, ct, torque) = (k?, c?, force?, kt?, ct?, torque?);
    // Adams' range: stiffness and damping at least 0 (a negative one drives
    // the parts apart, or pumps energy into them).
    for (keyword, coefficients) in [("K", k), ("C", c), ("KT", kt), ("CT", ct)] {
        if let Some(negative) = coefficients.iter().find(|value| **value < 0.0)
            && let Some(argument) = statement.argument(keyword, keyword.len())
        {
            return Err((
                format!(
                    "{}: {keyword} must be at least 0 (each of its three), not {}",
                    statement.label(),
                    crate::shown::Shown(*negative)
                ),
                argument.span,
            ));
        }
    }
    Ok(Linear {
        stiffness: diagonal(k, kt),
        damping: diagonal(c, ct),
        free: [0.0; 6],
        preload: [
            force[0], force[1], force[2], torque[0], torque[1], torque[2],
        ],
    })
}

/// A FIELD's `KMATRIX` and `CMATRIX` (36 numbers each, column by column),
/// or `CRATIO` times the stiffness, `LENGTH` (the free position: three
/// lengths, three angles) and `FORCE` (the preload).
pub(super) fn field(statement: &Statement) -> Result<Linear, Refusal> {
    let columns = |keyword: &str| {
        numbers(statement, keyword, [0.0; 36])
            .map(|values| {
                std::array::from_fn(|row| std::array::from_fn(|column| values[6 * column + row]))
            })
            .map_err(refusal)
    };
    let stiffness: Matrix6 = columns("KMATRIX")?;
    let damping = damping(statement, &stiffness, || columns("CMATRIX"))?;
    Ok(Linear {
        stiffness,
        damping,
        free: numbers(statement, "LENGTH", [0.0; 6]).map_err(refusal)?,
        preload: numbers(statement, "FORCE", [0.0; 6]).map_err(refusal)?,
    })
}

/// The place and reason of a `BEAM`'s FORMULATION other than LINEAR
/// (STRING, NONLINEAR), which mbexpr does not simulate.
pub(super) fn nonlinear_beam(statement: &Statement) -> Option<(Span, String)> {
    let argument = statement.argument("FORMULATION", 3)?;
    let word = super::word_of(argument).unwrap_or_default();
    if word.len() >= 3 && "LINEAR".starts_with(word.as_str()) {
        return None;
    }
    Some((
        argument.span,
        format!(
            "has FORMULATION = {word}: mbexpr has the LINEAR formulation of a BEAM (Timoshenko) only"
        ),
    ))
}

/// A BEAM's Timoshenko stiffness (Adams' linear formulation): the beam
/// along J's x axis from J to I, `LENGTH` long, of cross section `AREA`
/// with the area moments `IYY`, `IZZ`, the torsional constant `IXX`, the
/// shear area ratios `ASY`, `ASZ` (0: no shear deflection), the moduli
/// `EMODULUS` and `GMODULUS`; damping `CRATIO` times the stiffness, or the
/// 21 numbers of `CMATRIX` (the lower half, column by column).
/// Its FORMULATION must be LINEAR (or left out): see `nonlinear_beam`.
pub(super) fn beam(statement: &Statement) -> Result<Linear, Refusal> {
    let positive = |keyword: &str, what: &str| -> Result<f64, Refusal> {
        let value = number(statement, keyword, f64::NAN).map_err(refusal)?;
        if value > 0.0 && value.is_finite() {
            return Ok(value);
        }
        let span = statement.place_of(keyword, keyword.len().min(2));
        Err((
            format!(
                "{}: give {keyword} = {what}, a positive number",
                statement.label()
            ),
            span,
        ))
    };
    let length = positive("LENGTH", "the beam's free length")?;
    let area = positive("AREA", "the cross section's area")?;
    let ixx = positive("IXX", "the torsional constant")?;
    let iyy = positive("IYY", "the area moment about y")?;
    let izz = positive("IZZ", "the area moment about z")?;
    let young = positive("EMODULUS", "Young's modulus")?;
    let shear = positive("GMODULUS", "the shear modulus")?;
    let asy = number(statement, "ASY", 0.0).map_err(refusal)?;
    let asz = number(statement, "ASZ", 0.0).map_err(refusal)?;
    // The shear deflection's share in each bending plane.
    let py = 12.0 * young * izz * asy / (shear * area * length * length);
    let pz = 12.0 * young * iyy * asz / (shear * area * length * length);
    let mut k = [[0.0; 6]; 6];
    k[0][0] = young * area / length;
    k[1][1] = 12.0 * young * izz / (length.powi(3) * (1.0 + py));
    k[1][5] = -6.0 * young * izz / (length.powi(2) * (1.0 + py));
    k[5][1] = k[1][5];
    k[2][2] = 12.0 * young * iyy / (length.powi(3) * (1.0 + pz));
    k[2][4] = 6.0 * young * iyy / (length.powi(2) * (1.0 + pz));
    k[4][2] = k[2][4];
    k[3][3] = shear * ixx / length;
    k[4][4] = (4.0 + pz) * young * iyy / (length * (1.0 + pz));
    k[5][5] = (4.0 + py) * young * izz / (length * (1.0 + py));
    let damping = damping(statement, &k, || {
        let half = numbers(statement, "CMATRIX", [0.0; 21]).map_err(refusal)?;
        let mut matrix = [[0.0; 6]; 6];
        let lower = (0..6).flat_map(|column| (column..6).map(move |row| (row, column)));
        for ((row, column), value) in lower.zip(half) {
            matrix[row][column] = value;
            matrix[column][row] = value;
        }
        Ok(matrix)
    })?;
    Ok(Linear {
        stiffness: k,
        damping,
        free: [length, 0.0, 0.0, 0.0, 0.0, 0.0],
        preload: [0.0; 6],
    })
}
