//! mbexpr reads the function expressions of multibody-dynamics models (the
//! language of the Adams family of solvers: `STEP(TIME, 0, 0, 1, 10)`,
//! `BISTOP(DX(2,1,1), VX(2,1,1,1), -5, 5, 1e5, 2.2, 100, 0.1)`), checks them,
//! and evaluates them with exact first and second derivatives.
//!
//! The pipeline has one stage per module, each with its own error type:
//!
//! 1. [`parse`] — text to a syntax tree with byte spans ([`syntax`]);
//! 2. [`check()`] — names resolved, arguments counted and sorted, constant
//!    arguments checked against the functions' rules ([`mod@check`]);
//! 3. [`compile()`] — a flat [`Program`] for a list of inputs, constants folded
//!    ([`mod@compile`]);
//! 4. evaluate — the value over `f64`, or value, gradient and Hessian over
//!    dual numbers ([`eval`]).
//!
//! ```
//! use mbexpr::Order;
//!
//! let tree = mbexpr::parse("BISTOP(x, v, -10, 10, 1e5, 2.2, 100, 0.1)")?;
//! let checked = mbexpr::check(&tree)?;
//! let program = mbexpr::compile(&checked, &["x", "v"])?;
//!
//! // Beyond the upper wall (x2 = 10) by 0.05, moving outwards at 0.7:
//! let force = program.value(&[10.05, 0.7])?;
//! assert!(force < 0.0);
//!
//! // The gradient and Hessian in (x, v), for an implicit integrator.
//! let result = program.evaluate(&[10.05, 0.7], &[0, 1], Order::Hessian)?;
//! let gradient = result.gradient.unwrap();
//! assert_eq!(result.value, force);
//! assert!((gradient[1] - -50.0).abs() < 1e-9); // dF/dv = -c, half of cmax mid-ramp
//! assert!(result.hessian.unwrap()[(1, 1)] == 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Errors carry the [`Span`] of the text they speak of; the library never
//! prints. [`Location::of`] turns a span's offset into a line and column.

pub mod catalog;
pub mod check;
pub mod compile;
pub mod embed;
mod errors;
pub mod eval;
pub mod ffi;
pub mod help;
pub mod integrate;
pub mod kinematics;
pub mod kinks;
pub mod laws;
pub mod model;
pub mod number;
mod ops;
pub mod scene;
mod shown;
pub mod simulate;
pub mod span;
pub mod syntax;
pub mod utility;

pub use check::{CheckError, Checked, check};
pub use compile::{CompileError, Program, compile, compile_in_model, compile_in_scene};
pub use errors::Errors;
pub use eval::{EvalError, Evaluation, Evaluator, Order, Run};
pub use scene::Scene;
pub use shown::{Counted, Shown, ShownBuffer};
pub use span::{LineIndex, Location, Span};
pub use syntax::{ParseError, parse};
