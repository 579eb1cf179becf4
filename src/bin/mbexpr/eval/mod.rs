//! `mbexpr eval EXPR`: the value of an expression and, on request, its
//! gradient and Hessian, at one point or at every row of a CSV file.

use std::io::Write;

use clap::ValueEnum;
use std::collections::HashSet;

use mbexpr::{Evaluation, Order, Program, Scene};
use serde_json::Value;

mod model;
mod sweep;

use crate::support::files::read_scene_file;
use crate::support::points::PointsFile;
use crate::support::record::{Problem, Record};
use crate::support::values::{parse_assignment, show};
use crate::{Fatal, Outcome};
use sweep::Sweep;

/// Output formats of `eval`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// The value, then labelled gradient and Hessian tables; with
    /// --points, a table of one line per row.
    Text,
    /// One JSON document: the result, an object keyed by name for a
    /// scene's named expressions, an array of rows with --points.
    Json,
    /// One JSON object per result (per row with --points), one per line.
    Jsonl,
}

#[derive(clap::Args, Clone)]
pub struct Args {
    /// The expression, e.g. "BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)";
    /// with --scene and no expression, every named expression of the scene;
    /// with --model, evaluated in the model (`DM(68, 64)`) instead of the
    /// model's own expressions. It may start with a minus: `mbexpr eval "-2**2"`.
    #[arg(allow_hyphen_values = true)]
    pub expression: Option<String>,
    /// A scene (TOML): bodies, markers, time, variables and named expressions.
    #[arg(long, value_name = "FILE.toml", conflicts_with = "model")]
    pub scene: Option<String>,
    /// A solver dataset: evaluate every expression in it (or the expression
    /// given) at its initial configuration, at TIME = 0 unless --set gives
    /// TIME, DIF(id), a linear system's state ARYVAL(x, k) or a part's
    /// state (PART/3.x) another value; --wrt names any of them; --points
    /// gives them a value per row.
    #[arg(long, value_name = "FILE.adm")]
    model: Option<String>,
    /// A variable's value, NAME=VALUE (repeatable; names are case-insensitive; TIME too).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Derivative directions, comma-separated (blanks around a name are
    /// dropped; a comma inside parentheses, as in `ARYVAL(10, 1)`, is the
    /// name's).
    #[arg(long, value_name = "NAME,NAME")]
    pub wrt: Vec<String>,
    /// 0 (value), 1 (gradient) or 2 (Hessian); default 0, or 1 when --wrt is given.
    #[arg(long, value_parser = clap::value_parser!(u8).range(0..=2))]
    pub order: Option<u8>,
    /// Output format.
    #[arg(long, value_enum, default_value = "text")]
    pub format: Format,
    /// A CSV file (`-`: standard input): a header row of variable names,
    /// then one point per row; results carry the row's line in the file.
    #[arg(long, value_name = "FILE.csv")]
    pub points: Option<String>,
}

/// The names of `--wrt`'s values: split at the commas outside
/// parentheses, without the blanks around them (`--wrt "x, v"`), a linear
/// system's state written as its input is named (`ARYVAL(10,1)` as
/// `ARYVAL(10, 1)`).
fn direction_names(values: &[String]) -> Result<Vec<String>, Fatal> {
    let mut names = Vec::new();
    for value in values {
        let mut depth = 0_usize;
        let mut start = 0;
        let mut pieces = Vec::new();
        for (at, character) in value.char_indices() {
            match character {
                '(' => depth += 1,
                ')' => depth = depth.saturating_sub(1),
                ',' if depth == 0 => {
                    pieces.push(&value[start..at]);
                    start = at + 1;
                }
                _ => {}
            }
        }
        pieces.push(&value[start..]);
        for piece in pieces {
            let name = piece.trim();
            if name.is_empty() {
                return Err(Fatal::usage(
                    "error: --wrt: a name is empty: write --wrt NAME,NAME".to_string(),
                ));
            }
            names.push(match mbexpr::scene::parse_array_state_input(name) {
                Some((array, entry)) => mbexpr::scene::array_state_input(array, entry),
                None => name.to_string(),
            });
        }
    }
    Ok(names)
}

fn to_text(evaluation: &Evaluation, wrt: &[String]) -> String {
    let mut text = format!("value  {}\n", show(evaluation.value));
    let width = wrt
        .iter()
        .map(|name| name.len() + 3)
        .max()
        .unwrap_or(0)
        .max(5);
    if let Some(gradient) = evaluation.gradient.as_ref().filter(|_| !wrt.is_empty()) {
        text.push_str("gradient\n");
        for (name, entry) in wrt.iter().zip(gradient.iter()) {
            text.push_str(&format!(
                "  {:<width$} {}\n",
                format!("d/d{name}"),
                show(*entry)
            ));
        }
    }
    if let Some(hessian) = evaluation.hessian.as_ref().filter(|_| !wrt.is_empty()) {
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

/// The result of one evaluation as a JSON object, its derivatives named.
pub fn to_json(evaluation: &Evaluation, wrt: &[String]) -> Value {
    let record = Record {
        name: None,
        row: None,
        wrt,
        result: Ok(evaluation),
    };
    serde_json::to_value(record).expect("a record serializes")
}

/// Why an expression has no result.
enum Failure {
    /// Problems in the expression (exit status 1).
    Expression(Vec<Problem>),
    /// A problem with how mbexpr was called, or with writing (exit status 2).
    Usage(Fatal),
}

impl From<Fatal> for Failure {
    fn from(fatal: Fatal) -> Failure {
        Failure::Usage(fatal)
    }
}

impl From<std::io::Error> for Failure {
    fn from(error: std::io::Error) -> Failure {
        Failure::Usage(error.into())
    }
}

/// What every expression of one run shares.
struct Context<'a> {
    args: &'a Args,
    scene: Option<&'a Scene>,
    assignments: Vec<(String, f64)>,
}

pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let args = &Args {
        wrt: direction_names(&args.wrt)?,
        ..args.clone()
    };
    let result = match &args.model {
        Some(path) => model::run(args, path, out),
        None => run_expressions(args, out),
    };
    match result {
        // Under JSON formats an error is JSON too, on standard output.
        Err(fatal) if args.format != Format::Text && fatal.is_reportable() => {
            let message = fatal.message().trim_end();
            let problems = [Problem::plain(
                message.strip_prefix("error: ").unwrap_or(message),
            )];
            write_record(out, args.format, None, &[], Err(&problems), "")?;
            Err(fatal.reported())
        }
        result => result,
    }
}

fn run_expressions(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let scene_file = args.scene.as_deref().map(read_scene_file).transpose()?;
    let scene = scene_file.as_ref().map(|file| &file.scene);
    let expressions: Vec<(Option<String>, String)> = match (&args.expression, scene) {
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
        scene,
        assignments: args
            .set
            .iter()
            .map(|assignment| parse_assignment(assignment))
            .collect::<Result<_, _>>()?,
    };
    if args.points.as_deref() == Some("-") && expressions.len() > 1 {
        return Err(Fatal::usage(
            "error: --points - reads standard input once: give one expression to evaluate at its rows",
        ));
    }
    let mut first_points = args.points.as_deref().map(PointsFile::open).transpose()?;
    if let Some(points) = &first_points {
        warn_of_overridden_sets(points, &args.set);
    }
    // Named expressions under --format json: one object keyed by name.
    let keyed = args.format == Format::Json && expressions[0].0.is_some();
    if keyed {
        write!(out, "{{")?;
    }
    let (mut failed, mut misused) = (false, None);
    for (index, (label, text)) in expressions.iter().enumerate() {
        if keyed {
            let separator = if index == 0 { "" } else { "," };
            write!(out, "{separator}\n  {}: ", Value::from(label.as_deref()))?;
        } else if let Some(label) = label
            && args.format == Format::Text
        {
            writeln!(out, "== {label}")?;
        }
        let points = match (first_points.take(), &args.points) {
            (Some(points), _) => Some(points),
            (None, Some(path)) => Some(PointsFile::open(path)?),
            (None, None) => None,
        };
        let indent = if keyed { "  " } else { "" };
        let problems =
            match evaluate_expression(&context, label.as_deref(), text, points, indent, out) {
                Ok(Outcome::Success) => continue,
                Ok(Outcome::Failure) => {
                    failed = true;
                    continue;
                }
                Err(Failure::Expression(problems)) => {
                    failed = true;
                    problems
                }
                Err(Failure::Usage(fatal))
                    if args.format == Format::Text || !fatal.is_reportable() =>
                {
                    return Err(fatal);
                }
                Err(Failure::Usage(fatal)) => {
                    let message = fatal.message().trim_end();
                    let problems = vec![Problem::plain(
                        message.strip_prefix("error: ").unwrap_or(message),
                    )];
                    misused = Some(fatal.reported());
                    problems
                }
            };
        match args.format {
            Format::Text => {
                out.flush()?;
                let origin = label.as_deref().unwrap_or_default();
                // Those with a place once each, with their count (linear in
                // the number of problems); those without after them. A
                // scene's named expression is quoted from the scene file.
                let in_file = label
                    .as_deref()
                    .zip(scene_file.as_ref())
                    .and_then(|(name, file)| file.render(name, &problems));
                let mut rendered = in_file.unwrap_or_else(|| {
                    let placed = problems.iter().filter_map(|problem| {
                        problem.span.map(|span| (span, problem.message.clone()))
                    });
                    crate::support::render::diagnostics(origin, text, placed)
                });
                for problem in problems.iter().filter(|problem| problem.span.is_none()) {
                    rendered += &format!("error: {}\n", problem.message);
                }
                eprint!("{rendered}");
            }
            Format::Json | Format::Jsonl => {
                let name = if keyed { None } else { label.as_deref() };
                write_record(out, args.format, name, &[], Err(&problems), indent)?;
            }
        }
    }
    if keyed {
        writeln!(out, "\n}}")?;
    }
    match misused {
        Some(fatal) => Err(fatal),
        None if failed => Ok(Outcome::Failure),
        None => Ok(Outcome::Success),
    }
}

/// Says on standard error which `--set` a column of the points file
/// takes the place of.
fn warn_of_overridden_sets(points: &PointsFile, assignments: &[String]) {
    for assignment in assignments {
        let name = assignment
            .split_once('=')
            .map_or("", |(name, _)| name.trim());
        if let Some(column) = points
            .names
            .iter()
            .find(|column| column.eq_ignore_ascii_case(name))
        {
            eprintln!(
                "warning: column {column} of {} takes the place of --set {assignment}",
                points.path
            );
        }
    }
}

/// One result or one failure, as the JSON formats write it: a pretty
/// document (indented by `indent` inside a keyed one) or one line.
fn write_record(
    out: &mut impl Write,
    format: Format,
    name: Option<&str>,
    wrt: &[String],
    result: Result<&Evaluation, &[Problem]>,
    indent: &str,
) -> std::io::Result<()> {
    let record = Record {
        name,
        row: None,
        wrt,
        result,
    };
    if format == Format::Jsonl {
        return writeln!(out, "{}", serde_json::to_string(&record)?);
    }
    let pretty = serde_json::to_string_pretty(&record)?.replace('\n', &format!("\n{indent}"));
    if indent.is_empty() {
        writeln!(out, "{pretty}")
    } else {
        write!(out, "{pretty}")
    }
}

fn evaluate_expression(
    context: &Context<'_>,
    label: Option<&str>,
    source: &str,
    points: Option<PointsFile>,
    indent: &str,
    out: &mut impl Write,
) -> Result<Outcome, Failure> {
    let args = context.args;
    let in_expression = |span, message: &dyn std::fmt::Display| Problem::at(source, span, message);
    let tree = mbexpr::parse(source)
        .map_err(|error| Failure::Expression(vec![in_expression(error.span(), &error)]))?;
    let checked = mbexpr::check(&tree).map_err(|errors| {
        Failure::Expression(
            errors
                .iter()
                .map(|error| in_expression(error.span(), error))
                .collect(),
        )
    })?;

    // The inputs beyond --set and the scene: the columns of --points that
    // the expression can read, and the state components named as
    // derivative directions.
    let columns = points
        .as_ref()
        .map(|points| readable_columns(&points.names, &checked, context))
        .unwrap_or_default();
    if let Some(points) = &points
        && label.is_none()
        && columns.len() < points.names.len()
    {
        warn_of_unread_columns(points, &columns);
    }
    let mut extra: Vec<String> = columns.iter().map(|(_, name)| name.clone()).collect();
    if let Some(scene) = context.scene {
        extra.extend(
            args.wrt
                .iter()
                .filter(|name| scene.parse_state_name(name).is_some())
                .cloned(),
        );
    }
    let bound =
        crate::support::binding::bind(&checked, context.scene, &context.assignments, &extra)
            .map_err(|errors| {
                Failure::Expression(
                    errors
                        .iter()
                        .map(|error| {
                            let message = crate::support::binding::message(error, |name| {
                                how_to_set(name, points.as_ref())
                            });
                            in_expression(error.span(), &message)
                        })
                        .collect(),
                )
            })?;
    let (program, values): (Program, Vec<f64>) = (bound.program, bound.values);
    let inputs = program.inputs();

    let mut wrt = Vec::new();
    for name in &args.wrt {
        let Some(index) = program.input_index(name) else {
            let known = inputs.iter().map(String::as_str);
            let suggestion = mbexpr::catalog::did_you_mean(&mbexpr::catalog::closest(name, known));
            return Err(Fatal::usage(format!(
                "error: --wrt {name}: {name} has no value, so it cannot be a derivative direction; set it with --set {name}=VALUE{suggestion}"
            )).into());
        };
        if wrt.contains(&index) {
            return Err(Fatal::usage(format!("error: --wrt names {name} twice")).into());
        }
        wrt.push(index);
    }
    let order = match args.order {
        Some(order) => Order::from_number(order).expect("clap keeps --order in 0..=2"),
        None if wrt.is_empty() => Order::Value,
        None => Order::Gradient,
    };
    let wrt_names: Vec<String> = wrt.iter().map(|&index| inputs[index].clone()).collect();
    let name = if indent.is_empty() { label } else { None };

    let Some(mut points) = points else {
        let evaluation = program
            .evaluate(&values, &wrt, order)
            .map_err(|error| Failure::Expression(vec![in_expression(error.span(), &error)]))?;
        match args.format {
            Format::Text => {
                write!(out, "{}", to_text(&evaluation, &wrt_names))?;
                if order > Order::Value && wrt.is_empty() {
                    let note = crate::support::binding::no_directions(&program, "--wrt NAME,NAME");
                    writeln!(out, "{}", note.trim_start())?;
                }
            }
            Format::Json | Format::Jsonl => {
                write_record(out, args.format, name, &wrt_names, Ok(&evaluation), indent)?;
            }
        }
        return Ok(Outcome::Success);
    };

    let columns: Vec<(usize, usize)> = columns
        .iter()
        .filter_map(|(column, name)| Some((*column, program.input_index(name)?)))
        .collect();
    let sweep = Sweep {
        program: &program,
        source,
        base: &values,
        names: &points.names.clone(),
        columns: &columns,
        wrt: &wrt,
        wrt_names: &wrt_names,
        order,
        format: args.format,
        name,
        indent,
    };
    let failures = sweep.run(&mut points, out)?;
    if args.format == Format::Json && indent.is_empty() {
        writeln!(out)?;
    }
    if failures == 0 {
        return Ok(Outcome::Success);
    }
    if args.format == Format::Text {
        out.flush()?;
        eprintln!(
            "{}: {} failed",
            points.path,
            mbexpr::Counted(failures, "row")
        );
    }
    Ok(Outcome::Failure)
}

/// The columns of a points file that the expression can read, with their
/// index: its variables, the derivative directions, the scene's inputs and
/// the states of its bodies (a header of many columns costs nothing for
/// those it does not read).
fn readable_columns(
    names: &[String],
    checked: &mbexpr::Checked,
    context: &Context<'_>,
) -> Vec<(usize, String)> {
    let mut readable: HashSet<String> = checked
        .variables()
        .iter()
        .map(|name| name.to_ascii_lowercase())
        .chain(
            checked
                .system_variables()
                .iter()
                .map(|variable| variable.name().to_ascii_lowercase()),
        )
        .collect();
    readable.extend(
        context
            .args
            .wrt
            .iter()
            .map(|name| name.to_ascii_lowercase()),
    );
    if let Some(scene) = context.scene {
        readable.extend(
            scene
                .input_names()
                .iter()
                .map(|name| name.to_ascii_lowercase()),
        );
    }
    names
        .iter()
        .enumerate()
        .filter(|(_, name)| {
            readable.contains(&name.to_ascii_lowercase())
                || context
                    .scene
                    .is_some_and(|scene| scene.parse_state_name(name).is_some())
        })
        .map(|(column, name)| (column, name.clone()))
        .collect()
}

/// Says on standard error which columns of the points file the
/// expression does not read (a misspelt name would be one).
fn warn_of_unread_columns(points: &PointsFile, read: &[(usize, String)]) {
    let mut read = read.iter().map(|(column, _)| *column).peekable();
    let unread: Vec<&str> = (0..points.names.len())
        .filter(|&column| read.next_if_eq(&column).is_none())
        .map(|column| points.names[column].as_str())
        .collect();
    eprintln!(
        "warning: the expression reads no column {} of {}",
        crate::support::points::some_names(&unread),
        points.path
    );
}

/// How to give `name` a value: `--set`, or a column of the points file,
/// whose header the message shows.
fn how_to_set(name: &str, points: Option<&PointsFile>) -> String {
    match points {
        None => format!("--set {name}=VALUE"),
        Some(points) => format!(
            "--set {name}=VALUE or a column {name} in {}, whose header (line {}) names {}",
            points.path,
            points.header_line,
            crate::support::points::some_names(&points.names)
        ),
    }
}
