//! `mbexpr simulate FILE`: integrate a dataset's (or a scene file's) DIFF
//! equations and free parts in time, rows of states at equally spaced
//! times on standard output, statistics (and, on request, every branch
//! switch) on standard error.

use std::io::{IsTerminal, Write};
use std::path::Path;
use std::time::{Duration, Instant};

use clap::ValueEnum;
use mbexpr::integrate::Method;
use mbexpr::model::{self, FileKind};
use mbexpr::simulate::{self, Model, Place, Settings, SimulateError, Simulation};
use mbexpr::{Counted, Shown};

use crate::plot::{Curve, Plot, render_svg};
use crate::render::diagnostic;
use crate::{Fatal, Outcome};

/// How rows are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum RowFormat {
    /// Comma-separated values with a header line.
    Csv,
    /// One JSON object per row.
    Jsonl,
    /// Aligned columns, for a terminal.
    Text,
}

/// What a file to simulate is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ModelKind {
    /// A solver dataset.
    Adm,
    /// A scene file (TOML).
    Scene,
}

/// The arguments of `mbexpr simulate`.
#[derive(clap::Args)]
pub struct Args {
    /// A solver dataset (.adm; an .acf beside it may give END and STEPS) or
    /// a scene file (.toml); `-` reads standard input (a dataset unless
    /// --kind scene).
    file: String,
    /// What the file is (by default its extension says).
    #[arg(long, value_enum)]
    kind: Option<ModelKind>,
    /// The end time (the run starts at 0).
    #[arg(long, allow_hyphen_values = true)]
    end: Option<f64>,
    /// Output steps: STEPS + 1 rows at equally spaced times from 0 to END.
    #[arg(long)]
    steps: Option<usize>,
    /// The integration method: radau (implicit, exact Jacobian) or dop853 (explicit).
    #[arg(long, default_value = "radau", value_parser = parse_method)]
    method: Method,
    /// Relative tolerance.
    #[arg(long, default_value_t = 1e-6, allow_hyphen_values = true)]
    rtol: f64,
    /// Absolute tolerance (default: RTOL * 1e-3).
    #[arg(long, allow_hyphen_values = true)]
    atol: Option<f64>,
    /// The largest step.
    #[arg(long, allow_hyphen_values = true)]
    hmax: Option<f64>,
    /// The most integration steps, accepted and rejected; past them the run stops with an error.
    #[arg(long, default_value_t = simulate::DEFAULT_MAX_STEPS)]
    max_steps: usize,
    /// Row format (default: csv on a pipe, text on a terminal).
    #[arg(long, value_enum)]
    format: Option<RowFormat>,
    /// List every located branch switch on standard error.
    #[arg(long)]
    events: bool,
    /// Draw the states against time into an SVG file.
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<String>,
}

fn parse_method(name: &str) -> Result<Method, String> {
    name.parse::<Method>().map_err(|error| error.to_string())
}

/// A model and the file it came from, for messages.
struct Source {
    path: String,
    text: String,
}

impl Source {
    /// `FILE:LINE:COL: message` with the line and a caret, for a problem at
    /// `place` (in the file or in one of `model`'s expressions).
    fn render(&self, model: Option<&Model>, error: &SimulateError) -> String {
        let message = error.to_string();
        match (error.place(), model) {
            (Place::File(span), _) => diagnostic(&self.path, &self.text, span, &message),
            (Place::Expression { expression, span }, Some(model)) => {
                let expression = &model.expressions[expression];
                let span = expression.file_span(span);
                let message = format!("{}: {message}", expression.label);
                diagnostic(&self.path, &self.text, span, &message)
            }
            _ => format!("{}: {message}\n", self.path),
        }
    }

    fn render_all(&self, model: Option<&Model>, errors: &[SimulateError]) -> Fatal {
        Fatal::input(
            errors
                .iter()
                .map(|error| self.render(model, error))
                .collect::<String>(),
        )
    }
}

/// Reads the model of `path` (`-`: standard input), reporting every problem
/// at its place.
fn read_model(path: &str, kind: Option<ModelKind>) -> Result<(Source, Model), Fatal> {
    let text = crate::check_cmd::read(path)
        .map_err(|message| Fatal::usage(format!("error: {message}")))?;
    let source = Source {
        path: path.to_string(),
        text,
    };
    let kind = kind.unwrap_or(if path.to_ascii_lowercase().ends_with(".toml") {
        ModelKind::Scene
    } else {
        ModelKind::Adm
    });
    let model = if kind == ModelKind::Scene {
        simulate::from_scene(&source.text).map_err(|errors| source.render_all(None, &errors))?
    } else {
        let kind = match FileKind::of_path(path) {
            Some(FileKind::Acf) => FileKind::Acf,
            Some(FileKind::Cmd) => {
                return Err(Fatal::usage(format!(
                    "error: {path}: an Adams View command file is not simulated: give a solver dataset (.adm) or a scene file (.toml)"
                )));
            }
            _ => FileKind::Adm,
        };
        let dataset = model::read(&source.text, kind);
        let report = model::check_model(&source.text, &dataset);
        if !report.problems.is_empty() {
            let texts: String = report
                .problems
                .iter()
                .map(|problem| {
                    diagnostic(
                        path,
                        &source.text,
                        problem.error.span(),
                        &problem.error.to_string(),
                    )
                })
                .collect();
            return Err(Fatal::input(format!(
                "{texts}{path}: the model does not check: nothing simulated\n"
            )));
        }
        let mut model = simulate::from_dataset(&dataset, &report)
            .map_err(|errors| source.render_all(None, &errors))?;
        model.run = commands_beside(path)?;
        model
    };
    Ok((source, model))
}

/// END and STEPS from `SIMULATE/DYNAMIC` in an `.acf` beside the dataset.
fn commands_beside(path: &str) -> Result<Option<(f64, usize)>, Fatal> {
    let commands = Path::new(path).with_extension("acf");
    if path == "-" || path.to_ascii_lowercase().ends_with(".acf") || !commands.exists() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&commands).map_err(|error| {
        Fatal::usage(format!(
            "error: cannot read {}: {error}",
            commands.display()
        ))
    })?;
    let dataset = model::read(&text, FileKind::Acf);
    Ok(simulate::run_settings(&dataset).map(|(end, steps, _)| (end, steps)))
}

/// A progress bar on standard error, shown once a run has taken a second
/// (and only on a terminal).
struct Progress {
    bar: Option<indicatif::ProgressBar>,
    started: Instant,
    end: f64,
}

impl Progress {
    fn new(end: f64) -> Progress {
        Progress {
            bar: None,
            started: Instant::now(),
            end,
        }
    }

    fn at(&mut self, time: f64) {
        if self.bar.is_none()
            && std::io::stderr().is_terminal()
            && self.started.elapsed() > Duration::from_secs(1)
        {
            let bar = indicatif::ProgressBar::new(1000);
            bar.set_style(
                indicatif::ProgressStyle::with_template("{bar:40} t = {msg} {elapsed}")
                    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            bar.set_position((1000.0 * time / self.end) as u64);
            bar.set_message(format!("{time:.6}"));
        }
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// Runs `mbexpr simulate`.
pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let (source, model) = read_model(&args.file, args.kind)?;
    let (end, steps) = match (args.end, args.steps, model.run) {
        (Some(end), Some(steps), _) => (end, steps),
        (end, steps, Some((file_end, file_steps))) => {
            (end.unwrap_or(file_end), steps.unwrap_or(file_steps))
        }
        _ => {
            return Err(Fatal::usage(
                "error: give --end and --steps (or, beside a dataset, an .acf with SIMULATE/DYNAMIC, END = ..., STEPS = ...; in a scene file, [simulate] end = ..., steps = ...)",
            ));
        }
    };
    let settings = Settings {
        method: args.method,
        end,
        steps,
        rtol: args.rtol,
        atol: args.atol.unwrap_or(args.rtol * 1e-3),
        h_max: args.hmax.unwrap_or(f64::INFINITY),
        max_steps: args.max_steps,
    };
    let mut stderr = std::io::stderr();
    for (note, span) in &model.notes {
        let _ = write!(
            stderr,
            "{}",
            diagnostic(&source.path, &source.text, *span, &format!("note: {note}"))
        );
    }
    let simulation =
        Simulation::new(&model).map_err(|errors| source.render_all(Some(&model), &errors))?;
    let columns = simulate::columns(&model);
    let format = args.format.unwrap_or(if std::io::stdout().is_terminal() {
        RowFormat::Text
    } else {
        RowFormat::Csv
    });
    let writer = Rows::new(format, &columns);
    // The header goes with the first row: a run refused before it writes none.
    let mut written: std::io::Result<()> = Ok(());
    let mut kept: Vec<Vec<f64>> = Vec::new();
    let mut progress = Progress::new(end);
    let result = simulation.run(&settings, |time, values| {
        progress.at(time);
        if args.plot.is_some() {
            let mut row = vec![time];
            row.extend_from_slice(values);
            kept.push(row);
        }
        written = if time == 0.0 {
            writer.header(out)
        } else {
            Ok(())
        }
        .and_then(|()| writer.row(out, time, values));
        written.is_ok()
    });
    progress.finish();
    written?;
    out.flush()?;
    let summary = result.map_err(|error| Fatal::input(source.render(Some(&model), &error)))?;
    if args.events {
        for event in &summary.events {
            let expression = &model.expressions[event.expression];
            let span = expression.file_span(event.span);
            let at = mbexpr::Location::of(&source.text, span.start);
            let _ = writeln!(
                stderr,
                "event t = {}: {} at {}:{}:{} ({}): {} -> {}",
                Shown(event.time),
                event.function,
                source.path,
                at.line,
                at.column,
                expression.label,
                event.from,
                event.to
            );
        }
    }
    let stats = summary.stats;
    let _ = writeln!(
        stderr,
        "{}: t = 0 .. {}, {}: {} ({} rejected), {}, {}, {}, {}, {:.6} s",
        source.path,
        Shown(end),
        settings.method,
        Counted(stats.steps, "step"),
        stats.rejected,
        Counted(stats.rhs_evaluations, "right-hand side"),
        Counted(stats.jacobian_evaluations, "jacobian"),
        Counted(stats.lu_decompositions, "lu decomposition"),
        Counted(summary.events.len(), "event"),
        summary.wall_time.as_secs_f64()
    );
    if let Some(from) = summary.stiff_from {
        let _ = writeln!(
            stderr,
            "warning: the run is stiff from t = {}: DOP853's steps are held there by stability, not accuracy; --method radau takes far fewer",
            Shown(from)
        );
    }
    if let Some(path) = &args.plot {
        plot_states(path, &columns, &kept, &summary)
            .map_err(|message| Fatal::input(format!("error: --plot {path}: {message}\n")))?;
    }
    Ok(Outcome::Success)
}

/// Writes rows in one of the formats.
struct Rows<'c> {
    format: RowFormat,
    columns: &'c [String],
}

impl<'c> Rows<'c> {
    fn new(format: RowFormat, columns: &'c [String]) -> Rows<'c> {
        Rows { format, columns }
    }

    fn header(&self, out: &mut impl Write) -> std::io::Result<()> {
        match self.format {
            RowFormat::Csv => writeln!(out, "{}", self.columns.join(",")),
            RowFormat::Text => {
                for name in self.columns {
                    write!(out, "{name:>24}")?;
                }
                writeln!(out)
            }
            RowFormat::Jsonl => Ok(()),
        }
    }

    fn row(&self, out: &mut impl Write, time: f64, values: &[f64]) -> std::io::Result<()> {
        match self.format {
            RowFormat::Csv => {
                write!(out, "{}", Shown(time))?;
                for value in values {
                    write!(out, ",{}", Shown(*value))?;
                }
                writeln!(out)
            }
            RowFormat::Text => {
                write!(out, "{:>24}", Shown(time))?;
                for value in values {
                    write!(out, "{:>24}", Shown(*value))?;
                }
                writeln!(out)
            }
            RowFormat::Jsonl => {
                let mut object = serde_json::Map::new();
                for (name, value) in self
                    .columns
                    .iter()
                    .zip(std::iter::once(&time).chain(values))
                {
                    object.insert(name.clone(), serde_json::json!(value));
                }
                writeln!(out, "{}", serde_json::Value::Object(object))
            }
        }
    }
}

/// Up to how many rows a plot of a run draws each row as a dot.
const MAX_DOTTED_ROWS: usize = 250;

/// The states that change over the run, one panel each, with the switches
/// marked.
fn plot_states(
    path: &str,
    columns: &[String],
    rows: &[Vec<f64>],
    summary: &simulate::Summary,
) -> Result<(), String> {
    let curves: Vec<Curve> = (1..columns.len())
        .filter(|&column| {
            let first = rows.first().map(|row| row[column]);
            rows.iter().any(|row| Some(row[column]) != first)
        })
        .filter(|&column| !columns[column].contains(".q"))
        .take(8)
        .map(|column| Curve {
            label: columns[column].clone(),
            segments: vec![rows.iter().map(|row| (row[0], row[column])).collect()],
        })
        .collect();
    if curves.is_empty() {
        return Err("no state changes over the run".to_string());
    }
    let mut marks: Vec<f64> = summary.events.iter().map(|event| event.time).collect();
    marks.dedup();
    let range = (
        rows.first().map_or(0.0, |row| row[0]),
        rows.last().map_or(0.0, |row| row[0]),
    );
    let plot = Plot {
        curves,
        marks,
        gaps: Vec::new(),
        failed: 0,
        first_failure: None,
        sampled: rows.len(),
        range,
        // The curves join the output rows only: what happens between two
        // rows (a contact force's peak) is not drawn, and the axis says so.
        note: Some(format!(
            "through the {}; --steps for finer curves",
            Counted(rows.len(), "output row")
        )),
        dots: rows.len() <= MAX_DOTTED_ROWS,
    };
    render_svg(path, "time", &plot)
}
