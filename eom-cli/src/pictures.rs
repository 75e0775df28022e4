//! The pictures of one model at one point, shared by `eom analyze` and `eom report`: step
//! and impulse responses, the free response of one mode, mode shapes drawn from the model's
//! geometry, and the model at rest.

use crate::error::CliError;
use crate::format::g;
use crate::plot::Plot;
use crate::plot::geometry::{Sketch, body_motions};
use crate::plot::shape::{ShapeDrawing, shape_svg};
use crate::plot::time::{Column, input_legend, mode_legend, response_plot};
use eom_model::Model;
use eom_num::StateSpace;
use eom_num::initial::{initial, mode_state};
use eom_num::modes::{Mode, ModeKind, ModeOptions, Modes};
use eom_num::time::{TimeOptions, impulse, step};

/// The modes of `ss` as `eom analyze` numbers them (structural zeros set apart).
pub fn modes_of(ss: &StateSpace<f64>, structural_zeros: usize) -> Result<Modes, CliError> {
    let opts = ModeOptions {
        structural_zeros,
        ..ModeOptions::default()
    };
    Ok(Modes::compute_with(ss, &opts)?)
}

/// Step (left) and impulse (right) responses of every output to every input.
pub fn step_impulse_plot(model: &str, ss: &StateSpace<f64>) -> Result<Plot, CliError> {
    if ss.inputs() == 0 || ss.outputs() == 0 {
        return Err(CliError::BadArgument {
            argument: "--plot-step".into(),
            problem: format!(
                "the model `{model}` has {} inputs and {} outputs: a step response needs both",
                ss.inputs(),
                ss.outputs()
            ),
        });
    }
    let opts = TimeOptions::default();
    let (s, i) = (step(ss, &opts)?, impulse(ss, &opts)?);
    let columns = [
        Column {
            title: "unit step response".into(),
            response: &s,
        },
        Column {
            title: "unit impulse response".into(),
            response: &i,
        },
    ];
    let legend = input_legend(&ss.names, ss.inputs());
    response_plot(
        model,
        "step and impulse responses",
        &columns,
        &ss.names,
        &legend,
    )
}

/// The rows of the modes table of `eom analyze` as indices into `modes.modes`: one per real
/// or zero mode and one per conjugate pair (its member with Im λ > 0). The table's `#` is
/// the 1-based position in this list.
pub fn table_rows(modes: &Modes) -> Vec<usize> {
    modes
        .modes
        .iter()
        .enumerate()
        .filter(|(_, m)| !(m.kind == ModeKind::Oscillatory && m.eigenvalue.im < 0.0))
        .map(|(k, _)| k)
        .collect()
}

/// The mode `eom analyze --plot-initial` starts by default: the least damped oscillatory one
/// (largest real part), else the slowest real one; 1-based, as in the modes table.
pub fn default_mode(modes: &Modes) -> Option<usize> {
    let rows = table_rows(modes);
    let pick = |kind: ModeKind| {
        rows.iter()
            .enumerate()
            .map(|(row, &k)| (row, &modes.modes[k]))
            .filter(|(_, m)| m.kind == kind)
            .max_by(|a, b| a.1.eigenvalue.re.total_cmp(&b.1.eigenvalue.re))
            .map(|(row, _)| row + 1)
    };
    pick(ModeKind::Oscillatory).or_else(|| pick(ModeKind::Real))
}

/// Mode `k` (1-based), or an error naming the valid range.
pub fn mode_at<'m>(modes: &'m Modes, k: usize, option: &str) -> Result<&'m Mode, CliError> {
    let rows = table_rows(modes);
    rows.get(k.wrapping_sub(1))
        .map(|&i| &modes.modes[i])
        .ok_or_else(|| CliError::BadArgument {
            argument: format!("{option} {k}"),
            problem: format!(
                "the modes table has {} rows: give a number from 1 to {} (its # column)",
                rows.len(),
                rows.len()
            ),
        })
}

/// The free response of every output from `x₀ = Re v` of mode `k` (1-based).
pub fn initial_plot(
    model: &str,
    ss: &StateSpace<f64>,
    modes: &Modes,
    k: usize,
) -> Result<Plot, CliError> {
    let mode = mode_at(modes, k, "--mode")?;
    let v = mode_state(&ss.a, mode.eigenvalue)?;
    let x0 = v.map(|z| z.re);
    let r = initial(ss, &x0, &TimeOptions::default())?;
    let columns = [Column {
        title: format!("free response of mode {k}"),
        response: &r,
    }];
    response_plot(
        model,
        &format!("initial-condition response of mode {k}"),
        &columns,
        &ss.names,
        &mode_legend(mode.eigenvalue),
    )
}

/// The modes drawn by default: every row of the modes table that moves a body, 1-based.
pub fn drawable_modes(modes: &Modes) -> Vec<usize> {
    table_rows(modes)
        .iter()
        .enumerate()
        .filter(|&(_, &i)| {
            let m = &modes.modes[i];
            m.kind != ModeKind::Zero && m.reference_index.is_some()
        })
        .map(|(row, _)| row + 1)
        .collect()
}

/// A one-line description of a mode for headings.
pub fn mode_heading(k: usize, m: &Mode) -> String {
    let z = m.eigenvalue;
    let lambda = if z.im == 0.0 {
        g(z.re, 5)
    } else {
        format!("{} ± {}i", g(z.re, 5), g(z.im.abs(), 5))
    };
    let extra = match (m.kind, m.damping_ratio) {
        (ModeKind::Oscillatory, Some(zeta)) => format!(
            ", {} Hz, damping {}",
            g(m.natural_frequency_hz, 4),
            g(zeta, 3)
        ),
        _ => format!(", time constant {} s", g(m.time_constant, 4)),
    };
    format!("mode {k}: λ = {lambda} 1/s{extra}")
}

/// The SVG drawing of mode `k` (1-based) from the geometry of `model` (at the point).
pub fn mode_shape_svg(
    name: &str,
    model: &Model<f64>,
    ss: &StateSpace<f64>,
    modes: &Modes,
    k: usize,
) -> Result<String, CliError> {
    let mode = mode_at(modes, k, "--mode")?;
    if mode.shape.is_empty() {
        return Err(CliError::NothingToDraw(format!(
            "the model `{name}` has no map to the bodies' coordinates: its modes cannot be drawn"
        )));
    }
    let sketch = Sketch::of(model);
    let motions = body_motions(&sketch, &mode.shape, &ss.names.bodies);
    Ok(shape_svg(&ShapeDrawing {
        title: format!("{name}, {}", mode_heading(k, mode)),
        sketch: &sketch,
        motions: Some(motions),
    }))
}

/// The model at rest, from its geometry.
pub fn model_svg(name: &str, model: &Model<f64>) -> String {
    let sketch = Sketch::of(model);
    shape_svg(&ShapeDrawing {
        title: format!("{name}: bodies (dots), items (lines), ground points (triangles)"),
        sketch: &sketch,
        motions: None,
    })
}

/// Several SVG documents one below the other in one document.
pub fn stack_svgs(parts: &[String]) -> String {
    let size = |svg: &str, attr: &str| -> f64 {
        let key = format!("{attr}=\"");
        svg.find(&key)
            .and_then(|i| {
                let rest = &svg[i + key.len()..];
                rest[..rest.find('"')?].parse().ok()
            })
            .unwrap_or(0.0)
    };
    let width = parts.iter().map(|p| size(p, "width")).fold(0.0, f64::max);
    let mut y = 0.0;
    let mut body = String::new();
    for p in parts {
        let h = size(p, "height");
        // The inner document keeps its own attributes; placed by a nested <svg>.
        let inner = p.replacen("<svg ", &format!("<svg x=\"0\" y=\"{y}\" "), 1);
        body.push_str(&inner);
        y += h;
    }
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{y}\" viewBox=\"0 0 {width} {y}\">{body}</svg>\n"
    )
}
