//! `mbexpr eval --model FILE.adm [EXPR]`: every expression of a dataset, or
//! the user's expression, evaluated at the model's initial configuration
//! (TIME = 0 unless `--set TIME=...`), one row per expression. Each VARIABLE
//! is evaluated once, after the VARIABLEs it reads, and `VARVAL` passes its
//! value on with its derivatives.

use std::collections::HashMap;
use std::io::Write;

use mbexpr::model::{self, FileKind, FoundExpression};
use mbexpr::number::{Directional, Number};
use mbexpr::{Checked, Counted, Evaluation, LineIndex, Order, Scene};
use num_dual::{Dual2DVec64, DualDVec64};
use serde_json::{Value, json};

use crate::eval_cmd::{Args, Format, parse_assignment, show, to_json};
use crate::points::{Batch, PointsFile, line_of, read_values};
use crate::render::{diagnostic, diagnostics};
use crate::{Fatal, Outcome};

/// Why a row has no value.
#[derive(Clone)]
struct NoValue {
    message: String,
    kind: Missing,
}

/// What keeps a row from a value.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Missing {
    /// Something is wrong with the expression or the model.
    Error,
    /// Nothing is wrong: only a running solver has the value (a result, a
    /// solver state).
    Solver,
    /// Nothing is wrong: mbexpr does not evaluate the function (ORIENT,
    /// INCANG, a user subroutine).
    NotEvaluated,
}

impl NoValue {
    fn error(message: impl ToString) -> NoValue {
        NoValue {
            message: message.to_string(),
            kind: Missing::Error,
        }
    }
}

/// What keeps an expression that compiles with `errors` from a value: the
/// least harmless of them.
fn missing(errors: &[mbexpr::CompileError]) -> Missing {
    use mbexpr::CompileError;
    let kind = |error: &CompileError| match error {
        CompileError::NeedsSolver { .. } | CompileError::NeedsSolverState { .. } => Missing::Solver,
        CompileError::NotInScene { .. } | CompileError::UserSubroutine { .. } => {
            Missing::NotEvaluated
        }
        _ => Missing::Error,
    };
    if errors.iter().any(|error| kind(error) == Missing::Error) {
        Missing::Error
    } else if errors
        .iter()
        .any(|error| kind(error) == Missing::NotEvaluated)
    {
        Missing::NotEvaluated
    } else {
        Missing::Solver
    }
}

/// What every evaluation of one run shares: the scene, its input names,
/// the derivative directions and how to make and read numbers of type `T`.
struct Context<'a, T> {
    scene: &'a Scene,
    inputs: Vec<String>,
    wrt: &'a [String],
    /// A value as a number of type `T`, seeded as direction `Some(j)`.
    seed: fn(f64, Option<usize>, usize) -> T,
    /// The values of the VARIABLEs evaluated so far.
    variables: HashMap<u64, Result<T, NoValue>>,
}

impl<T: Number> Context<'_, T> {
    /// The value of `checked` with the VARIABLEs it reads from
    /// [`Context::variables`].
    fn evaluate(&self, checked: &Checked) -> Result<T, NoValue> {
        let program =
            mbexpr::compile_in_model(checked, &self.inputs, self.scene).map_err(|errors| {
                NoValue {
                    message: errors[0].to_string(),
                    kind: missing(&errors),
                }
            })?;
        let count = self.wrt.len();
        let values = program
            .inputs()
            .iter()
            .map(|name| match variable_id(name) {
                Some(id) => match self.variables.get(&id) {
                    Some(Ok(value)) => Ok(value.clone()),
                    Some(Err(no_value)) => Err(NoValue {
                        message: format!("VARVAL({id}) has no value: {}", no_value.message),
                        kind: no_value.kind,
                    }),
                    None => Err(NoValue::error(format!("VARIABLE/{id} depends on itself"))),
                },
                None => {
                    let value = self.scene.value_of(name).map_err(NoValue::error)?;
                    let direction = self
                        .wrt
                        .iter()
                        .position(|known| known.eq_ignore_ascii_case(name));
                    Ok((self.seed)(value, direction, count))
                }
            })
            .collect::<Result<Vec<T>, NoValue>>()?;
        program
            .evaluator::<T>()
            .evaluate_numbers(&values)
            .map_err(NoValue::error)
    }
}

/// The VARIABLE id of an input named `VARVAL(id)` by `compile_in_model`.
fn variable_id(name: &str) -> Option<u64> {
    name.strip_prefix("VARVAL(")?
        .strip_suffix(')')?
        .parse()
        .ok()
}

/// Every row (and the user's expression, last) evaluated over numbers of
/// type `T`, read into [`Evaluation`]s by `finish`.
fn evaluate_all<T: Number>(
    mut context: Context<'_, T>,
    rows: &[Option<&Checked>],
    finish: impl Fn(&T) -> Evaluation,
) -> Vec<Result<Evaluation, NoValue>> {
    let (order, looped) = model::evaluation_order(&context.scene.statements.variables);
    for id in looped {
        let message = format!("VARIABLE/{id} depends on itself (see mbexpr check)");
        context.variables.insert(id, Err(NoValue::error(message)));
    }
    for id in order {
        let value = context.evaluate(&context.scene.statements.variables[&id]);
        context.variables.insert(id, value);
    }
    rows.iter()
        .map(|row| match row {
            Some(checked) => context.evaluate(checked).map(|value| finish(&value)),
            None => Err(NoValue::error(
                "the expression does not check (see mbexpr check)",
            )),
        })
        .collect()
}

/// [`evaluate_all`] over the number type `order` needs.
fn evaluate_rows(
    scene: &Scene,
    inputs: Vec<String>,
    wrt: &[String],
    order: Order,
    rows: &[Option<&Checked>],
) -> Vec<Result<Evaluation, NoValue>> {
    fn context<'a, T: Directional>(
        scene: &'a Scene,
        inputs: Vec<String>,
        wrt: &'a [String],
    ) -> Context<'a, T> {
        Context {
            scene,
            inputs,
            wrt,
            seed: |value, direction, count| match direction {
                Some(direction) => T::variable(value, direction, count),
                None => T::from(value),
            },
            variables: HashMap::new(),
        }
    }
    let count = wrt.len();
    match order {
        Order::Value => {
            let context = Context::<f64> {
                scene,
                inputs,
                wrt,
                seed: |value, _, _| value,
                variables: HashMap::new(),
            };
            evaluate_all(context, rows, |value| Evaluation {
                value: *value,
                gradient: None,
                hessian: None,
            })
        }
        Order::Gradient => evaluate_all(context::<DualDVec64>(scene, inputs, wrt), rows, |value| {
            Evaluation {
                value: value.value(),
                gradient: Some(value.gradient(count)),
                hessian: None,
            }
        }),
        Order::Hessian => evaluate_all(context::<Dual2DVec64>(scene, inputs, wrt), rows, |value| {
            Evaluation {
                value: value.value(),
                gradient: Some(value.gradient(count)),
                hessian: value.hessian(count),
            }
        }),
    }
}

/// The text of the model file and its statements.
fn read_model(path: &str) -> Result<(String, model::Dataset), Fatal> {
    let text = crate::check_cmd::read(path)
        .map_err(|message| Fatal::usage(format!("error: {message}")))?;
    let kind = match FileKind::detect(path, &text) {
        Some(kind @ (FileKind::Adm | FileKind::Acf)) => kind,
        _ => {
            return Err(Fatal::usage(format!(
                "error: --model {path}: give a solver dataset (.adm, or a file whose first lines are a dataset's) or command file (.acf)"
            )));
        }
    };
    let dataset = model::read(&text, kind);
    Ok((text, dataset))
}

/// A model read for evaluation: its text, statements, check report and
/// the scene of its initial configuration, with the inputs `sets` gives
/// (TIME, MODE, `DIF(id)`, a part's state) set.
struct Model {
    text: String,
    dataset: model::Dataset,
    report: model::ModelCheck,
    scene: Scene,
}

fn read_in(path: &str, sets: &[String]) -> Result<Model, Fatal> {
    let (text, dataset) = read_model(path)?;
    let report = model::check_model(&text, &dataset);
    let mut scene = model::initial_scene(&dataset, &report).map_err(|errors| {
        let problems = errors.iter().map(|error| (error.span(), error.to_string()));
        Fatal::input(diagnostics(path, &text, problems))
    })?;
    for assignment in sets {
        let (name, value) = parse_assignment(assignment)?;
        set_input(&mut scene, &name, value)
            .map_err(|message| Fatal::usage(format!("error: --set {assignment}: {message}")))?;
    }
    Ok(Model {
        text,
        dataset,
        report,
        scene,
    })
}

/// Gives input `name` of a model's expressions the value `value` in
/// `scene`: `TIME`, `MODE`, a DIFF's state `DIF(id)`, or a part's state
/// component (`PART/3.x`; a rotation `rz` turns the part from its initial
/// orientation about ground z).
fn set_input(scene: &mut Scene, name: &str, value: f64) -> Result<(), String> {
    use mbexpr::catalog::SystemVariable;
    use mbexpr::scene::StateComponent;
    match SystemVariable::lookup(name) {
        Some(SystemVariable::Time) => scene.time = value,
        Some(SystemVariable::Mode) => match SystemVariable::mode_error(value) {
            Some(message) => return Err(message),
            None => scene.mode = Some(value),
        },
        None => {
            let diff = mbexpr::scene::parse_diff_input(name)
                .and_then(|id| scene.statements.diffs.get_mut(&id));
            if let Some(diff) = diff {
                diff.initial = value;
                return Ok(());
            }
            let (index, component) = scene
                .parse_state_name(name)
                .ok_or_else(|| not_a_state(scene, name))?;
            let body = &mut scene.bodies[index];
            match component {
                StateComponent::Position(axis) => body.position[axis] = value,
                StateComponent::Rotation(axis) => {
                    let turn = nalgebra::Vector3::ith(axis, value);
                    body.orientation =
                        nalgebra::UnitQuaternion::from_scaled_axis(turn) * body.orientation;
                }
                StateComponent::Velocity(axis) => body.velocity[axis] = value,
                StateComponent::AngularVelocity(axis) => body.angular_velocity[axis] = value,
            }
        }
    }
    Ok(())
}

pub fn run(args: &Args, path: &str, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let Model {
        text,
        dataset,
        report,
        scene,
    } = read_in(path, &args.set)?;
    let lines = LineIndex::new(&text);
    for name in &args.wrt {
        let state = scene.parse_state_name(name).is_some();
        let diff = mbexpr::scene::parse_diff_input(name)
            .is_some_and(|id| scene.statements.diffs.contains_key(&id));
        if !state && !diff && !name.eq_ignore_ascii_case("TIME") {
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
                    &format!(", {not_evaluated} not evaluated by mbexpr (ORIENT, INCANG, USER)");
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

/// `plot --model`: `checked` evaluated in the model at each sample of the
/// input `sampling.over` (TIME, `DIF(id)` or a part's state component), the
/// other inputs at the initial configuration. Its break points are not
/// looked for (each VARIABLE is its own program): the samples are even.
pub fn curves(
    path: &str,
    sets: &[String],
    checked: &Checked,
    sampling: &crate::plot::Sampling<'_>,
    samples: usize,
) -> Result<crate::plot::Plot, Fatal> {
    let scene = read_in(path, sets)?.scene;
    let over = sampling.over;
    set_input(&mut scene.clone(), over, sampling.range.0)
        .map_err(|message| Fatal::usage(format!("error: --over {over}: {message}")))?;
    let (wrt, order) = if sampling.derivatives {
        (vec![over.to_string()], Order::Hessian)
    } else {
        (Vec::new(), Order::Value)
    };
    let mut inputs = scene.input_names();
    inputs.extend(wrt.iter().cloned());
    let (low, high) = sampling.range;
    let xs = mbexpr::kinks::samples(low, high, samples, &[]);
    crate::plot::trace(sampling, &xs, Vec::new(), |x| {
        let mut at = scene.clone();
        set_input(&mut at, over, x)?;
        let mut results = evaluate_rows(&at, inputs.clone(), &wrt, order, &[Some(checked)]);
        results.remove(0).map_err(|no_value| no_value.message)
    })
    .map_err(|message| Fatal::input(format!("error: {message}")))
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

/// Why `name` is neither TIME nor a state component of a part of `scene`:
/// no part of that name (with the close ones), or no such component.
fn not_a_state(scene: &Scene, name: &str) -> String {
    const COMPONENTS: &str = "x y z rx ry rz vx vy vz wx wy wz";
    let Some((part, component)) = name.rsplit_once('.') else {
        return format!(
            "name TIME, a DIFF's state DIF(id) or a part's state component, such as PART/3.x ({COMPONENTS})"
        );
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
