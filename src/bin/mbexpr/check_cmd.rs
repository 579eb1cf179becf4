//! `mbexpr check FILE...`: every expression of every file, every problem.

use std::io::{self, Read, Write};

use clap::ValueEnum;

use mbexpr::model::{self, FileKind};

use crate::render::{diagnostic, line_diagnostics};
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

/// Checks a model file: every problem at its place, then a summary line.
/// Returns the number of expressions and of errors.
fn check_model_file(
    origin: &str,
    text: &str,
    kind: FileKind,
    format: Format,
    out: &mut impl Write,
) -> Result<(usize, usize), Fatal> {
    let dataset = model::read(text, kind);
    let report = model::check_model(text, &dataset);
    let statement_fields =
        |index: Option<usize>| match index.map(|index| &dataset.statements[index]) {
            Some(statement) => (
                serde_json::Value::String(statement.name.clone()),
                statement
                    .id
                    .map_or(serde_json::Value::Null, serde_json::Value::from),
            ),
            None => (serde_json::Value::Null, serde_json::Value::Null),
        };
    match format {
        Format::Text => {
            for problem in &report.problems {
                let message = problem.error.to_string();
                write!(
                    out,
                    "{}",
                    diagnostic(origin, text, problem.error.span(), &message)
                )?;
            }
            writeln!(
                out,
                "{origin}: {}, {}, {}",
                plural(dataset.statements.len(), "statement"),
                plural(report.expressions.len(), "expression"),
                plural(report.problems.len(), "error")
            )?;
        }
        Format::Jsonl => {
            for (index, found) in report.expressions.iter().enumerate() {
                let (statement, id) = statement_fields(Some(found.statement));
                let location = mbexpr::Location::of(text, found.span.start);
                let mut record = serde_json::json!({
                    "file": origin,
                    "line": location.line,
                    "statement": statement,
                    "id": id,
                    "keyword": found.keyword,
                    "ok": true,
                });
                if let Some(problem) = report
                    .problems
                    .iter()
                    .find(|problem| problem.expression == Some(index))
                {
                    let at = mbexpr::Location::of(text, problem.error.span().start);
                    record["ok"] = false.into();
                    record["line"] = at.line.into();
                    record["column"] = at.column.into();
                    record["error"] = problem.error.to_string().into();
                }
                writeln!(out, "{record}")?;
            }
            for problem in report
                .problems
                .iter()
                .filter(|problem| problem.expression.is_none())
            {
                let (statement, id) = statement_fields(problem.statement);
                let at = mbexpr::Location::of(text, problem.error.span().start);
                let record = serde_json::json!({
                    "file": origin,
                    "line": at.line,
                    "statement": statement,
                    "id": id,
                    "ok": false,
                    "column": at.column,
                    "error": problem.error.to_string(),
                });
                writeln!(out, "{record}")?;
            }
        }
    }
    Ok((report.expressions.len(), report.problems.len()))
}

/// `3 errors`, `1 error`.
fn plural(count: usize, word: &str) -> String {
    format!("{count} {word}{}", if count == 1 { "" } else { "s" })
}

pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let (mut expressions, mut errors) = (0usize, 0usize);
    let mut models = 0;
    for file in &args.files {
        let text = read(file)?;
        let origin = if file == "-" {
            "<stdin>"
        } else {
            file.as_str()
        };
        if let Some(kind) = FileKind::of_path(file) {
            let (found, problems) = check_model_file(origin, &text, kind, args.format, out)?;
            expressions += found;
            errors += problems;
            models += 1;
            continue;
        }
        for (index, raw_line) in text.split_inclusive('\n').enumerate() {
            let line = raw_line.trim_end_matches(['\n', '\r']);
            let trimmed = line.trim_start();
            if trimmed.is_empty() || trimmed.starts_with('!') {
                continue;
            }
            expressions += 1;
            let found = problems(mbexpr::syntax::without_comment(line));
            errors += found.len();
            match args.format {
                Format::Text => {
                    let problems = found
                        .into_iter()
                        .map(|problem| (problem.span, problem.message));
                    let rendered = line_diagnostics(origin, index + 1, line, problems);
                    write!(out, "{rendered}")?;
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
    // A single model file has its own summary line already.
    if args.format == Format::Text && !(models == 1 && args.files.len() == 1) {
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
