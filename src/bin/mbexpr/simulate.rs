//! `mbexpr simulate FILE`: integrate a dataset's (or a scene file's) DIFF
//! equations and free parts in time, rows of states at equally spaced
//! times on standard output, each written and flushed as soon as it is
//! computed; statistics (and, on request, every branch switch) on standard
//! error, as text or JSON. SIGINT and SIGTERM end the run at the next
//! step, every computed row written and the statistics printed.

use std::io::{IsTerminal, Write};
use std::ops::ControlFlow;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use clap::ValueEnum;
use mbexpr::integrate::Method;
use mbexpr::simulate::{
    self, CommandFileError, ErrorEstimate, Event, MethodChange, Model, ModelFormat, Place,
    Settings, SimulateError, Simulation, Sink, Summary, Unread,
};
use mbexpr::{Counted, Shown};
use serde_json::json;

use crate::support::files;
use crate::support::plotting::{Curve, Plot, check_svg_name, render_svg};
use crate::support::render::{diagnostic, diagnostics};
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

/// How the end statistics are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum StatsFormat {
    /// Lines of text.
    Text,
    /// One JSON object.
    Json,
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
    /// A solver dataset (.adm; an .acf beside it may give END and STEPS),
    /// an Adams View command file (.cmd; its last transient simulation
    /// gives END and STEPS) or a scene file (.toml); `-` reads standard
    /// input (a dataset unless --kind scene).
    file: String,
    /// What the file is (by default its extension says).
    #[arg(long, value_enum)]
    kind: Option<ModelKind>,
    /// Print the solver dataset an Adams View command file is read as (what View's File > Export > Adams Solver Dataset writes for it) and simulate nothing.
    #[arg(long)]
    dataset: bool,
    /// The end time (the run starts at 0).
    #[arg(long, allow_hyphen_values = true)]
    end: Option<f64>,
    /// Output steps: STEPS + 1 rows at equally spaced times from 0 to END.
    #[arg(long)]
    steps: Option<usize>,
    /// The integration method: auto (dop853 while the run is not stiff, radau while it is), radau (implicit, exact Jacobian) or dop853 (explicit).
    #[arg(long, default_value = "auto", value_parser = parse_method)]
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
    /// Start from a static equilibrium: the parts at rest where the forces balance, found from the initial conditions by Newton's method (as SIMULATE/STATICS before the dynamics in the .acf does).
    #[arg(long)]
    statics: bool,
    /// Radau5 steps onto each output time, as INTEGRATOR/INTERPOLATE = OFF in the .acf asks (Adams' default): its rows are then of the order of its steps, not of its continuous output (order 3 inside a step); by default the output times change neither the steps nor the rows.
    #[arg(long)]
    land_on_outputs: bool,
    /// Row format (default: csv on a pipe, text on a terminal).
    #[arg(long, value_enum)]
    format: Option<RowFormat>,
    /// List every located branch switch (and change of method) on standard error, as it is found, with how far a jointed model was off its joints there before assembly; with --format jsonl, one JSON object each.
    #[arg(long)]
    events: bool,
    /// Write every located branch switch (and change of method) into a file, one JSON object per line.
    #[arg(long, value_name = "FILE.jsonl")]
    events_file: Option<String>,
    /// How the end statistics are written on standard error.
    #[arg(long, value_enum, default_value = "text")]
    stats: StatsFormat,
    /// Run again at a hundredth of the tolerances and report, per column, the largest difference: the estimated global error.
    #[arg(long)]
    estimate_error: bool,
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

    /// Why the model was not read: the refusals, or the problems of a file
    /// that does not check (then that it does not, and `outcome`).
    fn unread(&self, unread: Unread, outcome: &str) -> Fatal {
        match unread {
            Unread::Refused(errors) => self.render_all(None, &errors),
            Unread::Unchecked(problems) => {
                let texts = diagnostics(
                    &self.path,
                    &self.text,
                    problems
                        .iter()
                        .map(|problem| (problem.error.span(), problem.error.to_string())),
                );
                Fatal::input(format!(
                    "{texts}{}: the model does not check: {outcome}\n",
                    self.path
                ))
            }
        }
    }

    /// Every error of `errors`, those placed in the file in one pass over
    /// it (in file order), then those placed nowhere.
    fn render_all(&self, model: Option<&Model>, errors: &[SimulateError]) -> Fatal {
        let mut placed = Vec::new();
        let mut nowhere = String::new();
        for error in errors {
            let message = error.to_string();
            match (error.place(), model) {
                (Place::File(span), _) => placed.push((span, message)),
                (Place::Expression { expression, span }, Some(model)) => {
                    let expression = &model.expressions[expression];
                    placed.push((
                        expression.file_span(span),
                        format!("{}: {message}", expression.label),
                    ));
                }
                _ => nowhere += &format!("{}: {message}\n", self.path),
            }
        }
        Fatal::input(diagnostics(&self.path, &self.text, placed) + &nowhere)
    }
}

/// Writes the solver dataset the View command file `path` is read as, its
/// notes on standard error.
fn write_dataset(path: &str, out: &mut impl Write) -> Result<Outcome, Fatal> {
    let (_, file_kind) = simulate::format_of_path(path, None)
        .map_err(|message| Fatal::usage(format!("error: {message}")))?;
    if file_kind != mbexpr::model::FileKind::Cmd {
        return Err(Fatal::usage(
            "error: --dataset writes the solver dataset of an Adams View command file (.cmd)",
        ));
    }
    let text = files::read(path).map_err(|message| Fatal::usage(format!("error: {message}")))?;
    let source = Source {
        path: path.to_string(),
        text,
    };
    let (dataset, notes) = simulate::view_dataset_text(&source.text)
        .map_err(|unread| source.unread(unread, "nothing written"))?;
    let notes = notes
        .into_iter()
        .map(|(note, span)| (span, format!("note: {note}")));
    let _ = write!(
        std::io::stderr(),
        "{}",
        diagnostics(path, &source.text, notes)
    );
    out.write_all(dataset.as_bytes()).map_err(Fatal::from)?;
    Ok(Outcome::Success)
}

/// Reads the model of `path` (`-`: standard input), reporting every problem
/// at its place.
fn read_model(
    path: &str,
    kind: Option<ModelKind>,
) -> Result<(Source, Model, Option<String>), Fatal> {
    let format = kind.map(|kind| match kind {
        ModelKind::Adm => ModelFormat::Dataset,
        ModelKind::Scene => ModelFormat::Scene,
    });
    let (format, file_kind) = simulate::format_of_path(path, format)
        .map_err(|message| Fatal::usage(format!("error: {message}")))?;
    let text = files::read(path).map_err(|message| Fatal::usage(format!("error: {message}")))?;
    let source = Source {
        path: path.to_string(),
        text,
    };
    let mut model = simulate::from_text(&source.text, format, file_kind)
        .map_err(|unread| source.unread(unread, "nothing simulated"))?;
    // Why the .acf gives no run: an error only for a run that needs it.
    let mut run_problem = None;
    if format == ModelFormat::Dataset && file_kind != mbexpr::model::FileKind::Cmd {
        match simulate::run_settings_beside(path) {
            Ok(run) => {
                model.run = run.map(|run| (run.end, run.steps));
                model.statics = run.is_some_and(|run| run.statics);
                model.land_on_outputs = run.is_some_and(|run| run.land_on_outputs);
            }
            Err(CommandFileError::Refused {
                path,
                text,
                problems,
            }) => run_problem = Some(diagnostics(&path, &text, problems)),
            Err(problem) => run_problem = Some(format!("error: {problem}\n")),
        }
    }
    Ok((source, model, run_problem))
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

/// The signal that asked the run to end (0: none yet).
static SIGNALLED: AtomicUsize = AtomicUsize::new(0);
/// A first signal has come: a second one ends the process at once.
static ARMED: AtomicBool = AtomicBool::new(false);

/// From now on SIGINT and SIGTERM ask the run to end at its next step
/// ([`SIGNALLED`]); a second one ends the process with 128 + its number.
fn catch_signals() -> std::io::Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use signal_hook::flag;
    for signal in [SIGINT, SIGTERM] {
        // The shutdown first: it acts only once the flag below is set.
        flag::register_conditional_shutdown(signal, 128 + signal, &ARMED)?;
        flag::register_usize(signal, &SIGNALLED, signal as usize)?;
        flag::register(signal, &ARMED)?;
    }
    Ok(())
}

/// The name of a signal `catch_signals` catches.
fn signal_name(signal: usize) -> &'static str {
    if signal == signal_hook::consts::SIGTERM as usize {
        "SIGTERM"
    } else {
        "SIGINT"
    }
}

/// Refuses an output file that cannot be written, before the run: its
/// folder must exist and the file be open for writing. A file that did not
/// exist is not left behind.
fn check_writable(option: &str, path: &str) -> Result<(), Fatal> {
    let existed = Path::new(path).exists();
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .map_err(|error| Fatal::usage(format!("error: {option} {path}: {error}")))?;
    if !existed {
        let _ = std::fs::remove_file(path);
    }
    Ok(())
}

/// Runs `mbexpr simulate`.
pub fn run(args: &Args, out: &mut impl Write) -> Result<Outcome, Fatal> {
    if args.dataset {
        return write_dataset(&args.file, out);
    }
    let (source, model, run_problem) = read_model(&args.file, args.kind)?;
    let (end, steps) = match (args.end, args.steps, model.run) {
        (Some(end), Some(steps), _) => (end, steps),
        _ if let Some(problem) = run_problem => {
            return Err(Fatal::usage(problem));
        }
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
        statics: args.statics || model.statics,
        land_on_outputs: args.land_on_outputs || model.land_on_outputs,
    };
    // Every output is checked before the first step.
    settings
        .check_for(&model)
        .map_err(|error| Fatal::input(source.render(Some(&model), &error)))?;
    if let Some(path) = &args.plot {
        check_svg_name(path)
            .map_err(|message| Fatal::usage(format!("error: --plot {path}: {message}")))?;
        check_writable("--plot", path)?;
    }
    let events_file = match &args.events_file {
        Some(path) => Some(
            std::fs::File::create(path)
                .map_err(|error| Fatal::usage(format!("error: --events-file {path}: {error}")))?,
        ),
        None => None,
    };
    let mut stderr = std::io::stderr();
    let notes = model
        .notes
        .iter()
        .map(|(note, span)| (*span, format!("note: {note}")));
    let _ = write!(stderr, "{}", diagnostics(&source.path, &source.text, notes));
    let simulation =
        Simulation::new(&model).map_err(|errors| source.render_all(Some(&model), &errors))?;
    let columns = simulate::columns(&model);
    let format = args.format.unwrap_or(if std::io::stdout().is_terminal() {
        RowFormat::Text
    } else {
        RowFormat::Csv
    });
    catch_signals()?;
    let mut sink = Written {
        out,
        rows: Rows::new(format, &columns),
        written: Ok(()),
        count: 0,
        kept: Vec::new(),
        keep: args.plot.is_some() || args.estimate_error,
        progress: Progress::new(end),
        events: Events {
            source: &source,
            model: &model,
            columns: &columns,
            on_stderr: args.events.then_some(format),
            file: events_file.map(std::io::BufWriter::new),
        },
    };
    let result = simulation.run_into(&settings, &mut sink);
    sink.progress.finish();
    sink.written?;
    sink.events.finish()?;
    // A run that fails keeps its rows: the plot draws those it has.
    let plot_kept = |marks: &[f64]| match &args.plot {
        Some(path) => plot_states(path, &columns, &sink.kept, marks)
            .err()
            .map(|message| format!("error: --plot {path}: {message}\n")),
        None => None,
    };
    let summary = match result {
        Ok(summary) => summary,
        Err(error) => {
            let failed = plot_kept(&[]).unwrap_or_default();
            return Err(Fatal::input(source.render(Some(&model), &error) + &failed));
        }
    };
    let marks: Vec<f64> = summary.events.iter().map(|event| event.time).collect();
    let signal = SIGNALLED.load(Ordering::SeqCst);
    let estimate = if args.estimate_error && signal == 0 {
        Some(
            simulation
                .estimate_error(&settings, &sink.kept)
                .map_err(|error| Fatal::input(source.render(Some(&model), &error)))?,
        )
    } else {
        None
    };
    let report = Report {
        path: &source.path,
        settings: &settings,
        summary: &summary,
        columns: &columns,
        estimate: estimate.as_ref(),
        signal,
        rows: sink.count,
        joints: model.joints.len(),
    };
    let _ = match args.stats {
        StatsFormat::Text => write!(stderr, "{}", report.text()),
        StatsFormat::Json => writeln!(stderr, "{}", report.json()),
    };
    let failed = plot_kept(&marks);
    if signal != 0 {
        return Err(Fatal::signalled(signal as u8));
    }
    match failed {
        Some(message) => Err(Fatal::input(message)),
        None => Ok(Outcome::Success),
    }
}

/// Where `mbexpr simulate` sends a run's results: each row written and
/// flushed at once (and kept for a plot or an error estimate), each event
/// written where asked.
struct Written<'a, W: Write> {
    out: &'a mut W,
    rows: Rows<'a>,
    /// The first failure to write a row, which stops the run.
    written: std::io::Result<()>,
    /// The rows written.
    count: usize,
    kept: Vec<Vec<f64>>,
    keep: bool,
    progress: Progress,
    events: Events<'a>,
}

impl<W: Write> Sink for Written<'_, W> {
    fn row(&mut self, time: f64, values: &[f64]) -> ControlFlow<()> {
        self.progress.at(time);
        if self.keep {
            self.kept.push([&[time], values].concat());
        }
        self.written = if self.count == 0 {
            self.rows.header(self.out)
        } else {
            Ok(())
        }
        .and_then(|()| self.rows.row(self.out, time, values))
        .and_then(|()| self.out.flush());
        if self.written.is_ok() {
            self.count += 1;
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(())
        }
    }

    fn event(&mut self, event: &Event) -> ControlFlow<()> {
        self.events.switch(event);
        ControlFlow::Continue(())
    }

    fn method_changed(&mut self, change: &MethodChange) {
        self.events.method(change);
    }

    fn stop_requested(&mut self) -> bool {
        SIGNALLED.load(Ordering::Relaxed) != 0
    }
}

/// Where events are written: standard error (text, or JSON under
/// `--format jsonl`) and a JSON-lines file.
struct Events<'a> {
    source: &'a Source,
    model: &'a Model,
    columns: &'a [String],
    on_stderr: Option<RowFormat>,
    file: Option<std::io::BufWriter<std::fs::File>>,
}

impl Events<'_> {
    fn switch(&mut self, event: &Event) {
        let span = event.place.file_span(self.model).unwrap_or_default();
        let at = mbexpr::Location::of(&self.source.text, span.start);
        let object = || {
            let state: serde_json::Map<String, serde_json::Value> = self.columns[1..]
                .iter()
                .zip(&event.values)
                .map(|(name, value)| (name.clone(), json!(value)))
                .collect();
            let mut object = json!({
                "time": event.time,
                "function": event.function,
                "file": self.source.path,
                "line": at.line,
                "column": at.column,
                "expression": event.label,
                "from": event.from,
                "to": event.to,
                "state": state,
            });
            if let Some(residuals) = event.residuals {
                object["residuals"] =
                    json!({"position": residuals.position, "velocity": residuals.velocity});
            }
            object
        };
        self.write(object, || {
            let assembled = event.residuals.map_or(String::new(), |residuals| {
                format!(
                    "; off the joints by {:.1e} (positions), {:.1e} (velocities) before assembly",
                    residuals.position, residuals.velocity
                )
            });
            format!(
                "event t = {}: {} at {}:{}:{} ({}): {} -> {}{assembled}",
                Shown(event.time),
                event.function,
                self.source.path,
                at.line,
                at.column,
                event.label,
                event.from,
                event.to
            )
        });
    }

    fn method(&mut self, change: &MethodChange) {
        self.write(
            || json!({"time": change.time, "method": {"from": change.from.to_string(), "to": change.to.to_string()}}),
            || format!("method t = {}: {} -> {}", Shown(change.time), change.from, change.to),
        );
    }

    /// One event, as JSON to the file and as `--format` says on standard
    /// error. A file that fails to take it is reported once at the end.
    fn write(&mut self, object: impl Fn() -> serde_json::Value, text: impl Fn() -> String) {
        if let Some(file) = &mut self.file {
            let _ = writeln!(file, "{}", object());
        }
        let line = match self.on_stderr {
            None => return,
            Some(RowFormat::Jsonl) => object().to_string(),
            Some(_) => text(),
        };
        let _ = writeln!(std::io::stderr(), "{line}");
    }

    fn finish(&mut self) -> std::io::Result<()> {
        match &mut self.file {
            Some(file) => file.flush(),
            None => Ok(()),
        }
    }
}

/// The end statistics of a run.
struct Report<'a> {
    path: &'a str,
    settings: &'a Settings,
    summary: &'a Summary,
    columns: &'a [String],
    estimate: Option<&'a ErrorEstimate>,
    /// The signal that ended the run (0: none).
    signal: usize,
    rows: usize,
    /// The number of joints of the model.
    joints: usize,
}

impl Report<'_> {
    fn text(&self) -> String {
        let (summary, stats) = (self.summary, self.summary.stats);
        let mut text = format!(
            "{}: t = 0 .. {}, {}: {} ({} rejected), {}, {}, {}, {}, {:.6} s\n",
            self.path,
            Shown(self.settings.end),
            self.settings.method,
            Counted(stats.steps, "step"),
            stats.rejected,
            Counted(stats.rhs_evaluations, "right-hand side"),
            Counted(stats.jacobian_evaluations, "jacobian"),
            Counted(stats.lu_decompositions, "lu decomposition"),
            Counted(summary.events.len(), "event"),
            summary.wall_time.as_secs_f64()
        );
        if !summary.method_changes.is_empty() {
            let changes: Vec<String> = summary
                .method_changes
                .iter()
                .map(|change| format!("{} at t = {}", change.to, Shown(change.time)))
                .collect();
            text += &format!("method changes: {}\n", changes.join(", "));
        }
        if self.joints > 0 {
            text += &format!(
                "constraints: {}; initial residuals {:.1e} (positions), {:.1e} (velocities) before assembly; largest after a step {:.1e}, {:.1e}; {}\n",
                Counted(self.joints, "joint"),
                summary.initial_residuals.position,
                summary.initial_residuals.velocity,
                summary.residuals.position,
                summary.residuals.velocity,
                Counted(summary.projections, "projection"),
            );
        }
        for trip in &summary.sensor_trips {
            text += &format!(
                "SENSOR/{} became active at t = {}{}\n",
                trip.sensor,
                Shown(trip.time),
                if trip.halted {
                    ": the run ends there"
                } else {
                    ""
                }
            );
        }
        if let Some(equilibrium) = summary.equilibrium {
            text += &format!(
                "static equilibrium: {}, largest acceleration left {:.1e}\n",
                Counted(equilibrium.iterations, "newton iteration"),
                equilibrium.residual
            );
        }
        if let Some(estimate) = self.estimate {
            let columns: Vec<String> = self.columns[1..]
                .iter()
                .zip(&estimate.largest)
                .map(|(name, error)| format!("{name} {:.1e}", error))
                .collect();
            text += &format!(
                "estimated error (largest difference from a run at rtol {}): {}\n",
                Shown(estimate.rtol),
                columns.join(", ")
            );
        }
        if let Some(from) = summary.stiff_from {
            text += &format!(
                "warning: the run is stiff from t = {}: DOP853's steps are held there by stability, not accuracy; --method radau or auto takes far fewer\n",
                Shown(from)
            );
        }
        if let Some(from) = stats.rounding_limited_from {
            text += &format!(
                "warning: {} from t = {} passed the error test only against the rounding of the accelerations (loads that cancel to rounding: a joint's reaction against forces or gravity far larger than the motion's): there the results are as accurate as double precision allows, not as rtol asks\n",
                Counted(stats.rounding_limited, "step"),
                Shown(from)
            );
        }
        if self.signal != 0 {
            text += &format!(
                "interrupted by {}: {} rows written\n",
                signal_name(self.signal),
                self.rows
            );
        }
        text
    }

    fn json(&self) -> serde_json::Value {
        let (summary, stats) = (self.summary, self.summary.stats);
        let estimate = self.estimate.map(|estimate| {
            let largest: serde_json::Map<String, serde_json::Value> = self.columns[1..]
                .iter()
                .zip(&estimate.largest)
                .map(|(name, error)| (name.clone(), json!(error)))
                .collect();
            json!({"rtol": estimate.rtol, "atol": estimate.atol, "largest": largest})
        });
        let changes: Vec<serde_json::Value> = summary
            .method_changes
            .iter()
            .map(|change| json!({"time": change.time, "from": change.from.to_string(), "to": change.to.to_string()}))
            .collect();
        json!({
            "file": self.path,
            "end": self.settings.end,
            "method": self.settings.method.to_string(),
            "rtol": self.settings.rtol,
            "atol": self.settings.atol,
            "steps": stats.steps,
            "rejected": stats.rejected,
            "rhs_evaluations": stats.rhs_evaluations,
            "rhs_failures": stats.rhs_failures,
            "jacobians": stats.jacobian_evaluations,
            "lu_decompositions": stats.lu_decompositions,
            "rounding_limited": stats.rounding_limited_from.map(|from| json!({
                "steps": stats.rounding_limited,
                "from": from,
            })),
            "events": summary.events.len(),
            "method_changes": changes,
            "stiff_from": summary.stiff_from,
            "wall_time": summary.wall_time.as_secs_f64(),
            "stopped": summary.stopped,
            "interrupted_by": (self.signal != 0).then(|| signal_name(self.signal)),
            "estimated_error": estimate,
            "constraints": (self.joints > 0).then(|| json!({
                "joints": self.joints,
                "initial_residuals": {"position": summary.initial_residuals.position, "velocity": summary.initial_residuals.velocity},
                "largest_residuals": {"position": summary.residuals.position, "velocity": summary.residuals.velocity},
                "projections": summary.projections,
            })),
            "sensors": summary.sensor_trips.iter().map(|trip| json!({
                "sensor": trip.sensor,
                "time": trip.time,
                "halted": trip.halted,
            })).collect::<Vec<_>>(),
            "static_equilibrium": summary.equilibrium.map(|equilibrium| json!({
                "iterations": equilibrium.iterations,
                "residual": equilibrium.residual,
            })),
        })
    }
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

/// The states that change over the run (or the part of it that ran), one
/// panel each, with the switches at `marks` marked; where none changes,
/// the first of them, flat.
fn plot_states(
    path: &str,
    columns: &[String],
    rows: &[Vec<f64>],
    marks: &[f64],
) -> Result<(), String> {
    let changes = |column: usize| {
        let first = rows.first().map(|row| row[column]);
        rows.iter().any(|row| Some(row[column]) != first)
    };
    let drawn: Vec<usize> = (1..columns.len())
        .filter(|&column| !columns[column].contains(".q"))
        .collect();
    let changing: Vec<usize> = drawn.iter().copied().filter(|&c| changes(c)).collect();
    let chosen = if changing.is_empty() { drawn } else { changing };
    let curves: Vec<Curve> = chosen
        .into_iter()
        .take(8)
        .map(|column| Curve {
            label: columns[column].clone(),
            segments: vec![rows.iter().map(|row| (row[0], row[column])).collect()],
        })
        .collect();
    if curves.is_empty() {
        return Err("the run has no state to draw".to_string());
    }
    let mut marks = marks.to_vec();
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
