//! The error of parametric reduced code against the full model away from the nominal point,
//! at random parameter points: the table in `docs/reduction.md`.
//!
//! The generated modules of `tests/build.rs` (chain50 reduced to 10 states and the bicycle to 5
//! by balanced truncation at the defaults) evaluated at random points, each compared with the
//! full model linearized anew at the same point: `max_ω σ_max(G(jω) − G_r(jω))` on 2001
//! frequencies from 1e-3 to 1e3 rad/s plus the full model's damped frequencies.
//!
//! `cargo run --release -p tests --example reduced_error`

use eom_model::Linearizer;
use eom_num::StateSpace;
use eom_num::freq::HessenbergForm;
use nalgebra::DMatrix;
use num_complex::Complex64;
use rand::{Rng, SeedableRng};

include!(concat!(env!("OUT_DIR"), "/reduced.rs"));

fn error(full: &StateSpace<f64>, red: &StateSpace<f64>) -> f64 {
    let (p, m) = (full.outputs(), full.inputs());
    let f = HessenbergForm::new(full).expect("full");
    let r = HessenbergForm::new(red).expect("reduced");
    let (mut wf, mut wr) = (f.workspace(), r.workspace());
    let (mut gf, mut gr) = (
        vec![Complex64::default(); p * m],
        vec![Complex64::default(); p * m],
    );
    let mut omegas: Vec<f64> = (0..=2000)
        .map(|k| 1e-3 * 1e6f64.powf(k as f64 / 2000.0))
        .collect();
    omegas.extend(
        eom_num::modes::eigenvalues(&full.a)
            .unwrap()
            .iter()
            .map(|z| z.im.abs())
            .filter(|w| *w > 0.0),
    );
    let mut worst = 0.0f64;
    for w in omegas {
        let s = Complex64::new(0.0, w);
        f.evaluate_in(s, &mut wf, &mut gf).unwrap();
        r.evaluate_in(s, &mut wr, &mut gr).unwrap();
        let d = DMatrix::from_fn(p, m, |i, j| gf[i + j * p] - gr[i + j * p]);
        worst = worst.max(d.singular_values().max());
    }
    worst
}

macro_rules! case {
    ($g:ident, $model:expr, $spread:expr, $rng:expr, $only:expr) => {{
        use $g as g;
        let nominal = g::Params::NOMINAL.to_array();
        let mut state = g::StateSpace::new();
        let (mut errs, mut invalid) = (Vec::new(), 0);
        for _ in 0..32 {
            let p: [f64; g::N_PARAMS] = core::array::from_fn(|k| {
                if $only.map_or(true, |n: &str| g::PARAM_NAMES[k] == n) {
                    nominal[k] * (1.0 + $spread * (2.0 * $rng.random::<f64>() - 1.0))
                } else {
                    nominal[k]
                }
            });
            if state.evaluate(&g::Params::from_array(&p)).is_err() {
                invalid += 1;
                continue;
            }
            let red = StateSpace::new(
                DMatrix::from_column_slice(g::N_STATES, g::N_STATES, state.a()),
                DMatrix::from_column_slice(g::N_STATES, g::N_INPUTS, state.b()),
                DMatrix::from_column_slice(g::N_OUTPUTS, g::N_STATES, state.c()),
                DMatrix::from_column_slice(g::N_OUTPUTS, g::N_INPUTS, state.d()),
            )
            .unwrap();
            let set: Vec<(&str, f64)> = g::PARAM_NAMES.iter().copied().zip(p).collect();
            let full = Linearizer::new(&models::build($model, &set).unwrap())
                .run()
                .unwrap()
                .state_space;
            errs.push(error(&full, &red));
        }
        errs.sort_by(f64::total_cmp);
        let above = errs.iter().filter(|e| **e > g::REDUCE_BOUND).count();
        println!(
            "| {} | {} ±{} % | {} | {:.4} | {:.4} | {:.4} | {} |",
            $model,
            $only.unwrap_or("all"),
            100.0 * $spread,
            errs.len(),
            errs[errs.len() / 2],
            errs[errs.len() - 1],
            g::REDUCE_BOUND,
            if invalid > 0 {
                format!("{above} ({invalid} outside the validity region)")
            } else {
                above.to_string()
            }
        );
    }};
}

fn main() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(2026);
    println!(
        "| model → states | parameters | points | median error | largest error | nominal bound | points above it |"
    );
    println!("|---|---|---|---|---|---|---|");
    for spread in [0.05, 0.1, 0.2, 0.5] {
        case!(chain50_r10, "chain50", spread, rng, None::<&str>);
    }
    for spread in [0.001, 0.01, 0.05, 0.1, 0.2] {
        case!(bicycle_r5, "bicycle", spread, rng, None::<&str>);
    }
    for spread in [0.01, 0.05, 0.2, 0.4, 0.6] {
        case!(bicycle_r5, "bicycle", spread, rng, Some("v"));
    }
}
