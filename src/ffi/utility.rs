//! The C and FORTRAN calling sequences of the utility subroutines (SPEC 6),
//! so that user subroutines written for the solver link against mbexpr
//! unchanged: `c_bistop`, `c_impact`, `c_step` with the prototypes of the
//! solver SDK (`include/mbexpr.h`), and the symbols gfortran emits for
//! `CALL BISTOP(...)`, `CALL IMPACT(...)`, `CALL STEP(...)`: lower case with
//! a trailing underscore, every argument by reference, ERRFLG a default
//! LOGICAL (`include/mbexpr.f90`).
//!
//! On any error ERRFLG is set (C: 1; FORTRAN: .TRUE.) and VECTOR zeroed; a
//! null output pointer is left alone; no panic crosses the boundary.

use std::os::raw::{c_double, c_int};
use std::panic::catch_unwind;

use crate::utility;

/// Writes `result` (or zeros) to `vector[0..3]` and the flag to `errflg`.
///
/// # Safety
/// `vector` is null or points to three writable doubles; `errflg` is null or
/// points to a writable int.
unsafe fn report(result: Option<[f64; 3]>, vector: *mut c_double, errflg: *mut c_int) {
    let (values, failed) = match result {
        Some(values) => (values, 0),
        None => ([0.0; 3], 1),
    };
    if !vector.is_null() {
        // SAFETY: the caller passes VECTOR(3), as the calling sequence says.
        unsafe { std::ptr::copy_nonoverlapping(values.as_ptr(), vector, 3) };
    }
    if !errflg.is_null() {
        // SAFETY: the caller passes a writable ERRFLG.
        unsafe { *errflg = failed };
    }
}

/// Runs `call` and turns an error or a panic into `None`.
fn guarded(call: impl FnOnce() -> Option<[f64; 3]>) -> Option<[f64; 3]> {
    catch_unwind(std::panic::AssertUnwindSafe(call))
        .ok()
        .flatten()
}

/// `void c_bistop(double x, double xd, double x1, double x2, double k,
/// double e, double cmax, double d, int iord, double *vector, int *errflg)`
///
/// # Safety
/// `vector` is null or points to three writable doubles; `errflg` is null or
/// points to a writable int.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn c_bistop(
    x: c_double,
    xd: c_double,
    x1: c_double,
    x2: c_double,
    k: c_double,
    e: c_double,
    cmax: c_double,
    d: c_double,
    iord: c_int,
    vector: *mut c_double,
    errflg: *mut c_int,
) {
    let result = guarded(|| utility::bistop(x, xd, x1, x2, k, e, cmax, d, iord).ok());
    // SAFETY: forwarded from this function's contract.
    unsafe { report(result, vector, errflg) };
}

/// `void c_impact(double x, double xd, double x1, double k, double e,
/// double cmax, double d, int iord, double *vector, int *errflg)`
///
/// # Safety
/// As [`c_bistop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn c_impact(
    x: c_double,
    xd: c_double,
    x1: c_double,
    k: c_double,
    e: c_double,
    cmax: c_double,
    d: c_double,
    iord: c_int,
    vector: *mut c_double,
    errflg: *mut c_int,
) {
    let result = guarded(|| utility::impact(x, xd, x1, k, e, cmax, d, iord).ok());
    // SAFETY: forwarded from this function's contract.
    unsafe { report(result, vector, errflg) };
}

/// `void c_step(double x, double x0, double h0, double x1, double h1,
/// int iord, double *value, int *errflg)`
///
/// # Safety
/// `value` is null or points to a writable double; `errflg` is null or
/// points to a writable int.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn c_step(
    x: c_double,
    x0: c_double,
    h0: c_double,
    x1: c_double,
    h1: c_double,
    iord: c_int,
    value: *mut c_double,
    errflg: *mut c_int,
) {
    let result = guarded(|| {
        utility::step(x, x0, h0, x1, h1, iord)
            .ok()
            .map(|value| [value, 0.0, 0.0])
    });
    if !value.is_null() {
        // SAFETY: the caller passes a writable VALUE.
        unsafe { *value = result.map_or(0.0, |entries| entries[0]) };
    }
    if !errflg.is_null() {
        // SAFETY: the caller passes a writable ERRFLG.
        unsafe { *errflg = c_int::from(result.is_none()) };
    }
}

/// Reads a FORTRAN argument passed by reference (0 when null).
///
/// # Safety
/// `pointer` is null or points to a readable value.
unsafe fn read<T: Copy + Default>(pointer: *const T) -> T {
    if pointer.is_null() {
        T::default()
    } else {
        // SAFETY: from this function's contract.
        unsafe { *pointer }
    }
}

/// IORD passed by reference: a null pointer is no valid order (-1), so the
/// call sets ERRFLG rather than taking order 0.
///
/// # Safety
/// `pointer` is null or valid for reading.
unsafe fn read_order(pointer: *const c_int) -> c_int {
    if pointer.is_null() {
        -1
    } else {
        // SAFETY: from this function's contract.
        unsafe { read(pointer) }
    }
}

/// `CALL BISTOP(X, XD, X1, X2, K, E, CMAX, D, IORD, VECTOR, ERRFLG)` from
/// FORTRAN: DOUBLE PRECISION arguments, INTEGER IORD, DOUBLE PRECISION
/// VECTOR(3), LOGICAL ERRFLG.
///
/// # Safety
/// Every pointer is null or valid for its FORTRAN type; VECTOR has 3 entries.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bistop_(
    x: *const c_double,
    xd: *const c_double,
    x1: *const c_double,
    x2: *const c_double,
    k: *const c_double,
    e: *const c_double,
    cmax: *const c_double,
    d: *const c_double,
    iord: *const c_int,
    vector: *mut c_double,
    errflg: *mut c_int,
) {
    // SAFETY: forwarded from this function's contract.
    unsafe {
        c_bistop(
            read(x),
            read(xd),
            read(x1),
            read(x2),
            read(k),
            read(e),
            read(cmax),
            read(d),
            read_order(iord),
            vector,
            errflg,
        );
    }
}

/// `CALL IMPACT(X, XD, X1, K, E, CMAX, D, IORD, VECTOR, ERRFLG)` from FORTRAN.
///
/// # Safety
/// As [`bistop_`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn impact_(
    x: *const c_double,
    xd: *const c_double,
    x1: *const c_double,
    k: *const c_double,
    e: *const c_double,
    cmax: *const c_double,
    d: *const c_double,
    iord: *const c_int,
    vector: *mut c_double,
    errflg: *mut c_int,
) {
    // SAFETY: forwarded from this function's contract.
    unsafe {
        c_impact(
            read(x),
            read(xd),
            read(x1),
            read(k),
            read(e),
            read(cmax),
            read(d),
            read_order(iord),
            vector,
            errflg,
        );
    }
}

/// `CALL STEP(X, X0, H0, X1, H1, IORD, VALUE, ERRFLG)` from FORTRAN.
///
/// # Safety
/// Every pointer is null or valid for its FORTRAN type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn step_(
    x: *const c_double,
    x0: *const c_double,
    h0: *const c_double,
    x1: *const c_double,
    h1: *const c_double,
    iord: *const c_int,
    value: *mut c_double,
    errflg: *mut c_int,
) {
    // SAFETY: forwarded from this function's contract.
    unsafe {
        c_step(
            read(x),
            read(x0),
            read(h0),
            read(x1),
            read(h1),
            read_order(iord),
            value,
            errflg,
        );
    }
}
