//! The integration tests, one binary (`cargo test` links it once).
//!
//! Each stage has a module with one `check(input) -> String` helper and its
//! cases as data, one per line.

mod accelerations;
mod architecture;
mod beams;
mod checker;
mod cli;
mod contacts;
mod control;
mod corpus;
mod couplers;
mod curve_curve;
mod delays;
mod diagnostics;
mod documents;
mod eval;
mod ffi;
mod force_values;
mod friction;
mod general_constraints;
mod implicit_diffs;
mod initial_conditions;
mod integrate;
mod integrate_problems;
mod joint_kinds;
mod joints;
mod joints_random;
mod loop_values;
mod magnitudes;
mod massless;
mod model;
mod motions;
mod nforce;
mod numerics;
mod parse;
mod plot;
mod point_curves;
mod probes;
mod properties;
mod reactions;
mod reference;
mod repl;
mod scene;
mod sensors;
mod simulate;
mod simulate_variants;
mod span;
mod spline;
mod statics;
mod turns;
mod view_files;

/// `case\n  => check(case)\n` for every non-blank line of `cases`: the
/// snapshot form of a data-driven test.
fn table(cases: &str, check: impl Fn(&str) -> String) -> String {
    cases
        .lines()
        .map(str::trim)
        .filter(|case| !case.is_empty())
        .map(|case| format!("{case}\n  => {}\n", check(case)))
        .collect()
}
