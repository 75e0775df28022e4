//! The root locus over a swept parameter (`eom sweep … --plot-locus FILE.svg`): every
//! non-neutral eigenvalue branch as a path in the complex plane, dots with the parameter's
//! value at five places along each path (labelled on the upper half-plane only: the lower one
//! mirrors it), a square where it starts and a triangle where it ends, and each stability
//! boundary as a ring on the imaginary axis with its value.

use super::labels::Placer;
use super::{
    Mark, Plot, STABLE_FILL, axis_range_or, bounds, color, denoised, draw_legend, draw_mesh,
    draw_runs, drawing, render, runs, union, with_title,
};
use crate::error::CliError;
use crate::format::g;
use eom_num::sweep::{Crossing, SweepResult};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Size of the plot in pixels.
const SIZE: (u32, u32) = (1100, 820);

/// Font size of the labels in the SVG, in pixels.
const LABEL_PX: f64 = 11.0;

/// plotters writes a font of size s as font-size s/1.24 in the SVG.
const SVG_SCALE: f64 = 1.24;

/// Places along a path where the parameter is shown.
const LABELS: usize = 5;

/// The paths `(Re λ, Im λ)` of the non-neutral branches, in branch order.
pub(crate) fn paths(r: &SweepResult) -> Vec<Vec<(f64, f64)>> {
    r.branches
        .iter()
        .filter(|b| !b.neutral)
        .map(|b| {
            r.points
                .iter()
                .map(|p| {
                    p.eigenvalues
                        .get(b.index)
                        .map_or((f64::NAN, f64::NAN), |z| (z.re, z.im))
                })
                .collect()
        })
        .collect()
}

/// The grid indices labelled along every path: evenly spaced, both ends included.
fn label_indices(n: usize) -> Vec<usize> {
    if n == 0 {
        return Vec::new();
    }
    let mut k: Vec<usize> = (0..LABELS)
        .map(|i| (i * (n - 1)) / (LABELS - 1).max(1))
        .collect();
    k.dedup();
    k
}

/// Draws the root locus of `model` over the sweep `r` (`unit`: the parameter's unit).
pub fn locus_plot(model: &str, r: &SweepResult, unit: &str) -> Result<Plot, CliError> {
    let paths = paths(r);
    let mut notes = Vec::new();
    if paths.is_empty() {
        notes.push("no eigenvalue branches to draw (no states, or all branches neutral)".into());
    }
    let left_out: usize = paths
        .iter()
        .map(|p| super::left_out(p.iter().copied()))
        .sum();
    if left_out > 0 {
        notes.push(format!(
            "{left_out} eigenvalue value(s) are NaN or infinite and are not drawn"
        ));
    }
    // Parts within their error estimate are rounding (0); an axis of zeros (the imaginary
    // axis of a purely real locus, the real axis of an undamped one) takes the size of the
    // other one instead of ±1.
    let noise = super::sweep::noise(r);
    let re = denoised(bounds(paths.iter().flatten().map(|p| p.0)), noise);
    let im = denoised(bounds(paths.iter().flatten().map(|p| p.1)), noise);
    let size = |s: Option<(f64, f64)>| s.map_or(0.0, |(lo, hi)| 0.5 * lo.abs().max(hi.abs()));
    let x = axis_range_or(union(re, Some((0.0, 0.0))), 0.08, size(im));
    let y = axis_range_or(union(im, Some((0.0, 0.0))), 0.08, size(re));
    let p = &r.param;
    let unit_text = if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    };
    let mut rows = vec![
        (Mark::Text, format!("{} branches over {p}", paths.len())),
        (
            Mark::Square(BLACK),
            format!("start: {p} = {}", g(first(r), 6)),
        ),
        (
            Mark::Triangle(BLACK),
            format!("end: {p} = {}", g(last(r), 6)),
        ),
        (Mark::Text, format!("dots: {p} at {LABELS} values")),
        (Mark::Swatch(STABLE_FILL), "stable half-plane".into()),
    ];
    for b in &r.boundaries {
        let dir = match b.crossing {
            Crossing::Destabilizing => "destabilizing",
            Crossing::Stabilizing => "stabilizing",
        };
        rows.push((
            Mark::Ring(RED),
            format!("{dir}: {p} = {}{unit_text}", g(b.value, 8)),
        ));
    }
    rows.extend(notes.iter().map(|n| (Mark::Note, n.clone())));
    let title = format!("{model}: root locus over {p}");
    let svg = render(SIZE, |root| {
        let (area, legend) = with_title(root, &title)?;
        let mut chart = ChartBuilder::on(&area)
            .margin(10)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)
            .map_err(drawing)?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x.0, y.0), (x.1.min(0.0), y.1)],
                STABLE_FILL.filled(),
            )))
            .map_err(drawing)?;
        draw_mesh(&mut chart, "Re λ [1/s]", "Im λ [rad/s]")?;
        for line in [[(0.0, y.0), (0.0, y.1)], [(x.0, 0.0), (x.1, 0.0)]] {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    line,
                    BLACK.stroke_width(1),
                )))
                .map_err(drawing)?;
        }
        let style = ("sans-serif", LABEL_PX * SVG_SCALE)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Top));
        // Labels go where they overlap no other label: the boundaries' first, then the
        // parameter values along the paths (a value with no free place is not labelled).
        let (xs, ys) = chart.plotting_area().get_pixel_range();
        let mut placer = Placer::new([
            f64::from(xs.start),
            f64::from(ys.start),
            f64::from(xs.end),
            f64::from(ys.end),
        ]);
        let mut labels: Vec<(String, (f64, f64), f64)> = Vec::new();
        for b in &r.boundaries {
            let text = format!("{p} = {}", g(b.value, 6));
            labels.push((text, (b.eigenvalue.re, b.eigenvalue.im.abs()), 10.0));
        }
        for path in &paths {
            for i in label_indices(path.len()) {
                let (zr, zi) = path[i];
                if zi >= 0.0 && super::plottable(zr) && super::plottable(zi) {
                    labels.push((g(r.points[i].value, 4), (zr, zi), 5.0));
                }
            }
        }
        for (text, at, gap) in labels {
            let (px, py) = chart.backend_coord(&at);
            if let Some((left, top)) =
                placer.place(&text, LABEL_PX, (f64::from(px), f64::from(py)), gap)
            {
                let offset = ((left - f64::from(px)) as i32, (top - f64::from(py)) as i32);
                chart
                    .draw_series(std::iter::once(
                        EmptyElement::at(at) + Text::new(text, offset, style.clone()),
                    ))
                    .map_err(drawing)?;
            }
        }
        for (k, path) in paths.iter().enumerate() {
            let c = color(k);
            draw_runs(&mut chart, &runs(path.iter().copied()), c)?;
            for i in label_indices(path.len()) {
                let (zr, zi) = path[i];
                if !(super::plottable(zr) && super::plottable(zi)) {
                    continue;
                }
                let at = (zr, zi);
                let drawn = if i == 0 {
                    chart.draw_series(std::iter::once(
                        EmptyElement::at(at)
                            + Rectangle::new([(-5, -5), (5, 5)], c.stroke_width(2)),
                    ))
                } else if i + 1 == path.len() {
                    chart.draw_series(std::iter::once(TriangleMarker::new(at, 7, c.filled())))
                } else {
                    chart.draw_series(std::iter::once(Circle::new(at, 3, c.filled())))
                };
                drawn.map_err(drawing)?;
            }
        }
        for b in &r.boundaries {
            for im in [b.eigenvalue.im, -b.eigenvalue.im] {
                chart
                    .draw_series(std::iter::once(Circle::new(
                        (b.eigenvalue.re, im),
                        8,
                        RED.stroke_width(2),
                    )))
                    .map_err(drawing)?;
            }
        }
        draw_legend(&legend, &rows)
    })?;
    Ok(Plot { svg, notes })
}

fn first(r: &SweepResult) -> f64 {
    r.points.first().map_or(f64::NAN, |p| p.value)
}

fn last(r: &SweepResult) -> f64 {
    r.points.last().map_or(f64::NAN, |p| p.value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_are_spread_over_the_grid() {
        assert_eq!(label_indices(101), vec![0, 25, 50, 75, 100]);
        assert_eq!(label_indices(2), vec![0, 1]);
        assert_eq!(label_indices(1), vec![0]);
        assert!(label_indices(0).is_empty());
    }
}
