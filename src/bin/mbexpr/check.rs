//! `mbexpr check FILE...`: every expression of every file, every problem.

use std::collections::HashSet;
use std::io::Write;

use clap::ValueEnum;
use serde_json::{Value, json};

use mbexpr::model::{self, FileKind};
use mbexpr::{CompileError, Counted, LineIndex, Span};

use crate::support::files::read;
use crate::support::render::{diagnostics, line_diagnostics};
use crate::{Fatal, Outcome};

/// Output formats of `check`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Each error as `FILE:LINE:COL: message` with the line and a caret, then a summary.
    Text,
    /// One JSON object per expression (with all its errors), and one per
    /// problem outside an expression.
    Jsonl,
}

/// What a file holds, when its extension and first lines do not say it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Kind {
    /// A solver dataset: a title line, then statements.
    Adm,
    /// A solver command file.
    Acf,
    /// An Adams View command file.
    Cmd,
    /// Expressions, one a line.
    Expressions,
}

#[derive(clap::Args)]
pub struct Args {
    /// Files of expressions, one a line (`!` starts a comment line), or model
    /// files (.adm, .acf, .cmd, or a dataset known by its first lines); `-`
    /// reads standard input.
    #[arg(required = true)]
    files: Vec<String>,
    /// Output format.
    #[arg(long, value_enum, default_value = "text")]
    format: Format,
    /// What every file holds, whatever its name and first lines say.
    #[arg(long, value_enum)]
    kind: Option<Kind>,
    /// The names an expression file's expressions may use (TIME and MODE
    /// always): any other name is an error, with the close names. Without
    /// it, the names are listed in a note.
    #[arg(long, value_name = "NAME,NAME", value_delimiter = ',')]
    names: Option<Vec<String>>,
}

/// The names the expressions of expression files use with no value, each
/// once (case-insensitively), in order of first use.
#[derive(Default)]
struct Unbound {
    names: Vec<String>,
    seen: HashSet<String>,
}

/// A problem in one expression: its span within the file and the message.
struct Problem {
    span: Span,
    message: String,
}

/// Parses and checks one expression, returning its problems in source
/// order; with `names`, a name outside them is a problem too. Names used
/// and not bound are added to `unbound`.
fn problems(expression: &str, names: Option<&[String]>, unbound: &mut Unbound) -> Vec<Problem> {
    let tree = match mbexpr::parse(expression) {
        Err(error) => {
            return vec![Problem {
                span: error.span(),
                message: error.to_string(),
            }];
        }
        Ok(tree) => tree,
    };
    let (checked, errors) = mbexpr::check::check_partial(&tree);
    let mut found: Vec<Problem> = errors
        .iter()
        .map(|error| Problem {
            span: error.span(),
            message: error.to_string(),
        })
        .collect();
    match names {
        Some(names) => {
            let mut inputs = names.to_vec();
            inputs.push("TIME".to_string());
            if let Err(errors) = mbexpr::compile(&checked, &inputs) {
                found.extend(
                    errors
                        .iter()
                        .filter(|error| matches!(error, CompileError::UnboundVariable { .. }))
                        .map(|error| Problem {
                            span: error.span(),
                            message: error.to_string(),
                        }),
                );
                found.sort_by_key(|problem| problem.span.start);
            }
        }
        None => {
            for name in checked.variables() {
                if unbound.seen.insert(name.to_ascii_uppercase()) {
                    unbound.names.push(name.to_string());
                }
            }
        }
    }
    found
}

/// `{"line", "column", "message"}` of a problem at `span`.
fn error_json(lines: &LineIndex<'_>, span: Span, message: String) -> Value {
    let at = lines.location(span.start);
    json!({"line": at.line, "column": at.column, "message": message})
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
    let mut report = model::check_model(text, &dataset);
    // A command file's run as `mbexpr simulate` reads it.
    if kind == FileKind::Acf
        && report.problems.is_empty()
        && let Err((message, span)) = mbexpr::simulate::run_settings(&dataset)
    {
        report.problems.push(model::Problem {
            error: model::ModelError::Run { message, span },
            statement: None,
            expression: None,
        });
    }
    let lines = LineIndex::new(text);
    let statement_fields =
        |index: Option<usize>| match index.map(|index| &dataset.statements[index]) {
            Some(statement) => (
                Value::String(statement.name.to_string()),
                statement.id.map_or(Value::Null, Value::from),
            ),
            None => (Value::Null, Value::Null),
        };
    match format {
        Format::Text => {
            let problems = report
                .problems
                .iter()
                .map(|problem| (problem.error.span(), problem.error.to_string()));
            write!(out, "{}", diagnostics(origin, text, problems))?;
            writeln!(
                out,
                "{origin}: {}, {}, {}",
                Counted(dataset.statements.len(), "statement"),
                Counted(report.expressions.len(), "expression"),
                Counted(report.problems.len(), "error")
            )?;
        }
        Format::Jsonl => {
            let mut errors: Vec<Vec<Value>> = vec![Vec::new(); report.expressions.len()];
            for problem in &report.problems {
                if let Some(index) = problem.expression {
                    let span = problem.error.span();
                    errors[index].push(error_json(&lines, span, problem.error.to_string()));
                }
            }
            for (found, errors) in report.expressions.iter().zip(errors) {
                let (statement, id) = statement_fields(Some(found.statement));
                let record = json!({
                    "file": origin,
                    "line": lines.location(found.span.start).line,
                    "statement": statement,
                    "id": id,
                    "keyword": found.keyword.as_str(),
                    "ok": errors.is_empty(),
                    "errors": errors,
                });
                writeln!(out, "{record}")?;
            }
            for problem in report
                .problems
                .iter()
                .filter(|problem| problem.expression.is_none())
            {
                let (statement, id) = statement_fields(problem.statement);
                let span = problem.error.span();
                let record = json!({
                    "file": origin,
                    "line": lines.location(span.start).line,
                    "statement": statement,
                    "id": id,
                    "ok": false,
                    "errors": [error_json(&lines, span, problem.error.to_string())],
                });
                writeln!(out, "{record}")?;
            }
        }
    }
    Ok((report.expressions.len(), report.problems.len()))
}

/// Checks a file of expressions, one a line. Returns the number of
/// expressions and of errors.
fn check_expression_file(
    args: &Args,
    origin: &str,
    text: &str,
    unbound: &mut Unbound,
    out: &mut impl Write,
) -> Result<(usize, usize), Fatal> {
    let lines = LineIndex::new(text);
    let (mut expressions, mut errors) = (0, 0);
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
        let expression = mbexpr::syntax::without_comment(line);
        let found = problems(expression, args.names.as_deref(), unbound);
        errors += found.len();
        match args.format {
            Format::Text => {
                let problems = found
                    .into_iter()
                    .map(|problem| (problem.span, problem.message));
                write!(
                    out,
                    "{}",
                    line_diagnostics(origin, index + 1, line, problems)
                )?;
            }
            Format::Jsonl => {
                let errors: Vec<Value> = found
                    .into_iter()
                    .map(|problem| {
                        error_json(&lines, problem.span.shifted(line_start), problem.message)
                    })
                    .collect();
                let record = json!({
                    "file": origin,
                    "line": index + 1,
                    "ok": errors.is_empty(),
                    "errors": errors,
                });
                writeln!(out, "{record}")?;
            }
        }
    }
    Ok((expressions, errors))
}

pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let (mut expressions, mut errors, mut unreadable) = (0usize, 0usize, 0usize);
    let mut models = 0;
    let mut unbound = Unbound::default();
    for file in &args.files {
        let text = match read(file) {
            Ok(text) => text,
            // One file that cannot be read does not stop the others.
            Err(message) => {
                out.flush()?;
                eprintln!("error: {message}");
                unreadable += 1;
                continue;
            }
        };
        let origin = if file == "-" {
            "<stdin>"
        } else {
            file.as_str()
        };
        let kind = match args.kind {
            Some(Kind::Adm) => Some(FileKind::Adm),
            Some(Kind::Acf) => Some(FileKind::Acf),
            Some(Kind::Cmd) => Some(FileKind::Cmd),
            Some(Kind::Expressions) => None,
            None => FileKind::detect(file, &text),
        };
        let (found, problems) = match kind {
            Some(kind) => {
                models += 1;
                check_model_file(origin, &text, kind, args.format, out)?
            }
            None => check_expression_file(args, origin, &text, &mut unbound, out)?,
        };
        expressions += found;
        errors += problems;
    }
    if args.format == Format::Text {
        // A single model file has its own summary line already.
        if !(models == 1 && args.files.len() == 1) {
            let mut summary = format!(
                "{}, {}",
                Counted(expressions, "expression"),
                Counted(errors, "error")
            );
            if unreadable > 0 {
                summary += &format!(", {} not read", Counted(unreadable, "file"));
            }
            writeln!(out, "{summary}")?;
        }
        if !unbound.names.is_empty() {
            const SHOWN: usize = 10;
            let mut listed = unbound.names[..unbound.names.len().min(SHOWN)].join(", ");
            if unbound.names.len() > SHOWN {
                listed += &format!(" and {} more", unbound.names.len() - SHOWN);
            }
            writeln!(
                out,
                "note: names with no value here: {listed} (give --names to check them)"
            )?;
        }
    }
    Ok(if unreadable > 0 {
        out.flush()?;
        return Err(Fatal::usage(format!(
            "error: {} not read",
            Counted(unreadable, "file")
        )));
    } else if errors == 0 {
        Outcome::Success
    } else {
        Outcome::Failure
    })
}
