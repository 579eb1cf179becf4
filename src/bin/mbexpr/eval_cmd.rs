//! `mbexpr eval EXPR`: the value of an expression and, on request, its
//! gradient and Hessian, at one point or at every row of a CSV file.

use std::io::Write;

use clap::ValueEnum;
use mbexpr::{Evaluation, Order, Program};
use serde_json::{Value, json};

use crate::render::diagnostic;
use crate::{Fatal, Outcome};

/// Output formats of `eval`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The value, then labelled gradient and Hessian tables.
    Text,
    /// One JSON document (an array of results with `--points`).
    Json,
    /// One JSON object per line.
    Jsonl,
}

#[derive(clap::Args)]
pub struct Args {
    /// The expression, e.g. "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)".
    expression: String,
    /// A variable's value, NAME=VALUE (repeatable; names are case-insensitive; TIME too).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Derivative directions, comma-separated.
    #[arg(long, value_name = "NAME,NAME", value_delimiter = ',')]
    wrt: Vec<String>,
    /// 0 (value), 1 (gradient) or 2 (Hessian); default 0, or 1 when --wrt is given.
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..=2))]
    order: Option<u8>,
    /// Output format.
    #[arg(long, value_enum, default_value = "text")]
    format: Format,
    /// A CSV file: a header row of variable names, then one point per row.
    #[arg(long, value_name = "FILE.csv")]
    points: Option<String>,
}

/// `NAME=VALUE` to its parts.
fn parse_assignment(assignment: &str) -> Result<(String, f64), Fatal> {
    let (name, value) = assignment
        .split_once('=')
        .ok_or_else(|| Fatal::usage(format!("error: --set {assignment}: write NAME=VALUE")))?;
    let value: f64 = value.trim().parse().map_err(|_| {
        Fatal::usage(format!(
            "error: --set {assignment}: `{}` is not a number",
            value.trim()
        ))
    })?;
    if !value.is_finite() {
        return Err(Fatal::usage(format!(
            "error: --set {assignment}: the value must be finite"
        )));
    }
    Ok((name.trim().to_string(), value))
}

/// The points to evaluate at: names, then one row of values per point (a
/// row that cannot be read is an error message instead).
struct Points {
    names: Vec<String>,
    rows: Vec<Result<Vec<f64>, String>>,
}

fn read_points(path: &str) -> Result<Points, Fatal> {
    let text = std::fs::read_to_string(path)
        .map_err(|error| Fatal::usage(format!("error: cannot read {path}: {error}")))?;
    let mut lines = text.lines().filter(|line| !line.trim().is_empty());
    let header = lines.next().ok_or_else(|| {
        Fatal::usage(format!(
            "error: {path} is empty: it needs a header row of variable names"
        ))
    })?;
    let names: Vec<String> = header
        .split(',')
        .map(|name| name.trim().to_string())
        .collect();
    let rows = lines
        .map(|line| {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            if cells.len() != names.len() {
                return Err(format!(
                    "the row has {} values for {} columns",
                    cells.len(),
                    names.len()
                ));
            }
            cells
                .iter()
                .zip(&names)
                .map(|(cell, name)| match cell.parse::<f64>() {
                    Ok(value) if value.is_finite() => Ok(value),
                    _ => Err(format!("{name}: `{cell}` is not a finite number")),
                })
                .collect()
        })
        .collect();
    Ok(Points { names, rows })
}

/// `-0` prints as `0`.
fn tidy(value: f64) -> f64 {
    value + 0.0
}

fn to_json(evaluation: &Evaluation) -> Value {
    let mut object = json!({"value": tidy(evaluation.value)});
    if let Some(gradient) = &evaluation.gradient {
        object["gradient"] = gradient.iter().map(|&entry| tidy(entry)).collect();
    }
    if let Some(hessian) = &evaluation.hessian {
        object["hessian"] = hessian
            .row_iter()
            .map(|row| row.iter().map(|&entry| tidy(entry)).collect::<Value>())
            .collect();
    }
    object
}

fn to_text(evaluation: &Evaluation, wrt: &[String]) -> String {
    let mut text = format!("value  {}\n", tidy(evaluation.value));
    let width = wrt
        .iter()
        .map(|name| name.len() + 2)
        .max()
        .unwrap_or(0)
        .max(5);
    if let Some(gradient) = &evaluation.gradient {
        text.push_str("gradient\n");
        for (name, entry) in wrt.iter().zip(gradient.iter()) {
            text.push_str(&format!(
                "  {:<width$} {}\n",
                format!("d/d{name}"),
                tidy(*entry)
            ));
        }
    }
    if let Some(hessian) = &evaluation.hessian {
        text.push_str("hessian\n");
        let cells: Vec<Vec<String>> = hessian
            .row_iter()
            .map(|row| row.iter().map(|&entry| tidy(entry).to_string()).collect())
            .collect();
        let column = cells
            .iter()
            .flatten()
            .map(String::len)
            .chain(wrt.iter().map(String::len))
            .max()
            .unwrap_or(1);
        text.push_str(&format!("  {:<width$}", ""));
        for name in wrt {
            text.push_str(&format!(" {name:>column$}"));
        }
        text.push('\n');
        for (name, row) in wrt.iter().zip(&cells) {
            text.push_str(&format!("  {name:<width$}"));
            for cell in row {
                text.push_str(&format!(" {cell:>column$}"));
            }
            text.push('\n');
        }
    }
    text
}

pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let source = &args.expression;
    let fail = |span, message: String| Fatal::input(diagnostic("", source, span, &message));
    let tree = mbexpr::parse(source).map_err(|error| fail(error.span(), error.to_string()))?;
    let checked = mbexpr::check(&tree).map_err(|errors| {
        let texts: Vec<String> = errors
            .iter()
            .map(|error| diagnostic("", source, error.span(), &error.to_string()))
            .collect();
        Fatal::input(texts.concat())
    })?;

    let mut names: Vec<String> = Vec::new();
    let mut values: Vec<f64> = Vec::new();
    for assignment in &args.set {
        let (name, value) = parse_assignment(assignment)?;
        match names
            .iter()
            .position(|known| known.eq_ignore_ascii_case(&name))
        {
            Some(index) => values[index] = value,
            None => {
                names.push(name);
                values.push(value);
            }
        }
    }
    let points = args.points.as_deref().map(read_points).transpose()?;
    let mut columns = Vec::new();
    for name in points.iter().flat_map(|points| &points.names) {
        let index = match names
            .iter()
            .position(|known| known.eq_ignore_ascii_case(name))
        {
            Some(index) => index,
            None => {
                names.push(name.clone());
                values.push(0.0);
                names.len() - 1
            }
        };
        columns.push(index);
    }

    let program: Program = mbexpr::compile(&checked, &names).map_err(|errors| {
        let texts: Vec<String> = errors
            .iter()
            .map(|error| {
                let hint = match error {
                    mbexpr::CompileError::UnboundVariable { name, .. } => {
                        format!("{error}: set it with --set {name}=VALUE")
                    }
                    _ => error.to_string(),
                };
                diagnostic("", source, error.span(), &hint)
            })
            .collect();
        Fatal::input(texts.concat())
    })?;

    let mut wrt = Vec::new();
    for name in &args.wrt {
        let Some(index) = program.input_index(name) else {
            let known = names.iter().map(String::as_str);
            let suggestion = mbexpr::catalog::did_you_mean(&mbexpr::catalog::closest(name, known));
            return Err(Fatal::usage(format!(
                "error: --wrt {name}: {name} has no value, so it cannot be a derivative direction; set it with --set {name}=VALUE{suggestion}"
            )));
        };
        if wrt.contains(&index) {
            return Err(Fatal::usage(format!("error: --wrt names {name} twice")));
        }
        wrt.push(index);
    }
    let order = match args.order {
        Some(order) => Order::from_number(order).expect("clap keeps --order in 0..=2"),
        None if wrt.is_empty() => Order::Value,
        None => Order::Gradient,
    };
    let wrt_names: Vec<String> = wrt.iter().map(|&index| names[index].clone()).collect();

    let evaluate = |values: &[f64]| program.evaluate(values, &wrt, order);
    let Some(points) = points else {
        return match evaluate(&values) {
            Ok(evaluation) => {
                match args.format {
                    Format::Text => write!(out, "{}", to_text(&evaluation, &wrt_names))?,
                    Format::Json => writeln!(out, "{:#}", to_json(&evaluation))?,
                    Format::Jsonl => writeln!(out, "{}", to_json(&evaluation))?,
                }
                Ok(Outcome::Success)
            }
            Err(error) => Err(fail(error.span(), error.to_string())),
        };
    };

    let mut failures = 0;
    let mut results = Vec::new();
    for (row_number, row) in points.rows.iter().enumerate() {
        let result = row.clone().and_then(|row| {
            let mut point = values.clone();
            for (&index, value) in columns.iter().zip(row) {
                point[index] = value;
            }
            evaluate(&point).map_err(|error| error.to_string())
        });
        if result.is_err() {
            failures += 1;
        }
        match args.format {
            Format::Text => match &result {
                Ok(evaluation) => write!(out, "{}", to_text(evaluation, &wrt_names))?,
                Err(message) => writeln!(out, "error: row {}: {message}", row_number + 2)?,
            },
            Format::Json | Format::Jsonl => {
                let object = match &result {
                    Ok(evaluation) => to_json(evaluation),
                    Err(message) => json!({"error": message}),
                };
                if args.format == Format::Jsonl {
                    writeln!(out, "{object}")?;
                } else {
                    results.push(object);
                }
            }
        }
    }
    if args.format == Format::Json {
        writeln!(out, "{:#}", Value::Array(results))?;
    }
    Ok(if failures == 0 {
        Outcome::Success
    } else {
        Outcome::Failure
    })
}
