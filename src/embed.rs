//! What the C API ([`crate::ffi`]) and the Python package (`python/`)
//! share, in safe Rust: an expression compiled with the names of its inputs
//! ([`Expression`]), evaluated at one point or in bulk over columns of
//! points on a pool of threads of this process ([`Expression::evaluate_bulk`]);
//! a model file checked ([`check_model_file`]) or loaded and simulated
//! ([`LoadedModel`]). Every error is a [`Located`]: a message with the line
//! and column it speaks of, in the expression or in the model's file.

use std::sync::{Arc, Mutex};

use rayon::prelude::*;

use crate::check::CheckError;
use crate::compile::CompileError;
use crate::eval::{EvalError, Evaluation, Order};
use crate::integrate::Method;
use crate::model::{self, FileKind};
use crate::simulate::{self, Model, Place, Settings, SimulateError, Simulation, Summary, Unread};
use crate::span::{LineIndex, Location, Span};
use crate::{Program, Shown};

/// A message and the place it speaks of (line and column from 1; both 0
/// when it speaks of no place, as for a setting out of range).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Located {
    /// What is wrong and what to do, lower-case, no trailing period.
    pub message: String,
    /// The line, from 1 (0: no place).
    pub line: usize,
    /// The column in characters, from 1 (0: no place).
    pub column: usize,
}

impl Located {
    /// `message` at the start of `span` in `text`.
    pub fn at(text: &str, span: Span, message: String) -> Located {
        let Location { line, column } = Location::of(text, span.start);
        Located {
            message,
            line,
            column,
        }
    }

    /// The first of `errors` (never empty), its message saying how many
    /// more there are.
    pub fn first_of(errors: Vec<Located>) -> Located {
        let more = errors.len().saturating_sub(1);
        let mut first = errors
            .into_iter()
            .next()
            .unwrap_or_else(|| Located::nowhere("no error".to_string()));
        if more > 0 {
            first.message += &format!(" (and {more} more)");
        }
        first
    }

    /// `message` with no place.
    pub fn nowhere(message: String) -> Located {
        Located {
            message,
            line: 0,
            column: 0,
        }
    }
}

impl std::fmt::Display for Located {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line == 0 {
            f.write_str(&self.message)
        } else {
            write!(f, "{}:{}: {}", self.line, self.column, self.message)
        }
    }
}

impl std::error::Error for Located {}

/// Every error of a stage at its place in `text`.
fn placed<E: std::fmt::Display>(text: &str, errors: &[E], span: fn(&E) -> Span) -> Vec<Located> {
    errors
        .iter()
        .map(|error| Located::at(text, span(error), error.to_string()))
        .collect()
}

/// An expression compiled for named inputs: immutable, shared freely
/// between threads.
#[derive(Clone, Debug)]
pub struct Expression {
    text: String,
    program: Program,
}

/// The points a bulk evaluation handles in one piece of work.
const CHUNK: usize = 1024;

impl Expression {
    /// Parses, checks and compiles `text` for inputs named `inputs`; the
    /// first problem in source order is the error (with how many more there
    /// are; [`Expression::compile_all`] gives every one).
    pub fn compile<S: AsRef<str>>(text: &str, inputs: &[S]) -> Result<Expression, Located> {
        Expression::compile_all(text, inputs).map_err(Located::first_of)
    }

    /// Parses, checks and compiles `text` for inputs named `inputs`; the
    /// error is every problem of the first stage that found any (a syntax
    /// error, else the checker's, else the compiler's), in source order.
    pub fn compile_all<S: AsRef<str>>(
        text: &str,
        inputs: &[S],
    ) -> Result<Expression, Vec<Located>> {
        // Names are read in any case, so two that differ only in case are
        // one input given twice.
        for (index, name) in inputs.iter().enumerate() {
            let name = name.as_ref();
            if let Some(first) = inputs[..index]
                .iter()
                .position(|other| other.as_ref().eq_ignore_ascii_case(name))
            {
                return Err(vec![Located::nowhere(format!(
                    "input {} ({name:?}) repeats input {} ({:?}): names are read in any case, so give each input once",
                    index + 1,
                    first + 1,
                    inputs[first].as_ref()
                ))]);
            }
        }
        let tree = crate::parse(text)
            .map_err(|error| vec![Located::at(text, error.span(), error.to_string())])?;
        let checked =
            crate::check(&tree).map_err(|errors| placed(text, &errors, CheckError::span))?;
        let program = crate::compile(&checked, inputs)
            .map_err(|errors| placed(text, &errors, CompileError::span))?;
        Ok(Expression {
            text: text.to_string(),
            program,
        })
    }

    /// The text it was compiled from.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The names of its inputs, in the order their values are given.
    pub fn inputs(&self) -> &[String] {
        self.program.inputs()
    }

    /// The compiled program.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// An evaluation error placed in the expression's text.
    fn locate(&self, error: &EvalError) -> Located {
        Located::at(&self.text, error.span(), error.to_string())
    }

    /// The value, and for `order` the gradient and Hessian in the inputs
    /// `wrt` (indices into [`Expression::inputs`]), at `point`.
    pub fn evaluate(
        &self,
        point: &[f64],
        wrt: &[usize],
        order: Order,
    ) -> Result<Evaluation, Located> {
        self.check_directions(wrt)?;
        self.program
            .evaluate(point, wrt, order)
            .map_err(|error| self.locate(&error))
    }

    /// Refuses a direction that is not an input or is named twice.
    fn check_directions(&self, wrt: &[usize]) -> Result<(), Located> {
        let count = self.inputs().len();
        for (position, &direction) in wrt.iter().enumerate() {
            if direction >= count {
                let inputs = if count == 1 { "input" } else { "inputs" };
                return Err(Located::nowhere(format!(
                    "derivative direction {direction} is not an input: the expression has {count} {inputs}, numbered from 0"
                )));
            }
            if wrt[..position].contains(&direction) {
                return Err(Located::nowhere(format!(
                    "derivative direction {direction} ({}) is asked for twice",
                    self.inputs()[direction]
                )));
            }
        }
        Ok(())
    }

    /// Evaluates at `n` points given as one column per input (structure of
    /// arrays: `columns[i][p]` is input `i` at point `p`), on `threads`
    /// threads (0: every core; 1: the calling thread alone). `out` receives
    /// per point the value, the gradient in `wrt` (`wrt.len()` entries) for
    /// [`Order::Gradient`] and beyond, the Hessian (`wrt.len()²`, row by
    /// row) for [`Order::Hessian`], and a status: 0, or 1 where the point
    /// cannot be evaluated (a domain error, an overflow, an input that is
    /// not finite: its entries are then 0; [`Expression::evaluate`] at that
    /// point says why). Returns the number of points that failed.
    ///
    /// The threads are a pool of this process, built again in a process
    /// forked from it, so a fork after a bulk evaluation does not hang.
    pub fn evaluate_bulk(
        &self,
        columns: &[&[f64]],
        wrt: &[usize],
        order: Order,
        out: Bulk<'_>,
        threads: usize,
    ) -> Result<usize, Located> {
        self.check_directions(wrt)?;
        let threads = thread_count(threads)?;
        let n = out.status.len();
        let inputs = self.inputs().len();
        if columns.len() != inputs {
            return Err(Located::nowhere(format!(
                "the expression has {inputs} inputs, but {} columns are given",
                columns.len()
            )));
        }
        if let Some(column) = columns.iter().position(|column| column.len() < n) {
            return Err(Located::nowhere(format!(
                "column {column} ({}) has {} points, fewer than {n}",
                self.inputs()[column],
                columns[column].len()
            )));
        }
        let k = wrt.len();
        let widths = [
            1,
            if order >= Order::Gradient { k } else { 0 },
            if order >= Order::Hessian { k * k } else { 0 },
        ];
        for (name, slice, width) in [
            ("values", out.values.len(), widths[0]),
            ("gradients", out.gradients.len(), widths[1]),
            ("hessians", out.hessians.len(), widths[2]),
        ] {
            if slice < n * width {
                return Err(Located::nowhere(format!(
                    "the {name} buffer holds {slice} numbers, fewer than the {} that {n} points need",
                    n * width
                )));
            }
        }
        // A program whose results continue from point to point (AX, AY,
        // AZ through ±π) runs its points in order, in one piece.
        let chunk = if self.program.continues_from_point_to_point() {
            n.max(1)
        } else {
            CHUNK
        };
        let mut pieces = Vec::with_capacity(n.div_ceil(chunk));
        let (mut values, mut gradients, mut hessians, mut status) =
            (out.values, out.gradients, out.hessians, out.status);
        let mut start = 0;
        while start < n {
            let len = chunk.min(n - start);
            let (v, rest_v) = std::mem::take(&mut values).split_at_mut(len);
            let (g, rest_g) = std::mem::take(&mut gradients).split_at_mut(len * widths[1]);
            let (h, rest_h) = std::mem::take(&mut hessians).split_at_mut(len * widths[2]);
            let (s, rest_s) = std::mem::take(&mut status).split_at_mut(len);
            (values, gradients, hessians, status) = (rest_v, rest_g, rest_h, rest_s);
            pieces.push(Piece {
                start,
                out: Bulk {
                    values: v,
                    gradients: g,
                    hessians: h,
                    status: s,
                },
            });
            start += len;
        }
        let run = |piece: Piece<'_>| self.run_piece(columns, wrt, order, piece);
        let failed = if threads == 1 || pieces.len() <= 1 {
            pieces.into_iter().map(run).sum()
        } else {
            pool(threads)?.install(|| pieces.into_par_iter().map(run).sum())
        };
        Ok(failed)
    }

    /// Evaluates the points of one piece on one evaluator.
    fn run_piece(
        &self,
        columns: &[&[f64]],
        wrt: &[usize],
        order: Order,
        piece: Piece<'_>,
    ) -> usize {
        let Piece { start, out } = piece;
        if order == Order::Value {
            return self
                .program
                .evaluator::<f64>()
                .values_of_columns(columns, start, out.values, out.status);
        }
        let k = wrt.len();
        let mut point = vec![0.0; columns.len()];
        let mut failed = 0;
        let load = |p: usize, point: &mut Vec<f64>| {
            for (value, column) in point.iter_mut().zip(columns) {
                *value = column[start + p];
            }
        };
        self.program.run().with_evaluator(wrt, order, |evaluate| {
            for p in 0..out.status.len() {
                load(p, &mut point);
                let gradient = &mut out.gradients[p * k..(p + 1) * k];
                let hessian = if order == Order::Hessian {
                    &mut out.hessians[p * k * k..(p + 1) * k * k]
                } else {
                    &mut []
                };
                match evaluate(&point) {
                    Ok(result) => {
                        out.status[p] = 0;
                        out.values[p] = result.value;
                        if let Some(g) = &result.gradient {
                            gradient.copy_from_slice(g.as_slice());
                        }
                        if let Some(h) = &result.hessian {
                            // nalgebra stores by column; the Hessian is symmetric.
                            hessian.copy_from_slice(h.as_slice());
                        }
                    }
                    Err(_) => {
                        failed += 1;
                        out.status[p] = 1;
                        out.values[p] = 0.0;
                        gradient.fill(0.0);
                        hessian.fill(0.0);
                    }
                }
            }
        });
        failed
    }
}

/// Where a bulk evaluation writes: per point a value, `k` gradient entries,
/// `k²` Hessian entries (empty slices when not asked for) and a status.
pub struct Bulk<'o> {
    /// One value per point.
    pub values: &'o mut [f64],
    /// `k` entries per point, for [`Order::Gradient`] and [`Order::Hessian`].
    pub gradients: &'o mut [f64],
    /// `k²` entries per point, row by row, for [`Order::Hessian`].
    pub hessians: &'o mut [f64],
    /// 0 where the point was evaluated, 1 where it failed; its length is
    /// the number of points.
    pub status: &'o mut [i32],
}

/// The points from `start` on, and where their results go.
struct Piece<'o> {
    start: usize,
    out: Bulk<'o>,
}

/// The thread pools of bulk evaluation, by process id and size. A child
/// forked after a pool started has none of its threads: it builds its own
/// (the parent's are forgotten, never dropped, since their threads are not
/// there to be told).
static POOLS: Mutex<Vec<(u32, usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());

/// The most threads a bulk evaluation starts for each core: more only
/// share the cores, and each count's pool is kept for the process's life.
const MOST_THREADS_PER_CORE: usize = 16;

/// How many threads a bulk evaluation asked for `threads` starts (0: one a
/// core), or the error that says how many it may.
fn thread_count(threads: usize) -> Result<usize, Located> {
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let most = MOST_THREADS_PER_CORE * cores;
    match threads {
        0 => Ok(cores),
        threads if threads > most => Err(Located::nowhere(format!(
            "at most {most} threads ({MOST_THREADS_PER_CORE} a core on this machine's {cores}), not {threads}: give 0 for one a core"
        ))),
        threads => Ok(threads),
    }
}

/// The pool of `threads` threads of this process.
fn pool(threads: usize) -> Result<Arc<rayon::ThreadPool>, Located> {
    let process = std::process::id();
    let mut pools = POOLS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if pools.iter().any(|(owner, ..)| *owner != process) {
        for stale in std::mem::take(&mut *pools) {
            if stale.0 == process {
                pools.push(stale);
            } else {
                std::mem::forget(stale);
            }
        }
    }
    if let Some((.., pool)) = pools.iter().find(|(_, size, _)| *size == threads) {
        return Ok(Arc::clone(pool));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|error| Located::nowhere(format!("cannot start {threads} threads: {error}")))?;
    let pool = Arc::new(pool);
    pools.push((process, threads, Arc::clone(&pool)));
    Ok(pool)
}

/// One diagnostic of a checked model file.
pub type Diagnostic = Located;

/// Reads a file's bytes as text (UTF-8, else Windows-1252, or UTF-16 by its
/// byte-order mark; docs/encoding.md).
fn read_text(path: &str) -> Result<String, Located> {
    let bytes = std::fs::read(path)
        .map_err(|error| Located::nowhere(format!("cannot read {path}: {error}")))?;
    Ok(model::decode_owned(bytes).0)
}

/// Checks the model file at `path` (a solver dataset, a command file, an
/// Adams View command file, or a scene file `.toml`): every problem at its
/// line and column, in file order; empty when it checks. The error is for
/// a file that cannot be read or is not a model file.
pub fn check_model_file(path: &str) -> Result<Vec<Diagnostic>, Located> {
    let text = read_text(path)?;
    if simulate::is_scene_path(path) {
        return Ok(match simulate::from_scene(&text) {
            Ok(_) => Vec::new(),
            Err(errors) => errors
                .iter()
                .map(|error| locate(&text, None, error))
                .collect(),
        });
    }
    let kind = FileKind::detect(path, &text).ok_or_else(|| {
        Located::nowhere(format!(
            "{path} is not a model file: give a solver dataset (.adm), a command file (.acf, .cmd) or a scene file (.toml)"
        ))
    })?;
    let dataset = model::read(&text, kind);
    Ok(placed_problems(
        &text,
        &model::check_model(&text, &dataset).problems,
    ))
}

/// The problems of a checked model file at their places.
fn placed_problems(text: &str, problems: &[model::Problem]) -> Vec<Diagnostic> {
    let lines = LineIndex::new(text);
    problems
        .iter()
        .map(|problem| {
            let Location { line, column } = lines.location(problem.error.span().start);
            Located {
                message: problem.error.to_string(),
                line,
                column,
            }
        })
        .collect()
}

/// A simulation error placed in the model's file.
fn locate(text: &str, model: Option<&Model>, error: &SimulateError) -> Located {
    let message = error.to_string();
    match (error.place(), model) {
        (Place::File(span), _) => Located::at(text, span, message),
        (Place::Expression { expression, span }, Some(model)) => {
            let expression = &model.expressions[expression];
            let message = format!("{}: {message}", expression.label);
            Located::at(text, expression.file_span(span), message)
        }
        _ => Located::nowhere(message),
    }
}

pub use crate::simulate::ModelFormat;

/// A model read from its file or text, ready to simulate.
pub struct LoadedModel {
    text: String,
    model: Model,
    /// Why the `.acf` beside the dataset gives no run (a command mbexpr
    /// does not carry out): the error of a run that needs its settings.
    run_problem: Option<String>,
}

/// How to run a simulation; `None` takes the model's own (END and STEPS
/// of a `SIMULATE/DYNAMIC` in an `.acf` beside the dataset, `[simulate]`
/// of a scene file) or the default.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOptions {
    /// The method ([`Method::Auto`] by default, as on the command line).
    pub method: Method,
    /// The end time.
    pub end: Option<f64>,
    /// The number of output steps.
    pub steps: Option<usize>,
    /// The relative tolerance.
    pub rtol: f64,
    /// The absolute tolerance (default a thousandth of `rtol`).
    pub atol: Option<f64>,
    /// The largest step (default none).
    pub h_max: Option<f64>,
    /// The most integration steps (default [`simulate::DEFAULT_MAX_STEPS`]).
    pub max_steps: Option<usize>,
    /// Start from a static equilibrium (default: as the `.acf` says).
    pub statics: Option<bool>,
    /// Radau5 steps onto each output time (default: as the `.acf` says,
    /// else `false`): [`simulate::Settings::land_on_outputs`].
    pub land_on_outputs: Option<bool>,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            method: Method::Auto,
            end: None,
            steps: None,
            rtol: 1e-6,
            atol: None,
            h_max: None,
            max_steps: None,
            statics: None,
            land_on_outputs: None,
        }
    }
}

impl RunOptions {
    /// Refuses options that no run can take, before any model is read (as
    /// a sweep does once, before its first run): what
    /// [`LoadedModel::simulate`] refuses of them whatever the model. An end
    /// time or a number of output steps left to the model is checked with
    /// each model, by its run.
    pub fn check(&self) -> Result<(), Located> {
        let settings = self.settings(self.end.unwrap_or(1.0), self.steps.unwrap_or(1), None);
        match self.end {
            Some(_) => settings.check(),
            None => settings.check_but_end(),
        }
        .map_err(|error| Located::nowhere(error.to_string()))
    }

    /// The settings of a run of `model` to `end` in `steps` output steps:
    /// these options, and the model's own where they leave a choice (with
    /// no model, the defaults).
    fn settings(&self, end: f64, steps: usize, model: Option<&Model>) -> Settings {
        Settings {
            method: self.method,
            end,
            steps,
            rtol: self.rtol,
            atol: self.atol.unwrap_or(self.rtol * 1e-3),
            h_max: self.h_max.unwrap_or(f64::INFINITY),
            max_steps: self.max_steps.unwrap_or(simulate::DEFAULT_MAX_STEPS),
            statics: self
                .statics
                .unwrap_or(model.is_some_and(|model| model.statics)),
            land_on_outputs: self
                .land_on_outputs
                .unwrap_or(model.is_some_and(|model| model.land_on_outputs)),
        }
    }
}

/// A located branch switch of a run, placed in the model's file.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedEvent {
    /// When.
    pub time: f64,
    /// The function (`BISTOP`) or `IF`.
    pub function: String,
    /// The branch it leaves.
    pub from: String,
    /// The branch it takes.
    pub to: String,
    /// Where the call is in the file.
    pub place: Located,
}

/// What a run cost and found.
pub struct Ran {
    /// The integrator's counts, the wall time, whether the callback stopped it.
    pub summary: Summary,
    /// Every branch switch, in time order, at its place in the file.
    pub events: Vec<PlacedEvent>,
}

impl LoadedModel {
    /// Reads the model of the file at `path`: a scene file (`.toml`), a
    /// solver dataset, with the END and STEPS of an `.acf` beside it, or an
    /// Adams View command file (`.cmd`), with those of its last transient
    /// simulation.
    pub fn from_path(path: &str) -> Result<LoadedModel, Vec<Located>> {
        let (format, kind) = simulate::format_of_path(path, None)
            .map_err(|message| vec![Located::nowhere(message)])?;
        let text = read_text(path).map_err(|error| vec![error])?;
        let mut loaded = LoadedModel::read(text, format, kind)?;
        if format == ModelFormat::Dataset && kind != FileKind::Cmd {
            match simulate::run_settings_beside(path) {
                Ok(run) => {
                    loaded.model.run = run.map(|run| (run.end, run.steps));
                    loaded.model.statics = run.is_some_and(|run| run.statics);
                    loaded.model.land_on_outputs = run.is_some_and(|run| run.land_on_outputs);
                }
                Err(problem) => loaded.run_problem = Some(problem.to_string()),
            }
        }
        Ok(loaded)
    }

    /// Reads a model from its text.
    pub fn from_text(text: String, format: ModelFormat) -> Result<LoadedModel, Vec<Located>> {
        LoadedModel::read(text, format, FileKind::Adm)
    }

    /// Reads a model from its text, a dataset read as `kind`.
    fn read(
        text: String,
        format: ModelFormat,
        kind: FileKind,
    ) -> Result<LoadedModel, Vec<Located>> {
        match simulate::from_text(&text, format, kind) {
            Ok(model) => Ok(LoadedModel {
                text,
                model,
                run_problem: None,
            }),
            Err(Unread::Unchecked(problems)) => Err(placed_problems(&text, &problems)),
            Err(Unread::Refused(errors)) => Err(errors
                .iter()
                .map(|error| locate(&text, None, error))
                .collect()),
        }
    }

    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The names of a run's columns, `time` first.
    pub fn columns(&self) -> Vec<String> {
        simulate::columns(&self.model)
    }

    /// The settings of a run with `options`.
    pub fn settings(&self, options: &RunOptions) -> Result<Settings, Located> {
        let (end, steps) = match (options.end, options.steps, self.model.run) {
            (Some(end), Some(steps), _) => (end, steps),
            (end, steps, Some((file_end, file_steps))) => {
                (end.unwrap_or(file_end), steps.unwrap_or(file_steps))
            }
            _ if let Some(problem) = &self.run_problem => {
                return Err(Located::nowhere(problem.clone()));
            }
            (Some(end), None, None) => (end, Settings::default().steps),
            _ => {
                return Err(Located::nowhere(
                    "give the end time (and the number of output steps), or a SIMULATE/DYNAMIC command with END and STEPS in an .acf beside the dataset, or [simulate] end and steps in a scene file".to_string(),
                ));
            }
        };
        Ok(options.settings(end, steps, Some(&self.model)))
    }

    /// Runs the model with `options`, calling `row` with the time and the
    /// values of the columns after `time` at each output time, as the run
    /// reaches it; `row` returns `false` to stop the run there.
    pub fn simulate(
        &self,
        options: &RunOptions,
        row: impl FnMut(f64, &[f64]) -> bool,
    ) -> Result<Ran, Located> {
        let settings = self.settings(options)?;
        let simulation = Simulation::new(&self.model).map_err(|errors| {
            Located::first_of(
                errors
                    .iter()
                    .map(|error| locate(&self.text, Some(&self.model), error))
                    .collect(),
            )
        })?;
        let summary = simulation
            .run(&settings, row)
            .map_err(|error| locate(&self.text, Some(&self.model), &error))?;
        let events = summary
            .events
            .iter()
            .map(|event| {
                let message = format!(
                    "{} switches from {} to {} at t = {} in {}",
                    event.function,
                    event.from,
                    event.to,
                    Shown(event.time),
                    event.label
                );
                PlacedEvent {
                    time: event.time,
                    function: event.function.clone(),
                    from: event.from.clone(),
                    to: event.to.clone(),
                    place: match event.place.file_span(&self.model) {
                        Some(span) => Located::at(&self.text, span, message),
                        None => Located::nowhere(message),
                    },
                }
            })
            .collect();
        Ok(Ran { summary, events })
    }
}
