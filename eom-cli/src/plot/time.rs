//! Time responses (`eom analyze … --plot-step FILE.svg`, `--plot-initial FILE.svg`): one row
//! of panels per output, one column per response (step, impulse; or the free response of a
//! mode), one colour per input. The responses come from `eom_num::time` (exact ZOH
//! discretisation, the horizon from the slowest mode).

use super::{
    Mark, Plot, axis_range, bounds, color, draw_legend, draw_mesh, draw_runs, drawing, render,
    runs, with_title, with_unit,
};
use crate::error::CliError;
use crate::format::g;
use eom_num::SignalNames;
use eom_num::time::TimeResponse;
use plotters::prelude::*;

/// Width of the plot in pixels.
const WIDTH: u32 = 1100;

/// Height of one row of panels, in pixels.
const ROW_HEIGHT: u32 = 230;

/// Most outputs drawn (one row each); the others are named in a note.
pub const MOST_ROWS: usize = 8;

/// One column of panels: a response and its name (`step`, `impulse`, …).
pub struct Column<'r> {
    /// Column heading, e.g. `step response`.
    pub title: String,
    /// The response; its columns are drawn in the input colours.
    pub response: &'r TimeResponse,
}

fn signal(names: &[String], units: &[String], k: usize, what: &str) -> (String, String) {
    let name = names
        .get(k)
        .filter(|n| !n.is_empty())
        .cloned()
        .unwrap_or_else(|| format!("{what} {}", k + 1));
    (name, units.get(k).cloned().unwrap_or_default())
}

/// The notes of a response: an early stop or a coarsened step, and the `D δ(t)` term.
fn response_notes(c: &Column<'_>, notes: &mut Vec<String>) {
    if let Some(m) = &c.response.message {
        notes.push(format!("{}: {m}", c.title));
    }
    if let Some(d) = &c.response.direct
        && d.iter().any(|x| *x != 0.0)
    {
        notes.push(format!(
            "{}: a D·δ(t) term at t = 0 is not drawn (D ≠ 0)",
            c.title
        ));
    }
}

/// Draws the responses `columns` of `model`; `legend` names what the colours are (the
/// inputs, or a single mode).
pub fn response_plot(
    model: &str,
    what: &str,
    columns: &[Column<'_>],
    names: &SignalNames,
    legend: &[String],
) -> Result<Plot, CliError> {
    let outputs = columns.first().map_or(0, |c| c.response.outputs);
    let rows = outputs.min(MOST_ROWS);
    let mut notes = Vec::new();
    if outputs == 0 || columns.is_empty() {
        notes.push("no outputs: nothing to draw".into());
    }
    if outputs > MOST_ROWS {
        notes.push(format!(
            "{} more outputs not drawn (the first {MOST_ROWS} are)",
            outputs - MOST_ROWS
        ));
    }
    for c in columns {
        response_notes(c, &mut notes);
    }
    let mut rows_legend: Vec<(Mark, String)> = legend
        .iter()
        .enumerate()
        .map(|(k, l)| (Mark::Swatch(color(k)), l.clone()))
        .collect();
    rows_legend.push((Mark::Text, String::new()));
    rows_legend.extend(notes.iter().map(|n| (Mark::Note, n.clone())));
    let height = 80 + ROW_HEIGHT * rows.max(1) as u32;
    let title = format!("{model}: {what}");
    let svg = render((WIDTH, height), |root| {
        let (area, legend_area) = with_title(root, &title)?;
        let cells = area.split_evenly((rows.max(1), columns.len().max(1)));
        for i in 0..rows {
            let (name, unit) = signal(&names.outputs, &names.output_units, i, "output");
            for (j, c) in columns.iter().enumerate() {
                let desc = with_unit(&name, &unit);
                draw_cell(&cells[i * columns.len() + j], c, i, &desc, i == 0)?;
            }
        }
        draw_legend(&legend_area, &rows_legend)
    })?;
    Ok(Plot { svg, notes })
}

/// One panel: output `i` of every column of the response.
fn draw_cell(
    area: &super::Area<'_>,
    c: &Column<'_>,
    i: usize,
    y_desc: &str,
    heading: bool,
) -> Result<(), CliError> {
    let r = c.response;
    let series: Vec<Vec<(f64, f64)>> = (0..r.columns)
        .map(|j| r.t.iter().copied().zip(r.series(i, j)).collect())
        .collect();
    let x = axis_range(bounds(r.t.iter().copied()), 0.0);
    let y = axis_range(
        super::union(
            bounds(series.iter().flatten().map(|p| p.1)),
            Some((0.0, 0.0)),
        ),
        0.06,
    );
    let mut b = ChartBuilder::on(area);
    b.margin(8).x_label_area_size(45).y_label_area_size(75);
    if heading {
        b.caption(&c.title, ("sans-serif", 17));
    }
    let mut chart = b.build_cartesian_2d(x.0..x.1, y.0..y.1).map_err(drawing)?;
    draw_mesh(&mut chart, "t [s]", y_desc)?;
    for (j, s) in series.iter().enumerate() {
        draw_runs(&mut chart, &runs(s.iter().copied()), color(j))?;
    }
    Ok(())
}

/// The legend of a step/impulse plot: one line per input.
pub fn input_legend(names: &SignalNames, inputs: usize) -> Vec<String> {
    (0..inputs)
        .map(|k| {
            let (n, u) = signal(&names.inputs, &names.input_units, k, "input");
            format!("unit {}", with_unit(&n, &u))
        })
        .collect()
}

/// The legend of a mode's free response.
pub fn mode_legend(eigenvalue: num_complex::Complex64) -> Vec<String> {
    vec![format!(
        "started at Re v of λ = {} {} {}i",
        g(eigenvalue.re, 5),
        if eigenvalue.im < 0.0 { "−" } else { "+" },
        g(eigenvalue.im.abs(), 5)
    )]
}
