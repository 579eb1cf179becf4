//! The integration tests, one binary (`cargo test` links it once).
//!
//! Each stage has a module with one `check(input) -> String` helper and its
//! cases as data, one per line.

mod checker;
mod cli;
mod corpus;
mod eval;
mod model;
mod parse;
mod scene;
