//! From a checked expression, the values a user gave and a scene, to a
//! program and the values of its inputs: shared by `plot` and the REPL.

use std::collections::{HashMap, HashSet};

use mbexpr::{Checked, CompileError, Errors, Program, Scene};

/// A compiled program and the value of each of its inputs.
pub struct Bound {
    /// The program.
    pub program: Program,
    /// One value per input of the program.
    pub values: Vec<f64>,
}

/// Compiles `checked` with the names of `bindings`, `extra` names (derivative
/// directions, a plotted variable), `TIME` and what `scene` provides as
/// inputs. An input takes its value from the last binding of its name, else
/// from the scene, else 0: `TIME` is 0 unless given, as at the start of a
/// model's simulation.
pub fn bind(
    checked: &Checked,
    scene: Option<&Scene>,
    bindings: &[(String, f64)],
    extra: &[String],
) -> Result<Bound, Errors<CompileError>> {
    let mut names: Vec<String> = Vec::new();
    let mut seen = HashSet::new();
    let mut add = |name: &str| {
        if seen.insert(name.to_ascii_uppercase()) {
            names.push(name.to_string());
        }
    };
    bindings.iter().for_each(|(name, _)| add(name));
    extra.iter().for_each(|name| add(name));
    add("TIME");
    if let Some(scene) = scene {
        scene.input_names().iter().for_each(|name| add(name));
    }
    let program = match scene {
        Some(scene) => mbexpr::compile_in_scene(checked, &names, scene),
        None => mbexpr::compile(checked, &names),
    }?;
    // The last binding of each name wins.
    let bound: HashMap<String, f64> = bindings
        .iter()
        .map(|(name, value)| (name.to_ascii_uppercase(), *value))
        .collect();
    let values = program
        .inputs()
        .iter()
        .map(
            |name| match (bound.get(&name.to_ascii_uppercase()), scene) {
                (Some(value), _) => *value,
                (None, Some(scene)) => scene.value_of(name).unwrap_or(0.0),
                (None, None) => 0.0,
            },
        )
        .collect();
    Ok(Bound { program, values })
}

/// Every compile error rendered under the expression, an unbound variable
/// with a hint in the words of the caller (`--set x=VALUE`, `:set x = VALUE`).
pub fn render(
    errors: &Errors<CompileError>,
    origin: &str,
    source: &str,
    how_to_set: impl Fn(&str) -> String,
) -> String {
    let problems = errors
        .iter()
        .map(|error| (error.span(), message(error, &how_to_set)));
    super::render::diagnostics(origin, source, problems)
}

/// Why a requested gradient is empty: the expression reads no input at
/// all, or no derivative direction was named (`how_to_name` says how).
pub fn no_directions(program: &Program, how_to_name: &str) -> String {
    let used: Vec<&str> = program
        .used_inputs()
        .map(|index| program.inputs()[index].as_str())
        .collect();
    if used.is_empty() {
        "  (no derivatives: the expression has no inputs, so every derivative is 0)".to_string()
    } else {
        format!(
            "  (no derivatives: name the directions with {how_to_name}; the inputs are {})",
            used.join(", ")
        )
    }
}

/// The message of a compile error, an unbound variable with the hint
/// `how_to_set` gives.
pub fn message(error: &CompileError, how_to_set: impl Fn(&str) -> String) -> String {
    match error {
        CompileError::UnboundVariable { name, .. } => {
            format!("{error}: set it with {}", how_to_set(name))
        }
        _ => error.to_string(),
    }
}
