//! `mbexpr eval --model FILE.adm`: every expression of a dataset evaluated
//! at the model's initial configuration (TIME = 0), one row per expression.

use std::io::Write;

use mbexpr::model::{self, FileKind};
use mbexpr::{Order, Scene};
use serde_json::{Value, json};

use crate::eval_cmd::{Args, Format, show, to_json};
use crate::render::diagnostic;
use crate::{Fatal, Outcome};

/// Why a row has no value.
struct NoValue {
    message: String,
    /// Nothing is wrong: only a running solver has the value, or mbexpr
    /// does not evaluate the function.
    needs_solver: bool,
}

impl NoValue {
    fn error(message: impl ToString) -> NoValue {
        NoValue {
            message: message.to_string(),
            needs_solver: false,
        }
    }
}

/// One row: the value and derivatives, or why there are none.
fn evaluate_row(
    scene: &Scene,
    checked: &mbexpr::Checked,
    wrt: &[String],
    order: Order,
) -> Result<mbexpr::Evaluation, NoValue> {
    let mut inputs = scene.input_names();
    inputs.extend(wrt.iter().cloned());
    let program = mbexpr::compile_in_scene(checked, &inputs, scene).map_err(|errors| NoValue {
        message: errors[0].to_string(),
        needs_solver: errors.iter().all(mbexpr::CompileError::is_unavailable),
    })?;
    let values = scene.values(program.inputs()).map_err(NoValue::error)?;
    let directions: Vec<usize> = wrt
        .iter()
        .filter_map(|name| program.input_index(name))
        .collect();
    program
        .evaluate(&values, &directions, order)
        .map_err(NoValue::error)
}

pub fn run(args: &Args, path: &str, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let kind = match FileKind::of_path(path) {
        Some(kind @ (FileKind::Adm | FileKind::Acf)) => kind,
        _ => {
            return Err(Fatal::usage(format!(
                "error: --model {path}: give a solver dataset (.adm) or command file (.acf)"
            )));
        }
    };
    let text = std::fs::read_to_string(path)
        .map_err(|error| Fatal::usage(format!("error: cannot read {path}: {error}")))?;
    let dataset = model::read(&text, kind);
    let report = model::check_model(&text, &dataset);
    let scene = model::initial_scene(&dataset, &report).map_err(|errors| {
        let texts: Vec<String> = errors
            .iter()
            .map(|error| diagnostic(path, &text, error.span(), &error.to_string()))
            .collect();
        Fatal::input(texts.concat())
    })?;
    for name in &args.wrt {
        if scene.parse_state_name(name).is_none() {
            return Err(Fatal::usage(format!(
                "error: --wrt {name}: {}",
                not_a_state(&scene, name)
            )));
        }
    }
    let order = match args.order {
        Some(order) => Order::from_number(order).expect("clap keeps --order in 0..=2"),
        None if args.wrt.is_empty() => Order::Value,
        None => Order::Gradient,
    };
    let (mut evaluated, mut need_solver, mut failures) = (0, 0, 0);
    let mut rows = Vec::new();
    if args.format == Format::Text {
        write!(out, "{:<28} {:>24}", "statement", "value")?;
        for name in &args.wrt {
            write!(out, " {:>24}", format!("d/d{name}"))?;
        }
        writeln!(out)?;
    }
    for found in &report.expressions {
        let statement = &dataset.statements[found.statement];
        let result = match &found.checked {
            Some(checked) => evaluate_row(&scene, checked, &args.wrt, order),
            None => Err(NoValue::error(
                "the expression does not check (see mbexpr check)",
            )),
        };
        match &result {
            Ok(_) => evaluated += 1,
            Err(no_value) if no_value.needs_solver => need_solver += 1,
            Err(_) => failures += 1,
        }
        let mut record = json!({
            "statement": statement.name,
            "id": statement.id,
            "keyword": found.keyword,
            "line": mbexpr::Location::of(&text, found.span.start).line,
        });
        let fields = match &result {
            Ok(evaluation) => to_json(evaluation, &args.wrt),
            Err(no_value) if no_value.needs_solver => json!({"needs_solver": no_value.message}),
            Err(no_value) => json!({"error": no_value.message}),
        };
        if let (Value::Object(record), Value::Object(fields)) = (&mut record, fields) {
            record.extend(fields);
        }
        match args.format {
            Format::Jsonl => writeln!(out, "{record}")?,
            Format::Json => rows.push(record),
            Format::Text => {
                let label = format!("{} {}", statement.label(), found.keyword);
                match &result {
                    Ok(evaluation) => {
                        write!(out, "{label:<28} {:>24}", show(evaluation.value))?;
                        for entry in evaluation.gradient.iter().flatten() {
                            write!(out, " {:>24}", show(*entry))?;
                        }
                        writeln!(out)?;
                    }
                    Err(no_value) => writeln!(out, "{label:<28} {}", no_value.message)?,
                }
            }
        }
    }
    match args.format {
        Format::Json => writeln!(out, "{:#}", Value::Array(rows))?,
        Format::Text => writeln!(
            out,
            "{path}: {} expressions: {evaluated} evaluated at TIME = 0, {need_solver} with no value outside a run, {failures} errors",
            report.expressions.len(),
        )?,
        Format::Jsonl => {}
    }
    Ok(if failures == 0 {
        Outcome::Success
    } else {
        Outcome::Failure
    })
}

/// Why `name` is not a state component of a part of `scene`: no part of
/// that name (with the close ones), or no such component.
fn not_a_state(scene: &mbexpr::Scene, name: &str) -> String {
    const COMPONENTS: &str = "x y z rx ry rz vx vy vz wx wy wz";
    let Some((part, component)) = name.rsplit_once('.') else {
        return format!("name a part's state component, such as PART/3.x ({COMPONENTS})");
    };
    if scene.find_body(part).is_none() {
        let parts = scene.bodies.iter().map(|body| body.name.as_str());
        let close = mbexpr::catalog::closest(part, parts);
        return format!(
            "{part} does not exist in this model{}",
            mbexpr::catalog::did_you_mean(&close)
        );
    }
    format!("`{component}` is not a state component of {part}: write one of {COMPONENTS}")
}
