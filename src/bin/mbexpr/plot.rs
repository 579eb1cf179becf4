//! `mbexpr plot`: an expression against one of its variables as an SVG, with
//! its first and second derivatives on request; shared with the REPL's `:plot`.

use plotters::prelude::*;

use mbexpr::{Checked, Order, Scene};

/// One curve to draw: a name and its points.
pub struct Curve {
    /// The legend's text.
    pub label: String,
    /// `(x, y)` where the expression could be evaluated.
    pub points: Vec<(f64, f64)>,
}

/// What to plot: an expression, the values of its other inputs, the variable
/// along the x axis and its range.
pub struct PlotRequest<'a> {
    /// The expression's text (for the title).
    pub text: &'a str,
    /// The checked expression.
    pub checked: &'a Checked,
    /// The scene, if any.
    pub scene: Option<&'a Scene>,
    /// Other inputs and their values.
    pub bindings: &'a [(String, f64)],
    /// The variable along the x axis.
    pub over: &'a str,
    /// Its range.
    pub range: (f64, f64),
    /// How many evenly spaced samples (break points are added).
    pub samples: usize,
    /// Whether to add the first and second derivative in `over`.
    pub derivatives: bool,
}

/// The curves of a plot, and the break points to mark on it.
pub struct Plot {
    /// Value, and derivatives on request.
    pub curves: Vec<Curve>,
    /// Where a STEP, IMPACT, BISTOP ... changes branch, inside the range.
    pub marks: Vec<f64>,
}

/// Evaluates the curves; a point where evaluation fails is left out.
pub fn curves(request: &PlotRequest<'_>) -> Result<Plot, String> {
    let bound = crate::binding::bind(
        request.checked,
        request.scene,
        request.bindings,
        &[request.over.to_string()],
    )
    .map_err(|errors| errors.to_string())?;
    let (program, mut values) = (bound.program, bound.values);
    let over = program
        .input_index(request.over)
        .expect("the plotted variable is an input");
    let breakpoints = mbexpr::kinks::breakpoints(request.checked, request.over);
    let xs = mbexpr::kinks::samples(
        request.range.0,
        request.range.1,
        request.samples,
        &breakpoints,
    );
    let order = if request.derivatives {
        Order::Hessian
    } else {
        Order::Value
    };
    let count = if request.derivatives { 3 } else { 1 };
    let mut curves: Vec<Curve> = (0..count)
        .map(|index| Curve {
            label: match index {
                0 => request.text.to_string(),
                1 => format!("d/d{}", request.over),
                _ => format!("d²/d{}²", request.over),
            },
            points: Vec::new(),
        })
        .collect();
    // The samples are one run: AX, AY, AZ stay continuous along the curve.
    let mut run = program.run();
    for x in xs {
        values[over] = x;
        let Ok(evaluation) = run.evaluate(&values, &[over], order) else {
            continue;
        };
        curves[0].points.push((x, evaluation.value));
        if let (Some(gradient), Some(hessian)) = (&evaluation.gradient, &evaluation.hessian)
            && request.derivatives
        {
            curves[1].points.push((x, gradient[0]));
            curves[2].points.push((x, hessian[(0, 0)]));
        }
    }
    if curves[0].points.is_empty() {
        return Err(format!(
            "the expression could not be evaluated anywhere in {}..{}",
            request.range.0, request.range.1
        ));
    }
    let (low, high) = request.range;
    let marks = breakpoints
        .into_iter()
        .filter(|point| (low..=high).contains(point))
        .collect();
    Ok(Plot { curves, marks })
}

/// Draws the curves into an SVG file, one panel each, the x axis labelled
/// with the variable's name and the break points marked by dashed lines.
pub fn render_svg(path: &str, over: &str, plot: &Plot) -> Result<(), String> {
    let curves = &plot.curves;
    let height = 320 * curves.len() as u32;
    let root = SVGBackend::new(path, (900, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|error| error.to_string())?;
    let panels = root.split_evenly((curves.len(), 1));
    let colors = [BLUE, RED, GREEN];
    for (index, ((panel, curve), color)) in panels.iter().zip(curves).zip(colors).enumerate() {
        let (x_min, x_max) = bounds(curve.points.iter().map(|point| point.0));
        let (y_min, y_max) = bounds(curve.points.iter().map(|point| point.1));
        let mut chart = ChartBuilder::on(panel)
            .caption(&curve.label, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(x_min..x_max, y_min..y_max)
            .map_err(|error| error.to_string())?;
        chart
            .configure_mesh()
            .x_desc(over)
            .y_desc(if index == 0 {
                "value"
            } else {
                curve.label.as_str()
            })
            .draw()
            .map_err(|error| error.to_string())?;
        for &mark in &plot.marks {
            chart
                .draw_series(DashedLineSeries::new(
                    [(mark, y_min), (mark, y_max)],
                    6,
                    4,
                    BLACK.mix(0.35).stroke_width(1),
                ))
                .map_err(|error| error.to_string())?;
        }
        chart
            .draw_series(LineSeries::new(
                curve.points.iter().copied(),
                color.stroke_width(2),
            ))
            .map_err(|error| error.to_string())?
            .label(&curve.label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperMiddle)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|error| error.to_string())?;
    }
    root.present().map_err(|error| error.to_string())
}

/// The range of the values, widened a little (and made non-empty).
fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), value| {
        (low.min(value), high.max(value))
    });
    let pad = ((high - low) * 0.05).max(1e-9 * low.abs().max(high.abs()).max(1.0));
    (low - pad, high + pad)
}

/// `NAME=A..B` to its parts.
pub fn parse_range(text: &str) -> Result<(String, f64, f64), String> {
    let (name, range) = text
        .split_once('=')
        .ok_or_else(|| format!("`{text}`: write NAME=A..B"))?;
    let (start, end) = range
        .split_once("..")
        .ok_or_else(|| format!("`{range}`: write the range as A..B"))?;
    let number = |text: &str| {
        text.trim()
            .parse::<f64>()
            .ok()
            .filter(|value| value.is_finite())
            .ok_or_else(|| format!("`{}` is not a finite number", text.trim()))
    };
    let (start, end) = (number(start)?, number(end)?);
    if start >= end {
        return Err(format!(
            "the range {start}..{end} is empty: A must be less than B"
        ));
    }
    Ok((name.trim().to_string(), start, end))
}

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
    #[arg(long, value_name = "FILE.toml")]
    scene: Option<String>,
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
    let fail =
        |span, message: String| Fatal::input(crate::render::diagnostic("", source, span, &message));
    let tree = mbexpr::parse(source).map_err(|error| fail(error.span(), error.to_string()))?;
    let checked =
        mbexpr::check(&tree).map_err(|errors| fail(errors[0].span(), errors[0].to_string()))?;
    let (over, start, end) = parse_range(&args.over)
        .map_err(|message| Fatal::usage(format!("error: --over {message}")))?;
    let bindings = args
        .set
        .iter()
        .map(|assignment| crate::eval_cmd::parse_assignment(assignment))
        .collect::<Result<Vec<_>, _>>()?;
    let scene = args
        .scene
        .as_deref()
        .map(crate::eval_cmd::read_scene)
        .transpose()?;
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
    render_svg(&args.output, &over, &plot).map_err(|message| {
        Fatal::usage(format!("error: cannot write {}: {message}", args.output))
    })?;
    writeln!(
        out,
        "wrote {} ({} points)",
        args.output,
        plot.curves[0].points.len()
    )?;
    Ok(crate::Outcome::Success)
}
