//! Rendering an error for a person: `FILE:LINE:COL: message`, the source
//! line, and a caret under the span.

use std::fmt::Write;

use mbexpr::{Location, Span};

/// `origin:line:col: message`, then the line of `text` holding `span` with
/// carets under it. `origin` may be empty (an expression from the command line).
pub fn diagnostic(origin: &str, text: &str, span: Span, message: &str) -> String {
    let start = Location::of(text, span.start);
    let mut out = String::new();
    if origin.is_empty() {
        let _ = writeln!(out, "error at {}:{}: {message}", start.line, start.column);
    } else {
        let _ = writeln!(out, "{origin}:{}:{}: {message}", start.line, start.column);
    }
    let line_start = text[..span.start.min(text.len())]
        .rfind('\n')
        .map_or(0, |newline| newline + 1);
    let line_end = text[line_start..]
        .find('\n')
        .map_or(text.len(), |newline| line_start + newline);
    let line = text[line_start..line_end].trim_end_matches('\r');
    let gutter = start.line.to_string();
    let pad = " ".repeat(gutter.len());
    let indent: String = line
        .chars()
        .take(start.column - 1)
        .map(|c| if c == '\t' { '\t' } else { ' ' })
        .collect();
    let end = span.end.min(line_start + line.len()).max(span.start);
    let width = text
        .get(span.start.min(text.len())..end.min(text.len()))
        .map_or(1, |covered| covered.chars().count())
        .max(1);
    let _ = writeln!(out, "{gutter} | {line}");
    let _ = writeln!(out, "{pad} | {indent}{}", "^".repeat(width));
    out
}
