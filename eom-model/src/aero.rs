//! Where the quasi-steady wing derivatives can be trusted.
//!
//! A wing's derivatives are those of a steady flow; they describe a moving wing well when the
//! motion is slow against the time the air takes to pass a chord, and its rates small:
//!
//! * [`reduced_frequencies`]: for every oscillatory eigenvalue λ and every wing, the reduced
//!   frequency β = |Im λ|·c/V, with a warning above
//!   [`REDUCED_FREQUENCY_LIMIT`](eom_aero::REDUCED_FREQUENCY_LIMIT) = 0.1 (k = β/2 ≲ 0.05, where
//!   the unsteady lift lag of Theodorsen's function is still a few percent);
//! * [`response_rates`]: the largest normalised rates |p b/2V|, |q c/2V|, |r b/2V| of each wing
//!   along a time response (given by its states), against AVL's limits 0.10, 0.03 and 0.25
//!   (beyond which the straight trailing legs of the vortex lattice no longer follow the
//!   wake); [`simulated_rates`] simulates the response first;
//! * [`resolve_unsteady`]: the `unsteady = "auto"` surfaces decided by the reduced
//!   frequencies of the modes: Jones' lag states where they matter, quasi-steady elsewhere.

use crate::Model;
use crate::error::ModelError;
use crate::items::{AUTO_REDUCED_FREQUENCY, AnyItem, Unsteady, Wing};
use crate::warning::{ItemRef, Warning};
use eom_aero::validity::{
    PITCH_RATE_LIMIT, REDUCED_FREQUENCY_LIMIT, ROLL_RATE_LIMIT, YAW_RATE_LIMIT, check_rates,
    reduced_frequency,
};
use eom_num::StateSpace;
use eom_num::{DimensionError, NumError};
use eom_sym::Expr;
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::borrow::Cow;

/// The reduced frequency of one oscillatory mode at one wing.
#[derive(Clone, Debug, PartialEq)]
pub struct ReducedFrequency {
    /// The wing.
    pub wing: String,
    /// The eigenvalue (the member of its pair with positive imaginary part).
    pub eigenvalue: Complex64,
    /// β = |Im λ|·c/V.
    pub beta: f64,
    /// Whether β exceeds the limit 0.1 on a quasi-steady wing.
    pub too_high: bool,
}

impl ReducedFrequency {
    /// The warning for a reduced frequency above the limit.
    pub fn warning(&self) -> Option<Warning> {
        self.too_high.then(|| Warning::ReducedFrequencyBeyondLimit {
            item: ItemRef::new("wing", &self.wing),
            eigenvalue: self.eigenvalue,
            beta: self.beta,
            limit: REDUCED_FREQUENCY_LIMIT,
        })
    }
}

/// β = |Im λ|·c/V of every eigenvalue with a positive imaginary part (one per conjugate pair)
/// at every wing of `model` (its airspeed as in [`Model::airspeed_of`]), wing by wing.
pub fn reduced_frequencies(model: &Model<f64>, eigenvalues: &[Complex64]) -> Vec<ReducedFrequency> {
    let mut out = Vec::new();
    for w in model.wings() {
        let v = model.airspeed_of(w);
        for z in eigenvalues.iter().filter(|z| z.im > 0.0) {
            let beta = reduced_frequency(z.im, w.chord, v);
            out.push(ReducedFrequency {
                wing: w.name.to_string(),
                eigenvalue: *z,
                beta,
                // A wing with Jones' lag states carries the lag (an `auto` one is decided by
                // the linearization, and says so).
                too_high: w.unsteady == crate::items::Unsteady::QuasiSteady
                    && eom_aero::validity::reduced_frequency_too_high(beta),
            });
        }
    }
    out
}

/// The largest normalised rates of one wing along a response.
#[derive(Clone, Debug, PartialEq)]
pub struct WingRates {
    /// The wing.
    pub wing: String,
    /// The largest |p b/2V|, |q c/2V|, |r b/2V| (the wing's own axes).
    pub max: [f64; 3],
    /// The sample at which each was reached.
    pub at: [usize; 3],
    /// AVL's limits 0.10, 0.03, 0.25.
    pub limits: [f64; 3],
    /// Whether each limit was reached or exceeded.
    pub exceeded: [bool; 3],
}

impl WingRates {
    /// One warning per exceeded limit.
    pub fn warnings(&self) -> Vec<Warning> {
        let names = ["p b/2V", "q c/2V", "r b/2V"];
        (0..3)
            .filter(|&k| self.exceeded[k])
            .map(|k| Warning::RateBeyondLimit {
                item: ItemRef::new("wing", &self.wing),
                rate: names[k],
                max: self.max[k],
                sample: self.at[k],
                limit: self.limits[k],
            })
            .collect()
    }
}

/// The normalised rates of every wing along a response of `ss` (the state space of `model`):
/// `states` holds one state vector per column, `inputs` the inputs at the same samples (zero
/// if `None`). The body rates are `phys · ẋ` (rotation rows), `ẋ = A x + B u`, turned into
/// each wing's axes and normalised by its span, chord and airspeed.
pub fn response_rates(
    model: &Model<f64>,
    ss: &StateSpace<f64>,
    states: &DMatrix<f64>,
    inputs: Option<&DMatrix<f64>>,
) -> Result<Vec<WingRates>, ModelError> {
    let n = ss.states();
    if states.nrows() != n {
        return Err(NumError::Dimension(DimensionError::ResponseStates {
            rows: states.nrows(),
            states: n,
        })
        .into());
    }
    let mut xdot = &ss.a * states;
    if let Some(u) = inputs {
        if u.nrows() != ss.inputs() || u.ncols() != states.ncols() {
            return Err(NumError::Dimension(DimensionError::ResponseInputs {
                rows: u.nrows(),
                cols: u.ncols(),
                expected_rows: ss.inputs(),
                expected_cols: states.ncols(),
            })
            .into());
        }
        xdot += &ss.b * u;
    }
    let mut out = Vec::new();
    for w in model.wings() {
        let Some(k) = ss.names.bodies.iter().position(|b| **b == *w.body) else {
            return Err(ModelError::NotInStateSpace {
                item: ItemRef::new("wing", &w.name),
                body: w.body.to_string(),
            });
        };
        let omega = ss.phys.rows(6 * k + 3, 3) * &xdot;
        out.push(rates_of(model, w, &omega));
    }
    Ok(out)
}

/// [`response_rates`] of the simulation of `ss` from `x0` (zero if `None`) under the inputs
/// `inputs` (one column per sample, held over each step `dt`; see
/// [`eom_num::time::simulate`]).
pub fn simulated_rates(
    model: &Model<f64>,
    ss: &StateSpace<f64>,
    inputs: &DMatrix<f64>,
    dt: f64,
    x0: Option<&nalgebra::DVector<f64>>,
) -> Result<Vec<WingRates>, ModelError> {
    // The states themselves as the outputs.
    let mut full = ss.clone();
    full.c = DMatrix::identity(ss.states(), ss.states());
    full.d = DMatrix::zeros(ss.states(), ss.inputs());
    full.names.outputs.clear();
    full.names.output_units.clear();
    let opts = eom_num::time::TimeOptions::default();
    let resp = eom_num::time::simulate(&full, inputs, dt, x0, &opts)?;
    let states = DMatrix::from_column_slice(ss.states(), resp.len(), &resp.y);
    let used = inputs.columns(0, resp.len()).into_owned();
    response_rates(model, ss, &states, Some(&used))
}

/// The largest normalised rates of `w` for the body rates `omega` (3 × samples, model axes).
fn rates_of(model: &Model<f64>, w: &Wing<f64>, omega: &DMatrix<f64>) -> WingRates {
    let q = w.rotation();
    let v = model.airspeed_of(w);
    let mut max = [0.0f64; 3];
    let mut at = [0usize; 3];
    let mut exceeded = [false; 3];
    for (s, col) in omega.column_iter().enumerate() {
        let own: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| q[i][j] * col[j]).sum());
        let c = check_rates(own[0], own[1], own[2], w.span, w.chord, v);
        for k in 0..3 {
            let x = c.normalised[k].abs();
            // NaN counts as the largest.
            if x.is_nan() || x > max[k] {
                max[k] = x;
                at[k] = s;
            }
            exceeded[k] |= c.exceeded[k];
        }
    }
    WingRates {
        wing: w.name.to_string(),
        max,
        at,
        limits: [ROLL_RATE_LIMIT, PITCH_RATE_LIMIT, YAW_RATE_LIMIT],
        exceeded,
    }
}

/// A surface with `unsteady = "auto"`: kind, name, semichord and airspeed at a point.
struct AutoSurface {
    kind: &'static str,
    name: String,
    semichord: f64,
    airspeed: f64,
}

fn auto_surfaces(m: &Model<f64>) -> Vec<AutoSurface> {
    let mut out = Vec::new();
    for w in m.wings().filter(|w| w.unsteady == Unsteady::Auto) {
        out.push(AutoSurface {
            kind: "wing",
            name: w.name.to_string(),
            semichord: 0.5 * w.chord,
            airspeed: m.airspeed_of(w),
        });
    }
    for s in m.strips().filter(|s| s.unsteady == Unsteady::Auto) {
        let velocity = m.body(&s.body).map_or([0.0; 3], |b| b.velocity);
        out.push(AutoSurface {
            kind: "strip",
            name: s.name.to_string(),
            semichord: s.semichord,
            airspeed: s.airspeed_with(&velocity),
        });
    }
    out
}

/// The model with every `auto` surface set to Jones' states when its name is in `lagged`,
/// else quasi-steady.
fn with_lags(model: &Model<Expr>, lagged: &[String]) -> Model<Expr> {
    let mut m = model.clone();
    for item in m.items_mut() {
        let (name, unsteady) = match item {
            AnyItem::Wing(w) => (&w.name, &mut w.unsteady),
            AnyItem::Strip(s) => (&s.name, &mut s.unsteady),
            _ => continue,
        };
        if *unsteady == Unsteady::Auto {
            *unsteady = if lagged.iter().any(|n| **n == **name) {
                Unsteady::Jones
            } else {
                Unsteady::QuasiSteady
            };
        }
    }
    m
}

/// Decides every `unsteady = "auto"` of `model` at the parameter `values` (scope order):
/// analyse with the undecided surfaces quasi-steady, give Jones' states to each surface at
/// which an oscillatory mode has the reduced frequency k = |Im λ|·b/V above
/// [`AUTO_REDUCED_FREQUENCY`] (b its semichord, V its airspeed), re-analyse, and repeat until
/// no surface is added. Returns the decided model (borrowed when nothing is `auto`) and one
/// line per `auto` surface saying what it got and why.
pub fn resolve_unsteady<'m>(
    model: &'m Model<Expr>,
    values: &[f64],
) -> Result<(Cow<'m, Model<Expr>>, Vec<Warning>), ModelError> {
    let any_auto = model.wings().any(|w| w.unsteady == Unsteady::Auto)
        || model.strips().any(|s| s.unsteady == Unsteady::Auto);
    if !any_auto {
        return Ok((Cow::Borrowed(model), Vec::new()));
    }
    let surfaces = auto_surfaces(&model.evaluate(values)?);
    let mut lagged: Vec<String> = Vec::new();
    let mut notes = Vec::new();
    loop {
        let m = with_lags(model, &lagged);
        let a = crate::assemble(&m.evaluate(values)?)?;
        let ss = match crate::reduce(&a, None) {
            Ok(r) => r.state_space,
            Err(_) => crate::reduce_robust(&a)?.0,
        };
        let eig = eom_num::modes::eigenvalues(&ss.a)?;
        let mut added = false;
        let mut rest = Vec::new();
        let pending: Vec<&AutoSurface> = surfaces
            .iter()
            .filter(|s| !lagged.contains(&s.name))
            .collect();
        for s in pending {
            let top = eig
                .iter()
                .filter(|z| z.im > 0.0)
                .map(|z| (z.im * s.semichord / s.airspeed, *z))
                .max_by(|a, b| a.0.total_cmp(&b.0));
            match top {
                Some((k, z)) if k > AUTO_REDUCED_FREQUENCY => {
                    notes.push(Warning::AutoLagged {
                        item: ItemRef::new(s.kind, &s.name),
                        re: z.re,
                        im: z.im,
                        reduced_frequency: k,
                        threshold: AUTO_REDUCED_FREQUENCY,
                    });
                    lagged.push(s.name.clone());
                    added = true;
                }
                Some((k, _)) => rest.push(Warning::AutoQuasiSteady {
                    item: ItemRef::new(s.kind, &s.name),
                    largest: Some(k),
                    threshold: AUTO_REDUCED_FREQUENCY,
                }),
                None => rest.push(Warning::AutoQuasiSteady {
                    item: ItemRef::new(s.kind, &s.name),
                    largest: None,
                    threshold: AUTO_REDUCED_FREQUENCY,
                }),
            }
        }
        if !added {
            notes.extend(rest);
            return Ok((Cow::Owned(m), notes));
        }
    }
}
