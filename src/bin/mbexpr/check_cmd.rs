//! `mbexpr check FILE...`: every expression of every file, every problem.

use std::io::{self, Read, Write};

use clap::ValueEnum;

use crate::render::diagnostic;
use crate::{Fatal, Outcome};

/// Output formats of `check`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Each error as `FILE:LINE:COL: message` with the line and a caret, then a summary.
    Text,
    /// One JSON object per expression line.
    Jsonl,
}

#[derive(clap::Args)]
pub struct Args {
    /// Files with one expression per line; `-` reads standard input.
    #[arg(required = true)]
    files: Vec<String>,
    /// Output format.
    #[arg(long, value_enum, default_value = "text")]
    format: Format,
}

/// A problem in one expression: its span within the line and the message.
struct Problem {
    span: mbexpr::Span,
    message: String,
}

/// Parses and checks one expression, returning its problems in source order.
fn problems(expression: &str) -> Vec<Problem> {
    match mbexpr::parse(expression) {
        Err(error) => vec![Problem {
            span: error.span(),
            message: error.to_string(),
        }],
        Ok(tree) => match mbexpr::check(&tree) {
            Ok(_) => Vec::new(),
            Err(errors) => errors
                .into_iter()
                .map(|error| Problem {
                    span: error.span(),
                    message: error.to_string(),
                })
                .collect(),
        },
    }
}

fn read(file: &str) -> Result<String, Fatal> {
    if file == "-" {
        let mut text = String::new();
        io::stdin()
            .read_to_string(&mut text)
            .map_err(|error| Fatal::usage(format!("error: cannot read standard input: {error}")))?;
        return Ok(text);
    }
    std::fs::read_to_string(file)
        .map_err(|error| Fatal::usage(format!("error: cannot read {file}: {error}")))
}

pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let (mut expressions, mut errors) = (0usize, 0usize);
    for file in &args.files {
        let text = read(file)?;
        let origin = if file == "-" {
            "<stdin>"
        } else {
            file.as_str()
        };
        let mut offset = 0;
        for (index, raw_line) in text.split_inclusive('\n').enumerate() {
            let line_start = offset;
            offset += raw_line.len();
            let line = raw_line.trim_end_matches(['\n', '\r']);
            let trimmed = line.trim_start();
            if trimmed.is_empty() || trimmed.starts_with('!') {
                continue;
            }
            expressions += 1;
            let found = problems(line);
            errors += found.len();
            match args.format {
                Format::Text => {
                    for problem in &found {
                        let span = problem.span.shifted(line_start);
                        write!(out, "{}", diagnostic(origin, &text, span, &problem.message))?;
                    }
                }
                Format::Jsonl => {
                    let record = match found.first() {
                        None => serde_json::json!({"file": origin, "line": index + 1, "ok": true}),
                        Some(problem) => serde_json::json!({
                            "file": origin,
                            "line": index + 1,
                            "ok": false,
                            "column": mbexpr::Location::of(line, problem.span.start).column,
                            "error": problem.message,
                        }),
                    };
                    writeln!(out, "{record}")?;
                }
            }
        }
    }
    if args.format == Format::Text {
        let plural = |count: usize, word: &str| {
            format!("{count} {word}{}", if count == 1 { "" } else { "s" })
        };
        writeln!(
            out,
            "{}, {}",
            plural(expressions, "expression"),
            plural(errors, "error")
        )?;
    }
    Ok(if errors == 0 {
        Outcome::Success
    } else {
        Outcome::Failure
    })
}
