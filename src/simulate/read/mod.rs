//! Readers: a [`Model`](super::Model) from a solver dataset (`.adm` with the END and
//! STEPS of an `.acf` beside it) or from a scene file, every problem
//! reported at its place. The command line and the embedding layer both
//! read models here.

mod commands;
mod contacts;
mod couplers;
mod dataset;
mod exact;
mod joints;
mod linear;
mod motions;
mod scene;
mod sensors;
mod units;

pub use commands::{RunCommands, run_settings};
pub use dataset::from_dataset;
pub use scene::from_scene;

use std::path::Path;

use super::error::SimulateError;
use crate::model::{self, FileKind, Problem};

/// What a model's text is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelFormat {
    /// A solver dataset (`.adm`).
    Dataset,
    /// A scene file (TOML).
    Scene,
}

/// Why a model's text gives no model to simulate.
#[derive(Clone, Debug)]
pub enum Unread {
    /// The dataset does not check: every problem, in file order.
    Unchecked(Vec<Problem>),
    /// The model is refused: every reason, at its place in the text.
    Refused(Vec<SimulateError>),
}

/// Whether `path` names a scene file (`.toml`).
pub fn is_scene_path(path: &str) -> bool {
    path.to_ascii_lowercase().ends_with(".toml")
}

/// How the file at `path` is read: as `format` when given, else a scene
/// file for `.toml` and a solver dataset otherwise; a dataset is read as
/// a command file for `.acf`. An Adams View command file is refused with
/// what to give instead.
pub fn format_of_path(
    path: &str,
    format: Option<ModelFormat>,
) -> Result<(ModelFormat, FileKind), String> {
    let format = format.unwrap_or(if is_scene_path(path) {
        ModelFormat::Scene
    } else {
        ModelFormat::Dataset
    });
    if format == ModelFormat::Scene {
        return Ok((format, FileKind::Adm));
    }
    match FileKind::of_path(path) {
        Some(FileKind::Acf) => Ok((format, FileKind::Acf)),
        Some(FileKind::Cmd) => Err(format!(
            "{path}: an Adams View command file is not simulated: give a solver dataset (.adm) or a scene file (.toml)"
        )),
        _ => Ok((format, FileKind::Adm)),
    }
}

/// The run of the `.acf` beside the dataset at `path` ([`run_settings`]);
/// none for an `.acf` itself, for standard input (`-`) or when there is no
/// such file.
pub fn run_settings_beside(path: &str) -> Result<Option<RunCommands>, String> {
    let commands = Path::new(path).with_extension("acf");
    if path == "-" || FileKind::of_path(path) == Some(FileKind::Acf) || !commands.exists() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&commands)
        .map_err(|error| format!("cannot read {}: {error}", commands.display()))?;
    let dataset = model::read(&text, FileKind::Acf);
    run_settings(&dataset).map_err(|(message, span)| {
        let at = crate::Location::of(&text, span.start);
        format!("{}:{at}: {message}", commands.display())
    })
}
