//! Readers: a [`Model`](super::Model) from a solver dataset (`.adm` with
//! its `.acf`) or from a scene file, every problem reported at its place.

mod dataset;
mod joints;
mod scene;

pub use dataset::{from_dataset, run_settings};
pub use scene::from_scene;
