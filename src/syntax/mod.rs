//! Stage 1, parse: text to a syntax tree with byte spans.
//!
//! The grammar is `grammar/expression.pest`; [`parse`] runs it and folds
//! operator precedence with pest's Pratt parser. A failed parse is explained by
//! a small token scanner (`scan`) in words a user understands.

pub mod ast;
mod error;
mod parse;
mod scan;

pub use error::ParseError;
pub use parse::parse;
pub use scan::{MAX_NESTING, without_comment};
