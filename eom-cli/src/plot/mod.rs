//! SVG plots of the analyses (`--plot`, `--plot-poles`), drawn with `plotters`.
//!
//! * [`sweep::sweep_plot`]: eigenvalue branches over the swept parameter;
//! * [`bode::bode_plot`]: magnitude and phase of every output/input pair;
//! * [`poles::pole_map`]: poles and transmission zeros in the complex plane;
//! * [`compare::compare_plot`]: two models' sweeps of one parameter.
//!
//! Every plot is drawn into a string first and written in one go ([`Plot::write`]), so a
//! drawing failure never leaves half a file behind, and values that cannot be drawn (NaN,
//! infinite) are left out with a note in the plot and on standard error instead of breaking
//! the axes. The helpers here are shared by the three plots: axis ranges that never have zero
//! width, splitting a series at the values left out, colours, and the legend column.

pub mod bode;
pub mod compare;
pub mod geometry;
pub mod hankel;
pub mod labels;
pub mod locus;
pub mod poles;
pub mod shape;
pub mod sweep;
pub mod time;
pub mod zoom;

use crate::error::CliError;
use crate::format::g;
use plotters::coord::Shift;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// A drawing area of the SVG backend in pixel coordinates.
pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A series of `(x, y)` points, in drawing order.
pub(crate) type Series = Vec<(f64, f64)>;

/// A chart on an SVG drawing area with the axes `X` and `Y`.
pub(crate) type Chart<'a, 'b, X, Y> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<X, Y>>;

/// Width of the legend column on the right of every plot, in pixels.
const LEGEND_WIDTH: u32 = 270;

/// Stroke width of data curves. Grid and axis lines are 1 pixel wide, so the data curves
/// can be told apart in the SVG (the tests count them by this width).
pub const CURVE_WIDTH: u32 = 2;

/// Font of every text.
const FONT: &str = "sans-serif";

/// Light green of the stable region (stable intervals, stable half-plane).
const STABLE_FILL: RGBColor = RGBColor(214, 240, 214);

/// Largest magnitude drawn. Larger values are left out like non-finite ones: the axis
/// arithmetic (differences, padding, tick spacing) must stay finite.
const LARGEST: f64 = 1e100;

/// A drawn plot: the SVG text and the notes on what it leaves out.
#[derive(Clone, Debug)]
pub struct Plot {
    /// The SVG document.
    pub svg: String,
    /// Notes (values not drawn, nothing to draw); also printed in the plot's legend.
    pub notes: Vec<String>,
}

impl Plot {
    /// Writes the SVG to `path` by [`crate::output::write_output`] (a temporary file renamed
    /// into place; a FIFO or a device written without blocking). Failures name the file and
    /// the option that asked for it.
    pub fn write(&self, option: &str, path: &Path) -> Result<(), CliError> {
        match crate::output::write_output(path, &self.svg) {
            Ok(_) => Ok(()),
            Err(CliError::Io { source, .. }) => Err(CliError::PlotFile {
                option: option.to_string(),
                path: eom_text::escaped(&path.display().to_string()).into_owned(),
                source,
            }),
            Err(e) => Err(e),
        }
    }

    /// The notes as lines for standard error (`note: FILE: …`), empty without notes.
    pub fn notes_text(&self, path: &Path) -> String {
        self.notes
            .iter()
            .map(|n| format!("note: {}: {n}\n", path.display()))
            .collect()
    }
}

/// Checks a plot file name before the computation, so that a mistyped path does not cost a
/// long sweep: the name must end in `.svg` (only SVG is written; exit code 2 as for any
/// malformed argument), its directory must exist and the path must not be a directory (exit
/// code 1, like the write failing later).
pub fn check_target(option: &str, path: &Path) -> Result<(), CliError> {
    // A stream (`/dev/stdout`) has no extension to check.
    let is_svg = crate::output::is_stream_path(path)
        || path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    if !is_svg {
        return Err(CliError::BadArgument {
            argument: format!("{option} {}", path.display()),
            problem: "plots are written as SVG: give a file name ending in .svg".into(),
        });
    }
    let fail = |kind: std::io::ErrorKind, why: String| CliError::PlotFile {
        option: option.to_string(),
        path: path.display().to_string(),
        source: std::io::Error::new(kind, why),
    };
    if path.is_dir() {
        return Err(fail(
            std::io::ErrorKind::IsADirectory,
            "it is a directory".into(),
        ));
    }
    // `Path::parent` of a bare file name is the empty path: the working directory.
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if dir.exists() && !dir.is_dir() {
        return Err(fail(
            std::io::ErrorKind::NotADirectory,
            format!("`{}` is not a directory", dir.display()),
        ));
    }
    if !dir.is_dir() {
        return Err(fail(
            std::io::ErrorKind::NotFound,
            format!("the directory `{}` does not exist", dir.display()),
        ));
    }
    Ok(())
}

/// Rejects two options naming the same file: the second plot would silently replace the
/// first.
pub fn check_distinct(a: (&str, &Path), b: (&str, &Path)) -> Result<(), CliError> {
    if a.1 == b.1 {
        return Err(CliError::BadArgument {
            argument: format!("{} {}", b.0, b.1.display()),
            problem: format!("the same file as {}; each plot needs its own file", a.0),
        });
    }
    Ok(())
}

/// Turns a `plotters` error into a [`CliError`].
pub(crate) fn drawing<E: std::fmt::Display>(e: E) -> CliError {
    CliError::Plot(e.to_string())
}

std::thread_local! {
    /// The data curves of the plot being rendered, drawn at sub-pixel precision: plotters'
    /// SVG backend rounds every coordinate to a whole pixel, which makes smooth curves
    /// stair-stepped. [`render`] splices them into its SVG (over everything else).
    static CURVES: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
}

/// Draws into an SVG string of `size` pixels: white background, then `draw`; the data curves
/// of [`draw_runs`] and [`draw_dashed`] go in at sub-pixel precision.
pub(crate) fn render(
    size: (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> Result<(), CliError>,
) -> Result<String, CliError> {
    let mut svg = String::new();
    let outer = CURVES.with(|c| c.replace(Some(String::new())));
    let drawn = (|| {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        draw(&root)?;
        root.present().map_err(drawing)
    })();
    let curves = CURVES.with(|c| c.replace(outer)).unwrap_or_default();
    drawn?;
    let end = svg.rfind("</svg>").unwrap_or(svg.len());
    svg.insert_str(end, &curves);
    Ok(svg)
}

/// Data to pixel coordinates of a chart without rounding: plotters' own map (linear or
/// logarithmic) at a resolution of 2⁻²⁴ of the axis, scaled to its pixels.
fn pixels<X, Y>(chart: &Chart<'_, '_, X, Y>, run: &[(f64, f64)]) -> Vec<(f64, f64)>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    const FINE: i32 = 1 << 24;
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let (x0, y0) = chart.backend_coord(&(xr.start, yr.start));
    let (x1, y1) = chart.backend_coord(&(xr.end, yr.end));
    let spec = chart.as_coord_spec();
    let (xs, ys) = (spec.x_spec(), spec.y_spec());
    run.iter()
        .map(|&(x, y)| {
            let fx = f64::from(xs.map(&x, (0, FINE))) / f64::from(FINE);
            let fy = f64::from(ys.map(&y, (0, FINE))) / f64::from(FINE);
            (
                f64::from(x0) + fx * f64::from(x1 - x0),
                f64::from(y0) + fy * f64::from(y1 - y0),
            )
        })
        .collect()
}

/// A polyline of data coordinates at sub-pixel precision into the curves of the plot being
/// rendered (`dash`: lengths of the dashes and gaps); `false` when no [`render`] is running.
fn overlay<X, Y>(
    chart: &Chart<'_, '_, X, Y>,
    run: &[(f64, f64)],
    color: RGBColor,
    width: u32,
    dash: Option<(u32, u32)>,
) -> bool
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    use std::fmt::Write;
    if CURVES.with(|c| c.borrow().is_none()) {
        return false;
    }
    let points = pixels(chart, run);
    CURVES.with(|c| {
        let mut c = c.borrow_mut();
        let Some(out) = c.as_mut() else {
            return false;
        };
        let RGBColor(r, g, b) = color;
        let dash = dash.map_or_else(String::new, |(on, off)| {
            format!(" stroke-dasharray=\"{on},{off}\"")
        });
        let _ = write!(
            out,
            "<polyline fill=\"none\" opacity=\"1\" stroke=\"#{r:02X}{g:02X}{b:02X}\"{dash} \
             stroke-width=\"{width}\" points=\""
        );
        for (x, y) in points {
            let _ = write!(out, "{x:.2},{y:.2} ");
        }
        out.push_str("\"/>\n");
        true
    })
}

/// Splits the area below the title into the chart region and the legend column.
pub(crate) fn with_title<'a>(
    root: &Area<'a>,
    title: &str,
) -> Result<(Area<'a>, Area<'a>), CliError> {
    // plotters writes a font of size s as font-size s/1.24 in the SVG; the title shrinks
    // to fit the picture's width (a long model name or file path).
    const SVG_SCALE: f64 = 1.24;
    let (width, _) = root.dim_in_pixel();
    let px = labels::fitting_size(title, 26.0 / SVG_SCALE, 8.0, f64::from(width) - 20.0);
    let body = root
        .titled(title, (FONT, px * SVG_SCALE))
        .map_err(drawing)?;
    let (w, _) = body.dim_in_pixel();
    Ok(body.split_horizontally(w.saturating_sub(LEGEND_WIDTH)))
}

/// Whether a value can be drawn: finite and below [`LARGEST`] in magnitude.
pub(crate) fn plottable(x: f64) -> bool {
    x.is_finite() && x.abs() <= LARGEST
}

/// Smallest and largest plottable value (`None` if there is none).
pub(crate) fn bounds(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .into_iter()
        .filter(|x| plottable(*x))
        .fold(None, |acc, x| match acc {
            None => Some((x, x)),
            Some((lo, hi)) => Some((lo.min(x), hi.max(x))),
        })
}

/// The smallest interval holding both `a` and `b` (either may be absent).
pub(crate) fn union(a: Option<(f64, f64)>, b: Option<(f64, f64)>) -> Option<(f64, f64)> {
    match (a, b) {
        (Some((l1, h1)), Some((l2, h2))) => Some((l1.min(l2), h1.max(h2))),
        (a, None) => a,
        (None, b) => b,
    }
}

/// A linear axis range for data spanning `span`: widened by `pad` (a fraction of the width)
/// on each side, and never of zero width — a single value, or values equal to within a
/// millionth of their magnitude, get ±10 % of their magnitude (±1 around zero), because a
/// zero-width axis has no scale at all. No data gives `[0, 1]`.
pub(crate) fn axis_range(span: Option<(f64, f64)>, pad: f64) -> (f64, f64) {
    axis_range_or(span, pad, 1.0)
}

/// [`axis_range`], with data that are all exactly zero spanning `±zero_half` instead of ±1:
/// the scale of the plot's other data (a purely real root locus gets an imaginary axis of
/// the real parts' size, not ±1). A `zero_half` that is not positive and finite means 1.
pub(crate) fn axis_range_or(span: Option<(f64, f64)>, pad: f64, zero_half: f64) -> (f64, f64) {
    let Some((lo, hi)) = span else {
        return (0.0, 1.0);
    };
    let scale = lo.abs().max(hi.abs());
    if hi - lo <= 1e-6 * scale || scale == 0.0 {
        let mid = 0.5 * (lo + hi);
        let half = if scale != 0.0 {
            0.1 * scale
        } else if zero_half.is_finite() && zero_half > 0.0 {
            zero_half
        } else {
            1.0
        };
        return (mid - half, mid + half);
    }
    let d = pad * (hi - lo);
    (lo - d, hi + d)
}

/// A data span whose values are all within `noise` of zero (their error estimate: rounding,
/// not data) taken as exactly zero, so that an axis is not scaled to rounding noise.
pub(crate) fn denoised(span: Option<(f64, f64)>, noise: f64) -> Option<(f64, f64)> {
    span.map(|(lo, hi)| {
        if lo.abs().max(hi.abs()) <= noise {
            (0.0, 0.0)
        } else {
            (lo, hi)
        }
    })
}

/// A logarithmic axis range for positive data spanning `span`. A range that holds no power
/// of ten is widened to the surrounding whole decades, so that the axis has at least one
/// labelled tick; a single value is widened to the decades around it. No data gives
/// `[1, 10]`.
pub(crate) fn log_axis_range(span: Option<(f64, f64)>) -> (f64, f64) {
    let Some((lo, hi)) = span.filter(|(lo, _)| *lo > 0.0) else {
        return (1.0, 10.0);
    };
    let (a, b) = (lo.log10(), hi.log10());
    let (lo, hi) = if b.floor() >= a.ceil() && hi > lo {
        (lo, hi)
    } else {
        let (mut da, mut db) = (a.floor(), b.ceil());
        if db <= da {
            // A single exact power of ten: one decade on either side.
            da -= 1.0;
            db += 1.0;
        }
        (10f64.powf(da), 10f64.powf(db))
    };
    // A hair wider: the tick search of `plotters` rounds log10(0.1) up to -0.99…, and would
    // otherwise drop the tick at an end that is an exact power of ten.
    (lo * (1.0 - 1e-9), hi * (1.0 + 1e-9))
}

/// Splits a series into runs of consecutive plottable points: a value that cannot be drawn
/// breaks the curve there, instead of a line being drawn across the gap.
pub(crate) fn runs(points: impl IntoIterator<Item = (f64, f64)>) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    let mut current = Vec::new();
    for (x, y) in points {
        if plottable(x) && plottable(y) {
            current.push((x, y));
        } else if !current.is_empty() {
            out.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}

/// Cuts a polyline to the band `lo ≤ y ≤ hi`: the pieces inside, each ending where the line
/// leaves the band (interpolated), so that a zoomed panel draws nothing outside its axes.
pub(crate) fn clip_to_band(run: &[(f64, f64)], lo: f64, hi: f64) -> Vec<Series> {
    let inside = |y: f64| (lo..=hi).contains(&y);
    // Where the segment p→q meets y = edge.
    let cut = |p: (f64, f64), q: (f64, f64), edge: f64| {
        let t = (edge - p.1) / (q.1 - p.1);
        (p.0 + t * (q.0 - p.0), edge)
    };
    let mut out: Vec<Series> = Vec::new();
    let mut current: Series = Vec::new();
    for (k, &q) in run.iter().enumerate() {
        let prev = k.checked_sub(1).map(|j| run[j]);
        match (prev, inside(q.1)) {
            (None, true) => current.push(q),
            (None, false) => {}
            (Some(p), true) => {
                if !inside(p.1) {
                    current.push(cut(p, q, if p.1 > hi { hi } else { lo }));
                }
                current.push(q);
            }
            (Some(p), false) => {
                if inside(p.1) {
                    current.push(cut(p, q, if q.1 > hi { hi } else { lo }));
                    out.push(std::mem::take(&mut current));
                } else if (p.1 > hi) != (q.1 > hi) {
                    // Straight across the band, from one side to the other.
                    let (a, b) = if p.1 > hi { (hi, lo) } else { (lo, hi) };
                    out.push(vec![cut(p, q, a), cut(p, q, b)]);
                }
            }
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}

/// Number of points of a series that cannot be drawn.
pub(crate) fn left_out(points: impl IntoIterator<Item = (f64, f64)>) -> usize {
    points
        .into_iter()
        .filter(|(x, y)| !(plottable(*x) && plottable(*y)))
        .count()
}

/// The `k`-th colour of the data curves: ten hues that stay apart on white, repeated.
pub(crate) fn color(k: usize) -> RGBColor {
    const PALETTE: [RGBColor; 10] = [
        RGBColor(31, 100, 180),
        RGBColor(230, 110, 0),
        RGBColor(40, 150, 40),
        RGBColor(200, 30, 40),
        RGBColor(130, 80, 180),
        RGBColor(130, 80, 60),
        RGBColor(220, 90, 180),
        RGBColor(90, 90, 90),
        RGBColor(170, 170, 20),
        RGBColor(20, 170, 190),
    ];
    PALETTE[k % PALETTE.len()]
}

/// Draws a curve given as runs: a polyline per run, a dot for a run of a single point (a
/// lone value would otherwise be invisible).
pub(crate) fn draw_runs<X, Y>(
    chart: &mut Chart<'_, '_, X, Y>,
    runs: &[Series],
    color: RGBColor,
) -> Result<(), CliError>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let style = color.stroke_width(CURVE_WIDTH);
    for run in runs {
        if let [p] = run[..] {
            chart
                .draw_series(std::iter::once(Circle::new(p, 3, color.filled())))
                .map_err(drawing)?;
        } else if !overlay(chart, run, color, CURVE_WIDTH, None) {
            chart
                .draw_series(std::iter::once(PathElement::new(run.clone(), style)))
                .map_err(drawing)?;
        }
    }
    Ok(())
}

/// A dashed data curve (dashes and gaps of 8 and 5 pixels), at sub-pixel precision.
pub(crate) fn draw_dashed<X, Y>(
    chart: &mut Chart<'_, '_, X, Y>,
    run: Series,
    color: RGBColor,
) -> Result<(), CliError>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    if !overlay(chart, &run, color, CURVE_WIDTH, Some((8, 5))) {
        chart
            .draw_series(std::iter::once(DashedPathElement::new(
                run,
                8,
                5,
                color.stroke_width(CURVE_WIDTH),
            )))
            .map_err(drawing)?;
    }
    Ok(())
}

/// The grid, tick labels (formatted like the text tables) and axis descriptions.
pub(crate) fn draw_mesh<X, Y>(
    chart: &mut Chart<'_, '_, X, Y>,
    x_desc: &str,
    y_desc: &str,
) -> Result<(), CliError>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    // A tick at zero computed as −0.3 + 3 × 0.1 is −5.55e-17: a tick within a billionth
    // of the axis width of zero is 0.
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let at_zero = |v: f64, r: &std::ops::Range<f64>| v.abs() <= 1e-9 * (r.end - r.start).abs();
    let x_fmt = |v: &f64| {
        if at_zero(*v, &xr) {
            "0".into()
        } else {
            g(*v, 4)
        }
    };
    let y_fmt = |v: &f64| {
        if at_zero(*v, &yr) {
            "0".into()
        } else {
            g(*v, 4)
        }
    };
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        // Few light lines: the data curves, not the grid, should catch the eye.
        .max_light_lines(4)
        .light_line_style(RGBColor(240, 240, 240))
        .bold_line_style(RGBColor(205, 205, 205))
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .draw()
        .map_err(drawing)
}

/// How a legend row shows what it names.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Mark {
    /// A filled colour square (a curve's colour).
    Swatch(RGBColor),
    /// A dashed line.
    Dashed(RGBColor),
    /// A cross (a pole).
    Cross(RGBColor),
    /// A filled triangle.
    Triangle(RGBColor),
    /// An open square.
    Square(RGBColor),
    /// An open circle (a zero).
    Ring(RGBColor),
    /// Text only.
    Text,
    /// A note about the data, in a darker colour.
    Note,
}

/// Height of a legend row, in pixels.
const ROW: i32 = 19;

/// Characters per legend line at the legend font size (beyond: wrapped).
const LEGEND_CHARS: usize = 38;

/// Splits a legend text into lines of at most [`LEGEND_CHARS`] characters at spaces (a word
/// longer than a line stays whole).
pub(crate) fn wrap(text: &str) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > LEGEND_CHARS {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// Draws the legend rows top-down in the legend column; rows that do not fit are counted
/// in a last line instead of being drawn outside the picture.
pub(crate) fn draw_legend(area: &Area<'_>, rows: &[(Mark, String)]) -> Result<(), CliError> {
    let (_, h) = area.dim_in_pixel();
    let lines: Vec<(Option<Mark>, String)> = rows
        .iter()
        .flat_map(|(mark, text)| {
            wrap(text)
                .into_iter()
                .enumerate()
                .map(move |(k, l)| ((k == 0).then_some(*mark), l))
        })
        .collect();
    let fit = ((h as i32 - 2 * ROW) / ROW).max(1) as usize;
    let shown = if lines.len() > fit {
        fit - 1
    } else {
        lines.len()
    };
    let mut y = ROW;
    for (mark, text) in &lines[..shown] {
        draw_legend_line(area, *mark, text, y)?;
        y += ROW;
    }
    if shown < lines.len() {
        let more = format!("… {} more legend lines", lines.len() - shown);
        draw_legend_line(area, Some(Mark::Note), &more, y)?;
    }
    Ok(())
}

/// One legend line at height `y`: the mark (if any) at the left, the text after it.
fn draw_legend_line(
    area: &Area<'_>,
    mark: Option<Mark>,
    text: &str,
    y: i32,
) -> Result<(), CliError> {
    let (x, cx) = (30, 13);
    let style = match mark {
        Some(Mark::Note) => (FONT, 15).into_font().color(&RGBColor(150, 40, 0)),
        _ => (FONT, 15).into_font().color(&BLACK),
    };
    match mark {
        Some(Mark::Swatch(c)) => area
            .draw(&Rectangle::new(
                [(cx - 6, y - 6), (cx + 6, y + 6)],
                c.filled(),
            ))
            .map_err(drawing)?,
        Some(Mark::Dashed(c)) => area
            .draw(&DashedPathElement::new(
                vec![(cx - 10, y), (cx + 10, y)],
                4,
                3,
                c.stroke_width(1),
            ))
            .map_err(drawing)?,
        Some(Mark::Cross(c)) => area
            .draw(&Cross::new((cx, y), 5, c.stroke_width(2)))
            .map_err(drawing)?,
        Some(Mark::Triangle(c)) => area
            .draw(&TriangleMarker::new((cx, y), 6, c.filled()))
            .map_err(drawing)?,
        Some(Mark::Square(c)) => area
            .draw(&Rectangle::new(
                [(cx - 5, y - 5), (cx + 5, y + 5)],
                c.stroke_width(2),
            ))
            .map_err(drawing)?,
        Some(Mark::Ring(c)) => area
            .draw(&Circle::new((cx, y), 5, c.stroke_width(2)))
            .map_err(drawing)?,
        Some(Mark::Text | Mark::Note) | None => {}
    }
    area.draw(&Text::new(
        text.to_string(),
        (x, y),
        style.pos(Pos::new(HPos::Left, VPos::Center)),
    ))
    .map_err(drawing)
}

/// `name [unit]`, or just `name` without a unit.
pub(crate) fn with_unit(name: &str, unit: &str) -> String {
    if unit.is_empty() {
        name.to_string()
    } else {
        format!("{name} [{unit}]")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_break_at_values_that_cannot_be_drawn() {
        let pts = [
            (0.0, 1.0),
            (1.0, f64::NAN),
            (2.0, 3.0),
            (3.0, 4.0),
            (f64::INFINITY, 0.0),
            (5.0, 1e200),
        ];
        assert_eq!(
            runs(pts),
            vec![vec![(0.0, 1.0)], vec![(2.0, 3.0), (3.0, 4.0)]]
        );
        assert_eq!(left_out(pts), 3);
        assert!(runs([(0.0, f64::NAN)]).is_empty());
    }

    #[test]
    fn clipping_keeps_the_band_and_interpolates_the_exits() {
        let run = [(0.0, 0.0), (1.0, 2.0), (2.0, 0.0), (3.0, -4.0), (4.0, 4.0)];
        let pieces = clip_to_band(&run, -1.0, 1.0);
        assert_eq!(pieces.len(), 3, "{pieces:?}");
        assert_eq!(pieces[0], vec![(0.0, 0.0), (0.5, 1.0)]);
        assert_eq!(pieces[1], vec![(1.5, 1.0), (2.0, 0.0), (2.25, -1.0)]);
        assert_eq!(pieces[2], vec![(3.375, -1.0), (3.625, 1.0)]);
        for p in pieces.iter().flatten() {
            assert!((-1.0..=1.0).contains(&p.1));
        }
    }

    #[test]
    fn axis_ranges_never_have_zero_width() {
        assert_eq!(axis_range(None, 0.05), (0.0, 1.0));
        assert_eq!(axis_range(Some((0.0, 0.0)), 0.05), (-1.0, 1.0));
        let (lo, hi) = axis_range(Some((5.0, 5.0)), 0.05);
        assert!((lo - 4.5).abs() < 1e-12 && (hi - 5.5).abs() < 1e-12);
        assert_eq!(axis_range(Some((0.0, 10.0)), 0.1), (-1.0, 11.0));
        // Data all zero take the other data's scale; noise within its estimate is zero.
        assert_eq!(axis_range_or(Some((0.0, 0.0)), 0.05, 5.0), (-5.0, 5.0));
        assert_eq!(axis_range_or(Some((0.0, 0.0)), 0.05, 0.0), (-1.0, 1.0));
        assert_eq!(denoised(Some((-1.1e-16, 0.0)), 1e-14), Some((0.0, 0.0)));
        assert_eq!(denoised(Some((-0.5, 0.0)), 1e-14), Some((-0.5, 0.0)));
        assert_eq!(
            bounds([f64::NAN, 2.0, -1.0, f64::INFINITY]),
            Some((-1.0, 2.0))
        );
        assert_eq!(bounds([f64::NAN]), None);
    }

    #[test]
    fn log_ranges_hold_a_power_of_ten() {
        let close = |(a, b): (f64, f64), (c, d): (f64, f64)| {
            assert!(
                (a / c - 1.0).abs() < 1e-8 && (b / d - 1.0).abs() < 1e-8,
                "{a} {b}"
            )
        };
        close(log_axis_range(Some((0.1, 100.0))), (0.1, 100.0));
        close(log_axis_range(Some((0.3, 300.0))), (0.3, 300.0));
        close(log_axis_range(Some((2.0, 5.0))), (1.0, 10.0));
        close(log_axis_range(Some((10.0, 10.0))), (1.0, 100.0));
        close(log_axis_range(Some((3.0, 3.0))), (1.0, 10.0));
        assert_eq!(log_axis_range(None), (1.0, 10.0));
    }

    #[test]
    fn legend_text_is_wrapped_at_spaces() {
        let w = wrap("a fairly long note that certainly does not fit on one legend line");
        assert!(w.len() >= 2 && w.iter().all(|l| l.chars().count() <= LEGEND_CHARS));
        assert_eq!(wrap(""), vec![String::new()]);
    }

    #[test]
    fn plot_targets_are_checked_before_the_computation() {
        let e = check_target("--plot", Path::new("out.png")).unwrap_err();
        assert!(matches!(e, CliError::BadArgument { .. }), "{e}");
        assert!(e.to_string().contains("--plot out.png"), "{e}");
        let e = check_target("--plot", Path::new("/no/such/dir/x.svg")).unwrap_err();
        assert_eq!(e.exit_code(), crate::error::EXIT_FAILURE);
        assert!(e.to_string().contains("/no/such/dir"), "{e}");
        assert!(check_target("--plot", Path::new("x.SVG")).is_ok());
        let e = check_distinct(
            ("--plot", Path::new("a.svg")),
            ("--plot-poles", Path::new("a.svg")),
        );
        assert!(e.is_err());
    }
}
