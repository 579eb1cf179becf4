//! `mbexpr plot`: an expression against one of its variables as an SVG, with
//! its first and second derivatives on request.

use crate::support::plotting::{Plot, PlotRequest, Sampling, curves, parse_range, render_svg};
use crate::support::{files, model_values, values};

#[derive(clap::Args)]
pub struct Args {
    /// The expression, e.g. "BISTOP(x, v, -1, 1, 1e4, 1.5, 50, 0.1)".
    #[arg(allow_hyphen_values = true)]
    expression: String,
    /// The variable along the x axis and its range, NAME=A..B.
    #[arg(long, value_name = "NAME=A..B")]
    over: String,
    /// A variable's value, NAME=VALUE (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// A scene (TOML) the expression is evaluated in.
    #[arg(long, value_name = "FILE.toml", conflicts_with = "model")]
    scene: Option<String>,
    /// A solver dataset the expression is evaluated in, at its initial
    /// configuration; --over and --set name TIME, DIF(id) or a part's
    /// state (PART/3.x).
    #[arg(long, value_name = "FILE.adm")]
    model: Option<String>,
    /// Also plot the first and second derivative in the plotted variable.
    #[arg(long)]
    derivatives: bool,
    /// Evenly spaced samples (the points where STEP, IMPACT, BISTOP ... change branch are added).
    #[arg(long, default_value_t = 400, value_parser = clap::value_parser!(u32).range(2..=1_000_000))]
    samples: u32,
    /// The SVG file to write.
    #[arg(short = 'o', long = "output", value_name = "FILE.svg")]
    output: String,
}

pub fn run(args: &Args, out: &mut impl std::io::Write) -> Result<crate::Outcome, crate::Fatal> {
    use crate::Fatal;
    let source = &args.expression;
    let fail = |span, message: String| {
        Fatal::input(crate::support::render::diagnostic(
            "", source, span, &message,
        ))
    };
    let tree = mbexpr::parse(source).map_err(|error| fail(error.span(), error.to_string()))?;
    let checked =
        mbexpr::check(&tree).map_err(|errors| fail(errors[0].span(), errors[0].to_string()))?;
    let (over, start, end) = parse_range(&args.over)
        .map_err(|message| Fatal::usage(format!("error: --over {message}")))?;
    if let Some(path) = &args.model {
        let sampling = Sampling {
            text: source,
            over: &over,
            range: (start, end),
            derivatives: args.derivatives,
        };
        let plot =
            model_values::curves(path, &args.set, &checked, &sampling, args.samples as usize)?;
        return write(args, &over, &plot, out);
    }
    let bindings = args
        .set
        .iter()
        .map(|assignment| values::parse_assignment(assignment))
        .collect::<Result<Vec<_>, _>>()?;
    let scene = args.scene.as_deref().map(files::read_scene).transpose()?;
    let request = PlotRequest {
        text: source,
        checked: &checked,
        scene: scene.as_ref(),
        bindings: &bindings,
        over: &over,
        range: (start, end),
        samples: args.samples as usize,
        derivatives: args.derivatives,
    };
    let plot = curves(&request).map_err(|message| Fatal::input(format!("error: {message}")))?;
    write(args, &over, &plot, out)
}

/// Writes the plot to its file and says so.
fn write(
    args: &Args,
    over: &str,
    plot: &Plot,
    out: &mut impl std::io::Write,
) -> Result<crate::Outcome, crate::Fatal> {
    render_svg(&args.output, over, plot).map_err(|message| {
        crate::Fatal::usage(format!("error: cannot write {}: {message}", args.output))
    })?;
    writeln!(out, "{}", plot.summary(&args.output, over))?;
    Ok(crate::Outcome::Success)
}
