//! `mbexpr eval EXPR`: the value of an expression and, on request, its
//! gradient and Hessian, at one point or at every row of a CSV file.

use std::io::Write;

use clap::ValueEnum;
use mbexpr::{Evaluation, Order, Program, Scene};
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
    /// The expression, e.g. "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)";
    /// with --scene and no expression, every named expression of the scene.
    pub expression: Option<String>,
    /// A scene (TOML): bodies, markers, time, variables and named expressions.
    #[arg(long, value_name = "FILE.toml", conflicts_with = "model")]
    pub scene: Option<String>,
    /// A solver dataset: evaluate every expression in it at its initial
    /// configuration (TIME = 0); --wrt names part states such as PART/3.x.
    #[arg(long, value_name = "FILE.adm", conflicts_with_all = ["expression", "points"])]
    model: Option<String>,
    /// A variable's value, NAME=VALUE (repeatable; names are case-insensitive; TIME too).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Derivative directions, comma-separated.
    #[arg(long, value_name = "NAME,NAME", value_delimiter = ',')]
    pub wrt: Vec<String>,
    /// 0 (value), 1 (gradient) or 2 (Hessian); default 0, or 1 when --wrt is given.
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..=2))]
    pub order: Option<u8>,
    /// Output format.
    #[arg(long, value_enum, default_value = "text")]
    pub format: Format,
    /// A CSV file: a header row of variable names, then one point per row.
    #[arg(long, value_name = "FILE.csv")]
    pub points: Option<String>,
}

/// `NAME=VALUE` to its parts.
pub fn parse_assignment(assignment: &str) -> Result<(String, f64), Fatal> {
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
pub fn tidy(value: f64) -> f64 {
    value + 0.0
}

/// A number for the text tables: shortest round-trip digits, in exponent
/// form when very small or very large.
pub fn show(value: f64) -> String {
    let value = tidy(value);
    if value != 0.0 && !(1e-4..1e15).contains(&value.abs()) {
        format!("{value:e}")
    } else {
        value.to_string()
    }
}

pub fn to_json(evaluation: &Evaluation) -> Value {
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
    let mut text = format!("value  {}\n", show(evaluation.value));
    let width = wrt
        .iter()
        .map(|name| name.len() + 3)
        .max()
        .unwrap_or(0)
        .max(5);
    if let Some(gradient) = &evaluation.gradient {
        text.push_str("gradient\n");
        for (name, entry) in wrt.iter().zip(gradient.iter()) {
            text.push_str(&format!(
                "  {:<width$} {}\n",
                format!("d/d{name}"),
                show(*entry)
            ));
        }
    }
    if let Some(hessian) = &evaluation.hessian {
        text.push_str("hessian\n");
        let cells: Vec<Vec<String>> = hessian
            .row_iter()
            .map(|row| row.iter().map(|&entry| show(entry)).collect())
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

pub fn read_scene(path: &str) -> Result<Scene, Fatal> {
    let text = std::fs::read_to_string(path)
        .map_err(|error| Fatal::usage(format!("error: cannot read {path}: {error}")))?;
    Scene::from_toml(&text).map_err(|error| Fatal::usage(format!("error: {path}: {error}")))
}

/// What every expression of one run shares.
struct Context<'a> {
    args: &'a Args,
    scene: Option<&'a Scene>,
    assignments: Vec<(String, f64)>,
    points: Option<Points>,
}

pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    if let Some(path) = &args.model {
        return crate::model_eval::run(args, path, out);
    }
    let scene = args.scene.as_deref().map(read_scene).transpose()?;
    let expressions: Vec<(Option<String>, String)> = match (&args.expression, &scene) {
        (Some(text), _) => vec![(None, text.clone())],
        (None, Some(scene)) if !scene.expressions.is_empty() => scene
            .expressions
            .iter()
            .map(|(name, text)| (Some(name.clone()), text.clone()))
            .collect(),
        (None, Some(_)) => {
            return Err(Fatal::usage(
                "error: the scene has no [expressions]: give an expression to evaluate",
            ));
        }
        (None, None) => {
            return Err(Fatal::usage(
                "error: give an expression, or --scene FILE whose [expressions] to evaluate",
            ));
        }
    };
    let context = Context {
        args,
        scene: scene.as_ref(),
        assignments: args
            .set
            .iter()
            .map(|assignment| parse_assignment(assignment))
            .collect::<Result<_, _>>()?,
        points: args.points.as_deref().map(read_points).transpose()?,
    };
    let mut outcome = Outcome::Success;
    let several = expressions.len() > 1;
    for (label, text) in &expressions {
        match evaluate_expression(&context, label.as_deref(), text, out) {
            Ok(Outcome::Success) => {}
            Ok(Outcome::Failure) => outcome = Outcome::Failure,
            // With several expressions, one that fails does not stop the others.
            Err(fatal) if several && fatal.is_input() => {
                out.flush()?;
                eprint!("{}", fatal.message());
                outcome = Outcome::Failure;
            }
            Err(fatal) => return Err(fatal),
        }
    }
    Ok(outcome)
}

fn evaluate_expression(
    context: &Context<'_>,
    label: Option<&str>,
    source: &str,
    out: &mut impl Write,
) -> Result<Outcome, Fatal> {
    let args = context.args;
    let origin = label.unwrap_or_default();
    let fail = |span, message: String| Fatal::input(diagnostic(origin, source, span, &message));
    let tree = mbexpr::parse(source).map_err(|error| fail(error.span(), error.to_string()))?;
    let checked = mbexpr::check(&tree).map_err(|errors| {
        let texts: Vec<String> = errors
            .iter()
            .map(|error| diagnostic(origin, source, error.span(), &error.to_string()))
            .collect();
        Fatal::input(texts.concat())
    })?;

    // The inputs beyond --set and the scene: --points columns, and the state
    // components named as derivative directions.
    let columns: Vec<String> = context
        .points
        .iter()
        .flat_map(|points| points.names.iter().cloned())
        .collect();
    let mut extra = columns.clone();
    if let Some(scene) = context.scene {
        extra.extend(
            args.wrt
                .iter()
                .filter(|name| scene.parse_state_name(name).is_some())
                .cloned(),
        );
    }
    let bound = crate::binding::bind(&checked, context.scene, &context.assignments, &extra)
        .map_err(|errors| {
            Fatal::input(crate::binding::render(&errors, origin, source, |name| {
                format!("--set {name}=VALUE")
            }))
        })?;
    let (program, values): (Program, Vec<f64>) = (bound.program, bound.values);
    let inputs = program.inputs();
    let columns: Vec<Option<usize>> = columns
        .iter()
        .map(|name| program.input_index(name))
        .collect();

    let mut wrt = Vec::new();
    for name in &args.wrt {
        let Some(index) = program.input_index(name) else {
            let known = inputs.iter().map(String::as_str);
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
    let wrt_names: Vec<String> = wrt.iter().map(|&index| inputs[index].clone()).collect();
    let labelled = |mut object: Value| {
        if let (Some(label), Value::Object(map)) = (label, &mut object) {
            map.shift_insert(0, "name".to_string(), Value::String(label.to_string()));
        }
        object
    };
    if let Some(label) = label
        && args.format == Format::Text
    {
        writeln!(out, "== {label}")?;
    }

    let Some(points) = &context.points else {
        return match program.evaluate(&values, &wrt, order) {
            Ok(evaluation) => {
                match args.format {
                    Format::Text => write!(out, "{}", to_text(&evaluation, &wrt_names))?,
                    Format::Json => writeln!(out, "{:#}", labelled(to_json(&evaluation)))?,
                    Format::Jsonl => writeln!(out, "{}", labelled(to_json(&evaluation)))?,
                }
                Ok(Outcome::Success)
            }
            Err(error) => Err(fail(error.span(), error.to_string())),
        };
    };

    let mut failures = 0;
    let mut results = Vec::new();
    // The rows are the points of one run: AX, AY, AZ stay continuous.
    let mut run = program.run();
    for (row_number, row) in points.rows.iter().enumerate() {
        let result = row.clone().and_then(|row| {
            let mut point = values.clone();
            for (column, value) in columns.iter().zip(row) {
                if let Some(index) = column {
                    point[*index] = value;
                }
            }
            run.evaluate(&point, &wrt, order)
                .map_err(|error| error.to_string())
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
                    Ok(evaluation) => labelled(to_json(evaluation)),
                    Err(message) => labelled(json!({"error": message})),
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
