//! What the commands share: reading files and scenes, numbers and
//! assignments on the command line, binding a checked expression to values,
//! files of points, result records, plots, a model's expressions at its
//! initial configuration, and rendering problems at their places. A
//! command's file imports from here and from `main.rs`, never from another
//! command (`tests/architecture.rs` holds this).

pub mod binding;
pub mod files;
pub mod model_values;
pub mod plotting;
pub mod points;
pub mod record;
pub mod render;
pub mod values;
