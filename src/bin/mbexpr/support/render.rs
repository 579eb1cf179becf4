//! Rendering errors for a person: `FILE:LINE:COL: message`, the source line
//! (a window of it around the place when the line is long) and a caret under
//! the span.
//!
//! Rendering is linear in the text and the number of errors: places are
//! located by one pass in source order, a message found at many places is
//! shown once, at its first place, with the count, and no more of a line
//! than the window is ever copied.

use std::collections::HashMap;
use std::fmt::Write;

use mbexpr::Span;

/// Characters of a long line shown before the place an error points at.
const BEFORE: usize = 40;
/// Characters of a line shown in all, from the window's start.
const WIDTH: usize = 100;

/// One error: `origin:line:col: message`, then the line of `text` holding
/// `span` with carets under it. `origin` may be empty (an expression from
/// the command line).
pub fn diagnostic(origin: &str, text: &str, span: Span, message: &str) -> String {
    diagnostics(origin, text, [(span, message.to_string())])
}

/// Every error of `problems` (spans into `text`), as [`diagnostic`] renders
/// one, in source order; a message found at several places is shown at the
/// first with `(N places; the first at LINE:COL)`.
pub fn diagnostics(
    origin: &str,
    text: &str,
    problems: impl IntoIterator<Item = (Span, String)>,
) -> String {
    line_diagnostics(origin, 1, text, problems)
}

/// [`diagnostics`] for `text` that starts on line `first_line` of its file
/// (one line of a file of expressions).
pub fn line_diagnostics(
    origin: &str,
    first_line: usize,
    text: &str,
    problems: impl IntoIterator<Item = (Span, String)>,
) -> String {
    let mut problems: Vec<(Span, String)> = problems.into_iter().collect();
    problems.sort_by_key(|(span, _)| span.start);
    // Each message once, at its first place, with how many places have it.
    let mut first_of: HashMap<&str, usize> = HashMap::new();
    let mut groups: Vec<(Span, &str, usize)> = Vec::new();
    for (span, message) in &problems {
        match first_of.get(message.as_str()) {
            Some(&group) => groups[group].2 += 1,
            None => {
                first_of.insert(message, groups.len());
                groups.push((*span, message, 1));
            }
        }
    }
    let mut cursor = Cursor {
        text,
        offset: 0,
        line: first_line,
        column: 1,
    };
    let mut out = String::new();
    for (span, message, count) in groups {
        let start = cursor.advance_to(span.start);
        let place = format!("{}:{}", cursor.line, cursor.column);
        let header = if origin.is_empty() {
            format!("error at {place}")
        } else {
            format!("{origin}:{place}")
        };
        let _ = write!(out, "{header}: {message}");
        if count > 1 {
            let _ = write!(out, " ({count} places; the first at {place})");
        }
        out.push('\n');
        let end = span.end.clamp(start, text.len());
        out.push_str(&excerpt(text, start, end, cursor.line));
    }
    out
}

/// A place in the text, moved forward only: locating errors in source
/// order costs one pass over the text.
struct Cursor<'a> {
    text: &'a str,
    offset: usize,
    line: usize,
    /// In characters, from 1.
    column: usize,
}

impl Cursor<'_> {
    /// Moves to `offset` (clamped to the text and a character boundary) and
    /// returns it.
    fn advance_to(&mut self, offset: usize) -> usize {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let offset = offset.max(self.offset);
        for c in self.text[self.offset..offset].chars() {
            if c == '\n' {
                self.line += 1;
                self.column = 1;
            } else {
                self.column += 1;
            }
        }
        self.offset = offset;
        offset
    }
}

/// The line holding byte `start` (a window of it, marked with `…` where it
/// is cut, when it is longer than [`WIDTH`]) and a caret line under
/// `start..end`, with a gutter for `line`. Only the window is read.
fn excerpt(text: &str, start: usize, end: usize, line: usize) -> String {
    let mut before: Vec<char> = text[..start]
        .chars()
        .rev()
        .take_while(|&c| c != '\n')
        .take(WIDTH + 1)
        .collect();
    before.reverse();
    let mut after: Vec<char> = text[start..]
        .chars()
        .take_while(|&c| c != '\n')
        .take(WIDTH + 1)
        .collect();
    while after.last() == Some(&'\r') {
        after.pop();
    }
    let (mut lead, mut tail) = ("", "");
    if before.len() + after.len() > WIDTH {
        // At least BEFORE characters of context before the place, more
        // when the line ends soon after it.
        let keep = before
            .len()
            .min(BEFORE.max(WIDTH.saturating_sub(after.len())));
        if keep < before.len() {
            before.drain(..before.len() - keep);
            lead = "…";
        }
        if after.len() > WIDTH - keep {
            after.truncate(WIDTH - keep);
            tail = "…";
        }
    }
    let covered = text[start..end]
        .chars()
        .take_while(|&c| c != '\n')
        .take(after.len())
        .count()
        .max(1);
    let indent: String = lead
        .chars()
        .chain(before.iter().copied())
        .map(|c| if c == '\t' { '\t' } else { ' ' })
        .collect();
    let before: String = before.into_iter().collect();
    let after: String = after.into_iter().collect();
    let gutter = line.to_string();
    let pad = " ".repeat(gutter.len());
    format!(
        "{gutter} | {lead}{before}{after}{tail}\n{pad} | {indent}{}\n",
        "^".repeat(covered)
    )
}
