//! `mbexpr._core`: the extension module of the Python package. It reaches
//! mbexpr only through the safe layer the C API shares
//! ([`mbexpr::embed`]) and the utility subroutines ([`mbexpr::utility`]),
//! and releases the GIL for every evaluation and run. The public API, with
//! broadcasting and its docstrings, is `mbexpr/__init__.py`.

use std::borrow::Cow;

use mbexpr::embed::{self, Bulk, Expression, LoadedModel, Located, ModelFormat, RunOptions};
use mbexpr::integrate::Method;
use mbexpr::{Order, utility};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// mimalloc keeps the memory a simulation frees for its next use
/// (BENCHMARKS.md, "The allocator"); the Rust side of the module only.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

create_exception!(
    _core,
    Error,
    PyValueError,
    "An expression, a model or a call that mbexpr refuses: `message`, and `line` and `column` (from 1) in the expression or the model's file, or None when it speaks of no place."
);

/// The Python exception of a located error.
fn raise(py: Python<'_>, located: &Located) -> PyErr {
    raise_all(py, std::slice::from_ref(located))
}

/// The Python exception of every error of a compilation or a load: its
/// text lists them, one a line; `message`, `line` and `column` are the
/// first's; `errors` holds each as an `mbexpr.Diagnostic`.
fn raise_all(py: Python<'_>, errors: &[Located]) -> PyErr {
    let nowhere = Located::nowhere("no error".to_string());
    let first = errors.first().unwrap_or(&nowhere);
    let text: Vec<String> = errors.iter().map(Located::to_string).collect();
    let error = Error::new_err(text.join("\n"));
    let value = error.value(py);
    // Setting attributes on a fresh exception instance cannot fail.
    let _ = value.setattr("message", &first.message);
    let _ = value.setattr("line", place(first.line));
    let _ = value.setattr("column", place(first.column));
    let _ = value.setattr("errors", diagnostics(py, errors));
    error
}

/// A line or column, None for no place (0).
fn place(number: usize) -> Option<usize> {
    (number > 0).then_some(number)
}

/// `errors` as a list of `mbexpr.Diagnostic` (tuples of message, line and
/// column if the package cannot be imported, as when `_core` is used alone).
fn diagnostics<'py>(py: Python<'py>, errors: &[Located]) -> Vec<Bound<'py, PyAny>> {
    let class = py
        .import("mbexpr")
        .and_then(|package| package.getattr("Diagnostic"))
        .ok();
    errors
        .iter()
        .filter_map(|located| {
            let fields = (
                located.message.clone(),
                place(located.line),
                place(located.column),
            );
            match &class {
                Some(class) => class.call1(fields).ok(),
                None => fields.into_pyobject(py).ok().map(Bound::into_any),
            }
        })
        .collect()
}

/// The values of a numpy array as a slice: itself when contiguous, a copy
/// when strided.
fn values<'a>(array: &'a PyReadonlyArray1<'_, f64>) -> Cow<'a, [f64]> {
    match array.as_slice() {
        Ok(slice) => Cow::Borrowed(slice),
        Err(_) => Cow::Owned(array.as_array().to_vec()),
    }
}

/// An expression compiled for named inputs (see `mbexpr.Program`).
#[pyclass(frozen, module = "mbexpr._core")]
struct Program {
    expression: Expression,
}

/// The flat outputs of a bulk evaluation: values, gradients, Hessians, status.
type BulkArrays<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<i32>>,
);

#[pymethods]
impl Program {
    #[new]
    fn new(py: Python<'_>, text: &str, inputs: Vec<String>) -> PyResult<Program> {
        let expression =
            Expression::compile_all(text, &inputs).map_err(|errors| raise_all(py, &errors))?;
        Ok(Program { expression })
    }

    /// The text it was compiled from.
    #[getter]
    fn text(&self) -> &str {
        self.expression.text()
    }

    /// The input names, in order.
    #[getter]
    fn inputs(&self) -> Vec<String> {
        self.expression.inputs().to_vec()
    }

    /// Evaluates at the `points` points of `columns` (one 1-D array per
    /// input, each of `points` values; a program without inputs has no
    /// column) for `order` 0, 1 or 2 in the inputs `wrt`, on `threads`
    /// threads (0: every core), without the GIL. Returns flat values,
    /// gradients (`k` a point), Hessians (`k²`) and the status.
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        columns: Vec<PyReadonlyArray1<'py, f64>>,
        wrt: Vec<usize>,
        order: u8,
        threads: usize,
        points: usize,
    ) -> PyResult<BulkArrays<'py>> {
        let order = Order::from_number(order)
            .ok_or_else(|| PyValueError::new_err(format!("order {order} is not 0, 1 or 2")))?;
        let columns: Vec<Cow<'_, [f64]>> = columns.iter().map(values).collect();
        let n = points;
        if let Some(index) = columns.iter().position(|column| column.len() != n) {
            return Err(PyValueError::new_err(format!(
                "input {} has {} values for {n} points: give each input one a point",
                index + 1,
                columns[index].len()
            )));
        }
        let k = wrt.len();
        let widths = [
            if order >= Order::Gradient { k } else { 0 },
            if order >= Order::Hessian { k * k } else { 0 },
        ];
        let (mut values, mut gradients, mut hessians, mut status) = (
            vec![0.0; n],
            vec![0.0; n * widths[0]],
            vec![0.0; n * widths[1]],
            vec![0; n],
        );
        let slices: Vec<&[f64]> = columns.iter().map(|column| column.as_ref()).collect();
        let expression = &self.expression;
        py.detach(|| {
            let out = Bulk {
                values: &mut values,
                gradients: &mut gradients,
                hessians: &mut hessians,
                status: &mut status,
            };
            expression.evaluate_bulk(&slices, &wrt, order, out, threads)
        })
        .map_err(|error| raise(py, &error))?;
        Ok((
            values.into_pyarray(py),
            gradients.into_pyarray(py),
            hessians.into_pyarray(py),
            status.into_pyarray(py),
        ))
    }

    /// Raises the error of one point (after a bulk status of 1 there).
    fn explain(&self, py: Python<'_>, point: Vec<f64>, wrt: Vec<usize>, order: u8) -> PyResult<()> {
        let order = Order::from_number(order).unwrap_or(Order::Value);
        match self.expression.evaluate(&point, &wrt, order) {
            Ok(_) => Ok(()),
            Err(error) => Err(raise(py, &error)),
        }
    }
}

/// The utility subroutine `name` over columns of arguments (the calling
/// sequence's order, then IORD): VECTOR per point, flat (3 a point); the
/// first point that sets ERRFLG raises, with its index.
#[pyfunction]
fn utility_bulk<'py>(
    py: Python<'py>,
    name: &str,
    columns: Vec<PyReadonlyArray1<'py, f64>>,
    iord: i32,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let columns: Vec<Cow<'_, [f64]>> = columns.iter().map(values).collect();
    let n = columns.first().map_or(0, |column| column.len());
    let arity = match name {
        "bistop" => 8,
        "impact" => 7,
        "step" => 5,
        _ => {
            return Err(PyValueError::new_err(format!(
                "no utility subroutine {name}"
            )));
        }
    };
    if columns.len() != arity {
        return Err(PyValueError::new_err(format!(
            "{name} takes {arity} arguments before iord, not {}",
            columns.len()
        )));
    }
    if let Some(k) = columns.iter().position(|column| column.len() != n) {
        return Err(PyValueError::new_err(format!(
            "{name}: argument {} has {} values, the first {n}: give each argument as many",
            k + 1,
            columns[k].len()
        )));
    }
    let run = || -> Result<Vec<f64>, (usize, String)> {
        let mut out = Vec::with_capacity(3 * n);
        let mut a = [0.0; 8];
        for p in 0..n {
            for (slot, column) in a.iter_mut().zip(&columns) {
                *slot = column[p];
            }
            let vector = match name {
                "bistop" => utility::bistop(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], iord),
                "impact" => utility::impact(a[0], a[1], a[2], a[3], a[4], a[5], a[6], iord),
                _ => {
                    utility::step(a[0], a[1], a[2], a[3], a[4], iord).map(|value| [value, 0.0, 0.0])
                }
            }
            .map_err(|error| (p, error.to_string()))?;
            out.extend(vector);
        }
        Ok(out)
    };
    match py.detach(run) {
        Ok(out) => Ok(out.into_pyarray(py)),
        Err((point, message)) => {
            let located = Located::nowhere(format!("{name} at point {point}: {message}"));
            Err(raise(py, &located))
        }
    }
}

/// The problems of the model file at `path`, as `mbexpr.Diagnostic`s.
#[pyfunction]
fn check_model<'py>(py: Python<'py>, path: &str) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let found = py
        .detach(|| embed::check_model_file(path))
        .map_err(|error| raise(py, &error))?;
    Ok(diagnostics(py, &found))
}

/// A branch switch: `(time, function, from, to, line, column)`.
type EventTuple = (f64, String, String, String, usize, usize);

/// A run: the column names, the rows flat, the events and the statistics.
type RunTuple<'py> = (
    Vec<String>,
    Bound<'py, PyArray1<f64>>,
    Vec<EventTuple>,
    Bound<'py, PyDict>,
);

/// A run's settings as Python passes them: `(method, end, steps, rtol,
/// atol, h_max, max_steps)`, `None` for the model's own or the default.
type RunSettings = (
    String,
    Option<f64>,
    Option<usize>,
    f64,
    Option<f64>,
    Option<f64>,
    Option<usize>,
);

/// The run options of `settings` (the model's own statics and landing on
/// outputs, as its command file says).
fn run_options(py: Python<'_>, settings: RunSettings) -> PyResult<RunOptions> {
    let (method, end, steps, rtol, atol, h_max, max_steps) = settings;
    let method: Method = method
        .parse()
        .map_err(|error: mbexpr::integrate::UnknownMethod| {
            raise(py, &Located::nowhere(error.to_string()))
        })?;
    Ok(RunOptions {
        method,
        end,
        steps,
        rtol,
        atol,
        h_max,
        max_steps,
        // As the model's command file says.
        statics: None,
        land_on_outputs: None,
    })
}

/// The format of a model's text, "dataset" or "scene".
fn model_format(py: Python<'_>, format: &str) -> PyResult<ModelFormat> {
    match format {
        "dataset" => Ok(ModelFormat::Dataset),
        "scene" => Ok(ModelFormat::Scene),
        other => {
            let message = format!("format {other:?} is neither \"dataset\" nor \"scene\"");
            Err(raise(py, &Located::nowhere(message)))
        }
    }
}

/// Refuses run settings that no model's run can take, before any run (as
/// a sweep does once): the format (when given), the method and what
/// [`RunOptions::check`] refuses.
#[pyfunction]
fn check_settings(py: Python<'_>, format: Option<&str>, settings: RunSettings) -> PyResult<()> {
    if let Some(format) = format {
        model_format(py, format)?;
    }
    run_options(py, settings)?
        .check()
        .map_err(|error| raise(py, &error))
}

/// Runs a model (a file when `is_path`, else text of `format` "dataset"
/// or "scene") with `settings`, without the GIL. Returns the column names,
/// the rows flat, the events and the statistics.
#[pyfunction]
fn simulate<'py>(
    py: Python<'py>,
    source: String,
    is_path: bool,
    format: &str,
    settings: RunSettings,
) -> PyResult<RunTuple<'py>> {
    let options = run_options(py, settings)?;
    let format = model_format(py, format)?;
    let outcome = py.detach(|| {
        let loaded = if is_path {
            LoadedModel::from_path(&source)
        } else {
            LoadedModel::from_text(source, format)
        };
        let loaded = loaded?;
        let mut rows = Vec::new();
        let ran = loaded
            .simulate(&options, |time, values| {
                rows.push(time);
                rows.extend_from_slice(values);
                true
            })
            .map_err(|error| vec![error])?;
        Ok::<_, Vec<Located>>((loaded.columns(), rows, ran))
    });
    let (columns, rows, ran) = outcome.map_err(|errors| raise_all(py, &errors))?;
    let events = ran
        .events
        .into_iter()
        .map(|event| {
            (
                event.time,
                event.function,
                event.from,
                event.to,
                event.place.line,
                event.place.column,
            )
        })
        .collect();
    let stats = ran.summary.stats;
    let statistics = PyDict::new(py);
    statistics.set_item("steps", stats.steps)?;
    statistics.set_item("rejected", stats.rejected)?;
    statistics.set_item("rhs_evaluations", stats.rhs_evaluations)?;
    statistics.set_item("jacobian_evaluations", stats.jacobian_evaluations)?;
    statistics.set_item("lu_decompositions", stats.lu_decompositions)?;
    statistics.set_item("wall_time", ran.summary.wall_time.as_secs_f64())?;
    statistics.set_item("stiff_from", ran.summary.stiff_from)?;
    let changes: Vec<(f64, String, String)> = ran
        .summary
        .method_changes
        .iter()
        .map(|change| (change.time, change.from.to_string(), change.to.to_string()))
        .collect();
    statistics.set_item("method_changes", changes)?;
    Ok((columns, rows.into_pyarray(py), events, statistics))
}

/// The extension module.
#[pymodule]
fn _core(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("Error", module.py().get_type::<Error>())?;
    module.add_class::<Program>()?;
    module.add_function(wrap_pyfunction!(utility_bulk, module)?)?;
    module.add_function(wrap_pyfunction!(check_model, module)?)?;
    module.add_function(wrap_pyfunction!(check_settings, module)?)?;
    module.add_function(wrap_pyfunction!(simulate, module)?)?;
    Ok(())
}
