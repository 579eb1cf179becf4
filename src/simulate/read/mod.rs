//! Readers: a [`Model`](super::Model) from a solver dataset (`.adm` with the END and
//! STEPS of an `.acf` beside it) or from a scene file, every problem
//! reported at its place. The command line and the embedding layer both
//! read models here.

mod commands;
mod contacts;
mod couplers;
mod curves;
mod dataset;
mod exact;
mod frictions;
mod joints;
mod linear;
mod motions;
mod nforce;
mod scene;
mod sensors;
mod units;
mod view;

pub use commands::{MOST_OUTPUT_STEPS, RunCommands, run_settings};
pub use dataset::from_dataset;
pub use scene::from_scene;
pub(crate) use view::solver_dataset;

use std::path::Path;

use super::error::SimulateError;
use crate::model::{self, FileKind, Problem};
use crate::span::Span;

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
/// a command file for `.acf`, and as an Adams View command file for `.cmd`.
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
        Some(FileKind::Cmd) => Ok((format, FileKind::Cmd)),
        _ => Ok((format, FileKind::Adm)),
    }
}

/// Why the `.acf` beside a dataset gives no run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CommandFileError {
    /// The file cannot be read.
    #[error("cannot read {path}: {message}")]
    Unreadable {
        /// The command file's path.
        path: String,
        /// What the system said.
        message: String,
    },
    /// The file does not check, or asks for a run mbexpr does not make.
    #[error("{}", located(path, text, problems))]
    Refused {
        /// The command file's path.
        path: String,
        /// Its text.
        text: String,
        /// Each problem, at its place in the text.
        problems: Vec<(Span, String)>,
    },
}

/// The marker `keyword = id` names in `statement` (a whole positive id of
/// a MARKER of `scene`), the one lookup the dataset's readers share.
fn named_marker(
    statement: &model::Statement,
    keyword: &str,
    scene: &crate::scene::Scene,
) -> Option<crate::scene::Target> {
    whole_id(statement, keyword)
        .and_then(|id| scene.find_marker(&crate::check::Reference::Id(id)).ok())
}

/// The marker `statement`'s `keyword` names; where it names none,
/// `None`, and the statement's label and `message` added to `errors` at
/// the keyword.
fn needed_marker(
    statement: &model::Statement,
    keyword: &str,
    scene: &crate::scene::Scene,
    errors: &mut Vec<crate::simulate::SimulateError>,
    message: &str,
) -> Option<crate::scene::Target> {
    let found = named_marker(statement, keyword, scene);
    if found.is_none() {
        errors.push(crate::simulate::SimulateError::Model {
            message: format!("{}: {message}", statement.label()),
            span: statement.place_of(keyword, keyword.len()),
        });
    }
    found
}

/// The word an argument is set to (`TYPE = SOLID_TO_SOLID`), upper case;
/// `None` when its value is not one word (a list, an expression): the one
/// reading of a keyword's word the dataset's readers share.
fn word_of(argument: &model::Argument) -> Option<String> {
    match &argument.value {
        model::Value::List(items) if items.len() == 1 => {
            Some(items[0].text.trim().to_ascii_uppercase())
        }
        _ => None,
    }
}

/// The id `keyword = id` gives in `statement`: a whole positive number
/// (`None` for anything else, `4.7` too).
fn whole_id(statement: &model::Statement, keyword: &str) -> Option<u64> {
    whole(model::initial::number(statement, keyword, f64::NAN).ok()?)
}

/// `value` as an id: a whole number from 1 to the largest id.
fn whole(value: f64) -> Option<u64> {
    (value.fract() == 0.0 && value > 0.0 && value <= model::LARGEST_ID as f64)
        .then_some(value as u64)
}

/// `path:line:column: message`, a line each.
fn located(path: &str, text: &str, problems: &[(Span, String)]) -> String {
    problems
        .iter()
        .map(|(span, message)| {
            let at = crate::Location::of(text, span.start);
            format!("{path}:{at}: {message}")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The run of the `.acf` beside the dataset at `path` ([`run_settings`]);
/// none for an `.acf` itself, for standard input (`-`) or when there is no
/// such file. A command file that does not check (a command the solver
/// does not know) is refused with its problems, as `mbexpr check` finds
/// them.
pub fn run_settings_beside(path: &str) -> Result<Option<RunCommands>, CommandFileError> {
    let commands = Path::new(path).with_extension("acf");
    if path == "-" || FileKind::of_path(path) == Some(FileKind::Acf) || !commands.exists() {
        return Ok(None);
    }
    let shown = commands.display().to_string();
    let bytes = std::fs::read(&commands).map_err(|error| CommandFileError::Unreadable {
        path: shown.clone(),
        message: error.to_string(),
    })?;
    // Command files are read as datasets are: bytes that are not UTF-8
    // as Windows-1252.
    let (text, _) = model::decode_owned(bytes);
    let refused = |problems: Vec<(Span, String)>| CommandFileError::Refused {
        path: shown.clone(),
        text: text.clone(),
        problems,
    };
    let dataset = model::read(&text, FileKind::Acf);
    let report = model::check_model(&text, &dataset);
    if !report.problems.is_empty() {
        return Err(refused(
            report
                .problems
                .iter()
                .map(|problem| (problem.error.span(), problem.error.to_string()))
                .collect(),
        ));
    }
    run_settings(&dataset).map_err(|(message, span)| refused(vec![(span, message)]))
}
