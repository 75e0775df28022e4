//! Steady-state gains (with integrating pairs reported as such) and the frequency response
//! on a logarithmic grid.

use super::*;
use crate::error::CliError;
use crate::shown_warning::ShownWarning;
use eom_num::StateSpace;
use eom_num::freq::{FreqOptions, FreqRange, FreqUnit, FrequencyResponse};
use eom_num::gain::{Gain, SteadyStateGain};

/// The steady-state gain of every input/output pair, integrating pairs marked as such.
pub(super) fn gain_entries(
    gain: &SteadyStateGain,
    inputs: &[Signal],
    outputs: &[Signal],
    warnings: &mut Vec<ShownWarning>,
) -> Vec<GainEntry> {
    warnings.extend(
        gain.warnings
            .iter()
            .map(|w| ShownWarning::of_num(w, "steady-state gain: ")),
    );
    let mut out = Vec::with_capacity(inputs.len() * outputs.len());
    for (i, o) in outputs.iter().enumerate() {
        for (j, u) in inputs.iter().enumerate() {
            let (value, error_estimate, integrating) = match gain.get(i, j) {
                Gain::Finite(v) => (Some(v), Some(gain.errors[(i, j)]), None),
                Gain::Integrating { order, coefficient } => {
                    (None, None, Some(Integrating { order, coefficient }))
                }
            };
            out.push(GainEntry {
                output: o.name.clone(),
                input: u.name.clone(),
                unit: ratio_unit(&o.unit, &u.unit),
                value,
                error_estimate,
                integrating,
            });
        }
    }
    out
}

/// `n` logarithmically spaced values from `lo` to `hi`, both included.
pub(super) fn logspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![lo];
    }
    let (a, b) = (lo.log10(), hi.log10());
    (0..n)
        .map(|k| {
            if k + 1 == n {
                hi
            } else {
                10f64.powf(a + (b - a) * k as f64 / (n - 1) as f64)
            }
        })
        .collect()
}

pub(super) fn frequency_response(
    ss: &StateSpace<f64>,
    req: &FreqRequest,
    inputs: &[Signal],
    outputs: &[Signal],
) -> Result<FreqReport, CliError> {
    let range = match (req.range, req.points) {
        (None, None) => FreqRange::Auto,
        (Some((low, high)), None) => FreqRange::Range {
            low,
            high,
            unit: FreqUnit::Hz,
        },
        (Some((lo, hi)), Some(n)) => FreqRange::Points {
            values: logspace(lo, hi, n),
            unit: FreqUnit::Hz,
        },
        (None, Some(n)) => {
            // The automatic range (whole decades around the modes), then n points across it.
            let probe = FrequencyResponse::compute(
                ss,
                &FreqOptions {
                    range: FreqRange::Auto,
                    points_per_decade: 1,
                },
            )?;
            let lo = probe.freq_hz.first().copied().unwrap_or(0.01);
            let hi = probe.freq_hz.last().copied().unwrap_or(100.0);
            FreqRange::Points {
                values: logspace(lo, hi, n),
                unit: FreqUnit::Hz,
            }
        }
    };
    let fr = FrequencyResponse::compute(
        ss,
        &FreqOptions {
            range,
            ..FreqOptions::default()
        },
    )?;
    let mut pairs = Vec::with_capacity(inputs.len() * outputs.len());
    for (i, o) in outputs.iter().enumerate() {
        for (j, u) in inputs.iter().enumerate() {
            pairs.push(FreqPair {
                output: o.name.clone(),
                input: u.name.clone(),
                magnitude_db: fr
                    .magnitude_db_of(i, j)
                    .iter()
                    .map(|&x| finite(x))
                    .collect(),
                phase_deg: fr.phase_deg_of(i, j).to_vec(),
            });
        }
    }
    Ok(FreqReport {
        frequency_hz: fr.freq_hz.clone(),
        singular: fr.singular.clone(),
        pairs,
    })
}
