//! Plots as SVG: an expression's curves against one of its variables (with
//! its first and second derivatives on request), drawn with their break
//! points and gaps; for `plot`, the REPL's `:plot`, `eval --model`'s and
//! `simulate --plot`.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use mbexpr::{Checked, Counted, Evaluation, Order, Scene, Shown};

/// One curve to draw: a name and its points.
pub struct Curve {
    /// The legend's text.
    pub label: String,
    /// `(x, y)` where the expression could be evaluated, in runs between
    /// the samples where it could not.
    pub segments: Vec<Vec<(f64, f64)>>,
}

impl Curve {
    fn points(&self) -> impl Iterator<Item = &(f64, f64)> {
        self.segments.iter().flatten()
    }
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

/// The curves of a plot, the break points to mark on it and the stretches
/// where it could not be evaluated.
pub struct Plot {
    /// Value, and derivatives on request.
    pub curves: Vec<Curve>,
    /// Where a STEP, IMPACT, BISTOP ... changes branch, inside the range.
    pub marks: Vec<f64>,
    /// Ranges of x with samples that failed, from the last good sample
    /// before to the first good one after.
    pub gaps: Vec<(f64, f64)>,
    /// How many samples failed, and the first failure's message and place.
    pub failed: usize,
    /// The first failure: `x` and what went wrong.
    pub first_failure: Option<(f64, String)>,
    /// How many samples were taken.
    pub sampled: usize,
    /// The range of x asked for.
    pub range: (f64, f64),
    /// What the x axis's title adds after the variable's name: how the
    /// curves were drawn, when it is not from dense samples.
    pub note: Option<String>,
    /// Whether each point is drawn as a dot too (the curves join few points).
    pub dots: bool,
}

impl Plot {
    /// `wrote FILE (N points)`, with the failed samples when there were.
    pub fn summary(&self, file: &str, over: &str) -> String {
        let points = self.curves[0].points().count();
        let mut text = format!("wrote {file} ({}", Counted(points, "point"));
        if let Some((x, message)) = &self.first_failure {
            text += &format!(
                "; {} of {} could not be evaluated and are a gap, the first at {over} = {}: {message}",
                self.failed,
                Counted(self.sampled, "sample"),
                Shown(*x)
            );
        }
        text + ")"
    }
}

/// Evaluates the curves; a sample where evaluation fails leaves a gap.
pub fn curves(request: &PlotRequest<'_>) -> Result<Plot, String> {
    let bound = super::binding::bind(
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
    let (low, high) = request.range;
    let even = mbexpr::kinks::samples(low, high, request.samples, &[]);
    let marks = mbexpr::kinks::breakpoints(&program, &values, over, &even);
    let xs = mbexpr::kinks::samples(low, high, request.samples, &marks);
    let order = if request.derivatives {
        Order::Hessian
    } else {
        Order::Value
    };
    // The samples are one run: AX, AY, AZ stay continuous along the curve.
    let mut run = program.run();
    let sampling = Sampling {
        text: request.text,
        over: request.over,
        range: request.range,
        derivatives: request.derivatives,
    };
    trace(&sampling, &xs, marks, |x| {
        values[over] = x;
        run.evaluate(&values, &[over], order)
            .map_err(|error| error.to_string())
    })
}

/// What a curve is sampled along: the expression's text (the first
/// curve's name), the variable along the x axis, its range, and whether
/// the first and second derivatives in it are curves too.
pub struct Sampling<'a> {
    /// The expression's text.
    pub text: &'a str,
    /// The variable along the x axis.
    pub over: &'a str,
    /// Its range.
    pub range: (f64, f64),
    /// Whether to add the first and second derivative in `over`.
    pub derivatives: bool,
}

/// The plot of `evaluate` (the value at `x`, with the derivatives in `x`
/// when asked for) at each of `xs`, sorted; a sample where it fails leaves
/// a gap. `marks` are the break points to draw.
pub fn trace(
    sampling: &Sampling<'_>,
    xs: &[f64],
    marks: Vec<f64>,
    mut evaluate: impl FnMut(f64) -> Result<Evaluation, String>,
) -> Result<Plot, String> {
    let count = if sampling.derivatives { 3 } else { 1 };
    let mut curves: Vec<Curve> = (0..count)
        .map(|index| Curve {
            label: match index {
                0 => sampling.text.to_string(),
                1 => format!("d/d{}", sampling.over),
                _ => format!("d²/d{}²", sampling.over),
            },
            segments: vec![Vec::new()],
        })
        .collect();
    let mut plot = Plot {
        curves: Vec::new(),
        marks,
        gaps: Vec::new(),
        failed: 0,
        first_failure: None,
        sampled: xs.len(),
        range: sampling.range,
        note: None,
        dots: false,
    };
    let (mut last_good, mut gap_open) = (None, false);
    for &x in xs {
        let evaluation = match evaluate(x) {
            Ok(evaluation) => evaluation,
            Err(error) => {
                plot.failed += 1;
                plot.first_failure.get_or_insert((x, error));
                if !gap_open {
                    gap_open = true;
                    plot.gaps.push((last_good.unwrap_or(x), sampling.range.1));
                    for curve in &mut curves {
                        curve.segments.push(Vec::new());
                    }
                }
                continue;
            }
        };
        if gap_open {
            gap_open = false;
            plot.gaps.last_mut().expect("an open gap").1 = x;
        }
        last_good = Some(x);
        let mut ys = vec![evaluation.value];
        if let (Some(gradient), Some(hessian)) = (&evaluation.gradient, &evaluation.hessian) {
            ys.extend([gradient[0], hessian[(0, 0)]]);
        }
        for (curve, y) in curves.iter_mut().zip(ys) {
            curve.segments.last_mut().expect("a segment").push((x, y));
        }
    }
    if curves[0].points().next().is_none() {
        let reason = plot
            .first_failure
            .map(|(x, message)| {
                format!(" (at {} = {}: {message})", sampling.over, mbexpr::Shown(x))
            })
            .unwrap_or_default();
        let (low, high) = sampling.range;
        return Err(format!(
            "the expression could not be evaluated anywhere in {}..{}{reason}",
            mbexpr::Shown(low),
            mbexpr::Shown(high)
        ));
    }
    for curve in &mut curves {
        curve.segments.retain(|segment| !segment.is_empty());
    }
    plot.curves = curves;
    Ok(plot)
}

/// Draws the curves as SVG into `path`, one panel each, the x axis labelled
/// with the variable's name, the break points marked by dashed lines and
/// the stretches that could not be evaluated shaded. Only SVG is written:
/// a name with the extension of another image format is refused.
pub fn render_svg(path: &str, over: &str, plot: &Plot) -> Result<(), String> {
    check_svg_name(path)?;
    let mut svg = String::new();
    draw(SVGBackend::with_string(&mut svg, size(plot)), over, plot)?;
    std::fs::write(path, svg).map_err(|error| error.to_string())
}

/// Refuses a plot file named for another picture format than SVG.
pub fn check_svg_name(path: &str) -> Result<(), String> {
    const OTHER_FORMATS: [&str; 10] = [
        "png", "jpg", "jpeg", "gif", "bmp", "tif", "tiff", "webp", "pdf", "eps",
    ];
    let extension = std::path::Path::new(path)
        .extension()
        .map(|extension| extension.to_string_lossy().to_ascii_lowercase());
    match extension.filter(|extension| OTHER_FORMATS.contains(&extension.as_str())) {
        Some(extension) => Err(format!(
            "plots are written as SVG, not {}: name the file FILE.svg (for a PNG, convert it, e.g. rsvg-convert FILE.svg -o FILE.png)",
            extension.to_uppercase()
        )),
        None => Ok(()),
    }
}

/// The picture's size in pixels: 320 high per panel.
fn size(plot: &Plot) -> (u32, u32) {
    (900, 320 * plot.curves.len() as u32)
}

fn draw<B: DrawingBackend>(backend: B, over: &str, plot: &Plot) -> Result<(), String> {
    let error = |error: DrawingAreaErrorKind<B::ErrorType>| error.to_string();
    let curves = &plot.curves;
    let root = backend.into_drawing_area();
    root.fill(&WHITE).map_err(error)?;
    let panels = root.split_evenly((curves.len(), 1));
    let colors = [
        BLUE,
        RED,
        RGBColor(0, 150, 0),
        MAGENTA,
        RGBColor(230, 130, 0),
        CYAN,
        BLACK,
        RGBColor(120, 60, 0),
    ];
    // Plotters ticks an axis only when its width is above 2e-16 and
    // finite: each axis is drawn in units of a power of ten that brings
    // its values near 1, and its labels say the power.
    let x_axis = Axis::new([plot.range.0, plot.range.1].into_iter(), false);
    let y_axes: Vec<Axis> = curves
        .iter()
        .map(|curve| {
            let ys: Vec<f64> = curve.points().map(|point| point.1).collect();
            let (low, high) = bulk(&ys);
            Axis::new(ys.into_iter().filter(|y| (low..=high).contains(y)), true)
        })
        .collect();
    // One width of the y labels for every panel, so that the x axes of
    // the stacked panels line up.
    let label_area = y_axes.iter().map(Axis::label_area).max().unwrap_or(0);
    for (index, ((panel, (curve, y_axis)), color)) in panels
        .iter()
        .zip(curves.iter().zip(&y_axes))
        .zip(colors.into_iter().cycle())
        .enumerate()
    {
        // The note once, under the last panel.
        let x_desc = match &plot.note {
            Some(note) if index + 1 == curves.len() => format!("{over} ({note})"),
            _ => over.to_string(),
        };
        let (x_low, x_high) = (x_axis.scaled(x_axis.low), x_axis.scaled(x_axis.high));
        let (y_low, y_high) = (y_axis.scaled(y_axis.low), y_axis.scaled(y_axis.high));
        // A point beyond the axis is drawn at its edge, where it leaves.
        let at = |(x, y): (f64, f64)| (x_axis.scaled(x), y_axis.scaled(y).clamp(y_low, y_high));
        let mut chart = ChartBuilder::on(panel)
            .caption(&curve.label, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(label_area)
            .build_cartesian_2d(x_low..x_high, y_low..y_high)
            .map_err(error)?;
        chart
            .configure_mesh()
            .x_desc(x_desc.as_str())
            .y_desc(axis_title(&curve.label))
            .x_label_formatter(&|x| x_axis.label(*x))
            .y_label_formatter(&|y| y_axis.label(*y))
            .draw()
            .map_err(error)?;
        for &(start, end) in &plot.gaps {
            chart
                .draw_series([Rectangle::new(
                    [(x_axis.scaled(start), y_low), (x_axis.scaled(end), y_high)],
                    RED.mix(0.08).filled(),
                )])
                .map_err(error)?;
        }
        for &mark in &plot.marks {
            let mark = x_axis.scaled(mark);
            chart
                .draw_series(DashedLineSeries::new(
                    [(mark, y_low), (mark, y_high)],
                    6,
                    4,
                    BLACK.mix(0.35).stroke_width(1),
                ))
                .map_err(error)?;
        }
        for segment in &curve.segments {
            let points = segment.iter().map(|&point| at(point));
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(error)?;
            if plot.dots {
                let dots = segment
                    .iter()
                    .map(|&point| Circle::new(at(point), 2, color.filled()));
                chart.draw_series(dots).map_err(error)?;
            }
        }
        let middle = (x_low + x_high) / 2.0;
        for (rank, exit) in exits(curve, y_axis).iter().enumerate() {
            let (x, y) = at((exit.x, exit.y));
            // An arrowhead at the edge, pointing the way the curve leaves.
            let tip = if exit.y > y_axis.high { 1 } else { -1 };
            let head = Polygon::new(vec![(0, 0), (-5, 9 * tip), (5, 9 * tip)], color.filled());
            let text = format!("{} at {over} = {}", rounded(exit.y), rounded(exit.x));
            let anchor = Pos::new(
                if x > middle { HPos::Right } else { HPos::Left },
                if tip > 0 { VPos::Top } else { VPos::Bottom },
            );
            let style = ("sans-serif", 13).into_font().color(&BLACK).pos(anchor);
            let shift = if x > middle { -8 } else { 8 };
            chart
                .draw_series([EmptyElement::at((x, y)) + head])
                .map_err(error)?;
            // The most extreme few are labelled; the others keep their arrowhead.
            if rank < MAX_EXIT_LABELS {
                let label = Text::new(text, (shift, 12 * tip), style);
                chart
                    .draw_series([EmptyElement::at((x, y)) + label])
                    .map_err(error)?;
            }
        }
    }
    root.present().map_err(error)
}

/// How many places where a curve leaves its axis are labelled with their value.
const MAX_EXIT_LABELS: usize = 6;

/// The y axis's title: the curve's name, shortened with an ellipsis when
/// it is longer than a panel is high (the caption above has it whole).
fn axis_title(label: &str) -> String {
    const FITS: usize = 36;
    if label.chars().count() <= FITS {
        return label.to_string();
    }
    let kept: String = label.chars().take(FITS - 1).collect();
    kept + "…"
}

/// `value` to three significant digits, as a tick or a note shows it.
fn rounded(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude == 0.0 || (1e-3..1e5).contains(&magnitude) {
        let text = format!(
            "{:.*}",
            (2 - magnitude.log10().floor() as i32).max(0) as usize,
            value
        );
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            text
        }
    } else {
        let text = format!("{value:.2e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        format!("{mantissa}e{exponent}")
    }
}

/// Where a curve leaves its axis: the most extreme point of each run of
/// points beyond it.
struct Exit {
    x: f64,
    y: f64,
}

/// The runs of `curve`'s points beyond `axis`, each by its most extreme
/// point, the most extreme run first.
fn exits(curve: &Curve, axis: &Axis) -> Vec<Exit> {
    let beyond = |y: f64| {
        if y > axis.high {
            y - axis.high
        } else if y < axis.low {
            axis.low - y
        } else {
            0.0
        }
    };
    let mut found: Vec<Exit> = Vec::new();
    for segment in &curve.segments {
        let mut run: Option<Exit> = None;
        for &(x, y) in segment {
            if beyond(y) == 0.0 {
                found.extend(run.take());
                continue;
            }
            let same_side = run
                .as_ref()
                .is_some_and(|exit| (exit.y > axis.high) == (y > axis.high));
            if !same_side {
                found.extend(run.take());
            }
            match &mut run {
                Some(exit) if beyond(y) <= beyond(exit.y) => {}
                _ => run = Some(Exit { x, y }),
            }
        }
        found.extend(run);
    }
    found.sort_by(|a, b| beyond(b.y).total_cmp(&beyond(a.y)));
    found
}

/// The range of `values` that sets a y axis: all of them, unless a few
/// lie far beyond the rest (the unbounded second derivative at a contact's
/// edge, a pole): then the range of those within three times the width of
/// the middle 98 % beyond it on either side, and the others leave the axis.
fn bulk(values: &[f64]) -> (f64, f64) {
    const TAIL: f64 = 0.01;
    const REACH: f64 = 3.0;
    let mut sorted: Vec<f64> = values.iter().copied().filter(|y| y.is_finite()).collect();
    sorted.sort_by(f64::total_cmp);
    let (Some(&first), Some(&last)) = (sorted.first(), sorted.last()) else {
        return (f64::NEG_INFINITY, f64::INFINITY);
    };
    let tail = ((sorted.len() as f64 * TAIL).ceil() as usize).max(1);
    if sorted.len() < 20 * tail {
        return (first, last);
    }
    let (low, high) = (sorted[tail], sorted[sorted.len() - 1 - tail]);
    // A flat bulk: a narrow peak on a constant is the curve's whole story.
    if low == high {
        return (first, last);
    }
    // Halves, so that no difference leaves the range of a double.
    let reach = (high / 2.0 - low / 2.0) * 2.0 * REACH;
    let (floor, ceiling) = (low - reach, high + reach);
    let within = sorted
        .iter()
        .copied()
        .filter(|y| (floor..=ceiling).contains(y));
    within.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), y| {
        (low.min(y), high.max(y))
    })
}

/// An axis: its range, the power of ten it is drawn in, and how its tick
/// labels are written.
struct Axis {
    low: f64,
    high: f64,
    /// The power of ten (a multiple of 3) of the axis's unit, 0 for plain
    /// numbers.
    exponent: i32,
    /// Digits after the point, enough to tell ticks apart.
    decimals: usize,
}

impl Axis {
    /// The axis for `values`, widened a little when `padded`.
    fn new(values: impl Iterator<Item = f64>, padded: bool) -> Axis {
        let (low, high) = bounds(values, padded);
        let magnitude = low.abs().max(high.abs());
        // Plain numbers from 0.001 to 99 999; engineering form beyond.
        let exponent =
            if (1e-3..1e5).contains(&magnitude) || magnitude == 0.0 || !magnitude.is_finite() {
                0
            } else {
                (magnitude.log10() / 3.0).floor() as i32 * 3
            };
        let mut axis = Axis {
            low,
            high,
            exponent,
            decimals: 0,
        };
        // A tenth of the range, in the axis's unit, sets the digits.
        let step = axis.scaled(high / 10.0) - axis.scaled(low / 10.0);
        axis.decimals = (-step.log10().floor()).clamp(0.0, 12.0) as usize;
        axis
    }

    /// `value` in the axis's unit: times 10 to the minus exponent, in two
    /// factors, since 10 to the 312th (for values near 1e-310) is no double.
    fn scaled(&self, value: f64) -> f64 {
        let half = -self.exponent / 2;
        value * 10f64.powi(half) * 10f64.powi(-self.exponent - half)
    }

    /// The label of the tick at `scaled` (in the axis's unit): `0.25`,
    /// `1.5e-9`, `250e6`.
    fn label(&self, scaled: f64) -> String {
        let mut text = format!("{scaled:.*}", self.decimals);
        if text.contains('.') {
            text = text.trim_end_matches('0').trim_end_matches('.').to_string();
        }
        if text.trim_start_matches(['-', '0', '.']).is_empty() {
            return "0".to_string();
        }
        if self.exponent == 0 {
            text
        } else {
            format!("{text}e{}", self.exponent)
        }
    }

    /// Room for the longest label and the axis title beside it, in pixels.
    fn label_area(&self) -> u32 {
        let longest = [self.low, (self.low + self.high) / 2.0, self.high]
            .map(|value| self.label(self.scaled(value)).chars().count())
            .into_iter()
            .max()
            .unwrap_or(1);
        30 + 8 * longest as u32
    }
}

/// The range of the values, widened by a twentieth on each side when
/// `padded` (and made non-empty), within a quarter of the largest double
/// either way: plotters loops forever on an axis whose width is not finite.
fn bounds(values: impl Iterator<Item = f64>, padded: bool) -> (f64, f64) {
    const LIMIT: f64 = f64::MAX / 4.0;
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), value| {
        (low.min(value), high.max(value))
    });
    let (low, high) = (low.clamp(-LIMIT, LIMIT), high.clamp(-LIMIT, LIMIT));
    let half_width = high / 2.0 - low / 2.0;
    let pad = if half_width > 0.0 {
        if padded { half_width / 10.0 } else { 0.0 }
    } else if low != 0.0 {
        low.abs() * 1e-9
    } else {
        1.0
    };
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
    if !(end - start).is_finite() {
        return Err(format!(
            "the range {} is wider than a double can hold: narrow it",
            range.trim()
        ));
    }
    if start >= end {
        let (start, end) = (mbexpr::Shown(start), mbexpr::Shown(end));
        return Err(format!(
            "the range {start}..{end} is empty: A must be less than B"
        ));
    }
    Ok((name.trim().to_string(), start, end))
}
