//! mbexpr: read, check and evaluate the function expressions of multibody models.
pub mod catalog;
pub mod check;
pub mod compile;
pub mod eval;
pub mod laws;
pub mod number;
pub mod span;
pub mod syntax;

pub use check::{CheckError, Checked, check};
pub use span::{Location, Span};
pub use syntax::{ParseError, parse};
pub use compile::{CompileError, Program, compile};
pub use eval::{EvalError, Evaluation, Evaluator, Order};
