//! The Hankel singular values of a reduction (`eom reduce … --plot FILE.svg`): σᵢ of the stable
//! part as points over the order they end, the bound `2 Σ σ` beyond each order as a line, and
//! the error measured at the chosen order, on a logarithmic axis.

use super::{
    Mark, Plot, bounds, color, draw_legend, draw_mesh, drawing, log_axis_range, render, with_title,
};
use crate::error::CliError;
use crate::format::g;
use crate::reduce::ReduceReport;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

/// Size of the plot in pixels.
const SIZE: (u32, u32) = (1100, 640);

/// Draws the plot of a reduction. Values at or below zero (exact zeros of a nonminimal part,
/// the bound of the full order) cannot be placed on the logarithmic axis and are left out
/// with a note.
pub fn hankel_plot(r: &ReduceReport) -> Result<Plot, CliError> {
    let kept = r.kept_whole as f64;
    let sigma: Vec<(f64, f64)> = r
        .hankel_singular_values
        .iter()
        .enumerate()
        .map(|(i, s)| (kept + i as f64 + 1.0, *s))
        .collect();
    let bound: Vec<(f64, f64)> = r
        .bounds
        .iter()
        .map(|b| (b.states as f64, b.bound))
        .collect();
    let positive = |v: &[(f64, f64)]| -> Vec<(f64, f64)> {
        v.iter()
            .copied()
            .filter(|p| p.1 > 0.0 && p.1.is_finite())
            .collect()
    };
    let (sig_p, bound_p) = (positive(&sigma), positive(&bound));
    let mut notes = Vec::new();
    let dropped = sigma.len() - sig_p.len();
    if dropped > 0 {
        notes.push(format!(
            "{dropped} Hankel singular value(s) are exactly zero and are not drawn"
        ));
    }
    let measured = (r.states as f64, r.measured.hinf);
    let y = log_axis_range(bounds(
        sig_p
            .iter()
            .chain(&bound_p)
            .map(|p| p.1)
            .chain((measured.1 > 0.0).then_some(measured.1)),
    ));
    let x = (kept - 0.5, (r.full_states as f64 + 0.5).max(kept + 1.5));
    let mut rows = vec![
        (
            Mark::Cross(color(0)),
            "σᵢ, at the order that keeps it".to_string(),
        ),
        (
            Mark::Swatch(color(1)),
            "bound 2·Σσ beyond the order".to_string(),
        ),
        (
            Mark::Ring(color(3)),
            format!(
                "measured error at order {}: {}",
                r.states,
                g(r.measured.hinf, 4)
            ),
        ),
        (
            Mark::Dashed(RGBColor(90, 90, 90)),
            format!("chosen order {}", r.states),
        ),
    ];
    if r.kept_whole > 0 {
        rows.push((
            Mark::Text,
            format!(
                "{} state(s) kept whole (zero, marginal, unstable)",
                r.kept_whole
            ),
        ));
    }
    rows.extend(notes.iter().map(|n| (Mark::Note, n.clone())));
    let title = format!("{}: Hankel singular values and the error bound", r.model);
    let svg = render(SIZE, |root| {
        let (chart_area, legend) = with_title(root, &title)?;
        let mut chart = ChartBuilder::on(&chart_area)
            .margin(10)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .build_cartesian_2d(x.0..x.1, (y.0..y.1).log_scale())
            .map_err(drawing)?;
        draw_mesh(&mut chart, "states of the reduced model", "σ, bound, error")?;
        chart
            .draw_series(
                sig_p
                    .iter()
                    .map(|&p| Cross::new(p, 5, color(0).stroke_width(2))),
            )
            .map_err(drawing)?;
        chart
            .draw_series(LineSeries::new(
                bound_p.iter().copied(),
                color(1).stroke_width(super::CURVE_WIDTH),
            ))
            .map_err(drawing)?;
        if measured.1 > 0.0 {
            chart
                .draw_series(std::iter::once(Circle::new(
                    measured,
                    6,
                    color(3).stroke_width(2),
                )))
                .map_err(drawing)?;
        }
        chart
            .draw_series(std::iter::once(DashedPathElement::new(
                vec![(measured.0, y.0), (measured.0, y.1)],
                6,
                4,
                RGBColor(90, 90, 90).stroke_width(1),
            )))
            .map_err(drawing)?;
        draw_legend(&legend, &rows)
    })?;
    Ok(Plot { svg, notes })
}
