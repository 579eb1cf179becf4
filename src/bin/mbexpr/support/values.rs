//! Numbers on the command line: a `NAME=VALUE` assignment whose value is a
//! constant expression, and numbers shown as the library's messages show
//! them.

use mbexpr::{Shown, ShownBuffer};

use crate::Fatal;

/// `NAME=VALUE` to its parts, VALUE a constant expression of the language
/// (`30D`, `1D3`, `2*PI`), as `:set` takes it in the REPL.
pub fn parse_assignment(assignment: &str) -> Result<(String, f64), Fatal> {
    let (name, value) = assignment
        .split_once('=')
        .ok_or_else(|| Fatal::usage(format!("error: --set {assignment}: write NAME=VALUE")))?;
    let value = constant_value(value).map_err(|message| {
        Fatal::usage(format!(
            "error: --set {assignment}: {message} (a --set value is a constant expression)"
        ))
    })?;
    Ok((name.trim().to_string(), value))
}

/// The value of the constant expression `text`, or the first reason it has
/// none.
fn constant_value(text: &str) -> Result<f64, String> {
    let tree = mbexpr::parse(text).map_err(|error| error.to_string())?;
    let checked = mbexpr::check(&tree).map_err(|errors| errors[0].to_string())?;
    let program = mbexpr::compile::<&str>(&checked, &[]).map_err(|errors| errors[0].to_string())?;
    program.value(&[]).map_err(|error| error.to_string())
}

/// A number as text, as the library's messages show numbers
/// ([`mbexpr::Shown`]).
pub fn show(value: f64) -> String {
    Shown(value).to_string()
}

/// Appends [`show`]'s text of `value`, right-aligned in `width` bytes.
pub fn push_aligned(out: &mut Vec<u8>, value: f64, width: usize) {
    const BLANKS: [u8; 32] = [b' '; 32];
    let mut buffer = ShownBuffer::new();
    let pieces = Shown(value).pieces(&mut buffer);
    let length: usize = pieces.iter().map(|piece| piece.len()).sum();
    out.extend_from_slice(&BLANKS[..width.saturating_sub(length).min(BLANKS.len())]);
    for piece in pieces {
        out.extend_from_slice(piece.as_bytes());
    }
}
