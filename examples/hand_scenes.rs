//! The five scenes of the simulation study and issue 22's variant,
//! integrated by the hand-written program of `benches/hand` (hand-coded
//! right-hand side, Jacobian and
//! switching functions, its own event driver), with output as `mbexpr
//! simulate` writes it: CSV rows `time,DIF(1),DIF(2)` on standard output
//! and one line of statistics on standard error. `scripts/work_precision.sh`
//! times it beside mbexpr, scipy and CVODE.
//!
//! ```sh
//! cargo run --release --example hand_scenes -- a1_ball --steps 199 --rtol 1e-9 --method dop853
//! ```

#[path = "../benches/hand/mod.rs"]
mod hand;

use std::io::{BufWriter, Write};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use mbexpr::integrate::Method;

/// Integrate one of the study's scenes with the hand-written program.
#[derive(Parser)]
struct Args {
    /// The scene: a1_ball, a2_stiff_ball, a3_softening_ball,
    /// a4_dropped_ball, b_slider or v_variant_ball.
    scene: String,
    /// Output steps: STEPS + 1 rows at equally spaced times from 0 to the
    /// scene's end.
    #[arg(long, default_value_t = 199)]
    steps: usize,
    /// The integration method: radau or dop853.
    #[arg(long, default_value = "radau")]
    method: Method,
    /// Relative tolerance.
    #[arg(long, default_value_t = 1e-6)]
    rtol: f64,
    /// Absolute tolerance (default: RTOL * 1e-3).
    #[arg(long)]
    atol: Option<f64>,
    /// List every located branch switch on standard error.
    #[arg(long)]
    events: bool,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let Some(scene) = hand::SCENES.iter().find(|scene| scene.name == args.scene) else {
        let names: Vec<&str> = hand::SCENES.iter().map(|scene| scene.name).collect();
        eprintln!(
            "error: no scene `{}`: expected one of {}",
            args.scene,
            names.join(", ")
        );
        return ExitCode::FAILURE;
    };
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let mut written = writeln!(out, "time,DIF(1),DIF(2)");
    let started = Instant::now();
    let result = hand::simulate(
        scene,
        args.method,
        args.rtol,
        args.atol.unwrap_or(args.rtol * 1e-3),
        args.steps,
        |time, x, v| {
            if written.is_ok() {
                written = writeln!(out, "{time},{x},{v}");
            }
        },
    );
    let wall_time = started.elapsed();
    if written.and_then(|()| out.flush()).is_err() {
        return ExitCode::SUCCESS; // a closed pipe: quietly
    }
    let cost = match result {
        Ok(cost) => cost,
        Err(error) => {
            eprintln!("error: {}: {error}", scene.name);
            return ExitCode::FAILURE;
        }
    };
    if args.events {
        for (time, from, to) in &cost.events {
            eprintln!("event t = {time}: {from} -> {to}");
        }
    }
    let stats = cost.stats;
    eprintln!(
        "{}: t = 0 .. {}, {}: {} steps ({} rejected), {} right-hand sides, {} jacobians, {} lu decompositions, {} events, {:.6} s",
        scene.name,
        scene.end,
        args.method,
        stats.steps,
        stats.rejected,
        stats.rhs_evaluations,
        stats.jacobian_evaluations,
        stats.lu_decompositions,
        cost.events.len(),
        wall_time.as_secs_f64()
    );
    ExitCode::SUCCESS
}
