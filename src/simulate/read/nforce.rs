//! NFORCE, Adams' multi-point linear force: `N` I markers tied to one J
//! marker by a `6N × 6N` stiffness and damping.
//!
//! Documented (Adams Solver's NFORCE statement; MotionSolve's
//! Force_MultiPoint): `IMARKERS = id1, ..., idn` (or any abbreviation of
//! it, down to `I`) lists the markers (1 to 350,
//! the J marker not among them); `J` is the marker whose axes resolve
//! the displacements, the velocities (taken relative to J, in J's frame)
//! and the forces; `KMATRIX` names a `6N × 6N` MATRIX of stiffness, and
//! `CMATRIX` a `6N × 6N` MATRIX of damping or `CRATIO` the ratio that
//! multiplies the stiffness into it (neither: no damping); `LENGTH` names
//! the `6N × 1` MATRIX of the I markers' free positions, `FORCE` the
//! `6N × 1` MATRIX of the forces and torques at those positions (the
//! preloads); each marker's six entries in order x, y, z, then the three
//! rotations, the markers in I's order. The NFORCE function
//! `NFORCE(id, at_marker, comp, rm)` gives the force at one of its I
//! markers or at its J marker.
//!
//! Our reading, the FIELD's law written for `N` markers: on I marker `n`,
//! along J's axes,
//!
//! ```text
//! Fₙ = −Σₘ Kₙₘ (Xₘ − Lₘ) − Σₘ Cₙₘ Vₘ + F₀ₙ
//! ```
//!
//! with `Xₘ` the displacement of I marker `m` from J (`DX DY DZ (Iₘ,J,J)`,
//! then the small angles `AX AY AZ (Iₘ,J)`), `Vₘ` its rate (`VX VY VZ
//! (Iₘ,J,J,J)`, the derivative taken in J's frame, then `WX WY WZ
//! (Iₘ,J,J)`). The reaction of each I marker's force falls on J's part at
//! that marker's origin, as a FIELD's does, so that J takes `−Σ Fₙ` and
//! the moments `−Σ (Tₙ + (Iₙ − J) × Fₙ)` about its origin: the element
//! as a whole applies no net force or moment.

use nalgebra::DMatrix;

use super::linear::{Refusal, damping_ratio_unless_matrix, refusal};
use crate::check::Reference;
use crate::model::initial::number_list;
use crate::model::linear_systems::{find, read_matrix};
use crate::model::{Dataset, Statement};
use crate::scene::{Scene, Target};

/// The most I markers an NFORCE has (Adams' limit).
const MOST_MARKERS: usize = 350;

/// An NFORCE's markers and matrices.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Multipoint {
    /// The I markers' ids and places in the scene, in I's order.
    pub(super) i: Vec<(u64, Target)>,
    /// The J marker's id and place.
    pub(super) j: (u64, Target),
    /// `K`, `6N × 6N`.
    pub(super) stiffness: DMatrix<f64>,
    /// `C`, `6N × 6N`.
    pub(super) damping: DMatrix<f64>,
    /// `L`, the free positions, `6N` entries.
    pub(super) free: Vec<f64>,
    /// `F₀`, the preloads, `6N` entries.
    pub(super) preload: Vec<f64>,
}

/// The markers and matrices of NFORCE `statement`, or what is wrong with
/// them and where.
pub(super) fn multipoint(
    dataset: &Dataset,
    statement: &Statement,
    scene: &Scene,
) -> Result<Multipoint, Refusal> {
    let label = statement.label();
    // IMARKERS, as Adams writes it, may be abbreviated to I.
    let ids = |keyword: &str, what: &str| -> Result<(Vec<u64>, crate::span::Span), Refusal> {
        let argument = statement
            .argument(keyword, 1)
            .ok_or_else(|| (format!("{label}: needs {keyword} = {what}"), statement.span))?;
        let listed = number_list(statement, argument).map_err(refusal)?;
        let ids = listed
            .iter()
            .map(|id| {
                super::whole(*id)
                    .filter(|id| scene.find_marker(&Reference::Id(*id)).is_ok())
                    .ok_or_else(|| {
                        (
                            format!(
                                "{label}: {keyword} lists {}, which is not a MARKER of the model",
                                crate::shown::Shown(*id)
                            ),
                            argument.span,
                        )
                    })
            })
            .collect::<Result<Vec<u64>, Refusal>>()?;
        Ok((ids, argument.span))
    };
    let place = |id: u64| {
        scene
            .find_marker(&Reference::Id(id))
            .unwrap_or(Target::Ground)
    };
    let (i, i_span) = ids("IMARKERS", "the markers its forces act on (1 to 350)")?;
    if i.is_empty() || i.len() > MOST_MARKERS {
        return Err((
            format!(
                "{label}: IMARKERS lists {} markers, where an NFORCE has 1 to {MOST_MARKERS}",
                i.len()
            ),
            i_span,
        ));
    }
    if let Some((index, id)) = i
        .iter()
        .enumerate()
        .find(|(index, id)| i[..*index].contains(id))
    {
        return Err((
            format!(
                "{label}: IMARKERS lists MARKER/{id} twice (its entry {})",
                index + 1
            ),
            i_span,
        ));
    }
    let (j, j_span) = ids("J", "the marker of its axes, which takes the reaction")?;
    let [j] = j[..] else {
        return Err((format!("{label}: J is one marker"), j_span));
    };
    if i.contains(&j) {
        return Err((
            format!(
                "{label}: J = {j} is also among its I markers: J takes the reaction of the forces on the I markers, so give it apart"
            ),
            j_span,
        ));
    }
    let size = 6 * i.len();
    let matrix = |keyword: &str, columns: usize| -> Result<Option<DMatrix<f64>>, Refusal> {
        let Some(argument) = statement.argument(keyword, keyword.len()) else {
            return Ok(None);
        };
        let listed = number_list(statement, argument).map_err(refusal)?;
        let found = match listed[..] {
            [id] => {
                super::whole(id).and_then(|id| find(dataset, "MATRIX", id).map(|found| (id, found)))
            }
            _ => None,
        };
        let Some((id, found)) = found else {
            return Err((
                format!("{label}: {keyword} must name a MATRIX statement of the model"),
                argument.span,
            ));
        };
        let read = read_matrix(found).map_err(refusal)?;
        if (read.nrows(), read.ncols()) != (size, columns) {
            return Err((
                format!(
                    "{label}: {keyword} = {id} names a {} by {} MATRIX, where its I markers make it {size} by {columns} (six rows for each)",
                    read.nrows(),
                    read.ncols(),
                ),
                argument.span,
            ));
        }
        Ok(Some(read))
    };
    let Some(stiffness) = matrix("KMATRIX", size)? else {
        return Err((
            format!(
                "{label}: needs KMATRIX = the MATRIX of its stiffness, {size} by {size} (six rows and columns for each I marker)"
            ),
            statement.span,
        ));
    };
    let damping = match damping_ratio_unless_matrix(statement)? {
        Some(ratio) => &stiffness * ratio,
        None => matrix("CMATRIX", size)?.unwrap_or_else(|| DMatrix::zeros(size, size)),
    };
    let column = |keyword: &str| -> Result<Vec<f64>, Refusal> {
        Ok(matrix(keyword, 1)?.map_or_else(|| vec![0.0; size], |read| read.as_slice().to_vec()))
    };
    Ok(Multipoint {
        i: i.iter().map(|id| (*id, place(*id))).collect(),
        j: (j, place(j)),
        free: column("LENGTH")?,
        preload: column("FORCE")?,
        stiffness,
        damping,
    })
}
