//! Two sweeps of the same parameter in one plot (`eom sweep A --compare B … --plot FILE.svg`):
//! real parts on top, damped frequencies |Im λ|/2π below, every branch of a model in that
//! model's colour (solid for the first, dashed for the second), each model's stable intervals
//! shaded in a light tint of its colour and its boundaries as dashed vertical lines.

use super::zoom::Zoom;
use super::{
    Area, Chart, Mark, Plot, axis_range, bounds, color, draw_legend, draw_mesh, drawing, plottable,
    render, runs, union, with_title, with_unit,
};
use crate::error::CliError;
use crate::format::g;
use eom_num::sweep::SweepResult;
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use std::f64::consts::TAU;

/// Size of the plot in pixels.
const SIZE: (u32, u32) = (1100, 820);

/// A model's sweep with its name and colour.
struct Side<'r> {
    name: &'r str,
    result: &'r SweepResult,
    color: RGBColor,
    dashed: bool,
}

impl Side<'_> {
    /// Every non-neutral branch as `(value, Re λ)` or `(value, |Im λ|/2π)`.
    fn curves(&self, imag: bool) -> Vec<Vec<(f64, f64)>> {
        let r = self.result;
        r.branches
            .iter()
            .filter(|b| !b.neutral)
            .map(|b| {
                r.points
                    .iter()
                    .map(|p| {
                        let z = p.eigenvalues.get(b.index).copied();
                        let y = z.map_or(f64::NAN, |z| if imag { z.im.abs() / TAU } else { z.re });
                        (p.value, y)
                    })
                    .collect()
            })
            .collect()
    }

    fn legend(&self, rows: &mut Vec<(Mark, String)>) {
        let p = &self.result.param;
        let style = if self.dashed { "dashed" } else { "solid" };
        rows.push((Mark::Swatch(self.color), format!("{} ({style})", self.name)));
        if self.result.stable_intervals.is_empty() {
            rows.push((Mark::Text, format!("  no stable interval of {p}")));
        }
        for i in &self.result.stable_intervals {
            rows.push((
                Mark::Text,
                format!("  stable: {p} in [{}, {}]", g(i.lo, 6), g(i.hi, 6)),
            ));
        }
        for b in &self.result.boundaries {
            rows.push((
                Mark::Dashed(self.color),
                format!("  boundary {p} = {}", g(b.value, 8)),
            ));
        }
    }

    fn draw(
        &self,
        chart: &mut Chart<'_, '_, RangedCoordf64, RangedCoordf64>,
        y: (f64, f64),
        imag: bool,
        clip: Option<f64>,
    ) -> Result<(), CliError> {
        for c in self.curves(imag) {
            let mut pieces = runs(c);
            if let Some(half) = clip {
                pieces = super::zoom::clipped(&pieces, half);
            }
            for run in pieces {
                if self.dashed && run.len() > 1 {
                    super::draw_dashed(chart, run, self.color)?;
                } else {
                    super::draw_runs(chart, &[run], self.color)?;
                }
            }
        }
        for b in &self.result.boundaries {
            chart
                .draw_series(std::iter::once(DashedPathElement::new(
                    vec![(b.value, y.0), (b.value, y.1)],
                    6,
                    4,
                    self.color.stroke_width(1),
                )))
                .map_err(drawing)?;
        }
        Ok(())
    }

    fn shade(
        &self,
        chart: &mut Chart<'_, '_, RangedCoordf64, RangedCoordf64>,
        y: (f64, f64),
    ) -> Result<(), CliError> {
        let fill = self.color.mix(0.12).filled();
        let boxes = self
            .result
            .stable_intervals
            .iter()
            .map(|i| Rectangle::new([(i.lo, y.0), (i.hi, y.1)], fill));
        chart.draw_series(boxes).map_err(drawing)?;
        Ok(())
    }
}

/// One panel with both models (`clip`: the zoomed panel's half-width).
fn panel(
    area: &Area<'_>,
    sides: &[Side<'_>; 2],
    (x, y): ((f64, f64), (f64, f64)),
    descs: (&str, &str),
    imag: bool,
    clip: Option<f64>,
) -> Result<(), CliError> {
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(drawing)?;
    for s in sides {
        s.shade(&mut chart, y)?;
    }
    draw_mesh(&mut chart, descs.0, descs.1)?;
    if !imag {
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(x.0, 0.0), (x.1, 0.0)],
                BLACK.stroke_width(1),
            )))
            .map_err(drawing)?;
    }
    for s in sides {
        s.draw(&mut chart, y, imag, clip)?;
    }
    Ok(())
}

/// Draws the sweeps `a` and `b` of the same parameter (with `unit`) in one plot; `zoom`
/// adds a panel of the real parts near zero.
pub fn compare_plot(
    a: (&str, &SweepResult),
    b: (&str, &SweepResult),
    unit: &str,
    zoom: Option<Zoom>,
) -> Result<Plot, CliError> {
    let sides = [
        Side {
            name: a.0,
            result: a.1,
            color: color(0),
            dashed: false,
        },
        Side {
            name: b.0,
            result: b.1,
            color: color(1),
            dashed: true,
        },
    ];
    let all = |imag: bool| {
        sides
            .iter()
            .flat_map(|s| s.curves(imag).into_iter().flatten())
            .filter(|p| plottable(p.0) && plottable(p.1))
            .map(|p| p.1)
            .collect::<Vec<_>>()
    };
    let left_out: usize = sides
        .iter()
        .flat_map(|s| [s.curves(false), s.curves(true)])
        .flatten()
        .flatten()
        .filter(|p| !(plottable(p.0) && plottable(p.1)))
        .count();
    let mut notes = Vec::new();
    if left_out > 0 {
        notes.push(format!(
            "{left_out} eigenvalue value(s) are NaN or infinite and are not drawn"
        ));
    }
    let x = axis_range(
        bounds(
            sides
                .iter()
                .flat_map(|s| s.result.points.iter().map(|p| p.value)),
        ),
        0.0,
    );
    let y_re = axis_range(union(bounds(all(false)), Some((0.0, 0.0))), 0.05);
    let y_hz = axis_range(union(bounds(all(true)), Some((0.0, 0.0))), 0.05);
    let y_hz = (y_hz.0.max(0.0), y_hz.1);
    let mut rows = Vec::new();
    for s in &sides {
        s.legend(&mut rows);
        rows.push((Mark::Text, String::new()));
    }
    rows.push((
        Mark::Text,
        "shaded: stable intervals, in the model's tint".into(),
    ));
    rows.extend(notes.iter().map(|n| (Mark::Note, n.clone())));
    let param = &a.1.param;
    let title = format!("{} vs {}: eigenvalues over {param}", a.0, b.0);
    let x_desc = with_unit(param, unit);
    let half = zoom.map(|z| z.half_width(&[a.1, b.1]));
    let size = if half.is_some() {
        super::sweep::ZOOM_SIZE
    } else {
        SIZE
    };
    let svg = render(size, |root| {
        let (charts, legend) = with_title(root, &title)?;
        let h = charts.dim_in_pixel().1;
        let (top, rest) = charts.split_vertically(if half.is_some() { h / 3 } else { h / 2 });
        panel(
            &top,
            &sides,
            (x, y_re),
            (&x_desc, "Re λ [1/s]"),
            false,
            None,
        )?;
        let bottom = match half {
            Some(half) => {
                let (middle, bottom) = rest.split_vertically(h / 3);
                let desc = (x_desc.as_str(), super::sweep::ZOOM_DESC);
                panel(&middle, &sides, (x, (-half, half)), desc, false, Some(half))?;
                bottom
            }
            None => rest,
        };
        panel(
            &bottom,
            &sides,
            (x, y_hz),
            (&x_desc, "|Im λ|/2π [Hz]"),
            true,
            None,
        )?;
        draw_legend(&legend, &rows)
    })?;
    Ok(Plot { svg, notes })
}
