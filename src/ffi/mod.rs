//! The C ABI of mbexpr, the only place with `unsafe` (the crate denies it
//! elsewhere): raw pointers from C, C++ and FORTRAN callers, the
//! `no_mangle` symbols they link to, and no panic crossing back
//! (`catch_unwind` around every entry point).
//!
//! - [`utility`]: the solver's utility subroutines with the calling
//!   sequences of user subroutines, `c_bistop`, `c_impact`, `c_step` and
//!   FORTRAN's `CALL BISTOP(...)`;
//! - [`capi`]: expressions compiled into thread-safe programs, evaluated
//!   with exact derivatives at a point and in bulk, model files checked and
//!   simulated (`include/mbexpr.h`, `include/mbexpr.hpp`,
//!   `include/mbexpr_c.f90`), over the safe [`crate::embed`].

// The one module tree with `unsafe` (Architecture Invariant in ARCHITECTURE.md).
#![allow(unsafe_code)]

pub mod capi;
pub mod utility;
