//! Reading the files commands are given: any text file (standard input
//! for `-`) and scene files, their problems rendered at their places.

use std::io::{self, Read};

use mbexpr::{Scene, model};

use super::record::Problem;
use super::render::diagnostics;
use crate::Fatal;

/// The text of `file`, decoded (`-` is standard input; docs/encoding.md),
/// or why there is none: it cannot be read, or it is binary.
pub fn read(file: &str) -> Result<String, String> {
    let mut bytes = Vec::new();
    if file == "-" {
        io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|error| format!("cannot read standard input: {error}"))?;
    } else {
        bytes = std::fs::read(file).map_err(|error| format!("cannot read {file}: {error}"))?;
    }
    let (text, encoding) = model::decode_owned(bytes);
    if model::is_binary(&text) {
        let name = if file == "-" { "standard input" } else { file };
        return Err(format!(
            "{name}: not a text file (it holds NUL or other control bytes): give a model file or a file of expressions"
        ));
    }
    if encoding != "UTF-8" {
        eprintln!("note: {file} is not UTF-8: read as {encoding}");
    }
    Ok(text)
}

/// The scene of the file `path`, or every problem of it at its place.
pub fn read_scene(path: &str) -> Result<Scene, Fatal> {
    read_scene_file(path).map(|file| file.scene)
}

/// A scene and the file it was read from, whose text its messages quote.
pub struct SceneFile {
    /// The path, as given.
    pub path: String,
    /// The file's text.
    pub text: String,
    /// The scene.
    pub scene: Scene,
}

impl SceneFile {
    /// `problems` of the scene's named expression `name` (spans into its
    /// text), rendered at their places in the file.
    pub fn render(&self, name: &str, problems: &[Problem]) -> Option<String> {
        let start = self.scene.expression_start(name)?;
        let placed = problems.iter().filter_map(|problem| {
            problem
                .span
                .map(|span| (span.shifted(start), problem.message.clone()))
        });
        Some(diagnostics(&self.path, &self.text, placed))
    }
}

/// The scene file at `path` with its text, or every problem of it at its
/// place.
pub fn read_scene_file(path: &str) -> Result<SceneFile, Fatal> {
    let text = std::fs::read_to_string(path)
        .map_err(|error| Fatal::usage(format!("error: cannot read {path}: {error}")))?;
    match Scene::from_toml(&text) {
        Ok(scene) => Ok(SceneFile {
            path: path.to_string(),
            text,
            scene,
        }),
        Err(errors) => {
            let placed = errors
                .iter()
                .filter_map(|error| error.file_span().map(|span| (span, error.to_string())));
            let mut message = diagnostics(path, &text, placed);
            for error in errors.iter().filter(|error| error.file_span().is_none()) {
                message += &format!("error: {path}: {error}\n");
            }
            Err(Fatal::usage(message))
        }
    }
}
