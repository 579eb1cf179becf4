//! `mbexpr eval --model FILE.adm [EXPR]`: every expression of a dataset, or
//! the user's expression, evaluated at the model's initial configuration
//! (TIME = 0 unless `--set TIME=...`), one row per expression. Each VARIABLE
//! is evaluated once, after the VARIABLEs it reads, and `VARVAL` passes its
//! value on with its derivatives.

use std::io::Write;

use mbexpr::model::{self, FoundExpression};
use mbexpr::{Checked, Counted, Evaluation, LineIndex, Order, Scene};
use serde_json::{Value, json};

use super::{Args, Format, to_json};
use crate::support::model_values::{
    Missing, Model, NoValue, evaluate_rows, not_a_state, read_in, set_input,
};
use crate::support::points::{Batch, PointsFile, line_of, read_values};
use crate::support::render::diagnostic;
use crate::support::values::show;
use crate::{Fatal, Outcome};

pub fn run(args: &Args, path: &str, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let Model {
        text,
        dataset,
        report,
        scene,
    } = read_in(path, &args.set)?;
    let lines = LineIndex::new(&text);
    let mut directions = std::collections::HashSet::new();
    for name in &args.wrt {
        let state = scene.parse_state_name(name).is_some();
        let diff_id = mbexpr::scene::parse_diff_input(name);
        let run_state = diff_id.is_some_and(|id| scene.statements.diffs.contains_key(&id))
            || scene.value_of(name).is_ok() && mbexpr::scene::is_run_state_input(name);
        let direction = diff_id.map_or_else(
            || name.trim().to_ascii_uppercase(),
            |id| format!("DIF({id})"),
        );
        if !directions.insert(direction) {
            return Err(Fatal::usage(format!("error: --wrt names {name} twice")));
        }
        if !state && !run_state && !name.eq_ignore_ascii_case("TIME") {
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
    let mut inputs = scene.input_names();
    inputs.extend(args.wrt.iter().cloned());

    // The user's expression, or every expression of the model.
    let own = match &args.expression {
        Some(source) => {
            let fail = |span, message: String| Fatal::input(diagnostic("", source, span, &message));
            let tree =
                mbexpr::parse(source).map_err(|error| fail(error.span(), error.to_string()))?;
            let checked = mbexpr::check(&tree).map_err(|errors| {
                let texts: Vec<String> = errors
                    .iter()
                    .map(|error| diagnostic("", source, error.span(), &error.to_string()))
                    .collect();
                Fatal::input(texts.concat())
            })?;
            Some((source.clone(), checked))
        }
        None => None,
    };
    let rows: Vec<Option<&Checked>> = match &own {
        Some((_, checked)) => vec![Some(checked)],
        None => report
            .expressions
            .iter()
            .map(|found| found.checked.as_ref())
            .collect(),
    };
    if let Some(points) = &args.points {
        let labels: Vec<(String, Value)> = match &own {
            Some((source, _)) => vec![(source.clone(), json!({"expression": source}))],
            None => (report.expressions.iter())
                .map(|found| row_fields(&dataset, found, &lines))
                .collect(),
        };
        let table = Table {
            scene: &scene,
            inputs,
            order,
            rows: &rows,
            labels: &labels,
        };
        return table.write(args, points, out);
    }
    let results = evaluate_rows(&scene, inputs, &args.wrt, order, &rows);

    let (mut evaluated, mut need_solver, mut not_evaluated, mut failures) = (0, 0, 0, 0);
    let mut records = Vec::new();
    if args.format == Format::Text {
        write!(out, "{:<28} {:>24}", "statement", "value")?;
        for name in &args.wrt {
            write!(out, " {:>24}", format!("d/d{name}"))?;
        }
        writeln!(out)?;
    }
    for (index, result) in results.iter().enumerate() {
        match result {
            Ok(_) => evaluated += 1,
            Err(no_value) => match no_value.kind {
                Missing::Solver => need_solver += 1,
                Missing::NotEvaluated => not_evaluated += 1,
                Missing::Error => failures += 1,
            },
        }
        let (label, mut record) = match &own {
            Some((source, _)) => (source.clone(), json!({"expression": source})),
            None => row_fields(&dataset, &report.expressions[index], &lines),
        };
        let fields = result_fields(result, &args.wrt);
        if let (Value::Object(record), Value::Object(fields)) = (&mut record, fields) {
            record.extend(fields);
        }
        match args.format {
            Format::Jsonl => writeln!(out, "{record}")?,
            Format::Json => records.push(record),
            Format::Text => write_row(out, &label, result, &args.wrt)?,
        }
    }
    let time = show(scene.time);
    match args.format {
        Format::Json => writeln!(out, "{:#}", Value::Array(records))?,
        Format::Text => {
            let mut summary = format!(
                "{path}: {}: {evaluated} evaluated at TIME = {time}, {need_solver} with no value outside a run",
                Counted(results.len(), "expression"),
            );
            if not_evaluated > 0 {
                summary +=
                    &format!(", {not_evaluated} not evaluated by mbexpr (CURVE, INTERP, USER)");
            }
            writeln!(out, "{summary}, {}", Counted(failures, "error"))?;
        }
        Format::Jsonl => {}
    }
    Ok(if failures == 0 {
        Outcome::Success
    } else {
        Outcome::Failure
    })
}

/// `eval --model --points`: the model's expressions (or the one given) at
/// each row of a points file, whose columns name TIME, MODE, a DIFF's state
/// `DIF(id)` or a part's state component (`PART/3.x`).
struct Table<'a> {
    scene: &'a Scene,
    inputs: Vec<String>,
    order: Order,
    rows: &'a [Option<&'a Checked>],
    /// Each expression's label in text and its fields in JSON.
    labels: &'a [(String, Value)],
}

impl Table<'_> {
    fn write(&self, args: &Args, path: &str, out: &mut impl Write) -> Result<Outcome, Fatal> {
        let mut file = PointsFile::open(path)?;
        for name in &file.names {
            set_input(&mut self.scene.clone(), name, 0.0).map_err(|message| {
                Fatal::usage(format!(
                    "error: {path}:{}: column {name}: {message}",
                    file.header_line
                ))
            })?;
        }
        if args.format == Format::Text {
            write!(out, "{:<28} {:>24}", "row", "value")?;
            for name in &args.wrt {
                write!(out, " {:>24}", format!("d/d{name}"))?;
            }
            writeln!(out)?;
        }
        let every: Vec<(usize, usize)> = (0..file.names.len())
            .map(|column| (column, column))
            .collect();
        let (mut batch, mut records, mut failures) = (Batch::default(), Vec::new(), 0);
        let mut point = vec![0.0; file.names.len()];
        loop {
            file.read_batch(&mut batch)?;
            if batch.rows().is_empty() {
                break;
            }
            for row in batch.rows() {
                let line = line_of(row);
                let results = match read_values(row, &file.names, &every, &mut point) {
                    Ok(()) => {
                        let mut scene = self.scene.clone();
                        for (name, value) in file.names.iter().zip(&point) {
                            set_input(&mut scene, name, *value).map_err(|message| {
                                Fatal::usage(format!("error: {path}:{line}: {name}: {message}"))
                            })?;
                        }
                        evaluate_rows(
                            &scene,
                            self.inputs.clone(),
                            &args.wrt,
                            self.order,
                            self.rows,
                        )
                    }
                    Err(message) => vec![Err(NoValue::error(message)); self.rows.len()],
                };
                for (result, (label, fields)) in results.iter().zip(self.labels) {
                    if result
                        .as_ref()
                        .is_err_and(|no_value| no_value.kind == Missing::Error)
                    {
                        failures += 1;
                    }
                    let label = if self.labels.len() == 1 {
                        line.to_string()
                    } else {
                        format!("{line} {label}")
                    };
                    let mut record = json!({"row": line});
                    if let (Value::Object(record), Value::Object(fields)) =
                        (&mut record, fields.clone())
                    {
                        record.extend(fields);
                    }
                    if let (Value::Object(record), Value::Object(fields)) =
                        (&mut record, result_fields(result, &args.wrt))
                    {
                        record.extend(fields);
                    }
                    match args.format {
                        Format::Jsonl => writeln!(out, "{record}")?,
                        Format::Json => records.push(record),
                        Format::Text => write_row(out, &label, result, &args.wrt)?,
                    }
                }
            }
        }
        if args.format == Format::Json {
            writeln!(out, "{:#}", Value::Array(records))?;
        }
        if failures > 0 {
            out.flush()?;
            eprintln!("{path}: {} failed", Counted(failures, "evaluation"));
        }
        Ok(if failures == 0 {
            Outcome::Success
        } else {
            Outcome::Failure
        })
    }
}

/// A result's fields in JSON: the value and derivatives, or why there is none.
fn result_fields(result: &Result<Evaluation, NoValue>, wrt: &[String]) -> Value {
    match result {
        Ok(evaluation) => to_json(evaluation, wrt),
        Err(no_value) => match no_value.kind {
            Missing::Solver => json!({"needs_solver": no_value.message}),
            Missing::NotEvaluated => json!({"not_evaluated": no_value.message}),
            Missing::Error => json!({"error": no_value.message}),
        },
    }
}

/// The label of a model row in text and its fields in JSON.
fn row_fields(
    dataset: &model::Dataset,
    found: &FoundExpression,
    lines: &LineIndex<'_>,
) -> (String, Value) {
    let statement = &dataset.statements[found.statement];
    let label = format!("{} {}", statement.label(), found.keyword);
    let record = json!({
        "statement": statement.name.as_str(),
        "id": statement.id,
        "keyword": found.keyword.as_str(),
        "line": lines.location(found.span.start).line,
    });
    (label, record)
}

/// One row of the text table: the value and gradient, then the Hessian's
/// rows under it, each labelled with its direction.
fn write_row(
    out: &mut impl Write,
    label: &str,
    result: &Result<Evaluation, NoValue>,
    wrt: &[String],
) -> std::io::Result<()> {
    let evaluation = match result {
        Ok(evaluation) => evaluation,
        Err(no_value) => return writeln!(out, "{label:<28} {}", no_value.message),
    };
    write!(out, "{label:<28} {:>24}", show(evaluation.value))?;
    for entry in evaluation.gradient.iter().flatten() {
        write!(out, " {:>24}", show(*entry))?;
    }
    writeln!(out)?;
    if let Some(hessian) = &evaluation.hessian {
        for (name, row) in wrt.iter().zip(hessian.row_iter()) {
            write!(out, "{:<28} {:>24}", format!("  d/d{name}"), "")?;
            for entry in row.iter() {
                write!(out, " {:>24}", show(*entry))?;
            }
            writeln!(out)?;
        }
    }
    Ok(())
}
