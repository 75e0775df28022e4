//! The work-precision chart: per model a panel of log10 eigenvalue error against log10 time
//! per A, one marker per method (the form of the differential-equation benchmark suites).

use super::{Row, WorkPrecisionError};
use plotters::prelude::*;

/// Errors below this are drawn at it (an exact result has error 0).
const FLOOR: f64 = 1e-17;

/// The methods' colours, in the order of [`METHODS`].
const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 100, 180),
    RGBColor(230, 110, 0),
    RGBColor(30, 130, 50),
    RGBColor(200, 30, 40),
    RGBColor(130, 60, 170),
    RGBColor(120, 80, 40),
    RGBColor(0, 150, 160),
    RGBColor(90, 90, 90),
];

/// The methods in legend order (the eigensolvers last: their time is per eigensolve of the
/// reference's A, not per A).
const METHODS: [&str; 8] = [
    "numeric",
    "robust",
    "symbolic (tape)",
    "generated f64",
    "generated f32",
    "generated f64 egg",
    super::SMALL_KERNEL,
    super::FAER_SOLVER,
];

fn chart_err(e: impl std::fmt::Display) -> WorkPrecisionError {
    WorkPrecisionError::Chart(e.to_string())
}

/// Draws the marker of method `k` centred at `at` (pixels): distinct shapes, so that methods
/// with equal results stay visible on top of each other.
fn draw_marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    k: usize,
    at: (i32, i32),
) -> Result<(), WorkPrecisionError> {
    let c = COLOURS[k % COLOURS.len()];
    let (x, y) = at;
    match k {
        0 => area.draw(&Circle::new(at, 9, c.stroke_width(2))),
        1 => area.draw(&TriangleMarker::new(at, 9, c.filled())),
        2 => area.draw(&Rectangle::new(
            [(x - 6, y - 6), (x + 6, y + 6)],
            c.stroke_width(2),
        )),
        3 => area.draw(&Cross::new(at, 6, c.stroke_width(3))),
        4 => area.draw(&Circle::new(at, 6, c.filled())),
        6 => area.draw(&Rectangle::new(
            [(x - 4, y - 4), (x + 4, y + 4)],
            c.filled(),
        )),
        7 => area.draw(&Cross::new(at, 8, c.stroke_width(1))),
        _ => area.draw(&Circle::new(at, 3, c.filled())),
    }
    .map_err(chart_err)
}

/// The chart as SVG text.
pub fn svg(rows: &[Row]) -> Result<String, WorkPrecisionError> {
    let models: Vec<&str> = rows.iter().fold(Vec::new(), |mut v, r| {
        if !v.contains(&r.model.as_str()) {
            v.push(r.model.as_str());
        }
        v
    });
    let cols = 4usize;
    let nrows = models.len().div_ceil(cols).max(1);
    let size = (1400u32, 360 * nrows as u32 + 80);
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        root.fill(&WHITE).map_err(chart_err)?;
        let (top, body) = root.split_vertically(80);
        top.titled(
            "Work-precision: largest relative eigenvalue error against a double-double reference, and time per A",
            ("sans-serif", 20),
        )
        .map_err(chart_err)?;
        // One legend for every panel.
        for (k, name) in METHODS.iter().enumerate() {
            let x = 120 + 200 * k as i32;
            draw_marker(&top, k, (x, 58))?;
            top.draw_text(
                name,
                &("sans-serif", 14).into_text_style(&top),
                (x + 14, 51),
            )
            .map_err(chart_err)?;
        }
        let panels = body.split_evenly((nrows, cols));
        for (panel, model) in panels.iter().zip(&models) {
            draw_panel(panel, model, rows)?;
        }
        root.present().map_err(chart_err)?;
    }
    Ok(out)
}

fn draw_panel(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    model: &str,
    rows: &[Row],
) -> Result<(), WorkPrecisionError> {
    let pts: Vec<(usize, f64, f64)> = rows
        .iter()
        .filter(|r| r.model == model && r.points > 0 && r.time_ns.is_finite())
        .filter_map(|r| {
            let k = METHODS.iter().position(|m| *m == r.method)?;
            Some((k, r.time_ns.log10(), r.eig_err.max(FLOOR).log10()))
        })
        .collect();
    let (tlo, thi) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
    let (tlo, thi) = if tlo.is_finite() {
        ((tlo - 0.3).floor(), (thi + 0.3).ceil())
    } else {
        (0.0, 1.0)
    };
    let mut chart = ChartBuilder::on(area)
        .caption(model, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(44)
        .build_cartesian_2d(tlo..thi, -17.0f64..-2.0)
        .map_err(chart_err)?;
    chart
        .configure_mesh()
        .x_desc("log10 time per A [ns]")
        .y_desc("log10 eigenvalue error")
        .label_style(("sans-serif", 12))
        .draw()
        .map_err(chart_err)?;
    // Largest markers first, so smaller ones stay visible on top.
    let mut pts = pts;
    pts.sort_by_key(|p| p.0);
    for (k, t, e) in pts {
        let (x, y) = chart.backend_coord(&(t, e));
        let (x0, y0) = area.get_base_pixel();
        draw_marker(area, k, (x - x0, y - y0))?;
    }
    Ok(())
}
