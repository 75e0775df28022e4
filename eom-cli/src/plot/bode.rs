//! The Bode plot (`eom analyze … --plot FILE.svg`): magnitude in dB on top and unwrapped
//! phase in degrees below, over a logarithmic frequency axis in Hz, one colour per
//! output/input pair.

use super::{
    Area, Mark, Plot, Series, axis_range, bounds, color, draw_legend, draw_mesh, draw_runs,
    drawing, left_out, log_axis_range, render, runs, with_title,
};
use crate::analyze::{Analysis, FreqReport, Signal, ratio_unit};
use crate::error::CliError;
use plotters::prelude::*;

/// Size of the Bode plot in pixels.
const SIZE: (u32, u32) = (1100, 820);

/// The legend label of every pair, in the order of [`FreqReport::pairs`] (outputs outer,
/// inputs inner): `input → output [output unit/input unit]`.
pub fn pair_labels(inputs: &[Signal], outputs: &[Signal]) -> Vec<String> {
    outputs
        .iter()
        .flat_map(|o| {
            inputs.iter().map(move |i| {
                let unit = ratio_unit(&o.unit, &i.unit);
                if unit.is_empty() {
                    format!("{} → {}", i.name, o.name)
                } else {
                    format!("{} → {} [{unit}]", i.name, o.name)
                }
            })
        })
        .collect()
}

/// The magnitude and phase curves of every pair. A frequency that is not positive cannot be
/// placed on the logarithmic axis and counts as a value left out.
fn curves(fr: &FreqReport) -> (Vec<Series>, Vec<Series>) {
    let f: Vec<f64> = fr
        .frequency_hz
        .iter()
        .map(|&f| if f > 0.0 { f } else { f64::NAN })
        .collect();
    let mag = fr
        .pairs
        .iter()
        .map(|p| {
            let db = p.magnitude_db.iter().map(|m| m.unwrap_or(f64::NAN));
            f.iter().copied().zip(db).collect()
        })
        .collect();
    let phase = fr
        .pairs
        .iter()
        .map(|p| f.iter().copied().zip(p.phase_deg.iter().copied()).collect())
        .collect();
    (mag, phase)
}

/// Notes on what the plot leaves out.
fn notes(fr: &FreqReport, mag: &[Series], phase: &[Series]) -> Vec<String> {
    let mut notes = Vec::new();
    if fr.pairs.is_empty() {
        notes.push("no output/input pairs: the model has no inputs or no outputs".into());
    }
    let m: usize = mag.iter().map(|c| left_out(c.iter().copied())).sum();
    if m > 0 {
        notes.push(format!(
            "{m} magnitude value(s) are infinite (a pole on the jω axis, or an exact zero) or \
             NaN and are not drawn"
        ));
    }
    let p: usize = phase.iter().map(|c| left_out(c.iter().copied())).sum();
    if p > 0 {
        notes.push(format!(
            "{p} phase value(s) are not finite and are not drawn"
        ));
    }
    notes
}

/// One panel over the logarithmic frequency axis `x`.
fn panel(
    area: &Area<'_>,
    x: (f64, f64),
    y_desc: &str,
    x_desc: &str,
    curves: &[Series],
) -> Result<(), CliError> {
    let y = axis_range(
        bounds(curves.iter().flat_map(|c| c.iter().map(|p| p.1))),
        0.05,
    );
    let mut chart = ChartBuilder::on(area)
        .margin(10)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x.0..x.1).log_scale(), y.0..y.1)
        .map_err(drawing)?;
    draw_mesh(&mut chart, x_desc, y_desc)?;
    for (k, c) in curves.iter().enumerate() {
        draw_runs(&mut chart, &runs(c.iter().copied()), color(k))?;
    }
    Ok(())
}

/// Draws the Bode plot of a frequency response; `labels` names the pairs (see
/// [`pair_labels`]). Values that cannot be drawn are left out with a note; a single
/// frequency is drawn as dots on an axis widened to whole decades.
pub fn bode_plot(title: &str, fr: &FreqReport, labels: &[String]) -> Result<Plot, CliError> {
    let (mag, phase) = curves(fr);
    let notes = notes(fr, &mag, &phase);
    let x = log_axis_range(bounds(fr.frequency_hz.iter().copied().filter(|f| *f > 0.0)));
    let mut rows: Vec<(Mark, String)> = labels
        .iter()
        .enumerate()
        .map(|(k, l)| (Mark::Swatch(color(k)), l.clone()))
        .collect();
    rows.push((Mark::Text, String::new()));
    rows.push((Mark::Text, "magnitude: 20 log10 |G| in dB".into()));
    rows.push((Mark::Text, "phase: unwrapped along frequency".into()));
    rows.extend(notes.iter().map(|n| (Mark::Note, n.clone())));
    let svg = render(SIZE, |root| {
        let (charts, legend) = with_title(root, title)?;
        let (top, bottom) = charts.split_vertically(charts.dim_in_pixel().1 / 2);
        panel(&top, x, "magnitude [dB]", "frequency [Hz]", &mag)?;
        panel(&bottom, x, "phase [deg]", "frequency [Hz]", &phase)?;
        draw_legend(&legend, &rows)
    })?;
    Ok(Plot { svg, notes })
}

/// The Bode plot of an analysis run with a frequency response (`--freq`).
pub fn bode_of(a: &Analysis) -> Result<Plot, CliError> {
    let fr = a.frequency_response.as_ref().ok_or_else(|| {
        CliError::Inconsistent("a Bode plot was asked for without a frequency response".into())
    })?;
    let title = format!("{}: frequency response", a.model);
    bode_plot(&title, fr, &pair_labels(&a.inputs, &a.outputs))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analyze::FreqPair;

    fn report(f: Vec<f64>, db: Vec<Option<f64>>, phase: Vec<f64>) -> FreqReport {
        FreqReport {
            singular: vec![false; f.len()],
            frequency_hz: f,
            pairs: vec![FreqPair {
                output: "y".into(),
                input: "u".into(),
                magnitude_db: db,
                phase_deg: phase,
            }],
        }
    }

    #[test]
    fn infinite_magnitudes_are_left_out_with_a_note() {
        let fr = report(
            vec![0.1, 1.0, 10.0, 100.0],
            vec![Some(0.0), None, Some(-20.0), Some(-40.0)],
            vec![0.0, -90.0, -180.0, f64::NAN],
        );
        let p = bode_plot("t", &fr, &["u → y".into()]).unwrap();
        assert_eq!(p.notes.len(), 2, "{:?}", p.notes);
        assert!(p.notes[0].starts_with("1 magnitude"), "{:?}", p.notes);
        assert!(p.svg.contains("u → y"));
    }

    #[test]
    fn a_single_frequency_and_no_pairs_do_not_panic() {
        let fr = report(vec![3.0], vec![Some(-6.0)], vec![-45.0]);
        let p = bode_plot("t", &fr, &["u → y".into()]).unwrap();
        assert!(p.notes.is_empty(), "{:?}", p.notes);
        assert_eq!(p.svg.matches("<circle").count(), 2, "one dot per panel");
        let mut fr = report(vec![1.0, 2.0], vec![], vec![]);
        fr.pairs.clear();
        let p = bode_plot("t", &fr, &[]).unwrap();
        assert!(
            p.notes[0].contains("no output/input pairs"),
            "{:?}",
            p.notes
        );
    }

    #[test]
    fn labels_follow_the_pair_order_with_units() {
        let s = |name: &str, unit: &str| Signal {
            name: name.into(),
            unit: unit.into(),
        };
        let l = pair_labels(&[s("f", "N"), s("g", "")], &[s("z", "m")]);
        assert_eq!(l, vec!["f → z [m/N]".to_string(), "g → z [m]".to_string()]);
    }
}
