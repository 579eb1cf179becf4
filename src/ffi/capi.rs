//! The C API (`include/mbexpr.h`): an expression compiled with the names
//! of its inputs into an opaque, immutable program that threads share;
//! its value, gradient and Hessian at a point and in bulk (structure of
//! arrays, a status per point); a model file checked, loaded and
//! simulated into a row callback.
//!
//! Every entry point returns [`MBEXPR_OK`] or [`MBEXPR_ERROR`] and, on an
//! error, fills the caller's [`Error`] (a message with its line and
//! column; the message is freed with [`mbexpr_error_free`], or by the
//! next call that fills the same error). There is no
//! global error state, and no panic crosses into C: one is caught and
//! reported as an internal error. Everything the library allocates has a
//! `_free` function.

use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::ptr;

use crate::embed::{Bulk, Expression, LoadedModel, Located, ModelFormat, RunOptions};
use crate::eval::Order;
use crate::integrate::Method;

/// Success.
pub const MBEXPR_OK: c_int = 0;
/// Failure, described in the caller's [`Error`].
pub const MBEXPR_ERROR: c_int = 1;

/// `mbexpr_error`: why a call failed. Line and column count from 1; both
/// are 0 when the error speaks of no place. It starts zeroed (a NULL
/// message); a call that fails frees the message it held before writing
/// its own, so one error may be passed to call after call and freed once.
#[repr(C)]
pub struct Error {
    /// The message, NUL-terminated, allocated by the library (NULL when
    /// there is none); free it with [`mbexpr_error_free`].
    pub message: *mut c_char,
    /// The line, from 1 (0: no place).
    pub line: usize,
    /// The column, from 1 (0: no place).
    pub column: usize,
}

/// `mbexpr_program`: a compiled expression (opaque to C).
pub struct CProgram {
    expression: Expression,
    inputs: Vec<CString>,
}

/// `mbexpr_diagnostics`: messages at their places (opaque): the problems
/// of a checked model file, or every error of a compilation or a load.
pub struct Diagnostics {
    entries: Vec<(CString, usize, usize)>,
}

impl Diagnostics {
    /// The list of `found`.
    fn of(found: &[Located]) -> Diagnostics {
        let entries = found
            .iter()
            .map(|located| (c_string(&located.message), located.line, located.column))
            .collect();
        Diagnostics { entries }
    }
}

/// `mbexpr_model`: a model ready to simulate (opaque).
pub struct CModel {
    model: LoadedModel,
    columns: Vec<CString>,
}

/// `mbexpr_settings`: how to run a simulation. A zero asks for the model's
/// own setting or the default: `end` and `steps` from the model (an `.acf`
/// beside the dataset, `[simulate]` of a scene file), `rtol` 1e-6, `atol`
/// a thousandth of `rtol`, no largest step, ten million steps at most.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct CSettings {
    /// [`MBEXPR_AUTO`] (the default), [`MBEXPR_RADAU5`] or [`MBEXPR_DOP853`].
    pub method: c_int,
    /// The end time (the run starts at 0).
    pub end: f64,
    /// The number of output steps (`steps + 1` rows).
    pub steps: usize,
    /// The relative tolerance.
    pub rtol: f64,
    /// The absolute tolerance.
    pub atol: f64,
    /// The largest step.
    pub h_max: f64,
    /// The most integration steps.
    pub max_steps: usize,
}

/// Radau IIA of order 5, for stiff models.
pub const MBEXPR_RADAU5: c_int = 0;
/// Dormand and Prince's explicit method of order 8.
pub const MBEXPR_DOP853: c_int = 1;
/// DOP853 while the model is not stiff, Radau5 while it is (the default,
/// as on the command line; [`CSummary::method_changes`] counts the changes).
pub const MBEXPR_AUTO: c_int = 2;
/// A solver dataset (`.adm`) given as text.
pub const MBEXPR_DATASET: c_int = 0;
/// A scene file (TOML) given as text.
pub const MBEXPR_SCENE: c_int = 1;

/// `mbexpr_summary`: what a run cost and found.
#[repr(C)]
#[derive(Clone, Copy, Default)]
pub struct CSummary {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected trial steps.
    pub rejected: usize,
    /// Right-hand side evaluations.
    pub rhs_evaluations: usize,
    /// Jacobian evaluations.
    pub jacobian_evaluations: usize,
    /// LU decompositions.
    pub lu_decompositions: usize,
    /// Located branch switches.
    pub events: usize,
    /// Wall time of the run, in seconds.
    pub wall_time: f64,
    /// 1 when the row callback stopped the run before its end.
    pub stopped: c_int,
    /// Under [`MBEXPR_AUTO`], how many times the run changed method.
    pub method_changes: usize,
}

/// `int (*)(void *user, double time, const double *values, size_t count)`:
/// one output row (`values` holds the `count` columns after `time`, valid
/// during the call); return 0 to go on, anything else to stop the run.
pub type RowCallback = Option<
    unsafe extern "C" fn(user: *mut c_void, time: f64, values: *const f64, count: usize) -> c_int,
>;

/// `void (*)(void *user, double time, const char *function, const char
/// *from, const char *to, size_t line, size_t column)`: one located branch
/// switch, called after the run in time order (the strings are valid
/// during the call).
pub type EventCallback = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        time: f64,
        function: *const c_char,
        from: *const c_char,
        to: *const c_char,
        line: usize,
        column: usize,
    ),
>;

/// Runs `body`; its errors, or a panic caught as an internal error.
fn caught(body: impl FnOnce() -> Result<(), Vec<Located>>) -> Result<(), Vec<Located>> {
    catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|panic| {
        let what = panic
            .downcast_ref::<&str>()
            .map(|text| text.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        Err(vec![Located::nowhere(format!(
            "internal error in mbexpr (please report it with the call that made it): {what}"
        ))])
    })
}

/// Runs `body`, filling `error` with its error or a caught panic (the
/// first of several, with how many more there are), after freeing the
/// message an earlier failure left in it.
fn guarded(error: *mut Error, body: impl FnOnce() -> Result<(), Located>) -> c_int {
    let Err(failures) = caught(|| body().map_err(|failure| vec![failure])) else {
        return MBEXPR_OK;
    };
    let failure = Located::first_of(failures);
    if !error.is_null() {
        // SAFETY: a non-null `error` points to a writable mbexpr_error whose
        // message is NULL or the library's (every entry point's contract):
        // the message of an earlier failure is freed, not leaked.
        unsafe {
            mbexpr_error_free(error);
            *error = Error {
                message: c_string(&failure.message).into_raw(),
                line: failure.line,
                column: failure.column,
            };
        }
    }
    MBEXPR_ERROR
}

/// Runs `body`; on failure hands every error (or a caught panic) to C as
/// a list at `*errors` (when not null), else sets `*errors` to null.
fn guarded_list(
    errors: *mut *mut Diagnostics,
    body: impl FnOnce() -> Result<(), Vec<Located>>,
) -> c_int {
    let outcome = caught(body);
    if !errors.is_null() {
        let list = match &outcome {
            Ok(()) => ptr::null_mut(),
            Err(failures) => Box::into_raw(Box::new(Diagnostics::of(failures))),
        };
        // SAFETY: a non-null `errors` is writable (the entry points' contract).
        unsafe { errors.write(list) };
    }
    match outcome {
        Ok(()) => MBEXPR_OK,
        Err(_) => MBEXPR_ERROR,
    }
}

/// One error as a list.
fn one(error: Located) -> Vec<Located> {
    vec![error]
}

/// A refusal of a null pointer the call needs.
fn null(what: &str) -> Located {
    Located::nowhere(format!("{what} is a null pointer"))
}

/// The text at `pointer`, NUL-terminated UTF-8.
///
/// # Safety
/// `pointer` is null or points to a NUL-terminated string that outlives `'a`.
unsafe fn c_text<'a>(pointer: *const c_char, what: &str) -> Result<&'a str, Located> {
    if pointer.is_null() {
        return Err(null(what));
    }
    // SAFETY: from this function's contract.
    unsafe { CStr::from_ptr(pointer) }
        .to_str()
        .map_err(|error| Located::nowhere(format!("{what} is not UTF-8: {error}")))
}

/// `count` values at `pointer` (an empty slice when `count` is 0).
///
/// # Safety
/// `pointer` is null or points to `count` readable values that outlive `'a`.
unsafe fn slice<'a, T>(pointer: *const T, count: usize, what: &str) -> Result<&'a [T], Located> {
    if count == 0 {
        return Ok(&[]);
    }
    if pointer.is_null() {
        return Err(null(what));
    }
    // SAFETY: from this function's contract.
    Ok(unsafe { std::slice::from_raw_parts(pointer, count) })
}

/// `count` writable values at `pointer` (an empty slice when `count` is 0).
///
/// # Safety
/// `pointer` is null or points to `count` writable values, not aliased,
/// that outlive `'a`.
unsafe fn slice_mut<'a, T>(
    pointer: *mut T,
    count: usize,
    what: &str,
) -> Result<&'a mut [T], Located> {
    if count == 0 {
        return Ok(&mut []);
    }
    if pointer.is_null() {
        return Err(null(what));
    }
    // SAFETY: from this function's contract.
    Ok(unsafe { std::slice::from_raw_parts_mut(pointer, count) })
}

/// Writes `value` to `*out`.
///
/// # Safety
/// `out` is null or writable.
unsafe fn put<T>(out: *mut T, value: T, what: &str) -> Result<(), Located> {
    if out.is_null() {
        return Err(null(what));
    }
    // SAFETY: from this function's contract.
    unsafe { out.write(value) };
    Ok(())
}

/// Boxes `value` and writes the pointer to `*out` (C frees it with the
/// object's `_free`).
///
/// # Safety
/// `out` is null or writable.
unsafe fn hand_out<T>(value: T, out: *mut *mut T, what: &str) -> Result<(), Located> {
    if out.is_null() {
        return Err(null(what));
    }
    // SAFETY: from this function's contract.
    unsafe { out.write(Box::into_raw(Box::new(value))) };
    Ok(())
}

/// Frees an object handed out by [`hand_out`] (NULL is ignored).
///
/// # Safety
/// `pointer` is null or came from [`hand_out`] and is not used again.
unsafe fn free<T>(pointer: *mut T) {
    if !pointer.is_null() {
        // SAFETY: from this function's contract.
        drop(unsafe { Box::from_raw(pointer) });
    }
}

/// A borrowed reference to an opaque object.
///
/// # Safety
/// `pointer` is null or came from this library's constructor of `T` and
/// has not been freed.
unsafe fn object<'a, T>(pointer: *const T, what: &str) -> Result<&'a T, Located> {
    // SAFETY: from this function's contract.
    unsafe { pointer.as_ref() }.ok_or_else(|| null(what))
}

/// A string that C can hold (a NUL inside becomes a blank).
fn c_string(text: &str) -> CString {
    CString::new(text.replace('\0', " ")).unwrap_or_default()
}

/// `void mbexpr_error_free(mbexpr_error *error)`: frees the message and
/// sets it to NULL (an error with no message, or a null `error`, is left
/// alone).
///
/// # Safety
/// `error` is null or points to an mbexpr_error whose message is NULL or
/// was set by this library.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_error_free(error: *mut Error) {
    // SAFETY: from this function's contract.
    if let Some(error) = unsafe { error.as_mut() }
        && !error.message.is_null()
    {
        // SAFETY: the message came from `CString::into_raw` in `guarded`.
        drop(unsafe { CString::from_raw(error.message) });
        error.message = ptr::null_mut();
    }
}

/// `int mbexpr_compile(const char *text, const char *const *inputs, size_t
/// input_count, mbexpr_program **program, mbexpr_error *error)`: parses,
/// checks and compiles `text` for the inputs named `inputs` (their values
/// are later given in this order; `TIME` and `MODE` may be among them).
/// The program is immutable: any number of threads may evaluate it at once.
/// The error is the first problem, with how many more there are
/// ([`mbexpr_compile_all`] lists every one).
///
/// # Safety
/// `text` and each of the `input_count` names are NUL-terminated strings;
/// `program` points to a writable pointer; `error` is null or a writable
/// [`Error`] whose message is NULL or the library's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_compile(
    text: *const c_char,
    inputs: *const *const c_char,
    input_count: usize,
    program: *mut *mut CProgram,
    error: *mut Error,
) -> c_int {
    guarded(error, || {
        // SAFETY: from this function's contract.
        unsafe { compile(text, inputs, input_count, program) }.map_err(Located::first_of)
    })
}

/// `int mbexpr_compile_all(const char *text, const char *const *inputs,
/// size_t input_count, mbexpr_program **program, mbexpr_diagnostics
/// **errors)`: as [`mbexpr_compile`], but a failure hands every problem
/// found (in source order, each with its line and column) to `*errors`, a
/// list freed with [`mbexpr_diagnostics_free`]; `*errors` is NULL after a
/// success.
///
/// # Safety
/// As [`mbexpr_compile`]; `errors` is null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_compile_all(
    text: *const c_char,
    inputs: *const *const c_char,
    input_count: usize,
    program: *mut *mut CProgram,
    errors: *mut *mut Diagnostics,
) -> c_int {
    guarded_list(errors, || {
        // SAFETY: from this function's contract.
        unsafe { compile(text, inputs, input_count, program) }
    })
}

/// Compiles for [`mbexpr_compile`] and [`mbexpr_compile_all`].
///
/// # Safety
/// As [`mbexpr_compile`].
unsafe fn compile(
    text: *const c_char,
    inputs: *const *const c_char,
    input_count: usize,
    program: *mut *mut CProgram,
) -> Result<(), Vec<Located>> {
    // SAFETY: from this function's contract.
    let source = unsafe { c_text(text, "the expression text") }.map_err(one)?;
    // SAFETY: from this function's contract.
    let pointers = unsafe { slice(inputs, input_count, "the input names") }.map_err(one)?;
    let names = pointers
        .iter()
        // SAFETY: each name is a NUL-terminated string (the contract).
        .map(|&name| unsafe { c_text(name, "an input name") })
        .collect::<Result<Vec<&str>, Located>>()
        .map_err(one)?;
    let expression = Expression::compile_all(source, &names)?;
    let inputs = expression
        .inputs()
        .iter()
        .map(|name| c_string(name))
        .collect();
    let compiled = CProgram { expression, inputs };
    // SAFETY: from this function's contract.
    unsafe { hand_out(compiled, program, "the program pointer") }.map_err(one)
}

/// `void mbexpr_program_free(mbexpr_program *program)` (NULL is ignored).
///
/// # Safety
/// `program` is null or came from [`mbexpr_compile`] and is not used again.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_program_free(program: *mut CProgram) {
    // SAFETY: from this function's contract.
    unsafe { free(program) }
}

/// `size_t mbexpr_program_input_count(const mbexpr_program *program)`: the
/// number of inputs (0 for NULL).
///
/// # Safety
/// `program` is null or a live program.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_program_input_count(program: *const CProgram) -> usize {
    // SAFETY: from this function's contract.
    unsafe { program.as_ref() }.map_or(0, |program| program.inputs.len())
}

/// `const char *mbexpr_program_input(const mbexpr_program *program, size_t
/// index)`: the name of input `index` as compiled, valid while the program
/// lives (NULL beyond the last or for NULL).
///
/// # Safety
/// `program` is null or a live program.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_program_input(
    program: *const CProgram,
    index: usize,
) -> *const c_char {
    // SAFETY: from this function's contract.
    unsafe { program.as_ref() }
        .and_then(|program| program.inputs.get(index))
        .map_or(ptr::null(), |name| name.as_ptr())
}

/// Evaluates `program` at `point` for `order`, writing what is asked.
///
/// # Safety
/// As [`mbexpr_hessian`], with `gradient` and `hessian` unused below their order.
unsafe fn evaluate_one(
    program: *const CProgram,
    point: *const f64,
    wrt: *const usize,
    wrt_count: usize,
    order: Order,
    out: [*mut f64; 3],
) -> Result<(), Located> {
    // SAFETY: from this function's contract.
    let program = unsafe { object(program, "the program") }?;
    let expression = &program.expression;
    let count = expression.inputs().len();
    // SAFETY: `point` holds one value per input.
    let point = unsafe { slice(point, count, "the point") }?;
    // SAFETY: `wrt` holds `wrt_count` indices.
    let wrt = unsafe { slice(wrt, wrt_count, "the derivative directions") }?;
    let result = expression.evaluate(point, wrt, order)?;
    let k = wrt.len();
    // SAFETY: `value` is writable.
    unsafe { put(out[0], result.value, "the value pointer") }?;
    if let Some(gradient) = result.gradient {
        // SAFETY: `gradient` has room for `wrt_count` values.
        unsafe { slice_mut(out[1], k, "the gradient") }?.copy_from_slice(gradient.as_slice());
    }
    if let Some(hessian) = result.hessian {
        // SAFETY: `hessian` has room for `wrt_count²` values.
        unsafe { slice_mut(out[2], k * k, "the Hessian") }?.copy_from_slice(hessian.as_slice());
    }
    Ok(())
}

/// `int mbexpr_value(const mbexpr_program *program, const double *point,
/// double *value, mbexpr_error *error)`: the value at `point` (one number
/// per input, in the compiled order). An evaluation that fails (a domain
/// error, an overflow, an input that is not finite) is an error placed at
/// the operation in the expression: never a NaN or an infinity.
///
/// # Safety
/// `program` is a live program; `point` holds one double per input;
/// `value` is writable; `error` is null or a writable [`Error`] whose
/// message is NULL or the library's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_value(
    program: *const CProgram,
    point: *const f64,
    value: *mut f64,
    error: *mut Error,
) -> c_int {
    let out = [value, ptr::null_mut(), ptr::null_mut()];
    // SAFETY: from this function's contract.
    guarded(error, || unsafe {
        evaluate_one(program, point, ptr::null(), 0, Order::Value, out)
    })
}

/// `int mbexpr_gradient(const mbexpr_program *program, const double *point,
/// const size_t *wrt, size_t wrt_count, double *value, double *gradient,
/// mbexpr_error *error)`: the value and the exact derivatives in the
/// inputs `wrt` (indices from 0, each at most once).
///
/// # Safety
/// As [`mbexpr_value`]; `wrt` holds `wrt_count` indices; `gradient` has
/// room for `wrt_count` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_gradient(
    program: *const CProgram,
    point: *const f64,
    wrt: *const usize,
    wrt_count: usize,
    value: *mut f64,
    gradient: *mut f64,
    error: *mut Error,
) -> c_int {
    let out = [value, gradient, ptr::null_mut()];
    guarded(error, || {
        // SAFETY: from this function's contract.
        unsafe { evaluate_one(program, point, wrt, wrt_count, Order::Gradient, out) }
    })
}

/// `int mbexpr_hessian(const mbexpr_program *program, const double *point,
/// const size_t *wrt, size_t wrt_count, double *value, double *gradient,
/// double *hessian, mbexpr_error *error)`: the value, gradient and the
/// exact Hessian in `wrt` (`wrt_count²` doubles, symmetric).
///
/// # Safety
/// As [`mbexpr_gradient`]; `hessian` has room for `wrt_count²` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_hessian(
    program: *const CProgram,
    point: *const f64,
    wrt: *const usize,
    wrt_count: usize,
    value: *mut f64,
    gradient: *mut f64,
    hessian: *mut f64,
    error: *mut Error,
) -> c_int {
    let out = [value, gradient, hessian];
    guarded(error, || {
        // SAFETY: from this function's contract.
        unsafe { evaluate_one(program, point, wrt, wrt_count, Order::Hessian, out) }
    })
}

/// The arguments of a bulk evaluation.
struct BulkCall {
    program: *const CProgram,
    columns: *const *const f64,
    n: usize,
    wrt: *const usize,
    wrt_count: usize,
    order: Order,
    out: [*mut f64; 3],
    status: *mut c_int,
    threads: usize,
    failed: *mut usize,
}

/// Runs a bulk evaluation.
///
/// # Safety
/// As [`mbexpr_hessian_bulk`], the outputs unused beyond `order`.
unsafe fn evaluate_bulk(call: BulkCall) -> Result<(), Located> {
    // SAFETY: from this function's contract.
    let program = unsafe { object(call.program, "the program") }?;
    let expression = &program.expression;
    let n = call.n;
    // SAFETY: one column pointer per input.
    let pointers = unsafe { slice(call.columns, expression.inputs().len(), "the columns") }?;
    let columns = pointers
        .iter()
        // SAFETY: each column holds `n` doubles.
        .map(|&column| unsafe { slice(column, n, "a column") })
        .collect::<Result<Vec<&[f64]>, Located>>()?;
    // SAFETY: `wrt` holds `wrt_count` indices.
    let wrt = unsafe { slice(call.wrt, call.wrt_count, "the derivative directions") }?;
    let k = wrt.len();
    let widths = [
        1,
        if call.order >= Order::Gradient { k } else { 0 },
        if call.order >= Order::Hessian {
            k * k
        } else {
            0
        },
    ];
    // SAFETY: each output has room for `n` times its width, and none
    // overlaps another (the contract).
    let (values, gradients, hessians, status) = unsafe {
        (
            slice_mut(call.out[0], n * widths[0], "the values")?,
            slice_mut(call.out[1], n * widths[1], "the gradients")?,
            slice_mut(call.out[2], n * widths[2], "the Hessians")?,
            slice_mut(call.status, n, "the status")?,
        )
    };
    let out = Bulk {
        values,
        gradients,
        hessians,
        status,
    };
    let failed = expression.evaluate_bulk(&columns, wrt, call.order, out, call.threads)?;
    if !call.failed.is_null() {
        // SAFETY: a non-null `failed` is writable.
        unsafe { call.failed.write(failed) };
    }
    Ok(())
}

/// `int mbexpr_value_bulk(const mbexpr_program *program, const double
/// *const *columns, size_t n, double *values, int *status, size_t threads,
/// size_t *failed, mbexpr_error *error)`: the value at `n` points given as
/// one column per input (`columns[i][p]`: input `i` at point `p`), on
/// `threads` threads (0: every core, 1: the calling thread). `status[p]` is
/// 0, or 1 where point `p` cannot be evaluated (its outputs are then 0;
/// [`mbexpr_value`] at that point says why); `*failed` (if not NULL) counts
/// those points. The call fails only on bad arguments.
///
/// # Safety
/// `program` is live; `columns` holds one pointer per input to `n`
/// doubles; `values` and `status` have room for `n` entries; `failed` is
/// null or writable; `error` is null or a writable [`Error`] whose message
/// is NULL or the library's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_value_bulk(
    program: *const CProgram,
    columns: *const *const f64,
    n: usize,
    values: *mut f64,
    status: *mut c_int,
    threads: usize,
    failed: *mut usize,
    error: *mut Error,
) -> c_int {
    let call = BulkCall {
        program,
        columns,
        n,
        wrt: ptr::null(),
        wrt_count: 0,
        order: Order::Value,
        out: [values, ptr::null_mut(), ptr::null_mut()],
        status,
        threads,
        failed,
    };
    // SAFETY: from this function's contract.
    guarded(error, || unsafe { evaluate_bulk(call) })
}

/// `int mbexpr_gradient_bulk(const mbexpr_program *program, const double
/// *const *columns, size_t n, const size_t *wrt, size_t wrt_count, double
/// *values, double *gradients, int *status, size_t threads, size_t
/// *failed, mbexpr_error *error)`: as [`mbexpr_value_bulk`], and the
/// gradient in `wrt` of point `p` at `gradients[p * wrt_count ...]`.
///
/// # Safety
/// As [`mbexpr_value_bulk`]; `gradients` has room for `n * wrt_count` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_gradient_bulk(
    program: *const CProgram,
    columns: *const *const f64,
    n: usize,
    wrt: *const usize,
    wrt_count: usize,
    values: *mut f64,
    gradients: *mut f64,
    status: *mut c_int,
    threads: usize,
    failed: *mut usize,
    error: *mut Error,
) -> c_int {
    let call = BulkCall {
        program,
        columns,
        n,
        wrt,
        wrt_count,
        order: Order::Gradient,
        out: [values, gradients, ptr::null_mut()],
        status,
        threads,
        failed,
    };
    // SAFETY: from this function's contract.
    guarded(error, || unsafe { evaluate_bulk(call) })
}

/// `int mbexpr_hessian_bulk(..., double *values, double *gradients, double
/// *hessians, int *status, size_t threads, size_t *failed, mbexpr_error
/// *error)`: as [`mbexpr_gradient_bulk`], and the Hessian of point `p` at
/// `hessians[p * wrt_count * wrt_count ...]`.
///
/// # Safety
/// As [`mbexpr_gradient_bulk`]; `hessians` has room for `n * wrt_count²` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_hessian_bulk(
    program: *const CProgram,
    columns: *const *const f64,
    n: usize,
    wrt: *const usize,
    wrt_count: usize,
    values: *mut f64,
    gradients: *mut f64,
    hessians: *mut f64,
    status: *mut c_int,
    threads: usize,
    failed: *mut usize,
    error: *mut Error,
) -> c_int {
    let call = BulkCall {
        program,
        columns,
        n,
        wrt,
        wrt_count,
        order: Order::Hessian,
        out: [values, gradients, hessians],
        status,
        threads,
        failed,
    };
    // SAFETY: from this function's contract.
    guarded(error, || unsafe { evaluate_bulk(call) })
}

/// `int mbexpr_check_model(const char *path, mbexpr_diagnostics
/// **diagnostics, mbexpr_error *error)`: checks the model file at `path`
/// (dataset, command file, View command file, scene file); every problem
/// is a diagnostic with its line and column (none when it checks). The
/// call fails when the file cannot be read or is not a model file.
///
/// # Safety
/// `path` is a NUL-terminated string; `diagnostics` is writable; `error`
/// is null or a writable [`Error`] whose message is NULL or the library's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_check_model(
    path: *const c_char,
    diagnostics: *mut *mut Diagnostics,
    error: *mut Error,
) -> c_int {
    guarded(error, || {
        // SAFETY: from this function's contract.
        let path = unsafe { c_text(path, "the path") }?;
        let found = Diagnostics::of(&crate::embed::check_model_file(path)?);
        // SAFETY: from this function's contract.
        unsafe { hand_out(found, diagnostics, "the diagnostics pointer") }
    })
}

/// `size_t mbexpr_diagnostics_count(const mbexpr_diagnostics *diagnostics)`.
///
/// # Safety
/// `diagnostics` is null or live.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_diagnostics_count(diagnostics: *const Diagnostics) -> usize {
    // SAFETY: from this function's contract.
    unsafe { diagnostics.as_ref() }.map_or(0, |found| found.entries.len())
}

/// `const char *mbexpr_diagnostic(const mbexpr_diagnostics *diagnostics,
/// size_t index, size_t *line, size_t *column)`: the message of diagnostic
/// `index` (valid while `diagnostics` lives), its line and column written
/// where not NULL; NULL beyond the last.
///
/// # Safety
/// `diagnostics` is null or live; `line` and `column` are null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_diagnostic(
    diagnostics: *const Diagnostics,
    index: usize,
    line: *mut usize,
    column: *mut usize,
) -> *const c_char {
    // SAFETY: from this function's contract.
    let Some((message, at_line, at_column)) =
        unsafe { diagnostics.as_ref() }.and_then(|found| found.entries.get(index))
    else {
        return ptr::null();
    };
    // SAFETY: from this function's contract (a null pointer is skipped).
    unsafe {
        let _ = put(line, *at_line, "");
        let _ = put(column, *at_column, "");
    }
    message.as_ptr()
}

/// `void mbexpr_diagnostics_free(mbexpr_diagnostics *diagnostics)`.
///
/// # Safety
/// `diagnostics` is null or came from [`mbexpr_check_model`] or a `_all`
/// entry point and is not used again.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_diagnostics_free(diagnostics: *mut Diagnostics) {
    // SAFETY: from this function's contract.
    unsafe { free(diagnostics) }
}

/// Loads the model of the file at `path` and hands it to C.
///
/// # Safety
/// As [`mbexpr_model_load`].
unsafe fn load(path: *const c_char, out: *mut *mut CModel) -> Result<(), Vec<Located>> {
    // SAFETY: from this function's contract.
    let path = unsafe { c_text(path, "the path") }.map_err(one)?;
    // SAFETY: from this function's contract.
    unsafe { hand_over(LoadedModel::from_path(path)?, out) }
}

/// Reads a model from its text and hands it to C.
///
/// # Safety
/// As [`mbexpr_model_from_text`].
unsafe fn read(
    text: *const c_char,
    format: c_int,
    out: *mut *mut CModel,
) -> Result<(), Vec<Located>> {
    // SAFETY: from this function's contract.
    let source = unsafe { c_text(text, "the model text") }
        .map_err(one)?
        .to_string();
    let format = match format {
        MBEXPR_DATASET => ModelFormat::Dataset,
        MBEXPR_SCENE => ModelFormat::Scene,
        other => {
            return Err(vec![Located::nowhere(format!(
                "format {other} is neither MBEXPR_DATASET (0) nor MBEXPR_SCENE (1)"
            ))]);
        }
    };
    // SAFETY: from this function's contract.
    unsafe { hand_over(LoadedModel::from_text(source, format)?, out) }
}

/// Hands a loaded model to C.
///
/// # Safety
/// `out` is writable.
unsafe fn hand_over(model: LoadedModel, out: *mut *mut CModel) -> Result<(), Vec<Located>> {
    let columns = model.columns().iter().map(|name| c_string(name)).collect();
    // SAFETY: from this function's contract.
    unsafe { hand_out(CModel { model, columns }, out, "the model pointer") }.map_err(one)
}

/// `int mbexpr_model_load(const char *path, mbexpr_model **model,
/// mbexpr_error *error)`: reads a solver dataset (with the END and STEPS
/// of an `.acf` beside it), an Adams View command file (`.cmd`, with those
/// of its last transient simulation) or a scene file (`.toml`) for
/// simulation. A
/// model that does not check, or holds what the simulator does not run,
/// is an error at its first problem's line and column, with how many more
/// there are ([`mbexpr_model_load_all`] lists every one).
///
/// # Safety
/// `path` is a NUL-terminated string; `model` is writable; `error` is null
/// or a writable [`Error`] whose message is NULL or the library's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_model_load(
    path: *const c_char,
    model: *mut *mut CModel,
    error: *mut Error,
) -> c_int {
    // SAFETY: from this function's contract.
    guarded(error, || {
        unsafe { load(path, model) }.map_err(Located::first_of)
    })
}

/// `int mbexpr_model_load_all(const char *path, mbexpr_model **model,
/// mbexpr_diagnostics **errors)`: as [`mbexpr_model_load`], but a failure
/// hands every problem to `*errors` (as [`mbexpr_compile_all`] does).
///
/// # Safety
/// As [`mbexpr_model_load`]; `errors` is null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_model_load_all(
    path: *const c_char,
    model: *mut *mut CModel,
    errors: *mut *mut Diagnostics,
) -> c_int {
    // SAFETY: from this function's contract.
    guarded_list(errors, || unsafe { load(path, model) })
}

/// `int mbexpr_model_from_text(const char *text, int format, mbexpr_model
/// **model, mbexpr_error *error)`: as [`mbexpr_model_load`], from the text
/// of a dataset ([`MBEXPR_DATASET`]) or a scene file ([`MBEXPR_SCENE`]).
///
/// # Safety
/// As [`mbexpr_model_load`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_model_from_text(
    text: *const c_char,
    format: c_int,
    model: *mut *mut CModel,
    error: *mut Error,
) -> c_int {
    // SAFETY: from this function's contract.
    guarded(error, || {
        unsafe { read(text, format, model) }.map_err(Located::first_of)
    })
}

/// `int mbexpr_model_from_text_all(const char *text, int format,
/// mbexpr_model **model, mbexpr_diagnostics **errors)`: as
/// [`mbexpr_model_from_text`], but a failure hands every problem to
/// `*errors` (as [`mbexpr_compile_all`] does).
///
/// # Safety
/// As [`mbexpr_model_from_text`]; `errors` is null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_model_from_text_all(
    text: *const c_char,
    format: c_int,
    model: *mut *mut CModel,
    errors: *mut *mut Diagnostics,
) -> c_int {
    // SAFETY: from this function's contract.
    guarded_list(errors, || unsafe { read(text, format, model) })
}

/// `size_t mbexpr_model_column_count(const mbexpr_model *model)`: the
/// number of columns of a row, `time` included.
///
/// # Safety
/// `model` is null or live.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_model_column_count(model: *const CModel) -> usize {
    // SAFETY: from this function's contract.
    unsafe { model.as_ref() }.map_or(0, |model| model.columns.len())
}

/// `const char *mbexpr_model_column(const mbexpr_model *model, size_t
/// index)`: the name of column `index` (0 is `time`), valid while the
/// model lives; NULL beyond the last.
///
/// # Safety
/// `model` is null or live.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_model_column(model: *const CModel, index: usize) -> *const c_char {
    // SAFETY: from this function's contract.
    unsafe { model.as_ref() }
        .and_then(|model| model.columns.get(index))
        .map_or(ptr::null(), |name| name.as_ptr())
}

/// `void mbexpr_model_free(mbexpr_model *model)`.
///
/// # Safety
/// `model` is null or came from [`mbexpr_model_load`] or
/// [`mbexpr_model_from_text`] and is not used again.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_model_free(model: *mut CModel) {
    // SAFETY: from this function's contract.
    unsafe { free(model) }
}

/// `mbexpr_settings mbexpr_settings_default(void)`: [`MBEXPR_AUTO`] and
/// zeros (the model's own settings and the defaults).
#[unsafe(no_mangle)]
pub extern "C" fn mbexpr_settings_default() -> CSettings {
    CSettings {
        method: MBEXPR_AUTO,
        end: 0.0,
        steps: 0,
        rtol: 0.0,
        atol: 0.0,
        h_max: 0.0,
        max_steps: 0,
    }
}

/// The run options of C settings.
fn options(settings: &CSettings) -> Result<RunOptions, Located> {
    let given = |value: f64| (value != 0.0).then_some(value);
    let method = match settings.method {
        MBEXPR_RADAU5 => Method::Radau5,
        MBEXPR_DOP853 => Method::Dop853,
        MBEXPR_AUTO => Method::Auto,
        other => {
            return Err(Located::nowhere(format!(
                "method {other} is none of MBEXPR_RADAU5 (0), MBEXPR_DOP853 (1) and MBEXPR_AUTO (2)"
            )));
        }
    };
    Ok(RunOptions {
        method,
        end: given(settings.end),
        steps: (settings.steps != 0).then_some(settings.steps),
        rtol: given(settings.rtol).unwrap_or(RunOptions::default().rtol),
        atol: given(settings.atol),
        h_max: given(settings.h_max),
        max_steps: (settings.max_steps != 0).then_some(settings.max_steps),
        // As the model's command file says.
        statics: None,
        land_on_outputs: None,
    })
}

/// `int mbexpr_simulate(const mbexpr_model *model, const mbexpr_settings
/// *settings, mbexpr_row_callback row, mbexpr_event_callback event, void
/// *user, mbexpr_summary *summary, mbexpr_error *error)`: runs the model
/// from time 0, calling `row` (if not NULL) at each output time as the run
/// reaches it, then `event` (if not NULL) for each located branch switch;
/// `user` is passed to both. `summary` (if not NULL) receives the counts.
/// A run that cannot go on is an error (its rows so far delivered), placed
/// at the expression that stopped it. Several threads may simulate one
/// model at once.
///
/// # Safety
/// `model` is live; `settings` is null (the defaults) or readable; the
/// callbacks are null or functions of the documented types that return
/// normally; `summary` is null or writable; `error` is null or a writable
/// [`Error`] whose message is NULL or the library's.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn mbexpr_simulate(
    model: *const CModel,
    settings: *const CSettings,
    row: RowCallback,
    event: EventCallback,
    user: *mut c_void,
    summary: *mut CSummary,
    error: *mut Error,
) -> c_int {
    guarded(error, || {
        // SAFETY: from this function's contract.
        let model = unsafe { object(model, "the model") }?;
        // SAFETY: from this function's contract.
        let settings = unsafe { settings.as_ref() }
            .copied()
            .unwrap_or_else(|| mbexpr_settings_default());
        let ran = model
            .model
            .simulate(&options(&settings)?, |time, values| match row {
                // SAFETY: the callback's contract; `values` lives through the call.
                Some(row) => unsafe { row(user, time, values.as_ptr(), values.len()) == 0 },
                None => true,
            })?;
        if let Some(event) = event {
            for found in &ran.events {
                let [function, from, to] =
                    [&found.function, &found.from, &found.to].map(|text| c_string(text));
                // SAFETY: the callback's contract; the strings live through the call.
                unsafe {
                    event(
                        user,
                        found.time,
                        function.as_ptr(),
                        from.as_ptr(),
                        to.as_ptr(),
                        found.place.line,
                        found.place.column,
                    );
                }
            }
        }
        if !summary.is_null() {
            let stats = ran.summary.stats;
            // SAFETY: a non-null `summary` is writable.
            unsafe {
                summary.write(CSummary {
                    steps: stats.steps,
                    rejected: stats.rejected,
                    rhs_evaluations: stats.rhs_evaluations,
                    jacobian_evaluations: stats.jacobian_evaluations,
                    lu_decompositions: stats.lu_decompositions,
                    events: ran.events.len(),
                    wall_time: ran.summary.wall_time.as_secs_f64(),
                    stopped: c_int::from(ran.summary.stopped),
                    method_changes: ran.summary.method_changes.len(),
                });
            }
        }
        Ok(())
    })
}
