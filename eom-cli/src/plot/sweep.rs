//! The sweep plot (`eom sweep … --plot FILE.svg`): the eigenvalue branches over the swept
//! parameter, real parts on top (with the line Re λ = 0) and damped frequencies |Im λ|/2π
//! below; stable intervals shaded, stability boundaries as dashed vertical lines.
//!
//! The damped frequency is drawn as |Im λ|/2π in Hz rather than Im λ: a conjugate pair then
//! shares one curve, which halves the clutter, and Hz is the unit of the text tables.

use super::zoom::Zoom;
use super::{
    Area, Chart, Mark, Plot, STABLE_FILL, Series, axis_range, axis_range_or, bounds, color,
    denoised, draw_legend, draw_mesh, draw_runs, drawing, plottable, render, runs, union,
    with_title, with_unit,
};
use crate::error::CliError;
use crate::format::g;
use eom_num::sweep::{Crossing, SweepResult};
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use std::f64::consts::TAU;

/// Size of the sweep plot in pixels.
const SIZE: (u32, u32) = (1100, 820);

/// Size of the sweep plot with the zoomed panel, in pixels.
pub(crate) const ZOOM_SIZE: (u32, u32) = (1100, 1150);

/// Axis description of the zoomed panel.
pub(crate) const ZOOM_DESC: &str = "Re λ near 0 [1/s]";

/// Most boundaries and stable intervals listed one by one in the legend.
const LISTED: usize = 8;

/// Colour of a destabilizing boundary (stable → unstable as the parameter increases).
const DESTABILIZING: RGBColor = RGBColor(200, 30, 40);

/// Colour of a stabilizing boundary.
const STABILIZING: RGBColor = RGBColor(30, 130, 50);

/// One non-neutral eigenvalue branch as two curves over the parameter.
struct Branch {
    /// `(value, Re λ)`.
    re: Series,
    /// `(value, |Im λ|/2π)` in Hz.
    hz: Series,
}

/// The branches to draw (neutral ones left out: they are identically zero, which the line
/// Re λ = 0 already shows) and the number of eigenvalues that cannot be drawn.
fn branches(r: &SweepResult) -> (Vec<Branch>, usize) {
    let mut left_out = 0;
    let curves = r
        .branches
        .iter()
        .filter(|b| !b.neutral)
        .map(|b| {
            let (mut re, mut hz) = (Vec::new(), Vec::new());
            for p in &r.points {
                // A missing entry (should not happen) is drawn as a gap, like a NaN.
                let z = p.eigenvalues.get(b.index).copied();
                let (x, zr, zi) =
                    z.map_or((p.value, f64::NAN, f64::NAN), |z| (p.value, z.re, z.im));
                if !(plottable(x) && plottable(zr) && plottable(zi)) {
                    left_out += 1;
                }
                re.push((x, zr));
                hz.push((x, zi.abs() / TAU));
            }
            Branch { re, hz }
        })
        .collect();
    (curves, left_out)
}

/// The largest error estimate the sweep states (`points[].tolerance`): real parts within it
/// are rounding, and no axis is scaled to them.
pub(crate) fn noise(r: &SweepResult) -> f64 {
    r.points
        .iter()
        .filter_map(|p| p.tolerance)
        .filter(|t| t.is_finite())
        .fold(0.0, f64::max)
}

/// The largest |λ| of the non-neutral branches: the scale of an axis whose data are all 0.
pub(crate) fn eigen_scale(r: &SweepResult) -> f64 {
    let drawn: Vec<usize> = (r.branches.iter())
        .filter(|b| !b.neutral)
        .map(|b| b.index)
        .collect();
    r.points
        .iter()
        .flat_map(|p| drawn.iter().filter_map(|&j| p.eigenvalues.get(j)))
        .map(|z| z.norm())
        .filter(|m| plottable(*m))
        .fold(0.0, f64::max)
}

/// The legend rows: what the colours, shading and dashed lines mean, the boundaries and
/// intervals themselves, and the notes.
fn legend_rows(r: &SweepResult, drawn: usize, notes: &[String]) -> Vec<(Mark, String)> {
    let p = &r.param;
    let neutral = r.branches.iter().filter(|b| b.neutral).count();
    let mut rows = vec![(
        Mark::Text,
        format!("{drawn} eigenvalue branches, one colour each"),
    )];
    if neutral > 0 {
        rows.push((
            Mark::Text,
            format!("{neutral} neutral branches (identically zero) not drawn"),
        ));
    }
    rows.push((Mark::Text, String::new()));
    if r.stable_intervals.is_empty() {
        rows.push((Mark::Text, format!("no stable interval of {p}")));
    }
    for i in r.stable_intervals.iter().take(LISTED) {
        rows.push((
            Mark::Swatch(STABLE_FILL),
            format!("stable: {p} in [{}, {}]", g(i.lo, 6), g(i.hi, 6)),
        ));
    }
    if r.stable_intervals.len() > LISTED {
        rows.push((
            Mark::Text,
            format!(
                "… {} more stable intervals",
                r.stable_intervals.len() - LISTED
            ),
        ));
    }
    for b in r.boundaries.iter().take(LISTED) {
        let (c, dir) = match b.crossing {
            Crossing::Destabilizing => (DESTABILIZING, "destabilizing"),
            Crossing::Stabilizing => (STABILIZING, "stabilizing"),
        };
        rows.push((Mark::Dashed(c), format!("{dir}: {p} = {}", g(b.value, 8))));
    }
    if r.boundaries.len() > LISTED {
        rows.push((
            Mark::Text,
            format!("… {} more boundaries", r.boundaries.len() - LISTED),
        ));
    }
    rows.extend(notes.iter().map(|n| (Mark::Note, n.clone())));
    rows
}

/// Which curve of a branch a panel draws.
type Pick = fn(&Branch) -> &[(f64, f64)];

/// One panel: axes, shaded stable intervals, boundaries, optionally the line y = 0, curves.
struct Panel<'r> {
    result: &'r SweepResult,
    x: (f64, f64),
    y: (f64, f64),
    x_desc: String,
    y_desc: &'static str,
    zero_line: bool,
    /// Cut the curves to `±half` (the zoomed panel).
    clip: Option<f64>,
}

impl Panel<'_> {
    fn draw(&self, area: &Area<'_>, curves: &[Branch], pick: Pick) -> Result<(), CliError> {
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(self.x.0..self.x.1, self.y.0..self.y.1)
            .map_err(drawing)?;
        // The shading first, so that the grid and the curves are drawn over it.
        self.shade_stable(&mut chart)?;
        draw_mesh(&mut chart, &self.x_desc, self.y_desc)?;
        if self.zero_line {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(self.x.0, 0.0), (self.x.1, 0.0)],
                    BLACK.stroke_width(1),
                )))
                .map_err(drawing)?;
        }
        self.boundaries(&mut chart)?;
        for (k, b) in curves.iter().enumerate() {
            let mut pieces = runs(pick(b).iter().copied());
            if let Some(half) = self.clip {
                pieces = super::zoom::clipped(&pieces, half);
            }
            draw_runs(&mut chart, &pieces, color(k))?;
        }
        Ok(())
    }

    fn shade_stable(
        &self,
        chart: &mut Chart<'_, '_, RangedCoordf64, RangedCoordf64>,
    ) -> Result<(), CliError> {
        let boxes =
            self.result.stable_intervals.iter().map(|i| {
                Rectangle::new([(i.lo, self.y.0), (i.hi, self.y.1)], STABLE_FILL.filled())
            });
        chart.draw_series(boxes).map_err(drawing)?;
        Ok(())
    }

    fn boundaries(
        &self,
        chart: &mut Chart<'_, '_, RangedCoordf64, RangedCoordf64>,
    ) -> Result<(), CliError> {
        for b in &self.result.boundaries {
            let c = match b.crossing {
                Crossing::Destabilizing => DESTABILIZING,
                Crossing::Stabilizing => STABILIZING,
            };
            chart
                .draw_series(std::iter::once(DashedPathElement::new(
                    vec![(b.value, self.y.0), (b.value, self.y.1)],
                    6,
                    4,
                    c.stroke_width(1),
                )))
                .map_err(drawing)?;
        }
        Ok(())
    }
}

/// Draws the sweep plot of `model`; `unit` is the unit of the swept parameter (may be
/// empty); `zoom` adds a panel of the real parts near zero. Eigenvalues that cannot be drawn
/// are left out with a note; a sweep without branches to draw gives empty axes with a note.
pub fn sweep_plot(
    model: &str,
    r: &SweepResult,
    unit: &str,
    zoom: Option<Zoom>,
) -> Result<Plot, CliError> {
    let (curves, left_out) = branches(r);
    let mut notes = Vec::new();
    if curves.is_empty() {
        notes.push("no eigenvalue branches to draw (no states, or all branches neutral)".into());
    }
    if left_out > 0 {
        notes.push(format!(
            "{left_out} eigenvalue value(s) are NaN or infinite and are not drawn"
        ));
    }
    let x = axis_range(bounds(r.points.iter().map(|p| p.value)), 0.0);
    let re = bounds(curves.iter().flat_map(|b| b.re.iter().map(|p| p.1)));
    let hz = bounds(curves.iter().flat_map(|b| b.hz.iter().map(|p| p.1)));
    // Re λ = 0 is always in view: stability is read off against it. Real parts within their
    // error estimate are 0 (an undamped model's axis is not scaled to rounding), and an
    // axis of zeros takes a tenth of the eigenvalues' size.
    let tenth = 0.1 * eigen_scale(r);
    let y_re = axis_range_or(union(denoised(re, noise(r)), Some((0.0, 0.0))), 0.05, tenth);
    let y_hz = axis_range_or(union(hz, Some((0.0, 0.0))), 0.05, tenth / TAU);
    // Frequencies are not negative: start the axis at 0.
    let y_hz = (y_hz.0.max(0.0), y_hz.1);
    let rows = legend_rows(r, curves.len(), &notes);
    let title = format!("{model}: eigenvalues over {}", r.param);
    let x_desc = with_unit(&r.param, unit);
    let half = zoom.map(|z| z.half_width(&[r]));
    let size = if half.is_some() { ZOOM_SIZE } else { SIZE };
    let svg = render(size, |root| {
        let (charts, legend) = with_title(root, &title)?;
        let panel = |y, y_desc, zero_line, clip| Panel {
            result: r,
            x,
            y,
            x_desc: x_desc.clone(),
            y_desc,
            zero_line,
            clip,
        };
        let h = charts.dim_in_pixel().1;
        let (top, rest) = charts.split_vertically(if half.is_some() { h / 3 } else { h / 2 });
        panel(y_re, "Re λ [1/s]", true, None).draw(&top, &curves, |b| &b.re)?;
        let bottom = match half {
            Some(half) => {
                let (middle, bottom) = rest.split_vertically(h / 3);
                panel((-half, half), ZOOM_DESC, true, Some(half))
                    .draw(&middle, &curves, |b| &b.re)?;
                bottom
            }
            None => rest,
        };
        panel(y_hz, "|Im λ|/2π [Hz]", false, None).draw(&bottom, &curves, |b| &b.hz)?;
        draw_legend(&legend, &rows)
    })?;
    Ok(Plot { svg, notes })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::CURVE_WIDTH;
    use eom_num::sweep::{BranchInfo, PointStability, StableInterval, SweepPoint};
    use num_complex::Complex64;

    fn point(value: f64, eigenvalues: Vec<Complex64>) -> SweepPoint {
        SweepPoint {
            value,
            eigenvalues,
            max_real: None,
            stability: PointStability::Stable,
            norm: 1.0,
            tolerance: None,
        }
    }

    fn result(points: Vec<SweepPoint>, n: usize) -> SweepResult {
        SweepResult {
            param: "v".into(),
            points,
            branches: (0..n)
                .map(|index| BranchInfo {
                    index,
                    neutral: false,
                })
                .collect(),
            stable_intervals: vec![StableInterval { lo: 0.0, hi: 0.5 }],
            boundaries: Vec::new(),
        }
    }

    fn curves(svg: &str) -> usize {
        svg.matches(&format!("stroke-width=\"{CURVE_WIDTH}\" points="))
            .count()
    }

    #[test]
    fn nan_values_are_left_out_with_a_note() {
        let z = |re, im| Complex64::new(re, im);
        let r = result(
            vec![
                point(0.0, vec![z(-1.0, 2.0)]),
                point(0.5, vec![z(f64::NAN, 2.0)]),
                point(1.0, vec![z(-0.5, f64::INFINITY)]),
                point(1.5, vec![z(0.5, 1.0)]),
                point(2.0, vec![z(1.0, 1.0)]),
            ],
            1,
        );
        let p = sweep_plot("m", &r, "m/s", None).unwrap();
        assert!(p.svg.starts_with("<svg"), "{}", &p.svg[..60]);
        assert_eq!(p.notes.len(), 1, "{:?}", p.notes);
        assert!(
            p.notes[0].starts_with("2 eigenvalue value(s)"),
            "{:?}",
            p.notes
        );
        // Top: a dot at 0, then a line from 1 to 2 (the real part at 1 is finite); bottom:
        // lines over 0–0.5 (the imaginary part at 0.5 is finite) and 1.5–2.
        assert_eq!(curves(&p.svg), 3, "{}", p.svg);
        assert!(p.svg.contains("v [m/s]"));
    }

    #[test]
    fn a_single_point_and_no_branches_do_not_panic() {
        let r = result(vec![point(3.0, vec![Complex64::new(0.0, 0.0)])], 1);
        let p = sweep_plot("m", &r, "", None).unwrap();
        assert!(p.svg.contains("<circle"), "a lone value is a dot");
        let r = result(vec![point(0.0, vec![]), point(1.0, vec![])], 0);
        let p = sweep_plot("m", &r, "", None).unwrap();
        assert_eq!(curves(&p.svg), 0);
        assert!(
            p.notes[0].contains("no eigenvalue branches"),
            "{:?}",
            p.notes
        );
    }
}
